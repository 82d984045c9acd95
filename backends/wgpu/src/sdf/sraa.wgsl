// SRAA-RT on SDF scenes (Chiu et al., §3), passes "shading" and "geometry":
// the twins of subcone_cpu::sphere::SdfView::{sraa_shading_pass,
// sraa_geometry_pass, hit, shadow_states, shade_layers}, one invocation per
// pixel. Follows trace.wgsl (SdfFrame, normal_at, shadowed,
// ambient_occlusion), the scene's materials and `light_incident`
// (shading.rs) and the generated header (NL, LAYER_LIGHTS, SCENE_LIGHTS,
// SINGLE, SHADOWS, MATERIAL and the get_/put_ accessors of the optional
// buffers). Pass "antialiasing" (the paper's pass 2) is
// subcone_passes::SraaPass over these buffers (sdf/sraa.rs): the kernels'
// reconstruction loop (subcone_sraa_reconstruct_run) with eq. 1 / eq. 2
// weights.
//
// SDF scenes have no mirrors (the plan refuses them): no secondary buffers.

// Bindings (sdf/sraa.rs): frame (SdfFrame); sraa (subcone_SraaParams);
// ctss (subcone_CtssParams);
// color, the resolved pixels; counts_out, per pixel (SDF evaluations, shaded
// samples, shadow rays, occlusion rays); geo, the shaded samples' geometry;
// values, their NL layers; shadow_buf, their shadow states (with light
// layers); sub_geo_buf and sub_shadow_buf, the four subsamples' geometry and
// shadow states; sdf_data, the field's scatter table, when it has one.

struct SdfHit {
    q: vec3<f32>,
    hit: bool,
    // Facing the ray.
    n: vec3<f32>,
}

// SdfView::hit: the surface hit by the NoAA trace, its normal turned to face
// the ray; `hit` false on a miss (a NaN distance, the step budget or the ray's
// reach ends the trace: subcone_sphere_trace_split).
fn sdf_hit(o: vec3<f32>, d: vec3<f32>, steps: ptr<function, u32>) -> SdfHit {
    var r: SdfHit;
    r.hit = false;
    let h = subcone_sphere_trace_split(ctss, o, d);
    *steps += h.steps;
    if h.t >= 0.0 {
        r.hit = true;
        r.q = o + h.t * d;
        var n = normal_at(r.q, h.t, ctss.tan_theta);
        if dot(n, d) > 0.0 {
            n = -n;
        }
        r.n = n;
    }
    return r;
}

// Camera::view_depth.
fn view_depth(q: vec3<f32>) -> f32 {
    return dot(q - frame.camera.position, frame.camera.forward);
}

// SdfView::shadow_states: bit l set = light l shadowed at q (normal n facing
// the ray). A light facing away shadows without a ray, a light that does not
// reach q leaves it lit; only the lights in `cast_mask` are traced, the others
// take their bit from `inherited` (adaptive subpixel shadows).
fn shadow_states(q: vec3<f32>, n: vec3<f32>, cast_mask: u32, inherited: u32, count: ptr<function, u32>) -> u32 {
    var bits = 0u;
    for (var l = 0u; l < SCENE_LIGHTS; l++) {
        let inc = light_incident(l, q);
        if !inc.ok {
            continue;
        }
        if dot(inc.direction, n) <= 0.0 {
            bits |= 1u << l;
        } else if (cast_mask & (1u << l)) == 0u {
            bits |= inherited & (1u << l);
        } else if shadowed(q, n, inc.direction, inc.distance, count) {
            bits |= 1u << l;
        }
    }
    return bits;
}

// SdfView::shade_layers (§3.2): layer 0 the shadow-independent part (emission
// and ambient, times the unoccluded fraction), layer 1 + l light l's direct
// part where `bits` says it is lit; without light layers, all in layer 0, in
// the same order.
fn shade_layers(j: u32, q: vec3<f32>, n: vec3<f32>, bits: u32) {
    let m = min(u32(scene_sdf_split(q).z), MATERIAL_COUNT - 1u);
    let albedo = material_albedo(m, q);
    let ao = ambient_occlusion(q, n);
    var base = material_emission(m) + frame.ambient * ao * albedo;
    for (var l = 0u; l < SCENE_LIGHTS; l++) {
        var direct = vec3<f32>(0.0);
        if (bits & (1u << l)) == 0u {
            let inc = light_incident(l, q);
            if inc.ok {
                let cos = dot(inc.direction, n);
                if cos > 0.0 {
                    direct = albedo * 0.31830987f * cos * inc.irradiance;
                }
            }
        }
        if LAYER_LIGHTS > 0u {
            put_value(j, 1u + l, direct);
        } else {
            base += direct;
        }
    }
    put_value(j, 0u, base);
}

fn pixel_centre(x: u32, y: u32) -> vec2<f32> {
    return vec2<f32>(f32(x) + 0.5, f32(y) + 0.5);
}

// Pass "shading" (SdfView::sraa_shading_pass): one sample per pixel at the
// preset's shaded offset, sphere traced and shaded into layers.
@compute @workgroup_size(8, 8)
fn sdf_sraa_shade(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.camera.width || gid.y >= frame.camera.height {
        return;
    }
    let j = gid.y * frame.camera.width + gid.x;
    var steps = 0u;
    var samples = 0u;
    var shadow = 0u;
    ao_rays_traced = 0u;
    for (var l = 0u; l < NL; l++) {
        put_value(j, l, vec3<f32>(0.0));
    }
    geo[j] = subcone_Geometry(vec3<f32>(0.0), subcone_inf());
    put_shadow(j, 0u);
    let d = subcone_pinhole_dir(frame.camera, pixel_centre(gid.x, gid.y) + subcone_sraa_shaded_offset(sraa));
    let h = sdf_hit(frame.camera.position, d, &steps);
    if !h.hit {
        put_value(j, 0u, frame.background);
    } else {
        samples += 1u;
        geo[j] = subcone_Geometry(h.n, view_depth(h.q));
        var bits = 0u;
        if SHADOWS {
            bits = shadow_states(h.q, h.n, 0xffffffffu, 0u, &shadow);
        }
        put_shadow(j, bits);
        shade_layers(j, h.q, h.n, bits);
    }
    counts_out[j] = vec4<u32>(steps, samples, shadow, ao_rays_traced);
}

// render.rs `shadow_agreement` over the shaded samples of the neighbourhood
// the pixel's subsamples are reconstructed from: the lights whose subpixel
// shadow rays must be cast (x) and the states the others inherit (y); a
// light is skipped where every neighbour's layer of it is black or every
// neighbour agrees on its state (triangles/subpixel.wgsl's, on these buffers).
fn shadow_agreement(x: u32, y: u32) -> vec2<u32> {
    let all_lights = (1u << LAYER_LIGHTS) - 1u;
    var all_shadowed = 0xffffffffu;
    var any_shadowed = 0u;
    var dark = all_lights;
    let nb = subcone_neighbourhood(x, y, subcone_SHADED_SAMPLE, vec2<f32>(0.0), subcone_sraa_radius(sraa), frame.camera.width, frame.camera.height);
    for (var py = nb.y0; py < nb.y1; py++) {
        for (var px = nb.x0; px < nb.x1; px++) {
            let jj = py * frame.camera.width + px;
            let b = get_shadow(jj);
            all_shadowed &= b;
            any_shadowed |= b;
            for (var l = 0u; l < LAYER_LIGHTS; l++) {
                if any(get_value(jj, 1u + l) != vec3<f32>(0.0)) {
                    dark &= ~(1u << l);
                }
            }
        }
    }
    let agreed = (all_shadowed | ~any_shadowed | dark) & all_lights;
    return vec2<u32>(all_lights & ~agreed, all_shadowed & all_lights);
}

// Pass "geometry" (SdfView::sraa_geometry_pass, the paper's pass 1): the
// pixel's four subsamples sphere traced for geometry and, with subpixel
// shadows, their shadow states; a subsample that is the shaded sample copies
// the shading pass's.
@compute @workgroup_size(8, 8)
fn sdf_sraa_geometry(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= frame.camera.width || gid.y >= frame.camera.height {
        return;
    }
    let j = gid.y * frame.camera.width + gid.x;
    var steps = 0u;
    var shadow = 0u;
    var agreement = vec2<u32>(0xffffffffu, 0u);
    if HAS_SUB_SHADOW {
        agreement = shadow_agreement(gid.x, gid.y);
    }
    for (var k = 0u; k < 4u; k++) {
        if subcone_sraa_is_shaded_subsample(sraa, k) {
            put_sub_geo(j, k, geo[j]);
            put_sub_shadow(j, k, get_shadow(j));
            continue;
        }
        put_sub_geo(j, k, subcone_Geometry(vec3<f32>(0.0), subcone_inf()));
        put_sub_shadow(j, k, 0u);
        let d = subcone_pinhole_dir(frame.camera, pixel_centre(gid.x, gid.y) + subcone_subpixel_offset(k));
        let h = sdf_hit(frame.camera.position, d, &steps);
        if !h.hit {
            continue;
        }
        put_sub_geo(j, k, subcone_Geometry(h.n, view_depth(h.q)));
        if HAS_SUB_SHADOW {
            put_sub_shadow(j, k, shadow_states(h.q, h.n, agreement.x, agreement.y, &shadow));
        }
    }
    counts_out[j] += vec4<u32>(steps, 0u, shadow, 0u);
}
