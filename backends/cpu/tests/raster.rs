//! The rasteriser against the tracer (`-hybrid`, `subcone_cpu::raster`):
//! on the SRAA paper's scenes and the shared meshes (Sponza, the bunny, the
//! teapot), at the sample positions the methods use, the rasteriser finds
//! the triangle the traversal finds at ≥ 99.9 % of samples, and every
//! disagreement is at a triangle's edge or a depth tie; a hybrid method's
//! image is within FLIP 1e-3 of its traced method's.
//!
//! How a disagreement is told:
//! - **edge**: the tracer's own test misses the rasteriser's triangle (the
//!   two round a sample on the edge differently; the hybrid then traces the
//!   ray, so its data is the tracer's), or the triangle one of them found and
//!   the other did not is hit within 1e-4 of its edge (a barycentric below
//!   1e-4);
//! - **depth tie**: both triangles are hit, at distances within 1e-4 of
//!   each other (relative): overlapping or touching surfaces.
//! - anything else is a **fault**, and fails the test.

use glam::Vec2;
use subcone_cpu::bvh::Hit;
use subcone_cpu::raster::{sample_coordinates, PixelRect, Raster, Samples, NONE};
use subcone_cpu::CpuBackend;
use subcone_kernels::sraa::SUBPIXEL_OFFSETS;
use subcone_scene::{Backend, Method, RenderSettings, Scene};

/// Samples compared, and how the disagreements divide.
#[derive(Debug, Default)]
struct Agreement {
    samples: u64,
    same: u64,
    edge: u64,
    tie: u64,
    fault: u64,
}

/// Whether a hit lies within 1e-4 of its triangle's edge.
fn near_edge(h: &Hit) -> bool {
    let (u, v) = (h.barycentrics.x, h.barycentrics.y);
    u.min(v).min(1.0 - u - v) < 1e-4
}

fn scenes() -> Vec<Scene> {
    let mut out: Vec<Scene> = subcone_scene::builtin::PAPER_SCENES
        .iter()
        .map(|n| subcone_scene::builtin::builtin(n).expect("a paper scene"))
        .filter(|s| s.sdf_geometry().is_none())
        .collect();
    let dir = subcone_load::data_dir();
    for name in [
        "sponza".to_string(),
        dir.join("bunny/bunny_npm.obj").display().to_string(),
        dir.join("teapot/teapot.obj").display().to_string(),
    ] {
        let scene = subcone_load::scene_from_arg(&name).unwrap_or_else(|e| {
            panic!("{name}: {e} (the shared meshes are read from SUBCONE_DATA_DIR)")
        });
        out.push(scene);
    }
    assert!(out.len() >= 6, "three paper scenes and three meshes");
    out
}

/// Where sample `k` of pixel `(x, y)` lies.
type SamplePoint = fn(usize, usize, usize) -> Vec2;

/// The sample patterns of the methods: NoAA's pixel centre, SRAA's four
/// subsamples, SSAA 4's grid.
fn patterns() -> Vec<(&'static str, usize, SamplePoint)> {
    fn centre(x: usize, y: usize, _: usize) -> Vec2 {
        Vec2::new(x as f32 + 0.5, y as f32 + 0.5)
    }
    fn subsample(x: usize, y: usize, k: usize) -> Vec2 {
        Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + SUBPIXEL_OFFSETS[k]
    }
    fn grid(x: usize, y: usize, k: usize) -> Vec2 {
        Vec2::new(x as f32, y as f32)
            + Vec2::new(((k % 2) as f32 + 0.5) / 2.0, ((k / 2) as f32 + 0.5) / 2.0)
    }
    vec![
        ("centre", 1, centre),
        ("subsamples", 4, subsample),
        ("ssaa4", 4, grid),
    ]
}

fn agreement(scene: &Scene, (w, h): (usize, usize)) -> Agreement {
    let bvh = CpuBackend::new().bvh(scene).expect("a triangle scene");
    let cam = scene.camera.rays(w as u32, h as u32);
    let raster = Raster::new(&bvh, &cam, w, h);
    let rect = PixelRect {
        x0: 0,
        y0: 0,
        x1: w,
        y1: h,
    };
    let mut a = Agreement::default();
    let (mut u, mut v, mut depth, mut ids) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (_, count, at) in patterns() {
        sample_coordinates(&cam, rect, count, at, &mut u, &mut v);
        let samples = Samples {
            count,
            u: &u,
            v: &v,
        };
        raster.rasterise(rect, samples, &mut depth, &mut ids);
        for k in 0..count {
            for y in 0..h {
                for x in 0..w {
                    let (o, d) = cam.through(u[k * w + x], v[k * h + y]);
                    let id = ids[(k * h + y) * w + x];
                    let traced = bvh.closest(o, d, 0.0, f32::INFINITY);
                    a.samples += 1;
                    if id == traced.map_or(NONE, |t| t.slot) {
                        a.same += 1;
                        continue;
                    }
                    let mine = (id != NONE).then(|| bvh.hit_on(id, o, d));
                    match (mine, traced) {
                        // The tracer's test misses the raster's triangle.
                        (Some(None), _) => a.edge += 1,
                        (Some(Some(m)), Some(t)) => {
                            if (m.t - t.t).abs() <= 1e-4 * t.t.abs().max(1e-6) {
                                a.tie += 1;
                            } else if near_edge(&m) || near_edge(&t) {
                                a.edge += 1;
                            } else {
                                a.fault += 1;
                                println!(
                                    "fault at ({x}, {y}) sample {k}: raster {m:?}, traced {t:?}"
                                );
                            }
                        }
                        (Some(Some(m)), None) if near_edge(&m) => a.edge += 1,
                        (None, Some(t)) if near_edge(&t) => a.edge += 1,
                        _ => {
                            a.fault += 1;
                            println!("fault at ({x}, {y}) sample {k}: raster {id} {mine:?}, traced {traced:?}");
                        }
                    }
                }
            }
        }
    }
    a
}

#[test]
fn the_raster_finds_the_tracers_triangle() {
    let mut report = Vec::new();
    for scene in scenes() {
        let a = agreement(&scene, (256, 256));
        let share = a.same as f64 / a.samples as f64;
        println!(
            "{}: {:.4} % of {} samples agree; {} at an edge, {} depth ties, {} faults",
            scene.name,
            100.0 * share,
            a.samples,
            a.edge,
            a.tie,
            a.fault
        );
        if share < 0.999 || a.fault > 0 {
            report.push(format!("{}: {a:?}", scene.name));
        }
    }
    assert!(report.is_empty(), "{report:#?}");
}

#[test]
fn hybrid_images_are_within_flip_1e_3_of_the_traced_ones() {
    let cpu = CpuBackend::new();
    let s = RenderSettings::new(192, 192);
    let mut failures = Vec::new();
    for scene in scenes() {
        for name in ["noaa", "ssaa2", "ssaa4", "sraa", "sraa-rt", "sraa-rt-paper"] {
            let traced: Method = name.parse().unwrap();
            let hybrid = traced.with_hybrid().unwrap();
            let a = cpu.render(&scene, &scene.camera, &traced, &s).unwrap();
            let b = cpu.render(&scene, &scene.camera, &hybrid, &s).unwrap();
            assert!(b.stats.raster_samples > 0, "{hybrid} rasterised nothing");
            let f = subcone_conformance::flip(&a, &b).mean;
            println!("{} {hybrid}: FLIP {f:.2e} against {traced}", scene.name);
            if f > 1e-3 {
                failures.push(format!("{} {hybrid}: FLIP {f}", scene.name));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Triangles behind the camera, through its plane, edge-on, degenerate,
/// huge (products that overflow) or not finite are left out or bounded,
/// never a panic, and no sample outside the image is written.
#[test]
fn extreme_triangles_are_safe() {
    use glam::Vec3;
    let scene = subcone_scene::builtin::builtin("cornell").unwrap();
    let cam = scene.camera;
    let (p, f, up) = (cam.position, cam.forward, cam.up);
    let r = f.cross(up);
    let tris = [
        // Behind the camera.
        [p - f, p - f + r, p - f + up],
        // Through the camera's plane (clipped).
        [p - f + r, p + 5.0 * f - r, p + 5.0 * f + up],
        // Through the camera itself.
        [p, p + f + r, p + f - r],
        // Edge-on: in a plane through the camera.
        [p + f, p + 2.0 * f, p + 3.0 * f],
        // Degenerate: a point, a segment.
        [p + 2.0 * f; 3],
        [p + 2.0 * f, p + 3.0 * f + r, p + 4.0 * f + 2.0 * r],
        // Huge, and huger than f32's products.
        [p + 1e18 * (f - r), p + 1e18 * (f + r), p + 1e18 * (f + up)],
        [p + 1e30 * (f - r), p + 1e30 * (f + r), p + 1e30 * (f + up)],
        // Not finite.
        [Vec3::NAN, p + f, p + f + r],
        [Vec3::INFINITY, p + f, p + f + r],
        [p + f - r, p + f + r, Vec3::new(f32::NEG_INFINITY, 0.0, 0.0)],
        // An ordinary one in front, so something is drawn.
        [p + 3.0 * f - r, p + 3.0 * f + r, p + 3.0 * f + up],
    ];
    let mut drawn = 0;
    for (w, h) in [(1, 1), (7, 5), (130, 70)] {
        let rays = cam.rays(w as u32, h as u32);
        let raster = Raster::of_triangles(tris.len(), |i| tris[i as usize], 10.0, &rays, w, h);
        // A rectangle reaching past the image: the outside stays empty.
        let rect = PixelRect {
            x0: 0,
            y0: 0,
            x1: w + 3,
            y1: h + 2,
        };
        let (mut u, mut v, mut depth, mut ids) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        sample_coordinates(
            &rays,
            rect,
            1,
            |x, y, _| Vec2::new(x as f32 + 0.5, y as f32 + 0.5),
            &mut u,
            &mut v,
        );
        let samples = Samples {
            count: 1,
            u: &u,
            v: &v,
        };
        raster.rasterise(rect, samples, &mut depth, &mut ids);
        assert_eq!(ids.len(), rect.width() * rect.height());
        for y in 0..rect.height() {
            for x in 0..rect.width() {
                let id = ids[y * rect.width() + x];
                if x >= w || y >= h {
                    assert_eq!(id, NONE, "({x}, {y}) is outside the {w}x{h} image");
                } else if id != NONE {
                    assert!((id as usize) < tris.len());
                    assert!(![0, 3, 4, 5, 8, 9, 10].contains(&id), "triangle {id} drawn");
                    drawn += 1;
                }
            }
        }
    }
    assert!(drawn > 0, "the ordinary triangle is drawn");
}
