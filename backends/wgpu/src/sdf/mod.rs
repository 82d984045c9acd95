//! SDF scenes on the GPU: NoAA, SSAA, CTSS (with `ctss+edges`' group splits,
//! §5.3), CTSS-R and SSAA+CTSS as one compute
//! pass each, producing the images of the CPU reference
//! (`subcone_cpu::sphere::SdfView`); SRAA-RT as the CPU's three passes
//! (`sraa.rs`: sphere-traced shaded samples and subsamples, and the triangle
//! path's resolve through the kernels' reconstruction loop).
//!
//! Ambient occlusion (`RenderSettings::ao_rays`) multiplies the ambient term
//! of every shaded sample by the unoccluded fraction of the kernels' fixed
//! directions (`subcone_kernels::ao`), each an any-hit ray sphere traced
//! through the field up to `SdfGeometry::ao_radius` (trace.wgsl's
//! `ambient_occlusion`, the twin of `SdfView::ambient_occlusion`).
//!
//! Scenes with semi-transparent materials run `translucent.wgsl` instead of
//! `trace.wgsl`'s entry point, the twins of the CPU's semi-transparent path:
//! CTSS with the `K` masks of §5.3 (`subcone_cone_stepper_record_alpha_mask`,
//! group splits where the nearest object changes between a semi-transparent
//! object and another, passes through semi-transparent objects), and NoAA /
//! SSAA with alpha blending along the ray; materials' opacities are a WGSL
//! table (`material_opacity`, shading.rs). Samples are shaded as their
//! groups close; what the CPU refuses on semi-transparent scenes (SRAA-RT,
//! `ctss+edges`, delayed shading) this backend refuses with the same reason
//! (`WgpuBackend::plan`).
//!
//! The scene's tree is compiled to WGSL ([`subcone_sdf::wgsl::WgslField::compile`]), its materials
//! and lights to WGSL constants (`shading.rs`), and concatenated with the
//! kernels' WGSL (`cone`, `mask`, `aggregate`, `ctss` and its trace
//! `subcone_ctss_trace`, the twin of the CPU's `ctss::trace_field`: Algorithm
//! 1 of CTSS, eq. 3–10, the group masks and §5.3's splits) and this module's
//! entry points (`trace.wgsl`), which give the trace its hooks: one invocation per
//! pixel traces its `side × side` samples exactly as the CPU does (same rays,
//! same stepper, same normals, same shading, hard shadows inline). Only what
//! the passes need is built: no light loop without [`Passes::SHADOW`], no AOV
//! pipeline or buffer unless AOVs are asked for.
//!
//! CTSS marches each pixel's cone up to 8 samples ahead of shading them (in
//! order, so eq. 6 sums the same terms in the same order): the SIMD lanes of
//! a software or hardware GPU march together and trace shadows together.
//! This is already a bounded form of CTSS §5.1's delayed shading, for the
//! reason §5.1 gives (divergence between lanes), applied to every cone-traced
//! method. `ctss-delayed` ([`Method::delayed_shading`]) compiles the same
//! shader with a batch of [`DELAYED_BATCH`] samples instead: the whole
//! coverage of a cone is traced before any of it is shaded unless the cone
//! finds more groups than that (the CPU's `ctss-delayed` batches a whole
//! row). The image is the same either way; only the order of the work
//! changes.
//!
//! Differences from the CPU come from GPU arithmetic alone (a few ulps in
//! `sqrt`, `sin`, fused multiply-adds, and eq. 6's sums in f32 instead of
//! f64); they could flip a hit near a threshold. On lavapipe no decision
//! flips on any built-in SDF scene: every method gives the CPU's SDF
//! evaluation and sample counts exactly and colours within 1e-4 (`tests/sdf.rs`
//! bounds them more loosely, for other GPUs).

mod shading;
mod sraa;

#[cfg(test)]
pub(crate) use sraa::{SdfSraaFrame, SRAA_FRAME_WGSL};

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};

use subcone_kernels::passes::{Passes, Technique};
use subcone_scene::{Frame, FrameStats, Method, PassTiming, RayCounts, RenderError};
use subcone_sdf::wgsl::WgslField;
use wgpu::util::DeviceExt;

use crate::compute::{self, Allocate, Program};
use crate::context::{err, CacheKey, GpuContext};
use crate::Job;
use subcone_passes::bind::{Bindings, BufferAccess};

pub(crate) const TRACE_WGSL: &str = include_str!("trace.wgsl");
/// The CTSS / sphere-tracing frame's entry point (`sdf_render`).
const RENDER_WGSL: &str = include_str!("render.wgsl");
const AOVS_WGSL: &str = include_str!("aovs.wgsl");
const WORKGROUP: u32 = 8;
/// Hit groups a cone marches ahead of shading them (the
/// `subcone_CTSS_BATCH` of the kernels' `subcone_ctss_trace`) for ASAP
/// methods.
const ASAP_BATCH: u32 = 8;
/// The same for delayed shading (`ctss-delayed`): enough for every cone of
/// the built-in SDF scenes to be traced completely before it is shaded.
pub const DELAYED_BATCH: u32 = 32;

/// Most samples per pixel side (`ssaaN`, `ssaaN+ctss`) one invocation traces.
pub const MAX_SIDE_SAMPLES: u32 = 64;

/// The kernels' WGSL every SDF shader includes, after the prelude: `ao`
/// (the occlusion directions), then what a CTSS trace runs,
/// `subcone_passes::CTSS_KERNELS` (the stepper carries the K masks of
/// CTSS §5.3, `transparency`).
fn kernels() -> Vec<&'static str> {
    let mut k = vec![subcone_kernels::ao::WGSL];
    k.extend(subcone_passes::CTSS_KERNELS);
    k
}

/// The semi-transparent path (CTSS §5.3): the twins of the CPU's
/// `ctss_translucent` and `noaa_translucent`, as `sdf_render`'s samplers
/// `pixel_cone_sample` and `pixel_sphere_sample`; after `trace.wgsl` (whose
/// field hooks [`subcone_kernels::ctss::TRACE_WGSL`]'s `subcone_group_mask`
/// reads).
const TRANSLUCENT_WGSL: &str = include_str!("translucent.wgsl");

/// `sdf_render`'s samplers on opaque scenes: `trace.wgsl`'s own. One pixel
/// loop serves both paths; the translucent one binds its samplers instead.
const OPAQUE_SAMPLERS: &str = "
fn pixel_cone_sample(o: vec3<f32>, d: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    return ctss_sample(o, d, steps, samples, shadow);
}
fn pixel_sphere_sample(o: vec3<f32>, d: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    return noaa_sample(o, d, steps, samples, shadow);
}
";

/// The field's scatter table on the device, uploaded once per device and
/// table (`None` when the field has none).
/// A field's scatter table's cache key: its values' bits.
#[derive(PartialEq, Eq, Hash)]
struct ScatterTableKey(Vec<u32>);

impl CacheKey for ScatterTableKey {
    type Value = wgpu::Buffer;
}

fn scatter_table(
    ctx: &GpuContext,
    f: &WgslField,
) -> Result<Option<Arc<wgpu::Buffer>>, RenderError> {
    if f.data.is_empty() {
        return Ok(None);
    }
    let bits: Vec<u32> = f.data.iter().flatten().map(|x| x.to_bits()).collect();
    let key = ScatterTableKey(bits);
    if let Some(b) = ctx.cached(&key) {
        return Ok(Some(b));
    }
    let bytes: &[u8] = bytemuck::cast_slice(&f.data);
    ctx.check_buffer_size("the SDF's scatter table", bytes.len() as u64)?;
    let b = Arc::new(ctx.scoped("SDF scatter table", || {
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sdf_data"),
                contents: bytes,
                usage: wgpu::BufferUsages::STORAGE,
            })
    })?);
    ctx.cache_insert(key, b.clone());
    Ok(Some(b))
}

/// The frame's constants; `SdfFrame` in trace.wgsl (112 bytes).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct SdfFrame {
    pub(crate) position: [f32; 3],
    pub(crate) width: u32,
    pub(crate) forward: [f32; 3],
    pub(crate) height: u32,
    pub(crate) right: [f32; 3],
    /// tan(fov_y / 2).
    pub(crate) half: f32,
    pub(crate) up: [f32; 3],
    pub(crate) max_distance: f32,
    pub(crate) background: [f32; 3],
    pub(crate) max_steps: u32,
    pub(crate) ambient: [f32; 3],
    /// Samples per pixel side.
    pub(crate) side: u32,
    /// 1: cone tracing (the CTSS family), 0: sphere tracing.
    pub(crate) cone: u32,
    /// Ambient-occlusion rays per shaded point (0: off).
    pub(crate) ao_rays: u32,
    /// Their length ([`subcone_scene::scene::SdfGeometry::ao_radius`]; a NaN is 0).
    pub(crate) ao_radius: f32,
    pub(crate) _pad: u32,
}

pub(crate) fn render(ctx: &GpuContext, job: &Job) -> Result<Frame, RenderError> {
    let Job {
        scene,
        camera,
        method,
        settings,
        passes,
    } = *job;
    let g = scene
        .sdf_geometry()
        .ok_or_else(|| err("not an SDF scene"))?;
    // `WgpuBackend::plan` has refused mirrors and more than
    // MAX_SIDE_SAMPLES samples per side.
    // Every technique named (no wildcard): a new one must be routed.
    match method.technique() {
        Technique::SraaRt => return sraa::render(ctx, job),
        Technique::NoAa
        | Technique::Ssaa
        | Technique::Fxaa
        | Technique::Ctss
        | Technique::CtssR
        | Technique::SsaaCtss => {}
        t @ Technique::Sraa => {
            return Err(RenderError::Method(format!(
                "{t:?} has no sphere-traced path (sraa-rt renders SDF scenes)"
            )))
        }
    }
    let max_distance = settings.max_distance.unwrap_or(g.max_distance);
    let max_steps = settings.max_steps.unwrap_or(g.max_steps);
    if max_distance.is_nan() {
        return Err(err("the maximum ray distance is NaN"));
    }
    let (w, h) = (settings.width, settings.height);
    // Samples per pixel side (1 without supersampling), and whether a
    // cone is traced per sample (the CTSS family).
    let side = method.ssaa_side().max(1);
    let cone = method.technique().is_cone_traced();
    let params = method.ctss_params(camera, h, max_distance, max_steps);
    let pixels = w as u64 * h as u64;
    let groups = compute::workgroups(ctx, "SDF", w, h, WORKGROUP)?;
    let px_bytes = pixels * 16;
    ctx.check_buffer_size("the colour buffer", px_bytes)?;

    let shadows = passes.contains(Passes::SHADOW) && !scene.lights.is_empty();
    let batch = if cone && method.delayed_shading() {
        DELAYED_BATCH
    } else {
        ASAP_BATCH
    };
    let frame_constants = SdfFrame::new(job, (max_distance, max_steps), side, cone);
    let field = WgslField::compile(&g.root);
    let table = scatter_table(ctx, &field)?;
    let mut b = Bindings::new(0);
    b.uniform(ctx, "frame", "SdfFrame", &frame_constants)?;
    b.uniform(ctx, "ctss", "subcone_CtssParams", &params)?;
    b.storage(ctx, "color", "color_out", "array<vec4<f32>>", px_bytes)?;
    b.storage(ctx, "counts", "counts_out", "array<vec4<u32>>", px_bytes)?;
    if let Some(t) = &table {
        b.buffer("sdf_data", "array<vec4<f32>>", BufferAccess::Read, t);
    }
    if settings.aovs {
        // Depth and normal through each pixel centre (not timed, as on the CPU).
        let plain = Method::new(Technique::NoAa).ctss_params(camera, h, max_distance, max_steps);
        b.uniform(ctx, "aov_params", "subcone_CtssParams", &plain)?;
        b.storage(ctx, "aovs", "aov_out", "array<vec4<f32>>", px_bytes)?;
    }
    let shading = shading::shading_wgsl(&scene.materials, &scene.lights, shadows)?;
    let pending = format!("const subcone_CTSS_BATCH: u32 = {batch}u;\n");
    let sources = shader_sources(job, &field, &shading, &pending);
    let mut program = Program::new(ctx, "sdf", &sources, &[&b])?;
    let trace = program.pipeline("sdf_render")?;
    let name = if cone {
        "cone tracing"
    } else {
        "sphere tracing"
    };
    let mut timings = Vec::new();
    ctx.timed_pass(name, &mut timings, |enc| {
        program.dispatch(enc, &trace, groups)
    })?;
    let (color_px, post_buffers) = final_colour(ctx, job, &b, &mut timings)?;
    let count_px: Vec<[u32; 4]> = compute::read(ctx, b.get("counts_out")?, pixels as usize)?;

    let mut frame = Frame::new(w, h);
    for (c, p) in frame.color.iter_mut().zip(&color_px) {
        *c = glam::Vec3::new(p[0], p[1], p[2]);
    }
    let per_pixel = side * side;
    let totals = Totals::of(&count_px, per_pixel);
    let mut buffers = vec![("color", px_bytes as usize), ("counts", px_bytes as usize)];
    buffers.extend(post_buffers);
    if table.is_some() {
        buffers.push(("sdf scatter table", field.data.len() * 16));
    }

    if settings.aovs {
        centre_aovs(ctx, &mut program, &b, groups, pixels as usize, &mut frame)?;
        frame.samples_per_pixel = Some(count_px.iter().map(|c| c[1] as f32).collect());
        buffers.push(("aovs", px_bytes as usize));
    }

    frame.stats = FrameStats {
        passes,
        timings,
        buffers,
        rays: RayCounts {
            primary: pixels * per_pixel as u64,
            shadow: totals.shadow,
            ao: totals.ao,
            ..Default::default()
        },
        shaded_samples: totals.samples,
        sdf_evaluations: totals.steps,
        multi_sample_pixels: totals.multi,
    };
    Ok(frame)
}

/// Buffers by name and size in bytes ([`FrameStats::buffers`]).
type BufferSizes = Vec<(&'static str, usize)>;

/// The frame's colours, read back after the post-process (FXAA) when it is
/// planned, and the buffers the post-process allocated.
fn final_colour(
    ctx: &GpuContext,
    job: &Job,
    b: &Bindings,
    timings: &mut Vec<PassTiming>,
) -> Result<(Vec<[f32; 4]>, BufferSizes), RenderError> {
    let (w, h) = (job.settings.width, job.settings.height);
    let pixels = w as u64 * h as u64;
    let (color, post_buffers) = if job.passes.contains(Passes::POST_PROCESS) {
        crate::post::fxaa::run(
            ctx,
            b.get("color_out")?,
            w,
            h,
            &subcone_kernels::fxaa::FxaaParams::QUALITY,
            timings,
        )?
    } else {
        (b.get("color_out")?.clone(), Vec::new())
    };
    let color_px: Vec<[f32; 4]> = compute::read(ctx, &color, pixels as usize)?;
    Ok((color_px, post_buffers))
}

impl SdfFrame {
    /// The constants of `job`'s frame: its camera and size, the scene's
    /// background and ambient, the march's `(max_distance, max_steps)`,
    /// `side` samples per pixel side, cone or sphere tracing.
    fn new(job: &Job, (max_distance, max_steps): (f32, u32), side: u32, cone: bool) -> Self {
        let (scene, camera, settings) = (job.scene, job.camera, job.settings);
        let ao_radius = scene.sdf_geometry().map_or(0.0, |g| g.ao_radius());
        SdfFrame {
            position: camera.position.to_array(),
            width: settings.width,
            forward: camera.forward.to_array(),
            height: settings.height,
            right: camera.right().to_array(),
            half: (0.5 * camera.fov_y).tan(),
            up: camera.up.to_array(),
            max_distance,
            background: scene.background.to_array(),
            max_steps,
            ambient: scene.ambient.to_array(),
            side,
            cone: cone as u32,
            ao_rays: settings.ao_rays,
            ao_radius: if ao_radius.is_nan() { 0.0 } else { ao_radius },
            _pad: 0,
        }
    }
}

/// The shader of `job`'s frame, in order: the kernels, the compiled
/// `field`, the scene's `shading`, the batch constant (`pending`), the
/// entry points, the samplers of the opaque or semi-transparent path, and
/// the AOV entry point when AOVs are asked for.
fn shader_sources<'a>(
    job: &Job,
    field: &'a WgslField,
    shading: &'a str,
    pending: &'a str,
) -> Vec<&'a str> {
    let mut sources: Vec<&str> = kernels();
    // The entry point right after trace.wgsl, where it was written first.
    sources.extend([
        field.source.as_str(),
        shading,
        pending,
        TRACE_WGSL,
        RENDER_WGSL,
    ]);
    // Semi-transparent materials take the K-mask path (CTSS §5.3), as on
    // the CPU (`SdfView::render`); opaque scenes never compile it.
    let translucent = job.scene.has_translucency();
    sources.push(if translucent {
        TRANSLUCENT_WGSL
    } else {
        OPAQUE_SAMPLERS
    });
    if job.settings.aovs {
        sources.push(AOVS_WGSL);
    }
    sources
}

/// The frame's counters summed over its pixels (`counts_out`: steps,
/// shaded samples, shadow rays, occlusion rays per pixel).
struct Totals {
    steps: u64,
    samples: u64,
    shadow: u64,
    ao: u64,
    /// Pixels that shaded more samples than `per_pixel`
    /// (`FrameStats::multi_sample_pixels`).
    multi: u64,
}

impl Totals {
    fn of(count_px: &[[u32; 4]], per_pixel: u32) -> Self {
        let (mut steps, mut samples, mut shadow, mut ao, mut multi) =
            (0u64, 0u64, 0u64, 0u64, 0u64);
        for c in count_px {
            steps += c[0] as u64;
            samples += c[1] as u64;
            shadow += c[2] as u64;
            ao += c[3] as u64;
            if c[1] > per_pixel {
                multi += 1;
            }
        }
        Totals {
            steps,
            samples,
            shadow,
            ao,
            multi,
        }
    }
}

/// The AOV pass (not timed): depth and normal through each of the
/// `pixels` pixel centres into `frame`.
fn centre_aovs(
    ctx: &GpuContext,
    program: &mut Program,
    b: &Bindings,
    groups: (u32, u32),
    pixels: usize,
    frame: &mut Frame,
) -> Result<(), RenderError> {
    let aovs = program.pipeline("sdf_aovs")?;
    ctx.timed_pass("aovs", &mut Vec::new(), |enc| {
        program.dispatch(enc, &aovs, groups)
    })?;
    let g: Vec<[f32; 4]> = compute::read(ctx, b.get("aov_out")?, pixels)?;
    frame.depth = Some(g.iter().map(|a| a[3]).collect());
    frame.normal = Some(
        g.iter()
            .map(|a| glam::Vec3::new(a[0], a[1], a[2]))
            .collect(),
    );
    Ok(())
}
