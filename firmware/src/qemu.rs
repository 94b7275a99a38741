//! The QEMU board binding: the rig loop headless, with pins that count their edges and a start
//! button that reads pressed. Runs a small LCP, then the slow (0.1 m/s) and fast (5 m/s) scenes
//! (finger 1 from -0.35 m) in f32 with the 6x6 LCP, and prints for each its switch events, its
//! outcome, statistics and a checksum of the f32 trajectory (FNV-1a over the bits of the rod
//! state after every step), then the SysTick ticks the steps took and a calibration of ticks
//! against instructions. Exit status: 0 when the LCP was solved and both scenes ended as the
//! paper says (balanced, fell).

use defmt_semihosting as _;
use meterstick_core::lcp::{Lcp, Lemke};
use meterstick_core::rig::{NoDelay, Rig, RigConfig, RigState};
use meterstick_core::scene::{Outcome, SceneParams};

use crate::systick;

/// FNV-1a over 32-bit words.
fn fnv1a(hash: u32, word: u32) -> u32 {
    let mut h = hash;
    for byte in word.to_le_bytes() {
        h ^= u32::from(byte);
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// 0.1 mm per stepper pulse, so that the fast scene (5 mm per step) fits a tick's budget.
const CONFIG: RigConfig = RigConfig {
    steps_per_meter: 10_000.0,
    pulse_ns: 2_000,
    max_pulses_per_tick: 1_000,
    button_active_low: true,
};

/// Runs the paper's scene at `speed` (finger 1 starting at -0.35 m) through the rig and
/// reports it; `None` on a rig fault.
fn run_scene(name: &str, speed: f32) -> Option<Outcome> {
    let params = SceneParams { finger_speed: speed, finger1_x: -0.35, ..SceneParams::<f32>::paper() };
    let mut rig = match Rig::<_, _, _, 6, 32>::headless(params, CONFIG, NoDelay) {
        Ok(rig) => rig,
        Err(e) => {
            defmt::println!("{=str}: rig not started: {}", name, e);
            return None;
        }
    };
    let mut checksum = 0x811c_9dc5u32;
    let (mut steps, mut ticks, mut worst) = (0u64, 0u64, 0u32);
    let state = loop {
        let t0 = systick::now();
        let result = rig.tick();
        let t1 = systick::now();
        let state = match result {
            Ok(s) => s,
            Err(e) => {
                defmt::println!("{=str}: pin error {}", name, e);
                return None;
            }
        };
        if rig.scene().stats().steps > steps {
            steps = rig.scene().stats().steps;
            let used = systick::elapsed(t0, t1);
            ticks += u64::from(used);
            worst = worst.max(used);
            let s = rig.scene().state();
            for v in [s.x, s.y, s.theta, s.vx, s.vy, s.omega] {
                checksum = fnv1a(checksum, v.to_bits());
            }
        }
        if !matches!(state, RigState::WaitingForStart | RigState::Running) {
            break state;
        }
    };
    let scene = rig.scene();
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
    let outcome = match state {
        RigState::Finished(o) => o,
        other => {
            defmt::println!("{=str} rig stopped: {}", name, other);
            return None;
        }
    };
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
    let (pins, _) = rig.release();
    defmt::println!(
        "{=str} rig pulses={=u32} systicks={=u64} worst_step_systicks={=u32} steps={=u64}",
        name,
        pins.step.rises(),
        ticks,
        worst,
        steps
    );
    Some(outcome)
}

pub fn main() -> ! {
    defmt::println!("meterstick-firmware {} core {}", env!("CARGO_PKG_VERSION"), meterstick_core::VERSION);
    let Some(mut cp) = cortex_m::Peripherals::take() else {
        defmt::println!("core peripherals already taken");
        semihosting::process::exit(103)
    };
    systick::start(&mut cp.SYST, systick::MASK);
    // Calibration: `asm::delay(n)` runs `subs; bne` n + 1 times.
    let (n, t0) = (1_000_000u32, systick::now());
    cortex_m::asm::delay(n);
    let ticks = systick::elapsed(t0, systick::now());
    defmt::println!("calibration instructions={=u32} systicks={=u32}", 2 * (n + 1), ticks);

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
    if run_scene("slow", 0.1) != Some(Outcome::Balanced) {
        failures += 1;
    }
    if run_scene("fast", 5.0) != Some(Outcome::Fell) {
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
