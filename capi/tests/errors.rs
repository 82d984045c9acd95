//! The C ABI's error reporting: `subcone_last_error_message` after a
//! failure (a valid C string naming the function, the parameter and its
//! value), after a success (empty, never null), per thread; and the size
//! check of `SubconeSraaFrame` (`SubconeStatus::StructSize`, a message
//! naming the struct and both sizes, a short struct refused without being
//! read past its `size`).

use std::ffi::CStr;
use std::ptr::{null, null_mut};

use subcone_capi::*;

/// The calling thread's last error message, checked to be a valid,
/// NUL-terminated UTF-8 string.
fn last_error() -> String {
    let p = subcone_last_error_message();
    assert!(!p.is_null(), "subcone_last_error_message returned NULL");
    // SAFETY: the library returns a NUL-terminated string it owns, valid
    // until the next call into it on this thread.
    let m = unsafe { CStr::from_ptr(p) };
    m.to_str()
        .expect("the last error message is UTF-8")
        .to_string()
}

/// A 2×1 frame of one layer and its output, all valid.
struct Frame2x1 {
    colors: [SubconeVec3; 2],
    geometry: [SubconeGeometry; 2],
    subsamples: [SubconeGeometry; 8],
}

impl Frame2x1 {
    fn new() -> Self {
        let g = SubconeGeometry {
            normal: SubconeVec3 {
                x: 0.0,
                y: 0.0,
                z: 1.0,
            },
            depth: 2.0,
        };
        let c = SubconeVec3 {
            x: 0.5,
            y: 0.25,
            z: 0.125,
        };
        Frame2x1 {
            colors: [c; 2],
            geometry: [g; 2],
            subsamples: [g; 8],
        }
    }

    fn frame(&self) -> SubconeSraaFrame {
        SubconeSraaFrame {
            width: 2,
            height: 1,
            layers: 1,
            colors: self.colors.as_ptr(),
            colors_len: 2,
            shaded_geometry: self.geometry.as_ptr(),
            shaded_geometry_len: 2,
            subsample_geometry: self.subsamples.as_ptr(),
            subsample_geometry_len: 8,
            ..SubconeSraaFrame::default()
        }
    }
}

fn paper() -> SubconeSraaParams {
    let mut p = SubconeSraaParams::default();
    assert_eq!(
        unsafe { subcone_sraa_params_paper(&mut p) },
        SubconeStatus::Ok
    );
    p
}

#[test]
fn the_default_frame_has_its_size() {
    assert_eq!(
        SubconeSraaFrame::default().size as usize,
        size_of::<SubconeSraaFrame>()
    );
    assert_eq!(std::mem::offset_of!(SubconeSraaFrame, size), 0);
}

#[test]
fn a_frame_of_the_right_size_resolves() {
    let data = Frame2x1::new();
    let frame = data.frame();
    let mut out = [SubconeVec3::default(); 2];
    let s = unsafe { subcone_sraa_resolve(&paper(), &frame, out.as_mut_ptr(), 2) };
    assert_eq!(s, SubconeStatus::Ok, "{}", last_error());
    assert_eq!(last_error(), "");
}

#[test]
fn a_wrong_frame_size_is_refused_with_its_own_code_and_message() {
    let data = Frame2x1::new();
    let want = size_of::<SubconeSraaFrame>();
    for size in [0, 1, want as u32 - 8, want as u32 + 8, u32::MAX] {
        let frame = SubconeSraaFrame {
            size,
            ..data.frame()
        };
        let sentinel = SubconeVec3 {
            x: -1.0,
            y: -2.0,
            z: -3.0,
        };
        let mut out = [sentinel; 2];
        let s = unsafe { subcone_sraa_resolve(&paper(), &frame, out.as_mut_ptr(), 2) };
        assert_eq!(s, SubconeStatus::StructSize, "size {size}");
        assert_eq!(out, [sentinel; 2], "size {size}: wrote on an error");
        let m = last_error();
        assert!(
            m.starts_with("subcone_sraa_resolve: frame->size"),
            "size {size}: {m}"
        );
        assert!(m.contains("SubconeSraaFrame"), "size {size}: {m}");
        assert!(
            m.contains(&format!("is {size}")) && m.contains(&format!("is {want}")),
            "size {size}: the message names both sizes: {m}"
        );
    }
}

/// A host of an older header may pass a smaller struct: only its leading
/// `size` is read before the refusal (Miri or AddressSanitizer would see a
/// read past this 4-byte allocation).
#[test]
fn a_short_struct_is_refused_from_its_size_alone() {
    let short = Box::new(16u32);
    let frame = (&*short as *const u32).cast::<SubconeSraaFrame>();
    let mut out = [SubconeVec3::default(); 2];
    let s = unsafe { subcone_sraa_resolve(&paper(), frame, out.as_mut_ptr(), 2) };
    assert_eq!(s, SubconeStatus::StructSize);
    assert!(
        last_error().contains("frame->size is 16"),
        "{}",
        last_error()
    );
}

#[test]
fn the_struct_size_is_checked_after_the_params_and_before_the_frame() {
    let data = Frame2x1::new();
    let bad_size = SubconeSraaFrame {
        size: 3,
        width: 0,
        ..data.frame()
    };
    let mut out = [SubconeVec3::default(); 2];
    // A null `params` is reported first.
    let s = unsafe { subcone_sraa_resolve(null(), &bad_size, out.as_mut_ptr(), 2) };
    assert_eq!(s, SubconeStatus::NullPointer);
    assert_eq!(last_error(), "subcone_sraa_resolve: params is NULL");
    // The size before the zero width it would misread.
    let s = unsafe { subcone_sraa_resolve(&paper(), &bad_size, out.as_mut_ptr(), 2) };
    assert_eq!(s, SubconeStatus::StructSize);
}

#[test]
fn the_message_is_empty_before_any_call_and_after_a_success() {
    std::thread::spawn(|| {
        assert_eq!(last_error(), "", "a new thread has no error");
        let mut w = 0.0f32;
        let s = unsafe { subcone_cone_radius(2.0, 0.5, &mut w) };
        assert_eq!(s, SubconeStatus::Ok);
        assert_eq!(last_error(), "");
        let s = unsafe { subcone_cone_radius(2.0, 0.5, null_mut()) };
        assert_eq!(s, SubconeStatus::NullPointer);
        assert_eq!(last_error(), "subcone_cone_radius: out is NULL");
        // Reading it does not change it, and neither does subcone_version.
        let p = subcone_last_error_message();
        let _ = subcone_version();
        assert_eq!(p, subcone_last_error_message());
        assert_eq!(last_error(), "subcone_cone_radius: out is NULL");
        // The next success clears it.
        let s = unsafe { subcone_cone_radius(2.0, 0.5, &mut w) };
        assert_eq!(s, SubconeStatus::Ok);
        assert_eq!(last_error(), "");
    })
    .join()
    .unwrap();
}

#[test]
fn each_thread_has_its_own_message() {
    let mut w = 0.0f32;
    let s = unsafe { subcone_sample_weight(1, 7, 0.0, &mut w) };
    assert_eq!(s, SubconeStatus::InvalidArgument);
    let here = last_error();
    assert!(here.contains("weighting is 7"), "{here}");
    std::thread::spawn(|| {
        assert_eq!(last_error(), "");
        let mut t = 0.0f32;
        let s = unsafe { subcone_cone_tan_theta(0.8, 720, 1.0, 9, &mut t) };
        assert_eq!(s, SubconeStatus::InvalidArgument);
        assert!(last_error().contains("footprint is 9"), "{}", last_error());
    })
    .join()
    .unwrap();
    assert_eq!(last_error(), here);
}

/// Every kind of refusal, each with the parts its message must name.
#[test]
fn every_refusal_names_the_function_and_what_was_wrong() {
    let params = paper();
    let data = &Frame2x1::new();
    let g = data.geometry[0];
    let mut f = 0.0f32;
    let mut u = 0u32;
    let mut out = [SubconeVec3::default(); 2];
    let mut nan_params = params;
    nan_params.sigma_n = f32::NAN;
    let mut ctss = SubconeCtssParams::default();
    assert_eq!(
        unsafe { subcone_ctss_params_default(0.001, &mut ctss) },
        SubconeStatus::Ok
    );
    let bad_k = SubconeCtssParams {
        visibility_k: 40,
        ..ctss
    };
    extern "C" fn field(_: *mut std::ffi::c_void, _: SubconeVec3) -> SubconeFieldSample {
        SubconeFieldSample {
            distance: 1.0,
            step: 1.0,
            object: 0,
        }
    }
    extern "C" fn shade(
        _: *mut std::ffi::c_void,
        _: SubconeVec3,
        _: SubconeVec3,
        _: SubconeVec3,
    ) -> SubconeVec3 {
        SubconeVec3::default()
    }
    let zero = SubconeVec3::default();
    let z = SubconeVec3 {
        x: 0.0,
        y: 0.0,
        z: 1.0,
    };
    let y = SubconeVec3 {
        x: 0.0,
        y: 1.0,
        z: 0.0,
    };
    let mut result = SubconeCtssResult::default();
    let mut taa = SubconeTaaParams::default();
    let (mut jx, mut jy) = (0.0f32, 0.0f32);
    let pixels = [0.0f32; 8];
    let mut dst = [0.0f32; 8];
    let mut fxaa = SubconeFxaaParams::default();
    assert_eq!(
        unsafe { subcone_fxaa_params_quality(&mut fxaa) },
        SubconeStatus::Ok
    );

    type Case<'a> = (
        &'a str,
        SubconeStatus,
        Box<dyn FnOnce() -> SubconeStatus + 'a>,
        &'a [&'a str],
    );
    let cases: Vec<Case> = vec![
        (
            "subcone_bilateral_weight",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe { subcone_bilateral_weight(&nan_params, &g, &g, &mut f) }),
            &["params->sigma_n is NaN", "finite"],
        ),
        (
            "subcone_shadow_gated_weight",
            SubconeStatus::NullPointer,
            Box::new(move || unsafe {
                subcone_shadow_gated_weight(&params, null(), &g, 0, 0, &mut f)
            }),
            &["gi is NULL"],
        ),
        (
            "subcone_resolve_pixel",
            SubconeStatus::NullPointer,
            Box::new(move || unsafe { subcone_resolve_pixel(null(), &mut out[0]) }),
            &["subsamples"],
        ),
        (
            "subcone_cone_tan_theta",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe { subcone_cone_tan_theta(4.0, 720, 1.0, 0, &mut f) }),
            &["fov_y is 4", "(0, π)"],
        ),
        (
            "subcone_visibility_mask",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe { subcone_visibility_mask(0.5, 1.0, 0.0, 3, &mut u) }),
            &["placement is 3", "0", "2"],
        ),
        (
            "subcone_ctss_params_default",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe { subcone_ctss_params_default(-1.0, &mut ctss) }),
            &["tan_theta is -1", "not negative"],
        ),
        (
            "subcone_sraa_resolve",
            SubconeStatus::SizeMismatch,
            Box::new(move || unsafe {
                let frame = SubconeSraaFrame {
                    colors_len: 3,
                    ..data.frame()
                };
                subcone_sraa_resolve(&params, &frame, out.as_mut_ptr(), 2)
            }),
            &["frame->colors_len is 3", "width·height·layers = 2"],
        ),
        (
            "subcone_sraa_resolve",
            SubconeStatus::SizeMismatch,
            Box::new(move || unsafe {
                subcone_sraa_resolve(&params, &data.frame(), out.as_mut_ptr(), 1)
            }),
            &["out_len is 1", "= 2"],
        ),
        (
            "subcone_sraa_resolve",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe {
                let gates = [40i8];
                let frame = SubconeSraaFrame {
                    layer_lights: gates.as_ptr(),
                    ..data.frame()
                };
                subcone_sraa_resolve(&params, &frame, out.as_mut_ptr(), 2)
            }),
            &["frame->layer_lights[0] is 40", "32"],
        ),
        (
            "subcone_ctss_trace",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe {
                subcone_ctss_trace(
                    &bad_k,
                    zero,
                    z,
                    y,
                    Some(field),
                    None,
                    Some(shade),
                    null_mut(),
                    zero,
                    &mut result,
                )
            }),
            &["params->visibility_k is 40", "1..=32"],
        ),
        (
            "subcone_ctss_trace",
            SubconeStatus::NullPointer,
            Box::new(move || unsafe {
                subcone_ctss_trace(
                    &ctss,
                    zero,
                    z,
                    y,
                    None,
                    None,
                    Some(shade),
                    null_mut(),
                    zero,
                    &mut result,
                )
            }),
            &["distance is NULL"],
        ),
        (
            "subcone_ctss_trace",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe {
                subcone_ctss_trace(
                    &ctss,
                    zero,
                    zero,
                    y,
                    Some(field),
                    None,
                    Some(shade),
                    null_mut(),
                    zero,
                    &mut result,
                )
            }),
            &["dir is (0, 0, 0)"],
        ),
        (
            "subcone_sraa_pass_uniform",
            SubconeStatus::SizeMismatch,
            Box::new(move || unsafe {
                let mut uniform = SubconeSraaPassUniform::default();
                subcone_sraa_pass_uniform(&params, 0, 4, null(), 0.0, 0.0, &mut uniform)
            }),
            &["width × height is 0 × 4"],
        ),
        (
            "subcone_ctss_pass_uniform",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe {
                let mut uniform = SubconeCtssPassUniform::default();
                subcone_ctss_pass_uniform(zero, y, y, 0.8, 4, 4, zero, &mut uniform)
            }),
            &["forward", "up_hint", "parallel"],
        ),
        (
            "subcone_pinhole_ray",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe {
                let uniform = SubconeCtssPassUniform {
                    projection: 2,
                    ..Default::default()
                };
                let mut d = zero;
                subcone_pinhole_ray(&uniform, 0.5, 0.5, &mut d)
            }),
            &["uniform->projection is 2"],
        ),
        (
            "subcone_taa_params",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe { subcone_taa_params(4, 4, 0, f32::INFINITY, &mut taa) }),
            &["exposure is inf"],
        ),
        (
            "subcone_taa_jitter",
            SubconeStatus::InvalidArgument,
            Box::new(move || unsafe { subcone_taa_jitter(0, 0, &mut jx, &mut jy) }),
            &["phases is 0"],
        ),
        (
            "subcone_fxaa_image",
            SubconeStatus::SizeMismatch,
            Box::new(move || unsafe {
                subcone_fxaa_image(&fxaa, 2, 1, pixels.as_ptr(), 7, dst.as_mut_ptr(), 8)
            }),
            &["src_len is 7", "4·width·height = 8"],
        ),
        (
            "subcone_taa_resolve",
            SubconeStatus::SizeMismatch,
            Box::new(move || unsafe {
                let p = SubconeTaaParams {
                    width: 0,
                    height: 1,
                    ..Default::default()
                };
                subcone_taa_resolve(&p, null(), 0, null(), 0, null(), 0, null_mut(), 0)
            }),
            &["params->width × params->height is 0 × 1"],
        ),
    ];
    for (function, status, call, parts) in cases {
        let s = call();
        let m = last_error();
        assert_eq!(s, status, "{function}: {m}");
        assert!(
            m.starts_with(&format!("{function}: ")),
            "the message names the function {function}: {m}"
        );
        for part in parts {
            assert!(m.contains(part), "{function}: {m:?} does not name {part:?}");
        }
        assert!(!m.contains('\n'), "{function}: one line: {m:?}");
    }
}
