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

// The stages of `run`, in order: the plan (`plan`: what the arguments ask
// for; `scenes`: the scenes; `work`: what applies to each); per scene
// (`scene`), on the runner's state (`runner`) and its renders (`render`),
// the reference and classes (`quality`), every method's warm-ups and the
// timed rounds (`rounds`), each method's row and error (`measure`) and the
// post-process rows (`post_rows`); then the SRAA Table 1 sweep (`sweep`)
// and the CPU targets (`cpu_targets`). What they produce: the rows (`row`)
// and the run's summary (`summary`).
mod cpu_targets;
mod measure;
mod plan;
mod post_rows;
mod quality;
mod render;
mod rounds;
mod row;
mod runner;
mod scene;
mod scenes;
mod summary;
mod sweep;
mod work;

use std::time::{Duration, Instant};

use anyhow::{anyhow, Context, Result};
use subcone_scene::Backend;

use plan::Plan;
use runner::Progress;
use work::{applicable, load_scenes, progress_length};

/// The built-in scenes of the papers, which the report runs by default:
/// triangle scenes (SRAA) then SDF scenes (CTSS). Names that do not load are
/// skipped with a note.
pub use subcone_scene::builtin::PAPER_SCENES;

pub use args::ReportArgs;
pub use plan::{
    default_methods, Mode, QUICK_SIZE, SDF_QUALITY_SIZE, SDF_TIMING_SIZE, SMAA,
    TRIANGLE_QUALITY_SIZE, TRIANGLE_TIMING_SIZE,
};
pub use row::{OffsetError, ResultRow};
pub use scenes::{file_safe, image_dir, paper_scenes, SceneJob, Unavailable, QUICK_EXTRA_SCENES};
pub use summary::{
    ErrorOffsets, Failure, ReportSummary, SceneClasses, SceneCrops, Skipped, ThroughputRow,
};
pub use sweep::{SWEEP_METHODS, SWEEP_SCENE, SWEEP_SIZES};

// The runner and its renders, for the stages that extend it (`ao_sweep`,
// `motion`).
pub(crate) use render::{classes_at, render, render_from};
pub(crate) use runner::Runner;

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
            reference: plan.reference.to_string(),
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
        offsets: plan.offsets.clone(),
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
