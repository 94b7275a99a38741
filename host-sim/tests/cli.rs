//! The `host-sim` binary: `lcp` output and exit statuses, `scene`, `version`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;

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
            assert_eq!(header.join(","), meterstick_host_sim::trajectory::CSV_HEADER);
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
    for pic in ["error_vs_runtime.svg", "error_vs_h.svg", "map/map.svg"] {
        assert!(md.contains(pic), "report.md does not link {pic}");
        assert!(std::fs::read_to_string(out.join(pic)).unwrap().starts_with("<svg"));
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(json["sweep"].as_array().unwrap().len(), 12);
    std::fs::remove_dir_all(&out).unwrap();
}

/// `host-sim envelope --quick`: 2 speeds x 2 steps, where the f32 core holds within 1e-5 m of
/// the f64 core and the f64 core equals the independent reference to round-off.
#[test]
fn envelope_quick_holds_and_checks_the_reference() {
    let out = temp_dir("envelope");
    let (code, stdout, err) = host_sim(&["envelope", "--quick", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("| finger speed (m/s) |"), "{stdout}");
    let (header, rows) = read_csv(&out.join("envelope.csv"));
    assert_eq!(header[7], "f32_deviation_m");
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert_eq!(r.last().unwrap(), "holds", "{r:?}");
        assert!(num(&r[7]) < 1e-5, "{r:?}");
        assert_eq!(r[8], "true", "the same switch events: {r:?}");
        assert!(num(&r[13]) < 1e-9, "f64 core vs reference: {r:?}");
    }
    let (code, _, err) = host_sim(&["envelope", "--max-steps", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--max-steps 0"), "{err}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// `host-sim map` on a small grid: the slow, high-friction corner balances and the fast corner
/// falls (eq. 21 and the paper's fig. 5); every bisected boundary is confirmed by `host-sim scene`
/// run on each side of it, a separate command.
#[test]
fn map_locates_boundaries_that_scene_confirms() {
    let out = temp_dir("map");
    let (code, stdout, err) = host_sim(&[
        "map",
        "--x-range",
        "0.05,1.2",
        "--x-cells",
        "6",
        "--y-range",
        "0.6,0.7",
        "--y-cells",
        "1",
        "--tolerance",
        "0.01",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("6 x 1 cells"), "{stdout}");
    let (header, cells) = read_csv(&out.join("map.csv"));
    assert_eq!(header, ["x", "y", "outcome"]);
    assert_eq!(cells.len(), 6);
    assert_eq!(cells[0][2], "Balanced", "0.146 m/s, mu_k/mu_s = 0.65: {cells:?}");
    assert_eq!(cells[5][2], "Fell", "1.104 m/s: {cells:?}");
    let (_, bounds) = read_csv(&out.join("boundaries.csv"));
    assert!(!bounds.is_empty(), "Balanced and Fell cells in one row have a boundary between them");
    let mu_k = format!("{}", 0.6 * num(&cells[0][1]));
    for b in &bounds {
        let (x, width) = (num(&b[1]), num(&b[2]));
        assert!(width <= 0.01, "{b:?}");
        for (speed, want) in [(x - width / 2.0, &b[3]), (x + width / 2.0, &b[4])] {
            let (code, stdout, err) = host_sim(&["scene", "--speed", &format!("{speed}"), "--mu-k", &mu_k]);
            assert_eq!(code, 0, "{err}");
            assert!(stdout.contains(&format!("outcome {want} ")), "speed {speed}: want {want}: {stdout}");
        }
    }
    assert!(std::fs::read_to_string(out.join("map.svg")).unwrap().starts_with("<svg"));
    for (args, says) in [
        (&["map", "--x-axis", "wind"][..], "no axis \"wind\""),
        (&["map", "--x-range", "1,1"][..], "--x-range \"1,1\""),
        (&["map", "--x-cells", "0"][..], "--x-cells 0"),
        (&["map", "--y-range", "0.2,1.5"][..], "--mu-k"),
    ] {
        let (code, _, err) = host_sim(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
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
        (&["--x2", "0.51"], "--x2 0.51 m"),
        (&["--x1", "0.3", "--x2", "0.305"], "finger 1 must start left of finger 2"),
        (&["--scene", "incline", "--angle", "95"], "--angle 95 deg: out of range (0 <= angle < 90 deg)"),
        (&["--scene", "ladder", "--angle", "0"], "--angle 0 deg: out of range (0 < angle < 90 deg)"),
        (&["--scene", "ladder", "--mu-s", "0.3"], "--mu-s does not apply to --scene ladder"),
        (&["--width", "0.2"], "--width does not apply to --scene meter-stick (it is a parameter of incline)"),
        (&["--speed", "0.1,0.2", "--h", "1e-3,1e-4"], "only one flag may"),
        (&["--lcp-size", "7"], "invalid value '7' for '--lcp-size"),
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
