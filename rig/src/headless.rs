//! Pins and a delay for running the rig without hardware: QEMU, host tests.

use core::convert::Infallible;

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{ErrorType, InputPin, OutputPin};
use meterstick_core::scene::MeterStickParams;

use crate::{ModeLights, MultibodyRig, MultibodyRigPins, Rig, RigConfig, RigError, RigPins, RigScene};

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

impl<D: DelayNs, const N: usize, const E: usize> Rig<HeadlessPin, HeadlessPin, D, N, E> {
    /// A rig on [`HeadlessPin`]s (the start button reads pressed).
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn headless(
        params: MeterStickParams<f32>,
        config: RigConfig,
        delay: D,
    ) -> Result<Self, RigError<Infallible>> {
        let pins = RigPins {
            start: HeadlessPin::default(),
            step: HeadlessPin::default(),
            dir: HeadlessPin::default(),
            lights: [headless_lights(), headless_lights()],
            fault: HeadlessPin::default(),
        };
        Self::new(params, config, pins, delay)
    }
}

impl<S: RigScene<B, P>, const B: usize, const P: usize> MultibodyRig<HeadlessPin, HeadlessPin, S, B, P> {
    /// A rig of several bodies on [`HeadlessPin`]s (the start button reads pressed).
    ///
    /// # Errors
    /// Invalid parameters, or a step outside the config's range.
    pub fn headless(params: S::Params, config: RigConfig) -> Result<Self, RigError<Infallible>> {
        let pins = MultibodyRigPins {
            start: HeadlessPin::default(),
            lights: core::array::from_fn(|_| headless_lights()),
            fault: HeadlessPin::default(),
        };
        Self::new(params, config, pins)
    }
}

fn headless_lights() -> ModeLights<HeadlessPin> {
    ModeLights {
        sticking: HeadlessPin::default(),
        sliding: HeadlessPin::default(),
        separated: HeadlessPin::default(),
    }
}
