//! Primitive shapes in canonical position: centred on the origin, axis along
//! `y` where there is one. Place them with [`SdfNode::translate`],
//! [`SdfNode::rotate`] and [`SdfNode::scale`](crate::sdf::SdfNode::scale).
//!
//! Formulas follow Inigo Quilez's list of distance functions
//! (<https://iquilezles.org/articles/distfunctions/>), reparametrised where his
//! parameters are awkward (outer sizes everywhere, half extents for boxes).
//!
//! [`SdfNode::translate`]: crate::sdf::SdfNode::translate
//! [`SdfNode::rotate`]: crate::sdf::SdfNode::rotate

use glam::Vec3;
use subcone_kernels::math::Euclidean;

use super::bounds::Aabb;
use super::check::{all_finite, at_most, finite, nonneg, nonneg3, UNIT_TOLERANCE};
use super::{Exactness, SdfError};

/// A primitive shape. Build a node from it with
/// [`SdfNode::shape`](crate::sdf::SdfNode::shape) (which validates it) or the
/// per-shape constructors of [`SdfNode`](crate::sdf::SdfNode).
///
/// Sizes are non-negative and finite; zero sizes give degenerate but valid
/// shapes (a sphere of radius 0 is a point). All shapes are exact distances
/// except [`Shape::Ellipsoid`] (a bound).
///
/// Not `#[non_exhaustive]`: every compiler of a tree (the 8-lane interpreter
/// and the WGSL generator of `subcone-sdf`, the file writer of
/// `subcone-load`) matches on it, so a new shape is a breaking change that
/// does not compile until each says how to evaluate or write it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Sphere. Exact.
    Sphere {
        /// Radius.
        radius: f32,
    },
    /// Axis-aligned box. Exact.
    Box {
        /// Half extents.
        half: Vec3,
    },
    /// Box with rounded edges; `half` is the outer half extent. Exact.
    RoundBox {
        /// Outer half extents.
        half: Vec3,
        /// Edge radius, at most the smallest half extent.
        radius: f32,
    },
    /// The twelve edges of a box, as square bars. Exact.
    BoxFrame {
        /// Outer half extents.
        half: Vec3,
        /// Bar thickness (full width of a bar's square section), at most the
        /// smallest half extent.
        thickness: f32,
    },
    /// Torus in the `xz` plane. Exact (outside; a spindle torus with
    /// `minor > major` is exact outside too).
    Torus {
        /// Radius of the centre circle.
        major: f32,
        /// Radius of the tube.
        minor: f32,
    },
    /// A chain link: a torus of `major` radius stretched by `half_length`
    /// along `y`, tube radius `minor`. Exact.
    Link {
        /// Half length of the straight parts.
        half_length: f32,
        /// Radius of the centre line's round ends.
        major: f32,
        /// Radius of the tube.
        minor: f32,
    },
    /// Capsule along `y`: a segment from `-half_height` to `half_height`
    /// thickened by `radius`. Exact.
    Capsule {
        /// Half length of the segment.
        half_height: f32,
        /// Radius.
        radius: f32,
    },
    /// Capped cylinder along `y`. Exact.
    Cylinder {
        /// Radius.
        radius: f32,
        /// Half height.
        half_height: f32,
    },
    /// Capped cylinder along `y` with rounded rims; outer dimensions. Exact.
    RoundedCylinder {
        /// Outer radius.
        radius: f32,
        /// Outer half height.
        half_height: f32,
        /// Rim radius, at most `radius` and `half_height`.
        rounding: f32,
    },
    /// Capped cone along `y`: radius `bottom` at `y = -half_height`, `top` at
    /// `y = half_height`. Exact.
    CappedCone {
        /// Half height.
        half_height: f32,
        /// Radius at the bottom.
        bottom: f32,
        /// Radius at the top.
        top: f32,
    },
    /// Regular octahedron `|x| + |y| + |z| = size`. Exact (Quilez's exact
    /// version, not the `(|x|+|y|+|z|-s)/√3` bound).
    Octahedron {
        /// Distance from the centre to a vertex.
        size: f32,
    },
    /// Hexagonal prism along `y`. Exact.
    HexPrism {
        /// Distance from the axis to a flat side.
        apothem: f32,
        /// Half height.
        half_height: f32,
    },
    /// Ellipsoid with semi-axes `radii`. A **bound**: Quilez's
    /// `k0 (k0 − 1) / k1`, which never overestimates outside but whose gradient
    /// is far from unit length near the flat sides of thin ellipsoids.
    Ellipsoid {
        /// Semi-axes, all strictly positive.
        radii: Vec3,
    },
    /// Half-space `dot(p, normal) + offset ≤ 0`. Exact. Unbounded.
    Plane {
        /// Outward normal (normalised on construction).
        normal: Vec3,
        /// Signed offset: the plane is `dot(p, normal) = -offset`.
        offset: f32,
    },
}

/// A box's half extents and a size that runs along its edges (a rounding
/// radius, a bar's thickness), at most the smallest half extent.
fn box_and_edge(
    shape: &'static str,
    half: Vec3,
    param: &'static str,
    edge: f32,
) -> Result<(), SdfError> {
    nonneg3(shape, "half extents", half)?;
    nonneg(shape, param, edge)?;
    at_most(
        shape,
        param,
        edge,
        half.min_element(),
        "the smallest half extent",
    )
}

impl Shape {
    /// The shape's name, for messages.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "sphere",
            Shape::Box { .. } => "box",
            Shape::RoundBox { .. } => "round box",
            Shape::BoxFrame { .. } => "box frame",
            Shape::Torus { .. } => "torus",
            Shape::Link { .. } => "link",
            Shape::Capsule { .. } => "capsule",
            Shape::Cylinder { .. } => "cylinder",
            Shape::RoundedCylinder { .. } => "rounded cylinder",
            Shape::CappedCone { .. } => "capped cone",
            Shape::Octahedron { .. } => "octahedron",
            Shape::HexPrism { .. } => "hex prism",
            Shape::Ellipsoid { .. } => "ellipsoid",
            Shape::Plane { .. } => "plane",
        }
    }

    /// Check the parameters and bring the shape to canonical form (the
    /// plane's normal normalised).
    pub fn validated(self) -> Result<Shape, SdfError> {
        let n = self.name();
        match self {
            Shape::Sphere { radius } => {
                nonneg(n, "radius", radius)?;
            }
            Shape::Box { half } => nonneg3(n, "half extents", half)?,
            Shape::RoundBox { half, radius } => box_and_edge(n, half, "radius", radius)?,
            Shape::BoxFrame { half, thickness } => box_and_edge(n, half, "thickness", thickness)?,
            Shape::Torus { major, minor } => {
                nonneg(n, "major radius", major)?;
                nonneg(n, "minor radius", minor)?;
            }
            Shape::Link {
                half_length,
                major,
                minor,
            } => {
                nonneg(n, "half length", half_length)?;
                nonneg(n, "major radius", major)?;
                nonneg(n, "minor radius", minor)?;
            }
            Shape::Capsule {
                half_height,
                radius,
            } => {
                nonneg(n, "half height", half_height)?;
                nonneg(n, "radius", radius)?;
            }
            Shape::Cylinder {
                radius,
                half_height,
            } => {
                nonneg(n, "radius", radius)?;
                nonneg(n, "half height", half_height)?;
            }
            Shape::RoundedCylinder {
                radius,
                half_height,
                rounding,
            } => {
                nonneg(n, "radius", radius)?;
                nonneg(n, "half height", half_height)?;
                nonneg(n, "rounding", rounding)?;
                at_most(
                    n,
                    "rounding",
                    rounding,
                    radius.min(half_height),
                    "the radius or half height",
                )?;
            }
            Shape::CappedCone {
                half_height,
                bottom,
                top,
            } => {
                nonneg(n, "half height", half_height)?;
                nonneg(n, "bottom radius", bottom)?;
                nonneg(n, "top radius", top)?;
            }
            Shape::Octahedron { size } => {
                nonneg(n, "size", size)?;
            }
            Shape::HexPrism {
                apothem,
                half_height,
            } => {
                nonneg(n, "apothem", apothem)?;
                nonneg(n, "half height", half_height)?;
            }
            Shape::Ellipsoid { radii } => {
                nonneg3(n, "radii", radii)?;
                if radii.min_element() <= 0.0 {
                    return Err(SdfError::Invalid {
                        node: n,
                        reason: format!("radii must be strictly positive, got {radii}"),
                    });
                }
            }
            Shape::Plane { normal, offset } => {
                all_finite(n, "normal", normal.is_finite())?;
                finite(n, "offset", offset)?;
                let len = normal.norm();
                if len <= 1e-12 || !len.is_finite() {
                    return Err(SdfError::Invalid {
                        node: n,
                        reason: format!("normal {normal} has no usable direction"),
                    });
                }
                // Kept as given when already unit (see `UNIT_TOLERANCE`).
                let unit = (f64::from(len) - 1.0).abs() <= UNIT_TOLERANCE;
                return Ok(Shape::Plane {
                    normal: if unit { normal } else { normal / len },
                    offset,
                });
            }
        }
        Ok(self)
    }

    /// Whether the formula is an exact distance or a bound.
    pub fn exactness(&self) -> Exactness {
        match self {
            Shape::Ellipsoid { .. } => Exactness::Bound,
            _ => Exactness::Exact,
        }
    }

    /// A box containing the shape (infinite for the plane unless it is
    /// axis-aligned, where one side is bounded).
    pub(crate) fn bounds(&self) -> Aabb {
        let b = |h: Vec3| Aabb::new(-h, h);
        match *self {
            Shape::Sphere { radius } => b(Vec3::splat(radius)),
            Shape::Box { half } | Shape::RoundBox { half, .. } | Shape::BoxFrame { half, .. } => {
                b(half)
            }
            Shape::Torus { major, minor } => b(Vec3::new(major + minor, minor, major + minor)),
            Shape::Link {
                half_length,
                major,
                minor,
            } => b(Vec3::new(major + minor, half_length + major + minor, minor)),
            Shape::Capsule {
                half_height,
                radius,
            } => b(Vec3::new(radius, half_height + radius, radius)),
            Shape::Cylinder {
                radius,
                half_height,
            }
            | Shape::RoundedCylinder {
                radius,
                half_height,
                ..
            } => b(Vec3::new(radius, half_height, radius)),
            Shape::CappedCone {
                half_height,
                bottom,
                top,
            } => {
                let r = bottom.max(top);
                b(Vec3::new(r, half_height, r))
            }
            Shape::Octahedron { size } => b(Vec3::splat(size)),
            Shape::HexPrism {
                apothem,
                half_height,
            } => {
                // Corner radius of the hexagon: apothem / cos 30°.
                let r = apothem * 1.154_700_6;
                b(Vec3::new(r, half_height, r))
            }
            Shape::Ellipsoid { radii } => b(radii),
            Shape::Plane { normal, offset } => {
                let mut min = Vec3::NEG_INFINITY;
                let mut max = Vec3::INFINITY;
                // An axis-aligned plane bounds one side.
                for k in 0..3 {
                    let others = (0..3).filter(|&j| j != k).all(|j| normal[j] == 0.0);
                    if others {
                        if normal[k] > 0.0 {
                            max[k] = -offset / normal[k];
                        } else if normal[k] < 0.0 {
                            min[k] = -offset / normal[k];
                        }
                    }
                }
                Aabb::new(min, max)
            }
        }
    }

    /// Whether the shape is its own mirror image about the planes `x = 0`,
    /// `y = 0`, `z = 0`.
    pub(crate) fn symmetry(&self) -> [bool; 3] {
        match *self {
            Shape::CappedCone { bottom, top, .. } => [true, bottom == top, true],
            Shape::Plane { normal, .. } => [normal.x == 0.0, normal.y == 0.0, normal.z == 0.0],
            _ => [true; 3],
        }
    }
}
