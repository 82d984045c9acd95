//! SDF scene files end to end: `subcone scene --export` writes every built-in
//! SDF scene, `--scene FILE` reads it back, and the renders are the built-in's,
//! byte for byte; the example scenes render with `ctss` and go through
//! `report --quick` on both backends.

mod binary;

use std::path::{Path, PathBuf};

use subcone_cpu::CpuBackend;
use subcone_load::scene_from_arg;
use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
use subcone_scene::{Backend, Frame, Method, RenderSettings, Scene};

/// Runs `subcone args…`, which must succeed: its output.
fn subcone(args: &[&str]) -> String {
    let (ok, text) = binary::subcone(args);
    assert!(ok, "subcone {args:?}: {text}");
    text
}

fn render(scene: &Scene, method: &str) -> Frame {
    let method: Method = method.parse().unwrap();
    CpuBackend::new()
        .render(scene, &scene.camera, &method, &RenderSettings::new(64, 36))
        .unwrap_or_else(|e| panic!("{} {method}: {e}", scene.name))
}

#[test]
fn every_exported_builtin_renders_as_the_builtin_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    for name in SDF_SCENES
        .into_iter()
        .chain(STIFF_SCENES)
        .chain(TRANSPARENT_SCENES)
    {
        let file = dir.path().join(format!("{name}.sdf.ron"));
        subcone(&["scene", "--export", name, "-o", file.to_str().unwrap()]);
        let builtin = scene_from_arg(name).unwrap();
        let loaded = scene_from_arg(file.to_str().unwrap()).unwrap();
        assert_eq!(loaded.name, builtin.name);
        // The wgpu backend renders the tree's WGSL: the same text.
        let wgsl =
            |s: &Scene| subcone_sdf::wgsl::WgslField::compile(&s.sdf_geometry().unwrap().root);
        let (a, b) = (wgsl(&builtin), wgsl(&loaded));
        assert!(a.source == b.source, "{name}: the WGSL differs");
        // Bits: empty scatter cells hold NaN.
        let bits = |d: &[[f32; 4]]| d.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert!(
            bits(&a.data) == bits(&b.data),
            "{name}: the WGSL data differ"
        );
        for method in ["noaa", "ctss"] {
            let (x, y) = (render(&builtin, method), render(&loaded, method));
            assert!(
                x.color_bits() == y.color_bits(),
                "{name} {method}: the frames differ"
            );
        }
    }
}

fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(files.len() >= 2, "{files:?}");
    files
}

/// The backends a test that runs the binary can use here: the CPU always,
/// wgpu when it has an adapter. Without one the wgpu half skips, printing
/// why, unless `SUBCONE_REQUIRE_GPU` is set, when it fails.
fn backends(test: &str) -> Vec<&'static str> {
    let gpu = subcone_wgpu::test_util::gpu_or_skip(test).is_some();
    if gpu {
        vec!["cpu", "wgpu"]
    } else {
        vec!["cpu"]
    }
}

#[test]
fn the_example_scenes_render_with_ctss_on_both_backends() {
    let dir = tempfile::tempdir().unwrap();
    let backends = backends("ctss on the wgpu backend");
    for file in examples() {
        for &backend in &backends {
            let out = dir.path().join("out.png");
            let text = subcone(&[
                "render",
                "--scene",
                file.to_str().unwrap(),
                "--method",
                "ctss",
                "--backend",
                backend,
                "--size",
                "64x36",
                "-o",
                out.to_str().unwrap(),
            ]);
            assert!(text.contains("ctss 64x36"), "{text}");
            let img = image::open(&out).unwrap().to_rgb8();
            // Not a blank frame: the scene is there.
            let first = img.get_pixel(0, 0);
            assert!(
                img.pixels().any(|p| p != first),
                "{}: blank",
                file.display()
            );
        }
    }
}

#[test]
fn the_example_scenes_go_through_the_quick_report_on_both_backends() {
    let file = examples()
        .into_iter()
        .find(|f| f.ends_with("few-primitives.sdf.ron"))
        .unwrap();
    let out = tempfile::tempdir().unwrap();
    let backends = backends("the quick report on the wgpu backend");
    let backend_arg = backends.join(",");
    subcone(&[
        "report",
        "--quick",
        "--no-paper-scenes",
        "--no-sweep",
        "--scene",
        file.to_str().unwrap(),
        "--backend",
        &backend_arg,
        "--method",
        "noaa,ssaa4,ctss,ctss-r",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    let csv = std::fs::read_to_string(out.path().join("results.csv")).unwrap();
    // By name, not position: the report may add columns.
    let flip_col = csv
        .lines()
        .next()
        .and_then(|h| h.split(',').position(|c| c == "flip_mean"))
        .unwrap_or_else(|| panic!("no flip_mean column:\n{csv}"));
    for &backend in &backends {
        for method in ["noaa", "ssaa4", "ctss", "ctss-r"] {
            // scene,method,backend,…, with a measured FLIP.
            let row = csv
                .lines()
                .map(|l| l.split(',').collect::<Vec<_>>())
                .find(|c| {
                    c.len() > flip_col
                        && c[0] == "few-primitives"
                        && c[1] == method
                        && c[2] == backend
                });
            let row = row.unwrap_or_else(|| panic!("no {backend} {method} row:\n{csv}"));
            let flip: f64 = row[flip_col].parse().unwrap_or(f64::NAN);
            assert!(flip > 0.0 && flip < 1.0, "{backend} {method}: FLIP {flip}");
        }
    }
}

/// The fuzz target `sdf_file` starts from these seeds: every exported built-in
/// as `subcone scene --export` writes it today, and the examples.
#[test]
fn the_fuzz_seeds_are_the_current_exports_and_the_examples() {
    let seeds = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/seeds/sdf_file");
    for name in SDF_SCENES
        .into_iter()
        .chain(STIFF_SCENES)
        .chain(TRANSPARENT_SCENES)
    {
        let seed = std::fs::read_to_string(seeds.join(format!("{name}.sdf.ron"))).unwrap();
        let now = subcone(&["scene", "--export", name]);
        assert!(
            seed == now,
            "fuzz/seeds/sdf_file/{name}.sdf.ron is stale: regenerate it with \
             `subcone scene --export {name} -o fuzz/seeds/sdf_file/{name}.sdf.ron`"
        );
    }
    for file in examples() {
        let seed = std::fs::read(seeds.join(file.file_name().unwrap())).unwrap();
        assert!(
            seed == std::fs::read(&file).unwrap(),
            "{}: stale seed",
            file.display()
        );
    }
}

/// The README shows `examples/scenes/few-primitives.sdf.ron` as it is.
#[test]
fn the_readme_shows_the_example_file_as_it_is() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let shown = readme
        .split("```ron\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("README.md has a ```ron block");
    let file =
        std::fs::read_to_string(root.join("examples/scenes/few-primitives.sdf.ron")).unwrap();
    let body = &file[file.find("SdfScene(").unwrap()..];
    assert_eq!(
        shown, body,
        "README.md's ```ron block is not the example file"
    );
}

/// A bad scene file or export name fails with a message that says where and
/// what, and writes no image.
#[test]
fn bad_scene_files_and_export_names_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.sdf.ron");
    std::fs::write(
        &bad,
        "SdfScene(\n    camera: (position: (0, 1, -5), target: (0, 0, 0)),\n    root: Sphere(radius: -2),\n)\n",
    )
    .unwrap();
    let out = dir.path().join("x.png");
    let run = |args: &[&str]| {
        let (ok, text) = binary::subcone(args);
        assert!(!ok, "{text}");
        text
    };
    let text = run(&[
        "render",
        "--scene",
        bad.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        text.contains("bad.sdf.ron:3:28: root: sphere: radius must not be negative, got -2"),
        "{text}"
    );
    assert!(!out.exists(), "an image was written for a bad scene");
    let text = run(&["scene", "--export", "cornell"]);
    assert!(
        text.contains("no built-in SDF scene named \"cornell\""),
        "{text}"
    );
    let missing = dir.path().join("missing.sdf.ron");
    let text = run(&["render", "--scene", missing.to_str().unwrap()]);
    assert!(text.contains("cannot read the file"), "{text}");
}
