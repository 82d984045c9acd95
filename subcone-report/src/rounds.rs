//! A method's warm-ups, and the timed rounds of one backend's methods,
//! interleaved so that the machine's drift falls on every method alike.

use anyhow::Result;
use subcone_metrics::Rgb8;
use subcone_scene::{Backend, Frame, Method};

use crate::named::NOAA;
use crate::render::render;
use crate::runner::Runner;
use crate::scenes::SceneJob;
use crate::summary::Failure;
use crate::timing::{self, Timings};

/// The per-pixel figures of a timed frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrameFigures {
    /// Shading evaluations per pixel.
    pub(crate) spp: f64,
    /// Rays of every kind per pixel.
    pub(crate) rays_per_pixel: f64,
    /// Rasterised primary samples per pixel.
    pub(crate) raster_spp: f64,
    /// Frame buffers, MiB.
    pub(crate) buffer_mib: f64,
}

impl FrameFigures {
    pub(crate) fn of(f: &Frame) -> Self {
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
pub(crate) struct Contender {
    pub(crate) method: Method,
    /// The quality render, when errors are measured and it rendered.
    pub(crate) quality: Option<Rgb8>,
    /// Mean of the quality render's samples-per-pixel AOV, when it has one.
    pub(crate) quality_spp: Option<f64>,
    /// The rounds so far, in round order.
    pub(crate) timings: Timings,
    /// Figures of the last timed frame.
    pub(crate) figures: Option<FrameFigures>,
    /// The last timed frame, kept for NoAA only (the post-process rows'
    /// input): one frame, not one per method, stays in memory during the
    /// rounds.
    pub(crate) last_noaa: Option<Frame>,
    /// The quality render with its AOVs, kept for NoAA only when the run has
    /// post-process rows.
    pub(crate) noaa_quality: Option<Frame>,
    /// A render failed: no row, no further rounds.
    pub(crate) dropped: bool,
}

impl Runner<'_> {
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
    pub(crate) fn warm_up(
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
    pub(crate) fn rounds(
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
}
