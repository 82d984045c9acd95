//! The per-pixel antialiasing pass of SRAA (§3, pass 2), for a whole frame's
//! slices: every layer of the four geometric subsamples of a pixel
//! reconstructed from the shaded samples around it (eq. 1, gated by eq. 2 per
//! light, §3.1–3.3), then the box resolve ([`resolve_pixel`]).
//!
//! [`Resolver::resolve`] gives, bit for bit, what the per-subsample,
//! per-layer-group path gives ([`reconstruct_layers`] and
//! [`reconstruct_layers_material`] over [`neighbourhood`], summed per
//! subsample, then [`resolve_pixel`]); `kernels/tests/properties.rs` holds
//! the two together. What it does differently is only the order of the work:
//! - the neighbourhood's geometry, shadow bits and colours are gathered once
//!   per pixel, not once per subsample and layer group;
//! - the weights of one neighbour for the four subsamples are computed
//!   together, one subsample per lane of a `Vec4` ([`weights_product_lanes`],
//!   [`gaussian_sum_lanes`]), in the same f32 operations as
//!   [`reconstruction_weight`], so to the same bits;
//! - the spatial term's `d²/σs²` of each (subsample, neighbour) pair is a
//!   table built once per frame ([`Resolver::new`]);
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

use glam::{BVec4A, Vec2, Vec3, Vec3A, Vec4};

use super::{
    albedo_root, neighbourhood, reconstruct_layers, reconstruct_layers_material,
    reconstruction_weight, resolve_pixel, root_difference, DepthMetric, Geometry, LayeredSample,
    SraaParams, WeightForm, MAX_LAYERS, NORMAL_COS_SNAP, SUBPIXEL_OFFSETS,
};
use crate::sum::WeightedSum4;

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
    /// The spatial exponent `d²/σs²` of each (slot, subsample), one lane per
    /// subsample, as [`reconstruction_weight`] computes it.
    spatial: [Vec4; SLOTS],
}

impl<'g> Resolver<'g> {
    /// A resolver for `params`, with layer `i` of each group gated by shadow
    /// bit `gates[i]` (eq. 2; `None`: ungated), and the material gate's
    /// `tolerance` ([`super::ALBEDO_TOLERANCE`] by default) for groups that
    /// carry albedos. At most [`MAX_LAYERS`] gates are used.
    pub fn new(params: &SraaParams, gates: &'g [Option<u8>], tolerance: f32) -> Self {
        let shaded = params.shaded_offset();
        let mut distance2 = [[0.0; SLOTS]; 4];
        let mut spatial = [Vec4::ZERO; SLOTS];
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
            spatial,
        }
    }

    /// The antialiased colour of pixel `(x, y)`: each subsample's primary
    /// layers reconstructed on `primary` from `frame.primary` (material-gated
    /// when both `primary.albedo` and `frame.albedo` are given), plus, where
    /// its secondary depth is not NaN, its secondary layers on `secondary`
    /// from `frame.secondary`; each subsample's colour is the sum of its
    /// layers, and the pixel the box resolve of the four ([`resolve_pixel`]).
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
        self.add_group(frame, &hood, &frame.primary, primary, albedo, &mut subs);
        if let (Some(group), Some(targets)) = (frame.secondary.as_ref(), secondary) {
            if targets.geometry.iter().any(|g| !g.depth.is_nan()) {
                let mut s2 = [Vec3::ZERO; 4];
                self.add_group(frame, &hood, group, targets, None, &mut s2);
                for k in 0..4 {
                    if !targets.geometry[k].depth.is_nan() {
                        subs[k] += s2[k];
                    }
                }
            }
        }
        resolve_pixel(&subs)
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
    #[inline(always)]
    fn add_group(
        &self,
        frame: &ShadedFrame,
        hood: &Hood,
        group: &ShadedGroup,
        targets: &Subsamples,
        albedo: Option<[Vec3; 4]>,
        out: &mut [Vec3; 4],
    ) {
        let n = self.gates.len();
        let scan = LayerScan::new(frame, hood, group, n);
        if scan.live == 0 {
            return;
        }
        if scan.live & scan.varied == 0 {
            // Every layer that is not black is uniform: no weight needed.
            for (i, &uniform) in scan.uniform[..n].iter().enumerate() {
                if scan.live & (1 << i) != 0 {
                    add_to_each(out, uniform);
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
                add_to_each(out, scan.uniform[i]);
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
        let mut weights = [[0.0f64; 4]; SLOTS];
        let mut nonzero = 0u32;
        let lanes = GeometryLanes::new(&targets.geometry);
        let gate = albedo.map(|a| MaterialGateLanes::new(a, self.tolerance));
        for slot in hood.slots() {
            let mut w = match self.params.form() {
                WeightForm::Product => {
                    weights_product_lanes(&self.params, &lanes, &geometry[slot], self.spatial[slot])
                }
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
            weights[slot] = w.to_array().map(|w| w as f64);
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
        resolve_pixel(&subs)
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

/// One pass over a group's colours in the 3×3 neighbourhood, before any
/// weight: which layers can change a subsample's sum of layers and which
/// reconstruct to one colour whatever the weights.
///
/// A layer without a colour that is finite and not exactly black anywhere
/// in the neighbourhood (`live` clear) reconstructs to black. A layer with
/// one colour, bit for bit, wherever it is finite (`varied` clear)
/// reconstructs to that colour: each product `w·C` is exact in f64 and the
/// normalised sum is within a few f64 ulps of `C`, which rounds back to `C`
/// in f32; the fallback is `C` too.
struct LayerScan {
    /// Bit `i`: layer `i` has a finite colour that is not black.
    live: u32,
    /// Bit `i`: layer `i`'s finite colours are not all one colour.
    varied: u32,
    /// Layer `i`'s colour, where `varied` is clear.
    uniform: [Vec3A; MAX_LAYERS],
    /// Each slot's index, in `frame.colors`, of the group's first layer.
    base: [usize; SLOTS],
    /// Bit `i` of a slot: its colour of layer `i` is finite.
    finite: [u32; SLOTS],
}

impl LayerScan {
    /// The scan of layers `0..n` of `group` over the valid slots of `hood`.
    // Layer `i` indexes bit masks and the per-layer arrays alike.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn new(frame: &ShadedFrame, hood: &Hood, group: &ShadedGroup, n: usize) -> Self {
        let mut live = 0u32;
        let mut varied = 0u32;
        let mut seen = 0u32;
        let mut uniform = [Vec3A::ZERO; MAX_LAYERS];
        let mut base = [0usize; SLOTS];
        let mut finite = [0u32; SLOTS];
        for slot in hood.slots() {
            base[slot] = hood.index[slot] * frame.layers + group.first_layer;
            for i in 0..n {
                // In one vector register: three lanes compared at once.
                let c = Vec3A::from(color_at(frame, base[slot] + i));
                if c.is_finite_mask().all() {
                    finite[slot] |= 1 << i;
                    if c.cmpne(Vec3A::ZERO).any() {
                        live |= 1 << i;
                    }
                    if seen & (1 << i) == 0 {
                        seen |= 1 << i;
                        uniform[i] = c;
                    } else if c.cmpne(uniform[i]).any() {
                        // (−0 and +0 count as one colour: either adds
                        // nothing to a subsample's sum of layers.)
                        varied |= 1 << i;
                    }
                }
            }
        }
        Self {
            live,
            varied,
            uniform,
            base,
            finite,
        }
    }
}

/// Every neighbour's weights for the four subsamples
/// ([`Resolver::neighbour_weights`]) and its shadow bits.
struct NeighbourWeights {
    /// Slot by slot, one lane per subsample, widened to f64.
    weights: [[f64; 4]; SLOTS],
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
                    let (w, keep) = (self.weights[slot], KEEP_LANES[differ]);
                    [
                        w[0] * keep[0],
                        w[1] * keep[1],
                        w[2] * keep[2],
                        w[3] * keep[3],
                    ]
                }
                None => self.weights[slot],
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

/// The in-image part of a pixel's 3×3 neighbourhood: a bit per slot
/// (row-major) and each slot's pixel index.
struct Hood {
    valid: u32,
    index: [usize; SLOTS],
}

impl Hood {
    #[inline(always)]
    fn new(frame: &ShadedFrame, x: u32, y: u32) -> Self {
        let mut valid = 0;
        let mut index = [0; SLOTS];
        for (slot, i) in index.iter_mut().enumerate() {
            let px = x as i64 + (slot % 3) as i64 - 1;
            let py = y as i64 + (slot / 3) as i64 - 1;
            if px >= 0 && py >= 0 && px < frame.width as i64 && py < frame.height as i64 {
                valid |= 1 << slot;
                *i = py as usize * frame.width as usize + px as usize;
            }
        }
        Self { valid, index }
    }

    /// The valid slots in row-major order (that of [`neighbourhood`]).
    fn slots(&self) -> impl Iterator<Item = usize> {
        slots(self.valid)
    }
}

/// Colour `i` of the frame's flat layer array; black past its end.
#[inline]
fn color_at(frame: &ShadedFrame, i: usize) -> Vec3 {
    frame.colors.get(i).copied().unwrap_or(Vec3::ZERO)
}

/// The slots set in `mask`, in increasing (row-major) order.
#[inline]
fn slots(mut mask: u32) -> impl Iterator<Item = usize> {
    core::iter::from_fn(move || {
        if mask == 0 {
            return None;
        }
        let slot = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        Some(slot)
    })
}

/// The four subsamples' geometry, one subsample per lane.
#[derive(Clone, Copy, Debug)]
pub struct GeometryLanes {
    nx: Vec4,
    ny: Vec4,
    nz: Vec4,
    depth: Vec4,
    /// Lanes whose normal has a NaN component.
    nan_normal: BVec4A,
}

impl GeometryLanes {
    /// Lanes from four geometries.
    pub fn new(g: &[Geometry; 4]) -> Self {
        let nx = Vec4::new(g[0].normal.x, g[1].normal.x, g[2].normal.x, g[3].normal.x);
        let ny = Vec4::new(g[0].normal.y, g[1].normal.y, g[2].normal.y, g[3].normal.y);
        let nz = Vec4::new(g[0].normal.z, g[1].normal.z, g[2].normal.z, g[3].normal.z);
        Self {
            nx,
            ny,
            nz,
            depth: Vec4::new(g[0].depth, g[1].depth, g[2].depth, g[3].depth),
            nan_normal: nx.is_nan_mask() | ny.is_nan_mask() | nz.is_nan_mask(),
        }
    }
}

/// `sat(x)` of §3.1 per lane ([`super::saturate`]): NaN gives 0.
#[inline]
fn saturate_lanes(x: Vec4) -> Vec4 {
    // `max` returns its argument, 0, for a NaN lane (SSE's `maxps` returns
    // its second operand, the scalar fallback the number).
    x.max(Vec4::ZERO).min(Vec4::ONE)
}

/// [`reconstruction_weight`] of the product form (eq. 1 times the spatial
/// term) for four targets `gi` (lanes) against one neighbour `gj`, with
/// `spatial` the lanes' `d²/σs²` (0 for none). The same f32 operations in
/// the same order as the scalar function, lane by lane, and the same
/// exponential ([`gaussian_sum_lanes`]): each lane equals the scalar weight
/// bit for bit. Domain and out-of-domain behaviour are the scalar function's.
#[inline]
pub fn weights_product_lanes(
    p: &SraaParams,
    gi: &GeometryLanes,
    gj: &Geometry,
    spatial: Vec4,
) -> Vec4 {
    let inf = Vec4::splat(f32::INFINITY);
    // depth_difference(zi, zj, metric)
    let zi = gi.depth;
    let zj = Vec4::splat(gj.depth);
    let diff = (zj - zi).abs();
    let r = match p.depth_metric() {
        DepthMetric::Absolute => diff,
        DepthMetric::Relative => {
            diff / (Vec4::splat(0.5) * zi.abs() + Vec4::splat(0.5 * gj.depth.abs()))
        }
    };
    let r = Vec4::select(r.is_nan_mask(), inf, r);
    let dz = Vec4::select(zi.cmpeq(zj), Vec4::ZERO, r);
    // The normal term: gj.normal.dot(gi.normal), saturated and snapped.
    let n = gj.normal;
    let cos = saturate_lanes(
        Vec4::splat(n.x) * gi.nx + Vec4::splat(n.y) * gi.ny + Vec4::splat(n.z) * gi.nz,
    );
    let dn = Vec4::select(
        cos.cmpge(Vec4::splat(1.0 - NORMAL_COS_SNAP)),
        Vec4::ZERO,
        Vec4::ONE - cos,
    );
    let a = Vec4::splat(p.sigma_z) * dz;
    let b = Vec4::splat(p.sigma_n) * dn;
    let w = saturate_lanes(gaussian_sum_lanes(a * a + b * b + spatial));
    let w = if gj.normal.is_nan() {
        Vec4::ZERO
    } else {
        Vec4::select(gi.nan_normal, Vec4::ZERO, w)
    };
    if gj.depth == f32::INFINITY {
        // Two misses weigh 1 whatever their normals.
        Vec4::select(zi.cmpeq(inf), Vec4::ONE, w)
    } else {
        w
    }
}

// libm's expf (FreeBSD's e_expf.c), constants and thresholds.
const LN2_HI: f32 = 6.931_457_5e-1; // 0x3f317200
const LN2_LO: f32 = 1.428_606_8e-6; // 0x35bfbe8e
const INV_LN2: f32 = 1.442_695_1; // 0x3fb8aa3b
const P1: f32 = 1.666_662_5e-1; // 0xaaaa8f.0p-26
const P2: f32 = -2.766_733_3e-3; // -0xb55215.0p-32

/// `exp(−s)` of `gaussian_sum` in four lanes: exactly 1 for `s = 0`,
/// 0 for `s ≥ 105`, `+∞` or NaN, and `libm::expf(−s)` in between.
///
/// Error against libm's `expf`: none. This is libm 0.2's `expf` (FreeBSD's
/// `e_expf.c`: reduction by `k·ln 2` in two parts, a degree-2 rational
/// approximation, `scalbnf`) with its branches turned into lane selects; for
/// `x = −s ≤ 0` every branch is the same f32 operations in the same order,
/// and `scalbnf(y, k)` is `y·2⁻¹⁰²·2^(k+102)` below `k = −126` and `y·2^k`
/// above, as libm computes it, so each lane equals `libm::expf(−s)` bit for
/// bit (`kernels/tests/lanes.rs` compares the f32s of `[0, ∞]` at a stride
/// and densely around every branch threshold and the subnormal range, and
/// all of them with `--ignored`). Its error against the true `e^−s` is
/// libm's, under 1 ulp. The WGSL twin (`subcone_gaussian_sum`) keeps the
/// GPU's `exp`, whose tolerance in the kernel conformance table is unchanged.
///
/// Domain: `s ≥ 0` or NaN, as `gaussian_sum` is called (a sum of squares).
/// A negative `s` is outside it: its lane returns `1 − s`, not `expf(−s)`
/// (never NaN, never a panic).
#[inline]
pub fn gaussian_sum_lanes(s: Vec4) -> Vec4 {
    let x = -s;
    // |x| > 1.5 ln 2: k = (int)(x/ln 2 − 0.5); 0.5 ln 2 < |x| ≤ 1.5 ln 2:
    // k = −1; below: k = 0 (for which the reduction below is exact: hi = x,
    // lo = 0).
    let k_big = (Vec4::splat(INV_LN2) * x + Vec4::splat(-0.5)).trunc();
    let k = Vec4::select(
        s.cmpgt(Vec4::splat(f32::from_bits(0x3f85_1592))),
        k_big,
        Vec4::splat(-1.0),
    );
    let k = Vec4::select(
        s.cmpgt(Vec4::splat(f32::from_bits(0x3eb1_7218))),
        k,
        Vec4::ZERO,
    );
    let hi = x - k * Vec4::splat(LN2_HI);
    let lo = k * Vec4::splat(LN2_LO);
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr * (Vec4::splat(P1) + rr * Vec4::splat(P2));
    let y = Vec4::ONE + (r * c / (Vec4::splat(2.0) - c) - lo + hi);
    // scalbnf(y, k): pre-scale by 2⁻¹⁰² below k = −126 (exact), then one
    // rounding multiplication by a normal power of two.
    let deep = k.cmplt(Vec4::splat(-126.0));
    let (y, k) = if deep.any() {
        (
            Vec4::select(deep, y * Vec4::splat(f32::from_bits(0x0c80_0000)), y),
            Vec4::select(deep, k + Vec4::splat(102.0), k),
        )
    } else {
        (y, k)
    };
    // 2^k from the bits of k + 127 + 2²³ (exact: an integer below 2²⁴, so
    // its low mantissa bits are k + 127), moved into the exponent field: a
    // bit cast, a subtraction and a shift per lane, no float-to-int
    // conversion.
    let m = (k + Vec4::splat(127.0 + 8_388_608.0)).to_array();
    let e = m.map(|m| (m.to_bits().wrapping_sub(0x4b00_0000)) << 23);
    let y = y * Vec4::from_array(e.map(f32::from_bits));
    // |x| ≤ 2⁻¹⁴ (and s = 0): 1 + x.
    let y = Vec4::select(
        s.cmpgt(Vec4::splat(f32::from_bits(0x3900_0000))),
        y,
        Vec4::ONE + x,
    );
    // x ≤ −103.972084 underflows to 0 in libm; s ≥ 105 (EXP_UNDERFLOW), ∞ and
    // NaN give 0 in gaussian_sum.
    Vec4::select(
        s.cmplt(Vec4::splat(f32::from_bits(0x42cf_f1b5))),
        y,
        Vec4::ZERO,
    )
}
