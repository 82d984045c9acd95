//! `ctss+edges` (CTSS §5.3, hit groups subdivided at internal edges) on the
//! CPU backend: a box edge seen between two faces of one box, where plain
//! CTSS gives each pixel one face's colour.
mod common;

use common::{front_camera, render, white};
use glam::{Quat, Vec3};
use subcone_scene::sdf::{SdfNode, SdfScene};
use subcone_scene::{Frame, Light, Scene};

const W: u32 = 48;
const H: u32 = 48;

/// A white cube turned 45° about the vertical, then tilted 0.15 rad about
/// the view axis, seen from +z: its front is a nearly vertical edge through
/// the middle of the image (slanted, so it crosses the pixels at every
/// offset) between a left face lit by the ambient light only (0.1) and a
/// right face lit by a distant light, on black.
fn turned_box() -> Scene {
    let root = SdfNode::cuboid(Vec3::splat(0.9))
        .unwrap()
        .rotate(Quat::from_rotation_z(0.15) * Quat::from_rotation_y(std::f32::consts::FRAC_PI_4))
        .unwrap();
    let light = Light::Directional {
        direction: Vec3::new(1.0, 0.2, 0.4).normalize(),
        irradiance: Vec3::splat(std::f32::consts::PI),
    };
    let mut s = SdfScene::new(
        "turned-box",
        root,
        vec![white()],
        vec![light],
        front_camera(),
    )
    .unwrap();
    s.ambient = Vec3::splat(0.1);
    s.background = Vec3::ZERO;
    Scene::sdf(s).unwrap()
}

/// Mean |Δ| (red channel, linear) over the pixels of the internal edge: the
/// eight middle columns, in the rows well inside the box's height, where the
/// reference lies strictly between the two faces' values.
fn internal_edge_error(a: &Frame, reference: &Frame, lo: f32, hi: f32) -> (f64, usize) {
    let (mut sum, mut n) = (0.0, 0);
    for y in H / 4..3 * H / 4 {
        for x in W / 2 - 4..W / 2 + 4 {
            let r = reference.pixel(x, y).x;
            if r > lo + 0.02 * (hi - lo) && r < hi - 0.02 * (hi - lo) {
                sum += (a.pixel(x, y).x - r).abs() as f64;
                n += 1;
            }
        }
    }
    (sum / n.max(1) as f64, n)
}

/// On the internal edge, plain CTSS has one group per pixel and paints the
/// pixel with the face its sample lands on; `ctss+edges` splits the group into
/// four quadrant sub-samples. For a straight edge at a uniformly distributed
/// offset, a single sample errs by a quarter of the contrast on average and a
/// 2×2 stratified one by an eighth: half. The bound, three quarters of CTSS's
/// error, leaves room for the sub-samples sitting at 0.61 of the pixel's
/// half-width instead of 0.5 and for the few rows the test covers.
#[test]
fn ctss_edges_resolves_an_internal_box_edge() {
    let scene = turned_box();
    let reference = render(&scene, "ssaa256", W, H);
    let ctss = render(&scene, "ctss", W, H);
    let edges = render(&scene, "ctss+edges", W, H);
    for f in [&ctss, &edges] {
        assert!(f
            .color
            .iter()
            .all(|c| c.is_finite() && c.min_element() >= 0.0));
    }
    // The two faces' values, from the reference away from the edge.
    let (left, right) = (
        reference.pixel(W / 2 - 6, H / 2).x,
        reference.pixel(W / 2 + 5, H / 2).x,
    );
    let (lo, hi) = (left.min(right), left.max(right));
    assert!(hi - lo > 0.4, "faces {left} and {right}: no internal edge");
    let (e_ctss, n) = internal_edge_error(&ctss, &reference, lo, hi);
    let (e_edges, _) = internal_edge_error(&edges, &reference, lo, hi);
    println!(
        "[turned box {W}x{H}, {n} internal-edge pixels, contrast {:.3}] mean |Δ| vs ssaa256: ctss {e_ctss:.4}, ctss+edges {e_edges:.4}; shaded samples ctss {}, ctss+edges {}",
        hi - lo,
        ctss.stats.shaded_samples,
        edges.stats.shaded_samples
    );
    assert!(n >= 20, "only {n} internal-edge pixels");
    assert!(
        e_edges < 0.75 * e_ctss,
        "ctss+edges {e_edges} is not below 3/4 of ctss {e_ctss}"
    );
    // It costs extra samples, and only where groups split.
    assert!(edges.stats.shaded_samples > ctss.stats.shaded_samples);
    assert!(edges.stats.shaded_samples < 2 * ctss.stats.shaded_samples);
}

/// Off by default: `ctss` is unchanged by the option's existence, and both
/// methods agree away from the edges (a face's interior).
#[test]
fn ctss_edges_leaves_flat_faces_alone() {
    let scene = turned_box();
    let (a, b) = (
        render(&scene, "ctss", W, H),
        render(&scene, "ctss+edges", W, H),
    );
    for (x, y) in [(W / 2 - 6, H / 2), (W / 2 + 5, H / 2)] {
        assert_eq!(a.pixel(x, y), b.pixel(x, y), "pixel ({x}, {y})");
    }
}
