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

pub(crate) mod bvh;
pub(crate) mod raster;
pub(crate) mod resolve;

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use subcone_kernels::passes::{Passes, SubpixelPasses, Technique};
use subcone_kernels::sraa::{Geometry, SraaParams};
use subcone_scene::{
    Camera, Frame, FrameStats, Method, RayCounts, RenderError, RenderSettings, Scene,
};

use crate::compute::{self, Allocate, Program};
use crate::context::{err, GpuContext};
use crate::Job;
use bvh::{SceneGpu, MAX_LIGHTS, STACK_SIZE};
use subcone_passes::bind::{Bindings, BufferAccess};

pub(crate) const TRACE_WGSL: &str = include_str!("trace.wgsl");
pub(crate) const FRAME_WGSL: &str = include_str!("frame.wgsl");
pub(crate) const ALBEDO_WGSL: &str = include_str!("albedo.wgsl");
const SUPERSAMPLE_WGSL: &str = include_str!("supersample.wgsl");
/// The AOV pass's entry point (`centre_main`).
const CENTRE_WGSL: &str = include_str!("centre.wgsl");
const SUBPIXEL_WGSL: &str = include_str!("subpixel.wgsl");
/// SRAA-RT's traced subsamples' entry point (`geometry_main`).
const GEOMETRY_WGSL: &str = include_str!("geometry.wgsl");

/// The frame's constants; `FrameUniform` in frame.wgsl (176 bytes), read
/// by the compute passes and the raster pass.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct FrameUniform {
    pub(crate) cam_pos: [f32; 3],
    pub(crate) half: f32,
    pub(crate) forward: [f32; 3],
    pub(crate) aspect: f32,
    pub(crate) right: [f32; 3],
    pub(crate) eps: f32,
    pub(crate) up: [f32; 3],
    pub(crate) width_f: f32,
    pub(crate) ambient: [f32; 3],
    pub(crate) height_f: f32,
    pub(crate) background: [f32; 3],
    pub(crate) ssaa_side: u32,
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) lights: u32,
    pub(crate) reflection_depth: u32,
    pub(crate) node_count: u32,
    /// Near plane of the raster pass's reversed depth.
    pub(crate) near: f32,
    /// Ambient-occlusion rays per shaded primary hit (0: off).
    pub(crate) ao_rays: u32,
    /// Their length: `AO_RADIUS_FRACTION` of the bounding diagonal.
    pub(crate) ao_radius: f32,
    pub(crate) sraa: SraaParams,
    /// `Camera::jitter`: every primary ray's (and rasterised subsample's)
    /// sub-pixel offset.
    pub(crate) jitter: [f32; 2],
    /// 1 for `ssaa2`: only the diagonal of the `ssaa_side` grid
    /// (`Method::ssaa_diagonal`); 0 for the whole grid.
    pub(crate) ssaa_diagonal: u32,
    pub(crate) _pad: f32,
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
            ssaa_side: if method.technique() == Technique::Ssaa {
                method.ssaa_side().max(1)
            } else {
                1
            },
            width: s.width,
            height: s.height,
            lights: scene.lights.len().min(MAX_LIGHTS) as u32,
            reflection_depth: s.reflection_depth,
            node_count: sg.node_count,
            // Far below any ray offset; reversed Z keeps the precision.
            near: sg.scale * 1e-7,
            ao_rays: s.ao_rays,
            ao_radius: sg.scale * subcone_kernels::ao::AO_RADIUS_FRACTION,
            sraa: method.sraa(),
            jitter: camera.jitter.to_array(),
            ssaa_diagonal: u32::from(
                method.technique() == Technique::Ssaa && method.ssaa_diagonal(),
            ),
            _pad: 0.0,
        }
    }
}

/// `get_`/`put_` accessors of an optional per-pixel buffer `var` (element
/// `ty`, `per` elements per pixel): real ones when it is bound, else reads of
/// `default` and ignored writes. `HAS_<NAME>` says which.
pub(crate) fn accessors(
    fb: &Bindings,
    name: &str,
    var: &str,
    ty: &str,
    per: u32,
    default: &str,
) -> String {
    let has = fb.contains(var);
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

/// Group 0 of every triangle pass: the frame's constants, the scene's
/// buffers (shared with the cached scene) and the ray counters.
fn scene_bindings(
    ctx: &GpuContext,
    sg: &SceneGpu,
    uniform: &FrameUniform,
) -> Result<Bindings, RenderError> {
    let mut b = Bindings::new(0);
    b.uniform(ctx, "frame", "FrameUniform", uniform)?;
    b.buffer("nodes", "array<BvhNode>", BufferAccess::Read, &sg.nodes);
    sg.bind_surfaces(&mut b);
    b.buffer("lights", "array<LightGpu>", BufferAccess::Read, &sg.lights);
    // 64-bit as (lo, hi) pairs: primary, geometry, shadow, secondary,
    // shaded; then [10] traversals that ended before their stack emptied,
    // [11] unused; then [12, 13] ambient-occlusion rays.
    b.storage(
        ctx,
        "ray counters",
        "counters",
        "array<atomic<u32>, 14>",
        56,
    )?;
    Ok(b)
}

/// The host's limits trace.wgsl sizes its arrays by, as WGSL constants
/// (`STACK_SIZE`, `MAX_LIGHTS`): declared, not substituted into its text.
/// (Override constants cannot size a private array.)
pub(crate) fn limits_wgsl() -> String {
    format!("const STACK_SIZE: u32 = {STACK_SIZE}u;\nconst MAX_LIGHTS: u32 = {MAX_LIGHTS}u;\n")
}

/// A frame's compute program: group 0 the scene ([`scene_bindings`]), group
/// 1 the frame buffers `fb`, sources the SRAA kernels, trace.wgsl, `header`
/// and the entry-point files `entries`.
fn program<'a>(
    ctx: &'a GpuContext,
    scene: &Bindings,
    fb: &Bindings,
    header: &str,
    entries: &[&str],
) -> Result<Program<'a>, RenderError> {
    let limits = limits_wgsl();
    let mut sources = vec![
        subcone_kernels::sraa::WGSL,
        subcone_kernels::ao::WGSL,
        FRAME_WGSL,
        ALBEDO_WGSL,
        &limits,
        TRACE_WGSL,
        header,
    ];
    sources.extend(entries);
    Program::new(ctx, "triangles", &sources, &[scene, fb])
}

/// (primary, geometry, shadow, secondary, shaded, ao) of the scene group's
/// ray counters; an error when a traversal was cut short (the image would be
/// wrong).
fn counts(ctx: &GpuContext, scene: &Bindings) -> Result<[u64; 6], RenderError> {
    let v: Vec<u32> = compute::read(ctx, scene.get("counters")?, 14)?;
    if v[10] > 0 {
        return Err(err(format!(
            "{} BVH traversals stopped before finishing (the driver limits the \
             loop iterations of one shader invocation; llvmpipe allows 65 535): \
             the frame would be wrong. Use fewer mirror bounces or a smaller mesh",
            v[10]
        )));
    }
    // Pair 5 is the traversal flags; the AO rays are pair 6.
    Ok(std::array::from_fn(|k| {
        let k = if k == 5 { 6 } else { k };
        v[2 * k] as u64 | ((v[2 * k + 1] as u64) << 32)
    }))
}

fn read_vec4(ctx: &GpuContext, buf: &wgpu::Buffer, n: usize) -> Result<Vec<Vec3>, RenderError> {
    let v: Vec<[f32; 4]> = compute::read(ctx, buf, n)?;
    Ok(v.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect())
}

pub(crate) fn render(ctx: &GpuContext, job: &Job) -> Result<Frame, RenderError> {
    // `WgpuBackend::plan` has refused more than MAX_LIGHTS lights.
    // Every technique named (no wildcard): a new one must be routed.
    let subpixel = match job.method.technique() {
        Technique::NoAa | Technique::Ssaa | Technique::Fxaa => false,
        Technique::Sraa | Technique::SraaRt => true,
        t @ (Technique::Ctss | Technique::CtssR | Technique::SsaaCtss) => {
            return Err(RenderError::Method(format!("{t:?} needs an SDF scene")))
        }
    };
    let sg = bvh::scene_gpu(ctx, job.scene)?;
    let uniform = FrameUniform::new(job.scene, &sg, job.camera, job.method, job.settings);
    let setup = Setup {
        ctx,
        job,
        scene: scene_bindings(ctx, &sg, &uniform)?,
        sg,
        uniform,
    };
    if subpixel {
        self::subpixel(&setup)
    } else {
        supersample(&setup)
    }
}

/// What every pass of a triangle frame shares: the job, the scene on the
/// device, the frame's constants and the bind group of both (group 0).
struct Setup<'a> {
    ctx: &'a GpuContext,
    job: &'a Job<'a>,
    sg: Arc<SceneGpu>,
    uniform: FrameUniform,
    scene: Bindings,
}

fn to_rays(c: [u64; 6]) -> RayCounts {
    RayCounts {
        primary: c[0],
        geometry: c[1],
        shadow: c[2],
        secondary: c[3],
        ao: c[5],
    }
}

/// AOVs: centre-ray depth and normal, through `centre_main` (not timed).
fn centre_geometry(f: &Setup) -> Result<(Vec<f32>, Vec<Vec3>), RenderError> {
    let (ctx, s) = (f.ctx, f.job.settings);
    let n = s.width as usize * s.height as usize;
    // Its own ray counters: the frame's are read already, and AOVs are not
    // counted (nor are they on the CPU).
    let scene = scene_bindings(ctx, &f.sg, &f.uniform)?;
    let mut fb = Bindings::new(1);
    fb.storage(
        ctx,
        "aov geometry",
        "aov",
        "array<subcone_Geometry>",
        n as u64 * 16,
    )?;
    let mut prog = program(ctx, &scene, &fb, "", &[CENTRE_WGSL])?;
    let p = prog.pipeline("centre_main")?;
    let groups = workgroups(ctx, s)?;
    ctx.timed_pass("aov", &mut Vec::new(), |enc| prog.dispatch(enc, &p, groups))?;
    let g: Vec<Geometry> = compute::read(ctx, fb.get("aov")?, n)?;
    Ok((
        g.iter().map(|g| g.depth).collect(),
        g.iter().map(|g| g.normal).collect(),
    ))
}

/// The 8×8 workgroups of a frame.
fn workgroups(ctx: &GpuContext, s: &RenderSettings) -> Result<(u32, u32), RenderError> {
    compute::workgroups(ctx, "triangles", s.width, s.height, 8)
}

/// The indices `0..count` in a buffer, copied one at a time into a one-word
/// storage buffer by [`each_index`].
fn indices(ctx: &GpuContext, label: &'static str, count: u32) -> Result<wgpu::Buffer, RenderError> {
    use wgpu::util::DeviceExt;
    let v: Vec<u32> = (0..count).collect();
    ctx.scoped(label, || {
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(&v),
                usage: wgpu::BufferUsages::COPY_SRC,
            })
    })
}

/// For each index of `indices` (from [`indices`]), copy it into `slot` and
/// record `dispatch`: one dispatch per SSAA grid row or per subsample.
fn each_index(
    enc: &mut wgpu::CommandEncoder,
    indices: &wgpu::Buffer,
    slot: &wgpu::Buffer,
    mut dispatch: impl FnMut(&mut wgpu::CommandEncoder),
) {
    for i in 0..indices.size() / 4 {
        enc.copy_buffer_to_buffer(indices, 4 * i, slot, 0, 4);
        dispatch(enc);
    }
}

/// Where a frame's colour is once its passes have run.
enum FrameColor<'r, 'a> {
    /// The frame group's buffer `color`.
    Buffer,
    /// Hybrid SRAA's resolve output (a texture), or the colour buffer it
    /// copied the output into for a post-process.
    Resolved(&'r resolve::HybridResolve<'a>),
}

/// The end of every frame: FXAA when planned, the colour read back, the ray
/// counters checked and the stats filled (`extra` lists buffers allocated
/// besides the two groups).
fn finish(
    f: &Setup,
    fb: &Bindings,
    color: FrameColor<'_, '_>,
    mut timings: Vec<subcone_scene::PassTiming>,
    extra: &[(&'static str, usize)],
) -> Result<Frame, RenderError> {
    let (ctx, s, passes, scene) = (f.ctx, f.job.settings, f.job.passes, &f.scene);
    let n = s.width as usize * s.height as usize;
    let mut buffers = fb.accounts().to_vec();
    let mut frame = Frame::new(s.width, s.height);
    if passes.contains(Passes::POST_PROCESS) {
        let color = match color {
            FrameColor::Buffer => fb.get("color")?,
            FrameColor::Resolved(h) => h.post_process_input().ok_or_else(|| {
                err("post-process: the resolve was built without its colour buffer")
            })?,
        };
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
        frame.color = match color {
            FrameColor::Buffer => read_vec4(ctx, fb.get("color")?, n)?,
            FrameColor::Resolved(h) => h.read_output(ctx)?,
        };
    }
    let c = counts(ctx, scene)?;
    buffers.extend_from_slice(extra);
    buffers.extend_from_slice(scene.accounts());
    frame.stats = FrameStats {
        passes,
        timings,
        buffers,
        rays: to_rays(c),
        shaded_samples: c[4],
        ..Default::default()
    };
    Ok(frame)
}

/// NoAA and SSAA (render.rs `supersample`): one pass "shading"; FXAA adds
/// the pass "post-process" (`post::fxaa`).
fn supersample(f: &Setup) -> Result<Frame, RenderError> {
    let (ctx, s, scene) = (f.ctx, f.job.settings, &f.scene);
    let n = s.width as usize * s.height as usize;
    let mut fb = Bindings::new(1);
    fb.storage(ctx, "color", "color", "array<vec4<f32>>", n as u64 * 16)?;
    fb.storage(ctx, "sample row", "sample_row", "array<u32>", 4)?;
    let mut prog = program(ctx, scene, &fb, "", &[SUPERSAMPLE_WGSL])?;
    let p = prog.pipeline("supersample_main")?;
    let groups = workgroups(ctx, s)?;
    // The grid rows 0..side, one dispatch each; the diagonal (`ssaa2`)
    // takes its `side` samples in one.
    let side = f.uniform.ssaa_side.max(1);
    let diagonal = f.uniform.ssaa_diagonal != 0;
    let rows = indices(ctx, "sample rows", if diagonal { 1 } else { side })?;
    let row = fb.get("sample_row")?;
    let mut timings = Vec::new();
    ctx.timed_pass("shading", &mut timings, |enc| {
        each_index(enc, &rows, row, |enc| prog.dispatch(enc, &p, groups))
    })?;
    let mut frame = finish(
        f,
        &fb,
        FrameColor::Buffer,
        timings,
        &[("sample rows", side as usize * 4)],
    )?;
    if s.aovs {
        let side = f.uniform.ssaa_side as f32;
        let spp = if diagonal { side } else { side * side };
        frame.samples_per_pixel = Some(vec![spp; n]);
        let (d, nn) = centre_geometry(f)?;
        frame.depth = Some(d);
        frame.normal = Some(nn);
    }
    Ok(frame)
}

/// Which of SRAA's and SRAA-RT's frame buffers exist, from the frame's
/// method and planned passes: the kernels' [`SubpixelPasses`], which the
/// CPU backend's plan holds too, and the frame's size.
struct SubpixelPlan {
    /// Pixels.
    n: u64,
    /// What the frame computes beyond primary visibility. With
    /// `splits_layers` (SRAA-RT) the subsamples are traced into buffers;
    /// without, SRAA's raster pass fills them.
    passes: SubpixelPasses,
}

impl SubpixelPlan {
    fn new(f: &Setup) -> Self {
        let (scene, method, s, passes) = (f.job.scene, f.job.method, f.job.settings, f.job.passes);
        let lights = scene.lights.len().min(MAX_LIGHTS);
        SubpixelPlan {
            n: (s.width as usize * s.height as usize) as u64,
            passes: SubpixelPasses::new(
                method.technique(),
                passes,
                lights,
                method.gates_material(),
            ),
        }
    }
}

/// Hybrid SRAA's (§3.1) own passes: the raster pass that fills the
/// subsamples and the resolve that reads them.
struct Hybrid<'a> {
    raster: raster::Raster,
    resolve: resolve::HybridResolve<'a>,
}

/// The frame group of SRAA and SRAA-RT for `passes` (group 1), the WGSL
/// header that declares what it holds, and hybrid SRAA's raster pass and
/// resolve. The group is bound in the order of the steps: the shaded
/// samples', the subsamples' geometry, the gates'. Hybrid SRAA's shaded
/// samples are the resolve's textures, not buffers.
fn subpixel_bindings<'a>(
    f: &Setup<'a>,
) -> Result<(Bindings, String, Option<Hybrid<'a>>), RenderError> {
    let plan = SubpixelPlan::new(f);
    let mut fb = Bindings::new(1);
    let resolve = if plan.passes.splits_layers {
        shaded_sample_buffers(f.ctx, &mut fb, &plan)?;
        None
    } else {
        let s = f.job.settings;
        let r = resolve::HybridResolve::new(
            f.ctx,
            &f.job.method.sraa(),
            plan.passes.material,
            f.job.passes.contains(Passes::POST_PROCESS),
            s.width,
            s.height,
        )?;
        r.bind_shading_targets(&mut fb)?;
        Some(r)
    };
    let raster = subsample_geometry(f, &mut fb, &plan)?;
    gate_buffers(f.ctx, &mut fb, &plan)?;
    let mut header = subpixel_header(&fb, &plan);
    let hybrid = match (raster, resolve) {
        (Some(raster), Some(resolve)) => {
            header += &resolve.shading_accessors();
            Some(Hybrid { raster, resolve })
        }
        (None, None) => None,
        _ => {
            return Err(err(
                "hybrid SRAA needs both its raster pass and its resolve",
            ))
        }
    };
    Ok((fb, header, hybrid))
}

/// What SRAA-RT's shading pass writes: the colour, and per shaded sample
/// its geometry, its layers and, where planned, its shadow states and its
/// mirror hit's geometry and shadow states.
fn shaded_sample_buffers(
    ctx: &GpuContext,
    fb: &mut Bindings,
    plan: &SubpixelPlan,
) -> Result<(), RenderError> {
    let (n64, layout) = (plan.n, &plan.passes.layout);
    let nl = layout.len();
    fb.storage(ctx, "color", "color", "array<vec4<f32>>", n64 * 16)?;
    fb.storage(ctx, "geometry", "geo", "array<subcone_Geometry>", n64 * 16)?;
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
            "array<subcone_Geometry>",
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
    Ok(())
}

/// Where the subsamples' geometry comes from: SRAA-RT traces it into a
/// buffer (one subsample per dispatch, its index in `subsample`); SRAA
/// rasterises it (§3.1's hybrid), and the raster pass is returned.
fn subsample_geometry(
    f: &Setup,
    fb: &mut Bindings,
    plan: &SubpixelPlan,
) -> Result<Option<raster::Raster>, RenderError> {
    let (ctx, s, n64) = (f.ctx, f.job.settings, plan.n);
    if plan.passes.splits_layers {
        fb.storage(
            ctx,
            "subpixel geometry",
            "sub_geo_buf",
            "array<subcone_Geometry>",
            n64 * 64,
        )?;
        fb.storage(ctx, "subsample index", "subsample", "array<u32>", 4)?;
        return Ok(None);
    }
    let r = raster::Raster::new(
        ctx,
        &f.sg,
        &f.uniform,
        s.width,
        s.height,
        plan.passes.material,
    )?;
    fb.texture(
        "sub_tex",
        crate::compute::FLOAT,
        wgpu::TextureViewDimension::D2Array,
        false,
        &r.view(),
    );
    fb.account("subpixel geometry", r.target_bytes());
    fb.account("raster depth", r.depth_bytes());
    if let Some(albedo) = r.albedo_view() {
        fb.texture(
            "sub_alb_tex",
            crate::compute::FLOAT,
            wgpu::TextureViewDimension::D2Array,
            false,
            &albedo,
        );
        fb.account("subpixel albedo", r.target_bytes());
    }
    Ok(Some(r))
}

/// What the reconstruction's gates read besides geometry: the albedo of
/// shaded samples and traced subsamples (`+mat`), the subsamples' shadow
/// states (eq. 2) and their mirror hits' geometry and shadow states (§3.3).
fn gate_buffers(
    ctx: &GpuContext,
    fb: &mut Bindings,
    plan: &SubpixelPlan,
) -> Result<(), RenderError> {
    let (n64, lights) = (plan.n, plan.passes.layout.lights);
    // Hybrid SRAA's shaded albedo is the resolve's texture, its
    // subsamples' the raster pass's layers.
    if plan.passes.material && plan.passes.splits_layers {
        fb.storage(ctx, "albedo", "albedo_buf", "array<vec4<f32>>", n64 * 16)?;
        fb.storage(
            ctx,
            "subpixel albedo",
            "sub_albedo_buf",
            "array<vec4<f32>>",
            n64 * 64,
        )?;
    }
    if plan.passes.sub_shadows && lights > 0 {
        fb.storage(
            ctx,
            "subpixel shadow states",
            "sub_shadow_buf",
            "array<u32>",
            n64 * 16,
        )?;
    }
    if plan.passes.sub_secondary {
        fb.storage(
            ctx,
            "subpixel secondary geometry",
            "sub_geo2_buf",
            "array<subcone_Geometry>",
            n64 * 64,
        )?;
        if lights > 0 {
            fb.storage(
                ctx,
                "subpixel secondary shadow states",
                "sub_shadow2_buf",
                "array<u32>",
                n64 * 16,
            )?;
        }
    }
    Ok(())
}

/// The accessors of the optional shadow and secondary-hit buffers SRAA-RT's
/// shaders read (`triangles/sraa.wgsl`), triangles and SDF scenes alike:
/// real ones where `fb` binds the buffer, else reads of the CPU's initial
/// value.
pub(crate) fn shadow_and_secondary_accessors(fb: &Bindings) -> String {
    let no_secondary = "subcone_Geometry(vec3<f32>(0.0), bitcast<f32>(0x7fc00000u))";
    // (name, buffer, element type, elements per pixel, value when absent)
    [
        ("shadow", "shadow_buf", "u32", 1, "0u"),
        ("geo2", "geo2_buf", "subcone_Geometry", 1, no_secondary),
        ("shadow2", "shadow2_buf", "u32", 1, "0u"),
        ("sub_shadow", "sub_shadow_buf", "u32", 4, "0u"),
        (
            "sub_geo2",
            "sub_geo2_buf",
            "subcone_Geometry",
            4,
            no_secondary,
        ),
        ("sub_shadow2", "sub_shadow2_buf", "u32", 4, "0u"),
    ]
    .iter()
    .map(|&(name, var, ty, per, default)| accessors(fb, name, var, ty, per, default))
    .collect()
}

/// The accessors of SRAA-RT's shaded samples in its buffers `geo` and
/// `values` (triangles and SDF scenes alike; hybrid SRAA's are the
/// resolve's textures, `HybridResolve::shading_accessors`).
pub(crate) const SHADED_SAMPLE_ACCESSORS: &str =
    "fn get_geo(j: u32) -> subcone_Geometry { return geo[j]; }\n\
     fn put_geo(j: u32, g: subcone_Geometry) { geo[j] = g; }\n\
     fn get_value(j: u32, l: u32) -> vec3<f32> { return values[j * NL + l].xyz; }\n\
     fn put_value(j: u32, l: u32, v: vec3<f32>) { values[j * NL + l] = vec4<f32>(v, 0.0); }\n";

/// The WGSL header of `subpixel.wgsl` for the buffers bound in `fb`: the
/// plan's constants and an accessor pair per optional buffer (reads of the
/// CPU's initial value where it is absent). SRAA-RT's shaded samples are
/// buffers; hybrid SRAA's accessors of them, and of its shaded albedo, are
/// the resolve's (`HybridResolve::shading_accessors`).
fn subpixel_header(fb: &Bindings, plan: &SubpixelPlan) -> String {
    let (layout, rt, material) = (
        &plan.passes.layout,
        plan.passes.splits_layers,
        plan.passes.material,
    );
    let (nl, shadows, secondary_shading) = (
        layout.len(),
        plan.passes.shadows,
        plan.passes.secondary_shading,
    );
    let mut header = String::new();
    header += &format!(
        "const NL: u32 = {nl}u;\nconst LAYER_LIGHTS: u32 = {}u;\nconst SINGLE: bool = {};\n\
         const SECONDARY_LAYERS: bool = {};\nconst SHADOWS: bool = {shadows};\n\
         const SECONDARY_SHADING: bool = {secondary_shading};\nconst MATERIAL: bool = {material};\n",
        layout.lights, layout.single, layout.secondary
    );
    header += &shadow_and_secondary_accessors(fb);
    if rt {
        header += SHADED_SAMPLE_ACCESSORS;
        header += &accessors(fb, "albedo", "albedo_buf", "vec4<f32>", 1, "vec4<f32>(0.0)");
    }
    if !rt && material {
        header += raster::SUB_ALBEDO_ACCESSORS;
    } else {
        header += &accessors(
            fb,
            "sub_albedo",
            "sub_albedo_buf",
            "vec4<f32>",
            4,
            "vec4<f32>(0.0)",
        );
    }
    if rt {
        header += &accessors(
            fb,
            "sub_geo",
            "sub_geo_buf",
            "subcone_Geometry",
            4,
            "subcone_Geometry(vec3<f32>(0.0), subcone_inf())",
        );
    } else {
        header += raster::SUB_GEO_ACCESSORS;
    }
    header
}

/// The program of SRAA and SRAA-RT ([`subpixel`]): the frame buffers and
/// header of [`subpixel_bindings`], the subpixel entry points and, for
/// SRAA-RT (`rt`), its traced subsamples' (its resolve is
/// `subcone_passes::SraaPass`, [`resolve::BufferResolve`]).
fn subpixel_program<'a>(
    f: &Setup<'a>,
    fb: &Bindings,
    header: &str,
    rt: bool,
) -> Result<Program<'a>, RenderError> {
    let entries: &[&str] = if rt {
        &[SUBPIXEL_WGSL, GEOMETRY_WGSL]
    } else {
        &[SUBPIXEL_WGSL]
    };
    program(f.ctx, &f.scene, fb, header, entries)
}

/// SRAA (hybrid: raster subpixel geometry) and SRAA-RT (render.rs `subpixel`):
/// passes "shading", "geometry" and "antialiasing".
fn subpixel(f: &Setup) -> Result<Frame, RenderError> {
    let (ctx, s) = (f.ctx, f.job.settings);
    let n = s.width as usize * s.height as usize;
    let (fb, header, hybrid) = subpixel_bindings(f)?;
    let mut prog = subpixel_program(f, &fb, &header, hybrid.is_none())?;
    let shade = prog.pipeline("shade_main")?;
    let groups = workgroups(ctx, s)?;
    let mut timings = Vec::new();
    ctx.timed_pass("shading", &mut timings, |enc| {
        prog.dispatch(enc, &shade, groups)
    })?;
    let (color, extra) = match &hybrid {
        // Hybrid SRAA: the raster pass, then subcone_passes::SraaPass
        // (resolve.rs) over the raster layers and the shading pass's
        // textures.
        Some(h) => {
            ctx.timed_pass("geometry", &mut timings, |enc| h.raster.record(enc))?;
            let mut recorded = Ok(());
            ctx.timed_pass("antialiasing", &mut timings, |enc| {
                recorded = h.resolve.record(ctx, enc, &h.raster, groups);
            })?;
            recorded?;
            (FrameColor::Resolved(&h.resolve), h.resolve.stats.clone())
        }
        // SRAA-RT: the subsamples traced one dispatch per subsample, then
        // subcone_passes::SraaPass over the frame's buffers.
        None => {
            let geometry = prog.pipeline("geometry_main")?;
            let plan = SubpixelPlan::new(f);
            let resolve = resolve::BufferResolve::new(
                ctx,
                &f.job.method.sraa(),
                plan.passes.material,
                resolve::BufferLayers {
                    lights: plan.passes.layout.lights as u32,
                    secondary: plan.passes.layout.secondary,
                },
            )?;
            let subsamples = indices(ctx, "subsample indices", 4)?;
            let k = fb.get("subsample")?;
            ctx.timed_pass("geometry", &mut timings, |enc| {
                each_index(enc, &subsamples, k, |enc| {
                    prog.dispatch(enc, &geometry, groups)
                })
            })?;
            let mut recorded = Ok(());
            ctx.timed_pass("antialiasing", &mut timings, |enc| {
                recorded = resolve.record(ctx, enc, &fb, (s.width, s.height));
            })?;
            recorded?;
            (FrameColor::Buffer, vec![("subsample indices", 16)])
        }
    };
    let mut frame = finish(f, &fb, color, timings, &extra)?;
    if s.aovs {
        let (d, nn) = centre_geometry(f)?;
        frame.depth = Some(d);
        frame.normal = Some(nn);
        frame.samples_per_pixel = Some(vec![1.0; n]);
    }
    Ok(frame)
}

/// Four subsample geometries per pixel.
#[cfg(test)]
pub(crate) type SubGeometry = Vec<[Geometry; 4]>;

/// For tests: the four subpixel geometries of every pixel, from the raster
/// pass and from ray tracing (SRAA-RT's `geometry_main`),
/// `[pixel][subsample]`.
#[cfg(test)]
pub(crate) fn subpixel_geometry_both(
    ctx: &GpuContext,
    scene: &Scene,
    width: u32,
    height: u32,
) -> Result<(SubGeometry, SubGeometry), RenderError> {
    let s = RenderSettings::new(width, height);
    let method = Method::new(subcone_kernels::passes::Technique::SraaRt);
    let passes = subcone_kernels::passes::required_passes(method.technique(), scene.features())
        .map_err(|e| RenderError::Method(e.to_string()))?;
    let sg = bvh::scene_gpu(ctx, scene)?;
    let uniform = FrameUniform::new(scene, &sg, &scene.camera, &method, &s);
    let n = width as usize * height as usize;
    // Ray traced: SRAA-RT's shading and geometry passes.
    let job = Job {
        scene,
        camera: &scene.camera,
        method: &method,
        settings: &s,
        passes,
    };
    let f = Setup {
        ctx,
        job: &job,
        scene: scene_bindings(ctx, &sg, &uniform)?,
        sg: sg.clone(),
        uniform,
    };
    let (fb, header, _) = subpixel_bindings(&f)?;
    let mut prog = subpixel_program(&f, &fb, &header, true)?;
    let shade = prog.pipeline("shade_main")?;
    let geometry = prog.pipeline("geometry_main")?;
    let groups = workgroups(ctx, &s)?;
    let subsamples = indices(ctx, "subsample indices", 4)?;
    let k = fb.get("subsample")?;
    let mut t = Vec::new();
    ctx.timed_pass("shading", &mut t, |enc| prog.dispatch(enc, &shade, groups))?;
    ctx.timed_pass("geometry", &mut t, |enc| {
        each_index(enc, &subsamples, k, |enc| {
            prog.dispatch(enc, &geometry, groups)
        })
    })?;
    let traced: Vec<Geometry> = compute::read(ctx, fb.get("sub_geo_buf")?, 4 * n)?;
    // Rasterised.
    let r = raster::Raster::new(ctx, &sg, &uniform, width, height, false)?;
    ctx.timed_pass("geometry", &mut t, |enc| r.record(enc))?;
    let rastered = r.read(ctx)?;
    let group = |v: Vec<Geometry>| -> Vec<[Geometry; 4]> {
        v.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect()
    };
    Ok((group(rastered), group(traced)))
}
