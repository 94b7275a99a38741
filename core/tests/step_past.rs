//! `step_past`: a front end (the page) keeps stepping a scene after its outcome, so that the class
//! sees the stack tumble off the table after `Fell`; the outcome stays the one the judge decided
//! and the judged run is the same run, step for step.
#![allow(missing_docs, clippy::expect_used, clippy::float_cmp)]

use meterstick_core::multibody::scenes::{MultibodyScene, Stack3, StackParams};
use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};

#[test]
fn a_stack_past_its_balance_goes_on_falling_after_fell() {
    let params = StackParams::<f32> { overhang: 1.02, ..StackParams::default() };
    let mut stack = Stack3::<f32>::new(params).expect("valid");
    let top0 = stack.states()[2].y;
    let mut judged = stack.clone();
    // Before the outcome `step_past` is `step`.
    while let Some(report) = judged.step() {
        let past = stack.step_past().expect("a step");
        assert_eq!(past.states, report.states);
    }
    assert_eq!(judged.outcome(), Some(Outcome::Fell));
    assert_eq!(stack.outcome(), Some(Outcome::Fell));
    assert!(stack.step().is_none(), "the run has ended");
    // 0.5 s more: the top block falls past the table's edge, the outcome stays.
    for _ in 0..500 {
        let _ = stack.step_past().expect("a step past the outcome");
    }
    assert_eq!(stack.outcome(), Some(Outcome::Fell));
    assert!(top0 - stack.states()[2].y > params.height, "{} -> {}", top0, stack.states()[2].y);
}

#[test]
fn a_rod_that_fell_goes_on_falling() {
    let params = MeterStickParams::<f32> { finger1_velocity: 1.0, ..MeterStickParams::paper() };
    let mut rod = MeterStick6::<f32>::new(params).expect("valid");
    while rod.step().is_some() {}
    assert_eq!(rod.outcome(), Some(Outcome::Fell));
    let (t, y) = (rod.time(), rod.state().y);
    for _ in 0..200 {
        let _ = rod.step_past().expect("a step past the outcome");
    }
    assert_eq!(rod.outcome(), Some(Outcome::Fell));
    assert!(rod.time() > t && rod.state().y < y, "the rod goes on falling");
}
