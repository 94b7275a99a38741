//! [`RunStats`]: the counters of a run, the same in every engine.

use crate::planar::PathCounts;

/// Counters over a run, kept by every engine's stepper ([`crate::planar::Stepper::stats`],
/// [`crate::multibody::SystemStepper::stats`]) and shown by every scene's view
/// ([`crate::scene::SceneView::summary`]). A counter an engine has no use for stays 0 (or `None`);
/// each field says which.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RunStats {
    /// Steps taken.
    pub steps: u64,
    /// Complementary (Lemke) pivots, summed.
    pub pivots: u64,
    /// Most pivots in one step.
    pub max_pivots: u32,
    /// Steps whose answer came from the warm-start basis ([`crate::planar::SolvePath::Warm`]).
    pub warm_starts: u64,
    /// Steps where a reduced layout's dropped direction was needed (one body against supports;
    /// 0 for an engine that solves the full form only).
    pub reduced_check_fired: u64,
    /// Solves answered by the solver's regularised retry after a round-off ray
    /// ([`crate::lcp::LcpSolution::regularized`]; one body against supports, 0 elsewhere).
    pub regularized_solves: u64,
    /// Steps whose impulses were resolved only to more than [`crate::planar::ROUND_OFF_LIMIT`]
    /// of their size ([`crate::planar::StepReport::round_off_limited`]; one body against
    /// supports, 0 elsewhere).
    pub round_off_limited: u64,
    /// Solves per path.
    pub paths: PathCounts,
    /// Steps the rule looked at (`docs/formulation.md`, "One answer: the rule"): not at rest and
    /// flagged as possibly having several answers that move the bodies differently.
    pub rule_checked_steps: u64,
    /// Of those, steps whose solutions were enumerated (one body) or searched by the descent of
    /// `docs/formulation.md`, "Several bodies: the rule" (an answer of zero kinetic energy is the
    /// rule's choice as it is).
    pub rule_enumerated_steps: u64,
    /// Of those, steps whose LCP had solutions that move the bodies differently.
    pub ambiguous_steps: u64,
    /// Of those, steps where the rule's choice moves the bodies differently from the answer the
    /// solver's path reached first.
    pub rule_changed_answer: u64,
    /// Steps whose load the contacts left open, decided by the least 2-norm
    /// (`docs/formulation.md`, "The load: the least norm").
    pub load_decided_steps: u64,
    /// The most candidate contacts one step's LCP held (several bodies); `None` for an engine
    /// whose every step's LCP holds all its contacts (one body against supports).
    pub most_lcp_contacts: Option<u8>,
}

impl RunStats {
    /// Counts a step the rule looked at, and what it found.
    #[inline]
    pub(crate) fn count_rule(&mut self, rule: crate::rule::Resolution) {
        self.rule_checked_steps += 1;
        self.rule_enumerated_steps += u64::from(rule.enumerated);
        self.ambiguous_steps += u64::from(rule.ambiguous);
        self.rule_changed_answer += u64::from(rule.changed);
    }

    /// Counts a step's pivots.
    #[inline]
    pub(crate) fn count_pivots(&mut self, pivots: u32) {
        self.pivots += u64::from(pivots);
        self.max_pivots = self.max_pivots.max(pivots);
    }
}
