//! The `host-sim` binary on the scenes in three dimensions (`docs/scenes.md`, "Scenes in three
//! dimensions"): `run` writes each body's position, quaternion and Euler angles and the contact,
//! and the core follows the independent reference; the billiard ball rolls at the law's velocity;
//! `map` puts the puck's stop-or-slide boundary where `tan(angle) = mu_k` does; `scene` prints the
//! checksum; a flag out of range or of another scene is refused by name before any work.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;
use common::host_sim_within;

fn host_sim(args: &[&str]) -> (i32, String, String) {
    host_sim_within(args, &[], 300)
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("meterstick-spatial-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `host-sim run --scene <scene> --precision f64 <args>`: its `summary.json`, after checking
/// that the core and the reference end alike within 1e-9 m and 1e-9 rad at every step, and that
/// both CSV files hold every step of the body and its contact.
fn run(scene: &str, args: &[&str]) -> serde_json::Value {
    let out = temp_dir(scene);
    let mut all = vec!["run", "--scene", scene, "--precision", "f64", "--out", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let (code, stdout, err) = host_sim(&all);
    assert_eq!(code, 0, "{all:?}: {err}");
    let dir = out.join(scene);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["core"]["outcome"], s["reference"]["outcome"], "{all:?}: {stdout}");
    assert_eq!(s["core"]["steps"], s["reference"]["steps"], "{all:?}");
    let c = &s["comparison"];
    assert!(c["max_position_deviation_m"].as_f64().unwrap() < 1e-9, "{all:?}: {c}");
    assert!(c["max_angle_deviation_rad"].as_f64().unwrap() < 1e-9, "{all:?}: {c}");
    for file in ["core.csv", "reference.csv"] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        assert_eq!(header.len(), 1 + 16 + 8, "{file}: {header:?}");
        assert_eq!(header[4..11], ["qw0", "qx0", "qy0", "qz0", "roll0", "pitch0", "yaw0"], "{file}");
        assert_eq!(header[17..19], ["c0_mode", "c0_x"], "{file}");
        assert_eq!(lines.count() as u64, s["core"]["steps"].as_u64().unwrap() + 1, "{file}");
    }
    for plot in ["positions.svg", "velocities.svg", "path.svg"] {
        assert!(std::fs::metadata(dir.join(plot)).unwrap().len() > 1000, "{plot}");
    }
    std::fs::remove_dir_all(&out).unwrap();
    s
}

#[test]
fn the_puck_follows_the_reference_and_stops_where_the_law_says() {
    for heading in ["0", "-70", "135"] {
        let s = run("puck", &["--heading", heading]);
        assert_eq!(s["core"]["outcome"], "Stopped", "{heading}");
    }
    // On a level table the stopping distance is the law's to within a step's travel, h v.
    let s = run("puck", &["--angle", "0", "--speed", "1.2", "--heading", "33"]);
    let d = s["core"]["measured"]["displacement_m"].as_f64().unwrap();
    let law = s["law"]["measured"]["displacement_m"].as_f64().unwrap();
    assert!((d - law).abs() <= 1e-3 * 1.2, "{d} m against {law} m");
    let heading = s["core"]["measured"]["displacement_heading_deg"].as_f64().unwrap();
    assert!((heading - 33.0).abs() < 1e-9, "{heading}");
}

#[test]
fn the_billiard_ball_follows_the_reference_and_rolls_at_the_law_s_velocity() {
    for spin in [["0", "0", "0"], ["40", "30", "25"], ["-90", "10", "-60"]] {
        let s = run("billiard", &["--spin-x", spin[0], "--spin-y", spin[1], "--spin-z", spin[2]]);
        assert_eq!(s["core"]["outcome"], "Rolled", "{spin:?}");
        for key in ["rolling_velocity_x_m_s", "rolling_velocity_y_m_s"] {
            let (got, law) =
                (s["core"]["measured"][key].as_f64().unwrap(), s["law"]["measured"][key].as_f64().unwrap());
            assert!((got - law).abs() < 1e-12 * 2.0, "{spin:?} {key}: {got} against {law}");
        }
        let (t, law) = (
            s["core"]["measured"]["rolling_time_s"].as_f64().unwrap(),
            s["law"]["measured"]["rolling_time_s"].as_f64().unwrap(),
        );
        assert!(t >= law - 1e-12 && t <= law + 1e-3 + 1e-12, "{spin:?}: rolls at {t} s, law {law} s");
    }
}

#[test]
fn the_puck_s_map_puts_its_boundary_where_the_law_does() {
    let out = temp_dir("map");
    let (code, stdout, err) = host_sim(&[
        "map",
        "--scene",
        "puck",
        "--x-axis",
        "angle",
        "--x-range",
        "0,40",
        "--x-cells",
        "40",
        "--y-axis",
        "mu-ratio",
        "--y-cells",
        "20",
        "--mu-s",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let law = &s["law_disagreements"];
    assert!(law["cells_compared"].as_u64().unwrap() > 500, "{stdout}");
    assert_eq!(law["disagree"], 0, "{stdout}");
    std::fs::remove_dir_all(&out).unwrap();
    // Over one coefficient `mu` (mu_s = mu_k) x the angle: the boundary of each row at or above
    // the law's `tan(angle)` (from there the puck needs `v / (g (mu cos a - sin a))` to stop, so
    // within `max_time` a little more), the cells away from it as the law says.
    let out = temp_dir("map-mu");
    let (code, stdout, err) = host_sim(&[
        "map",
        "--scene",
        "puck",
        "--x-axis",
        "mu",
        "--x-range",
        "0.05,0.8",
        "--x-cells",
        "30",
        "--y-axis",
        "angle",
        "--y-range",
        "0,35",
        "--y-cells",
        "8",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(s["law_disagreements"]["cells_compared"].as_u64().unwrap() > 100, "{stdout}");
    assert_eq!(s["law_disagreements"]["disagree"], 0, "{stdout}");
    let boundaries = s["boundaries"].as_array().unwrap();
    assert_eq!(boundaries.len(), 7, "{stdout}");
    for b in boundaries {
        let (angle, mu) = (b["y"].as_f64().unwrap().to_radians(), b["x"].as_f64().unwrap());
        assert!(mu >= angle.tan() && mu <= angle.tan() + 0.03, "{b}");
    }
    std::fs::remove_dir_all(&out).unwrap();
    let (code, _, err) = host_sim(&["map", "--scene", "puck", "--x-axis", "mu", "--y-axis", "mu-s"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("mu sets mu-s and mu-k, so the two cannot both be axes"), "{err}");
}

#[test]
fn scene_prints_the_checksum_and_bad_flags_are_refused_by_name() {
    let (code, stdout, err) = host_sim(&["scene", "--scene", "billiard", "--spin-y", "80"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("outcome Rolled") && stdout.contains("checksum "), "{stdout}");
    for (args, words) in [
        (
            &["scene", "--scene", "puck", "--angle", "90"][..],
            "--angle 90 deg: out of range (0 <= angle < 90)",
        ),
        (&["scene", "--scene", "puck", "--spin-x", "3"][..], "--spin-x does not apply to --scene puck"),
        (&["scene", "--scene", "billiard", "--mu-k", "0.3"][..], "--mu-k"),
        (&["scene", "--scene", "billiard", "--radius", "-1"][..], "--radius"),
    ] {
        let (code, _, err) = host_sim(args);
        assert_ne!(code, 0, "{args:?}");
        assert!(err.contains(words), "{args:?}: {err}");
    }
}

#[test]
fn curling_runs_through_scene_and_its_bad_flags_are_refused_by_name() {
    let (code, stdout, err) = host_sim(&["scene", "--scene", "curling", "--shape", "ring", "--points", "4"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("outcome Stopped") && stdout.contains("terminal_ratio"), "{stdout}");
    for (args, words) in [
        (
            &["scene", "--scene", "curling", "--points", "9"][..],
            "--points 9: out of range (a whole number from 4 to 8)",
        ),
        (&["scene", "--scene", "curling", "--points", "4.5"][..], "--points 4.5: out of range"),
        (
            &["scene", "--scene", "curling", "--shape", "2"][..],
            "--shape 2: out of range (ring (0) or disc (1))",
        ),
        (
            &["scene", "--scene", "curling", "--shape", "cube"][..],
            "\"cube\" is not a number nor ring nor disc",
        ),
        (&["scene", "--scene", "curling", "--mu", "0"][..], "--mu"),
        (&["scene", "--scene", "curling", "--mu-k", "0.3"][..], "--mu-k does not apply to --scene curling"),
        (&["scene", "--scene", "puck", "--spin", "3"][..], "--spin does not apply to --scene puck"),
    ] {
        let (code, _, err) = host_sim(args);
        assert_ne!(code, 0, "{args:?}");
        assert!(err.contains(words), "{args:?}: {err}");
    }
}

/// The curling stone in f64 beside the independent reference (`reference/src/spatial/curling.rs`,
/// the step as a convex minimisation solved by cases): at the four launches of docs/scenes.md and
/// the ring, the same outcome in the same step, both stops in that step, the same terminal ratio,
/// and every step's position within 1e-12 m and angle within 1e-12 rad.
#[test]
fn the_curling_stone_follows_the_reference_to_its_stop() {
    for args in [
        &["--speed", "1", "--spin", "5"][..],
        &["--speed", "1", "--spin", "20"],
        &["--speed", "2", "--spin", "2"],
        &["--speed", "0.5", "--spin", "10"],
        &["--shape", "ring", "--points", "4"],
    ] {
        let out = temp_dir("curling-reference");
        let mut all = vec!["run", "--scene", "curling", "--precision", "f64", "--out", out.to_str().unwrap()];
        all.extend_from_slice(args);
        let (code, stdout, err) = host_sim(&all);
        assert_eq!(code, 0, "{all:?}: {err}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("curling").join("summary.json")).unwrap())
                .unwrap();
        let (core, reference) = (&s["core"], &s["reference"]);
        assert_eq!(core["outcome"], "Stopped", "{args:?}: {stdout}");
        assert_eq!(core["outcome"], reference["outcome"], "{args:?}");
        assert_eq!(core["steps"], reference["steps"], "{args:?}");
        // The core's time is summed step by step, the reference's is `n h`: the same step to 1e-12 s.
        let at = |r: &serde_json::Value, key: &str| r["measured"][key].as_f64().unwrap();
        for key in ["slide_stop_s", "spin_stop_s"] {
            assert_eq!(at(core, key).to_bits(), at(core, "slide_stop_s").to_bits(), "{args:?}: together");
            assert!((at(core, key) - at(reference, key)).abs() < 1e-12, "{args:?}: {key}");
        }
        let ratio = |r: &serde_json::Value| r["measured"]["terminal_ratio"].as_f64().unwrap();
        assert!((ratio(core) - ratio(reference)).abs() < 1e-9, "{args:?}");
        let c = &s["comparison"];
        assert!(c["max_position_deviation_m"].as_f64().unwrap() < 1e-12, "{args:?}: {c}");
        assert!(c["max_angle_deviation_rad"].as_f64().unwrap() < 1e-12, "{args:?}: {c}");
        std::fs::remove_dir_all(&out).unwrap();
    }
}

/// The meter stick in three dimensions in f64 beside the independent reference
/// (`reference/src/spatial/meter_stick.rs`, its three contacts by cases): at 10 and 30 deg the
/// same outcome in the same step, the same meeting, every step's position within 1e-12 m and
/// angle within 1e-12 rad (measured 1e-15 m), and `reference.csv` with the start and every step.
#[test]
fn the_meter_stick_in_three_dimensions_follows_the_reference() {
    for (heading, outcome) in [("10", "Balanced"), ("30", "Fell")] {
        let out = temp_dir("meter-stick-3d-reference");
        let all = [
            "run",
            "--scene",
            "meter-stick-3d",
            "--precision",
            "f64",
            "--heading",
            heading,
            "--out",
            out.to_str().unwrap(),
        ];
        let (code, stdout, err) = host_sim(&all);
        assert_eq!(code, 0, "{all:?}: {err}");
        let dir = out.join("meter-stick-3d");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
        let (core, reference) = (&s["core"], &s["reference"]);
        assert_eq!(core["outcome"], outcome, "{heading} deg: {stdout}");
        assert_eq!(core["outcome"], reference["outcome"], "{heading} deg");
        assert_eq!(core["steps"], reference["steps"], "{heading} deg");
        for key in ["time_s", "com_offset_m"] {
            let at = |r: &serde_json::Value| r["measured"]["meeting"][key].as_f64();
            match (at(core), at(reference)) {
                (Some(a), Some(b)) => assert!((a - b).abs() < 1e-12, "{heading} deg: {key} {a} {b}"),
                (a, b) => assert_eq!(a, b, "{heading} deg: {key}"),
            }
        }
        let c = &s["comparison"];
        assert!(c["max_position_deviation_m"].as_f64().unwrap() < 1e-12, "{heading} deg: {c}");
        assert!(c["max_angle_deviation_rad"].as_f64().unwrap() < 1e-12, "{heading} deg: {c}");
        let steps = reference["steps"].as_u64().unwrap();
        let csv = std::fs::read_to_string(dir.join("reference.csv")).unwrap();
        assert_eq!(csv.lines().count() as u64, steps + 2, "a header, the start and every step");
        std::fs::remove_dir_all(&out).unwrap();
    }
}

/// The curling ring's terminal ratio over `points` x the launch's `v0 / (R omega0)`: each cell's
/// value beside its outcome in `map.csv` and drawn in `measure.svg`, near 1 wherever the stone
/// stopped (Farkas et al.: whatever the launch); a measure the scene does not have is refused,
/// naming those it has.
#[test]
fn the_curling_map_draws_the_terminal_ratio_over_points_and_launch() {
    let out = temp_dir("map-curling");
    let (code, stdout, err) = host_sim(&[
        "map",
        "--scene",
        "curling",
        "--shape",
        "ring",
        "--measure",
        "terminal_ratio",
        "--x-axis",
        "points",
        "--x-range",
        "3.5,6.5",
        "--x-cells",
        "3",
        "--y-axis",
        "launch-ratio",
        "--y-range",
        "0.5,2",
        "--y-cells",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(out.join("map.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("x,y,outcome,terminal_ratio"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 6, "{csv}");
    let points: Vec<f64> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    assert_eq!(points[..3], [4.0, 5.0, 6.0], "{csv}");
    let stopped: Vec<f64> =
        rows.iter().filter(|r| r[2] == "Stopped").map(|r| r[3].parse().unwrap()).collect();
    assert!(stopped.len() >= 3, "{stdout}{csv}");
    assert!(stopped.iter().all(|r| (r - 1.0).abs() < 2e-3), "{csv}");
    assert!(std::fs::read_to_string(out.join("measure.svg")).unwrap().starts_with("<svg"));
    std::fs::remove_dir_all(&out).unwrap();
    let (code, _, err) = host_sim(&["map", "--scene", "puck", "--measure", "terminal_ratio"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--measure terminal_ratio: --scene puck measures final_speed_m_s, displacement_m"),
        "{err}"
    );
}

/// The stack in three dimensions (`docs/scenes.md`, "stack-3d") through `run` in f64 beside the
/// independent reference (`reference/src/spatial/stack.rs`: its own contacts, loads by nonnegative
/// least squares): held at 0.98 and fallen at 1.02, 2 and 3 blocks, at headings the law says do
/// not matter; the same outcome after the same steps, every block within 1e-12 m and 1e-12 rad;
/// each block in both CSV files at every step; `scene` prints its checksum and refuses a heading,
/// a block count or another scene's flag by name.
#[test]
fn the_stack_in_three_dimensions_follows_the_reference() {
    for (blocks, heading, overhang, outcome) in
        [("2", "30", "1.02", "Fell"), ("3", "-45", "0.98", "Held"), ("3", "60", "1.02", "Fell")]
    {
        let out = temp_dir("stack-3d");
        let all = [
            "run",
            "--scene",
            "stack-3d",
            "--precision",
            "f64",
            "--blocks",
            blocks,
            "--heading",
            heading,
            "--overhang",
            overhang,
            "--duration",
            "0.3",
            "--out",
            out.to_str().unwrap(),
        ];
        let (code, stdout, err) = host_sim(&all);
        assert_eq!(code, 0, "{all:?}: {err}");
        let dir = out.join("stack-3d");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
        let (core, reference) = (&s["core"], &s["reference"]);
        assert_eq!(s["scene"], "stack-3d", "{all:?}: the catalogue's name");
        assert_eq!(core["outcome"], outcome, "{all:?}: {stdout}");
        assert_eq!(core["outcome"], reference["outcome"], "{all:?}");
        assert_eq!(core["steps"], reference["steps"], "{all:?}");
        let c = &s["comparison"];
        assert!(c["max_position_deviation_m"].as_f64().unwrap() < 1e-12, "{all:?}: {c}");
        assert!(c["max_angle_deviation_rad"].as_f64().unwrap() < 1e-12, "{all:?}: {c}");
        let last = format!("x{}", blocks.parse::<usize>().unwrap() - 1);
        for file in ["core.csv", "reference.csv"] {
            let text = std::fs::read_to_string(dir.join(file)).unwrap();
            let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
            assert!(header.contains(&last.as_str()) && header.contains(&"qz0"), "{file}: {header:?}");
            let steps = core["steps"].as_u64().unwrap();
            assert_eq!(text.lines().count() as u64, steps + 2, "{file}: a header, the start and every step");
            for (k, line) in text.lines().enumerate() {
                assert_eq!(
                    line.split(',').count(),
                    header.len(),
                    "{file} line {k}: every row as wide as the header"
                );
            }
        }
        std::fs::remove_dir_all(&out).unwrap();
    }
    let (code, stdout, err) =
        host_sim(&["scene", "--scene", "stack-3d", "--blocks", "2", "--duration", "0.1"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("outcome Held") && stdout.contains("checksum "), "{stdout}");
    for (args, words) in [
        (
            &["scene", "--scene", "stack-3d", "--heading", "70"][..],
            "--heading 70 deg: out of range (-60 <= heading <= 60 deg)",
        ),
        (&["scene", "--scene", "stack-3d", "--blocks", "4"][..], "--blocks 4: out of range (2 or 3)"),
        (&["scene", "--scene", "stack-3d", "--spin", "3"][..], "--spin does not apply to --scene stack-3d"),
        (&["scene", "--scene", "stack-3d", "--width", "0"][..], "--width"),
    ] {
        let (code, _, err) = host_sim(args);
        assert_ne!(code, 0, "{args:?}");
        assert!(err.contains(words), "{args:?}: {err}");
    }
}
