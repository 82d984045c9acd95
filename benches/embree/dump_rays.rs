//! The obvhs half of the Embree comparison (`benches/embree/README.md`):
//! writes Sponza's triangles and the camera's primary rays through every
//! pixel centre of a 1024×1024 frame to a binary file, then times obvhs'
//! closest-hit and occlusion traversal of those rays on one thread (median of
//! 5 passes after a warm-up) on every instruction-set path the CPU supports,
//! and writes the rates beside the rays for `embree_bench.py`. The rates
//! compared are the renderer's (its triangle test on prepared edges); the
//! same traversal with obvhs' own triangle test is timed beside them.
//!
//! ```text
//! SUBCONE_DATA_DIR=... cargo run --release -p subcone-cpu --example dump_rays -- [OUT_DIR] [SCENE]
//! ```
//!
//! The file (`rays.bin`, little-endian): the 8 bytes `SUBCRAYS`, `u32`
//! version 1, `u32` triangle count, `u32` ray count, then 9 `f32` per
//! triangle (three vertices) and 6 `f32` per ray (origin, unit direction).
//! The rates go to `obvhs.json`.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use glam::{Vec2, Vec3};
use subcone_cpu::isa::Isa;
use subcone_cpu::{CpuBackend, SceneBvh};
use subcone_load::scene_from_arg;

const SIZE: u32 = 1024;
const RUNS: usize = 5;

/// Median rate in Mrays/s of `RUNS` timed passes of `pass` (after a warm-up)
/// over `n` rays.
fn median_mrays(n: usize, mut pass: impl FnMut() -> usize) -> f64 {
    std::hint::black_box(pass());
    let mut secs: Vec<f64> = (0..RUNS)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(pass());
            start.elapsed().as_secs_f64()
        })
        .collect();
    secs.sort_by(f64::total_cmp);
    n as f64 / secs[RUNS / 2] / 1e6
}

/// Which triangle test a pass uses.
#[derive(Clone, Copy)]
enum Test {
    /// The renderer's: obvhs' test on prepared edges (`SceneBvh::closest`,
    /// `SceneBvh::occluded`), which also returns the barycentrics.
    Renderer,
    /// obvhs' own `Triangle::intersect` (`raw_closest_t`, `raw_occluded`).
    Obvhs,
}

fn closest(bvh: &SceneBvh, rays: &[(Vec3, Vec3)], isa: Isa, test: Test) -> usize {
    isa.run(
        #[inline(always)]
        || {
            // A plain loop: an iterator adaptor's `count` would be a call
            // out of the instruction-set path.
            let mut hits = 0;
            for (o, d) in rays {
                hits += usize::from(match test {
                    Test::Renderer => bvh.closest(*o, *d, 0.0, f32::INFINITY).is_some(),
                    Test::Obvhs => bvh.raw_closest_t(*o, *d).is_finite(),
                });
            }
            hits
        },
    )
}

fn occluded(bvh: &SceneBvh, rays: &[(Vec3, Vec3)], isa: Isa, test: Test) -> usize {
    isa.run(
        #[inline(always)]
        || {
            let mut blocked = 0;
            for (o, d) in rays {
                blocked += usize::from(match test {
                    Test::Renderer => bvh.occluded(*o, *d, 0.0, f32::INFINITY),
                    Test::Obvhs => bvh.raw_occluded(*o, *d, f32::INFINITY),
                });
            }
            blocked
        },
    )
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = PathBuf::from(args.first().map_or("target/embree", String::as_str));
    let name = args.get(1).map_or("sponza", String::as_str);
    let scene = scene_from_arg(name).map_err(|e| format!("{name}: {e}"))?;
    let mesh = scene
        .mesh()
        .ok_or_else(|| format!("{name} is not a triangle scene"))?;
    let backend = CpuBackend::new();
    let bvh = backend.bvh(&scene).map_err(|e| e.to_string())?;
    let cam = scene.camera.rays(SIZE, SIZE);
    let rays: Vec<(Vec3, Vec3)> = (0..SIZE * SIZE)
        .map(|i| {
            let (x, y) = (i % SIZE, i / SIZE);
            cam.ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
        })
        .collect();

    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut bytes = Vec::with_capacity(20 + mesh.positions.len() * 36 + rays.len() * 24);
    bytes.extend_from_slice(b"SUBCRAYS");
    for v in [1, mesh.positions.len() as u32, rays.len() as u32] {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    let floats = mesh
        .positions
        .iter()
        .flat_map(|t| t.iter().flat_map(|v| v.to_array()))
        .chain(
            rays.iter()
                .flat_map(|(o, d)| [o.to_array(), d.to_array()].concat()),
        );
    for f in floats {
        bytes.extend_from_slice(&f.to_le_bytes());
    }
    let file = out.join("rays.bin");
    std::fs::write(&file, &bytes).map_err(|e| format!("{}: {e}", file.display()))?;

    let n = rays.len();
    let mut json = format!(
        "{{\n  \"scene\": \"{name}\",\n  \"triangles\": {},\n  \"rays\": {n},\n  \"runs\": {RUNS},\n  \"paths\": {{",
        mesh.positions.len()
    );
    for (k, isa) in Isa::supported().into_iter().rev().enumerate() {
        let hits = closest(&bvh, &rays, isa, Test::Renderer);
        let blocked = occluded(&bvh, &rays, isa, Test::Renderer);
        let c = median_mrays(n, || closest(&bvh, &rays, isa, Test::Renderer));
        let o = median_mrays(n, || occluded(&bvh, &rays, isa, Test::Renderer));
        let c_own = median_mrays(n, || closest(&bvh, &rays, isa, Test::Obvhs));
        let o_own = median_mrays(n, || occluded(&bvh, &rays, isa, Test::Obvhs));
        println!(
            "obvhs {name} {n} rays, one thread, {isa}: closest hit {c:.2} Mrays/s ({hits} hits), \
             occlusion {o:.2} Mrays/s ({blocked} occluded); with obvhs' own triangle test \
             {c_own:.2} and {o_own:.2} Mrays/s"
        );
        json += &format!(
            "{}\n    \"{}\": {{ \"closest_mrays\": {c:.4}, \"occluded_mrays\": {o:.4}, \"hits\": {hits}, \"occluded\": {blocked}, \"closest_obvhs_test_mrays\": {c_own:.4}, \"occluded_obvhs_test_mrays\": {o_own:.4} }}",
            if k > 0 { "," } else { "" },
            isa.name()
        );
    }
    json += "\n  },\n  \"detected\": \"";
    json += Isa::detected().name();
    json += "\"\n}\n";
    let file = out.join("obvhs.json");
    std::fs::File::create(&file)
        .and_then(|mut f| f.write_all(json.as_bytes()))
        .map_err(|e| format!("{}: {e}", file.display()))?;
    println!(
        "wrote {} and {}",
        out.join("rays.bin").display(),
        file.display()
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
