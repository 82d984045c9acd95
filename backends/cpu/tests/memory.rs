//! Buffer bytes per frame (`FrameStats::buffers`) and what leaving out unneeded
//! passes saves: the secondary passes on a scene without reflections, the
//! shadow passes on a scene without lights. (The 1024×1024 table is the
//! `memory` example.)
use subcone_cpu::CpuBackend;
use subcone_kernels::passes::Passes;
use subcone_scene::{builtin::builtin, Backend, Method, RenderSettings, Scene};

const SIZE: u32 = 32;

fn buffer_bytes(b: &CpuBackend, scene: &Scene, method: &str, force: Passes) -> (usize, Passes) {
    let m: Method = method.parse().unwrap();
    let mut settings = RenderSettings::new(SIZE, SIZE);
    settings.force_passes = force;
    let f = b.render(scene, &scene.camera, &m, &settings).unwrap();
    (f.stats.buffers.iter().map(|(_, n)| n).sum(), f.stats.passes)
}

const SECONDARY: Passes = Passes::SECONDARY
    .union(Passes::SECONDARY_SHADOW)
    .union(Passes::SUBPIXEL_SECONDARY_GEOMETRY)
    .union(Passes::SECONDARY_RECONSTRUCTION);

#[test]
fn leaving_out_secondary_passes_saves_buffers() {
    let b = CpuBackend::new();
    let nomirror = builtin("cornell-nomirror").unwrap();
    let cornell = builtin("cornell").unwrap();
    for m in ["noaa", "ssaa4", "sraa", "sraa-rt"] {
        let (lean, lp) = buffer_bytes(&b, &nomirror, m, Passes::empty());
        let (forced, fp) = buffer_bytes(&b, &nomirror, m, SECONDARY);
        let (mirror, _) = buffer_bytes(&b, &cornell, m, Passes::empty());
        assert!(!lp.intersects(Passes::SECONDARY), "{m}: {lp:?}");
        assert!(fp.contains(Passes::SECONDARY), "{m}: {fp:?}");
        println!(
            "[memory {SIZE}x{SIZE}] {m:<8} nomirror {lean:>7} B, secondary forced {forced:>7} B, cornell {mirror:>7} B"
        );
        if m == "sraa-rt" {
            // The secondary geometry, shadow states and layers of every
            // subsample: strictly more.
            assert!(
                forced > lean,
                "{m}: forcing saved nothing ({forced} vs {lean})"
            );
            assert!(
                mirror > lean,
                "{m}: the mirror costs nothing ({mirror} vs {lean})"
            );
            // Per pixel: at least the secondary geometry of the four subsamples.
            let px = (SIZE * SIZE) as usize;
            assert!(
                forced - lean >= px * 4 * 16,
                "{m}: {} B saved",
                forced - lean
            );
        } else {
            // No per-pass buffers: only the colour (and, for SRAA, the primary
            // geometry and one layer); leaving the pass out cannot grow them.
            assert!(forced >= lean, "{m}");
        }
    }
}

#[test]
fn leaving_out_shadow_passes_saves_buffers() {
    let b = CpuBackend::new();
    let lit = builtin("cornell-nomirror").unwrap();
    assert!(!lit.lights.is_empty());
    let mut unlit = lit.clone();
    unlit.lights.clear();
    unlit.touch();
    for m in ["noaa", "ssaa4", "sraa", "sraa-rt"] {
        let (with, wp) = buffer_bytes(&b, &lit, m, Passes::empty());
        let (without, up) = buffer_bytes(&b, &unlit, m, Passes::empty());
        assert!(wp.contains(Passes::SHADOW), "{m}: {wp:?}");
        assert!(
            !up.intersects(Passes::SHADOW | Passes::SUBPIXEL_SHADOW),
            "{m}: {up:?}"
        );
        println!("[memory {SIZE}x{SIZE}] {m:<8} lit {with:>7} B, unlit {without:>7} B");
        match m {
            // Shadow states per shaded sample and per subsample, and one
            // direct-light layer per light.
            "sraa-rt" => assert!(with > without, "{m}: {with} vs {without}"),
            // SRAA reconstructs the final colour only: no per-light buffer,
            // and NoAA/SSAA keep only the colour buffer.
            _ => assert_eq!(with, without, "{m}"),
        }
    }
}
