//! Refusals before any work runs, in the words of the flag or file the user gave, each within
//! seconds: each case here once ran (or panicked) instead.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;

mod common;
use common::host_sim_within;

/// Runs `host-sim args`, failing if it has not ended within 20 s; its status and stderr.
fn refused(args: &[&str]) -> (i32, String) {
    let (code, _, err) = host_sim_within(args, &[], 20);
    (code, err)
}

fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("meterstick-refusals-{}-{name}", std::process::id()))
}

/// A `--timeout-s` beyond what a deadline can hold panicked ("cannot convert float seconds to
/// Duration"); `--max-steps 0` was refused by the rig, after connecting, as `max_time`. Both are
/// refused before the port is opened (port 1 on the loopback: nothing listens there).
#[test]
fn monitor_refuses_its_numbers_before_connecting() {
    let (code, err) = refused(&["monitor", "--port", "tcp:127.0.0.1:1", "--timeout-s", "1e300"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--timeout-s 1e300: must be a positive number of seconds, at most"), "{err}");
    let (code, err) = refused(&["monitor", "--port", "tcp:127.0.0.1:1", "--stress-grid", "--max-steps", "0"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--max-steps 0:"), "{err}");
}

/// A map with `h` as an axis ran each cell for 10^9 steps ("map cells: 0/1" for ever): the step
/// limit of `host-sim scene` now holds at the grid's corners too.
#[test]
fn map_refuses_a_corner_with_too_many_steps() {
    let out = temp("map");
    let (code, err) = refused(&[
        "map",
        "--scene",
        "incline",
        "--x-axis",
        "h",
        "--x-range",
        "1e-9,2e-9",
        "--y-axis",
        "angle",
        "--y-range",
        "10,20",
        "--x-cells",
        "1",
        "--y-cells",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--x-range 1e-9,2e-9") && err.contains("a run may take at most 1e8"), "{err}");
    assert!(!out.exists(), "a refusal writes nothing");
}

/// `--horizon` was never checked: NaN, -1 or 1e6 ran the whole sweep, then failed at the plot;
/// a figures file was read without a cap (`/dev/zero` grew to 2 GB) and a directory was taken
/// for a missing file.
#[test]
fn report_refuses_its_horizon_and_figures_before_running() {
    let out = temp("report");
    let o = out.to_str().unwrap();
    for horizon in ["nan", "-1", "0", "1e6"] {
        let flag = format!("--horizon={horizon}");
        let (code, err) = refused(&["report", "--quick", &flag, "--out", o]);
        assert_eq!(code, 2, "{horizon}: {err}");
        assert!(err.contains("--horizon") && err.contains("at most 7.9"), "{horizon}: {err}");
    }
    let (code, err) = refused(&["report", "--quick", "--firmware-figures", "/dev/zero", "--out", o]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--firmware-figures /dev/zero") && err.contains("1 MiB"), "{err}");
    let dir = std::env::temp_dir();
    let (code, err) = refused(&["report", "--quick", "--bench-figures", dir.to_str().unwrap(), "--out", o]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--bench-figures"), "{err}");
    assert!(!out.exists(), "a refusal writes nothing");
}

/// The scenes of several bodies refuse what their stepper refuses (`multibody::SystemStepper::new`: a
/// negative step moved the blocks up, a negative mass or `mu_k > mu_s` was stepped, a zero mass
/// failed at the first step; `StackParams` took 1 to 4 blocks) in the words of the flag typed,
/// before any run: `host-sim run` writes nothing.
#[test]
fn several_bodies_refuse_their_steppers_bad_input_by_flag() {
    let out = temp("multibody");
    let o = out.to_str().unwrap();
    for (args, words) in [
        (&["--scene", "block-on-block", "--h", "-0.001"][..], "--h -0.001 s: must be greater than 0"),
        (&["--scene", "tablecloth", "--h", "nan"][..], "--h NaN s: not a finite number"),
        (&["--scene", "stack", "--mass", "-1"][..], "--mass -1 kg: must be greater than 0"),
        (&["--scene", "block-on-block", "--mass2", "0"][..], "--mass2 0 kg: must be greater than 0"),
        (&["--scene", "tablecloth", "--mu-s", "-0.1"][..], "--mu-s -0.1: must not be negative"),
        (&["--scene", "block-on-block", "--mu-k", "-0.1"][..], "--mu-k -0.1: must not be negative"),
        (&["--scene", "disc-on-board", "--mu-k", "0.7"][..], "--mu-k 0.7 must not exceed --mu-s 0.5"),
        (&["--scene", "stack", "--blocks", "1"][..], "--blocks 1: out of range (2 or 3)"),
        (&["--scene", "stack", "--blocks", "4"][..], "--blocks 4: out of range (2 or 3)"),
    ] {
        let run: Vec<&str> = ["run"].iter().chain(args).chain(&["--out", o]).copied().collect();
        let (code, err) = refused(&run);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(words), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?}: a refusal writes nothing");
        let scene: Vec<&str> = ["scene"].iter().chain(args).copied().collect();
        let (code, err) = refused(&scene);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(words), "{args:?}: {err}");
    }
}

/// A duration the user never typed is explained: the meter stick's default follows the fingers'
/// travel time, which a slow `--speed` makes long.
#[test]
fn a_duration_from_the_travel_time_says_so() {
    let (code, err) = refused(&["scene", "--speed", "1e-9"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("the default --duration follows the fingers' travel time"), "{err}");
    let (code, err) = refused(&["scene", "--scene", "incline", "--h", "1e-9", "--duration", "1000"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("imply") && !err.contains("travel time"), "{err}");
}

/// `host-sim qemu` named neither the file nor what was wrong with it ("Unknown file magic"), and
/// read the defmt table only after QEMU had run.
#[test]
fn qemu_names_a_file_that_is_not_a_firmware() {
    let junk = temp("junk.elf");
    std::fs::write(&junk, "not an ELF").unwrap();
    let (code, err) = refused(&["qemu", "--machine", "mps2-an386", junk.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(&format!("{}: not a firmware ELF", junk.display())), "{err}");
    let _ = std::fs::remove_file(&junk);
    // An ELF without a defmt table: this test's own executable.
    let me = std::env::current_exe().unwrap();
    let (code, err) = refused(&["qemu", "--machine", "mps2-an386", me.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("has no .defmt table"), "{err}");
}

/// Defaults in `--help` as a person writes them: the cylinder's 30 degrees went through radians
/// and showed as 29.999999999999996.
#[test]
fn help_shows_round_defaults() {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim")).args(["run", "--help"]).output().unwrap();
    let help = String::from_utf8(out.stdout).unwrap();
    assert!(help.contains("cylinder 30; painleve 30"), "{help}");
    assert!(!help.contains("29.99999"), "{help}");
}
