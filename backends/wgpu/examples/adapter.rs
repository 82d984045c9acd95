fn main() {
    let ctx = subcone_wgpu::GpuContext::new().unwrap();
    println!("{} timestamps={}", ctx.describe(), ctx.timestamps);
}
