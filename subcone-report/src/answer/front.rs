//! The Pareto fronts of time against error, each step with its evidence.

use super::excluded::{excluded, Excluded};
use super::{error, errors_at};
use crate::classes::Metric;
use crate::key::RowKey;
use crate::ResultRow;

/// A point of a front.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Method.
    pub method: RowKey,
    /// Median ms at the timing size.
    pub ms: f64,
    /// Time over NoAA's: the median of its per-round ratios, the statistic
    /// the front is ordered by and the budgets use.
    pub ratio: Option<f64>,
    /// Smallest and largest per-round time over NoAA's.
    pub ratio_range: Option<(f64, f64)>,
    /// Error under the front's metric (lower is better): the mean over the
    /// camera offsets.
    pub error: f64,
    /// The step to it from the point before it (`None` on the first).
    pub step: Option<Step>,
}

/// The evidence for one step of a front: a method against the faster one
/// before it, by the rule the verdicts follow (a difference counts when it
/// holds at every offset) and its like for time (at every round).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Step {
    /// Its error is below the faster point's at every camera offset,
    /// paired by offset (with one offset, the mean's order).
    pub error_at_every_offset: bool,
    /// It is slower than the faster point in every timed round, paired by
    /// round; rows not timed in the same rounds: their per-round ratio
    /// ranges do not overlap; without either, the medians' order, as
    /// measured.
    pub time_in_every_round: bool,
}

impl Step {
    /// The step from `faster` to `slower` under `metric`.
    pub fn between(faster: &ResultRow, slower: &ResultRow, metric: Metric) -> Step {
        let (ef, es) = (errors_at(faster, metric), errors_at(slower, metric));
        let error_at_every_offset = if ef.len() == es.len() && ef.len() > 1 {
            ef.iter().zip(&es).all(|(f, s)| s < f)
        } else {
            match (error(faster, metric), error(slower, metric)) {
                (Some(f), Some(s)) => s < f,
                _ => false,
            }
        };
        let (rf, rs) = (&faster.round_ms, &slower.round_ms);
        let time_in_every_round = if !rf.is_empty() && rf.len() == rs.len() {
            rf.iter().zip(rs).all(|(f, s)| f < s)
        } else if let (Some(f), Some(s)) = (faster.ratio_max, slower.ratio_min) {
            f < s
        } else {
            true
        };
        Step {
            error_at_every_offset,
            time_in_every_round,
        }
    }

    /// Whether the step holds: lower error at every offset and more time in
    /// every round.
    pub fn holds(&self) -> bool {
        self.error_at_every_offset && self.time_in_every_round
    }

    /// What does not hold, as the front's mark says it: `None` when the
    /// step holds.
    pub fn noise(&self) -> Option<&'static str> {
        match (self.error_at_every_offset, self.time_in_every_round) {
            (true, true) => None,
            (false, true) => Some("within noise: the error order changes with the camera offset"),
            (true, false) => Some("within noise: the time order changes between rounds"),
            (false, false) => Some(
                "within noise: the error order changes with the offset, the time order between rounds",
            ),
        }
    }
}

/// The Pareto front of one scene, backend and metric.
#[derive(Clone, Debug, PartialEq)]
pub struct Front {
    /// Scene.
    pub scene: String,
    /// Backend.
    pub backend: String,
    /// Metric.
    pub metric: Metric,
    /// The front, in time order.
    pub points: Vec<Point>,
}

/// The Pareto front of `rows` (one scene and backend) under `metric`: the
/// rows not in `ex` with a time and an error, in order of time over
/// NoAA's (the median of the per-round ratios, as the picks' budgets; the
/// median ms when a row has no ratio), each with less error than every
/// faster one (on equal times, the lower error first), and each step with
/// its evidence ([`Step`]).
pub fn front(rows: &[&ResultRow], ex: &[Excluded], metric: Metric) -> Vec<Point> {
    let candidates: Vec<(&ResultRow, f64)> = rows
        .iter()
        .filter(|r| excluded(ex, r).is_none())
        .filter(|r| r.ms_median.is_finite() && r.ms_median > 0.0)
        .filter_map(|r| Some((*r, error(r, metric)?)))
        .collect();
    let by_ratio = candidates
        .iter()
        .all(|(r, _)| r.ratio_to_noaa.is_some_and(f64::is_finite));
    let time = |r: &ResultRow| match r.ratio_to_noaa {
        Some(t) if by_ratio => t,
        _ => r.ms_median,
    };
    let kept = pareto_by(candidates, |(r, e)| (time(r), *e));
    kept.iter()
        .enumerate()
        .map(|(i, (r, e))| Point {
            method: r.method.clone(),
            ms: r.ms_median,
            ratio: r.ratio_to_noaa,
            ratio_range: r.ratio_min.zip(r.ratio_max),
            error: *e,
            step: (i > 0).then(|| Step::between(kept[i - 1].0, r, metric)),
        })
        .collect()
}

/// The Pareto front of `items` by `key` = (time, error): the items with a
/// finite time and error, sorted by time (on equal times, the lower error
/// first), each kept when its error is below every faster kept one's.
pub fn pareto_by<T>(items: Vec<T>, key: impl Fn(&T) -> (f64, f64)) -> Vec<T> {
    let mut p: Vec<T> = items
        .into_iter()
        .filter(|i| {
            let (t, e) = key(i);
            t.is_finite() && e.is_finite()
        })
        .collect();
    p.sort_by(|a, b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.total_cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    let mut out: Vec<T> = Vec::new();
    for q in p {
        if out.last().is_none_or(|l| key(&q).1 < key(l).1) {
            out.push(q);
        }
    }
    out
}
