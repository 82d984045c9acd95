//! The picks: the method to use per kind of scene, backend, metric and
//! budget, by the rule [`RULE`](super::RULE) states.

use super::excluded::{excluded, exclusions, Excluded, Why};
use super::front::{front, Front};
use super::{error, BUDGETS};
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
