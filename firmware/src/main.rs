//! meterstick firmware: the meter-stick scene on a Cortex-M, through the demo rig's loop
//! (`meterstick_rig`, rig/: generic over `embedded-hal` 1.0), with one of these board bindings:
//!
//! * `qemu-mps2-an386` / `qemu-microbit` / `qemu-mps2-an505` ([`qemu`]): headless (no real-time
//!   waiting) on QEMU's Cortex-M4F, Cortex-M0 and Cortex-M33 (with FPU, in Secure state)
//!   machines, pins that count their edges, defmt over semihosting and a semihosting exit
//!   status; it also counts SysTick ticks per step for the instruction count
//!   (`scripts/firmware-report.sh`).
//! * `board-blackpill` ([`blackpill`]): the tabletop rig on an STM32F411CEU6 "Black Pill"
//!   (stm32f4xx-hal): one scene step per SysTick period h = 1 ms, stepper STEP/DIR, mode and
//!   fault lights, start and preset buttons; defmt over RTT with the `log` feature. With
//!   `rig-stack`, the rig of the 3-block stack instead ([`realtime_stack`]): a light set per
//!   interface, no stepper; the host link as the meter-stick rig's.
//! * `board-pico2` / `board-pico` ([`pico`]): the same rig on a Raspberry Pi Pico 2 (RP2350,
//!   rp235x-hal) or Pico (RP2040, rp2040-hal), flashed from a `.uf2` file without a probe; with
//!   `link`, a rig of both scenes: the meter stick at boot, the 3-block stack when the host
//!   selects it (`realtime_stack::run_both_scenes`, a third light set); with `rig-stick-3d`
//!   (no `link`), the meter stick in three dimensions ([`realtime_stick_3d`]).
//!
//! The boards share the real-time loop ([`realtime`]), for either scene. With `link`, the rig is driven from a host
//! (`meterstick_rig::session`, the `meterstick-link` protocol): under QEMU over the machine's UART ([`uart`],
//! [`qemu_link`]), on the Black Pill over USB CDC (its USB-C port) or with `uart-link` over
//! USART2, on the Picos over UART0.
//!
//! **No panic path.** The panic handler of every QEMU build, of the Black Pill's without `log`
//! and without the USB link (`link` over USB; `uart-link` is fine) and of the Pico 2's without
//! `log` (with or without `link`) calls a function that is declared but defined nowhere, so a
//! panic path that survives optimisation fails the link with an undefined symbol
//! `meterstick_firmware_has_a_panic_path`: those builds link, so none has one
//! (`scripts/panic-paths.sh` lists the paths when one appears). Three dependencies keep panic
//! paths that cannot be removed from here: `defmt-rtt` panics when its logger is taken
//! reentrantly (a log from an interrupt during a log), by design; the USB stack (`usb-device`
//! 0.3, `synopsys-usb-otg` 0.4, `usbd-serial` 0.2) has about 60 (descriptor-writer asserts,
//! endpoint lookups, FIFO indexing); rp2040-hal 0.12 has one, a division by zero in its clock
//! set-up (`clocks::fractional_div`), run once at boot. So the Black Pill's `log` or USB `link`
//! builds, the Pico 2's `log` builds and every Pico build keep a panic handler that halts (and
//! logs, with `log`); the core, the rig loop, the protocol and the session, which they share
//! with the checked builds, are proven panic-free by those, and the rigs with the link on a UART
//! (Black Pill `uart-link`, Pico 2 `link`; no `log`) are checked whole.
#![no_std]
#![no_main]

#[cfg(any(
    all(feature = "qemu", any(feature = "board-blackpill", feature = "board-pico2", feature = "board-pico")),
    all(feature = "board-blackpill", any(feature = "board-pico2", feature = "board-pico")),
    all(feature = "board-pico2", feature = "board-pico"),
))]
compile_error!("choose one board binding: a qemu-* feature, board-blackpill, board-pico2 or board-pico");
#[cfg(not(any(
    feature = "qemu",
    feature = "board-blackpill",
    feature = "board-pico2",
    feature = "board-pico"
)))]
compile_error!(
    "choose a board binding: --features qemu-mps2-an386, qemu-microbit, qemu-mps2-an505, board-blackpill, \
     board-pico2 or board-pico"
);
#[cfg(all(feature = "qemu-mps2-an505", feature = "link"))]
compile_error!(
    "the host link under QEMU runs on mps2-an386 and microbit; mps2-an505 has no UART driver here"
);
#[cfg(all(feature = "uart-link", not(feature = "board-blackpill")))]
compile_error!("uart-link is the Black Pill's (the Picos' `link` is on a UART already)");
#[cfg(all(feature = "rig-stack", not(feature = "board-blackpill")))]
compile_error!("rig-stack is a Black Pill build (board-blackpill)");
#[cfg(all(
    feature = "rig-stick-3d",
    any(feature = "link", not(any(feature = "board-pico2", feature = "board-pico")))
))]
compile_error!("rig-stick-3d is a Pico 2 or Pico build (board-pico2, board-pico) without `link`");
#[cfg(all(feature = "builtins-float", not(feature = "board-pico")))]
compile_error!("builtins-float is the Pico's (RP2040) choice");

#[cfg(feature = "qemu-algebra")]
mod algebra_bench;
#[cfg(feature = "board-blackpill")]
mod blackpill;
#[cfg(any(feature = "board-pico2", feature = "board-pico"))]
mod pico;
#[cfg(all(feature = "qemu", not(feature = "link")))]
mod qemu;
#[cfg(all(feature = "qemu", feature = "link"))]
mod qemu_link;
#[cfg(any(feature = "board-blackpill", feature = "board-pico2", feature = "board-pico"))]
// The stack rig's build uses its loop, not the meter-stick rig's construction and buttons.
#[cfg_attr(any(feature = "rig-stack", feature = "rig-stick-3d"), allow(dead_code))]
mod realtime;
#[cfg(any(feature = "rig-stack", both_scenes))]
mod realtime_stack;
#[cfg(feature = "rig-stick-3d")]
mod realtime_stick_3d;
#[cfg(feature = "qemu")]
mod semihosting_log;
#[cfg(soft_float)]
mod soft_float;
#[cfg(all(feature = "qemu", not(feature = "link")))]
mod stack_peak;
mod systick;
#[cfg(all(feature = "qemu", feature = "link"))]
mod uart;

use cortex_m as _; // the single-core critical section defmt needs

#[cortex_m_rt::entry]
fn main() -> ! {
    #[cfg(all(feature = "qemu", not(feature = "link")))]
    qemu::main();
    #[cfg(all(feature = "qemu", feature = "link"))]
    qemu_link::main();
    #[cfg(feature = "board-blackpill")]
    blackpill::main();
    #[cfg(any(feature = "board-pico2", feature = "board-pico"))]
    pico::main();
}

/// The panic handler: it references a symbol that exists nowhere, so the final link fails
/// (`undefined symbol: meterstick_firmware_has_a_panic_path`) when any panic path is left
/// after optimisation. A firmware that links cannot panic.
#[cfg(not(any(
    feature = "panic-locate",
    all(
        feature = "board-blackpill",
        any(feature = "log", all(feature = "link", not(feature = "uart-link")))
    ),
    all(feature = "board-pico2", feature = "log"),
    feature = "board-pico"
)))]
#[panic_handler]
#[allow(unsafe_code)]
fn panic(_info: &core::panic::PanicInfo<'_>) -> ! {
    unsafe extern "Rust" {
        fn meterstick_firmware_has_a_panic_path() -> !;
    }
    // SAFETY: never executed in a firmware that links: the symbol is not defined anywhere.
    unsafe { meterstick_firmware_has_a_panic_path() }
}

/// The rig with `log` or the USB link (defmt-rtt and the USB stack keep panic paths, see the
/// crate docs): log (with `log`) and halt.
#[cfg(all(
    any(
        all(
            feature = "board-blackpill",
            any(feature = "log", all(feature = "link", not(feature = "uart-link")))
        ),
        all(feature = "board-pico2", feature = "log"),
        feature = "board-pico"
    ),
    not(feature = "panic-locate")
))]
#[panic_handler]
fn panic(_info: &core::panic::PanicInfo<'_>) -> ! {
    #[cfg(feature = "log")]
    defmt::error!("panic");
    loop {
        cortex_m::asm::nop();
    }
}

/// With `panic-locate` (diagnosis only, `scripts/panic-paths.sh`): a panic handler that links,
/// so that the panic paths can be listed from the ELF.
#[cfg(feature = "panic-locate")]
#[panic_handler]
fn panic(_info: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        cortex_m::asm::udf();
    }
}

#[cfg(feature = "qemu")]
#[allow(unsafe_code)] // cortex-m-rt requires the HardFault handler to be `unsafe fn`.
#[cortex_m_rt::exception]
unsafe fn HardFault(_frame: &cortex_m_rt::ExceptionFrame) -> ! {
    defmt::println!("HARDFAULT");
    semihosting::process::exit(102)
}
