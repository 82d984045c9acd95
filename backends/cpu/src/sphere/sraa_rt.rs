//! SRAA-RT on an SDF (Chiu et al., §3): its buffers, the shading and
//! geometry passes with every ray sphere traced, and the reconstruction and
//! resolve shared with the triangle path.

use std::time::Instant;

use glam::Vec3;
use rayon::prelude::*;
use subcone_kernels::ctss::CtssParams;
use subcone_kernels::passes::{LayerLayout, Passes, Technique, MAX_LIGHTS};
use subcone_kernels::sraa::{Geometry, LayerFlags, SUBPIXEL_OFFSETS};
use subcone_scene::sdf::SplitDistance;
use subcone_scene::{Frame, FrameStats, Method, PassTiming, RayCounts, RenderSettings};

use super::packet::Packets;
use super::{SdfField, SdfView, Tally};
use crate::render::{bands, pixel_centre, reconstruct_frame_on, shadow_agreement, Buffers, BAND};

/// The buffers of an SRAA-RT frame of `n` pixels on an SDF: `nl` layers per
/// pixel, shadow states when the shading is `split` per light, subpixel
/// shadow states with `sub_shadows`. No mirrors, so no secondary buffers.
fn sraa_rt_buffers(n: usize, nl: usize, split: bool, sub_shadows: bool) -> Buffers {
    Buffers {
        geo: vec![Geometry::MISS; n],
        values: vec![Vec3::ZERO; n * nl],
        shadow: if split { vec![0; n] } else { Vec::new() },
        geo2: Vec::new(),
        shadow2: Vec::new(),
        sub_geo: vec![[Geometry::MISS; 4]; n],
        sub_shadow: if sub_shadows {
            vec![[0; 4]; n]
        } else {
            Vec::new()
        },
        sub_geo2: Vec::new(),
        sub_shadow2: Vec::new(),
        // `+mat` is refused on SDF scenes before this point.
        albedo: Vec::new(),
        sub_albedo: Vec::new(),
        flags: vec![LayerFlags::default(); n],
        flags2: Vec::new(),
    }
}

impl<F: SdfField> SdfView<'_, F> {
    /// Shadow states of the point `q` with normal `n` (facing the ray) for
    /// every light, bit set = shadowed, as [`shade`](Self::shade) decides them:
    /// a light facing away shadows without a ray, a light that does not reach
    /// `q` leaves it lit, and only the lights in `cast` are traced; the others
    /// take their bit from `inherited` (SRAA-RT's adaptive subpixel shadows).
    fn shadow_states(&self, q: Vec3, n: Vec3, cast: u32, inherited: u32, tally: &mut Tally) -> u32 {
        let mut bits = 0;
        for (l, light) in self.lights.iter().enumerate().take(MAX_LIGHTS) {
            let Some(inc) = light.incident(q) else {
                continue;
            };
            if inc.direction.dot(n) <= 0.0 {
                bits |= 1 << l;
            } else if cast & (1 << l) == 0 {
                bits |= inherited & (1 << l);
            } else if self.shadowed(q, n, inc.direction, inc.distance, tally) {
                bits |= 1 << l;
            }
        }
        bits
    }

    /// The shading of [`shade`](Self::shade) split into SRAA-RT's layers
    /// (§3.2): `out[0]` the shadow-independent part (emission and ambient),
    /// `out[1 + l]` light `l`'s direct part where `bits` says it is lit. With
    /// `split` false, everything goes to `out[0]`; the sum is `shade`'s colour
    /// in the same order.
    fn shade_layers(
        &self,
        q: Vec3,
        n: Vec3,
        bits: u32,
        split: bool,
        out: &mut [Vec3],
        tally: &mut Tally,
    ) {
        let SplitDistance { material: m, .. } = self.field.eval_split(q);
        let ao = self.ambient_occlusion(q, n, tally);
        self.shade_layers_of(m, q, n, bits, (split, ao), out);
    }

    /// SRAA for ray tracing (Chiu et al., §3) on an SDF: the triangle path's
    /// passes (`render::subpixel`) with sphere tracing for every ray.
    ///
    /// Pass "shading" ([`sraa_shading_pass`](Self::sraa_shading_pass)): one
    /// sample per pixel at subsample
    /// [`SHADED_SUBSAMPLE`](subcone_kernels::sraa::SHADED_SUBSAMPLE), sphere traced and shaded as NoAA shades (hard
    /// shadows through the field), kept in layers: the shadow-independent part
    /// and one per light with its shadow state. Pass "geometry"
    /// ([`sraa_geometry_pass`](Self::sraa_geometry_pass), the paper's pass 1):
    /// the other three subsamples sphere traced for geometry (normal
    /// facing the ray, view depth) and, with lights, their shadow states by
    /// subpixel shadow rays (eq. 2's gate; cast only where the shaded samples
    /// around disagree, unless exhaustive). Pass "antialiasing" (pass 2): the
    /// kernels' reconstruction and resolve, shared with the triangle path.
    /// SDF scenes have no mirrors, so there are no secondary passes; a scene
    /// without lights gets no shadow pass and no shadow buffers.
    pub(super) fn sraa_rt(&self, method: &Method, s: &RenderSettings, passes: Passes) -> Frame {
        let (w, h) = (s.width as usize, s.height as usize);
        let n = w * h;
        let lights = self.lights.len().min(MAX_LIGHTS);
        let layout = LayerLayout::new(Technique::SraaRt, passes, lights);
        let shadows = passes.contains(Passes::SHADOW);
        let sub_shadows = passes.contains(Passes::SUBPIXEL_SHADOW) && layout.lights > 0;
        let nl = layout.len();
        let split = layout.lights > 0;
        let params = self.params(method, s.height);
        let mut b = sraa_rt_buffers(n, nl, split, sub_shadows);
        let mut timings = Vec::new();

        let start = Instant::now();
        let shaded = self.sraa_shading_pass(method, s, &params, (shadows, split, nl), &mut b);
        timings.push(PassTiming::cpu("shading", start.elapsed()));

        let start = Instant::now();
        let geometry = self.sraa_geometry_pass(method, s, &params, &layout, &mut b);
        timings.push(PassTiming::cpu("geometry", start.elapsed()));

        // Pass 2 of the paper: reconstruction and resolve.
        let start = Instant::now();
        let mut frame = Frame::new(s.width, s.height);
        reconstruct_frame_on(
            self.isa,
            &mut b,
            &layout,
            &method.sraa(),
            &mut frame.color,
            w,
            h,
        );
        timings.push(PassTiming::cpu("antialiasing", start.elapsed()));

        let tally = shaded + geometry;
        frame.stats = FrameStats {
            passes,
            timings,
            buffers: b.list(&frame.color),
            rays: RayCounts {
                primary: n as u64,
                geometry: 3 * n as u64,
                shadow: tally.shadow,
                ao: tally.ao,
                ..Default::default()
            },
            shaded_samples: tally.samples,
            sdf_evaluations: tally.steps,
            multi_sample_pixels: 0,
            raster_samples: 0,
        };
        if s.aovs {
            self.centre_aovs(&mut frame, s);
            frame.samples_per_pixel = Some(vec![1.0; n]);
        }
        frame
    }

    /// SRAA-RT's pass "shading" on an SDF: one sample per pixel at the
    /// method's shaded offset, sphere traced (in packets when the field has
    /// a program) and shaded into `layers` = (shadow rays, one layer per
    /// light, layers per pixel); returns its tally.
    #[allow(clippy::needless_range_loop)]
    fn sraa_shading_pass(
        &self,
        method: &Method,
        s: &RenderSettings,
        params: &CtssParams,
        layers: (bool, bool, usize),
        b: &mut Buffers,
    ) -> Tally {
        let (shadows, split, nl) = layers;
        let (w, h) = (s.width as usize, s.height as usize);
        let nb = h.div_ceil(BAND);
        let band = w * BAND;
        let packets = || self.program.as_ref().map(|p| Packets::new(self, p));
        bands(&mut b.geo, band, nb)
            .into_par_iter()
            .zip(bands(&mut b.values, band * nl, nb))
            .zip(bands(&mut b.shadow, band, nb))
            .enumerate()
            .map_init(packets, |packets, (bi, ((geo, values), shadow))| {
                let mut t = Tally::default();
                if let Some(pk) = packets {
                    pk.sraa_shading_band(
                        bi * BAND,
                        method.sraa().shaded_offset(),
                        params,
                        s,
                        layers,
                        geo,
                        values,
                        shadow,
                        &mut t,
                    );
                    return t;
                }
                for i in 0..geo.len() {
                    let (x, y) = (i % w, bi * BAND + i / w);
                    let px = pixel_centre(x, y) + method.sraa().shaded_offset();
                    let (o, d) = self.camera.ray(px, s.width, s.height);
                    let v = &mut values[i * nl..(i + 1) * nl];
                    let Some((q, nrm)) = self.hit(o, d, params, &mut t) else {
                        v[0] = self.background;
                        continue;
                    };
                    t.samples += 1;
                    geo[i] = Geometry::new(nrm, self.camera.view_depth(q));
                    let bits = if shadows {
                        self.shadow_states(q, nrm, u32::MAX, 0, &mut t)
                    } else {
                        0
                    };
                    if let Some(sh) = shadow.get_mut(i) {
                        *sh = bits;
                    }
                    self.shade_layers(q, nrm, bits, split, v, &mut t);
                }
                t
            })
            .reduce(Tally::default, |a, b| a + b)
    }

    /// SRAA-RT's pass "geometry" on an SDF (the paper's pass 1): every
    /// pixel's subsamples sphere traced for geometry and, with subpixel
    /// shadows, their shadow states (the shaded subsample's copied from the
    /// shading pass); returns its tally.
    #[allow(clippy::needless_range_loop)]
    fn sraa_geometry_pass(
        &self,
        method: &Method,
        s: &RenderSettings,
        params: &CtssParams,
        layout: &LayerLayout,
        b: &mut Buffers,
    ) -> Tally {
        let (w, h) = (s.width as usize, s.height as usize);
        let nl = layout.len();
        let nb = h.div_ceil(BAND);
        let band = w * BAND;
        let packets = || self.program.as_ref().map(|p| Packets::new(self, p));
        let radius = method.sraa().radius();
        let adaptive = !self.exhaustive_subpixel_shadows;
        let (geo, shadow, values) = (&b.geo, &b.shadow, &b.values);
        let agreement = |x: usize, y: usize| {
            if adaptive {
                shadow_agreement(shadow, values, nl, 0, layout.lights, x, y, radius, w, h)
            } else {
                (u32::MAX, 0)
            }
        };
        bands(&mut b.sub_geo, band, nb)
            .into_par_iter()
            .zip(bands(&mut b.sub_shadow, band, nb))
            .enumerate()
            .map_init(packets, |packets, (bi, (sub_geo, sub_shadow))| {
                let mut t = Tally::default();
                if let Some(pk) = packets {
                    // The shaded subsample's geometry and shadow states
                    // are the shading pass's.
                    if let Some(k) = method.sraa().shaded_subsample() {
                        for (i, g) in sub_geo.iter_mut().enumerate() {
                            g[k] = geo[bi * band + i];
                        }
                        for (i, ss) in sub_shadow.iter_mut().enumerate() {
                            ss[k] = shadow[bi * band + i];
                        }
                    }
                    pk.sraa_geometry_band(
                        bi * BAND,
                        method.sraa().shaded_subsample(),
                        params,
                        s,
                        agreement,
                        sub_geo,
                        sub_shadow,
                        &mut t,
                    );
                    return t;
                }
                for i in 0..sub_geo.len() {
                    let (x, y) = (i % w, bi * BAND + i / w);
                    let j = bi * band + i;
                    let mut agree = None;
                    for k in 0..4 {
                        if Some(k) == method.sraa().shaded_subsample() {
                            sub_geo[i][k] = geo[j];
                            if let Some(ss) = sub_shadow.get_mut(i) {
                                ss[k] = shadow[j];
                            }
                            continue;
                        }
                        let px = pixel_centre(x, y) + SUBPIXEL_OFFSETS[k];
                        let (o, d) = self.camera.ray(px, s.width, s.height);
                        let Some((q, nrm)) = self.hit(o, d, params, &mut t) else {
                            continue;
                        };
                        sub_geo[i][k] = Geometry::new(nrm, self.camera.view_depth(q));
                        if let Some(ss) = sub_shadow.get_mut(i) {
                            let (cast, inherited) = *agree.get_or_insert_with(|| agreement(x, y));
                            ss[k] = self.shadow_states(q, nrm, cast, inherited, &mut t);
                        }
                    }
                }
                t
            })
            .reduce(Tally::default, |a, b| a + b)
    }
}
