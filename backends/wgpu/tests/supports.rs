//! `Backend::supports` plans exactly what `render` does on the wgpu backend:
//! for every built-in scene (and variants reaching every refusal) and every
//! method, `supports` refuses exactly what `render` refuses, for the same
//! reason. Fails, rather than skips, without an adapter when
//! `SUBCONE_REQUIRE_GPU` is set.

use subcone_scene::builtin::{builtin, names};
use subcone_scene::conformance::plan_matches_render;
use subcone_scene::method::METHOD_NAMES;
use subcone_scene::{Backend, Method, RenderError, RenderSettings, UnsupportedReason};
use subcone_wgpu::test_util::gpu_or_skip;
use subcone_wgpu::WgpuBackend;

fn gpu() -> Option<WgpuBackend> {
    gpu_or_skip("supports")
}

#[test]
fn supports_predicts_every_refusal_of_render() {
    let Some(gpu) = gpu() else { return };
    let check = plan_matches_render(&gpu).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "{} renders planned and done, {} refusals planned and made",
        check.rendered,
        check.refusals.len()
    );
    use UnsupportedReason as R;
    assert!(check.refused(|r| matches!(r, R::Technique(_))));
    assert!(check.refused(|r| *r == subcone_wgpu::sdf::SRAA_RT_CPU_ONLY));
    assert!(check.refused(|r| *r == subcone_wgpu::sdf::CTSS_EDGES_CPU_ONLY));
    assert!(check.refused(|r| matches!(r, R::TooManyLights { lights: 9, max: 8 })));
    assert!(check.refused(|r| *r == R::SdfReflections));
    assert!(check.refused(|r| *r == R::MaterialGateOnSdf));
    assert!(check.refused(|r| matches!(r, R::Translucency { .. })));
}

/// The CPU-only refusals say so, and every method the wgpu backend refuses on
/// an opaque built-in scene is one the CPU reference renders there, unless
/// the technique itself does not apply.
#[test]
fn cpu_only_refusals_are_rendered_by_the_cpu() {
    let Some(gpu) = gpu() else { return };
    let cpu = subcone_cpu::CpuBackend::new();
    for name in names() {
        let scene = builtin(name).unwrap();
        for m in METHOD_NAMES {
            let method: Method = m.parse().unwrap();
            let Err(u) = gpu.supports(&scene, &method) else {
                continue;
            };
            if let UnsupportedReason::CpuOnly { .. } = u.reason {
                assert!(u.to_string().contains("CPU backend only"), "{u}");
                assert_eq!(cpu.supports(&scene, &method), Ok(()), "{u}");
            }
            if let UnsupportedReason::Technique(_) = u.reason {
                let c = cpu.supports(&scene, &method).unwrap_err();
                assert_eq!(c.reason, u.reason, "{name} {m}");
            }
        }
    }
}

/// A sample grid over the per-invocation limit is planned as refused, and
/// `render` refuses it the same way (without tracing anything).
#[test]
fn too_many_samples_per_side_are_refused() {
    let Some(gpu) = gpu() else { return };
    let scene = builtin("primitives").unwrap();
    let method = Method::ssaa_grid(subcone_wgpu::sdf::MAX_SIDE_SAMPLES + 1);
    let planned = gpu.supports(&scene, &method).unwrap_err();
    assert_eq!(
        planned.reason,
        UnsupportedReason::TooManySamples {
            side: subcone_wgpu::sdf::MAX_SIDE_SAMPLES + 1,
            max: subcone_wgpu::sdf::MAX_SIDE_SAMPLES
        }
    );
    match gpu.render(&scene, &scene.camera, &method, &RenderSettings::new(8, 8)) {
        Err(RenderError::NotSupported(u)) => assert_eq!(u, planned),
        other => panic!("{:?}", other.map(|_| "a frame")),
    }
}
