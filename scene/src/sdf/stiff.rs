//! Stiff scenes for the stability suite: sub-pixel features, a grazing plane,
//! objects very far away, and non-Eikonal fields.

use std::f32::consts::FRAC_PI_2;

use glam::{Quat, Vec3};

use super::scenes::{camera, checker, sun};
use super::{SdfError, SdfNode, SdfScene};
use crate::material::Material;

/// `thin`: sub-pixel features framed for 256 × 256 (a pixel is about 0.016 m
/// at the target): vertical rods 0.004 m thick every 0.1 m, horizontal wires
/// 0.002 m thick, a plate 0.003 m thick seen 1° from edge-on and a box frame of
/// 0.006 m bars, half against a wall and half against the sky.
///
/// **No lights** (ambient only): the scene for "no lights, no shadow rays".
/// A bound (repetition of rotated wires).
pub fn thin() -> Result<SdfScene, SdfError> {
    let rods = SdfNode::cylinder(0.002, 1.0)?
        .repeat_limited(Vec3::new(0.1, 0.0, 0.0), [-15, 0, 0], [15, 0, 0])?
        .translate(Vec3::new(0.0, 0.3, 0.0))?;
    let wires = SdfNode::capsule(1.4, 0.001)?
        .rotate(Quat::from_rotation_z(FRAC_PI_2))?
        .repeat_limited(Vec3::new(0.0, 0.23, 0.0), [0, -3, 0], [0, 3, 0])?
        .translate(Vec3::new(0.0, 0.3, 0.3))?;
    // The view ray to the plate's centre dips atan(1.1 / 5) = 12.4° below the
    // horizon; tilting the plate by 11.4° leaves 1° between them.
    let plate = SdfNode::cuboid(Vec3::new(1.2, 0.0015, 0.8))?
        .rotate(Quat::from_rotation_x(-11.4f32.to_radians()))?
        .translate(Vec3::new(0.0, -1.1, 0.0))?;
    let frame = SdfNode::box_frame(Vec3::new(0.45, 0.45, 0.45), 0.006)?
        .rotate(Quat::from_rotation_y(0.5) * Quat::from_rotation_x(0.35))?
        .translate(Vec3::new(0.9, 1.15, 0.4))?;
    let wall = SdfNode::cuboid(Vec3::new(2.5, 3.0, 0.05))?.translate(Vec3::new(-2.5, 0.0, -1.5))?;
    let root = SdfNode::union(vec![
        rods.with_material(0),
        wires.with_material(1),
        plate.with_material(2),
        frame.with_material(3),
        wall.with_material(4),
    ])?;
    let materials = vec![
        Material::diffuse("rods", Vec3::new(0.95, 0.9, 0.8)),
        Material::diffuse("wires", Vec3::new(0.9, 0.3, 0.2)),
        Material::diffuse("plate", Vec3::new(0.3, 0.8, 0.4)),
        Material::diffuse("frame", Vec3::new(0.95, 0.85, 0.2)),
        Material::diffuse("wall", Vec3::new(0.15, 0.2, 0.35)),
    ];
    let cam = camera(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 45.0)?;
    let mut s = SdfScene::new("thin", root, materials, Vec::new(), cam)?;
    s.background = Vec3::splat(0.5);
    s.ambient = Vec3::ONE;
    s.max_distance = 30.0;
    s.max_steps = 1024;
    Ok(s)
}

/// `grazing`: an infinite checkered plane seen at 89° from its normal (the
/// camera 1 m above it, looking 1° down: the centre ray meets it 57 m away),
/// with a row of posts receding to 400 m. Exact. One light.
pub fn grazing() -> Result<SdfScene, SdfError> {
    let pitch = 1f32.to_radians();
    let eye = Vec3::new(0.0, 1.0, 0.0);
    let forward = Vec3::new(0.0, -pitch.sin(), -pitch.cos());
    let posts = SdfNode::cuboid(Vec3::new(0.2, 0.6, 0.2))?
        .repeat_limited(Vec3::new(0.0, 0.0, 20.0), [0, 0, -20], [0, 0, -1])?
        .translate(Vec3::new(3.0, 0.6, 0.0))?;
    let root = SdfNode::union(vec![
        SdfNode::plane(Vec3::Y, 0.0)?.with_material(0),
        posts.with_material(1),
    ])?;
    let materials = vec![
        checker("plane", Vec3::splat(0.85), Vec3::splat(0.15), 0.5),
        Material::diffuse("posts", Vec3::new(0.8, 0.3, 0.2)),
    ];
    let cam = camera(eye, eye + forward, 50.0)?;
    let mut s = SdfScene::new(
        "grazing",
        root,
        materials,
        vec![sun(Vec3::new(-0.3, 1.0, -0.2), 3.0)],
        cam,
    )?;
    s.background = Vec3::new(0.55, 0.68, 0.85);
    s.ambient = Vec3::splat(0.1);
    s.max_distance = 1000.0;
    s.max_steps = 1024;
    Ok(s)
}

/// Where the `far` scene's camera sits in its original world. The scene is
/// stored **camera-relative**: this offset has been subtracted from everything,
/// so the camera is at the origin.
///
/// Why: a ray point is `p = o + t·d` in `f32`. With the camera at `4·10⁷` the
/// ulp of `o` is 4 m, and every point near the camera would be off by metres.
/// With `o = 0` the error of `p` is relative to `t` alone (ulp(10⁷) = 1 m at
/// the far end, where a 720p pixel covers ~1.2·10⁴ m and the cone hit threshold
/// `2ε·R_c` is ~250 m), and primitives evaluate `p − centre` with an absolute
/// error of about ulp(|p|), relative error ~10⁻⁷ of the distance to the camera.
/// Renderers must scale their epsilons with `t` (normals: step floored at 16
/// ulps of `|p|` by [`SdfNode::normal`]; shadow-ray offsets relative to `|p|`).
pub const FAR_ORIGIN_SHIFT: Vec3 = Vec3::new(4.0e7, 1.0e3, -2.5e7);

/// `far`: objects at 10⁵, 10⁶ and 10⁷ m from a camera at the origin (see
/// [`FAR_ORIGIN_SHIFT`] for the precision decision) above a ground plane 2·10⁴
/// m below: a sphere (radius 8·10³ at 10⁵), a rotated box (half size 6·10⁴ at
/// 10⁶) and a torus (radii 6·10⁵ and 1.5·10⁵ at 10⁷), each about 100 pixels
/// across at 720p. Exact. One light. Rays up to 5·10⁷.
pub fn far() -> Result<SdfScene, SdfError> {
    let sphere = SdfNode::sphere(8.0e3)?.translate(Vec3::new(-4.0e4, -4.0e3, -1.0e5))?;
    let cube = SdfNode::cuboid(Vec3::splat(6.0e4))?
        .rotate(Quat::from_rotation_y(0.6) * Quat::from_rotation_x(0.4))?
        .translate(Vec3::new(3.5e5, 5.0e4, -1.0e6))?;
    let torus = SdfNode::torus(6.0e5, 1.5e5)?
        .rotate(Quat::from_rotation_x(1.2))?
        .translate(Vec3::new(-1.5e6, 2.0e6, -1.0e7))?;
    let ground = SdfNode::plane(Vec3::Y, 2.0e4)?;
    let root = SdfNode::union(vec![
        ground.with_material(0),
        sphere.with_material(1),
        cube.with_material(2),
        torus.with_material(3),
    ])?;
    let materials = vec![
        checker("ground", Vec3::splat(0.6), Vec3::splat(0.3), 2.0e4),
        Material::diffuse("sphere", Vec3::new(0.8, 0.3, 0.2)),
        Material::diffuse("box", Vec3::new(0.3, 0.7, 0.35)),
        Material::diffuse("torus", Vec3::new(0.3, 0.4, 0.85)),
    ];
    let cam = camera(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), 50.0)?;
    let mut s = SdfScene::new(
        "far",
        root,
        materials,
        vec![sun(Vec3::new(0.4, 1.0, 0.5), 3.0)],
        cam,
    )?;
    s.background = Vec3::new(0.3, 0.4, 0.6);
    s.ambient = Vec3::splat(0.1);
    s.max_distance = 5.0e7;
    s.max_steps = 1024;
    Ok(s)
}

/// `non-eikonal`: fields that are not distances, beside an exact reference
/// sphere on an exact floor: a sphere whose distance is scaled by 0.2
/// (`|∇f| = 0.2`: safe, slow), a round box scaled by 5 (`|∇f| = 5`:
/// overestimates, sphere tracing can step through it) and a sphere displaced
/// by `0.12 sin(8x) sin(8y) sin(8z)` (`|∇f|` up to 2.7). Tagged non-Eikonal,
/// not conservative. One light.
pub fn non_eikonal() -> Result<SdfScene, SdfError> {
    let reference = SdfNode::sphere(0.8)?.translate(Vec3::new(-3.0, 0.8, 0.0))?;
    let slow = SdfNode::sphere(0.8)?
        .translate(Vec3::new(-1.0, 0.8, 0.0))?
        .scale_distance(0.2)?;
    let fast = SdfNode::round_box(Vec3::new(0.7, 0.7, 0.7), 0.15)?
        .rotate(Quat::from_rotation_y(0.5))?
        .translate(Vec3::new(1.0, 0.7, 0.0))?
        .scale_distance(5.0)?;
    let bumpy = SdfNode::sphere(0.75)?
        .displace(0.12, 8.0)?
        .translate(Vec3::new(3.0, 0.9, 0.0))?;
    let root = SdfNode::union(vec![
        SdfNode::plane(Vec3::Y, 0.0)?.with_material(0),
        reference.with_material(1),
        slow.with_material(2),
        fast.with_material(3),
        bumpy.with_material(4),
    ])?;
    let materials = vec![
        checker("floor", Vec3::splat(0.7), Vec3::splat(0.35), 1.0),
        Material::diffuse("exact", Vec3::new(0.85, 0.85, 0.82)),
        Material::diffuse("gradient 0.2", Vec3::new(0.25, 0.55, 0.85)),
        Material::diffuse("gradient 5", Vec3::new(0.85, 0.3, 0.2)),
        Material::diffuse("displaced", Vec3::new(0.3, 0.75, 0.35)),
    ];
    let cam = camera(Vec3::new(0.0, 2.6, 7.5), Vec3::new(0.0, 0.6, 0.0), 45.0)?;
    let mut s = SdfScene::new(
        "non-eikonal",
        root,
        materials,
        vec![sun(Vec3::new(-0.4, 1.0, 0.45), 2.8)],
        cam,
    )?;
    s.background = Vec3::new(0.55, 0.68, 0.85);
    s.ambient = Vec3::splat(0.12);
    s.max_distance = 60.0;
    s.max_steps = 1024;
    Ok(s)
}
