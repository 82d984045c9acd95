// Evaluates a generated field at given points (for conformance tests of the
// WGSL code generator against SdfNode::eval / eval_split).

@group(0) @binding(0) var<storage, read> field_points: array<vec4<f32>>;
// Two per point: (eval distance, eval material, split safe, split surface),
// (split material, 0, 0, 0).
@group(0) @binding(1) var<storage, read_write> field_out: array<vec4<f32>>;

@compute @workgroup_size(64)
fn sdf_field(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&field_points) {
        return;
    }
    let p = field_points[i].xyz;
    let e = scene_sdf(p);
    let s = scene_sdf_split(p);
    field_out[2u * i] = vec4<f32>(e.x, e.y, s.x, s.y);
    field_out[2u * i + 1u] = vec4<f32>(s.z, 0.0, 0.0, 0.0);
}
