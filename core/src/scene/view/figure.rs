//! [`StepFigure`]: a quantity of the last step that an engine reports beyond the records every
//! engine shares, named by what it is ([`FigureName`]), so that a driver records and prints it
//! without knowing the engine.

use core::fmt;

/// A world axis of the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// World `x`.
    X,
    /// World `y`.
    Y,
}

/// A part of a contact's force.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadPart {
    /// Along the contact's normal.
    Normal,
    /// Along its friction direction `+d`.
    Friction,
}

/// What a [`StepFigure`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum FigureName {
    /// The summed contact force on the upper body of resting pair `pair` over the step, along
    /// world `axis` (N).
    PairForce {
        /// The pair.
        pair: u8,
        /// The axis.
        axis: Axis,
    },
    /// Candidate contact `candidate` of resting pair `pair`: its force over the step along `part`
    /// (N; zero when not in the step's LCP).
    CandidateLoad {
        /// The pair.
        pair: u8,
        /// The candidate, in the pair's candidate order.
        candidate: u8,
        /// Normal or friction.
        part: LoadPart,
    },
}

impl fmt::Display for FigureName {
    /// The figure as a column is named: `pair0_fx`, `pair0_c1_normal`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::PairForce { pair, axis } => {
                write!(f, "pair{pair}_f{}", if axis == Axis::X { "x" } else { "y" })
            }
            Self::CandidateLoad { pair, candidate, part } => {
                let part = if part == LoadPart::Normal { "normal" } else { "friction" };
                write!(f, "pair{pair}_c{candidate}_{part}")
            }
        }
    }
}

/// One figure of the last step (before the first: zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepFigure<T> {
    /// What it is.
    pub name: FigureName,
    /// Its value.
    pub value: T,
}
