//! [`Rig`]: the demo rig's control loop, generic over `embedded-hal` 1.0 pins and delay,
//! separate from any board.
//!
//! The rig is a motor-driven finger carriage (finger 1) moving toward a fixed finger under a
//! real meter stick, with lights that show what the model predicts each finger is doing.
//! The board calls [`Rig::tick`] once per timer period `h` (real time: one scene step per
//! tick); each tick:
//!
//! 1. before the start: reads the start button, debounced ([`PressDetector`],
//!    [`RigConfig::debounce_ticks`] equal samples); on a press, sets the stepper's direction
//!    pin (toward finger 2) and lights each finger's initial mode;
//! 2. running: advances the scene one step, emits the stepper pulses that bring the carriage
//!    to the scene's finger 1 position (`round((x1(t) - x1(0)) * steps_per_meter)` pulses in
//!    all), switches a finger's light when its mode changes, and stops at the outcome;
//! 3. a solver error (or a non-finite state, or more pulses due in one tick than
//!    [`RigConfig::max_pulses_per_tick`]: with checked parameters only when the carriage's
//!    resolution is finer than the f32 finger position's, e.g. 1 nm per pulse) never panics: the rig turns the mode lights off,
//!    turns the fault light on, logs it, and stays in [`RigState::Fault`].
//!
//! Lights: per finger one pin for each of sticking / sliding / separated; exactly one is on
//! while running. Pins are driven only when their state changes. Logging (mode switches,
//! outcome, faults) goes to `defmt` with the `defmt` feature and compiles to nothing without it.
//!
//! Parameters: [`Rig::new`] and [`Rig::reset`] accept only a set the core validates *and* the rig
//! can perform ([`RigConfig::check`]): a step its timer ticks in real time
//! ([`RigConfig::min_step`] ..= [`RigConfig::max_step`]), finger 2 fixed (the hardware has no
//! actuator for it), finger 1 approaching it or still (DIR is set toward finger 2 for the whole
//! run; the carriage only moves back while homing) and never faster than
//! [`RigConfig::max_pulses_per_tick`] pulses per tick. Anything else is
//! [`RigError::Unperformable`], and [`RigFault::ActuatorOverrun`] stays a fault of last resort.
//!
//! Runs on demand (a host link, a second button): [`Rig::start`] and [`Rig::stop`] do what the
//! button and the outcome do; [`Rig::reset`] loads a parameter set (validated as above; a
//! rejected set leaves the rig as it was), turns the lights off and returns to
//! [`RigState::WaitingForStart`], where the next ticks first drive the carriage back to its
//! origin (DIR low, at most `max_pulses_per_tick` pulses per tick) and only then accept a start;
//! after a reset the start button must be released (debounced) before a press starts a run again.
//! [`Rig::tick_with`] hands each step's report to the caller (telemetry). [`Rig::indicate`]
//! shows a small number on finger 1's lights while waiting (the selected [`Preset`]).

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::ParamError;
use meterstick_core::planar::{ContactMode, StepError, StepReport};
use meterstick_core::scene::{MeterStick, MeterStickParams, Outcome, Scene};

#[cfg(doc)]
use crate::Preset;
use crate::PressDetector;
use crate::lights::{self, ModeLights};

/// Rig constants.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RigConfig {
    /// Stepper pulses per metre of carriage travel (e.g. 80 steps/mm for a GT2 belt on a
    /// 200-step motor at 1/16 microstepping: 80,000).
    pub steps_per_meter: f32,
    /// High and low time of one step pulse (ns); drivers such as the A4988 need >= 1 us.
    pub pulse_ns: u32,
    /// The most pulses one tick may emit (they must fit in the tick's time budget); more is
    /// a fault ([`RigFault::ActuatorOverrun`]), not a silently lagging carriage.
    pub max_pulses_per_tick: u32,
    /// The start button reads low when pressed (a button to ground with a pull-up).
    pub button_active_low: bool,
    /// Equal samples of the start button (one per tick) before a press or a release counts
    /// ([`PressDetector`]); 0 and 1 both take a single sample.
    pub debounce_ticks: u16,
    /// The shortest step `h` (s) the board can tick in real time (one tick per step).
    pub min_step: f32,
    /// The longest step `h` (s) the board can tick in real time.
    pub max_step: f32,
}

/// What the rig cannot perform ([`RigError::Unperformable`]), though the core accepts it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Unperformable {
    /// The step is outside [`RigConfig::min_step`] ..= [`RigConfig::max_step`].
    Step,
    /// Finger 1 would need more than [`RigConfig::max_pulses_per_tick`] pulses per tick (less
    /// half a pulse for rounding).
    Finger1TooFast,
    /// Finger 1 would move away from finger 2 (the run drives the carriage toward it only).
    Finger1Backward,
    /// Finger 2 would move (it is fixed on the rig).
    Finger2Moves,
}

impl RigConfig {
    /// 80 steps/mm, 2 us pulses, at most 100 pulses per tick (finger 1 up to 1.24 m/s at
    /// h = 1 ms: [`Self::check`] keeps half a pulse to spare), active-low
    /// button debounced over 20 ticks, any step (the board narrows the range to what its timer
    /// ticks: [`Self::ticked_by`]).
    #[must_use]
    pub const fn default_rig() -> Self {
        Self {
            steps_per_meter: 80_000.0,
            pulse_ns: 2_000,
            max_pulses_per_tick: 100,
            button_active_low: true,
            debounce_ticks: 20,
            min_step: 0.0,
            max_step: f32::INFINITY,
        }
    }

    /// The config with the step range of a timer on a `clock_hz` clock whose period can be
    /// `min_cycles` ..= `max_cycles` cycles.
    #[must_use]
    #[inline]
    #[allow(clippy::cast_precision_loss)] // clocks and periods below 2^24 are exact; above, within 1e-7
    pub fn ticked_by(self, clock_hz: u32, min_cycles: u32, max_cycles: u32) -> Self {
        let hz = clock_hz as f32;
        Self { min_step: min_cycles as f32 / hz, max_step: max_cycles as f32 / hz, ..self }
    }

    /// Whether the board's timer ticks a step of `step` seconds in real time
    /// ([`Self::min_step`] ..= [`Self::max_step`]; a NaN is refused).
    ///
    /// # Errors
    /// [`Unperformable::Step`].
    #[inline]
    pub fn check_step(&self, step: f32) -> Result<(), Unperformable> {
        // Negated: a NaN is refused too.
        let ticks = step >= self.min_step && step <= self.max_step;
        if ticks { Ok(()) } else { Err(Unperformable::Step) }
    }

    /// Whether the rig can perform `params` (already valid for the core): see
    /// [`Unperformable`].
    ///
    /// # Errors
    /// What it cannot perform.
    #[inline]
    #[allow(clippy::cast_precision_loss)]
    pub fn check(&self, params: &MeterStickParams<f32>) -> Result<(), Unperformable> {
        self.check_step(params.step)?;
        if params.finger2_velocity != 0.0 {
            return Err(Unperformable::Finger2Moves);
        }
        if params.finger1_velocity < 0.0 {
            return Err(Unperformable::Finger1Backward);
        }
        // The pulses due in a tick are the increments of the rounded travel: the ceiling of
        // this rate at most, give or take the rounding of the finger's position in f32 (a few
        // thousandths of a pulse at 80 steps/mm); half a pulse to spare covers it.
        let per_tick = params.finger1_velocity * params.step * self.steps_per_meter;
        let follows = per_tick + 0.5 <= self.max_pulses_per_tick as f32;
        if !follows {
            return Err(Unperformable::Finger1TooFast);
        }
        Ok(())
    }
}

/// The rig's pins: `B` an input (the start button), `P` outputs.
#[derive(Debug)]
pub struct RigPins<B, P> {
    /// Start button.
    pub start: B,
    /// Stepper driver STEP (one pulse per step).
    pub step: P,
    /// Stepper driver DIR (high: toward finger 2).
    pub dir: P,
    /// Mode lights of finger 1 (moving) and finger 2 (fixed).
    pub lights: [ModeLights<P>; 2],
    /// Fault light.
    pub fault: P,
}

/// Why the rig stopped in a fault state.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RigFault {
    /// A scene step failed: the solver, a non-finite state, or the 6x6 model leaving its range
    /// without the 8x8 fallback compiled in.
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
    /// Waiting for the start button.
    WaitingForStart,
    /// Stepping the scene in real time.
    Running,
    /// The scene ended: balanced, fell, or unfinished.
    Finished(Outcome),
    /// Stopped on a fault (fault light on).
    Fault(RigFault),
}

/// The demo rig's loop over the scene `MeterStick<f32, N, E>` (`N` 6: reduced, 8: the paper's
/// form; room for `E` switch events).
#[derive(Debug)]
pub struct Rig<B, P, D, const N: usize, const E: usize = 8> {
    scene: MeterStick<f32, N, E>,
    pins: RigPins<B, P>,
    delay: D,
    config: RigConfig,
    state: RigState,
    origin: f32,
    pulses: i64,
    lit: [Option<ContactMode>; 2],
    /// The start button, debounced.
    start_press: PressDetector,
}

/// What went wrong with a pin (the HAL's error type).
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

impl<B, P, D, PinError, const N: usize, const E: usize> Rig<B, P, D, N, E>
where
    B: InputPin<Error = PinError>,
    P: OutputPin<Error = PinError>,
    D: DelayNs,
{
    /// A rig for `params`, with every output driven low.
    ///
    /// # Errors
    /// Invalid parameters, parameters the rig cannot perform ([`RigConfig::check`]), or a pin
    /// error.
    pub fn new(
        params: MeterStickParams<f32>,
        config: RigConfig,
        pins: RigPins<B, P>,
        delay: D,
    ) -> Result<Self, RigError<PinError>> {
        let scene = MeterStick::new(params).map_err(RigError::Params)?;
        config.check(&params).map_err(RigError::Unperformable)?;
        let mut rig = Self {
            scene,
            pins,
            delay,
            config,
            state: RigState::WaitingForStart,
            origin: params.finger1_x,
            pulses: 0,
            lit: [None; 2],
            start_press: PressDetector::new(config.debounce_ticks),
        };
        let p = &mut rig.pins;
        p.step.set_low().map_err(RigError::Pin)?;
        p.dir.set_low().map_err(RigError::Pin)?;
        p.fault.set_low().map_err(RigError::Pin)?;
        for l in &mut p.lights {
            l.all_low().map_err(RigError::Pin)?;
        }
        Ok(rig)
    }

    /// The scene being shown.
    #[must_use]
    pub const fn scene(&self) -> &MeterStick<f32, N, E> {
        &self.scene
    }

    /// The rig's state.
    #[must_use]
    pub const fn state(&self) -> RigState {
        self.state
    }

    /// Stepper pulses emitted so far.
    #[must_use]
    pub const fn pulses(&self) -> i64 {
        self.pulses
    }

    /// The parameters of the scene being shown (or about to be).
    #[must_use]
    pub const fn params(&self) -> &MeterStickParams<f32> {
        self.scene.params()
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

    /// `true` while the carriage is still being driven back to its origin after a reset.
    #[must_use]
    pub const fn homing(&self) -> bool {
        self.pulses > 0
    }

    /// Gives the pins and the delay back.
    pub fn release(self) -> (RigPins<B, P>, D) {
        (self.pins, self.delay)
    }

    /// One timer tick (call once per `h`); returns the state after it.
    ///
    /// # Errors
    /// A pin error (the rig's state is unchanged by it).
    pub fn tick(&mut self) -> Result<RigState, RigError<PinError>> {
        self.tick_with(|_| {})
    }

    /// [`Self::tick`], handing the step's report to `observe` when the tick stepped the scene
    /// (for telemetry; not called on a tick that waits, homes, finishes or faults).
    ///
    /// # Errors
    /// A pin error (the rig's state is unchanged by it).
    pub fn tick_with(
        &mut self,
        observe: impl FnOnce(&StepReport<f32, 2>),
    ) -> Result<RigState, RigError<PinError>> {
        match self.state {
            RigState::WaitingForStart if self.pulses > 0 => self.home()?,
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

    /// Starts the run (as the start button does), if the rig is waiting with the carriage at
    /// its origin; returns whether it started.
    ///
    /// # Errors
    /// A pin error.
    pub fn start(&mut self) -> Result<bool, RigError<PinError>> {
        if self.state != RigState::WaitingForStart || self.pulses > 0 {
            return Ok(false);
        }
        self.pins.dir.set_high().map_err(RigError::Pin)?;
        self.show_modes(self.scene.modes())?;
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
    /// [`RigError::Params`] or [`RigError::Unperformable`] nothing changes),
    /// turns the lights and the fault light off and goes back to
    /// [`RigState::WaitingForStart`]; the next ticks drive the carriage back to its origin.
    /// Allowed in any state (it also ends a run in progress, unfinished and unreported).
    ///
    /// # Errors
    /// Invalid parameters, parameters the rig cannot perform, or a pin error.
    #[inline(never)]
    pub fn reset(&mut self, params: MeterStickParams<f32>) -> Result<(), RigError<PinError>> {
        let scene = MeterStick::new(params).map_err(RigError::Params)?;
        self.config.check(&params).map_err(RigError::Unperformable)?;
        self.lights_off()?;
        self.pins.fault.set_low().map_err(RigError::Pin)?;
        self.pins.dir.set_low().map_err(RigError::Pin)?;
        self.scene = scene;
        self.origin = params.finger1_x;
        self.state = RigState::WaitingForStart;
        // A press held through the reset (the one that asked for it) is spent: a start needs a
        // debounced release, then a debounced press.
        self.start_press.spend_press();
        log_info!("rig: reset, {=i64} pulses back to the origin", self.pulses);
        Ok(())
    }

    /// While waiting: lights finger 1's light number `index` (0 sticking, 1 sliding,
    /// 2 separated; e.g. the selected [`Preset`]'s index), or none. The run's first modes
    /// replace it at the start. Ignored in other states.
    ///
    /// # Errors
    /// A pin error.
    pub fn indicate(&mut self, index: Option<u8>) -> Result<(), RigError<PinError>> {
        if self.state != RigState::WaitingForStart {
            return Ok(());
        }
        lights::indicate(&mut self.pins.lights, &mut self.lit, index).map_err(RigError::Pin)
    }

    /// One tick of the way back to the origin: DIR low, at most `max_pulses_per_tick` pulses.
    fn home(&mut self) -> Result<(), RigError<PinError>> {
        self.pins.dir.set_low().map_err(RigError::Pin)?;
        let n = self.pulses.min(i64::from(self.config.max_pulses_per_tick));
        for _ in 0..n {
            self.pulse()?;
            self.pulses -= 1;
        }
        Ok(())
    }

    fn pulse(&mut self) -> Result<(), RigError<PinError>> {
        self.pins.step.set_high().map_err(RigError::Pin)?;
        self.delay.delay_ns(self.config.pulse_ns);
        self.pins.step.set_low().map_err(RigError::Pin)?;
        self.delay.delay_ns(self.config.pulse_ns);
        Ok(())
    }

    fn advance(&mut self, observe: impl FnOnce(&StepReport<f32, 2>)) -> Result<(), RigError<PinError>> {
        let Some(report) = self.scene.step() else {
            return self.finish(self.scene.outcome().unwrap_or(Outcome::Unfinished));
        };
        observe(&report);
        let target = libm::roundf((self.scene.fingers()[0] - self.origin) * self.config.steps_per_meter);
        if !target.is_finite() {
            return self.fault(RigFault::NonFinite);
        }
        // `as i32` saturates (one instruction on an FPU; `as i64` is a library call): a target
        // beyond 2^31 pulses, 27 km at 80 steps/mm, is still more than one tick's worth.
        let due = i64::from(target as i32) - self.pulses;
        if due > i64::from(self.config.max_pulses_per_tick) {
            return self.fault(RigFault::ActuatorOverrun);
        }
        for _ in 0..due.max(0) {
            self.pulse()?;
            self.pulses += 1;
        }
        self.show_modes(report.modes())?;
        match self.scene.outcome() {
            None => Ok(()),
            Some(o) => self.finish(o),
        }
    }

    fn finish(&mut self, outcome: Outcome) -> Result<(), RigError<PinError>> {
        match outcome {
            Outcome::Failed(e) => self.fault(RigFault::Step(e)),
            o => {
                log_info!("rig: outcome {} at t={=f32}, {=i64} pulses", o, self.scene.time(), self.pulses);
                self.state = RigState::Finished(o);
                Ok(())
            }
        }
    }

    fn fault(&mut self, fault: RigFault) -> Result<(), RigError<PinError>> {
        log_error!("rig: fault {} at t={=f32}", fault, self.scene.time());
        self.state = RigState::Fault(fault);
        self.lights_off()?;
        self.pins.fault.set_high().map_err(RigError::Pin)
    }

    fn lights_off(&mut self) -> Result<(), RigError<PinError>> {
        lights::all_off(&mut self.pins.lights, &mut self.lit).map_err(RigError::Pin)
    }

    /// Lights each finger's mode (turning the previous light off first); pins that keep
    /// their state are not touched.
    // Out of line, as `reset`: inlined into a board's loop (`firmware/src/realtime.rs`) the two
    // cost about 1.6 KB of flash in the smallest rig build; the instructions per step are the
    // same (QEMU M4F and M0).
    #[inline(never)]
    fn show_modes(&mut self, modes: [ContactMode; 2]) -> Result<(), RigError<PinError>> {
        for i in 0..2 {
            let new = modes[i];
            let old = self.lit[i];
            if old != Some(new) {
                log_info!("rig: t={=f32} finger {=usize} -> {=str}", self.scene.time(), i + 1, new.name());
            }
            self.pins.lights[i].show_mode(&mut self.lit[i], Some(new)).map_err(RigError::Pin)?;
        }
        Ok(())
    }
}
