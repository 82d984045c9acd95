//! The texture formats the bindings name: the storage formats a
//! [`Group`] declares with their WGSL names, and the formats a
//! pass's output may be written in.
//!
//! [`Group`]: super::Group

use crate::PassError;

/// The formats [`Group::storage_texture`] declares.
///
/// [`Group::storage_texture`]: super::Group::storage_texture
pub(super) const STORAGE_FORMATS: &str =
    "Rgba8Unorm, Rgba16Float, Rgba32Float, R32Float or R32Uint";

/// The WGSL name of a storage texture format [`Group::storage_texture`]
/// declares, or `None`.
///
/// [`Group::storage_texture`]: super::Group::storage_texture
pub(super) fn storage_format_name(format: wgpu::TextureFormat) -> Option<&'static str> {
    match format {
        wgpu::TextureFormat::Rgba8Unorm => Some("rgba8unorm"),
        wgpu::TextureFormat::Rgba16Float => Some("rgba16float"),
        wgpu::TextureFormat::Rgba32Float => Some("rgba32float"),
        wgpu::TextureFormat::R32Float => Some("r32float"),
        wgpu::TextureFormat::R32Uint => Some("r32uint"),
        _ => None,
    }
}

/// Whether a pass's output may be of `format`: the formats a host's
/// output is written in ([`OUTPUT_FORMATS`]).
fn is_output_format(format: wgpu::TextureFormat) -> bool {
    matches!(
        format,
        wgpu::TextureFormat::Rgba8Unorm
            | wgpu::TextureFormat::Rgba16Float
            | wgpu::TextureFormat::Rgba32Float
    )
}

/// The output formats the passes write: `Rgba8Unorm`, `Rgba16Float`,
/// `Rgba32Float` (storage textures of core WebGPU).
pub(crate) const OUTPUT_FORMATS: &str = "Rgba8Unorm, Rgba16Float or Rgba32Float";

/// Refuse an output format the passes cannot write.
pub(crate) fn check_output_format(format: wgpu::TextureFormat) -> Result<(), PassError> {
    match is_output_format(format) {
        true => Ok(()),
        false => Err(PassError::Format {
            what: "output",
            found: format,
            expected: OUTPUT_FORMATS,
        }),
    }
}
