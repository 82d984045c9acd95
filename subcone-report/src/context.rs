//! What the report files say about the run besides the rows: the
//! [`Context`] every writer (markdown, JSON, HTML, the answer) reads, and the
//! number formats they share.

use crate::{load, Mode};

/// What the report files say about the run besides the rows.
pub struct Context {
    /// Mode.
    pub mode: Mode,
    /// Backends.
    pub backends: Vec<String>,
    /// What each backend runs on (e.g. the GPU adapter), in the same order.
    pub backend_descriptions: Vec<String>,
    /// Timed runs per method.
    pub runs: u32,
    /// Reference method.
    pub reference: String,
    /// Camera offsets every error is measured at (each at the quality size,
    /// against the reference).
    pub offsets: Vec<(f32, f32)>,
    /// Scenes.
    pub scenes: Vec<SceneInfo>,
    /// Ambient-occlusion rays per shaded point of every render (`--ao`).
    pub ao: u32,
    /// Other processes' CPU time during the timed rounds.
    pub other_cpu: load::OtherCpu,
}

impl Context {
    /// The names of the SDF scenes, in the run's order.
    pub fn sdf_scenes(&self) -> Vec<&str> {
        self.scenes
            .iter()
            .filter(|sc| sc.sdf)
            .map(|sc| sc.name.as_str())
            .collect()
    }
}

/// A scene in the report.
pub struct SceneInfo {
    /// File-safe name.
    pub name: crate::key::SceneId,
    /// Argument it was loaded from.
    pub arg: String,
    /// SDF scene.
    pub sdf: bool,
    /// Timing size.
    pub timing_size: (u32, u32),
    /// Quality size, when errors were measured.
    pub quality_size: Option<(u32, u32)>,
}

/// The processor's model name (Linux: `/proc/cpuinfo`), or the
/// architecture where that cannot be read.
pub fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, m)| m.trim().to_string())
        })
        .filter(|m| !m.is_empty())
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}

/// Milliseconds as the tables print them: whole above 100, one decimal
/// above 10, two below.
pub fn ms(v: f64) -> String {
    if !v.is_finite() {
        "–".into()
    } else if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}
