//! The CPU backend's rasteriser (`subcone_cpu::raster`, the `-hybrid`
//! methods' primary visibility) on arbitrary triangles, cameras, image sizes,
//! rectangles and sample positions.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::v3;
use glam::{DVec3, Vec2, Vec3};
use libfuzzer_sys::fuzz_target;
use subcone_cpu::raster::{sample_coordinates, PixelRect, Raster, Samples, NONE};
use subcone_scene::Camera;

/// A coordinate: raw bits, tame (`i16/64`), or special.
#[derive(Arbitrary, Debug, Clone, Copy)]
enum Coord {
    Raw(f32),
    Tame(i16),
    Special(u8),
}

impl Coord {
    fn get(self) -> f32 {
        match self {
            Coord::Raw(x) => x,
            Coord::Tame(i) => i as f32 / 64.0,
            Coord::Special(k) => [
                0.0,
                -0.0,
                f32::NAN,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::MAX,
                f32::MIN_POSITIVE,
                1e-30,
                1e30,
                -1e30,
            ][k as usize % 10],
        }
    }
}

#[derive(Arbitrary, Debug)]
struct Input {
    triangles: Vec<[[Coord; 3]; 3]>,
    eye: [i16; 3],
    target: [i16; 3],
    fov: u8,
    width: u8,
    height: u8,
    /// The rectangle: may reach past the image.
    rect: [u8; 4],
    /// Up to four sample offsets inside the pixel, in 1/256ths.
    offsets: Vec<(u8, u8)>,
}

/// `(a − o) × (b − o) · d` in f64.
fn edge(a: DVec3, b: DVec3, d: DVec3) -> (f64, f64) {
    let n = a.cross(b);
    (n.dot(d), n.length() * d.length())
}

fuzz_target!(|x: Input| {
    let tame = |a: [i16; 3]| Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32) / 64.0;
    let fov = 0.1 + 2.9 * (x.fov as f32 / 255.0);
    let Ok(camera) = Camera::look_at(tame(x.eye), tame(x.target), Vec3::Y, fov) else {
        return;
    };
    let (w, h) = (1 + x.width as usize % 48, 1 + x.height as usize % 48);
    let tris: Vec<[Vec3; 3]> = x
        .triangles
        .iter()
        .take(24)
        .map(|t| t.map(|v| v3(v.map(Coord::get))))
        .collect();
    let cam = camera.rays(w as u32, h as u32);
    let raster = Raster::of_triangles(tris.len(), |i| tris[i as usize], 10.0, &cam, w, h);
    let [a, b, c, d] = x.rect.map(|v| v as usize % 64);
    let rect = PixelRect {
        x0: a.min(b),
        y0: c.min(d),
        x1: a.max(b),
        y1: c.max(d),
    };
    let offsets: Vec<Vec2> = x
        .offsets
        .iter()
        .take(4)
        .map(|&(u, v)| Vec2::new(u as f32, v as f32) / 256.0)
        .collect();
    let count = offsets.len().max(1);
    let at = |px: usize, py: usize, k: usize| {
        Vec2::new(px as f32, py as f32) + offsets.get(k).copied().unwrap_or(Vec2::splat(0.5))
    };
    let (mut u, mut v, mut depth, mut ids) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    sample_coordinates(&cam, rect, count, at, &mut u, &mut v);
    raster.rasterise(rect, Samples { count, u: &u, v: &v }, &mut depth, &mut ids);
    let (cols, rows) = (rect.width(), rect.height());
    assert_eq!(ids.len(), count * cols * rows, "one id per sample");

    let (o, [f, r, up]) = cam.frame();
    let o = o.as_dvec3();
    for k in 0..count {
        for yy in 0..rows {
            for xx in 0..cols {
                let id = ids[(k * rows + yy) * cols + xx];
                let (px, py) = (rect.x0 + xx, rect.y0 + yy);
                if px >= w || py >= h {
                    assert_eq!(id, NONE, "sample of ({px}, {py}) outside the {w}x{h} image");
                    continue;
                }
                // The sample's ray direction, in f64.
                let dir = (f.as_dvec3()
                    + u[k * cols + xx] as f64 * r.as_dvec3()
                    + v[k * rows + yy] as f64 * up.as_dvec3())
                .normalize();
                // Every triangle that holds the sample well inside (by a
                // margin of 1e-4 of each edge function's scale, in f64),
                // well in front of the camera, with tame vertices.
                let inside = |t: &[Vec3; 3]| -> Option<f64> {
                    if !t.iter().all(|p| p.is_finite() && p.abs().max_element() < 1e4) {
                        return None;
                    }
                    let p = t.map(|q| q.as_dvec3() - o);
                    let det = p[0].dot(p[1].cross(p[2]));
                    let n = (p[1] - p[0]).cross(p[2] - p[0]);
                    let nd = n.dot(dir);
                    if det.abs() < 1e-6 || nd.abs() < 1e-6 * n.length() {
                        return None;
                    }
                    let s = det.signum();
                    for (a, b) in [(p[0], p[1]), (p[1], p[2]), (p[2], p[0])] {
                        let (e, scale) = edge(a, b, dir);
                        if s * e <= 1e-4 * scale {
                            return None;
                        }
                    }
                    let t_hit = n.dot(p[0]) / nd;
                    (t_hit > 1e-3).then_some(t_hit)
                };
                let nearest = tris.iter().filter_map(inside).fold(f64::INFINITY, f64::min);
                if nearest.is_finite() {
                    // A sample well inside a triangle in front is covered,
                    // by a triangle no farther than it (a tolerance of 1e-3).
                    assert_ne!(id, NONE, "({px}, {py}) sample {k} is inside a triangle at {nearest} but found none");
                }
                if id != NONE {
                    assert!((id as usize) < tris.len(), "id {id} of {} triangles", tris.len());
                    let t = &tris[id as usize];
                    if let Some(t_hit) = inside(t) {
                        assert!(
                            t_hit <= nearest * (1.0 + 1e-3) + 1e-3,
                            "({px}, {py}) sample {k}: triangle {id} at {t_hit}, nearer one at {nearest}"
                        );
                    }
                }
            }
        }
    }
});
