//! The core's and the rig's values as the link names them, and back (the presets).

use meterstick_core::ParamError;
use meterstick_core::StepError;
use meterstick_core::planar::{ContactMode, Direction};
use meterstick_core::scene::{Outcome, OutcomeKind};
use meterstick_link::{ErrorCode, Mode, OutcomeCode, ParamId, RejectReason, RigState};

use crate::{InterfaceMode, RigFault, RigState as CoreState, Unperformable};

#[inline]
pub(super) const fn state_of(s: CoreState) -> RigState {
    match s {
        CoreState::WaitingForStart => RigState::Waiting,
        CoreState::Running => RigState::Running,
        CoreState::Finished(_) => RigState::Finished,
        CoreState::Fault(_) => RigState::Fault,
    }
}

#[inline]
pub(super) const fn mode_of(m: ContactMode) -> Mode {
    match m {
        ContactMode::Separated => Mode::Separated,
        ContactMode::Sticking => Mode::Sticking,
        ContactMode::Sliding(Direction::Plus) => Mode::SlidingPositive,
        ContactMode::Sliding(Direction::Minus) => Mode::SlidingNegative,
    }
}

/// An interface's mode as the link names it (the lights' [`InterfaceMode`]).
#[inline]
pub(super) const fn interface_mode_of(m: InterfaceMode) -> Mode {
    match m {
        InterfaceMode::Sticking => Mode::Sticking,
        InterfaceMode::Sliding(d) => mode_of(ContactMode::Sliding(d)),
        InterfaceMode::Tipping => Mode::Tipping,
        InterfaceMode::Separated => Mode::Separated,
    }
}

#[inline]
const fn step_error_code(e: StepError) -> OutcomeCode {
    match e {
        StepError::NonFinite => OutcomeCode::NonFinite,
        StepError::ReducedModelLeftRange => OutcomeCode::ReducedModelLeftRange,
        _ => OutcomeCode::SolverFailed,
    }
}

/// The link's code for a run that ended in `o`: every outcome as itself, a failed step by its
/// cause. The match is over [`OutcomeKind`], which has no hidden variants, so an outcome added
/// to the core does not compile here until the link names it.
#[inline]
#[must_use]
pub const fn outcome_code(o: Outcome) -> OutcomeCode {
    if let Outcome::Failed(e) = o {
        return step_error_code(e);
    }
    match o.kind() {
        OutcomeKind::Balanced => OutcomeCode::Balanced,
        OutcomeKind::Fell => OutcomeCode::Fell,
        OutcomeKind::Held => OutcomeCode::Held,
        OutcomeKind::Slid => OutcomeCode::Slid,
        OutcomeKind::Tipped => OutcomeCode::Tipped,
        OutcomeKind::Rolled => OutcomeCode::Rolled,
        OutcomeKind::Jammed => OutcomeCode::Jammed,
        OutcomeKind::Unfinished => OutcomeCode::Unfinished,
        OutcomeKind::Rode => OutcomeCode::Rode,
        OutcomeKind::Stayed => OutcomeCode::Stayed,
        OutcomeKind::Stopped => OutcomeCode::Stopped,
        // `Outcome::Failed` returned above.
        OutcomeKind::Failed => OutcomeCode::SolverFailed,
    }
}

#[inline]
pub(super) const fn fault_code(f: RigFault) -> OutcomeCode {
    match f {
        RigFault::Step(e) => step_error_code(e),
        RigFault::NonFinite => OutcomeCode::NonFinite,
        RigFault::ActuatorOverrun => OutcomeCode::ActuatorOverrun,
    }
}

#[inline]
pub(super) const fn reason_of(e: ParamError) -> RejectReason {
    match e {
        ParamError::NonFinite(_) => RejectReason::NotFinite,
        ParamError::NotPositive(_) => RejectReason::NotPositive,
        ParamError::Negative(_) => RejectReason::Negative,
        ParamError::KineticAboveStatic => RejectReason::KineticAboveStatic,
        ParamError::FingerOutsideRod => RejectReason::FingerOutsideRod,
        ParamError::FingersCrossed => RejectReason::FingersCrossed,
        ParamError::OutOfRange(_) => RejectReason::OutOfRange,
        ParamError::InertiaOutOfRange { .. } => RejectReason::InertiaOutOfRange,
        _ => RejectReason::Other,
    }
}

/// The error reported when a run ends in the fault `f` (before its outcome).
#[inline]
pub(super) const fn fault_error(f: RigFault) -> ErrorCode {
    match f {
        RigFault::ActuatorOverrun => ErrorCode::ActuatorOverrun,
        RigFault::Step(_) | RigFault::NonFinite => ErrorCode::CoreFault,
    }
}

/// The parameter a preset the rig cannot perform is refused for.
#[inline]
pub(super) const fn param_of(u: Unperformable) -> ParamId {
    match u {
        Unperformable::Step => ParamId::Step,
        Unperformable::Finger1TooFast | Unperformable::Finger1Backward => ParamId::Finger1Velocity,
        Unperformable::Finger2Moves => ParamId::Finger2Velocity,
    }
}
