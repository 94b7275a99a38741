//! meterstick firmware: runs the core on a Cortex-M and reports over defmt.
//!
//! It solves a small LCP, then runs the paper's slow scene (v = 0.1 m/s) and a fast one
//! (v = 5 m/s) in f32 with the reduced 6x6 LCP, printing each run's outcome, switch
//! events, statistics and a checksum of the f32 trajectory (FNV-1a over the bits of the
//! rod state after every step). Under QEMU (`qemu-*` features) the defmt frames go out over
//! semihosting and the firmware ends with a semihosting exit status: 0 when the LCP was
//! solved and both scenes ended as the paper says (balanced, fell).
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use meterstick_core::lcp::{Lcp, Lemke};
use meterstick_core::scene::{Outcome, Scene6, SceneParams};

use cortex_m as _; // provides the single-core critical section defmt needs
use defmt_semihosting as _;

/// FNV-1a over 32-bit words.
fn fnv1a(hash: u32, word: u32) -> u32 {
    let mut h = hash;
    for byte in word.to_le_bytes() {
        h ^= u32::from(byte);
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// Runs the paper's scene at `speed` (finger 1 starting at -0.35 m) and reports it.
fn run_scene(name: &str, speed: f32) -> Outcome {
    let params = SceneParams { finger_speed: speed, finger1_x: -0.35, ..SceneParams::<f32>::paper() };
    let mut scene = match Scene6::<f32, 32>::new(params) {
        Ok(scene) => scene,
        Err(e) => {
            defmt::println!("{=str}: invalid parameters: {}", name, e);
            return Outcome::NonFinite;
        }
    };
    let mut checksum = 0x811c_9dc5u32;
    let outcome = scene.run(|r| {
        for v in [r.state.x, r.state.y, r.state.theta, r.state.vx, r.state.vy, r.state.omega] {
            checksum = fnv1a(checksum, v.to_bits());
        }
    });
    for e in scene.events() {
        defmt::println!(
            "{=str} event t={=f32} finger={=u8} mode={=str} x1={=f32} x2={=f32}",
            name,
            e.time,
            e.finger + 1,
            e.mode.name(),
            e.along[0],
            e.along[1]
        );
    }
    let st = scene.stats();
    defmt::println!(
        "{=str} outcome={} t={=f32} steps={=u64} pivots={=u64} checks={=u64} checksum={=u32:08x}",
        name,
        outcome,
        scene.time(),
        st.steps,
        st.pivots,
        st.reduced_check_fired,
        checksum
    );
    outcome
}

#[entry]
fn main() -> ! {
    defmt::println!("meterstick-firmware {} core {}", env!("CARGO_PKG_VERSION"), meterstick_core::VERSION);
    let mut failures = 0i32;
    // Kostreva's cycling example in f32: z = (1/3, 1/3, 1/3).
    let lcp =
        Lcp::<f32, 3>::from_rows(&[[1.0, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]], &[-1.0, -1.0, -1.0]);
    match Lemke::<f32, 3>::new().solve(&lcp) {
        Ok(sol) => defmt::println!(
            "lcp3 z = [{=f32}, {=f32}, {=f32}] pivots={=u32}",
            sol.z[0],
            sol.z[1],
            sol.z[2],
            sol.pivots
        ),
        Err(e) => {
            defmt::println!("lcp3 error: {}", e);
            failures += 1;
        }
    }
    if run_scene("slow", 0.1) != Outcome::Balanced {
        failures += 1;
    }
    if run_scene("fast", 5.0) != Outcome::Fell {
        failures += 1;
    }
    defmt::println!("exit {=i32}", failures);
    semihosting::process::exit(failures)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    defmt::println!("PANIC at line {=u32}", info.location().map_or(0, core::panic::Location::line));
    semihosting::process::exit(101)
}

#[allow(unsafe_code)] // cortex-m-rt requires the HardFault handler to be `unsafe fn`.
#[cortex_m_rt::exception]
unsafe fn HardFault(_frame: &cortex_m_rt::ExceptionFrame) -> ! {
    defmt::println!("HARDFAULT");
    semihosting::process::exit(102)
}
