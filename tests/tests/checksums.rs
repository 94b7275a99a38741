//! The trajectory checksums of every scene's default run, in f32 and f64, in its reduced and its
//! full layout: 24 committed values. A change to the core that moves one bit of one step of these
//! runs fails here, naming the run; a change meant to move them updates the table in the same
//! commit, and its message says why. The firmware under QEMU, the page and `host-sim scene` print
//! the same checksums (`tests/tests/qemu.rs`, `tests/tests/browser.rs`).
#![allow(clippy::expect_used)]

use meterstick_core::Real;
use meterstick_core::planar::Checksum;
use meterstick_core::scene::{
    Cylinder, CylinderParams, Incline, InclineParams, Ladder, LadderParams, MeterStick, MeterStickParams,
    OutcomeKind, Painleve, PainleveParams, Scene, ThreeFingers, ThreeFingersParams,
};

/// Runs `scene` to its outcome: the outcome and the checksum of every step's state.
fn checksum<T: Real, S: Scene<T, K>, const K: usize>(mut scene: S) -> (OutcomeKind, u32) {
    let mut sum = Checksum::new();
    let outcome = scene.run(|report| sum.add(&report.state));
    (outcome.kind(), sum.value())
}

/// A scene's default run: its outcome and checksum.
type Run = (OutcomeKind, u32);

/// The default run of each scene in scalar `T`, as `host-sim scene` makes it (the parameters
/// are given in f64 and cast): (scene, layout, outcome, checksum), the reduced layout first.
fn runs<T: Real>() -> Vec<(&'static str, &'static str, Run)> {
    fn valid(r: Result<Run, meterstick_core::ParamError>) -> Run {
        r.expect("the default parameters are valid")
    }
    let m = MeterStickParams::<f64>::default().cast::<T>();
    let i = InclineParams::<f64>::default().cast::<T>();
    let l = LadderParams::<f64>::default().cast::<T>();
    let t = ThreeFingersParams::<f64>::default().cast::<T>();
    let c = CylinderParams::<f64>::default().cast::<T>();
    let p = PainleveParams::<f64>::default().cast::<T>();
    vec![
        ("meter-stick", "reduced", valid(MeterStick::<T, 6, 0>::new(m).map(checksum))),
        ("meter-stick", "full", valid(MeterStick::<T, 8, 0>::new(m).map(checksum))),
        ("incline", "reduced", valid(Incline::<T, 6, 0>::new(i).map(checksum))),
        ("incline", "full", valid(Incline::<T, 8, 0>::new(i).map(checksum))),
        ("ladder", "reduced", valid(Ladder::<T, 6, 0>::new(l).map(checksum))),
        ("ladder", "full", valid(Ladder::<T, 8, 0>::new(l).map(checksum))),
        ("three-fingers", "reduced", valid(ThreeFingers::<T, 9, 0>::new(t).map(checksum))),
        ("three-fingers", "full", valid(ThreeFingers::<T, 12, 0>::new(t).map(checksum))),
        ("cylinder", "reduced", valid(Cylinder::<T, 3, 0>::new(c).map(checksum))),
        ("cylinder", "full", valid(Cylinder::<T, 4, 0>::new(c).map(checksum))),
        ("painleve", "reduced", valid(Painleve::<T, 3, 0>::new(p).map(checksum))),
        ("painleve", "full", valid(Painleve::<T, 4, 0>::new(p).map(checksum))),
    ]
}

/// The committed values: (scene, precision, layout, outcome, checksum).
const EXPECTED: [(&str, &str, &str, OutcomeKind, u32); 24] = [
    ("meter-stick", "f32", "reduced", OutcomeKind::Balanced, 0x1166_94d1),
    ("meter-stick", "f32", "full", OutcomeKind::Balanced, 0x5c2a_76bb),
    ("incline", "f32", "reduced", OutcomeKind::Slid, 0x3639_107d),
    ("incline", "f32", "full", OutcomeKind::Slid, 0x3639_107d),
    ("ladder", "f32", "reduced", OutcomeKind::Fell, 0x7338_2558),
    ("ladder", "f32", "full", OutcomeKind::Fell, 0x7338_2558),
    // The rule (docs/formulation.md, "One answer: the rule") replaced 5 drag answers by the rod at rest.
    ("three-fingers", "f32", "reduced", OutcomeKind::Held, 0x6dce_cf03),
    ("three-fingers", "f32", "full", OutcomeKind::Held, 0x6dc8_b745),
    ("cylinder", "f32", "reduced", OutcomeKind::Rolled, 0xd21b_e56d),
    ("cylinder", "f32", "full", OutcomeKind::Rolled, 0xd21b_e56d),
    ("painleve", "f32", "reduced", OutcomeKind::Jammed, 0x7c0c_4e0e),
    ("painleve", "f32", "full", OutcomeKind::Jammed, 0x7c0c_4e0e),
    ("meter-stick", "f64", "reduced", OutcomeKind::Balanced, 0xd512_2c41),
    ("meter-stick", "f64", "full", OutcomeKind::Balanced, 0x8eb7_954e),
    ("incline", "f64", "reduced", OutcomeKind::Slid, 0x1d90_b360),
    ("incline", "f64", "full", OutcomeKind::Slid, 0x1d90_b360),
    ("ladder", "f64", "reduced", OutcomeKind::Fell, 0xcc34_48f9),
    ("ladder", "f64", "full", OutcomeKind::Fell, 0xcc34_48f9),
    // The rule replaced 1 drag answer by the rod at rest (docs/formulation.md, "One answer: the rule").
    ("three-fingers", "f64", "reduced", OutcomeKind::Held, 0x53f1_a6b8),
    ("three-fingers", "f64", "full", OutcomeKind::Held, 0x8389_6971),
    ("cylinder", "f64", "reduced", OutcomeKind::Rolled, 0xb15a_a97a),
    ("cylinder", "f64", "full", OutcomeKind::Rolled, 0xb15a_a97a),
    ("painleve", "f64", "reduced", OutcomeKind::Jammed, 0x0c99_3a39),
    ("painleve", "f64", "full", OutcomeKind::Jammed, 0x0c99_3a39),
];

#[test]
fn every_default_run_keeps_its_checksum() {
    let got: Vec<_> = runs::<f32>()
        .into_iter()
        .map(|(s, l, r)| (s, "f32", l, r))
        .chain(runs::<f64>().into_iter().map(|(s, l, r)| (s, "f64", l, r)))
        .collect();
    assert_eq!(got.len(), EXPECTED.len());
    let mut moved = Vec::new();
    for ((scene, precision, layout, (outcome, sum)), want) in got.into_iter().zip(EXPECTED) {
        assert_eq!((scene, precision, layout), (want.0, want.1, want.2), "the table's order");
        if (outcome, sum) != (want.3, want.4) {
            moved.push(format!(
                "{scene} {precision} {layout}: {outcome:?} {sum:08x}, committed {:?} {:08x}",
                want.3, want.4
            ));
        }
    }
    assert!(moved.is_empty(), "trajectories moved:\n{}", moved.join("\n"));
}
