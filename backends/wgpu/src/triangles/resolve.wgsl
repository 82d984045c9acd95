// Hybrid SRAA's output copied into a colour buffer (resolve.rs), only for a
// post-process that runs after the resolve and reads a buffer (FXAA forced
// onto an SRAA frame). The frame itself is read back from the texture.
//
// Bindings (resolve.rs): sraa_output (SraaPass's output) and color (the
// buffer the post-process reads).

@compute @workgroup_size(8, 8)
fn output_to_buffer_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(sraa_output);
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let j = gid.y * size.x + gid.x;
    color[j] = vec4<f32>(textureLoad(sraa_output, vec2<i32>(i32(gid.x), i32(gid.y)), 0).xyz, 0.0);
}
