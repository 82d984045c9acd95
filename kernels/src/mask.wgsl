// WGSL mirror of subcone_kernels::mask (CTSS §3.4–3.5, Fig. 6, eq. 7–8).
// Needs cone.wgsl (subcone_is_nan, subcone_is_finite).

// subcone_kernels::mask::GRID_SCALE: √(9π/32), the 32 cells have the disk's area.
const GRID_SCALE: f32 = 0.9399856f;
// subcone_kernels::mask::FARTHEST_CENTRE
const FARTHEST_CENTRE: f32 = GRID_SCALE * 0.9718253f;

// subcone_kernels::mask::MaskPlacement codes.
const MASK_DERIVED: u32 = 0u;
const MASK_AUTHORS_CODE: u32 = 1u;
const MASK_PAPER_EQ8: u32 = 2u;

// subcone_kernels::mask::project_normal — n_p = (n·right, n·up) of the unit normal.
fn project_normal(normal: vec3<f32>, right: vec3<f32>, up: vec3<f32>) -> vec2<f32> {
    let a = abs(normal);
    let m = max(max(a.x, a.y), a.z);
    if !(m > 0.0) || !subcone_is_finite(m) {
        return vec2<f32>(0.0);
    }
    var n = normal / m;
    n = n * (1.0 / sqrt(dot(n, n)));
    let p = vec2<f32>(dot(n, right), dot(n, up));
    if subcone_is_finite(p.x) && subcone_is_finite(p.y) {
        return p;
    }
    return vec2<f32>(0.0);
}

// subcone_kernels::mask::occlusion_to_distance — d/R_c = 1 − 2ω (eq. 5 inverted).
fn occlusion_to_distance(omega: f32) -> f32 {
    return 1.0 - 2.0 * omega;
}

// subcone_kernels::mask::half_plane — the covered half-plane q·dir < h;
// returns (dir, h, 1) or (0, 0, 0, 0) for None.
fn half_plane(occlusion: f32, projected_normal: vec2<f32>, placement: u32) -> vec4<f32> {
    let len = length(projected_normal);
    if !(len > 0.0) || !subcone_is_finite(len) {
        return vec4<f32>(0.0);
    }
    let dir = projected_normal / len;
    let delta = occlusion_to_distance(occlusion);
    var h: f32;
    if placement == MASK_AUTHORS_CODE {
        h = -delta;
    } else if placement == MASK_PAPER_EQ8 {
        h = delta * min(len, 1.0);
    } else {
        h = -delta / min(len, 1.0);
    }
    if subcone_is_nan(h) {
        h = -2.0;
    } else {
        h = clamp(h, -2.0, 2.0);
    }
    return vec4<f32>(dir, h, 1.0);
}

// subcone_kernels::mask::centres_below — cell centres of a 6-wide row left of x.
fn centres_below(x: f32) -> u32 {
    let v = ceil((3.0f / GRID_SCALE) * clamp(x, -2.0, 2.0) + 2.5);
    return u32(clamp(v, 0.0, 6.0));
}

// subcone_kernels::mask::half_plane_mask — rasterise q·dir < h on the 32-cell grid.
fn half_plane_mask(dir: vec2<f32>, h: f32) -> u32 {
    var mask = 0u;
    for (var r = 0u; r < 6u; r++) {
        var y: f32;
        switch r {
            case 0u: { y = (-5.0f / 6.0f) * GRID_SCALE; }
            case 1u: { y = -0.5f * GRID_SCALE; }
            case 2u: { y = (-1.0f / 6.0f) * GRID_SCALE; }
            case 3u: { y = (1.0f / 6.0f) * GRID_SCALE; }
            case 4u: { y = 0.5f * GRID_SCALE; }
            default: { y = (5.0f / 6.0f) * GRID_SCALE; }
        }
        let rhs = h - y * dir.y;
        var row6: u32;
        if abs(dir.x) < 1e-6 {
            row6 = select(0u, 0x3fu, 0.0 < rhs);
        } else {
            let x = rhs / dir.x;
            if dir.x > 0.0 {
                let k = centres_below(x);
                row6 = (1u << k) - 1u;
            } else {
                let k = centres_below(-x);
                row6 = 0x3fu & ~((1u << (6u - k)) - 1u);
            }
        }
        var row = row6;
        var shift: u32;
        switch r {
            case 0u: { shift = 0u; }
            case 1u: { shift = 4u; }
            case 2u: { shift = 10u; }
            case 3u: { shift = 16u; }
            case 4u: { shift = 22u; }
            default: { shift = 28u; }
        }
        if r == 0u || r == 5u {
            row = (row6 >> 1u) & 0xfu;
        }
        mask |= row << shift;
    }
    return mask;
}

// subcone_kernels::mask::visibility_mask — eq. 7–8 (Derived placement by default).
fn visibility_mask(occlusion: f32, projected_normal: vec2<f32>, placement: u32) -> u32 {
    if subcone_is_nan(occlusion) {
        return 0u;
    }
    let hp = half_plane(occlusion, projected_normal, placement);
    if hp.w > 0.0 {
        return half_plane_mask(hp.xy, hp.z);
    }
    if occlusion >= 0.5 {
        return 0xffffffffu;
    }
    return 0u;
}

// subcone_kernels::mask::needs_normal — whether the mask depends on the normal.
fn needs_normal(occlusion: f32, placement: u32) -> bool {
    if subcone_is_nan(occlusion) {
        return false;
    }
    let delta = occlusion_to_distance(occlusion);
    if placement == MASK_PAPER_EQ8 {
        return true;
    }
    return abs(delta) < FARTHEST_CENTRE;
}

// subcone_kernels::mask::mask_weight — bitCount(m)/32.
fn mask_weight(mask: u32) -> f32 {
    return f32(countOneBits(mask)) * (1.0 / 32.0);
}
