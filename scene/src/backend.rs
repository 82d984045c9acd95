//! The interface every backend implements.

pub use subcone_kernels::ao::{AO_RADIUS_FRACTION, MAX_AO_RAYS};
use subcone_kernels::passes::{required_passes, Passes};

use crate::camera::Camera;
use crate::error::RenderError;
pub use crate::error::{Unsupported, UnsupportedReason};
use std::time::Instant;

use glam::Vec3;

use crate::frame::{Frame, PassTiming};
use crate::history::{self, TaaInput};
use crate::method::Method;
use crate::registry::{self, info};
use crate::scene::Scene;

/// Largest accepted image side.
pub const MAX_SIDE: u32 = 16_384;
/// Largest accepted pixel count (a 16k × 16k frame is 3 GiB of f32 RGB alone).
pub const MAX_PIXELS: u64 = 1 << 26;

/// Settings of one render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Mirror bounces (Whitted); 1 by default.
    pub reflection_depth: u32,
    /// Passes to run even where the scene does not need them (for tests that
    /// check that leaving a pass out changes nothing).
    pub force_passes: Passes,
    /// Record the AOVs: depth, normal and samples per pixel; the CPU
    /// backend also records albedo, per-light visibility and mirror
    /// reflectance (`Frame::albedo`, `Frame::light_visibility`,
    /// `Frame::mirror`), which the report's edge classes need.
    pub aovs: bool,
    /// SDF scenes: step budget per ray, overriding the scene's.
    pub max_steps: Option<u32>,
    /// SDF scenes: maximum ray distance, overriding the scene's.
    pub max_distance: Option<f32>,
    /// Ambient-occlusion rays per shaded point; 0 (the default) is off. At
    /// most [`MAX_AO_RAYS`]. Each shaded primary hit casts this many any-hit
    /// rays over [`AO_RADIUS_FRACTION`] of the scene's bounding diagonal, in
    /// the fixed directions of `subcone_kernels::ao`, and multiplies the
    /// scene's ambient term by the unoccluded fraction. SSAA shades it per
    /// subsample; SRAA and SRAA-RT reconstruct it with the shadow-independent
    /// shading. Not applied at mirror hits (secondary shading keeps the full
    /// ambient term). On SDF scenes every shaded sample (each CTSS hit group's
    /// too) sphere traces its occlusion rays through the field, up to
    /// [`AO_RADIUS_FRACTION`] of the field's size
    /// ([`SdfGeometry::ao_radius`](crate::scene::SdfGeometry::ao_radius)).
    pub ao_rays: u32,
}

impl RenderSettings {
    /// Settings for a `width × height` image.
    pub fn new(width: u32, height: u32) -> Self {
        RenderSettings {
            width,
            height,
            reflection_depth: 1,
            force_passes: Passes::empty(),
            aovs: false,
            max_steps: None,
            max_distance: None,
            ao_rays: 0,
        }
    }

    /// Check the resolution: non-zero, at most [`MAX_SIDE`] per side and
    /// [`MAX_PIXELS`] in all; and the other settings: a step budget of at
    /// least 1, a positive finite distance, at most [`MAX_AO_RAYS`]
    /// ambient-occlusion rays.
    pub fn validate(&self) -> Result<(), RenderError> {
        let err = |reason: String| RenderError::Resolution {
            width: self.width,
            height: self.height,
            reason,
        };
        if self.width == 0 || self.height == 0 {
            return Err(err("width and height must be at least 1".into()));
        }
        if self.width > MAX_SIDE || self.height > MAX_SIDE {
            return Err(err(format!("each side must be at most {MAX_SIDE}")));
        }
        if self.width as u64 * self.height as u64 > MAX_PIXELS {
            return Err(err(format!("at most {MAX_PIXELS} pixels")));
        }
        if self.max_steps == Some(0) {
            return Err(RenderError::Method("max steps must be at least 1".into()));
        }
        if self.ao_rays > MAX_AO_RAYS {
            return Err(RenderError::Method(format!(
                "{} ambient-occlusion rays per point: at most {MAX_AO_RAYS} are supported",
                self.ao_rays
            )));
        }
        if let Some(d) = self.max_distance {
            if !(d > 0.0 && d.is_finite()) {
                return Err(RenderError::Method(format!(
                    "max distance {d} must be positive and finite"
                )));
            }
        }
        Ok(())
    }
}

impl Unsupported {
    /// `backend` cannot render `scene` with `method` because of `reason`.
    pub fn new(
        backend: &'static str,
        scene: &Scene,
        method: &Method,
        reason: UnsupportedReason,
    ) -> Self {
        Unsupported {
            backend,
            scene: scene.name.clone(),
            method: method.to_string(),
            reason,
        }
    }
}

/// The passes `method` needs on `scene` ([`required_passes`]), or why
/// `backend` cannot render it ([`UnsupportedReason::Technique`]): what the
/// default [`Backend::supports`] answers, and where [`plan`] starts.
pub fn planned_passes(
    backend: &'static str,
    scene: &Scene,
    method: &Method,
) -> Result<Passes, Unsupported> {
    required_passes(method.technique(), scene.features())
        .map_err(|u| Unsupported::new(backend, scene, method, UnsupportedReason::Technique(u)))
}

/// What a backend renders, as data: the one support [`plan`] reads it, so
/// that every backend refuses with the same rules and the same messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capabilities {
    /// The backend's [`Backend::name`].
    pub backend: &'static str,
    /// Most lights shaded on triangle scenes (`None`: no limit).
    pub max_lights_triangles: Option<usize>,
    /// Most lights shaded on SDF scenes (`None`: no limit).
    pub max_lights_sdf: Option<usize>,
    /// Sphere-traced subpixel geometry and its reconstruction (SRAA-RT on SDF
    /// scenes, [`registry::Needs::sdf_subpixel_geometry`]): `Ok`, or what
    /// the backend lacks for it.
    pub sdf_subpixel_geometry: Result<(), &'static str>,
    /// Most samples per pixel side on SDF scenes (`None`: no limit).
    pub max_sdf_side_samples: Option<u32>,
    /// Rasterised primary visibility on triangle scenes (`-hybrid`,
    /// [`Method::is_hybrid`]): `Ok`, or what the backend lacks for it. On
    /// SDF scenes a hybrid method is traced as the method without it.
    pub raster_primary: Result<(), &'static str>,
    /// `ssaa2` on triangle scenes ([`Method::SSAA2`], the diagonal of the
    /// 2×2 grid): `Ok`, or what the backend lacks for it.
    pub diagonal_ssaa: Result<(), &'static str>,
}

pub use crate::registry::SDF_SUBPIXEL_GEOMETRY;

/// What [`UnsupportedReason::CpuOnly`] names when a backend lacks
/// rasterised primary visibility ([`Capabilities::raster_primary`]).
pub const RASTER_PRIMARY: &str = "rasterised primary visibility (-hybrid)";

/// What [`UnsupportedReason::CpuOnly`] names when a backend lacks `ssaa2`
/// ([`Capabilities::diagonal_ssaa`]).
pub const DIAGONAL_SSAA: &str = "ssaa2 (the 2×2 grid's diagonal)";

/// The passes of `method` on `scene` for a backend with `caps`, or why it
/// cannot render them: the one support plan behind every backend's
/// [`Backend::supports`] and [`Backend::render`].
///
/// In order: a temporal method ([`UnsupportedReason::Temporal`]: one
/// frame of it is its [`Method::single_frame`]); more lights than the backend shades; what the kernels refuse
/// ([`required_passes`]); on SDF scenes mirror reflections, the material
/// gate, semi-transparent materials with a method that does not carry
/// opacity ([`registry::TechniqueInfo::carries_opacity`], hit-group
/// subdivision, delayed shading), and what the backend lacks
/// ([`Capabilities`]); on triangle scenes semi-transparent materials.
///
/// ```
/// use subcone_kernels::passes::Technique;
/// use subcone_scene::backend::{plan, Capabilities};
/// use subcone_scene::builtin::builtin;
/// use subcone_scene::Method;
///
/// let caps = Capabilities {
///     backend: "mine",
///     max_lights_triangles: Some(8),
///     max_lights_sdf: None,
///     sdf_subpixel_geometry: Err("no sphere-traced subsamples yet"),
///     max_sdf_side_samples: Some(8),
///     raster_primary: Err("no rasteriser"),
///     diagonal_ssaa: Ok(()),
/// };
/// let cornell = builtin("cornell").unwrap();
/// let sraa_rt = Method::new(Technique::SraaRt);
/// assert!(plan(&cornell, &sraa_rt, &caps).is_ok());
/// let primitives = builtin("primitives").unwrap();
/// let no = plan(&primitives, &sraa_rt, &caps).unwrap_err();
/// assert!(no.to_string().contains("no sphere-traced subsamples yet"));
/// ```
pub fn plan(scene: &Scene, method: &Method, caps: &Capabilities) -> Result<Passes, Unsupported> {
    plan_forced(scene, method, caps, Passes::empty())
}

/// What every backend's [`Backend::render`] checks before it renders: the
/// settings and the camera are valid, and the method runs on the scene with
/// `caps`, the passes `settings.force_passes` asks for included
/// ([`plan_forced`]). The frame's passes, or the first refusal.
pub fn render_passes(
    scene: &Scene,
    camera: &Camera,
    method: &Method,
    settings: &RenderSettings,
    caps: &Capabilities,
) -> Result<Passes, RenderError> {
    settings.validate()?;
    camera.validate()?;
    Ok(plan_forced(scene, method, caps, settings.force_passes)?)
}

/// [`plan`] with `force` added to the planned passes (the passes
/// [`RenderSettings::force_passes`] asks for) before the rules that read
/// them: forcing the secondary passes on an SDF scene is refused as its
/// mirrors would be.
pub fn plan_forced(
    scene: &Scene,
    method: &Method,
    caps: &Capabilities,
    force: Passes,
) -> Result<Passes, Unsupported> {
    let refuse = |reason| Err(Unsupported::new(caps.backend, scene, method, reason));
    if method.is_temporal() {
        return refuse(UnsupportedReason::Temporal);
    }
    let sdf = scene.sdf_geometry().is_some();
    let max_lights = if sdf {
        caps.max_lights_sdf
    } else {
        caps.max_lights_triangles
    };
    if let Some(max) = max_lights.filter(|&max| scene.lights.len() > max) {
        return refuse(UnsupportedReason::TooManyLights {
            lights: scene.lights.len(),
            max,
        });
    }
    let passes = planned_passes(caps.backend, scene, method)? | force;
    let translucent = scene.has_translucency();
    let technique = info(method.technique());
    if !sdf {
        if translucent {
            // Triangle scenes have no semi-transparent path on any backend:
            // refuse rather than draw them opaque.
            return refuse(UnsupportedReason::Translucency {
                what: "ray tracing triangles".into(),
                instead: "they render on SDF scenes only".into(),
            });
        }
        if let (true, Err(why)) = (method.is_hybrid(), caps.raster_primary) {
            return refuse(UnsupportedReason::CpuOnly {
                what: RASTER_PRIMARY,
                why,
            });
        }
        if let (true, Err(why)) = (method.ssaa_diagonal(), caps.diagonal_ssaa) {
            return refuse(UnsupportedReason::CpuOnly {
                what: DIAGONAL_SSAA,
                why,
            });
        }
        return Ok(passes);
    }
    if method.ssaa_diagonal() {
        return refuse(UnsupportedReason::DiagonalSsaaOnSdf);
    }
    if passes.intersects(Passes::SECONDARY) {
        return refuse(UnsupportedReason::SdfReflections);
    }
    if method.gates_material() {
        return refuse(UnsupportedReason::MaterialGateOnSdf);
    }
    let opaque_only = if !technique.carries_opacity {
        Some(technique.name.to_string())
    } else if method.split_groups() {
        Some(format!(
            "hit group subdivision ({}{})",
            technique.name,
            registry::EDGES
        ))
    } else if method.delayed_shading() {
        Some("delayed shading".to_string())
    } else {
        None
    };
    if let Some(what) = opaque_only.filter(|_| translucent) {
        return refuse(UnsupportedReason::Translucency {
            what,
            instead: format!("{} render them", registry::opacity_methods()),
        });
    }
    if technique.needs.sdf_subpixel_geometry {
        if let Err(why) = caps.sdf_subpixel_geometry {
            return refuse(UnsupportedReason::CpuOnly {
                what: SDF_SUBPIXEL_GEOMETRY,
                why,
            });
        }
    }
    let side = method.ssaa_side();
    let limit = caps
        .max_sdf_side_samples
        .filter(|_| technique.needs.sdf_supersampling);
    if let Some(max) = limit.filter(|&max| side > max) {
        return refuse(UnsupportedReason::TooManySamples { side, max });
    }
    Ok(passes)
}

/// A renderer: the CPU reference, the wgpu backend, or your own.
pub trait Backend {
    /// Short name (`"cpu"`, `"wgpu"`).
    fn name(&self) -> &'static str;

    /// What the backend runs on, for reports (e.g. the GPU adapter and driver).
    fn describe(&self) -> String {
        self.name().to_string()
    }

    /// Whether this backend renders `scene` with `method`, decided without
    /// rendering: `Ok` exactly when [`render`](Backend::render) with default
    /// settings does not fail with [`RenderError::NotSupported`], and
    /// otherwise the same [`Unsupported`] that `render` returns.
    ///
    /// Only scene and method decide it; a render it accepts can still fail for
    /// its settings (resolution, step budget, forced passes), its camera or the
    /// device.
    ///
    /// The default refuses only what [`required_passes`] refuses (the
    /// technique does not apply to the geometry); a backend with limits of its
    /// own must override it, and should call it at the start of `render` so
    /// that the two cannot disagree.
    fn supports(&self, scene: &Scene, method: &Method) -> Result<(), Unsupported> {
        planned_passes(self.name(), scene, method).map(|_| ())
    }

    /// Render `scene` through `camera` with `method`. Fails with
    /// [`RenderError::NotSupported`] where [`supports`](Backend::supports)
    /// does.
    fn render(
        &self,
        scene: &Scene,
        camera: &Camera,
        method: &Method,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError>;

    /// One TAA resolve ([`crate::temporal::Taa`] calls it every frame): the
    /// resolved colours and the resolve's timing (`"taa"`). The default runs
    /// `subcone_kernels::taa` on the CPU ([`history::resolve`]); a GPU
    /// backend runs its twin. Errors when a buffer does not hold one value
    /// per pixel.
    fn resolve_taa(&self, input: &TaaInput<'_>) -> Result<(Vec<Vec3>, PassTiming), RenderError> {
        let start = Instant::now();
        let out = history::resolve(input)?;
        Ok((out, PassTiming::cpu("taa", start.elapsed())))
    }
}
