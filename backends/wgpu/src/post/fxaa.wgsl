// FXAA over a frame's colour buffer (backends/wgpu/src/post/fxaa.rs): the
// CPU backend's post::fxaa. Appended to params.wgsl and fxaa.wgsl.

struct FxaaFrame {
    width: u32,
    height: u32,
    _pad0: u32,
    _pad1: u32,
}

// Bindings (fxaa.rs): fxaa_params (subcone_FxaaParams), fxaa_frame
// (FxaaFrame); fxaa_src, the rendered frame, linear RGB (w unused);
// fxaa_encoded, subcone_fxaa_encode of every pixel (displayed sRGB colour
// and luma); fxaa_dst, the filtered frame, linear RGB.

// The hook fxaa.wgsl reads pixels through: clamp to edge.
fn fxaa_fetch(x: i32, y: i32) -> vec4<f32> {
    let cx = u32(clamp(x, 0, i32(fxaa_frame.width) - 1));
    let cy = u32(clamp(y, 0, i32(fxaa_frame.height) - 1));
    return fxaa_encoded[cy * fxaa_frame.width + cx];
}

@compute @workgroup_size(8, 8)
fn fxaa_encode_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= fxaa_frame.width || gid.y >= fxaa_frame.height {
        return;
    }
    let i = gid.y * fxaa_frame.width + gid.x;
    fxaa_encoded[i] = subcone_fxaa_encode(fxaa_src[i].xyz);
}

@compute @workgroup_size(8, 8)
fn fxaa_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= fxaa_frame.width || gid.y >= fxaa_frame.height {
        return;
    }
    let i = gid.y * fxaa_frame.width + gid.x;
    let c = subcone_fxaa_pixel(i32(gid.x), i32(gid.y), fxaa_params);
    fxaa_dst[i] = vec4<f32>(subcone_fxaa_decode(c), 1.0);
}
