//! A host that cone-traces its own signed distance field with `CtssPass`.
//!
//! The field (a sphere, a box and a floor, each its own object) is written
//! twice, once as a Rust closure for the CPU ([`field`], run through
//! `subcone_kernels::ctss::trace_field`) and once as WGSL for the GPU
//! ([`HOST_WGSL`], the hooks `subcone_field` and `subcone_shade`; the normal
//! is the pass's default, tetrahedral differences of the field, as the
//! CPU's `ConeField::normal`). Both trace the same cones (CTSS eq. 3 at the
//! default coverage) with the same parameters.
//!
//! `cargo run -p subcone-passes --example host_ctss [out.png]` writes the
//! GPU image. The test `tests/host_examples.rs` compares [`render_gpu`] with
//! [`render_cpu`] by FLIP.

use glam::{Vec2, Vec3, Vec4};
use subcone_kernels::cone::{cone_tan_theta, PixelFootprint};
use subcone_kernels::ctss::{
    cross_section_frame, trace_field, ConeField, CtssParams, FieldSample, SplitRay, CONE_COVERAGE,
};
use subcone_passes::{CtssCamera, CtssFrame, CtssPass, CtssPassDesc};
use wgpu::util::DeviceExt;

// Device, texture, read-back and sRGB helpers shared with the other host
// example and the tests.
#[path = "host/mod.rs"]
pub mod host;
pub use host::{open_device, to_srgb8};

/// Colour of the part of a pixel no surface covers.
pub const BACKGROUND: Vec3 = Vec3::new(0.05, 0.06, 0.09);

/// The host's field in WGSL: `subcone_field` (distance, step, object) and
/// `subcone_shade`, the twins of [`field`] and [`shade`]. The light
/// direction comes from the host's own bind group (`@group(1)`).
pub const HOST_WGSL: &str = "
@group(1) @binding(0) var<uniform> host_light: vec4<f32>;

fn host_box(p: vec3<f32>, b: vec3<f32>) -> f32 {
    let q = abs(p) - b;
    return length(max(q, vec3<f32>(0.0))) + min(max(q.x, max(q.y, q.z)), 0.0);
}

fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let sphere = length(p - vec3<f32>(-0.6, 0.0, 0.0)) - 0.6;
    let cube = host_box(p - vec3<f32>(0.7, -0.1, -0.4), vec3<f32>(0.45, 0.5, 0.45));
    let floor = p.y + 0.6;
    var r = vec3<f32>(sphere, sphere, 0.0);
    if cube < r.x {
        r = vec3<f32>(cube, cube, 1.0);
    }
    if floor < r.x {
        r = vec3<f32>(floor, floor, 2.0);
    }
    return r;
}

fn host_albedo(object: f32) -> vec3<f32> {
    if object < 0.5 {
        return vec3<f32>(0.85, 0.3, 0.2);
    }
    if object < 1.5 {
        return vec3<f32>(0.25, 0.6, 0.85);
    }
    return vec3<f32>(0.7, 0.7, 0.65);
}

fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let a = host_albedo(subcone_field(p).z);
    return a * (0.15 + 0.85 * max(dot(n, host_light.xyz), 0.0));
}
";

/// Unit direction towards the light.
pub fn light() -> Vec3 {
    Vec3::new(0.4, 0.8, 0.5).normalize()
}

fn host_box(p: Vec3, b: Vec3) -> f32 {
    let q = p.abs() - b;
    q.max(Vec3::ZERO).length() + q.x.max(q.y.max(q.z)).min(0.0)
}

/// The field in Rust: (distance, object), the twin of `subcone_field`.
pub fn field(p: Vec3) -> (f32, u32) {
    let sphere = (p - Vec3::new(-0.6, 0.0, 0.0)).length() - 0.6;
    let cube = host_box(p - Vec3::new(0.7, -0.1, -0.4), Vec3::new(0.45, 0.5, 0.45));
    let floor = p.y + 0.6;
    let mut r = (sphere, 0);
    if cube < r.0 {
        r = (cube, 1);
    }
    if floor < r.0 {
        r = (floor, 2);
    }
    r
}

/// The shading in Rust, the twin of `subcone_shade`.
pub fn shade(p: Vec3, n: Vec3) -> Vec3 {
    let a = match field(p).1 {
        0 => Vec3::new(0.85, 0.3, 0.2),
        1 => Vec3::new(0.25, 0.6, 0.85),
        _ => Vec3::new(0.7, 0.7, 0.65),
    };
    a * (0.15 + 0.85 * n.dot(light()).max(0.0))
}

struct Field;

impl ConeField for Field {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        let (d, object) = field(p);
        FieldSample {
            distance: d,
            step: d,
            object,
        }
    }
}

/// The camera.
pub fn camera() -> CtssCamera {
    let eye = Vec3::new(0.3, 0.9, 3.2);
    CtssCamera::new(eye, Vec3::new(0.0, -0.1, 0.0) - eye, Vec3::Y, 0.9)
}

/// The trace's parameters at `height` pixels: subcone's default cone
/// (CTSS eq. 3 at `CONE_COVERAGE`), 20 units, 300 steps.
pub fn params(height: u32) -> CtssParams {
    let tan = cone_tan_theta(
        camera().fov_y,
        height,
        CONE_COVERAGE,
        PixelFootprint::Circumscribed,
    );
    CtssParams::new(tan)
        .with_range(0.0, 20.0)
        .with_max_steps(300)
}

/// The CPU image: `trace_field` of [`field`] per pixel, linear RGB.
pub fn render_cpu(width: u32, height: u32) -> Vec<Vec3> {
    let (cam, params) = (camera(), params(height));
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (origin, dir) = cam.ray(p, width, height);
            let (right, up) = cross_section_frame(dir, cam.up);
            let ray = SplitRay {
                origin,
                dir,
                right,
                up,
            };
            let r = trace_field(&params, &ray, &mut Field, |p, n, _| shade(p, n), BACKGROUND);
            out.push(r.color);
        }
    }
    out
}

/// The GPU image: `CtssPass` with [`HOST_WGSL`] on the host's device,
/// linear RGB.
pub fn render_gpu(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    width: u32,
    height: u32,
) -> Result<Vec<Vec3>, String> {
    // The host's own bind group: the light direction.
    let host_layout = host::uniform_layout(device, wgpu::ShaderStages::COMPUTE);
    let light_buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("host light"),
        contents: bytemuck::bytes_of(&light().extend(0.0)),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let host_group = host::uniform_group(device, &host_layout, &light_buf);
    let format = wgpu::TextureFormat::Rgba32Float;
    let pass = CtssPass::new(
        device,
        HOST_WGSL,
        &CtssPassDesc::default()
            .with_batch(8)
            .with_output_format(format)
            .with_host_layout(&host_layout),
    )
    .map_err(|e| e.to_string())?;
    let output = host::texture(
        device,
        "ctss output",
        (width, height, 1),
        1,
        format,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    );
    let output_view = output.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    pass.encode(
        device,
        queue,
        &mut enc,
        &CtssFrame {
            camera: camera().into(),
            params: params(height),
            background: BACKGROUND,
            host_group: Some(&host_group),
            output: &output_view,
            depth: None,
            rect: None,
        },
        None,
    )
    .map_err(|e| e.to_string())?;
    let pixels = host::read_rgba32f(device, queue, enc, &output)?;
    // The encoder is submitted: tell the pass, as a frame loop does after
    // each submit, so its uniform slots are free for the next frame.
    pass.end_submission();
    Ok(pixels
        .iter()
        .map(|p| Vec4::from_array(*p).truncate())
        .collect())
}

#[allow(dead_code)]
fn main() -> Result<(), String> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "host_ctss.png".into());
    let (device, queue) = open_device()?;
    let (w, h) = (192, 128);
    let pixels = render_gpu(&device, &queue, w, h)?;
    host::save_png(&out, w, h, &pixels)
}
