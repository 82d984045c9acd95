//! FXAA 3.11 (`subcone_kernels::fxaa`, preset 12) on the GPU: two compute
//! passes over a frame's colour buffer (`array<vec4<f32>>`, linear RGB),
//! encode (clamp, sRGB, luma) then filter and decode, timed together as the
//! pass `"post-process"`. The input buffer is left untouched; the filtered
//! frame is a new buffer for the caller to read back.

use std::sync::Arc;

use subcone_kernels::fxaa::FxaaParams;
use subcone_scene::{PassTiming, RenderError};
use wgpu::util::DeviceExt;

use crate::context::{err, GpuContext};

const FXAA_WGSL: &str = include_str!("fxaa.wgsl");
const WORKGROUP: u32 = 8;

struct Pipelines {
    encode: wgpu::ComputePipeline,
    filter: wgpu::ComputePipeline,
}

fn pipelines(ctx: &GpuContext) -> Result<Arc<Pipelines>, RenderError> {
    // One per device; the source never changes.
    const KEY: u64 = 0x6678_6161_0000_0001;
    if let Some(p) = ctx.cached::<Pipelines>(KEY) {
        return Ok(p);
    }
    let source = [
        subcone_kernels::wgsl::PARAMS,
        subcone_kernels::fxaa::WGSL,
        FXAA_WGSL,
    ]
    .concat();
    let p = ctx.scoped("compiling the FXAA shader", || {
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("fxaa"),
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
        Pipelines {
            encode: make("fxaa_encode_main"),
            filter: make("fxaa_main"),
        }
    })?;
    let p = Arc::new(p);
    ctx.cache_insert(KEY, p.clone());
    Ok(p)
}

/// Buffers allocated by a pass, by name, with their bytes.
pub(crate) type Buffers = Vec<(&'static str, usize)>;

fn entry(binding: u32, buf: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buf.as_entire_binding(),
    }
}

/// FXAA of the `width`×`height` frame in `color` (16 bytes per pixel, needs
/// `STORAGE`): the filtered frame (`STORAGE | COPY_SRC`, same layout) and the
/// buffers the pass allocated, by name. Pushes the pass's timing onto
/// `timings`.
pub(crate) fn run(
    ctx: &GpuContext,
    color: &wgpu::Buffer,
    width: u32,
    height: u32,
    params: &FxaaParams,
    timings: &mut Vec<PassTiming>,
) -> Result<(wgpu::Buffer, Buffers), RenderError> {
    let px_bytes = width as u64 * height as u64 * 16;
    if color.size() < px_bytes {
        return Err(err(format!(
            "FXAA: the colour buffer holds {} bytes, {width}x{height} needs {px_bytes}",
            color.size()
        )));
    }
    let groups = (width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP));
    let max_groups = ctx.device.limits().max_compute_workgroups_per_dimension;
    if groups.0 > max_groups || groups.1 > max_groups {
        return Err(err(format!(
            "FXAA: {width}x{height} needs more than {max_groups} workgroups per dimension"
        )));
    }
    ctx.check_buffer_size("the FXAA buffers", px_bytes)?;
    let pipes = pipelines(ctx)?;
    let frame_words = [width, height, 0, 0];
    let (params_buf, frame_buf, encoded, out) = ctx.scoped("FXAA buffers", || {
        let uniform = |label, contents: &[u8]| {
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: wgpu::BufferUsages::UNIFORM,
                })
        };
        let storage = |label, usage| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: px_bytes,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        (
            uniform("fxaa params", bytemuck::bytes_of(params)),
            uniform("fxaa frame", bytemuck::cast_slice(&frame_words)),
            storage("fxaa encoded", wgpu::BufferUsages::empty()),
            storage("fxaa color", wgpu::BufferUsages::COPY_SRC),
        )
    })?;
    let (encode_group, filter_group) = ctx.scoped("FXAA bind groups", || {
        let encode = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("fxaa encode"),
            layout: &pipes.encode.get_bind_group_layout(0),
            entries: &[entry(1, &frame_buf), entry(2, color), entry(3, &encoded)],
        });
        let filter = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("fxaa filter"),
            layout: &pipes.filter.get_bind_group_layout(0),
            entries: &[
                entry(0, &params_buf),
                entry(1, &frame_buf),
                entry(3, &encoded),
                entry(4, &out),
            ],
        });
        (encode, filter)
    })?;
    ctx.timed_pass("post-process", timings, |enc| {
        // Two compute passes, so that every encoded pixel is written before
        // any is read (the pass boundary orders them).
        for (label, pipeline, group) in [
            ("fxaa encode", &pipes.encode, &encode_group),
            ("fxaa filter", &pipes.filter, &filter_group),
        ] {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        }
    })?;
    Ok((
        out,
        vec![
            ("post-process input", px_bytes as usize),
            ("post-process output", px_bytes as usize),
        ],
    ))
}
