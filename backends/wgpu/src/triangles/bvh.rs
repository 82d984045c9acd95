//! The scene on the GPU: an obvhs BVH2 of the mesh flattened into storage
//! buffers, with the triangles' attributes, the materials (albedo kinds of
//! `subcone_scene::material`), their palettes and texels, and the lights.
//! Traversed by `trace.wgsl` (closest hit and any hit, bounded stack).

use std::sync::Arc;
use std::time::Duration;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::bvh2::Bvh2;
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use subcone_scene::{Albedo, Light, RenderError, Scene, TriangleMesh};
use wgpu::util::DeviceExt;

use crate::context::{err, CacheKey, GpuContext};
use subcone_passes::bind::{Bindings, BufferAccess};

/// Entries of the traversal stack in `trace.wgsl`. A BVH deeper than this is
/// refused at upload (obvhs' builds stay far below it).
pub(crate) const STACK_SIZE: usize = 48;

pub(crate) use subcone_kernels::passes::MAX_LIGHTS;

/// A BVH2 node: inner (`count == 0`, children at `index` and `index + 1`) or
/// leaf (`count` triangles from `index` in BVH order).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct GpuNode {
    pub(crate) min: [f32; 3],
    pub(crate) count: u32,
    pub(crate) max: [f32; 3],
    pub(crate) index: u32,
}

/// A material; `kind`: 0 solid (`a`), 1 checker (`a`, `b`, `size`), 2 patches
/// (`extra.x` first palette colour, `extra.y` colours, `size`), 3 texture
/// (`extra.x` first texel, `extra.y` width, `extra.z` height, `extra.w` texels).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct GpuMaterial {
    pub(crate) a: [f32; 3],
    pub(crate) kind: u32,
    pub(crate) b: [f32; 3],
    pub(crate) size: f32,
    pub(crate) emission: [f32; 3],
    pub(crate) mirror: f32,
    pub(crate) extra: [u32; 4],
}

/// A light; `kind`: 0 point (`v` position, `value` intensity), 1 directional
/// (`v` unit direction towards it, `value` irradiance), 2 none (a
/// directional light with a zero direction never arrives).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct GpuLight {
    pub(crate) v: [f32; 3],
    pub(crate) kind: u32,
    pub(crate) value: [f32; 3],
    pub(crate) _pad: u32,
}

/// A scene's buffers on one device.
pub(crate) struct SceneGpu {
    pub nodes: wgpu::Buffer,
    /// Three `vec4` per triangle (BVH order): the vertices; `v0.w` holds the
    /// material index, `v1.w` 1 when the triangle casts shadows (bits).
    pub tris: wgpu::Buffer,
    /// Four `vec4` per triangle: n0.xyz uv0.x | n1.xyz uv0.y | n2.xyz uv1.x |
    /// uv1.y uv2.x uv2.y 0.
    pub attrs: wgpu::Buffer,
    pub materials: wgpu::Buffer,
    pub texels: wgpu::Buffer,
    pub lights: wgpu::Buffer,
    pub node_count: u32,
    pub triangle_count: u32,
    /// Bounding-box diagonal (the CPU's `SceneBvh::scale`).
    pub scale: f32,
}

/// The uploaded scene, built on first use per device and `scene.id()`, kept
/// in the device's own cache (device ids repeat across wgpu instances, so a
/// process-wide cache keyed by device could hand one device another's buffers).
impl SceneGpu {
    /// Bind what both the trace and the raster passes read of the scene:
    /// triangles, their attributes, materials and texels.
    pub(crate) fn bind_surfaces(&self, b: &mut Bindings) {
        b.buffer("tris", "array<vec4<f32>>", BufferAccess::Read, &self.tris);
        b.buffer("attrs", "array<vec4<f32>>", BufferAccess::Read, &self.attrs);
        b.buffer(
            "materials",
            "array<MaterialGpu>",
            BufferAccess::Read,
            &self.materials,
        );
        b.buffer(
            "texels",
            "array<vec4<f32>>",
            BufferAccess::Read,
            &self.texels,
        );
    }
}

/// An uploaded triangle scene's cache key: the scene's identity
/// ([`Scene::id`], renewed by [`Scene::touch`] when the scene changes).
#[derive(PartialEq, Eq, Hash)]
struct SceneKey(u64);

impl CacheKey for SceneKey {
    type Value = SceneGpu;
}

pub(crate) fn scene_gpu(ctx: &GpuContext, scene: &Scene) -> Result<Arc<SceneGpu>, RenderError> {
    ctx.cached_or_insert(SceneKey(scene.id()), |_| upload(ctx, scene))
}

fn f3(v: Vec3) -> [f32; 3] {
    v.to_array()
}

fn depth_of(nodes: &[obvhs::bvh2::node::Bvh2Node]) -> usize {
    let mut max = 0;
    let mut stack = vec![(0usize, 1usize)];
    while let Some((i, d)) = stack.pop() {
        max = max.max(d);
        let n = &nodes[i];
        if n.prim_count == 0 {
            let c = n.first_index as usize;
            if c + 1 < nodes.len() && d < 4 * STACK_SIZE {
                stack.push((c, d + 1));
                stack.push((c + 1, d + 1));
            } else {
                return usize::MAX;
            }
        }
    }
    max
}

fn upload(ctx: &GpuContext, scene: &Scene) -> Result<SceneGpu, RenderError> {
    let mesh = scene
        .mesh()
        .filter(|m| !m.is_empty())
        .ok_or_else(|| err(format!("scene {:?} has no triangles", scene.name)))?;
    let (bvh, nodes) = build_bvh(ctx, mesh)?;
    let order = &bvh.primitive_indices;
    let (tri_data, attr_data) = triangle_data(scene, mesh, order)?;
    let (materials, texels) = materials_and_texels(ctx, scene)?;
    let lights = gpu_lights(scene);
    let sizes = [
        ("BVH nodes", std::mem::size_of_val(nodes.as_slice())),
        ("triangles", std::mem::size_of_val(tri_data.as_slice())),
        (
            "triangle attributes",
            std::mem::size_of_val(attr_data.as_slice()),
        ),
        ("texels", std::mem::size_of_val(texels.as_slice())),
    ];
    for (what, bytes) in sizes {
        ctx.check_buffer_size(what, bytes as u64)?;
    }
    let scale = mesh
        .bounds()
        .map(|(lo, hi)| (hi - lo).length())
        .unwrap_or(1.0)
        .max(f32::MIN_POSITIVE);
    let usage = wgpu::BufferUsages::STORAGE;
    let buffer = |label: &str, contents: &[u8]| {
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
    };
    ctx.scoped("scene upload", || SceneGpu {
        nodes: buffer("BVH nodes", bytemuck::cast_slice(&nodes)),
        tris: buffer("triangles", bytemuck::cast_slice(&tri_data)),
        attrs: buffer("triangle attributes", bytemuck::cast_slice(&attr_data)),
        materials: buffer("materials", bytemuck::cast_slice(&materials)),
        texels: buffer("texels", bytemuck::cast_slice(&texels)),
        lights: buffer("lights", bytemuck::cast_slice(&lights)),
        node_count: nodes.len() as u32,
        triangle_count: order.len() as u32,
        scale,
    })
}

/// The mesh's obvhs BVH2 and its nodes as [`GpuNode`]s; refuses a mesh too
/// large for 32-bit indices or the buffer budget, and a BVH deeper than the
/// traversal stack.
fn build_bvh(ctx: &GpuContext, mesh: &TriangleMesh) -> Result<(Bvh2, Vec<GpuNode>), RenderError> {
    let n = mesh.len();
    if n > (u32::MAX / 4) as usize {
        return Err(err(format!("{n} triangles are too many for one mesh")));
    }
    // Budget the largest per-triangle buffer before building anything.
    ctx.check_buffer_size("triangle attributes", n as u64 * 64)?;
    let tris: Vec<Triangle> = mesh
        .positions
        .iter()
        .map(|v| Triangle {
            v0: v[0].into(),
            v1: v[1].into(),
            v2: v[2].into(),
        })
        .collect();
    let bvh = build_bvh2_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    if bvh.nodes.is_empty() {
        return Err(err("the BVH of the mesh is empty"));
    }
    let depth = depth_of(&bvh.nodes);
    if depth > STACK_SIZE {
        return Err(err(format!(
            "the BVH is {depth} levels deep; the GPU traversal stack holds {STACK_SIZE}"
        )));
    }
    let nodes: Vec<GpuNode> = bvh
        .nodes
        .iter()
        .map(|nd| GpuNode {
            min: nd.aabb.min.to_array(),
            count: nd.prim_count,
            max: nd.aabb.max.to_array(),
            index: nd.first_index,
        })
        .collect();
    Ok((bvh, nodes))
}

/// A storage buffer's contents as `vec4<f32>` elements.
type Vec4s = Vec<[f32; 4]>;

/// The triangles in BVH `order`: their vertices (`SceneGpu::tris`, with the
/// material, whether they cast shadows and their mesh index in the `w`s)
/// and their normals and texture coordinates (`SceneGpu::attrs`).
fn triangle_data(
    scene: &Scene,
    mesh: &TriangleMesh,
    order: &[u32],
) -> Result<(Vec4s, Vec4s), RenderError> {
    let n = mesh.len();
    // Emitters cast no shadows.
    let casts = |i: usize| {
        let m = mesh.materials[i] as usize;
        scene
            .materials
            .get(m)
            .is_none_or(|m| m.emission == Vec3::ZERO)
    };
    let mut tri_data: Vec<[f32; 4]> = Vec::with_capacity(order.len() * 3);
    let mut attr_data: Vec<[f32; 4]> = Vec::with_capacity(order.len() * 4);
    for &pi in order {
        let i = pi as usize;
        if i >= n {
            return Err(err("the BVH refers to a triangle the mesh does not have"));
        }
        let v = mesh.positions[i];
        let material = mesh.materials[i].min(scene.materials.len().saturating_sub(1) as u32);
        tri_data.push([v[0].x, v[0].y, v[0].z, f32::from_bits(material)]);
        tri_data.push([v[1].x, v[1].y, v[1].z, f32::from_bits(casts(i) as u32)]);
        tri_data.push([v[2].x, v[2].y, v[2].z, f32::from_bits(pi)]);
        let nv = mesh.normals[i];
        let uv = mesh.uvs[i];
        attr_data.push([nv[0].x, nv[0].y, nv[0].z, uv[0].x]);
        attr_data.push([nv[1].x, nv[1].y, nv[1].z, uv[0].y]);
        attr_data.push([nv[2].x, nv[2].y, nv[2].z, uv[1].x]);
        attr_data.push([uv[1].y, uv[2].x, uv[2].y, 0.0]);
    }
    Ok((tri_data, attr_data))
}

/// The scene's materials as [`GpuMaterial`]s and the texels their palettes
/// and textures read (one black texel when none does, so the buffer is not
/// empty); refuses a scene without materials, a texture with fewer texels
/// than its size, and texels over the buffer budget.
fn materials_and_texels(
    ctx: &GpuContext,
    scene: &Scene,
) -> Result<(Vec<GpuMaterial>, Vec4s), RenderError> {
    if scene.materials.is_empty() {
        return Err(err(format!("scene {:?} has no materials", scene.name)));
    }
    let mut texels: Vec<[f32; 4]> = Vec::new();
    let mut materials = Vec::with_capacity(scene.materials.len());
    for m in &scene.materials {
        let mut g = GpuMaterial {
            a: [0.5; 3],
            kind: 0,
            b: [0.5; 3],
            size: 1.0,
            emission: f3(m.emission),
            mirror: m.mirror,
            extra: [0; 4],
        };
        let push = |texels: &mut Vec<[f32; 4]>, c: &[Vec3]| -> Result<u32, RenderError> {
            let first = texels.len();
            let bytes = (first + c.len()) as u64 * 16;
            ctx.check_buffer_size(&format!("the texels of material {:?}", m.name), bytes)?;
            texels.extend(c.iter().map(|c| [c.x, c.y, c.z, 0.0]));
            u32::try_from(first).map_err(|_| err("too many texels"))
        };
        match &m.albedo {
            Albedo::Solid(c) => g.a = f3(*c),
            Albedo::Checker { a, b, size } => {
                g.kind = 1;
                g.a = f3(*a);
                g.b = f3(*b);
                g.size = *size;
            }
            Albedo::Patches { palette, size } => {
                g.kind = 2;
                g.size = *size;
                g.extra = [push(&mut texels, palette)?, palette.len() as u32, 0, 0];
            }
            Albedo::Texture(t) => {
                g.kind = 3;
                let len = t.texels.len();
                let w = t.width as u64;
                let h = t.height as u64;
                if w * h > len as u64 && len > 0 {
                    return Err(err(format!(
                        "texture of material {:?} is {w}x{h} but has {len} texels",
                        m.name
                    )));
                }
                let bytes = len as u64 * 16;
                ctx.check_buffer_size(&format!("the texture of material {:?}", m.name), bytes)?;
                g.extra = [push(&mut texels, &t.texels)?, t.width, t.height, len as u32];
            }
        }
        materials.push(g);
    }
    if texels.is_empty() {
        texels.push([0.0; 4]);
    }
    Ok((materials, texels))
}

/// The scene's lights as [`GpuLight`]s (one of kind "none" when it has
/// none, so the buffer is not empty).
fn gpu_lights(scene: &Scene) -> Vec<GpuLight> {
    // `WgpuBackend::render` has refused more than MAX_LIGHTS lights before
    // uploading.
    let mut lights: Vec<GpuLight> = scene
        .lights
        .iter()
        .map(|l| match *l {
            Light::Point {
                position,
                intensity,
            } => GpuLight {
                v: f3(position),
                kind: 0,
                value: f3(intensity),
                _pad: 0,
            },
            Light::Directional {
                direction,
                irradiance,
            } => {
                let d = direction.normalize_or_zero();
                GpuLight {
                    v: f3(d),
                    kind: if d == Vec3::ZERO { 2 } else { 1 },
                    value: f3(irradiance),
                    _pad: 0,
                }
            }
        })
        .collect();
    if lights.is_empty() {
        lights.push(GpuLight::zeroed());
    }
    lights
}
