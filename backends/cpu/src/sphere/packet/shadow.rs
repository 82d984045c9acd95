//! Shadow rays and the shading that casts them: one ray's march
//! ([`ShadowRay`]), a packet's rays ([`Packets::shadowed`]), a row's rays as
//! one stream with every lane kept busy ([`Packets::shadowed_stream`]), and
//! the Lambert shading of a row's samples over it
//! ([`Packets::shade_samples`]).

use glam::{Vec2, Vec3};
use subcone_kernels::math::Euclidean;
use subcone_sdf::program::{Points, LANES};

use super::{first, lanes, LaneMask, Packets, SdfField, Tally};

/// A shadow ray's march towards a light (the scalar path's `shadowed`), one
/// evaluation at a time.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::sphere) struct ShadowRay {
    o: Vec3,
    l: Vec3,
    eps: f32,
    t: f32,
    limit: f32,
    steps: u32,
}

impl ShadowRay {
    /// From `p` (normal `n`, facing the light side) towards unit `l`, at most
    /// `dist` (the light) or `max_distance` away.
    #[inline(always)]
    pub(in crate::sphere) fn new(
        p: Vec3,
        n: Vec3,
        l: Vec3,
        dist: f32,
        max_distance: f32,
    ) -> ShadowRay {
        let eps = 1e-4 * (1.0 + p.norm());
        ShadowRay {
            o: p + n * (4.0 * eps),
            l,
            eps,
            t: 0.0,
            limit: dist.min(max_distance),
            steps: 0,
        }
    }

    /// The next point to evaluate, or the answer (`false`: lit) when the
    /// march ends before it.
    #[inline(always)]
    pub(in crate::sphere) fn next(&self, max_steps: u32) -> Result<Vec3, bool> {
        if self.steps >= max_steps || self.t >= self.limit {
            return Err(false);
        }
        Ok(self.o + self.l * self.t)
    }

    /// Takes the field at the point of [`next`](Self::next); the answer
    /// (`true`: shadowed) when the march ends.
    #[inline(always)]
    pub(in crate::sphere) fn feed(&mut self, safe: f32, d: f32) -> Option<bool> {
        self.steps += 1;
        if d.is_nan() {
            return Some(false);
        }
        if d < self.eps * (1.0 + self.t * 1e-3) {
            return Some(true);
        }
        let next = self.t + safe.min(d);
        self.t = if next > self.t {
            next
        } else {
            self.t.next_up()
        };
        None
    }
}

/// The per-sample state of [`Packets::shade_samples`], kept from one row to
/// the next: each sample's albedo and normal turned to face its ray, and
/// per light the shadow rays with the sample, cosine and irradiance each
/// belongs to, and their answers.
#[derive(Default)]
pub(super) struct ShadingRow {
    albedo: Vec<Vec3>,
    facing: Vec<Vec3>,
    rays: Vec<ShadowRay>,
    lit_by: Vec<(usize, f32, Vec3)>,
    blocked: Vec<bool>,
}

impl<F: SdfField> Packets<'_, '_, F> {
    /// Which of the `active` shadow rays are blocked, the whole march on
    /// the instruction-set path.
    #[inline(never)]
    pub(super) fn shadowed(&mut self, rays: &mut [ShadowRay; LANES], active: LaneMask) -> LaneMask {
        let isa = self.view.isa;
        isa.run(
            #[inline(always)]
            || self.shadowed_here(rays, active),
        )
    }

    #[inline(always)]
    fn shadowed_here(&mut self, rays: &mut [ShadowRay; LANES], mut active: LaneMask) -> LaneMask {
        let max_steps = self.view.max_steps;
        let mut blocked = 0;
        let mut pts = Points::default();
        loop {
            for k in lanes(active) {
                match rays[k].next(max_steps) {
                    Ok(p) => pts.set(k, p),
                    Err(_) => active &= !(1 << k),
                }
            }
            if active == 0 {
                return blocked;
            }
            let r = self.eval(&pts, active);
            for k in lanes(active) {
                if let Some(b) = rays[k].feed(r.safe[k], r.surface[k]) {
                    blocked |= (b as LaneMask) << k;
                    active &= !(1 << k);
                }
            }
        }
    }

    /// Which of `rays` are blocked, into `blocked` (one answer per ray):
    /// the rays marched eight at a time with every lane kept busy, a lane
    /// that finishes its ray taking the next one at once. [`shadowed`]
    /// marches a packet's rays until the last of them ends, with fewer and
    /// fewer lanes active; a stream loses no lanes until its last rays. Each
    /// ray sees the field values it sees alone (a lane's evaluation does not
    /// depend on the other lanes), so each answer is the scalar path's.
    ///
    /// [`shadowed`]: Self::shadowed
    #[inline(never)]
    pub(super) fn shadowed_stream(&mut self, rays: &mut [ShadowRay], blocked: &mut [bool]) {
        let isa = self.view.isa;
        isa.run(
            #[inline(always)]
            || self.shadowed_stream_here(rays, blocked),
        )
    }

    #[inline(always)]
    fn shadowed_stream_here(&mut self, rays: &mut [ShadowRay], blocked: &mut [bool]) {
        let max_steps = self.view.max_steps;
        let mut pts = Points::default();
        // The ray each lane marches, and the next ray to start.
        let mut slot = [0usize; LANES];
        let mut next = 0;
        let mut active: LaneMask = 0;
        loop {
            for (k, sk) in slot.iter_mut().enumerate() {
                loop {
                    if active & (1 << k) == 0 {
                        if next == rays.len() {
                            break;
                        }
                        *sk = next;
                        next += 1;
                        active |= 1 << k;
                    }
                    match rays[*sk].next(max_steps) {
                        Ok(p) => {
                            pts.set(k, p);
                            break;
                        }
                        Err(b) => {
                            blocked[*sk] = b;
                            active &= !(1 << k);
                        }
                    }
                }
            }
            if active == 0 {
                return;
            }
            let r = self.eval(&pts, active);
            for k in lanes(active) {
                if let Some(b) = rays[slot[k]].feed(r.safe[k], r.surface[k]) {
                    blocked[slot[k]] = b;
                    active &= !(1 << k);
                }
            }
        }
    }

    /// The scalar path's `shade` (Lambert with hard shadows and ambient
    /// light) for every sample of a row at once, into `out`: sample `i` at point `q[i]` with normal `n[i]`, seen along
    /// `dir[i]`. The materials are read in packets of eight; each light's
    /// shadow rays go through [`shadowed_stream`](Self::shadowed_stream)
    /// together. Every sample's colour is `shade`'s, the same operations
    /// in the same order (base, then each light in turn), so the same bits.
    pub(super) fn shade_samples(
        &mut self,
        q: &[Vec3],
        n: &[Vec3],
        dir: &[Vec3],
        out: &mut [Vec3],
        tally: &mut Tally,
    ) {
        let view = self.view;
        let mut row = std::mem::take(&mut self.shading);
        row.albedo.clear();
        row.facing.clear();
        for start in (0..q.len()).step_by(LANES) {
            let end = (start + LANES).min(q.len());
            let mut pts = Points::default();
            for (k, qk) in q[start..end].iter().enumerate() {
                pts.set(k, *qk);
            }
            let mats = self.eval(&pts, first(end - start)).material;
            for (i, &m) in (start..end).zip(&mats) {
                let mat = view.material(m);
                let albedo = mat.albedo_at(q[i], Vec2::ZERO);
                row.albedo.push(albedo);
                row.facing
                    .push(if n[i].dot(dir[i]) > 0.0 { -n[i] } else { n[i] });
                out[i] = mat.emission + view.ambient * albedo;
            }
        }
        for light in view.lights {
            row.rays.clear();
            row.lit_by.clear();
            for (i, qi) in q.iter().enumerate() {
                let Some(inc) = light.incident(*qi) else {
                    continue;
                };
                let cos = inc.direction.dot(row.facing[i]);
                if cos <= 0.0 {
                    continue;
                }
                row.rays.push(ShadowRay::new(
                    *qi,
                    row.facing[i],
                    inc.direction,
                    inc.distance,
                    view.max_distance,
                ));
                row.lit_by.push((i, cos, inc.irradiance));
            }
            tally.shadow += row.rays.len() as u64;
            row.blocked.clear();
            row.blocked.resize(row.rays.len(), false);
            self.shadowed_stream(&mut row.rays, &mut row.blocked);
            for (&(i, cos, irradiance), &b) in row.lit_by.iter().zip(&row.blocked) {
                if !b {
                    out[i] += row.albedo[i] * std::f32::consts::FRAC_1_PI * cos * irradiance;
                }
            }
        }
        self.shading = row;
    }

    /// The row buffers of the samples to shade, emptied (kept allocated from
    /// one row to the next; [`put_samples`](Self::put_samples) returns them).
    pub(super) fn take_samples(&mut self) -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec3>) {
        let mut q = std::mem::take(&mut self.points);
        let mut n = std::mem::take(&mut self.normals);
        let mut dir = std::mem::take(&mut self.directions);
        q.clear();
        n.clear();
        dir.clear();
        (q, n, dir)
    }

    pub(super) fn put_samples(&mut self, q: Vec<Vec3>, n: Vec<Vec3>, dir: Vec<Vec3>) {
        (self.points, self.normals, self.directions) = (q, n, dir);
    }
}
