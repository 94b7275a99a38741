//! The stack rig's real-time loop (`rig-stack`, on the Black Pill): one [`StackRig::tick`] per
//! SysTick period `h` (the scene's step, 1 ms) on the core clock, the buttons between runs and
//! the real-time margin, on [`crate::realtime`]'s clock ([`Ticker`]), start button between runs
//! ([`RestartButton`]) and constants, as the meter-stick rig runs; with `link`, the host link as
//! the meter-stick rig's (`meterstick_rig::session` serving the stack: `Report::Body` telemetry,
//! `Report::InterfaceSwitch` events, the stack's parameters by name).
//!
//! Buttons (debounced, [`DEBOUNCE_TICKS`] ticks): a press of the start button starts a run (the
//! rig debounces it while waiting); once the run has ended, a press resets it (all lights off)
//! and the next press starts it again. While no run is in progress, the preset button toggles
//! the overhang between [`OVERHANGS`] (0.98, the catalogue's stack, which the model holds; 1.02,
//! beyond the critical 1, which it sees fall), shown on the table interface's lights (sticking:
//! the first, sliding: the second) until the start.

use core::convert::Infallible;

use cortex_m::peripheral::SYST;
use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::multibody::scenes::StackParams;
use meterstick_rig::{NoActuator, PressDetector, RigError, RigPins, RigState, StackRig};

#[cfg(feature = "link")]
use crate::realtime::LinkPort;
use crate::realtime::{DEBOUNCE_TICKS, RestartButton, Ticker, config, period_of};

/// The overhangs the preset button selects (the scale `s` of the harmonic overhangs,
/// `StackParams::overhang`); the first at boot. The blocks on the table must be stacked to the
/// selected one.
pub const OVERHANGS: [f32; 2] = [0.98, 1.02];

/// The stack of three at the catalogue's defaults (h = 1 ms) and the first of [`OVERHANGS`],
/// with `pins`, its start button debounced over [`DEBOUNCE_TICKS`] and the steps SysTick can tick
/// at `sysclk_hz`; the selection shown. `None` if it cannot start (logged).
pub fn new_rig<B, P>(pins: RigPins<B, P, 3>, sysclk_hz: u32) -> Option<StackRig<B, P>>
where
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    let params = StackParams { overhang: OVERHANGS[0], ..StackParams::default() };
    let rig = StackRig::new(params, config(sysclk_hz), pins, NoActuator);
    #[cfg(feature = "log")]
    if let Err(e) = &rig {
        defmt::error!("stack rig not started: {}", e);
    }
    let mut rig = rig.ok()?;
    let _ = rig.indicate(Some(0));
    Some(rig)
}

/// Runs the stack rig in real time on SysTick at `sysclk_hz` (the core clock), forever.
/// `preset_pressed` reads the preset button (`true`: pressed).
pub fn run<B, P>(
    mut rig: StackRig<B, P>,
    mut preset_pressed: impl FnMut() -> bool,
    syst: SYST,
    sysclk_hz: u32,
    #[cfg(feature = "link")] mut port: impl LinkPort,
) -> !
where
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    #[cfg(feature = "link")]
    let mut session = {
        use meterstick_rig::session::{Session, build_id, version};
        let mut session = Session::new(0, version(env!("CARGO_PKG_VERSION")), build_id(env!("MS_BUILD_ID")));
        session.boot(&rig);
        session
    };
    // The buttons' sets have the catalogue's step; one from the host may change it (between
    // runs, below).
    let mut ticker = Ticker::start(syst, period_of(rig.params().step, sysclk_hz));
    #[cfg(feature = "link")]
    session.set_period(ticker.period());
    let mut buttons = Buttons {
        selected: 0,
        preset_press: PressDetector::new(DEBOUNCE_TICKS),
        restart: RestartButton::new(),
    };
    loop {
        while !ticker.due() {
            #[cfg(feature = "link")]
            port.poll();
        }
        // The stack is this build's one scene: a `SelectScene` of another is refused by the
        // session (`NoSuchScene`), never returned.
        #[cfg(feature = "link")]
        if let Err(RigError::Pin(never)) = session.poll(&mut port, &mut rig) {
            match never {}
        }
        #[cfg(feature = "link")]
        let (state, used) = ticker.time(|| rig.tick_with(|r| session.record(r)));
        #[cfg(not(feature = "link"))]
        let (state, used) = ticker.time(|| rig.tick());
        #[cfg(feature = "link")]
        {
            session.end_tick(&rig, used);
            session.flush(&mut port);
        }
        #[cfg(not(feature = "link"))]
        let _ = used;
        let state = match state {
            Ok(s) => s,
            // `Params` and `Unperformable` only come from `new` and `reset`; pins on this HAL
            // cannot fail.
            Err(RigError::Params(_) | RigError::Unperformable(_)) => continue,
            Err(RigError::Pin(never)) => match never {},
        };
        buttons.between_runs(&mut rig, state, preset_pressed());
        let want = period_of(rig.params().step, sysclk_hz);
        if want != ticker.period() && !matches!(state, RigState::Running) {
            ticker.set_period(want);
            #[cfg(feature = "link")]
            session.set_period(want);
        }
    }
}

/// The buttons between runs: the preset button toggles the overhang (shown on the table
/// interface's lights), the start button resets a finished run (the next press starts it).
struct Buttons {
    /// The selected entry of [`OVERHANGS`].
    selected: u8,
    preset_press: PressDetector,
    restart: RestartButton,
}

impl Buttons {
    fn between_runs<B, P>(&mut self, rig: &mut StackRig<B, P>, state: RigState, preset_pressed: bool)
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
            let _ = rig.indicate(Some(self.selected));
        }
    }
}
