//! A method's row once its rounds are over: its times, the figures of its
//! last timed frame, and its error against the scene's reference at each
//! camera offset, with its images written beside the reference.

use std::path::Path;
use std::time::Instant;

use anyhow::{bail, Result};
use subcone_metrics::{ssim, Rgb8};
use subcone_scene::{Backend, Frame, Method};

use crate::named::NOAA;
use crate::plan::Plan;
use crate::quality::SceneQuality;
use crate::render::render_from;
use crate::rounds::Contender;
use crate::row::{OffsetError, ResultRow};
use crate::runner::Runner;
use crate::scenes::{file_safe, SceneJob};
use crate::summary::Failure;
use crate::{answer, files, metrics, offsets};

/// One method on one backend, measured.
pub(crate) struct Measured {
    pub(crate) row: ResultRow,
    /// The quality image (when errors are measured).
    pub(crate) quality: Option<Rgb8>,
    /// NoAA's frames, the post-process rows' input (NoAA only).
    pub(crate) noaa: Option<NoaaFrames>,
}

/// The NoAA frames a post-process filters.
pub(crate) struct NoaaFrames {
    /// The last timed frame (no AOVs).
    pub(crate) timing: Frame,
    /// The quality render, with its AOVs (when errors are measured).
    pub(crate) quality: Option<Frame>,
    /// The renders at the camera offsets after the first, with AOVs.
    pub(crate) offsets: Vec<Frame>,
}

impl Runner<'_> {
    /// The row of a method that went through every round: its times over
    /// the rounds, the figures of its last timed frame, and with `sq` its
    /// error, measured on its quality image (images written beside the
    /// reference).
    pub(crate) fn finish(
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
    pub(crate) fn measure_offsets(
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
}

/// Measure the error of `img` (the quality render of `row`'s method) against
/// the scene's reference: mean, PSNR, edge and per-class FLIP, mean and
/// per-class SSIM; writes the image, its FLIP map and its `1 − SSIM` map
/// beside the reference.
pub(crate) fn measure(
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
pub(crate) fn image_name(prefix: &str, method: &str, backend: &str, first: bool) -> String {
    let m = file_safe(method);
    if first {
        format!("{prefix}{m}.png")
    } else {
        format!("{prefix}{m}-{}.png", file_safe(backend))
    }
}
