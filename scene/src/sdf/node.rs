//! The SDF tree: validated nodes, evaluation and normals.

use glam::{Quat, Vec3, Vec4};
use subcone_kernels::math::Euclidean;

use super::bounds::{round_cell, Aabb};
use super::check::{all_finite, nonneg, positive};
use super::scatter::{Scatter, ScatterConfig};
use super::shape::Shape;
use super::{Exactness, SdfError};

/// Deepest tree accepted: evaluation recurses once per level, so the depth is
/// bounded to keep stack use small on worker threads.
pub const MAX_DEPTH: u32 = 64;

/// How far from 1 the length of a rotation quaternion or a plane normal may be
/// for it to be taken as unit and kept as given (a few f32 ulps): normalising
/// again would move its last bits.
pub const UNIT_TOLERANCE: f64 = 4.0 * f32::EPSILON as f64;

/// One evaluation of a field with the step bound and the surface distance
/// apart ([`SdfNode::eval_split`]): named, so the two cannot be swapped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitDistance {
    /// A distance that is safe to march by: at most the surface distance,
    /// capped at repetition cell walls (plus their margin).
    pub safe: f32,
    /// The distance to the surface itself: occlusion, hits and normals use it.
    /// `+∞` where no object is evaluated (a scatter's empty cell, which has
    /// no surface of its own; the step bound is finite there), never NaN or
    /// `−∞` for a point in [`SdfNode`]'s domain.
    pub surface: f32,
    /// The material of the nearest object.
    pub material: u32,
}

impl SplitDistance {
    /// The same evaluation bit for bit (what the compiled program promises
    /// of the tree), any NaN matching any NaN: a NaN's payload is not part
    /// of the result, constant folding may choose another one.
    pub fn same_bits(&self, other: &SplitDistance) -> bool {
        let same = |a: f32, b: f32| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        same(self.safe, other.safe)
            && same(self.surface, other.surface)
            && self.material == other.material
    }
}

/// A node of an SDF tree, and the tree below it.
///
/// Nodes are built by the constructors below, which validate their parameters
/// (finite, non-negative sizes, positive scales, non-empty operators, instances
/// confined to their repetition cells, depth ≤ [`MAX_DEPTH`]), so every
/// `SdfNode` that exists can be evaluated: for finite `p` (with `|p|` and
/// every size well inside `f32` range, say below `10¹⁸`, so that squared
/// lengths do not overflow), [`eval`](SdfNode::eval) returns a finite distance
/// and a material index no larger than [`max_material`](SdfNode::max_material).
/// It never panics or allocates; a NaN point gives a NaN or arbitrary finite
/// distance (a NaN is what the CTSS stepper stops on).
///
/// Each node caches what its constructor learnt: a conservative bounding box,
/// its [`Exactness`], whether it may overestimate, its mirror symmetries, its
/// depth and its object count.
#[derive(Clone, Debug)]
pub struct SdfNode {
    pub(super) op: Op,
    pub(super) info: Info,
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Info {
    pub(super) bounds: Aabb,
    exactness: Exactness,
    /// `f ≤` the true distance outside (and `|f| ≤` depth inside).
    conservative: bool,
    /// Mirror symmetric about `x = 0`, `y = 0`, `z = 0`.
    symmetry: [bool; 3],
    depth: u32,
    /// Saturating; `u64::MAX` for infinite repetition.
    objects: u64,
    /// How far operators above may lower this field (round, onion,
    /// displacement, smooth union) before a capped step bound in it would
    /// turn negative away from every surface; `∞` when the field has no cap.
    /// See [`SdfNode::onion`].
    offset_limit: f32,
    max_material: u32,
    /// A material of the subtree, returned where no object decides.
    pub(super) material: u32,
}

/// A node's operation and operands, as [`SdfNode::op`] shows them to code
/// that compiles or writes a tree (`subcone-sdf`'s interpreter and WGSL
/// generator, `subcone-load`'s file writer). Read only: a tree is built by
/// [`SdfNode`]'s validating constructors, whose cached facts these values
/// must agree with.
///
/// Not `#[non_exhaustive]`, on purpose: a new operation is a breaking change
/// that every compiler of a tree must handle, and an exhaustive `match` makes
/// each one say how.
#[derive(Clone, Debug)]
pub enum Op {
    /// A primitive.
    Shape {
        /// The primitive and its parameters.
        shape: Shape,
        /// Its material index.
        material: u32,
    },
    /// `min` of the children.
    Union {
        /// The operands.
        children: Vec<SdfNode>,
        /// Per child: bounding sphere `(centre, radius)`, radius ∞ when the
        /// child is unbounded or may not be skipped.
        spheres: Vec<Vec4>,
    },
    /// `max` of the children.
    Intersection(Vec<SdfNode>),
    /// Polynomial smooth minimum of the children.
    SmoothUnion {
        /// The blend radius.
        k: f32,
        /// The operands.
        children: Vec<SdfNode>,
    },
    /// The first minus the second.
    Subtract(Box<(SdfNode, SdfNode)>),
    /// A child moved, rotated and uniformly scaled.
    Transform(Box<Transform>),
    /// A child mirrored across the planes `x = 0`, `y = 0`, `z = 0`.
    Mirror {
        /// Which planes.
        axes: [bool; 3],
        /// The operand.
        child: Box<SdfNode>,
    },
    /// A child repeated on a grid.
    Repeat(Box<Repeat>),
    /// The child's surface pushed out by a radius.
    Round {
        /// The radius.
        radius: f32,
        /// The operand.
        child: Box<SdfNode>,
    },
    /// A shell of the child's surface.
    Onion {
        /// The shell's thickness.
        thickness: f32,
        /// The operand.
        child: Box<SdfNode>,
    },
    /// The child's value times a factor (not a distance unless 1).
    ScaleDistance {
        /// The factor.
        factor: f32,
        /// The operand.
        child: Box<SdfNode>,
    },
    /// The child plus a sine displacement.
    Displace {
        /// The displacement's amplitude.
        amplitude: f32,
        /// Its spatial frequency.
        frequency: f32,
        /// The operand.
        child: Box<SdfNode>,
    },
    /// The child, skipped while farther than its bounds plus a pad.
    Bounded {
        /// The pad around the bounds.
        pad: f32,
        /// The operand.
        child: Box<SdfNode>,
    },
    /// Templates scattered over a random grid.
    Scatter(Box<Scatter>),
}

/// The operand of [`Op::Transform`].
#[derive(Clone, Debug)]
pub struct Transform {
    /// Child space to world: `p = translation + rotation · (scale · q)`.
    pub translation: Vec3,
    /// The rotation, unit.
    pub rotation: Quat,
    /// The uniform scale, positive.
    pub scale: f32,
    /// `rotation`'s inverse.
    pub inv_rotation: Quat,
    /// `1 / scale`.
    pub inv_scale: f32,
    /// Whether `rotation` is not the identity.
    pub rotated: bool,
    /// The transformed node.
    pub child: SdfNode,
}

/// The operand of [`Op::Repeat`].
#[derive(Clone, Debug)]
pub struct Repeat {
    /// Period per axis; 0 = not repeated along that axis.
    pub period: Vec3,
    /// Lowest cell index (inclusive) per axis, −∞ when unlimited.
    pub lo: Vec3,
    /// Highest cell index (inclusive) per axis, +∞ when unlimited.
    pub hi: Vec3,
    /// Take `min(d, distance to the cell's walls + margin)` (asymmetric child).
    pub guard: bool,
    /// The margin added to the distance to the cell's walls.
    pub margin: f32,
    /// The repeated node.
    pub child: SdfNode,
}

impl Repeat {
    /// The point in its cell's frame, and (for guarded repetition) the distance
    /// to the walls that have a neighbouring cell; `∞` otherwise.
    #[inline]
    fn cell(&self, p: Vec3) -> (Vec3, f32) {
        let mut q = p;
        let mut wall = f32::INFINITY;
        for k in 0..3 {
            let c = self.period[k];
            if c > 0.0 {
                let i = round_cell(p[k] / c).clamp(self.lo[k], self.hi[k]);
                q[k] = p[k] - c * i;
                if self.guard {
                    if i < self.hi[k] {
                        wall = wall.min(0.5 * c - q[k]);
                    }
                    if i > self.lo[k] {
                        wall = wall.min(0.5 * c + q[k]);
                    }
                }
            }
        }
        (q, wall)
    }
}

fn depth_of(node: &'static str, children: &[&SdfNode]) -> Result<u32, SdfError> {
    let d = 1 + children.iter().map(|c| c.info.depth).max().unwrap_or(0);
    if d > MAX_DEPTH {
        Err(SdfError::TooDeep {
            node,
            max: MAX_DEPTH,
        })
    } else {
        Ok(d)
    }
}

impl SdfNode {
    // ---------------------------------------------------------------- shapes

    /// A primitive shape with material 0 (see [`SdfNode::with_material`]).
    pub fn shape(shape: Shape) -> Result<SdfNode, SdfError> {
        let shape = shape.validated()?;
        Ok(SdfNode {
            info: Info {
                bounds: shape.bounds(),
                exactness: shape.exactness(),
                conservative: true,
                symmetry: shape.symmetry(),
                depth: 1,
                objects: 1,
                offset_limit: f32::INFINITY,
                max_material: 0,
                material: 0,
            },
            op: Op::Shape { shape, material: 0 },
        })
    }

    /// [`Shape::Sphere`].
    pub fn sphere(radius: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Sphere { radius })
    }

    /// [`Shape::Box`] with half extents `half`.
    pub fn cuboid(half: Vec3) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Box { half })
    }

    /// [`Shape::RoundBox`].
    pub fn round_box(half: Vec3, radius: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::RoundBox { half, radius })
    }

    /// [`Shape::BoxFrame`].
    pub fn box_frame(half: Vec3, thickness: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::BoxFrame { half, thickness })
    }

    /// [`Shape::Torus`].
    pub fn torus(major: f32, minor: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Torus { major, minor })
    }

    /// [`Shape::Link`].
    pub fn link(half_length: f32, major: f32, minor: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Link {
            half_length,
            major,
            minor,
        })
    }

    /// [`Shape::Capsule`].
    pub fn capsule(half_height: f32, radius: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Capsule {
            half_height,
            radius,
        })
    }

    /// [`Shape::Cylinder`].
    pub fn cylinder(radius: f32, half_height: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Cylinder {
            radius,
            half_height,
        })
    }

    /// [`Shape::RoundedCylinder`].
    pub fn rounded_cylinder(
        radius: f32,
        half_height: f32,
        rounding: f32,
    ) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::RoundedCylinder {
            radius,
            half_height,
            rounding,
        })
    }

    /// [`Shape::CappedCone`].
    pub fn capped_cone(half_height: f32, bottom: f32, top: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::CappedCone {
            half_height,
            bottom,
            top,
        })
    }

    /// [`Shape::Octahedron`].
    pub fn octahedron(size: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Octahedron { size })
    }

    /// [`Shape::HexPrism`].
    pub fn hex_prism(apothem: f32, half_height: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::HexPrism {
            apothem,
            half_height,
        })
    }

    /// [`Shape::Ellipsoid`] (a bound).
    pub fn ellipsoid(radii: Vec3) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Ellipsoid { radii })
    }

    /// [`Shape::Plane`]: the half-space `dot(p, normal) + offset ≤ 0`.
    pub fn plane(normal: Vec3, offset: f32) -> Result<SdfNode, SdfError> {
        Self::shape(Shape::Plane { normal, offset })
    }

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
    /// the scene's materials; checked by [`SdfScene::new`](super::SdfScene::new)).
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

    // ----------------------------------------------------------- properties

    /// Whether the tree is an exact distance (see [`Exactness`]).
    pub fn is_exact(&self) -> bool {
        self.info.exactness == Exactness::Exact
    }

    /// Exact, bound or non-Eikonal.
    pub fn exactness(&self) -> Exactness {
        self.info.exactness
    }

    /// Whether the value never overestimates the distance to the surface
    /// (exact, bound, or a non-Eikonal tree whose gradient is at most 1): safe
    /// for sphere tracing.
    pub fn is_conservative(&self) -> bool {
        self.info.conservative
    }

    /// A conservative bounding box of the surface (possibly infinite).
    pub fn bounds(&self) -> Aabb {
        self.info.bounds
    }

    /// The box of the tree's bounded objects: [`bounds`](Self::bounds) when
    /// it is finite; for a union (sharp or smooth) whose box is not, the
    /// union of its children's finite boxes, found the same way, so that an
    /// infinite floor plane beside bounded objects leaves the objects' box;
    /// `None` when no part of the tree is bounded (a lone plane, infinite
    /// repetition, an unbounded intersection or transform of one).
    pub fn finite_bounds(&self) -> Option<Aabb> {
        if self.info.bounds.is_finite() {
            return Some(self.info.bounds);
        }
        match &self.op {
            Op::Union { children, .. } | Op::SmoothUnion { children, .. } => children
                .iter()
                .filter_map(SdfNode::finite_bounds)
                .reduce(|a, b| a.union(&b)),
            _ => None,
        }
    }

    /// Depth of the tree (a single primitive is 1).
    pub fn depth(&self) -> u32 {
        self.info.depth
    }

    /// Number of primitive instances (repetition and mirrors multiply,
    /// scatters count occupied cells); `None` when infinite.
    pub fn object_count(&self) -> Option<u64> {
        (self.info.objects != u64::MAX).then_some(self.info.objects)
    }

    /// The node's operation and operands, for code that compiles or writes
    /// the tree.
    pub fn op(&self) -> &Op {
        &self.op
    }

    /// The material returned where no object decides (a point where every
    /// operand was skipped): a material of the subtree.
    pub fn default_material(&self) -> u32 {
        self.info.material
    }

    /// The largest material index used.
    pub fn max_material(&self) -> u32 {
        self.info.max_material
    }

    /// Every material index used, ascending.
    pub fn materials_used(&self) -> Vec<u32> {
        let mut out = Vec::new();
        self.collect_materials(&mut out);
        out.sort_unstable();
        out.dedup();
        out
    }

    fn collect_materials(&self, out: &mut Vec<u32>) {
        match &self.op {
            Op::Shape { material, .. } => out.push(*material),
            Op::Union { children: c, .. }
            | Op::Intersection(c)
            | Op::SmoothUnion { children: c, .. } => {
                c.iter().for_each(|c| c.collect_materials(out))
            }
            Op::Subtract(ab) => {
                ab.0.collect_materials(out);
                ab.1.collect_materials(out);
            }
            Op::Transform(t) => t.child.collect_materials(out),
            Op::Repeat(r) => r.child.collect_materials(out),
            Op::Mirror { child, .. }
            | Op::Round { child, .. }
            | Op::Onion { child, .. }
            | Op::ScaleDistance { child, .. }
            | Op::Displace { child, .. }
            | Op::Bounded { child, .. } => child.collect_materials(out),
            Op::Scatter(s) => {
                if s.palette().is_empty() {
                    s.templates().iter().for_each(|t| t.collect_materials(out));
                } else {
                    out.extend_from_slice(s.palette());
                }
            }
        }
    }

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
