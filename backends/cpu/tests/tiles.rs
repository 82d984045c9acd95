//! SRAA and SRAA-RT render tile by tile (`CpuBackend::with_tile`): every tile
//! size gives the whole-frame image bit for bit, and the buffers are one
//! tile's per thread, whatever the image size.
use subcone_cpu::CpuBackend;
use subcone_scene::{builtin::builtin, Backend, Frame, Method, RenderSettings, Scene};

fn render(b: &CpuBackend, scene: &Scene, method: &str, (w, h): (u32, u32)) -> Frame {
    let m: Method = method.parse().unwrap();
    b.render(scene, &scene.camera, &m, &RenderSettings::new(w, h))
        .unwrap_or_else(|e| panic!("{} {method}: {e}", scene.name))
}

fn bits(f: &Frame) -> Vec<u32> {
    f.color
        .iter()
        .flat_map(|c| c.to_array())
        .map(f32::to_bits)
        .collect()
}

/// Tiles of 1, 7 and 64 pixels (the default), and one tile for the whole
/// image, on an image whose sides are no multiple of any of them: the same
/// bits for every method of the SRAA family, on a scene with a mirror and
/// shadows and on a textured one (the material gate), with adaptive and
/// exhaustive subpixel shadows.
#[test]
fn every_tile_size_renders_the_whole_frame_image() {
    let size = (131, 70);
    for scene in ["cornell", "checker"] {
        let scene = builtin(scene).unwrap();
        for method in [
            "sraa",
            "sraa-paper",
            "sraa-rt",
            "sraa-rt+mat",
            "sraa-paper+mat",
            "sraa-hybrid",
            "sraa-rt-paper+mat-hybrid",
        ] {
            for exhaustive in [false, true] {
                let b = |tile| {
                    CpuBackend::new()
                        .with_exhaustive_subpixel_shadows(exhaustive)
                        .with_tile(tile)
                };
                let whole = render(&b(1024), &scene, method, size);
                for tile in [1, 7, 64] {
                    let tiled = render(&b(tile), &scene, method, size);
                    assert!(
                        bits(&tiled) == bits(&whole),
                        "{} {method} (exhaustive shadows: {exhaustive}): tiles of {tile} differ from the whole frame",
                        scene.name
                    );
                    // The apron's shaded samples are shaded once per tile
                    // that reads them: never fewer rays than the whole frame.
                    assert!(tiled.stats.rays.primary >= whole.stats.rays.primary);
                    assert_eq!(tiled.stats.rays.geometry, whole.stats.rays.geometry);
                }
            }
        }
    }
}

/// The non-colour buffers are a tile's per thread: the same bytes at 256²
/// and 512² (each has at least as many tile rows as threads here).
#[test]
fn buffers_do_not_grow_with_the_image() {
    let scene = builtin("cornell").unwrap();
    let b = CpuBackend::new().with_tile(32);
    let threads = rayon_threads();
    if threads > 8 {
        println!("skipped the size comparison: {threads} threads exceed 256 / 32 tile rows");
        return;
    }
    for method in ["sraa", "sraa-rt"] {
        let other = |f: &Frame| -> usize {
            f.stats
                .buffers
                .iter()
                .filter(|(n, _)| *n != "color")
                .map(|(_, b)| b)
                .sum()
        };
        let (small, large) = (
            render(&b, &scene, method, (256, 256)),
            render(&b, &scene, method, (512, 512)),
        );
        assert_eq!(other(&small), other(&large), "{method}");
        // Per thread, one tile: at most 34² shaded samples and 32² pixels'
        // subsamples, a few hundred bytes each.
        assert!(
            other(&large) <= threads * 34 * 34 * 400,
            "{method}: {}",
            other(&large)
        );
    }
}

/// The threads the backend's tiles run on (as its buffer count assumes).
fn rayon_threads() -> usize {
    rayon::current_num_threads()
}
