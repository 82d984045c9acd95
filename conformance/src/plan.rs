//! The support plan against the renders: every backend's
//! [`Backend::supports`] must answer what its [`Backend::render`] does.
//!
//! ```no_run
//! /// In a backend's tests: `supports` and `render` agree everywhere.
//! fn plan_agrees(backend: &dyn subcone_scene::Backend) {
//!     let check = subcone_conformance::plan_matches_render(backend)
//!         .unwrap_or_else(|disagreements| panic!("{disagreements}"));
//!     println!("{} renders, {} refusals", check.rendered, check.refusals.len());
//! }
//! ```

use glam::Vec3;
use subcone_kernels::passes::{SceneFeatures, MAX_LIGHTS};
use subcone_scene::backend::{Backend, RenderSettings, Unsupported};
use subcone_scene::builtin::{builtin, names};
use subcone_scene::error::RenderError;
use subcone_scene::light::Light;
use subcone_scene::method::{Method, METHOD_NAMES};
use subcone_scene::scene::Scene;

/// Every built-in scene, and variants of them that reach the refusals no
/// built-in scene reaches: too many lights (on triangles and on an SDF),
/// semi-transparent triangles, mirrors in an SDF scene.
pub fn plan_scenes() -> Vec<Scene> {
    let mut scenes: Vec<Scene> = names().filter_map(|n| builtin(n).ok()).collect();
    for base in ["cornell", "primitives"] {
        let Ok(mut s) = builtin(base) else { continue };
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
    if let Ok(mut s) = builtin("cornell") {
        s.materials[0].alpha = 0.5;
        s.name = "cornell-translucent".into();
        s.touch();
        scenes.push(s);
    }
    if let Ok(mut s) = builtin("primitives") {
        for m in &mut s.materials {
            m.mirror = 0.5;
        }
        s.name = "primitives-mirror".into();
        s.touch();
        debug_assert!(s.features().contains(SceneFeatures::HAS_REFLECTIONS));
        scenes.push(s);
    }
    scenes
}

/// What [`plan_matches_render`] saw.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanCheck {
    /// Combinations planned as supported and rendered.
    pub rendered: usize,
    /// Refusals planned by `supports` and made by `render`, alike.
    pub refusals: Vec<Unsupported>,
}

impl PlanCheck {
    /// Whether some refusal has a reason matching `pred`.
    pub fn refused(&self, pred: impl Fn(&crate::UnsupportedReason) -> bool) -> bool {
        self.refusals.iter().any(|u| pred(&u.reason))
    }
}

/// [`Backend::supports`] against an 8×8 [`Backend::render`] of every
/// [`plan_scenes`] scene with every [`METHOD_NAMES`] method: both refuse with
/// the same [`Unsupported`], or neither does and the render succeeds. Errs
/// with every disagreement, one per line (including renders that failed for
/// another reason).
pub fn plan_matches_render(backend: &dyn Backend) -> Result<PlanCheck, String> {
    let settings = RenderSettings::new(8, 8);
    let mut check = PlanCheck {
        rendered: 0,
        refusals: Vec::new(),
    };
    let mut disagreements = Vec::new();
    for scene in plan_scenes() {
        for m in METHOD_NAMES {
            let Ok(method) = m.parse::<Method>() else {
                disagreements.push(format!("{m} does not parse"));
                continue;
            };
            let plan = backend.supports(&scene, &method);
            let frame = backend.render(&scene, &scene.camera, &method, &settings);
            let what = format!("{} {} {m}", backend.name(), scene.name);
            match (plan, frame) {
                (Ok(()), Ok(_)) => check.rendered += 1,
                (Err(planned), Err(RenderError::NotSupported(refused))) => {
                    if planned == refused {
                        check.refusals.push(planned);
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
    if disagreements.is_empty() {
        Ok(check)
    } else {
        Err(format!(
            "supports and render disagree:\n{}",
            disagreements.join("\n")
        ))
    }
}
