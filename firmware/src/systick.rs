//! SysTick as a free-running 24-bit down-counter on the core clock, to measure how long a
//! piece of code takes (in ticks; under QEMU `-icount shift=0` a tick is a fixed number of
//! instructions, calibrated against `cortex_m::asm::delay`, whose loop is 2 instructions per
//! iteration).

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;

/// The counter's range.
pub const MASK: u32 = 0x00FF_FFFF;

/// Starts SysTick free-running at `reload` (at most [`MASK`]) on the core clock.
pub fn start(syst: &mut SYST, reload: u32) {
    syst.disable_interrupt();
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(reload & MASK);
    syst.clear_current();
    syst.enable_counter();
}

#[cfg_attr(not(any(feature = "qemu", feature = "log")), allow(dead_code))]
/// The counter now.
#[must_use]
pub fn now() -> u32 {
    SYST::get_current()
}

#[cfg_attr(not(feature = "qemu"), allow(dead_code))]
/// Ticks from `start` to `end` (it counts down; one wrap at most, full 24-bit reload).
#[must_use]
pub fn elapsed(start: u32, end: u32) -> u32 {
    start.wrapping_sub(end) & MASK
}
