//! The program's lanes: eight `f32`s as one value (`F8`), their masks
//! (`W8`) and points (`V3`), each operation the scalar one lane by lane, and
//! the primitives and bounds on them.

use core::ops::{Add, Div, Mul, Neg, Sub};

use glam::{Quat, Vec3};

use subcone_scene::sdf::lane::{self, Lane};
use subcone_scene::sdf::{Aabb, Shape};

use super::{LaneMask, LANES};
// ------------------------------------------------------------------ lanes

/// `[e(0), e(1), …, e(7)]`: an expression per lane, written out. Not a loop
/// (`for` or `core::array::from_fn`): the interpreter inlines thousands of
/// lane-wise operations, and as loops each was a loop for LLVM's loop passes
/// to rotate and unroll before vectorising, a cost that grew with the
/// interpreter's size (loop rotation alone was two thirds of the CPU
/// backend's build). Written out, the eight operations are straight-line code
/// that the SLP vectoriser packs into one vector operation, as the unrolled
/// loops were: the same operations lane by lane, so the same bits.
macro_rules! each_lane {
    (|$k:pat_param| $e:expr) => {{
        const _: () = assert!(LANES == 8);
        [
            {
                let $k = 0usize;
                $e
            },
            {
                let $k = 1usize;
                $e
            },
            {
                let $k = 2usize;
                $e
            },
            {
                let $k = 3usize;
                $e
            },
            {
                let $k = 4usize;
                $e
            },
            {
                let $k = 5usize;
                $e
            },
            {
                let $k = 6usize;
                $e
            },
            {
                let $k = 7usize;
                $e
            },
        ]
    }};
}

/// [`lanewise!`] as a loop, for the operations with a branch per lane
/// (glam's `min`/`max`, `clamp`, the cell rounding): the few of them cost
/// the build little, and as loops they run fewer instructions than written
/// out (measured on the AVX2 path: `primitives` 1 % fewer in all).
macro_rules! lanewise_loop {
    ($a:expr, |$k:ident| $e:expr) => {{
        let mut r = [0.0f32; LANES];
        for $k in 0..LANES {
            r[$k] = $e;
        }
        F8(r)
    }};
}

macro_rules! lanewise {
    ($a:expr, |$k:ident| $e:expr) => {{
        F8(each_lane!(|$k| $e))
    }};
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
pub(super) struct F8(pub(super) [f32; LANES]);

/// A lane mask.
pub(super) type M8 = W8;

/// A lane mask as the vector units hold one: each lane all ones or all
/// zeros. The hot union instructions use it; `[bool; 8]` masks make LLVM
/// pack and unpack bytes at every step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
pub(super) struct W8(pub(super) [u32; LANES]);

impl W8 {
    /// The lanes of `bits`.
    #[inline(always)]
    pub(super) fn of_bits(bits: LaneMask) -> W8 {
        W8(each_lane!(|k| {
            0u32.wrapping_sub(((bits >> k) & 1) as u32)
        }))
    }
    /// Lane-wise `cond`.
    #[inline(always)]
    pub(super) fn from_fn(cond: impl Fn(usize) -> bool) -> W8 {
        W8(each_lane!(|k| 0u32.wrapping_sub(cond(k) as u32)))
    }
    #[inline(always)]
    pub(super) fn and(self, o: W8) -> W8 {
        W8(each_lane!(|k| self.0[k] & o.0[k]))
    }
    #[inline(always)]
    pub(super) fn and_not(self, o: W8) -> W8 {
        W8(each_lane!(|k| self.0[k] & !o.0[k]))
    }
    /// Whether any lane is set.
    #[inline(always)]
    pub(super) fn any(self) -> bool {
        let w = self.0;
        ((w[0] | w[1]) | (w[2] | w[3])) | ((w[4] | w[5]) | (w[6] | w[7])) != 0
    }
    /// The lanes as bits.
    #[inline(always)]
    pub(super) fn bits(self) -> LaneMask {
        let w = self.0;
        let bit = |k: usize| ((w[k] & 1) as LaneMask) << k;
        ((bit(0) | bit(1)) | (bit(2) | bit(3))) | ((bit(4) | bit(5)) | (bit(6) | bit(7)))
    }
    /// `a` in the set lanes, `b` elsewhere, bit for bit.
    #[inline(always)]
    pub(super) fn select(self, a: F8, b: F8) -> F8 {
        F8(each_lane!(|k| {
            f32::from_bits((a.0[k].to_bits() & self.0[k]) | (b.0[k].to_bits() & !self.0[k]))
        }))
    }
    /// [`select`](W8::select) for materials.
    #[inline(always)]
    pub(super) fn select_u(self, a: [u32; LANES], b: [u32; LANES]) -> [u32; LANES] {
        each_lane!(|k| (a[k] & self.0[k]) | (b[k] & !self.0[k]))
    }
}

impl F8 {
    /// glam's vector `min`: `if a < b { a } else { b }`.
    #[inline(always)]
    pub(super) fn gmin(self, o: F8) -> F8 {
        lanewise_loop!(self, |k| if self.0[k] < o.0[k] {
            self.0[k]
        } else {
            o.0[k]
        })
    }
    #[inline(always)]
    pub(super) fn ge(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] >= o.0[k])
    }
}

macro_rules! binop {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F8 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: F8) -> F8 {
                lanewise!(self, |k| self.0[k] $op o.0[k])
            }
        }
        impl $tr<f32> for F8 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: f32) -> F8 {
                lanewise!(self, |k| self.0[k] $op o)
            }
        }
        impl $tr<F8> for f32 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: F8) -> F8 {
                lanewise!(o, |k| self $op o.0[k])
            }
        }
    };
}
binop!(Add, add, +);
binop!(Sub, sub, -);
binop!(Mul, mul, *);
binop!(Div, div, /);

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        lanewise!(self, |k| -self.0[k])
    }
}

/// The primitives' operations ([`subcone_scene::sdf::lane`]) on eight lanes:
/// each the `f32` operation of [`Lane for f32`](lane::Lane), lane by lane.
impl Lane for F8 {
    type Mask = M8;
    #[inline(always)]
    fn splat(v: f32) -> F8 {
        F8([v; LANES])
    }
    /// Rust's `f32::min` (NaN-ignoring), lane-wise.
    #[inline(always)]
    fn min(self, o: F8) -> F8 {
        lanewise!(self, |k| self.0[k].min(o.0[k]))
    }
    /// Rust's `f32::max`, lane-wise.
    #[inline(always)]
    fn max(self, o: F8) -> F8 {
        lanewise!(self, |k| self.0[k].max(o.0[k]))
    }
    /// glam's vector `max`: `if a > b { a } else { b }`.
    #[inline(always)]
    fn gmax(self, o: F8) -> F8 {
        lanewise_loop!(self, |k| if self.0[k] > o.0[k] {
            self.0[k]
        } else {
            o.0[k]
        })
    }
    /// Rust's `f32::clamp`.
    #[inline(always)]
    fn clamp(self, lo: F8, hi: F8) -> F8 {
        lanewise_loop!(self, |k| {
            let mut v = self.0[k];
            if v < lo.0[k] {
                v = lo.0[k];
            }
            if v > hi.0[k] {
                v = hi.0[k];
            }
            v
        })
    }
    #[inline(always)]
    fn abs(self) -> F8 {
        lanewise!(self, |k| self.0[k].abs())
    }
    #[inline(always)]
    fn sqrt(self) -> F8 {
        lanewise!(self, |k| self.0[k].sqrt())
    }
    #[inline(always)]
    fn lt(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] < o.0[k])
    }
    #[inline(always)]
    fn gt(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] > o.0[k])
    }
    #[inline(always)]
    fn eq(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] == o.0[k])
    }
    #[inline(always)]
    fn is_finite(self) -> M8 {
        W8::from_fn(|k| self.0[k].is_finite())
    }
    #[inline(always)]
    fn and(a: M8, b: M8) -> M8 {
        a.and(b)
    }
    #[inline(always)]
    fn or(a: M8, b: M8) -> M8 {
        W8(each_lane!(|k| a.0[k] | b.0[k]))
    }
    #[inline(always)]
    fn select(m: M8, a: F8, b: F8) -> F8 {
        m.select(a, b)
    }
}

/// Three coordinates of eight lanes, with glam's `Vec3` semantics.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct V3 {
    pub(super) x: F8,
    pub(super) y: F8,
    pub(super) z: F8,
}

impl V3 {
    #[inline(always)]
    pub(super) fn new(x: F8, y: F8, z: F8) -> V3 {
        V3 { x, y, z }
    }
    #[inline(always)]
    pub(super) fn splat(v: Vec3) -> V3 {
        V3::new(F8::splat(v.x), F8::splat(v.y), F8::splat(v.z))
    }
    #[inline(always)]
    pub(super) fn sub(self, o: V3) -> V3 {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
    #[inline(always)]
    pub(super) fn mul(self, o: V3) -> V3 {
        V3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }
    #[inline(always)]
    pub(super) fn scale(self, s: F8) -> V3 {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
    #[inline(always)]
    pub(super) fn dot(self, o: V3) -> F8 {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }
    #[inline(always)]
    pub(super) fn length(self) -> F8 {
        self.dot(self).sqrt()
    }
    /// glam's `max`.
    #[inline(always)]
    pub(super) fn gmax(self, o: V3) -> V3 {
        V3::new(self.x.gmax(o.x), self.y.gmax(o.y), self.z.gmax(o.z))
    }
    /// glam's `max(Vec3::ZERO)`.
    #[inline(always)]
    pub(super) fn pos(self) -> V3 {
        self.gmax(V3::splat(Vec3::ZERO))
    }
    /// glam's `Quat * Vec3` (SSE2): `v(w² − b·b) + b(2 v·b) + (b × v)(2w)`.
    #[inline(always)]
    pub(super) fn rotate(self, q: Quat) -> V3 {
        self.rotate_lanes([
            F8::splat(q.x),
            F8::splat(q.y),
            F8::splat(q.z),
            F8::splat(q.w),
        ])
    }
    /// [`V3::rotate`] by a different quaternion per lane.
    #[inline(always)]
    pub(super) fn rotate_lanes(self, q: [F8; 4]) -> V3 {
        let [bx, by, bz, w] = q;
        let b2 = (bx * bx + by * by) + bz * bz;
        let ww = w * w - b2;
        let vb2 = ((self.x * bx + self.y * by) + self.z * bz) * 2.0;
        let w2 = w * 2.0;
        // b × v, as glam's SSE2 `cross` forms it.
        let cx = by * self.z - self.y * bz;
        let cy = bz * self.x - self.z * bx;
        let cz = bx * self.y - self.x * by;
        V3::new(
            (self.x * ww + bx * vb2) + cx * w2,
            (self.y * ww + by * vb2) + cy * w2,
            (self.z * ww + bz * vb2) + cz * w2,
        )
    }
}

// ------------------------------------------------------------------ shapes

/// `Shape::distance`, lane-wise: the one definition of the primitives
/// ([`subcone_scene::sdf::lane`]), on eight lanes.
#[inline(always)]
pub(super) fn shape_distance(shape: &Shape, p: V3) -> F8 {
    lane::shape_distance(shape, p.x, p.y, p.z)
}

/// `Aabb::distance`, lane-wise.
#[inline(always)]
pub(super) fn aabb_distance(b: &Aabb, p: V3) -> F8 {
    V3::splat(b.min)
        .sub(p)
        .gmax(p.sub(V3::splat(b.max)))
        .pos()
        .length()
}

/// `round_cell` (`⌊x + ½⌋` through a truncation to `i64`), lane-wise and
/// bit for bit, with `floor` (one instruction from SSE4.1 on): below `2²³`
/// in magnitude the two agree but for the sign of a zero; from there on every
/// `f32` is an integer, which the scalar form returns as is up to its `i64`
/// saturation at `±2⁶³`; NaN gives 0 in both.
#[inline(always)]
pub(super) fn round_cell(x: F8) -> F8 {
    const BIG: f32 = 8_388_608.0; // 2²³
    const SAT: f32 = 9_223_372_036_854_775_808.0; // 2⁶³
    lanewise_loop!(x, |k| {
        let f = x.0[k] + 0.5;
        // Below 2²³ the truncation then the step down is `floor`, but for
        // `−0`, which the truncation makes `+0` (and `+ 0.0` too).
        let small = f.floor() + 0.0;
        let large = f.clamp(-SAT, SAT);
        if f.abs() < BIG {
            small
        } else if f.is_nan() {
            0.0
        } else {
            large
        }
    })
}
