//! The frame conformance suite (`subcone-conformance`) on the CPU backend: the
//! comparison with the CPU backend's own frame only checks determinism here;
//! the `ssaa64` bounds are the CPU's real check.

use subcone_cpu::CpuBackend;

subcone_conformance::conformance_suite!(cpu, CpuBackend::new());
