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
//! 2. [`front`]: per scene, backend and metric, the Pareto front of median
//!    time against error: in time order, every row with less error than
//!    every faster row.
//! 3. [`picks`]: per kind of scene (triangle or SDF), backend, metric and
//!    budget of time over NoAA's ([`BUDGETS`]), the method to use, by the
//!    rule [`RULE`] states.
//!
//! The error under FLIP is the mean FLIP; under SSIM it is 1 − mean SSIM,
//! so that lower is better under both ([`error`]).

use std::fmt::Write as _;

use serde_json::{json, Value};
use subcone_scene::TimingSource;

use crate::classes::Metric;
use crate::context::{cpu_model, ms, Context, SceneInfo};
use crate::key::{RowKey, SceneId};
use crate::named::NOAA;
use crate::{Mode, ResultRow};

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

/// The name the report gives the error of `metric`.
pub fn error_name(metric: Metric) -> &'static str {
    match metric {
        Metric::Flip => "FLIP",
        Metric::Ssim => "1 − SSIM",
    }
}

/// Why a row is left out of the fronts (and, [`Why::OtherDevice`], of the
/// picks).
#[derive(Clone, Debug, PartialEq)]
pub enum Why {
    /// Its image is byte-identical to `as_method`'s (same scene and
    /// backend), which comes first in table order.
    SameImage {
        /// The row it repeats.
        as_method: RowKey,
    },
    /// Part of its time was measured by `sources`, which NoAA's row of the
    /// same scene and backend (timed by `noaa`) does not use.
    OtherDevice {
        /// The row's timing sources that NoAA's row does not have.
        sources: Vec<TimingSource>,
        /// NoAA's timing sources.
        noaa: Vec<TimingSource>,
    },
}

/// A row left out of the fronts (and, timed on another device, of the
/// picks).
#[derive(Clone, Debug, PartialEq)]
pub struct Excluded {
    /// Scene.
    pub scene: SceneId,
    /// Backend.
    pub backend: String,
    /// Method.
    pub method: RowKey,
    /// Why.
    pub why: Why,
}

impl Excluded {
    /// The mark the row's method gets in tables and plots: `†` for another
    /// device, `(same image as …)` for a repeated image.
    pub fn mark(&self) -> String {
        match &self.why {
            Why::SameImage { as_method } => format!("(same image as {as_method})"),
            Why::OtherDevice { .. } => "†".into(),
        }
    }

    /// Why the row is left out, as a clause.
    pub fn reason(&self) -> String {
        match &self.why {
            Why::SameImage { as_method } => format!(
                "its image is byte-identical to {as_method}'s, so it adds no point of its own (its time is in the scene's table, and it stays a candidate for the picks)"
            ),
            Why::OtherDevice { sources, noaa } => format!(
                "part of its time is measured by {}, not by the {} every {} row without a post-process is timed by, so its time is not on their axis",
                join(sources),
                join(noaa),
                self.backend
            ),
        }
    }
}

fn join(sources: &[TimingSource]) -> String {
    sources
        .iter()
        .map(|s| s.to_string())
        .collect::<Vec<_>>()
        .join(" and ")
}

/// A hash of an 8-bit image's size and bytes, to find rows whose images are
/// byte-identical ([`ResultRow::image_digest`]).
pub fn digest(width: u32, height: u32, data: &[u8]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::hash::DefaultHasher::new();
    (width, height, data).hash(&mut h);
    h.finish()
}

/// The rows of `rows` left out of the fronts (and, timed on another device,
/// of the picks), in row order. A group of rows with byte-identical images
/// is named after the row that every timed round tells apart as the fastest
/// (its slowest round faster than every other's fastest: a `-hybrid` beside
/// its traced twin), else after the first row of the group in table order
/// (a row timed on another device last): the name does not change with the
/// clock's noise from scene to scene, and a front never shows a point at a
/// time its image's fastest method beats in every round.
pub fn exclusions(rows: &[&ResultRow]) -> Vec<Excluded> {
    let base = |r: &ResultRow| {
        rows.iter()
            .find(|x| x.scene == r.scene && x.backend == r.backend && x.method == NOAA)
            .map(|x| x.timed_by.clone())
    };
    let other = |r: &ResultRow| -> Option<Why> {
        let noaa = base(r)?;
        let sources: Vec<TimingSource> = r
            .timed_by
            .iter()
            .filter(|s| !noaa.contains(s))
            .copied()
            .collect();
        (!sources.is_empty()).then_some(Why::OtherDevice { sources, noaa })
    };
    let mut out = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let twin = r.image_digest.and_then(|d| {
            let group: Vec<(usize, &&ResultRow)> = rows
                .iter()
                .enumerate()
                .filter(|(_, x)| {
                    x.scene == r.scene && x.backend == r.backend && x.image_digest == Some(d)
                })
                .collect();
            let clearly_fastest = group.iter().find(|(j, x)| {
                other(x).is_none()
                    && x.ms_max.is_finite()
                    && group
                        .iter()
                        .filter(|(k, _)| k != j)
                        .all(|(_, y)| x.ms_max < y.ms_min)
            });
            clearly_fastest
                .or_else(|| group.iter().min_by_key(|(j, x)| (other(x).is_some(), *j)))
                .filter(|(j, _)| *j != i)
                .map(|(_, x)| x.method.clone())
        });
        let why = match twin {
            Some(as_method) => Some(Why::SameImage { as_method }),
            None => other(r),
        };
        if let Some(why) = why {
            out.push(Excluded {
                scene: r.scene.clone(),
                backend: r.backend.clone(),
                method: r.method.clone(),
                why,
            });
        }
    }
    out
}

/// `r`'s entry in `ex`, when it is left out.
pub fn excluded<'a>(ex: &'a [Excluded], r: &ResultRow) -> Option<&'a Excluded> {
    ex.iter()
        .find(|e| e.scene == r.scene && e.backend == r.backend && e.method == r.method)
}

/// The methods whose images `r`'s repeats, for its label (`ctss (=
/// ctss-delayed)`): the rows left out as the same image as `r`.
pub fn same_image_twins(ex: &[Excluded], r: &ResultRow) -> Vec<RowKey> {
    ex.iter()
        .filter(|e| {
            e.scene == r.scene
                && e.backend == r.backend
                && matches!(&e.why, Why::SameImage { as_method } if *as_method == r.method)
        })
        .map(|e| e.method.clone())
        .collect()
}

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

/// The kind of a scene, for the picks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Triangle meshes.
    Triangles,
    /// Signed distance fields.
    Sdf,
}

impl Kind {
    /// Both, in the order the report shows them.
    pub const ALL: [Kind; 2] = [Kind::Triangles, Kind::Sdf];

    /// The name the report prints.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Triangles => "triangle",
            Kind::Sdf => "SDF",
        }
    }

    fn of(sc: &SceneInfo) -> Kind {
        if sc.sdf {
            Kind::Sdf
        } else {
            Kind::Triangles
        }
    }
}

/// The method to use on one kind of scene, backend, metric and budget.
#[derive(Clone, Debug, PartialEq)]
pub struct Pick {
    /// Kind of scene.
    pub kind: Kind,
    /// Backend.
    pub backend: String,
    /// Metric.
    pub metric: Metric,
    /// Largest time over NoAA's (`None`: any).
    pub budget: Option<f64>,
    /// The scenes the pick is over (those of the kind with a NoAA error).
    pub scenes: Vec<String>,
    /// The method.
    pub method: RowKey,
    /// Mean over the scenes of its error over NoAA's.
    pub mean_error_ratio: f64,
    /// Its largest time over NoAA's over the scenes.
    pub worst_time_ratio: f64,
    /// On how many of the scenes it is on the front.
    pub on_front: usize,
}

/// A method that ran (and was not timed on another device) on some scenes of a kind but
/// not all: no candidate for that kind's picks.
#[derive(Clone, Debug, PartialEq)]
pub struct Partial {
    /// Kind of scene.
    pub kind: Kind,
    /// Backend.
    pub backend: String,
    /// Method.
    pub method: RowKey,
    /// The scenes of the kind it has no usable row on.
    pub missing: Vec<String>,
}

/// Everything the answer section says.
#[derive(Clone, Debug, PartialEq)]
pub struct Answer {
    /// Rows left out, with the reason.
    pub excluded: Vec<Excluded>,
    /// Per scene (in `scenes` order), backend and metric.
    pub fronts: Vec<Front>,
    /// Per kind, backend, metric and budget.
    pub picks: Vec<Pick>,
    /// Methods not a candidate for a kind because they miss a scene of it.
    pub partial: Vec<Partial>,
}

fn backends(rows: &[&ResultRow]) -> Vec<String> {
    let mut b: Vec<String> = Vec::new();
    for r in rows {
        if !b.contains(&r.backend) {
            b.push(r.backend.clone());
        }
    }
    b
}

impl Answer {
    /// The answer of `rows` on `scenes`.
    pub fn of(rows: &[ResultRow], scenes: &[SceneInfo]) -> Answer {
        let all: Vec<&ResultRow> = rows.iter().collect();
        let excluded = exclusions(&all);
        let mut fronts = Vec::new();
        for sc in scenes {
            let here: Vec<&ResultRow> =
                all.iter().copied().filter(|r| r.scene == sc.name).collect();
            for b in backends(&here) {
                let rb: Vec<&ResultRow> = here.iter().copied().filter(|r| r.backend == b).collect();
                for metric in Metric::ALL {
                    let points = front(&rb, &excluded, metric);
                    if !points.is_empty() {
                        fronts.push(Front {
                            scene: sc.name.to_string(),
                            backend: b.clone(),
                            metric,
                            points,
                        });
                    }
                }
            }
        }
        let (picks, partial) = picks(&all, &excluded, &fronts, scenes);
        Answer {
            excluded,
            fronts,
            picks,
            partial,
        }
    }

    /// The pick of one kind, backend, metric and budget.
    pub fn pick(
        &self,
        kind: Kind,
        backend: &str,
        metric: Metric,
        budget: Option<f64>,
    ) -> Option<&Pick> {
        self.picks.iter().find(|p| {
            p.kind == kind && p.backend == backend && p.metric == metric && p.budget == budget
        })
    }

    /// The front of one scene, backend and metric.
    pub fn front(&self, scene: &str, backend: &str, metric: Metric) -> Option<&Front> {
        self.fronts
            .iter()
            .find(|f| f.scene == scene && f.backend == backend && f.metric == metric)
    }
}

/// The picks ([`RULE`]) for every kind, backend, metric and budget, and the
/// methods that are no candidate for a kind because they miss a scene of it.
pub fn picks(
    rows: &[&ResultRow],
    ex: &[Excluded],
    fronts: &[Front],
    scenes: &[SceneInfo],
) -> (Vec<Pick>, Vec<Partial>) {
    let noaa = RowKey::from(NOAA);
    let (mut out, mut partial) = (Vec::new(), Vec::new());
    for kind in Kind::ALL {
        for b in backends(rows) {
            let usable = |scene: &str, method: &RowKey, metric: Metric| {
                rows.iter()
                    .find(|r| r.scene == scene && r.backend == b && r.method == *method)
                    .filter(|r| {
                        !matches!(
                            excluded(ex, r).map(|e| &e.why),
                            Some(Why::OtherDevice { .. })
                        )
                    })
                    .and_then(|r| Some((*r, error(r, metric)?)))
            };
            let mut methods: Vec<RowKey> = Vec::new();
            for r in rows.iter().filter(|r| r.backend == b) {
                let of_kind = scenes
                    .iter()
                    .any(|sc| sc.name == r.scene && Kind::of(sc) == kind);
                if of_kind && !methods.contains(&r.method) {
                    methods.push(r.method.clone());
                }
            }
            for metric in Metric::ALL {
                // Scenes of the kind with NoAA's error on this backend, the
                // denominator of every error ratio.
                let kind_scenes: Vec<(&str, f64)> = scenes
                    .iter()
                    .filter(|sc| Kind::of(sc) == kind)
                    .filter_map(|sc| {
                        let (_, e) = usable(&sc.name, &noaa, metric)?;
                        (e > 0.0).then_some((sc.name.as_str(), e))
                    })
                    .collect();
                if kind_scenes.is_empty() {
                    continue;
                }
                if metric == Metric::Flip {
                    for m in &methods {
                        let missing: Vec<String> = kind_scenes
                            .iter()
                            .filter(|(sc, _)| usable(sc, m, metric).is_none())
                            .map(|(sc, _)| sc.to_string())
                            .collect();
                        if !missing.is_empty() && missing.len() < kind_scenes.len() {
                            partial.push(Partial {
                                kind,
                                backend: b.clone(),
                                method: m.clone(),
                                missing,
                            });
                        }
                    }
                }
                for budget in BUDGETS {
                    let mut best: Option<Pick> = None;
                    for m in &methods {
                        let mut sum = 0.0;
                        let mut worst: f64 = 0.0;
                        let mut ok = true;
                        for (sc, e_noaa) in &kind_scenes {
                            let Some((r, e)) = usable(sc, m, metric) else {
                                ok = false;
                                break;
                            };
                            let ratio = if *m == noaa {
                                Some(r.ratio_to_noaa.unwrap_or(1.0))
                            } else {
                                r.ratio_to_noaa
                            };
                            match (budget, ratio) {
                                (Some(lim), Some(t)) if t <= lim => worst = worst.max(t),
                                (Some(_), _) => {
                                    ok = false;
                                    break;
                                }
                                (None, t) => worst = worst.max(t.unwrap_or(f64::NAN)),
                            }
                            sum += e / e_noaa;
                        }
                        if !ok {
                            continue;
                        }
                        let mean = sum / kind_scenes.len() as f64;
                        let better = best.as_ref().is_none_or(|p| {
                            mean < p.mean_error_ratio
                                || (mean == p.mean_error_ratio
                                    && worst.total_cmp(&p.worst_time_ratio).is_lt())
                        });
                        if better {
                            let on_front = kind_scenes
                                .iter()
                                .filter(|(sc, _)| {
                                    fronts.iter().any(|f| {
                                        f.scene == *sc
                                            && f.backend == b
                                            && f.metric == metric
                                            && f.points.iter().any(|p| {
                                                p.method == *m
                                                    || ex.iter().any(|e| {
                                                        e.scene == *sc
                                                            && e.backend == b
                                                            && e.method == *m
                                                            && matches!(&e.why, Why::SameImage { as_method } if *as_method == p.method)
                                                    })
                                            })
                                    })
                                })
                                .count();
                            best = Some(Pick {
                                kind,
                                backend: b.clone(),
                                metric,
                                budget,
                                scenes: kind_scenes.iter().map(|(s, _)| s.to_string()).collect(),
                                method: m.clone(),
                                mean_error_ratio: mean,
                                worst_time_ratio: worst,
                                on_front,
                            });
                        }
                    }
                    out.extend(best);
                }
            }
        }
    }
    (out, partial)
}

fn budget_name(b: Option<f64>) -> String {
    match b {
        Some(x) => format!("≤ {x}× NoAA"),
        None => "any".into(),
    }
}

/// The sizes of `kind`'s scenes, `96x64 (errors at 96x64)`, distinct ones
/// joined.
fn sizes(scenes: &[SceneInfo], kind: Kind) -> Option<String> {
    let mut s: Vec<String> = Vec::new();
    for sc in scenes.iter().filter(|sc| Kind::of(sc) == kind) {
        let t = format!(
            "{}x{}{}",
            sc.timing_size.0,
            sc.timing_size.1,
            match sc.quality_size {
                Some(q) => format!(" (errors at {}x{})", q.0, q.1),
                None => String::new(),
            }
        );
        if !s.contains(&t) {
            s.push(t);
        }
    }
    (!s.is_empty()).then(|| s.join(", "))
}

/// The regime of the run in one sentence: backend, machine, threads,
/// sizes, shading cost.
pub fn regime(ctx: &Context) -> String {
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    let mut sz = Vec::new();
    for kind in Kind::ALL {
        if let Some(s) = sizes(&ctx.scenes, kind) {
            sz.push(format!("{} scenes timed at {s}", kind.name()));
        }
    }
    format!(
        "**Regime:** backend {} on {}, {threads} hardware threads; {}; shading with {} ambient-occlusion rays per shaded point on triangle scenes (none on SDF scenes); {} timed rounds{}.",
        ctx.backend_descriptions.join(", "),
        cpu_model(),
        sz.join("; "),
        ctx.ao,
        ctx.runs,
        if ctx.mode == Mode::TimingOnly {
            String::new()
        } else {
            format!(", errors against {}", ctx.reference)
        }
    )
}

fn point(p: &Point, twins: &[RowKey]) -> String {
    let name = if twins.is_empty() {
        p.method.to_string()
    } else {
        let twins: Vec<String> = twins.iter().map(RowKey::to_string).collect();
        format!("{} (= {})", p.method, twins.join(", "))
    };
    format!("{name} {} ms · {:.4}", ms(p.ms), p.error)
}

/// The section of `report.md`: the regime, the picks per kind and budget
/// under both metrics and where they disagree, the fronts per scene, and
/// what was left out.
pub fn section(a: &Answer, rows: &[ResultRow], ctx: &Context) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## The answer: what to use at each cost\n");
    let _ = writeln!(md, "{}\n", regime(ctx));
    if a.fronts.is_empty() {
        let _ = writeln!(
            md,
            "No errors were measured, so there is no front and no pick.\n"
        );
        return md;
    }
    let twins_of = |scene: &str, backend: &str, method: &RowKey| -> Vec<RowKey> {
        rows.iter()
            .find(|r| r.scene == scene && r.backend == backend && r.method == *method)
            .map(|r| same_image_twins(&a.excluded, r))
            .unwrap_or_default()
    };
    if !a.picks.is_empty() {
        let _ = writeln!(
            md,
            "Which method to use per kind of scene and budget of time over NoAA's, under each metric (FLIP, and 1 − SSIM so that lower is better under both): {RULE}. In brackets: that mean error ratio, and on how many of the scenes the method is on the front below.\n"
        );
        let _ = writeln!(
            md,
            "| scenes | backend | budget | use (FLIP) | use (SSIM) | the metrics |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|---|");
        for kind in Kind::ALL {
            for b in backends(&rows.iter().collect::<Vec<_>>()) {
                for budget in BUDGETS {
                    let fl = a.pick(kind, &b, Metric::Flip, budget);
                    let ss = a.pick(kind, &b, Metric::Ssim, budget);
                    if fl.is_none() && ss.is_none() {
                        continue;
                    }
                    let cell = |p: Option<&Pick>| match p {
                        Some(p) => format!(
                            "{} ({:.2}, {}/{})",
                            p.method,
                            p.mean_error_ratio,
                            p.on_front,
                            p.scenes.len()
                        ),
                        None => "–".into(),
                    };
                    let n = fl.or(ss).map_or(0, |p| p.scenes.len());
                    let agree = match (fl, ss) {
                        (Some(x), Some(y)) if x.method == y.method => "agree".to_string(),
                        (Some(x), Some(y)) => {
                            format!("**disagree**: {} or {}", x.method, y.method)
                        }
                        _ => "–".into(),
                    };
                    let _ = writeln!(
                        md,
                        "| {} ({n}) | {b} | {} | {} | {} | {agree} |",
                        kind.name(),
                        budget_name(budget),
                        cell(fl),
                        cell(ss),
                    );
                }
            }
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(
        md,
        "Pareto fronts per scene: methods in time order with their median ms at the timing size and their error; a method is on the front when every faster method has a higher error.\n"
    );
    let _ = writeln!(
        md,
        "| scene | backend | FLIP front (ms · FLIP) | SSIM front (ms · 1 − SSIM) |"
    );
    let _ = writeln!(md, "|---|---|---|---|");
    let mut keys: Vec<(&str, &str)> = Vec::new();
    for f in &a.fronts {
        if !keys.contains(&(f.scene.as_str(), f.backend.as_str())) {
            keys.push((f.scene.as_str(), f.backend.as_str()));
        }
    }
    for (scene, b) in keys {
        let show = |metric: Metric| match a.front(scene, b, metric) {
            Some(f) => f
                .points
                .iter()
                .map(|p| point(p, &twins_of(scene, b, &p.method)))
                .collect::<Vec<_>>()
                .join(" → "),
            None => "–".into(),
        };
        let _ = writeln!(
            md,
            "| {scene} | {b} | {} | {} |",
            show(Metric::Flip),
            show(Metric::Ssim)
        );
    }
    let _ = writeln!(md);
    let mut notes: Vec<String> = Vec::new();
    // One line per method, backend and reason, naming the scenes.
    let mut groups: Vec<(&Excluded, Vec<&str>)> = Vec::new();
    for e in &a.excluded {
        match groups.iter_mut().find(|(g, _)| {
            g.method == e.method && g.backend == e.backend && g.reason() == e.reason()
        }) {
            Some((_, s)) => s.push(&e.scene),
            None => groups.push((e, vec![&e.scene])),
        }
    }
    for (e, scenes) in groups {
        let label = match &e.why {
            Why::SameImage { as_method } => {
                format!("{} (same image as {as_method})", e.method)
            }
            Why::OtherDevice { .. } => format!("{} †", e.method),
        };
        notes.push(format!(
            "{label} on {} ({}): {}",
            e.backend,
            scenes.join(", "),
            e.reason()
        ));
    }
    if !notes.is_empty() {
        let _ = writeln!(md, "Left out of the fronts: {}.\n", notes.join("; "));
    }
    let partial: Vec<String> = a
        .partial
        .iter()
        .map(|p| {
            format!(
                "{} on {} scenes ({}; not on {})",
                p.method,
                p.kind.name(),
                p.backend,
                p.missing.join(", ")
            )
        })
        .collect();
    if !partial.is_empty() {
        let _ = writeln!(
            md,
            "No candidate for a kind because it did not run (or was timed on another device) on every scene of it: {}.\n",
            partial.join("; ")
        );
    }
    md
}

/// The answer in `results.json`: the budgets, the rule, the fronts, the
/// picks and what was left out.
pub fn json(a: &Answer) -> Value {
    let metric = |m: Metric| match m {
        Metric::Flip => "flip",
        Metric::Ssim => "ssim",
    };
    json!({
        "error": {"flip": "mean FLIP", "ssim": "1 - mean SSIM"},
        "budgets": BUDGETS,
        "rule": RULE,
        "fronts": a.fronts.iter().map(|f| json!({
            "scene": f.scene,
            "backend": f.backend,
            "metric": metric(f.metric),
            "points": f.points.iter().map(|p| json!({
                "method": p.method, "ms_median": p.ms, "ratio_to_noaa": p.ratio, "error": p.error,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "picks": a.picks.iter().map(|p| json!({
            "kind": match p.kind { Kind::Triangles => "triangles", Kind::Sdf => "sdf" },
            "backend": p.backend,
            "metric": metric(p.metric),
            "budget": p.budget,
            "scenes": p.scenes,
            "method": p.method,
            "mean_error_ratio": p.mean_error_ratio,
            "worst_time_ratio": if p.worst_time_ratio.is_finite() { json!(p.worst_time_ratio) } else { Value::Null },
            "on_front": p.on_front,
        })).collect::<Vec<_>>(),
        "excluded": a.excluded.iter().map(|e| json!({
            "scene": e.scene,
            "backend": e.backend,
            "method": e.method,
            "same_image_as": match &e.why { Why::SameImage { as_method } => json!(as_method), _ => Value::Null },
            "other_device": matches!(e.why, Why::OtherDevice { .. }),
            "reason": e.reason(),
        })).collect::<Vec<_>>(),
        "partial": a.partial.iter().map(|p| json!({
            "kind": match p.kind { Kind::Triangles => "triangles", Kind::Sdf => "sdf" },
            "backend": p.backend, "method": p.method, "missing": p.missing,
        })).collect::<Vec<_>>(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timing::Timings;

    /// The name of the method `a` picks on the cpu backend.
    fn picked(a: &Answer, kind: Kind, metric: Metric, budget: Option<f64>) -> String {
        a.pick(kind, "cpu", metric, budget)
            .unwrap()
            .method
            .to_string()
    }

    /// What `a` picks on the cpu backend under FLIP: `method`, with its mean
    /// error ratio over NoAA's and on how many scenes it is on the front.
    fn assert_pick(
        a: &Answer,
        kind: Kind,
        budget: Option<f64>,
        method: &str,
        mean_error_ratio: f64,
        on_front: usize,
    ) {
        let p = a.pick(kind, "cpu", Metric::Flip, budget).unwrap();
        assert_eq!(p.method.to_string(), method);
        assert!(
            (p.mean_error_ratio - mean_error_ratio).abs() < 1e-12,
            "{method}: mean error ratio {}",
            p.mean_error_ratio
        );
        assert_eq!(p.on_front, on_front, "{method}");
    }

    const WHY: &str = "software adapter";

    #[test]
    fn pareto_front_keeps_only_improvements() {
        let key = |p: &(f64, f64)| *p;
        let f = pareto_by(
            vec![(10.0, 0.2), (1.0, 0.5), (5.0, 0.6), (20.0, 0.1), (2.0, 0.3)],
            key,
        );
        assert_eq!(f, vec![(1.0, 0.5), (2.0, 0.3), (10.0, 0.2), (20.0, 0.1)]);
        assert!(pareto_by(vec![(f64::NAN, 0.1)], key).is_empty());
    }

    fn row(scene: &str, method: &str, ms: f64, flip: f64, ssim: f64) -> ResultRow {
        let mut r = ResultRow::timed(
            scene,
            crate::key::named(method),
            "cpu",
            (4, 4),
            3,
            &Timings::default(),
        );
        r.ms_median = ms;
        // Rounds within 10 % of the median, as on a quiet machine.
        (r.ms_min, r.ms_max) = (ms * 0.9, ms * 1.1);
        r.timed_by = vec![TimingSource::Cpu];
        r.flip_mean = Some(flip);
        r.ssim_mean = Some(ssim);
        r
    }

    /// `row` with its time over NoAA's, NoAA taking 1 ms.
    fn timed(scene: &str, method: &str, ratio: f64, flip: f64, ssim: f64) -> ResultRow {
        let mut r = row(scene, method, ratio, flip, ssim);
        r.ratio_to_noaa = Some(ratio);
        r
    }

    fn scene(name: &str, sdf: bool) -> SceneInfo {
        SceneInfo {
            name: crate::key::SceneId::new(name),
            arg: name.into(),
            sdf,
            timing_size: (4, 4),
            quality_size: Some((4, 4)),
        }
    }

    fn methods(f: Option<&Front>) -> Vec<String> {
        f.map(|f| f.points.iter().map(|p| p.method.to_string()).collect())
            .unwrap_or_default()
    }

    /// One triangle scene: noaa, fxaa (cheap, a little better), ssaa4,
    /// sraa (dearer than ssaa4 and worse), ssaa16.
    fn triangle_rows() -> Vec<ResultRow> {
        vec![
            timed("t", "noaa", 1.0, 0.10, 0.90),
            timed("t", "fxaa", 1.2, 0.09, 0.95),
            timed("t", "ssaa4", 3.0, 0.05, 0.96),
            timed("t", "sraa", 5.0, 0.06, 0.97),
            timed("t", "ssaa16", 12.0, 0.03, 0.99),
        ]
    }

    #[test]
    fn a_row_slower_changes_the_front_and_the_pick() {
        let scenes = [scene("t", false)];
        let mut rows = triangle_rows();
        let a = Answer::of(&rows, &scenes);
        assert_eq!(
            methods(a.front("t", "cpu", Metric::Flip)),
            ["noaa", "fxaa", "ssaa4", "ssaa16"]
        );
        assert_pick(&a, Kind::Triangles, Some(4.0), "ssaa4", 0.5, 1);
        assert_eq!(picked(&a, Kind::Triangles, Metric::Flip, Some(1.5)), "fxaa");
        assert_eq!(picked(&a, Kind::Triangles, Metric::Flip, None), "ssaa16");

        // ssaa4 now takes 6× NoAA: sraa (5×, worse than ssaa4) joins the
        // front, and nothing but fxaa is left within 4×.
        let s4 = rows
            .iter_mut()
            .find(|r| r.method.to_string() == "ssaa4")
            .unwrap();
        s4.ms_median = 6.0;
        s4.ratio_to_noaa = Some(6.0);
        let b = Answer::of(&rows, &scenes);
        assert_eq!(
            methods(b.front("t", "cpu", Metric::Flip)),
            ["noaa", "fxaa", "sraa", "ssaa4", "ssaa16"]
        );
        assert_eq!(picked(&b, Kind::Triangles, Metric::Flip, Some(4.0)), "fxaa");
        let md = section(&b, &rows, &context(&scenes));
        assert!(
            md.contains("noaa 1.00 ms · 0.1000 → fxaa 1.20 ms · 0.0900 → sraa 5.00 ms · 0.0600"),
            "{md}"
        );
    }

    fn context(scenes: &[SceneInfo]) -> Context {
        Context {
            mode: Mode::Quick,
            backends: vec!["cpu".into()],
            backend_descriptions: vec!["cpu (test)".into()],
            runs: 3,
            reference: "ssaa64".into(),
            scenes: scenes
                .iter()
                .map(|s| SceneInfo {
                    name: s.name.clone(),
                    arg: s.arg.clone(),
                    ..*s
                })
                .collect(),
            ao: 0,
            other_cpu: Default::default(),
        }
    }

    #[test]
    fn the_metrics_can_disagree_and_the_section_says_so() {
        let scenes = [scene("t", false)];
        // Under SSIM fxaa is better than ssaa4 within 4×, under FLIP worse.
        let mut rows = triangle_rows();
        rows[1].ssim_mean = Some(0.98);
        let a = Answer::of(&rows, &scenes);
        assert_eq!(picked(&a, Kind::Triangles, Metric::Ssim, Some(4.0)), "fxaa");
        assert_eq!(
            picked(&a, Kind::Triangles, Metric::Flip, Some(4.0)),
            "ssaa4"
        );
        let md = section(&a, &rows, &context(&scenes));
        let line = md
            .lines()
            .find(|l| l.starts_with("| triangle (1) | cpu | ≤ 4× NoAA |"))
            .unwrap_or_else(|| panic!("{md}"));
        assert!(line.ends_with("| **disagree**: ssaa4 or fxaa |"), "{line}");
        assert!(md
            .lines()
            .any(|l| l.starts_with("| triangle (1) | cpu | any |") && l.ends_with("| agree |")));
    }

    #[test]
    fn a_repeated_image_is_named_and_plotted_once() {
        let mut rows = vec![
            timed("s", "noaa", 1.0, 0.10, 0.90),
            timed("s", "ctss", 1.2, 0.08, 0.92),
            timed("s", "ctss-delayed", 1.4, 0.08, 0.92),
        ];
        rows[1].image_digest = Some(7);
        rows[2].image_digest = Some(7);
        rows[0].image_digest = Some(8);
        let all: Vec<&ResultRow> = rows.iter().collect();
        let ex = exclusions(&all);
        assert_eq!(ex.len(), 1);
        assert_eq!(ex[0].method.to_string(), "ctss-delayed");
        assert_eq!(ex[0].mark(), "(same image as ctss)");
        assert_eq!(
            same_image_twins(&ex, &rows[1]),
            [crate::key::named("ctss-delayed")]
        );
        assert_eq!(
            methods(Some(&Front {
                scene: "s".into(),
                backend: "cpu".into(),
                metric: Metric::Flip,
                points: front(&all, &ex, Metric::Flip)
            })),
            ["noaa", "ctss"]
        );
        // Were the delayed one faster within the rounds' noise, the name
        // would not change with the clock: ctss, first in table order,
        // stands for the image.
        rows[2].ms_median = 1.1;
        let all: Vec<&ResultRow> = rows.iter().collect();
        let ex = exclusions(&all);
        assert_eq!(ex.len(), 1);
        assert_eq!(ex[0].method.to_string(), "ctss-delayed");
        let a = Answer::of(&rows, &[scene("s", true)]);
        let md = section(&a, &rows, &context(&[scene("s", true)]));
        assert!(md.contains("ctss (= ctss-delayed) 1.20 ms"), "{md}");
        assert!(
            md.contains("ctss-delayed (same image as ctss) on cpu (s): its image is byte-identical to ctss's"),
            "{md}"
        );
    }

    #[test]
    fn a_repeated_image_faster_in_every_round_stands_for_it_and_stays_a_candidate() {
        // A hybrid gives its traced twin's image sooner in every round: the
        // front shows the hybrid's time, and the picks may take either.
        let mut rows = vec![
            timed("s", "noaa", 1.0, 0.10, 0.90),
            timed("s", "ssaa4", 3.0, 0.05, 0.95),
            timed("s", "ssaa4-hybrid", 2.0, 0.05, 0.95),
        ];
        rows[0].image_digest = Some(8);
        rows[1].image_digest = Some(7);
        rows[2].image_digest = Some(7);
        let a = Answer::of(&rows, &[scene("s", false)]);
        assert_eq!(a.excluded.len(), 1);
        assert_eq!(a.excluded[0].mark(), "(same image as ssaa4-hybrid)");
        assert_eq!(
            methods(a.front("s", "cpu", Metric::Flip)),
            ["noaa", "ssaa4-hybrid"]
        );
        // Same error, lower worst time: the hybrid is the pick; and the
        // traced twin, no longer left out of the picks, is no partial.
        assert_eq!(
            picked(&a, Kind::Triangles, Metric::Flip, Some(4.0)),
            "ssaa4-hybrid"
        );
        assert!(a.partial.is_empty(), "{:?}", a.partial);
        let p = a.pick(Kind::Triangles, "cpu", Metric::Flip, None).unwrap();
        assert_eq!(p.on_front, 1);
        // Within a budget only the traced twin meets, the traced twin is
        // picked, and counted on the front through the hybrid that stands
        // for its image.
        rows[2].ratio_to_noaa = Some(5.0);
        let a = Answer::of(&rows, &[scene("s", false)]);
        let p = a
            .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
            .unwrap();
        assert_eq!((p.method.to_string(), p.on_front), ("ssaa4".into(), 1));
    }

    #[test]
    fn a_row_timed_on_another_device_is_left_out_with_its_reason() {
        let mut rows = triangle_rows();
        let mut smaa = timed("t", "smaa", 1.1, 0.01, 0.999);
        smaa.timed_by = vec![TimingSource::Cpu, TimingSource::GpuWallClock { why: WHY }];
        rows.push(smaa);
        let a = Answer::of(&rows, &[scene("t", false)]);
        assert!(!methods(a.front("t", "cpu", Metric::Flip)).contains(&"smaa".to_string()));
        assert_eq!(picked(&a, Kind::Triangles, Metric::Flip, Some(1.5)), "fxaa");
        assert_eq!(a.excluded.len(), 1);
        assert_eq!(a.excluded[0].mark(), "†");
        let reason = a.excluded[0].reason();
        assert!(
            reason.contains(WHY) && reason.contains("CPU wall clock"),
            "{reason}"
        );
        // Without NoAA there is no axis to be off.
        rows.retain(|r| r.method.to_string() != "noaa");
        let all: Vec<&ResultRow> = rows.iter().collect();
        assert!(exclusions(&all).is_empty());
    }

    #[test]
    fn picks_are_per_kind_and_need_every_scene_of_it() {
        let scenes = [scene("t", false), scene("u", false), scene("d", true)];
        let mut rows = triangle_rows();
        rows.extend([
            timed("u", "noaa", 1.0, 0.20, 0.90),
            timed("u", "ssaa4", 3.0, 0.12, 0.95),
            // fxaa did not run on u: no candidate for triangle scenes.
            timed("d", "noaa", 1.0, 0.10, 0.90),
            timed("d", "ctss", 1.2, 0.07, 0.93),
            timed("d", "ssaa4", 3.5, 0.05, 0.96),
        ]);
        let a = Answer::of(&rows, &scenes);
        let t = a
            .pick(Kind::Triangles, "cpu", Metric::Flip, Some(1.5))
            .unwrap();
        assert_eq!((t.method.to_string().as_str(), t.scenes.len()), ("noaa", 2));
        // (0.05/0.10 + 0.12/0.20) / 2
        assert_pick(&a, Kind::Triangles, Some(4.0), "ssaa4", 0.55, 2);
        assert_eq!(picked(&a, Kind::Sdf, Metric::Flip, Some(1.5)), "ctss");
        assert_eq!(picked(&a, Kind::Sdf, Metric::Flip, Some(4.0)), "ssaa4");
        let missing: Vec<(String, &[String])> = a
            .partial
            .iter()
            .filter(|p| p.kind == Kind::Triangles)
            .map(|p| (p.method.to_string(), p.missing.as_slice()))
            .collect();
        assert!(
            missing
                .iter()
                .any(|(m, s)| *m == "fxaa" && *s == ["u".to_string()]),
            "{missing:?}"
        );
    }

    #[test]
    fn no_errors_no_front() {
        let mut rows = triangle_rows();
        for r in &mut rows {
            (r.flip_mean, r.ssim_mean) = (None, None);
        }
        let a = Answer::of(&rows, &[scene("t", false)]);
        assert!(a.fronts.is_empty() && a.picks.is_empty());
        assert!(section(&a, &rows, &context(&[scene("t", false)])).contains("no front"));
    }
}
