//! Ray throughput of the CPU pipeline against obvhs' raw traversal on the same
//! rays (see `subcone_cpu::throughput`).
//!
//! ```text
//! cargo run --release -p subcone-cpu --example throughput -- [SCENE] [WxH] [RUNS] [ISA]
//! ```
//!
//! `SCENE` is a built-in name or a mesh path (default `cornell`), `WxH` the
//! frame the rays cover (default 512x512), `RUNS` the timed passes per figure
//! (default 5; the median is printed), `ISA` the instruction-set path
//! (`baseline`, `avx2`, `avx512`; default the widest the CPU supports).

mod common;

use std::process::ExitCode;

use subcone_cpu::isa::Isa;
use subcone_cpu::throughput::RayWorkload;
use subcone_cpu::CpuBackend;

fn main() -> ExitCode {
    common::exit(run())
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map(String::as_str).unwrap_or("cornell");
    let size = args.get(1).map(String::as_str).unwrap_or("512x512");
    let runs: usize = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(5);
    let isa = match args.get(3) {
        Some(i) => i.parse::<Isa>().map_err(|e| e.to_string())?,
        None => Isa::detected(),
    };
    let (w, h) = common::size(size)?;
    let scene = common::scene(name)?;
    let backend = CpuBackend::new().with_isa(isa);
    let work = RayWorkload::new(&backend, &scene, w, h).map_err(|e| format!("{name}: {e}"))?;
    let t = work.measure(runs);
    println!(
        "{name} {w}x{h}, {}, median of {runs}: primary {:.2} of {:.2} Mrays/s raw ({:.1}%)",
        backend.isa(),
        t.pipeline_primary / 1e6,
        t.raw_primary / 1e6,
        100.0 * t.primary_ratio()
    );
    if let (Some(p), Some(r), Some(q)) = (t.pipeline_shadow, t.raw_shadow, t.shadow_ratio()) {
        println!(
            "{name}: {} shadow rays: {:.2} of {:.2} Mrays/s raw ({:.1}%)",
            t.shadow_rays,
            p / 1e6,
            r / 1e6,
            100.0 * q
        );
    }
    Ok(())
}
