//! `subcone-cpu`: the CPU reference backend.
//!
//! Triangle scenes are ray traced through an obvhs CWBVH (built once per scene
//! and cached), in parallel over image bands with rayon, with Whitted shading:
//! direct light with hard shadows and mirror reflection. Methods: NoAA, SSAA,
//! SRAA and SRAA-RT. All weight and reconstruction maths is the kernels'.
//!
//! ```
//! use subcone_cpu::CpuBackend;
//! use subcone_scene::{builtin::builtin, Backend, RenderSettings};
//!
//! let scene = builtin("cornell").unwrap();
//! let frame = CpuBackend::new()
//!     .render(&scene, &scene.camera, &"sraa-rt".parse().unwrap(), &RenderSettings::new(32, 32))
//!     .unwrap();
//! assert_eq!(frame.color.len(), 32 * 32);
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod bvh;
mod render;
pub mod shade;
pub mod sphere;

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use subcone_kernels::passes::{required_passes, Technique};
use subcone_scene::{Backend, Camera, Frame, Method, RenderError, RenderSettings, Scene};

pub use bvh::SceneBvh;
use shade::{Tracer, MAX_LIGHTS};

/// The CPU backend. Cheap to create; it caches one BVH per scene.
#[derive(Default)]
pub struct CpuBackend {
    cache: Mutex<HashMap<u64, Arc<SceneBvh>>>,
}

impl CpuBackend {
    /// A backend with an empty BVH cache.
    pub fn new() -> Self {
        Self::default()
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

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn render(
        &self,
        scene: &Scene,
        camera: &Camera,
        method: &Method,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError> {
        settings.validate()?;
        camera.validate()?;
        if scene.lights.len() > MAX_LIGHTS {
            return Err(RenderError::Backend {
                backend: "cpu",
                reason: format!(
                    "{} lights; at most {MAX_LIGHTS} are supported",
                    scene.lights.len()
                ),
            });
        }
        let passes = required_passes(method.technique, scene.features())? | settings.force_passes;
        let bvh = self.bvh(scene)?;
        let mesh = scene.mesh().expect("checked by bvh()");
        let tracer = Tracer::new(&bvh, scene, mesh, camera, settings.reflection_depth);
        Ok(match method.technique {
            Technique::NoAa | Technique::Ssaa => {
                render::supersample(&tracer, method, settings, passes)
            }
            Technique::Sraa | Technique::SraaRt => {
                render::subpixel(&tracer, method, settings, passes)
            }
            t => return Err(RenderError::Method(format!("{t:?} needs an SDF scene"))),
        })
    }
}
