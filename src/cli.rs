//! What the command line does, as functions that return errors as values.

use std::path::Path;
use std::time::Instant;

use anyhow::{anyhow, Result};
use subcone_cpu::CpuBackend;
use subcone_scene::{Backend, Frame, Method, RenderSettings, Scene};

/// Parse `WxH` (e.g. `1024x768`).
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| anyhow!("invalid --size {s:?}: expected WxH, e.g. 512x512"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| anyhow!("invalid --size {s:?}: {v:?} is not a whole number"))
    };
    Ok((p(w)?, p(h)?))
}

/// A backend by name (`cpu`).
pub fn backend(name: &str) -> Result<Box<dyn Backend + Send + Sync>> {
    match name {
        "cpu" => Ok(Box::new(CpuBackend::new())),
        other => Err(anyhow!("unknown backend {other:?}: expected cpu")),
    }
}

/// Load a scene by name (built-in, or `sponza`/`sponza-mirror` from the data
/// directory) or by path (`.obj`, `.gltf`, `.glb`).
pub fn scene(arg: &str) -> Result<Scene> {
    Ok(subcone_scene::load::scene_from_arg(arg)?)
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
}

impl RenderReport {
    /// One line: scene, method, size, time.
    pub fn summary(&self) -> String {
        let f = &self.frame;
        format!(
            "{} {} {}x{}: {:.1} ms ({:.1} ms in passes), {:.2} rays/pixel",
            self.scene,
            self.method,
            f.width,
            f.height,
            self.wall_ms,
            f.stats.total_time().as_secs_f64() * 1e3,
            f.stats.rays.total() as f64 / (f.width as f64 * f.height as f64)
        )
    }

    /// Passes, timings, rays and buffers.
    pub fn details(&self) -> String {
        let s = &self.frame.stats;
        let px = self.frame.width as f64 * self.frame.height as f64;
        let mut out = format!("passes: {:?}\n", s.passes);
        for t in &s.timings {
            out += &format!(
                "  pass {:<14} {:>9.2} ms\n",
                t.name,
                t.time.as_secs_f64() * 1e3
            );
        }
        let r = s.rays;
        out += &format!(
            "rays per pixel: primary {:.2}, geometry {:.2}, shadow {:.2}, secondary {:.2}\n",
            r.primary as f64 / px,
            r.geometry as f64 / px,
            r.shadow as f64 / px,
            r.secondary as f64 / px
        );
        out += &format!("buffers: {} bytes\n", s.buffer_bytes());
        for (name, bytes) in &s.buffers {
            out += &format!("  {name:<34} {bytes:>12} bytes\n");
        }
        out
    }
}

/// Render `scene_arg` with `method` on the CPU and write the image to `output`.
pub fn render(
    scene_arg: &str,
    method: Method,
    width: u32,
    height: u32,
    reflection_depth: u32,
    output: &Path,
) -> Result<RenderReport> {
    let scene = scene(scene_arg)?;
    let mut settings = RenderSettings::new(width, height);
    settings.reflection_depth = reflection_depth;
    settings.validate()?;
    let start = Instant::now();
    let frame = CpuBackend::new().render(&scene, &scene.camera, &method, &settings)?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    frame.save(output)?;
    Ok(RenderReport {
        scene: scene.name.clone(),
        method,
        frame,
        wall_ms,
    })
}
