//! The crate-private checks of what a host gives a pass: its texture views
//! (size or rect, dimension, samples, layers, usage, format), its buffers,
//! its timestamp writes, and the inputs a configuration requires.

use super::rect::Rect;
use crate::PassError;

/// What a host texture must be for one role.
pub(crate) struct Expect {
    pub(crate) what: &'static str,
    pub(crate) size: (u32, u32),
    pub(crate) samples: u32,
    /// Exact array layer count.
    pub(crate) layers: u32,
    pub(crate) usage: wgpu::TextureUsages,
}

/// Check the texture of view `v` against `e`: 2D, size, samples, layers,
/// usage (format is the caller's). wgpu 30 exposes a view's texture
/// (`TextureView::texture`) but not the view's own range or dimension, so
/// those are the host's contract: a view of the whole texture (mip level 0).
pub(crate) fn check(v: &wgpu::TextureView, e: &Expect) -> Result<(), PassError> {
    check_region(v, e, None)
}

/// [`check`], but with a `rect` the texture's size is not compared with
/// `e.size`: the rect must lie inside it ([`Rect::lies_inside`]), a
/// [`PassError::Rect`] otherwise.
pub(crate) fn check_region(
    v: &wgpu::TextureView,
    e: &Expect,
    rect: Option<&Rect>,
) -> Result<(), PassError> {
    let t = v.texture();
    let found = (t.width(), t.height());
    if t.dimension() != wgpu::TextureDimension::D2 {
        return Err(PassError::Dimension {
            what: e.what,
            found: t.dimension(),
        });
    }
    match rect {
        Some(r) if !r.lies_inside(found) => {
            return Err(PassError::Rect {
                what: e.what,
                rect: *r,
                size: found,
            })
        }
        Some(_) => {}
        None if found != e.size => {
            return Err(PassError::Size {
                what: e.what,
                expected: e.size,
                found,
            })
        }
        None => {}
    }
    if t.sample_count() != e.samples {
        return Err(PassError::SampleCount {
            what: e.what,
            expected: e.samples,
            found: t.sample_count(),
        });
    }
    if t.depth_or_array_layers() != e.layers {
        return Err(PassError::Layers {
            what: e.what,
            expected: e.layers,
            found: t.depth_or_array_layers(),
        });
    }
    if !t.usage().contains(e.usage) {
        return Err(PassError::Usage {
            what: e.what,
            missing: e.usage - t.usage(),
        });
    }
    Ok(())
}

/// Check a pass's output texture: one-sample 2D, one layer, writable as a
/// storage texture, of the `format` the pass was built for (`expected` says
/// where that format was given). Its size is the frame's, returned.
pub(crate) fn check_output(
    output: &wgpu::TextureView,
    format: wgpu::TextureFormat,
    expected: &'static str,
) -> Result<(u32, u32), PassError> {
    check_output_region(output, format, expected, None).map(|r| r.size())
}

/// [`check_output`] for a pass that writes `rect` of its output (the whole
/// texture for `None`): the rect must lie inside the output texture. The
/// rect of pixels to write, returned.
pub(crate) fn check_output_region(
    output: &wgpu::TextureView,
    format: wgpu::TextureFormat,
    expected: &'static str,
    rect: Option<&Rect>,
) -> Result<Rect, PassError> {
    let size = (output.texture().width(), output.texture().height());
    check_region(
        output,
        &Expect {
            what: "output",
            size,
            samples: 1,
            layers: 1,
            usage: wgpu::TextureUsages::STORAGE_BINDING,
        },
        rect,
    )?;
    if output.texture().format() != format {
        return Err(PassError::Format {
            what: "output",
            found: output.texture().format(),
            expected,
        });
    }
    Ok(rect.copied().unwrap_or(Rect::whole(size)))
}

/// Refuse a texture `what` that `textureLoad` does not read as `f32`
/// ([`is_float_color`]).
pub(crate) fn check_float_color(
    what: &'static str,
    v: &wgpu::TextureView,
) -> Result<(), PassError> {
    let format = v.texture().format();
    if is_float_color(format) {
        Ok(())
    } else {
        Err(PassError::Format {
            what,
            found: format,
            expected: "a float, unorm or snorm colour format",
        })
    }
}

/// Whether `format` is read as `f32` by `textureLoad` (a colour format with
/// a float, unorm or snorm sample type).
pub(crate) fn is_float_color(format: wgpu::TextureFormat) -> bool {
    !format.is_depth_stencil_format()
        && matches!(
            format.sample_type(None, None),
            Some(wgpu::TextureSampleType::Float { .. })
        )
}

/// Refuse timestamp writes the device cannot take: without
/// `Features::TIMESTAMP_QUERY`, into a query set of another type, or at an
/// index past its end.
pub(super) fn check_timestamps(
    device: &wgpu::Device,
    t: &wgpu::ComputePassTimestampWrites<'_>,
) -> Result<(), PassError> {
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        return Err(PassError::Config(
            "timestamps: the device was opened without Features::TIMESTAMP_QUERY".into(),
        ));
    }
    if !matches!(t.query_set.ty(), wgpu::QueryType::Timestamp) {
        return Err(PassError::Config(
            "timestamps: the query set is not of QueryType::Timestamp".into(),
        ));
    }
    let count = t.query_set.count();
    for i in [t.beginning_of_pass_write_index, t.end_of_pass_write_index]
        .into_iter()
        .flatten()
    {
        if i >= count {
            return Err(PassError::Config(format!(
                "timestamps: index {i} is past the query set's {count} queries"
            )));
        }
    }
    Ok(())
}

/// Check buffer `b` (`what`) holds `count` elements of `element` bytes and
/// can be bound as storage.
pub(crate) fn check_buffer(
    what: &'static str,
    b: &wgpu::Buffer,
    count: u64,
    element: u64,
) -> Result<(), PassError> {
    if !b.usage().contains(wgpu::BufferUsages::STORAGE) {
        return Err(PassError::BufferUsage {
            what,
            missing: wgpu::BufferUsages::STORAGE,
        });
    }
    let expected = count * element;
    if b.size() < expected {
        return Err(PassError::BufferSize {
            what,
            expected,
            found: b.size(),
        });
    }
    Ok(())
}

/// The input of an `Option` role: `Ok(Some)` when it is given and
/// required, `Ok(None)` when neither; when given and required disagree, a
/// [`PassError::Missing`] naming `missing` or a [`PassError::Unexpected`]
/// naming `unexpected`.
pub(crate) fn required<T>(
    given: Option<T>,
    required: bool,
    missing: &'static str,
    unexpected: &'static str,
) -> Result<Option<T>, PassError> {
    match (given, required) {
        (Some(_), false) => Err(PassError::Unexpected(unexpected)),
        (None, true) => Err(PassError::Missing(missing)),
        (given, _) => Ok(given),
    }
}
