//! The host examples, run on a device of the test's own (as a host opens
//! it) and compared by FLIP with subcone's CPU renderers of the same scene.

// Both examples include their shared helpers (`examples/host/mod.rs`).
#![allow(clippy::duplicate_mod)]

mod common;

#[allow(dead_code)]
#[path = "../examples/host_sraa.rs"]
mod host_sraa;

use glam::Vec2;
use subcone_kernels::sraa::SraaParams;
use subcone_scene::{Backend, Camera, Light, Material, RenderSettings, Scene, TriangleMesh};

/// Small: the tests run on 2 cores with software Vulkan.
const W: u32 = 96;
const H: u32 = 64;

/// The host's scene for the CPU backend: the same triangles, materials,
/// camera, light (a point light at the eye) and ambient.
fn cpu_scene() -> Scene {
    let mut mesh = TriangleMesh::default();
    for t in host_sraa::scene_triangles() {
        mesh.push(t.p, t.n, [Vec2::ZERO; 3], t.material);
    }
    let materials = host_sraa::ALBEDO
        .iter()
        .enumerate()
        .map(|(i, a)| Material::diffuse(&format!("m{i}"), *a))
        .collect();
    let camera = Camera::look_at(
        host_sraa::EYE,
        host_sraa::TARGET,
        host_sraa::UP,
        host_sraa::FOV_Y,
    )
    .expect("camera");
    let light = Light::Point {
        position: host_sraa::EYE,
        intensity: host_sraa::LIGHT,
    };
    let mut scene = Scene::triangles("host", mesh, materials, vec![light], camera).expect("scene");
    scene.ambient = host_sraa::AMBIENT;
    scene.background = host_sraa::BACKGROUND;
    scene
}

fn cpu_frame(scene: &Scene, method: &str) -> Vec<u8> {
    let method = method.parse().expect("method");
    let frame = subcone_cpu::CpuBackend::new()
        .render(scene, &scene.camera, &method, &RenderSettings::new(W, H))
        .expect("CPU render");
    frame.to_srgb8()
}

/// `host_sraa`: a host's 4x MSAA prepass and one shaded sample per pixel,
/// resolved by `SraaPass`, against the CPU backend's SRAA of the same
/// triangles (ray-traced subsamples and shaded samples, the kernels'
/// `Resolver`), for the paper's preset (shaded on subsample 0, so the
/// shaded geometry is MSAA sample 0) and the tuned one (shaded at the
/// centre, with the host's centre geometry). Bound: mean FLIP ≤ 0.01 (the
/// two differ only by rasterisation against ray tracing and f16 storage of
/// normals and colour); 99th percentile ≤ 0.1. And SRAA must be doing
/// something: the host's image is closer to the CPU's SRAA than to the
/// CPU's NoAA.
#[test]
fn host_sraa_matches_the_cpu_backend() {
    let Some((device, queue)) = common::device_or_skip("host_sraa", host_sraa::open_device) else {
        return;
    };
    let scene = cpu_scene();
    let noaa = cpu_frame(&scene, "noaa");
    for (params, method) in [
        (SraaParams::PAPER, "sraa-paper"),
        (SraaParams::TUNED, "sraa"),
    ] {
        let host = host_sraa::render(&device, &queue, params, W, H).expect("host render");
        let host = host_sraa::host::to_srgb8(&host);
        let cpu = cpu_frame(&scene, method);
        let (mean, p99) = common::flip(W, H, &cpu, &host);
        let (noaa_mean, _) = common::flip(W, H, &noaa, &host);
        eprintln!(
            "{method}: host vs CPU mean FLIP {mean:.5}, p99 {p99:.4}; host vs CPU NoAA {noaa_mean:.5}"
        );
        if mean > 0.01 || p99 > 0.1 {
            let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
            for (name, px) in [("host", &host), ("cpu", &cpu)] {
                let path = dir.join(format!("host_sraa_{method}_{name}.png"));
                let _ = image::save_buffer(&path, px, W, H, image::ExtendedColorType::Rgb8);
            }
        }
        assert!(mean <= 0.01, "{method}: mean FLIP {mean} > 0.01");
        assert!(p99 <= 0.1, "{method}: 99th percentile FLIP {p99} > 0.1");
        assert!(
            noaa_mean > mean,
            "{method}: the host's SRAA is as close to NoAA ({noaa_mean}) as to SRAA ({mean})"
        );
    }
}

#[allow(dead_code)]
#[path = "../examples/host_ctss.rs"]
mod host_ctss;

/// `host_ctss`: `CtssPass` with the host's WGSL field against the kernels'
/// `trace_field` of the same field written in Rust, pixel by pixel (the
/// same cones, parameters and shading). Bound: mean FLIP ≤ 0.01 (the two
/// differ by the GPU's `length`, `sqrt` and `exp` against libm's, a few
/// ulps that can move a step); 99th percentile ≤ 0.05. Most pixels are
/// surfaces (the image is not trivially the background).
#[test]
fn host_ctss_matches_the_cpu_trace() {
    let Some((device, queue)) = common::device_or_skip("host_ctss", host_ctss::open_device) else {
        return;
    };
    let gpu = host_ctss::render_gpu(&device, &queue, W, H).expect("GPU render");
    let cpu = host_ctss::render_cpu(W, H);
    let surface = gpu
        .iter()
        .filter(|c| (**c - host_ctss::BACKGROUND).abs().max_element() > 1e-3)
        .count();
    assert!(
        surface > gpu.len() / 2,
        "{surface} of {} pixels show a surface",
        gpu.len()
    );
    let (g8, c8) = (host_ctss::to_srgb8(&gpu), host_ctss::to_srgb8(&cpu));
    let (mean, p99) = common::flip(W, H, &c8, &g8);
    let worst = gpu
        .iter()
        .zip(&cpu)
        .map(|(g, c)| (*g - *c).abs().max_element())
        .fold(0.0f32, f32::max);
    eprintln!(
        "ctss: GPU vs CPU mean FLIP {mean:.6}, p99 {p99:.5}, largest channel difference {worst:e}"
    );
    assert!(mean <= 0.01, "mean FLIP {mean} > 0.01");
    assert!(p99 <= 0.05, "99th percentile FLIP {p99} > 0.05");
}

/// `FxaaPass` on a host texture against the CPU backend's FXAA
/// (`subcone_cpu::post::fxaa`, the same kernel in Rust) of the same frame:
/// the CPU's NoAA frame of the host scene. Bound: mean FLIP ≤ 0.01 and no
/// channel off by more than 2/255 in sRGB (the kernel quantises to 8 bits:
/// the GPU's `pow` may round a value across a step). FXAA must change the
/// frame (edges are blended).
#[test]
fn fxaa_pass_matches_the_cpu_post_process() {
    use subcone_passes::{FxaaInput, FxaaPass, FxaaPassDesc};
    let Some((device, queue)) = common::device_or_skip("fxaa pass", host_sraa::open_device) else {
        return;
    };
    let scene = cpu_scene();
    let method = "noaa".parse().expect("method");
    let frame = subcone_cpu::CpuBackend::new()
        .render(&scene, &scene.camera, &method, &RenderSettings::new(W, H))
        .expect("CPU render");
    let mut cpu = frame.clone();
    subcone_cpu::post::fxaa(&mut cpu, &subcone_kernels::fxaa::FxaaParams::QUALITY);
    let format = wgpu::TextureFormat::Rgba32Float;
    let texture =
        |label, usage| host_sraa::host::texture(&device, label, (W, H, 1), 1, format, usage);
    let input = texture(
        "fxaa input",
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let output = texture(
        "fxaa output",
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    );
    let texels: Vec<[f32; 4]> = frame.color.iter().map(|c| c.extend(1.0).into()).collect();
    queue.write_texture(
        input.as_image_copy(),
        bytemuck::cast_slice(&texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(W * 16),
            rows_per_image: Some(H),
        },
        input.size(),
    );
    // The CPU's NoAA frame in a float texture: display-referred colour
    // (the kernel clamps it to [0, 1], as the CPU's post-process does).
    let desc = FxaaPassDesc::default()
        .with_output_format(format)
        .with_input(FxaaInput::ToneMapped);
    let pass = FxaaPass::new(&device, &desc).expect("pass");
    let mut enc = device.create_command_encoder(&Default::default());
    let (input_view, output_view) = (
        input.create_view(&Default::default()),
        output.create_view(&Default::default()),
    );
    pass.encode(&device, &queue, &mut enc, &input_view, &output_view, None)
        .expect("encode");
    let gpu = host_sraa::read_rgba32f(&device, &queue, enc, &output).expect("read-back");
    let gpu: Vec<glam::Vec3> = gpu
        .iter()
        .map(|p| glam::Vec3::new(p[0], p[1], p[2]))
        .collect();
    let (g8, c8) = (host_sraa::host::to_srgb8(&gpu), cpu.to_srgb8());
    let (mean, p99) = common::flip(W, H, &c8, &g8);
    let worst = g8
        .iter()
        .zip(&c8)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    // Pixels FXAA blended (beyond its 8-bit quantisation).
    let changed = frame
        .to_srgb8()
        .chunks(3)
        .zip(c8.chunks(3))
        .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 4))
        .count();
    eprintln!("fxaa: GPU vs CPU mean FLIP {mean:.6}, p99 {p99:.5}, worst {worst}/255; {changed} pixels filtered");
    assert!(changed > 20, "FXAA changed only {changed} pixels");
    assert!(mean <= 0.01, "mean FLIP {mean} > 0.01");
    assert!(worst <= 2, "a channel differs by {worst}/255");
}
