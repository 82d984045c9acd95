//! The rows of "Where SRAA pays" ([`crate::ao_sweep`], which renders them)
//! and their crossover: per scene,
//! backend and [`Pair`], the fewest ambient-occlusion rays per shaded point
//! at which the pair's `sraa-rt` takes less time than its `ssaa4`.
//!
//! The two pairs are compared within themselves: traced with traced
//! (`ssaa4` against `sraa-rt`) and hybrid with hybrid (`ssaa4-hybrid`
//! against `sraa-rt-hybrid`, primary visibility rasterised as in SRAA §3.1
//! and §4.2). Rasterising takes the same primary cost off both sides of a
//! pair, so the crossover says where SRAA's one shaded sample per pixel
//! starts to pay for its reconstruction under each way of finding the
//! primary hits; the hybrid one is judged against
//! [`HYBRID_CROSSOVER_AO`].

use crate::named::{hybrid, NOAA, SRAA_RT, SSAA2, SSAA4};
use subcone_scene::Method;

/// One method at one AO ray count on one scene and backend.
#[derive(Clone, Debug, PartialEq)]
pub struct AoSweepRow {
    /// Scene name.
    pub scene: String,
    /// Method.
    pub method: Method,
    /// Backend.
    pub backend: String,
    /// AO rays per shaded point.
    pub ao: u32,
    /// Median wall time of the timed runs, ms.
    pub ms_median: f64,
    /// Fastest and slowest timed run, ms.
    pub ms_range: (f64, f64),
    /// Every ray cast, per pixel.
    pub rays_per_pixel: f64,
    /// AO rays cast, per pixel.
    pub ao_rays_per_pixel: f64,
    /// Mean FLIP over the silhouette, crease and shadow pixels together
    /// (`None` without a reference, or when the scene has none).
    pub edge_flip: Option<f64>,
    /// Mean FLIP of the whole image.
    pub flip_mean: Option<f64>,
}

/// A method a backend did not sweep because it refuses it
/// ([`Backend::supports`](subcone_scene::Backend::supports)).
#[derive(Clone, Debug, PartialEq)]
pub struct Refused {
    /// Scene.
    pub scene: String,
    /// Backend.
    pub backend: String,
    /// Method.
    pub method: Method,
    /// The backend's reason.
    pub reason: String,
}

/// What the section has: its rows and the scenes it could not sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AoSweep {
    /// Whether it ran (the default report, or `--sraa-sweep`).
    pub ran: bool,
    /// The AO ray counts swept, increasing.
    pub aos: Vec<u32>,
    /// The reference of the rows with AO, when it is not the run's.
    pub ao_reference: Option<String>,
    /// One row per scene, backend, method and AO ray count.
    pub rows: Vec<AoSweepRow>,
    /// Scenes of [`AO_SWEEP_SCENES`](crate::ao_sweep::AO_SWEEP_SCENES) not swept, with the reason.
    pub missing: Vec<(String, String)>,
    /// Methods a backend refuses, not swept there (no failure).
    pub refused: Vec<Refused>,
}

/// The row of `method` at `ao` on `scene` and `backend`.
pub(crate) fn find<'a>(
    rows: &'a [AoSweepRow],
    scene: &str,
    backend: &str,
    method: Method,
    ao: u32,
) -> Option<&'a AoSweepRow> {
    rows.iter()
        .find(|r| r.scene == scene && r.backend == backend && r.method == method && r.ao == ao)
}

/// `(ray-count ratio, time ratio)` of the pair's ssaa4 over its sraa-rt.
pub fn ratios(
    rows: &[AoSweepRow],
    scene: &str,
    backend: &str,
    pair: Pair,
    ao: u32,
) -> Option<(f64, f64)> {
    let ss = find(rows, scene, backend, pair.ssaa4(), ao)?;
    let rt = find(rows, scene, backend, pair.sraa_rt(), ao)?;
    (rt.rays_per_pixel > 0.0 && rt.ms_median > 0.0).then(|| {
        (
            ss.rays_per_pixel / rt.rays_per_pixel,
            ss.ms_median / rt.ms_median,
        )
    })
}

/// Scenes and backends in the order the rows have them.
pub(crate) fn groups(rows: &[AoSweepRow]) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    for r in rows {
        if !out.iter().any(|(s, b)| *s == r.scene && *b == r.backend) {
            out.push((r.scene.clone(), r.backend.clone()));
        }
    }
    out
}

pub(crate) fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("–".into(), |v| format!("{v:.digits$}"))
}

/// How a triple of the sweep finds its primary samples' triangles. Each
/// crossover compares methods of one pair: hybrid with hybrid, traced with
/// traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pair {
    /// Ray traversal: `noaa`, `ssaa4`, `sraa-rt`.
    Traced,
    /// Rasterisation (`-hybrid`, SRAA §3.1 and §4.2): `noaa-hybrid`,
    /// `ssaa4-hybrid`, `sraa-rt-hybrid`.
    Hybrid,
}

impl Pair {
    /// Both, traced first.
    pub const ALL: [Pair; 2] = [Pair::Traced, Pair::Hybrid];

    /// `"traced"` or `"hybrid"`: the pair column of the table and the
    /// `pair` field of `results.json`'s `ao_crossover`.
    pub fn name(self) -> &'static str {
        match self {
            Pair::Traced => "traced",
            Pair::Hybrid => "hybrid",
        }
    }

    /// The pair a method belongs to.
    pub fn of(method: Method) -> Pair {
        if method.is_hybrid() {
            Pair::Hybrid
        } else {
            Pair::Traced
        }
    }

    /// The pair's version of a traced method.
    fn with(self, traced: Method) -> Method {
        match self {
            Pair::Traced => traced,
            Pair::Hybrid => hybrid(traced),
        }
    }

    /// The pair's NoAA.
    pub fn noaa(self) -> Method {
        self.with(NOAA)
    }

    /// The pair's 2-sample supersampling (the 2×2 grid's diagonal).
    pub fn ssaa2(self) -> Method {
        self.with(SSAA2)
    }

    /// The pair's 2×2 supersampling.
    pub fn ssaa4(self) -> Method {
        self.with(SSAA4)
    }

    /// The pair's SRAA-RT.
    pub fn sraa_rt(self) -> Method {
        self.with(SRAA_RT)
    }

    /// NoAA, SSAA2, SSAA4 and SRAA-RT of the pair: SRAA-RT with an SSAA
    /// neighbour on either side in error.
    pub fn methods(self) -> [Method; 4] {
        [self.noaa(), self.ssaa2(), self.ssaa4(), self.sraa_rt()]
    }
}

/// Target: the hybrid crossover (`sraa-rt-hybrid` faster than
/// `ssaa4-hybrid`, [`Pair::Hybrid`]) at most this many AO rays per shaded
/// point: with the primary visibility rasterised, SRAA should pay from
/// the first ray of shading cost.
pub const HYBRID_CROSSOVER_AO: u32 = 1;

/// The crossover of one pair on one scene and backend: where the pair's
/// `sraa-rt` starts to take less time than its `ssaa4`.
#[derive(Clone, Debug, PartialEq)]
pub struct Crossover {
    /// Scene.
    pub scene: String,
    /// Backend.
    pub backend: String,
    /// The pair compared: traced with traced, or hybrid with hybrid.
    pub pair: Pair,
    /// The fewest swept AO rays at which sraa-rt is faster, with both
    /// methods' rows there; `None` when it is faster at no swept count.
    pub first_faster: Option<FirstFaster>,
    /// The AO ray count where the two times meet, by linear interpolation of
    /// `ssaa4 − sraa-rt` between the last swept count where sraa-rt is slower
    /// and the first where it is faster (`None` when they do not cross
    /// inside the sweep, or sraa-rt is faster from the first count on).
    pub interpolated: Option<f64>,
    /// The AO ray counts at which both methods of the pair were timed,
    /// increasing.
    pub timed_at: Vec<u32>,
    /// Where the times meet when each side's runs are taken at their most
    /// and least favourable to sraa-rt (its fastest run against ssaa4's
    /// slowest, then the other way round), by the same interpolation: the
    /// earliest and latest crossing the runs allow. `None` where either
    /// does not cross inside the sweep; an end at the first swept count
    /// when sraa-rt is faster there already.
    pub interpolated_range: Option<(f64, f64)>,
}

/// Where the pair's sraa-rt first takes less time than its ssaa4
/// ([`Crossover`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstFaster {
    /// AO rays per shaded point.
    pub ao: u32,
    /// sraa-rt's median time there, ms.
    pub sraa_rt_ms: f64,
    /// ssaa4's median time there, ms.
    pub ssaa4_ms: f64,
    /// sraa-rt's edge FLIP there.
    pub sraa_rt_edge_flip: Option<f64>,
    /// ssaa4's edge FLIP there.
    pub ssaa4_edge_flip: Option<f64>,
    /// sraa-rt's fastest and slowest run there, ms.
    pub sraa_rt_ms_range: (f64, f64),
    /// ssaa4's fastest and slowest run there, ms.
    pub ssaa4_ms_range: (f64, f64),
    /// sraa-rt's whole-image FLIP there.
    pub sraa_rt_flip: Option<f64>,
    /// ssaa4's whole-image FLIP there.
    pub ssaa4_flip: Option<f64>,
}

/// The crossover of every scene, backend and pair of the sweep: a pair
/// only where the sweep has a row of its ssaa4 or its sraa-rt.
pub fn crossovers(sweep: &AoSweep) -> Vec<Crossover> {
    let mut out = Vec::new();
    for (scene, backend) in groups(&sweep.rows) {
        for pair in Pair::ALL {
            let has = sweep.rows.iter().any(|r| {
                r.scene == scene
                    && r.backend == backend
                    && (r.method == pair.ssaa4() || r.method == pair.sraa_rt())
            });
            if has {
                out.push(crossover(sweep, &scene, &backend, pair));
            }
        }
    }
    out
}

/// Where a gap `ssaa4 − sraa-rt` (by AO count, increasing) first turns
/// positive: the index of that count, and the count where the gap crosses
/// zero by linear interpolation from the count before (`None` when it is
/// positive from the first count on).
fn meet(gaps: &[(u32, f64)]) -> Option<(usize, Option<f64>)> {
    let at = gaps.iter().position(|g| g.1 > 0.0)?;
    let crossing = at.checked_sub(1).map(|i| {
        let (lo, hi) = (gaps[i], gaps[at]);
        // lo.1 ≤ 0 < hi.1: the gap crosses 0 between them.
        let f = -lo.1 / (hi.1 - lo.1);
        lo.0 as f64 + f * (hi.0 - lo.0) as f64
    });
    Some((at, crossing))
}

/// The crossover of `pair` on `scene` and `backend` (see [`Crossover`]).
pub fn crossover(sweep: &AoSweep, scene: &str, backend: &str, pair: Pair) -> Crossover {
    // (ao, ssaa4 − sraa-rt in ms) where both were timed: by the medians,
    // and by the runs most and least favourable to sraa-rt.
    let (mut gaps, mut best, mut worst) = (Vec::new(), Vec::new(), Vec::new());
    let mut both: Vec<(&AoSweepRow, &AoSweepRow)> = Vec::new();
    let (ssaa4, sraa_rt) = (pair.ssaa4(), pair.sraa_rt());
    let mut aos: Vec<u32> = sweep
        .rows
        .iter()
        .filter(|r| r.scene == scene && r.backend == backend)
        .map(|r| r.ao)
        .collect();
    aos.sort_unstable();
    aos.dedup();
    for ao in aos {
        let (Some(a), Some(b)) = (
            find(&sweep.rows, scene, backend, ssaa4, ao),
            find(&sweep.rows, scene, backend, sraa_rt, ao),
        ) else {
            continue;
        };
        gaps.push((ao, a.ms_median - b.ms_median));
        best.push((ao, a.ms_range.1 - b.ms_range.0));
        worst.push((ao, a.ms_range.0 - b.ms_range.1));
        both.push((a, b));
    }
    let median = meet(&gaps);
    let first_faster = median.map(|(at, _)| {
        let (a, b) = both[at];
        FirstFaster {
            ao: gaps[at].0,
            sraa_rt_ms: b.ms_median,
            ssaa4_ms: a.ms_median,
            sraa_rt_edge_flip: b.edge_flip,
            ssaa4_edge_flip: a.edge_flip,
            sraa_rt_ms_range: b.ms_range,
            ssaa4_ms_range: a.ms_range,
            sraa_rt_flip: b.flip_mean,
            ssaa4_flip: a.flip_mean,
        }
    });
    let end = |m: Option<(usize, Option<f64>)>| m.map(|(at, x)| x.unwrap_or(gaps[at].0 as f64));
    let interpolated_range = end(meet(&best)).zip(end(meet(&worst)));
    Crossover {
        scene: scene.into(),
        backend: backend.into(),
        pair,
        first_faster,
        interpolated: median.and_then(|m| m.1),
        timed_at: gaps.iter().map(|g| g.0).collect(),
        interpolated_range,
    }
}

/// Where sraa-rt's edge FLIP falls among the pair's supersampling at `ao`
/// (SRAA at equal quality): between ssaa2's and ssaa4's, or beyond one of
/// them, with the three figures and the whole-image FLIP. `None` without
/// the three rows' edge FLIP.
pub fn equal_quality(
    sweep: &AoSweep,
    scene: &str,
    backend: &str,
    pair: Pair,
    ao: u32,
) -> Option<String> {
    let get = |m: Method| find(&sweep.rows, scene, backend, m, ao);
    let (s2, s4, rt) = (get(pair.ssaa2())?, get(pair.ssaa4())?, get(pair.sraa_rt())?);
    let (e2, e4, er) = (s2.edge_flip?, s4.edge_flip?, rt.edge_flip?);
    let place = if er <= e4 {
        format!("at or below {}'s", pair.ssaa4())
    } else if er <= e2 {
        format!("between {}'s and {}'s", pair.ssaa2(), pair.ssaa4())
    } else {
        format!("above {}'s", pair.ssaa2())
    };
    let whole = |r: &AoSweepRow| opt(r.flip_mean, 4);
    Some(format!(
        "at AO {ao}, {}'s edge FLIP {er:.4} is {place} ({} {e2:.4}, {} {e4:.4}); whole-image FLIP {} against {} and {}, in {} ms against {} and {}",
        pair.sraa_rt(),
        pair.ssaa2(),
        pair.ssaa4(),
        whole(rt),
        whole(s2),
        whole(s4),
        ms_with_range(rt),
        ms_with_range(s2),
        ms_with_range(s4),
    ))
}

/// A row's median ms with its fastest and slowest run, `93.5 (91.0–97.2)`.
fn ms_with_range(r: &AoSweepRow) -> String {
    format!(
        "{:.1} ({:.1}–{:.1})",
        r.ms_median, r.ms_range.0, r.ms_range.1
    )
}

/// The crossover as a sentence of the report.
pub fn crossover_sentence(c: &Crossover) -> String {
    let flip = |v: Option<f64>| opt(v, 4);
    let (rt, ss) = (c.pair.sraa_rt(), c.pair.ssaa4());
    let head = format!(
        "**Crossover, {} ({}), {}:**",
        c.scene,
        c.backend,
        c.pair.name()
    );
    if c.timed_at.is_empty() {
        return format!("{head} {rt} and {ss} were not both timed at any swept AO ray count.");
    }
    match c.first_faster {
        None => format!("{head} {rt} is faster than {ss} at no swept AO ray count."),
        Some(f) => {
            let range = match c.interpolated_range {
                Some((lo, hi)) => format!(
                    "; the runs allow {lo:.1} to {hi:.1} (each side's fastest and slowest run)"
                ),
                None => "; the runs do not bound it inside the sweep".into(),
            };
            let meet = match c.interpolated {
                Some(x) => format!(
                    " The two times meet at about {x:.1} AO rays per shaded point (linear between the swept counts{range})."
                ),
                None if f.ao == 0 => " It is faster without any AO.".into(),
                None => String::new(),
            };
            format!(
                "{head} {rt} is faster than {ss} from {} AO rays per shaded point on (the fewest swept): {:.1} ms ({:.1}–{:.1}) against {:.1} ms ({:.1}–{:.1}), with edge FLIP {} against {ss}'s {} and whole-image FLIP {} against {}.{meet}",
                f.ao,
                f.sraa_rt_ms,
                f.sraa_rt_ms_range.0,
                f.sraa_rt_ms_range.1,
                f.ssaa4_ms,
                f.ssaa4_ms_range.0,
                f.ssaa4_ms_range.1,
                flip(f.sraa_rt_edge_flip),
                flip(f.ssaa4_edge_flip),
                flip(f.sraa_rt_flip),
                flip(f.ssaa4_flip),
            )
        }
    }
}

/// The figure of the hybrid crossover target ([`HYBRID_CROSSOVER_AO`]) and
/// whether it is met: met where the pair's sraa-rt is faster at some swept
/// count of at most the limit; not met where it is not, and the pair was
/// timed at the limit itself; else not judged (`Err`, why).
pub fn hybrid_crossover_judged(c: &Crossover) -> (String, Result<bool, String>) {
    let meet = c
        .interpolated
        .map(|x| format!(", the times meet at about {x:.1}"))
        .unwrap_or_default();
    let figure = match c.first_faster {
        Some(f) => format!(
            "faster from AO {}: {:.1} vs {:.1} ms{meet}",
            f.ao, f.sraa_rt_ms, f.ssaa4_ms
        ),
        None if c.timed_at.is_empty() => "not timed".into(),
        None => format!(
            "slower at every swept AO ({})",
            c.timed_at
                .iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let met = match c.first_faster {
        Some(f) if f.ao <= HYBRID_CROSSOVER_AO => Ok(true),
        _ if c.timed_at.contains(&HYBRID_CROSSOVER_AO) => Ok(false),
        _ => Err(format!(
            "not judged: the pair was not timed at AO {HYBRID_CROSSOVER_AO}"
        )),
    };
    (figure, met)
}
