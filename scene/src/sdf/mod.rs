//! Signed-distance-field scenes for sphere tracing and CTSS.
//!
//! An [`SdfNode`] tree of primitives ([`Shape`]) and operators, evaluated by
//! [`SdfNode::eval`] as `(signed distance, material index)`; an [`SdfScene`]
//! adds materials, lights, a camera and tracing limits; the built-in SDF
//! scenes are constructors here, registered in
//! [`builtin::SCENES`](crate::builtin::SCENES): the paper's
//! ([`SDF_SCENES`](crate::builtin::SDF_SCENES), after CTSS §4 and Table 1) and
//! a stability suite ([`STIFF_SCENES`](crate::builtin::STIFF_SCENES)).
//!
//! ```
//! use glam::Vec3;
//! use subcone_scene::{builtin::sdf_builtin, sdf::SdfNode};
//!
//! let ball = SdfNode::sphere(1.0).unwrap().translate(Vec3::new(0.0, 1.0, 0.0)).unwrap();
//! assert!(ball.is_exact());
//! assert_eq!(ball.eval(Vec3::new(0.0, 3.0, 0.0)), (1.0, 0));
//!
//! let scene = sdf_builtin("primitives").unwrap().unwrap();
//! let (d, material) = scene.root.eval(scene.camera.position);
//! assert!(d > 0.0 && (material as usize) < scene.materials.len());
//! ```
//!
//! # Exact, bound, non-Eikonal
//!
//! Every node carries an [`Exactness`] tag following Inigo Quilez's list of
//! distance functions:
//!
//! | node | tag |
//! |---|---|
//! | sphere, box, round box, box frame, torus, link, capsule, cylinder, rounded cylinder, capped cone, octahedron (exact version), hex prism, plane | exact |
//! | ellipsoid (`k0 (k0 − 1) / k1`) | bound |
//! | translate, rotate, uniform scale (`s · f(p / s)`), mirror (child confined to one side) | child's |
//! | union (`min`, skipping children by bounding spheres) | child's: exact **outside** (inside overlapping children it underestimates the depth; we tag it exact, as is customary) |
//! | subtraction, intersection, smooth union | bound |
//! | repetition, symmetric child | child's (exact: see [`SdfNode::repeat_limited`]) |
//! | repetition, asymmetric child | bound (guarded by the cell walls) |
//! | scatter (random grid) | bound (guarded by the cell walls) |
//! | round | child's; onion: exact only for a single primitive |
//! | bounded (skip far children) | bound |
//! | scale distance by a factor ≠ 1, displacement | non-Eikonal |
//!
//! A bound never overestimates the distance; [`SdfNode::is_conservative`] says
//! whether a whole tree never does (non-Eikonal trees with a gradient above 1
//! may).
//!
//! # Errors
//!
//! Constructors validate everything (non-finite or negative sizes, zero scale,
//! empty operators, overlapping repetition cells, instances grown across
//! their cell walls by an offset above a guarded repetition (see
//! [`SdfNode::onion`]), out-of-range materials, …)
//! and return an [`SdfError`]; nothing here panics on any input. Callers that
//! need a [`SceneError`](crate::SceneError) map it themselves.

mod bounds;
mod check;
pub mod lane;
mod node;
mod scenes;
mod shape;
mod stiff;

pub use crate::error::SdfError;
pub use bounds::Aabb;
pub use check::UNIT_TOLERANCE;
pub use node::scatter::{Instance, Scatter, ScatterConfig, MAX_SCATTER_CELLS};
pub use node::{
    tetra_normal_from, tetra_taps, Op, Repeat, SdfNode, SplitDistance, Transform, MAX_DEPTH,
};
pub use scenes::{atrium, glass, primitives, random_box, random_shape, sparse_shape};
pub use shape::Shape;
pub use stiff::{far, grazing, non_eikonal, thin, FAR_ORIGIN_SHIFT};

use glam::Vec3;
use subcone_kernels::passes::SceneFeatures;

use crate::camera::Camera;
use crate::light::Light;
use crate::material::Material;

/// How faithfully a tree's value measures the distance to its surface.
///
/// Ordered: combining nodes takes the worst (`max`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Exactness {
    /// The Euclidean distance to the surface (outside; see the table in the
    /// module docs for unions), `|∇f| = 1`.
    Exact,
    /// Never more than the distance: safe for sphere tracing, but steps may be
    /// short and CTSS's cone occlusion is overestimated near such surfaces.
    Bound,
    /// Not a distance: `|∇f|` is far from 1 by construction (scaled or displaced
    /// fields). May under- or overestimate; see [`SdfNode::is_conservative`].
    NonEikonal,
}

/// A scene made of one SDF tree.
#[derive(Clone, Debug)]
pub struct SdfScene {
    /// Name, for messages and reports.
    pub name: String,
    /// The field.
    pub root: SdfNode,
    /// Materials, indexed by the tree's material indices.
    pub materials: Vec<Material>,
    /// Lights that cast hard shadows (none: no shadow rays).
    pub lights: Vec<Light>,
    /// The default camera.
    pub camera: Camera,
    /// Colour of rays that hit nothing.
    pub background: Vec3,
    /// Ambient light.
    pub ambient: Vec3,
    /// Distance at which a ray leaves the scene.
    pub max_distance: f32,
    /// Step budget per ray.
    pub max_steps: u32,
}

impl SdfScene {
    /// A scene with a dark background, faint ambient light, rays up to 100
    /// units and 512 steps; adjust the public fields afterwards (and call
    /// [`SdfScene::validate`] if they come from outside).
    ///
    /// Errors when a material index is out of range (an empty `materials`
    /// becomes one grey diffuse material), a light is not finite, or the camera
    /// is invalid.
    pub fn new(
        name: &str,
        root: SdfNode,
        materials: Vec<Material>,
        lights: Vec<Light>,
        camera: Camera,
    ) -> Result<Self, SdfError> {
        let materials = if materials.is_empty() {
            vec![Material::diffuse("default", Vec3::splat(0.7))]
        } else {
            materials
        };
        let scene = SdfScene {
            name: name.into(),
            root,
            materials,
            lights,
            camera,
            background: Vec3::new(0.05, 0.05, 0.06),
            ambient: Vec3::splat(0.03),
            max_distance: 100.0,
            max_steps: 512,
        };
        scene.validate()?;
        Ok(scene)
    }

    /// The scene's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Check materials, lights, camera and limits.
    pub fn validate(&self) -> Result<(), SdfError> {
        let bad = |reason: String| SdfError::Scene {
            name: self.name.clone(),
            reason,
        };
        let m = self.root.max_material();
        if m as usize >= self.materials.len() {
            return Err(SdfError::Material {
                index: m,
                count: self.materials.len(),
            });
        }
        for l in &self.lights {
            // A directional light needs a direction as well.
            let pointless =
                matches!(*l, Light::Directional { direction, .. } if direction == Vec3::ZERO);
            if !l.is_finite() || pointless {
                return Err(bad(format!("light {l:?} is not finite")));
            }
        }
        self.camera
            .validate()
            .map_err(|e| SdfError::Camera(e.to_string()))?;
        if !(self.max_distance.is_finite() && self.max_distance > 0.0) {
            return Err(bad(format!(
                "max distance {} must be positive and finite",
                self.max_distance
            )));
        }
        if self.max_steps == 0 {
            return Err(bad("the step budget is zero".into()));
        }
        if !(self.background.is_finite() && self.ambient.is_finite()) {
            return Err(bad("background and ambient must be finite".into()));
        }
        Ok(())
    }

    /// Whether the field is an exact distance.
    pub fn is_exact(&self) -> bool {
        self.root.is_exact()
    }

    /// The field's exactness tag.
    pub fn exactness(&self) -> Exactness {
        self.root.exactness()
    }

    /// What the scene contains, as far as passes are concerned: lights,
    /// mirrors and textures among the materials the tree uses.
    pub fn features(&self) -> SceneFeatures {
        let mut f = SceneFeatures::empty();
        if !self.lights.is_empty() {
            f |= SceneFeatures::HAS_LIGHTS;
        }
        let used = self.root.materials_used().into_iter();
        f | Material::features(used.filter_map(|i| self.materials.get(i as usize)))
    }
}
