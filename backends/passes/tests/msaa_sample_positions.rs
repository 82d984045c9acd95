//! SRAA's geometric subsamples are the standard 4x MSAA sample pattern:
//! sample `k` of a 4x multisampled target lies at
//! `subcone_kernels::sraa::SUBPIXEL_OFFSETS[k]` from the pixel centre (x
//! right, y down), so a host's 4x MSAA prepass is SRAA's geometry pass
//! (`SraaPass`'s `GeometryLayout::Multisampled` relies on it).
//!
//! Measured on the device: a per-sample-shaded pass (`@builtin(sample_index)`
//! forces one fragment per sample) writes each sample's
//! `@builtin(position)` fraction into a 4x `Rgba16Float` target (eighths of
//! a pixel are exact in f16), and a compute pass reads every sample back.

mod common;

#[allow(dead_code)]
#[path = "../examples/host_sraa.rs"]
mod host_sraa;

use subcone_kernels::sraa::SUBPIXEL_OFFSETS;
use wgpu::util::DeviceExt;

const SIZE: u32 = 4;

const WGSL: &str = "
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the viewport.
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) pos: vec4<f32>, @builtin(sample_index) k: u32) -> @location(0) vec4<f32> {
    return vec4<f32>(fract(pos.xy), f32(k), 1.0);
}

@group(0) @binding(0) var ms: texture_multisampled_2d<f32>;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(1)
fn read_main(@builtin(global_invocation_id) id: vec3<u32>) {
    for (var k = 0u; k < 4u; k++) {
        out[(id.y * SIZE + id.x) * 4u + k] = textureLoad(ms, vec2<i32>(id.xy), i32(k));
    }
}
";

#[test]
fn msaa_sample_positions_are_subpixel_offsets() {
    let Some((device, queue)) =
        common::device_or_skip("msaa sample positions", host_sraa::open_device)
    else {
        return;
    };
    let source = format!("const SIZE: u32 = {SIZE}u;\n{WGSL}");
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("sample positions"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let format = wgpu::TextureFormat::Rgba16Float;
    let draw = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("sample positions"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState {
            count: 4,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let read = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("sample positions read"),
        layout: None,
        module: &module,
        entry_point: Some("read_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let target = host_sraa::host::texture(
        &device,
        "4x target",
        (SIZE, SIZE, 1),
        4,
        format,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    );
    let view = target.create_view(&Default::default());
    let n = (SIZE * SIZE * 4) as usize;
    let out = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sample positions"),
        contents: &vec![0u8; n * 16],
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    });
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("staging"),
        size: (n * 16) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &read.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: out.as_entire_binding(),
            },
        ],
    });
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: -1.0,
                        g: -1.0,
                        b: -1.0,
                        a: 0.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&draw);
        pass.draw(0..3, 0..1);
    }
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&read);
        pass.set_bind_group(0, Some(&group), &[]);
        pass.dispatch_workgroups(SIZE, SIZE, 1);
    }
    enc.copy_buffer_to_buffer(&out, 0, &staging, 0, (n * 16) as u64);
    queue.submit([enc.finish()]);
    let data = host_sraa::host::read_buffer(&device, &staging).expect("read-back");
    let v: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&data);
    for p in 0..(SIZE * SIZE) as usize {
        for (k, offset) in SUBPIXEL_OFFSETS.iter().enumerate() {
            let s = v[p * 4 + k];
            assert_eq!(
                s[2], k as f32,
                "pixel {p} sample {k}: fragment ran for sample {}",
                s[2]
            );
            let measured = glam::Vec2::new(s[0] - 0.5, s[1] - 0.5);
            assert_eq!(
                measured, *offset,
                "pixel {p}: sample {k} lies at {measured} from the centre, SUBPIXEL_OFFSETS[{k}] = {offset}"
            );
        }
    }
}
