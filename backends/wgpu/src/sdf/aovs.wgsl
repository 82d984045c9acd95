// AOVs of SDF scenes: view depth and normal through each pixel centre, by
// sphere tracing with a pixel-wide cone (SdfView::render's AOV block).
// Appended to trace.wgsl only when AOVs are requested.

// Bindings (sdf/mod.rs): aov_params (subcone_CtssParams); aov_out, per
// pixel (normal, view depth), depth +inf and normal 0 on a miss.

@compute @workgroup_size(8, 8)
fn sdf_aovs(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.width || gid.y >= frame.height {
        return;
    }
    let d = camera_dir(vec2<f32>(f32(gid.x) + 0.5, f32(gid.y) + 0.5));
    let hit = subcone_sphere_trace_split(aov_params, frame.position, d);
    var out = vec4<f32>(0.0, 0.0, 0.0, subcone_inf());
    if hit.t >= 0.0 {
        let q = frame.position + hit.t * d;
        out = vec4<f32>(normal_at(q, hit.t, aov_params.tan_theta), dot(q - frame.position, frame.forward));
    }
    aov_out[gid.y * frame.width + gid.x] = out;
}
