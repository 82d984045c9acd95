//! A thin sheet seen face-on: opaque under every CTSS method.
//!
//! A slab ten times thinner than the narrowest cone's diameter at its depth,
//! face-on in front of a wall of another colour, lit by ambient light alone.
//! The cone passes through the slab without full occlusion; the paper's
//! half-space mask then lets the wall show through (CTSS §5.2's sub-pixel
//! limit). With the default rule for thin shells
//! ([`group_mask`](subcone_kernels::ctss::group_mask)) the slab covers its
//! pixels: every interior pixel (two pixels inside its projected edge)
//! equals NoAA's within 1/255 in every channel. `ctss-paper` fails it (on
//! the CPU its interior is the wall's colour: off by 0.9), so the `-paper`
//! methods are not in the list ([`thin_slab_methods`]).

use subcone_kernels::glam::Vec3;
use subcone_scene::sdf::{SdfNode, SdfScene};
use subcone_scene::{Backend, Camera, Material, Method, RenderSettings, Scene};

use crate::named::{delayed, split_groups, CTSS, CTSS_R, NOAA, SSAA4_CTSS};

/// The CTSS methods that must draw the slab opaque: every default one
/// (`ctss`, `ctss-delayed`, `ctss+edges`, `ctss-r`, `ctss-r-delayed`,
/// `ssaa4+ctss`, `ssaa4+ctss-delayed`).
pub fn thin_slab_methods() -> [Method; 7] {
    [
        CTSS,
        delayed(CTSS),
        split_groups(CTSS),
        CTSS_R,
        delayed(CTSS_R),
        SSAA4_CTSS,
        delayed(SSAA4_CTSS),
    ]
}

/// Largest difference from NoAA on an interior pixel, per channel.
pub const THIN_SLAB_TOLERANCE: f32 = 1.0 / 255.0;

const SIZE: u32 = 32;
const DISTANCE: f32 = 6.0;
const HALF: f32 = 1.0;

/// The slab (material 0, white) 6 units in front of the camera, the wall
/// (material 1, red) 2 units behind it; the slab's thickness is a tenth of
/// the narrowest cone's diameter among [`thin_slab_methods`] at its depth.
pub fn thin_slab_scene() -> Scene {
    let cam = Camera::look_at(
        Vec3::new(0.0, 0.0, DISTANCE),
        Vec3::ZERO,
        Vec3::Y,
        30f32.to_radians(),
    )
    .expect("camera");
    let narrowest = thin_slab_methods()
        .iter()
        .map(|m| m.cone_tan_theta(&cam, SIZE))
        .fold(f32::INFINITY, f32::min);
    let thickness = 2.0 * DISTANCE * narrowest / 10.0;
    let slab = SdfNode::cuboid(Vec3::new(HALF, HALF, 0.5 * thickness)).expect("slab");
    let wall = SdfNode::cuboid(Vec3::new(4.0, 4.0, 0.1))
        .and_then(|w| w.translate(Vec3::new(0.0, 0.0, -2.0)))
        .expect("wall")
        .with_material(1);
    let root = SdfNode::union(vec![slab, wall]).expect("union");
    let materials = vec![
        Material::diffuse("slab", Vec3::ONE),
        Material::diffuse("wall", Vec3::new(1.0, 0.1, 0.1)),
    ];
    let mut s = SdfScene::new("thin-slab", root, materials, vec![], cam).expect("scene");
    s.ambient = Vec3::ONE;
    s.background = Vec3::ZERO;
    Scene::sdf(s).expect("scene")
}

/// Renders [`thin_slab_scene`] with NoAA and every [`thin_slab_methods`]
/// method on `backend`, and requires each interior pixel within
/// [`THIN_SLAB_TOLERANCE`] of NoAA's.
pub fn check_thin_slab(backend: &dyn Backend) {
    let scene = thin_slab_scene();
    let settings = RenderSettings::new(SIZE, SIZE);
    let render = |m: &Method| {
        backend
            .render(&scene, &scene.camera, m, &settings)
            .unwrap_or_else(|e| panic!("{}: thin slab {m}: {e}", backend.name()))
    };
    let noaa = render(&NOAA);
    // The slab's projected half-size in pixels: HALF at DISTANCE with a 30°
    // vertical field of view.
    let half_px = HALF / (DISTANCE * 15f32.to_radians().tan()) * SIZE as f32 / 2.0;
    let c = SIZE as f32 / 2.0;
    let inside = |x: u32, y: u32| {
        let (dx, dy) = ((x as f32 + 0.5 - c).abs(), (y as f32 + 0.5 - c).abs());
        dx.max(dy) < half_px - 2.0
    };
    let interior: Vec<usize> = (0..SIZE * SIZE)
        .filter(|i| inside(i % SIZE, i / SIZE))
        .map(|i| i as usize)
        .collect();
    assert!(interior.len() > 100, "{} interior pixels", interior.len());
    assert!(
        interior.iter().all(|&i| noaa.color[i].y > 0.9),
        "NoAA draws the slab"
    );
    let mut failures = Vec::new();
    for m in thin_slab_methods() {
        let f = render(&m);
        let worst = interior
            .iter()
            .map(|&i| (f.color[i] - noaa.color[i]).abs().max_element())
            .fold(0.0f32, f32::max);
        eprintln!(
            "{}: thin slab {m}: interior max |Δ| from NoAA {worst:.5}",
            backend.name()
        );
        if worst.is_nan() || worst > THIN_SLAB_TOLERANCE {
            failures.push(format!(
                "{m}: interior max |Δ| {worst} > {THIN_SLAB_TOLERANCE}"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{}: thin slab not opaque: {}",
        backend.name(),
        failures.join("; ")
    );
}
