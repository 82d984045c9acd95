// Subpixel Reconstruction Antialiasing for ray tracing (Chiu et al., §3), in WGSL.
//
// Mirrors subcone_kernels::sraa function by function (same names, same
// parameter structs from params.wgsl). Functions only: no bindings, no entry
// points. Concatenate after subcone_kernels::wgsl::PARAMS.
//
// Differences from the Rust kernels, all in the rounding:
// - exp() is the GPU's, not libm's expf (a few ulps apart);
// - the weighted sums of reconstruct/reconstruct_layers accumulate in f32 with
//   compensated (Kahan) summation, where the Rust accumulates in f64
//   (kernels/src/sum.rs). The results agree to about one f32 ulp for ordinary
//   weights and colours; where w·C falls into f32's subnormal range (weights
//   below ~1e-19 times colours below ~1e-19) the products lose precision that
//   f64 keeps, and the normalised result may leave the neighbours' convex hull
//   by that loss.
// - depth_difference's relative metric, for depths above 2^100, is computed
//   as a ratio to the larger depth (Rust: difference over the mean), because
//   GPUs may rewrite 0.5·a + 0.5·b as 0.5·(a + b) and overflow; a few ulps
//   apart there, the same elsewhere;
// - iterators become loops: `subcone_neighbourhood` returns its bounds and
//   `subcone_neighbour_distance2` the distance of one pixel; `reconstruct_layers` is
//   split into begin / add one neighbour's layer / end, which the caller
//   drives in the Rust function's order.
//
// NaN tests are done on the bits: shader compilers may fold `x != x` away.

// Mirrors sraa::NORMAL_COS_SNAP (2^-21).
const subcone_NORMAL_COS_SNAP: f32 = 4.76837158203125e-7;
// Mirrors sraa::SHADED_SUBSAMPLE.
const subcone_SHADED_SUBSAMPLE: u32 = 0u;
// Mirrors sraa::SHADED_SAMPLE: the `sub` of subcone_neighbourhood that means
// the shaded sample itself.
const subcone_SHADED_SAMPLE: u32 = 4u;

fn subcone_sraa_is_finite3(c: vec3<f32>) -> bool {
    return subcone_is_finite(c.x) && subcone_is_finite(c.y) && subcone_is_finite(c.z);
}

fn subcone_sraa_any_nan3(c: vec3<f32>) -> bool {
    return subcone_is_nan(c.x) || subcone_is_nan(c.y) || subcone_is_nan(c.z);
}

// Mirrors sraa::SUBPIXEL_OFFSETS (§3.1, Fig. 2): the 4x rotated grid on a 4×4
// grid, relative to the pixel centre, in pixels. Indices >= 4 read as 0.
fn subcone_subpixel_offset(k: u32) -> vec2<f32> {
    switch k {
        case 1u: { return vec2<f32>(0.375, -0.125); }
        case 2u: { return vec2<f32>(-0.375, 0.125); }
        case 3u: { return vec2<f32>(0.125, 0.375); }
        default: { return vec2<f32>(-0.125, -0.375); }
    }
}

// Mirrors sraa::SraaParams::form (0 = Product, 1 = ChajdasMax; unknown = Product).
fn subcone_sraa_form(p: subcone_SraaParams) -> u32 {
    if (p.packed & 0xffu) == 1u {
        return 1u;
    }
    return 0u;
}

// Mirrors sraa::SraaParams::depth_metric (0 = Relative, 1 = Absolute; unknown = Relative).
fn subcone_sraa_depth_metric(p: subcone_SraaParams) -> u32 {
    if ((p.packed >> 8u) & 0xffu) == 1u {
        return 1u;
    }
    return 0u;
}

// Mirrors sraa::SraaParams::radius.
fn subcone_sraa_radius(p: subcone_SraaParams) -> u32 {
    return p.packed >> 16u;
}

// Mirrors sraa::SraaParams::shaded_offset: the shaded sample's offset from the
// pixel centre (subsample 0 for code 0 and unknown codes, the centre for 1).
fn subcone_sraa_shaded_offset(p: subcone_SraaParams) -> vec2<f32> {
    if p.shading == 1u {
        return vec2<f32>(0.0);
    }
    return subcone_subpixel_offset(subcone_SHADED_SUBSAMPLE);
}

// Mirrors sraa::SraaParams::shaded_subsample: whether geometric subsample k
// is also the shaded sample (its geometry is the shaded ray's).
fn subcone_sraa_is_shaded_subsample(p: subcone_SraaParams, k: u32) -> bool {
    return p.shading != 1u && k == subcone_SHADED_SUBSAMPLE;
}

// Mirrors sraa::gaussian: G(x) = exp(-x²) of eq. 1; 0 for ±inf and NaN.
fn subcone_gaussian(x: f32) -> f32 {
    let e = exp(-(x * x));
    if subcone_is_nan(e) {
        return 0.0;
    }
    return e;
}

// Mirrors sraa::gaussian_sum: exp(-s); exactly 1 for s = 0, 0 for s ≥ 105
// (sraa::EXP_UNDERFLOW, where exp(-s) rounds to 0), s = inf or NaN.
fn subcone_gaussian_sum(s: f32) -> f32 {
    if s == 0.0 {
        return 1.0;
    }
    if subcone_is_nan(s) || !(s < 105.0) {
        return 0.0;
    }
    let e = exp(-s);
    if subcone_is_nan(e) {
        return 0.0;
    }
    return e;
}

// Mirrors sraa::saturate: sat(x) = max(0, min(1, x)), sat(NaN) = 0 (§3.1).
fn subcone_saturate(x: f32) -> f32 {
    if x > 0.0 {
        if x < 1.0 {
            return x;
        }
        return 1.0;
    }
    return 0.0;
}

// Mirrors sraa::depth_difference: Δz of eq. 1 under `metric` (0 = Relative,
// 1 = Absolute), >= 0; +inf for a miss against a hit or any NaN.
fn subcone_depth_difference(zi: f32, zj: f32, metric: u32) -> f32 {
    if zi == zj && !subcone_is_nan(zi) {
        return 0.0;
    }
    let diff = abs(zj - zi);
    var r = diff;
    if metric != 1u {
        let m = max(abs(zi), abs(zj));
        if m > 1.2676506e30 {
            // Above 2^100, as a ratio to the larger depth: a GPU may evaluate
            // 0.5·a + 0.5·b as 0.5·(a + b), which overflows near f32::MAX
            // (lavapipe does, and cancels any scale factor put around it).
            r = (diff / m) / (0.5 + 0.5 * (min(abs(zi), abs(zj)) / m));
        } else {
            let mean = 0.5 * abs(zi) + 0.5 * abs(zj);
            if mean == 0.0 {
                // diff / 0: +inf for diff > 0 (diff = 0 only when zi == zj).
                return subcone_inf();
            }
            r = diff / mean;
        }
    }
    if subcone_is_nan(r) {
        return subcone_inf();
    }
    return r;
}

// Mirrors sraa::bilateral_weight (eq. 1):
// w_ij = G(σz·Δz) · G(σn·(1 − sat(nj·ni))) for the Product form,
// exp(−s·max(1 − sat(nj·ni), σz·Δz)) for ChajdasMax. In [0, 1]; NaN gives 0;
// two misses give 1.
fn subcone_bilateral_weight(params: subcone_SraaParams, gi: subcone_Geometry, gj: subcone_Geometry) -> f32 {
    return subcone_reconstruction_weight(params, gi, gj, 0.0);
}

// Mirrors sraa::reconstruction_weight: eq. 1 times exp(−d²/σs²) when σs > 0
// (one exponential for the Product form); distance2 ignored when σs ≤ 0 or NaN.
fn subcone_reconstruction_weight(params: subcone_SraaParams, gi: subcone_Geometry, gj: subcone_Geometry, distance2: f32) -> f32 {
    var spatial = 0.0;
    if params.sigma_s > 0.0 && distance2 != 0.0 {
        spatial = distance2 / (params.sigma_s * params.sigma_s);
    }
    let dz = subcone_depth_difference(gi.depth, gj.depth, subcone_sraa_depth_metric(params));
    let cos = subcone_saturate(dot(gj.normal, gi.normal));
    var dn = 1.0 - cos;
    if cos >= 1.0 - subcone_NORMAL_COS_SNAP {
        dn = 0.0;
    }
    let inf = subcone_inf();
    if gi.depth == inf && gj.depth == inf {
        return 1.0;
    }
    if subcone_sraa_any_nan3(gi.normal) || subcone_sraa_any_nan3(gj.normal) {
        return 0.0;
    }
    var w = 0.0;
    if subcone_sraa_form(params) == 0u {
        let a = params.sigma_z * dz;
        let b = params.sigma_n * dn;
        w = subcone_gaussian_sum(a * a + b * b + spatial);
    } else {
        let x = params.scale * max(dn, params.sigma_z * dz);
        if subcone_is_nan(x) || x == inf {
            w = 0.0;
        } else {
            w = exp(-x);
            if subcone_is_nan(w) {
                w = 0.0;
            }
        }
        if spatial != 0.0 {
            w = w * subcone_gaussian_sum(spatial);
        }
    }
    return subcone_saturate(w);
}

// Mirrors sraa::shadow_gated_weight (eq. 2): 0 when the shadow states differ,
// eq. 1 when they agree.
fn subcone_shadow_gated_weight(params: subcone_SraaParams, gi: subcone_Geometry, gj: subcone_Geometry, si: bool, sj: bool) -> f32 {
    if si != sj {
        return 0.0;
    }
    return subcone_bilateral_weight(params, gi, gj);
}

// Mirrors sraa::ALBEDO_TOLERANCE: the material gate's default tolerance.
const subcone_ALBEDO_TOLERANCE: f32 = 0.1;

// Mirrors sraa::albedo_difference: max over channels of |sqrt(a) - sqrt(b)|,
// negative components counted as 0; +inf when a component of either albedo is
// NaN or infinite.
fn subcone_albedo_difference(a: vec3<f32>, b: vec3<f32>) -> f32 {
    if !subcone_sraa_is_finite3(a) || !subcone_sraa_is_finite3(b) {
        return subcone_inf();
    }
    let d = abs(sqrt(max(a, vec3<f32>(0.0))) - sqrt(max(b, vec3<f32>(0.0))));
    return max(d.x, max(d.y, d.z));
}

// Mirrors sraa::material_gated_weight (§4.1, Fig. 6; the gate of eq. 2 on
// albedo): 0 when the albedos differ by more than `tolerance` (or one is not
// finite, or the tolerance is NaN), eq. 1 when they match.
fn subcone_material_gated_weight(params: subcone_SraaParams, gi: subcone_Geometry, gj: subcone_Geometry, ai: vec3<f32>, aj: vec3<f32>, tolerance: f32) -> f32 {
    if subcone_material_gate(ai, aj, tolerance) {
        return subcone_bilateral_weight(params, gi, gj);
    }
    return 0.0;
}

// Mirrors sraa::material_gate: whether the albedos match within `tolerance`.
fn subcone_material_gate(ai: vec3<f32>, aj: vec3<f32>, tolerance: f32) -> bool {
    let d = subcone_albedo_difference(ai, aj);
    return d <= tolerance && d < subcone_inf();
}

// Mirrors sraa::neighbourhood: the clipped (2r+1)² pixels around (x, y), as
// bounds [x0, x1) × [y0, y1), and the target subsample's position minus the
// shaded sample's within a pixel. Iterate rows y0..y1, columns x0..x1 (row-major,
// the Rust iterator's order).
struct subcone_Neighbourhood {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
    offset: vec2<f32>,
}

fn subcone_sraa_saturating_add(a: u32, b: u32) -> u32 {
    let s = a + b;
    if s < a {
        return 0xffffffffu;
    }
    return s;
}

fn subcone_neighbourhood(x: u32, y: u32, sub: u32, shaded: vec2<f32>, radius: u32, width: u32, height: u32) -> subcone_Neighbourhood {
    var pos = shaded;
    if sub < 4u {
        pos = subcone_subpixel_offset(sub);
    }
    var n: subcone_Neighbourhood;
    n.offset = pos - shaded;
    n.x0 = select(0u, x - radius, x >= radius);
    n.y0 = select(0u, y - radius, y >= radius);
    n.x1 = min(subcone_sraa_saturating_add(subcone_sraa_saturating_add(x, radius), 1u), width);
    n.y1 = min(subcone_sraa_saturating_add(subcone_sraa_saturating_add(y, radius), 1u), height);
    return n;
}

// Mirrors sraa::Neighbourhood::next's distance2: squared distance in pixels² from the
// target subsample of (x, y) to the shaded sample of (px, py).
fn subcone_neighbour_distance2(n: subcone_Neighbourhood, x: u32, y: u32, px: u32, py: u32) -> f32 {
    let d = vec2<f32>(f32(px) - f32(x), f32(py) - f32(y)) - n.offset;
    return d.x * d.x + d.y * d.y;
}

// Mirrors sum::WeightedSum: Σ w·C and Σ w, compensated (Kahan) in f32 instead
// of f64 (see the header).
struct subcone_WeightedSum {
    sum: vec3<f32>,
    sum_c: vec3<f32>,
    weight: f32,
    weight_c: f32,
}

fn subcone_weighted_sum_zero() -> subcone_WeightedSum {
    return subcone_WeightedSum(vec3<f32>(0.0), vec3<f32>(0.0), 0.0, 0.0);
}

// Mirrors sum::WeightedSum::add.
fn subcone_weighted_sum_add(acc: ptr<function, subcone_WeightedSum>, w: f32, c: vec3<f32>) {
    let y = w * c - (*acc).sum_c;
    let t = (*acc).sum + y;
    (*acc).sum_c = (t - (*acc).sum) - y;
    (*acc).sum = t;
    let yw = w - (*acc).weight_c;
    let tw = (*acc).weight + yw;
    (*acc).weight_c = (tw - (*acc).weight) - yw;
    (*acc).weight = tw;
}

// Mirrors sum::WeightedSum::mean: Σ w·C / Σ w in .xyz, .w = 1; .w = 0 when the weight
// is negligible (or NaN) or the mean is not finite.
fn subcone_weighted_sum_mean(acc: subcone_WeightedSum) -> vec4<f32> {
    if !(acc.weight >= subcone_NEGLIGIBLE_WEIGHT) {
        return vec4<f32>(0.0);
    }
    let inv = 1.0 / acc.weight;
    let c = acc.sum * inv;
    if !subcone_sraa_is_finite3(c) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(c, 1.0);
}

// One layer's state in sraa::reconstruct_layers: its weighted sum and the
// nearest finite colour (the fallback).
struct subcone_LayerState {
    acc: subcone_WeightedSum,
    nearest: vec3<f32>,
    nearest_d2: f32,
    any: bool,
}

// Every gate's state of subcone_sraa_reconstruct_run (eq. 2: the ungated
// layer and one per light, at most 9).
// Held in a struct, not a bare local array: naga writes a local array's
// zero value in HLSL as `(T[N])0`, which glslang's HLSL front end cannot
// parse, and a struct's as `(S)0`, which every HLSL compiler reads.
struct subcone_LayerStates {
    at: array<subcone_LayerState, 9>,
}

// sraa::reconstruct_layers, before the loop over neighbours.
fn subcone_reconstruct_layers_begin() -> subcone_LayerState {
    return subcone_LayerState(subcone_weighted_sum_zero(), vec3<f32>(0.0), subcone_inf(), false);
}

// sraa::reconstruct_layers, the body of the loop for one neighbour and one
// layer: `w` is the neighbour's subcone_bilateral_weight (eq. 1, computed once per
// neighbour), `gated` says whether this layer has a gate and `bit` which light
// it is (eq. 2: weight 0 when the target's and neighbour's states differ).
fn subcone_reconstruct_layers_add(
    state: ptr<function, subcone_LayerState>,
    w: f32,
    gated: bool,
    bit: u32,
    target_shadow: u32,
    shadow: u32,
    distance2: f32,
    c: vec3<f32>,
) {
    if !subcone_sraa_is_finite3(c) {
        return;
    }
    var d2 = distance2;
    if subcone_is_nan(d2) {
        d2 = subcone_inf();
    }
    if !(*state).any || d2 < (*state).nearest_d2 {
        (*state).nearest = c;
        (*state).nearest_d2 = d2;
        (*state).any = true;
    }
    var wi = w;
    if gated && bit < 32u && (((target_shadow ^ shadow) >> bit) & 1u) != 0u {
        wi = 0.0;
    }
    // Through a local: naga's SPIR-V writer cannot pass a pointer into a
    // struct behind a pointer as an argument.
    var acc = (*state).acc;
    subcone_weighted_sum_add(&acc, wi, c);
    (*state).acc = acc;
}

// sraa::reconstruct_layers, after the loop: the mean, or the nearest shaded
// sample when the weights underflowed (black with no usable neighbour).
fn subcone_reconstruct_layers_end(state: subcone_LayerState) -> vec3<f32> {
    let m = subcone_weighted_sum_mean(state.acc);
    if m.w > 0.0 {
        return m.xyz;
    }
    return state.nearest;
}

// Mirrors sraa::resolve_pixel: the box filter over the four reconstructed
// subsamples (§3); non-finite subsamples are dropped, none finite gives black.
fn subcone_resolve_pixel(s0: vec3<f32>, s1: vec3<f32>, s2: vec3<f32>, s3: vec3<f32>) -> vec3<f32> {
    let f0 = subcone_sraa_is_finite3(s0);
    let f1 = subcone_sraa_is_finite3(s1);
    let f2 = subcone_sraa_is_finite3(s2);
    let f3 = subcone_sraa_is_finite3(s3);
    let n = u32(f0) + u32(f1) + u32(f2) + u32(f3);
    if n == 0u {
        return vec3<f32>(0.0);
    }
    let inv = 1.0 / f32(n);
    var s = vec3<f32>(0.0);
    if f0 {
        s = s + s0 * inv;
    }
    if f1 {
        s = s + s1 * inv;
    }
    if f2 {
        s = s + s2 * inv;
    }
    if f3 {
        s = s + s3 * inv;
    }
    return s;
}

// Mirrors sraa::RESOLVE_LUMA: BT.709 luma weights of linear RGB.
const subcone_RESOLVE_LUMA: vec3<f32> = vec3<f32>(0.2126, 0.7152, 0.0722);

// Mirrors sraa::tone_map_weight (Karis 2014): 1 / (1 + exposure·luma(c)),
// negative luma as 0; 0 for a non-finite colour or exposure. In f32 (the
// Rust computes in f64 and rounds): an exposed luma that overflows f32
// gives 1 / inf = 0, where the Rust's weight is a tiny f64.
fn subcone_tone_map_weight(c: vec3<f32>, exposure: f32) -> f32 {
    if !subcone_sraa_is_finite3(c) || !subcone_is_finite(exposure) {
        return 0.0;
    }
    var luma = dot(c, subcone_RESOLVE_LUMA) * exposure;
    if !(luma > 0.0) {
        luma = 0.0;
    }
    return 1.0 / (1.0 + luma);
}

// Mirrors sraa::resolve_pixel_tone_mapped: the four subsamples weighted by
// subcone_tone_map_weight, Σ w·c / Σ w over the finite ones; the linear box
// (subcone_resolve_pixel) for an exposure that is not positive and finite.
// Summed in f32, where the Rust sums in f64: a few ulps apart, and where
// every finite subsample's exposed luma overflows f32 (weights all 0) or
// the mean is not finite, this takes the box where the Rust still weighs.
// The four subsamples of subcone_resolve_pixel_tone_mapped, held in a struct, not a bare local array: naga writes a local array's
// zero value in HLSL as `(T[N])0`, which glslang's HLSL front end cannot
// parse, and a struct's as `(S)0`, which every HLSL compiler reads.
struct subcone_Subsamples4 {
    at: array<vec3<f32>, 4>,
}

fn subcone_resolve_pixel_tone_mapped(s0: vec3<f32>, s1: vec3<f32>, s2: vec3<f32>, s3: vec3<f32>, exposure: f32) -> vec3<f32> {
    if !(exposure > 0.0) || !subcone_is_finite(exposure) {
        return subcone_resolve_pixel(s0, s1, s2, s3);
    }
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    var subs = subcone_Subsamples4(array<vec3<f32>, 4>(s0, s1, s2, s3));
    for (var k = 0u; k < 4u; k++) {
        let c = subs.at[k];
        if subcone_sraa_is_finite3(c) {
            let w = subcone_tone_map_weight(c, exposure);
            sum = sum + w * c;
            weight = weight + w;
        }
    }
    if weight > 0.0 {
        let m = sum / weight;
        if subcone_sraa_is_finite3(m) {
            return m;
        }
    }
    return subcone_resolve_pixel(s0, s1, s2, s3);
}
