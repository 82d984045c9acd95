//! Every one of the backend's own `#[repr(C)]` GPU structs against its WGSL
//! twin (triangles, SDF scenes, FXAA),
//! through naga's layouter (WGSL's layout rules), as `kernels/tests/
//! wgsl_layout.rs` checks the kernels' structs: every WGSL member, in order,
//! at the offset and with the size of the Rust field it mirrors, and the same
//! total size. Rust arrays of padding (`_pad: [u32; 3]`) are spelled as
//! scalars in WGSL (`_pad0` …); `[f32; 3]` is a `vec3<f32>` member.

use core::mem::{offset_of, size_of};

use crate::post::fxaa::{FxaaFrame, FXAA_WGSL};
use crate::sdf::{SdfFrame, TRACE_WGSL as SDF_WGSL};
use crate::triangles::bvh::{GpuLight, GpuMaterial, GpuNode};
use crate::triangles::{FrameUniform, ALBEDO_WGSL, FRAME_WGSL, TRACE_WGSL};

/// The text of `struct <name> { … }` in `source`.
fn struct_text<'a>(source: &'a str, name: &str) -> &'a str {
    let start = source
        .find(&format!("struct {name} {{"))
        .unwrap_or_else(|| panic!("no struct {name} in the WGSL"));
    let end = start + source[start..].find('}').expect("closing brace") + 1;
    &source[start..end]
}

/// One Rust field as WGSL members: (WGSL name, offset, size).
type Member = (String, usize, usize);

/// `members!(T: field, field, pad[N] as f32, …)`: a field is the WGSL member
/// of the same name; `pad[N] as E` is N scalar members `pad0` … of type E.
macro_rules! members {
    ($ty:ty: $($field:ident $([$n:literal as $e:ty])?),+ $(,)?) => {{
        let mut m: Vec<Member> = Vec::new();
        $( members!(@one m, $ty, $field $([$n as $e])?); )+
        m
    }};
    (@one $m:ident, $ty:ty, $field:ident) => {{
        let probe = |s: &$ty| core::mem::size_of_val(&s.$field);
        let size = probe(&bytemuck::Zeroable::zeroed());
        $m.push((stringify!($field).to_string(), offset_of!($ty, $field), size));
    }};
    (@one $m:ident, $ty:ty, $field:ident [$n:literal as $e:ty]) => {{
        for i in 0..$n {
            $m.push((
                format!("{}{i}", stringify!($field)),
                offset_of!($ty, $field) + i * size_of::<$e>(),
                size_of::<$e>(),
            ));
        }
    }};
}

/// Compare the WGSL struct `wgsl_name` (declared in `source`, after the
/// kernels' shared structs) with the Rust layout `members` of total `size`.
fn compare(source: &str, wgsl_name: &str, size: usize, members: &[Member]) -> Result<(), String> {
    let text = format!(
        "{}\n{}\n",
        subcone_kernels::wgsl::PARAMS,
        struct_text(source, wgsl_name)
    );
    let module = naga::front::wgsl::parse_str(&text).map_err(|e| e.emit_to_string(&text))?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|e| e.to_string())?;
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(wgsl_name))
        .ok_or_else(|| format!("no WGSL struct {wgsl_name}"))?;
    let naga::TypeInner::Struct {
        members: wgsl,
        span,
    } = &ty.inner
    else {
        return Err(format!("{wgsl_name} is not a struct"));
    };
    let names: Vec<&str> = wgsl
        .iter()
        .map(|m| m.name.as_deref().unwrap_or("?"))
        .collect();
    let rust: Vec<&str> = members.iter().map(|m| m.0.as_str()).collect();
    if names != rust {
        return Err(format!(
            "{wgsl_name}: WGSL members {names:?}, Rust {rust:?}"
        ));
    }
    for (w, (name, offset, bytes)) in wgsl.iter().zip(members) {
        let wsize = layouter[w.ty].size as usize;
        if w.offset as usize != *offset || wsize != *bytes {
            return Err(format!(
                "{wgsl_name}.{name}: WGSL offset {} size {wsize}, Rust offset {offset} size {bytes}",
                w.offset
            ));
        }
    }
    if *span as usize != size || layouter[handle].size as usize != size {
        return Err(format!("{wgsl_name}: WGSL size {span}, Rust size {size}"));
    }
    Ok(())
}

#[test]
fn backend_gpu_structs_match_their_wgsl() {
    let checks: Vec<(&str, &str, usize, Vec<Member>)> = vec![
        (
            FRAME_WGSL,
            "FrameUniform",
            size_of::<FrameUniform>(),
            members!(FrameUniform: cam_pos, half, forward, aspect, right, eps, up, width_f,
                ambient, height_f, background, ssaa_side, width, height, lights,
                reflection_depth, node_count, near, ao_rays, ao_radius, sraa),
        ),
        (
            TRACE_WGSL,
            "BvhNode",
            size_of::<GpuNode>(),
            members!(GpuNode: min, count, max, index),
        ),
        (
            TRACE_WGSL,
            "LightGpu",
            size_of::<GpuLight>(),
            members!(GpuLight: v, kind, value, _pad),
        ),
        (
            ALBEDO_WGSL,
            "MaterialGpu",
            size_of::<GpuMaterial>(),
            members!(GpuMaterial: a, kind, b, size, emission, mirror, extra),
        ),
        (
            SDF_WGSL,
            "SdfFrame",
            size_of::<SdfFrame>(),
            members!(SdfFrame: position, width, forward, height, right, half, up,
                max_distance, background, max_steps, ambient, side, cone, _pad[3 as u32]),
        ),
        (
            FXAA_WGSL,
            "FxaaFrame",
            size_of::<FxaaFrame>(),
            members!(FxaaFrame: width, height, _pad[2 as u32]),
        ),
    ];
    let errors: Vec<String> = checks
        .iter()
        .filter_map(|(src, name, size, m)| compare(src, name, *size, m).err())
        .collect();
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// The comparison can fail: fields out of order, a field at another offset
/// and another total size are each caught.
#[test]
fn a_mismatched_layout_is_caught() {
    let good = members!(GpuNode: min, count, max, index);
    let size = size_of::<GpuNode>();
    assert_eq!(compare(TRACE_WGSL, "BvhNode", size, &good), Ok(()));
    let mut swapped = good.clone();
    swapped.swap(1, 2);
    assert!(compare(TRACE_WGSL, "BvhNode", size, &swapped).is_err());
    let mut moved = good.clone();
    moved[1].1 += 4;
    assert!(compare(TRACE_WGSL, "BvhNode", size, &moved).is_err());
    assert!(compare(TRACE_WGSL, "BvhNode", size + 16, &good).is_err());
}
