//! Pins and a delay for running the rig without hardware: QEMU, host tests.

use core::convert::Infallible;

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{ErrorType, InputPin, OutputPin};

use crate::{Carriage, CarriedFinger, ModeLights, NoActuator, Rig, RigConfig, RigError, RigPins, RigScene};

/// A headless pin, for running the rig without hardware (QEMU, host tests): as an output it
/// counts its rising edges; as an input it reads low, i.e. a pressed active-low button.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct HeadlessPin {
    high: bool,
    rises: u32,
}

impl HeadlessPin {
    /// Rising edges so far (for STEP: the pulses; for a light: the times it came on).
    #[must_use]
    pub const fn rises(&self) -> u32 {
        self.rises
    }
}

impl ErrorType for HeadlessPin {
    type Error = Infallible;
}

impl OutputPin for HeadlessPin {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.high = false;
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        self.rises += u32::from(!self.high);
        self.high = true;
        Ok(())
    }
}

impl InputPin for HeadlessPin {
    fn is_high(&mut self) -> Result<bool, Infallible> {
        Ok(false)
    }
    fn is_low(&mut self) -> Result<bool, Infallible> {
        Ok(true)
    }
}

/// A delay that does not wait (headless runs).
#[derive(Debug, Default, Clone, Copy)]
pub struct NoDelay;

impl DelayNs for NoDelay {
    fn delay_ns(&mut self, _ns: u32) {}
}

impl<S: RigScene<2> + CarriedFinger, D: DelayNs>
    Rig<S, Carriage<HeadlessPin, D>, HeadlessPin, HeadlessPin, 2>
{
    /// A rig whose carriage moves finger 1 (the meter stick's, in the plane or in space), on
    /// [`HeadlessPin`]s (the start button reads pressed), its carriage's pulses timed by `delay`.
    ///
    /// # Errors
    /// Invalid parameters, or parameters the rig cannot perform.
    pub fn headless(params: S::Params, config: RigConfig, delay: D) -> Result<Self, RigError<Infallible>> {
        let carriage = Carriage::new(HeadlessPin::default(), HeadlessPin::default(), delay);
        Self::new(params, config, headless_pins(), carriage)
    }
}

impl<S: RigScene<L>, const L: usize> Rig<S, NoActuator, HeadlessPin, HeadlessPin, L> {
    /// A rig without an actuator on [`HeadlessPin`]s (the start button reads pressed).
    ///
    /// # Errors
    /// Invalid parameters, or a step outside the config's range.
    pub fn headless(params: S::Params, config: RigConfig) -> Result<Self, RigError<Infallible>> {
        Self::new(params, config, headless_pins(), NoActuator)
    }
}

fn headless_pins<const L: usize>() -> RigPins<HeadlessPin, HeadlessPin, L> {
    RigPins {
        start: HeadlessPin::default(),
        lights: core::array::from_fn(|_| headless_lights()),
        fault: HeadlessPin::default(),
    }
}

fn headless_lights() -> ModeLights<HeadlessPin> {
    ModeLights {
        sticking: HeadlessPin::default(),
        sliding: HeadlessPin::default(),
        separated: HeadlessPin::default(),
    }
}
