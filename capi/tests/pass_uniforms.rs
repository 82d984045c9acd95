//! The C header's pass uniforms (`SubconeSraaPassUniform`,
//! `SubconeCtssPassUniform`) against naga's layout of the uniform each
//! shader of `shaders/` declares: every member's offset and size, in order
//! (nested structs flattened), and the total size.

use std::mem::{offset_of, size_of};

use subcone_capi::*;
use subcone_passes::standalone;

/// (offset, size) of every scalar, vector or matrix member of `ty`, nested
/// structs flattened, in declaration order.
fn flatten(
    m: &naga::Module,
    l: &naga::proc::Layouter,
    ty: naga::Handle<naga::Type>,
    base: u32,
    out: &mut Vec<(usize, usize)>,
) {
    match &m.types[ty].inner {
        naga::TypeInner::Struct { members, .. } => {
            for member in members {
                flatten(m, l, member.ty, base + member.offset, out);
            }
        }
        _ => out.push((base as usize, l[ty].size as usize)),
    }
}

/// The flattened layout of the uniform bound as `binding` in `wgsl`, and
/// its size.
fn uniform_layout(wgsl: &str, binding: &str) -> (Vec<(usize, usize)>, usize) {
    let m = naga::front::wgsl::parse_str(wgsl).expect("WGSL parses");
    let mut l = naga::proc::Layouter::default();
    l.update(m.to_ctx()).expect("layout");
    let (_, var) = m
        .global_variables
        .iter()
        .find(|(_, v)| v.name.as_deref() == Some(binding))
        .expect("binding declared");
    let mut out = Vec::new();
    flatten(&m, &l, var.ty, 0, &mut out);
    (out, l[var.ty].size as usize)
}

/// (offset, size) of each field, arrays of scalars split into their
/// elements as naga's vectors are not: `[f32; 3]` is one `vec3<f32>`.
macro_rules! fields {
    ($t:ty: $($f:ident $(: $n:literal x $e:ty)?),+ $(,)?) => {{
        let mut v: Vec<(usize, usize)> = Vec::new();
        $(
            fields!(@one v, $t, $f $(, $n, $e)?);
        )+
        v
    }};
    (@one $v:ident, $t:ty, $f:ident) => {{
        let probe = |s: &$t| std::mem::size_of_val(&s.$f);
        $v.push((offset_of!($t, $f), probe(&<$t>::default())));
    }};
    (@one $v:ident, $t:ty, $f:ident, $n:literal, $e:ty) => {{
        for i in 0..$n {
            $v.push((offset_of!($t, $f) + i * size_of::<$e>(), size_of::<$e>()));
        }
    }};
}

#[test]
fn sraa_pass_uniform_matches_every_sraa_shader() {
    let c = {
        let mut v = Vec::new();
        let p = offset_of!(SubconeSraaPassUniform, sraa);
        for (o, s) in fields!(SubconeSraaParams: sigma_z, sigma_n, scale, packed, sigma_s, shading, pad: 2 x u32)
        {
            v.push((p + o, s));
        }
        v.extend(
            fields!(SubconeSraaPassUniform: projection, width, height, depth_miss,
            albedo_tolerance, origin_x, origin_y, exposure, pad),
        );
        v
    };
    let catalog = standalone::catalog().expect("catalog");
    let sraa: Vec<_> = catalog.iter().filter(|s| s.pass == "sraa").collect();
    assert!(sraa.len() >= 4);
    for s in sraa {
        let (naga, size) = uniform_layout(&s.wgsl, "frame");
        assert_eq!(naga, c, "sraa/{}", s.variant);
        assert_eq!(
            size,
            size_of::<SubconeSraaPassUniform>(),
            "sraa/{}",
            s.variant
        );
    }
}

#[test]
fn ctss_pass_uniform_and_params_match_every_ctss_shader() {
    // The camera's members at its offset, then the uniform's own.
    let at = offset_of!(SubconeCtssPassUniform, camera);
    let mut c: Vec<(usize, usize)> = fields!(SubconePinholeCamera: position, width, forward,
        height, right, tan_half_fov, up, pad0, jitter, pad1: 2 x u32)
    .into_iter()
    .map(|(o, s)| (at + o, s))
    .collect();
    c.extend(
        fields!(SubconeCtssPassUniform: background, projection, inverse_view_projection,
        forward, depth_offset, origin, row_length, pad),
    );
    // naga lays out the matrix and the jitter as one member each, the
    // padding pair as one vec2<u32>: merge the C side's split elements.
    let merge = |v: Vec<(usize, usize)>| -> Vec<(usize, usize)> {
        let mut out: Vec<(usize, usize)> = Vec::new();
        for (o, s) in v {
            match out.last_mut() {
                // pad1's two u32 are naga's one vec2<u32>.
                Some(last) if last.0 == 72 && o == 76 => last.1 += s,
                _ => out.push((o, s)),
            }
        }
        out
    };
    let c = merge(c);
    let params = fields!(SubconeCtssParams: tan_theta, alpha, eps, t_min, t_max,
        min_sample_weight, max_steps, max_samples, visibility_k, flags, pad: 2 x u32);
    let catalog = standalone::catalog().expect("catalog");
    let ctss: Vec<_> = catalog.iter().filter(|s| s.pass == "ctss").collect();
    assert!(!ctss.is_empty());
    for s in ctss {
        let (naga, size) = uniform_layout(&s.wgsl, "subcone_pass_frame");
        assert_eq!(naga, c, "ctss/{}", s.variant);
        assert_eq!(size, size_of::<SubconeCtssPassUniform>());
        let (naga, size) = uniform_layout(&s.wgsl, "subcone_pass_params");
        assert_eq!(naga, params, "ctss/{}", s.variant);
        assert_eq!(size, size_of::<SubconeCtssParams>());
    }
}

#[test]
fn fxaa_and_taa_uniforms_match_their_shaders() {
    let catalog = standalone::catalog().expect("catalog");
    let fxaa = catalog.iter().find(|s| s.pass == "fxaa").expect("fxaa");
    let params = fields!(SubconeFxaaParams: subpix, edge_threshold, edge_threshold_min, pad);
    assert_eq!(uniform_layout(&fxaa.wgsl, "fxaa_params"), (params, 16));
    let frame = fields!(SubconeFxaaPassFrame: width, height, pad: 2 x u32);
    assert_eq!(uniform_layout(&fxaa.wgsl, "fxaa_frame"), (frame, 16));
    let taa = catalog.iter().find(|s| s.pass == "taa").expect("taa");
    let params = fields!(SubconeTaaParams: exposure, min_current_weight, clip_gamma,
        history_frames, width, height, tone_mapped, depth_dilation, motion_scale, pad: 2 x u32);
    assert_eq!(uniform_layout(&taa.wgsl, "taa_params"), (params, 48));
    let origin = fields!(SubconeTaaPassOrigin: x, y, pad: 2 x u32);
    assert_eq!(uniform_layout(&taa.wgsl, "taa_origin"), (origin, 16));
}

#[test]
fn fxaa_and_taa_fills_are_the_rust_ones() {
    use subcone_kernels::taa::{jitter, ResolveSpace, TaaParams};
    // SAFETY: valid pointers or null.
    unsafe {
        let mut f = SubconeFxaaParams::default();
        assert_eq!(subcone_fxaa_params_quality(&mut f), SubconeStatus::Ok);
        assert_eq!(
            (f.subpix, f.edge_threshold, f.edge_threshold_min),
            (0.75, 0.166, 0.0833)
        );
        let mut frame = SubconeFxaaPassFrame::default();
        assert_eq!(
            subcone_fxaa_pass_frame(0, 2, &mut frame),
            SubconeStatus::SizeMismatch
        );
        assert_eq!(subcone_fxaa_pass_frame(3, 2, &mut frame), SubconeStatus::Ok);
        assert_eq!((frame.width, frame.height), (3, 2));

        let mut t = SubconeTaaParams::default();
        assert_eq!(
            subcone_taa_params(8, 6, 3, -1.0, &mut t),
            SubconeStatus::InvalidArgument
        );
        assert_eq!(subcone_taa_params(8, 6, 3, 0.0, &mut t), SubconeStatus::Ok);
        let rust = TaaParams::new((8, 6)).with_history_frames(3);
        assert_eq!(TaaParams::from(t), rust);
        assert_eq!(subcone_taa_params(8, 6, 0, 2.0, &mut t), SubconeStatus::Ok);
        let rust = TaaParams::new((8, 6)).with_space(ResolveSpace::ToneMapped { exposure: 2.0 });
        assert_eq!(TaaParams::from(t), rust);

        let (mut x, mut y) = (0.0f32, 0.0f32);
        assert_eq!(
            subcone_taa_jitter(5, 0, &mut x, &mut y),
            SubconeStatus::InvalidArgument
        );
        assert_eq!(
            subcone_taa_jitter(5, 16, &mut x, std::ptr::null_mut()),
            SubconeStatus::NullPointer
        );
        assert_eq!(subcone_taa_jitter(5, 16, &mut x, &mut y), SubconeStatus::Ok);
        assert_eq!((x, y), jitter(5, 16).into());
    }
}

#[test]
fn pass_uniforms_refuse_bad_input() {
    let mut params = SubconeSraaParams::default();
    let mut u = SubconeSraaPassUniform::default();
    // SAFETY: valid pointers or null.
    unsafe {
        assert_eq!(subcone_sraa_params_default(&mut params), SubconeStatus::Ok);
        let m = std::ptr::null();
        assert_eq!(
            subcone_sraa_pass_uniform(&params, 0, 4, m, 0.0, 0.0, &mut u),
            SubconeStatus::SizeMismatch
        );
        assert_eq!(
            subcone_sraa_pass_uniform(&params, 4, 4, m, 0.0, -1.0, &mut u),
            SubconeStatus::InvalidArgument
        );
        assert_eq!(
            subcone_sraa_pass_uniform(std::ptr::null(), 4, 4, m, 0.0, 0.0, &mut u),
            SubconeStatus::NullPointer
        );
        let nan = [f32::NAN; 16];
        assert_eq!(
            subcone_sraa_pass_uniform(&params, 4, 4, nan.as_ptr(), 0.0, 0.0, &mut u),
            SubconeStatus::InvalidArgument
        );
        let mut proj = [0.0f32; 16];
        (proj[10], proj[14], proj[11], proj[15]) = (1.0, 2.0, 3.0, 4.0);
        assert_eq!(
            subcone_sraa_pass_uniform(&params, 4, 3, proj.as_ptr(), 0.5, 0.0, &mut u),
            SubconeStatus::Ok
        );
        assert_eq!(u.projection, [1.0, 2.0, 3.0, 4.0]);
        assert_eq!((u.width, u.height, u.depth_miss), (4, 3, 0.5));

        let v = |x, y, z| SubconeVec3 { x, y, z };
        let mut c = SubconeCtssPassUniform::default();
        let (eye, fwd, up) = (v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), v(0.0, 1.0, 0.0));
        assert_eq!(
            subcone_ctss_pass_uniform(eye, fwd, fwd, 0.8, 4, 4, eye, &mut c),
            SubconeStatus::InvalidArgument,
            "forward parallel to up"
        );
        assert_eq!(
            subcone_ctss_pass_uniform(eye, fwd, up, 4.0, 4, 4, eye, &mut c),
            SubconeStatus::InvalidArgument,
            "fov beyond π"
        );
        assert_eq!(
            subcone_ctss_pass_uniform(v(f32::NAN, 0.0, 0.0), fwd, up, 0.8, 4, 4, eye, &mut c),
            SubconeStatus::InvalidArgument
        );
        assert_eq!(
            subcone_ctss_pass_uniform(eye, fwd, up, 0.8, 8, 6, v(0.1, 0.2, 0.3), &mut c),
            SubconeStatus::Ok
        );
        assert_eq!((c.camera.width, c.camera.height, c.row_length), (8, 6, 8));
        assert_eq!(c.camera.forward, [0.0, 0.0, 1.0]);
        assert_eq!(c.forward, [0.0, 0.0, 1.0]);
        assert!((c.camera.tan_half_fov - 0.4f32.tan()).abs() < 1e-7);
        // A tiny up_hint, whose cross product with forward has a subnormal
        // squared length (a fuzzing find): the frame is still orthonormal.
        let up_hint = v(0.0, 1e-20, 1e-20);
        assert_eq!(
            subcone_ctss_pass_uniform(eye, v(-1.0, 0.0, 0.0), up_hint, 0.8, 2, 2, eye, &mut c),
            SubconeStatus::Ok
        );
        assert_eq!(c.camera.right, [0.0, 0.70710677, -0.70710677]);
        let len = |a: [f32; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        assert!(
            (len(c.camera.right) - 1.0).abs() < 1e-6,
            "{:?}",
            c.camera.right
        );
        assert!((len(c.camera.up) - 1.0).abs() < 1e-6, "{:?}", c.camera.up);
        // Within 10⁻⁴ of parallel the cross product cancels too much to be
        // orthogonal to forward (a second fuzzing find): no frame.
        let nearly = v(1.0, 1e-5, 0.0);
        assert_eq!(
            subcone_ctss_pass_uniform(eye, v(1.0, 0.0, 0.0), nearly, 0.8, 2, 2, eye, &mut c),
            SubconeStatus::InvalidArgument
        );
    }
}
