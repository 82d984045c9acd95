//! The answer at the top of `report.md`: which method buys the least error
//! for its time, computed from the result rows and nothing else.
//!
//! Three steps, each a pure function of the rows:
//!
//! 1. [`exclusions`]: rows that add no point of their own to a time–error
//!    plane. A row whose quality image is byte-identical to another row's of
//!    the same scene and backend is *same image as* the one that stands for
//!    the image (it would repeat that row's error); a row part of whose
//!    time was measured by a timing source that NoAA's row of the same scene
//!    and backend does not use (the SMAA post-process on a GPU adapter,
//!    beside CPU rows) is *timed on another device*, and its time does not
//!    share the axis with the others. Both are left out of the fronts, and
//!    the report says so where it leaves them out; a repeated image stays a
//!    candidate for the picks (its error is its twin's, its time its own:
//!    a `-hybrid` is the same image sooner), a row timed on another device
//!    does not.
//! 2. [`front`]: per scene, backend and metric, the Pareto front of time
//!    over NoAA's (the median of the per-round ratios, the statistic the
//!    budgets use) against error: in time order, every row with less error
//!    than every faster row. Each step (a row against the faster one before
//!    it) holds when its error is lower at every camera offset and its time
//!    higher in every round ([`Step`]); otherwise the front marks it within
//!    noise.
//! 3. [`picks`]: per kind of scene (triangle or SDF), backend, metric and
//!    budget of time over NoAA's ([`BUDGETS`]), the method to use, by the
//!    rule [`RULE`] states, with its runner-up, the margin, and whether the
//!    decision stays inside the noise ([`Pick::noise`]): the order against
//!    the runner-up at every camera offset, and the budget's admissions
//!    across the rounds.
//!
//! The error under FLIP is the mean FLIP; under SSIM it is 1 − mean SSIM,
//! so that lower is better under both ([`error`]).

mod excluded;
mod front;
mod pick;
mod section;
#[cfg(test)]
mod tests;

pub use excluded::{digest, excluded, exclusions, same_image_twins, Excluded, Why};
pub use front::{front, pareto_by, Front, Point, Step};
pub use pick::{picks, Answer, Kind, Partial, Pick};
pub use section::{json, regime, section};

use crate::classes::Metric;
use crate::ResultRow;

/// The cost budgets of the picks: time over NoAA's at most 1.5×, at most
/// 4×, and any (`None`).
pub const BUDGETS: [Option<f64>; 3] = [Some(1.5), Some(4.0), None];

/// How a pick is made, as the report states it.
pub const RULE: &str = "of the methods that ran on every scene of the kind, were not timed on another \
device there, and whose time over NoAA's (the median of its per-round ratios) is within the budget on \
every one of those scenes, the one with the lowest mean over the scenes of its error over NoAA's; \
on a tie, the one with the lower worst time over NoAA's. NoAA itself (1.00×, error ratio 1) is \
always a candidate, so a pick of noaa means that nothing within the budget lowers the error on \
average";

/// The error of `r` under `metric`, lower is better: mean FLIP, or
/// 1 − mean SSIM. `None` when it was not measured or is not finite.
pub fn error(r: &ResultRow, metric: Metric) -> Option<f64> {
    match metric {
        Metric::Flip => r.flip_mean,
        Metric::Ssim => r.ssim_mean.map(|s| 1.0 - s),
    }
    .filter(|e| e.is_finite())
}

/// The error of `r` under `metric` at each camera offset it was measured
/// at, in offset order (empty without per-offset errors).
pub fn errors_at(r: &ResultRow, metric: Metric) -> Vec<f64> {
    r.errors_at
        .iter()
        .map(|e| match metric {
            Metric::Flip => e.flip,
            Metric::Ssim => 1.0 - e.ssim,
        })
        .collect()
}

/// The name the report gives the error of `metric`.
pub fn error_name(metric: Metric) -> &'static str {
    match metric {
        Metric::Flip => "FLIP",
        Metric::Ssim => "1 − SSIM",
    }
}
