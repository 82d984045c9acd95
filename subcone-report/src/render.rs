//! One render of a scene, timed and checked against the size asked for, and
//! the edge classes of an image from the sub-sample AOVs of a NoAA render.

use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Result};
use subcone_scene::{Backend, Frame, Method, RenderSettings, Scene};

use crate::classes;
use crate::named::NOAA;

pub(crate) fn render(
    backend: &dyn Backend,
    scene: &Scene,
    method: &Method,
    settings: &RenderSettings,
) -> Result<(Frame, Duration)> {
    render_from(backend, scene, &scene.camera, method, settings)
}

/// Sub-samples per pixel side for the classes of a `w × h` image:
/// [`classes::SUBSAMPLES`], fewer when that frame would be beyond
/// [`subcone_scene::backend::MAX_PIXELS`].
pub(crate) fn sub_sample_side(w: u32, h: u32) -> u32 {
    (1..=classes::SUBSAMPLES)
        .rev()
        .find(|s| {
            let mut t = RenderSettings::new(w * s, h * s);
            t.aovs = true;
            t.validate().is_ok()
        })
        .unwrap_or(1)
}

/// The edge classes of a `w × h` image of `scene` seen from `camera`, from
/// the AOVs of a NoAA frame of `backend` (the cpu's: it records them all)
/// at [`sub_sample_side`]× the size per side.
pub(crate) fn classes_at(
    backend: &dyn Backend,
    scene: &Scene,
    camera: &subcone_scene::Camera,
    (w, h): (u32, u32),
) -> Result<classes::ClassMasks> {
    let side = sub_sample_side(w, h);
    let mut settings = RenderSettings::new(w * side, h * side);
    settings.aovs = true;
    let (sub, _) = render_from(backend, scene, camera, &NOAA, &settings)?;
    classes::classify(&sub, side)
}

/// [`render`] from `camera` instead of the scene's.
pub(crate) fn render_from(
    backend: &dyn Backend,
    scene: &Scene,
    camera: &subcone_scene::Camera,
    method: &Method,
    settings: &RenderSettings,
) -> Result<(Frame, Duration)> {
    let start = Instant::now();
    let frame = backend
        .render(scene, camera, method, settings)
        .map_err(|e| anyhow!("{} {} {}: {e}", backend.name(), scene.name, method))?;
    let wall = start.elapsed();
    let n = settings.width as usize * settings.height as usize;
    if frame.width != settings.width || frame.height != settings.height || frame.color.len() != n {
        bail!(
            "{} {} {}: the backend returned a {}x{} frame with {} pixels for {}x{}",
            backend.name(),
            scene.name,
            method,
            frame.width,
            frame.height,
            frame.color.len(),
            settings.width,
            settings.height
        );
    }
    Ok((frame, wall))
}
