//! The picks: the method to use per kind of scene, backend, metric and
//! budget, by the rule [`RULE`](super::RULE) states.

use super::excluded::{excluded, exclusions, Excluded, Why};
use super::front::{front, Front};
use super::{error, errors_at, BUDGETS};
use crate::classes::Metric;
use crate::context::SceneInfo;
use crate::key::RowKey;
use crate::named::NOAA;
use crate::ResultRow;

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

    pub(super) fn of(sc: &SceneInfo) -> Kind {
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
    /// The next method by the same rule within the budget that renders
    /// other images (a `-hybrid` and its traced twin are one choice), with
    /// its mean error ratio (`None` when there is none).
    pub runner_up: Option<(RowKey, f64)>,
    /// Why the decision is within noise, one clause each: the runner-up
    /// with less error at some camera offset, the pick over the budget in
    /// some round, a method with less error out of the budget by its
    /// median but within it in some round. Empty when the pick holds.
    pub noise: Vec<String>,
}

impl Pick {
    /// The runner-up's mean error ratio over the pick's, less one: how much
    /// more error the next choice has (`None` without a runner-up).
    pub fn margin(&self) -> Option<f64> {
        self.runner_up
            .as_ref()
            .map(|(_, e)| e / self.mean_error_ratio - 1.0)
    }
}

/// Whether a median time over NoAA's `t` is within the budget `lim`
/// (no time is not).
fn within(t: Option<f64>, lim: f64) -> bool {
    t.is_some_and(|t| t <= lim)
}

/// One scene's time over NoAA's for a candidate: the scene, the median of
/// the per-round ratios, and their smallest and largest.
type SceneTime<'a> = (&'a str, Option<f64>, Option<(f64, f64)>);

/// A method's figures over the scenes of a kind, for the picks.
struct Candidate<'a> {
    method: &'a RowKey,
    /// Mean over the scenes of its error over NoAA's.
    mean: f64,
    /// Per scene: the scene, its time over NoAA's (median of the rounds)
    /// and the smallest and largest per-round one.
    times: Vec<SceneTime<'a>>,
    /// Per camera offset, the mean over the scenes of its error over
    /// NoAA's at that offset (empty unless every row has the same offsets).
    at_offsets: Vec<f64>,
    /// Its quality image's digest on each scene ([`ResultRow::image_digest`]).
    digests: Vec<Option<u64>>,
}

impl Candidate<'_> {
    /// Whether it rendered the same image as `other` on every scene (a
    /// `-hybrid` and its traced twin): no alternative to it.
    fn same_images(&self, other: &Candidate) -> bool {
        self.digests.len() == other.digests.len()
            && self
                .digests
                .iter()
                .zip(&other.digests)
                .all(|(a, b)| a.is_some() && a == b)
    }

    /// Whether its median time over NoAA's is within `budget` on every
    /// scene (any time without a budget).
    fn within(&self, budget: Option<f64>) -> bool {
        match budget {
            None => true,
            Some(lim) => self.times.iter().all(|(_, t, _)| within(*t, lim)),
        }
    }

    /// Its largest median time over NoAA's over the scenes (NaN without
    /// one).
    fn worst(&self) -> f64 {
        self.times
            .iter()
            .map(|(_, t, _)| t.unwrap_or(f64::NAN))
            .fold(0.0, f64::max)
    }
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

pub(super) fn backends(rows: &[&ResultRow]) -> Vec<String> {
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

/// The picks ([`RULE`](super::RULE)) for every kind, backend, metric and budget, and the
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
                let noaa_rows: Vec<&ResultRow> = kind_scenes
                    .iter()
                    .filter_map(|(sc, _)| Some(usable(sc, &noaa, metric)?.0))
                    .collect();
                let candidates: Vec<Candidate> = methods
                    .iter()
                    .filter_map(|m| {
                        let got: Vec<(&ResultRow, f64)> = kind_scenes
                            .iter()
                            .map(|(sc, _)| usable(sc, m, metric))
                            .collect::<Option<_>>()?;
                        Some(candidate(
                            m,
                            *m == noaa,
                            &got,
                            &kind_scenes,
                            &noaa_rows,
                            metric,
                        ))
                    })
                    .collect();
                for budget in BUDGETS {
                    let mut admitted: Vec<&Candidate> =
                        candidates.iter().filter(|c| c.within(budget)).collect();
                    // Stable: on equal figures, the first in table order.
                    admitted.sort_by(|x, y| {
                        x.mean
                            .total_cmp(&y.mean)
                            .then(x.worst().total_cmp(&y.worst()))
                    });
                    let Some(best) = admitted.first() else {
                        continue;
                    };
                    // The runner-up: the next that renders other images
                    // (a repeated image is no alternative).
                    let runner = admitted
                        .iter()
                        .skip(1)
                        .find(|c| !c.same_images(best))
                        .copied();
                    let on_front = kind_scenes
                        .iter()
                        .filter(|(sc, _)| on_the_front(fronts, ex, sc, &b, metric, best.method))
                        .count();
                    out.push(Pick {
                        kind,
                        backend: b.clone(),
                        metric,
                        budget,
                        scenes: kind_scenes.iter().map(|(s, _)| s.to_string()).collect(),
                        method: best.method.clone(),
                        mean_error_ratio: best.mean,
                        worst_time_ratio: best.worst(),
                        on_front,
                        runner_up: runner.map(|r| (r.method.clone(), r.mean)),
                        noise: noise(best, runner, &candidates, budget),
                    });
                }
            }
        }
    }
    (out, partial)
}

/// The figures of method `m` (NoAA itself when `is_noaa`) over the scenes
/// of a kind: `got[i]` its row and error on `kind_scenes[i]`, whose NoAA
/// error is the denominator; `noaa_rows` NoAA's rows, for the per-offset
/// errors.
fn candidate<'a>(
    m: &'a RowKey,
    is_noaa: bool,
    got: &[(&'a ResultRow, f64)],
    kind_scenes: &[(&'a str, f64)],
    noaa_rows: &[&ResultRow],
    metric: Metric,
) -> Candidate<'a> {
    let mean = got
        .iter()
        .zip(kind_scenes)
        .map(|((_, e), (_, n))| e / n)
        .sum::<f64>()
        / kind_scenes.len() as f64;
    let times = got
        .iter()
        .zip(kind_scenes)
        .map(|((r, _), (sc, _))| {
            let t = if is_noaa {
                Some(r.ratio_to_noaa.unwrap_or(1.0))
            } else {
                r.ratio_to_noaa
            };
            (*sc, t, r.ratio_min.zip(r.ratio_max))
        })
        .collect();
    // Per offset: the mean over the scenes of its error over NoAA's at the
    // same offset; only when every row has the same offsets, NoAA's all
    // non-zero.
    let mine: Vec<Vec<f64>> = got.iter().map(|(r, _)| errors_at(r, metric)).collect();
    let theirs: Vec<Vec<f64>> = noaa_rows.iter().map(|r| errors_at(r, metric)).collect();
    let k = mine.first().map_or(0, Vec::len);
    let paired = k > 1
        && theirs.len() == mine.len()
        && mine.iter().chain(&theirs).all(|v| v.len() == k)
        && theirs.iter().flatten().all(|&e| e > 0.0);
    let at_offsets = if paired {
        (0..k)
            .map(|o| {
                mine.iter()
                    .zip(&theirs)
                    .map(|(a, n)| a[o] / n[o])
                    .sum::<f64>()
                    / mine.len() as f64
            })
            .collect()
    } else {
        Vec::new()
    };
    Candidate {
        method: m,
        mean,
        times,
        at_offsets,
        digests: got.iter().map(|(r, _)| r.image_digest).collect(),
    }
}

/// Whether `method` (or a row whose image it repeats) is on the front of
/// `scene`, `backend` and `metric`.
fn on_the_front(
    fronts: &[Front],
    ex: &[Excluded],
    scene: &str,
    backend: &str,
    metric: Metric,
    method: &RowKey,
) -> bool {
    fronts.iter().any(|f| {
        f.scene == scene
            && f.backend == backend
            && f.metric == metric
            && f.points.iter().any(|p| {
                p.method == *method || ex.iter().any(|e| {
                    e.scene == scene
                        && e.backend == backend
                        && e.method == *method
                        && matches!(&e.why, Why::SameImage { as_method } if *as_method == p.method)
                })
            })
    })
}

/// Why the pick `best` (with `runner` next) is within noise under
/// `budget`, one clause each ([`Pick::noise`]).
fn noise(
    best: &Candidate,
    runner: Option<&Candidate>,
    all: &[Candidate],
    budget: Option<f64>,
) -> Vec<String> {
    let mut why = Vec::new();
    if let Some(r) = runner {
        if best.at_offsets.len() == r.at_offsets.len() {
            let flips: Vec<String> = best
                .at_offsets
                .iter()
                .zip(&r.at_offsets)
                .enumerate()
                .filter(|(_, (b, r))| r <= b)
                .map(|(k, _)| k.to_string())
                .collect();
            if !flips.is_empty() {
                why.push(format!(
                    "{} has the lower mean error ratio at camera offset {} of {}",
                    r.method,
                    flips.join(", "),
                    best.at_offsets.len()
                ));
            }
        }
    }
    let Some(lim) = budget else {
        return why;
    };
    for (sc, _, range) in &best.times {
        if let Some((_, hi)) = range.filter(|(_, hi)| *hi > lim) {
            why.push(format!(
                "its own time over NoAA's on {sc} reaches {hi:.2}× in a round, over the {lim}× budget"
            ));
        }
    }
    for c in all
        .iter()
        .filter(|c| c.mean < best.mean && !c.within(Some(lim)))
    {
        // Out of the budget by its median on some scenes: within it in a
        // round on every one of them?
        let out: Vec<&SceneTime> = c
            .times
            .iter()
            .filter(|(_, t, _)| !within(*t, lim))
            .collect();
        let in_a_round = out
            .iter()
            .all(|(_, _, range)| range.is_some_and(|(lo, _)| lo <= lim));
        if in_a_round {
            let spans: Vec<String> = out
                .iter()
                .map(|(sc, t, range)| {
                    let (lo, hi) = range.unwrap_or((f64::NAN, f64::NAN));
                    format!(
                        "{:.2}× on {sc} (rounds {lo:.2}–{hi:.2}×)",
                        t.unwrap_or(f64::NAN)
                    )
                })
                .collect();
            why.push(format!(
                "{} (mean error ratio {:.2}) is out of the {lim}× budget by its median, {}, but within it in a round",
                c.method,
                c.mean,
                spans.join(", ")
            ));
        }
    }
    why
}
