//! Shared by the loader targets (`obj_loader`, `gltf_loader`): a private
//! scratch directory for side files and the checks on a loaded mesh.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use subcone_scene::{Albedo, Material, SceneError, TriangleMesh};

/// Separates the main file from a side file (the OBJ's `m.mtl`, the glTF's
/// `b.bin`) in one fuzz input: `main ‖ SEPARATOR ‖ side`.
pub const SEPARATOR: &[u8] = b"\n#--8<--\n";

/// A directory of this process only (so `-fork`/`-jobs` workers never share a
/// side file), created once and reused.
pub fn scratch_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("subcone-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the scratch directory");
        dir
    })
}

/// Split an input into the main file and an optional side file.
pub fn split(data: &[u8]) -> (&[u8], Option<&[u8]>) {
    match data.windows(SEPARATOR.len()).position(|w| w == SEPARATOR) {
        Some(i) => (&data[..i], Some(&data[i + SEPARATOR.len()..])),
        None => (data, None),
    }
}

/// Write (or remove) the side file `name` in the scratch directory.
pub fn side_file(name: &str, contents: Option<&[u8]>) {
    let path = scratch_dir().join(name);
    match contents {
        Some(c) => std::fs::write(&path, c).expect("write the side file"),
        None => {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// What a successful load promises: a non-empty mesh of finite, non-degenerate
/// triangles, finite unit (or zero) normals, finite uvs, material indices into
/// `materials`, and materials with finite colours in range.
pub fn check_mesh(mesh: &TriangleMesh, materials: &[Material]) {
    assert!(!mesh.is_empty(), "an empty mesh loaded");
    assert!(!materials.is_empty(), "no materials");
    let n = mesh.len();
    assert_eq!(mesh.positions.len(), n);
    assert_eq!(mesh.normals.len(), n);
    assert_eq!(mesh.uvs.len(), n);
    assert_eq!(mesh.materials.len(), n);
    for i in 0..n {
        let [a, b, c] = mesh.positions[i];
        assert!(
            a.is_finite() && b.is_finite() && c.is_finite(),
            "triangle {i} not finite"
        );
        // What the wgpu renderer divides by for barycentrics (the CPU's
        // intersector divides by `n · d` and misses where it is 0).
        let area2 = (b - a).cross(c - a).length_squared();
        assert!(
            area2.is_finite() && area2 >= f32::MIN_POSITIVE,
            "triangle {i} is degenerate (|e1 x e2|^2 = {area2}): {:?}",
            mesh.positions[i]
        );
        for nk in mesh.normals[i] {
            assert!(
                nk.is_finite() && (nk.length() - 1.0).abs() < 1e-4,
                "triangle {i}: normal {nk} is not a unit vector ({:?})",
                mesh.normals[i]
            );
        }
        for uk in mesh.uvs[i] {
            assert!(uk.is_finite(), "triangle {i}: uv {uk} not finite");
        }
        let m = mesh.materials[i] as usize;
        assert!(
            m < materials.len(),
            "triangle {i}: material {m} of {}",
            materials.len()
        );
    }
    for m in materials {
        assert!(
            m.emission.is_finite() && m.emission.min_element() >= 0.0,
            "{m:?}"
        );
        match &m.albedo {
            Albedo::Solid(c) => assert!(
                c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0,
                "{m:?}"
            ),
            other => panic!("a loader made a non-solid albedo: {other:?}"),
        }
        assert!((0.0..=1.0).contains(&m.mirror), "{m:?}");
    }
}

/// The error of a failed load must be one a loader documents.
pub fn check_error(e: &SceneError) {
    let msg = e.to_string();
    assert!(!msg.is_empty());
    assert!(
        !msg.contains("the parser failed"),
        "a parser panicked (caught by the loader): {msg}"
    );
    assert!(
        matches!(
            e,
            SceneError::Load { .. } | SceneError::Empty { .. } | SceneError::Camera(_)
        ),
        "unexpected error kind: {e:?}"
    );
}

/// Load `main` as `name` in the scratch directory (not written: the loaders
/// read from memory) and check the outcome; on success also frame a camera
/// and, for one input in eight, build the whole scene.
pub fn load_and_check(name: &str, main: &[u8]) {
    let path = scratch_dir().join(name);
    match subcone_load::load_mesh_bytes(&path, main) {
        Ok((mesh, materials, _dropped)) => {
            check_mesh(&mesh, &materials);
            match subcone_load::framing_camera(&mesh) {
                Ok(cam) => cam
                    .validate()
                    .expect("framing_camera returned an invalid camera"),
                Err(e) => check_error(&e),
            }
            if main.len().is_multiple_of(8) {
                match subcone_load::load_scene_bytes(&path, main) {
                    Ok(scene) => {
                        let m = scene.mesh().expect("a triangle scene");
                        assert_eq!(m.len(), mesh.len());
                        scene.camera.validate().expect("valid camera");
                        for l in &scene.lights {
                            assert!(l.is_finite(), "{l:?}");
                        }
                    }
                    Err(e) => check_error(&e),
                }
            }
        }
        Err(e) => check_error(&e),
    }
}
