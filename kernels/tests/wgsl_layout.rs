//! The WGSL the crate ships against its Rust twins, through naga (the WGSL
//! front end wgpu uses):
//!
//! - every shared parameter struct of `params.wgsl` ([`wgsl::PARAMS`]) has, member
//!   by member, the offset and size of the `#[repr(C)]` Rust field it mirrors,
//!   and the same total size (naga's `Layouter`, i.e. WGSL's layout rules);
//! - [`wgsl::PARAMS`] and every kernel source, concatenated the way backends
//!   concatenate them, parse and pass naga's validator with no optional
//!   capability (WGSL core only).

use core::mem::{offset_of, size_of};

use naga::valid::{Capabilities, ValidationFlags, Validator};
use subcone_kernels::camera::PinholeCamera;
use subcone_kernels::ctss::CtssParams;
use subcone_kernels::fxaa::FxaaParams;
use subcone_kernels::sraa::{Geometry, SraaParams};
use subcone_kernels::taa::TaaParams;
use subcone_kernels::wgsl;

/// The kernel WGSL sources, in dependency order: each is validated
/// concatenated after [`wgsl::PARAMS`] and every source above it. One line
/// per kernel module.
const KERNELS: &[(&str, &str)] = &[
    ("sraa::WGSL", subcone_kernels::sraa::WGSL),
    // The reconstruction loop's hooks are the including shader's: a 4×4
    // image of one surface, unshadowed, grey, stands in for them.
    ("the caller's sraa_params etc.", SRAA_RECONSTRUCT_HOOKS),
    (
        "sraa::RECONSTRUCT_WGSL",
        subcone_kernels::sraa::RECONSTRUCT_WGSL,
    ),
    ("cone::WGSL", subcone_kernels::cone::WGSL),
    ("mask::WGSL", subcone_kernels::mask::WGSL),
    ("aggregate::WGSL", subcone_kernels::aggregate::WGSL),
    ("transparency::WGSL", subcone_kernels::transparency::WGSL),
    // The stepper's SDF is the including shader's: a sphere stands in for it.
    ("the caller's ctss_field", CTSS_FIELD),
    ("ctss::WGSL", subcone_kernels::ctss::WGSL),
    // The trace's field, normal, shading and batch are the including
    // shader's: a sphere, its normal and white stand in for them.
    ("the caller's subcone_field etc.", CTSS_TRACE_HOOKS),
    ("ctss::TRACE_WGSL", subcone_kernels::ctss::TRACE_WGSL),
    // The pixel fetch is the including shader's: a constant stands in for it.
    ("the caller's fxaa_fetch", FXAA_FETCH),
    ("fxaa::WGSL", subcone_kernels::fxaa::WGSL),
    ("ao::WGSL", subcone_kernels::ao::WGSL),
    // The fetches are the including shader's: constants stand in for them.
    ("the caller's taa fetches", TAA_FETCHES),
    ("taa::WGSL", subcone_kernels::taa::WGSL),
    // The motion and depth fetches are the including shader's: constants
    // stand in for them.
    ("the caller's taa motion and depth", TAA_DILATION_FETCHES),
    ("taa::DILATION_WGSL", subcone_kernels::taa::DILATION_WGSL),
];

/// The hooks `taa_dilation.wgsl` expects its including shader to define.
const TAA_DILATION_FETCHES: &str = "
fn taa_motion(x: i32, y: i32) -> vec2<f32> { return vec2<f32>(f32(x), f32(y)); }
fn taa_depth(x: i32, y: i32) -> f32 { return f32(x + y); }
";

/// The hooks `taa.wgsl` expects its including shader to define.
const TAA_FETCHES: &str = "
fn taa_current(x: i32, y: i32) -> vec3<f32> { return vec3<f32>(f32(x & 1)); }
fn taa_history(x: i32, y: i32) -> vec3<f32> { return vec3<f32>(0.5); }
";

/// The hooks `sraa/reconstruct.wgsl` expects its including shader to define.
const SRAA_RECONSTRUCT_HOOKS: &str = "
const SRAA_GATES: u32 = 3u;
const SRAA_MATERIAL: bool = true;
fn sraa_params() -> subcone_SraaParams { return subcone_SraaParams(10.0, 1.0, 1.0, 1u << 16u, 0.4, 1u, 0u, 0u); }
fn sraa_size() -> vec2<u32> { return vec2<u32>(4u, 4u); }
fn sraa_albedo_tolerance() -> f32 { return 0.1; }
fn sraa_shaded_geometry(x: u32, y: u32, secondary: bool) -> subcone_Geometry { return subcone_Geometry(vec3<f32>(0.0, 0.0, 1.0), 1.0); }
fn sraa_shaded_shadow(x: u32, y: u32, secondary: bool) -> u32 { return 0u; }
fn sraa_shaded_albedo(x: u32, y: u32) -> vec3<f32> { return vec3<f32>(0.5); }
fn sraa_shaded_value(x: u32, y: u32, layer: u32) -> vec3<f32> { return vec3<f32>(0.5); }
";

/// The hook `fxaa.wgsl` expects its including shader to define.
const FXAA_FETCH: &str =
    "fn fxaa_fetch(x: i32, y: i32) -> vec4<f32> { return vec4<f32>(f32(x & 1), 0.0, 0.0, 0.5); }";

/// The hook `ctss.wgsl` expects its including shader to define.
const CTSS_FIELD: &str =
    "fn ctss_field(p: vec3<f32>) -> vec2<f32> { let d = length(p) - 1.0; return vec2<f32>(d, d); }";

/// The hooks `ctss/trace.wgsl` expects its including shader to define.
const CTSS_TRACE_HOOKS: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> { let d = length(p) - 1.0; return vec3<f32>(d, d, 0.0); }
fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> { return normalize(p); }
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> { return vec3<f32>(1.0); }
const subcone_CTSS_BATCH: u32 = 8u;
";

/// One WGSL member expected at a Rust offset with a Rust size.
#[derive(Debug)]
struct Member {
    wgsl: String,
    offset: usize,
    size: usize,
}

/// A Rust struct shared with WGSL.
struct Shared {
    /// The WGSL name: `subcone_` + the Rust name.
    name: &'static str,
    size: usize,
    members: Vec<Member>,
}

fn field_size<S, T>(_: impl Fn(&S) -> &T) -> usize {
    size_of::<T>()
}

fn element_size<S, T, const N: usize>(_: impl Fn(&S) -> &[T; N]) -> (usize, usize) {
    (size_of::<T>(), N)
}

/// `shared!(Struct: field, field, array[N], …)`: a scalar or vector field is
/// the WGSL member of the same name; an array field `array[N]` is the N
/// WGSL members `array0` … `array{N-1}` (uniform arrays have a 16-byte
/// stride, so padding is spelled as scalars in WGSL).
macro_rules! shared {
    ($ty:ident: $($field:ident $([$n:literal])?),+ $(,)?) => {
        Shared {
            name: concat!("subcone_", stringify!($ty)),
            size: size_of::<$ty>(),
            members: {
                let mut m = Vec::new();
                $( shared!(@field m, $ty, $field $([$n])?); )+
                m
            },
        }
    };
    (@field $m:ident, $ty:ident, $field:ident) => {
        $m.push(Member {
            wgsl: stringify!($field).to_string(),
            offset: offset_of!($ty, $field),
            size: field_size(|s: &$ty| &s.$field),
        });
    };
    (@field $m:ident, $ty:ident, $field:ident [$n:literal]) => {
        let (size, n) = element_size(|s: &$ty| &s.$field);
        assert_eq!(n, $n, "{}::{} has {n} elements", stringify!($ty), stringify!($field));
        for i in 0..n {
            $m.push(Member {
                wgsl: format!("{}{i}", stringify!($field)),
                offset: offset_of!($ty, $field) + i * size,
                size,
            });
        }
    };
}

/// Every struct `params.wgsl` shares with Rust: one line each.
fn shared_structs() -> Vec<Shared> {
    vec![
        shared!(SraaParams: sigma_z, sigma_n, scale, packed, sigma_s, shading, _pad[2]),
        shared!(Geometry: normal, depth),
        shared!(CtssParams: tan_theta, alpha, eps, t_min, t_max, min_sample_weight,
            max_steps, max_samples, visibility_k, flags, _pad[2]),
        shared!(PinholeCamera: position, width, forward, height, right, tan_half_fov, up, _pad, jitter, _pad2),
        shared!(FxaaParams: subpix, edge_threshold, edge_threshold_min, _pad),
        shared!(TaaParams: exposure, min_current_weight, clip_gamma, history_frames, width,
            height, tone_mapped, depth_dilation, motion_scale, _pad[2]),
    ]
}

fn parse(name: &str, source: &str) -> naga::Module {
    naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name} does not parse:\n{}", e.emit_to_string(source)))
}

fn validate(name: &str, source: &str) -> naga::Module {
    let module = parse(name, source);
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name} is invalid:\n{}", e.emit_to_string(source)));
    module
}

/// Compare every shared struct of `source` with its Rust twin: the first
/// difference, or `Ok`.
fn compare_layouts(source: &str) -> Result<(), String> {
    let module = parse("wgsl::PARAMS", source);
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|e| e.to_string())?;
    for s in shared_structs() {
        let (handle, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(s.name))
            .ok_or_else(|| format!("no WGSL struct {}", s.name))?;
        let naga::TypeInner::Struct { members, span } = &ty.inner else {
            return Err(format!("{} is not a struct in WGSL", s.name));
        };
        let wgsl_members: Vec<&str> = members
            .iter()
            .map(|m| m.name.as_deref().unwrap_or("?"))
            .collect();
        let rust_members: Vec<&str> = s.members.iter().map(|m| m.wgsl.as_str()).collect();
        if wgsl_members != rust_members {
            return Err(format!(
                "{}: WGSL members {wgsl_members:?}, Rust fields {rust_members:?}",
                s.name
            ));
        }
        for (w, r) in members.iter().zip(&s.members) {
            if w.offset as usize != r.offset {
                return Err(format!(
                    "{}.{}: WGSL offset {} but Rust offset {}",
                    s.name, r.wgsl, w.offset, r.offset
                ));
            }
            let size = layouter[w.ty].size as usize;
            if size != r.size {
                return Err(format!(
                    "{}.{}: WGSL size {size} but Rust size {}",
                    s.name, r.wgsl, r.size
                ));
            }
        }
        let size = layouter[handle].size as usize;
        if *span as usize != s.size || size != s.size {
            return Err(format!(
                "{}: WGSL size {span} (layouter {size}) but Rust size {}",
                s.name, s.size
            ));
        }
    }
    Ok(())
}

#[test]
fn shared_structs_have_the_rust_layout() {
    if let Err(e) = compare_layouts(wgsl::PARAMS) {
        panic!("{e}");
    }
}

/// The comparison catches what it is for: `PARAMS` with a member moved, a
/// padding member dropped, or a type changed each fail it.
#[test]
fn layout_mismatches_are_detected() {
    for (edit, from, to) in [
        (
            "subcone_Geometry with depth first (WGSL pads normal to offset 16)",
            "    normal: vec3<f32>,\n    depth: f32,",
            "    depth: f32,\n    normal: vec3<f32>,",
        ),
        ("subcone_CtssParams without _pad1", "    _pad1: u32,\n", ""),
        (
            "subcone_SraaParams.packed as a vec2",
            "    packed: u32,",
            "    packed: vec2<u32>,",
        ),
        (
            "subcone_Geometry.normal as a vec4",
            "normal: vec3<f32>",
            "normal: vec4<f32>",
        ),
    ] {
        assert!(
            wgsl::PARAMS.contains(from),
            "{edit}: PARAMS has no {from:?}"
        );
        let source = wgsl::PARAMS.replacen(from, to, 1);
        let result = compare_layouts(&source);
        assert!(result.is_err(), "{edit}: not detected");
    }
}

/// Every struct `params.wgsl` declares is in the table above, so a struct added
/// there cannot go unchecked.
#[test]
fn every_wgsl_struct_is_checked() {
    let module = parse("wgsl::PARAMS", wgsl::PARAMS);
    let checked: Vec<&str> = shared_structs().iter().map(|s| s.name).collect();
    for (_, ty) in module.types.iter() {
        if let (naga::TypeInner::Struct { .. }, Some(name)) = (&ty.inner, ty.name.as_deref()) {
            assert!(
                checked.contains(&name),
                "struct {name} of params.wgsl is not in shared_structs()"
            );
        }
    }
}

#[test]
fn params_and_kernels_validate() {
    validate("wgsl::PARAMS", wgsl::PARAMS);
    let mut source = wgsl::PARAMS.to_string();
    let mut names = vec!["wgsl::PARAMS"];
    for &(name, kernel) in KERNELS {
        source.push('\n');
        source.push_str(kernel);
        names.push(name);
        validate(&names.join(" + "), &source);
    }
}

/// The SRAA sources export what the GPU resolves call: the weights (eq. 1,
/// eq. 2, the material gate), the neighbourhood, the per-layer
/// reconstruction steps and the box resolve from `sraa::WGSL`, and the loop
/// that drives them, `subcone_sraa_reconstruct_run`, from
/// `sraa::RECONSTRUCT_WGSL`.
#[test]
fn sraa_wgsl_exports_the_resolve() {
    let source = [
        wgsl::PARAMS,
        subcone_kernels::sraa::WGSL,
        SRAA_RECONSTRUCT_HOOKS,
        subcone_kernels::sraa::RECONSTRUCT_WGSL,
    ]
    .join("\n");
    let module = validate("sraa::WGSL + sraa::RECONSTRUCT_WGSL", &source);
    for f in [
        "subcone_bilateral_weight",
        "subcone_shadow_gated_weight",
        "subcone_reconstruction_weight",
        "subcone_albedo_difference",
        "subcone_material_gated_weight",
        "subcone_material_gate",
        "subcone_depth_difference",
        "subcone_gaussian",
        "subcone_saturate",
        "subcone_neighbourhood",
        "subcone_neighbour_distance2",
        "subcone_reconstruct_layers_begin",
        "subcone_reconstruct_layers_add",
        "subcone_reconstruct_layers_end",
        "subcone_resolve_pixel",
        "subcone_tone_map_weight",
        "subcone_resolve_pixel_tone_mapped",
        "subcone_sraa_reconstruct_run",
    ] {
        assert!(
            module
                .functions
                .iter()
                .any(|(_, g)| g.name.as_deref() == Some(f)),
            "{f} missing"
        );
    }
}

/// A kernel source that parses but does not validate fails the check.
#[test]
#[should_panic(expected = "is invalid")]
fn an_invalid_kernel_fails_validation() {
    let source = [
        wgsl::PARAMS,
        "fn bad(p: subcone_SraaParams) -> f32 { return p.packed; }",
    ]
    .concat();
    validate("wgsl::PARAMS + bad", &source);
}

/// The hooks a kernel source expects its including shader to define: the
/// only names the kernels use that they do not export.
const HOOKS: &[&str] = &[
    "fxaa_fetch",
    "taa_current",
    "taa_history",
    "taa_motion",
    "taa_depth",
    "ctss_field",
    "SRAA_GATES",
    "SRAA_MATERIAL",
    "sraa_params",
    "sraa_size",
    "sraa_albedo_tolerance",
    "sraa_shaded_geometry",
    "sraa_shaded_shadow",
    "sraa_shaded_albedo",
    "sraa_shaded_value",
];

/// Every function, struct and constant the kernels export is `subcone_` +
/// its Rust name (ARCHITECTURE.md rule 10), so that a host shader including
/// them collides with none of its own names and shadows no built-in (before
/// the prefix, `saturate` hid WGSL's own).
#[test]
fn every_exported_wgsl_name_is_prefixed() {
    let mut source = wgsl::PARAMS.to_string();
    for &(_, kernel) in KERNELS {
        source.push('\n');
        source.push_str(kernel);
    }
    let module = parse("the kernels", &source);
    let mut names: Vec<&str> = Vec::new();
    names.extend(
        module
            .functions
            .iter()
            .filter_map(|(_, f)| f.name.as_deref()),
    );
    names.extend(
        module
            .constants
            .iter()
            .filter_map(|(_, c)| c.name.as_deref()),
    );
    names.extend(module.types.iter().filter_map(|(_, t)| match t.inner {
        naga::TypeInner::Struct { .. } => t.name.as_deref(),
        _ => None,
    }));
    assert!(names.len() > 100, "only {} names found", names.len());
    let bare: Vec<&str> = names
        .into_iter()
        .filter(|n| !n.starts_with("subcone_") && !HOOKS.contains(n))
        .collect();
    assert!(
        bare.is_empty(),
        "exported without the subcone_ prefix: {bare:?}"
    );
}
