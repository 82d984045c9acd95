//! Which passes (and the buffers they write) a frame needs, derived from the
//! technique and what the scene contains.
//!
//! This is where "leave out what a given scene does not need" is decided: a scene
//! without reflective materials gets no secondary pass and no secondary buffers,
//! a scene without lights no shadow pass. Backends allocate and run exactly
//! [`required_passes`], nothing more.
//!
//! ```
//! use subcone_kernels::passes::{required_passes, Passes, SceneFeatures, Technique};
//!
//! let p = required_passes(Technique::SraaRt, SceneFeatures::HAS_LIGHTS).unwrap();
//! assert!(p.contains(Passes::SUBPIXEL_SHADOW));
//! assert!(!p.intersects(Passes::SECONDARY | Passes::SUBPIXEL_SECONDARY_GEOMETRY));
//! ```

use bitflags::bitflags;

/// An antialiasing technique, with nothing beyond what decides its passes.
/// (The scene crate's `Method` wraps it with its parameters: sample counts, cone
/// coverage, k, …)
///
/// Deliberately not `#[non_exhaustive]`: every backend routes techniques
/// with a `match` that names each one, so a technique added here does not
/// compile until each backend says what it does with it (renders it, or
/// refuses it with a typed reason), instead of falling through to another
/// technique's path. A match that leaves one out is an error:
///
/// ```compile_fail,E0004
/// use subcone_kernels::passes::Technique;
///
/// // A backend that forgot FXAA.
/// fn path(t: Technique) -> &'static str {
///     match t {
///         Technique::NoAa | Technique::Ssaa => "samples",
///         Technique::Sraa | Technique::SraaRt => "subpixel",
///         Technique::Ctss | Technique::CtssR | Technique::SsaaCtss => "cones",
///     }
/// }
/// ```
///
/// and naming every technique compiles:
///
/// ```
/// use subcone_kernels::passes::Technique;
///
/// fn path(t: Technique) -> &'static str {
///     match t {
///         Technique::NoAa | Technique::Ssaa | Technique::Fxaa => "samples",
///         Technique::Sraa | Technique::SraaRt => "subpixel",
///         Technique::Ctss | Technique::CtssR | Technique::SsaaCtss => "cones",
///     }
/// }
/// assert!(Technique::ALL.iter().all(|&t| !path(t).is_empty()));
/// ```
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Technique {
    /// One sample per pixel.
    NoAa = 0,
    /// N×N samples per pixel, box-filtered.
    Ssaa = 1,
    /// Original SRAA (Chajdas et al.): subpixel primary geometry, final colour
    /// reconstructed with eq. 1 only.
    Sraa = 2,
    /// SRAA for ray tracing (Chiu et al.): plus subpixel shadow rays (eq. 2) and
    /// separately reconstructed secondary shading (§3.3).
    SraaRt = 3,
    /// Cone-traced supersampling, to full occlusion.
    Ctss = 4,
    /// CTSS-R: stop at the first hard hit.
    CtssR = 5,
    /// N×N supersampling with CTSS on every sample (§4.2).
    SsaaCtss = 6,
    /// One sample per pixel, then FXAA 3.11 on the displayed image (the
    /// post-process baseline, [`crate::fxaa`]).
    Fxaa = 7,
}

impl Technique {
    /// Every technique.
    pub const ALL: [Technique; 8] = [
        Technique::NoAa,
        Technique::Ssaa,
        Technique::Sraa,
        Technique::SraaRt,
        Technique::Ctss,
        Technique::CtssR,
        Technique::SsaaCtss,
        Technique::Fxaa,
    ];

    /// Whether this is one of the CTSS family (needs an SDF).
    pub const fn is_cone_traced(self) -> bool {
        matches!(
            self,
            Technique::Ctss | Technique::CtssR | Technique::SsaaCtss
        )
    }

    /// Whether this is one of the SRAA family (needs subpixel geometry).
    pub const fn is_subpixel_reconstruction(self) -> bool {
        matches!(self, Technique::Sraa | Technique::SraaRt)
    }

    /// Whether the technique is SRAA for ray tracing's form of SRAA
    /// (Chiu et al., §3.2–3.3): its shading kept in layers reconstructed
    /// apart, its subsamples carrying ray-traced shadow states and
    /// reflections; plain SRAA (Chajdas et al.) reconstructs one colour.
    pub const fn splits_layers(self) -> bool {
        matches!(self, Technique::SraaRt)
    }
}

bitflags! {
    /// What a scene contains, as far as passes are concerned.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
    pub struct SceneFeatures: u32 {
        /// At least one light that casts shadows.
        const HAS_LIGHTS = 1 << 0;
        /// At least one material with non-zero mirror reflectance.
        const HAS_REFLECTIONS = 1 << 1;
        /// The geometry is a signed distance field (sphere traced), not triangles.
        const IS_SDF = 1 << 2;
        /// Some albedo varies over a surface (checker, texture).
        const HAS_TEXTURES = 1 << 3;
    }
}

bitflags! {
    /// Every pass (with the buffers it writes) a frame can need.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
    pub struct Passes: u32 {
        /// Primary visibility of the shaded samples (BVH rays or sphere tracing):
        /// position, normal, depth, material per shaded sample.
        const PRIMARY = 1 << 0;
        /// The four geometric subsamples per pixel (§3.1; raster or geometry-only
        /// rays): normal and depth, and position when a subpixel pass follows.
        const SUBPIXEL_GEOMETRY = 1 << 1;
        /// Direct shading of the shaded samples: one colour buffer.
        const SHADING = 1 << 2;
        /// Shadow rays from the shaded samples: one shadow state per light.
        const SHADOW = 1 << 3;
        /// Shadow rays from every geometric subsample (§3.2, eq. 2's gate).
        const SUBPIXEL_SHADOW = 1 << 4;
        /// Reflection rays from the shaded samples and the shading of their hits.
        const SECONDARY = 1 << 5;
        /// Shadow rays from secondary hits.
        const SECONDARY_SHADOW = 1 << 6;
        /// Reflection rays from every geometric subsample, geometry only (§3.3):
        /// secondary normal and depth per subsample.
        const SUBPIXEL_SECONDARY_GEOMETRY = 1 << 7;
        /// Bilateral reconstruction of the primary shading (eq. 1/2).
        const RECONSTRUCTION = 1 << 8;
        /// Bilateral reconstruction of the secondary shading on secondary geometry (§3.3).
        const SECONDARY_RECONSTRUCTION = 1 << 9;
        /// Filter the four reconstructed subsamples into the pixel.
        const RESOLVE = 1 << 10;
        /// Cone tracing with hit groups and visibility masks (CTSS, Algorithm 1).
        const CONE_TRACE = 1 << 11;
        /// Several samples per pixel, box-filtered (SSAA, SSAA+CTSS).
        const SUPERSAMPLE = 1 << 12;
        /// A filter over the finished image (FXAA): one more colour buffer.
        const POST_PROCESS = 1 << 13;
    }
}

/// A technique that cannot render a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unsupported {
    /// The technique asked for.
    pub technique: Technique,
    /// Why not.
    pub reason: &'static str,
}

impl core::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{:?} cannot render this scene: {}",
            self.technique, self.reason
        )
    }
}

impl core::error::Error for Unsupported {}

/// The passes a frame of `technique` needs on a scene with `features`.
///
/// Shadow passes exist only with [`SceneFeatures::HAS_LIGHTS`], secondary passes
/// only with [`SceneFeatures::HAS_REFLECTIONS`], secondary shadows only with both.
/// The CTSS family needs an SDF. Plain SRAA needs triangles (its subpixel
/// G-buffer is rasterised); SRAA-RT takes its samples by ray casting and so
/// also runs on SDFs, sphere tracing them (the passes are the same; SDF
/// backends refuse reflections).
/// Textures change no pass.
pub fn required_passes(
    technique: Technique,
    features: SceneFeatures,
) -> Result<Passes, Unsupported> {
    let lights = features.contains(SceneFeatures::HAS_LIGHTS);
    let reflections = features.contains(SceneFeatures::HAS_REFLECTIONS);
    let sdf = features.contains(SceneFeatures::IS_SDF);

    if technique.is_cone_traced() && !sdf {
        return Err(Unsupported {
            technique,
            reason: "cone tracing needs a signed distance field",
        });
    }
    if technique == Technique::Sraa && sdf {
        return Err(Unsupported {
            technique,
            reason: "plain SRAA runs on triangle scenes only (sraa-rt renders SDF scenes)",
        });
    }

    // What shading one sample costs, whatever the technique.
    let mut shading = Passes::SHADING;
    if lights {
        shading |= Passes::SHADOW;
    }
    if reflections {
        shading |= Passes::SECONDARY;
        if lights {
            shading |= Passes::SECONDARY_SHADOW;
        }
    }

    let passes = match technique {
        Technique::NoAa => Passes::PRIMARY | shading,
        Technique::Fxaa => Passes::PRIMARY | shading | Passes::POST_PROCESS,
        Technique::Ssaa => Passes::PRIMARY | Passes::SUPERSAMPLE | shading,
        Technique::Sraa => {
            Passes::PRIMARY
                | Passes::SUBPIXEL_GEOMETRY
                | shading
                | Passes::RECONSTRUCTION
                | Passes::RESOLVE
        }
        Technique::SraaRt => {
            let mut p = Passes::PRIMARY
                | Passes::SUBPIXEL_GEOMETRY
                | shading
                | Passes::RECONSTRUCTION
                | Passes::RESOLVE;
            if lights {
                p |= Passes::SUBPIXEL_SHADOW;
            }
            if reflections {
                p |= Passes::SUBPIXEL_SECONDARY_GEOMETRY | Passes::SECONDARY_RECONSTRUCTION;
            }
            p
        }
        Technique::Ctss | Technique::CtssR => Passes::CONE_TRACE | shading,
        Technique::SsaaCtss => Passes::CONE_TRACE | Passes::SUPERSAMPLE | shading,
    };
    Ok(passes)
}

/// Most lights a frame may have on any backend: shadow states are bits of a
/// `u32`, and per-light shading parts live in fixed arrays.
pub const MAX_LIGHTS: usize = 8;

/// The shading layers an SRAA frame reconstructs separately (§3.2–3.3): the
/// shadow-independent part, one layer per light gated by that light's shadow
/// state (eq. 2), and the same again for secondary (reflected) shading. Plain
/// SRAA reconstructs one layer, the final colour.
///
/// Derived from the planned passes, so a scene without lights has no
/// per-light layers and one without mirrors no secondary layers; every
/// backend sizes its buffers from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LayerLayout {
    /// Lights whose direct part is a layer of its own.
    pub lights: usize,
    /// Secondary layers exist.
    pub secondary: bool,
    /// One layer only (plain SRAA).
    pub single: bool,
}

impl LayerLayout {
    /// The layers of a `technique` frame running `passes` with `lights` lights
    /// (already capped at what the backend supports). Only SRAA-RT splits
    /// shading into layers; every other technique gets the single layer.
    pub const fn new(technique: Technique, passes: Passes, lights: usize) -> Self {
        let rt = technique.splits_layers();
        LayerLayout {
            lights: if rt && passes.contains(Passes::SHADOW) {
                lights
            } else {
                0
            },
            secondary: rt && passes.contains(Passes::SECONDARY_RECONSTRUCTION),
            single: !rt,
        }
    }

    /// Number of layers.
    pub const fn len(&self) -> usize {
        if self.single {
            1
        } else {
            (1 + self.lights) * if self.secondary { 2 } else { 1 }
        }
    }

    /// Never empty: at least the one layer.
    pub const fn is_empty(&self) -> bool {
        false
    }

    /// Index of the first secondary layer.
    pub const fn secondary_base(&self) -> usize {
        1 + self.lights
    }
}

/// What an SRAA frame computes beyond its primary visibility, decided once
/// from its technique, planned passes, lights and material gate: the part of
/// a frame's plan every backend reads its buffers and passes from (§3.1–3.3
/// of SRAA for ray tracing; §4.1 for the material gate).
///
/// ```
/// use subcone_kernels::passes::{required_passes, SceneFeatures, SubpixelPasses, Technique};
///
/// let lit = SceneFeatures::HAS_LIGHTS;
/// let rt = SubpixelPasses::new(Technique::SraaRt, required_passes(Technique::SraaRt, lit)?, 1, false);
/// assert!(rt.splits_layers && rt.sub_shadows && !rt.sub_secondary);
/// assert_eq!(rt.layout.len(), 2); // the shadow-independent part and the light's
/// let plain = SubpixelPasses::new(Technique::Sraa, required_passes(Technique::Sraa, lit)?, 1, false);
/// assert!(!plain.splits_layers && !plain.sub_shadows && plain.layout.single);
/// # Ok::<(), subcone_kernels::passes::Unsupported>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SubpixelPasses {
    /// SRAA-RT's form ([`Technique::splits_layers`]): shading in layers,
    /// subsamples with shadow states and reflections of their own.
    pub splits_layers: bool,
    /// The layers each shaded sample keeps.
    pub layout: LayerLayout,
    /// Shadow rays from the shaded samples ([`Passes::SHADOW`]).
    pub shadows: bool,
    /// The subsamples' shadow states (§3.2, [`Passes::SUBPIXEL_SHADOW`]).
    pub sub_shadows: bool,
    /// The subsamples' reflection geometry and its shadow states (§3.3,
    /// [`Passes::SUBPIXEL_SECONDARY_GEOMETRY`]).
    pub sub_secondary: bool,
    /// Mirrors shade what they reflect ([`Passes::SECONDARY`]).
    pub secondary_shading: bool,
    /// `+mat`: the albedo of shaded samples and subsamples is kept for the
    /// material gate.
    pub material: bool,
}

impl SubpixelPasses {
    /// The plan of a `technique` frame running `passes` with `lights`
    /// lights (already capped at what the backend supports), gated by
    /// material when `material`. A subpixel pass the technique does not
    /// run is off whatever `passes` says.
    pub const fn new(technique: Technique, passes: Passes, lights: usize, material: bool) -> Self {
        let rt = technique.splits_layers();
        SubpixelPasses {
            splits_layers: rt,
            layout: LayerLayout::new(technique, passes, lights),
            shadows: passes.contains(Passes::SHADOW),
            sub_shadows: rt && passes.contains(Passes::SUBPIXEL_SHADOW),
            sub_secondary: rt && passes.contains(Passes::SUBPIXEL_SECONDARY_GEOMETRY),
            secondary_shading: passes.contains(Passes::SECONDARY),
            material,
        }
    }
}
