//! CTSS's cone kernels: the cone, its occlusion, the march's step and the
//! backtrace.

use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, cone_tan_theta,
    min_step, PixelFootprint,
};

use super::rng::special_pairs;
use super::rng::{Rng, GENERATED};
use super::tolerance::*;
use super::words::{out, R, W};
use super::KernelVectors;
use super::NO_REFERENCE;

pub(super) const CONE_TAN_THETA: KernelVectors = KernelVectors {
    name: "cone_tan_theta",
    inputs: "fov_y:f32 height:u32 coverage:f32 footprint:u32",
    outputs: "tan_theta:f32",
    tolerance: TOL_CONE_TAN_THETA,
    tolerance_constant: "TOL_CONE_TAN_THETA",
    non_finite: "coverage * r * 2 tan(fov_y/2) / height, r the footprint's radius in pixels (footprint 0: circumscribed, 1/sqrt(2); 1: balanced, 2/(2 + sqrt(2)); 2: inscribed, 1/2; other codes are not generated). Domain: fov_y in (0, pi), height >= 1, coverage > 0, all finite. Outside it (and where the result is not finite) returns 0.",
    reference: "f64: coverage * r * 2 tan(fov_y/2) / height on the domain, within TOL_CONE_TAN_THETA (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        let (fov, h, cov) = (r.f(), r.u(), r.f());
        let fp = match r.u() {
            1 => PixelFootprint::Balanced,
            2 => PixelFootprint::Inscribed,
            _ => PixelFootprint::Circumscribed,
        };
        out(&[cone_tan_theta(fov, h, cov, fp)])
    },
    generate: |rng| {
        let heights = [0u32, 1, 2, 480, 512, 1080, 2160, u32::MAX];
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let h = if rng.below(4) == 0 {
                    rng.pick(&heights)
                } else {
                    1 + rng.below(8192)
                };
                W::default()
                    .f(rng.any_f32(0.0, 3.2))
                    .u(h)
                    .f(rng.any_f32(0.0, 4.0))
                    .u(rng.below(3))
                    .0
            })
            .collect();
        v.extend(special_pairs().map(|(a, b)| W::default().f(a).u(512).f(b).u(0).0));
        v
    },
};

pub(super) const CONE_RADIUS: KernelVectors = KernelVectors {
    name: "cone_radius",
    inputs: "t:f32 tan_theta:f32",
    outputs: "r_c:f32",
    tolerance: TOL_CONE,
    tolerance_constant: "TOL_CONE",
    non_finite: "t * tan_theta when both are > 0, else 0. Domain: t >= 0, tan_theta >= 0. Negative, zero or NaN inputs give 0 (a point); +inf propagates (inf * tan_theta).",
    reference: "f64: t * tan_theta rounded once, for t, tan_theta > 0 finite, within TOL_CONE (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[cone_radius(r.f(), r.f())])
    },
    generate: |rng| cone_pairs(rng, (0.0, 1e3), (0.0, 0.01)),
};

pub(super) const CONE_OCCLUSION: KernelVectors = KernelVectors {
    name: "cone_occlusion",
    inputs: "d:f32 r_c:f32",
    outputs: "omega:f32",
    tolerance: TOL_OCCLUSION,
    tolerance_constant: "TOL_OCCLUSION",
    non_finite: "(1 - d/r_c)/2, clamped to [-1, 2]. Domain: d finite, r_c > 0 finite. r_c <= 0 or NaN: the limit, -1 for d > 0, 2 for d < 0, 0.5 for d = 0; d = +inf gives -1, d = -inf gives 2, d = NaN gives -1; r_c = +inf with finite d gives 0.5. Never NaN or infinite.",
    reference: "f64: (1 - d/r_c)/2 for d/r_c in [-3, 3], r_c > 0 finite, within 1e-6 absolute, the f64 bound of kernels/tests/f64_reference.rs (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[cone_occlusion(r.f(), r.f())])
    },
    generate: |rng| cone_pairs(rng, (-1.0, 1.0), (0.0, 10.0)),
};

pub(super) const MIN_STEP: KernelVectors = KernelVectors {
    name: "min_step",
    inputs: "alpha:f32 r_c:f32",
    outputs: "s_min:f32",
    tolerance: TOL_CONE,
    tolerance_constant: "TOL_CONE",
    non_finite: "alpha * r_c. Domain: alpha in (0, 1], r_c >= 0. NaN or negative products give 0.",
    reference: "f64: alpha * r_c rounded once, for positive finite inputs, within TOL_CONE (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[min_step(r.f(), r.f())])
    },
    generate: |rng| cone_pairs(rng, (0.0, 1.0), (0.0, 10.0)),
};

pub(super) const ADVANCE: KernelVectors = KernelVectors {
    name: "advance",
    inputs: "t:f32 d:f32 alpha:f32 r_c:f32",
    outputs: "t_next:f32",
    tolerance: TOL_CONE,
    tolerance_constant: "TOL_CONE",
    non_finite: "t + max(d, alpha * r_c), promoted to the next float above t when the sum rounds back to t. Domain: finite t >= 0. A NaN d steps by alpha * r_c (then by one ulp); the result is > t for every finite t, and +inf only when the step is.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        out(&[advance(r.f(), r.f(), r.f(), r.f())])
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                W::default()
                    .f(rng.any_f32(0.0, 1e3))
                    .f(rng.any_f32(-1.0, 1.0))
                    .f(rng.any_f32(0.0, 1.0))
                    .f(rng.any_f32(0.0, 10.0))
                    .0
            })
            .collect();
        for _ in 0..512 {
            let t = rng.awkward();
            let d = rng.awkward();
            let rc = rng.awkward().abs();
            v.push(W::default().f(t).f(d).f(0.5).f(rc).0);
        }
        v.extend(special_pairs().map(|(t, d)| W::default().f(t).f(d).f(0.5).f(1e-3).0));
        v
    },
};

pub(super) const BACKTRACE_CONE_ENTRY: KernelVectors = KernelVectors {
    name: "backtrace_cone_entry",
    inputs: "t_i:f32 tan_theta:f32",
    outputs: "t_s:f32",
    tolerance: TOL_CONE,
    tolerance_constant: "TOL_CONE",
    non_finite: "t_i / (1 + tan_theta) (eq. 9-10). Domain: t_i >= 0, tan_theta >= 0, finite. Returns a value in [0, t_i]; a NaN or negative tan_theta returns t_i, a NaN t_i returns 0.",
    reference: "f64: t_i / (1 + tan_theta) on the domain, within TOL_CONE (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[backtrace_cone_entry(r.f(), r.f())])
    },
    generate: |rng| cone_pairs(rng, (0.0, 1e3), (0.0, 0.01)),
};

pub(super) const BACKTRACE_HARD_HIT: KernelVectors = KernelVectors {
    name: "backtrace_hard_hit",
    inputs: "t_prev:f32 d_prev:f32 t_i:f32",
    outputs: "t_s:f32",
    tolerance: TOL_CONE,
    tolerance_constant: "TOL_CONE",
    non_finite: "t_prev + d_prev (section 3.6), clamped to [t_prev, t_i]. Domain: t_prev <= t_i, d_prev >= 0. A non-Eikonal or negative d_prev cannot push the result past t_i or behind t_prev; a NaN d_prev returns t_prev.",
    reference: "f64: min(max(t_prev + d_prev, t_prev), t_i) rounded once, on finite inputs with t_prev <= t_i, within TOL_CONE (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[backtrace_hard_hit(r.f(), r.f(), r.f())])
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let t = rng.any_f32(0.0, 1e3);
                let d = rng.any_f32(-1.0, 1.0);
                let rc = rng.any_f32(0.0, 10.0);
                W::default().f(t).f(d).f(t + rc).0
            })
            .collect();
        for _ in 0..512 {
            let (t, d, ti) = (rng.awkward(), rng.awkward(), rng.awkward());
            v.push(W::default().f(t).f(d).f(ti).0);
        }
        v.extend(special_pairs().map(|(t, d)| W::default().f(t).f(d).f(1.0).0));
        v
    },
};

/// Two-input cone kernels: generated over the two domains, 512 awkward pairs
/// (signed, log-uniform, specials; the second non-negative), and every pair
/// of [`SPECIALS`](super::grids::SPECIALS).
fn cone_pairs(rng: &mut Rng, a: (f32, f32), b: (f32, f32)) -> Vec<Vec<u32>> {
    let mut v: Vec<Vec<u32>> = (0..GENERATED)
        .map(|_| {
            W::default()
                .f(rng.any_f32(a.0, a.1))
                .f(rng.any_f32(b.0, b.1))
                .0
        })
        .collect();
    for _ in 0..512 {
        let (x, y) = (rng.awkward(), rng.awkward().abs());
        v.push(W::default().f(x).f(y).0);
    }
    v.extend(special_pairs().map(|(x, y)| W::default().f(x).f(y).0));
    v
}
