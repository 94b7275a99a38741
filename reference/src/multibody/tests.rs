//! The multibody reference's checks: its solver against textbook LCPs and against the
//! exhaustive enumerator (`crate::enumerate`) on random small multibody steps, the
//! indeterminate interface, and the analytic laws of docs/scenes.md ("block-on-block",
//! "tablecloth", "stack") on its own runs. The measured figures are printed
//! (`-- --nocapture`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::geometry::{Body, Lower, Pair, Shape, Table, dot};
use super::lcp::{LemkeFailure, lemke, solve_basis, verify};
use super::step::{Starts, StepLcp, assemble, solve};
use super::system::{State, System};
use super::*;
use crate::Sample;
use crate::enumerate::{Lcp, enumerate, is_lcp_solution};

const G: f64 = 9.81;

/// A small deterministic generator (xorshift64*), uniform in `[lo, hi)`.
struct Random(u64);

impl Random {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        lo + (hi - lo) * (x as f64 / (1_u64 << 53) as f64)
    }
}

/// A box's `(a, b)`.
fn half_extents(body: &Body) -> [f64; 2] {
    let Shape::Box { half_width, half_height } = body.shape else { panic!("not a box: {body:?}") };
    [half_width, half_height]
}

fn run_spec(spec: Spec) -> Run {
    run(&spec, Sample::None).unwrap()
}

// ---------------------------------------------------------------------------------------------
// The solver.

#[test]
fn lemke_solves_textbook_lcps() {
    // A cyclic P-matrix (each row 1 on the diagonal, 2 on the next): the unique solution
    // z = (1/3, 1/3, 1/3), w = 0.
    let a = [1.0, 2.0, 0.0, 0.0, 1.0, 2.0, 2.0, 0.0, 1.0];
    let b = [-1.0, -1.0, -1.0];
    let (z, basis) = lemke(&a, &b, &[1.0; 3], 100).unwrap();
    assert!(verify(&a, &b, &z) && basis == vec![true; 3], "{z:?}");
    assert!(z.iter().all(|x| (x - 1.0 / 3.0).abs() < 1e-15), "{z:?}");
    // A symmetric positive definite matrix: z = (4/3, 7/3).
    let (a, b) = ([2.0, 1.0, 1.0, 2.0], [-5.0, -6.0]);
    let (z, _) = lemke(&a, &b, &[1.0; 2], 100).unwrap();
    assert!((z[0] - 4.0 / 3.0).abs() < 1e-14 && (z[1] - 7.0 / 3.0).abs() < 1e-14, "{z:?}");
    // b >= 0: z = 0 without a pivot.
    assert_eq!(lemke(&a, &[1.0, 0.0], &[1.0; 2], 0).unwrap().0, vec![0.0, 0.0]);
    // Degenerate: A = [[1, 1], [1, 1]], b = (-1, -1): the solutions are z1 + z2 = 1; any answer
    // must verify.
    let (a, b) = ([1.0; 4], [-1.0, -1.0]);
    let (z, _) = lemke(&a, &b, &[1.0; 2], 100).unwrap();
    assert!(verify(&a, &b, &z) && (z[0] + z[1] - 1.0).abs() < 1e-15, "{z:?}");
    // Infeasible with a copositive-plus (skew) matrix: w1 = -z2 - 1 < 0 always, so the method
    // must end on a ray (for a copositive-plus matrix Lemke's method ends on a ray only when
    // the LCP has no solution: Cottle, Pang & Stone, section 4.4).
    let (a, b) = ([0.0, -1.0, 1.0, 0.0], [-1.0, -1.0]);
    assert_eq!(lemke(&a, &b, &[1.0; 2], 100), Err(LemkeFailure::Ray));
    // An upper-triangular P-matrix (1 on the diagonal, 2 above, as in Murty's examples of long
    // pivot paths), n = 8, b = -1: the unique
    // solution is found by the enumeration too.
    let n = 8;
    let a: Vec<f64> = (0..n * n)
        .map(|e| match (e / n, e % n) {
            (i, j) if i == j => 1.0,
            (i, j) if j > i => 2.0,
            _ => 0.0,
        })
        .collect();
    let b = vec![-1.0; n];
    let (z, _) = lemke(&a, &b, &vec![1.0; n], 10_000).unwrap();
    let all = enumerate(&Lcp { size: n, matrix: a.clone(), offset: b.clone() });
    assert_eq!(all.len(), 1);
    assert!(verify(&a, &b, &z) && z.iter().zip(&all[0].z).all(|(x, y)| (x - y).abs() < 1e-14), "{z:?}");
}

#[test]
fn lemke_agrees_with_enumeration_on_random_p_matrix_lcps() {
    // A = B B^T + I/2 is positive definite (a P-matrix): exactly one solution, which Lemke's
    // method must reach.
    let mut rng = Random(0x9e37_79b9_7f4a_7c15);
    for n in [3, 6, 10, 12] {
        for _ in 0..20 {
            let m: Vec<f64> = (0..n * n).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let mut a = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    a[i * n + j] = (0..n).map(|k| m[i * n + k] * m[j * n + k]).sum::<f64>();
                }
                a[i * n + i] += 0.5;
            }
            let b: Vec<f64> = (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let (z, _) = lemke(&a, &b, &vec![1.0; n], 100 * n).unwrap();
            let all = enumerate(&Lcp { size: n, matrix: a.clone(), offset: b.clone() });
            assert_eq!(all.len(), 1, "a P-matrix LCP with {} solutions", all.len());
            let err = z.iter().zip(&all[0].z).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            assert!(verify(&a, &b, &z) && err < 1e-12, "n = {n}: |z - z_enum| = {err:e}");
        }
    }
}

/// A system, its state `(q, v)` and each candidate's `mu` for one step.
type RandomStep = (System, Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<f64>);

/// A random two-box step: a box (body 1) on a box (body 0) on the floor, tilted, moving and
/// penetrating a little, pulled; `k` (2..=4) active contacts: 16 rows at most.
fn random_step(rng: &mut Random) -> RandomStep {
    let (w0, h0, w1, h1) =
        (rng.uniform(0.2, 0.5), rng.uniform(0.05, 0.2), rng.uniform(0.05, 0.2), rng.uniform(0.05, 0.3));
    let system = System {
        bodies: vec![Body::block(w0, h0, rng.uniform(0.5, 3.0)), Body::block(w1, h1, rng.uniform(0.2, 2.0))],
        table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
        pairs: vec![
            Pair { upper: 0, lower: Lower::Table, mu_static: 0.3, mu_kinetic: 0.3 },
            Pair { upper: 1, lower: Lower::Body(0), mu_static: 0.6, mu_kinetic: 0.4 },
        ],
        forces: vec![[rng.uniform(-40.0, 40.0), 0.0], [rng.uniform(-5.0, 5.0), 0.0]],
        gravity: G,
        step: 1e-3,
        stick_speed: 1e-5,
        margin: 1e-3,
    };
    let tilt0 = rng.uniform(-0.01, 0.01);
    let tilt1 = rng.uniform(-0.03, 0.03);
    let x1 = rng.uniform(-(w0 - w1) / 2.0, (w0 - w1) / 2.0);
    let q = vec![
        [0.0, h0 / 2.0 + rng.uniform(-1e-4, 1e-4) + (w0 / 2.0) * tilt0.abs(), tilt0],
        [
            x1,
            h0 + h1 / 2.0 + rng.uniform(-1e-4, 1e-4) + (w1 / 2.0) * (tilt1 - tilt0).abs() + x1 * tilt0,
            tilt1,
        ],
    ];
    let mut speed = || rng.uniform(-0.2, 0.2);
    let v = vec![[speed(), speed() * 0.1, speed()], [speed(), speed() * 0.1, speed()]];
    let mu: Vec<f64> = (0..6)
        .map(|i| {
            if i < 2 {
                0.3
            } else if rng.uniform(0.0, 1.0) < 0.5 {
                0.6
            } else {
                0.4
            }
        })
        .collect();
    (system, q, v, mu)
}

/// The least-kinetic-energy motion among the enumerated solutions of `lcp`, ties by the smallest
/// `||z||_1` (the single-body reference's rule, `reference/src/step.rs`).
fn enumerated_choice(system: &System, lcp: &StepLcp) -> Option<(Vec<f64>, bool)> {
    let n = lcp.offset.len();
    let solutions = enumerate(&Lcp { size: n, matrix: lcp.matrix.clone(), offset: lcp.offset.clone() });
    let energy = |v: &[f64]| (0..v.len()).map(|c| v[c] * v[c] / lcp.weights[c]).sum::<f64>();
    let velocities: Vec<Vec<f64>> = solutions.iter().map(|s| lcp.velocity(&s.z)).collect();
    let least = velocities.iter().map(|v| energy(v)).min_by(f64::total_cmp)?;
    let scale = lcp.free.iter().fold(0.0_f64, |m, x| m.max(x.abs())).max(1e-3);
    let mass_sum: f64 = system.bodies.iter().map(|b| b.mass / system.reference_mass()).sum();
    let chosen = velocities.iter().find(|v| energy(v) <= least + 1e-12 * scale * scale * mass_sum)?.clone();
    let ambiguous =
        velocities.iter().any(|v| v.iter().zip(&chosen).any(|(a, b)| (a - b).abs() > 1e-9 * scale));
    Some((chosen, ambiguous))
}

#[test]
fn the_solver_agrees_with_enumeration_on_random_two_box_steps() {
    let mut rng = Random(0x2545_f491_4f6c_dd1d);
    let (mut cases, mut ambiguous, mut by_size) = (0, 0, [0_usize; 5]);
    let mut worst: f64 = 0.0;
    while cases < 60 {
        let (system, q, v, mu) = random_step(&mut rng);
        let frames = system.frames(&q, &v);
        let lcp = assemble(&system, &q, &v, &frames, &mu);
        let k = lcp.active.len();
        if k < 2 {
            continue;
        }
        cases += 1;
        by_size[k] += 1;
        let Some((expected, enumerated_ambiguous)) = enumerated_choice(&system, &lcp) else {
            panic!("the enumeration found no solution of a {}-row step", 4 * k);
        };
        let result = solve(&system, &lcp, &vec![0; frames.len()], frames.len(), Starts::ALL).unwrap();
        let got: Vec<f64> = result.velocity.iter().flatten().copied().collect();
        let scale = lcp.free.iter().fold(0.0_f64, |m, x| m.max(x.abs())).max(1e-3);
        let err = got.iter().zip(&expected).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
        worst = worst.max(err);
        ambiguous += usize::from(enumerated_ambiguous);
        assert!(err < 1e-9, "case {cases} ({k} contacts): v+ {got:?}, the enumeration's {expected:?}");
        assert!(result.normal.iter().chain(&result.friction).all(|x| x.is_finite()));
        assert!(result.normal.iter().all(|&x| x >= 0.0));
    }
    eprintln!(
        "random two-box steps: {cases} ({:?} with 2/3/4 contacts), {ambiguous} ambiguous by enumeration, worst |v - v_enum| / S = {worst:e}",
        &by_size[2..]
    );
}

#[test]
fn every_answer_of_the_solver_passes_the_enumerators_acceptance_check() {
    let mut rng = Random(0xdead_beef_cafe_f00d);
    let (mut checked, mut rays) = (0, 0);
    while checked < 40 {
        let (system, q, v, mu) = random_step(&mut rng);
        let frames = system.frames(&q, &v);
        let lcp = assemble(&system, &q, &v, &frames, &mu);
        let n = lcp.offset.len();
        if n == 0 {
            continue;
        }
        let Ok((z, basis)) = lemke(&lcp.matrix, &lcp.offset, &vec![1.0; n], 50 * (n + 1)) else {
            rays += 1;
            continue;
        };
        checked += 1;
        let m: Vec<Vec<f64>> = (0..n).map(|i| lcp.matrix[i * n..(i + 1) * n].to_vec()).collect();
        assert!(verify(&lcp.matrix, &lcp.offset, &z));
        assert!(is_lcp_solution(&m, &lcp.offset, &z, 1e-9), "{z:?}");
        // The basis Lemke's method ended on solves to the same z.
        let again = solve_basis(&lcp.matrix, &lcp.offset, &basis).unwrap();
        assert!(again.iter().zip(&z).all(|(a, b)| (a.max(0.0) - b).abs() < 1e-12), "{again:?} {z:?}");
    }
    eprintln!(
        "Lemke's method on random two-box steps: {checked} answers verified, {rays} rays (the step then opens the cone rows)"
    );
    assert!(rays <= checked / 4, "{rays} rays in {} steps", checked + rays);
}

#[test]
fn an_indeterminate_interface_moves_the_same_from_every_start() {
    // The default top block on the bottom one pulled so that they ride together: the top block's
    // two corners stick, their split of the load is statically indeterminate.
    let p = BlockOnBlock { force: 15.0, ..BlockOnBlock::default() };
    let system = p.system();
    let mut state = State::at_rest(&system, p.start());
    for _ in 0..3 {
        state.advance(&system, Starts::ALL).unwrap();
    }
    let frames = system.frames(&state.q, &state.v);
    let mu: Vec<f64> = frames.iter().map(|f| system.pairs[f.pair].mu_static).collect();
    let lcp = assemble(&system, &state.q, &state.v, &frames, &mu);
    let reference = solve(&system, &lcp, &state.patterns, frames.len(), Starts::ALL).unwrap();
    let top: Vec<usize> = (0..frames.len()).filter(|&i| frames[i].pair == 1 && frames[i].active).collect();
    assert_eq!(top.len(), 2, "the top block's two corners");
    // Every start: Lemke's method alone, and each of the 8 x 8 warm patterns of the top block's
    // corners (the floor's as in the reference answer) alone.
    let mut answers = vec![
        solve(
            &system,
            &lcp,
            &state.patterns,
            frames.len(),
            Starts { warm: false, lemke: true, descend: false },
        )
        .unwrap(),
    ];
    let patterns = [0, 2 | 8, 4 | 8, 1, 1 | 2, 1 | 4, 1 | 2 | 8, 1 | 4 | 8];
    for &a in &patterns {
        for &b in &patterns {
            let mut previous = reference.patterns.clone();
            previous[top[0]] = a;
            previous[top[1]] = b;
            if let Ok(r) = solve(
                &system,
                &lcp,
                &previous,
                frames.len(),
                Starts { warm: true, lemke: false, descend: false },
            ) {
                answers.push(r);
            }
        }
    }
    let splits: Vec<(f64, f64)> = answers.iter().map(|r| (r.normal[top[0]], r.friction[top[0]])).collect();
    let distinct = splits
        .iter()
        .filter(|s| (s.0 - splits[0].0).abs() > 1e-9 || (s.1 - splits[0].1).abs() > 1e-9)
        .count();
    eprintln!(
        "indeterminate interface: {} verified starts, {} with another split than the first",
        answers.len(),
        distinct
    );
    // Every start reaches a vertex of its own, and the load's rule (docs/formulation.md, "The
    // load: the least norm") takes the one split of least norm from each: the same.
    assert!(answers.len() >= 3 && distinct == 0, "{splits:?}");
    let total = |r: &step::StepResult| {
        top.iter().map(|&i| (r.normal[i], r.friction[i])).fold((0.0, 0.0), |s, x| (s.0 + x.0, s.1 + x.1))
    };
    for r in &answers {
        for (a, b) in r.velocity.iter().flatten().zip(reference.velocity.iter().flatten()) {
            assert!((a - b).abs() < 1e-12, "{:?} vs {:?}", r.velocity, reference.velocity);
        }
        let (t, t0) = (total(r), total(&reference));
        assert!(
            (t.0 - t0.0).abs() < 1e-12 && (t.1 - t0.1).abs() < 1e-12,
            "summed interface impulse {t:?} vs {t0:?}"
        );
        assert!(!r.ambiguous);
    }
}

// ---------------------------------------------------------------------------------------------
// block-on-block.

#[test]
fn block_on_block_follows_its_laws() {
    let p = BlockOnBlock::default();
    let (m, big_m) = (p.top_mass, p.bottom_mass);
    let held = p.mu_floor * (big_m + m) * G;
    let slides = (p.mu_static + p.mu_floor) * (big_m + m) * G;
    let tol = 1e-9;
    let mut worst: f64 = 0.0;
    for (force, expected) in [
        (0.5 * held, Outcome::Held),
        (0.98 * held, Outcome::Held),
        (1.02 * held, Outcome::Rode),
        (0.5 * (held + slides), Outcome::Rode),
        (0.98 * slides, Outcome::Rode),
        (1.02 * slides, Outcome::Slid),
        (1.5 * slides, Outcome::Slid),
        (3.0 * slides, Outcome::Slid),
    ] {
        let r = run_spec(Spec::BlockOnBlock(BlockOnBlock { force, ..p }));
        let (lower, upper) = (r.lower_acceleration.unwrap(), r.upper_acceleration.unwrap());
        let (expected_lower, expected_upper) = match expected {
            Outcome::Held => (0.0, 0.0),
            Outcome::Rode => {
                let a = force / (big_m + m) - p.mu_floor * G;
                (a, a)
            }
            _ => ((force - p.mu_kinetic * m * G - p.mu_floor * (big_m + m) * G) / big_m, p.mu_kinetic * G),
        };
        let err = (lower - expected_lower).abs().max((upper - expected_upper).abs());
        worst = worst.max(err);
        eprintln!(
            "block-on-block F = {force:7.3} N: {:?}, a_bottom {lower:.12} (law {expected_lower:.12}), a_top {upper:.12} (law {expected_upper:.12}), {} ambiguous",
            r.outcome, r.ambiguous_steps
        );
        assert_eq!(r.outcome, expected, "F = {force}");
        assert!(err < tol, "F = {force}: accelerations off the law by {err:e}");
        // Held or riding to the end: the summed force of the bottom block on the top one (the
        // model decides the sum, not the corners' shares) is m a along x and m g up; the
        // floor's on the pair (M + m) a - F along x and (M + m) g up.
        if expected != Outcome::Slid {
            let [top, floor] = [r.interface_forces[1], r.interface_forces[0]];
            let floor_x = (big_m + m) * expected_upper - force;
            assert!((top[0] - m * expected_upper).abs() < 1e-9 && (top[1] - m * G).abs() < 1e-9, "{top:?}");
            assert!(
                (floor[0] - floor_x).abs() < 1e-9 && (floor[1] - (big_m + m) * G).abs() < 1e-9,
                "{floor:?}"
            );
        }
        if expected == Outcome::Held {
            assert!(r.max_speed < 1e-12, "held, yet moved at {:e} m/s", r.max_speed);
        }
    }
    eprintln!("block-on-block: worst acceleration error {worst:e} m/s^2 (tolerance {tol:e})");
}

#[test]
fn a_tall_top_block_tips_above_g_w_over_h() {
    // w / h = 1/4 < mu_s: tipping comes first, at a = g w / h.
    let p = BlockOnBlock { top_width: 0.05, top_height: 0.2, max_time: 1.0, ..BlockOnBlock::default() };
    let total = p.top_mass + p.bottom_mass;
    let tips = total * (G * p.top_width / p.top_height + p.mu_floor * G);
    assert!(p.top_width / p.top_height < p.mu_static);
    for (factor, expected) in
        [(0.9, Outcome::Rode), (0.97, Outcome::Rode), (1.03, Outcome::Tipped), (1.2, Outcome::Tipped)]
    {
        let force = factor * tips;
        let r = run_spec(Spec::BlockOnBlock(BlockOnBlock { force, ..p }));
        eprintln!(
            "tall top block F = {force:.3} N ({factor} of the tipping force): {:?} at t = {:.3} s",
            r.outcome, r.end_time
        );
        assert_eq!(r.outcome, expected, "F = {force}");
        if expected == Outcome::Rode {
            let a = force / total - p.mu_floor * G;
            assert!((r.upper_acceleration.unwrap() - a).abs() < 1e-9, "{r:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// tablecloth.

#[test]
fn tablecloth_follows_its_laws() {
    let p = Tablecloth::default();
    let (m, mb) = (p.block_mass, p.board_mass);
    let held = p.mu_floor * (m + mb) * G;
    let rides = (p.mu_static + p.mu_floor) * (m + mb) * G;
    let tol = 1e-9;
    let mut worst: f64 = 0.0;
    for (force, expected) in [
        (0.5 * held, Outcome::Held),
        (0.98 * held, Outcome::Held),
        (1.02 * held, Outcome::Rode),
        (0.98 * rides, Outcome::Rode),
    ] {
        let r = run_spec(Spec::Tablecloth(Tablecloth { force, max_time: 0.3, ..p }));
        let a = if expected == Outcome::Held { 0.0 } else { force / (m + mb) - p.mu_floor * G };
        let (lower, upper) = (r.lower_acceleration.unwrap(), r.upper_acceleration.unwrap());
        eprintln!(
            "tablecloth F = {force:.3} N: {:?}, a_board {lower:.12}, a_block {upper:.12} (law {a:.12})",
            r.outcome
        );
        assert_eq!(r.outcome, expected, "F = {force}");
        worst = worst.max((lower - a).abs()).max((upper - a).abs());
        assert!((lower - a).abs() < tol && (upper - a).abs() < tol, "{r:?}");
    }
    let mut previous = f64::INFINITY;
    for factor in [1.03, 1.5, 3.0, 6.0, 12.0] {
        let force = factor * rides;
        let r = run_spec(Spec::Tablecloth(Tablecloth { force, ..p }));
        let a_board = (force - p.mu_kinetic * m * G - p.mu_floor * (m + mb) * G) / mb;
        let a_block = p.mu_kinetic * G;
        let (lower, upper) = (r.lower_acceleration.unwrap(), r.upper_acceleration.unwrap());
        let d = r.block_displacement.unwrap();
        // The block leaves the board after a relative travel between `offset` (its rear corner
        // reaches the trailing edge) and `offset + w` (its front corner does), accelerating at
        // mu_k g until then (time `t = sqrt(2 s / a_rel)`, speed `v = mu_k g t`); it then drops
        // the board's thickness `t_b` (at most `sqrt(2 t_b / g)` in the air) and slides to rest
        // at mu_floor g, having lost at most `mu_floor sqrt(2 g t_b)` of speed in the landing.
        let travel = |s: f64| {
            let t = (2.0 * s / (a_board - a_block)).sqrt();
            (0.5 * a_block * t * t, a_block * t)
        };
        let stop = |v: f64| v * v / (2.0 * p.mu_floor * G);
        let (x_low, v_low) = travel(p.offset);
        let low = x_low + stop((v_low - p.mu_floor * (2.0 * G * p.board_thickness).sqrt()).max(0.0));
        let (x_high, v_high) = travel(p.offset + p.block_width);
        let high = x_high + v_high * (2.0 * p.board_thickness / G).sqrt() + stop(v_high);
        eprintln!(
            "tablecloth F = {force:.3} N: {:?} at {:.3} s, a_board {lower:.9} (law {a_board:.9}), a_block {upper:.9} (law {a_block:.9}), displacement {d:.6} m in [{low:.6}, {high:.6}]",
            r.outcome, r.end_time
        );
        assert_eq!(r.outcome, Outcome::Stayed, "F = {force}");
        worst = worst.max((lower - a_board).abs() / a_board).max((upper - a_block).abs());
        assert!((lower - a_board).abs() < tol * a_board && (upper - a_block).abs() < tol, "{r:?}");
        assert!(low <= d && d <= high, "displacement {d} outside [{low}, {high}]");
        assert!(d < previous, "pulling harder moved the block more: {d} after {previous}");
        previous = d;
    }
    eprintln!(
        "tablecloth: worst acceleration error {worst:e} (m/s^2, the board's above the threshold relative)"
    );
}

// ---------------------------------------------------------------------------------------------
// stack.

#[test]
fn the_stack_holds_below_the_harmonic_overhangs_and_falls_above() {
    for blocks in [2, 3] {
        for (overhang, expected) in
            [(0.9, Outcome::Held), (0.98, Outcome::Held), (1.02, Outcome::Fell), (1.1, Outcome::Fell)]
        {
            let r = run_spec(Spec::Stack(Stack { blocks, overhang, max_time: 1.0, ..Stack::default() }));
            eprintln!(
                "stack of {blocks} at overhang {overhang}: {:?} at {:.3} s, max speed {:e} m/s, {} rows, {:.1} us/step",
                r.outcome,
                r.end_time,
                r.max_speed,
                r.max_rows,
                r.seconds_per_step * 1e6
            );
            assert_eq!(r.outcome, expected, "{blocks} blocks at {overhang}");
            if expected == Outcome::Held {
                assert!(r.max_speed < 1e-12, "held, yet moved at {:e} m/s", r.max_speed);
            }
        }
    }
}

#[test]
fn a_held_stack_of_three_does_not_creep_in_ten_seconds() {
    let p = Stack::default();
    assert_eq!((p.blocks, p.overhang, p.max_time, p.step), (3, 0.98, 10.0, 1e-3));
    let start = p.start();
    let r = run_spec(Spec::Stack(p));
    let drift =
        r.q.iter()
            .zip(&start)
            .flat_map(|(q, s)| (0..3).map(move |c| (q[c] - s[c]).abs()))
            .fold(0.0, f64::max);
    eprintln!(
        "stack of 3 at 0.98 over 10 s: {:?}, max speed {:e} m/s, largest drift {drift:e}, interface forces {:?} N, {} rows, {:.1} us/step",
        r.outcome,
        r.max_speed,
        r.interface_forces,
        r.max_rows,
        r.seconds_per_step * 1e6
    );
    assert_eq!(r.outcome, Outcome::Held);
    assert_eq!(r.steps, 10_000);
    assert!(r.max_speed < 1e-12, "creep: {:e} m/s", r.max_speed);
    assert!(drift < 1e-12, "drift {drift:e}");
    // The table carries the whole stack; each interface the blocks above it (the sums the
    // model decides).
    for (pair, f) in r.interface_forces.iter().enumerate() {
        let carried = (p.blocks - pair) as f64 * p.mass * G;
        assert!((f[1] - carried).abs() < 1e-9 * carried && f[0].abs() < 1e-9 * carried, "pair {pair}: {f:?}");
    }
    assert_eq!(r.ambiguous_steps, 0);
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let err =
        run(&Spec::BlockOnBlock(BlockOnBlock { top_width: 0.5, ..BlockOnBlock::default() }), Sample::None)
            .unwrap_err();
    assert!(err.contains("top_width"), "{err}");
    let err = run(&Spec::Tablecloth(Tablecloth { mu_kinetic: 0.9, ..Tablecloth::default() }), Sample::None)
        .unwrap_err();
    assert!(err.contains("mu_kinetic"), "{err}");
    let err =
        run(&Spec::Tablecloth(Tablecloth { contact_margin: 0.01, ..Tablecloth::default() }), Sample::None)
            .unwrap_err();
    assert!(err.contains("contact_margin"), "{err}");
    let err = run(&Spec::Stack(Stack { blocks: 6, ..Stack::default() }), Sample::None).unwrap_err();
    assert!(err.contains("blocks"), "{err}");
    let err = run(&Spec::Stack(Stack { overhang: f64::NAN, ..Stack::default() }), Sample::None).unwrap_err();
    assert!(err.contains("overhang"), "{err}");
}

#[test]
fn stacks_of_four_and_five_solve_32_and_40_rows_and_an_aligned_stack_holds() {
    // Four blocks: 4 interfaces x 2 contacts = 8 contacts, a 32-row LCP each step; five: 40.
    for (blocks, overhang, expected, max_time) in [
        (4, 0.98, Outcome::Held, 1.0),
        (4, 1.02, Outcome::Fell, 1.0),
        (5, 0.98, Outcome::Held, 0.3),
        (5, 1.02, Outcome::Fell, 1.0),
        (3, 0.0, Outcome::Held, 1.0),
    ] {
        let p = Stack { blocks, overhang, max_time, ..Stack::default() };
        let r = run_spec(Spec::Stack(p));
        eprintln!(
            "stack of {blocks} at overhang {overhang}: {:?} at {:.3} s, max speed {:e} m/s, {} rows, {:.1} us/step",
            r.outcome,
            r.end_time,
            r.max_speed,
            r.max_rows,
            r.seconds_per_step * 1e6
        );
        assert_eq!(r.outcome, expected);
        assert_eq!(r.max_rows, 8 * blocks);
        if expected == Outcome::Held {
            assert!(r.max_speed < 1e-12, "held, yet moved at {:e} m/s", r.max_speed);
            // Aligned blocks (overhang 0) rest on both corners: indeterminate, the sums decided.
            for (pair, f) in r.interface_forces.iter().enumerate() {
                let carried = (blocks - pair) as f64 * p.mass * G;
                assert!(
                    (f[1] - carried).abs() < 1e-9 * carried && f[0].abs() < 1e-9 * carried,
                    "pair {pair}: {f:?}"
                );
            }
        }
    }
}

/// A violent two-box step: the top box tilted up to 0.6 rad, moving at up to 3 m/s and turning at
/// up to 5 rad/s, every coefficient up to 4 (Painlevé's territory: several motions solve the LCP).
fn violent_step(rng: &mut Random) -> RandomStep {
    let (mut system, mut q, mut v, _) = random_step(rng);
    let mu = rng.uniform(0.5, 4.0);
    for p in &mut system.pairs {
        p.mu_static = mu;
        p.mu_kinetic = mu * rng.uniform(0.3, 1.0);
    }
    let ([_, bottom_half_height], [top_half_width, top_half_height]) =
        (half_extents(&system.bodies[0]), half_extents(&system.bodies[1]));
    q[1][2] = rng.uniform(-0.6, 0.6);
    q[1][1] = q[0][1]
        + bottom_half_height
        + top_half_width * q[1][2].sin().abs()
        + top_half_height * q[1][2].cos()
        + rng.uniform(-1e-4, 1e-4);
    v[1] = [rng.uniform(-3.0, 3.0), rng.uniform(-1.0, 0.2), rng.uniform(-5.0, 5.0)];
    let frames = system.frames(&q, &v);
    let mu = frames
        .iter()
        .map(|f| {
            let pair = system.pairs[f.pair];
            if rng.uniform(0.0, 1.0) < 0.5 { pair.mu_static } else { pair.mu_kinetic }
        })
        .collect();
    (system, q, v, mu)
}

#[test]
fn the_solver_takes_the_least_energy_motion_of_violent_steps_as_enumeration_does() {
    let mut rng = Random(0x1234_5678_9abc_def1);
    let (mut cases, mut ambiguous, mut flagged) = (0, 0, 0);
    while cases < 300 {
        let (system, q, v, mu) = violent_step(&mut rng);
        let frames = system.frames(&q, &v);
        let lcp = assemble(&system, &q, &v, &frames, &mu);
        if lcp.active.len() < 2 {
            continue;
        }
        cases += 1;
        let (expected, enumerated_ambiguous) = enumerated_choice(&system, &lcp).unwrap();
        let result = solve(&system, &lcp, &vec![0; frames.len()], frames.len(), Starts::ALL).unwrap();
        let got: Vec<f64> = result.velocity.iter().flatten().copied().collect();
        let scale = lcp.free.iter().fold(0.0_f64, |m, x| m.max(x.abs())).max(1e-3);
        let err = got.iter().zip(&expected).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
        assert!(err < 1e-9, "case {cases}: v+ {got:?}, the enumeration's least-energy {expected:?}");
        ambiguous += usize::from(enumerated_ambiguous);
        flagged += usize::from(enumerated_ambiguous && result.ambiguous);
    }
    eprintln!(
        "violent two-box steps: {cases}, {ambiguous} with several motions (enumeration), {flagged} of them flagged ambiguous"
    );
    assert!(ambiguous >= 5, "the rule was exercised on {ambiguous} steps only");
    assert_eq!(flagged, ambiguous, "an ambiguous step was not flagged");
}

#[test]
fn rows_are_kept_as_asked() {
    let spec = Spec::BlockOnBlock(BlockOnBlock { force: 15.0, ..BlockOnBlock::default() });
    let all = run(&spec, Sample::All).unwrap();
    assert_eq!((all.outcome.clone(), all.steps), (Outcome::Rode, 300));
    assert_eq!(all.rows.len(), 301);
    assert_eq!(all.rows[0].t.to_bits(), 0.0_f64.to_bits());
    assert_eq!(all.rows[0].v, vec![[0.0; 3]; 2]);
    let last = all.rows.last().unwrap();
    assert_eq!((last.q.clone(), last.v.clone()), (all.q.clone(), all.v.clone()));
    assert_eq!(last.interface_forces, all.interface_forces);
    let every = run(&spec, Sample::Every(100)).unwrap();
    let times: Vec<f64> = every.rows.iter().map(|r| r.t).collect();
    assert_eq!(times, vec![0.0, all.rows[100].t, all.rows[200].t, all.rows[300].t]);
    assert_eq!(every.rows[2], all.rows[200]);
    assert_eq!(run(&spec, Sample::None).unwrap().rows.len(), 1);
}

// ---------------------------------------------------------------------------------------------
// disc-on-board (docs/formulation.md, "The rim-on-face contact").

/// The law of docs/formulation.md ("The rim-on-face contact") for `p`: the outcome and the
/// accelerations `(A, a_c)` of the board and the disc's centre.
fn disc_law(p: &DiscOnBoard) -> (Outcome, f64, f64) {
    let (big_m, m, g) = (p.board_mass, p.disc_mass, p.gravity);
    let floor = p.mu_floor * (big_m + m) * g;
    if p.force <= floor {
        return (Outcome::Held, 0.0, 0.0);
    }
    let rolling = (p.force - floor) / (big_m + m / 3.0);
    if rolling <= 3.0 * p.mu_static * g {
        (Outcome::Rolled, rolling, rolling / 3.0)
    } else {
        (Outcome::Slid, (p.force - p.mu_kinetic * m * g - floor) / big_m, p.mu_kinetic * g)
    }
}

#[test]
fn a_disc_on_a_pulled_board_follows_the_rim_law() {
    let p = DiscOnBoard::default();
    let (big_m, m, r) = (p.board_mass, p.disc_mass, p.disc_radius);
    let held = p.mu_floor * (big_m + m) * G;
    // The largest pull under which the disc rolls: A = 3 mu_s g.
    let rolls = 3.0 * p.mu_static * G * (big_m + m / 3.0) + held;
    let tol = 1e-9;
    let mut worst: f64 = 0.0;
    // The sliding runs are cut short: the disc slides back over the board's rear end (at 0.98 of
    // the threshold the rolling one stays on it for 0.3 s).
    for (force, max_time, expected) in [
        (0.5 * held, 0.3, Outcome::Held),
        (0.98 * held, 0.3, Outcome::Held),
        (1.02 * held, 0.3, Outcome::Rolled),
        (p.force, 0.3, Outcome::Rolled),
        (0.98 * rolls, 0.3, Outcome::Rolled),
        (1.02 * rolls, 0.2, Outcome::Slid),
        (100.0, 0.1, Outcome::Slid),
    ] {
        let q = DiscOnBoard { force, max_time, ..p };
        let (law, a_board, a_disc) = disc_law(&q);
        assert_eq!(law, expected, "the law's outcome at F = {force}");
        let run = run(&Spec::DiscOnBoard(q), Sample::All).unwrap();
        let (lower, upper) = (run.lower_acceleration.unwrap(), run.upper_acceleration.unwrap());
        let err = (lower - a_board).abs().max((upper - a_disc).abs());
        worst = worst.max(err);
        // Rolling: the rim's lowest point moves with the board, v_c + omega r = V (every step).
        let roll_slip = run
            .rows
            .iter()
            .map(|row| (row.v[1][0] + row.v[1][2] * r - row.v[0][0]).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "disc-on-board F = {force:7.3} N: {:?} after {} steps, A {lower:.12} (law {a_board:.12}), a_c {upper:.12} (law {a_disc:.12}), largest |v_c + omega r - V| {roll_slip:e} m/s, omega {:.6} rad/s, {} ambiguous",
            run.outcome, run.steps, run.v[1][2], run.ambiguous_steps
        );
        assert_eq!(run.outcome, expected, "F = {force}");
        assert_eq!(run.steps, (max_time / p.step).round() as u64);
        assert!(err < tol, "F = {force}: accelerations off the law by {err:e}");
        assert_eq!(run.ambiguous_steps, 0);
        // The disc never bounces or sinks: it stays on the board's top face.
        for row in &run.rows {
            let gap = row.q[1][1] - r - (row.q[0][1] + p.board_height / 2.0);
            assert!(gap.abs() < 1e-12 && row.q[0][2].abs() < 1e-12, "t {}: gap {gap:e}", row.t);
        }
        let [disc, floor] = [run.interface_forces[1], run.interface_forces[0]];
        match expected {
            Outcome::Held => assert!(run.max_speed < 1e-12, "held, yet moved at {:e} m/s", run.max_speed),
            Outcome::Rolled => {
                assert!(roll_slip < 1e-12, "rolling, yet slipping at {roll_slip:e} m/s");
                // Turning counter-clockwise at omega = (A - a_c) t / r, moving forward.
                let t = run.end_time;
                let omega = (a_board - a_disc) * t / r;
                assert!((run.v[1][2] - omega).abs() < 1e-9 * omega, "omega {} vs {omega}", run.v[1][2]);
                assert!(run.v[1][0] > 0.0 && run.v[1][0] < run.v[0][0], "{:?}", run.v);
                // The board's friction on the disc m A / 3 forward and its support m g; the
                // floor's on the board M A + m a_c - F along x (backward) and (M + m) g up.
                assert!((disc[0] - m * a_disc).abs() < 1e-9 && (disc[1] - m * G).abs() < 1e-9, "{disc:?}");
                let floor_x = big_m * a_board + m * a_disc - force;
                assert!(
                    (floor[0] - floor_x).abs() < 1e-9 && (floor[1] - (big_m + m) * G).abs() < 1e-9,
                    "{floor:?}"
                );
            }
            _ => {
                // Sliding back over the board: kinetic friction m mu_k g forward.
                assert!((disc[0] - m * p.mu_kinetic * G).abs() < 1e-9, "{disc:?}");
                assert!(roll_slip > 1e-3, "sliding, yet rolling");
            }
        }
    }
    eprintln!("disc-on-board: worst acceleration error {worst:e} m/s^2 (tolerance {tol:e})");
}

#[test]
fn a_disc_whose_contact_leaves_the_board_ends_the_run_unfinished() {
    // F = 100 N slides the disc back at A - mu_k g = 42.6 m/s^2: 0.5 m in about 0.153 s; a disc
    // started 5 cm from the rear end rolls back at 2 A / 3 = 4.87 m/s^2 and leaves within 0.15 s.
    for q in [
        DiscOnBoard { force: 100.0, ..DiscOnBoard::default() },
        DiscOnBoard { offset: -0.45, ..DiscOnBoard::default() },
    ] {
        let r = run(&Spec::DiscOnBoard(q), Sample::None).unwrap();
        let along = r.q[1][0] - r.q[0][0];
        eprintln!(
            "disc-on-board F {} offset {}: {:?} at {:.3} s, the disc {along:.4} m from the board's centre",
            q.force, q.offset, r.outcome, r.end_time
        );
        assert_eq!(r.outcome, Outcome::Unfinished);
        assert!(r.end_time < 0.2, "{}", r.end_time);
        assert!(along < -q.board_length / 2.0 && along > -q.board_length / 2.0 - 0.01, "{along}");
    }
}

/// A disc (body 1) on a tilted, moving board (body 0) on the floor, touching or nearly; `k`
/// (1..=3) active contacts.
fn random_disc_step(rng: &mut Random) -> RandomStep {
    let (length, height, radius) = (rng.uniform(0.3, 1.0), rng.uniform(0.01, 0.1), rng.uniform(0.02, 0.2));
    let mu_s = rng.uniform(0.1, 1.5);
    let system = System {
        bodies: vec![
            Body::block(length, height, rng.uniform(0.5, 3.0)),
            Body::disc(radius, rng.uniform(0.2, 2.0)),
        ],
        table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
        pairs: vec![
            Pair { upper: 0, lower: Lower::Table, mu_static: 0.3, mu_kinetic: 0.3 },
            Pair {
                upper: 1,
                lower: Lower::Body(0),
                mu_static: mu_s,
                mu_kinetic: mu_s * rng.uniform(0.3, 1.0),
            },
        ],
        forces: vec![[rng.uniform(-60.0, 60.0), 0.0], [rng.uniform(-5.0, 5.0), 0.0]],
        gravity: G,
        step: 1e-3,
        stick_speed: 1e-5,
        margin: 1e-3,
    };
    let tilt = rng.uniform(-0.01, 0.01);
    let q0 = [0.0, height / 2.0 + (length / 2.0) * tilt.abs() + rng.uniform(-1e-4, 1e-4), tilt];
    // The disc over the board at s, its centre r + gap along the face's normal.
    let s = rng.uniform(-0.45, 0.45) * length;
    let n = [-tilt.sin(), tilt.cos()];
    let e = [tilt.cos(), tilt.sin()];
    let lift = height / 2.0 + radius + rng.uniform(-1e-4, 1e-4);
    let q1 = [q0[0] + s * e[0] + lift * n[0], q0[1] + s * e[1] + lift * n[1], rng.uniform(-3.0, 3.0)];
    let v = vec![
        [rng.uniform(-0.5, 0.5), rng.uniform(-0.02, 0.02), rng.uniform(-0.2, 0.2)],
        [rng.uniform(-0.5, 0.5), rng.uniform(-0.05, 0.02), rng.uniform(-20.0, 20.0)],
    ];
    let frames = system.frames(&[q0, q1], &v);
    let mu = frames
        .iter()
        .map(|f| {
            let pair = system.pairs[f.pair];
            if rng.uniform(0.0, 1.0) < 0.5 { pair.mu_static } else { pair.mu_kinetic }
        })
        .collect();
    (system, vec![q0, q1], v, mu)
}

/// The world position after `q` moves to `moved` of body `i`'s material point at world `point`.
fn material_point(q: [f64; 3], moved: [f64; 3], point: [f64; 2]) -> [f64; 2] {
    let (s, c) = q[2].sin_cos();
    let l = [point[0] - q[0], point[1] - q[1]];
    let body = [c * l[0] + s * l[1], -s * l[0] + c * l[1]];
    let (s, c) = moved[2].sin_cos();
    [moved[0] + c * body[0] - s * body[1], moved[1] + s * body[0] + c * body[1]]
}

#[test]
fn the_rim_contacts_jacobian_is_its_closed_form_and_its_finite_differences() {
    let mut rng = Random(0x5eed_d15c_0b0a_4d00);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let (system, q, v, _) = random_disc_step(&mut rng);
        let frames = system.frames(&q, &v);
        // Pair 0: the board's two lower corners on the endless floor; pair 1: the rim alone.
        assert_eq!(frames.len(), 3);
        let f = frames[2];
        assert_eq!((f.pair, f.corner_body, f.face_body), (1, Some(1), Some(0)));
        let Shape::Disc { radius } = system.bodies[1].shape else { unreachable!() };
        let Shape::Box { half_height, .. } = system.bodies[0].shape else { unreachable!() };
        // P = c_U - r n_f, n = n_f = R(theta_S) (0, 1), d = (n_y, -n_x).
        let n = [-q[0][2].sin(), q[0][2].cos()];
        let d = [n[1], -n[0]];
        let rim = [q[1][0] - radius * n[0], q[1][1] - radius * n[1]];
        assert!(f.point.iter().zip(&rim).all(|(a, b)| (a - b).abs() < 1e-15), "{:?} {rim:?}", f.point);
        let face_centre = [q[0][0] + half_height * n[0], q[0][1] + half_height * n[1]];
        let gap = (q[1][0] - face_centre[0]) * n[0] + (q[1][1] - face_centre[1]) * n[1] - radius;
        assert!((f.gap - gap).abs() < 1e-15, "{} {gap}", f.gap);
        let r_s = [rim[0] - q[0][0], rim[1] - q[0][1]];
        // Closed form: the normal through the centre (r_U x n = 0), the friction's lever r
        // (r_U x d = r, r_U x -d = -r).
        for (t, spin) in [(n, 0.0), (d, radius), ([-d[0], -d[1]], -radius)] {
            let row = f.row(t, 2);
            let closed = [-t[0], -t[1], -(r_s[0] * t[1] - r_s[1] * t[0]), t[0], t[1], spin];
            for (a, b) in row.iter().zip(&closed) {
                assert!((a - b).abs() < 1e-14, "{row:?} vs {closed:?}");
            }
            // Finite differences: each body moved rigidly by +-eps V, the rim's material point
            // relative to the board's (both at P at the start) along t, over 2 eps, is J_t V.
            let eps = 1e-6;
            let moved = |sign: f64, i: usize| {
                [
                    q[i][0] + sign * eps * v[i][0],
                    q[i][1] + sign * eps * v[i][1],
                    q[i][2] + sign * eps * v[i][2],
                ]
            };
            let relative = |sign: f64| {
                let a = material_point(q[1], moved(sign, 1), rim);
                let b = material_point(q[0], moved(sign, 0), rim);
                (a[0] - b[0]) * t[0] + (a[1] - b[1]) * t[1]
            };
            let fd = (relative(1.0) - relative(-1.0)) / (2.0 * eps);
            let jv: f64 = row.iter().zip(v.iter().flatten()).map(|(a, b)| a * b).sum();
            let scale = v.iter().flatten().fold(1.0_f64, |s, x| s.max(x.abs()));
            worst = worst.max((fd - jv).abs() / scale);
            assert!((fd - jv).abs() < 1e-7 * scale, "finite differences {fd} vs J_t V {jv}");
            let t_dot_v_rel = dot(t, f.relative_velocity(&v));
            assert!((jv - t_dot_v_rel).abs() < 1e-13 * scale, "{jv} vs {t_dot_v_rel}");
        }
    }
    eprintln!("the rim contact's rows against finite differences: worst |fd - J_t V| / |V| = {worst:e}");
}

#[test]
fn the_solver_agrees_with_enumeration_on_disc_on_board_steps() {
    // Random disc-on-board steps, and every step of the scene's runs (held, rolling, sliding).
    let mut rng = Random(0x0dd5_eed5_d15c_0001);
    let mut steps: Vec<RandomStep> = Vec::new();
    while steps.len() < 150 {
        let step = random_disc_step(&mut rng);
        if step.0.frames(&step.1, &step.2).iter().any(|f| f.active && f.pair == 1) {
            steps.push(step);
        }
    }
    let mut scene_steps = 0;
    for force in [2.0, 20.0, 100.0] {
        let p = DiscOnBoard { force, max_time: 0.05, ..DiscOnBoard::default() };
        let system = p.system();
        let mut state = State::at_rest(&system, p.start());
        for _ in 0..50 {
            let frames = system.frames(&state.q, &state.v);
            let mu = system
                .friction(&frames)
                .iter()
                .zip(&state.modes)
                .map(|(&(mu_s, mu_k), mode)| if mode.is_sliding() { mu_k } else { mu_s })
                .collect();
            steps.push((system.clone(), state.q.clone(), state.v.clone(), mu));
            scene_steps += 1;
            state.advance(&system, Starts::ALL).unwrap();
        }
    }
    let (mut by_size, mut ambiguous, mut worst) = ([0_usize; 4], 0, 0.0_f64);
    for (case, (system, q, v, mu)) in steps.iter().enumerate() {
        let frames = system.frames(q, v);
        let lcp = assemble(system, q, v, &frames, mu);
        by_size[lcp.active.len()] += 1;
        let Some((expected, enumerated_ambiguous)) = enumerated_choice(system, &lcp) else {
            panic!("case {case}: the enumeration found no solution of a {}-row step", lcp.offset.len());
        };
        let result = solve(system, &lcp, &vec![0; frames.len()], frames.len(), Starts::ALL).unwrap();
        let got: Vec<f64> = result.velocity.iter().flatten().copied().collect();
        let scale = lcp.free.iter().fold(0.0_f64, |m, x| m.max(x.abs())).max(1e-3);
        let err = got.iter().zip(&expected).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
        worst = worst.max(err);
        ambiguous += usize::from(enumerated_ambiguous);
        assert!(err < 1e-9, "case {case}: v+ {got:?}, the enumeration's {expected:?}");
        assert_eq!(result.ambiguous, enumerated_ambiguous, "case {case}");
    }
    eprintln!(
        "disc-on-board steps: {} ({scene_steps} from the scene; {:?} with 1/2/3 contacts), {ambiguous} ambiguous by enumeration, worst |v - v_enum| / S = {worst:e}",
        steps.len(),
        &by_size[1..]
    );
    assert!(by_size[3] >= 100, "{by_size:?}");
}

#[test]
fn bad_disc_on_board_parameters_and_a_disc_under_a_body_are_refused_by_name() {
    for (spec, name) in [
        (DiscOnBoard { disc_radius: 0.0, ..DiscOnBoard::default() }, "disc_radius"),
        (DiscOnBoard { disc_mass: f64::NAN, ..DiscOnBoard::default() }, "disc_mass"),
        (DiscOnBoard { offset: 0.6, ..DiscOnBoard::default() }, "offset"),
        (DiscOnBoard { mu_kinetic: 0.6, ..DiscOnBoard::default() }, "mu_kinetic"),
        (DiscOnBoard { board_height: -0.02, ..DiscOnBoard::default() }, "board_height"),
        (DiscOnBoard { step: 1.0, ..DiscOnBoard::default() }, "step"),
    ] {
        let err = run(&Spec::DiscOnBoard(spec), Sample::None).unwrap_err();
        assert!(err.contains(name), "{name}: {err}");
    }
    // A board resting on the disc: refused, and the pair has no candidate (a disc has no face).
    let mut system = DiscOnBoard::default().system();
    system.pairs[1] = Pair { upper: 0, lower: Lower::Body(1), mu_static: 0.5, mu_kinetic: 0.4 };
    let err = system.check_pairs(&["board", "disc"]).unwrap_err();
    assert!(err.contains("board rests on disc, a disc"), "{err}");
    let q = DiscOnBoard::default().start();
    assert!(system.frames(&q, &[[0.0; 3]; 2]).iter().all(|f| f.pair == 0));
    assert!(DiscOnBoard::default().system().check_pairs(&["board", "disc"]).is_ok());
}

#[test]
fn a_disc_pushed_at_its_centre_on_the_table_rolls_at_two_thirds_of_f_over_m() {
    // The rim on the table (no face body): F at the centre, friction f back, m a = F - f,
    // (m r^2 / 2) alpha = r f, rolling a = alpha r: a = 2 F / (3 m) while F / 3 <= mu_s m g;
    // beyond, a = F / m - mu_k g and alpha = 2 mu_k g / r.
    let (m, r, mu_s, mu_k) = (1.5, 0.08, 0.4, 0.3);
    for (force, rolls) in [(6.0, true), (0.99 * 3.0 * mu_s * m * G, true), (20.0, false)] {
        let system = System {
            bodies: vec![Body::disc(r, m)],
            table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
            pairs: vec![Pair { upper: 0, lower: Lower::Table, mu_static: mu_s, mu_kinetic: mu_k }],
            forces: vec![[force, 0.0]],
            gravity: G,
            step: 1e-3,
            stick_speed: 1e-5,
            margin: 1e-3,
        };
        let mut state = State::at_rest(&system, vec![[0.0, r, 0.0]]);
        let mut slid = false;
        for _ in 0..200 {
            let stepped = state.advance(&system, Starts::ALL).unwrap();
            assert_eq!(stepped.frames.len(), 1);
            slid |= state.modes[0].is_sliding();
        }
        let t = state.time(&system);
        // Sliding, the first step's friction is mu_s (the disc was sticking at rest), mu_k after.
        let (v_law, omega_law) = if rolls {
            (2.0 * force / (3.0 * m) * t, -2.0 * force / (3.0 * m * r) * t)
        } else {
            let h = system.step;
            (
                (force / m - mu_k * G) * t - h * (mu_s - mu_k) * G,
                -2.0 * G * (mu_k * t + h * (mu_s - mu_k)) / r,
            )
        };
        let v = state.v[0];
        eprintln!(
            "disc on the table F = {force:.4} N: v {:.12} (law {v_law:.12}), omega {:.9} (law {omega_law:.9}), slid {slid}",
            v[0], v[2]
        );
        assert_eq!(slid, !rolls, "F = {force}");
        // Moving to the right, turning clockwise (omega < 0).
        assert!((v[0] - v_law).abs() < 1e-12 && (v[2] - omega_law).abs() < 1e-10, "{v:?}");
        assert!((state.q[0][1] - r).abs() < 1e-12 && v[1].abs() < 1e-12, "{:?}", state.q);
    }
}
