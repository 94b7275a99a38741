//! What one step's LCP is made of (`docs/formulation.md`, "One time step"; paper, eqs. 13-18):
//! the step's inputs ([`StepInputs`]) and the terms of its right-hand side.
//!
//! With `c_j` the wrench column of impulse variable `j` (`W_n` of its contact, or `+-W_d` for a
//! friction row along `+-d`) and `v~ = v + h M^-1 w_ext` (eq. 16):
//!
//! ```text
//! b_n = W_n^T v~ - n . u_i + beta(psi_i)        normal rows (eq. 13)
//! b_f = +-(W_d^T v~ - d . u_i)                  friction rows
//! b_sigma = 0
//! ```
//!
//! `beta(psi) = psi / h` for a gap, and for a penetration the push-out speed capped at the speed of
//! a fall through it, `max(psi / h, -sqrt(2 g |psi|))`, the gap first shrunk toward zero by its
//! round-off, `4 eps (|x| + |y| + size)` ([`normal_bias`]; `docs/formulation.md`, "One time
//! step"). Both the factored rows ([`super::FactoredLcp`]) and the dense form
//! ([`super::assemble`]) are built from these.

use super::contact::ContactFrame;
use super::layout::Direction;
use crate::real::Real;

/// What one step's assembly needs besides the layout.
#[derive(Debug, Clone, Copy)]
pub struct StepInputs<'a, T, const K: usize> {
    /// Each contact's frame at the step's start.
    pub frames: &'a [ContactFrame<T>; K],
    /// Each contact's friction coefficient for this step.
    pub mu: [T; K],
    /// Each support's velocity over the step (world).
    pub support_velocity: [[T; 2]; K],
    /// `v~ = v + h M^-1 w_ext`.
    pub v_free: [T; 3],
    /// `diag(M^-1)` times the body's mass, `(1, 1, m / J)`: the impulses `z` then come out per unit
    /// mass and every row of the LCP is a velocity ([`super::Body::inverse_mass_per_unit_mass`]).
    pub m_inv: [T; 3],
    /// Step `h`.
    pub h: T,
    /// Gravity `g` (for the penetration-recovery cap).
    pub gravity: T,
    /// A gap with at most this magnitude counts as zero: the round-off of the positions it is
    /// computed from ([`normal_bias`]).
    pub gap_round_off: T,
}

/// The normal row's stabilisation term `beta(psi)`: `psi / h` for a gap, the push-out speed capped
/// at `sqrt(2 g |psi|)` for a penetration, after the gap is shrunk toward zero by its round-off:
/// `psi' = sign(psi) max(|psi| - round_off, 0)`.
///
/// **Round-off is not a gap.** A gap is a difference of positions of order `|x| + |y| + size`,
/// computed with a few roundings: its error is a few `eps` of that. Divided by `h` it becomes a
/// velocity: in f32, one ulp of a 0.5 m coordinate over h = 1e-4 s is 6e-4 m/s, more than a
/// ladder's fall in its first steps (the contact would alternate between touching and apart), and
/// at h = 1 ms 3e-5 m/s, three times a 1e-5 m/s stick threshold. Within `round_off` (the stepper passes `4 eps (|x| + |y| + size)`: 0.8 um in f32 for a
/// 1 m rod, 1e-15 m in f64) the contact counts as exactly touching; beyond it the gap counts less
/// that much, so the term is continuous (a cut-off would turn the drift that reaches its edge into a
/// jump of `round_off / h`).
#[must_use]
pub fn normal_bias<T: Real>(gap: T, h: T, gravity: T, round_off: T) -> T {
    let excess = gap.abs_exact() - round_off;
    if excess <= T::zero() {
        return T::zero();
    }
    if gap > T::zero() {
        return excess / h;
    }
    let one_step = -excess / h;
    let cap = -(T::of(2.0) * gravity * excess).sqrt_rounded();
    if one_step > cap { one_step } else { cap }
}

#[inline]
pub(crate) fn dot3<T: Real>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn dot2<T: Real>(a: &[T; 2], b: &[T; 2]) -> T {
    a[0] * b[0] + a[1] * b[1]
}

/// `+1` or `-1`.
#[inline]
pub(crate) fn sign<T: Real>(direction: Direction) -> T {
    match direction {
        Direction::Plus => T::one(),
        Direction::Minus => -T::one(),
    }
}
