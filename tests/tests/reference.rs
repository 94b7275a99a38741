//! The core against the independent f64 reference (`host-sim`'s `reference`, which enumerates
//! complementary bases and shares no code with the core's solver, assembly or stepper).
//!
//! Tolerances:
//! * **f64 core vs reference**: both solve the same LCP each step to round-off (~1e-16 relative),
//!   so with the same modes the trajectories differ by round-off only (measured: <= 2e-15 m,
//!   <= 2e-14 rad over whole runs). Asserted: same steps, outcome and switch events, and
//!   1e-9 m / 1e-9 rad, a margin for other platforms' `sin`/`cos`.
//! * **f32 core vs reference**: f32 positions carry ~6e-8 m of rounding per step, and a mode
//!   switch may come one step earlier or later, which moves the rod relative to its f64 path
//!   by at most the finger's travel in one step, `v h`, per switch. Asserted: the same outcome,
//!   COM within `3 v h + 1e-5` m, angle within 1e-4 rad (measured: 1.0e-4 m at v = 0.1 with
//!   8x8, 1.3e-4 m at v = 5; angles <= 6e-6 rad), meeting offsets within 0.5 mm, eq. 21
//!   ratios within `1.5 v h / x_start + 0.002` (a switch one step later moves `x_stop` by `v h`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::scene::SceneParams;
use meterstick_host_sim::reference::Reference;
use meterstick_host_sim::trajectory::{Record, Trajectory, max_deviation, run_core, switches};

fn scene(v: f64, x1: f64, duration: f64) -> SceneParams<f64> {
    SceneParams { finger_speed: v, finger1_x: x1, max_time: duration, ..SceneParams::paper() }
}

fn reference(p: &SceneParams<f64>) -> Trajectory {
    Reference::new(*p).unwrap().run(Record::All)
}

fn assert_same_events(core: &Trajectory, reference: &Trajectory) {
    assert_eq!(core.events.len(), reference.events.len(), "{} vs reference", core.label);
    for (a, b) in core.events.iter().zip(&reference.events) {
        assert_eq!((a.finger, a.mode), (b.finger, b.mode), "{a:?} vs {b:?}");
        assert!((a.t - b.t).abs() < 1e-9, "{a:?} vs {b:?}");
    }
}

#[test]
fn f64_core_matches_the_reference_to_round_off() {
    for (v, x1, duration) in [(0.1, -0.35, 30.0), (0.5, -0.4, 30.0), (5.0, -0.4, 30.0), (0.1, -0.4, 2.0)] {
        let p = scene(v, x1, duration);
        let r = reference(&p);
        for core in
            [run_core::<f64, 8>(&p, Record::All).unwrap(), run_core::<f64, 6>(&p, Record::All).unwrap()]
        {
            let what = format!("{} at v = {v}, x1 = {x1}", core.label);
            assert_eq!(core.steps, r.steps, "{what}");
            assert_eq!(core.outcome, r.outcome, "{what}");
            assert_same_events(&core, &r);
            let (com, angle) = max_deviation(&core, &r);
            assert!(com < 1e-9 && angle < 1e-9, "{what}: {com:e} m, {angle:e} rad");
            let (mc, mr) = (core.meeting.map(|m| m.1), r.meeting.map(|m| m.1));
            assert_eq!(mc.is_some(), mr.is_some(), "{what}");
            if let (Some(a), Some(b)) = (mc, mr) {
                assert!((a - b).abs() < 1e-9, "{what}: meeting {a} vs {b}");
            }
        }
    }
}

#[test]
fn f32_core_matches_the_reference_within_one_step_of_travel() {
    for (v, x1) in [(0.1, -0.35), (0.1, -0.4), (5.0, -0.4)] {
        let p = scene(v, x1, 30.0);
        let r = reference(&p);
        for core in
            [run_core::<f32, 6>(&p, Record::All).unwrap(), run_core::<f32, 8>(&p, Record::All).unwrap()]
        {
            let what = format!("{} at v = {v}, x1 = {x1}", core.label);
            assert_eq!(core.outcome, r.outcome, "{what}");
            let (com, angle) = max_deviation(&core, &r);
            assert!(com <= 3.0 * v * p.step + 1e-5, "{what}: COM deviation {com:e} m");
            assert!(angle <= 1e-4, "{what}: angle deviation {angle:e} rad");
            let (a, b) = (core.meeting.unwrap().1, r.meeting.unwrap().1);
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
    let p = scene(0.1, -0.35, 30.0);
    let r = reference(&p);
    assert_eq!(r.outcome.class(), "Balanced");
    assert!(r.meeting.unwrap().1.abs() < 3e-3, "{:?}", r.meeting); // bound: tests/scene.rs MEETING_BOUND
    let sw = switches(&r);
    assert!(sw.len() >= 4, "{sw:?}");
    for s in &sw {
        assert!((s.ratio / (0.4 / 0.6) - 1.0).abs() < 0.02, "{s:?}");
    }
    // Fast finger: the rod falls.
    assert_eq!(reference(&scene(5.0, -0.4, 30.0)).outcome.class(), "Fell");
    // Its LCP choice was never ambiguous in these scenes.
    assert_eq!(r.counters.ambiguous_steps, 0);
}

#[test]
fn the_reference_rejects_invalid_parameters() {
    let mut p = SceneParams::<f64>::paper();
    p.step = 0.0;
    let e = Reference::new(p).unwrap_err().to_string();
    assert!(e.contains("step must be positive"), "{e}");
}
