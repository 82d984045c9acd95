//! A renderable scene: geometry, materials, lights, a default camera.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec3;
use subcone_kernels::passes::SceneFeatures;

use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::Light;
use crate::material::Material;
use crate::mesh::TriangleMesh;
use crate::sdf::{SdfNode, SdfScene};

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// The geometry of a scene.
#[derive(Clone, Debug)]
pub enum Geometry {
    /// Triangles, ray traced through a BVH.
    Triangles(TriangleMesh),
    /// A signed distance field, sphere traced.
    Sdf(SdfGeometry),
}

/// An SDF scene's field and its tracing limits.
#[derive(Clone, Debug)]
pub struct SdfGeometry {
    /// The field.
    pub root: SdfNode,
    /// Distance at which a ray leaves the scene.
    pub max_distance: f32,
    /// Step budget per ray.
    pub max_steps: u32,
}

impl SdfGeometry {
    /// The field's size, as a triangle scene's is its mesh's bounding-box
    /// diagonal: the diagonal of the box of its bounded objects
    /// ([`SdfNode::finite_bounds`]: an infinite floor plane does not count),
    /// or, when no part of the field is bounded or that diagonal is zero or
    /// not finite, [`max_distance`](Self::max_distance) (the reach of its
    /// rays). Always finite and positive for a validated scene.
    pub fn size(&self) -> f32 {
        let diagonal = self
            .root
            .finite_bounds()
            .map(|b| subcone_kernels::math::Euclidean::norm(b.max - b.min))
            .filter(|d| d.is_finite() && *d > 0.0);
        diagonal.unwrap_or(self.max_distance)
    }

    /// The length of ambient-occlusion rays
    /// ([`RenderSettings::ao_rays`](crate::RenderSettings::ao_rays)):
    /// [`AO_RADIUS_FRACTION`](crate::backend::AO_RADIUS_FRACTION) of
    /// [`size`](Self::size), as triangle scenes take it of their bounding
    /// diagonal. Every backend reads it here.
    pub fn ao_radius(&self) -> f32 {
        self.size() * subcone_kernels::ao::AO_RADIUS_FRACTION
    }
}

/// A scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Name, for messages and reports.
    pub name: String,
    /// The geometry.
    pub geometry: Geometry,
    /// Materials, indexed by the geometry.
    pub materials: Vec<Material>,
    /// Lights that cast hard shadows.
    pub lights: Vec<Light>,
    /// The default camera.
    pub camera: Camera,
    /// Colour of rays that hit nothing.
    pub background: Vec3,
    /// Ambient light, so that unlit surfaces are not black.
    pub ambient: Vec3,
    id: u64,
}

impl Scene {
    /// A triangle scene. Fails when no usable triangle is left, or when a
    /// material index points past `materials` (it is clamped with a message).
    pub fn triangles(
        name: &str,
        mesh: TriangleMesh,
        materials: Vec<Material>,
        lights: Vec<Light>,
        camera: Camera,
    ) -> Result<Self, SceneError> {
        if mesh.is_empty() {
            return Err(SceneError::Empty {
                name: name.into(),
                detail: String::new(),
            });
        }
        let materials = if materials.is_empty() {
            vec![Material::diffuse("default", Vec3::splat(0.7))]
        } else {
            materials
        };
        let mut mesh = mesh;
        let last = materials.len() as u32 - 1;
        for m in &mut mesh.materials {
            *m = (*m).min(last);
        }
        camera.validate()?;
        Ok(Scene {
            name: name.into(),
            geometry: Geometry::Triangles(mesh),
            materials,
            lights,
            camera,
            background: Vec3::new(0.05, 0.05, 0.06),
            ambient: Vec3::splat(0.03),
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        })
    }

    /// A scene from an SDF scene description.
    pub fn sdf(scene: SdfScene) -> Result<Self, SceneError> {
        scene.validate()?;
        let SdfScene {
            name,
            root,
            materials,
            lights,
            camera,
            background,
            ambient,
            max_distance,
            max_steps,
        } = scene;
        Ok(Scene {
            name,
            geometry: Geometry::Sdf(SdfGeometry {
                root,
                max_distance,
                max_steps,
            }),
            materials,
            lights,
            camera,
            background,
            ambient,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        })
    }

    /// The SDF, if this is an SDF scene.
    pub fn sdf_geometry(&self) -> Option<&SdfGeometry> {
        match &self.geometry {
            Geometry::Sdf(g) => Some(g),
            Geometry::Triangles(_) => None,
        }
    }

    /// A process-unique identity, for backends that cache per-scene data (a
    /// BVH). Clones share it; any `*_mut` change must call [`Scene::touch`].
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Give the scene a new identity after changing it, so caches rebuild.
    pub fn touch(&mut self) {
        self.id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
    }

    /// The triangles, if this is a triangle scene.
    pub fn mesh(&self) -> Option<&TriangleMesh> {
        match &self.geometry {
            Geometry::Triangles(m) => Some(m),
            Geometry::Sdf(_) => None,
        }
    }

    /// Whether any material is semi-transparent ([`Material::is_translucent`]),
    /// so the renderer must take the non-binary visibility path (CTSS §5.3).
    pub fn has_translucency(&self) -> bool {
        self.materials.iter().any(Material::is_translucent)
    }

    /// What the scene contains, as far as passes are concerned.
    pub fn features(&self) -> SceneFeatures {
        let mut f = SceneFeatures::empty();
        if !self.lights.is_empty() {
            f |= SceneFeatures::HAS_LIGHTS;
        }
        if let Geometry::Sdf(_) = self.geometry {
            f |= SceneFeatures::IS_SDF;
        }
        let sdf_used: Vec<u32> = match &self.geometry {
            Geometry::Sdf(g) => g.root.materials_used().into_iter().collect(),
            Geometry::Triangles(_) => Vec::new(),
        };
        let used = |i: usize| match &self.geometry {
            Geometry::Triangles(m) => m.materials.iter().any(|&k| k as usize == i),
            Geometry::Sdf(_) => sdf_used.contains(&(i as u32)),
        };
        let materials = self.materials.iter().enumerate();
        f | Material::features(materials.filter(|&(i, _)| used(i)).map(|(_, m)| m))
    }
}
