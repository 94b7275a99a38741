//! What a step and a run report: each contact's impulses and mode ([`ContactReport`]), the step's
//! state, solve path and precision flag ([`StepReport`]), and the counters over a run
//! ([`RunStats`]). Impulses are physical (N s): the LCP's `z` per unit mass times the body's mass
//! (`docs/formulation.md`, "Friction and contact modes", "Precision").

use super::body::BodyState;
use super::contact::ContactMode;
use super::strategy::SolvePath;
use crate::real::Real;

/// One contact's part of a [`StepReport`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactReport<T> {
    /// Mode after the step.
    pub mode: ContactMode,
    /// Mode before it (after the previous step; before the first, the initial mode).
    pub previous_mode: ContactMode,
    /// Normal impulse on the body (N s).
    pub normal_impulse: T,
    /// Net friction impulse on the body along the contact's `+d` (N s).
    pub friction_impulse: T,
    /// The contact's coordinate along its tangent at the step's start ([`super::ContactFrame::along`]).
    pub along: T,
}

impl<T> ContactReport<T> {
    /// `true` when the contact's mode changed in this step: a switch event.
    #[must_use]
    pub fn switched(&self) -> bool {
        self.mode != self.previous_mode
    }
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport<T, const K: usize> {
    /// Time at the end of the step (s).
    pub time: T,
    /// State at the end of the step.
    pub state: BodyState<T>,
    /// Each contact.
    pub contacts: [ContactReport<T>; K],
    /// Complementary pivots of the step's solve(s).
    pub pivots: u32,
    /// `true` when the warm-start basis gave the answer.
    pub warm_start_used: bool,
    /// Which path answered the step's LCP (the full layout's, when it was used).
    pub path: SolvePath,
    /// Reduced layout only: a dropped direction was needed (or the reduced LCP had no solution),
    /// so the step was solved in the full layout (the reported values are the full layout's).
    pub full_layout_used: bool,
    /// The normalised verification residual of the solution used ([`crate::lcp::verify`]).
    pub residual: T,
    /// The step's impulses are resolved only to `eps V / (g h)` of their size, more than
    /// [`ROUND_OFF_LIMIT`], where `V` is the step's velocity scale (the fastest support's speed
    /// plus the body's): the LCP holds both slips of order `V` and impulses of order `g h`, and
    /// its solve is exact only to round-off of the larger. In f32 that is `V > 0.082 m/s x (h /
    /// 1e-5 s)`: fingers from about 0.1 m/s at h = 1e-5 s, 1 m/s at 1e-4 s, 10 m/s at 1e-3 s
    /// (`docs/formulation.md`, "Precision", has the measured deviations). Take a larger `h` or
    /// f64.
    pub round_off_limited: bool,
}

/// The largest `eps V / (g h)` a step may have before [`StepReport::round_off_limited`] says
/// so: 1e-4 (in f32, `V / (g h)` of 840). Chosen so that every cell of `host-sim envelope`'s
/// table where f32 misses its target is flagged: the least of them, 0.1 m/s at h = 1e-5 s
/// (1.2e-4 .. 2.4e-4), held its COM within 6e-6 m of f64 but switched 11 steps late; 0.2 m/s
/// at 1e-5 s drifted 2.9e-4 m, 1 m/s 3e-5 m. Beyond the limit f32 may still hold (1 and
/// 10 m/s at 1e-4 s held within 1.6e-6 m): the flag says it is no longer assured.
pub const ROUND_OFF_LIMIT: f64 = 1e-4;

/// The largest `mu eps` a friction coefficient may have in a precision before
/// [`friction_beyond_precision`] says so: `2^-9`. A contact that sticks under friction impulses up
/// to `mu` times its normal one holds them against another contact's (the meter stick's two
/// fingers, whatever moves the body), and what is left, the net impulse (the weight's `g h` per
/// unit mass), is resolved only to `mu eps` of itself. With the cone rows weighted
/// (`docs/formulation.md`, "Precision") f32 reaches f64's outcome on the meter stick (both
/// layouts, h = 1 ms) at every `mu` measured up to `3.2e4`, but at `32,768` (`mu eps = 2^-8`) and
/// `5e4` the 8x8 falls; at `1e5` it balances with eq. 21's ratios 1.3 % off (f64: 0.4 %), at `1e6`
/// 18 %. So the limit is half the first failure: `mu = 2^14 = 16,384` in f32, `2^43 = 8.8e12` in
/// f64.
pub const FRICTION_ROUND_OFF_LIMIT: f64 = 1.0 / 512.0;

/// `true` when the friction coefficient `mu` is beyond what precision `T` resolves:
/// `mu eps > FRICTION_ROUND_OFF_LIMIT` ([`FRICTION_ROUND_OFF_LIMIT`]). For drivers, before a run
/// (the step does not check it).
#[must_use]
pub fn friction_beyond_precision<T: Real>(mu: f64) -> bool {
    mu * T::EPS.as_f64() > FRICTION_ROUND_OFF_LIMIT
}

/// The largest friction coefficient precision `T` resolves ([`friction_beyond_precision`]):
/// `FRICTION_ROUND_OFF_LIMIT / eps`.
#[must_use]
pub fn friction_limit<T: Real>() -> f64 {
    FRICTION_ROUND_OFF_LIMIT / T::EPS.as_f64()
}

impl<T: Real, const K: usize> StepReport<T, K> {
    /// Each contact's mode after the step.
    #[must_use]
    pub fn modes(&self) -> [ContactMode; K] {
        let mut modes = [ContactMode::Separated; K];
        for (m, c) in modes.iter_mut().zip(&self.contacts) {
            *m = c.mode;
        }
        modes
    }

    /// Each contact's coordinate along it at the step's start.
    #[must_use]
    pub fn along(&self) -> [T; K] {
        let mut along = [T::zero(); K];
        for (a, c) in along.iter_mut().zip(&self.contacts) {
            *a = c.along;
        }
        along
    }

    /// The contacts whose mode changed in this step, with their new mode.
    pub fn switches(&self) -> impl Iterator<Item = (usize, ContactMode)> + '_ {
        self.contacts.iter().enumerate().filter(|(_, c)| c.switched()).map(|(i, c)| (i, c.mode))
    }
}
