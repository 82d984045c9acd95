//! The host example `host_composite`: CtssPass's output composited over the
//! host's rasterised plane by depth, read back on both sides of the
//! sphere's intersection with the plane.

mod common;

#[allow(dead_code)]
#[path = "../examples/host_composite.rs"]
mod host_composite;

use glam::{Mat4, Vec3, Vec4};
use host_composite::{matrices, PLANE, SPHERE};

const W: u32 = 96;
const H: u32 = 64;

/// The pixel a world point projects to.
fn pixel(view_projection: Mat4, p: Vec3) -> (u32, u32) {
    let c = view_projection * Vec4::new(p.x, p.y, p.z, 1.0);
    let (x, y) = (c.x / c.w, c.y / c.w);
    (
        ((x + 1.0) * 0.5 * W as f32) as u32,
        ((1.0 - y) * 0.5 * H as f32) as u32,
    )
}

/// Above the plane the sphere is nearer than the plane and covers it; below
/// it the sphere (which CtssPass alone shows there, wholly covered) is
/// farther and the plane covers it; the sphere's upper silhouette, over
/// the plane behind it, carries fractional alpha and composites to a blend
/// of the two; and the composite is exactly the depth test and `over` of
/// what was read back.
#[test]
fn ctss_composites_over_the_raster_by_depth() {
    let Some((device, queue)) =
        common::device_or_skip("host_composite", host_composite::open_device)
    else {
        return;
    };
    let c = host_composite::render(&device, &queue, W, H).expect("render");
    let (view, projection) = matrices(W, H);
    let vp = projection * view;
    let at = |(x, y): (u32, u32)| (y * W + x) as usize;
    let (centre, r) = SPHERE;
    let eye_dir = (host_composite::EYE - centre).normalize();

    // The sphere's point facing the eye, above the plane: sphere in front.
    let front = centre + r * (eye_dir + Vec3::new(0.0, 0.6, 0.0)).normalize();
    assert!(front.y > 0.0);
    let i = at(pixel(vp, front));
    assert_eq!(c.sdf[i][3], 1.0, "the sphere covers its front");
    assert!(
        c.sdf_depth[i] < c.raster_depth[i],
        "above the plane the sphere is nearer"
    );
    let sdf = Vec3::new(c.sdf[i][0], c.sdf[i][1], c.sdf[i][2]);
    assert_eq!(c.image[i], sdf, "the sphere shows");
    assert!((c.image[i] - PLANE).length() > 0.1);

    // The sphere's point below the plane, seen from the eye through the
    // plane: the sphere is farther, the plane shows.
    let below = Vec3::new(0.0, -0.5, -(1.0f32 - 0.25).sqrt());
    let j = at(pixel(vp, below));
    assert_eq!(c.sdf[j][3], 1.0, "CtssPass alone shows the sphere there");
    assert!(
        c.sdf_depth[j] > c.raster_depth[j],
        "below the plane the sphere is farther"
    );
    assert!(
        (c.image[j] - PLANE).length() < 1e-6,
        "the plane shows: {:?}",
        c.image[j]
    );

    // The upper silhouette, straight above the centre: edge pixels with the
    // plane behind them.
    let (x, y_top) = pixel(vp, centre + Vec3::new(0.0, r, 0.0));
    let edge: Vec<usize> = (y_top.saturating_sub(3)..y_top + 3)
        .map(|y| at((x, y)))
        .filter(|&k| c.sdf[k][3] > 0.0 && c.sdf[k][3] < 1.0)
        .collect();
    assert!(!edge.is_empty(), "fractional alpha on the silhouette");
    for &k in &edge {
        assert!(
            c.sdf_depth[k] < c.raster_depth[k],
            "the edge is in front of the plane"
        );
        let a = c.sdf[k][3];
        let sdf = Vec3::new(c.sdf[k][0], c.sdf[k][1], c.sdf[k][2]);
        assert!((c.image[k] - (sdf + (1.0 - a) * PLANE)).length() < 1e-6);
        assert!(
            (c.image[k] - PLANE).length() > 1e-3,
            "the edge is not the plane alone"
        );
    }
    let fractional = c.sdf.iter().filter(|s| s[3] > 0.0 && s[3] < 1.0).count();
    println!("host_composite: {fractional} pixels of fractional alpha, edge {edge:?}");
}
