//! Ambient occlusion directions: the shading-cost axis of the report's
//! "Where SRAA pays" section (not from either paper).
//!
//! A shaded point casts `count` any-hit occlusion rays over a fixed radius
//! ([`AO_RADIUS_FRACTION`] of the scene's bounding diagonal). The directions
//! are one fixed, stratified, cosine-weighted set per `count`
//! ([`ao_direction_local`]), turned into the tangent frame of the normal
//! ([`tangent_frame`]), the same at every point: ambient occlusion is a
//! deterministic, noise-free function of position and normal, so no
//! antialiasing method is credited for denoising it. The backends multiply
//! the scene's ambient term by the unoccluded fraction ([`ao_fraction`]).
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::ao::{ao_direction, ao_fraction};
//!
//! let n = Vec3::Y;
//! for i in 0..16 {
//!     let d = ao_direction(n, i, 16);
//!     assert!((d.length() - 1.0).abs() < 1e-5 && d.dot(n) > 0.0);
//! }
//! assert_eq!(ao_fraction(12, 16), 0.75);
//! assert_eq!(ao_fraction(0, 0), 1.0); // no rays: nothing is occluded
//! ```

use glam::Vec3;

/// The WGSL mirror of this module (`subcone_tangent_frame`,
/// `subcone_ao_direction_local`, `subcone_ao_direction`,
/// `subcone_ao_fraction`).
pub const WGSL: &str = include_str!("ao.wgsl");

/// The occlusion radius as a fraction of the scene's bounding-box diagonal.
/// A tenth: long enough that corners, the feet of columns and the gaps
/// between objects darken over several pixels at the report's sizes, short
/// enough that an open floor stays unoccluded (a radius of the whole scene
/// would make AO a second, global shadow term instead of a local one).
pub const AO_RADIUS_FRACTION: f32 = 0.1;

/// Most occlusion rays per shaded point a render accepts
/// (`RenderSettings::validate`): 4× the report's largest sweep value, 64.
pub const MAX_AO_RAYS: u32 = 256;

/// `φ − 1`, the golden ratio's fractional part: the azimuth of direction `i`
/// is `2π·fract(i·(φ − 1))` (the Fibonacci spiral, whose successive angles
/// never repeat and fill the circle evenly for any count).
pub const GOLDEN_FRACTION: f32 = 0.618_034;

/// An orthonormal tangent frame `(t, b)` of the unit normal `n`, so that
/// `(t, b, n)` is right-handed (Duff et al., "Building an Orthonormal
/// Basis, Revisited", 2017: branchless, continuous except where `n.z`
/// changes sign).
///
/// Input domain: a unit `n`. A finite `n` of any other length is normalised
/// first. An `n` whose squared length is not a finite normal `f32` (zero,
/// NaN, infinite, overflowing, or `|n| < 1.1e-19`) is replaced by `+Z`,
/// giving `(X, Y)`: the result is always finite, never NaN.
pub fn tangent_frame(n: Vec3) -> (Vec3, Vec3) {
    let n = unit_or_z(n);
    let sign = if n.z.is_sign_negative() { -1.0 } else { 1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// `n / |n|`, or `+Z` where `|n|²` is not a finite normal number (zero,
/// NaN, overflowing, or below `f32::MIN_POSITIVE`, where a GPU that flushes
/// subnormals would see zero).
fn unit_or_z(n: Vec3) -> Vec3 {
    let d = n.dot(n);
    if d >= f32::MIN_POSITIVE && d.is_finite() {
        n * (1.0 / crate::math::sqrt(d))
    } else {
        Vec3::Z
    }
}

/// Direction `i` of the fixed set of `count` occlusion directions, in the
/// tangent frame (`z` along the normal): stratified in `cos²θ` (stratum
/// `i` of `count`, at its centre, `u = (i + ½)/count`) with the golden-angle
/// azimuth [`GOLDEN_FRACTION`], mapped to the hemisphere by Malley's method
/// (`r = √u` on the disk, `z = √(1 − u)`), so the set is cosine-weighted:
/// the unoccluded fraction estimates the cosine-weighted visibility that
/// ambient light is integrated with.
///
/// Input domain: `i < count ≤ MAX_AO_RAYS` ([`MAX_AO_RAYS`]). Outside it:
/// `count == 0` gives `+Z` (the normal); `i ≥ count` is clamped to
/// `count − 1`. The result is always a finite unit vector (within
/// rounding) with `z > 0`.
pub fn ao_direction_local(i: u32, count: u32) -> Vec3 {
    if count == 0 {
        return Vec3::Z;
    }
    let i = i.min(count - 1);
    let u = (i as f32 + 0.5) / count as f32;
    let frac = i as f32 * GOLDEN_FRACTION;
    // In [−π, π): WGSL bounds sin and cos there (2^-11 absolute).
    let phi = core::f32::consts::TAU * (frac - libm::floorf(frac)) - core::f32::consts::PI;
    let r = crate::math::sqrt(u);
    Vec3::new(
        r * libm::cosf(phi),
        r * libm::sinf(phi),
        crate::math::sqrt((1.0 - u).max(0.0)),
    )
}

/// Direction `i` of `count` around the normal `n`: [`ao_direction_local`]
/// turned into [`tangent_frame`]`(n)`. The same `(n, i, count)` gives the
/// same direction at every point.
///
/// Input domain: as [`tangent_frame`] (a zero or non-finite `n` is `+Z`) and
/// [`ao_direction_local`] (`count == 0` gives the normal, `i` is clamped).
/// The result is always finite.
pub fn ao_direction(n: Vec3, i: u32, count: u32) -> Vec3 {
    let (t, b) = tangent_frame(n);
    let l = ao_direction_local(i, count);
    t * l.x + b * l.y + unit_or_z(n) * l.z
}

/// The unoccluded fraction, `unoccluded / count`, in `[0, 1]`: what the
/// ambient term is multiplied by.
///
/// Input domain: `unoccluded ≤ count`. `count == 0` (ambient occlusion off)
/// gives exactly 1; `unoccluded > count` is clamped to 1.
pub fn ao_fraction(unoccluded: u32, count: u32) -> f32 {
    if count == 0 {
        return 1.0;
    }
    unoccluded.min(count) as f32 / count as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_and_right_handed() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.0, 0.0, -0.0),
            Vec3::new(1.0, 2.0, -3.0),
            Vec3::new(1e-3, 0.0, -1.0),
        ] {
            let (t, b) = tangent_frame(n);
            let n = unit_or_z(n);
            assert!((t.length() - 1.0).abs() < 1e-6, "{n}");
            assert!((b.length() - 1.0).abs() < 1e-6, "{n}");
            assert!(t.dot(b).abs() < 1e-6 && t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6);
            assert!((t.cross(b) - n).length() < 1e-5, "{n}: {t} × {b}");
        }
    }

    #[test]
    fn non_finite_normals_give_finite_directions() {
        for n in [
            Vec3::ZERO,
            Vec3::NAN,
            Vec3::new(f32::INFINITY, 0.0, 0.0),
            Vec3::splat(f32::MAX),
            Vec3::splat(1e-30),
        ] {
            for i in [0, 3, 7, 1000] {
                let d = ao_direction(n, i, 8);
                assert!(
                    d.is_finite() && (d.length() - 1.0).abs() < 1e-5,
                    "{n} {i}: {d}"
                );
            }
        }
    }

    #[test]
    fn the_set_is_cosine_weighted_and_stratified() {
        for count in [1, 4, 16, 64, 256] {
            let mut mean_z = 0.0f64;
            for i in 0..count {
                let d = ao_direction_local(i, count);
                assert!(d.z > 0.0 && (d.length() - 1.0).abs() < 1e-5);
                // Stratum i of count in cos²θ = 1 − u.
                let u = 1.0 - d.z * d.z;
                assert!(u >= i as f32 / count as f32 - 1e-5);
                assert!(u <= (i + 1) as f32 / count as f32 + 1e-5);
                mean_z += d.z as f64 / count as f64;
            }
            // E[cos θ] under the cosine density is 2/3.
            if count >= 16 {
                assert!((mean_z - 2.0 / 3.0).abs() < 5e-3, "{count}: {mean_z}");
            }
        }
        assert_eq!(ao_direction_local(0, 0), Vec3::Z);
        assert_eq!(ao_direction_local(99, 4), ao_direction_local(3, 4));
    }

    #[test]
    fn fraction_is_in_unit_range() {
        assert_eq!(ao_fraction(0, 0), 1.0);
        assert_eq!(ao_fraction(5, 0), 1.0);
        assert_eq!(ao_fraction(0, 4), 0.0);
        assert_eq!(ao_fraction(4, 4), 1.0);
        assert_eq!(ao_fraction(9, 4), 1.0);
    }
}
