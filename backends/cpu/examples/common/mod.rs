//! What the examples' command lines share: a frame size and a scene, read
//! from their arguments, each error a message that names the argument.

use std::process::ExitCode;

use subcone_load::scene_from_arg;
use subcone_scene::Scene;

/// `WxH` as a width and a height.
pub fn size(size: &str) -> Result<(u32, u32), String> {
    size.split_once('x')
        .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
        .ok_or_else(|| format!("size {size:?} is not WxH"))
}

/// A built-in scene by name, or a mesh or SDF scene file by path.
pub fn scene(name: &str) -> Result<Scene, String> {
    scene_from_arg(name).map_err(|e| format!("{name}: {e}"))
}

/// The exit code of an example's run, its error printed.
pub fn exit(run: Result<(), String>) -> ExitCode {
    match run {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
