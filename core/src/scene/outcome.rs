//! [`Outcome`]: how a scene's run ended.

use crate::StepError;

/// How a run ended. Each scene uses the variants its rules name (`docs/scenes.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Outcome {
    /// Meter stick: the fingers met with the centre of mass between them and the rod stayed on
    /// them for the hold time.
    Balanced,
    /// Meter stick: the rod tipped, dropped or left both fingers. Ladder: its top reached the floor.
    /// Stack: a block tilted or dropped.
    Fell,
    /// Incline, ladder: the body never slid (it stands). Block-on-block, tablecloth: nothing slid;
    /// stack: nothing fell.
    Held,
    /// Incline: the block slid down the slope. Block-on-block: the top block slid on the bottom one.
    Slid,
    /// Incline: the block tipped over its lower edge. Block-on-block: the top block tipped.
    Tipped,
    /// Cylinder: it rolled down the slope without slipping.
    Rolled,
    /// Painlevé: the sliding end stopped within one step under an impulsive friction (a tangential
    /// impact).
    Jammed,
    /// The time limit passed with no other outcome.
    Unfinished,
    /// A step failed, in any engine (the state is that before it).
    Failed(StepError),
    /// Block-on-block, tablecloth: the lower body slid on the floor with the upper one riding on
    /// it, never sliding.
    Rode,
    /// Tablecloth: the board came out from under the block, which came to rest behind it.
    Stayed,
    /// Puck: the sliding body came to rest (its contact sticks).
    Stopped,
}

/// An [`Outcome`] without its cause: the one list of outcomes every driver names and numbers
/// (`host-sim`'s summaries and CSV files, the page's codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum OutcomeKind {
    /// See [`Outcome::Balanced`].
    Balanced,
    /// See [`Outcome::Fell`].
    Fell,
    /// See [`Outcome::Held`].
    Held,
    /// See [`Outcome::Slid`].
    Slid,
    /// See [`Outcome::Tipped`].
    Tipped,
    /// See [`Outcome::Rolled`].
    Rolled,
    /// See [`Outcome::Jammed`].
    Jammed,
    /// See [`Outcome::Unfinished`].
    Unfinished,
    /// See [`Outcome::Failed`].
    Failed,
    /// See [`Outcome::Rode`].
    Rode,
    /// See [`Outcome::Stayed`].
    Stayed,
    /// See [`Outcome::Stopped`].
    Stopped,
}

impl OutcomeKind {
    /// Every outcome, in the order of their codes ([`Self::code`]).
    pub const ALL: [Self; 12] = [
        Self::Balanced,
        Self::Fell,
        Self::Held,
        Self::Slid,
        Self::Tipped,
        Self::Rolled,
        Self::Jammed,
        Self::Unfinished,
        Self::Failed,
        Self::Rode,
        Self::Stayed,
        Self::Stopped,
    ];

    /// A short stable name: `Balanced`, `Fell`, `Held`, `Slid`, `Tipped`, `Rolled`, `Jammed`,
    /// `Unfinished`, `Failed`, `Rode`, `Stayed`, `Stopped`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Balanced => "Balanced",
            Self::Fell => "Fell",
            Self::Held => "Held",
            Self::Slid => "Slid",
            Self::Tipped => "Tipped",
            Self::Rolled => "Rolled",
            Self::Jammed => "Jammed",
            Self::Unfinished => "Unfinished",
            Self::Failed => "Failed",
            Self::Rode => "Rode",
            Self::Stayed => "Stayed",
            Self::Stopped => "Stopped",
        }
    }

    /// Its code, the index in [`Self::ALL`].
    #[must_use]
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// The names in the order of their codes.
    #[must_use]
    pub const fn names() -> [&'static str; Self::ALL.len()] {
        let mut out = [""; Self::ALL.len()];
        let mut i = 0;
        while i < Self::ALL.len() {
            out[i] = Self::ALL[i].name();
            i += 1;
        }
        out
    }
}

impl core::fmt::Display for OutcomeKind {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

impl Outcome {
    /// The outcome without its cause.
    #[must_use]
    pub const fn kind(&self) -> OutcomeKind {
        match self {
            Self::Balanced => OutcomeKind::Balanced,
            Self::Fell => OutcomeKind::Fell,
            Self::Held => OutcomeKind::Held,
            Self::Slid => OutcomeKind::Slid,
            Self::Tipped => OutcomeKind::Tipped,
            Self::Rolled => OutcomeKind::Rolled,
            Self::Jammed => OutcomeKind::Jammed,
            Self::Unfinished => OutcomeKind::Unfinished,
            Self::Failed(_) => OutcomeKind::Failed,
            Self::Rode => OutcomeKind::Rode,
            Self::Stayed => OutcomeKind::Stayed,
            Self::Stopped => OutcomeKind::Stopped,
        }
    }

    /// A short stable name ([`OutcomeKind::name`]).
    #[must_use]
    pub const fn name(&self) -> &'static str {
        self.kind().name()
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
