//! The operators' constructors: each validates its operands and
//! parameters and computes what the new node caches.

use glam::{Quat, Vec3, Vec4};
use subcone_kernels::math::Euclidean;

use super::scatter::{Scatter, ScatterConfig};
use super::{depth_of, Info, Op, Repeat, SdfNode, Transform};
use crate::sdf::bounds::Aabb;
use crate::sdf::check::{all_finite, nonneg, positive, UNIT_TOLERANCE};
use crate::sdf::{Exactness, SdfError};

impl SdfNode {
    // ------------------------------------------------------------- operators

    /// Union, `min` of the children, with the material of the nearest.
    ///
    /// Tagged [`Exactness::Exact`] when every child is: `min` of exact
    /// distances is exact **outside** the union; inside, where children
    /// overlap, it underestimates the depth (a bound). Nested unions are
    /// flattened; a union of one node is that node. Errors on no children.
    ///
    /// Evaluation skips a child whose bounding sphere is no nearer than the
    /// best value so far: for exact children that cannot change the result;
    /// for bound children the result may be larger than the plain `min` but
    /// is still a bound; non-Eikonal children are never skipped.
    pub fn union(children: Vec<SdfNode>) -> Result<SdfNode, SdfError> {
        let mut flat = Vec::with_capacity(children.len());
        for c in children {
            match c.op {
                Op::Union { children, .. } => flat.extend(children),
                _ => flat.push(c),
            }
        }
        Self::nary(
            "union",
            flat,
            |children| {
                let spheres = children.iter().map(skip_sphere).collect();
                Op::Union { children, spheres }
            },
            |e| e,
        )
    }

    /// Intersection, `max` of the children (a bound), with the material of the
    /// child that decides. Errors on no children.
    pub fn intersection(children: Vec<SdfNode>) -> Result<SdfNode, SdfError> {
        let node = Self::nary(
            "intersection",
            children,
            Op::Intersection,
            |e: Exactness| e.max(Exactness::Bound),
        )?;
        Ok(node.fix_intersection_bounds())
    }

    /// Smooth union with Quilez's quadratic polynomial `smin` of width `k`
    /// (`k = 0` is a plain union). A bound: `smin ≤ min`, and it is 1-Lipschitz
    /// (its gradient is a convex combination of the children's), so it never
    /// overestimates the distance to its own (grown) zero set. The `smin` is
    /// applied child by child, each step lowering the value by at most `k/4`,
    /// so with `n` children the surface grows by at most `(n − 1)·k/4` (and the
    /// bounding box by as much). Material: the nearest child's.
    ///
    /// Lowering the field is an offset like [`onion`](SdfNode::onion)'s:
    /// errors when `(n − 1)·k/4` exceeds the margin of a capped step bound
    /// among the children (see there).
    pub fn smooth_union(k: f32, children: Vec<SdfNode>) -> Result<SdfNode, SdfError> {
        let k = nonneg("smooth union", "k", k)?;
        if k == 0.0 {
            return Self::union(children);
        }
        let mut node = Self::nary(
            "smooth union",
            children,
            |children| Op::SmoothUnion { k, children },
            |e: Exactness| e.max(Exactness::Bound),
        )?;
        if let Op::SmoothUnion { children, .. } = &node.op {
            let steps = (children.len() - 1) as f32;
            let lowered = 0.25 * k * steps;
            node.info.offset_limit = node.offset_limit_after("smooth union", "k", lowered)?;
            node.info.bounds = node.info.bounds.expand(lowered);
        }
        Ok(node)
    }

    fn nary(
        name: &'static str,
        children: Vec<SdfNode>,
        make: impl FnOnce(Vec<SdfNode>) -> Op,
        exactness: impl Fn(Exactness) -> Exactness,
    ) -> Result<SdfNode, SdfError> {
        if children.is_empty() {
            return Err(SdfError::Empty { node: name });
        }
        if children.len() == 1 {
            let mut only = children;
            return only.pop().ok_or(SdfError::Empty { node: name });
        }
        let refs: Vec<&SdfNode> = children.iter().collect();
        let depth = depth_of(name, &refs)?;
        let first = &children[0].info;
        let mut info = Info {
            bounds: first.bounds,
            exactness: first.exactness,
            conservative: true,
            symmetry: first.symmetry,
            depth,
            objects: 0,
            offset_limit: first.offset_limit,
            max_material: 0,
            material: first.material,
        };
        for c in &children {
            let ci = &c.info;
            info.bounds = info.bounds.union(&ci.bounds);
            info.exactness = info.exactness.max(ci.exactness);
            info.conservative &= ci.conservative;
            for k in 0..3 {
                info.symmetry[k] &= ci.symmetry[k];
            }
            info.objects = info.objects.saturating_add(ci.objects);
            info.offset_limit = info.offset_limit.min(ci.offset_limit);
            info.max_material = info.max_material.max(ci.max_material);
        }
        info.exactness = exactness(info.exactness);
        Ok(SdfNode {
            op: make(children),
            info,
        })
    }

    fn fix_intersection_bounds(mut self) -> SdfNode {
        if let Op::Intersection(children) = &self.op {
            let mut b = Aabb::EVERYTHING;
            for c in children {
                b = b.intersect(&c.info.bounds);
            }
            self.info.bounds = b;
        }
        self
    }

    /// `self` minus `other`: `max(a, −b)`, a bound. The surface carved by
    /// `other` takes `other`'s material.
    pub fn subtract(self, other: SdfNode) -> Result<SdfNode, SdfError> {
        let depth = depth_of("subtraction", &[&self, &other])?;
        let mut symmetry = self.info.symmetry;
        for (k, s) in symmetry.iter_mut().enumerate() {
            *s &= other.info.symmetry[k];
        }
        let info = Info {
            bounds: self.info.bounds,
            exactness: self
                .info
                .exactness
                .max(other.info.exactness)
                .max(Exactness::Bound),
            conservative: self.info.conservative && other.info.conservative,
            symmetry,
            depth,
            objects: self.info.objects,
            // `−b` is capped too (towards zero, inside `self`): an onion above
            // would read it as a shell.
            offset_limit: self.info.offset_limit.min(other.info.offset_limit),
            max_material: self.info.max_material.max(other.info.max_material),
            material: self.info.material,
        };
        Ok(SdfNode {
            op: Op::Subtract(Box::new((self, other))),
            info,
        })
    }

    /// Move by `offset`. Exactness preserved.
    pub fn translate(self, offset: Vec3) -> Result<SdfNode, SdfError> {
        self.transform(offset, Quat::IDENTITY, 1.0)
    }

    /// Rotate about the origin by `rotation` (normalised here; errors on a
    /// non-finite or zero quaternion). Exactness preserved.
    pub fn rotate(self, rotation: Quat) -> Result<SdfNode, SdfError> {
        self.transform(Vec3::ZERO, rotation, 1.0)
    }

    /// Scale uniformly about the origin by `factor > 0`: evaluated exactly as
    /// `factor · f(p / factor)`, so exactness is preserved. Errors on zero,
    /// negative or non-finite factors.
    pub fn scale(self, factor: f32) -> Result<SdfNode, SdfError> {
        self.transform(Vec3::ZERO, Quat::IDENTITY, factor)
    }

    /// Scale by `scale`, then rotate by `rotation`, then translate by
    /// `translation`. Consecutive transforms are merged into one node.
    pub fn transform(
        self,
        translation: Vec3,
        rotation: Quat,
        scale: f32,
    ) -> Result<SdfNode, SdfError> {
        const NAME: &str = "transform";
        all_finite(NAME, "translation", translation.is_finite())?;
        all_finite(NAME, "rotation", rotation.is_finite())?;
        // In f64: the squared length of a finite f32 quaternion can overflow
        // f32 (then `rotation / len` would be the zero quaternion).
        let q = rotation.to_array().map(f64::from);
        let len = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        if len <= 1e-6 {
            return Err(SdfError::Invalid {
                node: NAME,
                reason: format!("rotation quaternion {rotation} has zero length"),
            });
        }
        // A quaternion that is already unit to f32 precision is kept as given:
        // normalising is then idempotent, so a tree written to a scene file
        // and read back is the same tree, bit for bit.
        let rotation = if (len - 1.0).abs() <= UNIT_TOLERANCE {
            rotation
        } else {
            Quat::from_array(q.map(|c| (c / len) as f32))
        };
        let scale = positive(NAME, "scale", scale)?;
        // Merge with a transform below: outer ∘ inner.
        let (translation, rotation, scale, child) = match self.op {
            Op::Transform(inner) => {
                let t = translation + rotation * (scale * inner.translation);
                let r = (rotation * inner.rotation).normalize();
                let s = scale * inner.scale;
                (t, r, s, inner.child)
            }
            op => (
                translation,
                rotation,
                scale,
                SdfNode {
                    op,
                    info: self.info,
                },
            ),
        };
        if !(scale.is_finite() && scale > 0.0 && translation.is_finite()) {
            return Err(SdfError::Invalid {
                node: NAME,
                reason: "composed transform overflows".into(),
            });
        }
        let rotated = rotation != Quat::IDENTITY;
        let mut symmetry = child.info.symmetry;
        for k in 0..3 {
            symmetry[k] &= !rotated && translation[k] == 0.0;
        }
        let depth = depth_of(NAME, &[&child])?;
        let info = Info {
            bounds: child.info.bounds.transform(translation, rotation, scale),
            symmetry,
            depth,
            offset_limit: child.info.offset_limit * scale,
            ..child.info
        };
        if translation == Vec3::ZERO && !rotated && scale == 1.0 {
            return Ok(child);
        }
        Ok(SdfNode {
            op: Op::Transform(Box::new(Transform {
                translation,
                rotation,
                scale,
                inv_rotation: rotation.conjugate(),
                inv_scale: 1.0 / scale,
                rotated,
                child,
            })),
            info,
        })
    }

    /// Mirror about the planes `x = 0`, `y = 0`, `z = 0` selected by `axes`
    /// (evaluate at `|p|` on those axes): the child plus its mirror image.
    /// Exact when the child is, because the child must lie on the positive side
    /// of each mirror plane (checked with its bounding box; errors otherwise).
    pub fn mirror(self, axes: [bool; 3]) -> Result<SdfNode, SdfError> {
        const NAME: &str = "mirror";
        for (k, &on) in axes.iter().enumerate() {
            if on && (self.info.bounds.min[k] < 0.0 || self.info.bounds.min[k].is_nan()) {
                return Err(SdfError::Overlap {
                    node: NAME,
                    reason: format!(
                        "the child reaches {} = {} on the negative side of the mirror plane",
                        ["x", "y", "z"][k],
                        self.info.bounds.min[k]
                    ),
                });
            }
        }
        let depth = depth_of(NAME, &[&self])?;
        let mut info = self.info;
        info.depth = depth;
        let mut objects = info.objects;
        for (k, &on) in axes.iter().enumerate() {
            if on {
                info.bounds.min[k] = -info.bounds.max[k];
                info.symmetry[k] = true;
                objects = objects.saturating_mul(2);
            }
        }
        info.objects = objects;
        Ok(SdfNode {
            op: Op::Mirror {
                axes,
                child: Box::new(self),
            },
            info,
        })
    }

    /// Infinite repetition with `period` per axis (0 = not repeated on that
    /// axis). See [`SdfNode::repeat_limited`].
    pub fn repeat(self, period: Vec3) -> Result<SdfNode, SdfError> {
        self.repeat_cells(period, Vec3::NEG_INFINITY, Vec3::INFINITY)
    }

    /// Repetition with `period` per axis (0 = not repeated) over the cells
    /// `lo..=hi` (cell `i` is centred at `i · period`).
    ///
    /// The child must fit in its cell (its bounding box within
    /// `±period/2` on repeated axes; errors otherwise), so instances never
    /// overlap. Then:
    /// - if the child is mirror symmetric about its cell's centre planes on the
    ///   repeated axes (known structurally: centred, unrotated primitives and
    ///   their unions/CSG), evaluating the child in the cell of `p` is **exact**
    ///   when the child is: every other instance is a reflection of the own one
    ///   across a cell wall that `p` is on the near side of, so it is farther;
    /// - otherwise the node is a **bound**: it evaluates the own cell's
    ///   instance and takes `min(d, w + m)`, where `w` is the distance from `p`
    ///   to the walls of its cell that have neighbours and `m` the margin
    ///   between the child's box and the cell walls: every other instance is at
    ///   least `w + m` away. That cap is a step bound, not a distance, so an
    ///   offset above it (onion, round, displacement, smooth union) may lower
    ///   the field by at most `m`: see [`SdfNode::onion`].
    ///
    /// One child evaluation per call either way.
    pub fn repeat_limited(
        self,
        period: Vec3,
        lo: [i32; 3],
        hi: [i32; 3],
    ) -> Result<SdfNode, SdfError> {
        if (0..3).any(|k| lo[k] > hi[k]) {
            return Err(SdfError::Invalid {
                node: "repetition",
                reason: format!("empty cell range {lo:?}..={hi:?}"),
            });
        }
        let f = |v: [i32; 3]| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
        self.repeat_cells(period, f(lo), f(hi))
    }

    fn repeat_cells(self, period: Vec3, lo: Vec3, hi: Vec3) -> Result<SdfNode, SdfError> {
        const NAME: &str = "repetition";
        for c in period.to_array() {
            nonneg(NAME, "period", c)?;
        }
        if period == Vec3::ZERO {
            return Err(SdfError::Invalid {
                node: NAME,
                reason: "no axis is repeated (period is zero)".into(),
            });
        }
        let b = self.info.bounds;
        let mut margin = f32::INFINITY;
        let mut lo = lo;
        let mut hi = hi;
        let mut bounds = b;
        let mut objects = self.info.objects;
        let mut guard = false;
        let mut symmetry = self.info.symmetry;
        for k in 0..3 {
            let c = period[k];
            if c == 0.0 {
                lo[k] = 0.0;
                hi[k] = 0.0;
                continue;
            }
            let reach = b.min[k].abs().max(b.max[k].abs());
            let m = 0.5 * c - reach;
            if m < 0.0 || m.is_nan() {
                return Err(SdfError::Overlap {
                    node: NAME,
                    reason: format!(
                        "the child reaches {} = ±{reach} but cells along {} are only {c} wide",
                        ["x", "y", "z"][k],
                        ["x", "y", "z"][k],
                    ),
                });
            }
            margin = margin.min(m);
            guard |= !self.info.symmetry[k];
            bounds.min[k] = b.min[k] + lo[k] * c;
            bounds.max[k] = b.max[k] + hi[k] * c;
            let n = hi[k] - lo[k] + 1.0;
            objects = if n.is_finite() {
                objects.saturating_mul(n as u64)
            } else {
                u64::MAX
            };
            symmetry[k] &= lo[k] == -hi[k];
        }
        let depth = depth_of(NAME, &[&self])?;
        let exactness = if guard {
            self.info.exactness.max(Exactness::Bound)
        } else {
            self.info.exactness
        };
        // A guarded cell answers at most `wall + margin` (a step bound, no
        // surface): lowering that by more than `margin` makes it negative
        // next to the walls.
        let offset_limit = if guard {
            margin.min(self.info.offset_limit)
        } else {
            self.info.offset_limit
        };
        let info = Info {
            bounds,
            exactness,
            symmetry,
            depth,
            objects,
            offset_limit,
            ..self.info
        };
        Ok(SdfNode {
            op: Op::Repeat(Box::new(Repeat {
                period,
                lo,
                hi,
                guard,
                margin,
                child: self,
            })),
            info,
        })
    }

    /// Round by `radius`: `d − radius` (grows the shape). Exactness preserved
    /// outside. An offset like [`onion`](SdfNode::onion)'s: errors when
    /// `radius` exceeds the margin of a capped step bound below (see there).
    pub fn round(self, radius: f32) -> Result<SdfNode, SdfError> {
        let radius = nonneg("round", "radius", radius)?;
        let offset_limit = self.offset_limit_after("round", "radius", radius)?;
        self.unary(
            "round",
            |child| Op::Round { radius, child },
            |i| {
                i.bounds = i.bounds.expand(radius);
                i.offset_limit = offset_limit;
            },
        )
    }

    /// Shell of `thickness`: `|d| − thickness`. Exact only for an exact single
    /// primitive (whose inside is exact too); a bound otherwise.
    ///
    /// Errors ([`SdfError::Overlap`]) when `thickness` exceeds the child's
    /// *offset limit*: the margin of the capped step bounds in it. A guarded
    /// repetition or a scatter grid answers `min(d, w + m)` (`w` the distance
    /// to its cell's walls, `m` the margin between the instances and the
    /// walls) and a [`bounded`](SdfNode::bounded) node its box's distance
    /// beyond `pad`: step bounds, positive but not distances, which may be
    /// tiny far from every surface (`w` ignores the other axes: a point 100
    /// units beside a row of cells can be next to a wall's plane). `|d| − t`
    /// of such a cap reads as inside the shell wherever the cap is below `t`,
    /// which puts solid slabs on the cell walls, outside the node's bounds.
    /// Below the margin (`t ≤ m`) the cap stays a valid bound of the grown
    /// instances (`w + m − t ≥ w ≥ 0`, and every other instance's shell is at
    /// least that far); above it the shells cross the cell walls, which an
    /// evaluation of one cell cannot see, as a repetition of a child that does
    /// not fit its cell (refused by [`repeat_limited`](SdfNode::repeat_limited)).
    /// Apply the onion below the repetition instead. The same holds for every
    /// operator that lowers the field ([`round`](SdfNode::round),
    /// [`displace`](SdfNode::displace), [`smooth_union`](SdfNode::smooth_union)):
    /// the limit is tracked through the tree (scaled by transforms and
    /// distance factors, reduced by each offset, the smallest of the
    /// children's), so `eval`, `eval_split` and the WGSL field are unchanged.
    pub fn onion(self, thickness: f32) -> Result<SdfNode, SdfError> {
        let thickness = nonneg("onion", "thickness", thickness)?;
        let offset_limit = self.offset_limit_after("onion", "thickness", thickness)?;
        let single = self.is_single_primitive();
        self.unary(
            "onion",
            |child| Op::Onion { thickness, child },
            |i| {
                i.bounds = i.bounds.expand(thickness);
                i.offset_limit = offset_limit;
                if !single {
                    i.exactness = i.exactness.max(Exactness::Bound);
                }
            },
        )
    }

    /// Multiply the distance by `factor > 0`: the same surface, but
    /// `|∇f| = factor`, so not a distance at all (**non-Eikonal**). A factor
    /// below 1 underestimates (safe, slow marching); above 1 overestimates
    /// (sphere tracing may step through surfaces).
    pub fn scale_distance(self, factor: f32) -> Result<SdfNode, SdfError> {
        let factor = positive("distance scale", "factor", factor)?;
        if factor == 1.0 {
            return Ok(self);
        }
        self.unary(
            "distance scale",
            |child| Op::ScaleDistance { factor, child },
            |i| {
                i.exactness = Exactness::NonEikonal;
                i.conservative &= factor <= 1.0;
                i.offset_limit *= factor;
            },
        )
    }

    /// Displace the surface by `amplitude · sin(f x) sin(f y) sin(f z)`:
    /// non-Eikonal (`|∇f|` up to `1 + amplitude · frequency · √3`), may
    /// overestimate. Lowers the field by up to `amplitude`: errors when that
    /// exceeds the margin of a capped step bound below (see
    /// [`onion`](SdfNode::onion)).
    pub fn displace(self, amplitude: f32, frequency: f32) -> Result<SdfNode, SdfError> {
        let amplitude = nonneg("displacement", "amplitude", amplitude)?;
        let frequency = nonneg("displacement", "frequency", frequency)?;
        let lowered = if frequency > 0.0 { amplitude } else { 0.0 };
        let offset_limit = self.offset_limit_after("displacement", "amplitude", lowered)?;
        self.unary(
            "displacement",
            |child| Op::Displace {
                amplitude,
                frequency,
                child,
            },
            |i| {
                i.bounds = i.bounds.expand(amplitude);
                i.offset_limit = offset_limit;
                if amplitude > 0.0 && frequency > 0.0 {
                    i.exactness = Exactness::NonEikonal;
                    i.conservative = false;
                }
                i.symmetry = [false; 3];
            },
        )
    }

    /// Skip the child while `p` is more than `pad` from its bounding box,
    /// returning the distance to the box instead (a bound). `pad` must exceed
    /// the largest cone radius (or normal step) at which the child is shaded,
    /// so that points near the surface always see the real child. Errors when
    /// the child is unbounded.
    pub fn bounded(self, pad: f32) -> Result<SdfNode, SdfError> {
        let pad = nonneg("bounded", "pad", pad)?;
        if !self.info.bounds.is_finite() {
            return Err(SdfError::Invalid {
                node: "bounded",
                reason: "the child is unbounded".into(),
            });
        }
        self.unary(
            "bounded",
            |child| Op::Bounded { pad, child },
            |i| {
                i.exactness = i.exactness.max(Exactness::Bound);
                // Beyond `pad` it answers the box's distance, not the surface's.
                i.offset_limit = i.offset_limit.min(pad);
            },
        )
    }

    /// A grid of cells, each holding at most one randomly chosen, scaled,
    /// rotated and offset copy of a template: see [`ScatterConfig`]. A bound
    /// (one template evaluation per call, guarded by the cell walls).
    pub fn scatter(config: ScatterConfig, templates: Vec<SdfNode>) -> Result<SdfNode, SdfError> {
        let depth = depth_of("scatter", &templates.iter().collect::<Vec<_>>())?;
        let scatter = Scatter::new(config, templates)?;
        let mut exactness = Exactness::Bound;
        let mut conservative = true;
        let mut max_material = 0;
        for t in scatter.templates() {
            exactness = exactness.max(t.info.exactness);
            conservative &= t.info.conservative;
            max_material = max_material.max(t.info.max_material);
        }
        if let Some(m) = scatter.palette().iter().max() {
            max_material = *m;
        }
        // Cells answer at most `wall + margin`; an instance's own caps shrink
        // with its scale.
        let mut offset_limit = scatter.margin();
        for inst in scatter.instances() {
            if let Some(t) = scatter.templates().get(inst.template as usize) {
                offset_limit = offset_limit.min(t.info.offset_limit * inst.scale);
            }
        }
        let info = Info {
            bounds: scatter.bounds(),
            exactness,
            conservative,
            symmetry: [false; 3],
            depth,
            objects: scatter.object_count(),
            offset_limit,
            max_material,
            material: scatter.default_material(),
        };
        Ok(SdfNode {
            op: Op::Scatter(Box::new(scatter)),
            info,
        })
    }

    fn unary(
        self,
        name: &'static str,
        make: impl FnOnce(Box<SdfNode>) -> Op,
        adjust: impl FnOnce(&mut Info),
    ) -> Result<SdfNode, SdfError> {
        let depth = depth_of(name, &[&self])?;
        let mut info = self.info;
        info.depth = depth;
        adjust(&mut info);
        Ok(SdfNode {
            op: make(Box::new(self)),
            info,
        })
    }

    /// The offset limit left after lowering this node's field by `by`, or an
    /// [`SdfError::Overlap`] when `by` exceeds it (see [`SdfNode::onion`]).
    fn offset_limit_after(
        &self,
        node: &'static str,
        param: &'static str,
        by: f32,
    ) -> Result<f32, SdfError> {
        let limit = self.info.offset_limit;
        if by <= limit {
            Ok(limit - by)
        } else {
            Err(SdfError::Overlap {
                node,
                reason: format!(
                    "{param} {by} lowers the field by more than the margin {limit} of a guarded \
                     repetition, scatter grid or bounded node below: instances would grow \
                     across their cell walls (apply it below the repetition)"
                ),
            })
        }
    }

    fn is_single_primitive(&self) -> bool {
        match &self.op {
            Op::Shape { .. } => true,
            Op::Transform(t) => t.child.is_single_primitive(),
            _ => false,
        }
    }

    /// Give every object below this node material `material` (an index into
    /// the scene's materials; checked by [`SdfScene::new`](crate::sdf::SdfScene::new)).
    pub fn with_material(mut self, material: u32) -> SdfNode {
        self.set_material(material);
        self
    }

    fn set_material(&mut self, m: u32) {
        self.info.max_material = m;
        self.info.material = m;
        match &mut self.op {
            Op::Shape { material, .. } => *material = m,
            Op::Union { children: c, .. }
            | Op::Intersection(c)
            | Op::SmoothUnion { children: c, .. } => c.iter_mut().for_each(|c| c.set_material(m)),
            Op::Subtract(ab) => {
                ab.0.set_material(m);
                ab.1.set_material(m);
            }
            Op::Transform(t) => t.child.set_material(m),
            Op::Repeat(r) => r.child.set_material(m),
            Op::Mirror { child, .. }
            | Op::Round { child, .. }
            | Op::Onion { child, .. }
            | Op::ScaleDistance { child, .. }
            | Op::Displace { child, .. }
            | Op::Bounded { child, .. } => child.set_material(m),
            Op::Scatter(s) => s.set_material(m),
        }
    }
}

/// The bounding sphere a union may use to skip a child. An exact child's
/// value is at least the distance to any volume enclosing it, so when that distance is no
/// less than the best value so far, the child cannot lower the minimum and
/// skipping it changes nothing. A bound child's value may be lower, but the
/// result stays a bound: the skipped child's true distance is at least the
/// best value. Non-Eikonal children are never skipped, so their fields stay
/// as built.
fn skip_sphere(c: &SdfNode) -> Vec4 {
    let b = c.info.bounds;
    if c.info.exactness == Exactness::NonEikonal || !b.is_finite() || b.min.cmpgt(b.max).any() {
        return Vec4::new(0.0, 0.0, 0.0, f32::INFINITY);
    }
    let centre = 0.5 * (b.min + b.max);
    let radius = 0.5 * (b.max - b.min).norm();
    // Grow by a few ulps so rounding never skips a child that matters.
    let slack = 1e-5 * (radius + centre.abs().max_element());
    centre.extend(radius + slack)
}
