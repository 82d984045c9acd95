//! Packets of rays in SIMD lanes: the sphere-traced methods with the field
//! evaluated for [`LANES`] rays at once through the scene's compiled
//! [`SdfProgram`].
//!
//! Each lane runs the scalar path's own state machine (the kernels'
//! [`SphereMarch`] and [`march_step`](subcone_kernels::ctss::march_step),
//! this module's [`ShadowRay`]), so every ray takes the steps, hits and samples it takes alone; only the field
//! evaluations are shared. A lane whose ray has ended idles until the packet
//! ends. Colours are summed in the scalar path's order, so frames are bit for
//! bit those of one ray at a time (`tests/sdf.rs` compares them).
//!
//! - NoAA and SSAA: the rays of a row (every subsample of every pixel, in
//!   pixel order) eight at a time: trace, normals (the four tetrahedral taps
//!   of a normal side by side, two normals per packet), material, and each
//!   light's shadow rays as a packet.
//! - CTSS and CTSS-R: the cones of a row eight at a time through the kernels'
//!   stepper. The normals of the groups that close at a step (the shading
//!   point's and those of the group's mask, [`group_normal_depths`]) are
//!   taken in packets too, then each group is closed as
//!   [`march_step`](subcone_kernels::ctss::march_step) closes it
//!   ([`close_group`]). The hit groups are recorded, then shaded
//!   in packets of eight samples (CTSS §5.1's delayed shading, which sums
//!   eq. 6 in the same order as shading as soon as a group closes).
//!   `ctss+edges` (§5.3) takes every group's coarse normal in those packets
//!   and records a split group's parts ([`split_samples`]), its sub-rays
//!   traced one at a time through the tree.
//! - SRAA-RT (Chiu et al. §3) on an SDF: the shading pass's and the
//!   geometry pass's rays eight at a time (trace, normals, shadow states,
//!   materials), each buffer entry as the scalar path writes it.
//! - The centre AOVs (depth, normal, albedo, light visibility, mirror), a
//!   row's rays eight at a time.

use glam::{Vec2, Vec3};
use subcone_kernels::aggregate::Aggregate;
use subcone_kernels::ctss::{
    close_group, coarse_normal_step, group_normal_depths, normal_step, split_samples, ConeField,
    ConeStepper, CtssParams, Event, FieldSample, GroupSample, PartSample, SphereHit, SphereMarch,
    SplitRay,
};
use subcone_kernels::passes::MAX_LIGHTS;
use subcone_kernels::sraa::{Geometry, SUBPIXEL_OFFSETS};
use subcone_scene::sdf::{tetra_normal_from, tetra_taps};
use subcone_scene::RenderSettings;
use subcone_sdf::program::{LaneMask, Points, Scratch, SdfProgram, SplitLanes, LANES};

use super::{CentreAovs, ConeFieldOf, SdfField, SdfView, Tally, MISS_AOVS};
use crate::render::pixel_centre;

mod shadow;

use shadow::ShadingRow;
pub(super) use shadow::ShadowRay;

/// All of the first `n` lanes.
#[inline(always)]
fn first(n: usize) -> LaneMask {
    if n >= LANES {
        LaneMask::MAX
    } else {
        ((1u16 << n) - 1) as LaneMask
    }
}

#[inline(always)]
fn lanes(m: LaneMask) -> impl Iterator<Item = usize> {
    (0..LANES).filter(move |k| m & (1 << k) != 0)
}

/// A hit-group sample waiting for shading: point, normal and the direction
/// it is seen along, and its weight in eq. 6.
#[derive(Clone, Copy)]
struct Pending {
    q: Vec3,
    n: Vec3,
    dir: Vec3,
    w: f32,
    /// 0: shade it. `r > 0`: it takes the colour of the sample `r` places
    /// before it (a split group's parts that take the group's own colour,
    /// [`PartSample::Group`], shaded once as `shade_split` shades it).
    reuse: u32,
}

/// A [`ConeField`] that serves the normals computed in packets for the
/// groups closing at this step, and asks the field for anything else.
struct NormalCache<'c, F: SdfField> {
    field: ConeFieldOf<'c, F>,
    /// Point and step of each normal computed.
    at: &'c [(Vec3, f32)],
    normals: &'c [Vec3],
}

impl<F: SdfField> ConeField for NormalCache<'_, F> {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        self.field.sample(p)
    }

    fn normal(&mut self, p: Vec3, h: f32) -> Vec3 {
        let same = |(q, g): &(Vec3, f32)| {
            q.to_array().map(f32::to_bits) == p.to_array().map(f32::to_bits)
                && g.to_bits() == h.to_bits()
        };
        match self.at.iter().position(same) {
            Some(i) => self.normals[i],
            None => self.field.normal(p, h),
        }
    }
}

/// One cone's trace, waiting for its samples' shading.
#[derive(Clone, Copy)]
struct PendingCone {
    background_weight: f32,
    end: usize,
    samples: u32,
}

/// The packet renderer of one rayon task: the view, its program and the
/// program's stacks, and row buffers kept from one row to the next.
pub(super) struct Packets<'v, 'a, F: SdfField> {
    view: &'v SdfView<'a, F>,
    program: &'v SdfProgram<'a>,
    scratch: Scratch,
    rays: Vec<(Vec3, Vec3)>,
    colors: Vec<Vec3>,
    hits: Vec<bool>,
    batch: Vec<Pending>,
    lane_batch: [Vec<Pending>; LANES],
    /// `ctss+edges`: each lane's evaluations and shaded samples beyond its
    /// stepper's (coarse normals, split groups' sub-traces and parts), as
    /// `trace_field` adds them.
    lane_extra: [(u32, u32); LANES],
    cones: Vec<PendingCone>,
    /// The samples of the batch that are shaded (not reused).
    to_shade: Vec<usize>,
    normal_at: Vec<(Vec3, f32)>,
    normal_values: Vec<Vec3>,
    /// [`shade_samples`](Self::shade_samples)' working rows.
    shading: ShadingRow,
    /// A row's samples to shade: points, normals, ray directions; their
    /// colours.
    points: Vec<Vec3>,
    normals: Vec<Vec3>,
    directions: Vec<Vec3>,
    shaded: Vec<Vec3>,
}

impl<'v, 'a, F: SdfField> Packets<'v, 'a, F> {
    pub(super) fn new(view: &'v SdfView<'a, F>, program: &'v SdfProgram<'a>) -> Self {
        Packets {
            view,
            program,
            scratch: program.scratch(),
            rays: Vec::new(),
            colors: Vec::new(),
            hits: Vec::new(),
            batch: Vec::new(),
            lane_batch: Default::default(),
            lane_extra: [(0, 0); LANES],
            cones: Vec::new(),
            to_shade: Vec::new(),
            normal_at: Vec::new(),
            normal_values: Vec::new(),
            shading: ShadingRow::default(),
            points: Vec::new(),
            normals: Vec::new(),
            directions: Vec::new(),
            shaded: Vec::new(),
        }
    }

    /// The one call into the program: compiled once per instruction-set
    /// path ([`Isa::run`](crate::isa::Isa::run) inlines the whole
    /// interpreter into it), and called from every loop of this module.
    ///
    /// The march loops (`trace`, `shadowed`, `march_cones`) run on the
    /// instruction-set path themselves but still call this out of line:
    /// inlined into each of them, the interpreter was compiled twelve times
    /// (four loops × three paths), which was most of this crate's build. A
    /// call per step is small beside one evaluation of a program.
    #[inline(never)]
    fn eval(&mut self, p: &Points, active: LaneMask) -> SplitLanes {
        let (program, scratch) = (self.program, &mut self.scratch);
        self.view.isa.run(
            #[inline(always)]
            || program.eval_split(p, active, scratch),
        )
    }

    /// The rays of row `y`: `side²` subsamples per pixel, pixel by pixel, as
    /// the scalar loop visits them.
    fn row_rays(&mut self, y: usize, side: usize, s: &RenderSettings) {
        self.rays.clear();
        for x in 0..s.width as usize {
            for sy in 0..side {
                for sx in 0..side {
                    let off = Vec2::new(
                        (sx as f32 + 0.5) / side as f32,
                        (sy as f32 + 0.5) / side as f32,
                    );
                    self.rays.push(self.view.camera.ray(
                        Vec2::new(x as f32, y as f32) + off,
                        s.width,
                        s.height,
                    ));
                }
            }
        }
    }

    /// Sphere traces up to [`LANES`] rays together, the whole march on the
    /// instruction-set path.
    #[inline(never)]
    fn trace(&mut self, rays: &[(Vec3, Vec3)], params: &CtssParams) -> [Option<SphereHit>; LANES] {
        let isa = self.view.isa;
        isa.run(
            #[inline(always)]
            || self.trace_here(rays, params),
        )
    }

    #[inline(always)]
    fn trace_here(
        &mut self,
        rays: &[(Vec3, Vec3)],
        params: &CtssParams,
    ) -> [Option<SphereHit>; LANES] {
        let mut m = [SphereMarch::new(params); LANES];
        let mut out = [None; LANES];
        let mut active = first(rays.len());
        let mut pts = Points::default();
        loop {
            for k in lanes(active) {
                match m[k].before_step(params) {
                    Some(h) => {
                        out[k] = Some(h);
                        active &= !(1 << k);
                    }
                    None => {
                        let (o, d) = rays[k];
                        pts.set(k, o + m[k].t() * d);
                    }
                }
            }
            if active == 0 {
                return out;
            }
            let r = self.eval(&pts, active);
            for k in lanes(active) {
                if let Some(h) = m[k].after_step(params, r.surface[k], r.safe[k]) {
                    out[k] = Some(h);
                    active &= !(1 << k);
                }
            }
        }
    }

    /// The surface normals at `q` with difference steps `h` (the scalar
    /// path's `normal_surface`) in the `active` lanes.
    #[inline(always)]
    fn normals(&mut self, q: &[Vec3; LANES], h: &[f32; LANES], active: LaneMask) -> [Vec3; LANES] {
        let mut at = std::mem::take(&mut self.normal_at);
        let mut values = std::mem::take(&mut self.normal_values);
        at.clear();
        at.extend(lanes(active).map(|k| (q[k], h[k])));
        self.normals_at(&at, &mut values);
        let mut out = [Vec3::ZERO; LANES];
        for (k, n) in lanes(active).zip(&values) {
            out[k] = *n;
        }
        self.normal_at = at;
        self.normal_values = values;
        out
    }

    /// The surface normals at each point and step of `at` (the scalar
    /// path's `normal_surface`), appended to `out` after clearing it. The
    /// four taps of each normal go side by side, two normals per packet.
    #[inline(always)]
    fn normals_at(&mut self, at: &[(Vec3, f32)], out: &mut Vec<Vec3>) {
        out.clear();
        let mut pts = Points::default();
        for pair in at.chunks(LANES / 4) {
            for (i, &(q, h)) in pair.iter().enumerate() {
                for (j, tap) in tetra_taps(q, h).into_iter().enumerate() {
                    pts.set(4 * i + j, tap);
                }
            }
            let r = self.eval(&pts, first(4 * pair.len()));
            for i in 0..pair.len() {
                let d = std::array::from_fn(|j| r.surface[4 * i + j]);
                out.push(tetra_normal_from(d));
            }
        }
    }

    /// One NoAA or SSAA row (the scalar path's pixel loop with `noaa`):
    /// writes colours and samples per pixel; returns the pixels with more
    /// samples than rays.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sphere_row(
        &mut self,
        y: usize,
        side: usize,
        params: &CtssParams,
        s: &RenderSettings,
        row: &mut [Vec3],
        spp_row: &mut [f32],
        tally: &mut Tally,
    ) -> u64 {
        self.row_rays(y, side, s);
        let rays = std::mem::take(&mut self.rays);
        self.hits.clear();
        let (mut q, mut n, mut dir) = self.take_samples();
        for chunk in rays.chunks(LANES) {
            // `shade` turns the normals towards the ray again: no change.
            let surf = self.surfaces(chunk, params, tally);
            let hit = surf.hit;
            tally.samples += hit.count_ones() as u64;
            for (k, ray) in chunk.iter().enumerate() {
                let on = hit & (1 << k) != 0;
                if on {
                    q.push(surf.q[k]);
                    n.push(surf.n[k]);
                    dir.push(ray.1);
                }
                self.hits.push(on);
            }
        }
        self.rays = rays;
        // The row's hits shaded together (their shadow rays as one stream),
        // then each sample's colour in the row's order.
        let mut shaded = std::mem::take(&mut self.shaded);
        shaded.clear();
        shaded.resize(q.len(), Vec3::ZERO);
        self.shade_samples(&q, &n, &dir, &mut shaded, tally);
        self.colors.clear();
        let mut next = shaded.iter();
        for &on in &self.hits {
            let c = if on { next.next() } else { None };
            self.colors.push(c.copied().unwrap_or(self.view.background));
        }
        self.shaded = shaded;
        self.put_samples(q, n, dir);
        let per_pixel = side * side;
        let mut multi = 0;
        for (x, (colors, hits)) in self
            .colors
            .chunks(per_pixel)
            .zip(self.hits.chunks(per_pixel))
            .enumerate()
        {
            let mut sum = Vec3::ZERO;
            for c in colors {
                sum += *c;
            }
            let samples = hits.iter().filter(|h| **h).count();
            row[x] = sum / per_pixel as f32;
            spp_row[x] = samples as f32;
            if samples > per_pixel {
                multi += 1;
            }
        }
        multi
    }

    /// Closes the groups of the lanes in `closing` as
    /// [`march_step`](subcone_kernels::ctss::march_step) would
    /// ([`close_group`]), their normals taken in packets first. Kept out of
    /// line: groups close at few steps, and the march loop stays small.
    #[inline(never)]
    fn close_groups(
        &mut self,
        params: &CtssParams,
        cones: &[SplitRay; LANES],
        steppers: &mut [ConeStepper; LANES],
        closing: &[Option<GroupSample>; LANES],
    ) {
        let tan = params.tan_theta;
        self.normal_at.clear();
        for (k, g) in closing.iter().enumerate() {
            let Some(g) = g else { continue };
            let (depths, n) = group_normal_depths(params, &steppers[k], g);
            for &t in &depths[..n] {
                self.normal_at
                    .push((cones[k].origin + t * cones[k].dir, normal_step(t, tan)));
            }
            // `ctss+edges` takes every group's coarse normal at its shading
            // point (`split_samples`).
            if params.splits_groups() {
                self.normal_at.push((
                    cones[k].origin + g.t * cones[k].dir,
                    coarse_normal_step(g.t, params),
                ));
            }
        }
        let at = std::mem::take(&mut self.normal_at);
        let mut values = std::mem::take(&mut self.normal_values);
        self.normals_at(&at, &mut values);
        self.normal_values = values;
        let mut field = NormalCache {
            field: ConeFieldOf(self.view.field),
            at: &at,
            normals: &self.normal_values,
        };
        for (k, g) in closing.iter().enumerate() {
            let Some(g) = *g else { continue };
            let (out, extra) = (&mut self.lane_batch[k], &mut self.lane_extra[k]);
            let ray = &cones[k];
            close_group(
                params,
                ray,
                &mut steppers[k],
                g,
                &mut field,
                &mut |field, hit| {
                    let whole = Pending {
                        q: hit.point,
                        n: hit.normal,
                        dir: ray.dir,
                        w: hit.weight,
                        reuse: 0,
                    };
                    if params.splits_groups() {
                        // `trace_field`'s split (`shade_split`), recorded.
                        let mut group_at = None;
                        let split = split_samples(params, ray, field, hit, |part| {
                            out.push(match part {
                                PartSample::Hit {
                                    point,
                                    normal,
                                    dir,
                                    weight,
                                } => Pending {
                                    q: point,
                                    n: normal,
                                    dir,
                                    w: weight,
                                    reuse: 0,
                                },
                                PartSample::Group { weight } => {
                                    let at = out.len();
                                    let first = *group_at.get_or_insert(at);
                                    Pending {
                                        w: weight,
                                        reuse: (at - first) as u32,
                                        ..whole
                                    }
                                }
                            })
                        });
                        match split {
                            Some((steps, parts)) => {
                                extra.0 = extra.0.saturating_add(steps);
                                extra.1 = extra.1.saturating_add(parts);
                                return;
                            }
                            None => extra.0 = extra.0.saturating_add(4),
                        }
                    }
                    out.push(whole);
                },
            );
        }
        self.normal_at = at;
    }

    /// Marches the `active` cones of a packet to their ends, their hit
    /// groups closed into [`lane_batch`](Self::lane_batch), the whole march
    /// on the instruction-set path.
    #[inline(never)]
    fn march_cones(
        &mut self,
        params: &CtssParams,
        cones: &[SplitRay; LANES],
        steppers: &mut [ConeStepper; LANES],
        active: LaneMask,
    ) {
        let isa = self.view.isa;
        isa.run(
            #[inline(always)]
            || self.march_cones_here(params, cones, steppers, active),
        )
    }

    #[inline(always)]
    fn march_cones_here(
        &mut self,
        params: &CtssParams,
        cones: &[SplitRay; LANES],
        steppers: &mut [ConeStepper; LANES],
        mut active: LaneMask,
    ) {
        let mut pts = Points::default();
        while active != 0 {
            for k in lanes(active) {
                pts.set(k, cones[k].origin + steppers[k].t() * cones[k].dir);
            }
            let r = self.eval(&pts, active);
            let mut closing = [None::<GroupSample>; LANES];
            let mut any_closing = false;
            // Free-space steps side by side; the rest one lane at a time.
            let slow = ConeStepper::advance_free_lanes(steppers, &r.surface, &r.safe, active.into())
                as LaneMask;
            for k in lanes(slow) {
                match steppers[k].advance_object(r.surface[k], r.safe[k], r.material[k]) {
                    Event::March => {}
                    Event::Sample(g) => {
                        closing[k] = Some(g);
                        any_closing = true;
                    }
                    // `Event::Stop`: the march is over.
                    _ => active &= !(1 << k),
                }
            }
            if any_closing {
                self.close_groups(params, cones, steppers, &closing);
            }
        }
    }

    /// One CTSS (or CTSS-R, SSAA+CTSS) row: every cone of the row traced in
    /// packets with its hit groups recorded, then the samples shaded in
    /// packets and summed per cone in the order they were found (eq. 6).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn cone_row(
        &mut self,
        y: usize,
        side: usize,
        params: &CtssParams,
        s: &RenderSettings,
        row: &mut [Vec3],
        spp_row: &mut [f32],
        tally: &mut Tally,
    ) -> u64 {
        self.row_rays(y, side, s);
        let rays = std::mem::take(&mut self.rays);
        self.batch.clear();
        self.cones.clear();
        let view = self.view;
        for chunk in rays.chunks(LANES) {
            let cones: [SplitRay; LANES] = std::array::from_fn(|k| {
                let (o, d) = chunk.get(k).copied().unwrap_or((Vec3::ZERO, Vec3::Z));
                view.cone_ray(o, d)
            });
            let mut steppers: [ConeStepper; LANES] =
                std::array::from_fn(|_| ConeStepper::new(params));
            for b in &mut self.lane_batch {
                b.clear();
            }
            self.lane_extra = [(0, 0); LANES];
            self.march_cones(params, &cones, &mut steppers, first(chunk.len()));
            for (k, st) in steppers.iter().enumerate().take(chunk.len()) {
                let (steps, samples) = self.lane_extra[k];
                let samples = st.samples().saturating_add(samples);
                tally.steps += st.steps().saturating_add(steps) as u64;
                tally.samples += samples as u64;
                self.batch.extend_from_slice(&self.lane_batch[k]);
                self.cones.push(PendingCone {
                    background_weight: st.background_weight(),
                    end: self.batch.len(),
                    samples,
                });
            }
        }
        self.rays = rays;

        // Shading, eight samples at a time; reused colours copied after.
        let batch = std::mem::take(&mut self.batch);
        let mut to_shade = std::mem::take(&mut self.to_shade);
        to_shade.clear();
        to_shade.extend((0..batch.len()).filter(|&i| batch[i].reuse == 0));
        self.colors.clear();
        self.colors.resize(batch.len(), Vec3::ZERO);
        // The row's samples shaded together (their shadow rays as one
        // stream).
        let (mut q, mut n, mut dir) = self.take_samples();
        for &i in &to_shade {
            q.push(batch[i].q);
            n.push(batch[i].n);
            dir.push(batch[i].dir);
        }
        let mut shaded = std::mem::take(&mut self.shaded);
        shaded.clear();
        shaded.resize(q.len(), Vec3::ZERO);
        self.shade_samples(&q, &n, &dir, &mut shaded, tally);
        for (&i, c) in to_shade.iter().zip(&shaded) {
            self.colors[i] = *c;
        }
        self.shaded = shaded;
        self.put_samples(q, n, dir);
        for (i, p) in batch.iter().enumerate() {
            if p.reuse > 0 {
                self.colors[i] = self.colors[i - p.reuse as usize];
            }
        }
        self.to_shade = to_shade;

        let per_pixel = side * side;
        let mut multi = 0;
        let mut start = 0;
        for (x, pixel) in self.cones.chunks(per_pixel).enumerate() {
            let mut sum = Vec3::ZERO;
            let mut samples = 0;
            for cone in pixel {
                let mut agg = Aggregate::new();
                for (p, c) in batch[start..cone.end]
                    .iter()
                    .zip(&self.colors[start..cone.end])
                {
                    agg.add(p.w, *c);
                }
                start = cone.end;
                sum += agg.resolve(view.background, cone.background_weight);
                samples += cone.samples;
            }
            row[x] = sum / per_pixel as f32;
            spp_row[x] = samples as f32;
            if samples as usize > per_pixel {
                multi += 1;
            }
        }
        self.batch = batch;
        multi
    }
}

/// What SRAA-RT keeps of up to [`LANES`] traced rays (the scalar path's
/// `hit`): in the lanes of `hit`, the point and the unit normal facing the
/// ray.
pub(super) struct Surfaces {
    pub(super) q: [Vec3; LANES],
    pub(super) n: [Vec3; LANES],
    /// The field's normal as it is (not turned towards the ray).
    pub(super) normal: [Vec3; LANES],
    pub(super) hit: LaneMask,
}

/// SRAA-RT on an SDF (`SdfView::sraa_rt`) in packets: its shading and
/// geometry passes trace, take normals, shadow states and materials eight
/// rays at a time, each lane as the scalar path takes it alone, so the
/// buffers, and so the frames, are bit for bit the scalar path's.
impl<F: SdfField> Packets<'_, '_, F> {
    /// The scalar path's `hit` for each of up to [`LANES`] rays: sphere
    /// traced, then the normals of the hits in packets, turned to face the
    /// ray.
    pub(super) fn surfaces(
        &mut self,
        rays: &[(Vec3, Vec3)],
        params: &CtssParams,
        tally: &mut Tally,
    ) -> Surfaces {
        let traced = self.trace(rays, params);
        let mut q = [Vec3::ZERO; LANES];
        let mut h = [0.0f32; LANES];
        let mut hit: LaneMask = 0;
        for (k, ray) in rays.iter().enumerate() {
            let Some(r) = traced[k] else { continue };
            tally.steps += r.steps as u64;
            if let Some(t) = r.t {
                q[k] = ray.0 + t * ray.1;
                h[k] = normal_step(t, params.tan_theta);
                hit |= 1 << k;
            }
        }
        let normal = self.normals(&q, &h, hit);
        let mut n = normal;
        for k in lanes(hit) {
            if n[k].dot(rays[k].1) > 0.0 {
                n[k] = -n[k];
            }
        }
        Surfaces { q, n, normal, hit }
    }

    /// The scalar path's `shadow_states` in the lanes of `s.hit`: bit `l`
    /// set where light `l` shadows the point. A light facing away shadows
    /// without a ray, one that does not reach the point leaves it lit; of
    /// the others, a lane casts a ray where its `cast` bit is set (each
    /// light's rays as one packet) and takes its `inherited` bit elsewhere.
    pub(super) fn shadow_states(
        &mut self,
        s: &Surfaces,
        cast: &[u32; LANES],
        inherited: &[u32; LANES],
        tally: &mut Tally,
    ) -> [u32; LANES] {
        self.light_states(s, cast, inherited, false, tally)
    }

    /// The light-visibility AOV of the lanes of `s.hit` (the scalar
    /// `centre_aovs`): bit `l` set where no geometry blocks light `l`, or
    /// where the point faces away from it (its cosine falls to 0 smoothly:
    /// no shadow edge); clear where the light does not reach the point.
    pub(super) fn light_visibility(&mut self, s: &Surfaces, tally: &mut Tally) -> [u32; LANES] {
        self.light_states(s, &[u32::MAX; LANES], &[0; LANES], true, tally)
    }

    /// [`shadow_states`](Self::shadow_states), or with `visibility`
    /// [`light_visibility`](Self::light_visibility): the two differ only in
    /// the bit a cast ray sets (blocked, or not blocked).
    fn light_states(
        &mut self,
        s: &Surfaces,
        cast: &[u32; LANES],
        inherited: &[u32; LANES],
        visibility: bool,
        tally: &mut Tally,
    ) -> [u32; LANES] {
        let view = self.view;
        let mut bits = [0u32; LANES];
        for (l, light) in view.lights.iter().enumerate().take(MAX_LIGHTS) {
            let mut need: LaneMask = 0;
            let mut rays = [ShadowRay::default(); LANES];
            for k in lanes(s.hit) {
                let Some(inc) = light.incident(s.q[k]) else {
                    continue;
                };
                if inc.direction.dot(s.n[k]) <= 0.0 {
                    bits[k] |= 1 << l;
                } else if cast[k] & (1 << l) == 0 {
                    bits[k] |= inherited[k] & (1 << l);
                } else {
                    rays[k] = ShadowRay::new(
                        s.q[k],
                        s.n[k],
                        inc.direction,
                        inc.distance,
                        view.max_distance,
                    );
                    need |= 1 << k;
                }
            }
            tally.shadow += need.count_ones() as u64;
            let blocked = self.shadowed(&mut rays, need);
            for k in lanes(if visibility { need & !blocked } else { blocked }) {
                bits[k] |= 1 << l;
            }
        }
        bits
    }

    /// The AOVs of row `y` through each pixel centre (the scalar
    /// `centre_aovs`, NoAA's trace with `params`): per pixel the view depth,
    /// the field's normal, the albedo, the light visibility and the mirror
    /// reflectance; a miss is `(∞, 0, 0, 0, 0)`.
    pub(super) fn aov_row(
        &mut self,
        y: usize,
        params: &CtssParams,
        s: &RenderSettings,
        out: &mut [CentreAovs],
    ) {
        let view = self.view;
        let mut tally = Tally::default();
        self.row_rays(y, 1, s);
        let rays = std::mem::take(&mut self.rays);
        for (chunk, out) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
            let surf = self.surfaces(chunk, params, &mut tally);
            let visible = self.light_visibility(&surf, &mut tally);
            let material = self.materials(&surf);
            for (k, o) in out.iter_mut().enumerate() {
                *o = if surf.hit & (1 << k) == 0 {
                    MISS_AOVS
                } else {
                    let mat = view.material(material[k]);
                    (
                        view.camera.view_depth(surf.q[k]),
                        surf.normal[k],
                        mat.albedo_at(surf.q[k], Vec2::ZERO),
                        visible[k],
                        mat.mirror,
                    )
                };
            }
        }
        self.rays = rays;
    }

    /// The field's material at each hit point of `s` (0 elsewhere), as the
    /// scalar path reads it off `eval_split`.
    fn materials(&mut self, s: &Surfaces) -> [u32; LANES] {
        if s.hit == 0 {
            return [0; LANES];
        }
        let mut pts = Points::default();
        for k in lanes(s.hit) {
            pts.set(k, s.q[k]);
        }
        self.eval(&pts, s.hit).material
    }

    /// SRAA-RT's shading pass over the pixels of one band (`geo`, from row
    /// `first_row` on): each pixel's ray through its centre plus `offset`,
    /// its geometry in `geo`, its shadow states in `shadow` (when not empty;
    /// with `shadows` false, no shadow ray is cast), its layers (`nl` per
    /// pixel, split by light when `split`) in `values`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sraa_shading_band(
        &mut self,
        first_row: usize,
        offset: Vec2,
        params: &CtssParams,
        s: &RenderSettings,
        (shadows, split, nl): (bool, bool, usize),
        geo: &mut [Geometry],
        values: &mut [Vec3],
        shadow: &mut [u32],
        tally: &mut Tally,
    ) {
        let view = self.view;
        let w = s.width as usize;
        let mut rays = std::mem::take(&mut self.rays);
        for start in (0..geo.len()).step_by(LANES) {
            let m = LANES.min(geo.len() - start);
            rays.clear();
            rays.extend((start..start + m).map(|i| {
                let px = pixel_centre(i % w, first_row + i / w) + offset;
                view.camera.ray(px, s.width, s.height)
            }));
            let surf = self.surfaces(&rays, params, tally);
            tally.samples += surf.hit.count_ones() as u64;
            let bits = if shadows {
                self.shadow_states(&surf, &[u32::MAX; LANES], &[0; LANES], tally)
            } else {
                [0; LANES]
            };
            let material = self.materials(&surf);
            for k in 0..m {
                let i = start + k;
                let v = &mut values[i * nl..(i + 1) * nl];
                if surf.hit & (1 << k) == 0 {
                    v[0] = view.background;
                    continue;
                }
                let (q, n) = (surf.q[k], surf.n[k]);
                geo[i] = Geometry::new(n, view.camera.view_depth(q));
                if let Some(sh) = shadow.get_mut(i) {
                    *sh = bits[k];
                }
                view.shade_layers_of(material[k], q, n, bits[k], (split, 1.0), v);
            }
        }
        self.rays = rays;
    }

    /// SRAA-RT's geometry pass (the paper's pass 1) over the pixels of one
    /// band (`sub_geo`, from row `first_row` on): subsample `k` of each
    /// pixel (every one but `shaded`, which the caller copies from the
    /// shading pass) traced for its geometry and, when `sub_shadow` is not
    /// empty, its shadow states, casting the lights `agree(x, y)` names for
    /// pixel `(x, y)` and inheriting the others (`(cast, inherited)`).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sraa_geometry_band(
        &mut self,
        first_row: usize,
        shaded: Option<usize>,
        params: &CtssParams,
        s: &RenderSettings,
        agree: impl Fn(usize, usize) -> (u32, u32),
        sub_geo: &mut [[Geometry; 4]],
        sub_shadow: &mut [[u32; 4]],
        tally: &mut Tally,
    ) {
        let view = self.view;
        let w = s.width as usize;
        let subsamples: Vec<usize> = (0..4).filter(|k| Some(*k) != shaded).collect();
        let total = sub_geo.len() * subsamples.len();
        let mut rays = std::mem::take(&mut self.rays);
        let mut which = [(0usize, 0usize); LANES];
        // The last pixel's `agree` (its subsamples share packets).
        let mut agreed: Option<(usize, (u32, u32))> = None;
        for start in (0..total).step_by(LANES) {
            let m = LANES.min(total - start);
            rays.clear();
            for (slot, j) in which.iter_mut().zip(start..start + m) {
                let (i, k) = (j / subsamples.len(), subsamples[j % subsamples.len()]);
                *slot = (i, k);
                let px = pixel_centre(i % w, first_row + i / w) + SUBPIXEL_OFFSETS[k];
                rays.push(view.camera.ray(px, s.width, s.height));
            }
            let surf = self.surfaces(&rays, params, tally);
            for k in lanes(surf.hit) {
                let (i, sub) = which[k];
                sub_geo[i][sub] = Geometry::new(surf.n[k], view.camera.view_depth(surf.q[k]));
            }
            if sub_shadow.is_empty() || surf.hit == 0 {
                continue;
            }
            let mut cast = [0u32; LANES];
            let mut inherited = [0u32; LANES];
            for k in lanes(surf.hit) {
                let i = which[k].0;
                let a = match agreed {
                    Some((p, a)) if p == i => a,
                    _ => {
                        let a = agree(i % w, first_row + i / w);
                        agreed = Some((i, a));
                        a
                    }
                };
                (cast[k], inherited[k]) = a;
            }
            let bits = self.shadow_states(&surf, &cast, &inherited, tally);
            for k in lanes(surf.hit) {
                let (i, sub) = which[k];
                sub_shadow[i][sub] = bits[k];
            }
        }
        self.rays = rays;
    }
}
