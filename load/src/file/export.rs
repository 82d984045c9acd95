//! From a scene to the file's data model: every node as the builder call that
//! makes it again, with the values the tree stores, so that reading the file
//! back builds the same tree, bit for bit.

use glam::{Quat, Vec3};

use super::desc::{
    AlbedoDesc, Axis, CameraDesc, LightDesc, MaterialDesc, NodeDesc, RotationDesc, SceneDesc,
    Written, FORMAT_VERSION,
};
use subcone_scene::light::Light;
use subcone_scene::material::{Albedo, Material};
use subcone_scene::sdf::Op;
use subcone_scene::sdf::{SdfNode, SdfScene, Shape};

fn a(x: Vec3) -> [f32; 3] {
    x.to_array()
}

/// The scene as the file describes it; errors name what the format cannot
/// hold (a texture).
pub(super) fn scene(s: &SdfScene) -> Result<SceneDesc<Written>, String> {
    let c = &s.camera;
    let degrees = c.fov_y.to_degrees();
    let exact_degrees = degrees.to_radians() == c.fov_y;
    Ok(SceneDesc {
        version: FORMAT_VERSION,
        name: Some(s.name.clone()),
        camera: CameraDesc {
            position: a(c.position),
            target: None,
            forward: Some(a(c.forward)),
            up: Some(a(c.up)),
            fov_degrees: exact_degrees.then_some(degrees),
            fov_radians: (!exact_degrees).then_some(c.fov_y),
        },
        materials: s.materials.iter().map(material).collect::<Result<_, _>>()?,
        lights: s.lights.iter().map(light).collect(),
        background: a(s.background),
        ambient: a(s.ambient),
        max_distance: s.max_distance,
        max_steps: s.max_steps,
        root: node(&s.root),
    })
}

fn material(m: &Material) -> Result<MaterialDesc, String> {
    let albedo = match &m.albedo {
        Albedo::Solid(c) => AlbedoDesc::Solid(a(*c)),
        Albedo::Checker { a: ca, b, size } => AlbedoDesc::Checker {
            a: a(*ca),
            b: a(*b),
            size: *size,
        },
        Albedo::Patches { palette, size } => AlbedoDesc::Patches {
            palette: palette.iter().map(|c| a(*c)).collect(),
            size: *size,
        },
        Albedo::Texture(_) => {
            return Err(format!(
                "material {:?} is textured, which SDF scene files cannot describe",
                m.name
            ))
        }
    };
    Ok(MaterialDesc {
        name: Some(m.name.clone()),
        albedo,
        mirror: m.mirror,
        emission: a(m.emission),
        alpha: m.alpha,
    })
}

fn light(l: &Light) -> LightDesc {
    match *l {
        Light::Point {
            position,
            intensity,
        } => LightDesc::Point {
            position: a(position),
            intensity: a(intensity),
        },
        Light::Directional {
            direction,
            irradiance,
        } => LightDesc::Directional {
            direction: a(direction),
            irradiance: a(irradiance),
        },
    }
}

fn boxed(n: &SdfNode) -> Box<Written> {
    Box::new(node(n))
}

fn all(children: &[SdfNode]) -> Vec<Written> {
    children.iter().map(node).collect()
}

/// Infinite cell limits (an unlimited repetition) are written as none.
fn limits(x: Vec3) -> Option<[i32; 3]> {
    x.is_finite()
        .then_some([x.x as i32, x.y as i32, x.z as i32])
}

fn node(n: &SdfNode) -> Written {
    Written(match n.op() {
        Op::Shape { shape, material } => shape_desc(*shape, *material),
        Op::Union { children, .. } => NodeDesc::Union(all(children)),
        Op::Intersection(children) => NodeDesc::Intersection(all(children)),
        Op::SmoothUnion { k, children } => NodeDesc::SmoothUnion {
            k: *k,
            children: all(children),
        },
        Op::Subtract(ab) => NodeDesc::Subtract {
            from: boxed(&ab.0),
            remove: boxed(&ab.1),
        },
        Op::Transform(t) => NodeDesc::Transform {
            translate: (t.translation != Vec3::ZERO).then(|| a(t.translation)),
            rotate: (t.rotation != Quat::IDENTITY).then(|| {
                let [x, y, z, w] = t.rotation.to_array();
                RotationDesc::Quat(x, y, z, w)
            }),
            scale: (t.scale != 1.0).then_some(t.scale),
            child: boxed(&t.child),
        },
        Op::Mirror { axes, child } => NodeDesc::Mirror {
            axes: Axis::ALL
                .into_iter()
                .filter(|&ax| axes[ax as usize])
                .collect(),
            child: boxed(child),
        },
        Op::Repeat(r) => {
            let (lo, hi) = match (limits(r.lo), limits(r.hi)) {
                (Some(lo), Some(hi)) => (Some(lo), Some(hi)),
                _ => (None, None),
            };
            NodeDesc::Repeat {
                period: a(r.period),
                lo,
                hi,
                child: boxed(&r.child),
            }
        }
        Op::Round { radius, child } => NodeDesc::Round {
            radius: *radius,
            child: boxed(child),
        },
        Op::Onion { thickness, child } => NodeDesc::Onion {
            thickness: *thickness,
            child: boxed(child),
        },
        Op::ScaleDistance { factor, child } => NodeDesc::ScaleDistance {
            factor: *factor,
            child: boxed(child),
        },
        Op::Displace {
            amplitude,
            frequency,
            child,
        } => NodeDesc::Displace {
            amplitude: *amplitude,
            frequency: *frequency,
            child: boxed(child),
        },
        Op::Bounded { pad, child } => NodeDesc::Bounded {
            pad: *pad,
            child: boxed(child),
        },
        Op::Scatter(s) => {
            let c = s.config();
            NodeDesc::Scatter {
                origin: a(c.origin),
                cell: a(c.cell),
                lo: c.lo,
                hi: c.hi,
                seed: c.seed,
                fill: c.fill,
                margin: Some(c.margin),
                min_size: c.min_size,
                max_size: c.max_size,
                rotate: c.rotate,
                jitter: c.jitter,
                palette: c.palette,
                templates: all(&s.templates),
            }
        }
    })
}

fn shape_desc(s: Shape, material: u32) -> NodeDesc<Written> {
    match s {
        Shape::Sphere { radius } => NodeDesc::Sphere { radius, material },
        Shape::Box { half } => NodeDesc::Box {
            half: a(half),
            material,
        },
        Shape::RoundBox { half, radius } => NodeDesc::RoundBox {
            half: a(half),
            radius,
            material,
        },
        Shape::BoxFrame { half, thickness } => NodeDesc::BoxFrame {
            half: a(half),
            thickness,
            material,
        },
        Shape::Torus { major, minor } => NodeDesc::Torus {
            major,
            minor,
            material,
        },
        Shape::Link {
            half_length,
            major,
            minor,
        } => NodeDesc::Link {
            half_length,
            major,
            minor,
            material,
        },
        Shape::Capsule {
            half_height,
            radius,
        } => NodeDesc::Capsule {
            half_height,
            radius,
            material,
        },
        Shape::Cylinder {
            radius,
            half_height,
        } => NodeDesc::Cylinder {
            radius,
            half_height,
            material,
        },
        Shape::RoundedCylinder {
            radius,
            half_height,
            rounding,
        } => NodeDesc::RoundedCylinder {
            radius,
            half_height,
            rounding,
            material,
        },
        Shape::CappedCone {
            half_height,
            bottom,
            top,
        } => NodeDesc::CappedCone {
            half_height,
            bottom,
            top,
            material,
        },
        Shape::Octahedron { size } => NodeDesc::Octahedron { size, material },
        Shape::HexPrism {
            apothem,
            half_height,
        } => NodeDesc::HexPrism {
            apothem,
            half_height,
            material,
        },
        Shape::Ellipsoid { radii } => NodeDesc::Ellipsoid {
            radii: a(radii),
            material,
        },
        Shape::Plane { normal, offset } => NodeDesc::Plane {
            normal: a(normal),
            offset,
            material,
        },
    }
}

/// The path, in the file's terms (`root.Union[1].Transform.child.Sphere`), of
/// the first object below `n` whose material index is at least `count`.
pub(super) fn material_path(n: &SdfNode, count: usize, at: &str) -> Option<String> {
    let child = |c: &SdfNode, seg: String| material_path(c, count, &format!("{at}.{seg}"));
    let list = |cs: &[SdfNode], seg: &str| {
        cs.iter()
            .enumerate()
            .find_map(|(i, c)| material_path(c, count, &format!("{at}.{seg}[{i}]")))
    };
    let variant = variant_name(n.op());
    match n.op() {
        Op::Shape { material, .. } => {
            ((*material as usize) >= count).then(|| format!("{at}.{variant}.material"))
        }
        Op::Union { children, .. } | Op::Intersection(children) => list(children, variant),
        Op::SmoothUnion { children, .. } => list(children, "SmoothUnion.children"),
        Op::Subtract(ab) => {
            child(&ab.0, "Subtract.from".into()).or_else(|| child(&ab.1, "Subtract.remove".into()))
        }
        Op::Transform(t) => child(&t.child, "Transform.child".into()),
        Op::Repeat(r) => child(&r.child, "Repeat.child".into()),
        Op::Mirror { child: c, .. }
        | Op::Round { child: c, .. }
        | Op::Onion { child: c, .. }
        | Op::ScaleDistance { child: c, .. }
        | Op::Displace { child: c, .. }
        | Op::Bounded { child: c, .. } => child(c, format!("{variant}.child")),
        Op::Scatter(s) => {
            let palette = &s.palette;
            match palette.iter().position(|&m| m as usize >= count) {
                Some(i) => Some(format!("{at}.Scatter.palette[{i}]")),
                None if palette.is_empty() => list(&s.templates, "Scatter.templates"),
                None => None,
            }
        }
    }
}

/// The node's name in the file.
fn variant_name(op: &Op) -> &'static str {
    match op {
        Op::Shape { shape, .. } => match shape {
            Shape::Sphere { .. } => "Sphere",
            Shape::Box { .. } => "Box",
            Shape::RoundBox { .. } => "RoundBox",
            Shape::BoxFrame { .. } => "BoxFrame",
            Shape::Torus { .. } => "Torus",
            Shape::Link { .. } => "Link",
            Shape::Capsule { .. } => "Capsule",
            Shape::Cylinder { .. } => "Cylinder",
            Shape::RoundedCylinder { .. } => "RoundedCylinder",
            Shape::CappedCone { .. } => "CappedCone",
            Shape::Octahedron { .. } => "Octahedron",
            Shape::HexPrism { .. } => "HexPrism",
            Shape::Ellipsoid { .. } => "Ellipsoid",
            Shape::Plane { .. } => "Plane",
        },
        Op::Union { .. } => "Union",
        Op::Intersection(_) => "Intersection",
        Op::SmoothUnion { .. } => "SmoothUnion",
        Op::Subtract(_) => "Subtract",
        Op::Transform(_) => "Transform",
        Op::Mirror { .. } => "Mirror",
        Op::Repeat(_) => "Repeat",
        Op::Round { .. } => "Round",
        Op::Onion { .. } => "Onion",
        Op::ScaleDistance { .. } => "ScaleDistance",
        Op::Displace { .. } => "Displace",
        Op::Bounded { .. } => "Bounded",
        Op::Scatter(_) => "Scatter",
    }
}
