//! The page's layer against the command line it mirrors (both generated from the core's catalogue,
//! `catalogue/src/lib.rs`): the same refusals (without the `--`), the same resolved parameters and the same trajectory
//! checksum and outcome as `host-sim scene` (on the host; the browser test checks the wasm build).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use meterstick_host_sim::commands::scene::{SceneCmdArgs as SceneCmd, run as run_scene};
use meterstick_host_sim::scenes::SceneArgs;
use meterstick_host_sim::trajectory::{Record, run_k};
use meterstick_web::config::{Config, LcpLayout, Precision};
use meterstick_web::flags::{Catalogued as _, FLAGS, SceneKind, flag_index};
use meterstick_web::session::Session;

/// Flags and their values, in their units.
type Given = &'static [(&'static str, f64)];

/// The same configuration for both: `host-sim scene` options and the page's.
fn both(
    kind: SceneKind,
    given: &[(&str, f64)],
    precision: Precision,
    layout: LcpLayout,
) -> (SceneArgs, Session) {
    let mut args = SceneArgs { scene: Some(kind), precision, layout, ..SceneArgs::default() };
    let mut session = Session::new();
    session.configure(kind);
    for (long, v) in given {
        args.given.push((&FLAGS[flag_index(long).unwrap()], vec![*v]));
        assert!(session.give(flag_index(long).unwrap(), *v));
    }
    (args, session)
}

#[test]
fn refusals_are_worded_as_host_sim_words_them() {
    let cases: &[(SceneKind, Given, Precision)] = &[
        (SceneKind::MeterStick, &[("mu-k", 0.7)], Precision::F32),
        (SceneKind::MeterStick, &[("x1", -0.6)], Precision::F32),
        (SceneKind::MeterStick, &[("x1", 0.3), ("x2", 0.305)], Precision::F32),
        (SceneKind::MeterStick, &[("mass", 0.0)], Precision::F32),
        (SceneKind::MeterStick, &[("finger-width", -1e-3)], Precision::F32),
        (SceneKind::MeterStick, &[("gravity", f64::NAN)], Precision::F64),
        (SceneKind::MeterStick, &[("mass", 1e39)], Precision::F32),
        (SceneKind::MeterStick, &[("h", 1e-12)], Precision::F64),
        (SceneKind::MeterStick, &[("speed", 1.0), ("width", 0.1)], Precision::F32),
        (SceneKind::MeterStick, &[("x1", 1.0 / 3.0), ("x2", 0.1)], Precision::F32),
        (SceneKind::Incline, &[("angle", 95.0)], Precision::F32),
        (SceneKind::Incline, &[("angle", -1.0)], Precision::F64),
        (SceneKind::Incline, &[("speed", 1.0)], Precision::F32),
        (SceneKind::Ladder, &[("angle", 0.0)], Precision::F32),
        (SceneKind::Ladder, &[("mu-wall", -0.1)], Precision::F32),
        (SceneKind::Ladder, &[("mu-s", 0.5)], Precision::F64),
        (SceneKind::ThreeFingers, &[("x3", 0.6)], Precision::F32),
        (SceneKind::ThreeFingers, &[("speed2", 0.1)], Precision::F32),
        (SceneKind::Cylinder, &[("radius", 0.0)], Precision::F64),
        (SceneKind::Cylinder, &[("angle", 90.0)], Precision::F32),
        (SceneKind::Painleve, &[("angle", 0.0)], Precision::F32),
        (SceneKind::Painleve, &[("mu-k", -3.0)], Precision::F64),
    ];
    for (kind, given, precision) in cases {
        let (args, mut session) = both(*kind, given, *precision, LcpLayout::Reduced);
        let theirs = run_scene(&SceneCmd { scene: args }).unwrap_err().to_string();
        let ours = session.create(*precision, LcpLayout::Reduced).unwrap_err().to_string();
        assert_eq!(ours, theirs.replace("--", ""), "{kind:?} {given:?}");
    }
}

#[test]
fn parameters_outcome_and_checksum_match_host_sim_scene() {
    let cases: &[(SceneKind, Given, Precision, LcpLayout)] = &[
        (SceneKind::MeterStick, &[("x1", -0.35)], Precision::F32, LcpLayout::Reduced),
        (SceneKind::MeterStick, &[("x1", -0.35), ("speed", 0.5)], Precision::F32, LcpLayout::Full),
        (SceneKind::MeterStick, &[("speed", 0.05), ("speed2", -0.05)], Precision::F64, LcpLayout::Reduced),
        (SceneKind::MeterStick, &[("speed", 0.02), ("duration", 3.0)], Precision::F32, LcpLayout::Reduced),
        (
            SceneKind::Incline,
            &[("angle", 20.0), ("width", 0.05), ("height", 0.2)],
            Precision::F32,
            LcpLayout::Reduced,
        ),
        (SceneKind::Incline, &[], Precision::F64, LcpLayout::Full),
        (
            SceneKind::Ladder,
            &[("angle", 60.0), ("mu-floor", 0.0), ("mu-wall", 0.0)],
            Precision::F32,
            LcpLayout::Reduced,
        ),
        (SceneKind::ThreeFingers, &[], Precision::F32, LcpLayout::Reduced),
        (SceneKind::ThreeFingers, &[("speed", 0.5), ("duration", 3.0)], Precision::F64, LcpLayout::Full),
        (SceneKind::Cylinder, &[], Precision::F32, LcpLayout::Reduced),
        (SceneKind::Cylinder, &[("angle", 70.0)], Precision::F64, LcpLayout::Full),
        (SceneKind::Painleve, &[], Precision::F32, LcpLayout::Reduced),
        (SceneKind::Painleve, &[("mu-s", 1.0), ("mu-k", 1.0)], Precision::F64, LcpLayout::Full),
        (SceneKind::Painleve, &[("angle", 60.0), ("mu-k", 2.0)], Precision::F32, LcpLayout::Full),
    ];
    for (kind, given, precision, size) in cases {
        let (args, mut session) = both(*kind, given, *precision, *size);
        let (_, spec) = args.specs(None).unwrap().remove(0);
        let implementation = args.implementation();
        session.create(*precision, *size).unwrap();
        let ours = session.spec().unwrap();
        for (i, (name, value)) in spec.fields().enumerate() {
            assert_eq!(ours.field(i).map(f64::to_bits), Some(value.to_bits()), "{kind:?} {name}");
        }
        let text = run_scene(&SceneCmd { scene: args }).unwrap();
        let sim = session.sim_mut().unwrap();
        sim.run(u64::MAX);
        let outcome = sim.outcome().unwrap().to_string();
        assert!(
            text.contains(&format!(": outcome {outcome} at t = ")),
            "{kind:?} {given:?}: {outcome}\n{text}"
        );
        assert!(text.contains(&format!("checksum {:08x}", sim.checksum())), "{kind:?} {given:?}\n{text}");
        // The measured quantities, named by the catalogue as `summary.json` names them.
        let summary = measured_by_host_sim(*kind, &spec, implementation);
        let measured = sim.measured();
        let names = kind.info().measures;
        for (name, ours) in names.iter().zip(measured) {
            let theirs = name.split('.').fold(&summary, |v, key| &v[key]);
            let theirs = theirs.as_f64().unwrap_or(f64::NAN);
            assert_eq!(ours.to_bits(), theirs.to_bits(), "{kind:?} {given:?} {name}: {ours} vs {summary}");
        }
        assert!(measured[names.len()..].iter().all(|m| m.is_nan()), "{kind:?}: {measured:?}");
    }
}

/// The scenes in three dimensions (the module `meterstick_web_sp.wasm`, feature `sp`): the same
/// parameters, outcome and checksum as `host-sim scene`, in both precisions and both friction cones
/// (the page holds the puck and the ball in the curling stone's LCP capacity, `SpatialViews`).
#[test]
fn a_scene_in_three_dimensions_ends_as_host_sim_scene() {
    let cases: &[(SceneKind, Given, Precision)] = &[
        (SceneKind::Puck, &[], Precision::F32),
        (SceneKind::Puck, &[], Precision::F64),
        (
            SceneKind::Puck,
            &[("angle", 20.0), ("mu-k", 0.3), ("speed", 0.9), ("heading", 15.0)],
            Precision::F32,
        ),
        (SceneKind::Puck, &[("friction-directions", 8.0)], Precision::F32),
        (SceneKind::Billiard, &[], Precision::F32),
        (SceneKind::Billiard, &[("friction-directions", 4.0)], Precision::F64),
        (SceneKind::Curling, &[], Precision::F32),
        (SceneKind::Curling, &[], Precision::F64),
        (SceneKind::MeterStick3d, &[], Precision::F32),
        (SceneKind::MeterStick3d, &[], Precision::F64),
    ];
    for (kind, given, precision) in cases {
        let (args, mut session) = both(*kind, given, *precision, LcpLayout::Reduced);
        let (_, spec) = args.specs(None).unwrap().remove(0);
        session.create(*precision, LcpLayout::Reduced).unwrap();
        let ours = session.spec().unwrap();
        for (i, (name, value)) in spec.fields().enumerate() {
            assert_eq!(ours.field(i).map(f64::to_bits), Some(value.to_bits()), "{kind:?} {name}");
        }
        let text = run_scene(&SceneCmd { scene: args }).unwrap();
        let sim = session.sim_mut().unwrap();
        assert_eq!(sim.row_len(), meterstick_web::spatial::SPATIAL_ROW, "{kind:?}");
        sim.run(u64::MAX);
        let outcome = sim.outcome().unwrap().to_string();
        assert!(
            text.contains(&format!(": outcome {outcome} at t = ")),
            "{kind:?} {given:?} {precision:?}: {outcome}\n{text}"
        );
        assert!(
            text.contains(&format!("checksum {:08x}", sim.checksum())),
            "{kind:?} {given:?} {precision:?}: {:08x}\n{text}",
            sim.checksum()
        );
    }
}

#[test]
fn a_config_gives_each_flag_once() {
    let mut c = Config::new(SceneKind::MeterStick);
    assert!(c.give(flag_index("speed").unwrap(), 0.2));
    assert!(c.give(flag_index("speed").unwrap(), 0.3));
    assert!(!c.give(FLAGS.len(), 1.0));
    let spec = c.resolve(Precision::F32).unwrap();
    assert_eq!(
        spec.get("finger1_velocity"),
        Some(0.3),
        "the last value given counts, as on the command line"
    );
}

#[test]
#[allow(clippy::float_cmp)] // exact: the same computation, the bits compared
fn a_run_of_several_bodies_through_the_exports_ends_as_host_sims_core_run() {
    use meterstick_host_sim::bodies::run_core;
    use meterstick_web::{
        ms_configure, ms_create, ms_give, ms_outcome, ms_start_row, ms_step, ms_time, trace_row,
    };
    let cases: &[(SceneKind, Given, Precision)] = &[
        (SceneKind::Tablecloth, &[], Precision::F32),
        (SceneKind::Tablecloth, &[("force", 2.0)], Precision::F64),
        (SceneKind::BlockOnBlock, &[], Precision::F32),
        (SceneKind::BlockOnBlock, &[("force", 5.0)], Precision::F64),
        (SceneKind::Stack, &[("blocks", 2.0)], Precision::F32),
        (SceneKind::Stack, &[("overhang", 1.5)], Precision::F64),
        (SceneKind::DiscOnBoard, &[], Precision::F32),
        (SceneKind::DiscOnBoard, &[("force", 40.0), ("mu-s", 0.3), ("mu-k", 0.2)], Precision::F64),
    ];
    for (kind, given, precision) in cases {
        let scene = SceneKind::ALL.iter().position(|k| k == kind).unwrap();
        assert_eq!(ms_configure(u32::try_from(scene).unwrap()), 0);
        for (long, v) in *given {
            assert_eq!(ms_give(u32::try_from(flag_index(long).unwrap()).unwrap(), *v), 0);
        }
        let bits = if *precision == Precision::F32 { 32 } else { 64 };
        assert_eq!(ms_create(bits, 8), 0, "{kind:?} {given:?}");
        assert_eq!(ms_start_row(), 1);
        let (mut steps, mut last) = (0_u64, trace_row(0, 10));
        loop {
            let n = ms_step(2048);
            if n == 0 {
                break;
            }
            steps += u64::from(n);
            last = trace_row(n as usize - 1, 10);
        }
        // host-sim's own resolution of the same flags, and its core run.
        let (args, _) = both(*kind, given, *precision, LcpLayout::Reduced);
        let (_, spec) = args.specs(None).unwrap().remove(0);
        let theirs = run_core(&spec, *precision, false, None).unwrap();
        let ours = meterstick_web::sim::OUTCOMES[usize::try_from(ms_outcome()).unwrap()];
        assert_eq!(ours, theirs.outcome.class.name(), "{kind:?} {given:?}");
        assert_eq!((steps, last[0]), (theirs.steps, theirs.end_time), "{kind:?} {given:?}");
        assert_eq!(ms_time(), theirs.end_time);
        for (b, q) in theirs.last.q.iter().enumerate() {
            assert_eq!(&last[1 + 3 * b..4 + 3 * b], q, "{kind:?} {given:?} body {b}");
        }
        assert!(last[1 + 3 * theirs.last.q.len()..].iter().all(|v| v.is_nan()), "no further bodies");
    }
}

#[test]
fn a_run_of_several_bodies_gives_its_shapes() {
    use meterstick_web::{ms_body_round, ms_body_size, ms_configure, ms_create, ms_table_end};
    let stack = SceneKind::ALL.iter().position(|k| *k == SceneKind::Stack).unwrap();
    assert_eq!(ms_configure(u32::try_from(stack).unwrap()), 0);
    assert_eq!(ms_create(64, 6), 0);
    // Three blocks of the defaults, 0.2 m x 0.05 m, on a table with one edge.
    for b in 0..3 {
        assert_eq!((ms_body_size(b, 0), ms_body_size(b, 1)), (0.2, 0.05), "block {b}");
    }
    assert!(ms_body_size(3, 0).is_nan() && ms_body_size(0, 2).is_nan());
    assert_eq!(u8::from(ms_table_end(0).is_nan()) + u8::from(ms_table_end(1).is_nan()), 1, "one edge");
    assert_eq!([0_u32, 1, 2, 3].map(|b| ms_body_round(b)), [0; 4], "boxes");
    // Disc-on-board: a board of 1 m x 0.02 m on a floor, a disc of radius 0.05 m on it.
    let disc = SceneKind::ALL.iter().position(|k| *k == SceneKind::DiscOnBoard).unwrap();
    assert_eq!(ms_configure(u32::try_from(disc).unwrap()), 0);
    assert_eq!(ms_create(32, 6), 0);
    assert_eq!(
        [0, 1].map(|b| [ms_body_size(b, 0), ms_body_size(b, 1)]),
        [[1.0, 0.02f32.into()], [0.1f32.into(); 2]]
    );
    assert_eq!([0_u32, 1, 2].map(|b| ms_body_round(b)), [0, 1, 0], "the board a box, the disc round");
    assert!(ms_table_end(0).is_nan() && ms_table_end(1).is_nan(), "a floor without ends");
}

/// `host-sim`'s measured quantities of `spec` as `summary.json` names them (a scene of one body:
/// the page's are compared with the recorded run's).
fn measured_by_host_sim(
    kind: SceneKind,
    spec: &meterstick_host_sim::scenes::SceneParams,
    implementation: meterstick_host_sim::scenes::Implementation,
) -> serde_json::Value {
    let run = || -> Result<serde_json::Value, Box<dyn std::error::Error + Send + Sync>> {
        Ok(meterstick_host_sim::with_contacts!(kind, K => {
            let host = run_k::<K>(spec, implementation, Record::Nothing)?;
            serde_json::to_value(host.measured)?
        }))
    };
    run().unwrap_or_else(|e| panic!("{kind:?}: {e}"))
}
