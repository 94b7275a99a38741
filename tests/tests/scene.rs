//! The meter-stick scene against checks that need no simulation to trust: torque balance
//! (eq. 19), the switch law (eq. 21), the meeting point, and the 6x6 model's agreement
//! with the paper's 8x8 form.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::Real;
use meterstick_core::scene::{ContactMode, Outcome, ParamError, Scene, SceneParams, SwitchEvent};

/// The paper's scene with an asymmetric start, so the first slip is determined.
fn slow<T: Real>() -> SceneParams<T> {
    SceneParams { finger1_x: T::of(-0.35), ..SceneParams::paper() }
}

fn with_speed<T: Real>(v: f64) -> SceneParams<T> {
    SceneParams { finger_speed: T::of(v), ..slow() }
}

/// Switches where a sticking finger starts to slide while the other slides, before the
/// fingers meet: `(x_start, x_stop)` distances from the centre of mass (eq. 21).
fn eq21_switches<T: Real>(events: &[SwitchEvent<T>], meeting_time: f64, h: f64) -> Vec<(f64, f64)> {
    // Modes before the step of each event (events of one step share its time), so the
    // impulsive start, where both fingers begin to slide in the first step, is no switch.
    let mut mode = [ContactMode::Sticking; 2];
    let mut before = mode;
    let mut step_time = f64::NAN;
    let mut out = Vec::new();
    for e in events {
        if e.time.as_f64().to_bits() != step_time.to_bits() {
            step_time = e.time.as_f64();
            before = mode;
        }
        let i = e.finger as usize;
        let other = 1 - i;
        if e.time.as_f64() < meeting_time - h
            && before[i] == ContactMode::Sticking
            && e.mode.is_sliding()
            && before[other].is_sliding()
        {
            out.push((e.along[i].as_f64().abs(), e.along[other].as_f64().abs()));
        }
        mode[i] = e.mode;
    }
    out
}

fn check_slow_case<T: Real, const N: usize>() {
    let params = slow::<T>();
    let mut scene = Scene::<T, N, 128>::new(params).unwrap();
    let outcome = scene.run(|r| assert!(r.error.is_none(), "{:?}", r.error));
    let name = format!("{}x{} {}", N, N, T::NAME);
    assert_eq!(outcome, Outcome::Balanced, "{name}");
    let meeting = scene.meeting().unwrap();
    assert!(meeting.com_offset.as_f64().abs() < 0.002, "{name}: meeting offset {:?}", meeting.com_offset);
    let ratio = params.mu_kinetic.as_f64() / params.mu_static.as_f64();
    let switches = eq21_switches(scene.events(), meeting.time.as_f64(), params.step.as_f64());
    assert!(switches.len() >= 4, "{name}: stick/slip should alternate, got {switches:?}");
    for (x_start, x_stop) in &switches {
        let measured = x_stop / x_start;
        assert!(
            (measured / ratio - 1.0).abs() < 0.01,
            "{name}: x_stop/x_start = {measured:.5} vs mu_k/mu_s = {ratio:.5} at x_start {x_start:.4}"
        );
    }
    // Both fingers alternate: each one sticks at least twice.
    for finger in 0..2u8 {
        let sticks =
            scene.events().iter().filter(|e| e.finger == finger && e.mode == ContactMode::Sticking).count();
        assert!(sticks >= 2, "{name}: finger {finger} stuck {sticks} times");
    }
    assert_eq!(scene.stats().reduced_check_fired_before_meeting, 0, "{name}");
    assert_eq!(scene.stats().events_dropped, 0);
}

#[test]
fn slow_case_alternates_and_obeys_the_switch_law_8x8_f64() {
    check_slow_case::<f64, 8>();
}
#[test]
fn slow_case_alternates_and_obeys_the_switch_law_8x8_f32() {
    check_slow_case::<f32, 8>();
}
#[test]
fn slow_case_alternates_and_obeys_the_switch_law_6x6_f64() {
    check_slow_case::<f64, 6>();
}
#[test]
fn slow_case_alternates_and_obeys_the_switch_law_6x6_f32() {
    check_slow_case::<f32, 6>();
}

/// Eq. 19: on a horizontal rod at rest, W1 x1 = W2 x2 and W1 + W2 = m g (impulses over h).
fn check_torque_balance<T: Real, const N: usize>(tol: f64) {
    let params = SceneParams::<T> {
        finger_speed: T::zero(),
        finger1_x: T::of(-0.3),
        finger2_x: T::of(0.45),
        ..SceneParams::paper()
    };
    let mut scene = Scene::<T, N>::new(params).unwrap();
    let mut last = None;
    for _ in 0..500 {
        last = scene.step();
    }
    let r = last.unwrap();
    let (w1, w2) = (r.normal_impulse[0].as_f64(), r.normal_impulse[1].as_f64());
    let (x1, x2) = (r.along[0].as_f64().abs(), r.along[1].as_f64().abs());
    let weight = params.rod_mass.as_f64() * params.gravity.as_f64() * params.step.as_f64();
    assert!((w1 * x1 - w2 * x2).abs() <= tol * weight * x2, "W1 x1 = {} vs W2 x2 = {}", w1 * x1, w2 * x2);
    assert!((w1 + w2 - weight).abs() <= tol * weight);
    // Exact analytic split: W1 = m g h x2 / (x1 + x2).
    assert!((w1 - weight * 0.45 / 0.75).abs() <= tol * weight);
    let s = scene.state();
    for (what, v) in [("x", s.x), ("theta", s.theta), ("vx", s.vx), ("vy", s.vy), ("omega", s.omega)] {
        assert!(v.as_f64().abs() <= tol, "{what} = {v:?}: the rod moved");
    }
    assert!((s.y.as_f64() - 0.0025).abs() <= tol);
    assert_eq!(scene.modes(), [ContactMode::Sticking; 2]);
}

#[test]
fn static_rod_obeys_torque_balance() {
    check_torque_balance::<f64, 8>(1e-9);
    check_torque_balance::<f64, 6>(1e-9);
    check_torque_balance::<f32, 8>(1e-4);
    check_torque_balance::<f32, 6>(1e-4);
}

fn outcome<T: Real, const N: usize>(params: SceneParams<T>) -> Outcome {
    Scene::<T, N, 128>::new(params).unwrap().run(|_| {})
}

#[test]
fn fast_finger_makes_the_rod_fall() {
    for v in [1.0, 5.0, 10.0] {
        assert_eq!(outcome::<f64, 8>(with_speed(v)), Outcome::Fell, "8x8 f64 v={v}");
        assert_eq!(outcome::<f32, 8>(with_speed(v)), Outcome::Fell, "8x8 f32 v={v}");
        assert_eq!(outcome::<f64, 6>(with_speed(v)), Outcome::Fell, "6x6 f64 v={v}");
        assert_eq!(outcome::<f32, 6>(with_speed(v)), Outcome::Fell, "6x6 f32 v={v}");
    }
}

/// Brackets the speed where the outcome changes (f64, 8x8, paper scene with x1 = -0.35)
/// by bisection between 0.1 m/s (balanced) and 5 m/s (fell), and checks f32 6x6 agrees on
/// both ends of the final bracket.
#[test]
fn fall_threshold_is_bracketed() {
    let (mut lo, mut hi) = (0.1, 5.0);
    assert_eq!(outcome::<f64, 8>(with_speed(lo)), Outcome::Balanced);
    assert_eq!(outcome::<f64, 8>(with_speed(hi)), Outcome::Fell);
    while hi - lo > 0.02 {
        let mid = 0.5 * (lo + hi);
        match outcome::<f64, 8>(with_speed(mid)) {
            Outcome::Balanced => lo = mid,
            Outcome::Fell => hi = mid,
            other => panic!("v = {mid}: {other:?}"),
        }
    }
    println!("outcome changes between v = {lo:.3} m/s (balanced) and {hi:.3} m/s (fell)");
    assert_eq!(outcome::<f32, 6>(with_speed(lo)), Outcome::Balanced);
    assert_eq!(outcome::<f32, 6>(with_speed(hi)), Outcome::Fell);
}

#[test]
fn equal_friction_coefficients_still_balance_at_low_speed() {
    let params = SceneParams::<f64> { mu_static: 0.5, mu_kinetic: 0.5, ..slow() };
    let mut scene = Scene::<f64, 8, 128>::new(params).unwrap();
    assert_eq!(scene.run(|_| {}), Outcome::Balanced);
    assert!(scene.meeting().unwrap().com_offset.abs() < 0.002);
    assert_eq!(
        outcome::<f32, 6>(SceneParams { mu_static: 0.5, mu_kinetic: 0.5, ..slow() }),
        Outcome::Balanced
    );
}

/// Until the fingers meet, the 6x6 and 8x8 scenes take the same steps (the dropped
/// directions carry no impulse), to round-off: 1e-9 m / rad in f64, 1e-4 in f32 (f32
/// round-off accumulated over ~7,000 steps of a trajectory with stick/slip switches).
fn check_sizes_agree<T: Real>(v: f64, tol: f64) {
    let params = with_speed::<T>(v);
    let mut s6 = Scene::<T, 6, 128>::new(params).unwrap();
    let mut s8 = Scene::<T, 8, 128>::new(params).unwrap();
    let mut worst: f64 = 0.0;
    while s8.meeting().is_none() && s8.outcome().is_none() {
        let (a, b) = (s6.step().unwrap(), s8.step().unwrap());
        for (x, y) in [(a.state.x, b.state.x), (a.state.y, b.state.y), (a.state.theta, b.state.theta)] {
            worst = worst.max((x.as_f64() - y.as_f64()).abs());
        }
    }
    assert!(worst <= tol, "{} v={v}: 6x6 and 8x8 differ by {worst:e} before the fingers met", T::NAME);
}

#[test]
fn reduced_and_full_models_agree_until_the_fingers_meet() {
    check_sizes_agree::<f64>(0.1, 1e-9);
    check_sizes_agree::<f32>(0.1, 1e-4);
    check_sizes_agree::<f64>(1.0, 1e-9);
}

/// The 6x6 check fires where the reduced model leaves its range, after the fingers stop
/// (the rod slides on, either way) or while it falls, and never before in these scenes.
#[test]
fn reduced_check_fires_only_after_the_fingers_stop() {
    for v in [0.5, 1.0, 5.0] {
        for stats in [
            {
                let mut s = Scene::<f64, 6, 128>::new(with_speed(v)).unwrap();
                s.run(|_| {});
                *s.stats()
            },
            {
                let mut s = Scene::<f32, 6, 128>::new(with_speed(v)).unwrap();
                s.run(|_| {});
                *s.stats()
            },
        ] {
            assert!(stats.reduced_check_fired > 0, "v={v}: {stats:?}");
            assert_eq!(stats.reduced_check_fired_before_meeting, 0, "v={v}: {stats:?}");
        }
    }
}

/// Symmetric start (both fingers 0.4 m from the centre of mass): the run is deterministic.
/// There is no tie to break in practice: finger 1 starts moving at full speed under a rod
/// at rest, so it slides from the first step (an impulsive start), while finger 2 holds the
/// rod with static friction; finger 2 is the first to change mode after that.
#[test]
fn symmetric_start_is_deterministic() {
    let params = SceneParams::<f32>::paper();
    let mut a = Scene::<f32, 6, 128>::new(params).unwrap();
    let mut b = Scene::<f32, 6, 128>::new(params).unwrap();
    assert_eq!(a.run(|_| {}), Outcome::Balanced);
    b.run(|_| {});
    assert_eq!(a.events(), b.events());
    assert_eq!(a.state().x.to_bits(), b.state().x.to_bits());
    let first = a.events()[0];
    assert_eq!((first.finger, first.mode.name()), (0, "sliding+"));
    assert!((first.time - params.step).abs() < 1e-9);
    let second = a.events()[1];
    assert_eq!(second.finger, 1, "finger 2 changes mode next: {second:?}");
}

#[test]
fn invalid_parameters_are_rejected() {
    let ok = SceneParams::<f64>::paper();
    let cases: Vec<(SceneParams<f64>, ParamError)> = vec![
        (SceneParams { rod_mass: f64::NAN, ..ok }, ParamError::NonFinite("rod_mass")),
        (SceneParams { step: f64::INFINITY, ..ok }, ParamError::NonFinite("step")),
        (SceneParams { rod_mass: -1.0, ..ok }, ParamError::NotPositive("rod_mass")),
        (SceneParams { rod_length: 0.0, ..ok }, ParamError::NotPositive("rod_length")),
        (SceneParams { rod_thickness: 0.0, ..ok }, ParamError::NotPositive("rod_thickness")),
        (SceneParams { step: 0.0, ..ok }, ParamError::NotPositive("step")),
        (SceneParams { step: -1e-3, ..ok }, ParamError::NotPositive("step")),
        (SceneParams { mu_static: -0.1, ..ok }, ParamError::Negative("mu_static")),
        (SceneParams { finger_speed: -1.0, ..ok }, ParamError::Negative("finger_speed")),
        (SceneParams { mu_kinetic: 0.7, ..ok }, ParamError::KineticAboveStatic),
        (SceneParams { finger1_x: -0.6, ..ok }, ParamError::FingerOutsideRod),
        (SceneParams { finger2_x: 0.51, ..ok }, ParamError::FingerOutsideRod),
        (SceneParams { finger1_x: 0.3, finger2_x: 0.2, ..ok }, ParamError::FingersCrossed),
        (SceneParams { finger1_x: 0.0, finger2_x: 0.005, ..ok }, ParamError::FingersCrossed),
    ];
    for (params, expected) in cases {
        assert_eq!(Scene::<f64, 8>::new(params).err(), Some(expected));
        assert_eq!(params.validate(), Err(expected));
    }
    let bad_state = meterstick_core::scene::RodState { vx: f64::NAN, ..Default::default() };
    assert_eq!(Scene::<f64, 6>::with_state(ok, bad_state).err(), Some(ParamError::NonFiniteState));
}
