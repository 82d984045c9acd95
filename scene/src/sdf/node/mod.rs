//! The SDF tree: validated nodes, their operations and what each node
//! caches (here: the types, the primitives' constructors and the
//! properties), the operators' constructors (`ops`), evaluation and normals
//! (`eval`), and the scatter operator's grid (`scatter`), whose templates
//! are trees in turn.

use glam::{Quat, Vec3, Vec4};

use super::bounds::{round_cell, Aabb};
use super::shape::Shape;
use super::{Exactness, SdfError};

mod eval;
mod ops;
pub(super) mod scatter;

pub use eval::{tetra_normal_from, tetra_taps};
use scatter::Scatter;

/// Deepest tree accepted: evaluation recurses once per level, so the depth is
/// bounded to keep stack use small on worker threads.
pub const MAX_DEPTH: u32 = 64;

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
}
