//! The stack rig on the real-time loop (`crate::realtime::run`, [`crate::realtime::serve`]): its
//! parameters at boot, its buttons, and the Picos' rig of both scenes (`run_both_scenes`, with `link`). One
//! [`StackRig::tick`] per SysTick period `h` (the scene's step, 1 ms) on the core clock, on
//! [`crate::realtime`]'s clock ([`crate::realtime::Ticker`]), start button between runs
//! ([`RestartButton`]) and constants, as the meter-stick rig runs; with `link`, the host link as
//! the meter-stick rig's (`meterstick_rig::session` serving the stack: `Report::Body` telemetry,
//! `Report::InterfaceSwitch` events, the stack's parameters by name). The Black Pill runs it alone
//! (`rig-stack`); the Picos with `link` run it when the host selects it.
//!
//! Buttons (debounced, [`DEBOUNCE_TICKS`] ticks): a press of the start button starts a run (the
//! rig debounces it while waiting); once the run has ended, a press resets it (all lights off)
//! and the next press starts it again. While no run is in progress, the preset button toggles
//! the overhang between [`OVERHANGS`] (0.98, the catalogue's stack, which the model holds; 1.02,
//! beyond the critical 1, which it sees fall), shown on the table interface's lights (sticking:
//! the first, sliding: the second) until the start.

use core::convert::Infallible;

use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::multibody::scenes::StackParams;
use meterstick_rig::{NoActuator, PressDetector, RigPins, RigState, StackRig};

use crate::realtime::{DEBOUNCE_TICKS, RestartButton, config};

/// The overhangs the preset button selects (the scale `s` of the harmonic overhangs,
/// `StackParams::overhang`); the first at boot. The blocks on the table must be stacked to the
/// selected one.
pub const OVERHANGS: [f32; 2] = [0.98, 1.02];

/// The stack of three at the catalogue's defaults (h = 1 ms) and the first of [`OVERHANGS`].
pub fn boot_params() -> StackParams<f32> {
    StackParams { overhang: OVERHANGS[0], ..StackParams::default() }
}

/// The stack rig of `params` with `pins`, its start button debounced over [`DEBOUNCE_TICKS`] and
/// the steps SysTick can tick at `sysclk_hz`. `None` if it cannot start (logged).
pub fn new_rig<B, P>(
    pins: RigPins<B, P, 3>,
    params: StackParams<f32>,
    sysclk_hz: u32,
) -> Option<StackRig<B, P>>
where
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    let rig = StackRig::new(params, config(sysclk_hz), pins, NoActuator);
    #[cfg(feature = "log")]
    if let Err(e) = &rig {
        defmt::error!("stack rig not started: {}", e);
    }
    rig.ok()
}

/// The stack rig's buttons between runs: the preset button toggles the overhang (shown on the
/// table interface's lights), the start button resets a finished run (the next press starts it).
pub struct Buttons {
    /// The selected entry of [`OVERHANGS`].
    selected: u8,
    preset_press: PressDetector,
    restart: RestartButton,
}

impl Buttons {
    /// The first of [`OVERHANGS`] selected (the rig's at boot, [`new_rig`]).
    pub const fn new() -> Self {
        Self { selected: 0, preset_press: PressDetector::new(DEBOUNCE_TICKS), restart: RestartButton::new() }
    }

    /// Shows the selection on `rig`'s lights (while it waits).
    pub fn show<B, P>(&self, rig: &mut StackRig<B, P>)
    where
        B: InputPin<Error = Infallible>,
        P: OutputPin<Error = Infallible>,
    {
        let _ = rig.indicate(Some(self.selected));
    }

    /// One sample per tick, after it: `state` the rig's, `preset_pressed` the preset button
    /// (`true`: pressed).
    pub fn between_runs<B, P>(&mut self, rig: &mut StackRig<B, P>, state: RigState, preset_pressed: bool)
    where
        B: InputPin<Error = Infallible>,
        P: OutputPin<Error = Infallible>,
    {
        // Pins on this HAL cannot fail (`Infallible`); both overhangs are valid for the core.
        if self.preset_press.sample(preset_pressed) && !matches!(state, RigState::Running) {
            let next = (self.selected + 1) % OVERHANGS.len() as u8;
            if let Some(&overhang) = OVERHANGS.get(usize::from(next))
                && rig.reset(StackParams { overhang, ..*rig.params() }).is_ok()
            {
                self.selected = next;
                let _ = rig.indicate(Some(next));
            }
        }
        let ended = matches!(state, RigState::Finished(_) | RigState::Fault(_));
        if self.restart.sample(ended, || rig.start_pressed().unwrap_or(false)) {
            let _ = rig.reset(*rig.params());
            self.show(rig);
        }
    }
}

/// The scenes of a rig that runs both ([`run_both_scenes`]).
#[cfg(both_scenes)]
const BOTH: &[meterstick_rig::session::SceneId] =
    &[meterstick_rig::session::SceneId::MeterStick, meterstick_rig::session::SceneId::Stack];

/// The rig of both scenes (the Picos with `link`), in real time, forever: the meter stick's
/// `meter` at boot and, when the host selects it (`SelectScene`, between runs), the stack's, one
/// at a time, a [`crate::realtime::serve`] each, one session carried over
/// (`meterstick_rig::session::Session::select`). The stack's lights are the meter stick's two
/// finger light sets (the table / block 1 and block 1 / block 2 interfaces) and `third` (block 2
/// / block 3), off while the meter stick runs; the buttons are each scene's ([`Buttons`],
/// `crate::realtime::Buttons`). Each scene keeps its parameters and its buttons' selection across
/// the switches, and the carriage its place: it stays where the meter stick's last run left it
/// while the stack runs, and the meter stick's rig, back, first drives it home (its pulse count
/// is the carriage's, kept).
#[cfg(both_scenes)]
pub fn run_both_scenes<B, P>(
    mut meter: meterstick_rig::MeterStickRig<B, P, crate::realtime::CycleDelay, 6>,
    mut third: meterstick_rig::ModeLights<P>,
    mut preset_pressed: impl FnMut() -> bool,
    syst: cortex_m::peripheral::SYST,
    sysclk_hz: u32,
    mut port: impl crate::realtime::LinkPort,
) -> !
where
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    use meterstick_rig::MeterStickRig;

    use crate::realtime::{self, Ticker, halt, period_of, serve};

    let mut ticker = Ticker::start(syst, period_of(meter.params().step, sysclk_hz));
    let mut session = realtime::open_session(&meter, &ticker, BOTH);
    let (mut meter_buttons, mut stack_buttons) = (realtime::Buttons::new(), Buttons::new());
    let mut stack_params = boot_params();
    loop {
        // Returns on the host's `SelectScene` of the other scene, the stack (the only other
        // `BOTH` names), with the rig waiting or finished.
        let _ = serve(
            &mut meter,
            &mut |rig, state| meter_buttons.between_runs(rig, state, preset_pressed()),
            &mut ticker,
            sysclk_hz,
            &mut session,
            &mut port,
        );
        let meter_params = *meter.params();
        let (RigPins { start, lights: [first, second], fault }, carriage) = meter.release();
        let pins = RigPins { start, lights: [first, second, third], fault };
        let Some(mut stack) = new_rig(pins, stack_params, sysclk_hz) else { halt() };
        stack_buttons.show(&mut stack);
        let mut stack_session = session.select(&stack);
        // Back to the meter stick on its `SelectScene`.
        let _ = serve(
            &mut stack,
            &mut |rig, state| stack_buttons.between_runs(rig, state, preset_pressed()),
            &mut ticker,
            sysclk_hz,
            &mut stack_session,
            &mut port,
        );
        stack_params = *stack.params();
        let (RigPins { start, lights: [first, second, mut last], fault }, NoActuator) = stack.release();
        // Pins on these HALs cannot fail (`Infallible`).
        let _ = (last.sticking.set_low(), last.sliding.set_low(), last.separated.set_low());
        third = last;
        let pins = RigPins { start, lights: [first, second], fault };
        // The parameters it ran before, valid for it then: it starts again.
        let Ok(rig) = MeterStickRig::new(meter_params, config(sysclk_hz), pins, carriage) else { halt() };
        meter = rig;
        session = stack_session.select(&meter);
    }
}
