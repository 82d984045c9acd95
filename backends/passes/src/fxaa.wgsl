// FxaaPass (fxaa.rs): FXAA 3.11 (subcone_kernels::fxaa, preset 12) from a
// host texture into a host storage texture, one compute pass. Follows
// subcone_kernels::wgsl::PARAMS, subcone_kernels::fxaa::WGSL and the
// declarations fxaa.rs generates (fxaa_params, fxaa_frame, fxaa_src, fxaa_dst).
//
// The wgpu backend encodes every pixel into a buffer first (post/fxaa.wgsl);
// here the hook encodes each tap as it is read (subcone_fxaa_encode is a pure
// function of the pixel, so the taps are the same values) and no intermediate
// texture is allocated.

// fxaa.rs `FxaaFrame` (16 bytes).
struct FxaaFrame {
    width: u32,
    height: u32,
    _pad0: u32,
    _pad1: u32,
}

// The hook fxaa.wgsl reads pixels through: clamp to edge, encoded.
fn fxaa_fetch(x: i32, y: i32) -> vec4<f32> {
    let cx = clamp(x, 0, i32(fxaa_frame.width) - 1);
    let cy = clamp(y, 0, i32(fxaa_frame.height) - 1);
    return subcone_fxaa_encode(textureLoad(fxaa_src, vec2<i32>(cx, cy), 0).xyz);
}

@compute @workgroup_size(8, 8)
fn fxaa_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= fxaa_frame.width || gid.y >= fxaa_frame.height {
        return;
    }
    let c = subcone_fxaa_pixel(i32(gid.x), i32(gid.y), fxaa_params);
    textureStore(fxaa_dst, vec2<i32>(i32(gid.x), i32(gid.y)), vec4<f32>(subcone_fxaa_decode(c), 1.0));
}
