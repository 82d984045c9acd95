//! The comparison of `report.md` with the papers' published numbers (SRAA
//! Table 1, the hybrid's, CTSS Table 1), and SRAA-RT against CTSS on the
//! SDF scenes.

use std::fmt::Write as _;

use super::{f, row_of, rows_for, MeanRatio, CTSS_TABLE1, SRAA_SPEEDUP_OVER_SSAA16, SRAA_TABLE1};
use crate::classes::Metric;
use crate::context::{ms, Context};
use crate::key::RowKey;
use crate::named::{CTSS, NOAA, SRAA_RT, SSAA16, SSAA4_CTSS};
use crate::{ReportSummary, ResultRow};

/// The block comparing our numbers with the papers' published ones.
pub fn paper_comparison(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## Against the papers' numbers\n");
    let _ = writeln!(
        md,
        "The papers time GPU implementations; ours are {} wall times, so absolute milliseconds \
do not compare, but the split between passes and the ratios between methods do.\n",
        ctx.backends.join(" and ")
    );
    let _ = writeln!(md, "### SRAA for ray tracing, Table 1 (Sponza)\n");
    let _ = writeln!(
        md,
        "Paper: pass 1 (geometric information, ray tracer) and pass 2 (antialiasing), ms; about \
{SRAA_SPEEDUP_OVER_SSAA16}× faster than 16× SSAA with the GPU hybrid (Fig. 3). Ours: the passes \
`geometry` and `antialiasing` of sraa-rt (`shading` is the one shaded sample per pixel), and \
ssaa16's median time over sraa-rt's.\n"
    );
    let sdf_scene = |name: &str| ctx.scenes.iter().any(|sc| sc.sdf && sc.name == name);
    for b in &ctx.backends {
        let sweep: Vec<&ResultRow> = rows_for(&s.sweep, SRAA_RT, b);
        let (source, rows): (&[ResultRow], Vec<&ResultRow>) = if sweep.is_empty() {
            // Table 1 is about triangle scenes: SDF rows are in `sdf_pick`.
            let rows = rows_for(&s.rows, SRAA_RT, b)
                .into_iter()
                .filter(|r| !sdf_scene(&r.scene))
                .collect();
            (&s.rows, rows)
        } else {
            (&s.sweep, sweep)
        };
        if rows.is_empty() {
            let _ = writeln!(md, "No sraa-rt results on {b}.\n");
            continue;
        }
        let _ = writeln!(
            md,
            "| scene | size | paper pass 1 | paper pass 2 | paper total | ours geometry | ours antialiasing | ours shading | ours sraa-rt | ours ssaa16 / sraa-rt |"
        );
        let _ = writeln!(md, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|");
        for r in rows {
            let paper = SRAA_TABLE1
                .iter()
                .find(|p| p.0 == r.width && p.0 == r.height);
            let ss = source.iter().find(|x| {
                x.method == SSAA16
                    && x.backend == r.backend
                    && x.scene == r.scene
                    && x.width == r.width
                    && x.height == r.height
            });
            let p = |i: usize| {
                paper
                    .map(|p| format!("{:.0}", [p.1, p.2, p.3][i]))
                    .unwrap_or_else(|| "–".into())
            };
            let _ = writeln!(
                md,
                "| {} ({b}) | {}x{} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r.scene,
                r.width,
                r.height,
                p(0),
                p(1),
                p(2),
                f(r.pass("geometry"), 1),
                f(r.pass("antialiasing"), 1),
                f(r.pass("shading"), 1),
                ms(r.ms_median),
                f(ss.map(|x| x.ms_median / r.ms_median), 2),
            );
        }
        let _ = writeln!(
            md,
            "\nPaper: ssaa16 / SRAA ≈ {SRAA_SPEEDUP_OVER_SSAA16:.0} (GPU hybrid, Fig. 3).\n"
        );
    }
    md.push_str(&crate::hybrid::paper_section(&s.rows, ctx));

    let _ = writeln!(md, "### CTSS, Table 1 (average frame-time ratio to NoAA)\n");
    let sdf = ctx.sdf_scenes();
    if sdf.is_empty() {
        let _ = writeln!(md, "No SDF scene was reported on.\n");
        return md;
    }
    let _ = writeln!(
        md,
        "Ours: the mean over the scenes of each scene's median per-round ratio to NoAA; in brackets \
the means of the scenes' smallest and of their largest per-round ratios.\n"
    );
    for b in &ctx.backends {
        let _ = writeln!(
            md,
            "| method | paper avg ratio | ours avg ratio ({b}, {}) | scenes |",
            sdf.join(", ")
        );
        let _ = writeln!(md, "|---|--:|--:|--:|");
        let mut lines = CTSS_TABLE1
            .iter()
            .map(|(paper, ours, ratio)| (format!("{paper} / {ours}"), Some(*ratio), *ours))
            .collect::<Vec<_>>();
        lines.push((format!("4x SS + CTSS / {SSAA4_CTSS}"), None, SSAA4_CTSS));
        for (name, paper, ours) in lines {
            let avg = MeanRatio::of(s.rows.iter().filter(|r| {
                r.backend == *b && r.method == ours && sdf.contains(&r.scene.as_str())
            }));
            let _ = writeln!(
                md,
                "| {name} | {} | {} | {} |",
                f(paper, 2),
                avg.map_or_else(|| "–".into(), |a| a.show(2, false)),
                avg.map_or(0, |a| a.n)
            );
        }
        let _ = writeln!(md);
    }
    md
}

/// SRAA-RT (sphere-traced samples) against CTSS on the SDF scenes: error and
/// time side by side, and which of the two are on each scene's Pareto fronts.
pub fn sdf_pick(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let sdf = ctx.sdf_scenes();
    if sdf.is_empty() {
        return md;
    }
    let _ = writeln!(
        md,
        "## SRAA-RT or CTSS on SDF content
"
    );
    let _ = writeln!(
        md,
        "SRAA-RT here takes its one shaded sample and four geometric subsamples per pixel by \
sphere tracing; CTSS cone traces one ray per pixel. Error: mean FLIP against the reference (whole \
image and edge mask); time: median ms at the timing size. *On the front* names which of the two \
are on the scene's Pareto front under FLIP and under SSIM; which method to use at each cost, \
these two and every other, is *The answer* at the top, computed from the fronts.\n"
    );
    let answer = crate::answer::Answer::of(&s.rows, &ctx.scenes);
    for b in &ctx.backends {
        let find = |scene: &str, method| row_of(&s.rows, method, b, scene);
        let mut lines = Vec::new();
        for sc in &sdf {
            let (Some(rt), Some(ct)) = (find(sc, SRAA_RT), find(sc, CTSS)) else {
                continue;
            };
            if rt.flip_mean.is_none() || ct.flip_mean.is_none() {
                continue;
            }
            let on_front = |metric: Metric| {
                let on: Vec<String> = [rt, ct]
                    .iter()
                    .map(|r| &r.method)
                    .filter(|m| {
                        answer
                            .front(sc, b, metric)
                            .is_some_and(|f| f.points.iter().any(|p| p.method == **m))
                    })
                    .map(RowKey::to_string)
                    .collect();
                if on.is_empty() {
                    "neither".to_string()
                } else {
                    on.join(", ")
                }
            };
            let noaa = find(sc, NOAA).and_then(|r| r.flip_mean);
            lines.push(format!(
                "| {sc} | {} | {} | {} | {} | {} | {} | {} | {} / {} |",
                f(noaa, 4),
                f(rt.flip_mean, 4),
                f(ct.flip_mean, 4),
                f(rt.edge_flip_mean, 4),
                f(ct.edge_flip_mean, 4),
                ms(rt.ms_median),
                ms(ct.ms_median),
                on_front(Metric::Flip),
                on_front(Metric::Ssim),
            ));
        }
        if lines.is_empty() {
            let _ = writeln!(md, "No sraa-rt and ctss errors on {b} to compare.\n");
            continue;
        }
        let _ = writeln!(
            md,
            "| scene ({b}) | noaa FLIP | sraa-rt FLIP | ctss FLIP | sraa-rt edge FLIP | ctss edge FLIP | sraa-rt ms | ctss ms | on the front (FLIP / SSIM) |"
        );
        let _ = writeln!(md, "|---|--:|--:|--:|--:|--:|--:|--:|---|");
        for l in &lines {
            let _ = writeln!(md, "{l}");
        }
        let _ = writeln!(md);
    }
    md
}
