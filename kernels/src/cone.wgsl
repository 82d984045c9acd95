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
