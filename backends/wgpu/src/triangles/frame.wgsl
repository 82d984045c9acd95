// The constants of a triangle frame, shared by the compute passes
// (trace.wgsl and its entry points) and the raster pass (raster.wgsl).
// The frame's constants (triangles/mod.rs, `FrameUniform`).
struct FrameUniform {
    cam_pos: vec3<f32>,
    // tan(fov_y / 2), computed as Camera::ray does.
    half: f32,
    forward: vec3<f32>,
    // width / height as f32 (Camera::ray's `w / h`).
    aspect: f32,
    right: vec3<f32>,
    // Offset of secondary ray origins (Tracer::eps = scale · 2e-5).
    eps: f32,
    up: vec3<f32>,
    width_f: f32,
    ambient: vec3<f32>,
    height_f: f32,
    background: vec3<f32>,
    ssaa_side: u32,
    width: u32,
    height: u32,
    lights: u32,
    reflection_depth: u32,
    node_count: u32,
    // Near plane of the raster pass's reversed depth (scale · 1e-7).
    near: f32,
    // Ambient-occlusion rays per shaded primary hit (0: off) and their length.
    ao_rays: u32,
    ao_radius: f32,
    sraa: subcone_SraaParams,
    // Camera::jitter: every primary ray's sub-pixel offset.
    jitter: vec2<f32>,
    // 1: only the diagonal of the ssaa_side grid (ssaa2); 0: the grid.
    ssaa_diagonal: u32,
    _pad: f32,
}

// The SRAA parameters the resolve's hooks (sraa.wgsl) read.
fn sraa_params() -> subcone_SraaParams {
    return frame.sraa;
}

