// Hybrid SRAA's pass "antialiasing" through subcone_passes::SraaResolve
// (resolve.rs): the shading pass's storage buffers copied into the textures
// SraaResolve reads (to_textures_main), and its output copied back into the
// frame's colour buffer (from_texture_main). Follows the header resolve.rs
// generates (put_centre, put_albedo).
//
// Bindings (resolve.rs): geo (array<subcone_Geometry>, the shaded samples'
// geometry), values (array<vec4<f32>>, their colour: one layer per pixel),
// albedo_buf (+mat), the storage textures res_color and, as the preset and
// +mat need them, res_centre_depth, res_centre_normal, res_albedo; res_output
// (SraaResolve's output) and color (the frame).

@compute @workgroup_size(8, 8)
fn to_textures_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(res_color);
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let j = gid.y * size.x + gid.x;
    let p = vec2<i32>(i32(gid.x), i32(gid.y));
    textureStore(res_color, p, vec4<f32>(values[j].xyz, 1.0));
    put_centre(p, j);
    put_albedo(p, j);
}

@compute @workgroup_size(8, 8)
fn from_texture_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(res_output);
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let j = gid.y * size.x + gid.x;
    color[j] = vec4<f32>(textureLoad(res_output, vec2<i32>(i32(gid.x), i32(gid.y)), 0).xyz, 0.0);
}
