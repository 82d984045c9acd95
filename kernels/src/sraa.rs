//! Subpixel Reconstruction Antialiasing for ray tracing (Chiu et al., §3).
//!
//! One shaded sample and four geometric subsamples per pixel. The colour of each
//! geometric subsample is reconstructed from the shaded samples of the
//! neighbouring pixels with bilateral weights ([`bilateral_weight`], eq. 1),
//! gated by shadow state ([`shadow_gated_weight`], eq. 2), and the four
//! reconstructed subsamples are filtered into the pixel ([`resolve_pixel`]).
//!
//! The API takes any geometry: a backend calls it once on primary-hit geometry
//! and, separately, on secondary-hit geometry (§3.3), so reflections are
//! reconstructed from the geometry they show.

use glam::{Vec2, Vec3};

use crate::sum::WeightedSum;

mod resolver;
pub use resolver::{
    gaussian_sum_lanes, gaussian_sum_wide, weights_product_lanes, weights_product_wide, FrameFlags,
    GeometryLanes, GeometryWide, LayerFlags, Resolver, ShadedFrame, ShadedGroup, Subsamples,
    WIDE_LANES,
};

/// The WGSL mirror of this module's functions (same names; functions only, no
/// bindings). Concatenate after [`crate::wgsl::PARAMS`]. Its header lists the
/// differences in rounding (GPU `exp`, compensated f32 sums instead of f64).
pub const WGSL: &str = include_str!("sraa.wgsl");

/// The WGSL twin of [`reconstruct_layers`] (and, with the albedo gate, of
/// [`reconstruct_layers_material`]) over [`neighbourhood`]: the SRAA
/// reconstruction loop, eq. 1 with the spatial term ([`reconstruction_weight`])
/// gated per light by eq. 2 (§3.1–3.2), on the primary or, for mirrors, the
/// secondary hits' geometry (§3.3). `subcone_sraa_reconstruct_run(tgt,
/// target_shadow, ta, secondary, first, x, y, k) -> vec3<f32>` reconstructs
/// subsample `k` of pixel `(x, y)` from one group of layers (`first ..
/// first + SRAA_GATES`: layer 0 ungated, layer `1 + l` gated by light `l`'s
/// shadow bit) and returns the sum of the group's layers, as [`Resolver`]
/// sums a subsample's layers. It drives [`WGSL`]'s
/// `subcone_reconstruct_layers_begin/add/end` in the order of the Rust loop.
/// Every GPU resolve runs it (`subcone_passes::SraaPass` and the wgpu
/// backend's SRAA-RT resolve); `tests/conformance_kernels.rs` holds it to
/// [`reconstruct_layers`] and [`Resolver`].
///
/// Concatenate after [`crate::wgsl::PARAMS`], [`WGSL`] and the hooks the
/// including shader defines (the source's header lists them):
///
/// - `const SRAA_GATES: u32`: layers per group, `1 +` gated lights (≤ 9);
/// - `const SRAA_MATERIAL: bool`: the albedo gate on the primary group;
/// - `fn sraa_params() -> subcone_SraaParams`, `fn sraa_size() -> vec2<u32>`
///   (the image's width and height), `fn sraa_albedo_tolerance() -> f32`;
/// - `fn sraa_shaded_geometry(x, y, secondary) -> subcone_Geometry`,
///   `fn sraa_shaded_shadow(x, y, secondary) -> u32`,
///   `fn sraa_shaded_albedo(x, y) -> vec3<f32>`,
///   `fn sraa_shaded_value(x, y, layer) -> vec3<f32>`: pixel `(x, y)`'s
///   shaded sample (its geometry, shadow bits, albedo and colour layers).
pub const RECONSTRUCT_WGSL: &str = include_str!("sraa/reconstruct.wgsl");

/// The four subpixel offsets of the 4x rotated grid on a 4×4 grid (§3.1, Fig. 2),
/// relative to the pixel's centre, in pixels.
///
/// Cell `(col, row)` of the 4×4 grid holds a sample for `(1,0)`, `(3,1)`,
/// `(0,2)`, `(2,3)`: every row and every column of the grid holds exactly one
/// sample, which is what makes a rotated grid resolve near-horizontal and
/// near-vertical edges at four levels each.
pub const SUBPIXEL_OFFSETS: [Vec2; 4] = [
    Vec2::new(-0.125, -0.375),
    Vec2::new(0.375, -0.125),
    Vec2::new(-0.375, 0.125),
    Vec2::new(0.125, 0.375),
];

/// Which of [`SUBPIXEL_OFFSETS`] is also the shaded sample.
///
/// All four lie at the same distance from the pixel centre, so any one serves;
/// a fixed index makes the shaded samples a regular lattice across the image,
/// which the reconstruction's fixed-radius neighbourhood relies on.
pub const SHADED_SUBSAMPLE: usize = 0;

/// The `sub` of [`neighbourhood`] that means the shaded sample itself,
/// wherever [`SraaParams::shaded_offset`] puts it.
pub const SHADED_SAMPLE: usize = 4;

/// Which functional form the bilateral weight takes.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WeightForm {
    /// Eq. 1 of the paper: `G(σz·Δz) · G(σn·(1 − sat(nj·ni)))`, `G(x) = exp(−x²)`.
    Product = 0,
    /// The original SRAA (Chajdas et al. 2011): `exp(−s · max(1 − sat(n·n), k·Δz))`,
    /// one exponential of the larger of the two dissimilarities.
    ChajdasMax = 1,
}

/// How the depth difference `zj − zi` is measured.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthMetric {
    /// `|zj − zi| / mean(|zi|, |zj|)`: scale-free, so σz = 10 means "a 10 %
    /// depth step costs `e⁻¹`" whether the scene is modelled in metres or in
    /// millimetres. Symmetric in `i` and `j` (the mean, not `zi`, is the scale).
    /// This is the default.
    Relative = 0,
    /// `|zj − zi|` in scene units, the paper's literal eq. 1. σz then carries a
    /// unit, and the paper's σz = 10 is only right for the scale it was tuned on.
    Absolute = 1,
}

/// Parameters of the bilateral weights (eq. 1 and eq. 2) and the reconstruction.
///
/// `#[repr(C)]`, 16 bytes, only `f32`/`u32` fields: it is uploaded unchanged as
/// a uniform by GPU backends.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct SraaParams {
    /// σz of eq. 1; for [`WeightForm::ChajdasMax`], the depth factor `k`.
    pub sigma_z: f32,
    /// σn of eq. 1 (for [`WeightForm::ChajdasMax`]: unused).
    pub sigma_n: f32,
    /// `s` of the Chajdas form; ignored by [`WeightForm::Product`].
    pub scale: f32,
    /// Bits 0..8: [`WeightForm`]; bits 8..16: [`DepthMetric`]; bits 16..32: the
    /// reconstruction radius in pixels (1 = the 3×3 neighbourhood).
    pub packed: u32,
    /// σs, the spatial falloff in pixels: a neighbour's weight is multiplied
    /// by `exp(−d²/σs²)`, `d` the screen distance from the target subsample
    /// to the neighbour's shaded sample ([`reconstruction_weight`]). `0` (or
    /// negative, or NaN) turns the term off, as in eq. 1.
    pub sigma_s: f32,
    /// Where each pixel's shaded sample lies: a [`ShadedPosition`] code.
    pub shading: u32,
    /// Padding to 32 bytes (uniform blocks are laid out in 16-byte rows).
    pub _pad: [u32; 2],
}

/// Where a pixel's one shaded sample lies.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShadedPosition {
    /// On geometric subsample [`SHADED_SUBSAMPLE`] of the rotated grid, as
    /// §3.1 and Fig. 2 put it ("one of those geometric samples is also a
    /// shaded sample"): the subsample's geometry is the shaded ray's.
    Subsample = 0,
    /// At the pixel centre, the NoAA sample: every one of the four geometric
    /// subsamples is traced (or rasterised) on its own. Beyond the paper: a
    /// shaded lattice offset from the pixel centres by a subsample offset
    /// shifts the whole reconstructed image by that offset wherever the
    /// geometry agrees (flat, textured surfaces: about 0.4 px), which the
    /// reference does not; at the centre, a flat pixel reconstructs around
    /// NoAA's own sample. Costs one geometry ray more per pixel in SRAA-RT.
    Centre = 1,
}

impl SraaParams {
    /// The paper's values (§3.1): σz = 10, σn = 0.25, eq. 1, a 3×3 neighbourhood,
    /// with the scale-free depth metric.
    ///
    /// With σn = 0.25 the normal term is nearly inert: perpendicular normals still
    /// weigh `exp(−0.0625) ≈ 0.94`, and opposite normals the same (sat clamps the
    /// dot product at 0). The preset is kept as published; tuned presets must be
    /// measured against a reference before they become defaults.
    pub const PAPER: Self = Self::new(
        10.0,
        0.25,
        1.0,
        WeightForm::Product,
        DepthMetric::Relative,
        1,
    );

    /// The default: eq. 1 (σz = 10, the paper's) with a normal term that
    /// separates creases (σn = 1: perpendicular normals weigh `e⁻¹`, where
    /// the paper's 0.25 leaves them 0.94), a spatial term σs = 0.4 px (a
    /// neighbour one pixel away weighs `e⁻⁶·²⁵` against one at the subsample;
    /// Fig. 2's caption weighs samples "by their distance", eq. 1 has no such
    /// term) and the shaded sample at the pixel centre
    /// ([`ShadedPosition::Centre`]).
    ///
    /// Tuned on the `cornell` and `checker` scenes only, by the report's
    /// edge-class FLIP at 96×64 and 512×512 (σs = 0.5 blurred checker's
    /// texture enough to lose on its flat pixels at 512²; 0.35 and below
    /// give back silhouette and crease quality on `cornell`); judged on
    /// the others (the report's verdicts). Without
    /// the spatial term the 3×3 neighbourhood is a box filter over every
    /// neighbour of like geometry, which blurs highlights and textures that
    /// NoAA keeps sharp.
    pub const TUNED: Self = Self::new(
        10.0,
        1.0,
        1.0,
        WeightForm::Product,
        DepthMetric::Relative,
        1,
    )
    .with_spatial(0.4)
    .with_shaded_position(ShadedPosition::Centre);

    /// The original SRAA form for comparison: `exp(−s·max(1 − n·n, k·Δz))` with
    /// `s = 10`, `k = 1` on the relative depth metric (so a 10 % depth step and a
    /// 0.1 drop of the normal cosine both cost `e⁻¹`, as in [`Self::PAPER`]'s depth term).
    /// These constants are ours, not Chajdas et al.'s, chosen to match eq. 1's depth falloff.
    pub const CHAJDAS: Self = Self::new(
        1.0,
        0.0,
        10.0,
        WeightForm::ChajdasMax,
        DepthMetric::Relative,
        1,
    );

    /// Build a parameter block.
    pub const fn new(
        sigma_z: f32,
        sigma_n: f32,
        scale: f32,
        form: WeightForm,
        depth: DepthMetric,
        radius: u16,
    ) -> Self {
        Self {
            sigma_z,
            sigma_n,
            scale,
            packed: (form as u32) | ((depth as u32) << 8) | ((radius as u32) << 16),
            sigma_s: 0.0,
            shading: ShadedPosition::Subsample as u32,
            _pad: [0; 2],
        }
    }

    /// The same parameters with the spatial falloff σs (pixels; 0 = none).
    pub const fn with_spatial(self, sigma_s: f32) -> Self {
        Self { sigma_s, ..self }
    }

    /// The same parameters with the shaded sample at `position`.
    pub const fn with_shaded_position(self, position: ShadedPosition) -> Self {
        Self {
            shading: position as u32,
            ..self
        }
    }

    /// Where the shaded sample lies. Unknown codes read as
    /// [`ShadedPosition::Subsample`] (the paper).
    pub const fn shaded_position(&self) -> ShadedPosition {
        match self.shading {
            1 => ShadedPosition::Centre,
            _ => ShadedPosition::Subsample,
        }
    }

    /// The shaded sample's offset from the pixel centre, in pixels.
    pub const fn shaded_offset(&self) -> Vec2 {
        match self.shaded_position() {
            ShadedPosition::Subsample => SUBPIXEL_OFFSETS[SHADED_SUBSAMPLE],
            ShadedPosition::Centre => Vec2::ZERO,
        }
    }

    /// The geometric subsample that is also the shaded sample (its geometry
    /// is the shaded ray's), if any: [`SHADED_SUBSAMPLE`] in the paper's
    /// layout, none with the shaded sample at the centre.
    pub const fn shaded_subsample(&self) -> Option<usize> {
        match self.shaded_position() {
            ShadedPosition::Subsample => Some(SHADED_SUBSAMPLE),
            ShadedPosition::Centre => None,
        }
    }

    /// The weight form. Unknown codes read as [`WeightForm::Product`].
    pub const fn form(&self) -> WeightForm {
        match self.packed & 0xff {
            1 => WeightForm::ChajdasMax,
            _ => WeightForm::Product,
        }
    }

    /// The depth metric. Unknown codes read as [`DepthMetric::Relative`].
    pub const fn depth_metric(&self) -> DepthMetric {
        match (self.packed >> 8) & 0xff {
            1 => DepthMetric::Absolute,
            _ => DepthMetric::Relative,
        }
    }

    /// Reconstruction radius in pixels: the neighbourhood is `(2r+1)²` pixels.
    /// The paper's "fixed radius" is 1 (3×3, as in Chajdas' kernel).
    pub const fn radius(&self) -> u32 {
        self.packed >> 16
    }

    /// The same parameters with another weight form.
    pub const fn with_form(self, form: WeightForm) -> Self {
        Self {
            packed: (self.packed & !0xff) | form as u32,
            ..self
        }
    }

    /// The same parameters with another depth metric.
    pub const fn with_depth_metric(self, depth: DepthMetric) -> Self {
        Self {
            packed: (self.packed & !0xff00) | ((depth as u32) << 8),
            ..self
        }
    }

    /// The same parameters with another neighbourhood radius.
    pub const fn with_radius(self, radius: u16) -> Self {
        Self {
            packed: (self.packed & 0xffff) | ((radius as u32) << 16),
            ..self
        }
    }
}

impl Default for SraaParams {
    /// [`SraaParams::TUNED`].
    fn default() -> Self {
        Self::TUNED
    }
}

/// Geometry of one sample: a unit normal and a view depth.
///
/// `#[repr(C)]`, 16 bytes: `normal` at offset 0 and `depth` at offset 12. A WGSL
/// `struct { normal: vec3<f32>, depth: f32 }` has the same offsets, because WGSL
/// packs a scalar into the 4-byte tail of a 16-byte-aligned `vec3`; keep the
/// scalar after the vector or the layouts drift apart.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Geometry {
    /// Unit surface normal. Any length is accepted (the dot product is saturated),
    /// NaN excludes the sample.
    pub normal: Vec3,
    /// Distance along the view axis, `≥ 0`. `+∞` marks a miss (background):
    /// two misses match each other and nothing else.
    pub depth: f32,
}

impl Geometry {
    /// A geometry sample.
    pub const fn new(normal: Vec3, depth: f32) -> Self {
        Self { normal, depth }
    }

    /// The geometry of a ray that hit nothing.
    pub const MISS: Self = Self {
        normal: Vec3::ZERO,
        depth: f32::INFINITY,
    };
}

/// Cosines within this of 1 count as equal normals in [`bilateral_weight`]
/// (`2⁻²¹ ≈ 4.8·10⁻⁷`, eight ulps of 1): rounding noise of f32 normalisation.
pub const NORMAL_COS_SNAP: f32 = 1.0 / 2_097_152.0;

/// Weight sums below this (`2⁻⁶⁴ ≈ 5.4·10⁻²⁰`) count as underflowed: products
/// `w·C` of such weights with ordinary colours approach f32's subnormal range,
/// where the normalised result would lose its precision.
pub const NEGLIGIBLE_WEIGHT: f32 = 5.421_011e-20;

/// `G(x) = exp(−x²)`, the Gaussian of eq. 1. `G(±∞) = 0`, `G(NaN) = 0`.
#[inline]
pub fn gaussian(x: f32) -> f32 {
    let e = libm::expf(-(x * x));
    // NaN must exclude, never propagate.
    if !e.is_nan() {
        e
    } else {
        0.0
    }
}

/// Beyond this `s`, `exp(−s) < 2⁻¹⁵¹` rounds to 0 in f32 (`e⁻¹⁰⁵ ≈ 2.5·10⁻⁴⁶`).
const EXP_UNDERFLOW: f32 = 105.0;

/// `exp(−s)` for `s = a² + b² ≥ 0`; 0 for `s = ∞` or NaN.
///
/// The two ends skip the exponential and return what it would: `s = 0`
/// (same depth, same normal: the common case inside a surface, and `w_ii`)
/// gives exactly 1, and `s ≥ 105`, ∞ or NaN gives 0.
#[inline]
fn gaussian_sum(s: f32) -> f32 {
    if s == 0.0 {
        1.0
    } else if s < EXP_UNDERFLOW {
        libm::expf(-s)
    } else {
        0.0
    }
}

/// `sat(x) = max(0, min(1, x))` (§3.1). `sat(NaN) = 0`.
#[inline]
pub fn saturate(x: f32) -> f32 {
    if x > 0.0 {
        if x < 1.0 {
            x
        } else {
            1.0
        }
    } else {
        0.0
    }
}

/// The depth dissimilarity `Δz` of eq. 1 under `metric`, always `≥ 0`.
///
/// Domain: depths `≥ 0`, finite or `+∞` (a miss). Equal depths (including two
/// misses) give 0. A miss against a hit, or a NaN, gives `+∞`, so the weight is 0.
/// Under the relative metric a step away from depth 0 is total (`2`), and
/// subnormal depths are compared like any others.
#[inline]
pub fn depth_difference(zi: f32, zj: f32, metric: DepthMetric) -> f32 {
    if zi == zj {
        return 0.0;
    }
    let diff = libm::fabsf(zj - zi);
    let r = match metric {
        DepthMetric::Absolute => diff,
        DepthMetric::Relative => {
            // Halve before adding so two depths near f32::MAX do not overflow.
            // Subnormal means divide fine; a mean that underflows to 0 gives ∞.
            let mean = 0.5 * libm::fabsf(zi) + 0.5 * libm::fabsf(zj);
            diff / mean
        }
    };
    // ∞/∞ and anything involving NaN: the samples cannot be matched.
    if !r.is_nan() {
        r
    } else {
        f32::INFINITY
    }
}

/// Bilateral weight `w_ij` of sample `j` when reconstructing sample `i` (eq. 1).
///
/// `w_ij = G(σz·Δz) · G(σn·(1 − sat(nj·ni)))` for [`WeightForm::Product`] (the
/// paper), or `exp(−s·max(1 − sat(nj·ni), σz·Δz))` for [`WeightForm::ChajdasMax`].
///
/// Domain: unit normals, depths in `[0, ∞]`, finite non-negative parameters.
/// Returns a value in `[0, 1]`; `w_ii = 1`; symmetric in `i` and `j`;
/// non-increasing in `|Δz|` and in the angle between the normals.
/// Outside the domain: a NaN anywhere gives 0 (the neighbour is excluded, never
/// blended); two misses (`depth = +∞`) give 1 whatever their normals; non-unit normals are accepted (the cosine is saturated to `[0, 1]`);
/// weights that underflow are 0, and [`reconstruct`] falls back.
#[inline]
pub fn bilateral_weight(params: &SraaParams, gi: &Geometry, gj: &Geometry) -> f32 {
    reconstruction_weight(params, gi, gj, 0.0)
}

/// The weight a reconstruction gives shaded sample `j` for subsample `i`:
/// eq. 1 ([`bilateral_weight`]) times the spatial term `exp(−d²/σs²)`,
/// `d² = distance2` the squared screen distance in pixels² from the
/// subsample to the shaded sample, when [`SraaParams::sigma_s`] is positive.
///
/// The paper's Fig. 2 weighs neighbours "by their distance and the normal
/// change"; eq. 1 itself has no distance, and without one a 3×3
/// neighbourhood of like geometry is a box filter. For the product form the
/// three Gaussians are one exponential, `exp(−(a² + b² + d²/σs²))`.
///
/// Domain: that of [`bilateral_weight`], and `distance2 ≥ 0`. With the term
/// on, a NaN or infinite `distance2` gives 0; with it off (`σs ≤ 0` or NaN),
/// `distance2` is ignored and the result is eq. 1's, bit for bit.
#[inline]
pub fn reconstruction_weight(
    params: &SraaParams,
    gi: &Geometry,
    gj: &Geometry,
    distance2: f32,
) -> f32 {
    // At distance 0 the term is 1 whatever σs (an underflowing σs² must
    // not turn eq. 1 into 0/0).
    let spatial = if params.sigma_s > 0.0 && distance2 != 0.0 {
        distance2 / (params.sigma_s * params.sigma_s)
    } else {
        0.0
    };
    let dz = depth_difference(gi.depth, gj.depth, params.depth_metric());
    // A unit vector normalised in f32 has |n|² within a few ulps of 1, so its
    // cosine with itself may be 1 − 2⁻²³·k; count cosines that close to 1 as 1,
    // or w_ii = 1 fails for the (linear) Chajdas form.
    let cos = saturate(gj.normal.dot(gi.normal));
    let dn = if cos >= 1.0 - NORMAL_COS_SNAP {
        0.0
    } else {
        1.0 - cos
    };
    if gi.depth == f32::INFINITY && gj.depth == f32::INFINITY {
        // Two misses: both are background, whatever their (meaningless) normals.
        return 1.0;
    }
    if gi.normal.is_nan() || gj.normal.is_nan() {
        return 0.0;
    }
    let w = match params.form() {
        // G(a)·G(b) = exp(−(a² + b²)): one exponential instead of two, the
        // same value up to rounding (bounded against f64 in the tests).
        WeightForm::Product => {
            let (a, b) = (params.sigma_z * dz, params.sigma_n * dn);
            gaussian_sum(a * a + b * b + spatial)
        }
        WeightForm::ChajdasMax => {
            let x = params.scale * dn.max(params.sigma_z * dz);
            let e = libm::expf(-x);
            let e = if !e.is_nan() { e } else { 0.0 };
            if spatial == 0.0 {
                e
            } else {
                e * gaussian_sum(spatial)
            }
        }
    };
    saturate(w)
}

/// Shadow-gated weight (eq. 2): 0 when the shadow states of `i` and `j` differ,
/// eq. 1 ([`bilateral_weight`]) when they agree.
///
/// `si`/`sj` are one light's states (`true` = in shadow). With several lights the
/// faithful extension reconstructs each light's direct contribution with its own
/// gate; which combination a backend uses is its choice.
///
/// Domain and out-of-domain behaviour are those of [`bilateral_weight`].
#[inline]
pub fn shadow_gated_weight(
    params: &SraaParams,
    gi: &Geometry,
    gj: &Geometry,
    si: bool,
    sj: bool,
) -> f32 {
    if si != sj {
        0.0
    } else {
        bilateral_weight(params, gi, gj)
    }
}

/// Default tolerance of the albedo gate ([`material_gated_weight`]), in the
/// square-root encoding of [`albedo_difference`].
///
/// `0.1` is a tenth of the encoded range, about 25 of 255 sRGB codes: slow
/// texture variation and noise below it is blended by eq. 1 as before (gating
/// it would turn the reconstruction into nearest-sample lookup on every
/// textured surface), while the edges between differently coloured patches or
/// texels that SRAA cannot see (§4.1, Fig. 6) lie far above it: the closest
/// two colours of the `checker` palette differ by 0.42.
pub const ALBEDO_TOLERANCE: f32 = 0.1;

/// Dissimilarity of two diffuse albedos for the material gate: the largest
/// per-channel difference of their square roots, `max_c |√a_c − √b_c|`.
///
/// The square root is a cheap perceptual encoding (gamma 2, close to sRGB's
/// transfer curve), so one tolerance means about the same visible step on
/// dark and on bright albedos; the maximum over channels sees a hue change at
/// constant luminance (red against green) that a luminance difference would
/// miss.
///
/// Domain: albedos with finite components, nominally in `[0, 1]`. Negative
/// components count as 0; components above 1 are compared as they are.
/// Outside the domain: a NaN or infinite component in either albedo gives
/// `+∞` (the samples never match). Symmetric; 0 for equal albedos.
#[inline]
pub fn albedo_difference(a: Vec3, b: Vec3) -> f32 {
    if !(a.is_finite() && b.is_finite()) {
        return f32::INFINITY;
    }
    root_difference(albedo_root(a), albedo_root(b))
}

/// `√max(a, 0)` per channel: the space [`albedo_difference`] compares in.
/// Kept apart so the resolver can take each albedo's roots once per pixel
/// instead of once per (subsample, neighbour) pair, to the same bits.
#[inline(always)]
pub(crate) fn albedo_root(a: Vec3) -> Vec3 {
    let e = |x: f32| crate::math::sqrt(if x > 0.0 { x } else { 0.0 });
    Vec3::new(e(a.x), e(a.y), e(a.z))
}

/// The largest channel difference of two [`albedo_root`]s.
#[inline(always)]
pub(crate) fn root_difference(ra: Vec3, rb: Vec3) -> f32 {
    let d = |x: f32, y: f32| libm::fabsf(x - y);
    d(ra.x, rb.x).max(d(ra.y, rb.y)).max(d(ra.z, rb.z))
}

/// Material-gated weight: eq. 2's gate applied to albedo instead of shadow
/// state. 0 when the albedos of `i` (the geometric subsample) and `j` (the
/// shaded sample) differ by more than `tolerance` ([`albedo_difference`]),
/// eq. 1 ([`bilateral_weight`]) when they match.
///
/// This is the fix for the failure case of §4.1 (Fig. 6): edges between
/// patches of different colour on one flat surface are invisible to depth and
/// normal, so eq. 1 blends the colours of both patches into every subsample
/// near the edge and the edge stays as jagged as the shaded samples. With the
/// albedo of each geometric subsample (a texture lookup at its hit; the
/// material's constant albedo elsewhere), a subsample only takes colour from
/// shaded samples of its own patch. As with eq. 2, when the gate removes every
/// neighbour the reconstruction falls back to the nearest shaded sample
/// ([`reconstruct`]).
///
/// Domain: that of [`bilateral_weight`] for the geometry, finite albedos, a
/// tolerance `≥ 0`. Outside it: a non-finite albedo, or a NaN or negative
/// tolerance, gates (weight 0); the result is always in `[0, 1]`, never NaN.
#[inline]
pub fn material_gated_weight(
    params: &SraaParams,
    gi: &Geometry,
    gj: &Geometry,
    ai: Vec3,
    aj: Vec3,
    tolerance: f32,
) -> f32 {
    if material_gate(ai, aj, tolerance) {
        bilateral_weight(params, gi, gj)
    } else {
        0.0
    }
}

/// The gate of [`material_gated_weight`]: whether albedos `ai` and `aj` match
/// within `tolerance` ([`albedo_difference`]). A non-finite albedo, or a NaN
/// or negative tolerance, never matches.
#[inline]
pub fn material_gate(ai: Vec3, aj: Vec3, tolerance: f32) -> bool {
    let d = albedo_difference(ai, aj);
    // d = ∞ (a non-finite albedo) gates even under an infinite tolerance.
    d <= tolerance && d < f32::INFINITY
}

/// A pixel of a reconstruction neighbourhood, with the squared screen distance
/// from the target subsample to that pixel's shaded sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeighbourPixel {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// Squared distance in pixels² (what [`ShadedSample::distance2`] wants).
    pub distance2: f32,
}

/// The pixels whose shaded samples reconstruct subsample `sub` of pixel `(x, y)`:
/// the `(2r+1)²` pixels around it (the paper's "fixed radius"; `r = 1` is the 3×3
/// neighbourhood), clipped to a `width × height` image, in row-major order,
/// with each shaded sample's squared distance to the subsample. `shaded` is
/// where a pixel's shaded sample lies ([`SraaParams::shaded_offset`]).
///
/// Domain: `sub < 4`, `(x, y)` inside the image. A `sub ≥ 4` (e.g.
/// [`SHADED_SAMPLE`]) is the shaded sample itself; a pixel outside the image
/// yields only the in-image part of its neighbourhood (possibly nothing).
pub fn neighbourhood(
    x: u32,
    y: u32,
    sub: usize,
    shaded: Vec2,
    radius: u32,
    width: u32,
    height: u32,
) -> Neighbourhood {
    let target = if sub < 4 {
        SUBPIXEL_OFFSETS[sub]
    } else {
        shaded
    };
    let offset = target - shaded;
    let x0 = x.saturating_sub(radius);
    let y0 = y.saturating_sub(radius);
    let x1 = x.saturating_add(radius).saturating_add(1).min(width);
    let y1 = y.saturating_add(radius).saturating_add(1).min(height);
    Neighbourhood {
        x,
        y,
        offset,
        x0,
        x1,
        y1,
        cx: x0,
        cy: y0,
    }
}

/// Iterator returned by [`neighbourhood`].
#[derive(Clone, Debug)]
pub struct Neighbourhood {
    x: u32,
    y: u32,
    /// Target subsample position minus the shaded sample position, within a pixel.
    offset: Vec2,
    x0: u32,
    x1: u32,
    y1: u32,
    cx: u32,
    cy: u32,
}

impl Iterator for Neighbourhood {
    type Item = NeighbourPixel;

    fn next(&mut self) -> Option<NeighbourPixel> {
        if self.cx >= self.x1 {
            self.cx = self.x0;
            self.cy += 1;
        }
        if self.cy >= self.y1 || self.x0 >= self.x1 {
            return None;
        }
        let (px, py) = (self.cx, self.cy);
        self.cx += 1;
        // Shaded sample of (px, py) minus target subsample of (x, y).
        let d = Vec2::new(px as f32 - self.x as f32, py as f32 - self.y as f32) - self.offset;
        Some(NeighbourPixel {
            x: px,
            y: py,
            distance2: d.length_squared(),
        })
    }
}

/// One shaded sample offered to [`reconstruct`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadedSample {
    /// Geometry at the shaded sample.
    pub geometry: Geometry,
    /// Its shaded colour (linear RGB). Non-finite colours are excluded.
    pub color: Vec3,
    /// Its shadow state for the light being reconstructed (ignored when the
    /// target has no gate).
    pub shadowed: bool,
    /// Squared screen distance, in pixels², from the target subsample: the
    /// spatial term's `d²` ([`reconstruction_weight`]) and what chooses the
    /// fallback sample.
    pub distance2: f32,
}

/// Result of reconstructing one geometric subsample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reconstruction {
    /// The reconstructed colour.
    pub color: Vec3,
    /// Sum of the weights used (0 when the fallback applied).
    pub weight_sum: f32,
    /// `true` when every weight was 0 or underflowed and the nearest shaded
    /// sample was taken instead.
    pub fell_back: bool,
}

/// Reconstruct the colour of a geometric subsample from shaded neighbours (§3.1–3.3).
///
/// `C_i = Σ_j w_ij C_j / Σ_j w_ij`, with `w_ij` from [`reconstruction_weight`]
/// (eq. 1 times the spatial term), gated as [`shadow_gated_weight`] gates when
/// `target_shadow` is `Some` (eq. 2).
/// The caller chooses the neighbourhood (by default the shaded samples of the
/// 3×3 pixels around, [`SraaParams::radius`]).
///
/// When every weight is 0 or their sum is negligible, below
/// [`NEGLIGIBLE_WEIGHT`] (e.g. `σz·Δz = 1e20` for every neighbour), returns the nearest shaded sample with a finite colour (smallest
/// `distance2`, first on ties) with `fell_back = true`; with no usable neighbour
/// at all, returns black. Never NaN: non-finite neighbour colours are excluded.
/// The result lies in the convex hull of the neighbours' colours, up to f32 rounding.
pub fn reconstruct<I>(
    params: &SraaParams,
    target: &Geometry,
    target_shadow: Option<bool>,
    neighbours: I,
) -> Reconstruction
where
    I: IntoIterator<Item = ShadedSample>,
{
    let mut acc = WeightedSum::ZERO;
    let mut nearest = Vec3::ZERO;
    let mut nearest_d2 = f32::INFINITY;
    let mut any = false;
    for s in neighbours {
        if !s.color.is_finite() {
            continue;
        }
        let d2 = if !s.distance2.is_nan() {
            s.distance2
        } else {
            f32::INFINITY
        };
        if !any || d2 < nearest_d2 {
            nearest = s.color;
            nearest_d2 = d2;
            any = true;
        }
        let w = match target_shadow {
            Some(si) if si != s.shadowed => 0.0,
            _ => reconstruction_weight(params, target, &s.geometry, d2),
        };
        acc.add(w, s.color);
    }
    if let Some(c) = acc.mean() {
        return Reconstruction {
            color: c,
            weight_sum: acc.weight(),
            fell_back: false,
        };
    }
    Reconstruction {
        color: nearest,
        weight_sum: 0.0,
        fell_back: true,
    }
}

/// The pixel resolve (§3, "the subpixel shading values are filtered into an
/// antialiased screen-resolution image"): a box filter over the four
/// reconstructed subsamples, each of which covers a quarter of the pixel.
///
/// Domain: finite colours. A non-finite subsample is dropped and the others are
/// averaged; with none finite, returns black.
#[inline(always)]
pub fn resolve_pixel(subsamples: &[Vec3; 4]) -> Vec3 {
    let n = subsamples.iter().filter(|c| c.is_finite()).count();
    if n == 0 {
        return Vec3::ZERO;
    }
    // Scale before summing, so four colours near f32::MAX do not overflow.
    let inv = 1.0 / n as f32;
    subsamples
        .iter()
        .filter(|c| c.is_finite())
        .fold(Vec3::ZERO, |s, c| s + *c * inv)
}

/// Luma weights of linear RGB (ITU-R BT.709, the sRGB primaries) for the
/// tone-mapped resolve's weights ([`tone_map_weight`]).
pub const RESOLVE_LUMA: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// The weight of one subsample in the tone-mapped resolve (Karis 2014,
/// *High Quality Temporal Supersampling*, the resolve of UE4's TAA):
/// `1 / (1 + exposure · luma(c))`, [`RESOLVE_LUMA`]. It is the derivative
/// factor of the reversible tone map `T(c) = c / (1 + luma(c))`, whose
/// inverse is `T⁻¹(c) = c / (1 − luma(c))`: `Σ wᵢ cᵢ / Σ wᵢ` with these
/// weights equals `T⁻¹(mean T(cᵢ))` exactly in exact arithmetic (with the
/// exposure folded into both), so a pixel is averaged as it will be seen
/// after tone mapping, not as linear radiance, and one HDR subsample no
/// longer takes over the pixel.
///
/// Computed in f64 (so the exposed luma of any finite colour at any finite
/// exposure is finite) and rounded to f32.
///
/// Domain: finite colours, `exposure > 0` and finite. Negative luma counts
/// as 0 (weight 1); an exposed luma above about `10⁴⁵` gives a weight that
/// rounds to 0 in f32. Outside the domain: a non-finite colour or exposure
/// gives 0 (the subsample is excluded, as [`resolve_pixel`] drops it); the
/// result is always in `[0, 1]`, never NaN.
#[inline]
pub fn tone_map_weight(c: Vec3, exposure: f32) -> f32 {
    tone_map_weight_f64(c, exposure) as f32
}

/// [`tone_map_weight`] before its rounding to f32.
#[inline]
fn tone_map_weight_f64(c: Vec3, exposure: f32) -> f64 {
    if !(c.is_finite() && exposure.is_finite()) {
        return 0.0;
    }
    let luma = (f64::from(c.x) * f64::from(RESOLVE_LUMA.x)
        + f64::from(c.y) * f64::from(RESOLVE_LUMA.y)
        + f64::from(c.z) * f64::from(RESOLVE_LUMA.z))
        * f64::from(exposure);
    // Negative luma (and a negative exposure's) reads as 0.
    let luma = if luma > 0.0 { luma } else { 0.0 };
    1.0 / (1.0 + luma)
}

/// The pixel resolve in tone-mapped space: the four reconstructed
/// subsamples averaged with [`tone_map_weight`]s, `Σ wₖ cₖ / Σ wₖ`, the
/// weighting TAA resolves with (Karis 2014, *High Quality Temporal
/// Supersampling*) so that an edge beside an HDR highlight is antialiased
/// as it is displayed. The result is linear radiance, like
/// [`resolve_pixel`]'s (the exposure only shapes the weights); tone mapped
/// with the same exposure, `T(exposure · result)` is the mean of the
/// subsamples' `T(exposure · cₖ)`, up to rounding. Subsamples of one luma
/// get equal weights, so the result is [`resolve_pixel`]'s box (up to the
/// box's f32 rounding), a pixel of one colour is returned unchanged (bit
/// for bit), and `exposure → 0` tends to the box.
///
/// Weights and sums in f64 (every weight of a finite colour is then
/// positive, at least about `10⁻⁷⁷`, so the mean never underflows), the
/// mean rounded to f32 once.
///
/// Domain: finite colours, `exposure > 0` and finite. Outside it: a
/// non-finite subsample is dropped (none finite gives black, as
/// [`resolve_pixel`]); an exposure that is not positive and finite gives
/// [`resolve_pixel`]'s box. Never NaN: the result is a convex combination
/// of finite f32 colours, so finite.
#[inline]
pub fn resolve_pixel_tone_mapped(subsamples: &[Vec3; 4], exposure: f32) -> Vec3 {
    if !(exposure > 0.0 && exposure.is_finite()) {
        return resolve_pixel(subsamples);
    }
    let mut sum = [0.0f64; 3];
    let mut weight = 0.0f64;
    for c in subsamples.iter().filter(|c| c.is_finite()) {
        let w = tone_map_weight_f64(*c, exposure);
        for (s, x) in sum.iter_mut().zip(c.to_array()) {
            *s += w * f64::from(x);
        }
        weight += w;
    }
    if !(weight > 0.0) {
        return Vec3::ZERO;
    }
    Vec3::from_array(sum.map(|s| (s / weight) as f32))
}

/// The space a pixel's four reconstructed subsamples are averaged in, the
/// last step of the SRAA resolve (§3: "the subpixel shading values are
/// filtered into an antialiased screen-resolution image").
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum ResolveSpace {
    /// The box filter over linear radiance ([`resolve_pixel`]), the paper's
    /// resolve and the default.
    #[default]
    Linear,
    /// Weighted by [`tone_map_weight`] ([`resolve_pixel_tone_mapped`],
    /// Karis 2014): for HDR radiance that is tone mapped after the resolve.
    ToneMapped {
        /// The exposure the frame is tone mapped with (the factor on
        /// radiance before the tone curve), `> 0` and finite.
        exposure: f32,
    },
}

impl ResolveSpace {
    /// Resolve a pixel's four subsamples in this space.
    #[inline(always)]
    pub fn resolve(&self, subsamples: &[Vec3; 4]) -> Vec3 {
        match *self {
            ResolveSpace::Linear => resolve_pixel(subsamples),
            ResolveSpace::ToneMapped { exposure } => {
                resolve_pixel_tone_mapped(subsamples, exposure)
            }
        }
    }

    /// Whether the space is in its domain: always for
    /// [`ResolveSpace::Linear`], an exposure `> 0` and finite for
    /// [`ResolveSpace::ToneMapped`].
    pub fn is_valid(&self) -> bool {
        match *self {
            ResolveSpace::Linear => true,
            ResolveSpace::ToneMapped { exposure } => exposure > 0.0 && exposure.is_finite(),
        }
    }
}

/// Most layers [`reconstruct_layers`] handles at once.
pub const MAX_LAYERS: usize = 16;

/// One shaded neighbour offered to [`reconstruct_layers`]: its geometry, its
/// shadow states (bit `b` = in light `b`'s shadow) and one colour per layer.
#[derive(Clone, Copy, Debug)]
pub struct LayeredSample<'a> {
    /// Geometry at the shaded sample.
    pub geometry: Geometry,
    /// Shadow states, one bit per light.
    pub shadow: u32,
    /// Squared screen distance to the target subsample (for the fallback).
    pub distance2: f32,
    /// One colour per layer.
    pub colors: &'a [Vec3],
}

/// [`reconstruct`] for several layers that share the target's geometry, in one
/// pass over the neighbours: the weight ([`reconstruction_weight`]: eq. 1 and
/// the spatial term) is computed once per neighbour, and layer `i` applies eq. 2's gate on shadow bit `gates[i]` (or no
/// gate for `None`). This is how SRAA-RT reconstructs a subsample's
/// shadow-independent part and each light's direct part (§3.1–3.2).
///
/// Writes `min(gates.len(), out.len(), MAX_LAYERS)` layers to `out`; each equals,
/// bit for bit, what [`reconstruct`] returns for that layer alone (same
/// weights, same order of summation, same fallback). A neighbour with fewer
/// colours than layers contributes black to the missing ones.
pub fn reconstruct_layers<'a, I>(
    params: &SraaParams,
    target: &Geometry,
    target_shadow: u32,
    gates: &[Option<u8>],
    neighbours: I,
    out: &mut [Vec3],
) where
    I: IntoIterator<Item = LayeredSample<'a>>,
{
    // A NaN distance needs no sanitising here: reconstruction_weight gives
    // it weight 0 with the spatial term on, and ignores it with the term off.
    let weighted = neighbours.into_iter().map(|s| {
        (
            reconstruction_weight(params, target, &s.geometry, s.distance2),
            s,
        )
    });
    reconstruct_weighted_layers(target_shadow, gates, weighted, out);
}

/// [`reconstruct_layers`] with the material gate: each neighbour's weight is
/// [`material_gated_weight`] of the target's albedo and the neighbour's (the
/// second item of each pair) instead of [`bilateral_weight`], so every layer
/// is gated by albedo (§4.1, Fig. 6) and, where `gates` says so, by shadow
/// state (eq. 2). Same order of summation and fallback as
/// [`reconstruct_layers`]; with all albedos equal, the same bits.
#[allow(clippy::too_many_arguments)]
pub fn reconstruct_layers_material<'a, I>(
    params: &SraaParams,
    target: &Geometry,
    target_shadow: u32,
    target_albedo: Vec3,
    tolerance: f32,
    gates: &[Option<u8>],
    neighbours: I,
    out: &mut [Vec3],
) where
    I: IntoIterator<Item = (LayeredSample<'a>, Vec3)>,
{
    let weighted = neighbours.into_iter().map(|(s, albedo)| {
        // As material_gated_weight gates, with the spatial term.
        let w = if material_gate(target_albedo, albedo, tolerance) {
            reconstruction_weight(params, target, &s.geometry, s.distance2)
        } else {
            0.0
        };
        (w, s)
    });
    reconstruct_weighted_layers(target_shadow, gates, weighted, out);
}

/// The loop of [`reconstruct_layers`] over neighbours whose ungated weight
/// is already known.
fn reconstruct_weighted_layers<'a, I>(
    target_shadow: u32,
    gates: &[Option<u8>],
    neighbours: I,
    out: &mut [Vec3],
) where
    I: Iterator<Item = (f32, LayeredSample<'a>)>,
{
    let n = gates.len().min(out.len()).min(MAX_LAYERS);
    let mut acc = [WeightedSum::ZERO; MAX_LAYERS];
    let mut nearest = [Vec3::ZERO; MAX_LAYERS];
    let mut nearest_d2 = [f32::INFINITY; MAX_LAYERS];
    let mut any = [false; MAX_LAYERS];
    for (w, s) in neighbours {
        let d2 = if !s.distance2.is_nan() {
            s.distance2
        } else {
            f32::INFINITY
        };
        for i in 0..n {
            let c = s.colors.get(i).copied().unwrap_or(Vec3::ZERO);
            if !c.is_finite() {
                continue;
            }
            if !any[i] || d2 < nearest_d2[i] {
                nearest[i] = c;
                nearest_d2[i] = d2;
                any[i] = true;
            }
            let wi = match gates[i] {
                Some(bit) if bit < 32 && ((target_shadow ^ s.shadow) >> bit) & 1 != 0 => 0.0,
                _ => w,
            };
            acc[i].add(wi, c);
        }
    }
    for i in 0..n {
        out[i] = acc[i].mean().unwrap_or(nearest[i]);
    }
}
