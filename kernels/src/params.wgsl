// The `#[repr(C)]` parameter structs of subcone-kernels, in WGSL.
//
// Each struct here has exactly the field offsets of its Rust twin (checked by
// kernels/tests/wgsl_layout.rs through naga's layouter). WGSL aligns vec3 to
// 16 bytes while glam's Vec3 aligns to 4: a scalar after a vec3 fills its
// 4-byte tail in both languages, which is why `subcone_Geometry` puts `depth` last.
// Arrays in the uniform address space have a 16-byte stride, so padding is
// spelled as scalars (`_pad0`, `_pad1` are Rust's `_pad: [u32; 2]`).

// subcone_kernels::sraa::SraaParams (32 bytes).
struct subcone_SraaParams {
    sigma_z: f32,
    sigma_n: f32,
    scale: f32,
    // Bits 0..8: WeightForm; 8..16: DepthMetric; 16..32: reconstruction radius.
    packed: u32,
    // σs, the spatial falloff in pixels (0: none, as in eq. 1).
    sigma_s: f32,
    // ShadedPosition: 0 on subsample 0 (the paper), 1 at the pixel centre.
    shading: u32,
    _pad0: u32,
    _pad1: u32,
}

// subcone_kernels::sraa::Geometry (16 bytes). depth = +inf marks a miss; WGSL
// cannot spell infinity as a literal, so shaders use SUBCONE_MISS_DEPTH.
struct subcone_Geometry {
    normal: vec3<f32>,
    depth: f32,
}

// subcone_kernels::ctss::CtssParams (48 bytes).
struct subcone_CtssParams {
    tan_theta: f32,
    alpha: f32,
    eps: f32,
    t_min: f32,
    t_max: f32,
    min_sample_weight: f32,
    max_steps: u32,
    max_samples: u32,
    visibility_k: u32,
    // Bit 0: subcone_FLAG_RELAXED. Bits 8..16: MaskPlacement. Bits 16..24: Weighting.
    flags: u32,
    _pad0: u32,
    _pad1: u32,
}

// subcone_kernels::camera::PinholeCamera (80 bytes).
struct subcone_PinholeCamera {
    position: vec3<f32>,
    width: u32,
    forward: vec3<f32>,
    height: u32,
    right: vec3<f32>,
    tan_half_fov: f32,
    up: vec3<f32>,
    _pad: u32,
    // Sub-pixel offset of every ray, in pixels (a temporal method's jitter).
    jitter: vec2<f32>,
    _pad2: vec2<u32>,
}

// subcone_kernels::taa::TaaParams (48 bytes).
struct subcone_TaaParams {
    exposure: f32,
    min_current_weight: f32,
    clip_gamma: f32,
    history_frames: u32,
    width: u32,
    height: u32,
    tone_mapped: u32,
    // 0 off, 1 a smaller depth is nearer, 2 a larger one is.
    depth_dilation: u32,
    // Host motion vector times this: pixels, current minus previous.
    motion_scale: vec2<f32>,
    _pad0: u32,
    _pad1: u32,
}

// subcone_kernels::fxaa::FxaaParams (16 bytes).
struct subcone_FxaaParams {
    subpix: f32,
    edge_threshold: f32,
    edge_threshold_min: f32,
    _pad: f32,
}

// subcone_kernels::sraa::NEGLIGIBLE_WEIGHT (2^-64): weight sums below it are
// treated as empty by the SRAA reconstruction and the CTSS aggregation alike.
const subcone_NEGLIGIBLE_WEIGHT: f32 = 5.421011e-20;

// The one +inf, NaN test and finiteness test of every shader that includes
// these parameters (kernels, backend passes, generated SDF fields). +inf is a
// bit pattern: WGSL has no infinity literal, and a constant-folded 1/0 is a
// shader-creation error. The tests read the bits, so no compiler may fold
// them away under fast-math assumptions.
fn subcone_inf() -> f32 {
    return bitcast<f32>(0x7f800000u);
}

fn subcone_is_nan(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) > 0x7f800000u;
}

fn subcone_is_finite(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) < 0x7f800000u;
}

// subcone_kernels::camera::PinholeCamera::ray_dir: the unit direction from
// c.position through image point p + c.jitter (pixels, y down).
fn subcone_pinhole_dir(c: subcone_PinholeCamera, p_in: vec2<f32>) -> vec3<f32> {
    let p = p_in + c.jitter;
    let w = f32(max(c.width, 1u));
    let h = f32(max(c.height, 1u));
    let u = (2.0 * p.x / w - 1.0) * c.tan_half_fov * (w / h);
    let v = (1.0 - 2.0 * p.y / h) * c.tan_half_fov;
    let d = c.forward + u * c.right + v * c.up;
    return d * (1.0 / length(d));
}
