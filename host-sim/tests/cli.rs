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

#[test]
fn scene_and_version_run() {
    let (code, out, _) = host_sim(&["version"]);
    assert_eq!(code, 0);
    assert!(out.contains("meterstick-core"));
    let (code, out, _) = host_sim(&["scene", "--speed", "5"]);
    assert_eq!(code, 0);
    assert!(out.contains("outcome: Fell"), "{out}");
    let (code, _, err) = host_sim(&["scene", "--h", "0"]);
    assert_ne!(code, 0);
    assert!(err.contains("step must be positive"), "{err}");
}
