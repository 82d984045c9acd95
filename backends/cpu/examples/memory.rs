//! Peak memory of each method at 1024×1024 (or the size given as the first
//! argument), and what leaving out the passes a scene does not need saves.
//!
//! Two figures per frame:
//! - **buffers**: the sum of `FrameStats::buffers`, the per-frame buffers the
//!   backend reports (colour, geometry, shading layers, shadow states, …);
//! - **peak heap**: the largest heap footprint while the frame renders, above
//!   what was allocated before it (a counting global allocator; the BVH is built
//!   by a warm-up frame first, so this is the frame alone).
//!
//! Comparisons:
//! - cornell (a mirror) against cornell-nomirror (same box, no mirror);
//! - cornell-nomirror with its required passes against the same frame with the
//!   secondary passes forced (`RenderSettings::force_passes`): the saving of
//!   leaving them out on a scene without reflections;
//! - cornell-nomirror without its lights against cornell-nomirror: the saving
//!   on a scene without lights (the shadow buffers and per-light layers are
//!   sized by the light count, so forcing the shadow passes on the unlit scene
//!   adds nothing: that column shows it).
//!
//! `cargo run --release -p subcone-cpu --example memory [SIZE]`

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use subcone_cpu::CpuBackend;
use subcone_kernels::passes::{Passes, Technique};
use subcone_scene::{builtin::builtin, Backend, Frame, Method, RenderSettings, Scene};

/// The system allocator, counting live bytes and their high-water mark.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call forwards to `System` with the same arguments; the
// counters only observe sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(live, Ordering::Relaxed);
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(live, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                let live = LIVE.fetch_add(new_size - layout.size(), Ordering::Relaxed) + new_size
                    - layout.size();
                PEAK.fetch_max(live, Ordering::Relaxed);
            } else {
                LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

const METHODS: [Method; 4] = [
    Method::new(Technique::NoAa),
    Method::ssaa_grid(2),
    Method::new(Technique::Sraa),
    Method::new(Technique::SraaRt),
];

/// Buffer bytes and peak heap bytes of one frame.
struct Measure {
    buffers: usize,
    peak: usize,
}

fn measure(b: &CpuBackend, scene: &Scene, m: Method, size: u32, force: Passes) -> Measure {
    let mut settings = RenderSettings::new(size, size);
    settings.force_passes = force;
    // Warm-up at a small size: builds and caches the BVH.
    let _ = b.render(scene, &scene.camera, &m, &RenderSettings::new(8, 8));
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let frame: Frame = b
        .render(scene, &scene.camera, &m, &settings)
        .expect("the frame renders");
    let peak = PEAK.load(Ordering::Relaxed) - before;
    Measure {
        buffers: frame.stats.buffers.iter().map(|(_, n)| n).sum(),
        peak,
    }
}

fn mib(n: usize) -> String {
    format!("{:.1}", n as f64 / (1024.0 * 1024.0))
}

fn saving(lean: &Measure, full: &Measure) -> String {
    let d = full.buffers as i64 - lean.buffers as i64;
    let p = full.peak as i64 - lean.peak as i64;
    format!(
        "{:>8} {:>6.1}% {:>8}",
        format!("{:.1}", d as f64 / 1048576.0),
        100.0 * d as f64 / full.buffers.max(1) as f64,
        format!("{:.1}", p as f64 / 1048576.0)
    )
}

fn main() {
    let size: u32 = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("SIZE is a number"))
        .unwrap_or(1024);
    let b = CpuBackend::new();
    let cornell = builtin("cornell").expect("built-in");
    let nomirror = builtin("cornell-nomirror").expect("built-in");
    let mut unlit = nomirror.clone();
    unlit.lights.clear();
    unlit.touch();

    let secondary = Passes::SECONDARY
        | Passes::SECONDARY_SHADOW
        | Passes::SUBPIXEL_SECONDARY_GEOMETRY
        | Passes::SECONDARY_RECONSTRUCTION;
    let shadow = Passes::SHADOW | Passes::SUBPIXEL_SHADOW;

    println!("Memory per frame at {size}x{size}, MiB (buffers = FrameStats::buffers; peak = heap high-water mark of the frame)");
    println!();
    println!(
        "{:<8} | {:>17} | {:>17} | {:>17} | {:>17} | {:>17}",
        "method", "cornell", "nomirror", "nomirror+2nd forc", "unlit", "unlit+shadow forc"
    );
    println!("{:<8} | {}", "", ["  buffers     peak"; 5].join(" | "));
    let mut rows = Vec::new();
    for m in METHODS {
        let a = measure(&b, &cornell, m, size, Passes::empty());
        let n = measure(&b, &nomirror, m, size, Passes::empty());
        let nf = measure(&b, &nomirror, m, size, secondary);
        let u = measure(&b, &unlit, m, size, Passes::empty());
        let uf = measure(&b, &unlit, m, size, shadow);
        let cell = |x: &Measure| format!("{:>8} {:>8}", mib(x.buffers), mib(x.peak));
        println!(
            "{:<8} | {} | {} | {} | {} | {}",
            m,
            cell(&a),
            cell(&n),
            cell(&nf),
            cell(&u),
            cell(&uf)
        );
        rows.push((m, a, n, nf, u, uf));
    }
    println!();
    println!("Savings, MiB (buffers, % of the larger frame's buffers, peak heap):");
    println!(
        "{:<8} | {:>25} | {:>25} | {:>25} | {:>25}",
        "method",
        "cornell -> nomirror",
        "no reflections (forced)",
        "no lights (lit -> unlit)",
        "unlit, shadow forced"
    );
    for (m, a, n, nf, u, uf) in &rows {
        println!(
            "{:<8} | {:>25} | {:>25} | {:>25} | {:>25}",
            m,
            saving(n, a),
            saving(n, nf),
            saving(u, n),
            saving(u, uf)
        );
    }
}
