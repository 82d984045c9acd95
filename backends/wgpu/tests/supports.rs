//! The wgpu backend's own refusals. That `supports` plans exactly what
//! `render` does, for every built-in scene (and variants reaching every
//! refusal) and every method, is the conformance suite's
//! (`tests/conformance.rs`, `supports_matches_render`); what is asserted here
//! is which refusals this backend makes and why. Fails, rather than skips,
//! without an adapter when `SUBCONE_REQUIRE_GPU` is set.

use subcone_conformance::plan_scenes;
use subcone_scene::backend::RASTER_PRIMARY;
use subcone_scene::builtin::{builtin, names};
use subcone_scene::method::METHOD_NAMES;
use subcone_scene::{Backend, Method, RenderError, RenderSettings, UnsupportedReason};
use subcone_wgpu::test_util::gpu_or_skip;
use subcone_wgpu::WgpuBackend;

fn gpu() -> Option<WgpuBackend> {
    gpu_or_skip("supports")
}

#[test]
fn refuses_what_it_lacks() {
    let Some(gpu) = gpu() else { return };
    let refusals: Vec<_> = plan_scenes()
        .iter()
        .flat_map(|scene| {
            let gpu = &gpu;
            METHOD_NAMES
                .iter()
                .filter_map(move |m| gpu.supports(scene, &m.parse().unwrap()).err())
        })
        .collect();
    let refused =
        |pred: &dyn Fn(&UnsupportedReason) -> bool| refusals.iter().any(|u| pred(&u.reason));
    use UnsupportedReason as R;
    assert!(refused(&|r| matches!(r, R::Technique(_))));
    // SRAA-RT on SDF scenes renders here too: nothing is CPU-only but the
    // hybrids' rasterised primary visibility (this backend's SRAA
    // rasterises its subsamples in its own prepass), refused on triangle
    // scenes.
    assert!(refusals.iter().all(|u| match &u.reason {
        R::CpuOnly { what, .. } => {
            *what == RASTER_PRIMARY && u.method.parse::<Method>().unwrap().is_hybrid()
        }
        _ => true,
    }));
    assert!(refused(
        &|r| matches!(r, R::CpuOnly { what, .. } if *what == RASTER_PRIMARY)
    ));
    assert_eq!(subcone_wgpu::CAPABILITIES.sdf_subpixel_geometry, Ok(()));
    assert!(refused(&|r| matches!(
        r,
        R::TooManyLights { lights: 9, max: 8 }
    )));
    assert!(refused(&|r| *r == R::SdfReflections));
    assert!(refused(&|r| *r == R::MaterialGateOnSdf));
    assert!(refused(&|r| matches!(r, R::Translucency { .. })));
}

/// The semi-transparent SDF scenes (CTSS §5.3) render on this backend with
/// exactly the methods the CPU backend renders them with, and are refused,
/// for the CPU's reason, with the others (the paths that do not carry
/// opacity); a semi-transparent triangle scene is refused as translucency,
/// never drawn opaque.
#[test]
fn semi_transparent_scenes_are_planned_as_on_the_cpu() {
    let Some(gpu) = gpu() else { return };
    let cpu = subcone_cpu::CpuBackend::new();
    let mut rendered = 0;
    for name in subcone_scene::builtin::TRANSPARENT_SCENES {
        let scene = builtin(name).unwrap();
        for m in METHOD_NAMES {
            let method = m.parse().unwrap();
            let (want, got) = (cpu.supports(&scene, &method), gpu.supports(&scene, &method));
            match (&want, &got) {
                (Ok(()), Ok(())) => rendered += 1,
                (Err(w), Err(g)) => assert_eq!(w.reason, g.reason, "{name} {m}: {g}"),
                _ => panic!("{name} {m}: cpu {want:?}, wgpu {got:?}"),
            }
        }
    }
    assert!(
        rendered >= 5,
        "only {rendered} semi-transparent cases render"
    );
    let triangles = plan_scenes()
        .into_iter()
        .find(|s| s.name == "cornell-translucent")
        .expect("a semi-transparent triangle scene");
    for m in METHOD_NAMES {
        let u = gpu
            .supports(&triangles, &m.parse().unwrap())
            .expect_err("wgpu refuses a semi-transparent triangle scene");
        assert!(
            matches!(
                u.reason,
                UnsupportedReason::Translucency { .. } | UnsupportedReason::Technique(_)
            ),
            "{m}: {u}"
        );
    }
}

/// Every method the wgpu backend refuses on an opaque built-in scene is one
/// the CPU reference refuses there too, for the same reason, when the
/// technique itself does not apply; no refusal is CPU-only but the hybrids'
/// (`-hybrid`, [`RASTER_PRIMARY`]), and those only on triangle scenes.
#[test]
fn no_refusal_is_cpu_only() {
    let Some(gpu) = gpu() else { return };
    let cpu = subcone_cpu::CpuBackend::new();
    for name in names() {
        let scene = builtin(name).unwrap();
        for m in METHOD_NAMES {
            let method: Method = m.parse().unwrap();
            let Err(u) = gpu.supports(&scene, &method) else {
                continue;
            };
            if let UnsupportedReason::CpuOnly { what, .. } = u.reason {
                assert!(
                    method.is_hybrid() && what == RASTER_PRIMARY && scene.sdf_geometry().is_none(),
                    "{name} {m}: {u}"
                );
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
