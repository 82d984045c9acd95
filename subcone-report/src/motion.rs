//! Antialiasing in motion (`report --motion`; the quick report runs a small
//! version).
//!
//! Neither paper measures temporal stability, yet motion is what viewers
//! see: a sub-pixel feature that one frame's sample catches and the next
//! misses flickers. Each scene's camera follows a short path of sub-pixel
//! steps ([`camera_path`]: a pan of [`PAN_PIXELS`] and a dolly that moves
//! the image edge by [`DOLLY_PIXELS`] per frame), and every frame of each
//! method is compared with that frame's reference:
//!
//! - **FLIP per frame** against the reference, averaged over the frames;
//! - **temporal instability** per edge class: for frames `1..N`, the mean
//!   over the class's pixels (classes from each frame's own sub-sample
//!   AOVs, as in the still report) of `|Δmethod − Δreference|`, where `Δ` is
//!   a pixel's change of luminance from the previous frame. A method that
//!   changes as the reference changes scores 0; one that adds flicker the
//!   reference does not have is penalised, and one that follows the
//!   reference's own change is not.
//!
//! The section has a table and a chart (FLIP per frame) per scene, and an
//! animated PNG of the window where NoAA is least stable: NoAA, each method
//! and the reference side by side, each tile named above it and the frame's
//! number below, the frames played forward then backward ([`ping_pong`]), so
//! that the loop steps back from the last frame to the one before it instead
//! of jumping to the first (a jump of `N − 1` camera steps).
//!
//! A camera moving over still scenes never shows TAA its hardest case: an
//! object moving over a background, whose neighbour pixels move differently
//! and which uncovers background its history does not hold. The section
//! ends with such a scene ([`MovingObject::cornell_box`]: a cube crossing
//! the Cornell box at [`MOVING_PIXELS`] a frame, on the same camera path),
//! `taa` given the object's and the camera's motion vectors, without and
//! with closest-depth dilation ([`DepthDilation`]), beside NoAA: FLIP per
//! frame, and the FLIP on the pixels the cube uncovered, judged
//! [`MOVING_JUDGED_AFTER`] frames later (a history smeared over them stays
//! above NoAA's there; [`MovingObjectRun`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{anyhow, Context, Result};
use glam::Quat;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::classes::{self, ClassMasks, CLASSES};
use crate::named::{CTSS, CTSS_TAA, NOAA, SRAA_RT, SRAA_RT_TAA, SSAA4, TAA};
use crate::plot::{legend, method_line, save_chart, Chart, FAMILY, PLOT_SIZE};
use crate::{classes_at, file_safe, render_from, Runner, SceneJob};
use subcone_kernels::taa::DepthDilation;
use subcone_metrics::{self as metrics, Rgb8};
use subcone_scene::moving::{disoccluded, MovingObject};
use subcone_scene::temporal::{Taa, TaaConfig};
use subcone_scene::{Backend, Camera, Frame, Method, RenderSettings};

mod animation;
mod moving;
#[cfg(test)]
mod tests;

pub use animation::{ping_pong, save_apng};
use animation::{strip, worst_window};
pub use moving::{
    moving_against_camera_only, moving_object, moving_section, MovingObjectRun, MovingRow,
    MOVING_JUDGED_AFTER, MOVING_PIXELS,
};

/// Frames of the path with `--motion`.
pub const FRAMES: u32 = 16;
/// Frames of the quick report's small version.
pub const QUICK_FRAMES: u32 = 4;
/// Image size with `--motion` (the quick version uses the quick size).
pub const MOTION_SIZE: (u32, u32) = (320, 180);
/// The methods followed (each where the CPU backend runs it): the
/// single-frame ones and, after each that runs under TAA, its `+taa`
/// sequence (a reset at the path's first frame).
pub const MOTION_METHODS: [Method; 7] = [NOAA, SSAA4, TAA, SRAA_RT, SRAA_RT_TAA, CTSS, CTSS_TAA];
/// The reference of every frame: 64 samples per pixel, a quarter of the
/// still report's ssaa256, to keep a run of N frames affordable.
pub const MOTION_REFERENCE: Method = Method::ssaa_grid(8);
/// Pan per frame, in pixels at the image centre (a yaw about the camera's
/// up axis).
pub const PAN_PIXELS: f32 = 0.37;
/// Dolly per frame: the camera moves forward so that a point at the subject
/// distance on the image's left or right edge moves by this many pixels.
pub const DOLLY_PIXELS: f32 = 0.25;
/// Side of the window the animation shows, in pixels (smaller on small
/// images).
pub const CROP_SIDE: u32 = 24;
/// Zoom of the animation (nearest neighbour).
pub const CROP_ZOOM: u32 = 4;
/// Frames per second of the animation.
pub const ANIMATION_FPS: u16 = 4;
/// Height of the animation's label bands (method names above the tiles, the
/// frame's number below), in pixels.
pub const LABEL_BAND: u32 = 14;

/// One method in motion on one scene (cpu backend).
#[derive(Clone, Debug, PartialEq)]
pub struct MotionRow {
    /// Scene name.
    pub scene: String,
    /// Method.
    pub method: String,
    /// FLIP of each frame against that frame's reference.
    pub flip: Vec<f64>,
    /// SSIM of each frame against that frame's reference.
    pub ssim: Vec<f64>,
    /// Frames from the path's start (a reset, for a temporal method) until
    /// the first whose FLIP is below NoAA's on the same frame (1: the first
    /// frame already is); `None` when none is, or for NoAA itself.
    pub frames_to_beat_noaa: Option<u32>,
    /// Temporal instability per class, pooled over frames `1..N`, and the
    /// pixel count it is pooled over (class-frames).
    pub instability: classes::ClassError,
    /// Median wall time of one frame, ms.
    pub ms_per_frame: f64,
}

impl MotionRow {
    /// Mean FLIP over the frames.
    pub fn flip_mean(&self) -> f64 {
        self.flip.iter().sum::<f64>() / self.flip.len().max(1) as f64
    }

    /// Mean SSIM over the frames.
    pub fn ssim_mean(&self) -> f64 {
        self.ssim.iter().sum::<f64>() / self.ssim.len().max(1) as f64
    }
}

/// The window of a scene the animation shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MotionCrop {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Side in pixels.
    pub side: u32,
}

/// The motion section's data.
#[derive(Clone, Debug, Default)]
pub struct Motion {
    /// Whether it ran.
    pub ran: bool,
    /// Frames per path.
    pub frames: u32,
    /// Image size.
    pub size: (u32, u32),
    /// One row per scene and method.
    pub rows: Vec<MotionRow>,
    /// The animation's window per scene.
    pub crops: Vec<(String, MotionCrop)>,
    /// The moving-object scene, when it ran.
    pub moving: Option<MovingObjectRun>,
    /// Wall time of the whole section.
    pub elapsed: Duration,
}

/// The camera of each frame: frame `t` is `base` turned about its up axis
/// by `t · PAN_PIXELS` pixels' worth of angle and moved forward along its
/// view axis by `t` dolly steps, a step being the distance that moves a point
/// at `subject` on the image's side edge by [`DOLLY_PIXELS`] (for a point at
/// distance `d` and half-width `w/2`, moving by `Δ` scales its image
/// position by `d / (d − Δ)`). Errors when the path leaves a valid camera
/// (a non-finite subject distance, say).
pub fn camera_path(
    base: &Camera,
    frames: u32,
    (w, h): (u32, u32),
    subject: f32,
) -> Result<Vec<Camera>> {
    let pixel_angle = base.fov_y / h.max(1) as f32;
    let step = subject * 2.0 * DOLLY_PIXELS / w.max(1) as f32;
    (0..frames)
        .map(|t| {
            let t = t as f32;
            let turn = Quat::from_axis_angle(base.up, t * PAN_PIXELS * pixel_angle);
            let forward = turn * base.forward;
            let position = base.position + base.forward * (t * step);
            Camera::look_at(position, position + forward, base.up, base.fov_y)
                .map_err(|e| anyhow!("motion path, frame {t}: {e}"))
        })
        .collect()
}

/// The median finite view depth of `frame`'s depth AOV: the distance the
/// dolly is scaled to (1 when nothing is hit).
pub fn subject_distance(frame: &Frame) -> f32 {
    let mut d: Vec<f32> = frame
        .depth
        .as_deref()
        .unwrap_or(&[])
        .iter()
        .copied()
        .filter(|d| d.is_finite() && *d > 0.0)
        .collect();
    if d.is_empty() {
        return 1.0;
    }
    let mid = d.len() / 2;
    *d.select_nth_unstable_by(mid, f32::total_cmp).1
}

/// Per pixel, `|Δmethod − Δreference|` between two consecutive frames, on
/// luminance; errors on mismatched sizes.
pub fn instability(method: (&Rgb8, &Rgb8), reference: (&Rgb8, &Rgb8)) -> Result<Vec<f32>> {
    let change = |(before, after): (&Rgb8, &Rgb8)| -> Result<Vec<f32>> {
        metrics::same_size(before, after)?;
        Ok(after
            .luma()
            .iter()
            .zip(before.luma())
            .map(|(a, b)| a - b)
            .collect())
    };
    let (dm, dr) = (change(method)?, change(reference)?);
    metrics::same_size(method.0, reference.0)?;
    Ok(dm.iter().zip(&dr).map(|(m, r)| (m - r).abs()).collect())
}

/// Running per-class sums of an error map over frames.
#[derive(Default)]
struct Pooled {
    sum: [f64; 6],
    px: [u64; 6],
}

impl Pooled {
    /// Add `map` over each class of `masks`. The instability is a
    /// per-pixel measure with no filter to spread an edge's error, so its
    /// flat is every pixel in no class ([`ClassMasks::unclassed`]), not
    /// FLIP's flat beyond its filters' reach.
    fn add(&mut self, map: &[f32], masks: &ClassMasks) {
        let unclassed = masks.unclassed();
        for c in CLASSES {
            let mask = if c == classes::Class::Flat {
                &unclassed[..]
            } else {
                masks.mask(c)
            };
            for (v, &m) in map.iter().zip(mask) {
                if m {
                    self.sum[c.index()] += f64::from(*v);
                    self.px[c.index()] += 1;
                }
            }
        }
    }

    fn mean(&self) -> classes::ClassError {
        classes::ClassError {
            mean: std::array::from_fn(|i| {
                (self.px[i] > 0).then(|| self.sum[i] / self.px[i] as f64)
            }),
            px: self.px,
            ..Default::default()
        }
    }
}

/// The frames of one method along the path, and their times.
struct Followed {
    method: Method,
    /// A temporal method's sequence.
    taa: Option<Taa>,
    images: Vec<Rgb8>,
    ms: Vec<f64>,
}

/// Frames until `flip` is first below `noaa`'s on the same frame.
fn frames_to_beat(flip: &[f64], noaa: &[f64]) -> Option<u32> {
    flip.iter()
        .zip(noaa)
        .position(|(m, n)| m < n)
        .map(|t| t as u32 + 1)
}

impl Runner<'_> {
    /// The motion section over `jobs`: [`FRAMES`] (or `frames`) frames at
    /// [`MOTION_SIZE`] (or the quick size) on the cpu backend.
    pub(super) fn motion(&mut self, jobs: &[SceneJob], frames: u32) -> Result<Motion> {
        let start = Instant::now();
        let quick = self.plan.mode == crate::Mode::Quick;
        let mut motion = Motion {
            ran: true,
            frames,
            ..Default::default()
        };
        let cpu = self.cpu;
        let dir = self.plan.out.join("images");
        for job in jobs {
            let size = if quick { job.quality_size } else { MOTION_SIZE };
            motion.size = size;
            self.progress.note(&format!(
                "{}: motion, {frames} frames at {}x{}",
                job.name, size.0, size.1
            ));
            let (rows, crop) = self.follow(cpu, job, frames, size, &dir)?;
            motion.rows.extend(rows);
            motion.crops.push((job.name.to_string(), crop));
        }
        self.progress.note(&format!(
            "cornell-moving: motion, {frames} frames at {}x{}",
            motion.size.0, motion.size.1
        ));
        motion.moving = Some(moving_object(cpu, frames, motion.size)?);
        motion.elapsed = start.elapsed();
        self.plots
            .extend(plots(&self.plan.out.join("plots"), &motion)?);
        Ok(motion)
    }

    /// One scene along its path: every method's frames, the references, the
    /// classes, the rows and the animation.
    fn follow(
        &mut self,
        cpu: &(dyn Backend + Send + Sync),
        job: &SceneJob,
        frames: u32,
        (w, h): (u32, u32),
        dir: &Path,
    ) -> Result<(Vec<MotionRow>, MotionCrop)> {
        let mut aov = RenderSettings::new(w, h);
        aov.aovs = true;
        let (first, _) = render_from(cpu, &job.scene, &job.scene.camera, &NOAA, &aov)?;
        let path = camera_path(&job.scene.camera, frames, (w, h), subject_distance(&first))?;
        let mut followed = followers(cpu, job)?;
        let (references, masks) = self.render_path(cpu, job, &path, (w, h), &mut followed)?;
        let mut rows: Vec<MotionRow> = Vec::new();
        let mut noaa_unstable = vec![0.0f32; (w * h) as usize];
        for f in &followed {
            rows.push(motion_row(job, f, &references, &masks, &mut noaa_unstable)?);
        }
        set_frames_to_beat_noaa(&mut rows);
        let crop = worst_window(&noaa_unstable, w, h, CROP_SIDE.min(w / 3).min(h / 3));
        save_animation(
            &dir.join(file_safe(&job.name)),
            &followed,
            &references,
            crop,
        )?;
        Ok((rows, crop))
    }

    /// Renders every camera of `path`: its reference and classes, and each
    /// followed method's frame (a temporal one through its sequence) with
    /// its wall time. Returns the references and the classes, frame by
    /// frame.
    fn render_path(
        &self,
        cpu: &(dyn Backend + Send + Sync),
        job: &SceneJob,
        path: &[Camera],
        (w, h): (u32, u32),
        followed: &mut [Followed],
    ) -> Result<(Vec<Rgb8>, Vec<ClassMasks>)> {
        let frames = path.len();
        let plain = RenderSettings::new(w, h);
        let mut references = Vec::new();
        let mut masks = Vec::new();
        for (t, cam) in path.iter().enumerate() {
            self.progress
                .bar
                .set_message(format!("{}: motion frame {}/{frames}", job.name, t + 1));
            let (r, _) = render_from(cpu, &job.scene, cam, &MOTION_REFERENCE, &plain)?;
            references.push(Rgb8::from_frame(&r)?);
            masks.push(classes_at(cpu, &job.scene, cam, (w, h))?);
            for f in followed.iter_mut() {
                let (img, wall) = match &mut f.taa {
                    Some(taa) => {
                        let start = Instant::now();
                        let img = taa
                            .render(cpu, &job.scene, cam, &plain)
                            .with_context(|| format!("{} {} frame {t}", job.name, f.method))?;
                        (img, start.elapsed())
                    }
                    None => render_from(cpu, &job.scene, cam, &f.method, &plain)?,
                };
                f.images.push(Rgb8::from_frame(&img)?);
                f.ms.push(wall.as_secs_f64() * 1e3);
            }
        }
        Ok((references, masks))
    }
}

/// The methods followed on `job`'s scene: those of [`MOTION_METHODS`] the
/// cpu backend renders there, each temporal one with a fresh sequence.
fn followers(cpu: &(dyn Backend + Send + Sync), job: &SceneJob) -> Result<Vec<Followed>> {
    MOTION_METHODS
        .iter()
        .filter(|m| cpu.supports(&job.scene, &m.single_frame()).is_ok())
        .map(|&method| -> Result<Followed> {
            let taa = method
                .is_temporal()
                .then(|| Taa::new(method, TaaConfig::default()))
                .transpose()?;
            Ok(Followed {
                method,
                taa,
                images: Vec::new(),
                ms: Vec::new(),
            })
        })
        .collect()
}

/// The row of one followed method: its FLIP and SSIM per frame, its
/// instability pooled per class, its median frame time. NoAA's instability
/// maps are also summed into `noaa_unstable`, where the crop is chosen.
fn motion_row(
    job: &SceneJob,
    f: &Followed,
    references: &[Rgb8],
    masks: &[ClassMasks],
    noaa_unstable: &mut [f32],
) -> Result<MotionRow> {
    let mut pooled = Pooled::default();
    for t in 1..f.images.len() {
        let map = instability(
            (&f.images[t - 1], &f.images[t]),
            (&references[t - 1], &references[t]),
        )?;
        pooled.add(&map, &masks[t]);
        if f.method == NOAA {
            noaa_unstable
                .iter_mut()
                .zip(&map)
                .for_each(|(a, b)| *a += b);
        }
    }
    let flip = f
        .images
        .iter()
        .zip(references)
        .map(|(i, r)| metrics::flip(r, i).map(|fl| fl.mean))
        .collect::<Result<Vec<f64>, _>>()?;
    let ssim = f
        .images
        .iter()
        .zip(references)
        .map(|(i, r)| metrics::ssim::ssim(r, i).map(|s| s.mean))
        .collect::<Result<Vec<f64>, _>>()?;
    let mut ms = f.ms.clone();
    ms.sort_by(f64::total_cmp);
    Ok(MotionRow {
        scene: job.name.to_string(),
        method: f.method.to_string(),
        flip,
        ssim,
        frames_to_beat_noaa: None,
        instability: pooled.mean(),
        ms_per_frame: ms[ms.len() / 2],
    })
}

/// Each row's [`MotionRow::frames_to_beat_noaa`] against NoAA's row, where
/// there is one (NoAA's own stays `None`).
fn set_frames_to_beat_noaa(rows: &mut [MotionRow]) {
    let noaa_name = NOAA.to_string();
    if let Some(noaa) = rows
        .iter()
        .find(|r| r.method == noaa_name)
        .map(|r| r.flip.clone())
    {
        for r in rows.iter_mut().filter(|r| r.method != noaa_name) {
            r.frames_to_beat_noaa = frames_to_beat(&r.flip, &noaa);
        }
    }
}

/// Writes `scene_dir/motion.png`: the crop of every followed method and of
/// the reference side by side, frame after frame, played forth and back.
fn save_animation(
    scene_dir: &Path,
    followed: &[Followed],
    references: &[Rgb8],
    crop: MotionCrop,
) -> Result<()> {
    let mut names: Vec<String> = followed.iter().map(|f| f.method.to_string()).collect();
    names.push("reference".into());
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let n = references.len();
    let strips: Vec<Rgb8> = ping_pong(n)
        .into_iter()
        .map(|t| {
            let mut images: Vec<&Rgb8> = followed.iter().map(|f| &f.images[t]).collect();
            images.push(&references[t]);
            strip(&images, &names, &format!("frame {} of {n}", t + 1), crop)
        })
        .collect::<Result<_>>()?;
    std::fs::create_dir_all(scene_dir)
        .with_context(|| format!("cannot create {}", scene_dir.display()))?;
    save_apng(&scene_dir.join("motion.png"), &strips)
}

fn opt(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{v:.4}"))
}

/// The "Motion" section of report.md.
pub fn section(m: &Motion) -> String {
    let mut md = String::new();
    if !m.ran {
        return md;
    }
    let _ = writeln!(md, "## Motion\n");
    let _ = writeln!(
        md,
        "Each scene's camera follows a path of {} frames at {}x{} on the cpu backend: per frame it \
turns about its up axis by {PAN_PIXELS} pixel (at the image centre) and dollies forward so that \
a point at the scene's median depth on the image's side edge moves by {DOLLY_PIXELS} pixel. \
Every frame is compared with its own {MOTION_REFERENCE} reference. *FLIP* and *SSIM* are the \
means over the frames. `taa` and the `+taa` methods (Karis 2014 with Salvi's variance clipping, \
16 Halton (2, 3) jitter phases; `sraa-rt+taa` rotates its shaded subsample instead) start from a \
reset at the path's first frame; *frames to beat noaa* counts the frames until the first whose FLIP \
is below NoAA's on the same frame. *Instability* is, over frames 2 to {} and the pixels of each class (classes from each \
frame's own sub-samples; flat is every pixel in no class, as the measure is per pixel and \
spreads no edge's error), the mean of |Δmethod − Δreference|, Δ being a pixel's change of \
luminance (0 to 1) from the previous frame: 0 when a method changes exactly as the reference \
does; the last row gives the pixels each class's instability is pooled over, summed over those \
frames. *ms/frame* is the median wall time of one frame (for a temporal method, its jittered \
frame with depth, the velocities and the resolve). The section took {:.1} s on this machine \
(references and classes included).\n",
        m.frames,
        m.size.0,
        m.size.1,
        m.frames,
        m.elapsed.as_secs_f64()
    );
    let mut scenes: Vec<&str> = Vec::new();
    for r in &m.rows {
        if !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
    }
    for scene in scenes {
        let _ = writeln!(md, "### {scene} in motion\n");
        let head: Vec<String> = CLASSES.iter().map(|c| format!("instability {c}")).collect();
        let _ = writeln!(
            md,
            "| method | FLIP | SSIM | frames to beat noaa | {} | ms/frame |",
            head.join(" | ")
        );
        let _ = writeln!(md, "|---|--:|--:|--:|{}--:|", "--:|".repeat(CLASSES.len()));
        let rows: Vec<&MotionRow> = m.rows.iter().filter(|r| r.scene == scene).collect();
        for r in &rows {
            let cells: Vec<String> = CLASSES
                .iter()
                .map(|c| opt(r.instability.mean[c.index()]))
                .collect();
            let beat = match (r.method == NOAA.to_string(), r.frames_to_beat_noaa) {
                (true, _) => "–".to_string(),
                (false, Some(n)) => n.to_string(),
                (false, None) => "never".to_string(),
            };
            let _ = writeln!(
                md,
                "| {} | {:.4} | {:.4} | {beat} | {} | {:.1} |",
                r.method,
                r.flip_mean(),
                r.ssim_mean(),
                cells.join(" | "),
                r.ms_per_frame
            );
        }
        // The pixels each class's instability is pooled over: the same
        // frames' classes for every method, so one row.
        if let Some(r) = rows.first() {
            let px: Vec<String> = CLASSES
                .iter()
                .map(|c| r.instability.px[c.index()].to_string())
                .collect();
            let _ = writeln!(
                md,
                "| *pixels (frames 2 to {})* | | | | {} | |",
                m.frames,
                px.join(" | ")
            );
        }
        let _ = writeln!(md, "\n{}", against_taa(&rows));
        let stem = file_safe(scene);
        let _ = writeln!(
            md,
            "\n![{scene}: FLIP per frame](plots/{stem}_motion_flip.png)\n"
        );
        if let Some((_, c)) = m.crops.iter().find(|(s, _)| s == scene) {
            let order: Vec<&str> = rows.iter().map(|r| r.method.as_str()).collect();
            let _ = writeln!(
                md,
                "Animated ({}×, {} frames per second, frames 1 to {} and back, each labelled with \
its number): the {}×{} window at ({}, {}) where NoAA is least stable; left to right {}, \
reference.\n\n![{scene} in motion](images/{stem}/motion.png)\n",
                CROP_ZOOM,
                ANIMATION_FPS,
                m.frames,
                c.side,
                c.side,
                c.x,
                c.y,
                order.join(", ")
            );
        }
    }
    if let Some(run) = &m.moving {
        md.push_str(&moving_section(m, run));
    }
    md
}

/// Where each `+taa` combination beats `taa` alone on one scene's rows: mean
/// FLIP, mean SSIM and the instability of every class both have pixels in,
/// as a sentence per combination (computed, so the prose cannot drift from
/// the table).
pub fn against_taa(rows: &[&MotionRow]) -> String {
    let taa_name = TAA.to_string();
    let Some(taa) = rows.iter().find(|r| r.method == taa_name) else {
        return "No taa row: no comparison with TAA alone.".into();
    };
    let mut out = Vec::new();
    for r in rows.iter().filter(|r| r.method.ends_with("+taa")) {
        let mut wins = Vec::new();
        let mut losses = Vec::new();
        let mut judge = |what: String, better: bool| {
            if better {
                wins.push(what)
            } else {
                losses.push(what)
            }
        };
        judge(
            format!("FLIP ({:.4} vs {:.4})", r.flip_mean(), taa.flip_mean()),
            r.flip_mean() < taa.flip_mean(),
        );
        judge(
            format!("SSIM ({:.4} vs {:.4})", r.ssim_mean(), taa.ssim_mean()),
            r.ssim_mean() > taa.ssim_mean(),
        );
        for c in CLASSES {
            if let (Some(a), Some(b)) = (
                r.instability.mean[c.index()],
                taa.instability.mean[c.index()],
            ) {
                judge(format!("{c} instability ({a:.4} vs {b:.4})"), a < b);
            }
        }
        let verdict = match (wins.is_empty(), losses.is_empty()) {
            (false, true) => format!("better on every measure: {}", wins.join(", ")),
            (true, false) => format!("better on no measure: {}", losses.join(", ")),
            _ => format!(
                "better on {}; not better on {}",
                wins.join(", "),
                losses.join(", ")
            ),
        };
        out.push(format!(
            "**{}** against taa alone: {verdict}; {:.1} against {:.1} ms/frame.",
            r.method, r.ms_per_frame, taa.ms_per_frame
        ));
    }
    out.join("\n")
}

/// The section's rows for results.json.
pub fn json(m: &Motion) -> serde_json::Value {
    let rows: Vec<serde_json::Value> = m
        .rows
        .iter()
        .map(|r| {
            let mut o = serde_json::Map::new();
            o.insert("scene".into(), r.scene.clone().into());
            o.insert("method".into(), r.method.clone().into());
            o.insert("flip_mean".into(), r.flip_mean().into());
            o.insert("flip_per_frame".into(), r.flip.clone().into());
            o.insert("ssim_mean".into(), r.ssim_mean().into());
            o.insert("ssim_per_frame".into(), r.ssim.clone().into());
            o.insert(
                "frames_to_beat_noaa".into(),
                r.frames_to_beat_noaa
                    .map_or(serde_json::Value::Null, Into::into),
            );
            for c in CLASSES {
                o.insert(
                    format!("instability_{c}"),
                    r.instability.mean[c.index()].map_or(serde_json::Value::Null, Into::into),
                );
            }
            for c in CLASSES {
                o.insert(format!("px_{c}"), r.instability.px[c.index()].into());
            }
            o.insert("ms_per_frame".into(), r.ms_per_frame.into());
            serde_json::Value::Object(o)
        })
        .collect();
    let moving = m.moving.as_ref().map_or(serde_json::Value::Null, |run| {
        let rows: Vec<serde_json::Value> = run
            .rows
            .iter()
            .map(|r| {
                serde_json::json!({
                    "method": r.method,
                    "flip_mean": r.flip_mean(),
                    "flip_per_frame": r.flip,
                    "uncovered": r.uncovered,
                })
            })
            .collect();
        serde_json::json!({
            "scene": run.scene,
            "pixels_per_frame": MOVING_PIXELS,
            "judged_after": MOVING_JUDGED_AFTER,
            "judged_frames": run.judged_frames,
            "uncovered_px": run.uncovered_px,
            "rows": rows,
        })
    });
    serde_json::json!({
        "ran": m.ran,
        "frames": m.frames,
        "width": m.size.0,
        "height": m.size.1,
        "reference": MOTION_REFERENCE.to_string(),
        "seconds": m.elapsed.as_secs_f64(),
        "rows": rows,
        "moving_object": moving,
    })
}

/// FLIP per frame of each method on one scene.
struct FlipPerFrame<'a> {
    scene: &'a str,
    rows: Vec<&'a MotionRow>,
}

impl Chart for FlipPerFrame<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let pe = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("motion plot: {e:?}");
        root.fill(&WHITE).map_err(pe)?;
        let frames = self.rows.iter().map(|r| r.flip.len()).max().unwrap_or(1);
        let ymax = self
            .rows
            .iter()
            .flat_map(|r| r.flip.iter().copied())
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let size = (PLOT_SIZE.1 / 32) as i32;
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("{}: FLIP per frame in motion", self.scene),
                (FAMILY, size + 4),
            )
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(
                0.0..(frames.max(2) - 1) as f64,
                0.0..(ymax * 1.15).max(1e-3),
            )
            .map_err(pe)?;
        chart
            .configure_mesh()
            .x_desc("frame")
            .y_desc("mean FLIP against the frame's reference")
            .x_labels(frames.min(16))
            // Frames are whole numbers: no label between two of them.
            .x_label_formatter(&|v| {
                if v.fract().abs() < 1e-6 {
                    format!("{:.0}", v + 1.0)
                } else {
                    String::new()
                }
            })
            .y_label_formatter(&|v| format!("{v:.3}"))
            .label_style((FAMILY, size - 4))
            .axis_desc_style((FAMILY, size - 2))
            .draw()
            .map_err(pe)?;
        for r in &self.rows {
            let pts: Vec<(f64, f64)> = r
                .flip
                .iter()
                .enumerate()
                .map(|(t, &v)| (t as f64, v))
                .collect();
            method_line(&mut chart, &r.method, &pts, 4)?;
        }
        legend(
            &mut chart,
            SeriesLabelPosition::UpperRight,
            size - 4,
            "motion plot",
        )?;
        root.present().map_err(pe)?;
        Ok(())
    }
}

/// One chart per scene: FLIP per frame of each method.
pub fn plots(dir: &Path, m: &Motion) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    if m.rows.is_empty() {
        return Ok(out);
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut scenes: Vec<&str> = Vec::new();
    for r in &m.rows {
        if !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
    }
    for scene in scenes {
        let chart = FlipPerFrame {
            scene,
            rows: m.rows.iter().filter(|r| r.scene == scene).collect(),
        };
        out.extend(save_chart(
            dir,
            &format!("{}_motion_flip", file_safe(scene)),
            &chart,
        )?);
    }
    Ok(out)
}
