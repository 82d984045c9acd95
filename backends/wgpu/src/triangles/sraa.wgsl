// Pass "antialiasing" (the paper's pass 2): render.rs `reconstruct_subsample`
// for each of the four subsamples, then sraa::resolve_pixel. Follows
// subpixel.wgsl and the generated frame header.

// render.rs `reconstruct_subsample`'s `run`: sraa::reconstruct_layers over the
// neighbourhood's shaded samples, `first` the first layer, on primary
// (`secondary` false) or secondary geometry; returns the sum of the layers.
// Layer 0 is ungated, layer 1 + l gated by light l's shadow bit (eq. 2).
// With MATERIAL (`+mat`) the primary layers are also gated by albedo
// (sraa::reconstruct_layers_material): `ta` is the target's albedo.
fn reconstruct_run(tgt: subcone_Geometry, target_shadow: u32, ta: vec3<f32>, secondary: bool, first: u32, x: u32, y: u32, k: u32) -> vec3<f32> {
    var gates = 1u + LAYER_LIGHTS;
    if SINGLE {
        gates = 1u;
    }
    var st: array<subcone_LayerState, 9>;
    for (var i = 0u; i < gates; i++) {
        st[i] = subcone_reconstruct_layers_begin();
    }
    let nb = subcone_neighbourhood(x, y, k, subcone_sraa_shaded_offset(frame.sraa), subcone_sraa_radius(frame.sraa), frame.width, frame.height);
    for (var py = nb.y0; py < nb.y1; py++) {
        for (var px = nb.x0; px < nb.x1; px++) {
            let jj = py * frame.width + px;
            let d2 = subcone_neighbour_distance2(nb, x, y, px, py);
            var g = geo[jj];
            var s = get_shadow(jj);
            if secondary {
                g = get_geo2(jj);
                s = get_shadow2(jj);
            }
            // sraa::reconstruction_weight (eq. 1 and the spatial term), gated
            // by albedo as sraa::reconstruct_layers_material gates.
            var w = 0.0;
            if !(MATERIAL && !secondary) || subcone_material_gate(ta, get_albedo(jj).xyz, subcone_ALBEDO_TOLERANCE) {
                w = subcone_reconstruction_weight(frame.sraa, tgt, g, d2);
            }
            for (var i = 0u; i < gates; i++) {
                // Through a local: naga's SPIR-V writer cannot pass a pointer
                // to an array element as an argument.
                var layer = st[i];
                subcone_reconstruct_layers_add(&layer, w, i > 0u, i - 1u, target_shadow, s, d2, get_value(jj, first + i));
                st[i] = layer;
            }
        }
    }
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < gates; i++) {
        sum = sum + subcone_reconstruct_layers_end(st[i]);
    }
    return sum;
}

fn reconstruct_subsample(x: u32, y: u32, j: u32, k: u32) -> vec3<f32> {
    let tgt = get_sub_geo(j, k);
    var c = reconstruct_run(tgt, get_sub_shadow(j, k), get_sub_albedo(j, k).xyz, false, 0u, x, y, k);
    if SECONDARY_LAYERS {
        let tgt2 = get_sub_geo2(j, k);
        if !subcone_is_nan(tgt2.depth) {
            c = c + reconstruct_run(tgt2, get_sub_shadow2(j, k), vec3<f32>(0.0), true, 1u + LAYER_LIGHTS, x, y, k);
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
