//! The run's plan: what [`ReportArgs`] asks for, resolved and validated
//! (mode, backends, methods, post-process rows, sizes, rounds, camera
//! offsets), and the defaults it falls back on.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::{anyhow, bail, Context, Result};
use subcone_scene::{Backend, Method, RenderSettings};

use crate::args::ReportArgs;
use crate::named::{NOAA, SRAA_RT};
use crate::{ao_sweep, motion, offsets, post, setup, smaa};

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

/// Everything a run needs, resolved and validated from [`ReportArgs`].
pub(crate) struct Plan {
    pub(crate) mode: Mode,
    pub(crate) out: PathBuf,
    pub(crate) cache: PathBuf,
    pub(crate) backends: Vec<(String, Box<dyn Backend + Send + Sync>)>,
    pub(crate) methods: Vec<Method>,
    pub(crate) runs: u32,
    pub(crate) reference: Method,
    pub(crate) size: Option<(u32, u32)>,
    pub(crate) sweep: bool,
    pub(crate) refresh: bool,
    pub(crate) keep_going: bool,
    /// The post-process rows, in table order after the methods.
    pub(crate) post: Vec<PostPlan>,
    /// Ambient-occlusion rays per shaded point of every render (`--ao`).
    pub(crate) ao: u32,
    /// The "Where SRAA pays" section, when it runs: the default report's
    /// short sweep, or `--sraa-sweep`'s full one.
    pub(crate) sraa_sweep: Option<ao_sweep::SweepSpec>,
    /// Frames of the motion section, when it runs.
    pub(crate) motion_frames: Option<u32>,
    /// Camera offsets the error is measured at (a prefix of
    /// [`offsets::ERROR_OFFSETS`]), every one at the quality size against
    /// the run's reference.
    pub(crate) offsets: Vec<(f32, f32)>,
}

/// A method that some backend renders on a scene, with the indices (in the
/// plan) of the backends that do.
pub(crate) type Applicable = (Method, Vec<usize>);

/// A post-process row of the run ([`post`](mod@post)).
pub(crate) enum PostPlan {
    /// The step, ready.
    On(Box<dyn post::PostProcess>),
    /// Asked for, but it cannot run here (SMAA without an adapter): its name
    /// and the reason, listed under Skipped.
    Unavailable { name: String, reason: String },
}

impl PostPlan {
    /// The `smaa` row: SMAA 1x on the shared GPU, or the reason it cannot
    /// run (an error instead when `SUBCONE_REQUIRE_GPU` is set).
    pub(crate) fn smaa() -> Result<PostPlan> {
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
    pub(crate) fn all(names: &[String], args: &ReportArgs) -> Result<Vec<PostPlan>> {
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

pub(crate) fn parse_backends(list: &str) -> Result<Vec<(String, Box<dyn Backend + Send + Sync>)>> {
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

pub(crate) fn parse_method(s: &str, what: &str) -> Result<Method> {
    s.parse::<Method>().map_err(|e| anyhow!("{what}: {e}"))
}

/// The run mode `args` asks for: `--timing-only` wins over `--quick`.
fn mode_of(args: &ReportArgs) -> Mode {
    match (args.quick, args.timing_only) {
        (_, true) => Mode::TimingOnly,
        (true, false) => Mode::Quick,
        (false, false) => Mode::Full,
    }
}

/// The names `--method` gives, trimmed, blanks dropped ([`default_methods`]
/// when none is given); an error when only blanks are.
fn method_names(args: &ReportArgs) -> Result<Vec<String>> {
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
    Ok(names)
}

/// The methods the run renders, in the order named, once each: every name
/// that is not a post-process row, and NoAA first when a post-process
/// needs its frame but `names` does not ask for it.
fn methods_of(names: &[String], post: &[PostPlan]) -> Result<Vec<Method>> {
    let mut methods: Vec<Method> = Vec::new();
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
    Ok(methods)
}

/// The `--size` asked for, checked to be a size renders accept.
fn size_of(args: &ReportArgs) -> Result<Option<(u32, u32)>> {
    Ok(match &args.size {
        Some(s) => {
            let (w, h) = setup::parse_size(s)?;
            RenderSettings::new(w, h)
                .validate()
                .map_err(|e| anyhow!("--size {s}: {e}"))?;
            Some((w, h))
        }
        None => None,
    })
}

/// The frames of the motion section when it runs (asked with `--motion`,
/// always in quick mode): `--motion-frames` or the mode's default, 2 to
/// 1000. An error with `--timing-only`, which has no references to compare
/// with.
fn motion_frames_of(args: &ReportArgs, mode: Mode) -> Result<Option<u32>> {
    if args.motion || mode == Mode::Quick {
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
        Ok(Some(frames))
    } else {
        Ok(None)
    }
}

/// The camera offsets the error is measured at: the first `--error-offsets`
/// of [`offsets::ERROR_OFFSETS`] (all by default), none in timing-only mode.
fn error_offsets_of(args: &ReportArgs, mode: Mode) -> Result<Vec<(f32, f32)>> {
    Ok(match (mode, args.error_offsets) {
        (Mode::TimingOnly, _) => Vec::new(),
        (_, Some(k)) if !(1..=offsets::ERROR_OFFSETS.len()).contains(&k) => bail!(
            "--error-offsets {k}: expected 1 to {}",
            offsets::ERROR_OFFSETS.len()
        ),
        (_, k) => offsets::ERROR_OFFSETS[..k.unwrap_or(offsets::ERROR_OFFSETS.len())].to_vec(),
    })
}

impl Plan {
    /// The plan `args` asks for, resolved and validated, flag by flag in
    /// the order below: the first bad one is the error.
    pub(crate) fn new(args: &ReportArgs) -> Result<Plan> {
        let mode = mode_of(args);
        let backends = parse_backends(&args.backend)?;
        let names = method_names(args)?;
        let post = PostPlan::all(&names, args)?;
        let methods = methods_of(&names, &post)?;
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
        let size = size_of(args)?;
        if args.no_paper_scenes && args.scenes.is_empty() {
            bail!("--no-paper-scenes leaves no scene: add at least one --scene");
        }
        let cache = args.cache.clone().unwrap_or_else(|| args.out.join("cache"));
        let motion_frames = motion_frames_of(args, mode)?;
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
        let offsets = error_offsets_of(args, mode)?;
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
            offsets,
        })
    }

    /// The settings of a `w × h` render of the run: the run's ambient
    /// occlusion, on triangle scenes (the report's SDF scenes render without
    /// it, though both backends render it there).
    pub(crate) fn settings(&self, w: u32, h: u32, sdf: bool) -> RenderSettings {
        let mut s = RenderSettings::new(w, h);
        if !sdf {
            s.ao_rays = self.ao;
        }
        s
    }

    pub(crate) fn sizes(&self, sdf: bool) -> ((u32, u32), (u32, u32)) {
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

#[cfg(test)]
mod tests {
    use super::*;

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
        // The default report and the quick one: 4 offsets (each at the
        // quality size, against the run's reference).
        let p = plan(ReportArgs::default()).unwrap();
        assert_eq!(p.offsets, offsets::ERROR_OFFSETS.to_vec());
        let quick = ReportArgs {
            quick: true,
            ..Default::default()
        };
        let p = plan(quick.clone()).unwrap();
        assert_eq!(p.offsets.len(), 4);
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
}
