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
    reconstruction_weight, root_difference, DepthMetric, Geometry, LayeredSample, ResolveSpace,
    SraaParams, WeightForm, MAX_LAYERS, NORMAL_COS_SNAP, SUBPIXEL_OFFSETS,
};
use crate::sum::WeightedSum4;

mod scan;
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
        self.add_group(frame, &hood, group, flags.primary, primary, albedo, &mut subs);
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

/// The four subsamples' geometry, one subsample per lane.
#[derive(Clone, Copy, Debug)]
pub struct GeometryLanes {
    nx: Vec4,
    ny: Vec4,
    nz: Vec4,
    depth: Vec4,
}

impl GeometryLanes {
    /// Lanes from four geometries.
    pub fn new(g: &[Geometry; 4]) -> Self {
        Self {
            nx: Vec4::new(g[0].normal.x, g[1].normal.x, g[2].normal.x, g[3].normal.x),
            ny: Vec4::new(g[0].normal.y, g[1].normal.y, g[2].normal.y, g[3].normal.y),
            nz: Vec4::new(g[0].normal.z, g[1].normal.z, g[2].normal.z, g[3].normal.z),
            depth: Vec4::new(g[0].depth, g[1].depth, g[2].depth, g[3].depth),
        }
    }
}

/// [`reconstruction_weight`] of the product form (§3.1, eq. 1 times the
/// spatial term) for four targets `gi` (lanes) against one neighbour `gj`,
/// with `spatial` the lanes' `d²/σs²` (0 for none): [`weights_product_wide`]
/// in four lanes, so each lane equals the scalar weight bit for bit.
/// Domain and out-of-domain behaviour are the scalar function's.
#[inline]
pub fn weights_product_lanes(
    p: &SraaParams,
    gi: &GeometryLanes,
    gj: &Geometry,
    spatial: Vec4,
) -> Vec4 {
    let gi = GeometryWide {
        nx: gi.nx.to_array(),
        ny: gi.ny.to_array(),
        nz: gi.nz.to_array(),
        depth: gi.depth.to_array(),
    };
    let gj = GeometryWide::from_fn(|_| *gj);
    Vec4::from_array(weights_product_wide(p, &gi, &gj, &spatial.to_array()))
}

// libm's expf (FreeBSD's e_expf.c), constants and thresholds, by their
// bits: a shortest decimal can name the neighbouring f32 (1.442_695_1 is
// 0x3fb8aa3c, one ulp above libm's 1/ln 2).
const LN2_HI: f32 = f32::from_bits(0x3f31_7200); // 6.9314575195e-01
const LN2_LO: f32 = f32::from_bits(0x35bf_be8e); // 1.4286067653e-06
const INV_LN2: f32 = f32::from_bits(0x3fb8_aa3b); // 1.4426950216e+00
const P1: f32 = f32::from_bits(0x3e2a_aa8f); // 0xaaaa8f.0p-26
const P2: f32 = f32::from_bits(0xbb35_5215); // -0xb55215.0p-32
/// `1.5·2²³`: `(t + ROUND_MAGIC) − ROUND_MAGIC` is `t` rounded to the
/// nearest integer (ties to even), exactly, for `|t| < 2²²`.
const ROUND_MAGIC: f32 = 12_582_912.0;

/// `exp(−s)` of `gaussian_sum` in four lanes: exactly 1 for `s = 0`,
/// 0 for `s ≥ 105`, `+∞` or NaN, and `libm::expf(−s)` in between:
/// [`gaussian_sum_wide`] in four lanes.
///
/// Error against libm's `expf`: none (see [`gaussian_sum_wide`]). Its
/// error against the true `e^−s` is libm's, under 1 ulp. The WGSL twin
/// (`subcone_gaussian_sum`) keeps the GPU's `exp`, whose tolerance in the
/// kernel conformance table is unchanged.
///
/// Domain: `s ≥ 0` or NaN, as `gaussian_sum` is called (a sum of squares).
/// A negative `s` is outside it: its lane returns `1 − s`, not `expf(−s)`
/// (never NaN, never a panic).
#[inline]
pub fn gaussian_sum_lanes(s: Vec4) -> Vec4 {
    Vec4::from_array(gaussian_sum_wide(&s.to_array()))
}

/// Lanes of a full chunk of [`weights_product_wide`] in
/// [`Resolver::weights_product`]: 16 f32 lanes, one AVX-512 register (two
/// AVX2 registers, four SSE ones). A pixel's 36 (slot, subsample) pairs are
/// two such chunks and one of 4 lanes.
pub const WIDE_LANES: usize = 16;

/// `N` geometries in lanes, one array per component (structure of arrays),
/// for [`weights_product_wide`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeometryWide<const N: usize> {
    /// The normals' x components.
    pub nx: [f32; N],
    /// The normals' y components.
    pub ny: [f32; N],
    /// The normals' z components.
    pub nz: [f32; N],
    /// The depths.
    pub depth: [f32; N],
}

impl<const N: usize> GeometryWide<N> {
    /// Lane `l` is `f(l)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> Geometry) -> Self {
        let mut g = Self {
            nx: [0.0; N],
            ny: [0.0; N],
            nz: [0.0; N],
            depth: [0.0; N],
        };
        for l in 0..N {
            let s = f(l);
            g.nx[l] = s.normal.x;
            g.ny[l] = s.normal.y;
            g.nz[l] = s.normal.z;
            g.depth[l] = s.depth;
        }
        g
    }
}

/// `|x|`, by clearing the sign bit (no call: it stays in the vector loop).
#[inline(always)]
fn abs_lane(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
}

/// [`super::saturate`], as the same comparisons written as selects.
#[inline(always)]
fn saturate_lane(x: f32) -> f32 {
    let below_one = if x < 1.0 { x } else { 1.0 };
    if x > 0.0 {
        below_one
    } else {
        0.0
    }
}

/// `gaussian_sum` for one lane, branch-free: every branch of libm's `expf`
/// is computed and the lane's result selected, so that a loop of it over an
/// array vectorises at the width of the target (see [`gaussian_sum_wide`]).
/// The same f32 operations in the same order as libm's `expf` for
/// `x = −s ≤ 0`; only `trunc` and `scalbnf` are written differently, to the
/// same values.
#[inline(always)]
fn gaussian_sum_lane(s: f32) -> f32 {
    // s ≥ 103.972084 (libm's underflow: x ≤ −103.972084 gives 0), ∞ and
    // NaN give 0. Those lanes are computed on s = 0 instead and selected
    // out at the end: their garbage would otherwise hold subnormals (and
    // NaNs), which cost microcode assists on some cores even when unused.
    let live = s < f32::from_bits(0x42cf_f1b5);
    let s = if live { s } else { 0.0 };
    let x = -s;
    // k = (int)(x/ln 2 − 0.5) where |x| > 1.5 ln 2: there (−104 < x) the
    // argument t lies in (−151, −1.5). Adding and subtracting 1.5·2²³
    // rounds |t| < 2²² to the nearest integer, exactly; a negative t
    // rounded down is then moved up by 1: truncation, in float operations
    // only (a saturating f32 → i32 conversion does not vectorise).
    // Elsewhere (|x| ≤ 1.5 ln 2, negative s) the value is not used.
    let t = INV_LN2 * x + -0.5;
    let nearest = (t + ROUND_MAGIC) - ROUND_MAGIC;
    let k_big = if nearest < t { nearest + 1.0 } else { nearest };
    let k = if s > f32::from_bits(0x3f85_1592) {
        k_big
    } else {
        -1.0
    };
    let k = if s > f32::from_bits(0x3eb1_7218) {
        k
    } else {
        0.0
    };
    let hi = x - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr * (P1 + rr * P2);
    let y = 1.0 + (r * c / (2.0 - c) - lo + hi);
    // scalbnf(y, k): pre-scale by 2⁻¹⁰² below k = −126 (exact).
    let deep = k < -126.0;
    let y = if deep {
        y * f32::from_bits(0x0c80_0000)
    } else {
        y
    };
    let k = if deep { k + 102.0 } else { k };
    // 2^k from the bits of k + 127 + 2²³ (exact: an integer below 2²⁴, so
    // its low mantissa bits are k + 127, in [1, 127] here), moved into the
    // exponent field: a bit cast, a subtraction and a shift per lane, no
    // float-to-int conversion. Wrapping, so that no lane can panic.
    let m = (k + (127.0 + 8_388_608.0)).to_bits();
    let y = y * f32::from_bits(m.wrapping_sub(0x4b00_0000) << 23);
    // |x| ≤ 2⁻¹⁴ (and s = 0): 1 + x.
    let y = if s > f32::from_bits(0x3900_0000) {
        y
    } else {
        1.0 + x
    };
    // s ≥ 103.972084, ∞ and NaN: 0 (see above).
    if live {
        y
    } else {
        0.0
    }
}

/// `exp(−s)` of `gaussian_sum` in `N` lanes: lane `l` is
/// [`gaussian_sum_lanes`]' result for `s[l]`, bit for bit, so exactly 1 for
/// `s = 0`, 0 for `s ≥ 105`, `+∞` or NaN, and `libm::expf(−s)` in between
/// (the exponential of eq. 1's product form, §3.1, eq. 1).
///
/// One straight-line, branch-free loop over the lanes (every branch of
/// libm's `expf` computed and selected per lane, no call inside), so that
/// inside code compiled for AVX2 or AVX-512 (`#[target_feature]`, with this
/// function inlined: it is `#[inline(always)]`) LLVM vectorises it 8 or 16
/// lanes wide. It never contracts `a·b + c` into an FMA (Rust does not), so
/// the results are the same bits on every target.
///
/// Error against libm's `expf`: none. This is libm 0.2's `expf` (FreeBSD's
/// `e_expf.c`: reduction by `k·ln 2` in two parts, a degree-2 rational
/// approximation, `scalbnf`) with its branches turned into lane selects; for
/// `x = −s ≤ 0` every branch is the same f32 operations in the same order,
/// `k = (int)(x/ln 2 − 0.5)` is truncated exactly (by rounding with
/// `1.5·2²³`, on the range `(−152, −1.5)` where it is used), and `scalbnf(y, k)` is
/// `y·2⁻¹⁰²·2^(k+102)` below `k = −126` and `y·2^k` above, as libm computes
/// it, so each lane equals `libm::expf(−s)` bit for bit
/// (`kernels/tests/lanes.rs` compares the f32s of `[0, ∞]` at a stride and
/// densely around every branch threshold and the subnormal range, and all
/// of them with `--ignored`). Its error against the true `e^−s` is libm's,
/// under 1 ulp.
///
/// Domain: `s ≥ 0` or NaN (a sum of squares). A negative `s` is outside it:
/// its lane returns `1 − s` (`−0` gives 1), not `expf(−s)`; never NaN,
/// never a panic.
#[inline(always)]
pub fn gaussian_sum_wide<const N: usize>(s: &[f32; N]) -> [f32; N] {
    let mut out = [0.0; N];
    for (o, &s) in out.iter_mut().zip(s) {
        *o = gaussian_sum_lane(s);
    }
    out
}

/// [`reconstruction_weight`] of the product form (§3.1, eq. 1 times the
/// spatial term) for one lane: target `(zi, ni)` against neighbour
/// `(zj, nj)`, `spatial` the pair's `d²/σs²`. The same f32 operations in the
/// same order as the scalar function and as [`weights_product_lanes`],
/// every branch a select.
#[inline(always)]
fn weight_product_lane<const RELATIVE: bool>(
    sigma_z: f32,
    sigma_n: f32,
    (zi, nix, niy, niz): (f32, f32, f32, f32),
    (zj, njx, njy, njz): (f32, f32, f32, f32),
    spatial: f32,
) -> f32 {
    // depth_difference(zi, zj, metric)
    let diff = abs_lane(zj - zi);
    let r = if RELATIVE {
        diff / (0.5 * abs_lane(zi) + 0.5 * abs_lane(zj))
    } else {
        diff
    };
    let r = if r.is_nan() { f32::INFINITY } else { r };
    let dz = if zi == zj { 0.0 } else { r };
    // The normal term: nj·ni, saturated and snapped.
    let cos = saturate_lane(njx * nix + njy * niy + njz * niz);
    let dn = if cos >= 1.0 - NORMAL_COS_SNAP {
        0.0
    } else {
        1.0 - cos
    };
    let a = sigma_z * dz;
    let b = sigma_n * dn;
    let w = saturate_lane(gaussian_sum_lane(a * a + b * b + spatial));
    let nan_normal = nix.is_nan() | niy.is_nan() | niz.is_nan();
    let nan_normal = nan_normal | njx.is_nan() | njy.is_nan() | njz.is_nan();
    let w = if nan_normal { 0.0 } else { w };
    // Two misses weigh 1 whatever their normals.
    if (zi == f32::INFINITY) & (zj == f32::INFINITY) {
        1.0
    } else {
        w
    }
}

/// [`reconstruction_weight`] of the product form (§3.1, eq. 1 times the
/// spatial term `exp(−d²/σs²)`) in `N` lanes: lane `l` weighs neighbour
/// `gj` lane `l` for target `gi` lane `l`, with `spatial[l]` the pair's
/// `d²/σs²` (0 for none, as [`reconstruction_weight`] computes it from
/// `distance2` and `σs`). `p`'s form is not read: this is the product form
/// whatever [`SraaParams::form`] says.
///
/// Each lane is the scalar weight bit for bit: the same f32 operations in
/// the same order (depth difference by the metric, NaN → `+∞`, equal depths
/// → 0; the cosine saturated and snapped by [`NORMAL_COS_SNAP`]; the sigma
/// products; one exponential of the sum, [`gaussian_sum_wide`]; saturated;
/// 0 for a NaN normal on either side; 1 for two misses), each branch a
/// select, so that the loop vectorises at the target's width like
/// [`gaussian_sum_wide`] (it is `#[inline(always)]`).
///
/// Domain and out-of-domain behaviour are [`reconstruction_weight`]'s, lane
/// by lane: unit normals, depths in `[0, ∞]`, finite non-negative
/// parameters, `spatial ≥ 0` (NaN or `+∞` gives 0). A NaN anywhere gives 0
/// (two misses excepted: 1); never a panic.
#[inline(always)]
pub fn weights_product_wide<const N: usize>(
    p: &SraaParams,
    gi: &GeometryWide<N>,
    gj: &GeometryWide<N>,
    spatial: &[f32; N],
) -> [f32; N] {
    // The metric chosen outside the loop: one branch-free loop each.
    match p.depth_metric() {
        DepthMetric::Absolute => weights_product_loop::<N, false>(p, gi, gj, spatial),
        DepthMetric::Relative => weights_product_loop::<N, true>(p, gi, gj, spatial),
    }
}

/// The lane loop of [`weights_product_wide`] for one depth metric.
// Lane `l` indexes the five input arrays and the output alike.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn weights_product_loop<const N: usize, const RELATIVE: bool>(
    p: &SraaParams,
    gi: &GeometryWide<N>,
    gj: &GeometryWide<N>,
    spatial: &[f32; N],
) -> [f32; N] {
    let (sigma_z, sigma_n) = (p.sigma_z, p.sigma_n);
    let mut out = [0.0; N];
    for l in 0..N {
        out[l] = weight_product_lane::<RELATIVE>(
            sigma_z,
            sigma_n,
            (gi.depth[l], gi.nx[l], gi.ny[l], gi.nz[l]),
            (gj.depth[l], gj.nx[l], gj.ny[l], gj.nz[l]),
            spatial[l],
        );
    }
    out
}
