//! What both host examples do the same way: open a device as a host would,
//! make textures, read a texture back, encode 8-bit sRGB and save it.
//! Included by each example (and so by the tests that include the
//! examples, which use these helpers too).
#![allow(dead_code)] // each includer uses its own part

use glam::Vec3;

/// Open a device as a host would: `WGPU_BACKEND` or Vulkan, Metal, DX12,
/// with wgpu's default limits.
pub fn open_device() -> Result<(wgpu::Device, wgpu::Queue), String> {
    open_device_with("host", wgpu::Features::empty(), |_| wgpu::Limits::default())
}

/// [`open_device`] asking for the adapter's own limits (as
/// `subcone_wgpu::GpuContext::new` does).
pub fn open_device_with_adapter_limits() -> Result<(wgpu::Device, wgpu::Queue), String> {
    open_device_with(
        "host, adapter limits",
        wgpu::Features::empty(),
        wgpu::Adapter::limits,
    )
}

/// Open a device labelled `label` on the first adapter, with those of the
/// `optional` features the adapter has and the `limits` it gives for that
/// adapter.
pub fn open_device_with(
    label: &str,
    optional: wgpu::Features,
    limits: impl FnOnce(&wgpu::Adapter) -> wgpu::Limits,
) -> Result<(wgpu::Device, wgpu::Queue), String> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
    let instance = wgpu::Instance::new(desc);
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: None,
        apply_limit_buckets: false,
    }))
    .map_err(|e| format!("no GPU adapter: {e}"))?;
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some(label),
        required_features: adapter.features() & optional,
        required_limits: limits(&adapter),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::Performance,
        trace: wgpu::Trace::Off,
    }))
    .map_err(|e| format!("cannot open a device: {e}"))
}

/// A 2D texture of one mip level: `layers` array layers (1 for a plain 2D
/// texture) of `samples` samples per pixel.
pub fn texture(
    device: &wgpu::Device,
    label: &str,
    (width, height, layers): (u32, u32, u32),
    samples: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: samples,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// The layout of a host bind group of one uniform buffer (binding 0) that
/// the stages `visibility` read.
pub fn uniform_layout(
    device: &wgpu::Device,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("host"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    })
}

/// The bind group of `layout` ([`uniform_layout`]) over `buffer`.
pub fn uniform_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buffer: &wgpu::Buffer,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("host"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: buffer.as_entire_binding(),
        }],
    })
}

/// Wait until the device has finished all submitted work.
pub fn wait(device: &wgpu::Device) -> Result<(), String> {
    device
        .poll(wgpu::PollType::Wait {
            submission_index: None,
            timeout: Some(std::time::Duration::from_secs(300)),
        })
        .map(|_| ())
        .map_err(|e| format!("waiting for the GPU: {e}"))
}

/// The bytes of `buffer` (`MAP_READ`), once the copies into it already
/// submitted have run.
pub fn read_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>, String> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = tx.send(r);
    });
    wait(device)?;
    rx.recv_timeout(std::time::Duration::from_secs(5))
        .map_err(|_| "read-back did not complete".to_string())?
        .map_err(|e| format!("read-back failed: {e}"))?;
    let data = buffer
        .get_mapped_range(..)
        .map_err(|e| format!("read-back failed: {e}"))?;
    Ok(data.to_vec())
}

/// Submit `enc` with a copy of `texture` (`Rgba32Float`) and read it back.
pub fn read_rgba32f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    enc: wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, String> {
    read_texels(device, queue, enc, texture)
}

/// Submit `enc` with a copy of `texture` and read it back, one `T` per
/// texel (`T` the texel's size: `[f32; 4]` for `Rgba32Float`, `f32` for
/// `R32Float`).
pub fn read_texels<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mut enc: wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> Result<Vec<T>, String> {
    let texel = size_of::<T>() as u32;
    let (w, h) = (texture.width(), texture.height());
    let row = (w * texel).div_ceil(256) * 256;
    let buf = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read-back"),
        size: (row * h) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    enc.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buf,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(h),
            },
        },
        texture.size(),
    );
    queue.submit([enc.finish()]);
    let data = read_buffer(device, &buf)?;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let o = (y * row + x * texel) as usize;
            out.push(bytemuck::pod_read_unaligned(&data[o..o + texel as usize]));
        }
    }
    Ok(out)
}

/// Write linear RGB `pixels` (row-major, `width × height`) to `path` as an
/// 8-bit sRGB PNG, and say so.
pub fn save_png(path: &str, width: u32, height: u32, pixels: &[Vec3]) -> Result<(), String> {
    image::save_buffer(
        path,
        &to_srgb8(pixels),
        width,
        height,
        image::ExtendedColorType::Rgb8,
    )
    .map_err(|e| e.to_string())?;
    println!("wrote {path}");
    Ok(())
}

/// Linear RGB to 8-bit sRGB, row-major.
pub fn to_srgb8(pixels: &[Vec3]) -> Vec<u8> {
    let enc = |c: f32| {
        let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
        let s = if c <= 0.003_130_8 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0 + 0.5) as u8
    };
    pixels
        .iter()
        .flat_map(|p| [enc(p.x), enc(p.y), enc(p.z)])
        .collect()
}
