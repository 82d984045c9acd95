//! Print the adapter subcone's wgpu backend opens, the limits it got and how
//! its passes are timed (`scripts/gpu-check` writes the same as JSON).
//!
//! `WGPU_BACKEND=vulkan cargo run -p subcone-wgpu --example adapter`
fn main() {
    match subcone_wgpu::GpuContext::new() {
        Ok(ctx) => {
            let l = ctx.device.limits();
            println!("{}", ctx.describe());
            println!("passes timed by: {}", ctx.timing_source());
            println!(
                "largest 2D texture {}, storage binding {} bytes, buffer {} bytes, {} storage buffers per stage",
                l.max_texture_dimension_2d,
                l.max_storage_buffer_binding_size,
                l.max_buffer_size,
                l.max_storage_buffers_per_shader_stage
            );
        }
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}
