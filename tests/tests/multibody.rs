//! The multibody core (`meterstick_core::multibody`) against the laws of `docs/scenes.md`, "Scenes
//! of several bodies", in f32 and f64, several points on each side of every threshold, and against
//! the independent reference (`meterstick_reference::multibody`) on the three default runs.
#![allow(clippy::expect_used)]

use meterstick_core::lcp::LcpError;
use meterstick_core::multibody::scenes::{
    BlockOnBlock, BlockOnBlockParams, DiscOnBoard, DiscOnBoardParams, MultibodyScene as _, Stack, Stack2,
    Stack3, StackParams, Tablecloth, TableclothParams,
};
use meterstick_core::multibody::{
    Pair, RestsOn, Shape, StepError, System, SystemSettings, SystemStepReport, SystemStepper, Table,
};
use meterstick_core::planar::{Body, BodyState, ContactMode, PathCounts};
use meterstick_core::scene::Outcome;
use meterstick_core::{ParamError, Real};
use meterstick_reference::multibody as reference;

/// What a run measured, in f64.
#[derive(Debug)]
struct Measured {
    outcome: Outcome,
    steps: u64,
    /// `[lower, upper]` accelerations in full contact (m/s^2).
    accelerations: Option<[f64; 2]>,
    /// The largest `|vx|` of any body over the run (m/s).
    max_vx: f64,
    /// Each body's `(x, y, theta)` at the end.
    q: Vec<[f64; 3]>,
    /// The last step's summed interface force on the upper body of each pair (N).
    forces: Vec<[f64; 2]>,
}

fn max_vx<T: Real, const B: usize, const P: usize>(report: &SystemStepReport<T, B, P>, max: &mut f64) {
    for s in &report.states {
        *max = max.max(s.vx.as_f64().abs());
    }
}

fn forces<T: Real, const B: usize, const P: usize>(report: &SystemStepReport<T, B, P>) -> Vec<[f64; 2]> {
    report.interface_forces.iter().map(|f| [f[0].as_f64(), f[1].as_f64()]).collect()
}

fn positions<T: Real>(states: &[BodyState<T>]) -> Vec<[f64; 3]> {
    states.iter().map(|s| [s.x.as_f64(), s.y.as_f64(), s.theta.as_f64()]).collect()
}

fn block_on_block<T: Real>(p: BlockOnBlockParams<f64>) -> Measured {
    let mut scene = BlockOnBlock::new(p.cast::<T>()).expect("valid parameters");
    let mut max = 0.0;
    let mut last = Vec::new();
    let outcome = scene.run(|r| {
        max_vx(r, &mut max);
        last = forces(r);
    });
    Measured {
        outcome,
        steps: scene.stepper().stats().steps,
        accelerations: scene.accelerations().map(|a| a.map(Real::as_f64)),
        max_vx: max,
        q: positions(scene.stepper().states()),
        forces: last,
    }
}

fn tablecloth<T: Real>(p: TableclothParams<f64>) -> (Measured, f64) {
    let mut scene = Tablecloth::new(p.cast::<T>()).expect("valid parameters");
    let mut max = 0.0;
    let mut last = Vec::new();
    let outcome = scene.run(|r| {
        max_vx(r, &mut max);
        last = forces(r);
    });
    let measured = Measured {
        outcome,
        steps: scene.stepper().stats().steps,
        accelerations: scene.accelerations().map(|a| a.map(Real::as_f64)),
        max_vx: max,
        q: positions(scene.stepper().states()),
        forces: last,
    };
    (measured, scene.block_displacement().as_f64())
}

/// A stack's run: outcome, `max_speed`, the last step's interface forces `(x, y)` per pair, the end
/// positions.
fn stack<T: Real, const B: usize, const N: usize>(
    p: StackParams<f64>,
) -> (Outcome, f64, Vec<[f64; 2]>, Vec<[f64; 3]>) {
    let mut scene = Stack::<T, B, N>::new(p.cast::<T>()).expect("valid parameters");
    let mut forces = Vec::new();
    let outcome =
        scene.run(|r| forces = r.interface_forces.iter().map(|f| [f[0].as_f64(), f[1].as_f64()]).collect());
    (outcome, scene.max_speed().as_f64(), forces, positions(scene.stepper().states()))
}

/// The tolerance on an acceleration from the laws (m/s^2): f64 `1e-9` (measured 8.7e-14 at
/// worst on block-on-block); f32 `2e-4` (measured 2.8e-5: velocities of ~3 m/s carry ~2e-7 m/s
/// of round-off per step, differenced over 0.3 s).
fn acceleration_tolerance<T: Real>() -> f64 {
    if T::BYTES == 8 { 1e-9 } else { 2e-4 }
}

/// The largest speed a held run may reach: f64 `1e-12` m/s, f32 `1e-5` m/s (round-off).
fn rest_speed<T: Real>() -> f64 {
    if T::BYTES == 8 { 1e-12 } else { 1e-5 }
}

fn block_on_block_laws<T: Real>() {
    let d = BlockOnBlockParams::<f64>::default();
    let (g, m, big_m) = (d.gravity, d.top_mass, d.bottom_mass);
    let held = d.mu_floor * (big_m + m) * g;
    let sliding = (d.mu_static + d.mu_floor) * (big_m + m) * g;
    let tol = acceleration_tolerance::<T>();
    for (force, expected) in [
        (0.5 * held, Outcome::Held),
        (0.98 * held, Outcome::Held),
        (1.02 * held, Outcome::Rode),
        (0.5 * (held + sliding), Outcome::Rode),
        (0.98 * sliding, Outcome::Rode),
        (1.02 * sliding, Outcome::Slid),
        (1.5 * sliding, Outcome::Slid),
        (3.0 * sliding, Outcome::Slid),
    ] {
        let run = block_on_block::<T>(BlockOnBlockParams { force, ..d });
        assert_eq!(run.outcome, expected, "{} F = {force}: {run:?}", T::NAME);
        let [a_bottom, a_top] = run.accelerations.expect("both blocks in full contact");
        let (want_bottom, want_top) = match expected {
            Outcome::Held => {
                assert!(
                    run.max_vx < rest_speed::<T>(),
                    "{} F = {force}: held at {} m/s",
                    T::NAME,
                    run.max_vx
                );
                (0.0, 0.0)
            }
            Outcome::Rode => {
                let a = force / (big_m + m) - d.mu_floor * g;
                (a, a)
            }
            _ => ((force - d.mu_kinetic * m * g - d.mu_floor * (big_m + m) * g) / big_m, d.mu_kinetic * g),
        };
        assert!(
            (a_bottom - want_bottom).abs() < tol && (a_top - want_top).abs() < tol,
            "{} F = {force}: a_bottom {a_bottom} (law {want_bottom}), a_top {a_top} (law {want_top})",
            T::NAME
        );
        // Held or riding, the top block sticks on two corners (statically indeterminate); the
        // summed force on it is decided: (m a, m g) at the end.
        if expected != Outcome::Slid {
            let [fx, fy] = run.forces[1];
            let force_tol = if T::BYTES == 8 { 1e-9 } else { 1e-3 };
            assert!(
                (fx - m * want_top).abs() < force_tol && (fy - m * g).abs() < force_tol,
                "{} F = {force}: interface force ({fx}, {fy}), law ({}, {})",
                T::NAME,
                m * want_top,
                m * g
            );
        }
    }
    // A tall top block tips when g w / h < a <= mu_s g.
    let tall = BlockOnBlockParams { top_width: 0.05, top_height: 0.2, max_time: 1.0, ..d };
    let tipping = (big_m + m) * (g * tall.top_width / tall.top_height + d.mu_floor * g);
    assert!(tipping < 1.2 * tipping && 1.2 * tipping < sliding, "tipping comes before sliding");
    for (factor, expected) in
        [(0.9, Outcome::Rode), (0.97, Outcome::Rode), (1.03, Outcome::Tipped), (1.2, Outcome::Tipped)]
    {
        let run = block_on_block::<T>(BlockOnBlockParams { force: factor * tipping, ..tall });
        assert_eq!(run.outcome, expected, "{} {factor} of the tipping force: {run:?}", T::NAME);
    }
}

#[test]
fn block_on_block_follows_its_laws_in_f64() {
    block_on_block_laws::<f64>();
}

#[test]
fn block_on_block_follows_its_laws_in_f32() {
    block_on_block_laws::<f32>();
}

fn tablecloth_laws<T: Real>() {
    let d = TableclothParams::<f64>::default();
    let (g, m, mb) = (d.gravity, d.block_mass, d.board_mass);
    let held = d.mu_floor * (m + mb) * g;
    let riding = (d.mu_static + d.mu_floor) * (m + mb) * g;
    let tol = acceleration_tolerance::<T>();
    for (force, expected) in [
        (0.5 * held, Outcome::Held),
        (0.98 * held, Outcome::Held),
        (1.02 * held, Outcome::Rode),
        (0.98 * riding, Outcome::Rode),
    ] {
        let (run, _) = tablecloth::<T>(TableclothParams { force, max_time: 0.3, ..d });
        assert_eq!(run.outcome, expected, "{} F = {force}: {run:?}", T::NAME);
        let [a_board, a_block] = run.accelerations.expect("full contact");
        let a = if expected == Outcome::Held { 0.0 } else { force / (m + mb) - d.mu_floor * g };
        assert!(
            (a_board - a).abs() < tol && (a_block - a).abs() < tol,
            "{} F = {force}: a_board {a_board}, a_block {a_block}, law {a}",
            T::NAME
        );
        if expected == Outcome::Held {
            assert!(run.max_vx < rest_speed::<T>(), "{} F = {force}: held at {} m/s", T::NAME, run.max_vx);
        }
    }
    // Above the riding force the board comes out and the block stays: pulling harder moves it less.
    let stop = |v: f64| v.max(0.0).powi(2) / (2.0 * d.mu_floor * g);
    let mut previous = f64::INFINITY;
    for factor in [1.03, 1.5, 3.0, 6.0, 12.0] {
        let force = factor * riding;
        let (run, displacement) = tablecloth::<T>(TableclothParams { force, ..d });
        assert_eq!(run.outcome, Outcome::Stayed, "{} {factor} of the riding force: {run:?}", T::NAME);
        let [a_board, a_block] = run.accelerations.expect("full contact");
        let want_board = (force - d.mu_kinetic * m * g - d.mu_floor * (m + mb) * g) / mb;
        let want_block = d.mu_kinetic * g;
        let relative = if T::BYTES == 8 { 1e-9 } else { 1e-3 };
        assert!(
            (a_board - want_board).abs() < relative * want_board
                && (a_block - want_block).abs() < relative * want_block,
            "{} {factor}: a_board {a_board} (law {want_board}), a_block {a_block} (law {want_block})",
            T::NAME
        );
        let a_rel = want_board - want_block;
        let x = |s: f64| want_block * s / a_rel;
        let v = |s: f64| want_block * (2.0 * s / a_rel).sqrt();
        let (near, far) = (d.offset, d.offset + d.block_width);
        let low = x(near) + stop(v(near) - d.mu_floor * (2.0 * g * d.board_thickness).sqrt());
        let high = x(far) + v(far) * (2.0 * d.board_thickness / g).sqrt() + stop(v(far));
        assert!(
            low <= displacement && displacement <= high && displacement < previous,
            "{} {factor}: displacement {displacement} outside [{low}, {high}] or not below {previous}",
            T::NAME
        );
        previous = displacement;
    }
}

#[test]
fn tablecloth_follows_its_laws_in_f64() {
    tablecloth_laws::<f64>();
}

#[test]
fn tablecloth_follows_its_laws_in_f32() {
    tablecloth_laws::<f32>();
}

fn stack_laws<T: Real>() {
    let d = StackParams::<f64> { max_time: 1.0, ..StackParams::default() };
    for (overhang, expected) in
        [(0.9, Outcome::Held), (0.98, Outcome::Held), (1.02, Outcome::Fell), (1.1, Outcome::Fell)]
    {
        let p = StackParams { overhang, ..d };
        let two = stack::<T, 2, 24>(p);
        let three = stack::<T, 3, 32>(p);
        for (blocks, (outcome, max_speed, _, _)) in [(2, two), (3, three)] {
            assert_eq!(outcome, expected, "{} {blocks} blocks at overhang {overhang}", T::NAME);
            if expected == Outcome::Held {
                assert!(
                    max_speed < rest_speed::<T>(),
                    "{} {blocks} blocks at {overhang}: {max_speed} m/s",
                    T::NAME
                );
            }
        }
    }
}

/// Three aligned blocks (`s = 0`, each on both lower corners: every interface statically
/// indeterminate): held at rest, each interface carrying the weight above it.
fn aligned_stack_rests<T: Real>() {
    let d = StackParams::<f64> { overhang: 0.0, max_time: 1.0, ..StackParams::default() };
    let (outcome, max_speed, forces, _) = stack::<T, 3, 32>(d);
    assert_eq!(outcome, Outcome::Held);
    assert!(max_speed < rest_speed::<T>(), "{}: {max_speed} m/s", T::NAME);
    let weight = d.mass * d.gravity;
    let tol = if T::BYTES == 8 { 1e-9 } else { 1e-3 };
    for (i, f) in forces.iter().enumerate() {
        let carried = (3 - i) as f64 * weight;
        assert!(f[0].abs() < tol && (f[1] - carried).abs() < tol * carried, "{} pair {i}: {f:?}", T::NAME);
    }
}

#[test]
fn aligned_stack_rests_on_indeterminate_interfaces() {
    aligned_stack_rests::<f64>();
    aligned_stack_rests::<f32>();
}

#[test]
fn stack_holds_below_the_harmonic_overhang_and_falls_above_it_in_f64() {
    stack_laws::<f64>();
}

#[test]
fn stack_holds_below_the_harmonic_overhang_and_falls_above_it_in_f32() {
    stack_laws::<f32>();
}

/// The default 3-block stack over 10 s (10,000 steps): held, its largest speed at round-off, the
/// table carrying `3 m g` and each interface `i` the `(3 - i) m g` above it (the last step's
/// summed interface forces). Returns the run.
fn stack_rests<T: Real>() -> (Outcome, f64, Vec<[f64; 2]>, Vec<[f64; 3]>) {
    let d = StackParams::<f64>::default();
    let run = stack::<T, 3, 32>(d);
    let (outcome, max_speed, ref forces, _) = run;
    assert_eq!(outcome, Outcome::Held);
    assert!(max_speed < rest_speed::<T>(), "{}: max speed {max_speed} m/s", T::NAME);
    let weight = d.mass * d.gravity;
    let tol = if T::BYTES == 8 { 1e-9 } else { 1e-3 };
    for (i, f) in forces.iter().enumerate() {
        let carried = (3 - i) as f64 * weight;
        assert!(
            f[0].abs() < tol && (f[1] - carried).abs() < tol * carried,
            "{} pair {i}: {f:?}, want {carried}",
            T::NAME
        );
    }
    println!("3-block stack at overhang 0.98, 10 s, {}: max speed {max_speed:e} m/s", T::NAME);
    run
}

#[test]
fn three_block_stack_rests_for_ten_seconds_in_f32() {
    stack_rests::<f32>();
}

/// Positions of the core in f64 within this of the reference's (m, rad) on the default runs
/// (measured: block-on-block 1.5e-13, tablecloth 7.1e-13, stack 5.3e-16).
const REFERENCE_TOLERANCE: f64 = 1e-9;

fn assert_positions_near(scene: &str, core: &[[f64; 3]], reference: &[[f64; 3]], tol: f64) {
    assert_eq!(core.len(), reference.len());
    for (c, r) in core.iter().zip(reference) {
        for k in 0..3 {
            assert!((c[k] - r[k]).abs() < tol, "{scene}: core {c:?}, reference {r:?} (tolerance {tol})");
        }
    }
}

fn reference_run(spec: reference::Spec) -> reference::Run {
    reference::run(&spec, meterstick_reference::Sample::None).expect("the reference's defaults are valid")
}

#[test]
fn block_on_block_matches_the_reference() {
    let r = reference_run(reference::Spec::BlockOnBlock(reference::BlockOnBlock::default()));
    let core = block_on_block::<f64>(BlockOnBlockParams::default());
    assert_eq!(r.outcome, reference::Outcome::Slid);
    assert_eq!(core.outcome, Outcome::Slid);
    assert_eq!(u64::from(core.steps), r.steps);
    assert_positions_near("block-on-block", &core.q, &r.q, REFERENCE_TOLERANCE);
    let [a_bottom, a_top] = core.accelerations.expect("measured");
    let (ra_bottom, ra_top) =
        (r.lower_acceleration.expect("measured"), r.upper_acceleration.expect("measured"));
    assert!((a_bottom - ra_bottom).abs() < 1e-9 && (a_top - ra_top).abs() < 1e-9);
    // f32 against the reference: the same outcome, positions within 1e-5 m (measured 1.1e-6).
    let f32_run = block_on_block::<f32>(BlockOnBlockParams::default());
    assert_eq!(f32_run.outcome, Outcome::Slid);
    assert_positions_near("block-on-block f32", &f32_run.q, &r.q, 1e-5);
}

#[test]
fn tablecloth_matches_the_reference() {
    let r = reference_run(reference::Spec::Tablecloth(reference::Tablecloth::default()));
    let (core, displacement) = tablecloth::<f64>(TableclothParams::default());
    assert_eq!(r.outcome, reference::Outcome::Stayed);
    assert_eq!(core.outcome, Outcome::Stayed);
    assert_eq!(u64::from(core.steps), r.steps);
    assert_positions_near("tablecloth", &core.q, &r.q, REFERENCE_TOLERANCE);
    assert!((displacement - r.block_displacement.expect("measured")).abs() < REFERENCE_TOLERANCE);
    let (f32_run, f32_displacement) = tablecloth::<f32>(TableclothParams::default());
    assert_eq!(f32_run.outcome, Outcome::Stayed);
    // Measured 3.3e-6 m apart.
    assert!(
        (f32_displacement - displacement).abs() < 3e-5,
        "f32 displacement {f32_displacement}, f64 {displacement}"
    );
}

/// The default stack (10 s) in f64: the laws of [`stack_rests`], and the reference's positions,
/// largest speed and interface forces.
#[test]
fn three_block_stack_rests_for_ten_seconds_in_f64_as_the_reference() {
    let r = reference_run(reference::Spec::Stack(reference::Stack::default()));
    let (_, max_speed, forces, q) = stack_rests::<f64>();
    assert_eq!(r.outcome, reference::Outcome::Held);
    assert_positions_near("stack", &q, &r.q, REFERENCE_TOLERANCE);
    assert!(max_speed < 1e-12 && r.max_speed < 1e-12);
    for (c, f) in forces.iter().zip(&r.interface_forces) {
        assert!(
            (c[0] - f[0]).abs() < 1e-9 && (c[1] - f[1]).abs() < 1e-9,
            "interface force {c:?}, reference {f:?}"
        );
    }
    // The aliases are the generic type at its capacities.
    let _: fn(StackParams<f64>) -> Result<Stack2<f64>, _> = Stack::<f64, 2, 24>::new;
    let _: fn(StackParams<f64>) -> Result<Stack3<f64>, _> = Stack::<f64, 3, 32>::new;
}

#[test]
fn invalid_parameters_are_refused_by_name() {
    let d = BlockOnBlockParams::<f64>::default();
    assert_eq!(
        BlockOnBlock::new(BlockOnBlockParams { top_width: 0.5, ..d }).err(),
        Some(ParamError::OutOfRange("top_width"))
    );
    assert_eq!(
        BlockOnBlock::new(BlockOnBlockParams { mu_kinetic: 0.6, ..d }).err(),
        Some(ParamError::KineticAboveStatic)
    );
    assert_eq!(
        BlockOnBlock::new(BlockOnBlockParams { force: f64::NAN, ..d }).err(),
        Some(ParamError::NonFinite("force"))
    );
    let t = TableclothParams::<f64>::default();
    assert_eq!(
        Tablecloth::new(TableclothParams { offset: 0.99, ..t }).err(),
        Some(ParamError::OutOfRange("offset"))
    );
    assert_eq!(
        Tablecloth::new(TableclothParams { contact_margin: 0.005, ..t }).err(),
        Some(ParamError::OutOfRange("contact_margin"))
    );
    let s = StackParams::<f64>::default();
    assert_eq!(
        Stack3::new(StackParams { overhang: 6.0, ..s }).err(),
        Some(ParamError::OutOfRange("overhang"))
    );
    assert_eq!(Stack3::new(StackParams { step: 20.0, ..s }).err(), Some(ParamError::OutOfRange("step")));
}

/// The hand-built systems' step: 1 ms, `g` 9.81 m/s^2, stick below 1e-5 m/s, a 1 mm margin.
const SETTINGS: SystemSettings<f64> = SystemSettings {
    base: meterstick_core::planar::Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 },
    margin: 1e-3,
};

/// Two equal boxes of 1 kg, one exactly on the other, on a floor; `force` pulls the lower one.
fn aligned_pair<const N: usize>(force: f64) -> SystemStepper<f64, 2, 2, N> {
    aligned_pair_of(1.0, force).expect("a valid system")
}

/// [`aligned_pair`] with boxes of `mass`.
fn aligned_pair_of<const N: usize>(mass: f64, force: f64) -> Result<SystemStepper<f64, 2, 2, N>, ParamError> {
    let block = Body::block(mass, 0.2, 0.1);
    let system = System {
        bodies: [block; 2],
        table: Table::floor(),
        pairs: [Pair::boxed(0, RestsOn::Table, 0.5, 0.5), Pair::boxed(1, RestsOn::Body(0), 0.5, 0.5)],
        forces: [[force, 0.0], [0.0; 2]],
        settings: SETTINGS,
    };
    SystemStepper::new(system, [BodyState::at_rest(0.0, 0.05, 0.0), BodyState::at_rest(0.0, 0.15, 0.0)])
}

/// The activity rule (`docs/formulation.md`, "The corner-on-face contact"): the upper box's
/// corners over the lower one's top face count with its ends included, the lower box's corners
/// under the upper one's lower face only strictly inside it, so aligned edges make one contact
/// each, the upper box's; a table end is a corner only where the table has one.
#[test]
fn aligned_edges_make_one_contact_each() {
    let stepper = aligned_pair::<32>(0.0);
    let active = |p: usize| stepper.frames()[p].map(|f| f.active);
    assert_eq!(active(0), [true, true, false, false], "an endless floor has no corners");
    assert_eq!(active(1), [true, true, false, false], "aligned edges: the upper box's corners only");
    assert!(stepper.modes().iter().flatten().filter(|m| **m == ContactMode::Sticking).count() == 4);
    // A table ending under the box's middle: its corner is under the lower face, the right corner
    // is past the end.
    let block = Body::block(1.0, 0.2, 0.1);
    let system = System {
        bodies: [block],
        table: Table { lo: None, hi: Some(0.05) },
        pairs: [Pair::boxed(0, RestsOn::Table, 0.5, 0.5)],
        forces: [[0.0; 2]],
        settings: SETTINGS,
    };
    let edge =
        SystemStepper::<f64, 1, 1, 8>::new(system, [BodyState::at_rest(0.0, 0.05, 0.0)]).expect("valid");
    assert_eq!(edge.frames()[0].map(|f| f.active), [true, false, false, true]);
}

/// Failure is a typed error and leaves the state as it was: more active contacts than the LCP
/// holds; a force whose velocity change `h F / m` overflows. A non-finite force is refused before
/// any step.
#[test]
fn a_failed_step_is_a_typed_error() {
    let mut small = aligned_pair::<12>(0.0);
    let before = *small.states();
    assert_eq!(small.step().err(), Some(StepError::TooManyContacts(4)));
    assert_eq!(*small.states(), before);
    assert_eq!(aligned_pair_of::<16>(1.0, f64::NAN).err(), Some(ParamError::NonFinite("forces")));
    let mut broken = aligned_pair_of::<16>(1e-6, f64::MAX).expect("finite");
    assert_eq!(broken.step().err(), Some(StepError::Solver(LcpError::NonFiniteInput)));
    assert_eq!(*broken.states(), before);
    // The same system with room for its four contacts steps, the pull held by the floor.
    let mut ok = aligned_pair::<16>(5.0);
    let report = ok.step().expect("a step");
    assert_eq!(report.active, 4);
    let [fx, fy] = report.interface_forces[0];
    assert!((fx + 5.0).abs() < 1e-9 && (fy - 2.0 * 9.81).abs() < 1e-9, "floor force ({fx}, {fy})");
}

/// The stack's two friction coefficients: a stack of three beyond its harmonic overhangs
/// (`s = 1.1`, `mu_s = 0.3`) falling past the default tilt and drop limits, its corners sliding,
/// with `mu_k = mu_s` and with `mu_k = mu_s / 3`: the core (f64) steps as the independent reference
/// does in both (same steps, positions within 1e-9 m), and the kinetic coefficient changes the
/// fall (the run ends on another step).
#[test]
fn stack_slides_with_its_kinetic_coefficient_as_the_reference() {
    let d = StackParams::<f64> {
        overhang: 1.1,
        mu_static: 0.3,
        tilt_limit: 1.2,
        drop_limit: 0.2,
        max_time: 1.0,
        ..StackParams::default()
    };
    let mut steps = Vec::new();
    for mu_kinetic in [0.3, 0.1] {
        let p = StackParams { mu_kinetic, ..d };
        let mut scene = Stack3::<f64>::new(p).expect("valid parameters");
        let outcome = scene.run(|_| {});
        let r = reference_run(reference::Spec::Stack(reference::Stack {
            overhang: p.overhang,
            mu_static: p.mu_static,
            mu_kinetic,
            tilt_limit: p.tilt_limit,
            drop_limit: p.drop_limit,
            max_time: p.max_time,
            ..reference::Stack::default()
        }));
        assert_eq!((outcome, r.outcome), (Outcome::Fell, reference::Outcome::Fell), "mu_k {mu_kinetic}");
        assert_eq!(u64::from(scene.stepper().stats().steps), r.steps, "mu_k {mu_kinetic}");
        assert_positions_near("stack", &positions(scene.stepper().states()), &r.q, REFERENCE_TOLERANCE);
        steps.push(r.steps);
    }
    assert_ne!(steps[0], steps[1], "mu_k changes the fall");
}

/// The core's run of the tablecloth at `mu = 2` beside the reference's `r`: its ambiguous steps and
/// the largest position (m) and angle (rad) deviation over the steps.
fn open_tablecloth<T: Real>(r: &reference::Run) -> (u64, f64, f64) {
    let p = TableclothParams::<f64> { mu_static: 2.0, mu_kinetic: 2.0, ..TableclothParams::default() };
    let mut scene = Tablecloth::new(p.cast::<T>()).expect("valid parameters");
    let (mut position, mut angle) = (0.0_f64, 0.0_f64);
    let mut n = 0;
    while let Some(report) = scene.step() {
        n += 1;
        let row = &r.rows[n];
        for (s, q) in report.states.iter().zip(&row.q) {
            position = position.max((s.x.as_f64() - q[0]).hypot(s.y.as_f64() - q[1]));
            angle = angle.max((s.theta.as_f64() - q[2]).abs());
        }
    }
    assert_eq!(n as u64, r.steps);
    let stats = scene.stepper().stats();
    assert!(stats.rule_enumerated_steps >= stats.ambiguous_steps && stats.rule_checked_steps > 0);
    (stats.ambiguous_steps, position, angle)
}

/// The tablecloth at `mu_s = mu_k = 2`: the block tips about its corner on the board, and on 4
/// steps (43 to 46) its LCP has solutions that move the bodies differently (the corner sticks,
/// slides or lifts): the reference counts them, the core's rule finds the same steps among those
/// it flags, and both take the least kinetic energy: the core in f64 on the reference's path
/// within 1e-9 m and rad on every step (measured 2.4e-14 m), in f32 within 1e-5 m and 1e-3 rad
/// (measured 6.5e-6 m, 2.0e-4 rad: a block turning at 20 rad/s).
#[test]
fn where_the_tablecloths_motion_is_open_the_core_takes_the_references_answer() {
    let spec = reference::Tablecloth { mu_static: 2.0, mu_kinetic: 2.0, ..reference::Tablecloth::default() };
    let r = reference::run(&reference::Spec::Tablecloth(spec), meterstick_reference::Sample::All)
        .expect("valid parameters");
    assert_eq!(r.ambiguous_steps, 4);
    let (ambiguous, position, angle) = open_tablecloth::<f64>(&r);
    assert_eq!(ambiguous, r.ambiguous_steps);
    assert!(position < REFERENCE_TOLERANCE && angle < REFERENCE_TOLERANCE, "{position:e} m, {angle:e} rad");
    let (ambiguous, position, angle) = open_tablecloth::<f32>(&r);
    assert_eq!(ambiguous, r.ambiguous_steps);
    assert!(position < 1e-5 && angle < 1e-3, "f32: {position:e} m, {angle:e} rad");
}

/// The rule's detection costs the determinate steps one test: the default block-on-block (always
/// sliding) and stack (always at rest) have no step it flags, in f32 and f64.
#[test]
fn the_default_block_on_block_and_stack_flag_no_step() {
    fn flagged<T: Real>() -> [u64; 2] {
        let mut block = BlockOnBlock::new(BlockOnBlockParams::<f64>::default().cast::<T>()).expect("valid");
        let _ = block.run(|_| ());
        let mut stack = Stack3::<T>::new(StackParams::<f64>::default().cast::<T>()).expect("valid");
        let _ = stack.run(|_| ());
        [block.stepper().stats().rule_checked_steps, stack.stepper().stats().rule_checked_steps]
    }
    assert_eq!(flagged::<f64>(), [0, 0]);
    assert_eq!(flagged::<f32>(), [0, 0]);
}

/// A stack beyond its overhang tips over one edge corner per interface on its first step: the
/// candidate that lifts the corners whose normal impulse comes out negative, one after another,
/// answers it in at most one solve per interface (without it the step went through 63 candidate
/// solves and Lemke's method), in f32 and f64, the run falling as the reference's does.
#[test]
fn a_tipping_stack_lifts_its_inner_corners_in_one_candidate_chain() {
    fn first_step<T: Real>() -> (PathCounts, Outcome) {
        let p = StackParams::<f64> { overhang: 1.02, ..StackParams::default() };
        let mut stack = Stack3::<T>::new(p.cast::<T>()).expect("valid");
        let _ = stack.step();
        let paths = stack.stepper().stats().paths;
        (paths, stack.run(|_| ()))
    }
    for (paths, outcome) in [first_step::<f32>(), first_step::<f64>()] {
        assert_eq!(outcome, Outcome::Fell);
        assert_eq!((paths.candidate, paths.lemke), (1, 0), "{paths:?}");
        assert!(paths.candidates_tried <= 3, "{paths:?}");
    }
}

/// Block-on-block with masses 1000:1 apart both ways and the tablecloth with a 1 g block on a 1 kg
/// board, each below, between and above its thresholds: the laws' outcomes, and held runs still
/// (largest `|vx|` at round-off). In f32 the held block-on-block runs need each velocity row held
/// to its own round-off: a floor scaled by the light body's diagonal times the heavy body's
/// impulses passes a basis whose slip (2.2e-5 m/s) is no round-off, and the run reads `Rode`
/// (`docs/formulation.md`, "Solving a multibody step (the core)").
fn mass_ratios<T: Real>() {
    let d = BlockOnBlockParams::<f64> { max_time: 0.2, ..BlockOnBlockParams::default() };
    for (top_mass, bottom_mass) in [(1.0, 1000.0), (1000.0, 1.0)] {
        let p = BlockOnBlockParams { top_mass, bottom_mass, ..d };
        let total = (top_mass + bottom_mass) * p.gravity;
        let (held, sliding) = (p.mu_floor * total, (p.mu_static + p.mu_floor) * total);
        for (force, expected) in [
            (0.5 * held, Outcome::Held),
            (0.5 * (held + sliding), Outcome::Rode),
            (1.5 * sliding, Outcome::Slid),
        ] {
            let run = block_on_block::<T>(BlockOnBlockParams { force, ..p });
            let case = format!("{} m:M = {top_mass}:{bottom_mass}, F = {force}", T::NAME);
            assert_eq!(run.outcome, expected, "{case}: {run:?}");
            if expected == Outcome::Held {
                assert!(run.max_vx < rest_speed::<T>(), "{case}: held at {} m/s", run.max_vx);
            }
        }
    }
    let d = TableclothParams::<f64> { block_mass: 1e-3, board_mass: 1.0, ..TableclothParams::default() };
    let riding = (d.mu_static + d.mu_floor) * (d.block_mass + d.board_mass) * d.gravity;
    let (run, _) = tablecloth::<T>(TableclothParams { force: 0.5 * riding, ..d });
    assert_eq!(run.outcome, Outcome::Rode, "{} tablecloth 0.001:1: {run:?}", T::NAME);
}

#[test]
fn mass_ratios_of_a_thousand_follow_the_laws_in_f32() {
    mass_ratios::<f32>();
}

#[test]
fn mass_ratios_of_a_thousand_follow_the_laws_in_f64() {
    mass_ratios::<f64>();
}

/// The stack's energy `sum m (vx^2 + vy^2) / 2 + J omega^2 / 2 + m g y` (J), in f64.
fn stack_energy<T: Real>(p: &StackParams<f64>, states: &[BodyState<T>]) -> f64 {
    let inertia = p.mass * (p.length * p.length + p.height * p.height) / 12.0;
    states
        .iter()
        .map(|s| {
            let [y, vx, vy, omega] = [s.y, s.vx, s.vy, s.omega].map(Real::as_f64);
            0.5 * p.mass * (vx * vx + vy * vy) + 0.5 * inertia * omega * omega + p.mass * p.gravity * y
        })
        .sum()
}

/// Friction of 1e3 and 1e4 in f32 (the cone rows weighted, `docs/formulation.md`, "Extreme
/// friction: the cone rows weighted"): block-on-block held by `mu_floor = 1e4` stays still; the
/// 3-block stack beyond the harmonic overhang (s = 1.02) falls on the reference's step (200) with
/// positions within 1e-5 m of it (measured 1.4e-6), and its energy never rises above the start's
/// by more than 1e-5 J (no pull does work on it: the implicit step only loses energy; measured: it
/// never rises). With the cone rows unweighted, f32 at 1e3 gains 4.5e-2 J and falls 2 steps early,
/// at 1e4 gains up to 3e-5 J in a step and falls 3 steps early.
#[test]
fn extreme_friction_in_f32() {
    let held = block_on_block::<f32>(BlockOnBlockParams { mu_floor: 1e4, ..BlockOnBlockParams::default() });
    assert_eq!(held.outcome, Outcome::Held, "{held:?}");
    assert!(held.max_vx < rest_speed::<f32>(), "held at {} m/s", held.max_vx);
    for mu in [1e3, 1e4] {
        let p = StackParams::<f64> {
            mu_static: mu,
            mu_kinetic: mu,
            overhang: 1.02,
            max_time: 1.0,
            ..StackParams::default()
        };
        let mut scene = Stack3::<f32>::new(p.cast()).expect("valid parameters");
        let start = stack_energy(&p, scene.stepper().states());
        let mut gain = f64::NEG_INFINITY;
        let outcome = scene.run(|r| gain = gain.max(stack_energy(&p, &r.states) - start));
        let r = reference_run(reference::Spec::Stack(reference::Stack {
            mu_static: mu,
            mu_kinetic: mu,
            overhang: p.overhang,
            max_time: p.max_time,
            ..reference::Stack::default()
        }));
        assert_eq!((outcome, r.outcome), (Outcome::Fell, reference::Outcome::Fell), "mu {mu}");
        assert_eq!(u64::from(scene.stepper().stats().steps), r.steps, "mu {mu}");
        assert_positions_near("stack f32", &positions(scene.stepper().states()), &r.q, 1e-5);
        assert!(gain <= 1e-5, "mu {mu}: energy rose {gain} J above the start's");
    }
}

/// The frictionless 3-block stack beyond the harmonic overhang in f64 falls as the reference does
/// (the same step, 207: 0.207 s; positions within 1e-9 m, measured 1.2e-13), with no Lemke ray
/// on its violent first steps.
#[test]
fn frictionless_stack_falls_as_the_reference_in_f64() {
    let p = StackParams::<f64> {
        mu_static: 0.0,
        mu_kinetic: 0.0,
        overhang: 1.02,
        max_time: 1.0,
        ..StackParams::default()
    };
    let mut scene = Stack3::<f64>::new(p).expect("valid parameters");
    let outcome = scene.run(|_| {});
    let r = reference_run(reference::Spec::Stack(reference::Stack {
        mu_static: 0.0,
        mu_kinetic: 0.0,
        overhang: p.overhang,
        max_time: p.max_time,
        ..reference::Stack::default()
    }));
    assert_eq!((outcome, r.outcome), (Outcome::Fell, reference::Outcome::Fell));
    assert_eq!(u64::from(scene.stepper().stats().steps), r.steps);
    assert_positions_near("stack", &positions(scene.stepper().states()), &r.q, REFERENCE_TOLERANCE);
}

/// What [`disc_on_board`] measured, in f64.
#[derive(Debug)]
struct DiscRun {
    outcome: Outcome,
    /// The scene's `[a_board, a_disc]` (m/s^2).
    accelerations: Option<[f64; 2]>,
    /// The largest `|v_c + omega r - V_board|` over the run (the rim's slip on the board, m/s).
    max_slip: f64,
    /// The largest `|vx| + |vy| + r |omega|` of the two bodies over the run (m/s).
    max_speed: f64,
    /// The disc's contact was active on every step.
    on_board: bool,
    /// Each step's `(x, y, theta)` of the board and the disc.
    q: Vec<[[f64; 3]; 2]>,
    /// The end time (s).
    end_time: f64,
}

/// The disc-on-board scene (`docs/scenes.md`, "disc-on-board": a disc whose rim rests on a board
/// pulled along a floor, `docs/formulation.md`, "The rim-on-face contact") with `p` in `T`.
fn disc_on_board<T: Real>(p: DiscOnBoardParams<f64>) -> DiscRun {
    let mut scene = DiscOnBoard::new(p.cast::<T>()).expect("valid parameters");
    let r = p.disc_radius;
    let (mut max_slip, mut max_speed, mut on_board, mut q) = (0.0f64, 0.0f64, true, Vec::new());
    let outcome = scene.run(|report| {
        let [board, disc] = report.states.map(|s| s.to_array().map(Real::as_f64));
        max_slip = max_slip.max((disc[3] + disc[5] * r - board[3]).abs());
        for v in [board, disc] {
            max_speed = max_speed.max(v[3].abs() + v[4].abs() + r * v[5].abs());
        }
        q.push([[board[0], board[1], board[2]], [disc[0], disc[1], disc[2]]]);
        on_board &= report.touching(&[(1, 0)]);
    });
    DiscRun {
        outcome,
        accelerations: scene.accelerations().map(|a| a.map(Real::as_f64)),
        max_slip,
        max_speed,
        on_board,
        q,
        end_time: scene.stepper().time().as_f64(),
    }
}

/// The law of `docs/scenes.md` ("disc-on-board") for `p`, written out here: the outcome and
/// `[A, a_c]`. Nothing moves while `F <= mu_floor (M + m) g`; the disc rolls while
/// `A = (F - mu_floor (M + m) g) / (M + m / 3) <= 3 mu_s g`, its centre at `A / 3`; beyond it
/// slides, `a_c = mu_k g`, `A = (F - mu_k m g - mu_floor (M + m) g) / M`.
fn disc_law(p: &DiscOnBoardParams<f64>) -> (Outcome, [f64; 2]) {
    let (big_m, m, g) = (p.board_mass, p.disc_mass, p.gravity);
    let floor = p.mu_floor * (big_m + m) * g;
    let rolling = (p.force - floor) / (big_m + m / 3.0);
    if p.force <= floor {
        (Outcome::Held, [0.0; 2])
    } else if rolling <= 3.0 * p.mu_static * g {
        (Outcome::Rolled, [rolling, rolling / 3.0])
    } else {
        (Outcome::Slid, [(p.force - p.mu_kinetic * m * g - floor) / big_m, p.mu_kinetic * g])
    }
}

fn disc_laws<T: Real>() {
    let d = DiscOnBoardParams::<f64>::default();
    let (big_m, m, g) = (d.board_mass, d.disc_mass, d.gravity);
    let held = d.mu_floor * (big_m + m) * g;
    let rolls = 3.0 * d.mu_static * g * (big_m + m / 3.0) + held;
    // Relative to the larger of A and g: f64 measured 3.3e-15, f32 8.1e-7.
    let tol = if T::BYTES == 8 { 1e-12 } else { 1e-5 };
    let mut worst = 0.0f64;
    // The sliding runs are cut short before the disc slides back over the board's rear end.
    for (force, max_time, expected) in [
        (0.5 * held, 0.3, Outcome::Held),
        (0.98 * held, 0.3, Outcome::Held),
        (1.02 * held, 0.3, Outcome::Rolled),
        (d.force, 0.3, Outcome::Rolled),
        (0.98 * rolls, 0.3, Outcome::Rolled),
        (1.02 * rolls, 0.2, Outcome::Slid),
        (100.0, 0.12, Outcome::Slid),
    ] {
        let p = DiscOnBoardParams { force, max_time, ..d };
        let (law, a) = disc_law(&p);
        assert_eq!(law, expected, "the law at F = {force}");
        let run = disc_on_board::<T>(p);
        assert_eq!(run.outcome, expected, "{} F = {force}: {run:?}", T::NAME);
        assert!(run.on_board, "{} F = {force}", T::NAME);
        let got = run.accelerations.expect("measured");
        let scale = a[0].max(g);
        worst = worst.max((got[0] - a[0]).abs().max((got[1] - a[1]).abs()) / scale);
        assert!(
            (got[0] - a[0]).abs() < tol * scale && (got[1] - a[1]).abs() < tol * scale,
            "{} F = {force}: {got:?} vs the law's {a:?}",
            T::NAME
        );
        match expected {
            Outcome::Rolled => {
                assert!(run.max_slip < rest_speed::<T>(), "{} F = {force}: the rim slipped", T::NAME);
            }
            Outcome::Slid => assert!(run.max_slip > 1e-3, "{} F = {force}: sliding, yet rolling", T::NAME),
            _ => assert!(run.max_speed < rest_speed::<T>(), "{} F = {force}: held, yet moved", T::NAME),
        }
    }
    eprintln!("disc-on-board {}: accelerations within {worst:e} of the law, relative", T::NAME);
    // The rim's point past an end of the board ends the run: sliding back at 100 N, or rolling
    // back from 5 cm before the rear end.
    for p in [DiscOnBoardParams { force: 100.0, ..d }, DiscOnBoardParams { offset: -0.45, ..d }] {
        let run = disc_on_board::<T>(p);
        let [board, disc] = *run.q.last().expect("steps");
        assert_eq!(run.outcome, Outcome::Unfinished, "{} {p:?}", T::NAME);
        assert!(run.end_time < 0.2 && disc[0] - board[0] < -0.5, "{} {run:?}", T::NAME);
    }
}

/// The disc on a pulled board against its law (`docs/scenes.md`, "disc-on-board"), through the
/// scene, on each side of both thresholds: held, rolling (the disc's centre at a third of the
/// board's acceleration, the rim's slip at round-off), sliding at `mu_k g`, and ended when the rim
/// passes an end of the board.
#[test]
fn a_disc_rolls_on_a_pulled_board_at_a_third_of_its_acceleration_in_f64() {
    disc_laws::<f64>();
}

#[test]
fn a_disc_rolls_on_a_pulled_board_at_a_third_of_its_acceleration_in_f32() {
    disc_laws::<f32>();
}

/// A disc has no faces: a pair resting on one is refused; so are a disc whose width and height (its
/// diameter) differ and a body two pairs give two shapes; named by the field.
#[test]
fn a_disc_is_only_an_upper_body() {
    let (disc, block) = (Body::disc(1.0, 0.05), Body::block(1.0, 0.1, 0.1));
    let pair = |upper: u8, lower: RestsOn, upper_shape: Shape| Pair {
        upper,
        lower,
        mu_static: 0.5,
        mu_kinetic: 0.5,
        upper_shape,
    };
    let states = [BodyState::at_rest(0.0, 0.05, 0.0), BodyState::at_rest(0.0, 0.15, 0.0)];
    let build = |bodies: [Body<f64>; 2], pairs: [Pair<f64>; 2]| {
        let system =
            System { bodies, table: Table::floor(), pairs, forces: [[0.0; 2]; 2], settings: SETTINGS };
        SystemStepper::<f64, 2, 2, 16>::new(system, states).err()
    };
    // The disc on a block on the floor: valid.
    let valid = [pair(0, RestsOn::Table, Shape::Box), pair(1, RestsOn::Body(0), Shape::Disc)];
    assert_eq!(build([block, disc], valid), None);
    // A block on a disc.
    let on_disc = [pair(0, RestsOn::Table, Shape::Disc), pair(1, RestsOn::Body(0), Shape::Box)];
    assert_eq!(build([disc, block], on_disc), Some(ParamError::OutOfRange("pairs")));
    // A disc 0.2 m wide and 0.1 m high.
    assert_eq!(
        build([block, Body { width: 0.2, ..disc }], valid),
        Some(ParamError::OutOfRange("upper_shape"))
    );
    // Body 1 a disc on body 0 and a box on the table.
    let both = [pair(1, RestsOn::Table, Shape::Box), pair(1, RestsOn::Body(0), Shape::Disc)];
    assert_eq!(build([block, disc], both), Some(ParamError::OutOfRange("upper_shape")));
}

/// The disc-on-board scene against the independent reference (`meterstick_reference::multibody`,
/// `DiscOnBoard`, written from the same text, sharing no code): rolling slowly (3 N) and at the
/// defaults (20 N), sliding just beyond the rolling limit (38.02 N), the same outcome, the same
/// accelerations and every step's positions of both bodies close (f64 to round-off, f32 to its
/// precision over 300 steps; measured f64 2.6e-14 m and 1.9e-13 m/s^2, f32 7.7e-6 m and 3.0e-5
/// m/s^2).
#[test]
fn a_disc_on_a_board_steps_as_the_reference() {
    for (force, steps) in [(3.0, 300), (20.0, 300), (38.02, 200)] {
        let max_time = f64::from(steps) * 1e-3;
        let spec = reference::DiscOnBoard { force, max_time, ..reference::DiscOnBoard::default() };
        let r = reference::run(&reference::Spec::DiscOnBoard(spec), meterstick_reference::Sample::All)
            .expect("valid parameters");
        let p = DiscOnBoardParams { force, max_time, ..DiscOnBoardParams::default() };
        let rolled = r.outcome == reference::Outcome::Rolled;
        assert!(rolled || r.outcome == reference::Outcome::Slid, "{force} N: {:?}", r.outcome);
        let expected = if rolled { Outcome::Rolled } else { Outcome::Slid };
        let ra = [r.lower_acceleration.expect("measured"), r.upper_acceleration.expect("measured")];
        for (precision, run, tol, a_tol) in [
            ("f64", disc_on_board::<f64> as fn(DiscOnBoardParams<f64>) -> DiscRun, 1e-12, 1e-11),
            ("f32", disc_on_board::<f32>, 2e-5, 1e-4),
        ] {
            let core = run(p);
            assert_eq!(core.outcome, expected, "{precision} {force} N");
            assert_eq!(core.q.len() + 1, r.rows.len(), "{precision} {force} N: steps");
            let mut worst = 0.0f64;
            for (c, row) in core.q.iter().zip(&r.rows[1..]) {
                for (body, reference) in c.iter().zip(&row.q) {
                    for (a, b) in body.iter().zip(reference) {
                        worst = worst.max((a - b).abs());
                    }
                }
            }
            assert!(worst < tol, "{precision} {force} N: positions {worst:e} from the reference");
            let a = core.accelerations.expect("measured");
            eprintln!(
                "disc-on-board {precision} {force} N: positions within {worst:e} m, accelerations within {:e} m/s^2 of the reference",
                (a[0] - ra[0]).abs().max((a[1] - ra[1]).abs())
            );
            assert!(
                (a[0] - ra[0]).abs() < a_tol && (a[1] - ra[1]).abs() < a_tol,
                "{precision} {force} N: {a:?} vs the reference's {ra:?}"
            );
        }
    }
}

/// The rim's frame (`docs/formulation.md`, "The rim-on-face contact") on a board tilted by
/// `theta`, the disc placed at `s` along its top face and `psi` above it: the rim's point
/// `P = c - r n_f`, `s`, `psi`, the normal, the levers and the activity rule (over the face with
/// its ends included, within the margin) against their closed form; candidates 2-4 never active.
#[test]
fn a_disc_s_rim_frame_on_a_tilted_board_is_the_text_s() {
    let (length, height, r) = (1.0, 0.02, 0.05);
    for theta in [0.0f64, 0.2, -0.3, 1.0] {
        for (s, psi) in [(0.0, 0.0), (0.3, 5e-4), (-0.49, 0.0), (0.5, 0.0), (0.51, 0.0), (0.1, 2e-3)] {
            let (sin, cos) = theta.sin_cos();
            let (e, n) = ([cos, sin], [-sin, cos]);
            let board = BodyState::at_rest(0.3, 0.2, theta);
            let o = [0.3 + height / 2.0 * n[0], 0.2 + height / 2.0 * n[1]];
            let c = [o[0] + s * e[0] + (psi + r) * n[0], o[1] + s * e[1] + (psi + r) * n[1]];
            let system = System {
                bodies: [Body::block(2.0, length, height), Body::disc(1.0, r)],
                table: Table::floor(),
                pairs: [Pair::boxed(0, RestsOn::Table, 0.5, 0.5), Pair::disc(1, RestsOn::Body(0), 0.5, 0.5)],
                forces: [[0.0; 2]; 2],
                settings: SETTINGS,
            };
            let stepper =
                SystemStepper::<f64, 2, 2, 24>::new(system, [board, BodyState::at_rest(c[0], c[1], 0.7)])
                    .expect("a valid system");
            let f = stepper.frames()[1][0];
            let case = format!("theta {theta}, s {s}, psi {psi}: {f:?}");
            let near = |a: f64, b: f64| (a - b).abs() < 1e-14;
            let point = [c[0] - r * n[0], c[1] - r * n[1]];
            assert!(near(f.along, s) && near(f.gap, psi), "{case}");
            assert_eq!(f.active, s.abs() <= length / 2.0 && psi <= 1e-3, "{case}");
            assert!(stepper.frames()[1][1..].iter().all(|f| !f.active), "{case}");
            if !f.active {
                // An inactive frame's other fields are not this step's (`SystemStepper::frames`).
                continue;
            }
            assert!(near(f.point[0], point[0]) && near(f.point[1], point[1]), "{case}");
            assert!(near(f.normal[0], n[0]) && near(f.normal[1], n[1]), "{case}");
            assert!(near(f.tangent[0], n[1]) && near(f.tangent[1], -n[0]), "{case}");
            assert!(near(f.lever_corner[0], -r * n[0]) && near(f.lever_corner[1], -r * n[1]), "{case}");
            assert!(near(f.lever_face[0], point[0] - 0.3) && near(f.lever_face[1], point[1] - 0.2), "{case}");
            assert_eq!((f.corner, f.face), (Some(1), Some(0)), "{case}");
        }
    }
}

/// A disc with no box under it, its rim on the table, pushed at its centre by `F`: it rolls at
/// `2 F / (3 m)` (friction `F / 3` back, `J alpha = r f`), its rim at rest on the table
/// (`v + omega r = 0`), while `F / 3 <= mu_s m g`; beyond it slides at `(F - mu_k m g) / m`.
#[test]
fn a_disc_pushed_on_the_table_rolls_at_two_thirds_of_f_over_m() {
    let (m, r, g, mu_s, mu_k) = (1.0, 0.05, 9.81, 0.5, 0.4);
    let run = |force: f64| {
        let system = System {
            bodies: [Body::disc(m, r)],
            table: Table::floor(),
            pairs: [Pair::disc(0, RestsOn::Table, mu_s, mu_k)],
            forces: [[force, 0.0]],
            settings: SystemSettings {
                base: meterstick_core::planar::Settings { step: 1e-3, gravity: g, stick_speed: 1e-5 },
                margin: 1e-3,
            },
        };
        let mut stepper = SystemStepper::<f64, 1, 1, 8>::new(system, [BodyState::at_rest(0.0, r, 0.0)])
            .expect("a valid system");
        let (mut v10, mut rim) = (0.0, 0.0f64);
        for n in 1..=200 {
            let st = stepper.step().expect("a step").states[0];
            rim = rim.max((st.vx + st.omega * r).abs());
            if n == 10 {
                v10 = st.vx;
            }
        }
        ((stepper.states()[0].vx - v10) / 0.19, rim)
    };
    let (a, rim) = run(6.0);
    assert!((a - 2.0 * 6.0 / (3.0 * m)).abs() < 1e-9 && rim < 1e-12, "rolling: a {a}, rim speed {rim:e}");
    let (a, rim) = run(20.0);
    assert!((a - (20.0 - mu_k * m * g) / m).abs() < 1e-9 && rim > 0.1, "sliding: a {a}, rim speed {rim:e}");
}
