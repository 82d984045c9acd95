//! Loading the shared meshes. These read `$SUBCONE_DATA_DIR` (CI sets it to
//! `../shared/data`) and fail, not skip, when it is missing.

mod common;

use common::data_file;
use glam::Vec3;
use subcone_kernels::passes::SceneFeatures;
use subcone_load::data_dir;
use subcone_load::{load_mesh_file, load_scene, scene_from_arg, sponza, SPONZA_STONE};
use subcone_scene::{Albedo, Sanitized};

#[test]
fn bunny_loads_with_every_triangle() {
    let path = data_file("bunny/bunny_npm.obj");
    let (mesh, materials, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 3674);
    assert_eq!(dropped, Sanitized::default());
    assert_eq!(materials.len(), 1, "no .mtl: one default material");
    assert!(mesh.materials.iter().all(|&m| m == 0));
    // Sanitized normals are unit length.
    assert!(mesh
        .normals
        .iter()
        .flatten()
        .all(|n| (n.length() - 1.0).abs() < 1e-4));
}

#[test]
fn teapot_loads_with_every_triangle() {
    let path = data_file("teapot/teapot.obj");
    let (mesh, _, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 6320);
    assert!(!dropped.any(), "{dropped}");
}

#[test]
fn cornell_obj_takes_its_mtl_colours() {
    let path = data_file("cornell/cornell_box.obj");
    let (mesh, materials, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 32, "16 quads, triangulated");
    assert!(!dropped.any());
    let (lo, hi) = mesh.bounds().unwrap();
    assert_eq!(lo, Vec3::ZERO);
    assert_eq!(hi, Vec3::new(556.0, 548.8, 559.2));
    let red = materials
        .iter()
        .find(|m| m.name == "red")
        .expect("red from the .mtl");
    assert_eq!(red.albedo, Albedo::Solid(Vec3::new(0.63, 0.065, 0.05)));
    let light = materials.iter().find(|m| m.name == "light").unwrap();
    assert_eq!(light.emission, Vec3::new(17.0, 12.0, 4.0), "Ke is emission");
    // Every material index is valid and the walls use their colours.
    assert!(mesh
        .materials
        .iter()
        .all(|&m| (m as usize) < materials.len()));
    let used_red = mesh
        .materials
        .iter()
        .filter(|&&m| materials[m as usize].name == "red")
        .count();
    assert_eq!(used_red, 2, "one red wall, two triangles");
}

#[test]
fn load_scene_frames_and_lights_the_model() {
    let path = data_file("bunny/bunny_npm.obj");
    let scene = load_scene(&path).unwrap();
    assert_eq!(scene.name, "bunny_npm");
    scene.camera.validate().unwrap();
    let (lo, hi) = scene.mesh().unwrap().bounds().unwrap();
    let centre = 0.5 * (lo + hi);
    let radius = 0.5 * (hi - lo).length();
    // Looking at the centre from outside the bounding sphere, within the view.
    let to_centre = centre - scene.camera.position;
    assert!(to_centre.length() > radius);
    assert!(to_centre.normalize().dot(scene.camera.forward) > 0.999);
    // Every bounding-box corner is inside the vertical field of view.
    let half = (0.5 * scene.camera.fov_y).tan();
    for i in 0..8 {
        let c = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let d = c - scene.camera.position;
        let z = d.dot(scene.camera.forward);
        assert!(z > 0.0);
        assert!(
            d.dot(scene.camera.up).abs() / z < half,
            "corner {c} out of view"
        );
        assert!(
            d.dot(scene.camera.right()).abs() / z < half,
            "corner {c} out of view"
        );
    }
    assert_eq!(scene.lights.len(), 1);
    let inc = scene.lights[0].incident(centre).unwrap();
    assert!(inc.direction.y > 0.5, "the light is above the model");
    assert!(
        (1.0..10.0).contains(&inc.irradiance.x),
        "irradiance at the centre {}",
        inc.irradiance
    );
    assert!(scene.features().contains(SceneFeatures::HAS_LIGHTS));
}

#[test]
fn sponza_counts_and_its_one_degenerate_triangle() {
    let path = data_file("sponza/sponza_dabrovic.obj");
    let (mesh, materials, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(
        dropped,
        Sanitized {
            non_finite: 0,
            degenerate: 1
        }
    );
    assert_eq!(mesh.len(), 66_454 - 1);
    assert_eq!(materials.len(), 1, "Sponza has no materials");
    let (lo, hi) = mesh.bounds().unwrap();
    let size = hi - lo;
    assert!((size.x - 34.82).abs() < 0.05, "{size}");
    assert!((size.y - 16.56).abs() < 0.05, "{size}");
    assert!((size.z - 15.60).abs() < 0.05, "{size}");
}

#[test]
fn sponza_scene_with_and_without_mirror_floor() {
    let dir = data_dir();
    data_file("sponza/sponza_dabrovic.obj");
    let plain = sponza(&dir, false).unwrap();
    assert_eq!(plain.name, "sponza");
    assert_eq!(plain.mesh().unwrap().len(), 66_453);
    assert_eq!(plain.materials[0].albedo, Albedo::Solid(SPONZA_STONE));
    assert!(plain.features().contains(SceneFeatures::HAS_LIGHTS));
    assert!(!plain.features().contains(SceneFeatures::HAS_REFLECTIONS));
    plain.camera.validate().unwrap();

    let mirror = scene_from_arg("sponza-mirror").unwrap();
    assert_eq!(mirror.name, "sponza-mirror");
    assert!(mirror.features().contains(SceneFeatures::HAS_REFLECTIONS));
    let mesh = mirror.mesh().unwrap();
    let floor: Vec<usize> = (0..mesh.len())
        .filter(|&i| mirror.materials[mesh.materials[i] as usize].is_reflective())
        .collect();
    // The courtyard and aisle floor: 34 upward-facing triangles at y ≈ 0.09-0.13.
    assert_eq!(floor.len(), 34);
    let area: f32 = floor
        .iter()
        .map(|&i| {
            let v = mesh.positions[i];
            0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length()
        })
        .sum();
    assert!((460.0..480.0).contains(&area), "floor area {area}");
    for &i in &floor {
        assert!(mesh.positions[i].iter().all(|p| p.y > 0.0 && p.y < 0.2));
    }

    // The camera is inside the atrium near the -x end, looking along +x.
    let (lo, hi) = mesh.bounds().unwrap();
    let cam = mirror.camera;
    assert!(cam.position.cmpgt(lo).all() && cam.position.cmplt(hi).all());
    assert!(cam.position.x < lo.x + 0.3 * (hi.x - lo.x));
    assert!(cam.forward.x > 0.95);
    assert!((cam.fov_y.to_degrees() - 60.0).abs() < 1e-3);
    // A sun and a weaker fill, both directional.
    assert!(matches!(
        mirror.lights[..],
        [
            subcone_scene::Light::Directional { .. },
            subcone_scene::Light::Directional { .. }
        ]
    ));
}
