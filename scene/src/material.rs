//! Materials: diffuse albedo (solid, checker, coloured patches or texture) and
//! mirror reflectance.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use subcone_kernels::passes::SceneFeatures;

/// An RGB texture, linear, sampled nearest-neighbour with wrapping.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Row-major linear RGB.
    pub texels: Vec<Vec3>,
}

impl Texture {
    /// Sample at `uv` (wrapping). `#[inline]` so that the CPU backend's
    /// instruction-set paths compile it in, rather than call baseline code.
    #[inline]
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        if self.texels.is_empty() || !uv.is_finite() {
            return Vec3::splat(0.5);
        }
        let x = ((uv.x.rem_euclid(1.0)) * self.width as f32) as u32 % self.width;
        let y = (((1.0 - uv.y).rem_euclid(1.0)) * self.height as f32) as u32 % self.height;
        self.texels[(y * self.width + x) as usize]
    }
}

/// Where a surface's diffuse colour comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Albedo {
    /// One colour.
    Solid(Vec3),
    /// A two-colour checkerboard on the world `x`/`z` plane, `size` per square.
    Checker {
        /// First colour.
        a: Vec3,
        /// Second colour.
        b: Vec3,
        /// Side of a square in scene units.
        size: f32,
    },
    /// Square patches on the world `x`/`z` plane, each coloured from `palette` by
    /// a hash of its cell: the coloured floor of the SRAA paper's Fig. 6.
    Patches {
        /// Colours to choose from.
        palette: Vec<Vec3>,
        /// Side of a patch in scene units.
        size: f32,
    },
    /// A texture, by the surface's `uv`.
    Texture(Arc<Texture>),
}

/// A surface material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name, for messages.
    pub name: String,
    /// Diffuse colour.
    pub albedo: Albedo,
    /// Mirror reflectance in `[0, 1]`: the share of the colour taken from the
    /// reflected ray (Whitted).
    pub mirror: f32,
    /// Emitted radiance (area lights are drawn, not sampled).
    pub emission: Vec3,
    /// Opacity in `[0, 1]`: the share of the light along a ray that a surface of
    /// this material stops (1, the default, is opaque). A ray that enters a
    /// semi-transparent object takes `alpha` of the entry surface's colour and
    /// continues where it leaves the object with the remaining transmittance
    /// `1 − alpha` (non-binary visibility, CTSS §5.3, see
    /// `subcone_kernels::transparency`). Honoured by the CPU backend's SDF
    /// renderer with every SDF method; the triangle renderers and the wgpu
    /// backend refuse a scene that uses `alpha < 1` with an error rather than
    /// draw it opaque. Read through [`Material::opacity`]: NaN is opaque, values
    /// outside `[0, 1]` are clamped.
    pub alpha: f32,
}

impl Material {
    /// A plain diffuse material.
    pub fn diffuse(name: &str, albedo: Vec3) -> Self {
        Material {
            name: name.into(),
            albedo: Albedo::Solid(albedo),
            mirror: 0.0,
            emission: Vec3::ZERO,
            alpha: 1.0,
        }
    }

    /// A diffuse material of opacity `alpha` (clamped to `[0, 1]`, NaN reads
    /// as 1): see [`Material::alpha`].
    pub fn translucent(name: &str, albedo: Vec3, alpha: f32) -> Self {
        Material {
            alpha: crate::material::clamp_opacity(alpha),
            ..Material::diffuse(name, albedo)
        }
    }

    /// A mirror with `reflectance` and a diffuse remainder of `albedo`.
    pub fn mirror(name: &str, albedo: Vec3, reflectance: f32) -> Self {
        Material {
            mirror: reflectance.clamp(0.0, 1.0),
            ..Material::diffuse(name, albedo)
        }
    }

    /// The opacity in `[0, 1]`: [`Material::alpha`] clamped, NaN as 1 (opaque).
    pub fn opacity(&self) -> f32 {
        clamp_opacity(self.alpha)
    }

    /// Whether light passes through this material (`opacity() < 1`).
    pub fn is_translucent(&self) -> bool {
        self.opacity() < 1.0
    }

    /// Whether this material reflects.
    pub fn is_reflective(&self) -> bool {
        self.mirror > 0.0
    }

    /// Whether the albedo varies over the surface.
    pub fn is_textured(&self) -> bool {
        !matches!(self.albedo, Albedo::Solid(_))
    }

    /// The passes a scene needs for the materials its geometry uses:
    /// reflections for a reflective one, textures for a textured one.
    pub(crate) fn features<'a>(used: impl IntoIterator<Item = &'a Material>) -> SceneFeatures {
        let mut f = SceneFeatures::empty();
        for m in used {
            if m.is_reflective() {
                f |= SceneFeatures::HAS_REFLECTIONS;
            }
            if m.is_textured() {
                f |= SceneFeatures::HAS_TEXTURES;
            }
        }
        f
    }

    /// Diffuse colour at world point `p` with surface coordinates `uv`.
    #[inline(always)]
    pub fn albedo_at(&self, p: Vec3, uv: Vec2) -> Vec3 {
        match &self.albedo {
            Albedo::Solid(c) => *c,
            Albedo::Checker { a, b, size } => {
                let (i, k) = cell(p, *size);
                if (i + k).rem_euclid(2) == 0 {
                    *a
                } else {
                    *b
                }
            }
            Albedo::Patches { palette, size } => {
                if palette.is_empty() {
                    return Vec3::splat(0.5);
                }
                let (i, k) = cell(p, *size);
                let h = (i as u32).wrapping_mul(0x9E37_79B1) ^ (k as u32).wrapping_mul(0x85EB_CA77);
                let h = (h ^ (h >> 15)).wrapping_mul(0x2C1B_3C6D);
                // `(h >> 7) % len` in 32 bits (a 64-bit division is much
                // slower); a palette too long for `u32` is longer than
                // `h >> 7 < 2²⁵`, which it leaves as is.
                let at = h >> 7;
                palette[u32::try_from(palette.len()).map_or(at, |len| at % len) as usize]
            }
            Albedo::Texture(t) => t.sample(uv),
        }
    }
}

/// `alpha` clamped to `[0, 1]`; NaN is opaque (1), so a broken value never lets
/// hidden surfaces show through.
pub fn clamp_opacity(alpha: f32) -> f32 {
    if alpha.is_nan() {
        1.0
    } else {
        alpha.clamp(0.0, 1.0)
    }
}

fn cell(p: Vec3, size: f32) -> (i64, i64) {
    let s = if size > 0.0 && size.is_finite() {
        size
    } else {
        1.0
    };
    ((p.x / s).floor() as i64, (p.z / s).floor() as i64)
}
