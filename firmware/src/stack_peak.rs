//! The deepest the stack has grown, measured by painting (QEMU builds): [`paint`] fills the free
//! RAM between the end of the static data (`_stack_end`, cortex-m-rt's linker script) and a
//! little below the current stack pointer with a pattern; after a run, [`peak_bytes`] finds the
//! lowest word no longer holding it, so the stack reached at least down to there. The figure is
//! the stack top (`_stack_start`) minus that address: what a board's RAM must hold above its
//! static data for that run (`scripts/firmware-report.sh` prints it per scene).
#![allow(unsafe_code)] // The measurement reads and writes free RAM by address.

use core::ptr::{addr_of, read_volatile, write_volatile};

/// The pattern painted into the free RAM.
const PAINT: u32 = 0xA5C3_5A3C;
/// Bytes left unpainted below the stack pointer of [`paint`] (its own frame and its callees').
const MARGIN: usize = 64;

unsafe extern "C" {
    /// The top of the stack (cortex-m-rt: the end of RAM).
    static _stack_start: u32;
    /// The lowest address the stack may use (cortex-m-rt: the end of `.bss`/`.uninit`).
    static _stack_end: u32;
}

/// Paints the free RAM below the current stack pointer (less [`MARGIN`]).
#[inline(never)]
pub fn paint() {
    let bottom = addr_of!(_stack_end) as usize;
    let top = cortex_m::register::msp::read() as usize - MARGIN;
    let mut p = bottom;
    while p + 4 <= top {
        // SAFETY: [bottom, top) is RAM below the live stack frames and above every static: no
        // object lives there, and nothing else runs (one core, no interrupt touches the stack
        // below this frame while it paints).
        unsafe { write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
}

/// The RAM the stack may grow into, in bytes: the stack top (`_stack_start`) less the end of the
/// static data (`_stack_end`). A run's [`peak_bytes`] beyond it has overflowed.
#[must_use]
pub fn room_bytes() -> u32 {
    (addr_of!(_stack_start) as usize - addr_of!(_stack_end) as usize) as u32
}

/// The deepest the stack reached since [`paint`], in bytes below the stack top.
#[must_use]
#[inline(never)]
pub fn peak_bytes() -> u32 {
    let (bottom, top) = (addr_of!(_stack_end) as usize, addr_of!(_stack_start) as usize);
    let mut p = bottom;
    // SAFETY: reads of RAM between the statics' end and the stack top, word-aligned
    // (`_stack_end` is 4-aligned: cortex-m-rt asserts it).
    while p < top && unsafe { read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    (top - p) as u32
}
