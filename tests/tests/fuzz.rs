//! Fuzzing the scene's public entry points with raw parameters and initial states, garbage
//! included (NaN, infinities, zero, negative, huge, tiny): every input either runs (each step
//! verified or ending in a typed outcome, the state finite while the run goes on) or is
//! rejected by validation with a `ParamError`. Nothing panics. Cases: `PROPTEST_CASES`
//! (default 256 per test); a failure is shrunk and saved in `proptest-regressions/`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::Real;
use meterstick_core::scene::{Outcome, RodState, Scene, SceneParams};
use proptest::prelude::*;

/// Mostly plausible values, often an edge or garbage.
fn raw(typical: std::ops::Range<f64>) -> impl Strategy<Value = f64> {
    prop_oneof![
        40 => typical,
        1 => Just(0.0),
        1 => Just(-1.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(1e30),
        1 => Just(1e-30),
        1 => -1e3..1e3f64,
    ]
}

fn params() -> impl Strategy<Value = SceneParams<f64>> {
    (
        (raw(0.1..3.0), raw(1e-4..0.1), raw(1e-3..10.0), raw(0.0..20.0), raw(-0.5..0.0), raw(0.0..0.5)),
        (raw(0.0..0.05), raw(0.0..10.0), raw(0.0..2.0), raw(0.0..1.0), raw(1e-5..1e-2), raw(0.0..1e-3)),
    )
        .prop_map(|((l, t, m, g, x1, x2), (w, v, mu_s, mu_k, h, stick))| SceneParams {
            rod_length: l,
            rod_thickness: t,
            rod_mass: m,
            gravity: g,
            finger1_x: x1 * l,
            finger2_x: x2 * l,
            finger_width: w,
            finger_speed: v,
            mu_static: mu_s,
            mu_kinetic: mu_k * mu_s, // typically a fraction of mu_s
            step: h,
            stick_speed: stick,
            max_time: 0.2,
            ..SceneParams::paper()
        })
}

fn state() -> impl Strategy<Value = RodState<f64>> {
    (raw(-0.01..0.01), raw(0.0..0.01), raw(-0.05..0.05), raw(-0.1..0.1), raw(-0.1..0.1), raw(-0.5..0.5))
        .prop_map(|(x, y, theta, vx, vy, omega)| RodState { x, y, theta, vx, vy, omega })
}

fn convert<T: Real>(p: &SceneParams<f64>) -> SceneParams<T> {
    meterstick_host_sim::trajectory::convert(p)
}

/// Runs at most `cap` steps and checks the invariants; returns how the run went.
fn exercise<T: Real, const N: usize>(
    p: &SceneParams<f64>,
    s: Option<&RodState<f64>>,
    cap: usize,
) -> &'static str {
    let pt = convert::<T>(p);
    let made = match s {
        None => Scene::<T, N, 16>::new(pt),
        Some(s) => Scene::<T, N, 16>::with_state(
            pt,
            RodState {
                x: T::of(s.x),
                y: T::of(s.y + p.rod_thickness / 2.0),
                theta: T::of(s.theta),
                vx: T::of(s.vx),
                vy: T::of(s.vy),
                omega: T::of(s.omega),
            },
        ),
    };
    let mut scene = match made {
        Ok(scene) => scene,
        Err(e) => {
            // Validation is the only way in: the same parameters fail `validate` (in T).
            assert!(pt.validate().is_err() || s.is_some(), "{e:?} but validate() passed");
            return "rejected";
        }
    };
    for _ in 0..cap {
        let Some(r) = scene.step() else { break };
        if r.error.is_none() && scene.outcome() != Some(Outcome::NonFinite) {
            let st = r.state;
            for v in [st.x, st.y, st.theta, st.vx, st.vy, st.omega] {
                assert!(v.finite(), "non-finite state without an outcome: {st:?}");
            }
        }
    }
    match scene.outcome() {
        None => "running",
        Some(Outcome::SolverFailed(e)) => e.kind(),
        Some(Outcome::NonFinite) => "non-finite",
        Some(_) => "ended",
    }
}

/// Runs `cases` random cases through `check`, tallying what happened; the tally must show
/// that both accepted and rejected inputs were exercised (no vacuous pass).
fn fuzz<S: Strategy>(strategy: S, check: impl Fn(&S::Value) -> [&'static str; 2]) {
    use proptest::test_runner::{Config, TestRunner};
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(256);
    let mut runner = TestRunner::new(Config { cases, ..Config::default() });
    let tally = std::cell::RefCell::new(std::collections::BTreeMap::<&str, u32>::new());
    runner
        .run(&strategy, |v| {
            for what in check(&v) {
                *tally.borrow_mut().entry(what).or_default() += 1;
            }
            Ok(())
        })
        .unwrap();
    let tally = tally.into_inner();
    println!("{cases} cases x 2 configurations: {tally:?}");
    let ran: u32 = tally.iter().filter(|(k, _)| **k != "rejected").map(|(_, n)| n).sum();
    assert!(ran >= cases / 4, "too few inputs ran: {tally:?}");
    assert!(tally.get("rejected").copied().unwrap_or(0) >= cases / 20, "too few were rejected: {tally:?}");
}

#[test]
fn raw_parameters_run_or_are_rejected() {
    fuzz(params(), |p| [exercise::<f32, 6>(p, None, 300), exercise::<f64, 8>(p, None, 300)]);
}

#[test]
fn raw_initial_states_run_or_are_rejected() {
    let p = SceneParams::<f64> { max_time: 0.2, ..SceneParams::paper() };
    fuzz(state(), |s| [exercise::<f32, 6>(&p, Some(s), 300), exercise::<f64, 8>(&p, Some(s), 300)]);
}
