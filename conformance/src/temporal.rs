//! The temporal methods' cases (`taa`, `sraa-rt+taa`, `ctss+taa`): a still
//! camera converges, a reset recovers, and every frame of a moving sequence
//! matches the CPU backend's.

use glam::Quat;
use subcone_kernels::passes::Technique;
use subcone_scene::builtin::builtin;
use subcone_scene::temporal::{Taa, TaaConfig};
use subcone_scene::{Backend, Camera, Frame, Method, RenderSettings, Scene};

use crate::named::{NOAA, SSAA16};
use crate::{flip, save_failure, FRAME_TOLERANCE, H, REFERENCE_METHOD, W};

/// Frames of the still-camera case: one Halton (2, 3) cycle of 16 phases.
pub const STILL_FRAMES: u32 = 16;
/// How close to ssaa16's FLIP a still camera's TAA must come after
/// [`STILL_FRAMES`](crate::STILL_FRAMES) frames (issue acceptance: within 1.1×).
pub const STILL_RATIO: f64 = 1.1;
/// Frames after a cut within which TAA's error must be back below NoAA's.
pub const RESET_FRAMES: u32 = 4;
/// Frames of the sequences compared with the CPU backend's.
pub const SEQUENCE_FRAMES: u32 = 4;

/// The temporal methods and the scene each is compared on.
pub const TEMPORAL_CASES: [(Method, &str); 4] = [
    (Method::temporal(Technique::NoAa), "cornell"),
    (Method::temporal(Technique::SraaRt), "cornell"),
    (Method::temporal(Technique::NoAa), "primitives"),
    (Method::temporal(Technique::Ctss), "primitives"),
];

fn scene(name: &str) -> Scene {
    builtin(name).unwrap_or_else(|e| panic!("built-in scene {name}: {e}"))
}

fn render_one(backend: &dyn Backend, scene: &Scene, camera: &Camera, method: &Method) -> Frame {
    backend
        .render(scene, camera, method, &RenderSettings::new(W, H))
        .unwrap_or_else(|e| panic!("{}: {} {method}: {e}", backend.name(), scene.name))
}

/// `frames` frames of `method` through `cameras(t)` on `backend`.
fn sequence(
    backend: &dyn Backend,
    scene: &Scene,
    method: Method,
    frames: u32,
    camera: impl Fn(u32) -> Camera,
) -> Vec<Frame> {
    let mut taa = Taa::new(method, TaaConfig::default()).expect("temporal method");
    (0..frames)
        .map(|t| {
            taa.render(backend, scene, &camera(t), &RenderSettings::new(W, H))
                .unwrap_or_else(|e| {
                    panic!("{}: {} {method} frame {t}: {e}", backend.name(), scene.name)
                })
        })
        .collect()
}

/// `base` turned about its up axis by `t` steps of `step` radians.
fn panned(base: &Camera, t: u32, step: f32) -> Camera {
    let turn = Quat::from_axis_angle(base.up, t as f32 * step);
    Camera::look_at(
        base.position,
        base.position + turn * base.forward,
        base.up,
        base.fov_y,
    )
    .expect("panned camera")
}

/// A still camera: after [`STILL_FRAMES`](crate::STILL_FRAMES) frames, `taa` on cornell is within
/// [`STILL_RATIO`](crate::STILL_RATIO) of ssaa16's FLIP against the ssaa64 reference.
pub fn check_taa_still(backend: &dyn Backend) {
    let scene = scene("cornell");
    let reference = render_one(backend, &scene, &scene.camera, &REFERENCE_METHOD);
    let ssaa16 = flip(
        &reference,
        &render_one(backend, &scene, &scene.camera, &SSAA16),
    )
    .mean;
    let noaa = flip(
        &reference,
        &render_one(backend, &scene, &scene.camera, &NOAA),
    )
    .mean;
    let frames = sequence(
        backend,
        &scene,
        Method::temporal(Technique::NoAa),
        STILL_FRAMES,
        |_| scene.camera,
    );
    let errors: Vec<f64> = frames.iter().map(|f| flip(&reference, f).mean).collect();
    let last = errors[errors.len() - 1];
    println!(
        "{}: cornell taa still, FLIP per frame {errors:.4?}; ssaa16 {ssaa16:.4}, noaa {noaa:.4}",
        backend.name()
    );
    assert!(
        last <= STILL_RATIO * ssaa16,
        "{}: taa after {STILL_FRAMES} still frames: FLIP {last:.5}, above {STILL_RATIO} × ssaa16's {ssaa16:.5}",
        backend.name()
    );
}

/// A cut: a sequence panning over cornell, then a reset to a camera turned
/// away by a quarter of the field of view; within [`RESET_FRAMES`](crate::RESET_FRAMES) frames
/// the error against the new view's reference is below NoAA's there.
pub fn check_taa_reset(backend: &dyn Backend) {
    let scene = scene("cornell");
    let base = scene.camera;
    let step = base.fov_y / H as f32 * 0.37;
    let method = Method::temporal(Technique::NoAa);
    let mut taa = Taa::new(method, TaaConfig::default()).expect("temporal method");
    let settings = RenderSettings::new(W, H);
    for t in 0..6 {
        taa.render(backend, &scene, &panned(&base, t, step), &settings)
            .unwrap_or_else(|e| panic!("{}: taa frame {t}: {e}", backend.name()));
    }
    let cut = panned(&base, 1, base.fov_y * 0.25);
    taa.reset();
    let reference = render_one(backend, &scene, &cut, &REFERENCE_METHOD);
    let noaa = flip(&reference, &render_one(backend, &scene, &cut, &NOAA)).mean;
    let mut errors = Vec::new();
    for t in 0..RESET_FRAMES {
        let f = taa
            .render(backend, &scene, &cut, &settings)
            .unwrap_or_else(|e| panic!("{}: taa frame {t} after the cut: {e}", backend.name()));
        errors.push(flip(&reference, &f).mean);
    }
    println!(
        "{}: cornell taa after a cut, FLIP per frame {errors:.4?}; noaa {noaa:.4}",
        backend.name()
    );
    assert!(
        errors.iter().any(|&e| e < noaa),
        "{}: taa {RESET_FRAMES} frames after a cut: FLIP {errors:.5?}, none below noaa's {noaa:.5}",
        backend.name()
    );
}

/// Every frame of each of [`TEMPORAL_CASES`](crate::TEMPORAL_CASES) over a panning camera matches
/// the CPU backend's within [`FRAME_TOLERANCE`] (for the CPU backend itself
/// there is nothing to compare).
pub fn check_temporal_matches_cpu(backend: &dyn Backend) {
    let cpu = subcone_cpu::CpuBackend::new();
    if backend.name() == cpu.name() {
        println!("cpu: the temporal sequences are the cpu's own");
        return;
    }
    let mut failures = Vec::new();
    for (method, name) in TEMPORAL_CASES {
        let scene = scene(name);
        let base = scene.camera;
        let step = base.fov_y / H as f32 * 0.37;
        let cam = |t| panned(&base, t, step);
        let expected = sequence(&cpu, &scene, method, SEQUENCE_FRAMES, cam);
        let actual = sequence(backend, &scene, method, SEQUENCE_FRAMES, cam);
        for (t, (e, a)) in expected.iter().zip(&actual).enumerate() {
            let f = flip(e, a);
            let tol = FRAME_TOLERANCE;
            println!(
                "{:>5} {name:>12} {method:>12} frame {t}: vs cpu FLIP mean {:.5}, p99 {:.4}",
                backend.name(),
                f.mean,
                f.p99()
            );
            if f.mean > tol.mean || f.p99() > tol.p99 {
                let what = format!("{method}-frame{t}");
                let stem = save_failure(backend.name(), name, &what, "cpu", e, a, &f);
                failures.push(format!(
                    "{name} {method} frame {t}: FLIP mean {:.5} (limit {}), p99 {:.4} (limit {}); images in {stem}-*.png",
                    f.mean, tol.mean, f.p99(), tol.p99
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} temporal frames differ from the cpu's:\n{}",
        backend.name(),
        failures.join("\n")
    );
}
