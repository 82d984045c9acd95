//! FXAA: the post-process antialiasing baseline most engines ship, against
//! which the geometry-aware methods of this crate are measured.
//!
//! This is Timothy Lottes' FXAA 3.11, the PC "quality" path (`FxaaPixelShader`
//! with `FXAA_PC == 1`), **preset 12** (the header's default): search steps
//! `FXAA_QUALITY__P0..P4 = 1.0, 1.5, 2.0, 4.0, 12.0` (5 steps,
//! `FXAA_QUALITY__PS = 5`) and the header's defaults `fxaaQualitySubpix =
//! 0.75`, `fxaaQualityEdgeThreshold = 0.166`, `fxaaQualityEdgeThresholdMin =
//! 0.0833` ([`FxaaParams::QUALITY`]). The arithmetic below follows the
//! shader's statements in its order, with its variable names (`lumaNS` →
//! `luma_ns`), so each line can be checked against the original.
//!
//! FXAA runs where an engine runs it: on the final LDR image, after
//! tone mapping (here: clamping to `[0, 1]`) and sRGB encoding, with its luma
//! computed from the encoded colour ("FXAA_GREEN_AS_LUMA 0": luma in alpha,
//! `dot(rgb, (0.299, 0.587, 0.114))` of the gamma-space colour).
//! [`fxaa_encode`] makes that input from a linear HDR pixel, [`fxaa_pixel`]
//! filters one pixel, [`fxaa_decode`] turns the result back into linear RGB
//! so that the frame keeps the format of every other method (and its 8-bit
//! sRGB view is FXAA's output).
//!
//! The hardware bilinear taps of the original (`FxaaTexTop` at half-pixel
//! positions) are written out as four clamped integer fetches, so the CPU and
//! the WGSL twin (`fxaa.wgsl`, [`WGSL`]) compute the same sums. Neither the
//! original's `FxaaTexOff` 3×3 taps nor its final tap ever leave the centre's
//! row or column by more than one pixel; the edge search walks at most
//! 1 + 1.5 + 2 + 4 + 12 = 20.5 pixels along the edge.
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::fxaa::{fxaa_encode, fxaa_pixel, FxaaParams};
//!
//! // A white pixel on black: a one-pixel feature FXAA's sub-pixel filter softens.
//! let fetch = |x: i32, y: i32| fxaa_encode(if (x, y) == (0, 0) { Vec3::ONE } else { Vec3::ZERO });
//! let out = fxaa_pixel(&fetch, 0, 0, &FxaaParams::QUALITY);
//! assert!(out.x < 1.0 && out.x > 0.0);
//! ```

use glam::{Vec3, Vec4};

/// The WGSL mirror of this module (same names; the filter reads pixels through
/// a hook `fxaa_fetch(x: i32, y: i32) -> vec4<f32>` the including shader
/// defines, as [`fxaa_pixel`]'s `fetch`). Needs [`crate::wgsl::PARAMS`].
pub const WGSL: &str = include_str!("fxaa.wgsl");

/// FXAA 3.11 quality preset 12's search steps, `FXAA_QUALITY__P0..P4`, in
/// pixels along the edge.
pub const SEARCH_STEPS: [f32; 5] = [1.0, 1.5, 2.0, 4.0, 12.0];

/// The luma weights FXAA 3.11 documents for its alpha channel (Rec. 601),
/// applied to the gamma-encoded colour.
pub const LUMA_WEIGHTS: Vec3 = Vec3::new(0.299, 0.587, 0.114);

/// FXAA's three quality knobs.
///
/// `#[repr(C)]`, 16 bytes, only `f32` fields: uploaded unchanged as a uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct FxaaParams {
    /// `fxaaQualitySubpix`: amount of sub-pixel aliasing removal, `[0, 1]`
    /// (1 = softest, 0 = off).
    pub subpix: f32,
    /// `fxaaQualityEdgeThreshold`: minimum local contrast, relative to the
    /// local maximum luma, for a pixel to be processed (0.333 too little,
    /// 0.063 overkill).
    pub edge_threshold: f32,
    /// `fxaaQualityEdgeThresholdMin`: absolute contrast below which dark
    /// pixels are left alone.
    pub edge_threshold_min: f32,
    /// Padding to 16 bytes.
    pub _pad: f32,
}

impl FxaaParams {
    /// FXAA 3.11's defaults: subpix 0.75, edge threshold 0.166, edge
    /// threshold min 0.0833.
    pub const QUALITY: Self = Self {
        subpix: 0.75,
        edge_threshold: 0.166,
        edge_threshold_min: 0.0833,
        _pad: 0.0,
    };
}

impl Default for FxaaParams {
    fn default() -> Self {
        Self::QUALITY
    }
}

/// `[0, 1]` with NaN as 0 (infinities clamp).
#[inline]
fn clean01(x: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(0.0, 1.0)
    }
}

/// The sRGB transfer function of one channel (IEC 61966-2-1), for
/// `c ∈ [0, 1]`; NaN reads as 0, values outside `[0, 1]` are clamped first
/// (the display's tone mapping).
#[inline]
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = clean01(c);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * libm::powf(c, 1.0 / 2.4) - 0.055
    }
}

/// The inverse of [`linear_to_srgb`] on `[0, 1]`; NaN reads as 0, values
/// outside `[0, 1]` are clamped first.
#[inline]
pub fn srgb_to_linear(c: f32) -> f32 {
    let c = clean01(c);
    if c <= 0.040_45 {
        c / 12.92
    } else {
        libm::powf((c + 0.055) / 1.055, 2.4)
    }
}

/// `x ∈ [0, 1]` rounded to the nearest of the 256 levels of an 8-bit channel.
#[inline]
pub fn quantize8(x: f32) -> f32 {
    libm::floorf(clean01(x) * 255.0 + 0.5) * (1.0 / 255.0)
}

/// FXAA's input pixel from a linear HDR colour, as an engine stores it for
/// FXAA: an RGBA8 texel holding the displayed colour (clamped to `[0, 1]`,
/// sRGB-encoded) in `xyz` and its luma ([`LUMA_WEIGHTS`] of the stored
/// colour) in `w`, each rounded to 8 bits ([`quantize8`]). Total: NaN
/// channels read as 0, ±∞ clamp; the result is always in `[0, 1]⁴`.
///
/// The 8-bit storage is also what makes FXAA reproducible across backends:
/// its decisions have exact ties (for a centre darker or brighter than all
/// of its eight neighbours, `edgeHorz == edgeVert` algebraically), and on
/// unrounded input a one-ulp difference in `pow` or in the luma's dot product
/// breaks them differently on a GPU. On 8-bit levels both sides compute the
/// same sums in the same order and break them alike.
#[inline]
pub fn fxaa_encode(linear: Vec3) -> Vec4 {
    let c = Vec3::new(
        quantize8(linear_to_srgb(linear.x)),
        quantize8(linear_to_srgb(linear.y)),
        quantize8(linear_to_srgb(linear.z)),
    );
    let luma = c.x * LUMA_WEIGHTS.x + c.y * LUMA_WEIGHTS.y + c.z * LUMA_WEIGHTS.z;
    c.extend(quantize8(luma))
}

/// The fetch [`fxaa_pixel`] needs over a row-major `width × height` image of
/// pixels already encoded by [`fxaa_encode`]: coordinates outside the image
/// are clamped to its edge (the original's clamp-to-edge sampler; in WGSL
/// the including shader's `fxaa_fetch` hook does the same on its texture).
///
/// Domain: `encoded` holds `width·height` pixels, both sizes ≥ 1. A zero size
/// reads as 1, and a pixel past the end of a shorter slice reads as zero
/// (black), so no input panics.
#[inline]
pub fn edge_clamped(encoded: &[Vec4], width: u32, height: u32) -> impl Fn(i32, i32) -> Vec4 + '_ {
    let (w, h) = (width.max(1) as i32, height.max(1) as i32);
    move |x: i32, y: i32| {
        let (x, y) = (x.clamp(0, w - 1) as usize, y.clamp(0, h - 1) as usize);
        encoded
            .get(y * w as usize + x)
            .copied()
            .unwrap_or(Vec4::ZERO)
    }
}

/// A filtered sRGB colour back to linear RGB ([`srgb_to_linear`] per channel).
#[inline]
pub fn fxaa_decode(srgb: Vec3) -> Vec3 {
    Vec3::new(
        srgb_to_linear(srgb.x),
        srgb_to_linear(srgb.y),
        srgb_to_linear(srgb.z),
    )
}

/// One input pixel through `fetch`, cleaned to `[0, 1]⁴` (NaN as 0), so a
/// caller's garbage never reaches the arithmetic.
#[inline]
fn tap(fetch: &impl Fn(i32, i32) -> Vec4, x: i32, y: i32) -> Vec4 {
    let v = fetch(x, y);
    Vec4::new(clean01(v.x), clean01(v.y), clean01(v.z), clean01(v.w))
}

/// Bilinear interpolation at `(px, py)` in pixel units (pixel `(i, j)`'s
/// centre at `(i, j)`): the original's `FxaaTexTop` with a linear sampler.
#[inline]
fn bilinear(fetch: &impl Fn(i32, i32) -> Vec4, px: f32, py: f32) -> Vec4 {
    let (fx0, fy0) = (libm::floorf(px), libm::floorf(py));
    let (fx, fy) = (px - fx0, py - fy0);
    let (x0, y0) = (fx0 as i32, fy0 as i32);
    let top = tap(fetch, x0, y0) * (1.0 - fx) + tap(fetch, x0 + 1, y0) * fx;
    let bottom = tap(fetch, x0, y0 + 1) * (1.0 - fx) + tap(fetch, x0 + 1, y0 + 1) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// FXAA 3.11 quality (preset 12) on pixel `(x, y)`: the filtered colour, in
/// the space of the input's `xyz` (sRGB-encoded when the input comes from
/// [`fxaa_encode`]).
///
/// `fetch(i, j)` returns the input pixel `(i, j)` as [`fxaa_encode`] makes it
/// (colour in `xyz`, luma in `w`) and must clamp coordinates outside the image
/// to its edge (the original's clamp-to-edge sampler): the filter reads up to
/// 1 pixel across and 21.5 pixels along an edge from `(x, y)`.
///
/// Domain: fetched values in `[0, 1]`; anything else is cleaned first (NaN as
/// 0, clamped), so the output is always finite and in `[0, 1]³`. The output is
/// the centre pixel unchanged (early exit) or a linear blend of the centre and
/// one of its four direct neighbours (the original's final `FxaaTexTop` moves
/// at most one pixel along one axis); the blend factor is clamped to `[0, 1]`,
/// which is a no-op for finite parameters in their documented ranges and keeps
/// any parameter values (even NaN) from producing garbage. A flat
/// neighbourhood (zero contrast) always exits early, whatever the thresholds.
pub fn fxaa_pixel(fetch: &impl Fn(i32, i32) -> Vec4, x: i32, y: i32, p: &FxaaParams) -> Vec3 {
    // The shader's steps, in its order: the early exit on low contrast, the
    // edge's orientation, the sub-pixel blend, the side of the edge, the
    // search for the edge's ends along it, and the offset across it.
    let pos_m = (x as f32, y as f32);
    let rgby_m = tap(fetch, x, y);
    let Some(contrast) = local_contrast(fetch, x, y, rgby_m.w, p) else {
        return rgby_m.truncate();
    };
    let l = Lumas::around(fetch, x, y, &contrast);
    let horz_span = l.horizontal_span();
    let subpix_h = subpixel_blend(l.subpix_a(), l.m, contrast.range, p);
    let side = EdgeSide::new(&l, horz_span);
    let ends = search_edge_ends(fetch, pos_m, horz_span, &side);
    let pixel_offset_good = ends.pixel_offset(pos_m, horz_span, &side);

    // The final tap, by the larger of the two offsets across the edge. The
    // clamp is ours (see the doc comment): a no-op in the domain.
    let pixel_offset_subpix = clean01(pixel_offset_good.max(subpix_h));
    let (mut px, mut py) = pos_m;
    if !horz_span {
        px += pixel_offset_subpix * side.length_sign;
    } else {
        py += pixel_offset_subpix * side.length_sign;
    }
    bilinear(fetch, px, py).truncate()
}

/// The centre and its four direct neighbours' lumas when their contrast
/// passes FXAA 3.11's early exit.
struct LocalContrast {
    luma_m: f32,
    luma_n: f32,
    luma_s: f32,
    luma_e: f32,
    luma_w: f32,
    /// `range`: the largest minus the smallest of the five, `> 0`.
    range: f32,
}

/// FXAA 3.11's early exit: the local contrast of the centre (luma `luma_m`)
/// and its four direct neighbours, or `None` where it is below
/// `max(edge_threshold_min, edge_threshold · the largest luma)`, or zero.
#[inline(always)]
fn local_contrast(
    fetch: &impl Fn(i32, i32) -> Vec4,
    x: i32,
    y: i32,
    luma_m: f32,
    p: &FxaaParams,
) -> Option<LocalContrast> {
    let luma_s = tap(fetch, x, y + 1).w;
    let luma_e = tap(fetch, x + 1, y).w;
    let luma_n = tap(fetch, x, y - 1).w;
    let luma_w = tap(fetch, x - 1, y).w;

    let max_sm = luma_s.max(luma_m);
    let min_sm = luma_s.min(luma_m);
    let max_esm = luma_e.max(max_sm);
    let min_esm = luma_e.min(min_sm);
    let max_wn = luma_n.max(luma_w);
    let min_wn = luma_n.min(luma_w);
    let range_max = max_wn.max(max_esm);
    let range_min = min_wn.min(min_esm);
    let range_max_scaled = range_max * p.edge_threshold;
    let range = range_max - range_min;
    let range_max_clamped = p.edge_threshold_min.max(range_max_scaled);
    // `range < rangeMaxClamped` in the original; a zero range also exits (its
    // reciprocal below would be infinite when the thresholds are 0).
    if !(range >= range_max_clamped) || !(range > 0.0) {
        return None;
    }
    Some(LocalContrast {
        luma_m,
        luma_n,
        luma_s,
        luma_e,
        luma_w,
        range,
    })
}

/// The lumas of the centre's 3×3 neighbourhood (FXAA 3.11's `lumaM`,
/// `lumaN`, …, `lumaSE`), with the pair sums that both the edge test
/// ([`Lumas::horizontal_span`]) and the sub-pixel low-pass
/// ([`Lumas::subpix_a`]) read, each computed once.
struct Lumas {
    m: f32,
    n: f32,
    s: f32,
    e: f32,
    w: f32,
    /// `lumaNS`, `lumaWE`, `lumaNESE`, `lumaNWNE`, `lumaNWSW`, `lumaSWSE`.
    ns: f32,
    we: f32,
    nese: f32,
    nwne: f32,
    nwsw: f32,
    swse: f32,
}

impl Lumas {
    /// The four corners fetched (`lumaNW`, `lumaSE`, `lumaNE`, `lumaSW`, in
    /// the original's order) beside the contrast's five lumas, and the pair
    /// sums.
    #[inline(always)]
    fn around(fetch: &impl Fn(i32, i32) -> Vec4, x: i32, y: i32, c: &LocalContrast) -> Self {
        let luma_nw = tap(fetch, x - 1, y - 1).w;
        let luma_se = tap(fetch, x + 1, y + 1).w;
        let luma_ne = tap(fetch, x + 1, y - 1).w;
        let luma_sw = tap(fetch, x - 1, y + 1).w;
        Self {
            m: c.luma_m,
            n: c.luma_n,
            s: c.luma_s,
            e: c.luma_e,
            w: c.luma_w,
            ns: c.luma_n + c.luma_s,
            we: c.luma_w + c.luma_e,
            nese: luma_ne + luma_se,
            nwne: luma_nw + luma_ne,
            nwsw: luma_nw + luma_sw,
            swse: luma_sw + luma_se,
        }
    }

    /// FXAA 3.11's edge orientation (`horzSpan`): whether the luma changes
    /// more across rows than across columns (second differences of the 3×3
    /// neighbourhood, the centre row and column weighted twice), so that the
    /// edge runs horizontally.
    #[inline(always)]
    fn horizontal_span(&self) -> bool {
        let edge_horz1 = -2.0 * self.m + self.ns;
        let edge_vert1 = -2.0 * self.m + self.we;
        let edge_horz2 = -2.0 * self.e + self.nese;
        let edge_vert2 = -2.0 * self.n + self.nwne;
        let edge_horz4 = edge_horz1.abs() * 2.0 + edge_horz2.abs();
        let edge_vert4 = edge_vert1.abs() * 2.0 + edge_vert2.abs();
        let edge_horz3 = -2.0 * self.w + self.nwsw;
        let edge_vert3 = -2.0 * self.s + self.swse;
        let edge_horz = edge_horz3.abs() + edge_horz4;
        let edge_vert = edge_vert3.abs() + edge_vert4;
        edge_horz >= edge_vert
    }

    /// `subpixA`: twelve times the low-pass luma of the neighbourhood (the
    /// direct neighbours weighted 2, the corners 1).
    #[inline(always)]
    fn subpix_a(&self) -> f32 {
        let subpix_nswe = self.ns + self.we;
        let subpix_nwswnese = self.nwsw + self.nese;
        subpix_nswe * 2.0 + subpix_nwswnese
    }
}

/// FXAA 3.11's sub-pixel aliasing removal (`subpixB` … `subpixH`): how far
/// the centre's luma lies from the neighbourhood's low-pass (`subpix_a`
/// over 12), relative to the local contrast `range`, smoothstepped, squared
/// and scaled by `fxaaQualitySubpix`: the blend toward the neighbour that a
/// one-pixel feature gets whatever the edge search finds.
#[inline(always)]
fn subpixel_blend(subpix_a: f32, luma_m: f32, range: f32, p: &FxaaParams) -> f32 {
    let subpix_rcp_range = 1.0 / range;
    let subpix_b = subpix_a * (1.0 / 12.0) - luma_m;
    let subpix_c = clean01((subpix_b).abs() * subpix_rcp_range);
    let subpix_d = -2.0 * subpix_c + 3.0;
    let subpix_e = subpix_c * subpix_c;
    let subpix_f = subpix_d * subpix_e;
    let subpix_g = subpix_f * subpix_f;
    subpix_g * p.subpix
}

/// The side of the edge FXAA 3.11 blends toward: of the two neighbours
/// across the edge, the one of the steeper luma gradient (`pairN`).
struct EdgeSide {
    /// `lengthSign`: one pixel toward that neighbour, across the edge.
    length_sign: f32,
    /// `lumaNN`: the centre's luma plus that neighbour's (twice their mean,
    /// the luma on the edge).
    luma_nn: f32,
    /// `gradientScaled`: a quarter of the steeper gradient, the change in
    /// luma that ends the search along the edge.
    gradient_scaled: f32,
    /// `lumaMLTZero`: the centre is darker than the edge's mean luma.
    luma_m_lt_zero: bool,
}

impl EdgeSide {
    #[inline(always)]
    fn new(l: &Lumas, horz_span: bool) -> Self {
        let luma_m = l.m;
        // The original overwrites lumaN and lumaS here; new names keep every
        // value single-assignment (as in the WGSL twin).
        let (luma_n_span, luma_s_span) = if horz_span { (l.n, l.s) } else { (l.w, l.e) };
        // fxaaQualityRcpFrame.x, in pixels (if horzSpan, lengthSign =
        // fxaaQualityRcpFrame.y: also 1 pixel).
        let mut length_sign = 1.0f32;
        let gradient_n = luma_n_span - luma_m;
        let gradient_s = luma_s_span - luma_m;
        let mut luma_nn = luma_n_span + luma_m;
        let luma_ss = luma_s_span + luma_m;
        let pair_n = gradient_n.abs() >= gradient_s.abs();
        let gradient = gradient_n.abs().max(gradient_s.abs());
        if pair_n {
            length_sign = -length_sign;
        }
        if !pair_n {
            luma_nn = luma_ss;
        }
        let gradient_scaled = gradient * 1.0 / 4.0;
        let luma_mm = luma_m - luma_nn * 0.5;
        Self {
            length_sign,
            luma_nn,
            gradient_scaled,
            luma_m_lt_zero: luma_mm < 0.0,
        }
    }
}

/// Where FXAA 3.11's search along the edge stopped on each side (`posN`,
/// `posP`) and the luma found there, relative to the edge's
/// (`lumaEndN`, `lumaEndP`).
struct EdgeEnds {
    pos_n: (f32, f32),
    pos_p: (f32, f32),
    luma_end_n: f32,
    luma_end_p: f32,
}

/// FXAA 3.11's search for the two ends of the edge: from half a pixel
/// across the edge (`posB`, toward the [`EdgeSide`]), it walks both ways
/// along it by [`SEARCH_STEPS`] (preset 12), bilinear taps straddling the
/// edge, until the luma departs from the edge's by the scaled gradient.
#[inline(always)]
fn search_edge_ends(
    fetch: &impl Fn(i32, i32) -> Vec4,
    pos_m: (f32, f32),
    horz_span: bool,
    side: &EdgeSide,
) -> EdgeEnds {
    let (pos_m_x, pos_m_y) = pos_m;
    let luma_nn = side.luma_nn;
    let gradient_scaled = side.gradient_scaled;
    // Along the edge: the unit step `off_np`; `pos_b` is half a pixel across,
    // between the centre and the neighbour of the steeper gradient.
    let (off_x, off_y) = if horz_span { (1.0, 0.0) } else { (0.0, 1.0) };
    let (mut pos_b_x, mut pos_b_y) = (pos_m_x, pos_m_y);
    if !horz_span {
        pos_b_x += side.length_sign * 0.5;
    } else {
        pos_b_y += side.length_sign * 0.5;
    }

    let mut pos_n_x = pos_b_x - off_x * SEARCH_STEPS[0];
    let mut pos_n_y = pos_b_y - off_y * SEARCH_STEPS[0];
    let mut pos_p_x = pos_b_x + off_x * SEARCH_STEPS[0];
    let mut pos_p_y = pos_b_y + off_y * SEARCH_STEPS[0];
    let mut luma_end_n = bilinear(fetch, pos_n_x, pos_n_y).w;
    let mut luma_end_p = bilinear(fetch, pos_p_x, pos_p_y).w;

    luma_end_n -= luma_nn * 0.5;
    luma_end_p -= luma_nn * 0.5;
    let mut done_n = luma_end_n.abs() >= gradient_scaled;
    let mut done_p = luma_end_p.abs() >= gradient_scaled;
    if !done_n {
        pos_n_x -= off_x * SEARCH_STEPS[1];
        pos_n_y -= off_y * SEARCH_STEPS[1];
    }
    if !done_p {
        pos_p_x += off_x * SEARCH_STEPS[1];
        pos_p_y += off_y * SEARCH_STEPS[1];
    }
    // The original's nested `if (doneNP)` blocks for P2..P(PS−1), as a loop
    // bounded by the preset's step count.
    for &step in &SEARCH_STEPS[2..] {
        if done_n && done_p {
            break;
        }
        if !done_n {
            luma_end_n = bilinear(fetch, pos_n_x, pos_n_y).w - luma_nn * 0.5;
        }
        if !done_p {
            luma_end_p = bilinear(fetch, pos_p_x, pos_p_y).w - luma_nn * 0.5;
        }
        done_n = luma_end_n.abs() >= gradient_scaled;
        done_p = luma_end_p.abs() >= gradient_scaled;
        if !done_n {
            pos_n_x -= off_x * step;
            pos_n_y -= off_y * step;
        }
        if !done_p {
            pos_p_x += off_x * step;
            pos_p_y += off_y * step;
        }
    }
    EdgeEnds {
        pos_n: (pos_n_x, pos_n_y),
        pos_p: (pos_p_x, pos_p_y),
        luma_end_n,
        luma_end_p,
    }
}

impl EdgeEnds {
    /// FXAA 3.11's offset across the edge (`pixelOffsetGood`): from the
    /// nearer end, `0.5 − distance / span length`, the coverage of the
    /// centre by the polygon the edge bounds, where the luma at that end
    /// changes toward the centre's side (`goodSpan`); otherwise 0.
    #[inline(always)]
    fn pixel_offset(&self, pos_m: (f32, f32), horz_span: bool, side: &EdgeSide) -> f32 {
        let (pos_m_x, pos_m_y) = pos_m;
        let (dst_n, dst_p) = if horz_span {
            (pos_m_x - self.pos_n.0, self.pos_p.0 - pos_m_x)
        } else {
            (pos_m_y - self.pos_n.1, self.pos_p.1 - pos_m_y)
        };
        let good_span_n = (self.luma_end_n < 0.0) != side.luma_m_lt_zero;
        let span_length = dst_p + dst_n;
        let good_span_p = (self.luma_end_p < 0.0) != side.luma_m_lt_zero;
        let span_length_rcp = 1.0 / span_length;

        let direction_n = dst_n < dst_p;
        let dst = dst_n.min(dst_p);
        let good_span = if direction_n {
            good_span_n
        } else {
            good_span_p
        };
        let pixel_offset = dst * -span_length_rcp + 0.5;
        if good_span {
            pixel_offset
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An image as a clamped fetch over encoded pixels.
    fn image(w: i32, h: i32, f: impl Fn(i32, i32) -> Vec3) -> impl Fn(i32, i32) -> Vec4 {
        move |x, y| fxaa_encode(f(x.clamp(0, w - 1), y.clamp(0, h - 1)))
    }

    #[test]
    fn flat_images_are_unchanged() {
        for c in [
            Vec3::ZERO,
            Vec3::splat(0.3),
            Vec3::new(0.9, 0.1, 0.5),
            Vec3::ONE,
        ] {
            let f = image(8, 8, |_, _| c);
            for (x, y) in [(0, 0), (3, 4), (7, 7)] {
                assert_eq!(
                    fxaa_pixel(&f, x, y, &FxaaParams::QUALITY),
                    f(x, y).truncate()
                );
            }
        }
    }

    #[test]
    fn low_contrast_is_left_alone() {
        // A luma step below edgeThresholdMin (0.0833) is not an edge.
        let f = image(8, 8, |x, _| Vec3::splat(if x < 4 { 0.0 } else { 0.004 }));
        for x in 0..8 {
            assert_eq!(
                fxaa_pixel(&f, x, 3, &FxaaParams::QUALITY),
                f(x, 3).truncate()
            );
        }
    }

    #[test]
    fn encode_decode_round_trip_in_range() {
        for i in 0..=100 {
            let c = i as f32 / 100.0;
            let back = fxaa_decode(fxaa_encode(Vec3::splat(c)).truncate());
            assert!((back.x - c).abs() < 5e-3, "{c} -> {back}");
        }
        let e = fxaa_encode(Vec3::new(f32::NAN, f32::INFINITY, -1.0));
        assert!(
            (e - Vec4::new(0.0, 1.0, 0.0, 150.0 / 255.0))
                .abs()
                .max_element()
                < 1e-6,
            "{e}"
        );
    }
}
