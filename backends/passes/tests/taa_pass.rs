//! `TaaPass` on a device:
//! - its output against the kernels' CPU resolve
//!   (`subcone_kernels::taa::resolve_pixel`) on a small frame with edges, an
//!   HDR highlight, motion and a point reprojected off the image, for the
//!   linear and the tone-mapped resolve, and with closest-depth dilation
//!   (`dilated_motion`) in both depth orders, within 1e-4 relative (the
//!   GPU's `sqrt` and divisions may round differently);
//! - Bevy's motion vectors (UV units) with `motion_scale = (width, height)`
//!   and FSR2's (previous minus current) with `(−1, −1)` against the same
//!   motion in pixels;
//! - `encode_rect` on a rect of larger textures against `encode` on
//!   textures of the rect's size holding the same inputs (bit for bit), the
//!   pixels outside the rect untouched;
//! - its typed refusals: a desc outside its domain, an 8-bit output, a
//!   history that is the output.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use glam::{Vec2, Vec3};
use subcone_kernels::taa::{
    dilated_motion, resolve_pixel, DepthDilation, ResolveSpace, TaaParams, TaaSettings,
};
use subcone_passes::{PassError, Rect, TaaInputs, TaaPass, TaaPassDesc};

const F32: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const RG: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;
const R: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

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

/// A view of all of `t`.
fn view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&Default::default())
}

/// Run `pass` over `(cur, hist, vel)` at `size` into a fresh output (or the
/// given rect of textures of `size`), read back.
fn run(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pass: &TaaPass,
    size: (u32, u32),
    frame: (&[Vec3], &[Vec3], &[Vec2]),
    rect: Option<Rect>,
) -> Vec<[f32; 4]> {
    run_with(device, queue, pass, size, frame, rect, [1.0, 1.0], None)
}

/// [`run`] with the motion vectors' scale and a depth input.
#[allow(clippy::too_many_arguments)]
fn run_with(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pass: &TaaPass,
    size: (u32, u32),
    (cur, hist, vel): (&[Vec3], &[Vec3], &[Vec2]),
    rect: Option<Rect>,
    motion_scale: [f32; 2],
    depth: Option<&[f32]>,
) -> Vec<[f32; 4]> {
    let c = upload(device, queue, size, F32, &rgba(cur));
    let h = upload(device, queue, size, F32, &rgba(hist));
    let v: Vec<f32> = vel.iter().flat_map(|v| [v.x, v.y]).collect();
    let v = upload(device, queue, size, RG, &v);
    let d = depth.map(|d| view(&upload(device, queue, size, R, d)));
    // The output starts as a fill the pass must leave outside the rect.
    let out = upload(
        device,
        queue,
        size,
        F32,
        &vec![-7.0; (size.0 * size.1 * 4) as usize],
    );
    let (cv, vv, hv) = (view(&c), view(&v), view(&h));
    let mut inputs = TaaInputs::new(&cv, &vv, &hv, 3).with_motion_scale(motion_scale);
    if let Some(d) = &d {
        inputs = inputs.with_depth(d);
    }
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

fn at<T: Copy>(b: &[T], w: u32) -> impl Fn(i32, i32) -> T + '_ {
    move |x, y| b[(y as u32 * w + x as u32) as usize]
}

/// The largest relative difference of the pass's output from `want`.
fn worst(got: &[[f32; 4]], want: &[Vec3]) -> f32 {
    got.iter()
        .zip(want)
        .map(|(g, w)| {
            let g = Vec3::new(g[0], g[1], g[2]);
            ((g - *w).abs() / w.abs().max(Vec3::splat(1e-3))).max_element()
        })
        .fold(0.0, f32::max)
}

/// A depth of `w × h` with near blobs (a view depth of 2 against 10, a pixel
/// with nothing hit, +∞), in the order `dilation` reads: the near blobs are
/// the smallest for `NearestSmallest`, the largest (reversed Z) for
/// `NearestLargest`.
fn depth(w: u32, h: u32, dilation: DepthDilation) -> Vec<f32> {
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let view = if (x + 2 * y) % 7 == 0 {
                2.0 + (x % 3) as f32 * 0.25
            } else if (x, y) == (5, 5) {
                f32::INFINITY
            } else {
                10.0 - (y % 2) as f32
            };
            match dilation {
                DepthDilation::NearestLargest if view.is_finite() => 1.0 - view / 20.0,
                DepthDilation::NearestLargest => 0.0,
                _ => view,
            }
        })
        .collect()
}

/// With closest-depth dilation (both depth orders) the pass is the
/// kernels' `dilated_motion` then `resolve_pixel`, within the same 1e-4;
/// and the dilation changes the output (the test would see a pass that
/// ignored the depth).
#[test]
fn the_dilated_pass_is_the_kernel_resolve() {
    let Some((device, queue)) = open() else {
        return;
    };
    let (w, h) = (12, 8);
    let (cur, hist, vel) = frame(w, h);
    for dilation in [
        DepthDilation::NearestSmallest,
        DepthDilation::NearestLargest,
    ] {
        let desc = TaaPassDesc::default()
            .with_settings(TaaSettings {
                depth_dilation: dilation,
                ..TaaSettings::default()
            })
            .with_output_format(F32);
        let pass = TaaPass::new(&device, &desc).expect("pass");
        let d = depth(w, h, dilation);
        let got = run_with(
            &device,
            &queue,
            &pass,
            (w, h),
            (&cur, &hist, &vel),
            None,
            [1.0, 1.0],
            Some(&d),
        );
        let params = TaaParams::new((w, h))
            .with_history_frames(3)
            .with_depth_dilation(dilation);
        let want: Vec<Vec3> = (0..(w * h) as i32)
            .map(|i| {
                let (x, y) = (i % w as i32, i / w as i32);
                let v = dilated_motion(&at(&vel, w), &at(&d, w), (x, y), &params);
                resolve_pixel(&at(&cur, w), &at(&hist, w), (x, y), v, &params)
            })
            .collect();
        let own: Vec<Vec3> = (0..(w * h) as i32)
            .map(|i| {
                let (x, y) = (i % w as i32, i / w as i32);
                resolve_pixel(
                    &at(&cur, w),
                    &at(&hist, w),
                    (x, y),
                    vel[i as usize],
                    &params,
                )
            })
            .collect();
        let worst_dilated = worst(&got, &want);
        eprintln!("{dilation:?}: worst relative difference {worst_dilated:.3e}");
        assert!(
            worst_dilated < 1e-4,
            "{dilation:?}: the dilated pass differs from the kernel by {worst_dilated}"
        );
        assert!(
            worst(&got, &own) > 1e-2,
            "{dilation:?}: the dilation changed nothing"
        );
    }
}

/// An engine's motion vectors in its own convention, scaled by the pass,
/// resolve as the same motion in pixels: Bevy's (UV units, current minus
/// previous) with `motion_scale = (width, height)`, within 1e-5 relative
/// (`uv · width` rounds), and FSR2's (previous minus current, pixels) with
/// `(−1, −1)`, bit for bit.
#[test]
fn bevy_and_fsr2_motion_vectors_resolve_as_pixels() {
    let Some((device, queue)) = open() else {
        return;
    };
    let (w, h) = (12, 8);
    let (cur, hist, px) = frame(w, h);
    let pass =
        TaaPass::new(&device, &TaaPassDesc::default().with_output_format(F32)).expect("pass");
    let size = Vec2::new(w as f32, h as f32);
    let pixels = run(&device, &queue, &pass, (w, h), (&cur, &hist, &px), None);
    let go = |vel: &[Vec2], scale| {
        run_with(
            &device,
            &queue,
            &pass,
            (w, h),
            (&cur, &hist, vel),
            None,
            scale,
            None,
        )
    };
    let uv: Vec<Vec2> = px.iter().map(|v| *v / size).collect();
    let bevy = go(&uv, [w as f32, h as f32]);
    let pixels_rgb: Vec<Vec3> = pixels.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
    let d = worst(&bevy, &pixels_rgb);
    assert!(d < 1e-5, "Bevy's vectors differ from pixels by {d}");
    let unscaled = go(&uv, [1.0, 1.0]);
    assert!(
        worst(&unscaled, &pixels_rgb) > 1e-2,
        "the scale changed nothing"
    );
    let fsr2: Vec<Vec2> = px.iter().map(|v| -*v).collect();
    let got = go(&fsr2, [-1.0, -1.0]);
    assert_eq!(
        got.iter().map(|p| p.map(f32::to_bits)).collect::<Vec<_>>(),
        pixels
            .iter()
            .map(|p| p.map(f32::to_bits))
            .collect::<Vec<_>>(),
        "FSR2's vectors with scale (-1, -1)"
    );
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
    let inputs = TaaInputs::new(&t, &v, &t, 1);
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
    let inputs = TaaInputs::new(&t, &v, &out, 1);
    let mut enc = device.create_command_encoder(&Default::default());
    let e = pass
        .encode(&device, &queue, &mut enc, &inputs, &out, None)
        .unwrap_err();
    assert!(matches!(e, PassError::Config(_)), "{e:?}");
    // A depth with dilation off, and dilation without a depth, are refused;
    // so is a depth of another size.
    let d = view(&upload(&device, &queue, (4, 4), R, &[1.0; 16]));
    let with_depth = TaaInputs::new(&t, &v, &t, 1).with_depth(&d);
    let e = pass
        .encode(&device, &queue, &mut enc, &with_depth, &out, None)
        .unwrap_err();
    assert!(matches!(e, PassError::Config(_)), "{e:?}");
    let dilating = TaaPass::new(
        &device,
        &TaaPassDesc::default()
            .with_output_format(F32)
            .with_settings(TaaSettings {
                depth_dilation: DepthDilation::NearestSmallest,
                ..TaaSettings::default()
            }),
    )
    .expect("pass");
    let e = dilating
        .encode(
            &device,
            &queue,
            &mut enc,
            &TaaInputs::new(&t, &v, &t, 1),
            &out,
            None,
        )
        .unwrap_err();
    assert!(matches!(e, PassError::Config(_)), "{e:?}");
    let small = view(&upload(&device, &queue, (2, 2), R, &[1.0; 4]));
    let e = dilating
        .encode(
            &device,
            &queue,
            &mut enc,
            &TaaInputs::new(&t, &v, &t, 1).with_depth(&small),
            &out,
            None,
        )
        .unwrap_err();
    assert!(matches!(e, PassError::Size { .. }), "{e:?}");
    // The encoder is still good to submit.
    queue.submit([enc.finish()]);
}
