//! The CPU backend's own refusals. That `supports` plans exactly what
//! `render` does, for every built-in scene (and variants reaching every
//! refusal) and every method, is the conformance suite's
//! (`tests/conformance.rs`, `supports_matches_render`); what is asserted here
//! is which refusals the CPU backend makes, and that they are the reference's:
//! few, and never "CPU backend only".

use subcone_conformance::plan_scenes;
use subcone_cpu::CpuBackend;
use subcone_kernels::passes::Passes;
use subcone_scene::builtin::{builtin, names};
use subcone_scene::method::METHOD_NAMES;
use subcone_scene::{Backend, Method, RenderError, RenderSettings, UnsupportedReason};

#[test]
fn refuses_only_what_the_reference_cannot_render() {
    let cpu = CpuBackend::new();
    let refusals: Vec<_> = plan_scenes()
        .iter()
        .flat_map(|scene| {
            let cpu = &cpu;
            METHOD_NAMES
                .iter()
                .filter_map(move |m| cpu.supports(scene, &m.parse().unwrap()).err())
        })
        .collect();
    let refused =
        |pred: &dyn Fn(&UnsupportedReason) -> bool| refusals.iter().any(|u| pred(&u.reason));
    use UnsupportedReason as R;
    assert!(refused(&|r| matches!(r, R::Technique(_))));
    assert!(refused(&|r| matches!(
        r,
        R::TooManyLights { lights: 9, max: 8 }
    )));
    assert!(refused(&|r| *r == R::SdfReflections));
    assert!(refused(&|r| *r == R::MaterialGateOnSdf));
    assert!(refused(&|r| matches!(r, R::Translucency { .. })));
    // The CPU is the reference: it renders every method somewhere, and
    // nothing is CPU-only for it.
    assert!(!refused(&|r| matches!(r, R::CpuOnly { .. })));
    for m in METHOD_NAMES {
        let method: Method = m.parse().unwrap();
        assert!(
            names().any(|n| cpu.supports(&builtin(n).unwrap(), &method).is_ok()),
            "the cpu backend renders {m} on no built-in scene"
        );
    }
}

/// The refusals of `glass`: the paths that carry opacity render it, the
/// others say what does.
#[test]
fn translucency_refusals_name_what_renders_instead() {
    let glass = builtin("glass").unwrap();
    let cpu = CpuBackend::new();
    for m in ["noaa", "ssaa4", "ctss", "ctss-r", "ssaa4+ctss", "fxaa"] {
        assert_eq!(cpu.supports(&glass, &m.parse().unwrap()), Ok(()), "{m}");
    }
    for (m, what) in [
        ("sraa-rt", "sraa-rt"),
        ("ctss-delayed", "delayed shading"),
        ("ctss+edges", "hit group subdivision (ctss+edges)"),
    ] {
        let u = cpu.supports(&glass, &m.parse().unwrap()).unwrap_err();
        assert!(
            matches!(&u.reason, UnsupportedReason::Translucency { what: w, .. } if w == what),
            "{m}: {u:?}"
        );
        let text = u.to_string();
        assert!(
            text.contains("semi-transparent") && text.contains("ctss, ctss-r"),
            "{text}"
        );
    }
}

/// Forced passes are settings, not a plan: `supports` accepts the scene, and
/// `render` refuses the forced secondary passes on an SDF scene as it would
/// refuse mirrors.
#[test]
fn forced_secondary_passes_on_sdf_are_refused_by_render() {
    let scene = builtin("primitives").unwrap();
    let method: Method = "noaa".parse().unwrap();
    let cpu = CpuBackend::new();
    assert_eq!(cpu.supports(&scene, &method), Ok(()));
    let settings = RenderSettings {
        force_passes: Passes::SECONDARY,
        ..RenderSettings::new(8, 8)
    };
    match cpu.render(&scene, &scene.camera, &method, &settings) {
        Err(RenderError::NotSupported(u)) => {
            assert_eq!(u.reason, UnsupportedReason::SdfReflections)
        }
        other => panic!("{:?}", other.map(|_| "a frame")),
    }
}
