//! [`Stepper`]: `B` boxes on each other and on a table, one LCP per step solved by Lemke's method
//! (`docs/formulation.md`, "Several bodies", "One step").

use nalgebra::{SMatrix, SVector};

use super::geometry::{CornerFrame, Pair, Table, pair_frames, slip};
use crate::lcp::{Basis, Lcp, LcpError, LcpSolution, Lemke, verify};
use crate::params::ParamError;
use crate::planar::assemble::normal_bias;
use crate::planar::{Body, BodyState, Checksum, ContactMode};
use crate::real::Real;

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

/// The bodies, the table, the `P` resting pairs and the external forces of a system of `B` boxes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct System<T, const B: usize, const P: usize> {
    /// The boxes, in body order (body 0's mass is the reference mass of the LCP).
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
    /// `(1/h) sum +-(p_n n + p_f d)`. One corner's share is never reported (it is not decided).
    pub interface_forces: [[T; 2]; P],
    /// Each candidate's mode after the step.
    pub modes: [[ContactMode; 4]; P],
    /// Active candidates this step (the LCP has `4` rows for each).
    pub active: u8,
    /// Lemke pivots spent (0 when the warm basis solved directly).
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
    /// Steps the warm basis solved without a pivot.
    pub warm_direct: u32,
    /// Lemke pivots over the run.
    pub pivots: u64,
    /// The most pivots of one step.
    pub max_pivots: u32,
    /// The most active candidates of one step.
    pub max_active: u8,
}

/// The basic variables of one candidate's slot: bit 0 `p_n`, 1 `p_+d`, 2 `p_-d`, 3 `sigma`.
type Pattern = u8;

/// The eight patterns of a contact a retry tries: separated; separated while slipping along `+d`,
/// `-d`; touching without friction; sticking with `p_+d`, `p_-d`; sliding along `+d`, `-d`.
const PATTERNS: [Pattern; 8] = [0b0000, 0b1010, 0b1100, 0b0001, 0b0011, 0b0101, 0b1011, 0b1101];

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
/// solutions. Lemke's method with its lexicographic rule (`core/src/lcp/lemke.rs`) ends on one
/// vertex of that set, verified; a singular warm basis is declined by its direct solve and the
/// method starts cold. What is reported is what every solution shares: velocities, positions and
/// per pair the summed interface force ([`StepReport::interface_forces`]); no corner's share.
/// Where solutions move the bodies differently (the model's "ambiguous" steps), the reference
/// takes the least kinetic energy after the step and this stepper the solution Lemke's method
/// reaches.
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
    stats: Stats,
}

impl<T: Real, const B: usize, const P: usize, const N: usize> Stepper<T, B, P, N> {
    const SIZE_CHECK: () =
        assert!(B > 0 && P > 0 && N >= 4 && N <= 32, "Stepper needs B, P > 0, 4 <= N <= 32");

    /// A stepper at `states` (every body at rest: the modes before the first step are sticking
    /// for an active touching candidate, separated otherwise).
    ///
    /// # Errors
    /// [`ParamError::NonFiniteState`] for a non-finite state, [`ParamError::OutOfRange`]`("pairs")`
    /// for a pair naming a body that does not exist or resting on itself.
    pub fn new(system: System<T, B, P>, states: [BodyState<T>; B]) -> Result<Self, ParamError> {
        let () = Self::SIZE_CHECK;
        if !states.iter().all(BodyState::is_finite) {
            return Err(ParamError::NonFiniteState);
        }
        for pair in &system.pairs {
            let bad_lower = match pair.lower {
                super::Support::Body(s) => usize::from(s) >= B || s == pair.upper,
                super::Support::Table => false,
            };
            if usize::from(pair.upper) >= B || bad_lower {
                return Err(ParamError::OutOfRange("pairs"));
            }
        }
        let m_ref = system.bodies[0].mass;
        let mut m_min = m_ref;
        let mut inverse_mass = [[T::zero(); 3]; B];
        for (i, body) in system.bodies.iter().enumerate() {
            inverse_mass[i] = [m_ref / body.mass, m_ref / body.mass, m_ref / body.inertia];
            if body.mass < m_min {
                m_min = body.mass;
            }
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
            stats: Stats::default(),
        };
        stepper.update_frames();
        for p in 0..P {
            for c in 0..4 {
                let f = &stepper.frames[p][c];
                if f.active && f.gap <= f.touch {
                    stepper.modes[p][c] = ContactMode::Sticking;
                    // The warm start's guess: touching, no friction yet.
                    stepper.patterns[p][c] = 1;
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

    /// Each candidate's geometry now (the next step's frames).
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
        for p in 0..P {
            self.frames[p] = pair_frames(
                &self.system.pairs[p],
                &self.system.bodies,
                &self.states,
                &self.system.table,
                s.margin,
                s.base.step,
            );
        }
    }

    /// The retries after a failed solve (a ray, the pivot cap, an answer that failed
    /// verification). The friction LCP is not copositive-plus, so Lemke's method may end in a ray
    /// although a solution exists: the `sigma` of a contact without normal impulse is unbounded
    /// above (its column touches only its friction rows), a ray of the solution set; and a long
    /// pivot sequence in f32 can lose the precision its answer is verified to.
    ///
    /// 1. Each cone row's `q` is opened by `sqrt(eps) ||q||_inf`; the basis Lemke's method ends on
    ///    there is solved on the exact problem (its direct solve, verified), or the opened answer
    ///    counts if it verifies against the exact problem (`docs/formulation.md`, "Solving a
    ///    multibody step", 2).
    /// 2. The warm basis with one active contact's pattern replaced by each of the eight of the
    ///    reference's descent (separated; separated while slipping either way; touching without
    ///    friction; sticking either way; sliding either way), each solved directly and then by
    ///    Lemke's method from its tableau.
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
        let mut opened = *lcp;
        let delta = T::EPS.sqrt_libm() * lcp.q_norm_inf();
        for j in 3 * k..4 * k {
            opened.q[j] += delta;
        }
        if let Ok(near) = self.solver.solve(&opened) {
            if let Ok(exact) = self.solver.solve_from_basis(lcp, near.basis) {
                return Ok(exact);
            }
            if verify(lcp, &near.z, self.solver.tolerance()).passed() {
                return Ok(LcpSolution { w: lcp.w_of(&near.z), warm_start_used: false, ..near });
            }
        }
        for j in 0..k {
            let rows = [j, k + 2 * j, k + 2 * j + 1, 3 * k + j];
            for pattern in PATTERNS {
                let mut basis = warm;
                for (bit, &row) in rows.iter().enumerate() {
                    basis.set_z_basic(row, pattern >> bit & 1 == 1);
                }
                if let Ok(solution) = self.solver.solve_from_basis(lcp, basis) {
                    return Ok(solution);
                }
            }
        }
        Err(StepError::Solver(error))
    }

    /// Advances one step: the active candidates' LCP (per unit reference mass), solved by Lemke's
    /// method warm-started from the last step's basic variables, verified; `V+ = v~ + M~ J^T z`,
    /// `q+ = q + h V+` (compensated sums), modes after the step.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged.
    #[allow(clippy::too_many_lines)] // the model's step in order: slots, assemble, solve, integrate, classify
    pub fn step(&mut self) -> Result<StepReport<T, B, P>, StepError> {
        let s = self.system.settings.base;
        let h = s.step;
        // Slots: the active candidates in candidate order.
        let mut slots = [(0usize, 0usize); N];
        let mut k = 0usize;
        let mut active = 0u8;
        for p in 0..P {
            for c in 0..4 {
                if self.frames[p][c].active {
                    active = active.saturating_add(1);
                    if 4 * (k + 1) <= N {
                        slots[k] = (p, c);
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
        // v~ = V + h M^-1 w_ext (eq. 16).
        let m_ref = self.system.bodies[0].mass;
        let mut v_free = [[T::zero(); 3]; B];
        for i in 0..B {
            let (st, f, m) = (&self.states[i], self.system.forces[i], self.system.bodies[i].mass);
            v_free[i] = [st.vx + h * f[0] / m, st.vy + h * (f[1] / m - s.gravity), st.omega];
        }
        // Rows of the 3k impulses: normal of slot j at j, +d at k + 2j, -d at k + 2j + 1.
        // Each row dense in 3B coordinates (zero outside its two bodies): an entry of `J M~ J^T`
        // is then 3B multiply-adds without a branch.
        let mut rows = [[[T::zero(); 3]; B]; N];
        let mut scaled = [[[T::zero(); 3]; B]; N];
        for (j, &(p, c)) in slots[..k].iter().enumerate() {
            // Every slot's (p, c) is below (P, 4) by construction: said so, so that no index below
            // needs a check (no panic path).
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let d = f.tangent;
            rows[j] = f.row(f.normal).dense();
            rows[k + 2 * j] = f.row(d).dense();
            rows[k + 2 * j + 1] = f.row([-d[0], -d[1]]).dense();
        }
        for j in 0..3 * k {
            for body in 0..B {
                for c in 0..3 {
                    scaled[j][body][c] = rows[j][body][c] * self.inverse_mass[body][c];
                }
            }
        }
        let mut a = SMatrix::<T, N, N>::zeros();
        let mut b = SVector::<T, N>::zeros();
        // The 3k impulse rows (3k < N: `min` and `get_mut` say so, no panic path).
        let rows_3k = (3 * k).min(N);
        for i in 0..rows_3k {
            for j in i..rows_3k {
                let e = dense_dot(&rows[i], &scaled[j]);
                for entry in [(i, j), (j, i)] {
                    if let Some(x) = a.get_mut(entry) {
                        *x = e;
                    }
                }
            }
            b[i] = dense_dot(&rows[i], &v_free);
        }
        let mut warm = Basis::<N>::all_w();
        for (j, &(p, c)) in slots[..k].iter().enumerate() {
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            b[j] += normal_bias(f.gap, h, s.gravity, f.gap_round_off);
            let pair = &self.system.pairs[p];
            let mu = if self.modes[p][c].is_sliding() { pair.mu_kinetic } else { pair.mu_static };
            let (plus, minus, sigma) = (k + 2 * j, k + 2 * j + 1, 3 * k + j);
            // All below 4k <= N (`get_mut`: no panic path).
            let cone = [
                ((plus, sigma), T::one()),
                ((minus, sigma), T::one()),
                ((sigma, j), mu),
                ((sigma, plus), -T::one()),
                ((sigma, minus), -T::one()),
            ];
            for (entry, value) in cone {
                if let Some(x) = a.get_mut(entry) {
                    *x = value;
                }
            }
            let pattern = self.patterns[p][c];
            for (bit, row) in [j, plus, minus, sigma].into_iter().enumerate() {
                warm.set_z_basic(row, pattern >> bit & 1 == 1);
            }
        }
        for i in 4 * k..N {
            a[(i, i)] = T::one();
            b[i] = T::one();
        }
        let lcp = Lcp::new(a, b);
        let solution = match self.solver.solve_warm(&lcp, warm) {
            Err(LcpError::NonFiniteInput) => return Err(StepError::Solver(LcpError::NonFiniteInput)),
            Err(error) => self.retry(&lcp, k, warm, error)?,
            Ok(solution) => solution,
        };
        let z = solution.z;
        // V+ = v~ + M~ J^T z.
        let mut v_plus = v_free;
        for j in 0..3 * k {
            if z[j] != T::zero() {
                for body in 0..B {
                    for c in 0..3 {
                        v_plus[body][c] += z[j] * scaled[j][body][c];
                    }
                }
            }
        }
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
        // Modes after the step, interface forces, the next warm patterns.
        let mut modes = [[ContactMode::Separated; 4]; P];
        let mut patterns = [[0; 4]; P];
        let mut impulses = [[T::zero(); 2]; P];
        for (j, &(p, c)) in slots[..k].iter().enumerate() {
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let (plus, minus, sigma) = (k + 2 * j, k + 2 * j + 1, 3 * k + j);
            let mut pattern = 0;
            for (bit, row) in [j, plus, minus, sigma].into_iter().enumerate() {
                pattern |= u8::from(solution.basis.is_z_basic(row)) << bit;
            }
            patterns[p][c] = pattern;
            let (pn, pf) = (z[j], z[plus] - z[minus]);
            if pn > self.impulse_floor {
                modes[p][c] = ContactMode::from_slip(slip(f, &v_plus), s.stick_speed);
            }
            // On the upper body: + for its corners, - for the lower body's.
            let sign = if c < 2 { T::one() } else { -T::one() };
            let impulse = &mut impulses[p];
            impulse[0] += sign * (pn * f.normal[0] + pf * f.tangent[0]);
            impulse[1] += sign * (pn * f.normal[1] + pf * f.tangent[1]);
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
        st.steps += 1;
        st.pivots += u64::from(solution.pivots);
        st.max_pivots = st.max_pivots.max(solution.pivots);
        st.max_active = st.max_active.max(active);
        if solution.warm_start_used && solution.pivots == 0 {
            st.warm_direct += 1;
        }
        Ok(StepReport { time: self.time(), states, interface_forces, modes, active, pivots: solution.pivots })
    }
}

/// `sum over bodies and coordinates of a * b` (two rows dense in `3B` coordinates).
#[inline]
fn dense_dot<T: Real, const B: usize>(a: &[[T; 3]; B], b: &[[T; 3]; B]) -> T {
    let mut sum = T::zero();
    for body in 0..B {
        sum += a[body][0] * b[body][0] + a[body][1] * b[body][1] + a[body][2] * b[body][2];
    }
    sum
}
