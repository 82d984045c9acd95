//! [`SraaPass`]: SRAA's antialiasing pass (Chiu et al., *Subpixel
//! Reconstruction Antialiasing for Ray Tracing*, §3, the paper's pass 2) over
//! a host renderer's textures.
//!
//! SRAA shades one sample per pixel and reconstructs four geometric
//! subsamples per pixel from the shaded samples of the 3×3 neighbourhood,
//! each weighted by how alike its geometry is (eq. 1: depth and normal;
//! eq. 2: the same shadow state per light), then box-filters the four
//! (`subcone_kernels::sraa::resolve_pixel`). The four subsamples lie at
//! [`subcone_kernels::sraa::SUBPIXEL_OFFSETS`] from the pixel centre,
//! `(−1/8, −3/8), (3/8, −1/8), (−3/8, 1/8), (1/8, 3/8)` pixels (x right,
//! y down): the standard 4x MSAA sample pattern of Vulkan, Metal and D3D,
//! sample `k` at offset `k`. So a host's 4x multisampled depth + normal
//! prepass already holds SRAA's geometric subsamples.
//!
//! The maths is the kernels' WGSL (`subcone_kernels::sraa::WGSL` and the
//! reconstruction loop, `subcone_kernels::sraa::RECONSTRUCT_WGSL`); this
//! module binds the host's textures to it (`sraa.wgsl`).

use subcone_kernels::passes::MAX_LIGHTS;
use subcone_kernels::sraa::{ResolveSpace, ShadedPosition, SraaParams};

use crate::bind::{self, check_buffer, required, Bound, Expect, Group, PassPipeline, Rect};
use crate::bind::{
    Buffer, CommandEncoder, ComputePassTimestampWrites, Device, Queue, TextureFormat,
    TextureSampleType, TextureUsages, TextureView, TextureViewDimension,
};
use crate::PassError;

pub(crate) const SRAA_WGSL: &str = include_str!("sraa.wgsl");

/// The SRAA reconstruction loop every GPU resolve shares ([`SraaPass`]
/// and the wgpu backend's own), `subcone_sraa_reconstruct_run`: the
/// kernels' WGSL twin of `sraa::reconstruct_layers` (with the albedo gate,
/// `sraa::reconstruct_layers_material`), re-exported from
/// [`subcone_kernels::sraa::RECONSTRUCT_WGSL`], whose documentation lists
/// the hooks the including shader defines. `sraa.wgsl` defines them over
/// the host's textures.
pub use subcone_kernels::sraa::RECONSTRUCT_WGSL;

/// The pass's constants; `SraaFrame` in `sraa.wgsl` (80 bytes).
pub(crate) use subcone_kernels::uniforms::SraaFrame;

/// How a shader declares a hardware depth texture ([`DepthKind::Hardware`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum DepthBinding {
    /// A depth texture (`texture_depth_*`), as wgpu binds it.
    Depth,
    /// A float texture whose `.x` is the depth: what GLSL reads, since it
    /// has no texel fetch from a depth (shadow) sampler and naga's GLSL
    /// back end refuses `textureLoad` of a depth texture. Vulkan and OpenGL
    /// bind a depth image to a float sampler, depth in the red channel.
    Float,
}

/// How the four geometric subsamples of a pixel are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeometryLayout {
    /// A 4x multisampled depth texture and a 4x multisampled normal texture
    /// (a host's MSAA prepass): sample `k` is subsample `k`, at
    /// `SUBPIXEL_OFFSETS[k]` (the standard 4x pattern; the crate's test
    /// `msaa_sample_positions` measures it on the device).
    Multisampled,
    /// Two one-sample 2D array textures of exactly 4 layers, depth and
    /// normal: layer `k` is subsample `k`, rendered with the projection
    /// shifted by `SUBPIXEL_OFFSETS[k]`.
    Layers,
    /// One one-sample `Rgba32Float` 2D array of 4 layers, normal in `.xyz`
    /// and linear view depth in `.w` (negative where nothing was drawn): the
    /// layout `subcone-wgpu` rasterises. Needs [`DepthKind::LinearView`] and
    /// [`NormalEncoding::Signed`]; no separate normal texture.
    Packed,
    /// Storage buffers instead of textures, read with
    /// [`SraaPass::encode_buffers`] ([`SraaBuffers`]): every geometry is
    /// the kernels' `subcone_kernels::sraa::Geometry` (`subcone_Geometry`
    /// in WGSL, 16 bytes: a unit normal facing the eye, then linear view
    /// depth, `+inf` a miss), taken as it is stored (not renormalised), and
    /// the shaded samples' geometry is an input of its own wherever the
    /// preset shades. The layout of a renderer that traces its samples
    /// into buffers (`subcone-wgpu`'s SRAA-RT). Needs
    /// [`DepthKind::LinearView`] and [`NormalEncoding::Signed`].
    Buffers,
}

/// How depth is stored, fixed for the pass's life (it selects the binding
/// type and how a depth is read): the one depth convention of a
/// [`SraaPass`]. The projection of hardware depth, which changes from frame
/// to frame (a jittered or moving camera), is [`SraaInputs::projection`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthKind {
    /// A colour texture (e.g. `R32Float`) of linear view depth: the distance
    /// from the eye along the view direction, `> 0`; `0`, negative or
    /// non-finite values are a miss (nothing drawn).
    LinearView,
    /// A depth texture (`Depth32Float`, `Depth24Plus`, …) of hardware depth
    /// `d` written through the frame's projection `P`
    /// ([`SraaInputs::projection`]: column-major,
    /// `glam::Mat4::to_cols_array_2d`, clip = P · view, depth range 0..1,
    /// right- or left-handed). View depth is
    /// `|(m32 − d·m33) / (d·m23 − m22)|` (`m[c][r]`), which inverts
    /// perspective projections with forward or reversed Z and finite or
    /// infinite far planes, and orthographic ones. The projection's
    /// `m[0][2]` and `m[1][2]` must be 0 (no x or y in clip z), as in every
    /// standard projection, jittered ones included.
    Hardware {
        /// The depth of a sample nothing was drawn at (the clear value):
        /// `0.0` for reversed Z, `1.0` for forward Z. A miss.
        miss: f32,
    },
}

impl DepthKind {
    fn is_hardware(&self) -> bool {
        matches!(self, DepthKind::Hardware { .. })
    }
}

/// How normals are stored. Any space (world or view) will do, the same for
/// every input; normals must face the eye (flip back faces), as SRAA's
/// geometry does. They are normalised after decoding; a zero normal is
/// allowed (it is dissimilar to every other).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalEncoding {
    /// `.xyz` is the normal, components in `[−1, 1]` (a float or snorm format).
    Signed,
    /// `.xyz` is `normal · 0.5 + 0.5` (a unorm format such as `Rgba8Unorm` or
    /// `Rgb10a2Unorm`).
    Unsigned,
}

/// The configuration of a [`SraaPass`]: what the host renders and how it
/// stores it. Fixed for the pass's life (it selects the pipeline).
///
/// Start from a preset ([`SraaPassDesc::msaa`], [`SraaPassDesc::packed`])
/// and change what differs with the `with_` methods (or assign the public
/// fields): the struct is `#[non_exhaustive]`, so a field added in a later
/// release, with its default in the presets, breaks no host.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SraaPassDesc {
    /// Lights whose shadows gate the reconstruction (SRAA eq. 2), at most
    /// `subcone_kernels::passes::MAX_LIGHTS` (8). With 0, the shaded colour
    /// is one layer and nothing is gated (SRAA's eq. 1 alone); with `L > 0`
    /// the host supplies `1 + L` colour layers (layer 0 what no shadow
    /// decides: emission, ambient; layer `1 + l` light `l`'s direct
    /// contribution) and shadow bits ([`SraaInputs::shadows`]).
    pub lights: u32,
    /// Secondary shading (mirror reflections, SRAA-RT §3.3) reconstructed
    /// on the secondary hits' own geometry ([`SecondaryInputs`]): the colour
    /// then has twice the layers, the primary group's `1 + L` followed by
    /// the secondary group's `1 + L` (each weighted by the mirror's
    /// reflectance by the host), and a subsample's secondary layers are
    /// added to its primary ones where it sees a mirror.
    pub secondary: bool,
    /// The material gate (§4.1, Fig. 6; `sraa::material_gated_weight`): a
    /// neighbour whose albedo differs from the subsample's by more than
    /// `sraa::ALBEDO_TOLERANCE` is not used. Needs [`SraaInputs::albedo`].
    pub albedo_gate: bool,
    /// The weights' preset: `SraaParams::TUNED` (the default, shaded sample
    /// at the pixel centre) or `SraaParams::PAPER` (§3.1's σz = 10,
    /// σn = 0.25, shaded sample on subsample `SHADED_SUBSAMPLE`). Where it
    /// puts the shaded sample decides where the host shades: at
    /// `SUBPIXEL_OFFSETS[SHADED_SUBSAMPLE]` (its geometry is then MSAA
    /// sample 0) or at the pixel centre (then the host also supplies
    /// [`CentreGeometry`]).
    pub params: SraaParams,
    /// How the subsamples are stored.
    pub geometry: GeometryLayout,
    /// How depth is stored (for the subsamples and the centre geometry).
    pub depth: DepthKind,
    /// How normals are stored.
    pub normal: NormalEncoding,
    /// The output texture's format: `Rgba8Unorm`, `Rgba16Float` or
    /// `Rgba32Float` (written as a storage texture, linear values, alpha 1).
    pub output_format: TextureFormat,
    /// The space each pixel's four reconstructed subsamples are averaged
    /// in: `ResolveSpace::Linear` (the default in every preset: the box of
    /// `sraa::resolve_pixel`, SRAA §3) or `ResolveSpace::ToneMapped {
    /// exposure }` (`sraa::resolve_pixel_tone_mapped`: weights
    /// `1 / (1 + luma(c · exposure))`, Karis 2014, *High Quality Temporal
    /// Supersampling*), for HDR colour that is tone mapped after the pass,
    /// so that an edge beside a highlight is antialiased as it is shown.
    /// The output stays linear radiance either way. The exposure must be
    /// `> 0` and finite ([`PassError::Exposure`] from [`SraaPass::new`]).
    pub resolve: ResolveSpace,
}

impl SraaPassDesc {
    /// The configuration for a host's 4x MSAA prepass of reversed-Z
    /// hardware depth (`DepthKind::Hardware { miss: 0.0 }`) and signed
    /// normals: no lights, no gate, `SraaParams::PAPER`, writing
    /// `Rgba16Float`.
    ///
    /// It keeps the paper's preset, whose shaded sample lies on subsample 0
    /// (`SHADED_SUBSAMPLE`), rather than the tuned one
    /// (`SraaParams::TUNED`), which shades the pixel centre: a plain MSAA
    /// prepass has no sample at the pixel centre, so the tuned preset would
    /// need the host to render the centre's geometry in an extra pass
    /// ([`CentreGeometry`]). Subsample 0's geometry is MSAA sample 0, which
    /// the prepass already holds (SRAA §3: the shaded sample is one of the
    /// geometric subsamples).
    pub fn msaa() -> Self {
        SraaPassDesc {
            lights: 0,
            secondary: false,
            albedo_gate: false,
            params: SraaParams::PAPER,
            geometry: GeometryLayout::Multisampled,
            depth: DepthKind::Hardware { miss: 0.0 },
            normal: NormalEncoding::Signed,
            output_format: TextureFormat::Rgba16Float,
            resolve: ResolveSpace::Linear,
        }
    }

    /// The configuration for [`GeometryLayout::Packed`] layers (what
    /// `subcone-wgpu` rasterises): linear view depth and signed normals in
    /// one `Rgba32Float` array, `params`, no lights, no gate, writing
    /// `Rgba32Float`.
    pub fn packed(params: SraaParams) -> Self {
        SraaPassDesc {
            lights: 0,
            secondary: false,
            albedo_gate: false,
            params,
            geometry: GeometryLayout::Packed,
            depth: DepthKind::LinearView,
            normal: NormalEncoding::Signed,
            output_format: TextureFormat::Rgba32Float,
            resolve: ResolveSpace::Linear,
        }
    }

    /// The configuration for [`GeometryLayout::Buffers`] (geometry as the
    /// kernels' `Geometry` in storage buffers): linear view depth, signed
    /// normals, `params`, no lights, no gate. `output_format` is not read:
    /// the output is a buffer ([`SraaBuffers::output`]).
    pub fn buffers(params: SraaParams) -> Self {
        SraaPassDesc {
            geometry: GeometryLayout::Buffers,
            ..Self::packed(params)
        }
    }

    with_setters! {
        /// With `lights` lights gating the reconstruction ([`Self::lights`]).
        with_lights(lights: u32);
        /// With or without secondary shading ([`Self::secondary`]).
        with_secondary(secondary: bool);
        /// With or without the material gate ([`Self::albedo_gate`]).
        with_albedo_gate(albedo_gate: bool);
        /// With the weights' preset `params` ([`Self::params`]).
        with_params(params: SraaParams);
        /// With the subsamples stored as `geometry` ([`Self::geometry`]).
        with_geometry(geometry: GeometryLayout);
        /// With depth stored as `depth` ([`Self::depth`]).
        with_depth(depth: DepthKind);
        /// With normals stored as `normal` ([`Self::normal`]).
        with_normal(normal: NormalEncoding);
        /// Writing `output_format` ([`Self::output_format`]).
        with_output_format(output_format: TextureFormat);
        /// Averaging the subsamples in `resolve` ([`Self::resolve`]).
        with_resolve(resolve: ResolveSpace);
    }

    /// Colour layers: `1 + lights`, twice that with secondary shading.
    fn color_layers(&self) -> u32 {
        (1 + self.lights) * if self.secondary { 2 } else { 1 }
    }

    fn shaded_at_centre(&self) -> bool {
        self.params.shaded_position() == ShadedPosition::Centre
    }

    /// Whether the shaded sample's geometry is an input of its own (the
    /// centre's, or every shaded sample's in buffers), not subsample
    /// `SHADED_SUBSAMPLE`'s.
    fn shaded_given(&self) -> bool {
        self.shaded_at_centre() || self.geometry == GeometryLayout::Buffers
    }
}

/// Geometry at the pixel centres (one sample per pixel, the same size as
/// the output), needed when the preset shades the pixel centre
/// (`ShadedPosition::Centre`, e.g. `SraaParams::TUNED`): the geometry of
/// the shaded sample. Depth as [`SraaPassDesc::depth`], normals as
/// [`SraaPassDesc::normal`].
#[derive(Clone, Copy, Debug)]
pub struct CentreGeometry<'a> {
    /// Depth at the pixel centres.
    pub depth: &'a TextureView,
    /// Normals at the pixel centres.
    pub normal: &'a TextureView,
}

/// One input read at each pixel's shaded sample and at its four geometric
/// subsamples: `R` is a `&wgpu::TextureView` in [`SraaInputs`] and
/// [`SecondaryInputs`], a `&wgpu::Buffer` in [`SraaBuffers`] and
/// [`SecondaryBuffers`]. The role that holds it says what it stores and
/// how its subsamples are laid out.
#[derive(Clone, Copy, Debug)]
pub struct Samples<R> {
    /// At the shaded sample of each pixel: one sample and one layer of a
    /// texture, one element per pixel of a buffer.
    pub shaded: R,
    /// At each geometric subsample: four per pixel of a buffer (subsample
    /// `k` of pixel `j`, row-major, at `4j + k`); a texture's layout is
    /// its role's.
    pub subsamples: R,
}

/// The secondary hits (SRAA-RT §3.3: where a mirror reflects the ray) for
/// [`SraaPassDesc::secondary`]. Depth is always the linear length of the
/// reflected path (eye to mirror plus mirror to hit), in a float colour
/// format (e.g. `R32Float`), whatever the primary depth's kind: a value
/// `> 0` and finite is a hit; `0` or `+inf` a miss (the reflection left the
/// scene: its layers hold the background); negative or NaN means no mirror
/// at that sample (its secondary layers are not used). Normals as
/// [`SraaPassDesc::normal`].
#[derive(Clone, Copy, Debug)]
pub struct SecondaryInputs<'a> {
    /// At the shaded sample of each pixel (one sample, one layer).
    pub shaded_depth: &'a TextureView,
    /// Normals at the shaded sample.
    pub shaded_normal: &'a TextureView,
    /// At each geometric subsample: 4x multisampled for
    /// [`GeometryLayout::Multisampled`], else a 4-layer array.
    pub subsample_depth: &'a TextureView,
    /// Normals at each geometric subsample, in the same layout.
    pub subsample_normal: &'a TextureView,
    /// The secondary hits' shadow bits, as [`SraaInputs::shadows`]:
    /// required exactly when `lights > 0`.
    pub shadows: Option<Samples<&'a TextureView>>,
}

/// The geometric subsamples of one frame, in the desc's
/// [`GeometryLayout`]: a depth and a normal view
/// ([`GeometryLayout::Multisampled`], [`GeometryLayout::Layers`]), or the
/// one packed view ([`GeometryLayout::Packed`]).
#[derive(Clone, Copy, Debug)]
pub enum SubsampleGeometry<'a> {
    /// Depth (as [`SraaPassDesc::depth`]) and normals (as
    /// [`SraaPassDesc::normal`]) in two textures.
    Separate {
        /// Subsample depth.
        depth: &'a TextureView,
        /// Subsample normals.
        normal: &'a TextureView,
    },
    /// Normals in `.xyz` and linear view depth in `.w` of one texture.
    Packed(&'a TextureView),
}

/// One frame's views for [`SraaPass::encode`]. Each view is of a whole
/// texture of one mip level (`Texture::create_view(&Default::default())`
/// gives the right view of every input; of a depth-stencil format, its
/// `TextureAspect::DepthOnly`); the sizes, formats, sample counts, layer
/// counts and usages are checked on the views' textures
/// (`TextureView::texture`). Every texture is the output's size (with
/// [`SraaPass::encode_rect`]: any size that holds the rect), 2D, and has
/// `TEXTURE_BINDING`; the output has `STORAGE_BINDING`.
#[derive(Clone, Copy, Debug)]
pub struct SraaInputs<'a> {
    /// The geometric subsamples.
    pub geometry: SubsampleGeometry<'a>,
    /// The projection this frame's hardware depth was rendered with
    /// (column-major, `glam::Mat4::to_cols_array_2d`; see
    /// [`DepthKind::Hardware`]). Only its z and w rows are read, and only
    /// with [`DepthKind::Hardware`]; a pass of linear view depth ignores it.
    pub projection: [[f32; 4]; 4],
    /// Geometry at the pixel centres: required exactly when the preset
    /// shades the pixel centre.
    pub centre: Option<CentreGeometry<'a>>,
    /// The shaded colour, linear RGB in `.xyz`, one sample per pixel, shaded
    /// where the preset puts the shaded sample (see
    /// [`SraaPassDesc::params`]). With 0 lights and no secondary shading
    /// one layer (a 2D texture); else a 2D array of exactly `1 + L` layers,
    /// `2·(1 + L)` with secondary shading.
    pub color: &'a TextureView,
    /// Shadow states for eq. 2, required exactly when `lights > 0`:
    /// `R32Uint`, bit `l` set where light `l`'s shadow ray is blocked; the
    /// subsamples a one-sample 2D array of exactly 4 layers, layer `k`
    /// subsample `k`, whatever the geometry layout (integer formats cannot
    /// be multisampled everywhere).
    pub shadows: Option<Samples<&'a TextureView>>,
    /// Diffuse albedo for the material gate, required exactly when the
    /// albedo gate is on: `.xyz` linear RGB, any float format; the
    /// subsamples in the geometry's layout (4x multisampled for
    /// [`GeometryLayout::Multisampled`], else a 4-layer array).
    pub albedo: Option<Samples<&'a TextureView>>,
    /// The secondary hits: required exactly when the desc has `secondary`.
    pub secondary: Option<SecondaryInputs<'a>>,
    /// Where the antialiased colour is written (level 0, layer 0).
    pub output: &'a TextureView,
}

/// The secondary hits (§3.3) in buffers, for [`SraaBuffers`]: geometry as
/// `subcone_Geometry` (depth the reflected path's length, `+inf` where the
/// reflection left the scene, NaN where there is no mirror).
#[derive(Clone, Copy, Debug)]
pub struct SecondaryBuffers<'a> {
    /// The secondary hits' geometry.
    pub geometry: Samples<&'a Buffer>,
    /// The secondary hits' shadow bits, as [`SraaBuffers::shadows`]:
    /// required exactly when `lights > 0`.
    pub shadows: Option<Samples<&'a Buffer>>,
}

/// One frame's storage buffers for [`SraaPass::encode_buffers`]
/// ([`GeometryLayout::Buffers`]). Pixel `j` is `y · width + x`; each
/// buffer needs `STORAGE` usage and at least the bytes its role takes for
/// `size` (a [`PassError::BufferSize`] otherwise). The roles are those of
/// [`SraaInputs`], each required under the same condition.
#[derive(Clone, Copy, Debug)]
pub struct SraaBuffers<'a> {
    /// The frame's `(width, height)`.
    pub size: (u32, u32),
    /// The geometry, `array<subcone_Geometry>`: of the shaded samples
    /// (wherever the preset shades) and of the geometric subsamples
    /// (subsample `k` at `SUBPIXEL_OFFSETS[k]`).
    pub geometry: Samples<&'a Buffer>,
    /// The shaded colour's layers, `array<vec4<f32>>` (`.xyz`), layer `l`
    /// of pixel `j` at `j · layers + l` (`1 + L` layers, twice that with
    /// secondary shading).
    pub color: &'a Buffer,
    /// Shadow bits, `array<u32>` (bit `l` set where light `l`'s shadow
    /// ray is blocked): required exactly when `lights > 0`.
    pub shadows: Option<Samples<&'a Buffer>>,
    /// Albedo, `array<vec4<f32>>` (linear RGB in `.xyz`): required exactly
    /// when the albedo gate is on.
    pub albedo: Option<Samples<&'a Buffer>>,
    /// The secondary hits: required exactly when the desc has `secondary`.
    pub secondary: Option<SecondaryBuffers<'a>>,
    /// Where the antialiased colour is written, `array<vec4<f32>>`, one per
    /// pixel (alpha 1).
    pub output: &'a Buffer,
}

/// The secondary hits' loaders of a pass without them (never read).
const NO_SECONDARY_LOADERS: &str =
    "fn sraa_load_sec_shaded(p: vec2<i32>) -> vec4<f32> { return vec4<f32>(0.0); }\n\
     fn sraa_load_sec_sub(p: vec2<i32>, k: u32) -> vec4<f32> { return vec4<f32>(0.0); }\n";

/// The albedo loaders of a pass without the albedo gate (never read).
const NO_ALBEDO_LOADERS: &str =
    "fn sraa_load_shaded_albedo(p: vec2<i32>) -> vec3<f32> { return vec3<f32>(0.0); }\n\
     fn sraa_load_sub_albedo(p: vec2<i32>, k: u32) -> vec3<f32> { return vec3<f32>(0.0); }\n";

/// The shadow loaders of group `g` (`""` primary, `"sec_"` secondary)
/// without shadow bits: every sample lit (eq. 2's gate always passes).
fn no_shadow_loaders(g: &str) -> String {
    format!(
        "fn sraa_load_{g}shaded_shadow(p: vec2<i32>) -> u32 {{ return 0u; }}\n\
         fn sraa_load_{g}sub_shadow(p: vec2<i32>, k: u32) -> u32 {{ return 0u; }}\n"
    )
}

impl Samples<&Buffer> {
    /// Check both buffers (named `[shaded, subsamples]`) for `pixels`
    /// pixels: one element of `element` bytes per pixel at the shaded
    /// sample, four at the subsamples.
    fn check(
        &self,
        [shaded, subsamples]: [&'static str; 2],
        pixels: u64,
        element: u64,
    ) -> Result<(), PassError> {
        check_buffer(shaded, self.shaded, pixels, element)?;
        check_buffer(subsamples, self.subsamples, 4 * pixels, element)
    }
}

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

/// What the input textures of one frame must be, for one configuration
/// and the frame's `size` ([`SraaPass::check`]): that size exactly, or,
/// with a `rect`, any size the rect lies inside.
struct InputRules<'a> {
    desc: &'a SraaPassDesc,
    size: (u32, u32),
    rect: Option<&'a Rect>,
}

impl InputRules<'_> {
    /// Check `v` against `e` and the rules' size or rect.
    fn check(&self, v: &TextureView, e: &Expect) -> Result<(), PassError> {
        bind::check_region(v, e, self.rect)
    }

    /// A texture at the geometric subsamples, in the desc's geometry
    /// layout: 4x multisampled, or a one-sample array of 4 layers.
    fn sub(&self, what: &'static str) -> Expect {
        let ms = self.desc.geometry == GeometryLayout::Multisampled;
        Expect {
            what,
            size: self.size,
            samples: if ms { 4 } else { 1 },
            layers: if ms { 1 } else { 4 },
            usage: TextureUsages::TEXTURE_BINDING,
        }
    }

    /// A one-sample texture of `layers` layers.
    fn one(&self, what: &'static str, layers: u32) -> Expect {
        Expect {
            what,
            size: self.size,
            samples: 1,
            layers,
            usage: TextureUsages::TEXTURE_BINDING,
        }
    }

    /// A float texture of the geometric subsamples ([`Self::sub`]).
    fn float_sub(&self, what: &'static str, v: &TextureView) -> Result<(), PassError> {
        self.check(v, &self.sub(what))?;
        bind::check_float_color(what, v)
    }

    /// A one-sample, one-layer float texture.
    fn float_one(&self, what: &'static str, v: &TextureView) -> Result<(), PassError> {
        self.check(v, &self.one(what, 1))?;
        bind::check_float_color(what, v)
    }

    /// A depth texture's format for the desc's [`DepthKind`].
    fn depth_format(&self, what: &'static str, v: &TextureView) -> Result<(), PassError> {
        let format = v.texture().format();
        let ok = match self.desc.depth {
            DepthKind::Hardware { .. } => format.has_depth_aspect(),
            DepthKind::LinearView => bind::is_float_color(format),
        };
        if ok {
            Ok(())
        } else {
            Err(PassError::Format {
                what,
                found: format,
                expected: match self.desc.depth {
                    DepthKind::Hardware { .. } => "a depth format (DepthKind::Hardware)",
                    DepthKind::LinearView => "a float colour format such as R32Float",
                },
            })
        }
    }

    /// The subsamples' depth and normals: one packed texture, or a depth
    /// and a normal texture.
    fn subsample_geometry(&self, inputs: &SraaInputs<'_>) -> Result<(), PassError> {
        let packed = self.desc.geometry == GeometryLayout::Packed;
        match (packed, inputs.geometry) {
            (true, SubsampleGeometry::Packed(p)) => self.float_sub("packed subsamples", p),
            (false, SubsampleGeometry::Separate { depth, normal }) => {
                self.check(depth, &self.sub("subsample depth"))?;
                self.depth_format("subsample depth", depth)?;
                self.float_sub("subsample normal", normal)
            }
            (true, SubsampleGeometry::Separate { .. }) => Err(PassError::Config(
                "SubsampleGeometry::Separate given to a pass built for GeometryLayout::Packed"
                    .into(),
            )),
            (false, SubsampleGeometry::Packed(_)) => Err(PassError::Config(
                "SubsampleGeometry::Packed given to a pass built for separate depth and normals"
                    .into(),
            )),
        }
    }

    /// The centre geometry (given exactly when the preset shades the pixel
    /// centre).
    fn centre_geometry(&self, c: &CentreGeometry<'_>) -> Result<(), PassError> {
        self.check(c.depth, &self.one("centre depth", 1))?;
        self.depth_format("centre depth", c.depth)?;
        self.float_one("centre normal", c.normal)
    }

    /// A pair of shadow textures: `R32Uint`, one layer at the shaded
    /// sample, four at the subsamples.
    fn shadows(&self, s: &Samples<&TextureView>) -> Result<(), PassError> {
        for (what, t, layers) in [
            ("shaded shadows", s.shaded, 1),
            ("subsample shadows", s.subsamples, 4),
        ] {
            self.check(t, &self.one(what, layers))?;
            if t.texture().format() != TextureFormat::R32Uint {
                return Err(PassError::Format {
                    what,
                    found: t.texture().format(),
                    expected: "R32Uint",
                });
            }
        }
        Ok(())
    }

    /// The secondary hits (§3.3; given exactly when the desc has
    /// `secondary`), with their shadows exactly when it has lights.
    fn secondary(&self, s: &SecondaryInputs<'_>) -> Result<(), PassError> {
        self.float_one("secondary shaded depth", s.shaded_depth)?;
        self.float_one("secondary shaded normal", s.shaded_normal)?;
        self.float_sub("secondary subsample depth", s.subsample_depth)?;
        self.float_sub("secondary subsample normal", s.subsample_normal)?;
        let shadows = required(
            s.shadows.as_ref(),
            self.desc.lights > 0,
            "secondary shadow textures (lights > 0)",
            "secondary shadow textures (0 lights)",
        )?;
        shadows.map_or(Ok(()), |sh| self.shadows(sh))
    }

    /// The albedo textures (given exactly when the albedo gate is on).
    fn albedo(&self, a: &Samples<&TextureView>) -> Result<(), PassError> {
        self.float_one("shaded albedo", a.shaded)?;
        self.float_sub("subsample albedo", a.subsamples)
    }
}

/// SRAA's antialiasing pass on the host's device. See the module docs of
/// the crate and [`SraaPassDesc`] for the conventions.
///
/// Built once (`new` compiles the pipeline and makes the uniform buffer),
/// encoded every frame: after the first frame with given views, `encode`
/// creates no buffer, texture, bind group or pipeline (it writes the frame's
/// constants into a slot of its uniform buffer, [`crate::UNIFORM_SLOTS`],
/// and reuses the bind group of those views, [`crate::BIND_GROUP_CACHE`]).
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

fn float_sample() -> TextureSampleType {
    TextureSampleType::Float { filterable: false }
}

impl SraaPass {
    /// Build the pass (compile its pipeline) on the host's device. Refuses
    /// more than `MAX_LIGHTS` lights, an output format
    /// it cannot write, and [`GeometryLayout::Packed`] with hardware depth
    /// or unsigned normals.
    pub fn new(device: &Device, desc: &SraaPassDesc) -> Result<Self, PassError> {
        let source = Self::source(desc)?;
        let group = Self::group(desc)?;
        let source = [source, group.declarations()].concat();
        let pipeline = PassPipeline::new(
            device,
            "subcone sraa resolve",
            group,
            source,
            None,
            "sraa_resolve_main",
        )?;
        Ok(SraaPass {
            desc: *desc,
            pipeline,
        })
    }

    /// The configuration.
    pub fn desc(&self) -> &SraaPassDesc {
        &self.desc
    }

    /// The bindings of [`GeometryLayout::Buffers`], in order.
    fn buffer_group(desc: &SraaPassDesc) -> Group {
        use crate::bind::BufferAccess::{Read, ReadWrite};
        let mut g = Group::default();
        g.ring_uniform::<SraaFrame>("frame", "SraaFrame");
        let geo = "array<subcone_Geometry>";
        let (words, float4) = ("array<u32>", "array<vec4<f32>>");
        let lit = desc.lights > 0;
        // The roles read at the shaded samples and at the subsamples
        // ([`Samples`]), each where the desc reads it.
        for (read, [shaded, sub], ty) in [
            (true, ["shaded_geo", "sub_geo"], geo),
            (lit, ["shaded_shadow", "sub_shadow"], words),
            (desc.secondary, ["sec_shaded_geo", "sec_sub_geo"], geo),
            (
                desc.secondary && lit,
                ["sec_shaded_shadow", "sec_sub_shadow"],
                words,
            ),
            (desc.albedo_gate, ["shaded_albedo", "sub_albedo"], float4),
        ] {
            if read {
                g.buffer(shaded, ty, Read);
                g.buffer(sub, ty, Read);
            }
        }
        g.buffer("color", float4, Read);
        g.buffer("sraa_output", float4, ReadWrite);
        g
    }

    /// The bindings, in order.
    pub(crate) fn group(desc: &SraaPassDesc) -> Result<Group, PassError> {
        Self::group_with(desc, DepthBinding::Depth)
    }

    /// The bindings, hardware depth declared as `depth`.
    pub(crate) fn group_with(desc: &SraaPassDesc, depth: DepthBinding) -> Result<Group, PassError> {
        use TextureViewDimension::{D2Array, D2};
        if desc.geometry == GeometryLayout::Buffers {
            return Ok(Self::buffer_group(desc));
        }
        let mut g = Group::default();
        g.ring_uniform::<SraaFrame>("frame", "SraaFrame");
        let hw = desc.depth.is_hardware();
        let (dim, ms) = match desc.geometry {
            GeometryLayout::Multisampled => (D2, true),
            _ => (D2Array, false),
        };
        let depth_sample = if hw && depth == DepthBinding::Depth {
            TextureSampleType::Depth
        } else {
            float_sample()
        };
        g.texture("sub_depth", depth_sample, dim, ms);
        if desc.geometry != GeometryLayout::Packed {
            g.texture("sub_normal", float_sample(), dim, ms);
        }
        if desc.shaded_at_centre() {
            g.texture("centre_depth", depth_sample, D2, false);
            g.texture("centre_normal", float_sample(), D2, false);
        }
        if desc.color_layers() == 1 {
            g.texture("color", float_sample(), D2, false);
        } else {
            g.texture("color", float_sample(), D2Array, false);
        }
        let u = TextureSampleType::Uint;
        if desc.lights > 0 {
            g.texture("shaded_shadow", u, D2, false);
            g.texture("sub_shadow", u, D2Array, false);
        }
        if desc.secondary {
            let f = float_sample();
            g.texture("sec_shaded_depth", f, D2, false);
            g.texture("sec_shaded_normal", f, D2, false);
            g.texture("sec_sub_depth", f, dim, ms);
            g.texture("sec_sub_normal", f, dim, ms);
            if desc.lights > 0 {
                g.texture("sec_shaded_shadow", u, D2, false);
                g.texture("sec_sub_shadow", u, D2Array, false);
            }
        }
        if desc.albedo_gate {
            g.texture("shaded_albedo", float_sample(), D2, false);
            g.texture("sub_albedo", float_sample(), dim, ms);
        }
        g.storage_texture("sraa_output", desc.output_format)?;
        Ok(g)
    }

    /// The shader: the kernels, the generated header (constants, loaders),
    /// `sraa.wgsl`; the declarations are appended by [`Self::new`].
    pub(crate) fn source(desc: &SraaPassDesc) -> Result<String, PassError> {
        Self::source_with(desc, DepthBinding::Depth)
    }

    /// The shader, hardware depth read as `depth` declares it.
    pub(crate) fn source_with(
        desc: &SraaPassDesc,
        depth: DepthBinding,
    ) -> Result<String, PassError> {
        if desc.lights as usize > MAX_LIGHTS {
            return Err(PassError::Config(format!(
                "{} lights: SRAA's eq. 2 gates at most {MAX_LIGHTS}",
                desc.lights
            )));
        }

        bind::check_output_format(desc.output_format)?;
        if let ResolveSpace::ToneMapped { exposure } = desc.resolve {
            if !desc.resolve.is_valid() {
                return Err(PassError::Exposure {
                    found_bits: exposure.to_bits(),
                });
            }
        }
        let buffers = desc.geometry == GeometryLayout::Buffers;
        if matches!(
            desc.geometry,
            GeometryLayout::Packed | GeometryLayout::Buffers
        ) && (desc.depth != DepthKind::LinearView || desc.normal != NormalEncoding::Signed)
        {
            return Err(PassError::Config(format!(
                "GeometryLayout::{:?} holds linear view depth and signed normals",
                desc.geometry
            )));
        }
        let hw = desc.depth.is_hardware();
        let mut h = format!(
            "const LIGHTS: u32 = {}u;\nconst MATERIAL: bool = {};\nconst HARDWARE_DEPTH: bool = {hw};\n\
             const UNSIGNED_NORMALS: bool = {};\nconst SHADED_GIVEN: bool = {};\n\
             const DECODED: bool = {buffers};\nconst SECONDARY: bool = {};\n\
             const TONE_MAPPED_RESOLVE: bool = {};\n",
            desc.lights,
            desc.albedo_gate,
            desc.normal == NormalEncoding::Unsigned,
            desc.shaded_given(),
            desc.secondary,
            matches!(desc.resolve, ResolveSpace::ToneMapped { .. }),
        );
        h += &if buffers {
            Self::buffer_loaders(desc)
        } else {
            Self::texture_loaders(desc, depth)
        };
        Ok([
            subcone_kernels::wgsl::PARAMS,
            subcone_kernels::sraa::WGSL,
            &h,
            SRAA_WGSL,
            RECONSTRUCT_WGSL,
        ]
        .concat())
    }

    /// The loaders of the texture layouts (see `sraa.wgsl`'s header).
    fn texture_loaders(desc: &SraaPassDesc, depth: DepthBinding) -> String {
        let packed = desc.geometry == GeometryLayout::Packed;
        let hw = desc.depth.is_hardware();
        let ms = desc.geometry == GeometryLayout::Multisampled;
        // textureLoad's trailing arguments: sample index, or layer and level.
        let sub_at = if ms { "i32(k)" } else { "i32(k), 0" };
        let scalar = if hw && depth == DepthBinding::Depth {
            ""
        } else {
            ".x"
        };
        let mut h = String::from(
            "fn sraa_store(p: vec2<i32>, c: vec4<f32>) { textureStore(sraa_output, p, c); }\n",
        );
        if packed {
            h += &format!(
                "fn sraa_load_sub(p: vec2<i32>, k: u32) -> vec4<f32> {{ return textureLoad(sub_depth, p, {sub_at}); }}\n"
            );
        } else {
            h += &format!(
                "fn sraa_load_sub(p: vec2<i32>, k: u32) -> vec4<f32> {{ return vec4<f32>(textureLoad(sub_normal, p, {sub_at}).xyz, textureLoad(sub_depth, p, {sub_at}){scalar}); }}\n"
            );
        }
        if desc.shaded_at_centre() {
            h += &format!(
                "fn sraa_load_shaded(p: vec2<i32>) -> vec4<f32> {{ return vec4<f32>(textureLoad(centre_normal, p, 0).xyz, textureLoad(centre_depth, p, 0){scalar}); }}\n"
            );
        } else {
            h += "fn sraa_load_shaded(p: vec2<i32>) -> vec4<f32> { return vec4<f32>(0.0); }\n";
        }
        if desc.color_layers() == 1 {
            h += "fn sraa_load_color(p: vec2<i32>, l: u32) -> vec3<f32> { return textureLoad(color, p, 0).xyz; }\n";
        } else {
            h += "fn sraa_load_color(p: vec2<i32>, l: u32) -> vec3<f32> { return textureLoad(color, p, i32(l), 0).xyz; }\n";
        }
        // Shadow bits of the primary (`g` empty) and secondary (`sec_`) hits.
        for g in ["", "sec_"] {
            if desc.lights > 0 && (g.is_empty() || desc.secondary) {
                h += &format!(
                    "fn sraa_load_{g}shaded_shadow(p: vec2<i32>) -> u32 {{ return textureLoad({g}shaded_shadow, p, 0).x; }}\n\
                     fn sraa_load_{g}sub_shadow(p: vec2<i32>, k: u32) -> u32 {{ return textureLoad({g}sub_shadow, p, i32(k), 0).x; }}\n"
                );
            } else {
                h += &no_shadow_loaders(g);
            }
        }
        if desc.secondary {
            h += &format!(
                "fn sraa_load_sec_shaded(p: vec2<i32>) -> vec4<f32> {{ return vec4<f32>(textureLoad(sec_shaded_normal, p, 0).xyz, textureLoad(sec_shaded_depth, p, 0).x); }}\n\
                 fn sraa_load_sec_sub(p: vec2<i32>, k: u32) -> vec4<f32> {{ return vec4<f32>(textureLoad(sec_sub_normal, p, {sub_at}).xyz, textureLoad(sec_sub_depth, p, {sub_at}).x); }}\n"
            );
        } else {
            h += NO_SECONDARY_LOADERS;
        }
        if desc.albedo_gate {
            h += &format!(
                "fn sraa_load_shaded_albedo(p: vec2<i32>) -> vec3<f32> {{ return textureLoad(shaded_albedo, p, 0).xyz; }}\n\
                 fn sraa_load_sub_albedo(p: vec2<i32>, k: u32) -> vec3<f32> {{ return textureLoad(sub_albedo, p, {sub_at}).xyz; }}\n"
            );
        } else {
            h += NO_ALBEDO_LOADERS;
        }
        h
    }

    /// The loaders of [`GeometryLayout::Buffers`]: pixel `p`'s element of
    /// each buffer ([`SraaBuffers`]), the geometry as stored.
    fn buffer_loaders(desc: &SraaPassDesc) -> String {
        let mut h = format!(
            "const SRAA_LAYERS: u32 = {}u;\n\
             fn sraa_pixel(p: vec2<i32>) -> u32 {{ return u32(p.y) * frame.width + u32(p.x); }}\n\
             fn sraa_load_sub(p: vec2<i32>, k: u32) -> vec4<f32> {{ let g = sub_geo[sraa_pixel(p) * 4u + k]; return vec4<f32>(g.normal, g.depth); }}\n\
             fn sraa_load_shaded(p: vec2<i32>) -> vec4<f32> {{ let g = shaded_geo[sraa_pixel(p)]; return vec4<f32>(g.normal, g.depth); }}\n\
             fn sraa_load_color(p: vec2<i32>, l: u32) -> vec3<f32> {{ return color[sraa_pixel(p) * SRAA_LAYERS + l].xyz; }}\n\
             fn sraa_store(p: vec2<i32>, c: vec4<f32>) {{ sraa_output[sraa_pixel(p)] = c; }}\n",
            desc.color_layers()
        );
        for g in ["", "sec_"] {
            if desc.lights > 0 && (g.is_empty() || desc.secondary) {
                h += &format!(
                    "fn sraa_load_{g}shaded_shadow(p: vec2<i32>) -> u32 {{ return {g}shaded_shadow[sraa_pixel(p)]; }}\n\
                     fn sraa_load_{g}sub_shadow(p: vec2<i32>, k: u32) -> u32 {{ return {g}sub_shadow[sraa_pixel(p) * 4u + k]; }}\n"
                );
            } else {
                h += &no_shadow_loaders(g);
            }
        }
        if desc.secondary {
            h += "fn sraa_load_sec_shaded(p: vec2<i32>) -> vec4<f32> { let g = sec_shaded_geo[sraa_pixel(p)]; return vec4<f32>(g.normal, g.depth); }\n\
                  fn sraa_load_sec_sub(p: vec2<i32>, k: u32) -> vec4<f32> { let g = sec_sub_geo[sraa_pixel(p) * 4u + k]; return vec4<f32>(g.normal, g.depth); }\n";
        } else {
            h += NO_SECONDARY_LOADERS;
        }
        if desc.albedo_gate {
            h += "fn sraa_load_shaded_albedo(p: vec2<i32>) -> vec3<f32> { return shaded_albedo[sraa_pixel(p)].xyz; }\n\
                  fn sraa_load_sub_albedo(p: vec2<i32>, k: u32) -> vec3<f32> { return sub_albedo[sraa_pixel(p) * 4u + k].xyz; }\n";
        } else {
            h += NO_ALBEDO_LOADERS;
        }
        h
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
}

#[cfg(test)]
pub(crate) fn test_source(desc: &SraaPassDesc) -> String {
    let group = SraaPass::group(desc).expect("valid desc");
    [
        SraaPass::source(desc).expect("valid desc"),
        group.declarations(),
    ]
    .concat()
}
