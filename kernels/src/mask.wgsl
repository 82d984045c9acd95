// WGSL mirror of subcone_kernels::mask (CTSS §3.4–3.5, Fig. 6, eq. 7–8).
// Needs cone.wgsl (subcone_is_nan, subcone_is_finite).

// subcone_kernels::mask::GRID_SCALE: √(9π/32), the 32 cells have the disk's area.
const subcone_GRID_SCALE: f32 = 0.9399856f;
// subcone_kernels::mask::FARTHEST_CENTRE
const subcone_FARTHEST_CENTRE: f32 = subcone_GRID_SCALE * 0.9718253f;

// subcone_kernels::mask::MaskPlacement codes.
// subcone_kernels::mask::FULL_MASK: every cell.
const subcone_FULL_MASK: u32 = 0xffffffffu;

const subcone_MASK_DERIVED: u32 = 0u;
const subcone_MASK_AUTHORS_CODE: u32 = 1u;
const subcone_MASK_PAPER_EQ8: u32 = 2u;

// subcone_kernels::mask::project_normal — n_p = (n·right, n·up) of the unit normal.
fn subcone_project_normal(normal: vec3<f32>, right: vec3<f32>, up: vec3<f32>) -> vec2<f32> {
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
fn subcone_occlusion_to_distance(omega: f32) -> f32 {
    return 1.0 - 2.0 * omega;
}

// subcone_kernels::mask::half_plane — the covered half-plane q·dir < h;
// returns (dir, h, 1) or (0, 0, 0, 0) for None.
fn subcone_half_plane(occlusion: f32, projected_normal: vec2<f32>, placement: u32) -> vec4<f32> {
    let len = length(projected_normal);
    if !(len > 0.0) || !subcone_is_finite(len) {
        return vec4<f32>(0.0);
    }
    let dir = projected_normal / len;
    let delta = subcone_occlusion_to_distance(occlusion);
    var h: f32;
    if placement == subcone_MASK_AUTHORS_CODE {
        h = -delta;
    } else if placement == subcone_MASK_PAPER_EQ8 {
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

// subcone_kernels::mask::CELL_XY — centre of the cell held by `bit`, in units
// of s/3: (c − 2.5, r − 2.5) (Fig. 6b layout: rows 0 and 5 hold columns 1–4).
fn subcone_mask_cell_xy(bit: u32) -> vec2<f32> {
    var r: u32;
    var c: u32;
    if bit < 4u {
        r = 0u;
        c = bit + 1u;
    } else if bit < 28u {
        r = 1u + (bit - 4u) / 6u;
        c = (bit - 4u) % 6u;
    } else {
        r = 5u;
        c = bit - 27u;
    }
    return vec2<f32>(f32(c) - 2.5, f32(r) - 2.5);
}

// subcone_kernels::mask::half_plane_mask — rasterise q·dir < h on the 32-cell grid.
// Cell (r, c) is covered when (c − 2.5)·dx + (r − 2.5)·dy < (3/s)·h (centres
// (s/3)·(c − 2.5, r − 2.5)); no division. |dx| < 1e-6 counts as 0 (rows all
// or nothing, §3.5).
fn subcone_half_plane_mask(dir: vec2<f32>, h: f32) -> u32 {
    let dx = select(dir.x, 0.0, abs(dir.x) < 1e-6);
    let hs = (3.0 / subcone_GRID_SCALE) * h;
    var mask = 0u;
    for (var bit = 0u; bit < 32u; bit++) {
        let q = subcone_mask_cell_xy(bit);
        if q.x * dx + q.y * dir.y < hs {
            mask |= 1u << bit;
        }
    }
    return mask;
}

// subcone_kernels::mask::visibility_mask — eq. 7–8 (Derived placement by default).
fn subcone_visibility_mask(occlusion: f32, projected_normal: vec2<f32>, placement: u32) -> u32 {
    if subcone_is_nan(occlusion) {
        return 0u;
    }
    let hp = subcone_half_plane(occlusion, projected_normal, placement);
    if hp.w > 0.0 {
        return subcone_half_plane_mask(hp.xy, hp.z);
    }
    if occlusion >= 0.5 {
        return 0xffffffffu;
    }
    return 0u;
}

// subcone_kernels::mask::needs_normal — whether the mask depends on the normal.
fn subcone_needs_normal(occlusion: f32, placement: u32) -> bool {
    if subcone_is_nan(occlusion) {
        return false;
    }
    let delta = subcone_occlusion_to_distance(occlusion);
    if placement == subcone_MASK_PAPER_EQ8 {
        return true;
    }
    return abs(delta) < subcone_FARTHEST_CENTRE;
}

// subcone_kernels::mask::mask_weight — bitCount(m)/32.
fn subcone_mask_weight(mask: u32) -> f32 {
    return f32(countOneBits(mask)) * (1.0 / 32.0);
}
