//! [`InterfaceMode`]: what an interface between two resting bodies (or a body and the table) is
//! doing, from its four candidate contacts' modes, and the lights that show it.

use meterstick_core::planar::{ContactMode, Direction};

use crate::lights::{SEPARATED, SLIDING, STICKING, Shown};

/// An interface's mode after a step, from its candidates' ([`Self::of`]). A candidate *touches*
/// when it carries a normal impulse ([`ContactMode::is_touching`]: sticking or sliding); one that
/// carries none is separated, whatever its gap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum InterfaceMode {
    /// At least two candidates touch (a face resting on a face: both ends of the overlap carry
    /// load), none slides. Light: sticking.
    Sticking,
    /// A touching candidate slides (the first sliding candidate's direction). Light: sliding.
    Sliding(Direction),
    /// Exactly one candidate touches, and sticks: the interface's whole load is on that corner,
    /// so the upper body pivots about it, its other end lifting (a stack beyond the critical
    /// overhang falls this way, every interface at once). Lights: sticking and separated
    /// together.
    Tipping,
    /// No candidate touches. Light: separated.
    Separated,
}

impl InterfaceMode {
    /// The interface's mode from its candidates' modes (see each variant).
    #[must_use]
    pub fn of(candidates: [ContactMode; 4]) -> Self {
        let mut touching = 0u8;
        for m in candidates {
            match m {
                ContactMode::Sliding(d) => return Self::Sliding(d),
                ContactMode::Sticking => touching += 1,
                ContactMode::Separated => {}
            }
        }
        match touching {
            0 => Self::Separated,
            1 => Self::Tipping,
            _ => Self::Sticking,
        }
    }

    /// A short stable name: `sticking`, `sliding+`, `sliding-`, `tipping`, `separated`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Sticking => "sticking",
            Self::Sliding(d) => ContactMode::Sliding(d).name(),
            Self::Tipping => "tipping",
            Self::Separated => "separated",
        }
    }
}

impl Shown for InterfaceMode {
    #[inline]
    fn lights(self) -> u8 {
        match self {
            Self::Sticking => STICKING,
            Self::Sliding(_) => SLIDING,
            Self::Tipping => STICKING | SEPARATED,
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
