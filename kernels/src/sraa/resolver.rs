//! The per-pixel antialiasing pass of SRAA (§3, pass 2), for a whole frame's
//! slices: every layer of the four geometric subsamples of a pixel
//! reconstructed from the shaded samples around it (eq. 1, gated by eq. 2 per
//! light, §3.1–3.3), then the box resolve ([`resolve_pixel`](super::resolve_pixel)).
//!
//! [`Resolver::resolve`] gives, bit for bit, what the per-subsample,
//! per-layer-group path gives ([`reconstruct_layers`] and
//! [`reconstruct_layers_material`] over [`neighbourhood`], summed per
//! subsample, then [`resolve_pixel`](super::resolve_pixel)); `kernels/tests/properties.rs` holds
//! the two together. What it does differently is only the order of the work:
//! - the neighbourhood's geometry, shadow bits and colours are gathered once
//!   per pixel, not once per subsample and layer group;
//! - the product-form weights of all nine neighbours for the four
//!   subsamples are computed together, one (neighbour, subsample) pair per
//!   lane, in two chunks of [`WIDE_LANES`] = 16 lanes and one of 4
//!   ([`Resolver::weights_product`] over [`weights_product_wide`] and
//!   [`gaussian_sum_wide`]: branch-free loops that vectorise 8 or 16 wide
//!   in AVX2 or AVX-512 code), in the same f32 operations as
//!   [`reconstruction_weight`], so to the same bits;
//! - the spatial term's `d²/σs²` of each (subsample, neighbour) pair is a
//!   table built once per frame ([`Resolver::new`]);
//! - with [`Resolver::resolve_flagged`], which layers of a neighbourhood are
//!   black, non-finite or one colour is read from [`LayerFlags`] computed
//!   once per shaded sample ([`Resolver::layer_flags`]), not found again by
//!   each of the nine neighbourhoods the sample is in;
//! - what cannot change the sum is skipped: a neighbour whose weight is
//!   exactly 0 (adding `0·C` to the f64 sum changes nothing), a layer whose
//!   every neighbour colour is exactly black or not finite (it reconstructs
//!   to black, which adds nothing to the subsample's sum of layers), the
//!   secondary layers of a pixel none of whose subsamples sees a mirror, and
//!   the search for the fallback sample unless the weights underflowed.
//!
//! This is the CPU side of the pass. The GPU side is the per-subsample path
//! in WGSL, [`RECONSTRUCT_WGSL`](super::RECONSTRUCT_WGSL)
//! (`subcone_sraa_reconstruct_run`, which drives the twins of the same
//! functions, `subcone_reconstruct_layers_begin/add/end`, in the same order),
//! and the pixel's box resolve (`subcone_resolve_pixel`); the kernel
//! conformance suite (`tests/conformance_kernels.rs`) holds them to
//! [`reconstruct_layers`] and to this resolver.

use glam::{Vec2, Vec3, Vec3A, Vec4};

use super::{
    albedo_root, neighbourhood, reconstruct_layers, reconstruct_layers_material,
    reconstruction_weight, root_difference, Geometry, LayeredSample, ResolveSpace, SraaParams,
    WeightForm, MAX_LAYERS, SUBPIXEL_OFFSETS,
};
use crate::sum::WeightedSum4;

mod lanes;
mod scan;
pub use lanes::{
    gaussian_sum_lanes, gaussian_sum_wide, weights_product_lanes, weights_product_wide,
    GeometryLanes, GeometryWide, WIDE_LANES,
};
use scan::{color_at, slots, Hood, LayerScan};
pub use scan::{FrameFlags, LayerFlags};

/// One group of shaded layers of a frame, reconstructed on one geometry:
/// the primary hits' (layers `first_layer..`) or, on mirrors, the secondary
/// hits' (§3.3).
#[derive(Clone, Copy, Debug)]
pub struct ShadedGroup<'a> {
    /// Geometry of every pixel's shaded sample for this group, row-major.
    pub geometry: &'a [Geometry],
    /// Shadow bits of every pixel's shaded sample (bit `b`: in light `b`'s
    /// shadow); empty when the frame has no shadow pass (all 0).
    pub shadow: &'a [u32],
    /// Index, within a pixel's layers, of the group's first layer.
    pub first_layer: usize,
}

/// A frame's shaded samples: what [`Resolver::resolve`] reads around a pixel.
#[derive(Clone, Copy, Debug)]
pub struct ShadedFrame<'a> {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Every pixel's layer colours, `layers` per pixel, row-major.
    pub colors: &'a [Vec3],
    /// Layers per pixel (the stride of `colors`).
    pub layers: usize,
    /// Albedo of every pixel's shaded sample, for the material gate of the
    /// primary group ([`reconstruct_layers_material`]); empty for none.
    pub albedo: &'a [Vec3],
    /// The primary group (layers from `primary.first_layer`).
    pub primary: ShadedGroup<'a>,
    /// The secondary group, when the frame reconstructs reflections on their
    /// own geometry (§3.3).
    pub secondary: Option<ShadedGroup<'a>>,
}

/// A pixel's four geometric subsamples ([`SUBPIXEL_OFFSETS`]) for one group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Subsamples {
    /// Geometry of each subsample. For the secondary group a NaN depth means
    /// "no mirror here": that subsample has no secondary layers.
    pub geometry: [Geometry; 4],
    /// Shadow bits of each subsample (0 without a subpixel shadow pass).
    pub shadow: [u32; 4],
    /// Albedo of each subsample when the group is gated by material.
    pub albedo: Option<[Vec3; 4]>,
}

/// Slots of the 3×3 neighbourhood, row-major.
const SLOTS: usize = 9;

/// The lanes of [`Resolver::weights_product`], one per (slot, subsample)
/// pair, slot-major: slots 0–3 and slots 4–7 in two chunks of
/// [`WIDE_LANES`] = 16 lanes (lane `4·(slot mod 4) + k`), slot 8 in four.
/// Exactly the 36 pairs, no padding: at 16 lanes (AVX-512) two full
/// registers and a quarter one, at 8 (AVX2) four and a half.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PairLanes {
    low: [f32; WIDE_LANES],
    high: [f32; WIDE_LANES],
    last: [f32; 4],
}

impl PairLanes {
    /// Pair (slot, k) is `f(slot, k)`.
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize, usize) -> f32) -> Self {
        Self {
            low: core::array::from_fn(|l| f(l / 4, l % 4)),
            high: core::array::from_fn(|l| f(4 + l / 4, l % 4)),
            last: core::array::from_fn(|k| f(8, k)),
        }
    }
}

/// Lane factors that zero the lanes set in a 4-bit mask and keep the others:
/// `w · KEEP_LANES[m]` is `w` (exactly: `w · 1`) or 0 per lane.
const KEEP_LANES: [[f64; 4]; 16] = {
    let mut t = [[0.0; 4]; 16];
    let mut m = 0;
    while m < 16 {
        let mut k = 0;
        while k < 4 {
            t[m][k] = ((m >> k) & 1 == 0) as u32 as f64;
            k += 1;
        }
        m += 1;
    }
    t
};

/// The per-pixel SRAA resolve over a frame's slices, set up once per frame:
/// the parameters, the layer gates, and the spatial term of every
/// (subsample, neighbour) pair of the 3×3 neighbourhood.
#[derive(Clone, Copy, Debug)]
pub struct Resolver<'g> {
    params: SraaParams,
    gates: &'g [Option<u8>],
    tolerance: f32,
    /// `distance2` of each (subsample, slot): what [`neighbourhood`] yields.
    distance2: [[f32; SLOTS]; 4],
    /// The spatial exponent `d²/σs²` of each (slot, subsample), as
    /// [`reconstruction_weight`] computes it, in the lanes of
    /// [`Resolver::weights_product`].
    spatial: PairLanes,
    /// How the four subsamples become the pixel ([`ResolveSpace::Linear`]
    /// unless [`Resolver::with_resolve_space`] says otherwise).
    space: ResolveSpace,
}

impl<'g> Resolver<'g> {
    /// A resolver for `params`, with layer `i` of each group gated by shadow
    /// bit `gates[i]` (eq. 2; `None`: ungated), and the material gate's
    /// `tolerance` ([`super::ALBEDO_TOLERANCE`] by default) for groups that
    /// carry albedos. At most [`MAX_LAYERS`] gates are used.
    pub fn new(params: &SraaParams, gates: &'g [Option<u8>], tolerance: f32) -> Self {
        let shaded = params.shaded_offset();
        let mut distance2 = [[0.0; SLOTS]; 4];
        let mut spatial = [[0.0; 4]; SLOTS];
        for (k, row) in distance2.iter_mut().enumerate() {
            let offset = SUBPIXEL_OFFSETS[k] - shaded;
            for (slot, d2) in row.iter_mut().enumerate() {
                // As `Neighbourhood::next`: (px − x, py − y) − offset.
                let d = Vec2::new((slot % 3) as f32 - 1.0, (slot / 3) as f32 - 1.0) - offset;
                *d2 = d.length_squared();
                // As `reconstruction_weight`'s spatial term.
                let s = if params.sigma_s > 0.0 && *d2 != 0.0 {
                    *d2 / (params.sigma_s * params.sigma_s)
                } else {
                    0.0
                };
                spatial[slot][k] = s;
            }
        }
        Self {
            params: *params,
            gates: &gates[..gates.len().min(MAX_LAYERS)],
            tolerance,
            distance2,
            spatial: PairLanes::from_fn(|slot, k| spatial[slot][k]),
            space: ResolveSpace::Linear,
        }
    }

    /// The same resolver, averaging each pixel's four subsamples in
    /// `space` ([`ResolveSpace::resolve`]) instead of the linear box
    /// ([`resolve_pixel`](super::resolve_pixel), the default).
    pub fn with_resolve_space(self, space: ResolveSpace) -> Self {
        Self { space, ..self }
    }

    /// The [`LayerFlags`] of `frame`'s pixels `first..first + out.len()`
    /// for `group` and this resolver's layers, into `out` (see
    /// [`LayerFlags::fill`]), for [`Resolver::resolve_flagged`].
    pub fn layer_flags(
        &self,
        frame: &ShadedFrame,
        group: &ShadedGroup,
        first: usize,
        out: &mut [LayerFlags],
    ) {
        LayerFlags::fill(frame, group, self.gates.len(), first, out);
    }

    /// The antialiased colour of pixel `(x, y)`: each subsample's primary
    /// layers reconstructed on `primary` from `frame.primary` (material-gated
    /// when both `primary.albedo` and `frame.albedo` are given), plus, where
    /// its secondary depth is not NaN, its secondary layers on `secondary`
    /// from `frame.secondary`; each subsample's colour is the sum of its
    /// layers, and the pixel the box resolve of the four ([`resolve_pixel`](super::resolve_pixel);
    /// in another [`ResolveSpace`] with [`Resolver::with_resolve_space`]).
    ///
    /// Bit for bit what [`reconstruct_layers`] / [`reconstruct_layers_material`]
    /// give per subsample and group over [`neighbourhood`] (see the module
    /// documentation), for every radius: radius 1 (the paper's 3×3) takes the
    /// gathered, lane-parallel path, other radii the per-subsample one.
    ///
    /// Domain: `(x, y)` inside a `width × height` image with both below
    /// `2²⁴` (where pixel coordinates are exact in f32), slices of
    /// `width·height` entries (`colors`: `width·height·layers`). Outside it:
    /// a pixel outside the image reconstructs from the in-image part of its
    /// neighbourhood (possibly nothing: black), and entries missing from a
    /// short slice read as a miss, no shadow and black; never a panic.
    #[inline(always)]
    pub fn resolve(
        &self,
        frame: &ShadedFrame,
        x: u32,
        y: u32,
        primary: &Subsamples,
        secondary: Option<&Subsamples>,
    ) -> Vec3 {
        self.resolve_flagged(frame, &FrameFlags::default(), x, y, primary, secondary)
    }

    /// [`Resolver::resolve`], bit for bit, reading which layers of a
    /// neighbourhood can change a sum from `flags` (each group's
    /// [`Resolver::layer_flags`], computed once per frame) instead of scanning
    /// the nine colours of every layer at every pixel; a group whose flags do
    /// not cover the frame, and the image's border pixels, are scanned as
    /// [`Resolver::resolve`] scans them.
    ///
    /// Domain and out-of-domain behaviour: [`Resolver::resolve`]'s. Flags
    /// filled for another frame or another resolver's layers are outside it:
    /// the result is then some weighted mean of the neighbourhood's colours,
    /// never a panic.
    #[inline(always)]
    pub fn resolve_flagged(
        &self,
        frame: &ShadedFrame,
        flags: &FrameFlags,
        x: u32,
        y: u32,
        primary: &Subsamples,
        secondary: Option<&Subsamples>,
    ) -> Vec3 {
        if self.params.radius() != 1 {
            return self.resolve_generic(frame, x, y, primary, secondary);
        }
        let mut subs = [Vec3::ZERO; 4];
        let albedo = if frame.albedo.is_empty() {
            None
        } else {
            primary.albedo
        };
        let hood = Hood::new(frame, x, y);
        let group = &frame.primary;
        self.add_group(
            frame,
            &hood,
            group,
            flags.primary,
            primary,
            albedo,
            &mut subs,
        );
        if let (Some(group), Some(targets)) = (frame.secondary.as_ref(), secondary) {
            if targets.geometry.iter().any(|g| !g.depth.is_nan()) {
                let mut s2 = [Vec3::ZERO; 4];
                self.add_group(frame, &hood, group, flags.secondary, targets, None, &mut s2);
                for k in 0..4 {
                    if !targets.geometry[k].depth.is_nan() {
                        subs[k] += s2[k];
                    }
                }
            }
        }
        self.space.resolve(&subs)
    }

    /// One group of layers for the four subsamples: `out[k]` is the sum of
    /// subsample `k`'s layers, in layer order, from `Vec3::ZERO`. Each layer
    /// is [`reconstruct_layers`]' (eq. 1 with the spatial term, eq. 2's gate
    /// for a light's layer, §3.1–3.2; the material gate with `albedo`, §4.1)
    /// for the four subsamples at once: the neighbourhood's colours scanned
    /// first ([`LayerScan`]), each neighbour's weights for the four lanes
    /// next ([`Resolver::neighbour_weights`]), then, layer by layer, the
    /// gated weighted mean ([`NeighbourWeights::gated_sum`]) or, where the
    /// weights underflowed, the nearest finite colour
    /// ([`Resolver::nearest_finite`]).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn add_group(
        &self,
        frame: &ShadedFrame,
        hood: &Hood,
        group: &ShadedGroup,
        flags: &[LayerFlags],
        targets: &Subsamples,
        albedo: Option<[Vec3; 4]>,
        out: &mut [Vec3; 4],
    ) {
        let n = self.gates.len();
        let scan = LayerScan::of(frame, hood, group, n, flags);
        if scan.live == 0 {
            return;
        }
        if scan.live & scan.varied == 0 {
            // Every layer that is not black is uniform: no weight needed.
            for i in 0..n {
                if scan.live & (1 << i) != 0 {
                    add_to_each(out, scan.uniform(frame, i));
                }
            }
            return;
        }
        let weights = self.neighbour_weights(frame, hood, group, targets, albedo);
        for (i, gate) in self.gates.iter().enumerate() {
            if scan.live & (1 << i) == 0 {
                continue;
            }
            if scan.varied & (1 << i) == 0 {
                add_to_each(out, scan.uniform(frame, i));
                continue;
            }
            let bit = match *gate {
                Some(bit) if bit < 32 => Some(bit as usize),
                _ => None,
            };
            let acc = weights.gated_sum(frame, &scan, hood.valid, i, bit, &targets.shadow);
            for (k, sum) in out.iter_mut().enumerate() {
                *sum += match acc.mean(k) {
                    Some(c) => c,
                    None => self.nearest_finite(frame, hood, &scan, i, k),
                };
            }
        }
    }

    /// The weights of every neighbour of the 3×3 neighbourhood for the four
    /// subsamples, one lane each: [`reconstruction_weight`] (eq. 1 times the
    /// spatial term, or the Chajdas form), zeroed in the lanes the material
    /// gate closes (`albedo`: the subsamples' albedos, §4.1, Fig. 6), with
    /// each neighbour's shadow bits for eq. 2.
    #[inline(always)]
    fn neighbour_weights(
        &self,
        frame: &ShadedFrame,
        hood: &Hood,
        group: &ShadedGroup,
        targets: &Subsamples,
        albedo: Option<[Vec3; 4]>,
    ) -> NeighbourWeights {
        let mut geometry = [Geometry::MISS; SLOTS];
        let mut shadow = [0u32; SLOTS];
        for slot in hood.slots() {
            let j = hood.index[slot];
            geometry[slot] = group.geometry.get(j).copied().unwrap_or(Geometry::MISS);
            shadow[slot] = group.shadow.get(j).copied().unwrap_or(0);
        }

        // The weights of every neighbour for the four subsamples, one lane
        // each; `nonzero`: the slots with a weight above 0 in some lane.
        let mut weights = [[0.0f32; 4]; SLOTS];
        let mut nonzero = 0u32;
        let form = self.params.form();
        // The product form: all (slot, subsample) pairs at once; the slots
        // outside the image are computed too (as misses) and dropped below.
        let product = match form {
            WeightForm::Product => self.weights_product(&targets.geometry, &geometry),
            WeightForm::ChajdasMax => [[0.0; 4]; SLOTS],
        };
        let gate = albedo.map(|a| MaterialGateLanes::new(a, self.tolerance));
        for slot in hood.slots() {
            let mut w = match form {
                WeightForm::Product => Vec4::from_array(product[slot]),
                WeightForm::ChajdasMax => Vec4::from_array(core::array::from_fn(|k| {
                    reconstruction_weight(
                        &self.params,
                        &targets.geometry[k],
                        &geometry[slot],
                        self.distance2[k][slot],
                    )
                })),
            };
            if let Some(gate) = &gate {
                let aj = frame.albedo.get(hood.index[slot]).copied();
                w *= Vec4::from_array(KEEP_LANES[gate.gated(aj)].map(|k| k as f32));
            }
            weights[slot] = w.to_array();
            if w.cmpgt(Vec4::ZERO).any() {
                nonzero |= 1 << slot;
            }
        }
        NeighbourWeights {
            weights,
            nonzero,
            shadow,
        }
    }

    /// The product-form weights (§3.1, eq. 1 times the spatial term) of the
    /// nine shaded samples of the 3×3 neighbourhood, `neighbours` (row-major:
    /// slot `3·(dy + 1) + dx + 1` is pixel `(x + dx, y + dy)`), for the four
    /// subsamples of pixel `(x, y)`, `targets`: `w[slot][k]` is
    /// [`reconstruction_weight`] for `params.with_form(WeightForm::Product)`
    /// (whatever the resolver's form and radius), `targets[k]` against
    /// `neighbours[slot]` at the squared distance [`neighbourhood`] gives
    /// subsample `k` from that sample, bit for bit.
    ///
    /// The 36 (slot, subsample) pairs are computed together, one per lane
    /// ([`weights_product_wide`]: two chunks of [`WIDE_LANES`] = 16 lanes and
    /// one of 4, branch-free), so that inside AVX2 or AVX-512 code (this is
    /// `#[inline(always)]`) they vectorise 8 or 16 wide.
    ///
    /// Domain and out-of-domain behaviour are [`reconstruction_weight`]'s,
    /// pair by pair (a NaN gives 0, two misses 1; never a panic).
    #[inline(always)]
    pub fn weights_product(
        &self,
        targets: &[Geometry; 4],
        neighbours: &[Geometry; SLOTS],
    ) -> [[f32; 4]; SLOTS] {
        let p = &self.params;
        let sp = &self.spatial;
        // Targets repeat every four lanes; a neighbour fills four lanes.
        let gi = GeometryWide::<WIDE_LANES>::from_fn(|l| targets[l % 4]);
        let low = GeometryWide::from_fn(|l| neighbours[l / 4]);
        let high = GeometryWide::from_fn(|l| neighbours[4 + l / 4]);
        let low = weights_product_wide(p, &gi, &low, &sp.low);
        let high = weights_product_wide(p, &gi, &high, &sp.high);
        let last = weights_product_wide(
            p,
            &GeometryWide::from_fn(|k| targets[k]),
            &GeometryWide::from_fn(|_| neighbours[8]),
            &sp.last,
        );
        core::array::from_fn(|slot| match slot {
            0..4 => core::array::from_fn(|k| low[4 * slot + k]),
            4..8 => core::array::from_fn(|k| high[4 * (slot - 4) + k]),
            _ => last,
        })
    }

    /// [`reconstruct_layers`]' fallback for subsample `k`'s layer `i` when
    /// its weights underflowed: the nearest shaded sample with a finite
    /// colour, the first on ties (black with none).
    #[inline(always)]
    fn nearest_finite(
        &self,
        frame: &ShadedFrame,
        hood: &Hood,
        scan: &LayerScan,
        i: usize,
        k: usize,
    ) -> Vec3 {
        let mut nearest = Vec3::ZERO;
        let mut nearest_d2 = f32::INFINITY;
        let mut any = false;
        for slot in hood.slots() {
            let d2 = self.distance2[k][slot];
            if scan.finite[slot] & (1 << i) != 0 && (!any || d2 < nearest_d2) {
                nearest = color_at(frame, scan.base[slot] + i);
                nearest_d2 = d2;
                any = true;
            }
        }
        nearest
    }

    /// Any radius: the per-subsample path over [`neighbourhood`].
    #[inline]
    fn resolve_generic(
        &self,
        frame: &ShadedFrame,
        x: u32,
        y: u32,
        primary: &Subsamples,
        secondary: Option<&Subsamples>,
    ) -> Vec3 {
        let mut subs = [Vec3::ZERO; 4];
        let albedo = if frame.albedo.is_empty() {
            None
        } else {
            primary.albedo
        };
        for (k, sub) in subs.iter_mut().enumerate() {
            *sub = self.subsample_generic(frame, x, y, k, &frame.primary, primary, albedo);
            if let (Some(group), Some(targets)) = (frame.secondary.as_ref(), secondary) {
                if !targets.geometry[k].depth.is_nan() {
                    *sub += self.subsample_generic(frame, x, y, k, group, targets, None);
                }
            }
        }
        self.space.resolve(&subs)
    }

    /// One subsample's layers of one group, summed: [`reconstruct_layers`]
    /// (or its material-gated form) over [`neighbourhood`].
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn subsample_generic(
        &self,
        frame: &ShadedFrame,
        x: u32,
        y: u32,
        k: usize,
        group: &ShadedGroup,
        targets: &Subsamples,
        albedo: Option<[Vec3; 4]>,
    ) -> Vec3 {
        let p = &self.params;
        let hood = neighbourhood(
            x,
            y,
            k,
            p.shaded_offset(),
            p.radius(),
            frame.width,
            frame.height,
        );
        let n = self.gates.len();
        let samples = hood.map(|np| {
            let j = np.y as usize * frame.width as usize + np.x as usize;
            let base = j * frame.layers + group.first_layer;
            let s = LayeredSample {
                geometry: group.geometry.get(j).copied().unwrap_or(Geometry::MISS),
                shadow: group.shadow.get(j).copied().unwrap_or(0),
                distance2: np.distance2,
                colors: frame.colors.get(base..base + n).unwrap_or(&[]),
            };
            (s, frame.albedo.get(j).copied().unwrap_or(Vec3::NAN))
        });
        let mut out = [Vec3::ZERO; MAX_LAYERS];
        let target = &targets.geometry[k];
        let ts = targets.shadow[k];
        match albedo {
            Some(a) => reconstruct_layers_material(
                p,
                target,
                ts,
                a[k],
                self.tolerance,
                self.gates,
                samples,
                &mut out,
            ),
            None => {
                reconstruct_layers(p, target, ts, self.gates, samples.map(|(s, _)| s), &mut out)
            }
        }
        out[..n].iter().fold(Vec3::ZERO, |a, c| a + *c)
    }
}

/// `out[k] += c` for the four subsamples: a layer that reconstructs to `c`
/// whatever the weights.
#[inline(always)]
fn add_to_each(out: &mut [Vec3; 4], c: Vec3A) {
    for sum in out.iter_mut() {
        *sum += Vec3::from(c);
    }
}

/// Every neighbour's weights for the four subsamples
/// ([`Resolver::neighbour_weights`]) and its shadow bits.
struct NeighbourWeights {
    /// Slot by slot, one lane per subsample (widened to f64, exactly, where
    /// summed: half the bytes to fill and move).
    weights: [[f32; 4]; SLOTS],
    /// The slots with a weight above 0 in some lane.
    nonzero: u32,
    /// Each slot's shadow bits (bit `b`: in light `b`'s shadow).
    shadow: [u32; SLOTS],
}

impl NeighbourWeights {
    /// Layer `i`'s weighted sums for the four subsamples over the valid
    /// slots (`valid`) with a finite colour, in row-major order (that of
    /// [`neighbourhood`]), each neighbour's weight gated by eq. 2 on shadow
    /// bit `bit` (`None`: ungated): 0 in the lanes whose subsample's bit in
    /// `target_shadow` differs from the neighbour's.
    #[inline(always)]
    fn gated_sum(
        &self,
        frame: &ShadedFrame,
        scan: &LayerScan,
        valid: u32,
        i: usize,
        bit: Option<usize>,
        target_shadow: &[u32; 4],
    ) -> WeightedSum4 {
        // Bit k: subsample k's shadow bit of this layer's light.
        let mine = bit.map_or(0, |b| {
            let t = target_shadow;
            ((t[0] >> b) & 1)
                | ((t[1] >> b) & 1) << 1
                | ((t[2] >> b) & 1) << 2
                | ((t[3] >> b) & 1) << 3
        });
        let mut acc = WeightedSum4::ZERO;
        for slot in slots(valid & self.nonzero) {
            if scan.finite[slot] & (1 << i) == 0 {
                continue;
            }
            let w = match bit {
                // Eq. 2: lanes whose shadow bit differs from the
                // neighbour's weigh 0.
                Some(b) => {
                    let theirs = if (self.shadow[slot] >> b) & 1 != 0 {
                        0xf
                    } else {
                        0
                    };
                    let differ = (mine ^ theirs) as usize;
                    if differ == 0xf {
                        continue;
                    }
                    let (w, keep) = (self.weights[slot].map(f64::from), KEEP_LANES[differ]);
                    [
                        w[0] * keep[0],
                        w[1] * keep[1],
                        w[2] * keep[2],
                        w[3] * keep[3],
                    ]
                }
                None => self.weights[slot].map(f64::from),
            };
            acc.add(w, color_at(frame, scan.base[slot] + i));
        }
        acc
    }
}

/// The material gate ([`material_gate`](super::material_gate)) of the four subsamples against one
/// neighbour at a time, to the same decisions: each subsample's albedo is
/// taken to the compared space ([`albedo_root`], three square roots) once per
/// pixel, not once per neighbour, and a neighbour whose albedo equals a
/// subsample's (the common case inside a patch: the difference is exactly 0)
/// needs no square root at all.
struct MaterialGateLanes {
    albedo: [Vec3; 4],
    root: [Vec3; 4],
    /// Bit k: subsample k's albedo is finite.
    finite: u32,
    tolerance: f32,
    /// Whether a difference of exactly 0 passes (`0 ≤ tolerance`; false for a
    /// negative or NaN tolerance, as in [`material_gate`](super::material_gate)).
    equal_passes: bool,
}

impl MaterialGateLanes {
    #[inline(always)]
    fn new(albedo: [Vec3; 4], tolerance: f32) -> Self {
        let mut finite = 0;
        let mut root = [Vec3::ZERO; 4];
        for (k, a) in albedo.iter().enumerate() {
            if a.is_finite() {
                finite |= 1 << k;
                root[k] = albedo_root(*a);
            }
        }
        Self {
            albedo,
            root,
            finite,
            tolerance,
            equal_passes: 0.0 <= tolerance,
        }
    }

    /// Bit k set: subsample k is gated off from a neighbour of albedo `aj`
    /// (`None`: the neighbour has none, which gates every subsample).
    #[inline(always)]
    fn gated(&self, aj: Option<Vec3>) -> usize {
        let Some(aj) = aj.filter(|a| a.is_finite()) else {
            return 0b1111;
        };
        let mut gated = 0;
        let mut rj = None;
        for k in 0..4 {
            let pass = if self.finite & (1 << k) == 0 {
                false
            } else if self.albedo[k] == aj {
                // Equal albedos have equal roots: the difference is 0.
                self.equal_passes
            } else {
                let rj = *rj.get_or_insert_with(|| albedo_root(aj));
                let d = root_difference(self.root[k], rj);
                d <= self.tolerance && d < f32::INFINITY
            };
            if !pass {
                gated |= 1 << k;
            }
        }
        gated
    }
}
