//! `subcone-report`, the library behind `subcone report`: image error against run time for every method, scene and
//! backend, with plots, zoomed crops and a comparison with the papers' numbers.
//!
//! For each scene (the built-in paper scenes by default, plus `--scene`), each
//! backend and each method that the backend renders on the scene (asked of
//! [`Backend::supports`] before anything renders; the others are listed under
//! *Skipped* with the typed reason), the report
//!
//! 1. times the methods in interleaved rounds. First every method's
//!    warm-up: the quality render of step 2 when errors are measured (a
//!    render the row needs anyway), followed by one at the timing size only
//!    where the sizes differ and the frame is predicted shorter than
//!    [`timing::SHORT_RENDER`]; else a render at the timing size. Then
//!    `runs` rounds, each calling [`Backend::render`] once per method at the
//!    *timing size*, round `r` starting at the method of index `r mod n` (of
//!    the `n` methods in table order) and wrapping
//!    ([`timing::round_order`]), so that the machine's drift falls on every
//!    method alike. A method's time is the median and range of its wall
//!    times over the rounds, with the median of every pass of
//!    [`FrameStats::timings`](subcone_scene::FrameStats); its ratio to NoAA
//!    is the median (and range) of its per-round ratios to NoAA's time in the
//!    same round ([`timing::round_ratios`]). The SMAA row, whose
//!    post-process is timed apart from the rounds, keeps the ratio of
//!    medians, without a range; the SRAA Table 1 sweep times each method's
//!    runs back to back and has no ratio to NoAA. The header says how much
//!    CPU time other processes took during the rounds ([`load`](mod@load));
//! 2. measures its error at the *quality size* against a supersampled reference
//!    (SSAA256; cached on disk, see [`reference`](mod@reference)): mean FLIP, PSNR and mean FLIP
//!    on the edge mask, all on the tone-mapped 8-bit sRGB images; FLIP and
//!    SSIM, whole and per class, again at the sub-pixel camera offsets of
//!    [`offsets`](mod@offsets) (quality renders only, each offset against
//!    its own reference), reported as the mean and range over the offsets;
//! 3. classifies every pixel into edge classes from sub-sample AOVs
//!    ([`classes`](mod@classes)) and measures FLIP per class, then judges
//!    each method against NoAA on the classes it claims;
//! 4. adds an `smaa` row per backend: SMAA 1x ([`smaa`](mod@smaa)) on that
//!    backend's NoAA frame;
//! 5. writes `report.md`, `results.csv`, `results.json`, plots (FLIP against
//!    time with the Pareto front, FLIP by edge class, stacked pass times) and images (every method,
//!    the reference, FLIP maps, zoomed crops of an edge, a shadow and a
//!    reflection region).
//!
//! Sizes: the default run times at the papers' sizes (1024×1024 for triangle
//! scenes, SRAA Table 1's largest; 1280×720 for SDF scenes, CTSS Table 1) and
//! measures error at smaller sizes (512×512 for triangles, 320×180 for SDFs),
//! where a 256-sample reference per scene is affordable on a CPU (sphere
//! tracing costs several times more per sample than the BVH). `--size` sets
//! both; `--quick` uses 96×64 for both with an SSAA64 reference; `--timing-only`
//! skips references and errors. Every mode times 3 rounds after the warm-ups
//! unless `--runs` says otherwise. The default run leaves ssaa16 out on SDF
//! scenes (minutes per 720p frame; CTSS Table 1 stops at 4× SS); an explicit
//! `--method` keeps it.
//!
//! ```no_run
//! let args = subcone_report::ReportArgs { quick: true, ..Default::default() };
//! let summary = subcone_report::run(&args).unwrap();
//! println!("{summary}");
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod answer;
pub mod ao_crossover;
pub mod ao_sweep;
mod args;
pub mod classes;
pub mod context;
pub mod crops;
pub mod files;
pub mod html;
pub mod hybrid;
pub mod kernel_timing;
pub mod key;
pub mod load;
pub mod metrics;
pub mod motion;
pub mod named;
pub mod offsets;
pub mod output;
pub mod papers;
pub mod plot;
pub mod post;
pub mod reference;
pub mod setup;
pub mod smaa;
pub mod timing;

use std::fmt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};
use subcone_kernels::passes::SceneFeatures;
use subcone_scene::{
    Albedo, Backend, Frame, Method, RenderSettings, Scene, Unsupported, UnsupportedReason,
};

use key::{RowKey, SceneId};
use named::{NOAA, SRAA_RT, SSAA16};
use subcone_metrics::{ssim, Rgb8};
use timing::Timings;

/// The built-in scenes of the papers, which the report runs by default:
/// triangle scenes (SRAA) then SDF scenes (CTSS). Names that do not load are
/// skipped with a note.
pub use subcone_scene::builtin::PAPER_SCENES;

/// Built-in scenes the quick report adds after the paper scenes: not from the
/// papers, cheap at the quick size. `glass` shows CTSS §5.3's semi-transparent
/// materials (CPU only: the wgpu backend lists it as skipped).
pub const QUICK_EXTRA_SCENES: [&str; 1] = ["glass"];

/// The methods compared, in table order: every method of
/// [`METHOD_NAMES`](subcone_scene::method::METHOD_NAMES), then the `smaa`
/// post-process row.
pub fn default_methods() -> Vec<&'static str> {
    subcone_scene::method::METHOD_NAMES
        .into_iter()
        .chain([SMAA])
        .collect()
}

/// The name of the SMAA row: not a [`Method`] (no backend renders it), but
/// [`smaa::SmaaPost`] on the NoAA frame of each backend.
pub const SMAA: &str = "smaa";

/// Timing size of triangle scenes: SRAA Table 1's largest.
pub const TRIANGLE_TIMING_SIZE: (u32, u32) = (1024, 1024);
/// Timing size of SDF scenes: CTSS Table 1's 720p.
pub const SDF_TIMING_SIZE: (u32, u32) = (1280, 720);
/// Quality (reference) size of triangle scenes.
pub const TRIANGLE_QUALITY_SIZE: (u32, u32) = (512, 512);
/// Quality (reference) size of SDF scenes.
pub const SDF_QUALITY_SIZE: (u32, u32) = (320, 180);
/// Both sizes in `--quick` mode.
pub const QUICK_SIZE: (u32, u32) = (96, 64);
/// Sizes of the SRAA Table 1 sweep (square).
pub const SWEEP_SIZES: [u32; 4] = [256, 512, 768, 1024];
/// The scene of the SRAA Table 1 sweep: our Sponza-like atrium.
pub const SWEEP_SCENE: &str = "atrium";

pub use args::ReportArgs;

/// One method on one scene with one backend: a row of `results.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct ResultRow {
    /// The scene (its name is the one used in file names).
    pub scene: SceneId,
    /// What the row is of: a method (e.g. `sraa-rt`) or a post-process.
    pub method: RowKey,
    /// Backend, e.g. `cpu`.
    pub backend: String,
    /// Timing width.
    pub width: u32,
    /// Timing height.
    pub height: u32,
    /// Timed runs.
    pub runs: u32,
    /// Median wall time of `Backend::render`, ms.
    pub ms_median: f64,
    /// Fastest run, ms.
    pub ms_min: f64,
    /// Slowest run, ms.
    pub ms_max: f64,
    /// Time over NoAA's on the same scene and backend: the median over the
    /// rounds of the method's time over NoAA's in the same round; for rows
    /// not timed in NoAA's rounds (the `smaa` row), `ms_median` over NoAA's.
    pub ratio_to_noaa: Option<f64>,
    /// Smallest per-round ratio to NoAA (`None` without per-round ratios).
    pub ratio_min: Option<f64>,
    /// Largest per-round ratio to NoAA (`None` without per-round ratios).
    pub ratio_max: Option<f64>,
    /// Mean FLIP against the reference (quality size).
    pub flip_mean: Option<f64>,
    /// PSNR in dB against the reference; `+∞` when identical.
    pub psnr_db: Option<f64>,
    /// Mean FLIP over the edge mask.
    pub edge_flip_mean: Option<f64>,
    /// Mean FLIP and pixel count per edge class ([`classes`](mod@classes)),
    /// when the error was measured.
    pub classes: Option<classes::ClassError>,
    /// Mean SSIM against the reference ([`ssim`](mod@ssim), luminance,
    /// 11×11 Gaussian window of σ = 1.5).
    pub ssim_mean: Option<f64>,
    /// Mean `1 − SSIM` and pixel count per edge class, when the error was
    /// measured: the second metric the verdicts are computed under.
    pub classes_ssim: Option<classes::ClassError>,
    /// The error at each camera offset it was measured at
    /// ([`offsets::ERROR_OFFSETS`], in order; offset 0 is the scene's
    /// camera, the one the images show). `flip_mean`, `ssim_mean`,
    /// `classes` and `classes_ssim` are their means (class pixel counts the
    /// smallest over the offsets); PSNR and edge FLIP are offset 0's. Not a
    /// results column itself: `offsets` and the `_min`/`_max` columns come
    /// from it.
    pub errors_at: Vec<OffsetError>,
    /// Shaded samples per pixel: the mean of the samples-per-pixel AOV of the
    /// quality render, or, without one, shading evaluations per pixel.
    pub samples_per_pixel: f64,
    /// Rays of every kind per pixel (timing frame).
    pub rays_per_pixel: f64,
    /// Primary samples whose triangle the rasteriser found, per pixel
    /// (timing frame, [`FrameStats::raster_samples`](subcone_scene::FrameStats::raster_samples)):
    /// 0 for a method that traces its primary rays.
    pub raster_samples_per_pixel: f64,
    /// MiB of frame buffers the backend allocated (timing frame): what leaving
    /// out passes a scene does not need saves shows here.
    pub buffer_mib: f64,
    /// Width the error was measured at.
    pub quality_width: Option<u32>,
    /// Height the error was measured at.
    pub quality_height: Option<u32>,
    /// Reference method the error is against.
    pub reference: Option<String>,
    /// Median ms of each pass (column-safe name without `ms_`), in run order.
    pub pass_ms: Vec<(String, f64)>,
    /// Wall time of each timed round, ms, in round order: the rows of one
    /// scene and backend share their rounds, so `round_ms[r]` of two of them
    /// were measured a few frames apart. Empty for rows not timed in rounds
    /// (the `smaa` row, the sweep). Not a results column.
    pub round_ms: Vec<f64>,
    /// For a post-process row (`smaa`, `--post-process`): what filtered
    /// NoAA's frame, where, and what its time covers
    /// ([`PostProcess::describe`](post::PostProcess::describe)).
    pub post_process: Option<String>,
    /// How the row's passes were timed (distinct sources, in the order
    /// first seen): the CPU's wall clock, GPU timestamps, or the wall clock
    /// around GPU work whose timestamps are not used.
    pub timed_by: Vec<subcone_scene::TimingSource>,
    /// A hash of the quality image's size and bytes
    /// ([`answer::digest`]), when the error was measured: rows of one scene
    /// and backend with equal digests rendered the same image. Not a results
    /// column.
    pub image_digest: Option<u64>,
}

impl ResultRow {
    /// The row of `method` on `scene` with `backend`, timed at `size` over
    /// `runs` runs: times and passes from `t`; no error measured yet, and
    /// per-frame figures (spp, rays, buffers) 0 until the caller sets them.
    pub fn timed(
        scene: &str,
        method: RowKey,
        backend: &str,
        size: (u32, u32),
        runs: u32,
        t: &Timings,
    ) -> Self {
        ResultRow {
            scene: SceneId::new(scene),
            method,
            backend: backend.into(),
            width: size.0,
            height: size.1,
            runs,
            ms_median: t.median(),
            ms_min: t.min(),
            ms_max: t.max(),
            ratio_to_noaa: None,
            ratio_min: None,
            ratio_max: None,
            flip_mean: None,
            psnr_db: None,
            edge_flip_mean: None,
            classes: None,
            ssim_mean: None,
            classes_ssim: None,
            errors_at: Vec::new(),
            samples_per_pixel: 0.0,
            rays_per_pixel: 0.0,
            raster_samples_per_pixel: 0.0,
            buffer_mib: 0.0,
            quality_width: None,
            quality_height: None,
            reference: None,
            pass_ms: t.pass_medians(),
            round_ms: Vec::new(),
            post_process: None,
            timed_by: t.sources.clone(),
            image_digest: None,
        }
    }

    /// The row's per-class error under `metric`, when it was measured.
    pub fn class_error(&self, metric: classes::Metric) -> Option<classes::ClassError> {
        match metric {
            classes::Metric::Flip => self.classes,
            classes::Metric::Ssim => self.classes_ssim,
        }
    }

    /// The row's per-class error under `metric` at each camera offset, in
    /// offset order: [`ResultRow::errors_at`]'s, or without them the one
    /// [`ResultRow::class_error`] (empty when not measured).
    pub fn class_errors_at(&self, metric: classes::Metric) -> Vec<classes::ClassError> {
        if self.errors_at.is_empty() {
            return self.class_error(metric).into_iter().collect();
        }
        self.errors_at
            .iter()
            .map(|e| match metric {
                classes::Metric::Flip => e.classes,
                classes::Metric::Ssim => e.classes_ssim,
            })
            .collect()
    }

    /// Smallest and largest whole-image error under `metric` (mean FLIP,
    /// or mean SSIM) over the offsets, when measured at more than one.
    pub fn range(&self, metric: classes::Metric) -> Option<(f64, f64)> {
        if self.errors_at.len() < 2 {
            return None;
        }
        let v = self.errors_at.iter().map(|e| match metric {
            classes::Metric::Flip => e.flip,
            classes::Metric::Ssim => e.ssim,
        });
        Some(v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        }))
    }

    /// Set the means over the offsets (`flip_mean`, `ssim_mean`, `classes`,
    /// `classes_ssim`) from [`ResultRow::errors_at`]; nothing without them.
    pub fn settle_offsets(&mut self) {
        let n = self.errors_at.len();
        if n == 0 {
            return;
        }
        self.flip_mean = Some(self.errors_at.iter().map(|e| e.flip).sum::<f64>() / n as f64);
        self.ssim_mean = Some(self.errors_at.iter().map(|e| e.ssim).sum::<f64>() / n as f64);
        self.classes =
            classes::ClassError::over_offsets(&self.class_errors_at(classes::Metric::Flip));
        self.classes_ssim =
            classes::ClassError::over_offsets(&self.class_errors_at(classes::Metric::Ssim));
    }

    /// The classes the row claims to fix: a post-process row's
    /// ([`POST_PROCESS_CLAIMS`](subcone_scene::registry::POST_PROCESS_CLAIMS)),
    /// else what its method claims ([`Method::claims`]), nothing for any
    /// other post-process step.
    pub fn claims(&self) -> Vec<classes::Class> {
        match (&self.post_process, &self.method) {
            (Some(_), _) => subcone_scene::registry::POST_PROCESS_CLAIMS.to_vec(),
            (None, RowKey::Method(m)) => m.claims(),
            (None, RowKey::Post(_)) => Vec::new(),
        }
    }

    /// Median ms of pass `name` (column-safe), if the method has it.
    pub fn pass(&self, name: &str) -> Option<f64> {
        self.pass_ms.iter().find(|p| p.0 == name).map(|p| p.1)
    }
}

/// A method's error at one camera offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffsetError {
    /// The offset ([`offsets::ERROR_OFFSETS`]), pixels.
    pub offset: (f32, f32),
    /// Mean FLIP.
    pub flip: f64,
    /// Mean SSIM.
    pub ssim: f64,
    /// Mean FLIP per class (the offset's own classes).
    pub classes: classes::ClassError,
    /// Mean `1 − SSIM` per class.
    pub classes_ssim: classes::ClassError,
}

impl OffsetError {
    /// The error of `img` against `reference` at `offset`, with the
    /// offset's class masks.
    pub fn measure(
        offset: (f32, f32),
        reference: &Rgb8,
        img: &Rgb8,
        masks: &classes::ClassMasks,
    ) -> Result<OffsetError> {
        let fl = subcone_metrics::flip(reference, img)?;
        let ss = ssim::ssim(reference, img)?;
        Ok(OffsetError::of(offset, &fl, &ss, masks))
    }

    fn of(
        offset: (f32, f32),
        fl: &subcone_metrics::Flip,
        ss: &ssim::Ssim,
        masks: &classes::ClassMasks,
    ) -> OffsetError {
        OffsetError {
            offset,
            flip: fl.mean,
            ssim: ss.mean,
            classes: classes::ClassError::measure(&fl.map, masks),
            classes_ssim: classes::ClassError::measure(&ss.dissimilarity(), masks),
        }
    }
}

/// The error offsets of a run: which, at what size, and what they cost.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ErrorOffsets {
    /// The offsets measured ([`offsets::ERROR_OFFSETS`], a prefix).
    pub offsets: Vec<(f32, f32)>,
    /// The offsets after the first are measured at the quality size divided
    /// by this on each side.
    pub divisor: u32,
    /// The reference method of the offsets after the first.
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

/// The run mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Timing at the papers' sizes, error at the quality sizes.
    Full,
    /// Small sizes, few runs.
    Quick,
    /// No references, no errors.
    TimingOnly,
}

impl Mode {
    /// Name for the report.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Full => "full",
            Mode::Quick => "quick",
            Mode::TimingOnly => "timing-only",
        }
    }
}

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

/// Everything a run needs, resolved and validated from [`ReportArgs`].
struct Plan {
    mode: Mode,
    out: PathBuf,
    cache: PathBuf,
    backends: Vec<(String, Box<dyn Backend + Send + Sync>)>,
    methods: Vec<Method>,
    runs: u32,
    reference: Method,
    size: Option<(u32, u32)>,
    sweep: bool,
    refresh: bool,
    keep_going: bool,
    /// The post-process rows, in table order after the methods.
    post: Vec<PostPlan>,
    /// Ambient-occlusion rays per shaded point of every render (`--ao`).
    ao: u32,
    /// The "Where SRAA pays" section, when it runs: the default report's
    /// short sweep, or `--sraa-sweep`'s full one.
    sraa_sweep: Option<ao_sweep::SweepSpec>,
    /// Frames of the motion section, when it runs.
    motion_frames: Option<u32>,
    /// Camera offsets the error is measured at (a prefix of
    /// [`offsets::ERROR_OFFSETS`]).
    offsets: Vec<(f32, f32)>,
    /// The offsets after the first are measured at the quality size over
    /// this on each side.
    offset_divisor: u32,
    /// The reference of the offsets after the first.
    offset_reference: Method,
}

/// A method that some backend renders on a scene, with the indices (in the
/// plan) of the backends that do.
type Applicable = (Method, Vec<usize>);

/// A post-process row of the run ([`post`](mod@post)).
enum PostPlan {
    /// The step, ready.
    On(Box<dyn post::PostProcess>),
    /// Asked for, but it cannot run here (SMAA without an adapter): its name
    /// and the reason, listed under Skipped.
    Unavailable { name: String, reason: String },
}

impl PostPlan {
    /// The `smaa` row: SMAA 1x on the shared GPU, or the reason it cannot
    /// run (an error instead when `SUBCONE_REQUIRE_GPU` is set).
    fn smaa() -> Result<PostPlan> {
        match smaa::SmaaPost::new() {
            Ok(p) => Ok(PostPlan::On(Box::new(p))),
            Err(e) if subcone_wgpu::gpu_required() => {
                Err(e.context("the smaa row needs a GPU adapter and SUBCONE_REQUIRE_GPU is set"))
            }
            Err(e) => Ok(PostPlan::Unavailable {
                name: SMAA.into(),
                reason: format!("no GPU adapter for the SMAA post-process: {e:#}"),
            }),
        }
    }

    /// The `smaa` row when `names` asks for it, then one row per
    /// `--post-process NAME=COMMAND` (names distinct).
    fn all(names: &[String], args: &ReportArgs) -> Result<Vec<PostPlan>> {
        let mut out = Vec::new();
        if names.iter().any(|n| n == SMAA) {
            out.push(PostPlan::smaa()?);
        }
        let timeout = match args.post_timeout {
            None => post::DEFAULT_TIMEOUT,
            Some(s) if s.is_finite() && s > 0.0 && s <= 86_400.0 => Duration::from_secs_f64(s),
            Some(s) => bail!("--post-timeout {s}: expected seconds in (0, 86400]"),
        };
        let mut seen: Vec<String> = Vec::new();
        for spec in &args.post_processes {
            let c = post::CommandPost::parse(spec, timeout)?;
            if seen.iter().any(|n| n == post::PostProcess::name(&c)) {
                bail!(
                    "--post-process: the name {:?} is given twice",
                    post::PostProcess::name(&c)
                );
            }
            seen.push(post::PostProcess::name(&c).to_string());
            out.push(PostPlan::On(Box::new(c)));
        }
        Ok(out)
    }
}

fn parse_backends(list: &str) -> Result<Vec<(String, Box<dyn Backend + Send + Sync>)>> {
    let mut out: Vec<(String, Box<dyn Backend + Send + Sync>)> = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        if out.iter().any(|(n, _)| n == name) {
            continue;
        }
        let b = setup::backend(name).with_context(|| format!("--backend {list:?}"))?;
        out.push((name.to_string(), b));
    }
    if out.is_empty() {
        bail!("--backend {list:?} names no backend (expected e.g. cpu or cpu,wgpu)");
    }
    Ok(out)
}

fn parse_method(s: &str, what: &str) -> Result<Method> {
    s.parse::<Method>().map_err(|e| anyhow!("{what}: {e}"))
}

impl Plan {
    fn new(args: &ReportArgs) -> Result<Plan> {
        let mode = match (args.quick, args.timing_only) {
            (_, true) => Mode::TimingOnly,
            (true, false) => Mode::Quick,
            (false, false) => Mode::Full,
        };
        let backends = parse_backends(&args.backend)?;
        let names: Vec<String> = if args.methods.is_empty() {
            default_methods().into_iter().map(String::from).collect()
        } else {
            args.methods
                .iter()
                .map(|s| s.trim().to_string())
                .filter(|s| !s.is_empty())
                .collect()
        };
        if names.is_empty() {
            bail!("--method names no method");
        }
        let mut methods: Vec<Method> = Vec::new();
        let post = PostPlan::all(&names, args)?;
        if !post.is_empty()
            && !names
                .iter()
                .any(|n| n.parse::<Method>().is_ok_and(|m| m == NOAA))
        {
            // A post-process filters the NoAA frame and is judged against it.
            methods.push(NOAA);
        }
        let is_post = |n: &String| {
            post.iter()
                .any(|p| matches!(p, PostPlan::On(p) if p.name() == n.as_str()))
                || n == SMAA
        };
        for n in names.iter().filter(|n| !is_post(n)) {
            let m = parse_method(n, "--method")?;
            if !methods.contains(&m) {
                methods.push(m);
            }
        }
        let runs = match args.runs {
            Some(0) => bail!("--runs must be at least 1"),
            Some(n) if n > 1000 => bail!("--runs {n} is more than 1000"),
            Some(n) => n,
            None => 3,
        };
        let reference = match &args.reference {
            Some(r) => parse_method(r, "--reference")?,
            None if args.quick => Method::ssaa_grid(8),
            None => Method::ssaa_grid(16),
        };
        let size = match &args.size {
            Some(s) => {
                let (w, h) = setup::parse_size(s)?;
                RenderSettings::new(w, h)
                    .validate()
                    .map_err(|e| anyhow!("--size {s}: {e}"))?;
                Some((w, h))
            }
            None => None,
        };
        if args.no_paper_scenes && args.scenes.is_empty() {
            bail!("--no-paper-scenes leaves no scene: add at least one --scene");
        }
        let cache = args.cache.clone().unwrap_or_else(|| args.out.join("cache"));
        let motion_frames = if args.motion || mode == Mode::Quick {
            if mode == Mode::TimingOnly {
                bail!("--motion compares frames with references: it cannot run with --timing-only");
            }
            let default = if mode == Mode::Quick {
                motion::QUICK_FRAMES
            } else {
                motion::FRAMES
            };
            let frames = args.motion_frames.unwrap_or(default);
            if !(2..=1000).contains(&frames) {
                bail!("--motion-frames {frames}: a path needs 2 to 1000 frames");
            }
            Some(frames)
        } else {
            None
        };
        let sweep =
            mode != Mode::Quick && size.is_none() && !args.no_sweep && methods.contains(&SRAA_RT);
        // "Where SRAA pays": the full sweep when asked; otherwise a short one
        // in the default (full-mode) report wherever the parameter sweep runs.
        let sraa_sweep = if args.sraa_sweep {
            Some(ao_sweep::SweepSpec::full())
        } else if sweep && mode == Mode::Full {
            Some(ao_sweep::SweepSpec::default_report())
        } else {
            None
        };
        Ok(Plan {
            mode,
            out: args.out.clone(),
            cache,
            backends,
            methods,
            runs,
            reference,
            size,
            sweep,
            refresh: args.refresh_references,
            keep_going: args.keep_going,
            post,
            ao: args.ao,
            sraa_sweep,
            motion_frames,
            offsets: match (mode, args.error_offsets) {
                (Mode::TimingOnly, _) => Vec::new(),
                (_, Some(k)) if !(1..=offsets::ERROR_OFFSETS.len()).contains(&k) => bail!(
                    "--error-offsets {k}: expected 1 to {}",
                    offsets::ERROR_OFFSETS.len()
                ),
                (_, k) => {
                    offsets::ERROR_OFFSETS[..k.unwrap_or(offsets::ERROR_OFFSETS.len())].to_vec()
                }
            },
            offset_divisor: if mode == Mode::Full && size.is_none() {
                offsets::FULL_OFFSET_DIVISOR
            } else {
                1
            },
            offset_reference: if mode == Mode::Full && size.is_none() && args.reference.is_none() {
                offsets::FULL_OFFSET_REFERENCE
            } else {
                reference
            },
        })
    }

    /// The size the offsets after the first are measured at for `job`.
    fn offset_size(&self, job: &SceneJob) -> (u32, u32) {
        let (w, h) = job.quality_size;
        let d = self.offset_divisor.max(1);
        ((w / d).max(1), (h / d).max(1))
    }

    /// The settings of a `w × h` render of the run: the run's ambient
    /// occlusion, on triangle scenes (the report's SDF scenes render without
    /// it, though both backends render it there).
    fn settings(&self, w: u32, h: u32, sdf: bool) -> RenderSettings {
        let mut s = RenderSettings::new(w, h);
        if !sdf {
            s.ao_rays = self.ao;
        }
        s
    }

    fn sizes(&self, sdf: bool) -> ((u32, u32), (u32, u32)) {
        if let Some(s) = self.size {
            return (s, s);
        }
        match (self.mode, sdf) {
            (Mode::Quick, _) => (QUICK_SIZE, QUICK_SIZE),
            (_, false) => (TRIANGLE_TIMING_SIZE, TRIANGLE_QUALITY_SIZE),
            (_, true) => (SDF_TIMING_SIZE, SDF_QUALITY_SIZE),
        }
    }
}

fn load_scenes(args: &ReportArgs, plan: &Plan) -> Result<(Vec<SceneJob>, Unavailable)> {
    let mut loaded: Vec<(String, Scene)> = Vec::new();
    let mut unavailable = Vec::new();
    if !args.no_paper_scenes {
        let (ok, missing) = paper_scenes();
        loaded = ok;
        unavailable = missing;
        if plan.mode == Mode::Quick {
            for name in QUICK_EXTRA_SCENES {
                match setup::scene(name) {
                    Ok(s) => loaded.push((name.to_string(), s)),
                    Err(e) => unavailable.push((name.to_string(), format!("{e:#}"))),
                }
            }
        }
    }
    for arg in &args.scenes {
        if loaded.iter().any(|(a, _)| a == arg) {
            continue;
        }
        let s = setup::scene(arg).with_context(|| format!("--scene {arg}"))?;
        loaded.push((arg.clone(), s));
    }
    if loaded.is_empty() {
        bail!("no scene could be loaded");
    }
    let mut jobs: Vec<SceneJob> = Vec::new();
    for (arg, scene) in loaded {
        let base = file_safe(if scene.name.is_empty() {
            &arg
        } else {
            &scene.name
        });
        let mut name = base.clone();
        let mut k = 2;
        while jobs.iter().any(|j| j.name == name) {
            name = format!("{base}-{k}");
            k += 1;
        }
        let sdf = scene.features().contains(SceneFeatures::IS_SDF);
        let (timing_size, quality_size) = plan.sizes(sdf);
        jobs.push(SceneJob {
            arg,
            name: SceneId::new(name),
            scene,
            sdf,
            timing_size,
            quality_size,
        });
    }
    Ok((jobs, unavailable))
}

fn render(
    backend: &dyn Backend,
    scene: &Scene,
    method: &Method,
    settings: &RenderSettings,
) -> Result<(Frame, Duration)> {
    render_from(backend, scene, &scene.camera, method, settings)
}

/// Sub-samples per pixel side for the classes of a `w × h` image:
/// [`classes::SUBSAMPLES`], fewer when that frame would be beyond
/// [`subcone_scene::backend::MAX_PIXELS`].
fn sub_sample_side(w: u32, h: u32) -> u32 {
    (1..=classes::SUBSAMPLES)
        .rev()
        .find(|s| {
            let mut t = RenderSettings::new(w * s, h * s);
            t.aovs = true;
            t.validate().is_ok()
        })
        .unwrap_or(1)
}

/// The edge classes of a `w × h` image of `scene` seen from `camera`, from
/// the AOVs of a NoAA frame of `backend` (the cpu's: it records them all)
/// at [`sub_sample_side`]× the size per side.
fn classes_at(
    backend: &dyn Backend,
    scene: &Scene,
    camera: &subcone_scene::Camera,
    (w, h): (u32, u32),
) -> Result<classes::ClassMasks> {
    let side = sub_sample_side(w, h);
    let mut settings = RenderSettings::new(w * side, h * side);
    settings.aovs = true;
    let (sub, _) = render_from(backend, scene, camera, &NOAA, &settings)?;
    classes::classify(&sub, side)
}

/// [`render`] from `camera` instead of the scene's.
fn render_from(
    backend: &dyn Backend,
    scene: &Scene,
    camera: &subcone_scene::Camera,
    method: &Method,
    settings: &RenderSettings,
) -> Result<(Frame, Duration)> {
    let start = Instant::now();
    let frame = backend
        .render(scene, camera, method, settings)
        .map_err(|e| anyhow!("{} {} {}: {e}", backend.name(), scene.name, method))?;
    let wall = start.elapsed();
    let n = settings.width as usize * settings.height as usize;
    if frame.width != settings.width || frame.height != settings.height || frame.color.len() != n {
        bail!(
            "{} {} {}: the backend returned a {}x{} frame with {} pixels for {}x{}",
            backend.name(),
            scene.name,
            method,
            frame.width,
            frame.height,
            frame.color.len(),
            settings.width,
            settings.height
        );
    }
    Ok((frame, wall))
}

/// What the quality phase knows about a scene.
struct SceneQuality {
    reference: Rgb8,
    edges: Vec<bool>,
    geometric: Vec<bool>,
    noaa_error_base: Rgb8,
    shadow: Option<Vec<bool>>,
    reflective: Option<Vec<bool>>,
    classes: classes::ClassMasks,
    /// The camera offsets after the first, each with its reference and
    /// classes.
    offsets: Vec<OffsetQuality>,
}

/// What the error needs at one camera offset.
struct OffsetQuality {
    offset: (f32, f32),
    camera: subcone_scene::Camera,
    size: (u32, u32),
    reference: Rgb8,
    classes: classes::ClassMasks,
}

struct Progress {
    bar: ProgressBar,
}

impl Progress {
    fn new(len: u64) -> Self {
        let bar = ProgressBar::new(len);
        if let Ok(style) = ProgressStyle::with_template(
            "{elapsed_precise} [{bar:30}] {pos}/{len} renders, eta {eta} {wide_msg}",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress { bar }
    }

    fn note(&self, msg: &str) {
        self.bar.suspend(|| eprintln!("report: {msg}"));
    }
}

/// The run's state while it measures: the plan, the progress bar and what
/// has been measured so far.
struct Runner<'a> {
    plan: &'a Plan,
    /// The CPU backend of every render that is not timed on the plan's
    /// backends (references, edge classes, masks, motion): the plan's own
    /// `cpu` backend when it times one, so that each scene's BVH is built
    /// once for all its renders ([`CpuBackend`](subcone_cpu::CpuBackend)
    /// caches one per scene).
    cpu: &'a (dyn Backend + Send + Sync),
    progress: Progress,
    references_rendered: usize,
    references_cached: usize,
    rows: Vec<ResultRow>,
    failures: Vec<Failure>,
    crops: Vec<SceneCrops>,
    classes: Vec<SceneClasses>,
    plots: Vec<PathBuf>,
    /// Other processes' CPU time over the timed rounds, summed over scenes
    /// and backends.
    load: load::OtherCpu,
    /// Wall time spent on the camera offsets after the first.
    offsets_elapsed: Duration,
}

impl Runner<'_> {
    /// A failed render: an error that stops the run, or with `--keep-going`
    /// a note and an entry in `failures`.
    fn fail(&mut self, f: Failure) -> Result<()> {
        if !self.plan.keep_going {
            self.progress.bar.abandon();
            bail!(
                "{} / {} on {} failed: {} (pass --keep-going to list failures in the report and go on)",
                f.scene,
                f.method,
                f.backend,
                f.error
            );
        }
        self.progress.note(&format!(
            "FAILED {} / {} on {}: {}",
            f.scene, f.method, f.backend, f.error
        ));
        self.failures.push(f);
        Ok(())
    }

    fn reference(&mut self, job: &SceneJob) -> Result<Frame> {
        let (w, h) = job.quality_size;
        let settings = self.plan.settings(w, h, job.sdf);
        self.reference_with(job, &settings)
    }

    /// The scene's reference at `settings` (size and ambient occlusion),
    /// from the cache or rendered on the CPU and cached.
    fn reference_with(&mut self, job: &SceneJob, settings: &RenderSettings) -> Result<Frame> {
        self.reference_by(job, settings, None)
    }

    /// [`Self::reference_with`] by `method` instead of the run's reference
    /// (`None`: the run's), cached under its own key.
    fn reference_by(
        &mut self,
        job: &SceneJob,
        settings: &RenderSettings,
        method: Option<Method>,
    ) -> Result<Frame> {
        self.reference_from(job, settings, method, None)
    }

    /// [`Self::reference_by`] seen from `camera` instead of the scene's
    /// (`None`: the scene's), cached under its own key.
    fn reference_from(
        &mut self,
        job: &SceneJob,
        settings: &RenderSettings,
        method: Option<Method>,
        camera: Option<&subcone_scene::Camera>,
    ) -> Result<Frame> {
        let reference = method.unwrap_or(self.plan.reference);
        let (w, h) = (settings.width, settings.height);
        let key = reference::ReferenceKey {
            scene: reference::scene_identity(&job.arg),
            width: w,
            height: h,
            method: reference.to_string(),
            reflection_depth: settings.reflection_depth,
            ao_rays: settings.ao_rays,
            backend: "cpu".into(),
            version: reference::code_version(),
            camera: camera.map(offsets::describe),
        };
        let path = key.path(&self.plan.cache);
        if !self.plan.refresh {
            if let Some(f) = reference::load(&path, w, h)? {
                self.references_cached += 1;
                self.progress.bar.inc(1);
                return Ok(f);
            }
        }
        self.progress
            .bar
            .set_message(format!("{}: reference {} at {w}x{h}", job.name, reference));
        let camera = camera.unwrap_or(&job.scene.camera);
        let (frame, wall) = render_from(self.cpu, &job.scene, camera, &reference, settings)?;
        self.progress.note(&format!(
            "{}: rendered reference {} at {w}x{h}{} in {:.1} s",
            job.name,
            reference,
            if settings.ao_rays > 0 {
                format!(" with {} AO rays", settings.ao_rays)
            } else {
                String::new()
            },
            wall.as_secs_f64()
        ));
        reference::store(&path, &key, &frame)?;
        self.references_rendered += 1;
        self.progress.bar.inc(1);
        Ok(frame)
    }

    /// The edge classes of a scene at its quality size ([`classes_at`]).
    fn classes(&mut self, job: &SceneJob) -> Result<classes::ClassMasks> {
        let (w, h) = job.quality_size;
        let side = sub_sample_side(w, h);
        self.progress.bar.set_message(format!(
            "{}: edge classes from {side}x{side} sub-samples per pixel",
            job.name
        ));
        classes_at(self.cpu, &job.scene, &job.scene.camera, (w, h))
    }

    /// Reference, edge mask and the masks the crop heuristics need.
    fn quality(&mut self, job: &SceneJob) -> Result<SceneQuality> {
        let reference = Rgb8::from_frame(&self.reference(job)?)?;
        let (w, h) = job.quality_size;
        let noaa = NOAA;
        let mut aov_settings = self.plan.settings(w, h, job.sdf);
        aov_settings.aovs = true;
        self.progress
            .bar
            .set_message(format!("{}: edge mask and region masks", job.name));
        let (aov, _) = render(self.cpu, &job.scene, &noaa, &aov_settings)?;
        let geometric = metrics::geometric_edges(&aov)?;
        let edges = metrics::edge_mask(&aov, &reference)?;
        let noaa8 = Rgb8::from_frame(&aov)?;
        let features = job.scene.features();
        let mut flat = RenderSettings::new(w, h);
        flat.reflection_depth = 0;
        let reflective = if features.contains(SceneFeatures::HAS_REFLECTIONS) {
            let (f, _) = render(self.cpu, &job.scene, &noaa, &flat)?;
            Some(metrics::differing_pixels(
                &noaa8,
                &Rgb8::from_frame(&f)?,
                2,
            )?)
        } else {
            None
        };
        let shadow = if features.contains(SceneFeatures::HAS_LIGHTS) {
            let mut grey = job.scene.clone();
            for m in &mut grey.materials {
                m.albedo = Albedo::Solid(Vec3::splat(0.6));
            }
            match render(self.cpu, &grey, &noaa, &flat) {
                Ok((f, _)) => {
                    let g = metrics::gradient_edges(&Rgb8::from_frame(&f)?);
                    Some(g.iter().zip(&geometric).map(|(&g, &e)| g && !e).collect())
                }
                Err(e) => {
                    self.progress.note(&format!(
                        "{}: no untextured render for the shadow crop: {e:#}",
                        job.name
                    ));
                    None
                }
            }
        } else {
            None
        };
        let classes = self.classes(job)?;
        self.progress.bar.inc(1);
        Ok(SceneQuality {
            reference,
            edges,
            geometric,
            noaa_error_base: noaa8,
            shadow,
            reflective,
            classes,
            offsets: Vec::new(),
        })
    }

    /// The reference and classes at each camera offset after the first
    /// ([`Plan::offset_size`]); the time they take is added to
    /// `offsets_elapsed`.
    fn offset_qualities(&mut self, job: &SceneJob) -> Result<Vec<OffsetQuality>> {
        let start = Instant::now();
        let plan = self.plan;
        let size = plan.offset_size(job);
        let mut out = Vec::new();
        for &offset in plan.offsets.iter().skip(1) {
            let camera = offsets::offset_camera(&job.scene.camera, offset, size.1)?;
            let settings = plan.settings(size.0, size.1, job.sdf);
            let by = Some(plan.offset_reference);
            let reference = self.reference_from(job, &settings, by, Some(&camera))?;
            self.progress.bar.set_message(format!(
                "{}: edge classes at offset {}",
                job.name,
                offsets::label(offset)
            ));
            let classes = classes_at(self.cpu, &job.scene, &camera, size)?;
            self.progress.bar.inc(1);
            out.push(OffsetQuality {
                offset,
                camera,
                size,
                reference: Rgb8::from_frame(&reference)?,
                classes,
            });
        }
        self.offsets_elapsed += start.elapsed();
        Ok(out)
    }
}

/// Where the post-process rows of one scene and backend go.
struct PostAt<'a> {
    job: &'a SceneJob,
    /// The backend's index in the plan.
    bi: usize,
    sq: Option<&'a SceneQuality>,
    img_dir: &'a Path,
}

/// The row of post-process `step` on one backend: NoAA's row with the step
/// (one warm-up, then `runs` timed calls on the timing-size NoAA frame)
/// added to its times, as the pass named after the step, and the step
/// described; with the scene's quality, its error on the filtered NoAA
/// quality image. `timing` is the timing-size NoAA frame the step gets
/// (with AOVs when it reads them).
fn post_measured(
    step: &dyn post::PostProcess,
    noaa: &Measured,
    timing: &Frame,
    at: &PostAt<'_>,
    plan: &Plan,
    offsets_spent: &mut Duration,
) -> Result<Measured> {
    let name = step.name();
    let image = Rgb8::from_frame(timing)?;
    let input = post::PostInput {
        scene: &at.job.name,
        image: &image,
        frame: timing,
    };
    step.apply(&input)?;
    let mut ms: Vec<f64> = Vec::new();
    let mut timed_by = noaa.row.timed_by.clone();
    for _ in 0..plan.runs.max(1) {
        let (_, timing) = step.apply(&input)?;
        ms.push(timing.time.as_secs_f64() * 1e3);
        if !timed_by.contains(&timing.source) {
            timed_by.push(timing.source);
        }
    }
    ms.sort_by(f64::total_cmp);
    let median = ms[ms.len() / 2];
    let base = &noaa.row;
    let mut pass_ms = base.pass_ms.clone();
    pass_ms.push((file_safe(name), median));
    let mut row = ResultRow {
        ms_median: base.ms_median + median,
        ms_min: base.ms_min + ms[0],
        ms_max: base.ms_max + ms[ms.len() - 1],
        pass_ms,
        post_process: Some(step.describe()),
        timed_by,
        ..ResultRow::timed(
            &base.scene,
            RowKey::Post(name.to_string()),
            &base.backend,
            (base.width, base.height),
            base.runs,
            &Timings::default(),
        )
    };
    row.samples_per_pixel = base.samples_per_pixel;
    row.rays_per_pixel = base.rays_per_pixel;
    row.raster_samples_per_pixel = base.raster_samples_per_pixel;
    row.buffer_mib = base.buffer_mib;
    let mut quality = None;
    let noaa_quality = noaa.noaa.as_ref().and_then(|f| f.quality.as_ref());
    if let (Some(q), Some(img), Some(frame)) = (at.sq, &noaa.quality, noaa_quality) {
        let input = post::PostInput {
            scene: &at.job.name,
            image: img,
            frame,
        };
        let (out, _) = step.apply(&input)?;
        measure(&mut row, &out, q, plan, at.img_dir, at.bi == 0)?;
        quality = Some(out);
        // The same step on NoAA's frame at each further offset.
        let start = Instant::now();
        let frames = noaa.noaa.as_ref().map_or(&[][..], |f| &f.offsets[..]);
        for (oq, frame) in q.offsets.iter().zip(frames) {
            let image = Rgb8::from_frame(frame)?;
            let input = post::PostInput {
                scene: &at.job.name,
                image: &image,
                frame,
            };
            let (out, _) = step.apply(&input)?;
            row.errors_at.push(OffsetError::measure(
                oq.offset,
                &oq.reference,
                &out,
                &oq.classes,
            )?);
        }
        row.settle_offsets();
        *offsets_spent += start.elapsed();
    }
    Ok(Measured {
        row,
        quality,
        noaa: None,
    })
}

/// Measure the error of `img` (the quality render of `row`'s method) against
/// the scene's reference: mean, PSNR, edge and per-class FLIP, mean and
/// per-class SSIM; writes the image, its FLIP map and its `1 − SSIM` map
/// beside the reference.
fn measure(
    row: &mut ResultRow,
    img: &Rgb8,
    q: &SceneQuality,
    plan: &Plan,
    img_dir: &Path,
    first_backend: bool,
) -> Result<()> {
    let fl = subcone_metrics::flip(&q.reference, img)?;
    row.psnr_db = Some(subcone_metrics::psnr(&q.reference, img)?);
    row.edge_flip_mean = metrics::masked_mean(&fl.map, &q.edges);
    let ss = ssim::ssim(&q.reference, img)?;
    let first = plan.offsets.first().copied().unwrap_or((0.0, 0.0));
    row.errors_at = vec![OffsetError::of(first, &fl, &ss, &q.classes)];
    row.settle_offsets();
    row.quality_width = Some(img.width);
    row.quality_height = Some(img.height);
    row.reference = Some(plan.reference.to_string());
    row.image_digest = Some(answer::digest(img.width, img.height, &img.data));
    files::save_png(
        &img_dir.join(image_name(
            "",
            &row.method.to_string(),
            &row.backend,
            first_backend,
        )),
        img,
    )?;
    files::save_png(
        &img_dir.join(image_name(
            "flip_",
            &row.method.to_string(),
            &row.backend,
            first_backend,
        )),
        &fl.magma,
    )?;
    files::save_png(
        &img_dir.join(image_name(
            "ssim_",
            &row.method.to_string(),
            &row.backend,
            first_backend,
        )),
        &ss.image(img.width, img.height),
    )?;
    Ok(())
}

/// The file name of a method's image for `backend` (the first backend gets the
/// plain name).
fn image_name(prefix: &str, method: &str, backend: &str, first: bool) -> String {
    let m = file_safe(method);
    if first {
        format!("{prefix}{m}.png")
    } else {
        format!("{prefix}{m}-{}.png", file_safe(backend))
    }
}

/// The methods of the SRAA Table 1 sweep.
pub const SWEEP_METHODS: [Method; 3] = [NOAA, SRAA_RT, SSAA16];

/// Run the report: plan what applies, measure each scene (its methods, the
/// SMAA row, crops and plots), run the SRAA Table 1 sweep and the CPU
/// performance targets, then write the files.
pub fn run(args: &ReportArgs) -> Result<ReportSummary> {
    let start = Instant::now();
    let plan = Plan::new(args)?;
    std::fs::create_dir_all(&plan.out)
        .with_context(|| format!("cannot create output directory {}", plan.out.display()))?;
    let (jobs, unavailable) = load_scenes(args, &plan)?;
    plot::register_fonts()?;

    let (work, skipped) = applicable(&plan, &jobs, args.methods.is_empty());
    let sweep_job = jobs
        .iter()
        .find(|j| j.arg == SWEEP_SCENE && !j.sdf)
        .filter(|_| plan.sweep);
    let own_cpu;
    let cpu: &(dyn Backend + Send + Sync) = match plan.backends.iter().find(|(n, _)| n == "cpu") {
        Some((_, b)) => b.as_ref(),
        None => {
            own_cpu = subcone_cpu::CpuBackend::new();
            &own_cpu
        }
    };
    let mut runner = Runner {
        plan: &plan,
        cpu,
        progress: Progress::new(progress_length(&plan, &work, sweep_job.is_some())),
        references_rendered: 0,
        references_cached: 0,
        rows: Vec::new(),
        failures: Vec::new(),
        crops: Vec::new(),
        classes: Vec::new(),
        plots: Vec::new(),
        load: load::OtherCpu::default(),
        offsets_elapsed: Duration::ZERO,
    };
    for (i, methods) in &work {
        runner.scene(&jobs[*i], methods)?;
    }
    let sweep = match sweep_job {
        Some(job) => runner.sweep(job)?,
        None => Vec::new(),
    };
    let ao_sweep = match &plan.sraa_sweep {
        Some(spec) => runner.ao_sweep(&jobs, spec)?,
        None => ao_sweep::AoSweep::default(),
    };
    let motion = match plan.motion_frames {
        Some(frames) => runner.motion(&jobs, frames)?,
        None => motion::Motion::default(),
    };
    let (throughput, kernels) = runner.cpu_targets(&jobs);
    runner.progress.bar.finish_and_clear();

    let summary = ReportSummary {
        out_dir: plan.out.clone(),
        report_md: plan.out.join("report.md"),
        results_csv: plan.out.join("results.csv"),
        results_json: plan.out.join("results.json"),
        report_html: plan.out.join("report.html"),
        plots: runner.plots,
        rows: runner.rows,
        sweep,
        ao_sweep,
        motion,
        skipped,
        failures: runner.failures,
        unavailable_scenes: unavailable,
        crops: runner.crops,
        classes: runner.classes,
        references_rendered: runner.references_rendered,
        references_cached: runner.references_cached,
        throughput,
        kernels,
        error_offsets: ErrorOffsets {
            offsets: plan.offsets.clone(),
            divisor: plan.offset_divisor,
            reference: plan.offset_reference.to_string(),
            elapsed: runner.offsets_elapsed,
        },
        elapsed: start.elapsed(),
    };
    write_all(&summary, &context(&plan, &jobs, runner.load))?;
    Ok(summary)
}

/// Write `results.csv`, `results.json`, `report.md` and `report.html`.
fn write_all(s: &ReportSummary, ctx: &context::Context) -> Result<()> {
    reference::write_atomic(&s.results_csv, output::csv(&s.rows).as_bytes())?;
    let j = serde_json::to_string_pretty(&output::json(s, ctx))
        .map_err(|e| anyhow!("cannot encode results.json: {e}"))?;
    reference::write_atomic(&s.results_json, j.as_bytes())?;
    let md = output::markdown(s, ctx);
    reference::write_atomic(&s.report_md, md.as_bytes())?;
    html::write(s, ctx, &md)
}

/// What the output files say about the run besides its rows.
fn context(plan: &Plan, jobs: &[SceneJob], other_cpu: load::OtherCpu) -> context::Context {
    context::Context {
        other_cpu,
        mode: plan.mode,
        backends: plan.backends.iter().map(|b| b.0.clone()).collect(),
        backend_descriptions: plan.backends.iter().map(|b| b.1.describe()).collect(),
        runs: plan.runs,
        reference: plan.reference.to_string(),
        ao: plan.ao,
        scenes: jobs
            .iter()
            .map(|j| context::SceneInfo {
                name: j.name.clone(),
                arg: j.arg.clone(),
                sdf: j.sdf,
                timing_size: j.timing_size,
                quality_size: (plan.mode != Mode::TimingOnly).then_some(j.quality_size),
            })
            .collect(),
    }
}

/// Per scene (by index in `jobs`), each method that some backend renders,
/// with the backends that do (asked of [`Backend::supports`] before anything
/// renders), and the combinations skipped, with the reason.
fn applicable(
    plan: &Plan,
    jobs: &[SceneJob],
    default_methods: bool,
) -> (Vec<(usize, Vec<Applicable>)>, Vec<Skipped>) {
    let mut skipped = Vec::new();
    let mut work = Vec::new();
    let skip = |job: &SceneJob, method: String, backend: &str, reason: String| Skipped {
        scene: job.name.to_string(),
        method,
        backend: backend.into(),
        reason,
    };
    for (i, job) in jobs.iter().enumerate() {
        let mut ms = Vec::new();
        for m in &plan.methods {
            // ssaa16 on an SDF scene at 1280x720 costs minutes per run and is
            // not in the CTSS comparison (its Table 1 stops at 4x SS); the
            // default run leaves it out there, an explicit --method keeps it.
            if job.sdf && default_methods && m.supersamples() > 4 && plan.mode != Mode::Quick {
                skipped.push(skip(job, m.to_string(), "*", "left out of the default run on SDF scenes (minutes per frame at 1280x720; pass --method to include it)".into()));
                continue;
            }
            // No triangles to rasterise: a hybrid is its traced method there.
            if job.sdf && m.is_hybrid() {
                skipped.push(skip(job, m.to_string(), "*", format!("an SDF scene has no triangles to rasterise: {m} would trace its rays as {} does", m.traced())));
                continue;
            }
            let mut able = Vec::new();
            let mut refused = Vec::new();
            for (bi, (bname, backend)) in plan.backends.iter().enumerate() {
                match backend.supports(&job.scene, m) {
                    Ok(()) => able.push(bi),
                    Err(u) => refused.push((bname.as_str(), u)),
                }
            }
            // A refusal of the technique itself holds for every backend: one
            // line for all of them.
            let technique = |u: &Unsupported| matches!(u.reason, UnsupportedReason::Technique(_));
            if able.is_empty() && refused.iter().all(|(_, u)| technique(u)) {
                if let Some((_, u)) = refused.first() {
                    skipped.push(skip(job, m.to_string(), "*", u.reason.to_string()));
                }
            } else {
                for (bname, u) in refused {
                    skipped.push(skip(job, m.to_string(), bname, u.reason.to_string()));
                }
            }
            if !able.is_empty() {
                ms.push((*m, able));
            }
        }
        for p in &plan.post {
            if let PostPlan::Unavailable { name, reason } = p {
                skipped.push(skip(job, name.clone(), "*", reason.clone()));
            }
        }
        work.push((i, ms));
    }
    (work, skipped)
}

/// Renders the progress bar counts: per method and backend a warm-up (the
/// quality render when errors are measured) and one render in each timed
/// round, two per scene with errors (reference and masks), and the sweep's.
/// A second warm-up at the timing size adds itself to the length when it
/// happens; a method dropped after a failure counts its renders left as done.
fn progress_length(plan: &Plan, work: &[(usize, Vec<Applicable>)], sweep: bool) -> u64 {
    let quality = plan.mode != Mode::TimingOnly;
    let per_method = 1 + plan.runs as u64;
    let extra = plan.offsets.len().saturating_sub(1) as u64;
    let mut total: u64 = 0;
    for (_, ms) in work {
        let renders: u64 = ms.iter().map(|(_, b)| b.len() as u64).sum();
        total += renders * per_method;
        if quality && !ms.is_empty() {
            // Reference and masks, then a reference and classes and each
            // method's render at every further camera offset.
            total += 2 + extra * (2 + renders);
        }
    }
    if sweep {
        total +=
            (SWEEP_SIZES.len() * SWEEP_METHODS.len() * plan.backends.len()) as u64 * per_method;
    }
    total
}

/// One method on one backend, measured.
struct Measured {
    row: ResultRow,
    /// The quality image (when errors are measured).
    quality: Option<Rgb8>,
    /// NoAA's frames, the post-process rows' input (NoAA only).
    noaa: Option<NoaaFrames>,
}

/// The NoAA frames a post-process filters.
struct NoaaFrames {
    /// The last timed frame (no AOVs).
    timing: Frame,
    /// The quality render, with its AOVs (when errors are measured).
    quality: Option<Frame>,
    /// The renders at the camera offsets after the first, with AOVs.
    offsets: Vec<Frame>,
}

/// The per-pixel figures of a timed frame.
#[derive(Clone, Copy, Debug)]
struct FrameFigures {
    /// Shading evaluations per pixel.
    spp: f64,
    /// Rays of every kind per pixel.
    rays_per_pixel: f64,
    /// Rasterised primary samples per pixel.
    raster_spp: f64,
    /// Frame buffers, MiB.
    buffer_mib: f64,
}

impl FrameFigures {
    fn of(f: &Frame) -> Self {
        let px = (f.width as f64 * f.height as f64).max(1.0);
        FrameFigures {
            spp: f.stats.shaded_samples as f64 / px,
            rays_per_pixel: f.stats.rays.total() as f64 / px,
            raster_spp: f.stats.raster_samples as f64 / px,
            buffer_mib: f.stats.buffer_bytes() as f64 / (1u64 << 20) as f64,
        }
    }
}

/// A method of one backend between its warm-ups and its row. Its quality
/// image waits here, as 8-bit RGB, until the rounds are over: the error
/// measurement (FLIP, image files) stays out of the timed rounds.
struct Contender {
    method: Method,
    /// The quality render, when errors are measured and it rendered.
    quality: Option<Rgb8>,
    /// Mean of the quality render's samples-per-pixel AOV, when it has one.
    quality_spp: Option<f64>,
    /// The rounds so far, in round order.
    timings: Timings,
    /// Figures of the last timed frame.
    figures: Option<FrameFigures>,
    /// The last timed frame, kept for NoAA only (the post-process rows'
    /// input): one frame, not one per method, stays in memory during the
    /// rounds.
    last_noaa: Option<Frame>,
    /// The quality render with its AOVs, kept for NoAA only when the run has
    /// post-process rows.
    noaa_quality: Option<Frame>,
    /// A render failed: no row, no further rounds.
    dropped: bool,
}

impl Runner<'_> {
    /// Measure every applicable method of one scene on every backend, then
    /// the ratios to NoAA, the crops and the plots.
    ///
    /// Per backend: every method's warm-ups ([`Runner::warm_up`]), then the
    /// timed rounds of all of them ([`Runner::rounds`]), then each surviving
    /// method's row and error ([`Runner::finish`]) and the SMAA row.
    fn scene(&mut self, job: &SceneJob, methods: &[Applicable]) -> Result<()> {
        let plan = self.plan;
        if methods.is_empty() {
            self.progress
                .note(&format!("{}: no method applies, skipped", job.name));
            return Ok(());
        }
        let quality = plan.mode != Mode::TimingOnly;
        self.progress.note(&format!(
            "{}: {} methods, timing at {}x{} in {} rounds{}",
            job.name,
            methods.len(),
            job.timing_size.0,
            job.timing_size.1,
            plan.runs,
            if quality {
                format!(
                    ", error at {}x{} against {}",
                    job.quality_size.0, job.quality_size.1, plan.reference
                )
            } else {
                String::new()
            }
        ));
        let img_dir = plan.out.join("images").join(job.name.as_str());
        let sq = if quality {
            self.scene_quality(job, &img_dir)?
        } else {
            None
        };
        // Quality images of the first backend, for the crops.
        let mut crop_images: Vec<(RowKey, Rgb8)> = Vec::new();
        let first = self.rows.len();
        for (bi, (_, backend)) in plan.backends.iter().enumerate() {
            let mut contenders = Vec::new();
            for (m, _) in methods.iter().filter(|(_, able)| able.contains(&bi)) {
                if let Some(c) = self.warm_up(job, bi, backend.as_ref(), m, sq.is_some())? {
                    contenders.push(c);
                }
            }
            self.rounds(job, bi, backend.as_ref(), &mut contenders)?;
            let mut noaa: Option<Measured> = None;
            for c in contenders.into_iter().filter(|c| !c.dropped) {
                // `noaa` itself: its hybrid twin and TAA share its
                // technique, but the post-process rows filter NoAA's frame.
                let is_noaa = c.method == NOAA;
                let done = self.finish(job, bi, backend.as_ref(), c, sq.as_ref(), &img_dir)?;
                if let (0, Some(img)) = (bi, &done.quality) {
                    crop_images.push((done.row.method.clone(), img.clone()));
                }
                self.rows.push(done.row.clone());
                if is_noaa {
                    noaa = Some(done);
                }
            }
            if let Some(noaa) = noaa {
                let at = PostAt {
                    job,
                    bi,
                    sq: sq.as_ref(),
                    img_dir: &img_dir,
                };
                for (name, img) in self.post_rows(&at, backend.as_ref(), noaa)? {
                    crop_images.push((name, img));
                }
            }
        }
        ratios_to_noaa(&mut self.rows[first..]);
        if let Some(q) = &sq {
            let regions = write_crops(q, &crop_images, plan, &img_dir)?;
            self.crops.push(SceneCrops {
                scene: job.name.to_string(),
                regions,
            });
            self.classes.push(SceneClasses {
                scene: job.name.to_string(),
                masks: q.classes.clone(),
            });
        }
        let scene_rows: Vec<&ResultRow> = self.rows[first..].iter().collect();
        self.plots.extend(plot::scene_plots(
            &plan.out.join("plots"),
            &job.name,
            &scene_rows,
        )?);
        Ok(())
    }

    /// The post-process rows of one scene and backend, pushed to the rows
    /// (a failing step listed, with `--keep-going`), and the quality images
    /// of the first backend's, for the crops. A step that reads AOVs gets a
    /// NoAA frame rendered with them at the timing size, once for all such
    /// steps and apart from the rounds; the others get NoAA's last timed
    /// frame.
    fn post_rows(
        &mut self,
        at: &PostAt<'_>,
        backend: &dyn Backend,
        noaa: Measured,
    ) -> Result<Vec<(RowKey, Rgb8)>> {
        let plan = self.plan;
        let (job, bname) = (at.job, &plan.backends[at.bi].0);
        let steps: Vec<&dyn post::PostProcess> = plan
            .post
            .iter()
            .filter_map(|p| match p {
                PostPlan::On(step) => Some(step.as_ref()),
                PostPlan::Unavailable { .. } => None,
            })
            .collect();
        let Some(frames) = &noaa.noaa else {
            return Ok(Vec::new());
        };
        let with_aovs = if steps.iter().any(|s| s.needs_aovs()) {
            self.progress
                .bar
                .set_message(format!("{}: NoAA with AOVs on {bname}", job.name));
            let (tw, th) = job.timing_size;
            let mut settings = plan.settings(tw, th, job.sdf);
            settings.aovs = true;
            Some(render(backend, &job.scene, &NOAA, &settings).map(|(f, _)| f))
        } else {
            None
        };
        let mut crops = Vec::new();
        for step in steps {
            let name = step.name();
            self.progress
                .bar
                .set_message(format!("{}: {name} on the {bname} NoAA frame", job.name));
            let timing = match (step.needs_aovs(), &with_aovs) {
                (true, Some(Ok(f))) => Ok(f),
                (true, Some(Err(e))) => Err(anyhow!("the NoAA frame with AOVs: {e:#}")),
                _ => Ok(&frames.timing),
            };
            let spent = &mut self.offsets_elapsed;
            match timing.and_then(|t| post_measured(step, &noaa, t, at, plan, spent)) {
                Ok(done) => {
                    if let (0, Some(img)) = (at.bi, done.quality) {
                        crops.push((RowKey::Post(name.to_string()), img));
                    }
                    self.rows.push(done.row);
                }
                Err(e) => self.fail(Failure::new(&job.name, name, bname.clone(), &e))?,
            }
        }
        Ok(crops)
    }

    /// The scene's reference and masks, with the reference and edge mask
    /// written beside the images; `None` (with `--keep-going`) when the
    /// reference fails.
    fn scene_quality(&mut self, job: &SceneJob, img_dir: &Path) -> Result<Option<SceneQuality>> {
        std::fs::create_dir_all(img_dir)
            .with_context(|| format!("cannot create {}", img_dir.display()))?;
        match self.quality(job) {
            Ok(mut q) => {
                match self.offset_qualities(job) {
                    Ok(o) => q.offsets = o,
                    Err(e) => {
                        let what =
                            format!("reference {} at the camera offsets", self.plan.reference);
                        self.fail(Failure::new(&job.name, what, "cpu", &e))?;
                    }
                }
                files::save_png(&img_dir.join("reference.png"), &q.reference)?;
                files::save_png(
                    &img_dir.join("edge_mask.png"),
                    &files::mask_image(q.reference.width, q.reference.height, &q.edges),
                )?;
                Ok(Some(q))
            }
            Err(e) => {
                let what = format!("reference {}", self.plan.reference);
                self.fail(Failure::new(&job.name, what, "cpu", &e))?;
                Ok(None)
            }
        }
    }

    /// A method's warm-ups on one backend, before the rounds; with `errors`
    /// its quality render, kept for the error. `None` (with `--keep-going`)
    /// when the warm-up at the timing size fails.
    ///
    /// The warm-up is a render the row needs anyway: the quality render when
    /// errors are measured (at the quality size), else a render at the
    /// timing size. It runs the method's code on the scene's tree and the
    /// thread pool once before any clock starts. A frame predicted shorter
    /// than [`timing::SHORT_RENDER`] gets a warm-up at the timing size as
    /// well ([`timing::warm_up_at_timing_size`]). A failed quality render is
    /// listed and the method is still timed, without an error.
    fn warm_up(
        &mut self,
        job: &SceneJob,
        bi: usize,
        backend: &dyn Backend,
        m: &Method,
        errors: bool,
    ) -> Result<Option<Contender>> {
        let plan = self.plan;
        let (mname, bname) = (m.to_string(), plan.backends[bi].0.clone());
        self.progress
            .bar
            .set_message(format!("{}: {mname} on {bname}, warm-up", job.name));
        let (tw, th) = job.timing_size;
        let (qw, qh) = job.quality_size;
        let (mut quality, mut quality_spp, mut quality_wall) = (None, None, None);
        let mut noaa_quality = None;
        if errors {
            let mut qs = plan.settings(qw, qh, job.sdf);
            qs.aovs = true;
            let r = render(backend, &job.scene, m, &qs);
            self.progress.bar.inc(1);
            match r {
                Ok((qf, wall)) => {
                    quality_wall = Some(wall);
                    quality_spp = qf
                        .samples_per_pixel
                        .as_ref()
                        .filter(|s| !s.is_empty())
                        .map(|s| s.iter().map(|&v| v as f64).sum::<f64>() / s.len() as f64);
                    quality = Some(Rgb8::from_frame(&qf)?);
                    if *m == NOAA && !plan.post.is_empty() {
                        noaa_quality = Some(qf);
                    }
                }
                Err(e) => {
                    let what = format!("{mname} (quality render)");
                    self.fail(Failure::new(&job.name, what, bname.clone(), &e))?;
                }
            }
        }
        if timing::warm_up_at_timing_size(quality_wall, (tw, th), (qw, qh)) {
            if errors {
                // Not in the bar's length, which counts one warm-up.
                self.progress.bar.inc_length(1);
            }
            let warm = render(backend, &job.scene, m, &plan.settings(tw, th, job.sdf));
            self.progress.bar.inc(1);
            if let Err(e) = warm {
                self.fail(Failure::new(&job.name, mname, bname, &e))?;
                self.progress.bar.inc(plan.runs as u64);
                return Ok(None);
            }
        }
        Ok(Some(Contender {
            method: *m,
            quality,
            quality_spp,
            timings: Timings::default(),
            figures: None,
            last_noaa: None,
            noaa_quality,
            dropped: false,
        }))
    }

    /// The timed rounds of one backend's methods: `plan.runs` rounds, each
    /// rendering every method not dropped once at the timing size, round `r`
    /// starting at method `r mod n` ([`timing::round_order`]), so the
    /// machine's drift falls on every method alike. A method whose render
    /// fails is dropped (with `--keep-going`; else the run stops) and its
    /// renders left are counted as done. Other processes' CPU time over the
    /// rounds is added to `self.load`.
    fn rounds(
        &mut self,
        job: &SceneJob,
        bi: usize,
        backend: &dyn Backend,
        cs: &mut [Contender],
    ) -> Result<()> {
        if cs.is_empty() {
            return Ok(());
        }
        let plan = self.plan;
        let bname = &plan.backends[bi].0;
        let (tw, th) = job.timing_size;
        let settings = plan.settings(tw, th, job.sdf);
        let runs = plan.runs as usize;
        let started = self.load.start();
        for r in 0..runs {
            for i in timing::round_order(cs.len(), r) {
                let c = &mut cs[i];
                if c.dropped {
                    continue;
                }
                self.progress.bar.set_message(format!(
                    "{}: {} on {bname}, round {}/{runs}",
                    job.name,
                    c.method,
                    r + 1
                ));
                let result = render(backend, &job.scene, &c.method, &settings);
                self.progress.bar.inc(1);
                match result {
                    Ok((f, wall)) => {
                        c.timings.push(wall, &f);
                        c.figures = Some(FrameFigures::of(&f));
                        if c.method == NOAA {
                            c.last_noaa = Some(f);
                        }
                    }
                    Err(e) => {
                        c.dropped = true;
                        let failure = Failure::new(&job.name, c.method.to_string(), bname, &e);
                        self.progress.bar.inc((runs - r - 1) as u64);
                        self.fail(failure)?;
                    }
                }
            }
        }
        self.load.stop(started);
        Ok(())
    }

    /// The row of a method that went through every round: its times over
    /// the rounds, the figures of its last timed frame, and with `sq` its
    /// error, measured on its quality image (images written beside the
    /// reference).
    fn finish(
        &mut self,
        job: &SceneJob,
        bi: usize,
        backend: &dyn Backend,
        c: Contender,
        sq: Option<&SceneQuality>,
        img_dir: &Path,
    ) -> Result<Measured> {
        let plan = self.plan;
        let (mname, bname) = (c.method.to_string(), &plan.backends[bi].0);
        let Some(fig) = c.figures else {
            bail!("{} / {mname} on {bname}: no timed round", job.name);
        };
        let mut row = ResultRow::timed(
            &job.name,
            c.method.into(),
            bname,
            job.timing_size,
            c.timings.wall_ms.len() as u32,
            &c.timings,
        );
        row.round_ms = c.timings.wall_ms.clone();
        row.samples_per_pixel = c.quality_spp.unwrap_or(fig.spp);
        row.rays_per_pixel = fig.rays_per_pixel;
        row.raster_samples_per_pixel = fig.raster_spp;
        row.buffer_mib = fig.buffer_mib;
        let mut noaa = c.last_noaa.map(|timing| NoaaFrames {
            timing,
            quality: c.noaa_quality,
            offsets: Vec::new(),
        });
        let quality = match (sq, c.quality) {
            (Some(q), Some(img)) => {
                measure(&mut row, &img, q, plan, img_dir, bi == 0)?;
                let frames = self.measure_offsets(job, bi, backend, &c.method, &mut row, q)?;
                if let Some(n) = &mut noaa {
                    n.offsets = frames;
                }
                Some(img)
            }
            _ => None,
        };
        Ok(Measured { row, quality, noaa })
    }

    /// The error of `method` at the camera offsets after the first: a
    /// quality render from each offset's camera, measured against that
    /// offset's reference and classes, pushed to `row.errors_at`, and the
    /// row's means set over the offsets. Returns NoAA's renders (with
    /// AOVs) when the run has post-process rows, which filter them. A
    /// failed render is listed (with `--keep-going`) and ends the row's
    /// offsets there.
    fn measure_offsets(
        &mut self,
        job: &SceneJob,
        bi: usize,
        backend: &dyn Backend,
        method: &Method,
        row: &mut ResultRow,
        q: &SceneQuality,
    ) -> Result<Vec<Frame>> {
        let start = Instant::now();
        let plan = self.plan;
        let keep = *method == NOAA && !plan.post.is_empty();
        let mut frames = Vec::new();
        for oq in &q.offsets {
            self.progress.bar.set_message(format!(
                "{}: {method} on {}, offset {}",
                job.name,
                plan.backends[bi].0,
                offsets::label(oq.offset)
            ));
            let mut settings = plan.settings(oq.size.0, oq.size.1, job.sdf);
            settings.aovs = keep;
            let r = render_from(backend, &job.scene, &oq.camera, method, &settings);
            self.progress.bar.inc(1);
            match r {
                Ok((f, _)) => {
                    let img = Rgb8::from_frame(&f)?;
                    row.errors_at.push(OffsetError::measure(
                        oq.offset,
                        &oq.reference,
                        &img,
                        &oq.classes,
                    )?);
                    if keep {
                        frames.push(f);
                    }
                }
                Err(e) => {
                    let what = format!("{method} (offset {})", offsets::label(oq.offset));
                    let bname = plan.backends[bi].0.clone();
                    self.fail(Failure::new(&job.name, what, bname, &e))?;
                    break;
                }
            }
        }
        row.settle_offsets();
        self.offsets_elapsed += start.elapsed();
        Ok(frames)
    }

    /// The SRAA Table 1 sweep on `job`: timing only, 256² to 1024².
    fn sweep(&mut self, job: &SceneJob) -> Result<Vec<ResultRow>> {
        let plan = self.plan;
        self.progress.note(&format!(
            "{}: SRAA Table 1 sweep (noaa, sraa-rt, ssaa16 at 256² to 1024²)",
            job.name
        ));
        let methods: Vec<Method> = SWEEP_METHODS.to_vec();
        let mut sweep = Vec::new();
        for (bname, backend) in &plan.backends {
            for side in SWEEP_SIZES {
                for m in &methods {
                    self.progress.bar.set_message(format!(
                        "sweep {}: {m} at {side}x{side} on {bname}",
                        job.name
                    ));
                    let settings = plan.settings(side, side, job.sdf);
                    let mut t = Timings::default();
                    let mut ok = true;
                    for k in 0..=plan.runs {
                        match render(backend.as_ref(), &job.scene, m, &settings) {
                            Ok((f, wall)) if k > 0 => t.push(wall, &f),
                            Ok(_) => {}
                            Err(e) => {
                                let what = format!("{m} (sweep at {side}x{side})");
                                self.fail(Failure::new(&job.name, what, bname.clone(), &e))?;
                                ok = false;
                            }
                        }
                        self.progress.bar.inc(1);
                        if !ok {
                            break;
                        }
                    }
                    if ok {
                        let mut row = ResultRow::timed(
                            &job.name,
                            (*m).into(),
                            bname,
                            (side, side),
                            plan.runs,
                            &t,
                        );
                        row.samples_per_pixel = f64::NAN;
                        row.rays_per_pixel = f64::NAN;
                        row.buffer_mib = f64::NAN;
                        sweep.push(row);
                    }
                }
            }
        }
        Ok(sweep)
    }

    /// The CPU-side performance targets (when the CPU backend is in the run):
    /// ray throughput on every triangle scene at its timing size, and ns per
    /// kernel call.
    fn cpu_targets(
        &mut self,
        jobs: &[SceneJob],
    ) -> (Vec<ThroughputRow>, Vec<kernel_timing::KernelTiming>) {
        let mut throughput = Vec::new();
        if !self.plan.backends.iter().any(|b| b.0 == "cpu") {
            return (throughput, Vec::new());
        }
        // Every path the machine runs, not only the one it picks: a path
        // chosen at run time must never be slower than the baseline, and a
        // figure from one path says nothing about another (issue 37).
        for isa in subcone_cpu::isa::Isa::supported() {
            let cpu = subcone_cpu::CpuBackend::new().with_isa(isa);
            for job in jobs.iter().filter(|j| !j.sdf) {
                self.progress.note(&format!(
                    "{}: ray throughput on the {} path",
                    job.name,
                    isa.name()
                ));
                let (w, h) = job.timing_size;
                match subcone_cpu::throughput::RayWorkload::new(&cpu, &job.scene, w, h) {
                    Ok(work) => throughput.push(ThroughputRow {
                        scene: job.name.to_string(),
                        isa,
                        width: w,
                        height: h,
                        rates: work.measure(self.plan.runs as usize),
                    }),
                    Err(e) => self
                        .progress
                        .note(&format!("{}: no ray throughput: {e}", job.name)),
                }
            }
        }
        self.progress.note("kernels: ns per call");
        (throughput, kernel_timing::measure())
    }
}

/// `ratio_to_noaa`, `ratio_min` and `ratio_max` of every row of one scene,
/// against NoAA on the same backend.
///
/// A row timed in NoAA's rounds (its `round_ms` pairs with NoAA's, round by
/// round) gets the median, min and max over the rounds of its time over
/// NoAA's in the same round ([`timing::round_ratios`]): the drift between
/// rounds cancels in each ratio. A row that was not (the `smaa` row, whose
/// post-process is timed on its own) keeps the ratio of medians, without a
/// range. No NoAA row on the backend, no ratio.
fn ratios_to_noaa(rows: &mut [ResultRow]) {
    let noaa: Vec<(String, f64, Vec<f64>)> = rows
        .iter()
        .filter(|r| r.method == NOAA)
        .map(|r| (r.backend.clone(), r.ms_median, r.round_ms.clone()))
        .collect();
    for r in rows.iter_mut() {
        let Some((_, median, rounds)) = noaa.iter().find(|(b, ..)| *b == r.backend) else {
            continue;
        };
        if let Some(s) = timing::round_ratios(&r.round_ms, rounds) {
            r.ratio_to_noaa = Some(s.median);
            r.ratio_min = Some(s.min);
            r.ratio_max = Some(s.max);
        } else if *median > 0.0 && median.is_finite() {
            r.ratio_to_noaa = Some(r.ms_median / median);
        }
    }
}

/// Choose the scene's crop regions and write the zoomed panels (NoAA first,
/// then every method, then the reference) and the overview.
fn write_crops(
    q: &SceneQuality,
    images: &[(RowKey, Rgb8)],
    plan: &Plan,
    img_dir: &Path,
) -> Result<Vec<crops::Region>> {
    let noaa_err = metrics::luma_difference(&q.noaa_error_base, &q.reference)?;
    let regions = crops::choose_regions(&crops::RegionInputs {
        width: q.reference.width,
        height: q.reference.height,
        edges: &q.edges,
        geometric: &q.geometric,
        noaa_error: &noaa_err,
        shadow: q.shadow.as_deref(),
        reflective: q.reflective.as_deref(),
    })?;
    let mut tiles: Vec<(String, &Rgb8)> = Vec::new();
    if let Some((n, img)) = images.iter().find(|(n, _)| *n == NOAA) {
        tiles.push((n.to_string(), img));
    }
    for (n, img) in images.iter().filter(|(n, _)| *n != NOAA) {
        tiles.push((n.to_string(), img));
    }
    tiles.push((format!("reference ({})", plan.reference), &q.reference));
    for r in &regions {
        let zoomed: Vec<(String, Rgb8)> = tiles
            .iter()
            .map(|(n, img)| Ok((n.clone(), crops::zoom(img, &r.window)?)))
            .collect::<Result<_>>()?;
        let panel = plot::label_panel(&zoomed)?;
        files::save_png(&img_dir.join(format!("crops_{}.png", r.kind)), &panel)?;
    }
    files::save_png(
        &img_dir.join("crops_overview.png"),
        &crops::outline(&q.reference, &regions),
    )?;
    Ok(regions)
}

/// The directory of a scene's images.
pub fn image_dir(out: &Path, scene: &str) -> PathBuf {
    out.join("images").join(file_safe(scene))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(method: &str, backend: &str, ms_median: f64, rounds: &[f64]) -> ResultRow {
        let mut r = ResultRow::timed(
            "s",
            crate::key::named(method),
            backend,
            (4, 4),
            3,
            &Timings::default(),
        );
        r.ms_median = ms_median;
        r.round_ms = rounds.to_vec();
        r
    }

    #[test]
    fn ratios_per_round_with_range_and_medians_without_rounds() {
        let mut rows = vec![
            // NoAA drifts from 10 to 20 ms over the rounds.
            row("noaa", "cpu", 15.0, &[10.0, 20.0, 15.0]),
            // 1.1, 1.3, 1.2 × NoAA in its rounds; its median time (18) over
            // NoAA's (15) would say 1.2 by luck, not by round.
            row("ctss", "cpu", 18.0, &[11.0, 26.0, 18.0]),
            // The smaa row: not in the rounds, ratio of medians.
            row("smaa", "cpu", 16.5, &[]),
            // Another backend without NoAA: no ratio.
            row("ctss", "wgpu", 2.0, &[2.0, 2.0, 2.0]),
        ];
        ratios_to_noaa(&mut rows);
        let close = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-12);
        assert!(close(rows[0].ratio_to_noaa, 1.0));
        assert!(close(rows[0].ratio_min, 1.0) && close(rows[0].ratio_max, 1.0));
        assert!(
            close(rows[1].ratio_to_noaa, 1.2),
            "{:?}",
            rows[1].ratio_to_noaa
        );
        assert!(close(rows[1].ratio_min, 1.1), "{:?}", rows[1].ratio_min);
        assert!(close(rows[1].ratio_max, 1.3), "{:?}", rows[1].ratio_max);
        assert!(close(rows[2].ratio_to_noaa, 1.1));
        assert_eq!((rows[2].ratio_min, rows[2].ratio_max), (None, None));
        assert_eq!(rows[3].ratio_to_noaa, None);
    }

    #[test]
    fn the_median_of_ratios_is_not_the_ratio_of_medians() {
        // The method is 2× NoAA in two rounds of three; NoAA's slow round
        // fell on the method's fast one. Ratio of medians: 20 / 20 = 1;
        // per-round ratios 2, 2, 0.5: median 2.
        let mut rows = vec![
            row("noaa", "cpu", 20.0, &[10.0, 20.0, 40.0]),
            row("sraa", "cpu", 20.0, &[20.0, 40.0, 20.0]),
        ];
        ratios_to_noaa(&mut rows);
        assert_eq!(rows[1].ratio_to_noaa, Some(2.0));
        assert_eq!(
            (rows[1].ratio_min, rows[1].ratio_max),
            (Some(0.5), Some(2.0))
        );
    }

    #[test]
    fn where_sraa_pays_runs_short_in_the_default_report_and_full_when_asked() {
        let plan = |args: ReportArgs| Plan::new(&args).unwrap().sraa_sweep;
        assert_eq!(
            plan(ReportArgs::default()),
            Some(ao_sweep::SweepSpec::default_report())
        );
        let asked = ReportArgs {
            sraa_sweep: true,
            ..Default::default()
        };
        assert_eq!(plan(asked), Some(ao_sweep::SweepSpec::full()));
        for args in [
            ReportArgs {
                quick: true,
                ..Default::default()
            },
            ReportArgs {
                size: Some("64x64".into()),
                ..Default::default()
            },
            ReportArgs {
                no_sweep: true,
                ..Default::default()
            },
            ReportArgs {
                methods: vec!["noaa".into(), "ssaa4".into()],
                ..Default::default()
            },
        ] {
            assert_eq!(plan(args), None);
        }
    }

    #[test]
    fn errors_are_measured_at_the_offsets_asked() {
        let plan = |args: ReportArgs| Plan::new(&args);
        // The default report: 4 offsets, the further ones at half size
        // against ssaa64.
        let p = plan(ReportArgs::default()).unwrap();
        assert_eq!(p.offsets, offsets::ERROR_OFFSETS.to_vec());
        assert_eq!(p.offset_divisor, offsets::FULL_OFFSET_DIVISOR);
        assert_eq!(p.offset_reference, offsets::FULL_OFFSET_REFERENCE);
        // The quick report: every offset at its size, its own reference.
        let quick = ReportArgs {
            quick: true,
            ..Default::default()
        };
        let p = plan(quick.clone()).unwrap();
        assert_eq!((p.offsets.len(), p.offset_divisor), (4, 1));
        assert_eq!(p.offset_reference, p.reference);
        let two = ReportArgs {
            error_offsets: Some(2),
            ..quick.clone()
        };
        assert_eq!(
            plan(two).unwrap().offsets,
            offsets::ERROR_OFFSETS[..2].to_vec()
        );
        for k in [0, 5] {
            let bad = ReportArgs {
                error_offsets: Some(k),
                ..quick.clone()
            };
            let e = plan(bad).err().expect("an error");
            assert!(e.to_string().contains("--error-offsets"), "{e}");
        }
        let timing = ReportArgs {
            timing_only: true,
            ..Default::default()
        };
        assert!(plan(timing).unwrap().offsets.is_empty());
    }

    #[test]
    fn progress_counts_a_warm_up_and_every_round() {
        let args = ReportArgs {
            quick: true,
            runs: Some(4),
            methods: vec!["noaa".into(), "sraa".into()],
            ..Default::default()
        };
        let plan = Plan::new(&args).unwrap();
        let noaa = NOAA;
        // Scene 0: two methods on backend 0; scene 1: nothing applies.
        let work = vec![(0, vec![(noaa, vec![0]), (noaa, vec![0])]), (1, vec![])];
        // 2 methods × (1 warm-up + 4 rounds) + reference and masks, then
        // at each of the 3 further camera offsets a reference, classes and
        // each method's render.
        assert_eq!(plan.offsets.len(), 4);
        assert_eq!(
            progress_length(&plan, &work, false),
            2 * 5 + 2 + 3 * (2 + 2)
        );
    }
}
