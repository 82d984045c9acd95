//! The default's hit groups and masks against the paper's (`FLAG_PAPER`):
//! one group per surface, masks of thin shells, CTSS-R's last group.
use glam::Vec3;
use subcone_kernels::cone::cone_radius;
use subcone_kernels::ctss::{
    group_normal_depths, trace_field, ConeField, ConeStepper, CtssParams, Event, FieldSample,
    GroupSample, SplitRay, StopReason, NO_OBJECT,
};
use subcone_kernels::mask::FULL_MASK;

const TAN: f32 = 0.01;

/// Drive a stepper with `(occlusion, object)` per step (the distance that
/// gives that occlusion at the step's depth) and return its samples.
fn groups(params: &CtssParams, steps: &[(f32, u32)]) -> Vec<GroupSample> {
    let mut st = ConeStepper::new(params);
    let mut out = Vec::new();
    for &(omega, object) in steps
        .iter()
        .chain(std::iter::repeat_n(&(-1.0, NO_OBJECT), 4))
    {
        let rc = cone_radius(st.t(), TAN);
        let d = rc * (1.0 - 2.0 * omega);
        match st.advance_object(d, d, object) {
            Event::Sample(s) => {
                st.record(&s, glam::Vec2::X);
                out.push(s)
            }
            Event::Stop(_) => break,
            Event::March => {}
            e => panic!("an event this test does not know: {e:?}"),
        }
    }
    out
}

fn params() -> CtssParams {
    CtssParams::new(TAN).with_range(1.0, 100.0)
}

/// A cone in contact with one object, then with another (the floor behind a
/// sphere's silhouette): two groups by default, one in the paper.
#[test]
fn a_group_ends_where_the_nearest_object_changes() {
    let steps = [(0.2, 1), (0.3, 1), (0.3, 2), (0.4, 2), (0.2, 2)];
    let ours = groups(&params(), &steps);
    assert_eq!(ours.len(), 2, "{ours:?}");
    assert!((ours[0].occlusion - 0.3).abs() < 1e-4 && (ours[1].occlusion - 0.4).abs() < 1e-4);
    assert_eq!(groups(&params().paper(true), &steps).len(), 1);
    // Unknown objects never split.
    let unknown: Vec<_> = steps.iter().map(|&(w, _)| (w, NO_OBJECT)).collect();
    assert_eq!(groups(&params(), &unknown).len(), 1);
}

/// Occlusion that falls by more than GROUP_DIP and rises again by as much:
/// a second surface within the cone, a second group.
#[test]
fn a_group_ends_where_occlusion_rises_after_a_dip() {
    let steps = [(0.3, 0), (0.45, 0), (0.2, 0), (0.4, 0), (0.1, 0)];
    assert_eq!(groups(&params(), &steps).len(), 2);
    assert_eq!(groups(&params().paper(true), &steps).len(), 1);
    // A shallow dip keeps the group.
    let shallow = [(0.3, 0), (0.45, 0), (0.4, 0), (0.44, 0), (0.1, 0)];
    assert_eq!(groups(&params(), &shallow).len(), 1);
}

/// A closing step that also meets full occlusion: the closed group is
/// sampled, then the new one, then the trace stops; the cap still holds.
#[test]
fn a_split_on_the_stopping_step_samples_both_groups() {
    let steps = [(0.3, 1), (1.0, 2)];
    let g = groups(&params(), &steps);
    assert_eq!(g.len(), 2, "{g:?}");
    let mut capped = params();
    capped.max_samples = 1;
    assert_eq!(groups(&capped, &steps).len(), 1);
}

/// An axis-aligned box field, object 0, in front of a wall (object 1).
struct BoxBeforeWall {
    centre: Vec3,
    half: Vec3,
    wall_z: f32,
}

impl ConeField for BoxBeforeWall {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        let q = (p - self.centre).abs() - self.half;
        let b = q.max(Vec3::ZERO).length() + q.max_element().min(0.0);
        let w = self.wall_z - p.z;
        if b < w {
            FieldSample {
                distance: b,
                step: b,
                object: 0,
            }
        } else {
            FieldSample {
                distance: w,
                step: w,
                object: 1,
            }
        }
    }
}

fn trace_box(params: &CtssParams, field: &mut BoxBeforeWall, dir: Vec3) -> Vec3 {
    let ray = SplitRay::new(Vec3::ZERO, dir, Vec3::Y);
    // The box white, the wall red.
    trace_field(
        params,
        &ray,
        field,
        |p, _, _| {
            if p.z < field_wall() - 0.01 {
                Vec3::ONE
            } else {
                Vec3::X
            }
        },
        Vec3::ZERO,
    )
    .color
}

fn field_wall() -> f32 {
    10.0
}

/// A sheet a tenth of the cone's diameter thick, face-on, covers the pixel
/// by default; the paper's mask shows the wall through it.
#[test]
fn a_thin_sheet_face_on_is_opaque() {
    let rc = cone_radius(5.0, TAN);
    let mut sheet = BoxBeforeWall {
        centre: Vec3::new(0.0, 0.0, 5.0),
        half: Vec3::new(2.0, 2.0, 0.1 * rc),
        wall_z: field_wall(),
    };
    let mut worst = 0.0f32;
    let mut worst_paper = 0.0f32;
    for i in 0..50 {
        let dir = Vec3::new(0.003 * i as f32, 0.002 * i as f32, 1.0).normalize();
        let c = trace_box(&params(), &mut sheet, dir);
        worst = worst.max((c - Vec3::ONE).abs().max_element());
        let c = trace_box(&params().paper(true), &mut sheet, dir);
        worst_paper = worst_paper.max((c - Vec3::ONE).abs().max_element());
    }
    assert!(worst <= 1.0 / 255.0, "ours: {worst}");
    assert!(worst_paper > 0.2, "the paper's mask: {worst_paper}");
}

/// A box smaller than the cone, passed through, is not a sheet: the
/// thin-shell rule leaves it the paper's mask, on rays through and beside it.
#[test]
fn a_small_box_is_not_a_sheet() {
    let rc = cone_radius(5.0, TAN);
    let mut small = BoxBeforeWall {
        centre: Vec3::new(0.0, 0.0, 5.0),
        half: Vec3::splat(0.3 * rc),
        wall_z: field_wall(),
    };
    for i in 0..40 {
        let dir = Vec3::new(0.0003 * i as f32, 0.0001 * i as f32, 1.0).normalize();
        let ours = trace_box(&params(), &mut small, dir);
        let paper = trace_box(&params().paper(true), &mut small, dir);
        assert!(
            (ours - paper).abs().max_element() < 1e-6,
            "ray {i}: {ours} vs {paper}"
        );
    }
}

/// CTSS-R's hard hit takes the rest of the pixel: with a glancing group in
/// front, its share is its own mask, not stretched by renormalisation.
#[test]
fn ctss_r_last_group_takes_the_rest_of_the_pixel() {
    for paper in [false, true] {
        let p = params().relaxed(true).paper(paper);
        let mut st = ConeStepper::new(&p);
        let mut coverage = 0;
        // Per sample: whether the stepper ignores its mask, and how many
        // normals `close_group` takes for it.
        let mut takes_rest = Vec::new();
        for &(omega, object) in &[(0.3, 1), (0.0, 1), (-0.5, 1), (0.2, 2), (0.5, 2), (0.6, 2)] {
            let rc = cone_radius(st.t(), TAN);
            let d = rc * (1.0 - 2.0 * omega);
            match st.advance_object(d, d, object) {
                Event::Sample(s) => {
                    takes_rest.push((st.takes_rest_of_pixel(), group_normal_depths(&p, &st, &s).1));
                    st.record(&s, glam::Vec2::X);
                    coverage = st.coverage();
                }
                Event::Stop(r) => {
                    assert_eq!(r, StopReason::HardHit);
                    break;
                }
                Event::March => {}
                e => panic!("an event this test does not know: {e:?}"),
            }
        }
        assert_eq!(st.stop_reason(), Some(StopReason::HardHit));
        assert_eq!(
            coverage == FULL_MASK,
            !paper,
            "paper {paper}: {coverage:#x}"
        );
        // Only the last group takes the rest, and then only the shading
        // normal is taken: the mask it would have made is never asked for.
        let last = takes_rest.pop().expect("a last group");
        assert_eq!(last.0, !paper, "paper {paper}");
        if !paper {
            assert_eq!(last.1, 1);
        }
        assert!(takes_rest.iter().all(|t| !t.0), "{takes_rest:?}");
    }
}
