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

struct subcone_Aggregate {
    float3 sum;
    float weight;
    float3 last;
    uint has_last;
    uint samples;
    int _end_pad_0;
    int _end_pad_1;
    int _end_pad_2;
};

struct subcone_TransparencyAccumulator {
    uint4 planes;
};

struct subcone_GroupSample {
    float t;
    float t_entry;
    float t_exit;
    float occlusion;
    float t_occlusion;
    float t_first;
    float t_last;
    uint hard;
};

struct subcone_CtssEvent {
    uint kind;
    subcone_GroupSample sample_;
    uint reason;
};

struct subcone_ConeStepper {
    subcone_CtssParams params;
    float3 thresholds;
    float t;
    float t_prev;
    float d_prev;
    uint have_prev;
    uint prev_soft;
    uint prev_hard;
    uint group_open;
    float g_t_entry;
    float g_t_sample;
    float g_occlusion;
    float g_t_occlusion;
    float g_t_first;
    float g_t_last;
    uint g_hard;
    uint g_object;
    float g_dip;
    uint steps;
    uint samples;
    uint covered;
    uint stop;
    uint pending_stop;
    subcone_TransparencyAccumulator layers;
    uint translucent;
    uint passing;
    int _end_pad_0;
    int _end_pad_1;
};

struct subcone_SphereHit {
    float t;
    uint steps;
    uint stop;
};

struct subcone_FieldSample {
    float distance_;
    float step_;
    uint object;
};

struct subcone_SplitRay {
    float3 origin;
    int _pad1_0;
    float3 dir;
    int _pad2_0;
    float3 right;
    int _pad3_0;
    float3 up;
    int _end_pad_0;
};

struct subcone_CtssTraceResult {
    float3 color;
    uint samples;
    uint steps;
    uint coverage;
    uint stop;
    float depth;
};

struct subcone_GroupHit {
    subcone_GroupSample sample_;
    float3 point_;
    int _pad2_0;
    float3 normal;
    uint visible;
    float weight;
    int _end_pad_0;
    int _end_pad_1;
    int _end_pad_2;
};

struct subcone_PendingHits {
    subcone_GroupHit at[8];
};

struct subcone_SplitPart {
    float weight;
    int _pad1_0;
    int _pad1_1;
    int _pad1_2;
    float3 dir;
    float t;
};

struct subcone_SplitGroup {
    subcone_SplitPart parts[4];
    uint steps;
    uint split;
    int _end_pad_0;
    int _end_pad_1;
};

struct CtssUniform {
    subcone_PinholeCamera camera;
    float3 background;
    uint projection;
    row_major float4x4 inverse_view_projection;
    float3 forward;
    float depth_offset;
    uint2 origin;
    uint row_length;
    uint _pad;
};

static const float subcone_NEGLIGIBLE_WEIGHT = 5.421011e-20;
static const float subcone_OCCLUSION_MIN = -1.0;
static const float subcone_OCCLUSION_MAX = 2.0;
static const float subcone_GRID_SCALE = 0.9399856;
static const float subcone_FARTHEST_CENTRE = 0.91350174;
static const uint subcone_FULL_MASK = 4294967295u;
static const uint subcone_MASK_DERIVED = 0u;
static const uint subcone_MASK_AUTHORS_CODE = 1u;
static const uint subcone_MASK_PAPER_EQ8_ = 2u;
static const uint subcone_WEIGHTING_VISIBILITY = 0u;
static const uint subcone_WEIGHTING_UNIFORM = 1u;
static const uint subcone_LEVELS = 4u;
static const uint subcone_FLAG_RELAXED = 1u;
static const uint subcone_FLAG_SPLIT_GROUPS = 2u;
static const uint subcone_FLAG_PAPER = 4u;
static const float subcone_GROUP_DIP = 0.1;
static const uint subcone_NO_OBJECT = 4294967295u;
static const uint subcone_STOP_NONE = 0u;
static const uint subcone_STOP_FULL_OCCLUSION = 1u;
static const uint subcone_STOP_HARD_HIT = 2u;
static const uint subcone_STOP_VISIBILITY_THRESHOLD = 3u;
static const uint subcone_STOP_SAMPLE_CAP = 4u;
static const uint subcone_STOP_MAX_DISTANCE = 5u;
static const uint subcone_STOP_STEP_BUDGET = 6u;
static const uint subcone_STOP_INVALID_DISTANCE = 7u;
static const uint subcone_EVENT_MARCH = 0u;
static const uint subcone_EVENT_SAMPLE = 1u;
static const uint subcone_EVENT_STOP = 2u;
static const float subcone_SHEET_PROBE = 0.2;
static const float subcone_SHELL_LENGTH = 5.0;
static const float subcone_SPLIT_MIN_COS = 0.9396926;
static const float subcone_SPLIT_LENGTH_RATIO = 8.0;
static const uint subcone_SPLIT_MAX_STEPS = 32u;
static const uint4 subcone_SPLIT_QUADRANTS = uint4(7283u, 58252u, 835125248u, 3459776512u);
static const float subcone_SPLIT_OFFSET = 0.4308267;
static const uint subcone_CTSS_BATCH = 8u;
static const uint subcone_pass_SIDE = 1u;

RWTexture2D<float4> subcone_pass_output : register(u2);
cbuffer subcone_pass_frame : register(b0) { CtssUniform subcone_pass_frame; }
cbuffer subcone_pass_params : register(b1) { subcone_CtssParams subcone_pass_params; }

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
    float2 p_15 = (p_in + c.jitter);
    float w_3 = float(max(c.width, 1u));
    float h_4 = float(max(c.height, 1u));
    float u = (((((2.0 * p_15.x) / w_3) - 1.0) * c.tan_half_fov) * (w_3 / h_4));
    float v_1 = ((1.0 - ((2.0 * p_15.y) / h_4)) * c.tan_half_fov);
    float3 d_6 = ((c.forward + (u * c.right)) + (v_1 * c.up));
    return (d_6 * (1.0 / length(d_6)));
}

float subcone_next_up(float x_2)
{
    uint b_3 = asuint(x_2);
    if (((b_3 & 2147483647u) == 0u)) {
        return asfloat(1u);
    }
    if (((b_3 & 2147483648u) == 0u)) {
        return asfloat((b_3 + 1u));
    }
    return asfloat((b_3 - 1u));
}

float subcone_cone_radius(float t, float tan_theta)
{
    bool local_2 = (bool)0;

    if ((t > 0.0)) {
        local_2 = (tan_theta > 0.0);
    } else {
        local_2 = false;
    }
    bool _e9 = local_2;
    if (_e9) {
        return (t * tan_theta);
    }
    return 0.0;
}

float subcone_cone_occlusion(float d, float rc)
{
    float omega = (float)0;
    bool local_3 = (bool)0;

    const bool _e2 = subcone_is_nan(d);
    if (_e2) {
        return subcone_OCCLUSION_MIN;
    }
    bool thin = !((rc > 0.0));
    if (!(thin)) {
        const bool _e11 = subcone_is_finite(d);
        local_3 = !(_e11);
    } else {
        local_3 = true;
    }
    bool _e14 = local_3;
    if (_e14) {
        if ((d > 0.0)) {
            omega = subcone_OCCLUSION_MIN;
        } else {
            if ((d < 0.0)) {
                omega = subcone_OCCLUSION_MAX;
            } else {
                omega = 0.5;
            }
        }
    } else {
        const bool _e22 = subcone_is_finite(rc);
        if (!(_e22)) {
            omega = 0.5;
        } else {
            omega = ((1.0 - (d / rc)) * 0.5);
        }
    }
    float _e30 = omega;
    return clamp(_e30, subcone_OCCLUSION_MIN, subcone_OCCLUSION_MAX);
}

float3 subcone_occlusion_thresholds(float eps)
{
    return float3((0.0 - eps), (0.5 - eps), (1.0 - eps));
}

float subcone_min_step(float alpha_1, float rc_1)
{
    float s_15 = (alpha_1 * rc_1);
    if ((s_15 > 0.0)) {
        return s_15;
    }
    return 0.0;
}

float subcone_advance(float t_1, float d_1, float alpha_2, float rc_2)
{
    float step_ = (float)0;
    bool local_4 = (bool)0;

    const float _e4 = subcone_min_step(alpha_2, rc_2);
    step_ = _e4;
    const bool _e6 = subcone_is_nan(d_1);
    if (!(_e6)) {
        local_4 = (d_1 > _e4);
    } else {
        local_4 = false;
    }
    bool _e12 = local_4;
    if (_e12) {
        step_ = d_1;
    }
    float _e13 = step_;
    float next_1 = (t_1 + _e13);
    if ((next_1 > t_1)) {
        return next_1;
    } else {
        const bool _e16 = subcone_is_finite(t_1);
        if (_e16) {
            const float _e17 = subcone_next_up(t_1);
            return _e17;
        }
    }
    const float _e18 = subcone_inf();
    return _e18;
}

float subcone_backtrace_cone_entry(float t_i, float tan_theta_1)
{
    if (!((t_i > 0.0))) {
        const bool _e5 = subcone_is_nan(t_i);
        if (_e5) {
            return 0.0;
        }
        return max(t_i, 0.0);
    }
    if (!((tan_theta_1 > 0.0))) {
        return t_i;
    }
    float ts = (t_i / (1.0 + tan_theta_1));
    return min(ts, t_i);
}

float subcone_backtrace_hard_hit(float t_prev, float d_prev, float t_i_1)
{
    float ts_1 = (t_prev + d_prev);
    const bool _e4 = subcone_is_nan(ts_1);
    if (_e4) {
        return t_prev;
    }
    return min(max(ts_1, t_prev), t_i_1);
}

float2 subcone_project_normal(float3 normal, float3 right, float3 up)
{
    bool local_5 = (bool)0;
    float3 n = (float3)0;
    bool local_6 = (bool)0;

    float3 a_3 = abs(normal);
    float m_4 = max(max(a_3.x, a_3.y), a_3.z);
    if (!(!((m_4 > 0.0)))) {
        const bool _e15 = subcone_is_finite(m_4);
        local_5 = !(_e15);
    } else {
        local_5 = true;
    }
    bool _e18 = local_5;
    if (_e18) {
        return (0.0).xx;
    }
    n = (normal / (m_4).xxx);
    float3 _e24 = n;
    float3 _e25 = n;
    float3 _e26 = n;
    n = (_e24 * (1.0 / sqrt(dot(_e25, _e26))));
    float3 _e32 = n;
    float3 _e34 = n;
    float2 p_16 = float2(dot(_e32, right), dot(_e34, up));
    const bool _e38 = subcone_is_finite(p_16.x);
    if (_e38) {
        const bool _e42 = subcone_is_finite(p_16.y);
        local_6 = _e42;
    } else {
        local_6 = false;
    }
    bool _e44 = local_6;
    if (_e44) {
        return p_16;
    }
    return (0.0).xx;
}

float subcone_occlusion_to_distance(float omega_1)
{
    return (1.0 - (2.0 * omega_1));
}

float4 subcone_half_plane(float occlusion, float2 projected_normal, uint placement)
{
    bool local_7 = (bool)0;
    float h = (float)0;

    float len = length(projected_normal);
    if (!(!((len > 0.0)))) {
        const bool _e10 = subcone_is_finite(len);
        local_7 = !(_e10);
    } else {
        local_7 = true;
    }
    bool _e13 = local_7;
    if (_e13) {
        return (0.0).xxxx;
    }
    float2 dir_8 = (projected_normal / (len).xx);
    const float _e18 = subcone_occlusion_to_distance(occlusion);
    if ((placement == subcone_MASK_AUTHORS_CODE)) {
        h = -(_e18);
    } else {
        if ((placement == subcone_MASK_PAPER_EQ8_)) {
            h = (_e18 * min(len, 1.0));
        } else {
            h = (-(_e18) / min(len, 1.0));
        }
    }
    float _e32 = h;
    const bool _e33 = subcone_is_nan(_e32);
    if (_e33) {
        h = -2.0;
    } else {
        float _e35 = h;
        h = clamp(_e35, -2.0, 2.0);
    }
    float _e39 = h;
    return float4(dir_8, _e39, 1.0);
}

uint naga_div(uint lhs, uint rhs) {
    return lhs / (rhs == 0u ? 1u : rhs);
}

uint naga_mod(uint lhs, uint rhs) {
    return lhs % (rhs == 0u ? 1u : rhs);
}

float2 subcone_mask_cell_xy(uint bit)
{
    uint r = (uint)0;
    uint c_1 = (uint)0;

    if ((bit < 4u)) {
        r = 0u;
        c_1 = (bit + 1u);
    } else {
        if ((bit < 28u)) {
            r = (1u + naga_div((bit - 4u), 6u));
            c_1 = naga_mod((bit - 4u), 6u);
        } else {
            r = 5u;
            c_1 = (bit - 27u);
        }
    }
    uint _e23 = c_1;
    uint _e27 = r;
    return float2((float(_e23) - 2.5), (float(_e27) - 2.5));
}

uint subcone_half_plane_mask(float2 dir, float h_1)
{
    uint mask = 0u;
    uint bit_1 = 0u;

    float dx = ((abs(dir.x) < 1e-6) ? 0.0 : dir.x);
    float hs = (3.1915383 * h_1);
    uint2 loop_bound = uint2(4294967295u, 4294967295u);
    bool loop_init = true;
    while(true) {
        if (all(loop_bound == uint2(0u, 0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        if (!loop_init) {
            uint _e33 = bit_1;
            bit_1 = (_e33 + 1u);
        }
        loop_init = false;
        uint _e15 = bit_1;
        if ((_e15 < 32u)) {
        } else {
            break;
        }
        {
            uint _e18 = bit_1;
            const float2 _e19 = subcone_mask_cell_xy(_e18);
            if ((((_e19.x * dx) + (_e19.y * dir.y)) < hs)) {
                uint _e27 = mask;
                uint _e29 = bit_1;
                mask = (_e27 | (1u << _e29));
            }
        }
    }
    uint _e35 = mask;
    return _e35;
}

uint subcone_visibility_mask(float occlusion_1, float2 projected_normal_1, uint placement_1)
{
    const bool _e3 = subcone_is_nan(occlusion_1);
    if (_e3) {
        return 0u;
    }
    const float4 _e5 = subcone_half_plane(occlusion_1, projected_normal_1, placement_1);
    if ((_e5.w > 0.0)) {
        const uint _e11 = subcone_half_plane_mask(_e5.xy, _e5.z);
        return _e11;
    }
    if ((occlusion_1 >= 0.5)) {
        return 4294967295u;
    }
    return 0u;
}

bool subcone_needs_normal(float occlusion_2, uint placement_2)
{
    const bool _e2 = subcone_is_nan(occlusion_2);
    if (_e2) {
        return false;
    }
    const float _e4 = subcone_occlusion_to_distance(occlusion_2);
    if ((placement_2 == subcone_MASK_PAPER_EQ8_)) {
        return true;
    }
    return (abs(_e4) < subcone_FARTHEST_CENTRE);
}

float subcone_mask_weight(uint mask_1)
{
    return (float(countbits(mask_1)) * 0.03125);
}

float subcone_sample_weight(uint visible, uint weighting, float min_weight)
{
    float floor_w = 0.0;

    if ((weighting == subcone_WEIGHTING_UNIFORM)) {
        return 1.0;
    }
    if ((min_weight > 0.0)) {
        floor_w = min(min_weight, 1.0);
    }
    const float _e12 = subcone_mask_weight(visible);
    float _e13 = floor_w;
    return max(_e12, _e13);
}

subcone_Aggregate Constructsubcone_Aggregate(float3 arg0, float arg1, float3 arg2, uint arg3, uint arg4) {
    subcone_Aggregate ret = (subcone_Aggregate)0;
    ret.sum = arg0;
    ret.weight = arg1;
    ret.last = arg2;
    ret.has_last = arg3;
    ret.samples = arg4;
    return ret;
}

subcone_Aggregate subcone_aggregate_new()
{
    const subcone_Aggregate subcone_aggregate = Constructsubcone_Aggregate((0.0).xxx, 0.0, (0.0).xxx, 0u, 0u);
    return subcone_aggregate;
}

bool subcone_finite3_(float3 c_2)
{
    bool local_8 = (bool)0;
    bool local_9 = (bool)0;

    const bool _e2 = subcone_is_finite(c_2.x);
    if (_e2) {
        const bool _e6 = subcone_is_finite(c_2.y);
        local_8 = _e6;
    } else {
        local_8 = false;
    }
    bool _e8 = local_8;
    if (_e8) {
        const bool _e12 = subcone_is_finite(c_2.z);
        local_9 = _e12;
    } else {
        local_9 = false;
    }
    bool _e14 = local_9;
    return _e14;
}

void subcone_aggregate_add(inout subcone_Aggregate agg, float w, float3 color)
{
    float wc = 0.0;

    uint _e4 = agg.samples;
    agg.samples = (_e4 + 1u);
    const bool _e7 = subcone_finite3_(color);
    if (!(_e7)) {
        return;
    }
    if ((w > 0.0)) {
        wc = min(w, 1.0);
    }
    float3 _e16 = agg.sum;
    float _e17 = wc;
    agg.sum = (_e16 + (_e17 * color));
    float _e21 = agg.weight;
    float _e22 = wc;
    agg.weight = (_e21 + _e22);
    agg.last = color;
    agg.has_last = 1u;
    return;
}

float3 subcone_aggregate_resolve(subcone_Aggregate agg_1, float3 background, float bg_weight)
{
    float bgw = 0.0;
    bool local_10 = (bool)0;
    float3 sum_1 = (float3)0;
    float weight = (float)0;

    if ((bg_weight > 0.0)) {
        const bool _e9 = subcone_finite3_(background);
        local_10 = _e9;
    } else {
        local_10 = false;
    }
    bool _e11 = local_10;
    if (_e11) {
        bgw = min(bg_weight, 1.0);
    }
    sum_1 = agg_1.sum;
    weight = agg_1.weight;
    float _e18 = bgw;
    if ((_e18 > 0.0)) {
        float3 _e21 = sum_1;
        float _e22 = bgw;
        sum_1 = (_e21 + (_e22 * background));
        float _e25 = weight;
        float _e26 = bgw;
        weight = (_e25 + _e26);
    }
    float _e28 = weight;
    if ((_e28 >= subcone_NEGLIGIBLE_WEIGHT)) {
        float _e31 = weight;
        float inv = (1.0 / _e31);
        float3 _e34 = sum_1;
        float3 c_5 = (_e34 * inv);
        const bool _e36 = subcone_finite3_(c_5);
        if (_e36) {
            return c_5;
        }
    }
    if ((agg_1.has_last != 0u)) {
        return agg_1.last;
    }
    const bool _e41 = subcone_finite3_(background);
    if (_e41) {
        return background;
    }
    return (0.0).xxx;
}

float subcone_clamp_alpha(float alpha_3)
{
    const bool _e1 = subcone_is_nan(alpha_3);
    if (_e1) {
        return 1.0;
    }
    return clamp(alpha_3, 0.0, 1.0);
}

uint naga_f2u32(float value) {
    return uint(clamp(value, 0.0, 4294967000.0));
}

uint subcone_remaining_after(uint r0_, float alpha_4)
{
    uint r_1 = min(r0_, subcone_LEVELS);
    const float _e4 = subcone_clamp_alpha(alpha_4);
    uint keep = naga_f2u32(max(floor(((float(r_1) * (1.0 - _e4)) + 0.5)), 0.0));
    return min(keep, r_1);
}

bool subcone_is_opaque(float alpha_5)
{
    const uint _e2 = subcone_remaining_after(subcone_LEVELS, alpha_5);
    return (_e2 == 0u);
}

float subcone_level_weight(uint gained)
{
    return (float(min(gained, 128u)) * 0.0078125);
}

subcone_TransparencyAccumulator Constructsubcone_TransparencyAccumulator(uint4 arg0) {
    subcone_TransparencyAccumulator ret = (subcone_TransparencyAccumulator)0;
    ret.planes = arg0;
    return ret;
}

subcone_TransparencyAccumulator subcone_transparency_accumulator_new()
{
    const subcone_TransparencyAccumulator subcone_transparencyaccumulator = Constructsubcone_TransparencyAccumulator((0u).xxxx);
    return subcone_transparencyaccumulator;
}

uint subcone_transparency_accumulator_plane(subcone_TransparencyAccumulator acc, uint k)
{
    if ((k == 0u)) {
        return subcone_FULL_MASK;
    }
    if ((k > subcone_LEVELS)) {
        return 0u;
    }
    return acc.planes[min(uint((k - 1u)), 3u)];
}

uint subcone_transparency_accumulator_level_set(subcone_TransparencyAccumulator acc_1, uint l)
{
    const uint _e2 = subcone_transparency_accumulator_plane(acc_1, l);
    const uint _e5 = subcone_transparency_accumulator_plane(acc_1, (l + 1u));
    return (_e2 & ~(_e5));
}

uint subcone_transparency_accumulator_level(subcone_TransparencyAccumulator acc_2, uint bit_2)
{
    uint n_1 = 0u;
    uint k_1 = 0u;

    uint b_4 = (1u << min(bit_2, 31u));
    uint2 loop_bound_1 = uint2(4294967295u, 4294967295u);
    bool loop_init_1 = true;
    while(true) {
        if (all(loop_bound_1 == uint2(0u, 0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init_1) {
            uint _e23 = k_1;
            k_1 = (_e23 + 1u);
        }
        loop_init_1 = false;
        uint _e10 = k_1;
        if ((_e10 < subcone_LEVELS)) {
        } else {
            break;
        }
        {
            uint _e14 = k_1;
            if (((acc_2.planes[min(uint(_e14), 3u)] & b_4) != 0u)) {
                uint _e19 = n_1;
                n_1 = (_e19 + 1u);
            }
        }
    }
    uint _e25 = n_1;
    return _e25;
}

uint2 subcone_transparency_accumulator_add(inout subcone_TransparencyAccumulator acc_3, uint mask_2, float alpha_6)
{
    uint4 next = (uint4)0;
    uint visible_1 = 0u;
    uint gained_1 = 0u;
    uint l_1 = 0u;
    uint k_2 = (uint)0;

    uint4 _e4 = acc_3.planes;
    next = (_e4 & (~(mask_2)).xxxx);
    uint2 loop_bound_2 = uint2(4294967295u, 4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (all(loop_bound_2 == uint2(0u, 0u))) { break; }
        loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
        if (!loop_init_2) {
            uint _e52 = l_1;
            l_1 = (_e52 + 1u);
        }
        loop_init_2 = false;
        uint _e15 = l_1;
        if ((_e15 <= subcone_LEVELS)) {
        } else {
            break;
        }
        {
            subcone_TransparencyAccumulator _e18 = acc_3;
            uint _e19 = l_1;
            const uint _e20 = subcone_transparency_accumulator_level_set(_e18, _e19);
            uint cells = (_e20 & mask_2);
            if ((cells == 0u)) {
                continue;
            }
            uint _e26 = l_1;
            const uint _e28 = subcone_remaining_after((subcone_LEVELS - _e26), alpha_6);
            uint to = (subcone_LEVELS - _e28);
            uint _e30 = l_1;
            if ((to > _e30)) {
                uint _e32 = visible_1;
                visible_1 = (_e32 | cells);
                uint _e34 = gained_1;
                uint _e35 = l_1;
                gained_1 = (_e34 + ((to - _e35) * countbits(cells)));
            }
            k_2 = 0u;
            uint2 loop_bound_3 = uint2(4294967295u, 4294967295u);
            bool loop_init_3 = true;
            while(true) {
                if (all(loop_bound_3 == uint2(0u, 0u))) { break; }
                loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
                if (!loop_init_3) {
                    uint _e49 = k_2;
                    k_2 = (_e49 + 1u);
                }
                loop_init_3 = false;
                uint _e42 = k_2;
                if ((_e42 < to)) {
                } else {
                    break;
                }
                {
                    uint _e44 = k_2;
                    uint _e46 = next[min(uint(_e44), 3u)];
                    next[min(uint(_e44), 3u)] = (_e46 | cells);
                }
            }
        }
    }
    uint4 _e55 = next;
    acc_3.planes = _e55;
    uint _e56 = visible_1;
    uint _e57 = gained_1;
    return uint2(_e56, _e57);
}

uint subcone_transparency_accumulator_opaque(subcone_TransparencyAccumulator acc_4)
{
    return acc_4.planes.w;
}

bool subcone_transparency_accumulator_is_binary(subcone_TransparencyAccumulator acc_5)
{
    const uint _e2 = subcone_transparency_accumulator_plane(acc_5, 1u);
    const uint _e3 = subcone_transparency_accumulator_opaque(acc_5);
    return (_e2 == _e3);
}

uint subcone_transparency_accumulator_total_levels(subcone_TransparencyAccumulator acc_6)
{
    uint4 c_6 = countbits(acc_6.planes);
    return (((c_6.x + c_6.y) + c_6.z) + c_6.w);
}

float subcone_transparency_accumulator_uncovered_weight(subcone_TransparencyAccumulator acc_7)
{
    const uint _e1 = subcone_transparency_accumulator_total_levels(acc_7);
    const float _e2 = subcone_level_weight(_e1);
    return (1.0 - _e2);
}

bool subcone_covers_pixel(uint reason)
{
    bool local_11 = (bool)0;
    bool local_12 = (bool)0;

    if (!((reason == subcone_STOP_FULL_OCCLUSION))) {
        local_11 = (reason == subcone_STOP_HARD_HIT);
    } else {
        local_11 = true;
    }
    bool _e9 = local_11;
    if (!(_e9)) {
        local_12 = (reason == subcone_STOP_VISIBILITY_THRESHOLD);
    } else {
        local_12 = true;
    }
    bool _e16 = local_12;
    return _e16;
}

bool subcone_ctss_is_relaxed(subcone_CtssParams p)
{
    return ((p.flags & subcone_FLAG_RELAXED) != 0u);
}

bool subcone_ctss_is_paper(subcone_CtssParams p_1)
{
    return ((p_1.flags & subcone_FLAG_PAPER) != 0u);
}

bool subcone_ctss_splits_groups(subcone_CtssParams p_2)
{
    return ((p_2.flags & subcone_FLAG_SPLIT_GROUPS) != 0u);
}

uint subcone_ctss_placement(subcone_CtssParams p_3)
{
    uint v_2 = ((p_3.flags >> 8u) & 255u);
    return ((v_2 <= 2u) ? v_2 : subcone_MASK_DERIVED);
}

uint subcone_ctss_weighting(subcone_CtssParams p_4)
{
    uint v_3 = ((p_4.flags >> 16u) & 255u);
    return ((v_3 <= 1u) ? v_3 : subcone_WEIGHTING_VISIBILITY);
}

subcone_GroupSample Constructsubcone_GroupSample(float arg0, float arg1, float arg2, float arg3, float arg4, float arg5, float arg6, uint arg7) {
    subcone_GroupSample ret = (subcone_GroupSample)0;
    ret.t = arg0;
    ret.t_entry = arg1;
    ret.t_exit = arg2;
    ret.occlusion = arg3;
    ret.t_occlusion = arg4;
    ret.t_first = arg5;
    ret.t_last = arg6;
    ret.hard = arg7;
    return ret;
}

subcone_CtssEvent Constructsubcone_CtssEvent(uint arg0, subcone_GroupSample arg1, uint arg2) {
    subcone_CtssEvent ret = (subcone_CtssEvent)0;
    ret.kind = arg0;
    ret.sample_ = arg1;
    ret.reason = arg2;
    return ret;
}

subcone_CtssEvent subcone_ctss_event(uint kind, uint reason_1)
{
    const subcone_CtssEvent subcone_ctssevent = Constructsubcone_CtssEvent(kind, Constructsubcone_GroupSample(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0u), reason_1);
    return subcone_ctssevent;
}

subcone_ConeStepper Constructsubcone_ConeStepper(subcone_CtssParams arg0, float3 arg1, float arg2, float arg3, float arg4, uint arg5, uint arg6, uint arg7, uint arg8, float arg9, float arg10, float arg11, float arg12, float arg13, float arg14, uint arg15, uint arg16, float arg17, uint arg18, uint arg19, uint arg20, uint arg21, uint arg22, subcone_TransparencyAccumulator arg23, uint arg24, uint arg25) {
    subcone_ConeStepper ret = (subcone_ConeStepper)0;
    ret.params = arg0;
    ret.thresholds = arg1;
    ret.t = arg2;
    ret.t_prev = arg3;
    ret.d_prev = arg4;
    ret.have_prev = arg5;
    ret.prev_soft = arg6;
    ret.prev_hard = arg7;
    ret.group_open = arg8;
    ret.g_t_entry = arg9;
    ret.g_t_sample = arg10;
    ret.g_occlusion = arg11;
    ret.g_t_occlusion = arg12;
    ret.g_t_first = arg13;
    ret.g_t_last = arg14;
    ret.g_hard = arg15;
    ret.g_object = arg16;
    ret.g_dip = arg17;
    ret.steps = arg18;
    ret.samples = arg19;
    ret.covered = arg20;
    ret.stop = arg21;
    ret.pending_stop = arg22;
    ret.layers = arg23;
    ret.translucent = arg24;
    ret.passing = arg25;
    return ret;
}

subcone_ConeStepper subcone_cone_stepper_new(subcone_CtssParams params)
{
    float t0_ = 0.0;

    if ((params.t_min > 0.0)) {
        t0_ = params.t_min;
    }
    const float3 _e8 = subcone_occlusion_thresholds(params.eps);
    float _e9 = t0_;
    float _e10 = t0_;
    const subcone_TransparencyAccumulator _e22 = subcone_transparency_accumulator_new();
    const subcone_ConeStepper subcone_conestepper = Constructsubcone_ConeStepper(params, _e8, _e9, _e10, 0.0, 0u, 0u, 0u, 0u, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0u, subcone_NO_OBJECT, 0.0, 0u, 0u, 0u, subcone_STOP_NONE, 0u, _e22, 0u, 0u);
    return subcone_conestepper;
}

subcone_GroupSample subcone_cone_stepper_group_sample(inout subcone_ConeStepper s, float t_exit)
{
    float _e3 = s.g_t_sample;
    float _e5 = s.g_t_entry;
    float _e7 = s.g_occlusion;
    float _e9 = s.g_t_occlusion;
    float _e11 = s.g_t_first;
    float _e13 = s.g_t_last;
    uint _e15 = s.g_hard;
    const subcone_GroupSample subcone_groupsample = Constructsubcone_GroupSample(_e3, _e5, t_exit, _e7, _e9, _e11, _e13, _e15);
    return subcone_groupsample;
}

subcone_CtssEvent subcone_cone_stepper_end(inout subcone_ConeStepper s_1, uint reason_2, float t_exit_1)
{
    s_1.stop = reason_2;
    uint _e5 = s_1.group_open;
    if ((_e5 != 0u)) {
        s_1.group_open = 0u;
        uint _e11 = s_1.samples;
        s_1.samples = (_e11 + 1u);
        const subcone_GroupSample _e15 = subcone_cone_stepper_group_sample(s_1, t_exit_1);
        const subcone_CtssEvent subcone_ctssevent_1 = Constructsubcone_CtssEvent(subcone_EVENT_SAMPLE, _e15, subcone_STOP_NONE);
        return subcone_ctssevent_1;
    }
    const subcone_CtssEvent _e19 = subcone_ctss_event(subcone_EVENT_STOP, reason_2);
    const subcone_CtssEvent subcone_ctssevent_2 = _e19;
    return subcone_ctssevent_2;
}

subcone_CtssEvent subcone_cone_stepper_advance_object(inout subcone_ConeStepper s_2, float d_2, float step_1, uint object)
{
    bool stop = (bool)0;
    bool local_13 = (bool)0;
    bool local_14 = (bool)0;
    bool closed = false;
    subcone_GroupSample closed_sample = Constructsubcone_GroupSample(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0u);
    bool local_15 = (bool)0;
    bool local_16 = (bool)0;
    bool local_17 = (bool)0;
    bool local_18 = (bool)0;
    bool local_19 = (bool)0;
    bool local_20 = (bool)0;
    bool local_21 = (bool)0;
    bool local_22 = (bool)0;
    bool local_23 = (bool)0;
    bool local_24 = (bool)0;
    float te = (float)0;
    bool local_25 = (bool)0;
    bool local_26 = (bool)0;
    bool local_27 = (bool)0;
    bool local_28 = (bool)0;
    float m = (float)0;
    bool local_29 = (bool)0;
    bool local_30 = (bool)0;
    subcone_CtssEvent event = (subcone_CtssEvent)0;
    bool local_31 = (bool)0;
    float step_by = (float)0;
    bool local_32 = (bool)0;

    uint _e5 = s_2.stop;
    if ((_e5 != subcone_STOP_NONE)) {
        uint _e10 = s_2.stop;
        const subcone_CtssEvent _e11 = subcone_ctss_event(subcone_EVENT_STOP, _e10);
        const subcone_CtssEvent subcone_ctssevent_3 = _e11;
        return subcone_ctssevent_3;
    }
    subcone_CtssParams _e13 = s_2.params;
    const bool _e14 = subcone_ctss_is_relaxed(_e13);
    uint _e16 = s_2.pending_stop;
    if ((_e16 != 0u)) {
        s_2.pending_stop = 0u;
        uint reason_3 = (_e14 ? subcone_STOP_HARD_HIT : subcone_STOP_FULL_OCCLUSION);
        float _e25 = s_2.t;
        float _e28 = s_2.params.tan_theta;
        const float _e29 = subcone_backtrace_cone_entry(_e25, _e28);
        const subcone_CtssEvent _e30 = subcone_cone_stepper_end(s_2, reason_3, _e29);
        const subcone_CtssEvent subcone_ctssevent_4 = _e30;
        return subcone_ctssevent_4;
    }
    float t_9 = s_2.t;
    uint _e34 = s_2.steps;
    uint _e37 = s_2.params.max_steps;
    if ((_e34 >= _e37)) {
        const subcone_CtssEvent _e40 = subcone_cone_stepper_end(s_2, subcone_STOP_STEP_BUDGET, t_9);
        const subcone_CtssEvent subcone_ctssevent_5 = _e40;
        return subcone_ctssevent_5;
    }
    float _e43 = s_2.params.t_max;
    if (!((t_9 < _e43))) {
        const subcone_CtssEvent _e47 = subcone_cone_stepper_end(s_2, subcone_STOP_MAX_DISTANCE, t_9);
        const subcone_CtssEvent subcone_ctssevent_6 = _e47;
        return subcone_ctssevent_6;
    }
    const bool _e48 = subcone_is_nan(d_2);
    if (_e48) {
        const subcone_CtssEvent _e50 = subcone_cone_stepper_end(s_2, subcone_STOP_INVALID_DISTANCE, t_9);
        const subcone_CtssEvent subcone_ctssevent_7 = _e50;
        return subcone_ctssevent_7;
    }
    uint _e52 = s_2.steps;
    s_2.steps = (_e52 + 1u);
    float tan_ = s_2.params.tan_theta;
    const float _e58 = subcone_cone_radius(t_9, tan_);
    const float _e59 = subcone_cone_occlusion(d_2, _e58);
    float3 th = s_2.thresholds;
    bool soft = (_e59 > th.x);
    bool hard = (_e59 > th.y);
    float stop_at = (_e14 ? th.y : th.z);
    stop = (_e59 > stop_at);
    uint _e72 = s_2.passing;
    if ((_e72 != 0u)) {
        if ((d_2 > 0.0)) {
            uint _e80 = s_2.have_prev;
            local_13 = (_e80 != 0u);
        } else {
            local_13 = false;
        }
        bool _e84 = local_13;
        if (_e84) {
            float _e88 = s_2.d_prev;
            local_14 = (d_2 < _e88);
        } else {
            local_14 = false;
        }
        bool _e91 = local_14;
        if (_e91) {
            s_2.passing = 0u;
            s_2.prev_soft = 0u;
            s_2.prev_hard = 0u;
        } else {
            stop = false;
        }
    }
    if (soft) {
        uint _e114 = s_2.prev_soft;
        local_15 = (_e114 != 0u);
    } else {
        local_15 = false;
    }
    bool _e118 = local_15;
    if (_e118) {
        subcone_CtssParams _e122 = s_2.params;
        const bool _e123 = subcone_ctss_is_paper(_e122);
        local_16 = !(_e123);
    } else {
        local_16 = false;
    }
    bool _e126 = local_16;
    if (_e126) {
        uint _e130 = s_2.passing;
        local_17 = (_e130 == 0u);
    } else {
        local_17 = false;
    }
    bool _e134 = local_17;
    if (_e134) {
        uint _e138 = s_2.group_open;
        local_18 = (_e138 != 0u);
    } else {
        local_18 = false;
    }
    bool _e142 = local_18;
    if (_e142) {
        float _e145 = s_2.g_dip;
        s_2.g_dip = min(_e145, _e59);
        uint _e148 = s_2.g_object;
        if ((object != _e148)) {
            local_19 = (object != subcone_NO_OBJECT);
        } else {
            local_19 = false;
        }
        bool _e155 = local_19;
        if (_e155) {
            uint _e159 = s_2.g_object;
            local_20 = (_e159 != subcone_NO_OBJECT);
        } else {
            local_20 = false;
        }
        bool other = local_20;
        float _e165 = s_2.g_dip;
        float _e167 = s_2.g_occlusion;
        if ((_e165 < (_e167 - subcone_GROUP_DIP))) {
            float _e174 = s_2.g_dip;
            local_21 = (_e59 > (_e174 + subcone_GROUP_DIP));
        } else {
            local_21 = false;
        }
        bool rises = local_21;
        if (!(other)) {
            local_22 = rises;
        } else {
            local_22 = true;
        }
        bool _e184 = local_22;
        if (_e184) {
            closed = true;
            const subcone_GroupSample _e186 = subcone_cone_stepper_group_sample(s_2, t_9);
            closed_sample = _e186;
            s_2.group_open = 0u;
            uint _e190 = s_2.samples;
            s_2.samples = (_e190 + 1u);
            s_2.prev_hard = 0u;
            s_2.have_prev = 0u;
        }
    }
    if (soft) {
        uint _e200 = s_2.prev_soft;
        if (!((_e200 == 0u))) {
            bool _e206 = closed;
            local_24 = _e206;
        } else {
            local_24 = true;
        }
        bool _e208 = local_24;
        local_23 = _e208;
    } else {
        local_23 = false;
    }
    bool _e210 = local_23;
    if (_e210) {
        te = t_9;
        bool _e212 = closed;
        if (!(_e212)) {
            const float _e214 = subcone_backtrace_cone_entry(t_9, tan_);
            te = _e214;
        }
        s_2.group_open = 1u;
        float _e218 = te;
        s_2.g_t_entry = _e218;
        float _e220 = te;
        s_2.g_t_sample = _e220;
        s_2.g_occlusion = _e59;
        s_2.g_t_occlusion = t_9;
        s_2.g_t_first = t_9;
        s_2.g_t_last = t_9;
        s_2.g_hard = 0u;
        s_2.g_object = object;
        s_2.g_dip = _e59;
    }
    if (soft) {
        uint _e232 = s_2.group_open;
        local_25 = (_e232 != 0u);
    } else {
        local_25 = false;
    }
    bool _e236 = local_25;
    if (_e236) {
        s_2.g_t_last = t_9;
        float _e239 = s_2.g_occlusion;
        if ((_e59 > _e239)) {
            s_2.g_occlusion = _e59;
            s_2.g_t_occlusion = t_9;
            s_2.g_dip = _e59;
        }
        if (hard) {
            uint _e247 = s_2.prev_hard;
            local_26 = (_e247 == 0u);
        } else {
            local_26 = false;
        }
        bool _e251 = local_26;
        if (_e251) {
            uint _e255 = s_2.g_hard;
            local_27 = (_e255 == 0u);
        } else {
            local_27 = false;
        }
        bool _e259 = local_27;
        if (_e259) {
            s_2.g_hard = 1u;
            uint _e263 = s_2.have_prev;
            if ((_e263 != 0u)) {
                float _e268 = s_2.t_prev;
                float _e270 = s_2.d_prev;
                const float _e271 = subcone_backtrace_hard_hit(_e268, _e270, t_9);
                s_2.g_t_sample = _e271;
            } else {
                s_2.g_t_sample = t_9;
            }
        }
    }
    if (!(soft)) {
        uint _e277 = s_2.prev_soft;
        local_28 = (_e277 != 0u);
    } else {
        local_28 = false;
    }
    bool exit = local_28;
    if (exit) {
        s_2.passing = 0u;
    }
    s_2.prev_soft = (soft ? 1u : 0u);
    s_2.prev_hard = (hard ? 1u : 0u);
    m = d_2;
    const bool _e293 = subcone_is_nan(step_1);
    if (!(_e293)) {
        local_29 = (step_1 < d_2);
    } else {
        local_29 = false;
    }
    bool _e299 = local_29;
    if (_e299) {
        m = step_1;
    }
    bool _e300 = closed;
    if (_e300) {
        s_2.t_prev = t_9;
        s_2.d_prev = d_2;
        s_2.have_prev = 1u;
        uint _e306 = s_2.samples;
        uint _e309 = s_2.params.max_samples;
        if ((_e306 >= _e309)) {
            s_2.group_open = 0u;
            s_2.stop = subcone_STOP_SAMPLE_CAP;
        } else {
            bool _e315 = stop;
            if (_e315) {
                s_2.pending_stop = 1u;
            }
        }
        uint _e319 = s_2.stop;
        if ((_e319 == subcone_STOP_NONE)) {
            uint _e325 = s_2.pending_stop;
            local_30 = (_e325 == 0u);
        } else {
            local_30 = false;
        }
        bool _e329 = local_30;
        if (_e329) {
            float _e331 = m;
            float _e334 = s_2.params.alpha;
            const float _e335 = subcone_advance(t_9, _e331, _e334, _e58);
            s_2.t = _e335;
        }
        subcone_GroupSample _e337 = closed_sample;
        const subcone_CtssEvent subcone_ctssevent_8 = Constructsubcone_CtssEvent(subcone_EVENT_SAMPLE, _e337, subcone_STOP_NONE);
        return subcone_ctssevent_8;
    }
    const subcone_CtssEvent _e342 = subcone_ctss_event(subcone_EVENT_MARCH, subcone_STOP_NONE);
    event = _e342;
    if (!(exit)) {
        bool _e347 = stop;
        local_31 = _e347;
    } else {
        local_31 = true;
    }
    bool _e349 = local_31;
    if (_e349) {
        uint _e351 = s_2.group_open;
        if ((_e351 != 0u)) {
            const float _e355 = subcone_backtrace_cone_entry(t_9, tan_);
            const subcone_GroupSample _e356 = subcone_cone_stepper_group_sample(s_2, _e355);
            event = Constructsubcone_CtssEvent(subcone_EVENT_SAMPLE, _e356, subcone_STOP_NONE);
            s_2.group_open = 0u;
            uint _e362 = s_2.samples;
            s_2.samples = (_e362 + 1u);
        }
        bool _e365 = stop;
        if (_e365) {
            s_2.stop = (_e14 ? subcone_STOP_HARD_HIT : subcone_STOP_FULL_OCCLUSION);
        } else {
            uint _e371 = s_2.samples;
            uint _e374 = s_2.params.max_samples;
            if ((_e371 >= _e374)) {
                s_2.stop = subcone_STOP_SAMPLE_CAP;
            }
        }
    }
    s_2.t_prev = t_9;
    s_2.d_prev = d_2;
    s_2.have_prev = 1u;
    uint _e383 = s_2.stop;
    if ((_e383 == subcone_STOP_NONE)) {
        float _e386 = m;
        step_by = _e386;
        uint _e389 = s_2.passing;
        if ((_e389 != 0u)) {
            local_32 = (d_2 < 0.0);
        } else {
            local_32 = false;
        }
        bool _e397 = local_32;
        if (_e397) {
            step_by = -(d_2);
        }
        float _e400 = step_by;
        float _e403 = s_2.params.alpha;
        const float _e404 = subcone_advance(t_9, _e400, _e403, _e58);
        s_2.t = _e404;
    }
    subcone_CtssEvent _e405 = event;
    const subcone_CtssEvent subcone_ctssevent_9 = _e405;
    return subcone_ctssevent_9;
}

subcone_CtssEvent subcone_cone_stepper_advance_split(inout subcone_ConeStepper s_3, float d_3, float step_2)
{
    const subcone_CtssEvent _e4 = subcone_cone_stepper_advance_object(s_3, d_3, step_2, subcone_NO_OBJECT);
    const subcone_CtssEvent subcone_ctssevent_10 = _e4;
    return subcone_ctssevent_10;
}

bool subcone_cone_stepper_takes_rest_of_pixel(inout subcone_ConeStepper s_4)
{
    bool local_33 = (bool)0;

    subcone_CtssParams _e2 = s_4.params;
    const bool _e3 = subcone_ctss_is_paper(_e2);
    if (!(_e3)) {
        uint _e8 = s_4.stop;
        local_33 = (_e8 == subcone_STOP_HARD_HIT);
    } else {
        local_33 = false;
    }
    bool _e12 = local_33;
    return _e12;
}

uint2 subcone_cone_stepper_record_mask(inout subcone_ConeStepper s_5, uint m0_)
{
    uint m_1 = (uint)0;
    bool local_34 = (bool)0;

    m_1 = m0_;
    const bool _e3 = subcone_cone_stepper_takes_rest_of_pixel(s_5);
    if (_e3) {
        m_1 = 4294967295u;
    }
    uint _e5 = m_1;
    uint _e7 = s_5.covered;
    uint visible_4 = (_e5 & ~(_e7));
    uint _e11 = s_5.covered;
    s_5.covered = (_e11 | visible_4);
    uint _e14 = s_5.stop;
    if ((_e14 == subcone_STOP_NONE)) {
        uint _e20 = s_5.covered;
        uint _e24 = s_5.params.visibility_k;
        local_34 = (countbits(_e20) >= _e24);
    } else {
        local_34 = false;
    }
    bool _e27 = local_34;
    if (_e27) {
        s_5.stop = subcone_STOP_VISIBILITY_THRESHOLD;
    }
    subcone_CtssParams _e31 = s_5.params;
    const uint _e32 = subcone_ctss_weighting(_e31);
    float _e35 = s_5.params.min_sample_weight;
    const float _e36 = subcone_sample_weight(visible_4, _e32, _e35);
    return uint2(visible_4, asuint(_e36));
}

uint2 subcone_cone_stepper_record(inout subcone_ConeStepper s_6, subcone_GroupSample sample_, float2 projected_normal_2)
{
    subcone_CtssParams _e5 = s_6.params;
    const uint _e6 = subcone_ctss_placement(_e5);
    const uint _e7 = subcone_visibility_mask(sample_.occlusion, projected_normal_2, _e6);
    const uint2 _e8 = subcone_cone_stepper_record_mask(s_6, _e7);
    return _e8;
}

void subcone_cone_stepper_restart_grouping(inout subcone_ConeStepper s_7)
{
    s_7.prev_soft = 0u;
    s_7.prev_hard = 0u;
    s_7.have_prev = 0u;
    s_7.passing = 0u;
    return;
}

bool subcone_cone_stepper_is_passing(subcone_ConeStepper s_8)
{
    return (s_8.passing != 0u);
}

void subcone_cone_stepper_end_pass(inout subcone_ConeStepper s_9)
{
    uint _e2 = s_9.passing;
    if ((_e2 != 0u)) {
        subcone_cone_stepper_restart_grouping(s_9);
        return;
    } else {
        return;
    }
}

bool subcone_cone_stepper_in_group(subcone_ConeStepper s_10)
{
    return (s_10.group_open != 0u);
}

subcone_CtssEvent subcone_cone_stepper_split_group(inout subcone_ConeStepper s_11)
{
    bool local_35 = (bool)0;

    uint _e2 = s_11.stop;
    if (!((_e2 != subcone_STOP_NONE))) {
        uint _e9 = s_11.group_open;
        local_35 = (_e9 == 0u);
    } else {
        local_35 = true;
    }
    bool _e13 = local_35;
    if (_e13) {
        const subcone_CtssEvent _e16 = subcone_ctss_event(subcone_EVENT_MARCH, subcone_STOP_NONE);
        const subcone_CtssEvent subcone_ctssevent_11 = _e16;
        return subcone_ctssevent_11;
    }
    s_11.group_open = 0u;
    uint _e20 = s_11.samples;
    s_11.samples = (_e20 + 1u);
    subcone_cone_stepper_restart_grouping(s_11);
    uint _e24 = s_11.samples;
    uint _e27 = s_11.params.max_samples;
    if ((_e24 >= _e27)) {
        s_11.stop = subcone_STOP_SAMPLE_CAP;
    }
    float _e32 = s_11.t;
    float _e35 = s_11.params.tan_theta;
    const float _e36 = subcone_backtrace_cone_entry(_e32, _e35);
    const subcone_GroupSample _e38 = subcone_cone_stepper_group_sample(s_11, _e36);
    const subcone_CtssEvent subcone_ctssevent_12 = Constructsubcone_CtssEvent(subcone_EVENT_SAMPLE, _e38, subcone_STOP_NONE);
    return subcone_ctssevent_12;
}

uint2 subcone_cone_stepper_record_alpha_mask(inout subcone_ConeStepper s_12, uint mask_3, float alpha_7)
{
    bool local_36 = (bool)0;
    uint m_2 = (uint)0;
    bool local_37 = (bool)0;
    bool local_38 = (bool)0;
    bool local_39 = (bool)0;
    bool local_40 = (bool)0;
    subcone_TransparencyAccumulator layers = (subcone_TransparencyAccumulator)0;
    bool local_41 = (bool)0;
    bool local_42 = (bool)0;
    bool local_43 = (bool)0;
    float w_1 = 1.0;
    float floor_w_1 = 0.0;

    s_12.translucent = 1u;
    uint _e6 = s_12.stop;
    if (!((_e6 == subcone_STOP_FULL_OCCLUSION))) {
        uint _e13 = s_12.stop;
        local_36 = (_e13 == subcone_STOP_HARD_HIT);
    } else {
        local_36 = true;
    }
    bool ended = local_36;
    m_2 = mask_3;
    subcone_CtssParams _e20 = s_12.params;
    const bool _e21 = subcone_ctss_is_paper(_e20);
    if (!(_e21)) {
        uint _e26 = s_12.stop;
        local_37 = (_e26 == subcone_STOP_HARD_HIT);
    } else {
        local_37 = false;
    }
    bool relaxed_full = local_37;
    if (ended) {
        const bool _e33 = subcone_is_opaque(alpha_7);
        if (!(!(_e33))) {
            subcone_TransparencyAccumulator _e39 = s_12.layers;
            const bool _e40 = subcone_transparency_accumulator_is_binary(_e39);
            local_39 = !(_e40);
        } else {
            local_39 = true;
        }
        bool _e43 = local_39;
        if (!(_e43)) {
            local_40 = relaxed_full;
        } else {
            local_40 = true;
        }
        bool _e48 = local_40;
        local_38 = _e48;
    } else {
        local_38 = false;
    }
    bool _e50 = local_38;
    if (_e50) {
        m_2 = subcone_FULL_MASK;
    }
    subcone_TransparencyAccumulator _e53 = s_12.layers;
    layers = _e53;
    uint _e55 = m_2;
    const uint2 _e56 = subcone_transparency_accumulator_add(layers, _e55, alpha_7);
    subcone_TransparencyAccumulator _e58 = layers;
    s_12.layers = _e58;
    subcone_TransparencyAccumulator _e59 = layers;
    const uint _e60 = subcone_transparency_accumulator_opaque(_e59);
    if (ended) {
        const bool _e63 = subcone_is_opaque(alpha_7);
        local_41 = !(_e63);
    } else {
        local_41 = false;
    }
    bool _e66 = local_41;
    if (_e66) {
        local_42 = (_e60 != subcone_FULL_MASK);
    } else {
        local_42 = false;
    }
    bool _e72 = local_42;
    if (_e72) {
        s_12.stop = subcone_STOP_NONE;
        s_12.passing = 1u;
    }
    uint _e78 = s_12.stop;
    if ((_e78 == subcone_STOP_NONE)) {
        uint _e86 = s_12.params.visibility_k;
        local_43 = (countbits(_e60) >= _e86);
    } else {
        local_43 = false;
    }
    bool _e89 = local_43;
    if (_e89) {
        s_12.stop = subcone_STOP_VISIBILITY_THRESHOLD;
    }
    subcone_CtssParams _e95 = s_12.params;
    const uint _e96 = subcone_ctss_weighting(_e95);
    if ((_e96 == subcone_WEIGHTING_VISIBILITY)) {
        float _e103 = s_12.params.min_sample_weight;
        if ((_e103 > 0.0)) {
            float _e108 = s_12.params.min_sample_weight;
            floor_w_1 = min(_e108, 1.0);
        }
        const float _e112 = subcone_level_weight(_e56.y);
        float _e113 = floor_w_1;
        w_1 = max(_e112, _e113);
    }
    float _e116 = w_1;
    return uint2(_e56.x, asuint(_e116));
}

uint subcone_cone_stepper_coverage(subcone_ConeStepper s_13)
{
    if ((s_13.translucent != 0u)) {
        const uint _e5 = subcone_transparency_accumulator_opaque(s_13.layers);
        return _e5;
    }
    return s_13.covered;
}

float subcone_cone_stepper_background_weight(subcone_ConeStepper s_14)
{
    bool local_44 = (bool)0;

    if ((s_14.stop != subcone_STOP_NONE)) {
        const bool _e7 = subcone_covers_pixel(s_14.stop);
        local_44 = _e7;
    } else {
        local_44 = false;
    }
    bool _e9 = local_44;
    if (_e9) {
        return 0.0;
    }
    const uint _e12 = subcone_ctss_weighting(s_14.params);
    if ((_e12 == subcone_WEIGHTING_UNIFORM)) {
        return 1.0;
    }
    if ((s_14.translucent != 0u)) {
        const float _e20 = subcone_transparency_accumulator_uncovered_weight(s_14.layers);
        return _e20;
    }
    const float _e22 = subcone_mask_weight(s_14.covered);
    return (1.0 - _e22);
}

uint subcone_sphere_trace_step(subcone_CtssParams params_1, inout float t_2, float d_4, float step_3)
{
    float m_3 = (float)0;
    bool local_45 = (bool)0;

    const bool _e4 = subcone_is_nan(d_4);
    if (_e4) {
        return subcone_STOP_INVALID_DISTANCE;
    }
    float _e6 = t_2;
    const float _e8 = subcone_cone_radius(_e6, params_1.tan_theta);
    const float _e9 = subcone_cone_occlusion(d_4, _e8);
    const float3 _e11 = subcone_occlusion_thresholds(params_1.eps);
    if ((_e9 > _e11.y)) {
        return subcone_STOP_HARD_HIT;
    }
    m_3 = d_4;
    const bool _e16 = subcone_is_nan(step_3);
    if (!(_e16)) {
        local_45 = (step_3 < d_4);
    } else {
        local_45 = false;
    }
    bool _e22 = local_45;
    if (_e22) {
        m_3 = step_3;
    }
    float _e23 = t_2;
    float _e24 = m_3;
    const float _e26 = subcone_advance(_e23, _e24, 0.0, _e8);
    t_2 = _e26;
    return subcone_STOP_NONE;
}

float3 subcone_field(float3 p_5)
{
    float sphere = (length((p_5 - float3(0.0, 0.0, 4.0))) - 1.0);
    float ground = (p_5.y + 1.0);
    if ((sphere < ground)) {
        return float3(sphere, sphere, 0.0);
    }
    return float3(ground, ground, 1.0);
}

float2 ctss_field(float3 p_6)
{
    const float3 _e1 = subcone_field(p_6);
    return _e1.xy;
}

subcone_SphereHit Constructsubcone_SphereHit(float arg0, uint arg1, uint arg2) {
    subcone_SphereHit ret = (subcone_SphereHit)0;
    ret.t = arg0;
    ret.steps = arg1;
    ret.stop = arg2;
    return ret;
}

subcone_SphereHit subcone_sphere_trace_split(subcone_CtssParams params_2, float3 origin, float3 dir_1)
{
    float t_3 = 0.0;
    uint steps_1 = 0u;
    uint i = 0u;

    if ((params_2.t_min > 0.0)) {
        t_3 = params_2.t_min;
    }
    uint2 loop_bound_4 = uint2(4294967295u, 4294967295u);
    bool loop_init_4 = true;
    while(true) {
        if (all(loop_bound_4 == uint2(0u, 0u))) { break; }
        loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
        if (!loop_init_4) {
            uint _e44 = i;
            i = (_e44 + 1u);
        }
        loop_init_4 = false;
        uint _e13 = i;
        if ((_e13 < params_2.max_steps)) {
        } else {
            break;
        }
        {
            float _e16 = t_3;
            if (!((_e16 < params_2.t_max))) {
                uint _e20 = steps_1;
                const subcone_SphereHit subcone_spherehit = Constructsubcone_SphereHit(-1.0, _e20, subcone_STOP_MAX_DISTANCE);
                return subcone_spherehit;
            }
            float _e24 = t_3;
            const float2 _e27 = ctss_field((origin + (_e24 * dir_1)));
            uint _e28 = steps_1;
            steps_1 = (_e28 + 1u);
            float t_hit = t_3;
            const uint _e34 = subcone_sphere_trace_step(params_2, t_3, _e27.x, _e27.y);
            if ((_e34 != subcone_STOP_NONE)) {
                uint _e41 = steps_1;
                const subcone_SphereHit subcone_spherehit_1 = Constructsubcone_SphereHit(((_e34 == subcone_STOP_HARD_HIT) ? t_hit : -1.0), _e41, _e34);
                return subcone_spherehit_1;
            }
        }
    }
    uint _e46 = steps_1;
    const subcone_SphereHit subcone_spherehit_2 = Constructsubcone_SphereHit(-1.0, _e46, subcone_STOP_STEP_BUDGET);
    return subcone_spherehit_2;
}

float3 subcone_normalize_or_zero(float3 v)
{
    bool local_46 = (bool)0;

    float rcp_ = (1.0 / length(v));
    const bool _e4 = subcone_is_finite(rcp_);
    if (_e4) {
        local_46 = (rcp_ > 0.0);
    } else {
        local_46 = false;
    }
    bool _e10 = local_46;
    if (_e10) {
        return (v * rcp_);
    }
    return (0.0).xxx;
}

float2x3 subcone_cross_section_frame(float3 dir_2, float3 up_hint)
{
    float3 right_1 = (float3)0;

    const float3 _e2 = subcone_normalize_or_zero(dir_2);
    if (all((_e2 == (0.0).xxx))) {
        return float2x3(float3(1.0, 0.0, 0.0), float3(0.0, 1.0, 0.0));
    }
    const float3 _e17 = subcone_normalize_or_zero(cross(_e2, up_hint));
    right_1 = _e17;
    float3 _e19 = right_1;
    if (all((_e19 == (0.0).xxx))) {
        float sgn = ((_e2.z >= 0.0) ? 1.0 : -1.0);
        float a_4 = (-1.0 / (sgn + _e2.z));
        float b_5 = ((_e2.x * _e2.y) * a_4);
        right_1 = float3(b_5, (sgn + ((_e2.y * _e2.y) * a_4)), -(_e2.y));
    }
    float3 _e46 = right_1;
    float3 _e47 = right_1;
    return float2x3(_e46, cross(_e47, _e2));
}

uint subcone_saturating_add(uint a, uint b)
{
    uint s_16 = (a + b);
    return ((s_16 < a) ? 4294967295u : s_16);
}

subcone_FieldSample Constructsubcone_FieldSample(float arg0, float arg1, uint arg2) {
    subcone_FieldSample ret = (subcone_FieldSample)0;
    ret.distance_ = arg0;
    ret.step_ = arg1;
    ret.object = arg2;
    return ret;
}

subcone_FieldSample subcone_field_sample(float3 p_7)
{
    uint object_1 = subcone_NO_OBJECT;
    bool local_47 = (bool)0;

    const float3 _e1 = subcone_field(p_7);
    if ((_e1.z >= 0.0)) {
        local_47 = (_e1.z < 4294967300.0);
    } else {
        local_47 = false;
    }
    bool _e13 = local_47;
    if (_e13) {
        object_1 = naga_f2u32(_e1.z);
    }
    uint _e18 = object_1;
    const subcone_FieldSample subcone_fieldsample = Constructsubcone_FieldSample(_e1.x, _e1.y, _e18);
    return subcone_fieldsample;
}

float subcone_ctss_coverage_alpha(uint coverage, uint stop_1)
{
    const bool _e2 = subcone_covers_pixel(stop_1);
    if (_e2) {
        return 1.0;
    }
    const float _e4 = subcone_mask_weight(coverage);
    return _e4;
}

float subcone_normal_step(float t_4, float tan_theta_2)
{
    float floor_h = 1e-5;

    if ((t_4 > 1.0)) {
        floor_h = (1e-5 * t_4);
    }
    float h_5 = ((0.25 * t_4) * tan_theta_2);
    float _e11 = floor_h;
    if ((h_5 > _e11)) {
        return h_5;
    }
    float _e13 = floor_h;
    return _e13;
}

float subcone_coarse_normal_step(float t_5, subcone_CtssParams params_3)
{
    const float _e3 = subcone_normal_step(t_5, params_3.tan_theta);
    return (4.0 * _e3);
}

float3 subcone_tetra_normal(float3 p_8, float h_2)
{
    float3 n_2 = (0.0).xxx;

    float3 k0_ = float3(1.0, -1.0, -1.0);
    float3 k1_ = float3(-1.0, -1.0, 1.0);
    float3 k2_ = float3(-1.0, 1.0, -1.0);
    float3 k3_ = float3(1.0, 1.0, 1.0);
    float3 _e21 = n_2;
    const float3 _e24 = subcone_field((p_8 + (k0_ * h_2)));
    n_2 = (_e21 + (k0_ * _e24.x));
    float3 _e28 = n_2;
    const float3 _e31 = subcone_field((p_8 + (k1_ * h_2)));
    n_2 = (_e28 + (k1_ * _e31.x));
    float3 _e35 = n_2;
    const float3 _e38 = subcone_field((p_8 + (k2_ * h_2)));
    n_2 = (_e35 + (k2_ * _e38.x));
    float3 _e42 = n_2;
    const float3 _e45 = subcone_field((p_8 + (k3_ * h_2)));
    n_2 = (_e42 + (k3_ * _e45.x));
    float3 _e49 = n_2;
    const float3 _e50 = subcone_normalize_or_zero(_e49);
    return _e50;
}

float3 subcone_normal(float3 p_9, float h_3)
{
    const float3 _e2 = subcone_tetra_normal(p_9, h_3);
    return _e2;
}

float3 subcone_group_normal_at(subcone_SplitRay ray, subcone_GroupSample sample_1, float3 normal_1, float t_6, float tan_theta_3)
{
    if ((t_6 == sample_1.t)) {
        return normal_1;
    }
    const float _e11 = subcone_normal_step(t_6, tan_theta_3);
    const float3 _e12 = subcone_normal((ray.origin + (t_6 * ray.dir)), _e11);
    return _e12;
}

float3 ZeroValuefloat3() {
    return (float3)0;
}

bool subcone_sheet_across(subcone_SplitRay ray_1, float t_7, float tan_theta_4, float3 n0_)
{
    bool local_48 = (bool)0;
    float3 along = (float3)0;
    uint i_1 = 0u;
    float3 e = (float3)0;

    const float _e4 = subcone_cone_radius(t_7, tan_theta_4);
    const float3 _e5 = subcone_normalize_or_zero(n0_);
    if (!(all((_e5 == (0.0).xxx)))) {
        local_48 = !((_e4 > 0.0));
    } else {
        local_48 = true;
    }
    bool _e17 = local_48;
    if (_e17) {
        return false;
    }
    float cosv = abs(dot(_e5, ray_1.dir));
    const float3 _e27 = subcone_normalize_or_zero((ray_1.dir - (dot(_e5, ray_1.dir) * _e5)));
    along = _e27;
    float3 _e29 = along;
    if (all((_e29 == (0.0).xxx))) {
        along = ray_1.right;
    }
    float3 _e35 = along;
    const float3 _e37 = subcone_normalize_or_zero(cross(_e5, _e35));
    float stretch = (_e4 / ((cosv > 0.25) ? cosv : 0.25));
    float3 c_7 = (ray_1.origin + (t_7 * ray_1.dir));
    uint2 loop_bound_5 = uint2(4294967295u, 4294967295u);
    bool loop_init_5 = true;
    while(true) {
        if (all(loop_bound_5 == uint2(0u, 0u))) { break; }
        loop_bound_5 -= uint2(loop_bound_5.y == 0u, 1u);
        if (!loop_init_5) {
            uint _e73 = i_1;
            i_1 = (_e73 + 1u);
        }
        loop_init_5 = false;
        uint _e49 = i_1;
        if ((_e49 < 4u)) {
        } else {
            break;
        }
        {
            e = ZeroValuefloat3();
            uint _e54 = i_1;
            bool should_continue = false;
            switch(_e54) {
                case 0u: {
                    float3 _e55 = along;
                    e = (_e55 * stretch);
                    break;
                }
                case 1u: {
                    float3 _e57 = along;
                    e = (-(_e57) * stretch);
                    break;
                }
                case 2u: {
                    e = (_e37 * _e4);
                    break;
                }
                default: {
                    e = (-(_e37) * _e4);
                    break;
                }
            }
            float3 _e63 = e;
            const subcone_FieldSample _e65 = subcone_field_sample((c_7 + _e63));
            if (!((_e65.distance_ < (subcone_SHEET_PROBE * _e4)))) {
                return false;
            }
        }
    }
    return true;
}

uint subcone_group_mask(subcone_CtssParams params_4, subcone_SplitRay ray_2, subcone_GroupSample sample_2, float3 normal_2)
{
    bool local_49 = (bool)0;

    const uint _e4 = subcone_ctss_placement(params_4);
    float omega_2 = sample_2.occlusion;
    const bool _e6 = subcone_needs_normal(omega_2, _e4);
    if (!(_e6)) {
        const uint _e10 = subcone_visibility_mask(omega_2, (0.0).xx, _e4);
        return _e10;
    }
    float tan_1 = params_4.tan_theta;
    const bool _e12 = subcone_ctss_is_paper(params_4);
    if (!(_e12)) {
        const float3 _e15 = subcone_group_normal_at(ray_2, sample_2, normal_2, sample_2.t_first, tan_1);
        const float3 _e17 = subcone_group_normal_at(ray_2, sample_2, normal_2, sample_2.t_last, tan_1);
        if ((dot(_e15, _e17) < 0.0)) {
            const bool _e22 = subcone_sheet_across(ray_2, sample_2.t_occlusion, tan_1, _e15);
            if (_e22) {
                return subcone_FULL_MASK;
            }
            const float2 _e26 = subcone_project_normal(_e15, ray_2.right, ray_2.up);
            const float2 _e29 = subcone_project_normal(_e17, ray_2.right, ray_2.up);
            const float _e35 = subcone_cone_radius(sample_2.t_first, tan_1);
            bool long_ = ((sample_2.t_last - sample_2.t_first) > (subcone_SHELL_LENGTH * _e35));
            if (long_) {
                local_49 = (dot(_e26, _e29) < 0.0);
            } else {
                local_49 = false;
            }
            bool _e44 = local_49;
            if (_e44) {
                const uint _e45 = subcone_visibility_mask(omega_2, _e26, _e4);
                const uint _e46 = subcone_visibility_mask(omega_2, _e29, _e4);
                return (_e45 | _e46);
            }
        }
    }
    const float3 _e49 = subcone_group_normal_at(ray_2, sample_2, normal_2, sample_2.t_occlusion, tan_1);
    const float2 _e52 = subcone_project_normal(_e49, ray_2.right, ray_2.up);
    const uint _e53 = subcone_visibility_mask(omega_2, _e52, _e4);
    return _e53;
}

bool subcone_group_needs_split(float3 n_fine, float3 n_coarse, float group_length, float depth_1, subcone_CtssParams params_5)
{
    bool local_50 = (bool)0;
    bool local_51 = (bool)0;
    bool local_52 = (bool)0;
    bool local_53 = (bool)0;
    bool local_54 = (bool)0;
    bool local_55 = (bool)0;

    const float _e6 = subcone_cone_radius(depth_1, params_5.tan_theta);
    const bool _e7 = subcone_is_finite(_e6);
    if (_e7) {
        local_50 = (_e6 > 0.0);
    } else {
        local_50 = false;
    }
    bool _e13 = local_50;
    if (_e13) {
        const bool _e16 = subcone_is_finite(group_length);
        local_51 = _e16;
    } else {
        local_51 = false;
    }
    bool _e18 = local_51;
    if (_e18) {
        local_52 = (group_length > (subcone_SPLIT_LENGTH_RATIO * _e6));
    } else {
        local_52 = false;
    }
    bool long_1 = local_52;
    const float3 _e26 = subcone_normalize_or_zero(n_fine);
    const float3 _e27 = subcone_normalize_or_zero(n_coarse);
    if (any((_e26 != (0.0).xxx))) {
        local_53 = any((_e27 != (0.0).xxx));
    } else {
        local_53 = false;
    }
    bool _e39 = local_53;
    if (_e39) {
        local_54 = (dot(_e26, _e27) < subcone_SPLIT_MIN_COS);
    } else {
        local_54 = false;
    }
    bool bent = local_54;
    if (!(long_1)) {
        local_55 = bent;
    } else {
        local_55 = true;
    }
    bool _e51 = local_55;
    return _e51;
}

float4 subcone_split_weights(uint visible_2, float weight_1)
{
    bool local_56 = (bool)0;
    float4 w_2 = (0.0).xxxx;
    uint j = 0u;

    uint n_4 = countbits(visible_2);
    if (!((n_4 == 0u))) {
        const bool _e8 = subcone_is_finite(weight_1);
        local_56 = !(_e8);
    } else {
        local_56 = true;
    }
    bool _e11 = local_56;
    if (_e11) {
        return (0.0).xxxx;
    }
    float per_cell = (weight_1 / float(n_4));
    uint2 loop_bound_6 = uint2(4294967295u, 4294967295u);
    bool loop_init_6 = true;
    while(true) {
        if (all(loop_bound_6 == uint2(0u, 0u))) { break; }
        loop_bound_6 -= uint2(loop_bound_6.y == 0u, 1u);
        if (!loop_init_6) {
            uint _e34 = j;
            j = (_e34 + 1u);
        }
        loop_init_6 = false;
        uint _e21 = j;
        if ((_e21 < 4u)) {
        } else {
            break;
        }
        {
            uint _e24 = j;
            uint _e27 = j;
            w_2[min(uint(_e24), 3u)] = (float(countbits((visible_2 & subcone_SPLIT_QUADRANTS[min(uint(_e27), 3u)]))) * per_cell);
        }
    }
    float4 _e36 = w_2;
    return _e36;
}

float2 subcone_split_offset(uint j_1)
{
    switch(j_1) {
        case 0u: {
            return float2(-(subcone_SPLIT_OFFSET), -(subcone_SPLIT_OFFSET));
        }
        case 1u: {
            return float2(subcone_SPLIT_OFFSET, -(subcone_SPLIT_OFFSET));
        }
        case 2u: {
            return float2(-(subcone_SPLIT_OFFSET), subcone_SPLIT_OFFSET);
        }
        default: {
            return float2(subcone_SPLIT_OFFSET, subcone_SPLIT_OFFSET);
        }
    }
}

float3 subcone_split_direction(float3 dir_3, float3 right_2, float3 up_1, float tan_theta_5, float2 offset)
{
    float3 d_7 = ((dir_3 + ((tan_theta_5 * offset.x) * right_2)) + ((tan_theta_5 * offset.y) * up_1));
    const float3 _e13 = subcone_normalize_or_zero(d_7);
    if (all((_e13 == (0.0).xxx))) {
        return dir_3;
    }
    return _e13;
}

float subcone_max_num(float a_1, float b_1)
{
    bool local_57 = (bool)0;

    const bool _e2 = subcone_is_nan(a_1);
    if (!(_e2)) {
        local_57 = (b_1 > a_1);
    } else {
        local_57 = true;
    }
    bool _e8 = local_57;
    if (_e8) {
        return b_1;
    }
    return a_1;
}

float subcone_min_num(float a_2, float b_2)
{
    bool local_58 = (bool)0;

    const bool _e2 = subcone_is_nan(a_2);
    if (!(_e2)) {
        local_58 = (b_2 < a_2);
    } else {
        local_58 = true;
    }
    bool _e8 = local_58;
    if (_e8) {
        return b_2;
    }
    return a_2;
}

subcone_CtssParams subcone_split_trace_params(subcone_CtssParams params_6, subcone_GroupSample sample_3)
{
    subcone_CtssParams p_10 = (subcone_CtssParams)0;

    const float _e4 = subcone_max_num(sample_3.t_exit, sample_3.t_occlusion);
    const float _e6 = subcone_max_num(_e4, sample_3.t);
    const float _e8 = subcone_cone_radius(_e6, params_6.tan_theta);
    float hi = (_e6 + (2.0 * _e8));
    p_10 = params_6;
    p_10.t_min = sample_3.t_entry;
    const float _e17 = subcone_min_num(hi, params_6.t_max);
    p_10.t_max = _e17;
    p_10.max_steps = subcone_SPLIT_MAX_STEPS;
    subcone_CtssParams _e20 = p_10;
    const subcone_CtssParams subcone_ctssparams = _e20;
    return subcone_ctssparams;
}

subcone_SphereHit subcone_sphere_trace_field(subcone_CtssParams params_7, float3 origin_1, float3 dir_4)
{
    float t_8 = 0.0;
    uint steps_2 = 0u;
    uint i_2 = 0u;

    if ((params_7.t_min > 0.0)) {
        t_8 = params_7.t_min;
    }
    uint2 loop_bound_7 = uint2(4294967295u, 4294967295u);
    bool loop_init_7 = true;
    while(true) {
        if (all(loop_bound_7 == uint2(0u, 0u))) { break; }
        loop_bound_7 -= uint2(loop_bound_7.y == 0u, 1u);
        if (!loop_init_7) {
            uint _e44 = i_2;
            i_2 = (_e44 + 1u);
        }
        loop_init_7 = false;
        uint _e13 = i_2;
        if ((_e13 < params_7.max_steps)) {
        } else {
            break;
        }
        {
            float _e16 = t_8;
            if (!((_e16 < params_7.t_max))) {
                uint _e20 = steps_2;
                const subcone_SphereHit subcone_spherehit_3 = Constructsubcone_SphereHit(-1.0, _e20, subcone_STOP_MAX_DISTANCE);
                return subcone_spherehit_3;
            }
            float _e24 = t_8;
            const subcone_FieldSample _e27 = subcone_field_sample((origin_1 + (_e24 * dir_4)));
            uint _e28 = steps_2;
            steps_2 = (_e28 + 1u);
            float t_hit_1 = t_8;
            const uint _e34 = subcone_sphere_trace_step(params_7, t_8, _e27.distance_, _e27.step_);
            if ((_e34 != subcone_STOP_NONE)) {
                uint _e41 = steps_2;
                const subcone_SphereHit subcone_spherehit_4 = Constructsubcone_SphereHit(((_e34 == subcone_STOP_HARD_HIT) ? t_hit_1 : -1.0), _e41, _e34);
                return subcone_spherehit_4;
            }
        }
    }
    uint _e46 = steps_2;
    const subcone_SphereHit subcone_spherehit_5 = Constructsubcone_SphereHit(-1.0, _e46, subcone_STOP_STEP_BUDGET);
    return subcone_spherehit_5;
}

subcone_SplitPart Constructsubcone_SplitPart(float arg0, float3 arg1, float arg2) {
    subcone_SplitPart ret = (subcone_SplitPart)0;
    ret.weight = arg0;
    ret.dir = arg1;
    ret.t = arg2;
    return ret;
}

subcone_SplitGroup subcone_split_group(subcone_CtssParams params_8, subcone_GroupSample sample_4, subcone_SplitRay ray_3, uint visible_3, float weight_2)
{
    subcone_SplitGroup g = (subcone_SplitGroup)0;
    uint j_2 = 0u;
    bool local_59 = (bool)0;
    uint j_3 = 0u;

    uint2 loop_bound_8 = uint2(4294967295u, 4294967295u);
    bool loop_init_8 = true;
    while(true) {
        if (all(loop_bound_8 == uint2(0u, 0u))) { break; }
        loop_bound_8 -= uint2(loop_bound_8.y == 0u, 1u);
        if (!loop_init_8) {
            uint _e19 = j_2;
            j_2 = (_e19 + 1u);
        }
        loop_init_8 = false;
        uint _e8 = j_2;
        if ((_e8 < 4u)) {
        } else {
            break;
        }
        {
            uint _e12 = j_2;
            g.parts[min(uint(_e12), 3u)] = Constructsubcone_SplitPart(0.0, ray_3.dir, -1.0);
        }
    }
    g.steps = 0u;
    g.split = 0u;
    const float4 _e25 = subcone_split_weights(visible_3, weight_2);
    if (!((countbits(visible_3) == 0u))) {
        const bool _e32 = subcone_is_finite(weight_2);
        local_59 = !(_e32);
    } else {
        local_59 = true;
    }
    bool _e35 = local_59;
    if (_e35) {
        subcone_SplitGroup _e36 = g;
        const subcone_SplitGroup subcone_splitgroup = _e36;
        return subcone_splitgroup;
    }
    g.split = 1u;
    const subcone_CtssParams _e39 = subcone_split_trace_params(params_8, sample_4);
    uint2 loop_bound_9 = uint2(4294967295u, 4294967295u);
    bool loop_init_9 = true;
    while(true) {
        if (all(loop_bound_9 == uint2(0u, 0u))) { break; }
        loop_bound_9 -= uint2(loop_bound_9.y == 0u, 1u);
        if (!loop_init_9) {
            uint _e72 = j_3;
            j_3 = (_e72 + 1u);
        }
        loop_init_9 = false;
        uint _e42 = j_3;
        if ((_e42 < 4u)) {
        } else {
            break;
        }
        {
            uint _e45 = j_3;
            if (!((_e25[min(uint(_e45), 3u)] > 0.0))) {
                continue;
            }
            uint _e54 = j_3;
            const float2 _e55 = subcone_split_offset(_e54);
            const float3 _e56 = subcone_split_direction(ray_3.dir, ray_3.right, ray_3.up, params_8.tan_theta, _e55);
            const subcone_SphereHit _e58 = subcone_sphere_trace_field(_e39, ray_3.origin, _e56);
            uint _e61 = g.steps;
            const uint _e63 = subcone_saturating_add(_e61, _e58.steps);
            g.steps = _e63;
            uint _e65 = j_3;
            uint _e67 = j_3;
            g.parts[min(uint(_e65), 3u)] = Constructsubcone_SplitPart(_e25[min(uint(_e67), 3u)], _e56, _e58.t);
        }
    }
    subcone_SplitGroup _e74 = g;
    const subcone_SplitGroup subcone_splitgroup_1 = _e74;
    return subcone_splitgroup_1;
}

float3 subcone_shade(float3 p_11, float3 n_3, float3 dir_5)
{
    float3 albedo = float3(0.9, 0.3, 0.2);

    float3 light = float3(0.48, 0.8, -0.36);
    if ((p_11.y < -0.999)) {
        albedo = float3(0.7, 0.7, 0.7);
    }
    float3 _e19 = albedo;
    return (_e19 * (0.15 + max(dot(n_3, light), 0.0)));
}

uint2 subcone_ctss_shade_hit(subcone_CtssParams params_9, subcone_SplitRay ray_4, subcone_GroupHit hit, inout subcone_Aggregate agg_2)
{
    float3 group_color = (0.0).xxx;
    bool have_group_color = false;
    uint shaded = 0u;
    uint j_4 = 0u;
    float3 c_3 = (float3)0;

    const bool _e4 = subcone_ctss_splits_groups(params_9);
    if (_e4) {
        subcone_GroupSample s_17 = hit.sample_;
        const float _e8 = subcone_coarse_normal_step(s_17.t, params_9);
        const float3 _e9 = subcone_normal(hit.point_, _e8);
        const bool _e15 = subcone_group_needs_split(hit.normal, _e9, (s_17.t_exit - s_17.t_entry), s_17.t, params_9);
        if (_e15) {
            const subcone_SplitGroup _e18 = subcone_split_group(params_9, s_17, ray_4, hit.visible, hit.weight);
            if ((_e18.split != 0u)) {
                uint2 loop_bound_10 = uint2(4294967295u, 4294967295u);
                bool loop_init_10 = true;
                while(true) {
                    if (all(loop_bound_10 == uint2(0u, 0u))) { break; }
                    loop_bound_10 -= uint2(loop_bound_10.y == 0u, 1u);
                    if (!loop_init_10) {
                        uint _e71 = j_4;
                        j_4 = (_e71 + 1u);
                    }
                    loop_init_10 = false;
                    uint _e31 = j_4;
                    if ((_e31 < 4u)) {
                    } else {
                        break;
                    }
                    {
                        uint _e35 = j_4;
                        subcone_SplitPart part = _e18.parts[min(uint(_e35), 3u)];
                        if (!((part.weight > 0.0))) {
                            continue;
                        }
                        c_3 = ZeroValuefloat3();
                        if ((part.t >= 0.0)) {
                            float3 x_3 = (ray_4.origin + (part.t * part.dir));
                            const float _e53 = subcone_normal_step(part.t, params_9.tan_theta);
                            const float3 _e54 = subcone_normal(x_3, _e53);
                            const float3 _e56 = subcone_shade(x_3, _e54, part.dir);
                            c_3 = _e56;
                        } else {
                            bool _e57 = have_group_color;
                            if (!(_e57)) {
                                const float3 _e62 = subcone_shade(hit.point_, hit.normal, ray_4.dir);
                                group_color = _e62;
                                have_group_color = true;
                            }
                            float3 _e64 = group_color;
                            c_3 = _e64;
                        }
                        float3 _e66 = c_3;
                        subcone_aggregate_add(agg_2, part.weight, _e66);
                        uint _e67 = shaded;
                        shaded = (_e67 + 1u);
                    }
                }
                const uint _e75 = subcone_saturating_add(_e18.steps, 4u);
                uint _e76 = shaded;
                return uint2(_e75, (max(_e76, 1u) - 1u));
            }
        }
        const float3 _e86 = subcone_shade(hit.point_, hit.normal, ray_4.dir);
        subcone_aggregate_add(agg_2, hit.weight, _e86);
        return uint2(4u, 0u);
    }
    const float3 _e94 = subcone_shade(hit.point_, hit.normal, ray_4.dir);
    subcone_aggregate_add(agg_2, hit.weight, _e94);
    return uint2(0u, 0u);
}

subcone_SplitRay Constructsubcone_SplitRay(float3 arg0, float3 arg1, float3 arg2, float3 arg3) {
    subcone_SplitRay ret = (subcone_SplitRay)0;
    ret.origin = arg0;
    ret.dir = arg1;
    ret.right = arg2;
    ret.up = arg3;
    return ret;
}

subcone_GroupHit Constructsubcone_GroupHit(subcone_GroupSample arg0, float3 arg1, float3 arg2, uint arg3, float arg4) {
    subcone_GroupHit ret = (subcone_GroupHit)0;
    ret.sample_ = arg0;
    ret.point_ = arg1;
    ret.normal = arg2;
    ret.visible = arg3;
    ret.weight = arg4;
    return ret;
}

subcone_CtssTraceResult Constructsubcone_CtssTraceResult(float3 arg0, uint arg1, uint arg2, uint arg3, uint arg4, float arg5) {
    subcone_CtssTraceResult ret = (subcone_CtssTraceResult)0;
    ret.color = arg0;
    ret.samples = arg1;
    ret.steps = arg2;
    ret.coverage = arg3;
    ret.stop = arg4;
    ret.depth = arg5;
    return ret;
}

subcone_CtssTraceResult subcone_ctss_trace(subcone_CtssParams params_10, float3 origin_2, float3 dir_6, float3 right_3, float3 up_2, float3 background_1)
{
    subcone_ConeStepper st = (subcone_ConeStepper)0;
    subcone_Aggregate agg_3 = (subcone_Aggregate)0;
    uint extra_steps = 0u;
    uint extra_samples = 0u;
    float depth_2 = (float)0;
    bool have_depth_1 = false;
    subcone_PendingHits pending = (subcone_PendingHits)0;
    bool done = false;
    uint round_i = 0u;
    bool local_60 = (bool)0;
    uint k_3 = (uint)0;
    uint i_3 = (uint)0;
    uint mask_4 = (uint)0;
    uint j_5 = (uint)0;
    bool local_61 = (bool)0;
    uint stop_2 = (uint)0;

    subcone_SplitRay ray_5 = Constructsubcone_SplitRay(origin_2, dir_6, right_3, up_2);
    const subcone_ConeStepper _e7 = subcone_cone_stepper_new(params_10);
    st = _e7;
    const subcone_Aggregate _e9 = subcone_aggregate_new();
    agg_3 = _e9;
    const float _e15 = subcone_inf();
    depth_2 = _e15;
    uint budget = (min(params_10.max_steps, 2147483647u) + 4u);
    uint2 loop_bound_11 = uint2(4294967295u, 4294967295u);
    bool loop_init_11 = true;
    while(true) {
        if (all(loop_bound_11 == uint2(0u, 0u))) { break; }
        loop_bound_11 -= uint2(loop_bound_11.y == 0u, 1u);
        if (!loop_init_11) {
            uint _e130 = round_i;
            round_i = (_e130 + 1u);
        }
        loop_init_11 = false;
        uint _e29 = round_i;
        if ((_e29 < budget)) {
            bool _e33 = done;
            local_60 = !(_e33);
        } else {
            local_60 = false;
        }
        bool _e36 = local_60;
        if (_e36) {
        } else {
            break;
        }
        {
            k_3 = 0u;
            i_3 = 0u;
            uint2 loop_bound_12 = uint2(4294967295u, 4294967295u);
            bool loop_init_12 = true;
            while(true) {
                if (all(loop_bound_12 == uint2(0u, 0u))) { break; }
                loop_bound_12 -= uint2(loop_bound_12.y == 0u, 1u);
                if (!loop_init_12) {
                    uint _e88 = i_3;
                    i_3 = (_e88 + 1u);
                }
                loop_init_12 = false;
                uint _e41 = i_3;
                if ((_e41 < budget)) {
                } else {
                    break;
                }
                {
                    float _e44 = st.t;
                    const subcone_FieldSample _e47 = subcone_field_sample((origin_2 + (_e44 * dir_6)));
                    const subcone_CtssEvent _e51 = subcone_cone_stepper_advance_object(st, _e47.distance_, _e47.step_, _e47.object);
                    if ((_e51.kind == subcone_EVENT_STOP)) {
                        done = true;
                        break;
                    }
                    if ((_e51.kind == subcone_EVENT_SAMPLE)) {
                        subcone_GroupSample s_18 = _e51.sample_;
                        float3 point_ = (origin_2 + (s_18.t * dir_6));
                        const float _e65 = subcone_normal_step(s_18.t, params_10.tan_theta);
                        const float3 _e66 = subcone_normal(point_, _e65);
                        mask_4 = 4294967295u;
                        const bool _e69 = subcone_cone_stepper_takes_rest_of_pixel(st);
                        if (!(_e69)) {
                            const uint _e71 = subcone_group_mask(params_10, ray_5, s_18, _e66);
                            mask_4 = _e71;
                        }
                        uint _e72 = mask_4;
                        const uint2 _e73 = subcone_cone_stepper_record_mask(st, _e72);
                        uint _e75 = k_3;
                        pending.at[min(uint(_e75), 7u)] = Constructsubcone_GroupHit(s_18, point_, _e66, _e73.x, asfloat(_e73.y));
                        uint _e81 = k_3;
                        k_3 = (_e81 + 1u);
                        uint _e84 = k_3;
                        if ((_e84 >= subcone_CTSS_BATCH)) {
                            break;
                        }
                    }
                }
            }
            j_5 = 0u;
            uint2 loop_bound_13 = uint2(4294967295u, 4294967295u);
            bool loop_init_13 = true;
            while(true) {
                if (all(loop_bound_13 == uint2(0u, 0u))) { break; }
                loop_bound_13 -= uint2(loop_bound_13.y == 0u, 1u);
                if (!loop_init_13) {
                    uint _e127 = j_5;
                    j_5 = (_e127 + 1u);
                }
                loop_init_13 = false;
                uint _e92 = j_5;
                uint _e93 = k_3;
                if ((_e92 < _e93)) {
                } else {
                    break;
                }
                {
                    bool _e95 = have_depth_1;
                    if (!(_e95)) {
                        uint _e100 = j_5;
                        float _e103 = pending.at[min(uint(_e100), 7u)].weight;
                        local_61 = (_e103 > 0.0);
                    } else {
                        local_61 = false;
                    }
                    bool _e107 = local_61;
                    if (_e107) {
                        uint _e109 = j_5;
                        float _e113 = pending.at[min(uint(_e109), 7u)].sample_.t;
                        depth_2 = _e113;
                        have_depth_1 = true;
                    }
                    uint _e116 = j_5;
                    subcone_GroupHit _e118 = pending.at[min(uint(_e116), 7u)];
                    const uint2 _e119 = subcone_ctss_shade_hit(params_10, ray_5, _e118, agg_3);
                    uint _e120 = extra_steps;
                    const uint _e122 = subcone_saturating_add(_e120, _e119.x);
                    extra_steps = _e122;
                    uint _e123 = extra_samples;
                    const uint _e125 = subcone_saturating_add(_e123, _e119.y);
                    extra_samples = _e125;
                }
            }
        }
    }
    uint _e133 = st.stop;
    stop_2 = _e133;
    uint _e135 = stop_2;
    if ((_e135 == subcone_STOP_NONE)) {
        stop_2 = subcone_STOP_STEP_BUDGET;
    }
    subcone_Aggregate _e139 = agg_3;
    subcone_ConeStepper _e140 = st;
    const float _e141 = subcone_cone_stepper_background_weight(_e140);
    const float3 _e142 = subcone_aggregate_resolve(_e139, background_1, _e141);
    uint _e144 = st.samples;
    uint _e145 = extra_samples;
    const uint _e146 = subcone_saturating_add(_e144, _e145);
    uint _e148 = st.steps;
    uint _e149 = extra_steps;
    const uint _e150 = subcone_saturating_add(_e148, _e149);
    uint _e152 = st.covered;
    uint _e153 = stop_2;
    float _e154 = depth_2;
    const subcone_CtssTraceResult subcone_ctsstraceresult = Constructsubcone_CtssTraceResult(_e142, _e146, _e150, _e152, _e153, _e154);
    return subcone_ctsstraceresult;
}

subcone_CtssTraceResult subcone_pass_trace(subcone_CtssParams params_11, float3 origin_3, float3 dir_7, float3 right_4, float3 up_3, float3 background_2)
{
    const subcone_CtssTraceResult _e6 = subcone_ctss_trace(params_11, origin_3, dir_7, right_4, up_3, background_2);
    const subcone_CtssTraceResult subcone_ctsstraceresult_1 = _e6;
    return subcone_ctsstraceresult_1;
}

float4 subcone_pass_color(float3 color_1, float alpha_8)
{
    return float4(color_1, 1.0);
}

void subcone_pass_store(uint2 p_12, float4 c_4, float depth_3, uint steps_3, uint samples_1)
{
    subcone_pass_output[int2(p_12)] = c_4;
    return;
}

uint subcone_pass_index(uint2 p_13)
{
    uint _e4 = subcone_pass_frame.row_length;
    return ((p_13.y * _e4) + p_13.x);
}

float3 subcone_pass_unproject(CtssUniform f, float2 xy, float z)
{
    float4 h_6 = mul(float4(xy, z, 1.0), f.inverse_view_projection);
    return (h_6.xyz / (h_6.w).xxx);
}

typedef float3 ret_Constructarray2_float3_[2];
ret_Constructarray2_float3_ Constructarray2_float3_(float3 arg0, float3 arg1) {
    float3 ret[2] = { arg0, arg1 };
    return ret;
}

typedef float3 ret_subcone_pass_ray[2];
ret_subcone_pass_ray subcone_pass_ray(CtssUniform f_1, float2 p_14)
{
    float3 d_5 = (float3)0;

    if ((f_1.projection == 0u)) {
        const float3 _e8 = subcone_pinhole_dir(f_1.camera, p_14);
        return Constructarray2_float3_(f_1.camera.position, _e8);
    }
    float w_4 = float(max(f_1.camera.width, 1u));
    float h_7 = float(max(f_1.camera.height, 1u));
    float2 ndc = float2((((2.0 * p_14.x) / w_4) - 1.0), (1.0 - ((2.0 * p_14.y) / h_7)));
    if ((f_1.projection == 1u)) {
        const float3 _e37 = subcone_pass_unproject(f_1, ndc, 0.5);
        return Constructarray2_float3_(f_1.camera.position, normalize((_e37 - f_1.camera.position)));
    }
    const float3 _e46 = subcone_pass_unproject(f_1, ndc, 0.25);
    const float3 _e48 = subcone_pass_unproject(f_1, ndc, 0.75);
    d_5 = normalize((_e48 - _e46));
    float3 _e52 = d_5;
    if ((dot(_e52, f_1.forward) < 0.0)) {
        float3 _e57 = d_5;
        d_5 = -(_e57);
    }
    float3 _e59 = d_5;
    float3 _e64 = d_5;
    float3 o = (_e46 - (_e59 * ((dot(_e46, f_1.forward) + f_1.depth_offset) / dot(_e64, f_1.forward))));
    float3 _e70 = d_5;
    return Constructarray2_float3_(o, _e70);
}

[numthreads(8, 8, 1)]
void subcone_pass_ctss_main(uint3 gid : SV_DispatchThreadID)
{
    bool local = (bool)0;
    uint steps = 0u;
    uint samples = 0u;
    float3 sum = (0.0).xxx;
    float alpha = 0.0;
    float depth = (float)0;
    bool have_depth = false;
    uint sy = 0u;
    uint sx = (uint)0;
    bool local_1 = (bool)0;

    CtssUniform f_2 = subcone_pass_frame;
    if (!((gid.x >= f_2.camera.width))) {
        local = (gid.y >= f_2.camera.height);
    } else {
        local = true;
    }
    bool _e15 = local;
    if (_e15) {
        return;
    }
    const float _e26 = subcone_inf();
    depth = _e26;
    uint2 loop_bound_14 = uint2(4294967295u, 4294967295u);
    bool loop_init_14 = true;
    while(true) {
        if (all(loop_bound_14 == uint2(0u, 0u))) { break; }
        loop_bound_14 -= uint2(loop_bound_14.y == 0u, 1u);
        if (!loop_init_14) {
            uint _e109 = sy;
            sy = (_e109 + 1u);
        }
        loop_init_14 = false;
        uint _e32 = sy;
        if ((_e32 < subcone_pass_SIDE)) {
        } else {
            break;
        }
        {
            sx = 0u;
            uint2 loop_bound_15 = uint2(4294967295u, 4294967295u);
            bool loop_init_15 = true;
            while(true) {
                if (all(loop_bound_15 == uint2(0u, 0u))) { break; }
                loop_bound_15 -= uint2(loop_bound_15.y == 0u, 1u);
                if (!loop_init_15) {
                    uint _e106 = sx;
                    sx = (_e106 + 1u);
                }
                loop_init_15 = false;
                uint _e36 = sx;
                if ((_e36 < subcone_pass_SIDE)) {
                } else {
                    break;
                }
                {
                    uint _e38 = sx;
                    uint _e44 = sy;
                    float2 off = float2(((float(_e38) + 0.5) / float(subcone_pass_SIDE)), ((float(_e44) + 0.5) / float(subcone_pass_SIDE)));
                    const float3 _e57[2] = subcone_pass_ray(f_2, (float2(float(gid.x), float(gid.y)) + off));
                    float3 d_8 = _e57[1];
                    const float2x3 _e61 = subcone_cross_section_frame(d_8, f_2.camera.up);
                    subcone_CtssParams _e63 = subcone_pass_params;
                    const subcone_CtssTraceResult _e68 = subcone_pass_trace(_e63, _e57[0], d_8, _e61[0], _e61[1], f_2.background);
                    float3 _e69 = sum;
                    sum = (_e69 + _e68.color);
                    uint _e72 = steps;
                    steps = (_e72 + _e68.steps);
                    uint _e75 = samples;
                    samples = (_e75 + _e68.samples);
                    float _e78 = alpha;
                    const float _e81 = subcone_ctss_coverage_alpha(_e68.coverage, _e68.stop);
                    alpha = (_e78 + _e81);
                    const bool _e84 = subcone_is_finite(_e68.depth);
                    if (_e84) {
                        float z_1 = ((_e68.depth * dot(d_8, f_2.forward)) + (dot(_e57[0], f_2.forward) + f_2.depth_offset));
                        bool _e95 = have_depth;
                        if (!(!(_e95))) {
                            float _e100 = depth;
                            local_1 = (z_1 < _e100);
                        } else {
                            local_1 = true;
                        }
                        bool _e103 = local_1;
                        if (_e103) {
                            depth = z_1;
                            have_depth = true;
                        }
                    }
                }
            }
        }
    }
    float n_5 = float((subcone_pass_SIDE * subcone_pass_SIDE));
    float3 _e116 = sum;
    float _e119 = alpha;
    const float4 _e121 = subcone_pass_color((_e116 / (n_5).xxx), (_e119 / n_5));
    float _e122 = depth;
    uint _e123 = steps;
    uint _e124 = samples;
    subcone_pass_store((f_2.origin + gid.xy), _e121, _e122, _e123, _e124);
    return;
}
