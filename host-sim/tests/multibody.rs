//! The `host-sim` binary on the scenes of several bodies (`docs/scenes.md`, "Scenes of several
//! bodies"): `run` and `scene` take them, their outcomes and measures agree with the laws written
//! out here from `docs/scenes.md` on each side of every threshold, the core agrees with the
//! independent reference, a refused flag names itself, and the drivers that do not run them yet
//! refuse them before any work; `scene` prints the firmware's checksum, `run` draws the bodies'
//! motion, and `map` draws block-on-block's and disc-on-board's regions where the laws put them.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;
use common::host_sim_within;

const G: f64 = 9.81;

fn host_sim(args: &[&str]) -> (i32, String, String) {
    host_sim_within(args, &[], 300)
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("meterstick-multibody-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `host-sim run --scene <scene> <args> --precision f64`: its `summary.json`, after checking the
/// core and the reference ended alike, the trajectory files hold every step of every body and of
/// every pair (its interface force and four candidates' loads), and the summary the last step's
/// loads.
fn run(scene: &str, name: &str, args: &[&str]) -> serde_json::Value {
    let out = temp_dir(name);
    let mut all = vec!["run", "--scene", scene, "--precision", "f64", "--out", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let (code, stdout, err) = host_sim(&all);
    assert_eq!(code, 0, "{all:?}: {err}");
    let dir = out.join(scene);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["scene"], scene);
    assert_eq!(s["core"]["outcome"], s["reference"]["outcome"], "{all:?}: {stdout}");
    let bodies = s["parameters"]["blocks"].as_f64().map_or(2, |b| b as usize);
    // Each body on the one below; the tablecloth's block also on the floor.
    let pairs = if scene == "tablecloth" { 3 } else { bodies };
    for file in ["core.csv", "reference.csv"] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        assert_eq!(header.len(), 1 + 6 * bodies + (2 + 4 * 2) * pairs, "{file}");
        assert_eq!(
            header[1 + 6 * bodies..][..4],
            ["pair0_fx", "pair0_fy", "pair0_c0_normal", "pair0_c0_friction"]
        );
        let who = if file == "core.csv" { "core" } else { "reference" };
        assert_eq!(lines.count() as u64, s[who]["steps"].as_u64().unwrap() + 1, "{file}");
        assert_eq!(s[who]["interface_forces_n"].as_array().unwrap().len(), pairs, "{who}");
        assert_eq!(s[who]["corner_loads_n"].as_array().unwrap().len(), pairs, "{who}");
    }
    std::fs::remove_dir_all(&out).unwrap();
    s
}

fn measured(s: &serde_json::Value, who: &str, key: &str) -> f64 {
    s[who]["measured"][key].as_f64().unwrap_or_else(|| panic!("{who} {key}: {s}"))
}

/// Block-on-block at its defaults (`m = 1`, `M = 2`, `mu_s = 0.5`, `mu_k = 0.4`, `mu_floor =
/// 0.2`): held up to `mu_floor (M + m) g`, riding at `F / (M + m) - mu_floor g` up to
/// `(mu_s + mu_floor) (M + m) g`, the top block sliding at `mu_k g` above it while the bottom one
/// accelerates at `(F - mu_k m g - mu_floor (M + m) g) / M`; a tall top block tips when riding
/// needs more than `g w / h`.
#[test]
fn block_on_block_holds_rides_and_slides_as_the_laws_say() {
    let (m, big_m, mu_s, mu_k, mu_floor) = (1.0, 2.0, 0.5, 0.4, 0.2);
    let held = mu_floor * (big_m + m) * G;
    let sliding = (mu_s + mu_floor) * (big_m + m) * G;
    for (force, outcome) in
        [(0.98 * held, "Held"), (1.02 * held, "Rode"), (0.98 * sliding, "Rode"), (1.02 * sliding, "Slid")]
    {
        let s = run("block-on-block", "bob", &["--force", &force.to_string()]);
        assert_eq!(s["core"]["outcome"], outcome, "F = {force}: {s}");
        let (a_bottom, a_top) = match outcome {
            "Held" => (0.0, 0.0),
            "Rode" => (force / (big_m + m) - mu_floor * G, force / (big_m + m) - mu_floor * G),
            _ => ((force - mu_k * m * G - mu_floor * (big_m + m) * G) / big_m, mu_k * G),
        };
        for who in ["core", "reference"] {
            let (bottom, top) =
                (measured(&s, who, "acceleration_m_s2"), measured(&s, who, "top_acceleration_m_s2"));
            assert!((bottom - a_bottom).abs() < 1e-6 && (top - a_top).abs() < 1e-6, "{who} F = {force}: {s}");
        }
        assert!(s["comparison"]["max_position_deviation_m"].as_f64().unwrap() < 1e-6, "{s}");
    }
    // A tall top block (w = 0.05, h = 0.2: w / h < mu_s) tips before it slides, once riding
    // needs more than g w / h: above (M + m) (g w / h + mu_floor g).
    let tipping = (big_m + m) * (G * 0.05 / 0.2 + mu_floor * G);
    for (force, outcome) in [(0.97 * tipping, "Rode"), (1.03 * tipping, "Tipped")] {
        let tall = ["--width", "0.05", "--height", "0.2", "--duration", "1"];
        let s = run("block-on-block", "bob", &[&tall[..], &["--force", &force.to_string()]].concat());
        assert_eq!(s["core"]["outcome"], outcome, "F = {force}: {s}");
    }
    // `host-sim scene` says the same, beside the law.
    let (code, stdout, err) = host_sim(&["scene", "--scene", "block-on-block", "--force", "10"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.contains("core f32: outcome Rode at t = 0.300 s") && stdout.contains("law: Rode"),
        "{stdout}"
    );
}

/// The tablecloth (`m_b = 0.2`, `m = 0.5`, `mu_floor = 0.3`, `mu_s = 0.5`): held up to
/// `mu_floor (m + m_b) g`, riding up to `(mu_s + mu_floor) (m + m_b) g`; above it the board comes
/// out and the block stays, displaced within `docs/scenes.md`'s bounds, less the harder the pull.
#[test]
fn the_tablecloth_holds_rides_and_stays_as_the_laws_say() {
    let (m_b, t_b, m, w, offset, mu_s, mu_k, mu_floor) = (0.2, 0.005, 0.5, 0.05, 0.1, 0.5, 0.4, 0.3);
    let held = mu_floor * (m + m_b) * G;
    let riding = (mu_s + mu_floor) * (m + m_b) * G;
    for (force, outcome) in [(0.98 * held, "Held"), (1.02 * held, "Rode"), (0.98 * riding, "Rode")] {
        let s = run("tablecloth", "cloth", &["--force", &force.to_string(), "--duration", "0.3"]);
        assert_eq!(s["core"]["outcome"], outcome, "F = {force}: {s}");
        // Riding, the block moves with the board: (F / (m + m_b) - mu_floor g) t^2 / 2 over 0.3 s.
        let a = if outcome == "Held" { 0.0 } else { force / (m + m_b) - mu_floor * G };
        for who in ["core", "reference"] {
            let x = measured(&s, who, "block_displacement_m");
            let law = a * 0.3 * 0.3 / 2.0;
            // Within the step's share (h / t = 1/300) of it: the steps sum to a h^2 n (n + 1) / 2.
            assert!((x - law).abs() <= 5e-3 * law + 1e-9, "{who} F = {force}: {x}, law {law}: {s}");
        }
    }
    let stop = |v: f64| v.max(0.0).powi(2) / (2.0 * mu_floor * G);
    let mut last = f64::INFINITY;
    for force in [1.5 * riding, 20.0, 40.0] {
        let s = run("tablecloth", "cloth", &["--force", &force.to_string()]);
        assert_eq!(s["core"]["outcome"], "Stayed", "F = {force}: {s}");
        let a_rel = (force - mu_k * m * G - mu_floor * (m + m_b) * G) / m_b - mu_k * G;
        let x = |s: f64| mu_k * G * s / a_rel;
        let v = |s: f64| mu_k * G * (2.0 * s / a_rel).sqrt();
        let low = x(offset) + stop(v(offset) - mu_floor * (2.0 * G * t_b).sqrt());
        let high = x(offset + w) + v(offset + w) * (2.0 * t_b / G).sqrt() + stop(v(offset + w));
        let moved = measured(&s, "core", "block_displacement_m");
        assert!(low <= moved && moved <= high, "F = {force}: {low} <= {moved} <= {high}");
        assert!(moved < last, "pulling harder moved the block more: F = {force}, {moved} after {last}");
        last = moved;
        assert!((measured(&s, "reference", "block_displacement_m") - moved).abs() < 1e-3, "{s}");
    }
}

/// Disc-on-board at its defaults (`M = 2`, `m = 1`, `mu_s = 0.5`, `mu_k = 0.4`, `mu_floor = 0.1`):
/// held up to `mu_floor (M + m) g`; beyond it the board accelerates at
/// `A = (F - mu_floor (M + m) g) / (M + m / 3)` with the disc rolling, its centre at `A / 3`, up to
/// `A = 3 mu_s g`; beyond, the disc slides at `mu_k g` and the board accelerates at
/// `(F - mu_k m g - mu_floor (M + m) g) / M`; the rim's point past the board's end ends the run.
#[test]
fn disc_on_board_holds_rolls_and_slides_as_the_law_says() {
    let (big_m, m, mu_s, mu_k, mu_floor) = (2.0, 1.0, 0.5, 0.4, 0.1);
    let held = mu_floor * (big_m + m) * G;
    let rolls = 3.0 * mu_s * G * (big_m + m / 3.0) + held;
    for (force, outcome) in [
        (0.98 * held, "Held"),
        (1.02 * held, "Rolled"),
        (20.0, "Rolled"),
        (0.98 * rolls, "Rolled"),
        (1.02 * rolls, "Slid"),
    ] {
        let s = run("disc-on-board", "disc", &["--force", &force.to_string(), "--duration", "0.2"]);
        assert_eq!(s["core"]["outcome"], outcome, "F = {force}: {s}");
        let a = (force - held) / (big_m + m / 3.0);
        let (a_board, a_disc) = match outcome {
            "Held" => (0.0, 0.0),
            "Rolled" => (a, a / 3.0),
            _ => ((force - mu_k * m * G - held) / big_m, mu_k * G),
        };
        for who in ["core", "reference"] {
            let (board, disc) =
                (measured(&s, who, "acceleration_m_s2"), measured(&s, who, "top_acceleration_m_s2"));
            assert!((board - a_board).abs() < 1e-6 && (disc - a_disc).abs() < 1e-6, "{who} F = {force}: {s}");
        }
        assert_eq!(s["law"]["outcome"], outcome, "{s}");
        assert!(s["comparison"]["max_position_deviation_m"].as_f64().unwrap() < 1e-6, "{s}");
    }
    // Sliding back at A - mu_k g = 42.6 m/s^2 at 100 N, the rim leaves the board within 0.16 s.
    let s = run("disc-on-board", "disc", &["--force", "100"]);
    assert_eq!(
        (&s["core"]["outcome"], &s["law"]["outcome"]),
        (&"Unfinished".into(), &"Unfinished".into()),
        "{s}"
    );
    assert!(s["core"]["end_time_s"].as_f64().unwrap() < 0.16, "{s}");
    let (code, stdout, err) = host_sim(&["scene", "--scene", "disc-on-board"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.contains("core f32: outcome Rolled at t = 0.300 s") && stdout.contains("law: Rolled"),
        "{stdout}"
    );
}

/// The stack (`docs/scenes.md`, "stack"): harmonic overhangs scaled below 1 hold (nothing moves
/// beyond round-off), above 1 fall, with two blocks and with three.
#[test]
fn the_stack_holds_below_the_harmonic_overhangs_and_falls_above() {
    for blocks in ["2", "3"] {
        for (overhang, outcome) in [("0.98", "Held"), ("1.02", "Fell")] {
            let s = run("stack", "stack", &["--blocks", blocks, "--overhang", overhang, "--duration", "1"]);
            assert_eq!(s["core"]["outcome"], outcome, "{blocks} blocks at {overhang}: {s}");
            if outcome == "Held" {
                for who in ["core", "reference"] {
                    assert!(measured(&s, who, "max_speed_m_s") < 1e-12, "{who}: {s}");
                }
            }
        }
    }
}

/// A refused value names its flag, in the user's words; a flag of another scene is refused by
/// name; the drivers that do not run these scenes yet say so before any work.
#[test]
fn refusals_name_the_flag_and_the_driver() {
    for (args, words) in [
        (&["scene", "--scene", "stack", "--blocks", "4"][..], "--blocks 4: out of range (2 or 3)"),
        (
            &["scene", "--scene", "block-on-block", "--width", "0.5"][..],
            "--width 0.5 m: out of range (the top block no wider than the bottom one: width <= width2)",
        ),
        (&["run", "--scene", "tablecloth", "--mass2", "-1"][..], "--mass2 -1 kg: must be greater than 0"),
        (
            &["scene", "--scene", "tablecloth", "--offset", "0.99"][..],
            "--offset 0.99 m: out of range (the block starts on the board: offset + width <= length2)",
        ),
        (
            &["scene", "--scene", "block-on-block", "--mu-k", "0.7"][..],
            "--mu-k 0.7 must not exceed --mu-s 0.5",
        ),
        (&["scene", "--scene", "stack", "--x1", "0.1"][..], "--x1 does not apply to --scene stack"),
        (&["map", "--scene", "stack"][..], "--speed does not apply to --scene stack"),
        (&["scene", "--scene", "stack", "--mu-k", "0.6"][..], "--mu-k 0.6 must not exceed --mu-s 0.5"),
        (&["run", "--scene", "stack", "--layout", "reduced"][..], "--layout does not apply to --scene stack"),
        (
            &["scene", "--scene", "disc-on-board", "--offset", "0.6"][..],
            "--offset 0.6 m: out of range (the disc starts over the board: |offset| <= length2 / 2)",
        ),
        (&["run", "--scene", "disc-on-board", "--radius", "0"][..], "--radius 0 m: must be greater than 0"),
        (
            &["scene", "--scene", "disc-on-board", "--width", "0.1"][..],
            "--width does not apply to --scene disc-on-board",
        ),
    ] {
        let (code, stdout, err) = host_sim(args);
        assert_ne!(code, 0, "{args:?}: {stdout}");
        assert!(err.contains(words), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// `host-sim scene` prints the trajectory checksum of the core's run, the fingerprint the
/// firmware prints (`tests/tests/qemu.rs`): every step's states of all bodies in body order
/// (`StepReport::add_to`), computed here through the registry; the stack's at its defaults is the
/// one the QEMU runs print (`tests/tests/qemu.rs`), and a stack whose `mu_k` is its default `mu_s` is that stack.
#[test]
fn scene_prints_the_firmwares_checksum() {
    use meterstick_core::Real;
    use meterstick_core::multibody::scenes::MultibodyScene;
    use meterstick_core::planar::Checksum;
    use meterstick_core::scene::{MultibodyVisitor, Precision, SceneKind, SceneParams};
    struct Sum;
    impl MultibodyVisitor for Sum {
        type Output = u32;
        fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
            self,
            mut scene: S,
        ) -> u32 {
            let mut sum = Checksum::new();
            while let Some(report) = scene.step() {
                report.add_to(&mut sum);
            }
            sum.value()
        }
    }
    let mut stack_sum = None;
    for (kind, precision) in [
        (SceneKind::BlockOnBlock, Precision::F32),
        (SceneKind::Tablecloth, Precision::F64),
        (SceneKind::Stack, Precision::F32),
        (SceneKind::DiscOnBoard, Precision::F32),
        (SceneKind::DiscOnBoard, Precision::F64),
    ] {
        let sum = SceneParams::defaults(kind).build_multibody(precision, Sum).unwrap();
        let (code, stdout, err) =
            host_sim(&["scene", "--scene", kind.name(), "--precision", precision.name()]);
        assert_eq!(code, 0, "{kind}: {err}");
        assert!(stdout.lines().any(|l| l == format!("checksum {sum:08x}")), "{kind}: {sum:08x}: {stdout}");
        if kind == SceneKind::Stack {
            stack_sum = Some(sum);
        }
    }
    let stack_sum = stack_sum.unwrap();
    let (_, stdout, _) =
        host_sim(&["scene", "--scene", "stack", "--precision", "f32", "--mu-s", "0.5", "--mu-k", "0.5"]);
    assert!(stdout.lines().any(|l| l == format!("checksum {stack_sum:08x}")), "{stdout}");
}

/// Friction beyond what f32 resolves (`mu eps > 2^-9`, f32: `mu > 16384`) on a scene of several
/// bodies gets the single body's warning from `scene` and `run`, naming the flags typed; within it,
/// and in f64, none. (The f32 stack at s = 1.02 with `mu = 3e4` falls 8 steps after f64's.)
#[test]
fn friction_beyond_f32_is_warned_about_on_several_bodies() {
    let beyond =
        ["--scene", "stack", "--overhang", "1.02", "--duration", "0.3", "--mu-s", "3e4", "--mu-k", "3e4"];
    let warning = "warning: --mu-s 30000 and --mu-k 30000: friction beyond what f32 resolves";
    let (code, stdout, err) = host_sim(&[&["scene"], &beyond[..]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(stdout.lines().any(|l| l.starts_with(warning)), "{stdout}");
    let (_, stdout, _) = host_sim(&[&["scene"], &beyond[..], &["--precision", "f64"]].concat());
    assert!(!stdout.contains("warning"), "{stdout}");
    let within = [
        "scene",
        "--scene",
        "stack",
        "--overhang",
        "1.02",
        "--max-time",
        "0.3",
        "--mu-s",
        "1e4",
        "--mu-k",
        "1e4",
    ];
    let (_, stdout, _) = host_sim(&within);
    assert!(!stdout.contains("warning"), "{stdout}");
    let out = temp_dir("friction-warning");
    let (code, stdout, err) = host_sim(&[&["run", "--out", out.to_str().unwrap()], &beyond[..]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(stdout.lines().any(|l| l.starts_with(&format!("stack: {warning}"))), "{stdout}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// A 1e6 kg top block on a 1 kg one in f32, pulled where they ride together, is beyond f32's
/// measured reach (`docs/host-sim.md`, "Where f32 holds: several bodies"): `scene` prints a warning
/// naming the two mass flags as typed and the ratio, `run` prints it and `summary.json` carries it by
/// cause; the defaults, and f64, get none.
#[test]
fn a_mass_ratio_beyond_f32s_reach_is_named() {
    let force = format!("{}", 0.45 * (1e6 + 1.0) * G);
    let beyond = ["--scene", "block-on-block", "--mass", "1e6", "--mass2", "1", "--force", &force];
    let warning = "warning: --mass 1000000 kg on --mass2 1 kg: mass ratio 1.00e6: outside 1.00e-4 .. 1.00e5";
    let (code, stdout, err) = host_sim(&[&["scene"], &beyond[..]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(stdout.lines().any(|l| l.starts_with(warning)), "{stdout}");
    for args in [
        &["scene", "--scene", "block-on-block"][..],
        &[&["scene"], &beyond[..], &["--precision", "f64"]].concat(),
    ] {
        let (code, stdout, err) = host_sim(args);
        assert_eq!(code, 0, "{err}");
        assert!(!stdout.contains("warning"), "{args:?}: {stdout}");
    }
    let out = temp_dir("mass-ratio-warning");
    let (code, stdout, err) = host_sim(&[&["run", "--out", out.to_str().unwrap()], &beyond[..]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(stdout.lines().any(|l| l.starts_with(&format!("block-on-block: {warning}"))), "{stdout}");
    let s: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("block-on-block").join("summary.json")).unwrap(),
    )
    .unwrap();
    let w = &s["warnings"][0];
    assert_eq!(w["cause"], "outside_measured", "{s}");
    assert_eq!(w["upper"], serde_json::json!(["--mass", 1e6]), "{s}");
    assert_eq!(w["lower"], serde_json::json!(["--mass2", 1.0]), "{s}");
    assert_eq!(w["ratio"], 1e6, "{s}");
    std::fs::remove_dir_all(&out).unwrap();
    let out = temp_dir("mass-ratio-default");
    let (code, _, err) = host_sim(&["run", "--scene", "block-on-block", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let s: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("block-on-block").join("summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(s["warnings"], serde_json::json!([]), "{s}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// Block-on-block at zero pull: the top block rests flat and centred on the bottom one, the bottom
/// one flat on the floor. Each resting face's two corners carry equal normal loads (the least-norm
/// split of the interface's load, `docs/formulation.md`, "The load: the least norm") that sum to
/// the interface's normal force, each pair's weight above it, in every step of the core (f64) and of
/// the reference; the other two candidates (the lower body's corners, outside the upper one's face,
/// or the floor's ends, which it has not) carry nothing.
#[test]
fn a_centred_resting_box_loads_both_corners_alike() {
    use meterstick_host_sim::bodies::{run_core, run_reference};
    use meterstick_host_sim::scenes::{Precision, SceneKind, SceneParams};
    let mut spec = SceneParams::defaults(SceneKind::BlockOnBlock);
    assert!(spec.set("force", 0.0));
    let mass = |field: &str| spec.get(field).unwrap();
    let g = spec.get("gravity").unwrap();
    // Pair 0: the bottom block on the floor (both blocks' weight); pair 1: the top on the bottom.
    let weights = [(mass("bottom_mass") + mass("top_mass")) * g, mass("top_mass") * g];
    let close = |a: f64, b: f64, rel: f64| (a - b).abs() <= rel * a.abs().max(b.abs());
    for run in [run_core(&spec, Precision::F64, true, None).unwrap(), run_reference(&spec, true).unwrap()] {
        assert_eq!(run.outcome.class.to_string(), "Held", "{}", run.label);
        assert_eq!(run.rows.len() as u64, run.steps + 1, "{}", run.label);
        for row in run.rows.iter().skip(1).chain([&run.last]) {
            assert_eq!(row.corner_loads.len(), 2, "{}", run.label);
            for (p, (loads, force)) in row.corner_loads.iter().zip(&row.interface_forces).enumerate() {
                let at = format!("{} t = {} pair {p}: loads {loads:?}, force {force:?}", run.label, row.t);
                let [left, right] = [loads[0][0], loads[1][0]];
                assert!(left > 0.0 && close(left, right, 1e-9), "{at}");
                assert!(close(left + right, force[1], 1e-9), "{at}");
                assert!(close(force[1], weights[p], 1e-6), "{at}");
                assert_eq!([loads[2], loads[3]], [[0.0; 2]; 2], "{at}");
            }
        }
    }
    // The stack at its defaults (the bottom block over the table's edge, candidate 3): the core's
    // and the reference's loads of each candidate agree, candidate by candidate.
    let mut stack = SceneParams::defaults(SceneKind::Stack);
    assert!(stack.set("max_time", 0.05));
    let (core, reference) =
        (run_core(&stack, Precision::F64, true, None).unwrap(), run_reference(&stack, true).unwrap());
    let weight = stack.get("mass").unwrap() * stack.get("gravity").unwrap();
    for (c, r) in core.rows.iter().zip(&reference.rows).skip(1) {
        for (p, (a, b)) in c.corner_loads.iter().zip(&r.corner_loads).enumerate() {
            let worst =
                a.as_flattened().iter().zip(b.as_flattened()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            assert!(worst <= 1e-6 * weight, "t = {} pair {p}: core {a:?}, reference {b:?}", c.t);
        }
    }
}

/// `host-sim run` draws each body's positions, velocities and angle, core beside reference.
#[test]
fn run_draws_every_bodys_motion() {
    let out = temp_dir("plots");
    let (code, _, err) = host_sim(&[
        "run",
        "--scene",
        "stack",
        "--blocks",
        "2",
        "--duration",
        "0.2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    for file in ["positions.svg", "velocities.svg", "angles.svg"] {
        let svg = std::fs::read_to_string(out.join("stack").join(file)).unwrap();
        for label in ["block 1 (bottom)", "block 2", "(core f32)", "(reference f64)"] {
            assert!(svg.contains(label), "{file} has no {label}");
        }
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// `host-sim map` of block-on-block over force x mu_s (`m = 1`, `M = 2`, `mu_floor = 0.2`,
/// `mu_k = 0.1` so that every `mu_s` of the range is valid) in f32 and f64: the three regions,
/// every cell more than one cell from the laws' boundaries (`F = mu_floor (M + m) g`,
/// `F = (mu_s + mu_floor) (M + m) g`; the top block is too squat to tip below `mu_s = w / h = 1`)
/// classified as the laws say (computed here, not by host-sim), and the laws' boundaries it draws
/// where the formulas put them.
#[test]
fn block_on_block_map_shows_the_laws_regions() {
    let (total, mu_floor) = (3.0, 0.2);
    let law = |f: f64, mu_s: f64| {
        if f <= mu_floor * total * G {
            "Held"
        } else if f <= (mu_s + mu_floor) * total * G {
            "Rode"
        } else {
            "Slid"
        }
    };
    let (columns, rows) = (36_usize, 12_usize);
    let (f_range, mu_range) = ((0.0, 45.0), (0.1, 1.0));
    let centre = |(a, b): (f64, f64), n: usize, k: f64| a + (b - a) * (k + 0.5) / n as f64;
    for precision in ["f32", "f64"] {
        let out = temp_dir(&format!("map-{precision}"));
        let (code, stdout, err) = host_sim(&[
            "map",
            "--scene",
            "block-on-block",
            "--mu-k",
            "0.1",
            "--precision",
            precision,
            "--x-axis",
            "force",
            "--x-range",
            "0,45",
            "--x-cells",
            &columns.to_string(),
            "--y-axis",
            "mu-s",
            "--y-range",
            "0.1,1",
            "--y-cells",
            &rows.to_string(),
            "--tolerance",
            "0.01",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{precision}: {err}");
        let csv = std::fs::read_to_string(out.join("map.csv")).unwrap();
        let (mut compared, mut seen) = (0, std::collections::BTreeSet::new());
        for (k, line) in csv.lines().skip(1).enumerate() {
            let v: Vec<&str> = line.split(',').collect();
            let (f, mu_s, outcome) = (v[0].parse::<f64>().unwrap(), v[1].parse::<f64>().unwrap(), v[2]);
            seen.insert(outcome.to_string());
            let (i, j) = ((k % columns) as f64, (k / columns) as f64);
            let here = law(f, mu_s);
            let far = [-1.0, 0.0, 1.0].iter().all(|di| {
                [-1.0, 0.0, 1.0]
                    .iter()
                    .all(|dj| law(centre(f_range, columns, i + di), centre(mu_range, rows, j + dj)) == here)
            });
            if far {
                compared += 1;
                assert_eq!(outcome, here, "{precision}: force {f} N, mu_s {mu_s}");
            }
        }
        assert_eq!(seen.into_iter().collect::<Vec<_>>(), ["Held", "Rode", "Slid"], "{precision}");
        assert!(compared > columns * rows / 2, "{precision}: only {compared} cells away from the boundaries");
        // The drawn law boundaries, row by row.
        let bounds = std::fs::read_to_string(out.join("law_boundaries.csv")).unwrap();
        assert_eq!(bounds.lines().count(), 1 + 2 * rows, "{bounds}");
        for line in bounds.lines().skip(1) {
            let v: Vec<&str> = line.split(',').collect();
            let (mu_s, f) = (v[0].parse::<f64>().unwrap(), v[1].parse::<f64>().unwrap());
            let want = match (v[3], v[4]) {
                ("Held", "Rode") => mu_floor * total * G,
                ("Rode", "Slid") => (mu_s + mu_floor) * total * G,
                other => panic!("{other:?}"),
            };
            assert!((f - want).abs() < 1e-9, "{line}: {want}");
        }
        // The runs' own boundaries, bisected to 0.01 N, beside the laws'.
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
        for b in summary["boundaries"].as_array().unwrap() {
            let (f, mu_s) = (b["x"].as_f64().unwrap(), b["y"].as_f64().unwrap());
            let want =
                if b["below"] == "Held" { mu_floor * total * G } else { (mu_s + mu_floor) * total * G };
            assert!((f - want).abs() < 0.05, "{precision}: {b} vs the law's {want}");
        }
        assert!(stdout.contains("disagree"), "{stdout}");
        std::fs::remove_dir_all(&out).unwrap();
    }
}

/// `host-sim map` of the stack over its overhang scale: the law's boundary at `s = 1` (the
/// bisection on the law reaches its undecided point and stops there), held below, fallen above
/// (`s >= 1.02`: a stack barely over 1 falls too slowly for the run's limits).
#[test]
fn stack_map_has_the_law_boundary_at_the_critical_overhang() {
    let out = temp_dir("map-stack");
    let (code, _, err) = host_sim(&[
        "map",
        "--scene",
        "stack",
        "--mu-k",
        "0.1",
        "--duration",
        "0.5",
        "--precision",
        "f64",
        "--x-axis",
        "overhang",
        "--x-range",
        "0.9,1.1",
        "--x-cells",
        "5",
        "--y-axis",
        "mu-s",
        "--y-range",
        "0.2,0.8",
        "--y-cells",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let bounds = std::fs::read_to_string(out.join("law_boundaries.csv")).unwrap();
    assert_eq!(bounds.lines().count(), 3, "{bounds}");
    for line in bounds.lines().skip(1) {
        let v: Vec<&str> = line.split(',').collect();
        assert!((v[1].parse::<f64>().unwrap() - 1.0).abs() < 1e-12 && v[3..] == ["Held", "Fell"], "{line}");
    }
    let csv = std::fs::read_to_string(out.join("map.csv")).unwrap();
    for line in csv.lines().skip(1) {
        let v: Vec<&str> = line.split(',').collect();
        let s: f64 = v[0].parse().unwrap();
        let want = if s < 1.0 {
            "Held"
        } else if s >= 1.02 {
            "Fell"
        } else {
            continue;
        };
        assert_eq!(v[2], want, "{line}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// `host-sim map` of disc-on-board over force x mu_s (`M = 2`, `m = 1`, `mu_floor = 0.1`,
/// `mu_k = 0.1` so that every `mu_s` of the range is valid; 0.1 s, so that no sliding disc leaves
/// the board) in f64: the three regions, every cell more than one cell from the law's boundaries
/// (`F = mu_floor (M + m) g`; `A = 3 mu_s g`, i.e. `F = 3 mu_s g (M + m / 3) + mu_floor (M + m) g`)
/// classified as the law says (computed here, not by host-sim), the law's boundaries drawn where
/// the formulas put them, and the runs' own within 0.05 N of them.
#[test]
fn disc_on_board_map_shows_the_laws_regions() {
    let (big_m, m, mu_floor) = (2.0, 1.0, 0.1);
    let held = mu_floor * (big_m + m) * G;
    let rolls = |mu_s: f64| 3.0 * mu_s * G * (big_m + m / 3.0) + held;
    let law = |f: f64, mu_s: f64| {
        if f <= held {
            "Held"
        } else if f <= rolls(mu_s) {
            "Rolled"
        } else {
            "Slid"
        }
    };
    let (columns, rows) = (24_usize, 6_usize);
    let (f_range, mu_range) = ((0.0, 48.0), (0.2, 0.6));
    let centre = |(a, b): (f64, f64), n: usize, k: f64| a + (b - a) * (k + 0.5) / n as f64;
    let out = temp_dir("map-disc");
    let (code, _, err) = host_sim(&[
        "map",
        "--scene",
        "disc-on-board",
        "--mu-k",
        "0.1",
        "--duration",
        "0.1",
        "--precision",
        "f64",
        "--x-axis",
        "force",
        "--x-range",
        "0,48",
        "--x-cells",
        &columns.to_string(),
        "--y-axis",
        "mu-s",
        "--y-range",
        "0.2,0.6",
        "--y-cells",
        &rows.to_string(),
        "--tolerance",
        "0.01",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(out.join("map.csv")).unwrap();
    let (mut compared, mut seen) = (0, std::collections::BTreeSet::new());
    for (k, line) in csv.lines().skip(1).enumerate() {
        let v: Vec<&str> = line.split(',').collect();
        let (f, mu_s, outcome) = (v[0].parse::<f64>().unwrap(), v[1].parse::<f64>().unwrap(), v[2]);
        seen.insert(outcome.to_string());
        let (i, j) = ((k % columns) as f64, (k / columns) as f64);
        let here = law(f, mu_s);
        let far = [-1.0, 0.0, 1.0].iter().all(|di| {
            [-1.0, 0.0, 1.0]
                .iter()
                .all(|dj| law(centre(f_range, columns, i + di), centre(mu_range, rows, j + dj)) == here)
        });
        if far {
            compared += 1;
            assert_eq!(outcome, here, "force {f} N, mu_s {mu_s}");
        }
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), ["Held", "Rolled", "Slid"]);
    assert!(compared > columns * rows / 2, "only {compared} cells away from the boundaries");
    let bounds = std::fs::read_to_string(out.join("law_boundaries.csv")).unwrap();
    assert_eq!(bounds.lines().count(), 1 + 2 * rows, "{bounds}");
    for line in bounds.lines().skip(1) {
        let v: Vec<&str> = line.split(',').collect();
        let (mu_s, f) = (v[0].parse::<f64>().unwrap(), v[1].parse::<f64>().unwrap());
        let want = match (v[3], v[4]) {
            ("Held", "Rolled") => held,
            ("Rolled", "Slid") => rolls(mu_s),
            other => panic!("{other:?}"),
        };
        assert!((f - want).abs() < 1e-9, "{line}: {want}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    for b in summary["boundaries"].as_array().unwrap() {
        let (f, mu_s) = (b["x"].as_f64().unwrap(), b["y"].as_f64().unwrap());
        let want = if b["below"] == "Held" { held } else { rolls(mu_s) };
        assert!((f - want).abs() < 0.05, "{b} vs the law's {want}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}
