// The frame's way into and out of subcone_passes::FxaaPass (post/fxaa.rs):
// the backend's frames are colour buffers (array<vec4<f32>>, linear RGB) and
// FxaaPass reads and writes textures, so fxaa_to_texture_main copies the
// frame into the pass's input texture and fxaa_from_texture_main copies the
// pass's output into a new buffer. FXAA itself is FxaaPass's
// (backends/passes/src/fxaa.wgsl), the kernels' subcone_kernels::fxaa.

// post/fxaa.rs `FxaaFrame` (16 bytes).
struct FxaaFrame {
    width: u32,
    height: u32,
    _pad0: u32,
    _pad1: u32,
}

// Bindings (fxaa.rs): fxaa_frame (FxaaFrame); fxaa_src, the rendered frame;
// fxaa_in, FxaaPass's input texture (storage, written here); fxaa_out, its
// output texture (read here); fxaa_dst, the filtered frame.

@compute @workgroup_size(8, 8)
fn fxaa_to_texture_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= fxaa_frame.width || gid.y >= fxaa_frame.height {
        return;
    }
    let i = gid.y * fxaa_frame.width + gid.x;
    textureStore(fxaa_in, vec2<i32>(i32(gid.x), i32(gid.y)), vec4<f32>(fxaa_src[i].xyz, 1.0));
}

@compute @workgroup_size(8, 8)
fn fxaa_from_texture_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= fxaa_frame.width || gid.y >= fxaa_frame.height {
        return;
    }
    let i = gid.y * fxaa_frame.width + gid.x;
    fxaa_dst[i] = textureLoad(fxaa_out, vec2<i32>(i32(gid.x), i32(gid.y)), 0);
}
