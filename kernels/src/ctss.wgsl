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
// where the occlusion rises by GROUP_DIP after a dip as deep. One long
// function on purpose: it is the stepper of Algorithm 1 as the Rust twin
// writes it, branch for branch, so the conformance suite's agreement can be
// checked by reading.
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
