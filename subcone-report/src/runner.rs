//! The run's state while it measures (the plan, the progress bar, the rows
//! so far), and how a failed render stops the run or is listed.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::{bail, Result};
use indicatif::{ProgressBar, ProgressStyle};
use subcone_scene::Backend;

use crate::load;
use crate::plan::Plan;
use crate::row::ResultRow;
use crate::summary::{Failure, SceneClasses, SceneCrops};

pub(crate) struct Progress {
    pub(crate) bar: ProgressBar,
}

impl Progress {
    pub(crate) fn new(len: u64) -> Self {
        let bar = ProgressBar::new(len);
        if let Ok(style) = ProgressStyle::with_template(
            "{elapsed_precise} [{bar:30}] {pos}/{len} renders, eta {eta} {wide_msg}",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress { bar }
    }

    pub(crate) fn note(&self, msg: &str) {
        self.bar.suspend(|| eprintln!("report: {msg}"));
    }
}

/// The run's state while it measures: the plan, the progress bar and what
/// has been measured so far.
pub(crate) struct Runner<'a> {
    pub(crate) plan: &'a Plan,
    /// The CPU backend of every render that is not timed on the plan's
    /// backends (references, edge classes, masks, motion): the plan's own
    /// `cpu` backend when it times one, so that each scene's BVH is built
    /// once for all its renders ([`CpuBackend`](subcone_cpu::CpuBackend)
    /// caches one per scene).
    pub(crate) cpu: &'a (dyn Backend + Send + Sync),
    pub(crate) progress: Progress,
    pub(crate) references_rendered: usize,
    pub(crate) references_cached: usize,
    pub(crate) rows: Vec<ResultRow>,
    pub(crate) failures: Vec<Failure>,
    pub(crate) crops: Vec<SceneCrops>,
    pub(crate) classes: Vec<SceneClasses>,
    pub(crate) plots: Vec<PathBuf>,
    /// Other processes' CPU time over the timed rounds, summed over scenes
    /// and backends.
    pub(crate) load: load::OtherCpu,
    /// Wall time spent on the camera offsets after the first.
    pub(crate) offsets_elapsed: Duration,
}

impl Runner<'_> {
    /// A failed render: an error that stops the run, or with `--keep-going`
    /// a note and an entry in `failures`.
    pub(crate) fn fail(&mut self, f: Failure) -> Result<()> {
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
}
