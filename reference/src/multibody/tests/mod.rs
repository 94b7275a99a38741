//! The multibody reference's checks: its solver against textbook LCPs and against the
//! exhaustive enumerator (`crate::enumerate`) on random small multibody steps, the
//! indeterminate interface, and the analytic laws of docs/scenes.md ("block-on-block",
//! "tablecloth", "stack") on its own runs. The measured figures are printed
//! (`-- --nocapture`). The laws of the scenes are in `laws.rs`, the disc on a board in `disc.rs`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::geometry::{Body, Lower, Pair, Shape, Table, dot};
use super::lcp::{LemkeFailure, lemke, solve_basis, verify};
use super::step::{Starts, StepLcp, assemble, solve};
use super::system::{State, System};
use super::*;
use crate::Sample;
use crate::enumerate::{Lcp, enumerate, is_lcp_solution};

mod disc;
mod laws;

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
