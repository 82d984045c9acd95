//! The pass's bindings: its group 0 for each configuration, in binding
//! order.

use super::desc::{GeometryLayout, SraaPassDesc};
use super::pass::SraaPass;
use super::SraaFrame;
use crate::bind::{Group, TextureSampleType, TextureViewDimension};
use crate::PassError;

/// How a shader declares a hardware depth texture ([`DepthKind::Hardware`]).
///
/// [`DepthKind::Hardware`]: super::DepthKind::Hardware
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

fn float_sample() -> TextureSampleType {
    TextureSampleType::Float { filterable: false }
}

impl SraaPass {
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

    /// The bindings, in order, hardware depth declared as `depth`.
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
}
