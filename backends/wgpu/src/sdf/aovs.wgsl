// AOVs of SDF scenes: view depth and normal through each pixel centre, by
// sphere tracing with a pixel-wide cone (SdfView::render's AOV block).
// After trace.wgsl, in a program of its own, only when AOVs are requested.

// Bindings (sdf/mod.rs `centre_aovs`): aov_params (subcone_CtssParams);
// aov_out, per pixel (normal, view depth), depth +inf and normal 0 on a miss;
// and trace.wgsl's frame, ctss and sdf_data.

@compute @workgroup_size(8, 8)
fn sdf_aovs(@builtin(global_invocation_id) gid: vec3<u32>) {
    let c = frame.camera;
    if gid.x >= c.width || gid.y >= c.height {
        return;
    }
    let d = subcone_pinhole_dir(c, vec2<f32>(f32(gid.x) + 0.5, f32(gid.y) + 0.5));
    let hit = subcone_sphere_trace_split(aov_params, c.position, d);
    var out = vec4<f32>(0.0, 0.0, 0.0, subcone_inf());
    if hit.t >= 0.0 {
        let q = c.position + hit.t * d;
        out = vec4<f32>(normal_at(q, hit.t, aov_params.tan_theta), dot(q - c.position, c.forward));
    }
    aov_out[gid.y * c.width + gid.x] = out;
}
