//! The meter stick in three dimensions, the core (`meterstick_core::scene::spatial::MeterStick3d`,
//! one friction line per point turned to the slip, Lemke's method) beside the independent
//! reference (`meterstick_reference::spatial::run_meter_stick_3d_keeping`, the circular cone by
//! cases): the same outcome and meeting, the centres of mass step by step (docs/scenes.md,
//! "meter-stick-3d").
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::print_stdout)]

use meterstick_core::scene::Outcome;
use meterstick_core::scene::spatial::{MeterStick3d, MeterStick3dParams};
use meterstick_reference::spatial::{self as reference, Keep};

/// The largest distance between the centres of mass, the steps, and the meetings' offsets.
fn compare(degrees: f64) -> (f64, usize, [Option<f64>; 2]) {
    let params = MeterStick3dParams::<f64> { heading: degrees.to_radians(), ..MeterStick3dParams::default() };
    let p = reference::MeterStick3d { heading: params.heading, ..reference::MeterStick3d::default() };
    let started = std::time::Instant::now();
    let run = reference::run_meter_stick_3d_keeping(&p, Keep::All).expect("the reference runs");
    let reference_time = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let mut core = MeterStick3d::<f64>::new(params).expect("valid");
    let (mut worst, mut worst_velocity) = (0.0_f64, 0.0_f64);
    let mut steps = 0;
    while let Some(report) = core.step() {
        steps += 1;
        let row = run.run.trajectory.get(steps).expect("the reference ran as long");
        let d: f64 = (0..3).map(|k| (report.state.position[k] - row.position[k]).powi(2)).sum::<f64>().sqrt();
        worst = worst.max(d);
        let dv: f64 =
            (0..3).map(|k| (report.state.velocity[k] - row.velocity[k]).powi(2)).sum::<f64>().sqrt();
        worst_velocity = worst_velocity.max(dv);
    }
    let core_time = started.elapsed().as_secs_f64();
    let outcome = core.outcome().expect("ended");
    let expected = match run.run.outcome {
        reference::Outcome::Balanced => Outcome::Balanced,
        reference::Outcome::Fell => Outcome::Fell,
        _ => Outcome::Unfinished,
    };
    assert_eq!(outcome, expected, "{degrees} deg");
    assert_eq!(steps as u64, run.run.steps, "{degrees} deg");
    let meetings = [core.meeting().map(|m| m.com_offset), run.run.measured[1]];
    println!(
        "{degrees} deg: {outcome:?} after {steps} steps; centres of mass within {worst:.1e} m, velocities {worst_velocity:.1e} m/s; meeting offsets {meetings:?}; \
         reference {reference_time:.2} s, core {core_time:.2} s"
    );
    (worst, steps, meetings)
}

/// Both in f64 over about 9,000 steps at the headings of docs/scenes.md's outcomes: the runs
/// differ by round-off alone (measured at most 2.7e-15 m, at 30 deg; the meeting offsets by
/// 5e-16 m), asserted within `1e-12` m.
#[test]
fn the_core_agrees_with_the_reference() {
    for degrees in [0.0, 5.0, 10.0, 20.0, 30.0] {
        let (worst, _, meetings) = compare(degrees);
        assert!(worst <= 1e-12, "{degrees} deg: {worst}");
        match meetings {
            [Some(a), Some(b)] => assert!((a - b).abs() <= 1e-12, "{degrees} deg: {meetings:?}"),
            [None, None] => {}
            _ => panic!("{degrees} deg: {meetings:?}"),
        }
    }
}

/// At 0.3 and 1 deg the runs part by more than round-off, and the reference is the exact one.
/// At 0.3 deg, from step 3,247 (the pad carrying the rod, one of its points at the edge of its
/// cone), the core's answers let that point creep (slip `4e-11` growing to `2.4e-7` m/s, below
/// `stick_speed`, so reported sticking) with its friction at the cone's edge but 0.02 rad off
/// the slip's direction: the core holds a point slipping within the stick speed to its cone
/// alone (`core/src/spatial/mod.rs`, "A restart"); the reference sticks it, its slip nil to
/// `1e-13` and every cone verified, and every combination of cases that meets the cone there
/// moves the rod alike to `5.4e-14` m/s (`reference/src/spatial/meter_stick_tests.rs`): the
/// step's answer is one, and the core's is off it by up to `1.7e-6` m/s. At 1 deg the same at step 8,183 (all three points stopping
/// after the meeting, the core's slips left at up to `7e-6` m/s). Measured: 5.6e-8 m at 0.3 deg,
/// 5e-11 m at 1 deg; asserted within `1e-6` m, the same outcome and steps, the meetings' offsets
/// within `1e-6` m.
#[test]
fn near_the_edge_of_sticking_the_core_creeps_within_the_stick_speed() {
    for degrees in [0.3, 1.0] {
        let (worst, _, meetings) = compare(degrees);
        assert!(worst <= 1e-6, "{degrees} deg: {worst}");
        match meetings {
            [Some(a), Some(b)] => assert!((a - b).abs() <= 1e-6, "{degrees} deg: {meetings:?}"),
            _ => panic!("{degrees} deg: {meetings:?}"),
        }
    }
}
