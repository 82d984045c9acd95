// The `#[repr(C)]` parameter structs of subcone-kernels, in WGSL.
//
// Each struct here has exactly the field offsets of its Rust twin (checked by
// kernels/tests/wgsl_layout.rs through naga's layouter). WGSL aligns vec3 to
// 16 bytes while glam's Vec3 aligns to 4: a scalar after a vec3 fills its
// 4-byte tail in both languages, which is why `subcone_Geometry` puts `depth` last.
// Arrays in the uniform address space have a 16-byte stride, so padding is
// spelled as scalars (`_pad0`, `_pad1` are Rust's `_pad: [u32; 2]`).

// subcone_kernels::sraa::SraaParams (32 bytes).
struct subcone_SraaParams {
    sigma_z: f32,
    sigma_n: f32,
    scale: f32,
    // Bits 0..8: WeightForm; 8..16: DepthMetric; 16..32: reconstruction radius.
    packed: u32,
    // σs, the spatial falloff in pixels (0: none, as in eq. 1).
    sigma_s: f32,
    // ShadedPosition: 0 on subsample 0 (the paper), 1 at the pixel centre.
    shading: u32,
    _pad0: u32,
    _pad1: u32,
}

// subcone_kernels::sraa::Geometry (16 bytes). depth = +inf marks a miss; WGSL
// cannot spell infinity as a literal, so shaders use SUBCONE_MISS_DEPTH.
struct subcone_Geometry {
    normal: vec3<f32>,
    depth: f32,
}

// subcone_kernels::ctss::CtssParams (48 bytes).
struct subcone_CtssParams {
    tan_theta: f32,
    alpha: f32,
    eps: f32,
    t_min: f32,
    t_max: f32,
    min_sample_weight: f32,
    max_steps: u32,
    max_samples: u32,
    visibility_k: u32,
    // Bit 0: subcone_FLAG_RELAXED. Bits 8..16: MaskPlacement. Bits 16..24: Weighting.
    flags: u32,
    _pad0: u32,
    _pad1: u32,
}

// subcone_kernels::camera::PinholeCamera (80 bytes).
struct subcone_PinholeCamera {
    position: vec3<f32>,
    width: u32,
    forward: vec3<f32>,
    height: u32,
    right: vec3<f32>,
    tan_half_fov: f32,
    up: vec3<f32>,
    _pad: u32,
    // Sub-pixel offset of every ray, in pixels (a temporal method's jitter).
    jitter: vec2<f32>,
    _pad2: vec2<u32>,
}

// subcone_kernels::taa::TaaParams (32 bytes).
struct subcone_TaaParams {
    exposure: f32,
    min_current_weight: f32,
    clip_gamma: f32,
    history_frames: u32,
    width: u32,
    height: u32,
    tone_mapped: u32,
    _pad: u32,
}

// subcone_kernels::fxaa::FxaaParams (16 bytes).
struct subcone_FxaaParams {
    subpix: f32,
    edge_threshold: f32,
    edge_threshold_min: f32,
    _pad: f32,
}

// subcone_kernels::sraa::NEGLIGIBLE_WEIGHT (2^-64): weight sums below it are
// treated as empty by the SRAA reconstruction and the CTSS aggregation alike.
const subcone_NEGLIGIBLE_WEIGHT: f32 = 5.421011e-20;

// The one +inf, NaN test and finiteness test of every shader that includes
// these parameters (kernels, backend passes, generated SDF fields). +inf is a
// bit pattern: WGSL has no infinity literal, and a constant-folded 1/0 is a
// shader-creation error. The tests read the bits, so no compiler may fold
// them away under fast-math assumptions.
fn subcone_inf() -> f32 {
    return bitcast<f32>(0x7f800000u);
}

fn subcone_is_nan(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) > 0x7f800000u;
}

fn subcone_is_finite(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) < 0x7f800000u;
}

// subcone_kernels::camera::PinholeCamera::ray_dir: the unit direction from
// c.position through image point p + c.jitter (pixels, y down).
fn subcone_pinhole_dir(c: subcone_PinholeCamera, p_in: vec2<f32>) -> vec3<f32> {
    let p = p_in + c.jitter;
    let w = f32(max(c.width, 1u));
    let h = f32(max(c.height, 1u));
    let u = (2.0 * p.x / w - 1.0) * c.tan_half_fov * (w / h);
    let v = (1.0 - 2.0 * p.y / h) * c.tan_half_fov;
    let d = c.forward + u * c.right + v * c.up;
    return d * (1.0 / length(d));
}
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
const LIGHTS: u32 = 0u;
const MATERIAL: bool = false;
const HARDWARE_DEPTH: bool = false;
const UNSIGNED_NORMALS: bool = false;
const SHADED_GIVEN: bool = true;
const DECODED: bool = false;
const SECONDARY: bool = false;
const TONE_MAPPED_RESOLVE: bool = false;
fn sraa_store(p: vec2<i32>, c: vec4<f32>) { textureStore(sraa_output, p, c); }
fn sraa_load_sub(p: vec2<i32>, k: u32) -> vec4<f32> { return textureLoad(sub_depth, p, i32(k), 0); }
fn sraa_load_shaded(p: vec2<i32>) -> vec4<f32> { return vec4<f32>(textureLoad(centre_normal, p, 0).xyz, textureLoad(centre_depth, p, 0).x); }
fn sraa_load_color(p: vec2<i32>, l: u32) -> vec3<f32> { return textureLoad(color, p, 0).xyz; }
fn sraa_load_shaded_shadow(p: vec2<i32>) -> u32 { return 0u; }
fn sraa_load_sub_shadow(p: vec2<i32>, k: u32) -> u32 { return 0u; }
fn sraa_load_sec_shaded_shadow(p: vec2<i32>) -> u32 { return 0u; }
fn sraa_load_sec_sub_shadow(p: vec2<i32>, k: u32) -> u32 { return 0u; }
fn sraa_load_sec_shaded(p: vec2<i32>) -> vec4<f32> { return vec4<f32>(0.0); }
fn sraa_load_sec_sub(p: vec2<i32>, k: u32) -> vec4<f32> { return vec4<f32>(0.0); }
fn sraa_load_shaded_albedo(p: vec2<i32>) -> vec3<f32> { return vec3<f32>(0.0); }
fn sraa_load_sub_albedo(p: vec2<i32>, k: u32) -> vec3<f32> { return vec3<f32>(0.0); }
// SraaPass (sraa.rs): SRAA's antialiasing pass (Chiu et al., §3, the
// paper's pass 2) over the host's textures. The loop is the wgpu backend's
// resolve (backends/wgpu/src/triangles/sraa.wgsl) and the kernels' Resolver:
// for each of the four geometric subsamples, sraa::reconstruct_layers over
// the neighbourhood's shaded samples (eq. 1, eq. 2 per light, the material
// gate; the kernels' loop subcone_kernels::sraa::RECONSTRUCT_WGSL, shared
// with the backend), then sraa::resolve_pixel. All the mathematics is the
// kernels' (subcone_kernels::sraa::WGSL and RECONSTRUCT_WGSL); this file
// only reads the host's textures.
//
// Follows subcone_kernels::wgsl::PARAMS, subcone_kernels::sraa::WGSL and the
// header sraa.rs generates, and comes before
// subcone_kernels::sraa::RECONSTRUCT_WGSL (the loop, whose hooks this file
// defines): the constants LIGHTS, MATERIAL, HARDWARE_DEPTH,
// UNSIGNED_NORMALS, SHADED_GIVEN (the shaded sample's geometry is an input
// of its own), DECODED (geometry is stored as the kernels' subcone_Geometry,
// taken as it is), SECONDARY, TONE_MAPPED_RESOLVE (sraa::ResolveSpace),
// the bindings, the loaders
// sraa_load_sub (normal and depth), sraa_load_sub_shadow and
// sraa_load_sub_albedo (subsample k of pixel p),
// sraa_load_sec_shaded / sraa_load_sec_sub (secondary normal and path
// length), sraa_load_sec_shaded_shadow / sraa_load_sec_sub_shadow,
// sraa_load_shaded (the shaded sample's own normal and depth),
// sraa_load_color (layer l), sraa_load_shaded_shadow and
// sraa_load_shaded_albedo (the shaded sample), and sraa_store (the output).

// sraa.rs `SraaFrame` (80 bytes).
struct SraaFrame {
    sraa: subcone_SraaParams,
    // The host projection's entries that map view-space z to clip z and w
    // (column-major m[2][2], m[3][2], m[2][3], m[3][3]): clip.z = x·z + y,
    // clip.w = z·z + w. Read only with HARDWARE_DEPTH.
    projection: vec4<f32>,
    width: u32,
    height: u32,
    // The hardware depth of a sample nothing covered (the clear value).
    depth_miss: f32,
    albedo_tolerance: f32,
    // The top-left pixel of the rect resolved (SraaPass::encode_rect; 0 for
    // the whole texture and for buffers): width and height are the rect's,
    // the reconstruction runs in the rect's own coordinates (so its
    // neighbourhood is clipped to the rect) and every texel is read and
    // written at origin + those coordinates (sraa_texel).
    origin_x: u32,
    origin_y: u32,
    // The tone-mapped resolve's exposure (TONE_MAPPED_RESOLVE).
    exposure: f32,
    _pad: u32,
}

// The texel of the rect's pixel (x, y).
fn sraa_texel(x: u32, y: u32) -> vec2<i32> {
    return vec2<i32>(i32(x + frame.origin_x), i32(y + frame.origin_y));
}

// View depth from the host's depth sample: a linear view depth (> 0 and
// finite, anything else a miss), or a hardware depth d inverted through the
// projection, z = |(m32 − d·m33) / (d·m23 − m22)| (forward or reversed Z,
// finite or infinite far plane); +inf (a miss) for the clear value.
fn sraa_decode_depth(d: f32) -> f32 {
    var z = d;
    if HARDWARE_DEPTH {
        if d == frame.depth_miss {
            return subcone_inf();
        }
        let m = frame.projection;
        z = abs((m.y - d * m.w) / (d * m.z - m.x));
    }
    if subcone_is_finite(z) && z > 0.0 {
        return z;
    }
    return subcone_inf();
}

// A unit normal from the host's encoding (xyz signed, or xyz·0.5 + 0.5 with
// UNSIGNED_NORMALS); zero when the vector is zero or not finite.
fn sraa_decode_normal(v: vec3<f32>) -> vec3<f32> {
    var n = v;
    if UNSIGNED_NORMALS {
        n = v * 2.0 - vec3<f32>(1.0);
    }
    let l2 = dot(n, n);
    if l2 > 0.0 && subcone_is_finite(l2) {
        return n * (1.0 / sqrt(l2));
    }
    return vec3<f32>(0.0);
}

// The geometry of a sample from its stored normal (.xyz) and depth (.w):
// decoded, or as stored (DECODED: already the kernels' convention).
fn sraa_geometry(v: vec4<f32>) -> subcone_Geometry {
    if DECODED {
        return subcone_Geometry(v.xyz, v.w);
    }
    let z = sraa_decode_depth(v.w);
    if z == subcone_inf() {
        return subcone_Geometry(vec3<f32>(0.0), z);
    }
    return subcone_Geometry(sraa_decode_normal(v.xyz), z);
}

// Geometric subsample k of pixel p (at SUBPIXEL_OFFSETS[k]).
fn sraa_sub_geo(p: vec2<i32>, k: u32) -> subcone_Geometry {
    return sraa_geometry(sraa_load_sub(p, k));
}

// The geometry of pixel p's shaded sample: its own (SHADED_GIVEN: the
// pixel centre's when the preset shades there, or a host's shaded geometry),
// else subsample SHADED_SUBSAMPLE.
fn sraa_shaded_geo(p: vec2<i32>) -> subcone_Geometry {
    if SHADED_GIVEN {
        return sraa_geometry(sraa_load_shaded(p));
    }
    return sraa_sub_geo(p, subcone_SHADED_SUBSAMPLE);
}

// A secondary hit's geometry from (normal, path length): a NaN depth (no
// mirror here, excluded by every weight) for a negative or NaN length, a
// miss for 0 or +inf, else a hit; as stored with DECODED.
fn sraa_secondary_geometry(v: vec4<f32>) -> subcone_Geometry {
    if DECODED {
        return subcone_Geometry(v.xyz, v.w);
    }
    if subcone_is_nan(v.w) || v.w < 0.0 {
        return subcone_Geometry(vec3<f32>(0.0), bitcast<f32>(0x7fc00000u));
    }
    if v.w == 0.0 || v.w == subcone_inf() {
        return subcone_Geometry(vec3<f32>(0.0), subcone_inf());
    }
    return subcone_Geometry(sraa_decode_normal(v.xyz), v.w);
}

// The hooks of the reconstruction loop (subcone_kernels::sraa::RECONSTRUCT_WGSL).
const SRAA_GATES: u32 = 1u + LIGHTS;
const SRAA_MATERIAL: bool = MATERIAL;

fn sraa_params() -> subcone_SraaParams {
    return frame.sraa;
}

fn sraa_size() -> vec2<u32> {
    return vec2<u32>(frame.width, frame.height);
}

fn sraa_albedo_tolerance() -> f32 {
    return frame.albedo_tolerance;
}

fn sraa_shaded_geometry(x: u32, y: u32, secondary: bool) -> subcone_Geometry {
    let p = sraa_texel(x, y);
    if secondary {
        return sraa_secondary_geometry(sraa_load_sec_shaded(p));
    }
    return sraa_shaded_geo(p);
}

fn sraa_shaded_shadow(x: u32, y: u32, secondary: bool) -> u32 {
    let p = sraa_texel(x, y);
    if secondary {
        return sraa_load_sec_shaded_shadow(p);
    }
    return sraa_load_shaded_shadow(p);
}

fn sraa_shaded_albedo(x: u32, y: u32) -> vec3<f32> {
    return sraa_load_shaded_albedo(sraa_texel(x, y));
}

fn sraa_shaded_value(x: u32, y: u32, layer: u32) -> vec3<f32> {
    return sraa_load_color(sraa_texel(x, y), layer);
}

// Subsample k of pixel (x, y), reconstructed: its primary layers, plus its
// secondary layers where it sees a mirror (§3.3).
fn sraa_reconstruct_subsample(x: u32, y: u32, k: u32) -> vec3<f32> {
    let p = sraa_texel(x, y);
    var c = subcone_sraa_reconstruct_run(sraa_sub_geo(p, k), sraa_load_sub_shadow(p, k), sraa_load_sub_albedo(p, k), false, 0u, x, y, k);
    if SECONDARY {
        let tgt2 = sraa_secondary_geometry(sraa_load_sec_sub(p, k));
        if !subcone_is_nan(tgt2.depth) {
            c = c + subcone_sraa_reconstruct_run(tgt2, sraa_load_sec_sub_shadow(p, k), vec3<f32>(0.0), true, SRAA_GATES, x, y, k);
        }
    }
    return c;
}

@compute @workgroup_size(8, 8)
fn sraa_resolve_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let s0 = sraa_reconstruct_subsample(id.x, id.y, 0u);
    let s1 = sraa_reconstruct_subsample(id.x, id.y, 1u);
    let s2 = sraa_reconstruct_subsample(id.x, id.y, 2u);
    let s3 = sraa_reconstruct_subsample(id.x, id.y, 3u);
    // sraa::ResolveSpace: the box (sraa::resolve_pixel) or Karis' weights
    // (sraa::resolve_pixel_tone_mapped).
    var c: vec3<f32>;
    if TONE_MAPPED_RESOLVE {
        c = subcone_resolve_pixel_tone_mapped(s0, s1, s2, s3, frame.exposure);
    } else {
        c = subcone_resolve_pixel(s0, s1, s2, s3);
    }
    sraa_store(sraa_texel(id.x, id.y), vec4<f32>(c, 1.0));
}
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
@group(0) @binding(0) var<uniform> frame: SraaFrame;
@group(0) @binding(1) var sub_depth: texture_2d_array<f32>;
@group(0) @binding(2) var centre_depth: texture_2d<f32>;
@group(0) @binding(3) var centre_normal: texture_2d<f32>;
@group(0) @binding(4) var color: texture_2d<f32>;
@group(0) @binding(5) var sraa_output: texture_storage_2d<rgba32float, write>;
