//! The core against the independent f64 reference (`host-sim`'s `reference`, which enumerates
//! complementary bases of the full form and shares no code with the core's geometry, assembly,
//! solver or stepper), on every scene.
//!
//! Tolerances:
//! * **f64 core vs reference**: both solve the same LCP each step to round-off (~1e-16 relative),
//!   so with the same modes the trajectories differ by round-off only (measured: <= 1.8e-14 m over
//!   whole runs of every scene). Asserted: same steps, outcome and switch events, measured
//!   quantities within 1e-9, and 1e-9 m / 1e-9 rad, a margin for other platforms' `sin`/`cos`.
//! * **f32 core vs reference** (meter stick): f32 positions carry ~6e-8 m of rounding per step,
//!   and a mode switch may come one step earlier or later, which moves the rod relative to its
//!   f64 path by at most the finger's travel in one step, `v h`, per switch. Asserted: the same
//!   outcome, COM within `3 v h + 1e-5` m, angle within 1e-4 rad, meeting offsets within 0.5 mm,
//!   eq. 21 ratios within `1.5 v h / x_start + 0.002` (a switch one step later moves `x_stop` by
//!   `v h`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::scene::{InclineParams, LadderParams, MeterStickParams};
use meterstick_host_sim::scenes::{Implementation, SceneSpec};
use meterstick_host_sim::trajectory::{OutcomeClass, Record, Trajectory, max_deviation, run, switches};

fn stick(v: f64, x1: f64, duration: f64) -> MeterStickParams<f64> {
    MeterStickParams { finger1_velocity: v, finger1_x: x1, max_time: duration, ..MeterStickParams::paper() }
}

fn reference(spec: &SceneSpec) -> Trajectory {
    run(spec, Implementation::Reference, Record::All).unwrap()
}

fn assert_same_events(core: &Trajectory, reference: &Trajectory) {
    assert_eq!(core.events.len(), reference.events.len(), "{} vs reference", core.implementation);
    for (a, b) in core.events.iter().zip(&reference.events) {
        assert_eq!((a.contact, a.mode), (b.contact, b.mode), "{a:?} vs {b:?}");
        assert!((a.t - b.t).abs() < 1e-9, "{a:?} vs {b:?}");
    }
}

fn close(a: Option<f64>, b: Option<f64>, what: &str) {
    assert_eq!(a.is_some(), b.is_some(), "{what}: {a:?} vs {b:?}");
    if let (Some(a), Some(b)) = (a, b) {
        assert!((a - b).abs() < 1e-9, "{what}: {a} vs {b}");
    }
}

/// Every scene, in several regimes: the meter stick with either or both fingers moving and a
/// raised finger; a block held, sliding, tipping; a ladder standing, slipping, frictionless.
fn scenes() -> Vec<(&'static str, SceneSpec)> {
    use SceneSpec::{Incline, Ladder, MeterStick};
    let deg = f64::to_radians;
    vec![
        ("slow", MeterStick(stick(0.1, -0.35, 30.0))),
        ("fig. 5, 0.5 m/s", MeterStick(stick(0.5, -0.4, 30.0))),
        ("fig. 5, 5 m/s", MeterStick(stick(5.0, -0.4, 30.0))),
        ("cut short", MeterStick(stick(0.1, -0.4, 2.0))),
        (
            "finger 2 moves",
            MeterStick(MeterStickParams {
                finger1_velocity: 0.0,
                finger2_velocity: -0.1,
                finger2_x: 0.35,
                ..MeterStickParams::paper()
            }),
        ),
        (
            "both inward",
            MeterStick(MeterStickParams {
                finger1_velocity: 0.07,
                finger2_velocity: -0.05,
                ..stick(0.1, -0.35, 30.0)
            }),
        ),
        ("finger 1 raised", MeterStick(MeterStickParams { finger1_y: 0.03, ..stick(0.1, -0.35, 30.0) })),
        ("incline held", Incline(InclineParams { angle: deg(20.0), ..InclineParams::default() })),
        ("incline slides", Incline(InclineParams::default())),
        (
            "incline tips",
            Incline(InclineParams { angle: deg(20.0), width: 0.05, height: 0.2, ..InclineParams::default() }),
        ),
        ("ladder stands", Ladder(LadderParams { angle: deg(60.0), ..LadderParams::default() })),
        ("ladder slips", Ladder(LadderParams::default())),
        (
            "ladder frictionless",
            Ladder(LadderParams { mu_floor: 0.0, mu_wall: 0.0, ..LadderParams::default() }),
        ),
    ]
}

#[test]
fn f64_core_matches_the_reference_to_round_off_on_every_scene() {
    let mut worst: f64 = 0.0;
    for (name, spec) in scenes() {
        let r = reference(&spec);
        for implementation in [
            Implementation::CORE_F64_8,
            Implementation::Core(
                meterstick_host_sim::lcp_io::Precision::F64,
                meterstick_host_sim::scenes::LcpSize::Reduced,
            ),
        ] {
            let core = run(&spec, implementation, Record::All).unwrap();
            let what = format!("{name}: {implementation}");
            assert_eq!(core.steps, r.steps, "{what}");
            assert_eq!(core.outcome, r.outcome, "{what}");
            assert_same_events(&core, &r);
            let (com, angle) = max_deviation(&core, &r);
            assert!(com < 1e-9 && angle < 1e-9, "{what}: {com:e} m, {angle:e} rad");
            worst = worst.max(com);
            let (mc, mr) = (&core.measured, &r.measured);
            close(mc.meeting.map(|m| m.com_offset_m), mr.meeting.map(|m| m.com_offset_m), &what);
            close(mc.acceleration_m_s2, mr.acceleration_m_s2, &what);
            close(mc.wall_release_height_m, mr.wall_release_height_m, &what);
        }
        // The reference's choice among several solutions never changed the motion.
        assert_eq!(r.counters.ambiguous_steps, 0, "{name}");
    }
    println!("largest COM deviation, f64 core vs reference, all scenes: {worst:e} m");
}

#[test]
fn f32_core_matches_the_reference_within_one_step_of_travel() {
    for (v, x1) in [(0.1, -0.35), (0.1, -0.4), (5.0, -0.4)] {
        let p = stick(v, x1, 30.0);
        let spec = SceneSpec::MeterStick(p);
        let r = reference(&spec);
        for implementation in [Implementation::CORE_F32_6, Implementation::CORE_F32_8] {
            let core = run(&spec, implementation, Record::All).unwrap();
            let what = format!("{implementation} at v = {v}, x1 = {x1}");
            assert_eq!(core.outcome, r.outcome, "{what}");
            let (com, angle) = max_deviation(&core, &r);
            assert!(com <= 3.0 * v * p.step + 1e-5, "{what}: COM deviation {com:e} m");
            assert!(angle <= 1e-4, "{what}: angle deviation {angle:e} rad");
            let (a, b) =
                (core.measured.meeting.unwrap().com_offset_m, r.measured.meeting.unwrap().com_offset_m);
            assert!((a - b).abs() < 5e-4, "{what}: meeting {a} vs {b}");
            let (sa, sb) = (switches(&core), switches(&r));
            assert_eq!(sa.len(), sb.len(), "{what}");
            for (x, y) in sa.iter().zip(&sb) {
                // One step later moves x_stop by v h: the ratio by v h / x_start.
                let tol = 1.5 * v * p.step / y.x_start + 2e-3;
                assert!((x.ratio - y.ratio).abs() < tol, "{what}: {x:?} vs {y:?}");
            }
        }
    }
}

#[test]
fn the_reference_reproduces_the_papers_claims_by_itself() {
    // Slow finger: balanced, fingers meet near the COM, eq. 21 ratios near mu_k/mu_s.
    let r = reference(&SceneSpec::MeterStick(stick(0.1, -0.35, 30.0)));
    assert_eq!(r.outcome.class, OutcomeClass::Balanced);
    let meeting = r.measured.meeting.unwrap();
    assert!(meeting.com_offset_m.abs() < 3e-3, "{meeting:?}"); // bound: tests/scene.rs MEETING_BOUND
    let sw = switches(&r);
    assert!(sw.len() >= 4, "{sw:?}");
    for s in &sw {
        assert!((s.ratio / (0.4 / 0.6) - 1.0).abs() < 0.02, "{s:?}");
    }
    // Fast finger: the rod falls.
    assert_eq!(reference(&SceneSpec::MeterStick(stick(5.0, -0.4, 30.0))).outcome.class, OutcomeClass::Fell);
}

#[test]
fn the_reference_rejects_invalid_parameters() {
    let spec = SceneSpec::MeterStick(MeterStickParams { step: 0.0, ..MeterStickParams::paper() });
    let e = run(&spec, Implementation::Reference, Record::Nothing).unwrap_err().to_string();
    assert!(e.contains("step"), "{e}");
}

/// The f32 envelope's cause, fixed: a gap within round-off of the positions is not a gap
/// (`docs/formulation.md`, "One time step" and "Precision"). At 0.001 m/s with fingers starting at -/+0.1 m
/// (190,500 steps), the f32 core left the reference by 1.9e-4 m, and one eq. 21 ratio was 0.6876
/// where the reference has 0.6664, while the gap's rounding over h (one ulp of 0.5 m over 1 ms,
/// 6e-5 m/s) was 6% of the finger's speed. Asserted: the envelope's target (`host-sim envelope`),
/// 1e-5 m, and the same switches with ratios within 1e-3.
#[test]
fn f32_core_holds_1e_5_m_at_a_slow_finger() {
    let spec = SceneSpec::MeterStick(MeterStickParams { finger2_x: 0.1, ..stick(0.001, -0.1, 200.0) });
    let r = reference(&spec);
    let core = run(&spec, Implementation::CORE_F32_6, Record::All).unwrap();
    assert_eq!(core.outcome, r.outcome);
    let (com, _) = max_deviation(&core, &r);
    assert!(com < 1e-5, "COM deviation {com:e} m");
    let (sa, sb) = (switches(&core), switches(&r));
    assert_eq!(sa.len(), sb.len(), "{sa:?} vs {sb:?}");
    for (x, y) in sa.iter().zip(&sb) {
        assert!((x.ratio - y.ratio).abs() < 1e-3, "{x:?} vs {y:?}");
    }
}
