//! [`Stepper`]: one rigid body against `K` supports, stepped by an LCP per step.
//!
//! One [`Stepper::step`] (`docs/formulation.md`, "One time step"):
//!
//! 1. the contact frames of the step's start (computed at the end of the previous step) and the
//!    supports' velocities over the step, given by the scene;
//! 2. each contact's friction coefficient from its mode after the previous step (`mu_s` while
//!    sticking or separated, `mu_k` while sliding);
//! 3. the LCP of eq. 18 for the solved [`Layout`], solved by [`Lemke`] warm-started from the
//!    previous step's basis;
//! 4. for a reduced layout, the dropped directions checked; when one is needed (or the reduced LCP
//!    has no solution) the step is solved again in the full layout, warm-started from the reduced
//!    basis mapped into it (feature `fallback`; without it the step fails with
//!    [`StepError::ReducedModelLeftRange`] and no full-layout code is linked);
//! 5. `v+ = v~ + M^-1 W z` (eq. 16) and `q+ = q + h v+` with compensated sums (eq. 14), refused
//!    when not finite;
//! 6. each contact's mode after the step, the [`StepReport`], and the frames for the next step.
//!
//! A failed step leaves the state as it was and returns a [`StepError`]; nothing here panics.

use super::assemble::{StepInputs, StepLcp, fill_from_factored, sign};
use super::body::{Body, BodyState};
use super::contact::{Contact, ContactFrame, ContactMode, Pose, Support};
use super::factored::{CANDIDATES, Declined, FactoredLcp, PlanCache, basis_of_modes};
use super::layout::{Direction, Layout, Variable};
use crate::lcp::{Basis, LcpError, Lemke};
use crate::params::ParamError;
use crate::real::{Real, max, zero_if_finite};

/// The stepper's numbers, besides the body and its contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Settings<T> {
    /// Time step `h` (s, > 0).
    pub step: T,
    /// Gravity `g` along `-y` (m/s^2, >= 0).
    pub gravity: T,
    /// A touching contact whose slip speed is at most this sticks (m/s, >= 0).
    pub stick_speed: T,
}

/// What the stepper moves: the body, its contacts and the numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model<T, const K: usize> {
    /// The body.
    pub body: Body<T>,
    /// Its contacts, in the order of the LCP's variables.
    pub contacts: [Contact<T>; K],
    /// Step, gravity, thresholds.
    pub settings: Settings<T>,
}

/// Why a step failed. The state is that before the step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum StepError {
    /// The step's LCP could not be solved.
    Solver(LcpError),
    /// The state after the step would not be finite.
    NonFinite,
    /// A reduced layout's dropped direction was needed and the `fallback` feature is off.
    ReducedModelLeftRange,
    /// A support cannot carry its contact's feature (the contact's index).
    SupportMismatch(u8),
    /// A line's normal is not a unit vector ([`Support::is_well_formed`]; the contact's index).
    /// (A support whose position or velocity is not finite fails the step with
    /// [`LcpError::NonFiniteInput`].)
    MalformedSupport(u8),
}

impl core::fmt::Display for StepError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Solver(e) => write!(f, "solver: {e}"),
            Self::NonFinite => f.write_str("the state became non-finite"),
            Self::ReducedModelLeftRange => {
                f.write_str("the reduced friction model left its range (no fallback compiled in)")
            }
            Self::SupportMismatch(i) => write!(f, "the support of contact {i} cannot carry its feature"),
            Self::MalformedSupport(i) => {
                write!(f, "the line supporting contact {i} has a normal that is not a unit vector")
            }
        }
    }
}

impl core::error::Error for StepError {}

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
    /// The contact's coordinate along its tangent at the step's start ([`ContactFrame::along`]).
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

/// Which path answered a step's LCP (`docs/formulation.md`, "Solving a step"). Every path's
/// answer is verified; a path that cannot answer hands the step to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SolvePath {
    /// `q >= 0`: no impulse is needed, `z = 0` (as Lemke's method answers it, before any pivot).
    Free,
    /// The previous step's basis, solved in the body's coordinates ([`FactoredLcp`]).
    Warm,
    /// One of the bases next to the previous one (one contact's mode changed), solved the same way.
    Candidate,
    /// Lemke's method on the assembled LCP, warm-started from the previous basis: the solver of
    /// record, for whatever the other paths do not answer.
    Lemke,
}

impl SolvePath {
    /// Every path, in the order they are tried.
    pub const ALL: [Self; 4] = [Self::Free, Self::Warm, Self::Candidate, Self::Lemke];

    /// A short stable name: `free`, `warm`, `candidate`, `lemke`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Free => "free",
            Self::Warm => "warm",
            Self::Candidate => "candidate",
            Self::Lemke => "lemke",
        }
    }
}

/// How many solves each [`SolvePath`] answered over a run (a step that fell back to the full
/// layout counts two solves), and how many candidate bases were tried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PathCounts {
    /// Answered with `z = 0`.
    pub free: u64,
    /// Answered by the previous basis.
    pub warm: u64,
    /// Answered by a candidate basis.
    pub candidate: u64,
    /// Answered by Lemke's method (or failed there).
    pub lemke: u64,
    /// Candidate bases solved, answered or not.
    pub candidates_tried: u64,
}

impl PathCounts {
    /// The solves `path` answered.
    #[must_use]
    pub const fn of(&self, path: SolvePath) -> u64 {
        match path {
            SolvePath::Free => self.free,
            SolvePath::Warm => self.warm,
            SolvePath::Candidate => self.candidate,
            SolvePath::Lemke => self.lemke,
        }
    }

    fn count(&mut self, path: SolvePath) {
        match path {
            SolvePath::Free => self.free += 1,
            SolvePath::Warm => self.warm += 1,
            SolvePath::Candidate => self.candidate += 1,
            SolvePath::Lemke => self.lemke += 1,
        }
    }
}

/// Counters over a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RunStats {
    /// Steps taken.
    pub steps: u64,
    /// Complementary pivots, summed.
    pub pivots: u64,
    /// Most pivots in one step.
    pub max_pivots: u32,
    /// Steps whose answer came from the warm-start basis.
    pub warm_starts: u64,
    /// Steps where a reduced layout's dropped direction was needed.
    pub reduced_check_fired: u64,
    /// Solves answered by the solver's regularised retry after a round-off ray
    /// ([`crate::lcp::LcpSolution::regularized`]).
    pub regularized_solves: u64,
    /// Steps whose impulses were resolved only to more than [`ROUND_OFF_LIMIT`] of their size
    /// ([`StepReport::round_off_limited`]).
    pub round_off_limited: u64,
    /// Solves per path.
    pub paths: PathCounts,
}

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
    /// the same LCP, and a floor of `eps V` called a contact carrying 1/40 of a 1 m/s scene's
    /// weight at h = 1e-5 s separated (and its next step used `mu_s`).
    impulse_floor: T,
    /// A step whose velocity scale exceeds this is [`StepReport::round_off_limited`]:
    /// `ROUND_OFF_LIMIT g h / eps` (infinite without gravity: no impulse scale).
    round_off_speed: T,
    layout: Layout<K, N>,
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    full: Layout<K, NF>,
    /// Where each solved variable sits in the full layout.
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
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
    /// from the store buffer). Out of line on a microcontroller: one copy for `new` and `step`.
    #[cfg_attr(target_os = "none", inline(never))]
    #[cfg_attr(not(any(target_os = "none", target_family = "wasm")), inline(always))]
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
    // Inlined into its caller on the host (not on a microcontroller, nor in the page's smaller
    // modules): the supports, just built there, and the report are then not read back from memory
    // at once, which stalls an x86 core.
    #[allow(clippy::too_many_lines)] // the paper's step in order: assemble, solve, check, integrate, classify
    #[cfg_attr(not(any(target_os = "none", target_family = "wasm")), inline(always))]
    #[allow(clippy::inline_always)] // measured, as said above
    pub fn step(&mut self, supports: &[Support<T>; K]) -> Result<StepReport<T, K>, StepError> {
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
            // velocity is ([`LcpError::NonFiniteInput`]), with no branch of its own.
            let (p, u) = (supports[i].position(), supports[i].velocity());
            support_velocity[i] = [u[0] + zero_if_finite(p[0]), u[1] + zero_if_finite(p[1])];
            mu[i] = if self.modes[i].is_sliding() { c.mu_kinetic } else { c.mu_static };
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
        self.factored.refill(&inputs);
        let factored = &self.factored;
        // The reduced layout's answer, and the full layout's when it is used.
        let (mut z, mut w) = ([T::zero(); N], [T::zero(); N]);
        #[cfg_attr(not(feature = "fallback"), allow(unused_mut, unused_variables))]
        let (mut z_full, mut w_full) = ([T::zero(); NF], [T::zero(); NF]);
        let mut v_plus = v_free;
        let reduced = N != NF;
        #[cfg_attr(not(feature = "fallback"), allow(unused_mut))]
        let (mut pivots, mut warm_start_used, mut residual, mut path, solved) = match solve(
            factored,
            self.basis,
            &mut self.plan,
            &self.solver,
            &mut self.stats,
            &mut z,
            &mut w,
        ) {
            Ok(sol) => {
                self.basis = sol.basis;
                v_plus = sol.v_plus;
                (sol.pivots, sol.warm_start_used, sol.residual, sol.path, true)
            }
            // A reduced LCP may have no solution when a dropped direction is needed: that too
            // is the reduced model leaving its range.
            Err(e) if reduced => {
                self.basis = Basis::all_w();
                (e.pivots(), false, T::zero(), SolvePath::Lemke, false)
            }
            Err(e) => return Err(StepError::Solver(e)),
        };
        // The step's velocity scale, for the reduced check's round-off and the precision flag.
        let speed = velocity_scale(&support_velocity, &v_plus, self.size);
        let needed = if solved { self.dropped_direction_needed(&inputs, &z, &w, speed) } else { None };
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
                let sol = solve(
                    &full,
                    wide,
                    &mut PlanCache::<K>::default(),
                    &Lemke::<T, NF>::new(),
                    &mut self.stats,
                    &mut z_full,
                    &mut w_full,
                )
                .map_err(StepError::Solver)?;
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
            let increment = h * v_plus[k] - carry[k];
            let sum = *coordinate + increment;
            carry[k] = (sum - *coordinate) - increment;
            *coordinate = sum;
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
        if pivots > 0 {
            self.stats.pivots += u64::from(pivots);
            self.stats.max_pivots = self.stats.max_pivots.max(pivots);
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

    /// The reduced layout's check (`docs/formulation.md`, "Reduced friction layouts"): for each
    /// active contact that keeps one direction `s` of two, the row of the dropped direction,
    /// `-s (W_d^T v+ - d . u) + sigma`, must not be negative beyond round-off: `64 N eps` of this
    /// step's velocities (the fastest support's and the body's). Not of a scene-wide speed: after
    /// a 10 m/s finger stopped, a tolerance of `eps x 10 m/s` let an f32 rod slide the wrong way
    /// on the kept direction for 500 steps (2 mm from the full layout; `host-sim envelope`).
    ///
    /// Except where `sigma` is free: when the kept direction carries no impulse and the cone row
    /// `mu p_n - p_f` is zero too (`mu = 0`, or no normal impulse), `sigma` can be raised to
    /// `|W_d^T v+ - d . u|` without breaking any complementarity, and the reduced answer (same
    /// impulses) extends to a solution of the full LCP. (Without this exception the frictionless
    /// meter stick fell back to the full layout in 441 of 3,998 steps; `host-sim stress`.)
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
            if sigma < N && z[sigma] + z[sigma] - w[j] < -tol {
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

/// One layout's verified answer ([`solve`]); `z` and `w` are written into the caller's arrays.
struct Solved<T: Real, const M: usize> {
    v_plus: [T; 3],
    basis: Basis<M>,
    pivots: u32,
    warm_start_used: bool,
    residual: T,
    path: SolvePath,
}

/// Solves the step's LCP `factored` (`docs/formulation.md`, "Solving a step"): `z = 0` when
/// `q >= 0`; else the previous basis `warm` in the body's coordinates; else its neighbours the same
/// way; else Lemke's method on the assembled LCP, warm-started from `warm`. Every answer is
/// verified; `z` and `w` receive it. Counts the path (and each candidate tried) in `stats`.
/// `plan` keeps the warm basis' unknowns from one call to the next ([`FactoredLcp`]'s layout must
/// be the same each call; a default one for a one-off).
fn solve<T: Real, const K: usize, const M: usize>(
    factored: &FactoredLcp<T, K, M>,
    warm: Basis<M>,
    plan: &mut PlanCache<K>,
    solver: &Lemke<T, M>,
    stats: &mut RunStats,
    z: &mut [T; M],
    w: &mut [T; M],
) -> Result<Solved<T, M>, LcpError> {
    if !factored.is_finite() {
        return Err(LcpError::NonFiniteInput);
    }
    if factored.is_free() {
        *z = [T::zero(); M];
        *w = *factored.q();
        stats.paths.count(SolvePath::Free);
        return Ok(Solved {
            v_plus: *factored.v_free(),
            basis: Basis::all_w(),
            pivots: 0,
            warm_start_used: false,
            residual: T::zero(),
            path: SolvePath::Free,
        });
    }
    match factored.solve_basis_cached_into(warm, plan, solver.tolerance(), z, w) {
        Ok((v_plus, residual)) => {
            stats.paths.count(SolvePath::Warm);
            Ok(Solved {
                v_plus,
                basis: warm,
                pivots: 0,
                warm_start_used: true,
                residual,
                path: SolvePath::Warm,
            })
        }
        Err(why) => solve_cold(factored, warm, why, solver, stats, z, w),
    }
}

/// [`solve`] after the previous basis failed with `why`: its neighbours, then Lemke's method. Out
/// of line, so that the warm path the most steps take stays small.
#[cold]
#[inline(never)]
fn solve_cold<T: Real, const K: usize, const M: usize>(
    factored: &FactoredLcp<T, K, M>,
    warm: Basis<M>,
    why: Declined,
    solver: &Lemke<T, M>,
    stats: &mut RunStats,
    z: &mut [T; M],
    w: &mut [T; M],
) -> Result<Solved<T, M>, LcpError> {
    let tolerance = solver.tolerance();
    let answer = (0..CANDIDATES * K).find_map(|k| {
        let basis = factored.candidate(warm, why, k)?;
        stats.paths.candidates_tried += 1;
        factored.solve_basis_into(basis, tolerance, z, w).ok().map(|(v_plus, residual)| Solved {
            v_plus,
            basis,
            pivots: 0,
            warm_start_used: false,
            residual,
            path: SolvePath::Candidate,
        })
    });
    if let Some(answer) = answer {
        stats.paths.count(SolvePath::Candidate);
        return Ok(answer);
    }
    stats.paths.count(SolvePath::Lemke);
    let mut lcp = StepLcp::zeros();
    fill_from_factored(factored, &mut lcp);
    let sol = solver.solve_from_basis(&lcp.lcp, warm)?;
    stats.regularized_solves += u64::from(sol.regularized);
    for j in 0..M {
        z[j] = sol.z[j];
        w[j] = sol.w[j];
    }
    Ok(Solved {
        v_plus: factored.velocity_after(z),
        basis: sol.basis,
        pivots: sol.pivots,
        warm_start_used: sol.warm_start_used,
        residual: sol.residual,
        path: SolvePath::Lemke,
    })
}

/// A step count for [`Real::of_count`], saturating at `u32::MAX` (4.3e9 steps: 50 days at
/// h = 1 ms; f32 time is exact only to 2^24 steps anyway).
fn count_u32(n: u64) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// The set-up checks of [`Stepper::new`].
fn validate<T: Real, const K: usize>(
    model: &Model<T, K>,
    start: &BodyState<T>,
    supports: &[Support<T>; K],
) -> Result<(), ParamError> {
    use crate::params::{Check, check_fields};
    let (b, s) = (&model.body, &model.settings);
    check_fields(&[
        ("width", b.width, Check::Positive),
        ("height", b.height, Check::NonNegative),
        ("mass", b.mass, Check::Positive),
        ("inertia", b.inertia, Check::Positive),
        ("step", s.step, Check::Positive),
        ("gravity", s.gravity, Check::NonNegative),
        ("stick_speed", s.stick_speed, Check::NonNegative),
    ])?;
    for (i, c) in model.contacts.iter().enumerate() {
        check_fields(&[
            ("mu_static", c.mu_static, Check::NonNegative),
            ("mu_kinetic", c.mu_kinetic, Check::NonNegative),
        ])?;
        if c.mu_kinetic > c.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if let super::Feature::Point(p) = c.feature
            && !(p[0].finite() && p[1].finite())
        {
            return Err(ParamError::NonFinite("feature"));
        }
        if let super::Feature::Round(radius) = c.feature {
            check_fields(&[("radius", radius, Check::Positive)])?;
        }
        let sup = &supports[i];
        if !sup.fits(&c.feature) {
            return Err(ParamError::SupportMismatch(i as u8));
        }
        let mut values = [
            sup.position()[0],
            sup.position()[1],
            sup.velocity()[0],
            sup.velocity()[1],
            T::zero(),
            T::zero(),
        ];
        if let Support::Line { normal, .. } = sup {
            values[4] = normal[0];
            values[5] = normal[1];
        }
        if !values.iter().all(|v| v.finite()) {
            return Err(ParamError::NonFinite("support"));
        }
        if !sup.is_well_formed() {
            return Err(ParamError::OutOfRange("support")); // a line's normal not a unit vector
        }
    }
    if !start.is_finite() {
        return Err(ParamError::NonFiniteState);
    }
    Ok(())
}
