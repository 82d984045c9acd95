//! A trace's coverage alpha and depth (`TraceResult::alpha`, `::depth`):
//! the colour resolved against black, composited `over` a background with
//! the coverage alpha, is the colour resolved against that background
//! (CTSS §3.4–3.5, eq. 6), across a sphere's silhouette, for plain, paper
//! and split-group traces; the depth is the sphere's near surface.
use glam::Vec3;
use subcone_kernels::ctss::{cross_section_frame, trace, CtssParams, StopReason};

/// A unit sphere 5 ahead.
fn sphere(p: Vec3) -> f32 {
    (p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0
}

fn normal(p: Vec3) -> Vec3 {
    (p - Vec3::new(0.0, 0.0, 5.0)).normalize()
}

fn shade(_p: Vec3, n: Vec3) -> Vec3 {
    Vec3::new(0.5 + 0.5 * n.y, 0.3, 0.8)
}

#[test]
fn black_over_the_background_is_the_background_resolve() {
    let background = Vec3::new(0.2, 0.9, 0.4);
    let (mut partial, mut whole, mut none) = (0, 0, 0);
    for params in [
        CtssParams::new(0.01).with_range(0.0, 100.0),
        CtssParams::new(0.01).with_range(0.0, 100.0).paper(true),
        CtssParams::new(0.01)
            .with_range(0.0, 100.0)
            .with_split_groups(true),
    ] {
        // Rays from inside the silhouette (x < 0.2041: tan of the sphere's
        // half angle, 1/√24) to beyond it.
        for i in 0..200 {
            let x = 0.17 + 0.0004 * i as f32;
            let dir = Vec3::new(x, 0.013, 1.0).normalize();
            let (right, up) = cross_section_frame(dir, Vec3::Y);
            let run = |bg| {
                trace(
                    &params,
                    Vec3::ZERO,
                    dir,
                    right,
                    up,
                    sphere,
                    normal,
                    shade,
                    bg,
                )
            };
            let (opaque, clear) = (run(background), run(Vec3::ZERO));
            let a = clear.alpha();
            assert!((0.0..=1.0).contains(&a));
            assert_eq!(
                a,
                opaque.alpha(),
                "the coverage does not depend on the background"
            );
            let over = clear.color + (1.0 - a) * background;
            assert!(
                (over - opaque.color).abs().max_element() < 1e-6,
                "x {x}: {over:?} ≠ {:?} (alpha {a}, {:?})",
                opaque.color,
                opaque.stop
            );
            match a {
                0.0 => {
                    none += 1;
                    assert_eq!(clear.depth, f32::INFINITY);
                }
                1.0 => whole += 1,
                _ => partial += 1,
            }
            if a > 0.0 {
                // The group's sample lies on the sphere's near side, within
                // a cone radius of it.
                let p = clear.depth * dir;
                assert!(
                    sphere(p).abs() < 0.1 && p.z < 5.0,
                    "x {x}: depth {}",
                    clear.depth
                );
            }
        }
    }
    assert!(
        partial > 20 && whole > 20 && none > 20,
        "{partial} {whole} {none}"
    );
    // A hard hit of the axis covers the pixel whatever the mask says.
    assert_eq!(
        subcone_kernels::ctss::coverage_alpha(0, StopReason::HardHit),
        1.0
    );
    assert_eq!(
        subcone_kernels::ctss::coverage_alpha(0xFFFF, StopReason::MaxDistance),
        0.5
    );
}
