#version 310 es

precision highp float;
precision highp int;

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

struct subcone_SraaParams {
    float sigma_z;
    float sigma_n;
    float scale;
    uint packed_;
    float sigma_s;
    uint shading;
    uint _pad0_;
    uint _pad1_;
};
struct subcone_Geometry {
    vec3 normal;
    float depth;
};
struct subcone_CtssParams {
    float tan_theta;
    float alpha;
    float eps;
    float t_min;
    float t_max;
    float min_sample_weight;
    uint max_steps;
    uint max_samples;
    uint visibility_k;
    uint flags;
    uint _pad0_;
    uint _pad1_;
};
struct subcone_PinholeCamera {
    vec3 position;
    uint width;
    vec3 forward;
    uint height;
    vec3 right;
    float tan_half_fov;
    vec3 up;
    uint _pad;
    vec2 jitter;
    uvec2 _pad2_;
};
struct subcone_TaaParams {
    float exposure;
    float min_current_weight;
    float clip_gamma;
    uint history_frames;
    uint width;
    uint height;
    uint tone_mapped;
    uint _pad;
};
struct subcone_FxaaParams {
    float subpix;
    float edge_threshold;
    float edge_threshold_min;
    float _pad;
};
struct FxaaFrame {
    uint width;
    uint height;
    uint _pad0_;
    uint _pad1_;
};
const float subcone_NEGLIGIBLE_WEIGHT = 5.421011e-20;

layout(std140, binding = 1) uniform FxaaFrame_block_0Compute { FxaaFrame _group_0_binding_1_cs; };

layout(binding = 2) uniform highp sampler2D _group_0_binding_2_cs;

layout(std140, binding = 0) uniform subcone_FxaaParams_block_1Compute { subcone_FxaaParams _group_0_binding_0_cs; };

layout(binding = 3,rgba16f) writeonly uniform highp image2D _group_0_binding_3_cs;


float subcone_inf() {
    return uintBitsToFloat(2139095040u);
}

bool subcone_is_nan(float x) {
    return ((floatBitsToUint(x) & 2147483647u) > 2139095040u);
}

bool subcone_is_finite(float x_1) {
    return ((floatBitsToUint(x_1) & 2147483647u) < 2139095040u);
}

vec3 subcone_pinhole_dir(subcone_PinholeCamera c, vec2 p_in) {
    vec2 p_1 = (p_in + c.jitter);
    float w = float(max(c.width, 1u));
    float h = float(max(c.height, 1u));
    float u = (((((2.0 * p_1.x) / w) - 1.0) * c.tan_half_fov) * (w / h));
    float v = ((1.0 - ((2.0 * p_1.y) / h)) * c.tan_half_fov);
    vec3 d = ((c.forward + (u * c.right)) + (v * c.up));
    return (d * (1.0 / length(d)));
}

float subcone_fxaa_search_step(uint i) {
    switch(i) {
        case 0u: {
            return 1.0;
        }
        case 1u: {
            return 1.5;
        }
        case 2u: {
            return 2.0;
        }
        case 3u: {
            return 4.0;
        }
        default: {
            return 12.0;
        }
    }
}

float subcone_fxaa_clean01_(float x_2) {
    bool _e1 = subcone_is_nan(x_2);
    if (_e1) {
        return 0.0;
    }
    return clamp(x_2, 0.0, 1.0);
}

float subcone_fxaa_linear_to_srgb(float x_3) {
    float _e1 = subcone_fxaa_clean01_(x_3);
    if ((_e1 <= 0.0031308)) {
        return (12.92 * _e1);
    }
    return ((1.055 * pow(_e1, 0.41666666)) - 0.055);
}

float subcone_fxaa_srgb_to_linear(float x_4) {
    float _e1 = subcone_fxaa_clean01_(x_4);
    if ((_e1 <= 0.04045)) {
        return (_e1 / 12.92);
    }
    return pow(((_e1 + 0.055) / 1.055), 2.4);
}

float subcone_quantize8_(float x_5) {
    float _e1 = subcone_fxaa_clean01_(x_5);
    return (floor(((_e1 * 255.0) + 0.5)) * 0.003921569);
}

vec4 subcone_fxaa_encode(vec3 linear) {
    float _e2 = subcone_fxaa_linear_to_srgb(linear.x);
    float _e3 = subcone_quantize8_(_e2);
    float _e5 = subcone_fxaa_linear_to_srgb(linear.y);
    float _e6 = subcone_quantize8_(_e5);
    float _e8 = subcone_fxaa_linear_to_srgb(linear.z);
    float _e9 = subcone_quantize8_(_e8);
    vec3 c_1 = vec3(_e3, _e6, _e9);
    float luma = (((c_1.x * 0.299) + (c_1.y * 0.587)) + (c_1.z * 0.114));
    float _e22 = subcone_quantize8_(luma);
    return vec4(c_1, _e22);
}

vec3 subcone_fxaa_decode(vec3 srgb) {
    float _e2 = subcone_fxaa_srgb_to_linear(srgb.x);
    float _e4 = subcone_fxaa_srgb_to_linear(srgb.y);
    float _e6 = subcone_fxaa_srgb_to_linear(srgb.z);
    return vec3(_e2, _e4, _e6);
}

vec4 fxaa_fetch(int x_6, int y) {
    uint _e4 = _group_0_binding_1_cs.width;
    int cx = min(max(x_6, 0), (int(_e4) - 1));
    uint _e12 = _group_0_binding_1_cs.height;
    int cy = min(max(y, 0), (int(_e12) - 1));
    vec4 _e21 = texelFetch(_group_0_binding_2_cs, ivec2(cx, cy), 0);
    vec4 _e23 = subcone_fxaa_encode(_e21.xyz);
    return _e23;
}

vec4 subcone_fxaa_tap(int x_7, int y_1) {
    vec4 _e2 = fxaa_fetch(x_7, y_1);
    float _e4 = subcone_fxaa_clean01_(_e2.x);
    float _e6 = subcone_fxaa_clean01_(_e2.y);
    float _e8 = subcone_fxaa_clean01_(_e2.z);
    float _e10 = subcone_fxaa_clean01_(_e2.w);
    return vec4(_e4, _e6, _e8, _e10);
}

vec4 subcone_fxaa_bilinear(float px, float py) {
    float fx0_ = floor(px);
    float fy0_ = floor(py);
    float fx = (px - fx0_);
    float fy = (py - fy0_);
    int x0_ = int(fx0_);
    int y0_ = int(fy0_);
    vec4 _e8 = subcone_fxaa_tap(x0_, y0_);
    vec4 _e14 = subcone_fxaa_tap((x0_ + 1), y0_);
    vec4 top = ((_e8 * (1.0 - fx)) + (_e14 * fx));
    vec4 _e19 = subcone_fxaa_tap(x0_, (y0_ + 1));
    vec4 _e27 = subcone_fxaa_tap((x0_ + 1), (y0_ + 1));
    vec4 bottom = ((_e19 * (1.0 - fx)) + (_e27 * fx));
    return ((top * (1.0 - fy)) + (bottom * fy));
}

vec3 subcone_fxaa_pixel(int x_8, int y_2, subcone_FxaaParams p) {
    bool local_1 = false;
    float length_sign = 1.0;
    float luma_nn = 0.0;
    float off_x = 0.0;
    float off_y = 1.0;
    float pos_b_x = 0.0;
    float pos_b_y = 0.0;
    float pos_n_x = 0.0;
    float pos_n_y = 0.0;
    float pos_p_x = 0.0;
    float pos_p_y = 0.0;
    float luma_end_n = 0.0;
    float luma_end_p = 0.0;
    bool done_n = false;
    bool done_p = false;
    uint i_1 = 2u;
    bool local_2 = false;
    float dst_n = 0.0;
    float dst_p = 0.0;
    float px_1 = 0.0;
    float py_1 = 0.0;
    float pos_m_x = float(x_8);
    float pos_m_y = float(y_2);
    vec4 _e5 = subcone_fxaa_tap(x_8, y_2);
    float luma_m = _e5.w;
    vec4 _e9 = subcone_fxaa_tap(x_8, (y_2 + 1));
    float luma_s = _e9.w;
    vec4 _e13 = subcone_fxaa_tap((x_8 + 1), y_2);
    float luma_e = _e13.w;
    vec4 _e17 = subcone_fxaa_tap(x_8, (y_2 - 1));
    float luma_n = _e17.w;
    vec4 _e21 = subcone_fxaa_tap((x_8 - 1), y_2);
    float luma_w = _e21.w;
    float max_sm = max(luma_s, luma_m);
    float min_sm = min(luma_s, luma_m);
    float max_esm = max(luma_e, max_sm);
    float min_esm = min(luma_e, min_sm);
    float max_wn = max(luma_n, luma_w);
    float min_wn = min(luma_n, luma_w);
    float range_max = max(max_wn, max_esm);
    float range_min = min(min_wn, min_esm);
    float range_max_scaled = (range_max * p.edge_threshold);
    float range = (range_max - range_min);
    float range_max_clamped = max(p.edge_threshold_min, range_max_scaled);
    if (!(!((range >= range_max_clamped)))) {
        local_1 = !((range > 0.0));
    } else {
        local_1 = true;
    }
    bool _e45 = local_1;
    if (_e45) {
        return _e5.xyz;
    }
    vec4 _e51 = subcone_fxaa_tap((x_8 - 1), (y_2 - 1));
    float luma_nw = _e51.w;
    vec4 _e57 = subcone_fxaa_tap((x_8 + 1), (y_2 + 1));
    float luma_se = _e57.w;
    vec4 _e63 = subcone_fxaa_tap((x_8 + 1), (y_2 - 1));
    float luma_ne = _e63.w;
    vec4 _e69 = subcone_fxaa_tap((x_8 - 1), (y_2 + 1));
    float luma_sw = _e69.w;
    float luma_ns = (luma_n + luma_s);
    float luma_we = (luma_w + luma_e);
    float subpix_rcp_range = (1.0 / range);
    float subpix_nswe = (luma_ns + luma_we);
    float edge_horz1_ = ((-2.0 * luma_m) + luma_ns);
    float edge_vert1_ = ((-2.0 * luma_m) + luma_we);
    float luma_nese = (luma_ne + luma_se);
    float luma_nwne = (luma_nw + luma_ne);
    float edge_horz2_ = ((-2.0 * luma_e) + luma_nese);
    float edge_vert2_ = ((-2.0 * luma_n) + luma_nwne);
    float luma_nwsw = (luma_nw + luma_sw);
    float luma_swse = (luma_sw + luma_se);
    float edge_horz4_ = ((abs(edge_horz1_) * 2.0) + abs(edge_horz2_));
    float edge_vert4_ = ((abs(edge_vert1_) * 2.0) + abs(edge_vert2_));
    float edge_horz3_ = ((-2.0 * luma_w) + luma_nwsw);
    float edge_vert3_ = ((-2.0 * luma_s) + luma_swse);
    float edge_horz = (abs(edge_horz3_) + edge_horz4_);
    float edge_vert = (abs(edge_vert3_) + edge_vert4_);
    float subpix_nwswnese = (luma_nwsw + luma_nese);
    bool horz_span = (edge_horz >= edge_vert);
    float subpix_a = ((subpix_nswe * 2.0) + subpix_nwswnese);
    float luma_n_span = (horz_span ? luma_n : luma_w);
    float luma_s_span = (horz_span ? luma_s : luma_e);
    float subpix_b = ((subpix_a * 0.083333336) - luma_m);
    float gradient_n = (luma_n_span - luma_m);
    float gradient_s = (luma_s_span - luma_m);
    luma_nn = (luma_n_span + luma_m);
    float luma_ss = (luma_s_span + luma_m);
    bool pair_n = (abs(gradient_n) >= abs(gradient_s));
    float gradient = max(abs(gradient_n), abs(gradient_s));
    if (pair_n) {
        float _e135 = length_sign;
        length_sign = -(_e135);
    }
    float _e139 = subcone_fxaa_clean01_((abs(subpix_b) * subpix_rcp_range));
    if (horz_span) {
        off_x = 1.0;
        off_y = 0.0;
    }
    pos_b_x = pos_m_x;
    pos_b_y = pos_m_y;
    if (!(horz_span)) {
        float _e149 = pos_b_x;
        float _e150 = length_sign;
        pos_b_x = (_e149 + (_e150 * 0.5));
    } else {
        float _e154 = pos_b_y;
        float _e155 = length_sign;
        pos_b_y = (_e154 + (_e155 * 0.5));
    }
    float _e159 = pos_b_x;
    float _e160 = off_x;
    float _e162 = subcone_fxaa_search_step(0u);
    pos_n_x = (_e159 - (_e160 * _e162));
    float _e166 = pos_b_y;
    float _e167 = off_y;
    float _e169 = subcone_fxaa_search_step(0u);
    pos_n_y = (_e166 - (_e167 * _e169));
    float _e173 = pos_b_x;
    float _e174 = off_x;
    float _e176 = subcone_fxaa_search_step(0u);
    pos_p_x = (_e173 + (_e174 * _e176));
    float _e180 = pos_b_y;
    float _e181 = off_y;
    float _e183 = subcone_fxaa_search_step(0u);
    pos_p_y = (_e180 + (_e181 * _e183));
    float subpix_d = ((-2.0 * _e139) + 3.0);
    float _e191 = pos_n_x;
    float _e192 = pos_n_y;
    vec4 _e193 = subcone_fxaa_bilinear(_e191, _e192);
    luma_end_n = _e193.w;
    float subpix_e = (_e139 * _e139);
    float _e197 = pos_p_x;
    float _e198 = pos_p_y;
    vec4 _e199 = subcone_fxaa_bilinear(_e197, _e198);
    luma_end_p = _e199.w;
    if (!(pair_n)) {
        luma_nn = luma_ss;
    }
    float gradient_scaled = ((gradient * 1.0) / 4.0);
    float _e207 = luma_nn;
    float luma_mm = (luma_m - (_e207 * 0.5));
    float subpix_f = (subpix_d * subpix_e);
    bool luma_m_lt_zero = (luma_mm < 0.0);
    float _e214 = luma_end_n;
    float _e215 = luma_nn;
    luma_end_n = (_e214 - (_e215 * 0.5));
    float _e219 = luma_end_p;
    float _e220 = luma_nn;
    luma_end_p = (_e219 - (_e220 * 0.5));
    float _e224 = luma_end_n;
    done_n = (abs(_e224) >= gradient_scaled);
    float _e228 = luma_end_p;
    done_p = (abs(_e228) >= gradient_scaled);
    bool _e232 = done_n;
    if (!(_e232)) {
        float _e234 = pos_n_x;
        float _e235 = off_x;
        float _e237 = subcone_fxaa_search_step(1u);
        pos_n_x = (_e234 - (_e235 * _e237));
        float _e240 = pos_n_y;
        float _e241 = off_y;
        float _e243 = subcone_fxaa_search_step(1u);
        pos_n_y = (_e240 - (_e241 * _e243));
    }
    bool _e246 = done_p;
    if (!(_e246)) {
        float _e248 = pos_p_x;
        float _e249 = off_x;
        float _e251 = subcone_fxaa_search_step(1u);
        pos_p_x = (_e248 + (_e249 * _e251));
        float _e254 = pos_p_y;
        float _e255 = off_y;
        float _e257 = subcone_fxaa_search_step(1u);
        pos_p_y = (_e254 + (_e255 * _e257));
    }
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e320 = i_1;
            i_1 = (_e320 + 1u);
        }
        loop_init = false;
        uint _e262 = i_1;
        if ((_e262 < 5u)) {
        } else {
            break;
        }
        {
            bool _e265 = done_n;
            if (_e265) {
                bool _e268 = done_p;
                local_2 = _e268;
            } else {
                local_2 = false;
            }
            bool _e270 = local_2;
            if (_e270) {
                break;
            }
            uint _e271 = i_1;
            float _e272 = subcone_fxaa_search_step(_e271);
            bool _e273 = done_n;
            if (!(_e273)) {
                float _e275 = pos_n_x;
                float _e276 = pos_n_y;
                vec4 _e277 = subcone_fxaa_bilinear(_e275, _e276);
                float _e279 = luma_nn;
                luma_end_n = (_e277.w - (_e279 * 0.5));
            }
            bool _e283 = done_p;
            if (!(_e283)) {
                float _e285 = pos_p_x;
                float _e286 = pos_p_y;
                vec4 _e287 = subcone_fxaa_bilinear(_e285, _e286);
                float _e289 = luma_nn;
                luma_end_p = (_e287.w - (_e289 * 0.5));
            }
            float _e293 = luma_end_n;
            done_n = (abs(_e293) >= gradient_scaled);
            float _e296 = luma_end_p;
            done_p = (abs(_e296) >= gradient_scaled);
            bool _e299 = done_n;
            if (!(_e299)) {
                float _e301 = pos_n_x;
                float _e302 = off_x;
                pos_n_x = (_e301 - (_e302 * _e272));
                float _e305 = pos_n_y;
                float _e306 = off_y;
                pos_n_y = (_e305 - (_e306 * _e272));
            }
            bool _e309 = done_p;
            if (!(_e309)) {
                float _e311 = pos_p_x;
                float _e312 = off_x;
                pos_p_x = (_e311 + (_e312 * _e272));
                float _e315 = pos_p_y;
                float _e316 = off_y;
                pos_p_y = (_e315 + (_e316 * _e272));
            }
        }
    }
    float _e322 = pos_n_y;
    dst_n = (pos_m_y - _e322);
    float _e325 = pos_p_y;
    dst_p = (_e325 - pos_m_y);
    if (horz_span) {
        float _e328 = pos_n_x;
        dst_n = (pos_m_x - _e328);
        float _e330 = pos_p_x;
        dst_p = (_e330 - pos_m_x);
    }
    float _e332 = luma_end_n;
    bool good_span_n = ((_e332 < 0.0) != luma_m_lt_zero);
    float _e336 = dst_p;
    float _e337 = dst_n;
    float span_length = (_e336 + _e337);
    float _e339 = luma_end_p;
    bool good_span_p = ((_e339 < 0.0) != luma_m_lt_zero);
    float span_length_rcp = (1.0 / span_length);
    float _e345 = dst_n;
    float _e346 = dst_p;
    bool direction_n = (_e345 < _e346);
    float _e348 = dst_n;
    float _e349 = dst_p;
    float dst = min(_e348, _e349);
    bool good_span = (direction_n ? good_span_n : good_span_p);
    float subpix_g = (subpix_f * subpix_f);
    float pixel_offset = ((dst * -(span_length_rcp)) + 0.5);
    float subpix_h = (subpix_g * p.subpix);
    float pixel_offset_good = (good_span ? pixel_offset : 0.0);
    float _e362 = subcone_fxaa_clean01_(max(pixel_offset_good, subpix_h));
    px_1 = pos_m_x;
    py_1 = pos_m_y;
    if (!(horz_span)) {
        float _e366 = px_1;
        float _e367 = length_sign;
        px_1 = (_e366 + (_e362 * _e367));
    } else {
        float _e370 = py_1;
        float _e371 = length_sign;
        py_1 = (_e370 + (_e362 * _e371));
    }
    float _e374 = px_1;
    float _e375 = py_1;
    vec4 _e376 = subcone_fxaa_bilinear(_e374, _e375);
    return _e376.xyz;
}

void main() {
    uvec3 gid = gl_GlobalInvocationID;
    bool local = false;
    uint _e4 = _group_0_binding_1_cs.width;
    if (!((gid.x >= _e4))) {
        uint _e12 = _group_0_binding_1_cs.height;
        local = (gid.y >= _e12);
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    subcone_FxaaParams _e21 = _group_0_binding_0_cs;
    vec3 _e22 = subcone_fxaa_pixel(int(gid.x), int(gid.y), _e21);
    vec3 _e29 = subcone_fxaa_decode(_e22);
    imageStore(_group_0_binding_3_cs, ivec2(int(gid.x), int(gid.y)), vec4(_e29, 1.0));
    return;
}

