//! The crate's `#[repr(C)]` GPU structs against their WGSL twins through
//! naga's layouter (the check of `subcone-wgpu`'s `layout_tests.rs`): every
//! WGSL member, in order, at the offset and with the size of the Rust field
//! it mirrors, and the same total size. And every shader the passes build,
//! for every configuration, parses and validates.

use crate::layout_check::{assert_all_match, compare, Member};

use crate::ctss::{CtssPass, CtssUniform, CTSS_WGSL};
use crate::fxaa::{FxaaFrame, FxaaPass, FXAA_WGSL};
use crate::sraa::{SraaFrame, SRAA_WGSL};

#[test]
fn pass_gpu_structs_match_their_wgsl() {
    assert_all_match(&[
        (
            SRAA_WGSL,
            "SraaFrame",
            size_of::<SraaFrame>(),
            members!(SraaFrame: sraa, projection, width, height, depth_miss, albedo_tolerance),
        ),
        (
            CTSS_WGSL,
            "CtssUniform",
            size_of::<CtssUniform>(),
            members!(CtssUniform: position, width, forward, height, right, half, up, _pad0,
                background, _pad1),
        ),
        (
            FXAA_WGSL,
            "FxaaFrame",
            size_of::<FxaaFrame>(),
            members!(FxaaFrame: width, height, _pad[2 as u32]),
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
    for (label, host) in [
        ("ctss", field.to_string()),
        ("ctss, host normal", own_normal),
    ] {
        let g = CtssPass::group_for_tests(wgpu::TextureFormat::Rgba16Float);
        if let Err(e) = validate(label, &CtssPass::source(&host, 8, &g)) {
            errors.push(e);
        }
    }
    let g = FxaaPass::group(wgpu::TextureFormat::Rgba8Unorm).expect("an output format");
    if let Err(e) = validate("fxaa", &FxaaPass::source(&g)) {
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
    let g = CtssPass::group_for_tests(wgpu::TextureFormat::Rgba16Float);
    let source = CtssPass::source(host, 8, &g);
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
