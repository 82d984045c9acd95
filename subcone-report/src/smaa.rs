//! SMAA 1x, the third-party morphological baseline, as a post-process on an
//! 8-bit sRGB frame.
//!
//! The report's `smaa` row is [SMAA](http://www.iryoku.com/smaa) applied by the
//! [`smaa`] crate (0.21, built on the wgpu 30 of our backend) to the NoAA frame
//! of whichever backend rendered it. That crate has a single mode, SMAA 1x with
//! the reference shader's `SMAA_PRESET_HIGH` (luma edge detection, threshold
//! 0.1, 16 search steps, 8 diagonal steps, corner rounding 25 %): that is the
//! SMAA this row measures. It is not one of our kernels, so it has no CPU twin
//! and no WGSL of ours; it always runs on the GPU, through the wgpu backend's
//! shared device ([`GpuContext::shared`]).
//!
//! One frame: the RGB bytes are padded to RGBA and uploaded into a texture, a
//! fullscreen triangle copies it texel for texel into the SMAA target's colour
//! buffer (that buffer is a render attachment only, so a copy command cannot
//! write it), dropping the [`smaa::SmaaFrame`] runs SMAA's three passes (edge
//! detection, blending weights, neighbourhood blending) into our output
//! texture, and the output is copied to a buffer and read back.
//!
//! # Formats: everything `Rgba8Unorm`
//!
//! The input bytes are already sRGB-encoded (the displayed image), and every
//! texture here is `Rgba8Unorm`, so the shaders see those encoded values
//! unchanged and the bytes come back as SMAA wrote them, with no decode or
//! encode on the way. The crate binds one view of its colour buffer to both
//! edge detection and neighbourhood blending, so one format has to serve both,
//! and the reference shader (`SMAA.hlsl`, notes 5 and the luma edge detection
//! notice) says edge detection *requires* gamma-encoded input, while an sRGB
//! read in the blending pass is optional ("the technique will work anyway, but
//! will perform antialiasing in gamma space"). `Rgba8UnormSrgb` would blend
//! in linear light but detect edges on linear luma, where the 0.1 threshold
//! misses most edges between dark colours (sRGB 50 against 90 is a linear step
//! of 0.07: on lavapipe a 50/90 staircase comes back untouched, while
//! `Rgba8Unorm` blends 92 of its pixels). `Rgba8Unorm` keeps SMAA's edges and
//! blends in gamma space, the reference's documented fallback and what a game
//! without an sRGB swapchain shows.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use smaa::{SmaaMode, SmaaTarget};
use subcone_scene::{PassTiming, TimingSource};
use subcone_wgpu::GpuContext;

use crate::post::{PostInput, PostProcess, POST_PASS};
use subcone_metrics::Rgb8;

/// The format of every texture of the post-process; see the module doc.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Copies the upload texture into the SMAA colour buffer texel for texel:
/// `textureLoad` at the fragment's pixel, no sampler, so no filtering can
/// touch the values.
const BLIT_WGSL: &str = r"
@group(0) @binding(0) var src: texture_2d<f32>;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the viewport: (-1,-1), (3,-1), (-1,3).
    let x = select(-1.0, 3.0, i == 1u);
    let y = select(-1.0, 3.0, i == 2u);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(src, vec2<i32>(p.xy), 0);
}
";

/// SMAA 1x on the shared GPU device, with its targets kept between frames of
/// one size (creating an [`SmaaTarget`] compiles the crate's GLSL shaders).
pub struct SmaaPost {
    ctx: Arc<GpuContext>,
    blit_layout: wgpu::BindGroupLayout,
    blit: wgpu::RenderPipeline,
    state: Mutex<Option<State>>,
    /// Two timestamps around the blit and SMAA's passes, and the buffer
    /// they resolve to, where the device's timestamps are trusted
    /// ([`GpuContext::timing_source`]).
    timestamps: Option<(wgpu::QuerySet, wgpu::Buffer)>,
}

impl std::fmt::Debug for SmaaPost {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SmaaPost")
            .field("adapter", &self.ctx.info.name)
            .finish_non_exhaustive()
    }
}

/// What one frame size needs, kept until the size changes.
struct State {
    width: u32,
    height: u32,
    smaa: SmaaTarget,
    input: wgpu::Texture,
    blit_group: wgpu::BindGroup,
    output: wgpu::Texture,
    output_view: wgpu::TextureView,
}

impl State {
    /// The frame's size as a copy extent.
    fn extent(&self) -> wgpu::Extent3d {
        wgpu::Extent3d {
            width: self.width,
            height: self.height,
            depth_or_array_layers: 1,
        }
    }
}

/// Bytes per row of the read-back buffer: `4 · width` rounded up to
/// [`wgpu::COPY_BYTES_PER_ROW_ALIGNMENT`], as texture-to-buffer copies demand.
fn padded_row(width: u32) -> u64 {
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as u64;
    (4 * width as u64).div_ceil(align) * align
}

/// The RGB bytes of `image` as RGBA, alpha opaque, for the `Rgba8Unorm`
/// input texture (there is no three-channel texture format).
fn rgba_of(image: &Rgb8) -> Vec<u8> {
    image
        .data
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}

/// Refuse an image the GPU must never see: empty, or whose bytes do not
/// match its size (a mismatch would upload garbage or read out of bounds).
fn check_input(image: &Rgb8) -> Result<()> {
    if image.width == 0 || image.height == 0 {
        bail!(
            "SMAA needs a non-empty image, got {}x{}",
            image.width,
            image.height
        );
    }
    let expected = (image.width as u64)
        .checked_mul(image.height as u64)
        .and_then(|n| n.checked_mul(3))
        .ok_or_else(|| anyhow!("{}x{} is too large", image.width, image.height))?;
    if image.data.len() as u64 != expected {
        bail!(
            "image of {}x{} has {} bytes, expected {expected} (RGB)",
            image.width,
            image.height,
            image.data.len()
        );
    }
    Ok(())
}

impl SmaaPost {
    /// Opens (or reuses) the shared GPU context and builds the blit pipeline.
    /// Fails when there is no adapter, with a reason naming the driver to
    /// install ([`subcone_wgpu::context::NO_ADAPTER`]).
    pub fn new() -> Result<SmaaPost> {
        let ctx = GpuContext::shared().map_err(|e| anyhow!("SMAA needs a GPU: {e}"))?;
        let device = &ctx.device;
        let (blit_layout, blit) = ctx
            .scoped("SMAA blit pipeline", || {
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("smaa blit"),
                    source: wgpu::ShaderSource::Wgsl(BLIT_WGSL.into()),
                });
                let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("smaa blit"),
                    entries: &[wgpu::BindGroupLayoutEntry {
                        binding: 0,
                        visibility: wgpu::ShaderStages::FRAGMENT,
                        ty: wgpu::BindingType::Texture {
                            sample_type: wgpu::TextureSampleType::Float { filterable: false },
                            view_dimension: wgpu::TextureViewDimension::D2,
                            multisampled: false,
                        },
                        count: None,
                    }],
                });
                let pipeline_layout =
                    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                        label: Some("smaa blit"),
                        bind_group_layouts: &[Some(&layout)],
                        immediate_size: 0,
                    });
                let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("smaa blit"),
                    layout: Some(&pipeline_layout),
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("vs"),
                        buffers: &[],
                        compilation_options: Default::default(),
                    },
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("fs"),
                        targets: &[Some(wgpu::ColorTargetState {
                            format: FORMAT,
                            blend: None,
                            write_mask: wgpu::ColorWrites::ALL,
                        })],
                        compilation_options: Default::default(),
                    }),
                    primitive: Default::default(),
                    depth_stencil: None,
                    multisample: Default::default(),
                    multiview_mask: None,
                    cache: None,
                });
                (layout, pipeline)
            })
            .map_err(|e| anyhow!("{e}"))?;
        let timestamps = ctx.timestamps.then(|| {
            let set = device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("smaa timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("smaa timestamp resolve"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (set, resolve)
        });
        Ok(SmaaPost {
            ctx,
            blit_layout,
            blit,
            state: Mutex::new(None),
            timestamps,
        })
    }

    /// The adapter the post-process runs on, e.g.
    /// `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Mesa 22.3.6)`: the report
    /// prints it beside the row, since SMAA's time is a GPU time even when
    /// the frame came from the CPU backend.
    pub fn adapter(&self) -> String {
        self.ctx.describe()
    }

    /// Whether [`SmaaPost::apply`] times the post-process by GPU timestamps
    /// (the device's are trusted) rather than by the wall clock.
    pub fn timed_by_timestamps(&self) -> bool {
        self.timestamps.is_some()
    }

    /// SMAA 1x of `image`. Returns the result and the time of one frame. On
    /// a device with trusted timestamps ([`GpuContext::timing_source`]) it is
    /// the GPU's time from before the blit to after SMAA's three passes,
    /// from timestamps written between the submissions; elsewhere (software
    /// adapters) the wall time of RGBA packing, upload, blit, SMAA's three
    /// passes, copy and read-back to an [`Rgb8`]. The one-off setup for a new size (targets, and on the
    /// first call the compilation of SMAA's shaders) is not counted, as a
    /// renderer pays it once, not per frame. The first frame can still be
    /// slower (lavapipe: 71 ms against 45 ms at 512×512, its pipelines being
    /// built lazily): time after a warm-up call, as for the renderers.
    ///
    /// Fails, without touching the GPU, on an empty image or one whose bytes
    /// do not match its size; fails on a size beyond the device's texture or
    /// buffer limits, and on any GPU error.
    pub fn apply(&self, image: &Rgb8) -> Result<(Rgb8, PassTiming)> {
        check_input(image)?;
        let (w, h) = (image.width, image.height);
        let (row, readback_size) = self.readback_layout(w, h)?;

        let mut guard = self.state.lock().unwrap_or_else(|e| e.into_inner());
        let state = self.prepare(&mut guard, w, h)?;

        let start = Instant::now();
        let rgba = rgba_of(image);
        let readback = self
            .ctx
            .scoped("SMAA", || {
                self.upload(state, &rgba);
                self.blit_and_smaa(state);
                self.copy_out(state, row, readback_size)
            })
            .map_err(|e| anyhow!("{e}"))?;
        let data = self.read_back(&readback, w, h, row, image.data.len())?;
        let wall = start.elapsed();
        let timing = self.timing(wall)?;
        Ok((
            Rgb8 {
                width: w,
                height: h,
                data,
            },
            timing,
        ))
    }

    /// The read-back buffer's padded row and total size for a `w × h` frame,
    /// refusing a size past the device's texture or buffer limits before any
    /// GPU work.
    fn readback_layout(&self, w: u32, h: u32) -> Result<(u64, u64)> {
        let ctx = &self.ctx;
        ctx.check_texture_size(w, h).map_err(|e| anyhow!("{e}"))?;
        let row = padded_row(w);
        let readback_size = row * h as u64;
        let max_buffer = ctx.device.limits().max_buffer_size;
        if readback_size > max_buffer {
            bail!(
                "SMAA read-back of {w}x{h} needs {readback_size} bytes, over this adapter's \
                 buffer limit of {max_buffer}"
            );
        }
        Ok((row, readback_size))
    }

    /// Writes the RGBA bytes into the input texture.
    fn upload(&self, state: &State, rgba: &[u8]) {
        self.ctx.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &state.input,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            rgba,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * state.width),
                rows_per_image: Some(state.height),
            },
            state.extent(),
        );
    }

    /// Submits the blit of the input into SMAA's colour buffer (after the
    /// first timestamp), then SMAA's three passes into the output texture.
    fn blit_and_smaa(&self, state: &mut State) {
        let device = &self.ctx.device;
        let queue = &self.ctx.queue;
        let frame = state.smaa.start_frame(device, queue, &state.output_view);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("smaa blit"),
        });
        if let Some((set, _)) = &self.timestamps {
            encoder.write_timestamp(set, 0);
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("smaa blit"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &frame,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.blit);
            pass.set_bind_group(0, &state.blit_group, &[]);
            pass.draw(0..3, 0..1);
        }
        queue.submit([encoder.finish()]);
        // Submits edge detection, blending weights and neighbourhood
        // blending into `output_view`, after the blit above.
        frame.resolve();
    }

    /// Submits the second timestamp (and the resolve of both) and the copy
    /// of the output texture into a new read-back buffer of `row`-byte rows,
    /// which it returns.
    fn copy_out(&self, state: &State, row: u64, readback_size: u64) -> wgpu::Buffer {
        let device = &self.ctx.device;
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("smaa read-back"),
            size: readback_size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("smaa read-back"),
        });
        if let Some((set, resolve)) = &self.timestamps {
            encoder.write_timestamp(set, 1);
            encoder.resolve_query_set(set, 0..2, resolve, 0);
        }
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &state.output,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row as u32),
                    rows_per_image: Some(state.height),
                },
            },
            state.extent(),
        );
        self.ctx.queue.submit([encoder.finish()]);
        readback
    }

    /// Waits for the GPU, maps `readback` and returns its `w × h` pixels as
    /// RGB bytes (`capacity` of them), dropping alpha and each row's padding
    /// to `row` bytes.
    fn read_back(
        &self,
        readback: &wgpu::Buffer,
        w: u32,
        h: u32,
        row: u64,
        capacity: usize,
    ) -> Result<Vec<u8>> {
        let (tx, rx) = std::sync::mpsc::channel();
        readback.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        self.ctx.wait("SMAA").map_err(|e| anyhow!("{e}"))?;
        match rx.recv_timeout(Duration::from_secs(1)) {
            Ok(Ok(())) => {}
            Ok(Err(e)) => bail!("SMAA read-back failed: {e}"),
            Err(_) => bail!("SMAA read-back did not complete"),
        }
        let mut data = Vec::with_capacity(capacity);
        {
            let mapped = readback
                .get_mapped_range(..)
                .map_err(|e| anyhow!("SMAA read-back failed: {e}"))?;
            for y in 0..h as usize {
                let line = &mapped[y * row as usize..][..4 * w as usize];
                data.extend(line.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]));
            }
        }
        readback.unmap();
        Ok(data)
    }

    /// The frame's time: from the two GPU timestamps where the device has
    /// them, falling back to `wall` (marked why) when they read zero; the
    /// wall time elsewhere.
    fn timing(&self, wall: Duration) -> Result<PassTiming> {
        let ctx = &self.ctx;
        Ok(match &self.timestamps {
            Some((_, resolve)) => {
                let bytes = ctx
                    .read_buffer(resolve, 0, 16)
                    .map_err(|e| anyhow!("{e}"))?;
                let stamp = |i: usize| {
                    bytes
                        .get(8 * i..8 * i + 8)
                        .and_then(|b| b.try_into().ok())
                        .map_or(0, u64::from_le_bytes)
                };
                let ns = stamp(1).saturating_sub(stamp(0)) as f64
                    * ctx.queue.get_timestamp_period() as f64;
                if ns > 0.0 {
                    PassTiming {
                        name: POST_PASS,
                        time: Duration::from_nanos(ns as u64),
                        source: TimingSource::GpuTimestamps,
                    }
                } else {
                    PassTiming {
                        name: POST_PASS,
                        time: wall,
                        source: TimingSource::GpuWallClock {
                            why: "the pass's timestamps read zero",
                        },
                    }
                }
            }
            None => PassTiming {
                name: POST_PASS,
                time: wall,
                source: ctx.timing_source(),
            },
        })
    }

    /// The state for a `w × h` frame: kept if the size is unchanged, else
    /// resized (the SMAA pipelines survive a resize) or created.
    fn prepare<'a>(&self, slot: &'a mut Option<State>, w: u32, h: u32) -> Result<&'a mut State> {
        if slot.as_ref().is_some_and(|s| s.width == w && s.height == h) {
            return slot.as_mut().context("SMAA state vanished");
        }
        let device = &self.ctx.device;
        let queue = &self.ctx.queue;
        let previous = slot.take().map(|s| s.smaa);
        let state = self
            .ctx
            .scoped("SMAA targets", || {
                let smaa = match previous {
                    Some(mut smaa) => {
                        smaa.resize(device, w, h);
                        smaa
                    }
                    None => SmaaTarget::new(device, queue, w, h, FORMAT, SmaaMode::Smaa1X),
                };
                let desc = |label, usage| wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: w,
                        height: h,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: FORMAT,
                    usage,
                    view_formats: &[],
                };
                let input = device.create_texture(&desc(
                    "smaa input",
                    wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                ));
                let output = device.create_texture(&desc(
                    "smaa output",
                    wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                ));
                let blit_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("smaa blit"),
                    layout: &self.blit_layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(
                            &input.create_view(&Default::default()),
                        ),
                    }],
                });
                let output_view = output.create_view(&Default::default());
                State {
                    width: w,
                    height: h,
                    smaa,
                    input,
                    blit_group,
                    output,
                    output_view,
                }
            })
            .map_err(|e| anyhow!("{e}"))?;
        Ok(slot.insert(state))
    }
}

/// The SMAA row: SMAA 1x on NoAA's frame, judged like a method.
impl PostProcess for SmaaPost {
    fn name(&self) -> &str {
        crate::SMAA
    }

    fn describe(&self) -> String {
        format!(
            "SMAA 1x (the `smaa` crate, quality High) on {}; its time is NoAA's plus the \
             post-process ({})",
            self.adapter(),
            if self.timed_by_timestamps() {
                "blit and SMAA's three passes, by GPU timestamps"
            } else {
                "upload, SMAA, read-back, by the wall clock"
            }
        )
    }

    fn apply(&self, input: &PostInput<'_>) -> Result<(Rgb8, PassTiming)> {
        SmaaPost::apply(self, input.image)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The post-process, or `None` (with a note) when there is no adapter and
    /// no GPU is required; with `SUBCONE_REQUIRE_GPU` set, no adapter fails.
    fn post() -> Option<SmaaPost> {
        subcone_scene::conformance::or_skip("SMAA", SmaaPost::new().map_err(|e| format!("{e:#}")))
    }

    fn image(width: u32, height: u32, f: impl Fn(u32, u32) -> [u8; 3]) -> Rgb8 {
        let mut data = Vec::new();
        for y in 0..height {
            for x in 0..width {
                data.extend(f(x, y));
            }
        }
        Rgb8 {
            width,
            height,
            data,
        }
    }

    fn max_diff(a: &Rgb8, b: &Rgb8) -> u8 {
        a.data
            .iter()
            .zip(&b.data)
            .map(|(p, q)| p.abs_diff(*q))
            .max()
            .unwrap_or(0)
    }

    /// A flat image, and a gradient whose steps (2 codes) are far below SMAA's
    /// 0.1 luma threshold, come back unchanged. The gradient differs in every
    /// row and column, so a flipped, shifted or wrongly padded read-back
    /// (37 pixels: 148 bytes per row, padded to 256) fails, and so would an
    /// sRGB decode without the matching encode.
    #[test]
    fn edgeless_images_come_back_unchanged() {
        let Some(post) = post() else { return };
        let flat = image(37, 23, |_, _| [37, 140, 201]);
        let (out, _) = post.apply(&flat).unwrap();
        assert_eq!((out.width, out.height), (37, 23));
        assert_eq!(out.data.len(), flat.data.len());
        assert!(max_diff(&out, &flat) <= 1, "flat image changed");

        let ramp = image(37, 23, |x, y| [(x * 2) as u8, (y * 2 + 60) as u8, 100]);
        let (out, timing) = post.apply(&ramp).unwrap();
        let d = max_diff(&out, &ramp);
        assert!(d <= 1, "gradient changed by up to {d} codes");
        assert!(timing.time > Duration::ZERO);
        // The source is the device's: timestamps only where they are trusted.
        assert_eq!(timing.source, post.ctx.timing_source());
    }

    /// A black/white staircase (the boundary `y = 20 + x/4`: steps of four
    /// pixels, the aliasing SMAA's area texture is built for) gets
    /// intermediate greys (R = G = B) along the edge, while every pixel more
    /// than two pixels from the edge keeps its value: SMAA blends a pixel only
    /// with its direct neighbours. On lavapipe each step becomes a ramp
    /// (0, 6, 32, 91 | 164, 223, 249, 255): three of every four edge pixels
    /// are blended, 84 of 112; at least two thirds must be. Without SMAA (the
    /// crate's `Disabled` mode) none are, and this test fails.
    #[test]
    fn staircase_edge_is_antialiased_and_the_rest_untouched() {
        let Some(post) = post() else { return };
        let (w, h) = (64u32, 48u32);
        let white = |x: u32, y: u32| y < 20 + x / 4;
        let img = image(w, h, |x, y| if white(x, y) { [255; 3] } else { [0; 3] });
        let (out, _) = post.apply(&img).unwrap();
        let px = |x: u32, y: u32| {
            let i = 3 * (y * w + x) as usize;
            [out.data[i], out.data[i + 1], out.data[i + 2]]
        };
        // Pixels with a 4-neighbour of the other colour, away from the border
        // (SMAA clamps its searches there).
        let is_edge = |x: u32, y: u32| {
            let c = white(x, y);
            (x > 0 && white(x - 1, y) != c)
                || (x + 1 < w && white(x + 1, y) != c)
                || (y > 0 && white(x, y - 1) != c)
                || (y + 1 < h && white(x, y + 1) != c)
        };
        let (mut edge, mut grey) = (0, 0);
        for y in 2..h - 2 {
            for x in 4..w - 4 {
                if is_edge(x, y) {
                    edge += 1;
                    let p = px(x, y);
                    assert!(p[0] == p[1] && p[1] == p[2], "colour at ({x},{y}): {p:?}");
                    if (1..=254).contains(&p[0]) {
                        grey += 1;
                    }
                }
            }
        }
        assert!(edge > 50, "{edge} edge pixels");
        assert!(
            grey * 3 >= edge * 2,
            "only {grey} of {edge} edge pixels were blended"
        );
        for y in 0..h {
            for x in 0..w {
                let near = (x.saturating_sub(2)..=(x + 2).min(w - 1))
                    .any(|i| (y.saturating_sub(2)..=(y + 2).min(h - 1)).any(|j| is_edge(i, j)));
                if !near {
                    let want = if white(x, y) { 255 } else { 0 };
                    assert_eq!(px(x, y), [want; 3], "far pixel ({x},{y}) changed");
                }
            }
        }
    }

    /// The report may hold one post-process for all its threads.
    #[test]
    fn post_is_send_and_sync() {
        fn check<T: Send + Sync>() {}
        check::<SmaaPost>();
    }

    /// Bad input is refused before any GPU work, with or without an adapter.
    #[test]
    fn bad_input_is_refused_without_a_gpu() {
        let short = Rgb8 {
            width: 4,
            height: 4,
            data: vec![0; 47],
        };
        assert!(check_input(&short).is_err());
        let long = Rgb8 {
            data: vec![0; 49],
            ..short.clone()
        };
        assert!(check_input(&long).is_err());
        for (width, height) in [(0, 4), (4, 0), (0, 0)] {
            let empty = Rgb8 {
                width,
                height,
                data: vec![],
            };
            assert!(check_input(&empty).is_err(), "{width}x{height} accepted");
        }
        assert!(check_input(&image(4, 4, |_, _| [1, 2, 3])).is_ok());
    }

    /// Through [`SmaaPost::apply`]: bad data, an empty image and a size past
    /// the device's largest texture are errors, not panics, and leave the
    /// post-process usable (a 1×1 image then works).
    #[test]
    fn bad_input_is_an_error() {
        let Some(post) = post() else { return };
        let short = Rgb8 {
            width: 8,
            height: 8,
            data: vec![0; 8 * 8 * 3 - 1],
        };
        assert!(post.apply(&short).is_err());
        let empty = Rgb8 {
            width: 0,
            height: 5,
            data: vec![],
        };
        assert!(post.apply(&empty).is_err());
        let max = post.ctx.device.limits().max_texture_dimension_2d;
        let wide = image(max + 1, 1, |_, _| [0; 3]);
        let e = post.apply(&wide).unwrap_err();
        assert!(e.to_string().contains("max_texture_dimension_2d"), "{e}");
        let one = image(1, 1, |_, _| [9, 99, 199]);
        let (out, _) = post.apply(&one).unwrap();
        assert!(max_diff(&out, &one) <= 1);
    }

    /// The format choice, pinned: a staircase between two dark greys (sRGB 50
    /// and 90: 0.16 apart encoded, 0.07 in linear light, against SMAA's 0.1
    /// luma threshold) is antialiased, as SMAA intends on the displayed image.
    /// With `Rgba8UnormSrgb` textures edge detection runs on linear values and
    /// leaves this edge untouched (0 pixels changed, 92 with `Rgba8Unorm`).
    #[test]
    fn dark_low_contrast_edge_is_detected() {
        let Some(post) = post() else { return };
        let img = image(
            64,
            48,
            |x, y| if y < 20 + x / 4 { [90; 3] } else { [50; 3] },
        );
        let (out, _) = post.apply(&img).unwrap();
        let changed = out
            .data
            .chunks_exact(3)
            .zip(img.data.chunks_exact(3))
            .filter(|(p, q)| p != q)
            .count();
        assert!(changed > 50, "only {changed} pixels changed");
    }
}
