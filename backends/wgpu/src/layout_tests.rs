//! Every one of the backend's own `#[repr(C)]` GPU structs against its WGSL
//! twin (triangles, SDF scenes, FXAA),
//! through naga's layouter (WGSL's layout rules), as `kernels/tests/
//! wgsl_layout.rs` checks the kernels' structs: every WGSL member, in order,
//! at the offset and with the size of the Rust field it mirrors, and the same
//! total size. Rust arrays of padding (`_pad: [u32; 3]`) are spelled as
//! scalars in WGSL (`_pad0` …); `[f32; 3]` is a `vec3<f32>` member.

// The checker is `subcone-passes`' own (one copy for both crates).
#[macro_use]
#[path = "../../passes/src/layout_check.rs"]
mod layout_check;

use layout_check::{compare, Member};

use crate::post::fxaa::{FxaaFrame, FXAA_WGSL};
use crate::sdf::{SdfFrame, TRACE_WGSL as SDF_WGSL};
use crate::triangles::bvh::{GpuLight, GpuMaterial, GpuNode};
use crate::triangles::{FrameUniform, ALBEDO_WGSL, FRAME_WGSL, TRACE_WGSL};

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
