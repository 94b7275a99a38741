//! The QEMU board binding with the host link (features `qemu-*` and `link`): the rig loop
//! headless on QEMU's Cortex-M4F (mps2-an386) or Cortex-M0 (micro:bit), serving
//! `meterstick-link` commands on the machine's UART ([`crate::uart`]), which QEMU connects to a
//! TCP socket (`-serial tcp:HOST:PORT`). It waits for commands: nothing runs until the host
//! sends `Start` (the headless start button reads released). Runs are not in real time (a
//! tick follows the last as soon as the link has taken its reports), so the comparison with the
//! host is exact and no report is dropped; the margins are SysTick ticks (`period_cycles` 0),
//! which `-icount shift=0` makes an instruction count (the calibration line on semihosting
//! gives instructions per tick). Never exits: the host ends QEMU.

use meterstick_rig::session::{Session, build_id, version};
use meterstick_rig::{MeterStickRig, NoDelay, Preset, PresetScene as _, RigConfig, RigError};

use crate::systick;
use crate::uart::Uart;

/// 1 cm per stepper pulse and no practical limit per tick: the headless carriage costs a few
/// instructions a tick even at 100 m/s (the margins measure the scene, not pulse trains); and a
/// start button that reads released: `HeadlessPin` reads low, which is "not pressed" for an
/// active-high button.
const CONFIG: RigConfig = RigConfig {
    steps_per_meter: 100.0,
    pulse_ns: 2_000,
    max_pulses_per_tick: 1_000_000,
    button_active_low: false,
    // One sample: the headless button is constant (no bounce to filter), so the run starts on
    // the first tick; not real time, so any step.
    debounce_ticks: 1,
    min_step: 0.0,
    max_step: f32::INFINITY,
};

pub fn main() -> ! {
    defmt::println!(
        "meterstick-firmware {} core {} link on the UART",
        env!("CARGO_PKG_VERSION"),
        meterstick_core::VERSION
    );
    let Some(mut cp) = cortex_m::Peripherals::take() else {
        defmt::println!("core peripherals already taken");
        semihosting::process::exit(103)
    };
    systick::start(&mut cp.SYST, systick::MASK);
    let (n, t0) = (1_000_000u32, systick::now());
    cortex_m::asm::delay(n);
    let ticks = systick::elapsed(t0, systick::now());
    defmt::println!("calibration instructions={=u32} systicks={=u32}", 2 * (n + 1), ticks);

    let mut rig = match MeterStickRig::<_, _, _, 6, 8>::headless(Preset::Slow.params(1e-3), CONFIG, NoDelay) {
        Ok(rig) => rig,
        Err(e) => {
            defmt::println!("rig not started: {}", e);
            semihosting::process::exit(104)
        }
    };
    let mut uart = Uart::new();
    let mut session = Session::new(0, version(env!("CARGO_PKG_VERSION")), build_id(env!("MS_BUILD_ID")));
    session.boot(&rig);
    loop {
        // Headless pins cannot fail (`Infallible`).
        if let Err(RigError::Pin(never)) = session.poll(&mut uart, &mut rig) {
            match never {}
        }
        let t0 = systick::now();
        let ticked = rig.tick_with(|r| session.record(r));
        let t1 = systick::now();
        if let Err(RigError::Pin(never)) = ticked {
            match never {}
        }
        session.end_tick(&rig, systick::elapsed(t0, t1));
        while session.busy() {
            session.flush(&mut uart);
        }
    }
}
