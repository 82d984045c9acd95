//! The hit-group logic of CTSS (Algorithm 1, §3.3, §3.6) as a pure stepper, plus
//! [`trace`], which drives it with closures, and [`sphere_trace`], the NoAA
//! baseline with the same cone-based hit threshold.
//!
//! The caller owns the SDF and the shading. It asks the [`ConeStepper`] where to
//! evaluate ([`ConeStepper::t`]), feeds the distance back ([`ConeStepper::advance`])
//! and gets an [`Event`]: march on, sample a hit group, or stop. For a sample it
//! computes the normal at the sample point and hands the projected normal to
//! [`ConeStepper::record`], which makes the visibility mask, correlates it with
//! the pixel's global mask `M` and returns the sample's weight.
//! For semi-transparent surfaces, [`ConeStepper::record_alpha`] takes the
//! surface's opacity and composites into the `K` masks of §5.3
//! ([`crate::transparency`]) instead; [`trace_translucent`] drives it.
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::ctss::{trace, CtssParams};
//!
//! // A unit sphere 5 units in front of the camera, seen by a pixel whose ray
//! // grazes its silhouette.
//! let sphere = |p: Vec3| (p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0;
//! let normal = |p: Vec3| (p - Vec3::new(0.0, 0.0, 5.0)).normalize();
//! let params = CtssParams::new(0.02);
//! let dir = Vec3::new(0.2, 0.0, 1.0).normalize();
//! let r = trace(&params, Vec3::ZERO, dir, Vec3::X, Vec3::Y, sphere, normal, |_, _| Vec3::ONE, Vec3::ZERO);
//! // The pixel is partly sphere (white), partly background (black).
//! assert!(r.color.x > 0.0 && r.color.x < 1.0, "{:?}", r);
//! ```

/// The WGSL mirror of this module (ConeStepper, with the translucent parts of
/// CTSS §5.3, and sphere_trace_split): same names, the parameter structs of
/// [`crate::wgsl::PARAMS`]; concatenate after `PARAMS`, [`crate::cone::WGSL`],
/// [`crate::mask::WGSL`], [`crate::aggregate::WGSL`] and
/// [`crate::transparency::WGSL`] (see [`crate::wgsl`]).
pub const WGSL: &str = include_str!("ctss.wgsl");

/// The WGSL mirror of [`trace_field`] (with [`march`], [`group_mask`],
/// [`shade_split`] and the §5.3 split kernels [`group_needs_split`],
/// [`split_weights`], [`split_direction`], [`split_trace_params`],
/// [`split_group`], [`coarse_normal_step`], [`normal_step`],
/// [`tetra_normal`]): `subcone_ctss_trace(params, origin, dir, right, up,
/// background) -> subcone_CtssTraceResult` (colour, samples, steps, coverage,
/// stop code). Concatenate after [`WGSL`] (which needs `PARAMS`, `cone`,
/// `mask` and `aggregate`).
///
/// The scene is the including shader's, through hooks it defines (the
/// [`ConeField`] trait and `trace_field`'s `shade` closure):
///
/// - `fn subcone_field(p: vec3<f32>) -> vec3<f32>`: [`ConeField::sample`] as
///   (signed distance, safe step `≤` distance, object id). The id is an exact
///   integer held in an `f32` (every integer below 2²⁴ is exact; a material
///   index, say); a negative or NaN id is [`NO_OBJECT`].
/// - `fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32>`:
///   [`ConeField::normal`] with difference step `h`; `return
///   subcone_tetra_normal(p, h);` is the trait's default ([`tetra_normal`] of
///   `subcone_field`'s distance). It is also the coarse normal of
///   `ctss+edges` ([`ConeField::coarse_normal`]'s default).
/// - `fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32>`:
///   the colour of a surface point seen along `dir`. Work the host counts
///   while shading (shadow rays) goes into a `var<private>` of its own.
/// - `const subcone_CTSS_BATCH: u32` (≥ 1): the hit groups the trace marches
///   ahead of shading them. The groups wait in order and are shaded together,
///   so the lanes of a SIMD group march together and shade together: the
///   GPU's bounded form of delayed shading (§5.1). Eq. 6 adds the same terms
///   in the same order whatever the batch, so the result does not depend on
///   it.
///
/// [`WGSL`]'s own hook `ctss_field` (for `subcone_sphere_trace_split`, the
/// NoAA trace) is independent of these: the sub-traces of a split group run
/// on `subcone_field`.
pub const TRACE_WGSL: &str = include_str!("ctss/trace.wgsl");

mod normals;
mod params;
mod sphere;
mod split;
mod stepper;
mod trace;

pub use normals::{coarse_normal_step, normal_step, tetra_normal};
pub use params::{
    CtssParams, CONE_COVERAGE, FLAG_PAPER, FLAG_RELAXED, FLAG_SPLIT_GROUPS, GROUP_DIP,
};
pub use sphere::{sphere_trace, sphere_trace_split, SphereHit, SphereMarch};
pub use split::{
    cross_section_frame, group_needs_split, split_direction, split_group, split_trace_params,
    split_weights, SplitGroup, SplitPart, SplitRay, SPLIT_LENGTH_RATIO, SPLIT_MAX_STEPS,
    SPLIT_MIN_COS, SPLIT_OFFSETS, SPLIT_QUADRANTS,
};
pub use stepper::{ConeStepper, Event, GroupSample, StopReason, NO_OBJECT};
pub use trace::{
    close_group, group_mask, group_normal_depths, march, march_step, shade_split, split_samples,
    trace_field, ClosureField, ConeField, FieldSample, GroupHit, PartSample, SHEET_PROBE,
    SHELL_LENGTH,
};

use glam::Vec3;

use crate::aggregate::Aggregate;

/// Result of [`trace`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceResult {
    /// The antialiased pixel colour (eq. 6 with the background as a sample).
    pub color: Vec3,
    /// Shaded samples taken.
    pub samples: u32,
    /// SDF evaluations.
    pub steps: u32,
    /// The final global mask `M`.
    pub coverage: u32,
    /// Why the trace ended.
    pub stop: StopReason,
    /// Depth along the ray (from its origin, in units of its direction) of
    /// the nearest hit group that adds to eq. 6 (weight above 0): that
    /// group's sample depth `t` (the backtraced entry, eq. 10, or the
    /// backtraced first hard hit, §3.6); `+∞` when no group does. A group the
    /// cone grazed without covering a cell of the mask is not the pixel's
    /// surface, so it gives no depth.
    pub depth: f32,
}

impl TraceResult {
    /// The pixel's coverage as an alpha ([`coverage_alpha`] of
    /// [`Self::coverage`] and [`Self::stop`]).
    pub fn alpha(&self) -> f32 {
        coverage_alpha(self.coverage, self.stop)
    }
}

/// The part of a pixel its hit groups cover, from the global mask `M`
/// (§3.4–3.5): `bitCount(M)/32`, or 1 when the trace ended on a rule that
/// gives the background no weight ([`StopReason::covers_pixel`]). With
/// visibility weights and no minimum weight (the defaults), it is
/// `1 − ConeStepper::background_weight()` and the hit weights of eq. 6 sum
/// to it, so the colour resolved against a black background is the pixel's
/// premultiplied colour and `premultiplied + (1 − alpha)·background` is the
/// colour resolved against `background` (the `over` operator, Porter and
/// Duff 1984), up to rounding.
pub fn coverage_alpha(coverage: u32, stop: StopReason) -> f32 {
    if stop.covers_pixel() {
        1.0
    } else {
        crate::mask::mask_weight(coverage)
    }
}

/// Trace one pixel's cone with CTSS (Algorithm 1) through closures.
///
/// `sdf(p)` is the signed distance, `normal(p)` the surface normal, `shade(p, n)`
/// the colour of a surface point, `background` the colour of a miss. `right`/`up`
/// span the cone's cross-section ([`cross_section_frame`]). Shading is ASAP (§5.1).
///
/// With [`FLAG_SPLIT_GROUPS`] every group's coarse normal is taken from `sdf`
/// ([`tetra_normal`], step [`coarse_normal_step`]) and a group that
/// [`group_needs_split`] is shaded at its [`split_group`] parts instead of
/// once; `steps` and `samples` then include the extra evaluations (coarse
/// normals and sub-traces) and shaded parts.
#[allow(clippy::too_many_arguments)]
pub fn trace<S, N, C>(
    params: &CtssParams,
    origin: Vec3,
    dir: Vec3,
    right: Vec3,
    up: Vec3,
    sdf: S,
    normal: N,
    mut shade: C,
    background: Vec3,
) -> TraceResult
where
    S: FnMut(Vec3) -> f32,
    N: FnMut(Vec3) -> Vec3,
    C: FnMut(Vec3, Vec3) -> Vec3,
{
    let ray = SplitRay {
        origin,
        dir,
        right,
        up,
    };
    trace_field(
        params,
        &ray,
        &mut ClosureField { sdf, normal },
        |p, n, _| shade(p, n),
        background,
    )
}

/// [`trace`] for scenes with semi-transparent surfaces (CTSS §5.3): `shade(p, n)`
/// returns the colour and the opacity of the surface, and every sample goes
/// through [`ConeStepper::record_alpha`]. With every opacity 1 the result is
/// [`trace`]'s.
#[allow(clippy::too_many_arguments)]
pub fn trace_translucent<S, N, C>(
    params: &CtssParams,
    origin: Vec3,
    dir: Vec3,
    right: Vec3,
    up: Vec3,
    sdf: S,
    normal: N,
    mut shade: C,
    background: Vec3,
) -> TraceResult
where
    S: FnMut(Vec3) -> f32,
    N: FnMut(Vec3) -> Vec3,
    C: FnMut(Vec3, Vec3) -> (Vec3, f32),
{
    let ray = SplitRay {
        origin,
        dir,
        right,
        up,
    };
    let mut field = ClosureField { sdf, normal };
    let mut stepper = ConeStepper::new(params);
    let mut agg = Aggregate::new();
    let mut depth = f32::INFINITY;
    let stop = loop {
        let t = stepper.t();
        let d = field.sample(origin + t * dir).distance;
        match stepper.advance(d) {
            Event::March => {}
            Event::Sample(s) => {
                let p = origin + s.t * dir;
                let n = field.normal(p, normal_step(s.t, params.tan_theta));
                let (c, a) = shade(p, n);
                let mask = group_mask(params, &ray, &s, n, &mut field);
                let (_, w) = stepper.record_alpha_mask(mask, a);
                if depth == f32::INFINITY && w > 0.0 {
                    depth = s.t;
                }
                agg.add(w, c);
            }
            Event::Stop(r) => break r,
        }
    };
    TraceResult {
        color: agg.resolve(background, stepper.background_weight()),
        samples: stepper.samples(),
        steps: stepper.steps(),
        coverage: stepper.coverage(),
        stop,
        depth,
    }
}
