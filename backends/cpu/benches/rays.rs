//! Ray throughput: the pipeline's primary rays against obvhs' raw traversal on
//! the same rays, and the same for shadow rays. The passes are those of
//! [`subcone_cpu::throughput::RayWorkload`] (see its docs), which the report
//! times too.
//!
//! Mrays/s = elements/s of each group; the ratio pipeline/raw is the target
//! (≥ 70 %). Sponza is read from `SUBCONE_DATA_DIR`. Both run on the widest
//! instruction-set path the CPU supports, or on `SUBCONE_ISA` (`baseline`,
//! `avx2`, `avx512`); the path is printed first.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use subcone_cpu::isa::Isa;
use subcone_cpu::throughput::RayWorkload;
use subcone_cpu::CpuBackend;
use subcone_load::scene_from_arg;

const W: u32 = 512;
const H: u32 = 512;

fn bench(c: &mut Criterion) {
    let backend = match std::env::var("SUBCONE_ISA") {
        Ok(name) => match name.parse::<Isa>() {
            Ok(isa) => CpuBackend::new().with_isa(isa),
            Err(e) => panic!("SUBCONE_ISA: {e}"),
        },
        Err(_) => CpuBackend::new(),
    };
    eprintln!("cpu path: {}", backend.isa());
    for name in ["cornell", "sponza"] {
        let scene = match scene_from_arg(name) {
            Ok(s) => s,
            Err(e) => panic!("{name}: {e} (set SUBCONE_DATA_DIR to the shared data directory)"),
        };
        let work = RayWorkload::new(&backend, &scene, W, H).expect("a triangle scene");

        let mut g = c.benchmark_group(format!("primary/{name}"));
        g.throughput(Throughput::Elements(work.primary_rays() as u64))
            .sample_size(10);
        g.bench_function(BenchmarkId::new("raw", W), |b| {
            b.iter(|| black_box(work.raw_primary_pass()))
        });
        g.bench_function(BenchmarkId::new("pipeline", W), |b| {
            b.iter(|| black_box(work.pipeline_primary_pass().expect("renders")))
        });
        g.finish();

        if work.shadow_rays() == 0 {
            continue;
        }
        let mut g = c.benchmark_group(format!("shadow/{name}"));
        g.throughput(Throughput::Elements(work.shadow_rays() as u64))
            .sample_size(10);
        g.bench_function("raw", |b| b.iter(|| black_box(work.raw_shadow_pass())));
        g.bench_function("pipeline", |b| {
            b.iter(|| black_box(work.pipeline_shadow_pass().expect("traces")))
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
