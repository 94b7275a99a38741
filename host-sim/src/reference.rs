//! An independent f64 reference of the meter-stick scene: the same physics as `core`, written
//! separately, to catch formulation and precision errors in `core`.
//!
//! Nothing here calls `core`'s solver, assembly or stepper; only its parameter struct and its
//! mode names are shared, as data.
//!
//! # How it differs from `core`
//! * **Sizes.** Only contacts whose finger is under the rod enter the LCP, with the paper's full
//!   form (eqs. 13-18): per active contact one normal impulse, two friction impulses (`+d`, `-d`)
//!   and one `sigma`, so the LCP is 4x4 or 8x8 (or empty). `core` keeps a fixed 6x6/8x8 and
//!   decouples inactive contacts.
//! * **Matrices.** `A = [W_n W_f]^T M^-1 [W_n W_f]` is formed as a dense product of `Vec`s from
//!   the rotation matrix `R(theta)`; `core` forms dot products of precomputed wrench columns.
//! * **Solver.** Exhaustive enumeration of all `2^n` complementary bases: for each index set
//!   `a` of basic `z`, solve `A_aa z_a = -b_a` by Gaussian elimination with partial pivoting
//!   and keep it when `z_a >= 0` and `w = A z + b >= 0` to `1e-13` of the problem's scale
//!   (f64 elimination on these well-conditioned systems of size <= 8 is good to ~1e-15; a
//!   looser `1e-9` admitted near-solutions that, chosen for their lower energy, delayed
//!   stick-to-slip switches by up to 5 ms at h <= 2.5e-6 s: found by the convergence study).
//!   A solution of the Anitescu-Potra/Stewart-Trinkle friction LCP always exists, but need not
//!   be unique (e.g. how friction splits between two sticking fingers). **Choice among
//!   solutions:** the one whose post-step rod velocity has the least kinetic energy (the
//!   maximum-dissipation principle that motivates the friction model), ties broken by the
//!   smallest `||z||_1` and then by the lowest basis index. A step whose solutions give rod
//!   velocities that differ by more than the tolerance is counted as *ambiguous*.
//! * **Rules** (the documented semantics, re-implemented): `mu_s` for a contact that was
//!   sticking or separated after the previous step, `mu_k` for one that was sliding (before the
//!   first step, finger 1 slides, as it moves under a resting rod, and finger 2 sticks); after a
//!   step a contact with a positive normal impulse sticks when its slip speed is at most
//!   `stick_speed`; time after `n` steps is `n h`; finger 1 is at `x1 + v t` until it stops
//!   `finger_width` from finger 2, and the LCP sees its velocity `v` (on the stopping step, the
//!   partial travel over `h`); a penetration `psi < 0` is pushed out at most at the speed of a
//!   fall through it, `sqrt(2 g |psi|)`, instead of `|psi| / h`; the outcome tests are those of
//!   `core`'s `Outcome` docs.

use meterstick_core::scene::{ContactMode, SceneParams, Slide};

use crate::trajectory::{Event, Record, Recorder, Row, RunOutcome, SolverCounters, Trajectory};

/// Geometry of one finger against the rod.
#[derive(Debug, Clone, Copy)]
struct Touch {
    /// Finger in the rod frame.
    local: [f64; 2],
    gap: f64,
    under_rod: bool,
    /// Contact point relative to the COM, world.
    r: [f64; 2],
    normal: [f64; 2],
    tangent: [f64; 2],
}

fn rotate(theta: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

fn touch(p: &SceneParams<f64>, q: [f64; 3], finger_x: f64) -> Touch {
    let rel = [finger_x - q[0], -q[1]];
    let local = rotate(-q[2], rel);
    let under_rod = local[0].abs() <= p.rod_length / 2.0 && local[1] <= 0.0;
    Touch {
        local,
        gap: -local[1] - p.rod_thickness / 2.0,
        under_rod,
        r: rotate(q[2], [local[0], -p.rod_thickness / 2.0]),
        normal: rotate(q[2], [0.0, 1.0]),
        tangent: rotate(q[2], [1.0, 0.0]),
    }
}

/// Wrench `[a; r x a]` of a unit impulse along `a` applied at `r`.
fn wrench(r: [f64; 2], a: [f64; 2]) -> [f64; 3] {
    [a[0], a[1], r[0] * a[1] - r[1] * a[0]]
}

/// The LCP of one step and what is needed to use its solution.
#[derive(Debug, Clone)]
struct StepProblem {
    a: Vec<Vec<f64>>,
    b: Vec<f64>,
    /// Wrench column of each impulse variable (the first `4k` of `z`... laid out below).
    columns: Vec<[f64; 3]>,
    /// Active contacts, in order.
    contacts: Vec<usize>,
}

/// Assembles eq. 18 for the active contacts: `z = (p_n[k], p_f[2k] (+d, -d per contact), sigma[k])`.
fn assemble(
    p: &SceneParams<f64>,
    touches: &[Touch; 2],
    mu: [f64; 2],
    v_free: [f64; 3],
    finger_v: [[f64; 2]; 2],
) -> StepProblem {
    let contacts: Vec<usize> = (0..2).filter(|&i| touches[i].under_rod).collect();
    let k = contacts.len();
    let n = 4 * k;
    let m_inv = [1.0 / p.rod_mass, 1.0 / p.rod_mass, 12.0 / (p.rod_mass * p.rod_length * p.rod_length)];
    let mut columns = Vec::with_capacity(3 * k);
    let mut b = vec![0.0; n];
    for (slot, &i) in contacts.iter().enumerate() {
        let t = &touches[i];
        let wn = wrench(t.r, t.normal);
        columns.push(wn);
        b[slot] = (0..3).map(|c| wn[c] * v_free[c]).sum::<f64>()
            - (t.normal[0] * finger_v[i][0] + t.normal[1] * finger_v[i][1])
            + if t.gap >= 0.0 {
                t.gap / p.step
            } else {
                (t.gap / p.step).max(-(2.0 * p.gravity * -t.gap).sqrt())
            };
    }
    for (slot, &i) in contacts.iter().enumerate() {
        let t = &touches[i];
        for (dir, sign) in [1.0, -1.0].into_iter().enumerate() {
            let d = [sign * t.tangent[0], sign * t.tangent[1]];
            let wf = wrench(t.r, d);
            columns.push(wf);
            b[k + 2 * slot + dir] = (0..3).map(|c| wf[c] * v_free[c]).sum::<f64>()
                - (d[0] * finger_v[i][0] + d[1] * finger_v[i][1]);
        }
    }
    let mut a = vec![vec![0.0; n]; n];
    for (j, cj) in columns.iter().enumerate() {
        for (l, cl) in columns.iter().enumerate() {
            a[j][l] = (0..3).map(|c| cj[c] * m_inv[c] * cl[c]).sum();
        }
    }
    for (slot, &i) in contacts.iter().enumerate() {
        let sigma = 3 * k + slot;
        for dir in 0..2 {
            let f = k + 2 * slot + dir;
            a[f][sigma] = 1.0; // E
            a[sigma][f] = -1.0; // -E^T
        }
        a[sigma][slot] = mu[i]; // U
    }
    StepProblem { a, b, columns, contacts }
}

/// The largest LCP the reference builds (two active contacts).
const MAX_N: usize = 8;

/// Solves the `k x k` system `a x = rhs` in place by Gaussian elimination with partial
/// pivoting; `false` when a pivot is at most `tiny` (a singular principal submatrix).
fn solve_dense(a: &mut [[f64; MAX_N]; MAX_N], rhs: &mut [f64; MAX_N], k: usize, tiny: f64) -> bool {
    for col in 0..k {
        let mut piv = col;
        for row in col + 1..k {
            if a[row][col].abs() > a[piv][col].abs() {
                piv = row;
            }
        }
        if a[piv][col].abs() <= tiny {
            return false;
        }
        a.swap(col, piv);
        rhs.swap(col, piv);
        for row in col + 1..k {
            let f = a[row][col] / a[col][col];
            if f != 0.0 {
                for c in col..k {
                    a[row][c] -= f * a[col][c];
                }
                rhs[row] -= f * rhs[col];
            }
        }
    }
    for row in (0..k).rev() {
        let mut s = rhs[row];
        for c in row + 1..k {
            s -= a[row][c] * rhs[c];
        }
        rhs[row] = s / a[row][row];
    }
    true
}

/// Every solution of `w = A z + b >= 0, z >= 0, z.w = 0` found among the `2^n` complementary
/// bases with a nonsingular principal submatrix, as `(basis mask, z)`.
fn enumerate(a: &[Vec<f64>], b: &[f64]) -> Vec<(u32, Vec<f64>)> {
    let n = b.len();
    assert!(n <= MAX_N, "the reference builds LCPs of size 0, 4 or 8");
    let a_max = a.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    let b_max = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let tiny = 1e-12 * a_max.max(f64::MIN_POSITIVE);
    let mut found = Vec::new();
    let mut basic = [0usize; MAX_N];
    for mask in 0u32..(1 << n) {
        let mut k = 0;
        for i in 0..n {
            if mask & (1 << i) != 0 {
                basic[k] = i;
                k += 1;
            }
        }
        let mut sub = [[0.0; MAX_N]; MAX_N];
        let mut za = [0.0; MAX_N];
        for r in 0..k {
            for c in 0..k {
                sub[r][c] = a[basic[r]][basic[c]];
            }
            za[r] = -b[basic[r]];
        }
        if !solve_dense(&mut sub, &mut za, k, tiny) {
            continue;
        }
        let z_max = za[..k].iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let tol = 1e-13 * (b_max + a_max * z_max);
        if za[..k].iter().any(|&v| v < -tol) {
            continue;
        }
        let mut z = vec![0.0; n];
        for r in 0..k {
            z[basic[r]] = za[r];
        }
        let w_ok = (0..n)
            .all(|i| mask & (1 << i) != 0 || (0..n).map(|j| a[i][j] * z[j]).sum::<f64>() + b[i] >= -tol);
        if w_ok {
            for v in &mut z {
                *v = v.max(0.0);
            }
            found.push((mask, z));
        }
    }
    found
}

/// The f64 reference scene.
#[derive(Debug, Clone)]
pub struct Reference {
    p: SceneParams<f64>,
    q: [f64; 3],
    v: [f64; 3],
    fingers: [f64; 2],
    t: f64,
    steps: u64,
    modes: [ContactMode; 2],
    y0: f64,
    meeting: Option<(f64, f64)>,
    outcome: Option<RunOutcome>,
    ambiguous_steps: u64,
}

impl Reference {
    /// The rod at rest on the fingers. The parameters must be valid (`SceneParams::validate`).
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn new(p: SceneParams<f64>) -> anyhow::Result<Self> {
        p.validate().map_err(|e| anyhow::anyhow!("invalid scene: {e}"))?;
        let y0 = p.rod_thickness / 2.0;
        // Before the first step: finger 1 moves at v under a resting rod (sliding toward the
        // rod's +x end, so mu_k in the first step); finger 2 is at rest under it (sticking).
        let first = if p.finger_speed > p.stick_speed {
            ContactMode::Sliding(Slide::TowardPositiveEnd)
        } else {
            ContactMode::Sticking
        };
        Ok(Self {
            p,
            q: [0.0, y0, 0.0],
            v: [0.0; 3],
            fingers: [p.finger1_x, p.finger2_x],
            t: 0.0,
            steps: 0,
            modes: [first, ContactMode::Sticking],
            y0,
            meeting: None,
            outcome: None,
            ambiguous_steps: 0,
        })
    }

    fn row(&self, along: [f64; 2], pn: [f64; 2], pf: [f64; 2]) -> Row {
        Row {
            t: self.t,
            q: self.q,
            fingers: self.fingers,
            along,
            modes: self.modes,
            normal_impulse: pn,
            friction_impulse: pf,
        }
    }

    /// One step; `None` once the run has an outcome.
    fn step(&mut self) -> Option<Row> {
        if self.outcome.is_some() {
            return None;
        }
        let p = self.p;
        let h = p.step;
        let stop = p.finger2_x - p.finger_width;
        let free = p.finger1_x + p.finger_speed * ((self.steps + 1) as f64 * h);
        let finger_stopped = free >= stop;
        let finger_end = free.min(stop);
        let finger_v = if finger_stopped {
            [[(finger_end - self.fingers[0]).max(0.0) / h, 0.0], [0.0, 0.0]]
        } else {
            [[p.finger_speed, 0.0], [0.0, 0.0]]
        };
        let touches = [touch(&p, self.q, self.fingers[0]), touch(&p, self.q, self.fingers[1])];
        let mu = self.modes.map(|m| if m.is_sliding() { p.mu_kinetic } else { p.mu_static });
        let v_free = [self.v[0], self.v[1] - h * p.gravity, self.v[2]];
        let prob = assemble(&p, &touches, mu, v_free, finger_v);
        let m_inv = [1.0 / p.rod_mass, 1.0 / p.rod_mass, 12.0 / (p.rod_mass * p.rod_length * p.rod_length)];
        let velocity = |z: &[f64]| {
            let mut v = v_free;
            for (c, zj) in prob.columns.iter().zip(z) {
                for d in 0..3 {
                    v[d] += m_inv[d] * c[d] * zj;
                }
            }
            v
        };
        let energy = |v: [f64; 3]| v[0] * v[0] / m_inv[0] + v[1] * v[1] / m_inv[1] + v[2] * v[2] / m_inv[2];
        let solutions = enumerate(&prob.a, &prob.b);
        let chosen = solutions.iter().map(|(mask, z)| (velocity(z), z, *mask)).min_by(|x, y| {
            energy(x.0)
                .total_cmp(&energy(y.0))
                .then(x.1.iter().sum::<f64>().total_cmp(&y.1.iter().sum::<f64>()))
                .then(x.2.cmp(&y.2))
        });
        let Some((v_plus, z, _)) = chosen else {
            self.outcome = Some(RunOutcome::Failed(format!(
                "no complementary basis solves the {0}x{0} LCP at t = {1}",
                prob.b.len(),
                self.t
            )));
            return None;
        };
        let speed_scale = v_free.iter().fold(p.finger_speed, |m, x| m.max(x.abs()));
        if solutions.iter().any(|(_, z2)| {
            let v2 = velocity(z2);
            (0..3).any(|d| {
                let scale = if d == 2 { p.rod_length / 2.0 } else { 1.0 };
                ((v2[d] - v_plus[d]) * scale).abs() > 1e-9 * speed_scale
            })
        }) {
            self.ambiguous_steps += 1;
        }
        let k = prob.contacts.len();
        let mut pn = [0.0; 2];
        let mut pf = [0.0; 2];
        for (slot, &i) in prob.contacts.iter().enumerate() {
            pn[i] = z[slot];
            pf[i] = z[k + 2 * slot] - z[k + 2 * slot + 1];
        }
        // Eq. 14: q+ = q + h v+.
        self.v = v_plus;
        for d in 0..3 {
            self.q[d] += h * v_plus[d];
        }
        self.fingers[0] = finger_end;
        self.steps += 1;
        self.t = self.steps as f64 * h;
        let impulse_floor = 1e-12 * p.rod_mass * (p.gravity * h + p.finger_speed);
        let mut modes = [ContactMode::Separated; 2];
        for i in 0..2 {
            if touches[i].under_rod && pn[i] > impulse_floor {
                // Slip of the finger relative to the rod's material point, along d.
                let t = &touches[i];
                let point = [v_plus[0] - v_plus[2] * t.r[1], v_plus[1] + v_plus[2] * t.r[0]];
                let slip =
                    t.tangent[0] * (finger_v[i][0] - point[0]) + t.tangent[1] * (finger_v[i][1] - point[1]);
                modes[i] = if slip.abs() <= p.stick_speed {
                    ContactMode::Sticking
                } else if slip > 0.0 {
                    ContactMode::Sliding(Slide::TowardPositiveEnd)
                } else {
                    ContactMode::Sliding(Slide::TowardNegativeEnd)
                };
            }
        }
        self.modes = modes;
        let along = [touches[0].local[0], touches[1].local[0]];
        self.judge(finger_stopped);
        Some(self.row(along, pn, pf))
    }

    fn judge(&mut self, finger_stopped: bool) {
        let p = self.p;
        if !self.q.iter().chain(&self.v).all(|x| x.is_finite()) {
            self.outcome = Some(RunOutcome::Failed("non-finite state".into()));
            return;
        }
        let now = [touch(&p, self.q, self.fingers[0]), touch(&p, self.q, self.fingers[1])];
        if self.meeting.is_none() && finger_stopped {
            self.meeting = Some((self.t, -(now[0].local[0] + now[1].local[0]) / 2.0));
        }
        if self.q[2].abs() > p.tilt_limit
            || self.q[1] < self.y0 - p.drop_limit
            || !(now[0].under_rod || now[1].under_rod)
        {
            self.outcome = Some(RunOutcome::Fell);
        } else if self.meeting.is_some_and(|(t, _)| self.t - t >= p.hold_time)
            && self.modes.iter().all(|m| *m != ContactMode::Separated)
            && now[0].local[0] <= 0.0
            && now[1].local[0] >= 0.0
        {
            self.outcome = Some(RunOutcome::Balanced);
        } else if self.t >= p.max_time {
            self.outcome = Some(RunOutcome::Unfinished);
        }
    }

    /// Runs to the outcome and records the run.
    #[must_use]
    pub fn run(mut self, record: Record) -> Trajectory {
        let start = [self.fingers[0] - self.q[0], self.fingers[1] - self.q[0]];
        let initial_modes = self.modes;
        let mut rows = Recorder::new(record);
        rows.push(self.row(start, [0.0; 2], [0.0; 2]));
        let mut events = Vec::new();
        let mut modes = self.modes;
        while let Some(row) = self.step() {
            for i in 0..2 {
                if row.modes[i] != modes[i] {
                    events.push(Event {
                        t: row.t,
                        finger: i,
                        mode: row.modes[i],
                        along: row.along,
                        fingers: row.fingers,
                    });
                }
            }
            modes = row.modes;
            rows.push(row);
        }
        Trajectory {
            label: "reference f64 8x8".into(),
            steps: self.steps,
            end_time: self.t,
            rows: rows.finish(),
            initial_modes,
            events,
            outcome: self.outcome.unwrap_or(RunOutcome::Unfinished),
            meeting: self.meeting,
            counters: SolverCounters { ambiguous_steps: self.ambiguous_steps, ..SolverCounters::default() },
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn enumeration_finds_the_unique_solution_of_a_p_matrix_lcp() {
        // M = [[2, 1], [1, 2]], q = [-5, -6]: z = (4/3, 7/3), w = 0.
        let sols = enumerate(&[vec![2.0, 1.0], vec![1.0, 2.0]], &[-5.0, -6.0]);
        assert_eq!(sols.len(), 1);
        assert!((sols[0].1[0] - 4.0 / 3.0).abs() < 1e-12 && (sols[0].1[1] - 7.0 / 3.0).abs() < 1e-12);
        // q >= 0: z = 0.
        let sols = enumerate(&[vec![2.0, 1.0], vec![1.0, 2.0]], &[1.0, 0.5]);
        assert_eq!(sols, vec![(0, vec![0.0, 0.0])]);
    }

    #[test]
    fn a_resting_rod_carries_its_weight_by_torque_balance() {
        // Fingers at -0.4 and +0.2, at rest: W1 x1 = W2 x2 (eq. 19), W1 + W2 = m g h.
        let mut p = SceneParams::<f64>::paper();
        p.finger1_x = -0.4;
        p.finger2_x = 0.2;
        p.finger_speed = 0.0;
        let mut r = Reference::new(p).unwrap();
        let row = r.step().unwrap();
        let [n1, n2] = row.normal_impulse;
        let weight = p.rod_mass * p.gravity * p.step;
        assert!((n1 + n2 - weight).abs() < 1e-9 * weight, "{n1} {n2}");
        assert!((n1 * 0.4 - n2 * 0.2).abs() < 1e-6 * weight, "{n1} {n2}");
        assert_eq!(row.modes, [ContactMode::Sticking; 2]);
    }
}
