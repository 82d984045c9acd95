//! The Pareto fronts of median time against error.

use super::error;
use super::excluded::{excluded, Excluded};
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
    /// Time over NoAA's.
    pub ratio: Option<f64>,
    /// Error under the front's metric (lower is better).
    pub error: f64,
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
/// rows not in `ex` with a time and an error, in time order, each with less
/// error than every faster one (on equal times, the lower error first).
pub fn front(rows: &[&ResultRow], ex: &[Excluded], metric: Metric) -> Vec<Point> {
    let p: Vec<Point> = rows
        .iter()
        .filter(|r| excluded(ex, r).is_none())
        .filter(|r| r.ms_median.is_finite() && r.ms_median > 0.0)
        .filter_map(|r| {
            Some(Point {
                method: r.method.clone(),
                ms: r.ms_median,
                ratio: r.ratio_to_noaa,
                error: error(r, metric)?,
            })
        })
        .collect();
    pareto_by(p, |q| (q.ms, q.error))
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
