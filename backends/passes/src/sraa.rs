//! [`SraaResolve`]: SRAA's antialiasing pass (Chiu et al., *Subpixel
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

use bytemuck::{Pod, Zeroable};
use subcone_kernels::passes::MAX_LIGHTS;
use subcone_kernels::sraa::{ShadedPosition, SraaParams, ALBEDO_TOLERANCE};

use crate::bind::{self, Expect, Group, PassPipeline};
use crate::PassError;

pub(crate) const SRAA_WGSL: &str = include_str!("sraa.wgsl");

/// The SRAA reconstruction loop every GPU resolve shares ([`SraaResolve`]
/// and the wgpu backend's own), `subcone_sraa_reconstruct_run`: the
/// kernels' WGSL twin of `sraa::reconstruct_layers` (with the albedo gate,
/// `sraa::reconstruct_layers_material`), re-exported from
/// [`subcone_kernels::sraa::RECONSTRUCT_WGSL`], whose documentation lists
/// the hooks the including shader defines. `sraa.wgsl` defines them over
/// the host's textures.
pub use subcone_kernels::sraa::RECONSTRUCT_WGSL;

/// The pass's constants; `SraaFrame` in `sraa.wgsl` (64 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct SraaFrame {
    pub(crate) sraa: SraaParams,
    /// Column-major `m[2][2], m[3][2], m[2][3], m[3][3]` of the projection.
    pub(crate) projection: [f32; 4],
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) depth_miss: f32,
    pub(crate) albedo_tolerance: f32,
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
}

/// How depth is stored (the binding type): chosen at [`SraaResolve::new`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthKind {
    /// A colour texture (e.g. `R32Float`) of linear view depth: the distance
    /// from the eye along the view direction, `> 0`; `0`, negative or
    /// non-finite values are a miss (nothing drawn).
    LinearView,
    /// A depth texture (`Depth32Float`, `Depth24Plus`, …) written by the
    /// hardware through a projection, given per frame in
    /// [`DepthConvention::Hardware`].
    Hardware,
}

/// How the depth of one frame is converted to view depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthConvention {
    /// The textures hold linear view depth ([`DepthKind::LinearView`]).
    LinearView,
    /// The textures hold hardware depth `d` produced by `projection`
    /// (column-major, `glam::Mat4::to_cols_array_2d`, clip = P · view,
    /// depth range 0..1, right- or left-handed). View depth is
    /// `|(m32 − d·m33) / (d·m23 − m22)|` (`m[c][r]`), which inverts
    /// perspective projections with forward or reversed Z and finite or
    /// infinite far planes, and orthographic ones. The projection's
    /// `m[0][2]` and `m[1][2]` must be 0 (no x or y in clip z), as in every
    /// standard projection, jittered ones included.
    Hardware {
        /// The projection the depth was rendered with.
        projection: [[f32; 4]; 4],
        /// The depth of a sample nothing was drawn at (the clear value):
        /// `0.0` for reversed Z, `1.0` for forward Z. A miss.
        miss: f32,
    },
}

impl DepthConvention {
    fn kind(&self) -> DepthKind {
        match self {
            DepthConvention::LinearView => DepthKind::LinearView,
            DepthConvention::Hardware { .. } => DepthKind::Hardware,
        }
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

/// The configuration of a [`SraaResolve`]: what the host renders and how it
/// stores it. Fixed for the pass's life (it selects the pipeline).
#[derive(Clone, Copy, Debug)]
pub struct SraaResolveDesc {
    /// Lights whose shadows gate the reconstruction (SRAA eq. 2), at most
    /// `subcone_kernels::passes::MAX_LIGHTS` (8). With 0, the shaded colour
    /// is one layer and nothing is gated (SRAA's eq. 1 alone); with `L > 0`
    /// the host supplies `1 + L` colour layers (layer 0 what no shadow
    /// decides: emission, ambient; layer `1 + l` light `l`'s direct
    /// contribution) and shadow bits ([`ShadowTextures`]).
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
    /// `sraa::ALBEDO_TOLERANCE` is not used. Needs [`AlbedoTextures`].
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
    /// How depth is stored.
    pub depth: DepthKind,
    /// How normals are stored.
    pub normal: NormalEncoding,
    /// The output texture's format: `Rgba8Unorm`, `Rgba16Float` or
    /// `Rgba32Float` (written as a storage texture, linear values, alpha 1).
    pub output_format: wgpu::TextureFormat,
}

impl SraaResolveDesc {
    /// The default configuration for a host's 4x MSAA prepass of hardware
    /// depth and signed normals, no lights, no gate, `SraaParams::PAPER`
    /// (shaded at subsample 0, so no centre geometry is needed), writing
    /// `Rgba16Float`.
    pub fn msaa() -> Self {
        SraaResolveDesc {
            lights: 0,
            secondary: false,
            albedo_gate: false,
            params: SraaParams::PAPER,
            geometry: GeometryLayout::Multisampled,
            depth: DepthKind::Hardware,
            normal: NormalEncoding::Signed,
            output_format: wgpu::TextureFormat::Rgba16Float,
        }
    }

    /// Colour layers: `1 + lights`, twice that with secondary shading.
    fn color_layers(&self) -> u32 {
        (1 + self.lights) * if self.secondary { 2 } else { 1 }
    }

    fn shaded_at_centre(&self) -> bool {
        self.params.shaded_position() == ShadedPosition::Centre
    }
}

/// Geometry at the pixel centres (one sample per pixel, the same size as
/// the output), needed when the preset shades the pixel centre
/// (`ShadedPosition::Centre`, e.g. `SraaParams::TUNED`): the geometry of
/// the shaded sample. Depth as [`SraaResolveDesc::depth`], normals as
/// [`SraaResolveDesc::normal`].
#[derive(Clone, Copy, Debug)]
pub struct CentreGeometry<'a> {
    /// Depth at the pixel centres.
    pub depth: &'a wgpu::Texture,
    /// Normals at the pixel centres.
    pub normal: &'a wgpu::Texture,
}

/// Shadow states for eq. 2 (`SraaResolveDesc::lights > 0`): `R32Uint`, bit
/// `l` set where light `l`'s shadow ray is blocked.
#[derive(Clone, Copy, Debug)]
pub struct ShadowTextures<'a> {
    /// At the shaded sample of each pixel (one sample, one layer).
    pub shaded: &'a wgpu::Texture,
    /// At each geometric subsample: a one-sample 2D array of exactly 4
    /// layers, layer `k` subsample `k` (whatever the geometry layout:
    /// integer formats cannot be multisampled everywhere).
    pub subsamples: &'a wgpu::Texture,
}

/// Diffuse albedo for the material gate (`SraaResolveDesc::albedo_gate`):
/// `.xyz` linear RGB, any float format.
#[derive(Clone, Copy, Debug)]
pub struct AlbedoTextures<'a> {
    /// At the shaded sample of each pixel (one sample, one layer).
    pub shaded: &'a wgpu::Texture,
    /// At each geometric subsample, in the geometry's layout: 4x
    /// multisampled for [`GeometryLayout::Multisampled`], else a 4-layer
    /// array.
    pub subsamples: &'a wgpu::Texture,
}

/// The secondary hits (SRAA-RT §3.3: where a mirror reflects the ray) for
/// [`SraaResolveDesc::secondary`]. Depth is always the linear length of the
/// reflected path (eye to mirror plus mirror to hit), in a float colour
/// format (e.g. `R32Float`), whatever the primary depth's kind: a value
/// `> 0` and finite is a hit; `0` or `+inf` a miss (the reflection left the
/// scene: its layers hold the background); negative or NaN means no mirror
/// at that sample (its secondary layers are not used). Normals as
/// [`SraaResolveDesc::normal`].
#[derive(Clone, Copy, Debug)]
pub struct SecondaryInputs<'a> {
    /// At the shaded sample of each pixel (one sample, one layer).
    pub shaded_depth: &'a wgpu::Texture,
    /// Normals at the shaded sample.
    pub shaded_normal: &'a wgpu::Texture,
    /// At each geometric subsample: 4x multisampled for
    /// [`GeometryLayout::Multisampled`], else a 4-layer array.
    pub subsample_depth: &'a wgpu::Texture,
    /// Normals at each geometric subsample, in the same layout.
    pub subsample_normal: &'a wgpu::Texture,
    /// The secondary hits' shadow bits: required exactly when `lights > 0`.
    pub shadows: Option<ShadowTextures<'a>>,
}

/// One frame's textures for [`SraaResolve::encode`]. Every texture is the
/// output's size, 2D, one mip level read (level 0), and has
/// `TEXTURE_BINDING`; the output has `STORAGE_BINDING`.
#[derive(Clone, Copy, Debug)]
pub struct SraaInputs<'a> {
    /// Subsample depth ([`GeometryLayout`]; for [`GeometryLayout::Packed`],
    /// the packed normal + depth texture).
    pub subsample_depth: &'a wgpu::Texture,
    /// Subsample normals; `None` exactly for [`GeometryLayout::Packed`].
    pub subsample_normal: Option<&'a wgpu::Texture>,
    /// How to read depth this frame (its kind must be the desc's).
    pub depth: DepthConvention,
    /// Geometry at the pixel centres: required exactly when the preset
    /// shades the pixel centre.
    pub centre: Option<CentreGeometry<'a>>,
    /// The shaded colour, linear RGB in `.xyz`, one sample per pixel, shaded
    /// where the preset puts the shaded sample (see
    /// [`SraaResolveDesc::params`]). With 0 lights and no secondary shading
    /// one layer (a 2D texture); else a 2D array of exactly `1 + L` layers,
    /// `2·(1 + L)` with secondary shading.
    pub color: &'a wgpu::Texture,
    /// Shadow bits: required exactly when `lights > 0`.
    pub shadows: Option<ShadowTextures<'a>>,
    /// Albedo: required exactly when the albedo gate is on.
    pub albedo: Option<AlbedoTextures<'a>>,
    /// The secondary hits: required exactly when the desc has `secondary`.
    pub secondary: Option<SecondaryInputs<'a>>,
    /// Where the antialiased colour is written (level 0, layer 0).
    pub output: &'a wgpu::Texture,
}

/// What the input textures of one frame must be, for one configuration
/// and the frame's `size` ([`SraaResolve::check`]).
struct InputRules<'a> {
    desc: &'a SraaResolveDesc,
    size: (u32, u32),
}

impl InputRules<'_> {
    /// A texture at the geometric subsamples, in the desc's geometry
    /// layout: 4x multisampled, or a one-sample array of 4 layers.
    fn sub(&self, what: &'static str) -> Expect {
        let ms = self.desc.geometry == GeometryLayout::Multisampled;
        Expect {
            what,
            size: self.size,
            samples: if ms { 4 } else { 1 },
            layers: if ms { 1 } else { 4 },
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
        }
    }

    /// A one-sample texture of `layers` layers.
    fn one(&self, what: &'static str, layers: u32) -> Expect {
        Expect {
            what,
            size: self.size,
            samples: 1,
            layers,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
        }
    }

    /// A depth texture's format for the desc's [`DepthKind`].
    fn depth_format(&self, what: &'static str, t: &wgpu::Texture) -> Result<(), PassError> {
        let ok = match self.desc.depth {
            DepthKind::Hardware => t.format().has_depth_aspect(),
            DepthKind::LinearView => bind::is_float_color(t.format()),
        };
        if ok {
            Ok(())
        } else {
            Err(PassError::Format {
                what,
                found: t.format(),
                expected: match self.desc.depth {
                    DepthKind::Hardware => "a depth format (DepthKind::Hardware)",
                    DepthKind::LinearView => "a float colour format such as R32Float",
                },
            })
        }
    }

    /// The subsamples' depth and normals: one packed texture, or a depth
    /// and a normal texture.
    fn subsample_geometry(&self, inputs: &SraaInputs<'_>) -> Result<(), PassError> {
        bind::check(inputs.subsample_depth, &self.sub("subsample depth"))?;
        if self.desc.geometry == GeometryLayout::Packed {
            bind::check_float_color("subsample depth", inputs.subsample_depth)?;
            if inputs.subsample_normal.is_some() {
                return Err(PassError::Unexpected(
                    "subsample normal (GeometryLayout::Packed holds the normals)",
                ));
            }
        } else {
            self.depth_format("subsample depth", inputs.subsample_depth)?;
            let n = inputs
                .subsample_normal
                .ok_or(PassError::Missing("subsample normal"))?;
            bind::check(n, &self.sub("subsample normal"))?;
            bind::check_float_color("subsample normal", n)?;
        }
        Ok(())
    }

    /// The centre geometry: present exactly when the preset shades the
    /// pixel centre.
    fn centre_geometry(&self, inputs: &SraaInputs<'_>) -> Result<(), PassError> {
        match (self.desc.shaded_at_centre(), &inputs.centre) {
            (true, Some(c)) => {
                bind::check(c.depth, &self.one("centre depth", 1))?;
                self.depth_format("centre depth", c.depth)?;
                bind::check(c.normal, &self.one("centre normal", 1))?;
                bind::check_float_color("centre normal", c.normal)?;
            }
            (true, None) => {
                return Err(PassError::Missing(
                    "centre geometry (the preset shades the pixel centre)",
                ))
            }
            (false, Some(_)) => {
                return Err(PassError::Unexpected(
                    "centre geometry (the preset shades subsample 0)",
                ))
            }
            (false, None) => {}
        }
        Ok(())
    }

    /// A pair of shadow textures: `R32Uint`, one layer at the shaded
    /// sample, four at the subsamples.
    fn shadows(&self, s: &ShadowTextures<'_>) -> Result<(), PassError> {
        for (what, t, layers) in [
            ("shaded shadows", s.shaded, 1),
            ("subsample shadows", s.subsamples, 4),
        ] {
            bind::check(t, &self.one(what, layers))?;
            if t.format() != wgpu::TextureFormat::R32Uint {
                return Err(PassError::Format {
                    what,
                    found: t.format(),
                    expected: "R32Uint",
                });
            }
        }
        Ok(())
    }

    /// The secondary hits (§3.3): present exactly when the desc has
    /// `secondary`, with their shadows exactly when it has lights.
    fn secondary(&self, inputs: &SraaInputs<'_>) -> Result<(), PassError> {
        let d = self.desc;
        match (d.secondary, &inputs.secondary) {
            (true, Some(s)) => {
                bind::check(s.shaded_depth, &self.one("secondary shaded depth", 1))?;
                bind::check_float_color("secondary shaded depth", s.shaded_depth)?;
                bind::check(s.shaded_normal, &self.one("secondary shaded normal", 1))?;
                bind::check_float_color("secondary shaded normal", s.shaded_normal)?;
                bind::check(s.subsample_depth, &self.sub("secondary subsample depth"))?;
                bind::check_float_color("secondary subsample depth", s.subsample_depth)?;
                bind::check(s.subsample_normal, &self.sub("secondary subsample normal"))?;
                bind::check_float_color("secondary subsample normal", s.subsample_normal)?;
                match (d.lights > 0, &s.shadows) {
                    (true, Some(sh)) => self.shadows(sh)?,
                    (true, None) => {
                        return Err(PassError::Missing("secondary shadow textures (lights > 0)"))
                    }
                    (false, Some(_)) => {
                        return Err(PassError::Unexpected(
                            "secondary shadow textures (0 lights)",
                        ))
                    }
                    (false, None) => {}
                }
            }
            (true, None) => return Err(PassError::Missing("secondary inputs (secondary on)")),
            (false, Some(_)) => {
                return Err(PassError::Unexpected("secondary inputs (secondary off)"))
            }
            (false, None) => {}
        }
        Ok(())
    }

    /// The albedo textures: present exactly when the albedo gate is on.
    fn albedo(&self, inputs: &SraaInputs<'_>) -> Result<(), PassError> {
        match (self.desc.albedo_gate, &inputs.albedo) {
            (true, Some(a)) => {
                bind::check(a.shaded, &self.one("shaded albedo", 1))?;
                bind::check_float_color("shaded albedo", a.shaded)?;
                bind::check(a.subsamples, &self.sub("subsample albedo"))?;
                bind::check_float_color("subsample albedo", a.subsamples)?;
            }
            (true, None) => return Err(PassError::Missing("albedo textures (albedo gate on)")),
            (false, Some(_)) => {
                return Err(PassError::Unexpected("albedo textures (albedo gate off)"))
            }
            (false, None) => {}
        }
        Ok(())
    }
}

/// SRAA's antialiasing pass on the host's device. See the module docs of
/// the crate and [`SraaResolveDesc`] for the conventions.
///
/// ```no_run
/// # fn f(device: &wgpu::Device, encoder: &mut wgpu::CommandEncoder, depth: &wgpu::Texture,
/// #      normal: &wgpu::Texture, color: &wgpu::Texture, output: &wgpu::Texture, projection: [[f32; 4]; 4])
/// # -> Result<(), subcone_passes::PassError> {
/// use subcone_passes::{DepthConvention, SraaInputs, SraaResolve, SraaResolveDesc};
/// let sraa = SraaResolve::new(device, &SraaResolveDesc::msaa())?;
/// sraa.encode(device, encoder, &SraaInputs {
///     subsample_depth: depth,   // Depth32Float, 4x MSAA, reversed Z
///     subsample_normal: Some(normal), // Rgba16Float, 4x MSAA
///     depth: DepthConvention::Hardware { projection, miss: 0.0 },
///     centre: None,
///     color,                    // shaded at SUBPIXEL_OFFSETS[0]
///     shadows: None,
///     albedo: None,
///     secondary: None,
///     output,                   // Rgba16Float, STORAGE_BINDING
/// })?;
/// # Ok(()) }
/// ```
pub struct SraaResolve {
    desc: SraaResolveDesc,
    pipeline: PassPipeline,
}

impl std::fmt::Debug for SraaResolve {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SraaResolve")
            .field("desc", &self.desc)
            .finish()
    }
}

fn float_sample() -> wgpu::TextureSampleType {
    wgpu::TextureSampleType::Float { filterable: false }
}

impl SraaResolve {
    /// Build the pass (compile its pipeline) on the host's device. Refuses
    /// more than `MAX_LIGHTS` lights, an output format
    /// it cannot write, and [`GeometryLayout::Packed`] with hardware depth
    /// or unsigned normals.
    pub fn new(device: &wgpu::Device, desc: &SraaResolveDesc) -> Result<Self, PassError> {
        let source = Self::source(desc)?;
        let group = Self::group(desc);
        let source = [source, group.declarations()].concat();
        let pipeline = PassPipeline::new(
            device,
            "subcone sraa resolve",
            group,
            source,
            None,
            "sraa_resolve_main",
        );
        Ok(SraaResolve {
            desc: *desc,
            pipeline,
        })
    }

    /// The configuration.
    pub fn desc(&self) -> &SraaResolveDesc {
        &self.desc
    }

    /// The bindings, in order.
    fn group(desc: &SraaResolveDesc) -> Group {
        use wgpu::TextureViewDimension::{D2Array, D2};
        let mut g = Group::default();
        g.uniform("frame", "SraaFrame");
        let hw = desc.depth == DepthKind::Hardware;
        let (dim, ms) = match desc.geometry {
            GeometryLayout::Multisampled => (D2, true),
            _ => (D2Array, false),
        };
        let sub_ty = |depth: bool| match (depth && hw, ms) {
            (true, true) => "texture_depth_multisampled_2d",
            (true, false) => "texture_depth_2d_array",
            (false, true) => "texture_multisampled_2d<f32>",
            (false, false) => "texture_2d_array<f32>",
        };
        let depth_sample = if hw {
            wgpu::TextureSampleType::Depth
        } else {
            float_sample()
        };
        g.texture("sub_depth", sub_ty(true), depth_sample, dim, ms);
        if desc.geometry != GeometryLayout::Packed {
            g.texture("sub_normal", sub_ty(false), float_sample(), dim, ms);
        }
        if desc.shaded_at_centre() {
            let ty = if hw {
                "texture_depth_2d"
            } else {
                "texture_2d<f32>"
            };
            g.texture("centre_depth", ty, depth_sample, D2, false);
            g.texture(
                "centre_normal",
                "texture_2d<f32>",
                float_sample(),
                D2,
                false,
            );
        }
        if desc.color_layers() == 1 {
            g.texture("color", "texture_2d<f32>", float_sample(), D2, false);
        } else {
            g.texture(
                "color",
                "texture_2d_array<f32>",
                float_sample(),
                D2Array,
                false,
            );
        }
        let u = wgpu::TextureSampleType::Uint;
        if desc.lights > 0 {
            g.texture("shaded_shadow", "texture_2d<u32>", u, D2, false);
            g.texture("sub_shadow", "texture_2d_array<u32>", u, D2Array, false);
        }
        if desc.secondary {
            let f = float_sample();
            let sub = if ms {
                "texture_multisampled_2d<f32>"
            } else {
                "texture_2d_array<f32>"
            };
            g.texture("sec_shaded_depth", "texture_2d<f32>", f, D2, false);
            g.texture("sec_shaded_normal", "texture_2d<f32>", f, D2, false);
            g.texture("sec_sub_depth", sub, f, dim, ms);
            g.texture("sec_sub_normal", sub, f, dim, ms);
            if desc.lights > 0 {
                g.texture("sec_shaded_shadow", "texture_2d<u32>", u, D2, false);
                g.texture("sec_sub_shadow", "texture_2d_array<u32>", u, D2Array, false);
            }
        }
        if desc.albedo_gate {
            g.texture(
                "shaded_albedo",
                "texture_2d<f32>",
                float_sample(),
                D2,
                false,
            );
            g.texture("sub_albedo", sub_ty(false), float_sample(), dim, ms);
        }
        g.storage_texture("sraa_output", desc.output_format);
        g
    }

    /// The shader: the kernels, the generated header (constants, loaders),
    /// `sraa.wgsl`; the declarations are appended by [`Self::new`].
    fn source(desc: &SraaResolveDesc) -> Result<String, PassError> {
        if desc.lights as usize > MAX_LIGHTS {
            return Err(PassError::Config(format!(
                "{} lights: SRAA's eq. 2 gates at most {MAX_LIGHTS}",
                desc.lights
            )));
        }

        bind::check_output_format(desc.output_format)?;
        let packed = desc.geometry == GeometryLayout::Packed;
        if packed && (desc.depth != DepthKind::LinearView || desc.normal != NormalEncoding::Signed)
        {
            return Err(PassError::Config(
                "GeometryLayout::Packed holds linear view depth and signed normals".into(),
            ));
        }
        let hw = desc.depth == DepthKind::Hardware;
        let ms = desc.geometry == GeometryLayout::Multisampled;
        // textureLoad's trailing arguments: sample index, or layer and level.
        let sub_at = if ms { "i32(k)" } else { "i32(k), 0" };
        let scalar = if hw { "" } else { ".x" };
        let mut h = format!(
            "const LIGHTS: u32 = {}u;\nconst MATERIAL: bool = {};\nconst HARDWARE_DEPTH: bool = {hw};\n\
             const UNSIGNED_NORMALS: bool = {};\nconst SHADED_AT_CENTRE: bool = {};\n\
             const SECONDARY: bool = {};\n",
            desc.lights,
            desc.albedo_gate,
            desc.normal == NormalEncoding::Unsigned,
            desc.shaded_at_centre(),
            desc.secondary,
        );
        if packed {
            h += &format!(
                "fn sraa_load_sub_depth(p: vec2<i32>, k: u32) -> f32 {{ return textureLoad(sub_depth, p, {sub_at}).w; }}\n\
                 fn sraa_load_sub_normal(p: vec2<i32>, k: u32) -> vec3<f32> {{ return textureLoad(sub_depth, p, {sub_at}).xyz; }}\n"
            );
        } else {
            h += &format!(
                "fn sraa_load_sub_depth(p: vec2<i32>, k: u32) -> f32 {{ return textureLoad(sub_depth, p, {sub_at}){scalar}; }}\n\
                 fn sraa_load_sub_normal(p: vec2<i32>, k: u32) -> vec3<f32> {{ return textureLoad(sub_normal, p, {sub_at}).xyz; }}\n"
            );
        }
        if desc.shaded_at_centre() {
            h += &format!(
                "fn sraa_load_centre_depth(p: vec2<i32>) -> f32 {{ return textureLoad(centre_depth, p, 0){scalar}; }}\n\
                 fn sraa_load_centre_normal(p: vec2<i32>) -> vec3<f32> {{ return textureLoad(centre_normal, p, 0).xyz; }}\n"
            );
        } else {
            h += "fn sraa_load_centre_depth(p: vec2<i32>) -> f32 { return 0.0; }\n\
                  fn sraa_load_centre_normal(p: vec2<i32>) -> vec3<f32> { return vec3<f32>(0.0); }\n";
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
                h += &format!(
                    "fn sraa_load_{g}shaded_shadow(p: vec2<i32>) -> u32 {{ return 0u; }}\n\
                     fn sraa_load_{g}sub_shadow(p: vec2<i32>, k: u32) -> u32 {{ return 0u; }}\n"
                );
            }
        }
        if desc.secondary {
            h += &format!(
                "fn sraa_load_sec_shaded(p: vec2<i32>) -> vec4<f32> {{ return vec4<f32>(textureLoad(sec_shaded_normal, p, 0).xyz, textureLoad(sec_shaded_depth, p, 0).x); }}\n\
                 fn sraa_load_sec_sub(p: vec2<i32>, k: u32) -> vec4<f32> {{ return vec4<f32>(textureLoad(sec_sub_normal, p, {sub_at}).xyz, textureLoad(sec_sub_depth, p, {sub_at}).x); }}\n"
            );
        } else {
            h += "fn sraa_load_sec_shaded(p: vec2<i32>) -> vec4<f32> { return vec4<f32>(0.0); }\n\
                  fn sraa_load_sec_sub(p: vec2<i32>, k: u32) -> vec4<f32> { return vec4<f32>(0.0); }\n";
        }
        if desc.albedo_gate {
            h += &format!(
                "fn sraa_load_shaded_albedo(p: vec2<i32>) -> vec3<f32> {{ return textureLoad(shaded_albedo, p, 0).xyz; }}\n\
                 fn sraa_load_sub_albedo(p: vec2<i32>, k: u32) -> vec3<f32> {{ return textureLoad(sub_albedo, p, {sub_at}).xyz; }}\n"
            );
        } else {
            h += "fn sraa_load_shaded_albedo(p: vec2<i32>) -> vec3<f32> { return vec3<f32>(0.0); }\n\
                  fn sraa_load_sub_albedo(p: vec2<i32>, k: u32) -> vec3<f32> { return vec3<f32>(0.0); }\n";
        }
        Ok([
            subcone_kernels::wgsl::PARAMS,
            subcone_kernels::sraa::WGSL,
            &h,
            SRAA_WGSL,
            RECONSTRUCT_WGSL,
        ]
        .concat())
    }

    /// Check `inputs` against the configuration; the frame's size. Each
    /// input in turn, in the order of [`SraaInputs`]' roles: the output and
    /// the depth convention, the subsample geometry, the centre geometry,
    /// the colour, the shadows, the secondary hits, the albedo.
    fn check(&self, inputs: &SraaInputs<'_>) -> Result<(u32, u32), PassError> {
        let d = &self.desc;
        let size = self.check_output(inputs)?;
        let rules = InputRules { desc: d, size };
        rules.subsample_geometry(inputs)?;
        rules.centre_geometry(inputs)?;
        bind::check(inputs.color, &rules.one("colour", d.color_layers()))?;
        bind::check_float_color("colour", inputs.color)?;
        match (d.lights > 0, &inputs.shadows) {
            (true, Some(s)) => rules.shadows(s)?,
            (true, None) => return Err(PassError::Missing("shadow textures (lights > 0)")),
            (false, Some(_)) => return Err(PassError::Unexpected("shadow textures (0 lights)")),
            (false, None) => {}
        }
        rules.secondary(inputs)?;
        rules.albedo(inputs)?;
        Ok(size)
    }

    /// Check the output texture (its size is the frame's, returned) and
    /// that the frame's depth convention is the one the pass was built for.
    fn check_output(&self, inputs: &SraaInputs<'_>) -> Result<(u32, u32), PassError> {
        let d = &self.desc;
        let size = bind::check_output(inputs.output, d.output_format, "the desc's output_format")?;
        if inputs.depth.kind() != d.depth {
            return Err(PassError::Config(format!(
                "the frame's depth convention is {:?}, the pass was built for {:?}",
                inputs.depth.kind(),
                d.depth
            )));
        }
        Ok(size)
    }

    /// Record the resolve of one frame into `encoder` (one compute pass of
    /// 8×8 workgroups, one invocation per pixel). Checks every input first:
    /// on an error nothing is recorded. Each call creates a 64-byte uniform
    /// buffer and a bind group (the frame's size, preset and projection).
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &SraaInputs<'_>,
    ) -> Result<(), PassError> {
        use wgpu::TextureViewDimension::{D2Array, D2};
        let (width, height) = self.check(inputs)?;
        let d = &self.desc;
        let (projection, depth_miss) = match inputs.depth {
            DepthConvention::LinearView => ([0.0; 4], 0.0),
            DepthConvention::Hardware {
                projection: m,
                miss,
            } => ([m[2][2], m[3][2], m[2][3], m[3][3]], miss),
        };
        let frame = SraaFrame {
            sraa: d.params,
            projection,
            width,
            height,
            depth_miss,
            albedo_tolerance: ALBEDO_TOLERANCE,
        };
        let uniform = bind::uniform_buffer(device, "subcone sraa frame", &frame);
        let sub_dim = if d.geometry == GeometryLayout::Multisampled {
            D2
        } else {
            D2Array
        };
        let mut views: Vec<(&'static str, wgpu::TextureView)> = Vec::new();
        views.push(("sub_depth", bind::view(inputs.subsample_depth, sub_dim)));
        if let Some(n) = inputs.subsample_normal {
            views.push(("sub_normal", bind::view(n, sub_dim)));
        }
        if let Some(c) = &inputs.centre {
            views.push(("centre_depth", bind::view(c.depth, D2)));
            views.push(("centre_normal", bind::view(c.normal, D2)));
        }
        let color_dim = if d.color_layers() == 1 { D2 } else { D2Array };
        views.push(("color", bind::view(inputs.color, color_dim)));
        if let Some(s) = &inputs.shadows {
            views.push(("shaded_shadow", bind::view(s.shaded, D2)));
            views.push(("sub_shadow", bind::view(s.subsamples, D2Array)));
        }
        if let Some(s) = &inputs.secondary {
            views.push(("sec_shaded_depth", bind::view(s.shaded_depth, D2)));
            views.push(("sec_shaded_normal", bind::view(s.shaded_normal, D2)));
            views.push(("sec_sub_depth", bind::view(s.subsample_depth, sub_dim)));
            views.push(("sec_sub_normal", bind::view(s.subsample_normal, sub_dim)));
            if let Some(sh) = &s.shadows {
                views.push(("sec_shaded_shadow", bind::view(sh.shaded, D2)));
                views.push(("sec_sub_shadow", bind::view(sh.subsamples, D2Array)));
            }
        }
        if let Some(a) = &inputs.albedo {
            views.push(("shaded_albedo", bind::view(a.shaded, D2)));
            views.push(("sub_albedo", bind::view(a.subsamples, sub_dim)));
        }
        views.push(("sraa_output", bind::view(inputs.output, D2)));
        let mut resources = vec![("frame", uniform.as_entire_binding())];
        resources.extend(
            views
                .iter()
                .map(|(n, v)| (*n, wgpu::BindingResource::TextureView(v))),
        );
        self.pipeline
            .encode(device, encoder, (width, height), &resources, None)
    }
}

#[cfg(test)]
pub(crate) fn test_source(desc: &SraaResolveDesc) -> String {
    let group = SraaResolve::group(desc);
    [
        SraaResolve::source(desc).expect("valid desc"),
        group.declarations(),
    ]
    .concat()
}
