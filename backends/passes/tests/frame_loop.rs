//! The passes in a host's frame loop: after the first frame, `encode`
//! creates no buffer, texture, view, bind group or pipeline for views it
//! has seen (wgpu's internal resource counters, the `counters` feature,
//! stay where the first frame left them); several encodes of one pass in
//! one submission each read their own uniforms (`UNIFORM_SLOTS` distinct
//! values here, the ring as `new` makes it; `uniform_slots.rs` goes past
//! it); and each pass can be timed with the host's timestamp queries.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use glam::Vec3;
use subcone_kernels::ctss::CtssParams;
use subcone_kernels::sraa::SraaParams;
use subcone_passes::{
    CtssCamera, CtssFrame, CtssPass, CtssPassDesc, FxaaInput, FxaaPass, FxaaPassDesc, SraaInputs,
    SraaPass, SraaPassDesc, SubsampleGeometry, UNIFORM_SLOTS,
};

/// Frames encoded by the allocation tests.
const FRAMES: usize = 100;

/// A field of one sphere in front of the camera, shaded by its normal.
const FIELD_WGSL: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let d = length(p - vec3<f32>(0.0, 0.0, 5.0)) - 1.0;
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.5) + 0.5 * n;
}
";

/// Open a device as a host would, with `TIMESTAMP_QUERY` when the adapter
/// has it.
fn open_device() -> Result<(wgpu::Device, wgpu::Queue), String> {
    host::open_device_with("frame loop host", wgpu::Features::TIMESTAMP_QUERY, |_| {
        wgpu::Limits::default()
    })
}

/// The live objects of the kinds a pass could create, by name (wgpu-hal's
/// counters: created minus destroyed).
fn live_objects(device: &wgpu::Device) -> Vec<(&'static str, isize)> {
    let c = device.get_internal_counters().hal;
    vec![
        ("buffers", c.buffers.read()),
        ("textures", c.textures.read()),
        ("texture_views", c.texture_views.read()),
        ("bind_groups", c.bind_groups.read()),
        ("bind_group_layouts", c.bind_group_layouts.read()),
        ("pipeline_layouts", c.pipeline_layouts.read()),
        ("compute_pipelines", c.compute_pipelines.read()),
        ("shader_modules", c.shader_modules.read()),
        ("query_sets", c.query_sets.read()),
        ("buffer_memory", c.buffer_memory.read()),
        ("texture_memory", c.texture_memory.read()),
    ]
}

/// Print the counters after frame 1 and after the last frame, and assert
/// that none grew.
fn assert_flat(what: &str, first: &[(&str, isize)], last: &[(&str, isize)]) {
    eprintln!("{what}: live wgpu objects after frame 1 -> after frame {FRAMES}");
    for ((name, a), (_, b)) in first.iter().zip(last) {
        eprintln!("  {name:>20}: {a} -> {b}");
    }
    // The counters are compiled in (the test enables wgpu's `counters`
    // feature): a device with the passes' pipelines has some.
    let pipelines = first
        .iter()
        .find(|(n, _)| *n == "compute_pipelines")
        .map_or(0, |c| c.1);
    assert!(
        pipelines >= 3,
        "{what}: wgpu's counters read {pipelines} compute pipelines"
    );
    for ((name, a), (_, b)) in first.iter().zip(last) {
        assert!(b <= a, "{what}: {name} grew from {a} to {b}");
    }
}

/// The host's resources of one frame of all three passes: built once, the
/// views made once, as a host keeps its render targets.
struct Host {
    sraa: SraaPass,
    ctss: CtssPass,
    fxaa: FxaaPass,
    views: Vec<wgpu::TextureView>,
    projection: [[f32; 4]; 4],
}

const W: u32 = 16;
const H: u32 = 16;

impl Host {
    fn new(device: &wgpu::Device) -> Self {
        use wgpu::TextureFormat::{Depth32Float, Rgba16Float};
        let read = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
        let store = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let size = (W, H, 1);
        let t = |label, samples, format, usage| {
            host::texture(device, label, size, samples, format, usage)
                .create_view(&Default::default())
        };
        let views = vec![
            t("msaa depth", 4, Depth32Float, read),
            t("msaa normal", 4, Rgba16Float, read),
            t("shaded colour", 1, Rgba16Float, read),
            t("sraa output", 1, Rgba16Float, store),
            t("ctss output", 1, Rgba16Float, store),
            t("fxaa output", 1, Rgba16Float, store),
        ];
        Host {
            sraa: SraaPass::new(device, &SraaPassDesc::msaa().with_params(SraaParams::PAPER))
                .expect("sraa"),
            ctss: CtssPass::new(device, FIELD_WGSL, &CtssPassDesc::default()).expect("ctss"),
            // FXAA reads the SRAA output, a float texture: declared tone
            // mapped (the frame loop counts objects, not colours).
            fxaa: FxaaPass::new(
                device,
                &FxaaPassDesc::default().with_input(FxaaInput::ToneMapped),
            )
            .expect("fxaa"),
            views,
            // Reversed Z, infinite far plane, near 0.05.
            projection: [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 0.0, -1.0],
                [0.0, 0.0, 0.05, 0.0],
            ],
        }
    }

    fn camera(x: f32) -> CtssCamera {
        CtssCamera::new(Vec3::new(x, 0.0, 0.0), Vec3::Z, Vec3::Y, 0.8)
    }

    /// Encode one frame: SRAA, CTSS of a camera at `x`, FXAA of the SRAA
    /// output; `timestamps` gives each pass a (begin, end) pair of queries.
    fn encode(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        enc: &mut wgpu::CommandEncoder,
        x: f32,
        timestamps: Option<&wgpu::QuerySet>,
    ) {
        let v = &self.views;
        let writes = |pass: u32| {
            timestamps.map(|query_set| wgpu::ComputePassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: Some(2 * pass),
                end_of_pass_write_index: Some(2 * pass + 1),
            })
        };
        self.sraa
            .encode(
                device,
                queue,
                enc,
                &SraaInputs {
                    geometry: SubsampleGeometry::Separate {
                        depth: &v[0],
                        normal: &v[1],
                    },
                    projection: self.projection,
                    centre: None,
                    color: &v[2],
                    shadows: None,
                    albedo: None,
                    secondary: None,
                    output: &v[3],
                },
                writes(0),
            )
            .expect("sraa encode");
        self.ctss
            .encode(
                device,
                queue,
                enc,
                &CtssFrame {
                    camera: Self::camera(x).into(),
                    params: CtssParams::new(0.002)
                        .with_range(0.0, 100.0)
                        .with_max_steps(64),
                    background: Vec3::new(0.1, 0.2, 0.3),
                    host_group: None,
                    output: &v[4],
                    depth: None,
                    rect: None,
                },
                writes(1),
            )
            .expect("ctss encode");
        self.fxaa
            .encode(device, queue, enc, &v[3], &v[5], writes(2))
            .expect("fxaa encode");
    }
}

/// 100 frames of each pass into ONE encoder, submitted once: after frame 1
/// no live object is added (the camera is still, so no uniform is written
/// again either: an equal value reuses its slot).
#[test]
fn one_hundred_frames_in_one_encoder_create_nothing_after_the_first() {
    let Some((device, queue)) = common::device_or_skip("frame loop", open_device) else {
        return;
    };
    let h = Host::new(&device);
    let mut enc = device.create_command_encoder(&Default::default());
    h.encode(&device, &queue, &mut enc, 0.0, None);
    let first = live_objects(&device);
    for _ in 1..FRAMES {
        h.encode(&device, &queue, &mut enc, 0.0, None);
    }
    let last = live_objects(&device);
    queue.submit([enc.finish()]);
    host::wait(&device).expect("poll");
    assert_flat("one encoder, one submission", &first, &last);
}

/// A frame loop with a moving camera, one submission per frame: the uniform
/// slots are rewritten every frame (through `Queue::write_buffer`, whose
/// staging wgpu frees once the submission ran) and nothing stays behind.
#[test]
fn a_moving_camera_frame_loop_creates_nothing_after_the_first_frame() {
    let Some((device, queue)) = common::device_or_skip("frame loop", open_device) else {
        return;
    };
    let h = Host::new(&device);
    let mut first = Vec::new();
    for frame in 0..FRAMES {
        let mut enc = device.create_command_encoder(&Default::default());
        h.encode(&device, &queue, &mut enc, 0.01 * frame as f32, None);
        queue.submit([enc.finish()]);
        host::wait(&device).expect("poll");
        if frame == 0 {
            first = live_objects(&device);
        }
    }
    let last = live_objects(&device);
    assert_flat("one submission per frame, moving camera", &first, &last);
}

/// `UNIFORM_SLOTS` encodes of one pass in one submission, each with its own
/// uniform value (a background colour; the camera looks away from the
/// sphere, so every pixel is background), into their own outputs: each
/// output holds its own value, not the last one written.
#[test]
fn encodes_in_one_submission_each_read_their_own_uniforms() {
    let Some((device, queue)) = common::device_or_skip("uniform slots", open_device) else {
        return;
    };
    let format = wgpu::TextureFormat::Rgba32Float;
    let pass = CtssPass::new(
        &device,
        FIELD_WGSL,
        &CtssPassDesc::default().with_output_format(format),
    )
    .expect("ctss");
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC;
    let outputs: Vec<wgpu::Texture> = (0..UNIFORM_SLOTS)
        .map(|_| host::texture(&device, "output", (W, H, 1), 1, format, usage))
        .collect();
    let background = |i: usize| Vec3::new(i as f32 / 16.0, 0.5, 1.0 - i as f32 / 32.0);
    let row = W * 16; // 256 bytes: a multiple of COPY_BYTES_PER_ROW_ALIGNMENT.
    let frame_bytes = u64::from(row * H);
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read-back"),
        size: frame_bytes * UNIFORM_SLOTS as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut enc = device.create_command_encoder(&Default::default());
    for (i, out) in outputs.iter().enumerate() {
        let view = out.create_view(&Default::default());
        pass.encode(
            &device,
            &queue,
            &mut enc,
            &CtssFrame {
                // Looking away from the sphere.
                camera: CtssCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 0.8).into(),
                params: CtssParams::new(0.002)
                    .with_range(0.0, 100.0)
                    .with_max_steps(64),
                background: background(i),
                host_group: None,
                output: &view,
                depth: None,
                rect: None,
            },
            None,
        )
        .expect("encode");
    }
    for (i, out) in outputs.iter().enumerate() {
        enc.copy_texture_to_buffer(
            out.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &read,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: frame_bytes * i as u64,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(H),
                },
            },
            out.size(),
        );
    }
    queue.submit([enc.finish()]);
    let bytes = host::read_buffer(&device, &read).expect("read-back");
    let texels: Vec<[f32; 4]> = bytes
        .chunks_exact(16)
        .map(bytemuck::pod_read_unaligned)
        .collect();
    let per_frame = (W * H) as usize;
    for i in 0..UNIFORM_SLOTS {
        let want = background(i);
        for t in &texels[i * per_frame..(i + 1) * per_frame] {
            let got = Vec3::new(t[0], t[1], t[2]);
            assert!(
                (got - want).abs().max_element() < 1e-6,
                "encode {i}: {got} where its background is {want}"
            );
        }
    }
}

/// Each pass writes the host's timestamps when given a query set. Without
/// an adapter feature `TIMESTAMP_QUERY` (check the test's output), only
/// encoding without timestamps is exercised, which every other test does,
/// and timestamps are refused as a `PassError` (`host_errors.rs`).
#[test]
fn each_pass_writes_the_hosts_timestamps() {
    let Some((device, queue)) = common::device_or_skip("timestamps", open_device) else {
        return;
    };
    let h = Host::new(&device);
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        eprintln!("timestamps: the adapter has no TIMESTAMP_QUERY; encoding without them");
        let mut enc = device.create_command_encoder(&Default::default());
        h.encode(&device, &queue, &mut enc, 0.0, None);
        queue.submit([enc.finish()]);
        host::wait(&device).expect("poll");
        return;
    }
    let set = device.create_query_set(&wgpu::QuerySetDescriptor {
        label: Some("pass timestamps"),
        ty: wgpu::QueryType::Timestamp,
        count: 6,
    });
    let resolve = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("timestamps"),
        size: 6 * 8,
        usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("timestamps read-back"),
        size: 6 * 8,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut enc = device.create_command_encoder(&Default::default());
    h.encode(&device, &queue, &mut enc, 0.0, Some(&set));
    enc.resolve_query_set(&set, 0..6, &resolve, 0);
    enc.copy_buffer_to_buffer(&resolve, 0, &read, 0, 6 * 8);
    queue.submit([enc.finish()]);
    let bytes = host::read_buffer(&device, &read).expect("read-back");
    let ticks: Vec<u64> = bytes
        .chunks_exact(8)
        .map(bytemuck::pod_read_unaligned)
        .collect();
    let period = queue.get_timestamp_period();
    for (name, pair) in ["sraa", "ctss", "fxaa"].iter().zip(ticks.chunks(2)) {
        eprintln!(
            "timestamps: {name} {} ticks ({:.1} us)",
            pair[1].wrapping_sub(pair[0]),
            pair[1].wrapping_sub(pair[0]) as f64 * f64::from(period) / 1000.0
        );
        assert!(pair[0] > 0, "{name}: no start timestamp written");
        assert!(
            pair[1] >= pair[0],
            "{name}: end {} < start {}",
            pair[1],
            pair[0]
        );
    }
}
