//! Triangle scenes on the GPU: NoAA, SSAA, SRAA (hybrid: rasterised subpixel
//! G-buffers, §3.1) and SRAA-RT (all ray traced), the same images as
//! subcone-cpu's `render.rs`.
//!
//! The scene is a BVH2 in storage buffers ([`bvh`]), traversed in WGSL compute
//! shaders (`trace.wgsl`: closest hit, any hit for shadows, Whitted shading).
//! Each frame's shader is generated for its planned passes: only the buffers
//! [`Passes`] asks for are declared, allocated and bound, and reads of an
//! absent buffer return the CPU backend's initial value. Compiled pipelines
//! are cached per device and shader source.

mod bvh;
#[cfg(test)]
mod layout_tests;
pub(crate) mod raster;

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use subcone_kernels::passes::{LayerLayout, Passes, Technique};
use subcone_kernels::sraa::{Geometry, SraaParams};
use subcone_scene::{
    Camera, Frame, FrameStats, Method, RayCounts, RenderError, RenderSettings, Scene,
};

use crate::context::{err, GpuContext};
use bvh::{SceneGpu, MAX_LIGHTS, STACK_SIZE};

const TRACE_WGSL: &str = include_str!("trace.wgsl");
pub(crate) const ALBEDO_WGSL: &str = include_str!("albedo.wgsl");
const SUPERSAMPLE_WGSL: &str = include_str!("supersample.wgsl");
const SUBPIXEL_WGSL: &str = include_str!("subpixel.wgsl");
const SRAA_WGSL: &str = include_str!("sraa.wgsl");

/// The frame's constants; `FrameUniform` in trace.wgsl (144 bytes).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct FrameUniform {
    cam_pos: [f32; 3],
    half: f32,
    forward: [f32; 3],
    aspect: f32,
    right: [f32; 3],
    eps: f32,
    up: [f32; 3],
    width_f: f32,
    ambient: [f32; 3],
    height_f: f32,
    background: [f32; 3],
    ssaa_side: u32,
    width: u32,
    height: u32,
    lights: u32,
    reflection_depth: u32,
    node_count: u32,
    _pad: [u32; 3],
    sraa: SraaParams,
}

impl FrameUniform {
    fn new(
        scene: &Scene,
        sg: &SceneGpu,
        camera: &Camera,
        method: &Method,
        s: &RenderSettings,
    ) -> Self {
        // Exactly the f32 values Camera::ray computes.
        let (w, h) = (s.width.max(1) as f32, s.height.max(1) as f32);
        FrameUniform {
            cam_pos: camera.position.to_array(),
            half: (0.5 * camera.fov_y).tan(),
            forward: camera.forward.to_array(),
            aspect: w / h,
            right: camera.right().to_array(),
            eps: sg.scale * 2e-5,
            up: camera.up.to_array(),
            width_f: w,
            ambient: scene.ambient.to_array(),
            height_f: h,
            background: scene.background.to_array(),
            ssaa_side: if method.technique == Technique::Ssaa {
                method.ssaa_side.max(1)
            } else {
                1
            },
            width: s.width,
            height: s.height,
            lights: scene.lights.len().min(MAX_LIGHTS) as u32,
            reflection_depth: s.reflection_depth,
            node_count: sg.node_count,
            _pad: [0; 3],
            sraa: method.sraa,
        }
    }
}

/// A frame buffer or texture bound in group 1.
pub(crate) enum Resource {
    Buffer(wgpu::Buffer),
    Texture(wgpu::TextureView),
}

/// One group-1 binding: its WGSL variable, element type and resource.
pub(crate) struct Binding {
    var: &'static str,
    ty: &'static str,
    res: Resource,
}

/// Frame buffers: what is bound, and what FrameStats reports.
#[derive(Default)]
pub(crate) struct FrameBuffers {
    bindings: Vec<Binding>,
    pub stats: Vec<(&'static str, usize)>,
}

impl FrameBuffers {
    /// Allocate a zeroed storage buffer of `bytes`, bound as `var: ty`, reported
    /// as `name`.
    pub(crate) fn storage(
        &mut self,
        ctx: &GpuContext,
        name: &'static str,
        var: &'static str,
        ty: &'static str,
        bytes: u64,
    ) -> Result<(), RenderError> {
        ctx.check_buffer_size(name, bytes)?;
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(name),
            size: bytes.max(16),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.stats.push((name, bytes as usize));
        self.bindings.push(Binding {
            var,
            ty,
            res: Resource::Buffer(buffer),
        });
        Ok(())
    }

    pub(crate) fn texture(&mut self, var: &'static str, view: wgpu::TextureView) {
        self.bindings.push(Binding {
            var,
            ty: "texture_2d_array<f32>",
            res: Resource::Texture(view),
        });
    }

    fn has(&self, var: &str) -> bool {
        self.bindings.iter().any(|b| b.var == var)
    }

    pub(crate) fn buffer(&self, var: &str) -> Option<&wgpu::Buffer> {
        self.bindings.iter().find_map(|b| match &b.res {
            Resource::Buffer(buf) if b.var == var => Some(buf),
            _ => None,
        })
    }

    /// The WGSL declarations of group 1.
    fn declarations(&self) -> String {
        let mut s = String::new();
        for (i, b) in self.bindings.iter().enumerate() {
            match b.res {
                Resource::Buffer(_) => {
                    s += &format!(
                        "@group(1) @binding({i}) var<storage, read_write> {}: {};\n",
                        b.var, b.ty
                    )
                }
                Resource::Texture(_) => {
                    s += &format!("@group(1) @binding({i}) var {}: {};\n", b.var, b.ty)
                }
            }
        }
        s
    }

    fn layout(&self, ctx: &GpuContext) -> wgpu::BindGroupLayout {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = self
            .bindings
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupLayoutEntry {
                binding: i as u32,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: match b.res {
                    Resource::Buffer(_) => wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    Resource::Texture(_) => wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                },
                count: None,
            })
            .collect();
        ctx.device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("frame buffers"),
                entries: &entries,
            })
    }

    fn bind_group(&self, ctx: &GpuContext, layout: &wgpu::BindGroupLayout) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = self
            .bindings
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: match &b.res {
                    Resource::Buffer(buf) => buf.as_entire_binding(),
                    Resource::Texture(v) => wgpu::BindingResource::TextureView(v),
                },
            })
            .collect();
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame buffers"),
            layout,
            entries: &entries,
        })
    }
}

/// `get_`/`put_` accessors of an optional per-pixel buffer `var` (element
/// `ty`, `per` elements per pixel): real ones when it is bound, else reads of
/// `default` and ignored writes. `HAS_<NAME>` says which.
fn accessors(
    fb: &FrameBuffers,
    name: &str,
    var: &str,
    ty: &str,
    per: u32,
    default: &str,
) -> String {
    let has = fb.has(var);
    let upper = name.to_uppercase();
    let (args, index) = if per == 1 {
        ("j: u32", "j".to_string())
    } else {
        ("j: u32, k: u32", format!("j * {per}u + k"))
    };
    if has {
        format!(
            "const HAS_{upper}: bool = true;\n\
             fn get_{name}({args}) -> {ty} {{ return {var}[{index}]; }}\n\
             fn put_{name}({args}, v: {ty}) {{ {var}[{index}] = v; }}\n"
        )
    } else {
        format!(
            "const HAS_{upper}: bool = false;\n\
             fn get_{name}({args}) -> {ty} {{ return {default}; }}\n\
             fn put_{name}({args}, v: {ty}) {{ }}\n"
        )
    }
}

/// The scene-wide bind group layout (group 0) for compute passes.
fn scene_layout(ctx: &GpuContext) -> wgpu::BindGroupLayout {
    let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let mut entries = vec![wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }];
    for b in 1..=6 {
        entries.push(storage(b, true));
    }
    entries.push(storage(7, false));
    ctx.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene"),
            entries: &entries,
        })
}

/// A compiled shader: its source hash and (lazily) its module.
struct Program<'a> {
    ctx: &'a GpuContext,
    source: String,
    hash: u64,
    module: Option<wgpu::ShaderModule>,
    layout: wgpu::PipelineLayout,
}

impl<'a> Program<'a> {
    fn new(ctx: &'a GpuContext, source: String, frame_layout: &wgpu::BindGroupLayout) -> Self {
        let mut h = DefaultHasher::new();
        source.hash(&mut h);
        let scene = scene_layout(ctx);
        let layout = ctx
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("triangles"),
                bind_group_layouts: &[Some(&scene), Some(frame_layout)],
                immediate_size: 0,
            });
        Program {
            ctx,
            source,
            hash: h.finish(),
            module: None,
            layout,
        }
    }

    fn pipeline(&mut self, entry: &'static str) -> Result<Arc<wgpu::ComputePipeline>, RenderError> {
        let ctx = self.ctx;
        let key = {
            let mut h = DefaultHasher::new();
            ("triangle pipeline", self.hash, entry).hash(&mut h);
            h.finish()
        };
        if let Some(p) = ctx.cached::<wgpu::ComputePipeline>(key) {
            return Ok(p);
        }
        if self.module.is_none() {
            let source = &self.source;
            self.module = Some(ctx.scoped("triangle shader", || {
                ctx.device
                    .create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some("triangles"),
                        source: wgpu::ShaderSource::Wgsl(source.as_str().into()),
                    })
            })?);
        }
        let module = self.module.as_ref().expect("compiled above");
        let layout = &self.layout;
        let p = Arc::new(ctx.scoped(entry, || {
            ctx.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(layout),
                    module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
        })?);
        ctx.cache_insert(key, p.clone());
        Ok(p)
    }
}

/// Everything a frame's compute passes bind.
struct Bound {
    scene_group: wgpu::BindGroup,
    frame_group: wgpu::BindGroup,
    counters: wgpu::Buffer,
    groups: (u32, u32),
}

impl Bound {
    fn new(
        ctx: &GpuContext,
        sg: &SceneGpu,
        uniform: &FrameUniform,
        fb: &FrameBuffers,
        frame_layout: &wgpu::BindGroupLayout,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        use wgpu::util::DeviceExt;
        ctx.scoped("frame setup", || {
            let uniform = ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("frame constants"),
                    contents: bytemuck::bytes_of(uniform),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
            let counters = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ray counters"),
                size: 48,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let layout = scene_layout(ctx);
            let scene_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("scene"),
                layout: &layout,
                entries: &[
                    uniform.as_entire_binding(),
                    sg.nodes.as_entire_binding(),
                    sg.tris.as_entire_binding(),
                    sg.attrs.as_entire_binding(),
                    sg.materials.as_entire_binding(),
                    sg.texels.as_entire_binding(),
                    sg.lights.as_entire_binding(),
                    counters.as_entire_binding(),
                ]
                .into_iter()
                .enumerate()
                .map(|(i, resource)| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource,
                })
                .collect::<Vec<_>>(),
            });
            Bound {
                scene_group,
                frame_group: fb.bind_group(ctx, frame_layout),
                counters,
                groups: (width.div_ceil(8), height.div_ceil(8)),
            }
        })
    }

    fn dispatch(&self, enc: &mut wgpu::CommandEncoder, p: &wgpu::ComputePipeline) {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: None,
            timestamp_writes: None,
        });
        pass.set_pipeline(p);
        pass.set_bind_group(0, &self.scene_group, &[]);
        pass.set_bind_group(1, &self.frame_group, &[]);
        pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
    }

    /// (primary, geometry, shadow, secondary, shaded); an error when a
    /// traversal was cut short (the image would be wrong).
    fn counts(&self, ctx: &GpuContext) -> Result<[u64; 5], RenderError> {
        let bytes = ctx.read_buffer(&self.counters, 0, 48)?;
        let v: &[u32] = bytemuck::cast_slice(&bytes);
        if v[10] > 0 {
            return Err(err(format!(
                "{} BVH traversals stopped before finishing (the driver limits the \
                 loop iterations of one shader invocation; llvmpipe allows 65 535): \
                 the frame would be wrong. Use fewer mirror bounces or a smaller mesh",
                v[10]
            )));
        }
        Ok(std::array::from_fn(|k| {
            v[2 * k] as u64 | ((v[2 * k + 1] as u64) << 32)
        }))
    }
}

fn read_vec4(ctx: &GpuContext, buf: &wgpu::Buffer, n: usize) -> Result<Vec<Vec3>, RenderError> {
    let bytes = ctx.read_buffer(buf, 0, (n * 16) as u64)?;
    let v: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    Ok(v.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect())
}

pub(crate) fn read_geometry(
    ctx: &GpuContext,
    buf: &wgpu::Buffer,
    n: usize,
) -> Result<Vec<Geometry>, RenderError> {
    let bytes = ctx.read_buffer(buf, 0, (n * 16) as u64)?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}

/// The shader of a frame: PARAMS, the SRAA kernels, trace.wgsl, the generated
/// header and the entry-point files.
fn shader(header: &str, entries: &[&str]) -> String {
    let mut s = String::new();
    s += subcone_kernels::wgsl::PARAMS;
    s += subcone_kernels::sraa::WGSL;
    s += ALBEDO_WGSL;
    s += &TRACE_WGSL
        .replace("__STACK_SIZE__", &STACK_SIZE.to_string())
        .replace("__MAX_LIGHTS__", &MAX_LIGHTS.to_string());
    s += header;
    for e in entries {
        s += e;
    }
    s
}

pub(crate) fn render(
    ctx: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    method: &Method,
    settings: &RenderSettings,
    passes: Passes,
) -> Result<Frame, RenderError> {
    // `WgpuBackend::plan` has refused more than MAX_LIGHTS lights.
    match method.technique {
        Technique::NoAa
        | Technique::Ssaa
        | Technique::Sraa
        | Technique::SraaRt
        | Technique::Fxaa => {}
        t => return Err(RenderError::Method(format!("{t:?} needs an SDF scene"))),
    }
    let sg = bvh::scene_gpu(ctx, scene)?;
    let uniform = FrameUniform::new(scene, &sg, camera, method, settings);
    match method.technique {
        Technique::NoAa | Technique::Ssaa | Technique::Fxaa => {
            supersample(ctx, &sg, &uniform, settings, passes)
        }
        _ => subpixel(ctx, scene, &sg, &uniform, method, settings, passes),
    }
}

fn to_rays(c: [u64; 5]) -> RayCounts {
    RayCounts {
        primary: c[0],
        geometry: c[1],
        shadow: c[2],
        secondary: c[3],
    }
}

/// AOVs: centre-ray depth and normal, through `centre_main` (not timed).
fn centre_geometry(
    ctx: &GpuContext,
    sg: &SceneGpu,
    uniform: &FrameUniform,
    s: &RenderSettings,
) -> Result<(Vec<f32>, Vec<Vec3>), RenderError> {
    let n = s.width as usize * s.height as usize;
    let mut fb = FrameBuffers::default();
    fb.storage(ctx, "aov geometry", "aov", "array<Geometry>", n as u64 * 16)?;
    // `color` belongs to supersample_main, which this program does not run.
    let header = fb.declarations()
        + "fn put_aov(j: u32, g: Geometry) { aov[j] = g; }\n"
        + "var<private> color: array<vec4<f32>, 1>;\n"
        + "var<private> sample_row: array<u32, 1>;\n";
    let layout = fb.layout(ctx);
    let source = shader(&header, &[SUPERSAMPLE_WGSL]);
    let mut prog = Program::new(ctx, source, &layout);
    let p = prog.pipeline("centre_main")?;
    let bound = Bound::new(ctx, sg, uniform, &fb, &layout, s.width, s.height)?;
    let mut t = Vec::new();
    ctx.timed_pass("aov", &mut t, |enc| bound.dispatch(enc, &p))?;
    let g = read_geometry(ctx, fb.buffer("aov").expect("allocated above"), n)?;
    Ok((
        g.iter().map(|g| g.depth).collect(),
        g.iter().map(|g| g.normal).collect(),
    ))
}

/// NoAA and SSAA (render.rs `supersample`): one pass "shading"; FXAA adds
/// the pass "post-process" (`post::fxaa`).
fn supersample(
    ctx: &GpuContext,
    sg: &SceneGpu,
    uniform: &FrameUniform,
    s: &RenderSettings,
    passes: Passes,
) -> Result<Frame, RenderError> {
    let n = s.width as usize * s.height as usize;
    let mut fb = FrameBuffers::default();
    fb.storage(ctx, "color", "color", "array<vec4<f32>>", n as u64 * 16)?;
    fb.storage(ctx, "sample row", "sample_row", "array<u32>", 4)?;
    let header = fb.declarations() + "fn put_aov(j: u32, g: Geometry) { }\n";
    let layout = fb.layout(ctx);
    let mut prog = Program::new(ctx, shader(&header, &[SUPERSAMPLE_WGSL]), &layout);
    let p = prog.pipeline("supersample_main")?;
    let bound = Bound::new(ctx, sg, uniform, &fb, &layout, s.width, s.height)?;
    // The grid rows 0..n, copied into `sample_row` before each row's dispatch.
    let side = uniform.ssaa_side.max(1);
    let rows: Vec<u32> = (0..side).collect();
    let rows = ctx.scoped("sample rows", || {
        use wgpu::util::DeviceExt;
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sample rows"),
                contents: bytemuck::cast_slice(&rows),
                usage: wgpu::BufferUsages::COPY_SRC,
            })
    })?;
    let row = fb.buffer("sample_row").expect("allocated above");
    let mut timings = Vec::new();
    ctx.timed_pass("shading", &mut timings, |enc| {
        for sy in 0..side as u64 {
            enc.copy_buffer_to_buffer(&rows, 4 * sy, row, 0, 4);
            bound.dispatch(enc, &p);
        }
    })?;
    let color = fb.buffer("color").expect("allocated above");
    let mut buffers = fb.stats.clone();
    let mut frame = Frame::new(s.width, s.height);
    if passes.contains(Passes::POST_PROCESS) {
        // FXAA on the GPU, then one read-back of the filtered frame.
        let (filtered, post_buffers) = crate::post::fxaa::run(
            ctx,
            color,
            s.width,
            s.height,
            &subcone_kernels::fxaa::FxaaParams::QUALITY,
            &mut timings,
        )?;
        buffers.extend(post_buffers);
        frame.color = read_vec4(ctx, &filtered, n)?;
    } else {
        frame.color = read_vec4(ctx, color, n)?;
    }
    let c = bound.counts(ctx)?;
    buffers.push(("sample rows", side as usize * 4));
    buffers.push(("ray counters", 48));
    frame.stats = FrameStats {
        passes,
        timings,
        buffers,
        rays: to_rays(c),
        shaded_samples: c[4],
        ..Default::default()
    };
    if s.aovs {
        let side = uniform.ssaa_side as f32;
        frame.samples_per_pixel = Some(vec![side * side; n]);
        let (d, nn) = centre_geometry(ctx, sg, uniform, s)?;
        frame.depth = Some(d);
        frame.normal = Some(nn);
    }
    Ok(frame)
}

/// SRAA (hybrid: raster subpixel geometry) and SRAA-RT (render.rs `subpixel`):
/// passes "shading", "geometry" and "antialiasing".
fn subpixel(
    ctx: &GpuContext,
    scene: &Scene,
    sg: &SceneGpu,
    uniform: &FrameUniform,
    method: &Method,
    s: &RenderSettings,
    passes: Passes,
) -> Result<Frame, RenderError> {
    let n = s.width as usize * s.height as usize;
    let rt = method.technique == Technique::SraaRt;
    let lights = scene.lights.len().min(MAX_LIGHTS);
    let layout = LayerLayout::new(method.technique, passes, lights);
    let shadows = passes.contains(Passes::SHADOW);
    let sub_shadows = rt && passes.contains(Passes::SUBPIXEL_SHADOW);
    let sub_secondary = rt && passes.contains(Passes::SUBPIXEL_SECONDARY_GEOMETRY);
    let secondary_shading = passes.contains(Passes::SECONDARY);
    let material = method.gates_material();
    let nl = layout.len();
    let n64 = n as u64;

    let mut fb = FrameBuffers::default();
    fb.storage(ctx, "color", "color", "array<vec4<f32>>", n64 * 16)?;
    fb.storage(ctx, "geometry", "geo", "array<Geometry>", n64 * 16)?;
    fb.storage(
        ctx,
        "shading layers",
        "values",
        "array<vec4<f32>>",
        n64 * nl as u64 * 16,
    )?;
    if layout.lights > 0 {
        fb.storage(ctx, "shadow states", "shadow_buf", "array<u32>", n64 * 4)?;
    }
    if layout.secondary {
        fb.storage(
            ctx,
            "secondary geometry",
            "geo2_buf",
            "array<Geometry>",
            n64 * 16,
        )?;
        if layout.lights > 0 {
            fb.storage(
                ctx,
                "secondary shadow states",
                "shadow2_buf",
                "array<u32>",
                n64 * 4,
            )?;
        }
    }
    let raster = if rt {
        fb.storage(
            ctx,
            "subpixel geometry",
            "sub_geo_buf",
            "array<Geometry>",
            n64 * 64,
        )?;
        fb.storage(ctx, "subsample index", "subsample", "array<u32>", 4)?;
        None
    } else {
        let r = raster::Raster::new(ctx, sg, uniform, s.width, s.height, material)?;
        fb.texture("sub_tex", r.view());
        fb.stats.push(("subpixel geometry", r.target_bytes()));
        fb.stats.push(("raster depth", r.depth_bytes()));
        if let Some(albedo) = r.albedo_view() {
            fb.texture("sub_alb_tex", albedo);
            fb.stats.push(("subpixel albedo", r.target_bytes()));
        }
        Some(r)
    };
    if material {
        fb.storage(ctx, "albedo", "albedo_buf", "array<vec4<f32>>", n64 * 16)?;
        if rt {
            fb.storage(
                ctx,
                "subpixel albedo",
                "sub_albedo_buf",
                "array<vec4<f32>>",
                n64 * 64,
            )?;
        }
    }
    if sub_shadows && layout.lights > 0 {
        fb.storage(
            ctx,
            "subpixel shadow states",
            "sub_shadow_buf",
            "array<u32>",
            n64 * 16,
        )?;
    }
    if sub_secondary {
        fb.storage(
            ctx,
            "subpixel secondary geometry",
            "sub_geo2_buf",
            "array<Geometry>",
            n64 * 64,
        )?;
        if layout.lights > 0 {
            fb.storage(
                ctx,
                "subpixel secondary shadow states",
                "sub_shadow2_buf",
                "array<u32>",
                n64 * 16,
            )?;
        }
    }

    let no_secondary = "Geometry(vec3<f32>(0.0), bitcast<f32>(0x7fc00000u))";
    let mut header = fb.declarations();
    header += &format!(
        "const NL: u32 = {nl}u;\nconst LAYER_LIGHTS: u32 = {}u;\nconst SINGLE: bool = {};\n\
         const SECONDARY_LAYERS: bool = {};\nconst SHADOWS: bool = {shadows};\n\
         const SECONDARY_SHADING: bool = {secondary_shading};\nconst MATERIAL: bool = {material};\n",
        layout.lights, layout.single, layout.secondary
    );
    header += &accessors(&fb, "shadow", "shadow_buf", "u32", 1, "0u");
    header += &accessors(&fb, "geo2", "geo2_buf", "Geometry", 1, no_secondary);
    header += &accessors(&fb, "shadow2", "shadow2_buf", "u32", 1, "0u");
    header += &accessors(&fb, "sub_shadow", "sub_shadow_buf", "u32", 4, "0u");
    header += &accessors(&fb, "sub_geo2", "sub_geo2_buf", "Geometry", 4, no_secondary);
    header += &accessors(&fb, "sub_shadow2", "sub_shadow2_buf", "u32", 4, "0u");
    header += &accessors(
        &fb,
        "albedo",
        "albedo_buf",
        "vec4<f32>",
        1,
        "vec4<f32>(0.0)",
    );
    if !rt && material {
        header += raster::SUB_ALBEDO_ACCESSORS;
    } else {
        header += &accessors(
            &fb,
            "sub_albedo",
            "sub_albedo_buf",
            "vec4<f32>",
            4,
            "vec4<f32>(0.0)",
        );
    }
    if rt {
        header += &accessors(
            &fb,
            "sub_geo",
            "sub_geo_buf",
            "Geometry",
            4,
            "Geometry(vec3<f32>(0.0), subcone_inf())",
        );
    } else {
        header += raster::SUB_GEO_ACCESSORS;
        header += "var<private> subsample: array<u32, 1>;\n";
    }
    let frame_layout = fb.layout(ctx);
    let source = shader(&header, &[SUBPIXEL_WGSL, SRAA_WGSL]);
    let mut prog = Program::new(ctx, source, &frame_layout);
    let shade = prog.pipeline("shade_main")?;
    let geometry = if rt {
        Some(prog.pipeline("geometry_main")?)
    } else {
        None
    };
    let resolve = prog.pipeline("resolve_main")?;
    let bound = Bound::new(ctx, sg, uniform, &fb, &frame_layout, s.width, s.height)?;

    let indices = subsample_indices(ctx)?;
    let mut timings = Vec::new();
    ctx.timed_pass("shading", &mut timings, |enc| bound.dispatch(enc, &shade))?;
    match (&geometry, &raster) {
        (Some(p), _) => ctx.timed_pass("geometry", &mut timings, |enc| {
            let k = fb.buffer("subsample").expect("allocated above");
            for i in 0..4 {
                enc.copy_buffer_to_buffer(&indices, 4 * i, k, 0, 4);
                bound.dispatch(enc, p);
            }
        })?,
        (None, Some(r)) => ctx.timed_pass("geometry", &mut timings, |enc| r.record(enc))?,
        (None, None) => unreachable!("one of the two is set above"),
    }
    ctx.timed_pass("antialiasing", &mut timings, |enc| {
        bound.dispatch(enc, &resolve)
    })?;

    let color = fb.buffer("color").expect("allocated above");
    let mut buffers = fb.stats.clone();
    let mut frame = Frame::new(s.width, s.height);
    if passes.contains(Passes::POST_PROCESS) {
        // FXAA on the GPU, then one read-back of the filtered frame.
        let (filtered, post_buffers) = crate::post::fxaa::run(
            ctx,
            color,
            s.width,
            s.height,
            &subcone_kernels::fxaa::FxaaParams::QUALITY,
            &mut timings,
        )?;
        buffers.extend(post_buffers);
        frame.color = read_vec4(ctx, &filtered, n)?;
    } else {
        frame.color = read_vec4(ctx, color, n)?;
    }
    let c = bound.counts(ctx)?;
    buffers.push(("subsample indices", 16));
    buffers.push(("ray counters", 48));
    frame.stats = FrameStats {
        passes,
        timings,
        buffers,
        rays: to_rays(c),
        shaded_samples: c[4],
        ..Default::default()
    };
    if s.aovs {
        let (d, nn) = centre_geometry(ctx, sg, uniform, s)?;
        frame.depth = Some(d);
        frame.normal = Some(nn);
        frame.samples_per_pixel = Some(vec![1.0; n]);
    }
    Ok(frame)
}

/// Four subsample geometries per pixel.
#[cfg(test)]
pub(crate) type SubGeometry = Vec<[Geometry; 4]>;

/// The subsample indices 0..4, copied one at a time into `subsample` before
/// each of the geometry pass's dispatches.
fn subsample_indices(ctx: &GpuContext) -> Result<wgpu::Buffer, RenderError> {
    use wgpu::util::DeviceExt;
    ctx.scoped("subsample indices", || {
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("subsample indices"),
                contents: bytemuck::cast_slice(&[0u32, 1, 2, 3]),
                usage: wgpu::BufferUsages::COPY_SRC,
            })
    })
}

/// For tests: the four subpixel geometries of every pixel, from the raster
/// pass and from ray tracing (`geometry_main`), `[pixel][subsample]`.
#[cfg(test)]
pub(crate) fn subpixel_geometry_both(
    ctx: &GpuContext,
    scene: &Scene,
    width: u32,
    height: u32,
) -> Result<(SubGeometry, SubGeometry), RenderError> {
    let s = RenderSettings::new(width, height);
    let method: Method = "sraa-rt"
        .parse()
        .map_err(|e| RenderError::Method(format!("{e:?}")))?;
    let passes = subcone_kernels::passes::required_passes(method.technique, scene.features())
        .map_err(|e| RenderError::Method(e.to_string()))?;
    let sg = bvh::scene_gpu(ctx, scene)?;
    let uniform = FrameUniform::new(scene, &sg, &scene.camera, &method, &s);
    // Ray traced: run SRAA-RT's shading and geometry passes.
    let n = width as usize * height as usize;
    let mut fb = FrameBuffers::default();
    fb.storage(ctx, "geometry", "geo", "array<Geometry>", n as u64 * 16)?;
    fb.storage(
        ctx,
        "shading layers",
        "values",
        "array<vec4<f32>>",
        n as u64 * 16,
    )?;
    fb.storage(ctx, "color", "color", "array<vec4<f32>>", n as u64 * 16)?;
    fb.storage(
        ctx,
        "subpixel geometry",
        "sub_geo_buf",
        "array<Geometry>",
        n as u64 * 64,
    )?;
    fb.storage(ctx, "subsample index", "subsample", "array<u32>", 4)?;
    let mut header = fb.declarations();
    header += "const NL: u32 = 1u;\nconst LAYER_LIGHTS: u32 = 0u;\nconst SINGLE: bool = true;\n\
               const SECONDARY_LAYERS: bool = false;\nconst SHADOWS: bool = false;\n\
               const SECONDARY_SHADING: bool = false;\nconst MATERIAL: bool = false;\n";
    let no_secondary = "Geometry(vec3<f32>(0.0), bitcast<f32>(0x7fc00000u))";
    header += &accessors(&fb, "shadow", "shadow_buf", "u32", 1, "0u");
    header += &accessors(&fb, "geo2", "geo2_buf", "Geometry", 1, no_secondary);
    header += &accessors(&fb, "shadow2", "shadow2_buf", "u32", 1, "0u");
    header += &accessors(&fb, "sub_shadow", "sub_shadow_buf", "u32", 4, "0u");
    header += &accessors(&fb, "sub_geo2", "sub_geo2_buf", "Geometry", 4, no_secondary);
    header += &accessors(&fb, "sub_shadow2", "sub_shadow2_buf", "u32", 4, "0u");
    header += &accessors(&fb, "sub_geo", "sub_geo_buf", "Geometry", 4, "Geometry()");
    header += &accessors(
        &fb,
        "albedo",
        "albedo_buf",
        "vec4<f32>",
        1,
        "vec4<f32>(0.0)",
    );
    header += &accessors(
        &fb,
        "sub_albedo",
        "sub_albedo_buf",
        "vec4<f32>",
        4,
        "vec4<f32>(0.0)",
    );
    let layout = fb.layout(ctx);
    let mut prog = Program::new(ctx, shader(&header, &[SUBPIXEL_WGSL, SRAA_WGSL]), &layout);
    let shade = prog.pipeline("shade_main")?;
    let geometry = prog.pipeline("geometry_main")?;
    let bound = Bound::new(ctx, &sg, &uniform, &fb, &layout, width, height)?;
    let mut t = Vec::new();
    ctx.timed_pass("shading", &mut t, |enc| bound.dispatch(enc, &shade))?;
    let indices = subsample_indices(ctx)?;
    ctx.timed_pass("geometry", &mut t, |enc| {
        let k = fb.buffer("subsample").expect("allocated");
        for i in 0..4 {
            enc.copy_buffer_to_buffer(&indices, 4 * i, k, 0, 4);
            bound.dispatch(enc, &geometry);
        }
    })?;
    let traced = read_geometry(ctx, fb.buffer("sub_geo_buf").expect("allocated"), 4 * n)?;
    let _ = passes;
    // Rasterised.
    let r = raster::Raster::new(ctx, &sg, &uniform, width, height, false)?;
    ctx.timed_pass("geometry", &mut t, |enc| r.record(enc))?;
    let rastered = r.read(ctx)?;
    let group = |v: Vec<Geometry>| -> Vec<[Geometry; 4]> {
        v.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect()
    };
    Ok((group(rastered), group(traced)))
}
