//! The command line, end to end: every method on the built-in scenes, and bad
//! input answered with a clear error and a failure exit code, never a panic or a
//! half-written file.
mod binary;

use std::path::Path;
use std::process::Command;

use binary::subcone;

#[test]
fn render_writes_png_and_exr_for_every_triangle_method() {
    let dir = tempfile::tempdir().unwrap();
    for method in ["noaa", "ssaa4", "sraa", "sraa-rt"] {
        for ext in ["png", "exr"] {
            let out = dir.path().join(format!("{method}.{ext}"));
            let (ok, text) = subcone(&[
                "render",
                "--scene",
                "cornell",
                "--method",
                method,
                "--size",
                "24x16",
                "-o",
                out.to_str().unwrap(),
                "--verbose",
            ]);
            assert!(ok, "{method}: {text}");
            assert!(text.contains("pass "), "--verbose lists the passes: {text}");
            assert!(
                text.contains("cpu path: "),
                "--verbose names the instruction-set path: {text}"
            );
            let img = image::open(&out).unwrap();
            assert_eq!((img.width(), img.height()), (24, 16));
        }
    }
}

#[test]
fn bad_input_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let o = out.to_str().unwrap();
    let cases: [(&[&str], &str); 10] = [
        (&["render", "--size", "0x0", "-o", o], "resolution"),
        (
            &["render", "--size", "100000x100000", "-o", o],
            "resolution",
        ),
        (&["render", "--size", "abc", "-o", o], "--size"),
        (&["render", "--method", "ssaa5", "-o", o], "unknown method"),
        (
            &["render", "--isa", "sse9", "-o", o],
            "unknown instruction set",
        ),
        (
            &["render", "--backend", "wgpu", "--isa", "avx2", "-o", o],
            "--isa",
        ),
        (&["render", "--scene", "nope", "-o", o], "no built-in scene"),
        (
            &["render", "--scene", "/does/not/exist.obj", "-o", o],
            "cannot load",
        ),
        (
            &["render", "--size", "8x8", "-o", "/does/not/exist/x.png"],
            "does not exist",
        ),
        (
            &[
                "render", "--size", "8x8", "--method", "ctss", "--scene", "cornell", "-o", o,
            ],
            "signed distance field",
        ),
    ];
    for (args, needle) in cases {
        let (ok, text) = subcone(args);
        assert!(!ok, "{args:?} succeeded");
        assert!(
            text.contains(needle),
            "{args:?}: expected {needle:?} in {text:?}"
        );
    }
    assert!(
        !Path::new(&out).exists(),
        "a failed render left an output file"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "a failed render left a temporary file"
    );
}

/// A scene and method the backend does not render fail with its typed
/// reason, before anything is rendered or written.
#[test]
fn unsupported_combinations_are_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let o = out.to_str().unwrap();
    let cases: [(&str, &str, &str); 3] = [
        ("cornell", "ctss", "needs a signed distance field"),
        ("glass", "sraa-rt", "semi-transparent materials"),
        ("primitives", "sraa-rt+mat", "material gate"),
    ];
    for (scene, method, needle) in cases {
        let (ok, text) = subcone(&[
            "render", "--size", "8x8", "--scene", scene, "--method", method, "-o", o,
        ]);
        assert!(!ok, "{scene} {method} succeeded");
        assert!(
            text.contains(&format!(
                "the cpu backend cannot render scene {scene:?} with {method}: "
            )) && text.contains(needle),
            "{scene} {method}: expected {needle:?} in {text:?}"
        );
        assert!(!out.exists(), "a refused render wrote {o}");
    }
}

/// Without an adapter for the requested API, `--backend wgpu` fails with a
/// message naming the driver to install, not a panic. DX12 never exists on
/// Linux; on Windows, Metal never does.
#[test]
fn wgpu_without_an_adapter_names_the_fix() {
    let missing = if cfg!(windows) { "metal" } else { "dx12" };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let run = Command::new(env!("CARGO_BIN_EXE_subcone"))
        .args(["render", "--backend", "wgpu", "--size", "8x8", "-o"])
        .arg(&out)
        .env("WGPU_BACKEND", missing)
        .output()
        .expect("run subcone");
    let text = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "no adapter must fail: {text}");
    assert!(!text.contains("panicked"), "{text}");
    assert!(text.contains("no GPU adapter"), "{text}");
    assert!(text.contains("mesa-vulkan-drivers"), "{text}");
    assert!(!out.exists(), "no image is written on failure");
}

/// Every method of the one list (`METHOD_NAMES`) is documented where a user
/// looks: in `subcone render --help` and in README.md (`ssaa4`, `ssaa16` and
/// `ssaa4+ctss` as the `ssaaN` and `ssaaN+ctss` families, `-delayed`
/// variants as the suffix).
#[test]
fn every_method_name_is_documented() {
    let (ok, help) = subcone(&["render", "--help"]);
    assert!(ok, "{help}");
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .expect("README.md");
    for name in subcone_scene::method::METHOD_NAMES {
        let family = if name.starts_with("ssaa") {
            if name.ends_with("+ctss") {
                "ssaaN+ctss"
            } else {
                "ssaaN"
            }
        } else {
            name.strip_suffix("-delayed").unwrap_or(name)
        };
        assert!(help.contains(family), "render --help does not name {name}");
        assert!(
            readme.contains(&format!("`{family}`")),
            "README.md does not name {name} (as `{family}`)"
        );
        if name.ends_with("-delayed") {
            assert!(
                help.contains("-delayed"),
                "render --help: no -delayed suffix"
            );
        }
    }
}

/// `--ao N` on `render` and `report`: accepted up to the cap on triangle and
/// SDF scenes (the rays are listed with `--verbose`), refused above it, with
/// a message naming what to change.
#[test]
fn ambient_occlusion_flag() {
    let dir = tempfile::tempdir().unwrap();
    let text = render_with_ao("cornell", &dir.path().join("ao.png"));
    assert!(text.contains("ao "), "--verbose counts the AO rays: {text}");
    let text = render_with_ao("primitives", &dir.path().join("ao-sdf.png"));
    assert!(
        text.contains("ao ") && !text.contains("ao 0.00"),
        "--verbose counts the SDF scene's AO rays: {text}"
    );
    for (args, needle) in [
        (
            vec!["render", "--size", "8x8", "--ao", "257"],
            "at most 256",
        ),
        (vec!["render", "--size", "8x8", "--ao", "many"], "--ao"),
        (vec!["report", "--quick", "--ao", "1000"], "at most 256"),
    ] {
        let bad = dir.path().join("bad.png");
        let mut args = args.clone();
        args.extend(["-o", bad.to_str().unwrap()]);
        if args[0] == "report" {
            args.truncate(args.len() - 2);
        }
        let (ok, text) = subcone(&args);
        assert!(!ok, "{args:?} succeeded");
        assert!(
            text.contains(needle),
            "{args:?}: expected {needle:?} in {text:?}"
        );
        assert!(!bad.exists());
    }
}

/// `subcone render --ao 4 --verbose` of `scene` with SRAA-RT at 24×16 into
/// `out`, which must succeed and write `out`; its output.
fn render_with_ao(scene: &str, out: &Path) -> String {
    let (ok, text) = subcone(&[
        "render",
        "--scene",
        scene,
        "--method",
        "sraa-rt",
        "--size",
        "24x16",
        "--ao",
        "4",
        "--verbose",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{scene}: {text}");
    assert!(out.exists(), "{scene}: no {}", out.display());
    text
}

/// A bad scene file is an error that says where and why once: the scene
/// error's message holds the file error's, and the chain of causes does not
/// print it a second time.
#[test]
fn a_bad_scene_file_prints_its_cause_once() {
    let dir = std::env::temp_dir().join(format!("subcone-cli-cause-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("nan.sdf.ron");
    std::fs::write(
        &path,
        "SdfScene(\n    camera: (position: (0, 1, -5), target: (0, 1, 0)),\n    materials: [(name: \"floor\")],\n    lights: [],\n    root: Sphere(radius: NaN),\n)\n",
    )
    .unwrap();
    let (ok, text) = subcone(&[
        "render",
        "--scene",
        path.to_str().unwrap(),
        "--method",
        "noaa",
    ]);
    std::fs::remove_dir_all(&dir).ok();
    assert!(!ok, "{text}");
    assert!(text.contains("radius must be finite"), "{text}");
    assert_eq!(text.matches("radius must be finite").count(), 1, "{text}");
    assert_eq!(text.matches("nan.sdf.ron:").count(), 1, "{text}");
}
