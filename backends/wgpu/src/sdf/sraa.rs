//! SRAA for ray tracing (Chiu et al., §3) on SDF scenes: the three passes of
//! `subcone_cpu::sphere::SdfView::sraa_rt`, every ray sphere traced.
//!
//! Pass "shading" (`sdf_sraa_shade`, `sraa.wgsl`): one sample per pixel at
//! the preset's shaded offset, sphere traced and shaded as NoAA shades (hard
//! shadows through the field, ambient occlusion when asked for), kept in
//! layers: the shadow-independent part and one per light with its shadow
//! state (§3.2). Pass "geometry" (`sdf_sraa_geometry`, the paper's pass 1):
//! the subsamples sphere traced for geometry (normal facing the ray, view
//! depth) and, with lights, their shadow states by subpixel shadow rays (eq.
//! 2's gate, cast only where the shaded samples around disagree). Pass
//! "antialiasing" (pass 2): `subcone_passes::SraaPass` over these buffers,
//! as on triangle scenes (`triangles::resolve::BufferResolve`): the
//! kernels' reconstruction loop (`subcone_kernels::sraa::RECONSTRUCT_WGSL`:
//! eq. 1 and eq. 2's weights, written once) and `subcone_resolve_pixel`.
//! SDF scenes have no mirrors (the plan refuses them), so there are no
//! secondary passes.

use subcone_kernels::passes::{LayerLayout, Passes, Technique, MAX_LIGHTS};
use subcone_scene::{Frame, PassTiming, RayCounts, RenderError};
use subcone_sdf::wgsl::WgslField;

use super::{
    centre_aovs, colour_frame, host_bindings, kernels, march, scatter_table, shading, SdfFrame,
    Totals, ASAP_BATCH, TRACE_WGSL, WORKGROUP,
};
use crate::compute::{self, Allocate, Program};
use crate::context::GpuContext;
use crate::triangles::resolve::{BufferLayers, BufferResolve};
use crate::triangles::{accessors, shadow_and_secondary_accessors, SHADED_SAMPLE_ACCESSORS};
use crate::Job;
use subcone_passes::bind::Bindings;

/// This module's entry points (`sdf_sraa_shade`, `sdf_sraa_geometry`).
const SDF_SRAA_WGSL: &str = include_str!("sraa.wgsl");

/// The WGSL header of the frame's buffers (as `triangles::subpixel_header`
/// writes it for SRAA-RT on triangles): the layout constants and an accessor
/// pair per optional buffer, reads of the CPU's initial value where absent.
fn header(b: &Bindings, layout: &LayerLayout, shadows: bool) -> String {
    let mut h = format!(
        "const NL: u32 = {}u;\nconst LAYER_LIGHTS: u32 = {}u;\nconst SINGLE: bool = false;\n\
         const SECONDARY_LAYERS: bool = false;\nconst SHADOWS: bool = {shadows};\n\
         const MATERIAL: bool = false;\n",
        layout.len(),
        layout.lights
    );
    h += &shadow_and_secondary_accessors(b);
    for (name, var, ty, per, default) in [
        ("albedo", "albedo_buf", "vec4<f32>", 1, "vec4<f32>(0.0)"),
        (
            "sub_albedo",
            "sub_albedo_buf",
            "vec4<f32>",
            4,
            "vec4<f32>(0.0)",
        ),
        (
            "sub_geo",
            "sub_geo_buf",
            "subcone_Geometry",
            4,
            "subcone_Geometry(vec3<f32>(0.0), subcone_inf())",
        ),
    ] {
        h += &accessors(b, name, var, ty, per, default);
    }
    h += SHADED_SAMPLE_ACCESSORS;
    h
}

/// SRAA-RT on an SDF scene: passes "shading", "geometry" and
/// "antialiasing" (see the module's documentation).
pub(crate) fn render(ctx: &GpuContext, job: &Job) -> Result<Frame, RenderError> {
    let Job {
        scene,
        camera,
        method,
        settings,
        passes,
    } = *job;
    let (g, (max_distance, max_steps)) = march(job)?;
    let (w, h) = (settings.width, settings.height);
    let n = w as u64 * h as u64;
    let lights = scene.lights.len().min(MAX_LIGHTS);
    let layout = LayerLayout::new(Technique::SraaRt, passes, lights);
    let shadows = passes.contains(Passes::SHADOW);
    let sub_shadows = passes.contains(Passes::SUBPIXEL_SHADOW) && layout.lights > 0;
    let params = method.ctss_params(camera, h, max_distance, max_steps);
    let groups = compute::workgroups(ctx, "SDF", w, h, WORKGROUP)?;
    for (what, bytes) in [
        ("the colour buffer", n * 16),
        ("the shading layers", n * layout.len() as u64 * 16),
        ("the subpixel geometry", n * 64),
    ] {
        ctx.check_buffer_size(what, bytes)?;
    }

    let frame = SdfFrame::new(job, (max_distance, max_steps));
    let field = subcone_sdf::wgsl::WgslField::compile(&g.root);
    let table = scatter_table(ctx, &field)?;
    let mut b = host_bindings(ctx, 0, &frame, &params, table.as_deref())?;
    b.uniform(ctx, "sraa", "subcone_SraaParams", &method.sraa())?;
    frame_buffers(ctx, &mut b, &layout, sub_shadows, n)?;

    let shading = shading::shading_wgsl(&scene.materials, &scene.lights, shadows)?;
    let mut program = sraa_program(ctx, job, &b, (&layout, shadows), (&field, &shading))?;
    let shade = program.pipeline("sdf_sraa_shade")?;
    let geometry = program.pipeline("sdf_sraa_geometry")?;
    let resolve = BufferResolve::new(
        ctx,
        &method.sraa(),
        false,
        BufferLayers {
            lights: layout.lights as u32,
            secondary: false,
        },
    )?;
    let mut timings: Vec<PassTiming> = Vec::new();
    ctx.timed_pass("shading", &mut timings, |enc| {
        program.dispatch(enc, &shade, groups)
    })?;
    ctx.timed_pass("geometry", &mut timings, |enc| {
        program.dispatch(enc, &geometry, groups)
    })?;
    let mut recorded = Ok(());
    ctx.timed_pass("antialiasing", &mut timings, |enc| {
        recorded = resolve.record(ctx, enc, &b, (w, h));
    })?;
    recorded?;

    let pixels = n as usize;
    let color_px: Vec<[f32; 4]> = compute::read(ctx, b.get("color")?, pixels)?;
    let count_px: Vec<[u32; 4]> = compute::read(ctx, b.get("counts_out")?, pixels)?;
    let mut out = colour_frame(w, h, &color_px);
    let totals = Totals::of(&count_px, 1);
    let mut buffers = b.accounts().to_vec();
    if settings.aovs {
        // Depth and normal through each pixel centre (not timed, as on the
        // CPU), over a host group of its own.
        let host = host_bindings(ctx, 1, &frame, &params, table.as_deref())?;
        centre_aovs(
            ctx,
            job,
            (max_distance, max_steps),
            (&field, &shading),
            &host,
            &mut out,
        )?;
        out.samples_per_pixel = Some(vec![1.0; pixels]);
        buffers.push(("aovs", pixels * 16));
    }
    if table.is_some() {
        buffers.push(("sdf scatter table", field.data.len() * 16));
    }
    let rays = RayCounts {
        primary: n,
        geometry: 3 * n,
        ..Default::default()
    };
    out.stats = totals.stats(passes, timings, buffers, rays, 0);
    Ok(out)
}

/// The frame's buffers of the three passes, for `n` pixels, bound in `b`:
/// colours and counts, the shaded samples' geometry and shading layers
/// (`layout`) and, with lights, shadow states, and the subsamples' geometry
/// and, with `sub_shadows`, their shadow states.
fn frame_buffers(
    ctx: &GpuContext,
    b: &mut Bindings,
    layout: &LayerLayout,
    sub_shadows: bool,
    n: u64,
) -> Result<(), RenderError> {
    b.storage(ctx, "color", "color", "array<vec4<f32>>", n * 16)?;
    b.storage(ctx, "counts", "counts_out", "array<vec4<u32>>", n * 16)?;
    b.storage(ctx, "geometry", "geo", "array<subcone_Geometry>", n * 16)?;
    b.storage(
        ctx,
        "shading layers",
        "values",
        "array<vec4<f32>>",
        n * layout.len() as u64 * 16,
    )?;
    if layout.lights > 0 {
        b.storage(ctx, "shadow states", "shadow_buf", "array<u32>", n * 4)?;
    }
    b.storage(
        ctx,
        "subpixel geometry",
        "sub_geo_buf",
        "array<subcone_Geometry>",
        n * 64,
    )?;
    if sub_shadows {
        b.storage(
            ctx,
            "subpixel shadow states",
            "sub_shadow_buf",
            "array<u32>",
            n * 16,
        )?;
    }
    Ok(())
}

/// The program of passes "shading" and "geometry" over the frame's
/// bindings `b`: the kernels, the compiled `field` and its `shading`, the
/// lights' incident radiance, the sphere trace's hooks, the header of the
/// buffers (`layout`, `shadows`) and this module's entry points.
fn sraa_program<'c>(
    ctx: &'c GpuContext,
    job: &Job,
    b: &Bindings,
    (layout, shadows): (&LayerLayout, bool),
    (field, shading): (&WgslField, &str),
) -> Result<Program<'c>, RenderError> {
    let incident = shading::light_incident_wgsl(&job.scene.lights);
    let pending = format!("const subcone_CTSS_BATCH: u32 = {ASAP_BATCH}u;\n");
    let head = header(b, layout, shadows);
    let mut sources: Vec<&str> = kernels();
    sources.extend([
        subcone_kernels::sraa::WGSL,
        field.source.as_str(),
        shading,
        &incident,
        &pending,
        subcone_passes::SPHERE_TRACE_HOOK,
        TRACE_WGSL,
        head.as_str(),
        SDF_SRAA_WGSL,
    ]);
    Program::new(ctx, "sdf sraa-rt", &sources, &[b])
}
