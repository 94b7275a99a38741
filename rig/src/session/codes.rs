//! The core's and the rig's values as the link names them, and back (the presets).

use meterstick_core::ParamError;
use meterstick_core::planar::{ContactMode, Direction, StepError};
use meterstick_core::scene::Outcome;
use meterstick_link::{ErrorCode, Mode, OutcomeCode, ParamId, RejectReason, RigState};

use crate::{RigFault, RigState as CoreState, Unperformable};

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

#[inline]
const fn step_error_code(e: StepError) -> OutcomeCode {
    match e {
        StepError::NonFinite => OutcomeCode::NonFinite,
        StepError::ReducedModelLeftRange => OutcomeCode::ReducedModelLeftRange,
        _ => OutcomeCode::SolverFailed,
    }
}

#[inline]
pub(super) const fn outcome_code(o: Outcome) -> OutcomeCode {
    match o {
        Outcome::Balanced => OutcomeCode::Balanced,
        Outcome::Fell => OutcomeCode::Fell,
        Outcome::Held => OutcomeCode::Held,
        Outcome::Slid => OutcomeCode::Slid,
        Outcome::Tipped => OutcomeCode::Tipped,
        Outcome::Failed(e) => step_error_code(e),
        _ => OutcomeCode::Unfinished,
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
