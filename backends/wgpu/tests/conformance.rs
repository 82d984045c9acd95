//! The frame conformance suite (`subcone-conformance`) on the wgpu backend:
//! every frame against the CPU backend's and the `ssaa64` reference. Fails,
//! rather than skips, without an adapter when `SUBCONE_REQUIRE_GPU` is set.

use subcone_wgpu::WgpuBackend;

subcone_conformance::conformance_suite!(wgpu, fallible WgpuBackend::new());
