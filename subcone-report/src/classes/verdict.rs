//! The verdicts: a method's error per class against NoAA's, judged by the
//! same rules under each metric.

use subcone_scene::Method;

use super::masks::ClassMasks;
use super::{figure, Class, CLASSES, MIN_VERDICT_PIXELS};
use crate::key::RowKey;

/// A method beats NoAA on a class when its error there (FLIP, or 1 − SSIM)
/// is at most this factor of NoAA's (at every camera offset).
pub const BEAT_FACTOR: f64 = 0.95;
/// A method loses to NoAA on a claimed class when its error there is at
/// least this factor of NoAA's (at every camera offset): the beat factor's
/// inverse, so that a loss is as far above NoAA as a win is below.
pub const LOSE_FACTOR: f64 = 1.0 / BEAT_FACTOR;
/// A method holds on flat pixels when its flat error is at most this factor
/// of NoAA's.
pub const FLAT_FACTOR: f64 = 1.02;
/// The smallest difference of mean `1 − SSIM` that counts, on either side
/// of a verdict. Chosen from the metric before any method was measured:
/// rounding an image to 8 bits alone adds noise of variance `(1/255)² / 12`,
/// which lowers SSIM on a flat window by about that over `C2 = 0.03²`,
/// 0.0014; a difference smaller than that is quantisation, not
/// antialiasing. FLIP has no floor (its verdicts are the ones the report
/// always gave).
pub const DSSIM_FLOOR: f64 = 0.0015;

/// An error metric the verdicts are computed under, by the same rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Metric {
    /// LDR-FLIP ([`subcone_metrics::flip`]).
    Flip,
    /// `1 − SSIM` on luminance ([`subcone_metrics::ssim`]).
    Ssim,
}

impl Metric {
    /// Both, in the order the report shows them.
    pub const ALL: [Metric; 2] = [Metric::Flip, Metric::Ssim];

    /// The name the report prints.
    pub fn name(self) -> &'static str {
        match self {
            Metric::Flip => "FLIP",
            Metric::Ssim => "SSIM",
        }
    }

    /// The absolute difference below which a difference does not count.
    pub fn floor(self) -> f64 {
        match self {
            Metric::Flip => 0.0,
            Metric::Ssim => DSSIM_FLOOR,
        }
    }

    /// Whether an error `a` beats NoAA's `n`: at most [`BEAT_FACTOR`] of it,
    /// and lower by at least the floor.
    pub fn beats(self, a: f64, n: f64) -> bool {
        a <= BEAT_FACTOR * n && n - a >= self.floor()
    }

    /// Whether an error `a` on a claimed class loses to NoAA's `n`: at
    /// least [`LOSE_FACTOR`] of it, and higher by at least the floor.
    pub fn loses(self, a: f64, n: f64) -> bool {
        a >= LOSE_FACTOR * n && a - n >= self.floor() && a > n
    }

    /// Whether a flat error `a` holds against NoAA's `n`: at most
    /// [`FLAT_FACTOR`] of it, or higher by less than the floor.
    pub fn holds(self, a: f64, n: f64) -> bool {
        a <= FLAT_FACTOR * n || a - n < self.floor()
    }
}

/// The masks as each metric judges them (here, beside [`Metric`], so that
/// the masks' file does not depend on the verdicts').
impl ClassMasks {
    /// The flat mask under `metric`: in no class and out of the metric's
    /// near-edge band.
    pub fn flat(&self, metric: Metric) -> &[bool] {
        match metric {
            Metric::Flip => self.mask(Class::Flat),
            Metric::Ssim => &self.ssim_flat,
        }
    }

    /// The near-edge band under `metric`.
    pub fn near(&self, metric: Metric) -> &[bool] {
        match metric {
            Metric::Flip => &self.near_edge,
            Metric::Ssim => &self.ssim_near_edge,
        }
    }

    /// The mask of `class` under `metric`: flat is the metric's own
    /// ([`ClassMasks::flat`]), the other classes the same under both.
    pub fn mask_for(&self, class: Class, metric: Metric) -> &[bool] {
        match class {
            Class::Flat => self.flat(metric),
            c => self.mask(c),
        }
    }
}

/// The per-class error of one result under one metric: `mean[c]` is the
/// mean of the error map (FLIP, or `1 − SSIM`) over the pixels of class `c`
/// (`None` where the class has no pixel), `px[c]` their count, both indexed
/// by [`Class::index`]; the near-edge band's alike.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClassError {
    /// Mean error per class.
    pub mean: [Option<f64>; 6],
    /// Pixels per class.
    pub px: [u64; 6],
    /// Mean error over the near-edge band ([`ClassMasks::near_edge`]).
    pub near_edge: Option<f64>,
    /// Pixels in the near-edge band.
    pub near_edge_px: u64,
}

impl ClassError {
    /// Mean error map values per class, `map` being `metric`'s (flat and
    /// the near-edge band are the metric's own, [`ClassMasks::flat`]).
    pub fn measure(map: &[f32], masks: &ClassMasks, metric: Metric) -> Self {
        let mut out = ClassError::default();
        for c in CLASSES {
            let mask = masks.mask_for(c, metric);
            out.mean[c.index()] = crate::metrics::masked_mean(map, mask);
            out.px[c.index()] = mask.iter().filter(|&&m| m).count() as u64;
        }
        let near = masks.near(metric);
        out.near_edge = crate::metrics::masked_mean(map, near);
        out.near_edge_px = near.iter().filter(|&&m| m).count() as u64;
        out
    }

    /// The errors of several camera offsets in one: per class the mean over
    /// the offsets where the class has pixels, and the smallest pixel count
    /// of any offset (a class is only as well sampled as its thinnest
    /// offset). `None` without an offset.
    pub fn over_offsets(at: &[ClassError]) -> Option<ClassError> {
        if at.is_empty() {
            return None;
        }
        let mean = |v: &dyn Fn(&ClassError) -> Option<f64>| {
            let got: Vec<f64> = at.iter().filter_map(v).collect();
            (!got.is_empty()).then(|| got.iter().sum::<f64>() / got.len() as f64)
        };
        Some(ClassError {
            mean: std::array::from_fn(|i| mean(&|e| e.mean[i])),
            px: std::array::from_fn(|i| at.iter().map(|e| e.px[i]).min().unwrap_or(0)),
            near_edge: mean(&|e| e.near_edge),
            near_edge_px: at.iter().map(|e| e.near_edge_px).min().unwrap_or(0),
        })
    }

    /// The smallest and largest value of `v` over the offsets `at` where it
    /// is measured.
    pub fn range(at: &[ClassError], v: impl Fn(&ClassError) -> Option<f64>) -> Option<(f64, f64)> {
        at.iter().filter_map(v).fold(None, |r, x| match r {
            None => Some((x, x)),
            Some((lo, hi)) => Some((x.min(lo), x.max(hi))),
        })
    }
}

/// A verdict on one class (or on flat pixels) against NoAA, over the
/// camera offsets. Each word means its rule: a call that changes with the
/// offset is *noise* only when the offsets disagree in direction (better
/// at one, worse at another); a method on one side of NoAA at every offset
/// that does not clear the margin at every one *leans* that way, or *ties*
/// consistently on that side when it clears it at none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Beats NoAA at every offset ([`Metric::beats`]).
    Beats,
    /// Better than NoAA at every offset, beyond the margin at some of them
    /// but not all.
    LeansBetter,
    /// Better than NoAA at every offset, within the margin at every one.
    TiesBetter,
    /// Within the margin at every offset, on both sides of NoAA (or equal).
    Ties,
    /// Worse than NoAA at every offset, within the margin at every one.
    TiesWorse,
    /// Worse than NoAA at every offset, beyond the margin at some of them
    /// but not all (on flat: holds at some offsets, not at others).
    LeansWorse,
    /// The offsets disagree in direction, and the margin is cleared at one
    /// of them at least: the spread is larger than the difference.
    Noise,
    /// Loses at every offset ([`Metric::loses`]; on flat, does not hold).
    Loses,
    /// Flat only: holds at every offset ([`Metric::holds`]).
    Holds,
    /// Fewer than [`MIN_VERDICT_PIXELS`] pixels at some offset: no verdict.
    FewPixels,
}

impl Outcome {
    /// Every outcome, in the order the verdict lines list them.
    pub const ALL: [Outcome; 10] = [
        Outcome::Beats,
        Outcome::LeansBetter,
        Outcome::TiesBetter,
        Outcome::Ties,
        Outcome::TiesWorse,
        Outcome::LeansWorse,
        Outcome::Noise,
        Outcome::Loses,
        Outcome::Holds,
        Outcome::FewPixels,
    ];

    /// The outcome of per-offset `calls` (`Some(true)` a win or a hold,
    /// `Some(false)` a loss, `None` neither) and per-offset `directions`
    /// (`Some(true)` lower error than NoAA's, `Some(false)` higher, `None`
    /// equal), on a class with `px` pixels at the fewest. `flat` turns an
    /// all-win into [`Outcome::Holds`].
    pub fn of(calls: &[Option<bool>], directions: &[Option<bool>], px: u64, flat: bool) -> Outcome {
        let all = |v: &[Option<bool>], x: Option<bool>| v.iter().all(|c| *c == x);
        if px < MIN_VERDICT_PIXELS {
            Outcome::FewPixels
        } else if all(calls, Some(true)) {
            if flat {
                Outcome::Holds
            } else {
                Outcome::Beats
            }
        } else if all(calls, Some(false)) {
            Outcome::Loses
        } else if all(directions, Some(true)) && !flat {
            if all(calls, None) {
                Outcome::TiesBetter
            } else {
                Outcome::LeansBetter
            }
        } else if all(directions, Some(false)) {
            if all(calls, None) {
                Outcome::TiesWorse
            } else {
                Outcome::LeansWorse
            }
        } else if all(calls, None) {
            Outcome::Ties
        } else {
            Outcome::Noise
        }
    }

    /// The word the verdict lines lead a list of classes with, e.g.
    /// `beats NoAA on`; `None` for the outcomes written otherwise (losses,
    /// holds, too few pixels).
    pub fn lead(self) -> Option<&'static str> {
        Some(match self {
            Outcome::Beats => "beats NoAA on",
            Outcome::LeansBetter => {
                "better than NoAA at every offset, not always by the margin, on"
            }
            Outcome::TiesBetter => "ties (consistently better, within the margin) on",
            Outcome::Ties => "ties NoAA on",
            Outcome::TiesWorse => "ties (consistently worse, within the margin) on",
            Outcome::LeansWorse => "worse than NoAA at every offset, not always by the margin, on",
            Outcome::Noise => "tie (within noise) on",
            Outcome::Loses | Outcome::Holds | Outcome::FewPixels => return None,
        })
    }
}

/// One judged class: the outcome and its figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Judged {
    /// The class.
    pub class: Class,
    /// The outcome.
    pub outcome: Outcome,
    /// The method's error, mean over the offsets.
    pub it: f64,
    /// NoAA's, mean over the offsets.
    pub noaa: f64,
    /// Smallest and largest per-offset ratio of the method's error to
    /// NoAA's (paired by offset).
    pub ratio: (f64, f64),
    /// Offsets compared.
    pub offsets: usize,
    /// Pixels of the class (the smallest count over the offsets).
    pub px: u64,
}

impl Judged {
    /// The ratio of the mean errors, the `N` of "loses by N×".
    pub fn mean_ratio(&self) -> f64 {
        if self.noaa > 0.0 {
            self.it / self.noaa
        } else {
            f64::INFINITY
        }
    }

    /// Its figures: `0.1900 vs 0.2000`, with the per-offset ratio range
    /// when there is more than one offset.
    pub fn figures(&self) -> String {
        let figures = format!("{} vs {}", figure(self.it), figure(self.noaa));
        if self.offsets > 1 {
            format!(
                "{figures}, {}–{}× over {} offsets",
                ratio_text(self.ratio.0),
                ratio_text(self.ratio.1),
                self.offsets
            )
        } else {
            figures
        }
    }
}

/// A ratio as the verdicts print it: 2 decimals (`∞` when NoAA's error is
/// 0).
pub fn ratio_text(r: f64) -> String {
    if r.is_finite() {
        format!("{r:.2}")
    } else {
        "∞".into()
    }
}

/// "loses by N×": one decimal from 1.1 on, two below (so a loss never
/// reads "1.0×").
pub fn loss_text(r: f64) -> String {
    if !r.is_finite() {
        "∞×".into()
    } else if r >= 1.1 {
        format!("{r:.1}×")
    } else {
        format!("{r:.2}×")
    }
}

/// Judge one class from the paired per-offset errors `pairs` (the method's,
/// NoAA's) and its smallest pixel count, by `per`: per offset, `Some(true)`
/// for a win (a hold on flat), `Some(false)` for a loss, `None` for
/// neither.
fn judge_class(
    class: Class,
    pairs: &[(f64, f64)],
    px: u64,
    flat: bool,
    per: impl Fn(f64, f64) -> Option<bool>,
) -> Judged {
    let n = pairs.len().max(1) as f64;
    let it = pairs.iter().map(|p| p.0).sum::<f64>() / n;
    let noaa = pairs.iter().map(|p| p.1).sum::<f64>() / n;
    let ratios = pairs.iter().map(|&(a, b)| {
        if b > 0.0 {
            a / b
        } else if a > 0.0 {
            f64::INFINITY
        } else {
            1.0
        }
    });
    let ratio = ratios.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
        (lo.min(r), hi.max(r))
    });
    let calls: Vec<Option<bool>> = pairs.iter().map(|&(a, b)| per(a, b)).collect();
    let directions: Vec<Option<bool>> = pairs
        .iter()
        .map(|&(a, b)| (a != b).then_some(a < b))
        .collect();
    let outcome = Outcome::of(&calls, &directions, px, flat);
    Judged {
        class,
        outcome,
        it,
        noaa,
        ratio,
        offsets: pairs.len(),
        px,
    }
}

/// How one method fares against NoAA on one scene and backend, under one
/// metric, over the camera offsets its error was measured at.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// The row judged: a method, or a post-process step.
    pub method: RowKey,
    /// The metric the errors are in.
    pub metric: Metric,
    /// The classes it claims.
    pub claims: Vec<Class>,
    /// Claimed classes it beats at every offset: (class, its mean error,
    /// NoAA's).
    pub beats: Vec<(Class, f64, f64)>,
    /// Claimed classes with a verdict that it does not beat (ties, ties
    /// within noise, losses).
    pub misses: Vec<(Class, f64, f64)>,
    /// Claimed classes with no pixel in the scene.
    pub absent: Vec<Class>,
    /// Flat pixels: (its mean error, NoAA's), when the scene has any.
    pub flat: Option<(f64, f64)>,
    /// Every claimed class with pixels, judged, in claim order (including
    /// those with too few pixels for a verdict).
    pub judged: Vec<Judged>,
    /// Flat pixels, judged.
    pub flat_judged: Option<Judged>,
}

impl Verdict {
    /// Judge `method` from its per-class FLIP against NoAA's on the same
    /// scene, backend and class masks (one offset), on the classes it claims
    /// ([`Method::claims`]).
    pub fn judge(method: Method, it: &ClassError, noaa: &ClassError) -> Verdict {
        Verdict::judge_claims(
            method.into(),
            method.claims(),
            Metric::Flip,
            std::slice::from_ref(it),
            std::slice::from_ref(noaa),
        )
    }

    /// Judge the row `method` on the classes in `claims` (a post-process
    /// row's, say) from its per-class error under `metric` at each camera
    /// offset (`it[k]` and `noaa[k]` measured at offset `k`; offsets past
    /// the shorter of the two are left out).
    ///
    /// Per class, paired by offset ([`Outcome::of`]): it **beats** NoAA
    /// when it beats at every offset ([`Metric::beats`]), **loses** when it
    /// loses at every offset ([`Metric::loses`]); when it is on one side of
    /// NoAA at every offset otherwise, it **leans** that way (the margin
    /// cleared at some offsets) or **ties consistently** on that side (at
    /// none); with the offsets on both sides, it **ties** when it does
    /// neither at any offset and is a **tie within noise** otherwise. Flat
    /// pixels **hold** when they hold at every offset ([`Metric::holds`]),
    /// **lose** when they hold at none, **lean worse** when they hold at
    /// some and are worse at every one, and are a tie within noise
    /// otherwise. A class with fewer than [`MIN_VERDICT_PIXELS`] pixels at
    /// some offset gets no verdict.
    pub fn judge_claims(
        method: RowKey,
        claims: Vec<Class>,
        metric: Metric,
        it: &[ClassError],
        noaa: &[ClassError],
    ) -> Verdict {
        let mut v = Verdict {
            method,
            metric,
            claims: claims.clone(),
            beats: Vec::new(),
            misses: Vec::new(),
            absent: Vec::new(),
            flat: None,
            judged: Vec::new(),
            flat_judged: None,
        };
        let pairs = |c: Class| -> (Vec<(f64, f64)>, u64) {
            let i = c.index();
            let pairs: Vec<(f64, f64)> = it
                .iter()
                .zip(noaa)
                .filter_map(|(a, n)| a.mean[i].zip(n.mean[i]))
                .collect();
            let px = it
                .iter()
                .zip(noaa)
                .map(|(a, n)| a.px[i].min(n.px[i]))
                .min()
                .unwrap_or(0);
            (pairs, px)
        };
        for c in claims {
            let (p, px) = pairs(c);
            if p.is_empty() {
                v.absent.push(c);
                continue;
            }
            let j = judge_class(c, &p, px, false, |a, n| {
                if metric.beats(a, n) {
                    Some(true)
                } else if metric.loses(a, n) {
                    Some(false)
                } else {
                    None
                }
            });
            match j.outcome {
                Outcome::Beats => v.beats.push((c, j.it, j.noaa)),
                Outcome::FewPixels => {}
                _ => v.misses.push((c, j.it, j.noaa)),
            }
            v.judged.push(j);
        }
        let (p, px) = pairs(Class::Flat);
        if !p.is_empty() {
            let j = judge_class(Class::Flat, &p, px, true, |a, n| Some(metric.holds(a, n)));
            v.flat = Some((j.it, j.noaa));
            v.flat_judged = Some(j);
        }
        v
    }

    /// Whether it holds on flat pixels: not a loss at every offset (true
    /// without flat pixels, or with too few for a verdict).
    pub fn holds_on_flat(&self) -> bool {
        self.flat_judged.is_none_or(|j| j.outcome != Outcome::Loses)
    }

    /// The judged classes with `outcome`.
    pub fn with(&self, outcome: Outcome) -> impl Iterator<Item = &Judged> {
        self.judged.iter().filter(move |j| j.outcome == outcome)
    }

    /// The flat verdict's word: `holds`, `loses by 1.3×`, `tie (within
    /// noise)`, `too few pixels`; `no pixels` without flat pixels.
    pub fn flat_word(&self) -> String {
        match &self.flat_judged {
            None => "no pixels".into(),
            Some(j) => outcome_word(j),
        }
    }

    /// The verdict as one Markdown list item, e.g. `- **sraa-rt** (cpu,
    /// FLIP): beats NoAA on silhouette (0.0810 vs 0.1200, 0.62–0.71× over
    /// 4 offsets); tie (within noise) on shadow (…); no pixels of
    /// reflection; flat: holds (…).`
    pub fn line(&self, backend: &str) -> String {
        let list = |o: Outcome| {
            self.with(o)
                .map(|j| format!("{} ({})", j.class, j.figures()))
                .collect::<Vec<_>>()
        };
        let mut parts = Vec::new();
        if self.claims.is_empty() {
            parts.push("claims no class".to_string());
        }
        for (o, lead) in Outcome::ALL.iter().filter_map(|&o| Some((o, o.lead()?))) {
            let l = list(o);
            if !l.is_empty() {
                parts.push(format!("{lead} {}", l.join(", ")));
            }
        }
        for j in self.with(Outcome::Loses) {
            parts.push(format!(
                "loses by {} on {} ({})",
                loss_text(j.mean_ratio()),
                j.class,
                j.figures()
            ));
        }
        let few: Vec<String> = self
            .with(Outcome::FewPixels)
            .map(|j| format!("{} ({} px)", j.class, j.px))
            .collect();
        if !few.is_empty() {
            parts.push(format!(
                "too few pixels for a verdict on {}",
                few.join(", ")
            ));
        }
        if !self.absent.is_empty() {
            let a: Vec<&str> = self.absent.iter().map(|c| c.name()).collect();
            parts.push(format!("no pixels of {}", a.join(", ")));
        }
        parts.push(match &self.flat_judged {
            Some(j) if j.outcome == Outcome::FewPixels => {
                format!("flat: too few pixels ({} px)", j.px)
            }
            Some(j) => format!("flat: {} ({})", outcome_word(j), j.figures()),
            None => "flat: no pixels".to_string(),
        });
        format!(
            "- **{}** ({backend}, {}): {}.",
            self.method,
            self.metric.name(),
            parts.join("; ")
        )
    }
}

/// One outcome in words: `beats`, `ties`, `tie (within noise)`, `loses by
/// 1.3×`, `holds`, `too few pixels`.
pub fn outcome_word(j: &Judged) -> String {
    match j.outcome {
        Outcome::Beats => "beats".into(),
        Outcome::LeansBetter => "better at every offset, not always by the margin".into(),
        Outcome::TiesBetter => "ties (consistently better, within the margin)".into(),
        Outcome::Ties => "ties".into(),
        Outcome::TiesWorse => "ties (consistently worse, within the margin)".into(),
        Outcome::LeansWorse => "worse at every offset, not always by the margin".into(),
        Outcome::Noise => "tie (within noise)".into(),
        Outcome::Loses => format!("loses by {}", loss_text(j.mean_ratio())),
        Outcome::Holds => "holds".into(),
        Outcome::FewPixels => "too few pixels".into(),
    }
}
