//! The configuration of a [`SraaPass`]: how the host stores
//! its geometry ([`GeometryLayout`], [`DepthKind`], [`NormalEncoding`]) and
//! what it renders ([`SraaPassDesc`]).
//!
//! [`SraaPass`]: super::SraaPass

use subcone_kernels::passes::MAX_LIGHTS;
use subcone_kernels::sraa::{ResolveSpace, ShadedPosition, SraaParams};

use crate::bind::{self, TextureFormat};
use crate::PassError;

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
    ///
    /// [`SraaPass::encode_buffers`]: super::SraaPass::encode_buffers
    /// [`SraaBuffers`]: super::SraaBuffers
    Buffers,
}

/// How depth is stored, fixed for the pass's life (it selects the binding
/// type and how a depth is read): the one depth convention of a
/// [`SraaPass`]. The projection of hardware depth, which changes from frame
/// to frame (a jittered or moving camera), is [`SraaInputs::projection`].
///
/// [`SraaPass`]: super::SraaPass
/// [`SraaInputs::projection`]: super::SraaInputs::projection
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
    ///
    /// [`SraaInputs::projection`]: super::SraaInputs::projection
    Hardware {
        /// The depth of a sample nothing was drawn at (the clear value):
        /// `0.0` for reversed Z, `1.0` for forward Z. A miss.
        miss: f32,
    },
}

impl DepthKind {
    pub(super) fn is_hardware(&self) -> bool {
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
///
/// [`SraaPass`]: super::SraaPass
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SraaPassDesc {
    /// Lights whose shadows gate the reconstruction (SRAA eq. 2), at most
    /// `subcone_kernels::passes::MAX_LIGHTS` (8). With 0, the shaded colour
    /// is one layer and nothing is gated (SRAA's eq. 1 alone); with `L > 0`
    /// the host supplies `1 + L` colour layers (layer 0 what no shadow
    /// decides: emission, ambient; layer `1 + l` light `l`'s direct
    /// contribution) and shadow bits ([`SraaInputs::shadows`]).
    ///
    /// [`SraaInputs::shadows`]: super::SraaInputs::shadows
    pub lights: u32,
    /// Secondary shading (mirror reflections, SRAA-RT §3.3) reconstructed
    /// on the secondary hits' own geometry ([`SecondaryInputs`]): the colour
    /// then has twice the layers, the primary group's `1 + L` followed by
    /// the secondary group's `1 + L` (each weighted by the mirror's
    /// reflectance by the host), and a subsample's secondary layers are
    /// added to its primary ones where it sees a mirror.
    ///
    /// [`SecondaryInputs`]: super::SecondaryInputs
    pub secondary: bool,
    /// The material gate (§4.1, Fig. 6; `sraa::material_gated_weight`): a
    /// neighbour whose albedo differs from the subsample's by more than
    /// `sraa::ALBEDO_TOLERANCE` is not used. Needs [`SraaInputs::albedo`].
    ///
    /// [`SraaInputs::albedo`]: super::SraaInputs::albedo
    pub albedo_gate: bool,
    /// The weights' preset: `SraaParams::TUNED` (the default, shaded sample
    /// at the pixel centre) or `SraaParams::PAPER` (§3.1's σz = 10,
    /// σn = 0.25, shaded sample on subsample `SHADED_SUBSAMPLE`). Where it
    /// puts the shaded sample decides where the host shades: at
    /// `SUBPIXEL_OFFSETS[SHADED_SUBSAMPLE]` (its geometry is then MSAA
    /// sample 0) or at the pixel centre (then the host also supplies
    /// [`CentreGeometry`]).
    ///
    /// [`CentreGeometry`]: super::CentreGeometry
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
    ///
    /// [`PassError::Exposure`]: crate::PassError::Exposure
    /// [`SraaPass::new`]: super::SraaPass::new
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
    ///
    /// [`CentreGeometry`]: super::CentreGeometry
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
    ///
    /// [`SraaBuffers::output`]: super::SraaBuffers::output
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

    /// Refuse what [`SraaPass::new`] refuses before compiling: more than
    /// `MAX_LIGHTS` lights, an output format it cannot write, a tone-mapped
    /// resolve without a valid exposure, and [`GeometryLayout::Packed`] or
    /// [`GeometryLayout::Buffers`] with hardware depth or unsigned normals.
    ///
    /// [`SraaPass::new`]: super::SraaPass::new
    pub(super) fn validate(&self) -> Result<(), PassError> {
        if self.lights as usize > MAX_LIGHTS {
            return Err(PassError::Config(format!(
                "{} lights: SRAA's eq. 2 gates at most {MAX_LIGHTS}",
                self.lights
            )));
        }

        bind::check_output_format(self.output_format)?;
        if let ResolveSpace::ToneMapped { exposure } = self.resolve {
            if !self.resolve.is_valid() {
                return Err(PassError::Exposure {
                    found_bits: exposure.to_bits(),
                });
            }
        }
        if matches!(
            self.geometry,
            GeometryLayout::Packed | GeometryLayout::Buffers
        ) && (self.depth != DepthKind::LinearView || self.normal != NormalEncoding::Signed)
        {
            return Err(PassError::Config(format!(
                "GeometryLayout::{:?} holds linear view depth and signed normals",
                self.geometry
            )));
        }
        Ok(())
    }

    /// Colour layers: `1 + lights`, twice that with secondary shading.
    pub(super) fn color_layers(&self) -> u32 {
        (1 + self.lights) * if self.secondary { 2 } else { 1 }
    }

    pub(super) fn shaded_at_centre(&self) -> bool {
        self.params.shaded_position() == ShadedPosition::Centre
    }

    /// Whether the shaded sample's geometry is an input of its own (the
    /// centre's, or every shaded sample's in buffers), not subsample
    /// `SHADED_SUBSAMPLE`'s.
    pub(super) fn shaded_given(&self) -> bool {
        self.shaded_at_centre() || self.geometry == GeometryLayout::Buffers
    }
}
