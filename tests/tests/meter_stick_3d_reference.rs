//! The meter stick in three dimensions, the core (`meterstick_core::scene::spatial::MeterStick3d`,
//! one friction line per point turned to the slip, Lemke's method) beside the independent
//! reference (`meterstick_reference::spatial::run_meter_stick_3d_keeping`, the circular cone by
//! cases): the same outcome and meeting, the centres of mass step by step (docs/scenes.md,
//! "meter-stick-3d").
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout)]

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
    let mut worst = 0.0_f64;
    let mut steps = 0;
    while let Some(report) = core.step() {
        steps += 1;
        let row = run.run.trajectory.get(steps).expect("the reference ran as long");
        let d: f64 = (0..3).map(|k| (report.state.position[k] - row.position[k]).powi(2)).sum::<f64>().sqrt();
        worst = worst.max(d);
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
        "{degrees} deg: {outcome:?} after {steps} steps; centres of mass within {worst:.1e} m; meeting offsets {meetings:?}; \
         reference {reference_time:.2} s, core {core_time:.2} s"
    );
    (worst, steps, meetings)
}

#[test]
fn the_core_agrees_with_the_reference() {
    for degrees in [0.0, 5.0, 10.0, 20.0, 30.0] {
        let (worst, _, meetings) = compare(degrees);
        assert!(worst <= 1e-9, "{degrees} deg: {worst}");
        match meetings {
            [Some(a), Some(b)] => assert!((a - b).abs() <= 1e-9, "{degrees} deg: {meetings:?}"),
            [None, None] => {}
            _ => panic!("{degrees} deg: {meetings:?}"),
        }
    }
}
