//! SDF scenes on the GPU: NoAA, SSAA, CTSS (with `ctss+edges`' group splits,
//! §5.3), CTSS-R and SSAA+CTSS as one [`CtssPass`] each, the pass a host
//! embeds, producing the images of the CPU reference
//! (`subcone_cpu::sphere::SdfView`); SRAA-RT as the CPU's three passes
//! (`sraa.rs`: sphere-traced shaded samples and subsamples, and
//! `subcone_passes::SraaPass`'s resolve through the kernels' reconstruction
//! loop).
//!
//! Ambient occlusion (`RenderSettings::ao_rays`) multiplies the ambient term
//! of every shaded sample by the unoccluded fraction of the kernels' fixed
//! directions (`subcone_kernels::ao`), each an any-hit ray sphere traced
//! through the field up to `SdfGeometry::ao_radius` (trace.wgsl's
//! `ambient_occlusion`, the twin of `SdfView::ambient_occlusion`).
//!
//! Scenes with semi-transparent materials trace each sample with
//! `translucent.wgsl`'s samplers (the pass's host trace, `HostTrace`), the
//! twins of the CPU's semi-transparent path:
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
//! and lights to WGSL constants (`shading.rs`), and with `trace.wgsl` (the
//! field, normal and shading hooks, SdfView's shading and shadow rays) they
//! are the host WGSL of a [`CtssPass`] over the host group of the frame's
//! constants (`host_bindings`): the pass's one pixel loop traces each
//! pixel's `side × side` samples (`CtssPassDesc::samples_per_side`) with the
//! kernels' `subcone_ctss_trace`, the twin of the CPU's `ctss::trace_field`
//! (Algorithm 1 of CTSS, eq. 3–10, the group masks and §5.3's splits), or
//! with the host trace of `HostTrace` (sphere tracing, semi-transparent
//! scenes), exactly as the CPU does (same rays, same stepper, same normals,
//! same shading, hard shadows inline), and writes the colour and the
//! per-pixel counts (`subcone_counters`: shadow and occlusion rays) into
//! buffers. Only what the passes need is built: no light loop without
//! [`Passes::SHADOW`], no AOV pipeline or buffer unless AOVs are asked for.
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

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};

use subcone_kernels::camera::PinholeCamera;
use subcone_kernels::passes::{Passes, Technique};
use subcone_passes::{CtssBuffers, CtssCamera, CtssOutput, CtssPass, CtssPassDesc, CtssTrace};
use subcone_scene::scene::SdfGeometry;
use subcone_scene::{Frame, FrameStats, Method, PassTiming, RayCounts, RenderError};
use subcone_sdf::wgsl::WgslField;
use wgpu::util::DeviceExt;

use crate::compute::{self, Allocate, Program};
use crate::context::{err, CacheKey, GpuContext};
use crate::Job;
use subcone_passes::bind::{Bindings, BufferAccess};

pub(crate) const TRACE_WGSL: &str = include_str!("trace.wgsl");
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

/// The kernels' WGSL every SDF program of this backend's own includes
/// (SRAA-RT, AOVs; [`CtssPass`] includes them itself), after the prelude: `ao`
/// (the occlusion directions), then what a CTSS trace runs,
/// `subcone_passes::CTSS_KERNELS` (the stepper carries the K masks of
/// CTSS §5.3, `transparency`).
fn kernels() -> Vec<&'static str> {
    let mut k = vec![subcone_kernels::ao::WGSL];
    k.extend(subcone_passes::CTSS_KERNELS);
    k
}

/// The semi-transparent path (CTSS §5.3): the twins of the CPU's
/// `ctss_translucent` and `noaa_translucent`, as the host trace's samplers
/// `ctss_translucent_sample` and `noaa_translucent_sample` ([`HostTrace`]);
/// after `trace.wgsl` (whose field hooks
/// [`subcone_kernels::ctss::TRACE_WGSL`]'s `subcone_group_mask` reads).
const TRANSLUCENT_WGSL: &str = include_str!("translucent.wgsl");

/// What traces each sample of a CTSS / NoAA / SSAA frame through
/// [`CtssPass`] when the kernels' CTSS trace does not (opaque scenes under
/// a cone-traced method): the pass's host trace, `subcone_trace`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum HostTrace {
    /// Sphere tracing (NoAA, SSAA) of an opaque scene: `noaa_sample`.
    Sphere,
    /// A semi-transparent scene (CTSS §5.3): `ctss_translucent_sample`
    /// under a cone-traced method, `noaa_translucent_sample` (alpha
    /// blending along the ray) otherwise, chosen by `SdfFrame::cone`, as
    /// one shader for both: compiled with only the sphere sampler reachable,
    /// lavapipe (Mesa 22.3) crashes.
    Translucent,
}

impl HostTrace {
    /// The trace of `job`'s samples: `None` for the kernels' CTSS trace.
    fn of(job: &Job) -> Option<Self> {
        let cone = job.method.technique().is_cone_traced();
        match (cone, job.scene.has_translucency()) {
            (true, false) => None,
            (false, false) => Some(HostTrace::Sphere),
            (_, true) => Some(HostTrace::Translucent),
        }
    }

    /// `subcone_trace`, CtssPass's host trace, over this trace's sampler:
    /// its colour, shaded samples and field evaluations, its shadow rays
    /// added to the pixel's count (`shadow_rays_traced`, trace.wgsl).
    fn wgsl(self) -> &'static str {
        match self {
            HostTrace::Sphere => SPHERE_TRACE_WGSL,
            HostTrace::Translucent => TRANSLUCENT_TRACE_WGSL,
        }
    }
}

/// [`HostTrace::Sphere`]'s `subcone_trace`.
const SPHERE_TRACE_WGSL: &str = "
fn subcone_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {
    var steps = 0u;
    var samples = 0u;
    var shadow = 0u;
    let c = noaa_sample(origin, dir, background, &steps, &samples, &shadow);
    shadow_rays_traced += shadow;
    return subcone_CtssTraceResult(c, samples, steps, 0u, 0u, subcone_inf());
}
";

/// [`HostTrace::Translucent`]'s `subcone_trace`.
const TRANSLUCENT_TRACE_WGSL: &str = "
fn subcone_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {
    var steps = 0u;
    var samples = 0u;
    var shadow = 0u;
    var c: vec3<f32>;
    if frame.cone != 0u {
        c = ctss_translucent_sample(origin, dir, background, &steps, &samples, &shadow);
    } else {
        c = noaa_translucent_sample(origin, dir, background, &steps, &samples, &shadow);
    }
    shadow_rays_traced += shadow;
    return subcone_CtssTraceResult(c, samples, steps, 0u, 0u, subcone_inf());
}
";

/// A field's scatter table's cache key: its values' bits.
#[derive(PartialEq, Eq, Hash)]
struct ScatterTableKey(Vec<u32>);

impl CacheKey for ScatterTableKey {
    type Value = wgpu::Buffer;
}

/// The field's scatter table on the device, uploaded once per device and
/// table (`None` when the field has none).
fn scatter_table(
    ctx: &GpuContext,
    f: &WgslField,
) -> Result<Option<Arc<wgpu::Buffer>>, RenderError> {
    if f.data.is_empty() {
        return Ok(None);
    }
    let bits: Vec<u32> = f.data.iter().flatten().map(|x| x.to_bits()).collect();
    let table = ctx.cached_or_insert(ScatterTableKey(bits), |_| {
        let bytes: &[u8] = bytemuck::cast_slice(&f.data);
        ctx.check_buffer_size("the SDF's scatter table", bytes.len() as u64)?;
        ctx.scoped("SDF scatter table", || {
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sdf_data"),
                    contents: bytes,
                    usage: wgpu::BufferUsages::STORAGE,
                })
        })
    })?;
    Ok(Some(table))
}

/// The frame's constants; `SdfFrame` in trace.wgsl (128 bytes).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct SdfFrame {
    /// The camera, for the programs that sphere trace through it (AOVs,
    /// SRAA-RT); [`CtssPass`] has its own copy.
    pub(crate) camera: PinholeCamera,
    pub(crate) background: [f32; 3],
    pub(crate) max_distance: f32,
    pub(crate) ambient: [f32; 3],
    pub(crate) max_steps: u32,
    /// Ambient-occlusion rays per shaded point (0: off).
    pub(crate) ao_rays: u32,
    /// Their length ([`subcone_scene::scene::SdfGeometry::ao_radius`]; a NaN is 0).
    pub(crate) ao_radius: f32,
    /// 1 under a cone-traced method (the semi-transparent host trace's
    /// choice, [`HostTrace::Translucent`]), else 0.
    pub(crate) cone: u32,
    pub(crate) _pad: u32,
}

/// A [`CtssPass`] over one scene's field and shading: its host WGSL (the
/// declarations of the host group included) and the desc's choices.
#[derive(PartialEq, Eq, Hash)]
struct SdfPassKey {
    host_wgsl: String,
    batch: u32,
    side: u32,
    trace: Option<HostTrace>,
}

impl CacheKey for SdfPassKey {
    type Value = CtssPass;
}

pub(crate) fn render(ctx: &GpuContext, job: &Job) -> Result<Frame, RenderError> {
    let Job {
        scene,
        camera,
        method,
        settings,
        passes,
    } = *job;
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
    let (g, (max_distance, max_steps)) = march(job)?;
    let (w, h) = (settings.width, settings.height);
    // Samples per pixel side (1 without supersampling), and whether a
    // cone is traced per sample (the CTSS family).
    let side = method.ssaa_side().max(1);
    let cone = method.technique().is_cone_traced();
    let params = method.ctss_params(camera, h, max_distance, max_steps);
    let pixels = w as u64 * h as u64;
    // The pass dispatches 8×8 workgroups: refuse a frame the device cannot
    // dispatch with this backend's message.
    compute::workgroups(ctx, "SDF", w, h, WORKGROUP)?;
    let px_bytes = pixels * 16;
    ctx.check_buffer_size("the colour buffer", px_bytes)?;

    let shadows = passes.contains(Passes::SHADOW) && !scene.lights.is_empty();
    let frame_constants = SdfFrame::new(job, (max_distance, max_steps));
    let field = WgslField::compile(&g.root);
    let table = scatter_table(ctx, &field)?;
    let shading = shading::shading_wgsl(&scene.materials, &scene.lights, shadows)?;
    let host = host_bindings(ctx, 1, &frame_constants, &params, table.as_deref())?;
    let (pass, group) = frame_pass(ctx, job, (&field, &shading), &host)?;
    // The pass's outputs: allocated (and accounted) here, bound by the pass.
    let mut out = Bindings::new(0);
    out.storage(ctx, "color", "color_out", "array<vec4<f32>>", px_bytes)?;
    out.storage(ctx, "counts", "counts_out", "array<vec4<u32>>", px_bytes)?;
    let inputs = ctss_inputs(job, params, &group, &out)?;
    let name = if cone {
        "cone tracing"
    } else {
        "sphere tracing"
    };
    let mut timings = Vec::new();
    let mut recorded = Ok(());
    ctx.timed_pass(name, &mut timings, |enc| {
        recorded = pass.encode_buffers(&ctx.device, &ctx.queue, enc, &inputs, None);
    })?;
    recorded.map_err(|e| err(format!("{name}: {e}")))?;
    // This frame's buffers are its own: the pass need not keep them.
    pass.release_views();
    let (color_px, post_buffers) = final_colour(ctx, job, &out, &mut timings)?;
    let count_px: Vec<[u32; 4]> = compute::read(ctx, out.get("counts_out")?, pixels as usize)?;

    let mut frame = colour_frame(w, h, &color_px);
    let per_pixel = side * side;
    let totals = Totals::of(&count_px, per_pixel);
    let mut buffers = out.accounts().to_vec();
    buffers.extend(post_buffers);
    if table.is_some() {
        buffers.push(("sdf scatter table", field.data.len() * 16));
    }

    if settings.aovs {
        centre_aovs(
            ctx,
            job,
            (max_distance, max_steps),
            (&field, &shading),
            &host,
            &mut frame,
        )?;
        frame.samples_per_pixel = Some(count_px.iter().map(|c| c[1] as f32).collect());
        buffers.push(("aovs", px_bytes as usize));
    }

    let rays = RayCounts {
        primary: pixels * per_pixel as u64,
        ..Default::default()
    };
    frame.stats = totals.stats(passes, timings, buffers, rays, totals.multi);
    Ok(frame)
}

/// The [`CtssPass`] of `job`'s frame (compiled once per device and key) and
/// its host group's bind group: `side × side` samples per pixel, traced by
/// the kernels' CTSS trace or the host trace ([`HostTrace::of`]), cones
/// marching [`ASAP_BATCH`] samples ahead of shading them, or
/// [`DELAYED_BATCH`] under delayed shading.
fn frame_pass(
    ctx: &GpuContext,
    job: &Job,
    (field, shading): (&WgslField, &str),
    host: &Bindings,
) -> Result<(Arc<CtssPass>, wgpu::BindGroup), RenderError> {
    let method = job.method;
    let side = method.ssaa_side().max(1);
    let cone = method.technique().is_cone_traced();
    let batch = if cone && method.delayed_shading() {
        DELAYED_BATCH
    } else {
        ASAP_BATCH
    };
    let trace = HostTrace::of(job);
    let host_wgsl = host_source(job, field, shading, trace, host);
    let layout = host.layout(&ctx.device, "sdf");
    let pass = ctss_pass(
        ctx,
        SdfPassKey {
            host_wgsl,
            batch,
            side,
            trace,
        },
        &layout,
    )?;
    let group = host.bind_group(&ctx.device, "sdf", &layout);
    Ok((pass, group))
}

/// The host WGSL of `job`'s [`CtssPass`]: the occlusion directions, the
/// compiled `field`, its `shading` and `trace.wgsl`'s hooks, the
/// semi-transparent samplers when the scene has translucency, the host
/// trace when the kernels' CTSS trace does not trace the samples (`trace`),
/// and the declarations of the `host` group.
fn host_source(
    job: &Job,
    field: &WgslField,
    shading: &str,
    trace: Option<HostTrace>,
    host: &Bindings,
) -> String {
    let mut host_wgsl = [
        subcone_kernels::ao::WGSL,
        field.source.as_str(),
        shading,
        TRACE_WGSL,
    ]
    .concat();
    if job.scene.has_translucency() {
        host_wgsl += TRANSLUCENT_WGSL;
    }
    if let Some(t) = trace {
        host_wgsl += t.wgsl();
    }
    host_wgsl += &host.declarations();
    host_wgsl
}

/// What the [`CtssPass`] of `job`'s frame reads and writes: the camera, the
/// trace's `params`, the background, the host's bind `group`, and the
/// colour and count buffers of `out`, over the whole image.
fn ctss_inputs<'a>(
    job: &Job,
    params: subcone_kernels::ctss::CtssParams,
    group: &'a wgpu::BindGroup,
    out: &'a Bindings,
) -> Result<CtssBuffers<'a>, RenderError> {
    let camera = job.camera;
    Ok(CtssBuffers {
        camera: CtssCamera {
            position: camera.position,
            forward: camera.forward,
            right: camera.right(),
            up: camera.up,
            fov_y: camera.fov_y,
            jitter: camera.jitter,
        }
        .into(),
        params,
        background: job.scene.background,
        host_group: Some(group),
        size: (job.settings.width, job.settings.height),
        output: out.get("color_out")?,
        counts: Some(out.get("counts_out")?),
        depth: None,
        rect: None,
    })
}

/// A `w × h` frame of the colours read back (`color_px`, RGBA: the alpha
/// dropped).
fn colour_frame(w: u32, h: u32, color_px: &[[f32; 4]]) -> Frame {
    let mut frame = Frame::new(w, h);
    for (c, p) in frame.color.iter_mut().zip(color_px) {
        *c = glam::Vec3::new(p[0], p[1], p[2]);
    }
    frame
}

/// The field of `job`'s SDF scene and its march `(max_distance,
/// max_steps)`, the settings' overrides applied; not an SDF scene or a NaN
/// distance is an error.
fn march<'a>(job: &Job<'a>) -> Result<(&'a SdfGeometry, (f32, u32)), RenderError> {
    let g = job
        .scene
        .sdf_geometry()
        .ok_or_else(|| err("not an SDF scene"))?;
    let max_distance = job.settings.max_distance.unwrap_or(g.max_distance);
    let max_steps = job.settings.max_steps.unwrap_or(g.max_steps);
    if max_distance.is_nan() {
        return Err(err("the maximum ray distance is NaN"));
    }
    Ok((g, (max_distance, max_steps)))
}

/// The host group of `frame`'s programs, as group `index`: the frame's
/// constants, the trace's parameters (`ctss`) and the field's scatter
/// table, when it has one.
fn host_bindings(
    ctx: &GpuContext,
    index: u32,
    frame: &SdfFrame,
    params: &subcone_kernels::ctss::CtssParams,
    table: Option<&wgpu::Buffer>,
) -> Result<Bindings, RenderError> {
    let mut b = Bindings::new(index);
    b.uniform(ctx, "frame", "SdfFrame", frame)?;
    b.uniform(ctx, "ctss", "subcone_CtssParams", params)?;
    if let Some(t) = table {
        b.buffer("sdf_data", "array<vec4<f32>>", BufferAccess::Read, t);
    }
    Ok(b)
}

/// The [`CtssPass`] of `key`, compiled once per device and key, with the
/// host group's `layout`.
fn ctss_pass(
    ctx: &GpuContext,
    key: SdfPassKey,
    layout: &wgpu::BindGroupLayout,
) -> Result<Arc<CtssPass>, RenderError> {
    ctx.cached_or_insert(key, |key| {
        let desc = CtssPassDesc::default()
            .with_batch(key.batch)
            .with_samples_per_side(key.side)
            .with_trace(match key.trace {
                None => CtssTrace::Kernels,
                Some(_) => CtssTrace::Host,
            })
            .with_output(CtssOutput::Buffers { counts: true })
            .with_host_layout(layout);
        ctx.scoped("sdf", || CtssPass::new(&ctx.device, &key.host_wgsl, &desc))?
            .map_err(|e| err(format!("sdf: {e}")))
    })
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
    /// background and ambient, the march's `(max_distance, max_steps)`.
    fn new(job: &Job, (max_distance, max_steps): (f32, u32)) -> Self {
        let (scene, camera, settings) = (job.scene, job.camera, job.settings);
        let ao_radius = scene.sdf_geometry().map_or(0.0, |g| g.ao_radius());
        SdfFrame {
            camera: PinholeCamera::new(
                camera.position,
                (camera.forward, camera.right(), camera.up),
                (0.5 * camera.fov_y).tan(),
                (settings.width, settings.height),
            )
            .with_jitter(camera.jitter),
            background: scene.background.to_array(),
            max_distance,
            ambient: scene.ambient.to_array(),
            max_steps,
            ao_rays: settings.ao_rays,
            ao_radius: if ao_radius.is_nan() { 0.0 } else { ao_radius },
            cone: job.method.technique().is_cone_traced() as u32,
            _pad: 0,
        }
    }
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
    /// The totals of the per-pixel counters `count_px`, a pixel's `multi`
    /// against `per_pixel` samples.
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

    /// The [`FrameStats`] of a frame with these totals: its `passes`,
    /// `timings` and `buffers`, its `rays` with the totals' shadow and
    /// occlusion rays, its shaded samples and field evaluations, and
    /// `multi_sample_pixels` as the method counts them.
    fn stats(
        &self,
        passes: Passes,
        timings: Vec<PassTiming>,
        buffers: BufferSizes,
        rays: RayCounts,
        multi_sample_pixels: u64,
    ) -> FrameStats {
        FrameStats {
            passes,
            timings,
            buffers,
            rays: RayCounts {
                shadow: self.shadow,
                ao: self.ao,
                ..rays
            },
            shaded_samples: self.samples,
            sdf_evaluations: self.steps,
            multi_sample_pixels,
            raster_samples: 0,
        }
    }
}

/// The AOV pass (not timed): depth and normal through each pixel centre
/// into `frame`, sphere traced through `field` (with the frame's
/// `shading`, which the shared hooks compile against) in a program of its
/// own over the frame's `host` group (group 1: [`host_bindings`]).
fn centre_aovs(
    ctx: &GpuContext,
    job: &Job,
    (max_distance, max_steps): (f32, u32),
    (field, shading): (&WgslField, &str),
    host: &Bindings,
    frame: &mut Frame,
) -> Result<(), RenderError> {
    let (camera, settings) = (job.camera, job.settings);
    let (w, h) = (settings.width, settings.height);
    let pixels = w as usize * h as usize;
    let plain = Method::new(Technique::NoAa).ctss_params(camera, h, max_distance, max_steps);
    let mut b = Bindings::new(0);
    b.uniform(ctx, "aov_params", "subcone_CtssParams", &plain)?;
    b.storage(
        ctx,
        "aovs",
        "aov_out",
        "array<vec4<f32>>",
        pixels as u64 * 16,
    )?;
    let pending = format!("const subcone_CTSS_BATCH: u32 = {ASAP_BATCH}u;\n");
    let mut sources = kernels();
    sources.extend([
        field.source.as_str(),
        shading,
        &pending,
        subcone_passes::SPHERE_TRACE_HOOK,
        TRACE_WGSL,
        AOVS_WGSL,
    ]);
    let mut program = Program::new(ctx, "sdf aovs", &sources, &[&b, host])?;
    let aovs = program.pipeline("sdf_aovs")?;
    let groups = compute::workgroups(ctx, "SDF", w, h, WORKGROUP)?;
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
