// The AOV pass (triangles/mod.rs `centre_geometry`). Follows trace.wgsl and
// the generated frame bindings (`aov`).

// render.rs `centre_geometry`: depth and normal of the ray through each pixel
// centre (AOVs; not counted).
@compute @workgroup_size(8, 8)
fn centre_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let j = id.y * frame.width + id.x;
    let p = vec2<f32>(f32(id.x) + 0.5, f32(id.y) + 0.5);
    aov[j] = primary_geometry(intersect(frame.cam_pos, camera_ray(p), 0.0));
}
