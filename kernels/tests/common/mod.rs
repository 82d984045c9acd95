//! Shared test support: f64 reference implementations of every kernel, and the
//! macro that bounds each f32 kernel against its reference.
#![allow(dead_code)]

/// Run `$cases` deterministic pseudo-random inputs through an f32 kernel and its
/// f64 reference, print the worst error, and assert it is within `$bound`.
///
/// `$gen` maps a `&mut Lcg` to an input tuple; `$f32`/`$f64` map the input to a
/// value; `$err` maps `(f32 result, f64 result)` to an error figure.
#[macro_export]
macro_rules! bound_against_f64 {
    ($name:ident, cases = $cases:expr, gen = $gen:expr, f32 = $f32:expr, f64 = $f64:expr, err = $err:expr, bound = $bound:expr, unit = $unit:expr) => {
        #[test]
        fn $name() {
            let mut rng = $crate::common::Lcg::new(0x5eed ^ line!() as u64);
            let mut worst = 0.0f64;
            let mut worst_input = None;
            let mut sum = 0.0f64;
            for _ in 0..$cases {
                let input = ($gen)(&mut rng);
                let a = ($f32)(&input);
                let b = ($f64)(&input);
                let e: f64 = ($err)(a, b);
                assert!(e.is_finite(), "{}: non-finite error for {:?}: f32 {:?} f64 {:?}", stringify!($name), input, a, b);
                sum += e;
                if e > worst {
                    worst = e;
                    worst_input = Some(format!("{:?} -> f32 {:?}, f64 {:?}", input, a, b));
                }
            }
            println!(
                "[f32 vs f64] {:<28} cases {:>7}  mean {:.3e} {}  max {:.3e} {}  (bound {:.1e})  worst: {}",
                stringify!($name),
                $cases,
                sum / $cases as f64,
                $unit,
                worst,
                $unit,
                $bound,
                worst_input.unwrap_or_default()
            );
            assert!(worst <= $bound, "{}: worst error {:e} exceeds {:e}", stringify!($name), worst, $bound);
        }
    };
}

/// A small deterministic generator (PCG-like LCG), so figures are reproducible.
pub struct Lcg(u64);

impl Lcg {
    pub fn new(seed: u64) -> Self {
        Lcg(seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407))
    }
    pub fn next_u32(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) as u32
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.next_u32() as f64 / (1u64 << 31) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Log-uniform in [lo, hi], lo > 0.
    pub fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }
    /// A uniformly distributed unit vector.
    pub fn unit_vec3(&mut self) -> [f64; 3] {
        loop {
            let v = [
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            ];
            let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if l2 > 1e-6 && l2 <= 1.0 {
                let l = l2.sqrt();
                return [v[0] / l, v[1] / l, v[2] / l];
            }
        }
    }
}

/// Units in the last place of an f32 between an f32 result and an f64 reference,
/// measured in ulps of the reference rounded to f32.
pub fn ulps(a: f32, b: f64) -> f64 {
    let r = b as f32;
    let ulp = (r.abs().next_up() - r.abs()) as f64;
    ((a as f64) - b).abs() / ulp.max(f32::from_bits(1) as f64)
}

/// f64 reference implementations, written from the papers' equations, not from
/// the f32 code.
pub mod reference {
    /// G(x) = exp(−x²).
    pub fn gaussian(x: f64) -> f64 {
        (-(x * x)).exp()
    }
    pub fn sat(x: f64) -> f64 {
        x.clamp(0.0, 1.0)
    }
    /// Eq. 1 with the relative depth metric.
    pub fn bilateral_weight(sz: f64, sn: f64, ni: [f64; 3], zi: f64, nj: [f64; 3], zj: f64) -> f64 {
        let dz = (zj - zi).abs() / (0.5 * (zi.abs() + zj.abs()));
        let dz = if zi == zj { 0.0 } else { dz };
        let dot = ni[0] * nj[0] + ni[1] * nj[1] + ni[2] * nj[2];
        gaussian(sz * dz) * gaussian(sn * (1.0 - sat(dot)))
    }
    /// Chajdas' form with the relative depth metric.
    pub fn chajdas_weight(k: f64, s: f64, ni: [f64; 3], zi: f64, nj: [f64; 3], zj: f64) -> f64 {
        let dz = if zi == zj {
            0.0
        } else {
            (zj - zi).abs() / (0.5 * (zi.abs() + zj.abs()))
        };
        let dot = ni[0] * nj[0] + ni[1] * nj[1] + ni[2] * nj[2];
        (-s * (1.0 - sat(dot)).max(k * dz)).exp()
    }
    /// Eq. 3 from §3.1's geometry: half the pixel diagonal over unit distance.
    pub fn tan_theta(fov_y: f64, height: u32, coverage: f64) -> f64 {
        let pixel = 2.0 * (0.5 * fov_y).tan() / height as f64;
        coverage * pixel * std::f64::consts::SQRT_2 / 2.0
    }
    /// Eq. 5.
    pub fn occlusion(d: f64, rc: f64) -> f64 {
        (1.0 - d / rc) / 2.0
    }
    /// Eq. 10.
    pub fn backtrace(t: f64, tan: f64) -> f64 {
        t / (1.0 + tan)
    }
    /// Area fraction of the unit disk on the side {q·dir < h}.
    pub fn disk_fraction_below(h: f64) -> f64 {
        if h <= -1.0 {
            return 0.0;
        }
        if h >= 1.0 {
            return 1.0;
        }
        1.0 - (h.acos() - h * (1.0 - h * h).sqrt()) / std::f64::consts::PI
    }
    /// The mask rasterisation of the derived placement, in f64.
    pub fn derived_mask(omega: f64, np: [f64; 2]) -> u32 {
        let len = (np[0] * np[0] + np[1] * np[1]).sqrt();
        if len == 0.0 {
            return if omega >= 0.5 { u32::MAX } else { 0 };
        }
        let dir = [np[0] / len, np[1] / len];
        let h = -(1.0 - 2.0 * omega) / len.min(1.0);
        half_plane_mask(dir, h)
    }
    /// Cell-centre rasterisation of {q·dir < h}, in f64, cell by cell.
    pub fn half_plane_mask(dir: [f64; 2], h: f64) -> u32 {
        let mut m = 0;
        for bit in 0..32 {
            let (x, y) = cell_centre(bit);
            if x * dir[0] + y * dir[1] < h {
                m |= 1 << bit;
            }
        }
        m
    }
    /// The layout of Fig. 6b as documented in `mask.rs`.
    pub fn cell_centre(bit: u32) -> (f64, f64) {
        let (row, col) = match bit {
            0..=3 => (0, bit + 1),
            4..=27 => (1 + (bit - 4) / 6, (bit - 4) % 6),
            _ => (5, bit - 28 + 1),
        };
        let s = (9.0 * std::f64::consts::PI / 32.0).sqrt();
        (
            s * ((2 * col + 1) as f64 / 6.0 - 1.0),
            s * ((2 * row + 1) as f64 / 6.0 - 1.0),
        )
    }
}
