//! The paper's five scenes (CTSS §4, Table 1), designed after their
//! descriptions: primitives, random boxes, random shapes, a Sponza-like atrium
//! built with CSG and repetition, and a sparse scene. Units are metres; cameras
//! frame a 16:9 image (the benches run at 1280×720).

use std::f32::consts::FRAC_PI_2;
use subcone_kernels::math::Euclidean;

use glam::{Quat, Vec3};

use super::{ScatterConfig, SdfError, SdfNode, SdfScene};
use crate::camera::Camera;
use crate::light::Light;
use crate::material::{Albedo, Material};

pub(super) fn camera(position: Vec3, target: Vec3, fov_deg: f32) -> Result<Camera, SdfError> {
    Camera::look_at(position, target, Vec3::Y, fov_deg.to_radians())
        .map_err(|e| SdfError::Camera(e.to_string()))
}

pub(super) fn checker(name: &str, a: Vec3, b: Vec3, size: f32) -> Material {
    Material {
        albedo: Albedo::Checker { a, b, size },
        ..Material::diffuse(name, a)
    }
}

pub(super) fn sun(direction: Vec3, irradiance: f32) -> Light {
    Light::Directional {
        direction: direction.unit(),
        irradiance: Vec3::new(1.0, 0.96, 0.88) * irradiance,
    }
}

fn floor() -> Result<SdfNode, SdfError> {
    SdfNode::plane(Vec3::Y, 0.0)
}

/// Colours shared by the showcase scenes.
const PALETTE: [(&str, [f32; 3]); 8] = [
    ("red", [0.75, 0.18, 0.15]),
    ("orange", [0.85, 0.45, 0.12]),
    ("yellow", [0.85, 0.75, 0.2]),
    ("green", [0.25, 0.6, 0.25]),
    ("teal", [0.15, 0.55, 0.6]),
    ("blue", [0.2, 0.3, 0.75]),
    ("purple", [0.5, 0.25, 0.65]),
    ("white", [0.85, 0.85, 0.82]),
];

fn palette_materials() -> Vec<Material> {
    PALETTE
        .iter()
        .map(|(n, c)| Material::diffuse(n, Vec3::from_array(*c)))
        .collect()
}

/// `primitives`: the twelve exact primitives in a 4 × 3 grid on a checkered
/// floor. 13 objects, exact. Two lights.
pub fn primitives() -> Result<SdfScene, SdfError> {
    let yaw = |deg: f32| Quat::from_rotation_y(deg.to_radians());
    // (shape, half height above the floor, rotation)
    let shapes: Vec<(SdfNode, f32, Quat)> = vec![
        (SdfNode::sphere(0.8)?, 0.8, Quat::IDENTITY),
        (SdfNode::cuboid(Vec3::splat(0.65))?, 0.65, yaw(30.0)),
        (
            SdfNode::round_box(Vec3::new(0.75, 0.6, 0.75), 0.18)?,
            0.6,
            yaw(-20.0),
        ),
        (SdfNode::box_frame(Vec3::splat(0.7), 0.1)?, 0.7, yaw(35.0)),
        (
            SdfNode::torus(0.58, 0.2)?,
            0.78,
            yaw(-30.0) * Quat::from_rotation_x(FRAC_PI_2),
        ),
        (SdfNode::link(0.3, 0.35, 0.12)?, 0.77, yaw(60.0)),
        (SdfNode::capsule(0.45, 0.35)?, 0.8, Quat::IDENTITY),
        (SdfNode::cylinder(0.6, 0.6)?, 0.6, Quat::IDENTITY),
        (
            SdfNode::rounded_cylinder(0.65, 0.5, 0.15)?,
            0.5,
            Quat::IDENTITY,
        ),
        (SdfNode::capped_cone(0.7, 0.7, 0.25)?, 0.7, Quat::IDENTITY),
        (SdfNode::octahedron(0.85)?, 0.85, yaw(20.0)),
        (SdfNode::hex_prism(0.6, 0.6)?, 0.6, yaw(10.0)),
    ];
    let spacing = 2.6;
    let mut objects = vec![floor()?.with_material(0)];
    for (i, (node, lift, rot)) in shapes.into_iter().enumerate() {
        let (col, row) = ((i % 4) as f32, (i / 4) as f32);
        let at = Vec3::new((col - 1.5) * spacing, lift, (row - 1.0) * spacing);
        objects.push(
            node.rotate(rot)?
                .translate(at)?
                .with_material(1 + (i % 7) as u32),
        );
    }
    let mut materials = vec![checker("floor", Vec3::splat(0.75), Vec3::splat(0.35), 1.0)];
    materials.extend(palette_materials());
    let lights = vec![
        sun(Vec3::new(-0.45, 1.0, 0.35), 2.2),
        Light::Point {
            position: Vec3::new(3.0, 5.0, 4.0),
            intensity: Vec3::splat(45.0),
        },
    ];
    let cam = camera(Vec3::new(0.0, 4.4, 8.6), Vec3::new(0.0, 0.3, -0.2), 50.0)?;
    let mut s = SdfScene::new(
        "primitives",
        SdfNode::union(objects)?,
        materials,
        lights,
        cam,
    )?;
    s.background = Vec3::new(0.55, 0.68, 0.85);
    s.ambient = Vec3::splat(0.12);
    s.max_distance = 100.0;
    Ok(s)
}

fn field_camera() -> Result<Camera, SdfError> {
    camera(Vec3::new(2.0, 5.5, 14.0), Vec3::new(0.0, 2.2, -4.0), 50.0)
}

fn field_lights() -> Vec<Light> {
    vec![sun(Vec3::new(-0.4, 1.0, 0.55), 2.6)]
}

/// The grid of the random scenes: cells 1.6 m over 25 × 4 × 25 cells above
/// the floor, about half of them occupied.
fn field_config(cell: f32, seed: u64, fill: f32) -> ScatterConfig {
    let mut c = ScatterConfig::new(Vec3::splat(cell), [-12, 0, -20], [12, 3, 4], seed);
    c.origin = Vec3::new(0.0, 0.5 * cell + 0.05, 0.0);
    c.fill = fill;
    c.margin = 0.08 * cell;
    c.min_size = 0.45;
    c.max_size = 1.0;
    c.palette = (1..=PALETTE.len() as u32).collect();
    c
}

fn field_scene(name: &str, scatter: SdfNode) -> Result<SdfScene, SdfError> {
    let root = SdfNode::union(vec![floor()?.with_material(0), scatter])?;
    let mut materials = vec![checker("floor", Vec3::splat(0.7), Vec3::splat(0.4), 1.6)];
    materials.extend(palette_materials());
    let mut s = SdfScene::new(name, root, materials, field_lights(), field_camera()?)?;
    s.background = Vec3::new(0.55, 0.68, 0.85);
    s.ambient = Vec3::splat(0.12);
    s.max_distance = 150.0;
    s.max_steps = 768;
    Ok(s)
}

/// `random-box`: about 1,400 randomly sized, rotated and coloured boxes in a
/// 25 × 4 × 25 grid of 1.6 m cells over a floor (fixed seed). A bound: one box
/// per evaluation, guarded by its cell's walls.
pub fn random_box() -> Result<SdfScene, SdfError> {
    let templates = vec![
        SdfNode::cuboid(Vec3::splat(1.0))?,
        SdfNode::cuboid(Vec3::new(1.4, 0.5, 0.8))?,
        SdfNode::cuboid(Vec3::new(0.4, 1.5, 0.6))?,
        SdfNode::cuboid(Vec3::new(1.2, 0.3, 1.2))?,
    ];
    let scatter = SdfNode::scatter(field_config(1.6, 0x5eed_b0c5, 0.55), templates)?;
    field_scene("random-box", scatter)
}

/// `random-shape`: about 1,400 random shapes of ten kinds (sphere, round box,
/// torus, capsule, cylinder, capped cone, octahedron, ellipsoid, hex prism,
/// link), in the grid of `random-box` with another seed. A bound.
pub fn random_shape() -> Result<SdfScene, SdfError> {
    let templates = vec![
        SdfNode::sphere(1.0)?,
        SdfNode::round_box(Vec3::new(1.0, 0.6, 0.8), 0.2)?,
        SdfNode::torus(0.75, 0.25)?,
        SdfNode::capsule(0.6, 0.4)?,
        SdfNode::cylinder(0.6, 0.8)?,
        SdfNode::capped_cone(0.8, 0.7, 0.2)?,
        SdfNode::octahedron(1.0)?,
        SdfNode::ellipsoid(Vec3::new(1.0, 0.45, 0.7))?,
        SdfNode::hex_prism(0.6, 0.7)?,
        SdfNode::link(0.35, 0.4, 0.14)?,
    ];
    let scatter = SdfNode::scatter(field_config(1.6, 0x5eed_5a9e, 0.55), templates)?;
    field_scene("random-shape", scatter)
}

/// `sparse-shape`: five objects far apart in an empty sky, no floor: most
/// rays miss everything. A bound (smooth union in the blob). One light.
pub fn sparse_shape() -> Result<SdfScene, SdfError> {
    let blob = SdfNode::smooth_union(
        0.6,
        vec![
            SdfNode::sphere(1.0)?,
            SdfNode::capsule(0.9, 0.45)?
                .rotate(Quat::from_rotation_z(1.1))?
                .translate(Vec3::new(0.9, 0.5, 0.0))?,
            SdfNode::sphere(0.6)?.translate(Vec3::new(-0.8, 0.9, 0.3))?,
        ],
    )?;
    let objects = vec![
        blob.translate(Vec3::new(-1.0, 0.5, -2.0))?.with_material(0),
        SdfNode::torus(1.6, 0.35)?
            .rotate(Quat::from_rotation_x(1.2) * Quat::from_rotation_z(0.3))?
            .translate(Vec3::new(-11.0, 4.0, -22.0))?
            .with_material(1),
        SdfNode::octahedron(2.0)?
            .rotate(Quat::from_rotation_y(0.4))?
            .translate(Vec3::new(12.0, -2.5, -28.0))?
            .with_material(2),
        SdfNode::round_box(Vec3::new(1.2, 0.8, 2.0), 0.3)?
            .rotate(Quat::from_euler(glam::EulerRot::YXZ, 0.7, 0.3, 0.2))?
            .translate(Vec3::new(7.0, 3.5, -12.0))?
            .with_material(3),
        SdfNode::capped_cone(1.5, 1.2, 0.2)?
            .translate(Vec3::new(-6.0, -3.5, -9.0))?
            .with_material(4),
    ];
    let materials = vec![
        Material::diffuse("blob", Vec3::new(0.8, 0.35, 0.2)),
        Material::diffuse("torus", Vec3::new(0.25, 0.6, 0.3)),
        Material::diffuse("octahedron", Vec3::new(0.3, 0.4, 0.8)),
        Material::diffuse("box", Vec3::new(0.85, 0.8, 0.3)),
        Material::diffuse("cone", Vec3::new(0.7, 0.7, 0.72)),
    ];
    let lights = vec![sun(Vec3::new(0.3, 1.0, 0.6), 3.0)];
    let cam = camera(Vec3::new(0.0, 1.0, 6.0), Vec3::new(0.0, 0.5, -10.0), 55.0)?;
    let mut s = SdfScene::new(
        "sparse-shape",
        SdfNode::union(objects)?,
        materials,
        lights,
        cam,
    )?;
    s.background = Vec3::new(0.08, 0.09, 0.12);
    s.ambient = Vec3::splat(0.1);
    s.max_distance = 120.0;
    Ok(s)
}

const FLOOR: u32 = 0;
const STONE: u32 = 1;
const WALL: u32 = 2;
const BANNER: u32 = 3;
const FOUNTAIN: u32 = 4;

/// Padding of the atrium's bounding boxes: far above the largest cone radius
/// at which anything is shaded (about 0.05 m at 30 m in 720p).
const PAD: f32 = 0.4;

/// One side of the atrium, at `x ≥ 3.6`, mirrored to the other side.
fn atrium_side() -> Result<SdfNode, SdfError> {
    // Ground-floor column, centred on its axis: symmetric, so its repetition
    // along z is exact.
    let column = SdfNode::union(vec![
        SdfNode::cuboid(Vec3::new(0.35, 0.15, 0.35))?.translate(Vec3::new(0.0, 0.15, 0.0))?,
        SdfNode::cylinder(0.22, 1.75)?.translate(Vec3::new(0.0, 2.05, 0.0))?,
        SdfNode::cuboid(Vec3::new(0.35, 0.12, 0.35))?.translate(Vec3::new(0.0, 3.92, 0.0))?,
    ])?;
    let columns = column.repeat_limited(Vec3::new(0.0, 0.0, 3.0), [0, 0, -4], [0, 0, 4])?;
    // Arcade wall above the capitals with semicircular arches between them.
    let slab = SdfNode::cuboid(Vec3::new(0.3, 0.78, 13.5))?.translate(Vec3::new(0.0, 4.82, 0.0))?;
    let arch = SdfNode::cylinder(1.15, 0.5)?
        .rotate(Quat::from_rotation_z(FRAC_PI_2))?
        .translate(Vec3::new(0.0, 4.04, 0.0))?;
    let arches = arch
        .repeat_limited(Vec3::new(0.0, 0.0, 3.0), [0, 0, -4], [0, 0, 3])?
        .translate(Vec3::new(0.0, 0.0, 1.5))?;
    let arcade = slab.subtract(arches)?;
    // Gallery: floor slab, balustrade, small columns, entablature, roof.
    let gallery_floor =
        SdfNode::cuboid(Vec3::new(1.65, 0.1, 13.5))?.translate(Vec3::new(1.35, 5.7, 0.0))?;
    let balustrade =
        SdfNode::cuboid(Vec3::new(0.08, 0.45, 13.5))?.translate(Vec3::new(-0.15, 6.25, 0.0))?;
    let small_column = SdfNode::union(vec![
        SdfNode::cylinder(0.13, 1.1)?.translate(Vec3::new(0.0, 6.9, 0.0))?,
        SdfNode::cuboid(Vec3::new(0.2, 0.08, 0.2))?.translate(Vec3::new(0.0, 8.0, 0.0))?,
    ])?;
    let small_columns =
        small_column.repeat_limited(Vec3::new(0.0, 0.0, 1.5), [0, 0, -8], [0, 0, 8])?;
    let entablature =
        SdfNode::cuboid(Vec3::new(0.3, 0.2, 13.5))?.translate(Vec3::new(0.0, 8.28, 0.0))?;
    let roof =
        SdfNode::cuboid(Vec3::new(1.85, 0.08, 13.5))?.translate(Vec3::new(1.55, 8.56, 0.0))?;
    // Outer wall with ground-floor niches and upper windows cut through.
    let wall = SdfNode::cuboid(Vec3::new(0.2, 4.25, 13.5))?.translate(Vec3::new(3.2, 4.25, 0.0))?;
    let niche = SdfNode::cuboid(Vec3::new(0.12, 1.1, 0.6))?.translate(Vec3::new(-0.2, 1.6, 0.0))?;
    let window =
        SdfNode::cuboid(Vec3::new(0.3, 0.55, 0.45))?.translate(Vec3::new(0.0, 7.0, 0.0))?;
    let openings = SdfNode::union(vec![niche, window])?
        .repeat_limited(Vec3::new(0.0, 0.0, 3.0), [0, 0, -4], [0, 0, 3])?
        .translate(Vec3::new(3.2, 0.0, 1.5))?;
    let outer = wall.subtract(openings)?;
    // Banners hanging in the arches.
    let banners = SdfNode::cuboid(Vec3::new(0.015, 1.1, 0.45))?
        .repeat_limited(Vec3::new(0.0, 0.0, 3.0), [0, 0, -4], [0, 0, 3])?
        .translate(Vec3::new(-0.45, 4.5, 1.5))?;
    // Groups skipped as a whole while a point is more than PAD from their box.
    let ground = SdfNode::union(vec![
        columns.with_material(STONE),
        arcade.with_material(STONE),
        banners.with_material(BANNER),
    ])?
    .bounded(PAD)?;
    let gallery = SdfNode::union(vec![
        gallery_floor,
        balustrade,
        small_columns,
        entablature,
        roof,
    ])?
    .with_material(STONE)
    .bounded(PAD)?;
    let side = SdfNode::union(vec![
        ground,
        gallery,
        outer.with_material(WALL).bounded(PAD)?,
    ])?;
    side.translate(Vec3::new(4.0, 0.0, 0.0))?.bounded(PAD)
}

/// `sdf-atrium`: a Sponza-like courtyard. Two storeys of arcades on both sides
/// (columns and gallery columns by exact repetition, arches carved from a wall
/// by repeated cylinders, niches and windows cut through the outer walls),
/// banners in the arches, a back wall with an arched doorway, a fountain
/// (smooth union) and a checkered floor. A bound (CSG). Sun and a point light.
pub fn atrium() -> Result<SdfScene, SdfError> {
    let sides = atrium_side()?.mirror([true, false, false])?;
    let back = SdfNode::cuboid(Vec3::new(7.4, 4.25, 0.2))?
        .translate(Vec3::new(0.0, 4.25, -13.7))?
        .subtract(
            SdfNode::union(vec![
                SdfNode::cuboid(Vec3::new(1.5, 1.5, 0.5))?.translate(Vec3::new(0.0, 1.5, 0.0))?,
                SdfNode::cylinder(1.5, 0.5)?
                    .rotate(Quat::from_rotation_x(FRAC_PI_2))?
                    .translate(Vec3::new(0.0, 3.0, 0.0))?,
            ])?
            .translate(Vec3::new(0.0, 0.0, -13.7))?,
        )?;
    let basin = SdfNode::cylinder(1.3, 0.3)?
        .translate(Vec3::new(0.0, 0.3, 0.0))?
        .subtract(SdfNode::cylinder(1.12, 0.3)?.translate(Vec3::new(0.0, 0.62, 0.0))?)?;
    let spout = SdfNode::smooth_union(
        0.25,
        vec![
            SdfNode::capsule(0.5, 0.1)?.translate(Vec3::new(0.0, 0.8, 0.0))?,
            SdfNode::sphere(0.28)?.translate(Vec3::new(0.0, 1.45, 0.0))?,
            SdfNode::torus(0.3, 0.06)?.translate(Vec3::new(0.0, 1.0, 0.0))?,
        ],
    )?;
    let fountain = SdfNode::union(vec![basin, spout])?
        .translate(Vec3::new(0.0, 0.0, -2.0))?
        .bounded(PAD)?;
    let root = SdfNode::union(vec![
        floor()?.with_material(FLOOR),
        sides,
        back.with_material(WALL).bounded(PAD)?,
        fountain.with_material(FOUNTAIN),
    ])?;
    let materials = vec![
        checker(
            "floor",
            Vec3::new(0.72, 0.68, 0.6),
            Vec3::new(0.42, 0.38, 0.33),
            1.0,
        ),
        Material::diffuse("stone", Vec3::new(0.8, 0.76, 0.68)),
        Material::diffuse("wall", Vec3::new(0.7, 0.6, 0.48)),
        Material::diffuse("banner", Vec3::new(0.7, 0.12, 0.1)),
        Material::diffuse("fountain", Vec3::new(0.55, 0.62, 0.68)),
    ];
    let lights = vec![
        sun(Vec3::new(0.45, 1.0, 0.25), 3.0),
        Light::Point {
            position: Vec3::new(0.0, 3.5, 2.0),
            intensity: Vec3::new(1.0, 0.8, 0.55) * 20.0,
        },
    ];
    let cam = camera(Vec3::new(0.0, 1.7, 11.5), Vec3::new(0.0, 3.4, -8.0), 55.0)?;
    let mut s = SdfScene::new("sdf-atrium", root, materials, lights, cam)?;
    s.background = Vec3::new(0.55, 0.7, 0.9);
    s.ambient = Vec3::new(0.16, 0.17, 0.2);
    s.max_distance = 80.0;
    s.max_steps = 768;
    Ok(s)
}

/// `glass`: semi-transparent objects in front of opaque ones (CTSS §5.3's
/// non-binary visibility): a half-opaque pane (`alpha` 0.5) before a red box
/// and a green capsule, a faint orange sphere (`alpha` 0.3) before a blue
/// sphere, on a plain floor (a texture would put edges CTSS does not see, §5.2,
/// into every comparison). Exact primitives, one sun. Shadows stay
/// opaque (shadow rays do not blend). Rendered by the CPU backend only (see
/// [`Material::alpha`]); not one of the paper's scenes.
pub fn glass() -> Result<SdfScene, SdfError> {
    let yaw = |deg: f32| Quat::from_rotation_y(deg.to_radians());
    let objects = vec![
        floor()?.with_material(0),
        SdfNode::cuboid(Vec3::splat(0.6))?
            .rotate(yaw(25.0))?
            .translate(Vec3::new(-1.3, 0.6, -1.6))?
            .with_material(1),
        SdfNode::sphere(0.8)?
            .translate(Vec3::new(1.4, 0.8, -1.4))?
            .with_material(2),
        SdfNode::capsule(0.6, 0.35)?
            .translate(Vec3::new(-0.1, 0.95, -3.2))?
            .with_material(3),
        SdfNode::cuboid(Vec3::new(1.25, 0.8, 0.05))?
            .rotate(yaw(12.0))?
            .translate(Vec3::new(-0.75, 0.9, 0.5))?
            .with_material(4),
        SdfNode::sphere(0.6)?
            .translate(Vec3::new(1.05, 0.6, 0.9))?
            .with_material(5),
    ];
    let materials = vec![
        Material::diffuse("floor", Vec3::new(0.7, 0.68, 0.62)),
        Material::diffuse("red", Vec3::from_array(PALETTE[0].1)),
        Material::diffuse("blue", Vec3::from_array(PALETTE[5].1)),
        Material::diffuse("green", Vec3::from_array(PALETTE[3].1)),
        Material::translucent("pane", Vec3::new(0.75, 0.9, 0.95), 0.5),
        Material::translucent("orange-glass", Vec3::from_array(PALETTE[1].1), 0.3),
    ];
    let lights = vec![sun(Vec3::new(-0.4, 1.0, 0.5), 2.4)];
    let cam = camera(Vec3::new(0.0, 1.7, 6.0), Vec3::new(0.0, 0.7, -0.8), 45.0)?;
    let mut s = SdfScene::new("glass", SdfNode::union(objects)?, materials, lights, cam)?;
    s.background = Vec3::new(0.55, 0.68, 0.85);
    s.ambient = Vec3::splat(0.15);
    s.max_distance = 60.0;
    Ok(s)
}
