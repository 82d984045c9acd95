//! The performance targets of `report.md`: each target, met or not, with
//! its figure (CTSS's overhead and quality bars, SRAA's, SRAA-RT's against
//! ssaa16, ray throughput and kernel timings).

use std::fmt::Write as _;

use super::{f, row_of, rows_for, MeanRatio};
use crate::classes::{Class, Metric, Verdict};
use crate::context::Context;
use crate::key::RowKey;
use crate::named::{CTSS, CTSS_R, NOAA, SRAA, SRAA_RT, SSAA16, SSAA4};
use crate::{kernel_timing, timing, ReportSummary, ResultRow};
use subcone_scene::Method;

/// CTSS overhead targets: average time ratio to NoAA over the SDF scenes.
pub const CTSS_TARGETS: [(Method, f64); 2] = [(CTSS, 1.20), (CTSS_R, 1.08)];
/// CTSS's quality bar on the paper's SDF scenes
/// ([`SDF_SCENES`](subcone_scene::builtin::SDF_SCENES)): `ctss` beats NoAA on
/// silhouettes and holds on flat pixels (the verdict's rules), its
/// whole-image FLIP is below NoAA's, and its silhouette FLIP is at most this
/// factor of `ssaa4`'s (the paper's "comparable to 4× supersampling").
pub const CTSS_SSAA4_FACTOR: f64 = 1.25;
/// On the stiff scenes and the semi-transparent ones, no CTSS method's
/// whole-image FLIP exceeds NoAA's by more than this factor (the default
/// methods; the `-paper` ones are the paper's behaviour, shown beside them).
pub const CTSS_STIFF_FACTOR: f64 = 1.02;

/// SRAA-RT target: at most this share of `ssaa16`'s time...
pub const SRAA_RT_TIME_SHARE: f64 = 1.0 / 6.0;
/// ...with an edge FLIP at most this factor above `ssaa16`'s.
pub const SRAA_RT_EDGE_FACTOR: f64 = 1.25;
/// Ray throughput target: the pipeline's rate at least this share of obvhs'
/// raw traversal on the same rays.
pub const RAY_THROUGHPUT_SHARE: f64 = 0.70;
/// Fewest rays per pass at which a ray-throughput figure is judged: 16 of
/// the raw passes' rayon tasks ([`subcone_cpu::throughput::CHUNK`] rays
/// each). With fewer, the raw pass is a few uneven tasks that cannot keep
/// the threads busy, so its rate is no bound on the pipeline's (which
/// splits its frame into tiles of its own).
pub const RAY_THROUGHPUT_MIN_RAYS: usize = 16 * subcone_cpu::throughput::CHUNK;

/// Whether a ray-throughput target is judged on a pass of `rays` rays whose
/// pipeline rate is `ratio` of raw traversal's: `Ok(met)`, or `Err(why
/// not)`. Raw traversal is a bound on the pipeline (which runs the same
/// traversal and more) only on a pass long enough for it to use the
/// threads; where the pipeline still outruns it, it bounds nothing.
pub fn throughput_judged(rays: usize, ratio: f64) -> Result<bool, String> {
    if rays < RAY_THROUGHPUT_MIN_RAYS {
        Err(format!(
            "not judged at this size: {rays} rays are under {RAY_THROUGHPUT_MIN_RAYS}, 16 of raw traversal's {}-ray tasks, so raw traversal is no bound",
            subcone_cpu::throughput::CHUNK
        ))
    } else if !ratio.is_finite() || ratio > 1.0 {
        Err("not judged: the pipeline outran raw traversal, which is then no bound".into())
    } else {
        Ok(ratio >= RAY_THROUGHPUT_SHARE)
    }
}

/// SRAA's quality bar against NoAA: on every triangle scene, `sraa` and
/// `sraa-rt` beat NoAA on each class they claim and hold on flat pixels (the
/// verdict's rules) and their whole-image FLIP is below NoAA's.
pub const SRAA_METHODS: [Method; 2] = [SRAA, SRAA_RT];
/// `sraa-rt`'s FLIP on silhouette, crease and shadow pixels at most this
/// factor of `ssaa4`'s...
pub const SRAA_RT_SSAA4_FACTOR: f64 = 1.25;
/// ...on these scenes, where it should also be faster than `ssaa4`.
pub const SRAA_RT_SSAA4_SCENES: [&str; 2] = ["atrium", "sponza"];

/// The word of a target's *met* column.
fn yes(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "**not met**"
    }
}

/// `method`'s verdict against NoAA under FLIP on the classes it claims,
/// paired by camera offset as the verdict lines, and its flat figures in
/// words.
fn flip_verdict(method: Method, it: &ResultRow, noaa: &ResultRow) -> (Verdict, String) {
    let v = Verdict::judge_claims(
        method.into(),
        method.claims(),
        Metric::Flip,
        &it.class_errors_at(Metric::Flip),
        &noaa.class_errors_at(Metric::Flip),
    );
    let flat = v
        .flat
        .map(|(x, y)| format!("flat {x:.4} vs {y:.4}"))
        .unwrap_or_else(|| "no flat pixels".into());
    (v, flat)
}

/// The rows of the SRAA targets for backend `b` (triangle scenes only).
fn sraa_targets(s: &ReportSummary, sdf: &[&str], b: &str, md: &mut String) {
    let find = |method, scene: &str| row_of(&s.rows, method, b, scene);
    for method in SRAA_METHODS {
        for r in rows_for(&s.rows, method, b)
            .into_iter()
            .filter(|r| !sdf.contains(&r.scene.as_str()))
        {
            let Some(noaa) = find(NOAA, &r.scene) else {
                continue;
            };
            let (Some(_), Some(_), Some(a), Some(na)) =
                (r.classes, noaa.classes, r.flip_mean, noaa.flip_mean)
            else {
                continue;
            };
            let (v, flat) = flip_verdict(method, r, noaa);
            let met = v.misses.is_empty() && v.holds_on_flat() && a < na;
            let _ = writeln!(
                md,
                "| {method} beats NoAA on its claimed classes, holds on flat, whole FLIP below NoAA's | {b} | {} | {} of {} claimed classes beaten, {flat}, whole {a:.4} vs {na:.4} | {} |",
                r.scene,
                v.beats.len(),
                v.beats.len() + v.misses.len(),
                yes(met)
            );
        }
    }
    for scene in SRAA_RT_SSAA4_SCENES {
        let (Some(rt), Some(ss)) = (find(SRAA_RT, scene), find(SSAA4, scene)) else {
            continue;
        };
        if let (Some(a), Some(e)) = (rt.classes, ss.classes) {
            let mut figures = Vec::new();
            let mut met = true;
            for c in [Class::Silhouette, Class::Crease, Class::Shadow] {
                if let (Some(x), Some(y)) = (a.mean[c.index()], e.mean[c.index()]) {
                    let ratio = x / y;
                    met &= ratio <= SRAA_RT_SSAA4_FACTOR;
                    figures.push(format!("{c} {ratio:.2}x"));
                }
            }
            let _ = writeln!(
                md,
                "| sraa-rt FLIP ≤ {SRAA_RT_SSAA4_FACTOR}x ssaa4's on silhouette, crease and shadow | {b} | {scene} | {} | {} |",
                figures.join(", "),
                yes(met && !figures.is_empty())
            );
        }
        let _ = writeln!(
            md,
            "| sraa-rt faster than ssaa4 | {b} | {scene} ({}x{}) | {:.2} vs {:.2} ms | {} |",
            rt.width,
            rt.height,
            rt.ms_median,
            ss.ms_median,
            yes(rt.ms_median < ss.ms_median)
        );
    }
}

/// The rows of the CTSS quality targets for backend `b` (SDF scenes only).
fn ctss_targets(s: &ReportSummary, b: &str, md: &mut String) {
    use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
    let find = |method, scene: &str| row_of(&s.rows, method, b, scene);
    for scene in SDF_SCENES {
        let (Some(r), Some(noaa)) = (find(CTSS, scene), find(NOAA, scene)) else {
            continue;
        };
        let (Some(it), Some(n), Some(a), Some(na)) =
            (r.classes, noaa.classes, r.flip_mean, noaa.flip_mean)
        else {
            continue;
        };
        let (v, flat) = flip_verdict(CTSS, r, noaa);
        let sil = Class::Silhouette.index();
        let silhouettes = match (it.mean[sil], n.mean[sil]) {
            (Some(x), Some(y)) => format!("silhouette {x:.4} vs {y:.4}"),
            _ => "no silhouette pixels".into(),
        };
        let met = v.misses.is_empty() && !v.beats.is_empty() && v.holds_on_flat() && a < na;
        let _ = writeln!(
            md,
            "| ctss beats NoAA on silhouettes, holds on flat, whole FLIP below NoAA's | {b} | {scene} | {silhouettes}, {flat}, whole {a:.4} vs {na:.4} | {} |",
            yes(met)
        );
        if let Some(ss) = find(SSAA4, scene).and_then(|x| x.classes) {
            if let (Some(x), Some(y)) = (it.mean[sil], ss.mean[sil]) {
                let ratio = x / y;
                let _ = writeln!(
                    md,
                    "| ctss silhouette FLIP ≤ {CTSS_SSAA4_FACTOR}x ssaa4's | {b} | {scene} | {x:.4} vs {y:.4} ({ratio:.2}x) | {} |",
                    yes(ratio <= CTSS_SSAA4_FACTOR)
                );
            }
        }
    }
    for scene in STIFF_SCENES.iter().chain(&TRANSPARENT_SCENES) {
        let Some(na) = find(NOAA, scene).and_then(|x| x.flip_mean) else {
            continue;
        };
        let mut worst: Option<(&RowKey, f64)> = None;
        for r in s.rows.iter().filter(|x| {
            x.backend == b
                && x.scene == *scene
                && x.method
                    .method()
                    .is_some_and(|m| m.technique().is_cone_traced() && !m.is_paper())
                && x.flip_mean.is_some()
        }) {
            let ratio = r.flip_mean.unwrap_or(0.0) / na.max(f64::MIN_POSITIVE);
            if worst.is_none_or(|(_, w)| ratio > w) {
                worst = Some((&r.method, ratio));
            }
        }
        if let Some((m, ratio)) = worst {
            let _ = writeln!(
                md,
                "| every CTSS method's whole FLIP ≤ {CTSS_STIFF_FACTOR}x NoAA's | {b} | {scene} | worst {m}: {ratio:.3}x | {} |",
                yes(ratio <= CTSS_STIFF_FACTOR)
            );
        }
    }
}

/// The performance targets, each met or not met, with its figure.
pub fn targets(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    targets_intro(&mut md);
    let sdf = ctx.sdf_scenes();
    for b in &ctx.backends {
        ctss_overhead_targets(s, &sdf, b, &mut md);
        ctss_targets(s, b, &mut md);
        sraa_targets(s, &sdf, b, &mut md);
        sraa_rt_ssaa16_targets(s, &sdf, b, &mut md);
    }
    md.push_str(&crate::ao_sweep::target_rows(&s.ao_sweep));
    md.push_str(&crate::hybrid::target_rows(&s.rows, ctx));
    throughput_targets(s, &mut md);
    kernel_targets(s, &mut md);
    md.push_str(&crate::hybrid::raster_throughput(&s.throughput));
    let _ = writeln!(md);
    md
}

/// The section's heading, the paragraph on how each target is measured and
/// judged, and the table's header.
fn targets_intro(md: &mut String) {
    let _ = writeln!(md, "## Performance targets\n");
    let _ = writeln!(
        md,
        "Each target as measured by this run (its sizes and runs; the targets are stated for \
1280x720 on the CTSS scenes and 1024x1024 on `cornell` and Sponza). Ray throughput is \
measured on the CPU backend, on every instruction-set path this machine runs ({}; the \
default is the widest), at each triangle scene's timing size (median of \
the run's timed passes, raw and pipeline on the same path; `cargo bench -p subcone-cpu --bench rays` measures the same passes with criterion; judged only where raw traversal is a bound: on a pass of at least {min} rays, \
16 of raw traversal's rayon tasks, on which the pipeline does not outrun it), \
ns per kernel call on one thread (\"a few ns\" read as ≤ {} ns; `cargo bench --bench kernels` \
has the full set). Time ratios between methods are medians of per-round ratios (the methods of \
a scene are timed in interleaved rounds); a target is judged on them. In brackets: for one scene, \
the smallest and largest per-round ratio; for a mean over scenes, the means of the scenes' smallest \
and of their largest per-round ratios, the range the mean would take were every scene at its \
lowest or its highest round.\n",
        subcone_cpu::isa::Isa::supported()
            .iter()
            .map(|i| i.name())
            .collect::<Vec<_>>()
            .join(", "),
        kernel_timing::FEW_NS,
        min = RAY_THROUGHPUT_MIN_RAYS
    );
    let _ = writeln!(md, "| target | backend | scenes | figure | met |");
    let _ = writeln!(md, "|---|---|---|--:|---|");
}

/// The rows of the CTSS overhead targets ([`CTSS_TARGETS`]) for backend
/// `b`: each method's mean time ratio to NoAA over the SDF scenes.
fn ctss_overhead_targets(s: &ReportSummary, sdf: &[&str], b: &str, md: &mut String) {
    for (method, limit) in CTSS_TARGETS {
        let Some(avg) =
            MeanRatio::of(s.rows.iter().filter(|r| {
                r.backend == b && r.method == method && sdf.contains(&r.scene.as_str())
            }))
        else {
            continue;
        };
        // Judged on the medians; a limit inside the range is worth a word.
        let close = match avg.range {
            Some((lo, hi)) if lo <= limit && limit <= hi => ", the limit inside the range",
            _ => "",
        };
        let _ = writeln!(
            md,
            "| {method} ≤ {limit:.2}x NoAA (mean time ratio) | {b} | {} SDF scenes | {}{close} | {} |",
            avg.n,
            avg.show(3, true),
            yes(avg.mean <= limit)
        );
    }
}

/// The rows of the SRAA-RT target against `ssaa16` for backend `b`: its
/// share of the time and its edge FLIP ratio, per triangle scene.
fn sraa_rt_ssaa16_targets(s: &ReportSummary, sdf: &[&str], b: &str, md: &mut String) {
    // The SRAA-RT target is the paper's, on triangle scenes.
    for rt in rows_for(&s.rows, SRAA_RT, b)
        .into_iter()
        .filter(|r| !sdf.contains(&r.scene.as_str()))
    {
        let Some(ss) = s
            .rows
            .iter()
            .find(|x| x.method == SSAA16 && x.backend == b && x.scene == rt.scene)
        else {
            continue;
        };
        // Per round where both were timed in the same rounds; else the
        // ratio of medians.
        let per_round = timing::round_ratios(&rt.round_ms, &ss.round_ms);
        let share = per_round.map_or(rt.ms_median / ss.ms_median, |p| p.median);
        let range = per_round
            .filter(|p| p.min != p.max)
            .map(|p| format!(" (1/{:.2}–1/{:.2})", 1.0 / p.max, 1.0 / p.min))
            .unwrap_or_default();
        let edge = match (rt.edge_flip_mean, ss.edge_flip_mean) {
            (Some(a), Some(e)) if e > 0.0 => Some(a / e),
            _ => None,
        };
        let met = share <= SRAA_RT_TIME_SHARE && edge.is_some_and(|e| e <= SRAA_RT_EDGE_FACTOR);
        let _ = writeln!(
            md,
            "| sraa-rt ≤ 1/6 of ssaa16's time, edge FLIP ≤ {SRAA_RT_EDGE_FACTOR}x ssaa16's | {b} | {} ({}x{}) | 1/{:.2}{range} of the time, edge FLIP {}x | {} |",
            rt.scene,
            rt.width,
            rt.height,
            1.0 / share,
            f(edge, 2),
            yes(met)
        );
    }
}

/// The rows of the ray-throughput targets: per instruction-set path and
/// scene, the pipeline's primary (and shadow) ray rate against raw
/// traversal's.
fn throughput_targets(s: &ReportSummary, md: &mut String) {
    let pct = |x: f64| format!("{:.1}%", 100.0 * x);
    for t in &s.throughput {
        let r = &t.rates;
        let _ = writeln!(
            md,
            "| primary rays ≥ {} of raw traversal | cpu ({}) | {} ({}x{}) | {:.2} of {:.2} Mrays/s ({}) | {} |",
            pct(RAY_THROUGHPUT_SHARE),
            t.isa.name(),
            t.scene,
            t.width,
            t.height,
            r.pipeline_primary / 1e6,
            r.raw_primary / 1e6,
            pct(r.primary_ratio()),
            throughput_judged(r.primary_rays, r.primary_ratio())
                .map_or_else(|why| why, |met| yes(met).to_string())
        );
        if let (Some(p), Some(raw), Some(ratio)) =
            (r.pipeline_shadow, r.raw_shadow, r.shadow_ratio())
        {
            let _ = writeln!(
                md,
                "| shadow rays ≥ {} of raw traversal | cpu ({}) | {} ({} rays) | {:.2} of {:.2} Mrays/s ({}) | {} |",
                pct(RAY_THROUGHPUT_SHARE),
                t.isa.name(),
                t.scene,
                r.shadow_rays,
                p / 1e6,
                raw / 1e6,
                pct(ratio),
                throughput_judged(r.shadow_rays, ratio)
                    .map_or_else(|why| why, |met| yes(met).to_string())
            );
        }
    }
}

/// The rows of the kernels' ns-per-call targets, then (after the table) the
/// ns per call of every timed kernel.
fn kernel_targets(s: &ReportSummary, md: &mut String) {
    for k in &s.kernels {
        let Some(target) = k.target_ns else { continue };
        let _ = writeln!(
            md,
            "| {} ≤ {} ns per call | cpu | one thread | {:.2} ns | {} |",
            k.name,
            target,
            k.ns_per_call,
            yes(k.ns_per_call <= target)
        );
    }
    if !s.kernels.is_empty() {
        let _ = writeln!(md, "\nns per call of every timed kernel (one thread, median of {} batches of {} inputs):\n", kernel_timing::BATCHES, kernel_timing::INPUTS);
        let _ = writeln!(md, "| kernel | ns per call |");
        let _ = writeln!(md, "|---|--:|");
        for k in &s.kernels {
            let _ = writeln!(md, "| {} | {:.2} |", k.name, k.ns_per_call);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_throughput_is_judged_only_where_raw_traversal_is_a_bound() {
        let small = 96 * 64;
        assert!(throughput_judged(small, 0.5)
            .unwrap_err()
            .starts_with("not judged at this size"));
        assert!(throughput_judged(small, 1.1).is_err());
        let big = RAY_THROUGHPUT_MIN_RAYS;
        assert_eq!(throughput_judged(big, 0.8), Ok(true));
        assert_eq!(throughput_judged(big, 0.6), Ok(false));
        assert!(throughput_judged(big, 1.1)
            .unwrap_err()
            .contains("outran raw traversal"));
        assert!(throughput_judged(big, f64::NAN).is_err());
    }
}
