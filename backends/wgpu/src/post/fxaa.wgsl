// The frame's way into and out of subcone_passes::FxaaPass (post/fxaa.rs):
// the backend's frames are colour buffers (array<vec4<f32>>, linear RGB) and
// FxaaPass reads and writes textures, so fxaa_to_texture_main copies the
// frame into the pass's input texture and fxaa_from_texture_main copies the
// pass's output into a new buffer. FXAA itself is FxaaPass's
// (backends/passes/src/fxaa.wgsl), the kernels' subcone_kernels::fxaa.

// Bindings (fxaa.rs): fxaa_src, the rendered frame; fxaa_in, FxaaPass's
// input texture (storage, written here); fxaa_out, its output texture (read
// here), whose size is the frame's; fxaa_dst, the filtered frame.

@compute @workgroup_size(8, 8)
fn fxaa_to_texture_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(fxaa_out);
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let i = gid.y * size.x + gid.x;
    textureStore(fxaa_in, vec2<i32>(i32(gid.x), i32(gid.y)), vec4<f32>(fxaa_src[i].xyz, 1.0));
}

@compute @workgroup_size(8, 8)
fn fxaa_from_texture_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(fxaa_out);
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let i = gid.y * size.x + gid.x;
    fxaa_dst[i] = textureLoad(fxaa_out, vec2<i32>(i32(gid.x), i32(gid.y)), 0);
}
