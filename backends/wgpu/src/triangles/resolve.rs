//! Hybrid SRAA's pass "antialiasing" (the paper's pass 2) through
//! [`subcone_passes::SraaPass`], the resolve a host renderer runs, with
//! no copy on either side: the rasterised subsamples are its
//! `GeometryLayout::Packed` input (the `Rgba32Float` layers of `raster.rs`),
//! the shading pass writes the shaded colour, the centre geometry (when the
//! preset shades the pixel centre) and the albedo (`+mat`) straight into the
//! storage textures the resolve reads ([`HybridResolve::bind_shading_targets`]
//! and [`HybridResolve::shading_accessors`]), and the frame is read back from
//! the resolve's output texture. No buffer holds what a texture holds. Only
//! a post-process after the resolve (FXAA forced onto an SRAA frame), which
//! reads a colour buffer, gets the output copied into one
//! (`resolve.wgsl`). SRAA-RT, whose subsamples are traced into buffers
//! (on triangle and SDF scenes), runs the same pass on those buffers
//! ([`BufferResolve`], `SraaPass::encode_buffers`).

use std::sync::Arc;

use glam::Vec3;
use subcone_kernels::sraa::{ShadedPosition, SraaParams};
use subcone_passes::{
    CentreGeometry, Samples, SecondaryBuffers, SraaBuffers, SraaInputs, SraaPass, SraaPassDesc,
    SubsampleGeometry,
};
use subcone_scene::RenderError;

use super::raster::Raster;
use crate::compute::{Allocate, Program};
use crate::context::{err, CacheKey, GpuContext};
use subcone_passes::bind::Bindings;

const RESOLVE_WGSL: &str = include_str!("resolve.wgsl");

const FLOAT4: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const FLOAT1: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// The centre normals' format. Half floats keep the frame within the memory
/// of the buffers it replaces (the depth has a texture of its own, so a
/// 32-bit normal would cost 20 bytes a pixel where the buffer took 16), and
/// cost the weights next to nothing: a component rounds by at most 2⁻¹², the
/// resolve renormalises, and eq. 1 reads `1 − cos`, second order in that
/// error (≤ 9·10⁻⁸ between equal normals, below `NORMAL_COS_SNAP`, so they
/// still weigh 1).
const HALF4: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// A resolve's cache key: what its descriptor is built from
/// ([`SraaPassKey::desc`]), the parameters by their bits.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct SraaPassKey {
    params: [u32; size_of::<SraaParams>() / 4],
    material: bool,
    /// SRAA-RT's buffers ([`BufferLayers`]), or hybrid SRAA's textures.
    buffers: Option<BufferLayers>,
}

/// The layers of SRAA-RT's shading buffers (`passes::LayerLayout`): gated
/// lights and secondary shading.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct BufferLayers {
    pub(crate) lights: u32,
    pub(crate) secondary: bool,
}

impl SraaPassKey {
    /// Hybrid SRAA's: the packed-geometry resolve with the albedo gate
    /// where `material`, writing [`FLOAT4`]. SRAA-RT's: the buffer resolve
    /// with its layers.
    fn desc(&self) -> SraaPassDesc {
        let params = bytemuck::cast(self.params);
        match self.buffers {
            None => SraaPassDesc::packed(params).with_output_format(FLOAT4),
            Some(l) => SraaPassDesc::buffers(params)
                .with_lights(l.lights)
                .with_secondary(l.secondary),
        }
        .with_albedo_gate(self.material)
    }
}

impl CacheKey for SraaPassKey {
    type Value = SraaPass;
}

/// The pass on this device for `key`, compiled once per device and
/// configuration.
fn pass(ctx: &GpuContext, key: SraaPassKey) -> Result<Arc<SraaPass>, RenderError> {
    ctx.cached_or_insert(key, |key| {
        ctx.scoped("sraa resolve", || SraaPass::new(&ctx.device, &key.desc()))?
            .map_err(|e| err(format!("sraa resolve: {e}")))
    })
}

/// The copy of the output into a colour buffer, for a post-process that
/// follows the resolve.
struct PostProcessInput<'a> {
    program: Program<'a>,
    pipeline: Arc<wgpu::ComputePipeline>,
    color: wgpu::Buffer,
}

/// The textures of one frame's resolve: what the shading pass writes and
/// the resolve reads, and the resolve's output, which is the frame.
pub(crate) struct HybridResolve<'a> {
    sraa: Arc<SraaPass>,
    color: wgpu::Texture,
    centre: Option<(wgpu::Texture, wgpu::Texture)>,
    albedo: Option<wgpu::Texture>,
    output: wgpu::Texture,
    post: Option<PostProcessInput<'a>>,
    width: u32,
    height: u32,
    /// Bytes of the textures (and the post-process's colour buffer), by
    /// name (for `FrameStats`).
    pub(crate) stats: Vec<(&'static str, usize)>,
}

impl<'a> HybridResolve<'a> {
    /// The resolve of a `width × height` frame with `params`; with
    /// `post_process`, the colour buffer a post-process reads from the
    /// output ([`Self::post_process_input`]).
    pub(crate) fn new(
        ctx: &'a GpuContext,
        params: &SraaParams,
        material: bool,
        post_process: bool,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        ctx.check_texture_size(width, height)?;
        let key = SraaPassKey {
            params: bytemuck::cast(*params),
            material,
            buffers: None,
        };
        let sraa = pass(ctx, key)?;
        let centre = params.shaded_position() == ShadedPosition::Centre;
        let texture =
            |label, format, usage| ctx.frame_texture(label, (width, height), format, usage);
        // Written by the shading pass, read by the resolve.
        let shaded = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING;
        // Written by the resolve, read back (copied out).
        let out = wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        let (color, centre, albedo, output) = ctx.scoped("sraa resolve textures", || {
            (
                texture("shaded colour", FLOAT4, shaded),
                centre.then(|| {
                    (
                        texture("shaded centre depth", FLOAT1, shaded),
                        texture("shaded centre normal", HALF4, shaded),
                    )
                }),
                material.then(|| texture("shaded albedo", FLOAT4, shaded)),
                texture("sraa output", FLOAT4, out),
            )
        })?;
        let px = width as usize * height as usize;
        let mut stats = vec![("shaded colour", px * 16)];
        if centre.is_some() {
            stats.push(("shaded centre geometry", px * 12));
        }
        if albedo.is_some() {
            stats.push(("shaded albedo", px * 16));
        }
        stats.push(("sraa output", px * 16));
        let post = if post_process {
            let mut b = Bindings::new(0);
            b.texture(
                "sraa_output",
                crate::compute::FLOAT,
                wgpu::TextureViewDimension::D2,
                false,
                &view(&output),
            );
            b.storage(ctx, "color", "color", "array<vec4<f32>>", px as u64 * 16)?;
            stats.extend_from_slice(b.accounts());
            let mut program = Program::new(ctx, "sraa output copy", &[RESOLVE_WGSL], &[&b])?;
            let pipeline = program.pipeline("output_to_buffer_main")?;
            let color = b.get("color")?.clone();
            Some(PostProcessInput {
                program,
                pipeline,
                color,
            })
        } else {
            None
        };
        Ok(HybridResolve {
            sraa,
            color,
            centre,
            albedo,
            output,
            post,
            width,
            height,
            stats,
        })
    }

    /// Bind what the shading pass writes, as storage textures of the frame
    /// group `fb`: `shaded_color`, and as configured `shaded_centre_depth`,
    /// `shaded_centre_normal` and `shaded_albedo`.
    pub(crate) fn bind_shading_targets(&self, fb: &mut Bindings) -> Result<(), RenderError> {
        fb.storage_texture("shaded_color", FLOAT4, &view(&self.color))
            .map_err(crate::compute::bind_err)?;
        if let Some((d, n)) = &self.centre {
            fb.storage_texture("shaded_centre_depth", FLOAT1, &view(d))
                .map_err(crate::compute::bind_err)?;
            fb.storage_texture("shaded_centre_normal", HALF4, &view(n))
                .map_err(crate::compute::bind_err)?;
        }
        if let Some(a) = &self.albedo {
            fb.storage_texture("shaded_albedo", FLOAT4, &view(a))
                .map_err(crate::compute::bind_err)?;
        }
        Ok(())
    }

    /// The shading pass's accessors (`subpixel.wgsl`) over those textures:
    /// `put_value` (hybrid SRAA shades one layer, the final colour),
    /// `put_geo` (the centre geometry; nothing when the preset shades
    /// subsample 0, whose geometry the resolve takes from the raster
    /// layers) and `put_albedo`. The shading pass only writes them; the
    /// reads, which only SRAA-RT's passes make, return the CPU's initial
    /// values.
    pub(crate) fn shading_accessors(&self) -> String {
        let mut s = String::from(
            "fn shaded_texel(j: u32) -> vec2<i32> {\n\
             \x20   return vec2<i32>(i32(j % frame.width), i32(j / frame.width));\n}\n\
             fn put_value(j: u32, l: u32, v: vec3<f32>) {\n\
             \x20   textureStore(shaded_color, shaded_texel(j), vec4<f32>(v, 0.0));\n}\n\
             fn get_value(j: u32, l: u32) -> vec3<f32> { return vec3<f32>(0.0); }\n\
             fn get_geo(j: u32) -> subcone_Geometry {\n\
             \x20   return subcone_Geometry(vec3<f32>(0.0), subcone_inf());\n}\n",
        );
        if self.centre.is_some() {
            s += "fn put_geo(j: u32, g: subcone_Geometry) {\n\
                  \x20   textureStore(shaded_centre_depth, shaded_texel(j), vec4<f32>(g.depth, 0.0, 0.0, 0.0));\n\
                  \x20   textureStore(shaded_centre_normal, shaded_texel(j), vec4<f32>(g.normal, 0.0));\n}\n";
        } else {
            s += "fn put_geo(j: u32, g: subcone_Geometry) { }\n";
        }
        if self.albedo.is_some() {
            s += "const HAS_ALBEDO: bool = true;\n\
                  fn put_albedo(j: u32, v: vec4<f32>) { textureStore(shaded_albedo, shaded_texel(j), v); }\n";
        } else {
            s += "const HAS_ALBEDO: bool = false;\n\
                  fn put_albedo(j: u32, v: vec4<f32>) { }\n";
        }
        s += "fn get_albedo(j: u32) -> vec4<f32> { return vec4<f32>(0.0); }\n";
        s
    }

    /// Record the resolve, reading the raster pass's layers and the shading
    /// pass's textures; then, for a post-process, the copy of the output
    /// into its colour buffer.
    pub(crate) fn record(
        &self,
        ctx: &GpuContext,
        enc: &mut wgpu::CommandEncoder,
        raster: &Raster,
        groups: (u32, u32),
    ) -> Result<(), RenderError> {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let packed = view(raster.texture());
        let centre = self.centre.as_ref().map(|(d, n)| (view(d), view(n)));
        let albedo = match (&self.albedo, raster.albedo_texture()) {
            (Some(shaded), Some(subsamples)) => Some(Samples {
                shaded: view(shaded),
                subsamples: view(subsamples),
            }),
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
                    albedo: albedo.as_ref().map(|a| Samples {
                        shaded: &a.shaded,
                        subsamples: &a.subsamples,
                    }),
                    secondary: None,
                    output: &output,
                },
                None,
            )
            .map_err(|e| err(format!("sraa resolve: {e}")))?;
        // This frame's textures are its own: the pass need not keep them.
        self.sraa.release_views();
        if let Some(p) = &self.post {
            p.program.dispatch(enc, &p.pipeline, groups);
        }
        Ok(())
    }

    /// The colour buffer holding the output, when built for a post-process.
    pub(crate) fn post_process_input(&self) -> Option<&wgpu::Buffer> {
        self.post.as_ref().map(|p| &p.color)
    }

    /// The output on the CPU, row-major: one copy from the texture into a
    /// mappable buffer (rows padded to wgpu's 256-byte alignment), as
    /// `GpuContext::read_buffer` does from a buffer.
    pub(crate) fn read_output(&self, ctx: &GpuContext) -> Result<Vec<Vec3>, RenderError> {
        let (w, h) = (self.width as usize, self.height as usize);
        let row = (w * 16).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as usize);
        let size = (row * h) as u64;
        let what = "sraa output read-back";
        ctx.check_buffer_size(what, size)?;
        let copy = |encoder: &mut wgpu::CommandEncoder, staging: &wgpu::Buffer| {
            encoder.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture: &self.output,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: staging,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(row as u32),
                        rows_per_image: Some(self.height),
                    },
                },
                self.output.size(),
            );
        };
        ctx.read_back(what, size, copy, |bytes| {
            let mut color = Vec::with_capacity(w * h);
            for r in bytes.chunks(row).take(h) {
                color.extend(r[..w * 16].chunks_exact(16).map(|texel| {
                    let c: [f32; 4] = bytemuck::pod_read_unaligned(texel);
                    Vec3::new(c[0], c[1], c[2])
                }));
            }
            color
        })
    }
}

fn view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&Default::default())
}

/// SRAA-RT's pass "antialiasing" (the paper's pass 2) through
/// [`subcone_passes::SraaPass`] on the frame's storage buffers
/// (`GeometryLayout::Buffers`), triangles and SDF scenes alike: the shaded
/// samples' geometry `geo` and layers `values`, the traced subsamples
/// `sub_geo_buf`, and as planned their shadow bits, mirror hits and albedo,
/// into the colour buffer `color`. The buffers are bound under these names
/// in the frame's group.
pub(crate) struct BufferResolve {
    sraa: Arc<SraaPass>,
}

impl BufferResolve {
    /// The resolve of `params` over `layers`, with the albedo gate where
    /// `material`; compiled once per device and configuration, so build
    /// it before timing the pass.
    pub(crate) fn new(
        ctx: &GpuContext,
        params: &SraaParams,
        material: bool,
        layers: BufferLayers,
    ) -> Result<Self, RenderError> {
        let key = SraaPassKey {
            params: bytemuck::cast(*params),
            material,
            buffers: Some(layers),
        };
        Ok(BufferResolve {
            sraa: pass(ctx, key)?,
        })
    }

    /// Record the resolve of the `width × height` frame whose buffers `fb`
    /// binds.
    pub(crate) fn record(
        &self,
        ctx: &GpuContext,
        enc: &mut wgpu::CommandEncoder,
        fb: &Bindings,
        (width, height): (u32, u32),
    ) -> Result<(), RenderError> {
        let pair = |shaded: &str, subsamples: &str| match (
            fb.buffer_named(shaded),
            fb.buffer_named(subsamples),
        ) {
            (Some(shaded), Some(subsamples)) => Ok(Some(Samples { shaded, subsamples })),
            (None, None) => Ok(None),
            _ => Err(err(format!(
                "sraa-rt resolve: `{shaded}` and `{subsamples}` are bound apart"
            ))),
        };
        let secondary = pair("geo2_buf", "sub_geo2_buf")?.map(|geometry| {
            Ok::<_, RenderError>(SecondaryBuffers {
                geometry,
                shadows: pair("shadow2_buf", "sub_shadow2_buf")?,
            })
        });
        let inputs = SraaBuffers {
            size: (width, height),
            geometry: Samples {
                shaded: fb.get("geo")?,
                subsamples: fb.get("sub_geo_buf")?,
            },
            color: fb.get("values")?,
            shadows: pair("shadow_buf", "sub_shadow_buf")?,
            albedo: pair("albedo_buf", "sub_albedo_buf")?,
            secondary: secondary.transpose()?,
            output: fb.get("color")?,
        };
        self.sraa
            .encode_buffers(&ctx.device, &ctx.queue, enc, &inputs, None)
            .map_err(|e| err(format!("sraa-rt resolve: {e}")))?;
        // This frame's buffers are its own: the pass need not keep them.
        self.sraa.release_views();
        Ok(())
    }
}
