//! The parameters of a CTSS trace ([`CtssParams`], uploaded unchanged as a
//! uniform) and their flag bits: CTSS-R (§4), the §5.3 group splits, the
//! paper's groups and masks.

use crate::aggregate::Weighting;
use crate::cone::{OcclusionThresholds, OCCLUSION_EPS};
use crate::mask::MaskPlacement;

/// `flags` bit: CTSS-R, stop at the first hard hit instead of full occlusion (§4).
pub const FLAG_RELAXED: u32 = 1;
/// `flags` bit: subdivide hit groups whose normal varies across the cone or
/// that are long for their depth, and shade them with extra samples (§5.3,
/// [`group_needs_split`], [`split_group`]). Off by default; both backends
/// (the WGSL twin is [`TRACE_WGSL`]).
///
/// [`group_needs_split`]: super::group_needs_split
/// [`split_group`]: super::split_group
/// [`TRACE_WGSL`]: super::TRACE_WGSL
pub const FLAG_SPLIT_GROUPS: u32 = 1 << 1;
/// `flags` bit: the paper's hit groups and masks (the `-paper` methods). A
/// group then runs as long as the cone touches any surface, and its mask is
/// the half-plane of its peak occlusion alone. Without it (the default) a
/// group also ends where the nearest object changes
/// ([`ConeStepper::advance_object`]) or where the occlusion rises again after
/// a dip of [`GROUP_DIP`] (a second surface within the cone), and a group
/// whose surface the cone passes through is masked from both of its sides
/// ([`group_mask`]).
///
/// [`ConeStepper::advance_object`]: super::ConeStepper::advance_object
/// [`group_mask`]: super::group_mask
pub const FLAG_PAPER: u32 = 1 << 2;

/// Cone coverage (§5.1's multiplier of the pixel's cone, eq. 3) of the CTSS
/// methods by default: a cone of radius `0.6·√2/2 ≈ 0.42` pixels instead of
/// the paper's `0.71` (the circle through the pixel's corners, coverage 1,
/// kept by the `-paper` methods). The half-plane mask overestimates how much
/// of the cross-section a curved or small object covers, and a wide cone
/// blurs each edge over more than its pixel; both cost more than the
/// narrower cone loses at the pixel's corners. Swept over 0.5–1 on the
/// `primitives` and `random-box` scenes at 96×64 and 320×180, against
/// `ssaa64`/`ssaa256`: 0.6 gave the least silhouette error on both scenes at
/// both sizes.
pub const CONE_COVERAGE: f32 = 0.6;

/// Fall and rise of the cone occlusion inside a hit group, below its peak
/// and then above the lowest value since, that ends the group and opens a
/// new one (beyond the paper, off with [`FLAG_PAPER`]): the cone has passed
/// one surface and met another one behind it.
pub const GROUP_DIP: f32 = 0.1;

/// Parameters of a CTSS trace.
///
/// `#[repr(C)]`, 48 bytes, only `f32`/`u32` fields (explicit padding): uploaded
/// unchanged as a uniform by GPU backends.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct CtssParams {
    /// `tan θ` of the pixel's cone (eq. 3, [`cone_tan_theta`](crate::cone::cone_tan_theta)).
    pub tan_theta: f32,
    /// Minimum step factor α of `s_min = α·R_c` (§3.1; paper: 0.5).
    pub alpha: f32,
    /// ε of the occlusion thresholds (§3.2; authors: 0.01).
    pub eps: f32,
    /// First depth evaluated.
    pub t_min: f32,
    /// Depth at which the ray leaves the scene.
    pub t_max: f32,
    /// The authors' minimum sample weight (0.01); ours is 0, see
    /// [`sample_weight`].
    ///
    /// [`sample_weight`]: crate::aggregate::sample_weight
    pub min_sample_weight: f32,
    /// Step budget: no trace takes more SDF evaluations than this.
    pub max_steps: u32,
    /// Sample cap (the authors use 8, `CTSS_NUM_SAMPLES`).
    pub max_samples: u32,
    /// Visibility threshold k (§5.1): stop once `bitCount(M) ≥ k`. 32 = off.
    pub visibility_k: u32,
    /// Bit 0: [`FLAG_RELAXED`]. Bit 1: [`FLAG_SPLIT_GROUPS`]. Bit 2: [`FLAG_PAPER`]. Bits 8..16: [`MaskPlacement`]. Bits 16..24: [`Weighting`].
    pub flags: u32,
    /// Padding to a multiple of 16 bytes (WGSL uniform layout).
    pub _pad: [u32; 2],
}

impl CtssParams {
    /// The paper's configuration for a cone of `tan_theta`: α = 0.5, ε = 0.01, up
    /// to 8 samples, k = 32, visibility weights, the derived mask placement, no
    /// minimum sample weight, `t` in `[0, 10⁴]`, 1024 steps.
    pub const fn new(tan_theta: f32) -> Self {
        Self {
            tan_theta,
            alpha: 0.5,
            eps: OCCLUSION_EPS,
            t_min: 0.0,
            t_max: 1.0e4,
            min_sample_weight: 0.0,
            max_steps: 1024,
            max_samples: 8,
            visibility_k: 32,
            flags: 0,
            _pad: [0; 2],
        }
    }

    /// CTSS-R (§4): terminate at the first hard hit (half cone occlusion).
    pub const fn relaxed(self, on: bool) -> Self {
        self.with_flag(FLAG_RELAXED, on)
    }

    /// Subdivide hit groups at internal edges (§5.3, [`FLAG_SPLIT_GROUPS`]).
    pub const fn with_split_groups(self, on: bool) -> Self {
        self.with_flag(FLAG_SPLIT_GROUPS, on)
    }

    /// The paper's hit groups and masks ([`FLAG_PAPER`]).
    pub const fn paper(self, on: bool) -> Self {
        self.with_flag(FLAG_PAPER, on)
    }

    /// `flag` (one of the `FLAG_*` bits) set or cleared, the other bits kept.
    const fn with_flag(mut self, flag: u32, on: bool) -> Self {
        self.flags = if on {
            self.flags | flag
        } else {
            self.flags & !flag
        };
        self
    }

    /// Whether the paper's hit groups and masks are on ([`FLAG_PAPER`]).
    pub const fn is_paper(&self) -> bool {
        self.flags & FLAG_PAPER != 0
    }

    /// Whether hit groups are subdivided ([`FLAG_SPLIT_GROUPS`]).
    pub const fn splits_groups(&self) -> bool {
        self.flags & FLAG_SPLIT_GROUPS != 0
    }

    /// Choose the mask placement.
    pub const fn with_placement(mut self, p: MaskPlacement) -> Self {
        self.flags = (self.flags & !0xff00) | ((p as u32) << 8);
        self
    }

    /// Choose the sample weighting.
    pub const fn with_weighting(mut self, w: Weighting) -> Self {
        self.flags = (self.flags & !0xff0000) | ((w as u32) << 16);
        self
    }

    /// Set the visibility threshold k (clamped to 1..=32).
    pub const fn with_visibility_k(mut self, k: u32) -> Self {
        self.visibility_k = if k == 0 {
            1
        } else if k > 32 {
            32
        } else {
            k
        };
        self
    }

    /// Set the depth range.
    pub const fn with_range(mut self, t_min: f32, t_max: f32) -> Self {
        self.t_min = t_min;
        self.t_max = t_max;
        self
    }

    /// Set the step budget.
    pub const fn with_max_steps(mut self, n: u32) -> Self {
        self.max_steps = n;
        self
    }

    /// The authors' code's choices where they differ from the paper: the 0.01
    /// minimum sample weight and their mask placement. (Their narrower cone is a
    /// [`PixelFootprint`](crate::cone::PixelFootprint) of the tangent.)
    pub const fn authors_code(self) -> Self {
        let mut s = self.with_placement(MaskPlacement::AuthorsCode);
        s.min_sample_weight = 0.01;
        s
    }

    /// Whether CTSS-R is on.
    pub const fn is_relaxed(&self) -> bool {
        self.flags & FLAG_RELAXED != 0
    }

    /// The mask placement.
    pub const fn placement(&self) -> MaskPlacement {
        MaskPlacement::from_u32((self.flags >> 8) & 0xff)
    }

    /// The weighting.
    pub const fn weighting(&self) -> Weighting {
        Weighting::from_u32((self.flags >> 16) & 0xff)
    }

    /// The thresholds for this ε.
    pub const fn thresholds(&self) -> OcclusionThresholds {
        OcclusionThresholds::with_eps(self.eps)
    }
}
