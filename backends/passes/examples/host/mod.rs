//! What both host examples do the same way: open a device as a host would,
//! read a texture back, encode 8-bit sRGB. Included by each example (and so
//! by the tests that include the examples).
#![allow(dead_code)] // each includer uses its own part

use glam::Vec3;

/// Open a device as a host would: `WGPU_BACKEND` or Vulkan, Metal, DX12.
pub fn open_device() -> Result<(wgpu::Device, wgpu::Queue), String> {
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
        label: Some("host"),
        required_features: wgpu::Features::empty(),
        required_limits: wgpu::Limits::default(),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::Performance,
        trace: wgpu::Trace::Off,
    }))
    .map_err(|e| format!("cannot open a device: {e}"))
}

/// Submit `enc` with a copy of `texture` (`Rgba32Float`) and read it back.
pub fn read_rgba32f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mut enc: wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, String> {
    let (w, h) = (texture.width(), texture.height());
    let row = (w * 16).div_ceil(256) * 256;
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
    let (tx, rx) = std::sync::mpsc::channel();
    buf.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::Wait {
            submission_index: None,
            timeout: Some(std::time::Duration::from_secs(300)),
        })
        .map_err(|e| format!("waiting for the GPU: {e}"))?;
    rx.recv_timeout(std::time::Duration::from_secs(5))
        .map_err(|_| "read-back did not complete".to_string())?
        .map_err(|e| format!("read-back failed: {e}"))?;
    let data = buf
        .get_mapped_range(..)
        .map_err(|e| format!("read-back failed: {e}"))?;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let o = (y * row + x * 16) as usize;
            out.push(bytemuck::pod_read_unaligned(&data[o..o + 16]));
        }
    }
    Ok(out)
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
