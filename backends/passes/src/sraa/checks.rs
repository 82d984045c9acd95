//! The checks of one frame's inputs against the pass's configuration,
//! before anything is recorded.

use super::desc::{DepthKind, GeometryLayout, SraaPassDesc};
use super::inputs::{CentreGeometry, Samples, SecondaryInputs, SraaInputs, SubsampleGeometry};
use crate::bind::{self, check_buffer, required, Expect, Rect};
use crate::bind::{Buffer, TextureFormat, TextureUsages, TextureView};
use crate::PassError;

impl Samples<&Buffer> {
    /// Check both buffers (named `[shaded, subsamples]`) for `pixels`
    /// pixels: one element of `element` bytes per pixel at the shaded
    /// sample, four at the subsamples.
    pub(super) fn check(
        &self,
        [shaded, subsamples]: [&'static str; 2],
        pixels: u64,
        element: u64,
    ) -> Result<(), PassError> {
        check_buffer(shaded, self.shaded, pixels, element)?;
        check_buffer(subsamples, self.subsamples, 4 * pixels, element)
    }
}

/// What the input textures of one frame must be, for one configuration
/// and the frame's `size` ([`SraaPass::check`]): that size exactly, or,
/// with a `rect`, any size the rect lies inside.
///
/// [`SraaPass::check`]: super::SraaPass::check
pub(super) struct InputRules<'a> {
    pub(super) desc: &'a SraaPassDesc,
    pub(super) size: (u32, u32),
    pub(super) rect: Option<&'a Rect>,
}

impl InputRules<'_> {
    /// Check `v` against `e` and the rules' size or rect.
    pub(super) fn check(&self, v: &TextureView, e: &Expect) -> Result<(), PassError> {
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
    pub(super) fn one(&self, what: &'static str, layers: u32) -> Expect {
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
    pub(super) fn subsample_geometry(&self, inputs: &SraaInputs<'_>) -> Result<(), PassError> {
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
    pub(super) fn centre_geometry(&self, c: &CentreGeometry<'_>) -> Result<(), PassError> {
        self.check(c.depth, &self.one("centre depth", 1))?;
        self.depth_format("centre depth", c.depth)?;
        self.float_one("centre normal", c.normal)
    }

    /// A pair of shadow textures: `R32Uint`, one layer at the shaded
    /// sample, four at the subsamples.
    pub(super) fn shadows(&self, s: &Samples<&TextureView>) -> Result<(), PassError> {
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
    pub(super) fn secondary(&self, s: &SecondaryInputs<'_>) -> Result<(), PassError> {
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
    pub(super) fn albedo(&self, a: &Samples<&TextureView>) -> Result<(), PassError> {
        self.float_one("shaded albedo", a.shaded)?;
        self.float_sub("subsample albedo", a.subsamples)
    }
}
