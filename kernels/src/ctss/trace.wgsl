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
