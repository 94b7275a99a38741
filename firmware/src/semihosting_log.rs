//! The QEMU builds' `defmt` global logger: frames written to the host's stdout through
//! semihosting (`SYS_OPEN(":tt", "w")`, `SYS_WRITE`), with no panic path: `defmt-semihosting`
//! panics on a nested `acquire` and, through the `semihosting` crate, on an invalid handle,
//! which the firmware's link-time check refuses. Here a nested frame (impossible in these
//! builds: no interrupt logs) is dropped, and output is skipped when the console cannot be
//! opened.
#![allow(unsafe_code)]

use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicBool, Ordering};

#[defmt::global_logger]
struct Logger;

/// The encoder and the console handle, used only between `acquire` and `release` (a
/// critical section: one user at a time).
struct State {
    taken: AtomicBool,
    restore: UnsafeCell<critical_section::RestoreState>,
    encoder: UnsafeCell<defmt::Encoder>,
    /// The semihosting handle of the console, `u32::MAX` before opening, 0 when it failed.
    handle: UnsafeCell<u32>,
}

// SAFETY: the cells are touched only inside the critical section taken in `acquire`.
unsafe impl Sync for State {}

static STATE: State = State {
    taken: AtomicBool::new(false),
    restore: UnsafeCell::new(critical_section::RestoreState::invalid()),
    encoder: UnsafeCell::new(defmt::Encoder::new()),
    handle: UnsafeCell::new(u32::MAX),
};

const SYS_OPEN: u32 = 0x01;
const SYS_WRITE: u32 = 0x05;

/// Writes `bytes` to the console handle `handle` (0: none).
fn write_console(handle: u32, bytes: &[u8]) {
    if handle == 0 || handle == u32::MAX || bytes.is_empty() {
        return;
    }
    let args = [handle, bytes.as_ptr() as u32, bytes.len() as u32];
    // SAFETY: SYS_WRITE reads `len` bytes at `ptr`, both valid for the call's duration.
    unsafe {
        cortex_m::asm::semihosting_syscall(SYS_WRITE, args.as_ptr() as u32);
    }
}

fn open_console() -> u32 {
    let name = b":tt\0";
    // Mode 4 ("w") on ":tt" is the host's stdout.
    let args = [name.as_ptr() as u32, 4, 3];
    // SAFETY: SYS_OPEN reads the NUL-terminated name; the arguments live for the call.
    let h = unsafe { cortex_m::asm::semihosting_syscall(SYS_OPEN, args.as_ptr() as u32) };
    if h == u32::MAX { 0 } else { h }
}

// SAFETY: defmt calls these in `acquire`, `write`*, `release` order; the critical section
// makes the cells exclusive.
unsafe impl defmt::Logger for Logger {
    fn acquire() {
        // SAFETY: paired with the `release` in `Logger::release` (or right here when nested).
        let restore = unsafe { critical_section::acquire() };
        if STATE.taken.load(Ordering::Relaxed) {
            // Nested: the outer frame keeps the encoder; this one is dropped.
            // SAFETY: releases the critical section acquired just above.
            unsafe { critical_section::release(restore) };
            return;
        }
        STATE.taken.store(true, Ordering::Relaxed);
        // SAFETY: inside the critical section, sole user of the cells.
        unsafe {
            STATE.restore.get().write(restore);
            let handle = &mut *STATE.handle.get();
            if *handle == u32::MAX {
                *handle = open_console();
            }
            let h = *handle;
            (*STATE.encoder.get()).start_frame(|b| write_console(h, b));
        }
    }

    unsafe fn flush() {}

    unsafe fn release() {
        if !STATE.taken.load(Ordering::Relaxed) {
            return;
        }
        // SAFETY: between `acquire` and here the cells are ours.
        unsafe {
            let h = *STATE.handle.get();
            (*STATE.encoder.get()).end_frame(|b| write_console(h, b));
            let restore = STATE.restore.get().read();
            STATE.taken.store(false, Ordering::Relaxed);
            critical_section::release(restore);
        }
    }

    unsafe fn write(bytes: &[u8]) {
        if !STATE.taken.load(Ordering::Relaxed) {
            return;
        }
        // SAFETY: as in `release`.
        unsafe {
            let h = *STATE.handle.get();
            (*STATE.encoder.get()).write(bytes, |b| write_console(h, b));
        }
    }
}
