//! The wgpu backend on SDF scenes against the CPU reference: every method
//! renders the same images (up to GPU rounding) on every paper and stiff
//! scene. The generated field and the kernels' WGSL twins are checked value by
//! value in the kernel conformance suite (`tests/conformance_kernels.rs`).

use std::time::Instant;

use subcone_cpu::CpuBackend;
use subcone_scene::builtin::builtin;
use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
use subcone_scene::{Backend, Frame, Method, RenderSettings};
use subcone_wgpu::test_util::gpu_or_skip;
use subcone_wgpu::WgpuBackend;

/// The backend, or `None` when the test may skip (see [`gpu_or_skip`]).
fn gpu() -> Option<WgpuBackend> {
    gpu_or_skip("sdf")
}

/// Mean absolute error over all channels, and the fraction of pixels whose
/// largest channel differs by more than 0.05.
fn compare(a: &Frame, b: &Frame) -> (f32, f32) {
    let mut sum = 0.0f64;
    let mut bad = 0;
    for (x, y) in a.color.iter().zip(&b.color) {
        let d = (*x - *y).abs();
        sum += (d.x + d.y + d.z) as f64;
        if d.max_element() > 0.05 {
            bad += 1;
        }
    }
    let n = a.color.len();
    ((sum / (3 * n) as f64) as f32, bad as f32 / n as f32)
}

const METHODS: [&str; 9] = [
    "noaa",
    "ssaa4",
    "sraa-rt",
    "sraa-rt-paper",
    "ctss",
    "ctss-paper",
    "ctss+edges",
    "ctss-r",
    "ssaa4+ctss",
];

/// Thresholds: sphere and cone tracing decide hits by comparisons of f32
/// values that the GPU computes within a few ulps of the CPU; a flipped
/// decision changes a silhouette or shadow pixel, nothing else. On lavapipe
/// every scene and method agrees to the last printed digit (mean < 5e-6, no
/// pixel off); other GPUs round differently, so the bounds leave room for a
/// few flipped pixels: mean absolute error ≤ 0.002 and ≤ 1 % of pixels off by
/// more than 0.05 (64×48: ≤ 30 pixels).
const MAX_MEAN: f32 = 0.002;
const MAX_BAD: f32 = 0.01;

fn agree(names: &[&str], w: u32, h: u32) {
    agree_with(names, &METHODS, w, h, 0);
}

/// [`agree`] on `methods`, with `ao` ambient-occlusion rays per shaded point.
fn agree_with(names: &[&str], methods: &[&str], w: u32, h: u32, ao: u32) {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    for name in names {
        let scene = builtin(name).unwrap();
        for &m in methods {
            let method: Method = m.parse().unwrap();
            // What the reference refuses on a scene (`ctss+edges` on the
            // semi-transparent ones) the GPU refuses too.
            if let Err(planned) = cpu.supports(&scene, &method) {
                assert!(
                    gpu.supports(&scene, &method).is_err(),
                    "{name} {m}: the CPU refuses it ({planned}), the GPU plans it"
                );
                continue;
            }
            let mut s = RenderSettings::new(w, h);
            s.aovs = true;
            s.ao_rays = ao;
            let t0 = Instant::now();
            let want = cpu.render(&scene, &scene.camera, &method, &s).unwrap();
            let t1 = Instant::now();
            let got = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
            let t2 = Instant::now();
            assert!(
                got.color.iter().all(|c| c.is_finite()),
                "{name} {m}: non-finite pixels"
            );
            let (mean, bad) = compare(&want, &got);
            eprintln!(
                "{name:>13} {m:>10}: mean {mean:.1e} bad {:.2}% | cpu {:.2?} gpu {:.2?} (pass {:.2?}) | samples {} vs {}, evals {} vs {}, multi {} vs {}",
                bad * 100.0,
                t1 - t0,
                t2 - t1,
                got.stats.total_time(),
                want.stats.shaded_samples,
                got.stats.shaded_samples,
                want.stats.sdf_evaluations,
                got.stats.sdf_evaluations,
                want.stats.multi_sample_pixels,
                got.stats.multi_sample_pixels,
            );
            assert!(
                mean <= MAX_MEAN && bad <= MAX_BAD,
                "{name} {m}: mean abs error {mean}, {:.2}% pixels off by > 0.05",
                bad * 100.0
            );
            // Work counters agree within 1 % (the same flipped decisions).
            let close =
                |a: u64, b: u64| (a as f64 - b as f64).abs() <= 0.01 * a.max(b) as f64 + 8.0;
            assert!(
                close(want.stats.sdf_evaluations, got.stats.sdf_evaluations),
                "{name} {m}: evaluations {} vs {}",
                want.stats.sdf_evaluations,
                got.stats.sdf_evaluations
            );
            assert!(
                close(want.stats.shaded_samples, got.stats.shaded_samples),
                "{name} {m}: samples {} vs {}",
                want.stats.shaded_samples,
                got.stats.shaded_samples
            );
            assert!(
                close(want.stats.rays.ao, got.stats.rays.ao),
                "{name} {m}: occlusion rays {} vs {}",
                want.stats.rays.ao,
                got.stats.rays.ao
            );
            assert_eq!(ao > 0, got.stats.rays.ao > 0, "{name} {m}: occlusion rays");
            assert_eq!(want.stats.passes, got.stats.passes);
            assert_eq!(want.stats.rays.primary, got.stats.rays.primary);
            assert_eq!(want.stats.rays.geometry, got.stats.rays.geometry);
            let names = |f: &Frame| f.stats.timings.iter().map(|t| t.name).collect::<Vec<_>>();
            assert_eq!(names(&want), names(&got), "{name} {m}: passes timed");
            // AOVs: hits agree on ≥ 98 % of pixels, normals of agreeing hits within 0.05.
            let (dw, dg) = (want.depth.as_ref().unwrap(), got.depth.as_ref().unwrap());
            let (nw, ng) = (want.normal.as_ref().unwrap(), got.normal.as_ref().unwrap());
            let mut same = 0;
            for i in 0..dw.len() {
                if dw[i].is_finite() == dg[i].is_finite() {
                    same += 1;
                    if dw[i].is_finite() && (dw[i] - dg[i]).abs() < 1e-3 * dw[i].abs().max(1.0) {
                        assert!((nw[i] - ng[i]).length() < 0.05, "{name} {m}: normal {i}");
                    }
                }
            }
            assert!(same * 50 >= dw.len() * 49, "{name} {m}: depth hits differ");
            assert_eq!(
                got.samples_per_pixel.as_ref().unwrap().len(),
                (w * h) as usize
            );
        }
    }
}

#[test]
fn paper_scenes_match_the_cpu() {
    agree(&SDF_SCENES, 64, 48);
}

/// Ambient occlusion on SDF scenes (4 rays per shaded point) against the
/// CPU, with the thresholds of [`agree`] (occlusion rays are sphere traced as
/// shadow rays are: the same flipped decisions, no others).
#[test]
fn ambient_occlusion_matches_the_cpu() {
    agree_with(
        &["primitives", "sdf-atrium"],
        &["noaa", "sraa-rt", "ctss", "ctss-r"],
        64,
        48,
        4,
    );
}

#[test]
fn stiff_scenes_are_finite_and_match_the_cpu() {
    agree(&STIFF_SCENES, 64, 48);
}

/// The semi-transparent scenes (`glass`: CTSS §5.3's K masks for the cone
/// methods, alpha blending along the ray for NoAA and SSAA), within the
/// same bounds as the opaque ones.
#[test]
fn semi_transparent_scenes_match_the_cpu() {
    agree(&TRANSPARENT_SCENES, 64, 48);
}

/// Only what the scene needs is built: no shadow rays without lights, and
/// the same image with shadows forced on a scene without lights.
#[test]
fn no_shadow_work_without_lights() {
    let Some(gpu) = gpu() else { return };
    let scene = builtin("thin").unwrap();
    assert!(scene.lights.is_empty());
    let method: Method = "ctss".parse().unwrap();
    let s = RenderSettings::new(32, 24);
    let f = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
    assert_eq!(f.stats.rays.shadow, 0);
    assert!(!f
        .stats
        .passes
        .contains(subcone_kernels::passes::Passes::SHADOW));
    let lit = builtin("primitives").unwrap();
    let f = gpu.render(&lit, &lit.camera, &method, &s).unwrap();
    assert!(f.stats.rays.shadow > 0);
}

/// Bad input is an error, not a panic or a hang.
#[test]
fn bad_input_is_an_error() {
    let Some(gpu) = gpu() else { return };
    let scene = builtin("primitives").unwrap();
    let method: Method = "ctss".parse().unwrap();
    assert!(gpu
        .render(&scene, &scene.camera, &method, &RenderSettings::new(0, 10))
        .is_err());
    let mut s = RenderSettings::new(16, 16);
    s.max_distance = Some(f32::NAN);
    assert!(gpu.render(&scene, &scene.camera, &method, &s).is_err());
    let sraa: Method = "sraa".parse().unwrap();
    assert!(gpu.render(&scene, &scene.camera, &sraa, &s).is_err());
    s.max_distance = Some(f32::INFINITY);
    assert!(gpu.render(&scene, &scene.camera, &method, &s).is_err());
    // A step budget of one, or a huge distance, still ends, with finite pixels.
    for (steps, dist) in [(1, 100.0), (100_000, 1e30)] {
        let mut s = RenderSettings::new(16, 16);
        s.max_steps = Some(steps);
        s.max_distance = Some(dist);
        for m in METHODS {
            let f = gpu
                .render(&scene, &scene.camera, &m.parse().unwrap(), &s)
                .unwrap();
            assert!(f.color.iter().all(|c| c.is_finite()), "{m}");
        }
    }
}

/// Pipelines are cached per device: a second device renders the same image,
/// and a scene changed in place (its lights) is compiled anew.
#[test]
fn pipelines_follow_the_device_and_the_scene() {
    let Some(gpu) = gpu() else { return };
    let other = WgpuBackend::with_context(std::sync::Arc::new(
        subcone_wgpu::GpuContext::new().unwrap(),
    ));
    let mut scene = builtin("sparse-shape").unwrap();
    let method: Method = "ctss".parse().unwrap();
    let s = RenderSettings::new(32, 24);
    let a = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
    let b = other.render(&scene, &scene.camera, &method, &s).unwrap();
    assert_eq!(a.color, b.color);
    for l in scene.lights.iter_mut() {
        if let subcone_scene::Light::Directional { irradiance, .. } = l {
            *irradiance *= 0.25;
        }
    }
    let c = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
    let want = CpuBackend::new()
        .render(&scene, &scene.camera, &method, &s)
        .unwrap();
    assert_ne!(a.color, c.color);
    let (mean, _) = compare(&want, &c);
    assert!(mean < 1e-4, "{mean}");
}
