//! `go_on`: a front end (the page) keeps stepping a copy of a scene after its outcome, so that the
//! class sees the stack tumble off the table after `Fell`; the judged run is untouched (it is the
//! same run, step for step, up to its outcome).
#![allow(missing_docs, clippy::expect_used, clippy::float_cmp)]

use meterstick_core::multibody::scenes::{MultibodyScene, Stack3, StackParams};
use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};

#[test]
fn a_stack_past_its_balance_goes_on_falling_after_fell() {
    let params = StackParams::<f32> { overhang: 1.02, ..StackParams::default() };
    let mut stack = Stack3::<f32>::new(params).expect("valid");
    let top0 = stack.states()[2].y;
    assert_eq!(stack.go_on(), None, "nothing to take before the outcome");
    while stack.step().is_some() {}
    assert_eq!(stack.outcome(), Some(Outcome::Fell));
    assert!(stack.step().is_none(), "the run has ended");
    let mut past = stack.clone();
    // 0.5 s more: the top block falls past the table's edge.
    for _ in 0..500 {
        let _ = past.go_on();
        assert!(past.step().is_some(), "a step past the outcome");
    }
    assert!(top0 - past.states()[2].y > params.height, "{} -> {}", top0, past.states()[2].y);
    assert_eq!(stack.outcome(), Some(Outcome::Fell), "the judged run is untouched");
}

#[test]
fn a_rod_that_fell_goes_on_falling() {
    let params = MeterStickParams::<f32> { finger1_velocity: 1.0, ..MeterStickParams::paper() };
    let mut rod = MeterStick6::<f32>::new(params).expect("valid");
    while rod.step().is_some() {}
    assert_eq!(rod.outcome(), Some(Outcome::Fell));
    let (t, y) = (rod.time(), rod.state().y);
    for _ in 0..200 {
        assert_eq!(rod.go_on(), Some(Outcome::Fell), "judged Fell again after each step");
        assert!(rod.step().is_some());
    }
    assert!(rod.time() > t && rod.state().y < y, "the rod goes on falling");
}
