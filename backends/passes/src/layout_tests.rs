//! The crate's `#[repr(C)]` GPU structs against their WGSL twins through
//! naga's layouter (the check of `subcone-wgpu`'s `layout_tests.rs`): every
//! WGSL member, in order, at the offset and with the size of the Rust field
//! it mirrors, and the same total size. And every shader the passes build,
//! for every configuration, parses and validates.

use crate::layout_check::{assert_all_match, compare, Member};

use crate::bind::TextureFormat;
use crate::ctss::{
    CtssBackground, CtssDepth, CtssKey, CtssOutput, CtssPass, CtssPassDesc, CtssTrace, CtssUniform,
    CTSS_WGSL,
};
use crate::fxaa::{FxaaFrame, FxaaPass, FxaaPassDesc, FXAA_WGSL};
use crate::skeleton;
use crate::sraa::{SraaFrame, SRAA_WGSL};
use crate::taa::{TaaOrigin, TaaPass, TaaPassDesc, TAA_WGSL};

#[test]
fn pass_gpu_structs_match_their_wgsl() {
    assert_all_match(&[
        (
            SRAA_WGSL,
            "SraaFrame",
            size_of::<SraaFrame>(),
            members!(
                SraaFrame: sraa,
                projection,
                width,
                height,
                depth_miss,
                albedo_tolerance,
                origin_x,
                origin_y,
                exposure,
                _pad
            ),
        ),
        (
            CTSS_WGSL,
            "CtssUniform",
            size_of::<CtssUniform>(),
            members!(
                CtssUniform: camera,
                background,
                projection,
                inverse_view_projection,
                forward,
                depth_offset,
                origin,
                row_length,
                _pad
            ),
        ),
        (
            FXAA_WGSL,
            "FxaaFrame",
            size_of::<FxaaFrame>(),
            members!(FxaaFrame: width, height, _pad[2 as u32]),
        ),
        (
            TAA_WGSL,
            "TaaOrigin",
            size_of::<TaaOrigin>(),
            members!(TaaOrigin: x, y, _pad[2 as u32]),
        ),
    ]);
}

/// The comparison can fail: fields out of order, a field at another offset
/// and another total size are each caught. (The one test of the checker:
/// `subcone-wgpu`'s layout tests include this crate's.)
#[test]
fn a_mismatched_layout_is_caught() {
    let good = members!(FxaaFrame: width, height, _pad[2 as u32]);
    let size = size_of::<FxaaFrame>();
    assert_eq!(compare(FXAA_WGSL, "FxaaFrame", size, &good), Ok(()));
    let mut swapped = good.clone();
    swapped.swap(0, 1);
    assert!(compare(FXAA_WGSL, "FxaaFrame", size, &swapped).is_err());
    let mut moved = good.clone();
    moved[1].1 += 4;
    assert!(compare(FXAA_WGSL, "FxaaFrame", size, &moved).is_err());
    assert!(compare(FXAA_WGSL, "FxaaFrame", size + 16, &good).is_err());
}

/// Parse and validate a whole shader as wgpu would.
fn validate(label: &str, source: &str) -> Result<(), String> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| format!("{label}: {}", e.emit_to_string(source)))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| format!("{label}: {}", e.emit_to_string(source)))?;
    Ok(())
}

/// The CTSS pass's whole shader over `host_wgsl` for `desc`.
fn ctss_source(host_wgsl: &str, desc: &CtssPassDesc<'_>) -> String {
    let key = CtssKey { host_wgsl, desc };
    skeleton::shader::<CtssPass>(&key).expect("a valid desc").1
}

/// Every SRAA configuration's shader (layout, textures or buffers × depth ×
/// normals × centre or subsample shading × lights × albedo gate × secondary
/// shading) validates, and so do the
/// CTSS (with and without the host's normal) and FXAA shaders.
#[test]
fn every_pass_shader_validates() {
    use crate::sraa::{test_source, DepthKind, GeometryLayout, NormalEncoding, SraaPassDesc};
    use subcone_kernels::sraa::SraaParams;
    let mut errors = Vec::new();
    for geometry in [
        GeometryLayout::Multisampled,
        GeometryLayout::Layers,
        GeometryLayout::Packed,
        GeometryLayout::Buffers,
    ] {
        for depth in [DepthKind::Hardware { miss: 0.0 }, DepthKind::LinearView] {
            for normal in [NormalEncoding::Signed, NormalEncoding::Unsigned] {
                if matches!(geometry, GeometryLayout::Packed | GeometryLayout::Buffers)
                    && (depth != DepthKind::LinearView || normal != NormalEncoding::Signed)
                {
                    continue;
                }
                for params in [SraaParams::PAPER, SraaParams::TUNED] {
                    for (lights, albedo_gate, secondary) in [
                        (0, false, false),
                        (2, true, true),
                        (8, false, true),
                        (0, false, true),
                    ] {
                        let desc = SraaPassDesc {
                            lights,
                            albedo_gate,
                            secondary,
                            params,
                            geometry,
                            depth,
                            normal,
                            ..SraaPassDesc::msaa()
                        };
                        if let Err(e) = validate(&format!("{desc:?}"), &test_source(&desc)) {
                            errors.push(e);
                        }
                    }
                }
            }
        }
    }
    let field = "fn subcone_field(p: vec3<f32>) -> vec3<f32> { let d = length(p) - 1.0; return vec3<f32>(d, d, 0.0); }\n\
                 fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> { return n; }\n";
    let own_normal = format!(
        "{field}fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> {{ return normalize(p); }}\n"
    );
    // The host's own trace and counters, as CtssTrace::Host and counted
    // buffers ask for them.
    let own_trace = format!(
        "{field}fn subcone_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, \
         right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {{\n\
         return subcone_CtssTraceResult(dir, 1u, 2u, 0u, 0u, 0.0); }}\n\
         fn subcone_counters() -> vec2<u32> {{ return vec2<u32>(3u, 4u); }}\n"
    );
    for (host, normal) in [(field.to_string(), ""), (own_normal, ", host normal")] {
        for output in [CtssOutput::Texture, CtssOutput::Buffers { counts: false }] {
            for (side, background, depth) in [
                (1, CtssBackground::Opaque, CtssDepth::None),
                (3, CtssBackground::Opaque, CtssDepth::None),
                (1, CtssBackground::Transparent, CtssDepth::View),
                (2, CtssBackground::Transparent, CtssDepth::None),
                (2, CtssBackground::Opaque, CtssDepth::View),
            ] {
                let desc = CtssPassDesc::default()
                    .with_output(output)
                    .with_samples_per_side(side)
                    .with_background(background)
                    .with_depth(depth);
                let label =
                    format!("ctss{normal}, {output:?}, side {side}, {background:?}, {depth:?}");
                if let Err(e) = validate(&label, &ctss_source(&host, &desc)) {
                    errors.push(e);
                }
            }
        }
    }
    for output in [
        CtssOutput::Texture,
        CtssOutput::Buffers { counts: false },
        CtssOutput::Buffers { counts: true },
    ] {
        let desc = CtssPassDesc::default()
            .with_trace(CtssTrace::Host)
            .with_output(output)
            .with_samples_per_side(2)
            .with_depth(CtssDepth::View);
        let label = format!("ctss, host trace, {output:?}");
        if let Err(e) = validate(&label, &ctss_source(&own_trace, &desc)) {
            errors.push(e);
        }
    }
    let fxaa = FxaaPassDesc::default().with_output_format(TextureFormat::Rgba8Unorm);
    let (_, source) = skeleton::shader::<FxaaPass>(&fxaa).expect("a valid desc");
    if let Err(e) = validate("fxaa", &source) {
        errors.push(e);
    }
    let (_, source) = skeleton::shader::<TaaPass>(&TaaPassDesc::default()).expect("a valid desc");
    if let Err(e) = validate("taa", &source) {
        errors.push(e);
    }
    assert!(errors.is_empty(), "{}", errors.join("\n\n"));
}

/// The object id that means "none" is one constant: the WGSL the CTSS pass
/// runs declares `subcone_NO_OBJECT` with the value of the kernels'
/// `ctss::NO_OBJECT` (which the C ABI's `SubconeFieldSample::object`
/// documents as `0xFFFFFFFF`).
#[test]
fn the_wgsl_no_object_is_the_kernels_constant() {
    let host = "fn subcone_field(p: vec3<f32>) -> vec3<f32> { let d = length(p) - 1.0; return vec3<f32>(d, d, 0.0); }\n\
                fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> { return n; }\n";
    let desc = CtssPassDesc::default();
    let source = ctss_source(host, &desc);
    let module = naga::front::wgsl::parse_str(&source).expect("the CTSS pass's shader parses");
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some("subcone_NO_OBJECT"))
        .expect("ctss.wgsl declares subcone_NO_OBJECT");
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::U32(v)) => {
            assert_eq!(v, subcone_kernels::ctss::NO_OBJECT)
        }
        ref other => panic!("subcone_NO_OBJECT is {other:?}, not a u32 literal"),
    }
    assert_eq!(subcone_kernels::ctss::NO_OBJECT, 0xFFFF_FFFF);
}
