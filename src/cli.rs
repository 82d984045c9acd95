//! What the command line does, as functions that return errors as values.

use std::path::Path;
use std::time::Instant;

use anyhow::{anyhow, Result};
use subcone_cpu::isa::Isa;
use subcone_load::SaveFrame;
use subcone_scene::temporal::{Taa, TaaConfig};
use subcone_scene::{Frame, Method, RenderSettings};

pub use subcone_report::setup::{backend, backend_on, parse_ao, parse_isa, parse_size, scene};

/// A built-in SDF scene written as an SDF scene file (see
/// [`subcone_load::file`]); errors name the built-in SDF scenes when
/// `name` is none of them.
pub fn export_sdf_scene(name: &str) -> Result<String> {
    use subcone_scene::builtin::sdf_builtin;
    use subcone_scene::builtin::SCENES;
    let Some(scene) = sdf_builtin(name) else {
        let known: Vec<&str> = SCENES
            .iter()
            .filter(|e| e.is_sdf())
            .map(|e| e.name)
            .collect();
        anyhow::bail!(
            "no built-in SDF scene named {name:?} (built-in SDF scenes: {})",
            known.join(", ")
        );
    };
    Ok(subcone_load::file::write_sdf_scene(&scene?)?)
}

/// What a render did.
pub struct RenderReport {
    /// Scene name.
    pub scene: String,
    /// Method.
    pub method: Method,
    /// The frame.
    pub frame: Frame,
    /// Wall time including setup (BVH build).
    pub wall_ms: f64,
    /// What the backend ran on (for `wgpu`, the adapter and driver).
    pub backend: String,
    /// The CPU backend's instruction-set path (`None` on other backends).
    pub cpu_path: Option<Isa>,
}

impl RenderReport {
    /// One line: scene, method, size, time.
    pub fn summary(&self) -> String {
        let f = &self.frame;
        format!(
            "{} {} {}x{} on {}: {:.1} ms ({:.1} ms in passes), {:.2} rays/pixel",
            self.scene,
            self.method,
            f.width,
            f.height,
            self.backend,
            self.wall_ms,
            f.stats.total_time().as_secs_f64() * 1e3,
            f.stats.rays.total() as f64 / (f.width as f64 * f.height as f64)
        )
    }

    /// SDF evaluations, samples per pixel and the share of pixels with more than
    /// one sample (the CTSS paper's Fig. 9).
    pub fn stats(&self) -> String {
        let s = &self.frame.stats;
        let px = self.frame.width as f64 * self.frame.height as f64;
        format!(
            "stats: {:.2} SDF evaluations/pixel, {:.3} samples/pixel, {:.2}% of pixels with more than one sample",
            s.sdf_evaluations as f64 / px,
            s.shaded_samples as f64 / px,
            100.0 * s.multi_sample_pixels as f64 / px
        )
    }

    /// Passes, timings, rays and buffers.
    pub fn details(&self) -> String {
        let s = &self.frame.stats;
        let px = self.frame.width as f64 * self.frame.height as f64;
        let mut out = String::new();
        if let Some(isa) = self.cpu_path {
            out += &format!("cpu path: {isa}\n");
        }
        out += &format!("passes: {:?}\n", s.passes);
        for source in s.timing_sources() {
            out += &format!("timed by: {source}\n");
        }
        for t in &s.timings {
            out += &format!(
                "  pass {:<14} {:>9.2} ms  [{}]\n",
                t.name,
                t.time.as_secs_f64() * 1e3,
                t.source.tag()
            );
        }
        let r = s.rays;
        out += &format!(
            "rays per pixel: primary {:.2}, geometry {:.2}, shadow {:.2}, secondary {:.2}, ao {:.2}\n",
            r.primary as f64 / px,
            r.geometry as f64 / px,
            r.shadow as f64 / px,
            r.secondary as f64 / px,
            r.ao as f64 / px
        );
        if s.raster_samples > 0 {
            out += &format!(
                "raster samples per pixel: {:.2} (primary visibility rasterised; a sample whose triangle the tracer's test misses is traced, and counted above)\n",
                s.raster_samples as f64 / px
            );
        }
        out += &format!("buffers: {} bytes\n", s.buffer_bytes());
        for (name, bytes) in &s.buffers {
            out += &format!("  {name:<34} {bytes:>12} bytes\n");
        }
        out
    }
}

/// An AOV image written beside the output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Aov {
    /// Shaded samples per pixel, black = 0, white = the frame's maximum.
    Samples,
    /// View depth, near = white.
    Depth,
    /// Shading normal, `0.5 + 0.5·n` as RGB.
    Normal,
}

/// What `subcone render` was asked to do.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Scene name or path.
    pub scene: String,
    /// Method with its parameters.
    pub method: Method,
    /// Backend name.
    pub backend: String,
    /// Size, mirror bounces, SDF overrides and ambient-occlusion rays; the
    /// AOVs are recorded when [`aov`](Self::aov) asks for one, whatever
    /// `settings.aovs` says.
    pub settings: RenderSettings,
    /// AOV to write beside the output.
    pub aov: Option<Aov>,
    /// Output path.
    pub output: std::path::PathBuf,
    /// CPU backend only: the instruction-set path (default: the widest the
    /// CPU supports).
    pub isa: Option<Isa>,
    /// A temporal method's frames of a still camera (at least 1): the last
    /// is the image; the time is the median frame's.
    pub frames: u32,
}

/// The path of an AOV image beside `output`: `out.png` → `out.samples.png`.
pub fn aov_path(output: &Path, aov: Aov) -> std::path::PathBuf {
    let stem = output.file_stem().and_then(|s| s.to_str()).unwrap_or("out");
    let name = format!("{stem}.{}.png", format!("{aov:?}").to_ascii_lowercase());
    output.with_file_name(name)
}

fn aov_frame(frame: &Frame, aov: Aov) -> Result<Frame> {
    let mut out = Frame::new(frame.width, frame.height);
    let missing = || anyhow!("the backend did not record the {aov:?} AOV");
    match aov {
        Aov::Samples => {
            let spp = frame.samples_per_pixel.as_ref().ok_or_else(missing)?;
            let max = spp.iter().copied().fold(0.0f32, f32::max).max(1.0);
            for (o, s) in out.color.iter_mut().zip(spp) {
                *o = glam::Vec3::splat(s / max);
            }
        }
        Aov::Depth => {
            let depth = frame.depth.as_ref().ok_or_else(missing)?;
            let finite = depth.iter().copied().filter(|d| d.is_finite());
            let (lo, hi) = finite.fold((f32::INFINITY, 0.0f32), |(l, h), d| (l.min(d), h.max(d)));
            for (o, d) in out.color.iter_mut().zip(depth) {
                let v = if d.is_finite() && hi > lo {
                    1.0 - (d - lo) / (hi - lo)
                } else {
                    0.0
                };
                *o = glam::Vec3::splat(v);
            }
        }
        Aov::Normal => {
            let normal = frame.normal.as_ref().ok_or_else(missing)?;
            for (o, n) in out.color.iter_mut().zip(normal) {
                *o = 0.5 + 0.5 * *n;
            }
        }
    }
    Ok(out)
}

/// Render a scene and write the image (and an AOV image if asked). Asks the
/// backend first ([`Backend::supports`](subcone_scene::Backend::supports)): a scene and method it does not
/// render fail with its [`subcone_scene::Unsupported`] (downcast the error to
/// read the typed reason), before anything is traced or written.
pub fn render(opts: &RenderOptions) -> Result<RenderReport> {
    let backend = backend_on(&opts.backend, opts.isa)?;
    let scene = scene(&opts.scene)?;
    backend.supports(&scene, &opts.method.single_frame())?;
    let settings = RenderSettings {
        aovs: opts.aov.is_some(),
        ..opts.settings
    };
    settings
        .validate()
        .map_err(|e| ao_context(e, settings.ao_rays))?;
    if opts.method.is_hybrid() && scene.sdf_geometry().is_some() {
        eprintln!(
            "note: {} is an SDF scene, with no triangles to rasterise: {} traces its rays as {} does",
            scene.name,
            opts.method,
            opts.method.traced()
        );
    }
    let (frame, wall_ms) = if opts.method.is_temporal() {
        if opts.frames == 0 {
            return Err(anyhow!(
                "--frames: a temporal method needs at least one frame"
            ));
        }
        let mut taa = Taa::new(opts.method, TaaConfig::default())?;
        let bar = indicatif::ProgressBar::new(u64::from(opts.frames));
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..opts.frames {
            let start = Instant::now();
            last = Some(taa.render(backend.as_ref(), &scene, &scene.camera, &settings)?);
            times.push(start.elapsed().as_secs_f64() * 1e3);
            bar.inc(1);
        }
        bar.finish_and_clear();
        times.sort_by(f64::total_cmp);
        let frame = last.ok_or_else(|| anyhow!("no frame rendered"))?;
        (frame, times[times.len() / 2])
    } else {
        let start = Instant::now();
        let frame = backend.render(&scene, &scene.camera, &opts.method, &settings)?;
        (frame, start.elapsed().as_secs_f64() * 1e3)
    };
    frame.save(&opts.output)?;
    if let Some(aov) = opts.aov {
        aov_frame(&frame, aov)?.save(&aov_path(&opts.output, aov))?;
    }
    let cpu_path = (opts.backend.trim() == "cpu")
        .then(|| opts.isa.map_or_else(Isa::detected, Isa::or_supported));
    Ok(RenderReport {
        cpu_path,
        backend: backend.describe(),
        scene: scene.name.clone(),
        method: opts.method,
        frame,
        wall_ms,
    })
}

/// A settings error, naming the `--ao` flag when it is about the AO rays.
pub fn ao_context(e: subcone_scene::RenderError, ao: u32) -> anyhow::Error {
    if ao > subcone_scene::backend::MAX_AO_RAYS {
        anyhow!("--ao {ao}: {e}")
    } else {
        e.into()
    }
}
