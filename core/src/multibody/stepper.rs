//! [`Stepper`]: `B` boxes on each other and on a table, one LCP per step, solved in the bodies'
//! coordinates when a basis near the last one answers and by Lemke's method otherwise
//! (`docs/formulation.md`, "Several bodies", "One step", "Solving a multibody step (the core)").

use super::factored::{Answer, ContactBlocks, Factored, MOST_SLOTS};
use super::geometry::{CornerFrame, Pair, Shape, Table, pair_frames, poses, rim_frames, slip};
use super::resolve::{self, Detector};
use super::slots::{PATTERNS, Pattern, TOUCH, pattern_bits, slot_pattern, slot_rows, with_pattern};
use crate::lcp::{Basis, Lcp, LcpError, LcpSolution, Lemke, verify};
#[cfg(feature = "fallback")]
use crate::load::{Carry, LoadContact, LoadPath, least_norm};
use crate::params::{Check, ParamError, check_fields};
use crate::planar::assemble::normal_bias;
use crate::planar::check_friction;
use crate::planar::{Body, BodyState, Checksum, ContactMode, Declined, PathCounts, SolvePath};
use crate::real::Real;
#[cfg(feature = "fallback")]
use crate::real::max;
use crate::rule::Resolution;

/// The scalars of a step: one body's ([`crate::planar::Settings`]: time step, gravity, stick
/// threshold) and the activity rule's margin.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Settings<T> {
    /// Time step `h` (s), gravity `g` (m/s^2, along world `-y`), and the slip (m/s) at or below
    /// which a contact sticks.
    pub base: crate::planar::Settings<T>,
    /// The activity rule's `margin` (m): a corner further than this (plus what the approach speed
    /// closes within the step) from a face is not a contact.
    pub margin: T,
}

/// The bodies, the table, the `P` resting pairs and the external forces of a system of `B` bodies
/// (boxes, or discs resting by their rims).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct System<T, const B: usize, const P: usize> {
    /// The bodies, in body order (body 0's mass is the reference mass of the LCP).
    pub bodies: [Body<T>; B],
    /// The fixed table.
    pub table: Table<T>,
    /// Which body rests on which, each with its friction coefficients.
    pub pairs: [Pair<T>; P],
    /// The external force on each body at its centre of mass (N, world), besides its weight.
    pub forces: [[T; 2]; B],
    /// The step's scalars.
    pub settings: Settings<T>,
}

impl<T, const B: usize, const P: usize> System<T, B, P> {
    /// Each body's shape: a disc when a pair says its upper body is one
    /// ([`Pair::upper_shape`]), else a box ([`Stepper::new`] refuses pairs that disagree).
    #[must_use]
    pub fn shapes(&self) -> [Shape; B] {
        let mut shapes = [Shape::Box; B];
        for pair in &self.pairs {
            if let (Shape::Disc, Some(shape)) = (pair.upper_shape, shapes.get_mut(usize::from(pair.upper))) {
                *shape = Shape::Disc;
            }
        }
        shapes
    }
}

/// Why a step failed. The state is then that before the step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum StepError {
    /// The step's LCP could not be solved (or its answer not verified).
    Solver(LcpError),
    /// The state after the step would not be finite.
    NonFinite,
    /// More candidates are active than the LCP's capacity `N / 4` holds (the count).
    TooManyContacts(u8),
}

impl core::fmt::Display for StepError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Solver(e) => write!(f, "solver: {e}"),
            Self::NonFinite => f.write_str("the state became non-finite"),
            Self::TooManyContacts(k) => write!(f, "{k} contacts are active, more than the LCP holds"),
        }
    }
}

impl core::error::Error for StepError {}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use]
pub struct StepReport<T, const B: usize, const P: usize> {
    /// Time at the step's end (s).
    pub time: T,
    /// Each body's state after the step.
    pub states: [BodyState<T>; B],
    /// Each pair's summed contact force on its upper body over the step (N, world):
    /// `(1/h) sum +-(p_n n + p_f d)`.
    pub interface_forces: [[T; 2]; P],
    /// Each candidate's normal and friction force over the step (N, along its normal and its
    /// `+d`; zero when not active): where the contacts leave the split open, the least-norm load
    /// (`docs/formulation.md`, "The load: the least norm").
    pub corner_loads: [[[T; 2]; 4]; P],
    /// Each candidate's mode after the step.
    pub modes: [[ContactMode; 4]; P],
    /// Active candidates this step (the LCP has `4` rows for each).
    pub active: u8,
    /// Lemke pivots spent (0 when a basis solved in the bodies' coordinates answered).
    pub pivots: u32,
}

impl<T, const B: usize, const P: usize> StepReport<T, B, P> {
    /// `true` when a contact of pair `p` was sliding after the step.
    #[must_use]
    pub fn pair_slid(&self, p: usize) -> bool {
        self.modes.get(p).is_some_and(|m| m.iter().any(|m| m.is_sliding()))
    }

    /// `true` when every listed `(pair, candidate)` touches (is not separated) after the step.
    #[must_use]
    pub fn touching(&self, contacts: &[(usize, usize)]) -> bool {
        contacts.iter().all(|&(p, c)| {
            self.modes.get(p).and_then(|m| m.get(c)).is_some_and(|m| *m != ContactMode::Separated)
        })
    }
}

impl<T: Real, const B: usize, const P: usize> StepReport<T, B, P> {
    /// Adds every body's state after the step, in body order, to a trajectory checksum: over a
    /// run, the fingerprint the firmware prints and the host compares bit for bit.
    pub fn add_to(&self, checksum: &mut Checksum) {
        for state in &self.states {
            checksum.add(state);
        }
    }
}

/// Counters of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Stats {
    /// Steps taken.
    pub steps: u32,
    /// Steps the warm basis answered ([`SolvePath::Warm`]).
    pub warm_direct: u32,
    /// Lemke pivots over the run.
    pub pivots: u64,
    /// The most pivots of one step.
    pub max_pivots: u32,
    /// The most active candidates of one step.
    pub max_active: u8,
    /// How many steps each path answered (`docs/formulation.md`, "Solving a multibody step").
    pub paths: PathCounts,
    /// Steps the rule looked at (`docs/formulation.md`, "One answer: the rule"): not at rest and
    /// flagged as possibly having several answers that move the bodies differently.
    pub rule_checked_steps: u64,
    /// Of those, steps whose solutions were searched (at most four active contacts: the descent
    /// of `docs/formulation.md`, "Several bodies: the rule").
    pub rule_enumerated_steps: u64,
    /// Of those, steps whose LCP had solutions that move the bodies differently.
    pub ambiguous_steps: u64,
    /// Of those, steps where the rule's choice moves the bodies differently from the answer the
    /// solver's path reached first.
    pub rule_changed_answer: u64,
    /// Steps whose load the contacts left open, decided by the least 2-norm
    /// (`docs/formulation.md`, "The load: the least norm").
    pub load_decided_steps: u64,
}

/// Steps a [`System`] of `B` bodies and `P` pairs (`4 P` candidate contacts) with an LCP of
/// capacity `N` rows (at most `N / 4` active contacts; `N <= 32`, Lemke's limit).
///
/// **Layout.** The `k` active candidates fill the leading `4 k` rows in candidate order, as
/// `docs/formulation.md` ("One step") writes the LCP: `(p_n[1..k], p_+d[1], p_-d[1], ...,
/// sigma[1..k])`; rows `4 k .. N` are trivially decoupled (the identity, `q = 1`: their `z` is 0
/// and no pivot touches them). So a step's LCP is the model's, whatever `N`.
///
/// **Indeterminacy.** Two sticking corners of one box on another leave the split of the load
/// between them undetermined: the impulse block `J M~ J^T` is singular and the LCP has a set of
/// solutions. A singular basis (both corners sticking) is declined by the factored solve; the
/// regular one in which one corner carries the interface's friction and the other only its
/// normal is what the first step's guess, the candidates and Lemke's method (with its
/// lexicographic rule, `core/src/lcp/lemke.rs`) leave, and the warm path keeps it (it is the
/// next step's warm basis). What is reported is the load of least 2-norm with the step's motion
/// (`docs/formulation.md`, "The load: the least norm"; each corner's share in
/// [`StepReport::corner_loads`], their sum per pair in [`StepReport::interface_forces`]). Where
/// solutions move the bodies differently (the model's "ambiguous" steps), this stepper takes the
/// reference's rule, the least kinetic energy after the step (`docs/formulation.md`, "Several
/// bodies: the rule"; `resolve.rs`).
#[derive(Debug, Clone)]
pub struct Stepper<T: Real, const B: usize, const P: usize, const N: usize> {
    system: System<T, B, P>,
    /// `m_ref diag(M^-1)` per body (`m_ref` body 0's mass).
    inverse_mass: [[T; 3]; B],
    states: [BodyState<T>; B],
    /// Kahan carries of each body's `x`, `y`, `theta`.
    carry: [[T; 3]; B],
    frames: [[CornerFrame<T>; 4]; P],
    modes: [[ContactMode; 4]; P],
    patterns: [[Pattern; 4]; P],
    /// `64 eps g h m_min / m_ref`: a normal impulse per unit reference mass at most this is none.
    impulse_floor: T,
    steps: u32,
    solver: Lemke<T, N>,
    /// The step's LCP in factored form, refilled each step ([`Self::refill`]).
    pub(super) lcp: StepLcp<T, B, N>,
    /// The rule's metric and reaches (`docs/formulation.md`, "One answer: the rule").
    detector: Detector<T, B>,
    /// The basis of the last step whose load needed the least-norm LCP (`crate::load`; its rows
    /// in this stepper's LCP size, three per slot).
    #[cfg(feature = "fallback")]
    load_basis: Basis<N>,
    /// The last load the rule decided, for a rest state to keep.
    #[cfg(feature = "fallback")]
    load_memory: LoadMemory<T>,
    /// The last step's load was open: the next step takes the copy that decides it
    /// ([`Self::step_loading`]; the first step does).
    #[cfg(feature = "fallback")]
    load_next: bool,
    stats: Stats,
}

impl<T: Real, const B: usize, const P: usize, const N: usize> Stepper<T, B, P, N> {
    /// `P <= 32`: the pairs' bit sets are `u32` (`Factored::held_and_pinned`), and a pair's
    /// index narrows to the `u8` a slot keeps exactly.
    const SIZE_CHECK: () = assert!(
        B > 0 && B < 255 && P > 0 && P <= 32 && N >= 4 && N <= 32,
        "Stepper needs 0 < B < 255, 0 < P <= 32, 4 <= N <= 32"
    );

    /// A stepper at `states` (every body at rest: the modes before the first step are sticking
    /// for an active touching candidate, separated otherwise).
    ///
    /// # Errors
    /// The first of, in this order:
    /// * a body's `width`, `height`, `mass` or `inertia` not finite ([`ParamError::NonFinite`]) or
    ///   not positive ([`ParamError::NotPositive`]), or its `mass / inertia` not finite
    ///   ([`ParamError::InertiaOutOfRange`]);
    /// * the settings' `step` not finite or not positive, `gravity`, `stick_speed` or `margin`
    ///   not finite or negative ([`ParamError::Negative`]);
    /// * a pair's `mu_static` or `mu_kinetic` not finite or negative, or
    ///   [`ParamError::KineticAboveStatic`];
    /// * [`ParamError::OutOfRange`]`("upper_shape")` for a disc whose width and height differ or a
    ///   body the pairs give two shapes, [`ParamError::OutOfRange`]`("pairs")` for a pair naming a
    ///   body that does not exist, resting on itself or on a disc;
    /// * [`ParamError::NonFinite`]`("table")` for a table end that is not finite,
    ///   [`ParamError::OutOfRange`]`("table")` for `lo > hi`;
    /// * [`ParamError::NonFinite`]`("forces")` for an external force that is not finite;
    /// * [`ParamError::NonFiniteState`] for a non-finite state;
    /// * [`ParamError::OutOfRange`]`("mass")` for a body whose mass or inertia per body 0's mass
    ///   (the LCP's unit) is not a positive finite number in `T`.
    pub fn new(system: System<T, B, P>, states: [BodyState<T>; B]) -> Result<Self, ParamError> {
        let () = Self::SIZE_CHECK;
        validate(&system, &states)?;
        let shapes = system.shapes();
        let m_ref = system.bodies[0].mass;
        let mut m_min = m_ref;
        let mut inverse_mass = [[T::zero(); 3]; B];
        for (i, body) in system.bodies.iter().enumerate() {
            inverse_mass[i] = [m_ref / body.mass, m_ref / body.mass, m_ref / body.inertia];
            if body.mass < m_min {
                m_min = body.mass;
            }
        }
        // Each body's `M~` (per body 0's mass) in `T`'s range: a mass ratio whose quotient
        // overflows or underflows is refused here rather than stepped.
        if !inverse_mass.iter().flatten().all(|&m| m.finite() && m > T::zero()) {
            return Err(ParamError::OutOfRange("mass"));
        }
        let s = system.settings.base;
        let mut stepper = Self {
            system,
            inverse_mass,
            states,
            carry: [[T::zero(); 3]; B],
            frames: [[CornerFrame::inactive(); 4]; P],
            modes: [[ContactMode::Separated; 4]; P],
            patterns: [[0; 4]; P],
            impulse_floor: T::of(64.0) * T::EPS * s.gravity * s.step * m_min / m_ref,
            steps: 0,
            solver: Lemke::new(),
            lcp: StepLcp {
                factored: Factored::new(),
                slots: [(0, 0); N],
                k: 0,
                active: 0,
                warm: Basis::all_w(),
            },
            detector: Detector::new(&system.bodies, &shapes, &inverse_mass),
            #[cfg(feature = "fallback")]
            load_basis: Basis::all_w(),
            #[cfg(feature = "fallback")]
            load_memory: LoadMemory::none(),
            #[cfg(feature = "fallback")]
            load_next: true,
            stats: Stats::default(),
        };
        stepper.update_frames();
        for p in 0..P {
            let mut sticking = false;
            for c in 0..4 {
                let f = &stepper.frames[p][c];
                if f.active && f.gap <= f.touch {
                    stepper.modes[p][c] = ContactMode::Sticking;
                    // The warm start's guess: the pair's first touching corner sticks (`p_n`,
                    // `p_+d`), the others touch (`p_n`): both sticking is singular.
                    stepper.patterns[p][c] = if sticking { 0b0001 } else { 0b0011 };
                    sticking = true;
                }
            }
        }
        Ok(stepper)
    }

    /// The system stepped.
    #[must_use]
    pub const fn system(&self) -> &System<T, B, P> {
        &self.system
    }

    /// Each body's state now.
    #[must_use]
    pub const fn states(&self) -> &[BodyState<T>; B] {
        &self.states
    }

    /// Each candidate's geometry now (the next step's frames): an active candidate's frame; an
    /// inactive one's `active` is `false` and its other fields are from an earlier step.
    #[must_use]
    pub const fn frames(&self) -> &[[CornerFrame<T>; 4]; P] {
        &self.frames
    }

    /// Each candidate's mode after the last step (before the first: from the start).
    #[must_use]
    pub const fn modes(&self) -> &[[ContactMode; 4]; P] {
        &self.modes
    }

    /// The run's counters.
    #[must_use]
    pub const fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Time now, `n h` after `n` steps (s).
    #[must_use]
    pub fn time(&self) -> T {
        T::of_count(self.steps) * self.system.settings.base.step
    }

    fn update_frames(&mut self) {
        let s = self.system.settings;
        let poses = poses(&self.system.bodies, &self.states);
        for p in 0..P {
            let (pair, frames) = (&self.system.pairs[p], &mut self.frames[p]);
            let (states, table) = (&self.states, &self.system.table);
            if pair.upper_shape == Shape::Disc {
                rim_frames(pair, states, &poses, table, s.margin, s.base.step, frames);
            } else {
                pair_frames(pair, states, &poses, table, s.margin, s.base.step, frames);
            }
        }
    }

    /// The retries after a failed solve (a ray, the pivot cap, an answer that failed
    /// verification) of `lcp` from the warm basis `warm`, which has run Lemke's method from
    /// `warm`'s tableau, then from the cold start and its regularised retry
    /// ([`Lemke::solve_from_basis`]). The friction LCP is not copositive-plus, so Lemke's method
    /// may end in a ray although a solution exists: the `sigma` of a contact without normal
    /// impulse is unbounded above (its column touches only its friction rows), a ray of the
    /// solution set; and a long pivot sequence in f32 can lose the precision its answer is
    /// verified to.
    ///
    /// 1. Each cone row's `q` is opened by `sqrt(eps) ||q||_inf` and Lemke's method run cold there
    ///    (with its regularised retry: another LCP, so another run); the basis it ends on is run
    ///    from its tableau on the exact problem (verified), or the opened answer counts if it
    ///    verifies against the exact problem (`docs/formulation.md`, "Solving a multibody step",
    ///    4).
    /// 2. The warm basis with one active contact's pattern replaced by each of [`PATTERNS`] (the
    ///    eight of the reference's descent: sticking, sliding either way; touching without
    ///    friction; separated; separated while slipping either way), each by Lemke's method from
    ///    its tableau only.
    ///
    /// **Cost** (a contract): no run is made twice. Bases whose run has been made on `lcp` are
    /// skipped: `warm` itself (one pattern replaced by its own), the trivial basis (its tableau is
    /// the cold start's) and the opened answer's. So at most two cold runs (the opened LCP's and
    /// its regularised retry) and `1 + 8 k` runs from a tableau, each within the pivot cap.
    ///
    /// Every answer is verified against the exact problem; the first error is the step's when none
    /// answers.
    fn retry(
        &self,
        lcp: &Lcp<T, N>,
        k: usize,
        warm: Basis<N>,
        error: LcpError,
    ) -> Result<LcpSolution<T, N>, StepError> {
        // `k <= N / 4` (said so: every row index below is in range, no panic path).
        let k = k.min(N / 4);
        let mut opened = *lcp;
        let delta = T::EPS.sqrt_libm() * lcp.q_norm_inf();
        for j in 3 * k..4 * k {
            opened.q[j] += delta;
        }
        // The bases whose run from the tableau (or, for the trivial one, the cold run) is made.
        let made = [warm, Basis::all_w()];
        let mut near_basis = None;
        if let Ok(near) = self.solver.solve(&opened) {
            if !made.contains(&near.basis)
                && let Some(exact) = self.solver.solve_from_tableau(lcp, near.basis)
            {
                return Ok(exact);
            }
            if verify(lcp, &near.z, self.solver.tolerance()).passed() {
                return Ok(LcpSolution { w: lcp.w_of(&near.z), warm_start_used: false, ..near });
            }
            near_basis = Some(near.basis);
        }
        for j in 0..k {
            for pattern in PATTERNS {
                let basis = with_pattern(warm, k, j, pattern);
                if made.contains(&basis) || Some(basis) == near_basis {
                    continue;
                }
                if let Some(solution) = self.solver.solve_from_tableau(lcp, basis) {
                    return Ok(solution);
                }
            }
        }
        Err(StepError::Solver(error))
    }

    /// Refills this step's LCP in factored form ([`StepLcp`], kept in the stepper and refilled in
    /// place each step: no copy of its rows): the active candidates in candidate order (`slots`),
    /// `v~ = V + h M^-1 w_ext` (eq. 16), each slot's Jacobian rows, bias and `mu`; and the warm
    /// basis (each slot's pattern of the last step).
    ///
    /// # Errors
    /// [`StepError::TooManyContacts`].
    pub(super) fn refill(&mut self) -> Result<(), StepError> {
        let s = self.system.settings.base;
        let h = s.step;
        let out = &mut self.lcp;
        let mut k = 0usize;
        let mut active = 0u8;
        for p in 0..P {
            for c in 0..4 {
                if self.frames[p][c].active {
                    active = active.saturating_add(1);
                    if 4 * (k + 1) <= N {
                        out.slots[k] = (p, c);
                        k += 1;
                    }
                }
            }
        }
        if usize::from(active) > k {
            return Err(StepError::TooManyContacts(active));
        }
        // `k <= N / 4` already; said so that every row index below (< 4 k) is in range without a
        // check (no panic path).
        let k = k.min(N / 4);
        let mut v_free = [[T::zero(); 3]; B];
        for i in 0..B {
            let (st, f, m) = (&self.states[i], self.system.forces[i], self.system.bodies[i].mass);
            v_free[i] = [st.vx + h * f[0] / m, st.vy + h * (f[1] / m - s.gravity), st.omega];
        }
        out.factored.reset(k, v_free);
        // The warm basis' bit mask (bit `row`: `z_row` basic), each slot's pattern at its rows.
        let mut warm = 0u32;
        for (j, &(p, c)) in out.slots[..k].iter().enumerate() {
            // Every slot's (p, c) is below (P, 4) by construction: said so, so that no index below
            // needs a check (no panic path).
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let d = f.tangent;
            let pair = &self.system.pairs[p];
            let mu = if self.modes[p][c].is_sliding() { pair.mu_kinetic } else { pair.mu_static };
            out.factored.set_slot(
                j,
                // `p < P <= 32` ([`Self::SIZE_CHECK`]): exact.
                p as u8,
                [f.dense_row(f.normal), f.dense_row(d)],
                normal_bias(f.gap, h, s.gravity, f.gap_round_off),
                mu,
                &self.inverse_mass,
            );
            warm |= pattern_bits(self.patterns[p][c], k, j);
        }
        out.factored.finish();
        out.k = k;
        out.active = active;
        out.warm = Basis::from_z_mask(warm);
        Ok(())
    }

    /// Solves the step's LCP (`docs/formulation.md`, "Solving a multibody step (the core)", and its
    /// worst case of a step, a contract: no solve or Lemke run made twice): `z = 0`
    /// when `q >= 0` ([`SolvePath::Free`]); else the warm basis in factored form
    /// ([`SolvePath::Warm`]); else the bases of [`Self::candidate`] ([`SolvePath::Candidate`]);
    /// else Lemke's method on
    /// the assembled LCP from the warm basis, with its retries ([`SolvePath::Lemke`]). Every answer
    /// is verified. Writes `z` (zero on entry, as [`Factored::solve_basis`] wants it: the step's own
    /// array); returns `v+`, the basis and the pivots.
    fn solve(
        &self,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
    ) -> Result<Solved<T, B, N>, StepError> {
        let step = &self.lcp;
        let f = &step.factored;
        if !f.is_finite() {
            return Err(StepError::Solver(LcpError::NonFiniteInput));
        }
        if f.is_free() {
            return Ok(Solved {
                v_plus: *f.v_free(),
                basis: Basis::all_w(),
                pivots: 0,
                path: SolvePath::Free,
                along: None,
            });
        }
        let tolerance = self.solver.tolerance();
        let warm = step.warm;
        let why = match f.solve_basis(warm.z_mask(), tolerance, blocks, z, None) {
            Ok(a) => return Ok(Solved::of(a, SolvePath::Warm)),
            Err(why) => why,
        };
        self.unwarmed(why, paths, blocks, z)
    }

    /// [`Self::solve`] after the warm basis declined (`why`): the candidates, then Lemke's method.
    /// Out of line and cold: a warm step (most steps) does not reach it. Lemke's method, per
    /// assembled LCP (at most two: the weighted cone rows, then the model's): one run from the warm
    /// basis' tableau, one cold run and its regularised retry, then [`Self::retry`]'s (two cold
    /// runs, at most `1 + 8 k` from a tableau).
    #[cold]
    #[inline(never)]
    fn unwarmed(
        &self,
        why: Declined,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
    ) -> Result<Solved<T, B, N>, StepError> {
        if let Some(answer) = self.candidate(why, paths, blocks, z) {
            return Ok(answer);
        }
        let (step, warm) = (&self.lcp, self.lcp.warm);
        let f = &step.factored;
        let k = step.k.min(N / 4);
        // The weighted cone rows first (`docs/formulation.md`, "Extreme friction: the cone rows
        // weighted"; the same solutions), with their retries; when none answers, the model's own
        // rows, verified on their own scale.
        let mut weighted = f.is_weighted();
        let solution = loop {
            let lcp = f.assemble(weighted);
            let solved = match self.solver.solve_from_basis(&lcp, warm) {
                Err(LcpError::NonFiniteInput) => return Err(StepError::Solver(LcpError::NonFiniteInput)),
                Err(error) => self.retry(&lcp, k, warm, error),
                Ok(solution) => Ok(solution),
            };
            match solved {
                Ok(solution) => break solution,
                Err(_) if weighted => weighted = false,
                Err(error) => return Err(error),
            }
        };
        for j in 0..N {
            z[j] = solution.z[j];
        }
        Ok(Solved {
            v_plus: f.velocity_after(z),
            basis: solution.basis,
            pivots: solution.pivots,
            path: SolvePath::Lemke,
            along: None,
        })
    }

    /// The candidates of [`Self::solve`] after the warm basis failed with `why`: the first that
    /// answers (written into `z`), or `None`.
    ///
    /// **Cost** (a contract): at most `1 + k + 8 k + 8 P` factored solves (the sliding basis, the
    /// lifting chain's `k`, the failing slot's and its pair's 8, the other slots' and pairs' 8
    /// each), none of one basis twice: a basis equal to the warm one, to one solved out of the
    /// list's order (the sliding one, the chain's) or to one of the failing pair's is skipped, and
    /// so is a pair's basis that changes one slot only (that slot's eight solve it).
    fn candidate(
        &self,
        why: Declined,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
    ) -> Option<Solved<T, B, N>> {
        let step = &self.lcp;
        let f = &step.factored;
        let tolerance = self.solver.tolerance();
        let warm = step.warm;
        let k = step.k.min(N / 4);
        let first = match why {
            Declined::Infeasible(v) => f.slot_of(usize::from(v)),
            Declined::Pattern | Declined::Singular | Declined::Unverified => 0,
        };
        // One slot's pattern replaced, or every slot of one pair at once (an interface that starts
        // or stops sliding changes both its corners: sticking and touching to sliding along the
        // same direction); sticking patterns pair-wide stick the pair's first slot and touch the
        // others (both sticking is singular). The failing slot first, then its pair, then the
        // other slots, then the other pairs.
        let pair_of = |j: usize| step.slots[j.min(N - 1)].0;
        let with_slot = |basis: Basis<N>, j: usize, pattern: Pattern| with_pattern(basis, k, j, pattern);
        let with_pair = |p: usize, pattern: Pattern| {
            let mut basis = warm;
            let mut slots = 0;
            for j in 0..k {
                if pair_of(j) == p {
                    let sticking = pattern == PATTERNS[0] || pattern == PATTERNS[1];
                    basis = with_slot(basis, j, if sticking && slots > 0 { TOUCH } else { pattern });
                    slots += 1;
                }
            }
            (slots > 1).then_some(basis)
        };
        // And the basis in which every touching slot slides against its free slip (the sign of
        // its `+d` row's `q`, the relative tangential velocity before any impulse): several
        // interfaces starting to slide in one step (a pushed block under another).
        let sliding = {
            let mut basis = warm;
            for j in 0..k {
                let [n, plus, ..] = slot_rows(k, j);
                let q = f.q()[plus.min(N - 1)];
                if warm.is_z_basic(n) && q != T::zero() {
                    basis = with_slot(basis, j, if q < T::zero() { PATTERNS[2] } else { PATTERNS[3] });
                }
            }
            basis
        };
        let first_pair = pair_of(first);
        let lifting = self.lifted(warm, why);
        // The warm basis, the bases solved out of the list's order (the sliding one, the lifting
        // chain's) and the failing pair's: a later basis equal to one of them is not solved again.
        let mut made = [warm; 2 + MOST_SLOTS + 8];
        let mut count = 1;
        // The sliding basis and why it declined, when it did: the chain goes on from it unsolved.
        let mut declined = None;
        // The slots (bits) in which `basis` differs from the warm one.
        let changed = |basis: Basis<N>| {
            let (diff, mut slots) = (basis.z_mask() ^ warm.z_mask(), 0u32);
            for j in 0..k {
                if slot_pattern(diff, k, j) != 0 {
                    slots |= 1 << j;
                }
            }
            slots
        };
        // The list, as one index (no iterator adapters: no panic path): the sliding one (one solve,
        // and the first step of a push needs it), the lifting chain, the failing slot's 8, its
        // pair's 8, the other slots' 8 each, the other pairs' 8 each.
        let slots = k.max(1);
        let others = 18 + 8 * (slots - 1);
        for n in 0..others + 8 * P {
            let basis = if n == 0 {
                Some(sliding)
            } else if n == 1 {
                let chain = (&mut made[..], &mut count, declined);
                if let Some(answer) = self.lifting_chain(lifting, paths, blocks, z, chain) {
                    return Some(answer);
                }
                None
            } else if n < 10 {
                Some(with_slot(warm, first, PATTERNS[(n - 2) % 8]))
            } else if n < 18 {
                // One slot changed: the failing slot's, solved above, or another's, solved below
                // (and skipped there).
                with_pair(first_pair, PATTERNS[(n - 2) % 8])
                    .filter(|&b| changed(b).count_ones() > 1 || changed(b) & 1 << first == 0)
            } else if n < others {
                let m = n - 18;
                Some(with_slot(warm, (first + 1 + m / 8) % slots, PATTERNS[m % 8]))
            } else {
                // One slot changed: solved above, as that slot's pattern.
                let m = n - others;
                (m / 8 != first_pair)
                    .then(|| with_pair(m / 8, PATTERNS[m % 8]))
                    .flatten()
                    .filter(|&b| changed(b).count_ones() > 1)
            };
            let Some(basis) = basis.filter(|b| !made[..count.min(made.len())].contains(b)) else {
                continue;
            };
            paths.candidates_tried += 1;
            match f.solve_basis(basis.z_mask(), tolerance, blocks, z, None) {
                Ok(a) => return Some(Solved::of(a, SolvePath::Candidate)),
                Err(why) if n == 0 => declined = Some((basis, why)),
                Err(_) => {}
            }
            if (n == 0 || (10..18).contains(&n))
                && let Some(slot) = made.get_mut(count)
            {
                *slot = basis;
                count += 1;
            }
        }
        None
    }

    /// `basis` with the slot whose normal impulse came out negative (`why`) lifting off: its own
    /// pattern without `p_n` (a sliding contact keeps its friction row and sigma basic: separated
    /// while the support slips past; a sticking one separates and passes its pair's friction to
    /// another of the pair's slots that touches without friction, if one does), or `None`.
    fn lifted(&self, basis: Basis<N>, why: Declined) -> Option<Basis<N>> {
        let k = self.lcp.k.min(N / 4);
        let Declined::Infeasible(v) = why else { return None };
        let j = usize::from(v);
        if j >= k || !basis.is_z_basic(j) {
            return None;
        }
        let pair_of = |i: usize| self.lcp.slots[i.min(N - 1)].0;
        let current = slot_pattern(basis.z_mask(), k, j);
        if PATTERNS.contains(&(current & !1)) {
            return Some(with_pattern(basis, k, j, current & !1));
        }
        if current != PATTERNS[0] && current != PATTERNS[1] {
            return None;
        }
        let mut lifted = with_pattern(basis, k, j, PATTERNS[5]);
        let touching =
            (0..k).find(|&i| pair_of(i) == pair_of(j) && slot_pattern(lifted.z_mask(), k, i) == TOUCH);
        if let Some(i) = touching {
            lifted = with_pattern(lifted, k, i, current);
        }
        Some(lifted)
    }

    /// The lifting candidate `start` ([`Self::lifted`]), and while its answer has another slot
    /// whose normal impulse is negative, that slot lifting too: the first basis that answers.
    /// Each lift takes one `p_n` out of the basis, so at most `k` solves (a stack tipping over its
    /// edges lifts one corner of each interface in its first step).
    ///
    /// `made` holds the first `count` bases solved so far (the warm one first), and adds each the
    /// chain solves (as many as it holds); `declined` a basis solved before and why it declined,
    /// which the chain goes on from without solving it again.
    fn lifting_chain(
        &self,
        start: Option<Basis<N>>,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
        (made, count, declined): (&mut [Basis<N>], &mut usize, Option<(Basis<N>, Declined)>),
    ) -> Option<Solved<T, B, N>> {
        let (f, warm, tolerance) = (&self.lcp.factored, self.lcp.warm, self.solver.tolerance());
        let mut basis = start;
        while let Some(lifted) = basis.filter(|&b| b != warm) {
            if let Some((known, why)) = declined.filter(|&(known, _)| known == lifted) {
                basis = self.lifted(known, why);
                continue;
            }
            paths.candidates_tried += 1;
            match f.solve_basis(lifted.z_mask(), tolerance, blocks, z, None) {
                Ok(a) => return Some(Solved::of(a, SolvePath::Candidate)),
                Err(why) => basis = self.lifted(lifted, why),
            }
            if let Some(slot) = made.get_mut(*count) {
                *slot = lifted;
                *count += 1;
            }
        }
        None
    }

    /// The load of least 2-norm with this step's motion `v_plus` (`crate::load`) in place of the
    /// answer `z`'s: each slot's mode, its pair's summed impulse and its corner's load rewritten
    /// (`report`). A slot touches when it carries load or its normal velocity `c_n^T v+ + bias` is
    /// within the rule's velocity tolerance (`max(1e-9, 256 eps) S`, `S` the rule's speed scale)
    /// of zero, and sticks when its slip is within it too. A rest state (the answer at the least
    /// energy, the same slots with the same modes before the step, the answer's load the same
    /// within round-off as the step before) keeps the load decided then: not solved again.
    #[cfg(feature = "fallback")]
    #[cold]
    #[inline(never)]
    #[allow(clippy::type_complexity)]
    fn decide_load(
        &mut self,
        k: usize,
        z: &[T; N],
        v_plus: &[[T; 3]; B],
        report: (&mut [[ContactMode; 4]; P], &mut [[T; 2]; P], &mut [[[T; 2]; 4]; P]),
    ) -> Result<(), StepError> {
        let (modes, impulses, corner_loads) = report;
        let s = self.system.settings.base;
        let rule = self.detector.rule(&self.lcp.factored);
        // Every index below is in range: said so (no panic path).
        let slots = k.min(MOST_SLOTS).min(N / 4);
        let mut path = [[T::zero(); 2]; MOST_SLOTS];
        let mut before = [ContactMode::Separated; MOST_SLOTS];
        let mut scale = T::zero();
        for j in 0..slots {
            let rows = slot_rows(k, j);
            path[j] = [z[rows[0]], z[rows[1]] - z[rows[2]]];
            scale = max(scale, max(path[j][0].abs_exact(), path[j][1].abs_exact()));
            let (p, c) = self.lcp.slots[j];
            before[j] = self.modes[p.min(P - 1)][c.min(3)];
        }
        // A rest state keeps the load decided the step before: the answer at the least energy, the
        // same slots with the same modes before the step, the answer's load the same within
        // round-off.
        let round_off = T::of(64.0 * N as f64) * T::EPS * scale;
        let memory = &self.load_memory;
        let kept = rule.at_least_energy(v_plus)
            && (0..MOST_SLOTS).all(|j| {
                j >= slots
                    || (memory.slots[j] == self.lcp.slots[j]
                        && memory.before[j] == before[j]
                        && (path[j][0] - memory.path[j][0]).abs_exact() <= round_off
                        && (path[j][1] - memory.path[j][1]).abs_exact() <= round_off)
            })
            && memory.count == slots;
        let (load, after) = if kept {
            // The memory stays but for the path, which the next step's is compared with.
            let (load, after) = (memory.load, memory.after);
            self.load_memory.path = path;
            (load, after)
        } else {
            let tolerance = rule.velocity_tolerance();
            let off = LoadContact {
                normal: [[T::zero(); 3]; B],
                tangent: [[T::zero(); 3]; B],
                carry: Carry::Nothing,
            };
            let mut contacts = [off; MOST_SLOTS];
            let mut slips = [T::zero(); MOST_SLOTS];
            for j in 0..slots {
                let (p, c) = self.lcp.slots[j];
                let (p, c) = (p.min(P - 1), c.min(3));
                let f = &self.frames[p][c];
                let normal = f.dense_row::<B>(f.normal);
                let mut normal_velocity = normal_bias(f.gap, s.step, s.gravity, f.gap_round_off);
                for (row, v) in normal.iter().zip(v_plus) {
                    normal_velocity += row[0] * v[0] + row[1] * v[1] + row[2] * v[2];
                }
                slips[j] = slip(f, v_plus);
                if path[j][0] <= self.impulse_floor && normal_velocity > tolerance {
                    continue;
                }
                let pair = &self.system.pairs[p];
                let mu = if before[j].is_sliding() { pair.mu_kinetic } else { pair.mu_static };
                let carry = if slips[j].abs_exact() <= tolerance {
                    Carry::Sticking { mu }
                } else {
                    Carry::Sliding { friction_per_normal: if slips[j] > T::zero() { mu } else { -mu } }
                };
                contacts[j] = LoadContact { normal, tangent: f.dense_row::<B>(f.tangent), carry };
            }
            let (load, how) =
                least_norm(&contacts, &path, &mut self.load_basis).map_err(StepError::Solver)?;
            if how == LoadPath::Determinate {
                return Ok(());
            }
            let mut after = [ContactMode::Separated; MOST_SLOTS];
            for j in 0..slots {
                if load[j][0] > self.impulse_floor {
                    after[j] = ContactMode::from_slip(slips[j], s.stick_speed);
                }
            }
            let mut remembered = [(usize::MAX, usize::MAX); MOST_SLOTS];
            for (r, &slot) in remembered.iter_mut().zip(&self.lcp.slots).take(slots) {
                *r = slot;
            }
            self.load_memory = LoadMemory { slots: remembered, count: slots, before, path, load, after };
            (load, after)
        };
        self.stats.load_decided_steps += 1;
        // The report again, from the load.
        *impulses = [[T::zero(); 2]; P];
        let per_second = self.system.bodies[0].mass / s.step;
        for j in 0..slots {
            let (p, c) = self.lcp.slots[j];
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let [pn, pf] = load[j];
            modes[p][c] = after[j];
            corner_loads[p][c] = [pn * per_second, pf * per_second];
            let sign = if c >= 2 { -T::one() } else { T::one() };
            impulses[p][0] += sign * (pn * f.normal[0] + pf * f.tangent[0]);
            impulses[p][1] += sign * (pn * f.normal[1] + pf * f.tangent[1]);
        }
        Ok(())
    }

    /// Advances one step: the active candidates' LCP (per unit reference mass) in factored form,
    /// solved by the paths of `docs/formulation.md` ("Solving a multibody step") and verified;
    /// `V+ = v~ + M~ J^T z`, `q+ = q + h V+` (compensated sums), modes after the step.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged.
    pub fn step(&mut self) -> Result<StepReport<T, B, P>, StepError> {
        #[cfg(feature = "fallback")]
        if self.load_next {
            return self.step_loading();
        }
        self.step_with::<false>()
    }

    /// [`Self::step`] after a step whose load was open (`docs/formulation.md`, "The load: the least
    /// norm"): out of line, so that the other steps' copy has none of the load's code.
    #[cfg(feature = "fallback")]
    #[inline(never)]
    fn step_loading(&mut self) -> Result<StepReport<T, B, P>, StepError> {
        self.step_with::<true>()
    }

    /// [`Self::step`], deciding the load where it is open when `LOAD`.
    #[inline(always)]
    #[allow(clippy::inline_always)] // into `step` and `step_loading`: two copies, as said there
    fn step_with<const LOAD: bool>(&mut self) -> Result<StepReport<T, B, P>, StepError> {
        let s = self.system.settings.base;
        let h = s.step;
        self.refill()?;
        let (k, active) = (self.lcp.k.min(N / 4), self.lcp.active);
        let mut z = [T::zero(); N];
        let mut paths = self.stats.paths;
        // A sliding step's blocks, formed once for its solve and its detection.
        self.lcp.factored.form_blocks(self.lcp.warm.z_mask());
        let blocks = self.lcp.factored.blocks();
        let Solved { mut v_plus, basis, pivots, path, along } = self.solve(&mut paths, blocks, &mut z)?;
        let mut mask = basis.z_mask();
        let tolerance = self.solver.tolerance();
        let f = &self.lcp.factored;
        let rule = resolve::apply(&self.detector, f, blocks, tolerance, (&mut v_plus, &mut z, &mut mask));
        // The slips the basis solve formed, unless the rule took another answer.
        let (along, from_solve) = match along {
            Some(along) if rule.is_none_or(|r| !r.changed) => (along, true),
            _ => ([T::zero(); MOST_SLOTS], false),
        };
        let m_ref = self.system.bodies[0].mass;
        // q+ = q + h V+, compensated sums.
        let mut states = self.states;
        let mut carry = self.carry;
        for i in 0..B {
            let st = &mut states[i];
            [st.vx, st.vy, st.omega] = v_plus[i];
            for (c, coordinate) in [&mut st.x, &mut st.y, &mut st.theta].into_iter().enumerate() {
                let increment = h * v_plus[i][c] - carry[i][c];
                let sum = *coordinate + increment;
                carry[i][c] = (sum - *coordinate) - increment;
                *coordinate = sum;
            }
            if !st.is_finite() {
                return Err(StepError::NonFinite);
            }
        }
        // Modes after the step, interface forces, each corner's load, the next warm patterns.
        let mut modes = [[ContactMode::Separated; 4]; P];
        let mut patterns = [[0; 4]; P];
        let mut impulses = [[T::zero(); 2]; P];
        let mut corner_loads = [[[T::zero(); 2]; 4]; P];
        let per_second = m_ref / h;
        // Whether the load may be open (`docs/formulation.md`, "The load: the least norm"): two
        // sticking corners of one pair carrying load, or more unknowns (two per sticking slot,
        // one per sliding one) than the bodies' `3B` coordinates.
        #[cfg(feature = "fallback")]
        let (mut open, mut unknowns, mut sticking_pair) = (false, 0, usize::MAX);
        // Each slot's pattern ([`slot_pattern`]) from the normals', frictions' and sigmas' bits,
        // shifted out slot by slot.
        let (mut normals, mut frictions, mut sigmas) = (mask, mask >> k.min(8), mask >> (3 * k.min(8)));
        for j in 0..k {
            let (p, c) = self.lcp.slots[j];
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let rows = slot_rows(k, j);
            patterns[p][c] = (normals & 1 | (frictions & 3) << 1 | (sigmas & 1) << 3) as Pattern;
            (normals, frictions, sigmas) = (normals >> 1, frictions >> 2, sigmas >> 1);
            let (pn, pf) = (z[rows[0]], z[rows[1]] - z[rows[2]]);
            if pn > self.impulse_floor {
                // `-c_+d^T v+` as the solve formed it, else from the frame.
                let slip = if from_solve { -along[j.min(MOST_SLOTS - 1)] } else { slip(f, &v_plus) };
                let mode = ContactMode::from_slip(slip, s.stick_speed);
                modes[p][c] = mode;
                #[cfg(feature = "fallback")]
                if mode == ContactMode::Sticking {
                    unknowns += 2;
                    open |= sticking_pair == p;
                    sticking_pair = p;
                } else {
                    unknowns += 1;
                }
            }
            corner_loads[p][c] = [pn * per_second, pf * per_second];
            // On the upper body: + for its corners, - for the lower body's (negated: the bits of
            // `+-1` times it, a product by `+-1` being exact).
            let impulse = &mut impulses[p];
            let mut along = [pn * f.normal[0] + pf * f.tangent[0], pn * f.normal[1] + pf * f.tangent[1]];
            if c >= 2 {
                along = [-along[0], -along[1]];
            }
            impulse[0] += along[0];
            impulse[1] += along[1];
        }
        // The load, where it may be open: in place of the answer's, before the frames move on.
        #[cfg(feature = "fallback")]
        {
            self.load_next = open || unknowns > 3 * B;
            if LOAD && self.load_next {
                self.decide_load(k, &z, &v_plus, (&mut modes, &mut impulses, &mut corner_loads))?;
            }
        }
        let mut interface_forces = [[T::zero(); 2]; P];
        for p in 0..P {
            interface_forces[p] = [impulses[p][0] * m_ref / h, impulses[p][1] * m_ref / h];
        }
        self.states = states;
        self.carry = carry;
        self.modes = modes;
        self.patterns = patterns;
        self.steps += 1;
        self.update_frames();
        let st = &mut self.stats;
        paths.count(path);
        st.paths = paths;
        st.count_rule(rule);
        st.steps += 1;
        st.pivots += u64::from(pivots);
        st.max_pivots = st.max_pivots.max(pivots);
        st.max_active = st.max_active.max(active);
        if path == SolvePath::Warm {
            st.warm_direct += 1;
        }
        Ok(StepReport { time: self.time(), states, interface_forces, corner_loads, modes, active, pivots })
    }
}

/// The set-up checks of [`Stepper::new`] (its `# Errors`, in that order) but the mass ratios:
/// each body as [`crate::planar::Stepper`]'s body is checked, and its height positive too (a box
/// or a disc); the settings as its settings, and the margin; each pair's friction as a contact's;
/// the pairs' bodies and shapes; the table's ends; the forces; the states.
fn validate<T: Real, const B: usize, const P: usize>(
    system: &System<T, B, P>,
    states: &[BodyState<T>; B],
) -> Result<(), ParamError> {
    for body in &system.bodies {
        check_fields(&body.fields())?;
        check_fields(&[("height", body.height, Check::Positive)])?;
        body.check_inertia("mass", "width")?;
    }
    let [step, gravity, stick_speed] = system.settings.base.fields();
    check_fields(&[step, gravity, stick_speed, ("margin", system.settings.margin, Check::NonNegative)])?;
    for pair in &system.pairs {
        check_friction(pair.mu_static, pair.mu_kinetic)?;
    }
    let shapes = system.shapes();
    for (body, shape) in system.bodies.iter().zip(&shapes) {
        if *shape == Shape::Disc && body.width != body.height {
            return Err(ParamError::OutOfRange("upper_shape"));
        }
    }
    for pair in &system.pairs {
        let bad_lower = match pair.lower {
            // A body that does not exist has no shape: refused as a disc is.
            super::Support::Body(s) => s == pair.upper || shapes.get(usize::from(s)) != Some(&Shape::Box),
            super::Support::Table => false,
        };
        if shapes.get(usize::from(pair.upper)).is_some_and(|shape| *shape != pair.upper_shape) {
            return Err(ParamError::OutOfRange("upper_shape"));
        }
        if usize::from(pair.upper) >= B || bad_lower {
            return Err(ParamError::OutOfRange("pairs"));
        }
    }
    let Table { lo, hi } = system.table;
    if !lo.into_iter().chain(hi).all(Real::finite) {
        return Err(ParamError::NonFinite("table"));
    }
    if let (Some(lo), Some(hi)) = (lo, hi)
        && lo > hi
    {
        return Err(ParamError::OutOfRange("table"));
    }
    if !system.forces.iter().flatten().all(|f| f.finite()) {
        return Err(ParamError::NonFinite("forces"));
    }
    if !states.iter().all(BodyState::is_finite) {
        return Err(ParamError::NonFiniteState);
    }
    Ok(())
}

/// The last load the rule decided ([`Stepper::decide_load`]): its slots and their modes before
/// the step, the path's load, the decided one and the modes it gave.
#[cfg(feature = "fallback")]
#[derive(Debug, Clone, Copy)]
struct LoadMemory<T> {
    slots: [(usize, usize); MOST_SLOTS],
    count: usize,
    before: [ContactMode; MOST_SLOTS],
    path: [[T; 2]; MOST_SLOTS],
    load: [[T; 2]; MOST_SLOTS],
    after: [ContactMode; MOST_SLOTS],
}

#[cfg(feature = "fallback")]
impl<T: Real> LoadMemory<T> {
    /// No load decided yet: matches no step.
    fn none() -> Self {
        Self {
            slots: [(usize::MAX, usize::MAX); MOST_SLOTS],
            count: usize::MAX,
            before: [ContactMode::Separated; MOST_SLOTS],
            path: [[T::zero(); 2]; MOST_SLOTS],
            load: [[T::zero(); 2]; MOST_SLOTS],
            after: [ContactMode::Separated; MOST_SLOTS],
        }
    }
}

impl Stats {
    /// Counts what the rule did on a step ([`resolve::apply`]'s answer).
    pub(super) fn count_rule(&mut self, rule: Option<Resolution>) {
        if let Some(r) = rule {
            self.rule_checked_steps += 1;
            self.rule_enumerated_steps += u64::from(r.enumerated);
            self.ambiguous_steps += u64::from(r.ambiguous);
            self.rule_changed_answer += u64::from(r.changed);
        }
    }
}

/// A step's verified answer ([`Stepper::solve`]; `z` is written into the caller's array).
struct Solved<T, const B: usize, const N: usize> {
    /// `v+ = v~ + M~ J^T z`.
    v_plus: [[T; 3]; B],
    /// The basis of the answer (the next step's warm basis).
    basis: Basis<N>,
    /// Lemke pivots spent.
    pivots: u32,
    /// The path that answered.
    path: SolvePath,
    /// Each slot's `c_+d^T v+` as a basis solve formed it ([`super::factored::Answer`]), `None`
    /// from Lemke's method or with no impulse.
    along: Option<[T; MOST_SLOTS]>,
}

impl<T: Copy, const B: usize, const N: usize> Solved<T, B, N> {
    /// A basis solve's answer `a`, reached by `path` (no pivot).
    #[inline]
    fn of(a: Answer<T, B>, path: SolvePath) -> Self {
        Self { v_plus: a.v_plus, basis: Basis::from_z_mask(a.mask), pivots: 0, path, along: Some(a.along) }
    }
}

/// One step's LCP in factored form with its slots and warm basis ([`Stepper::refill`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct StepLcp<T, const B: usize, const N: usize> {
    /// The factored rows.
    pub(super) factored: Factored<T, B, N>,
    /// The active candidates `(pair, candidate)` in slot order.
    pub(super) slots: [(usize, usize); N],
    /// How many slots.
    pub(super) k: usize,
    /// Active candidates (`k`, as a count).
    pub(super) active: u8,
    /// The last step's patterns as a basis.
    pub(super) warm: Basis<N>,
}

#[cfg(test)]
#[allow(clippy::expect_used)] // a test's setup may fail loudly
mod tests {
    //! [`Stepper::new`] refuses a system it cannot step, each by its [`ParamError`], before any
    //! step: every field of its contract broken once, the rest valid.

    use super::*;
    use crate::multibody::Support;

    /// Two boxes, one on the other, on a floor, pulled: the valid system every case breaks once.
    fn pulled_pair() -> (System<f64, 2, 2>, [BodyState<f64>; 2]) {
        let block = Body::block(1.0, 0.2, 0.1);
        let system = System {
            bodies: [block; 2],
            table: Table::floor(),
            pairs: [Pair::boxed(0, Support::Table, 0.5, 0.4), Pair::boxed(1, Support::Body(0), 0.5, 0.4)],
            forces: [[5.0, 0.0], [0.0; 2]],
            settings: Settings {
                base: crate::planar::Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 },
                margin: 1e-3,
            },
        };
        (system, [BodyState::at_rest(0.0, 0.05, 0.0), BodyState::at_rest(0.0, 0.15, 0.0)])
    }

    /// `pulled_pair` changed by `change`: `Stepper::new`'s error, `None` when it builds.
    fn refusal(change: impl FnOnce(&mut System<f64, 2, 2>, &mut [BodyState<f64>; 2])) -> Option<ParamError> {
        let (mut system, mut states) = pulled_pair();
        change(&mut system, &mut states);
        Stepper::<f64, 2, 2, 24>::new(system, states).err()
    }

    #[test]
    fn the_valid_system_builds_and_steps() {
        assert_eq!(refusal(|_, _| {}), None);
        let (system, states) = pulled_pair();
        let mut stepper = Stepper::<f64, 2, 2, 24>::new(system, states).expect("valid");
        assert!(stepper.step().is_ok());
    }

    #[test]
    fn a_body_without_a_positive_finite_mass_inertia_or_size_is_refused() {
        assert_eq!(refusal(|s, _| s.bodies[1].mass = -1.0), Some(ParamError::NotPositive("mass")));
        assert_eq!(refusal(|s, _| s.bodies[0].mass = 0.0), Some(ParamError::NotPositive("mass")));
        assert_eq!(refusal(|s, _| s.bodies[1].mass = f64::NAN), Some(ParamError::NonFinite("mass")));
        assert_eq!(refusal(|s, _| s.bodies[1].inertia = 0.0), Some(ParamError::NotPositive("inertia")));
        assert_eq!(
            refusal(|s, _| s.bodies[0].inertia = f64::INFINITY),
            Some(ParamError::NonFinite("inertia"))
        );
        assert_eq!(refusal(|s, _| s.bodies[1].width = -0.2), Some(ParamError::NotPositive("width")));
        // A planar body's height may be 0 (a rod as a line); a box's may not.
        assert_eq!(refusal(|s, _| s.bodies[1].height = 0.0), Some(ParamError::NotPositive("height")));
        assert_eq!(
            refusal(|s, _| s.bodies[1].inertia = 1e-310),
            Some(ParamError::InertiaOutOfRange { mass: "mass", size: "width" })
        );
    }

    /// `M~` is per body 0's mass: a ratio whose quotient leaves `T`'s range is refused.
    #[test]
    fn masses_whose_ratio_leaves_the_range_are_refused() {
        let ratio = |s: &mut System<f64, 2, 2>, _: &mut _| {
            s.bodies[0] = Body::block(1e300, 0.2, 0.1);
            s.bodies[1] = Body::block(1e-20, 0.2, 0.1);
        };
        assert_eq!(refusal(ratio), Some(ParamError::OutOfRange("mass")));
    }

    #[test]
    fn a_step_that_is_not_positive_and_finite_is_refused() {
        assert_eq!(refusal(|s, _| s.settings.base.step = -1e-3), Some(ParamError::NotPositive("step")));
        assert_eq!(refusal(|s, _| s.settings.base.step = 0.0), Some(ParamError::NotPositive("step")));
        assert_eq!(refusal(|s, _| s.settings.base.step = f64::NAN), Some(ParamError::NonFinite("step")));
        assert_eq!(refusal(|s, _| s.settings.base.gravity = -9.81), Some(ParamError::Negative("gravity")));
        assert_eq!(
            refusal(|s, _| s.settings.base.stick_speed = -1.0),
            Some(ParamError::Negative("stick_speed"))
        );
        assert_eq!(refusal(|s, _| s.settings.margin = -1e-3), Some(ParamError::Negative("margin")));
        assert_eq!(refusal(|s, _| s.settings.margin = f64::INFINITY), Some(ParamError::NonFinite("margin")));
    }

    #[test]
    fn friction_outside_zero_to_mu_static_is_refused() {
        assert_eq!(refusal(|s, _| s.pairs[1].mu_kinetic = 0.6), Some(ParamError::KineticAboveStatic));
        assert_eq!(refusal(|s, _| s.pairs[0].mu_static = -0.1), Some(ParamError::Negative("mu_static")));
        assert_eq!(refusal(|s, _| s.pairs[1].mu_kinetic = -0.1), Some(ParamError::Negative("mu_kinetic")));
        assert_eq!(refusal(|s, _| s.pairs[1].mu_static = f64::NAN), Some(ParamError::NonFinite("mu_static")));
        // Frictionless and `mu_k = mu_s` are valid.
        assert_eq!(refusal(|s, _| s.pairs[1] = Pair::boxed(1, Support::Body(0), 0.0, 0.0)), None);
        assert_eq!(refusal(|s, _| s.pairs[1].mu_kinetic = 0.5), None);
    }

    #[test]
    fn a_table_forces_or_states_that_are_not_finite_are_refused() {
        assert_eq!(refusal(|s, _| s.table.hi = Some(f64::NAN)), Some(ParamError::NonFinite("table")));
        assert_eq!(
            refusal(|s, _| s.table = Table { lo: Some(0.5), hi: Some(-0.5) }),
            Some(ParamError::OutOfRange("table"))
        );
        assert_eq!(refusal(|s, _| s.table = Table { lo: Some(-0.5), hi: Some(0.5) }), None);
        assert_eq!(refusal(|s, _| s.forces[1][1] = f64::INFINITY), Some(ParamError::NonFinite("forces")));
        assert_eq!(refusal(|_, st| st[1].omega = f64::NAN), Some(ParamError::NonFiniteState));
    }

    #[test]
    fn pairs_naming_no_body_are_refused() {
        assert_eq!(refusal(|s, _| s.pairs[1].upper = 2), Some(ParamError::OutOfRange("pairs")));
        assert_eq!(
            refusal(|s, _| s.pairs[1].lower = Support::Body(1)),
            Some(ParamError::OutOfRange("pairs"))
        );
    }

    /// The step's checks are the constructor's: `f32` refuses the same way.
    #[test]
    fn f32_refuses_as_f64() {
        let (system, states) = pulled_pair();
        let mut system = System {
            bodies: system.bodies.map(|b| Body::block(b.mass as f32, b.width as f32, b.height as f32)),
            table: Table::floor(),
            pairs: system.pairs.map(|p| Pair::boxed(p.upper, p.lower, 0.5_f32, 0.4)),
            forces: [[5.0, 0.0], [0.0; 2]],
            settings: Settings {
                base: crate::planar::Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 },
                margin: 1e-3,
            },
        };
        let states = states.map(|s| BodyState::at_rest(s.x as f32, s.y as f32, 0.0));
        assert!(Stepper::<f32, 2, 2, 24>::new(system, states).is_ok());
        system.settings.base.step = -1e-3;
        assert_eq!(
            Stepper::<f32, 2, 2, 24>::new(system, states).err(),
            Some(ParamError::NotPositive("step"))
        );
    }
}
