//! The crossover of "Where SRAA pays" ([`crate::ao_sweep`]): per scene,
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

use crate::ao_sweep::{find, groups, opt, AoSweep};
use crate::named::{hybrid, NOAA, SRAA_RT, SSAA4};
use subcone_scene::Method;

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

    /// The pair's 2×2 supersampling.
    pub fn ssaa4(self) -> Method {
        self.with(SSAA4)
    }

    /// The pair's SRAA-RT.
    pub fn sraa_rt(self) -> Method {
        self.with(SRAA_RT)
    }

    /// NoAA, SSAA4 and SRAA-RT of the pair.
    pub fn methods(self) -> [Method; 3] {
        [self.noaa(), self.ssaa4(), self.sraa_rt()]
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

/// The crossover of `pair` on `scene` and `backend` (see [`Crossover`]).
pub fn crossover(sweep: &AoSweep, scene: &str, backend: &str, pair: Pair) -> Crossover {
    // (ao, ssaa4 − sraa-rt in ms) where both were timed.
    let mut gaps: Vec<(u32, f64)> = Vec::new();
    let mut first_faster = None;
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
        if first_faster.is_none() && b.ms_median < a.ms_median {
            first_faster = Some(FirstFaster {
                ao,
                sraa_rt_ms: b.ms_median,
                ssaa4_ms: a.ms_median,
                sraa_rt_edge_flip: b.edge_flip,
                ssaa4_edge_flip: a.edge_flip,
            });
        }
    }
    let interpolated = first_faster.and_then(|f| {
        let at = gaps.iter().position(|g| g.0 == f.ao)?;
        let (lo, hi) = (gaps.get(at.checked_sub(1)?)?, gaps[at]);
        // lo.1 ≤ 0 < hi.1: the gap crosses 0 between them.
        let f = -lo.1 / (hi.1 - lo.1);
        Some(lo.0 as f64 + f * (hi.0 - lo.0) as f64)
    });
    Crossover {
        scene: scene.into(),
        backend: backend.into(),
        pair,
        first_faster,
        interpolated,
        timed_at: gaps.iter().map(|g| g.0).collect(),
    }
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
        Some(FirstFaster {
            ao,
            sraa_rt_ms: rt_ms,
            ssaa4_ms: ss_ms,
            sraa_rt_edge_flip: rt_f,
            ssaa4_edge_flip: ss_f,
        }) => {
            let meet = match c.interpolated {
                Some(x) => format!(
                    " The two times meet at about {x:.1} AO rays per shaded point (linear between the swept counts)."
                ),
                None if ao == 0 => " It is faster without any AO.".into(),
                None => String::new(),
            };
            format!(
                "{head} {rt} is faster than {ss} from {ao} AO rays per shaded point on (the fewest swept): {rt_ms:.1} ms against {ss_ms:.1} ms, with edge FLIP {} against {ss}'s {}.{meet}",
                flip(rt_f),
                flip(ss_f),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ao_sweep::tests::row;
    use crate::ao_sweep::{ratios, section, target_rows, AoSweepRow};

    #[test]
    fn the_crossover_is_computed_from_the_rows() {
        let sweep = |rows| AoSweep {
            ran: true,
            aos: vec![0, 4, 16],
            ao_reference: None,
            rows,
            missing: vec![],
            refused: vec![],
        };
        // sraa-rt 40 ms slower at AO 0, 120 ms faster at AO 4: the gap
        // crosses 0 a quarter of the way, at AO 1.
        let s = sweep(vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 140.0, 6.0, 0.08),
            row("ssaa4", 4, 300.0, 20.0, 0.08),
            row("sraa-rt", 4, 180.0, 9.0, 0.09),
            row("ssaa4", 16, 800.0, 70.0, 0.08),
            row("sraa-rt", 16, 300.0, 20.0, 0.09),
        ]);
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        let f = c.first_faster.unwrap();
        assert_eq!((f.ao, f.sraa_rt_ms, f.ssaa4_ms), (4, 180.0, 300.0));
        assert_eq!(
            (f.sraa_rt_edge_flip, f.ssaa4_edge_flip),
            (Some(0.09), Some(0.08))
        );
        assert_eq!(c.interpolated, Some(1.0));
        let text = crossover_sentence(&c);
        assert!(
            text.contains("from 4 AO rays") && text.contains("about 1.0 AO rays"),
            "{text}"
        );
        assert!(section(&s, Some("ssaa256")).contains("**Crossover, atrium (cpu), traced:**"));

        // Faster from the first count: no interpolation; never faster: none.
        let s = sweep(vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 90.0, 6.0, 0.08),
        ]);
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        assert_eq!((c.first_faster.unwrap().ao, c.interpolated), (0, None));
        let s = sweep(vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 190.0, 6.0, 0.08),
        ]);
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        assert!(c.first_faster.is_none());
        assert!(crossover_sentence(&c).contains("at no swept AO ray count"));
    }

    #[test]
    fn each_pair_has_its_own_crossover() {
        let sweep = |rows| AoSweep {
            ran: true,
            aos: vec![0, 1, 4, 16],
            ao_reference: None,
            rows,
            missing: vec![],
            refused: vec![],
        };
        // Traced: sraa-rt slower at 0 and 1, faster from 4 on. Hybrid:
        // slower at 0, faster from 1 on (gap −20 at 0, +60 at 1: they
        // meet at 0.25). A hybrid ssaa4 row alone at 16 changes nothing.
        let rows = vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 140.0, 6.0, 0.08),
            row("ssaa4", 1, 150.0, 12.0, 0.07),
            row("sraa-rt", 1, 160.0, 7.0, 0.08),
            row("ssaa4", 4, 300.0, 20.0, 0.08),
            row("sraa-rt", 4, 180.0, 9.0, 0.09),
            row("ssaa4-hybrid", 0, 60.0, 4.0, 0.07),
            row("sraa-rt-hybrid", 0, 80.0, 2.0, 0.08),
            row("ssaa4-hybrid", 1, 150.0, 8.0, 0.07),
            row("sraa-rt-hybrid", 1, 90.0, 3.0, 0.08),
            row("ssaa4-hybrid", 16, 700.0, 68.0, 0.07),
        ];
        let s = sweep(rows.clone());
        let all = crossovers(&s);
        assert_eq!(
            all.iter().map(|c| c.pair).collect::<Vec<_>>(),
            [Pair::Traced, Pair::Hybrid]
        );
        let (traced, hybrid) = (&all[0], &all[1]);
        assert_eq!(traced.first_faster.unwrap().ao, 4);
        assert_eq!(traced.timed_at, [0, 1, 4]);
        let f = hybrid.first_faster.unwrap();
        assert_eq!((f.ao, f.sraa_rt_ms, f.ssaa4_ms), (1, 90.0, 150.0));
        assert_eq!(hybrid.timed_at, [0, 1]);
        assert_eq!(hybrid.interpolated, Some(0.25));
        let text = crossover_sentence(hybrid);
        assert!(
            text.starts_with(
                "**Crossover, atrium (cpu), hybrid:** sraa-rt-hybrid is faster than ssaa4-hybrid from 1 AO rays"
            ),
            "{text}"
        );
        // The pair's rows only: the hybrid ratios at AO 1.
        assert_eq!(
            ratios(&s.rows, "atrium", "cpu", Pair::Hybrid, 1),
            Some((8.0 / 3.0, 150.0 / 90.0))
        );
        assert_eq!(ratios(&s.rows, "atrium", "cpu", Pair::Hybrid, 16), None);
        // The table: a row per AO count and pair, the pair named.
        let md = section(&s, Some("ssaa256"));
        assert!(md.contains("| 1 | hybrid | – | 150.0 | 90.0 |"), "{md}");
        assert!(md.contains("| 1 | traced | – | 150.0 | 160.0 |"), "{md}");
        assert!(md.contains("| 16 | hybrid | – | 700.0 | – |"), "{md}");
        assert!(!md.contains("| 16 | traced |"), "{md}");
        // The target: met at AO 1.
        let t = target_rows(&s);
        let line = t
            .lines()
            .find(|l| {
                l.starts_with(
                    "| hybrid crossover (sraa-rt-hybrid faster than ssaa4-hybrid) at ≤ 1 AO ray",
                )
            })
            .unwrap_or_else(|| panic!("{t}"));
        assert!(
            line.contains("faster from AO 1: 90.0 vs 150.0 ms, the times meet at about 0.2"),
            "{line}"
        );
        assert!(line.ends_with("| met |"), "{line}");

        // Hybrid slower at 0 and 1, faster at 16: not met.
        let mut late = rows.clone();
        late[9] = row("sraa-rt-hybrid", 1, 200.0, 3.0, 0.08);
        late.push(row("sraa-rt-hybrid", 16, 300.0, 20.0, 0.08));
        let c = crossover(&sweep(late.clone()), "atrium", "cpu", Pair::Hybrid);
        assert_eq!(c.first_faster.unwrap().ao, 16);
        assert_eq!(hybrid_crossover_judged(&c).1, Ok(false));
        assert!(target_rows(&sweep(late)).contains("**not met** |"));
        // Never faster: the figure says so, not met.
        let mut never = rows.clone();
        never[9] = row("sraa-rt-hybrid", 1, 200.0, 3.0, 0.08);
        let c = crossover(&sweep(never), "atrium", "cpu", Pair::Hybrid);
        let (figure, met) = hybrid_crossover_judged(&c);
        assert_eq!(
            (figure.as_str(), met),
            ("slower at every swept AO (0, 1)", Ok(false))
        );
        // Not timed at AO 1 and not faster at 0: not judged.
        let no_one: Vec<AoSweepRow> = rows
            .iter()
            .filter(|r| !(r.ao == 1 && r.method.is_hybrid()))
            .cloned()
            .collect();
        let c = crossover(&sweep(no_one), "atrium", "cpu", Pair::Hybrid);
        assert!(hybrid_crossover_judged(&c).1.is_err());
        // A backend without hybrids: no hybrid crossover, no target row.
        let traced_only: Vec<AoSweepRow> = rows
            .iter()
            .filter(|r| !r.method.is_hybrid())
            .cloned()
            .collect();
        let s = sweep(traced_only);
        assert_eq!(crossovers(&s).len(), 1);
        assert!(!target_rows(&s).contains("hybrid crossover"));
    }
}
