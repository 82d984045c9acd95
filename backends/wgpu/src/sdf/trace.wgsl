// SDF scenes: the hooks and shading through which subcone_passes::CtssPass
// traces a scene's field (CTSS, CTSS-R, SSAA+CTSS with the kernels' trace;
// NoAA, SSAA and semi-transparent scenes with the traces of sdf/mod.rs's
// HostTrace), and the AOV and SRAA-RT programs sphere trace it, mirroring
// subcone_cpu::sphere::SdfView::{noaa, shade, shadowed, normal_at}.
//
// Concatenated after PARAMS, the kernels' ao, cone/mask/aggregate/ctss/ctss
// trace WGSL, the field (scene_sdf_split) and the scene's materials and
// lights (shading.rs).

// Per-frame constants (sdf/mod.rs SdfFrame, 128 bytes).
struct SdfFrame {
    camera: subcone_PinholeCamera,
    background: vec3<f32>,
    max_distance: f32,
    ambient: vec3<f32>,
    max_steps: u32,
    // Ambient-occlusion rays per shaded point (0: off) and their length.
    ao_rays: u32,
    ao_radius: f32,
    // 1 under a cone-traced method (sdf/mod.rs HostTrace::Translucent).
    cone: u32,
    _pad: u32,
}

// Bindings (sdf/mod.rs, sdf/sraa.rs): frame (SdfFrame); ctss
// (subcone_CtssParams, the values CtssPass traces with); sdf_data, the
// field's scatter table, when it has one.

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

// Occlusion rays traced in the current invocation (SdfView's Tally::ao);
// the entry points hand them on to counts_out.
var<private> ao_rays_traced: u32;

// SdfView::ambient_occlusion: of frame.ao_rays fixed directions around the
// normal n (facing the ray; subcone_ao_direction, all above the surface),
// the fraction whose any-hit ray of length frame.ao_radius meets nothing.
// Each is SdfView::ao_occluded, a shadow ray towards a light that far
// (`shadowed`): a march that reaches the radius (or max_distance), a NaN
// distance or a spent step budget is open. Exactly 1 when off.
fn ambient_occlusion(p: vec3<f32>, n: vec3<f32>) -> f32 {
    let count = frame.ao_rays;
    var open = 0u;
    var traced = 0u;
    for (var i = 0u; i < count; i++) {
        let d = subcone_ao_direction(n, i, count);
        if !shadowed(p, n, d, frame.ao_radius, &traced) {
            open += 1u;
        }
    }
    ao_rays_traced += traced;
    return subcone_ao_fraction(open, count);
}

// SdfView::shade: Lambert with hard shadows and ambient light (times the
// unoccluded fraction).
fn shade(p: vec3<f32>, n0: vec3<f32>, dir: vec3<f32>, count: ptr<function, u32>) -> vec3<f32> {
    let m = min(u32(scene_sdf_split(p).z), MATERIAL_COUNT - 1u);
    let albedo = material_albedo(m, p);
    var n = n0;
    if dot(n0, dir) > 0.0 {
        n = -n0;
    }
    let ao = ambient_occlusion(p, n);
    var c = material_emission(m) + frame.ambient * ao * albedo;
    shade_lights(p, n, albedo, &c, count);
    return c;
}

// SdfView::noaa: one sphere-traced sample against `background`.
// The tallies (SdfView's Tally) are separate variables: steps, samples, shadow rays.
fn noaa_sample(o: vec3<f32>, d: vec3<f32>, background: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    let hit = subcone_sphere_trace_split(ctss, o, d);
    *steps += hit.steps;
    if hit.t >= 0.0 {
        *samples += 1u;
        let q = o + hit.t * d;
        return shade(q, normal_at(q, hit.t, ctss.tan_theta), d, shadow);
    }
    return background;
}

// The hooks of the kernels' subcone_ctss_trace (ctss/trace.wgsl): the field
// as SdfView's ConeFieldOf reads it (surface distance, safe step, material as
// the object id; scene_sdf_split returns (safe, surface, material)), its normal
// (normal_surface, SdfNode::normal) and its shading. subcone_CTSS_BATCH is
// declared by CtssPass from its desc (8 for ASAP methods, DELAYED_BATCH for
// delayed shading), and by sdf/sraa.rs for its own program; the NoAA hook
// ctss_field (subcone_sphere_trace_split's field) is
// subcone_passes::SPHERE_TRACE_HOOK on subcone_field.
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let r = scene_sdf_split(p);
    return vec3<f32>(r.y, r.x, r.z);
}

fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> {
    return normal_surface(p, h);
}

// Shadow rays traced in the current invocation (SdfView's Tally::shadow)
// by subcone_shade and the host traces; with ao_rays_traced, the pass's
// counters (subcone_counters).
var<private> shadow_rays_traced: u32;

fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    var count = 0u;
    let c = shade(p, n, dir, &count);
    shadow_rays_traced += count;
    return c;
}

// CtssPass's counts.zw: the pixel's shadow and occlusion rays.
fn subcone_counters() -> vec2<u32> {
    return vec2<u32>(shadow_rays_traced, ao_rays_traced);
}
