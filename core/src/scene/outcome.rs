//! [`Outcome`]: how a scene's run ended.

use crate::planar::StepError;

/// How a run ended. Each scene uses the variants its rules name (`docs/scenes.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Outcome {
    /// Meter stick: the fingers met with the centre of mass between them and the rod stayed on
    /// them for the hold time.
    Balanced,
    /// Meter stick: the rod tipped, dropped or left both fingers. Ladder: its top reached the floor.
    Fell,
    /// Incline, ladder: the body never slid (it stands).
    Held,
    /// Incline: the block slid down the slope.
    Slid,
    /// Incline: the block tipped over its lower edge.
    Tipped,
    /// The time limit passed with no other outcome.
    Unfinished,
    /// A step failed (the state is that before it).
    Failed(StepError),
}

impl Outcome {
    /// A short stable name: `Balanced`, `Fell`, `Held`, `Slid`, `Tipped`, `Unfinished`, `Failed`.
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Balanced => "Balanced",
            Self::Fell => "Fell",
            Self::Held => "Held",
            Self::Slid => "Slid",
            Self::Tipped => "Tipped",
            Self::Unfinished => "Unfinished",
            Self::Failed(_) => "Failed",
        }
    }

    /// `true` for an outcome of the physics (not a failed step).
    #[must_use]
    pub const fn is_physical(&self) -> bool {
        !matches!(self, Self::Failed(_))
    }
}

impl From<StepError> for Outcome {
    fn from(e: StepError) -> Self {
        Self::Failed(e)
    }
}

impl core::fmt::Display for Outcome {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Failed(e) => write!(f, "Failed ({e})"),
            other => f.write_str(other.name()),
        }
    }
}
