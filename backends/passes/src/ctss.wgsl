// CtssPass (ctss.rs): cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10,
// §5.3) of the host's signed distance field, N × N cones per pixel, through
// the kernels' trace subcone_ctss_trace (subcone_kernels::ctss::TRACE_WGSL),
// the twin of subcone_kernels::ctss::trace_field, or the host's own
// subcone_trace (CtssTrace::Host).
//
// Follows the kernels (PARAMS, with subcone_PinholeCamera and
// subcone_pinhole_dir; cone, mask, aggregate, ctss, ctss/trace), the host's
// WGSL (subcone_field, subcone_shade, optionally subcone_normal; and
// subcone_CTSS_BATCH, which ctss.rs declares), the desc's variant
// (subcone_pass_SIDE, subcone_pass_trace, subcone_pass_color,
// subcone_pass_store, which ctss.rs writes) and the declarations ctss.rs
// generates: subcone_pass_frame (CtssUniform), subcone_pass_params
// (subcone_CtssParams), subcone_pass_output (a storage texture or buffer)
// and, with counts, subcone_pass_counts; with depth, subcone_pass_depth.

// ctss.rs `CtssUniform` (192 bytes): the camera (CtssView: the pinhole of
// CtssCamera::ray, or the eye and frame of a CtssProjection; its width and
// height are the rectangle's), the background, how rays are made
// (projection: 0 pinhole, 1 perspective, 2 orthographic), the projection's
// NDC-to-world matrix, the forward axis and offset of view depth, the
// rectangle's origin in the output and the output's row length.
struct CtssUniform {
    camera: subcone_PinholeCamera,
    background: vec3<f32>,
    projection: u32,
    inverse_view_projection: mat4x4<f32>,
    forward: vec3<f32>,
    depth_offset: f32,
    origin: vec2<u32>,
    row_length: u32,
    _pad: u32,
}

// A pixel's index in the row-major buffers.
fn subcone_pass_index(p: vec2<u32>) -> u32 {
    return p.y * subcone_pass_frame.row_length + p.x;
}

// The world point of NDC (xy, z) through the projection.
fn subcone_pass_unproject(f: CtssUniform, xy: vec2<f32>, z: f32) -> vec3<f32> {
    let h = f.inverse_view_projection * vec4<f32>(xy, z, 1.0);
    return h.xyz / h.w;
}

// The ray (origin, unit direction) of image point p of the rectangle
// (pixels, y down): the pinhole's (subcone_pinhole_dir from the eye), or,
// for a CtssProjection, from the eye through the unprojected point at NDC
// depth 1/2 (perspective), or parallel through the points at NDC depths
// 1/4 and 3/4 from the plane of view depth 0 (orthographic).
fn subcone_pass_ray(f: CtssUniform, p: vec2<f32>) -> array<vec3<f32>, 2> {
    if f.projection == 0u {
        return array<vec3<f32>, 2>(f.camera.position, subcone_pinhole_dir(f.camera, p));
    }
    let w = f32(max(f.camera.width, 1u));
    let h = f32(max(f.camera.height, 1u));
    let ndc = vec2<f32>(2.0 * p.x / w - 1.0, 1.0 - 2.0 * p.y / h);
    if f.projection == 1u {
        let q = subcone_pass_unproject(f, ndc, 0.5);
        return array<vec3<f32>, 2>(f.camera.position, normalize(q - f.camera.position));
    }
    let a = subcone_pass_unproject(f, ndc, 0.25);
    var d = normalize(subcone_pass_unproject(f, ndc, 0.75) - a);
    if dot(d, f.forward) < 0.0 {
        d = -d;
    }
    let o = a - d * ((dot(a, f.forward) + f.depth_offset) / dot(d, f.forward));
    return array<vec3<f32>, 2>(o, d);
}

// One pixel of the rectangle: the mean of its subcone_pass_SIDE² cones
// through the sub-pixel centres (SSAA over CTSS; one cone through the
// centre when the side is 1), each about the ray of subcone_pass_ray with
// the cross-section axes of subcone_cross_section_frame; its coverage alpha
// (the mean of subcone_ctss_coverage_alpha) and view depth (the least over
// its cones of the nearest contributing group's, +inf for none), written at
// the rectangle's origin + gid.
@compute @workgroup_size(8, 8)
fn subcone_pass_ctss_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let f = subcone_pass_frame;
    if gid.x >= f.camera.width || gid.y >= f.camera.height {
        return;
    }
    let side = subcone_pass_SIDE;
    var steps = 0u;
    var samples = 0u;
    var sum = vec3<f32>(0.0);
    var alpha = 0.0;
    var depth = subcone_inf();
    var have_depth = false;
    for (var sy = 0u; sy < side; sy++) {
        for (var sx = 0u; sx < side; sx++) {
            let off = vec2<f32>((f32(sx) + 0.5) / f32(side), (f32(sy) + 0.5) / f32(side));
            let ray = subcone_pass_ray(f, vec2<f32>(f32(gid.x), f32(gid.y)) + off);
            let d = ray[1];
            let axes = subcone_cross_section_frame(d, f.camera.up);
            let r = subcone_pass_trace(subcone_pass_params, ray[0], d, axes[0], axes[1], f.background);
            sum += r.color;
            steps += r.steps;
            samples += r.samples;
            alpha += subcone_ctss_coverage_alpha(r.coverage, r.stop);
            if subcone_is_finite(r.depth) {
                let z = r.depth * dot(d, f.forward) + (dot(ray[0], f.forward) + f.depth_offset);
                if !have_depth || z < depth {
                    depth = z;
                    have_depth = true;
                }
            }
        }
    }
    let n = f32(side * side);
    subcone_pass_store(f.origin + gid.xy, subcone_pass_color(sum / n, alpha / n), depth, steps, samples);
}
