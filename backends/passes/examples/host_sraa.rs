//! A host renderer that antialiases with SRAA from its own 4x MSAA prepass.
//!
//! The host draws a small scene (two boxes and a sphere, lit by a point light
//! at the eye) with its own wgpu pipelines, on a device it opened itself:
//!
//! 1. a 4x MSAA prepass writing reversed-Z hardware depth and eye-facing
//!    normals per sample (`@interpolate(perspective, sample)`): sample `k` is
//!    SRAA's geometric subsample `k`, at `SUBPIXEL_OFFSETS[k]`;
//! 2. one shaded sample per pixel, rendered without MSAA through the
//!    projection shifted to where the preset puts the shaded sample
//!    (`SraaParams::shaded_offset`: subsample 0 for `SraaParams::PAPER`, the
//!    pixel centre for `SraaParams::TUNED`), with its depth and normal (the
//!    centre geometry the tuned preset needs);
//! 3. `SraaPass` into an `Rgba32Float` storage texture, read back.
//!
//! `cargo run -p subcone-passes --example host_sraa [out.png] [paper|tuned]`
//! writes the image. The test `tests/host_examples.rs` runs [`render`] and
//! compares it by FLIP with the CPU backend's `sraa-paper` / `sraa` of the
//! same triangles ([`scene_triangles`]).

use glam::{Mat4, Vec2, Vec3, Vec4};
use subcone_kernels::sraa::{ShadedPosition, SraaParams};
use subcone_passes::{CentreGeometry, SraaInputs, SraaPass, SraaPassDesc, SubsampleGeometry};
use wgpu::util::DeviceExt;

// Device, texture, read-back and sRGB helpers shared with the other host
// example and the tests.
#[path = "host/mod.rs"]
pub mod host;
use host::texture;
pub use host::{open_device, read_rgba32f};

/// The eye, the point it looks at, up, the vertical field of view.
pub const EYE: Vec3 = Vec3::new(0.0, 0.4, 4.0);
/// Where the camera looks.
pub const TARGET: Vec3 = Vec3::new(0.0, 0.0, 0.0);
/// Roughly up.
pub const UP: Vec3 = Vec3::Y;
/// Vertical field of view, radians.
pub const FOV_Y: f32 = 0.9;
/// The point light's intensity (it sits at the eye, so nothing visible is in
/// shadow: the host needs no shadow pass and matches the CPU's ray tracer).
pub const LIGHT: Vec3 = Vec3::new(14.0, 14.0, 14.0);
/// Ambient radiance.
pub const AMBIENT: Vec3 = Vec3::new(0.05, 0.05, 0.05);
/// Colour of pixels nothing covers.
pub const BACKGROUND: Vec3 = Vec3::new(0.02, 0.03, 0.05);
/// The materials' albedos.
pub const ALBEDO: [Vec3; 3] = [
    Vec3::new(0.8, 0.25, 0.2),
    Vec3::new(0.2, 0.7, 0.3),
    Vec3::new(0.9, 0.9, 0.85),
];
/// Near plane of the host's reversed, infinite projection.
const NEAR: f32 = 0.05;

/// One triangle: corners, per-corner normals, material.
#[derive(Clone, Copy, Debug)]
pub struct Triangle {
    /// Corners.
    pub p: [Vec3; 3],
    /// Normals at the corners.
    pub n: [Vec3; 3],
    /// Index into [`ALBEDO`].
    pub material: u32,
}

fn push_box(out: &mut Vec<Triangle>, m: Mat4, material: u32) {
    let c = |x: f32, y: f32, z: f32| m.transform_point3(Vec3::new(x, y, z));
    // Each face: four corners counter-clockwise seen from outside.
    let faces = [
        [(-1., -1., 1.), (1., -1., 1.), (1., 1., 1.), (-1., 1., 1.)],
        [
            (1., -1., -1.),
            (-1., -1., -1.),
            (-1., 1., -1.),
            (1., 1., -1.),
        ],
        [(1., -1., 1.), (1., -1., -1.), (1., 1., -1.), (1., 1., 1.)],
        [
            (-1., -1., -1.),
            (-1., -1., 1.),
            (-1., 1., 1.),
            (-1., 1., -1.),
        ],
        [(-1., 1., 1.), (1., 1., 1.), (1., 1., -1.), (-1., 1., -1.)],
        [
            (-1., -1., -1.),
            (1., -1., -1.),
            (1., -1., 1.),
            (-1., -1., 1.),
        ],
    ];
    for f in faces {
        let q = f.map(|(x, y, z)| c(x, y, z));
        let n = (q[1] - q[0]).cross(q[2] - q[0]).normalize();
        out.push(Triangle {
            p: [q[0], q[1], q[2]],
            n: [n; 3],
            material,
        });
        out.push(Triangle {
            p: [q[0], q[2], q[3]],
            n: [n; 3],
            material,
        });
    }
}

fn push_sphere(out: &mut Vec<Triangle>, centre: Vec3, r: f32, material: u32) {
    let (rings, segments) = (12, 20);
    let at = |i: u32, j: u32| {
        let th = std::f32::consts::PI * i as f32 / rings as f32;
        let ph = std::f32::consts::TAU * j as f32 / segments as f32;
        Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin())
    };
    for i in 0..rings {
        for j in 0..segments {
            let n = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            let p = n.map(|n| centre + r * n);
            for t in [[0, 1, 2], [0, 2, 3]] {
                let tri = Triangle {
                    p: t.map(|k| p[k]),
                    n: t.map(|k| n[k]),
                    material,
                };
                // Skip the degenerate triangles at the poles.
                if (tri.p[1] - tri.p[0]).cross(tri.p[2] - tri.p[0]).length() > 1e-9 {
                    out.push(tri);
                }
            }
        }
    }
}

/// The scene's triangles: a rotated box in front, a second box behind it
/// (a silhouette over a farther surface), a smooth sphere.
pub fn scene_triangles() -> Vec<Triangle> {
    let mut t = Vec::new();
    push_box(
        &mut t,
        Mat4::from_translation(Vec3::new(0.55, -0.1, 0.6))
            * Mat4::from_rotation_y(0.6)
            * Mat4::from_rotation_x(0.35)
            * Mat4::from_scale(Vec3::splat(0.45)),
        0,
    );
    push_box(
        &mut t,
        Mat4::from_translation(Vec3::new(0.1, 0.15, -0.8))
            * Mat4::from_rotation_y(-0.3)
            * Mat4::from_scale(Vec3::new(1.2, 0.8, 0.3)),
        2,
    );
    push_sphere(&mut t, Vec3::new(-0.8, -0.05, 0.3), 0.55, 1);
    t
}

/// The host's vertex: position, normal, material.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    p: [f32; 3],
    material: u32,
    n: [f32; 3],
    _pad: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Uniforms {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    light: [f32; 4],
    ambient: [f32; 4],
    albedo: [[f32; 4]; 3],
}

/// The host's shaders: one vertex stage, a per-sample G-buffer fragment
/// stage and a shading fragment stage (shaded sample colour, normal).
const HOST_WGSL: &str = "
struct Uniforms {
    view_proj: mat4x4<f32>,
    eye: vec4<f32>,
    light: vec4<f32>,
    ambient: vec4<f32>,
    albedo: array<vec4<f32>, 3>,
}
@group(0) @binding(0) var<uniform> u: Uniforms;

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(perspective, sample) world: vec3<f32>,
    @location(1) @interpolate(perspective, sample) normal: vec3<f32>,
    @location(2) @interpolate(flat) material: u32,
}

@vertex
fn vs_main(@location(0) p: vec3<f32>, @location(1) material: u32, @location(2) n: vec3<f32>) -> VsOut {
    var o: VsOut;
    o.clip = u.view_proj * vec4<f32>(p, 1.0);
    o.world = p;
    o.normal = n;
    o.material = material;
    return o;
}

// The normal facing the eye.
fn facing(in: VsOut) -> vec3<f32> {
    var n = normalize(in.normal);
    if dot(n, in.world - u.eye.xyz) > 0.0 {
        n = -n;
    }
    return n;
}

@fragment
fn fs_gbuffer(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(facing(in), 0.0);
}

struct Shaded {
    @location(0) color: vec4<f32>,
    @location(1) normal: vec4<f32>,
}

// Ambient plus the point light at the eye: albedo · (ambient + cos/π · I/d²).
@fragment
fn fs_shade(in: VsOut) -> Shaded {
    let n = facing(in);
    let to = u.eye.xyz - in.world;
    let d2 = dot(to, to);
    let cos = max(dot(to * inverseSqrt(d2), n), 0.0);
    let a = u.albedo[in.material].xyz;
    var o: Shaded;
    o.color = vec4<f32>(a * u.ambient.xyz + a * (0.31830988618 * cos) * u.light.xyz / d2, 1.0);
    o.normal = vec4<f32>(n, 0.0);
    return o;
}
";

/// Camera view matrix (right-handed, looking from [`EYE`] at [`TARGET`]).
pub fn view() -> Mat4 {
    let f = (TARGET - EYE).normalize();
    let s = f.cross(UP).normalize();
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(EYE), -u.dot(EYE), f.dot(EYE), 1.0),
    )
}

/// The projection: reversed Z, infinite far plane (depth 0 = nothing drawn).
pub fn projection(width: u32, height: u32) -> Mat4 {
    let f = 1.0 / (0.5 * FOV_Y).tan();
    let aspect = width as f32 / height as f32;
    Mat4::from_cols(
        Vec4::new(f / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, f, 0.0, 0.0),
        Vec4::new(0.0, 0.0, 0.0, -1.0),
        Vec4::new(0.0, 0.0, NEAR, 0.0),
    )
}

/// `projection` shifted so that the sample at each pixel centre sees the
/// image point `offset` pixels (x right, y down) away from it.
fn jittered(width: u32, height: u32, offset: Vec2) -> Mat4 {
    let shift = Mat4::from_cols(
        Vec4::X,
        Vec4::Y,
        Vec4::Z,
        Vec4::new(
            -2.0 * offset.x / width as f32,
            2.0 * offset.y / height as f32,
            0.0,
            1.0,
        ),
    );
    shift * projection(width, height)
}

/// Render the scene at `width × height` with SRAA under `params` on the
/// host's device: linear RGB, row-major.
pub fn render(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    params: SraaParams,
    width: u32,
    height: u32,
) -> Result<Vec<Vec3>, String> {
    let size = (width, height, 1);
    let tris = scene_triangles();
    let vertices: Vec<Vertex> = tris
        .iter()
        .flat_map(|t| {
            (0..3).map(move |k| Vertex {
                p: t.p[k].into(),
                material: t.material,
                n: t.n[k].into(),
                _pad: 0,
            })
        })
        .collect();
    let vbuf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("host vertices"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let shaded_offset = params.shaded_offset();
    let uniforms = |proj: Mat4| {
        let u = Uniforms {
            view_proj: (proj * view()).to_cols_array_2d(),
            eye: EYE.extend(1.0).into(),
            light: LIGHT.extend(0.0).into(),
            ambient: AMBIENT.extend(0.0).into(),
            albedo: ALBEDO.map(|a| a.extend(0.0).into()),
        };
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("host uniforms"),
            contents: bytemuck::bytes_of(&u),
            usage: wgpu::BufferUsages::UNIFORM,
        })
    };
    let geometry_u = uniforms(projection(width, height));
    let shaded_u = uniforms(jittered(width, height, shaded_offset));
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("host"),
        source: wgpu::ShaderSource::Wgsl(HOST_WGSL.into()),
    });
    let bgl = host::uniform_layout(device, wgpu::ShaderStages::VERTEX_FRAGMENT);
    let (geometry_g, shaded_g) = (
        host::uniform_group(device, &bgl, &geometry_u),
        host::uniform_group(device, &bgl, &shaded_u),
    );
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("host"),
        bind_group_layouts: &[Some(&bgl)],
        immediate_size: 0,
    });
    let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Uint32, 2 => Float32x3];
    let pipeline = |entry: &str, targets: &[Option<wgpu::ColorTargetState>], samples: u32| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(entry),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attributes,
                })],
            },
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: samples,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    };
    let target = |format| {
        Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })
    };
    use wgpu::TextureFormat::{Depth32Float, Rgba16Float, Rgba32Float};
    let gbuffer = pipeline("fs_gbuffer", &[target(Rgba16Float)], 4);
    let shade = pipeline("fs_shade", &[target(Rgba16Float), target(Rgba16Float)], 1);
    let attach = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
    let ms_depth = texture(device, "msaa depth", size, 4, Depth32Float, attach);
    let ms_normal = texture(device, "msaa normal", size, 4, Rgba16Float, attach);
    let color = texture(device, "shaded colour", size, 1, Rgba16Float, attach);
    let normal = texture(device, "shaded normal", size, 1, Rgba16Float, attach);
    let depth = texture(device, "shaded depth", size, 1, Depth32Float, attach);
    let output = texture(
        device,
        "sraa output",
        size,
        1,
        Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    );
    let centre = params.shaded_position() == ShadedPosition::Centre;
    let sraa = SraaPass::new(
        device,
        &SraaPassDesc::msaa()
            .with_params(params)
            .with_output_format(Rgba32Float),
    )
    .map_err(|e| e.to_string())?;

    let mut enc = device.create_command_encoder(&Default::default());
    let clear = |c: Vec3| wgpu::Color {
        r: c.x as f64,
        g: c.y as f64,
        b: c.z as f64,
        a: 1.0,
    };
    let views = [&ms_normal, &color, &normal].map(|t| t.create_view(&Default::default()));
    fn attachment(
        view: &wgpu::TextureView,
        c: wgpu::Color,
    ) -> Option<wgpu::RenderPassColorAttachment<'_>> {
        Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(c),
                store: wgpu::StoreOp::Store,
            },
        })
    }
    let passes = [
        (
            &gbuffer,
            &geometry_g,
            vec![attachment(&views[0], clear(Vec3::ZERO))],
            &ms_depth,
        ),
        (
            &shade,
            &shaded_g,
            vec![
                attachment(&views[1], clear(BACKGROUND)),
                attachment(&views[2], clear(Vec3::ZERO)),
            ],
            &depth,
        ),
    ];
    for (pipeline, group, attachments, depth) in &passes {
        let dview = depth.create_view(&Default::default());
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("host"),
            color_attachments: attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &dview,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, Some(*group), &[]);
        pass.set_vertex_buffer(0, vbuf.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
    // The views the pass reads: whole textures (the depth aspect of the
    // depth textures).
    let [ms_depth_v, ms_normal_v, color_v, normal_v, depth_v, output_v] =
        [&ms_depth, &ms_normal, &color, &normal, &depth, &output]
            .map(|t| t.create_view(&Default::default()));
    sraa.encode(
        device,
        queue,
        &mut enc,
        &SraaInputs {
            geometry: SubsampleGeometry::Separate {
                depth: &ms_depth_v,
                normal: &ms_normal_v,
            },
            // The centre geometry's depth went through the jittered
            // projection, whose z row is the same: one inversion serves both.
            projection: projection(width, height).to_cols_array_2d(),
            centre: centre.then_some(CentreGeometry {
                depth: &depth_v,
                normal: &normal_v,
            }),
            color: &color_v,
            shadows: None,
            albedo: None,
            secondary: None,
            output: &output_v,
        },
        None,
    )
    .map_err(|e| e.to_string())?;
    let pixels = read_rgba32f(device, queue, enc, &output)?;
    // The encoder is submitted: tell the pass, as a frame loop does after
    // each submit, so its uniform slots are free for the next frame.
    sraa.end_submission();
    Ok(pixels.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect())
}

#[allow(dead_code)]
fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let out = args.next().unwrap_or_else(|| "host_sraa.png".into());
    let params = match args.next().as_deref() {
        Some("tuned") => SraaParams::TUNED,
        _ => SraaParams::PAPER,
    };
    let (device, queue) = open_device()?;
    let (w, h) = (192, 128);
    let pixels = render(&device, &queue, params, w, h)?;
    host::save_png(&out, w, h, &pixels)
}
