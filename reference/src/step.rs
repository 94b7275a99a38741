//! One time step: docs/formulation.md, "One time step (eqs. 13-18)" and "Friction and contact
//! modes".
//!
//! Only the `k` active contacts enter the LCP, each with the paper's full form: one normal
//! impulse, two friction impulses (along `+d` and `-d`) and one `sigma`, so
//! `z = (p_n[1..k], p_+d[1], p_-d[1], ..., p_+d[k], p_-d[k], sigma[1..k])` and `n = 4k`. With
//! the wrench columns `W` of the `3k` impulses (eq. 3) and `v~ = v + h (0, -g, 0)` (eq. 16):
//!
//! ```text
//! A = [ W^T M~ W   E ]     b = [ W_n^T v~ - n . u + beta(psi)  (normal rows)   ]
//!     [ U   -E^T   0 ]         [ W_f^T v~ - f . u              (f = +d or -d)  ]
//!                              [ 0                             (sigma rows)    ]
//! ```
//!
//! assembled **per unit mass**: `M~ = m M^-1 = diag(1, 1, m / J)`, so every row of `w` is a
//! velocity and `z` is the impulses divided by `m` (the motion does not depend on `m`).
//! `E` has a 1 in row `f`, column `sigma_k` for each friction row of contact `k`, and `U` puts
//! `mu_k` (the contact's coefficient for this step) in row `sigma_k`, column `p_n,k`. The
//! penetration recovery is `beta(psi) = max(psi / h, -sqrt(2 g |psi|))`.
//!
//! The LCP is solved by enumerating its `2^n` complementary bases (`enumerate.rs`). A
//! solution exists but need not be unique (how friction splits between two sticking contacts);
//! the post-step velocity of each is `v+ = v~ + M~ W z` (eq. 16). **Choice:** the least kinetic
//! energy `vx^2 + vy^2 + (J/m) omega^2` (maximum dissipation, the principle behind the friction
//! model); energies within `1e-12 S^2` of the least are ties, broken by the smallest `||z||_1`
//! (sums within `1e-12` of each other, relative, are ties too: a rod at rest on three tips carried
//! by the middle one or by the outer two has the same sum to round-off, and round-off must not
//! pick between them step by step), then by the lowest basis. `S` is the step's speed scale, `max(V, |v~_x|, |v~_y|, (D/2)
//! |v~_omega|)` with `V` the scene's characteristic speed and `D` the body's size. A step is
//! **ambiguous** when two solutions give velocities that differ by more than `1e-9 S` in a
//! component (`omega` times `D/2`).
//!
//! **Modes after the step.** A contact is separated when it was inactive or its normal impulse
//! per unit mass is at most `64 eps g h` (the round-off of one step's gravity impulse; docs/formulation.md, "Precision": not `eps V`); otherwise its slip is `s = d . (u - v_P)` with
//! `v_P = (vx - omega r_y, vy + omega r_x)` after the step (`r`, `d` at the step's start): sticking
//! when `|s| <= stick_speed`, else sliding in the direction of `s`.

use super::Mode;
use super::enumerate::{Lcp, MAX_ENUMERATED, enumerate};
use super::geometry::{Body, Frame, dot, wrench};
use super::load::{Law, Touching, determinate, least_norm};

/// What every step of a scene shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Model {
    /// The body.
    pub body: Body,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// `h`, s.
    pub step: f64,
    /// The scene's characteristic support speed `V`, m/s.
    pub speed: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// The body's size `D` (its largest dimension), m.
    pub size: f64,
}

impl Model {
    /// `diag(M~) = m M^-1`.
    fn weights(&self) -> [f64; 3] {
        [1.0, 1.0, self.body.mass / self.body.inertia]
    }

    /// Normal impulse per unit mass at or below which a contact counts as separated.
    pub fn impulse_floor(&self) -> f64 {
        64.0 * f64::EPSILON * self.gravity * self.step
    }

    /// `beta(psi)`: the gap closed in one step, a penetration pushed out at most at the speed of a
    /// fall through it, after the gap is shrunk toward zero by `round_off` (the round-off of the
    /// positions it comes from, docs/formulation.md "Round-off is not a gap").
    fn recovery(&self, gap: f64, round_off: f64) -> f64 {
        let gap = gap.signum() * (gap.abs() - round_off).max(0.0);
        (gap / self.step).max(-(2.0 * self.gravity * gap.abs()).sqrt())
    }

    /// The velocity before contact impulses, `v~ = v + h M^-1 w_ext` (eq. 16).
    pub fn free_velocity(&self, v: [f64; 3]) -> [f64; 3] {
        [v[0], v[1] - self.step * self.gravity, v[2]]
    }
}

/// The answer of one step.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StepResult {
    /// `v+`.
    pub velocity: [f64; 3],
    /// Each contact's normal impulse per unit mass (0 when inactive), m/s.
    pub normal: Vec<f64>,
    /// Each contact's net friction impulse along `+d` per unit mass, m/s.
    pub friction: Vec<f64>,
    /// Whether solutions with different motions existed.
    pub ambiguous: bool,
    /// Each contact the load left touching and slipping but carrying nothing, on a body of three
    /// or more contacts: it takes `mu_k` next step, as a sliding contact does
    /// (docs/formulation.md, "The load: the least norm").
    pub slipping_unloaded: Vec<bool>,
}

/// Solves one step from velocity `v` with the contacts' geometry at the step's start, the
/// supports' velocities `support_velocity` over the step and friction coefficients `mu`.
///
/// # Errors
/// No complementary basis solves the LCP, or too many contacts are active to enumerate.
pub(super) fn solve(
    model: &Model,
    q: [f64; 3],
    v: [f64; 3],
    frames: &[Frame],
    support_velocity: &[[f64; 2]],
    mu: &[f64],
) -> Result<StepResult, String> {
    let active: Vec<usize> = (0..frames.len()).filter(|&i| frames[i].active).collect();
    let k = active.len();
    let n = 4 * k;
    if n > MAX_ENUMERATED {
        return Err(format!(
            "{k} active contacts: an LCP of {n} > {MAX_ENUMERATED} rows is too large to enumerate"
        ));
    }
    let weights = model.weights();
    let v_free = model.free_velocity(v);
    let round_off = 4.0 * f64::EPSILON * (q[0].abs() + q[1].abs() + model.size);
    // Impulse columns: normal of slot s at s, +d at k + 2s, -d at k + 2s + 1.
    let mut columns = vec![[0.0; 3]; 3 * k];
    let mut offset = vec![0.0; n];
    for (slot, &i) in active.iter().enumerate() {
        let f = &frames[i];
        let u = support_velocity[i];
        columns[slot] = wrench(f.lever, f.normal);
        offset[slot] = dot3(columns[slot], v_free) - dot(f.normal, u) + model.recovery(f.gap, round_off);
        for (dir, sign) in [1.0, -1.0].into_iter().enumerate() {
            let along = [sign * f.tangent[0], sign * f.tangent[1]];
            let c = k + 2 * slot + dir;
            columns[c] = wrench(f.lever, along);
            offset[c] = dot3(columns[c], v_free) - dot(along, u);
        }
    }
    let mut matrix = vec![0.0; n * n];
    for (row, wr) in columns.iter().enumerate() {
        for (col, wc) in columns.iter().enumerate() {
            matrix[row * n + col] = (0..3).map(|c| wr[c] * weights[c] * wc[c]).sum();
        }
    }
    for (slot, &i) in active.iter().enumerate() {
        let sigma = 3 * k + slot;
        for dir in 0..2 {
            let f = k + 2 * slot + dir;
            matrix[f * n + sigma] = 1.0; // E
            matrix[sigma * n + f] = -1.0; // -E^T
        }
        matrix[sigma * n + slot] = mu[i]; // U
    }
    let solutions = enumerate(&Lcp { size: n, matrix, offset });

    let velocity_of = |z: &[f64]| {
        let mut v_plus = v_free;
        for (column, &zc) in columns.iter().zip(z) {
            for c in 0..3 {
                v_plus[c] += weights[c] * column[c] * zc;
            }
        }
        v_plus
    };
    let energy = |w: [f64; 3]| w[0] * w[0] + w[1] * w[1] + w[2] * w[2] / weights[2];
    let reach = model.size / 2.0;
    let speed_scale = model.speed.max(v_free[0].abs()).max(v_free[1].abs()).max(reach * v_free[2].abs());
    let velocities: Vec<[f64; 3]> = solutions.iter().map(|s| velocity_of(&s.z)).collect();
    let energies: Vec<f64> = velocities.iter().map(|&w| energy(w)).collect();
    let Some(least) = energies.iter().copied().min_by(f64::total_cmp) else {
        return Err(format!("no complementary basis solves the {n}x{n} LCP"));
    };
    let tie = 1e-12 * speed_scale * speed_scale;
    let l1 = |z: &[f64]| z.iter().sum::<f64>();
    // Solutions come in increasing basis order, so the first of equal ||z||_1 has the lowest basis.
    let mut chosen: Option<usize> = None;
    for (s, solution) in solutions.iter().enumerate() {
        if energies[s] <= least + tie
            && chosen.is_none_or(|c| l1(&solution.z) < l1(&solutions[c].z) * (1.0 - 1e-12))
        {
            chosen = Some(s);
        }
    }
    let Some(chosen) = chosen else {
        return Err(format!("no solution of the {n}x{n} LCP has a finite energy"));
    };
    let v_plus = velocities[chosen];
    let differs = |w: [f64; 3]| {
        (w[0] - v_plus[0]).abs() > 1e-9 * speed_scale
            || (w[1] - v_plus[1]).abs() > 1e-9 * speed_scale
            || reach * (w[2] - v_plus[2]).abs() > 1e-9 * speed_scale
    };
    let ambiguous = velocities.iter().any(|&w| differs(w));

    let z = &solutions[chosen].z;
    let mut normal = vec![0.0; frames.len()];
    let mut friction = vec![0.0; frames.len()];
    for (slot, &i) in active.iter().enumerate() {
        normal[i] = z[slot];
        friction[i] = z[k + 2 * slot] - z[k + 2 * slot + 1];
    }
    let load = Load { model, frames, support_velocity, mu, columns: &columns, tolerance: 1e-9 * speed_scale };
    let slipping_unloaded = load.least_norm(&active, z, v_plus, round_off, &mut normal, &mut friction)?;
    Ok(StepResult { velocity: v_plus, normal, friction, ambiguous, slipping_unloaded })
}

/// What the load's rule reads of a step (docs/formulation.md, "The load: the least norm").
struct Load<'a> {
    model: &'a Model,
    frames: &'a [Frame],
    support_velocity: &'a [[f64; 2]],
    mu: &'a [f64],
    /// The impulse columns: normal of slot `s` at `s`, `+d` at `k + 2 s`, `-d` at `k + 2 s + 1`.
    columns: &'a [[f64; 3]],
    /// The velocity tolerance, `1e-9 S`.
    tolerance: f64,
}

impl Load<'_> {
    /// The load, where the contacts leave it open: the least 2-norm with the motion `v_plus` of the
    /// answer `z` over the `active` contacts (`load.rs`), in place of `normal` and `friction`. A
    /// contact touches when it carries load or its normal velocity is within the tolerance of
    /// zero, and sticks when its slip is within it too. Returns, for three or more contacts, each
    /// contact left touching and slipping (beyond the stick speed) with no load.
    fn least_norm(
        &self,
        active: &[usize],
        z: &[f64],
        v_plus: [f64; 3],
        round_off: f64,
        normal: &mut [f64],
        friction: &mut [f64],
    ) -> Result<Vec<bool>, String> {
        let (model, frames, support_velocity, mu, columns) =
            (self.model, self.frames, self.support_velocity, self.mu, self.columns);
        let k = active.len();
        let tolerance = self.tolerance;
        // The load, where the contacts leave it open: the least 2-norm with this motion
        // (docs/formulation.md, "The load: the least norm"; `load.rs`). A contact touches when it
        // carries load or its normal velocity is within the velocity tolerance of zero, and sticks
        // when its slip is within it too.
        let mut touching: Vec<(usize, Touching)> = Vec::new();
        let mut slipping = vec![false; frames.len()];
        for (slot, &i) in active.iter().enumerate() {
            let f = &frames[i];
            let normal_velocity = dot3(columns[slot], v_plus) - dot(f.normal, support_velocity[i])
                + model.recovery(f.gap, round_off);
            if z[slot] <= model.impulse_floor() && normal_velocity > tolerance {
                continue;
            }
            let slip = dot(f.tangent, support_velocity[i]) - dot3(columns[k + 2 * slot], v_plus);
            slipping[i] = frames.len() >= 3 && slip.abs() > model.stick_speed;
            let law = if slip.abs() <= tolerance {
                Law::Sticking { mu: mu[i] }
            } else {
                Law::Sliding { f: slip.signum() * mu[i] }
            };
            touching.push((
                i,
                Touching { normal: columns[slot].to_vec(), tangent: columns[k + 2 * slot].to_vec(), law },
            ));
        }
        let unknowns: usize =
            touching.iter().map(|(_, t)| if matches!(t.law, Law::Sticking { .. }) { 2 } else { 1 }).sum();
        if unknowns > 3 || (touching.len() >= 3 && unknowns == 3) {
            let mut r = [0.0; 3];
            for (i, t) in &touching {
                for c in 0..3 {
                    r[c] += t.normal[c] * normal[*i] + t.tangent[c] * friction[*i];
                }
            }
            let scale = z.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            let contacts: Vec<Touching> = touching.iter().map(|(_, t)| t.clone()).collect();
            match least_norm(&contacts, &r, scale) {
                Some(load) => {
                    for ((i, _), x) in touching.iter().zip(load) {
                        (normal[*i], friction[*i]) = (x[0], x[1]);
                    }
                }
                None if determinate(&contacts) => {}
                None => return Err(format!("no load within the contacts' laws gives the motion {v_plus:?}")),
            }
        }
        let floor = model.impulse_floor();
        Ok(slipping.iter().zip(normal.iter()).map(|(&slips, &n)| slips && n <= floor).collect())
    }
}

/// `a . b` in three dimensions.
fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The mode of a touching contact with slip `s = d . (u - v_P)`.
fn slip_mode(slip: f64, stick_speed: f64) -> Mode {
    if slip.abs() <= stick_speed {
        Mode::Sticking
    } else if slip > 0.0 {
        Mode::SlidingPositive
    } else {
        Mode::SlidingNegative
    }
}

/// Each contact's mode after a step: `frames` and `support_velocity` are the step's (at its
/// start, over it), `result` its answer.
pub(super) fn modes_after(
    model: &Model,
    frames: &[Frame],
    support_velocity: &[[f64; 2]],
    result: &StepResult,
) -> Vec<Mode> {
    let floor = model.impulse_floor();
    let v = result.velocity;
    frames
        .iter()
        .zip(support_velocity)
        .zip(&result.normal)
        .map(|((f, &u), &normal)| {
            if !f.active || normal <= floor {
                return Mode::Separated;
            }
            let point = [v[0] - v[2] * f.lever[1], v[1] + v[2] * f.lever[0]];
            slip_mode(dot(f.tangent, [u[0] - point[0], u[1] - point[1]]), model.stick_speed)
        })
        .collect()
}

/// The modes before the first step: a contact active and touching
/// (`psi <= 64 eps (D + |y|)`, `y` the centre of mass's height) takes its mode from the slip
/// `d . (u - v_P)` of the support's initial velocity against the body's start velocity `v` at the
/// contact point (at rest in every scene but painleve); any other is separated.
pub(super) fn initial_modes(
    model: &Model,
    q: [f64; 3],
    v: [f64; 3],
    frames: &[Frame],
    support_velocity: &[[f64; 2]],
) -> Vec<Mode> {
    let touching = 64.0 * f64::EPSILON * (model.size + q[1].abs());
    frames
        .iter()
        .zip(support_velocity)
        .map(|(f, &u)| {
            if f.active && f.gap <= touching {
                let point = [v[0] - v[2] * f.lever[1], v[1] + v[2] * f.lever[0]];
                slip_mode(dot(f.tangent, [u[0] - point[0], u[1] - point[1]]), model.stick_speed)
            } else {
                Mode::Separated
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::super::geometry::{Support, frame};
    use super::*;

    /// A level rod of 1 m, 0.2 kg, resting on tips at `xs`.
    fn rod_on(xs: &[f64]) -> (Model, [f64; 3], Vec<Frame>) {
        let body = Body { half_width: 0.5, half_height: 0.0025, mass: 0.2, inertia: 0.2 / 12.0 };
        let model = Model { body, gravity: 9.81, step: 1e-3, speed: 0.0, stick_speed: 1e-5, size: 1.0 };
        let q = [0.0, 0.0025, 0.0];
        let frames = xs.iter().map(|&x| frame(&body, q, &Support::Point { tip: [x, 0.0] })).collect();
        (model, q, frames)
    }

    #[test]
    fn three_supports_carry_a_rod_with_a_unique_motion() {
        // Three tips: the normal impulses are statically indeterminate, the motion (rest) is not.
        let (model, q, frames) = rod_on(&[-0.4, 0.1, 0.3]);
        let u = vec![[0.0; 2]; 3];
        let started = std::time::Instant::now();
        let result = solve(&model, q, [0.0; 3], &frames, &u, &[0.6; 3]).unwrap();
        eprintln!("three contacts: one 12x12 step by enumeration in {:?}", started.elapsed());
        assert!(result.velocity.iter().all(|x| x.abs() < 1e-15), "{result:?}");
        assert!(!result.ambiguous);
        let gh = model.gravity * model.step;
        let total: f64 = result.normal.iter().sum();
        let torque: f64 = result.normal.iter().zip([-0.4, 0.1, 0.3]).map(|(n, x)| n * x).sum();
        assert!((total - gh).abs() < 1e-14 && torque.abs() < 1e-14, "{result:?}");
        // The load of least norm: affine in the tips' positions, `N_i = a + b x_i`; with the
        // tips' positions summing to 0 under the centre of mass, `b = 0`: a third each, all sticking.
        for n in &result.normal {
            assert!((n - gh / 3.0).abs() < 1e-15, "{result:?}");
        }
        let modes = modes_after(&model, &frames, &u, &result);
        assert_eq!(modes, vec![Mode::Sticking; 3]);
    }

    #[test]
    fn a_finger_sliding_under_a_rod_on_three_supports_drags_it_at_most_by_kinetic_friction() {
        let (model, q, frames) = rod_on(&[-0.4, 0.1, 0.3]);
        let u = vec![[0.1, 0.0], [0.0; 2], [0.0; 2]];
        let result = solve(&model, q, [0.0; 3], &frames, &u, &[0.4, 0.6, 0.6]).unwrap();
        let modes = modes_after(&model, &frames, &u, &result);
        // The moving finger slides with friction at the cone's edge; the rod stays put (one of the
        // still tips may be unloaded, as above).
        assert_eq!(modes[0], Mode::SlidingPositive);
        assert!(modes[1..].iter().all(|&m| m == Mode::Sticking || m == Mode::Separated), "{modes:?}");
        assert!(!result.ambiguous);
        assert!((result.friction[0] - 0.4 * result.normal[0]).abs() < 1e-15, "{result:?}");
        assert!(result.velocity.iter().all(|x| x.abs() < 1e-15), "{result:?}");
    }

    #[test]
    fn too_many_active_contacts_are_refused() {
        let (model, q, frames) = rod_on(&[-0.4, -0.2, 0.0, 0.2, 0.4]);
        let err = solve(&model, q, [0.0; 3], &frames, &[[0.0; 2]; 5], &[0.6; 5]).unwrap_err();
        assert!(err.contains("5 active contacts"), "{err}");
    }

    #[test]
    fn a_penetration_is_pushed_out_at_most_at_the_speed_of_a_fall_through_it() {
        let (model, _, _) = rod_on(&[]);
        assert!((model.recovery(1e-4, 0.0) - 0.1).abs() < 1e-15);
        let depth: f64 = 1e-4;
        assert!((model.recovery(-depth, 0.0) + (2.0 * 9.81 * depth).sqrt()).abs() < 1e-15);
        assert!((model.recovery(-1e-9, 0.0) + 1e-6).abs() < 1e-18);
        assert!(model.recovery(1e-15, 4e-15).abs() < f64::MIN_POSITIVE);
        assert!((model.recovery(5e-15, 4e-15) - 1e-15 / model.step).abs() < 1e-20);
    }
}
