// SDF scenes with semi-transparent materials (CTSS §5.3), one pixel per
// invocation, mirroring subcone_cpu::sphere::SdfView::{ctss_translucent,
// noaa_translucent} (backends/cpu/src/sphere/translucent.rs):
// - CTSS, CTSS-R, SSAA+CTSS: the stepper with every sample composited through
//   subcone_cone_stepper_record_alpha_mask into the pixel's K masks; a group
//   is split where the nearest object changes between a semi-transparent
//   object and another, and the trace passes through semi-transparent
//   objects instead of stopping at their full occlusion;
// - NoAA, SSAA: sphere tracing with alpha blending along the ray.
// Samples are shaded as their groups close (ASAP), in the CPU's order.
//
// Concatenated after trace.wgsl (frame, ctss, normal_surface, normal_at,
// shade), the kernels' transparency.wgsl, ctss.wgsl and ctss/trace.wgsl
// (subcone_group_mask, through trace.wgsl's field hooks), and shading.rs's
// material_opacity. sdf/mod.rs includes it when the scene has translucency:
// its ctss_translucent_sample and noaa_translucent_sample are then the
// samplers of CtssPass's host trace (sdf/mod.rs HostTrace::Translucent).

// No group open (SdfView::ctss_translucent's group_material = None).
const NO_GROUP: u32 = 0xffffffffu;

// translucent.rs PASS_STEP: the least step, in cone radii, of the NoAA
// reference through a semi-transparent object.
const PASS_STEP: f32 = 0.04;

// ctss_translucent's sample closure: shade the group with the K masks.
fn translucent_record(st: ptr<function, subcone_ConeStepper>, agg: ptr<function, subcone_Aggregate>, o: vec3<f32>, d: vec3<f32>, axes: mat2x3<f32>, s: subcone_GroupSample, m: u32, shadow: ptr<function, u32>) {
    let q = o + s.t * d;
    let n = normal_at(q, s.t, ctss.tan_theta);
    let mask = subcone_group_mask(ctss, subcone_SplitRay(o, d, axes[0], axes[1]), s, n);
    let rec = subcone_cone_stepper_record_alpha_mask(st, mask, material_opacity(m));
    subcone_aggregate_add(agg, bitcast<f32>(rec.y), shade(q, n, d, shadow));
}

// SdfView::ctss_translucent: one CTSS sample with K transparency masks.
fn ctss_translucent_sample(o: vec3<f32>, d: vec3<f32>, background: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    let axes = subcone_cross_section_frame(d, frame.camera.up);
    var st = subcone_cone_stepper_new(ctss);
    var agg = subcone_aggregate_new();
    // The object nearest where the open group began, and the one the trace
    // is passing through.
    var group_material = NO_GROUP;
    var passing_material = 0u;
    // Every call evaluates the field once and advances the stepper once;
    // advance_object evaluates at most max_steps times, and a call that does
    // not evaluate follows one that closed a group on its full occlusion
    // (which record_alpha_mask may let pass through): the bound never cuts a
    // trace short.
    let budget = 2u * min(ctss.max_steps, 0x3fffffffu) + 8u;
    for (var i = 0u; i < budget; i++) {
        let f = scene_sdf_split(o + st.t * d);
        let m = u32(f.z);
        // One surface per group: split where the nearest object changes
        // between a semi-transparent object and another one.
        if group_material != NO_GROUP {
            if group_material != m && (material_opacity(group_material) < 1.0 || material_opacity(m) < 1.0) {
                let split = subcone_cone_stepper_split_group(&st);
                if split.kind == subcone_EVENT_SAMPLE {
                    translucent_record(&st, &agg, o, d, axes, split.sample, group_material, shadow);
                    if subcone_cone_stepper_is_passing(st) {
                        passing_material = group_material;
                    }
                }
                group_material = NO_GROUP;
            }
        }
        // Through a semi-transparent object into another one (touching it).
        if subcone_cone_stepper_is_passing(st) && m != passing_material {
            subcone_cone_stepper_end_pass(&st);
        }
        let ev = subcone_cone_stepper_advance_object(&st, f.y, f.x, m);
        let gm = select(group_material, m, group_material == NO_GROUP);
        group_material = select(NO_GROUP, gm, subcone_cone_stepper_in_group(st));
        if ev.kind == subcone_EVENT_STOP {
            break;
        }
        if ev.kind == subcone_EVENT_SAMPLE {
            translucent_record(&st, &agg, o, d, axes, ev.sample, gm, shadow);
            if subcone_cone_stepper_is_passing(st) {
                passing_material = gm;
            }
        }
    }
    *steps += st.steps;
    *samples += st.samples;
    return subcone_aggregate_resolve(agg, background, subcone_cone_stepper_background_weight(st));
}

// SdfView::noaa_translucent: one NoAA sample with alpha blending along the
// ray. At a hit of opacity alpha the ray takes alpha of the shaded colour
// (times the transmittance so far), marches through the object (steps of
// max(|d|, PASS_STEP·R_c)) until another object is nearest or it is outside
// and clear of the hit band, and traces on with transmittance ·(1 − alpha).
fn noaa_translucent_sample(o: vec3<f32>, d: vec3<f32>, background: vec3<f32>, steps: ptr<function, u32>, samples: ptr<function, u32>, shadow: ptr<function, u32>) -> vec3<f32> {
    let hard = subcone_occlusion_thresholds(ctss.eps).y;
    var color = vec3<f32>(0.0);
    var transmittance = 1.0;
    var t0 = ctss.t_min;
    var budget = ctss.max_steps;
    // Every round but the last spends at least one evaluation of the budget.
    for (var round_i = 0u; round_i <= ctss.max_steps; round_i++) {
        var params = ctss;
        params.t_min = t0;
        params.max_steps = budget;
        let hit = subcone_sphere_trace_split(params, o, d);
        *steps += hit.steps;
        budget -= min(hit.steps, budget);
        if !(hit.t >= 0.0) {
            return color + transmittance * background;
        }
        *samples += 1u;
        let q = o + hit.t * d;
        let hit_material = u32(scene_sdf_split(q).z);
        let alpha = material_opacity(hit_material);
        color += transmittance * alpha * shade(q, normal_at(q, hit.t, ctss.tan_theta), d, shadow);
        transmittance *= 1.0 - alpha;
        if transmittance <= 0.0 {
            return color;
        }
        // Through the object: on until outside and clear of the hit band.
        var t = hit.t;
        // Each iteration spends one evaluation of the budget.
        for (var j = 0u; j <= ctss.max_steps; j++) {
            if budget == 0u || subcone_is_nan(t) || t >= ctss.t_max {
                return color + transmittance * background;
            }
            let f = scene_sdf_split(o + t * d);
            budget -= 1u;
            *steps += 1u;
            let dist = f.y;
            if subcone_is_nan(dist) {
                return color + transmittance * background;
            }
            // Another object is nearest (or, if it touches this one, the ray
            // is inside it): trace on from here.
            if u32(f.z) != hit_material {
                break;
            }
            let rc = subcone_cone_radius(t, ctss.tan_theta);
            if dist > 0.0 && subcone_cone_occlusion(dist, rc) <= hard {
                break;
            }
            // Rust's safe.min(dist): a NaN safe step yields dist.
            var s = dist;
            if dist < 0.0 {
                s = -dist;
            } else if !subcone_is_nan(f.x) && f.x < dist {
                s = f.x;
            }
            t = subcone_advance(t, s, PASS_STEP, rc);
        }
        t0 = t;
    }
    return color + transmittance * background;
}
