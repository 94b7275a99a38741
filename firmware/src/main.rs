//! meterstick firmware: runs the core on a Cortex-M and reports over defmt.
//!
//! Under QEMU (`qemu-*` features) the defmt frames go out over semihosting and the
//! firmware ends with a semihosting exit status: 0 when every check passed.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use meterstick_core::lcp::{Lcp, Lemke};

use cortex_m as _; // provides the single-core critical section defmt needs
use defmt_semihosting as _;

#[entry]
fn main() -> ! {
    defmt::println!("meterstick-firmware {} core {}", env!("CARGO_PKG_VERSION"), meterstick_core::VERSION);
    // Kostreva's cycling example in f32: z = (1/3, 1/3, 1/3).
    let lcp =
        Lcp::<f32, 3>::from_rows(&[[1.0, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]], &[-1.0, -1.0, -1.0]);
    let code = match Lemke::<f32, 3>::new().solve(&lcp) {
        Ok(sol) => {
            defmt::println!(
                "lcp3 z = [{=f32}, {=f32}, {=f32}] pivots={=u32}",
                sol.z[0],
                sol.z[1],
                sol.z[2],
                sol.pivots
            );
            0
        }
        Err(e) => {
            defmt::println!("lcp3 error: {}", e);
            1
        }
    };
    defmt::println!("exit {=i32}", code);
    semihosting::process::exit(code)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    defmt::println!("PANIC at {}", info.location().map_or(0, core::panic::Location::line));
    semihosting::process::exit(101)
}

#[allow(unsafe_code)] // cortex-m-rt requires the HardFault handler to be `unsafe fn`.
#[cortex_m_rt::exception]
unsafe fn HardFault(_frame: &cortex_m_rt::ExceptionFrame) -> ! {
    defmt::println!("HARDFAULT");
    semihosting::process::exit(102)
}
