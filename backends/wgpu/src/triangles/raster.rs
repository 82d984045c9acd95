//! Hybrid SRAA's geometry pass (§3.1): the four subsamples' G-buffers
//! rasterised with a jittered projection (`raster.wgsl`), so each rasterised
//! sample lies exactly where the ray-traced subsample does (pixel centre plus
//! `SUBPIXEL_OFFSETS[k]`). One render pass per subsample, into layer `k` of
//! an `Rgba32Float` array (normal, view depth) with a reversed-Z
//! `Depth32Float` buffer. With the material gate (`+mat`), a second colour
//! attachment of the same passes receives each subsample's albedo.

#[cfg(test)]
use subcone_kernels::sraa::Geometry;
use subcone_scene::RenderError;

use super::bvh::SceneGpu;
use super::FrameUniform;
use crate::compute::{self, Allocate};
use crate::context::{err, CacheKey, GpuContext};
use subcone_passes::bind::Bindings;

const RASTER_WGSL: &str = include_str!("raster.wgsl");

const TARGET: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// `get_sub_geo`/`put_sub_geo` over the rasterised layers (bound as
/// `sub_tex`): depth < 0 is a pixel nothing covered, a miss.
pub(crate) const SUB_GEO_ACCESSORS: &str = "
const HAS_SUB_GEO: bool = true;
fn get_sub_geo(j: u32, k: u32) -> subcone_Geometry {
    let t = textureLoad(sub_tex, vec2<i32>(i32(j % frame.width), i32(j / frame.width)), i32(k), 0);
    if t.w < 0.0 {
        return subcone_Geometry(vec3<f32>(0.0), subcone_inf());
    }
    return subcone_Geometry(t.xyz, t.w);
}
fn put_sub_geo(j: u32, k: u32, g: subcone_Geometry) { }
";

/// `get_sub_albedo`/`put_sub_albedo` over the rasterised albedo layers (bound
/// as `sub_alb_tex`, cleared to 0: a miss's albedo, as on the CPU).
pub(crate) const SUB_ALBEDO_ACCESSORS: &str = "
const HAS_SUB_ALBEDO: bool = true;
fn get_sub_albedo(j: u32, k: u32) -> vec4<f32> {
    return textureLoad(sub_alb_tex, vec2<i32>(i32(j % frame.width), i32(j / frame.width)), i32(k), 0);
}
fn put_sub_albedo(j: u32, k: u32, v: vec4<f32>) { }
";

/// The bind group of the raster pass: its constants and the scene's
/// triangles, attributes, materials and texels, read by both stages.
fn bindings(ctx: &GpuContext, sg: &SceneGpu, u: &FrameUniform) -> Result<Bindings, RenderError> {
    let mut b = Bindings::visible_in(0, wgpu::ShaderStages::VERTEX_FRAGMENT);
    b.uniform(ctx, "frame", "FrameUniform", u)?;
    sg.bind_surfaces(&mut b);
    Ok(b)
}

/// The G-buffer pipeline's cache key: its whole source and the variant.
#[derive(PartialEq, Eq, Hash)]
struct RasterPipelineKey {
    source: String,
    albedo: bool,
}

impl CacheKey for RasterPipelineKey {
    type Value = wgpu::RenderPipeline;
}

/// The G-buffer pipeline for the bind group `b` of [`bindings`], compiled
/// once per device (in the device's own cache: device ids repeat across
/// wgpu instances) and source; with `albedo`, the variant with the albedo
/// attachment.
fn pipeline(
    ctx: &GpuContext,
    b: &Bindings,
    layout: &wgpu::BindGroupLayout,
    albedo: bool,
) -> Result<wgpu::RenderPipeline, RenderError> {
    let source = [
        compute::PRELUDE,
        subcone_kernels::sraa::WGSL,
        super::FRAME_WGSL,
        super::ALBEDO_WGSL,
        RASTER_WGSL,
        &b.declarations(),
    ]
    .concat();
    let key = RasterPipelineKey { source, albedo };
    let p = ctx.cached_or_insert(key, |key| {
        let target = Some(wgpu::ColorTargetState {
            format: TARGET,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        });
        let targets = [target.clone(), target];
        let (entry, targets) = if albedo {
            ("fs_albedo", &targets[..])
        } else {
            ("fs_main", &targets[..1])
        };
        ctx.scoped("raster pipeline", || {
            let module = ctx
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("raster"),
                    source: wgpu::ShaderSource::Wgsl(key.source.as_str().into()),
                });
            let pl = ctx
                .device
                .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some("raster"),
                    bind_group_layouts: &[Some(layout)],
                    immediate_size: 0,
                });
            ctx.device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("raster"),
                    layout: Some(&pl),
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("vs_main"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: wgpu::PrimitiveState {
                        topology: wgpu::PrimitiveTopology::TriangleList,
                        cull_mode: None,
                        ..Default::default()
                    },
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format: DEPTH,
                        depth_write_enabled: Some(true),
                        depth_compare: Some(wgpu::CompareFunction::Greater),
                        stencil: Default::default(),
                        bias: Default::default(),
                    }),
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some(entry),
                        compilation_options: Default::default(),
                        targets,
                    }),
                    multiview_mask: None,
                    cache: None,
                })
        })
    })?;
    Ok((*p).clone())
}

/// The raster targets of one frame and what draws into them.
pub(crate) struct Raster {
    pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
    target: wgpu::Texture,
    layers: [wgpu::TextureView; 4],
    array: wgpu::TextureView,
    depth: wgpu::TextureView,
    /// `+mat`: the albedo layers and their array view.
    albedo: Option<([wgpu::TextureView; 4], wgpu::TextureView, wgpu::Texture)>,
    vertices: u32,
    width: u32,
    height: u32,
}

impl Raster {
    pub(crate) fn new(
        ctx: &GpuContext,
        sg: &SceneGpu,
        u: &FrameUniform,
        width: u32,
        height: u32,
        albedo: bool,
    ) -> Result<Self, RenderError> {
        ctx.check_texture_size(width, height)?;
        let vertices = sg
            .triangle_count
            .checked_mul(3)
            .ok_or_else(|| err("too many triangles to rasterise in one draw"))?;
        let b = bindings(ctx, sg, u)?;
        let layout = b.layout(&ctx.device, "raster");
        let pipeline = pipeline(ctx, &b, &layout, albedo)?;
        ctx.scoped("raster targets", || {
            let group = b.bind_group(&ctx.device, "raster", &layout);
            let size = wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 4,
            };
            let layers = |label: &'static str| {
                ctx.device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size,
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: TARGET,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::TEXTURE_BINDING
                        | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                })
            };
            let target = layers("subpixel geometry");
            let depth = ctx.frame_texture(
                "raster depth",
                (width, height),
                DEPTH,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            );
            let layer_of = |target: &wgpu::Texture, k: u32| {
                target.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("subpixel geometry layer"),
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: k,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            };
            let array_of = |target: &wgpu::Texture| {
                target.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("subpixel geometry"),
                    dimension: Some(wgpu::TextureViewDimension::D2Array),
                    ..Default::default()
                })
            };
            let layer = |k: u32| layer_of(&target, k);
            let array = array_of(&target);
            let albedo = albedo.then(|| {
                let t = layers("subpixel albedo");
                let l = |k: u32| layer_of(&t, k);
                ([l(0), l(1), l(2), l(3)], array_of(&t), t.clone())
            });
            Raster {
                pipeline: pipeline.clone(),
                group,
                layers: [layer(0), layer(1), layer(2), layer(3)],
                array,
                depth: depth.create_view(&Default::default()),
                albedo,
                target,
                vertices,
                width,
                height,
            }
        })
    }

    /// The four layers, for the reconstruction pass.
    pub(crate) fn view(&self) -> wgpu::TextureView {
        self.array.clone()
    }

    /// The four layers' texture (`Rgba32Float`, 4 layers: normal, view
    /// depth; negative depth where nothing was drawn).
    pub(crate) fn texture(&self) -> &wgpu::Texture {
        &self.target
    }

    /// The four albedo layers' texture (`+mat` only).
    pub(crate) fn albedo_texture(&self) -> Option<&wgpu::Texture> {
        self.albedo.as_ref().map(|(_, _, t)| t)
    }

    /// The four albedo layers (`+mat` only).
    pub(crate) fn albedo_view(&self) -> Option<wgpu::TextureView> {
        self.albedo.as_ref().map(|(_, a, _)| a.clone())
    }

    pub(crate) fn target_bytes(&self) -> usize {
        self.width as usize * self.height as usize * 4 * 16
    }

    pub(crate) fn depth_bytes(&self) -> usize {
        self.width as usize * self.height as usize * 4
    }

    /// One render pass per subsample `k`: instance `k` selects the jitter.
    pub(crate) fn record(&self, enc: &mut wgpu::CommandEncoder) {
        for (k, view) in self.layers.iter().enumerate() {
            let attachment = |view, a: f64| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.0,
                            g: 0.0,
                            b: 0.0,
                            a,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })
            };
            let mut attachments = vec![attachment(view, -1.0)];
            if let Some((albedo, _, _)) = &self.albedo {
                attachments.push(attachment(&albedo[k], 0.0));
            }
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("subpixel raster"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.group, &[]);
            pass.draw(0..self.vertices, k as u32..k as u32 + 1);
        }
    }

    /// The four layers on the CPU, `[pixel * 4 + k]` (tests).
    #[cfg(test)]
    pub(crate) fn read(&self, ctx: &GpuContext) -> Result<Vec<Geometry>, RenderError> {
        let (w, h) = (self.width as usize, self.height as usize);
        let row = (w * 16).div_ceil(256) * 256;
        let buf = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("raster read-back"),
            size: (row * h * 4) as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let mut t = Vec::new();
        ctx.timed_pass("copy", &mut t, |enc| {
            enc.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture: &self.target,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: &buf,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(row as u32),
                        rows_per_image: Some(h as u32),
                    },
                },
                wgpu::Extent3d {
                    width: self.width,
                    height: self.height,
                    depth_or_array_layers: 4,
                },
            )
        })?;
        let bytes = ctx.read_buffer(&buf, 0, (row * h * 4) as u64)?;
        let mut out = vec![Geometry::MISS; w * h * 4];
        for k in 0..4 {
            for y in 0..h {
                for x in 0..w {
                    let o = k * row * h + y * row + x * 16;
                    let v: [f32; 4] = bytemuck::pod_read_unaligned(&bytes[o..o + 16]);
                    out[(y * w + x) * 4 + k] = if v[3] < 0.0 {
                        Geometry::MISS
                    } else {
                        Geometry::new(glam::Vec3::new(v[0], v[1], v[2]), v[3])
                    };
                }
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use subcone_scene::builtin::builtin;

    use crate::context::GpuContext;

    /// Hybrid SRAA's premise: the rasterised subsamples are the ray-traced
    /// ones. At every interior subsample (its 3×3 neighbourhood of pixels hits
    /// one smooth surface: depths within 5 %, normals within a dot of 0.999;
    /// no silhouette or crease nearby), the raster and the ray
    /// give the same view depth within 1e-4 relative and normals within
    /// 1e-3 (dot > 0.999); at least 97 % of all subsamples agree that well.
    #[test]
    fn raster_subsamples_line_up_with_traced_subsamples() {
        let Some(ctx) =
            subcone_scene::conformance::or_skip("raster subsamples", GpuContext::shared())
        else {
            return;
        };
        for name in ["cornell", "checker"] {
            let scene = builtin(name).unwrap();
            let (w, h) = (48, 40);
            let (raster, traced) = super::super::subpixel_geometry_both(&ctx, &scene, w, h)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let mut good = 0;
            let mut interior = 0;
            let mut worst = 0.0f32;
            for y in 1..h as usize - 1 {
                for x in 1..w as usize - 1 {
                    let j = y * w as usize + x;
                    for k in 0..4 {
                        let (r, t) = (raster[j][k], traced[j][k]);
                        let agree = |a: f32, b: f32| {
                            (a == b) || ((a - b).abs() <= 1e-4 * a.abs().max(b.abs()))
                        };
                        let ok = agree(r.depth, t.depth)
                            && (r.depth.is_infinite() || r.normal.dot(t.normal) > 0.999);
                        if ok {
                            good += 1;
                        }
                        // Interior: the traced depth of the neighbouring pixels is
                        // smooth (no silhouette within a pixel).
                        let smooth = (0..9).all(|q| {
                            let jj = (y + q / 3 - 1) * w as usize + (x + q % 3 - 1);
                            let d = traced[jj][k].depth;
                            d.is_finite()
                                && t.depth.is_finite()
                                && (d - t.depth).abs() < 0.05 * t.depth
                                && traced[jj][k].normal.dot(t.normal) > 0.999
                        });
                        if smooth {
                            interior += 1;
                            let rel = (r.depth - t.depth).abs() / t.depth;
                            worst = worst.max(rel);
                            assert!(
                                rel <= 1e-4 && r.normal.dot(t.normal) > 0.999,
                                "{name}: pixel ({x}, {y}) subsample {k}: raster {r:?}, traced {t:?}"
                            );
                        }
                    }
                }
            }
            let total = (w as usize - 2) * (h as usize - 2) * 4;
            eprintln!(
                "{name}: {good}/{total} subsamples agree, {interior} interior, worst interior depth error {worst:e}"
            );
            assert!(interior > total / 10, "{name}: too few interior subsamples");
            assert!(
                good as f64 >= 0.97 * total as f64,
                "{name}: {good}/{total} agree"
            );
        }
    }
}
