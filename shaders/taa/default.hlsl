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
    float3 normal;
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
    float3 position;
    uint width;
    float3 forward;
    uint height;
    float3 right;
    float tan_half_fov;
    float3 up;
    uint _pad;
    float2 jitter;
    uint2 _pad2_;
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

static const float subcone_NEGLIGIBLE_WEIGHT = 5.421011e-20;
static const float3 subcone_TAA_LUMA = float3(0.2126, 0.7152, 0.0722);

Texture2D<float4> taa_history_tex : register(t4);
cbuffer taa_origin : register(b1) { TaaOrigin taa_origin; }
Texture2D<float4> taa_current_tex : register(t2);
cbuffer taa_params : register(b0) { subcone_TaaParams taa_params; }
Texture2D<float4> taa_velocity : register(t3);
RWTexture2D<float4> taa_dst : register(u5);

float subcone_inf()
{
    return asfloat(2139095040u);
}

bool subcone_is_nan(float x)
{
    return ((asuint(x) & 2147483647u) > 2139095040u);
}

bool subcone_is_finite(float x_1)
{
    return ((asuint(x_1) & 2147483647u) < 2139095040u);
}

float3 subcone_pinhole_dir(subcone_PinholeCamera c, float2 p_in)
{
    float2 p_5 = (p_in + c.jitter);
    float w = float(max(c.width, 1u));
    float h_1 = float(max(c.height, 1u));
    float u = (((((2.0 * p_5.x) / w) - 1.0) * c.tan_half_fov) * (w / h_1));
    float v_1 = ((1.0 - ((2.0 * p_5.y) / h_1)) * c.tan_half_fov);
    float3 d = ((c.forward + (u * c.right)) + (v_1 * c.up));
    return (d * (1.0 / length(d)));
}

uint naga_mod(uint lhs, uint rhs) {
    return lhs % (rhs == 0u ? 1u : rhs);
}

uint naga_div(uint lhs, uint rhs) {
    return lhs / (rhs == 0u ? 1u : rhs);
}

float subcone_taa_halton(uint index_in, uint base)
{
    uint index = (uint)0;
    float f = 1.0;
    float r = 0.0;

    if ((base < 2u)) {
        return 0.0;
    }
    index = index_in;
    float inv = (1.0 / float(base));
    uint2 loop_bound = uint2(4294967295u, 4294967295u);
    while(true) {
        if (all(loop_bound == uint2(0u, 0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        uint _e13 = index;
        if ((_e13 > 0u)) {
        } else {
            break;
        }
        {
            float _e16 = f;
            f = (_e16 * inv);
            float _e18 = r;
            float _e19 = f;
            uint _e20 = index;
            r = (_e18 + (_e19 * float(naga_mod(_e20, base))));
            uint _e25 = index;
            index = naga_div(_e25, base);
        }
    }
    float _e27 = r;
    return _e27;
}

float2 subcone_taa_jitter(uint frame, uint phases)
{
    uint i_1 = (naga_mod(frame, max(phases, 1u)) + 1u);
    const float _e8 = subcone_taa_halton(i_1, 2u);
    const float _e10 = subcone_taa_halton(i_1, 3u);
    return (float2(_e8, _e10) - (0.5).xx);
}

float subcone_taa_exposure(subcone_TaaParams p)
{
    bool local_1 = (bool)0;

    if ((p.exposure > 0.0)) {
        const bool _e7 = subcone_is_finite(p.exposure);
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

float subcone_taa_current_weight(subcone_TaaParams p_1)
{
    float lo = 1.0;

    if ((p_1.min_current_weight > 0.0)) {
        lo = min(p_1.min_current_weight, 1.0);
    } else {
        const bool _e10 = subcone_is_nan(p_1.min_current_weight);
        if (!(_e10)) {
            lo = 1.1754944e-38;
        }
    }
    float mean = (1.0 / (float(p_1.history_frames) + 1.0));
    float _e19 = lo;
    return max(mean, _e19);
}

float subcone_taa_sanitize1_(float x_2)
{
    bool local_2 = (bool)0;

    if ((x_2 > 0.0)) {
        const bool _e5 = subcone_is_finite(x_2);
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

float3 subcone_taa_sanitize(float3 c_1)
{
    const float _e2 = subcone_taa_sanitize1_(c_1.x);
    const float _e4 = subcone_taa_sanitize1_(c_1.y);
    const float _e6 = subcone_taa_sanitize1_(c_1.z);
    return float3(_e2, _e4, _e6);
}

float3 subcone_taa_tonemap(float3 c_in, float exposure)
{
    float3 c_6 = (c_in * exposure);
    return (c_6 / ((1.0 + dot(c_6, subcone_TAA_LUMA))).xxx);
}

float3 subcone_taa_tonemap_inverse(float3 t, float exposure_1)
{
    float d_1 = max((1.0 - dot(t, subcone_TAA_LUMA)), 1.5258789e-5);
    return ((t / (d_1).xxx) / (exposure_1).xxx);
}

float3 subcone_taa_to_resolve_space(float3 c_2, subcone_TaaParams p_2)
{
    if ((p_2.tone_mapped == 1u)) {
        const float _e5 = subcone_taa_exposure(p_2);
        const float3 _e6 = subcone_taa_tonemap(c_2, _e5);
        return _e6;
    }
    return c_2;
}

float3 subcone_taa_from_resolve_space(float3 t_1, subcone_TaaParams p_3)
{
    if ((p_3.tone_mapped == 1u)) {
        const float _e5 = subcone_taa_exposure(p_3);
        const float3 _e6 = subcone_taa_tonemap_inverse(t_1, _e5);
        return _e6;
    }
    return t_1;
}

float3 subcone_taa_rgb_to_ycocg(float3 c_3)
{
    return float3((((0.25 * c_3.x) + (0.5 * c_3.y)) + (0.25 * c_3.z)), ((0.5 * c_3.x) - (0.5 * c_3.z)), (((-0.25 * c_3.x) + (0.5 * c_3.y)) - (0.25 * c_3.z)));
}

float3 subcone_taa_ycocg_to_rgb(float3 c_4)
{
    return float3(((c_4.x + c_4.y) - c_4.z), (c_4.x + c_4.z), ((c_4.x - c_4.y) - c_4.z));
}

float subcone_taa_clip_axis(float v, float e)
{
    if ((e > 0.0)) {
        return abs((v / e));
    }
    if ((v == 0.0)) {
        return 0.0;
    }
    const float _e9 = subcone_inf();
    return _e9;
}

float3 subcone_taa_clip_towards(float3 h, float3 centre, float3 extent)
{
    float3 v_2 = (h - centre);
    const float _e6 = subcone_taa_clip_axis(v_2.x, extent.x);
    const float _e9 = subcone_taa_clip_axis(v_2.y, extent.y);
    const float _e13 = subcone_taa_clip_axis(v_2.z, extent.z);
    float m = max(max(_e6, _e9), _e13);
    if ((m > 1.0)) {
        return (centre + (v_2 / (m).xxx));
    }
    return h;
}

float4 subcone_taa_catmull_rom_weights(float t_2)
{
    float t2_ = (t_2 * t_2);
    float t3_ = (t2_ * t_2);
    return float4((0.5 * ((-(t3_) + (2.0 * t2_)) - t_2)), (0.5 * (((3.0 * t3_) - (5.0 * t2_)) + 2.0)), (0.5 * (((-3.0 * t3_) + (4.0 * t2_)) + t_2)), (0.5 * (t3_ - t2_)));
}

int2 taa_at(int x_3, int y)
{
    uint _e4 = taa_origin.x;
    uint _e9 = taa_origin.y;
    return int2(asint(asuint(x_3) + asuint(int(_e4))), asint(asuint(y) + asuint(int(_e9))));
}

float3 taa_history(int x_4, int y_1)
{
    const int2 _e3 = taa_at(x_4, y_1);
    float4 _e5 = taa_history_tex.Load(int3(_e3, int(0)));
    return _e5.xyz;
}

int naga_f2i32(float value) {
    return int(clamp(value, -2147483600.0, 2147483500.0));
}

float4 subcone_taa_sample_history(float2 p_4, uint w_in, uint h_in)
{
    bool local_3 = (bool)0;
    bool local_4 = (bool)0;
    bool local_5 = (bool)0;
    float3 sum = (0.0).xxx;
    int j = int(0);
    float3 row = (float3)0;
    int i = (int)0;

    int w_1 = int(max(w_in, 1u));
    int h_2 = int(max(h_in, 1u));
    if ((p_4.x >= 0.0)) {
        local_3 = (p_4.y >= 0.0);
    } else {
        local_3 = false;
    }
    bool _e18 = local_3;
    if (_e18) {
        local_4 = (p_4.x <= float(w_1));
    } else {
        local_4 = false;
    }
    bool _e25 = local_4;
    if (_e25) {
        local_5 = (p_4.y <= float(h_2));
    } else {
        local_5 = false;
    }
    bool _e32 = local_5;
    if (!(_e32)) {
        return (0.0).xxxx;
    }
    float2 q = (p_4 - (0.5).xx);
    float fx = floor(q.x);
    float fy = floor(q.y);
    const float4 _e45 = subcone_taa_catmull_rom_weights((q.x - fx));
    const float4 _e48 = subcone_taa_catmull_rom_weights((q.y - fy));
    int x0_ = asint(asuint(naga_f2i32(fx)) - asuint(int(1)));
    int y0_ = asint(asuint(naga_f2i32(fy)) - asuint(int(1)));
    uint2 loop_bound_1 = uint2(4294967295u, 4294967295u);
    bool loop_init = true;
    while(true) {
        if (all(loop_bound_1 == uint2(0u, 0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init) {
            int _e100 = j;
            j = asint(asuint(_e100) + asuint(int(1)));
        }
        loop_init = false;
        int _e60 = j;
        if ((_e60 < int(4))) {
        } else {
            break;
        }
        {
            int _e63 = j;
            int y_3 = clamp(asint(asuint(y0_) + asuint(_e63)), int(0), asint(asuint(h_2) - asuint(int(1))));
            row = (0.0).xxx;
            i = int(0);
            uint2 loop_bound_2 = uint2(4294967295u, 4294967295u);
            bool loop_init_1 = true;
            while(true) {
                if (all(loop_bound_2 == uint2(0u, 0u))) { break; }
                loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
                if (!loop_init_1) {
                    int _e91 = i;
                    i = asint(asuint(_e91) + asuint(int(1)));
                }
                loop_init_1 = false;
                int _e74 = i;
                if ((_e74 < int(4))) {
                } else {
                    break;
                }
                {
                    int _e77 = i;
                    int x_6 = clamp(asint(asuint(x0_) + asuint(_e77)), int(0), asint(asuint(w_1) - asuint(int(1))));
                    float3 _e83 = row;
                    int _e84 = i;
                    const float3 _e86 = taa_history(x_6, y_3);
                    const float3 _e87 = subcone_taa_sanitize(_e86);
                    row = (_e83 + (_e45[min(uint(_e84), 3u)] * _e87));
                }
            }
            float3 _e93 = sum;
            int _e94 = j;
            float3 _e96 = row;
            sum = (_e93 + (_e48[min(uint(_e94), 3u)] * _e96));
        }
    }
    float3 _e102 = sum;
    const float3 _e103 = subcone_taa_sanitize(_e102);
    return float4(_e103, 1.0);
}

float3 taa_current(int x_5, int y_2)
{
    const int2 _e3 = taa_at(x_5, y_2);
    float4 _e5 = taa_current_tex.Load(int3(_e3, int(0)));
    return _e5.xyz;
}

float3 subcone_taa_resolve_pixel(int2 xy, float2 velocity, subcone_TaaParams params)
{
    float3 m1_ = (0.0).xxx;
    float3 m2_ = (0.0).xxx;
    int dy = int(-1);
    int dx = (int)0;
    float3 c_5 = (float3)0;
    bool local_6 = (bool)0;
    float gamma = 0.0;

    int w_2 = int(max(params.width, 1u));
    int h_3 = int(max(params.height, 1u));
    int x_7 = clamp(xy.x, int(0), asint(asuint(w_2) - asuint(int(1))));
    int y_4 = clamp(xy.y, int(0), asint(asuint(h_3) - asuint(int(1))));
    const float3 _e21 = taa_current(x_7, y_4);
    const float3 _e22 = subcone_taa_sanitize(_e21);
    if ((params.history_frames == 0u)) {
        return _e22;
    }
    float2 p_6 = (float2((float(x_7) + 0.5), (float(y_4) + 0.5)) - velocity);
    const float4 _e36 = subcone_taa_sample_history(p_6, uint(w_2), uint(h_3));
    if ((_e36.w == 0.0)) {
        return _e22;
    }
    uint2 loop_bound_3 = uint2(4294967295u, 4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (all(loop_bound_3 == uint2(0u, 0u))) { break; }
        loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
        if (!loop_init_2) {
            int _e94 = dy;
            dy = asint(asuint(_e94) + asuint(int(1)));
        }
        loop_init_2 = false;
        int _e48 = dy;
        if ((_e48 <= int(1))) {
        } else {
            break;
        }
        {
            dx = int(-1);
            uint2 loop_bound_4 = uint2(4294967295u, 4294967295u);
            bool loop_init_3 = true;
            while(true) {
                if (all(loop_bound_4 == uint2(0u, 0u))) { break; }
                loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
                if (!loop_init_3) {
                    int _e91 = dx;
                    dx = asint(asuint(_e91) + asuint(int(1)));
                }
                loop_init_3 = false;
                int _e53 = dx;
                if ((_e53 <= int(1))) {
                } else {
                    break;
                }
                {
                    c_5 = _e22;
                    int _e57 = dx;
                    if (!((_e57 != int(0)))) {
                        int _e63 = dy;
                        local_6 = (_e63 != int(0));
                    } else {
                        local_6 = true;
                    }
                    bool _e67 = local_6;
                    if (_e67) {
                        int _e68 = dx;
                        int _e74 = dy;
                        const float3 _e80 = taa_current(clamp(asint(asuint(x_7) + asuint(_e68)), int(0), asint(asuint(w_2) - asuint(int(1)))), clamp(asint(asuint(y_4) + asuint(_e74)), int(0), asint(asuint(h_3) - asuint(int(1)))));
                        const float3 _e81 = subcone_taa_sanitize(_e80);
                        c_5 = _e81;
                    }
                    float3 _e82 = c_5;
                    const float3 _e83 = subcone_taa_to_resolve_space(_e82, params);
                    const float3 _e84 = subcone_taa_rgb_to_ycocg(_e83);
                    float3 _e85 = m1_;
                    m1_ = (_e85 + _e84);
                    float3 _e87 = m2_;
                    m2_ = (_e87 + (_e84 * _e84));
                }
            }
        }
    }
    float3 _e96 = m1_;
    float3 mean_1 = (_e96 / (9.0).xxx);
    float3 _e100 = m2_;
    float3 var = max(((_e100 / (9.0).xxx) - (mean_1 * mean_1)), (0.0).xxx);
    float3 sigma = sqrt(var);
    if ((params.clip_gamma > 0.0)) {
        gamma = min(params.clip_gamma, 1000000.0);
    }
    const float3 _e118 = subcone_taa_to_resolve_space(_e22, params);
    const float3 _e119 = subcone_taa_rgb_to_ycocg(_e118);
    float _e120 = gamma;
    float3 lo_1 = min((mean_1 - (_e120 * sigma)), _e119);
    float _e124 = gamma;
    float3 hi = max((mean_1 + (_e124 * sigma)), _e119);
    const float3 _e129 = subcone_taa_to_resolve_space(_e36.xyz, params);
    const float3 _e130 = subcone_taa_rgb_to_ycocg(_e129);
    const float3 _e137 = subcone_taa_clip_towards(_e130, (0.5 * (lo_1 + hi)), (0.5 * (hi - lo_1)));
    const float _e138 = subcone_taa_current_weight(params);
    float3 out_ = (_e137 + ((_e119 - _e137) * _e138));
    const float3 _e142 = subcone_taa_ycocg_to_rgb(out_);
    const float3 _e143 = subcone_taa_from_resolve_space(_e142, params);
    const float3 _e144 = subcone_taa_sanitize(_e143);
    return _e144;
}

[numthreads(8, 8, 1)]
void taa_main(uint3 gid : SV_DispatchThreadID)
{
    bool local = (bool)0;

    uint _e4 = taa_params.width;
    if (!((gid.x >= _e4))) {
        uint _e12 = taa_params.height;
        local = (gid.y >= _e12);
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    int2 xy_1 = int2(int(gid.x), int(gid.y));
    const int2 _e24 = taa_at(xy_1.x, xy_1.y);
    float4 _e26 = taa_velocity.Load(int3(_e24, int(0)));
    float2 velocity_1 = _e26.xy;
    subcone_TaaParams _e29 = taa_params;
    const float3 _e30 = subcone_taa_resolve_pixel(xy_1, velocity_1, _e29);
    const int2 _e34 = taa_at(xy_1.x, xy_1.y);
    taa_dst[_e34] = float4(_e30, 1.0);
    return;
}
