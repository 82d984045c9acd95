#![allow(dead_code)]
//! What the GPU tests of this crate share: a host device, or a skip that
//! fails when `SUBCONE_REQUIRE_GPU` is set.

/// Whether a GPU is required (`SUBCONE_REQUIRE_GPU` set to anything but `0`
/// or empty): the tests then fail instead of skipping without an adapter.
pub fn gpu_required() -> bool {
    std::env::var("SUBCONE_REQUIRE_GPU").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// `open()`'s device, or `None` (skip, saying why) when there is no
/// adapter and a GPU is not required; panics when one is.
pub fn device_or_skip<T>(what: &str, open: impl FnOnce() -> Result<T, String>) -> Option<T> {
    match open() {
        Ok(d) => Some(d),
        Err(e) if !gpu_required() => {
            eprintln!("SKIPPED ({what}): no GPU adapter and SUBCONE_REQUIRE_GPU unset: {e}");
            None
        }
        Err(e) => panic!("{what}: no GPU adapter, and SUBCONE_REQUIRE_GPU is set: {e}"),
    }
}

/// Mean FLIP of two 8-bit sRGB images (nv-flip, 67 pixels per degree, as
/// the conformance suite measures) and its 99th percentile.
pub fn flip(w: u32, h: u32, reference: &[u8], test: &[u8]) -> (f32, f32) {
    let r = nv_flip::FlipImageRgb8::with_data(w, h, reference);
    let t = nv_flip::FlipImageRgb8::with_data(w, h, test);
    let error = nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mut pool = nv_flip::FlipPool::from_image(&error);
    (pool.mean(), pool.get_percentile(0.99, true))
}
