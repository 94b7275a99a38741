//! [`ModeLights`]: one contact's three mode lights (sticking / sliding / separated), the piece
//! the rig ([`crate::Rig`]) shows its modes with: a finger's on the meter-stick rig (exactly one
//! on), an interface's on the stack rig (one, or sticking and separated together while the
//! interface tips, [`crate::InterfaceMode::Tipping`]).
//!
//! What is shown is a set of lights ([`STICKING`], [`SLIDING`], [`SEPARATED`] as bits) of a mode
//! ([`Shown`]); a change turns the lights that leave the set off first, then those that join it
//! on, and touches no other pin (a slide that changes direction keeps the sliding light on
//! untouched). The rig lights their modes ([`ModeLights::show_mode`]), turn them off
//! ([`all_off`]) and show the waiting number ([`indicate`]) here.

use embedded_hal::digital::OutputPin;
use meterstick_core::planar::{ContactMode, Direction};

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

/// A mode a [`ModeLights`] shows: a contact's ([`ContactMode`], the meter-stick rig's fingers) or
/// an interface's ([`crate::InterfaceMode`]), the modes a [`crate::RigScene`] shows (public in this
/// private module: nameable in `RigScene`'s bound, implemented here only).
pub trait Shown: Copy + PartialEq {
    /// The set of lights that shows it.
    fn lights(self) -> u8;
    /// The mode that shows the small number `index` while a rig waits (0 sticking, 1 sliding,
    /// 2 and above separated: one light each).
    fn number(index: u8) -> Self;
    /// A short stable name, for logs.
    fn name(self) -> &'static str;
}

impl Shown for ContactMode {
    #[inline]
    fn lights(self) -> u8 {
        match self {
            Self::Sticking => STICKING,
            Self::Sliding(_) => SLIDING,
            Self::Separated => SEPARATED,
        }
    }

    #[inline]
    fn number(index: u8) -> Self {
        match index {
            0 => Self::Sticking,
            1 => Self::Sliding(Direction::Plus),
            _ => Self::Separated,
        }
    }

    #[inline]
    fn name(self) -> &'static str {
        Self::name(self)
    }
}

/// A contact's mode in three dimensions (feature `spatial`: the meter stick in space's fingers);
/// its sliding has no sign (a slip in the plane has a direction, not a side).
#[cfg(feature = "spatial")]
impl Shown for meterstick_core::spatial::Mode {
    #[inline]
    fn lights(self) -> u8 {
        match self {
            Self::Sticking => STICKING,
            Self::Sliding => SLIDING,
            Self::Separated => SEPARATED,
        }
    }

    #[inline]
    fn number(index: u8) -> Self {
        match index {
            0 => Self::Sticking,
            1 => Self::Sliding,
            _ => Self::Separated,
        }
    }

    #[inline]
    fn name(self) -> &'static str {
        match self {
            Self::Sticking => "sticking",
            Self::Sliding => "sliding",
            Self::Separated => "separated",
        }
    }
}

impl<P: OutputPin> ModeLights<P> {
    /// Drives all three lights low (a rig's start, before anything is shown).
    pub(crate) fn all_low(&mut self) -> Result<(), P::Error> {
        self.sticking.set_low()?;
        self.sliding.set_low()?;
        self.separated.set_low()
    }

    /// Shows `new` (nothing: all three off) where `*lit` is shown ([`Self::show`]), and records
    /// it in `lit`.
    pub(crate) fn show_mode<M: Shown>(
        &mut self,
        lit: &mut Option<M>,
        new: Option<M>,
    ) -> Result<(), P::Error> {
        self.show(lit.map_or(0, M::lights), new.map_or(0, M::lights))?;
        *lit = new;
        Ok(())
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

/// Turns every light of `lights` off (those `lit` records as shown), `lit` all `None`.
pub(crate) fn all_off<P: OutputPin, M: Shown, const I: usize>(
    lights: &mut [ModeLights<P>; I],
    lit: &mut [Option<M>; I],
) -> Result<(), P::Error> {
    for (l, shown) in lights.iter_mut().zip(lit) {
        l.show_mode(shown, None)?;
    }
    Ok(())
}

/// A rig's waiting number: `index` (or nothing) on the first of `lights` ([`Shown::number`]).
pub(crate) fn indicate<P: OutputPin, M: Shown, const I: usize>(
    lights: &mut [ModeLights<P>; I],
    lit: &mut [Option<M>; I],
    index: Option<u8>,
) -> Result<(), P::Error> {
    match (lights.first_mut(), lit.first_mut()) {
        (Some(l), Some(shown)) => l.show_mode(shown, index.map(M::number)),
        _ => Ok(()),
    }
}
