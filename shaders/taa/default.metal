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
struct TaaOrigin {
    uint x;
    uint y;
    uint _pad0_;
    uint _pad1_;
};
constant float subcone_NEGLIGIBLE_WEIGHT = 0.00000000000000000005421011;
constant metal::float3 subcone_TAA_LUMA = metal::float3(0.2126, 0.7152, 0.0722);

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
    subcone_PinholeCamera c,
    metal::float2 p_in
) {
    metal::float2 p_5 = p_in + c.jitter;
    float w = static_cast<float>(metal::max(c.width, 1u));
    float h_1 = static_cast<float>(metal::max(c.height, 1u));
    float u = ((((2.0 * p_5.x) / w) - 1.0) * c.tan_half_fov) * (w / h_1);
    float v_1 = (1.0 - ((2.0 * p_5.y) / h_1)) * c.tan_half_fov;
    metal::float3 d = (c.forward + (u * c.right)) + (v_1 * c.up);
    return d * (1.0 / metal::length(d));
}

uint naga_mod(uint lhs, uint rhs) {
    return lhs % metal::select(rhs, 1u, rhs == 0u);
}

uint naga_div(uint lhs, uint rhs) {
    return lhs / metal::select(rhs, 1u, rhs == 0u);
}

float subcone_taa_halton(
    uint index_in,
    uint base
) {
    uint index = {};
    float f = 1.0;
    float r = 0.0;
    if (base < 2u) {
        return 0.0;
    }
    index = index_in;
    float inv = 1.0 / static_cast<float>(base);
    uint2 loop_bound = uint2(4294967295u);
    while(true) {
        if (metal::all(loop_bound == uint2(0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        uint _e13 = index;
        if (_e13 > 0u) {
        } else {
            break;
        }
        {
            float _e16 = f;
            f = _e16 * inv;
            float _e18 = r;
            float _e19 = f;
            uint _e20 = index;
            r = _e18 + (_e19 * static_cast<float>(naga_mod(_e20, base)));
            uint _e25 = index;
            index = naga_div(_e25, base);
        }
    }
    float _e27 = r;
    return _e27;
}

metal::float2 subcone_taa_jitter(
    uint frame,
    uint phases
) {
    uint i_1 = naga_mod(frame, metal::max(phases, 1u)) + 1u;
    float _e8 = subcone_taa_halton(i_1, 2u);
    float _e10 = subcone_taa_halton(i_1, 3u);
    return metal::float2(_e8, _e10) - metal::float2(0.5);
}

float subcone_taa_exposure(
    subcone_TaaParams p
) {
    bool local_1 = {};
    if (p.exposure > 0.0) {
        bool _e7 = subcone_is_finite(p.exposure);
        local_1 = _e7;
    } else {
        local_1 = false;
    }
    bool _e9 = local_1;
    if (_e9) {
        return p.exposure;
    }
    return 1.0;
}

float subcone_taa_current_weight(
    subcone_TaaParams p_1
) {
    float lo = 1.0;
    if (p_1.min_current_weight > 0.0) {
        lo = metal::min(p_1.min_current_weight, 1.0);
    } else {
        bool _e10 = subcone_is_nan(p_1.min_current_weight);
        if (!(_e10)) {
            lo = 0.000000000000000000000000000000000000011754944;
        }
    }
    float mean = 1.0 / (static_cast<float>(p_1.history_frames) + 1.0);
    float _e19 = lo;
    return metal::max(mean, _e19);
}

float subcone_taa_sanitize1_(
    float x_2
) {
    bool local_2 = {};
    if (x_2 > 0.0) {
        bool _e5 = subcone_is_finite(x_2);
        local_2 = _e5;
    } else {
        local_2 = false;
    }
    bool _e7 = local_2;
    if (_e7) {
        return x_2;
    }
    return 0.0;
}

metal::float3 subcone_taa_sanitize(
    metal::float3 c_1
) {
    float _e2 = subcone_taa_sanitize1_(c_1.x);
    float _e4 = subcone_taa_sanitize1_(c_1.y);
    float _e6 = subcone_taa_sanitize1_(c_1.z);
    return metal::float3(_e2, _e4, _e6);
}

metal::float3 subcone_taa_tonemap(
    metal::float3 c_in,
    float exposure
) {
    metal::float3 c_6 = c_in * exposure;
    return c_6 / metal::float3(1.0 + metal::dot(c_6, subcone_TAA_LUMA));
}

metal::float3 subcone_taa_tonemap_inverse(
    metal::float3 t,
    float exposure_1
) {
    float d_1 = metal::max(1.0 - metal::dot(t, subcone_TAA_LUMA), 0.000015258789);
    return (t / metal::float3(d_1)) / metal::float3(exposure_1);
}

metal::float3 subcone_taa_to_resolve_space(
    metal::float3 c_2,
    subcone_TaaParams p_2
) {
    if (p_2.tone_mapped == 1u) {
        float _e5 = subcone_taa_exposure(p_2);
        metal::float3 _e6 = subcone_taa_tonemap(c_2, _e5);
        return _e6;
    }
    return c_2;
}

metal::float3 subcone_taa_from_resolve_space(
    metal::float3 t_1,
    subcone_TaaParams p_3
) {
    if (p_3.tone_mapped == 1u) {
        float _e5 = subcone_taa_exposure(p_3);
        metal::float3 _e6 = subcone_taa_tonemap_inverse(t_1, _e5);
        return _e6;
    }
    return t_1;
}

metal::float3 subcone_taa_rgb_to_ycocg(
    metal::float3 c_3
) {
    return metal::float3(((0.25 * c_3.x) + (0.5 * c_3.y)) + (0.25 * c_3.z), (0.5 * c_3.x) - (0.5 * c_3.z), ((-0.25 * c_3.x) + (0.5 * c_3.y)) - (0.25 * c_3.z));
}

metal::float3 subcone_taa_ycocg_to_rgb(
    metal::float3 c_4
) {
    return metal::float3((c_4.x + c_4.y) - c_4.z, c_4.x + c_4.z, (c_4.x - c_4.y) - c_4.z);
}

float subcone_taa_clip_axis(
    float v,
    float e
) {
    if (e > 0.0) {
        return metal::abs(v / e);
    }
    if (v == 0.0) {
        return 0.0;
    }
    float _e9 = subcone_inf();
    return _e9;
}

metal::float3 subcone_taa_clip_towards(
    metal::float3 h,
    metal::float3 centre,
    metal::float3 extent
) {
    metal::float3 v_2 = h - centre;
    float _e6 = subcone_taa_clip_axis(v_2.x, extent.x);
    float _e9 = subcone_taa_clip_axis(v_2.y, extent.y);
    float _e13 = subcone_taa_clip_axis(v_2.z, extent.z);
    float m = metal::max(metal::max(_e6, _e9), _e13);
    if (m > 1.0) {
        return centre + (v_2 / metal::float3(m));
    }
    return h;
}

metal::float4 subcone_taa_catmull_rom_weights(
    float t_2
) {
    float t2_ = t_2 * t_2;
    float t3_ = t2_ * t_2;
    return metal::float4(0.5 * ((-(t3_) + (2.0 * t2_)) - t_2), 0.5 * (((3.0 * t3_) - (5.0 * t2_)) + 2.0), 0.5 * (((-3.0 * t3_) + (4.0 * t2_)) + t_2), 0.5 * (t3_ - t2_));
}

metal::int2 taa_at(
    int x_3,
    int y,
    constant TaaOrigin& taa_origin
) {
    uint _e4 = taa_origin.x;
    uint _e9 = taa_origin.y;
    return metal::int2(as_type<int>(as_type<uint>(x_3) + as_type<uint>(static_cast<int>(_e4))), as_type<int>(as_type<uint>(y) + as_type<uint>(static_cast<int>(_e9))));
}

metal::float3 taa_history(
    int x_4,
    int y_1,
    metal::texture2d<float, metal::access::sample> taa_history_tex,
    constant TaaOrigin& taa_origin
) {
    metal::int2 _e3 = taa_at(x_4, y_1, taa_origin);
    metal::float4 _e5 = (uint(0) < taa_history_tex.get_num_mip_levels() && metal::all(metal::uint2(_e3) < metal::uint2(taa_history_tex.get_width(0), taa_history_tex.get_height(0))) ? taa_history_tex.read(metal::uint2(_e3), 0): DefaultConstructible());
    return _e5.xyz;
}

int naga_f2i32(float value) {
    return static_cast<int>(metal::clamp(value, -2147483600.0, 2147483500.0));
}

metal::float4 subcone_taa_sample_history(
    metal::float2 p_4,
    uint w_in,
    uint h_in,
    metal::texture2d<float, metal::access::sample> taa_history_tex,
    constant TaaOrigin& taa_origin
) {
    bool local_3 = {};
    bool local_4 = {};
    bool local_5 = {};
    metal::float3 sum = metal::float3(0.0);
    int j = 0;
    metal::float3 row = {};
    int i = {};
    int w_1 = static_cast<int>(metal::max(w_in, 1u));
    int h_2 = static_cast<int>(metal::max(h_in, 1u));
    if (p_4.x >= 0.0) {
        local_3 = p_4.y >= 0.0;
    } else {
        local_3 = false;
    }
    bool _e18 = local_3;
    if (_e18) {
        local_4 = p_4.x <= static_cast<float>(w_1);
    } else {
        local_4 = false;
    }
    bool _e25 = local_4;
    if (_e25) {
        local_5 = p_4.y <= static_cast<float>(h_2);
    } else {
        local_5 = false;
    }
    bool _e32 = local_5;
    if (!(_e32)) {
        return metal::float4(0.0);
    }
    metal::float2 q = p_4 - metal::float2(0.5);
    float fx = metal::floor(q.x);
    float fy = metal::floor(q.y);
    metal::float4 _e45 = subcone_taa_catmull_rom_weights(q.x - fx);
    metal::float4 _e48 = subcone_taa_catmull_rom_weights(q.y - fy);
    int x0_ = as_type<int>(as_type<uint>(naga_f2i32(fx)) - as_type<uint>(1));
    int y0_ = as_type<int>(as_type<uint>(naga_f2i32(fy)) - as_type<uint>(1));
    uint2 loop_bound_1 = uint2(4294967295u);
    bool loop_init = true;
    while(true) {
        if (metal::all(loop_bound_1 == uint2(0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init) {
            int _e100 = j;
            j = as_type<int>(as_type<uint>(_e100) + as_type<uint>(1));
        }
        loop_init = false;
        int _e60 = j;
        if (_e60 < 4) {
        } else {
            break;
        }
        {
            int _e63 = j;
            int y_3 = metal::clamp(as_type<int>(as_type<uint>(y0_) + as_type<uint>(_e63)), 0, as_type<int>(as_type<uint>(h_2) - as_type<uint>(1)));
            row = metal::float3(0.0);
            i = 0;
            uint2 loop_bound_2 = uint2(4294967295u);
            bool loop_init_1 = true;
            while(true) {
                if (metal::all(loop_bound_2 == uint2(0u))) { break; }
                loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
                if (!loop_init_1) {
                    int _e91 = i;
                    i = as_type<int>(as_type<uint>(_e91) + as_type<uint>(1));
                }
                loop_init_1 = false;
                int _e74 = i;
                if (_e74 < 4) {
                } else {
                    break;
                }
                {
                    int _e77 = i;
                    int x_6 = metal::clamp(as_type<int>(as_type<uint>(x0_) + as_type<uint>(_e77)), 0, as_type<int>(as_type<uint>(w_1) - as_type<uint>(1)));
                    metal::float3 _e83 = row;
                    int _e84 = i;
                    metal::float3 _e86 = taa_history(x_6, y_3, taa_history_tex, taa_origin);
                    metal::float3 _e87 = subcone_taa_sanitize(_e86);
                    row = _e83 + ((uint(_e84) < 4 ? _e45[_e84] : DefaultConstructible()) * _e87);
                }
            }
            metal::float3 _e93 = sum;
            int _e94 = j;
            metal::float3 _e96 = row;
            sum = _e93 + ((uint(_e94) < 4 ? _e48[_e94] : DefaultConstructible()) * _e96);
        }
    }
    metal::float3 _e102 = sum;
    metal::float3 _e103 = subcone_taa_sanitize(_e102);
    return metal::float4(_e103, 1.0);
}

metal::float3 taa_current(
    int x_5,
    int y_2,
    constant TaaOrigin& taa_origin,
    metal::texture2d<float, metal::access::sample> taa_current_tex
) {
    metal::int2 _e3 = taa_at(x_5, y_2, taa_origin);
    metal::float4 _e5 = (uint(0) < taa_current_tex.get_num_mip_levels() && metal::all(metal::uint2(_e3) < metal::uint2(taa_current_tex.get_width(0), taa_current_tex.get_height(0))) ? taa_current_tex.read(metal::uint2(_e3), 0): DefaultConstructible());
    return _e5.xyz;
}

metal::float3 subcone_taa_resolve_pixel(
    metal::int2 xy,
    metal::float2 velocity,
    subcone_TaaParams params,
    metal::texture2d<float, metal::access::sample> taa_history_tex,
    constant TaaOrigin& taa_origin,
    metal::texture2d<float, metal::access::sample> taa_current_tex
) {
    metal::float3 m1_ = metal::float3(0.0);
    metal::float3 m2_ = metal::float3(0.0);
    int dy = -1;
    int dx = {};
    metal::float3 c_5 = {};
    bool local_6 = {};
    float gamma = 0.0;
    int w_2 = static_cast<int>(metal::max(params.width, 1u));
    int h_3 = static_cast<int>(metal::max(params.height, 1u));
    int x_7 = metal::clamp(xy.x, 0, as_type<int>(as_type<uint>(w_2) - as_type<uint>(1)));
    int y_4 = metal::clamp(xy.y, 0, as_type<int>(as_type<uint>(h_3) - as_type<uint>(1)));
    metal::float3 _e21 = taa_current(x_7, y_4, taa_origin, taa_current_tex);
    metal::float3 _e22 = subcone_taa_sanitize(_e21);
    if (params.history_frames == 0u) {
        return _e22;
    }
    metal::float2 p_6 = metal::float2(static_cast<float>(x_7) + 0.5, static_cast<float>(y_4) + 0.5) - velocity;
    metal::float4 _e36 = subcone_taa_sample_history(p_6, static_cast<uint>(w_2), static_cast<uint>(h_3), taa_history_tex, taa_origin);
    if (_e36.w == 0.0) {
        return _e22;
    }
    uint2 loop_bound_3 = uint2(4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (metal::all(loop_bound_3 == uint2(0u))) { break; }
        loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
        if (!loop_init_2) {
            int _e94 = dy;
            dy = as_type<int>(as_type<uint>(_e94) + as_type<uint>(1));
        }
        loop_init_2 = false;
        int _e48 = dy;
        if (_e48 <= 1) {
        } else {
            break;
        }
        {
            dx = -1;
            uint2 loop_bound_4 = uint2(4294967295u);
            bool loop_init_3 = true;
            while(true) {
                if (metal::all(loop_bound_4 == uint2(0u))) { break; }
                loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
                if (!loop_init_3) {
                    int _e91 = dx;
                    dx = as_type<int>(as_type<uint>(_e91) + as_type<uint>(1));
                }
                loop_init_3 = false;
                int _e53 = dx;
                if (_e53 <= 1) {
                } else {
                    break;
                }
                {
                    c_5 = _e22;
                    int _e57 = dx;
                    if (!((_e57 != 0))) {
                        int _e63 = dy;
                        local_6 = _e63 != 0;
                    } else {
                        local_6 = true;
                    }
                    bool _e67 = local_6;
                    if (_e67) {
                        int _e68 = dx;
                        int _e74 = dy;
                        metal::float3 _e80 = taa_current(metal::clamp(as_type<int>(as_type<uint>(x_7) + as_type<uint>(_e68)), 0, as_type<int>(as_type<uint>(w_2) - as_type<uint>(1))), metal::clamp(as_type<int>(as_type<uint>(y_4) + as_type<uint>(_e74)), 0, as_type<int>(as_type<uint>(h_3) - as_type<uint>(1))), taa_origin, taa_current_tex);
                        metal::float3 _e81 = subcone_taa_sanitize(_e80);
                        c_5 = _e81;
                    }
                    metal::float3 _e82 = c_5;
                    metal::float3 _e83 = subcone_taa_to_resolve_space(_e82, params);
                    metal::float3 _e84 = subcone_taa_rgb_to_ycocg(_e83);
                    metal::float3 _e85 = m1_;
                    m1_ = _e85 + _e84;
                    metal::float3 _e87 = m2_;
                    m2_ = _e87 + (_e84 * _e84);
                }
            }
        }
    }
    metal::float3 _e96 = m1_;
    metal::float3 mean_1 = _e96 / metal::float3(9.0);
    metal::float3 _e100 = m2_;
    metal::float3 var = metal::max((_e100 / metal::float3(9.0)) - (mean_1 * mean_1), metal::float3(0.0));
    metal::float3 sigma = metal::sqrt(var);
    if (params.clip_gamma > 0.0) {
        gamma = metal::min(params.clip_gamma, 1000000.0);
    }
    metal::float3 _e118 = subcone_taa_to_resolve_space(_e22, params);
    metal::float3 _e119 = subcone_taa_rgb_to_ycocg(_e118);
    float _e120 = gamma;
    metal::float3 lo_1 = metal::min(mean_1 - (_e120 * sigma), _e119);
    float _e124 = gamma;
    metal::float3 hi = metal::max(mean_1 + (_e124 * sigma), _e119);
    metal::float3 _e129 = subcone_taa_to_resolve_space(_e36.xyz, params);
    metal::float3 _e130 = subcone_taa_rgb_to_ycocg(_e129);
    metal::float3 _e137 = subcone_taa_clip_towards(_e130, 0.5 * (lo_1 + hi), 0.5 * (hi - lo_1));
    float _e138 = subcone_taa_current_weight(params);
    metal::float3 out = _e137 + ((_e119 - _e137) * _e138);
    metal::float3 _e142 = subcone_taa_ycocg_to_rgb(out);
    metal::float3 _e143 = subcone_taa_from_resolve_space(_e142, params);
    metal::float3 _e144 = subcone_taa_sanitize(_e143);
    return _e144;
}

struct taa_mainInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void taa_main(
  metal::uint3 gid [[thread_position_in_grid]]
, metal::texture2d<float, metal::access::sample> taa_history_tex [[texture(2)]]
, constant TaaOrigin& taa_origin [[buffer(1)]]
, metal::texture2d<float, metal::access::sample> taa_current_tex [[texture(0)]]
, constant subcone_TaaParams& taa_params [[buffer(0)]]
, metal::texture2d<float, metal::access::sample> taa_velocity [[texture(1)]]
, metal::texture2d<float, metal::access::write> taa_dst [[texture(3)]]
) {
    bool local = {};
    uint _e4 = taa_params.width;
    if (!((gid.x >= _e4))) {
        uint _e12 = taa_params.height;
        local = gid.y >= _e12;
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    metal::int2 xy_1 = metal::int2(static_cast<int>(gid.x), static_cast<int>(gid.y));
    metal::int2 _e24 = taa_at(xy_1.x, xy_1.y, taa_origin);
    metal::float4 _e26 = (uint(0) < taa_velocity.get_num_mip_levels() && metal::all(metal::uint2(_e24) < metal::uint2(taa_velocity.get_width(0), taa_velocity.get_height(0))) ? taa_velocity.read(metal::uint2(_e24), 0): DefaultConstructible());
    metal::float2 velocity_1 = _e26.xy;
    subcone_TaaParams _e29 = taa_params;
    metal::float3 _e30 = subcone_taa_resolve_pixel(xy_1, velocity_1, _e29, taa_history_tex, taa_origin, taa_current_tex);
    metal::int2 _e34 = taa_at(xy_1.x, xy_1.y, taa_origin);
    taa_dst.write(metal::float4(_e30, 1.0), metal::uint2(_e34));
    return;
}
