// WGSL mirror of subcone_kernels::ctss::group_mask (with normal_step and
// sheet_across): the visibility mask of a closed hit group (CTSS §3.4–3.5)
// with the normals it needs, and the thin-shell rule beyond the paper (see
// the Rust doc comment): when the normals where the cone first and last
// touched the group oppose, a face-on sheet hit by the central ray that spans
// the cone's cross-section covers the pixel, and an oblique shell longer than
// SHELL_LENGTH cone radii whose projected normals oppose too shows the union
// of both faces' half-planes.
//
// Needs PARAMS, cone.wgsl, mask.wgsl and ctss.wgsl (subcone_GroupSample and
// the CtssParams decoders). The field is the including shader's, through two
// hooks:
//     fn subcone_field(p: vec3<f32>) -> vec3<f32>   // (distance, safe step, object id as f32)
//     fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32>   // unit normal, differences of step h

// subcone_kernels::ctss::FACE_ON_COS — |n·dir| above which a surface is seen face-on (45°).
const subcone_FACE_ON_COS: f32 = 0.70710677f;
// subcone_kernels::ctss::SHELL_LENGTH — least length, in cone radii, of a
// group that passed through an oblique thin shell.
const subcone_SHELL_LENGTH: f32 = 5.0;

// subcone_kernels::ctss::normal_step — a quarter of the cone radius, never
// below 1e-5 of the depth (or of 1).
fn subcone_normal_step(t: f32, tan_theta: f32) -> f32 {
    var floor_h = 1e-5f;
    if t > 1.0 {
        floor_h = 1e-5f * t;
    }
    let h = 0.25 * t * tan_theta;
    if h > floor_h {
        return h;
    }
    return floor_h;
}

// subcone_kernels::ctss::sheet_across (private): the field is within half a
// cone radius of a surface a full radius from the ray at depth t along
// ±right and ±up. NaN distances say no.
fn subcone_sheet_across(origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, t: f32, tan_theta: f32) -> bool {
    let rc = subcone_cone_radius(t, tan_theta);
    let c = origin + t * dir;
    for (var i = 0u; i < 4u; i++) {
        var e: vec3<f32>;
        switch i {
            case 0u: { e = right; }
            case 1u: { e = -right; }
            case 2u: { e = up; }
            default: { e = -up; }
        }
        if !(subcone_field(c + e * rc).x < 0.5 * rc) {
            return false;
        }
    }
    return true;
}

// The normal group_mask wants at depth t: the shading normal at the
// sample's own depth, else the field's at that depth (normal_step).
fn subcone_group_mask_normal_at(origin: vec3<f32>, dir: vec3<f32>, sample: subcone_GroupSample, normal: vec3<f32>, t: f32, tan_theta: f32) -> vec3<f32> {
    if t == sample.t {
        return normal;
    }
    return subcone_normal(origin + t * dir, subcone_normal_step(t, tan_theta));
}

// subcone_kernels::ctss::group_mask — the mask of a closed group; normal is
// the shading normal at the group's sample point.
fn subcone_group_mask(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, sample: subcone_GroupSample, normal: vec3<f32>) -> u32 {
    let placement = subcone_ctss_placement(params);
    let omega = sample.occlusion;
    if !subcone_needs_normal(omega, placement) {
        return subcone_visibility_mask(omega, vec2<f32>(0.0), placement);
    }
    let tan = params.tan_theta;
    if !subcone_ctss_is_paper(params) {
        let n1 = subcone_group_mask_normal_at(origin, dir, sample, normal, sample.t_first, tan);
        let n2 = subcone_group_mask_normal_at(origin, dir, sample, normal, sample.t_last, tan);
        if dot(n1, n2) < 0.0 {
            let face_on = abs(dot(n1, dir)) > subcone_FACE_ON_COS && abs(dot(n2, dir)) > subcone_FACE_ON_COS;
            if face_on {
                if sample.hard != 0u && subcone_sheet_across(origin, dir, right, up, sample.t, tan) {
                    return subcone_FULL_MASK;
                }
            } else {
                let p1 = subcone_project_normal(n1, right, up);
                let p2 = subcone_project_normal(n2, right, up);
                let is_long = sample.t_last - sample.t_first > subcone_SHELL_LENGTH * subcone_cone_radius(sample.t_first, tan);
                if is_long && dot(p1, p2) < 0.0 {
                    return subcone_visibility_mask(omega, p1, placement) | subcone_visibility_mask(omega, p2, placement);
                }
            }
        }
    }
    let peak = subcone_group_mask_normal_at(origin, dir, sample, normal, sample.t_occlusion, tan);
    return subcone_visibility_mask(omega, subcone_project_normal(peak, right, up), placement);
}
