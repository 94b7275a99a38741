//! Extreme friction (`docs/formulation.md`, "Precision", "Extreme friction: the cone rows
//! weighted"): with `mu_s = mu_k = mu` up to 1e4, f32 reaches f64's outcome on the meter stick, the
//! incline and Painleve's rod in both layouts, with no solver failure, and eq. 21 and the incline's
//! law hold; beyond `mu eps = 2^-9` the run is warned about, naming the friction. Before the cone
//! rows were weighted, f32 failed the meter stick at 1e4 in both layouts (a Lemke ray after 1.2 s)
//! and spread its eq. 21 ratios to 0.92 .. 1.03 at 1e3.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_core::planar::{friction_beyond_precision, friction_limit};
use meterstick_core::scene::OutcomeKind;
use meterstick_host_sim::scenes::{
    Implementation, LcpLayout, Precision, SceneKind, SceneParams, friction_warning,
};
use meterstick_host_sim::trajectory::{Record, Trajectory, run_k, switches};

const MUS: [f64; 3] = [1e2, 1e3, 1e4];

fn spec(kind: SceneKind, mu: f64) -> SceneParams {
    let mut spec = SceneParams::defaults(kind);
    assert!(spec.set("mu_static", mu) && spec.set("mu_kinetic", mu));
    spec
}

fn run<const K: usize>(spec: &SceneParams, precision: Precision, layout: LcpLayout) -> Trajectory<K> {
    run_k::<K>(spec, Implementation::Core(precision, layout), Record::Nothing).unwrap()
}

/// The meter stick balances in f32 as in f64 (the default finger speed 0.1 m/s), with eq. 21's
/// ratio `mu_k / mu_s = 1` at every stick-to-slip switch within 1 %: the discretisation alone puts
/// the reference's ratios at 0.9961..1.0000 at mu 1e3 and 1e4, and f32 with the rule's choices
/// (the steps are ambiguous at `mu_s = mu_k`) reaches 1.0055 at 1e4 in the full layout (before
/// the cone rows were weighted f32 read 2.0 there).
#[test]
fn the_meter_stick_balances_in_f32_as_in_f64_up_to_mu_1e4() {
    for mu in MUS {
        let spec = spec(SceneKind::MeterStick, mu);
        assert_eq!(friction_warning(&spec, Precision::F32), None, "mu {mu} is within f32's limit");
        for layout in [LcpLayout::Reduced, LcpLayout::Full] {
            let f64 = run::<2>(&spec, Precision::F64, layout);
            let f32 = run::<2>(&spec, Precision::F32, layout);
            let what = format!(
                "mu {mu}, {layout:?}: f32 {:?} ({:?}), f64 {:?}",
                f32.outcome.class, f32.outcome.detail, f64.outcome.class
            );
            assert_eq!(f64.outcome.class, OutcomeKind::Balanced, "{what}");
            assert_eq!(f32.outcome.class, f64.outcome.class, "{what}");
            let sw = switches(&f32);
            assert!(sw.len() > 100, "{what}: {} eq. 21 switches", sw.len());
            for s in &sw {
                assert!((s.ratio - 1.0).abs() <= 1e-2, "{what}: eq. 21 ratio {} at t = {}", s.ratio, s.t);
            }
            let (m32, m64) = (f32.measured.meeting.unwrap(), f64.measured.meeting.unwrap());
            let (a, b) = (m32.com_offset_m, m64.com_offset_m);
            assert!((a - b).abs() <= 3e-3, "{what}: met {a} m from the centre of mass, f64 {b} m");
        }
    }
}

/// Over the range the cone rows are weighted and f32 resolves (64 .. 16384, 16 log-spaced values, both
/// layouts) the meter stick balances in f32 and in f64, without a solver failure: at 8000 the f32 6x6
/// once failed near the meeting (Lemke's answer to the weighted rows unverifiable, residual 1.4e-3)
/// before the unweighted rows became the fallback of that solve, and at 1,783 the f64 6x6 failed (a
/// Lemke ray at the meeting) while f64's rows were weighted only from 8192.
#[test]
fn the_meter_stick_balances_in_f32_over_the_weighted_range() {
    for k in 0..16 {
        let mu = 64.0 * 256f64.powf(f64::from(k) / 15.0);
        let spec = spec(SceneKind::MeterStick, mu);
        for layout in [LcpLayout::Reduced, LcpLayout::Full] {
            let f32 = run::<2>(&spec, Precision::F32, layout);
            let f64 = run::<2>(&spec, Precision::F64, layout);
            let what = format!("mu {mu}, {layout:?}: f32 {:?} ({:?})", f32.outcome.class, f32.outcome.detail);
            assert_eq!(f64.outcome.class, OutcomeKind::Balanced, "{what}");
            assert_eq!(f32.outcome.class, OutcomeKind::Balanced, "{what}");
        }
    }
}

/// The incline (35 deg, wide block) holds, as its law says (`tan a <= mu_s`, `tan a < w / h`),
/// and Painleve's rod jams, in f32 as in f64, in both layouts.
#[test]
fn the_incline_holds_and_painleves_rod_jams_in_f32_as_in_f64_up_to_mu_1e4() {
    for mu in MUS {
        for layout in [LcpLayout::Reduced, LcpLayout::Full] {
            let incline = spec(SceneKind::Incline, mu);
            let angle = incline.get("angle").unwrap();
            let (w, h) = (incline.get("width").unwrap(), incline.get("height").unwrap());
            assert!(angle.tan() <= mu && angle.tan() < w / h);
            for precision in [Precision::F32, Precision::F64] {
                let t = run::<2>(&incline, precision, layout);
                assert_eq!(t.outcome.class, OutcomeKind::Held, "incline mu {mu} {layout:?} {precision:?}");
            }
            let painleve = spec(SceneKind::Painleve, mu);
            let f64 = run::<1>(&painleve, Precision::F64, layout);
            let f32 = run::<1>(&painleve, Precision::F32, layout);
            assert_eq!(f64.outcome.class, OutcomeKind::Jammed, "painleve mu {mu} {layout:?}");
            assert_eq!(f32.outcome.class, f64.outcome.class, "painleve mu {mu} {layout:?}");
        }
    }
}

/// Beyond `mu eps = 2^-9` (f32: 16384) the run is warned about, naming the flags and values; f64
/// resolves it.
#[test]
fn friction_beyond_f32_is_warned_about_by_name() {
    assert!((friction_limit::<f32>() - 16384.0).abs() < 1e-9);
    assert!(!friction_beyond_precision::<f32>(16384.0) && friction_beyond_precision::<f32>(16385.0));
    assert!(!friction_beyond_precision::<f64>(8e12) && friction_beyond_precision::<f64>(1e13));
    let spec = spec(SceneKind::MeterStick, 1e5);
    let warning = friction_warning(&spec, Precision::F32).unwrap();
    assert!(
        warning.contains("--mu-s 100000 and --mu-k 100000: friction beyond what f32 resolves"),
        "{warning}"
    );
    assert_eq!(friction_warning(&spec, Precision::F64), None);
}
