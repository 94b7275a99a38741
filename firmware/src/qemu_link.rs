//! The QEMU board binding with the host link (features `qemu-*` and `link`): the rig loop
//! headless on QEMU's Cortex-M4F (mps2-an386) or Cortex-M0 (micro:bit), serving
//! `meterstick-link` commands on the machine's UART ([`crate::uart`]), which QEMU connects to a
//! TCP socket (`-serial tcp:HOST:PORT`). It runs the meter stick (at boot) and, with
//! `qemu-multibody`, the 3-block stack, one at a time, switching on the host's `SelectScene`. It waits for commands:
//! nothing runs until the host sends `Start` (the headless start button reads released). Runs are not in real time (a
//! tick follows the last as soon as the link has taken its reports), so the comparison with the
//! host is exact and no report is dropped; the margins are SysTick ticks (`period_cycles` 0),
//! which `-icount shift=0` makes an instruction count (the calibration line on semihosting
//! gives instructions per tick). Never exits: the host ends QEMU.

use core::convert::Infallible;

use meterstick_rig::session::{LinkScene, SceneId, Session, build_id, version};
use meterstick_rig::{
    Actuator, HeadlessPin, MeterStickRig, NoDelay, Preset, PresetScene as _, Rig, RigConfig, RigError,
};

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

    let Some(mut meter_rig) = meter_stick_rig() else { semihosting::process::exit(104) };
    let mut uart = Uart::new();
    let mut meter = Session::new(0, version(env!("CARGO_PKG_VERSION")), build_id(env!("MS_BUILD_ID")))
        .with_scenes(SCENES);
    meter.boot(&meter_rig);
    // One scene at a time, each with its own concrete rig and session; `SelectScene` carries the
    // session over to the other (the only other scene `SCENES` lets it ask for).
    loop {
        serve(&mut meter_rig, &mut meter, &mut uart);
        #[cfg(feature = "qemu-multibody")]
        {
            let Some(mut stack_rig) = stack_rig() else { semihosting::process::exit(104) };
            let mut stack = meter.select(&stack_rig);
            serve(&mut stack_rig, &mut stack, &mut uart);
            let Some(rig) = meter_stick_rig() else { semihosting::process::exit(104) };
            meter_rig = rig;
            meter = stack.select(&meter_rig);
        }
    }
}

/// The scenes this build runs: the meter stick (at boot) and, with the scenes of several bodies
/// (`qemu-multibody`: not on the micro:bit's 16 KiB of RAM), the stack.
#[cfg(feature = "qemu-multibody")]
const SCENES: &[SceneId] = &[SceneId::MeterStick, SceneId::Stack];
#[cfg(not(feature = "qemu-multibody"))]
const SCENES: &[SceneId] = &[SceneId::MeterStick];

/// The meter stick's rig with the slow preset at h = 1 ms; `None` (logged) if it cannot start.
fn meter_stick_rig() -> Option<MeterStickRig<HeadlessPin, HeadlessPin, NoDelay, 6, 8>> {
    MeterStickRig::headless(Preset::Slow.params(1e-3), CONFIG, NoDelay)
        .map_err(|e| defmt::println!("rig not started: {}", e))
        .ok()
}

/// The stack rig with the catalogue's stack; `None` (logged) if it cannot start.
#[cfg(feature = "qemu-multibody")]
fn stack_rig() -> Option<meterstick_rig::StackRig<HeadlessPin, HeadlessPin>> {
    use meterstick_core::multibody::scenes::StackParams;
    meterstick_rig::StackRig::headless(StackParams::default(), CONFIG)
        .map_err(|e| defmt::println!("rig not started: {}", e))
        .ok()
}

/// Serves the link with `rig` until the host selects another scene.
fn serve<S, A, const L: usize>(
    rig: &mut Rig<S, A, HeadlessPin, HeadlessPin, L>,
    session: &mut Session<S, L>,
    uart: &mut Uart,
) -> SceneId
where
    S: LinkScene<L>,
    S::Report: Copy,
    A: Actuator<S, Infallible>,
{
    loop {
        // Headless pins cannot fail (`Infallible`); `Params` and `Unperformable` come only from
        // `new` and `reset`, which the session answers itself.
        if let Ok(Some(scene)) = session.poll(uart, rig) {
            while session.busy() {
                session.flush(uart);
            }
            return scene;
        }
        let t0 = systick::now();
        let ticked = rig.tick_with(|r| session.record(r));
        let t1 = systick::now();
        if let Err(RigError::Pin(never)) = ticked {
            match never {}
        }
        session.end_tick(rig, systick::elapsed(t0, t1));
        while session.busy() {
            session.flush(uart);
        }
    }
}
