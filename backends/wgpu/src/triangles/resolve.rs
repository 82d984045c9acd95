//! Hybrid SRAA's pass "antialiasing" (the paper's pass 2) through
//! [`subcone_passes::SraaPass`], the resolve a host renderer runs: the
//! rasterised subsamples are its `GeometryLayout::Packed` input (the
//! `Rgba32Float` layers of `raster.rs`), the shaded samples (the shading
//! pass's storage buffers) are copied into textures first, and the output
//! back into the frame's colour buffer (`resolve.wgsl`). SRAA-RT, whose
//! subsamples are traced into buffers, keeps its resolve in `sraa.wgsl`;
//! both run the one reconstruction loop, the kernels'
//! `sraa::RECONSTRUCT_WGSL`.

use std::sync::Arc;

use subcone_kernels::sraa::{ShadedPosition, SraaParams};
use subcone_passes::{
    AlbedoTextures, CentreGeometry, SraaInputs, SraaPass, SraaPassDesc, SubsampleGeometry,
};
use subcone_scene::RenderError;

use super::raster::Raster;
use crate::compute::{self, Access, Bindings, Program};
use crate::context::{err, GpuContext};

const RESOLVE_WGSL: &str = include_str!("resolve.wgsl");

const FLOAT4: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const FLOAT1: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// The pass on this device for `desc`, compiled once per device and
/// configuration.
fn pass(ctx: &GpuContext, desc: &SraaPassDesc) -> Result<Arc<SraaPass>, RenderError> {
    let key = compute::pipeline_key("sraa resolve", format!("{desc:?}"));
    if let Some(p) = ctx.cached::<SraaPass>(key) {
        return Ok(p);
    }
    let p = ctx
        .scoped("sraa resolve", || SraaPass::new(&ctx.device, desc))?
        .map_err(|e| err(format!("sraa resolve: {e}")))?;
    let p = Arc::new(p);
    ctx.cache_insert(key, p.clone());
    Ok(p)
}

/// The textures of one frame's resolve and what fills and empties them.
pub(crate) struct HybridResolve<'a> {
    sraa: Arc<SraaPass>,
    color: wgpu::Texture,
    centre: Option<(wgpu::Texture, wgpu::Texture)>,
    albedo: Option<wgpu::Texture>,
    output: wgpu::Texture,
    program: Program<'a>,
    to_textures: Arc<wgpu::ComputePipeline>,
    from_texture: Arc<wgpu::ComputePipeline>,
    /// Bytes of the textures, by name (for `FrameStats`).
    pub(crate) stats: Vec<(&'static str, usize)>,
}

impl<'a> HybridResolve<'a> {
    /// The resolve of a `width × height` frame with `params`, reading the
    /// shading pass's `geo`, `values` and (`+mat`) `albedo_buf` of `fb`.
    pub(crate) fn new(
        ctx: &'a GpuContext,
        fb: &Bindings,
        params: &SraaParams,
        material: bool,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        let desc = SraaPassDesc::packed(*params)
            .with_albedo_gate(material)
            .with_output_format(FLOAT4);
        let sraa = pass(ctx, &desc)?;
        let centre = params.shaded_position() == ShadedPosition::Centre;
        let texture = |label: &'static str, format, usage| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING;
        let (color, centre, albedo, output) = ctx.scoped("sraa resolve textures", || {
            (
                texture("resolve colour", FLOAT4, usage),
                centre.then(|| {
                    (
                        texture("resolve centre depth", FLOAT1, usage),
                        texture("resolve centre normal", FLOAT4, usage),
                    )
                }),
                material.then(|| texture("resolve albedo", FLOAT4, usage)),
                texture("resolve output", FLOAT4, usage),
            )
        })?;
        let px = width as usize * height as usize;
        let mut stats = vec![("resolve colour", px * 16), ("resolve output", px * 16)];
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let mut b = Bindings::new(0);
        b.buffer(
            "geo",
            "array<subcone_Geometry>",
            Access::Read,
            fb.get("geo")?,
        );
        b.buffer(
            "values",
            "array<vec4<f32>>",
            Access::Read,
            fb.get("values")?,
        );
        b.storage_texture("res_color", FLOAT4, "rgba32float", view(&color));
        let mut header = String::new();
        if let Some((d, n)) = &centre {
            b.storage_texture("res_centre_depth", FLOAT1, "r32float", view(d));
            b.storage_texture("res_centre_normal", FLOAT4, "rgba32float", view(n));
            stats.push(("resolve centre geometry", px * 20));
            header += "fn put_centre(p: vec2<i32>, j: u32) {\n\
                       textureStore(res_centre_depth, p, vec4<f32>(geo[j].depth, 0.0, 0.0, 0.0));\n\
                       textureStore(res_centre_normal, p, vec4<f32>(geo[j].normal, 0.0));\n}\n";
        } else {
            header += "fn put_centre(p: vec2<i32>, j: u32) { }\n";
        }
        if let Some(a) = &albedo {
            b.buffer(
                "albedo_buf",
                "array<vec4<f32>>",
                Access::Read,
                fb.get("albedo_buf")?,
            );
            b.storage_texture("res_albedo", FLOAT4, "rgba32float", view(a));
            stats.push(("resolve albedo", px * 16));
            header += "fn put_albedo(p: vec2<i32>, j: u32) { textureStore(res_albedo, p, albedo_buf[j]); }\n";
        } else {
            header += "fn put_albedo(p: vec2<i32>, j: u32) { }\n";
        }
        b.texture_2d("res_output", view(&output));
        b.buffer(
            "color",
            "array<vec4<f32>>",
            Access::ReadWrite,
            fb.get("color")?,
        );
        let mut program =
            Program::new(ctx, "sraa resolve copies", &[&header, RESOLVE_WGSL], &[&b])?;
        let to_textures = program.pipeline("to_textures_main")?;
        let from_texture = program.pipeline("from_texture_main")?;
        Ok(HybridResolve {
            sraa,
            color,
            centre,
            albedo,
            output,
            program,
            to_textures,
            from_texture,
            stats,
        })
    }

    /// Record the copies in and out and the resolve, reading the raster
    /// pass's layers.
    pub(crate) fn record(
        &self,
        ctx: &GpuContext,
        enc: &mut wgpu::CommandEncoder,
        raster: &Raster,
        groups: (u32, u32),
    ) -> Result<(), RenderError> {
        self.program.dispatch(enc, &self.to_textures, groups);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let packed = view(raster.texture());
        let centre = self.centre.as_ref().map(|(d, n)| (view(d), view(n)));
        let albedo = match (&self.albedo, raster.albedo_texture()) {
            (Some(shaded), Some(subsamples)) => Some((view(shaded), view(subsamples))),
            _ => None,
        };
        let (color, output) = (view(&self.color), view(&self.output));
        self.sraa
            .encode(
                &ctx.device,
                &ctx.queue,
                enc,
                &SraaInputs {
                    geometry: SubsampleGeometry::Packed(&packed),
                    // Linear view depth: no projection is read.
                    projection: [[0.0; 4]; 4],
                    centre: centre
                        .as_ref()
                        .map(|(depth, normal)| CentreGeometry { depth, normal }),
                    color: &color,
                    shadows: None,
                    albedo: albedo
                        .as_ref()
                        .map(|(shaded, subsamples)| AlbedoTextures { shaded, subsamples }),
                    secondary: None,
                    output: &output,
                },
                None,
            )
            .map_err(|e| err(format!("sraa resolve: {e}")))?;
        // This frame's textures are its own: the pass need not keep them.
        self.sraa.release_views();
        self.program.dispatch(enc, &self.from_texture, groups);
        Ok(())
    }
}
