//! One multibody step (docs/formulation.md, "Several bodies"): the LCP of eqs. 13-18 over the
//! `k` active contacts in the bodies' `3B` coordinates, solved by this module's own solver
//! (`lcp.rs`) and the least-kinetic-energy rule.
//!
//! `z = (p_n[1..k], p_+d[1], p_-d[1], ..., p_+d[k], p_-d[k], sigma[1..k])` (the single-body
//! reference's layout, `reference/src/step.rs`), per unit **reference mass** `m_ref` (body 0's):
//! `M~ = m_ref M^-1 = blockdiag(m_ref / m_i, m_ref / m_i, m_ref / J_i)`, so every row of `w` is
//! a velocity and `z` is the impulses divided by `m_ref`. With `J_t` the contact rows
//! (`geometry.rs`) and `v~_i = v_i + h (f_i / m_i - g e_y)` (eq. 16, `f_i` the external force
//! at body `i`'s centre of mass):
//!
//! ```text
//! A = [ J M~ J^T   E ]     b = [ J_n v~ + beta(psi')   (normal rows)   ]
//!     [ U   -E^T   0 ]         [ +-J_d v~             (friction rows) ]
//!                              [ 0                    (sigma rows)    ]
//! ```
//!
//! **Solutions considered** (docs/formulation.md, "Solving a multibody step"):
//!
//! 1. the previous step's basis (each candidate contact keeps its own pattern of basic
//!    variables; a contact that was not active starts with none);
//! 2. Lemke's method from the `w` basis (covering vector all ones); an answer that misses the
//!    tolerance has its basis solved afresh; on a ray, again with the cone rows opened;
//! 3. the **held** bases: every contact `{p_n, p_+d}`, every contact `{p_n, p_-d}`, every
//!    contact with all four variables basic and, when the last does not solve the LCP, each of
//!    its neighbours (one contact's pattern replaced by each of the eight below);
//! 4. a descent over neighbouring bases: from the least-energy solution so far, each active
//!    contact's pattern replaced in turn by each of the eight patterns `{}`, `{sigma, p_+d}`,
//!    `{sigma, p_-d}`, `{p_n}`, `{p_n, p_+d}`, `{p_n, p_-d}`, `{p_n, p_+d, sigma}`,
//!    `{p_n, p_-d, sigma}` (separated; separated while slipping; touching without friction;
//!    sticking; sliding), repeated while a neighbour lowers the energy (at most
//!    `DESCENT_ROUNDS` rounds); when no neighbour lowers it but the solutions found move the
//!    bodies differently, widened to two contacts of one pair at a time.
//!
//! Every candidate is verified (`lcp::verify`); among the verified, the least kinetic energy
//! `sum_i (m_i |v_i|^2 + J_i omega_i^2) / m_ref` wins, energies within
//! `1e-12 S^2 sum_i m_i / m_ref` tie and go to the smallest `||z||_1` (within `1e-12`, relative),
//! then to the first found. `S` is the step's speed scale,
//! `max_i max(|v~_x|, |v~_y|, reach_i |v~_omega|)` (`reach_i` half body `i`'s diagonal, a
//! disc's radius). The step is **ambiguous** when two verified solutions' velocities differ by
//! more than `1e-9 S` in a component (`omega` times `reach_i`).

use super::geometry::{Frame, dot};
use super::lcp::{Basis, lemke, solve_basis, verify};
use super::system::{State, System, slip_mode};
use crate::Mode;
use crate::load::{Law, Touching, determinate, least_norm};

/// Rounds of the descent over neighbouring bases.
const DESCENT_ROUNDS: usize = 8;

/// How far the cone rows are opened (relative to `||b||_inf`) when Lemke's method ends on a ray.
const CONE_OPENING: f64 = 1e-9;

/// A contact held with every variable basic (`p_n`, both friction impulses and `sigma`): sticking.
const STUCK: u8 = 1 | 2 | 4 | 8;

/// The eight per-contact patterns of basic variables: bits `p_n` 1, `p_+d` 2, `p_-d` 4, `sigma` 8.
const PATTERNS: [u8; 8] = [0, 2 | 8, 4 | 8, 1, 1 | 2, 1 | 4, 1 | 2 | 8, 1 | 4 | 8];

/// The answer of one step.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StepResult {
    /// `v+` per body.
    pub velocity: Vec<[f64; 3]>,
    /// Each candidate contact's normal impulse, N s (0 when inactive).
    pub normal: Vec<f64>,
    /// Each candidate contact's net friction impulse along `+d`, N s.
    pub friction: Vec<f64>,
    /// Each candidate contact's pattern of basic variables in the chosen solution.
    pub patterns: Vec<u8>,
    /// Whether verified solutions with different motions were found.
    pub ambiguous: bool,
    /// Verified solutions found.
    pub solutions: usize,
    /// The LCP's size `4 k`.
    pub rows: usize,
}

/// One step's LCP, assembled.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StepLcp {
    /// The active candidates' indices, in slot order.
    pub active: Vec<usize>,
    /// Each slot's pair.
    pub pairs: Vec<usize>,
    /// `A`, row-major `n x n`.
    pub matrix: Vec<f64>,
    /// `b`.
    pub offset: Vec<f64>,
    /// The rows `J` of the `3 k` impulses (normal of slot `s` at `s`, `+d` at `k + 2 s`, `-d` at
    /// `k + 2 s + 1`), each `3 B` long.
    pub rows: Vec<Vec<f64>>,
    /// `v~`, flattened (`3 B`).
    pub free: Vec<f64>,
    /// `diag(M~)`, flattened.
    pub weights: Vec<f64>,
}

impl StepLcp {
    /// `v+ = v~ + M~ J^T z`, flattened.
    pub fn velocity(&self, z: &[f64]) -> Vec<f64> {
        let mut v = self.free.clone();
        for (row, &zc) in self.rows.iter().zip(z) {
            if zc != 0.0 {
                for c in 0..v.len() {
                    v[c] += self.weights[c] * row[c] * zc;
                }
            }
        }
        v
    }
}

/// Assembles the step's LCP from the state `(q, v)`, the candidates' `frames` at it and each
/// candidate's friction coefficient `mu` for this step.
pub(super) fn assemble(
    system: &System,
    q: &[[f64; 3]],
    v: &[[f64; 3]],
    frames: &[Frame],
    mu: &[f64],
) -> StepLcp {
    let bodies = system.bodies.len();
    let active: Vec<usize> = (0..frames.len()).filter(|&i| frames[i].active).collect();
    let k = active.len();
    let n = 4 * k;
    let weights = system.weights();
    let free = system.free_velocity(v);
    let mut rows = vec![Vec::new(); 3 * k];
    let mut offset = vec![0.0; n];
    for (slot, &i) in active.iter().enumerate() {
        let f = &frames[i];
        rows[slot] = f.row(f.normal, bodies);
        offset[slot] = dot_n(&rows[slot], &free) + system.recovery(f.gap, system.gap_round_off(q, f));
        for (dir, sign) in [1.0, -1.0].into_iter().enumerate() {
            let c = k + 2 * slot + dir;
            rows[c] = f.row([sign * f.tangent[0], sign * f.tangent[1]], bodies);
            offset[c] = dot_n(&rows[c], &free);
        }
    }
    let mut matrix = vec![0.0; n * n];
    for (r, wr) in rows.iter().enumerate() {
        for (c, wc) in rows.iter().enumerate() {
            matrix[r * n + c] = (0..3 * bodies).map(|x| wr[x] * weights[x] * wc[x]).sum();
        }
    }
    for (slot, &i) in active.iter().enumerate() {
        let sigma = 3 * k + slot;
        for dir in 0..2 {
            let f = k + 2 * slot + dir;
            matrix[f * n + sigma] = 1.0;
            matrix[sigma * n + f] = -1.0;
        }
        matrix[sigma * n + slot] = mu[i];
    }
    let pairs = active.iter().map(|&i| frames[i].pair).collect();
    StepLcp { active, pairs, matrix, offset, rows, free, weights }
}

/// `a . b`.
fn dot_n(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The basis of per-slot `patterns` (`k` slots) in the layout of `z`.
fn basis_of(patterns: &[u8]) -> Basis {
    let k = patterns.len();
    let mut basis = vec![false; 4 * k];
    for (s, &p) in patterns.iter().enumerate() {
        basis[s] = p & 1 != 0;
        basis[k + 2 * s] = p & 2 != 0;
        basis[k + 2 * s + 1] = p & 4 != 0;
        basis[3 * k + s] = p & 8 != 0;
    }
    basis
}

/// The per-slot patterns of a basis.
fn patterns_of(basis: &[bool]) -> Vec<u8> {
    let k = basis.len() / 4;
    (0..k)
        .map(|s| {
            u8::from(basis[s])
                | u8::from(basis[k + 2 * s]) << 1
                | u8::from(basis[k + 2 * s + 1]) << 2
                | u8::from(basis[3 * k + s]) << 3
        })
        .collect()
}

/// A verified solution.
struct Found {
    z: Vec<f64>,
    basis: Basis,
    velocity: Vec<f64>,
    energy: f64,
}

/// Where the solver starts: the warm basis (per candidate, from the previous step), whether to
/// run Lemke's method, and whether to descend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Starts {
    /// Try the previous step's basis.
    pub warm: bool,
    /// Run Lemke's method from the `w` basis.
    pub lemke: bool,
    /// Descend over neighbouring bases.
    pub descend: bool,
}

impl Starts {
    /// Everything: the reference's rule.
    pub const ALL: Self = Self { warm: true, lemke: true, descend: true };
}

/// Every verified solution the starts reach (module documentation), in the order found.
fn gather(lcp: &StepLcp, previous: &[u8], starts: Starts, tie: f64, scale: &Scale) -> Vec<Found> {
    let k = lcp.active.len();
    let n = 4 * k;
    let weights = &lcp.weights;
    let energy = |v: &[f64]| (0..v.len()).map(|c| v[c] * v[c] / weights[c]).sum::<f64>();
    let mut pool: Vec<Found> = Vec::new();
    let consider = |z: Vec<f64>, basis: Basis, pool: &mut Vec<Found>| {
        let verified = verify(&lcp.matrix, &lcp.offset, &z);
        if verified {
            let z: Vec<f64> = z.into_iter().map(|x| x.max(0.0)).collect();
            let velocity = lcp.velocity(&z);
            let energy = energy(&velocity);
            pool.push(Found { z, basis, velocity, energy });
        }
        verified
    };
    let try_basis = |basis: Basis, pool: &mut Vec<Found>| {
        if let Some(z) = solve_basis(&lcp.matrix, &lcp.offset, &basis) {
            consider(z, basis, pool);
        }
    };
    if starts.warm {
        let patterns: Vec<u8> = lcp.active.iter().map(|&i| previous[i]).collect();
        try_basis(basis_of(&patterns), &mut pool);
    }
    if starts.lemke {
        if let Ok((z, basis)) = lemke(&lcp.matrix, &lcp.offset, &vec![1.0; n], 50 * (n + 1)) {
            // The tableau's round-off grows with the pivots: when its answer misses the
            // tolerance, its basis is solved afresh.
            if !consider(z, basis.clone(), &mut pool) {
                try_basis(basis, &mut pool);
            }
        } else {
            // The sigma of a contact without normal impulse is unbounded above (a ray of the
            // LCP's solution set, along which Lemke's method can end): cut it off by opening each
            // cone row by a little, then solve the basis reached on the exact problem.
            let b_norm = lcp.offset.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            let mut opened = lcp.offset.clone();
            for row in &mut opened[3 * k..] {
                *row += CONE_OPENING * b_norm;
            }
            if let Ok((_, basis)) = lemke(&lcp.matrix, &opened, &vec![1.0; n], 50 * (n + 1)) {
                try_basis(basis, &mut pool);
            }
        }
    }
    if starts.descend {
        // Every contact touching and holding (the solution of most dissipation when there is one),
        // and, whether or not it solves the LCP, each of its neighbours (one contact let go:
        // separated, slipping or sliding).
        for pattern in [1 | 2, 1 | 4] {
            try_basis(basis_of(&vec![pattern; k]), &mut pool);
        }
        let held = vec![STUCK; k];
        let before = pool.len();
        try_basis(basis_of(&held), &mut pool);
        // A held basis that solves is a start of the descent below, which visits its neighbours.
        let seeds = if pool.len() == before { k } else { 0 };
        for slot in 0..seeds {
            for &p in &PATTERNS {
                let mut patterns = held.clone();
                patterns[slot] = p;
                try_basis(basis_of(&patterns), &mut pool);
            }
        }
    }
    let least = |pool: &[Found]| (0..pool.len()).min_by(|&a, &b| pool[a].energy.total_cmp(&pool[b].energy));
    if starts.descend {
        // Widened once the solutions found move differently: two contacts of one pair at a time.
        let mut widened = false;
        for _ in 0..DESCENT_ROUNDS {
            let Some(best) = least(&pool) else { break };
            let (best_energy, best_patterns) = (pool[best].energy, patterns_of(&pool[best].basis));
            for slot in 0..k {
                for &p in PATTERNS.iter().filter(|&&p| p != best_patterns[slot]) {
                    let mut patterns = best_patterns.clone();
                    patterns[slot] = p;
                    try_basis(basis_of(&patterns), &mut pool);
                }
            }
            if widened {
                for (first, second) in (0..k).flat_map(|a| (a + 1..k).map(move |b| (a, b))) {
                    if lcp.pairs[first] != lcp.pairs[second] {
                        continue;
                    }
                    for &p in PATTERNS.iter().filter(|&&p| p != best_patterns[first]) {
                        for &r in PATTERNS.iter().filter(|&&r| r != best_patterns[second]) {
                            let mut patterns = best_patterns.clone();
                            patterns[first] = p;
                            patterns[second] = r;
                            try_basis(basis_of(&patterns), &mut pool);
                        }
                    }
                }
            }
            if least(&pool).is_none_or(|b| pool[b].energy >= best_energy - tie) {
                let several = pool.iter().any(|f| scale.differ(&f.velocity, &pool[best].velocity));
                if widened || !several {
                    break;
                }
                widened = true;
            }
        }
    }
    pool
}

/// How far apart two motions must be to differ: `1e-9 S` in a component, `omega` times its
/// body's reach.
struct Scale {
    /// `S`, m/s.
    speed: f64,
    /// Per coordinate: 1 for `vx`, `vy`, the body's reach for `omega`.
    factors: Vec<f64>,
}

impl Scale {
    fn differ(&self, a: &[f64], b: &[f64]) -> bool {
        a.iter().zip(b).zip(&self.factors).any(|((x, y), f)| f * (x - y).abs() > 1e-9 * self.speed)
    }
}

/// Solves the assembled `lcp` by the rule of the module's documentation. `previous` holds each
/// of the `candidates` contacts' pattern from the previous step; `system` gives the energy's
/// weights and the speed scale's reaches.
///
/// # Errors
/// No candidate solution verified.
pub(super) fn solve(
    system: &System,
    lcp: &StepLcp,
    previous: &[u8],
    candidates: usize,
    starts: Starts,
) -> Result<StepResult, String> {
    let k = lcp.active.len();
    let n = 4 * k;
    let bodies = system.bodies.len();
    let speed_scale = (0..bodies)
        .map(|i| {
            let reach = system.bodies[i].reach();
            lcp.free[3 * i].abs().max(lcp.free[3 * i + 1].abs()).max(reach * lcp.free[3 * i + 2].abs())
        })
        .fold(0.0, f64::max);
    let scale = Scale {
        speed: speed_scale,
        factors: system.bodies.iter().flat_map(|b| [1.0, 1.0, b.reach()]).collect(),
    };
    let m_ref = system.reference_mass();
    let mass_sum: f64 = system.bodies.iter().map(|b| b.mass / m_ref).sum();
    let tie = 1e-12 * speed_scale * speed_scale * mass_sum;
    let pool = gather(lcp, previous, starts, tie, &scale);
    let Some(least) = (0..pool.len()).min_by(|&a, &b| pool[a].energy.total_cmp(&pool[b].energy)) else {
        return Err(format!("no verified solution of the {n}x{n} LCP ({k} active contacts)"));
    };
    let l1 = |z: &[f64]| z.iter().sum::<f64>();
    let mut chosen = least;
    for (s, found) in pool.iter().enumerate() {
        if found.energy <= pool[least].energy + tie && l1(&found.z) < l1(&pool[chosen].z) * (1.0 - 1e-12) {
            chosen = s;
        }
    }
    let ambiguous = pool.iter().any(|f| scale.differ(&f.velocity, &pool[chosen].velocity));
    let z = &pool[chosen].z;
    let slot_patterns = patterns_of(&pool[chosen].basis);
    let mut normal = vec![0.0; candidates];
    let mut friction = vec![0.0; candidates];
    let mut patterns = vec![0; candidates];
    for (slot, &i) in lcp.active.iter().enumerate() {
        normal[i] = m_ref * z[slot];
        friction[i] = m_ref * (z[k + 2 * slot] - z[k + 2 * slot + 1]);
        patterns[i] = slot_patterns[slot];
    }
    let v_plus = &pool[chosen].velocity;
    least_norm_load(system, lcp, v_plus, 1e-9 * speed_scale, &mut normal, &mut friction)?;
    let velocity = (0..bodies).map(|i| [v_plus[3 * i], v_plus[3 * i + 1], v_plus[3 * i + 2]]).collect();
    Ok(StepResult { velocity, normal, friction, patterns, ambiguous, solutions: pool.len(), rows: n })
}

/// The load, where the contacts leave it open (docs/formulation.md, "The load: the least norm";
/// `reference/src/load.rs`): the least 2-norm of the candidates' `normal` and `friction` impulses
/// with the motion `v_plus`. A slot touches when it carries load or its normal velocity is within
/// `tolerance` of zero, and sticks when its slip is within it too.
///
/// # Errors
/// No load within the contacts' laws gives the motion.
fn least_norm_load(
    system: &System,
    lcp: &StepLcp,
    v_plus: &[f64],
    tolerance: f64,
    normal: &mut [f64],
    friction: &mut [f64],
) -> Result<(), String> {
    let k = lcp.active.len();
    let n = 4 * k;
    let mut touching: Vec<(usize, Touching)> = Vec::new();
    for (slot, &i) in lcp.active.iter().enumerate() {
        let normal_row = &lcp.rows[slot];
        let normal_velocity = lcp.offset[slot] + dot_n(normal_row, v_plus) - dot_n(normal_row, &lcp.free);
        if normal[i] <= system.impulse_floor() && normal_velocity > tolerance {
            continue;
        }
        let tangent_row = &lcp.rows[k + 2 * slot];
        let slip = -dot_n(tangent_row, v_plus);
        let mu = lcp.matrix[(3 * k + slot) * n + slot];
        let law = if slip.abs() <= tolerance {
            Law::Sticking { mu }
        } else {
            Law::Sliding { f: slip.signum() * mu }
        };
        touching.push((i, Touching { normal: normal_row.clone(), tangent: tangent_row.clone(), law }));
    }
    let contacts: Vec<Touching> = touching.iter().map(|(_, t)| t.clone()).collect();
    if contacts.len() < 2 || determinate(&contacts) {
        return Ok(());
    }
    let mut r = vec![0.0; v_plus.len()];
    let mut scale: f64 = 0.0;
    for (i, t) in &touching {
        scale = scale.max(normal[*i].abs()).max(friction[*i].abs());
        for c in 0..r.len() {
            r[c] += t.normal[c] * normal[*i] + t.tangent[c] * friction[*i];
        }
    }
    let Some(load) = least_norm(&contacts, &r, scale) else {
        return Err(format!("no load within the contacts' laws gives the motion {v_plus:?}"));
    };
    for ((i, _), x) in touching.iter().zip(load) {
        (normal[*i], friction[*i]) = (x[0], x[1]);
    }
    Ok(())
}

/// Each candidate's mode after a step: separated when inactive or its normal impulse is at most
/// the floor (`System::impulse_floor`); else from its slip `s = -d . v_rel(v+)` (the face's
/// owner moving along `+d` relative to the corner: positive).
pub(super) fn modes_after(system: &System, frames: &[Frame], result: &StepResult) -> Vec<Mode> {
    let floor = system.impulse_floor();
    frames
        .iter()
        .zip(&result.normal)
        .map(|(f, &normal)| {
            if !f.active || normal <= floor {
                return Mode::Separated;
            }
            slip_mode(-dot(f.tangent, f.relative_velocity(&result.velocity)), system.stick_speed)
        })
        .collect()
}

/// What one step did.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Stepped {
    /// The candidates at the step's start.
    pub frames: Vec<Frame>,
    /// The step's answer.
    pub result: StepResult,
    /// Modes before the step.
    pub before: Vec<Mode>,
}

impl State {
    /// One step with the solver's `starts`.
    ///
    /// # Errors
    /// No verified solution, or a non-finite state.
    pub fn advance(&mut self, system: &System, starts: Starts) -> Result<Stepped, String> {
        let frames = system.frames(&self.q, &self.v);
        let mu: Vec<f64> = system
            .friction(&frames)
            .iter()
            .zip(&self.modes)
            .map(|(&(mu_s, mu_k), mode)| if mode.is_sliding() { mu_k } else { mu_s })
            .collect();
        let lcp = assemble(system, &self.q, &self.v, &frames, &mu);
        let result = solve(system, &lcp, &self.patterns, frames.len(), starts)?;
        for (q, v) in self.q.iter_mut().zip(&result.velocity) {
            for c in 0..3 {
                q[c] += system.step * v[c];
            }
        }
        if self.q.iter().chain(&result.velocity).flatten().any(|x| !x.is_finite()) {
            return Err("the state became non-finite".to_string());
        }
        self.v.clone_from(&result.velocity);
        self.steps += 1;
        let before = std::mem::replace(&mut self.modes, modes_after(system, &frames, &result));
        self.patterns.clone_from(&result.patterns);
        Ok(Stepped { frames, result, before })
    }
}
