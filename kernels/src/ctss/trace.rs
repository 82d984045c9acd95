//! The one CTSS trace: Algorithm 1 through the [`ConeStepper`], with the
//! normals, the group masks, the §5.3 group splits and eq. 6, over any
//! [`ConeField`]. The CPU renderer runs it for every cone-traced method, and
//! its WGSL twin `subcone_ctss_trace` runs on the GPU, so the kernel tests
//! exercise what the renderers run.
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::ctss::{trace_field, CtssParams, FieldSample, ConeField, SplitRay};
//!
//! /// A unit sphere 5 units down +z, object 7.
//! struct Sphere;
//! impl ConeField for Sphere {
//!     fn sample(&mut self, p: Vec3) -> FieldSample {
//!         let d = (p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0;
//!         FieldSample { distance: d, step: d, object: 7 }
//!     }
//! }
//! let dir = Vec3::new(0.2, 0.0, 1.0).normalize();
//! let ray = SplitRay::new(Vec3::ZERO, dir, Vec3::Y);
//! let r = trace_field(&CtssParams::new(0.02), &ray, &mut Sphere, |_, _, _| Vec3::ONE, Vec3::ZERO);
//! // The pixel is partly sphere (white), partly background (black).
//! assert!(r.color.x > 0.0 && r.color.x < 1.0, "{:?}", r);
//! ```

use crate::math::Euclidean;
use glam::{Vec2, Vec3};

use super::normals::{coarse_normal_step, normal_step, tetra_normal};
use super::params::CtssParams;
use super::split::{group_needs_split, split_group, SplitRay};
use super::stepper::{ConeStepper, Event, GroupSample, NO_OBJECT};
use super::TraceResult;
use crate::aggregate::Aggregate;
use crate::cone::cone_radius;
use crate::mask::{needs_normal, project_normal, visibility_mask, FULL_MASK};

/// What a field tells the trace about one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldSample {
    /// Signed distance to the nearest surface: decides occlusion and groups.
    pub distance: f32,
    /// A safe step, `≤ distance` (e.g. capped at a repetition cell's walls;
    /// see [`ConeStepper::advance_split`]).
    pub step: f32,
    /// Id of the nearest object (its material, say), or [`NO_OBJECT`]. A
    /// group ends where it changes ([`ConeStepper::advance_object`]).
    pub object: u32,
}

impl FieldSample {
    /// A distance that is its own safe step, of no known object.
    pub const fn exact(distance: f32) -> Self {
        Self {
            distance,
            step: distance,
            object: NO_OBJECT,
        }
    }
}

/// A signed distance field as the trace sees it: the caller's scene.
pub trait ConeField {
    /// The field at `p`.
    fn sample(&mut self, p: Vec3) -> FieldSample;

    /// Unit surface normal at `p` from differences of step `h`
    /// ([`normal_step`], [`coarse_normal_step`]). The default is
    /// [`tetra_normal`] of [`sample`](Self::sample)'s distance.
    fn normal(&mut self, p: Vec3, h: f32) -> Vec3 {
        tetra_normal(|q| self.sample(q).distance, p, h)
    }

    /// The normal at `p` over the pixel's footprint, step `h`
    /// ([`coarse_normal_step`]), for `ctss+edges`' split test. The default is
    /// [`normal`](Self::normal).
    fn coarse_normal(&mut self, p: Vec3, h: f32) -> Vec3 {
        self.normal(p, h)
    }
}

/// Largest distance, in cone radii, from the probes of [`group_mask`]'s
/// sheet test to a surface. The step nearest a sheet lies within
/// `α·R_c·|n·dir|/2 ≤ R_c/4` of it, and so do the probes in its plane; a
/// small solid or a bar narrower than the cone leaves them farther. 0.2 was
/// chosen on the `primitives` and `random-box` scenes (of 0.2, 0.3, 0.5: the
/// least silhouette error on both, at 96×64).
pub const SHEET_PROBE: f32 = 0.2;

/// Least length, in cone radii at its first contact, of a group whose cone
/// passed through an oblique thin shell ([`group_mask`]). A shell the cone
/// meets at angle `φ` keeps it in contact for about `2/sin φ` radii; small
/// solids (a box smaller than the pixel) for about 2 to 3. 5 (shells seen
/// within about 24° of grazing) was chosen on the `primitives` and
/// `random-box` scenes as the shortest length that costs them nothing.
pub const SHELL_LENGTH: f32 = 5.0;

/// A closed hit group with its shading point and normal, its mask's visible
/// part and its eq. 6 weight, as [`march`] hands it on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroupHit {
    /// The group, as the stepper closed it.
    pub sample: GroupSample,
    /// Where to shade: `origin + sample.t·dir`.
    pub point: Vec3,
    /// The shading normal there ([`normal_step`]).
    pub normal: Vec3,
    /// The cells of the group's mask not covered before (`m & !M`).
    pub visible: u32,
    /// Its eq. 6 weight.
    pub weight: f32,
}

/// The visibility mask of a closed group (§3.4–3.5), with the normals it
/// needs from `field`; `normal` is the shading normal at the group's sample
/// point (reused where the mask wants the normal at the same depth).
///
/// The paper ([`FLAG_PAPER`](super::FLAG_PAPER)): the half-plane of the
/// group's peak occlusion `ω` and the normal where it peaked.
///
/// The default adds a rule for shells thinner than the cone (cloth, banners,
/// leaves, paper), through which the cone passes without full occlusion and
/// whose normal at the peak, on the medial surface, is either face's: the
/// half-plane model of a solid then shows the surface behind through the
/// shell. When the normals where the cone first and last touched the group
/// oppose (`n₁·n₂ < 0`: it saw the front face, then the back face):
/// - if the shell is a sheet over the cone's whole footprint on it (four
///   probes in its plane around the crossing, [`SHEET_PROBE`]), the mask is
///   full: every ray of the cone crosses it;
/// - else, when the group is longer than [`SHELL_LENGTH`] cone radii (a
///   shell seen obliquely) and the projected normals oppose too, the mask is
///   the union of both faces' half-planes.
///
/// Otherwise, and for convex solids passed at their silhouette (the same
/// side seen first and last), the paper's mask.
///
/// Cost: nothing for a group whose `ω` fixes the mask ([`needs_normal`]);
/// else one normal (the paper) or up to three, plus the 4 probes when the
/// first and last normals oppose.
pub fn group_mask<F: ConeField + ?Sized>(
    params: &CtssParams,
    ray: &SplitRay,
    sample: &GroupSample,
    normal: Vec3,
    field: &mut F,
) -> u32 {
    let placement = params.placement();
    let omega = sample.occlusion;
    if !needs_normal(omega, placement) {
        return visibility_mask(omega, Vec2::ZERO, placement);
    }
    let tan = params.tan_theta;
    let normal_at = |field: &mut F, t: f32| {
        if t == sample.t {
            normal
        } else {
            field.normal(ray.origin + t * ray.dir, normal_step(t, tan))
        }
    };
    let project = |n: Vec3| project_normal(n, ray.right, ray.up);
    if !params.is_paper() {
        let n1 = normal_at(field, sample.t_first);
        let n2 = normal_at(field, sample.t_last);
        if n1.dot(n2) < 0.0 {
            if sheet_across(ray, sample.t_occlusion, tan, n1, field) {
                return FULL_MASK;
            }
            let (p1, p2) = (project(n1), project(n2));
            let long =
                sample.t_last - sample.t_first > SHELL_LENGTH * cone_radius(sample.t_first, tan);
            if long && p1.dot(p2) < 0.0 {
                return visibility_mask(omega, p1, placement)
                    | visibility_mask(omega, p2, placement);
            }
        }
    }
    let peak = normal_at(field, sample.t_occlusion);
    visibility_mask(omega, project(peak), placement)
}

/// Whether the thin surface the ray crosses near depth `t` (where the
/// group's occlusion peaked), with front-face normal `n`, is a sheet over
/// the whole footprint of the cone on it: the field is within
/// [`SHEET_PROBE`] cone radii of a surface at four points of its plane
/// around the crossing, a
/// cone radius away across the tilt and `R_c/max(|n·dir|, 1/4)` along it
/// (the footprint's ellipse). A small solid or a bar narrower than the cone
/// fails in some direction. NaN distances, a zero normal, say no.
fn sheet_across<F: ConeField + ?Sized>(
    ray: &SplitRay,
    t: f32,
    tan: f32,
    n: Vec3,
    field: &mut F,
) -> bool {
    let rc = cone_radius(t, tan);
    let n = n.unit_or_zero();
    if n == Vec3::ZERO || !(rc > 0.0) {
        return false;
    }
    let cos = libm::fabsf(n.dot(ray.dir));
    let along = (ray.dir - n.dot(ray.dir) * n).unit_or_zero();
    let along = if along == Vec3::ZERO {
        ray.right
    } else {
        along
    };
    let across = n.cross(along).unit_or_zero();
    let stretch = rc / if cos > 0.25 { cos } else { 0.25 };
    let c = ray.origin + t * ray.dir;
    [along * stretch, -along * stretch, across * rc, -across * rc]
        .iter()
        .all(|e| field.sample(c + *e).distance < SHEET_PROBE * rc)
}

/// Algorithm 1 for `ray` through `field`: calls `on_hit` with each hit
/// group as it closes (its shading point and normal, its mask's visible
/// cells and its weight) and returns the stepper (counters, coverage,
/// background weight). [`trace_field`] shades the hits at once (ASAP);
/// a renderer with delayed shading (§5.1) records them instead.
pub fn march<F, H>(params: &CtssParams, ray: &SplitRay, field: &mut F, mut on_hit: H) -> ConeStepper
where
    F: ConeField + ?Sized,
    H: FnMut(&mut F, &GroupHit),
{
    let mut stepper = ConeStepper::new(params);
    loop {
        let f = field.sample(ray.origin + stepper.t() * ray.dir);
        if !march_step(params, ray, &mut stepper, f, field, &mut on_hit) {
            break;
        }
    }
    stepper
}

/// One step of [`march`]: `f` is the field at `ray.origin + stepper.t()·ray.dir`.
/// Advances the stepper and, when a group closes, takes its normal and mask
/// from `field` and calls `on_hit` ([`close_group`]). Returns whether the
/// march goes on. A caller that evaluates the field for several cones
/// together (SIMD lanes) runs [`march`] as this, one step per cone and
/// packet, or as [`ConeStepper::advance_object`] then [`close_group`].
#[inline]
pub fn march_step<F, H>(
    params: &CtssParams,
    ray: &SplitRay,
    stepper: &mut ConeStepper,
    f: FieldSample,
    field: &mut F,
    on_hit: &mut H,
) -> bool
where
    F: ConeField + ?Sized,
    H: FnMut(&mut F, &GroupHit),
{
    match stepper.advance_object(f.distance, f.step, f.object) {
        Event::March => true,
        Event::Sample(s) => {
            close_group(params, ray, stepper, s, field, on_hit);
            true
        }
        Event::Stop(_) => false,
    }
}

/// What [`march_step`] does with a group `s` the stepper has closed: the
/// normal at the shading point (Algorithm 1, line 16), the group's mask
/// ([`group_mask`], eq. 7–8) recorded in the stepper (line 19), then
/// `on_hit`.
#[inline]
pub fn close_group<F, H>(
    params: &CtssParams,
    ray: &SplitRay,
    stepper: &mut ConeStepper,
    s: GroupSample,
    field: &mut F,
    on_hit: &mut H,
) where
    F: ConeField + ?Sized,
    H: FnMut(&mut F, &GroupHit),
{
    let point = ray.origin + s.t * ray.dir;
    let normal = field.normal(point, normal_step(s.t, params.tan_theta));
    // The mask `record_mask` would discard is not made: CTSS-R's last group
    // takes the rest of the pixel, so its normals and sheet test are skipped.
    let mask = if stepper.takes_rest_of_pixel() {
        FULL_MASK
    } else {
        group_mask(params, ray, &s, normal, field)
    };
    let (visible, weight) = stepper.record_mask(mask);
    on_hit(
        field,
        &GroupHit {
            sample: s,
            point,
            normal,
            visible,
            weight,
        },
    );
}

/// The depths along the ray whose normals [`close_group`] takes for the
/// group `s`, each at `ray.origin + t·ray.dir` with step
/// [`normal_step`]`(t, tan θ)`: the shading point, then those
/// [`group_mask`] may ask for. The first `n` entries of the array are used;
/// repeated depths are listed once. A renderer that evaluates fields in
/// SIMD lanes computes these normals for several cones together and serves
/// them to [`close_group`] from a cache; [`group_mask`]'s other evaluations
/// (the sheet test) are not listed. `stepper` is the one that closed `s`:
/// when it [takes the rest of the pixel](ConeStepper::takes_rest_of_pixel),
/// `close_group` makes no mask and needs only the shading normal.
pub fn group_normal_depths(
    params: &CtssParams,
    stepper: &ConeStepper,
    s: &GroupSample,
) -> ([f32; 4], usize) {
    let mut out = [s.t; 4];
    let mut n = 1;
    let mut add = |t: f32| {
        if !out[..n].iter().any(|u| u.to_bits() == t.to_bits()) {
            out[n] = t;
            n += 1;
        }
    };
    if !stepper.takes_rest_of_pixel() && needs_normal(s.occlusion, params.placement()) {
        if !params.is_paper() {
            add(s.t_first);
            add(s.t_last);
        }
        add(s.t_occlusion);
    }
    (out, n)
}

/// Trace one pixel's cone with CTSS (Algorithm 1) through `field`, shading
/// each group as it closes (ASAP, §5.1) with `shade(point, normal, dir)` and
/// resolving eq. 6 against `background`.
///
/// With [`FLAG_SPLIT_GROUPS`](super::FLAG_SPLIT_GROUPS) (`ctss+edges`) every
/// group's coarse normal is taken ([`coarse_normal_step`], 4 evaluations)
/// and a group that [`group_needs_split`] is shaded at its [`split_group`]
/// parts instead of once; `steps` and `samples` include the extra
/// evaluations and shaded parts.
pub fn trace_field<F, C>(
    params: &CtssParams,
    ray: &SplitRay,
    field: &mut F,
    mut shade: C,
    background: Vec3,
) -> TraceResult
where
    F: ConeField + ?Sized,
    C: FnMut(Vec3, Vec3, Vec3) -> Vec3,
{
    let mut agg = Aggregate::new();
    let (mut extra_steps, mut extra_samples) = (0u32, 0u32);
    let mut depth = f32::INFINITY;
    let stepper = march(params, ray, field, |field, hit| {
        if depth == f32::INFINITY && hit.weight > 0.0 {
            depth = hit.sample.t;
        }
        if params.splits_groups() {
            if let Some((steps, parts)) = shade_split(params, ray, field, hit, &mut shade, &mut agg)
            {
                extra_steps = extra_steps.saturating_add(steps);
                extra_samples = extra_samples.saturating_add(parts);
                return;
            }
            extra_steps = extra_steps.saturating_add(4);
        }
        agg.add(hit.weight, shade(hit.point, hit.normal, ray.dir));
    });
    TraceResult {
        color: agg.resolve(background, stepper.background_weight()),
        samples: stepper.samples().saturating_add(extra_samples),
        steps: stepper.steps().saturating_add(extra_steps),
        coverage: stepper.coverage(),
        stop: stepper
            .stop_reason()
            .unwrap_or(super::StopReason::StepBudget),
        depth,
    }
}

/// `ctss+edges` (§5.3): split `hit` if [`group_needs_split`] says so and add
/// its parts to `agg`. Returns the SDF evaluations taken (the coarse normal's
/// 4 and the sub-traces') and the shaded samples beyond the group's one, or
/// `None` when the group stays whole (its coarse normal is then counted by
/// the caller).
pub fn shade_split<F, C>(
    params: &CtssParams,
    ray: &SplitRay,
    field: &mut F,
    hit: &GroupHit,
    shade: &mut C,
    agg: &mut Aggregate,
) -> Option<(u32, u32)>
where
    F: ConeField + ?Sized,
    C: FnMut(Vec3, Vec3, Vec3) -> Vec3,
{
    // The group's own colour, shaded once for every part that takes it.
    let mut group_color = None;
    split_samples(params, ray, field, hit, |part| match part {
        PartSample::Hit {
            point,
            normal,
            dir,
            weight,
        } => agg.add(weight, shade(point, normal, dir)),
        PartSample::Group { weight } => agg.add(
            weight,
            *group_color.get_or_insert_with(|| shade(hit.point, hit.normal, ray.dir)),
        ),
    })
}

/// A shaded part of a split group ([`split_samples`]), with its share of
/// eq. 6.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PartSample {
    /// A sub-ray's hit: shade `point` with `normal`, seen along `dir`.
    Hit {
        /// The hit point.
        point: Vec3,
        /// Its unit normal (step [`normal_step`]).
        normal: Vec3,
        /// The sub-ray's direction.
        dir: Vec3,
        /// Its weight.
        weight: f32,
    },
    /// A sub-ray that found no surface within the group: it takes the
    /// group's own sample (its point and normal seen along the cone's axis),
    /// shaded once for the group however many parts take it.
    Group {
        /// Its weight.
        weight: f32,
    },
}

/// [`shade_split`] without the shading: the parts of a split group, in the
/// order eq. 6 adds them, each passed to `part`, for a renderer that shades
/// later (delayed shading, §5.1, or packets of samples). Returns what
/// [`shade_split`] returns; `part` is not called when the group stays whole.
pub fn split_samples<F, P>(
    params: &CtssParams,
    ray: &SplitRay,
    field: &mut F,
    hit: &GroupHit,
    mut part: P,
) -> Option<(u32, u32)>
where
    F: ConeField + ?Sized,
    P: FnMut(PartSample),
{
    let s = &hit.sample;
    let coarse = field.coarse_normal(hit.point, coarse_normal_step(s.t, params));
    if !group_needs_split(hit.normal, coarse, s.t_exit - s.t_entry, s.t, params) {
        return None;
    }
    let g = split_group(params, s, ray, hit.visible, hit.weight, |x| {
        let f = field.sample(x);
        (f.distance, f.step)
    })?;
    let mut shaded = 0u32;
    for p in g.parts.iter().filter(|p| p.weight > 0.0) {
        part(match p.t {
            Some(t) => {
                let point = ray.origin + t * p.dir;
                PartSample::Hit {
                    point,
                    normal: field.normal(point, normal_step(t, params.tan_theta)),
                    dir: p.dir,
                    weight: p.weight,
                }
            }
            None => PartSample::Group { weight: p.weight },
        });
        shaded += 1;
    }
    Some((g.steps.saturating_add(4), shaded.saturating_sub(1)))
}

/// A [`ConeField`] of two closures: `sdf(p)` (its own safe step, no object)
/// and `normal(p)` (the step is the closure's business; the coarse normal
/// of `ctss+edges` is [`tetra_normal`] of `sdf`).
pub struct ClosureField<S, N> {
    /// The signed distance.
    pub sdf: S,
    /// The unit normal.
    pub normal: N,
}

impl<S: FnMut(Vec3) -> f32, N: FnMut(Vec3) -> Vec3> ConeField for ClosureField<S, N> {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        FieldSample::exact((self.sdf)(p))
    }
    fn normal(&mut self, p: Vec3, _h: f32) -> Vec3 {
        (self.normal)(p)
    }
    fn coarse_normal(&mut self, p: Vec3, h: f32) -> Vec3 {
        tetra_normal(&mut self.sdf, p, h)
    }
}
