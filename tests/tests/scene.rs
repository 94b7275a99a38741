//! The meter-stick scene against checks that need no simulation to trust: torque balance
//! (eq. 19), the switch law (eq. 21), the meeting point, and the 6x6 model's agreement
//! with the paper's 8x8 form.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::ParamError;
use meterstick_core::Real;
use meterstick_core::planar::{BodyState, ContactMode};
use meterstick_core::scene::{MeterStick, MeterStick6, MeterStick8, MeterStickParams, Outcome, Scene};
use meterstick_host_sim::scenes::{LcpLayout, Precision, SceneParams};
use meterstick_host_sim::trajectory::{Record, run_core, switches};

/// The paper's scene with an asymmetric start, so the first slip is determined.
fn slow<T: Real>() -> MeterStickParams<T> {
    MeterStickParams { finger1_x: T::of(-0.35), ..MeterStickParams::paper() }
}

fn with_speed<T: Real>(v: f64) -> MeterStickParams<T> {
    MeterStickParams { finger1_velocity: T::of(v), ..slow() }
}

/// The eq. 21 switches (host-sim's one implementation) strictly before the fingers met:
/// `(x_start, x_stop)` distances from the centre of mass.
fn eq21_switches<T: Real, const N: usize>(
    params: &MeterStickParams<T>,
    meeting_time: f64,
) -> Vec<(f64, f64)> {
    let p64 = params.cast::<f64>();
    let precision = Precision::from_name(T::NAME).unwrap();
    let layout = if N == 6 { LcpLayout::Reduced } else { LcpLayout::Full };
    let run = run_core::<2>(&SceneParams::MeterStick(p64), precision, layout, Record::Nothing).unwrap();
    switches(&run).iter().filter(|s| s.t < meeting_time - p64.step).map(|s| (s.x_start, s.x_stop)).collect()
}

/// Meeting-point bound: quasi-statically each finger's distance to the COM stays within
/// `mu_k/mu_s .. mu_s/mu_k` of the other's, so when the fingers stop `w` apart the COM is at
/// most `0.1 w` = 1 mm from their midpoint; each switch adds the rod's catch-up lag (both
/// fingers slide ~0.12 s while the rod accelerates). Measured 2.3 mm in all four
/// configurations and for h = 1e-3 .. 1e-5 s; asserted below 3 mm.
const MEETING_BOUND: f64 = 0.003;

fn check_slow_case<T: Real, const N: usize>() {
    let params = slow::<T>();
    let mut scene = MeterStick::<T, N, 128>::new(params).unwrap();
    let outcome = scene.run(|_| {});
    let name = format!("{}x{} {}", N, N, T::NAME);
    assert_eq!(outcome, Outcome::Balanced, "{name}");
    let meeting = scene.meeting().unwrap();
    assert!(
        meeting.com_offset.as_f64().abs() < MEETING_BOUND,
        "{name}: meeting offset {:?}",
        meeting.com_offset
    );
    let ratio = params.mu_kinetic.as_f64() / params.mu_static.as_f64();
    let switches = eq21_switches::<T, N>(&params, meeting.time.as_f64());
    assert!(switches.len() >= 4, "{name}: stick/slip should alternate, got {switches:?}");
    // Eq. 21 holds better as v -> 0: the rod's catch-up lag after a switch matters more
    // when the fingers are close. 1% while x_start > 5 cm, 3% closer in.
    for (x_start, x_stop) in &switches {
        let measured = x_stop / x_start;
        let tol = if *x_start > 0.05 { 0.01 } else { 0.03 };
        assert!(
            (measured / ratio - 1.0).abs() < tol,
            "{name}: x_stop/x_start = {measured:.5} vs mu_k/mu_s = {ratio:.5} at x_start {x_start:.4}"
        );
    }
    // Both fingers alternate: each one sticks at least twice.
    for finger in 0..2u8 {
        let sticks =
            scene.events().iter().filter(|e| e.contact == finger && e.mode == ContactMode::Sticking).count();
        assert!(sticks >= 2, "{name}: finger {finger} stuck {sticks} times");
    }
    assert_eq!(scene.reduced_check_fired_before_meeting(), 0, "{name}");
    assert_eq!(scene.events_dropped(), 0);
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
    let params = MeterStickParams::<T> {
        finger1_velocity: T::zero(),
        finger1_x: T::of(-0.3),
        finger2_x: T::of(0.45),
        ..MeterStickParams::paper()
    };
    let mut scene = MeterStick::<T, N>::new(params).unwrap();
    let mut last = None;
    for _ in 0..500 {
        last = scene.step();
    }
    let r = last.unwrap();
    let (w1, w2) = (r.contacts[0].normal_impulse.as_f64(), r.contacts[1].normal_impulse.as_f64());
    let (x1, x2) = (r.contacts[0].along.as_f64().abs(), r.contacts[1].along.as_f64().abs());
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

fn outcome<T: Real, const N: usize>(params: MeterStickParams<T>) -> Outcome {
    MeterStick::<T, N, 128>::new(params).unwrap().run(|_| {})
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
    let params = MeterStickParams::<f64> { mu_static: 0.5, mu_kinetic: 0.5, ..slow() };
    let mut scene = MeterStick::<f64, 8, 128>::new(params).unwrap();
    assert_eq!(scene.run(|_| {}), Outcome::Balanced);
    assert!(scene.meeting().unwrap().com_offset.abs() < MEETING_BOUND);
    assert_eq!(
        outcome::<f32, 6>(MeterStickParams { mu_static: 0.5, mu_kinetic: 0.5, ..slow() }),
        Outcome::Balanced
    );
}

/// Until the fingers meet, the 6x6 and 8x8 scenes take the same steps (the dropped
/// directions carry no impulse), to round-off: 1e-9 m / rad in f64; in f32, 2 v h = 2e-4 m
/// (their f32 round-off differs, so a stick/slip switch may come one step apart, which moves
/// the rod by up to one step of finger travel, v h; measured 1.02e-4 m).
fn check_sizes_agree<T: Real>(v: f64, tol: f64) {
    let params = with_speed::<T>(v);
    let mut s6 = MeterStick::<T, 6, 128>::new(params).unwrap();
    let mut s8 = MeterStick::<T, 8, 128>::new(params).unwrap();
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
    check_sizes_agree::<f32>(0.1, 2e-4);
    check_sizes_agree::<f64>(1.0, 1e-9);
}

/// The 6x6 check fires where the reduced model leaves its range, after the fingers stop
/// (the rod slides on, either way) or while it falls, and never before in these scenes; it
/// does fire in some of them (it is not dead code). (Where `sigma` is free, e.g. a contact
/// without normal impulse, the reduced answer extends to the full LCP and the check passes:
/// at v = 1 m/s it no longer fires at all.)
#[test]
fn reduced_check_fires_only_after_the_fingers_stop() {
    let mut fired = 0;
    for v in [0.5, 1.0, 5.0, 10.0] {
        for stats in [
            {
                let mut s = MeterStick::<f64, 6, 128>::new(with_speed(v)).unwrap();
                s.run(|_| {});
                (s.stats().reduced_check_fired, s.reduced_check_fired_before_meeting())
            },
            {
                let mut s = MeterStick::<f32, 6, 128>::new(with_speed(v)).unwrap();
                s.run(|_| {});
                (s.stats().reduced_check_fired, s.reduced_check_fired_before_meeting())
            },
        ] {
            fired += stats.0;
            assert_eq!(stats.1, 0, "v={v}: {stats:?}");
        }
    }
    assert!(fired > 0, "the 6x6 check never fired");
}

/// A tilted start's switch events, `(contact, mode)` in order, and the outcome.
fn switch_sequence<T: Real, const N: usize>(
    y1: f64,
    speed: f64,
    x1: f64,
) -> (Vec<(u8, ContactMode)>, Outcome) {
    let params = MeterStickParams::<f64> {
        finger1_y: y1,
        finger1_velocity: speed,
        finger1_x: x1,
        ..MeterStickParams::paper()
    };
    let mut scene = MeterStick::<T, N, 128>::new(params.cast::<T>()).unwrap();
    let outcome = scene.run(|_| {});
    assert_eq!(scene.events_dropped(), 0);
    (scene.events().iter().map(|e| (e.contact, e.mode)).collect(), outcome)
}

/// The firmware's layout (f32 6x6) logs f64's switch sequence on tilted starts (finger 1 raised
/// by `y1`), where finger 1's friction changes sign while it sticks near the end of the run. The
/// reduced layout drops that finger's `-d`; its check must not let f32's round-off floor (3e-5
/// m/s, above `stick_speed`) hide a slip in the dropped direction. It did: at `y1 = 0.02`,
/// `v = 0.12`, `x1 = -0.36` (issue #33) contact 0 alternated sticking / sliding fourteen times
/// in 35 ms, 24 events against f64's 10; the other starts logged 18, 15 and 49 against 10, 11, 11.
#[test]
fn f32_reduced_logs_the_f64_switch_sequence_on_tilted_starts() {
    for (y1, speed, x1) in
        [(0.02, 0.12, -0.36), (0.02, 0.10, -0.36), (0.01, 0.12, -0.36), (0.03, 0.10, -0.36)]
    {
        let (f32_reduced, f32_outcome) = switch_sequence::<f32, 6>(y1, speed, x1);
        let (f64_reduced, f64_outcome) = switch_sequence::<f64, 6>(y1, speed, x1);
        let (f64_full, _) = switch_sequence::<f64, 8>(y1, speed, x1);
        assert_eq!(f64_reduced, f64_full, "y1={y1} v={speed} x1={x1}: f64 6x6 against 8x8");
        assert_eq!(f32_reduced, f64_full, "y1={y1} v={speed} x1={x1}: f32 6x6 against f64");
        assert_eq!(f32_outcome, f64_outcome, "y1={y1} v={speed} x1={x1}");
        assert!(f64_full.len() >= 10, "y1={y1} v={speed} x1={x1}: {} events", f64_full.len());
    }
}

/// Symmetric start (both fingers 0.4 m from the centre of mass): there is no tie to break.
/// Finger 1 starts at full speed under a rod at rest, so it slides from `t = 0+` (kinetic
/// friction) while finger 2 holds the rod with static friction; the rod stays put until
/// `mu_k x2 = mu_s x1` (eq. 21), where finger 2 is the first to change mode. Deterministic.
#[test]
fn symmetric_start_is_deterministic_and_finger_2_switches_first() {
    let params = MeterStickParams::<f32>::paper();
    let mut a = MeterStick::<f32, 6, 128>::new(params).unwrap();
    let mut b = MeterStick::<f32, 6, 128>::new(params).unwrap();
    assert_eq!(a.modes()[0].name(), "sliding+");
    assert_eq!(a.modes()[1], ContactMode::Sticking);
    let (mut moved_before_first_switch, mut switched) = (0.0_f32, false);
    let outcome = a.run(|r| {
        switched |= r.contacts[1].mode != ContactMode::Sticking;
        if !switched {
            moved_before_first_switch = moved_before_first_switch.max(r.state.x.abs());
        }
    });
    assert_eq!(outcome, Outcome::Balanced);
    b.run(|_| {});
    assert_eq!(a.events(), b.events());
    assert_eq!(a.state().x.to_bits(), b.state().x.to_bits());
    let first = a.events()[0];
    assert_eq!((first.contact, first.mode.name()), (1, "sliding-"), "{first:?}");
    let ratio = (first.along[0] / first.along[1]).abs();
    assert!((ratio / (0.4 / 0.6) - 1.0).abs() < 0.01, "x_stop/x_start = {ratio}");
    assert!(moved_before_first_switch < 1e-6, "the rod moved {moved_before_first_switch} m before");
}

#[test]
fn invalid_parameters_are_rejected() {
    let ok = MeterStickParams::<f64>::paper();
    let cases: Vec<(MeterStickParams<f64>, ParamError)> = vec![
        (MeterStickParams { rod_mass: f64::NAN, ..ok }, ParamError::NonFinite("rod_mass")),
        (MeterStickParams { step: f64::INFINITY, ..ok }, ParamError::NonFinite("step")),
        (MeterStickParams { rod_mass: -1.0, ..ok }, ParamError::NotPositive("rod_mass")),
        (MeterStickParams { rod_length: 0.0, ..ok }, ParamError::NotPositive("rod_length")),
        (MeterStickParams { rod_thickness: 0.0, ..ok }, ParamError::NotPositive("rod_thickness")),
        (MeterStickParams { step: 0.0, ..ok }, ParamError::NotPositive("step")),
        (MeterStickParams { step: -1e-3, ..ok }, ParamError::NotPositive("step")),
        (MeterStickParams { mu_static: -0.1, ..ok }, ParamError::Negative("mu_static")),
        (MeterStickParams { mu_kinetic: 0.7, ..ok }, ParamError::KineticAboveStatic),
        (MeterStickParams { finger1_x: -0.6, ..ok }, ParamError::FingerOutsideRod),
        (MeterStickParams { finger2_x: 0.51, ..ok }, ParamError::FingerOutsideRod),
        (MeterStickParams { finger1_x: 0.3, finger2_x: 0.2, ..ok }, ParamError::FingersCrossed),
        (MeterStickParams { finger1_x: 0.0, finger2_x: 0.005, ..ok }, ParamError::FingersCrossed),
        // Accepted before, then failed at the first step (a ray, or a non-finite state).
        (MeterStickParams { rod_thickness: 1e7, ..ok }, ParamError::OutOfRange("rod_thickness")),
        (MeterStickParams { rod_thickness: 1.0, ..ok }, ParamError::OutOfRange("rod_thickness")),
        (MeterStickParams { step: 1e23, ..ok }, ParamError::OutOfRange("step")),
        (MeterStickParams { step: 31.0, max_time: 30.0, ..ok }, ParamError::OutOfRange("step")),
    ];
    for (params, expected) in cases {
        assert_eq!(MeterStick::<f64, 8>::new(params).err(), Some(expected));
        assert_eq!(params.validate(), Err(expected));
    }
    let bad_state = BodyState { vx: f64::NAN, ..Default::default() };
    assert_eq!(MeterStick::<f64, 6>::with_state(ok, bad_state).err(), Some(ParamError::NonFiniteState));
}

/// A mass and a length each in f32's range whose moment of inertia is not: refused by the scene
/// with both fields named, before any step (they were accepted, then the run failed at step 0 with
/// `NonFiniteInput`, or a rod of 1e20 m with an infinite inertia ran 30,000 steps without turning).
/// And a ladder started flat measures no ratio rather than an infinite one.
#[test]
fn an_inertia_out_of_range_is_refused_before_any_step() {
    use meterstick_core::scene::{
        Cylinder, CylinderParams, Incline, InclineParams, Ladder, LadderParams, Painleve, PainleveParams,
        ThreeFingers, ThreeFingersParams,
    };
    let ok = MeterStickParams::<f32>::paper();
    let inertia = |mass, size| Some(ParamError::InertiaOutOfRange { mass, size });
    for params in [MeterStickParams { rod_mass: 1e-45, ..ok }, MeterStickParams { rod_length: 1e20, ..ok }] {
        assert_eq!(MeterStick::<f32, 6>::new(params).err(), inertia("rod_mass", "rod_length"));
        assert!(MeterStick::<f64, 6>::new(params.cast()).is_ok(), "f64 holds it");
    }
    assert_eq!(
        Incline::<f32>::new(InclineParams { mass: 1e-45, ..InclineParams::default() }).err(),
        inertia("mass", "width")
    );
    assert_eq!(
        Ladder::<f32>::new(LadderParams { mass: 1e-45, ..LadderParams::default() }).err(),
        inertia("mass", "length")
    );
    assert_eq!(
        ThreeFingers::<f32>::new(ThreeFingersParams { rod_mass: 1e-45, ..ThreeFingersParams::default() })
            .err(),
        inertia("rod_mass", "rod_length")
    );
    assert_eq!(
        Painleve::<f32>::new(PainleveParams { mass: 1e-45, ..PainleveParams::default() }).err(),
        inertia("mass", "length")
    );
    assert_eq!(
        Cylinder::<f32>::new(CylinderParams { radius: 1e-30, ..CylinderParams::default() }).err(),
        inertia("mass", "radius")
    );
    let mut flat = Ladder::<f32>::new(LadderParams { angle: 1e-45, ..LadderParams::default() }).unwrap();
    flat.run(|_| {});
    let measured = flat.measured();
    assert!(measured.iter().flatten().all(|m| m.is_finite()), "{measured:?}");
}

/// The LCP is solved per unit mass, so the motion does not depend on the rod's mass at
/// all: f32 runs with m = 1e-4 kg and m = 1e4 kg are bit-identical in position. (Before, the
/// impulse rows scaled as 1/m against the friction-cone rows, and at 1e4 kg f32 rocked the
/// rod and ended Unfinished; `host-sim stress`.)
#[test]
fn motion_does_not_depend_on_the_mass() {
    let run = |mass: f32| {
        let mut p = MeterStickParams::<f32>::paper();
        p.finger1_x = -0.35;
        p.rod_mass = mass;
        let mut s = MeterStick6::<f32, 64>::new(p).unwrap();
        let mut trace = Vec::new();
        let outcome = s.run(|r| trace.push([r.state.x, r.state.y, r.state.theta].map(f32::to_bits)));
        (outcome, trace)
    };
    let (light, heavy) = (run(1e-4), run(1e4));
    assert_eq!(light.0, Outcome::Balanced);
    assert_eq!(light, heavy);
}

/// A rod started 1 mm into the fingers is pushed out no faster than a fall through 1 mm,
/// `sqrt(2 g psi)`: it climbs above its resting height by at most one step of that push-out
/// (the last step starts below the surface), where the paper's `psi / h` term would shoot
/// it up by `psi^2 / (2 g h^2)` (5 cm at h = 1 ms, 500 m at h = 1e-5 s), and it comes to
/// rest on the fingers.
#[test]
fn penetration_recovery_does_not_launch_the_rod() {
    for h in [1e-3, 1e-5] {
        let mut p = MeterStickParams::<f64>::paper();
        p.step = h;
        p.max_time = 0.2;
        let rest = p.resting_state();
        let mut start = rest;
        start.y -= 1e-3;
        let mut s = MeterStick8::<f64, 64>::with_state(p, start).unwrap();
        let mut highest = f64::MIN;
        s.run(|r| highest = highest.max(r.state.y));
        let one_step = h * (2.0 * p.gravity * 1e-3_f64).sqrt();
        assert!(highest <= rest.y + one_step, "h = {h}: climbed to {highest} (rest {})", rest.y);
        assert!((s.state().y - rest.y).abs() < 1e-6, "h = {h}: ends at {}", s.state().y);
    }
}

/// Over 10^5 steps in f32 the time is `n h` and finger 1 at `x1 + v t` to the rounding of
/// one product, not the sum of 10^5 rounded increments (which at v = 1e-4 m/s was a
/// systematic 10 % slow; `host-sim stress`).
#[test]
fn f32_time_and_finger_do_not_drift() {
    let mut p = MeterStickParams::<f32>::paper();
    p.finger1_velocity = 1e-4;
    p.stick_speed = 1e-8;
    p.max_time = 1000.0;
    let mut s = MeterStick6::<f32, 64>::new(p).unwrap();
    for _ in 0..100_000 {
        s.step().unwrap();
    }
    let t = 100_000.0 * f64::from(p.step);
    assert!((f64::from(s.time()) - t).abs() <= 1e-6 * t, "{}", s.time());
    let x = f64::from(p.finger1_x) + 1e-4 * t;
    assert!((f64::from(s.fingers()[0]) - x).abs() < 1e-7, "{} vs {x}", s.fingers()[0]);
}

/// Eq. 21 bookkeeping: only stick/slip exchanges before the fingers stop count as eq. 21
/// switches. At 0.01 m/s the stop itself makes a sticking finger slide while the other slides
/// (ratio 1.30, not eq. 21's 2/3); it must be left out, and every switch kept must obey eq. 21.
#[test]
fn eq21_switches_stop_where_the_fingers_stop() {
    use meterstick_host_sim::trajectory::run;
    let p = MeterStickParams::<f64> {
        finger1_x: -0.35,
        finger1_velocity: 0.01,
        max_time: 100.0,
        ..MeterStickParams::paper()
    };
    let t = run(
        &SceneParams::MeterStick(p),
        meterstick_host_sim::scenes::Implementation::CORE_F32_REDUCED,
        Record::Nothing,
    )
    .unwrap();
    let stop = t.measured.meeting.expect("the fingers met").time_s;
    let eq21 = switches(&t);
    assert!(eq21.len() >= 8, "{eq21:?}");
    for s in &eq21 {
        assert!(s.t < stop, "{s:?} after the stop at {stop}");
        let tol = if s.x_start > 0.05 { 0.01 } else { 0.03 };
        assert!((s.ratio / (0.4 / 0.6) - 1.0).abs() < tol, "{s:?}");
    }
    // Not vacuous: after the stop a sticking finger does start to slide while the other slides.
    let mut modes = t.initial_modes;
    let mut after_stop = 0;
    let mut step = None;
    let mut before = modes;
    for e in &t.events {
        if step != Some(e.t.to_bits()) {
            step = Some(e.t.to_bits());
            before = modes;
        }
        if e.t >= stop
            && before[e.contact] == ContactMode::Sticking
            && e.mode.is_sliding()
            && before[1 - e.contact].is_sliding()
        {
            after_stop += 1;
        }
        modes[e.contact] = e.mode;
    }
    assert!(after_stop >= 1, "expected a stop-caused change to leave out: {:?}", t.events);
}

/// The precision warning (`StepReport::round_off_limited`, beyond `eps V / (g h)` = 1e-4) is
/// raised where `host-sim envelope` measured f32 missing its target against f64 (0.1, 0.3 and
/// 1 m/s at h = 1e-5 s: 1.2e-4, 3.6e-4 and 1.2e-3 while finger 1 slides under the resting rod)
/// and not where it held (0.5 m/s at 1e-4 s: 6e-5; the paper's 0.1 m/s at 1 ms), nor ever in
/// f64 at these sizes.
#[test]
fn the_step_report_warns_where_f32_cannot_resolve_the_impulses() {
    fn flagged<T: Real>(v: f64, h: f64) -> u64 {
        let p = MeterStickParams { step: T::of(h), ..with_speed::<T>(v) };
        let mut s = MeterStick6::<T>::new(p).unwrap();
        let mut flagged = 0;
        for _ in 0..200 {
            flagged += u64::from(s.step().unwrap().round_off_limited);
        }
        assert_eq!(s.stats().round_off_limited, flagged);
        flagged
    }
    assert_eq!(flagged::<f32>(1.0, 1e-5), 200);
    assert_eq!(flagged::<f32>(0.3, 1e-5), 200);
    assert_eq!(flagged::<f32>(0.1, 1e-5), 200);
    assert_eq!(flagged::<f32>(0.5, 1e-4), 0);
    assert_eq!(flagged::<f32>(0.1, 1e-3), 0);
    assert_eq!(flagged::<f64>(10.0, 1e-5), 0);
}

/// The f32 envelope's cause at small h, fixed (`docs/formulation.md`, "Precision"): Lemke's method
/// took a basis whose sticking cone row was at -1% of its impulses as feasible (round-off judged
/// against the 0.1 m/s slip in the same LCP), and at h = 1e-5 s the first eq. 21 switch came
/// late: ratio 0.6646 in f32 against 0.6655 in f64. Asserted: the f32 core's first
/// switch within 5e-4 of the f64 core's (which equals the independent reference to round-off,
/// `tests/reference.rs`).
#[test]
fn f32_switches_on_time_at_a_small_step() {
    let p =
        MeterStickParams { finger1_velocity: 0.1, step: 1e-5, max_time: 1.5, ..MeterStickParams::paper() };
    let spec = SceneParams::MeterStick(p);
    let first = |run: &meterstick_host_sim::trajectory::Trajectory| switches(run).first().copied().unwrap();
    let f32_run = run_core::<2>(&spec, Precision::F32, LcpLayout::Reduced, Record::Nothing).unwrap();
    let f64_run = run_core::<2>(&spec, Precision::F64, LcpLayout::Full, Record::Nothing).unwrap();
    let (a, b) = (first(&f32_run), first(&f64_run));
    assert!((a.ratio - b.ratio).abs() < 5e-4, "f32 {a:?} vs f64 {b:?}");
}
