//! [`ModeLights`]: one contact's three mode lights (sticking / sliding / separated), the piece
//! every rig shows its modes with: a finger's on the meter-stick rig ([`crate::Rig`]: exactly one
//! on), an interface's on the rig of several bodies ([`crate::MultibodyRig`]: one, or sticking
//! and separated together while the interface tips, [`crate::InterfaceMode::Tipping`]).
//!
//! What is shown is a set of lights ([`STICKING`], [`SLIDING`], [`SEPARATED`] as bits); a change
//! turns the lights that leave the set off first, then those that join it on, and touches no
//! other pin (a slide that changes direction keeps the sliding light on untouched).

use embedded_hal::digital::OutputPin;
use meterstick_core::planar::ContactMode;

/// One contact's three mode lights.
#[derive(Debug)]
pub struct ModeLights<P> {
    /// On while the contact sticks.
    pub sticking: P,
    /// On while it slides.
    pub sliding: P,
    /// On while it does not touch.
    pub separated: P,
}

/// The sticking light in a set of lights.
pub(crate) const STICKING: u8 = 1;
/// The sliding light in a set of lights.
pub(crate) const SLIDING: u8 = 2;
/// The separated light in a set of lights.
pub(crate) const SEPARATED: u8 = 4;

/// The light a contact's mode shows on (either sliding direction: the sliding light).
pub(crate) const fn light_of(mode: ContactMode) -> u8 {
    match mode {
        ContactMode::Sticking => STICKING,
        ContactMode::Sliding(_) => SLIDING,
        ContactMode::Separated => SEPARATED,
    }
}

impl<P: OutputPin> ModeLights<P> {
    /// The pin of `mode`'s light.
    pub(crate) fn pin(&mut self, mode: ContactMode) -> &mut P {
        match mode {
            ContactMode::Sticking => &mut self.sticking,
            ContactMode::Sliding(_) => &mut self.sliding,
            ContactMode::Separated => &mut self.separated,
        }
    }

    /// Shows `new` where `old` (or nothing) was shown, one light each ([`Self::show`]).
    pub(crate) fn switch(&mut self, old: Option<ContactMode>, new: ContactMode) -> Result<(), P::Error> {
        self.show(old.map_or(0, light_of), light_of(new))
    }

    /// Shows the set of lights `new` where `old` was shown: the lights in `old` only off, then
    /// those in `new` only on; the others are not touched.
    pub(crate) fn show(&mut self, old: u8, new: u8) -> Result<(), P::Error> {
        // Most ticks change nothing: out at once.
        if old == new {
            return Ok(());
        }
        let (off, on) = (old & !new, new & !old);
        if off & STICKING != 0 {
            self.sticking.set_low()?;
        }
        if off & SLIDING != 0 {
            self.sliding.set_low()?;
        }
        if off & SEPARATED != 0 {
            self.separated.set_low()?;
        }
        if on & STICKING != 0 {
            self.sticking.set_high()?;
        }
        if on & SLIDING != 0 {
            self.sliding.set_high()?;
        }
        if on & SEPARATED != 0 {
            self.separated.set_high()?;
        }
        Ok(())
    }
}
