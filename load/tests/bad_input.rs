//! Bad input gives a clear error (or documented handling), never a panic.

mod common;

use std::path::Path;

use common::{load_error, write};
use glam::Vec3;
use subcone_load::{load_mesh_file, load_scene, scene_from_arg, SaveFrame};
use subcone_scene::{Camera, Frame, RenderError, RenderSettings, SceneError};

fn load_reason(path: &Path) -> String {
    match load_mesh_file(path) {
        Err(SceneError::Load { path: p, reason }) => {
            assert_eq!(p, path, "the error names the file");
            reason
        }
        other => panic!("expected a load error, got {other:?}"),
    }
}

#[test]
fn malformed_obj_garbage_text() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "garbage.obj",
        "this is not an OBJ file\n%%% ### @@@\nlorem ipsum 1 2 3\n",
    );
    let reason = load_reason(&path);
    assert!(reason.contains("no triangles"), "{reason}");
    // The same through load_scene, with the path in the message.
    let err = load_scene(&path).unwrap_err();
    assert!(err.to_string().contains("garbage.obj"), "{err}");
}

#[test]
fn malformed_obj_bad_records() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text, expect) in [
        (
            "bad_vertex.obj",
            "v 1 2 banana\nv 0 0 0\nv 1 0 0\nf 1 2 3\n",
            "malformed OBJ",
        ),
        (
            "bad_face.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
            "malformed OBJ",
        ),
        (
            "out_of_range.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
            "malformed OBJ",
        ),
    ] {
        let path = write(dir.path(), name, text);
        let reason = load_reason(&path);
        assert!(reason.contains(expect), "{name}: {reason}");
    }
}

#[test]
fn malformed_obj_binary_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let bytes: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    let path = write(dir.path(), "binary.obj", bytes);
    load_reason(&path);
}

#[test]
fn empty_obj() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "empty.obj", "");
    let reason = load_reason(&path);
    assert!(reason.contains("empty"), "{reason}");
    // Comments only: parses, but has no triangle.
    let path = write(dir.path(), "comments.obj", "# nothing here\n\n");
    assert!(load_reason(&path).contains("no triangles"));
}

#[test]
fn empty_gltf_and_glb() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["empty.gltf", "empty.glb"] {
        let path = write(dir.path(), name, "");
        assert!(load_reason(&path).contains("empty"));
    }
    // Valid glTF with no meshes: no triangles.
    let path = write(
        dir.path(),
        "nomesh.gltf",
        r#"{"asset": {"version": "2.0"}}"#,
    );
    assert!(load_reason(&path).contains("no triangles"));
}

#[test]
fn malformed_gltf_json() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in [
        ("broken.gltf", "{ \"asset\": { \"version\": "),
        ("notgltf.gltf", "{}"),
        ("array.gltf", "[1, 2, 3]"),
        ("text.gltf", "hello"),
        ("truncated.glb", "glTF\u{2}\0\0\0"),
        (
            "dangling.gltf",
            r#"{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 5}}]}]}"#,
        ),
    ] {
        let path = write(dir.path(), name, text);
        let reason = load_reason(&path);
        assert!(!reason.is_empty(), "{name}");
    }
}

#[test]
fn nan_and_inf_vertices_are_dropped_and_counted() {
    let dir = tempfile::tempdir().unwrap();
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv NaN 0 0\nv 0 inf 0\n\
                f 1 2 3\nf 1 2 4\nf 1 5 3\n";
    let path = write(dir.path(), "nan.obj", text);
    let (mesh, _, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 1);
    assert_eq!(dropped.non_finite, 2);
    assert_eq!(dropped.degenerate, 0);
    assert!(mesh.positions[0].iter().all(|p| p.is_finite()));
}

#[test]
fn all_nan_obj_is_empty() {
    let dir = tempfile::tempdir().unwrap();
    let text = "v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -inf\nf 1 2 3\nf 2 3 4\n";
    let path = write(dir.path(), "allnan.obj", text);
    match load_mesh_file(&path) {
        Err(SceneError::Empty { name, detail }) => {
            assert_eq!(name, "allnan");
            assert!(detail.contains("all 2 triangle(s)"), "{detail}");
            assert!(detail.contains("2 triangle(s) with NaN/Inf"), "{detail}");
        }
        other => panic!("expected Empty, got {other:?}"),
    }
    assert!(matches!(load_scene(&path), Err(SceneError::Empty { .. })));
}

#[test]
fn degenerate_triangles_are_dropped_and_counted() {
    let dir = tempfile::tempdir().unwrap();
    // A good triangle, a collinear one, one with a repeated vertex, one tiny
    // sliver far below f32 resolution of its edges.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 1000 0 0\nv 500 1e-9 0\n\
                f 1 2 3\nf 1 2 4\nf 1 1 3\nf 1 5 6\n";
    let path = write(dir.path(), "degenerate.obj", text);
    let (mesh, _, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 1);
    assert_eq!(dropped.degenerate, 3);
    assert_eq!(dropped.non_finite, 0);
    assert!(dropped.to_string().contains("3 degenerate"));

    // Only degenerate triangles: Empty, naming the count.
    let path = write(
        dir.path(),
        "flat.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
    );
    let err = load_error(&path, "1 degenerate");
    assert!(matches!(err, SceneError::Empty { .. }), "{err}");
}

#[test]
fn unknown_extension() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["mesh.stl", "mesh.OBJX", "mesh"] {
        let path = write(dir.path(), name, "v 0 0 0\n");
        match load_mesh_file(&path) {
            Err(SceneError::UnknownFormat { path: p }) => assert_eq!(p, path),
            other => panic!("{name}: expected UnknownFormat, got {other:?}"),
        }
    }
    // Upper-case extensions are fine.
    let path = write(
        dir.path(),
        "TRI.OBJ",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    assert_eq!(load_mesh_file(&path).unwrap().0.len(), 1);
}

#[test]
fn missing_file() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["missing.obj", "missing.gltf", "missing.glb"] {
        let path = dir.path().join(name);
        let reason = load_reason(&path);
        assert!(reason.to_lowercase().contains("no such file"), "{reason}");
    }
    // A directory with a mesh extension is not a file.
    let sub = dir.path().join("folder.obj");
    std::fs::create_dir(&sub).unwrap();
    assert!(load_reason(&sub).contains("not a regular file"));
}

#[test]
fn missing_mtl_falls_back_to_the_default_material() {
    let dir = tempfile::tempdir().unwrap();
    let text = "mtllib nowhere.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let path = write(dir.path(), "nomtl.obj", text);
    let (mesh, materials, _) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 1);
    assert_eq!(materials.len(), 1);
    assert_eq!(materials[0].name, "default");
}

#[test]
fn unknown_scene_name_lists_the_choices() {
    let err = scene_from_arg("no-such-scene").unwrap_err();
    assert!(matches!(err, SceneError::UnknownScene { .. }), "{err}");
    let msg = err.to_string();
    for name in ["cornell", "checker", "atrium", "sponza-mirror", ".obj"] {
        assert!(msg.contains(name), "{msg}");
    }
    // A path with a mesh extension that does not exist is a load error.
    assert!(matches!(
        scene_from_arg("/no/such/dir/mesh.obj"),
        Err(SceneError::Load { .. })
    ));
}

#[test]
fn zero_field_of_view() {
    let look = |fov: f32| Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, fov);
    for fov in [
        0.0,
        -0.5,
        std::f32::consts::PI,
        4.0,
        f32::NAN,
        f32::INFINITY,
    ] {
        match look(fov) {
            Err(SceneError::Camera(msg)) => assert!(msg.contains("field of view"), "{msg}"),
            other => panic!("fov {fov}: expected a camera error, got {other:?}"),
        }
    }
    assert!(look(1.0).is_ok());
    // Other degenerate cameras.
    assert!(matches!(
        Camera::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y, 1.0),
        Err(SceneError::Camera(_))
    ));
    assert!(matches!(
        Camera::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, 1.0),
        Err(SceneError::Camera(_))
    ));
    assert!(matches!(
        Camera::look_at(Vec3::NAN, Vec3::Y, Vec3::Y, 1.0),
        Err(SceneError::Camera(_))
    ));
}

#[test]
fn zero_and_absurd_resolutions() {
    for (w, h) in [
        (0, 0),
        (0, 100),
        (100, 0),
        (100_000, 100_000),
        (20_000, 1),
        (16_384, 16_384),
    ] {
        match RenderSettings::new(w, h).validate() {
            Err(RenderError::Resolution {
                width,
                height,
                reason,
            }) => {
                assert_eq!((width, height), (w, h));
                assert!(!reason.is_empty());
            }
            other => panic!("{w}x{h}: expected a resolution error, got {other:?}"),
        }
    }
    for (w, h) in [(1, 1), (256, 256), (1920, 1080), (16_384, 1)] {
        RenderSettings::new(w, h).validate().unwrap();
    }
}

fn test_frame(w: u32, h: u32) -> Frame {
    let mut f = Frame::new(w, h);
    for y in 0..h {
        for x in 0..w {
            f.color[(y * w + x) as usize] =
                Vec3::new(x as f32 / w as f32, y as f32 / h as f32, 0.25);
        }
    }
    f.color[0] = Vec3::new(1.0, 0.0, 0.0);
    f
}

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn save_into_missing_directory() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no_such_dir").join("out.png");
    match test_frame(8, 4).save(&path) {
        Err(RenderError::Output { path: p, reason }) => {
            assert_eq!(p, path);
            assert!(reason.contains("does not exist"), "{reason}");
        }
        other => panic!("expected an output error, got {other:?}"),
    }
    assert!(!path.exists());
    assert!(entries(dir.path()).is_empty(), "nothing left behind");
}

#[test]
fn save_failures_leave_no_temp_file() {
    let dir = tempfile::tempdir().unwrap();
    // Unknown image format.
    let err = test_frame(4, 4)
        .save(&dir.path().join("out.bmp"))
        .unwrap_err();
    assert!(matches!(err, RenderError::Output { .. }), "{err}");
    // The target is a directory: the rename fails after the temp file was written.
    let target = dir.path().join("taken.png");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("keep"), "x").unwrap();
    let err = test_frame(4, 4).save(&target).unwrap_err();
    assert!(matches!(err, RenderError::Output { .. }), "{err}");
    assert_eq!(entries(dir.path()), vec!["taken.png".to_string()]);
    // A frame whose pixels do not match its size.
    let mut bad = test_frame(4, 4);
    bad.color.pop();
    let err = bad.save(&dir.path().join("bad.png")).unwrap_err();
    assert!(matches!(err, RenderError::Output { .. }), "{err}");
    assert_eq!(entries(dir.path()), vec!["taken.png".to_string()]);
}

/// [`test_frame`] saved as `name` in a fresh directory (the one file there),
/// and the image read back, of the frame's size.
fn save_and_read(name: &str, w: u32, h: u32) -> (tempfile::TempDir, Frame, image::DynamicImage) {
    let dir = tempfile::tempdir().unwrap();
    let frame = test_frame(w, h);
    frame.save(&dir.path().join(name)).unwrap();
    assert_eq!(entries(dir.path()), vec![name.to_string()]);
    let img = image::open(dir.path().join(name)).unwrap();
    assert_eq!((img.width(), img.height()), (w, h));
    (dir, frame, img)
}

#[test]
fn save_png_reads_back() {
    let (dir, frame, img) = save_and_read("frame.png", 37, 21);
    let path = dir.path().join("frame.png");
    let img = img.to_rgb8();
    assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0]);
    let srgb = frame.to_srgb8();
    let i = (5 * 37 + 30) * 3;
    assert_eq!(img.get_pixel(30, 5).0, [srgb[i], srgb[i + 1], srgb[i + 2]]);
    // Overwriting an existing file works.
    test_frame(2, 3).save(&path).unwrap();
    assert_eq!(image::open(&path).unwrap().to_rgb8().dimensions(), (2, 3));
}

#[test]
fn save_exr_reads_back_linear() {
    let (_dir, frame, img) = save_and_read("frame.exr", 6, 5);
    let img = img.to_rgb32f();
    let p = img.get_pixel(3, 2).0;
    let c = frame.pixel(3, 2);
    assert!((Vec3::from_array(p) - c).abs().max_element() < 1e-6);
}
