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
// WGSL mirror of subcone_kernels::cone (CTSS §3.1, §3.2, §3.6).
// Functions only; needs nothing but core WGSL. NaN tests use the bits, so no
// compiler may fold them away.

// subcone_kernels::cone::OCCLUSION_MIN / subcone_OCCLUSION_MAX
const subcone_OCCLUSION_MIN: f32 = -1.0;
const subcone_OCCLUSION_MAX: f32 = 2.0;


// f32::next_up: the next representable value above x (x finite).
fn subcone_next_up(x: f32) -> f32 {
    let b = bitcast<u32>(x);
    if (b & 0x7fffffffu) == 0u {
        return bitcast<f32>(1u);
    }
    if (b & 0x80000000u) == 0u {
        return bitcast<f32>(b + 1u);
    }
    return bitcast<f32>(b - 1u);
}

// subcone_kernels::cone::cone_radius — eq. 4: R_c = t·tan θ (0 for t ≤ 0).
fn subcone_cone_radius(t: f32, tan_theta: f32) -> f32 {
    if t > 0.0 && tan_theta > 0.0 {
        return t * tan_theta;
    }
    return 0.0;
}

// subcone_kernels::cone::cone_occlusion — eq. 5: ω = (1 − d/R_c)/2, saturated
// to [−1, 2]; NaN d gives −1; a thin cone or infinite d gives the sign's limit.
fn subcone_cone_occlusion(d: f32, rc: f32) -> f32 {
    if subcone_is_nan(d) {
        return subcone_OCCLUSION_MIN;
    }
    let thin = !(rc > 0.0);
    var omega: f32;
    if thin || !subcone_is_finite(d) {
        if d > 0.0 {
            omega = subcone_OCCLUSION_MIN;
        } else if d < 0.0 {
            omega = subcone_OCCLUSION_MAX;
        } else {
            omega = 0.5;
        }
    } else if !subcone_is_finite(rc) {
        omega = 0.5;
    } else {
        omega = (1.0 - d / rc) * 0.5;
    }
    return clamp(omega, subcone_OCCLUSION_MIN, subcone_OCCLUSION_MAX);
}

// subcone_kernels::cone::OcclusionThresholds::with_eps — §3.2: (soft, hard,
// full) = (0 − ε, 0.5 − ε, 1 − ε).
fn subcone_occlusion_thresholds(eps: f32) -> vec3<f32> {
    return vec3<f32>(0.0 - eps, 0.5 - eps, 1.0 - eps);
}

// subcone_kernels::cone::min_step — §3.1: s_min = α·R_c (≥ 0).
fn subcone_min_step(alpha: f32, rc: f32) -> f32 {
    let s = alpha * rc;
    if s > 0.0 {
        return s;
    }
    return 0.0;
}

// subcone_kernels::cone::advance — t + max(d, s_min), at least one ulp.
fn subcone_advance(t: f32, d: f32, alpha: f32, rc: f32) -> f32 {
    let ms = subcone_min_step(alpha, rc);
    // f32::max ignores a NaN d.
    var step = ms;
    if !subcone_is_nan(d) && d > ms {
        step = d;
    }
    let next = t + step;
    if next > t {
        return next;
    } else if subcone_is_finite(t) {
        return subcone_next_up(t);
    }
    return subcone_inf();
}

// subcone_kernels::cone::backtrace_cone_entry — eq. 9–10: t* = t_i / (1 + tan θ).
fn subcone_backtrace_cone_entry(t_i: f32, tan_theta: f32) -> f32 {
    if !(t_i > 0.0) {
        if subcone_is_nan(t_i) {
            return 0.0;
        }
        return max(t_i, 0.0);
    }
    if !(tan_theta > 0.0) {
        return t_i;
    }
    let ts = t_i / (1.0 + tan_theta);
    return min(ts, t_i);
}

// subcone_kernels::cone::backtrace_hard_hit — §3.6: t_{i−1} + d_{i−1}, within [t_{i−1}, t_i].
fn subcone_backtrace_hard_hit(t_prev: f32, d_prev: f32, t_i: f32) -> f32 {
    let ts = t_prev + d_prev;
    if subcone_is_nan(ts) {
        return t_prev;
    }
    return min(max(ts, t_prev), t_i);
}
// WGSL mirror of subcone_kernels::mask (CTSS §3.4–3.5, Fig. 6, eq. 7–8).
// Needs cone.wgsl (subcone_is_nan, subcone_is_finite).

// subcone_kernels::mask::GRID_SCALE: √(9π/32), the 32 cells have the disk's area.
const subcone_GRID_SCALE: f32 = 0.9399856f;
// subcone_kernels::mask::FARTHEST_CENTRE
const subcone_FARTHEST_CENTRE: f32 = subcone_GRID_SCALE * 0.9718253f;

// subcone_kernels::mask::FULL_MASK — every cell of the pixel's disk.
const subcone_FULL_MASK: u32 = 0xffffffffu;

// subcone_kernels::mask::MaskPlacement codes.
const subcone_MASK_DERIVED: u32 = 0u;
const subcone_MASK_AUTHORS_CODE: u32 = 1u;
const subcone_MASK_PAPER_EQ8: u32 = 2u;

// subcone_kernels::mask::project_normal — n_p = (n·right, n·up) of the unit normal.
fn subcone_project_normal(normal: vec3<f32>, right: vec3<f32>, up: vec3<f32>) -> vec2<f32> {
    let a = abs(normal);
    let m = max(max(a.x, a.y), a.z);
    if !(m > 0.0) || !subcone_is_finite(m) {
        return vec2<f32>(0.0);
    }
    var n = normal / m;
    n = n * (1.0 / sqrt(dot(n, n)));
    let p = vec2<f32>(dot(n, right), dot(n, up));
    if subcone_is_finite(p.x) && subcone_is_finite(p.y) {
        return p;
    }
    return vec2<f32>(0.0);
}

// subcone_kernels::mask::occlusion_to_distance — d/R_c = 1 − 2ω (eq. 5 inverted).
fn subcone_occlusion_to_distance(omega: f32) -> f32 {
    return 1.0 - 2.0 * omega;
}

// subcone_kernels::mask::half_plane — the covered half-plane q·dir < h;
// returns (dir, h, 1) or (0, 0, 0, 0) for None.
fn subcone_half_plane(occlusion: f32, projected_normal: vec2<f32>, placement: u32) -> vec4<f32> {
    let len = length(projected_normal);
    if !(len > 0.0) || !subcone_is_finite(len) {
        return vec4<f32>(0.0);
    }
    let dir = projected_normal / len;
    let delta = subcone_occlusion_to_distance(occlusion);
    var h: f32;
    if placement == subcone_MASK_AUTHORS_CODE {
        h = -delta;
    } else if placement == subcone_MASK_PAPER_EQ8 {
        h = delta * min(len, 1.0);
    } else {
        h = -delta / min(len, 1.0);
    }
    if subcone_is_nan(h) {
        h = -2.0;
    } else {
        h = clamp(h, -2.0, 2.0);
    }
    return vec4<f32>(dir, h, 1.0);
}

// subcone_kernels::mask::CELL_XY — centre of the cell held by `bit`, in units
// of s/3: (c − 2.5, r − 2.5) (Fig. 6b layout: rows 0 and 5 hold columns 1–4).
fn subcone_mask_cell_xy(bit: u32) -> vec2<f32> {
    var r: u32;
    var c: u32;
    if bit < 4u {
        r = 0u;
        c = bit + 1u;
    } else if bit < 28u {
        r = 1u + (bit - 4u) / 6u;
        c = (bit - 4u) % 6u;
    } else {
        r = 5u;
        c = bit - 27u;
    }
    return vec2<f32>(f32(c) - 2.5, f32(r) - 2.5);
}

// subcone_kernels::mask::half_plane_mask — rasterise q·dir < h on the 32-cell grid.
// Cell (r, c) is covered when (c − 2.5)·dx + (r − 2.5)·dy < (3/s)·h (centres
// (s/3)·(c − 2.5, r − 2.5)); no division. |dx| < 1e-6 counts as 0 (rows all
// or nothing, §3.5).
fn subcone_half_plane_mask(dir: vec2<f32>, h: f32) -> u32 {
    let dx = select(dir.x, 0.0, abs(dir.x) < 1e-6);
    let hs = (3.0 / subcone_GRID_SCALE) * h;
    var mask = 0u;
    for (var bit = 0u; bit < 32u; bit++) {
        let q = subcone_mask_cell_xy(bit);
        if q.x * dx + q.y * dir.y < hs {
            mask |= 1u << bit;
        }
    }
    return mask;
}

// subcone_kernels::mask::visibility_mask — eq. 7–8 (Derived placement by default).
fn subcone_visibility_mask(occlusion: f32, projected_normal: vec2<f32>, placement: u32) -> u32 {
    if subcone_is_nan(occlusion) {
        return 0u;
    }
    let hp = subcone_half_plane(occlusion, projected_normal, placement);
    if hp.w > 0.0 {
        return subcone_half_plane_mask(hp.xy, hp.z);
    }
    if occlusion >= 0.5 {
        return 0xffffffffu;
    }
    return 0u;
}

// subcone_kernels::mask::needs_normal — whether the mask depends on the normal.
fn subcone_needs_normal(occlusion: f32, placement: u32) -> bool {
    if subcone_is_nan(occlusion) {
        return false;
    }
    let delta = subcone_occlusion_to_distance(occlusion);
    if placement == subcone_MASK_PAPER_EQ8 {
        return true;
    }
    return abs(delta) < subcone_FARTHEST_CENTRE;
}

// subcone_kernels::mask::mask_weight — bitCount(m)/32.
fn subcone_mask_weight(mask: u32) -> f32 {
    return f32(countOneBits(mask)) * (1.0 / 32.0);
}
// WGSL mirror of subcone_kernels::aggregate (CTSS §3.4, eq. 6). Needs
// mask.wgsl (subcone_mask_weight) and cone.wgsl (subcone_is_finite).
//
// The CPU accumulates Σw·C in f64 (subcone_kernels::sum); WGSL has no f64, so
// this sums in f32. The results differ only when weights or colours are so
// small that their products leave f32's normal range (below ~1e-38).

// subcone_kernels::aggregate::Weighting codes.
const subcone_WEIGHTING_VISIBILITY: u32 = 0u;
const subcone_WEIGHTING_UNIFORM: u32 = 1u;

// subcone_kernels::aggregate::sample_weight — w_i = bitCount(visible)/32 (eq. 6).
fn subcone_sample_weight(visible: u32, weighting: u32, min_weight: f32) -> f32 {
    if weighting == subcone_WEIGHTING_UNIFORM {
        return 1.0;
    }
    var floor_w = 0.0;
    if min_weight > 0.0 {
        floor_w = min(min_weight, 1.0);
    }
    return max(subcone_mask_weight(visible), floor_w);
}

// subcone_kernels::aggregate::Aggregate
struct subcone_Aggregate {
    sum: vec3<f32>,
    weight: f32,
    last: vec3<f32>,
    has_last: u32,
    samples: u32,
}

// subcone_kernels::aggregate::Aggregate::new
fn subcone_aggregate_new() -> subcone_Aggregate {
    return subcone_Aggregate(vec3<f32>(0.0), 0.0, vec3<f32>(0.0), 0u, 0u);
}

fn subcone_finite3(c: vec3<f32>) -> bool {
    return subcone_is_finite(c.x) && subcone_is_finite(c.y) && subcone_is_finite(c.z);
}

// subcone_kernels::aggregate::Aggregate::add
fn subcone_aggregate_add(agg: ptr<function, subcone_Aggregate>, w: f32, color: vec3<f32>) {
    (*agg).samples += 1u;
    if !subcone_finite3(color) {
        return;
    }
    var wc = 0.0;
    if w > 0.0 {
        wc = min(w, 1.0);
    }
    (*agg).sum += wc * color;
    (*agg).weight += wc;
    (*agg).last = color;
    (*agg).has_last = 1u;
}

// subcone_kernels::aggregate::Aggregate::resolve — Σ w_i C_i / Σ w_i with the
// background as a sample of weight bg_weight.
fn subcone_aggregate_resolve(agg: subcone_Aggregate, background: vec3<f32>, bg_weight: f32) -> vec3<f32> {
    var bgw = 0.0;
    if bg_weight > 0.0 && subcone_finite3(background) {
        bgw = min(bg_weight, 1.0);
    }
    var sum = agg.sum;
    var weight = agg.weight;
    if bgw > 0.0 {
        sum += bgw * background;
        weight += bgw;
    }
    if weight >= subcone_NEGLIGIBLE_WEIGHT {
        let inv = 1.0 / weight;
        let c = sum * inv;
        if subcone_finite3(c) {
            return c;
        }
    }
    if agg.has_last != 0u {
        return agg.last;
    }
    if subcone_finite3(background) {
        return background;
    }
    return vec3<f32>(0.0);
}
// WGSL mirror of subcone_kernels::transparency: the K bitmasks of CTSS §5.3
// (non-binary visibility for semi-transparent surfaces). Each of the pixel's
// 32 mask cells carries an opacity level l in 0..=K, stored as K nested
// masks M_k = {cells with l >= k}; a surface of opacity alpha over a cell
// with r = K - l levels of transmittance left keeps
// floor(r·(1 − alpha) + 1/2) of them, and the sample's eq. 6 weight is the
// transmittance it took, gained/(32·K). With opaque surfaces only every
// level is 0 or K and all of this reduces to the single mask M of §3.4.
//
// Needs PARAMS (subcone_is_nan) and mask.wgsl (subcone_FULL_MASK).
// Integer parts are exact; the one float step, remaining_after's
// floor(r·(1 − alpha) + 0.5), may be fused by a GPU, which can move an
// alpha within an ulp of a rounding boundary to the next level.

// subcone_kernels::transparency::LEVELS — K, the masks per pixel.
const subcone_LEVELS: u32 = 4u;

// subcone_kernels::transparency::clamp_alpha — alpha in [0, 1]; NaN is opaque.
fn subcone_clamp_alpha(alpha: f32) -> f32 {
    if subcone_is_nan(alpha) {
        return 1.0;
    }
    return clamp(alpha, 0.0, 1.0);
}

// subcone_kernels::transparency::remaining_after — levels of transmittance a
// cell with r left keeps under a surface of opacity alpha:
// floor(r·(1 − alpha) + 1/2), in [0, r] (r capped at K).
fn subcone_remaining_after(r0: u32, alpha: f32) -> u32 {
    let r = min(r0, subcone_LEVELS);
    let a = subcone_clamp_alpha(alpha);
    let keep = u32(max(floor(f32(r) * (1.0 - a) + 0.5), 0.0));
    return min(keep, r);
}

// subcone_kernels::transparency::is_opaque — a surface of this opacity leaves
// no transmittance in a clear cell (alpha > 0.875 for K = 4, and NaN).
fn subcone_is_opaque(alpha: f32) -> bool {
    return subcone_remaining_after(subcone_LEVELS, alpha) == 0u;
}

// subcone_kernels::transparency::level_weight — gained/(32·K), gained capped
// at 32·K; for an opaque surface exactly mask_weight of its visible cells.
fn subcone_level_weight(gained: u32) -> f32 {
    return f32(min(gained, 32u * subcone_LEVELS)) * (1.0 / f32(32u * subcone_LEVELS));
}

// subcone_kernels::transparency::TransparencyAccumulator — planes[k − 1] = M_k.
struct subcone_TransparencyAccumulator {
    planes: vec4<u32>,
}

// subcone_kernels::transparency::TransparencyAccumulator::new — every cell clear.
fn subcone_transparency_accumulator_new() -> subcone_TransparencyAccumulator {
    return subcone_TransparencyAccumulator(vec4<u32>(0u));
}

// subcone_kernels::transparency::TransparencyAccumulator::plane — M_k for k in
// 1..=K; M_0 is every cell, M_{K+1} none.
fn subcone_transparency_accumulator_plane(acc: subcone_TransparencyAccumulator, k: u32) -> u32 {
    if k == 0u {
        return subcone_FULL_MASK;
    }
    if k > subcone_LEVELS {
        return 0u;
    }
    return acc.planes[k - 1u];
}

// subcone_kernels::transparency::TransparencyAccumulator::level_set — the
// cells at exactly level l: M_l & !M_{l+1}.
fn subcone_transparency_accumulator_level_set(acc: subcone_TransparencyAccumulator, l: u32) -> u32 {
    return subcone_transparency_accumulator_plane(acc, l) & ~subcone_transparency_accumulator_plane(acc, l + 1u);
}

// subcone_kernels::transparency::TransparencyAccumulator::level — the level of
// cell bit (0..32, capped at 31), in 0..=K.
fn subcone_transparency_accumulator_level(acc: subcone_TransparencyAccumulator, bit: u32) -> u32 {
    let b = 1u << min(bit, 31u);
    var n = 0u;
    for (var k = 0u; k < subcone_LEVELS; k++) {
        if (acc.planes[k] & b) != 0u {
            n += 1u;
        }
    }
    return n;
}

// subcone_kernels::transparency::TransparencyAccumulator::add — composite a
// surface of opacity alpha over the cells of mask, front to back; returns
// (visible, gained): the cells whose level rose and the levels gained summed
// over cells (the weight is subcone_level_weight(gained)). alpha = 1 is
// VisibilityAccumulator::add: visible = mask & !M_K, gained = K·bitCount.
fn subcone_transparency_accumulator_add(acc: ptr<function, subcone_TransparencyAccumulator>, mask: u32, alpha: f32) -> vec2<u32> {
    var next = (*acc).planes & vec4<u32>(~mask);
    var visible = 0u;
    var gained = 0u;
    for (var l = 0u; l <= subcone_LEVELS; l++) {
        let cells = subcone_transparency_accumulator_level_set(*acc, l) & mask;
        if cells == 0u {
            continue;
        }
        let to = subcone_LEVELS - subcone_remaining_after(subcone_LEVELS - l, alpha);
        if to > l {
            visible |= cells;
            gained += (to - l) * countOneBits(cells);
        }
        for (var k = 0u; k < to; k++) {
            next[k] |= cells;
        }
    }
    (*acc).planes = next;
    return vec2<u32>(visible, gained);
}

// subcone_kernels::transparency::TransparencyAccumulator::opaque — M_K, the
// fully opaque cells.
fn subcone_transparency_accumulator_opaque(acc: subcone_TransparencyAccumulator) -> u32 {
    return acc.planes[subcone_LEVELS - 1u];
}

// subcone_kernels::transparency::TransparencyAccumulator::is_binary — every
// cell clear or opaque (M_1 = M_K): what only opaque surfaces leave.
fn subcone_transparency_accumulator_is_binary(acc: subcone_TransparencyAccumulator) -> bool {
    return subcone_transparency_accumulator_plane(acc, 1u) == subcone_transparency_accumulator_opaque(acc);
}

// subcone_kernels::transparency::TransparencyAccumulator::total_levels — Σ l.
fn subcone_transparency_accumulator_total_levels(acc: subcone_TransparencyAccumulator) -> u32 {
    let c = countOneBits(acc.planes);
    return c.x + c.y + c.z + c.w;
}

// subcone_kernels::transparency::TransparencyAccumulator::uncovered_weight —
// the background's share, 1 − Σ l/(32·K).
fn subcone_transparency_accumulator_uncovered_weight(acc: subcone_TransparencyAccumulator) -> f32 {
    return 1.0 - subcone_level_weight(subcone_transparency_accumulator_total_levels(acc));
}
// WGSL mirror of subcone_kernels::ctss: Algorithm 1 of CTSS (§3.3, §3.6) as
// the subcone_ConeStepper state machine, and subcone_sphere_trace_split, the NoAA baseline
// with the same cone-based hit threshold (§4).
//
// Needs PARAMS (subcone_CtssParams), cone.wgsl, mask.wgsl, aggregate.wgsl and
// transparency.wgsl (the K masks of CTSS §5.3, for semi-transparent
// surfaces: subcone_cone_stepper_record_alpha_mask and the pass through a
// semi-transparent object). The
// SDF is the caller's: subcone_sphere_trace_split calls
//     fn ctss_field(p: vec3<f32>) -> vec2<f32>   // (surface distance, safe step)
// which the including shader defines. Every loop is bounded by max_steps.

// subcone_kernels::ctss::FLAG_RELAXED
const subcone_FLAG_RELAXED: u32 = 1u;
// subcone_kernels::ctss::FLAG_SPLIT_GROUPS
const subcone_FLAG_SPLIT_GROUPS: u32 = 2u;
// subcone_kernels::ctss::FLAG_PAPER
const subcone_FLAG_PAPER: u32 = 4u;
// subcone_kernels::ctss::GROUP_DIP
const subcone_GROUP_DIP: f32 = 0.1;
// subcone_kernels::ctss::NO_OBJECT
const subcone_NO_OBJECT: u32 = 0xffffffffu;

// subcone_kernels::ctss::StopReason codes (0 = still running).
const subcone_STOP_NONE: u32 = 0u;
const subcone_STOP_FULL_OCCLUSION: u32 = 1u;
const subcone_STOP_HARD_HIT: u32 = 2u;
const subcone_STOP_VISIBILITY_THRESHOLD: u32 = 3u;
const subcone_STOP_SAMPLE_CAP: u32 = 4u;
const subcone_STOP_MAX_DISTANCE: u32 = 5u;
const subcone_STOP_STEP_BUDGET: u32 = 6u;
const subcone_STOP_INVALID_DISTANCE: u32 = 7u;

// subcone_kernels::ctss::Event codes.
const subcone_EVENT_MARCH: u32 = 0u;
const subcone_EVENT_SAMPLE: u32 = 1u;
const subcone_EVENT_STOP: u32 = 2u;

// subcone_kernels::ctss::StopReason::covers_pixel
fn subcone_covers_pixel(reason: u32) -> bool {
    return reason == subcone_STOP_FULL_OCCLUSION || reason == subcone_STOP_HARD_HIT
        || reason == subcone_STOP_VISIBILITY_THRESHOLD;
}

// subcone_kernels::ctss::GroupSample
struct subcone_GroupSample {
    t: f32,
    t_entry: f32,
    t_exit: f32,
    occlusion: f32,
    t_occlusion: f32,
    t_first: f32,
    t_last: f32,
    hard: u32,
}

// subcone_kernels::ctss::Event: kind EVENT_*, the sample of subcone_EVENT_SAMPLE, the
// reason of subcone_EVENT_STOP.
struct subcone_CtssEvent {
    kind: u32,
    sample: subcone_GroupSample,
    reason: u32,
}

// subcone_kernels::ctss::ConeStepper (the group is open when group_open != 0).
struct subcone_ConeStepper {
    params: subcone_CtssParams,
    thresholds: vec3<f32>,
    t: f32,
    t_prev: f32,
    d_prev: f32,
    have_prev: u32,
    prev_soft: u32,
    prev_hard: u32,
    group_open: u32,
    g_t_entry: f32,
    g_t_sample: f32,
    g_occlusion: f32,
    g_t_occlusion: f32,
    g_t_first: f32,
    g_t_last: f32,
    g_hard: u32,
    g_object: u32,
    g_dip: f32,
    steps: u32,
    samples: u32,
    // subcone_kernels::mask::VisibilityAccumulator: the pixel's global mask M.
    covered: u32,
    stop: u32,
    pending_stop: u32,
    // subcone_kernels::ctss::ConeStepper's layers: the K masks of CTSS §5.3,
    // used instead of covered once record_alpha_mask is called (translucent
    // != 0).
    layers: subcone_TransparencyAccumulator,
    translucent: u32,
    // Marching through a semi-transparent object after its full occlusion.
    passing: u32,
}

fn subcone_ctss_is_relaxed(p: subcone_CtssParams) -> bool {
    return (p.flags & subcone_FLAG_RELAXED) != 0u;
}

// subcone_kernels::ctss::CtssParams::is_paper
fn subcone_ctss_is_paper(p: subcone_CtssParams) -> bool {
    return (p.flags & subcone_FLAG_PAPER) != 0u;
}

// subcone_kernels::ctss::CtssParams::splits_groups
fn subcone_ctss_splits_groups(p: subcone_CtssParams) -> bool {
    return (p.flags & subcone_FLAG_SPLIT_GROUPS) != 0u;
}

// subcone_kernels::ctss::CtssParams::placement (unknown codes → Derived)
fn subcone_ctss_placement(p: subcone_CtssParams) -> u32 {
    let v = (p.flags >> 8u) & 0xffu;
    return select(subcone_MASK_DERIVED, v, v <= 2u);
}

// subcone_kernels::ctss::CtssParams::weighting (unknown codes → Visibility)
fn subcone_ctss_weighting(p: subcone_CtssParams) -> u32 {
    let v = (p.flags >> 16u) & 0xffu;
    return select(subcone_WEIGHTING_VISIBILITY, v, v <= 1u);
}

fn subcone_ctss_event(kind: u32, reason: u32) -> subcone_CtssEvent {
    return subcone_CtssEvent(kind, subcone_GroupSample(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0u), reason);
}

// subcone_kernels::ctss::ConeStepper::new — start at t_min.
fn subcone_cone_stepper_new(params: subcone_CtssParams) -> subcone_ConeStepper {
    var t0 = 0.0;
    if params.t_min > 0.0 {
        t0 = params.t_min;
    }
    return subcone_ConeStepper(params, subcone_occlusion_thresholds(params.eps), t0, t0, 0.0, 0u, 0u, 0u,
        0u, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0u, subcone_NO_OBJECT, 0.0, 0u, 0u, 0u, subcone_STOP_NONE, 0u,
        subcone_transparency_accumulator_new(), 0u, 0u);
}

// The open group's sample, exit at t_exit.
fn subcone_cone_stepper_group_sample(s: ptr<function, subcone_ConeStepper>, t_exit: f32) -> subcone_GroupSample {
    return subcone_GroupSample((*s).g_t_sample, (*s).g_t_entry, t_exit, (*s).g_occlusion, (*s).g_t_occlusion,
        (*s).g_t_first, (*s).g_t_last, (*s).g_hard);
}

// subcone_kernels::ctss::ConeStepper::end (private): sample a group still open.
fn subcone_cone_stepper_end(s: ptr<function, subcone_ConeStepper>, reason: u32, t_exit: f32) -> subcone_CtssEvent {
    (*s).stop = reason;
    if (*s).group_open != 0u {
        (*s).group_open = 0u;
        (*s).samples += 1u;
        return subcone_CtssEvent(subcone_EVENT_SAMPLE, subcone_cone_stepper_group_sample(s, t_exit), subcone_STOP_NONE);
    }
    return subcone_ctss_event(subcone_EVENT_STOP, reason);
}

// subcone_kernels::ctss::ConeStepper::advance_split — Algorithm 1, lines 7–26:
// d (surface distance) decides occlusion and hit groups, step (≤ d) the march.
fn subcone_cone_stepper_advance_split(s: ptr<function, subcone_ConeStepper>, d: f32, step: f32) -> subcone_CtssEvent {
    return subcone_cone_stepper_advance_object(s, d, step, subcone_NO_OBJECT);
}

// subcone_kernels::ctss::ConeStepper::advance_object — advance_split with the
// nearest object's id: unless FLAG_PAPER, a group ends where it changes, or
// where the occlusion rises by GROUP_DIP after a dip as deep.
fn subcone_cone_stepper_advance_object(s: ptr<function, subcone_ConeStepper>, d: f32, step: f32, object: u32) -> subcone_CtssEvent {
    if (*s).stop != subcone_STOP_NONE {
        return subcone_ctss_event(subcone_EVENT_STOP, (*s).stop);
    }
    let relaxed = subcone_ctss_is_relaxed((*s).params);
    if (*s).pending_stop != 0u {
        (*s).pending_stop = 0u;
        let reason = select(subcone_STOP_FULL_OCCLUSION, subcone_STOP_HARD_HIT, relaxed);
        return subcone_cone_stepper_end(s, reason, subcone_backtrace_cone_entry((*s).t, (*s).params.tan_theta));
    }
    let t = (*s).t;
    if (*s).steps >= (*s).params.max_steps {
        return subcone_cone_stepper_end(s, subcone_STOP_STEP_BUDGET, t);
    }
    if !(t < (*s).params.t_max) {
        return subcone_cone_stepper_end(s, subcone_STOP_MAX_DISTANCE, t);
    }
    if subcone_is_nan(d) {
        return subcone_cone_stepper_end(s, subcone_STOP_INVALID_DISTANCE, t);
    }
    (*s).steps += 1u;

    let tan = (*s).params.tan_theta;
    let rc = subcone_cone_radius(t, tan);
    let omega = subcone_cone_occlusion(d, rc);
    let th = (*s).thresholds;
    let soft = omega > th.x;
    let hard = omega > th.y;
    let stop_at = select(th.z, th.y, relaxed);
    var stop = omega > stop_at;
    if (*s).passing != 0u {
        // Inside (or just behind) a semi-transparent object whose full
        // occlusion did not end the trace (record_alpha_mask): no stop and no
        // new group until the cone leaves it, or until the distance, outside
        // the object, shrinks again: another surface lies within the cone,
        // and it starts a group of its own here.
        if d > 0.0 && (*s).have_prev != 0u && d < (*s).d_prev {
            (*s).passing = 0u;
            (*s).prev_soft = 0u;
            (*s).prev_hard = 0u;
        } else {
            stop = false;
        }
    }

    // Beyond the paper: one surface per group.
    var closed = false;
    var closed_sample = subcone_GroupSample(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0u);
    if soft && (*s).prev_soft != 0u && !subcone_ctss_is_paper((*s).params) && (*s).passing == 0u
        && (*s).group_open != 0u {
        (*s).g_dip = min((*s).g_dip, omega);
        let other = object != (*s).g_object && object != subcone_NO_OBJECT && (*s).g_object != subcone_NO_OBJECT;
        let rises = (*s).g_dip < (*s).g_occlusion - subcone_GROUP_DIP && omega > (*s).g_dip + subcone_GROUP_DIP;
        if other || rises {
            closed = true;
            closed_sample = subcone_cone_stepper_group_sample(s, t);
            (*s).group_open = 0u;
            (*s).samples += 1u;
            (*s).prev_hard = 0u;
            (*s).have_prev = 0u;
        }
    }
    if soft && ((*s).prev_soft == 0u || closed) {
        var te = t;
        if !closed {
            te = subcone_backtrace_cone_entry(t, tan);
        }
        (*s).group_open = 1u;
        (*s).g_t_entry = te;
        (*s).g_t_sample = te;
        (*s).g_occlusion = omega;
        (*s).g_t_occlusion = t;
        (*s).g_t_first = t;
        (*s).g_t_last = t;
        (*s).g_hard = 0u;
        (*s).g_object = object;
        (*s).g_dip = omega;
    }
    if soft && (*s).group_open != 0u {
        (*s).g_t_last = t;
        if omega > (*s).g_occlusion {
            (*s).g_occlusion = omega;
            (*s).g_t_occlusion = t;
            (*s).g_dip = omega;
        }
        if hard && (*s).prev_hard == 0u && (*s).g_hard == 0u {
            (*s).g_hard = 1u;
            if (*s).have_prev != 0u {
                (*s).g_t_sample = subcone_backtrace_hard_hit((*s).t_prev, (*s).d_prev, t);
            } else {
                (*s).g_t_sample = t;
            }
        }
    }
    let exit = !soft && (*s).prev_soft != 0u;
    if exit {
        (*s).passing = 0u;
    }
    (*s).prev_soft = select(0u, 1u, soft);
    (*s).prev_hard = select(0u, 1u, hard);

    // Rust's f32::min: a NaN step yields d.
    var m = d;
    if !subcone_is_nan(step) && step < d {
        m = step;
    }
    if closed {
        // The closed group is sampled now; the one opened here when it ends.
        (*s).t_prev = t;
        (*s).d_prev = d;
        (*s).have_prev = 1u;
        if (*s).samples >= (*s).params.max_samples {
            (*s).group_open = 0u;
            (*s).stop = subcone_STOP_SAMPLE_CAP;
        } else if stop {
            (*s).pending_stop = 1u;
        }
        if (*s).stop == subcone_STOP_NONE && (*s).pending_stop == 0u {
            (*s).t = subcone_advance(t, m, (*s).params.alpha, rc);
        }
        return subcone_CtssEvent(subcone_EVENT_SAMPLE, closed_sample, subcone_STOP_NONE);
    }

    var event = subcone_ctss_event(subcone_EVENT_MARCH, subcone_STOP_NONE);
    if exit || stop {
        if (*s).group_open != 0u {
            event = subcone_CtssEvent(subcone_EVENT_SAMPLE,
                subcone_cone_stepper_group_sample(s, subcone_backtrace_cone_entry(t, tan)), subcone_STOP_NONE);
            (*s).group_open = 0u;
            (*s).samples += 1u;
        }
        if stop {
            (*s).stop = select(subcone_STOP_FULL_OCCLUSION, subcone_STOP_HARD_HIT, relaxed);
        } else if (*s).samples >= (*s).params.max_samples {
            (*s).stop = subcone_STOP_SAMPLE_CAP;
        }
    }

    (*s).t_prev = t;
    (*s).d_prev = d;
    (*s).have_prev = 1u;
    if (*s).stop == subcone_STOP_NONE {
        // Through a semi-transparent object's inside, −d is a safe step.
        var step_by = m;
        if (*s).passing != 0u && d < 0.0 {
            step_by = -d;
        }
        (*s).t = subcone_advance(t, step_by, (*s).params.alpha, rc);
    }
    return event;
}

// subcone_kernels::ctss::ConeStepper::record — the sample's mask (eq. 7–8),
// correlated with M (m_i & !M, M |= m_i); returns (visible mask, weight bits).
fn subcone_cone_stepper_record(s: ptr<function, subcone_ConeStepper>, sample: subcone_GroupSample, projected_normal: vec2<f32>) -> vec2<u32> {
    let m = subcone_visibility_mask(sample.occlusion, projected_normal, subcone_ctss_placement((*s).params));
    return subcone_cone_stepper_record_mask(s, m);
}

// subcone_kernels::ctss::ConeStepper::takes_rest_of_pixel — whether
// record_mask ignores its mask: CTSS-R's hard hit (unless FLAG_PAPER) takes
// the rest of the pixel, so the caller can skip making the mask.
fn subcone_cone_stepper_takes_rest_of_pixel(s: ptr<function, subcone_ConeStepper>) -> bool {
    return !subcone_ctss_is_paper((*s).params) && (*s).stop == subcone_STOP_HARD_HIT;
}

// subcone_kernels::ctss::ConeStepper::record_mask — record with a mask the
// caller made (subcone_group_mask).
// CTSS-R (unless FLAG_PAPER): the group that ended the trace on its hard hit
// takes the rest of the pixel (full mask).
fn subcone_cone_stepper_record_mask(s: ptr<function, subcone_ConeStepper>, m0: u32) -> vec2<u32> {
    var m = m0;
    if subcone_cone_stepper_takes_rest_of_pixel(s) {
        m = 0xffffffffu;
    }
    let visible = m & ~(*s).covered;
    (*s).covered |= visible;
    if (*s).stop == subcone_STOP_NONE && countOneBits((*s).covered) >= (*s).params.visibility_k {
        (*s).stop = subcone_STOP_VISIBILITY_THRESHOLD;
    }
    let w = subcone_sample_weight(visible, subcone_ctss_weighting((*s).params), (*s).params.min_sample_weight);
    return vec2<u32>(visible, bitcast<u32>(w));
}

// subcone_kernels::ctss::ConeStepper::restart_grouping (private): forget the
// previous step for grouping, so that the next step touching a surface opens
// a new group whose hard hit is sampled at that step, not backtraced into the
// previous object.
fn subcone_cone_stepper_restart_grouping(s: ptr<function, subcone_ConeStepper>) {
    (*s).prev_soft = 0u;
    (*s).prev_hard = 0u;
    (*s).have_prev = 0u;
    (*s).passing = 0u;
}

// subcone_kernels::ctss::ConeStepper::is_passing — whether the trace is
// passing through a semi-transparent object (record_alpha_mask, §5.3).
fn subcone_cone_stepper_is_passing(s: subcone_ConeStepper) -> bool {
    return s.passing != 0u;
}

// subcone_kernels::ctss::ConeStepper::end_pass — end a pass through a
// semi-transparent object here (the caller saw the nearest object change):
// the next step opens a group on the object the ray has entered.
fn subcone_cone_stepper_end_pass(s: ptr<function, subcone_ConeStepper>) {
    if (*s).passing != 0u {
        subcone_cone_stepper_restart_grouping(s);
    }
}

// subcone_kernels::ctss::ConeStepper::in_group — a hit group is open.
fn subcone_cone_stepper_in_group(s: subcone_ConeStepper) -> bool {
    return s.group_open != 0u;
}

// subcone_kernels::ctss::ConeStepper::split_group — close the open group at
// the current depth (exit backtraced from t) so that the next advance starts
// a new one: one surface per group when the nearest object changes between a
// semi-transparent object and another (§5.3). Rust's Option<GroupSample> is
// an event: subcone_EVENT_SAMPLE with the group, or subcone_EVENT_MARCH for
// None (no open group, or the trace is over).
fn subcone_cone_stepper_split_group(s: ptr<function, subcone_ConeStepper>) -> subcone_CtssEvent {
    if (*s).stop != subcone_STOP_NONE || (*s).group_open == 0u {
        return subcone_ctss_event(subcone_EVENT_MARCH, subcone_STOP_NONE);
    }
    (*s).group_open = 0u;
    (*s).samples += 1u;
    subcone_cone_stepper_restart_grouping(s);
    if (*s).samples >= (*s).params.max_samples {
        (*s).stop = subcone_STOP_SAMPLE_CAP;
    }
    let t_exit = subcone_backtrace_cone_entry((*s).t, (*s).params.tan_theta);
    return subcone_CtssEvent(subcone_EVENT_SAMPLE, subcone_cone_stepper_group_sample(s, t_exit), subcone_STOP_NONE);
}

// subcone_kernels::ctss::ConeStepper::record_alpha_mask — record_mask for a
// surface of opacity alpha (CTSS §5.3): the mask is composited over the K
// masks instead of M, and the weight is the transmittance the sample took
// (subcone_level_weight). When the sample ended the trace on its occlusion
// rule but the surface is not opaque, or semi-transparent cells lie in front
// of it, the mask is full; a surface that is not opaque then lets the trace go
// on through the object (passing). Returns (visible mask, weight bits).
fn subcone_cone_stepper_record_alpha_mask(s: ptr<function, subcone_ConeStepper>, mask: u32, alpha: f32) -> vec2<u32> {
    (*s).translucent = 1u;
    let ended = (*s).stop == subcone_STOP_FULL_OCCLUSION || (*s).stop == subcone_STOP_HARD_HIT;
    var m = mask;
    // CTSS-R's hard hit takes the rest of the pixel by default (record_mask).
    let relaxed_full = !subcone_ctss_is_paper((*s).params) && (*s).stop == subcone_STOP_HARD_HIT;
    if ended && (!subcone_is_opaque(alpha) || !subcone_transparency_accumulator_is_binary((*s).layers) || relaxed_full) {
        m = subcone_FULL_MASK;
    }
    var layers = (*s).layers;
    let vg = subcone_transparency_accumulator_add(&layers, m, alpha);
    (*s).layers = layers;
    let opaque = subcone_transparency_accumulator_opaque(layers);
    if ended && !subcone_is_opaque(alpha) && opaque != subcone_FULL_MASK {
        (*s).stop = subcone_STOP_NONE;
        (*s).passing = 1u;
    }
    if (*s).stop == subcone_STOP_NONE && countOneBits(opaque) >= (*s).params.visibility_k {
        (*s).stop = subcone_STOP_VISIBILITY_THRESHOLD;
    }
    var w = 1.0;
    if subcone_ctss_weighting((*s).params) == subcone_WEIGHTING_VISIBILITY {
        var floor_w = 0.0;
        if (*s).params.min_sample_weight > 0.0 {
            floor_w = min((*s).params.min_sample_weight, 1.0);
        }
        w = max(subcone_level_weight(vg.y), floor_w);
    }
    return vec2<u32>(vg.x, bitcast<u32>(w));
}

// subcone_kernels::ctss::ConeStepper::coverage — the pixel's global mask M
// (M_K, the opaque cells, once record_alpha_mask was called).
fn subcone_cone_stepper_coverage(s: subcone_ConeStepper) -> u32 {
    if s.translucent != 0u {
        return subcone_transparency_accumulator_opaque(s.layers);
    }
    return s.covered;
}

// subcone_kernels::ctss::ConeStepper::background_weight — 0 when the hits cover
// the pixel, else 1 − bitCount(M)/32 (1 with uniform weights); for a trace
// through record_alpha_mask, the transmittance left, 1 − Σ l/(32·K).
fn subcone_cone_stepper_background_weight(s: subcone_ConeStepper) -> f32 {
    if s.stop != subcone_STOP_NONE && subcone_covers_pixel(s.stop) {
        return 0.0;
    }
    if subcone_ctss_weighting(s.params) == subcone_WEIGHTING_UNIFORM {
        return 1.0;
    }
    if s.translucent != 0u {
        return subcone_transparency_accumulator_uncovered_weight(s.layers);
    }
    return 1.0 - subcone_mask_weight(s.covered);
}

// subcone_kernels::ctss::SphereHit: t < 0 means no hit.
struct subcone_SphereHit {
    t: f32,
    steps: u32,
    stop: u32,
}

// One step of subcone_kernels::ctss::sphere_trace_split at depth *t, given the
// field's surface distance d and safe step there: the stop it makes
// (subcone_STOP_HARD_HIT or subcone_STOP_INVALID_DISTANCE), or
// subcone_STOP_NONE after moving *t on (eq. 1–2, the hit threshold
// ω > 0.5 − ε of §4). Shared by the two sphere traces below and in
// ctss/trace.wgsl, which read different hooks.
fn subcone_sphere_trace_step(params: subcone_CtssParams, t: ptr<function, f32>, d: f32, step: f32) -> u32 {
    if subcone_is_nan(d) {
        return subcone_STOP_INVALID_DISTANCE;
    }
    let rc = subcone_cone_radius(*t, params.tan_theta);
    if subcone_cone_occlusion(d, rc) > subcone_occlusion_thresholds(params.eps).y {
        return subcone_STOP_HARD_HIT;
    }
    // Rust's f32::min: a NaN step yields d.
    var m = d;
    if !subcone_is_nan(step) && step < d {
        m = step;
    }
    *t = subcone_advance(*t, m, 0.0, rc);
    return subcone_STOP_NONE;
}

// subcone_kernels::ctss::sphere_trace_split — eq. 1–2 with the hit threshold
// ω > 0.5 − ε of §4; the field is the caller's ctss_field (surface, safe).
fn subcone_sphere_trace_split(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>) -> subcone_SphereHit {
    var t = 0.0;
    if params.t_min > 0.0 {
        t = params.t_min;
    }
    var steps = 0u;
    // One evaluation per iteration: the loop ends within max_steps.
    for (var i = 0u; i < params.max_steps; i++) {
        if !(t < params.t_max) {
            return subcone_SphereHit(-1.0, steps, subcone_STOP_MAX_DISTANCE);
        }
        let f = ctss_field(origin + t * dir);
        steps += 1u;
        let t_hit = t;
        let stop = subcone_sphere_trace_step(params, &t, f.x, f.y);
        if stop != subcone_STOP_NONE {
            return subcone_SphereHit(select(-1.0, t_hit, stop == subcone_STOP_HARD_HIT), steps, stop);
        }
    }
    return subcone_SphereHit(-1.0, steps, subcone_STOP_STEP_BUDGET);
}

// glam's Vec3::normalize_or_zero: v·(1/|v|), or 0 when that is not finite.
fn subcone_normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let rcp = 1.0 / length(v);
    if subcone_is_finite(rcp) && rcp > 0.0 {
        return v * rcp;
    }
    return vec3<f32>(0.0);
}

// subcone_kernels::ctss::cross_section_frame — the cone cross-section's axes
// (right, up) for a ray dir; (X, Y) for a zero or non-finite dir.
fn subcone_cross_section_frame(dir: vec3<f32>, up_hint: vec3<f32>) -> mat2x3<f32> {
    let d = subcone_normalize_or_zero(dir);
    if all(d == vec3<f32>(0.0)) {
        return mat2x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0));
    }
    var right = subcone_normalize_or_zero(cross(d, up_hint));
    if all(right == vec3<f32>(0.0)) {
        // glam's any_orthonormal_vector (Duff et al.).
        let sgn = select(-1.0, 1.0, d.z >= 0.0);
        let a = -1.0 / (sgn + d.z);
        let b = d.x * d.y * a;
        right = vec3<f32>(b, sgn + d.y * d.y * a, -d.y);
    }
    return mat2x3<f32>(right, cross(right, d));
}
// WGSL mirror of subcone_kernels::ctss::trace: the one CTSS trace
// (Algorithm 1 through subcone_ConeStepper, the normals, the group masks of
// §3.4–3.5 with the thin-shell rule, the §5.3 group splits and eq. 6), as
// subcone_ctss_trace, plus the §5.3 split kernels of subcone_kernels::ctss
// (group_needs_split, split_weights, split_direction, split_trace_params,
// split_group, coarse_normal_step), which only this trace uses.
//
// Needs PARAMS, cone.wgsl, mask.wgsl, aggregate.wgsl and ctss.wgsl before it
// (subcone_kernels::ctss::TRACE_WGSL). The scene is the including shader's,
// through four hooks (the ConeField trait and trace_field's shade closure):
//
//     fn subcone_field(p: vec3<f32>) -> vec3<f32>
//         ConeField::sample: (signed distance, safe step ≤ distance, object
//         id). The id is an exact integer in f32 (a material index, say; every
//         integer below 2^24 is exact); a negative or NaN id is NO_OBJECT,
//         which never ends a group.
//     fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32>
//         ConeField::normal: the unit normal at p from differences of step h.
//         `return subcone_tetra_normal(p, h);` is the trait's default. It is
//         also the coarse normal of ctss+edges (ConeField::coarse_normal's
//         default), called with subcone_coarse_normal_step.
//     fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32>
//         trace_field's shade(point, normal, dir): the colour of a surface point
//         seen along dir. A host that counts work done while shading (shadow
//         rays) counts it in a var<private> of its own.
//     const subcone_CTSS_BATCH: u32
//         How many hit groups the trace marches ahead of shading them (≥ 1).
//         The groups wait, in order, and are shaded together when the march
//         ends or the batch is full: the lanes of a SIMD group march together
//         and shade together instead of idling while one lane shades (traces
//         shadows). This is the GPU's bounded form of delayed shading (§5.1);
//         eq. 6 adds the same terms in the same order whatever the batch, so
//         the result does not depend on it. The wgpu backend uses 8 for ASAP
//         methods, 32 for ctss-delayed.
//
// Every loop is bounded: the march by max_steps (plus the stepper's few
// closing calls), the sub-traces of a split by SPLIT_MAX_STEPS.

// subcone_kernels::ctss::SHEET_PROBE
const subcone_SHEET_PROBE: f32 = 0.2;
// subcone_kernels::ctss::SHELL_LENGTH
const subcone_SHELL_LENGTH: f32 = 5.0;
// subcone_kernels::ctss::SPLIT_MIN_COS (cos 20°)
const subcone_SPLIT_MIN_COS: f32 = 0.9396926;
// subcone_kernels::ctss::SPLIT_LENGTH_RATIO
const subcone_SPLIT_LENGTH_RATIO: f32 = 8.0;
// subcone_kernels::ctss::SPLIT_MAX_STEPS
const subcone_SPLIT_MAX_STEPS: u32 = 32u;
// subcone_kernels::ctss::SPLIT_QUADRANTS: (−x, −y), (+x, −y), (−x, +y), (+x, +y).
// A vector, not an array: naga writes a constant array in HLSL through a
// constructor function that glslang's HLSL front end takes for recursion.
const subcone_SPLIT_QUADRANTS: vec4<u32> = vec4<u32>(0x00001C73u, 0x0000E38Cu, 0x31C70000u, 0xCE380000u);
// subcone_kernels::ctss::SPLIT_OFFSETS: ±(11/8)·GRID_SCALE/3 in both axes, in
// the order of the quadrants (evaluated in f32 as the Rust const is).
const subcone_SPLIT_OFFSET: f32 = 1.375 * subcone_GRID_SCALE / 3.0;

// u32::saturating_add.
fn subcone_saturating_add(a: u32, b: u32) -> u32 {
    let s = a + b;
    return select(s, 0xffffffffu, s < a);
}

// subcone_kernels::ctss::FieldSample (the object as an integer).
struct subcone_FieldSample {
    distance: f32,
    step: f32,
    object: u32,
}

// The host's subcone_field as a subcone_FieldSample: a negative or NaN id is
// NO_OBJECT.
fn subcone_field_sample(p: vec3<f32>) -> subcone_FieldSample {
    let f = subcone_field(p);
    var object = subcone_NO_OBJECT;
    if f.z >= 0.0 && f.z < 4294967296.0 {
        object = u32(f.z);
    }
    return subcone_FieldSample(f.x, f.y, object);
}

// subcone_kernels::ctss::SplitRay: the pixel's ray and its cross-section axes.
struct subcone_SplitRay {
    origin: vec3<f32>,
    dir: vec3<f32>,
    right: vec3<f32>,
    up: vec3<f32>,
}

// subcone_kernels::ctss::TraceResult; stop is a subcone_STOP_* code, depth
// the sample depth of the nearest group of weight above 0 (+inf: none).
struct subcone_CtssTraceResult {
    color: vec3<f32>,
    samples: u32,
    steps: u32,
    coverage: u32,
    stop: u32,
    depth: f32,
}

// subcone_kernels::ctss::coverage_alpha — bitCount(M)/32 (§3.4–3.5), or 1
// when the trace ended on a rule that gives the background no weight.
fn subcone_ctss_coverage_alpha(coverage: u32, stop: u32) -> f32 {
    if subcone_covers_pixel(stop) {
        return 1.0;
    }
    return subcone_mask_weight(coverage);
}

// subcone_kernels::ctss::GroupHit: a closed group waiting to be shaded.
struct subcone_GroupHit {
    sample: subcone_GroupSample,
    point: vec3<f32>,
    normal: vec3<f32>,
    visible: u32,
    weight: f32,
}

// The hit groups marched ahead of shading (subcone_CTSS_BATCH of them).
// Held in a struct, not a bare local array: naga writes a local array's
// zero value in HLSL as `(T[N])0`, which glslang's HLSL front end cannot
// parse, and a struct's as `(S)0`, which every HLSL compiler reads.
struct subcone_PendingHits {
    at: array<subcone_GroupHit, subcone_CTSS_BATCH>,
}

// subcone_kernels::ctss::normal_step — a quarter of the cone radius, never
// below 1e-5 of the depth (or of 1); NaN or negative inputs give 1e-5.
fn subcone_normal_step(t: f32, tan_theta: f32) -> f32 {
    var floor_h = 1e-5;
    if t > 1.0 {
        floor_h = 1e-5 * t;
    }
    let h = 0.25 * t * tan_theta;
    if h > floor_h {
        return h;
    }
    return floor_h;
}

// subcone_kernels::ctss::coarse_normal_step — four times normal_step: the
// cone radius.
fn subcone_coarse_normal_step(t: f32, params: subcone_CtssParams) -> f32 {
    return 4.0 * subcone_normal_step(t, params.tan_theta);
}

// subcone_kernels::ctss::tetra_normal of the host's distance (subcone_field's
// x): tetrahedral differences of step h (4 evaluations, Quilez), zero when
// they are zero or not finite. ConeField::normal's default.
fn subcone_tetra_normal(p: vec3<f32>, h: f32) -> vec3<f32> {
    let k0 = vec3<f32>(1.0, -1.0, -1.0);
    let k1 = vec3<f32>(-1.0, -1.0, 1.0);
    let k2 = vec3<f32>(-1.0, 1.0, -1.0);
    let k3 = vec3<f32>(1.0, 1.0, 1.0);
    var n = vec3<f32>(0.0);
    n = n + k0 * subcone_field(p + k0 * h).x;
    n = n + k1 * subcone_field(p + k1 * h).x;
    n = n + k2 * subcone_field(p + k2 * h).x;
    n = n + k3 * subcone_field(p + k3 * h).x;
    return subcone_normalize_or_zero(n);
}

// group_mask's normal_at: the shading normal at the group's sample depth,
// otherwise the host's normal at depth t.
fn subcone_group_normal_at(ray: subcone_SplitRay, sample: subcone_GroupSample, normal: vec3<f32>, t: f32, tan_theta: f32) -> vec3<f32> {
    if t == sample.t {
        return normal;
    }
    return subcone_normal(ray.origin + t * ray.dir, subcone_normal_step(t, tan_theta));
}

// subcone_kernels::ctss::sheet_across (private) — whether the thin surface
// the ray crosses near depth t, with front-face normal n, is a sheet over the
// cone's footprint on it: the field within SHEET_PROBE cone radii of a
// surface at four points of its plane around the crossing (a cone radius
// across the tilt, R_c/max(|n·dir|, 1/4) along it). NaN says no.
fn subcone_sheet_across(ray: subcone_SplitRay, t: f32, tan_theta: f32, n0: vec3<f32>) -> bool {
    let rc = subcone_cone_radius(t, tan_theta);
    let n = subcone_normalize_or_zero(n0);
    if all(n == vec3<f32>(0.0)) || !(rc > 0.0) {
        return false;
    }
    let cosv = abs(dot(n, ray.dir));
    var along = subcone_normalize_or_zero(ray.dir - dot(n, ray.dir) * n);
    if all(along == vec3<f32>(0.0)) {
        along = ray.right;
    }
    let across = subcone_normalize_or_zero(cross(n, along));
    let stretch = rc / select(0.25, cosv, cosv > 0.25);
    let c = ray.origin + t * ray.dir;
    for (var i = 0u; i < 4u; i++) {
        var e: vec3<f32>;
        switch i {
            case 0u: { e = along * stretch; }
            case 1u: { e = -along * stretch; }
            case 2u: { e = across * rc; }
            default: { e = -across * rc; }
        }
        if !(subcone_field_sample(c + e).distance < subcone_SHEET_PROBE * rc) {
            return false;
        }
    }
    return true;
}

// subcone_kernels::ctss::group_mask — the visibility mask of a closed group
// (§3.4–3.5): with FLAG_PAPER the half-plane of the peak occlusion ω and the
// normal where it peaked; otherwise first the thin-shell rule (normals at
// t_first and t_last opposed: full mask for a sheet over the cone's
// footprint, the union of both faces' half-planes for a long oblique shell).
// normal is the shading normal at sample.t.
fn subcone_group_mask(params: subcone_CtssParams, ray: subcone_SplitRay, sample: subcone_GroupSample, normal: vec3<f32>) -> u32 {
    let placement = subcone_ctss_placement(params);
    let omega = sample.occlusion;
    if !subcone_needs_normal(omega, placement) {
        return subcone_visibility_mask(omega, vec2<f32>(0.0), placement);
    }
    let tan = params.tan_theta;
    if !subcone_ctss_is_paper(params) {
        let n1 = subcone_group_normal_at(ray, sample, normal, sample.t_first, tan);
        let n2 = subcone_group_normal_at(ray, sample, normal, sample.t_last, tan);
        if dot(n1, n2) < 0.0 {
            if subcone_sheet_across(ray, sample.t_occlusion, tan, n1) {
                return subcone_FULL_MASK;
            }
            let p1 = subcone_project_normal(n1, ray.right, ray.up);
            let p2 = subcone_project_normal(n2, ray.right, ray.up);
            let long = sample.t_last - sample.t_first
                > subcone_SHELL_LENGTH * subcone_cone_radius(sample.t_first, tan);
            if long && dot(p1, p2) < 0.0 {
                return subcone_visibility_mask(omega, p1, placement)
                    | subcone_visibility_mask(omega, p2, placement);
            }
        }
    }
    let peak = subcone_group_normal_at(ray, sample, normal, sample.t_occlusion, tan);
    return subcone_visibility_mask(omega, subcone_project_normal(peak, ray.right, ray.up), placement);
}

// subcone_kernels::ctss::group_needs_split — §5.3: the fine and coarse
// normals differ by more than 20° (SPLIT_MIN_COS), or the group is longer
// than SPLIT_LENGTH_RATIO cone radii at its depth. Non-finite inputs never
// vote for a split.
fn subcone_group_needs_split(n_fine: vec3<f32>, n_coarse: vec3<f32>, group_length: f32, depth: f32, params: subcone_CtssParams) -> bool {
    let rc = subcone_cone_radius(depth, params.tan_theta);
    let long = subcone_is_finite(rc) && rc > 0.0 && subcone_is_finite(group_length)
        && group_length > subcone_SPLIT_LENGTH_RATIO * rc;
    let a = subcone_normalize_or_zero(n_fine);
    let b = subcone_normalize_or_zero(n_coarse);
    let bent = any(a != vec3<f32>(0.0)) && any(b != vec3<f32>(0.0)) && dot(a, b) < subcone_SPLIT_MIN_COS;
    return long || bent;
}

// subcone_kernels::ctss::split_weights — the group's weight shared between
// the quadrants in proportion to their visible cells; all zero (Rust: None)
// when nothing is visible or the weight is not finite: do not split.
fn subcone_split_weights(visible: u32, weight: f32) -> vec4<f32> {
    let n = countOneBits(visible);
    if n == 0u || !subcone_is_finite(weight) {
        return vec4<f32>(0.0);
    }
    let per_cell = weight / f32(n);
    var w = vec4<f32>(0.0);
    for (var j = 0u; j < 4u; j++) {
        w[j] = f32(countOneBits(visible & subcone_SPLIT_QUADRANTS[j])) * per_cell;
    }
    return w;
}

// subcone_kernels::ctss::SPLIT_OFFSETS[j]
fn subcone_split_offset(j: u32) -> vec2<f32> {
    let a = subcone_SPLIT_OFFSET;
    switch j {
        case 0u: { return vec2<f32>(-a, -a); }
        case 1u: { return vec2<f32>(a, -a); }
        case 2u: { return vec2<f32>(-a, a); }
        default: { return vec2<f32>(a, a); }
    }
}

// subcone_kernels::ctss::split_direction — normalize(dir + tan θ·(x·right +
// y·up)), or dir when that is zero or not finite.
fn subcone_split_direction(dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, tan_theta: f32, offset: vec2<f32>) -> vec3<f32> {
    let d = dir + (tan_theta * offset.x) * right + (tan_theta * offset.y) * up;
    let n = subcone_normalize_or_zero(d);
    if all(n == vec3<f32>(0.0)) {
        return dir;
    }
    return n;
}

// f32::max as Rust has it: a NaN operand yields the other.
fn subcone_max_num(a: f32, b: f32) -> f32 {
    if subcone_is_nan(a) || b > a {
        return b;
    }
    return a;
}

// f32::min as Rust has it: a NaN operand yields the other.
fn subcone_min_num(a: f32, b: f32) -> f32 {
    if subcone_is_nan(a) || b < a {
        return b;
    }
    return a;
}

// subcone_kernels::ctss::split_trace_params — the same cone, depths from the
// group's backtraced entry to two cone radii past its last depth, at most
// SPLIT_MAX_STEPS evaluations.
fn subcone_split_trace_params(params: subcone_CtssParams, sample: subcone_GroupSample) -> subcone_CtssParams {
    let last = subcone_max_num(subcone_max_num(sample.t_exit, sample.t_occlusion), sample.t);
    let hi = last + 2.0 * subcone_cone_radius(last, params.tan_theta);
    var p = params;
    p.t_min = sample.t_entry;
    p.t_max = subcone_min_num(hi, params.t_max);
    p.max_steps = subcone_SPLIT_MAX_STEPS;
    return p;
}

// subcone_kernels::ctss::sphere_trace_split over the host's subcone_field
// (distance, step) instead of ctss_field: the sub-traces of split_group.
fn subcone_sphere_trace_field(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>) -> subcone_SphereHit {
    var t = 0.0;
    if params.t_min > 0.0 {
        t = params.t_min;
    }
    var steps = 0u;
    // One evaluation per iteration: the loop ends within max_steps.
    for (var i = 0u; i < params.max_steps; i++) {
        if !(t < params.t_max) {
            return subcone_SphereHit(-1.0, steps, subcone_STOP_MAX_DISTANCE);
        }
        let f = subcone_field_sample(origin + t * dir);
        steps += 1u;
        let t_hit = t;
        let stop = subcone_sphere_trace_step(params, &t, f.distance, f.step);
        if stop != subcone_STOP_NONE {
            return subcone_SphereHit(select(-1.0, t_hit, stop == subcone_STOP_HARD_HIT), steps, stop);
        }
    }
    return subcone_SphereHit(-1.0, steps, subcone_STOP_STEP_BUDGET);
}

// subcone_kernels::ctss::SplitPart: t < 0 when the sub-ray found no surface
// (Rust: None); weight 0: not traced.
struct subcone_SplitPart {
    weight: f32,
    dir: vec3<f32>,
    t: f32,
}

// subcone_kernels::ctss::SplitGroup; split = 0 when split_weights declined
// (Rust: None).
struct subcone_SplitGroup {
    parts: array<subcone_SplitPart, 4>,
    steps: u32,
    split: u32,
}

// subcone_kernels::ctss::split_group — §5.3: for every quadrant with visible
// cells, sphere-trace the sub-ray through its mean cell centre over the
// group's depths with subcone_field.
fn subcone_split_group(params: subcone_CtssParams, sample: subcone_GroupSample, ray: subcone_SplitRay, visible: u32, weight: f32) -> subcone_SplitGroup {
    var g: subcone_SplitGroup;
    for (var j = 0u; j < 4u; j++) {
        g.parts[j] = subcone_SplitPart(0.0, ray.dir, -1.0);
    }
    g.steps = 0u;
    g.split = 0u;
    let weights = subcone_split_weights(visible, weight);
    if countOneBits(visible) == 0u || !subcone_is_finite(weight) {
        return g;
    }
    g.split = 1u;
    let sub = subcone_split_trace_params(params, sample);
    for (var j = 0u; j < 4u; j++) {
        if !(weights[j] > 0.0) {
            continue;
        }
        let dir = subcone_split_direction(ray.dir, ray.right, ray.up, params.tan_theta, subcone_split_offset(j));
        let hit = subcone_sphere_trace_field(sub, ray.origin, dir);
        g.steps = subcone_saturating_add(g.steps, hit.steps);
        g.parts[j] = subcone_SplitPart(weights[j], dir, hit.t);
    }
    return g;
}

// subcone_kernels::ctss::trace_field's handling of one hit (the closure it
// hands to march, with shade_split inlined): with FLAG_SPLIT_GROUPS the
// group's coarse normal is taken (4 evaluations, counted) and a group that
// group_needs_split is shaded at its split_group parts, each with its own
// normal and shading (a part whose sub-ray found nothing takes the group's own
// colour, shaded once); otherwise the group is shaded once. Adds to agg in
// the order Rust does; returns the extra (evaluations, shaded samples).
fn subcone_ctss_shade_hit(params: subcone_CtssParams, ray: subcone_SplitRay, hit: subcone_GroupHit, agg: ptr<function, subcone_Aggregate>) -> vec2<u32> {
    if subcone_ctss_splits_groups(params) {
        let s = hit.sample;
        let coarse = subcone_normal(hit.point, subcone_coarse_normal_step(s.t, params));
        if subcone_group_needs_split(hit.normal, coarse, s.t_exit - s.t_entry, s.t, params) {
            let g = subcone_split_group(params, s, ray, hit.visible, hit.weight);
            if g.split != 0u {
                var group_color = vec3<f32>(0.0);
                var have_group_color = false;
                var shaded = 0u;
                for (var j = 0u; j < 4u; j++) {
                    let part = g.parts[j];
                    if !(part.weight > 0.0) {
                        continue;
                    }
                    var c: vec3<f32>;
                    if part.t >= 0.0 {
                        let x = ray.origin + part.t * part.dir;
                        let n = subcone_normal(x, subcone_normal_step(part.t, params.tan_theta));
                        c = subcone_shade(x, n, part.dir);
                    } else {
                        if !have_group_color {
                            group_color = subcone_shade(hit.point, hit.normal, ray.dir);
                            have_group_color = true;
                        }
                        c = group_color;
                    }
                    subcone_aggregate_add(agg, part.weight, c);
                    shaded += 1u;
                }
                return vec2<u32>(subcone_saturating_add(g.steps, 4u), max(shaded, 1u) - 1u);
            }
        }
        subcone_aggregate_add(agg, hit.weight, subcone_shade(hit.point, hit.normal, ray.dir));
        return vec2<u32>(4u, 0u);
    }
    subcone_aggregate_add(agg, hit.weight, subcone_shade(hit.point, hit.normal, ray.dir));
    return vec2<u32>(0u, 0u);
}

// subcone_kernels::ctss::trace_field (with march and shade_split) — one
// pixel's cone through the host's field (Algorithm 1): each group, as the
// stepper closes it (advance_object), gets its shading normal
// (normal_step), its mask (group_mask) and its eq. 6 weight (record_mask);
// groups wait in a batch of subcone_CTSS_BATCH and are shaded in order
// (subcone_ctss_shade_hit), so eq. 6 sums the terms of the CPU's ASAP trace in
// its order. right and up span the cone's cross-section
// (subcone_cross_section_frame). samples and steps include the extra shaded
// parts and evaluations of ctss+edges.
fn subcone_ctss_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {
    let ray = subcone_SplitRay(origin, dir, right, up);
    var st = subcone_cone_stepper_new(params);
    var agg = subcone_aggregate_new();
    var extra_steps = 0u;
    var extra_samples = 0u;
    // +inf until a group adds to eq. 6 (a flag, not a comparison with +inf,
    // which a compiler assuming finite values may fold).
    var depth = subcone_inf();
    var have_depth = false;
    // advance_object evaluates at most max_steps times and stops within a
    // few more calls: the bounds never cut a trace short.
    let budget = min(params.max_steps, 0x7fffffffu) + 4u;
    var pending: subcone_PendingHits;
    var done = false;
    for (var round_i = 0u; round_i < budget && !done; round_i++) {
        var k = 0u;
        for (var i = 0u; i < budget; i++) {
            let f = subcone_field_sample(origin + st.t * dir);
            let ev = subcone_cone_stepper_advance_object(&st, f.distance, f.step, f.object);
            if ev.kind == subcone_EVENT_STOP {
                done = true;
                break;
            }
            if ev.kind == subcone_EVENT_SAMPLE {
                let s = ev.sample;
                let point = origin + s.t * dir;
                let normal = subcone_normal(point, subcone_normal_step(s.t, params.tan_theta));
                // CTSS-R's last group takes the rest of the pixel: no mask
                // to make (close_group).
                var mask = 0xffffffffu;
                if !subcone_cone_stepper_takes_rest_of_pixel(&st) {
                    mask = subcone_group_mask(params, ray, s, normal);
                }
                let rec = subcone_cone_stepper_record_mask(&st, mask);
                pending.at[k] = subcone_GroupHit(s, point, normal, rec.x, bitcast<f32>(rec.y));
                k += 1u;
                if k >= subcone_CTSS_BATCH {
                    break;
                }
            }
        }
        for (var j = 0u; j < k; j++) {
            if !have_depth && pending.at[j].weight > 0.0 {
                depth = pending.at[j].sample.t;
                have_depth = true;
            }
            let extra = subcone_ctss_shade_hit(params, ray, pending.at[j], &agg);
            extra_steps = subcone_saturating_add(extra_steps, extra.x);
            extra_samples = subcone_saturating_add(extra_samples, extra.y);
        }
    }
    var stop = st.stop;
    if stop == subcone_STOP_NONE {
        stop = subcone_STOP_STEP_BUDGET;
    }
    return subcone_CtssTraceResult(
        subcone_aggregate_resolve(agg, background, subcone_cone_stepper_background_weight(st)),
        subcone_saturating_add(st.samples, extra_samples),
        subcone_saturating_add(st.steps, extra_steps),
        st.covered,
        stop,
        depth,
    );
}
const subcone_CTSS_BATCH: u32 = 8u;
fn ctss_field(p: vec3<f32>) -> vec2<f32> { let f = subcone_field(p); return f.xy; }
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let sphere = length(p - vec3<f32>(0.0, 0.0, 4.0)) - 1.0;
    let ground = p.y + 1.0;
    if sphere < ground {
        return vec3<f32>(sphere, sphere, 0.0);
    }
    return vec3<f32>(ground, ground, 1.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let light = vec3<f32>(0.48, 0.8, -0.36);
    var albedo = vec3<f32>(0.9, 0.3, 0.2);
    if p.y < -0.999 {
        albedo = vec3<f32>(0.7, 0.7, 0.7);
    }
    return albedo * (0.15 + max(dot(n, light), 0.0));
}

fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> { return subcone_tetra_normal(p, h); }
const subcone_pass_SIDE: u32 = 1u;
fn subcone_pass_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {
    return subcone_ctss_trace(params, origin, dir, right, up, background);
}
fn subcone_pass_color(color: vec3<f32>, alpha: f32) -> vec4<f32> {
    return vec4<f32>(color, 1.0);
}
fn subcone_pass_store(p: vec2<u32>, c: vec4<f32>, depth: f32, steps: u32, samples: u32) {
    textureStore(subcone_pass_output, vec2<i32>(p), c);
}
// CtssPass (ctss.rs): cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10,
// §5.3) of the host's signed distance field, N × N cones per pixel, through
// the kernels' trace subcone_ctss_trace (subcone_kernels::ctss::TRACE_WGSL),
// the twin of subcone_kernels::ctss::trace_field, or the host's own
// subcone_trace (CtssTrace::Host).
//
// Follows the kernels (PARAMS, with subcone_PinholeCamera and
// subcone_pinhole_dir; cone, mask, aggregate, ctss, ctss/trace), the host's
// WGSL (subcone_field, subcone_shade, optionally subcone_normal; and
// subcone_CTSS_BATCH, which ctss.rs declares), the desc's variant
// (subcone_pass_SIDE, subcone_pass_trace, subcone_pass_color,
// subcone_pass_store, which ctss.rs writes) and the declarations ctss.rs
// generates: subcone_pass_frame (CtssUniform), subcone_pass_params
// (subcone_CtssParams), subcone_pass_output (a storage texture or buffer)
// and, with counts, subcone_pass_counts; with depth, subcone_pass_depth.

// ctss.rs `CtssUniform` (192 bytes): the camera (CtssView: the pinhole of
// CtssCamera::ray, or the eye and frame of a CtssProjection; its width and
// height are the rectangle's), the background, how rays are made
// (projection: 0 pinhole, 1 perspective, 2 orthographic), the projection's
// NDC-to-world matrix, the forward axis and offset of view depth, the
// rectangle's origin in the output and the output's row length.
struct CtssUniform {
    camera: subcone_PinholeCamera,
    background: vec3<f32>,
    projection: u32,
    inverse_view_projection: mat4x4<f32>,
    forward: vec3<f32>,
    depth_offset: f32,
    origin: vec2<u32>,
    row_length: u32,
    _pad: u32,
}

// A pixel's index in the row-major buffers.
fn subcone_pass_index(p: vec2<u32>) -> u32 {
    return p.y * subcone_pass_frame.row_length + p.x;
}

// The world point of NDC (xy, z) through the projection.
fn subcone_pass_unproject(f: CtssUniform, xy: vec2<f32>, z: f32) -> vec3<f32> {
    let h = f.inverse_view_projection * vec4<f32>(xy, z, 1.0);
    return h.xyz / h.w;
}

// The ray (origin, unit direction) of image point p of the rectangle
// (pixels, y down): the pinhole's (subcone_pinhole_dir from the eye), or,
// for a CtssProjection, from the eye through the unprojected point at NDC
// depth 1/2 (perspective), or parallel through the points at NDC depths
// 1/4 and 3/4 from the plane of view depth 0 (orthographic).
fn subcone_pass_ray(f: CtssUniform, p: vec2<f32>) -> array<vec3<f32>, 2> {
    if f.projection == 0u {
        return array<vec3<f32>, 2>(f.camera.position, subcone_pinhole_dir(f.camera, p));
    }
    let w = f32(max(f.camera.width, 1u));
    let h = f32(max(f.camera.height, 1u));
    let ndc = vec2<f32>(2.0 * p.x / w - 1.0, 1.0 - 2.0 * p.y / h);
    if f.projection == 1u {
        let q = subcone_pass_unproject(f, ndc, 0.5);
        return array<vec3<f32>, 2>(f.camera.position, normalize(q - f.camera.position));
    }
    let a = subcone_pass_unproject(f, ndc, 0.25);
    var d = normalize(subcone_pass_unproject(f, ndc, 0.75) - a);
    if dot(d, f.forward) < 0.0 {
        d = -d;
    }
    let o = a - d * ((dot(a, f.forward) + f.depth_offset) / dot(d, f.forward));
    return array<vec3<f32>, 2>(o, d);
}

// One pixel of the rectangle: the mean of its subcone_pass_SIDE² cones
// through the sub-pixel centres (SSAA over CTSS; one cone through the
// centre when the side is 1), each about the ray of subcone_pass_ray with
// the cross-section axes of subcone_cross_section_frame; its coverage alpha
// (the mean of subcone_ctss_coverage_alpha) and view depth (the least over
// its cones of the nearest contributing group's, +inf for none), written at
// the rectangle's origin + gid.
@compute @workgroup_size(8, 8)
fn subcone_pass_ctss_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let f = subcone_pass_frame;
    if gid.x >= f.camera.width || gid.y >= f.camera.height {
        return;
    }
    let side = subcone_pass_SIDE;
    var steps = 0u;
    var samples = 0u;
    var sum = vec3<f32>(0.0);
    var alpha = 0.0;
    var depth = subcone_inf();
    var have_depth = false;
    for (var sy = 0u; sy < side; sy++) {
        for (var sx = 0u; sx < side; sx++) {
            let off = vec2<f32>((f32(sx) + 0.5) / f32(side), (f32(sy) + 0.5) / f32(side));
            let ray = subcone_pass_ray(f, vec2<f32>(f32(gid.x), f32(gid.y)) + off);
            let d = ray[1];
            let axes = subcone_cross_section_frame(d, f.camera.up);
            let r = subcone_pass_trace(subcone_pass_params, ray[0], d, axes[0], axes[1], f.background);
            sum += r.color;
            steps += r.steps;
            samples += r.samples;
            alpha += subcone_ctss_coverage_alpha(r.coverage, r.stop);
            if subcone_is_finite(r.depth) {
                let z = r.depth * dot(d, f.forward) + (dot(ray[0], f.forward) + f.depth_offset);
                if !have_depth || z < depth {
                    depth = z;
                    have_depth = true;
                }
            }
        }
    }
    let n = f32(side * side);
    subcone_pass_store(f.origin + gid.xy, subcone_pass_color(sum / n, alpha / n), depth, steps, samples);
}
@group(0) @binding(0) var<uniform> subcone_pass_frame: CtssUniform;
@group(0) @binding(1) var<uniform> subcone_pass_params: subcone_CtssParams;
@group(0) @binding(2) var subcone_pass_output: texture_storage_2d<rgba16float, write>;
