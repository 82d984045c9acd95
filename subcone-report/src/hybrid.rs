//! SRAA the way its paper runs it: rasterised primary visibility
//! (`-hybrid`, SRAA §3.1 and §4.2) against traced, in the report.
//!
//! The paper's SRAA is a hybrid: a rasteriser finds each primary sample's
//! triangle (the shaded sample and the geometric subsamples), and only the
//! secondary effects are ray traced; its Fig. 3 sets that hybrid against
//! 16× SSAA and finds it about [`SRAA_SPEEDUP_OVER_SSAA16`] times faster.
//! The report runs every triangle method both ways and reads the figure
//! three ways ([`PaperRatios`]): the paper's own comparison (traced ssaa16
//! over hybrid sraa-rt), the fair one (hybrid over hybrid) and the traced
//! one (traced over traced). This module computes those ratios, the
//! performance targets that rest on them ([`target_rows`]), each triangle
//! scene's table of traced against hybrid rows ([`traced_hybrid`]), and
//! the rasteriser's throughput beside raw traversal ([`raster_throughput`]).
//!
//! Every figure is computed from the rows the report already has: median
//! times over the timed rounds and median pass times. A ratio between two
//! methods of one scene and backend is the median of their per-round ratios
//! (they are timed in the same interleaved rounds, see
//! [`timing`]), else the ratio of their medians
//! ([`time_ratio`]).

use std::fmt::Write as _;

use subcone_scene::Method;

use crate::context::{cpu_model, ms, Context};
use crate::named::{hybrid, hybrid_bases, noaa_hybrid, sraa_rt_hybrid, NOAA, SRAA_RT, SSAA16};
use crate::papers::SRAA_SPEEDUP_OVER_SSAA16;
use crate::{timing, ResultRow, ThroughputRow};

/// Target: on these scenes, SRAA-RT's `antialiasing` pass (the paper's
/// pass 2, the reconstruction) at most [`AA_PASS_SHARE`] of NoAA's frame.
pub const AA_PASS_SCENES: [&str; 1] = ["cornell"];
/// The share of `noaa`'s median frame time SRAA-RT's antialiasing pass may
/// take.
pub const AA_PASS_SHARE: f64 = 0.5;
/// Target: on these scenes, the `raster` pass of a hybrid SRAA-RT frame at
/// most [`RASTER_SHARE`] of its median frame time.
pub const RASTER_SHARE_SCENES: [&str; 1] = ["atrium"];
/// The share of a hybrid `sraa-rt` frame its rasteriser may take.
pub const RASTER_SHARE: f64 = 0.15;

/// A time ratio between two rows of one scene and backend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeRatio {
    /// The median of the per-round ratios, or the ratio of the medians.
    pub value: f64,
    /// The smallest and largest per-round ratio (`None` for a ratio of
    /// medians).
    pub range: Option<(f64, f64)>,
}

impl TimeRatio {
    /// `6.12 (5.90–6.31)`, the range left out where there is none or it is
    /// one value.
    pub fn show(&self) -> String {
        match self.range {
            Some((lo, hi)) if lo != hi => format!("{:.2} ({lo:.2}–{hi:.2})", self.value),
            _ => format!("{:.2}", self.value),
        }
    }

    /// [`TimeRatio::show`] with `x` after each figure: `6.12x
    /// (5.90–6.31x)`.
    pub fn show_x(&self) -> String {
        match self.range {
            Some((lo, hi)) if lo != hi => format!("{:.2}x ({lo:.2}–{hi:.2}x)", self.value),
            _ => format!("{:.2}x", self.value),
        }
    }
}

/// `num`'s time over `den`'s: the median of the per-round ratios where both
/// were timed in the same rounds ([`timing::round_ratios`]), else the
/// ratio of their median times; `None` without a positive, finite
/// denominator.
pub fn time_ratio(num: &ResultRow, den: &ResultRow) -> Option<TimeRatio> {
    if let Some(s) = timing::round_ratios(&num.round_ms, &den.round_ms) {
        return Some(TimeRatio {
            value: s.median,
            range: Some((s.min, s.max)),
        });
    }
    let ok = |v: f64| v.is_finite() && v > 0.0;
    (ok(den.ms_median) && num.ms_median.is_finite()).then(|| TimeRatio {
        value: num.ms_median / den.ms_median,
        range: None,
    })
}

fn show(r: Option<TimeRatio>) -> String {
    r.map_or_else(|| "–".into(), |r| r.show())
}

/// The row of `method` on `scene` and `backend`.
fn find<'a>(
    rows: &'a [ResultRow],
    scene: &str,
    backend: &str,
    method: Method,
) -> Option<&'a ResultRow> {
    rows.iter()
        .find(|r| r.method == method && r.backend == backend && r.scene == scene)
}

/// SRAA Fig. 3 read three ways on one triangle scene and backend, and
/// SRAA-RT against SSAA4 with each primary visibility.
#[derive(Clone, Debug, PartialEq)]
pub struct PaperRatios {
    /// Scene.
    pub scene: String,
    /// Backend.
    pub backend: String,
    /// Timing size of the rows.
    pub size: (u32, u32),
    /// Median ms of ssaa16, ssaa16-hybrid, sraa-rt and sraa-rt-hybrid,
    /// where they ran.
    pub ms: [Option<f64>; 4],
    /// The paper's comparison (Fig. 3): traced `ssaa16` over hybrid
    /// `sraa-rt-hybrid`.
    pub paper: Option<TimeRatio>,
    /// Hybrid over hybrid: `ssaa16-hybrid` over `sraa-rt-hybrid`.
    pub fair: Option<TimeRatio>,
    /// Traced over traced: `ssaa16` over `sraa-rt`.
    pub traced: Option<TimeRatio>,
    /// `sraa-rt-hybrid` over `ssaa4-hybrid`.
    pub hybrid_rt_over_ssaa4: Option<TimeRatio>,
    /// `sraa-rt` over `ssaa4`.
    pub traced_rt_over_ssaa4: Option<TimeRatio>,
}

/// [`PaperRatios`] on `scene` and `backend`; `None` when neither SRAA-RT
/// row is there.
pub fn paper_ratios(rows: &[ResultRow], scene: &str, backend: &str) -> Option<PaperRatios> {
    let get = |m: Method| find(rows, scene, backend, m);
    let (ss16, ss16_h) = (get(SSAA16), get(hybrid(SSAA16)));
    let (rt, rt_h) = (get(SRAA_RT), get(sraa_rt_hybrid()));
    let (ss4, ss4_h) = (get(crate::named::SSAA4), get(hybrid(crate::named::SSAA4)));
    let size = rt.or(rt_h).map(|r| (r.width, r.height))?;
    let ratio = |a: Option<&ResultRow>, b: Option<&ResultRow>| time_ratio(a?, b?);
    Some(PaperRatios {
        scene: scene.into(),
        backend: backend.into(),
        size,
        ms: [ss16, ss16_h, rt, rt_h].map(|r| r.map(|r| r.ms_median)),
        paper: ratio(ss16, rt_h),
        fair: ratio(ss16_h, rt_h),
        traced: ratio(ss16, rt),
        hybrid_rt_over_ssaa4: ratio(rt_h, ss4_h),
        traced_rt_over_ssaa4: ratio(rt, ss4),
    })
}

/// The triangle scenes of the run, in its order.
fn triangle_scenes(ctx: &Context) -> Vec<&str> {
    ctx.scenes
        .iter()
        .filter(|sc| !sc.sdf)
        .map(|sc| sc.name.as_str())
        .collect()
}

/// Where the medians were measured: each backend with what it runs on, the
/// processor and its hardware threads.
fn machine(ctx: &Context) -> String {
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    format!(
        "{} on {}, {threads} hardware threads",
        ctx.backend_descriptions.join(", "),
        cpu_model()
    )
}

/// The "SRAA for ray tracing, Fig. 3" block of *Against the papers'
/// numbers*: per triangle scene and backend, the paper's comparison, the
/// fair and the traced one, and SRAA-RT over SSAA4 with each primary
/// visibility ([`paper_ratios`]). Empty without an SRAA-RT row on a
/// triangle scene.
pub fn paper_section(rows: &[ResultRow], ctx: &Context) -> String {
    let mut md = String::new();
    let mut tables = String::new();
    let (ss16, ss16_h) = (SSAA16, hybrid(SSAA16));
    let (rt, rt_h) = (SRAA_RT, sraa_rt_hybrid());
    let (ss4, ss4_h) = (crate::named::SSAA4, hybrid(crate::named::SSAA4));
    for b in &ctx.backends {
        let lines: Vec<PaperRatios> = triangle_scenes(ctx)
            .into_iter()
            .filter_map(|sc| paper_ratios(rows, sc, b))
            .collect();
        if lines.is_empty() {
            continue;
        }
        let _ = writeln!(
            tables,
            "| scene ({b}) | size | {ss16} ms | {ss16_h} ms | {rt} ms | {rt_h} ms | paper's: {ss16} / {rt_h} | hybrid: {ss16_h} / {rt_h} | traced: {ss16} / {rt} | {rt_h} / {ss4_h} | {rt} / {ss4} |"
        );
        let _ = writeln!(tables, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
        for p in lines {
            let m = |i: usize| p.ms[i].map_or_else(|| "–".into(), ms);
            let _ = writeln!(
                tables,
                "| {} | {}x{} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                p.scene,
                p.size.0,
                p.size.1,
                m(0),
                m(1),
                m(2),
                m(3),
                show(p.paper),
                show(p.fair),
                show(p.traced),
                show(p.hybrid_rt_over_ssaa4),
                show(p.traced_rt_over_ssaa4),
            );
        }
        let _ = writeln!(tables);
    }
    if tables.is_empty() {
        return md;
    }
    let _ = writeln!(md, "### SRAA for ray tracing, Fig. 3: hybrid and traced\n");
    let _ = writeln!(
        md,
        "The paper's SRAA is a hybrid (§3.1, §4.2): primary visibility, the shaded sample and \
the geometric subsamples, is rasterised, and only the rest is ray traced; Fig. 3 sets it against \
16× SSAA, about {SRAA_SPEEDUP_OVER_SSAA16:.0}× faster. Ours, per triangle scene at its timing \
size, three readings of that comparison: the paper's ({ss16} over {rt_h}), the hybrid one, both \
sides rasterised ({ss16_h} over {rt_h}), and the traced one, both sides traced ({ss16} over \
{rt}); then SRAA-RT over SSAA4 with each visibility ({rt_h} over {ss4_h}, {rt} over {ss4}). A \
ratio is the median over the timed rounds of the two methods' per-round ratio, the smallest and \
largest per-round ratio in brackets; the times are medians over the rounds, measured with {}.\n",
        machine(ctx)
    );
    md.push_str(&tables);
    md
}

/// The rows of the *Performance targets* table that rest on the hybrid
/// methods: SRAA Fig. 3's speed-up (traced ssaa16 over hybrid sraa-rt ≥
/// [`SRAA_SPEEDUP_OVER_SSAA16`]) on every triangle scene; SRAA-RT's
/// antialiasing pass, traced and hybrid, at most [`AA_PASS_SHARE`] of
/// NoAA's frame on [`AA_PASS_SCENES`]; the rasteriser's share of a hybrid
/// SRAA-RT frame at most [`RASTER_SHARE`] on [`RASTER_SHARE_SCENES`].
pub fn target_rows(rows: &[ResultRow], ctx: &Context) -> String {
    let mut md = String::new();
    let yes = |ok: bool| if ok { "met" } else { "**not met**" };
    let (ss16, rt_h) = (SSAA16, sraa_rt_hybrid());
    let triangles = triangle_scenes(ctx);
    for b in &ctx.backends {
        for &sc in &triangles {
            let (Some(a), Some(h)) = (find(rows, sc, b, ss16), find(rows, sc, b, rt_h)) else {
                continue;
            };
            let Some(r) = time_ratio(a, h) else { continue };
            let _ = writeln!(
                md,
                "| {ss16} / {rt_h} time ≥ {SRAA_SPEEDUP_OVER_SSAA16:.0} (SRAA Fig. 3: traced 16x SSAA against the hybrid) | {b} | {sc} ({}x{}) | {}: {} vs {} ms | {} |",
                h.width,
                h.height,
                r.show_x(),
                ms(a.ms_median),
                ms(h.ms_median),
                yes(r.value >= SRAA_SPEEDUP_OVER_SSAA16)
            );
        }
        for sc in AA_PASS_SCENES.into_iter().filter(|s| triangles.contains(s)) {
            let Some(noaa) = find(rows, sc, b, NOAA) else {
                continue;
            };
            for m in [SRAA_RT, rt_h] {
                let Some((aa, share)) = find(rows, sc, b, m).and_then(|r| aa_pass_share(r, noaa))
                else {
                    continue;
                };
                let _ = writeln!(
                    md,
                    "| antialiasing pass of {m} ≤ {AA_PASS_SHARE}x {NOAA}'s frame time | {b} | {sc} ({}x{}) | {} of {} ms ({share:.2}x) | {} |",
                    noaa.width,
                    noaa.height,
                    ms(aa),
                    ms(noaa.ms_median),
                    yes(share <= AA_PASS_SHARE)
                );
            }
        }
        for sc in RASTER_SHARE_SCENES
            .into_iter()
            .filter(|s| triangles.contains(s))
        {
            let Some(h) = find(rows, sc, b, rt_h) else {
                continue;
            };
            let Some((raster, share)) = raster_share(h) else {
                continue;
            };
            let _ = writeln!(
                md,
                "| raster share of a {rt_h} frame ≤ {:.0} % | {b} | {sc} ({}x{}) | {} of {} ms ({:.1} %) | {} |",
                100.0 * RASTER_SHARE,
                h.width,
                h.height,
                ms(raster),
                ms(h.ms_median),
                100.0 * share,
                yes(share <= RASTER_SHARE)
            );
        }
    }
    md
}

/// `it`'s `antialiasing` pass (median ms) and its share of `noaa`'s median
/// frame time; `None` without the pass or a positive NoAA time.
pub fn aa_pass_share(it: &ResultRow, noaa: &ResultRow) -> Option<(f64, f64)> {
    let aa = it.pass("antialiasing")?;
    (noaa.ms_median > 0.0 && noaa.ms_median.is_finite()).then(|| (aa, aa / noaa.ms_median))
}

/// A hybrid row's `raster` pass (median ms) and its share of the row's
/// median frame time; `None` without the pass or a positive frame time.
pub fn raster_share(it: &ResultRow) -> Option<(f64, f64)> {
    let raster = it.pass("raster")?;
    (it.ms_median > 0.0 && it.ms_median.is_finite()).then(|| (raster, raster / it.ms_median))
}

/// One method of a triangle scene and backend, traced and hybrid.
#[derive(Clone, Debug, PartialEq)]
pub struct TracedHybrid {
    /// The traced method (its hybrid is `base` with `-hybrid`).
    pub base: Method,
    /// Backend.
    pub backend: String,
    /// The traced method's median ms.
    pub traced_ms: f64,
    /// The hybrid's median ms.
    pub hybrid_ms: f64,
    /// Traced time over hybrid time: the hybrid's speed-up.
    pub speedup: Option<TimeRatio>,
    /// The traced method's time over `noaa`'s.
    pub traced_over_noaa: Option<TimeRatio>,
    /// The hybrid's time over `noaa-hybrid`'s.
    pub hybrid_over_noaa: Option<TimeRatio>,
    /// The hybrid's `raster` pass, median ms.
    pub raster_ms: Option<f64>,
    /// Rasterised primary samples per pixel of the hybrid.
    pub raster_samples_per_pixel: f64,
    /// The traced method's mean FLIP.
    pub traced_flip: Option<f64>,
    /// The hybrid's mean FLIP.
    pub hybrid_flip: Option<f64>,
}

/// Every method of [`hybrid_bases`] with both rows in `rows` (one scene),
/// per backend in the rows' order: what rasterising the primary visibility
/// changes, each side against its own NoAA (traced over `noaa`, hybrid over
/// `noaa-hybrid`).
pub fn traced_hybrid(rows: &[&ResultRow]) -> Vec<TracedHybrid> {
    let mut backends: Vec<&str> = Vec::new();
    for r in rows {
        if !backends.contains(&r.backend.as_str()) {
            backends.push(&r.backend);
        }
    }
    let mut out = Vec::new();
    for b in backends {
        let get = |m: Method| {
            rows.iter()
                .find(|r| r.method == m && r.backend == b)
                .copied()
        };
        let (noaa, noaa_h) = (get(NOAA), get(noaa_hybrid()));
        for base in hybrid_bases() {
            let (Some(t), Some(h)) = (get(base), get(hybrid(base))) else {
                continue;
            };
            let over = |a: &ResultRow, n: Option<&ResultRow>| time_ratio(a, n?);
            out.push(TracedHybrid {
                base,
                backend: b.to_string(),
                traced_ms: t.ms_median,
                hybrid_ms: h.ms_median,
                speedup: time_ratio(t, h),
                traced_over_noaa: over(t, noaa),
                hybrid_over_noaa: over(h, noaa_h),
                raster_ms: h.pass("raster"),
                raster_samples_per_pixel: h.raster_samples_per_pixel,
                traced_flip: t.flip_mean,
                hybrid_flip: h.flip_mean,
            });
        }
    }
    out
}

/// A scene section's table of [`traced_hybrid`]; empty without a method
/// that ran both ways.
pub fn scene_table(rows: &[&ResultRow]) -> String {
    let mut md = String::new();
    let lines = traced_hybrid(rows);
    if lines.is_empty() {
        return md;
    }
    let (noaa, noaa_h) = (NOAA, noaa_hybrid());
    let _ = writeln!(
        md,
        "**Traced against hybrid.** Each method that ran both ways: primary samples traced, and \
rasterised (`-hybrid`, SRAA §3.1 and §4.2: the rasteriser finds each primary sample's \
triangle, the tracer's test on it gives the hit; shadow, reflection and ambient-occlusion rays \
stay rays). *speed-up* is the traced time over the hybrid's; *× own NoAA* is each one's time \
over its own NoAA's, {noaa}'s for the traced method and {noaa_h}'s for the hybrid (medians of \
per-round ratios, range in brackets); *raster* is the hybrid's rasteriser pass and its \
rasterised primary samples per pixel; FLIP is each one's mean FLIP against the reference.\n"
    );
    let _ = writeln!(
        md,
        "| method | backend | traced ms | hybrid ms | speed-up | traced × {noaa} | hybrid × {noaa_h} | raster ms | raster samples/px | traced FLIP | hybrid FLIP |"
    );
    let _ = writeln!(md, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    let flip = |v: Option<f64>| v.map_or_else(|| "–".into(), |v| format!("{v:.4}"));
    for l in &lines {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.2} | {} | {} |",
            l.base,
            l.backend,
            ms(l.traced_ms),
            ms(l.hybrid_ms),
            show(l.speedup),
            show(l.traced_over_noaa),
            show(l.hybrid_over_noaa),
            l.raster_ms.map_or_else(|| "–".into(), ms),
            l.raster_samples_per_pixel,
            flip(l.traced_flip),
            flip(l.hybrid_flip),
        );
    }
    let _ = writeln!(md);
    if let Some(d) = FlipAgreement::of(&lines) {
        let _ = writeln!(md, "{}\n", d.sentence());
    }
    md
}

/// How far the hybrid rows' FLIP is from their traced twins' in a
/// [`traced_hybrid`] table.
#[derive(Clone, Debug, PartialEq)]
pub struct FlipAgreement {
    /// Pairs with both FLIPs.
    pub pairs: usize,
    /// Pairs whose FLIPs agree to the 4 decimals the table prints.
    pub equal: usize,
    /// The pair with the largest |hybrid − traced| FLIP: its method,
    /// backend and the difference (hybrid minus traced).
    pub largest: (Method, String, f64),
}

impl FlipAgreement {
    /// Over the pairs of `lines` with both FLIPs; `None` without one.
    pub fn of(lines: &[TracedHybrid]) -> Option<FlipAgreement> {
        let both: Vec<(Method, &str, f64, f64)> = lines
            .iter()
            .filter_map(|l| Some((l.base, l.backend.as_str(), l.traced_flip?, l.hybrid_flip?)))
            .collect();
        let largest = both
            .iter()
            .map(|&(m, b, t, h)| (m, b, h - t))
            .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))?;
        Some(FlipAgreement {
            pairs: both.len(),
            equal: both
                .iter()
                .filter(|&&(_, _, t, h)| format!("{t:.4}") == format!("{h:.4}"))
                .count(),
            largest: (largest.0, largest.1.to_string(), largest.2),
        })
    }

    /// The agreement in words.
    pub fn sentence(&self) -> String {
        let (m, b, d) = &self.largest;
        if *d == 0.0 {
            return format!(
                "Hybrid against traced FLIP: identical on all {} methods.",
                self.pairs
            );
        }
        format!(
            "Hybrid against traced FLIP: equal to 4 decimals on {} of {} methods; the largest \
difference (hybrid minus traced) is {d:+.2e} ({m}, {b}).",
            self.equal, self.pairs
        )
    }
}

/// The rasteriser beside raw traversal on each instruction-set path and
/// triangle scene ([`RayThroughput::raster_primary`](subcone_cpu::throughput::RayThroughput::raster_primary)):
/// samples per second over all threads and per thread, the raw traversal's
/// rays per second measured alternating with it, and their ratio. Empty
/// without throughput rows.
pub fn raster_throughput(rows: &[ThroughputRow]) -> String {
    let mut md = String::new();
    if rows.is_empty() {
        return md;
    }
    let _ = writeln!(
        md,
        "\nRasterised primary visibility (`-hybrid`, SRAA §3.1) against raw traversal, on each \
instruction-set path: the rasteriser's samples per second at every pixel centre of the scene's \
timing size (triangle setup, binning and coverage, which decide each sample's triangle; no hit \
reconstruction, no shading), timed alternating with the raw closest-hit traversal of the rays \
through the same pixel centres (medians of the run's timed passes). *Per core* divides by the \
threads the passes ran on.\n"
    );
    let _ = writeln!(
        md,
        "| scene | path | size | threads | raw traversal Mrays/s | per core | rasteriser Msamples/s | per core | rasteriser / raw |"
    );
    let _ = writeln!(md, "|---|---|---|--:|--:|--:|--:|--:|--:|");
    for t in rows {
        let r = &t.rates;
        let threads = r.threads.max(1) as f64;
        let _ = writeln!(
            md,
            "| {} | {} | {}x{} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            t.scene,
            t.isa.name(),
            t.width,
            t.height,
            r.threads,
            r.raw_beside_raster / 1e6,
            r.raw_beside_raster / threads / 1e6,
            r.raster_primary / 1e6,
            r.raster_primary / threads / 1e6,
            r.raster_ratio(),
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::context::SceneInfo;
    use crate::key::SceneId;
    use crate::timing::Timings;

    /// A row of `method` on `scene` with median `ms`, per-round times
    /// `rounds` and passes `passes`.
    fn row(
        scene: &str,
        method: &str,
        ms: f64,
        rounds: &[f64],
        passes: &[(&str, f64)],
    ) -> ResultRow {
        let mut r = ResultRow::timed(
            scene,
            crate::key::named(method),
            "cpu",
            (1024, 1024),
            rounds.len() as u32,
            &Timings::default(),
        );
        r.ms_median = ms;
        r.round_ms = rounds.to_vec();
        r.pass_ms = passes.iter().map(|(n, v)| (n.to_string(), *v)).collect();
        r
    }

    fn ctx(scenes: &[(&str, bool)]) -> Context {
        Context {
            mode: crate::Mode::Full,
            backends: vec!["cpu".into()],
            backend_descriptions: vec!["cpu".into()],
            runs: 3,
            reference: "ssaa256".into(),
            offsets: vec![(0.0, 0.0)],
            scenes: scenes
                .iter()
                .map(|&(name, sdf)| SceneInfo {
                    name: SceneId::new(name),
                    arg: name.into(),
                    sdf,
                    timing_size: (1024, 1024),
                    quality_size: None,
                })
                .collect(),
            ao: 0,
            other_cpu: Default::default(),
        }
    }

    fn close(a: Option<TimeRatio>, b: f64) -> bool {
        a.is_some_and(|a| (a.value - b).abs() < 1e-12)
    }

    #[test]
    fn a_time_ratio_is_per_round_where_it_can_be() {
        let a = row("s", "ssaa16", 600.0, &[500.0, 600.0, 700.0], &[]);
        let b = row("s", "sraa-rt-hybrid", 100.0, &[100.0, 120.0, 100.0], &[]);
        // Per round 5, 5, 7: median 5, not 600 / 100.
        let r = time_ratio(&a, &b).unwrap();
        assert_eq!((r.value, r.range), (5.0, Some((5.0, 7.0))));
        assert_eq!(r.show(), "5.00 (5.00–7.00)");
        // Without rounds: the ratio of medians, no range.
        let c = row("s", "sraa-rt", 200.0, &[], &[]);
        let r = time_ratio(&a, &c).unwrap();
        assert_eq!((r.value, r.range, r.show()), (3.0, None, "3.00".into()));
        let zero = row("s", "noaa", 0.0, &[], &[]);
        assert_eq!(time_ratio(&a, &zero), None);
    }

    /// The rows of one triangle scene: every method with its traced and
    /// hybrid times in three rounds.
    fn scene_rows(scene: &str) -> Vec<ResultRow> {
        vec![
            row(
                scene,
                "noaa",
                100.0,
                &[100.0, 100.0, 100.0],
                &[("shading", 90.0)],
            ),
            row(scene, "ssaa4", 400.0, &[400.0, 400.0, 400.0], &[]),
            row(scene, "ssaa16", 1500.0, &[1500.0, 1500.0, 1500.0], &[]),
            row(
                scene,
                "sraa-rt",
                300.0,
                &[300.0, 300.0, 300.0],
                &[("antialiasing", 60.0)],
            ),
            row(
                scene,
                "noaa-hybrid",
                50.0,
                &[50.0, 50.0, 50.0],
                &[("raster", 5.0)],
            ),
            row(scene, "ssaa4-hybrid", 200.0, &[200.0, 200.0, 200.0], &[]),
            row(scene, "ssaa16-hybrid", 800.0, &[800.0, 800.0, 800.0], &[]),
            row(
                scene,
                "sraa-rt-hybrid",
                200.0,
                &[200.0, 250.0, 200.0],
                &[("raster", 40.0), ("antialiasing", 55.0)],
            ),
        ]
    }

    #[test]
    fn the_papers_comparison_is_read_three_ways() {
        let rows = scene_rows("atrium");
        let p = paper_ratios(&rows, "atrium", "cpu").unwrap();
        // Per round: 1500 / (200, 250, 200) = 7.5, 6, 7.5.
        assert!(close(p.paper, 7.5), "{:?}", p.paper);
        assert_eq!(p.paper.unwrap().range, Some((6.0, 7.5)));
        // 800 / (200, 250, 200): 4, 3.2, 4.
        assert!(close(p.fair, 4.0), "{:?}", p.fair);
        assert!(close(p.traced, 5.0));
        // sraa-rt-hybrid / ssaa4-hybrid: 1, 1.25, 1; sraa-rt / ssaa4: 0.75.
        assert!(close(p.hybrid_rt_over_ssaa4, 1.0));
        assert!(close(p.traced_rt_over_ssaa4, 0.75));
        assert_eq!(p.ms, [Some(1500.0), Some(800.0), Some(300.0), Some(200.0)]);
        assert_eq!(p.size, (1024, 1024));
        // No SRAA-RT row at all: nothing to compare.
        assert_eq!(paper_ratios(&rows[..3], "atrium", "cpu"), None);
        // A traced run only: the traced ratio, no hybrid one.
        let traced: Vec<ResultRow> = rows
            .iter()
            .filter(|r| !r.method.method().unwrap().is_hybrid())
            .cloned()
            .collect();
        let p = paper_ratios(&traced, "atrium", "cpu").unwrap();
        assert!(close(p.traced, 5.0) && p.paper.is_none() && p.fair.is_none());
        // The section: one table row per triangle scene, none for SDF.
        let c = ctx(&[("atrium", false), ("mandelbulb", true)]);
        let summary_rows: Vec<ResultRow> = rows
            .iter()
            .cloned()
            .chain(scene_rows("mandelbulb"))
            .collect();
        let md = paper_section(&summary_rows, &c);
        assert!(
            md.contains("### SRAA for ray tracing, Fig. 3: hybrid and traced"),
            "{md}"
        );
        assert!(
            md.contains("| atrium | 1024x1024 | 1500 | 800 | 300 | 200 | 7.50 (6.00–7.50) | 4.00 (3.20–4.00) | 5.00 | 1.00 (1.00–1.25) | 0.75 |"),
            "{md}"
        );
        assert!(!md.contains("| mandelbulb |"), "{md}");
        assert!(paper_section(&rows[..3], &c).is_empty());
    }

    #[test]
    fn the_hybrid_targets_are_computed_from_the_rows() {
        let mut rows = scene_rows("atrium");
        rows.extend(scene_rows("cornell"));
        let c = ctx(&[("cornell", false), ("atrium", false)]);
        let t = target_rows(&rows, &c);
        let lines: Vec<&str> = t.lines().collect();
        // Fig. 3 on both scenes (7.5 ≥ 6: met), the antialiasing pass on
        // cornell for both SRAA-RTs, the raster share on atrium.
        assert_eq!(lines.len(), 5, "{t}");
        assert!(lines[0].starts_with("| ssaa16 / sraa-rt-hybrid time ≥ 6 (SRAA Fig. 3"));
        assert!(
            lines[0].contains("| cornell (1024x1024) | 7.50x (6.00–7.50x): 1500 vs 200 ms | met |"),
            "{}",
            lines[0]
        );
        assert!(lines[1].contains("| atrium (1024x1024) |") && lines[1].ends_with("| met |"));
        // 60 of NoAA's 100 ms: 0.6x, not met; the hybrid's 55: 0.55x.
        assert!(
            lines[2].starts_with(
                "| antialiasing pass of sraa-rt ≤ 0.5x noaa's frame time | cpu | cornell"
            ),
            "{}",
            lines[2]
        );
        assert!(
            lines[2].contains("60.0 of 100 ms (0.60x) | **not met** |"),
            "{}",
            lines[2]
        );
        assert!(lines[3].starts_with("| antialiasing pass of sraa-rt-hybrid ≤ 0.5x"));
        assert!(lines[3].contains("(0.55x) | **not met** |"), "{}", lines[3]);
        // 40 of 200 ms: 20 %, over 15 %.
        assert!(
            lines[4].starts_with("| raster share of a sraa-rt-hybrid frame ≤ 15 % | cpu | atrium"),
            "{}",
            lines[4]
        );
        assert!(
            lines[4].contains("40.0 of 200 ms (20.0 %) | **not met** |"),
            "{}",
            lines[4]
        );

        // Faster hybrids: every target met.
        for r in rows.iter_mut() {
            if r.method == sraa_rt_hybrid() {
                r.round_ms = vec![100.0; 3];
                r.ms_median = 100.0;
                r.pass_ms = vec![("raster".into(), 10.0), ("antialiasing".into(), 30.0)];
            }
            if r.method == SRAA_RT {
                r.pass_ms = vec![("antialiasing".into(), 50.0)];
            }
        }
        let t = target_rows(&rows, &c);
        assert_eq!(t.matches("| met |").count(), 5, "{t}");
        assert!(!t.contains("not met"), "{t}");
        // ssaa16 at 5x the hybrid's time: under the paper's 6, not met.
        for r in rows.iter_mut().filter(|r| r.method == SSAA16) {
            r.round_ms = vec![500.0; 3];
            r.ms_median = 500.0;
        }
        let t = target_rows(&rows, &c);
        assert_eq!(
            t.matches("5.00x: 500 vs 100 ms | **not met** |").count(),
            2,
            "{t}"
        );
        // SDF scenes and missing rows give no rows.
        assert!(target_rows(&rows, &ctx(&[("atrium", true)])).is_empty());
    }

    #[test]
    fn traced_and_hybrid_are_set_side_by_side() {
        let mut rows = scene_rows("atrium");
        rows[3].flip_mean = Some(0.05);
        rows[7].flip_mean = Some(0.051);
        rows[7].raster_samples_per_pixel = 5.0;
        let refs: Vec<&ResultRow> = rows.iter().collect();
        let t = traced_hybrid(&refs);
        let names: Vec<String> = t.iter().map(|l| l.base.to_string()).collect();
        assert_eq!(names, ["noaa", "ssaa4", "ssaa16", "sraa-rt"]);
        let rt = &t[3];
        assert_eq!((rt.traced_ms, rt.hybrid_ms), (300.0, 200.0));
        // 300 / (200, 250, 200): 1.5, 1.2, 1.5.
        assert!(close(rt.speedup, 1.5));
        assert_eq!(rt.speedup.unwrap().range, Some((1.2, 1.5)));
        // Each against its own NoAA: 300 / 100; (200, 250, 200) / 50.
        assert!(close(rt.traced_over_noaa, 3.0));
        assert!(close(rt.hybrid_over_noaa, 4.0));
        assert_eq!(rt.hybrid_over_noaa.unwrap().range, Some((4.0, 5.0)));
        assert_eq!(rt.raster_ms, Some(40.0));
        assert_eq!((rt.traced_flip, rt.hybrid_flip), (Some(0.05), Some(0.051)));
        assert!(close(t[0].speedup, 2.0) && close(t[0].hybrid_over_noaa, 1.0));
        let md = scene_table(&refs);
        assert!(md.contains("| method | backend | traced ms | hybrid ms | speed-up | traced × noaa | hybrid × noaa-hybrid |"), "{md}");
        assert!(
            md.contains("| sraa-rt | cpu | 300 | 200 | 1.50 (1.20–1.50) | 3.00 | 4.00 (4.00–5.00) | 40.0 | 5.00 | 0.0500 | 0.0510 |"),
            "{md}"
        );
        // FLIP agreement: only sraa-rt has both, 0.001 apart.
        let a = FlipAgreement::of(&t).unwrap();
        assert_eq!((a.pairs, a.equal), (1, 0));
        assert_eq!((a.largest.0, a.largest.1.as_str()), (SRAA_RT, "cpu"));
        assert!((a.largest.2 - 0.001).abs() < 1e-12);
        assert!(
            md.contains("equal to 4 decimals on 0 of 1 methods; the largest difference (hybrid minus traced) is +1.00e-3 (sraa-rt, cpu)"),
            "{md}"
        );
        rows[7].flip_mean = Some(0.05);
        let refs: Vec<&ResultRow> = rows.iter().collect();
        let a = FlipAgreement::of(&traced_hybrid(&refs)).unwrap();
        assert_eq!((a.pairs, a.equal, a.largest.2), (1, 1, 0.0));
        assert_eq!(
            a.sentence(),
            "Hybrid against traced FLIP: identical on all 1 methods."
        );
        // No hybrid row: no table.
        assert!(scene_table(&refs[..4]).is_empty());
    }

    #[test]
    fn raster_throughput_per_core_and_against_raw() {
        assert!(raster_throughput(&[]).is_empty());
        let row = ThroughputRow {
            scene: "atrium".into(),
            isa: subcone_cpu::isa::Isa::supported()[0],
            width: 1024,
            height: 1024,
            rates: subcone_cpu::throughput::RayThroughput {
                primary_rays: 1 << 20,
                shadow_rays: 0,
                raw_primary: 40e6,
                pipeline_primary: 30e6,
                raw_shadow: None,
                pipeline_shadow: None,
                raster_primary: 120e6,
                raw_beside_raster: 40e6,
                threads: 2,
            },
        };
        let md = raster_throughput(std::slice::from_ref(&row));
        assert!(
            md.contains("| 1024x1024 | 2 | 40.00 | 20.00 | 120.00 | 60.00 | 3.00 |"),
            "{md}"
        );
    }
}
