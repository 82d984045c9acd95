// TaaPass (taa.rs): temporal antialiasing (subcone_kernels::taa: Karis 2014,
// Salvi 2016's variance clipping) of a host frame against its history, one
// compute pass. Follows subcone_kernels::wgsl::PARAMS,
// subcone_kernels::taa::WGSL and the declarations taa.rs generates
// (taa_params, taa_current, taa_velocity, taa_history, taa_dst).
//
// The bindings are named after the hooks' textures; the hooks read them.

fn taa_current(x: i32, y: i32) -> vec3<f32> {
    return textureLoad(taa_current_tex, vec2<i32>(x, y), 0).xyz;
}

fn taa_history(x: i32, y: i32) -> vec3<f32> {
    return textureLoad(taa_history_tex, vec2<i32>(x, y), 0).xyz;
}

@compute @workgroup_size(8, 8)
fn taa_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= taa_params.width || gid.y >= taa_params.height {
        return;
    }
    let xy = vec2<i32>(i32(gid.x), i32(gid.y));
    let velocity = textureLoad(taa_velocity, xy, 0).xy;
    let c = subcone_taa_resolve_pixel(xy, velocity, taa_params);
    textureStore(taa_dst, xy, vec4<f32>(c, 1.0));
}
