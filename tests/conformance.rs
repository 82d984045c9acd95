//! The backend conformance suite: every built-in scene times every method that
//! applies to it, the numerical-stability scenes and the error cases, on every
//! backend, against the CPU reference.
//!
//! One macro, [`conformance_suite!`], holds the cases; each backend gets one
//! line that instantiates them (see "Adding a backend" in ARCHITECTURE.md):
//!
//! ```text
//! conformance_suite!(my_backend, MyBackend::new());
//! ```
//!
//! Run one backend's cases with `cargo test --test conformance wgpu::`. On a
//! failure the reference, the backend's frame and the FLIP map are written to
//! `target/conformance/<backend>/` and the message names them.
//!
//! A GPU backend that cannot open an adapter fails the suite when
//! `SUBCONE_REQUIRE_GPU` is set (as CI sets it) and skips it, saying so, when not.

use std::path::PathBuf;

use subcone::report::metrics::{flip, Rgb8};
use subcone_kernels::passes::{required_passes, Passes, SceneFeatures};
use subcone_scene::builtin::{builtin, TRIANGLE_SCENES};
use subcone_scene::sdf::{SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
use subcone_scene::{
    Backend, Frame, Method, RenderError, RenderSettings, Scene, UnsupportedReason,
};

/// Frame size of the suite: small, because lavapipe runs shaders on the CPU,
/// and not square, so that a swapped width and height shows.
const W: u32 = 64;
const H: u32 = 48;

/// Methods run on triangle scenes.
const TRIANGLE_METHODS: [&str; 8] = [
    "noaa",
    "ssaa4",
    "ssaa16",
    "sraa",
    "sraa-rt",
    "sraa+mat",
    "sraa-rt+mat",
    "fxaa",
];
/// Methods run on SDF scenes.
const SDF_METHODS: [&str; 8] = [
    "noaa",
    "ssaa4",
    "ctss",
    "ctss-r",
    "ssaa4+ctss",
    "ctss-delayed",
    "sraa-rt",
    "fxaa",
];

/// Methods only the CPU reference renders on SDF scenes, with the reason. Not
/// skipped: `cpu_only_methods` renders them on the CPU (every SDF and stiff
/// scene, frame invariants) and requires every other backend to plan and make
/// the refusal ([`Backend::supports`], then `render`) as
/// [`UnsupportedReason::CpuOnly`], saying "CPU backend only"; where they are
/// also in [`SDF_METHODS`], the per-scene cases check the refusal too. Any
/// other refusal of a method in the scene lists, but a technique that does
/// not apply to the scene, fails the suite.
const CPU_ONLY_ON_SDF: [(&str, &str); 2] = [
    (
        "sraa-rt",
        "sphere-traced subpixel geometry and its reconstruction exist on the CPU only",
    ),
    (
        "ctss+edges",
        "hit group subdivision (CTSS §5.3) has no WGSL twin",
    ),
];

/// How close a backend's frame must be to the CPU reference, in LDR-FLIP.
///
/// Both backends evaluate the same kernels on the same rays in f32, so the
/// images differ only where rounding decides a discrete outcome: a ray that
/// grazes an edge hits on one backend and misses on the other, a shadow ray
/// that grazes an occluder, a CTSS hit group that closes one step earlier. Each
/// such pixel can carry a large FLIP error, but they are rare, so the mean is
/// held tight and the 99th percentile (the worst 1 % of pixels may be those
/// edge pixels) a little looser, as wgpu's own image tests compare percentiles.
#[derive(Clone, Copy, Debug)]
struct Tolerance {
    mean: f64,
    p99: f32,
}

/// The tolerance of every frame comparison of the suite.
const FRAME_TOLERANCE: Tolerance = Tolerance {
    mean: 0.01,
    p99: 0.10,
};

fn output_dir(backend: &str) -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("conformance").join(backend)
}

fn save(img: &Rgb8, path: &PathBuf) {
    let _ = std::fs::create_dir_all(path.parent().expect("has a parent"));
    if let Err(e) = image::save_buffer(
        path,
        &img.data,
        img.width,
        img.height,
        image::ExtendedColorType::Rgb8,
    ) {
        eprintln!("could not write {}: {e}", path.display());
    }
}

fn percentile(values: &[f32], q: f64) -> f32 {
    let mut v = values.to_vec();
    v.sort_by(f32::total_cmp);
    let i = ((v.len() as f64 - 1.0) * q).round() as usize;
    v[i.min(v.len() - 1)]
}

/// What a frame must satisfy on any backend, reference or not.
fn check_invariants(backend: &str, scene: &Scene, method: &Method, frame: &Frame) {
    let what = format!("{backend}: {} {method}", scene.name);
    assert_eq!((frame.width, frame.height), (W, H), "{what}: frame size");
    assert_eq!(frame.color.len(), (W * H) as usize, "{what}: pixel count");
    if let Some(i) = frame
        .color
        .iter()
        .position(|c| !c.is_finite() || c.min_element() < 0.0)
    {
        panic!(
            "{what}: pixel {i} is {:?}: colours must be finite and non-negative",
            frame.color[i]
        );
    }
    let features = scene.features();
    let required = required_passes(method.technique, features).expect("applicable");
    assert_eq!(
        frame.stats.passes, required,
        "{what}: the backend ran other passes than the kernels require"
    );
    // A post-process pass (FXAA) is run and timed exactly when planned.
    assert_eq!(
        frame.stats.timings.iter().any(|t| t.name == "post-process"),
        required.contains(Passes::POST_PROCESS),
        "{what}: post-process pass timed {:?}",
        frame.stats.timings
    );
    // Leave out what the scene does not need: no work and no memory.
    let shadow = Passes::SHADOW | Passes::SUBPIXEL_SHADOW | Passes::SECONDARY_SHADOW;
    let secondary = Passes::SECONDARY
        | Passes::SECONDARY_SHADOW
        | Passes::SUBPIXEL_SECONDARY_GEOMETRY
        | Passes::SECONDARY_RECONSTRUCTION;
    let has = |word: &str| {
        frame
            .stats
            .buffers
            .iter()
            .filter(|b| b.0.contains(word) && b.1 > 0)
            .map(|b| b.0)
            .collect::<Vec<_>>()
    };
    if !features.contains(SceneFeatures::HAS_LIGHTS) {
        assert_eq!(
            frame.stats.rays.shadow, 0,
            "{what}: shadow rays without lights"
        );
    }
    if !required.intersects(shadow) {
        assert!(
            has("shadow").is_empty(),
            "{what}: shadow buffers {:?} allocated",
            has("shadow")
        );
    }
    if !features.contains(SceneFeatures::HAS_REFLECTIONS) {
        assert_eq!(
            frame.stats.rays.secondary, 0,
            "{what}: reflection rays without mirrors"
        );
    }
    if !required.intersects(secondary) {
        assert!(
            has("secondary").is_empty(),
            "{what}: secondary buffers {:?} allocated",
            has("secondary")
        );
    }
}

/// Render `scene_name` with every method of `methods` that `backend` supports,
/// on `backend` and on the CPU reference, and compare; where it does not,
/// check that `render` refuses as `supports` planned, and only for a reason
/// the suite allows.
fn check_scene(backend: &dyn Backend, scene_name: &str, methods: &[&str]) {
    let scene = builtin(scene_name).expect("built-in scene");
    let reference = subcone_cpu::CpuBackend::new();
    let settings = RenderSettings::new(W, H);
    let mut failures = Vec::new();
    let mut ran = 0;
    for m in methods {
        let method: Method = m.parse().expect("method name");
        let sdf = scene.features().contains(SceneFeatures::IS_SDF);
        let cpu_only = CPU_ONLY_ON_SDF
            .iter()
            .find(|(name, _)| sdf && *name == *m && backend.name() != "cpu");
        match backend.supports(&scene, &method) {
            Ok(()) => assert!(
                cpu_only.is_none(),
                "{}: {scene_name} {m} is listed as CPU-only but supported; compare it instead",
                backend.name()
            ),
            Err(u) => {
                // The plan is what render does.
                match backend.render(&scene, &scene.camera, &method, &settings) {
                    Err(RenderError::NotSupported(r)) => assert_eq!(
                        r,
                        u,
                        "{}: {scene_name} {m}: render refused otherwise than planned",
                        backend.name()
                    ),
                    other => panic!(
                        "{}: {scene_name} {m}: planned refusal ({u}) but render gave {:?}",
                        backend.name(),
                        other.map(|_| "a frame")
                    ),
                }
                match (&u.reason, cpu_only) {
                    // The technique does not apply: no backend renders it.
                    (UnsupportedReason::Technique(_), _) => {
                        assert!(
                            required_passes(method.technique, scene.features()).is_err(),
                            "{u}"
                        );
                    }
                    (UnsupportedReason::CpuOnly { .. }, Some((_, why))) => {
                        assert!(u.to_string().contains("CPU backend only"), "{u}");
                        ran += 1;
                        println!(
                            "{:>5} {scene_name:>16} {m:>10}: CPU-only ({why}), refused: {u}",
                            backend.name()
                        );
                    }
                    _ => panic!(
                        "{}: {scene_name} {m} refused, and not as listed in CPU_ONLY_ON_SDF: {u}",
                        backend.name()
                    ),
                }
                continue;
            }
        }
        ran += 1;
        let expected = reference
            .render(&scene, &scene.camera, &method, &settings)
            .unwrap_or_else(|e| panic!("cpu reference: {scene_name} {m}: {e}"));
        let actual = backend
            .render(&scene, &scene.camera, &method, &settings)
            .unwrap_or_else(|e| panic!("{}: {scene_name} {m}: {e}", backend.name()));
        check_invariants(backend.name(), &scene, &method, &actual);
        let r = Rgb8::from_frame(&expected).expect("8-bit reference");
        let a = Rgb8::from_frame(&actual).expect("8-bit frame");
        let f = flip(&r, &a).expect("FLIP");
        let p99 = percentile(&f.map, 0.99);
        let t = FRAME_TOLERANCE;
        println!(
            "{:>5} {scene_name:>16} {m:>10}: FLIP mean {:.5} (≤ {}), p99 {:.4} (≤ {})",
            backend.name(),
            f.mean,
            t.mean,
            p99,
            t.p99
        );
        if f.mean > t.mean || p99 > t.p99 {
            let dir = output_dir(backend.name());
            let stem = format!("{scene_name}-{}", m.replace('+', "_"));
            for (suffix, img) in [("reference", &r), ("actual", &a), ("flip", &f.magma)] {
                save(img, &dir.join(format!("{stem}-{suffix}.png")));
            }
            failures.push(format!(
                "{m}: FLIP mean {:.5} (limit {}), p99 {:.4} (limit {}); images in {}/{stem}-*.png",
                f.mean,
                t.mean,
                p99,
                t.p99,
                dir.display()
            ));
        }
    }
    assert!(ran > 0, "no method applies to {scene_name}");
    assert!(
        failures.is_empty(),
        "{} disagrees with the CPU reference on {scene_name}:\n{}",
        backend.name(),
        failures.join("\n")
    );
}

/// Extreme settings every backend must survive with finite frames: one step,
/// a ray length far below the scene, and a ray length far beyond f32's reach.
fn check_extreme_settings(backend: &dyn Backend) {
    let scene = builtin("primitives").expect("built-in");
    for m in ["noaa", "ctss", "ctss-r"] {
        let method: Method = m.parse().expect("method");
        for (label, steps, distance) in [
            ("one step", Some(1), None),
            ("tiny reach", None, Some(1e-6)),
            ("huge reach", None, Some(3.0e38)),
        ] {
            let settings = RenderSettings {
                max_steps: steps,
                max_distance: distance,
                ..RenderSettings::new(W, H)
            };
            let frame = backend
                .render(&scene, &scene.camera, &method, &settings)
                .unwrap_or_else(|e| panic!("{}: {m} with {label}: {e}", backend.name()));
            check_invariants(backend.name(), &scene, &method, &frame);
        }
    }
}

/// [`CPU_ONLY_ON_SDF`]: finite, invariant-abiding frames on the CPU on
/// every SDF scene; a clear error on any other backend.
fn check_cpu_only(backend: &dyn Backend) {
    let settings = RenderSettings::new(W, H);
    for (m, why) in CPU_ONLY_ON_SDF {
        let method: Method = m.parse().expect("method name");
        for name in SDF_SCENES.iter().chain(&STIFF_SCENES) {
            let scene = builtin(name).expect("built-in scene");
            let plan = backend.supports(&scene, &method);
            match backend.render(&scene, &scene.camera, &method, &settings) {
                Ok(frame) => {
                    assert_eq!(
                        backend.name(),
                        "cpu",
                        "{m} is CPU-only ({why}) but {} rendered it",
                        backend.name()
                    );
                    assert_eq!(plan, Ok(()), "cpu: {name} {m}: rendered what it refused");
                    check_invariants(backend.name(), &scene, &method, &frame);
                }
                Err(e) => {
                    assert_ne!(backend.name(), "cpu", "cpu: {name} {m}: {e}");
                    let planned = plan.expect_err("refused by render, so by supports");
                    assert!(
                        matches!(planned.reason, UnsupportedReason::CpuOnly { .. }),
                        "{}: {name} {m} refused without saying it is CPU-only: {planned}",
                        backend.name()
                    );
                    assert!(
                        matches!(&e, RenderError::NotSupported(u) if *u == planned),
                        "{}: {name} {m}: render refused otherwise than planned: {e}",
                        backend.name()
                    );
                    assert!(
                        e.to_string().contains("CPU backend only"),
                        "{}: {name} {m} refused without saying why: {e}",
                        backend.name()
                    );
                    break;
                }
            }
        }
    }
}

/// Bad input is an error value on every backend.
fn check_errors(backend: &dyn Backend) {
    let name = backend.name();
    let cornell = builtin("cornell").expect("built-in");
    let sraa: Method = "sraa".parse().expect("method");
    let zero = RenderSettings::new(0, 16);
    assert!(matches!(
        backend.render(&cornell, &cornell.camera, &sraa, &zero),
        Err(RenderError::Resolution { .. })
    ));
    let huge = RenderSettings::new(subcone_scene::backend::MAX_SIDE + 1, 16);
    assert!(
        backend
            .render(&cornell, &cornell.camera, &sraa, &huge)
            .is_err(),
        "{name}: a side over the limit must be refused"
    );
    let ctss: Method = "ctss".parse().expect("method");
    let primitives = builtin("primitives").expect("built-in");
    for (scene, method, why) in [
        (&cornell, &ctss, "CTSS needs an SDF scene"),
        (&primitives, &sraa, "SRAA needs a triangle scene"),
    ] {
        let planned = backend.supports(scene, method).expect_err(why);
        assert!(
            matches!(planned.reason, UnsupportedReason::Technique(_)),
            "{name}: {why}: {planned}"
        );
        let r = backend.render(scene, &scene.camera, method, &RenderSettings::new(8, 8));
        assert!(
            matches!(&r, Err(RenderError::NotSupported(u)) if *u == planned),
            "{name}: {why}: {:?}",
            r.map(|_| "a frame")
        );
    }
    let mut camera = cornell.camera;
    camera.fov_y = f32::NAN;
    assert!(
        backend
            .render(&cornell, &camera, &sraa, &RenderSettings::new(8, 8))
            .is_err(),
        "{name}: a NaN field of view must be refused"
    );
}

/// One test per scene: `scene_tests!(backend_fn; METHODS; test_name => "scene", ...)`.
macro_rules! scene_tests {
    ($backend:ident; $methods:expr; $($test:ident => $scene:expr),* $(,)?) => {$(
        #[test]
        fn $test() {
            if let Some(b) = $backend() {
                check_scene(b.as_ref(), $scene, &$methods);
            }
        }
    )*};
}

/// The conformance cases for one backend: `conformance_suite!(module, constructor)`
/// where `constructor` is an expression of type `Result<impl Backend, RenderError>`.
macro_rules! conformance_suite {
    ($name:ident, $make:expr) => {
        mod $name {
            use super::*;

            fn backend() -> Option<Box<dyn Backend>> {
                match $make {
                    Ok(b) => Some(Box::new(b)),
                    Err(e) if !subcone_wgpu::gpu_required() => {
                        eprintln!(
                            "SKIPPED: {} unavailable and SUBCONE_REQUIRE_GPU unset: {e}",
                            stringify!($name)
                        );
                        None
                    }
                    Err(e) => panic!("{} unavailable (SUBCONE_REQUIRE_GPU is set): {e}", stringify!($name)),
                }
            }

            scene_tests!(backend; TRIANGLE_METHODS;
                cornell => "cornell",
                cornell_nomirror => "cornell-nomirror",
                checker => "checker",
                atrium => "atrium",
            );
            scene_tests!(backend; SDF_METHODS;
                primitives => "primitives",
                random_box => "random-box",
                random_shape => "random-shape",
                sdf_atrium => "sdf-atrium",
                sparse_shape => "sparse-shape",
                stiff_thin => "thin",
                stiff_grazing => "grazing",
                stiff_far => "far",
                stiff_non_eikonal => "non-eikonal",
            );

            #[test]
            fn extreme_settings() {
                if let Some(b) = backend() {
                    check_extreme_settings(b.as_ref());
                }
            }

            #[test]
            fn cpu_only_methods() {
                if let Some(b) = backend() {
                    check_cpu_only(b.as_ref());
                }
            }

            #[test]
            fn errors() {
                if let Some(b) = backend() {
                    check_errors(b.as_ref());
                }
            }
        }
    };
}

conformance_suite!(cpu, Ok::<_, RenderError>(subcone_cpu::CpuBackend::new()));
conformance_suite!(wgpu, subcone_wgpu::WgpuBackend::new());

/// The suite's scene lists are the crate's: a new built-in scene must be added
/// to the suite.
#[test]
fn suite_covers_every_builtin_scene() {
    let covered = [
        "cornell",
        "cornell-nomirror",
        "checker",
        "atrium",
        "primitives",
        "random-box",
        "random-shape",
        "sdf-atrium",
        "sparse-shape",
        "thin",
        "grazing",
        "far",
        "non-eikonal",
    ];
    for s in TRIANGLE_SCENES
        .iter()
        .chain(&SDF_SCENES)
        .chain(&STIFF_SCENES)
    {
        assert!(
            covered.contains(s),
            "scene {s} is not in the conformance suite"
        );
    }
}

/// The scenes with semi-transparent materials ([`TRANSPARENT_SCENES`]) are
/// rendered by the CPU backend only (CTSS §5.3's K masks have no WGSL twin
/// yet), so they are not in the suite: the wgpu backend must refuse them with
/// an error, never draw them opaque, and the CPU backend must render them.
#[test]
fn transparent_scenes_are_refused_by_wgpu_and_rendered_by_cpu() {
    let gpu = subcone_wgpu::test_util::gpu_or_skip("the wgpu part");
    let settings = RenderSettings::new(W, H);
    for name in TRANSPARENT_SCENES {
        let scene = builtin(name).unwrap();
        assert!(scene.has_translucency(), "{name}");
        for m in SDF_METHODS {
            let method: Method = m.parse().unwrap();
            if let Some(gpu) = &gpu {
                let planned = gpu
                    .supports(&scene, &method)
                    .expect_err("wgpu plans to refuse a semi-transparent scene");
                assert!(
                    matches!(planned.reason, UnsupportedReason::Translucency { .. }),
                    "{name} {m}: {planned}"
                );
                let r = gpu.render(&scene, &scene.camera, &method, &settings);
                assert!(
                    matches!(&r, Err(RenderError::NotSupported(u)) if *u == planned),
                    "{name} {m}: wgpu did not refuse a semi-transparent scene as planned: {:?}",
                    r.map(|_| "a frame")
                );
            }
            let cpu_backend = subcone_cpu::CpuBackend::new();
            let plan = cpu_backend.supports(&scene, &method);
            let cpu = cpu_backend.render(&scene, &scene.camera, &method, &settings);
            // The paths that carry opacity render it; the others (SRAA-RT,
            // delayed shading, split groups) refuse it rather than draw it opaque.
            if ["noaa", "ssaa4", "ctss", "ctss-r", "ssaa4+ctss", "fxaa"].contains(&m) {
                assert_eq!(plan, Ok(()), "{name} {m}");
                assert!(cpu.is_ok(), "{name} {m}: {:?}", cpu.err());
            } else {
                let planned = plan.expect_err(m);
                assert!(
                    matches!(planned.reason, UnsupportedReason::Translucency { .. }),
                    "{name} {m}: {planned}"
                );
                let e = cpu.expect_err(m);
                assert!(
                    matches!(&e, RenderError::NotSupported(u) if *u == planned),
                    "{name} {m}: {e}"
                );
                assert!(
                    e.to_string().contains("semi-transparent"),
                    "{name} {m}: {e}"
                );
            }
        }
    }
}
