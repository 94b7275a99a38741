//! [`Actuator`]: what a rig moves to follow its scene, driven by the one rig state machine
//! ([`crate::Rig`]); [`Carriage`], the meter-stick rig's stepper-driven finger carriage, and
//! [`NoActuator`], a rig that moves nothing (the stack: the teacher builds the real stack).

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use meterstick_core::scene::MeterStick;

use crate::{RigConfig, RigFault};

/// What a rig moves to follow its scene `S`, over pins whose error is `E`. The rig calls
/// [`Self::init`] when it is built, [`Self::arm`] at a run's start, [`Self::follow`] after each
/// step, [`Self::park`] when it loads a new parameter set and, while [`Self::homing`], one
/// [`Self::home`] per tick before it accepts a start.
pub trait Actuator<S, E> {
    /// Drives every output low and takes `scene`'s start as its origin (the rig is built).
    ///
    /// # Errors
    /// A pin error.
    fn init(&mut self, scene: &S) -> Result<(), E>;

    /// Takes `scene`'s start as the origin to go back to (a new parameter set is loaded).
    ///
    /// # Errors
    /// A pin error.
    fn park(&mut self, scene: &S) -> Result<(), E>;

    /// `true` while it is still on its way back to the origin: no run starts until it is there.
    fn homing(&self) -> bool;

    /// One tick of the way back to the origin.
    ///
    /// # Errors
    /// A pin error.
    fn home(&mut self, config: &RigConfig) -> Result<(), E>;

    /// Readies it for a run (at the start).
    ///
    /// # Errors
    /// A pin error.
    fn arm(&mut self) -> Result<(), E>;

    /// Brings it to where `scene` is after a step; `Ok(Some(fault))` when it cannot.
    ///
    /// # Errors
    /// A pin error.
    fn follow(&mut self, scene: &S, config: &RigConfig) -> Result<Option<RigFault>, E>;
}

/// A rig that moves nothing: every call does nothing, and it is never homing.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct NoActuator;

impl<S, E> Actuator<S, E> for NoActuator {
    #[inline]
    fn init(&mut self, _: &S) -> Result<(), E> {
        Ok(())
    }

    #[inline]
    fn park(&mut self, _: &S) -> Result<(), E> {
        Ok(())
    }

    #[inline]
    fn homing(&self) -> bool {
        false
    }

    #[inline]
    fn home(&mut self, _: &RigConfig) -> Result<(), E> {
        Ok(())
    }

    #[inline]
    fn arm(&mut self) -> Result<(), E> {
        Ok(())
    }

    #[inline]
    fn follow(&mut self, _: &S, _: &RigConfig) -> Result<Option<RigFault>, E> {
        Ok(None)
    }
}

/// The meter-stick rig's finger carriage (finger 1): a stepper driver's STEP and DIR pins and the
/// delay that times the pulses. It follows finger 1's position from its start, the origin, in
/// pulses of [`RigConfig::steps_per_meter`]: after each step it emits the pulses that bring it to
/// `round((x1(t) - x1(0)) * steps_per_meter)` in all (DIR high, toward finger 2; a rig accepts
/// only runs where finger 1 approaches finger 2 or stays, [`RigConfig::check`]), each
/// [`RigConfig::pulse_ns`] high then low. A target that is not finite is [`RigFault::NonFinite`];
/// more than [`RigConfig::max_pulses_per_tick`] pulses due in one tick is
/// [`RigFault::ActuatorOverrun`] (a fault, not a silently lagging carriage). Homing drives DIR low
/// and emits at most `max_pulses_per_tick` pulses per tick until it is back at the origin.
#[derive(Debug)]
pub struct Carriage<P, D> {
    /// Stepper driver STEP (one pulse per step).
    pub step: P,
    /// Stepper driver DIR (high: toward finger 2).
    pub dir: P,
    /// Times the pulses.
    pub delay: D,
    origin: f32,
    pulses: i64,
}

impl<P, D> Carriage<P, D> {
    /// A carriage on `step` and `dir`, its pulses timed by `delay`, at its origin.
    #[must_use]
    pub const fn new(step: P, dir: P, delay: D) -> Self {
        Self { step, dir, delay, origin: 0.0, pulses: 0 }
    }

    /// Pulses from the origin (toward finger 2).
    #[must_use]
    pub const fn pulses(&self) -> i64 {
        self.pulses
    }
}

impl<P: OutputPin, D: DelayNs> Carriage<P, D> {
    fn pulse(&mut self, config: &RigConfig) -> Result<(), P::Error> {
        self.step.set_high()?;
        self.delay.delay_ns(config.pulse_ns);
        self.step.set_low()?;
        self.delay.delay_ns(config.pulse_ns);
        Ok(())
    }
}

/// A scene whose finger 1 a [`Carriage`] moves: where that finger is along the carriage's rail.
pub trait CarriedFinger {
    /// Finger 1 at the scene's start, along the rail (m): the carriage's origin.
    fn rail_start(&self) -> f32;
    /// Finger 1 now, along the rail (m).
    fn rail_position(&self) -> f32;
}

/// The rail along `x`: finger 1's `x`.
impl<const N: usize, const EV: usize> CarriedFinger for MeterStick<f32, N, EV> {
    #[inline]
    fn rail_start(&self) -> f32 {
        self.params().finger1_x
    }

    #[inline]
    fn rail_position(&self) -> f32 {
        self.fingers()[0]
    }
}

/// The rail along finger 1's path, at the heading `psi` to the rod's axis (`docs/scenes.md`,
/// "meter-stick-3d"): the finger's `x` over `cos psi`, the distance along the path from where it
/// crosses the rod's vertical plane (feature `spatial`).
#[cfg(feature = "spatial")]
impl CarriedFinger for meterstick_core::scene::spatial::MeterStick3d<f32> {
    #[inline]
    fn rail_start(&self) -> f32 {
        self.params().finger1_x / self.params().heading_sin_cos().1
    }

    #[inline]
    fn rail_position(&self) -> f32 {
        self.tips()[0][0] / self.path().1
    }
}

impl<S, P, D, E> Actuator<S, E> for Carriage<P, D>
where
    S: CarriedFinger,
    P: OutputPin<Error = E>,
    D: DelayNs,
{
    fn init(&mut self, scene: &S) -> Result<(), E> {
        self.step.set_low()?;
        self.dir.set_low()?;
        self.origin = scene.rail_start();
        Ok(())
    }

    fn park(&mut self, scene: &S) -> Result<(), E> {
        self.dir.set_low()?;
        self.origin = scene.rail_start();
        log_info!("rig: {=i64} pulses back to the origin", self.pulses);
        Ok(())
    }

    #[inline]
    fn homing(&self) -> bool {
        self.pulses > 0
    }

    fn home(&mut self, config: &RigConfig) -> Result<(), E> {
        self.dir.set_low()?;
        let n = self.pulses.min(i64::from(config.max_pulses_per_tick));
        for _ in 0..n {
            self.pulse(config)?;
            self.pulses -= 1;
        }
        Ok(())
    }

    #[inline]
    fn arm(&mut self) -> Result<(), E> {
        self.dir.set_high()
    }

    #[inline]
    fn follow(&mut self, scene: &S, config: &RigConfig) -> Result<Option<RigFault>, E> {
        let target = libm::roundf((scene.rail_position() - self.origin) * config.steps_per_meter);
        if !target.is_finite() {
            return Ok(Some(RigFault::NonFinite));
        }
        // `as i32` saturates (one instruction on an FPU; `as i64` is a library call): a target
        // beyond 2^31 pulses, 27 km at 80 steps/mm, is still more than one tick's worth.
        let due = i64::from(target as i32) - self.pulses;
        if due > i64::from(config.max_pulses_per_tick) {
            return Ok(Some(RigFault::ActuatorOverrun));
        }
        for _ in 0..due.max(0) {
            self.pulse(config)?;
            self.pulses += 1;
        }
        Ok(None)
    }
}
