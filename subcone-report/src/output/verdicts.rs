//! The verdicts of `report.md`: the edge classes and the rules of
//! judgement, the verdicts at a glance, and each scene's class errors and
//! verdicts under FLIP and SSIM, with where the two disagree and why.

use std::fmt::Write as _;

use super::with_range;
use crate::classes::{self, Class, Metric, Verdict, CLASSES};
use crate::context::Context;
use crate::key::RowKey;
use crate::named::NOAA;
use crate::{file_safe, ReportSummary, ResultRow};

/// The edge classes' definitions and thresholds, the camera offsets the
/// errors are measured at (`offsets`, with what they cost of a run of
/// `elapsed`), and the rules of judgement.
pub fn rules(offsets: &crate::ErrorOffsets, elapsed: std::time::Duration) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Edge classes and the rules of judgement\n\n\
Every pixel is classified from its own sub-samples: the AOVs of a CPU NoAA frame rendered at \
{s}× the quality size on each side, so each pixel has a {s}×{s} grid of sub-samples (fewer per side \
only where that frame would pass the pixel limit). A feature the one NoAA sample misses is still \
seen by a sub-sample. The classes may overlap; *flat* is a pixel in none of the others.\n\n\
| class | a pixel is in it when |\n|---|---|\n\
| silhouette | two 4-neighbouring sub-samples of the pixel see a surface and the background, or view depths that differ by more than {d} relatively, unless the inverse depth continues linearly from either side (as across one plane) |\n\
| crease | two 4-neighbouring sub-samples on one continuous surface (no silhouette between them) have normals whose cosine is below {c} |\n\
| shadow | no silhouette or crease in the pixel, and the per-light visibility of its surface sub-samples differs (a light that faces away counts as visible) |\n\
| texture | no silhouette or crease in the pixel, and its surface sub-samples' albedo differs by more than {t} in some channel of √albedo |\n\
| reflection | a sub-sample sees a mirror (reflectance above 0) |\n\
| near edge | none of the above, but within the metric's reach of a pixel that is (Chebyshev distance): {r} px under FLIP (the {side}×{side} square around it), {rs} px under SSIM ({sides}×{sides}); measured and reported, not judged |\n\
| flat | none of the above, and not near edge (under each metric, its own band) |\n\n\
The near-edge band holds the pixels an error metric with a spatial filter charges with a \
neighbouring edge's error, as far as the filter reaches: FLIP's filters at the {ppd} pixels per \
degree it is computed at reach {r} px (its colour filter's radius ⌈3 √(0.04 / 2π²) · {ppd}⌉, \
its feature filter's ⌈3 · ½ · 0.082 · {ppd}⌉ = {rf}; Andersson et al. 2020), SSIM's window {rs} px. \
Flat is judged without them, on what remains beyond them; each scene's section says how much \
that is. \
`flip_<class>` is the mean FLIP over the class's pixels and `px_<class>` their count (in \
`results.csv` and `results.json`; the band's columns are `flip_near_edge`, `px_near_edge`, \
`dssim_near_edge`).\n\n\
{offsets_text}\n\n\
The second metric is SSIM (Wang et al. 2004): an 11×11 Gaussian window of σ = 1.5, K1 = 0.01, \
K2 = 0.03, on the luminance of the same tone-mapped 8-bit images FLIP compares, one value per \
pixel (the window renormalised where it leaves the image). `ssim_mean` is its mean over the \
image and `dssim_<class>` the mean of 1 − SSIM over the class's pixels; the `ssim_<method>.png` \
images show 1 − SSIM from 0 (black) to 0.5 or more (white).\n\n\
Which classes each method claims to fix:\n\n\
| method | claimed classes |\n|---|---|\n\
| ssaaN, ssaaN+ctss | all |\n\
| sraa | silhouette, crease |\n\
| sraa-rt | silhouette, crease, shadow, reflection |\n\
| `+mat` variants | adds texture |\n\
| ctss, ctss-r, ctss-delayed | silhouette |\n\
| ctss+edges | silhouette, crease |\n\
| fxaa, smaa | silhouette, crease, shadow, texture (luminance edges of any origin) |\n\n\
Verdicts are computed under each metric by the same rules, comparing a method with NoAA (same \
scene and backend) at each camera offset, paired: the method's error at an offset against NoAA's \
at the same offset. On a claimed class, at one offset, the method *wins* when its error there \
(FLIP, or 1 − SSIM) is at most {b} × NoAA's and *loses* when it is at least {l:.4} × (1/{b}) \
NoAA's. It **beats** NoAA on the class when it wins at every offset, **loses by N×** when it \
loses at every offset (N the ratio of its mean error to NoAA's), **ties** when it neither wins nor \
loses at any offset. When its error is on one side of NoAA's at every offset without winning (or \
losing) at every one, it is **better (or worse) than NoAA at every offset, not always by the \
margin** where it wins (loses) at some offsets, and **ties (consistently better, or worse, within \
the margin)** where it does neither at any. It is a **tie (within noise)** only when the offsets \
disagree in direction (better at one, worse at another) and the margin is cleared at one of them: \
the spread over the offsets is larger than the difference. On flat pixels, at one offset, it \
*holds* when its flat error is at most {f} × NoAA's; it **holds** when it holds at every offset, \
**loses by N×** when it holds at none, is **worse at every offset, not always by the margin** when \
it holds at some and is worse than NoAA at every one, and is a **tie (within noise)** otherwise. A class (or flat) with fewer than \
{min_px} pixels at some offset gets no verdict (**too few pixels**). Under SSIM a difference of \
mean 1 − SSIM below {floor} does not count either way (to win, a method must also be at least \
that much lower; to lose, at least that much higher): that is what rounding to 8 bits alone does \
to a flat window ((1/255)²/12 over K2², about 0.0014), chosen before any method was measured. \
Each scene's verdict lines are computed from the rows by these rules, with the range of the \
per-offset ratios to NoAA, and list where the two metrics disagree, each with a computed cause \
line; a claimed class with no pixel in the scene is listed as having none.\n",
        s = classes::SUBSAMPLES,
        d = classes::SILHOUETTE_DEPTH,
        c = classes::CREASE_COS,
        t = classes::TEXTURE_ALBEDO,
        b = classes::BEAT_FACTOR,
        l = classes::LOSE_FACTOR,
        f = classes::FLAT_FACTOR,
        floor = classes::DSSIM_FLOOR,
        r = classes::near_edge_radius(Metric::Flip),
        side = 2 * classes::near_edge_radius(Metric::Flip) + 1,
        rs = classes::near_edge_radius(Metric::Ssim),
        sides = 2 * classes::near_edge_radius(Metric::Ssim) + 1,
        ppd = subcone_metrics::FLIP_PIXELS_PER_DEGREE,
        rf = subcone_metrics::flip_filter_radii(subcone_metrics::FLIP_PIXELS_PER_DEGREE).1,
        min_px = classes::MIN_VERDICT_PIXELS,
        offsets_text = offsets_text(offsets, elapsed),
    );
    md
}

/// What the rules say about the camera offsets of this run, and their cost.
fn offsets_text(o: &crate::ErrorOffsets, elapsed: std::time::Duration) -> String {
    if o.offsets.len() < 2 {
        return "Errors are measured from the scene's camera alone (one offset): verdicts are \
judged on that one frame."
            .into();
    }
    let list: Vec<String> = o
        .offsets
        .iter()
        .map(|&(x, y)| format!("({x}, {y})"))
        .collect();
    let secs = o.elapsed.as_secs_f64();
    format!(
        "Errors are measured at K = {k} sub-pixel camera offsets: the scene's camera turned right \
and down by {list} pixels' worth of angle at the image centre, each offset against its own \
reference and with its own classes (only the quality render is repeated; the timing rounds are \
not). FLIP, SSIM and every class error are the mean over the offsets, with the smallest and \
largest in brackets (`_min` and `_max` columns); PSNR, edge FLIP and the images are the first \
offset's; `px_<class>` is the fewest pixels the class has at any offset. Every offset is \
measured at the quality size against the same {reference} reference. The {extra} further \
offsets took {secs:.1} s of this run's {total:.1} s ({share:.1} %).",
        k = o.offsets.len(),
        list = list.join(", "),
        reference = o.reference,
        extra = o.offsets.len() - 1,
        total = elapsed.as_secs_f64(),
        share = 100.0 * secs / elapsed.as_secs_f64().max(1e-9),
    )
}

/// Every verdict of the run in one table: a row per method, backend and
/// metric, a column per scene, each cell the claimed classes beaten (of
/// those with pixels) and whether flat holds.
pub fn verdict_summary(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let scenes: Vec<&str> = ctx.scenes.iter().map(|sc| sc.name.as_str()).collect();
    let mut keys: Vec<(RowKey, String, Metric)> = Vec::new();
    let mut cells: Vec<((RowKey, String, Metric, String), String)> = Vec::new();
    for sc in &scenes {
        let rows: Vec<&ResultRow> = s.rows.iter().filter(|r| r.scene == *sc).collect();
        for metric in Metric::ALL {
            for (backend, v) in verdicts(&rows, metric) {
                let key = (v.method.clone(), backend.clone(), metric);
                if !keys.contains(&key) {
                    keys.push(key);
                }
                cells.push((
                    (v.method.clone(), backend, metric, sc.to_string()),
                    glance_cell(&v),
                ));
            }
        }
    }
    if keys.is_empty() {
        return md;
    }
    // Each method's FLIP row, then its SSIM row.
    let order = keys.clone();
    keys.sort_by_key(|k| {
        let first = order.iter().position(|f| f.0 == k.0 && f.1 == k.1);
        (first, k.2 == Metric::Ssim)
    });
    let _ = writeln!(
        md,
        "## Verdicts at a glance\n\n\
Per scene and metric: how many of the claimed classes with a verdict the method beats NoAA on \
(*b*/*n*), then how many it is better than NoAA on at every offset without the margin at every \
one (better), ties on one side (tie, better; tie, worse) or on both, is worse on at every offset \
(worse), ties within noise (the offsets disagree in direction) or loses, and how many have too \
few pixels for a verdict; then its flat verdict (holds, **loses N×**, worse, tie (noise), few px). The lines under \
each scene give the classes and figures, and where the two metrics disagree, with the cause.\n"
    );
    let _ = writeln!(md, "| method | backend | metric | {} |", scenes.join(" | "));
    let _ = writeln!(md, "|---|---|---|{}", "--:|".repeat(scenes.len()));
    for (method, backend, metric) in &keys {
        let row: Vec<String> = scenes
            .iter()
            .map(|sc| {
                cells
                    .iter()
                    .find(|(k, _)| {
                        k.0 == *method && k.1 == *backend && k.2 == *metric && k.3 == *sc
                    })
                    .map(|(_, c)| c.clone())
                    .unwrap_or_else(|| "–".into())
            })
            .collect();
        let _ = writeln!(
            md,
            "| {} | {backend} | {} | {} |",
            same_image_name(s, method, backend),
            metric.name(),
            row.join(" | ")
        );
    }
    let _ = writeln!(md);
    md
}

/// `method`, or `method (same image as ctss)` when on every scene where it
/// has an error on `backend` its image is byte-identical to one other
/// method's ([`answer::exclusions`](crate::answer::exclusions)).
fn same_image_name(s: &ReportSummary, method: &RowKey, backend: &str) -> String {
    let rows: Vec<&ResultRow> = s.rows.iter().collect();
    let left_out = crate::answer::exclusions(&rows);
    let measured = rows
        .iter()
        .filter(|r| r.method == *method && r.backend == backend && r.flip_mean.is_some())
        .count();
    let same: Vec<&RowKey> = left_out
        .iter()
        .filter(|e| e.method == *method && e.backend == backend)
        .filter_map(|e| match &e.why {
            crate::answer::Why::SameImage { as_method } => Some(as_method),
            _ => None,
        })
        .collect();
    match same.first() {
        Some(first) if same.len() == measured && same.iter().all(|m| m == first) => {
            format!("{method} (same image as {first})")
        }
        _ => method.to_string(),
    }
}

/// One cell of "Verdicts at a glance": `3/4 · 1 noise · holds`.
pub fn glance_cell(v: &Verdict) -> String {
    use classes::Outcome;
    let judged = v
        .judged
        .iter()
        .filter(|j| j.outcome != Outcome::FewPixels)
        .count();
    let mut cell = format!("{}/{judged}", v.beats.len());
    for (o, word) in [
        (Outcome::LeansBetter, "better"),
        (Outcome::TiesBetter, "tie, better"),
        (Outcome::Ties, "tie"),
        (Outcome::TiesWorse, "tie, worse"),
        (Outcome::LeansWorse, "worse"),
        (Outcome::Noise, "noise"),
        (Outcome::Loses, "**lost**"),
        (Outcome::FewPixels, "few px"),
    ] {
        let n = v.with(o).count();
        if n > 0 {
            let _ = write!(cell, " · {n} {word}");
        }
    }
    let flat = match &v.flat_judged {
        None => "no flat".to_string(),
        Some(j) => match j.outcome {
            Outcome::Holds => "holds".into(),
            Outcome::Loses => format!("**loses {}**", classes::loss_text(j.mean_ratio())),
            Outcome::Noise => "tie (noise)".into(),
            Outcome::LeansWorse => "worse".into(),
            _ => "few px".into(),
        },
    };
    let _ = write!(cell, " · {flat}");
    cell
}

/// How much of the image is flat beyond each metric's reach (the pixels
/// the flat verdicts are judged on), from the first measured row: its
/// fewest flat pixels over the offsets over the quality size. `None`
/// without a quality size.
fn flat_remaining(rows: &[&&ResultRow]) -> Option<String> {
    let r = rows.first()?;
    let px = u64::from(r.quality_width?) * u64::from(r.quality_height?);
    if px == 0 {
        return None;
    }
    let share = |m: Metric| {
        let k = r.class_error(m)?;
        Some(100.0 * k.px[Class::Flat.index()] as f64 / px as f64)
    };
    Some(format!(
        "Flat beyond the metrics' reach (what \"flat\" is judged on): {:.1} % of the pixels under FLIP (more than {} px from any class), {:.1} % under SSIM (more than {} px).",
        share(Metric::Flip)?,
        classes::near_edge_radius(Metric::Flip),
        share(Metric::Ssim)?,
        classes::near_edge_radius(Metric::Ssim),
    ))
}

/// A table of one metric's per-class error, a row per measured method.
fn class_table(md: &mut String, rows: &[&&ResultRow], metric: Metric) {
    let Some(first) = rows.first().and_then(|r| r.class_error(metric)) else {
        return;
    };
    let what = match metric {
        Metric::Flip => "FLIP",
        Metric::Ssim => "1 − SSIM",
    };
    let offsets = rows.iter().map(|r| r.errors_at.len()).max().unwrap_or(0);
    let _ = writeln!(
        md,
        "{what} by edge class (pixels per class in the header{}; *near edge* is measured, not judged):\n",
        if offsets > 1 {
            format!(
                ", the fewest over the {offsets} camera offsets; each cell the mean over the offsets and, in brackets, the smallest and largest"
            )
        } else {
            String::new()
        }
    );
    let mut head: Vec<String> = CLASSES
        .iter()
        .map(|c| format!("{c} ({} px)", first.px[c.index()]))
        .collect();
    head.push(format!("near edge ({} px)", first.near_edge_px));
    let _ = writeln!(md, "| method | backend | {} |", head.join(" | "));
    let _ = writeln!(md, "|---|---|{}", "--:|".repeat(CLASSES.len() + 1));
    for r in rows {
        let k = r.class_error(metric).unwrap_or_default();
        let at = r.class_errors_at(metric);
        let cell = |v: Option<f64>, get: &dyn Fn(&classes::ClassError) -> Option<f64>| {
            let range = (at.len() > 1)
                .then(|| classes::ClassError::range(&at, get))
                .flatten();
            with_range(v, range)
        };
        let mut cells: Vec<String> = CLASSES
            .iter()
            .map(|c| cell(k.mean[c.index()], &|e| e.mean[c.index()]))
            .collect();
        cells.push(cell(k.near_edge, &|e| e.near_edge));
        let _ = writeln!(
            md,
            "| {} | {} | {} |",
            r.method,
            r.backend,
            cells.join(" | ")
        );
    }
    let _ = writeln!(md);
}

/// A scene's error by class under each metric (tables and the FLIP chart),
/// its verdict lines under each, and where the two disagree.
pub(super) fn class_section(scene: &str, rows: &[&ResultRow]) -> String {
    let mut md = String::new();
    let with: Vec<&&ResultRow> = rows.iter().filter(|r| r.classes.is_some()).collect();
    if with.is_empty() {
        return md;
    }
    class_table(&mut md, &with, Metric::Flip);
    let _ = writeln!(
        md,
        "![{scene}: FLIP by edge class](plots/{}_classes.png)\n",
        file_safe(scene)
    );
    class_table(&mut md, &with, Metric::Ssim);
    if let Some(line) = flat_remaining(&with) {
        let _ = writeln!(md, "{line}\n");
    }
    let flip = verdicts(rows, Metric::Flip);
    let ssim = verdicts(rows, Metric::Ssim);
    if !flip.is_empty() || !ssim.is_empty() {
        let _ = writeln!(md, "Verdicts against NoAA:\n");
        for (backend, v) in flip.iter().chain(&ssim) {
            let _ = writeln!(md, "{}", v.line(backend));
        }
        let _ = writeln!(md);
        let disagree: Vec<String> = flip
            .iter()
            .filter_map(|(b, fv)| {
                let (_, sv) = ssim
                    .iter()
                    .find(|(sb, sv)| sb == b && sv.method == fv.method)?;
                let items = disagreement(fv, sv);
                if items.is_empty() {
                    return None;
                }
                let find = |m: &RowKey| {
                    rows.iter()
                        .find(|r| r.method == *m && r.backend == *b)
                        .copied()
                };
                let band = match (
                    rows.iter()
                        .find(|r| r.method == fv.method && r.backend == *b)
                        .copied(),
                    find(&NOAA.into()),
                ) {
                    (Some(it), Some(noaa)) => near_edge_share(it, noaa),
                    _ => None,
                };
                let mut text = format!("- **{}** ({b}):\n", fv.method);
                for (what, cause) in items {
                    let _ = writeln!(text, "  - {what}.\n    Cause: {cause}.");
                }
                if let Some(band) = band {
                    let _ = writeln!(text, "  - Near-edge band: {}.", band.sentence());
                }
                Some(text)
            })
            .collect();
        if disagree.is_empty() {
            let _ = writeln!(md, "FLIP and SSIM agree on every verdict of this scene.\n");
        } else {
            let _ = writeln!(
                md,
                "Where FLIP and SSIM disagree, each with its computed cause:\n\n{}",
                disagree.join("")
            );
        }
    }
    md
}

/// Where the verdicts of one row under FLIP (`flip`) and SSIM (`ssim`)
/// differ, class by class and on flat, with both metrics' words and
/// figures, each with its computed cause: noise when one metric's
/// per-offset ratios straddle its thresholds, else a disagreement at every
/// offset, with both ranges. Empty when they agree (a class with too few
/// pixels under either metric is not compared).
fn disagreement(flip: &Verdict, ssim: &Verdict) -> Vec<(String, String)> {
    use classes::{outcome_word, Judged, Outcome};
    let mut out = Vec::new();
    let mut compare = |what: String, f: &Judged, s: &Judged| {
        let few = |j: &Judged| j.outcome == Outcome::FewPixels;
        if f.outcome == s.outcome || few(f) || few(s) {
            return;
        }
        let range = |j: &Judged| {
            format!(
                "{}–{}×",
                classes::ratio_text(j.ratio.0),
                classes::ratio_text(j.ratio.1)
            )
        };
        let thresholds = if f.class == Class::Flat {
            format!("holds at ≤ {}×", classes::FLAT_FACTOR)
        } else {
            format!(
                "wins at ≤ {}×, loses at ≥ {:.2}×",
                classes::BEAT_FACTOR,
                classes::LOSE_FACTOR
            )
        };
        let noisy: Vec<String> = [(f, "FLIP"), (s, "SSIM")]
            .iter()
            .filter(|(j, _)| {
                matches!(
                    j.outcome,
                    Outcome::Noise | Outcome::LeansBetter | Outcome::LeansWorse
                )
            })
            .map(|(j, m)| format!("{m}'s ({})", range(j)))
            .collect();
        let cause = if !noisy.is_empty() {
            format!(
                "noise: the per-offset ratio to NoAA, {}, does not stay on one side of the \
thresholds ({thresholds}), so the call changes with the offset; FLIP's ratios are {}, SSIM's {}",
                noisy.join(" and "),
                range(f),
                range(s)
            )
        } else {
            format!(
                "not noise: each metric gives the same call at each of the {} offsets (FLIP ratio \
to NoAA {}, SSIM {}); the two metrics weigh the change differently",
                f.offsets,
                range(f),
                range(s)
            )
        };
        out.push((
            format!(
                "{what}: {} under FLIP ({}) but {} under SSIM ({})",
                outcome_word(f),
                f.figures(),
                outcome_word(s),
                s.figures()
            ),
            cause,
        ));
    };
    for j in &flip.judged {
        if let Some(s) = ssim.judged.iter().find(|s| s.class == j.class) {
            compare(j.class.to_string(), j, s);
        }
    }
    if let (Some(f), Some(s)) = (&flip.flat_judged, &ssim.flat_judged) {
        compare("flat".into(), f, s);
    }
    out
}

/// How a method's FLIP excess over NoAA on the pixels in no class splits
/// between the near-edge band and flat: sums over the pixels and the
/// camera offsets (paired, each offset's own masks).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandShare {
    /// Σ (method − NoAA) FLIP over the band's pixels.
    pub band_excess: f64,
    /// Σ (method − NoAA) FLIP over the flat pixels.
    pub flat_excess: f64,
    /// Band pixels, summed over the offsets.
    pub band_px: u64,
    /// Flat pixels, summed over the offsets.
    pub flat_px: u64,
}

impl BandShare {
    /// The band's share of the excess, when the excess is positive.
    pub fn share(&self) -> Option<f64> {
        let total = self.band_excess + self.flat_excess;
        (total > 0.0).then(|| self.band_excess / total)
    }

    /// The band's share of the pixels in no class.
    pub fn px_share(&self) -> f64 {
        self.band_px as f64 / (self.band_px + self.flat_px).max(1) as f64
    }

    /// In words, for a cause line.
    pub fn sentence(&self) -> String {
        let px = 100.0 * self.px_share();
        match self.share() {
            Some(share) if self.band_excess >= 0.0 && self.flat_excess >= 0.0 => format!(
                "{:.0} % of the method's FLIP excess over NoAA on the pixels in no class (flat and \
near edge, summed over the pixels and the offsets) lies in the near-edge band, which holds {px:.0} % \
of those pixels; flat, judged above, carries {:.0} %",
                100.0 * share,
                100.0 * (1.0 - share)
            ),
            _ => format!(
                "the method's FLIP minus NoAA's, summed over the pixels and the offsets, is {:+.2} on \
the near-edge band ({px:.0} % of the pixels in no class) and {:+.2} on flat",
                self.band_excess, self.flat_excess
            ),
        }
    }
}

/// [`BandShare`] of row `it` against `noaa` (FLIP, paired by offset);
/// `None` when either has no per-class errors or no pixel lies in no class.
pub fn near_edge_share(it: &ResultRow, noaa: &ResultRow) -> Option<BandShare> {
    let (a, n) = (
        it.class_errors_at(Metric::Flip),
        noaa.class_errors_at(Metric::Flip),
    );
    let mut out = BandShare {
        band_excess: 0.0,
        flat_excess: 0.0,
        band_px: 0,
        flat_px: 0,
    };
    let flat = Class::Flat.index();
    for (a, n) in a.iter().zip(&n) {
        if let (Some(x), Some(y)) = (a.near_edge, n.near_edge) {
            out.band_excess += (x - y) * a.near_edge_px as f64;
            out.band_px += a.near_edge_px;
        }
        if let (Some(x), Some(y)) = (a.mean[flat], n.mean[flat]) {
            out.flat_excess += (x - y) * a.px[flat] as f64;
            out.flat_px += a.px[flat];
        }
    }
    (out.band_px + out.flat_px > 0).then_some(out)
}

/// The verdict under `metric` of every method but NoAA among `rows` (one
/// scene), against NoAA on the same backend: (backend, verdict).
pub fn verdicts(rows: &[&ResultRow], metric: Metric) -> Vec<(String, Verdict)> {
    let mut out = Vec::new();
    for r in rows {
        if r.method == NOAA {
            continue;
        }
        let noaa = rows
            .iter()
            .find(|n| n.method == NOAA && n.backend == r.backend && n.scene == r.scene)
            .map(|n| n.class_errors_at(metric))
            .unwrap_or_default();
        let it = r.class_errors_at(metric);
        if !it.is_empty() && !noaa.is_empty() {
            let v = Verdict::judge_claims(r.method.clone(), r.claims(), metric, &it, &noaa);
            out.push((r.backend.clone(), v));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_rows::measured;

    #[test]
    fn flip_and_ssim_disagreements_get_a_computed_cause() {
        let noaa = measured("noaa", [0.2; 4], [0.05; 4], [0.1; 4], [0.1; 4]);
        // fxaa-like: FLIP loses on silhouette at every offset, SSIM beats;
        // flat holds under both; the band carries most of the excess.
        let fx = measured(
            "fxaa",
            [0.24, 0.25, 0.23, 0.24],
            [0.0505, 0.0505, 0.0505, 0.0505],
            [0.13, 0.14, 0.13, 0.12],
            [0.08; 4],
        );
        let rows = [&noaa, &fx];
        let md = class_section("s", &rows);
        assert!(
            md.contains("silhouette: loses by 1.2× under FLIP (0.2400 vs 0.2000, 1.15–1.25× over 4 offsets) but beats under SSIM"),
            "{md}"
        );
        assert!(md.contains("Cause: not noise: each metric gives the same call at each of the 4 offsets (FLIP ratio to NoAA 1.15–1.25×, SSIM 0.80–0.80×)"), "{md}");
        // Band: 0.03 × 100 per offset; flat: 0.0005 × 300: 12 / 12.6.
        let share = near_edge_share(&fx, &noaa).unwrap();
        assert!((share.share().unwrap() - 12.0 / 12.6).abs() < 1e-9);
        assert!((share.px_share() - 0.25).abs() < 1e-12);
        assert!(
            md.contains("Near-edge band: 95 % of the method's FLIP excess"),
            "{md}"
        );
        assert!(md.contains("which holds 25 % of those pixels"), "{md}");
        // Noise: FLIP wins at two offsets and not at the others.
        let noisy = measured(
            "fxaa",
            [0.18, 0.2, 0.18, 0.2],
            [0.05; 4],
            [0.1; 4],
            [0.08; 4],
        );
        let md = class_section("s", &[&noaa, &noisy]);
        assert!(
            md.contains("silhouette: tie (within noise) under FLIP"),
            "{md}"
        );
        assert!(md.contains("Cause: noise: the per-offset ratio to NoAA, FLIP's (0.90–1.00×), does not stay on one side"), "{md}");
        // Agreement: no disagreement section.
        let same = measured("fxaa", [0.1; 4], [0.05; 4], [0.1; 4], [0.05; 4]);
        let md = class_section("s", &[&noaa, &same]);
        assert!(md.contains("FLIP and SSIM agree on every verdict"), "{md}");
        // The table shows the spread and the band.
        assert!(md.contains("near edge (100 px)"), "{md}");
        // No excess: said so, not a share.
        let better = measured("fxaa", [0.1; 4], [0.04; 4], [0.05; 4], [0.05; 4]);
        let b = near_edge_share(&better, &noaa).unwrap();
        assert_eq!(b.share(), None);
        assert!(b.sentence().contains("is -20.00 on the near-edge band (25 % of the pixels in no class) and -12.00 on flat"), "{}", b.sentence());
    }

    #[test]
    fn glance_cells_count_each_outcome() {
        let noaa = measured("noaa", [0.2; 4], [0.05; 4], [0.1; 4], [0.1; 4]);
        let it = measured("sraa", [0.1, 0.2, 0.1, 0.1], [0.06; 4], [0.1; 4], [0.05; 4]);
        let v = &verdicts(&[&noaa, &it], Metric::Flip)[0].1;
        // sraa claims silhouette and crease; crease has no pixels.
        assert_eq!(glance_cell(v), "0/1 · 1 noise · **loses 1.2×**");
        let v = &verdicts(&[&noaa, &it], Metric::Ssim)[0].1;
        assert_eq!(glance_cell(v), "1/1 · holds");
    }
}
