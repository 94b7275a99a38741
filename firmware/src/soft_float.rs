//! The Cortex-M0's single-precision multiplication and addition: `__aeabi_fmul`, `__aeabi_fadd`
//! and `__aeabi_fsub` (what the compiler calls for `f32 * f32`, `+` and `-` on a core without an
//! FPU) answered by `meterstick_core::soft_float::{mul_normal, add_normal}`, which take the common
//! case (normal operands and results) in 32-bit words: the significand product from the core's
//! 32-bit `muls` instead of a 64-bit multiplication routine, the rounding without branches. The
//! cases they leave (subnormals, infinities, NaNs, overflow, underflow) go to `compiler_builtins`'
//! complete `__mulsf3` and `__addsf3`. Both round as IEEE 754 does, so the results are bit for
//! bit those of the host (the QEMU test compares the trajectories' checksums). Built for the
//! Cortex-M0 builds that use `compiler_builtins`' arithmetic (QEMU's micro:bit, the Pico with
//! `builtins-float`; `build.rs` sets `soft_float`); the Pico's default build takes its floats from
//! the boot ROM instead.
//!
//! The routines take and return the bit patterns (`u32`): in the Cortex-M0's soft-float calling
//! convention an `f32` is passed in a core register just as a `u32` is, and on bits the compiler
//! cannot turn a test of the pattern (`x & !SIGN == 0`) back into a float comparison, itself a
//! library call.

use meterstick_core::soft_float::{add_normal, mul_normal};

#[allow(unsafe_code)] // declaring compiler_builtins' complete routines
unsafe extern "C" {
    fn __mulsf3(a: u32, b: u32) -> u32;
    fn __addsf3(a: u32, b: u32) -> u32;
}

/// `a * b`, IEEE 754 binary32, round to nearest even.
#[allow(unsafe_code)] // exporting the symbol the compiler's float calls resolve to; calling the complete routine
#[unsafe(no_mangle)]
pub extern "C" fn __aeabi_fmul(a: u32, b: u32) -> u32 {
    match mul_normal(a, b) {
        Some(bits) => bits,
        // SAFETY: `__mulsf3` is compiler_builtins' multiplication, a pure function of its arguments.
        None => unsafe { __mulsf3(a, b) },
    }
}

/// `a + b`, IEEE 754 binary32, round to nearest even.
#[allow(unsafe_code)] // as `__aeabi_fmul`
#[unsafe(no_mangle)]
pub extern "C" fn __aeabi_fadd(a: u32, b: u32) -> u32 {
    match add_normal(a, b) {
        Some(bits) => bits,
        // SAFETY: `__addsf3` is compiler_builtins' addition, a pure function of its arguments.
        None => unsafe { __addsf3(a, b) },
    }
}

/// `a - b` = `a + (-b)`, IEEE 754 binary32, round to nearest even.
#[allow(unsafe_code)] // as `__aeabi_fmul`
#[unsafe(no_mangle)]
pub extern "C" fn __aeabi_fsub(a: u32, b: u32) -> u32 {
    __aeabi_fadd(a, b ^ 0x8000_0000)
}
