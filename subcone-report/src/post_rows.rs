//! The post-process rows of a scene and backend (the SMAA row,
//! `--post-process`): each step on NoAA's frame, timed and measured as a
//! method is.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{anyhow, Result};
use subcone_metrics::Rgb8;
use subcone_scene::{Backend, Frame};

use crate::key::RowKey;
use crate::measure::{measure, Measured};
use crate::named::NOAA;
use crate::plan::{Plan, PostPlan};
use crate::post;
use crate::quality::SceneQuality;
use crate::render::render;
use crate::row::{OffsetError, ResultRow};
use crate::runner::Runner;
use crate::scenes::{file_safe, SceneJob};
use crate::summary::Failure;
use crate::timing::Timings;

/// Where the post-process rows of one scene and backend go.
pub(crate) struct PostAt<'a> {
    pub(crate) job: &'a SceneJob,
    /// The backend's index in the plan.
    pub(crate) bi: usize,
    pub(crate) sq: Option<&'a SceneQuality>,
    pub(crate) img_dir: &'a Path,
}

/// The row of post-process `step` on one backend: NoAA's row with the step
/// (one warm-up, then `runs` timed calls on the timing-size NoAA frame)
/// added to its times, as the pass named after the step, and the step
/// described; with the scene's quality, its error on the filtered NoAA
/// quality image. `timing` is the timing-size NoAA frame the step gets
/// (with AOVs when it reads them).
pub(crate) fn post_measured(
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

impl Runner<'_> {
    /// The post-process rows of one scene and backend, pushed to the rows
    /// (a failing step listed, with `--keep-going`), and the quality images
    /// of the first backend's, for the crops. A step that reads AOVs gets a
    /// NoAA frame rendered with them at the timing size, once for all such
    /// steps and apart from the rounds; the others get NoAA's last timed
    /// frame.
    pub(crate) fn post_rows(
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
}
