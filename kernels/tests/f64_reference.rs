//! Every kernel against an f64 reference written from the papers' equations.
//! Each test prints its mean and worst error and asserts the stated bound over
//! the kernel's documented domain.
mod common;

use common::{reference as r, ulps, Lcg};
use glam::{Vec2, Vec3};
use subcone_kernels::cone::{backtrace_cone_entry, cone_occlusion, cone_tan_theta, PixelFootprint};
use subcone_kernels::mask::{visibility_mask, MaskPlacement};
use subcone_kernels::sraa::{bilateral_weight, reconstruct, Geometry, ShadedSample, SraaParams};

/// Target normal and depth, and neighbours as (normal, depth, colour, distance²).
type ReconstructCase = (Vec3, f32, Vec<(Vec3, f32, Vec3, f32)>);

fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
}
fn d3(v: Vec3) -> [f64; 3] {
    [v.x as f64, v.y as f64, v.z as f64]
}

/// A pair of geometry samples over the domain: unit normals (half of them close
/// to each other), depths log-uniform over 1e-3..1e6 with relative steps 0..50 %.
fn geometry_pair(rng: &mut Lcg) -> (Vec3, f32, Vec3, f32) {
    let ni = v3(rng.unit_vec3());
    let nj = if rng.unit() < 0.5 {
        (ni + 0.3 * v3(rng.unit_vec3())).normalize()
    } else {
        v3(rng.unit_vec3())
    };
    let zi = rng.log_range(1e-3, 1e6) as f32;
    let zj = (zi as f64 * (1.0 + rng.range(-0.5, 0.5))) as f32;
    (ni, zi, nj, zj)
}

/// The bilateral weight of the kernel under `params` against its f64 form
/// `reference(ni, zi, nj, zj)` over [`geometry_pair`]. Products and sums of
/// exps of O(1) arguments: the f32 error is a few ulps of the argument
/// propagated through exp. Bound: 2e-6 absolute.
macro_rules! weight_against_f64 {
    ($name:ident, $params:expr, $reference:expr) => {
        bound_against_f64!(
            $name,
            cases = 200_000,
            gen = geometry_pair,
            f32 = |&(ni, zi, nj, zj): &(Vec3, f32, Vec3, f32)| bilateral_weight(
                &$params,
                &Geometry::new(ni, zi),
                &Geometry::new(nj, zj)
            ),
            f64 = |&(ni, zi, nj, zj): &(Vec3, f32, Vec3, f32)| ($reference)(
                d3(ni),
                zi as f64,
                d3(nj),
                zj as f64
            ),
            err = |a: f32, b: f64| (a as f64 - b).abs(),
            bound = 2e-6,
            unit = "abs"
        );
    };
}

// Eq. 1 with the paper's σz = 10, σn = 0.25.
weight_against_f64!(bilateral_weight_eq1, SraaParams::PAPER, |ni, zi, nj, zj| {
    r::bilateral_weight(10.0, 0.25, ni, zi, nj, zj)
});
// The Chajdas form with k = 1, s = 10.
weight_against_f64!(
    bilateral_weight_chajdas,
    SraaParams::CHAJDAS,
    |ni, zi, nj, zj| { r::chajdas_weight(1.0, 10.0, ni, zi, nj, zj) }
);

// Reconstruction over a 3×3 neighbourhood: a normalised weighted mean of colours
// in [0, 1]. Bound: 1e-5 absolute per channel, whenever the f64 weight sum is
// not negligible (below 1e-6 the f32 and f64 may legitimately take different
// fallback decisions, which the stiff tests cover).
bound_against_f64!(
    reconstruct_3x3,
    cases = 50_000,
    gen = |rng: &mut Lcg| {
        let target = geometry_pair(rng);
        let mut n = Vec::new();
        for k in 0..9 {
            let (ni, zi, _, _) = geometry_pair(rng);
            let z = if rng.unit() < 0.7 {
                (target.1 as f64 * (1.0 + rng.range(-0.05, 0.05))) as f32
            } else {
                zi
            };
            let nn = if rng.unit() < 0.7 { target.0 } else { ni };
            let c = Vec3::new(rng.unit() as f32, rng.unit() as f32, rng.unit() as f32);
            n.push((nn, z, c, k as f32));
        }
        (target.0, target.1, n)
    },
    f32 = |(tn, tz, n): &ReconstructCase| {
        let r = reconstruct(
            &SraaParams::PAPER,
            &Geometry::new(*tn, *tz),
            None,
            n.iter().map(|&(nn, z, c, d2)| ShadedSample {
                geometry: Geometry::new(nn, z),
                color: c,
                shadowed: false,
                distance2: d2,
            }),
        );
        r.color
    },
    f64 = |(tn, tz, n): &ReconstructCase| {
        let mut s = [0.0f64; 3];
        let mut ws = 0.0;
        for &(nn, z, c, _) in n {
            let w = r::bilateral_weight(10.0, 0.25, d3(*tn), *tz as f64, d3(nn), z as f64);
            for a in 0..3 {
                s[a] += w * c[a] as f64;
            }
            ws += w;
        }
        (s.map(|x| x / ws), ws)
    },
    err = |a: Vec3, (b, ws): ([f64; 3], f64)| if ws < 1e-6 {
        0.0
    } else {
        (0..3)
            .map(|k| (a[k] as f64 - b[k]).abs())
            .fold(0.0, f64::max)
    },
    bound = 1e-5,
    unit = "abs"
);

// Eq. 3: one tan, one multiply, one divide. Bound: 4 ulps.
bound_against_f64!(
    cone_tan_theta_eq3,
    cases = 100_000,
    gen = |rng: &mut Lcg| (
        rng.range(0.01, 3.1) as f32,
        (rng.log_range(1.0, 16384.0)) as u32,
        rng.log_range(0.25, 8.0) as f32
    ),
    f32 = |&(fov, h, c): &(f32, u32, f32)| cone_tan_theta(fov, h, c, PixelFootprint::Circumscribed),
    f64 = |&(fov, h, c): &(f32, u32, f32)| r::tan_theta(fov as f64, h, c as f64),
    err = |a: f32, b: f64| ulps(a, b),
    bound = 4.0,
    unit = "ulp"
);

// Eq. 5 over the domain that matters, d/R_c in [−3, 3] (beyond it ω saturates):
// one division and one fma-free subtraction. Bound: 1e-6 absolute (ω is O(1);
// the ulp of 0.5 is 6e-8).
bound_against_f64!(
    cone_occlusion_eq5,
    cases = 200_000,
    gen = |rng: &mut Lcg| {
        let rc = rng.log_range(1e-6, 1e4);
        ((rng.range(-3.0, 3.0) * rc) as f32, rc as f32)
    },
    f32 = |&(d, rc): &(f32, f32)| cone_occlusion(d, rc),
    f64 = |&(d, rc): &(f32, f32)| r::occlusion(d as f64, rc as f64).clamp(-1.0, 2.0),
    err = |a: f32, b: f64| (a as f64 - b).abs(),
    bound = 1e-6,
    unit = "abs"
);

// Eq. 10: one add, one divide. Bound: 2 ulps.
bound_against_f64!(
    backtrace_eq10,
    cases = 200_000,
    gen = |rng: &mut Lcg| (
        rng.log_range(1e-4, 1e7) as f32,
        rng.log_range(1e-8, 0.1) as f32
    ),
    f32 = |&(t, tan): &(f32, f32)| backtrace_cone_entry(t, tan),
    f64 = |&(t, tan): &(f32, f32)| r::backtrace(t as f64, tan as f64),
    err = |a: f32, b: f64| ulps(a, b),
    bound = 2.0,
    unit = "ulp"
);

/// Where the f32 and f64 masks may disagree: cell centres this close to the
/// line (in units of the unit disk; the cell pitch is ≈ 0.31). The f32 test
/// rounds `(3/s)·h` and two products of magnitude ≤ 2.5, a few 1e-7.
const MASK_NEAR: f64 = 1e-5;

/// The worst "distance" of a differing cell's centre from the f64 line, or
/// 1.0 (far above [`MASK_NEAR`]) where one row differs in more than one cell.
fn mask_error((a, omega, np): (u32, f64, [f64; 2]), b: u32) -> f64 {
    let diff = a ^ b;
    if diff == 0 {
        return 0.0;
    }
    const ROWS: [(u32, u32); 6] = [(0, 4), (4, 6), (10, 6), (16, 6), (22, 6), (28, 4)];
    if ROWS
        .iter()
        .any(|&(shift, len)| ((diff >> shift) & ((1 << len) - 1)).count_ones() > 1)
    {
        return 1.0;
    }
    let len = (np[0] * np[0] + np[1] * np[1]).sqrt();
    let dir = [np[0] / len, np[1] / len];
    let h = -(1.0 - 2.0 * omega) / len.min(1.0);
    (0..32)
        .filter(|bit| diff >> bit & 1 == 1)
        .map(|bit| {
            let (x, y) = r::cell_centre(bit);
            (x * dir[0] + y * dir[1] - h).abs()
        })
        .fold(0.0, f64::max)
}

// The mask in f32 against the same rasterisation in f64: a cell may differ
// only where its centre lies within MASK_NEAR of the line (so, with rows
// 0.31 apart along the line's normal at most, at most one cell per row).
// The error is the largest such distance (1.0 for two cells of one row);
// the printed mean shows how rare any difference is.
bound_against_f64!(
    visibility_mask_bits,
    cases = 200_000,
    gen = |rng: &mut Lcg| {
        let n = rng.unit_vec3();
        (rng.range(-0.2, 1.2), [n[0], n[1]])
    },
    f32 = |&(omega, np): &(f64, [f64; 2])| (
        visibility_mask(
            omega as f32,
            Vec2::new(np[0] as f32, np[1] as f32),
            MaskPlacement::Derived
        ),
        omega as f32 as f64,
        [np[0] as f32 as f64, np[1] as f32 as f64]
    ),
    f64 = |&(omega, np): &(f64, [f64; 2])| r::derived_mask(
        omega as f32 as f64,
        [np[0] as f32 as f64, np[1] as f32 as f64]
    ),
    err = mask_error,
    bound = MASK_NEAR,
    unit = "from the line"
);
