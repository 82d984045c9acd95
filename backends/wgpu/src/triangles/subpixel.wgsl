// SRAA and SRAA-RT, passes "shading" and "geometry": subcone-cpu render.rs
// `subpixel`, one invocation per pixel. Follows trace.wgsl and the generated
// frame header (layout constants NL, LAYER_LIGHTS, SINGLE, SECONDARY_LAYERS,
// SHADOWS, SECONDARY_SHADING, and accessors get_/put_ for the optional
// buffers: absent buffers read as the CPU's initial values and ignore writes).
// The shaded samples' geometry (get_geo/put_geo) and layers
// (get_value/put_value, layer l of pixel j) go through the header too:
// SRAA-RT keeps them in buffers for its resolve (sraa.wgsl), hybrid SRAA
// writes them into the textures SraaPass reads (resolve.rs).

fn geometry_miss() -> subcone_Geometry {
    return subcone_Geometry(vec3<f32>(0.0), subcone_inf());
}

// render.rs NO_SECONDARY: NaN depth, which the bilateral weight excludes.
fn no_secondary() -> subcone_Geometry {
    return subcone_Geometry(vec3<f32>(0.0), bitcast<f32>(0x7fc00000u));
}

fn pixel_centre(x: u32, y: u32) -> vec2<f32> {
    return vec2<f32>(f32(x) + 0.5, f32(y) + 0.5);
}

// Pass "shading" (render.rs `subpixel`, first pass): one shaded sample per pixel
// where the preset puts it (sraa::SraaParams::shaded_offset: subsample 0, the
// paper's, or the pixel centre). SRAA keeps one layer (the final colour);
// SRAA-RT keeps the shadow-independent part, one layer per light (gated by its
// shadow state, eq. 2) and, on mirrors, the same split of the reflected
// radiance with the secondary hit's geometry and shadow states (§3.3). Every
// layer carries its mirror factor.
fn shade_pixel(x: u32, y: u32, j: u32, c: ptr<function, Counts>) {
    for (var l = 0u; l < NL; l++) {
        put_value(j, l, vec3<f32>(0.0));
    }
    put_geo2(j, no_secondary());
    let p = pixel_centre(x, y) + subcone_sraa_shaded_offset(frame.sraa);
    let d = camera_ray(p);
    (*c).primary += 1u;
    let sf = intersect(frame.cam_pos, d, 0.0);
    if MATERIAL {
        put_albedo(j, vec4<f32>(primary_albedo(sf), 0.0));
    }
    if !sf.hit {
        put_geo(j, geometry_miss());
        put_value(j, 0u, frame.background);
        return;
    }
    (*c).shaded += 1u;
    put_geo(j, primary_geometry(sf));
    var sh = 0u;
    if SHADOWS {
        sh = shadow_states(sf, c);
    }
    let pa = parts(sf, sh, ambient_occlusion(sf, c));
    let m = pa.mirror;
    let reflects = m > 0.0 && SECONDARY_SHADING && frame.reflection_depth > 0u;
    if SINGLE {
        let dif = diffuse(pa);
        if reflects {
            (*c).secondary += 1u;
            let r = radiance(sf.p + sf.ng * frame.eps, reflect_dir(d, sf.n), 1u, c);
            put_value(j, 0u, (1.0 - m) * dif + m * r);
        } else if m > 0.0 {
            put_value(j, 0u, (1.0 - m) * dif);
        } else {
            put_value(j, 0u, dif);
        }
        return;
    }
    if LAYER_LIGHTS > 0u {
        put_shadow(j, sh);
        put_value(j, 0u, (1.0 - m) * pa.base);
        for (var l = 0u; l < LAYER_LIGHTS; l++) {
            put_value(j, 1u + l, (1.0 - m) * pa.direct[l]);
        }
    } else {
        put_value(j, 0u, (1.0 - m) * diffuse(pa));
    }
    if !reflects {
        return;
    }
    (*c).secondary += 1u;
    let rd = reflect_dir(d, sf.n);
    let sb = 1u + LAYER_LIGHTS;
    let s2 = intersect(sf.p + sf.ng * frame.eps, rd, 0.0);
    if !s2.hit {
        put_geo2(j, geometry_miss());
        let bg = m * frame.background;
        if SECONDARY_LAYERS {
            put_value(j, sb, bg);
        } else {
            put_value(j, 0u, get_value(j, 0u) + bg);
        }
        return;
    }
    (*c).shaded += 1u;
    var sh2 = 0u;
    if SHADOWS {
        sh2 = shadow_states(s2, c);
    }
    // No ambient occlusion at mirror hits.
    let p2 = parts(s2, sh2, 1.0);
    let m2 = p2.mirror;
    var deeper = vec3<f32>(0.0);
    if m2 > 0.0 && frame.reflection_depth > 1u {
        (*c).secondary += 1u;
        deeper = radiance(s2.p + s2.ng * frame.eps, reflect_dir(rd, s2.n), 2u, c);
    }
    if SECONDARY_LAYERS {
        put_geo2(j, subcone_Geometry(s2.n, sf.t + s2.t));
        if LAYER_LIGHTS > 0u {
            put_shadow2(j, sh2);
            put_value(j, sb, m * ((1.0 - m2) * p2.base + m2 * deeper));
            for (var l = 0u; l < LAYER_LIGHTS; l++) {
                put_value(j, sb + 1u + l, m * (1.0 - m2) * p2.direct[l]);
            }
        } else {
            put_value(j, sb, m * ((1.0 - m2) * diffuse(p2) + m2 * deeper));
        }
    } else {
        // Reflections forced off: fold them into the primary base.
        put_value(j, 0u, get_value(j, 0u) + m * ((1.0 - m2) * diffuse(p2) + m2 * deeper));
    }
}

@compute @workgroup_size(8, 8)
fn shade_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    var c = counts_zero();
    shade_pixel(id.x, id.y, id.y * frame.width + id.x, &c);
    counts_flush(c);
}

// render.rs `shadow_agreement` (adaptive subpixel shadow rays): from the shaded
// samples of the neighbourhood the pixel's subsamples are reconstructed from,
// the lights whose subpixel shadow rays must be cast (x) and the states the
// others inherit (y). A light is skipped when every neighbour's layer of it is
// black (the layer reconstructs to 0 whatever the gate: exact) or every
// neighbour agrees on its shadow state (inherited; differs from the exhaustive
// ray only inside a shadow no shaded sample around sees, where eq. 2 would gate
// every neighbour out and fall back to the nearest one). `secondary` reads the
// secondary hits' states; `first` is the group's base layer.
fn shadow_agreement(x: u32, y: u32, secondary: bool, first: u32) -> vec2<u32> {
    let all_lights = (1u << LAYER_LIGHTS) - 1u;
    var all_shadowed = 0xffffffffu;
    var any_shadowed = 0u;
    var dark = all_lights;
    // Only which pixels: the distances are not read.
    let nb = subcone_neighbourhood(x, y, subcone_SHADED_SAMPLE, vec2<f32>(0.0), subcone_sraa_radius(frame.sraa), frame.width, frame.height);
    for (var py = nb.y0; py < nb.y1; py++) {
        for (var px = nb.x0; px < nb.x1; px++) {
            let jj = py * frame.width + px;
            var b = get_shadow(jj);
            if secondary {
                b = get_shadow2(jj);
            }
            all_shadowed &= b;
            any_shadowed |= b;
            for (var l = 0u; l < LAYER_LIGHTS; l++) {
                if any(get_value(jj, first + 1u + l) != vec3<f32>(0.0)) {
                    dark &= ~(1u << l);
                }
            }
        }
    }
    let agreed = (all_shadowed | ~any_shadowed | dark) & all_lights;
    return vec2<u32>(all_lights & ~agreed, all_shadowed & all_lights);
}

// Pass "geometry" (the paper's pass 1, ray traced): subsample `k` of every
// pixel, one dispatch per subsample (`subsample[0]`, which bounds the loop
// iterations of one invocation: llvmpipe stops a shader invocation's loops
// after 65 535 iterations in total). The subsamples other than the shaded
// one (all four with the shaded sample at the centre) are traced for geometry only, with their shadow states (subpixel shadow
// rays, cast only where `shadow_agreement` finds the neighbourhood disagreeing)
// and, on mirrors, the geometry and shadow states of their reflection rays. A
// subsample that is the shaded sample copies the shaded ray's, not traced again.
fn geometry_pixel(x: u32, y: u32, j: u32, k: u32, c: ptr<function, Counts>) {
    if subcone_sraa_is_shaded_subsample(frame.sraa, k) {
        put_sub_geo(j, k, get_geo(j));
        put_sub_shadow(j, k, get_shadow(j));
        put_sub_geo2(j, k, get_geo2(j));
        put_sub_shadow2(j, k, get_shadow2(j));
        put_sub_albedo(j, k, get_albedo(j));
        return;
    }
    put_sub_shadow(j, k, 0u);
    put_sub_geo2(j, k, no_secondary());
    put_sub_shadow2(j, k, 0u);
    let p = pixel_centre(x, y) + subcone_subpixel_offset(k);
    let d = camera_ray(p);
    (*c).geometry += 1u;
    let sf = intersect(frame.cam_pos, d, 0.0);
    put_sub_geo(j, k, primary_geometry(sf));
    if MATERIAL {
        put_sub_albedo(j, k, vec4<f32>(primary_albedo(sf), 0.0));
    }
    if !sf.hit {
        return;
    }
    if HAS_SUB_SHADOW {
        var a = vec2<u32>(0xffffffffu, 0u);
        if HAS_SHADOW {
            a = shadow_agreement(x, y, false, 0u);
        }
        put_sub_shadow(j, k, shadow_states_masked(sf, a.x, a.y, c));
    }
    if HAS_SUB_GEO2 {
        let mirror = materials[sf.material].mirror;
        if mirror > 0.0 && frame.reflection_depth > 0u {
            (*c).geometry += 1u;
            let rd = reflect_dir(d, sf.n);
            let s2 = intersect(sf.p + sf.ng * frame.eps, rd, 0.0);
            if !s2.hit {
                put_sub_geo2(j, k, geometry_miss());
            } else {
                if HAS_SUB_SHADOW2 {
                    var a = vec2<u32>(0xffffffffu, 0u);
                    if HAS_SHADOW2 {
                        a = shadow_agreement(x, y, true, 1u + LAYER_LIGHTS);
                    }
                    put_sub_shadow2(j, k, shadow_states_masked(s2, a.x, a.y, c));
                }
                put_sub_geo2(j, k, subcone_Geometry(s2.n, sf.t + s2.t));
            }
        }
    }
}
