//! The cost of CTSS §5.3's `K` transparency masks on the `glass` scene at
//! 320×180 (the report's SDF quality size), one frame per iteration:
//!
//! - `ctss/opaque-path`: every opacity set to 1, the opaque renderer (one mask);
//! - `ctss/k-masks-alpha1`: the same opaque scene on the semi-transparent path
//!   (`K` masks, an opacity lookup per sample): the path's own overhead;
//! - `ctss/k-masks-glass`: the scene as built (a pane of alpha 0.5, a sphere of
//!   0.3): the overhead plus marching through the glass and sampling behind it;
//! - `noaa/…`: the same for the NoAA reference's alpha blending.

use criterion::{criterion_group, criterion_main, Criterion};
use subcone_cpu::sphere::SdfView;
use subcone_kernels::passes::{required_passes, Technique};
use subcone_scene::{builtin::builtin, Method, RenderSettings, Scene};

const W: u32 = 320;
const H: u32 = 180;

fn frame(scene: &Scene, method: &Method, translucent: bool) -> f32 {
    let view = SdfView::of_scene(scene, &scene.camera).expect("an SDF scene");
    let passes = required_passes(method.technique(), scene.features()).unwrap();
    let f = view
        .render_with(method, &RenderSettings::new(W, H), passes, translucent)
        .expect("a CTSS method renders on an SDF scene");
    f.color[f.color.len() / 2].x
}

fn bench(c: &mut Criterion) {
    let glass = builtin("glass").unwrap();
    let mut opaque = glass.clone();
    for m in &mut opaque.materials {
        m.alpha = 1.0;
    }
    for (name, method) in [
        ("ctss", Method::new(Technique::Ctss)),
        ("noaa", Method::new(Technique::NoAa)),
    ] {
        let mut g = c.benchmark_group(format!("{name}/glass-{W}x{H}"));
        g.sample_size(10);
        g.bench_function("opaque-path", |b| b.iter(|| frame(&opaque, &method, false)));
        g.bench_function("k-masks-alpha1", |b| {
            b.iter(|| frame(&opaque, &method, true))
        });
        g.bench_function("k-masks-glass", |b| b.iter(|| frame(&glass, &method, true)));
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
