//! [`SraaPass`]: built once for a configuration, encoded every frame.

use super::checks::InputRules;
use super::desc::{DepthKind, GeometryLayout, SraaPassDesc};
use super::inputs::{Samples, SraaBuffers, SraaInputs, SubsampleGeometry};
use super::SraaFrame;
use crate::bind::{self, check_buffer, required, Bound, PassPipeline, Rect};
use crate::bind::{CommandEncoder, ComputePassTimestampWrites, Device, Queue};
use crate::skeleton;
use crate::PassError;

/// Bind the shaded samples' resource of `s` as `shaded` and the
/// subsamples' as `subsamples`.
fn bind_samples<'a, R: Into<Bound<'a>>>(
    s: Samples<R>,
    [shaded, subsamples]: [&'static str; 2],
    to: &mut Vec<(&'static str, Bound<'a>)>,
) {
    to.push((shaded, s.shaded.into()));
    to.push((subsamples, s.subsamples.into()));
}

/// SRAA's antialiasing pass on the host's device. See the module docs of
/// the crate and [`SraaPassDesc`] for the conventions.
///
/// Built once (`new` compiles the pipeline and makes the uniform buffer),
/// encoded every frame: after the first frame with given views, `encode`
/// creates no buffer, texture, bind group or pipeline (it writes the frame's
/// constants into a slot of its uniform buffer, [`crate::UNIFORM_SLOTS`],
/// and reuses the bind group of those views, [`crate::BIND_GROUP_CACHE`]).
/// Call [`SraaPass::end_submission`] after each submit that holds its
/// encodes, so that its uniform slots are free for the next.
///
/// ```no_run
/// # fn f(device: &wgpu::Device, queue: &wgpu::Queue, encoder: &mut wgpu::CommandEncoder,
/// #      depth: &wgpu::TextureView, normal: &wgpu::TextureView, color: &wgpu::TextureView,
/// #      output: &wgpu::TextureView, projection: [[f32; 4]; 4])
/// # -> Result<(), subcone_passes::PassError> {
/// use subcone_passes::{SraaInputs, SraaPass, SraaPassDesc, SubsampleGeometry};
/// let sraa = SraaPass::new(device, &SraaPassDesc::msaa())?;
/// sraa.encode(device, queue, encoder, &SraaInputs {
///     // Depth32Float (reversed Z) and Rgba16Float, 4x MSAA
///     geometry: SubsampleGeometry::Separate { depth, normal },
///     projection,               // this frame's
///     centre: None,
///     color,                    // shaded at SUBPIXEL_OFFSETS[0]
///     shadows: None,
///     albedo: None,
///     secondary: None,
///     output,                   // Rgba16Float, STORAGE_BINDING
/// }, None)?;
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct SraaPass {
    desc: SraaPassDesc,
    pipeline: PassPipeline,
}

impl SraaPass {
    /// Build the pass (compile its pipeline) on the host's device. Refuses
    /// more than `MAX_LIGHTS` lights, an output format
    /// it cannot write, and [`GeometryLayout::Packed`] with hardware depth
    /// or unsigned normals.
    pub fn new(device: &Device, desc: &SraaPassDesc) -> Result<Self, PassError> {
        let pipeline = skeleton::pipeline::<Self>(device, desc)?;
        Ok(SraaPass {
            desc: *desc,
            pipeline,
        })
    }

    /// The configuration.
    pub fn desc(&self) -> &SraaPassDesc {
        &self.desc
    }

    /// Check `inputs` against the configuration and `rect` (the whole
    /// output for `None`); the rect to resolve. Each input in turn, in the
    /// order of [`SraaInputs`]' roles: the output, the subsample geometry,
    /// the centre geometry, the colour, the shadows, the secondary hits,
    /// the albedo.
    fn check(&self, inputs: &SraaInputs<'_>, rect: Option<&Rect>) -> Result<Rect, PassError> {
        let d = &self.desc;
        let region = bind::check_output_region(
            inputs.output,
            d.output_format,
            "the desc's output_format",
            rect,
        )?;
        let size = (
            inputs.output.texture().width(),
            inputs.output.texture().height(),
        );
        let rules = InputRules {
            desc: d,
            size,
            rect,
        };
        rules.subsample_geometry(inputs)?;
        if let Some(c) = required(
            inputs.centre.as_ref(),
            d.shaded_at_centre(),
            "centre geometry (the preset shades the pixel centre)",
            "centre geometry (the preset shades subsample 0)",
        )? {
            rules.centre_geometry(c)?;
        }
        rules.check(inputs.color, &rules.one("colour", d.color_layers()))?;
        bind::check_float_color("colour", inputs.color)?;
        if let Some(s) = required(
            inputs.shadows.as_ref(),
            d.lights > 0,
            "shadow textures (lights > 0)",
            "shadow textures (0 lights)",
        )? {
            rules.shadows(s)?;
        }
        if let Some(s) = required(
            inputs.secondary.as_ref(),
            d.secondary,
            "secondary inputs (secondary on)",
            "secondary inputs (secondary off)",
        )? {
            rules.secondary(s)?;
        }
        if let Some(a) = required(
            inputs.albedo.as_ref(),
            d.albedo_gate,
            "albedo textures (albedo gate on)",
            "albedo textures (albedo gate off)",
        )? {
            rules.albedo(a)?;
        }
        Ok(region)
    }

    /// Record the resolve of one frame into `encoder` (one compute pass of
    /// 8×8 workgroups, one invocation per pixel), its constants (size,
    /// preset, projection) written through `queue`. Checks every input
    /// first: on an error nothing is recorded or written.
    ///
    /// `timestamps`, when given, are written at the start and end of the
    /// compute pass: the host creates the query set (`QueryType::Timestamp`,
    /// on a device with `Features::TIMESTAMP_QUERY`), resolves it
    /// (`CommandEncoder::resolve_query_set`) and reads it back.
    pub fn encode(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &SraaInputs<'_>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        self.encode_region(device, queue, encoder, inputs, None, timestamps)
    }

    /// Record the resolve of `rect` of the textures (a viewport: dynamic
    /// resolution, split screen), as [`Self::encode`] records the whole:
    /// every input is read, and the output written, at the rect's pixels,
    /// the same pixels in every texture; the output's pixels outside the
    /// rect are left as they were. The textures need not be the same size:
    /// each must hold the rect (a [`PassError::Rect`] otherwise, also for
    /// an empty rect), and is checked as [`Self::encode`] checks it
    /// otherwise.
    ///
    /// The rect is the image: the reconstruction's neighbourhood (SRAA's
    /// 3×3, or `(2r+1)²`) is clipped to the rect, not to the texture, as
    /// `sraa::neighbourhood` clips it to an image's edge, so pixels outside
    /// the rect (another view's) never bleed in, and the rect's pixels are
    /// exactly those of the pass over textures of the rect's size holding
    /// the same inputs.
    pub fn encode_rect(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &SraaInputs<'_>,
        rect: Rect,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        self.encode_region(device, queue, encoder, inputs, Some(&rect), timestamps)
    }

    /// [`Self::encode`] of `rect` (the whole output for `None`).
    fn encode_region(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &SraaInputs<'_>,
        rect: Option<&Rect>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        if self.desc.geometry == GeometryLayout::Buffers {
            return Err(PassError::Config(
                "GeometryLayout::Buffers is encoded with encode_buffers".into(),
            ));
        }
        let region = self.check(inputs, rect)?;
        let hardware_depth = match self.desc.depth {
            DepthKind::LinearView => None,
            DepthKind::Hardware { miss } => Some((inputs.projection, miss)),
        };
        let mut views: Vec<(&'static str, Bound<'_>)> = Vec::with_capacity(16);
        match inputs.geometry {
            SubsampleGeometry::Separate { depth, normal } => {
                views.push(("sub_depth", depth.into()));
                views.push(("sub_normal", normal.into()));
            }
            SubsampleGeometry::Packed(p) => views.push(("sub_depth", p.into())),
        }
        if let Some(c) = &inputs.centre {
            views.push(("centre_depth", c.depth.into()));
            views.push(("centre_normal", c.normal.into()));
        }
        views.push(("color", inputs.color.into()));
        if let Some(s) = inputs.shadows {
            bind_samples(s, ["shaded_shadow", "sub_shadow"], &mut views);
        }
        if let Some(s) = &inputs.secondary {
            views.push(("sec_shaded_depth", s.shaded_depth.into()));
            views.push(("sec_shaded_normal", s.shaded_normal.into()));
            views.push(("sec_sub_depth", s.subsample_depth.into()));
            views.push(("sec_sub_normal", s.subsample_normal.into()));
            if let Some(sh) = s.shadows {
                bind_samples(sh, ["sec_shaded_shadow", "sec_sub_shadow"], &mut views);
            }
        }
        if let Some(a) = inputs.albedo {
            bind_samples(a, ["shaded_albedo", "sub_albedo"], &mut views);
        }
        views.push(("sraa_output", inputs.output.into()));
        self.record(
            device,
            queue,
            encoder,
            region,
            hardware_depth,
            &views,
            timestamps,
        )
    }

    /// Record the resolve of one frame from storage buffers
    /// ([`GeometryLayout::Buffers`], [`SraaPassDesc::buffers`]), as
    /// [`Self::encode`] does from textures: one compute pass of 8×8
    /// workgroups, the constants written through `queue`, every buffer
    /// checked first (usage and size for `inputs.size`; the optional roles
    /// given exactly when the desc needs them), so that on an error nothing
    /// is recorded or written.
    pub fn encode_buffers(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &SraaBuffers<'_>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let d = &self.desc;
        if d.geometry != GeometryLayout::Buffers {
            return Err(PassError::Config(format!(
                "GeometryLayout::{:?} is encoded with encode (textures)",
                d.geometry
            )));
        }
        let (width, height) = inputs.size;
        let n = u64::from(width) * u64::from(height);
        let (geo, float4, word) = (16, 16, 4);
        inputs
            .geometry
            .check(["shaded geometry", "subsample geometry"], n, geo)?;
        let layers = u64::from(d.color_layers());
        check_buffer("colour", inputs.color, n * layers, float4)?;
        check_buffer("output", inputs.output, n, float4)?;
        let shadows = required(
            inputs.shadows,
            d.lights > 0,
            "shadow buffers (lights > 0)",
            "shadow buffers (0 lights)",
        )?;
        let albedo = required(
            inputs.albedo,
            d.albedo_gate,
            "albedo buffers (albedo gate on)",
            "albedo buffers (albedo gate off)",
        )?;
        let secondary = required(
            inputs.secondary,
            d.secondary,
            "secondary buffers (secondary on)",
            "secondary buffers (secondary off)",
        )?;
        let mut bound: Vec<(&'static str, Bound<'_>)> = Vec::with_capacity(16);
        bind_samples(inputs.geometry, ["shaded_geo", "sub_geo"], &mut bound);
        bound.push(("color", inputs.color.into()));
        if let Some(s) = shadows {
            s.check(["shaded shadow bits", "subsample shadow bits"], n, word)?;
            bind_samples(s, ["shaded_shadow", "sub_shadow"], &mut bound);
        }
        if let Some(s) = secondary {
            let geometry = ["secondary shaded geometry", "secondary subsample geometry"];
            s.geometry.check(geometry, n, geo)?;
            let shadows = required(
                s.shadows,
                d.lights > 0,
                "secondary shadow buffers (lights > 0)",
                "secondary shadow buffers (0 lights)",
            )?;
            bind_samples(s.geometry, ["sec_shaded_geo", "sec_sub_geo"], &mut bound);
            if let Some(sh) = shadows {
                let bits = [
                    "secondary shaded shadow bits",
                    "secondary subsample shadow bits",
                ];
                sh.check(bits, n, word)?;
                bind_samples(sh, ["sec_shaded_shadow", "sec_sub_shadow"], &mut bound);
            }
        }
        if let Some(a) = albedo {
            a.check(["shaded albedo", "subsample albedo"], n, float4)?;
            bind_samples(a, ["shaded_albedo", "sub_albedo"], &mut bound);
        }
        bound.push(("sraa_output", inputs.output.into()));
        self.record(
            device,
            queue,
            encoder,
            Rect::whole(inputs.size),
            None,
            &bound,
            timestamps,
        )
    }

    /// Record one frame's `rect` over the `bound` resources, with the
    /// projection and the depth of a miss for hardware depth (`None` for
    /// linear view depth).
    #[allow(clippy::too_many_arguments)]
    fn record(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        rect: Rect,
        hardware_depth: Option<([[f32; 4]; 4], f32)>,
        bound: &[(&'static str, Bound<'_>)],
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let frame = SraaFrame::new(
            self.desc.params,
            (rect.x, rect.y),
            (rect.width, rect.height),
            hardware_depth,
            self.desc.resolve,
        );
        self.pipeline.encode(
            device,
            queue,
            encoder,
            rect.size(),
            &[bytemuck::bytes_of(&frame)],
            bound,
            None,
            timestamps,
        )
    }

    /// Drop the bind groups cached for the views seen so far, and with them
    /// the pass's clones of the host's views (so textures the host has
    /// dropped are freed now rather than when evicted).
    pub fn release_views(&self) {
        self.pipeline.release_views();
    }

    /// Tell the pass that every command buffer it was encoded into so far
    /// has been submitted (`Queue::submit`), so its uniform slots may be
    /// rewritten: call it after each submit that holds this pass's encodes.
    ///
    /// Why: `encode` writes its uniforms with `Queue::write_buffer`, which
    /// lands before *any* command of the next submission runs, so a slot
    /// still bound by an unsubmitted encode is never rewritten; a new value
    /// takes a free slot, or the ring grows ([`crate::UNIFORM_SLOTS`] to
    /// [`crate::MAX_UNIFORM_SLOTS`]). Without this call a slot is freed only
    /// once its command buffer has run on the GPU and the host polled the
    /// device (or submitted again): still correct, but the ring may grow
    /// further, and a host that never submits gets
    /// [`PassError::UniformSlotsExhausted`]. Calling it while an encode of
    /// this pass is recorded but not submitted breaks that encode: it may
    /// read a later encode's values.
    pub fn end_submission(&self) {
        self.pipeline.end_submission();
    }
}
