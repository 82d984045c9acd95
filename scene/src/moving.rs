//! A scene in which one object moves over a static background: the case a
//! camera pan over a still scene never shows a temporal method, where the
//! history a pixel holds belongs to a surface that has just left it (a
//! disocclusion) and its neighbour's surface moves differently from its own.
//!
//! [`MovingObject`] keeps the background scene and the object apart and
//! builds each frame's scene by translating the object's positions by
//! [`MovingObject::offset`] (a backend sees a new scene per frame; nothing
//! else changes). It also says what an engine's motion-vector pass would
//! know: where each visible point was a frame earlier
//! ([`MovingObject::previous_point`], for
//! [`Taa::render_moving`](crate::temporal::Taa::render_moving)), and which
//! pixels the object covers ([`MovingObject::covered`], from which the
//! disoccluded pixels of a frame are those covered in the previous frame and
//! not in this one, [`disoccluded`]).
//!
//! ```
//! use subcone_scene::moving::MovingObject;
//!
//! // The measured Cornell box with a box floating in front, moving 3
//! // pixels a frame to the right on a 90-pixel-high image.
//! let m = MovingObject::cornell_box(90, 3.0)?;
//! let (a, b) = (m.scene(0)?, m.scene(1)?);
//! assert_eq!(a.mesh().unwrap().len(), b.mesh().unwrap().len());
//! // A point on the object at frame 1 was one step back at frame 0.
//! let (lo, hi) = m.object_bounds(1);
//! let p = 0.5 * (lo + hi);
//! assert!((m.previous_point(1, p) - (p - m.step())).length() < 1e-3);
//! # Ok::<(), subcone_scene::SceneError>(())
//! ```

use glam::{Mat4, Vec2, Vec3};

use crate::builtin::cornell;
use crate::camera::Camera;
use crate::error::SceneError;
use crate::material::Material;
use crate::mesh::TriangleMesh;
use crate::scene::{Geometry, Scene};

/// One object translated by a constant step per frame over a static
/// triangle scene.
///
/// The object's motion and coverage are judged on its axis-aligned bounding
/// box ([`Self::object_bounds`]): exact for an axis-aligned box (the
/// built-in [`Self::cornell_box`]), an approximation for any other shape.
/// [`Self::covered`] also assumes nothing lies between the camera and the
/// object.
#[derive(Clone, Debug)]
pub struct MovingObject {
    background: Scene,
    object: TriangleMesh,
    step: Vec3,
    bounds: (Vec3, Vec3),
    margin: f32,
}

impl MovingObject {
    /// `object` (at frame 0, in world space) moving by `step` per frame over
    /// `background` (a triangle scene, whose name, camera, lights, colours
    /// of background and ambient every frame keeps), in material `material`
    /// (appended to the background's). A surface point within `margin` of
    /// the object's bounds is the object's ([`Self::previous_point`]): about
    /// a pixel at the object's distance, since a frame's depth is its
    /// jittered sample's, seen along the pixel centre's ray.
    ///
    /// Errors ([`SceneError::Motion`]): a background that is not made of
    /// triangles, an object without triangles or with a position that is not
    /// finite, a step or a margin that is not finite (or a negative margin).
    pub fn new(
        background: Scene,
        object: TriangleMesh,
        material: Material,
        step: Vec3,
        margin: f32,
    ) -> Result<Self, SceneError> {
        let Geometry::Triangles(_) = background.geometry else {
            return Err(SceneError::Motion(format!(
                "{}: the background must be a triangle scene",
                background.name
            )));
        };
        let bounds = object
            .bounds()
            .filter(|(lo, hi)| lo.is_finite() && hi.is_finite())
            .ok_or_else(|| {
                SceneError::Motion("the object has no triangles, or a position not finite".into())
            })?;
        if !step.is_finite() {
            return Err(SceneError::Motion(format!("step {step} is not finite")));
        }
        if !(margin >= 0.0 && margin.is_finite()) {
            return Err(SceneError::Motion(format!(
                "margin {margin} must be finite and not negative"
            )));
        }
        let mut background = background;
        let index = background.materials.len() as u32;
        background.materials.push(material);
        let mut object = object;
        object.materials.iter_mut().for_each(|m| *m = index);
        Ok(MovingObject {
            background,
            object,
            step,
            bounds,
            margin,
        })
    }

    /// The built-in case, `cornell-moving`: the measured Cornell box without
    /// its mirror sphere (`cornell-nomirror`), and an 80 mm blue cube
    /// floating in front of the short block (nothing between it and the
    /// camera), moving to the camera's right by `pixels_per_frame` pixels a
    /// frame on an image `height` pixels high (its frames 0 to 15 stay in
    /// view for up to 4 pixels a frame). It passes over the short block, the
    /// floor's shadows and the back wall, and casts its own moving shadow.
    ///
    /// Errors: a `height` of 0 or a `pixels_per_frame` that is not finite.
    pub fn cornell_box(height: u32, pixels_per_frame: f32) -> Result<Self, SceneError> {
        if height == 0 || !pixels_per_frame.is_finite() {
            return Err(SceneError::Motion(format!(
                "{pixels_per_frame} pixels a frame on {height} rows: the height must be at \
                 least 1 and the speed finite"
            )));
        }
        let mut background = cornell(false);
        background.name = "cornell-moving".into();
        let camera = background.camera;
        let centre = Vec3::new(400.0, 300.0, 20.0);
        let side = 80.0;
        // The size of a pixel at the cube's distance.
        let pixel = 2.0 * camera.view_depth(centre) * (0.5 * camera.fov_y).tan() / height as f32;
        let mut object = TriangleMesh::default();
        object.push_box(
            Mat4::from_scale_rotation_translation(Vec3::splat(side), glam::Quat::IDENTITY, centre),
            0,
        );
        MovingObject::new(
            background,
            object,
            Material::diffuse("blue", Vec3::new(0.08, 0.16, 0.6)),
            camera.right() * (pixels_per_frame * pixel),
            1.5 * pixel,
        )
    }

    /// The scene's name (the background's).
    pub fn name(&self) -> &str {
        &self.background.name
    }

    /// The background's camera.
    pub fn camera(&self) -> Camera {
        self.background.camera
    }

    /// The object's translation per frame.
    pub fn step(&self) -> Vec3 {
        self.step
    }

    /// The object's translation at frame `t` from where it was given
    /// (frame 0).
    pub fn offset(&self, t: u32) -> Vec3 {
        self.step * t as f32
    }

    /// The object's axis-aligned bounds `(min, max)` at frame `t`.
    pub fn object_bounds(&self, t: u32) -> (Vec3, Vec3) {
        let o = self.offset(t);
        (self.bounds.0 + o, self.bounds.1 + o)
    }

    /// Frame `t`'s scene: the background and the object at
    /// [`Self::offset`]`(t)`, a new scene (a new [`Scene::id`]) each call.
    pub fn scene(&self, t: u32) -> Result<Scene, SceneError> {
        let Some(base) = self.background.mesh() else {
            return Err(SceneError::Motion(
                "the background lost its triangles".into(),
            ));
        };
        let mut mesh = base.clone();
        let mut object = self.object.clone();
        let o = self.offset(t);
        for tri in &mut object.positions {
            for p in tri {
                *p += o;
            }
        }
        mesh.extend(&object);
        let b = &self.background;
        let mut s = Scene::triangles(
            &b.name,
            mesh,
            b.materials.clone(),
            b.lights.clone(),
            b.camera,
        )?;
        s.background = b.background;
        s.ambient = b.ambient;
        Ok(s)
    }

    /// Where the surface point `p` of frame `t` was at frame `t − 1`: one
    /// step back if `p` lies on the object (within the margin of its bounds
    /// at `t`), `p` itself on the background and at frame 0.
    pub fn previous_point(&self, t: u32, p: Vec3) -> Vec3 {
        if t == 0 {
            return p;
        }
        let (lo, hi) = self.object_bounds(t);
        let m = Vec3::splat(self.margin);
        if p.cmpge(lo - m).all() && p.cmple(hi + m).all() {
            p - self.step
        } else {
            p
        }
    }

    /// Which pixels of a `width × height` image through `camera` (its
    /// jitter ignored) show the object at frame `t`: those whose centre's
    /// ray meets its bounds (the object is in front of all it overlaps),
    /// row-major.
    pub fn covered(&self, t: u32, camera: &Camera, (w, h): (u32, u32)) -> Vec<bool> {
        let rays = camera.with_jitter(Vec2::ZERO).rays(w, h);
        let (lo, hi) = self.object_bounds(t);
        let mut out = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            for x in 0..w {
                let (o, d) = rays.ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                out.push(ray_meets_box(o, d, lo, hi));
            }
        }
        out
    }
}

/// The pixels disoccluded between two frames: covered by the object in
/// the previous frame (`before`) and not in this one (`now`). Masks of
/// different lengths give none.
pub fn disoccluded(before: &[bool], now: &[bool]) -> Vec<bool> {
    if before.len() != now.len() {
        return vec![false; now.len()];
    }
    before.iter().zip(now).map(|(&b, &n)| b && !n).collect()
}

/// Whether the ray from `o` along `d` meets the box `[lo, hi]` in front of
/// its origin (the slab test; an axis the ray runs parallel to must hold
/// the origin).
fn ray_meets_box(o: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> bool {
    let (mut near, mut far) = (0.0f32, f32::INFINITY);
    for i in 0..3 {
        if d[i] == 0.0 {
            if o[i] < lo[i] || o[i] > hi[i] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[i] - o[i]) / d[i], (hi[i] - o[i]) / d[i]);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    near <= far
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_object_moves_by_its_step_and_the_background_stays() {
        let m = MovingObject::cornell_box(90, 3.0).unwrap();
        let (a, b) = (m.scene(0).unwrap(), m.scene(2).unwrap());
        let (ma, mb) = (a.mesh().unwrap(), b.mesh().unwrap());
        let n = ma.len();
        // The last 12 triangles are the cube's, moved by two steps.
        for i in 0..n {
            let moved = if i >= n - 12 {
                2.0 * m.step()
            } else {
                Vec3::ZERO
            };
            for k in 0..3 {
                let d = mb.positions[i][k] - ma.positions[i][k] - moved;
                assert!(d.length() < 1e-3, "triangle {i}: {d}");
            }
        }
        assert_eq!(a.name, "cornell-moving");
        assert_eq!(
            *mb.materials.last().unwrap() as usize,
            b.materials.len() - 1
        );
        // Three pixels at the cube's distance on 90 rows.
        let d = m
            .camera()
            .view_depth(0.5 * (m.object_bounds(0).0 + m.object_bounds(0).1));
        let pixel = 2.0 * d * (0.5 * m.camera().fov_y).tan() / 90.0;
        assert!((m.step().length() - 3.0 * pixel).abs() < 1e-3 * pixel);
    }

    #[test]
    fn points_on_the_object_move_back_and_others_stay() {
        let m = MovingObject::cornell_box(90, 3.0).unwrap();
        let (lo, hi) = m.object_bounds(4);
        let on = Vec3::new(lo.x, 0.5 * (lo.y + hi.y), lo.z);
        assert_eq!(m.previous_point(4, on), on - m.step());
        assert_eq!(m.previous_point(0, on), on);
        let wall = Vec3::new(300.0, 300.0, 559.2);
        assert_eq!(m.previous_point(4, wall), wall);
    }

    #[test]
    fn coverage_follows_the_object_and_disocclusion_trails_it() {
        let m = MovingObject::cornell_box(90, 3.0).unwrap();
        let cam = m.camera();
        let (w, h) = (160, 90);
        let c0 = m.covered(0, &cam, (w, h));
        let c1 = m.covered(1, &cam, (w, h));
        let count = |c: &[bool]| c.iter().filter(|&&b| b).count();
        // About 12 × 12 pixels (an 80 mm cube at ~6.5 mm a pixel).
        assert!((100..250).contains(&count(&c0)), "{}", count(&c0));
        let d = disoccluded(&c0, &c1);
        // A band three pixels wide on the cube's trailing (left) side.
        let n = count(&d);
        assert!((20..60).contains(&n), "{n}");
        let xs: Vec<u32> = d
            .iter()
            .enumerate()
            .filter(|(_, &b)| b)
            .map(|(i, _)| i as u32 % w)
            .collect();
        let left = c1
            .iter()
            .enumerate()
            .filter(|(_, &b)| b)
            .map(|(i, _)| i as u32 % w)
            .min()
            .unwrap();
        assert!(
            xs.iter().all(|&x| x < left && x + 4 >= left),
            "{xs:?} left of {left}"
        );
        assert!(disoccluded(&c0, &c1[..3]).iter().all(|b| !b));
    }

    #[test]
    fn bad_motions_are_refused() {
        assert!(matches!(
            MovingObject::cornell_box(0, 3.0),
            Err(SceneError::Motion(_))
        ));
        assert!(matches!(
            MovingObject::cornell_box(90, f32::NAN),
            Err(SceneError::Motion(_))
        ));
        let bg = cornell(false);
        let mut cube = TriangleMesh::default();
        cube.push_box(Mat4::IDENTITY, 0);
        let blue = Material::diffuse("blue", Vec3::Z);
        let refused = |r: Result<MovingObject, SceneError>| matches!(r, Err(SceneError::Motion(_)));
        assert!(refused(MovingObject::new(
            bg.clone(),
            TriangleMesh::default(),
            blue.clone(),
            Vec3::X,
            1.0
        )));
        assert!(refused(MovingObject::new(
            bg.clone(),
            cube.clone(),
            blue.clone(),
            Vec3::NAN,
            1.0
        )));
        assert!(refused(MovingObject::new(
            bg.clone(),
            cube.clone(),
            blue.clone(),
            Vec3::X,
            -1.0
        )));
        let sdf = crate::builtin::builtin("primitives").unwrap();
        assert!(refused(MovingObject::new(sdf, cube, blue, Vec3::X, 1.0)));
    }
}
