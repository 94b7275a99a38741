//! `host-sim stress`: numerical stability on stiff and extreme cases.
//!
//! A grid of scenes ([`cases`]), each run in the core as f32 6x6 (the firmware's), f32 8x8
//! and f64 8x8, with metrics computed here in f64 from what the core reports after every
//! step. The metrics are physics the core does not compute for itself:
//!
//! * **Penetration** `max(0, -psi)` of each finger under the rod, from the state after each
//!   step: `l = R(theta)^T (f - com)`, `psi = -l_y - t/2` (finger tips at `y = 0`).
//! * **Energy** `E = m (vx^2 + vy^2) / 2 + J omega^2 / 2 + m g y` and the work of the
//!   moving finger over a step, `u . P_1` with `u` the finger's velocity over the step and
//!   `P_1 = n p_n1 + d p_t1` its impulse on the rod (`n`, `d` at the step's start angle).
//!   For the implicit step of eqs. 13-18 one has exactly
//!   `E+ - E <= u . P_1 - sum_i p_ni min(psi_i, 0) / h - (v+ - v)^T M (v+ - v) / 2`
//!   (the normal and friction rows' complementarity, `sigma >= 0`, and
//!   `y+ = y + h vy+`), so apart from round-off the rod gains energy beyond the finger's
//!   work only by pushing out of a penetration.
//! * **LCP residual**: the normalised residual of each step's verified solution over the
//!   solver's tolerance (`256 N eps`; see `meterstick_core::lcp::verify`).
//!
//! # Pass criteria (per case and implementation; a case passes when all three pass)
//! 1. no panic;
//! 2. the run ends in a physical outcome (`Balanced`, `Fell`, `Unfinished`): no non-finite
//!    state, no solver error (valid parameters must be simulable);
//! 3. every LCP verified: residual over tolerance `<= 1` (guaranteed by the core, checked
//!    here);
//! 4. penetration `<= ` [`penetration_bound`]: the start's penetration plus the second-order
//!    terms of one step (`h^2 (|omega| (|u| + |v|) + L omega^2 / 2 + g)`), plus round-off;
//! 5. no energy from nowhere: over the whole run, `E(t) - E(0) - W_finger(0, t)` stays below
//!    `m g pen_0` (the potential energy a start penetration owes: the rod may climb back
//!    to where it should rest, not higher) plus [`energy_tolerance`];
//! 6. the physics claim of the case, where physics decides one: the outcome class (by
//!    similarity, mass scaling, or a clear quasi-static argument), "the rod is not dragged"
//!    (frictionless contacts, `mu_k = 0`: while finger 1 is left of the centre of mass the rod
//!    does not move along `x`), or "nothing moves" (zero speed, zero gravity).
//!
//! A case marked as a known limit reports its reason; its failures count as known limits,
//! not as passes.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use meterstick_core::Real;
use meterstick_core::lcp::default_tolerance;
use meterstick_core::scene::{Outcome, RodState, Scene, SceneParams};
use rayon::prelude::*;
use serde_json::json;

use crate::plot;
use crate::report::Config;
use crate::run_cmd::{params_json, progress, write_json};
use crate::trajectory::{CORE_EVENTS, RunOutcome, convert};

/// `host-sim stress` options.
#[derive(Debug, Clone, clap::Args)]
pub struct StressArgs {
    /// Output directory (created; files in it are overwritten).
    #[arg(long, default_value = "out/stress")]
    pub out: PathBuf,
    /// The small subset (a few seconds, for tests).
    #[arg(long)]
    pub quick: bool,
    /// Only cases whose name contains this.
    #[arg(long)]
    pub only: Option<String>,
}

/// A physics claim a case makes beyond the generic criteria.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Claim {
    /// None: the generic criteria only.
    None,
    /// While finger 1 is left of the centre of mass (by 1 % of `L`), the rod does not move
    /// along `x` (frictionless contacts or `mu_k = 0`: no force can drag it).
    NotDragged,
    /// The rod does not move at all (zero finger speed, or zero gravity: no force on it).
    RodStill,
}

/// One scene of the grid.
#[derive(Debug, Clone)]
pub struct Case {
    /// Which part of the grid.
    pub group: &'static str,
    /// A short name, unique.
    pub name: String,
    /// The scene.
    pub params: SceneParams<f64>,
    /// Start height above the resting position (m; negative: penetrating).
    pub start_dy: f64,
    /// The outcome class physics decides, if any.
    pub outcome: Option<&'static str>,
    /// Further claim.
    pub claim: Claim,
    /// Why this case is a known limit, if it is one.
    pub known_limit: Option<&'static str>,
}

/// The core configurations the grid runs.
pub const CONFIGS: [Config; 3] = [Config::CoreF32x6, Config::CoreF32x8, Config::CoreF64x8];

/// What one run of one case measured.
#[derive(Debug, Clone, Default)]
pub struct Metrics {
    /// `Balanced`, `Fell`, `Unfinished` or `Failed(..)` (`Panicked` when it panicked).
    pub outcome: String,
    /// Solver error kind, if the run ended on one.
    pub solver_error: Option<String>,
    /// The state became non-finite.
    pub non_finite: bool,
    /// The run panicked.
    pub panicked: bool,
    /// Steps taken.
    pub steps: u64,
    /// Largest verification residual over the tolerance.
    pub residual_ratio: f64,
    /// Largest penetration (m).
    pub penetration: f64,
    /// Largest penetration over its bound.
    pub penetration_ratio: f64,
    /// Largest `E+ - E - W_finger` over one step (J).
    pub step_energy_gain: f64,
    /// Largest `E(t) - E(0) - W_finger(0, t)` (J).
    pub energy_gain: f64,
    /// `energy_gain` over its allowance (`m g pen_0 + tolerance`).
    pub energy_ratio: f64,
    /// Most pivots in one step.
    pub max_pivots: u32,
    /// Mean pivots per step.
    pub mean_pivots: f64,
    /// 6x6 check firings.
    pub reduced_check_fired: u64,
    /// For [`Claim::NotDragged`]: largest `|x - x_0|` while finger 1 was left of the centre
    /// of mass; for [`Claim::RodStill`]: largest change of `x`, `y`, `L theta / 2` (m).
    pub claim_motion: f64,
    /// Solves answered by the solver's regularised retry.
    pub regularized_solves: u64,
    /// Machine epsilon of the run's scalar.
    pub eps: f64,
    /// Sampled `(x, y, theta)` for the f32-vs-f64 deviation.
    pub trace: Vec<[f64; 3]>,
    /// Wall-clock time (s).
    pub wall_s: f64,
}

/// Largest claim motion counted as "not moving", in units of `eps L`: round-off of a
/// position (a tilt of `eps` from rounding gives the normal impulse a horizontal part).
const STILL_TOLERANCE: f64 = 64.0;

/// The penetration bound of one step (criterion 4): what the step started with, the
/// second-order terms of the step's geometry (`h^2` times `|omega| (|u| + |v|)` for the
/// contact point's turning, `L omega^2 / 2` for the arc, `g` for gravity within the step),
/// and round-off of the coordinates (`64 eps (L + t + |x| + |y|)`).
#[must_use]
pub fn penetration_bound(p: &SceneParams<f64>, eps: f64, pen_before: f64, s: &[f64; 6], u: f64) -> f64 {
    let h = p.step;
    let omega = s[5].abs();
    let speed = s[3].abs() + s[4].abs();
    pen_before
        + h * h * (omega * (u.abs() + speed) + p.rod_length * omega * omega / 2.0 + p.gravity)
        + 64.0 * eps * (p.rod_length + p.rod_thickness + s[0].abs() + s[1].abs())
}

/// Round-off allowance of the run's energy balance (criterion 5): `4096 N eps` of the
/// energy scale `m (g (L + |y|) + v_f^2 + |v|^2 + (L omega)^2)` at the step (`v_f` the
/// finger speed parameter), where `N` is the
/// LCP size (the verification tolerance is `256 N eps`, and each of `N` complementarity
/// products contributes up to it times the impulse and velocity scales).
#[must_use]
pub fn energy_tolerance(p: &SceneParams<f64>, eps: f64, n: usize, s: &[f64; 6]) -> f64 {
    let v2 = s[3] * s[3] + s[4] * s[4] + (p.rod_length * s[5]).powi(2);
    let u2 = p.finger_speed * p.finger_speed;
    4096.0 * n as f64 * eps * p.rod_mass * (p.gravity * (p.rod_length + s[1].abs()) + u2 + v2)
}

fn energy(p: &SceneParams<f64>, s: &[f64; 6]) -> f64 {
    let j = p.rod_mass * p.rod_length * p.rod_length / 12.0;
    0.5 * p.rod_mass * (s[3] * s[3] + s[4] * s[4]) + 0.5 * j * s[5] * s[5] + p.rod_mass * p.gravity * s[1]
}

/// Each finger's penetration (0 when not under the rod or not touching).
fn penetrations(p: &SceneParams<f64>, s: &[f64; 6], fingers: [f64; 2]) -> [f64; 2] {
    let (sn, cn) = s[2].sin_cos();
    fingers.map(|fx| {
        let (dx, dy) = (fx - s[0], -s[1]);
        let lx = cn * dx + sn * dy;
        let ly = -sn * dx + cn * dy;
        if lx.abs() <= p.rod_length / 2.0 { (-(-ly - p.rod_thickness / 2.0)).max(0.0) } else { 0.0 }
    })
}

fn state_of<T: Real>(s: &RodState<T>) -> [f64; 6] {
    [s.x, s.y, s.theta, s.vx, s.vy, s.omega].map(Real::as_f64)
}

/// Runs one case in scalar `T` with LCP size `N`, measuring as it goes; samples the state
/// every `stride` steps.
fn measure<T: Real, const N: usize>(case: &Case, stride: u64) -> Metrics {
    let started = Instant::now();
    let p = &case.params;
    let eps = T::EPS.as_f64();
    let pt = convert::<T>(p);
    let mut start = RodState::resting(&pt);
    start.y += T::of(case.start_dy);
    let mut scene = match Scene::<T, N, CORE_EVENTS>::with_state(pt, start) {
        Ok(s) => s,
        Err(e) => return Metrics { outcome: format!("Failed(invalid: {e})"), ..Metrics::default() },
    };
    let mut m = Metrics { eps, ..Metrics::default() };
    let mut s = state_of(scene.state());
    let s0 = s;
    let mut fingers = scene.fingers().map(Real::as_f64);
    let pen0 = penetrations(p, &s, fingers).iter().fold(0.0_f64, |a, &b| a.max(b));
    let e0 = energy(p, &s);
    let mut e_before = e0;
    let mut work = 0.0;
    let mut pen = penetrations(p, &s, fingers);
    m.trace.push([s[0], s[1], s[2]]);
    while let Some(r) = scene.step() {
        if r.error.is_some() {
            break;
        }
        // The 8x8 tolerance when the 6x6 check sent the step to the 8x8 model.
        let n_used = if r.reduced_check_failed { 8.0 } else { N as f64 };
        let tolerance = default_tolerance::<T, 8>().as_f64() * n_used / 8.0;
        m.residual_ratio = m.residual_ratio.max(r.residual.as_f64() / tolerance);
        m.max_pivots = m.max_pivots.max(r.pivots);
        let after = state_of(&r.state);
        let fingers_after = r.fingers.map(Real::as_f64);
        let u = (fingers_after[0] - fingers[0]) / p.step;
        let (sn, cn) = s[2].sin_cos();
        let step_work = u * (-sn * r.normal_impulse[0].as_f64() + cn * r.friction_impulse[0].as_f64());
        let e_after = energy(p, &after);
        if e_after.is_finite() {
            m.step_energy_gain = m.step_energy_gain.max(e_after - e_before - step_work);
            work += step_work;
            let gain = e_after - e0 - work;
            m.energy_gain = m.energy_gain.max(gain);
            let allowance = p.rod_mass * p.gravity * pen0 + energy_tolerance(p, eps, N, &after);
            m.energy_ratio = m.energy_ratio.max(gain / allowance);
        }
        let pen_after = penetrations(p, &after, fingers_after);
        for i in 0..2 {
            let bound = penetration_bound(p, eps, pen[i], &s, u);
            m.penetration = m.penetration.max(pen_after[i]);
            m.penetration_ratio = m.penetration_ratio.max(pen_after[i] / bound);
        }
        match case.claim {
            Claim::NotDragged => {
                if fingers_after[0] < after[0] - 0.01 * p.rod_length {
                    m.claim_motion = m.claim_motion.max((after[0] - s0[0]).abs());
                }
            }
            Claim::RodStill => {
                let moved = [after[0] - s0[0], after[1] - s0[1], p.rod_length / 2.0 * (after[2] - s0[2])];
                m.claim_motion = moved.iter().fold(m.claim_motion, |a, d| a.max(d.abs()));
            }
            Claim::None => {}
        }
        s = after;
        e_before = e_after;
        fingers = fingers_after;
        pen = pen_after;
        if scene.stats().steps % stride == 0 {
            m.trace.push([s[0], s[1], s[2]]);
        }
    }
    let stats = scene.stats();
    m.steps = stats.steps;
    m.mean_pivots = stats.pivots as f64 / stats.steps.max(1) as f64;
    m.reduced_check_fired = stats.reduced_check_fired;
    m.regularized_solves = stats.regularized_solves;
    let outcome = scene.outcome().unwrap_or(Outcome::Unfinished);
    m.non_finite = outcome == Outcome::NonFinite;
    if let Outcome::SolverFailed(e) = outcome {
        m.solver_error = Some(format!("{e:?}"));
    }
    m.outcome = RunOutcome::from(outcome).to_string();
    m.wall_s = started.elapsed().as_secs_f64();
    m
}

/// Runs `case` in `config`, catching a panic.
#[must_use]
pub fn run_case(case: &Case, config: Config) -> Metrics {
    let p = &case.params;
    let stride = ((p.max_time / p.step) / 100_000.0).ceil().max(1.0) as u64;
    let run = std::panic::catch_unwind(|| match config {
        Config::CoreF32x6 => measure::<f32, 6>(case, stride),
        Config::CoreF32x8 => measure::<f32, 8>(case, stride),
        Config::CoreF64x8 | Config::Reference => measure::<f64, 8>(case, stride),
    });
    run.unwrap_or_else(|_| Metrics { outcome: "Panicked".into(), panicked: true, ..Metrics::default() })
}

/// The verdict of one run against the pass criteria.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verdict {
    /// The criteria that failed (empty: passed).
    pub failures: Vec<&'static str>,
}

impl Verdict {
    /// `true` when every criterion passed.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

/// Applies the pass criteria (module docs) to one run of `case`.
#[must_use]
pub fn judge(case: &Case, m: &Metrics) -> Verdict {
    let mut failures = Vec::new();
    if m.panicked {
        failures.push("panic");
    }
    if m.non_finite {
        failures.push("non-finite state");
    }
    if m.solver_error.is_some() || m.outcome.starts_with("Failed") {
        failures.push("no physical outcome");
    }
    if m.residual_ratio > 1.0 {
        failures.push("LCP residual");
    }
    if m.penetration_ratio > 1.0 {
        failures.push("penetration");
    }
    if m.energy_ratio > 1.0 {
        failures.push("energy gain");
    }
    if let Some(expected) = case.outcome
        && m.outcome != expected
    {
        failures.push("outcome");
    }
    if case.claim != Claim::None && m.claim_motion > STILL_TOLERANCE * m.eps * case.params.rod_length {
        failures.push(match case.claim {
            Claim::NotDragged => "rod dragged",
            _ => "rod moved",
        });
    }
    Verdict { failures }
}

/// The paper's scene with finger 1 at -0.35 (asymmetric, as the main job's slow scene).
fn base() -> SceneParams<f64> {
    let mut p = SceneParams::paper();
    p.finger1_x = -0.35;
    p
}

/// The base scene at finger speed `v`, with `stick_speed` 1e-4 of it (as the paper's 1e-5
/// of 0.1 m/s) and room for the fingers to meet and the hold time.
fn at_speed(v: f64) -> SceneParams<f64> {
    let mut p = base();
    p.finger_speed = v;
    p.stick_speed = if v > 0.0 { 1e-4 * v } else { 1e-5 };
    if v > 0.0 {
        p.max_time = (1.2 * (p.finger2_x - p.finger1_x) / v + 5.0).min(1000.0);
    } else {
        p.max_time = 2.0;
    }
    p
}

/// The base scene scaled to rod length `l` with every dimensionless group kept
/// (`v / sqrt(g L)`, `h sqrt(g / L)`, `t / L`, ...): by similarity it ends as the base does.
fn similar(l: f64) -> SceneParams<f64> {
    let mut p = base();
    let k = l / p.rod_length;
    let kt = k.sqrt();
    p.rod_length *= k;
    p.rod_thickness *= k;
    p.finger1_x *= k;
    p.finger2_x *= k;
    p.finger_width *= k;
    p.drop_limit *= k;
    p.finger_speed *= kt;
    p.stick_speed *= kt;
    p.step *= kt;
    p.hold_time *= kt;
    p.max_time *= kt;
    p
}

/// The grid (`quick`: the subset the test command runs).
#[must_use]
#[allow(clippy::too_many_lines)] // one table of cases
pub fn cases(quick: bool) -> Vec<Case> {
    let mut out = Vec::new();
    let mut add = |group: &'static str,
                   name: &str,
                   params: SceneParams<f64>,
                   start_dy: f64,
                   outcome: Option<&'static str>,
                   claim: Claim| {
        out.push(Case { group, name: name.into(), params, start_dy, outcome, claim, known_limit: None });
    };
    let balanced = Some("Balanced");
    let fell = Some("Fell");
    let unfinished = Some("Unfinished");

    // Finger speed, h = 1 ms.
    add("speed", "v=0", at_speed(0.0), 0.0, unfinished, Claim::RodStill);
    if !quick {
        add("speed", "v=1e-4 (10^6 steps)", at_speed(1e-4), 0.0, unfinished, Claim::None);
        add("speed", "v=1e-3", at_speed(1e-3), 0.0, balanced, Claim::None);
        add("speed", "v=1e-2", at_speed(1e-2), 0.0, balanced, Claim::None);
    }
    add("speed", "v=0.1", at_speed(0.1), 0.0, balanced, Claim::None);
    if !quick {
        add("speed", "v=1", at_speed(1.0), 0.0, fell, Claim::None);
        add("speed", "v=10", at_speed(10.0), 0.0, fell, Claim::None);
    }
    add("speed", "v=100", at_speed(100.0), 0.0, fell, Claim::None);

    // Time step.
    let with_h = |v: f64, h: f64, max_time: Option<f64>| {
        let mut p = at_speed(v);
        p.step = h;
        if let Some(t) = max_time {
            p.max_time = t;
        }
        p
    };
    if !quick {
        add("h", "v=0.1 h=1e-5", with_h(0.1, 1e-5, None), 0.0, balanced, Claim::None);
        add("h", "v=0.1 h=1e-4", with_h(0.1, 1e-4, None), 0.0, balanced, Claim::None);
        add("h", "v=0.1 h=1e-2", with_h(0.1, 1e-2, None), 0.0, None, Claim::None);
        add("h", "v=0.1 h=5e-2", with_h(0.1, 5e-2, None), 0.0, None, Claim::None);
        add("h", "v=1 h=1e-6", with_h(1.0, 1e-6, Some(1.0)), 0.0, fell, Claim::None);
        add("h", "v=1 h=5e-2", with_h(1.0, 5e-2, None), 0.0, None, Claim::None);
        add("h", "v=0.1 h=10 (> crossing time 7 s)", with_h(0.1, 10.0, None), 0.0, None, Claim::None);
    }
    add("h", "v=10 h=0.1 (> crossing time 0.07 s)", with_h(10.0, 0.1, None), 0.0, None, Claim::None);

    // Friction.
    let with_mu = |mu_s: f64, mu_k: f64| {
        let mut p = base();
        p.mu_static = mu_s;
        p.mu_kinetic = mu_k;
        p
    };
    add("friction", "mu=0 (frictionless)", with_mu(0.0, 0.0), 0.0, fell, Claim::NotDragged);
    if !quick {
        add("friction", "mu_s=0.6 mu_k=0", with_mu(0.6, 0.0), 0.0, fell, Claim::NotDragged);
        add("friction", "mu_s=mu_k=0.4", with_mu(0.4, 0.4), 0.0, None, Claim::None);
        add("friction", "mu_s=0.05 mu_k=0.04", with_mu(0.05, 0.04), 0.0, None, Claim::None);
        add("friction", "mu_s=mu_k=10", with_mu(10.0, 10.0), 0.0, None, Claim::None);
        add("friction", "mu_s=10 mu_k=5", with_mu(10.0, 5.0), 0.0, None, Claim::None);
    }

    // Mass: every force scales with m, so the motion does not depend on it.
    for (k, mass) in [1e-4, 1e-2, 1.0, 1e2, 1e4].into_iter().enumerate() {
        if quick && k != 0 && k != 4 {
            continue;
        }
        let mut p = base();
        p.rod_mass = mass;
        add("mass", &format!("m={mass:e} kg"), p, 0.0, balanced, Claim::None);
    }

    // Rod shape: similar rods end as the base does; thin and thick rods, and unscaled
    // short and long rods, make no claim.
    if !quick {
        add("shape", "similar L=0.01 m", similar(0.01), 0.0, balanced, Claim::None);
        add("shape", "similar L=100 m", similar(100.0), 0.0, balanced, Claim::None);
        let mut p = base();
        p.rod_length = 0.01;
        p.finger1_x = -0.0035;
        p.finger2_x = 0.004;
        p.finger_width = 1e-4;
        add("shape", "short L=0.01 m, v=0.1", p, 0.0, None, Claim::None);
        let mut p = base();
        p.rod_length = 100.0;
        p.finger1_x = -35.0;
        p.finger2_x = 40.0;
        p.finger_width = 1.0;
        p.drop_limit = 2.0;
        add("shape", "long L=100 m, v=0.1", p, 0.0, None, Claim::None);
        let mut p = base();
        p.rod_thickness = 1e-5;
        add("shape", "thin t=1e-5 m", p, 0.0, balanced, Claim::None);
        let mut p = base();
        p.rod_thickness = 0.2;
        add("shape", "thick t=0.2 m", p, 0.0, None, Claim::None);
    }

    // Gravity.
    let gravities =
        [(0.0, unfinished, Claim::RodStill), (1.0, None, Claim::None), (100.0, balanced, Claim::None)];
    for (k, (g, outcome, claim)) in gravities.into_iter().enumerate() {
        if quick && k != 0 {
            continue;
        }
        let mut p = base();
        p.gravity = g;
        p.max_time = 10.0;
        add("gravity", &format!("g={g}"), p, 0.0, outcome, claim);
    }

    // Geometry at the edges.
    if !quick {
        let mut p = base();
        p.finger1_x = -0.5;
        p.finger2_x = 0.5;
        add("edges", "fingers at the rod ends", p, 0.0, None, Claim::None);
        let mut p = base();
        p.finger1_x = -0.0051;
        p.finger2_x = 0.005;
        add("edges", "fingers nearly together", p, 0.0, balanced, Claim::None);
        let mut p = base();
        p.finger_width = 1e-6;
        add("edges", "finger width 1e-6 m", p, 0.0, None, Claim::None);
        let mut p = base();
        p.finger1_x = 0.0;
        add("edges", "finger 1 under the COM", p, 0.0, None, Claim::None);
        let mut p = base();
        p.finger1_x = -0.4;
        p.finger2_x = 0.0;
        add("edges", "finger 2 under the COM", p, 0.0, None, Claim::None);
        add("edges", "drop from 1 cm", base(), 0.01, None, Claim::None);
    }
    add("edges", "drop from 1 mm", base(), 1e-3, balanced, Claim::None);
    add("edges", "penetrating 0.1 mm", base(), -1e-4, balanced, Claim::None);
    if !quick {
        add("edges", "penetrating 1 mm", base(), -1e-3, balanced, Claim::None);
        let mut p = base();
        p.step = 1e-5;
        add("edges", "penetrating 0.1 mm, h=1e-5", p, -1e-4, balanced, Claim::None);
    }
    if quick {
        // Short runs (at most 5 s simulated): the subset checks the criteria, not long
        // physics; a run cut short cannot balance.
        for c in &mut out {
            if c.params.max_time > 5.0 {
                c.params.max_time = 5.0;
                if c.outcome == balanced {
                    c.outcome = unfinished;
                }
            }
        }
    }
    out
}

/// One case's runs.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The case.
    pub case: Case,
    /// One per [`CONFIGS`] entry.
    pub runs: Vec<(Metrics, Verdict)>,
    /// Largest `|COM_f32 - COM_f64|` (m) of the f32 6x6 and f32 8x8 runs against f64 8x8,
    /// over the sampled steps both have.
    pub deviation: [f64; 2],
}

impl CaseResult {
    /// `pass`, `FAIL` or `known limit`.
    #[must_use]
    pub fn status(&self) -> &'static str {
        let passed = self.runs.iter().all(|(_, v)| v.passed());
        match (passed, self.case.known_limit) {
            (true, _) => "pass",
            (false, None) => "FAIL",
            (false, Some(_)) => "known limit",
        }
    }
}

fn deviation(a: &Metrics, b: &Metrics) -> f64 {
    a.trace.iter().zip(&b.trace).fold(0.0, |acc, (x, y)| acc.max((x[0] - y[0]).hypot(x[1] - y[1])))
}

/// Runs every case in every configuration (in parallel).
#[must_use]
pub fn run_all(cases: Vec<Case>) -> Vec<CaseResult> {
    let jobs: Vec<(usize, Config)> =
        (0..cases.len()).flat_map(|i| CONFIGS.iter().map(move |&c| (i, c))).collect();
    let bar = progress(jobs.len() as u64, "stress runs");
    let mut done: Vec<(usize, Config, Metrics)> = jobs
        .par_iter()
        .map(|&(i, config)| {
            let m = run_case(&cases[i], config);
            bar.inc(1);
            (i, config, m)
        })
        .collect();
    bar.finish_and_clear();
    done.sort_by_key(|(i, c, _)| (*i, CONFIGS.iter().position(|x| x == c)));
    let mut results: Vec<CaseResult> = Vec::new();
    let mut runs = done.into_iter().peekable();
    for case in cases {
        let mut mine = Vec::new();
        while let Some((_, _, m)) = runs.next_if(|(i, _, _)| *i == results.len()) {
            let v = judge(&case, &m);
            mine.push((m, v));
        }
        let deviation = [deviation(&mine[0].0, &mine[2].0), deviation(&mine[1].0, &mine[2].0)];
        for (m, _) in &mut mine {
            m.trace = Vec::new();
        }
        results.push(CaseResult { case, runs: mine, deviation });
    }
    results
}

/// `host-sim stress`: runs the grid, writes `report.md`, `cases.csv`, `summary.json` and
/// `criteria.svg` to `args.out`, and returns the terminal summary and whether no case
/// failed (known limits aside).
///
/// # Errors
/// I/O.
pub fn run(args: &StressArgs) -> anyhow::Result<(String, bool)> {
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let mut cases = cases(args.quick);
    if let Some(only) = &args.only {
        cases.retain(|c| c.name.contains(only.as_str()));
    }
    let started = Instant::now();
    let results = run_all(cases);
    let wall = started.elapsed().as_secs_f64();
    write_csv(&args.out.join("cases.csv"), &results)?;
    plot_criteria(&args.out.join("criteria.svg"), &results)?;
    let md = markdown(&results, wall);
    std::fs::write(args.out.join("report.md"), &md)?;
    let count = |s: &str| results.iter().filter(|r| r.status() == s).count();
    let summary = json!({
        "cases": results.len(),
        "runs": results.len() * CONFIGS.len(),
        "passed": count("pass"),
        "failed": count("FAIL"),
        "known_limits": count("known limit"),
        "steps": results.iter().flat_map(|r| r.runs.iter().map(|(m, _)| m.steps)).sum::<u64>(),
        "wall_s": wall,
        "cases_detail": results.iter().map(|r| json!({
            "name": r.case.name,
            "group": r.case.group,
            "status": r.status(),
            "params": params_json(&r.case.params),
            "start_dy": r.case.start_dy,
            "deviation_f32x6_m": r.deviation[0],
            "deviation_f32x8_m": r.deviation[1],
            "runs": r.runs.iter().zip(CONFIGS).map(|((m, v), c)| json!({
                "config": c.label(),
                "outcome": m.outcome,
                "steps": m.steps,
                "failures": v.failures,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    });
    write_json(&args.out.join("summary.json"), &summary)?;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "stress: {} cases x {} implementations in {wall:.1} s: {} passed, {} failed, {} known limits",
        results.len(),
        CONFIGS.len(),
        count("pass"),
        count("FAIL"),
        count("known limit")
    );
    for r in results.iter().filter(|r| r.status() != "pass") {
        let why: Vec<String> = r
            .runs
            .iter()
            .zip(CONFIGS)
            .filter(|((_, v), _)| !v.passed())
            .map(|((m, v), c)| format!("{}: {} ({})", c.label(), v.failures.join(", "), m.outcome))
            .collect();
        let _ = writeln!(out, "  {} [{}]: {}", r.case.name, r.status(), why.join("; "));
    }
    let _ = writeln!(out, "report: {}", args.out.join("report.md").display());
    Ok((out, count("FAIL") == 0))
}

fn sci(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:.1e}") }
}

fn write_csv(path: &Path, results: &[CaseResult]) -> anyhow::Result<()> {
    let mut s = String::from(
        "group,case,status,config,outcome,steps,residual_over_tol,max_penetration_m,penetration_over_bound,\
         max_step_energy_gain_J,max_energy_gain_J,energy_gain_over_allowance,max_pivots,mean_pivots,\
         reduced_check_fired,regularized_solves,solver_error,non_finite,panicked,claim_motion_m,deviation_from_f64_m,failures,wall_s\n",
    );
    for r in results {
        for (k, ((m, v), c)) in r.runs.iter().zip(CONFIGS).enumerate() {
            let dev = r.deviation.get(k).map_or(String::new(), ToString::to_string);
            let _ = writeln!(
                s,
                "{},\"{}\",{},{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\",{}",
                r.case.group,
                r.case.name,
                r.status(),
                c.label(),
                m.outcome,
                m.steps,
                m.residual_ratio,
                m.penetration,
                m.penetration_ratio,
                m.step_energy_gain,
                m.energy_gain,
                m.energy_ratio,
                m.max_pivots,
                m.mean_pivots,
                m.reduced_check_fired,
                m.regularized_solves,
                m.solver_error.as_deref().unwrap_or(""),
                m.non_finite,
                m.panicked,
                m.claim_motion,
                dev,
                v.failures.join("; "),
                m.wall_s
            );
        }
    }
    std::fs::write(path, s).with_context(|| format!("writing {}", path.display()))
}

/// The heat map: one row per case, one column per (implementation, criterion), coloured by
/// `log10(value / bound)`.
fn plot_criteria(path: &Path, results: &[CaseResult]) -> anyhow::Result<()> {
    let mut columns = Vec::new();
    for c in CONFIGS {
        let short = c.label().trim_start_matches("core ");
        for what in ["res.", "pen.", "energy"] {
            columns.push(format!("{short} {what}"));
        }
    }
    // Rows are drawn bottom-up: reversed, the first case is at the top.
    let rows: Vec<String> = results.iter().rev().map(|r| r.case.name.clone()).collect();
    let values: Vec<Vec<Option<f64>>> = results
        .iter()
        .rev()
        .map(|r| {
            r.runs
                .iter()
                .flat_map(|(m, _)| {
                    let ran = m.steps > 0;
                    [m.residual_ratio, m.penetration_ratio, m.energy_ratio].map(|x| ran.then_some(x))
                })
                .collect()
        })
        .collect();
    plot::ratio_map(
        path,
        "stress: each criterion's worst value over its bound (log10)",
        &columns,
        &rows,
        &values,
    )
}

fn markdown(results: &[CaseResult], wall: f64) -> String {
    let count = |s: &str| results.iter().filter(|r| r.status() == s).count();
    let mut md = String::new();
    let _ = writeln!(md, "# meterstick stress report\n");
    let _ = writeln!(
        md,
        "{} cases x {} implementations (core f32 6x6, f32 8x8, f64 8x8), {} steps in all, {wall:.1} s wall \
         clock: **{} passed, {} failed, {} known limits**.\n",
        results.len(),
        CONFIGS.len(),
        results.iter().flat_map(|r| r.runs.iter().map(|(m, _)| m.steps)).sum::<u64>(),
        count("pass"),
        count("FAIL"),
        count("known limit"),
    );
    md.push_str(CRITERIA_MD);
    md.push_str("\n![criteria](criteria.svg)\n\n");
    let _ = writeln!(
        md,
        "| group | case | status | f32 6x6 | f32 8x8 | f64 8x8 | steps (f32 6x6) | residual/tol | \
         max penetration (m) | pen./bound | max step gain (J) | max run gain (J) | gain/allowance | \
         max pivots | mean pivots | 6x6 check | regularised | dev. f32 6x6 / 8x8 vs f64 (m) |"
    );
    let _ = writeln!(md, "|{}", "---|".repeat(18));
    for r in results {
        let worst = |f: fn(&Metrics) -> f64| r.runs.iter().map(|(m, _)| f(m)).fold(0.0_f64, f64::max);
        let outcome = |k: usize| {
            let (m, v) = &r.runs[k];
            if v.passed() {
                m.outcome.clone()
            } else {
                format!("{} ✗ {}", m.outcome, v.failures.join(", "))
            }
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.3} | {} | {} | {} / {} |",
            r.case.group,
            r.case.name,
            r.status(),
            outcome(0),
            outcome(1),
            outcome(2),
            r.runs[0].0.steps,
            sci(worst(|m| m.residual_ratio)),
            sci(worst(|m| m.penetration)),
            sci(worst(|m| m.penetration_ratio)),
            sci(worst(|m| m.step_energy_gain)),
            sci(worst(|m| m.energy_gain)),
            sci(worst(|m| m.energy_ratio)),
            r.runs.iter().map(|(m, _)| m.max_pivots).max().unwrap_or(0),
            r.runs[0].0.mean_pivots,
            r.runs[0].0.reduced_check_fired,
            r.runs.iter().map(|(m, _)| m.regularized_solves).sum::<u64>(),
            sci(r.deviation[0]),
            sci(r.deviation[1]),
        );
    }
    let limits: Vec<&CaseResult> = results.iter().filter(|r| r.case.known_limit.is_some()).collect();
    if !limits.is_empty() {
        md.push_str("\n## Known limits\n\n");
        for r in limits {
            let _ =
                writeln!(md, "- **{}** ({}): {}", r.case.name, r.status(), r.case.known_limit.unwrap_or(""));
        }
    }
    md
}

const CRITERIA_MD: &str = "\
## Criteria (per case and implementation; a case passes when every implementation passes)

1. no panic;
2. a physical outcome (Balanced, Fell, Unfinished): no non-finite state, no solver error;
3. every LCP verified: the normalised residual over the solver's tolerance (256 N eps) at most 1;
4. penetration at most the start's penetration plus the second-order terms of one step,
   h^2 (|omega| (|u| + |v|) + L omega^2 / 2 + g), plus 64 eps (L + t + |x| + |y|) of round-off;
5. no energy from nowhere: over the run, E(t) - E(0) - W_finger(0, t) at most m g pen_0 (what a
   start penetration owes) plus 4096 N eps m (g (L + |y|) + v_f^2 + |v|^2 + (L omega)^2). The
   implicit step satisfies E+ - E <= u . P_1 - sum p_n min(psi, 0) / h exactly, so only round-off
   and penetration recovery can add energy;
6. the case's physics claim where physics decides: the outcome class (similar scenes, mass
   scaling, quasi-static slow fingers, fast fingers), 'not dragged' (frictionless or mu_k = 0:
   while finger 1 is left of the COM the rod does not move along x by more than 64 eps L),
   'rod still' (zero speed or zero gravity: the rod does not move by more than 64 eps L).

Energies in J, lengths in m. 'dev.' is the largest distance between the f32 and the f64 8x8
centre of mass over the sampled steps both runs have (a chaotic case diverges legitimately).
";

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)]
    use super::*;

    type Breaker = fn(&mut Metrics);

    fn passing() -> Metrics {
        Metrics { outcome: "Balanced".into(), steps: 10, eps: f64::from(f32::EPSILON), ..Metrics::default() }
    }

    fn case(outcome: Option<&'static str>, claim: Claim) -> Case {
        Case {
            group: "test",
            name: "test".into(),
            params: base(),
            start_dy: 0.0,
            outcome,
            claim,
            known_limit: None,
        }
    }

    /// Each criterion can fail, alone.
    #[test]
    fn every_criterion_can_fail() {
        let c = case(Some("Balanced"), Claim::NotDragged);
        assert!(judge(&c, &passing()).passed());
        let failing: [(&str, Breaker); 8] = [
            ("panic", |m| m.panicked = true),
            ("non-finite state", |m| m.non_finite = true),
            ("no physical outcome", |m| m.solver_error = Some("Ray".into())),
            ("LCP residual", |m| m.residual_ratio = 1.5),
            ("penetration", |m| m.penetration_ratio = 1.01),
            ("energy gain", |m| m.energy_ratio = 2.0),
            ("outcome", |m| m.outcome = "Fell".into()),
            ("rod dragged", |m| m.claim_motion = 1e-4),
        ];
        for (what, break_it) in failing {
            let mut m = passing();
            break_it(&mut m);
            let v = judge(&c, &m);
            assert!(v.failures.contains(&what), "{what}: {v:?}");
        }
    }

    /// The energy measure: a free fall loses `m g^2 h^2 / 2` per step (symplectic Euler), a
    /// push-out at `|psi| / h` gains more than `m g |psi|`.
    #[test]
    fn energy_and_penetration_helpers() {
        let p = base();
        let rest = [0.0, p.rod_thickness / 2.0, 0.0, 0.0, 0.0, 0.0];
        assert_eq!(energy(&p, &rest), p.rod_mass * p.gravity * p.rod_thickness / 2.0);
        let sunk = [0.0, p.rod_thickness / 2.0 - 1e-4, 0.0, 0.0, 0.0, 0.0];
        let pen = penetrations(&p, &sunk, [p.finger1_x, p.finger2_x]);
        assert!((pen[0] - 1e-4).abs() < 1e-15 && (pen[1] - 1e-4).abs() < 1e-15, "{pen:?}");
        let outside = penetrations(&p, &sunk, [0.6, -0.6]);
        assert_eq!(outside, [0.0, 0.0]);
        let pushed = [0.0, sunk[1], 0.0, 0.0, 1e-4 / p.step, 0.0];
        assert!(energy(&p, &pushed) - energy(&p, &sunk) > p.rod_mass * p.gravity * 1e-4);
    }

    #[test]
    fn the_quick_grid_is_a_subset_with_unique_names() {
        let full = cases(false);
        let quick = cases(true);
        assert!(quick.len() < full.len());
        for c in &quick {
            assert!(full.iter().any(|f| f.name == c.name), "{}", c.name);
        }
        let mut names: Vec<&str> = full.iter().map(|c| c.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), full.len());
    }
}
