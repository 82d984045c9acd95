// Pass "antialiasing" (the paper's pass 2): render.rs `reconstruct_subsample`
// for each of the four subsamples, then sraa::resolve_pixel. Follows
// subpixel.wgsl and the generated frame header, and comes before
// subcone_kernels::sraa::RECONSTRUCT_WGSL (`subcone_sraa_reconstruct_run`,
// the loop every GPU resolve shares, SraaPass's included), whose hooks it
// defines over this backend's buffers.

// Layers per group: layer 0 ungated and layer 1 + l gated by light l's
// shadow bit (eq. 2); the final colour alone with SINGLE, where the layout
// (passes::LayerLayout) has no light layers. With MATERIAL (`+mat`) the
// primary layers are also gated by albedo (sraa::reconstruct_layers_material).
const SRAA_GATES: u32 = 1u + LAYER_LIGHTS;
const SRAA_MATERIAL: bool = MATERIAL;

fn sraa_size() -> vec2<u32> {
    return vec2<u32>(frame.width, frame.height);
}

fn sraa_albedo_tolerance() -> f32 {
    return subcone_ALBEDO_TOLERANCE;
}

// The shaded sample of pixel (x, y): its primary geometry, or (`secondary`)
// its mirror hit's.
fn sraa_shaded_geometry(x: u32, y: u32, secondary: bool) -> subcone_Geometry {
    let j = y * frame.width + x;
    if secondary {
        return get_geo2(j);
    }
    return get_geo(j);
}

fn sraa_shaded_shadow(x: u32, y: u32, secondary: bool) -> u32 {
    let j = y * frame.width + x;
    if secondary {
        return get_shadow2(j);
    }
    return get_shadow(j);
}

fn sraa_shaded_albedo(x: u32, y: u32) -> vec3<f32> {
    return get_albedo(y * frame.width + x).xyz;
}

fn sraa_shaded_value(x: u32, y: u32, layer: u32) -> vec3<f32> {
    return get_value(y * frame.width + x, layer);
}

fn reconstruct_subsample(x: u32, y: u32, j: u32, k: u32) -> vec3<f32> {
    let tgt = get_sub_geo(j, k);
    var c = subcone_sraa_reconstruct_run(tgt, get_sub_shadow(j, k), get_sub_albedo(j, k).xyz, false, 0u, x, y, k);
    if SECONDARY_LAYERS {
        let tgt2 = get_sub_geo2(j, k);
        if !subcone_is_nan(tgt2.depth) {
            c = c + subcone_sraa_reconstruct_run(tgt2, get_sub_shadow2(j, k), vec3<f32>(0.0), true, 1u + LAYER_LIGHTS, x, y, k);
        }
    }
    return c;
}

@compute @workgroup_size(8, 8)
fn resolve_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let j = id.y * frame.width + id.x;
    let s0 = reconstruct_subsample(id.x, id.y, j, 0u);
    let s1 = reconstruct_subsample(id.x, id.y, j, 1u);
    let s2 = reconstruct_subsample(id.x, id.y, j, 2u);
    let s3 = reconstruct_subsample(id.x, id.y, j, 3u);
    color[j] = vec4<f32>(subcone_resolve_pixel(s0, s1, s2, s3), 0.0);
}
