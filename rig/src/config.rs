//! [`RigConfig`]: what a board's rig can perform (its carriage, its start button, the steps its
//! timer ticks in real time), and [`Unperformable`], what it cannot though the core accepts it.

use meterstick_core::scene::MeterStickParams;

#[cfg(doc)]
use crate::{Carriage, PressDetector, RigError, RigFault};

/// Rig constants.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RigConfig {
    /// Stepper pulses per metre of carriage travel (e.g. 80 steps/mm for a GT2 belt on a 200-step
    /// motor at 1/16 microstepping: 80,000). This and the next two fields are the [`Carriage`]'s
    /// (the meter-stick rig's); a rig without an actuator ignores them.
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
