//! Hit group subdivision (§5.2–5.3)
//!
//! One hit group gets one shaded sample (§3.3), so an *internal* edge, where the
//! cone never leaves the surface (two faces of one box seen across the pixel),
//! is one group, one normal, one colour for the whole pixel (§5.2, Fig. 9–10).
//! §5.3 proposes to subdivide a group when its normals at different scales
//! disagree, or when its length-to-depth ratio is large. We do both
//! ([`group_needs_split`]) and shade a split group at four points spread across
//! the cone's cross-section ([`split_group`]), each with its own normal and
//! shading and the quarter of the group's mask nearest to it.

use crate::math::Euclidean;
use glam::{Vec2, Vec3};

use super::params::CtssParams;
use super::sphere::sphere_trace_split;
use super::stepper::GroupSample;
use crate::cone::cone_radius;

/// Smallest cosine between a group's fine and coarse normal that keeps the
/// group whole: `cos 20°`. Two faces of a box meet at 90°; a coarse normal
/// whose taps straddle the edge is bent towards the other face by a share of
/// that, the larger the nearer the edge is to the sample point (the kernel
/// test `split_on_a_box_edge` pins a point a fifth of a cone radius away).
/// On a sphere of radius `ρ` the tetrahedral differences' second-order error
/// bends the coarse normal by at most about `0.6·R_c/ρ` radians, so only
/// surfaces curved within about two cone radii split for their curvature,
/// where one normal per pixel is wrong as well.
pub const SPLIT_MIN_COS: f32 = 0.939_692_6;

/// Largest group length, in cone radii at the sample depth, that keeps the
/// group whole (§5.3's length-to-depth ratio, normalised by `tan θ` so it does
/// not depend on the resolution). A plane seen at angle `φ` from its normal
/// makes a group about `2/cos φ` cone radii long (from `ω = ε` to `ω = 1 − ε`),
/// so 8 splits surfaces seen beyond ~75°, whose pixel footprint is at least
/// four times longer than wide: grazing floors and walls, where shading and
/// texture vary across the pixel.
pub const SPLIT_LENGTH_RATIO: f32 = 8.0;

/// SDF evaluations each sub-sample's sphere trace may take.
pub const SPLIT_MAX_STEPS: u32 = 32;

/// The visibility mask's cells split into the four quadrants of the cone's
/// cross-section, in the order of [`SPLIT_OFFSETS`]: (−x, −y), (+x, −y),
/// (−x, +y), (+x, +y). No cell centre lies on an axis, so the four masks are
/// disjoint, 8 cells each, and their union is the full mask (unit-tested
/// against [`cell_centre`](crate::mask::cell_centre)).
pub const SPLIT_QUADRANTS: [u32; 4] = [0x0000_1C73, 0x0000_E38C, 0x31C7_0000, 0xCE38_0000];

/// Mean cell centre of each quadrant of [`SPLIT_QUADRANTS`], in cone radii:
/// `±(11/8)·s/3` with `s` = [`GRID_SCALE`](crate::mask::GRID_SCALE), ≈ 0.431
/// (the quarter disk's centroid is at 0.424).
pub const SPLIT_OFFSETS: [Vec2; 4] = {
    const A: f32 = 11.0 / 8.0 * crate::mask::GRID_SCALE / 3.0;
    [
        Vec2::new(-A, -A),
        Vec2::new(A, -A),
        Vec2::new(-A, A),
        Vec2::new(A, A),
    ]
};

/// Whether a hit group hides an internal edge and needs extra samples (§5.3).
///
/// `n_fine` is the normal at the sample point from small differences (the one
/// shading uses), `n_coarse` the normal at the same point from differences of
/// step [`coarse_normal_step`] (about the cone radius): "surface normals at
/// different scales". Where a box edge or a crease crosses the pixel's
/// footprint, the coarse taps straddle it and the two disagree; on a plane
/// they are equal. `group_length = t_exit − t_entry` and `depth` the sample's
/// depth give §5.3's length-to-depth ratio, measured in cone radii
/// (`group_length / (depth·tan θ)`).
///
/// Splits when the normals differ by more than 20° ([`SPLIT_MIN_COS`]) or the
/// group is longer than [`SPLIT_LENGTH_RATIO`] cone radii.
///
/// Domain: any. A zero or non-finite normal does not take part in the angle
/// test; a NaN or infinite length, a non-positive or non-finite cone radius
/// does not take part in the length test: a test whose inputs are not finite
/// never votes for a split (and nothing panics).
///
/// [`coarse_normal_step`]: super::coarse_normal_step
#[inline]
pub fn group_needs_split(
    n_fine: Vec3,
    n_coarse: Vec3,
    group_length: f32,
    depth: f32,
    params: &CtssParams,
) -> bool {
    let rc = cone_radius(depth, params.tan_theta);
    let long = rc.is_finite()
        && rc > 0.0
        && group_length.is_finite()
        && group_length > SPLIT_LENGTH_RATIO * rc;
    let (a, b) = (n_fine.unit_or_zero(), n_coarse.unit_or_zero());
    let bent = a != Vec3::ZERO && b != Vec3::ZERO && a.dot(b) < SPLIT_MIN_COS;
    long || bent
}

/// The group's weight `w` shared between its four sub-samples in proportion to
/// the visible cells of each quadrant: `w_j = w · bitCount(v & Q_j) / bitCount(v)`
/// for the correlated mask `v` and the quadrant masks `Q_j`
/// ([`SPLIT_QUADRANTS`]).
///
/// The `Q_j` partition the grid, so `Σ_j w_j = w` (up to rounding) and eq. 6's
/// weights, the global mask `M` and the background weight are exactly those of
/// the unsplit group: splitting moves colour within the group's share of the
/// pixel, never weight between groups. With visibility weights (the default,
/// no floor) this is `w_j = bitCount(v & Q_j)/32`, the sub-sample's own share
/// of the pixel, i.e. a 2×2 supersampling of the group's coverage.
///
/// `None` (do not split) when `v` is empty (the group is hidden; with a
/// minimum weight or uniform weights it keeps its single sample) or `w` is not
/// finite.
#[inline]
pub fn split_weights(visible: u32, weight: f32) -> Option<[f32; 4]> {
    let n = visible.count_ones();
    if n == 0 || !weight.is_finite() {
        return None;
    }
    let per_cell = weight / n as f32;
    Some(SPLIT_QUADRANTS.map(|q| (visible & q).count_ones() as f32 * per_cell))
}

/// Direction of the sub-ray through offset `offset` (in cone radii) of the
/// cross-section: `normalize(dir + tan θ·(offset.x·right + offset.y·up))`,
/// which passes through `o + t·dir + R_c(t)·(offset.x·right + offset.y·up)` at
/// every depth `t` (up to the normalisation, `1 + O(tan²θ)`). Returns `dir`
/// when the result is zero or not finite.
#[inline]
pub fn split_direction(dir: Vec3, right: Vec3, up: Vec3, tan_theta: f32, offset: Vec2) -> Vec3 {
    let d = dir + (tan_theta * offset.x) * right + (tan_theta * offset.y) * up;
    let n = d.unit_or_zero();
    if n == Vec3::ZERO {
        dir
    } else {
        n
    }
}

/// Parameters of a sub-sample's sphere trace: the same cone and thresholds,
/// depths from the group's backtraced entry (eq. 10: the cone there does not
/// reach the surface, so every sub-ray starts outside it) to two cone radii
/// past the group's last depth, at most [`SPLIT_MAX_STEPS`] evaluations.
pub fn split_trace_params(params: &CtssParams, sample: &GroupSample) -> CtssParams {
    let last = sample.t_exit.max(sample.t_occlusion).max(sample.t);
    let hi = last + 2.0 * cone_radius(last, params.tan_theta);
    params
        .with_range(sample.t_entry, hi.min(params.t_max))
        .with_max_steps(SPLIT_MAX_STEPS)
}

/// Orthonormal axes `(right, up)` of the cone's cross-section for a ray `dir`,
/// from the camera's up vector (the authors take `cross(rd, world_up)`).
///
/// Falls back to another axis when `dir ∥ up_hint`; returns `(X, Y)` for a zero
/// or non-finite `dir`.
pub fn cross_section_frame(dir: Vec3, up_hint: Vec3) -> (Vec3, Vec3) {
    let d = dir.unit_or_zero();
    if d == Vec3::ZERO {
        return (Vec3::X, Vec3::Y);
    }
    let mut right = d.cross(up_hint).unit_or_zero();
    if right == Vec3::ZERO {
        right = d.any_orthonormal_vector();
    }
    // For a camera looking down −z with +y up this gives right = +x, up = +y.
    (right, right.cross(d))
}

/// The pixel's ray and its cross-section axes ([`cross_section_frame`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitRay {
    /// Ray origin.
    pub origin: Vec3,
    /// Unit ray direction.
    pub dir: Vec3,
    /// Cross-section axis `x` of the mask.
    pub right: Vec3,
    /// Cross-section axis `y` of the mask.
    pub up: Vec3,
}

impl SplitRay {
    /// The ray from `origin` along the unit `dir`, its cross-section axes
    /// taken from the camera's `up_hint` by [`cross_section_frame`].
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3, up_hint: Vec3) -> Self {
        let (right, up) = cross_section_frame(dir, up_hint);
        Self {
            origin,
            dir,
            right,
            up,
        }
    }
}

/// One sub-sample of a split group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitPart {
    /// Its share of the group's weight ([`split_weights`]); 0: not traced.
    pub weight: f32,
    /// Direction of its sub-ray ([`split_direction`]).
    pub dir: Vec3,
    /// Depth of its hit along `dir`, or `None` when the sub-ray found no
    /// surface in range: the caller shades the group's own sample for it, as
    /// unsplit CTSS would.
    pub t: Option<f32>,
}

/// A split hit group: four parts and the SDF evaluations their traces took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitGroup {
    /// The sub-samples, in the order of [`SPLIT_QUADRANTS`].
    pub parts: [SplitPart; 4],
    /// SDF evaluations of the sub-traces.
    pub steps: u32,
}

/// Subdivide a hit group (§5.3): for every quadrant of the cross-section with
/// visible cells, sphere-trace the sub-ray through the quadrant's mean cell
/// centre ([`SPLIT_OFFSETS`], [`split_direction`]) over the group's depths
/// ([`split_trace_params`]) with `sdf` (`(surface distance, safe step)` as in
/// [`sphere_trace_split`]). `visible` and `weight` are what
/// [`ConeStepper::record`] returned for the group. The caller shades each
/// part with a positive weight at its hit (own normal, own shading) and adds
/// it to eq. 6 with its weight, instead of the group's single sample.
///
/// `None` when [`split_weights`] declines (nothing visible). Every sub-trace
/// ends within [`SPLIT_MAX_STEPS`]; NaN distances end it without a hit.
///
/// [`ConeStepper::record`]: super::ConeStepper::record
pub fn split_group<S>(
    params: &CtssParams,
    sample: &GroupSample,
    ray: &SplitRay,
    visible: u32,
    weight: f32,
    mut sdf: S,
) -> Option<SplitGroup>
where
    S: FnMut(Vec3) -> (f32, f32),
{
    let weights = split_weights(visible, weight)?;
    let sub = split_trace_params(params, sample);
    let mut steps = 0u32;
    let mut parts = [SplitPart {
        weight: 0.0,
        dir: ray.dir,
        t: None,
    }; 4];
    for (j, part) in parts.iter_mut().enumerate() {
        if !(weights[j] > 0.0) {
            continue;
        }
        let dir = split_direction(
            ray.dir,
            ray.right,
            ray.up,
            params.tan_theta,
            SPLIT_OFFSETS[j],
        );
        let hit = sphere_trace_split(&sub, ray.origin, dir, &mut sdf);
        steps = steps.saturating_add(hit.steps);
        *part = SplitPart {
            weight: weights[j],
            dir,
            t: hit.t,
        };
    }
    Some(SplitGroup { parts, steps })
}
