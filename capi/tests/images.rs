//! The whole-image functions a C host checks its FXAA and TAA shaders
//! against (`subcone_fxaa_image`, `subcone_taa_resolve`):
//! - bit for bit the Rust CPU implementations: the CPU backend's FXAA
//!   post-process (`subcone_cpu::post::fxaa`) and the TAA resolve every
//!   backend is checked against (`subcone_scene::history::resolve`), on a
//!   frame with edges, an HDR highlight, NaN, motion and points reprojected
//!   off the image;
//! - their refusals: null pointers, sizes and lengths that disagree,
//!   non-finite parameters, each leaving the output untouched.

use glam::{Vec2, Vec3};
use subcone_capi::*;
use subcone_kernels::fxaa::FxaaParams;
use subcone_kernels::taa::{ResolveSpace, TaaParams};
use subcone_scene::history::{resolve, TaaInput};
use subcone_scene::Frame;

const W: u32 = 23;
const H: u32 = 17;

/// A frame with edges at several slopes, an HDR pixel and a NaN.
fn colours(w: u32, h: u32, phase: u32) -> Vec<Vec3> {
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            if (x, y) == (5, 4) {
                Vec3::new(40.0, 30.0, 20.0)
            } else if (x, y) == (9, 9) {
                Vec3::new(f32::NAN, 0.5, 0.5)
            } else if (2 * x + y + phase) % 11 < 5 {
                Vec3::new(0.9, 0.7, 0.3)
            } else {
                Vec3::new(0.05, 0.1, 0.2 + 0.01 * (x % 3) as f32)
            }
        })
        .collect()
}

fn rgba(c: &[Vec3]) -> Vec<f32> {
    c.iter().flat_map(|v| [v.x, v.y, v.z, 1.0]).collect()
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn fxaa_image_is_the_cpu_backends_post_process() {
    let src = colours(W, H, 0);
    let mut frame = Frame::new(W, H);
    frame.color = src.clone();
    subcone_cpu::post::fxaa(&mut frame, &FxaaParams::QUALITY);
    let mut params = SubconeFxaaParams::default();
    assert_eq!(
        unsafe { subcone_fxaa_params_quality(&mut params) },
        SubconeStatus::Ok
    );
    let input = rgba(&src);
    let mut out = vec![0.0f32; input.len()];
    let s = unsafe {
        subcone_fxaa_image(
            &params,
            W,
            H,
            input.as_ptr(),
            input.len(),
            out.as_mut_ptr(),
            out.len(),
        )
    };
    assert_eq!(s, SubconeStatus::Ok);
    assert_eq!(bits(&out), bits(&rgba(&frame.color)));
    // FXAA changed the frame: the test compares filtering, not copies.
    let changed = frame
        .color
        .iter()
        .zip(&src)
        .filter(|(a, b)| (**a - b.clamp(Vec3::ZERO, Vec3::ONE)).abs().max_element() > 0.01)
        .count();
    assert!(changed > 10, "FXAA changed {changed} pixels");
}

#[test]
fn taa_resolve_is_the_scenes_cpu_resolve() {
    let (current, history) = (colours(W, H, 0), colours(W, H, 3));
    let velocity: Vec<Vec2> = (0..W * H)
        .map(|i| Vec2::new((i % 5) as f32 * 0.9 - 1.8, (i % 3) as f32 * 1.4 - 1.4))
        .collect();
    for (exposure, frames) in [(0.0, 3), (0.5, 3), (0.5, 0)] {
        let mut params = SubconeTaaParams::default();
        assert_eq!(
            unsafe { subcone_taa_params(W, H, frames, exposure, &mut params) },
            SubconeStatus::Ok
        );
        let space = if exposure > 0.0 {
            ResolveSpace::ToneMapped { exposure }
        } else {
            ResolveSpace::Linear
        };
        let want = resolve(&TaaInput {
            params: TaaParams::new((W, H))
                .with_space(space)
                .with_history_frames(frames),
            current: &current,
            velocity: &velocity,
            depth: None,
            history: &history,
        })
        .expect("resolve");
        let (c, h) = (rgba(&current), rgba(&history));
        let v: Vec<f32> = velocity.iter().flat_map(|v| [v.x, v.y]).collect();
        // No history after a reset: it may be passed empty.
        let (h_ptr, h_len) = if frames == 0 {
            (std::ptr::null(), 0)
        } else {
            (h.as_ptr(), h.len())
        };
        let mut out = vec![0.0f32; c.len()];
        let s = unsafe {
            subcone_taa_resolve(
                &params,
                c.as_ptr(),
                c.len(),
                v.as_ptr(),
                v.len(),
                h_ptr,
                h_len,
                out.as_mut_ptr(),
                out.len(),
            )
        };
        assert_eq!(s, SubconeStatus::Ok, "exposure {exposure}, {frames} frames");
        assert_eq!(
            bits(&out),
            bits(&rgba(&want)),
            "exposure {exposure}, {frames} frames"
        );
    }
}

/// One `subcone_fxaa_image` call, given the output pointer.
type FxaaCall<'a> = Box<dyn Fn(*mut f32) -> SubconeStatus + 'a>;

#[test]
fn the_image_functions_refuse_bad_input_and_leave_the_output() {
    let mut fxaa = SubconeFxaaParams::default();
    unsafe { subcone_fxaa_params_quality(&mut fxaa) };
    let input = vec![0.5f32; (4 * W * H) as usize];
    let sentinel = -3.0f32;
    let mut out = vec![sentinel; input.len()];
    let n = input.len();
    let nan_params = SubconeFxaaParams {
        edge_threshold: f32::NAN,
        ..fxaa
    };
    let cases: [(&str, SubconeStatus, FxaaCall); 6] = [
        (
            "null params",
            SubconeStatus::NullPointer,
            Box::new(|o| unsafe {
                subcone_fxaa_image(std::ptr::null(), W, H, input.as_ptr(), n, o, n)
            }),
        ),
        (
            "null source",
            SubconeStatus::NullPointer,
            Box::new(|o| unsafe { subcone_fxaa_image(&fxaa, W, H, std::ptr::null(), n, o, n) }),
        ),
        (
            "zero width",
            SubconeStatus::SizeMismatch,
            Box::new(|o| unsafe { subcone_fxaa_image(&fxaa, 0, H, input.as_ptr(), n, o, n) }),
        ),
        (
            "short source",
            SubconeStatus::SizeMismatch,
            Box::new(|o| unsafe { subcone_fxaa_image(&fxaa, W, H, input.as_ptr(), n - 1, o, n) }),
        ),
        (
            "NaN threshold",
            SubconeStatus::InvalidArgument,
            Box::new(|o| unsafe { subcone_fxaa_image(&nan_params, W, H, input.as_ptr(), n, o, n) }),
        ),
        (
            "overflowing size",
            SubconeStatus::SizeMismatch,
            Box::new(|o| unsafe {
                subcone_fxaa_image(&fxaa, u32::MAX, u32::MAX, input.as_ptr(), n, o, n)
            }),
        ),
    ];
    for (what, want, call) in &cases {
        assert_eq!(call(out.as_mut_ptr()), *want, "fxaa: {what}");
        assert!(out.iter().all(|&v| v == sentinel), "fxaa: {what} wrote");
    }
    let null_out =
        unsafe { subcone_fxaa_image(&fxaa, W, H, input.as_ptr(), n, std::ptr::null_mut(), n) };
    assert_eq!(null_out, SubconeStatus::NullPointer);

    let mut taa = SubconeTaaParams::default();
    unsafe { subcone_taa_params(W, H, 2, 0.0, &mut taa) };
    let velocity = vec![0.0f32; (2 * W * H) as usize];
    let run = |p: &SubconeTaaParams,
               history: *const f32,
               history_len: usize,
               v_len: usize,
               o: *mut f32| unsafe {
        subcone_taa_resolve(
            p,
            input.as_ptr(),
            n,
            velocity.as_ptr(),
            v_len,
            history,
            history_len,
            o,
            n,
        )
    };
    let vn = velocity.len();
    let nan_gamma = SubconeTaaParams {
        clip_gamma: f32::INFINITY,
        ..taa
    };
    let zero = SubconeTaaParams { height: 0, ..taa };
    let nan_scale = SubconeTaaParams {
        motion_scale: [1.0, f32::NAN],
        ..taa
    };
    let needs_depth = SubconeTaaParams {
        depth_dilation: 1,
        ..taa
    };
    for (what, want, s) in [
        // The history is read (two frames): it must be there.
        (
            "history missing",
            SubconeStatus::SizeMismatch,
            run(&taa, std::ptr::null(), 0, vn, out.as_mut_ptr()),
        ),
        (
            "null history",
            SubconeStatus::NullPointer,
            run(&taa, std::ptr::null(), n, vn, out.as_mut_ptr()),
        ),
        (
            "short velocity",
            SubconeStatus::SizeMismatch,
            run(&taa, input.as_ptr(), n, vn - 2, out.as_mut_ptr()),
        ),
        (
            "infinite gamma",
            SubconeStatus::InvalidArgument,
            run(&nan_gamma, input.as_ptr(), n, vn, out.as_mut_ptr()),
        ),
        (
            "zero height",
            SubconeStatus::SizeMismatch,
            run(&zero, input.as_ptr(), n, vn, out.as_mut_ptr()),
        ),
        (
            "NaN motion scale",
            SubconeStatus::InvalidArgument,
            run(&nan_scale, input.as_ptr(), n, vn, out.as_mut_ptr()),
        ),
        (
            "depth dilation without a depth",
            SubconeStatus::InvalidArgument,
            run(&needs_depth, input.as_ptr(), n, vn, out.as_mut_ptr()),
        ),
    ] {
        assert_eq!(s, want, "taa: {what}");
        assert!(out.iter().all(|&v| v == sentinel), "taa: {what} wrote");
    }
    assert_eq!(
        run(&taa, input.as_ptr(), n, vn, std::ptr::null_mut()),
        SubconeStatus::NullPointer
    );
}
