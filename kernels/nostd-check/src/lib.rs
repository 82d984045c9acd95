//! Calls every kernel family from a `#![no_std]` staticlib with its own panic
//! handler. It only has to link: a `std` in the graph would bring a second
//! `panic_impl`.
#![no_std]

use subcone_kernels::ctss::{trace, CtssParams};
use subcone_kernels::glam::Vec3;
use subcone_kernels::mask::{visibility_mask, MaskPlacement};
use subcone_kernels::passes::{required_passes, SceneFeatures, Technique};
use subcone_kernels::sraa::{bilateral_weight, Geometry, SraaParams};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// An exported symbol that uses the kernels, so nothing is optimised away.
#[no_mangle]
pub extern "C" fn subcone_nostd_check(x: f32) -> f32 {
    let w = bilateral_weight(&SraaParams::PAPER, &Geometry::new(Vec3::Y, 1.0), &Geometry::new(Vec3::Y, x));
    let m = visibility_mask(x, subcone_kernels::glam::Vec2::new(x, 1.0), MaskPlacement::Derived);
    let p = required_passes(Technique::Ctss, SceneFeatures::IS_SDF).map(|p| p.bits()).unwrap_or(0);
    let r = trace(
        &CtssParams::new(0.01),
        Vec3::ZERO,
        Vec3::NEG_Z,
        Vec3::X,
        Vec3::Y,
        |q| (q - Vec3::new(0.0, 0.0, -5.0)).length() - x,
        |q| q.normalize_or_zero(),
        |_, _| Vec3::ONE,
        Vec3::ZERO,
    );
    w + m.count_ones() as f32 + p as f32 + r.color.x
}
