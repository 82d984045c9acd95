//! A row of the results: one method (or post-process) on one scene with one
//! backend, its times, and its error at each camera offset.

use anyhow::Result;
use subcone_metrics::{ssim, Rgb8};

use crate::classes;
use crate::key::{RowKey, SceneId};
use crate::timing::Timings;

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
    /// ([`offsets::ERROR_OFFSETS`](crate::offsets::ERROR_OFFSETS), in order; offset 0 is the scene's
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
    /// ([`PostProcess::describe`](crate::post::PostProcess::describe)).
    pub post_process: Option<String>,
    /// How the row's passes were timed (distinct sources, in the order
    /// first seen): the CPU's wall clock, GPU timestamps, or the wall clock
    /// around GPU work whose timestamps are not used.
    pub timed_by: Vec<subcone_scene::TimingSource>,
    /// A hash of the quality image's size and bytes
    /// ([`answer::digest`](crate::answer::digest)), when the error was measured: rows of one scene
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
    /// else what its method claims ([`Method::claims`](subcone_scene::Method::claims)), nothing for any
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
    /// The offset ([`offsets::ERROR_OFFSETS`](crate::offsets::ERROR_OFFSETS)), pixels.
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

    pub(crate) fn of(
        offset: (f32, f32),
        fl: &subcone_metrics::Flip,
        ss: &ssim::Ssim,
        masks: &classes::ClassMasks,
    ) -> OffsetError {
        OffsetError {
            offset,
            flip: fl.mean,
            ssim: ss.mean,
            classes: classes::ClassError::measure(&fl.map, masks, classes::Metric::Flip),
            classes_ssim: classes::ClassError::measure(
                &ss.dissimilarity(),
                masks,
                classes::Metric::Ssim,
            ),
        }
    }
}
