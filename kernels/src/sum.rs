//! A weighted colour sum accumulated in f64.
//!
//! Products `w·C` of f32 weights and colours leave f32's normal range when both
//! are small (a weight of 1e-18 times a colour of 1e-28), and the normalised
//! result then drifts outside the convex hull of the inputs. In f64 every such
//! product of f32 values is exact enough (f64's exponent range covers the
//! square of f32's), so `Σ w·C / Σ w` stays inside the hull. The cost is nil on
//! CPUs; GPU ports without f64 document the difference in the subnormal range.

use glam::Vec3;

use crate::sraa::NEGLIGIBLE_WEIGHT;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct WeightedSum {
    sum: [f64; 3],
    weight: f64,
}

impl WeightedSum {
    pub(crate) const ZERO: Self = Self {
        sum: [0.0; 3],
        weight: 0.0,
    };

    #[inline]
    pub(crate) fn add(&mut self, w: f32, c: Vec3) {
        let w64 = w as f64;
        self.sum[0] += w64 * c.x as f64;
        self.sum[1] += w64 * c.y as f64;
        self.sum[2] += w64 * c.z as f64;
        self.weight += w64;
    }

    #[inline]
    pub(crate) fn weight(&self) -> f32 {
        self.weight as f32
    }

    /// `Σ w·C / Σ w`, or `None` when the weight is negligible or the mean is not
    /// finite in f32.
    #[inline]
    pub(crate) fn mean(&self) -> Option<Vec3> {
        if !(self.weight >= NEGLIGIBLE_WEIGHT as f64) {
            return None;
        }
        let inv = 1.0 / self.weight;
        let c = Vec3::new(
            (self.sum[0] * inv) as f32,
            (self.sum[1] * inv) as f32,
            (self.sum[2] * inv) as f32,
        );
        c.is_finite().then_some(c)
    }
}

/// Four [`WeightedSum`]s side by side, one per lane: the four subsamples of a
/// pixel accumulating one layer from the same neighbours. Each lane is the
/// same f64 arithmetic as [`WeightedSum::add`] and [`WeightedSum::mean`], so
/// to the same bits, and keeps the same convex-hull guarantee; laid out by
/// channel so that the four lanes of a channel are one multiply-add.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct WeightedSum4 {
    sum: [[f64; 4]; 3],
    weight: [f64; 4],
}

impl WeightedSum4 {
    pub(crate) const ZERO: Self = Self {
        sum: [[0.0; 4]; 3],
        weight: [0.0; 4],
    };

    /// Lane `k` adds `w[k]·c`, as [`WeightedSum::add`] (`w[k]` an f32 weight
    /// widened). `c` must be finite
    /// (a zero weight times a non-finite colour is NaN): the caller skips
    /// non-finite colours, as the scalar reconstruction does.
    #[inline]
    #[allow(clippy::needless_range_loop)]
    pub(crate) fn add(&mut self, w: [f64; 4], c: Vec3) {
        let c = [c.x as f64, c.y as f64, c.z as f64];
        for ch in 0..3 {
            let s = &mut self.sum[ch];
            s[0] += w[0] * c[ch];
            s[1] += w[1] * c[ch];
            s[2] += w[2] * c[ch];
            s[3] += w[3] * c[ch];
        }
        let s = &mut self.weight;
        s[0] += w[0];
        s[1] += w[1];
        s[2] += w[2];
        s[3] += w[3];
    }

    /// Lane `k`'s mean, as [`WeightedSum::mean`].
    #[inline]
    pub(crate) fn mean(&self, k: usize) -> Option<Vec3> {
        WeightedSum {
            sum: [self.sum[0][k], self.sum[1][k], self.sum[2][k]],
            weight: self.weight[k],
        }
        .mean()
    }
}
