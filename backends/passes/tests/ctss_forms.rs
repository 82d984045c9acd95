//! `CtssPass`'s forms beside the one-cone texture pass: `N × N` cones per
//! pixel, storage-buffer output with per-pixel counts, the host's own trace
//! (`CtssTrace::Host`), and the typed errors of each, on the host's device.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use glam::{Vec2, Vec3};
use subcone_kernels::ctss::CtssParams;
use subcone_passes::{
    CtssBuffers, CtssCamera, CtssFrame, CtssOutput, CtssPass, CtssPassDesc, CtssTrace, PassError,
};

const W: u32 = 12;
const H: u32 = 9;

/// A unit sphere 4 ahead, shaded by its normal's height; and the host's two
/// counters, constants a test can recognise.
const SPHERE: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let d = length(p - vec3<f32>(0.0, 0.0, 4.0)) - 1.0;
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.5 + 0.5 * n.y, 0.25, 1.0);
}
fn subcone_counters() -> vec2<u32> {
    return vec2<u32>(7u, 9u);
}
";

/// The host's own trace: the colour is the cone's axis, one sample of
/// three steps, so the pixel loop's rays can be read back.
const AXIS_TRACE: &str = "
fn subcone_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {
    return subcone_CtssTraceResult(dir, 1u, 3u, 0u, 0u, 0.0);
}
";

fn camera() -> CtssCamera {
    CtssCamera::new(Vec3::ZERO, Vec3::Z, Vec3::Y, 0.9)
}

fn params() -> CtssParams {
    CtssParams::new(0.01)
        .with_range(0.0, 50.0)
        .with_max_steps(128)
}

fn storage(device: &wgpu::Device, bytes: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("ctss test output"),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// Copy `buffer` into a mappable one after `enc` and read it back.
fn read<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mut enc: wgpu::CommandEncoder,
    buffer: &wgpu::Buffer,
) -> Vec<T> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("ctss test read-back"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    enc.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    queue.submit([enc.finish()]);
    bytemuck::cast_slice(&host::read_buffer(device, &staging).expect("read-back")).to_vec()
}

/// Trace `W × H` into buffers with `desc` and `host_wgsl`: colours and
/// counts.
fn trace_buffers(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    host_wgsl: &str,
    desc: &CtssPassDesc<'_>,
) -> (Vec<[f32; 4]>, Vec<[u32; 4]>) {
    let pass = CtssPass::new(device, host_wgsl, desc).expect("pass");
    let n = u64::from(W * H);
    let (output, counts) = (storage(device, n * 16), storage(device, n * 16));
    let mut enc = device.create_command_encoder(&Default::default());
    let frame = CtssBuffers {
        camera: camera().into(),
        params: params(),
        background: Vec3::new(0.0, 0.0, 0.1),
        host_group: None,
        size: (W, H),
        output: &output,
        counts: Some(&counts),
        depth: None,
        rect: None,
    };
    pass.encode_buffers(device, queue, &mut enc, &frame, None)
        .expect("encode");
    queue.submit([enc.finish()]);
    let colour = read(
        device,
        queue,
        device.create_command_encoder(&Default::default()),
        &output,
    );
    let count = read(
        device,
        queue,
        device.create_command_encoder(&Default::default()),
        &counts,
    );
    (colour, count)
}

/// The same frame as a texture (`Rgba32Float`) and as buffers gives the same
/// colours, bit for bit, and the counts say what the trace did: field
/// evaluations everywhere, one shaded group on the sphere and none beside
/// it, the host's counters in the last two lanes.
#[test]
fn buffers_hold_the_texture_image_and_the_counts() {
    let Some((device, queue)) = common::device_or_skip("ctss forms", host::open_device) else {
        return;
    };
    let desc = CtssPassDesc::default().with_output(CtssOutput::Buffers { counts: true });
    let (colour, counts) = trace_buffers(&device, &queue, SPHERE, &desc);

    let texture_desc = CtssPassDesc::default().with_output_format(wgpu::TextureFormat::Rgba32Float);
    let pass = CtssPass::new(&device, SPHERE, &texture_desc).expect("texture pass");
    let tex = host::texture(
        &device,
        "ctss out",
        (W, H, 1),
        1,
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    );
    let view = tex.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    let frame = CtssFrame {
        camera: camera().into(),
        params: params(),
        background: Vec3::new(0.0, 0.0, 0.1),
        host_group: None,
        output: &view,
        depth: None,
        rect: None,
    };
    pass.encode(&device, &queue, &mut enc, &frame, None)
        .expect("encode");
    let texels = host::read_rgba32f(&device, &queue, enc, &tex).expect("read");

    let bits = |v: &[[f32; 4]]| -> Vec<u32> { v.iter().flatten().map(|x| x.to_bits()).collect() };
    assert_eq!(bits(&colour), bits(&texels));
    let centre = ((H / 2) * W + W / 2) as usize;
    assert_eq!(
        counts[centre][1], 1,
        "the sphere's centre pixel shades one group"
    );
    assert_eq!(counts[0][1], 0, "the corner misses the sphere");
    for c in &counts {
        assert!(c[0] > 0, "every cone evaluates the field: {c:?}");
        assert_eq!([c[2], c[3]], [7, 9], "the host's counters");
    }
    assert!(colour.iter().all(|c| c[3] == 1.0));
}

/// `N × N` cones per pixel go through the sub-pixel centres
/// `(x + (i + ½)/N, y + (j + ½)/N)` of `CtssCamera::ray` and are averaged:
/// with the host's trace returning each cone's axis, the pixel is the mean
/// of those rays' directions; counts add up over the cones.
#[test]
fn samples_per_side_average_the_sub_pixel_cones() {
    let Some((device, queue)) = common::device_or_skip("ctss forms", host::open_device) else {
        return;
    };
    let host_wgsl = format!("{SPHERE}{AXIS_TRACE}");
    for side in [1u32, 2, 3] {
        let desc = CtssPassDesc::default()
            .with_output(CtssOutput::Buffers { counts: true })
            .with_trace(CtssTrace::Host)
            .with_samples_per_side(side);
        let (colour, counts) = trace_buffers(&device, &queue, &host_wgsl, &desc);
        for y in 0..H {
            for x in 0..W {
                let mut sum = Vec3::ZERO;
                for j in 0..side {
                    for i in 0..side {
                        let off = Vec2::new(
                            (i as f32 + 0.5) / side as f32,
                            (j as f32 + 0.5) / side as f32,
                        );
                        let p = Vec2::new(x as f32, y as f32) + off;
                        sum += camera().ray(p, W, H).1;
                    }
                }
                let expected = sum / (side * side) as f32;
                let i = (y * W + x) as usize;
                let got = Vec3::new(colour[i][0], colour[i][1], colour[i][2]);
                assert!(
                    (got - expected).abs().max_element() < 1e-5,
                    "side {side}, pixel ({x}, {y}): {got} against {expected}"
                );
                assert_eq!(counts[i], [3 * side * side, side * side, 7, 9]);
            }
        }
    }
}

/// Every way a frame or a desc can fail to fit is a typed error before
/// anything is recorded.
#[test]
fn forms_that_do_not_fit_are_typed_errors() {
    let Some((device, queue)) = common::device_or_skip("ctss forms", host::open_device) else {
        return;
    };
    for side in [0, subcone_passes::MAX_SAMPLES_PER_SIDE + 1] {
        let desc = CtssPassDesc::default().with_samples_per_side(side);
        assert!(matches!(
            CtssPass::new(&device, SPHERE, &desc),
            Err(PassError::Config(_))
        ));
    }
    let n = u64::from(W * H);
    let (output, counts) = (storage(&device, n * 16), storage(&device, n * 16));
    let frame = |output, counts| CtssBuffers {
        camera: camera().into(),
        params: params(),
        background: Vec3::ZERO,
        host_group: None,
        size: (W, H),
        output,
        counts,
        depth: None,
        rect: None,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    let counted = CtssPass::new(
        &device,
        SPHERE,
        &CtssPassDesc::default().with_output(CtssOutput::Buffers { counts: true }),
    )
    .expect("pass");
    let plain = CtssPass::new(
        &device,
        SPHERE,
        &CtssPassDesc::default().with_output(CtssOutput::Buffers { counts: false }),
    )
    .expect("pass");
    let texture = CtssPass::new(&device, SPHERE, &CtssPassDesc::default()).expect("pass");
    let small = storage(&device, n * 16 - 16);
    let cases: [(&CtssPass, CtssBuffers<'_>, &str); 4] = [
        (&counted, frame(&output, None), "missing counts"),
        (&plain, frame(&output, Some(&counts)), "unexpected counts"),
        (&counted, frame(&small, Some(&counts)), "small output"),
        (&texture, frame(&output, None), "a texture pass"),
    ];
    for (pass, f, what) in cases {
        let e = pass
            .encode_buffers(&device, &queue, &mut enc, &f, None)
            .expect_err(what);
        let fits = match what {
            "missing counts" => matches!(e, PassError::Missing(_)),
            "unexpected counts" => matches!(e, PassError::Unexpected(_)),
            "small output" => matches!(e, PassError::BufferSize { .. }),
            _ => matches!(e, PassError::Config(_)),
        };
        assert!(fits, "{what}: {e}");
    }
    let no_counts_usage = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("not storage"),
        size: n * 16,
        usage: wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let e = counted
        .encode_buffers(
            &device,
            &queue,
            &mut enc,
            &frame(&output, Some(&no_counts_usage)),
            None,
        )
        .expect_err("counts without STORAGE");
    assert!(matches!(e, PassError::BufferUsage { .. }), "{e}");
    // A buffer pass given a texture frame.
    let tex = host::texture(
        &device,
        "ctss out",
        (W, H, 1),
        1,
        wgpu::TextureFormat::Rgba16Float,
        wgpu::TextureUsages::STORAGE_BINDING,
    );
    let view = tex.create_view(&Default::default());
    let e = plain
        .encode(
            &device,
            &queue,
            &mut enc,
            &CtssFrame {
                camera: camera().into(),
                params: params(),
                background: Vec3::ZERO,
                host_group: None,
                output: &view,
                depth: None,
                rect: None,
            },
            None,
        )
        .expect_err("a buffer pass encodes buffers");
    assert!(matches!(e, PassError::Config(_)), "{e}");
    // Nothing was recorded: the encoder finishes empty and runs.
    queue.submit([enc.finish()]);
    host::wait(&device).expect("poll");
}
