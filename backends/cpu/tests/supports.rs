//! `Backend::supports` plans exactly what `render` does: for every built-in
//! scene (and variants reaching every refusal) and every method, the CPU
//! backend refuses in `supports` exactly what `render` refuses, for the same
//! reason.

use glam::Vec3;
use subcone_cpu::CpuBackend;
use subcone_kernels::passes::{Passes, SceneFeatures, MAX_LIGHTS};
use subcone_scene::builtin::{builtin, names};
use subcone_scene::{
    Backend, Light, Method, RenderError, RenderSettings, Scene, Unsupported, UnsupportedReason,
};

/// The method names the plan is checked with.
const METHODS: [&str; 13] = [
    "noaa",
    "ssaa4",
    "ssaa16",
    "sraa",
    "sraa-rt",
    "sraa+mat",
    "sraa-rt+mat",
    "ctss",
    "ctss-delayed",
    "ctss+edges",
    "ctss-r",
    "ssaa4+ctss",
    "fxaa",
];

/// Every built-in scene, and variants of them that reach the refusals no
/// built-in scene reaches: too many lights (on triangles and on an SDF),
/// semi-transparent triangles, mirrors in an SDF scene.
fn scenes() -> Vec<Scene> {
    let mut scenes: Vec<Scene> = names()
        .map(|n| builtin(n).unwrap_or_else(|e| panic!("{n}: {e}")))
        .collect();
    for base in ["cornell", "primitives"] {
        let mut s = builtin(base).unwrap();
        while s.lights.len() <= MAX_LIGHTS {
            s.lights.push(Light::Point {
                position: Vec3::new(0.0, 1.5, 0.5 + s.lights.len() as f32 * 0.1),
                intensity: Vec3::splat(0.2),
            });
        }
        s.name = format!("{base}-{}-lights", s.lights.len());
        s.touch();
        scenes.push(s);
    }
    let mut s = builtin("cornell").unwrap();
    s.materials[0].alpha = 0.5;
    s.name = "cornell-translucent".into();
    s.touch();
    scenes.push(s);
    let mut s = builtin("primitives").unwrap();
    for m in &mut s.materials {
        m.mirror = 0.5;
    }
    s.name = "primitives-mirror".into();
    s.touch();
    assert!(s.features().contains(SceneFeatures::HAS_REFLECTIONS));
    scenes.push(s);
    scenes
}

/// `supports` against an 8×8 `render` of every scene with every method:
/// refused by both with the same [`Unsupported`], or by neither. Returns the
/// refusals seen; panics listing every disagreement.
fn check_plan_matches_render(backend: &dyn Backend) -> Vec<Unsupported> {
    let settings = RenderSettings::new(8, 8);
    let mut refusals = Vec::new();
    let mut disagreements = Vec::new();
    let mut rendered = 0;
    for scene in scenes() {
        for m in METHODS {
            let method: Method = m.parse().expect("method name");
            let plan = backend.supports(&scene, &method);
            let frame = backend.render(&scene, &scene.camera, &method, &settings);
            let what = format!("{} {} {m}", backend.name(), scene.name);
            match (plan, frame) {
                (Ok(()), Ok(_)) => rendered += 1,
                (Err(planned), Err(RenderError::NotSupported(refused))) => {
                    if planned == refused {
                        refusals.push(planned);
                    } else {
                        disagreements.push(format!(
                            "{what}: planned {planned:?}, render refused with {refused:?}"
                        ));
                    }
                }
                (Err(planned), Ok(_)) => {
                    disagreements.push(format!("{what}: planned refusal ({planned}) but rendered"))
                }
                (Ok(()), Err(RenderError::NotSupported(refused))) => {
                    disagreements.push(format!("{what}: planned but render refused it: {refused}"))
                }
                (_, Err(e)) => disagreements.push(format!("{what}: render failed: {e}")),
            }
        }
    }
    assert!(
        disagreements.is_empty(),
        "supports and render disagree:\n{}",
        disagreements.join("\n")
    );
    println!(
        "{}: {rendered} renders planned and done, {} refusals planned and made",
        backend.name(),
        refusals.len()
    );
    refusals
}

/// Whether some refusal has a reason matching `pred`.
fn refused(refusals: &[Unsupported], pred: impl Fn(&UnsupportedReason) -> bool) -> bool {
    refusals.iter().any(|u| pred(&u.reason))
}

#[test]
fn supports_predicts_every_refusal_of_render() {
    let refusals = check_plan_matches_render(&CpuBackend::new());
    use UnsupportedReason as R;
    assert!(refused(&refusals, |r| matches!(r, R::Technique(_))));
    assert!(refused(&refusals, |r| matches!(
        r,
        R::TooManyLights { lights: 9, max: 8 }
    )));
    assert!(refused(&refusals, |r| *r == R::SdfReflections));
    assert!(refused(&refusals, |r| *r == R::MaterialGateOnSdf));
    assert!(refused(&refusals, |r| matches!(r, R::Translucency { .. })));
    // The CPU is the reference: it renders every method somewhere, and
    // nothing is CPU-only for it.
    assert!(!refused(&refusals, |r| matches!(r, R::CpuOnly { .. })));
    for m in METHODS {
        let method: Method = m.parse().unwrap();
        assert!(
            names().any(|n| CpuBackend::new()
                .supports(&builtin(n).unwrap(), &method)
                .is_ok()),
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
            matches!(u.reason, UnsupportedReason::Translucency { what: w, .. } if w == what),
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
