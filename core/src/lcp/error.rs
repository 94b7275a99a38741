//! [`LcpError`]: every way a solve can fail, by name.

/// Why the solver returned no solution. Each variant carries the pivots spent.
///
/// The residual and tolerance of [`LcpError::Unverified`] are kept as `f32` whatever the
/// scalar of the solve: they are diagnostics, and this keeps the type small and `Copy`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum LcpError {
    /// `M` or `q` holds a NaN or an infinity; nothing was attempted.
    NonFiniteInput,
    /// Ray termination: the entering column had no positive entry, so Lemke's method
    /// found no solution. For copositive-plus `M` (PSD included) this proves the LCP
    /// infeasible; for other matrices it means Lemke could not process it.
    Ray {
        /// Pivots performed before the ray was found.
        pivots: u32,
    },
    /// The pivot cap was reached before termination.
    MaxPivots {
        /// Pivots performed (the cap).
        pivots: u32,
    },
    /// The pivoting terminated but the candidate failed verification against the
    /// original `(M, q)` (round-off beyond tolerance).
    Unverified {
        /// Normalised residual of the candidate (see [`crate::lcp::verify`]).
        residual: f32,
        /// Tolerance it was held to.
        tolerance: f32,
        /// Pivots performed.
        pivots: u32,
    },
}

impl LcpError {
    /// A short stable name: `"non_finite"`, `"ray"`, `"max_pivots"`, `"unverified"`.
    #[must_use]
    pub const fn kind(&self) -> &'static str {
        match self {
            Self::NonFiniteInput => "non_finite",
            Self::Ray { .. } => "ray",
            Self::MaxPivots { .. } => "max_pivots",
            Self::Unverified { .. } => "unverified",
        }
    }

    /// Pivots spent before the failure.
    #[must_use]
    pub const fn pivots(&self) -> u32 {
        match *self {
            Self::NonFiniteInput => 0,
            Self::Ray { pivots } | Self::MaxPivots { pivots } | Self::Unverified { pivots, .. } => pivots,
        }
    }
}

impl core::fmt::Display for LcpError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::NonFiniteInput => f.write_str("LCP data holds a non-finite number"),
            Self::Ray { pivots } => write!(f, "Lemke ray termination after {pivots} pivots"),
            Self::MaxPivots { pivots } => write!(f, "Lemke pivot cap reached ({pivots} pivots)"),
            Self::Unverified { residual, tolerance, pivots } => write!(
                f,
                "Lemke result failed verification after {pivots} pivots: residual {residual:e} > tolerance {tolerance:e}"
            ),
        }
    }
}

impl core::error::Error for LcpError {}
