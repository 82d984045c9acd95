//! Evaluation of a tree: distances, split distances and normals.

use glam::Vec3;
use subcone_kernels::math::Euclidean;

use super::{Op, SdfNode, SplitDistance};

impl SdfNode {
    // ------------------------------------------------------------ evaluation

    /// Signed distance at `p` (negative inside) and the material index of the
    /// object that decides it. Allocation-free; one recursion per tree level.
    #[inline]
    pub fn eval(&self, p: Vec3) -> (f32, u32) {
        self.eval_leafy(p)
    }

    /// Primitives and transformed primitives (most nodes of a scene) are
    /// evaluated in place; operators go through [`SdfNode::eval_op`]. This keeps
    /// the per-node cost to the work itself rather than a call with a large
    /// frame.
    #[inline(always)]
    fn eval_leafy(&self, p: Vec3) -> (f32, u32) {
        match &self.op {
            Op::Shape { shape, material } => (shape.distance(p), *material),
            Op::Transform(t) => {
                let mut q = (p - t.translation) * t.inv_scale;
                if t.rotated {
                    q = t.inv_rotation * q;
                }
                let (d, m) = match &t.child.op {
                    Op::Shape { shape, material } => (shape.distance(q), *material),
                    _ => t.child.eval_op(q.x, q.y, q.z),
                };
                (d * t.scale, m)
            }
            _ => self.eval_op(p.x, p.y, p.z),
        }
    }

    /// Operators. The point comes as scalars, which travel in registers (see
    /// `Shape::distance_xyz`).
    #[inline(never)]
    fn eval_op(&self, x: f32, y: f32, z: f32) -> (f32, u32) {
        let p = Vec3::new(x, y, z);
        match &self.op {
            Op::Shape { .. } | Op::Transform(_) => self.eval_leafy(p),
            Op::Union { children, spheres } => {
                let mut best = (f32::INFINITY, self.info.material);
                for (c, s) in children.iter().zip(spheres) {
                    // A child whose bounding sphere is no nearer than the best
                    // so far cannot lower the minimum (see `skip_sphere`).
                    let reach = best.0 + s.w;
                    if reach >= 0.0 && (p - s.truncate()).length_squared() >= reach * reach {
                        continue;
                    }
                    let r = c.eval_leafy(p);
                    if r.0 < best.0 {
                        best = r;
                    }
                }
                best
            }
            Op::Intersection(children) => {
                let mut best = (f32::NEG_INFINITY, self.info.material);
                for c in children {
                    let r = c.eval(p);
                    if r.0 > best.0 {
                        best = r;
                    }
                }
                best
            }
            Op::SmoothUnion { k, children } => {
                let k = *k;
                let mut acc = (f32::INFINITY, self.info.material);
                for (i, c) in children.iter().enumerate() {
                    let (d, m) = c.eval(p);
                    if i == 0 {
                        acc = (d, m);
                        continue;
                    }
                    let h = (k - (acc.0 - d).abs()).max(0.0) / k;
                    let mat = if d < acc.0 { m } else { acc.1 };
                    acc = (acc.0.min(d) - 0.25 * k * h * h, mat);
                }
                acc
            }
            Op::Subtract(ab) => {
                let (a, ma) = ab.0.eval(p);
                let (b, mb) = ab.1.eval(p);
                if a >= -b {
                    (a, ma)
                } else {
                    (-b, mb)
                }
            }
            Op::Mirror { axes, child } => {
                let mut q = p;
                for k in 0..3 {
                    if axes[k] {
                        q[k] = q[k].abs();
                    }
                }
                child.eval(q)
            }
            Op::Repeat(r) => {
                let (q, wall) = r.cell(p);
                let (d, m) = r.child.eval(q);
                let guard = wall + r.margin;
                (if guard < d { guard } else { d }, m)
            }
            Op::Round { radius, child } => {
                let (d, m) = child.eval(p);
                (d - radius, m)
            }
            Op::Onion { thickness, child } => {
                let (d, m) = child.eval(p);
                (d.abs() - thickness, m)
            }
            Op::ScaleDistance { factor, child } => {
                let (d, m) = child.eval(p);
                (d * factor, m)
            }
            Op::Displace {
                amplitude,
                frequency,
                child,
            } => {
                let (d, m) = child.eval(p);
                let s = p * *frequency;
                (d + amplitude * s.x.sin() * s.y.sin() * s.z.sin(), m)
            }
            Op::Bounded { pad, child } => {
                let b = child.info.bounds.distance(p);
                if b > *pad {
                    (b, self.info.material)
                } else {
                    child.eval(p)
                }
            }
            Op::Scatter(s) => s.eval(p),
        }
    }

    /// [`SplitDistance`]: for guarded repetition and
    /// scatter, the field [`eval`](SdfNode::eval) returns is capped at the
    /// cell walls (`min(d_object, wall + margin)`), a bound that is right for
    /// stepping but puts fake near-surfaces on every wall. Cone tracing must
    /// measure occlusion on the surface itself, so this splits the two: the
    /// first value is `eval`'s bound (march by it), the second is the distance
    /// to the objects that are evaluated (the cell's own; occlusion and normals
    /// use it), as the CTSS authors' `GRID_TRACE` does. Both are equal for every
    /// other node. The first never exceeds the second.
    #[inline]
    pub fn eval_split(&self, p: Vec3) -> SplitDistance {
        let (safe, surface, material) = self.split(p);
        SplitDistance {
            safe,
            surface,
            material,
        }
    }

    /// [`eval_split`](SdfNode::eval_split) as `(safe, surface, material)`,
    /// for the recursion.
    fn split(&self, p: Vec3) -> (f32, f32, u32) {
        match &self.op {
            Op::Shape { shape, material } => {
                let d = shape.distance(p);
                (d, d, *material)
            }
            Op::Transform(t) => {
                let mut q = (p - t.translation) * t.inv_scale;
                if t.rotated {
                    q = t.inv_rotation * q;
                }
                let (a, b, m) = t.child.split(q);
                (a * t.scale, b * t.scale, m)
            }
            Op::Union { children, spheres } => {
                let (mut safe, mut surf, mut mat) =
                    (f32::INFINITY, f32::INFINITY, self.info.material);
                for (c, s) in children.iter().zip(spheres) {
                    let reach = surf + s.w;
                    let d2 = (p - s.truncate()).length_squared();
                    if reach >= 0.0 && d2 >= reach * reach {
                        // Not nearer than the best surface; its bounding sphere
                        // bounds its distance from below.
                        safe = safe.min(d2.sqrt() - s.w);
                        continue;
                    }
                    let (a, b, m) = c.split(p);
                    safe = safe.min(a);
                    if b < surf {
                        surf = b;
                        mat = m;
                    }
                }
                (safe.min(surf), surf, mat)
            }
            Op::Repeat(r) if r.guard => {
                let (q, wall) = r.cell(p);
                let (a, b, m) = r.child.split(q);
                (a.min(wall + r.margin), b, m)
            }
            Op::Scatter(s) => s.split(p),
            // `bounded` answers with its box's distance far from the box: a
            // bound for stepping, but no surface, so the surface distance must
            // come from the child (a wide cone can reach past the padding).
            Op::Bounded { pad, child } => {
                let b = child.info.bounds.distance(p);
                let (a, surface, m) = child.split(p);
                (if b > *pad { a.max(b).min(surface) } else { a }, surface, m)
            }
            _ => {
                let (d, m) = self.eval(p);
                (d, d, m)
            }
        }
    }

    /// Unit normal of the surface distance of [`eval_split`](SdfNode::eval_split)
    /// (tetrahedral differences, as [`normal`](SdfNode::normal)), so guarded
    /// cells do not bend normals towards their walls.
    pub fn normal_surface(&self, p: Vec3, h: f32) -> Vec3 {
        let taps = tetra_taps(p, h);
        tetra_normal_from(taps.map(|q| self.eval_split(q).surface))
    }

    /// The distance alone.
    #[inline]
    pub fn distance(&self, p: Vec3) -> f32 {
        self.eval(p).0
    }

    /// Unit normal by Quilez's tetrahedral differences: 4 evaluations at
    /// `p + k·h` for the corners `k ∈ {(1,−1,−1), (−1,−1,1), (−1,1,−1),
    /// (1,1,1)}`, `n ∝ Σ k f(p + k h) = 4h ∇f + 4h² (H_yz, H_xz, H_xy) + O(h³)`:
    /// first-order accurate (the error is `h` times the Hessian's off-diagonal
    /// terms, zero on planes and along principal axes), at 4 evaluations
    /// against [`normal_central`](SdfNode::normal_central)'s 6.
    ///
    /// The step `h` is raised to 16 ulps of `p`'s largest coordinate so that
    /// the differences never vanish in `f32` far from the origin; a zero or
    /// non-finite gradient gives `+y`.
    pub fn normal(&self, p: Vec3, h: f32) -> Vec3 {
        let h = step(p, h);
        let mut n = Vec3::ZERO;
        for k in TETRA {
            n += k * self.distance(p + k * h);
        }
        unit_or_up(n)
    }

    /// Unit normal by central differences: 6 evaluations,
    /// `n ∝ (f(p + h x) − f(p − h x), …)`. Second-order accurate; the reference
    /// for [`normal`](SdfNode::normal). Same step floor and fallback.
    pub fn normal_central(&self, p: Vec3, h: f32) -> Vec3 {
        let h = step(p, h);
        let mut n = Vec3::ZERO;
        for (k, axis) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            n[k] = self.distance(p + axis * h) - self.distance(p - axis * h);
        }
        unit_or_up(n)
    }
}

/// The corners of the tetrahedral differences (Quilez): `n ∝ Σ k f(p + k h)`.
const TETRA: [Vec3; 4] = [
    Vec3::new(1.0, -1.0, -1.0),
    Vec3::new(-1.0, -1.0, 1.0),
    Vec3::new(-1.0, 1.0, -1.0),
    Vec3::new(1.0, 1.0, 1.0),
];

/// The four points of [`SdfNode::normal_surface`]'s tetrahedral differences
/// at `p` with step `h` (raised to 16 ulps of `p`'s largest coordinate).
#[inline]
pub fn tetra_taps(p: Vec3, h: f32) -> [Vec3; 4] {
    let h = step(p, h);
    TETRA.map(|k| p + k * h)
}

/// [`SdfNode::normal_surface`] from the surface distances at the four
/// [`tetra_taps`], in their order: `Σ k·d`, normalised (or `+y`).
#[inline]
pub fn tetra_normal_from(d: [f32; 4]) -> Vec3 {
    let mut n = Vec3::ZERO;
    for (k, d) in TETRA.into_iter().zip(d) {
        n += k * d;
    }
    unit_or_up(n)
}

#[inline]
fn step(p: Vec3, h: f32) -> f32 {
    let floor = (p.abs().max_element() * (16.0 * f32::EPSILON)).max(1e-30);
    if h.is_finite() {
        h.max(floor)
    } else {
        floor
    }
}

/// `n / |n|`, or `+y` for a zero or non-finite `n`. Divided by its largest
/// component first: differences of tiny distances (near the origin, where the
/// step is tiny) square into subnormals, and of huge ones overflow, either of
/// which would make `n / |n|` miss unit length or vanish.
#[inline]
fn unit_or_up(n: Vec3) -> Vec3 {
    let m = n.abs().max_element();
    if n.is_finite() && m > 0.0 {
        (n / m).unit()
    } else {
        Vec3::Y
    }
}
