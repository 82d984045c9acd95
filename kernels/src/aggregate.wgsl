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
