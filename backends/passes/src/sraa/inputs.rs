//! One frame's inputs of a [`SraaPass`]: the host's views
//! ([`SraaInputs`]) or storage buffers ([`SraaBuffers`]).
//!
//! [`SraaPass`]: super::SraaPass

use crate::bind::{Buffer, TextureView};

/// Geometry at the pixel centres (one sample per pixel, the same size as
/// the output), needed when the preset shades the pixel centre
/// (`ShadedPosition::Centre`, e.g. `SraaParams::TUNED`): the geometry of
/// the shaded sample. Depth as [`SraaPassDesc::depth`], normals as
/// [`SraaPassDesc::normal`].
///
/// [`SraaPassDesc::depth`]: super::SraaPassDesc::depth
/// [`SraaPassDesc::normal`]: super::SraaPassDesc::normal
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
///
/// [`SraaPassDesc::secondary`]: super::SraaPassDesc::secondary
/// [`SraaPassDesc::normal`]: super::SraaPassDesc::normal
#[derive(Clone, Copy, Debug)]
pub struct SecondaryInputs<'a> {
    /// At the shaded sample of each pixel (one sample, one layer).
    pub shaded_depth: &'a TextureView,
    /// Normals at the shaded sample.
    pub shaded_normal: &'a TextureView,
    /// At each geometric subsample: 4x multisampled for
    /// [`GeometryLayout::Multisampled`], else a 4-layer array.
    ///
    /// [`GeometryLayout::Multisampled`]: super::GeometryLayout::Multisampled
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
///
/// [`GeometryLayout`]: super::GeometryLayout
/// [`GeometryLayout::Multisampled`]: super::GeometryLayout::Multisampled
/// [`GeometryLayout::Layers`]: super::GeometryLayout::Layers
/// [`GeometryLayout::Packed`]: super::GeometryLayout::Packed
#[derive(Clone, Copy, Debug)]
pub enum SubsampleGeometry<'a> {
    /// Depth (as [`SraaPassDesc::depth`]) and normals (as
    /// [`SraaPassDesc::normal`]) in two textures.
    ///
    /// [`SraaPassDesc::depth`]: super::SraaPassDesc::depth
    /// [`SraaPassDesc::normal`]: super::SraaPassDesc::normal
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
///
/// [`SraaPass::encode`]: super::SraaPass::encode
/// [`SraaPass::encode_rect`]: super::SraaPass::encode_rect
#[derive(Clone, Copy, Debug)]
pub struct SraaInputs<'a> {
    /// The geometric subsamples.
    pub geometry: SubsampleGeometry<'a>,
    /// The projection this frame's hardware depth was rendered with
    /// (column-major, `glam::Mat4::to_cols_array_2d`; see
    /// [`DepthKind::Hardware`]). Only its z and w rows are read, and only
    /// with [`DepthKind::Hardware`]; a pass of linear view depth ignores it.
    ///
    /// [`DepthKind::Hardware`]: super::DepthKind::Hardware
    pub projection: [[f32; 4]; 4],
    /// Geometry at the pixel centres: required exactly when the preset
    /// shades the pixel centre.
    pub centre: Option<CentreGeometry<'a>>,
    /// The shaded colour, linear RGB in `.xyz`, one sample per pixel, shaded
    /// where the preset puts the shaded sample (see
    /// [`SraaPassDesc::params`]). With 0 lights and no secondary shading
    /// one layer (a 2D texture); else a 2D array of exactly `1 + L` layers,
    /// `2·(1 + L)` with secondary shading.
    ///
    /// [`SraaPassDesc::params`]: super::SraaPassDesc::params
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
    ///
    /// [`GeometryLayout::Multisampled`]: super::GeometryLayout::Multisampled
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
///
/// [`SraaPass::encode_buffers`]: super::SraaPass::encode_buffers
/// [`GeometryLayout::Buffers`]: super::GeometryLayout::Buffers
/// [`PassError::BufferSize`]: crate::PassError::BufferSize
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
