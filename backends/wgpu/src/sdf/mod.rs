//! SDF scenes on the GPU: NoAA, SSAA, CTSS, CTSS-R and SSAA+CTSS as one compute
//! pass each, producing the images of the CPU reference
//! (`subcone_cpu::sphere::SdfView`). SRAA-RT on SDF scenes is CPU-only
//! ([`SRAA_RT_CPU_ONLY`]).
//!
//! The scene's tree is compiled to WGSL ([`SdfNode::to_wgsl`]), its materials
//! and lights to WGSL constants (`shading.rs`), and concatenated with the
//! kernels' WGSL (`cone`, `mask`, `aggregate`, `ctss`: Algorithm 1 of CTSS,
//! eq. 3–10) and this module's entry points (`trace.wgsl`): one invocation per
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

mod aovs;
mod shading;
mod trace;

use std::hash::{Hash, Hasher};
use std::sync::Arc;

use subcone_kernels::ctss::CtssParams;
use subcone_kernels::passes::{Passes, Technique};
use subcone_scene::sdf::wgsl::WgslField;
use subcone_scene::sdf::SdfNode;
use subcone_scene::{
    Camera, Frame, FrameStats, Method, RayCounts, RenderError, RenderSettings, Scene,
    UnsupportedReason,
};
use wgpu::util::DeviceExt;

use crate::context::{err, GpuContext};

const TRACE_WGSL: &str = include_str!("trace.wgsl");
const AOVS_WGSL: &str = include_str!("aovs.wgsl");
const WORKGROUP: u32 = 8;
/// Samples a cone marches ahead of shading them (the `PENDING` of
/// trace.wgsl) for ASAP methods.
const ASAP_BATCH: u32 = 8;
/// The same for delayed shading (`ctss-delayed`): enough for every cone of
/// the built-in SDF scenes to be traced completely before it is shaded.
pub const DELAYED_BATCH: u32 = 32;
/// Where generated fields find their scatter tables.
const DATA_BINDING: &str = "@group(0) @binding(4) var<storage, read> sdf_data: array<vec4<f32>>;\n";

/// Why SRAA-RT is refused on SDF scenes: its sphere-traced subsamples and
/// their reconstruction exist on the CPU only (`subcone_cpu::sphere`); this
/// backend would need a subpixel geometry pass in the generated SDF shader
/// feeding the triangle path's reconstruction pass.
pub const SRAA_RT_CPU_ONLY: UnsupportedReason = UnsupportedReason::CpuOnly {
    what: "sraa-rt on SDF scenes",
    why: "sphere-traced subsamples and their reconstruction have no WGSL twin",
};

/// Why `ctss+edges` is refused: hit group subdivision (CTSS §5.3,
/// `subcone_kernels::ctss::ConeStepper::split_group`) has no WGSL twin.
pub const CTSS_EDGES_CPU_ONLY: UnsupportedReason = UnsupportedReason::CpuOnly {
    what: "ctss+edges",
    why: "hit group subdivision, CTSS §5.3, has no WGSL twin",
};

/// Most samples per pixel side (`ssaaN`, `ssaaN+ctss`) one invocation traces.
pub const MAX_SIDE_SAMPLES: u32 = 64;

/// The kernels' WGSL every SDF shader starts with.
fn kernels_wgsl() -> String {
    [
        subcone_kernels::wgsl::PARAMS,
        subcone_kernels::cone::WGSL,
        subcone_kernels::mask::WGSL,
        subcone_kernels::aggregate::WGSL,
        subcone_kernels::ctss::WGSL,
    ]
    .concat()
}

/// The field's WGSL and its scatter table on the device (none when empty).
struct GpuField {
    data: Option<wgpu::Buffer>,
    data_bytes: usize,
}

/// Upload a compiled field's scatter table; returns the field's WGSL with
/// the table's binding declared when there is one.
fn upload_field(ctx: &GpuContext, f: &WgslField) -> Result<(String, GpuField), RenderError> {
    let mut source = f.source.clone();
    let data = if f.data.is_empty() {
        None
    } else {
        let bytes: &[u8] = bytemuck::cast_slice(&f.data);
        ctx.check_buffer_size("the SDF's scatter table", bytes.len() as u64)?;
        source.push_str(DATA_BINDING);
        Some(ctx.scoped("SDF scatter table", || {
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sdf_data"),
                    contents: bytes,
                    usage: wgpu::BufferUsages::STORAGE,
                })
        })?)
    };
    Ok((
        source,
        GpuField {
            data,
            data_bytes: f.data.len() * 16,
        },
    ))
}

/// Compiled pipelines of one scene (and variant), reused across frames.
struct Pipelines {
    render: wgpu::ComputePipeline,
    aovs: Option<wgpu::ComputePipeline>,
    field: GpuField,
}

fn hash_of(x: impl Hash) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    x.hash(&mut h);
    h.finish()
}

fn pipelines(
    ctx: &GpuContext,
    scene: &Scene,
    root: &SdfNode,
    shadows: bool,
    aovs: bool,
    batch: u32,
) -> Result<Arc<Pipelines>, RenderError> {
    let field = root.to_wgsl();
    let mut source = kernels_wgsl();
    source.push_str(&field.source);
    if !field.data.is_empty() {
        source.push_str(DATA_BINDING);
    }
    source.push_str(&shading::shading_wgsl(
        &scene.materials,
        &scene.lights,
        shadows,
    )?);
    source.push_str(&format!("const PENDING: u32 = {batch}u;\n"));
    source.push_str(TRACE_WGSL);
    if aovs {
        source.push_str(AOVS_WGSL);
    }
    let data_bits: Vec<u32> = field.data.iter().flatten().map(|x| x.to_bits()).collect();
    // Per device, by the shader source and the scatter table: a scene changed
    // in any way compiles anew.
    let key = hash_of(("sdf", &source, &data_bits));
    let cached = ctx
        .cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .get(&key)
        .cloned();
    if let Some(p) = cached.and_then(|p| p.downcast::<Pipelines>().ok()) {
        return Ok(p);
    }
    let (_, gpu_field) = upload_field(ctx, &field)?;
    let (render, aov) = ctx.scoped("compiling the SDF shader", || {
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("sdf trace"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        let make = |entry: &str| {
            ctx.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: None,
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
        };
        (make("sdf_render"), aovs.then(|| make("sdf_aovs")))
    })?;
    let p = Arc::new(Pipelines {
        render,
        aovs: aov,
        field: gpu_field,
    });
    ctx.cache_insert(key, p.clone());
    Ok(p)
}

/// `SdfView::params` of the CPU backend.
fn ctss_params(tan: f32, method: &Method, max_distance: f32, max_steps: u32) -> CtssParams {
    CtssParams::new(tan)
        .with_range(0.0, max_distance)
        .with_max_steps(max_steps)
        .relaxed(method.technique == Technique::CtssR)
        .with_visibility_k(method.visibility_k)
}

/// The `SdfFrame` uniform of trace.wgsl.
#[allow(clippy::too_many_arguments)]
fn frame_uniform(
    camera: &Camera,
    s: &RenderSettings,
    scene: &Scene,
    max_distance: f32,
    max_steps: u32,
    side: u32,
    cone: bool,
) -> Vec<u32> {
    let b = |x: f32| x.to_bits();
    let v = |v: glam::Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    let mut u = Vec::with_capacity(28);
    u.extend(v(camera.position));
    u.push(s.width);
    u.extend(v(camera.forward));
    u.push(s.height);
    u.extend(v(camera.right()));
    u.push(b((0.5 * camera.fov_y).tan()));
    u.extend(v(camera.up));
    u.push(b(max_distance));
    u.extend(v(scene.background));
    u.push(max_steps);
    u.extend(v(scene.ambient));
    u.push(side);
    u.extend([cone as u32, 0, 0, 0]);
    u
}

pub(crate) fn render(
    ctx: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    method: &Method,
    settings: &RenderSettings,
    passes: Passes,
) -> Result<Frame, RenderError> {
    let g = scene
        .sdf_geometry()
        .ok_or_else(|| err("not an SDF scene"))?;
    // `WgpuBackend::plan` has refused mirrors, SRAA-RT, ctss+edges and more
    // than MAX_SIDE_SAMPLES samples per side.
    let max_distance = settings.max_distance.unwrap_or(g.max_distance);
    let max_steps = settings.max_steps.unwrap_or(g.max_steps);
    if max_distance.is_nan() {
        return Err(err("the maximum ray distance is NaN"));
    }
    let (w, h) = (settings.width, settings.height);
    let side = match method.technique {
        Technique::Ssaa | Technique::SsaaCtss => method.ssaa_side.max(1),
        _ => 1,
    };
    let cone = matches!(
        method.technique,
        Technique::Ctss | Technique::CtssR | Technique::SsaaCtss
    );
    let tan = camera.cone_tan_theta(h, method.cone_coverage) / side as f32;
    let params = ctss_params(tan, method, max_distance, max_steps);
    let pixels = w as u64 * h as u64;
    let groups = (w.div_ceil(WORKGROUP), h.div_ceil(WORKGROUP));
    let max_groups = ctx.device.limits().max_compute_workgroups_per_dimension;
    if groups.0 > max_groups || groups.1 > max_groups {
        return Err(err(format!(
            "{w}x{h} needs more than {max_groups} workgroups per dimension"
        )));
    }
    let px_bytes = pixels * 16;
    ctx.check_buffer_size("the colour buffer", px_bytes)?;

    let shadows = passes.contains(Passes::SHADOW) && !scene.lights.is_empty();
    let batch = if cone && method.delayed_shading {
        DELAYED_BATCH
    } else {
        ASAP_BATCH
    };
    let pipes = pipelines(ctx, scene, &g.root, shadows, settings.aovs, batch)?;

    let frame_words = frame_uniform(camera, settings, scene, max_distance, max_steps, side, cone);
    let frame_buf = ctx.scoped("SDF frame uniform", || {
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sdf frame"),
                contents: bytemuck::cast_slice(&frame_words),
                usage: wgpu::BufferUsages::UNIFORM,
            })
    })?;
    let name = if cone {
        "cone tracing"
    } else {
        "sphere tracing"
    };
    let mut timings = Vec::new();
    let post = passes.contains(Passes::POST_PROCESS).then_some((w, h));
    let (color_px, count_px, post_buffers) = trace::run(
        ctx,
        &pipes.render,
        pipes.field.data.as_ref(),
        &frame_buf,
        &params,
        groups,
        px_bytes,
        name,
        &mut timings,
        post,
    )?;

    let mut frame = Frame::new(w, h);
    for (c, p) in frame.color.iter_mut().zip(&color_px) {
        *c = glam::Vec3::new(p[0], p[1], p[2]);
    }
    let per_pixel = side * side;
    let (mut steps, mut samples, mut shadow, mut multi) = (0u64, 0u64, 0u64, 0u64);
    for c in &count_px {
        steps += c[0] as u64;
        samples += c[1] as u64;
        shadow += c[2] as u64;
        if c[1] > per_pixel {
            multi += 1;
        }
    }
    let mut buffers = vec![("color", px_bytes as usize), ("counts", px_bytes as usize)];
    buffers.extend(post_buffers);
    if pipes.field.data.is_some() {
        buffers.push(("sdf scatter table", pipes.field.data_bytes));
    }

    if settings.aovs {
        let aov_pipe = pipes
            .aovs
            .as_ref()
            .ok_or_else(|| err("the AOV pipeline is missing"))?;
        // Depth and normal through each pixel centre (not timed, as on the CPU).
        let plain = ctss_params(
            camera.cone_tan_theta(h, 1.0),
            &Method::new(Technique::NoAa),
            max_distance,
            max_steps,
        );
        let g = aovs::run(
            ctx,
            aov_pipe,
            pipes.field.data.as_ref(),
            &frame_buf,
            &plain,
            groups,
            px_bytes,
        )?;
        frame.depth = Some(g.iter().map(|a| a[3]).collect());
        frame.normal = Some(
            g.iter()
                .map(|a| glam::Vec3::new(a[0], a[1], a[2]))
                .collect(),
        );
        frame.samples_per_pixel = Some(count_px.iter().map(|c| c[1] as f32).collect());
        buffers.push(("aovs", px_bytes as usize));
    }

    frame.stats = FrameStats {
        passes,
        timings,
        buffers,
        rays: RayCounts {
            primary: pixels * per_pixel as u64,
            shadow,
            ..Default::default()
        },
        shaded_samples: samples,
        sdf_evaluations: steps,
        multi_sample_pixels: multi,
    };
    Ok(frame)
}
