//! The report's files: `results.csv`, `results.json`, `report.md`, and PNG
//! images.
//!
//! Columns are stable: [`BASE_COLUMNS`] always, in that order, then one
//! `ms_<pass>` column per pass seen in the run, sorted by name, empty where a
//! method has no such pass. Missing values are empty in CSV and `null` in
//! JSON; an infinite PSNR (identical images) is `inf` in CSV and `null` in
//! JSON.
//!
//! Errors are means over the camera offsets they were measured at
//! ([`offsets`](crate::offsets), `offsets` of them): `flip_min`/`flip_max`,
//! `ssim_min`/`ssim_max` and the `_min`/`_max` of each class column are the
//! smallest and largest value over the offsets (empty with one offset);
//! `px_<class>` is the class's smallest pixel count over the offsets. The
//! near-edge band (`flip_near_edge`, `px_near_edge`, `dssim_near_edge`) is
//! measured like a class but not judged. `raster_samples_per_pixel` counts
//! the primary samples a `-hybrid` method's rasteriser resolved (0 for a
//! traced method); its rasteriser's time is the `ms_raster` pass column.
//!
//! Time ratios to NoAA are medians of per-round ratios (the methods of a
//! scene and backend are timed in interleaved rounds, see [`timing`](crate::timing));
//! `ratio_min` and `ratio_max` are the smallest and largest per-round
//! ratio, empty for rows not timed in NoAA's rounds.
//!
//! One file per output: the columns both results files share
//! (`columns.rs`), `results.csv` (`csv.rs`), `results.json` (`json.rs`),
//! `report.md` (`markdown.rs`) with its verdicts (`verdicts.rs`), its
//! performance targets (`targets.rs`) and its comparison with the papers
//! (`paper_comparison.rs`); the number formats and means they share are
//! here.

use std::fmt::Write as _;

use crate::ResultRow;
use subcone_scene::Method;

mod columns;
mod csv;
mod json;
mod markdown;
mod paper_comparison;
mod targets;
#[cfg(test)]
mod test_rows;
mod verdicts;

pub use self::columns::{pass_columns, BASE_COLUMNS};
pub use self::csv::csv;
pub use self::json::json;
pub(crate) use self::json::json_rows;
pub use self::markdown::markdown;
pub use self::paper_comparison::{paper_comparison, sdf_pick};
pub use self::targets::{
    targets, throughput_judged, CTSS_SSAA4_FACTOR, CTSS_STIFF_FACTOR, CTSS_TARGETS,
    RAY_THROUGHPUT_MIN_RAYS, RAY_THROUGHPUT_SHARE, SRAA_METHODS, SRAA_RT_EDGE_FACTOR,
    SRAA_RT_SSAA4_FACTOR, SRAA_RT_SSAA4_SCENES, SRAA_RT_TIME_SHARE,
};
pub use self::verdicts::{
    glance_cell, near_edge_share, rules, verdict_summary, verdicts, BandShare,
};

pub use crate::papers::{CTSS_TABLE1, SRAA_SPEEDUP_OVER_SSAA16, SRAA_TABLE1};

fn f(v: Option<f64>, digits: usize) -> String {
    match v {
        Some(x) if x.is_infinite() => "∞".into(),
        Some(x) if x.is_finite() => format!("{x:.digits$}"),
        _ => "–".into(),
    }
}

/// A mean error with its range over the camera offsets, `0.0769
/// (0.0712–0.0801)`; the mean alone without a range.
fn with_range(v: Option<f64>, range: Option<(f64, f64)>) -> String {
    match (v, range) {
        (Some(_), Some((lo, hi))) => format!("{} ({lo:.4}–{hi:.4})", f(v, 4)),
        _ => f(v, 4),
    }
}

/// A mean of ratios to NoAA over scenes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeanRatio {
    /// Mean of the rows' `ratio_to_noaa` (each a median over rounds).
    pub mean: f64,
    /// Means of the rows' `ratio_min` and of their `ratio_max`: the range
    /// the mean would take were every scene at its lowest, or its highest,
    /// round. `None` unless every row has a range.
    pub range: Option<(f64, f64)>,
    /// Rows averaged.
    pub n: usize,
}

impl MeanRatio {
    /// Over the rows that have a ratio to NoAA; `None` without one.
    pub fn of<'a>(rows: impl IntoIterator<Item = &'a ResultRow>) -> Option<MeanRatio> {
        let rows: Vec<&ResultRow> = rows
            .into_iter()
            .filter(|r| r.ratio_to_noaa.is_some())
            .collect();
        if rows.is_empty() {
            return None;
        }
        let n = rows.len() as f64;
        let mean_of = |v: &dyn Fn(&ResultRow) -> Option<f64>| -> Option<f64> {
            rows.iter()
                .map(|r| v(r))
                .sum::<Option<f64>>()
                .map(|s| s / n)
        };
        Some(MeanRatio {
            mean: mean_of(&|r| r.ratio_to_noaa)?,
            range: mean_of(&|r| r.ratio_min).zip(mean_of(&|r| r.ratio_max)),
            n: rows.len(),
        })
    }

    /// `1.153x (1.121–1.190)` with `digits` decimals, `x` after each
    /// figure when `times`.
    pub fn show(&self, digits: usize, times: bool) -> String {
        let x = if times { "x" } else { "" };
        let mut s = format!("{:.digits$}{x}", self.mean);
        if let Some((lo, hi)) = self.range {
            let _ = write!(s, " ({lo:.digits$}–{hi:.digits$}{x})");
        }
        s
    }
}

fn rows_for<'a>(s: &'a [ResultRow], method: Method, backend: &str) -> Vec<&'a ResultRow> {
    s.iter()
        .filter(|r| r.method == method && r.backend == backend)
        .collect()
}

/// The row of `method` on `backend` and `scene`.
fn row_of<'a>(
    rows: &'a [ResultRow],
    method: Method,
    backend: &str,
    scene: &str,
) -> Option<&'a ResultRow> {
    rows.iter()
        .find(|x| x.method == method && x.backend == backend && x.scene == scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_rows::{ratio, row};

    #[test]
    fn mean_ratio_over_scenes_averages_the_ranges() {
        let rows = [
            ratio(row("ctss", &[]), 1.2, Some((1.1, 1.3))),
            ratio(row("ctss", &[]), 1.0, Some((0.9, 1.5))),
            row("ctss", &[]),
        ];
        let m = MeanRatio::of(&rows).unwrap();
        assert_eq!(m.n, 2, "a row without a ratio is not averaged");
        assert!((m.mean - 1.1).abs() < 1e-12);
        let (lo, hi) = m.range.unwrap();
        assert!((lo - 1.0).abs() < 1e-12 && (hi - 1.4).abs() < 1e-12);
        assert_eq!(m.show(3, true), "1.100x (1.000–1.400x)");
        // One row without a range: the mean has none.
        let mixed = [rows[0].clone(), ratio(row("ctss", &[]), 1.5, None)];
        let m = MeanRatio::of(&mixed).unwrap();
        assert_eq!((m.range, m.show(2, false)), (None, "1.35".to_string()));
        assert_eq!(MeanRatio::of(&rows[2..]), None);
    }
}
