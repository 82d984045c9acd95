//! The file's data model: what serde reads and writes. Every type mirrors a
//! part of [`SdfScene`](subcone_scene::sdf::SdfScene) with the names a scene author
//! types; building checks happen in `build.rs`, one node at a time while the
//! file is read, so that an error carries the place it was found.

use serde::{Deserialize, Serialize};

/// `(x, y, z)`.
pub(super) type V3 = [f32; 3];

/// The whole file. `N` is a node: [`super::build::Parsed`] when reading
/// (built as it is read), [`Written`] when writing.
#[derive(Serialize, Deserialize)]
#[serde(rename = "SdfScene", deny_unknown_fields)]
pub(super) struct SceneDesc<N> {
    #[serde(default = "format_version")]
    pub(super) version: u32,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) name: Option<String>,
    pub(super) camera: CameraDesc,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub(super) materials: Vec<MaterialDesc>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub(super) lights: Vec<LightDesc>,
    #[serde(default = "background")]
    pub(super) background: V3,
    #[serde(default = "ambient")]
    pub(super) ambient: V3,
    #[serde(default = "max_distance")]
    pub(super) max_distance: f32,
    #[serde(default = "max_steps")]
    pub(super) max_steps: u32,
    pub(super) root: N,
}

/// The format version this build reads and writes.
pub(super) const FORMAT_VERSION: u32 = 1;

fn format_version() -> u32 {
    FORMAT_VERSION
}
pub(super) fn background() -> V3 {
    [0.05, 0.05, 0.06]
}
pub(super) fn ambient() -> V3 {
    [0.03; 3]
}
pub(super) fn max_distance() -> f32 {
    100.0
}
pub(super) fn max_steps() -> u32 {
    512
}
/// The default vertical field of view, in degrees.
pub(super) const DEFAULT_FOV_DEGREES: f32 = 45.0;

/// The camera: where it stands, where it looks, how wide.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Camera", deny_unknown_fields)]
pub(super) struct CameraDesc {
    pub(super) position: V3,
    /// A point to look at; or give `forward`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) target: Option<V3>,
    /// The view direction; or give `target`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) forward: Option<V3>,
    /// Roughly up; `(0, 1, 0)` when omitted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) up: Option<V3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) fov_degrees: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) fov_radians: Option<f32>,
}

/// A material.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Material", deny_unknown_fields)]
pub(super) struct MaterialDesc {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) name: Option<String>,
    #[serde(default = "grey")]
    pub(super) albedo: AlbedoDesc,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub(super) mirror: f32,
    #[serde(default, skip_serializing_if = "is_black")]
    pub(super) emission: V3,
    #[serde(default = "opaque", skip_serializing_if = "is_one")]
    pub(super) alpha: f32,
}

fn grey() -> AlbedoDesc {
    AlbedoDesc::Solid([0.7; 3])
}
fn opaque() -> f32 {
    1.0
}
#[allow(clippy::trivially_copy_pass_by_ref)] // serde's `skip_serializing_if` passes `&T`
fn is_zero(v: &f32) -> bool {
    v.to_bits() == 0
}
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_one(v: &f32) -> bool {
    *v == 1.0
}
fn is_black(v: &V3) -> bool {
    v.iter().all(|c| c.to_bits() == 0)
}
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_zero_u32(v: &u32) -> bool {
    *v == 0
}

/// Where a surface's colour comes from.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) enum AlbedoDesc {
    Solid(V3),
    Checker { a: V3, b: V3, size: f32 },
    Patches { palette: Vec<V3>, size: f32 },
}

/// A light.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) enum LightDesc {
    Point { position: V3, intensity: V3 },
    Directional { direction: V3, irradiance: V3 },
}

/// A rotation.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) enum RotationDesc {
    /// A quaternion `(x, y, z, w)`, normalised unless already unit.
    Quat(f32, f32, f32, f32),
    /// About `axis` (normalised) by `degrees`, counter-clockwise looking down
    /// the axis.
    AxisAngle { axis: V3, degrees: f32 },
}

/// A coordinate axis, for mirrors.
#[derive(Serialize, Deserialize, Clone, Copy, PartialEq, Eq)]
pub(super) enum Axis {
    X,
    Y,
    Z,
}

/// One node of the tree. `C` is a child node.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) enum NodeDesc<C> {
    // ------------------------------------------------------------ primitives
    Sphere {
        radius: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Box {
        half: V3,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    RoundBox {
        half: V3,
        radius: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    BoxFrame {
        half: V3,
        thickness: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Torus {
        major: f32,
        minor: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Link {
        half_length: f32,
        major: f32,
        minor: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Capsule {
        half_height: f32,
        radius: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Cylinder {
        radius: f32,
        half_height: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    RoundedCylinder {
        radius: f32,
        half_height: f32,
        rounding: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    CappedCone {
        half_height: f32,
        bottom: f32,
        top: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Octahedron {
        size: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    HexPrism {
        apothem: f32,
        half_height: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Ellipsoid {
        radii: V3,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    Plane {
        normal: V3,
        #[serde(default)]
        offset: f32,
        #[serde(default, skip_serializing_if = "is_zero_u32")]
        material: u32,
    },
    // ------------------------------------------------------------- operators
    Union(Vec<C>),
    Intersection(Vec<C>),
    SmoothUnion {
        k: f32,
        children: Vec<C>,
    },
    Subtract {
        from: Box<C>,
        remove: Box<C>,
    },
    Transform {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        translate: Option<V3>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rotate: Option<RotationDesc>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        scale: Option<f32>,
        child: Box<C>,
    },
    Mirror {
        axes: Vec<Axis>,
        child: Box<C>,
    },
    Repeat {
        period: V3,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        lo: Option<[i32; 3]>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        hi: Option<[i32; 3]>,
        child: Box<C>,
    },
    Round {
        radius: f32,
        child: Box<C>,
    },
    Onion {
        thickness: f32,
        child: Box<C>,
    },
    ScaleDistance {
        factor: f32,
        child: Box<C>,
    },
    Displace {
        amplitude: f32,
        frequency: f32,
        child: Box<C>,
    },
    Bounded {
        pad: f32,
        child: Box<C>,
    },
    /// [`subcone_scene::sdf::ScatterConfig`] and its templates.
    Scatter {
        #[serde(default)]
        origin: V3,
        cell: V3,
        lo: [i32; 3],
        hi: [i32; 3],
        #[serde(default)]
        seed: u64,
        #[serde(default = "opaque")]
        fill: f32,
        /// 5 % of the smallest cell side when omitted.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        margin: Option<f32>,
        #[serde(default = "half")]
        min_size: f32,
        #[serde(default = "opaque")]
        max_size: f32,
        #[serde(default = "yes")]
        rotate: bool,
        #[serde(default = "yes")]
        jitter: bool,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        palette: Vec<u32>,
        templates: Vec<C>,
    },
    Material {
        index: u32,
        child: Box<C>,
    },
}

fn half() -> f32 {
    0.5
}
fn yes() -> bool {
    true
}

/// A node on its way out.
#[derive(Serialize)]
#[serde(transparent)]
pub(super) struct Written(pub(super) NodeDesc<Written>);
