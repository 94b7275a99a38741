//! The core against the independent f64 reference (`host-sim`'s `reference`, which enumerates
//! complementary bases of the full form and shares no code with the core's geometry, assembly,
//! solver or stepper), on every scene.
//!
//! Tolerances:
//! * **f64 core vs reference**: both solve the same LCP each step to round-off (~1e-16 relative),
//!   so with the same modes the trajectories differ by round-off only (measured: <= 1.8e-14 m over
//!   whole runs of the two-contact scenes, 1.3e-14 m and 1.1e-13 rad on the cylinder, 1e-15 m on
//!   painleve). Asserted: same steps, outcome and switch events, measured quantities (and for one
//!   contact the impulses) within 1e-9, and 1e-9 m / 1e-9 rad, a margin for other platforms'
//!   `sin`/`cos`. Three fingers, whose motion the contact model leaves open, are held to the same
//!   1e-9 m through the rule both apply (`three_fingers_take_the_rules_answer_in_every_layout_and_precision`).
//! * **f32 core vs reference** (meter stick): f32 positions carry ~6e-8 m of rounding per step,
//!   and a mode switch may come one step earlier or later, which moves the rod relative to its
//!   f64 path by at most the finger's travel in one step, `v h`, per switch. Asserted: the same
//!   outcome, COM within `3 v h + 1e-5` m, angle within 1e-4 rad, meeting offsets within 0.5 mm,
//!   eq. 21 ratios within `1.5 v h / x_start + 0.002` (a switch one step later moves `x_stop` by
//!   `v h`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::scene::{
    CylinderParams, InclineParams, LadderParams, MeterStickParams, PainleveParams, ThreeFingersParams,
};
use meterstick_host_sim::lcp_io::Precision;
use meterstick_host_sim::scenes::{Implementation, LcpLayout, SceneParams};
use meterstick_host_sim::trajectory::{OutcomeKind, Record, Trajectory, max_deviation, run, run_k, switches};

fn stick(v: f64, x1: f64, duration: f64) -> MeterStickParams<f64> {
    MeterStickParams { finger1_velocity: v, finger1_x: x1, max_time: duration, ..MeterStickParams::paper() }
}

fn reference(spec: &SceneParams) -> Trajectory {
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
fn scenes() -> Vec<(&'static str, SceneParams)> {
    use SceneParams::{Incline, Ladder, MeterStick};
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
        for implementation in
            [Implementation::CORE_F64_FULL, Implementation::Core(Precision::F64, LcpLayout::Reduced)]
        {
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
        let spec = SceneParams::MeterStick(p);
        let r = reference(&spec);
        for implementation in [Implementation::CORE_F32_REDUCED, Implementation::CORE_F32_FULL] {
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
    let r = reference(&SceneParams::MeterStick(stick(0.1, -0.35, 30.0)));
    assert_eq!(r.outcome.class, OutcomeKind::Balanced);
    let meeting = r.measured.meeting.unwrap();
    assert!(meeting.com_offset_m.abs() < 3e-3, "{meeting:?}"); // bound: tests/scene.rs MEETING_BOUND
    let sw = switches(&r);
    assert!(sw.len() >= 4, "{sw:?}");
    for s in &sw {
        assert!((s.ratio / (0.4 / 0.6) - 1.0).abs() < 0.02, "{s:?}");
    }
    // Fast finger: the rod falls.
    assert_eq!(reference(&SceneParams::MeterStick(stick(5.0, -0.4, 30.0))).outcome.class, OutcomeKind::Fell);
}

#[test]
fn the_reference_rejects_invalid_parameters() {
    let spec = SceneParams::MeterStick(MeterStickParams { step: 0.0, ..MeterStickParams::paper() });
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
    let spec = SceneParams::MeterStick(MeterStickParams { finger2_x: 0.1, ..stick(0.001, -0.1, 200.0) });
    let r = reference(&spec);
    let core = run(&spec, Implementation::CORE_F32_REDUCED, Record::All).unwrap();
    assert_eq!(core.outcome, r.outcome);
    let (com, _) = max_deviation(&core, &r);
    assert!(com < 1e-5, "COM deviation {com:e} m");
    let (sa, sb) = (switches(&core), switches(&r));
    assert_eq!(sa.len(), sb.len(), "{sa:?} vs {sb:?}");
    for (x, y) in sa.iter().zip(&sb) {
        assert!((x.ratio - y.ratio).abs() < 1e-3, "{x:?} vs {y:?}");
    }
}

/// The core in f64, both layouts, against the reference on a one-contact scene: the same steps,
/// outcome and switch events, the trajectory within 1e-9 m / 1e-9 rad, measured quantities within
/// 1e-9. Returns the largest COM and angle deviations.
fn one_contact_matches(name: &str, spec: &SceneParams) -> (f64, f64) {
    let r = run_k::<1>(spec, Implementation::Reference, Record::All).unwrap();
    assert_eq!(r.counters.ambiguous_steps, 0, "{name}");
    let mut worst: (f64, f64) = (0.0, 0.0);
    for implementation in
        [Implementation::CORE_F64_FULL, Implementation::Core(Precision::F64, LcpLayout::Reduced)]
    {
        let core = run_k::<1>(spec, implementation, Record::All).unwrap();
        let what = format!("{name}: {implementation}");
        assert_eq!(core.steps, r.steps, "{what}");
        assert_eq!(core.outcome, r.outcome, "{what}");
        assert_eq!(core.initial_modes, r.initial_modes, "{what}");
        assert_eq!(core.events.len(), r.events.len(), "{what}");
        for (a, b) in core.events.iter().zip(&r.events) {
            assert_eq!((a.contact, a.mode), (b.contact, b.mode), "{what}: {a:?} vs {b:?}");
            assert!((a.t - b.t).abs() < 1e-9, "{what}: {a:?} vs {b:?}");
        }
        let (com, angle) = max_deviation(&core, &r);
        assert!(com < 1e-9 && angle < 1e-9, "{what}: {com:e} m, {angle:e} rad");
        worst = (worst.0.max(com), worst.1.max(angle));
        // Impulses step by step (N s).
        let impulse = core
            .rows
            .iter()
            .zip(&r.rows)
            .map(|(a, b)| {
                (a.contacts[0].normal_impulse - b.contacts[0].normal_impulse)
                    .abs()
                    .max((a.contacts[0].friction_impulse - b.contacts[0].friction_impulse).abs())
            })
            .fold(0.0, f64::max);
        assert!(impulse < 1e-9, "{what}: impulses {impulse:e} N s");
        let (mc, mr) = (&core.measured, &r.measured);
        close(mc.acceleration_m_s2, mr.acceleration_m_s2, &what);
        close(mc.jam.map(|j| j.normal_impulse_n_s), mr.jam.map(|j| j.normal_impulse_n_s), &what);
        close(mc.jam.map(|j| j.friction_impulse_n_s), mr.jam.map(|j| j.friction_impulse_n_s), &what);
        close(mc.jam.map(|j| j.time_s), mr.jam.map(|j| j.time_s), &what);
        close(mc.angular_acceleration_rad_s2, mr.angular_acceleration_rad_s2, &what);
        println!(
            "{what}: {:?}, {} steps, COM {com:.1e} m, angle {angle:.1e} rad, impulses {impulse:.1e} N s, \
             measured {:?}",
            core.outcome.class, core.steps, r.measured
        );
    }
    worst
}

/// The cylinder rolling and sliding, and Painlevé's rod jamming and sliding
/// (docs/scenes.md, "cylinder" and "painleve"): the round rim's geometry, a body that starts
/// moving, and an impulsive step, each written twice.
#[test]
fn f64_core_matches_the_reference_on_the_one_contact_scenes() {
    let deg = f64::to_radians;
    let cylinder = |angle: f64, k: f64| CylinderParams {
        angle: deg(angle),
        mu_static: 0.2,
        mu_kinetic: 0.15,
        inertia_factor: k,
        ..CylinderParams::default()
    };
    let scenes: Vec<(&str, SceneParams, OutcomeKind)> = vec![
        ("cylinder default", SceneParams::Cylinder(CylinderParams::default()), OutcomeKind::Rolled),
        // Critical angles atan(mu_s (1 + k) / k): 30.96 deg (k = 1/2), 21.80 deg (k = 1).
        ("cylinder rolls, k = 1/2", SceneParams::Cylinder(cylinder(28.96, 0.5)), OutcomeKind::Rolled),
        ("cylinder slides, k = 1/2", SceneParams::Cylinder(cylinder(32.96, 0.5)), OutcomeKind::Slid),
        ("ring slides", SceneParams::Cylinder(cylinder(40.0, 1.0)), OutcomeKind::Slid),
        ("painleve default", SceneParams::Painleve(PainleveParams::default()), OutcomeKind::Jammed),
        (
            "painleve 45 deg, h = 1e-4",
            SceneParams::Painleve(PainleveParams {
                angle: deg(45.0),
                mu_static: 2.0,
                mu_kinetic: 2.0,
                step: 1e-4,
                ..PainleveParams::default()
            }),
            OutcomeKind::Jammed,
        ),
        (
            // 0.96 times the critical mu at the start: the rod turns up, the normal response
            // `1 + 3 c^2 - 3 mu s c` falls toward 0 and the sliding impulses grow; the end sticks
            // after 5 steps under an impulse of the order of the last step's, a stop and no impact,
            // and the rod falls.
            "painleve stops late, falls",
            SceneParams::Painleve(PainleveParams {
                mu_static: 2.4,
                mu_kinetic: 2.4,
                ..PainleveParams::default()
            }),
            OutcomeKind::Fell,
        ),
        (
            // 0.8 times the critical mu: friction stops the slow end (no impact, no jam); the rod
            // pivots on its end and falls.
            "painleve stops, falls",
            SceneParams::Painleve(PainleveParams {
                speed: -0.1,
                mu_static: 2.0,
                mu_kinetic: 2.0,
                max_time: 1.0,
                ..PainleveParams::default()
            }),
            OutcomeKind::Fell,
        ),
        (
            "painleve slides",
            SceneParams::Painleve(PainleveParams {
                mu_static: 1.0,
                mu_kinetic: 1.0,
                max_time: 0.2,
                ..PainleveParams::default()
            }),
            OutcomeKind::Slid,
        ),
    ];
    let mut worst: (f64, f64) = (0.0, 0.0);
    for (name, spec, want) in scenes {
        let r = run_k::<1>(&spec, Implementation::Reference, Record::Nothing).unwrap();
        assert_eq!(r.outcome.class, want, "{name}");
        let (com, angle) = one_contact_matches(name, &spec);
        worst = (worst.0.max(com), worst.1.max(angle));
    }
    println!(
        "largest deviation, f64 core vs reference, cylinder and painleve: {:e} m, {:e} rad",
        worst.0, worst.1
    );
}

/// Three fingers (docs/scenes.md, "three-fingers"): the normal forces of three supports under a
/// rigid rod are statically indeterminate, and with friction `mu` times them the split decides the
/// motion: the LCP has solutions that rest the rod and solutions that let finger 1 drag it (one
/// that unloads finger 2 drags it once `|x1| < x3 mu_k / mu_s`). The reference and the core take
/// the same one by the rule of `docs/formulation.md` ("One answer: the rule"), the least kinetic
/// energy: the rod stays. Asserted for every layout and precision over the default run: the same
/// outcome, and the COM within 1e-9 m (f64) or 1e-5 m (f32) of the reference's, the angle within
/// 1e-9 rad (f64) or 1e-5 rad (f32); the reference flags most steps ambiguous (the rule decides
/// them).
#[test]
fn three_fingers_take_the_rules_answer_in_every_layout_and_precision() {
    let spec = SceneParams::ThreeFingers(ThreeFingersParams::default());
    let r = run_k::<3>(&spec, Implementation::Reference, Record::All).unwrap();
    assert_eq!(r.outcome.class, OutcomeKind::Held);
    assert!(r.counters.ambiguous_steps > r.steps / 2, "{}", r.counters.ambiguous_steps);
    for (precision, tolerance) in [(Precision::F64, 1e-9), (Precision::F32, 1e-5)] {
        for layout in [LcpLayout::Reduced, LcpLayout::Full] {
            let implementation = Implementation::Core(precision, layout);
            let core = run_k::<3>(&spec, implementation, Record::All).unwrap();
            let what = format!("three fingers: {implementation}");
            assert_eq!(core.outcome.class, r.outcome.class, "{what}");
            let (com, angle) = max_deviation(&core, &r);
            let c = &core.counters;
            println!(
                "{what}: COM {com:.1e} m, angle {angle:.1e} rad from the reference; the rule looked at {} \
                 steps, enumerated {}, {} with several answers, changed {} (reference: {} of {} ambiguous)",
                c.rule_checked_steps,
                c.rule_enumerated_steps,
                c.ambiguous_steps,
                c.rule_changed_answer,
                r.counters.ambiguous_steps,
                r.steps
            );
            assert!(com < tolerance && angle < tolerance, "{what}: {com:e} m, {angle:e} rad");
        }
    }
}

/// The meter stick at `mu_s = mu_k = 1000` (as a new user tries it): friction's torque about the
/// rod's centre outweighs the normal rows, and about half the steps have a solution where finger 2
/// holds the rod and one where finger 1 drags it. With the rule (least kinetic energy) every layout
/// and precision meets within 1 mm of the reference's meeting point (without it, f32 6x6 met
/// 1.2 mm away after 641 eq. 21 switches against the reference's 7,490).
#[test]
fn the_meter_stick_at_mu_1000_meets_where_the_reference_does() {
    let p = MeterStickParams { mu_static: 1000.0, mu_kinetic: 1000.0, ..stick(0.1, -0.4, 30.0) };
    let spec = SceneParams::MeterStick(p);
    let r = reference(&spec);
    let reference_meeting = r.measured.meeting.expect("the reference's fingers meet").com_offset_m;
    assert!(r.counters.ambiguous_steps > 1000, "{}", r.counters.ambiguous_steps);
    for precision in [Precision::F64, Precision::F32] {
        for layout in [LcpLayout::Reduced, LcpLayout::Full] {
            let implementation = Implementation::Core(precision, layout);
            let core = run(&spec, implementation, Record::All).unwrap();
            let what = format!("meter stick at mu 1000: {implementation}");
            assert_eq!(core.outcome.class, r.outcome.class, "{what}");
            let meeting = core.measured.meeting.expect("the core's fingers meet").com_offset_m;
            let c = &core.counters;
            println!(
                "{what}: meets at {meeting:.5} m (reference {reference_meeting:.5} m); the rule looked at {} \
                 steps, {} with several answers, changed {} (reference: {} ambiguous)",
                c.rule_checked_steps, c.ambiguous_steps, c.rule_changed_answer, r.counters.ambiguous_steps
            );
            assert!((meeting - reference_meeting).abs() < 1e-3, "{what}: {meeting} vs {reference_meeting}");
        }
    }
}
