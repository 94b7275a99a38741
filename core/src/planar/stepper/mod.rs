//! [`Stepper`]: one rigid body against `K` supports, stepped by an LCP per step.
//!
//! One [`Stepper::step`] (`docs/formulation.md`, "One time step"):
//!
//! 1. the contact frames of the step's start (computed at the end of the previous step) and the
//!    supports' velocities over the step, given by the scene;
//! 2. each contact's friction coefficient from its mode after the previous step (`mu_s` while
//!    sticking or separated, `mu_k` while sliding);
//! 3. the LCP of eq. 18 for the solved [`Layout`], in factored form ([`FactoredLcp`]), solved
//!    along the paths of [`SolvePath`]: the previous step's basis, its neighbours, [`Lemke`]'s
//!    method warm-started from it;
//! 4. for a reduced layout, the dropped directions checked; when one is needed (or the reduced LCP
//!    has no solution) the step is solved again in the full layout, warm-started from the reduced
//!    basis mapped into it (feature `fallback`; without it the step fails with
//!    [`StepError::ReducedModelLeftRange`] and no full-layout code is linked);
//! 5. `v+ = v~ + M^-1 W z` (eq. 16) and `q+ = q + h v+` with compensated sums (eq. 14), refused
//!    when not finite;
//! 6. each contact's mode after the step, the [`StepReport`], and the frames for the next step.
//!
//! A failed step leaves the state as it was and returns a [`StepError`]; nothing here panics.
//!
//! `load.rs`: the load where the contacts leave it open (`docs/formulation.md`, "The load: the
//! least norm"; feature `fallback`).

#[cfg(feature = "fallback")]
mod load;

use super::assemble::StepInputs;
use super::body::BodyState;
use super::candidates::basis_of_modes;
use super::contact::{Contact, ContactFrame, ContactMode, Pose, Support};
use super::factored::{FactoredLcp, PlanCache};
use super::inputs::sign;
use super::layout::{Direction, Layout, Variable};
use super::model::{Model, Settings, validate};
use super::report::{ContactReport, ROUND_OFF_LIMIT, StepReport};
use super::resolve::{Detector, resolve, solve_by_rule};
use super::strategy::{SolvePath, Solved, solve};
use crate::RunStats;
use crate::StepError;
use crate::lcp::{Basis, Lemke};
use crate::params::ParamError;
use crate::real::{Real, compensated_add, max, min, zero_if_finite};
use crate::rule::Resolution;
#[cfg(feature = "fallback")]
use load::PlanarLoadMemory;

/// One rigid body against `K` supports; each step solves the `N`-variable LCP of a [`Layout`],
/// and, when that layout is reduced, falls back to the `NF`-variable full layout (`NF = N`: no
/// reduction, no check).
#[derive(Debug, Clone)]
pub struct Stepper<T: Real, const K: usize, const N: usize, const NF: usize = N> {
    contacts: [Contact<T>; K],
    settings: Settings<T>,
    mass: T,
    /// `diag(M^-1)` per unit mass ([`Body::inverse_mass_per_unit_mass`]).
    m_inv: [T; 3],
    half: [T; 2],
    size: T,
    /// A contact with at most this normal impulse per unit mass is separated: `64 eps g h`, the
    /// round-off of a step's gravity impulse (constant, so computed once). Not `eps V`: the
    /// impulses are solved to round-off of their own scale even when the support speed `V` is in
    /// the same LCP, and at h = 1e-5 s `eps V` of a 1 m/s scene is 1/40 of its weight's impulse.
    impulse_floor: T,
    /// A step whose velocity scale exceeds this is [`StepReport::round_off_limited`]:
    /// `ROUND_OFF_LIMIT g h / eps` (infinite without gravity: no impulse scale).
    round_off_speed: T,
    layout: Layout<K, N>,
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    full: Layout<K, NF>,
    /// Where each solved variable sits in the full layout (only the fallback reads it: without
    /// it the stepper keeps none).
    #[cfg(feature = "fallback")]
    to_full: [usize; N],
    /// For each contact that keeps one direction of two: the kept friction row and direction.
    kept_alone: [Option<(usize, Direction)>; K],
    state: BodyState<T>,
    /// Compensated-summation carries of `x`, `y`, `theta` (Kahan): `q += h v` adds a `1e-7` m
    /// increment to a coordinate of `0.3` m at the slowest finger speeds, where f32's rounding was a
    /// systematic 10 % of the increment.
    carry: [T; 3],
    time: T,
    supports: [Support<T>; K],
    frames: [ContactFrame<T>; K],
    modes: [ContactMode; K],
    basis: Basis<N>,
    /// The step's LCP in factored form, refilled in place each step.
    factored: FactoredLcp<T, K, N>,
    /// The unknowns of the last basis the warm path solved, with its mask: the next step's warm
    /// basis is usually the same.
    plan: PlanCache<K>,
    solver: Lemke<T, N>,
    /// Which steps may have several answers, for the rule (`docs/formulation.md`, "One answer").
    detector: Detector,
    /// The basis of the last step whose load needed the least-norm LCP (`crate::load`; its
    /// `3K` rows in the full layout's size, whose solver the fallback has already).
    #[cfg(feature = "fallback")]
    load_basis: Basis<NF>,
    /// The last load the rule decided, for a rest state to keep.
    #[cfg(feature = "fallback")]
    load_memory: PlanarLoadMemory<T, K>,
    /// The contacts the last step's load left touching and slipping but carrying nothing (a model
    /// of three or more contacts, whose every step's load the rule decides): they take `mu_k`
    /// next step, as a sliding contact does (`docs/formulation.md`, "The load: the least norm").
    #[cfg(feature = "fallback")]
    slipping_unloaded: [bool; K],
    stats: RunStats,
}

impl<T: Real, const K: usize, const N: usize, const NF: usize> Stepper<T, K, N, NF> {
    const SIZES: () = assert!(
        K >= 1 && N >= 3 * K && N <= NF && NF <= 4 * K && NF <= 32,
        "Stepper<T, K, N, NF>: 3K <= N <= NF <= 4K, NF <= 32"
    );

    /// A stepper for `model`, solving `layout` each step with `full` as its fallback, from the state
    /// `start` with the supports where they are at `t = 0` and moving as they do at `t = 0+`.
    /// Contact modes before the first step come from that motion (`docs/formulation.md`).
    ///
    /// # Errors
    /// A non-finite or out-of-range setting, body value or friction coefficient, a non-finite start
    /// state or support, a support that does not fit its contact's feature, or a `full` that lacks a
    /// variable of `layout`.
    pub fn new(
        model: Model<T, K>,
        layout: Layout<K, N>,
        full: Layout<K, NF>,
        start: BodyState<T>,
        supports: [Support<T>; K],
    ) -> Result<Self, ParamError> {
        validate(&model, &start, &supports)?;
        Self::from_valid(model, layout, full, start, supports)
    }

    /// [`Self::new`] for a model, start and supports already known to be valid (a built-in scene
    /// whose own validation implies the stepper's); only the layouts are checked.
    pub(crate) fn from_valid(
        model: Model<T, K>,
        layout: Layout<K, N>,
        full: Layout<K, NF>,
        start: BodyState<T>,
        supports: [Support<T>; K],
    ) -> Result<Self, ParamError> {
        let () = Self::SIZES;
        #[cfg_attr(not(feature = "fallback"), allow(unused_variables))]
        let to_full = layout.index_in(&full).ok_or(ParamError::LayoutNotInFull)?;
        let mut kept_alone = [None; K];
        for (j, v) in layout.variables().iter().enumerate() {
            if let Variable::Friction(i, direction) = *v
                && layout.kept_alone(&full, usize::from(i)).is_some()
                && let Some(slot) = kept_alone.get_mut(usize::from(i))
            {
                *slot = Some((j, direction));
            }
        }
        let body = model.body;
        let s = &model.settings;
        let impulse_floor = T::of(64.0) * T::EPS * s.gravity * s.step + T::TINY;
        let mut stepper = Self {
            contacts: model.contacts,
            settings: model.settings,
            mass: body.mass,
            m_inv: body.inverse_mass_per_unit_mass(),
            half: body.half_extents(),
            size: body.size(),
            impulse_floor,
            round_off_speed: if s.gravity * s.step > T::zero() {
                T::of(ROUND_OFF_LIMIT) * s.gravity * s.step / T::EPS
            } else {
                T::of(f64::INFINITY)
            },
            layout,
            full,
            #[cfg(feature = "fallback")]
            to_full,
            kept_alone,
            state: start,
            carry: [T::zero(); 3],
            time: T::zero(),
            supports,
            frames: [ContactFrame {
                along: T::zero(),
                gap: T::zero(),
                active: false,
                wn: [T::zero(); 3],
                wt: [T::zero(); 3],
                r: [T::zero(); 2],
            }; K],
            modes: [ContactMode::Separated; K],
            basis: Basis::all_w(),
            factored: FactoredLcp::empty(&layout),
            plan: PlanCache::<K>::default(),
            solver: Lemke::new(),
            detector: Detector::new(&model.contacts, body.inverse_mass_per_unit_mass(), body.half_extents()),
            #[cfg(feature = "fallback")]
            load_basis: Basis::all_w(),
            #[cfg(feature = "fallback")]
            load_memory: PlanarLoadMemory::none(),
            #[cfg(feature = "fallback")]
            slipping_unloaded: [false; K],
            stats: RunStats::default(),
        };
        stepper.update_frames(&supports);
        stepper.modes = stepper.initial_modes();
        stepper.basis = basis_of_modes(stepper.layout.tangents(), &stepper.modes);
        Ok(stepper)
    }

    /// The body's state.
    #[must_use]
    pub const fn state(&self) -> &BodyState<T> {
        &self.state
    }
    /// Simulated time (s).
    #[must_use]
    pub const fn time(&self) -> T {
        self.time
    }
    /// The time at the end of the next step, `(steps + 1) h`: the scene's supports must be given
    /// where they are then.
    #[must_use]
    pub fn next_time(&self) -> T {
        T::of_count(count_u32(self.stats.steps + 1)) * self.settings.step
    }
    /// The settings.
    #[must_use]
    pub const fn settings(&self) -> &Settings<T> {
        &self.settings
    }
    /// The contacts.
    #[must_use]
    pub const fn contacts(&self) -> &[Contact<T>; K] {
        &self.contacts
    }
    /// The supports where the last step left them (at `t = 0`: the initial ones).
    #[must_use]
    pub const fn supports(&self) -> &[Support<T>; K] {
        &self.supports
    }
    /// The contact frames of the current state.
    #[must_use]
    pub const fn frames(&self) -> &[ContactFrame<T>; K] {
        &self.frames
    }
    /// Each contact's mode after the last step (before the first: from the prescribed motion).
    #[must_use]
    pub const fn modes(&self) -> [ContactMode; K] {
        self.modes
    }
    /// The layout each step solves.
    #[must_use]
    pub const fn layout(&self) -> &Layout<K, N> {
        &self.layout
    }
    /// Counters so far.
    #[must_use]
    pub const fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// Recomputes the contact frames for the current state against `supports`, in place (a
    /// support that does not fit gives an inactive frame; `new` and `step` refuse those first).
    /// The supports are passed in, not read back from `self.supports` just after they were
    /// copied there (an 8-byte load of a position stored as two 4-byte halves cannot be forwarded
    /// from the store buffer). Without `host-tuned` out of line: one copy for `new` and `step`.
    #[cfg_attr(not(feature = "host-tuned"), inline(never))]
    #[cfg_attr(feature = "host-tuned", inline(always))]
    #[allow(clippy::inline_always)] // measured: the host's step is faster so (left to itself, it was not inlined)
    fn update_frames(&mut self, supports: &[Support<T>; K]) {
        let pose = Pose { com: [self.state.x, self.state.y], sin_cos: self.state.theta.sin_cos_portable() };
        for i in 0..K {
            match ContactFrame::new(&self.contacts[i].feature, &supports[i], &pose, self.half) {
                Some(f) => self.frames[i] = f,
                None => self.frames[i].active = false,
            }
        }
    }

    /// The modes before the first step: a contact that is active and touching (gap at most
    /// `64 eps (size + |y|)`) gets its mode from the slip of its support's velocity against the
    /// body's; one that does not touch is separated.
    fn initial_modes(&self) -> [ContactMode; K] {
        let v = self.state.velocity();
        let touch_tol = T::of(64.0) * T::EPS * (self.size + self.state.y.abs_exact());
        let mut modes = [ContactMode::Separated; K];
        for i in 0..K {
            let f = &self.frames[i];
            if f.active && f.gap <= touch_tol {
                modes[i] =
                    ContactMode::from_slip(f.slip(v, self.supports[i].velocity()), self.settings.stick_speed);
            }
        }
        modes
    }

    /// Advances one step of `h`; `supports` are where the supports are at its end
    /// ([`Self::next_time`]) and how fast they moved over it.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged.
    // Inlined into its caller: with `host-tuned` the supports, just built there, and the report
    // are then not read back from memory at once, which stalls an x86 core; on a Cortex-M4F the
    // report is not copied out of a call (measured: 100 instructions a step).
    #[inline(always)]
    #[allow(clippy::inline_always)] // measured, as said above
    pub fn step(&mut self, supports: &[Support<T>; K]) -> Result<StepReport<T, K>, StepError> {
        // Without `host-tuned`, a model none of whose steps can have several answers steps
        // without the rule's code in its way (measured: a runtime test inside the one step cost
        // the Cortex-M4F 2 % a step). With it, one step tests at run time (measured: a branch to
        // two copies cost the host 8 %, the report no longer kept out of memory).
        #[cfg(feature = "host-tuned")]
        return self.step_with_rule::<true>(supports);
        #[cfg(not(feature = "host-tuned"))]
        if cfg!(feature = "fallback") && (self.detector.possible() || self.both_stuck()) {
            self.step_flagging(supports)
        } else {
            self.step_with_rule::<false>(supports)
        }
    }

    /// [`Self::step`] of a model whose steps may have several answers: out of line, so that the
    /// other models' step is the one it always was.
    #[cfg(not(feature = "host-tuned"))]
    #[inline(never)]
    fn step_flagging(&mut self, supports: &[Support<T>; K]) -> Result<StepReport<T, K>, StepError> {
        self.step_with_rule::<true>(supports)
    }

    /// `true` for a model of two contacts both sticking after the last step: its next step may
    /// end with both loaded and sticking, four unknowns in three coordinates, whose load the rule
    /// decides (`docs/formulation.md`, "The load: the least norm"); it takes the rule's copy of the
    /// step, so that the other steps' copy has none of that code (measured on the Cortex-M4F: the
    /// test and an out-of-line call in the one copy cost every step 30 to 75 instructions).
    #[cfg(not(feature = "host-tuned"))]
    #[inline]
    fn both_stuck(&self) -> bool {
        K == 2 && self.modes.iter().all(|m| *m == ContactMode::Sticking)
    }

    /// `true` when contact `i` was left touching and slipping but carrying nothing by the last
    /// step's load ([`Self::decide_load`], three or more contacts).
    #[inline]
    #[cfg_attr(not(feature = "fallback"), allow(clippy::unused_self))] // none is left without it
    fn slips_unloaded(&self, i: usize) -> bool {
        #[cfg(feature = "fallback")]
        return K >= 3 && self.slipping_unloaded[i];
        #[cfg(not(feature = "fallback"))]
        {
            let _ = i;
            false
        }
    }

    /// [`Self::step`], with the rule's detection when `RULE` (`docs/formulation.md`, "One answer:
    /// the rule").
    #[allow(clippy::too_many_lines)] // the paper's step in order: assemble, solve, check, integrate, classify
    #[inline(always)] // into `step` (the model without the rule's steps) and `step_flagging`
    #[allow(clippy::inline_always)]
    fn step_with_rule<const RULE: bool>(
        &mut self,
        supports: &[Support<T>; K],
    ) -> Result<StepReport<T, K>, StepError> {
        let s = self.settings;
        let h = s.step;
        let mut support_velocity = [[T::zero(); 2]; K];
        let mut mu = [T::zero(); K];
        for i in 0..K {
            let c = &self.contacts[i];
            if !supports[i].fits(&c.feature) {
                return Err(StepError::SupportMismatch(i as u8));
            }
            if let Support::Line { .. } = supports[i]
                && !supports[i].is_well_formed()
            {
                return Err(StepError::MalformedSupport(i as u8));
            }
            // The position enters as `p - p`, exactly 0 when it is finite and NaN when not: a
            // non-finite position (which only the next step's frames would read, and then as an
            // inactive contact) makes this step's data non-finite, refused as a non-finite
            // velocity is (`LcpError::NonFiniteInput`), with no branch of its own.
            let (p, u) = (supports[i].position(), supports[i].velocity());
            support_velocity[i] = [u[0] + zero_if_finite(p[0]), u[1] + zero_if_finite(p[1])];
            mu[i] = if self.modes[i].is_sliding() || (RULE && self.slips_unloaded(i)) {
                c.mu_kinetic
            } else {
                c.mu_static
            };
        }
        let v_free = [self.state.vx, self.state.vy - h * s.gravity, self.state.omega];
        // The round-off of a gap (`normal_bias`): a few eps of the positions it comes from.
        let gap_round_off =
            T::of(4.0) * T::EPS * (self.state.x.abs_exact() + self.state.y.abs_exact() + self.size);
        let inputs = StepInputs {
            frames: &self.frames,
            mu,
            support_velocity,
            v_free,
            m_inv: self.m_inv,
            h,
            gravity: s.gravity,
            gap_round_off,
        };
        if RULE {
            self.factored.refill_out_of_line(&inputs);
        } else {
            self.factored.refill(&inputs);
        }
        let factored = &self.factored;
        // The reduced layout's answer, and the full layout's when it is used.
        let (mut z, mut w) = ([T::zero(); N], [T::zero(); N]);
        #[cfg_attr(not(feature = "fallback"), allow(unused_mut, unused_variables))]
        let (mut z_full, mut w_full) = ([T::zero(); NF], [T::zero(); NF]);
        let mut v_plus = v_free;
        let reduced = N != NF;
        // Whether the step may have several answers: the rule applies (`docs/formulation.md`,
        // "One answer: the rule").
        let flagged =
            RULE && cfg!(feature = "fallback") && self.detector.possible() && Detector::flags(&inputs);
        let mut rule = Resolution::default();
        #[cfg_attr(not(feature = "fallback"), allow(unused_mut))]
        let (mut pivots, mut warm_start_used, mut residual, mut path, solved) = match solve(
            factored,
            self.basis,
            &mut self.plan,
            &self.solver,
            &mut self.stats.paths,
            &mut self.stats.regularized_solves,
            &mut z,
            &mut w,
        ) {
            Ok(sol) => {
                self.basis = sol.basis;
                v_plus = sol.v_plus;
                (sol.pivots, sol.warm_start_used, sol.residual, sol.path, true)
            }
            // On a step that may have several answers, the rule's enumeration answers when the
            // solver's paths did not (each of its answers is verified as theirs are).
            Err(e) => match flagged
                .then(|| {
                    solve_by_rule(
                        factored,
                        Detector::rule(&inputs, self.size),
                        self.solver.tolerance(),
                        &mut z,
                        &mut w,
                        |z, w, v| self.layout_admits(&inputs, &support_velocity, z, w, v),
                    )
                })
                .flatten()
            {
                Some((sol, r)) => {
                    rule = r;
                    self.basis = sol.basis;
                    v_plus = sol.v_plus;
                    (sol.pivots, sol.warm_start_used, sol.residual, sol.path, true)
                }
                // A reduced LCP may have no solution when a dropped direction is needed: that
                // too is the reduced model leaving its range.
                None if reduced => {
                    self.basis = Basis::all_w();
                    (e.pivots(), false, T::zero(), SolvePath::Lemke, false)
                }
                None => return Err(StepError::Solver(e)),
            },
        };
        // The step's velocity scale, for the reduced check's round-off and the precision flag.
        let mut speed = velocity_scale(&support_velocity, &v_plus, self.size);
        let needed = if solved { self.dropped_direction_needed(&inputs, &z, &w, speed) } else { None };
        // The rule, where the step may have several answers: among the solutions that need no
        // dropped direction (one that does goes to the full layout, which applies the rule again).
        if flagged && solved && needed.is_none() && !rule.enumerated {
            let mut sol = Solved { v_plus, basis: self.basis, pivots, warm_start_used, residual, path };
            rule = resolve(
                factored,
                Detector::rule(&inputs, self.size),
                self.solver.tolerance(),
                &mut sol,
                &mut z,
                &mut w,
                |z, w, v| self.layout_admits(&inputs, &support_velocity, z, w, v),
            );
            (self.basis, v_plus, residual) = (sol.basis, sol.v_plus, sol.residual);
            speed = velocity_scale(&support_velocity, &v_plus, self.size);
        }
        let full_layout_used = reduced && (!solved || needed.is_some());
        #[cfg_attr(not(feature = "fallback"), allow(unused_mut))]
        let mut slips = factored.slips(&z, &w);
        if full_layout_used {
            self.stats.reduced_check_fired += 1;
            #[cfg(feature = "fallback")]
            {
                let full = FactoredLcp::new(&self.full, &inputs);
                let mut wide = Basis::<NF>::all_w();
                for (j, &k) in self.to_full.iter().enumerate() {
                    wide.set_z_basic(k, self.basis.is_z_basic(j));
                }
                // The contact that needed its dropped direction tries it first.
                if let Some((i, dropped)) = needed {
                    wide = full.with_direction(wide, i, dropped);
                }
                let mut by_rule = false;
                let mut sol = match solve(
                    &full,
                    wide,
                    &mut PlanCache::<K>::default(),
                    &Lemke::<T, NF>::new(),
                    &mut self.stats.paths,
                    &mut self.stats.regularized_solves,
                    &mut z_full,
                    &mut w_full,
                ) {
                    Ok(sol) => sol,
                    Err(e) if flagged => {
                        let rule_full = Detector::rule(&inputs, self.size);
                        let found = solve_by_rule(
                            &full,
                            rule_full,
                            self.solver.tolerance(),
                            &mut z_full,
                            &mut w_full,
                            |_, _, _| true,
                        );
                        let (sol, r) = found.ok_or(StepError::Solver(e))?;
                        (rule.enumerated, by_rule) = (true, true);
                        rule.ambiguous |= r.ambiguous;
                        sol
                    }
                    Err(e) => return Err(StepError::Solver(e)),
                };
                if flagged && !by_rule {
                    let r = resolve(
                        &full,
                        Detector::rule(&inputs, self.size),
                        self.solver.tolerance(),
                        &mut sol,
                        &mut z_full,
                        &mut w_full,
                        |_, _, _| true,
                    );
                    rule.enumerated |= r.enumerated;
                    rule.ambiguous |= r.ambiguous;
                    rule.changed |= r.changed;
                }
                pivots += sol.pivots;
                residual = sol.residual;
                warm_start_used = sol.warm_start_used;
                path = sol.path;
                slips = full.slips(&z_full, &w_full);
                v_plus = sol.v_plus;
            }
            #[cfg(not(feature = "fallback"))]
            {
                log_warn!(
                    "reduced layout left its range at t={}: no fallback compiled in",
                    self.time.as_f32()
                );
                return Err(StepError::ReducedModelLeftRange);
            }
        }
        // Integrate (eq. 14): q+ = q + h v+, compensated sums; refused when not finite.
        let mut state = self.state;
        let mut carry = self.carry;
        state.vx = v_plus[0];
        state.vy = v_plus[1];
        state.omega = v_plus[2];
        for (k, coordinate) in [&mut state.x, &mut state.y, &mut state.theta].into_iter().enumerate() {
            compensated_add(coordinate, &mut carry[k], h * v_plus[k]);
        }
        if !state.is_finite() {
            return Err(StepError::NonFinite);
        }
        let round_off_limited = speed > self.round_off_speed;
        let time = self.next_time();
        self.stats.steps += 1;
        self.stats.warm_starts += u64::from(warm_start_used);
        // Rare: branches, not three 64-bit additions of 0 (each a load, two adds and a store on a
        // 32-bit core).
        if round_off_limited {
            self.stats.round_off_limited += 1;
        }
        if flagged {
            self.stats.count_rule(rule);
        }
        if pivots > 0 {
            self.stats.count_pivots(pivots);
        }

        // Impulses (z is per unit mass) and modes after the step.
        let (normal, friction, pn) = if full_layout_used {
            impulses(&self.full, &z_full, self.mass)
        } else {
            impulses(&self.layout, &z, self.mass)
        };
        let impulse_floor = self.impulse_floor;
        let mut contacts = [ContactReport {
            mode: ContactMode::Separated,
            previous_mode: ContactMode::Separated,
            normal_impulse: T::zero(),
            friction_impulse: T::zero(),
            along: T::zero(),
        }; K];
        for i in 0..K {
            let f = &self.frames[i];
            let mode = if f.active && pn[i] > impulse_floor {
                ContactMode::from_slip(slips[i], s.stick_speed)
            } else {
                ContactMode::Separated
            };
            contacts[i] = ContactReport {
                mode,
                previous_mode: self.modes[i],
                normal_impulse: normal[i],
                friction_impulse: friction[i],
                along: f.along,
            };
            self.modes[i] = mode;
        }
        // The load, where the contacts leave it open (`docs/formulation.md`, "The load: the least
        // norm"): on a model of three or more contacts every step looks; on one of two, a step
        // whose contacts both carry load and stick (four unknowns in three coordinates), in closed
        // form ([`Self::split_two_sticking`]), in the rule's copy of the step (without
        // `host-tuned`, taken after a step that left both sticking: `Self::both_stuck`).
        #[cfg(feature = "fallback")]
        if RULE && (K >= 3 || (K == 2 && contacts.iter().all(|c| c.mode == ContactMode::Sticking))) {
            let rows: &[T] = if full_layout_used { &w_full } else { &w };
            let v_plus = [state.vx, state.vy, state.omega];
            if K >= 3 {
                self.decide_load(&support_velocity, &mu, &v_plus, rows, &slips, &mut contacts)?;
            } else {
                let pair = [contacts[0], contacts[1 % K]];
                if let Some(split) =
                    self.split_two_sticking(supports, v_plus, [slips[0], slips[1 % K]], pair)?
                {
                    (contacts[0], contacts[1 % K]) = (split[0], split[1]);
                }
            }
        }
        self.state = state;
        self.carry = carry;
        self.time = time;
        self.update_frames(supports);
        self.supports = *supports;
        Ok(StepReport {
            time,
            state,
            contacts,
            pivots,
            warm_start_used,
            path,
            full_layout_used,
            residual,
            round_off_limited,
        })
    }

    /// `true` when this layout may answer with `z`, `w` and `v+ = v`: always in the full layout;
    /// in a reduced one when no dropped friction direction is needed (the rule's candidates are
    /// held to the same check as the solver's answer).
    fn layout_admits(
        &self,
        inputs: &StepInputs<'_, T, K>,
        support_velocity: &[[T; 2]; K],
        z: &[T; N],
        w: &[T; N],
        v: &[T; 3],
    ) -> bool {
        N == NF
            || self
                .dropped_direction_needed(inputs, z, w, velocity_scale(support_velocity, v, self.size))
                .is_none()
    }

    /// The reduced layout's check (`docs/formulation.md`, "Reduced friction layouts"): for each
    /// active contact that keeps one direction `s` of two, the row of the dropped direction,
    /// `-s (W_d^T v+ - d . u) + sigma`, must not be negative beyond round-off: `64 N eps` of this
    /// step's velocities (the fastest support's and the body's), and never beyond `stick_speed`,
    /// the slip at which the contact would be classified sliding. Not of a scene-wide speed: once
    /// a fast finger stops, `eps` of its former speed exceeds the slow slips the check must see.
    ///
    /// Except where `sigma` is free: when the kept direction carries no impulse and the cone row
    /// `mu p_n - p_f` is zero too (`mu = 0`, or no normal impulse), `sigma` can be raised to
    /// `|W_d^T v+ - d . u|` without breaking any complementarity, and the reduced answer (same
    /// impulses) extends to a solution of the full LCP (the frictionless meter stick's every
    /// step is such a case).
    ///
    /// Returns the first contact that needs its dropped direction, and that direction.
    fn dropped_direction_needed(
        &self,
        inputs: &StepInputs<'_, T, K>,
        z: &[T; N],
        w: &[T; N],
        speed: T,
    ) -> Option<(usize, Direction)> {
        let s = &self.settings;
        let speed_scale = speed + s.gravity * s.step;
        let tol = T::of(64.0 * N as f64) * T::EPS * speed_scale + T::TINY;
        // The dropped row's value is the contact's slip in the dropped direction (`sigma` is 0 while
        // the kept direction carries no impulse and the cone row is positive). A slip beyond
        // `stick_speed` is one the modes see: the contact would be classified sliding that way with
        // no friction against it. So the round-off floor may not hide it (in f32 `64 N eps V` is
        // 3e-5 m/s at V = 0.6 m/s, above the default 1e-5).
        let slip_tol = min(tol, s.stick_speed);
        for i in 0..K {
            let Some((j, kept)) = self.kept_alone[i] else { continue };
            let f = &inputs.frames[i];
            if !f.active || j >= N {
                continue;
            }
            if z[j] <= tol && inputs.mu[i] * z[i] <= tol {
                continue; // sigma is free
            }
            // The kept row is `w_j = s g + sigma` (`g = W_d^T v+ - d . u`); the dropped one is
            // `-s g + sigma = 2 sigma - w_j`.
            let sigma = Layout::<K, N>::SIGMA_START + i;
            if sigma < N && z[sigma] + z[sigma] - w[j] < -slip_tol {
                return Some((i, kept.opposite()));
            }
        }
        None
    }
}

/// A step's velocity scale `V`: the fastest support's speed plus the body's (`|vx| + |vy| +
/// |omega| size`), the size of the slips in its LCP.
#[inline]
fn velocity_scale<T: Real, const K: usize>(support_velocity: &[[T; 2]; K], v: &[T; 3], size: T) -> T {
    let mut support_speed = T::zero();
    for u in support_velocity {
        support_speed = max(support_speed, u[0].abs_exact() + u[1].abs_exact());
    }
    support_speed + v[0].abs_exact() + v[1].abs_exact() + (v[2] * size).abs_exact()
}

/// Each contact's normal and net friction impulse (physical, N s) and normal impulse per unit
/// mass, from `z` (per unit mass) in `layout`'s order (friction rows contact by contact, `+d`
/// before `-d`).
// Inlined into the step without `host-tuned`: out of line its three arrays are returned through
// memory and copied (measured on the Cortex-M4F: 35 instructions a step).
#[cfg_attr(not(feature = "host-tuned"), inline(always))]
#[allow(clippy::inline_always)] // measured, as said above
fn impulses<T: Real, const K: usize, const M: usize>(
    layout: &Layout<K, M>,
    z: &[T; M],
    mass: T,
) -> ([T; K], [T; K], [T; K]) {
    let mut normal = [T::zero(); K];
    let mut friction = [T::zero(); K];
    let mut per_unit_mass = [T::zero(); K];
    let mut j = K;
    for i in 0..K {
        per_unit_mass[i] = z[i];
        normal[i] = z[i] * mass;
        for direction in [Direction::Plus, Direction::Minus] {
            if layout.tangents()[i].keeps(direction) && j < M {
                friction[i] += sign::<T>(direction) * z[j] * mass;
                j += 1;
            }
        }
    }
    (normal, friction, per_unit_mass)
}

/// A step count for [`Real::of_count`], saturating at `u32::MAX` (4.3e9 steps: 50 days at
/// h = 1 ms; f32 time is exact only to 2^24 steps anyway).
fn count_u32(n: u64) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}
