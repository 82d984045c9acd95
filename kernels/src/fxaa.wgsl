// FXAA 3.11 quality, preset 12: the WGSL mirror of subcone_kernels::fxaa
// (kernels/src/fxaa.rs), same names, same statement order.
//
// Needs params.wgsl (subcone_FxaaParams). The including shader defines the pixel
// fetch, the twin of subcone_fxaa_pixel's `fetch` closure:
//     fn fxaa_fetch(x: i32, y: i32) -> vec4<f32>
// returning the input pixel (x, y) as subcone_fxaa_encode makes it, with coordinates
// outside the image clamped to its edge.
//
// NaN tests are done on the bits: shader compilers may fold `x != x` away.

// Mirrors fxaa::SEARCH_STEPS (FXAA_QUALITY__P0..P4 of preset 12).
// Indices >= 5 read as the last step.
fn subcone_fxaa_search_step(i: u32) -> f32 {
    switch i {
        case 0u: { return 1.0; }
        case 1u: { return 1.5; }
        case 2u: { return 2.0; }
        case 3u: { return 4.0; }
        default: { return 12.0; }
    }
}

// Mirrors fxaa::clean01: [0, 1], NaN as 0.
fn subcone_fxaa_clean01(x: f32) -> f32 {
    if subcone_is_nan(x) {
        return 0.0;
    }
    return clamp(x, 0.0, 1.0);
}

// Mirrors fxaa::linear_to_srgb.
fn subcone_fxaa_linear_to_srgb(x: f32) -> f32 {
    let c = subcone_fxaa_clean01(x);
    if c <= 0.0031308 {
        return 12.92 * c;
    }
    return 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

// Mirrors fxaa::srgb_to_linear.
fn subcone_fxaa_srgb_to_linear(x: f32) -> f32 {
    let c = subcone_fxaa_clean01(x);
    if c <= 0.04045 {
        return c / 12.92;
    }
    return pow((c + 0.055) / 1.055, 2.4);
}

// Mirrors fxaa::quantize8.
fn subcone_quantize8(x: f32) -> f32 {
    return floor(subcone_fxaa_clean01(x) * 255.0 + 0.5) * (1.0 / 255.0);
}

// Mirrors fxaa::fxaa_encode: the RGBA8 texel of the displayed colour and
// its luma, each rounded to 8 bits.
fn subcone_fxaa_encode(linear: vec3<f32>) -> vec4<f32> {
    let c = vec3<f32>(
        subcone_quantize8(subcone_fxaa_linear_to_srgb(linear.x)),
        subcone_quantize8(subcone_fxaa_linear_to_srgb(linear.y)),
        subcone_quantize8(subcone_fxaa_linear_to_srgb(linear.z)),
    );
    let luma = c.x * 0.299 + c.y * 0.587 + c.z * 0.114;
    return vec4<f32>(c, subcone_quantize8(luma));
}

// Mirrors fxaa::fxaa_decode.
fn subcone_fxaa_decode(srgb: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        subcone_fxaa_srgb_to_linear(srgb.x),
        subcone_fxaa_srgb_to_linear(srgb.y),
        subcone_fxaa_srgb_to_linear(srgb.z),
    );
}

// Mirrors fxaa::tap.
fn subcone_fxaa_tap(x: i32, y: i32) -> vec4<f32> {
    let v = fxaa_fetch(x, y);
    return vec4<f32>(subcone_fxaa_clean01(v.x), subcone_fxaa_clean01(v.y), subcone_fxaa_clean01(v.z), subcone_fxaa_clean01(v.w));
}

// Mirrors fxaa::bilinear.
fn subcone_fxaa_bilinear(px: f32, py: f32) -> vec4<f32> {
    let fx0 = floor(px);
    let fy0 = floor(py);
    let fx = px - fx0;
    let fy = py - fy0;
    let x0 = i32(fx0);
    let y0 = i32(fy0);
    let top = subcone_fxaa_tap(x0, y0) * (1.0 - fx) + subcone_fxaa_tap(x0 + 1, y0) * fx;
    let bottom = subcone_fxaa_tap(x0, y0 + 1) * (1.0 - fx) + subcone_fxaa_tap(x0 + 1, y0 + 1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}

// Mirrors fxaa::fxaa_pixel (see its doc comment for the domain). One long
// function on purpose: it follows FXAA 3.11's quality path and the Rust twin
// statement for statement, so the two can be read side by side.
fn subcone_fxaa_pixel(x: i32, y: i32, p: subcone_FxaaParams) -> vec3<f32> {
    let pos_m_x = f32(x);
    let pos_m_y = f32(y);
    let rgby_m = subcone_fxaa_tap(x, y);
    let luma_m = rgby_m.w;
    let luma_s = subcone_fxaa_tap(x, y + 1).w;
    let luma_e = subcone_fxaa_tap(x + 1, y).w;
    let luma_n = subcone_fxaa_tap(x, y - 1).w;
    let luma_w = subcone_fxaa_tap(x - 1, y).w;

    let max_sm = max(luma_s, luma_m);
    let min_sm = min(luma_s, luma_m);
    let max_esm = max(luma_e, max_sm);
    let min_esm = min(luma_e, min_sm);
    let max_wn = max(luma_n, luma_w);
    let min_wn = min(luma_n, luma_w);
    let range_max = max(max_wn, max_esm);
    let range_min = min(min_wn, min_esm);
    let range_max_scaled = range_max * p.edge_threshold;
    let range = range_max - range_min;
    let range_max_clamped = max(p.edge_threshold_min, range_max_scaled);
    if !(range >= range_max_clamped) || !(range > 0.0) {
        return rgby_m.xyz;
    }

    let luma_nw = subcone_fxaa_tap(x - 1, y - 1).w;
    let luma_se = subcone_fxaa_tap(x + 1, y + 1).w;
    let luma_ne = subcone_fxaa_tap(x + 1, y - 1).w;
    let luma_sw = subcone_fxaa_tap(x - 1, y + 1).w;

    let luma_ns = luma_n + luma_s;
    let luma_we = luma_w + luma_e;
    let subpix_rcp_range = 1.0 / range;
    let subpix_nswe = luma_ns + luma_we;
    let edge_horz1 = -2.0 * luma_m + luma_ns;
    let edge_vert1 = -2.0 * luma_m + luma_we;

    let luma_nese = luma_ne + luma_se;
    let luma_nwne = luma_nw + luma_ne;
    let edge_horz2 = -2.0 * luma_e + luma_nese;
    let edge_vert2 = -2.0 * luma_n + luma_nwne;

    let luma_nwsw = luma_nw + luma_sw;
    let luma_swse = luma_sw + luma_se;
    let edge_horz4 = abs(edge_horz1) * 2.0 + abs(edge_horz2);
    let edge_vert4 = abs(edge_vert1) * 2.0 + abs(edge_vert2);
    let edge_horz3 = -2.0 * luma_w + luma_nwsw;
    let edge_vert3 = -2.0 * luma_s + luma_swse;
    let edge_horz = abs(edge_horz3) + edge_horz4;
    let edge_vert = abs(edge_vert3) + edge_vert4;

    let subpix_nwswnese = luma_nwsw + luma_nese;
    var length_sign = 1.0;
    let horz_span = edge_horz >= edge_vert;
    let subpix_a = subpix_nswe * 2.0 + subpix_nwswnese;

    // The original overwrites lumaN and lumaS here; new names keep every
    // value single-assignment.
    let luma_n_span = select(luma_w, luma_n, horz_span);
    let luma_s_span = select(luma_e, luma_s, horz_span);
    let subpix_b = subpix_a * (1.0 / 12.0) - luma_m;

    let gradient_n = luma_n_span - luma_m;
    let gradient_s = luma_s_span - luma_m;
    var luma_nn = luma_n_span + luma_m;
    let luma_ss = luma_s_span + luma_m;
    let pair_n = abs(gradient_n) >= abs(gradient_s);
    let gradient = max(abs(gradient_n), abs(gradient_s));
    if pair_n {
        length_sign = -length_sign;
    }
    let subpix_c = subcone_fxaa_clean01(abs(subpix_b) * subpix_rcp_range);

    var off_x = 0.0;
    var off_y = 1.0;
    if horz_span {
        off_x = 1.0;
        off_y = 0.0;
    }
    var pos_b_x = pos_m_x;
    var pos_b_y = pos_m_y;
    if !horz_span {
        pos_b_x += length_sign * 0.5;
    } else {
        pos_b_y += length_sign * 0.5;
    }

    var pos_n_x = pos_b_x - off_x * subcone_fxaa_search_step(0u);
    var pos_n_y = pos_b_y - off_y * subcone_fxaa_search_step(0u);
    var pos_p_x = pos_b_x + off_x * subcone_fxaa_search_step(0u);
    var pos_p_y = pos_b_y + off_y * subcone_fxaa_search_step(0u);
    let subpix_d = -2.0 * subpix_c + 3.0;
    var luma_end_n = subcone_fxaa_bilinear(pos_n_x, pos_n_y).w;
    let subpix_e = subpix_c * subpix_c;
    var luma_end_p = subcone_fxaa_bilinear(pos_p_x, pos_p_y).w;

    if !pair_n {
        luma_nn = luma_ss;
    }
    let gradient_scaled = gradient * 1.0 / 4.0;
    let luma_mm = luma_m - luma_nn * 0.5;
    let subpix_f = subpix_d * subpix_e;
    let luma_m_lt_zero = luma_mm < 0.0;

    luma_end_n -= luma_nn * 0.5;
    luma_end_p -= luma_nn * 0.5;
    var done_n = abs(luma_end_n) >= gradient_scaled;
    var done_p = abs(luma_end_p) >= gradient_scaled;
    if !done_n {
        pos_n_x -= off_x * subcone_fxaa_search_step(1u);
        pos_n_y -= off_y * subcone_fxaa_search_step(1u);
    }
    if !done_p {
        pos_p_x += off_x * subcone_fxaa_search_step(1u);
        pos_p_y += off_y * subcone_fxaa_search_step(1u);
    }
    // Bounded by the preset's step count (P2..P4).
    for (var i = 2u; i < 5u; i++) {
        if done_n && done_p {
            break;
        }
        let step = subcone_fxaa_search_step(i);
        if !done_n {
            luma_end_n = subcone_fxaa_bilinear(pos_n_x, pos_n_y).w - luma_nn * 0.5;
        }
        if !done_p {
            luma_end_p = subcone_fxaa_bilinear(pos_p_x, pos_p_y).w - luma_nn * 0.5;
        }
        done_n = abs(luma_end_n) >= gradient_scaled;
        done_p = abs(luma_end_p) >= gradient_scaled;
        if !done_n {
            pos_n_x -= off_x * step;
            pos_n_y -= off_y * step;
        }
        if !done_p {
            pos_p_x += off_x * step;
            pos_p_y += off_y * step;
        }
    }

    var dst_n = pos_m_y - pos_n_y;
    var dst_p = pos_p_y - pos_m_y;
    if horz_span {
        dst_n = pos_m_x - pos_n_x;
        dst_p = pos_p_x - pos_m_x;
    }
    let good_span_n = (luma_end_n < 0.0) != luma_m_lt_zero;
    let span_length = dst_p + dst_n;
    let good_span_p = (luma_end_p < 0.0) != luma_m_lt_zero;
    let span_length_rcp = 1.0 / span_length;

    let direction_n = dst_n < dst_p;
    let dst = min(dst_n, dst_p);
    let good_span = select(good_span_p, good_span_n, direction_n);
    let subpix_g = subpix_f * subpix_f;
    let pixel_offset = dst * -span_length_rcp + 0.5;
    let subpix_h = subpix_g * p.subpix;

    let pixel_offset_good = select(0.0, pixel_offset, good_span);
    let pixel_offset_subpix = subcone_fxaa_clean01(max(pixel_offset_good, subpix_h));
    var px = pos_m_x;
    var py = pos_m_y;
    if !horz_span {
        px += pixel_offset_subpix * length_sign;
    } else {
        py += pixel_offset_subpix * length_sign;
    }
    return subcone_fxaa_bilinear(px, py).xyz;
}
