//! The primitives' distance functions, written once over a [`Lane`]: one
//! `f32` ([`Shape::distance`], the tree's evaluation) or eight at once (the
//! 8-lane program of `subcone-sdf`, which implements [`Lane`] for its lane
//! type).
//!
//! Both forms run these very functions, so a lane's value is the scalar's
//! bit for bit by construction, not by a second transcription kept in step.
//! The formulas are glam's, written out with the operations in glam's order
//! (`length` as `√((x·x + y·y) + z·z)`; a vector's `max` as SSE2's
//! compare-and-select, [`Lane::gmax`]; a scalar's `min`/`max` as Rust's
//! NaN-ignoring [`f32::min`]/[`f32::max`]); the exact order matters, because
//! floating-point addition is not associative. Branches on a point's value
//! are selects, so that eight lanes can take different sides; on `f32` a
//! select of two computed values is the branch's value.
//!
//! ```
//! use glam::Vec3;
//! use subcone_scene::sdf::{lane::shape_distance, Shape};
//!
//! let shape = Shape::Torus { major: 1.0, minor: 0.25 };
//! let d: f32 = shape_distance(&shape, 1.0, 0.5, 0.0);
//! assert_eq!(d.to_bits(), shape.distance(Vec3::new(1.0, 0.5, 0.0)).to_bits());
//! assert_eq!(d, 0.25);
//! ```

use core::ops::{Add, Div, Mul, Neg, Sub};

use glam::Vec3;

use super::shape::Shape;

/// One value per lane, with the operations the primitives use. Every
/// operation is the `f32` one applied lane by lane, so that an implementation
/// for `N` lanes gives, in lane `k`, exactly what `f32` gives for lane `k`'s
/// inputs.
pub trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f32, Output = Self>
    + Sub<f32, Output = Self>
    + Mul<f32, Output = Self>
    + Div<f32, Output = Self>
{
    /// A per-lane condition.
    type Mask: Copy;
    /// Every lane `v`.
    fn splat(v: f32) -> Self;
    /// [`f32::min`]: NaN-ignoring.
    fn min(self, o: Self) -> Self;
    /// [`f32::max`]: NaN-ignoring.
    fn max(self, o: Self) -> Self;
    /// A vector's `max` in glam (SSE2's `maxps`): `if a > b { a } else { b }`.
    fn gmax(self, o: Self) -> Self;
    /// [`f32::clamp`]: `lo` if below, then `hi` if above.
    fn clamp(self, lo: Self, hi: Self) -> Self;
    /// [`f32::abs`].
    fn abs(self) -> Self;
    /// [`f32::sqrt`], correctly rounded.
    fn sqrt(self) -> Self;
    /// `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// `self > o`.
    fn gt(self, o: Self) -> Self::Mask;
    /// `self == o`.
    fn eq(self, o: Self) -> Self::Mask;
    /// [`f32::is_finite`].
    fn is_finite(self) -> Self::Mask;
    /// Both conditions.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Either condition.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `a` where `m` holds, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

impl Lane for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f32) -> f32 {
        v
    }
    #[inline(always)]
    fn min(self, o: f32) -> f32 {
        f32::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: f32) -> f32 {
        f32::max(self, o)
    }
    #[inline(always)]
    fn gmax(self, o: f32) -> f32 {
        if self > o {
            self
        } else {
            o
        }
    }
    #[inline(always)]
    fn clamp(self, lo: f32, hi: f32) -> f32 {
        // `f32::clamp`'s own steps, without its assertion on the bounds.
        let mut v = self;
        if v < lo {
            v = lo;
        }
        if v > hi {
            v = hi;
        }
        v
    }
    #[inline(always)]
    fn abs(self) -> f32 {
        f32::abs(self)
    }
    #[inline(always)]
    fn sqrt(self) -> f32 {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn lt(self, o: f32) -> bool {
        self < o
    }
    #[inline(always)]
    fn gt(self, o: f32) -> bool {
        self > o
    }
    #[inline(always)]
    fn eq(self, o: f32) -> bool {
        self == o
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline(always)]
    fn and(a: bool, b: bool) -> bool {
        a & b
    }
    #[inline(always)]
    fn or(a: bool, b: bool) -> bool {
        a | b
    }
    #[inline(always)]
    fn select(m: bool, a: f32, b: f32) -> f32 {
        if m {
            a
        } else {
            b
        }
    }
}

/// glam's `Vec2::length`.
#[inline(always)]
fn len2<L: Lane>(x: L, y: L) -> L {
    (x * x + y * y).sqrt()
}

/// glam's `Vec3::length`: `√((x·x + y·y) + z·z)`.
#[inline(always)]
fn len3<L: Lane>(x: L, y: L, z: L) -> L {
    ((x * x + y * y) + z * z).sqrt()
}

/// glam's `max_element`: `max(x, max(y, z))` by `>`.
#[inline(always)]
fn max_element<L: Lane>(x: L, y: L, z: L) -> L {
    x.gmax(y.gmax(z))
}

/// The signed distance of `shape` at `(x, y, z)` (a bound for the
/// ellipsoid): [`Shape::distance`] on one lane or many.
#[inline(always)]
pub fn shape_distance<L: Lane>(shape: &Shape, x: L, y: L, z: L) -> L {
    let zero = L::splat(0.0);
    match *shape {
        Shape::Sphere { radius } => len3(x, y, z) - radius,
        Shape::Box { half } => sd_box(x, y, z, half),
        Shape::RoundBox { half, radius } => sd_box(x, y, z, half - Vec3::splat(radius)) - radius,
        Shape::BoxFrame { half, thickness } => sd_box_frame(x, y, z, half, 0.5 * thickness),
        Shape::Torus { major, minor } => len2(len2(x, z) - major, y) - minor,
        Shape::Link {
            half_length,
            major,
            minor,
        } => {
            let qy = (y.abs() - half_length).max(zero);
            len2(len2(x, qy) - major, z) - minor
        }
        Shape::Capsule {
            half_height,
            radius,
        } => {
            let y = y - y.clamp(L::splat(-half_height), L::splat(half_height));
            len3(x, y, z) - radius
        }
        Shape::Cylinder {
            radius,
            half_height,
        } => sd_cylinder(x, y, z, radius, half_height),
        Shape::RoundedCylinder {
            radius,
            half_height,
            rounding,
        } => sd_cylinder(x, y, z, radius - rounding, half_height - rounding) - rounding,
        Shape::CappedCone {
            half_height,
            bottom,
            top,
        } => sd_capped_cone(x, y, z, half_height, bottom, top),
        Shape::Octahedron { size } => sd_octahedron(x, y, z, size),
        Shape::HexPrism {
            apothem,
            half_height,
        } => sd_hex_prism(x, z, y, apothem, half_height),
        Shape::Ellipsoid { radii } => {
            let r2 = radii * radii;
            let k0 = len3(x / radii.x, y / radii.y, z / radii.z);
            let k1 = len3(x / r2.x, y / r2.y, z / r2.z);
            // The centre: the exact depth is the smallest semi-axis.
            let centre = L::splat(-radii.min_element());
            let inside = k0 * ((k0 - 1.0) / k1);
            // Radii so small that `r²` underflows: the bounding sphere's
            // distance, still a bound.
            let far = len3(x, y, z) - radii.max_element();
            let finite = L::and(k0.is_finite(), k1.is_finite());
            L::select(k1.eq(zero), centre, L::select(finite, inside, far))
        }
        Shape::Plane { normal, offset } => ((x * normal.x + y * normal.y) + z * normal.z) + offset,
    }
}

/// The tree's evaluation of a primitive: [`shape_distance`] on one `f32`
/// lane. Here, beside the function it runs, rather than with the shape's
/// data and checks (`shape.rs`), which then need nothing of this module.
impl Shape {
    /// Signed distance at `p` (a bound for the ellipsoid).
    #[inline]
    pub fn distance(&self, p: Vec3) -> f32 {
        self.distance_xyz(p.x, p.y, p.z)
    }

    /// [`Shape::distance`] with the point as scalars: they travel in registers,
    /// where a `Vec3` argument goes through memory and its reload can miss
    /// store forwarding (a stall of a dozen cycles per call).
    #[inline(never)]
    fn distance_xyz(&self, x: f32, y: f32, z: f32) -> f32 {
        shape_distance(self, x, y, z)
    }
}

#[inline(always)]
fn sd_box<L: Lane>(x: L, y: L, z: L, half: Vec3) -> L {
    let zero = L::splat(0.0);
    let (qx, qy, qz) = (x.abs() - half.x, y.abs() - half.y, z.abs() - half.z);
    len3(qx.gmax(zero), qy.gmax(zero), qz.gmax(zero)) + max_element(qx, qy, qz).min(zero)
}

#[inline(always)]
fn sd_box_frame<L: Lane>(x: L, y: L, z: L, half: Vec3, e: f32) -> L {
    let (px, py, pz) = (x.abs() - half.x, y.abs() - half.y, z.abs() - half.z);
    let (qx, qy, qz) = ((px + e).abs() - e, (py + e).abs() - e, (pz + e).abs() - e);
    // A function, not a closure: always inlined, where a closure left out of
    // line is compiled for the baseline and called from every
    // instruction-set path.
    #[inline(always)]
    fn part<L: Lane>(x: L, y: L, z: L) -> L {
        let zero = L::splat(0.0);
        len3(x.gmax(zero), y.gmax(zero), z.gmax(zero)) + max_element(x, y, z).min(zero)
    }
    part(px, qy, qz).min(part(qx, py, qz)).min(part(qx, qy, pz))
}

#[inline(always)]
fn sd_cylinder<L: Lane>(x: L, y: L, z: L, radius: f32, half_height: f32) -> L {
    let zero = L::splat(0.0);
    let dx = len2(x, z).abs() - radius;
    let dy = y.abs() - half_height;
    dx.max(dy).min(zero) + len2(dx.gmax(zero), dy.gmax(zero))
}

#[inline(always)]
fn sd_capped_cone<L: Lane>(x: L, y: L, z: L, h: f32, r1: f32, r2: f32) -> L {
    let zero = L::splat(0.0);
    let (qx, qy) = (len2(x, z), y);
    let (k1x, k1y) = (r2, h);
    let (k2x, k2y) = (r2 - r1, 2.0 * h);
    let cax = qx - qx.min(L::select(qy.lt(zero), L::splat(r1), L::splat(r2)));
    let cay = qy.abs() - h;
    let k2k2 = k2x * k2x + k2y * k2y;
    // Degenerate cone (h = 0 and r1 = r2): k2 = 0, the clamp's value is moot.
    let s = if k2k2 > 0.0 {
        (((L::splat(k1x) - qx) * k2x + (L::splat(k1y) - qy) * k2y) / k2k2)
            .clamp(zero, L::splat(1.0))
    } else {
        zero
    };
    let cbx = (qx - k1x) + s * k2x;
    let cby = (qy - k1y) + s * k2y;
    // Inside the slanted side: `q` left of the edge from the bottom corner
    // `(r1, −h)` to the top one, by the cross product. Quilez's test,
    // `cb.x < 0`, loses its sign to rounding on flat wide cones (`cb` nearly
    // vertical), which made the axis of such a cone read as outside.
    let side = (qy + h) * k2x - (qx - r1) * k2y;
    let inside = L::and(side.gt(zero), cay.lt(zero));
    let sign = L::select(inside, L::splat(-1.0), L::splat(1.0));
    sign * (cax * cax + cay * cay).min(cbx * cbx + cby * cby).sqrt()
}

#[inline(always)]
fn sd_octahedron<L: Lane>(x: L, y: L, z: L, s: f32) -> L {
    let (px, py, pz) = (x.abs(), y.abs(), z.abs());
    let m = px + py + pz - s;
    let ax = (px * 3.0).lt(m);
    let ay = (py * 3.0).lt(m);
    let az = (pz * 3.0).lt(m);
    // q = p, p.yzx or p.zxy by the first axis that passes; none: the face's
    // distance.
    #[inline(always)]
    fn pick<L: Lane>(ax: L::Mask, ay: L::Mask, a: L, b: L, c: L) -> L {
        L::select(ax, a, L::select(ay, b, c))
    }
    let qx = pick(ax, ay, px, py, pz);
    let qy = pick(ax, ay, py, pz, px);
    let qz = pick(ax, ay, pz, px, py);
    let k = ((qz - qy + s) * 0.5).clamp(L::splat(0.0), L::splat(s));
    let d = len3(qx, qy - s + k, qz - k);
    L::select(L::or(L::or(ax, ay), az), d, m * 0.577_350_26)
}

/// Quilez's hexagonal prism with its axis along `z`.
#[inline(always)]
fn sd_hex_prism<L: Lane>(x: L, y: L, z: L, apothem: f32, half_height: f32) -> L {
    const K: Vec3 = Vec3::new(-0.866_025_4, 0.5, 0.577_350_26);
    let zero = L::splat(0.0);
    let (px, py, pz) = (x.abs(), y.abs(), z.abs());
    let f = (px * K.x + py * K.y).min(zero) * 2.0;
    let px = px - f * K.x;
    let py = py - f * K.y;
    let ex = px - px.clamp(L::splat(-K.z * apothem), L::splat(K.z * apothem));
    let ey = py - apothem;
    let sign = L::select((py - apothem).lt(zero), L::splat(-1.0), L::splat(1.0));
    let dx = len2(ex, ey) * sign;
    let dy = pz - half_height;
    dx.max(dy).min(zero) + len2(dx.gmax(zero), dy.gmax(zero))
}
