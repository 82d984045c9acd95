//! Square roots the way every instruction-set path of a renderer needs them.
//!
//! **Why this module exists.** glam's `libm` feature (which this `no_std`
//! crate needs) routes `Vec2`/`Vec3` [`length`](glam::Vec3::length),
//! `normalize` and friends through `libm::sqrtf`, and libm's x86 `sqrtf` is
//! inline assembly: a legacy-SSE `sqrtss`. Inline assembly is never re-encoded
//! as VEX, so when a renderer inlines these calls into code compiled for AVX2
//! or AVX-512 (the CPU backend's instruction-set paths), a legacy-SSE
//! instruction runs while the upper halves of the vector registers are dirty.
//! Intel cores pay a state-transition or merge penalty on every such
//! instruction (measured: 72× on a loop of square roots on a Xeon with
//! AVX-512); AMD Zen cores barely do.
//!
//! With the `std` feature, [`sqrt`] is `f32::sqrt`, which LLVM lowers to
//! `sqrtss` on baseline x86-64, `vsqrtss` inside AVX code and a packed
//! `vsqrtps` where it vectorises. Without it (the `no_std` build), it is
//! `libm::sqrtf`. **Both are correctly rounded IEEE square roots, so every
//! result is bit-identical with and without the feature and on every path.**
//! Transcendental functions stay libm's everywhere: they are not correctly
//! rounded, and a platform libm would change images between machines.
//!
//! [`Euclidean`] gives `Vec2`/`Vec3` the lengths and normalisations of glam
//! with the same operations in the same order (so the same bits) through
//! [`sqrt`]. Renderer code uses these, never glam's own; the CI step that
//! disassembles the release binary's instruction-set paths fails on any
//! legacy-SSE instruction left there.
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::math::{sqrt, Euclidean};
//!
//! assert_eq!(sqrt(9.0), 3.0);
//! let v = Vec3::new(3.0, 0.0, 4.0);
//! assert_eq!(v.norm(), 5.0);
//! assert_eq!(v.unit(), Vec3::new(0.6, 0.0, 0.8));
//! assert_eq!(Vec3::ZERO.unit_or_zero(), Vec3::ZERO);
//! ```

use glam::{Vec2, Vec3};

/// The correctly rounded square root of `x`.
///
/// Domain: every `f32`. `sqrt(−0) = −0`, `sqrt(+∞) = +∞`, and a negative
/// number or NaN gives NaN, as IEEE 754 requires of both implementations.
#[inline(always)]
pub fn sqrt(x: f32) -> f32 {
    #[cfg(feature = "std")]
    {
        x.sqrt()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::sqrtf(x)
    }
}

/// Euclidean length and normalisation of `Vec2` and `Vec3` through [`sqrt`]:
/// glam's `length`, `length_recip`, `distance`, `normalize`, `normalize_or`,
/// `normalize_or_zero` and `try_normalize`, operation for operation, so
/// results are bit-identical to glam's.
///
/// Domain: as glam's. A zero, infinite or NaN vector makes [`unit`] return
/// non-finite lanes (as `normalize` does); [`unit_or`], [`unit_or_zero`] and
/// [`try_unit`] return their fallback for those instead.
///
/// [`unit`]: Euclidean::unit
/// [`unit_or`]: Euclidean::unit_or
/// [`unit_or_zero`]: Euclidean::unit_or_zero
/// [`try_unit`]: Euclidean::try_unit
pub trait Euclidean: Copy + Sized {
    /// The dot product with itself (glam's `length_squared`).
    fn norm_squared(self) -> f32;
    /// Every lane times `s`.
    fn scaled(self, s: f32) -> Self;
    /// The zero vector.
    const ZERO_VECTOR: Self;

    /// The length (glam's `length`).
    #[inline(always)]
    fn norm(self) -> f32 {
        sqrt(self.norm_squared())
    }

    /// `1 / length` (glam's `length_recip`): `+∞` for the zero vector.
    #[inline(always)]
    fn norm_recip(self) -> f32 {
        1.0 / self.norm()
    }

    /// The vector scaled to unit length (glam's `normalize`); non-finite for
    /// a zero, infinite or NaN vector.
    #[inline(always)]
    fn unit(self) -> Self {
        self.scaled(self.norm_recip())
    }

    /// The unit vector, or `None` when `1 / length` is not finite and
    /// positive (glam's `try_normalize`).
    #[inline(always)]
    fn try_unit(self) -> Option<Self> {
        let rcp = self.norm_recip();
        if rcp.is_finite() && rcp > 0.0 {
            Some(self.scaled(rcp))
        } else {
            None
        }
    }

    /// The unit vector, or `fallback` where [`try_unit`](Euclidean::try_unit)
    /// gives `None` (glam's `normalize_or`).
    #[inline(always)]
    fn unit_or(self, fallback: Self) -> Self {
        self.try_unit().unwrap_or(fallback)
    }

    /// The unit vector, or zero (glam's `normalize_or_zero`).
    #[inline(always)]
    fn unit_or_zero(self) -> Self {
        self.unit_or(Self::ZERO_VECTOR)
    }
}

/// One implementation for both vector types: what differs is only the type.
macro_rules! euclidean {
    ($($vector:ty),*) => {$(
        impl Euclidean for $vector {
            const ZERO_VECTOR: Self = <$vector>::ZERO;

            #[inline(always)]
            fn norm_squared(self) -> f32 {
                self.dot(self)
            }

            #[inline(always)]
            fn scaled(self, s: f32) -> Self {
                self * s
            }
        }
    )*};
}

euclidean!(Vec2, Vec3);

/// The distance between two points (glam's `distance`).
#[inline(always)]
pub fn distance<V: Euclidean + core::ops::Sub<Output = V>>(a: V, b: V) -> f32 {
    (a - b).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same bits as glam's methods (which go through `libm::sqrtf` in
    /// this build) on awkward inputs: tiny, huge, zero, non-finite.
    /// The same bits, or NaN on both sides (a NaN's payload is not part of
    /// any result: constant folding may choose another one).
    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn bit_identical_to_glam() {
        let vals = [
            0.0f32,
            -0.0,
            1e-30,
            -3.5,
            0.1,
            7.0,
            1e20,
            f32::MAX,
            f32::MIN_POSITIVE,
            f32::INFINITY,
            f32::NAN,
        ];
        let same3 = |a: Vec3, b: Vec3| same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z);
        // Through `black_box`, so the hardware computes what LLVM could fold.
        let vals = core::hint::black_box(vals);
        for &x in &vals {
            assert!(same(sqrt(x), libm::sqrtf(x)), "sqrt({x})");
            for &y in &vals {
                for &z in &vals[..5] {
                    let v = Vec3::new(x, y, z);
                    assert!(same(v.norm(), v.length()), "{v}");
                    assert!(same3(v.unit(), v.normalize()), "{v}");
                    assert!(same3(v.unit_or_zero(), v.normalize_or_zero()), "{v}");
                    assert_eq!(v.try_unit().is_some(), v.try_normalize().is_some(), "{v}");
                    if let (Some(a), Some(b)) = (v.try_unit(), v.try_normalize()) {
                        assert!(same3(a, b), "{v}");
                    }
                    let w = Vec2::new(x, y);
                    assert!(same(w.norm(), w.length()), "{w}");
                    let (u, g) = (w.unit(), w.normalize());
                    assert!(same(u.x, g.x) && same(u.y, g.y), "{w}");
                    assert!(same(distance(v, Vec3::ONE), v.distance(Vec3::ONE)), "{v}");
                }
            }
        }
    }
}
