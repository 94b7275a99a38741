//! [`MultibodyRig`]: the demo rig for a scene of several bodies, generic over `embedded-hal` 1.0
//! pins and the scene ([`RigScene`]), separate from any board; [`StackRig`] is the rig of the
//! 3-block stack (`docs/scenes.md`, "stack").
//!
//! The stack rig has no actuator: the teacher builds a real stack of three blocks over a table's
//! edge at the overhang the model is given (`StackParams::overhang`, the scale `s` of the harmonic
//! overhangs: the `k`-th block from the top reaches `s L / (2k)` beyond the one under it, the
//! bottom one beyond the table's edge), and the rig runs the model in real time beside it, showing
//! what the model predicts each interface is doing. The board calls [`MultibodyRig::tick`] once
//! per timer period `h` (the scene's step: one step per tick); each tick:
//!
//! 1. before the start: reads the start button, debounced ([`PressDetector`],
//!    [`RigConfig::debounce_ticks`] equal samples); on a press, lights each interface's mode at the
//!    scene's start;
//! 2. running: advances the scene one step, switches an interface's lights when its mode changes,
//!    and at the outcome (the stack: [`Outcome::Fell`] on the step a block tilts or drops past its
//!    limit, [`Outcome::Held`] at `max_time`) stops in [`MultibodyRigState::Finished`] with the
//!    lights showing the last step's modes;
//! 3. a failed step (the solver, a non-finite state, more contacts than the LCP holds: the core's
//!    [`StepError`]), or a step whose reported state the rig finds non-finite, never panics: the
//!    rig turns the mode lights off, turns the fault light on, logs it, and stays in
//!    [`MultibodyRigState::Fault`].
//!
//! Lights: one [`ModeLights`] per interface, i.e. per resting pair of the scene (the stack: pair 0
//! the table and block 1, pair `p` blocks `p` and `p + 1`, counted from the bottom), showing its
//! [`InterfaceMode`] from its four candidate contacts: *sliding* when any slides, *sticking* when
//! at least two touch (a block resting flat), *tipping* (the sticking and the separated lights
//! together) when one touches (all the load on one corner: the block above pivots about it, how a
//! stack falls over the table's edge), *separated* when none touches; a contact touches when it
//! carries a normal impulse. An interface
//! is shown from the start of a run to its end; pins are driven only when their state changes.
//! Logging (start, interface mode changes, outcome, faults) goes to `defmt` with the `defmt`
//! feature and compiles to nothing without it.
//!
//! Parameters: [`MultibodyRig::new`] and [`MultibodyRig::reset`] accept only a set the core
//! validates ([`RigScene::build`]: the stack's `Stack::new`) whose step the board's timer ticks in
//! real time ([`RigConfig::check_step`]); anything else is [`RigError::Params`] or
//! [`RigError::Unperformable`] ([`crate::Unperformable::Step`]) before any pin is touched. Of
//! [`RigConfig`] only the button's and the step's fields apply (the carriage's are the meter-stick
//! rig's).
//!
//! Runs on demand: [`MultibodyRig::start`] and [`MultibodyRig::stop`] do what the button and the
//! outcome do; [`MultibodyRig::reset`] loads a parameter set (a rejected set leaves the rig as it
//! was), turns every light off and returns to [`MultibodyRigState::WaitingForStart`]; after a
//! reset the start button must be released (debounced) before a press starts a run again.
//! [`MultibodyRig::tick_with`] hands each step's report to the caller. [`MultibodyRig::indicate`]
//! shows a small number on interface 0's lights while waiting (the board's selected set). There
//! is no host link ([`crate::session`] drives the meter-stick rig only).

use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::multibody::scenes::Stack3;
use meterstick_core::multibody::{StepError, SystemStepReport};
use meterstick_core::planar::{BodyState, ContactMode};
use meterstick_core::scene::Outcome;

use crate::lights::{self, ModeLights};
use crate::{InterfaceMode, PressDetector, RigConfig, RigError, RigScene};

/// The pins of a rig of `I` interfaces: `B` an input (the start button), `P` outputs.
#[derive(Debug)]
pub struct MultibodyRigPins<B, P, const I: usize> {
    /// Start button.
    pub start: B,
    /// Each interface's mode lights, in the scene's pair order (the stack: the table's first).
    pub lights: [ModeLights<P>; I],
    /// Fault light.
    pub fault: P,
}

/// Where a [`MultibodyRig`] is.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MultibodyRigState {
    /// Waiting for the start button.
    WaitingForStart,
    /// Stepping the scene in real time.
    Running,
    /// The scene ended (the stack: held or fell; unfinished when stopped); the lights show the
    /// last step's modes.
    Finished(Outcome),
    /// Stopped on a failed step (fault light on, mode lights off).
    Fault(StepError),
}

/// The demo rig's loop over a scene of several bodies `S` (`BODIES` bodies, `PAIRS` interfaces).
#[derive(Debug)]
pub struct MultibodyRig<B, P, S, const BODIES: usize, const PAIRS: usize>
where
    S: RigScene<BODIES, PAIRS>,
{
    scene: S,
    params: S::Params,
    pins: MultibodyRigPins<B, P, PAIRS>,
    config: RigConfig,
    state: MultibodyRigState,
    lit: [Option<InterfaceMode>; PAIRS],
    /// The start button, debounced.
    start_press: PressDetector,
}

/// The rig of the 3-block stack (`Stack3<f32>`): three interfaces, table-block 1, block 1-block 2,
/// block 2-block 3.
pub type StackRig<B, P> = MultibodyRig<B, P, Stack3<f32>, 3, 3>;

impl<B, P, S, PinError, const BODIES: usize, const PAIRS: usize> MultibodyRig<B, P, S, BODIES, PAIRS>
where
    B: InputPin<Error = PinError>,
    P: OutputPin<Error = PinError>,
    S: RigScene<BODIES, PAIRS>,
{
    /// A rig for `params`, with every output driven low.
    ///
    /// # Errors
    /// Invalid parameters, a step the board cannot tick ([`RigConfig::check_step`]), both before
    /// any pin is touched, or a pin error.
    pub fn new(
        params: S::Params,
        config: RigConfig,
        pins: MultibodyRigPins<B, P, PAIRS>,
    ) -> Result<Self, RigError<PinError>> {
        let scene = S::build(params).map_err(RigError::Params)?;
        config.check_step(S::step_of(&params)).map_err(RigError::Unperformable)?;
        let mut rig = Self {
            scene,
            params,
            pins,
            config,
            state: MultibodyRigState::WaitingForStart,
            lit: [None; PAIRS],
            start_press: PressDetector::new(config.debounce_ticks),
        };
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

    /// The parameters of the scene being shown (or about to be).
    #[must_use]
    pub const fn params(&self) -> &S::Params {
        &self.params
    }

    /// The rig's state.
    #[must_use]
    pub const fn state(&self) -> MultibodyRigState {
        self.state
    }

    /// Each interface's mode as its lights show it (`None`: all three off).
    #[must_use]
    pub const fn shown(&self) -> &[Option<InterfaceMode>; PAIRS] {
        &self.lit
    }

    /// Reads the start button now, raw (`true`: pressed), e.g. for the board to reset a finished
    /// run on a (debounced) press; [`Self::tick`] reads it only while waiting, through its own
    /// debouncer.
    ///
    /// # Errors
    /// A pin error.
    pub fn start_pressed(&mut self) -> Result<bool, RigError<PinError>> {
        Ok(self.pins.start.is_low().map_err(RigError::Pin)? == self.config.button_active_low)
    }

    /// Gives the pins back.
    pub fn release(self) -> MultibodyRigPins<B, P, PAIRS> {
        self.pins
    }

    /// One timer tick (call once per step `h`); returns the state after it.
    ///
    /// # Errors
    /// A pin error.
    pub fn tick(&mut self) -> Result<MultibodyRigState, RigError<PinError>> {
        self.tick_with(|_| {})
    }

    /// [`Self::tick`], handing the step's report to `observe` when the tick stepped the scene
    /// (not called on a tick that waits, or whose step failed).
    ///
    /// # Errors
    /// A pin error.
    pub fn tick_with(
        &mut self,
        observe: impl FnOnce(&SystemStepReport<f32, BODIES, PAIRS>),
    ) -> Result<MultibodyRigState, RigError<PinError>> {
        match self.state {
            MultibodyRigState::WaitingForStart => self.wait_for_start()?,
            MultibodyRigState::Running => self.advance(observe)?,
            MultibodyRigState::Finished(_) | MultibodyRigState::Fault(_) => {}
        }
        Ok(self.state)
    }

    /// A tick while waiting: the start button sampled, debounced; a press starts the run. Out of
    /// line: it must not weigh on the running tick's code.
    #[inline(never)]
    fn wait_for_start(&mut self) -> Result<(), RigError<PinError>> {
        let pressed = self.start_pressed()?;
        if self.start_press.sample(pressed) {
            self.start()?;
        }
        Ok(())
    }

    /// Starts the run (as the start button does) if the rig is waiting, lighting each
    /// interface's mode at the start; returns whether it started.
    ///
    /// # Errors
    /// A pin error.
    pub fn start(&mut self) -> Result<bool, RigError<PinError>> {
        if self.state != MultibodyRigState::WaitingForStart {
            return Ok(false);
        }
        let modes = *self.scene.modes();
        self.show_modes(&modes)?;
        log_info!("multibody rig: start");
        self.state = MultibodyRigState::Running;
        Ok(true)
    }

    /// Stops a run in progress: it ends [`Outcome::Unfinished`] (the lights keep the last
    /// modes); returns whether a run was stopped.
    ///
    /// # Errors
    /// A pin error.
    pub fn stop(&mut self) -> Result<bool, RigError<PinError>> {
        if self.state != MultibodyRigState::Running {
            return Ok(false);
        }
        self.finish(Outcome::Unfinished)?;
        Ok(true)
    }

    /// Loads `params` (validated by the core and checked against the board's timer first: on
    /// [`RigError::Params`] or [`RigError::Unperformable`] nothing changes), turns every light
    /// off and goes back to [`MultibodyRigState::WaitingForStart`]. Allowed in any state (it also
    /// ends a run in progress, unfinished and unreported).
    ///
    /// # Errors
    /// Invalid parameters, a step the board cannot tick, or a pin error.
    pub fn reset(&mut self, params: S::Params) -> Result<(), RigError<PinError>> {
        let scene = S::build(params).map_err(RigError::Params)?;
        self.config.check_step(S::step_of(&params)).map_err(RigError::Unperformable)?;
        self.lights_off()?;
        self.pins.fault.set_low().map_err(RigError::Pin)?;
        self.scene = scene;
        self.params = params;
        self.state = MultibodyRigState::WaitingForStart;
        // A press held through the reset (the one that asked for it) is spent: a start needs a
        // debounced release, then a debounced press.
        self.start_press.spend_press();
        log_info!("multibody rig: reset");
        Ok(())
    }

    /// While waiting: lights interface 0's light number `index` (0 sticking, 1 sliding,
    /// 2 separated; e.g. the board's selected parameter set), or none. The run's first modes
    /// replace it at the start. Ignored in other states.
    ///
    /// # Errors
    /// A pin error.
    pub fn indicate(&mut self, index: Option<u8>) -> Result<(), RigError<PinError>> {
        if self.state != MultibodyRigState::WaitingForStart {
            return Ok(());
        }
        lights::indicate(&mut self.pins.lights, &mut self.lit, index).map_err(RigError::Pin)
    }

    fn advance(
        &mut self,
        observe: impl FnOnce(&SystemStepReport<f32, BODIES, PAIRS>),
    ) -> Result<(), RigError<PinError>> {
        let Some(report) = self.scene.step() else {
            return self.finish(self.scene.outcome().unwrap_or(Outcome::Unfinished));
        };
        if !report.states.iter().all(BodyState::is_finite) {
            return self.fault(StepError::NonFinite);
        }
        observe(&report);
        self.show_modes(&report.modes)?;
        match self.scene.outcome() {
            None => Ok(()),
            Some(o) => self.finish(o),
        }
    }

    fn finish(&mut self, outcome: Outcome) -> Result<(), RigError<PinError>> {
        match outcome {
            Outcome::Failed(e) => self.fault(e),
            o => {
                log_info!("multibody rig: outcome {} at t={=f32}", o, self.scene.time());
                self.state = MultibodyRigState::Finished(o);
                Ok(())
            }
        }
    }

    fn fault(&mut self, fault: StepError) -> Result<(), RigError<PinError>> {
        log_error!("multibody rig: fault {} at t={=f32}", fault, self.scene.time());
        self.state = MultibodyRigState::Fault(fault);
        self.lights_off()?;
        self.pins.fault.set_high().map_err(RigError::Pin)
    }

    fn lights_off(&mut self) -> Result<(), RigError<PinError>> {
        lights::all_off(&mut self.pins.lights, &mut self.lit).map_err(RigError::Pin)
    }

    /// Lights each interface's mode (turning its previous light off first); pins that keep
    /// their state are not touched.
    fn show_modes(&mut self, modes: &[[ContactMode; 4]; PAIRS]) -> Result<(), RigError<PinError>> {
        let interfaces = self.lit.iter_mut().zip(&mut self.pins.lights).zip(modes);
        for (i, ((lit, lights), candidates)) in interfaces.enumerate() {
            let new = InterfaceMode::of(*candidates);
            let old = *lit;
            if old != Some(new) {
                log_info!(
                    "multibody rig: t={=f32} interface {=usize} -> {=str}",
                    self.scene.time(),
                    i,
                    new.name()
                );
            }
            lights.show_mode(lit, Some(new)).map_err(RigError::Pin)?;
        }
        Ok(())
    }
}
