// The hooks through which the kernels' ctss/group_mask.wgsl reads the scene
// (subcone_kernels::ctss::ConeField, as the CPU's SdfView implements it with
// ConeFieldOf), for the semi-transparent path (translucent.wgsl).
// Concatenated after the field (scene_sdf_split) and trace.wgsl
// (normal_surface).

// ConeField::sample: (surface distance, safe step, material).
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let r = scene_sdf_split(p);
    return vec3<f32>(r.y, r.x, r.z);
}

// ConeField::normal: SdfNode::normal_surface with step h.
fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> {
    return normal_surface(p, h);
}
