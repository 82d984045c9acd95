//! `Backend::supports` plans exactly what `render` does on the wgpu backend:
//! for every built-in scene (and variants reaching every refusal) and every
//! method, `supports` refuses exactly what `render` refuses, for the same
//! reason. Fails, rather than skips, without an adapter when
//! `SUBCONE_REQUIRE_GPU` is set.

use glam::Vec3;
use subcone_kernels::passes::{SceneFeatures, MAX_LIGHTS};
use subcone_scene::builtin::{builtin, names};
use subcone_scene::{
    Backend, Light, Method, RenderError, RenderSettings, Scene, Unsupported, UnsupportedReason,
};
use subcone_wgpu::{gpu_required, WgpuBackend};

fn gpu() -> Option<WgpuBackend> {
    match WgpuBackend::new() {
        Ok(b) => Some(b),
        Err(e) if !gpu_required() => {
            eprintln!("SKIPPED: no adapter and SUBCONE_REQUIRE_GPU unset: {e}");
            None
        }
        Err(e) => panic!("SUBCONE_REQUIRE_GPU is set but: {e}"),
    }
}

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
    let Some(gpu) = gpu() else { return };
    let refusals = check_plan_matches_render(&gpu);
    use UnsupportedReason as R;
    assert!(refused(&refusals, |r| matches!(r, R::Technique(_))));
    assert!(refused(&refusals, |r| *r == subcone_wgpu::sdf::SRAA_RT_CPU_ONLY));
    assert!(refused(&refusals, |r| *r == subcone_wgpu::sdf::CTSS_EDGES_CPU_ONLY));
    assert!(refused(&refusals, |r| matches!(
        r,
        R::TooManyLights { lights: 9, max: 8 }
    )));
    assert!(refused(&refusals, |r| *r == R::SdfReflections));
    assert!(refused(&refusals, |r| *r == R::MaterialGateOnSdf));
    assert!(refused(&refusals, |r| matches!(r, R::Translucency { .. })));
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
        for m in METHODS {
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
    let method = Method::ssaa(subcone_wgpu::sdf::MAX_SIDE_SAMPLES + 1);
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
