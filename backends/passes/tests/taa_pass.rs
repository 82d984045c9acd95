//! `TaaPass` on a device:
//! - its output against the kernels' CPU resolve
//!   (`subcone_kernels::taa::resolve_pixel`) on a small frame with edges, an
//!   HDR highlight, motion and a point reprojected off the image, for the
//!   linear and the tone-mapped resolve, within 1e-4 relative (the GPU's
//!   `sqrt` and divisions may round differently);
//! - `encode_rect` on a rect of larger textures against `encode` on
//!   textures of the rect's size holding the same inputs (bit for bit), the
//!   pixels outside the rect untouched;
//! - its typed refusals: a desc outside its domain, an 8-bit output, a
//!   history that is the output.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use glam::{Vec2, Vec3};
use subcone_kernels::taa::{resolve_pixel, ResolveSpace, TaaParams, TaaSettings};
use subcone_passes::{PassError, Rect, TaaInputs, TaaPass, TaaPassDesc};

const F32: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const RG: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;

/// An input texture holding `data` (`channels` floats per pixel).
fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    (w, h): (u32, u32),
    format: wgpu::TextureFormat,
    data: &[f32],
) -> wgpu::Texture {
    let usage = wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_DST
        | wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::COPY_SRC;
    let t = host::texture(device, "taa input", (w, h, 1), 1, format, usage);
    let per = (data.len() / (w * h) as usize) as u32;
    queue.write_texture(
        t.as_image_copy(),
        bytemuck::cast_slice(data),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(w * 4 * per),
            rows_per_image: Some(h),
        },
        t.size(),
    );
    t
}

/// A frame of `w × h`: a checker with an HDR pixel, a history of another
/// checker, and velocities that move by up to two pixels (some off the
/// image).
fn frame(w: u32, h: u32) -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec2>) {
    let n = (w * h) as usize;
    let cur = (0..n)
        .map(|i| {
            let (x, y) = (i as u32 % w, i as u32 / w);
            if (x, y) == (3, 2) {
                Vec3::new(40.0, 30.0, 20.0)
            } else if (x / 2 + y) % 2 == 0 {
                Vec3::new(0.8, 0.6, 0.2)
            } else {
                Vec3::new(0.05, 0.1, 0.3)
            }
        })
        .collect();
    let hist = (0..n)
        .map(|i| {
            let (x, y) = (i as u32 % w, i as u32 / w);
            Vec3::splat(0.1 + 0.07 * ((x + 2 * y) % 5) as f32)
        })
        .collect();
    let vel = (0..n)
        .map(|i| Vec2::new((i % 5) as f32 * 0.45 - 0.9, (i % 3) as f32 * 0.7 - 0.7))
        .collect();
    (cur, hist, vel)
}

/// Views of three zero 4×4 textures: a colour, a velocity, an output.
fn tiny(device: &wgpu::Device, queue: &wgpu::Queue) -> [wgpu::TextureView; 3] {
    [(F32, 64), (RG, 32), (F32, 64)]
        .map(|(format, n)| upload(device, queue, (4, 4), format, &vec![0.0; n]))
        .map(|t| t.create_view(&Default::default()))
}

fn rgba(c: &[Vec3]) -> Vec<f32> {
    c.iter().flat_map(|v| [v.x, v.y, v.z, 1.0]).collect()
}

fn open() -> Option<(wgpu::Device, wgpu::Queue)> {
    common::device_or_skip("taa pass", host::open_device)
}

/// Run `pass` over `(cur, hist, vel)` at `size` into a fresh output (or the
/// given rect of textures of `size`), read back.
fn run(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pass: &TaaPass,
    size: (u32, u32),
    (cur, hist, vel): (&[Vec3], &[Vec3], &[Vec2]),
    rect: Option<Rect>,
) -> Vec<[f32; 4]> {
    let c = upload(device, queue, size, F32, &rgba(cur));
    let h = upload(device, queue, size, F32, &rgba(hist));
    let v: Vec<f32> = vel.iter().flat_map(|v| [v.x, v.y]).collect();
    let v = upload(device, queue, size, RG, &v);
    // The output starts as a fill the pass must leave outside the rect.
    let out = upload(
        device,
        queue,
        size,
        F32,
        &vec![-7.0; (size.0 * size.1 * 4) as usize],
    );
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    let inputs = TaaInputs {
        current: &view(&c),
        velocity: &view(&v),
        history: &view(&h),
        history_frames: 3,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    match rect {
        None => pass.encode(device, queue, &mut enc, &inputs, &view(&out), None),
        Some(r) => pass.encode_rect(device, queue, &mut enc, &inputs, &view(&out), r, None),
    }
    .expect("encode");
    host::read_rgba32f(device, queue, enc, &out).expect("read-back")
}

#[test]
fn the_pass_is_the_kernel_resolve() {
    let Some((device, queue)) = open() else {
        return;
    };
    let (w, h) = (12, 8);
    let (cur, hist, vel) = frame(w, h);
    for space in [
        ResolveSpace::Linear,
        ResolveSpace::ToneMapped { exposure: 0.5 },
    ] {
        let desc = TaaPassDesc::default()
            .with_settings(TaaSettings {
                space,
                ..TaaSettings::default()
            })
            .with_output_format(F32);
        let pass = TaaPass::new(&device, &desc).expect("pass");
        let got = run(&device, &queue, &pass, (w, h), (&cur, &hist, &vel), None);
        let params = TaaParams::new((w, h))
            .with_history_frames(3)
            .with_space(space);
        fn at(b: &[Vec3], w: u32) -> impl Fn(i32, i32) -> Vec3 + '_ {
            move |x, y| b[(y as u32 * w + x as u32) as usize]
        }
        let mut worst = 0.0f32;
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                let i = (y as u32 * w + x as u32) as usize;
                let want = resolve_pixel(&at(&cur, w), &at(&hist, w), (x, y), vel[i], &params);
                let g = Vec3::new(got[i][0], got[i][1], got[i][2]);
                let rel = ((g - want).abs() / want.abs().max(Vec3::splat(1e-3))).max_element();
                worst = worst.max(rel);
            }
        }
        eprintln!("{space:?}: worst relative difference {worst:.3e}");
        assert!(
            worst < 1e-4,
            "{space:?}: the pass differs from the kernel by {worst}"
        );
    }
}

#[test]
fn a_rect_is_the_pass_on_the_rect_alone() {
    let Some((device, queue)) = open() else {
        return;
    };
    let pass =
        TaaPass::new(&device, &TaaPassDesc::default().with_output_format(F32)).expect("pass");
    let (w, h) = (20, 14);
    let rect = Rect::new(5, 3, 9, 7);
    let (cur, hist, vel) = frame(w, h);
    let big = run(
        &device,
        &queue,
        &pass,
        (w, h),
        (&cur, &hist, &vel),
        Some(rect),
    );
    fn crop<T: Copy>(b: &[T], rect: Rect, w: u32) -> Vec<T> {
        (0..rect.height)
            .flat_map(|y| (0..rect.width).map(move |x| ((rect.y + y) * w + rect.x + x) as usize))
            .map(|i| b[i])
            .collect()
    }
    let (c, hh, v) = (
        crop(&cur, rect, w),
        crop(&hist, rect, w),
        crop(&vel, rect, w),
    );
    let small = run(
        &device,
        &queue,
        &pass,
        (rect.width, rect.height),
        (&c, &hh, &v),
        None,
    );
    for y in 0..h {
        for x in 0..w {
            let px = big[(y * w + x) as usize];
            let inside = (rect.x..rect.x + rect.width).contains(&x)
                && (rect.y..rect.y + rect.height).contains(&y);
            if inside {
                let s = small[((y - rect.y) * rect.width + x - rect.x) as usize];
                assert_eq!(px.map(f32::to_bits), s.map(f32::to_bits), "({x}, {y})");
            } else {
                assert_eq!(px, [-7.0; 4], "({x}, {y}) outside the rect was written");
            }
        }
    }
    // A rect outside the textures is refused before anything is recorded.
    let [t, v, out] = tiny(&device, &queue);
    let inputs = TaaInputs {
        current: &t,
        velocity: &v,
        history: &t,
        history_frames: 1,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    let e = pass
        .encode_rect(
            &device,
            &queue,
            &mut enc,
            &inputs,
            &out,
            Rect::new(2, 2, 3, 3),
            None,
        )
        .unwrap_err();
    assert!(matches!(e, PassError::Rect { .. }), "{e:?}");
}

#[test]
fn bad_descs_and_inputs_are_refused() {
    let Some((device, queue)) = open() else {
        return;
    };
    let d = TaaSettings::default();
    for settings in [
        TaaSettings { phases: 0, ..d },
        TaaSettings {
            min_current_weight: 0.0,
            ..d
        },
        TaaSettings {
            clip_gamma: f32::NAN,
            ..d
        },
        TaaSettings {
            space: ResolveSpace::ToneMapped { exposure: -1.0 },
            ..d
        },
    ] {
        let desc = TaaPassDesc::default().with_settings(settings);
        assert!(
            matches!(TaaPass::new(&device, &desc), Err(PassError::Config(_))),
            "{desc:?}"
        );
    }
    let eight = TaaPassDesc::default().with_output_format(wgpu::TextureFormat::Rgba8Unorm);
    assert!(matches!(
        TaaPass::new(&device, &eight),
        Err(PassError::Format { .. })
    ));
    let pass =
        TaaPass::new(&device, &TaaPassDesc::default().with_output_format(F32)).expect("pass");
    let [t, v, out] = tiny(&device, &queue);
    let inputs = TaaInputs {
        current: &t,
        velocity: &v,
        history: &out,
        history_frames: 1,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    let e = pass
        .encode(&device, &queue, &mut enc, &inputs, &out, None)
        .unwrap_err();
    assert!(matches!(e, PassError::Config(_)), "{e:?}");
    // The encoder is still good to submit.
    queue.submit([enc.finish()]);
}
