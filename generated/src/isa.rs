//! The instruction set the Taylor kernels run in: AVX2 where the CPU has it, else the x86_64
//! baseline (SSE2). Hand-written.
//!
//! Why: compiled for AVX2 (three-operand VEX encoding: no register copies before each
//! operation), the rocking right-hand sides cost 12–29 % less, a Fig. 3 simulation 8–10 %
//! (docs/performance.md). A build for AVX2 alone would not start on older CPUs; one check per
//! call (cached by std) picks the code.
//!
//! Why the results do not change: Rust never fuses a multiply and an add into an FMA, nor
//! reorders a floating-point sum, so both instruction sets compute the same operations in the
//! same order, rounded the same. `tests/isa.rs` compares the rocking kernels of every variant
//! both ways bit for bit, and the digests of the example outputs (`.ci/digests.sh`) do not move.

/// `$call` (a call of an `#[inline(always)]` kernel of [`crate::taylor`]) compiled for the best
/// instruction set of [`run_best`]: `best_isa!(taylor::full::rocking_rhs_free(&mut x, s, &p))`.
/// A macro so that the closure is always inlined: otherwise the kernel may stay out of line, in
/// baseline code.
#[macro_export]
macro_rules! best_isa {
    ($call:expr) => {
        $crate::isa::run_best(
            #[inline(always)]
            || $call,
        )
    };
}

/// `f()`, compiled for AVX2 where the CPU has it (through [`best_isa!`], which inlines `f`).
#[inline(always)]
pub fn run_best<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, checked just above.
        return unsafe { avx2(f) };
    }
    f()
}

/// `f()` compiled with AVX2 enabled, so that `f` and everything inlined into it use it.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// The instruction set [`run_best`] runs on this CPU: `"avx2"` or `"baseline"`.
#[must_use]
pub fn best() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        return "avx2";
    }
    "baseline"
}
