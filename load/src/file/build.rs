//! From the file's data model to validated scene parts.
//!
//! Nodes are built while the file is read ([`Parsed`] is deserialised through
//! `TryFrom<NodeDesc<Parsed>>`), bottom-up like the builder calls a Rust
//! author would write, so a bad value is reported with the line and the path
//! of the node it is in. Camera, materials and lights are checked after the
//! whole file is read and reported by their path.

use glam::{Quat, Vec3};
use serde::Deserialize;
use subcone_kernels::math::Euclidean;

use super::desc::{
    AlbedoDesc, Axis, CameraDesc, LightDesc, MaterialDesc, NodeDesc, RotationDesc,
    DEFAULT_FOV_DEGREES, V3,
};
use subcone_scene::camera::Camera;
use subcone_scene::light::Light;
use subcone_scene::material::{Albedo, Material};
use subcone_scene::sdf::UNIT_TOLERANCE;
use subcone_scene::sdf::{ScatterConfig, SdfError, SdfNode};

/// A node read from a file, already built and validated.
#[derive(Deserialize)]
#[serde(try_from = "NodeDesc<Parsed>")]
pub(super) struct Parsed(pub(super) SdfNode);

fn v(a: V3) -> Vec3 {
    Vec3::from_array(a)
}

fn nodes(children: Vec<Parsed>) -> Vec<SdfNode> {
    children.into_iter().map(|c| c.0).collect()
}

impl TryFrom<NodeDesc<Parsed>> for Parsed {
    type Error = SdfError;

    fn try_from(d: NodeDesc<Parsed>) -> Result<Self, SdfError> {
        let node = match d {
            NodeDesc::Union(c) => SdfNode::union(nodes(c)),
            NodeDesc::Intersection(c) => SdfNode::intersection(nodes(c)),
            NodeDesc::SmoothUnion { k, children } => SdfNode::smooth_union(k, nodes(children)),
            NodeDesc::Subtract { from, remove } => from.0.subtract(remove.0),
            NodeDesc::Transform {
                translate,
                rotate,
                scale,
                child,
            } => {
                let rotation = match rotate {
                    None => Quat::IDENTITY,
                    Some(r) => rotation(r)?,
                };
                child.0.transform(
                    translate.map_or(Vec3::ZERO, v),
                    rotation,
                    scale.unwrap_or(1.0),
                )
            }
            NodeDesc::Mirror { axes, child } => {
                let mut on = [false; 3];
                for a in axes {
                    on[a as usize] = true;
                }
                child.0.mirror(on)
            }
            NodeDesc::Repeat {
                period,
                lo,
                hi,
                child,
            } => match (lo, hi) {
                (None, None) => child.0.repeat(v(period)),
                (Some(lo), Some(hi)) => child.0.repeat_limited(v(period), lo, hi),
                _ => Err(SdfError::Invalid {
                    node: "repetition",
                    reason: "give both `lo` and `hi` (a limited repetition) or neither".into(),
                }),
            },
            NodeDesc::Round { radius, child } => child.0.round(radius),
            NodeDesc::Onion { thickness, child } => child.0.onion(thickness),
            NodeDesc::ScaleDistance { factor, child } => child.0.scale_distance(factor),
            NodeDesc::Displace {
                amplitude,
                frequency,
                child,
            } => child.0.displace(amplitude, frequency),
            NodeDesc::Bounded { pad, child } => child.0.bounded(pad),
            NodeDesc::Scatter {
                origin,
                cell,
                lo,
                hi,
                seed,
                fill,
                margin,
                min_size,
                max_size,
                rotate,
                jitter,
                palette,
                templates,
            } => {
                let mut config = ScatterConfig::new(v(cell), lo, hi, seed);
                config.origin = v(origin);
                config.fill = fill;
                if let Some(m) = margin {
                    config.margin = m;
                }
                config.min_size = min_size;
                config.max_size = max_size;
                config.rotate = rotate;
                config.jitter = jitter;
                config.palette = palette;
                SdfNode::scatter(config, nodes(templates))
            }
            NodeDesc::Material { index, child } => Ok(child.0.with_material(index)),
            // Named, not a wildcard: a new node must be routed.
            d @ (NodeDesc::Sphere { .. }
            | NodeDesc::Box { .. }
            | NodeDesc::RoundBox { .. }
            | NodeDesc::BoxFrame { .. }
            | NodeDesc::Torus { .. }
            | NodeDesc::Link { .. }
            | NodeDesc::Capsule { .. }
            | NodeDesc::Cylinder { .. }
            | NodeDesc::RoundedCylinder { .. }
            | NodeDesc::CappedCone { .. }
            | NodeDesc::Octahedron { .. }
            | NodeDesc::HexPrism { .. }
            | NodeDesc::Ellipsoid { .. }
            | NodeDesc::Plane { .. }) => primitive(d),
        };
        node.map(Parsed)
    }
}

/// A primitive shape's node, with its material. [`Parsed::try_from`]
/// builds every other node and hands this only the primitives.
fn primitive(d: NodeDesc<Parsed>) -> Result<SdfNode, SdfError> {
    let shape = |n: Result<SdfNode, SdfError>, material: u32| n.map(|n| n.with_material(material));
    match d {
        NodeDesc::Sphere { radius, material } => shape(SdfNode::sphere(radius), material),
        NodeDesc::Box { half, material } => shape(SdfNode::cuboid(v(half)), material),
        NodeDesc::RoundBox {
            half,
            radius,
            material,
        } => shape(SdfNode::round_box(v(half), radius), material),
        NodeDesc::BoxFrame {
            half,
            thickness,
            material,
        } => shape(SdfNode::box_frame(v(half), thickness), material),
        NodeDesc::Torus {
            major,
            minor,
            material,
        } => shape(SdfNode::torus(major, minor), material),
        NodeDesc::Link {
            half_length,
            major,
            minor,
            material,
        } => shape(SdfNode::link(half_length, major, minor), material),
        NodeDesc::Capsule {
            half_height,
            radius,
            material,
        } => shape(SdfNode::capsule(half_height, radius), material),
        NodeDesc::Cylinder {
            radius,
            half_height,
            material,
        } => shape(SdfNode::cylinder(radius, half_height), material),
        NodeDesc::RoundedCylinder {
            radius,
            half_height,
            rounding,
            material,
        } => shape(
            SdfNode::rounded_cylinder(radius, half_height, rounding),
            material,
        ),
        NodeDesc::CappedCone {
            half_height,
            bottom,
            top,
            material,
        } => shape(SdfNode::capped_cone(half_height, bottom, top), material),
        NodeDesc::Octahedron { size, material } => shape(SdfNode::octahedron(size), material),
        NodeDesc::HexPrism {
            apothem,
            half_height,
            material,
        } => shape(SdfNode::hex_prism(apothem, half_height), material),
        NodeDesc::Ellipsoid { radii, material } => shape(SdfNode::ellipsoid(v(radii)), material),
        NodeDesc::Plane {
            normal,
            offset,
            material,
        } => shape(SdfNode::plane(v(normal), offset), material),
        _ => unreachable!("Parsed::try_from builds the nodes that are not primitives"),
    }
}

impl Axis {
    pub(super) const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];
}

fn rotation(r: RotationDesc) -> Result<Quat, SdfError> {
    const NAME: &str = "transform";
    match r {
        // Validated (finite, non-zero) and normalised by `SdfNode::transform`.
        RotationDesc::Quat(x, y, z, w) => Ok(Quat::from_xyzw(x, y, z, w)),
        RotationDesc::AxisAngle { axis, degrees } => {
            let axis = v(axis);
            if !(axis.is_finite() && degrees.is_finite()) {
                return Err(SdfError::NonFinite {
                    node: NAME,
                    param: "rotation axis and angle",
                });
            }
            let unit = axis.unit_or_zero();
            if unit == Vec3::ZERO {
                return Err(SdfError::Invalid {
                    node: NAME,
                    reason: format!("rotation axis {axis} has no direction"),
                });
            }
            Ok(Quat::from_axis_angle(unit, degrees.to_radians()))
        }
    }
}

/// `v` if its length is 1 within [`UNIT_TOLERANCE`], else `v` normalised; `None`
/// when it has no direction.
fn unit(a: Vec3) -> Option<Vec3> {
    let len = f64::from(a.x).hypot(f64::from(a.y)).hypot(f64::from(a.z));
    if !(len.is_finite() && len > 1e-12) {
        None
    } else if (len - 1.0).abs() <= UNIT_TOLERANCE {
        Some(a)
    } else {
        Some(Vec3::from_array(
            a.to_array().map(|c| (f64::from(c) / len) as f32),
        ))
    }
}

/// The camera: `target` (with `up` as a hint, like [`Camera::look_at`]) or
/// `forward` and `up`, used as given when they already form an orthonormal
/// frame (as an exported file's do), else orthonormalised the same way.
pub(super) fn camera(c: &CameraDesc) -> Result<Camera, String> {
    let fov = match (c.fov_degrees, c.fov_radians) {
        (Some(_), Some(_)) => return Err("give `fov_degrees` or `fov_radians`, not both".into()),
        (Some(d), None) => d.to_radians(),
        (None, Some(r)) => r,
        (None, None) => DEFAULT_FOV_DEGREES.to_radians(),
    };
    let position = v(c.position);
    let up = c.up.map_or(Vec3::Y, v);
    let camera = match (c.target, c.forward) {
        (Some(_), Some(_)) => return Err("give `target` or `forward`, not both".into()),
        (None, None) => return Err("give a `target` to look at, or a `forward` direction".into()),
        (Some(target), None) => Camera::look_at(position, v(target), up, fov),
        (None, Some(forward)) => {
            let frame = unit(v(forward)).zip(unit(up));
            match frame {
                Some((f, u)) if f64::from(f.dot(u)).abs() <= UNIT_TOLERANCE => {
                    let cam = Camera {
                        position,
                        forward: f,
                        up: u,
                        fov_y: fov,
                        jitter: glam::Vec2::ZERO,
                    };
                    cam.validate().map(|()| cam)
                }
                _ => Camera::look_at(position, position + v(forward), up, fov),
            }
        }
    };
    camera.map_err(|e| e.to_string())
}

fn finite3(what: &str, a: V3) -> Result<Vec3, String> {
    let x = v(a);
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("{what} {x} must be finite"))
    }
}

fn colour(what: &str, a: V3) -> Result<Vec3, String> {
    let c = finite3(what, a)?;
    if c.min_element() < 0.0 {
        return Err(format!("{what} {c} must not be negative"));
    }
    Ok(c)
}

/// A scene-level colour (background, ambient): finite, not negative.
pub(super) fn colour_field(what: &str, a: V3) -> Result<Vec3, String> {
    colour(what, a)
}

fn in_unit(what: &str, x: f32) -> Result<f32, String> {
    if (0.0..=1.0).contains(&x) {
        Ok(x)
    } else {
        Err(format!("{what} {x} must be in [0, 1]"))
    }
}

fn size(what: &str, x: f32) -> Result<f32, String> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(format!("{what} {x} must be positive and finite"))
    }
}

/// A material; `index` names it when the file does not.
pub(super) fn material(m: MaterialDesc, index: usize) -> Result<Material, String> {
    let albedo = match m.albedo {
        AlbedoDesc::Solid(c) => Albedo::Solid(colour("albedo", c)?),
        AlbedoDesc::Checker { a, b, size: s } => Albedo::Checker {
            a: colour("checker colour a", a)?,
            b: colour("checker colour b", b)?,
            size: size("checker size", s)?,
        },
        AlbedoDesc::Patches { palette, size: s } => {
            if palette.is_empty() {
                return Err("a patch palette needs at least one colour".into());
            }
            Albedo::Patches {
                palette: palette
                    .into_iter()
                    .map(|c| colour("patch colour", c))
                    .collect::<Result<_, _>>()?,
                size: size("patch size", s)?,
            }
        }
    };
    Ok(Material {
        name: m.name.unwrap_or_else(|| format!("material {index}")),
        albedo,
        mirror: in_unit("mirror reflectance", m.mirror)?,
        emission: colour("emission", m.emission)?,
        alpha: in_unit("alpha", m.alpha)?,
    })
}

/// A light.
pub(super) fn light(l: LightDesc) -> Result<Light, String> {
    Ok(match l {
        LightDesc::Point {
            position,
            intensity,
        } => Light::Point {
            position: finite3("position", position)?,
            intensity: colour("intensity", intensity)?,
        },
        LightDesc::Directional {
            direction,
            irradiance,
        } => Light::Directional {
            direction: unit(finite3("direction", direction)?)
                .ok_or_else(|| "direction has no length".to_string())?,
            irradiance: colour("irradiance", irradiance)?,
        },
    })
}
