// The CTSS / sphere-tracing frame's entry point (sdf/mod.rs `render`),
// after trace.wgsl and the samplers; writes `color_out` and `counts_out`.
// The SRAA-RT program (sdf/sraa.rs) has its own entry points and no
// `color_out`, so it does not include this file.

// SdfView::render, one pixel: side × side samples at sub-pixel centres, each
// through pixel_cone_sample or pixel_sphere_sample, which sdf/mod.rs binds to
// this file's samplers (ctss_sample, noaa_sample) on opaque scenes and to
// translucent.wgsl's on semi-transparent ones.
@compute @workgroup_size(8, 8)
fn sdf_render(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.width || gid.y >= frame.height {
        return;
    }
    let side = max(frame.side, 1u);
    var steps = 0u;
    var samples = 0u;
    var shadow = 0u;
    ao_rays_traced = 0u;
    var sum = vec3<f32>(0.0);
    for (var sy = 0u; sy < side; sy++) {
        for (var sx = 0u; sx < side; sx++) {
            let off = vec2<f32>((f32(sx) + 0.5) / f32(side), (f32(sy) + 0.5) / f32(side));
            let d = camera_dir(vec2<f32>(f32(gid.x), f32(gid.y)) + off);
            if frame.cone != 0u {
                sum += pixel_cone_sample(frame.position, d, &steps, &samples, &shadow);
            } else {
                sum += pixel_sphere_sample(frame.position, d, &steps, &samples, &shadow);
            }
        }
    }
    let i = gid.y * frame.width + gid.x;
    color_out[i] = vec4<f32>(sum / f32(side * side), 1.0);
    counts_out[i] = vec4<u32>(steps, samples, shadow, ao_rays_traced);
}
