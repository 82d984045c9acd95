//! The tracing pass (`trace.wgsl`): one invocation per pixel traces its
//! samples (sphere or cone tracing), shades them and writes the pixel's
//! colour and its work counters (SDF evaluations, shaded samples, shadow rays).

use subcone_kernels::ctss::CtssParams;
use subcone_scene::{PassTiming, RenderError};
use wgpu::util::DeviceExt;

use crate::context::GpuContext;

/// Per-pixel colours (RGBA) and counters, read back, and the buffers of the
/// post-process pass, by name.
pub(super) type Traced = (Vec<[f32; 4]>, Vec<[u32; 4]>, Vec<(&'static str, usize)>);

/// Run the pass over `groups` workgroups of 8×8 pixels, timed as `name`; with
/// `fxaa` (the frame's width and height), FXAA filters the colours on the GPU
/// before they are read back.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    ctx: &GpuContext,
    pipeline: &wgpu::ComputePipeline,
    data: Option<&wgpu::Buffer>,
    frame_buf: &wgpu::Buffer,
    params: &CtssParams,
    groups: (u32, u32),
    px_bytes: u64,
    name: &'static str,
    timings: &mut Vec<PassTiming>,
    fxaa: Option<(u32, u32)>,
) -> Result<Traced, RenderError> {
    let (params_buf, color, counts) = ctx.scoped("SDF frame buffers", || {
        let storage = |label| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: px_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        (
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("ctss params"),
                    contents: bytemuck::bytes_of(params),
                    usage: wgpu::BufferUsages::UNIFORM,
                }),
            storage("color"),
            storage("counts"),
        )
    })?;
    let group = ctx.scoped("SDF bind group", || {
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: params_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: color.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: counts.as_entire_binding(),
            },
        ];
        if let Some(d) = data {
            entries.push(wgpu::BindGroupEntry {
                binding: 4,
                resource: d.as_entire_binding(),
            });
        }
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sdf"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    })?;
    ctx.timed_pass(name, timings, |enc| {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(name),
            timestamp_writes: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(groups.0, groups.1, 1);
    })?;
    let (color, post_buffers) = match fxaa {
        Some((w, h)) => crate::post::fxaa::run(
            ctx,
            &color,
            w,
            h,
            &subcone_kernels::fxaa::FxaaParams::QUALITY,
            timings,
        )?,
        None => (color, Vec::new()),
    };
    Ok((
        bytemuck::pod_collect_to_vec(&ctx.read_buffer(&color, 0, px_bytes)?),
        bytemuck::pod_collect_to_vec(&ctx.read_buffer(&counts, 0, px_bytes)?),
        post_buffers,
    ))
}
