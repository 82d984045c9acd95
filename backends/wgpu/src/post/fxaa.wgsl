// FXAA over a frame's colour buffer (backends/wgpu/src/post/fxaa.rs): the
// CPU backend's post::fxaa. Appended to params.wgsl and fxaa.wgsl.

struct FxaaFrame {
    width: u32,
    height: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> fxaa_params: FxaaParams;
@group(0) @binding(1) var<uniform> fxaa_frame: FxaaFrame;
// The rendered frame, linear RGB (w unused).
@group(0) @binding(2) var<storage, read> fxaa_src: array<vec4<f32>>;
// fxaa_encode of every pixel: displayed sRGB colour and luma.
@group(0) @binding(3) var<storage, read_write> fxaa_encoded: array<vec4<f32>>;
// The filtered frame, linear RGB.
@group(0) @binding(4) var<storage, read_write> fxaa_dst: array<vec4<f32>>;

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
    fxaa_encoded[i] = fxaa_encode(fxaa_src[i].xyz);
}

@compute @workgroup_size(8, 8)
fn fxaa_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= fxaa_frame.width || gid.y >= fxaa_frame.height {
        return;
    }
    let i = gid.y * fxaa_frame.width + gid.x;
    let c = fxaa_pixel(i32(gid.x), i32(gid.y), fxaa_params);
    fxaa_dst[i] = vec4<f32>(fxaa_decode(c), 1.0);
}
