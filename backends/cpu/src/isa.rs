//! Run-time dispatch to the instruction set the machine has.
//!
//! The release binary targets baseline x86-64 (SSE2) so that it runs
//! everywhere. The hot loops (BVH traversal, SDF programs and ray packets,
//! SRAA reconstruction) are written once as ordinary `#[inline]` Rust and
//! compiled a second and third time inside a function that enables AVX2 (with
//! FMA, BMI and friends: x86-64-v3) or AVX-512 (x86-64-v4): [`Isa::run`] calls
//! its closure inside that function, where LLVM inlines the loops and
//! vectorises them for the wider registers.
//!
//! **Images are identical on every path.** Rust never contracts `a·b + c` into
//! a fused multiply-add (that would change the rounding), the lane-wise
//! operations the wider paths use (`+ − × ÷ √ min max`) are correctly rounded
//! IEEE operations on every path, and no transcendental function changes
//! with the instruction set (libm is software). The `isa` test renders every
//! supported path and compares the frames bit for bit.
//!
//! ```
//! use subcone_cpu::isa::Isa;
//!
//! let best = Isa::detected();
//! assert!(best.is_supported());
//! // Any path can be forced; an unsupported one falls back to the best below it.
//! let sum = Isa::Baseline.run(|| (0..10).sum::<u32>());
//! assert_eq!(sum, 45);
//! println!("running on {}", best);
//! ```
#![allow(unsafe_code)]

use std::fmt;
use std::sync::OnceLock;

/// An instruction-set path of the CPU backend, from the most portable up.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum Isa {
    /// What the binary was compiled for (baseline x86-64: SSE2), on any CPU.
    Baseline,
    /// x86-64-v3: AVX2, FMA, BMI1/2, LZCNT, MOVBE, F16C.
    Avx2,
    /// x86-64-v4: AVX2 plus AVX-512 F, BW, CD, DQ and VL.
    Avx512,
}

impl Isa {
    /// Every path, from the most portable up.
    pub const ALL: [Isa; 3] = [Isa::Baseline, Isa::Avx2, Isa::Avx512];

    /// The widest path this CPU supports (detected once per process).
    pub fn detected() -> Isa {
        static DETECTED: OnceLock<Isa> = OnceLock::new();
        *DETECTED.get_or_init(|| {
            Isa::ALL
                .into_iter()
                .rev()
                .find(|i| i.is_supported())
                .unwrap_or(Isa::Baseline)
        })
    }

    /// Every path this CPU supports, from the most portable up.
    pub fn supported() -> Vec<Isa> {
        Isa::ALL.into_iter().filter(|i| i.is_supported()).collect()
    }

    /// Whether this CPU can run the path.
    pub fn is_supported(self) -> bool {
        match self {
            Isa::Baseline => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => {
                std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma")
                    && std::arch::is_x86_feature_detected!("bmi1")
                    && std::arch::is_x86_feature_detected!("bmi2")
                    && std::arch::is_x86_feature_detected!("lzcnt")
                    && std::arch::is_x86_feature_detected!("movbe")
                    && std::arch::is_x86_feature_detected!("f16c")
            }
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => {
                Isa::Avx2.is_supported()
                    && std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512bw")
                    && std::arch::is_x86_feature_detected!("avx512cd")
                    && std::arch::is_x86_feature_detected!("avx512dq")
                    && std::arch::is_x86_feature_detected!("avx512vl")
            }
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// This path if the CPU supports it, else the widest supported one below.
    /// Each path's features include those of the paths below it, so this is
    /// the narrower of `self` and [`detected`](Isa::detected): one load, cheap
    /// enough for [`run`](Isa::run) to call in every inner loop.
    #[inline]
    pub fn or_supported(self) -> Isa {
        self.min(Isa::detected())
    }

    /// A short name: `baseline`, `avx2`, `avx512`.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            Isa::Avx2 => "avx2",
            Isa::Avx512 => "avx512",
        }
    }

    /// Runs `f` on this path (or the widest supported one below it): the
    /// closure, and every `#[inline]` function it calls, is compiled with the
    /// path's instructions enabled. Mark a large closure `#[inline(always)]`
    /// (`isa.run(#[inline(always)] || …)`): it is then compiled into each
    /// path's function instead of being called from it as baseline code.
    #[inline]
    pub fn run<R>(self, f: impl FnOnce() -> R) -> R {
        match self.or_supported() {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `or_supported` returned the path only after
            // `is_x86_feature_detected!` found every feature it enables.
            Isa::Avx512 => unsafe { avx512::run(f) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above.
            Isa::Avx2 => unsafe { avx2::run(f) },
            _ => f(),
        }
    }
}

impl fmt::Display for Isa {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Isa::Baseline => "baseline x86-64 (SSE2)",
            Isa::Avx2 => "AVX2 (x86-64-v3)",
            Isa::Avx512 => "AVX-512 (x86-64-v4)",
        })
    }
}

impl std::str::FromStr for Isa {
    type Err = String;

    fn from_str(s: &str) -> Result<Isa, String> {
        Isa::ALL
            .into_iter()
            .find(|i| i.name() == s)
            .ok_or_else(|| format!("unknown instruction set {s:?}: baseline, avx2 or avx512"))
    }
}

// Each path's entry point lives in a module of its own: rustc places a
// generic function's instances in the codegen unit of the function's module,
// so every closure run on AVX2 lands in one unit and every closure run on
// AVX-512 in another, and LLVM optimises the paths side by side instead of
// one after the other (the SDF interpreter, inlined into each path, was most
// of this crate's build time, in one unit).

#[cfg(target_arch = "x86_64")]
mod avx2 {
    #[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,movbe,f16c,popcnt")]
    #[inline(never)]
    pub(super) unsafe fn run<R>(f: impl FnOnce() -> R) -> R {
        f()
    }
}

#[cfg(target_arch = "x86_64")]
mod avx512 {
    #[target_feature(
        enable = "avx2,fma,bmi1,bmi2,lzcnt,movbe,f16c,popcnt,avx512f,avx512bw,avx512cd,avx512dq,avx512vl"
    )]
    #[inline(never)]
    pub(super) unsafe fn run<R>(f: impl FnOnce() -> R) -> R {
        f()
    }
}
