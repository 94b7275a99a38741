//! [`StepError`]: why a step of any engine failed. One list of causes, which every engine's
//! stepper returns and [`crate::scene::Outcome::Failed`] carries.

use crate::lcp::LcpError;

/// Why a step failed. The state is that before the step: a failed step changes nothing.
///
/// Each engine returns the causes it can meet: one body against supports
/// ([`crate::planar::Stepper`]) all but [`Self::TooManyContacts`] and the cone's; several bodies
/// ([`crate::multibody::SystemStepper`]) [`Self::Solver`], [`Self::NonFinite`] and
/// [`Self::TooManyContacts`]; three dimensions (`crate::spatial::SpatialStepper`, feature `spatial`)
/// [`Self::Solver`], [`Self::NonFinite`] and the cone's two.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum StepError {
    /// The step's LCP had no verified answer.
    Solver(LcpError),
    /// The state after the step would not be finite.
    NonFinite,
    /// A reduced layout's dropped direction was needed and the `fallback` feature is off.
    ReducedModelLeftRange,
    /// A support cannot carry its contact's feature (the contact's index).
    SupportMismatch(u8),
    /// A line's normal is not a unit vector (`crate::planar::Support::is_well_formed`; the
    /// contact's index). A support whose position or velocity is not finite fails the step with
    /// [`LcpError::NonFiniteInput`].
    MalformedSupport(u8),
    /// More candidate contacts are active than the step's LCP holds (the count).
    TooManyContacts(u8),
    /// Three dimensions: the friction direction and the slip did not agree within
    /// `crate::spatial::MAX_DIRECTIONS` tries.
    #[cfg(feature = "spatial")]
    ConeNotConverged,
    /// Three dimensions: the answer broke the circular cone's conditions beyond round-off (the
    /// residual, as `crate::spatial::SpatialContactReport::cone_residual`).
    #[cfg(feature = "spatial")]
    ConeUnverified {
        /// The residual.
        residual: f32,
    },
}

impl core::fmt::Display for StepError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Solver(e) => write!(f, "solver: {e}"),
            Self::NonFinite => f.write_str("the state became non-finite"),
            Self::ReducedModelLeftRange => {
                f.write_str("the reduced friction model left its range (no fallback compiled in)")
            }
            Self::SupportMismatch(i) => write!(f, "the support of contact {i} cannot carry its feature"),
            Self::MalformedSupport(i) => {
                write!(f, "the line supporting contact {i} has a normal that is not a unit vector")
            }
            Self::TooManyContacts(k) => write!(f, "{k} contacts are active, more than the LCP holds"),
            #[cfg(feature = "spatial")]
            Self::ConeNotConverged => write!(
                f,
                "the friction direction did not meet the slip in {} tries",
                crate::spatial::MAX_DIRECTIONS
            ),
            #[cfg(feature = "spatial")]
            Self::ConeUnverified { residual } => {
                write!(f, "the answer is outside Coulomb's circular cone by {residual:e} of mu p_n")
            }
        }
    }
}

impl core::error::Error for StepError {}
