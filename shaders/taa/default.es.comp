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
struct TaaOrigin {
    uint x;
    uint y;
    uint _pad0_;
    uint _pad1_;
};
const float subcone_NEGLIGIBLE_WEIGHT = 5.421011e-20;
const vec3 subcone_TAA_LUMA = vec3(0.2126, 0.7152, 0.0722);

layout(binding = 4) uniform highp sampler2D _group_0_binding_4_cs;

layout(std140, binding = 1) uniform TaaOrigin_block_0Compute { TaaOrigin _group_0_binding_1_cs; };

layout(binding = 2) uniform highp sampler2D _group_0_binding_2_cs;

layout(std140, binding = 0) uniform subcone_TaaParams_block_1Compute { subcone_TaaParams _group_0_binding_0_cs; };

layout(binding = 3) uniform highp sampler2D _group_0_binding_3_cs;

layout(binding = 5,rgba16f) writeonly uniform highp image2D _group_0_binding_5_cs;


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
    vec2 p_5 = (p_in + c.jitter);
    float w = float(max(c.width, 1u));
    float h_1 = float(max(c.height, 1u));
    float u = (((((2.0 * p_5.x) / w) - 1.0) * c.tan_half_fov) * (w / h_1));
    float v_1 = ((1.0 - ((2.0 * p_5.y) / h_1)) * c.tan_half_fov);
    vec3 d = ((c.forward + (u * c.right)) + (v_1 * c.up));
    return (d * (1.0 / length(d)));
}

float subcone_taa_halton(uint index_in, uint base) {
    uint index = 0u;
    float f = 1.0;
    float r = 0.0;
    if ((base < 2u)) {
        return 0.0;
    }
    index = index_in;
    float inv = (1.0 / float(base));
    while(true) {
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
            r = (_e18 + (_e19 * float((_e20 % base))));
            uint _e25 = index;
            index = (_e25 / base);
        }
    }
    float _e27 = r;
    return _e27;
}

vec2 subcone_taa_jitter(uint frame, uint phases) {
    uint i_1 = ((frame % max(phases, 1u)) + 1u);
    float _e8 = subcone_taa_halton(i_1, 2u);
    float _e10 = subcone_taa_halton(i_1, 3u);
    return (vec2(_e8, _e10) - vec2(0.5));
}

float subcone_taa_exposure(subcone_TaaParams p) {
    bool local_1 = false;
    if ((p.exposure > 0.0)) {
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

float subcone_taa_current_weight(subcone_TaaParams p_1) {
    float lo = 1.0;
    if ((p_1.min_current_weight > 0.0)) {
        lo = min(p_1.min_current_weight, 1.0);
    } else {
        bool _e10 = subcone_is_nan(p_1.min_current_weight);
        if (!(_e10)) {
            lo = 1.1754944e-38;
        }
    }
    float mean = (1.0 / (float(p_1.history_frames) + 1.0));
    float _e19 = lo;
    return max(mean, _e19);
}

float subcone_taa_sanitize1_(float x_2) {
    bool local_2 = false;
    if ((x_2 > 0.0)) {
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

vec3 subcone_taa_sanitize(vec3 c_1) {
    float _e2 = subcone_taa_sanitize1_(c_1.x);
    float _e4 = subcone_taa_sanitize1_(c_1.y);
    float _e6 = subcone_taa_sanitize1_(c_1.z);
    return vec3(_e2, _e4, _e6);
}

vec3 subcone_taa_tonemap(vec3 c_in, float exposure) {
    vec3 c_6 = (c_in * exposure);
    return (c_6 / vec3((1.0 + dot(c_6, subcone_TAA_LUMA))));
}

vec3 subcone_taa_tonemap_inverse(vec3 t, float exposure_1) {
    float d_1 = max((1.0 - dot(t, subcone_TAA_LUMA)), 1.5258789e-5);
    return ((t / vec3(d_1)) / vec3(exposure_1));
}

vec3 subcone_taa_to_resolve_space(vec3 c_2, subcone_TaaParams p_2) {
    if ((p_2.tone_mapped == 1u)) {
        float _e5 = subcone_taa_exposure(p_2);
        vec3 _e6 = subcone_taa_tonemap(c_2, _e5);
        return _e6;
    }
    return c_2;
}

vec3 subcone_taa_from_resolve_space(vec3 t_1, subcone_TaaParams p_3) {
    if ((p_3.tone_mapped == 1u)) {
        float _e5 = subcone_taa_exposure(p_3);
        vec3 _e6 = subcone_taa_tonemap_inverse(t_1, _e5);
        return _e6;
    }
    return t_1;
}

vec3 subcone_taa_rgb_to_ycocg(vec3 c_3) {
    return vec3((((0.25 * c_3.x) + (0.5 * c_3.y)) + (0.25 * c_3.z)), ((0.5 * c_3.x) - (0.5 * c_3.z)), (((-0.25 * c_3.x) + (0.5 * c_3.y)) - (0.25 * c_3.z)));
}

vec3 subcone_taa_ycocg_to_rgb(vec3 c_4) {
    return vec3(((c_4.x + c_4.y) - c_4.z), (c_4.x + c_4.z), ((c_4.x - c_4.y) - c_4.z));
}

float subcone_taa_clip_axis(float v, float e) {
    if ((e > 0.0)) {
        return abs((v / e));
    }
    if ((v == 0.0)) {
        return 0.0;
    }
    float _e9 = subcone_inf();
    return _e9;
}

vec3 subcone_taa_clip_towards(vec3 h, vec3 centre, vec3 extent) {
    vec3 v_2 = (h - centre);
    float _e6 = subcone_taa_clip_axis(v_2.x, extent.x);
    float _e9 = subcone_taa_clip_axis(v_2.y, extent.y);
    float _e13 = subcone_taa_clip_axis(v_2.z, extent.z);
    float m = max(max(_e6, _e9), _e13);
    if ((m > 1.0)) {
        return (centre + (v_2 / vec3(m)));
    }
    return h;
}

vec4 subcone_taa_catmull_rom_weights(float t_2) {
    float t2_ = (t_2 * t_2);
    float t3_ = (t2_ * t_2);
    return vec4((0.5 * ((-(t3_) + (2.0 * t2_)) - t_2)), (0.5 * (((3.0 * t3_) - (5.0 * t2_)) + 2.0)), (0.5 * (((-3.0 * t3_) + (4.0 * t2_)) + t_2)), (0.5 * (t3_ - t2_)));
}

ivec2 taa_at(int x_3, int y) {
    uint _e4 = _group_0_binding_1_cs.x;
    uint _e9 = _group_0_binding_1_cs.y;
    return ivec2((x_3 + int(_e4)), (y + int(_e9)));
}

vec3 taa_history(int x_4, int y_1) {
    ivec2 _e3 = taa_at(x_4, y_1);
    vec4 _e5 = texelFetch(_group_0_binding_4_cs, _e3, 0);
    return _e5.xyz;
}

vec4 subcone_taa_sample_history(vec2 p_4, uint w_in, uint h_in) {
    bool local_3 = false;
    bool local_4 = false;
    bool local_5 = false;
    vec3 sum = vec3(0.0);
    int j = 0;
    vec3 row = vec3(0.0);
    int i = 0;
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
        return vec4(0.0);
    }
    vec2 q = (p_4 - vec2(0.5));
    float fx = floor(q.x);
    float fy = floor(q.y);
    vec4 _e45 = subcone_taa_catmull_rom_weights((q.x - fx));
    vec4 _e48 = subcone_taa_catmull_rom_weights((q.y - fy));
    int x0_ = (int(fx) - 1);
    int y0_ = (int(fy) - 1);
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            int _e100 = j;
            j = (_e100 + 1);
        }
        loop_init = false;
        int _e60 = j;
        if ((_e60 < 4)) {
        } else {
            break;
        }
        {
            int _e63 = j;
            int y_3 = min(max((y0_ + _e63), 0), (h_2 - 1));
            row = vec3(0.0);
            i = 0;
            bool loop_init_1 = true;
            while(true) {
                if (!loop_init_1) {
                    int _e91 = i;
                    i = (_e91 + 1);
                }
                loop_init_1 = false;
                int _e74 = i;
                if ((_e74 < 4)) {
                } else {
                    break;
                }
                {
                    int _e77 = i;
                    int x_6 = min(max((x0_ + _e77), 0), (w_1 - 1));
                    vec3 _e83 = row;
                    int _e84 = i;
                    vec3 _e86 = taa_history(x_6, y_3);
                    vec3 _e87 = subcone_taa_sanitize(_e86);
                    row = (_e83 + (_e45[_e84] * _e87));
                }
            }
            vec3 _e93 = sum;
            int _e94 = j;
            vec3 _e96 = row;
            sum = (_e93 + (_e48[_e94] * _e96));
        }
    }
    vec3 _e102 = sum;
    vec3 _e103 = subcone_taa_sanitize(_e102);
    return vec4(_e103, 1.0);
}

vec3 taa_current(int x_5, int y_2) {
    ivec2 _e3 = taa_at(x_5, y_2);
    vec4 _e5 = texelFetch(_group_0_binding_2_cs, _e3, 0);
    return _e5.xyz;
}

vec3 subcone_taa_resolve_pixel(ivec2 xy, vec2 velocity, subcone_TaaParams params) {
    vec3 m1_ = vec3(0.0);
    vec3 m2_ = vec3(0.0);
    int dy = -1;
    int dx = 0;
    vec3 c_5 = vec3(0.0);
    bool local_6 = false;
    float gamma = 0.0;
    int w_2 = int(max(params.width, 1u));
    int h_3 = int(max(params.height, 1u));
    int x_7 = min(max(xy.x, 0), (w_2 - 1));
    int y_4 = min(max(xy.y, 0), (h_3 - 1));
    vec3 _e21 = taa_current(x_7, y_4);
    vec3 _e22 = subcone_taa_sanitize(_e21);
    if ((params.history_frames == 0u)) {
        return _e22;
    }
    vec2 p_6 = (vec2((float(x_7) + 0.5), (float(y_4) + 0.5)) - velocity);
    vec4 _e36 = subcone_taa_sample_history(p_6, uint(w_2), uint(h_3));
    if ((_e36.w == 0.0)) {
        return _e22;
    }
    bool loop_init_2 = true;
    while(true) {
        if (!loop_init_2) {
            int _e94 = dy;
            dy = (_e94 + 1);
        }
        loop_init_2 = false;
        int _e48 = dy;
        if ((_e48 <= 1)) {
        } else {
            break;
        }
        {
            dx = -1;
            bool loop_init_3 = true;
            while(true) {
                if (!loop_init_3) {
                    int _e91 = dx;
                    dx = (_e91 + 1);
                }
                loop_init_3 = false;
                int _e53 = dx;
                if ((_e53 <= 1)) {
                } else {
                    break;
                }
                {
                    c_5 = _e22;
                    int _e57 = dx;
                    if (!((_e57 != 0))) {
                        int _e63 = dy;
                        local_6 = (_e63 != 0);
                    } else {
                        local_6 = true;
                    }
                    bool _e67 = local_6;
                    if (_e67) {
                        int _e68 = dx;
                        int _e74 = dy;
                        vec3 _e80 = taa_current(min(max((x_7 + _e68), 0), (w_2 - 1)), min(max((y_4 + _e74), 0), (h_3 - 1)));
                        vec3 _e81 = subcone_taa_sanitize(_e80);
                        c_5 = _e81;
                    }
                    vec3 _e82 = c_5;
                    vec3 _e83 = subcone_taa_to_resolve_space(_e82, params);
                    vec3 _e84 = subcone_taa_rgb_to_ycocg(_e83);
                    vec3 _e85 = m1_;
                    m1_ = (_e85 + _e84);
                    vec3 _e87 = m2_;
                    m2_ = (_e87 + (_e84 * _e84));
                }
            }
        }
    }
    vec3 _e96 = m1_;
    vec3 mean_1 = (_e96 / vec3(9.0));
    vec3 _e100 = m2_;
    vec3 var = max(((_e100 / vec3(9.0)) - (mean_1 * mean_1)), vec3(0.0));
    vec3 sigma = sqrt(var);
    if ((params.clip_gamma > 0.0)) {
        gamma = min(params.clip_gamma, 1000000.0);
    }
    vec3 _e118 = subcone_taa_to_resolve_space(_e22, params);
    vec3 _e119 = subcone_taa_rgb_to_ycocg(_e118);
    float _e120 = gamma;
    vec3 lo_1 = min((mean_1 - (_e120 * sigma)), _e119);
    float _e124 = gamma;
    vec3 hi = max((mean_1 + (_e124 * sigma)), _e119);
    vec3 _e129 = subcone_taa_to_resolve_space(_e36.xyz, params);
    vec3 _e130 = subcone_taa_rgb_to_ycocg(_e129);
    vec3 _e137 = subcone_taa_clip_towards(_e130, (0.5 * (lo_1 + hi)), (0.5 * (hi - lo_1)));
    float _e138 = subcone_taa_current_weight(params);
    vec3 out_ = (_e137 + ((_e119 - _e137) * _e138));
    vec3 _e142 = subcone_taa_ycocg_to_rgb(out_);
    vec3 _e143 = subcone_taa_from_resolve_space(_e142, params);
    vec3 _e144 = subcone_taa_sanitize(_e143);
    return _e144;
}

void main() {
    uvec3 gid = gl_GlobalInvocationID;
    bool local = false;
    uint _e4 = _group_0_binding_0_cs.width;
    if (!((gid.x >= _e4))) {
        uint _e12 = _group_0_binding_0_cs.height;
        local = (gid.y >= _e12);
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    ivec2 xy_1 = ivec2(int(gid.x), int(gid.y));
    ivec2 _e24 = taa_at(xy_1.x, xy_1.y);
    vec4 _e26 = texelFetch(_group_0_binding_3_cs, _e24, 0);
    vec2 velocity_1 = _e26.xy;
    subcone_TaaParams _e29 = _group_0_binding_0_cs;
    vec3 _e30 = subcone_taa_resolve_pixel(xy_1, velocity_1, _e29);
    ivec2 _e34 = taa_at(xy_1.x, xy_1.y);
    imageStore(_group_0_binding_5_cs, _e34, vec4(_e30, 1.0));
    return;
}

