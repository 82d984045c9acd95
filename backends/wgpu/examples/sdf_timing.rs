//! Time every SDF method on every paper scene, wgpu against the CPU backend.
//!
//! `cargo run -p subcone-wgpu --example sdf_timing -- [WIDTH HEIGHT [RUNS]]`
//! (default 128×96, 3 runs): prints the median wall time per frame of each
//! backend (after one warm-up frame, which compiles the shader) and the GPU
//! pass time as the backend reports it.

use std::time::{Duration, Instant};

use subcone_cpu::CpuBackend;
use subcone_scene::builtin::builtin;
use subcone_scene::builtin::SDF_SCENES;
use subcone_scene::{Backend, Frame, Method, RenderError, RenderSettings, Scene};
use subcone_wgpu::WgpuBackend;

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn time(
    b: &dyn Backend,
    scene: &Scene,
    method: &Method,
    s: &RenderSettings,
    runs: usize,
) -> Result<(Duration, Duration, Frame), RenderError> {
    let mut frame = b.render(scene, &scene.camera, method, s)?;
    let mut wall = Vec::new();
    let mut pass = Vec::new();
    for _ in 0..runs {
        let t = Instant::now();
        frame = b.render(scene, &scene.camera, method, s)?;
        wall.push(t.elapsed());
        pass.push(frame.stats.total_time());
    }
    Ok((median(wall), median(pass), frame))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let w: u32 = args.first().map_or(Ok(128), |a| a.parse())?;
    let h: u32 = args.get(1).map_or(Ok(96), |a| a.parse())?;
    let runs: usize = args.get(2).map_or(Ok(3), |a| a.parse())?;
    let gpu = WgpuBackend::new()?;
    let cpu = CpuBackend::new();
    println!("{} | {w}x{h}, median of {runs}", gpu.context().describe());
    println!(
        "{:<13} {:<11} {:>10} {:>10} {:>10} {:>9}",
        "scene", "method", "cpu", "gpu wall", "gpu pass", "max diff"
    );
    let s = RenderSettings::new(w, h);
    for name in SDF_SCENES {
        let scene = builtin(name)?;
        for m in ["noaa", "ssaa4", "ctss", "ctss-r", "ssaa4+ctss"] {
            let method: Method = m.parse()?;
            let (c, _, a) = time(&cpu, &scene, &method, &s, runs)?;
            let (g, p, b) = time(&gpu, &scene, &method, &s, runs)?;
            let diff = a
                .color
                .iter()
                .zip(&b.color)
                .map(|(x, y)| (*x - *y).abs().max_element())
                .fold(0.0f32, f32::max);
            println!(
                "{name:<13} {m:<11} {:>10.2?} {:>10.2?} {:>10.2?} {diff:>9.2e}",
                c, g, p
            );
        }
    }
    Ok(())
}
