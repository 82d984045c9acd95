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

use std::process::ExitCode;

use subcone_cpu::isa::Isa;
use subcone_cpu::throughput::RayWorkload;
use subcone_cpu::CpuBackend;
use subcone_load::scene_from_arg;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map(String::as_str).unwrap_or("cornell");
    let size = args.get(1).map(String::as_str).unwrap_or("512x512");
    let runs: usize = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(5);
    let isa = match args.get(3).map(|i| i.parse::<Isa>()).transpose() {
        Ok(i) => i.unwrap_or_else(Isa::detected),
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let Some((w, h)) = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
    else {
        eprintln!("size {size:?} is not WxH");
        return ExitCode::FAILURE;
    };
    let scene = match scene_from_arg(name) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{name}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let backend = CpuBackend::new().with_isa(isa);
    let work = match RayWorkload::new(&backend, &scene, w, h) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("{name}: {e}");
            return ExitCode::FAILURE;
        }
    };
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
    ExitCode::SUCCESS
}
