// SDF scenes: sphere tracing (NoAA, SSAA) and cone tracing (CTSS, CTSS-R,
// SSAA+CTSS) of one pixel per invocation, mirroring
// subcone_cpu::sphere::SdfView::{render, noaa, ctss, shade, shadowed, normal_at}.
//
// Concatenated after PARAMS, the kernels' cone/mask/aggregate/ctss WGSL, the
// field (scene_sdf_split) and the scene's materials and lights (shading.rs).

// Per-frame constants (sdf/mod.rs SdfFrame).
struct SdfFrame {
    position: vec3<f32>,
    width: u32,
    forward: vec3<f32>,
    height: u32,
    right: vec3<f32>,
    // tan(fov_y / 2)
    half: f32,
    up: vec3<f32>,
    max_distance: f32,
    background: vec3<f32>,
    max_steps: u32,
    ambient: vec3<f32>,
    // Samples per pixel side.
    side: u32,
    // 1: cone tracing (CTSS family), 0: sphere tracing.
    cone: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Bindings (sdf/mod.rs): frame (SdfFrame); ctss (subcone_CtssParams);
// color_out, the pixels' colours; counts_out, per pixel (SDF evaluations,
// shaded samples, shadow rays, 0); sdf_data, the field's scatter table, when
// it has one.

// The field as the kernels' subcone_sphere_trace_split wants it: (surface, safe step).
fn ctss_field(p: vec3<f32>) -> vec2<f32> {
    let r = scene_sdf_split(p);
    return vec2<f32>(r.y, r.x);
}

// Camera::ray: origin is the camera position; the unit direction through image point px.
fn camera_dir(px: vec2<f32>) -> vec3<f32> {
    let w = f32(max(frame.width, 1u));
    let h = f32(max(frame.height, 1u));
    let u = (2.0 * px.x / w - 1.0) * frame.half * (w / h);
    let v = (1.0 - 2.0 * px.y / h) * frame.half;
    let d = frame.forward + u * frame.right + v * frame.up;
    return d * (1.0 / length(d));
}

// SdfNode::normal_surface: tetrahedral differences of the surface distance,
// step raised to 16 ulps of |p|, +y when the gradient vanishes.
fn normal_surface(p: vec3<f32>, h0: f32) -> vec3<f32> {
    let a = abs(p);
    let fl = max(max(max(a.x, a.y), a.z) * 0.0000019073486328125, 1e-30f);
    var h = fl;
    if subcone_is_finite(h0) {
        h = max(h0, fl);
    }
    var n = vec3<f32>(0.0);
    for (var i = 0u; i < 4u; i++) {
        var k: vec3<f32>;
        switch i {
            case 0u: { k = vec3<f32>(1.0, -1.0, -1.0); }
            case 1u: { k = vec3<f32>(-1.0, -1.0, 1.0); }
            case 2u: { k = vec3<f32>(-1.0, 1.0, -1.0); }
            default: { k = vec3<f32>(1.0, 1.0, 1.0); }
        }
        n += k * scene_sdf_split(p + k * h).y;
    }
    let rcp = 1.0 / length(n);
    if subcone_is_finite(rcp) && rcp > 0.0 {
        return n * rcp;
    }
    return vec3<f32>(0.0, 1.0, 0.0);
}

// SdfView::normal_at: differences over a quarter of the cone radius, never
// below 1e-5 of the depth.
fn normal_at(p: vec3<f32>, t: f32, tan_theta: f32) -> vec3<f32> {
    let h = max(0.25 * t * tan_theta, 1e-5f * max(t, 1.0));
    return normal_surface(p, h);
}

// SdfView::shadowed: plain sphere tracing towards a light.
fn shadowed(p: vec3<f32>, n: vec3<f32>, l: vec3<f32>, dist: f32, count: ptr<function, u32>) -> bool {
    *count += 1u;
    let eps = 1e-4f * (1.0 + length(p));
    let o = p + n * (4.0 * eps);
    var t = 0.0;
    let limit = min(dist, frame.max_distance);
    for (var i = 0u; i < frame.max_steps; i++) {
        if t >= limit {
            return false;
        }
        let f = scene_sdf_split(o + l * t);
        if subcone_is_nan(f.y) {
            return false;
        }
        if f.y < eps * (1.0 + t * 1e-3f) {
            return true;
        }
        var s = f.y;
        if !subcone_is_nan(f.x) && f.x < f.y {
            s = f.x;
        }
        let next = t + s;
        if next > t {
            t = next;
        } else {
            t = subcone_next_up(t);
        }
    }
    return false;
}

// SdfView::shade: Lambert with hard shadows and ambient light.
fn shade(p: vec3<f32>, n0: vec3<f32>, dir: vec3<f32>, count: ptr<function, u32>) -> vec3<f32> {
    let m = min(u32(scene_sdf_split(p).z), MATERIAL_COUNT - 1u);
    let albedo = material_albedo(m, p);
    var n = n0;
    if dot(n0, dir) > 0.0 {
        n = -n0;
    }
    var c = material_emission(m) + frame.ambient * albedo;
    shade_lights(p, n, albedo, &c, count);
    return c;
}

// SdfView::noaa: one sphere-traced sample.
// The tallies (SdfView's Tally) are separate variables: steps, samples, shadow rays.
fn noaa_sample(o: vec3<f32>, d: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    let hit = subcone_sphere_trace_split(ctss, o, d);
    *steps += hit.steps;
    if hit.t >= 0.0 {
        *samples += 1u;
        let q = o + hit.t * d;
        return shade(q, normal_at(q, hit.t, ctss.tan_theta), d, shadow);
    }
    return frame.background;
}

// PENDING, the samples shaded together in ctss_sample (the authors'
// CTSS_NUM_SAMPLES), is declared by sdf/mod.rs before this file: 8 for ASAP
// methods, DELAYED_BATCH for delayed shading.

// SdfView::ctss: one cone-traced sample (Algorithm 1 through subcone_ConeStepper).
fn ctss_sample(o: vec3<f32>, d: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    let axes = subcone_cross_section_frame(d, frame.up);
    var st = subcone_cone_stepper_new(ctss);
    var agg = subcone_aggregate_new();
    let placement = subcone_ctss_placement(ctss);
    // advance_split evaluates at most max_steps times and stops within two
    // more calls: the bounds never cut a trace short.
    let budget = min(ctss.max_steps, 0x7fffffffu) + 4u;
    // Samples wait here, in order, and are shaded together when the march
    // ends or PENDING of them wait: the lanes of a SIMD group march together
    // and shade together, instead of idling while one lane traces shadows.
    // Eq. 6 adds them in the same order as the CPU, so the result is the same.
    var pending: array<vec4<f32>, PENDING>;
    var pending_w: array<f32, PENDING>;
    var done = false;
    for (var round_i = 0u; round_i < budget && !done; round_i++) {
        var k = 0u;
        for (var i = 0u; i < budget; i++) {
            let f = scene_sdf_split(o + st.t * d);
            let ev = subcone_cone_stepper_advance_split(&st, f.y, f.x);
            if ev.kind == subcone_EVENT_STOP {
                done = true;
                break;
            }
            if ev.kind == subcone_EVENT_SAMPLE {
                let s = ev.sample;
                // Shading normal at the sample point; the mask's normal where
                // the group's peak occlusion was measured, only when the mask
                // needs it.
                var n = vec3<f32>(0.0);
                var nm = vec3<f32>(0.0);
                for (var j = 0u; j < 2u; j++) {
                    let tt = select(s.t, s.t_occlusion, j == 1u);
                    if j == 1u && !(s.t_occlusion != s.t && subcone_needs_normal(s.occlusion, placement)) {
                        nm = n;
                        break;
                    }
                    let nn = normal_at(o + tt * d, tt, ctss.tan_theta);
                    if j == 0u {
                        n = nn;
                    } else {
                        nm = nn;
                    }
                }
                let rec = subcone_cone_stepper_record(&st, s, subcone_project_normal(nm, axes[0], axes[1]));
                pending[k] = vec4<f32>(n, s.t);
                pending_w[k] = bitcast<f32>(rec.y);
                k += 1u;
                if k == PENDING {
                    break;
                }
            }
        }
        for (var j = 0u; j < k; j++) {
            let q = o + pending[j].w * d;
            subcone_aggregate_add(&agg, pending_w[j], shade(q, pending[j].xyz, d, shadow));
        }
    }
    *steps += st.steps;
    *samples += st.samples;
    return subcone_aggregate_resolve(agg, frame.background, subcone_cone_stepper_background_weight(st));
}

// SdfView::render, one pixel: side × side samples at sub-pixel centres.
@compute @workgroup_size(8, 8)
fn sdf_render(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.width || gid.y >= frame.height {
        return;
    }
    let side = max(frame.side, 1u);
    var steps = 0u;
    var samples = 0u;
    var shadow = 0u;
    var sum = vec3<f32>(0.0);
    for (var sy = 0u; sy < side; sy++) {
        for (var sx = 0u; sx < side; sx++) {
            let off = vec2<f32>((f32(sx) + 0.5) / f32(side), (f32(sy) + 0.5) / f32(side));
            let d = camera_dir(vec2<f32>(f32(gid.x), f32(gid.y)) + off);
            if frame.cone != 0u {
                sum += ctss_sample(frame.position, d, &steps, &samples, &shadow);
            } else {
                sum += noaa_sample(frame.position, d, &steps, &samples, &shadow);
            }
        }
    }
    let i = gid.y * frame.width + gid.x;
    color_out[i] = vec4<f32>(sum / f32(side * side), 1.0);
    counts_out[i] = vec4<u32>(steps, samples, shadow, 0u);
}
