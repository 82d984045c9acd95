//! [`FxaaPass`]: FXAA 3.11 quality preset 12 (`subcone_kernels::fxaa`, the
//! kernels' WGSL twin of the CPU backend's post-process) over a host texture.

use bytemuck::{Pod, Zeroable};
use subcone_kernels::fxaa::FxaaParams;

use crate::bind::{self, Expect, Group, PassPipeline};
use crate::PassError;

pub(crate) const FXAA_WGSL: &str = include_str!("fxaa.wgsl");

/// The frame's size; `FxaaFrame` in `fxaa.wgsl` (16 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct FxaaFrame {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) _pad: [u32; 2],
}

/// FXAA on the host's device: reads a one-sample texture of linear RGB
/// (`.xyz`, any float, unorm or snorm format, `TEXTURE_BINDING`) and writes
/// the filtered linear RGB, alpha 1, into a storage texture of the same size
/// (`STORAGE_BINDING`, the pass's output format). Pixels outside the image
/// are clamped to its edge. Input and output must be different textures.
pub struct FxaaPass {
    params: FxaaParams,
    output_format: wgpu::TextureFormat,
    pipeline: PassPipeline,
}

impl std::fmt::Debug for FxaaPass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FxaaPass")
            .field("params", &self.params)
            .field("output_format", &self.output_format)
            .finish()
    }
}

impl FxaaPass {
    /// Build the pass (compile its pipeline) for `params`
    /// (`FxaaParams::QUALITY`, the defaults of FXAA 3.11) writing
    /// `output_format` (`Rgba8Unorm`, `Rgba16Float` or `Rgba32Float`).
    pub fn new(
        device: &wgpu::Device,
        params: &FxaaParams,
        output_format: wgpu::TextureFormat,
    ) -> Result<Self, PassError> {
        bind::check_output_format(output_format)?;
        let group = Self::group(output_format);
        let source = Self::source(&group);
        let pipeline = PassPipeline::new(device, "subcone fxaa", group, source, None, "fxaa_main");
        Ok(FxaaPass {
            params: *params,
            output_format,
            pipeline,
        })
    }

    #[cfg(test)]
    pub(crate) fn group_for_tests(output_format: wgpu::TextureFormat) -> Group {
        Self::group(output_format)
    }

    fn group(output_format: wgpu::TextureFormat) -> Group {
        let mut g = Group::default();
        g.uniform("fxaa_params", "subcone_FxaaParams");
        g.uniform("fxaa_frame", "FxaaFrame");
        g.texture(
            "fxaa_src",
            "texture_2d<f32>",
            wgpu::TextureSampleType::Float { filterable: false },
            wgpu::TextureViewDimension::D2,
            false,
        );
        g.storage_texture("fxaa_dst", output_format);
        g
    }

    pub(crate) fn source(group: &Group) -> String {
        [
            subcone_kernels::wgsl::PARAMS,
            subcone_kernels::fxaa::WGSL,
            FXAA_WGSL,
            &group.declarations(),
        ]
        .concat()
    }

    /// Record FXAA of `input` into `output` (one compute pass). Checks both
    /// first: on an error nothing is recorded.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        input: &wgpu::Texture,
        output: &wgpu::Texture,
    ) -> Result<(), PassError> {
        let size = bind::check_output(output, self.output_format, "the pass's output format")?;
        bind::check(
            input,
            &Expect {
                what: "input",
                size,
                samples: 1,
                layers: 1,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
            },
        )?;
        bind::check_float_color("input", input)?;
        if input == output {
            return Err(PassError::Config(
                "FXAA cannot filter a texture in place".into(),
            ));
        }
        let params = bind::uniform_buffer(device, "subcone fxaa params", &self.params);
        let frame = FxaaFrame {
            width: size.0,
            height: size.1,
            _pad: [0; 2],
        };
        let frame = bind::uniform_buffer(device, "subcone fxaa frame", &frame);
        let src = bind::view(input, wgpu::TextureViewDimension::D2);
        let dst = bind::view(output, wgpu::TextureViewDimension::D2);
        self.pipeline.encode(
            device,
            encoder,
            size,
            &[
                ("fxaa_params", params.as_entire_binding()),
                ("fxaa_frame", frame.as_entire_binding()),
                ("fxaa_src", wgpu::BindingResource::TextureView(&src)),
                ("fxaa_dst", wgpu::BindingResource::TextureView(&dst)),
            ],
            None,
        )
    }
}
