//! What a run did and wrote: the [`ReportSummary`], and what it holds
//! besides the rows (the combinations skipped, the failures, the crops and
//! classes per scene, the ray throughput, the error offsets).

use std::fmt;
use std::path::PathBuf;
use std::time::Duration;

use crate::row::ResultRow;
use crate::scenes::Unavailable;
use crate::{ao_sweep, classes, crops, kernel_timing, motion};

/// The error offsets of a run: which, at what size, and what they cost.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ErrorOffsets {
    /// The offsets measured ([`offsets::ERROR_OFFSETS`](crate::offsets::ERROR_OFFSETS), a prefix).
    pub offsets: Vec<(f32, f32)>,
    /// The reference method every offset is measured against (the run's),
    /// each at the quality size.
    pub reference: String,
    /// Wall time the offsets after the first took (their references,
    /// classes, renders and errors).
    pub elapsed: Duration,
}

/// A method that was not run on a scene, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// Scene.
    pub scene: String,
    /// Method.
    pub method: String,
    /// Backend (`"*"` when the method does not apply to the scene at all).
    pub backend: String,
    /// Why.
    pub reason: String,
}

/// A render that failed (with `--keep-going`; otherwise the run stops).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failure {
    /// Scene.
    pub scene: String,
    /// Method (or `reference`).
    pub method: String,
    /// Backend.
    pub backend: String,
    /// The error, with its causes.
    pub error: String,
}

impl Failure {
    /// `method` on `scene` with `backend` failed with `error`.
    pub fn new(
        scene: &str,
        method: impl Into<String>,
        backend: impl Into<String>,
        error: &anyhow::Error,
    ) -> Self {
        Failure {
            scene: scene.into(),
            method: method.into(),
            backend: backend.into(),
            error: format!("{error:#}"),
        }
    }
}

/// A chosen crop region of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCrops {
    /// Scene.
    pub scene: String,
    /// The regions.
    pub regions: Vec<crops::Region>,
}

/// The edge classes of a scene at its quality size, kept for the
/// interactive page, which shows a pixel's classes under the cursor.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneClasses {
    /// Scene.
    pub scene: String,
    /// Its class masks.
    pub masks: classes::ClassMasks,
}

/// What a report run did and wrote.
#[derive(Clone, Debug)]
pub struct ReportSummary {
    /// Output directory.
    pub out_dir: PathBuf,
    /// `report.md`.
    pub report_md: PathBuf,
    /// `results.csv`.
    pub results_csv: PathBuf,
    /// `results.json`.
    pub results_json: PathBuf,
    /// `report.html`, the interactive page.
    pub report_html: PathBuf,
    /// Plots written (PNG and SVG).
    pub plots: Vec<PathBuf>,
    /// One row per scene, backend and method run.
    pub rows: Vec<ResultRow>,
    /// The SRAA Table 1 sweep (empty when not run).
    pub sweep: Vec<ResultRow>,
    /// "Where SRAA pays", the ambient-occlusion sweep (`--sraa-sweep`).
    pub ao_sweep: ao_sweep::AoSweep,
    /// Antialiasing in motion (`--motion`; a small version in the quick
    /// report).
    pub motion: motion::Motion,
    /// Methods not run, with the reason.
    pub skipped: Vec<Skipped>,
    /// Renders that failed (only with `--keep-going`).
    pub failures: Vec<Failure>,
    /// Scenes that could not be loaded, with the reason.
    pub unavailable_scenes: Unavailable,
    /// Crop regions chosen per scene.
    pub crops: Vec<SceneCrops>,
    /// Edge classes per scene whose errors were measured.
    pub classes: Vec<SceneClasses>,
    /// References rendered in this run.
    pub references_rendered: usize,
    /// References read from the cache.
    pub references_cached: usize,
    /// Ray throughput of the CPU pipeline against raw traversal, per
    /// instruction-set path the machine runs and triangle scene (empty when
    /// the CPU backend is not in the run).
    pub throughput: Vec<ThroughputRow>,
    /// ns per call of the hot kernels (empty when the CPU backend is not in the
    /// run: they are CPU figures).
    pub kernels: Vec<kernel_timing::KernelTiming>,
    /// The camera offsets errors were measured at, and their cost.
    pub error_offsets: ErrorOffsets,
    /// Wall time of the whole run.
    pub elapsed: Duration,
}

/// The ray throughput of one triangle scene on the CPU backend.
#[derive(Clone, Debug, PartialEq)]
pub struct ThroughputRow {
    /// Scene.
    pub scene: String,
    /// The CPU backend's instruction-set path, raw and pipeline alike.
    pub isa: subcone_cpu::isa::Isa,
    /// Frame size the rays cover (the scene's timing size).
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// The measured rates.
    pub rates: subcone_cpu::throughput::RayThroughput,
}

impl fmt::Display for ReportSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let scenes: std::collections::BTreeSet<&str> =
            self.rows.iter().map(|r| r.scene.as_str()).collect();
        writeln!(
            f,
            "report: {} results on {} scenes ({} skipped, {} failed, {} scenes unavailable) in {:.1} s; references: {} rendered, {} cached",
            self.rows.len(),
            scenes.len(),
            self.skipped.len(),
            self.failures.len(),
            self.unavailable_scenes.len(),
            self.elapsed.as_secs_f64(),
            self.references_rendered,
            self.references_cached
        )?;
        writeln!(f, "  {}", self.report_md.display())?;
        writeln!(f, "  {}", self.results_csv.display())?;
        writeln!(f, "  {}", self.report_html.display())?;
        write!(f, "  {}", self.results_json.display())
    }
}
