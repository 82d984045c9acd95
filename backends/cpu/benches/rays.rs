//! Ray throughput: the pipeline's primary rays against obvhs' raw traversal on
//! the same rays, and the same for shadow rays.
//!
//! - `raw_primary`: `CwBvh::ray_traverse` (closest hit, nothing else) on the
//!   camera rays through every pixel centre, in parallel over image bands.
//! - `pipeline_primary`: a NoAA frame of the same scene with its lights removed
//!   and its mirrors made diffuse, so every ray is a primary ray: ray
//!   generation, traversal, hit reconstruction (barycentrics, normals) and shading.
//! - `raw_shadow` / `pipeline_shadow`: the shadow rays of the primary hits
//!   towards the first light, raw `ray_traverse_miss` against the pipeline's
//!   shadow test (which also skips emitters).
//!
//! Mrays/s = elements/s of each group; the ratio pipeline/raw is the target
//! (≥ 70 %).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use subcone_cpu::shade::Tracer;
use subcone_cpu::CpuBackend;
use subcone_scene::{load::scene_from_arg, Backend, Method, RenderSettings, Scene};

const W: u32 = 512;
const H: u32 = 512;

fn unlit(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.lights.clear();
    for m in &mut s.materials {
        m.mirror = 0.0;
    }
    s.touch();
    s
}

fn bench(c: &mut Criterion) {
    let backend = CpuBackend::new();
    for name in ["cornell", "sponza"] {
        let scene = match scene_from_arg(name) {
            Ok(s) => s,
            Err(e) => panic!("{name}: {e} (set SUBCONE_DATA_DIR to the shared data directory)"),
        };
        let flat = unlit(&scene);
        let bvh = backend.bvh(&flat).unwrap();
        let cam = flat.camera;
        let rays: Vec<(Vec3, Vec3)> = (0..W * H)
            .map(|i| cam.ray(Vec2::new((i % W) as f32 + 0.5, (i / W) as f32 + 0.5), W, H))
            .collect();
        let n = rays.len() as u64;

        let mut g = c.benchmark_group(format!("primary/{name}"));
        g.throughput(Throughput::Elements(n)).sample_size(10);
        g.bench_function(BenchmarkId::new("raw", W), |b| {
            b.iter(|| {
                rays.par_chunks(W as usize * 4)
                    .map(|c| {
                        c.iter()
                            .map(|(o, d)| bvh.raw_closest_t(*o, *d))
                            .sum::<f32>()
                    })
                    .sum::<f32>()
            })
        });
        let noaa: Method = "noaa".parse().unwrap();
        let settings = RenderSettings::new(W, H);
        g.bench_function(BenchmarkId::new("pipeline", W), |b| {
            b.iter(|| {
                backend
                    .render(&flat, &cam, &noaa, &settings)
                    .unwrap()
                    .color
                    .len()
            })
        });
        g.finish();

        // Shadow rays from the primary hits towards the first light of the lit scene.
        let Some(light) = scene.lights.first().copied() else {
            continue;
        };
        let mesh = flat.mesh().unwrap();
        let tracer = Tracer::new(&bvh, &flat, mesh, &cam, 1);
        let hits: Vec<_> = rays
            .par_iter()
            .filter_map(|(o, d)| tracer.intersect(*o, *d, 0.0))
            .collect();
        let shadow_rays: Vec<(Vec3, Vec3, f32)> = hits
            .iter()
            .filter_map(|s| {
                let inc = light.incident(s.p)?;
                (inc.direction.dot(s.ng) > 0.0).then(|| {
                    (
                        s.p + s.ng * tracer.eps,
                        inc.direction,
                        inc.distance - tracer.eps,
                    )
                })
            })
            .collect();
        let mut g = c.benchmark_group(format!("shadow/{name}"));
        g.throughput(Throughput::Elements(shadow_rays.len() as u64))
            .sample_size(10);
        g.bench_function("raw", |b| {
            b.iter(|| {
                shadow_rays
                    .par_chunks(4096)
                    .map(|c| {
                        c.iter()
                            .filter(|(o, d, t)| bvh.raw_occluded(*o, *d, *t))
                            .count()
                    })
                    .sum::<usize>()
            })
        });
        let lit = {
            let mut s = flat.clone();
            s.lights = vec![light];
            s
        };
        let lit_tracer = Tracer::new(&bvh, &lit, mesh, &cam, 1);
        g.bench_function("pipeline", |b| {
            b.iter(|| {
                hits.par_chunks(4096)
                    .map(|c| {
                        let mut counts = Default::default();
                        c.iter()
                            .map(|s| lit_tracer.shadow_states(s, &mut counts).count_ones() as usize)
                            .sum::<usize>()
                    })
                    .sum::<usize>()
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
