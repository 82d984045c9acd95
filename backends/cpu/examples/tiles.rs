//! SRAA-RT (or another method) at several tile sizes: the frame's time, its
//! passes, its buffers and its shaded rays, so that the tile size
//! (`CpuBackend::with_tile`, `subcone_cpu::TILE` by default) can be judged on
//! a machine. Every tile size renders the same image (checked here too).
//!
//! ```text
//! cargo run --release -p subcone-cpu --example tiles -- [SCENE] [METHOD] [WxH] [RUNS] [TILE…]
//! ```
//!
//! Defaults: `cornell sraa-rt 1024x1024 5 16 32 64 128 256`. The sizes are
//! timed in interleaved rounds (every size once per round), and the median
//! of the rounds is printed.

mod common;

use std::process::ExitCode;
use std::time::Instant;

use subcone_cpu::CpuBackend;
use subcone_scene::{Backend, Method, RenderSettings};

fn main() -> ExitCode {
    common::exit(run())
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene = args.first().map(String::as_str).unwrap_or("cornell");
    let method = args.get(1).map(String::as_str).unwrap_or("sraa-rt");
    let size = args.get(2).map(String::as_str).unwrap_or("1024x1024");
    let runs: usize = args.get(3).and_then(|r| r.parse().ok()).unwrap_or(5);
    let mut tiles: Vec<usize> = args[4.min(args.len())..]
        .iter()
        .filter_map(|t| t.parse().ok())
        .collect();
    if tiles.is_empty() {
        tiles = vec![16, 32, 64, 128, 256];
    }
    let (w, h) = common::size(size)?;
    let scene = common::scene(scene)?;
    let method: Method = method.parse().map_err(|e| format!("{method}: {e}"))?;
    let settings = RenderSettings::new(w, h);
    let backends: Vec<CpuBackend> = tiles
        .iter()
        .map(|&t| CpuBackend::new().with_tile(t))
        .collect();
    let mut ms = vec![Vec::new(); tiles.len()];
    let mut first = Vec::new();
    // One warm-up round, then `runs` timed ones.
    for round in 0..=runs {
        for (i, b) in backends.iter().enumerate() {
            let start = Instant::now();
            let frame = b
                .render(&scene, &scene.camera, &method, &settings)
                .map_err(|e| e.to_string())?;
            let t = start.elapsed().as_secs_f64() * 1e3;
            if round == 0 {
                first.push(frame);
            } else {
                ms[i].push(t);
            }
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "{} {method} {w}x{h} on {}, median of {runs} rounds:",
        scene.name,
        backends[0].isa()
    );
    println!("(ms: median of the rounds; passes: the warm-up frame's)");
    println!("tile   ms      shading  geometry  antialiasing  primary rays/px  buffers MiB");
    for (i, &tile) in tiles.iter().enumerate() {
        let f = &first[i];
        let pass = |name: &str| {
            f.stats
                .timings
                .iter()
                .find(|p| p.name == name)
                .map_or(0.0, |p| p.time.as_secs_f64() * 1e3)
        };
        let same = f.color == first[0].color;
        println!(
            "{tile:>4}  {:>7.1}  {:>7.1}  {:>8.1}  {:>12.1}  {:>15.3}  {:>11.1}{}",
            median(&mut ms[i]),
            pass("shading"),
            pass("geometry"),
            pass("antialiasing"),
            f.stats.rays.primary as f64 / (w as f64 * h as f64),
            f.stats.buffer_bytes() as f64 / (1 << 20) as f64,
            if same { "" } else { "  IMAGE DIFFERS" }
        );
    }
    Ok(())
}
