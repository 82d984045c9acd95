// The SRAA reconstruction loop (Chiu et al., §3.1–3.3: eq. 1 with the
// spatial term, gated by eq. 2 per light), in WGSL: the twin of
// subcone_kernels::sraa::reconstruct_layers (and, with the albedo gate,
// sraa::reconstruct_layers_material) over sraa::neighbourhood, its layers
// summed, as sraa::Resolver sums a subsample's layers of one group.
// Shipped as subcone_kernels::sraa::RECONSTRUCT_WGSL (re-exported as
// subcone_passes::RECONSTRUCT_WGSL). Every GPU resolve runs it:
// subcone_passes::SraaPass and the wgpu backend's SRAA-RT resolve
// (backends/wgpu/src/triangles/sraa.wgsl), so there is one GPU resolve. It
// drives the kernels' WGSL (subcone_kernels::sraa::WGSL) in the order of the
// CPU's sraa::reconstruct_layers / reconstruct_layers_material.
//
// Follows subcone_kernels::wgsl::PARAMS and subcone_kernels::sraa::WGSL. The
// including shader defines these hooks:
//     const SRAA_GATES: u32             layers per group: 1 + gated lights (≤ 9)
//     const SRAA_MATERIAL: bool         the albedo gate on the primary group
//     fn sraa_params() -> subcone_SraaParams
//     fn sraa_size() -> vec2<u32>       the image's width and height
//     fn sraa_albedo_tolerance() -> f32
//     fn sraa_shaded_geometry(x: u32, y: u32, secondary: bool) -> subcone_Geometry
//     fn sraa_shaded_shadow(x: u32, y: u32, secondary: bool) -> u32
//     fn sraa_shaded_albedo(x: u32, y: u32) -> vec3<f32>
//     fn sraa_shaded_value(x: u32, y: u32, layer: u32) -> vec3<f32>
// the shaded sample of pixel (x, y): its geometry, shadow bits (bit l: light
// l's shadow), albedo, and colour layer `layer`.
//
// Differences from the Rust, all in the rounding: those of sraa.wgsl (the
// GPU's exp, compensated f32 sums instead of f64), and a GPU may flush a
// subnormal weight (below 2^-126) to zero: as the weights sum to at least
// 2^-64 (below, the nearest sample is taken), that moves the mean by less
// than 2^-62 times the neighbour's colour, visible only for colours above
// ~1e14.

// Mirrors sraa::reconstruct_layers (sraa::reconstruct_layers_material with
// SRAA_MATERIAL, on the primary group) of subsample k of pixel (x, y), whose
// geometry is `tgt`, shadow bits `target_shadow` and albedo `ta`, over the
// neighbourhood's shaded samples of one group (`secondary`: the secondary
// hits', §3.3), layers first .. first + SRAA_GATES: layer 0 of the group
// ungated, layer 1 + l gated by light l's shadow bit (eq. 2). Returns the sum
// of the group's reconstructed layers.
fn subcone_sraa_reconstruct_run(tgt: subcone_Geometry, target_shadow: u32, ta: vec3<f32>, secondary: bool, first: u32, x: u32, y: u32, k: u32) -> vec3<f32> {
    let params = sraa_params();
    let size = sraa_size();
    var st: subcone_LayerStates;
    for (var i = 0u; i < SRAA_GATES; i++) {
        st.at[i] = subcone_reconstruct_layers_begin();
    }
    let nb = subcone_neighbourhood(x, y, k, subcone_sraa_shaded_offset(params), subcone_sraa_radius(params), size.x, size.y);
    for (var py = nb.y0; py < nb.y1; py++) {
        for (var px = nb.x0; px < nb.x1; px++) {
            let d2 = subcone_neighbour_distance2(nb, x, y, px, py);
            let g = sraa_shaded_geometry(px, py, secondary);
            let s = sraa_shaded_shadow(px, py, secondary);
            // sraa::reconstruction_weight (eq. 1 and the spatial term), gated
            // by albedo as sraa::reconstruct_layers_material gates.
            var w = 0.0;
            if !(SRAA_MATERIAL && !secondary) || subcone_material_gate(ta, sraa_shaded_albedo(px, py), sraa_albedo_tolerance()) {
                w = subcone_reconstruction_weight(params, tgt, g, d2);
            }
            for (var i = 0u; i < SRAA_GATES; i++) {
                // Through a local: naga's SPIR-V writer cannot pass a pointer
                // to an array element as an argument.
                var layer = st.at[i];
                subcone_reconstruct_layers_add(&layer, w, i > 0u, i - 1u, target_shadow, s, d2, sraa_shaded_value(px, py, first + i));
                st.at[i] = layer;
            }
        }
    }
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < SRAA_GATES; i++) {
        sum = sum + subcone_reconstruct_layers_end(st.at[i]);
    }
    return sum;
}
