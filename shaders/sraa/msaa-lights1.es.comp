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
struct subcone_Neighbourhood {
    uint x0_;
    uint y0_;
    uint x1_;
    uint y1_;
    vec2 offset;
};
struct subcone_WeightedSum {
    vec3 sum;
    vec3 sum_c;
    float weight;
    float weight_c;
};
struct subcone_LayerState {
    subcone_WeightedSum acc;
    vec3 nearest;
    float nearest_d2_;
    bool any_;
};
struct subcone_LayerStates {
    subcone_LayerState at[9];
};
struct subcone_Subsamples4_ {
    vec3 at[4];
};
struct SraaFrame {
    subcone_SraaParams sraa;
    vec4 projection;
    uint width;
    uint height;
    float depth_miss;
    float albedo_tolerance;
    uint origin_x;
    uint origin_y;
    float exposure;
    uint _pad;
};
const float subcone_NEGLIGIBLE_WEIGHT = 5.421011e-20;
const float subcone_NORMAL_COS_SNAP = 4.7683716e-7;
const uint subcone_SHADED_SUBSAMPLE = 0u;
const uint subcone_SHADED_SAMPLE = 4u;
const float subcone_ALBEDO_TOLERANCE = 0.1;
const vec3 subcone_RESOLVE_LUMA = vec3(0.2126, 0.7152, 0.0722);
const uint LIGHTS = 1u;
const bool MATERIAL = false;
const bool HARDWARE_DEPTH = true;
const bool UNSIGNED_NORMALS = false;
const bool SHADED_GIVEN = false;
const bool DECODED = false;
const bool SECONDARY = false;
const bool TONE_MAPPED_RESOLVE = false;
const uint SRAA_GATES = 2u;
const bool SRAA_MATERIAL = false;

layout(binding = 6,rgba16f) writeonly uniform highp image2D _group_0_binding_6_cs;

layout(binding = 2) uniform highp sampler2DMS _group_0_binding_2_cs;

layout(binding = 1) uniform highp sampler2DMS _group_0_binding_1_cs;

layout(binding = 3) uniform highp sampler2DArray _group_0_binding_3_cs;

layout(binding = 4) uniform highp usampler2D _group_0_binding_4_cs;

layout(binding = 5) uniform highp usampler2DArray _group_0_binding_5_cs;

layout(std140, binding = 0) uniform SraaFrame_block_0Compute { SraaFrame _group_0_binding_0_cs; };


float subcone_inf() {
    return uintBitsToFloat(2139095040u);
}

bool subcone_is_nan(float x) {
    return ((floatBitsToUint(x) & 2147483647u) > 2139095040u);
}

bool subcone_is_finite(float x_1) {
    return ((floatBitsToUint(x_1) & 2147483647u) < 2139095040u);
}

vec3 subcone_pinhole_dir(subcone_PinholeCamera c_1, vec2 p_in) {
    vec2 p_19 = (p_in + c_1.jitter);
    float w_4 = float(max(c_1.width, 1u));
    float h = float(max(c_1.height, 1u));
    float u = (((((2.0 * p_19.x) / w_4) - 1.0) * c_1.tan_half_fov) * (w_4 / h));
    float v_3 = ((1.0 - ((2.0 * p_19.y) / h)) * c_1.tan_half_fov);
    vec3 d_1 = ((c_1.forward + (u * c_1.right)) + (v_3 * c_1.up));
    return (d_1 * (1.0 / length(d_1)));
}

bool subcone_sraa_is_finite3_(vec3 c_2) {
    bool local_1 = false;
    bool local_2 = false;
    bool _e2 = subcone_is_finite(c_2.x);
    if (_e2) {
        bool _e6 = subcone_is_finite(c_2.y);
        local_1 = _e6;
    } else {
        local_1 = false;
    }
    bool _e8 = local_1;
    if (_e8) {
        bool _e12 = subcone_is_finite(c_2.z);
        local_2 = _e12;
    } else {
        local_2 = false;
    }
    bool _e14 = local_2;
    return _e14;
}

bool subcone_sraa_any_nan3_(vec3 c_3) {
    bool local_3 = false;
    bool local_4 = false;
    bool _e2 = subcone_is_nan(c_3.x);
    if (!(_e2)) {
        bool _e7 = subcone_is_nan(c_3.y);
        local_3 = _e7;
    } else {
        local_3 = true;
    }
    bool _e9 = local_3;
    if (!(_e9)) {
        bool _e14 = subcone_is_nan(c_3.z);
        local_4 = _e14;
    } else {
        local_4 = true;
    }
    bool _e16 = local_4;
    return _e16;
}

vec2 subcone_subpixel_offset(uint k) {
    switch(k) {
        case 1u: {
            return vec2(0.375, -0.125);
        }
        case 2u: {
            return vec2(-0.375, 0.125);
        }
        case 3u: {
            return vec2(0.125, 0.375);
        }
        default: {
            return vec2(-0.125, -0.375);
        }
    }
}

uint subcone_sraa_form(subcone_SraaParams p) {
    if (((p.packed_ & 255u) == 1u)) {
        return 1u;
    }
    return 0u;
}

uint subcone_sraa_depth_metric(subcone_SraaParams p_1) {
    if ((((p_1.packed_ >> 8u) & 255u) == 1u)) {
        return 1u;
    }
    return 0u;
}

uint subcone_sraa_radius(subcone_SraaParams p_2) {
    return (p_2.packed_ >> 16u);
}

vec2 subcone_sraa_shaded_offset(subcone_SraaParams p_3) {
    if ((p_3.shading == 1u)) {
        return vec2(0.0);
    }
    vec2 _e7 = subcone_subpixel_offset(subcone_SHADED_SUBSAMPLE);
    return _e7;
}

bool subcone_sraa_is_shaded_subsample(subcone_SraaParams p_4, uint k_1) {
    bool local_5 = false;
    if ((p_4.shading != 1u)) {
        local_5 = (k_1 == subcone_SHADED_SUBSAMPLE);
    } else {
        local_5 = false;
    }
    bool _e10 = local_5;
    return _e10;
}

float subcone_gaussian(float x_2) {
    float e = exp(-((x_2 * x_2)));
    bool _e4 = subcone_is_nan(e);
    if (_e4) {
        return 0.0;
    }
    return e;
}

float subcone_gaussian_sum(float s) {
    bool local_6 = false;
    if ((s == 0.0)) {
        return 1.0;
    }
    bool _e4 = subcone_is_nan(s);
    if (!(_e4)) {
        local_6 = !((s < 105.0));
    } else {
        local_6 = true;
    }
    bool _e12 = local_6;
    if (_e12) {
        return 0.0;
    }
    float e_1 = exp(-(s));
    bool _e16 = subcone_is_nan(e_1);
    if (_e16) {
        return 0.0;
    }
    return e_1;
}

float subcone_saturate(float x_3) {
    if ((x_3 > 0.0)) {
        if ((x_3 < 1.0)) {
            return x_3;
        }
        return 1.0;
    }
    return 0.0;
}

float subcone_depth_difference(float zi, float zj, uint metric) {
    bool local_7 = false;
    float r = 0.0;
    if ((zi == zj)) {
        bool _e6 = subcone_is_nan(zi);
        local_7 = !(_e6);
    } else {
        local_7 = false;
    }
    bool _e9 = local_7;
    if (_e9) {
        return 0.0;
    }
    float diff = abs((zj - zi));
    r = diff;
    if ((metric != 1u)) {
        float m = max(abs(zi), abs(zj));
        if ((m > 1.2676506e30)) {
            r = ((diff / m) / (0.5 + (0.5 * (min(abs(zi), abs(zj)) / m))));
        } else {
            float mean = ((0.5 * abs(zi)) + (0.5 * abs(zj)));
            if ((mean == 0.0)) {
                float _e40 = subcone_inf();
                return _e40;
            }
            r = (diff / mean);
        }
    }
    float _e42 = r;
    bool _e43 = subcone_is_nan(_e42);
    if (_e43) {
        float _e44 = subcone_inf();
        return _e44;
    }
    float _e45 = r;
    return _e45;
}

float subcone_reconstruction_weight(subcone_SraaParams params, subcone_Geometry gi, subcone_Geometry gj, float distance2_) {
    float spatial = 0.0;
    bool local_8 = false;
    float dn = 0.0;
    bool local_9 = false;
    bool local_10 = false;
    float w = 0.0;
    bool local_11 = false;
    if ((params.sigma_s > 0.0)) {
        local_8 = (distance2_ != 0.0);
    } else {
        local_8 = false;
    }
    bool _e14 = local_8;
    if (_e14) {
        spatial = (distance2_ / (params.sigma_s * params.sigma_s));
    }
    uint _e21 = subcone_sraa_depth_metric(params);
    float _e22 = subcone_depth_difference(gi.depth, gj.depth, _e21);
    float _e26 = subcone_saturate(dot(gj.normal, gi.normal));
    dn = (1.0 - _e26);
    if ((_e26 >= 0.9999995)) {
        dn = 0.0;
    }
    float _e33 = subcone_inf();
    if ((gi.depth == _e33)) {
        local_9 = (gj.depth == _e33);
    } else {
        local_9 = false;
    }
    bool _e41 = local_9;
    if (_e41) {
        return 1.0;
    }
    bool _e44 = subcone_sraa_any_nan3_(gi.normal);
    if (!(_e44)) {
        bool _e49 = subcone_sraa_any_nan3_(gj.normal);
        local_10 = _e49;
    } else {
        local_10 = true;
    }
    bool _e51 = local_10;
    if (_e51) {
        return 0.0;
    }
    uint _e55 = subcone_sraa_form(params);
    if ((_e55 == 0u)) {
        float a_2 = (params.sigma_z * _e22);
        float _e61 = dn;
        float b_2 = (params.sigma_n * _e61);
        float _e66 = spatial;
        float _e68 = subcone_gaussian_sum((((a_2 * a_2) + (b_2 * b_2)) + _e66));
        w = _e68;
    } else {
        float _e70 = dn;
        float x_13 = (params.scale * max(_e70, (params.sigma_z * _e22)));
        bool _e75 = subcone_is_nan(x_13);
        if (!(_e75)) {
            local_11 = (x_13 == _e33);
        } else {
            local_11 = true;
        }
        bool _e81 = local_11;
        if (_e81) {
            w = 0.0;
        } else {
            w = exp(-(x_13));
            float _e85 = w;
            bool _e86 = subcone_is_nan(_e85);
            if (_e86) {
                w = 0.0;
            }
        }
        float _e88 = spatial;
        if ((_e88 != 0.0)) {
            float _e91 = w;
            float _e92 = spatial;
            float _e93 = subcone_gaussian_sum(_e92);
            w = (_e91 * _e93);
        }
    }
    float _e95 = w;
    float _e96 = subcone_saturate(_e95);
    return _e96;
}

float subcone_bilateral_weight(subcone_SraaParams params_1, subcone_Geometry gi_1, subcone_Geometry gj_1) {
    float _e4 = subcone_reconstruction_weight(params_1, gi_1, gj_1, 0.0);
    return _e4;
}

float subcone_shadow_gated_weight(subcone_SraaParams params_2, subcone_Geometry gi_2, subcone_Geometry gj_2, bool si, bool sj) {
    if ((si != sj)) {
        return 0.0;
    }
    float _e7 = subcone_bilateral_weight(params_2, gi_2, gj_2);
    return _e7;
}

float subcone_albedo_difference(vec3 a, vec3 b) {
    bool local_12 = false;
    bool _e2 = subcone_sraa_is_finite3_(a);
    if (!(!(_e2))) {
        bool _e7 = subcone_sraa_is_finite3_(b);
        local_12 = !(_e7);
    } else {
        local_12 = true;
    }
    bool _e10 = local_12;
    if (_e10) {
        float _e11 = subcone_inf();
        return _e11;
    }
    vec3 d_2 = abs((sqrt(max(a, vec3(0.0))) - sqrt(max(b, vec3(0.0)))));
    return max(d_2.x, max(d_2.y, d_2.z));
}

bool subcone_material_gate(vec3 ai, vec3 aj, float tolerance) {
    bool local_13 = false;
    float _e3 = subcone_albedo_difference(ai, aj);
    if ((_e3 <= tolerance)) {
        float _e7 = subcone_inf();
        local_13 = (_e3 < _e7);
    } else {
        local_13 = false;
    }
    bool _e10 = local_13;
    return _e10;
}

float subcone_material_gated_weight(subcone_SraaParams params_3, subcone_Geometry gi_3, subcone_Geometry gj_3, vec3 ai_1, vec3 aj_1, float tolerance_1) {
    bool _e6 = subcone_material_gate(ai_1, aj_1, tolerance_1);
    if (_e6) {
        float _e7 = subcone_bilateral_weight(params_3, gi_3, gj_3);
        return _e7;
    }
    return 0.0;
}

uint subcone_sraa_saturating_add(uint a_1, uint b_1) {
    uint s_2 = (a_1 + b_1);
    if ((s_2 < a_1)) {
        return 4294967295u;
    }
    return s_2;
}

subcone_Neighbourhood subcone_neighbourhood(uint x_4, uint y, uint sub, vec2 shaded, uint radius, uint width, uint height) {
    vec2 pos = vec2(0.0);
    subcone_Neighbourhood n = subcone_Neighbourhood(0u, 0u, 0u, 0u, vec2(0.0));
    pos = shaded;
    if ((sub < 4u)) {
        vec2 _e10 = subcone_subpixel_offset(sub);
        pos = _e10;
    }
    vec2 _e13 = pos;
    n.offset = (_e13 - shaded);
    n.x0_ = ((x_4 >= radius) ? (x_4 - radius) : 0u);
    n.y0_ = ((y >= radius) ? (y - radius) : 0u);
    uint _e26 = subcone_sraa_saturating_add(x_4, radius);
    uint _e28 = subcone_sraa_saturating_add(_e26, 1u);
    n.x1_ = min(_e28, width);
    uint _e31 = subcone_sraa_saturating_add(y, radius);
    uint _e33 = subcone_sraa_saturating_add(_e31, 1u);
    n.y1_ = min(_e33, height);
    subcone_Neighbourhood _e35 = n;
    return _e35;
}

float subcone_neighbour_distance2_(subcone_Neighbourhood n_1, uint x_5, uint y_1, uint px, uint py) {
    vec2 d_3 = (vec2((float(px) - float(x_5)), (float(py) - float(y_1))) - n_1.offset);
    return ((d_3.x * d_3.x) + (d_3.y * d_3.y));
}

subcone_WeightedSum subcone_weighted_sum_zero() {
    return subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0);
}

void subcone_weighted_sum_add(inout subcone_WeightedSum acc, float w_1, vec3 c_4) {
    vec3 _e5 = acc.sum_c;
    vec3 y_9 = ((w_1 * c_4) - _e5);
    vec3 _e8 = acc.sum;
    vec3 t = (_e8 + y_9);
    vec3 _e12 = acc.sum;
    acc.sum_c = ((t - _e12) - y_9);
    acc.sum = t;
    float _e17 = acc.weight_c;
    float yw = (w_1 - _e17);
    float _e20 = acc.weight;
    float tw = (_e20 + yw);
    float _e24 = acc.weight;
    acc.weight_c = ((tw - _e24) - yw);
    acc.weight = tw;
    return;
}

vec4 subcone_weighted_sum_mean(subcone_WeightedSum acc_1) {
    if (!((acc_1.weight >= subcone_NEGLIGIBLE_WEIGHT))) {
        return vec4(0.0);
    }
    float inv = (1.0 / acc_1.weight);
    vec3 c_9 = (acc_1.sum * inv);
    bool _e12 = subcone_sraa_is_finite3_(c_9);
    if (!(_e12)) {
        return vec4(0.0);
    }
    return vec4(c_9, 1.0);
}

subcone_LayerState subcone_reconstruct_layers_begin() {
    subcone_WeightedSum _e0 = subcone_weighted_sum_zero();
    float _e3 = subcone_inf();
    return subcone_LayerState(_e0, vec3(0.0), _e3, false);
}

void subcone_reconstruct_layers_add(inout subcone_LayerState state, float w_2, bool gated, uint bit, uint target_shadow, uint shadow, float distance2_1, vec3 c_5) {
    float d2_ = 0.0;
    bool local_14 = false;
    float wi = 0.0;
    bool local_15 = false;
    bool local_16 = false;
    subcone_WeightedSum acc_2 = subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0);
    bool _e8 = subcone_sraa_is_finite3_(c_5);
    if (!(_e8)) {
        return;
    }
    d2_ = distance2_1;
    float _e11 = d2_;
    bool _e12 = subcone_is_nan(_e11);
    if (_e12) {
        float _e13 = subcone_inf();
        d2_ = _e13;
    }
    bool _e15 = state.any_;
    if (!(!(_e15))) {
        float _e20 = d2_;
        float _e22 = state.nearest_d2_;
        local_14 = (_e20 < _e22);
    } else {
        local_14 = true;
    }
    bool _e25 = local_14;
    if (_e25) {
        state.nearest = c_5;
        float _e28 = d2_;
        state.nearest_d2_ = _e28;
        state.any_ = true;
    }
    wi = w_2;
    if (gated) {
        local_15 = (bit < 32u);
    } else {
        local_15 = false;
    }
    bool _e37 = local_15;
    if (_e37) {
        local_16 = ((((target_shadow ^ shadow) >> bit) & 1u) != 0u);
    } else {
        local_16 = false;
    }
    bool _e47 = local_16;
    if (_e47) {
        wi = 0.0;
    }
    subcone_WeightedSum _e50 = state.acc;
    acc_2 = _e50;
    float _e52 = wi;
    subcone_weighted_sum_add(acc_2, _e52, c_5);
    subcone_WeightedSum _e54 = acc_2;
    state.acc = _e54;
    return;
}

vec3 subcone_reconstruct_layers_end(subcone_LayerState state_1) {
    vec4 _e2 = subcone_weighted_sum_mean(state_1.acc);
    if ((_e2.w > 0.0)) {
        return _e2.xyz;
    }
    return state_1.nearest;
}

vec3 subcone_resolve_pixel(vec3 s0_, vec3 s1_, vec3 s2_, vec3 s3_) {
    vec3 s_1 = vec3(0.0);
    bool _e4 = subcone_sraa_is_finite3_(s0_);
    bool _e5 = subcone_sraa_is_finite3_(s1_);
    bool _e6 = subcone_sraa_is_finite3_(s2_);
    bool _e7 = subcone_sraa_is_finite3_(s3_);
    uint n_3 = (((uint(_e4) + uint(_e5)) + uint(_e6)) + uint(_e7));
    if ((n_3 == 0u)) {
        return vec3(0.0);
    }
    float inv_1 = (1.0 / float(n_3));
    if (_e4) {
        vec3 _e25 = s_1;
        s_1 = (_e25 + (s0_ * inv_1));
    }
    if (_e5) {
        vec3 _e28 = s_1;
        s_1 = (_e28 + (s1_ * inv_1));
    }
    if (_e6) {
        vec3 _e31 = s_1;
        s_1 = (_e31 + (s2_ * inv_1));
    }
    if (_e7) {
        vec3 _e34 = s_1;
        s_1 = (_e34 + (s3_ * inv_1));
    }
    vec3 _e37 = s_1;
    return _e37;
}

float subcone_tone_map_weight(vec3 c_6, float exposure) {
    bool local_17 = false;
    float luma = 0.0;
    bool _e2 = subcone_sraa_is_finite3_(c_6);
    if (!(!(_e2))) {
        bool _e7 = subcone_is_finite(exposure);
        local_17 = !(_e7);
    } else {
        local_17 = true;
    }
    bool _e10 = local_17;
    if (_e10) {
        return 0.0;
    }
    luma = (dot(c_6, subcone_RESOLVE_LUMA) * exposure);
    float _e16 = luma;
    if (!((_e16 > 0.0))) {
        luma = 0.0;
    }
    float _e21 = luma;
    return (1.0 / (1.0 + _e21));
}

vec3 subcone_resolve_pixel_tone_mapped(vec3 s0_1, vec3 s1_1, vec3 s2_1, vec3 s3_1, float exposure_1) {
    bool local_18 = false;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    subcone_Subsamples4_ subs = subcone_Subsamples4_(vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0)));
    uint k_2 = 0u;
    if (!(!((exposure_1 > 0.0)))) {
        bool _e11 = subcone_is_finite(exposure_1);
        local_18 = !(_e11);
    } else {
        local_18 = true;
    }
    bool _e14 = local_18;
    if (_e14) {
        vec3 _e15 = subcone_resolve_pixel(s0_1, s1_1, s2_1, s3_1);
        return _e15;
    }
    subs = subcone_Subsamples4_(vec3[4](s0_1, s1_1, s2_1, s3_1));
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e41 = k_2;
            k_2 = (_e41 + 1u);
        }
        loop_init = false;
        uint _e26 = k_2;
        if ((_e26 < 4u)) {
        } else {
            break;
        }
        {
            uint _e30 = k_2;
            vec3 c_10 = subs.at[_e30];
            bool _e33 = subcone_sraa_is_finite3_(c_10);
            if (_e33) {
                float _e34 = subcone_tone_map_weight(c_10, exposure_1);
                vec3 _e35 = sum;
                sum = (_e35 + (_e34 * c_10));
                float _e38 = weight;
                weight = (_e38 + _e34);
            }
        }
    }
    float _e43 = weight;
    if ((_e43 > 0.0)) {
        vec3 _e46 = sum;
        float _e47 = weight;
        vec3 m_1 = (_e46 / vec3(_e47));
        bool _e50 = subcone_sraa_is_finite3_(m_1);
        if (_e50) {
            return m_1;
        }
    }
    vec3 _e51 = subcone_resolve_pixel(s0_1, s1_1, s2_1, s3_1);
    return _e51;
}

void sraa_store(ivec2 p_5, vec4 c_7) {
    imageStore(_group_0_binding_6_cs, p_5, c_7);
    return;
}

vec4 sraa_load_sub(ivec2 p_6, uint k_3) {
    vec4 _e4 = texelFetch(_group_0_binding_2_cs, p_6, int(k_3));
    vec4 _e8 = texelFetch(_group_0_binding_1_cs, p_6, int(k_3));
    return vec4(_e4.xyz, _e8.x);
}

vec4 sraa_load_shaded(ivec2 p_7) {
    return vec4(0.0);
}

vec3 sraa_load_color(ivec2 p_8, uint l) {
    vec4 _e5 = texelFetch(_group_0_binding_3_cs, ivec3(p_8, int(l)), 0);
    return _e5.xyz;
}

uint sraa_load_shaded_shadow(ivec2 p_9) {
    uvec4 _e3 = texelFetch(_group_0_binding_4_cs, p_9, 0);
    return _e3.x;
}

uint sraa_load_sub_shadow(ivec2 p_10, uint k_4) {
    uvec4 _e5 = texelFetch(_group_0_binding_5_cs, ivec3(p_10, int(k_4)), 0);
    return _e5.x;
}

uint sraa_load_sec_shaded_shadow(ivec2 p_11) {
    return 0u;
}

uint sraa_load_sec_sub_shadow(ivec2 p_12, uint k_5) {
    return 0u;
}

vec4 sraa_load_sec_shaded(ivec2 p_13) {
    return vec4(0.0);
}

vec4 sraa_load_sec_sub(ivec2 p_14, uint k_6) {
    return vec4(0.0);
}

vec3 sraa_load_shaded_albedo(ivec2 p_15) {
    return vec3(0.0);
}

vec3 sraa_load_sub_albedo(ivec2 p_16, uint k_7) {
    return vec3(0.0);
}

ivec2 sraa_texel(uint x_6, uint y_2) {
    uint _e4 = _group_0_binding_0_cs.origin_x;
    uint _e9 = _group_0_binding_0_cs.origin_y;
    return ivec2(int((x_6 + _e4)), int((y_2 + _e9)));
}

float sraa_decode_depth(float d) {
    float z = 0.0;
    bool local_19 = false;
    z = d;
    if (HARDWARE_DEPTH) {
        float _e5 = _group_0_binding_0_cs.depth_miss;
        if ((d == _e5)) {
            float _e7 = subcone_inf();
            return _e7;
        }
        vec4 m_2 = _group_0_binding_0_cs.projection;
        z = abs(((m_2.y - (d * m_2.w)) / ((d * m_2.z) - m_2.x)));
    }
    float _e21 = z;
    bool _e22 = subcone_is_finite(_e21);
    if (_e22) {
        float _e25 = z;
        local_19 = (_e25 > 0.0);
    } else {
        local_19 = false;
    }
    bool _e29 = local_19;
    if (_e29) {
        float _e30 = z;
        return _e30;
    }
    float _e31 = subcone_inf();
    return _e31;
}

vec3 sraa_decode_normal(vec3 v) {
    vec3 n_2 = vec3(0.0);
    bool local_20 = false;
    n_2 = v;
    if (UNSIGNED_NORMALS) {
        n_2 = ((v * 2.0) - vec3(1.0));
    }
    vec3 _e8 = n_2;
    vec3 _e9 = n_2;
    float l2_ = dot(_e8, _e9);
    if ((l2_ > 0.0)) {
        bool _e15 = subcone_is_finite(l2_);
        local_20 = _e15;
    } else {
        local_20 = false;
    }
    bool _e17 = local_20;
    if (_e17) {
        vec3 _e18 = n_2;
        return (_e18 * (1.0 / sqrt(l2_)));
    }
    return vec3(0.0);
}

subcone_Geometry sraa_geometry(vec4 v_1) {
    if (DECODED) {
        return subcone_Geometry(v_1.xyz, v_1.w);
    }
    float _e6 = sraa_decode_depth(v_1.w);
    float _e7 = subcone_inf();
    if ((_e6 == _e7)) {
        return subcone_Geometry(vec3(0.0), _e6);
    }
    vec3 _e13 = sraa_decode_normal(v_1.xyz);
    return subcone_Geometry(_e13, _e6);
}

subcone_Geometry sraa_sub_geo(ivec2 p_17, uint k_8) {
    vec4 _e2 = sraa_load_sub(p_17, k_8);
    subcone_Geometry _e3 = sraa_geometry(_e2);
    return _e3;
}

subcone_Geometry sraa_shaded_geo(ivec2 p_18) {
    if (SHADED_GIVEN) {
        vec4 _e2 = sraa_load_shaded(p_18);
        subcone_Geometry _e3 = sraa_geometry(_e2);
        return _e3;
    }
    subcone_Geometry _e5 = sraa_sub_geo(p_18, subcone_SHADED_SUBSAMPLE);
    return _e5;
}

subcone_Geometry sraa_secondary_geometry(vec4 v_2) {
    bool local_21 = false;
    bool local_22 = false;
    if (DECODED) {
        return subcone_Geometry(v_2.xyz, v_2.w);
    }
    bool _e6 = subcone_is_nan(v_2.w);
    if (!(_e6)) {
        local_21 = (v_2.w < 0.0);
    } else {
        local_21 = true;
    }
    bool _e14 = local_21;
    if (_e14) {
        return subcone_Geometry(vec3(0.0), uintBitsToFloat(2143289344u));
    }
    if (!((v_2.w == 0.0))) {
        float _e27 = subcone_inf();
        local_22 = (v_2.w == _e27);
    } else {
        local_22 = true;
    }
    bool _e30 = local_22;
    if (_e30) {
        float _e33 = subcone_inf();
        return subcone_Geometry(vec3(0.0), _e33);
    }
    vec3 _e36 = sraa_decode_normal(v_2.xyz);
    return subcone_Geometry(_e36, v_2.w);
}

subcone_SraaParams sraa_params() {
    subcone_SraaParams _e2 = _group_0_binding_0_cs.sraa;
    return _e2;
}

uvec2 sraa_size() {
    uint _e2 = _group_0_binding_0_cs.width;
    uint _e5 = _group_0_binding_0_cs.height;
    return uvec2(_e2, _e5);
}

float sraa_albedo_tolerance() {
    float _e2 = _group_0_binding_0_cs.albedo_tolerance;
    return _e2;
}

subcone_Geometry sraa_shaded_geometry(uint x_7, uint y_3, bool secondary) {
    ivec2 _e3 = sraa_texel(x_7, y_3);
    if (secondary) {
        vec4 _e4 = sraa_load_sec_shaded(_e3);
        subcone_Geometry _e5 = sraa_secondary_geometry(_e4);
        return _e5;
    }
    subcone_Geometry _e6 = sraa_shaded_geo(_e3);
    return _e6;
}

uint sraa_shaded_shadow(uint x_8, uint y_4, bool secondary_1) {
    ivec2 _e3 = sraa_texel(x_8, y_4);
    if (secondary_1) {
        uint _e4 = sraa_load_sec_shaded_shadow(_e3);
        return _e4;
    }
    uint _e5 = sraa_load_shaded_shadow(_e3);
    return _e5;
}

vec3 sraa_shaded_albedo(uint x_9, uint y_5) {
    ivec2 _e2 = sraa_texel(x_9, y_5);
    vec3 _e3 = sraa_load_shaded_albedo(_e2);
    return _e3;
}

vec3 sraa_shaded_value(uint x_10, uint y_6, uint layer) {
    ivec2 _e3 = sraa_texel(x_10, y_6);
    vec3 _e4 = sraa_load_color(_e3, layer);
    return _e4;
}

vec3 subcone_sraa_reconstruct_run(subcone_Geometry tgt, uint target_shadow_1, vec3 ta, bool secondary_2, uint first, uint x_11, uint y_7, uint k_9) {
    subcone_LayerStates st = subcone_LayerStates(subcone_LayerState[9](subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false), subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false)));
    uint i = 0u;
    uint py_1 = 0u;
    uint px_1 = 0u;
    float w_3 = 0.0;
    bool local_23 = false;
    bool local_24 = false;
    uint i_1 = 0u;
    subcone_LayerState layer_1 = subcone_LayerState(subcone_WeightedSum(vec3(0.0), vec3(0.0), 0.0, 0.0), vec3(0.0), 0.0, false);
    vec3 sum_1 = vec3(0.0);
    uint i_2 = 0u;
    subcone_SraaParams _e8 = sraa_params();
    uvec2 _e9 = sraa_size();
    bool loop_init_1 = true;
    while(true) {
        if (!loop_init_1) {
            uint _e21 = i;
            i = (_e21 + 1u);
        }
        loop_init_1 = false;
        uint _e13 = i;
        if ((_e13 < SRAA_GATES)) {
        } else {
            break;
        }
        {
            uint _e17 = i;
            subcone_LayerState _e19 = subcone_reconstruct_layers_begin();
            st.at[_e17] = _e19;
        }
    }
    vec2 _e23 = subcone_sraa_shaded_offset(_e8);
    uint _e24 = subcone_sraa_radius(_e8);
    subcone_Neighbourhood _e27 = subcone_neighbourhood(x_11, y_7, k_9, _e23, _e24, _e9.x, _e9.y);
    py_1 = _e27.y0_;
    bool loop_init_2 = true;
    while(true) {
        if (!loop_init_2) {
            uint _e100 = py_1;
            py_1 = (_e100 + 1u);
        }
        loop_init_2 = false;
        uint _e30 = py_1;
        if ((_e30 < _e27.y1_)) {
        } else {
            break;
        }
        {
            px_1 = _e27.x0_;
            bool loop_init_3 = true;
            while(true) {
                if (!loop_init_3) {
                    uint _e97 = px_1;
                    px_1 = (_e97 + 1u);
                }
                loop_init_3 = false;
                uint _e35 = px_1;
                if ((_e35 < _e27.x1_)) {
                } else {
                    break;
                }
                {
                    uint _e38 = px_1;
                    uint _e39 = py_1;
                    float _e40 = subcone_neighbour_distance2_(_e27, x_11, y_7, _e38, _e39);
                    uint _e41 = px_1;
                    uint _e42 = py_1;
                    subcone_Geometry _e43 = sraa_shaded_geometry(_e41, _e42, secondary_2);
                    uint _e44 = px_1;
                    uint _e45 = py_1;
                    uint _e46 = sraa_shaded_shadow(_e44, _e45, secondary_2);
                    w_3 = 0.0;
                    if (SRAA_MATERIAL) {
                        local_23 = !(secondary_2);
                    } else {
                        local_23 = false;
                    }
                    bool _e54 = local_23;
                    if (!(!(_e54))) {
                        uint _e59 = px_1;
                        uint _e60 = py_1;
                        vec3 _e61 = sraa_shaded_albedo(_e59, _e60);
                        float _e62 = sraa_albedo_tolerance();
                        bool _e63 = subcone_material_gate(ta, _e61, _e62);
                        local_24 = _e63;
                    } else {
                        local_24 = true;
                    }
                    bool _e65 = local_24;
                    if (_e65) {
                        float _e66 = subcone_reconstruction_weight(_e8, tgt, _e43, _e40);
                        w_3 = _e66;
                    }
                    i_1 = 0u;
                    bool loop_init_4 = true;
                    while(true) {
                        if (!loop_init_4) {
                            uint _e94 = i_1;
                            i_1 = (_e94 + 1u);
                        }
                        loop_init_4 = false;
                        uint _e69 = i_1;
                        if ((_e69 < SRAA_GATES)) {
                        } else {
                            break;
                        }
                        {
                            uint _e73 = i_1;
                            subcone_LayerState _e75 = st.at[_e73];
                            layer_1 = _e75;
                            float _e77 = w_3;
                            uint _e78 = i_1;
                            uint _e81 = i_1;
                            uint _e84 = px_1;
                            uint _e85 = py_1;
                            uint _e86 = i_1;
                            vec3 _e88 = sraa_shaded_value(_e84, _e85, (first + _e86));
                            subcone_reconstruct_layers_add(layer_1, _e77, (_e78 > 0u), (_e81 - 1u), target_shadow_1, _e46, _e40, _e88);
                            uint _e90 = i_1;
                            subcone_LayerState _e92 = layer_1;
                            st.at[_e90] = _e92;
                        }
                    }
                }
            }
        }
    }
    bool loop_init_5 = true;
    while(true) {
        if (!loop_init_5) {
            uint _e118 = i_2;
            i_2 = (_e118 + 1u);
        }
        loop_init_5 = false;
        uint _e107 = i_2;
        if ((_e107 < SRAA_GATES)) {
        } else {
            break;
        }
        {
            vec3 _e110 = sum_1;
            uint _e112 = i_2;
            subcone_LayerState _e114 = st.at[_e112];
            vec3 _e115 = subcone_reconstruct_layers_end(_e114);
            sum_1 = (_e110 + _e115);
        }
    }
    vec3 _e120 = sum_1;
    return _e120;
}

vec3 sraa_reconstruct_subsample(uint x_12, uint y_8, uint k_10) {
    vec3 c_8 = vec3(0.0);
    ivec2 _e3 = sraa_texel(x_12, y_8);
    subcone_Geometry _e4 = sraa_sub_geo(_e3, k_10);
    uint _e5 = sraa_load_sub_shadow(_e3, k_10);
    vec3 _e6 = sraa_load_sub_albedo(_e3, k_10);
    vec3 _e9 = subcone_sraa_reconstruct_run(_e4, _e5, _e6, false, 0u, x_12, y_8, k_10);
    c_8 = _e9;
    if (SECONDARY) {
        vec4 _e12 = sraa_load_sec_sub(_e3, k_10);
        subcone_Geometry _e13 = sraa_secondary_geometry(_e12);
        bool _e15 = subcone_is_nan(_e13.depth);
        if (!(_e15)) {
            vec3 _e17 = c_8;
            uint _e18 = sraa_load_sec_sub_shadow(_e3, k_10);
            vec3 _e23 = subcone_sraa_reconstruct_run(_e13, _e18, vec3(0.0), true, SRAA_GATES, x_12, y_8, k_10);
            c_8 = (_e17 + _e23);
        }
    }
    vec3 _e25 = c_8;
    return _e25;
}

void main() {
    uvec3 id = gl_GlobalInvocationID;
    bool local = false;
    vec3 c = vec3(0.0);
    uint _e4 = _group_0_binding_0_cs.width;
    if (!((id.x >= _e4))) {
        uint _e12 = _group_0_binding_0_cs.height;
        local = (id.y >= _e12);
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    vec3 _e19 = sraa_reconstruct_subsample(id.x, id.y, 0u);
    vec3 _e23 = sraa_reconstruct_subsample(id.x, id.y, 1u);
    vec3 _e27 = sraa_reconstruct_subsample(id.x, id.y, 2u);
    vec3 _e31 = sraa_reconstruct_subsample(id.x, id.y, 3u);
    if (TONE_MAPPED_RESOLVE) {
        float _e36 = _group_0_binding_0_cs.exposure;
        vec3 _e37 = subcone_resolve_pixel_tone_mapped(_e19, _e23, _e27, _e31, _e36);
        c = _e37;
    } else {
        vec3 _e38 = subcone_resolve_pixel(_e19, _e23, _e27, _e31);
        c = _e38;
    }
    ivec2 _e41 = sraa_texel(id.x, id.y);
    vec3 _e42 = c;
    sraa_store(_e41, vec4(_e42, 1.0));
    return;
}

