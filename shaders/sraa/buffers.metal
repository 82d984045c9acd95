// language: metal2.1
#include <metal_stdlib>
#include <simd/simd.h>

using metal::uint;
struct DefaultConstructible {
    template<typename T>
    operator T() && {
        return T {};
    }
};

struct _mslBufferSizes {
    uint size1;
    uint size2;
    uint size3;
    uint size4;
};

struct subcone_SraaParams {
    float sigma_z;
    float sigma_n;
    float scale;
    uint packed;
    float sigma_s;
    uint shading;
    uint _pad0_;
    uint _pad1_;
};
struct subcone_Geometry {
    metal::packed_float3 normal;
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
    metal::packed_float3 position;
    uint width;
    metal::packed_float3 forward;
    uint height;
    metal::packed_float3 right;
    float tan_half_fov;
    metal::packed_float3 up;
    uint _pad;
    metal::float2 jitter;
    metal::uint2 _pad2_;
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
    metal::float2 offset;
};
struct subcone_WeightedSum {
    metal::float3 sum;
    metal::packed_float3 sum_c;
    float weight;
    float weight_c;
    char _pad4[12];
};
struct subcone_LayerState {
    subcone_WeightedSum acc;
    metal::packed_float3 nearest;
    float nearest_d2_;
    bool any;
    char _pad4[15];
};
struct type_8 {
    subcone_LayerState inner[9];
};
struct subcone_LayerStates {
    type_8 at;
};
struct type_10 {
    metal::float3 inner[4];
};
struct subcone_Subsamples4_ {
    type_10 at;
};
struct SraaFrame {
    subcone_SraaParams sraa;
    metal::float4 projection;
    uint width;
    uint height;
    float depth_miss;
    float albedo_tolerance;
    uint origin_x;
    uint origin_y;
    float exposure;
    uint _pad;
};
typedef subcone_Geometry type_12[1];
typedef metal::float4 type_13[1];
constant float subcone_NEGLIGIBLE_WEIGHT = 0.00000000000000000005421011;
constant float subcone_NORMAL_COS_SNAP = 0.00000047683716;
constant uint subcone_SHADED_SUBSAMPLE = 0u;
constant uint subcone_SHADED_SAMPLE = 4u;
constant float subcone_ALBEDO_TOLERANCE = 0.1;
constant metal::float3 subcone_RESOLVE_LUMA = metal::float3(0.2126, 0.7152, 0.0722);
constant uint LIGHTS = 0u;
constant bool MATERIAL = false;
constant bool HARDWARE_DEPTH = false;
constant bool UNSIGNED_NORMALS = false;
constant bool SHADED_GIVEN = true;
constant bool DECODED = true;
constant bool SECONDARY = false;
constant bool TONE_MAPPED_RESOLVE = false;
constant uint SRAA_LAYERS = 1u;
constant uint SRAA_GATES = 1u;
constant bool SRAA_MATERIAL = false;

float subcone_inf(
) {
    return as_type<float>(2139095040u);
}

bool subcone_is_nan(
    float x
) {
    return (as_type<uint>(x) & 2147483647u) > 2139095040u;
}

bool subcone_is_finite(
    float x_1
) {
    return (as_type<uint>(x_1) & 2147483647u) < 2139095040u;
}

metal::float3 subcone_pinhole_dir(
    subcone_PinholeCamera c_1,
    metal::float2 p_in
) {
    metal::float2 p_20 = p_in + c_1.jitter;
    float w_4 = static_cast<float>(metal::max(c_1.width, 1u));
    float h = static_cast<float>(metal::max(c_1.height, 1u));
    float u = ((((2.0 * p_20.x) / w_4) - 1.0) * c_1.tan_half_fov) * (w_4 / h);
    float v_3 = (1.0 - ((2.0 * p_20.y) / h)) * c_1.tan_half_fov;
    metal::float3 d_1 = (c_1.forward + (u * c_1.right)) + (v_3 * c_1.up);
    return d_1 * (1.0 / metal::length(d_1));
}

bool subcone_sraa_is_finite3_(
    metal::float3 c_2
) {
    bool local_1 = {};
    bool local_2 = {};
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

bool subcone_sraa_any_nan3_(
    metal::float3 c_3
) {
    bool local_3 = {};
    bool local_4 = {};
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

metal::float2 subcone_subpixel_offset(
    uint k
) {
    switch(k) {
        case 1u: {
            return metal::float2(0.375, -0.125);
        }
        case 2u: {
            return metal::float2(-0.375, 0.125);
        }
        case 3u: {
            return metal::float2(0.125, 0.375);
        }
        default: {
            return metal::float2(-0.125, -0.375);
        }
    }
}

uint subcone_sraa_form(
    subcone_SraaParams p
) {
    if ((p.packed & 255u) == 1u) {
        return 1u;
    }
    return 0u;
}

uint subcone_sraa_depth_metric(
    subcone_SraaParams p_1
) {
    if (((p_1.packed >> 8u) & 255u) == 1u) {
        return 1u;
    }
    return 0u;
}

uint subcone_sraa_radius(
    subcone_SraaParams p_2
) {
    return p_2.packed >> 16u;
}

metal::float2 subcone_sraa_shaded_offset(
    subcone_SraaParams p_3
) {
    if (p_3.shading == 1u) {
        return metal::float2(0.0);
    }
    metal::float2 _e7 = subcone_subpixel_offset(subcone_SHADED_SUBSAMPLE);
    return _e7;
}

bool subcone_sraa_is_shaded_subsample(
    subcone_SraaParams p_4,
    uint k_1
) {
    bool local_5 = {};
    if (p_4.shading != 1u) {
        local_5 = k_1 == subcone_SHADED_SUBSAMPLE;
    } else {
        local_5 = false;
    }
    bool _e10 = local_5;
    return _e10;
}

float subcone_gaussian(
    float x_2
) {
    float e = metal::exp(-((x_2 * x_2)));
    bool _e4 = subcone_is_nan(e);
    if (_e4) {
        return 0.0;
    }
    return e;
}

float subcone_gaussian_sum(
    float s
) {
    bool local_6 = {};
    if (s == 0.0) {
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
    float e_1 = metal::exp(-(s));
    bool _e16 = subcone_is_nan(e_1);
    if (_e16) {
        return 0.0;
    }
    return e_1;
}

float subcone_saturate(
    float x_3
) {
    if (x_3 > 0.0) {
        if (x_3 < 1.0) {
            return x_3;
        }
        return 1.0;
    }
    return 0.0;
}

float subcone_depth_difference(
    float zi,
    float zj,
    uint metric
) {
    bool local_7 = {};
    float r = {};
    if (zi == zj) {
        bool _e6 = subcone_is_nan(zi);
        local_7 = !(_e6);
    } else {
        local_7 = false;
    }
    bool _e9 = local_7;
    if (_e9) {
        return 0.0;
    }
    float diff = metal::abs(zj - zi);
    r = diff;
    if (metric != 1u) {
        float m = metal::max(metal::abs(zi), metal::abs(zj));
        if (m > 1267650600000000000000000000000.0) {
            r = (diff / m) / (0.5 + (0.5 * (metal::min(metal::abs(zi), metal::abs(zj)) / m)));
        } else {
            float mean = (0.5 * metal::abs(zi)) + (0.5 * metal::abs(zj));
            if (mean == 0.0) {
                float _e40 = subcone_inf();
                return _e40;
            }
            r = diff / mean;
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

float subcone_reconstruction_weight(
    subcone_SraaParams params,
    subcone_Geometry gi,
    subcone_Geometry gj,
    float distance2_
) {
    float spatial = 0.0;
    bool local_8 = {};
    float dn = {};
    bool local_9 = {};
    bool local_10 = {};
    float w = 0.0;
    bool local_11 = {};
    if (params.sigma_s > 0.0) {
        local_8 = distance2_ != 0.0;
    } else {
        local_8 = false;
    }
    bool _e14 = local_8;
    if (_e14) {
        spatial = distance2_ / (params.sigma_s * params.sigma_s);
    }
    uint _e21 = subcone_sraa_depth_metric(params);
    float _e22 = subcone_depth_difference(gi.depth, gj.depth, _e21);
    float _e26 = subcone_saturate(metal::dot(gj.normal, gi.normal));
    dn = 1.0 - _e26;
    if (_e26 >= 0.9999995) {
        dn = 0.0;
    }
    float _e33 = subcone_inf();
    if (gi.depth == _e33) {
        local_9 = gj.depth == _e33;
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
    if (_e55 == 0u) {
        float a_2 = params.sigma_z * _e22;
        float _e61 = dn;
        float b_2 = params.sigma_n * _e61;
        float _e66 = spatial;
        float _e68 = subcone_gaussian_sum(((a_2 * a_2) + (b_2 * b_2)) + _e66);
        w = _e68;
    } else {
        float _e70 = dn;
        float x_13 = params.scale * metal::max(_e70, params.sigma_z * _e22);
        bool _e75 = subcone_is_nan(x_13);
        if (!(_e75)) {
            local_11 = x_13 == _e33;
        } else {
            local_11 = true;
        }
        bool _e81 = local_11;
        if (_e81) {
            w = 0.0;
        } else {
            w = metal::exp(-(x_13));
            float _e85 = w;
            bool _e86 = subcone_is_nan(_e85);
            if (_e86) {
                w = 0.0;
            }
        }
        float _e88 = spatial;
        if (_e88 != 0.0) {
            float _e91 = w;
            float _e92 = spatial;
            float _e93 = subcone_gaussian_sum(_e92);
            w = _e91 * _e93;
        }
    }
    float _e95 = w;
    float _e96 = subcone_saturate(_e95);
    return _e96;
}

float subcone_bilateral_weight(
    subcone_SraaParams params_1,
    subcone_Geometry gi_1,
    subcone_Geometry gj_1
) {
    float _e4 = subcone_reconstruction_weight(params_1, gi_1, gj_1, 0.0);
    return _e4;
}

float subcone_shadow_gated_weight(
    subcone_SraaParams params_2,
    subcone_Geometry gi_2,
    subcone_Geometry gj_2,
    bool si,
    bool sj
) {
    if (si != sj) {
        return 0.0;
    }
    float _e7 = subcone_bilateral_weight(params_2, gi_2, gj_2);
    return _e7;
}

float subcone_albedo_difference(
    metal::float3 a,
    metal::float3 b
) {
    bool local_12 = {};
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
    metal::float3 d_2 = metal::abs(metal::sqrt(metal::max(a, metal::float3(0.0))) - metal::sqrt(metal::max(b, metal::float3(0.0))));
    return metal::max(d_2.x, metal::max(d_2.y, d_2.z));
}

bool subcone_material_gate(
    metal::float3 ai,
    metal::float3 aj,
    float tolerance
) {
    bool local_13 = {};
    float _e3 = subcone_albedo_difference(ai, aj);
    if (_e3 <= tolerance) {
        float _e7 = subcone_inf();
        local_13 = _e3 < _e7;
    } else {
        local_13 = false;
    }
    bool _e10 = local_13;
    return _e10;
}

float subcone_material_gated_weight(
    subcone_SraaParams params_3,
    subcone_Geometry gi_3,
    subcone_Geometry gj_3,
    metal::float3 ai_1,
    metal::float3 aj_1,
    float tolerance_1
) {
    bool _e6 = subcone_material_gate(ai_1, aj_1, tolerance_1);
    if (_e6) {
        float _e7 = subcone_bilateral_weight(params_3, gi_3, gj_3);
        return _e7;
    }
    return 0.0;
}

uint subcone_sraa_saturating_add(
    uint a_1,
    uint b_1
) {
    uint s_2 = a_1 + b_1;
    if (s_2 < a_1) {
        return 4294967295u;
    }
    return s_2;
}

subcone_Neighbourhood subcone_neighbourhood(
    uint x_4,
    uint y,
    uint sub,
    metal::float2 shaded,
    uint radius,
    uint width,
    uint height
) {
    metal::float2 pos = {};
    subcone_Neighbourhood n = {};
    pos = shaded;
    if (sub < 4u) {
        metal::float2 _e10 = subcone_subpixel_offset(sub);
        pos = _e10;
    }
    metal::float2 _e13 = pos;
    n.offset = _e13 - shaded;
    n.x0_ = (x_4 >= radius) ? (x_4 - radius) : 0u;
    n.y0_ = (y >= radius) ? (y - radius) : 0u;
    uint _e26 = subcone_sraa_saturating_add(x_4, radius);
    uint _e28 = subcone_sraa_saturating_add(_e26, 1u);
    n.x1_ = metal::min(_e28, width);
    uint _e31 = subcone_sraa_saturating_add(y, radius);
    uint _e33 = subcone_sraa_saturating_add(_e31, 1u);
    n.y1_ = metal::min(_e33, height);
    subcone_Neighbourhood _e35 = n;
    return _e35;
}

float subcone_neighbour_distance2_(
    subcone_Neighbourhood n_1,
    uint x_5,
    uint y_1,
    uint px,
    uint py
) {
    metal::float2 d_3 = metal::float2(static_cast<float>(px) - static_cast<float>(x_5), static_cast<float>(py) - static_cast<float>(y_1)) - n_1.offset;
    return (d_3.x * d_3.x) + (d_3.y * d_3.y);
}

subcone_WeightedSum subcone_weighted_sum_zero(
) {
    return subcone_WeightedSum {metal::float3(0.0), metal::float3(0.0), 0.0, 0.0};
}

void subcone_weighted_sum_add(
    thread subcone_WeightedSum& acc,
    float w_1,
    metal::float3 c_4
) {
    metal::float3 _e5 = acc.sum_c;
    metal::float3 y_9 = (w_1 * c_4) - _e5;
    metal::float3 _e8 = acc.sum;
    metal::float3 t = _e8 + y_9;
    metal::float3 _e12 = acc.sum;
    acc.sum_c = (t - _e12) - y_9;
    acc.sum = t;
    float _e17 = acc.weight_c;
    float yw = w_1 - _e17;
    float _e20 = acc.weight;
    float tw = _e20 + yw;
    float _e24 = acc.weight;
    acc.weight_c = (tw - _e24) - yw;
    acc.weight = tw;
    return;
}

metal::float4 subcone_weighted_sum_mean(
    subcone_WeightedSum acc_1
) {
    if (!((acc_1.weight >= subcone_NEGLIGIBLE_WEIGHT))) {
        return metal::float4(0.0);
    }
    float inv = 1.0 / acc_1.weight;
    metal::float3 c_9 = acc_1.sum * inv;
    bool _e12 = subcone_sraa_is_finite3_(c_9);
    if (!(_e12)) {
        return metal::float4(0.0);
    }
    return metal::float4(c_9, 1.0);
}

subcone_LayerState subcone_reconstruct_layers_begin(
) {
    subcone_WeightedSum _e0 = subcone_weighted_sum_zero();
    float _e3 = subcone_inf();
    return subcone_LayerState {_e0, metal::float3(0.0), _e3, false};
}

void subcone_reconstruct_layers_add(
    thread subcone_LayerState& state,
    float w_2,
    bool gated,
    uint bit,
    uint target_shadow,
    uint shadow,
    float distance2_1,
    metal::float3 c_5
) {
    float d2_ = {};
    bool local_14 = {};
    float wi = {};
    bool local_15 = {};
    bool local_16 = {};
    subcone_WeightedSum acc_2 = {};
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
    bool _e15 = state.any;
    if (!(!(_e15))) {
        float _e20 = d2_;
        float _e22 = state.nearest_d2_;
        local_14 = _e20 < _e22;
    } else {
        local_14 = true;
    }
    bool _e25 = local_14;
    if (_e25) {
        state.nearest = c_5;
        float _e28 = d2_;
        state.nearest_d2_ = _e28;
        state.any = true;
    }
    wi = w_2;
    if (gated) {
        local_15 = bit < 32u;
    } else {
        local_15 = false;
    }
    bool _e37 = local_15;
    if (_e37) {
        local_16 = (((target_shadow ^ shadow) >> bit) & 1u) != 0u;
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

metal::float3 subcone_reconstruct_layers_end(
    subcone_LayerState state_1
) {
    metal::float4 _e2 = subcone_weighted_sum_mean(state_1.acc);
    if (_e2.w > 0.0) {
        return _e2.xyz;
    }
    return state_1.nearest;
}

metal::float3 subcone_resolve_pixel(
    metal::float3 s0_,
    metal::float3 s1_,
    metal::float3 s2_,
    metal::float3 s3_
) {
    metal::float3 s_1 = metal::float3(0.0);
    bool _e4 = subcone_sraa_is_finite3_(s0_);
    bool _e5 = subcone_sraa_is_finite3_(s1_);
    bool _e6 = subcone_sraa_is_finite3_(s2_);
    bool _e7 = subcone_sraa_is_finite3_(s3_);
    uint n_3 = ((static_cast<uint>(_e4) + static_cast<uint>(_e5)) + static_cast<uint>(_e6)) + static_cast<uint>(_e7);
    if (n_3 == 0u) {
        return metal::float3(0.0);
    }
    float inv_1 = 1.0 / static_cast<float>(n_3);
    if (_e4) {
        metal::float3 _e25 = s_1;
        s_1 = _e25 + (s0_ * inv_1);
    }
    if (_e5) {
        metal::float3 _e28 = s_1;
        s_1 = _e28 + (s1_ * inv_1);
    }
    if (_e6) {
        metal::float3 _e31 = s_1;
        s_1 = _e31 + (s2_ * inv_1);
    }
    if (_e7) {
        metal::float3 _e34 = s_1;
        s_1 = _e34 + (s3_ * inv_1);
    }
    metal::float3 _e37 = s_1;
    return _e37;
}

float subcone_tone_map_weight(
    metal::float3 c_6,
    float exposure
) {
    bool local_17 = {};
    float luma = {};
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
    luma = metal::dot(c_6, subcone_RESOLVE_LUMA) * exposure;
    float _e16 = luma;
    if (!((_e16 > 0.0))) {
        luma = 0.0;
    }
    float _e21 = luma;
    return 1.0 / (1.0 + _e21);
}

metal::float3 subcone_resolve_pixel_tone_mapped(
    metal::float3 s0_1,
    metal::float3 s1_1,
    metal::float3 s2_1,
    metal::float3 s3_1,
    float exposure_1
) {
    bool local_18 = {};
    metal::float3 sum = metal::float3(0.0);
    float weight = 0.0;
    subcone_Subsamples4_ subs = {};
    uint k_2 = 0u;
    if (!(!((exposure_1 > 0.0)))) {
        bool _e11 = subcone_is_finite(exposure_1);
        local_18 = !(_e11);
    } else {
        local_18 = true;
    }
    bool _e14 = local_18;
    if (_e14) {
        metal::float3 _e15 = subcone_resolve_pixel(s0_1, s1_1, s2_1, s3_1);
        return _e15;
    }
    subs = subcone_Subsamples4_ {type_10 {{s0_1, s1_1, s2_1, s3_1}}};
    uint2 loop_bound = uint2(4294967295u);
    bool loop_init = true;
    while(true) {
        if (metal::all(loop_bound == uint2(0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        if (!loop_init) {
            uint _e41 = k_2;
            k_2 = _e41 + 1u;
        }
        loop_init = false;
        uint _e26 = k_2;
        if (_e26 < 4u) {
        } else {
            break;
        }
        {
            uint _e30 = k_2;
            metal::float3 c_10 = uint(_e30) < 4 ? subs.at.inner[_e30] : DefaultConstructible();
            bool _e33 = subcone_sraa_is_finite3_(c_10);
            if (_e33) {
                float _e34 = subcone_tone_map_weight(c_10, exposure_1);
                metal::float3 _e35 = sum;
                sum = _e35 + (_e34 * c_10);
                float _e38 = weight;
                weight = _e38 + _e34;
            }
        }
    }
    float _e43 = weight;
    if (_e43 > 0.0) {
        metal::float3 _e46 = sum;
        float _e47 = weight;
        metal::float3 m_1 = _e46 / metal::float3(_e47);
        bool _e50 = subcone_sraa_is_finite3_(m_1);
        if (_e50) {
            return m_1;
        }
    }
    metal::float3 _e51 = subcone_resolve_pixel(s0_1, s1_1, s2_1, s3_1);
    return _e51;
}

uint sraa_pixel(
    metal::int2 p_5,
    constant SraaFrame& frame
) {
    uint _e5 = frame.width;
    return (static_cast<uint>(p_5.y) * _e5) + static_cast<uint>(p_5.x);
}

metal::float4 sraa_load_sub(
    metal::int2 p_6,
    uint k_3,
    constant SraaFrame& frame,
    device type_12 const& sub_geo,
    constant _mslBufferSizes& _buffer_sizes
) {
    uint _e3 = sraa_pixel(p_6, frame);
    uint _e6 = (_e3 * 4u) + k_3;
    subcone_Geometry g = uint(_e6) < 1 + (_buffer_sizes.size1 - 0 - 16) / 16 ? sub_geo[_e6] : DefaultConstructible();
    return metal::float4(g.normal, g.depth);
}

metal::float4 sraa_load_shaded(
    metal::int2 p_7,
    constant SraaFrame& frame,
    device type_12 const& shaded_geo,
    constant _mslBufferSizes& _buffer_sizes
) {
    uint _e2 = sraa_pixel(p_7, frame);
    subcone_Geometry g_1 = uint(_e2) < 1 + (_buffer_sizes.size2 - 0 - 16) / 16 ? shaded_geo[_e2] : DefaultConstructible();
    return metal::float4(g_1.normal, g_1.depth);
}

metal::float3 sraa_load_color(
    metal::int2 p_8,
    uint l,
    constant SraaFrame& frame,
    device type_13 const& color,
    constant _mslBufferSizes& _buffer_sizes
) {
    uint _e3 = sraa_pixel(p_8, frame);
    uint _e6 = (_e3 * SRAA_LAYERS) + l;
    metal::float4 _e8 = uint(_e6) < 1 + (_buffer_sizes.size3 - 0 - 16) / 16 ? color[_e6] : DefaultConstructible();
    return _e8.xyz;
}

void sraa_store(
    metal::int2 p_9,
    metal::float4 c_7,
    constant SraaFrame& frame,
    device type_13& sraa_output,
    constant _mslBufferSizes& _buffer_sizes
) {
    uint _e3 = sraa_pixel(p_9, frame);
    if (uint(_e3) < 1 + (_buffer_sizes.size4 - 0 - 16) / 16) {
        sraa_output[_e3] = c_7;
    }
    return;
}

uint sraa_load_shaded_shadow(
    metal::int2 p_10
) {
    return 0u;
}

uint sraa_load_sub_shadow(
    metal::int2 p_11,
    uint k_4
) {
    return 0u;
}

uint sraa_load_sec_shaded_shadow(
    metal::int2 p_12
) {
    return 0u;
}

uint sraa_load_sec_sub_shadow(
    metal::int2 p_13,
    uint k_5
) {
    return 0u;
}

metal::float4 sraa_load_sec_shaded(
    metal::int2 p_14
) {
    return metal::float4(0.0);
}

metal::float4 sraa_load_sec_sub(
    metal::int2 p_15,
    uint k_6
) {
    return metal::float4(0.0);
}

metal::float3 sraa_load_shaded_albedo(
    metal::int2 p_16
) {
    return metal::float3(0.0);
}

metal::float3 sraa_load_sub_albedo(
    metal::int2 p_17,
    uint k_7
) {
    return metal::float3(0.0);
}

metal::int2 sraa_texel(
    uint x_6,
    uint y_2,
    constant SraaFrame& frame
) {
    uint _e4 = frame.origin_x;
    uint _e9 = frame.origin_y;
    return metal::int2(static_cast<int>(x_6 + _e4), static_cast<int>(y_2 + _e9));
}

float sraa_decode_depth(
    float d,
    constant SraaFrame& frame
) {
    float z = {};
    bool local_19 = {};
    z = d;
    if (HARDWARE_DEPTH) {
        float _e5 = frame.depth_miss;
        if (d == _e5) {
            float _e7 = subcone_inf();
            return _e7;
        }
        metal::float4 m_2 = frame.projection;
        z = metal::abs((m_2.y - (d * m_2.w)) / ((d * m_2.z) - m_2.x));
    }
    float _e21 = z;
    bool _e22 = subcone_is_finite(_e21);
    if (_e22) {
        float _e25 = z;
        local_19 = _e25 > 0.0;
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

metal::float3 sraa_decode_normal(
    metal::float3 v
) {
    metal::float3 n_2 = {};
    bool local_20 = {};
    n_2 = v;
    if (UNSIGNED_NORMALS) {
        n_2 = (v * 2.0) - metal::float3(1.0);
    }
    metal::float3 _e8 = n_2;
    metal::float3 _e9 = n_2;
    float l2_ = metal::dot(_e8, _e9);
    if (l2_ > 0.0) {
        bool _e15 = subcone_is_finite(l2_);
        local_20 = _e15;
    } else {
        local_20 = false;
    }
    bool _e17 = local_20;
    if (_e17) {
        metal::float3 _e18 = n_2;
        return _e18 * (1.0 / metal::sqrt(l2_));
    }
    return metal::float3(0.0);
}

subcone_Geometry sraa_geometry(
    metal::float4 v_1,
    constant SraaFrame& frame
) {
    if (DECODED) {
        return subcone_Geometry {v_1.xyz, v_1.w};
    }
    float _e6 = sraa_decode_depth(v_1.w, frame);
    float _e7 = subcone_inf();
    if (_e6 == _e7) {
        return subcone_Geometry {metal::float3(0.0), _e6};
    }
    metal::float3 _e13 = sraa_decode_normal(v_1.xyz);
    return subcone_Geometry {_e13, _e6};
}

subcone_Geometry sraa_sub_geo(
    metal::int2 p_18,
    uint k_8,
    constant SraaFrame& frame,
    device type_12 const& sub_geo,
    constant _mslBufferSizes& _buffer_sizes
) {
    metal::float4 _e2 = sraa_load_sub(p_18, k_8, frame, sub_geo, _buffer_sizes);
    subcone_Geometry _e3 = sraa_geometry(_e2, frame);
    return _e3;
}

subcone_Geometry sraa_shaded_geo(
    metal::int2 p_19,
    constant SraaFrame& frame,
    device type_12 const& sub_geo,
    device type_12 const& shaded_geo,
    constant _mslBufferSizes& _buffer_sizes
) {
    if (SHADED_GIVEN) {
        metal::float4 _e2 = sraa_load_shaded(p_19, frame, shaded_geo, _buffer_sizes);
        subcone_Geometry _e3 = sraa_geometry(_e2, frame);
        return _e3;
    }
    subcone_Geometry _e5 = sraa_sub_geo(p_19, subcone_SHADED_SUBSAMPLE, frame, sub_geo, _buffer_sizes);
    return _e5;
}

subcone_Geometry sraa_secondary_geometry(
    metal::float4 v_2
) {
    bool local_21 = {};
    bool local_22 = {};
    if (DECODED) {
        return subcone_Geometry {v_2.xyz, v_2.w};
    }
    bool _e6 = subcone_is_nan(v_2.w);
    if (!(_e6)) {
        local_21 = v_2.w < 0.0;
    } else {
        local_21 = true;
    }
    bool _e14 = local_21;
    if (_e14) {
        return subcone_Geometry {metal::float3(0.0), as_type<float>(2143289344u)};
    }
    if (!((v_2.w == 0.0))) {
        float _e27 = subcone_inf();
        local_22 = v_2.w == _e27;
    } else {
        local_22 = true;
    }
    bool _e30 = local_22;
    if (_e30) {
        float _e33 = subcone_inf();
        return subcone_Geometry {metal::float3(0.0), _e33};
    }
    metal::float3 _e36 = sraa_decode_normal(v_2.xyz);
    return subcone_Geometry {_e36, v_2.w};
}

subcone_SraaParams sraa_params(
    constant SraaFrame& frame
) {
    subcone_SraaParams _e2 = frame.sraa;
    return _e2;
}

metal::uint2 sraa_size(
    constant SraaFrame& frame
) {
    uint _e2 = frame.width;
    uint _e5 = frame.height;
    return metal::uint2(_e2, _e5);
}

float sraa_albedo_tolerance(
    constant SraaFrame& frame
) {
    float _e2 = frame.albedo_tolerance;
    return _e2;
}

subcone_Geometry sraa_shaded_geometry(
    uint x_7,
    uint y_3,
    bool secondary,
    constant SraaFrame& frame,
    device type_12 const& sub_geo,
    device type_12 const& shaded_geo,
    constant _mslBufferSizes& _buffer_sizes
) {
    metal::int2 _e3 = sraa_texel(x_7, y_3, frame);
    if (secondary) {
        metal::float4 _e4 = sraa_load_sec_shaded(_e3);
        subcone_Geometry _e5 = sraa_secondary_geometry(_e4);
        return _e5;
    }
    subcone_Geometry _e6 = sraa_shaded_geo(_e3, frame, sub_geo, shaded_geo, _buffer_sizes);
    return _e6;
}

uint sraa_shaded_shadow(
    uint x_8,
    uint y_4,
    bool secondary_1,
    constant SraaFrame& frame
) {
    metal::int2 _e3 = sraa_texel(x_8, y_4, frame);
    if (secondary_1) {
        uint _e4 = sraa_load_sec_shaded_shadow(_e3);
        return _e4;
    }
    uint _e5 = sraa_load_shaded_shadow(_e3);
    return _e5;
}

metal::float3 sraa_shaded_albedo(
    uint x_9,
    uint y_5,
    constant SraaFrame& frame
) {
    metal::int2 _e2 = sraa_texel(x_9, y_5, frame);
    metal::float3 _e3 = sraa_load_shaded_albedo(_e2);
    return _e3;
}

metal::float3 sraa_shaded_value(
    uint x_10,
    uint y_6,
    uint layer,
    constant SraaFrame& frame,
    device type_13 const& color,
    constant _mslBufferSizes& _buffer_sizes
) {
    metal::int2 _e3 = sraa_texel(x_10, y_6, frame);
    metal::float3 _e4 = sraa_load_color(_e3, layer, frame, color, _buffer_sizes);
    return _e4;
}

metal::float3 subcone_sraa_reconstruct_run(
    subcone_Geometry tgt,
    uint target_shadow_1,
    metal::float3 ta,
    bool secondary_2,
    uint first,
    uint x_11,
    uint y_7,
    uint k_9,
    constant SraaFrame& frame,
    device type_12 const& sub_geo,
    device type_12 const& shaded_geo,
    device type_13 const& color,
    constant _mslBufferSizes& _buffer_sizes
) {
    subcone_LayerStates st = {};
    uint i = 0u;
    uint py_1 = {};
    uint px_1 = {};
    float w_3 = {};
    bool local_23 = {};
    bool local_24 = {};
    uint i_1 = {};
    subcone_LayerState layer_1 = {};
    metal::float3 sum_1 = metal::float3(0.0);
    uint i_2 = 0u;
    subcone_SraaParams _e8 = sraa_params(frame);
    metal::uint2 _e9 = sraa_size(frame);
    uint2 loop_bound_1 = uint2(4294967295u);
    bool loop_init_1 = true;
    while(true) {
        if (metal::all(loop_bound_1 == uint2(0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init_1) {
            uint _e21 = i;
            i = _e21 + 1u;
        }
        loop_init_1 = false;
        uint _e13 = i;
        if (_e13 < SRAA_GATES) {
        } else {
            break;
        }
        {
            uint _e17 = i;
            subcone_LayerState _e19 = subcone_reconstruct_layers_begin();
            if (uint(_e17) < 9) {
                st.at.inner[_e17] = _e19;
            }
        }
    }
    metal::float2 _e23 = subcone_sraa_shaded_offset(_e8);
    uint _e24 = subcone_sraa_radius(_e8);
    subcone_Neighbourhood _e27 = subcone_neighbourhood(x_11, y_7, k_9, _e23, _e24, _e9.x, _e9.y);
    py_1 = _e27.y0_;
    uint2 loop_bound_2 = uint2(4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (metal::all(loop_bound_2 == uint2(0u))) { break; }
        loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
        if (!loop_init_2) {
            uint _e100 = py_1;
            py_1 = _e100 + 1u;
        }
        loop_init_2 = false;
        uint _e30 = py_1;
        if (_e30 < _e27.y1_) {
        } else {
            break;
        }
        {
            px_1 = _e27.x0_;
            uint2 loop_bound_3 = uint2(4294967295u);
            bool loop_init_3 = true;
            while(true) {
                if (metal::all(loop_bound_3 == uint2(0u))) { break; }
                loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
                if (!loop_init_3) {
                    uint _e97 = px_1;
                    px_1 = _e97 + 1u;
                }
                loop_init_3 = false;
                uint _e35 = px_1;
                if (_e35 < _e27.x1_) {
                } else {
                    break;
                }
                {
                    uint _e38 = px_1;
                    uint _e39 = py_1;
                    float _e40 = subcone_neighbour_distance2_(_e27, x_11, y_7, _e38, _e39);
                    uint _e41 = px_1;
                    uint _e42 = py_1;
                    subcone_Geometry _e43 = sraa_shaded_geometry(_e41, _e42, secondary_2, frame, sub_geo, shaded_geo, _buffer_sizes);
                    uint _e44 = px_1;
                    uint _e45 = py_1;
                    uint _e46 = sraa_shaded_shadow(_e44, _e45, secondary_2, frame);
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
                        metal::float3 _e61 = sraa_shaded_albedo(_e59, _e60, frame);
                        float _e62 = sraa_albedo_tolerance(frame);
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
                    uint2 loop_bound_4 = uint2(4294967295u);
                    bool loop_init_4 = true;
                    while(true) {
                        if (metal::all(loop_bound_4 == uint2(0u))) { break; }
                        loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
                        if (!loop_init_4) {
                            uint _e94 = i_1;
                            i_1 = _e94 + 1u;
                        }
                        loop_init_4 = false;
                        uint _e69 = i_1;
                        if (_e69 < SRAA_GATES) {
                        } else {
                            break;
                        }
                        {
                            uint _e73 = i_1;
                            subcone_LayerState _e75 = uint(_e73) < 9 ? st.at.inner[_e73] : DefaultConstructible();
                            layer_1 = _e75;
                            float _e77 = w_3;
                            uint _e78 = i_1;
                            uint _e81 = i_1;
                            uint _e84 = px_1;
                            uint _e85 = py_1;
                            uint _e86 = i_1;
                            metal::float3 _e88 = sraa_shaded_value(_e84, _e85, first + _e86, frame, color, _buffer_sizes);
                            subcone_reconstruct_layers_add(layer_1, _e77, _e78 > 0u, _e81 - 1u, target_shadow_1, _e46, _e40, _e88);
                            uint _e90 = i_1;
                            subcone_LayerState _e92 = layer_1;
                            if (uint(_e90) < 9) {
                                st.at.inner[_e90] = _e92;
                            }
                        }
                    }
                }
            }
        }
    }
    uint2 loop_bound_5 = uint2(4294967295u);
    bool loop_init_5 = true;
    while(true) {
        if (metal::all(loop_bound_5 == uint2(0u))) { break; }
        loop_bound_5 -= uint2(loop_bound_5.y == 0u, 1u);
        if (!loop_init_5) {
            uint _e118 = i_2;
            i_2 = _e118 + 1u;
        }
        loop_init_5 = false;
        uint _e107 = i_2;
        if (_e107 < SRAA_GATES) {
        } else {
            break;
        }
        {
            metal::float3 _e110 = sum_1;
            uint _e112 = i_2;
            subcone_LayerState _e114 = uint(_e112) < 9 ? st.at.inner[_e112] : DefaultConstructible();
            metal::float3 _e115 = subcone_reconstruct_layers_end(_e114);
            sum_1 = _e110 + _e115;
        }
    }
    metal::float3 _e120 = sum_1;
    return _e120;
}

metal::float3 sraa_reconstruct_subsample(
    uint x_12,
    uint y_8,
    uint k_10,
    constant SraaFrame& frame,
    device type_12 const& sub_geo,
    device type_12 const& shaded_geo,
    device type_13 const& color,
    constant _mslBufferSizes& _buffer_sizes
) {
    metal::float3 c_8 = {};
    metal::int2 _e3 = sraa_texel(x_12, y_8, frame);
    subcone_Geometry _e4 = sraa_sub_geo(_e3, k_10, frame, sub_geo, _buffer_sizes);
    uint _e5 = sraa_load_sub_shadow(_e3, k_10);
    metal::float3 _e6 = sraa_load_sub_albedo(_e3, k_10);
    metal::float3 _e9 = subcone_sraa_reconstruct_run(_e4, _e5, _e6, false, 0u, x_12, y_8, k_10, frame, sub_geo, shaded_geo, color, _buffer_sizes);
    c_8 = _e9;
    if (SECONDARY) {
        metal::float4 _e12 = sraa_load_sec_sub(_e3, k_10);
        subcone_Geometry _e13 = sraa_secondary_geometry(_e12);
        bool _e15 = subcone_is_nan(_e13.depth);
        if (!(_e15)) {
            metal::float3 _e17 = c_8;
            uint _e18 = sraa_load_sec_sub_shadow(_e3, k_10);
            metal::float3 _e23 = subcone_sraa_reconstruct_run(_e13, _e18, metal::float3(0.0), true, SRAA_GATES, x_12, y_8, k_10, frame, sub_geo, shaded_geo, color, _buffer_sizes);
            c_8 = _e17 + _e23;
        }
    }
    metal::float3 _e25 = c_8;
    return _e25;
}

struct sraa_resolve_mainInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sraa_resolve_main(
  metal::uint3 id [[thread_position_in_grid]]
, constant SraaFrame& frame [[buffer(0)]]
, device type_12 const& sub_geo [[buffer(2)]]
, device type_12 const& shaded_geo [[buffer(1)]]
, device type_13 const& color [[buffer(3)]]
, device type_13& sraa_output [[buffer(4)]]
, constant _mslBufferSizes& _buffer_sizes [[buffer(5)]]
) {
    bool local = {};
    metal::float3 c = {};
    uint _e4 = frame.width;
    if (!((id.x >= _e4))) {
        uint _e12 = frame.height;
        local = id.y >= _e12;
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    metal::float3 _e19 = sraa_reconstruct_subsample(id.x, id.y, 0u, frame, sub_geo, shaded_geo, color, _buffer_sizes);
    metal::float3 _e23 = sraa_reconstruct_subsample(id.x, id.y, 1u, frame, sub_geo, shaded_geo, color, _buffer_sizes);
    metal::float3 _e27 = sraa_reconstruct_subsample(id.x, id.y, 2u, frame, sub_geo, shaded_geo, color, _buffer_sizes);
    metal::float3 _e31 = sraa_reconstruct_subsample(id.x, id.y, 3u, frame, sub_geo, shaded_geo, color, _buffer_sizes);
    if (TONE_MAPPED_RESOLVE) {
        float _e36 = frame.exposure;
        metal::float3 _e37 = subcone_resolve_pixel_tone_mapped(_e19, _e23, _e27, _e31, _e36);
        c = _e37;
    } else {
        metal::float3 _e38 = subcone_resolve_pixel(_e19, _e23, _e27, _e31);
        c = _e38;
    }
    metal::int2 _e41 = sraa_texel(id.x, id.y, frame);
    metal::float3 _e42 = c;
    sraa_store(_e41, metal::float4(_e42, 1.0), frame, sraa_output, _buffer_sizes);
    return;
}
