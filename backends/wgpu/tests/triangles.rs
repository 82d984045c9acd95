//! The wgpu backend on triangle scenes against the CPU reference: per-pixel
//! agreement for every built-in triangle scene and method, the passes left
//! out, the statistics, and errors instead of panics.
use std::time::Instant;

use glam::Vec3;
use subcone_cpu::CpuBackend;
use subcone_kernels::passes::Passes;
use subcone_scene::{
    builtin::builtin, Backend, Frame, Material, Method, RenderError, RenderSettings, Scene,
    TriangleMesh,
};
use subcone_wgpu::test_util::gpu_or_skip;
use subcone_wgpu::WgpuBackend;

/// The backend, or `None` when the test may skip (see [`gpu_or_skip`]).
fn gpu() -> Option<WgpuBackend> {
    gpu_or_skip("triangles")
}

fn render(b: &dyn Backend, scene: &Scene, method: &str, w: u32, h: u32) -> Frame {
    let m: Method = method.parse().unwrap();
    b.render(scene, &scene.camera, &m, &RenderSettings::new(w, h))
        .unwrap_or_else(|e| panic!("{} {method}: {e}", b.name()))
}

/// Mean absolute difference per channel of the clamped linear colours, and the
/// fraction of pixels where any channel differs by more than 0.05.
fn compare(a: &Frame, b: &Frame) -> (f64, f64) {
    let mut sum = 0.0;
    let mut bad = 0;
    for (p, q) in a.color.iter().zip(&b.color) {
        let d = (p.clamp(Vec3::ZERO, Vec3::ONE) - q.clamp(Vec3::ZERO, Vec3::ONE)).abs();
        sum += (d.x + d.y + d.z) as f64 / 3.0;
        if d.max_element() > 0.05 {
            bad += 1;
        }
    }
    let n = a.color.len() as f64;
    (sum / n, bad as f64 / n)
}

/// wgpu against the CPU on cornell, cornell-nomirror, checker and atrium, for NoAA,
/// SSAA4, SRAA and SRAA-RT at 48×40. Both trace the same rays through
/// the same BVH leaves with the same shading, so NoAA, SSAA and SRAA-RT
/// differ only by f32 rounding (GPU `exp`/`normalize`, fused multiply-adds)
/// where a ray grazes an edge or a shadow boundary: mean error below 0.002,
/// at most 1 % of pixels off by more than 0.05. Hybrid SRAA rasterises its
/// subsamples, whose coverage at silhouettes follows the rasteriser's
/// tie-breaking rules, not the ray's: mean error below 0.01, at most 5 %.
#[test]
fn wgpu_matches_cpu_on_builtin_scenes() {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    for scene_name in ["cornell", "cornell-nomirror", "checker", "atrium"] {
        let scene = builtin(scene_name).unwrap();
        for method in ["noaa", "ssaa4", "sraa-rt", "sraa"] {
            let t = Instant::now();
            let g = render(&gpu, &scene, method, 48, 40);
            let gpu_time = t.elapsed();
            let c = render(&cpu, &scene, method, 48, 40);
            let (mean, frac) = compare(&g, &c);
            eprintln!(
                "{scene_name} {method}: mean {mean:.5}, >0.05 on {:.2} % ({gpu_time:?} on the GPU)",
                frac * 100.0
            );
            assert!(
                g.color.iter().all(|c| c.is_finite()),
                "{scene_name} {method}: NaN"
            );
            let (max_mean, max_frac) = if method == "sraa" {
                (0.01, 0.05)
            } else {
                (0.002, 0.01)
            };
            assert!(
                mean < max_mean && frac <= max_frac,
                "{scene_name} {method}: mean {mean}, fraction {frac}"
            );
            // The same work, counted the same way (sraa's geometry is rasterised).
            assert_eq!(
                g.stats.rays.primary, c.stats.rays.primary,
                "{scene_name} {method}"
            );
            if method != "sraa" {
                let close = |a: u64, b: u64| a.abs_diff(b) as f64 <= 0.01 * b as f64 + 2.0;
                assert!(
                    close(g.stats.rays.shadow, c.stats.rays.shadow)
                        && close(g.stats.rays.geometry, c.stats.rays.geometry)
                        && close(g.stats.rays.secondary, c.stats.rays.secondary)
                        && close(g.stats.shaded_samples, c.stats.shaded_samples),
                    "{scene_name} {method}: rays {:?} vs {:?}",
                    g.stats.rays,
                    c.stats.rays
                );
            } else {
                assert_eq!(
                    g.stats.rays.geometry, 0,
                    "hybrid SRAA traces no geometry rays"
                );
            }
            assert_eq!(g.stats.passes, c.stats.passes);
            let names: Vec<_> = g.stats.timings.iter().map(|t| t.name).collect();
            let cpu_names: Vec<_> = c.stats.timings.iter().map(|t| t.name).collect();
            assert_eq!(names, cpu_names, "{scene_name} {method}");
        }
    }
}

/// Buffers follow the plan: a scene without mirrors gets no secondary
/// buffer, one with mirrors and lights gets every SRAA-RT buffer, and the
/// reported sizes are the real ones.
#[test]
fn passes_left_out_allocate_nothing() {
    let Some(gpu) = gpu() else { return };
    let (w, h) = (24u32, 16u32);
    let n = (w * h) as usize;
    let names = |f: &Frame| -> Vec<&'static str> { f.stats.buffers.iter().map(|b| b.0).collect() };

    let plain = builtin("cornell-nomirror").unwrap();
    let f = render(&gpu, &plain, "sraa-rt", w, h);
    assert!(!f
        .stats
        .passes
        .intersects(Passes::SECONDARY | Passes::SUBPIXEL_SECONDARY_GEOMETRY));
    for b in names(&f) {
        assert!(!b.contains("secondary"), "cornell-nomirror allocated {b:?}");
    }
    assert!(names(&f).contains(&"subpixel shadow states"));

    let mirror = builtin("cornell").unwrap();
    let f = render(&gpu, &mirror, "sraa-rt", w, h);
    for b in [
        "secondary geometry",
        "secondary shadow states",
        "subpixel secondary geometry",
        "subpixel secondary shadow states",
        "subpixel shadow states",
        "shadow states",
    ] {
        assert!(
            names(&f).contains(&b),
            "cornell lacks {b:?}: {:?}",
            names(&f)
        );
    }
    let size = |name: &str| f.stats.buffers.iter().find(|b| b.0 == name).unwrap().1;
    assert_eq!(size("subpixel geometry"), n * 4 * 16);
    assert_eq!(size("color"), n * 16);
    let lights = mirror.lights.len();
    assert_eq!(size("shading layers"), n * 2 * (1 + lights) * 16);

    // Hybrid SRAA: one layer, raster targets, no shadow or secondary buffers.
    let f = render(&gpu, &mirror, "sraa", w, h);
    for b in names(&f) {
        assert!(
            !b.contains("shadow") && !b.contains("secondary"),
            "sraa allocated {b:?}"
        );
    }
    assert!(names(&f).contains(&"raster depth"));

    // A scene without lights: no shadow buffers, no shadow rays.
    let mut dark = builtin("cornell-nomirror").unwrap();
    dark.lights.clear();
    dark.touch();
    let f = render(&gpu, &dark, "sraa-rt", w, h);
    assert!(!f.stats.passes.contains(Passes::SHADOW));
    assert_eq!(f.stats.rays.shadow, 0);
    for b in names(&f) {
        assert!(
            !b.contains("shadow"),
            "a scene without lights allocated {b:?}"
        );
    }
}

/// Timings per pass, ray counts that follow from the image size, AOVs.
#[test]
fn stats_and_aovs() {
    let Some(gpu) = gpu() else { return };
    let scene = builtin("cornell").unwrap();
    let m: Method = "ssaa4".parse().unwrap();
    let mut s = RenderSettings::new(20, 12);
    s.aovs = true;
    let f = gpu.render(&scene, &scene.camera, &m, &s).unwrap();
    assert_eq!(f.stats.rays.primary, 20 * 12 * 4);
    assert_eq!(f.stats.timings.len(), 1);
    let cpu = CpuBackend::new()
        .render(&scene, &scene.camera, &m, &s)
        .unwrap();
    let (d, dc) = (f.depth.as_ref().unwrap(), cpu.depth.as_ref().unwrap());
    let agree = d
        .iter()
        .zip(dc)
        .filter(|(a, b)| a == b || (*a - *b).abs() <= 1e-4 * a.abs())
        .count();
    assert!(
        agree >= d.len() * 95 / 100,
        "{agree}/{} AOV depths agree",
        d.len()
    );
    assert_eq!(f.samples_per_pixel.as_ref().unwrap()[0], 4.0);
    let m: Method = "sraa-rt".parse().unwrap();
    let f = gpu.render(&scene, &scene.camera, &m, &s).unwrap();
    let names: Vec<_> = f.stats.timings.iter().map(|t| t.name).collect();
    assert_eq!(names, ["shading", "geometry", "antialiasing"]);
    assert!(f.stats.rays.geometry >= 20 * 12 * 3);
    assert!(f.normal.is_some());
}

/// SSAA256 traces 256 samples per pixel with mirror bounces: far more loop
/// iterations than one shader invocation may run on llvmpipe (it cuts a shader
/// invocation's loops after 65 535 iterations in total, silently). The
/// backend splits the grid into one dispatch per row, so every sample is
/// traced: the ray counts equal the CPU's, and so do the colours (within
/// 1e-3 per channel on every pixel but a handful at grazing edges).
#[test]
fn ssaa256_traces_every_sample() {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    let scene = builtin("cornell").unwrap();
    let g = render(&gpu, &scene, "ssaa256", 24, 24);
    let c = render(&cpu, &scene, "ssaa256", 24, 24);
    assert_eq!(g.stats.rays.primary, 24 * 24 * 256);
    assert_eq!(g.stats.rays.secondary, c.stats.rays.secondary);
    let close = |a: u64, b: u64| a.abs_diff(b) <= 2;
    assert!(close(g.stats.rays.shadow, c.stats.rays.shadow));
    let off = g
        .color
        .iter()
        .zip(&c.color)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3)
        .count();
    assert!(off <= 3, "{off} pixels differ");
}

/// Albedo textures (nearest, wrapping, as `Texture::sample`) and directional
/// lights, which no built-in scene uses: cornell with a 5×3 texture on its
/// white walls and a directional light added. NoAA and SRAA-RT against the
/// CPU: at most 1 % of pixels off by more than 0.05, mean below 0.002.
#[test]
fn textures_and_directional_lights_match_cpu() {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    let mut scene = builtin("cornell").unwrap();
    let texels = (0..15)
        .map(|i| Vec3::new((i % 5) as f32 / 4.0, (i / 5) as f32 / 2.0, 0.3))
        .collect();
    let texture = std::sync::Arc::new(subcone_scene::material::Texture {
        width: 5,
        height: 3,
        texels,
    });
    scene.materials[0].albedo = subcone_scene::Albedo::Texture(texture);
    scene.lights.push(subcone_scene::Light::Directional {
        direction: Vec3::new(0.3, 1.0, 0.5),
        irradiance: Vec3::new(0.4, 0.35, 0.3),
    });
    scene.touch();
    for method in ["noaa", "sraa-rt"] {
        let g = render(&gpu, &scene, method, 40, 32);
        let c = render(&cpu, &scene, method, 40, 32);
        let (mean, frac) = compare(&g, &c);
        eprintln!(
            "textured {method}: mean {mean:.5}, >0.05 on {:.2} %",
            frac * 100.0
        );
        assert!(
            mean < 0.002 && frac <= 0.01,
            "{method}: mean {mean}, fraction {frac}"
        );
        assert_eq!(g.stats.rays.shadow, c.stats.rays.shadow, "{method}");
    }
}

/// Bad input is an error, never a panic.
#[test]
fn errors_not_panics() {
    let Some(gpu) = gpu() else { return };
    let cornell = builtin("cornell").unwrap();
    // No triangles.
    let mut empty = cornell.clone();
    if let subcone_scene::Geometry::Triangles(m) = &mut empty.geometry {
        *m = TriangleMesh::default();
    }
    empty.touch();
    let m: Method = "noaa".parse().unwrap();
    let r = gpu.render(&empty, &empty.camera, &m, &RenderSettings::new(8, 8));
    assert!(
        matches!(
            r,
            Err(RenderError::Backend { .. }) | Err(RenderError::Scene(_))
        ),
        "{r:?}"
    );

    // A texture larger than any storage buffer.
    let mut big = cornell.clone();
    let side = 1u32 << 16;
    big.materials[0] = Material {
        albedo: subcone_scene::Albedo::Texture(std::sync::Arc::new(
            subcone_scene::material::Texture {
                width: side,
                height: side,
                texels: vec![Vec3::ONE; 1],
            },
        )),
        ..big.materials[0].clone()
    };
    big.touch();
    let r = gpu.render(&big, &big.camera, &m, &RenderSettings::new(8, 8));
    assert!(r.is_err(), "an inconsistent texture was accepted");

    // CTSS needs an SDF.
    let ctss: Result<Method, _> = "ctss".parse();
    if let Ok(ctss) = ctss {
        assert!(gpu
            .render(&cornell, &cornell.camera, &ctss, &RenderSettings::new(8, 8))
            .is_err());
    }
}

/// Lavapipe time of each method at 128×128 on cornell against the CPU
/// backend (printed; run with `--ignored --nocapture`). SRAA-RT runs before
/// SRAA: on lavapipe, GPU timestamps of compute-only frames read a few µs
/// once any render pass (SRAA's raster) has run in the process.
#[test]
#[ignore]
fn timings_128() {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    let scene = builtin("cornell").unwrap();
    for method in [
        "noaa", "ssaa4", "ssaa16", "ssaa64", "ssaa256", "sraa-rt", "sraa",
    ] {
        render(&gpu, &scene, method, 128, 128);
        let t = Instant::now();
        let g = render(&gpu, &scene, method, 128, 128);
        let tg = t.elapsed();
        let t = Instant::now();
        let c = render(&cpu, &scene, method, 128, 128);
        let tc = t.elapsed();
        let (mean, _) = compare(&g, &c);
        eprintln!(
            "{method}: wgpu {tg:?} (passes {:?}), cpu {tc:?}, mean diff {mean:.5}",
            g.stats
                .timings
                .iter()
                .map(|t| (t.name, t.time))
                .collect::<Vec<_>>()
        );
    }
}

/// Uploaded scenes and pipelines are cached per device: a second device
/// (its own wgpu instance, whose ids repeat the first's) renders the same
/// image from its own buffers.
#[test]
fn a_second_device_renders_the_same_image() {
    let Some(gpu) = gpu() else { return };
    let other = WgpuBackend::with_context(std::sync::Arc::new(
        subcone_wgpu::GpuContext::new().expect("a second device"),
    ));
    let scene = builtin("cornell").unwrap();
    for method in ["noaa", "sraa", "sraa-rt"] {
        let a = render(&gpu, &scene, method, 24, 20);
        let b = render(&other, &scene, method, 24, 20);
        assert_eq!(a.color, b.color, "{method}");
    }
}

/// A frame whose buffers exceed the adapter's storage binding limit is an
/// error that names the limit, not a panic or a device loss. SRAA-RT keeps
/// 64 bytes of subpixel geometry per pixel (4 subsamples × 16 bytes).
#[test]
fn buffers_over_the_adapter_limit_are_an_error() {
    let Some(gpu) = gpu() else { return };
    let limit = gpu
        .context()
        .device
        .limits()
        .max_storage_buffer_binding_size;
    let side = ((limit as f64 / 64.0).sqrt().ceil() as u32 + 1).max(2);
    let settings = RenderSettings::new(side, side);
    if settings.validate().is_err() {
        // This adapter binds more than the largest frame subcone accepts.
        println!("storage binding limit {limit} bytes: no valid frame exceeds it");
        return;
    }
    let scene = builtin("cornell").unwrap();
    let method: Method = "sraa-rt".parse().unwrap();
    let err = gpu
        .render(&scene, &scene.camera, &method, &settings)
        .expect_err("over the limit");
    let msg = err.to_string();
    assert!(
        matches!(
            err,
            RenderError::LimitExceeded {
                limit: "max_storage_buffer_binding_size",
                ..
            }
        ),
        "{msg}"
    );
    assert!(msg.contains("max_storage_buffer_binding_size"), "{msg}");
    println!("{side}x{side}: {msg}");
}

/// Ambient occlusion (`RenderSettings::ao_rays`) on the GPU against the CPU:
/// cornell with 4 AO rays at 48×40, NoAA, SSAA4 and SRAA-RT, within the
/// bounds of `wgpu_matches_cpu_on_builtin_scenes` (the same rays; the AO
/// directions differ by the WGSL twin's tolerance, `TOL_AO_DIRECTION`, which
/// can flip a grazing occlusion ray), and the same number of AO rays within
/// 1 %.
#[test]
fn ambient_occlusion_matches_cpu() {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    let scene = builtin("cornell").unwrap();
    let mut s = RenderSettings::new(48, 40);
    s.ao_rays = 4;
    for method in ["noaa", "ssaa4", "sraa-rt"] {
        let m: Method = method.parse().unwrap();
        let g = gpu.render(&scene, &scene.camera, &m, &s).unwrap();
        let c = cpu.render(&scene, &scene.camera, &m, &s).unwrap();
        let (mean, frac) = compare(&g, &c);
        eprintln!(
            "cornell --ao 4 {method}: mean {mean:.5}, >0.05 on {:.2} %",
            frac * 100.0
        );
        assert!(
            mean < 0.002 && frac <= 0.01,
            "cornell --ao 4 {method}: mean {mean}, fraction {frac}"
        );
        let (a, b) = (g.stats.rays.ao, c.stats.rays.ao);
        assert!(b > 0, "{method}: the CPU cast no AO rays");
        assert!(
            a.abs_diff(b) as f64 <= 0.01 * b as f64 + 2.0,
            "{method}: AO rays {a} on the GPU, {b} on the CPU"
        );
        // AO changes the image: the ambient term of occluded points darkens.
        let plain = gpu
            .render(&scene, &scene.camera, &m, &RenderSettings::new(48, 40))
            .unwrap();
        assert_ne!(plain.color, g.color, "{method}: AO changed nothing");
    }
}

/// Hybrid SRAA (`sraa`, `sraa-paper`, `sraa+mat`) resolves through
/// `subcone_passes::SraaPass`, the pass a host renderer runs, with no
/// copy around it: the shading pass writes the textures the resolve reads
/// (the shaded colour, the centre geometry where the preset shades the
/// centre, the albedo with `+mat`) and the frame is read back from the
/// resolve's output. The frame lists each once, at its size, and none of
/// the buffers SRAA-RT's resolve reads (`color`, `geometry`, `shading
/// layers`, `albedo`), which would hold the same data again.
#[test]
fn hybrid_sraa_resolves_through_the_pass_crate_without_copies() {
    let Some(g) = gpu() else { return };
    let scene = builtin("cornell").unwrap();
    let (w, h) = (16, 12);
    let n = (w * h) as usize;
    let buffers = |method: &str| -> Vec<(&'static str, usize)> {
        render(&g, &scene, method, w, h).stats.buffers
    };
    let names =
        |b: &[(&'static str, usize)]| -> Vec<&'static str> { b.iter().map(|b| b.0).collect() };
    let size =
        |b: &[(&'static str, usize)], name: &str| b.iter().find(|b| b.0 == name).map(|b| b.1);
    let rt_resolve_inputs = ["color", "geometry", "shading layers", "albedo"];

    let tuned = buffers("sraa");
    assert_eq!(size(&tuned, "shaded colour"), Some(n * 16), "{tuned:?}");
    // R32Float depth and Rgba16Float normal (resolve.rs).
    assert_eq!(
        size(&tuned, "shaded centre geometry"),
        Some(n * 12),
        "{tuned:?}"
    );
    assert_eq!(size(&tuned, "sraa output"), Some(n * 16), "{tuned:?}");
    assert_eq!(size(&tuned, "shaded albedo"), None, "{tuned:?}");
    let paper = buffers("sraa-paper");
    assert_eq!(size(&paper, "shaded colour"), Some(n * 16), "{paper:?}");
    assert_eq!(
        size(&paper, "shaded centre geometry"),
        None,
        "sraa-paper shades subsample 0: {paper:?}"
    );
    let material = buffers("sraa+mat");
    assert_eq!(
        size(&material, "shaded albedo"),
        Some(n * 16),
        "{material:?}"
    );
    for b in [&tuned, &paper, &material] {
        let names = names(b);
        for copy in rt_resolve_inputs {
            assert!(
                !names.contains(&copy),
                "hybrid SRAA allocated {copy:?}: {names:?}"
            );
        }
        let mut unique = names.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "a name listed twice: {names:?}");
    }
    let rt = names(&buffers("sraa-rt"));
    for b in ["shaded colour", "shaded centre geometry", "sraa output"] {
        assert!(!rt.contains(&b), "sraa-rt allocated {b:?}: {rt:?}");
    }
    for b in ["color", "geometry", "shading layers"] {
        assert!(rt.contains(&b), "sraa-rt lacks {b:?}: {rt:?}");
    }
}

/// Hybrid SRAA's frame is read back from a texture whose rows wgpu pads to
/// 256 bytes: at a width whose rows are not a multiple of that (21 pixels,
/// 336 bytes), and with FXAA forced after the resolve (which reads a colour
/// buffer, the one case the output is copied into one), the frame is still
/// the CPU's within hybrid SRAA's tolerance (mean below 0.01, at most 5 % of
/// pixels off by more than 0.05), and FXAA changes it.
#[test]
fn hybrid_sraa_reads_back_padded_rows_and_feeds_a_post_process() {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    let scene = builtin("cornell").unwrap();
    let m: Method = "sraa".parse().unwrap();
    let (w, h) = (21, 13);
    let plain = RenderSettings::new(w, h);
    let mut post = plain;
    post.force_passes = Passes::POST_PROCESS;
    let mut frames = Vec::new();
    for s in [&plain, &post] {
        let g = gpu.render(&scene, &scene.camera, &m, s).unwrap();
        let c = cpu.render(&scene, &scene.camera, &m, s).unwrap();
        let (mean, frac) = compare(&g, &c);
        let post_process = s.force_passes.contains(Passes::POST_PROCESS);
        assert!(
            mean < 0.01 && frac <= 0.05,
            "post-process {post_process}: mean {mean}, fraction {frac}"
        );
        let names: Vec<_> = g.stats.buffers.iter().map(|b| b.0).collect();
        assert_eq!(names.contains(&"color"), post_process, "{names:?}");
        frames.push(g);
    }
    assert_ne!(frames[0].color, frames[1].color, "FXAA changed nothing");
}
