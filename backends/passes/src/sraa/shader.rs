//! The pass's shader: the kernels' WGSL, a header generated for the
//! configuration (its constants and the loaders of its layout) and
//! `sraa.wgsl`; and the pass's `PassShader`, which the crate's skeleton
//! builds its pipeline and its standalone shader from.

use subcone_kernels::sraa::ResolveSpace;

use super::desc::{GeometryLayout, NormalEncoding, SraaPassDesc};
use super::group::DepthBinding;
use super::pass::SraaPass;
use super::RECONSTRUCT_WGSL;
use crate::bind::{BindingKind, Group};
use crate::skeleton::{PassNames, PassShader};
use crate::PassError;

pub(crate) const SRAA_WGSL: &str = include_str!("../sraa.wgsl");

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

impl SraaPass {
    /// The shader, hardware depth read as `depth` declares it: the
    /// kernels, the generated header (constants, loaders), `sraa.wgsl`
    /// (the skeleton adds the prelude and the declarations). The desc is
    /// valid ([`PassShader::check`]).
    fn wgsl_with(desc: &SraaPassDesc, depth: DepthBinding) -> String {
        let buffers = desc.geometry == GeometryLayout::Buffers;
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
        [subcone_kernels::sraa::WGSL, &h, SRAA_WGSL, RECONSTRUCT_WGSL].concat()
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
    ///
    /// [`SraaBuffers`]: super::SraaBuffers
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
}

impl PassShader for SraaPass {
    const NAMES: PassNames = PassNames::new("sraa", "subcone sraa resolve", "sraa_resolve_main");
    type Key<'a> = SraaPassDesc;

    fn check(desc: &SraaPassDesc) -> Result<(), PassError> {
        desc.validate()
    }

    fn group(desc: &SraaPassDesc) -> Result<Group, PassError> {
        Self::group_with(desc, DepthBinding::Depth)
    }

    fn wgsl(desc: &SraaPassDesc) -> String {
        Self::wgsl_with(desc, DepthBinding::Depth)
    }

    /// Where the group binds a depth texture: the group and shader with
    /// hardware depth declared as a float texture ([`DepthBinding::Float`]).
    fn glsl_variant(
        desc: &SraaPassDesc,
        group: &Group,
    ) -> Result<Option<(Group, String)>, PassError> {
        let depth_texture = group.entries().iter().any(|b| {
            matches!(
                b.kind,
                BindingKind::Texture {
                    sample: "depth",
                    ..
                }
            )
        });
        if !depth_texture {
            return Ok(None);
        }
        let float = Self::group_with(desc, DepthBinding::Float)?;
        Ok(Some((float, Self::wgsl_with(desc, DepthBinding::Float))))
    }
}

#[cfg(test)]
pub(crate) fn test_source(desc: &SraaPassDesc) -> String {
    crate::skeleton::shader::<SraaPass>(desc)
        .expect("valid desc")
        .1
}
