//! [`Rig`]: the demo rig's one state machine, over any scene a board runs ([`RigScene`]), the
//! [`Actuator`] that follows it, and `embedded-hal` 1.0 pins, separate from any board.
//! [`MeterStickRig`] is the meter stick's (a motor-driven finger carriage under a real meter
//! stick, [`Carriage`], a light per finger); [`StackRig`] the 3-block stack's (no actuator: the
//! teacher builds a real stack at the overhang the model is given, `StackParams::overhang`; a
//! light per interface).
//!
//! The board calls [`Rig::tick`] once per timer period `h` (real time: one scene step per tick);
//! each tick:
//!
//! 1. before the start: while the actuator is on its way back to its origin after a reset
//!    ([`Actuator::homing`]), one tick of that way ([`Actuator::home`]); then the start button,
//!    debounced ([`PressDetector`], [`RigConfig::debounce_ticks`] equal samples): a press readies
//!    the actuator ([`Actuator::arm`]: the carriage's DIR toward finger 2) and lights each
//!    light's mode at the scene's start ([`RigScene::start_modes`]);
//! 2. running: advances the scene one step, has the actuator follow it ([`Actuator::follow`]:
//!    the carriage's stepper pulses to finger 1's position), switches a light when its mode
//!    changes, and stops at the outcome with the lights showing the last step's modes;
//! 3. a failed step (the solver, a non-finite state, more contacts than the LCP holds: the
//!    core's `StepError`), a reported state the rig finds non-finite ([`RigScene::finite`]), or
//!    an actuator that cannot follow ([`RigFault`]) never panics: the rig turns the mode lights
//!    off, turns the fault light on, logs it, and stays in [`RigState::Fault`].
//!
//! Lights: one [`ModeLights`] per light of the scene: the meter stick's fingers (exactly one of
//! sticking / sliding / separated on), the stack's interfaces (their [`crate::InterfaceMode`]:
//! sticking and separated together while an interface tips). Pins are driven only when their
//! state changes. Logging (start, mode switches, outcome, faults) goes to `defmt` with the
//! `defmt` feature and compiles to nothing without it.
//!
//! Parameters: [`Rig::new`] and [`Rig::reset`] accept only a set the core validates
//! ([`RigScene::build`]) *and* the rig can perform ([`RigScene::check`]: for every scene a step
//! the board's timer ticks in real time, [`RigConfig::check_step`]; for the meter stick also a
//! run the carriage follows, [`RigConfig::check`]); anything else is [`RigError::Params`] or
//! [`RigError::Unperformable`] before any pin is touched, and [`RigFault::ActuatorOverrun`]
//! stays a fault of last resort.
//!
//! Runs on demand (a host link, a second button): [`Rig::start`] and [`Rig::stop`] do what the
//! button and the outcome do; [`Rig::reset`] loads a parameter set (a rejected set leaves the rig
//! as it was), turns the lights off and returns to [`RigState::WaitingForStart`], where the next
//! ticks first bring the actuator back to its origin and only then accept a start; after a reset
//! the start button must be released (debounced) before a press starts a run again.
//! [`Rig::tick_with`] hands each step's report to the caller (telemetry). [`Rig::indicate`]
//! shows a small number on the first light while waiting (the selected preset).

use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::multibody::scenes::Stack3;
use meterstick_core::scene::{MeterStick, Outcome};
use meterstick_core::{ParamError, StepError};

use crate::lights::{self, ModeLights, Shown as _};
use crate::{Actuator, Carriage, NoActuator, PressDetector, RigConfig, RigScene, Unperformable};

/// The rig's pins besides its actuator's, for `L` lights: `B` an input (the start button), `P`
/// outputs.
#[derive(Debug)]
pub struct RigPins<B, P, const L: usize> {
    /// Start button.
    pub start: B,
    /// Each light's mode lights, in the scene's order ([`RigScene`]: the meter stick's finger 1
    /// (moving) then finger 2 (fixed); the stack's interfaces from the table's up).
    pub lights: [ModeLights<P>; L],
    /// Fault light.
    pub fault: P,
}

/// Why the rig stopped in a fault state.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RigFault {
    /// A scene step failed: the solver, a non-finite state (the core's, or one the rig checks,
    /// [`RigScene::finite`]), more contacts than the LCP holds, or the 6x6 model leaving its
    /// range without the 8x8 fallback compiled in.
    Step(StepError),
    /// The carriage target became non-finite.
    NonFinite,
    /// More stepper pulses were due in one tick than `max_pulses_per_tick`.
    ActuatorOverrun,
}

/// Where the rig is.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RigState {
    /// Waiting for the start button (after the actuator is back at its origin).
    WaitingForStart,
    /// Stepping the scene in real time.
    Running,
    /// The scene ended (the meter stick: balanced, fell; the stack: held, fell; unfinished when
    /// stopped); the lights show the last step's modes.
    Finished(Outcome),
    /// Stopped on a fault (fault light on, mode lights off).
    Fault(RigFault),
}

/// What went wrong building or resetting the rig, or with a pin (the HAL's error type).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RigError<E> {
    /// The parameters are invalid.
    Params(ParamError),
    /// The parameters are valid, but the rig cannot perform them.
    Unperformable(Unperformable),
    /// A pin operation failed.
    Pin(E),
}

/// The demo rig's loop over the scene `S` shown on `L` lights, with the actuator `A`.
#[derive(Debug)]
pub struct Rig<S, A, B, P, const L: usize>
where
    S: RigScene<L>,
{
    scene: S,
    actuator: A,
    pins: RigPins<B, P, L>,
    config: RigConfig,
    state: RigState,
    lit: [Option<S::Mode>; L],
    /// The start button, debounced.
    start_press: PressDetector,
}

/// The meter-stick rig: the scene `MeterStick<f32, N, E>` (`N` 6: reduced, 8: the paper's form;
/// room for `E` switch events), its [`Carriage`] following finger 1, a light per finger.
pub type MeterStickRig<B, P, D, const N: usize, const E: usize = 8> =
    Rig<MeterStick<f32, N, E>, Carriage<P, D>, B, P, 2>;

/// The rig of the 3-block stack (`Stack3<f32>`): no actuator, three interfaces, table-block 1,
/// block 1-block 2, block 2-block 3.
pub type StackRig<B, P> = Rig<Stack3<f32>, NoActuator, B, P, 3>;

impl<S, A, B, P, PinError, const L: usize> Rig<S, A, B, P, L>
where
    S: RigScene<L>,
    A: Actuator<S, PinError>,
    B: InputPin<Error = PinError>,
    P: OutputPin<Error = PinError>,
{
    /// A rig for `params`, with every output driven low.
    ///
    /// # Errors
    /// Invalid parameters, parameters the rig cannot perform ([`RigScene::check`]), both before
    /// any pin is touched, or a pin error.
    pub fn new(
        params: S::Params,
        config: RigConfig,
        pins: RigPins<B, P, L>,
        actuator: A,
    ) -> Result<Self, RigError<PinError>> {
        let scene = S::build(params).map_err(RigError::Params)?;
        S::check(&config, &params).map_err(RigError::Unperformable)?;
        let mut rig = Self {
            scene,
            actuator,
            pins,
            config,
            state: RigState::WaitingForStart,
            lit: [None; L],
            start_press: PressDetector::new(config.debounce_ticks),
        };
        rig.actuator.init(&rig.scene).map_err(RigError::Pin)?;
        let p = &mut rig.pins;
        p.fault.set_low().map_err(RigError::Pin)?;
        for l in &mut p.lights {
            l.all_low().map_err(RigError::Pin)?;
        }
        Ok(rig)
    }

    /// The scene being shown.
    #[must_use]
    pub const fn scene(&self) -> &S {
        &self.scene
    }

    /// The actuator.
    #[must_use]
    pub const fn actuator(&self) -> &A {
        &self.actuator
    }

    /// The rig's state.
    #[must_use]
    pub const fn state(&self) -> RigState {
        self.state
    }

    /// The parameters of the scene being shown (or about to be).
    #[must_use]
    pub fn params(&self) -> &S::Params {
        self.scene.params()
    }

    /// Each light's mode as it shows it (`None`: all three off).
    #[must_use]
    pub const fn shown(&self) -> &[Option<S::Mode>; L] {
        &self.lit
    }

    /// Reads the start button now, raw (`true`: pressed), e.g. for the board to restart a
    /// finished run on a (debounced) press; [`Self::tick`] reads it only while waiting, through
    /// its own debouncer.
    ///
    /// # Errors
    /// A pin error.
    pub fn start_pressed(&mut self) -> Result<bool, RigError<PinError>> {
        Ok(self.pins.start.is_low().map_err(RigError::Pin)? == self.config.button_active_low)
    }

    /// `true` while the actuator is still on its way back to its origin after a reset.
    #[must_use]
    pub fn homing(&self) -> bool {
        self.actuator.homing()
    }

    /// Gives the pins and the actuator back.
    pub fn release(self) -> (RigPins<B, P, L>, A) {
        (self.pins, self.actuator)
    }

    /// One timer tick (call once per `h`); returns the state after it.
    ///
    /// # Errors
    /// A pin error (the rig's state is unchanged by it).
    pub fn tick(&mut self) -> Result<RigState, RigError<PinError>> {
        self.tick_with(|_| {})
    }

    /// [`Self::tick`], handing the step's report to `observe` when the tick stepped the scene
    /// (for telemetry; not called on a tick that waits, homes, finishes or whose step failed).
    ///
    /// # Errors
    /// A pin error (the rig's state is unchanged by it).
    pub fn tick_with(&mut self, observe: impl FnOnce(&S::Report)) -> Result<RigState, RigError<PinError>> {
        match self.state {
            RigState::WaitingForStart if self.actuator.homing() => {
                self.actuator.home(&self.config).map_err(RigError::Pin)?;
            }
            RigState::WaitingForStart => self.wait_for_start()?,
            RigState::Running => self.advance(observe)?,
            RigState::Finished(_) | RigState::Fault(_) => {}
        }
        Ok(self.state)
    }

    /// A tick while waiting at the origin: the start button sampled, debounced; a press starts
    /// the run. Out of line: it must not weigh on the running tick's code.
    #[inline(never)]
    fn wait_for_start(&mut self) -> Result<(), RigError<PinError>> {
        let pressed = self.start_pressed()?;
        if self.start_press.sample(pressed) {
            self.start()?;
        }
        Ok(())
    }

    /// Starts the run (as the start button does), if the rig is waiting with the actuator at
    /// its origin; returns whether it started.
    ///
    /// # Errors
    /// A pin error.
    pub fn start(&mut self) -> Result<bool, RigError<PinError>> {
        if self.state != RigState::WaitingForStart || self.actuator.homing() {
            return Ok(false);
        }
        self.actuator.arm().map_err(RigError::Pin)?;
        self.show_modes(self.scene.start_modes())?;
        log_info!("rig: start");
        self.state = RigState::Running;
        Ok(true)
    }

    /// Stops a run in progress: it ends [`Outcome::Unfinished`] (the lights keep the last
    /// modes); returns whether a run was stopped.
    ///
    /// # Errors
    /// A pin error.
    pub fn stop(&mut self) -> Result<bool, RigError<PinError>> {
        if self.state != RigState::Running {
            return Ok(false);
        }
        self.finish(Outcome::Unfinished)?;
        Ok(true)
    }

    /// Loads `params` (validated by the core and checked against the rig first: on
    /// [`RigError::Params`] or [`RigError::Unperformable`] nothing changes), turns the lights and
    /// the fault light off and goes back to [`RigState::WaitingForStart`]; the next ticks bring
    /// the actuator back to its origin. Allowed in any state (it also ends a run in progress,
    /// unfinished and unreported).
    ///
    /// # Errors
    /// Invalid parameters, parameters the rig cannot perform, or a pin error.
    #[inline(never)]
    pub fn reset(&mut self, params: S::Params) -> Result<(), RigError<PinError>> {
        let scene = S::build(params).map_err(RigError::Params)?;
        S::check(&self.config, &params).map_err(RigError::Unperformable)?;
        self.lights_off()?;
        self.pins.fault.set_low().map_err(RigError::Pin)?;
        self.actuator.park(&scene).map_err(RigError::Pin)?;
        self.scene = scene;
        self.state = RigState::WaitingForStart;
        // A press held through the reset (the one that asked for it) is spent: a start needs a
        // debounced release, then a debounced press.
        self.start_press.spend_press();
        log_info!("rig: reset");
        Ok(())
    }

    /// While waiting: lights the first light's number `index` (0 sticking, 1 sliding,
    /// 2 separated; e.g. the selected preset's index), or none. The run's first modes replace it
    /// at the start. Ignored in other states.
    ///
    /// # Errors
    /// A pin error.
    pub fn indicate(&mut self, index: Option<u8>) -> Result<(), RigError<PinError>> {
        if self.state != RigState::WaitingForStart {
            return Ok(());
        }
        lights::indicate(&mut self.pins.lights, &mut self.lit, index).map_err(RigError::Pin)
    }

    /// A running tick: one step, the actuator, the lights, the outcome. Out of line: inlined into
    /// a board's loop (and QEMU's timing harness, `firmware/src/qemu.rs`) it cost about 1 % more
    /// instructions per step of the meter stick's slow scene (QEMU M4F), and flash.
    #[inline(never)]
    fn advance(&mut self, observe: impl FnOnce(&S::Report)) -> Result<(), RigError<PinError>> {
        let Some(report) = self.scene.advance() else {
            return self.finish(self.scene.outcome().unwrap_or(Outcome::Unfinished));
        };
        if !S::finite(&report) {
            return self.fault(RigFault::Step(StepError::NonFinite));
        }
        observe(&report);
        if let Some(fault) = self.actuator.follow(&self.scene, &self.config).map_err(RigError::Pin)? {
            return self.fault(fault);
        }
        self.show_modes(S::modes_of(&report))?;
        match self.scene.outcome() {
            None => Ok(()),
            Some(o) => self.finish(o),
        }
    }

    fn finish(&mut self, outcome: Outcome) -> Result<(), RigError<PinError>> {
        match outcome {
            Outcome::Failed(e) => self.fault(RigFault::Step(e)),
            o => {
                log_info!("rig: outcome {} at t={=f32}", o, self.scene.time());
                self.state = RigState::Finished(o);
                Ok(())
            }
        }
    }

    /// Out of line (and cold): reached at most once a run, it must not weigh on the running
    /// tick's code.
    #[cold]
    #[inline(never)]
    fn fault(&mut self, fault: RigFault) -> Result<(), RigError<PinError>> {
        log_error!("rig: fault {} at t={=f32}", fault, self.scene.time());
        self.state = RigState::Fault(fault);
        self.lights_off()?;
        self.pins.fault.set_high().map_err(RigError::Pin)
    }

    fn lights_off(&mut self) -> Result<(), RigError<PinError>> {
        lights::all_off(&mut self.pins.lights, &mut self.lit).map_err(RigError::Pin)
    }

    /// Lights each light's mode (turning its previous lights off first); pins that keep their
    /// state are not touched.
    // Out of line, as `reset`: inlined into a board's loop (`firmware/src/realtime.rs`) the two
    // cost about 1.6 KB of flash in the smallest rig build; the instructions per step are the
    // same (QEMU M4F and M0).
    #[inline(never)]
    fn show_modes(&mut self, modes: [S::Mode; L]) -> Result<(), RigError<PinError>> {
        // Indexed as the meter-stick rig's two fingers were (`i < L` for every array here, so no
        // bounds check is left): zipped iterators cost it about 40 instructions a step (QEMU M4F).
        for i in 0..L {
            let new = modes[i];
            let old = self.lit[i];
            if old != Some(new) {
                log_info!(
                    "rig: t={=f32} {=str} {=usize} -> {=str}",
                    self.scene.time(),
                    S::LIGHT,
                    i + S::FIRST_LIGHT,
                    new.name()
                );
            }
            self.pins.lights[i].show_mode(&mut self.lit[i], Some(new)).map_err(RigError::Pin)?;
        }
        Ok(())
    }
}

impl<S: RigScene<L>, B, P, D, const L: usize> Rig<S, Carriage<P, D>, B, P, L> {
    /// Stepper pulses the carriage is from its origin (toward finger 2).
    #[must_use]
    pub const fn pulses(&self) -> i64 {
        self.actuator.pulses()
    }
}
