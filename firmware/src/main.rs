//! meterstick firmware: the meter-stick scene on a Cortex-M, through the demo rig's loop
//! (`meterstick_core::rig`, generic over `embedded-hal` 1.0), with one of two board bindings:
//!
//! * `qemu-mps2-an386` / `qemu-microbit` ([`qemu`]): headless (no real-time waiting) on QEMU's
//!   Cortex-M4F and Cortex-M0 machines, pins that count their edges, defmt over semihosting and
//!   a semihosting exit status; it also counts SysTick ticks per step for the instruction
//!   count (`scripts/firmware-report.sh`).
//! * `board-blackpill` ([`blackpill`]): the tabletop rig on an STM32F411CEU6 "Black Pill"
//!   (stm32f4xx-hal): one scene step per SysTick period h = 1 ms, stepper STEP/DIR, mode and
//!   fault lights, start button; defmt over RTT with the `log` feature.
#![no_std]
#![no_main]

#[cfg(all(feature = "qemu", feature = "board-blackpill"))]
compile_error!("choose one board binding: a qemu-* feature or board-blackpill");
#[cfg(not(any(feature = "qemu", feature = "board-blackpill")))]
compile_error!("choose a board binding: --features qemu-mps2-an386, qemu-microbit or board-blackpill");

#[cfg(feature = "board-blackpill")]
mod blackpill;
#[cfg(feature = "qemu")]
mod qemu;
mod systick;

use cortex_m as _; // the single-core critical section defmt needs

#[cortex_m_rt::entry]
fn main() -> ! {
    #[cfg(feature = "qemu")]
    qemu::main();
    #[cfg(feature = "board-blackpill")]
    blackpill::main();
}
