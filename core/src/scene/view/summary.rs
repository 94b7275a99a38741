//! [`RunSummary`]: the counters every engine keeps.

/// A run's counters, as far as every engine keeps them (each engine's own have more:
/// [`crate::planar::RunStats`], [`crate::multibody::Stats`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunSummary {
    /// Steps taken.
    pub steps: u64,
    /// Complementary (Lemke) pivots over the run.
    pub pivots: u64,
    /// The most pivots of one step.
    pub max_pivots: u32,
    /// Steps the warm-start basis answered.
    pub warm_starts: u64,
    /// Steps where a reduced LCP layout's dropped friction direction was needed (0 for an engine
    /// that solves the full form only).
    pub reduced_check_fired: u64,
    /// Solves answered by the solver's regularised retry after a round-off ray
    /// ([`crate::lcp::LcpSolution::regularized`]; 0 for an engine that does not count them).
    pub regularized_solves: u64,
    /// How many solves each path answered.
    pub paths: crate::planar::PathCounts,
    /// Steps the one-answer rule looked at (`docs/formulation.md`, "One answer: the rule").
    pub rule_checked_steps: u64,
    /// Of those, steps whose solutions were enumerated.
    pub rule_enumerated_steps: u64,
    /// Of those, steps whose LCP had solutions that move the bodies differently.
    pub ambiguous_steps: u64,
    /// Of those, steps where the rule's choice moved the bodies differently from the answer the
    /// solver's path reached first.
    pub rule_changed_answer: u64,
    /// Steps whose load the contacts left open, decided by the least 2-norm.
    pub load_decided_steps: u64,
    /// The most contacts one step's LCP held; `None` for an engine whose every step's LCP holds all
    /// its contacts (a scene of one body).
    pub most_lcp_contacts: Option<u8>,
}
