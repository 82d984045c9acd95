//! What a run is made of, from the words a user types: scenes, backends,
//! image sizes and instruction-set paths. The command line and the report
//! both build their runs from here.

use anyhow::{anyhow, Result};
use subcone_cpu::isa::Isa;
use subcone_cpu::CpuBackend;
use subcone_scene::{Backend, Scene};

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

/// A backend by name (`cpu` or `wgpu`). Opening `wgpu` fails with a message
/// naming the fix when no GPU adapter exists.
pub fn backend(name: &str) -> Result<Box<dyn Backend + Send + Sync>> {
    backend_on(name, None)
}

/// [`backend`], with the CPU backend's instruction-set path forced to `isa`
/// ([`CpuBackend::with_isa`]); `isa` with another backend is an error.
pub fn backend_on(name: &str, isa: Option<Isa>) -> Result<Box<dyn Backend + Send + Sync>> {
    match (name.trim(), isa) {
        ("cpu", Some(isa)) => Ok(Box::new(CpuBackend::new().with_isa(isa))),
        (other, Some(_)) if other != "cpu" => Err(anyhow!(
            "--isa chooses the cpu backend's instruction-set path; backend {other:?} has none"
        )),
        ("cpu", _) => Ok(Box::new(CpuBackend::new())),
        ("wgpu", _) => Ok(Box::new(subcone_wgpu::WgpuBackend::new()?)),
        (other, _) => Err(anyhow!("unknown backend {other:?}: expected cpu or wgpu")),
    }
}

/// Load a scene by name (built-in, or `sponza`/`sponza-mirror` from the data
/// directory) or by path (`.obj`, `.gltf`, `.glb`).
pub fn scene(arg: &str) -> Result<Scene> {
    Ok(subcone_load::scene_from_arg(arg)?)
}

/// Parse `--isa`: `baseline`, `avx2` or `avx512`.
pub fn parse_isa(s: &str) -> std::result::Result<Isa, String> {
    s.trim().parse()
}

/// Parse and check `--ao N`: ambient-occlusion rays per shaded point, at
/// most [`subcone_scene::backend::MAX_AO_RAYS`].
pub fn parse_ao(s: &str) -> std::result::Result<u32, String> {
    let max = subcone_scene::backend::MAX_AO_RAYS;
    let n: u32 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a whole number of rays (0 to {max})"))?;
    if n > max {
        return Err(format!(
            "{n} ambient-occlusion rays per point: at most {max} are supported"
        ));
    }
    Ok(n)
}
