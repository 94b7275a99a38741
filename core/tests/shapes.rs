//! The meter stick's trajectory checksums (`host-sim scene --scene meter-stick --precision f32|f64
//! --lcp-size 6|8`), held to the recorded values. `scripts/test.sh` runs this file in both of the
//! core's shapes: in the workspace run with the feature `host-tuned` (host-sim turns it on), and
//! in `cargo test -p meterstick-core` without it, the shape the microcontrollers run. Both must
//! give the same bits: the feature moves code, never an operation.
#![allow(missing_docs, clippy::expect_used)]

use meterstick_core::Real;
use meterstick_core::planar::Checksum;
use meterstick_core::scene::{MeterStick8, MeterStickParams, Outcome, Scene};

/// Steps `scene` to its end: its outcome and the checksum of every state after a step.
fn run<T: Real, S: Scene<T, 2>>(mut scene: S) -> (Option<Outcome>, u32) {
    let mut checksum = Checksum::new();
    while let Some(report) = scene.step() {
        checksum.add(&report.state);
    }
    (scene.outcome(), checksum.value())
}

#[test]
#[cfg(feature = "fallback")]
fn f32_reduced_layout_with_fallback() {
    let scene = meterstick_core::scene::MeterStick6::<f32>::new(MeterStickParams::paper())
        .expect("the paper's scene is valid");
    assert_eq!(run(scene), (Some(Outcome::Balanced), 0x1166_94d1));
}

#[test]
fn f32_full_layout() {
    let scene = MeterStick8::<f32>::new(MeterStickParams::paper()).expect("the paper's scene is valid");
    assert_eq!(run(scene), (Some(Outcome::Balanced), 0x5c2a_76bb));
}

#[test]
#[cfg(feature = "fallback")]
fn f64_reduced_layout_with_fallback() {
    let scene = meterstick_core::scene::MeterStick6::<f64>::new(MeterStickParams::paper())
        .expect("the paper's scene is valid");
    assert_eq!(run(scene), (Some(Outcome::Balanced), 0xd512_2c41));
}

#[test]
fn f64_full_layout() {
    let scene = MeterStick8::<f64>::new(MeterStickParams::paper()).expect("the paper's scene is valid");
    assert_eq!(run(scene), (Some(Outcome::Balanced), 0x8eb7_954e));
}
