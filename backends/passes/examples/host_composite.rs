//! A host that composites `CtssPass`'s output over its own rasterised scene
//! by depth.
//!
//! The host rasterises a ground plane with its own wgpu render pipeline and
//! depth buffer, writing colour and view depth (clip `w`: the distance along
//! the camera's forward axis). `CtssPass` cone-traces a sphere that
//! intersects the plane, through the same view and projection matrices
//! (`CtssProjection`), over a transparent background (premultiplied colour,
//! alpha the masks' coverage, `CtssBackground::Transparent`) with view depth
//! (`CtssDepth::View`). The host then composites on the CPU after read-back:
//! where the SDF's depth is nearer than the raster's, the SDF `over` the
//! raster colour; elsewhere the raster colour. The sphere's upper half stands
//! in front of the plane; its lower half is hidden by it; its edge pixels
//! blend with the plane behind them by their coverage.
//!
//! `cargo run -p subcone-passes --example host_composite [out.png]` writes
//! the composite. The test `tests/host_composite.rs` reads back pixels on
//! both sides of the intersection.

use glam::{Mat4, Vec3, Vec4};
use subcone_kernels::cone::{cone_tan_theta, PixelFootprint};
use subcone_kernels::ctss::{CtssParams, CONE_COVERAGE};
use subcone_passes::{
    CtssBackground, CtssDepth, CtssFrame, CtssPass, CtssPassDesc, CtssProjection,
};
use wgpu::util::DeviceExt;

#[path = "host/mod.rs"]
pub mod host;
pub use host::open_device;

/// The eye, the point it looks at and the vertical field of view.
pub const EYE: Vec3 = Vec3::new(0.0, 2.0, -4.5);
/// The point the camera looks at.
pub const TARGET: Vec3 = Vec3::new(0.0, 0.1, 0.0);
/// Vertical field of view in radians.
pub const FOV_Y: f32 = 0.8;
/// The sphere's centre (on the plane y = 0) and radius.
pub const SPHERE: (Vec3, f32) = (Vec3::new(0.0, 0.0, 0.0), 1.0);
/// The plane's colour.
pub const PLANE: Vec3 = Vec3::new(0.25, 0.55, 0.3);
/// The sky's colour (where the plane is not drawn).
pub const SKY: Vec3 = Vec3::new(0.6, 0.7, 0.9);

/// The sphere in WGSL, for `CtssPass`: a unit sphere at the origin, shaded
/// orange with a light from above.
pub const SPHERE_WGSL: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let d = length(p) - 1.0;
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let l = normalize(vec3<f32>(0.3, 1.0, -0.4));
    return vec3<f32>(0.9, 0.45, 0.15) * (0.25 + 0.75 * max(dot(n, l), 0.0));
}
";

/// The host's raster shader: world positions through `view_projection`,
/// the plane's colour and the view depth (clip w of a perspective
/// projection) into two colour targets.
const RASTER_WGSL: &str = "
@group(0) @binding(0) var<uniform> view_projection: mat4x4<f32>;
struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) depth: f32,
}
@vertex fn vs(@location(0) p: vec3<f32>) -> Out {
    let c = view_projection * vec4<f32>(p, 1.0);
    return Out(c, c.w);
}
struct Targets {
    @location(0) colour: vec4<f32>,
    @location(1) depth: vec4<f32>,
}
@fragment fn fs(i: Out) -> Targets {
    return Targets(vec4<f32>(0.25, 0.55, 0.3, 1.0), vec4<f32>(i.depth, 0.0, 0.0, 1.0));
}
";

/// The camera's view (right-handed: it looks down its −z) and projection
/// (perspective, wgpu's depth range 0 to 1) for a `width × height` image,
/// as a host's math library makes them.
pub fn matrices(width: u32, height: u32) -> (Mat4, Mat4) {
    let f = (TARGET - EYE).normalize();
    let s = f.cross(Vec3::Y).normalize();
    let u = s.cross(f);
    let view = Mat4::from_rows(
        s.extend(-s.dot(EYE)),
        u.extend(-u.dot(EYE)),
        (-f).extend(f.dot(EYE)),
        Vec4::W,
    );
    let (near, far) = (0.1, 100.0);
    let t = near * (0.5 * FOV_Y).tan();
    let r = t * width as f32 / height as f32;
    let projection = Mat4::from_rows(
        Vec4::new(near / r, 0.0, 0.0, 0.0),
        Vec4::new(0.0, near / t, 0.0, 0.0),
        Vec4::new(0.0, 0.0, far / (near - far), near * far / (near - far)),
        Vec4::new(0.0, 0.0, -1.0, 0.0),
    );
    (view, projection)
}

/// What the host has after read-back: its raster colour and view depth
/// (+∞ where the plane is not drawn), the CTSS layer (premultiplied colour
/// and alpha, view depth) and the composite.
pub struct Composite {
    /// Width and height.
    pub size: (u32, u32),
    /// The raster colour (the sky where the plane is not drawn).
    pub raster: Vec<Vec3>,
    /// The raster's view depth, +∞ for the sky.
    pub raster_depth: Vec<f32>,
    /// CtssPass's premultiplied colour and alpha.
    pub sdf: Vec<[f32; 4]>,
    /// CtssPass's view depth.
    pub sdf_depth: Vec<f32>,
    /// The composite.
    pub image: Vec<Vec3>,
}

/// The raster's colour and view depth (in `x`), read back.
type RasterImages = (Vec<[f32; 4]>, Vec<[f32; 4]>);

/// Rasterise the plane: colour and view depth, `Rgba32Float` each, with a
/// `Depth32Float` depth buffer.
fn rasterise(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    view_projection: Mat4,
    (width, height): (u32, u32),
) -> Result<RasterImages, String> {
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let f32x4 = wgpu::TextureFormat::Rgba32Float;
    let colour = host::texture(device, "raster colour", (width, height, 1), 1, f32x4, usage);
    let depth_out = host::texture(
        device,
        "raster view depth",
        (width, height, 1),
        1,
        f32x4,
        usage,
    );
    let zbuffer = host::texture(
        device,
        "raster depth buffer",
        (width, height, 1),
        1,
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    let s = 8.0f32;
    let quad: [[f32; 3]; 6] = [
        [-s, 0.0, -s],
        [s, 0.0, -s],
        [s, 0.0, s],
        [-s, 0.0, -s],
        [s, 0.0, s],
        [-s, 0.0, s],
    ];
    let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("plane"),
        contents: bytemuck::cast_slice(&quad),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let layout = host::uniform_layout(device, wgpu::ShaderStages::VERTEX);
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("view projection"),
        contents: bytemuck::cast_slice(&view_projection.to_cols_array()),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let group = host::uniform_group(device, &layout, &uniform);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("raster"),
        source: wgpu::ShaderSource::Wgsl(RASTER_WGSL.into()),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("raster"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let target = Some(wgpu::ColorTargetState {
        format: f32x4,
        blend: None,
        write_mask: wgpu::ColorWrites::ALL,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("raster"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 12,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3],
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[target.clone(), target],
        }),
        multiview_mask: None,
        cache: None,
    });
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let (cv, dv) = (
            colour.create_view(&Default::default()),
            depth_out.create_view(&Default::default()),
        );
        let zv = zbuffer.create_view(&Default::default());
        let attachment = |view, clear: [f64; 4]| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: clear[0],
                        g: clear[1],
                        b: clear[2],
                        a: clear[3],
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let sky = [SKY.x as f64, SKY.y as f64, SKY.z as f64, 1.0];
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("raster"),
            color_attachments: &[
                attachment(&cv, sky),
                attachment(&dv, [f64::INFINITY, 0.0, 0.0, 1.0]),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &zv,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.draw(0..6, 0..1);
    }
    let c = host::read_rgba32f(device, queue, enc, &colour)?;
    let d = host::read_rgba32f(
        device,
        queue,
        device.create_command_encoder(&Default::default()),
        &depth_out,
    )?;
    Ok((c, d))
}

/// Rasterise the plane, cone-trace the sphere and composite by depth.
pub fn render(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    width: u32,
    height: u32,
) -> Result<Composite, String> {
    let (view, projection) = matrices(width, height);
    let (raster, raster_depth) = rasterise(device, queue, projection * view, (width, height))?;

    let desc = CtssPassDesc::default()
        .with_output_format(wgpu::TextureFormat::Rgba32Float)
        .with_background(CtssBackground::Transparent)
        .with_depth(CtssDepth::View);
    let pass = CtssPass::new(device, SPHERE_WGSL, &desc).map_err(|e| e.to_string())?;
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC;
    let out = host::texture(
        device,
        "ctss",
        (width, height, 1),
        1,
        wgpu::TextureFormat::Rgba32Float,
        usage,
    );
    let depth = host::texture(
        device,
        "ctss depth",
        (width, height, 1),
        1,
        wgpu::TextureFormat::R32Float,
        usage,
    );
    let (ov, dv) = (
        out.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    let tan_theta = cone_tan_theta(FOV_Y, height, CONE_COVERAGE, PixelFootprint::Circumscribed);
    let mut enc = device.create_command_encoder(&Default::default());
    pass.encode(
        device,
        queue,
        &mut enc,
        &CtssFrame {
            camera: CtssProjection::new(view, projection).into(),
            params: CtssParams::new(tan_theta)
                .with_range(0.0, 100.0)
                .with_max_steps(256),
            background: Vec3::ZERO,
            host_group: None,
            output: &ov,
            depth: Some(&dv),
            rect: None,
        },
        None,
    )
    .map_err(|e| e.to_string())?;
    let sdf = host::read_rgba32f(device, queue, enc, &out)?;
    // The encoder is submitted: tell the pass, as a frame loop does after
    // each submit, so its uniform slots are free for the next frame.
    pass.end_submission();
    let sdf_depth = host::read_texels::<f32>(
        device,
        queue,
        device.create_command_encoder(&Default::default()),
        &depth,
    )?;

    let raster: Vec<Vec3> = raster.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect();
    let raster_depth: Vec<f32> = raster_depth.iter().map(|d| d[0]).collect();
    let image = (0..raster.len())
        .map(|i| {
            let [r, g, b, a] = sdf[i];
            if sdf_depth[i] < raster_depth[i] {
                Vec3::new(r, g, b) + (1.0 - a) * raster[i]
            } else {
                raster[i]
            }
        })
        .collect();
    Ok(Composite {
        size: (width, height),
        raster,
        raster_depth,
        sdf,
        sdf_depth,
        image,
    })
}

fn main() -> Result<(), String> {
    let (device, queue) = open_device()?;
    let (w, h) = (320, 200);
    let c = render(&device, &queue, w, h)?;
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "host_composite.png".into());
    host::save_png(&path, w, h, &c.image)
}
