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
