//! Evaluate a compiled SDF tree on the GPU at given points: the check that the
//! WGSL code generator ([`SdfNode::to_wgsl`]) computes [`SdfNode::eval`] and
//! [`SdfNode::eval_split`].

use glam::Vec3;
use subcone_scene::sdf::SdfNode;
use subcone_scene::RenderError;
use wgpu::util::DeviceExt;

use crate::context::{err, GpuContext};

const FIELD_WGSL: &str = include_str!("field.wgsl");

/// One point's values on the GPU.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldSample {
    /// `SdfNode::eval`: distance and material.
    pub eval: (f32, u32),
    /// `SdfNode::eval_split`: safe step, surface distance, material.
    pub split: (f32, f32, u32),
}

/// Evaluate `root`'s generated WGSL at `points` on the device. Errors on no
/// points, too many points, or any GPU failure.
pub fn evaluate_field(
    ctx: &GpuContext,
    root: &SdfNode,
    points: &[Vec3],
) -> Result<Vec<FieldSample>, RenderError> {
    if points.is_empty() {
        return Err(err("no points to evaluate"));
    }
    let n = points.len() as u64;
    let groups = n.div_ceil(64);
    if groups > ctx.device.limits().max_compute_workgroups_per_dimension as u64 {
        return Err(err(format!("{n} points are too many for one dispatch")));
    }
    ctx.check_buffer_size("the evaluation points", n * 32)?;
    let (source, field) = super::upload_field(ctx, &root.to_wgsl())?;
    let source = [source.as_str(), FIELD_WGSL].concat();
    let pts: Vec<[f32; 4]> = points.iter().map(|p| [p.x, p.y, p.z, 0.0]).collect();
    let (pipeline, pts_buf, out) = ctx.scoped("compiling the SDF field", || {
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("sdf field"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        let pipeline = ctx
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("sdf field"),
                layout: None,
                module: &module,
                entry_point: Some("sdf_field"),
                compilation_options: Default::default(),
                cache: None,
            });
        let pts_buf = ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("points"),
                contents: bytemuck::cast_slice(&pts),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let out = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("field values"),
            size: n * 32,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        (pipeline, pts_buf, out)
    })?;
    let group = ctx.scoped("SDF field bind group", || {
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: pts_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: out.as_entire_binding(),
            },
        ];
        if let Some(d) = &field.data {
            entries.push(wgpu::BindGroupEntry {
                binding: 4,
                resource: d.as_entire_binding(),
            });
        }
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sdf field"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    })?;
    let mut timings = Vec::new();
    ctx.timed_pass("sdf field", &mut timings, |enc| {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sdf field"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(groups as u32, 1, 1);
    })?;
    let v: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&ctx.read_buffer(&out, 0, n * 32)?);
    Ok(v.chunks_exact(2)
        .map(|c| FieldSample {
            eval: (c[0][0], c[0][1] as u32),
            split: (c[0][2], c[0][3], c[1][0] as u32),
        })
        .collect())
}
