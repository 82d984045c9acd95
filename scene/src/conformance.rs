//! Checks of the [`Backend`] contract that every backend runs in its own
//! tests, so that they are written once, beside the contract.
//!
//! ```no_run
//! /// In a backend's tests: `supports` and `render` agree everywhere.
//! fn plan_agrees(backend: &dyn subcone_scene::Backend) {
//!     let check = subcone_scene::conformance::plan_matches_render(backend)
//!         .unwrap_or_else(|disagreements| panic!("{disagreements}"));
//!     println!("{} renders, {} refusals", check.rendered, check.refusals.len());
//! }
//! ```

use glam::Vec3;
use subcone_kernels::passes::{SceneFeatures, MAX_LIGHTS};

use crate::backend::{Backend, RenderSettings, Unsupported};
use crate::builtin::{builtin, names};
use crate::error::RenderError;
use crate::light::Light;
use crate::method::{Method, METHOD_NAMES};
use crate::scene::Scene;

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

/// Whether a GPU is required: `SUBCONE_REQUIRE_GPU` set to anything but `0`
/// or empty, as CI sets it. GPU tests then fail instead of skipping when no
/// adapter exists: a GPU test must never pass by skipping where a GPU is
/// expected. The one reading of the variable, for every crate's tests.
pub fn gpu_required() -> bool {
    std::env::var("SUBCONE_REQUIRE_GPU").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// What a GPU test opened (`opened`), or `None` when it could not be opened
/// and no GPU is required ([`gpu_required`]): the test then skips, printing
/// one line, `skipped: <test>: no GPU adapter (<what>: <why>)`
/// ([`print_skipped`]), so machines without a GPU still run the rest and a
/// reader can count what checked nothing. Panics, naming `what` and the
/// error, when a GPU is required.
///
/// ```
/// use subcone_scene::conformance::or_skip;
///
/// let opened: Result<u32, &str> = Err("no adapter");
/// if !subcone_scene::conformance::gpu_required() {
///     assert_eq!(or_skip("an example", opened), None);
/// }
/// assert_eq!(or_skip("an example", Ok::<_, &str>(7)), Some(7));
/// ```
pub fn or_skip<T, E: std::fmt::Display>(what: &str, opened: Result<T, E>) -> Option<T> {
    match opened {
        Ok(t) => Some(t),
        Err(e) if !gpu_required() => {
            print_skipped(SKIP_NO_GPU, &format!("{what}: {e}"));
            None
        }
        Err(e) => panic!("{what}: no GPU adapter, and SUBCONE_REQUIRE_GPU is set: {e}"),
    }
}

/// The reason a test skips without a GPU adapter, as [`print_skipped`]
/// prints it (and as `.ci/run` counts it).
pub const SKIP_NO_GPU: &str = "no GPU adapter";

/// The reason a test skips without a browser, as [`print_skipped`] prints it.
pub const SKIP_NO_BROWSER: &str = "no browser";

/// Print the one line of a test that skips for want of a resource:
/// `skipped: <test>: <reason> (<detail>)`, where `<test>` is the running
/// test's name (libtest names each test's thread after it; `detail` alone
/// outside a test).
///
/// The line goes straight to the process's standard error, past the test
/// harness's capture, so that `cargo test` shows it even for a test that
/// passes: "470 passed" must not hide the tests that checked nothing.
/// `.ci/run` counts these lines after the README's test command.
pub fn print_skipped(reason: &str, detail: &str) {
    use std::io::Write;
    let thread = std::thread::current();
    let test = match thread.name() {
        Some(name) if name != "main" => name,
        _ => "(outside a test)",
    };
    let line = format!("skipped: {test}: {reason} ({detail})\n");
    // One write of the whole line, so that lines of parallel tests do not
    // interleave; nothing to do if standard error is gone.
    let _ = std::io::stderr().lock().write_all(line.as_bytes());
}
