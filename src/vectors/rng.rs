//! The seeded generator of the cases, and what every kernel's generator
//! shares.

use glam::Vec3;

use super::grids::SPECIALS;

/// A deterministic generator (SplitMix64): the same seed, the same cases, on
/// every machine.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub(super) fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in `[0, n)`.
    pub(super) fn below(&mut self, n: u32) -> u32 {
        (self.next() % n as u64) as u32
    }

    pub(super) fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let x = lo + (hi - lo) * self.unit();
        if x < hi {
            x
        } else {
            lo
        }
    }

    pub(super) fn bits(&mut self) -> u32 {
        self.next() as u32
    }

    /// Values from every part of f32, as the conformance suite draws them:
    /// two thirds uniform over `[lo, hi)` (the kernel's domain), a ninth a
    /// special value ([`SPECIALS`]), two ninths any bits at all.
    pub(super) fn any_f32(&mut self, lo: f32, hi: f32) -> f32 {
        match self.below(9) {
            0..=5 => self.range(lo, hi),
            6 => SPECIALS[self.below(SPECIALS.len() as u32) as usize],
            _ => f32::from_bits(self.bits()),
        }
    }

    /// Signed, log-uniform over 1e-3..1e3, every fifth a special.
    pub(super) fn awkward(&mut self) -> f32 {
        if self.below(5) == 0 {
            SPECIALS[self.below(SPECIALS.len() as u32) as usize]
        } else {
            (self.unit() * 2.0 - 1.0) * 10f32.powf(self.unit() * 6.0 - 3.0)
        }
    }

    /// Mostly unit vectors, a ninth any vector (non-finite included).
    pub(super) fn unit_vec(&mut self) -> Vec3 {
        if self.below(9) < 8 {
            let v = Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            v.try_normalize().unwrap_or(Vec3::Z)
        } else {
            Vec3::new(
                self.any_f32(-2.0, 2.0),
                self.any_f32(-2.0, 2.0),
                self.any_f32(-2.0, 2.0),
            )
        }
    }

    pub(super) fn colour(&mut self, hi: f32) -> Vec3 {
        Vec3::new(
            self.any_f32(0.0, hi),
            self.any_f32(0.0, hi),
            self.any_f32(0.0, hi),
        )
    }

    pub(super) fn pick<T: Copy>(&mut self, v: &[T]) -> T {
        v[self.below(v.len() as u32) as usize]
    }
}

/// Generated cases per kernel, before its fixed grids.
pub(super) const GENERATED: usize = 1024;

/// Every pair of [`SPECIALS`].
pub(super) fn special_pairs() -> impl Iterator<Item = (f32, f32)> {
    SPECIALS
        .iter()
        .flat_map(|&a| SPECIALS.iter().map(move |&b| (a, b)))
}
