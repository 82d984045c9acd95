// CtssPass (ctss.rs): cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10,
// §5.3) of the host's signed distance field, one cone per pixel, through the
// kernels' trace subcone_ctss_trace (subcone_kernels::ctss::TRACE_WGSL), the
// twin of subcone_kernels::ctss::trace_field.
//
// Follows the kernels (PARAMS, cone, mask, aggregate, ctss, ctss/trace), the
// host's WGSL (subcone_field, subcone_shade, optionally subcone_normal, and
// subcone_CTSS_BATCH, which ctss.rs declares) and the declarations ctss.rs
// generates: subcone_pass_frame (CtssUniform), subcone_pass_params
// (subcone_CtssParams), subcone_pass_output.

// ctss.rs `CtssUniform` (80 bytes): the camera of CtssCamera::ray.
struct CtssUniform {
    position: vec3<f32>,
    width: u32,
    forward: vec3<f32>,
    height: u32,
    right: vec3<f32>,
    // tan(fov_y / 2)
    half: f32,
    up: vec3<f32>,
    _pad0: u32,
    background: vec3<f32>,
    _pad1: u32,
}

// CtssCamera::ray: the unit direction through image point px (pixels, y down).
fn subcone_pass_camera_dir(px: vec2<f32>) -> vec3<f32> {
    let f = subcone_pass_frame;
    let w = f32(max(f.width, 1u));
    let h = f32(max(f.height, 1u));
    let u = (2.0 * px.x / w - 1.0) * f.half * (w / h);
    let v = (1.0 - 2.0 * px.y / h) * f.half;
    let d = f.forward + u * f.right + v * f.up;
    return d * (1.0 / length(d));
}

@compute @workgroup_size(8, 8)
fn subcone_pass_ctss_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let f = subcone_pass_frame;
    if gid.x >= f.width || gid.y >= f.height {
        return;
    }
    let d = subcone_pass_camera_dir(vec2<f32>(f32(gid.x) + 0.5, f32(gid.y) + 0.5));
    let axes = subcone_cross_section_frame(d, f.up);
    let r = subcone_ctss_trace(subcone_pass_params, f.position, d, axes[0], axes[1], f.background);
    textureStore(subcone_pass_output, vec2<i32>(i32(gid.x), i32(gid.y)), vec4<f32>(r.color, 1.0));
}
