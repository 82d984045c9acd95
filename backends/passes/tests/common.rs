#![allow(dead_code)]
//! What the GPU tests of this crate share: a host device, or a skip that
//! fails when `SUBCONE_REQUIRE_GPU` is set.

/// `open()`'s device, or `None` (skip, saying why) when there is no
/// adapter and a GPU is not required; panics when one is
/// ([`subcone_scene::conformance::or_skip`]).
pub fn device_or_skip<T>(what: &str, open: impl FnOnce() -> Result<T, String>) -> Option<T> {
    subcone_scene::conformance::or_skip(what, open())
}

/// Mean FLIP of two 8-bit sRGB images (nv-flip, 67 pixels per degree, as
/// the conformance suite measures) and its 99th percentile.
pub fn flip(w: u32, h: u32, reference: &[u8], test: &[u8]) -> (f32, f32) {
    let rgb8 = |data: &[u8]| subcone_metrics::Rgb8 {
        width: w,
        height: h,
        data: data.to_vec(),
    };
    let f = subcone_metrics::flip(&rgb8(reference), &rgb8(test)).unwrap();
    (f.mean as f32, f.p99())
}
