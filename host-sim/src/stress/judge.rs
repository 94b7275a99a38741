//! The pass criteria of `host-sim stress`, applied to one run's [`Metrics`].
//!
//! A case passes when every implementation passes all of:
//! 1. no panic;
//! 2. a physical outcome: no non-finite state, no solver error (valid parameters must be
//!    simulable);
//! 3. every LCP verified: residual over tolerance `<= 1` (guaranteed by the core, checked here);
//! 4. penetration `<=` [`super::metrics::penetration_bound`]: the start's plus the second-order
//!    terms of one step, plus round-off;
//! 5. no energy from nowhere: over the whole run `E(t) - E(0) - W_supports(0, t)` stays below
//!    `m g pen_0` (what a start penetration owes: the body may climb back to where it should
//!    rest, not higher) plus [`super::metrics::energy_tolerance`];
//! 6. the case's physics claim where physics decides one: the outcome class (by similarity, mass
//!    scaling, statics or a clear quasi-static argument), "not dragged" (frictionless or
//!    `mu_k = 0`: while finger 1 is left of the centre of mass the rod does not move along `x`),
//!    or "still" (zero speed or gravity, a block or a ladder held by friction: the body does not
//!    move beyond [`super::metrics::STILL_TOLERANCE`] `eps size`; several bodies: none moves), or
//!    block-on-block's accelerations in full contact the laws' ([`super::bodies`]).

use super::cases::{Case, Claim};
use super::metrics::{Metrics, STILL_TOLERANCE};
use crate::trajectory::OutcomeKind;

/// A criterion a run can fail.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Failure {
    /// It panicked.
    Panic,
    /// It ended on a solver error or a non-finite state.
    NoPhysicalOutcome,
    /// A residual above its tolerance.
    LcpResidual,
    /// A penetration above its bound.
    Penetration,
    /// Energy gained beyond the allowance.
    EnergyGain,
    /// Not the outcome physics decides.
    Outcome,
    /// The rod moved although nothing could drag it.
    Dragged,
    /// The body moved although it should be still.
    Moved,
    /// A measured acceleration is not the law's.
    Acceleration,
}

impl Failure {
    /// A short name.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Panic => "panic",
            Self::NoPhysicalOutcome => "no physical outcome",
            Self::LcpResidual => "LCP residual",
            Self::Penetration => "penetration",
            Self::EnergyGain => "energy gain",
            Self::Outcome => "outcome",
            Self::Dragged => "rod dragged",
            Self::Moved => "body moved",
            Self::Acceleration => "law's acceleration",
        }
    }
}

/// The verdict of one run against the pass criteria.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verdict {
    /// The criteria that failed (empty: passed).
    pub failures: Vec<Failure>,
}

impl Verdict {
    /// `true` when every criterion passed.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }

    /// The failures' names, joined.
    #[must_use]
    pub fn describe(&self) -> String {
        self.failures.iter().map(|f| f.name()).collect::<Vec<_>>().join(", ")
    }
}

/// Applies the pass criteria to one run of `case`.
#[must_use]
pub fn judge(case: &Case, m: &Metrics) -> Verdict {
    let mut failures = Vec::new();
    match m.class() {
        None => failures.push(Failure::Panic),
        Some(OutcomeKind::Failed) => failures.push(Failure::NoPhysicalOutcome),
        Some(_) => {}
    }
    if m.residual_ratio > 1.0 {
        failures.push(Failure::LcpResidual);
    }
    if m.penetration_ratio > 1.0 {
        failures.push(Failure::Penetration);
    }
    if m.energy_ratio > 1.0 {
        failures.push(Failure::EnergyGain);
    }
    if let Some(expected) = case.outcome
        && m.class() != Some(expected)
    {
        failures.push(Failure::Outcome);
    }
    let still = STILL_TOLERANCE * m.eps * m.still_scale;
    // A NaN (a claim that could not be measured) is not within any bound: it fails.
    let within = |x: f64, bound: f64| x.is_finite() && x <= bound;
    let failed = match case.claim {
        Claim::None => None,
        Claim::NotDragged => (!within(m.claim_motion, still)).then_some(Failure::Dragged),
        Claim::BodyStill => (!within(m.claim_motion, still)).then_some(Failure::Moved),
        Claim::LawAccelerations => (!within(m.claim_motion, 1.0)).then_some(Failure::Acceleration),
    };
    failures.extend(failed);
    Verdict { failures }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::stress::cases::cases;
    use crate::trajectory::RunOutcome;

    fn passing() -> Metrics {
        Metrics {
            outcome: Some(RunOutcome::of(OutcomeKind::Balanced)),
            steps: 10,
            eps: f64::from(f32::EPSILON),
            still_scale: 1.0,
            ..Metrics::default()
        }
    }

    type Breaker = fn(&mut Metrics);

    /// Each criterion can fail, alone.
    #[test]
    fn every_criterion_can_fail() {
        let mut c = cases(true).into_iter().find(|c| c.name == "v=0.1").unwrap();
        c.outcome = Some(OutcomeKind::Balanced);
        c.claim = Claim::NotDragged;
        assert!(judge(&c, &passing()).passed());
        let failing: [(Failure, Breaker); 8] = [
            (Failure::Panic, |m| m.outcome = None),
            (Failure::NoPhysicalOutcome, |m| {
                m.outcome = Some(RunOutcome { class: OutcomeKind::Failed, detail: Some("ray".into()) });
            }),
            (Failure::LcpResidual, |m| m.residual_ratio = 1.5),
            (Failure::Penetration, |m| m.penetration_ratio = 1.01),
            (Failure::EnergyGain, |m| m.energy_ratio = 2.0),
            (Failure::Outcome, |m| m.outcome = Some(RunOutcome::of(OutcomeKind::Fell))),
            (Failure::Dragged, |m| m.claim_motion = 1e-4),
            (Failure::Panic, |m| m.outcome = None),
        ];
        for (what, break_it) in failing {
            let mut m = passing();
            break_it(&mut m);
            let v = judge(&c, &m);
            assert!(v.failures.contains(&what), "{what:?}: {v:?}");
        }
        c.claim = Claim::BodyStill;
        let mut m = passing();
        m.claim_motion = 1e-4;
        assert!(judge(&c, &m).failures.contains(&Failure::Moved));
        c.claim = Claim::LawAccelerations;
        for off in [1.5, f64::NAN] {
            m.claim_motion = off;
            assert!(judge(&c, &m).failures.contains(&Failure::Acceleration), "{off}");
        }
        m.claim_motion = 0.5;
        assert!(judge(&c, &m).passed());
    }
}
