// CtssPass (ctss.rs): cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10,
// §5.3) of the host's signed distance field, N × N cones per pixel, through
// the kernels' trace subcone_ctss_trace (subcone_kernels::ctss::TRACE_WGSL),
// the twin of subcone_kernels::ctss::trace_field, or the host's own
// subcone_trace (CtssTrace::Host).
//
// Follows the kernels (PARAMS, with subcone_PinholeCamera and
// subcone_pinhole_dir; cone, mask, aggregate, ctss, ctss/trace), the host's
// WGSL (subcone_field, subcone_shade, optionally subcone_normal; and
// subcone_CTSS_BATCH, which ctss.rs declares), the desc's variant
// (subcone_pass_SIDE, subcone_pass_trace, subcone_pass_store, which ctss.rs
// writes) and the declarations ctss.rs generates: subcone_pass_frame
// (CtssUniform), subcone_pass_params (subcone_CtssParams),
// subcone_pass_output (a storage texture or buffer) and, with counts,
// subcone_pass_counts.

// ctss.rs `CtssUniform` (96 bytes): the camera of CtssCamera::ray and the
// background.
struct CtssUniform {
    camera: subcone_PinholeCamera,
    background: vec3<f32>,
    _pad: u32,
}

// A pixel's index in the row-major buffers.
fn subcone_pass_index(p: vec2<u32>) -> u32 {
    return p.y * subcone_pass_frame.camera.width + p.x;
}

// One pixel: the mean of its subcone_pass_SIDE² cones through the sub-pixel
// centres (SSAA over CTSS; one cone through the centre when the side is 1),
// each about the ray of CtssCamera::ray with the cross-section axes of
// subcone_cross_section_frame.
@compute @workgroup_size(8, 8)
fn subcone_pass_ctss_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let f = subcone_pass_frame;
    if gid.x >= f.camera.width || gid.y >= f.camera.height {
        return;
    }
    let side = subcone_pass_SIDE;
    var steps = 0u;
    var samples = 0u;
    var sum = vec3<f32>(0.0);
    for (var sy = 0u; sy < side; sy++) {
        for (var sx = 0u; sx < side; sx++) {
            let off = vec2<f32>((f32(sx) + 0.5) / f32(side), (f32(sy) + 0.5) / f32(side));
            let d = subcone_pinhole_dir(f.camera, vec2<f32>(f32(gid.x), f32(gid.y)) + off);
            let axes = subcone_cross_section_frame(d, f.camera.up);
            let r = subcone_pass_trace(subcone_pass_params, f.camera.position, d, axes[0], axes[1], f.background);
            sum += r.color;
            steps += r.steps;
            samples += r.samples;
        }
    }
    subcone_pass_store(gid.xy, sum / f32(side * side), steps, samples);
}
