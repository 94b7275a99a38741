//! `host-sim`: the meterstick host harness.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use anyhow::Context as _;
use clap::{Parser, Subcommand};
use meterstick_host_sim::serve;
use meterstick_host_sim::{envelope, lcp_io, map, monitor, qemu, report, run_cmd, scene_cmd, stress};

#[derive(Parser, Debug)]
#[command(
    name = "host-sim",
    version,
    about = "meterstick host harness: LCP solves, scenes, reports, QEMU runs"
)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// Print the versions of host-sim and of meterstick-core.
    Version,
    /// Solve one LCP from a file (JSON with "M", a list of rows, and "q"; or a Siconos .dat
    /// file) and print one JSON object.
    Lcp {
        /// The LCP file.
        file: PathBuf,
        /// Scalar precision of the core solver.
        #[arg(long, value_enum, default_value = "f64")]
        precision: lcp_io::Precision,
    },
    /// The main job: a scene (default: the meter stick at the paper's slow 0.1 m/s and the fast
    /// speeds of fig. 5) in the core (f32 6x6 by default, as the firmware) beside the independent
    /// f64 reference; writes trajectory and event CSVs, summary.json and SVG plots per run, and
    /// prints a summary. Units: m, s, kg, m/s, degrees for angles.
    Run(run_cmd::RunArgs),
    /// Error against run time over a sweep of h (core f32 6x6, f32 8x8, f64 8x8, reference),
    /// and a success map over finger speed and mu_k/mu_s; writes report.md with pictures.
    Report(report::ReportArgs),
    /// The outcome over two parameters (default: the meter stick over finger speed x mu_k/mu_s,
    /// 200 x 50 cells), in parallel, with the boundaries between outcomes bisected; writes
    /// map.csv, boundaries.csv, summary.json and map.svg.
    Map(map::MapArgs),
    /// Where f32 holds: the f32 core against the f64 core over finger speed (1e-4 .. 10 m/s) x h
    /// (1e-5 .. 1e-2 s), with f64's own error (against h/2); writes envelope.md, .csv and .json.
    Envelope(envelope::EnvelopeArgs),
    /// Numerical stability on stiff and extreme cases: a grid of scenes (speed, h, friction,
    /// mass, rod shape, gravity, edge geometry, drops and penetrations, 10^6-step runs) in
    /// core f32 6x6, f32 8x8 and f64 8x8, judged by residual, penetration, energy and
    /// physics criteria; writes report.md, cases.csv, summary.json and criteria.svg. Exits 1
    /// when a case fails.
    Stress(stress::StressArgs),
    /// Run one scene in the core and print its outcome, measured quantities, switch events (with
    /// the eq. 21 ratio), solver statistics and trajectory checksum. Units: m, s, kg, m/s, degrees.
    Scene(scene_cmd::SceneCmd),
    /// Talk to the rig over its link (a serial port, or tcp:HOST:PORT for QEMU's UART): send
    /// commands from flags, print a line per event and a progress line, record a run in
    /// `host-sim run`'s files and compare it with the host's f32 build.
    Monitor(monitor::MonitorArgs),
    /// Run a firmware ELF under QEMU, print its decoded defmt output, and exit with the
    /// firmware's status.
    Qemu {
        /// The firmware ELF.
        elf: PathBuf,
        /// The QEMU machine.
        #[arg(long, value_enum)]
        machine: qemu::Machine,
        /// Kill the run after this many seconds.
        #[arg(long, default_value_t = 60)]
        timeout_s: u64,
        /// Deterministic instruction counting (`-icount shift=0`).
        #[arg(long)]
        icount: bool,
    },
    /// Serve the browser page (web/page/, the core compiled to WebAssembly) on 127.0.0.1, and
    /// optionally runs of `host-sim run` to replay in it (--replay out/run).
    Serve(serve::ServeArgs),
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("host-sim: error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Cmd::Version => {
            println!("host-sim {}", meterstick_host_sim::VERSION);
            println!("meterstick-core {}", meterstick_core::VERSION);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Lcp { file, precision } => {
            let text =
                std::fs::read_to_string(&file).with_context(|| format!("reading {}", file.display()))?;
            let data =
                lcp_io::parse(&text).with_context(|| format!("reading the LCP in {}", file.display()))?;
            let report = lcp_io::solve(&data, precision)?;
            println!("{}", serde_json::to_string(&report)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Run(args) => {
            print!("{}", run_cmd::run_cmd(&args)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Report(args) => {
            print!("{}", report::run(&args)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Envelope(args) => {
            print!("{}", envelope::run_envelope(&args)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Map(args) => {
            print!("{}", map::run_map(&args)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Stress(args) => {
            let (text, all_passed) = stress::run(&args)?;
            print!("{text}");
            Ok(if all_passed { ExitCode::SUCCESS } else { ExitCode::from(1) })
        }
        Cmd::Scene(args) => {
            print!("{}", scene_cmd::run_scene(&args)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Monitor(args) => {
            print!("{}", monitor::monitor(&args)?);
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Qemu { elf, machine, timeout_s, icount } => {
            let run = qemu::run(&elf, machine, Duration::from_secs(timeout_s), icount)?;
            for line in &run.lines {
                println!("{line}");
            }
            if run.timed_out {
                eprintln!("host-sim: firmware timed out after {timeout_s} s");
                return Ok(ExitCode::from(124));
            }
            let code = run.exit_code.unwrap_or(125);
            eprintln!("host-sim: firmware exit status {code}");
            Ok(ExitCode::from(u8::try_from(code).unwrap_or(125)))
        }
        Cmd::Serve(args) => {
            serve::run(&args)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}
