//! The AOV pass (`aovs.wgsl`): view depth and normal through each pixel
//! centre by sphere tracing with a pixel-wide cone, as the CPU's AOV block.
//! Built and run only when AOVs are requested; not timed (nor is it on the CPU).

use subcone_kernels::ctss::CtssParams;
use subcone_scene::RenderError;
use wgpu::util::DeviceExt;

use crate::context::GpuContext;

/// Per pixel `(normal, depth)`: depth `+∞` and normal 0 on a miss.
pub(super) fn run(
    ctx: &GpuContext,
    pipeline: &wgpu::ComputePipeline,
    data: Option<&wgpu::Buffer>,
    frame_buf: &wgpu::Buffer,
    plain: &CtssParams,
    groups: (u32, u32),
    px_bytes: u64,
) -> Result<Vec<[f32; 4]>, RenderError> {
    let (plain_buf, aov) = ctx.scoped("SDF AOV buffers", || {
        (
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("aov params"),
                    contents: bytemuck::bytes_of(plain),
                    usage: wgpu::BufferUsages::UNIFORM,
                }),
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("aovs"),
                size: px_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
        )
    })?;
    let group = ctx.scoped("SDF AOV bind group", || {
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 5,
                resource: plain_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 6,
                resource: aov.as_entire_binding(),
            },
        ];
        if let Some(d) = data {
            entries.push(wgpu::BindGroupEntry {
                binding: 4,
                resource: d.as_entire_binding(),
            });
        }
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sdf aovs"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    })?;
    let mut untimed = Vec::new();
    ctx.timed_pass("aovs", &mut untimed, |enc| {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("aovs"),
            timestamp_writes: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(groups.0, groups.1, 1);
    })?;
    Ok(bytemuck::pod_collect_to_vec(
        &ctx.read_buffer(&aov, 0, px_bytes)?,
    ))
}
