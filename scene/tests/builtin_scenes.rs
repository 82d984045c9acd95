//! The built-in procedural scenes: they build, deterministically, with valid
//! cameras and the features their names promise.

use glam::{Vec2, Vec3};
use subcone_kernels::passes::SceneFeatures;
use subcone_scene::builtin::{builtin, CHECKER_PALETTE, CHECKER_PATCH, TRIANGLE_SCENES};
use subcone_scene::{Albedo, Camera, Light, Scene, SceneError};

fn features(name: &str) -> SceneFeatures {
    builtin(name).unwrap().features()
}

#[test]
fn every_builtin_builds_with_a_valid_camera() {
    for name in TRIANGLE_SCENES {
        let s = builtin(name).unwrap();
        assert_eq!(s.name, name);
        s.camera.validate().unwrap();
        let mesh = s.mesh().unwrap();
        assert!(!mesh.is_empty());
        // Already clean: sanitizing drops nothing.
        let mut copy = mesh.clone();
        assert!(!copy.sanitize().any(), "{name}");
        assert!(mesh
            .materials
            .iter()
            .all(|&m| (m as usize) < s.materials.len()));
        assert!(!s.lights.is_empty(), "{name} has a light");
    }
}

#[test]
fn builtins_are_deterministic() {
    for name in TRIANGLE_SCENES {
        let (a, b) = (builtin(name).unwrap(), builtin(name).unwrap());
        assert_eq!(a.mesh(), b.mesh(), "{name}");
        assert_eq!(a.materials, b.materials, "{name}");
        assert_eq!(a.lights, b.lights, "{name}");
        assert_eq!(a.camera, b.camera, "{name}");
        assert_ne!(a.id(), b.id(), "each build is a new scene");
    }
}

#[test]
fn unknown_builtin_lists_the_names() {
    let err = builtin("sponza").unwrap_err();
    assert!(matches!(err, SceneError::UnknownScene { .. }));
    let msg = err.to_string();
    for name in TRIANGLE_SCENES {
        assert!(msg.contains(name), "{msg}");
    }
}

#[test]
fn cornell_features() {
    let f = features("cornell");
    assert!(f.contains(SceneFeatures::HAS_LIGHTS | SceneFeatures::HAS_REFLECTIONS));
    assert!(!f.contains(SceneFeatures::HAS_TEXTURES));
    let f = features("cornell-nomirror");
    assert!(f.contains(SceneFeatures::HAS_LIGHTS));
    assert!(!f.contains(SceneFeatures::HAS_REFLECTIONS));
}

#[test]
fn checker_features() {
    let f = features("checker");
    assert!(f.contains(SceneFeatures::HAS_LIGHTS | SceneFeatures::HAS_TEXTURES));
    assert!(!f.contains(SceneFeatures::HAS_REFLECTIONS));
}

#[test]
fn atrium_features() {
    let f = features("atrium");
    assert!(f.contains(SceneFeatures::HAS_LIGHTS | SceneFeatures::HAS_REFLECTIONS));
    assert!(!f.contains(SceneFeatures::HAS_TEXTURES));
}

/// Where `p` lands in a `w × h` image, in pixels (None behind the camera).
fn project(cam: &Camera, p: Vec3, w: u32, h: u32) -> Option<Vec2> {
    let d = p - cam.position;
    let z = d.dot(cam.forward);
    if z <= 0.0 {
        return None;
    }
    let half = (0.5 * cam.fov_y).tan();
    let (wf, hf) = (w as f32, h as f32);
    let u = d.dot(cam.right()) / z / (half * wf / hf);
    let v = d.dot(cam.up) / z / half;
    Some(Vec2::new((u + 1.0) * 0.5 * wf, (1.0 - v) * 0.5 * hf))
}

/// The first floor hit (y = 0) of the ray through a pixel.
fn floor_point(s: &Scene, px: Vec2, w: u32, h: u32) -> Vec3 {
    let (o, d) = s.camera.ray(px, w, h);
    assert!(d.y < 0.0);
    o + d * (-o.y / d.y)
}

#[test]
fn checker_patches_are_a_few_pixels_wide_in_the_middle_distance() {
    let s = builtin("checker").unwrap();
    let floor = &s.materials[s.mesh().unwrap().materials[0] as usize];
    match &floor.albedo {
        Albedo::Patches { palette, size } => {
            assert_eq!(palette.len(), 6);
            assert_eq!(*size, CHECKER_PATCH);
            // Distinct, saturated colours.
            for (i, a) in palette.iter().enumerate() {
                assert!(
                    a.max_element() - a.min_element() > 0.5,
                    "{a} is not saturated"
                );
                for b in &palette[i + 1..] {
                    assert!((*a - *b).abs().max_element() > 0.3);
                }
            }
            assert_eq!(palette[..], CHECKER_PALETTE[..]);
        }
        other => panic!("floor albedo {other:?}"),
    }
    assert_eq!(floor.mirror, 0.0);
    // About 20° down.
    let down = (-s.camera.forward.y).asin().to_degrees();
    assert!((15.0..25.0).contains(&down), "{down}°");
    // At the image centre a patch spans 4-10 pixels at 256 × 256.
    let (w, h) = (256, 256);
    let p = floor_point(&s, Vec2::new(128.0, 128.0), w, h);
    let a = project(&s.camera, p, w, h).unwrap();
    let b = project(&s.camera, p + Vec3::X * CHECKER_PATCH, w, h).unwrap();
    let width = (b - a).length();
    assert!((4.0..10.0).contains(&width), "patch width {width} px");
    // Receding: far patches are smaller than near ones.
    let near = floor_point(&s, Vec2::new(128.0, 250.0), w, h);
    let far = floor_point(&s, Vec2::new(128.0, 60.0), w, h);
    let size_at = |p: Vec3| {
        (project(&s.camera, p + Vec3::X * CHECKER_PATCH, w, h).unwrap()
            - project(&s.camera, p, w, h).unwrap())
        .length()
    };
    assert!(size_at(near) > 1.5 * width && size_at(far) < 0.5 * width);
    // The objects are in view.
    for c in [Vec3::new(-1.1, 0.4, -0.6), Vec3::new(1.0, 0.5, 0.1)] {
        let q = project(&s.camera, c, w, h).unwrap();
        assert!(
            q.cmpge(Vec2::ZERO).all() && q.cmplt(Vec2::splat(256.0)).all(),
            "{c} at {q}"
        );
    }
}

#[test]
fn atrium_is_a_few_thousand_triangles_with_a_mirror_floor_and_a_sun() {
    let s = builtin("atrium").unwrap();
    let mesh = s.mesh().unwrap();
    assert!(
        (2_000..8_000).contains(&mesh.len()),
        "{} triangles",
        mesh.len()
    );
    let mirrors: Vec<_> = s.materials.iter().filter(|m| m.is_reflective()).collect();
    assert_eq!(mirrors.len(), 1);
    assert!((mirrors[0].mirror - 0.4).abs() < 1e-6);
    // Every mirror triangle lies flat on the floor.
    for (i, v) in mesh.positions.iter().enumerate() {
        if s.materials[mesh.materials[i] as usize].is_reflective() {
            assert!(v.iter().all(|p| p.y == 0.0));
        }
    }
    assert!(matches!(s.lights[..], [Light::Directional { direction, .. }] if direction.y > 0.5));
    // Thin railing bars: many triangles narrower than 5 cm.
    let thin = mesh
        .positions
        .iter()
        .filter(|v| {
            let (lo, hi) = v
                .iter()
                .fold((v[0], v[0]), |(l, h), p| (l.min(*p), h.max(*p)));
            let e = hi - lo;
            e.x < 0.05 && e.z < 0.05 && e.y > 0.5
        })
        .count();
    assert!(thin > 500, "{thin} thin bar triangles");
    // The camera stands inside the courtyard, below the gallery.
    let (lo, hi) = mesh.bounds().unwrap();
    assert!(s.camera.position.cmpgt(lo).all() && s.camera.position.cmplt(hi).all());
    assert!(s.camera.position.y < 5.0);
}

/// The registry is the one list: every derived list holds its entries of the
/// right kind in order, every name is unique, the paper scenes are entries,
/// and every entry builds a scene of its kind.
#[test]
fn the_scene_registry_is_the_one_list() {
    use subcone_scene::builtin::{find, names, SceneKind, PAPER_SCENES, SCENES, TRIANGLE_SCENES};
    use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
    let of = |kind: SceneKind| -> Vec<&str> {
        SCENES
            .iter()
            .filter(|e| e.kind == kind)
            .map(|e| e.name)
            .collect()
    };
    assert_eq!(TRIANGLE_SCENES.to_vec(), of(SceneKind::Triangles));
    assert_eq!(SDF_SCENES.to_vec(), of(SceneKind::PaperSdf));
    assert_eq!(STIFF_SCENES.to_vec(), of(SceneKind::Stiff));
    assert_eq!(TRANSPARENT_SCENES.to_vec(), of(SceneKind::Transparent));
    let all: Vec<&str> = names().collect();
    let mut unique = all.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(
        unique.len(),
        all.len(),
        "a name is registered twice: {all:?}"
    );
    for name in PAPER_SCENES {
        assert!(find(name).is_some(), "paper scene {name} is not registered");
    }
    for e in &SCENES {
        assert!(!e.description.is_empty(), "{}", e.name);
        let scene = e.build().unwrap_or_else(|err| panic!("{}: {err}", e.name));
        assert_eq!(
            scene.sdf_geometry().is_some(),
            e.is_sdf(),
            "{} builds the wrong kind of scene",
            e.name
        );
        assert_eq!(e.is_sdf(), e.kind != SceneKind::Triangles, "{}", e.name);
    }
    assert!(find("no-such-scene").is_none());
}
