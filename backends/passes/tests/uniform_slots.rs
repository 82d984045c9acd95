//! Many encodes of one pass in one submission, each with a uniform value of
//! its own: every encode reads its own value, however many distinct values
//! the submission holds (a pass's uniform ring grows past `UNIFORM_SLOTS`
//! rather than overwrite a slot an unsubmitted encode still reads), and a
//! submission beyond `MAX_UNIFORM_SLOTS` distinct values is a typed error.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use glam::Vec3;
use subcone_kernels::ctss::CtssParams;
use subcone_passes::{
    CtssCamera, CtssFrame, CtssPass, CtssPassDesc, CtssRect, PassError, MAX_UNIFORM_SLOTS,
    UNIFORM_SLOTS,
};

/// A field of one sphere in front of the camera; the tests look away from
/// it, so every pixel is the frame's background.
const FIELD_WGSL: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let d = length(p - vec3<f32>(0.0, 0.0, 5.0)) - 1.0;
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.5) + 0.5 * n;
}
";

/// Pixels per side of one encode's region.
const CELL: u32 = 8;
/// Regions per row of the output.
const COLUMNS: u32 = 10;

/// The background of encode `i`: distinct for every `i < 256`, and exact in
/// `f32` (dyadic), so a pixel holds it bit for bit.
fn background(i: usize) -> Vec3 {
    Vec3::new(i as f32 / 256.0, 0.5, 1.0 - i as f32 / 512.0)
}

/// The rect of encode `i` in the output.
fn rect(i: usize) -> CtssRect {
    let i = i as u32;
    CtssRect {
        origin: [(i % COLUMNS) * CELL, (i / COLUMNS) * CELL],
        size: [CELL, CELL],
    }
}

/// The frame of encode `i` into `output`: its own rect and background.
fn frame(i: usize, output: &wgpu::TextureView) -> CtssFrame<'_> {
    CtssFrame {
        // Looking away from the sphere.
        camera: CtssCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 0.8).into(),
        params: CtssParams::new(0.002)
            .with_range(0.0, 100.0)
            .with_max_steps(16),
        background: background(i),
        host_group: None,
        output,
        depth: None,
        rect: Some(rect(i)),
    }
}

/// An `Rgba32Float` output with a region for each of `n` encodes (zeroed,
/// so a region no encode wrote reads 0).
fn output(device: &wgpu::Device, n: usize) -> wgpu::Texture {
    let rows = (n as u32).div_ceil(COLUMNS);
    host::texture(
        device,
        "regions",
        (COLUMNS * CELL, rows * CELL, 1),
        1,
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    )
}

/// The regions of `texels` (of `output(_, n)`) whose pixels are not all
/// their encode's background, as `(encode, a wrong pixel's colour)`.
fn wrong_regions(texels: &[[f32; 4]], n: usize) -> Vec<(usize, Vec3)> {
    let width = (COLUMNS * CELL) as usize;
    (0..n)
        .filter_map(|i| {
            let r = rect(i);
            let want = background(i);
            (0..CELL * CELL).find_map(|k| {
                let (x, y) = (r.origin[0] + k % CELL, r.origin[1] + k / CELL);
                let t = texels[y as usize * width + x as usize];
                let got = Vec3::new(t[0], t[1], t[2]);
                (got != want).then_some((i, got))
            })
        })
        .collect()
}

/// Encode `n` frames of one CTSS pass into one encoder, each with its own
/// rect and background (so its own uniform value), submit once, and return
/// the regions that do not hold their own background.
fn distinct_values_in_one_submission(n: usize) -> Option<Vec<(usize, Vec3)>> {
    let (device, queue) = common::device_or_skip("uniform slots", host::open_device)?;
    let pass = CtssPass::new(
        &device,
        FIELD_WGSL,
        &CtssPassDesc::default().with_output_format(wgpu::TextureFormat::Rgba32Float),
    )
    .expect("ctss");
    let out = output(&device, n);
    let view = out.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    for i in 0..n {
        pass.encode(&device, &queue, &mut enc, &frame(i, &view), None)
            .unwrap_or_else(|e| panic!("encode {i}: {e}"));
    }
    let texels = host::read_rgba32f(&device, &queue, enc, &out).expect("read-back");
    Some(wrong_regions(&texels, n))
}

#[test]
fn seventeen_distinct_uniform_values_in_one_submission_each_read_their_own() {
    assert_eq!(UNIFORM_SLOTS + 1, 17);
    if let Some(wrong) = distinct_values_in_one_submission(17) {
        assert!(
            wrong.is_empty(),
            "regions without their own value: {wrong:?}"
        );
    }
}

#[test]
fn one_hundred_distinct_uniform_values_in_one_submission_each_read_their_own() {
    if let Some(wrong) = distinct_values_in_one_submission(100) {
        assert!(
            wrong.is_empty(),
            "regions without their own value: {wrong:?}"
        );
    }
}

/// The bytes of the live buffers of `device`, once its work has run (so
/// `Queue::write_buffer`'s staging is freed): wgpu-hal's counter (the tests
/// enable wgpu's `counters` feature). A ring that grew holds more.
fn buffer_memory(device: &wgpu::Device) -> isize {
    host::wait(device).expect("poll");
    device.get_internal_counters().hal.buffer_memory.read()
}

/// Two submissions of `UNIFORM_SLOTS` distinct values each, the host
/// calling `end_submission` after the first and never polling in between:
/// the second reuses the first's slots (the ring did not grow: the buffers
/// hold as many bytes as before) and every region of both holds its own
/// value.
#[test]
fn end_submission_frees_the_slots_for_the_next_submission() {
    let Some((device, queue)) = common::device_or_skip("uniform slots", host::open_device) else {
        return;
    };
    let pass = CtssPass::new(
        &device,
        FIELD_WGSL,
        &CtssPassDesc::default().with_output_format(wgpu::TextureFormat::Rgba32Float),
    )
    .expect("ctss");
    let n = 2 * UNIFORM_SLOTS;
    let out = output(&device, n);
    let view = out.create_view(&Default::default());
    let before = buffer_memory(&device);
    let mut enc = device.create_command_encoder(&Default::default());
    for i in 0..UNIFORM_SLOTS {
        pass.encode(&device, &queue, &mut enc, &frame(i, &view), None)
            .expect("encode");
    }
    queue.submit([enc.finish()]);
    pass.end_submission();
    let mut enc = device.create_command_encoder(&Default::default());
    for i in UNIFORM_SLOTS..n {
        pass.encode(&device, &queue, &mut enc, &frame(i, &view), None)
            .expect("encode");
    }
    queue.submit([enc.finish()]);
    let after = buffer_memory(&device);
    assert!(
        after <= before,
        "the ring grew although the host ended the submission: {before} -> {after} bytes"
    );
    let enc = device.create_command_encoder(&Default::default());
    let texels = host::read_rgba32f(&device, &queue, enc, &out).expect("read-back");
    let wrong = wrong_regions(&texels, n);
    assert!(
        wrong.is_empty(),
        "regions without their own value: {wrong:?}"
    );
}

/// A host that never calls `end_submission` but submits and polls each
/// frame gets its slots back from the encodes' work-done callbacks: 100
/// frames of distinct values leave the ring at `UNIFORM_SLOTS` (the
/// buffers hold as many bytes after the last frame as after the first).
#[test]
fn slots_come_back_once_the_work_ran_without_end_submission() {
    let Some((device, queue)) = common::device_or_skip("uniform slots", host::open_device) else {
        return;
    };
    let pass = CtssPass::new(
        &device,
        FIELD_WGSL,
        &CtssPassDesc::default().with_output_format(wgpu::TextureFormat::Rgba32Float),
    )
    .expect("ctss");
    let out = output(&device, 100);
    let view = out.create_view(&Default::default());
    let mut first = None;
    for i in 0..100 {
        let mut enc = device.create_command_encoder(&Default::default());
        pass.encode(&device, &queue, &mut enc, &frame(i, &view), None)
            .expect("encode");
        queue.submit([enc.finish()]);
        first.get_or_insert(buffer_memory(&device));
    }
    let (first, last) = (first.unwrap_or(0), buffer_memory(&device));
    assert!(last <= first, "the ring grew: {first} -> {last} bytes");
    let enc = device.create_command_encoder(&Default::default());
    let texels = host::read_rgba32f(&device, &queue, enc, &out).expect("read-back");
    let wrong = wrong_regions(&texels, 100);
    assert!(
        wrong.is_empty(),
        "regions without their own value: {wrong:?}"
    );
}

/// `MAX_UNIFORM_SLOTS` distinct values waiting for one submission fill the
/// ring; one more is `PassError::UniformSlotsExhausted`, with a message
/// that tells the host what to do, and is not recorded. After the
/// submission and `end_submission`, the same value encodes.
#[test]
fn one_value_past_the_bound_is_a_typed_error() {
    let Some((device, queue)) = common::device_or_skip("uniform slots", host::open_device) else {
        return;
    };
    let pass = CtssPass::new(
        &device,
        FIELD_WGSL,
        &CtssPassDesc::default().with_output_format(wgpu::TextureFormat::Rgba32Float),
    )
    .expect("ctss");
    let out = output(&device, 1);
    let view = out.create_view(&Default::default());
    // Distinct values by the background alone, on one rect: the frame's
    // uniform takes a slot each, the parameters one slot in all.
    let value = |i: usize| CtssFrame {
        background: Vec3::new(i as f32, 0.0, 0.0),
        ..frame(0, &view)
    };
    let mut enc = device.create_command_encoder(&Default::default());
    for i in 0..MAX_UNIFORM_SLOTS {
        pass.encode(&device, &queue, &mut enc, &value(i), None)
            .unwrap_or_else(|e| panic!("encode {i}: {e}"));
    }
    // A value equal to one in the ring takes no slot: still fine.
    pass.encode(
        &device,
        &queue,
        &mut enc,
        &value(MAX_UNIFORM_SLOTS - 1),
        None,
    )
    .expect("an equal value");
    let refused = pass.encode(&device, &queue, &mut enc, &value(MAX_UNIFORM_SLOTS), None);
    let Err(e) = refused else {
        panic!("value {MAX_UNIFORM_SLOTS} was encoded: {refused:?}");
    };
    assert_eq!(
        e,
        PassError::UniformSlotsExhausted {
            pass: "subcone ctss",
            slots: MAX_UNIFORM_SLOTS,
        }
    );
    let message = e.to_string();
    for needle in ["submit", "end_submission", "MAX_UNIFORM_SLOTS"] {
        assert!(message.contains(needle), "{message}");
    }
    queue.submit([enc.finish()]);
    pass.end_submission();
    let mut enc = device.create_command_encoder(&Default::default());
    pass.encode(&device, &queue, &mut enc, &value(MAX_UNIFORM_SLOTS), None)
        .expect("after end_submission");
    let texels = host::read_rgba32f(&device, &queue, enc, &out).expect("read-back");
    let want = Vec3::new(MAX_UNIFORM_SLOTS as f32, 0.0, 0.0);
    assert_eq!(Vec3::new(texels[0][0], texels[0][1], texels[0][2]), want);
}
