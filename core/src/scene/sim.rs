//! [`Scene`]: the meter-stick scene stepped in time, with its switch events and outcome.

use heapless::Vec;

use super::assemble::{StepInputs, assemble, friction_directions, sigma_index};
use super::contact::{ContactFrame, ContactMode};
use super::params::{ParamError, SceneParams};
use crate::lcp::{Basis, LcpError, Lemke};
use crate::real::{Real, max};

/// Position and velocity of the rod's centre of mass.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RodState<T> {
    /// `x` of the centre of mass (m).
    pub x: T,
    /// `y` of the centre of mass (m).
    pub y: T,
    /// Angle `theta` (rad, counter-clockwise).
    pub theta: T,
    /// `dx/dt` (m/s).
    pub vx: T,
    /// `dy/dt` (m/s).
    pub vy: T,
    /// `d theta / dt` (rad/s).
    pub omega: T,
}

impl<T: Real> RodState<T> {
    /// The rod at rest, horizontal, its bottom face on the finger tips (`y = t/2`).
    #[must_use]
    pub fn resting(params: &SceneParams<T>) -> Self {
        Self {
            x: T::zero(),
            y: params.rod_thickness / T::of(2.0),
            theta: T::zero(),
            vx: T::zero(),
            vy: T::zero(),
            omega: T::zero(),
        }
    }

    fn is_finite(&self) -> bool {
        [self.x, self.y, self.theta, self.vx, self.vy, self.omega].iter().all(|v| v.finite())
    }
}

/// A change of one finger's contact mode.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SwitchEvent<T> {
    /// Time at the end of the step where the new mode was found (s).
    pub time: T,
    /// The finger: 0 (moving) or 1 (fixed).
    pub finger: u8,
    /// Its new mode.
    pub mode: ContactMode,
    /// Both fingers' signed distances from the centre of mass along the rod (m) at the
    /// start of that step.
    pub along: [T; 2],
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Outcome {
    /// The fingers met with the centre of mass between them, and the rod stayed on them
    /// for the hold time.
    Balanced,
    /// The rod tipped past the tilt limit, dropped past the drop limit, or left both fingers.
    Fell,
    /// `max_time` passed without either.
    Unfinished,
    /// A step's LCP could not be solved; the state is that before the step.
    SolverFailed(LcpError),
    /// The state became non-finite.
    NonFinite,
    /// 6x6 scene built without the `fallback-8x8` feature: a step's 6x6 check failed (the
    /// reduced model left its range); the state is that before the step.
    ReducedModelLeftRange,
}

/// When and where the fingers met.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Meeting<T> {
    /// Time the moving finger stopped (s).
    pub time: T,
    /// Offset of the centre of mass from the midpoint between the fingers, along the rod
    /// (m): the meeting-point error.
    pub com_offset: T,
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
    /// Steps where the 6x6 model's dropped-direction check failed.
    pub reduced_check_fired: u64,
    /// Of those, steps before the fingers met.
    pub reduced_check_fired_before_meeting: u64,
    /// Switch events that did not fit the event buffer.
    pub events_dropped: u32,
    /// Solves answered by the regularised retry after a round-off ray
    /// ([`crate::lcp::LcpSolution::regularized`]).
    pub regularized_solves: u64,
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport<T> {
    /// Time at the end of the step (s).
    pub time: T,
    /// Rod state at the end of the step.
    pub state: RodState<T>,
    /// Finger tip `x` positions at the end of the step (m).
    pub fingers: [T; 2],
    /// Each finger's signed distance from the centre of mass along the rod, at the start.
    pub along: [T; 2],
    /// Each finger's contact mode after the step.
    pub modes: [ContactMode; 2],
    /// Normal impulse of each finger (N s).
    pub normal_impulse: [T; 2],
    /// Net friction impulse of each finger along the rod's `+x` direction (N s).
    pub friction_impulse: [T; 2],
    /// Complementary pivots of this step's solve(s).
    pub pivots: u32,
    /// `true` when the warm-start basis gave the answer.
    pub warm_start_used: bool,
    /// 6x6 model only: the dropped friction direction's row went negative, or the reduced
    /// LCP had no solution, so the step was re-solved with the full 8x8 model (the reported
    /// values are the 8x8 ones).
    pub reduced_check_failed: bool,
    /// The normalised verification residual of the solution used (see
    /// [`crate::lcp::verify`]; at most the solver's tolerance, `256 N eps` by default, with
    /// `N = 8` when the 6x6 check sent the step to the 8x8 model). Zero when the step failed.
    pub residual: T,
    /// The solver's error, when the step failed (the state is then unchanged).
    pub error: Option<LcpError>,
}

/// The meter-stick scene with an `N x N` LCP per step (`N = 8`: the paper's form; `N = 6`:
/// the reduced form, see [`super::assemble`]) and room for `E` switch events.
#[derive(Debug, Clone)]
pub struct Scene<T: Real, const N: usize, const E: usize = 64> {
    params: SceneParams<T>,
    /// `diag(M^-1)` per unit mass, `(1, 1, m / J)`: the LCP solves for impulses per unit
    /// mass (see [`StepInputs::m_inv`]); reported impulses are these times `m`.
    m_inv: [T; 3],
    state: RodState<T>,
    /// Compensated-summation carries of `x`, `y`, `theta` (Kahan): `q += h v` adds a
    /// `1e-7` m increment to a coordinate of `0.3` m at the slowest finger speeds, where
    /// f32's rounding was a systematic 10 % of the increment (found by `host-sim stress`).
    carry: [T; 3],
    fingers: [T; 2],
    time: T,
    modes: [ContactMode; 2],
    basis: Basis<N>,
    solver: Lemke<T, N>,
    events: Vec<SwitchEvent<T>, E>,
    meeting: Option<Meeting<T>>,
    outcome: Option<Outcome>,
    stats: RunStats,
    start_y: T,
    /// Contact frames of the current state (computed once per step, at its end).
    frames: [ContactFrame<T>; 2],
}

/// The paper's 8x8 scene.
pub type Scene8<T, const E: usize = 64> = Scene<T, 8, E>;
/// The reduced 6x6 scene.
pub type Scene6<T, const E: usize = 64> = Scene<T, 6, E>;

impl<T: Real, const N: usize, const E: usize> Scene<T, N, E> {
    /// The scene at rest on the fingers ([`RodState::resting`]).
    ///
    /// # Errors
    /// The first invalid parameter ([`SceneParams::validate`]).
    pub fn new(params: SceneParams<T>) -> Result<Self, ParamError> {
        Self::with_state(params, RodState::resting(&params))
    }

    /// The scene from a given initial rod state (e.g. slightly above the fingers).
    ///
    /// # Errors
    /// An invalid parameter, or a non-finite state.
    pub fn with_state(params: SceneParams<T>, state: RodState<T>) -> Result<Self, ParamError> {
        const { assert!(N == 6 || N == 8, "the meter-stick scene has N = 6 or N = 8") };
        params.validate()?;
        if !state.is_finite() {
            return Err(ParamError::NonFiniteState);
        }
        let mut scene = Self {
            m_inv: [T::one(), T::one(), params.rod_mass / params.inertia()],
            params,
            state,
            carry: [T::zero(); 3],
            fingers: [params.finger1_x, params.finger2_x],
            time: T::zero(),
            modes: [ContactMode::Sticking; 2],
            basis: Basis::all_w(),
            solver: Lemke::new(),
            events: Vec::new(),
            meeting: None,
            outcome: None,
            stats: RunStats::default(),
            start_y: state.y,
            frames: [ContactFrame::new(
                T::zero(),
                T::zero(),
                T::zero(),
                T::zero(),
                (T::zero(), T::one()),
                T::one(),
                T::one(),
            ); 2],
        };
        scene.frames = scene.compute_frames();
        scene.modes = scene.initial_modes();
        Ok(scene)
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &SceneParams<T> {
        &self.params
    }
    /// The rod's current state.
    #[must_use]
    pub const fn state(&self) -> &RodState<T> {
        &self.state
    }
    /// Finger tip `x` positions (m).
    #[must_use]
    pub const fn fingers(&self) -> [T; 2] {
        self.fingers
    }
    /// Simulated time (s).
    #[must_use]
    pub const fn time(&self) -> T {
        self.time
    }
    /// The contact modes found by the last step (before the first step: from the prescribed
    /// motion at `t = 0`, so finger 1 under a resting rod is sliding and finger 2 sticking).
    #[must_use]
    pub const fn modes(&self) -> [ContactMode; 2] {
        self.modes
    }
    /// The switch events so far (at most `E`; see [`RunStats::events_dropped`]).
    #[must_use]
    pub fn events(&self) -> &[SwitchEvent<T>] {
        &self.events
    }
    /// When and where the fingers met, once they have.
    #[must_use]
    pub const fn meeting(&self) -> Option<Meeting<T>> {
        self.meeting
    }
    /// The outcome, once the run has ended.
    #[must_use]
    pub const fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }
    /// Counters so far.
    #[must_use]
    pub const fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// Runs until an outcome, calling `observe` after every step; returns the outcome.
    pub fn run(&mut self, mut observe: impl FnMut(&StepReport<T>)) -> Outcome {
        while let Some(report) = self.step() {
            observe(&report);
        }
        self.outcome.unwrap_or(Outcome::Unfinished)
    }

    fn compute_frames(&self) -> [ContactFrame<T>; 2] {
        let p = &self.params;
        let sc = self.state.theta.sin_cos_portable();
        let frame = |fx| {
            ContactFrame::new(fx, T::zero(), self.state.x, self.state.y, sc, p.rod_length, p.rod_thickness)
        };
        [frame(self.fingers[0]), frame(self.fingers[1])]
    }

    /// The modes before the first step, from the prescribed motion at `t = 0`: a finger
    /// touching the rod (gap at most round-off) slides when its velocity relative to the rod's
    /// material point exceeds `stick_speed` (finger 1 starts at full speed under a resting rod,
    /// so it slides from `t = 0+` and gets `mu_k` in the first step), and sticks otherwise; a
    /// finger that does not touch the rod is separated.
    fn initial_modes(&self) -> [ContactMode; 2] {
        let p = &self.params;
        let v = [self.state.vx, self.state.vy, self.state.omega];
        let finger_velocity = [[p.finger_speed, T::zero()], [T::zero(), T::zero()]];
        let touch_tol = T::of(64.0) * T::EPS * (p.rod_thickness + self.state.y.abs_exact());
        let mut modes = [ContactMode::Separated; 2];
        for i in 0..2 {
            let f = &self.frames[i];
            if f.active && f.gap <= touch_tol {
                modes[i] = ContactMode::from_slip(f.slip(v, finger_velocity[i]), p.stick_speed);
            }
        }
        modes
    }

    fn mu(&self, mode: ContactMode) -> T {
        if mode.is_sliding() { self.params.mu_kinetic } else { self.params.mu_static }
    }

    /// Advances one step of `h`. `None` once the run has an outcome.
    ///
    /// One step (paper, eqs. 13-18): contact frames from the current state, friction
    /// coefficients from the previous modes (`mu_s` while sticking or separated, `mu_k`
    /// while sliding), the LCP solved warm-started from the previous basis, then
    /// `v+ = v~ + M^-1 W p` and `q+ = q + h v+`.
    #[allow(clippy::too_many_lines)] // the paper's step in order: assemble, solve, check, integrate
    pub fn step(&mut self) -> Option<StepReport<T>> {
        if self.outcome.is_some() {
            return None;
        }
        let p = self.params;
        let h = p.step;
        // Finger 1 at the step's end from the step count, not by accumulating `v h`: in
        // f32, `x += 1e-7` at `x = 0.35` rounds by a systematic 10 %, and `t += h` at
        // `t = 1000` s by 6 % (both found by `host-sim stress`).
        let t_end = T::of_count(count_u32(self.stats.steps + 1)) * h;
        let (finger_end, stopped) = {
            let free = p.finger1_x + p.finger_speed * t_end;
            let stop = p.finger2_x - p.finger_width;
            if free < stop { (free, false) } else { (stop, true) }
        };
        // The LCP sees the prescribed speed; only the stopping step's partial travel is a
        // difference of positions (a difference of rounded positions every step would make
        // the speed jitter by ulp(x) / h: 3e-5 m/s at h = 1 ms in f32, above stick_speed).
        let travel = if stopped { max(finger_end - self.fingers[0], T::zero()) } else { p.finger_speed * h };
        let finger_velocity = [[travel / h, T::zero()], [T::zero(), T::zero()]];
        let frames = self.frames;
        let v_free = [self.state.vx, self.state.vy - h * p.gravity, self.state.omega];
        let inputs = StepInputs {
            frames: &frames,
            mu: [self.mu(self.modes[0]), self.mu(self.modes[1])],
            finger_velocity,
            v_free,
            m_inv: self.m_inv,
            h,
            gravity: p.gravity,
        };
        let step_lcp = assemble::<T, N>(&inputs);
        let mut report = StepReport {
            time: self.time,
            state: self.state,
            fingers: self.fingers,
            along: [frames[0].along, frames[1].along],
            modes: self.modes,
            normal_impulse: [T::zero(); 2],
            friction_impulse: [T::zero(); 2],
            pivots: 0,
            warm_start_used: false,
            reduced_check_failed: false,
            residual: T::zero(),
            error: None,
        };
        let mut z = [T::zero(); 8];
        let mut columns = [[T::zero(); 3]; 8];
        #[cfg_attr(not(feature = "fallback-8x8"), allow(unused_mut))]
        let mut dirs = friction_directions(N);
        let mut v_plus = v_free;
        let reduced_ok = match self.solver.solve_warm(&step_lcp.lcp, self.basis) {
            Ok(sol) => {
                self.basis = sol.basis;
                report.pivots = sol.pivots;
                report.warm_start_used = sol.warm_start_used;
                report.residual = sol.residual;
                self.stats.regularized_solves += u64::from(sol.regularized);
                z[..N].copy_from_slice(sol.z.as_slice());
                columns[..N].copy_from_slice(&step_lcp.columns);
                v_plus = velocity_after(&v_free, &self.m_inv, &columns[..N - 2], &z[..N - 2]);
                true
            }
            // The reduced LCP may have no solution when a dropped direction is needed:
            // that too is the reduced model leaving its range.
            Err(e) if N == 6 => {
                report.pivots = e.pivots();
                self.basis = Basis::all_w();
                false
            }
            Err(e) => return Some(self.fail(report, e)),
        };
        if N == 6 && (!reduced_ok || reduced_check_fails(&inputs, &v_plus, &z, &p)) {
            report.reduced_check_failed = true;
            self.stats.reduced_check_fired += 1;
            if self.meeting.is_none() && !stopped {
                self.stats.reduced_check_fired_before_meeting += 1;
            }
            #[cfg(feature = "fallback-8x8")]
            {
                let full = assemble::<T, 8>(&inputs);
                match Lemke::<T, 8>::new().solve_warm(&full.lcp, widen_basis(self.basis)) {
                    Ok(sol8) => {
                        report.pivots += sol8.pivots;
                        report.residual = sol8.residual;
                        self.stats.regularized_solves += u64::from(sol8.regularized);
                        z.copy_from_slice(sol8.z.as_slice());
                        columns = full.columns;
                        dirs = friction_directions(8);
                        v_plus = velocity_after(&v_free, &self.m_inv, &columns[..6], &z[..6]);
                    }
                    Err(e) => return Some(self.fail(report, e)),
                }
            }
            #[cfg(not(feature = "fallback-8x8"))]
            {
                log_warn!("6x6 check failed at t={}: no 8x8 fallback compiled in", self.time.as_f32());
                self.outcome = Some(Outcome::ReducedModelLeftRange);
                return Some(report);
            }
        }
        self.stats.steps += 1;
        self.stats.pivots += u64::from(report.pivots);
        self.stats.max_pivots = self.stats.max_pivots.max(report.pivots);
        self.stats.warm_starts += u64::from(report.warm_start_used);
        // z holds impulses per unit mass.
        for (k, &(i, sign)) in dirs.iter().enumerate() {
            let s = if sign > 0 { T::one() } else { -T::one() };
            report.friction_impulse[i] += s * z[2 + k] * p.rod_mass;
        }
        report.normal_impulse = [z[0] * p.rod_mass, z[1] * p.rod_mass];

        // Integrate (eq. 14): q+ = q + h v+ (compensated sums), and move finger 1.
        let s = &mut self.state;
        s.vx = v_plus[0];
        s.vy = v_plus[1];
        s.omega = v_plus[2];
        let q = [&mut s.x, &mut s.y, &mut s.theta];
        for (k, coordinate) in q.into_iter().enumerate() {
            let increment = h * v_plus[k] - self.carry[k];
            let sum = *coordinate + increment;
            self.carry[k] = (sum - *coordinate) - increment;
            *coordinate = sum;
        }
        self.fingers[0] = finger_end;
        self.time = t_end;

        // Modes after the step, and switch events.
        let modes = self.classify(&frames, &z, v_plus, &finger_velocity);
        self.record_switches(modes, report.along);
        self.modes = modes;
        report.modes = modes;
        report.time = self.time;
        report.state = self.state;
        report.fingers = self.fingers;
        self.update_outcome(stopped, &report);
        Some(report)
    }

    /// Each contact's mode after a step: separated without a normal impulse, sticking when
    /// the slip speed is at most `stick_speed`, sliding otherwise.
    fn classify(
        &self,
        frames: &[ContactFrame<T>; 2],
        z: &[T; 8],
        v_plus: [T; 3],
        finger_velocity: &[[T; 2]; 2],
    ) -> [ContactMode; 2] {
        let p = &self.params;
        // `z` is per unit mass: a velocity scale.
        let impulse_floor = T::of(64.0) * T::EPS * (p.gravity * p.step + p.finger_speed) + T::TINY;
        let mut modes = [ContactMode::Separated; 2];
        for i in 0..2 {
            if frames[i].active && z[i] > impulse_floor {
                modes[i] = ContactMode::from_slip(frames[i].slip(v_plus, finger_velocity[i]), p.stick_speed);
            }
        }
        modes
    }

    /// Appends a [`SwitchEvent`] for each finger whose mode changed (counting overflow).
    fn record_switches(&mut self, modes: [ContactMode; 2], along: [T; 2]) {
        for i in 0..2 {
            if modes[i] != self.modes[i] {
                let event = SwitchEvent { time: self.time, finger: i as u8, mode: modes[i], along };
                if self.events.push(event).is_err() {
                    self.stats.events_dropped += 1;
                }
            }
        }
    }

    fn fail(&mut self, mut report: StepReport<T>, e: LcpError) -> StepReport<T> {
        report.error = Some(e);
        self.outcome = Some(Outcome::SolverFailed(e));
        report
    }

    fn update_outcome(&mut self, stopped: bool, report: &StepReport<T>) {
        let p = &self.params;
        if !self.state.is_finite() {
            self.outcome = Some(Outcome::NonFinite);
            return;
        }
        self.frames = self.compute_frames();
        let along = [self.frames[0].along, self.frames[1].along];
        let any_active = self.frames[0].active || self.frames[1].active;
        if self.meeting.is_none() && stopped {
            let com_offset = -(along[0] + along[1]) / T::of(2.0);
            self.meeting = Some(Meeting { time: self.time, com_offset });
        }
        let fell = self.state.theta.abs_exact() > p.tilt_limit
            || self.state.y < self.start_y - p.drop_limit
            || !any_active;
        if fell {
            self.outcome = Some(Outcome::Fell);
        } else if let Some(meeting) = self.meeting
            && self.time - meeting.time >= p.hold_time
            && report.modes.iter().all(|m| *m != ContactMode::Separated)
            && along[0] <= T::zero()
            && along[1] >= T::zero()
        {
            self.outcome = Some(Outcome::Balanced);
        } else if self.time >= p.max_time {
            self.outcome = Some(Outcome::Unfinished);
        }
    }
}

#[cfg(feature = "fallback-8x8")]
/// The 8x8 basis holding the same basic variables as a 6x6 one: 6x6 `z` is
/// `(p_n1, p_n2, p_f1+, p_f2-, s1, s2)`, 8x8 `z` is `(p_n1, p_n2, p_f1+, p_f1-, p_f2+, p_f2-, s1, s2)`.
fn widen_basis<const N: usize>(b: Basis<N>) -> Basis<8> {
    const SLOT: [usize; 6] = [0, 1, 2, 5, 6, 7];
    let mut wide = Basis::<8>::all_w();
    if N == 6 {
        for (i, &slot) in SLOT.iter().enumerate() {
            wide.set_z_basic(slot, b.is_z_basic(i));
        }
    }
    wide
}

/// A step count for [`Real::of_count`], saturating at `u32::MAX` (4.3e9 steps: 50 days at
/// h = 1 ms; f32 time is exact only to 2^24 steps anyway).
fn count_u32(n: u64) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// `v+ = v~ + M^-1 sum_j c_j z_j` (eq. 16).
fn velocity_after<T: Real>(v_free: &[T; 3], m_inv: &[T; 3], columns: &[[T; 3]], z: &[T]) -> [T; 3] {
    let mut v = *v_free;
    for (c, &zj) in columns.iter().zip(z) {
        for k in 0..3 {
            v[k] += m_inv[k] * c[k] * zj;
        }
    }
    v
}

/// The 6x6 model's validity check: for each contact in touch, the complementarity row of
/// the friction direction the reduced model dropped, `-s (W_t^T v+ - d . u) + sigma`, must
/// not be negative (beyond round-off): otherwise the slip goes the dropped way and the
/// reduced LCP's answer is not a solution of the full one.
///
/// Except where `sigma` is free: when the kept direction carries no impulse and the cone
/// row `mu p_n - p_f` is zero too (`mu = 0`, or no normal impulse), `sigma` can be raised to
/// `|W_t^T v+ - d . u|` without breaking any complementarity, and the reduced answer (same
/// impulses) extends to a solution of the full LCP. (Without this exception the frictionless
/// scene fell back to 8x8 in 441 of 3,998 steps; `host-sim stress`.)
fn reduced_check_fails<T: Real>(
    inputs: &StepInputs<'_, T>,
    v_plus: &[T; 3],
    z: &[T; 8],
    p: &SceneParams<T>,
) -> bool {
    let speed_scale = p.finger_speed
        + p.gravity * p.step
        + v_plus[0].abs_exact()
        + v_plus[1].abs_exact()
        + (v_plus[2] * p.rod_length).abs_exact();
    let tol = T::of(64.0 * 6.0) * T::EPS * speed_scale + T::TINY;
    friction_directions(6).iter().enumerate().any(|(k, &(i, sign))| {
        let f = &inputs.frames[i];
        if !f.active {
            return false;
        }
        let kept_impulse = z[2 + k];
        if kept_impulse <= tol && inputs.mu[i] * z[i] <= tol {
            return false; // sigma is free
        }
        let u = &inputs.finger_velocity[i];
        let g = f.wt[0] * v_plus[0] + f.wt[1] * v_plus[1] + f.wt[2] * v_plus[2]
            - (f.tangent[0] * u[0] + f.tangent[1] * u[1]);
        let kept_sign = if sign > 0 { T::one() } else { -T::one() };
        let dropped_row = -kept_sign * g + z[sigma_index(6, i)];
        dropped_row < -tol
    })
}
