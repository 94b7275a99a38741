//! The Cortex-M0's single-precision multiplication: `__aeabi_fmul` (what the compiler calls for
//! `f32 * f32` on a core without an FPU) answered by `meterstick_core::soft_float::mul_normal`,
//! whose 24 x 24-bit significand product uses the core's 32-bit `muls` instead of a 64-bit
//! multiplication routine; the cases it leaves (zeros, subnormals, infinities, NaNs, overflow,
//! underflow) go to `compiler_builtins`' complete `__mulsf3`. Both round as IEEE 754 does, so the
//! results are bit for bit those of the host (the QEMU test compares the trajectories'
//! checksums). Built for the Cortex-M0 builds that use `compiler_builtins`' arithmetic (QEMU's
//! micro:bit, the Pico with `builtins-float`; `build.rs` sets `soft_fmul`); the Pico's default
//! build takes its floats from the boot ROM instead.

#[allow(unsafe_code)] // declaring compiler_builtins' complete multiplication
unsafe extern "C" {
    fn __mulsf3(a: f32, b: f32) -> f32;
}

/// `a * b`, IEEE 754 binary32, round to nearest even.
#[allow(unsafe_code)] // exporting the symbol the compiler's float calls resolve to; calling the complete routine
#[unsafe(no_mangle)]
pub extern "C" fn __aeabi_fmul(a: f32, b: f32) -> f32 {
    match meterstick_core::soft_float::mul_normal(a.to_bits(), b.to_bits()) {
        Some(bits) => f32::from_bits(bits),
        // SAFETY: `__mulsf3` is compiler_builtins' multiplication, a pure function of its arguments.
        None => unsafe { __mulsf3(a, b) },
    }
}
