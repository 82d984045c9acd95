// WGSL mirror of subcone_kernels::ao (ambient occlusion directions).
// Functions only; needs the prelude's subcone_is_finite.

// subcone_kernels::ao::GOLDEN_FRACTION
const subcone_GOLDEN_FRACTION: f32 = 0.618034;

// subcone_kernels::ao::unit_or_z: n / |n|, or +Z where |n|² is not a finite
// normal number (zero, NaN, overflowing or below f32::MIN_POSITIVE).
fn subcone_unit_or_z(n: vec3<f32>) -> vec3<f32> {
    let d = dot(n, n);
    if d >= 1.17549435e-38 && subcone_is_finite(d) {
        return n * (1.0 / sqrt(d));
    }
    return vec3<f32>(0.0, 0.0, 1.0);
}

// subcone_kernels::ao::tangent_frame — Duff et al. 2017; columns t, b, n of a
// right-handed orthonormal frame of unit(n) (+Z for a zero or non-finite n).
fn subcone_tangent_frame(n0: vec3<f32>) -> mat3x3<f32> {
    let n = subcone_unit_or_z(n0);
    var sign = 1.0;
    if (bitcast<u32>(n.z) & 0x80000000u) != 0u {
        sign = -1.0;
    }
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return mat3x3<f32>(
        vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        vec3<f32>(b, sign + n.y * n.y * a, -n.y),
        n,
    );
}

// subcone_kernels::ao::ao_direction_local — direction i of count in the
// tangent frame: stratum (i + 1/2)/count in cos²θ, golden-angle azimuth,
// Malley's cosine mapping. count 0 gives +Z; i >= count is clamped.
fn subcone_ao_direction_local(i0: u32, count: u32) -> vec3<f32> {
    if count == 0u {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    let i = min(i0, count - 1u);
    let u = (f32(i) + 0.5) / f32(count);
    let frac = f32(i) * subcone_GOLDEN_FRACTION;
    let phi = 6.2831855 * (frac - floor(frac)) - 3.1415927;
    let r = sqrt(u);
    return vec3<f32>(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u, 0.0)));
}

// subcone_kernels::ao::ao_direction — ao_direction_local turned into the
// tangent frame of n.
fn subcone_ao_direction(n: vec3<f32>, i: u32, count: u32) -> vec3<f32> {
    let f = subcone_tangent_frame(n);
    let l = subcone_ao_direction_local(i, count);
    return f[0] * l.x + f[1] * l.y + f[2] * l.z;
}

// subcone_kernels::ao::ao_fraction — unoccluded / count in [0, 1]; 1 for count 0.
fn subcone_ao_fraction(unoccluded: u32, count: u32) -> f32 {
    if count == 0u {
        return 1.0;
    }
    return f32(min(unoccluded, count)) / f32(count);
}
