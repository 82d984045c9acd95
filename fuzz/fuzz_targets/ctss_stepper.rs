//! The CTSS stepper (Algorithm 1) driven over planes, spheres, non-Eikonal
//! spheres and replayed raw distances, with fuzzed object ids and the
//! paper's flag, plus `trace_field` and `sphere_trace`.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{unit, v3, Hull};
use glam::{Vec2, Vec3};
use libfuzzer_sys::fuzz_target;
use subcone_kernels::aggregate::Weighting;
use subcone_kernels::cone::{OCCLUSION_MAX, OCCLUSION_MIN};
use subcone_kernels::ctss::{
    cross_section_frame, group_mask, normal_step, sphere_trace, trace_field, ConeField,
    ConeStepper, CtssParams, Event, FieldSample, SplitRay, StopReason, FLAG_RELAXED, NO_OBJECT,
};

/// The harness's cap on the step budget.
const MAX_STEPS: u32 = 4096;

#[derive(Arbitrary, Debug, Clone)]
enum Sdf {
    /// `n̂·p + offset`.
    Plane { normal: [f32; 3], offset: f32 },
    /// A sphere centred `along` the ray and `offset` to its right.
    Sphere { along: f32, offset: f32, radius: f32 },
    /// The same sphere's distance times 0.2 (under-estimating, still safe) or
    /// 5 (over-estimating: not Eikonal, steps overshoot).
    Scaled {
        along: f32,
        offset: f32,
        radius: f32,
        big: bool,
    },
    /// Raw distances, replayed in order and cycled.
    Replay(Vec<f32>),
}

#[derive(Arbitrary, Debug)]
struct Input {
    tan_theta: f32,
    alpha: Option<f32>,
    eps: Option<f32>,
    range: Option<(f32, f32)>,
    authors_min_weight: bool,
    max_steps: u32,
    max_samples: u32,
    visibility_k: u32,
    relaxed: bool,
    paper: bool,
    /// Object ids of successive evaluations (cycled; empty: none known).
    objects: Vec<u8>,
    placement: u32,
    weighting: u32,
    dir: [f32; 3],
    sdf: Sdf,
    analytic_normal: bool,
    normal: [f32; 3],
    palette: Vec<[f32; 3]>,
    background: [f32; 3],
}

/// An SDF closure state: replay position for `Sdf::Replay`.
struct Scene {
    sdf: Sdf,
    dir: Vec3,
    right: Vec3,
    cursor: usize,
}

impl Scene {
    fn centre(&self, along: f32, offset: f32) -> Vec3 {
        along * self.dir + offset * self.right
    }

    fn distance(&mut self, p: Vec3) -> f32 {
        match &self.sdf {
            Sdf::Plane { normal, offset } => {
                let n = unit(v3(*normal)).unwrap_or(Vec3::NEG_Z);
                n.dot(p) + offset
            }
            &Sdf::Sphere {
                along,
                offset,
                radius,
            } => (p - self.centre(along, offset)).length() - radius,
            &Sdf::Scaled {
                along,
                offset,
                radius,
                big,
            } => {
                let d = (p - self.centre(along, offset)).length() - radius;
                d * if big { 5.0 } else { 0.2 }
            }
            Sdf::Replay(ds) => {
                if ds.is_empty() {
                    return f32::NAN;
                }
                let d = ds[self.cursor % ds.len()];
                self.cursor += 1;
                d
            }
        }
    }

    fn analytic_normal(&self, p: Vec3) -> Vec3 {
        match &self.sdf {
            Sdf::Plane { normal, .. } => unit(v3(*normal)).unwrap_or(Vec3::NEG_Z),
            &Sdf::Sphere { along, offset, .. } | &Sdf::Scaled { along, offset, .. } => {
                p - self.centre(along, offset)
            }
            Sdf::Replay(_) => -self.dir,
        }
    }
}

/// The scene as the kernels' trace reads it: distances, the fuzzed object
/// ids (cycled per evaluation) and the harness's normal.
struct Field<'a> {
    scene: Scene,
    objects: &'a [u8],
    calls: usize,
    analytic: bool,
    raw_normal: Vec3,
}

impl ConeField for Field<'_> {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        let d = self.scene.distance(p);
        let object = if self.objects.is_empty() {
            NO_OBJECT
        } else {
            self.objects[self.calls % self.objects.len()] as u32
        };
        self.calls += 1;
        FieldSample {
            distance: d,
            step: d,
            object,
        }
    }
    fn normal(&mut self, p: Vec3, _h: f32) -> Vec3 {
        if self.analytic {
            self.scene.analytic_normal(p)
        } else {
            self.raw_normal
        }
    }
}

fn params(x: &Input) -> CtssParams {
    let mut p = CtssParams::new(x.tan_theta).relaxed(x.relaxed);
    if let Some(a) = x.alpha {
        p.alpha = a;
    }
    if let Some(e) = x.eps {
        p.eps = e;
    }
    if let Some((lo, hi)) = x.range {
        p = p.with_range(lo, hi);
    }
    p.min_sample_weight = if x.authors_min_weight { 0.01 } else { 0.0 };
    p.max_steps = x.max_steps % (MAX_STEPS + 1);
    p.max_samples = x.max_samples % 16;
    p.visibility_k = x.visibility_k % 40;
    // Raw codes, unknown ones included (they decode to the defaults).
    p.flags = (p.flags & FLAG_RELAXED) | ((x.placement & 0xff) << 8) | ((x.weighting & 0xff) << 16);
    p.paper(x.paper)
}

fuzz_target!(|x: Input| {
    let p = params(&x);
    let dir = unit(v3(x.dir)).unwrap_or(Vec3::Z);
    let (right, up) = cross_section_frame(dir, Vec3::Y);
    assert!(right.is_finite() && up.is_finite());
    let origin = Vec3::ZERO;
    let raw_normal = v3(x.normal);
    let th = p.thresholds();
    let visibility = p.weighting() == Weighting::Visibility;
    let mw = p.min_sample_weight;

    // --- The stepper, driven by hand as `march` drives it. ---
    let field = |sdf: &Sdf| Field {
        scene: Scene {
            sdf: sdf.clone(),
            dir,
            right,
            cursor: 0,
        },
        objects: &x.objects,
        calls: 0,
        analytic: x.analytic_normal,
        raw_normal,
    };
    let mut scene = field(&x.sdf);
    let ray = SplitRay {
        origin,
        dir,
        right,
        up,
    };
    let mut st = ConeStepper::new(&p);
    let mut calls = 0u32;
    let mut sample_events = 0u32;
    let mut weight_sum = 0.0f32;
    let mut seen = 0u32;
    let stop = loop {
        calls += 1;
        // Each call either spends a step, or is the one closing sample of a
        // budget/distance/NaN cut, or is the final Stop.
        assert!(
            calls <= p.max_steps + 2,
            "{calls} advance() calls with max_steps = {}",
            p.max_steps
        );
        let t = st.t();
        let FieldSample {
            distance: d,
            step,
            object,
        } = scene.sample(origin + t * dir);
        let ev = st.advance_object(d, step, object);
        assert!(st.steps() <= p.max_steps);
        match ev {
            Event::Stop(r) => {
                assert!(st.stop_reason() == Some(r));
                break r;
            }
            Event::March => {}
            Event::Sample(s) => {
                sample_events += 1;
                assert!(
                    s.t.is_finite() && s.t >= 0.0 && s.t_entry >= 0.0,
                    "sample {s:?}"
                );
                assert!(
                    (OCCLUSION_MIN..=OCCLUSION_MAX).contains(&s.occlusion)
                        && s.occlusion > th.soft,
                    "sample {s:?} with thresholds {th:?}"
                );
                assert!(!s.hard || s.occlusion > th.hard, "hard sample {s:?}");
                let q = origin + s.t * dir;
                let n = scene.normal(q, normal_step(s.t, p.tan_theta));
                let mask = group_mask(&p, &ray, &s, n, &mut scene);
                let (visible, w) = st.record_mask(mask);
                assert!(visible & seen == 0, "visible masks overlap");
                seen |= visible;
                assert!(st.coverage() == seen);
                if visibility {
                    assert!((0.0..=1.0).contains(&w), "record() weight {w}");
                } else {
                    assert!(w == 1.0);
                }
                weight_sum += w;
            }
            e => panic!("an event this target does not know: {e:?}"),
        }
        // t strictly increases while the trace goes on.
        if st.stop_reason().is_none() && t.is_finite() {
            assert!(st.t() > t, "t did not increase: {t:e} -> {:e} (d = {d:e})", st.t());
        }
    };
    assert!(sample_events == st.samples());
    // A group is sampled only when it closes or when the trace is cut with one
    // open; reaching the cap stops the trace, so the cap is exceeded only when it
    // is 0 (the first group is still sampled).
    assert!(
        st.samples() <= p.max_samples.max(1),
        "{} samples with max_samples = {} (stop {stop:?})",
        st.samples(),
        p.max_samples
    );
    if visibility {
        let bound = 1.0 + mw * st.samples() as f32 + 1e-6;
        assert!(weight_sum <= bound, "weights sum to {weight_sum} > {bound}");
    }
    let bw = st.background_weight();
    assert!((0.0..=1.0).contains(&bw), "background weight {bw}");
    if stop.covers_pixel() {
        assert!(bw == 0.0);
    }
    if stop == StopReason::SampleCap {
        assert!(st.samples() >= p.max_samples);
    }

    // --- `trace` over the same scene. ---
    let palette: Vec<Vec3> = if x.palette.is_empty() {
        vec![Vec3::ONE]
    } else {
        x.palette.iter().take(4).map(|&c| v3(c)).collect()
    };
    let background = v3(x.background);
    let mut used: Vec<Vec3> = Vec::new();
    let r = trace_field(
        &p,
        &ray,
        &mut field(&x.sdf),
        |_, _, _| {
            let c = palette[used.len() % palette.len()];
            used.push(c);
            c
        },
        background,
    );
    assert!(r.color.is_finite(), "trace colour {r:?}");
    assert!(
        r.stop == stop && r.samples == st.samples() && r.steps == st.steps() && r.coverage == seen,
        "trace {r:?} disagrees with the stepper ({stop:?}, {} samples, {} steps)",
        st.samples(),
        st.steps()
    );
    assert!(used.len() as u32 == r.samples);
    let mut hull = Hull::new();
    for c in used.iter().chain(std::iter::once(&background)) {
        if c.is_finite() {
            hull.add(*c);
        }
    }
    if hull.is_empty() {
        assert!(r.color == Vec3::ZERO, "trace colour {r:?} with nothing finite");
    } else {
        assert!(
            hull.contains(r.color),
            "trace colour {r:?} outside the hull {hull:?} of {used:?} and {background:?}"
        );
    }

    // --- NoAA baseline: ends within the budget. ---
    let mut scene = Scene {
        sdf: x.sdf.clone(),
        dir,
        right,
        cursor: 0,
    };
    let h = sphere_trace(&p, origin, dir, |q| scene.distance(q));
    assert!(h.steps <= p.max_steps);
    if let Some(t) = h.t {
        assert!(t.is_finite() && t >= 0.0 && h.stop == StopReason::HardHit);
    }
    let _ = Vec2::ZERO;
});
