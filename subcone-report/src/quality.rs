//! What a scene's errors are measured against: its reference (from the
//! cache, or rendered on the CPU and cached), its edge mask, the masks the
//! crops need and its edge classes, from the scene's camera and from each
//! further camera offset.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use glam::Vec3;
use subcone_kernels::passes::SceneFeatures;
use subcone_metrics::Rgb8;
use subcone_scene::{Albedo, Frame, Method, RenderSettings};

use crate::named::NOAA;
use crate::render::{classes_at, render, render_from, sub_sample_side};
use crate::runner::Runner;
use crate::scenes::SceneJob;
use crate::summary::Failure;
use crate::{classes, files, metrics, offsets, reference};

/// What the quality phase knows about a scene.
pub(crate) struct SceneQuality {
    pub(crate) reference: Rgb8,
    pub(crate) edges: Vec<bool>,
    pub(crate) geometric: Vec<bool>,
    pub(crate) noaa_error_base: Rgb8,
    pub(crate) shadow: Option<Vec<bool>>,
    pub(crate) reflective: Option<Vec<bool>>,
    pub(crate) classes: classes::ClassMasks,
    /// The camera offsets after the first, each with its reference and
    /// classes.
    pub(crate) offsets: Vec<OffsetQuality>,
}

/// What the error needs at one camera offset.
pub(crate) struct OffsetQuality {
    pub(crate) offset: (f32, f32),
    pub(crate) camera: subcone_scene::Camera,
    pub(crate) size: (u32, u32),
    pub(crate) reference: Rgb8,
    pub(crate) classes: classes::ClassMasks,
}

impl Runner<'_> {
    pub(crate) fn reference(&mut self, job: &SceneJob) -> Result<Frame> {
        let (w, h) = job.quality_size;
        let settings = self.plan.settings(w, h, job.sdf);
        self.reference_with(job, &settings)
    }

    /// The scene's reference at `settings` (size and ambient occlusion),
    /// from the cache or rendered on the CPU and cached.
    pub(crate) fn reference_with(
        &mut self,
        job: &SceneJob,
        settings: &RenderSettings,
    ) -> Result<Frame> {
        self.reference_by(job, settings, None)
    }

    /// [`Self::reference_with`] by `method` instead of the run's reference
    /// (`None`: the run's), cached under its own key.
    pub(crate) fn reference_by(
        &mut self,
        job: &SceneJob,
        settings: &RenderSettings,
        method: Option<Method>,
    ) -> Result<Frame> {
        self.reference_from(job, settings, method, None)
    }

    /// [`Self::reference_by`] seen from `camera` instead of the scene's
    /// (`None`: the scene's), cached under its own key.
    pub(crate) fn reference_from(
        &mut self,
        job: &SceneJob,
        settings: &RenderSettings,
        method: Option<Method>,
        camera: Option<&subcone_scene::Camera>,
    ) -> Result<Frame> {
        let reference = method.unwrap_or(self.plan.reference);
        let (w, h) = (settings.width, settings.height);
        let key = reference::ReferenceKey {
            scene: reference::scene_identity(&job.arg),
            width: w,
            height: h,
            method: reference.to_string(),
            reflection_depth: settings.reflection_depth,
            ao_rays: settings.ao_rays,
            backend: "cpu".into(),
            version: reference::code_version(),
            camera: camera.map(offsets::describe),
        };
        let path = key.path(&self.plan.cache);
        if !self.plan.refresh {
            if let Some(f) = reference::load(&path, w, h)? {
                self.references_cached += 1;
                self.progress.bar.inc(1);
                return Ok(f);
            }
        }
        self.progress
            .bar
            .set_message(format!("{}: reference {} at {w}x{h}", job.name, reference));
        let camera = camera.unwrap_or(&job.scene.camera);
        let (frame, wall) = render_from(self.cpu, &job.scene, camera, &reference, settings)?;
        self.progress.note(&format!(
            "{}: rendered reference {} at {w}x{h}{} in {:.1} s",
            job.name,
            reference,
            if settings.ao_rays > 0 {
                format!(" with {} AO rays", settings.ao_rays)
            } else {
                String::new()
            },
            wall.as_secs_f64()
        ));
        reference::store(&path, &key, &frame)?;
        self.references_rendered += 1;
        self.progress.bar.inc(1);
        Ok(frame)
    }

    /// The edge classes of a scene at its quality size ([`classes_at`]).
    pub(crate) fn classes(&mut self, job: &SceneJob) -> Result<classes::ClassMasks> {
        let (w, h) = job.quality_size;
        let side = sub_sample_side(w, h);
        self.progress.bar.set_message(format!(
            "{}: edge classes from {side}x{side} sub-samples per pixel",
            job.name
        ));
        classes_at(self.cpu, &job.scene, &job.scene.camera, (w, h))
    }

    /// Reference, edge mask and the masks the crop heuristics need.
    pub(crate) fn quality(&mut self, job: &SceneJob) -> Result<SceneQuality> {
        let reference = Rgb8::from_frame(&self.reference(job)?)?;
        let (w, h) = job.quality_size;
        let noaa = NOAA;
        let mut aov_settings = self.plan.settings(w, h, job.sdf);
        aov_settings.aovs = true;
        self.progress
            .bar
            .set_message(format!("{}: edge mask and region masks", job.name));
        let (aov, _) = render(self.cpu, &job.scene, &noaa, &aov_settings)?;
        let geometric = metrics::geometric_edges(&aov)?;
        let edges = metrics::edge_mask(&aov, &reference)?;
        let noaa8 = Rgb8::from_frame(&aov)?;
        let features = job.scene.features();
        let mut flat = RenderSettings::new(w, h);
        flat.reflection_depth = 0;
        let reflective = if features.contains(SceneFeatures::HAS_REFLECTIONS) {
            let (f, _) = render(self.cpu, &job.scene, &noaa, &flat)?;
            Some(metrics::differing_pixels(
                &noaa8,
                &Rgb8::from_frame(&f)?,
                2,
            )?)
        } else {
            None
        };
        let shadow = if features.contains(SceneFeatures::HAS_LIGHTS) {
            let mut grey = job.scene.clone();
            for m in &mut grey.materials {
                m.albedo = Albedo::Solid(Vec3::splat(0.6));
            }
            match render(self.cpu, &grey, &noaa, &flat) {
                Ok((f, _)) => {
                    let g = metrics::gradient_edges(&Rgb8::from_frame(&f)?);
                    Some(g.iter().zip(&geometric).map(|(&g, &e)| g && !e).collect())
                }
                Err(e) => {
                    self.progress.note(&format!(
                        "{}: no untextured render for the shadow crop: {e:#}",
                        job.name
                    ));
                    None
                }
            }
        } else {
            None
        };
        let classes = self.classes(job)?;
        self.progress.bar.inc(1);
        Ok(SceneQuality {
            reference,
            edges,
            geometric,
            noaa_error_base: noaa8,
            shadow,
            reflective,
            classes,
            offsets: Vec::new(),
        })
    }

    /// The reference and classes at each camera offset after the first, at
    /// the quality size against the run's reference (as the first offset's);
    /// the time they take is added to `offsets_elapsed`.
    pub(crate) fn offset_qualities(&mut self, job: &SceneJob) -> Result<Vec<OffsetQuality>> {
        let start = Instant::now();
        let plan = self.plan;
        let size = job.quality_size;
        let mut out = Vec::new();
        for &offset in plan.offsets.iter().skip(1) {
            let camera = offsets::offset_camera(&job.scene.camera, offset, size.1)?;
            let settings = plan.settings(size.0, size.1, job.sdf);
            let reference = self.reference_from(job, &settings, None, Some(&camera))?;
            self.progress.bar.set_message(format!(
                "{}: edge classes at offset {}",
                job.name,
                offsets::label(offset)
            ));
            let classes = classes_at(self.cpu, &job.scene, &camera, size)?;
            self.progress.bar.inc(1);
            out.push(OffsetQuality {
                offset,
                camera,
                size,
                reference: Rgb8::from_frame(&reference)?,
                classes,
            });
        }
        self.offsets_elapsed += start.elapsed();
        Ok(out)
    }

    /// The scene's reference and masks, with the reference and edge mask
    /// written beside the images; `None` (with `--keep-going`) when the
    /// reference fails.
    pub(crate) fn scene_quality(
        &mut self,
        job: &SceneJob,
        img_dir: &Path,
    ) -> Result<Option<SceneQuality>> {
        std::fs::create_dir_all(img_dir)
            .with_context(|| format!("cannot create {}", img_dir.display()))?;
        match self.quality(job) {
            Ok(mut q) => {
                match self.offset_qualities(job) {
                    Ok(o) => q.offsets = o,
                    Err(e) => {
                        let what =
                            format!("reference {} at the camera offsets", self.plan.reference);
                        self.fail(Failure::new(&job.name, what, "cpu", &e))?;
                    }
                }
                files::save_png(&img_dir.join("reference.png"), &q.reference)?;
                files::save_png(
                    &img_dir.join("edge_mask.png"),
                    &files::mask_image(q.reference.width, q.reference.height, &q.edges),
                )?;
                Ok(Some(q))
            }
            Err(e) => {
                let what = format!("reference {}", self.plan.reference);
                self.fail(Failure::new(&job.name, what, "cpu", &e))?;
                Ok(None)
            }
        }
    }
}
