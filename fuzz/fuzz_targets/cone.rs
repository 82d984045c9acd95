//! Cone kernels (eq. 3–5, 9–10, §3.6) on arbitrary f32.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius,
    cone_tan_theta, min_step, OcclusionThresholds, PixelFootprint, OCCLUSION_MAX, OCCLUSION_MIN,
};

#[derive(Arbitrary, Debug)]
struct Input {
    fov_y: f32,
    height: u32,
    coverage: f32,
    footprint: u8,
    t: f32,
    tan_theta: f32,
    d1: f32,
    d2: f32,
    rc: f32,
    alpha: f32,
    t_prev: f32,
    d_prev: f32,
    t_i: f32,
    eps: f32,
}

fn ulp(t: f32) -> f32 {
    t.next_up() - t
}

fn check_occlusion(d: f32, rc: f32) -> f32 {
    let w = cone_occlusion(d, rc);
    assert!(
        (OCCLUSION_MIN..=OCCLUSION_MAX).contains(&w),
        "cone_occlusion({d:e}, {rc:e}) = {w} outside [{OCCLUSION_MIN}, {OCCLUSION_MAX}]"
    );
    w
}

fuzz_target!(|x: Input| {
    // Eq. 3: finite, non-negative, 0 outside the domain.
    let footprint = match x.footprint % 3 {
        0 => PixelFootprint::Circumscribed,
        1 => PixelFootprint::Balanced,
        _ => PixelFootprint::Inscribed,
    };
    let tan_px = cone_tan_theta(x.fov_y, x.height, x.coverage, footprint);
    assert!(
        tan_px.is_finite() && tan_px >= 0.0,
        "cone_tan_theta({}, {}, {}, {footprint:?}) = {tan_px}",
        x.fov_y,
        x.height,
        x.coverage
    );

    // Eq. 4.
    let r = cone_radius(x.t, x.tan_theta);
    assert!(r >= 0.0, "cone_radius({}, {}) = {r}", x.t, x.tan_theta);
    if x.t.is_finite() && x.tan_theta.is_finite() && x.t > 0.0 && x.tan_theta > 0.0 {
        assert!(r == x.t * x.tan_theta);
    }

    // Eq. 5: saturated range, never NaN, monotone non-increasing in d.
    for rc in [x.rc, r, 0.0, -0.0, f32::INFINITY, f32::NAN, f32::MIN_POSITIVE] {
        let w1 = check_occlusion(x.d1, rc);
        let w2 = check_occlusion(x.d2, rc);
        if !x.d1.is_nan() && !x.d2.is_nan() {
            let (lo, hi, wlo, whi) = if x.d1 <= x.d2 {
                (x.d1, x.d2, w1, w2)
            } else {
                (x.d2, x.d1, w2, w1)
            };
            assert!(
                wlo >= whi,
                "cone_occlusion not monotone at rc = {rc:e}: ω({lo:e}) = {wlo} < ω({hi:e}) = {whi}"
            );
        }
    }
    let th = OcclusionThresholds::with_eps(x.eps);
    if x.eps.is_finite() {
        assert!(th.soft <= th.hard && th.hard <= th.full);
    }

    // Minimum step.
    let s = min_step(x.alpha, x.rc);
    assert!(s >= 0.0, "min_step({}, {}) = {s}", x.alpha, x.rc);

    // The step rule always progresses for finite t.
    for t in [x.t, x.t.abs(), x.t_prev] {
        let next = advance(t, x.d1, x.alpha, x.rc);
        if t.is_finite() {
            assert!(
                next > t,
                "advance({t:e}, {:e}, {:e}, {:e}) = {next:e} does not progress",
                x.d1,
                x.alpha,
                x.rc
            );
        } else {
            assert!(next == f32::INFINITY || next > t, "advance({t}) = {next}");
        }
        assert!(!next.is_nan(), "advance({t}) = NaN");
    }

    // Eq. 9–10: in [0, t], strictly below t once the cone is wider than an ulp.
    for (t, tan) in [
        (x.t, x.tan_theta),
        (x.t.abs(), x.tan_theta.abs()),
        (x.t_i.abs(), tan_px),
    ] {
        let ts = backtrace_cone_entry(t, tan);
        assert!(!ts.is_nan(), "backtrace_cone_entry({t}, {tan}) = NaN");
        if t.is_finite() && t >= 0.0 && tan.is_finite() && tan >= 0.0 {
            assert!(
                ts >= 0.0 && ts <= t,
                "backtrace_cone_entry({t:e}, {tan:e}) = {ts:e} not in [0, t]"
            );
            if t * tan > ulp(t) {
                assert!(
                    ts < t,
                    "backtrace_cone_entry({t:e}, {tan:e}) = {ts:e} not strictly below t (t·tan = {:e}, ulp = {:e})",
                    t * tan,
                    ulp(t)
                );
            }
        }
        if tan.is_nan() || tan < 0.0 {
            if t > 0.0 {
                assert!(ts == t, "backtrace_cone_entry({t}, {tan}) = {ts}, expected t");
            }
        }
    }

    // §3.6: clamped to [t_prev, t_i].
    let th = backtrace_hard_hit(x.t_prev, x.d_prev, x.t_i);
    if x.t_prev.is_finite() && x.d_prev.is_finite() && x.t_i.is_finite() && x.t_prev <= x.t_i {
        assert!(
            th >= x.t_prev && th <= x.t_i,
            "backtrace_hard_hit({:e}, {:e}, {:e}) = {th:e} outside [t_prev, t_i]",
            x.t_prev,
            x.d_prev,
            x.t_i
        );
    }
    if x.d_prev.is_nan() {
        assert!(th.to_bits() == x.t_prev.to_bits());
    }
    if !x.t_prev.is_nan() && !x.t_i.is_nan() && x.t_prev <= x.t_i {
        assert!(!th.is_nan(), "backtrace_hard_hit = NaN");
    }
});
