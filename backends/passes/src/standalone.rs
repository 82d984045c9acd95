//! Every pass as a standalone compute shader, for an engine without wgpu.
//!
//! A [`StandaloneShader`] is the whole WGSL a pass compiles for one
//! configuration (the same source [`crate::SraaPass::new`] and its siblings
//! hand to wgpu, declarations included), with what a host needs to run it
//! on its own API: the entry point, the workgroup size, the bindings
//! ([`crate::bind::BindingEntry`], from the very [`crate::bind::Group`] the
//! wgpu pass builds its layout from), the uniforms' struct names and how
//! to size the dispatch. `subcone shaders` cross-compiles each
//! [`catalog`] entry to SPIR-V, HLSL, GLSL and MSL and writes its resource
//! table; a Rust host may call [`sraa`], [`ctss`], [`fxaa`] or [`taa`]
//! for a configuration the catalog does not hold.
//!
//! ```
//! use subcone_passes::standalone;
//! use subcone_passes::SraaPassDesc;
//! use subcone_kernels::sraa::SraaParams;
//!
//! let shader = standalone::sraa(&SraaPassDesc::buffers(SraaParams::TUNED))?;
//! assert_eq!(shader.entry_point, "sraa_resolve_main");
//! assert_eq!(shader.bindings[0].name, "frame");
//! assert!(shader.wgsl.contains("@group(0) @binding(0) var<uniform> frame: SraaFrame;"));
//! # Ok::<(), subcone_passes::PassError>(())
//! ```

use subcone_kernels::sraa::SraaParams;
use subcone_kernels::taa::{DepthDilation, TaaSettings};

use crate::bind::BindingEntry;
use crate::ctss::CtssKey;
use crate::skeleton;
use crate::{
    CtssOutput, CtssPass, CtssPassDesc, FxaaPass, FxaaPassDesc, PassError, SraaPass, SraaPassDesc,
    TaaPass, TaaPassDesc,
};

/// One pass in one configuration, as a host without wgpu compiles and
/// binds it.
#[derive(Clone, Debug)]
pub struct StandaloneShader {
    /// The pass: `"sraa"`, `"ctss"`, `"fxaa"` or `"taa"`.
    pub pass: &'static str,
    /// The configuration's name within the pass (`"buffers"`, `"msaa"`…).
    pub variant: String,
    /// What the configuration is, in a sentence.
    pub summary: String,
    /// The whole WGSL module, bindings declared (`@group(0)`).
    pub wgsl: String,
    /// The WGSL the GLSL is translated from, where it differs from
    /// [`Self::wgsl`]: a hardware depth texture declared as a float
    /// texture whose `.x` is the depth (GLSL has no texel fetch from a
    /// depth sampler; Vulkan and OpenGL bind a depth image to a float
    /// sampler, depth in red). `None`: the same module.
    pub glsl_wgsl: Option<String>,
    /// The compute entry point.
    pub entry_point: &'static str,
    /// `@workgroup_size`.
    pub workgroup_size: [u32; 3],
    /// Every binding, in binding order.
    pub bindings: Vec<BindingEntry>,
    /// How many workgroups a frame dispatches.
    pub dispatch: &'static str,
}

/// The dispatch of every pass: one invocation per pixel of the rect.
pub(crate) const DISPATCH: &str =
    "(ceil(width / 8), ceil(height / 8), 1) workgroups for a width × height \
     image (or rect): one invocation per pixel, those outside return at once";

/// [`crate::SraaPass`] built for `desc`.
pub fn sraa(desc: &SraaPassDesc) -> Result<StandaloneShader, PassError> {
    skeleton::standalone::<SraaPass>(desc)
}

/// [`crate::CtssPass`] built for the host's field `host_wgsl` (what
/// [`crate::CtssPass::new`] takes) and `desc`. The host layout
/// (`@group(1)`) is the host's own: its WGSL declares it.
pub fn ctss(host_wgsl: &str, desc: &CtssPassDesc<'_>) -> Result<StandaloneShader, PassError> {
    skeleton::standalone::<CtssPass>(&CtssKey { host_wgsl, desc })
}

/// [`crate::FxaaPass`] built for `desc`.
pub fn fxaa(desc: &FxaaPassDesc) -> Result<StandaloneShader, PassError> {
    skeleton::standalone::<FxaaPass>(desc)
}

/// [`crate::TaaPass`] built for `desc`.
pub fn taa(desc: &TaaPassDesc) -> Result<StandaloneShader, PassError> {
    skeleton::standalone::<TaaPass>(desc)
}

/// The test field of the catalog's CTSS shaders, and of the C host that
/// runs them (`capi/vulkan-host`): a unit sphere at `(0, 0, 4)` (object 0)
/// on the plane `y = −1` (object 1), shaded by one directional light with
/// an ambient term. A host compiles its own field with [`ctss`] (or
/// `subcone shaders --ctss-field`).
pub const TEST_FIELD_WGSL: &str = "\
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let sphere = length(p - vec3<f32>(0.0, 0.0, 4.0)) - 1.0;
    let ground = p.y + 1.0;
    if sphere < ground {
        return vec3<f32>(sphere, sphere, 0.0);
    }
    return vec3<f32>(ground, ground, 1.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let light = vec3<f32>(0.48, 0.8, -0.36);
    var albedo = vec3<f32>(0.9, 0.3, 0.2);
    if p.y < -0.999 {
        albedo = vec3<f32>(0.7, 0.7, 0.7);
    }
    return albedo * (0.15 + max(dot(n, light), 0.0));
}
";

/// The configurations `subcone shaders` writes: per pass, the ones a host
/// most likely selects at build time. Each is the pass's own preset or
/// one `with_` change from it, named for what differs.
pub fn catalog() -> Result<Vec<StandaloneShader>, PassError> {
    let named = |mut s: StandaloneShader, variant: &str, summary: &str| {
        s.variant = variant.to_owned();
        s.summary = summary.to_owned();
        s
    };
    let tuned = SraaParams::TUNED;
    let ctss_buffers = CtssPassDesc::default().with_output(CtssOutput::Buffers { counts: false });
    Ok(vec![
        named(
            sraa(&SraaPassDesc::msaa())?,
            "msaa",
            "SraaPassDesc::msaa(): a 4x MSAA prepass of reversed-Z hardware depth and signed \
             normals, the paper's weights (shaded sample on subsample 0), no lights, \
             Rgba16Float output",
        ),
        named(
            sraa(&SraaPassDesc::msaa().with_lights(1))?,
            "msaa-lights1",
            "SraaPassDesc::msaa() with one light's shadows gating the weights (eq. 2): \
             two colour layers, shadow bits per sample",
        ),
        named(
            sraa(&SraaPassDesc::packed(tuned))?,
            "packed",
            "SraaPassDesc::packed(SraaParams::TUNED): four Rgba32Float layers of \
             (normal, linear view depth), shaded at the pixel centre, Rgba32Float output",
        ),
        named(
            sraa(&SraaPassDesc::buffers(tuned))?,
            "buffers",
            "SraaPassDesc::buffers(SraaParams::TUNED): geometry, colour and output in storage \
             buffers (the C ABI's subcone_sraa_resolve over the same data), no lights",
        ),
        named(
            sraa(&SraaPassDesc::buffers(tuned).with_lights(1))?,
            "buffers-lights1",
            "SraaPassDesc::buffers(SraaParams::TUNED) with one light's shadows (eq. 2)",
        ),
        named(
            ctss(TEST_FIELD_WGSL, &ctss_buffers)?,
            "testfield-buffers",
            "CtssPassDesc::default() writing a storage buffer, over TEST_FIELD_WGSL \
             (a sphere on a plane); compile your own field with `subcone shaders --ctss-field`",
        ),
        named(
            ctss(TEST_FIELD_WGSL, &CtssPassDesc::default())?,
            "testfield-texture",
            "CtssPassDesc::default(): one cone per pixel into an Rgba16Float storage texture, \
             over TEST_FIELD_WGSL",
        ),
        named(
            fxaa(&FxaaPassDesc::default())?,
            "default",
            "FxaaPassDesc::default(): FXAA 3.11 quality preset from a unorm texture, \
             Rgba16Float output",
        ),
        named(
            taa(&TaaPassDesc::default())?,
            "default",
            "TaaPassDesc::default(): Karis 2014 with variance clipping, linear resolve, \
             Rgba16Float output",
        ),
        named(
            taa(&TaaPassDesc::default().with_settings(TaaSettings {
                depth_dilation: DepthDilation::NearestLargest,
                ..TaaSettings::default()
            }))?,
            "depth-dilation",
            "The default with a depth input (taa_depth_tex, after the history): each pixel \
             takes the motion vector of the nearest depth of its 3×3 neighbourhood, reversed \
             Z (taa_params.depth_dilation 2; write 1 for a depth where smaller is nearer)",
        ),
    ])
}
