//! Every outcome of the core crosses the rig's link as itself: the rig's code for it
//! (`meterstick_rig::session::outcome_code`), read back by the host
//! (`meterstick_host_sim::monitor::outcome_of`), is the outcome the core ended in. Until link
//! protocol 5 a cylinder's `Rolled` and Painlevé's `Jammed` arrived as `Unfinished`; the scenes of
//! several bodies' `Rode` and `Stayed` are in version 5 too, the puck's `Stopped` in version 6.

use meterstick_core::StepError;
use meterstick_core::scene::{Outcome, OutcomeKind};
use meterstick_host_sim::monitor::outcome_of;
use meterstick_link::OutcomeCode;
use meterstick_rig::session::outcome_code;

/// An outcome of each kind (the match has no wildcard: a new kind does not compile here until
/// it is listed).
const fn outcome_of_kind(kind: OutcomeKind) -> Outcome {
    match kind {
        OutcomeKind::Balanced => Outcome::Balanced,
        OutcomeKind::Fell => Outcome::Fell,
        OutcomeKind::Held => Outcome::Held,
        OutcomeKind::Slid => Outcome::Slid,
        OutcomeKind::Tipped => Outcome::Tipped,
        OutcomeKind::Rolled => Outcome::Rolled,
        OutcomeKind::Jammed => Outcome::Jammed,
        OutcomeKind::Unfinished => Outcome::Unfinished,
        OutcomeKind::Failed => Outcome::Failed(StepError::NonFinite),
        OutcomeKind::Rode => Outcome::Rode,
        OutcomeKind::Stayed => Outcome::Stayed,
        OutcomeKind::Stopped => Outcome::Stopped,
    }
}

#[test]
fn every_outcome_crosses_the_link_as_itself() {
    for kind in OutcomeKind::ALL {
        let outcome = outcome_of_kind(kind);
        let code = outcome_code(outcome);
        let host = outcome_of(code);
        assert_eq!(
            host.class, kind,
            "{outcome:?} crossed the link as {code:?}, read back as {:?}",
            host.class
        );
    }
}

#[test]
fn distinct_outcomes_get_distinct_codes() {
    let codes: Vec<OutcomeCode> =
        OutcomeKind::ALL.into_iter().map(|k| outcome_code(outcome_of_kind(k))).collect();
    for (i, a) in codes.iter().enumerate() {
        for (j, b) in codes.iter().enumerate().skip(i + 1) {
            assert_ne!(a, b, "{:?} and {:?} share the code {a:?}", OutcomeKind::ALL[i], OutcomeKind::ALL[j]);
        }
    }
}

#[test]
fn failed_steps_keep_their_cause() {
    assert_eq!(outcome_code(Outcome::Failed(StepError::NonFinite)), OutcomeCode::NonFinite);
    assert_eq!(
        outcome_code(Outcome::Failed(StepError::ReducedModelLeftRange)),
        OutcomeCode::ReducedModelLeftRange
    );
    assert_eq!(outcome_code(Outcome::Failed(StepError::TooManyContacts(7))), OutcomeCode::SolverFailed);
    let failed = outcome_of(OutcomeCode::SolverFailed);
    assert_eq!(failed.class, OutcomeKind::Failed);
    assert!(failed.detail.is_some(), "a failed run read back without its cause");
}
