//! [`StepStats`]: what the last step's solve took, as far as every engine reports it.

/// The last step's solve: its pivots and, where the engine reports one, the verification residual
/// of the answer it used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StepStats<T> {
    /// Complementary (Lemke) pivots of the step's solve(s).
    pub pivots: u32,
    /// The normalised verification residual of the answer used ([`crate::lcp::verify`]); `None`
    /// for an engine that reports none (a scene of several bodies verifies every answer itself
    /// and ends the run with `Failed` when it cannot).
    pub residual: Option<T>,
}
