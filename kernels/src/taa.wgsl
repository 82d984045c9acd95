// Temporal antialiasing (Karis 2014, Salvi 2016's variance clipping): the WGSL
// mirror of subcone_kernels::taa (kernels/src/taa.rs), same names with a
// subcone_ prefix, same statement order.
//
// Needs params.wgsl (subcone_TaaParams, subcone_is_finite). The including shader
// defines the two fetches, the twins of resolve_pixel's closures:
//     fn taa_current(x: i32, y: i32) -> vec3<f32>   this frame's colour
//     fn taa_history(x: i32, y: i32) -> vec3<f32>   the previous output
// called only with coordinates inside the image.

const subcone_TAA_LUMA: vec3<f32> = vec3<f32>(0.2126, 0.7152, 0.0722);

// taa::halton
fn subcone_taa_halton(index_in: u32, base: u32) -> f32 {
    if base < 2u {
        return 0.0;
    }
    var index = index_in;
    let inv = 1.0 / f32(base);
    var f = 1.0;
    var r = 0.0;
    while index > 0u {
        f *= inv;
        r += f * f32(index % base);
        index /= base;
    }
    return r;
}

// taa::jitter
fn subcone_taa_jitter(frame: u32, phases: u32) -> vec2<f32> {
    let i = frame % max(phases, 1u) + 1u;
    return vec2<f32>(subcone_taa_halton(i, 2u), subcone_taa_halton(i, 3u)) - vec2<f32>(0.5);
}

// TaaParams::exposure
fn subcone_taa_exposure(p: subcone_TaaParams) -> f32 {
    if p.exposure > 0.0 && subcone_is_finite(p.exposure) {
        return p.exposure;
    }
    return 1.0;
}

// TaaParams::current_weight
fn subcone_taa_current_weight(p: subcone_TaaParams) -> f32 {
    var lo = 1.0;
    if p.min_current_weight > 0.0 {
        lo = min(p.min_current_weight, 1.0);
    } else if !subcone_is_nan(p.min_current_weight) {
        lo = 1.17549435e-38;
    }
    let mean = 1.0 / (f32(p.history_frames) + 1.0);
    return max(mean, lo);
}

fn subcone_taa_scale1(s: f32) -> f32 {
    if s != 0.0 && subcone_is_finite(s) {
        return s;
    }
    return 1.0;
}

// TaaParams::motion_scale
fn subcone_taa_motion_scale(p: subcone_TaaParams) -> vec2<f32> {
    return vec2<f32>(subcone_taa_scale1(p.motion_scale.x), subcone_taa_scale1(p.motion_scale.y));
}

fn subcone_taa_sanitize1(x: f32) -> f32 {
    if x > 0.0 && subcone_is_finite(x) {
        return x;
    }
    return 0.0;
}

// taa::sanitize
fn subcone_taa_sanitize(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(subcone_taa_sanitize1(c.x), subcone_taa_sanitize1(c.y), subcone_taa_sanitize1(c.z));
}

// taa::tonemap
fn subcone_taa_tonemap(c_in: vec3<f32>, exposure: f32) -> vec3<f32> {
    let c = c_in * exposure;
    return c / (1.0 + dot(c, subcone_TAA_LUMA));
}

// taa::tonemap_inverse
fn subcone_taa_tonemap_inverse(t: vec3<f32>, exposure: f32) -> vec3<f32> {
    let d = max(1.0 - dot(t, subcone_TAA_LUMA), 1.0 / 65536.0);
    return t / d / exposure;
}

// taa::to_resolve_space
fn subcone_taa_to_resolve_space(c: vec3<f32>, p: subcone_TaaParams) -> vec3<f32> {
    if p.tone_mapped == 1u {
        return subcone_taa_tonemap(c, subcone_taa_exposure(p));
    }
    return c;
}

// taa::from_resolve_space
fn subcone_taa_from_resolve_space(t: vec3<f32>, p: subcone_TaaParams) -> vec3<f32> {
    if p.tone_mapped == 1u {
        return subcone_taa_tonemap_inverse(t, subcone_taa_exposure(p));
    }
    return t;
}

// taa::rgb_to_ycocg
fn subcone_taa_rgb_to_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        0.25 * c.x + 0.5 * c.y + 0.25 * c.z,
        0.5 * c.x - 0.5 * c.z,
        -0.25 * c.x + 0.5 * c.y - 0.25 * c.z,
    );
}

// taa::ycocg_to_rgb
fn subcone_taa_ycocg_to_rgb(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

fn subcone_taa_clip_axis(v: f32, e: f32) -> f32 {
    if e > 0.0 {
        return abs(v / e);
    }
    if v == 0.0 {
        return 0.0;
    }
    return subcone_inf();
}

// taa::clip_towards
fn subcone_taa_clip_towards(h: vec3<f32>, centre: vec3<f32>, extent: vec3<f32>) -> vec3<f32> {
    let v = h - centre;
    let m = max(max(subcone_taa_clip_axis(v.x, extent.x), subcone_taa_clip_axis(v.y, extent.y)),
        subcone_taa_clip_axis(v.z, extent.z));
    if m > 1.0 {
        return centre + v / m;
    }
    return h;
}

// taa::catmull_rom_weights
fn subcone_taa_catmull_rom_weights(t: f32) -> vec4<f32> {
    let t2 = t * t;
    let t3 = t2 * t;
    return vec4<f32>(
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    );
}

// taa::sample_history: .w is 1 with a history, 0 without.
fn subcone_taa_sample_history(p: vec2<f32>, w_in: u32, h_in: u32) -> vec4<f32> {
    let w = i32(max(w_in, 1u));
    let h = i32(max(h_in, 1u));
    if !(p.x >= 0.0 && p.y >= 0.0 && p.x <= f32(w) && p.y <= f32(h)) {
        return vec4<f32>(0.0);
    }
    let q = p - vec2<f32>(0.5);
    let fx = floor(q.x);
    let fy = floor(q.y);
    let wx = subcone_taa_catmull_rom_weights(q.x - fx);
    let wy = subcone_taa_catmull_rom_weights(q.y - fy);
    let x0 = i32(fx) - 1;
    let y0 = i32(fy) - 1;
    var sum = vec3<f32>(0.0);
    for (var j = 0; j < 4; j++) {
        let y = clamp(y0 + j, 0, h - 1);
        var row = vec3<f32>(0.0);
        for (var i = 0; i < 4; i++) {
            let x = clamp(x0 + i, 0, w - 1);
            row += wx[i] * subcone_taa_sanitize(taa_history(x, y));
        }
        sum += wy[j] * row;
    }
    return vec4<f32>(subcone_taa_sanitize(sum), 1.0);
}

// taa::resolve_pixel
fn subcone_taa_resolve_pixel(xy: vec2<i32>, velocity: vec2<f32>, params: subcone_TaaParams) -> vec3<f32> {
    let w = i32(max(params.width, 1u));
    let h = i32(max(params.height, 1u));
    let x = clamp(xy.x, 0, w - 1);
    let y = clamp(xy.y, 0, h - 1);
    let centre = subcone_taa_sanitize(taa_current(x, y));
    if params.history_frames == 0u {
        return centre;
    }
    let p = vec2<f32>(f32(x) + 0.5, f32(y) + 0.5) - velocity * subcone_taa_motion_scale(params);
    let past_s = subcone_taa_sample_history(p, u32(w), u32(h));
    if past_s.w == 0.0 {
        return centre;
    }
    var m1 = vec3<f32>(0.0);
    var m2 = vec3<f32>(0.0);
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            var c = centre;
            if dx != 0 || dy != 0 {
                c = subcone_taa_sanitize(taa_current(clamp(x + dx, 0, w - 1), clamp(y + dy, 0, h - 1)));
            }
            let t = subcone_taa_rgb_to_ycocg(subcone_taa_to_resolve_space(c, params));
            m1 += t;
            m2 += t * t;
        }
    }
    let mean = m1 / 9.0;
    let var_ = max(m2 / 9.0 - mean * mean, vec3<f32>(0.0));
    let sigma = sqrt(var_);
    var gamma = 0.0;
    if params.clip_gamma > 0.0 {
        gamma = min(params.clip_gamma, 1e6);
    }
    let now = subcone_taa_rgb_to_ycocg(subcone_taa_to_resolve_space(centre, params));
    let lo = min(mean - gamma * sigma, now);
    let hi = max(mean + gamma * sigma, now);
    let past = subcone_taa_rgb_to_ycocg(subcone_taa_to_resolve_space(past_s.xyz, params));
    let clipped = subcone_taa_clip_towards(past, 0.5 * (lo + hi), 0.5 * (hi - lo));
    let a = subcone_taa_current_weight(params);
    let out = clipped + (now - clipped) * a;
    return subcone_taa_sanitize(subcone_taa_from_resolve_space(subcone_taa_ycocg_to_rgb(out), params));
}
