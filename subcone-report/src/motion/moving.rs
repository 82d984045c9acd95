//! The motion section's moving-object scene: a cube crossing the Cornell
//! box, NoAA and TAA without and with closest-depth dilation, and the
//! pixels the cube uncovers judged a few frames later.

use super::*;

/// The moving object's speed in the section's moving-object scene, pixels a
/// frame at the section's image height.
pub const MOVING_PIXELS: f32 = 3.0;

/// How many frames after the cube uncovers them its uncovered pixels are
/// judged (the history has had that many frames of background by then).
pub const MOVING_JUDGED_AFTER: u32 = 2;

/// One method over the moving object.
#[derive(Clone, Debug, PartialEq)]
pub struct MovingRow {
    /// `noaa`, `taa`, or `taa, depth dilation`.
    pub method: String,
    /// FLIP of each frame against that frame's reference.
    pub flip: Vec<f64>,
    /// Mean FLIP on the pixels the cube uncovered, each judged
    /// [`MOVING_JUDGED_AFTER`] frames after it was uncovered, pooled over
    /// the path; `None` when the path is too short to judge any.
    pub uncovered: Option<f64>,
}

impl MovingRow {
    /// Mean FLIP over the frames.
    pub fn flip_mean(&self) -> f64 {
        self.flip.iter().sum::<f64>() / self.flip.len().max(1) as f64
    }
}

/// The section's moving-object scene: a cube crossing the Cornell box.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MovingObjectRun {
    /// Scene name.
    pub scene: String,
    /// NoAA and TAA without and with closest-depth dilation.
    pub rows: Vec<MovingRow>,
    /// Uncovered pixels judged, summed over the frames that uncover them.
    pub uncovered_px: usize,
    /// Frames whose uncovered pixels are judged.
    pub judged_frames: usize,
}

impl MovingObjectRun {
    /// The row of `method`.
    pub fn row(&self, method: &str) -> Option<&MovingRow> {
        self.rows.iter().find(|r| r.method == method)
    }
}

/// The section's moving-object scene at `(w, h)` over `frames` frames of the
/// section's camera path on the cpu backend: NoAA and `taa` (the cube's and
/// the camera's motion vectors) without and with closest-depth dilation,
/// each frame against its [`MOTION_REFERENCE`]; the pixels the cube
/// uncovers at frame `t` (it covered them at `t − 1`) judged at
/// `t + MOVING_JUDGED_AFTER`.
pub fn moving_object(
    cpu: &(dyn Backend + Send + Sync),
    frames: u32,
    (w, h): (u32, u32),
) -> Result<MovingObjectRun> {
    let m = MovingObject::cornell_box(h, MOVING_PIXELS)?;
    let scenes = (0..frames)
        .map(|t| m.scene(t))
        .collect::<Result<Vec<_>, _>>()?;
    let base = m.camera();
    let mut aov = RenderSettings::new(w, h);
    aov.aovs = true;
    let (first, _) = render_from(cpu, &scenes[0], &base, &NOAA, &aov)?;
    let path = camera_path(&base, frames, (w, h), subject_distance(&first))?;
    let plain = RenderSettings::new(w, h);
    let mut sequences = [DepthDilation::Off, DepthDilation::NearestSmallest]
        .map(|d| -> Result<Taa> {
            let config = TaaConfig {
                depth_dilation: d,
                ..TaaConfig::default()
            };
            Ok(Taa::new(TAA, config)?)
        })
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    let names = ["noaa", "taa", "taa, depth dilation"];
    // Per method, per frame: the FLIP map against the frame's reference.
    let mut maps: Vec<Vec<(f64, Vec<f32>)>> = vec![Vec::new(); names.len()];
    let mut covered = Vec::new();
    for (t, (scene, cam)) in scenes.iter().zip(&path).enumerate() {
        let t = t as u32;
        let (r, _) = render_from(cpu, scene, cam, &MOTION_REFERENCE, &plain)?;
        let reference = Rgb8::from_frame(&r)?;
        let (noaa, _) = render_from(cpu, scene, cam, &NOAA, &plain)?;
        let mut images = vec![noaa];
        for taa in &mut sequences {
            let f = taa
                .render_moving(cpu, scene, cam, &plain, &|p| m.previous_point(t, p))
                .with_context(|| format!("{} taa frame {t}", m.name()))?;
            images.push(f);
        }
        for (k, img) in images.iter().enumerate() {
            let f = metrics::flip(&reference, &Rgb8::from_frame(img)?)?;
            maps[k].push((f.mean, f.map));
        }
        covered.push(m.covered(t, cam, (w, h)));
    }
    let after = MOVING_JUDGED_AFTER as usize;
    let masks: Vec<(usize, Vec<bool>)> = (1..covered.len().saturating_sub(after))
        .map(|t| (t + after, disoccluded(&covered[t - 1], &covered[t])))
        .collect();
    let uncovered_px = masks
        .iter()
        .map(|(_, m)| m.iter().filter(|&&b| b).count())
        .sum();
    let rows = names
        .iter()
        .zip(&maps)
        .map(|(name, frames)| {
            let (sum, n) = masks.iter().fold((0.0f64, 0usize), |(s, n), (t, mask)| {
                frames[*t]
                    .1
                    .iter()
                    .zip(mask)
                    .filter(|(_, &m)| m)
                    .fold((s, n), |(s, n), (v, _)| (s + f64::from(*v), n + 1))
            });
            MovingRow {
                method: name.to_string(),
                flip: frames.iter().map(|f| f.0).collect(),
                uncovered: (n > 0).then(|| sum / n as f64),
            }
        })
        .collect();
    Ok(MovingObjectRun {
        scene: m.name().to_string(),
        rows,
        uncovered_px,
        judged_frames: masks.len(),
    })
}

/// The moving-object part of the section: its table, and the camera-only
/// and moving-object figures of `taa` side by side (computed, so the prose
/// cannot drift from the tables).
pub fn moving_section(m: &Motion, run: &MovingObjectRun) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "### A moving object: {}
",
        run.scene
    );
    let _ = writeln!(
        md,
        "Every scene above holds still while the camera moves. Here an 80 mm blue cube floats in \
front of the Cornell box's short block and crosses it at {MOVING_PIXELS} pixels a frame while the \
camera follows the same path ({} frames at {}x{}, each against its own {MOTION_REFERENCE}). `taa` \
is given what an engine's motion-vector pass writes, the cube's motion and the camera's; *taa, \
depth dilation* takes each pixel's vector from the nearest depth of its 3×3 neighbourhood (Karis \
2014; FSR2's reconstruct & dilate). *Uncovered* is the mean FLIP on the pixels the cube covered in \
one frame and not in the next, judged {MOVING_JUDGED_AFTER} frames later and pooled over the \
path ({} frames, {} pixels): a history smeared over the background it uncovered stays above \
NoAA's there.\n",
        m.frames, m.size.0, m.size.1, run.judged_frames, run.uncovered_px
    );
    let _ = writeln!(md, "| method | FLIP | FLIP per frame | uncovered |");
    let _ = writeln!(md, "|---|--:|---|--:|");
    for r in &run.rows {
        let per: Vec<String> = r.flip.iter().map(|v| format!("{v:.4}")).collect();
        let _ = writeln!(
            md,
            "| {} | {:.4} | {} | {} |",
            r.method,
            r.flip_mean(),
            per.join(" "),
            opt(r.uncovered)
        );
    }
    let _ = writeln!(md, "\n{}\n", moving_against_camera_only(m, run));
    md
}

/// One paragraph: `taa`'s mean FLIP with the camera alone moving (each
/// scene of the section) and with the cube moving, and its error on the
/// uncovered pixels against NoAA's.
pub fn moving_against_camera_only(m: &Motion, run: &MovingObjectRun) -> String {
    let taa = TAA.to_string();
    let camera_only: Vec<String> = m
        .rows
        .iter()
        .filter(|r| r.method == taa)
        .map(|r| format!("{} {:.4}", r.scene, r.flip_mean()))
        .collect();
    let mut out = if camera_only.is_empty() {
        "Camera only: no taa row.".to_string()
    } else {
        format!("Camera only, taa's mean FLIP: {}.", camera_only.join(", "))
    };
    let (Some(noaa), Some(plain), Some(dilated)) = (
        run.row("noaa"),
        run.row("taa"),
        run.row("taa, depth dilation"),
    ) else {
        return out;
    };
    let _ = write!(
        out,
        " With the cube moving, {}: taa {:.4}, with depth dilation {:.4}, noaa {:.4}.",
        run.scene,
        plain.flip_mean(),
        dilated.flip_mean(),
        noaa.flip_mean()
    );
    match (plain.uncovered, dilated.uncovered, noaa.uncovered) {
        (Some(p), Some(d), Some(n)) if n > 0.0 => {
            let _ = write!(
                out,
                " On the uncovered pixels {MOVING_JUDGED_AFTER} frames later: taa {p:.4} ({:.2}× \
noaa's {n:.4}), with depth dilation {d:.4} ({:.2}×).",
                p / n,
                d / n
            );
        }
        _ => {
            let _ = write!(
                out,
                " The path is too short to judge uncovered pixels {MOVING_JUDGED_AFTER} frames \
later."
            );
        }
    }
    out
}
