// TaaPass (taa.rs): temporal antialiasing (subcone_kernels::taa: Karis 2014,
// Salvi 2016's variance clipping) of a host frame against its history, one
// compute pass. Follows subcone_kernels::wgsl::PARAMS,
// subcone_kernels::taa::WGSL (and DILATION_WGSL with a depth input), the
// motion fetch taa.rs writes (taa_pixel_motion) and the declarations it
// generates (taa_params, taa_current, taa_velocity, taa_history,
// taa_depth_tex with a depth input, taa_dst).
//
// The kernel's image is the rect (taa_params' size); the hooks read the
// textures at the rect's origin (taa_origin).

// taa.rs `TaaOrigin` (16 bytes).
struct TaaOrigin {
    x: u32,
    y: u32,
    _pad0: u32,
    _pad1: u32,
}

fn taa_at(x: i32, y: i32) -> vec2<i32> {
    return vec2<i32>(x + i32(taa_origin.x), y + i32(taa_origin.y));
}

fn taa_current(x: i32, y: i32) -> vec3<f32> {
    return textureLoad(taa_current_tex, taa_at(x, y), 0).xyz;
}

fn taa_history(x: i32, y: i32) -> vec3<f32> {
    return textureLoad(taa_history_tex, taa_at(x, y), 0).xyz;
}

// The host's motion vector of a pixel (subcone_kernels::taa::resolve_pixel
// scales it by taa_params.motion_scale).
fn taa_motion(x: i32, y: i32) -> vec2<f32> {
    return textureLoad(taa_velocity, taa_at(x, y), 0).xy;
}

@compute @workgroup_size(8, 8)
fn taa_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= taa_params.width || gid.y >= taa_params.height {
        return;
    }
    let xy = vec2<i32>(i32(gid.x), i32(gid.y));
    // taa.rs defines taa_pixel_motion: the pixel's own vector, or with a
    // depth input the one of the nearest depth around it.
    let velocity = taa_pixel_motion(xy);
    let c = subcone_taa_resolve_pixel(xy, velocity, taa_params);
    textureStore(taa_dst, taa_at(xy.x, xy.y), vec4<f32>(c, 1.0));
}
