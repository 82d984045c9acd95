//! The report's arguments (`subcone report`).

use std::path::PathBuf;

use crate::setup::parse_ao;

/// Arguments of `subcone report`.
#[derive(clap::Args, Clone, Debug, PartialEq)]
pub struct ReportArgs {
    /// Add a scene: a built-in name, or a path to a mesh file (.obj, .gltf,
    /// .glb) or an SDF scene file (.sdf.ron) (repeatable).
    #[arg(long = "scene", value_name = "NAME|PATH")]
    pub scenes: Vec<String>,
    /// Leave out the built-in paper scenes: report only the --scene scenes.
    #[arg(long)]
    pub no_paper_scenes: bool,
    /// Methods to compare, comma-separated (default: noaa, ssaa4, ssaa16, sraa,
    /// sraa-rt, sraa+mat, sraa-rt+mat, their -paper presets, ctss, ctss-paper, ctss-delayed, ctss+edges, ctss-r, ssaa4+ctss, fxaa; each where it applies).
    #[arg(long = "method", value_delimiter = ',', value_name = "METHOD")]
    pub methods: Vec<String>,
    /// Output directory.
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Backends, comma-separated (cpu, wgpu).
    #[arg(long, default_value = "cpu")]
    pub backend: String,
    /// Image size WxH for both timing and error, overriding the defaults.
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Small, fast run (CI): 96x64, 1 warm-up + 3 runs, SSAA64 reference.
    #[arg(long)]
    pub quick: bool,
    /// Only time: skip references and errors.
    #[arg(long)]
    pub timing_only: bool,
    /// Timed runs per method after one warm-up (default 3).
    #[arg(long)]
    pub runs: Option<u32>,
    /// Reference method (default ssaa256; ssaa64 with --quick).
    #[arg(long, value_name = "METHOD")]
    pub reference: Option<String>,
    /// Reference cache directory (default OUT/cache).
    #[arg(long, value_name = "DIR")]
    pub cache: Option<PathBuf>,
    /// Re-render references even when cached.
    #[arg(long)]
    pub refresh_references: bool,
    /// Skip the SRAA Table 1 resolution sweep (256² to 1024² on the atrium).
    #[arg(long)]
    pub no_sweep: bool,
    /// Go on after a render fails: list the failures in the report and exit 0
    /// (without it, the first failure stops the run with its error).
    #[arg(long)]
    pub keep_going: bool,
    /// Ambient-occlusion rays per shaded point for every render of the run
    /// (triangle scenes; 0: off, at most 256). Part of the reference cache key.
    #[arg(long = "ao", value_name = "N", default_value_t = 0, value_parser = parse_ao)]
    pub ao: u32,
    /// The full section "Where SRAA pays": on atrium and Sponza at 512²,
    /// noaa, ssaa4 and sraa-rt with ambient occlusion 0, 4, 16 and 64 rays
    /// (time, silhouette + crease + shadow FLIP, ray-count and time ratios,
    /// the crossover). The default report has a short form of it (atrium,
    /// AO 0, 4 and 16); the quick report has neither.
    #[arg(long)]
    pub sraa_sweep: bool,
    /// Add a post-process row NAME: NoAA's frame filtered by COMMAND, judged
    /// like fxaa and smaa (repeatable). COMMAND gets the frame and its AOVs
    /// through placeholders ({color}, {linear}, {depth}, {normal}, {albedo},
    /// {output}, {width}, {height}, {scene}) or SUBCONE_POST_* variables, and
    /// writes an 8-bit PNG of the same size to {output}; see the
    /// `report::post` docs.
    #[arg(long = "post-process", value_name = "NAME=COMMAND")]
    pub post_processes: Vec<String>,
    /// Seconds one run of a --post-process command may take before it is
    /// killed and counted as a failure (default 60).
    #[arg(long, value_name = "SECONDS")]
    pub post_timeout: Option<f64>,
    /// Add the section "Motion": each scene's camera pans and dollies by
    /// sub-pixel steps over --motion-frames frames at 320x180; noaa, ssaa4,
    /// sraa-rt and ctss (where they apply) are compared with each frame's
    /// ssaa64 reference (FLIP per frame, temporal instability per edge
    /// class, an animated crop). The quick report always runs a small
    /// version (4 frames at its size).
    #[arg(long)]
    pub motion: bool,
    /// Frames of the motion path (default 16; 4 in the quick report).
    #[arg(long, value_name = "N")]
    pub motion_frames: Option<u32>,
    /// Camera offsets the error is measured at, 1 to 4 (default 4): the
    /// first N of `report::offsets::ERROR_OFFSETS`. Fewer offsets cost less
    /// time; with 1, verdicts rest on one frame.
    #[arg(long, value_name = "N")]
    pub error_offsets: Option<usize>,
}

impl Default for ReportArgs {
    /// The same defaults as the command line.
    fn default() -> Self {
        ReportArgs {
            scenes: Vec::new(),
            no_paper_scenes: false,
            methods: Vec::new(),
            out: PathBuf::from("report"),
            backend: "cpu".into(),
            size: None,
            quick: false,
            timing_only: false,
            runs: None,
            reference: None,
            cache: None,
            refresh_references: false,
            no_sweep: false,
            keep_going: false,
            ao: 0,
            sraa_sweep: false,
            post_processes: Vec::new(),
            post_timeout: None,
            motion: false,
            motion_frames: None,
            error_offsets: None,
        }
    }
}
