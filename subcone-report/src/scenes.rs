//! The scenes a run reports on: the built-in paper scenes (and the quick
//! report's extras) as [`SceneJob`]s with their sizes, and the file-safe
//! names their files are written under.

use std::path::{Path, PathBuf};

use subcone_scene::builtin::PAPER_SCENES;
use subcone_scene::Scene;

use crate::key::SceneId;
use crate::setup;

/// Built-in scenes the quick report adds after the paper scenes: not from the
/// papers, cheap at the quick size. `glass` shows CTSS §5.3's semi-transparent
/// materials (CPU only: the wgpu backend lists it as skipped).
pub const QUICK_EXTRA_SCENES: [&str; 1] = ["glass"];

/// Scenes that could not be loaded: (name, reason).
pub type Unavailable = Vec<(String, String)>;

/// A scene to report on.
pub struct SceneJob {
    /// The argument it was loaded from.
    pub arg: String,
    /// Unique, file-name-safe name.
    pub name: SceneId,
    /// The scene.
    pub scene: Scene,
    /// Whether it is an SDF scene.
    pub sdf: bool,
    /// Timing size.
    pub timing_size: (u32, u32),
    /// Quality size.
    pub quality_size: (u32, u32),
}

/// Load the built-in paper scenes that exist ([`PAPER_SCENES`]), printing a
/// note for each name that does not load. Returns the loaded scenes and the
/// names that failed with the reason.
pub fn paper_scenes() -> (Vec<(String, Scene)>, Unavailable) {
    let mut ok = Vec::new();
    let mut missing = Vec::new();
    for name in PAPER_SCENES {
        match setup::scene(name) {
            Ok(s) => ok.push((name.to_string(), s)),
            Err(e) => {
                eprintln!("note: scene {name} is not available, skipped: {e:#}");
                missing.push((name.to_string(), format!("{e:#}")));
            }
        }
    }
    (ok, missing)
}

/// A name safe for a file or directory: ASCII letters, digits, `-`, `_`, `.`.
pub fn file_safe(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    let s = s.trim_matches('.').to_string();
    if s.is_empty() {
        "scene".into()
    } else {
        s
    }
}

/// The directory of a scene's images.
pub fn image_dir(out: &Path, scene: &str) -> PathBuf {
    out.join("images").join(file_safe(scene))
}
