//! Whitted shading on top of the BVH: direct light with hard shadows and mirror
//! reflection, split into the parts SRAA-RT reconstructs separately.

use glam::{Vec2, Vec3, Vec3A};
use subcone_kernels::ao::{ao_direction, ao_fraction, AO_RADIUS_FRACTION};
use subcone_kernels::math::Euclidean;
use subcone_kernels::sraa::Geometry;
use subcone_scene::{Camera, Scene, TriangleMesh};

use crate::bvh::{Hit, SceneBvh};
use crate::isa::Isa;

pub use subcone_kernels::passes::MAX_LIGHTS;

/// A surface point seen by a ray.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// Position.
    pub p: Vec3,
    /// Shading normal, facing the incoming ray.
    pub n: Vec3,
    /// Geometric normal, facing the incoming ray (for ray offsets).
    pub ng: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Material index.
    pub material: u32,
    /// Distance along the ray.
    pub t: f32,
}

/// Ray counters of one worker, summed at the end of a pass.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counts {
    /// Shaded primary rays.
    pub primary: u64,
    /// Geometry-only rays.
    pub geometry: u64,
    /// Shadow rays.
    pub shadow: u64,
    /// Shaded reflection rays.
    pub secondary: u64,
    /// Shading evaluations.
    pub shaded: u64,
    /// Ambient-occlusion rays.
    pub ao: u64,
    /// Primary samples whose visibility the rasteriser decided (`-hybrid`).
    pub raster: u64,
}

impl std::ops::Add for Counts {
    type Output = Counts;
    fn add(self, o: Counts) -> Counts {
        Counts {
            primary: self.primary + o.primary,
            geometry: self.geometry + o.geometry,
            shadow: self.shadow + o.shadow,
            secondary: self.secondary + o.secondary,
            shaded: self.shaded + o.shaded,
            ao: self.ao + o.ao,
            raster: self.raster + o.raster,
        }
    }
}

/// The shading of one surface point, split into what SRAA-RT reconstructs
/// separately: the shadow-independent part, one part per light with its shadow
/// state, and the mirror share.
#[derive(Clone, Copy, Debug, Default)]
pub struct Parts {
    /// Emission plus ambient (times the ambient occlusion at primary hits):
    /// no shadow ray decides it.
    pub base: Vec3,
    /// Each light's direct contribution (0 when shadowed).
    pub direct: [Vec3; MAX_LIGHTS],
    /// Bit `l` set: the point is in light `l`'s shadow.
    pub shadowed: u32,
    /// Mirror reflectance of the material.
    pub mirror: f32,
}

impl Parts {
    /// The diffuse (non-mirror) radiance.
    pub fn diffuse(&self, lights: usize) -> Vec3 {
        self.direct[..lights].iter().fold(self.base, |a, d| a + *d)
    }
}

/// Everything a pass needs to trace and shade.
pub struct Tracer<'a> {
    /// The scene's BVH.
    pub bvh: &'a SceneBvh,
    /// The scene.
    pub scene: &'a Scene,
    /// Its triangles.
    pub mesh: &'a TriangleMesh,
    /// The camera.
    pub camera: &'a Camera,
    /// Mirror bounces.
    pub reflection_depth: u32,
    /// Offset of secondary ray origins, in scene units.
    pub eps: f32,
    /// SRAA-RT: cast every subsample's shadow rays, instead of only where the
    /// shaded samples around it disagree about a light (the default; see
    /// `render::shadow_agreement`).
    pub exhaustive_subpixel_shadows: bool,
    /// Ambient-occlusion rays per shaded primary hit (0: off).
    pub ao_rays: u32,
    /// Their length: `AO_RADIUS_FRACTION` of the scene's bounding diagonal.
    pub ao_radius: f32,
    /// The instruction-set path the passes run on (the widest the CPU
    /// supports unless set); every path gives the same bits.
    pub isa: Isa,
    /// Side of the tiles SRAA renders in (`CpuBackend::with_tile`).
    pub tile: usize,
}

impl<'a> Tracer<'a> {
    /// A tracer over a scene's BVH.
    pub fn new(
        bvh: &'a SceneBvh,
        scene: &'a Scene,
        mesh: &'a TriangleMesh,
        camera: &'a Camera,
        reflection_depth: u32,
    ) -> Self {
        Tracer {
            bvh,
            scene,
            mesh,
            camera,
            reflection_depth,
            eps: bvh.scale * 2e-5,
            exhaustive_subpixel_shadows: false,
            ao_rays: 0,
            ao_radius: bvh.scale * AO_RADIUS_FRACTION,
            isa: Isa::detected(),
            tile: crate::render::TILE,
        }
    }

    /// Closest surface along a ray.
    #[inline(always)]
    pub fn intersect(&self, o: Vec3, d: Vec3, tmin: f32) -> Option<Surface> {
        let hit = self.bvh.closest(o, d, tmin, f32::INFINITY)?;
        Some(self.surface(o, d, hit))
    }

    /// The surface a ray `o + t·d` hit: position, normals, texture
    /// coordinates and material ([`Self::intersect`] after the traversal).
    #[inline(always)]
    pub fn surface(&self, o: Vec3, d: Vec3, hit: Hit) -> Surface {
        let tri = self.bvh.shading(hit.slot);
        // In SIMD lanes (`Vec3A`): the same operations in the same order as
        // scalar `Vec3`, so the same bits, in fewer instructions. The
        // triangle's normal is precomputed by the same operations
        // (`bvh::TriangleShading`); the barycentrics are the intersector's,
        // from the test that found `t`.
        let (o, d) = (Vec3A::from(o), Vec3A::from(d));
        let p = o + hit.t * d;
        // The intersector's barycentrics: the weights of v1 and v2.
        let (b1, b2) = (hit.barycentrics.x, hit.barycentrics.y);
        let b0 = 1.0 - b1 - b2;
        let [n0, n1, n2] = tri.normals;
        let uv = tri.uvs;
        let mut ng = tri.normal;
        if ng.dot(d) > 0.0 {
            ng = -ng;
        }
        let mut n = (b0 * n0 + b1 * n1 + b2 * n2).normalize_or_zero();
        if n == Vec3A::ZERO {
            n = ng;
        } else if n.dot(d) > 0.0 {
            n = -n;
        }
        Surface {
            p: p.into(),
            n: n.into(),
            ng: ng.into(),
            uv: b0 * uv[0] + b1 * uv[1] + b2 * uv[2],
            material: tri.material,
            t: hit.t,
        }
    }

    /// The SRAA geometry (normal and view depth) of a primary surface.
    #[inline(always)]
    pub fn primary_geometry(&self, s: Option<&Surface>) -> Geometry {
        match s {
            Some(s) => Geometry::new(s.n, self.camera.view_depth(s.p)),
            None => Geometry::MISS,
        }
    }

    /// The diffuse albedo of a primary surface, for the material gate
    /// (`subcone_kernels::sraa::material_gated_weight`): the texture or
    /// pattern at the hit, the material's constant elsewhere; black for a
    /// miss (a miss never matches a hit anyway: its depth weight is 0).
    #[inline(always)]
    pub fn primary_albedo(&self, s: Option<&Surface>) -> Vec3 {
        match s {
            Some(s) => self.scene.materials[s.material as usize].albedo_at(s.p, s.uv),
            None => Vec3::ZERO,
        }
    }

    /// Shadow states of `s` for every light (bit set = shadowed), casting one
    /// shadow ray per light that faces the surface.
    #[inline(always)]
    pub fn shadow_states(&self, s: &Surface, c: &mut Counts) -> u32 {
        self.shadow_states_masked(s, u32::MAX, 0, c)
    }

    /// [`Self::shadow_states`], casting a shadow ray only for the lights whose
    /// bit is set in `cast`. A light outside `cast` still gets the free answers
    /// (no incident light: lit; facing away: shadowed); where a ray would have
    /// decided, it takes its bit from `inherited` instead.
    #[inline(always)]
    pub fn shadow_states_masked(
        &self,
        s: &Surface,
        cast: u32,
        inherited: u32,
        c: &mut Counts,
    ) -> u32 {
        let mut bits = 0;
        let origin = s.p + s.ng * self.eps;
        for (l, light) in self.scene.lights.iter().enumerate().take(MAX_LIGHTS) {
            let Some(inc) = light.incident(s.p) else {
                continue;
            };
            if inc.direction.dot(s.ng) <= 0.0 {
                bits |= 1 << l; // facing away: self-shadowed, no ray needed
                continue;
            }
            if cast & (1 << l) == 0 {
                bits |= inherited & (1 << l);
                continue;
            }
            c.shadow += 1;
            if self
                .bvh
                .occluded(origin, inc.direction, 0.0, inc.distance - self.eps)
            {
                bits |= 1 << l;
            }
        }
        bits
    }

    /// Per-light visibility of `s` for the AOV (`Frame::light_visibility`):
    /// bit `l` set when no geometry blocks the segment to light `l`. A light
    /// the surface faces away from is counted visible without a ray: its
    /// cosine falls smoothly to 0, so turning away is no shadow edge.
    #[inline]
    pub fn light_visibility(&self, s: &Surface) -> u32 {
        let mut bits = 0;
        let origin = s.p + s.ng * self.eps;
        for (l, light) in self.scene.lights.iter().enumerate().take(MAX_LIGHTS) {
            let Some(inc) = light.incident(s.p) else {
                continue;
            };
            if inc.direction.dot(s.ng) <= 0.0
                || !self
                    .bvh
                    .occluded(origin, inc.direction, 0.0, inc.distance - self.eps)
            {
                bits |= 1 << l;
            }
        }
        bits
    }

    /// The unoccluded fraction of `s` ([`subcone_kernels::ao`]): of
    /// [`Self::ao_rays`] fixed directions around the shading normal, those
    /// whose any-hit ray of length [`Self::ao_radius`] from the offset
    /// origin hits nothing that casts shadows (emitters do not occlude, as
    /// for shadow rays). A direction below the geometric surface (possible
    /// where the shading normal is interpolated) is occluded by the surface
    /// itself, without a ray. Exactly 1 when AO is off.
    #[inline(always)]
    pub fn ambient_occlusion(&self, s: &Surface, c: &mut Counts) -> f32 {
        let n = self.ao_rays;
        if n == 0 {
            return 1.0;
        }
        let origin = s.p + s.ng * self.eps;
        let mut open = 0;
        for i in 0..n {
            let d = ao_direction(s.n, i, n);
            if d.dot(s.ng) <= 0.0 {
                continue;
            }
            c.ao += 1;
            if !self.bvh.occluded(origin, d, 0.0, self.ao_radius) {
                open += 1;
            }
        }
        ao_fraction(open, n)
    }

    /// Shade a surface seen along `d`: the split parts (without the
    /// reflection). `ao` multiplies the ambient term: the point's
    /// [`Self::ambient_occlusion`] at primary hits, 1 at mirror hits (AO is
    /// not applied to secondary shading). With `ao == 1` the parts are bit for
    /// bit those without ambient occlusion (`x · 1 = x`).
    #[inline(always)]
    pub fn parts(&self, s: &Surface, shadowed: u32, ao: f32) -> Parts {
        let mat = &self.scene.materials[s.material as usize];
        let albedo = mat.albedo_at(s.p, s.uv);
        let mut parts = Parts {
            base: mat.emission + self.scene.ambient * ao * albedo,
            shadowed,
            mirror: mat.mirror,
            ..Default::default()
        };
        for (l, light) in self.scene.lights.iter().enumerate().take(MAX_LIGHTS) {
            if shadowed & (1 << l) != 0 {
                continue;
            }
            if let Some(inc) = light.incident(s.p) {
                let cos = inc.direction.dot(s.n).max(0.0);
                parts.direct[l] = albedo * std::f32::consts::FRAC_1_PI * cos * inc.irradiance;
            }
        }
        parts
    }

    /// Mirror direction of `d` about `n`.
    #[inline]
    pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
        (d - 2.0 * d.dot(n) * n).unit()
    }

    /// Full Whitted radiance along a ray, `depth` bounces already taken;
    /// ambient occlusion at `depth == 0` only.
    #[inline(always)]
    pub fn radiance(&self, o: Vec3, d: Vec3, depth: u32, c: &mut Counts) -> Vec3 {
        let s = self.intersect(o, d, 0.0);
        self.radiance_at(d, s.as_ref(), depth, c)
    }

    /// [`Self::radiance`] of a ray along `d` that was already traced to
    /// `surface` (`None`: a miss).
    #[inline(always)]
    pub fn radiance_at(
        &self,
        d: Vec3,
        surface: Option<&Surface>,
        depth: u32,
        c: &mut Counts,
    ) -> Vec3 {
        let Some(&s) = surface else {
            return self.scene.background;
        };
        c.shaded += 1;
        let shadow = self.shadow_states(&s, c);
        let ao = if depth == 0 {
            self.ambient_occlusion(&s, c)
        } else {
            1.0
        };
        let parts = self.parts(&s, shadow, ao);
        let diffuse = parts.diffuse(self.scene.lights.len().min(MAX_LIGHTS));
        if parts.mirror > 0.0 && depth < self.reflection_depth {
            c.secondary += 1;
            let r = self.reflected(s.p + s.ng * self.eps, Self::reflect(d, s.n), depth + 1, c);
            (1.0 - parts.mirror) * diffuse + parts.mirror * r
        } else {
            diffuse
        }
    }

    /// [`Self::radiance`] of a reflection ray: a call (the recursion cannot
    /// be inlined) that enters the instruction-set path again.
    #[inline(never)]
    pub fn reflected(&self, o: Vec3, d: Vec3, depth: u32, c: &mut Counts) -> Vec3 {
        self.isa.run(
            #[inline(always)]
            || self.radiance(o, d, depth, c),
        )
    }
}
