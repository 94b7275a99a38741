//! The stepper's fast path (`FactoredLcp::solve_basis`: a basis solved in the body's three
//! degrees of freedom, `docs/formulation.md`, "Solving a step") against the assembled LCP and the
//! test's own dense algebra (`meterstick_tests::enumeration`, f64, independent of the core), on
//! random planar steps, every complementary basis of each:
//!
//! * every answer the fast path gives solves the assembled LCP (the test's own check) and is zero
//!   off its basis;
//! * it is the complementary solution of that basis: where the basis' principal system is
//!   regular, the dense solve of `A_SS z_S = -q_S` gives the same `z`;
//! * `v+` is `v~ + M^-1 W z` (eq. 16);
//! * where the fast path declines a basis, Lemke's method from that basis (the stepper's last
//!   path) answers only solvable LCPs, and its answers solve them.
//!
//! The random steps include the degenerate ones: a level rod on two fingers (both sticking is
//! statically indeterminate: four constraints on three degrees of freedom), contacts exactly
//! touching with no approach speed (grazing), contacts apart (separated) and support speeds of
//! zero (zero slip).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::lcp::{Basis, Lemke, default_tolerance};
use meterstick_core::planar::assemble::{StepInputs, assemble};
use meterstick_core::planar::{ContactFrame, FactoredLcp, Layout, Pose, Tangents};
use meterstick_tests::enumeration::{Mat, all_solutions, is_lcp_solution, solve_dense};
use proptest::prelude::*;

/// One random step: a rod (or block) over two supports, given as plain numbers.
#[derive(Debug, Clone)]
struct Step {
    theta: f64,
    half: [f64; 2],
    /// Finger tips' x under the rod (point supports) or, with `lines`, the body points' x.
    xs: [f64; 2],
    /// Each support's height offset from touching (0: exactly touching).
    gaps: [f64; 2],
    lines: bool,
    mu: [f64; 2],
    u: [[f64; 2]; 2],
    v_free: [f64; 3],
    inertia_ratio: f64,
    /// The linear entries of `M^-1` (1 per unit mass, as the stepper has them; other values as a
    /// caller of `FactoredLcp` may give).
    linear: f64,
}

fn step_strategy() -> impl Strategy<Value = Step> {
    let gap = prop_oneof![3 => Just(0.0), 1 => -1e-6..1e-6f64, 1 => Just(1e-3)];
    let speed = prop_oneof![2 => Just(0.0), 1 => -0.2..0.2f64];
    (
        prop_oneof![Just(0.0), -0.3..0.3f64],
        (0.1..1.0f64, 0.001..0.2f64),
        (-0.9..0.9f64, -0.9..0.9f64),
        (gap.clone(), gap),
        any::<bool>(),
        (prop_oneof![Just(0.0), 0.05..2.0f64], prop_oneof![Just(0.0), 0.05..2.0f64]),
        ((speed.clone(), speed.clone()), (speed.clone(), speed)),
        (
            prop_oneof![Just(0.0), -0.1..0.1f64],
            prop_oneof![3 => Just(-0.00981), 1 => -0.1..0.1f64],
            prop_oneof![Just(0.0), -0.5..0.5f64],
        ),
        (prop_oneof![Just(12.0), 1.0..50.0f64], prop_oneof![3 => Just(1.0), 1 => 0.2..5.0f64]),
    )
        .prop_map(
            |(
                theta,
                (hx, hy),
                (a, b),
                (g1, g2),
                lines,
                (mu1, mu2),
                ((u1, u2), (u3, u4)),
                (vx, vy, w),
                (k, l),
            )| {
                Step {
                    theta,
                    half: [hx, hy],
                    xs: [a * hx, b * hx],
                    gaps: [g1, g2],
                    lines,
                    mu: [mu1, mu2],
                    u: [[u1, u2], [u3, u4]],
                    v_free: [vx, vy, w],
                    inertia_ratio: k,
                    linear: l,
                }
            },
        )
}

/// The contact frames of `s`: finger tips under the lower face, or the body's lower corners on a
/// floor (`lines`).
fn frames(s: &Step) -> [ContactFrame<f64>; 2] {
    let (sin, cos) = s.theta.sin_cos();
    let pose = Pose { com: [0.0, 0.0], sin_cos: (sin, cos) };
    core::array::from_fn(|i| {
        // The body point at (x, -hy) in the world, lowered or raised by the gap.
        let (bx, by) = (s.xs[i], -s.half[1]);
        let world = [cos * bx - sin * by, sin * bx + cos * by];
        if s.lines {
            let o = [world[0], world[1] - s.gaps[i]];
            ContactFrame::point_on_line([bx, by], o, [0.0, 1.0], &pose)
        } else {
            // A tip under the face: along the face's normal from the contact point.
            let tip = [world[0] + sin * s.gaps[i], world[1] - cos * s.gaps[i]];
            ContactFrame::under_lower_face(tip, &pose, s.half)
        }
    })
}

fn dense<const N: usize>(lcp: &meterstick_core::lcp::Lcp<f64, N>) -> (Mat, Vec<f64>) {
    let m = (0..N).map(|i| (0..N).map(|j| lcp.m[(i, j)]).collect()).collect();
    (m, (0..N).map(|i| lcp.q[i]).collect())
}

/// Checks every basis of one step in `layout`; returns (bases the fast path answered, declined
/// bases Lemke's method answered from).
fn check<const N: usize>(s: &Step, layout: &Layout<2, N>) -> (usize, usize) {
    let frames = frames(s);
    let m_inv = [s.linear, s.linear, s.inertia_ratio];
    let inputs = StepInputs {
        frames: &frames,
        mu: s.mu,
        support_velocity: s.u,
        v_free: s.v_free,
        m_inv,
        h: 1e-3,
        gravity: 9.81,
        gap_round_off: 0.0,
    };
    let factored = FactoredLcp::new(layout, &inputs);
    let step_lcp = assemble(layout, &inputs);
    let (m, q) = dense(&step_lcp.lcp);
    let tol = default_tolerance::<f64, N>();
    let mut answered = 0;
    for mask in 0u32..(1 << N) {
        let Ok(answer) = factored.solve_basis(Basis::from_z_mask(mask), tol) else { continue };
        answered += 1;
        let z = answer.z.to_vec();
        assert!(is_lcp_solution(&m, &q, &z, 1e-9), "basis {mask:0N$b}: z = {z:?} does not solve the LCP");
        for (j, &zj) in z.iter().enumerate() {
            assert!(mask >> j & 1 == 1 || zj == 0.0, "basis {mask:0N$b}: z_{j} = {zj} off the basis");
        }
        // The basis' own complementary solution, by the test's dense algebra.
        let set: Vec<usize> = (0..N).filter(|&j| mask >> j & 1 == 1).collect();
        let a_ss: Mat = set.iter().map(|&r| set.iter().map(|&c| m[r][c]).collect()).collect();
        let rhs: Vec<f64> = set.iter().map(|&r| -q[r]).collect();
        if let Some(zs) = solve_dense(&a_ss, &rhs) {
            let scale = 1.0 + z.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            for (k, &j) in set.iter().enumerate() {
                assert!(
                    (z[j] - zs[k]).abs() <= 1e-8 * scale,
                    "basis {mask:0N$b}: z_{j} = {} but the dense solve gives {}",
                    z[j],
                    zs[k]
                );
            }
        }
        // eq. 16: v+ = v~ + M^-1 sum_j c_j z_j.
        let mut v = s.v_free;
        for j in 0..N - 2 {
            for k in 0..3 {
                v[k] += m_inv[k] * step_lcp.columns[j][k] * z[j];
            }
        }
        for k in 0..3 {
            assert!(
                (answer.v_plus[k] - v[k]).abs() <= 1e-12 * (1.0 + v[k].abs()),
                "v+ differs: {:?} {v:?}",
                answer.v_plus
            );
        }
    }
    // Where the fast path declines, the stepper goes on to Lemke's method from the same basis:
    // whatever it answers from there solves the LCP (the first 16 declined bases of each step).
    let mut lemke_answered = 0;
    let solvable = !all_solutions(&m, &q).is_empty();
    for mask in
        (0u32..(1 << N)).filter(|&b| factored.solve_basis(Basis::from_z_mask(b), tol).is_err()).take(16)
    {
        if let Ok(sol) = Lemke::<f64, N>::new().solve_from_basis(&step_lcp.lcp, Basis::from_z_mask(mask)) {
            assert!(solvable, "Lemke answered an LCP that enumeration finds unsolvable");
            assert!(
                is_lcp_solution(&m, &q, sol.z.as_slice(), 1e-9),
                "Lemke's answer from {mask:0N$b} does not solve the LCP"
            );
            lemke_answered += 1;
        }
    }
    (answered, lemke_answered)
}

const REDUCED: Layout<2, 6> = Layout::new([Tangents::Plus, Tangents::Minus]);
const FULL: Layout<2, 8> = Layout::full();

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn fast_answers_are_the_bases_complementary_solutions_6x6(s in step_strategy()) {
        check(&s, &REDUCED);
    }

    #[test]
    fn fast_answers_are_the_bases_complementary_solutions_8x8(s in step_strategy()) {
        check(&s, &FULL);
    }
}

/// The degenerate steps by name: a level rod resting on two fingers, both sticking (statically
/// indeterminate), grazing and apart. The fast path answers each (some basis is accepted), and
/// what it answers solves the LCP (checked inside `check`).
#[test]
fn degenerate_steps_are_answered() {
    let rest = Step {
        theta: 0.0,
        half: [0.5, 0.0025],
        xs: [-0.3, 0.4],
        gaps: [0.0, 0.0],
        lines: false,
        mu: [0.6, 0.6],
        u: [[0.0; 2]; 2],
        v_free: [0.0, -0.00981, 0.0],
        inertia_ratio: 12.0,
        linear: 1.0,
    };
    let grazing = Step { v_free: [0.0, 0.0, 0.0], ..rest.clone() };
    let apart = Step { gaps: [1e-3, 1e-3], ..rest.clone() };
    let one_slides = Step { u: [[0.1, 0.0], [0.0, 0.0]], mu: [0.4, 0.6], ..rest.clone() };
    for (name, s) in
        [("resting", &rest), ("grazing", &grazing), ("apart", &apart), ("one slides", &one_slides)]
    {
        let (answered6, _) = check(s, &REDUCED);
        let (answered8, _) = check(s, &FULL);
        assert!(answered6 > 0 && answered8 > 0, "{name}: no basis answered ({answered6}, {answered8})");
    }
}

/// A support velocity that is not finite makes the step an error (`NonFiniteInput`), never an
/// answer: the fast path's `q >= 0` test must not be fooled by a NaN or an infinity in `q`.
#[test]
fn a_non_finite_support_velocity_is_an_error() {
    use meterstick_core::lcp::LcpError;
    use meterstick_core::planar::{
        Body, BodyState, Contact, Feature, Model, Settings, StepError, Stepper, Support,
    };
    const FULL: Layout<2, 8> = Layout::full();
    let body = Body::block(1.0_f64, 0.2, 0.1);
    let corner = |x: f64| Contact { feature: Feature::Point([x, -0.05]), mu_static: 0.5, mu_kinetic: 0.5 };
    let settings = Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 };
    let model = Model { body, contacts: [corner(-0.1), corner(0.1)], settings };
    let floor = Support::fixed_line([0.0, 0.0], [0.0, 1.0]);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut stepper =
            Stepper::new(model, FULL, FULL, BodyState::at_rest(0.0, 0.05, 0.0), [floor; 2]).unwrap();
        stepper.step(&[floor; 2]).unwrap();
        let moving = Support::Line { position: [0.0, 0.0], normal: [0.0, 1.0], velocity: [bad, 0.0] };
        let before = *stepper.state();
        let result = stepper.step(&[moving, floor]);
        assert_eq!(result.err(), Some(StepError::Solver(LcpError::NonFiniteInput)), "velocity {bad}");
        assert_eq!(*stepper.state(), before, "a failed step leaves the state as it was");
    }
}

/// A support whose position is not finite, or a line whose normal is not a unit vector, is an
/// error, never a step: a NaN position made its contact silently inactive (the rod tipped and
/// sank with every step `Ok`), a zero normal let a block fall through the floor (y = -4.88 m
/// after 1,000 steps, both contacts separated). The state is as it was, and the next step with
/// good supports goes on. `Stepper::new` refuses them too.
#[test]
fn a_malformed_support_is_an_error() {
    use meterstick_core::ParamError;
    use meterstick_core::lcp::LcpError;
    use meterstick_core::planar::{
        Body, BodyState, Contact, Feature, Model, Settings, StepError, Stepper, Support,
    };
    const FULL: Layout<2, 8> = Layout::full();
    let settings = Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 };
    // A rod on two fingers.
    let rod = Body::rod(1.0_f64, 1.0, 0.01);
    let face = Contact { feature: Feature::LowerFace, mu_static: 0.5, mu_kinetic: 0.4 };
    let model = Model { body: rod, contacts: [face; 2], settings };
    let finger = |x: f64| Support::point([x, 0.0], [0.0, 0.0]);
    let start = BodyState::at_rest(0.0, 0.005, 0.0);
    let mut stepper = Stepper::new(model, FULL, FULL, start, [finger(-0.3), finger(0.3)]).unwrap();
    stepper.step(&[finger(-0.3), finger(0.3)]).unwrap();
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let before = (*stepper.state(), stepper.time(), stepper.modes(), *stepper.frames());
        let result = stepper.step(&[finger(bad), finger(0.3)]);
        assert_eq!(result.err(), Some(StepError::Solver(LcpError::NonFiniteInput)), "position {bad}");
        assert_eq!(
            (*stepper.state(), stepper.time(), stepper.modes(), *stepper.frames()),
            before,
            "the state is as it was"
        );
        let report = stepper.step(&[finger(-0.3), finger(0.3)]).unwrap();
        assert!(report.contacts.iter().all(|c| c.mode.is_touching()), "{report:?}");
    }
    assert_eq!(
        Stepper::new(model, FULL, FULL, start, [finger(-0.3), finger(f64::NAN)]).err(),
        Some(ParamError::NonFinite("support"))
    );
    // A block on a floor whose normal is zero, then one whose normal is not a unit vector.
    let block = Body::block(1.0_f64, 0.2, 0.1);
    let corner = |x: f64| Contact { feature: Feature::Point([x, -0.05]), mu_static: 0.5, mu_kinetic: 0.5 };
    let model = Model { body: block, contacts: [corner(-0.1), corner(0.1)], settings };
    let floor = Support::fixed_line([0.0, 0.0], [0.0, 1.0]);
    let at_rest = BodyState::at_rest(0.0, 0.05, 0.0);
    for normal in [[0.0, 0.0], [0.0, 2.0], [0.6, 0.6]] {
        let bad = Support::fixed_line([0.0, 0.0], normal);
        assert_eq!(
            Stepper::new(model, FULL, FULL, at_rest, [bad, floor]).err(),
            Some(ParamError::OutOfRange("support")),
            "normal {normal:?}"
        );
        let mut stepper = Stepper::new(model, FULL, FULL, at_rest, [floor; 2]).unwrap();
        assert_eq!(stepper.step(&[floor, bad]).err(), Some(StepError::MalformedSupport(1)), "{normal:?}");
    }
    // A unit normal from an angle, rounded, is one.
    let (s, c) = 0.3_f64.sin_cos();
    let slope = Support::fixed_line([0.0, 0.0], [-s, c]);
    assert!(slope.is_well_formed());
}

/// The property tests above are not vacuous: over 300 random steps (a fixed seed), the fast path
/// answers some basis of nearly every one, in both layouts (every step's LCP has a solution, and
/// the patterns it declines are few).
#[test]
fn the_fast_path_answers_nearly_every_random_step() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let (mut steps, mut answered6, mut answered8) = (0usize, 0usize, 0usize);
    for _ in 0..300 {
        let s = step_strategy().new_tree(&mut runner).unwrap().current();
        steps += 1;
        answered6 += usize::from(check(&s, &REDUCED).0 > 0);
        answered8 += usize::from(check(&s, &FULL).0 > 0);
    }
    println!("steps with an answered basis: 6x6 {answered6}, 8x8 {answered8} of {steps}");
    assert!(
        answered6 * 10 >= steps * 9 && answered8 * 10 >= steps * 9,
        "6x6 {answered6}, 8x8 {answered8} of {steps}"
    );
}
