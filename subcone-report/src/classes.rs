//! Edge classes: which pixels need antialiasing, and why.
//!
//! A pixel is classified from its own **sub-samples**: the AOVs (view depth,
//! normal, albedo, per-light visibility, mirror reflectance) of a NoAA frame
//! rendered by the CPU reference at [`SUBSAMPLES`]× the quality size on each
//! side, so sub-sample `(i, j)` of pixel `(x, y)` is pixel
//! `(SUBSAMPLES·x + i, SUBSAMPLES·y + j)` of that frame: the centre of cell
//! `(i, j)` of a regular `SUBSAMPLES × SUBSAMPLES` grid over the pixel. A
//! feature that the one NoAA sample through the pixel centre misses (a thin
//! pole, a shadow corner) is still seen by some sub-sample, so the pixel is
//! not called flat.
//!
//! The classes may overlap; *flat* is a pixel in none of the others.
//!
//! | class | a pixel is in it when |
//! |---|---|
//! | silhouette | two 4-neighbouring sub-samples of the pixel see a surface and the background, or view depths that differ by more than [`SILHOUETTE_DEPTH`] relatively, unless the inverse depth continues linearly from either side (as across one plane, however grazing) |
//! | crease | two 4-neighbouring sub-samples on one continuous surface (no silhouette between them) have normals whose cosine is below [`CREASE_COS`] |
//! | shadow | no silhouette or crease in the pixel, and the per-light visibility of its surface sub-samples differs (some see a light that others do not) |
//! | texture | no silhouette or crease in the pixel, and the albedo of its surface sub-samples differs by more than [`TEXTURE_ALBEDO`] in some channel of `√albedo` |
//! | reflection | a sub-sample sees a mirror (reflectance above 0) |
//! | flat | none of the above, and no pixel of the above within [`NEAR_EDGE_RADIUS`] pixels (Chebyshev distance: the 5×5 square around it) |
//!
//! A pixel in none of the five classes but within [`NEAR_EDGE_RADIUS`] of
//! one is in the *near edge* band ([`ClassMasks::near_edge`]), not flat: an
//! error metric with a spatial filter (FLIP's) spreads an edge's error onto
//! its neighbours, so a method that changes the edge changes the error
//! there too. The band is measured and reported but not judged.

use anyhow::{bail, Result};
use glam::Vec3;
use subcone_scene::{Frame, Method};

use crate::key::RowKey;

/// Sub-samples per pixel side: the classes see a 4×4 grid in each pixel.
pub const SUBSAMPLES: u32 = 4;
/// Relative view-depth difference between neighbouring sub-samples above
/// which they see different surfaces (the edge mask's threshold, 2 %).
pub const SILHOUETTE_DEPTH: f32 = 0.02;
/// Cosine between neighbouring sub-samples' normals below which one surface
/// folds inside the pixel (about 26°; the edge mask's threshold).
pub const CREASE_COS: f32 = 0.9;
/// Difference of `√albedo` in one channel above which the albedo changes
/// inside the pixel: about 13 sRGB codes at mid-grey, so a printed pattern or
/// a texture step counts and texture noise of a few codes does not.
pub const TEXTURE_ALBEDO: f32 = 0.05;
/// Pixels in none of the classes within this Chebyshev distance of a
/// classed pixel (silhouette, crease, shadow, texture or reflection) are in
/// the near-edge band, not flat.
pub const NEAR_EDGE_RADIUS: u32 = 2;
/// A class with fewer pixels than this (at some camera offset) gets no
/// verdict: a mean over a handful of pixels moves with a sub-pixel shift of
/// the camera by more than the thresholds the verdicts use.
pub const MIN_VERDICT_PIXELS: u64 = 64;

/// A class mean as the verdict lines print it: 4 decimals, or 3 significant
/// digits below 0.001, so that two small errors a verdict tells apart do
/// not both read 0.0000.
pub fn figure(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.2e}")
    } else {
        format!("{v:.4}")
    }
}

/// An edge class: the registry's ([`subcone_scene::EdgeClass`]), which
/// also says which classes each method claims.
pub use subcone_scene::registry::EdgeClass as Class;
/// Every class, in column order.
pub use subcone_scene::registry::EDGE_CLASSES as CLASSES;

/// One mask per class over a `width × height` image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ClassMasks {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The masks, indexed by [`Class::index`], row-major.
    pub masks: [Vec<bool>; 6],
    /// The near-edge band, row-major: pixels in none of the classes within
    /// [`NEAR_EDGE_RADIUS`] of a classed pixel (and so not flat).
    pub near_edge: Vec<bool>,
}

impl ClassMasks {
    /// The mask of `class`.
    pub fn mask(&self, class: Class) -> &[bool] {
        &self.masks[class.index()]
    }

    /// Pixels in `class`.
    pub fn count(&self, class: Class) -> u64 {
        self.mask(class).iter().filter(|&&m| m).count() as u64
    }

    /// Split the pixels in no class into the near-edge band (within
    /// [`NEAR_EDGE_RADIUS`] of a classed pixel, Chebyshev) and flat (the
    /// rest): sets [`ClassMasks::near_edge`] and clears those pixels from
    /// the flat mask.
    fn split_near_edge(&mut self) {
        let (w, h) = (self.width as usize, self.height as usize);
        let r = NEAR_EDGE_RADIUS as usize;
        if w == 0 || h == 0 {
            self.near_edge = Vec::new();
            return;
        }
        let classed: Vec<bool> = (0..w * h)
            .map(|p| {
                CLASSES
                    .iter()
                    .any(|&c| c != Class::Flat && self.masks[c.index()][p])
            })
            .collect();
        // Separable dilation by a (2r+1)² square: rows, then columns.
        let mut rows = vec![false; w * h];
        for y in 0..h {
            for x in 0..w {
                let (a, b) = (x.saturating_sub(r), (x + r).min(w - 1));
                rows[y * w + x] = classed[y * w + a..=y * w + b].iter().any(|&c| c);
            }
        }
        let mut near = vec![false; w * h];
        for y in 0..h {
            let (a, b) = (y.saturating_sub(r), (y + r).min(h - 1));
            for x in 0..w {
                near[y * w + x] = !classed[y * w + x] && (a..=b).any(|yy| rows[yy * w + x]);
            }
        }
        let flat = &mut self.masks[Class::Flat.index()];
        for (f, &n) in flat.iter_mut().zip(&near) {
            *f &= !n;
        }
        self.near_edge = near;
    }

    /// One byte per pixel, row-major, bit `i` set when the pixel is in
    /// class `i` ([`Class::index`]): every class of a pixel in one lookup,
    /// as the interactive page reads them.
    pub fn bits(&self) -> Vec<u8> {
        let mut out = vec![0u8; (self.width * self.height) as usize];
        for (i, mask) in self.masks.iter().enumerate() {
            for (b, &m) in out.iter_mut().zip(mask) {
                *b |= u8::from(m) << i;
            }
        }
        out
    }
}

/// The AOVs a classification needs, checked against the frame size.
struct Aovs<'a> {
    w: usize,
    h: usize,
    depth: &'a [f32],
    normal: &'a [Vec3],
    albedo: &'a [Vec3],
    visibility: &'a [u32],
    mirror: &'a [f32],
}

impl<'a> Aovs<'a> {
    fn of(f: &'a Frame) -> Result<Self> {
        let (w, h) = (f.width as usize, f.height as usize);
        let (Some(depth), Some(normal), Some(albedo), Some(visibility), Some(mirror)) = (
            f.depth.as_deref(),
            f.normal.as_deref(),
            f.albedo.as_deref(),
            f.light_visibility.as_deref(),
            f.mirror.as_deref(),
        ) else {
            bail!(
                "the sub-sample frame lacks an AOV: classes need depth, normal, albedo, \
                 light visibility and mirror (render with aovs = true on the cpu backend)"
            );
        };
        let n = w * h;
        if [
            depth.len(),
            normal.len(),
            albedo.len(),
            visibility.len(),
            mirror.len(),
        ]
        .iter()
        .any(|&l| l != n)
        {
            bail!("the sub-sample AOVs do not match the frame size {w}x{h}");
        }
        Ok(Aovs {
            w,
            h,
            depth,
            normal,
            albedo,
            visibility,
            mirror,
        })
    }

    fn hit(&self, i: usize) -> bool {
        self.depth[i].is_finite()
    }

    /// Whether sub-samples `a` and `b` (4-neighbours) see different
    /// surfaces ([`metrics::depth_discontinuity`](crate::metrics::depth_discontinuity)
    /// at [`SILHOUETTE_DEPTH`]); `oa` and `ob` are their neighbours on the
    /// same line, away from each other.
    fn silhouette(&self, a: usize, b: usize, oa: Option<usize>, ob: Option<usize>) -> bool {
        crate::metrics::depth_discontinuity(self.depth, a, b, oa, ob, SILHOUETTE_DEPTH)
    }

    /// Whether the normals of `a` and `b` (both surface points) fold.
    fn crease(&self, a: usize, b: usize) -> bool {
        let (na, nb) = (self.normal[a], self.normal[b]);
        na.is_finite()
            && nb.is_finite()
            && na.length_squared() > 0.25
            && nb.length_squared() > 0.25
            && na.normalize().dot(nb.normalize()) < CREASE_COS
    }
}

/// Classify every pixel of a `sub.width / side × sub.height / side` image
/// from `sub`, a frame rendered at `side`× that size on each side with the
/// AOVs [`Frame::albedo`], [`Frame::light_visibility`], [`Frame::mirror`],
/// depth and normal (the CPU backend records them all).
///
/// Errors when an AOV is missing, the sizes disagree or `side` is 0; never
/// panics on NaN or infinite AOV values (a NaN depth is a miss, a NaN normal
/// never creases, NaN albedo never differs).
pub fn classify(sub: &Frame, side: u32) -> Result<ClassMasks> {
    if side == 0 || sub.width % side != 0 || sub.height % side != 0 {
        bail!(
            "a {}x{} sub-sample frame does not divide into {side}x{side} sub-samples per pixel",
            sub.width,
            sub.height
        );
    }
    let a = Aovs::of(sub)?;
    let s = side as usize;
    let (w, h) = (a.w / s, a.h / s);
    let mut masks: [Vec<bool>; 6] = std::array::from_fn(|_| vec![false; w * h]);
    for py in 0..h {
        for px in 0..w {
            let mut silhouette = false;
            let mut crease = false;
            let (mut vis_or, mut vis_and) = (0u32, u32::MAX);
            let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
            let mut mirror = false;
            let mut surfaces = 0;
            for j in 0..s {
                for i in 0..s {
                    let (x, y) = (px * s + i, py * s + j);
                    let k = y * a.w + x;
                    // Pairs inside the pixel: with the right and lower neighbour.
                    if i + 1 < s {
                        let oa = (x > 0).then(|| k - 1);
                        let ob = (x + 2 < a.w).then(|| k + 2);
                        let sil = a.silhouette(k, k + 1, oa, ob);
                        silhouette |= sil;
                        crease |= !sil && a.hit(k) && a.hit(k + 1) && a.crease(k, k + 1);
                    }
                    if j + 1 < s {
                        let oa = (y > 0).then(|| k - a.w);
                        let ob = (y + 2 < a.h).then(|| k + 2 * a.w);
                        let sil = a.silhouette(k, k + a.w, oa, ob);
                        silhouette |= sil;
                        crease |= !sil && a.hit(k) && a.hit(k + a.w) && a.crease(k, k + a.w);
                    }
                    mirror |= a.mirror[k] > 0.0;
                    if a.hit(k) {
                        surfaces += 1;
                        vis_or |= a.visibility[k];
                        vis_and &= a.visibility[k];
                        let c = a.albedo[k].max(Vec3::ZERO);
                        let e = Vec3::new(c.x.sqrt(), c.y.sqrt(), c.z.sqrt());
                        if e.is_finite() {
                            lo = lo.min(e);
                            hi = hi.max(e);
                        }
                    }
                }
            }
            let smooth = !silhouette && !crease;
            let shadow = smooth && surfaces > 1 && vis_or != vis_and;
            let texture = smooth && lo.x.is_finite() && (hi - lo).max_element() > TEXTURE_ALBEDO;
            let p = py * w + px;
            masks[Class::Silhouette.index()][p] = silhouette;
            masks[Class::Crease.index()][p] = crease;
            masks[Class::Shadow.index()][p] = shadow;
            masks[Class::Texture.index()][p] = texture;
            masks[Class::Reflection.index()][p] = mirror;
            masks[Class::Flat.index()][p] = !(silhouette || crease || shadow || texture || mirror);
        }
    }
    let mut out = ClassMasks {
        width: w as u32,
        height: h as u32,
        masks,
        near_edge: Vec::new(),
    };
    out.split_near_edge();
    Ok(out)
}

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
    /// Mean error map values per class.
    pub fn measure(map: &[f32], masks: &ClassMasks) -> Self {
        let mut out = ClassError::default();
        for c in CLASSES {
            out.mean[c.index()] = crate::metrics::masked_mean(map, masks.mask(c));
            out.px[c.index()] = masks.count(c);
        }
        out.near_edge = crate::metrics::masked_mean(map, &masks.near_edge);
        out.near_edge_px = masks.near_edge.iter().filter(|&&m| m).count() as u64;
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
/// camera offsets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Beats NoAA at every offset ([`Metric::beats`]).
    Beats,
    /// Neither beats nor loses at any offset.
    Ties,
    /// The offsets disagree: the margin does not clear the spread.
    Noise,
    /// Loses at every offset ([`Metric::loses`]; on flat, does not hold).
    Loses,
    /// Flat only: holds at every offset ([`Metric::holds`]).
    Holds,
    /// Fewer than [`MIN_VERDICT_PIXELS`] pixels at some offset: no verdict.
    FewPixels,
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
    let outcome = if px < MIN_VERDICT_PIXELS {
        Outcome::FewPixels
    } else if calls.iter().all(|c| *c == Some(true)) {
        if flat {
            Outcome::Holds
        } else {
            Outcome::Beats
        }
    } else if calls.iter().all(|c| *c == Some(false)) {
        Outcome::Loses
    } else if calls.iter().all(|c| c.is_none()) {
        Outcome::Ties
    } else {
        Outcome::Noise
    };
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
    /// Per class, paired by offset: it **beats** NoAA when it beats at
    /// every offset ([`Metric::beats`]), **loses** when it loses at every
    /// offset ([`Metric::loses`]), **ties** when it does neither at any
    /// offset, and is a **tie within noise** otherwise; flat pixels
    /// **hold** when they hold at every offset ([`Metric::holds`]), **lose**
    /// when they hold at none, and are a tie within noise otherwise. A class
    /// with fewer than [`MIN_VERDICT_PIXELS`] pixels at some offset gets no
    /// verdict.
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
        for (o, lead) in [
            (Outcome::Beats, "beats NoAA on"),
            (Outcome::Ties, "ties NoAA on"),
            (Outcome::Noise, "tie (within noise) on"),
        ] {
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
        Outcome::Ties => "ties".into(),
        Outcome::Noise => "tie (within noise)".into(),
        Outcome::Loses => format!("loses by {}", loss_text(j.mean_ratio())),
        Outcome::Holds => "holds".into(),
        Outcome::FewPixels => "too few pixels".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::key::named;
    use crate::named::{SRAA, SRAA_RT};

    #[test]
    fn bits_hold_each_pixels_classes() {
        let mut masks: [Vec<bool>; 6] = Default::default();
        for (i, m) in masks.iter_mut().enumerate() {
            // Pixel p is in class i when bit i of p is set.
            *m = (0..64u32).map(|p| p & (1 << i) != 0).collect();
        }
        let c = ClassMasks {
            width: 8,
            height: 8,
            masks,
            near_edge: vec![false; 64],
        };
        assert_eq!(c.bits(), (0..64u8).collect::<Vec<_>>());
    }

    /// The classes the method named `name` claims, none for any other name.
    fn claimed(name: &str) -> Vec<Class> {
        name.parse::<Method>()
            .map(|m| m.claims())
            .unwrap_or_default()
    }

    #[test]
    fn claims_follow_the_table() {
        use Class::*;
        assert_eq!(claimed("noaa"), vec![]);
        assert_eq!(claimed("ssaa4").len(), 5);
        assert_eq!(claimed("ssaa4+ctss").len(), 5);
        assert_eq!(claimed("sraa"), vec![Silhouette, Crease]);
        assert_eq!(claimed("sraa+mat"), vec![Silhouette, Crease, Texture]);
        assert_eq!(claimed("sraa-rt-paper+mat"), claimed("sraa-rt+mat"));
        assert_eq!(claimed("sraa-paper"), claimed("sraa"));
        assert_eq!(
            claimed("sraa-rt+mat"),
            vec![Silhouette, Crease, Shadow, Texture, Reflection]
        );
        assert_eq!(claimed("ctss-r-delayed"), vec![Silhouette]);
        assert_eq!(claimed("ctss+edges"), vec![Silhouette, Crease]);
        assert_eq!(claimed("ctss-paper"), vec![Silhouette]);
        assert_eq!(claimed("ctss-delayed-paper"), vec![Silhouette]);
        assert_eq!(claimed("ctss+edges-paper"), vec![Silhouette, Crease]);
        assert_eq!(claimed("ssaa4+ctss-paper").len(), 5);
        // A post-process row claims through its row, not its name.
        assert_eq!(claimed("smaa"), vec![]);
        let mut row = crate::ResultRow::timed(
            "s",
            crate::key::named("smaa"),
            "cpu",
            (1, 1),
            1,
            &Default::default(),
        );
        assert_eq!(row.claims(), vec![]);
        row.post_process = Some("SMAA".into());
        assert_eq!(row.claims(), vec![Silhouette, Crease, Shadow, Texture]);
        row.method = crate::key::named("sraa");
        assert_eq!(row.claims(), vec![Silhouette, Crease, Shadow, Texture]);
        assert!(!claimed("ssaa16").contains(&Flat));
    }

    fn cf(flips: [Option<f64>; 6]) -> ClassError {
        ClassError {
            mean: flips,
            px: flips.map(|f| f.map_or(0, |_| 100)),
            ..Default::default()
        }
    }

    #[test]
    fn judgement_applies_the_factors() {
        let noaa = cf([Some(0.2), Some(0.2), Some(0.2), None, Some(0.1), Some(0.01)]);
        // 0.19 = 0.95 × 0.2 beats (at most the factor), 0.1901 does not.
        let it = cf([
            Some(0.19),
            Some(0.1901),
            Some(0.5),
            None,
            Some(0.0),
            Some(0.0102),
        ]);
        let v = Verdict::judge(SRAA_RT, &it, &noaa);
        assert_eq!(
            v.beats.iter().map(|b| b.0).collect::<Vec<_>>(),
            vec![Class::Silhouette, Class::Reflection]
        );
        assert_eq!(
            v.misses.iter().map(|b| b.0).collect::<Vec<_>>(),
            vec![Class::Crease, Class::Shadow]
        );
        assert!(v.absent.is_empty());
        assert!(v.holds_on_flat());
        let worse = cf([None, None, None, None, None, Some(0.01021)]);
        assert!(!Verdict::judge(SRAA, &worse, &noaa).holds_on_flat());
        let line = v.line("cpu");
        assert!(
            line.starts_with(
                "- **sraa-rt** (cpu, FLIP): beats NoAA on silhouette (0.1900 vs 0.2000)"
            ),
            "{line}"
        );
        assert!(line.contains("flat: holds"));
        // A texture claim without texture pixels is absent.
        let v = Verdict::judge("sraa+mat".parse().unwrap(), &it, &noaa);
        assert_eq!(v.absent, vec![Class::Texture]);
    }

    /// NoAA's error at four offsets, and a method's at `ratios` of it,
    /// per offset, on silhouette and flat alike.
    fn offsets(ratios: [f64; 4], px: u64) -> (Vec<ClassError>, Vec<ClassError>) {
        let base = [0.20, 0.22, 0.18, 0.21];
        let at = |k: usize, r: f64| {
            let mut e = cf([Some(base[k] * r), None, None, None, None, Some(base[k] * r)]);
            e.px[Class::Silhouette.index()] = px;
            e.px[Class::Flat.index()] = px;
            e
        };
        (
            (0..4).map(|k| at(k, ratios[k])).collect(),
            (0..4).map(|k| at(k, 1.0)).collect(),
        )
    }

    fn outcome(ratios: [f64; 4], px: u64) -> (Outcome, Outcome) {
        let (it, noaa) = offsets(ratios, px);
        let v = Verdict::judge_claims(
            SRAA.into(),
            vec![Class::Silhouette],
            Metric::Flip,
            &it,
            &noaa,
        );
        (v.judged[0].outcome, v.flat_judged.unwrap().outcome)
    }

    #[test]
    fn a_verdict_needs_every_offset_to_agree() {
        use Outcome::*;
        // Wins at every offset: beats; flat holds (at most 1.02×) too.
        assert_eq!(outcome([0.9, 0.8, 0.95, 0.7], 100), (Beats, Holds));
        // One offset short of the factor: a tie within noise, not a win.
        assert_eq!(outcome([0.9, 0.8, 0.96, 0.7], 100), (Noise, Holds));
        // Worse beyond 1/0.95 at every offset: a loss, on flat too.
        assert_eq!(outcome([1.3, 1.25, 1.4, 1.06], 100), (Loses, Loses));
        // Inside the band at every offset: a tie; flat straddles 1.02×.
        assert_eq!(outcome([1.0, 0.97, 1.03, 1.01], 100), (Ties, Noise));
        // Win at one offset, loss at another: noise.
        assert_eq!(outcome([0.9, 1.1, 1.0, 1.0], 100).0, Noise);
        // 63 pixels at some offset: no verdict, whatever the figures.
        assert_eq!(outcome([0.5, 0.5, 0.5, 0.5], 63), (FewPixels, FewPixels));
        assert_eq!(outcome([0.5, 0.5, 0.5, 0.5], MIN_VERDICT_PIXELS).0, Beats);
    }

    #[test]
    fn verdict_lines_use_one_word_per_outcome() {
        let (mut it, noaa) = offsets([1.3, 1.25, 1.4, 1.3], 100);
        // Crease: noise; shadow: too few pixels.
        for (k, e) in it.iter_mut().enumerate() {
            e.mean[Class::Crease.index()] = Some([0.9, 1.1, 1.0, 1.0][k]);
            e.px[Class::Crease.index()] = 100;
            e.mean[Class::Shadow.index()] = Some(0.1);
            e.px[Class::Shadow.index()] = 8;
        }
        let mut noaa = noaa;
        for e in &mut noaa {
            e.mean[Class::Crease.index()] = Some(1.0);
            e.px[Class::Crease.index()] = 100;
            e.mean[Class::Shadow.index()] = Some(0.2);
            e.px[Class::Shadow.index()] = 8;
        }
        let claims = vec![
            Class::Silhouette,
            Class::Crease,
            Class::Shadow,
            Class::Texture,
        ];
        let v = Verdict::judge_claims(named("x"), claims, Metric::Flip, &it, &noaa);
        let line = v.line("cpu");
        assert!(
            line.contains(
                "tie (within noise) on crease (1.0000 vs 1.0000, 0.90–1.10× over 4 offsets)"
            ),
            "{line}"
        );
        // The mean ratio: (0.26 + 0.275 + 0.252 + 0.273) / 0.81 = 1.33.
        assert!(line.contains("loses by 1.3× on silhouette"), "{line}");
        assert!(
            line.contains("too few pixels for a verdict on shadow (8 px)"),
            "{line}"
        );
        assert!(line.contains("no pixels of texture"), "{line}");
        assert!(line.contains("flat: loses by 1.3×"), "{line}");
        assert!(!line.contains("does not beat"));
        assert_eq!(v.beats.len(), 0);
        assert_eq!(
            v.misses.len(),
            2,
            "noise and loss are misses; too few pixels is not"
        );
        assert!(!v.holds_on_flat());
        assert_eq!(loss_text(1.06), "1.06×");
        assert_eq!(loss_text(2.0), "2.0×");
    }

    #[test]
    fn errors_over_offsets_average_and_keep_the_fewest_pixels() {
        let mut a = cf([Some(0.1), None, None, None, None, Some(0.02)]);
        let mut b = cf([Some(0.3), Some(0.5), None, None, None, Some(0.04)]);
        a.px[0] = 120;
        b.px[0] = 80;
        (a.near_edge, a.near_edge_px) = (Some(0.05), 30);
        (b.near_edge, b.near_edge_px) = (Some(0.07), 20);
        let m = ClassError::over_offsets(&[a, b]).unwrap();
        assert!((m.mean[0].unwrap() - 0.2).abs() < 1e-12);
        assert_eq!(m.px[0], 80);
        // A class at one offset only: its mean there, its fewest pixels 0.
        assert_eq!(m.mean[1], Some(0.5));
        assert_eq!(m.px[1], 0);
        assert!((m.near_edge.unwrap() - 0.06).abs() < 1e-12);
        assert_eq!(m.near_edge_px, 20);
        assert_eq!(
            ClassError::range(&[a, b], |e| e.mean[5]),
            Some((0.02, 0.04))
        );
        assert_eq!(ClassError::over_offsets(&[]), None);
    }

    #[test]
    fn pixels_within_two_of_a_class_are_near_edge_not_flat() {
        // 7×7 pixels, a one-sub-sample pole in the centre pixel only.
        let (pw, s) = (7usize, 4usize);
        let mut f = uniform((pw * s) as u32, (pw * s) as u32);
        let w = pw * s;
        let mut depth = vec![2.0f32; w * w];
        for j in 0..s {
            depth[(3 * s + j) * w + 3 * s + 1] = 1.0;
        }
        f.depth = Some(depth);
        let m = classify(&f, s as u32).unwrap();
        let at = |x: usize, y: usize| y * pw + x;
        assert!(m.mask(Class::Silhouette)[at(3, 3)]);
        assert_eq!(m.count(Class::Silhouette), 1);
        // Chebyshev: the 5×5 square around it, corners included.
        for (x, y) in [(2, 3), (1, 3), (5, 5), (1, 1), (5, 1)] {
            assert!(m.near_edge[at(x, y)], "({x}, {y}) is within 2");
            assert!(!m.mask(Class::Flat)[at(x, y)]);
        }
        for (x, y) in [(0, 3), (6, 6), (3, 0), (6, 2)] {
            assert!(!m.near_edge[at(x, y)], "({x}, {y}) is 3 away");
            assert!(m.mask(Class::Flat)[at(x, y)]);
        }
        assert!(!m.near_edge[at(3, 3)], "a classed pixel is not in the band");
        assert_eq!(m.near_edge.iter().filter(|&&b| b).count(), 24);
        assert_eq!(m.count(Class::Flat), 49 - 25);
        // The band's error is measured apart from flat's.
        let map: Vec<f32> = (0..49)
            .map(|p| if m.near_edge[p] { 0.5 } else { 0.1 })
            .collect();
        let e = ClassError::measure(&map, &m);
        assert_eq!((e.near_edge, e.near_edge_px), (Some(0.5), 24));
        assert!((e.mean[Class::Flat.index()].unwrap() - 0.1).abs() < 1e-7);
    }

    #[test]
    fn small_figures_keep_three_significant_digits() {
        assert_eq!(figure(0.12345), "0.1235");
        assert_eq!(figure(0.0), "0.0000");
        assert_eq!(figure(2.5e-5), "2.50e-5");
        assert_eq!(figure(0.001), "0.0010");
    }

    #[test]
    fn ssim_differences_under_the_floor_do_not_count() {
        let f = DSSIM_FLOOR;
        let noaa = cf([Some(0.02), Some(0.01), None, None, None, Some(0.001)]);
        // Silhouette: 0.95× and more than the floor lower, beats. Crease:
        // 0.94×, but lower by less than the floor, does not.
        let it = cf([
            Some(0.02 * 0.95 - f),
            Some(0.0094),
            None,
            None,
            None,
            Some(0.001 + f * 0.9),
        ]);
        let v = Verdict::judge_claims(SRAA.into(), SRAA.claims(), Metric::Ssim, &[it], &[noaa]);
        assert_eq!(
            v.beats.iter().map(|b| b.0).collect::<Vec<_>>(),
            vec![Class::Silhouette]
        );
        assert_eq!(
            v.misses.iter().map(|b| b.0).collect::<Vec<_>>(),
            vec![Class::Crease]
        );
        // Flat: twice NoAA's, but higher by less than the floor: holds.
        assert!(v.holds_on_flat());
        assert!(v
            .line("cpu")
            .starts_with("- **sraa** (cpu, SSIM): beats NoAA on silhouette"));
        let worse = cf([None, None, None, None, None, Some(0.001 + f * 1.1)]);
        assert!(
            !Verdict::judge_claims(SRAA.into(), vec![], Metric::Ssim, &[worse], &[noaa])
                .holds_on_flat()
        );
        // Under FLIP the same figures are judged by the factors alone.
        let v = Verdict::judge_claims(SRAA.into(), SRAA.claims(), Metric::Flip, &[it], &[noaa]);
        assert_eq!(v.beats.len(), 2);
        assert!(!v.holds_on_flat());
    }

    /// A 2×1-pixel sub-sample frame (8×4 sub-samples), every AOV uniform.
    fn uniform(w: u32, h: u32) -> Frame {
        let mut f = Frame::new(w, h);
        let n = (w * h) as usize;
        f.depth = Some(vec![2.0; n]);
        f.normal = Some(vec![Vec3::Z; n]);
        f.albedo = Some(vec![Vec3::splat(0.5); n]);
        f.light_visibility = Some(vec![1; n]);
        f.mirror = Some(vec![0.0; n]);
        f
    }

    #[test]
    fn uniform_aovs_are_flat_and_errors_are_values() {
        let f = uniform(8, 4);
        let m = classify(&f, 4).unwrap();
        assert_eq!((m.width, m.height), (2, 1));
        assert_eq!(m.mask(Class::Flat), &[true, true]);
        assert!(classify(&f, 3).is_err());
        assert!(classify(&f, 0).is_err());
        let mut g = f.clone();
        g.albedo = None;
        assert!(classify(&g, 4).is_err());
        let mut g = f.clone();
        g.depth = Some(vec![f32::NAN; 32]);
        g.normal = Some(vec![Vec3::NAN; 32]);
        // NaN depth reads as a miss everywhere: background, flat.
        assert_eq!(classify(&g, 4).unwrap().mask(Class::Flat), &[true, true]);
    }

    /// The acceptance frame: each class known by construction. Two rows of
    /// 11 pixels at 4×4 sub-samples. Row 0, by pixel: wall; a box's
    /// silhouette against the wall; the box's face; a crease of the box;
    /// wall; a shadow edge; a texture step; a mirror; sky; the wall's edge
    /// against the sky; a pole one sub-sample wide (missed by a centre
    /// sample). Row 1: a floor seen at a grazing angle, whose depth grows by
    /// 20 % to 33 % per sub-sample but is one plane.
    #[test]
    fn classes_of_a_frame_built_to_contain_each() {
        let (pw, ph, s) = (11usize, 2usize, 4usize);
        let (w, h) = (pw * s, ph * s);
        let mut f = uniform(w as u32, h as u32);
        let n = w * h;
        let mut depth = vec![10.0f32; n];
        let mut normal = vec![Vec3::Z; n];
        let mut albedo = vec![Vec3::splat(0.5); n];
        let mut vis = vec![1u32; n];
        let mut mirror = vec![0.0f32; n];
        for y in 0..s {
            for i in 0..s {
                let at = |px: usize| y * w + px * s + i;
                // 1: the box's left edge over the wall.
                if i >= 2 {
                    depth[at(1)] = 5.0;
                }
                // 2: the box's front face.
                depth[at(2)] = 5.0;
                // 3: the box's corner: front face, then its side (continuous depth).
                depth[at(3)] = 5.0;
                if i >= 2 {
                    normal[at(3)] = Vec3::X;
                }
                // 5: a shadow edge.
                if i >= 2 {
                    vis[at(5)] = 0;
                }
                // 6: a texture step.
                albedo[at(6)] = Vec3::splat(if i >= 2 { 0.8 } else { 0.2 });
                // 7: a mirror.
                mirror[at(7)] = 0.9;
                // 8: sky.
                depth[at(8)] = f32::INFINITY;
                // 9: the wall's edge against the sky.
                if i >= 2 {
                    depth[at(9)] = f32::INFINITY;
                }
                // 10: a pole one sub-sample wide.
                if i == 1 {
                    depth[at(10)] = 3.0;
                }
            }
        }
        // Row 1: a grazing floor, inverse depth affine in the sub-sample row.
        for y in s..2 * s {
            for x in 0..w {
                depth[y * w + x] = 1.0 / (1.0 - 0.1 * y as f32);
                normal[y * w + x] = Vec3::Y;
            }
        }
        f.depth = Some(depth);
        f.normal = Some(normal);
        f.albedo = Some(albedo);
        f.light_visibility = Some(vis);
        f.mirror = Some(mirror);
        let m = classify(&f, s as u32).unwrap();
        // Near edge reads as flat here: this test is about the five classes
        // (every pixel of this small frame is within 2 of one).
        let of = |p: usize| -> Vec<Class> {
            let mut v: Vec<Class> = CLASSES.into_iter().filter(|c| m.mask(*c)[p]).collect();
            if m.near_edge[p] {
                v.push(Flat);
            }
            v
        };
        use Class::*;
        let expected = [
            vec![Flat],
            vec![Silhouette],
            vec![Flat],
            vec![Crease],
            vec![Flat],
            vec![Shadow],
            vec![Texture],
            vec![Reflection],
            vec![Flat],
            vec![Silhouette],
            vec![Silhouette],
        ];
        for (p, e) in expected.iter().enumerate() {
            assert_eq!(&of(p), e, "pixel {p} of row 0");
        }
        for p in pw..2 * pw {
            assert_eq!(of(p), vec![Flat], "pixel {} of the grazing floor", p - pw);
        }
        assert_eq!(m.count(Silhouette), 3);
        let near = m.near_edge.iter().filter(|&&b| b).count() as u64;
        assert_eq!(m.count(Flat) + near, 4 + pw as u64);
    }
}
