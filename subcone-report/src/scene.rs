//! One scene measured: per backend every method's warm-ups, the timed
//! rounds, each method's row and error and the post-process rows; then the
//! ratios to NoAA, the crops and the plots.

use std::path::Path;

use anyhow::Result;
use subcone_metrics::Rgb8;

use crate::key::RowKey;
use crate::measure::Measured;
use crate::named::NOAA;
use crate::plan::{Applicable, Mode, Plan};
use crate::post_rows::PostAt;
use crate::quality::SceneQuality;
use crate::row::ResultRow;
use crate::runner::Runner;
use crate::scenes::SceneJob;
use crate::summary::{SceneClasses, SceneCrops};
use crate::{crops, files, metrics, plot, timing};

impl Runner<'_> {
    /// Measure every applicable method of one scene on every backend, then
    /// the ratios to NoAA, the crops and the plots.
    ///
    /// Per backend: every method's warm-ups ([`Runner::warm_up`]), then the
    /// timed rounds of all of them ([`Runner::rounds`]), then each surviving
    /// method's row and error ([`Runner::finish`]) and the SMAA row.
    pub(crate) fn scene(&mut self, job: &SceneJob, methods: &[Applicable]) -> Result<()> {
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
pub(crate) fn ratios_to_noaa(rows: &mut [ResultRow]) {
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
pub(crate) fn write_crops(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timing::Timings;

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
}
