//! `subcone-cpu`: the CPU reference backend.
//!
//! Triangle scenes are ray traced through an obvhs CWBVH (built once per scene
//! and cached), in parallel over image bands with rayon, with Whitted shading:
//! direct light with hard shadows and mirror reflection. Methods: NoAA, SSAA,
//! SRAA and SRAA-RT. SDF scenes are sphere traced (`sphere`): NoAA, SSAA, the
//! CTSS family and SRAA-RT. All weight and reconstruction maths is the kernels'.
//! FXAA (every scene) is NoAA followed by [`post::fxaa`]. What it refuses
//! ([`Backend::supports`]): what the kernels refuse, more than
//! [`shade::MAX_LIGHTS`] lights, mirrors and the material gate on SDF scenes,
//! and semi-transparent materials outside the SDF paths that carry opacity.
//!
//! ```
//! use subcone_cpu::CpuBackend;
//! use subcone_kernels::passes::Technique;
//! use subcone_scene::{builtin::builtin, Backend, Method, RenderSettings};
//!
//! let scene = builtin("cornell").unwrap();
//! let sraa_rt = Method::new(Technique::SraaRt);
//! let frame = CpuBackend::new()
//!     .render(&scene, &scene.camera, &sraa_rt, &RenderSettings::new(32, 32))
//!     .unwrap();
//! assert_eq!(frame.color.len(), 32 * 32);
//! ```
// One module, `isa`, calls into `#[target_feature]` code after detecting the
// features at run time; everything else is safe code.
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod bvh;
pub mod isa;
pub mod post;
pub mod raster;
mod render;
pub mod shade;
pub mod sphere;
pub mod throughput;

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use subcone_kernels::passes::{Passes, Technique};
use subcone_scene::backend::{plan, render_passes, Capabilities};
use subcone_scene::{
    Backend, Camera, Frame, Method, RenderError, RenderSettings, Scene, Unsupported,
};

pub use bvh::SceneBvh;
// Public for `tests/render.rs` (the library has no unit-test build: see
// Cargo.toml), not part of the API.
#[doc(hidden)]
pub use render::shadow_agreement;
use shade::{Tracer, MAX_LIGHTS};
use sphere::{SdfField, SdfView};

impl SdfField for subcone_scene::sdf::SdfNode {
    #[inline]
    fn eval(&self, p: glam::Vec3) -> (f32, u32) {
        subcone_scene::sdf::SdfNode::eval(self, p)
    }

    #[inline]
    fn eval_split(&self, p: glam::Vec3) -> subcone_scene::sdf::SplitDistance {
        subcone_scene::sdf::SdfNode::eval_split(self, p)
    }

    #[inline]
    fn normal(&self, p: glam::Vec3, h: f32) -> glam::Vec3 {
        subcone_scene::sdf::SdfNode::normal_surface(self, p, h)
    }
}

/// The CPU backend. Cheap to create; it caches one BVH per scene.
#[derive(Default)]
pub struct CpuBackend {
    cache: Mutex<HashMap<u64, Arc<SceneBvh>>>,
    exhaustive_subpixel_shadows: bool,
    /// `None`: the widest path the CPU supports.
    isa: Option<isa::Isa>,
    /// `None`: [`TILE`].
    tile: Option<usize>,
}

/// The side, in pixels, of the tiles SRAA and SRAA-RT render a triangle
/// scene in (each tile's passes run before the next; see
/// [`CpuBackend::with_tile`]).
pub const TILE: usize = render::TILE;

impl CpuBackend {
    /// A backend with an empty BVH cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// SRAA-RT casts every subsample's shadow rays (the paper's pass 1 as
    /// written) when `on`; by default it casts them only where the shaded
    /// samples around a subsample disagree about a light's shadow.
    pub fn with_exhaustive_subpixel_shadows(mut self, on: bool) -> Self {
        self.exhaustive_subpixel_shadows = on;
        self
    }

    /// Runs the hot loops on instruction-set path `isa` (or the widest
    /// supported one below it) instead of the widest the CPU supports. Every
    /// path renders the same images bit for bit; this is for measuring and
    /// testing them.
    pub fn with_isa(mut self, isa: isa::Isa) -> Self {
        self.isa = Some(isa);
        self
    }

    /// SRAA and SRAA-RT on triangle scenes render in `side`×`side` tiles
    /// (at least 1) instead of [`TILE`]×[`TILE`]. Every tile size renders
    /// the same image bit for bit; what changes is the memory (buffers of
    /// one tile per thread), the cache traffic, and the shaded samples of
    /// the tiles' aprons, shaded once per tile that reads them. For
    /// measuring and testing; a side as large as the image is the
    /// whole-frame pipeline.
    ///
    /// ```
    /// use subcone_cpu::CpuBackend;
    /// use subcone_scene::{builtin::builtin, Backend, Method, RenderSettings};
    ///
    /// let scene = builtin("cornell").unwrap();
    /// let method: Method = "sraa-rt".parse().unwrap();
    /// let s = RenderSettings::new(40, 24);
    /// let tiled = CpuBackend::new().with_tile(16).render(&scene, &scene.camera, &method, &s);
    /// let whole = CpuBackend::new().with_tile(40).render(&scene, &scene.camera, &method, &s);
    /// assert_eq!(tiled.unwrap().color, whole.unwrap().color);
    /// ```
    pub fn with_tile(mut self, side: usize) -> Self {
        self.tile = Some(side.max(1));
        self
    }

    /// The instruction-set path the hot loops run on.
    pub fn isa(&self) -> isa::Isa {
        self.isa
            .map_or_else(isa::Isa::detected, isa::Isa::or_supported)
    }

    /// The BVH of `scene`, built on first use.
    pub fn bvh(&self, scene: &Scene) -> Result<Arc<SceneBvh>, RenderError> {
        let mesh = scene.mesh().ok_or_else(|| RenderError::Backend {
            backend: "cpu",
            reason: format!("scene {:?} has no triangles", scene.name),
        })?;
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        let casts = |i: usize| {
            let m = mesh.materials[i] as usize;
            scene
                .materials
                .get(m)
                .is_none_or(|m| m.emission == glam::Vec3::ZERO)
        };
        Ok(cache
            .entry(scene.id())
            .or_insert_with(|| Arc::new(SceneBvh::build(mesh, casts)))
            .clone())
    }
}

/// What the CPU backend renders: every technique on every scene the
/// kernels accept, up to [`MAX_LIGHTS`] lights, SRAA-RT on SDF scenes
/// included; the refusals are the one plan's
/// ([`subcone_scene::backend::plan`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    backend: "cpu",
    max_lights_triangles: Some(MAX_LIGHTS),
    max_lights_sdf: Some(MAX_LIGHTS),
    sdf_subpixel_geometry: Ok(()),
    max_sdf_side_samples: None,
    raster_primary: Ok(()),
    diagonal_ssaa: Ok(()),
};

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        CAPABILITIES.backend
    }

    /// `cpu` and the instruction-set path its hot loops run on, e.g.
    /// `cpu (AVX2 (x86-64-v3))`: what its timings were measured on.
    fn describe(&self) -> String {
        format!("cpu ({})", self.isa())
    }

    /// Refuses more than [`MAX_LIGHTS`] lights, what the kernels refuse
    /// (`required_passes`), and on SDF scenes mirror reflections and the
    /// material gate; semi-transparent materials only with the SDF methods
    /// that carry opacity (not sraa-rt, ctss+edges or delayed shading).
    fn supports(&self, scene: &Scene, method: &Method) -> Result<(), Unsupported> {
        plan(scene, method, &CAPABILITIES).map(|_| ())
    }

    fn render(
        &self,
        scene: &Scene,
        camera: &Camera,
        method: &Method,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError> {
        let passes = render_passes(scene, camera, method, settings, &CAPABILITIES)?;
        if let Some(g) = scene.sdf_geometry() {
            let of_scene = SdfView::of_scene(scene, camera).expect("an SDF scene");
            let view = SdfView {
                max_distance: settings.max_distance.unwrap_or(g.max_distance),
                max_steps: settings.max_steps.unwrap_or(g.max_steps),
                exhaustive_subpixel_shadows: self.exhaustive_subpixel_shadows,
                isa: self.isa(),
                ao_rays: settings.ao_rays,
                // Occlusion rays are traced one ray at a time (`SdfView::ao_rays`).
                program: of_scene.program.filter(|_| settings.ao_rays == 0),
                ..of_scene
            };
            let mut frame = view.render(method, settings, passes)?;
            post_process(&mut frame, passes);
            return Ok(frame);
        }
        let bvh = self.bvh(scene)?;
        let mesh = scene.mesh().expect("checked by bvh()");
        let mut tracer = Tracer::new(&bvh, scene, mesh, camera, settings.reflection_depth);
        tracer.exhaustive_subpixel_shadows = self.exhaustive_subpixel_shadows;
        tracer.ao_rays = settings.ao_rays;
        tracer.isa = self.isa();
        tracer.tile = self.tile.unwrap_or(TILE);
        let mut frame = match method.technique() {
            Technique::NoAa | Technique::Ssaa | Technique::Fxaa => {
                render::supersample(&tracer, method, settings, passes)
            }
            Technique::Sraa | Technique::SraaRt => {
                render::subpixel(&tracer, method, settings, passes)
            }
            // Named one by one (no wildcard): a new technique must be routed.
            t @ (Technique::Ctss | Technique::CtssR | Technique::SsaaCtss) => {
                return Err(RenderError::Method(format!("{t:?} needs an SDF scene")))
            }
        };
        post_process(&mut frame, passes);
        Ok(frame)
    }
}

/// The planned post-process pass (FXAA), after the frame is rendered.
fn post_process(frame: &mut Frame, passes: Passes) {
    if passes.contains(Passes::POST_PROCESS) {
        post::fxaa(frame, &subcone_kernels::fxaa::FxaaParams::QUALITY);
    }
}
