//! The `host-sim` binary: `lcp` output and exit statuses, `scene`, `version`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;

mod common;
use common::host_sim_within;

fn host_sim(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim")).args(args).output().unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!("meterstick-cli-{}-{name}", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

fn corpus(file: &str) -> String {
    format!("{}/../tests/data/lcp-corpus/{file}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn lcp_solves_a_siconos_file() {
    let (code, out, _) = host_sim(&["lcp", &corpus("lcp_CPS_2.dat")]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["n"], 3);
    assert_eq!(v["status"], "solution");
    assert_eq!(v["precision"], "f64");
    let z: Vec<f64> = v["z"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    for (a, b) in z.iter().zip([0.0, 1.0, 3.0]) {
        assert!((a - b).abs() < 1e-12, "{z:?}");
    }
    assert_eq!(v["w"].as_array().unwrap().len(), 3);
}

#[test]
fn lcp_reports_a_ray_with_exit_status_zero() {
    let (code, out, _) = host_sim(&["lcp", &corpus("lcp_CPS_3.dat"), "--precision", "f32"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["status"], "ray");
    assert!(v["z"].is_null() && v["w"].is_null());
    assert_eq!(v["precision"], "f32");
}

#[test]
fn lcp_reads_json_and_flags_non_finite() {
    let path = temp_file("ok.json", r#"{"M": [[2, 1], [1, 2]], "q": [-5, -6]}"#);
    let (code, out, _) = host_sim(&["lcp", path.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(out.contains(r#""status":"solution""#), "{out}");
    let nan = temp_file("nan.dat", "1 0 1 1 1 1 nan -1");
    let (code, out, _) = host_sim(&["lcp", nan.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(out.contains(r#""status":"non_finite""#), "{out}");
}

#[test]
fn lcp_rejects_unreadable_and_oversized_files() {
    let (code, _, err) = host_sim(&["lcp", "/nonexistent/meterstick.dat"]);
    assert_ne!(code, 0);
    assert!(err.contains("reading /nonexistent/meterstick.dat"), "{err}");
    let garbage = temp_file("garbage.dat", "3 0 3 3 3 3 1 2");
    let (code, _, err) = host_sim(&["lcp", garbage.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("file ends before"), "{err}");
    let n = 17;
    let m: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect()).collect();
    let big = temp_file("big.json", &serde_json::json!({"M": m, "q": vec![-1.0; n]}).to_string());
    let (code, _, err) = host_sim(&["lcp", big.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("size 17 is not supported"), "{err}");
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("meterstick-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Parses a CSV with a header, checks every row has the header's width, and returns the rows.
fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let rows: Vec<Vec<String>> = lines.map(|l| l.split(',').map(str::to_owned).collect()).collect();
    for r in &rows {
        assert_eq!(r.len(), header.len(), "{}: {r:?}", path.display());
    }
    (header, rows)
}

fn num(s: &str) -> f64 {
    s.parse().unwrap_or_else(|e| panic!("{s:?}: {e}"))
}

#[test]
fn run_writes_every_output_file() {
    let out = temp_dir("run");
    let (code, stdout, err) =
        host_sim(&["run", "--speed", "0.1,5", "--duration", "2", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("core f32 6x6") && stdout.contains("reference f64 8x8"), "{stdout}");
    let all: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(all["runs"].as_array().unwrap().len(), 2);
    for (run, outcome) in [("v0.1", "Unfinished"), ("v5", "Fell")] {
        let dir = out.join(run);
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
        assert_eq!(s["scene"], "meter-stick");
        assert_eq!(s["core"]["outcome"], outcome, "{run}");
        assert_eq!(s["reference"]["outcome"], outcome, "{run}");
        assert_eq!(s["core"]["implementation"], "core f32 6x6");
        assert!(s["comparison"]["max_com_deviation_m"].as_f64().unwrap() < 1e-3, "{s}");
        assert_eq!(s["parameters"]["step"], serde_json::json!(1e-3));
        for (name, steps_key) in [("core.csv", "core"), ("reference.csv", "reference")] {
            let (header, rows) = read_csv(&dir.join(name));
            assert_eq!(header.join(","), meterstick_host_sim::trajectory::csv_header(2));
            assert_eq!(rows.len() as u64, s[steps_key]["steps"].as_u64().unwrap() + 1, "{name}");
            for r in &rows {
                for (k, cell) in r.iter().enumerate() {
                    if header[k].starts_with("mode") {
                        assert!(["separated", "sticking", "sliding+", "sliding-"].contains(&cell.as_str()));
                    } else {
                        assert!(num(cell).is_finite(), "{name}: {r:?}");
                    }
                }
            }
        }
        for name in ["core-events.csv", "reference-events.csv"] {
            let (header, rows) = read_csv(&dir.join(name));
            assert_eq!(header.join(","), "t,kind,contact,mode,along1,along2");
            assert!(!rows.is_empty(), "{name}");
            for r in &rows {
                match r[1].as_str() {
                    "switch" => assert!(num(&r[0]) > 0.0 && ["1", "2"].contains(&r[2].as_str()), "{r:?}"),
                    "stop" => assert!(r[2].is_empty() && r[3].is_empty(), "{r:?}"),
                    other => panic!("{name}: kind {other:?} in {r:?}"),
                }
            }
        }
        for name in ["positions.svg", "motion.svg", "relative.svg"] {
            let svg = std::fs::read_to_string(dir.join(name)).unwrap();
            assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{name}");
            assert!(svg.contains("<polyline") || svg.contains("<path"), "{name} has no lines");
            assert!(svg.contains(&format!("reference {outcome}")), "{name}: the outcome is in the title");
        }
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// `--scene incline` and `--scene ladder`: one run each, beside the reference, with the scene's
/// measured quantity in summary.json.
#[test]
fn run_takes_every_scene() {
    for (scene, extra, key, outcome) in [
        ("incline", &["--angle", "35"][..], "acceleration_m_s2", "Slid"),
        (
            "ladder",
            &["--mu-floor", "0", "--mu-wall", "0", "--angle", "60"][..],
            "wall_release_height_m",
            "Fell",
        ),
    ] {
        let out = temp_dir(scene);
        let mut args = vec!["run", "--scene", scene, "--out", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let (code, stdout, err) = host_sim(&args);
        assert_eq!(code, 0, "{err}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(scene).join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(s["scene"], scene);
        for who in ["core", "reference"] {
            assert_eq!(s[who]["outcome"], outcome, "{scene} {who}: {stdout}");
            assert!(s[who]["measured"][key].as_f64().unwrap() > 0.0, "{scene} {who}: {}", s[who]["measured"]);
        }
        assert!(s["comparison"]["max_com_deviation_m"].as_f64().unwrap() < 1e-3, "{s}");
        assert!(out.join(scene).join("motion.svg").exists());
        std::fs::remove_dir_all(&out).unwrap();
    }
}

/// A scene of three contacts (`core/examples/three_fingers.rs` in the catalogue) runs in `run` and
/// `scene`: its CSV has a column group per finger, and the independent reference runs beside the
/// core (`reference.csv`, `reference` and `comparison` in summary.json).
#[test]
fn run_and_scene_take_a_three_contact_scene() {
    let out = temp_dir("three-fingers");
    let (code, stdout, err) = host_sim(&[
        "run",
        "--scene",
        "three-fingers",
        "--x3",
        "0.3",
        "--precision",
        "f64",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!stdout.contains("no independent reference"), "{stdout}");
    let dir = out.join("three-fingers");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["scene"], "three-fingers");
    assert_eq!(s["core"]["outcome"], "Held", "{s}");
    assert_eq!(s["reference"]["outcome"], "Held", "{s}");
    assert!(s["comparison"].is_object(), "{s}");
    assert_eq!(s["parameters"]["finger3_x"], serde_json::json!(0.3));
    let (header, rows) = read_csv(&dir.join("core.csv"));
    assert_eq!(header.join(","), meterstick_host_sim::trajectory::csv_header(3));
    assert!(header.contains(&"support3_x".to_string()) && header.contains(&"pn3".to_string()));
    assert_eq!(rows.len() as u64, s["core"]["steps"].as_u64().unwrap() + 1);
    // Finger 3 stays where it was put; finger 1 ends the finger width short of finger 2.
    let last = rows.last().unwrap();
    let col = |name: &str| num(&last[header.iter().position(|h| h == name).unwrap()]);
    assert!((col("support3_x") - 0.3).abs() < 1e-9, "{last:?}");
    assert!((col("support2_x") - col("support1_x") - 0.01).abs() < 1e-9, "{last:?}");
    let (reference_header, _) = read_csv(&dir.join("reference.csv"));
    assert_eq!(reference_header, header);
    assert!(dir.join("core-events.csv").exists() && dir.join("positions.svg").exists());
    std::fs::remove_dir_all(&out).unwrap();
    let (code, stdout, err) =
        host_sim(&["scene", "--scene", "three-fingers", "--precision", "f64", "--layout", "full"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("outcome Held at t = ") && stdout.contains("checksum "), "{stdout}");
    // A flag of a two-contact scene is refused by name.
    let (code, _, err) = host_sim(&["scene", "--scene", "three-fingers", "--y1", "0.1"]);
    assert_eq!(code, 2);
    assert!(
        err.contains(
            "--y1 does not apply to --scene three-fingers (it is a parameter of meter-stick, meter-stick-3d)"
        ),
        "{err}"
    );
}

/// The cylinder (one contact) through `scene` and `run`: the outcome and the acceleration the
/// analytic law gives (`docs/scenes.md`, "cylinder"), either side of the critical angle.
#[test]
fn the_cylinder_rolls_or_slides_as_the_law_says() {
    for (angle, outcome) in [("25", "Rolled"), ("40", "Slid")] {
        let args = [
            "scene",
            "--scene",
            "cylinder",
            "--angle",
            angle,
            "--mu-s",
            "0.2",
            "--mu-k",
            "0.15",
            "--precision",
            "f64",
        ];
        let (code, stdout, err) = host_sim(&args);
        assert_eq!(code, 0, "{err}");
        assert!(stdout.contains(&format!("outcome {outcome} at t = ")), "{stdout}");
        let line = stdout.lines().find(|l| l.starts_with("acceleration down the slope")).unwrap();
        let numbers: Vec<f64> = line.split([' ', '(', ')']).filter_map(|w| w.parse().ok()).collect();
        // The measured value first, the law's last.
        let (measured, law) = (numbers[0], numbers[numbers.len() - 1]);
        assert!(numbers.len() >= 2 && (measured / law - 1.0).abs() < 1e-6, "{line}");
    }
    let out = temp_dir("cylinder");
    let (code, _, err) = host_sim(&["run", "--scene", "cylinder", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (header, _) = read_csv(&out.join("cylinder").join("core.csv"));
    assert_eq!(header.join(","), meterstick_host_sim::trajectory::csv_header(1));
    // The reference beside it: the same acceleration, and the angular one (30 degrees, mu_s 0.6:
    // it rolls, omega_dot = a / r).
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("cylinder").join("summary.json")).unwrap())
            .unwrap();
    let measured = |who: &str, what: &str| s[who]["measured"][what].as_f64().unwrap();
    let a = measured("reference", "acceleration_m_s2");
    assert!((a - measured("core", "acceleration_m_s2")).abs() < 1e-4, "{s}");
    assert!((measured("reference", "angular_acceleration_rad_s2") * 0.1 / a - 1.0).abs() < 1e-9, "{s}");
    std::fs::remove_dir_all(&out).unwrap();
    let (code, _, err) = host_sim(&["scene", "--scene", "cylinder", "--radius", "-1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--radius -1 m: must be greater than 0"), "{err}");
}

/// Painlevé's rod jams on its first step with the tangential impact's impulses (`docs/scenes.md`,
/// "painleve"), and `summary.json` carries them.
#[test]
fn the_painleve_rod_jams() {
    let (code, stdout, err) =
        host_sim(&["scene", "--scene", "painleve", "--precision", "f64", "--h", "1e-5"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("outcome Jammed at t = 0.000"), "{stdout}");
    assert!(stdout.contains("the end jammed at t = 0.000010 s"), "{stdout}");
    let out = temp_dir("painleve");
    let (code, _, err) =
        host_sim(&["run", "--scene", "painleve", "--angle", "45", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("painleve").join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(s["core"]["outcome"], "Jammed", "{s}");
    // 45 degrees, m = 1, V = 1: normal impulse 3 m V s c / 4 = 0.375 N s, within m g h.
    let pn = s["core"]["measured"]["jam"]["normal_impulse_n_s"].as_f64().unwrap();
    assert!((pn - 0.375).abs() < 9.81e-3, "{s}");
    // The reference's jam beside it (the core here is f32: within its round-off).
    let reference_pn = s["reference"]["measured"]["jam"]["normal_impulse_n_s"].as_f64().unwrap();
    assert!((reference_pn - pn).abs() < 1e-5, "{s}");
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn report_quick_writes_its_tables_and_pictures() {
    let out = temp_dir("report");
    std::fs::create_dir_all(&out).unwrap();
    // The side-by-side figures are included when their file exists; the firmware's are not here.
    let bench = out.join("rapier.md");
    std::fs::write(&bench, "ratio rapier2d / core: 12.3x (test figure)\n").unwrap();
    let (code, stdout, err) = host_sim(&[
        "report",
        "--quick",
        "--out",
        out.to_str().unwrap(),
        "--bench-figures",
        bench.to_str().unwrap(),
        "--firmware-figures",
        out.join("missing.md").to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("order"), "{stdout}");
    let (header, rows) = read_csv(&out.join("error_vs_runtime.csv"));
    assert_eq!(header[0], "config");
    assert_eq!(header[9], "pivots_per_step");
    assert_eq!(rows.len(), 3 * 4, "3 values of h x 4 configurations");
    for r in &rows {
        assert!(num(&r[4]) > 0.0 && num(&r[7]) > 0.0, "{r:?}"); // an error and a run time
        // Pivots per step: the core's count (warm-started: well below one), none for the reference.
        if r[0].starts_with("core") {
            assert!((0.0..1.0).contains(&num(&r[9])), "{r:?}");
        } else {
            assert!(num(&r[9]).is_nan(), "{r:?}");
        }
    }
    let (_, map) = read_csv(&out.join("success_map.csv"));
    assert_eq!(map.len(), 4);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("## Performance\n") && md.contains("| config | host ns/step | steps/s | pivots/step |")
    );
    assert!(md.contains("### Against rapier2d") && md.contains("12.3x (test figure)"));
    assert!(
        md.contains("## Where f32 holds\n")
            && md.contains("| finger speed (m/s) | h = 1e-3 s | h = 1e-2 s |")
    );
    assert!(md.contains("run `scripts/firmware-report.sh` before this report"));
    // The scenes in three dimensions: 4 cases x 2 precisions x 2 values of h, each with an error.
    let (_, spatial) = read_csv(&out.join("spatial_error_vs_h.csv"));
    assert_eq!(spatial.len(), 16);
    assert!(spatial.iter().all(|r| num(&r[5]).is_finite() && num(&r[6]) > 0.0), "{spatial:?}");
    assert!(md.contains("## Three dimensions: error against the closed forms\n"));
    assert!(md.contains("### Where f32 holds: the puck\n") && md.contains("| 10 | ok "));
    for pic in ["error_vs_runtime.svg", "error_vs_h.svg", "map/map.svg", "spatial_error_vs_h.svg"] {
        assert!(md.contains(pic), "report.md does not link {pic}");
        assert!(std::fs::read_to_string(out.join(pic)).unwrap().starts_with("<svg"));
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(json["sweep"].as_array().unwrap().len(), 12);
    assert_eq!(json["spatial_sweep"].as_array().unwrap().len(), 16);
    assert_eq!(json["spatial_envelope"].as_array().unwrap().len(), 4 * 2);
    std::fs::remove_dir_all(&out).unwrap();
}

/// `host-sim envelope --quick`: 2 speeds x 2 steps, where the f32 core holds within 1e-5 m of
/// the f64 core and the f64 core equals the independent reference to round-off; and the friction
/// table at two `mu`, where f32 reaches f64's outcome in every scene and layout.
#[test]
fn envelope_quick_holds_and_checks_the_reference() {
    let out = temp_dir("envelope");
    let (code, stdout, err) = host_sim(&["envelope", "--quick", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("| finger speed (m/s) |"), "{stdout}");
    let (header, rows) = read_csv(&out.join("envelope.csv"));
    let col =
        |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}: {header:?}"));
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert_eq!(r[col("verdict")], "holds", "{r:?}");
        assert!(num(&r[col("f32_deviation_m")]) < 1e-5, "{r:?}");
        assert_eq!(r[col("events_agree")], "true", "the same switch events: {r:?}");
        assert_eq!(r[col("outcome_f32")], r[col("outcome_f64")], "{r:?}");
        assert_eq!(r[col("flagged_steps")], "0", "no step beyond f32's resolution here: {r:?}");
        assert!(num(&r[col("reference_deviation_m")]) < 1e-9, "f64 core vs reference: {r:?}");
    }
    // The mu axis: meter stick, incline and Painleve in both layouts at mu_s = mu_k = 1e2 and 1e4,
    // where f32 reaches f64's outcome (and no warning is due).
    assert!(stdout.contains("| scene (layout) |"), "{stdout}");
    let (header, rows) = read_csv(&out.join("envelope-mu.csv"));
    let col =
        |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}: {header:?}"));
    assert_eq!(rows.len(), 12);
    for r in &rows {
        assert_eq!(r[col("outcome_f32")], r[col("outcome_f64")], "{r:?}");
        assert_eq!(r[col("agree")], "true", "{r:?}");
        assert_eq!(r[col("beyond_f32")], "false", "{r:?}");
        assert_ne!(r[col("outcome_f32")], "Failed", "{r:?}");
    }
    let (code, _, err) = host_sim(&["envelope", "--max-steps", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--max-steps 0"), "{err}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// `host-sim map` on small grids: the slow, high-friction corner balances and the fast corner
/// falls (eq. 21 and the paper's fig. 5); every bisected boundary is confirmed by `host-sim scene`
/// (a separate command) on each side of it, also in a row where a third class (Unfinished: the
/// rod still rocking at max-time) sits between Balanced and Fell: the bisection labelled such a
/// boundary with its two cells' classes, and 33 of the default map's 318 boundaries had an end
/// whose outcome was not its label.
#[test]
fn map_locates_boundaries_that_scene_confirms() {
    let out = temp_dir("map");
    for (x_range, y_range, cells_x) in [("0.05,1.2", "0.6,0.7", "6"), ("0.30,0.33", "0.463,0.465", "6")] {
        let (code, stdout, err) = host_sim(&[
            "map",
            "--x-range",
            x_range,
            "--x-cells",
            cells_x,
            "--y-range",
            y_range,
            "--y-cells",
            "1",
            "--tolerance",
            "0.002",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{err}");
        assert!(stdout.contains("6 x 1 cells"), "{stdout}");
        let (header, cells) = read_csv(&out.join("map.csv"));
        assert_eq!(header, ["x", "y", "outcome"]);
        assert_eq!(cells.len(), 6);
        if x_range == "0.05,1.2" {
            assert_eq!(cells[0][2], "Balanced", "0.146 m/s, mu_k/mu_s = 0.65: {cells:?}");
            assert_eq!(cells[5][2], "Fell", "1.104 m/s: {cells:?}");
        }
        let (_, bounds) = read_csv(&out.join("boundaries.csv"));
        assert!(
            !bounds.is_empty(),
            "{x_range}: cells of different outcomes in one row have a boundary: {cells:?}"
        );
        let mu_k = format!("{}", 0.6 * num(&cells[0][1]));
        for b in &bounds {
            let (x, width) = (num(&b[1]), num(&b[2]));
            assert!(width <= 0.002, "{b:?}");
            for (speed, want) in [(x - width / 2.0, &b[3]), (x + width / 2.0, &b[4])] {
                let (code, stdout, err) =
                    host_sim(&["scene", "--speed", &format!("{speed}"), "--mu-k", &mu_k]);
                assert_eq!(code, 0, "{err}");
                assert!(stdout.contains(&format!("outcome {want} ")), "speed {speed}: want {want}: {stdout}");
            }
        }
        assert!(std::fs::read_to_string(out.join("map.svg")).unwrap().starts_with("<svg"));
    }
    for (args, says) in [
        (&["map", "--x-axis", "wind"][..], "no axis \"wind\""),
        (&["map", "--x-range", "1,1"][..], "--x-range \"1,1\""),
        (&["map", "--x-range", "1,0.05"][..], "from < to"),
        (&["map", "--x-cells", "0"][..], "--x-cells 0"),
        (&["map", "--y-range", "0.2,1.5"][..], "--mu-k"),
        (&["map", "--y-axis", "speed"][..], "both speed"),
        (&["map", "--x-axis", "mu-k", "--x-range", "0.1,0.3"][..], "mu-ratio sets mu-k"),
        // Numbers as typed: 1e300 was written out in 301 digits, twice.
        (&["map", "--x-range", "0.05,1e300"][..], "--x-range 0.05,1e300 x --y-range 0.2,1.0"),
    ] {
        let (code, _, err) = host_sim(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(err.len() < 300, "{args:?}: a short message: {err}");
    }
    // mu-ratio scales each cell's mu_s, whichever axis sets it (it was applied to the base mu_s
    // when it came first: refused as "--mu-k 0.54 must not exceed --mu-s 0.5").
    let (code, _, err) = host_sim(&[
        "map",
        "--x-axis",
        "mu-ratio",
        "--x-range",
        "0.5,0.9",
        "--x-cells",
        "2",
        "--y-axis",
        "mu-s",
        "--y-range",
        "0.5,0.7",
        "--y-cells",
        "1",
        "--speed",
        "1",
        "--tolerance",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// Every documented parameter error, through the command line, in the user's words: the flag,
/// the value given and what is allowed.
#[test]
fn run_and_scene_reject_each_invalid_parameter() {
    let cases: &[(&[&str], &str)] = &[
        (&["--h", "0"], "--h 0 s: must be greater than 0"),
        (&["--h", "-1e-3"], "--h -0.001 s: must be greater than 0"),
        (&["--h", "NaN"], "--h NaN s: not a finite number"),
        (&["--duration", "inf"], "--duration inf s: not a finite number"),
        (&["--mass", "-0.2"], "--mass -0.2 kg: must be greater than 0"),
        (&["--length", "0"], "--length 0 m: must be greater than 0"),
        (&["--thickness", "0"], "--thickness 0 m: must be greater than 0"),
        (&["--mu-s", "-0.1"], "--mu-s -0.1: must not be negative"),
        (&["--gravity", "-9.81"], "--gravity -9.81 m/s^2: must not be negative"),
        (&["--finger-width", "-0.01"], "--finger-width -0.01 m: must not be negative"),
        (&["--mu-k", "0.7"], "--mu-k 0.7 must not exceed --mu-s 0.6"),
        (&["--x1", "-0.6"], "a finger starts beyond an end of the rod: --x1 -0.6 m"),
        (
            &["--x2", "0.51"],
            "a finger starts beyond an end of the rod: --x2 0.51 m must be within --length 1 m / 2",
        ),
        (
            &["--scene", "three-fingers", "--x3", "0.6"],
            "a finger starts beyond an end of the rod: --x3 0.6 m must be",
        ),
        (
            &["--scene", "three-fingers", "--x3", "-0.1"],
            "finger 3 must start right of finger 2: --x3 -0.1 m > --x2 0 m",
        ),
        (&["--x1", "0.3", "--x2", "0.305"], "finger 1 must start left of finger 2"),
        (&["--scene", "incline", "--angle", "95"], "--angle 95 deg: out of range (0 <= angle < 90 deg)"),
        (&["--scene", "ladder", "--angle", "0"], "--angle 0 deg: out of range (0 < angle < 90 deg)"),
        (&["--scene", "ladder", "--mu-s", "0.3"], "--mu-s does not apply to --scene ladder"),
        (
            &["--width", "0.2"],
            "--width does not apply to --scene meter-stick (it is a parameter of incline, meter-stick-3d, block-on-block, tablecloth, stack-3d)",
        ),
        (&["--speed", "0.1,0.2", "--h", "1e-3,1e-4"], "only one flag may"),
        (&["--layout", "8"], "invalid value '8' for '--layout"),
        (&["--lcp-size", "8"], "unexpected argument '--lcp-size'"),
        (&["--precision", "f16"], "invalid value 'f16'"),
        (&["--speed", "fast"], "\"fast\" is not a number"),
        (&["--scene", "pendulum"], "invalid value 'pendulum' for '--scene"),
    ];
    let out = temp_dir("bad");
    for (args, expected) in cases {
        for cmd in ["scene", "run"] {
            let mut all = vec![cmd];
            all.extend_from_slice(args);
            if cmd == "run" {
                all.extend_from_slice(&["--out", out.to_str().unwrap()]);
            }
            let (code, _, err) = host_sim(&all);
            assert_ne!(code, 0, "{all:?} should fail");
            assert!(err.contains(expected), "{all:?}: expected {expected:?} in {err}");
        }
    }
    assert!(!out.exists(), "a rejected run must not write anything");
}

#[test]
fn scene_and_version_run() {
    let (code, out, _) = host_sim(&["version"]);
    assert_eq!(code, 0);
    assert!(out.contains("meterstick-core"));
    let (code, out, _) = host_sim(&["scene", "--speed", "5"]);
    assert_eq!(code, 0);
    assert!(out.contains("outcome Fell"), "{out}");
    assert!(out.contains("checksum "), "{out}");
    let (code, out, err) = host_sim(&["scene", "--scene", "ladder", "--angle", "70"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("outcome Held"), "{out}");
}

#[test]
fn stress_quick_passes_and_writes_its_report() {
    let out = std::env::temp_dir().join(format!("meterstick-cli-{}-stress", std::process::id()));
    let (code, stdout, stderr) = host_sim(&["stress", "--quick", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains(" 0 failed"), "{stdout}");
    let csv = std::fs::read_to_string(out.join("cases.csv")).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let cases = summary["cases"].as_u64().unwrap();
    assert!(cases >= 8, "{summary}");
    // One CSV line per case and implementation (3), after the header.
    assert_eq!(csv.lines().count() as u64, 1 + 3 * cases);
    assert!(std::fs::read_to_string(out.join("report.md")).unwrap().contains("| v=0 |"));
    assert!(std::fs::read_to_string(out.join("criteria.svg")).unwrap().starts_with("<svg"));
    std::fs::remove_dir_all(&out).unwrap();
}

/// Bad LCP files, each refused with status 2, the file, the format expected and what is wrong,
/// within a bound of time and memory. What it guards against: `/dev/zero` read without end
/// (killed by the timeout); `huge.dat`, 38 bytes declaring n = 10^9, allocated 10^18 entries and
/// aborted ("memory allocation failed", status 134); `usize::MAX` as n panicked ("capacity
/// overflow", status 101); a sparse block size beyond n panicked ("index out of bounds", 101); an
/// empty `.json` file got "Siconos .dat: file ends before n".
#[test]
fn lcp_refuses_bad_files_within_bounds() {
    let huge = temp_file("huge.dat", "1000000000 0 1000000000 1000000000 1000000000 1000000000 1");
    let max = temp_file("max.dat", "18446744073709551615 1 18446744073709551615 18446744073709551615 1");
    let blocks =
        temp_file("blocks.dat", "3 1 3 3\n1\n2 1\n5 3\n3\n3 1\n0 1 1\n0\n0\n1 2 3 4 5 6 7 8 9\n1 2 3\n");
    let empty_json = temp_file("empty.json", "");
    let json_in_dat = temp_file("json.dat", r#"{"M": [[1]], "q": [-1]}"#);
    let bad_json = temp_file("bad.json", "3 0 3 3 3 3 1 2 3 4 5 6 7 8 9 1 2 3");
    let cases: Vec<(String, &str)> = vec![
        ("/dev/zero".into(), "reading /dev/zero: larger than the 1 MiB this input may have"),
        (
            huge.display().to_string(),
            "LCP size 1000000000 is not supported: the core solver is built for 1..=16",
        ),
        (max.display().to_string(), "LCP size 18446744073709551615 is not supported"),
        (blocks.display().to_string(), "blocksize0 is 5, more than 3"),
        (
            empty_json.display().to_string(),
            r#"expected an LCP in JSON ({"M": [[row], ...], "q": [...]}) (as its name ends in .json): the file is empty"#,
        ),
        (json_in_dat.display().to_string(), "(as its name ends in .dat; the content looks like JSON)"),
        (
            bad_json.display().to_string(),
            "(as its name ends in .json; the content is not JSON): parsing the LCP JSON",
        ),
    ];
    for (file, says) in &cases {
        if file.starts_with("/dev/") && !std::path::Path::new(file).exists() {
            continue;
        }
        let (code, out, err) = host_sim_within(&["lcp", file], &[], 20);
        assert_eq!(code, 2, "{file}: {out}{err}");
        assert!(
            err.starts_with(&format!(
                "host-sim: error: {}",
                if file.starts_with("/dev/") { "reading " } else { "" }
            )),
            "{err}"
        );
        assert!(err.contains(says), "{file}: expected {says:?} in {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// The exit statuses `host-sim --help` documents: 0 done, 2 bad input (before anything runs),
/// 1 a check failed (`monitor_exits_1_when_the_rigs_run_differs`; for `stress`, whose cases all
/// pass today, the unit test `cli::tests::exit_statuses_follow_the_error`), 130 Ctrl-C (`ctrl_c_*`).
/// `--help` states them.
#[test]
fn exit_statuses_are_as_documented() {
    let (code, help, _) = host_sim(&["--help"]);
    assert_eq!(code, 0);
    assert!(help.contains("Exit status:") && help.contains("130  stopped by Ctrl-C"), "{help}");
    for cmd in
        ["lcp", "run", "report", "map", "envelope", "stress", "scene", "monitor", "qemu", "serve", "version"]
    {
        let (code, help, err) = host_sim(&[cmd, "--help"]);
        assert_eq!(code, 0, "{cmd}: {err}");
        assert!(help.contains("Exit status: "), "host-sim {cmd} --help:\n{help}");
    }
    let (code, _, _) = host_sim(&["lcp", &corpus("lcp_CPS_2.dat")]);
    assert_eq!(code, 0);
    let out = temp_dir("status");
    let o = out.to_str().unwrap();
    for args in [
        &["run", "--h", "0", "--out", o][..],
        &["map", "--x-cells", "0", "--out", o],
        &["envelope", "--max-steps", "0", "--out", o],
        &["stress", "--only", "no such case", "--out", o],
        &["scene", "--speed", "fast"],
        &["lcp", "/nonexistent/meterstick.json"],
        &["monitor", "--port", "/nonexistent/tty", "--set", "mu=1"],
        &["no-such-command"],
    ] {
        let (code, _, err) = host_sim(args);
        assert_eq!(code, 2, "{args:?}: {err}");
    }
    assert!(!out.exists(), "a refusal writes nothing");
}

/// A missing value is named: `run --h --duration 2` must not say "unexpected argument '2'
/// found" (clap taking `--duration` as the value of `--h`).
#[test]
fn a_missing_value_is_named() {
    let (code, _, err) = host_sim(&["run", "--h", "--duration", "2"]);
    assert_eq!(code, 2);
    assert!(
        err.contains(
            "a value is required for '--h' but none was supplied (the next argument, '--duration', is a flag)"
        ),
        "{err}"
    );
}

/// A value f64 holds but f32 does not, in the user's words, before anything runs: not, as it
/// could be, `--mass 1e39` shown as `--mass 999999999999999939709166371603178586112 kg: not a
/// finite number` and `--mass 1e-50` as `--mass 0 kg: must be greater than 0` (a rounded 0).
#[test]
fn values_that_only_f32_refuses_say_so() {
    for (args, says) in [
        (
            &["--mass", "1e39"][..],
            "--mass 1e39 kg: not a finite number as f32 (--precision f32; f64 accepts it)",
        ),
        (
            &["--mass", "1e-50"],
            "--mass 1e-50 kg: must be greater than 0 as f32 (--precision f32; f64 accepts it)",
        ),
        (&["--h", "1e-30"], "--h 1e-30 s and --duration 30 s imply 3.000e31 steps"),
        (&["--gravity", "-1e-20"], "--gravity -1e-20 m/s^2: must not be negative"),
    ] {
        let mut all = vec!["scene"];
        all.extend_from_slice(args);
        let (code, _, err) = host_sim(&all);
        assert_eq!(code, 2, "{args:?}");
        assert!(err.contains(says), "{args:?}: expected {says:?} in {err}");
    }
    let (code, out, err) = host_sim(&["scene", "--mass", "1e39", "--precision", "f64"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("outcome Balanced"), "{out}");
}

/// Off a terminal, a command that runs longer than the period (`MS_PROGRESS_SECS`, default 5 s)
/// prints plain progress lines to stderr (the indicatif bar is hidden off a terminal, so without
/// them it would print nothing).
#[test]
fn progress_lines_off_a_terminal() {
    let out = temp_dir("progress");
    let (code, _, err) = host_sim_within(
        &["run", "--speed", "0.1", "--h", "1e-4", "--out", out.to_str().unwrap()],
        &[("MS_PROGRESS_SECS", "0.1")],
        300,
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.lines().any(|l| l.starts_with("host-sim: running scenes: ") && l.contains("/2 (")), "{err}");
    let (code, _, err) =
        host_sim_within(&["scene", "--speed", "0.1", "--h", "1e-5"], &[("MS_PROGRESS_SECS", "0.05")], 300);
    assert_eq!(code, 0, "{err}");
    assert!(err.lines().any(|l| l.starts_with("host-sim: steps: ") && l.contains("/3000000 (")), "{err}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// Sends SIGINT to a `host-sim` once its stderr shows `ready`, and returns its status and stderr.
#[cfg(unix)]
fn interrupt_when(args: &[&str], ready: &str) -> (i32, String) {
    use std::io::{BufRead as _, BufReader};
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(args)
        .env("MS_PROGRESS_SECS", "0.1")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let mut err = String::new();
    for line in lines.by_ref() {
        let line = line.unwrap();
        err += &line;
        err.push('\n');
        if line.contains(ready) {
            break;
        }
    }
    assert!(err.contains(ready), "host-sim {args:?} ended before {ready:?}: {err}");
    let sent = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(sent.success());
    let started = std::time::Instant::now();
    for line in lines {
        err += &line.unwrap();
        err.push('\n');
    }
    let status = child.wait().unwrap();
    assert!(started.elapsed().as_secs() < 20, "{:?} after Ctrl-C: {err}", started.elapsed());
    (status.code().unwrap(), err)
}

/// Ctrl-C during `host-sim run`: no new run starts, the one under way (the slow reference) is
/// dropped, the finished run is written, and the files are listed; status 130 (not a process
/// killed by SIGINT with nothing written and nothing said).
#[test]
#[cfg(unix)]
fn ctrl_c_ends_run_cleanly_listing_what_was_written() {
    let out = temp_dir("ctrl-c");
    let o = out.to_str().unwrap();
    // v5 falls within 0.1 s; v0.1 runs 8.4 s at h = 2e-5 s (the reference: tens of seconds);
    // --duration 10 keeps the two runs' 2 x 5 x 10^5 steps within what host-sim run records.
    let (code, err) =
        interrupt_when(&["run", "--speed", "5,0.1", "--h", "2e-5", "--duration", "10", "--out", o], "3/4 (");
    assert_eq!(code, 130, "{err}");
    assert!(err.contains("host-sim: Ctrl-C: no new run starts"), "{err}");
    assert!(err.contains(&format!("written so far in {o} (")), "{err}");
    assert!(err.contains(&format!("{o}/v5/core.csv")) && err.contains(&format!("{o}/summary.json")), "{err}");
    assert!(!out.join("v0.1").exists(), "the interrupted run is dropped: {err}");
    let all: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(all["runs"].as_array().unwrap().len(), 1);
    assert_eq!(all["runs"][0]["name"], "v5");
    std::fs::remove_dir_all(&out).unwrap();

    let (code, err) = interrupt_when(&["scene", "--speed", "0.1", "--h", "1e-5"], "host-sim: steps: ");
    assert_eq!(code, 130, "{err}");
    assert!(
        err.contains(
            "stopped by Ctrl-C: no new run started, the runs under way were dropped; nothing written"
        ),
        "{err}"
    );
}

/// `host-sim run` records every step of the core and the reference: more than 2 x 10^6 is refused
/// before anything runs: without the cap, `run --h 1e-6 --duration 100` would start five runs
/// of 10^8 recorded steps each (about 70 GB each at 700 bytes a step).
#[test]
fn run_refuses_more_steps_than_it_can_record() {
    let out = temp_dir("record-cap");
    let (code, _, err) =
        host_sim(&["run", "--h", "1e-6", "--duration", "100", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        err.contains(
            "--h 0.000001 s and --duration 100 s imply 1.000e8 steps; host-sim run records every step"
        ),
        "{err}"
    );
    let (code, _, err) = host_sim(&["run", "--speed", "1e-4", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        err.contains(
            "the default --duration follows the fingers' travel time: --h 0.001 s and --duration 15801.5 s"
        ),
        "{err}"
    );
    assert!(!out.exists());
}

/// The cap on recorded steps holds for a list's runs together, since every run is kept until the
/// last has finished: four runs of 2 x 10^6 steps each (each within the cap) are refused at once,
/// naming the list, `--h` and `--duration` and what to change. Before, this ran and peaked at
/// 3.2 GB resident (memory grew with the number of values).
#[test]
fn run_refuses_a_list_whose_runs_together_record_too_many_steps() {
    let out = temp_dir("record-cap-list");
    let o = out.to_str().unwrap();
    let start = std::time::Instant::now();
    let (code, _, err) = host_sim(&[
        "run",
        "--scene",
        "incline",
        "--angle",
        "10,11,12,13",
        "--h",
        "1e-5",
        "--duration",
        "20",
        "--out",
        o,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(
            "--angle 10,11,12,13 deg: 4 runs of --h 0.00001 s and --duration 20 s imply 8.000e6 steps in all; \
             host-sim run keeps every step of every run until the last has finished"
        ),
        "{err}"
    );
    assert!(
        err.contains("takes at most 2e6 in all (give fewer values of --angle, raise --h or lower --duration"),
        "{err}"
    );
    // The paper's speeds when --speed is not given; the durations follow the travel time.
    let (code, _, err) = host_sim(&["run", "--h", "2e-5", "--out", o]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(
            "the default --duration follows the fingers' travel time: --speed (not given: the paper's \
             0.1,0.5,1,5,10 m/s): 5 runs of --h 0.00002 s and --duration 30 s imply 7.500e6 steps in all"
        ),
        "{err}"
    );
    assert!(err.contains("give fewer values of --speed"), "{err}");
    assert!(
        start.elapsed() < std::time::Duration::from_secs(20),
        "refused before any run: {:?}",
        start.elapsed()
    );
    assert!(!out.exists(), "a refusal writes nothing");
}

/// A fake rig on a TCP socket: answers every command as the firmware does (the defaults read back
/// with `GetParam`; a step over 50 s refused as out of range, as the core refuses a step longer
/// than the run), and on `Start` sends a run whose checksum is not the host's.
fn fake_rig_with_a_wrong_checksum() -> (std::net::SocketAddr, std::thread::JoinHandle<()>) {
    use meterstick_link::{
        Command, CommandDecoder, MAX_FRAME, OutcomeCode, PROTOCOL_VERSION, ParamId, RejectReason, Report,
        RigState, SceneId, encode,
    };
    use std::io::{Read as _, Write as _};
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap();
    let rig = std::thread::spawn(move || {
        let (mut s, _) = listener.accept().unwrap();
        let params = meterstick_core::scene::MeterStickParams::<f32>::default();
        let mut dec = CommandDecoder::new();
        let mut buf = [0u8; 256];
        loop {
            let Ok(n) = s.read(&mut buf) else { return };
            if n == 0 {
                return;
            }
            let mut commands = Vec::new();
            dec.feed(&buf[..n], |c| commands.extend(c.ok()));
            for c in commands {
                let replies: Vec<Report> = match c {
                    Command::Hello => vec![Report::Hello {
                        protocol: PROTOCOL_VERSION,
                        firmware: (0, 1, 0),
                        core: (0, 1, 0),
                        build: *b"fakerig ",
                        scene: SceneId::MeterStick,
                        lcp_size: 6,
                        step_us: 1000,
                    }],
                    Command::GetParam { id } => {
                        vec![Report::Param { id, value: params.get(id.name()).unwrap() }]
                    }
                    Command::SetParam { id: ParamId::Step, value } if value > 50.0 => {
                        vec![Report::Rejected { id: ParamId::Step, reason: RejectReason::OutOfRange }]
                    }
                    Command::Start => vec![
                        Report::Ack { command: c.tag() },
                        Report::State(RigState::Running),
                        Report::Outcome {
                            outcome: OutcomeCode::Balanced,
                            time: 8.4,
                            steps: 8400,
                            checksum: 0xdead_beef,
                        },
                        Report::State(RigState::Finished),
                    ],
                    other => vec![Report::Ack { command: other.tag() }],
                };
                for r in replies {
                    let mut frame = [0u8; MAX_FRAME];
                    let _ = s.write_all(encode(&r, &mut frame).unwrap());
                }
            }
        }
    });
    (addr, rig)
}

/// A value the rig refuses is named with the rig's reason in words (not a debug name, not `Other`).
#[test]
fn monitor_words_the_rigs_refusal() {
    let (addr, rig) = fake_rig_with_a_wrong_checksum();
    let port = format!("tcp:{addr}");
    let (code, _, err) = host_sim_within(&["monitor", "--port", &port, "--set", "step=100"], &[], 120);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("--set step: the rig refused it: it is outside its range"), "{err}");
    rig.join().unwrap();
}

/// Exit status 1: a check failed. `host-sim monitor` against a rig whose run is not the host's
/// (its checksum differs) writes its files and exits 1, not 2 (the status of bad input).
#[test]
fn monitor_exits_1_when_the_rigs_run_differs() {
    let (addr, rig) = fake_rig_with_a_wrong_checksum();
    let out = temp_dir("monitor-differs");
    let port = format!("tcp:{addr}");
    let (code, _, err) =
        host_sim_within(&["monitor", "--port", &port, "--start", "--out", out.to_str().unwrap()], &[], 120);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("the rig's run differs from the host's f32 build"), "{err}");
    assert!(out.join("summary.json").exists() && out.join("core.csv").exists(), "{err}");
    rig.join().unwrap();
    std::fs::remove_dir_all(&out).unwrap();
}
