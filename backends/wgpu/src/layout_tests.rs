//! Every one of the backend's own `#[repr(C)]` GPU structs against its WGSL
//! twin (triangles, SDF scenes),
//! through naga's layouter (WGSL's layout rules), as `kernels/tests/
//! wgsl_layout.rs` checks the kernels' structs: every WGSL member, in order,
//! at the offset and with the size of the Rust field it mirrors, and the same
//! total size. Rust arrays of padding (`_pad: [u32; 3]`) are spelled as
//! scalars in WGSL (`_pad0` …); `[f32; 3]` is a `vec3<f32>` member.

// The checker is `subcone-passes`' own (one copy for both crates, tested
// there: `a_mismatched_layout_is_caught`).
#[macro_use]
#[path = "../../passes/src/layout_check.rs"]
mod layout_check;

use layout_check::{assert_all_match, Member};

use crate::sdf::{SdfFrame, TRACE_WGSL as SDF_WGSL};
use crate::triangles::bvh::{GpuLight, GpuMaterial, GpuNode};
use crate::triangles::{FrameUniform, ALBEDO_WGSL, FRAME_WGSL, TRACE_WGSL};

#[test]
fn backend_gpu_structs_match_their_wgsl() {
    assert_all_match(&[
        (
            FRAME_WGSL,
            "FrameUniform",
            size_of::<FrameUniform>(),
            members!(FrameUniform: cam_pos, half, forward, aspect, right, eps, up, width_f,
                ambient, height_f, background, ssaa_side, width, height, lights,
                reflection_depth, node_count, near, ao_rays, ao_radius, sraa, jitter, ssaa_diagonal,
                _pad),
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
            members!(SdfFrame: camera, background, max_distance, ambient, max_steps, ao_rays,
                ao_radius, cone, _pad),
        ),
    ]);
}
