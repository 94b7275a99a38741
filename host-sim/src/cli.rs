//! The `host-sim` command line: its arguments ([`Cli`]), how they are read ([`parse_from`]), what
//! each command does ([`run`]) and the exit status ([`main_with`]), in the library so that tests
//! (and the fuzz target `tests/tests/fuzz_inputs.rs`) reach them.
//!
//! Exit status (also in `host-sim --help`, each subcommand's `--help` and `docs/host-sim.md`):
//! 0 done; 1 a check failed (`stress`: a case failed; `monitor`: the rig's run differs from the
//! host's); 2 bad input (a refused flag or value, an unreadable, oversized or malformed file) or
//! another error (I/O); 130 stopped by Ctrl-C (the files written so far are listed); `qemu`
//! passes the firmware's own status through (124 timed out, 125 no status).

use std::ffi::OsString;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::SystemTime;

use clap::{CommandFactory as _, Parser, Subcommand};

use crate::commands::{
    envelope, lcp, map, monitor, qemu, report, run as run_command, scene, serve, stress, version,
};
use crate::progress;

/// The exit statuses, as `host-sim --help` shows them.
pub const EXIT_STATUS_HELP: &str = "\
Exit status:
  0    done (lcp: also when the LCP has no solution; its \"status\" says so)
  1    a check failed: stress (a case failed), monitor (the rig's run differs from the host's)
  2    bad input (a refused flag or value; an unreadable, oversized or malformed file), or another
       error (I/O); after a refusal nothing has run
  130  stopped by Ctrl-C (run, report, map, envelope, stress, scene): the files written so far
       are listed
  qemu exits with the firmware's own status (124: timed out, 125: no status)";

const DONE_OR_BAD: &str = "Exit status: 0 done, 2 bad input or another error (I/O).";
const LONG: &str = "Exit status: 0 done, 2 bad input or another error (I/O), 130 stopped by Ctrl-C (the \
                    files written so far are listed).";

/// `host-sim`'s arguments.
#[derive(Parser, Debug)]
#[command(
    name = "host-sim",
    version,
    about = "meterstick host harness: LCP solves, scenes, reports, QEMU runs",
    after_help = EXIT_STATUS_HELP
)]
pub struct Cli {
    /// The command.
    #[command(subcommand)]
    pub command: Cmd,
}

/// `host-sim`'s commands.
#[derive(Subcommand, Debug)]
pub enum Cmd {
    /// Print the versions of host-sim and of meterstick-core.
    #[command(after_help = "Exit status: 0.")]
    Version,
    /// Solve one LCP from a file (JSON with "M", a list of rows, and "q"; or a Siconos .dat
    /// file) and print one JSON object. The format is the one the file's name says (.json,
    /// .dat), else the one its content suggests; at most 1 MiB is read, and n <= 16.
    #[command(after_help = "Exit status: 0 solved or not (the printed \"status\" says which: solution, \
                            ray, max_pivots, non_finite, unverified), 2 an unreadable, oversized or \
                            malformed file, or n outside 1..=16.")]
    Lcp(lcp::LcpArgs),
    /// The main job: a scene (default: the meter stick at the paper's slow 0.1 m/s and the fast
    /// speeds of fig. 5) in the core (f32 6x6 by default, as the firmware) beside the independent
    /// f64 reference; writes trajectory and event CSVs, summary.json and SVG plots per run, and
    /// prints a summary. Units: m, s, kg, m/s, degrees for angles.
    #[command(after_help = LONG)]
    Run(run_command::RunArgs),
    /// Error against run time over a sweep of h (core f32 6x6, f32 8x8, f64 8x8, reference),
    /// and a success map over finger speed and mu_k/mu_s; writes report.md with pictures.
    #[command(after_help = LONG)]
    Report(report::ReportArgs),
    /// The outcome over two parameters (default: the meter stick over finger speed x mu_k/mu_s,
    /// 200 x 50 cells), in parallel, with the boundaries between outcomes bisected; writes
    /// map.csv, boundaries.csv, summary.json and map.svg.
    #[command(after_help = LONG)]
    Map(map::MapArgs),
    /// Where f32 holds: the f32 core against the f64 core over finger speed (1e-4 .. 10 m/s) x h
    /// (1e-5 .. 1e-2 s), with f64's own error (against h/2); writes envelope.md, .csv and .json.
    #[command(after_help = LONG)]
    Envelope(envelope::EnvelopeArgs),
    /// Numerical stability on stiff and extreme cases: a grid of scenes (speed, h, friction,
    /// mass, rod shape, gravity, edge geometry, drops and penetrations, 10^6-step runs) in
    /// core f32 6x6, f32 8x8 and f64 8x8, judged by residual, penetration, energy and
    /// physics criteria; writes report.md, cases.csv, summary.json and criteria.svg.
    #[command(after_help = "Exit status: 0 every case passed, 1 a case failed, 2 bad input or another \
                            error (I/O), 130 stopped by Ctrl-C (the report covers the cases finished; \
                            the files written are listed).")]
    Stress(crate::stress::StressArgs),
    /// Run one scene in the core and print its outcome, measured quantities, switch events (with
    /// the eq. 21 ratio), solver statistics and trajectory checksum. Units: m, s, kg, m/s, degrees.
    #[command(after_help = "Exit status: 0 done (whatever the outcome), 2 bad input, 130 stopped by Ctrl-C.")]
    Scene(scene::SceneCmdArgs),
    /// Talk to the rig over its link (a serial port, or tcp:HOST:PORT for QEMU's UART): send
    /// commands from flags, print a line per event and a progress line, record a run in
    /// `host-sim run`'s files and compare it with the host's f32 build.
    #[command(after_help = "Exit status: 0 done (a recorded run identical to the host's), 1 the rig's \
                            run differs from the host's, 2 bad input, a refused parameter, or a link \
                            error (the port, a timeout).")]
    Monitor(monitor::MonitorArgs),
    /// Run a firmware ELF under QEMU, print its decoded defmt output, and exit with the
    /// firmware's status.
    #[command(after_help = "Exit status: the firmware's (semihosting exit), 124 timed out, 125 ended \
                            without a status, 2 bad input or QEMU not startable.")]
    Qemu(qemu::QemuArgs),
    /// Serve the browser page (web/page/, the core compiled to WebAssembly) on 127.0.0.1, and
    /// optionally runs of `host-sim run` to replay in it (--replay out/run).
    #[command(after_help = DONE_OR_BAD)]
    Serve(crate::serve::ServeArgs),
}

impl Cmd {
    /// The output folder of a command that writes one.
    #[must_use]
    pub fn out_dir(&self) -> Option<&Path> {
        match self {
            Self::Run(a) => Some(&a.out),
            Self::Report(a) => Some(&a.out),
            Self::Map(a) => Some(&a.out),
            Self::Envelope(a) => Some(&a.out),
            Self::Stress(a) => Some(&a.out),
            Self::Monitor(a) => Some(&a.out),
            _ => None,
        }
    }

    /// `true` for the commands that stop cleanly on Ctrl-C ([`progress`]).
    #[must_use]
    pub const fn stops_on_ctrl_c(&self) -> bool {
        matches!(
            self,
            Self::Run(_)
                | Self::Report(_)
                | Self::Map(_)
                | Self::Envelope(_)
                | Self::Stress(_)
                | Self::Scene(_)
        )
    }
}

/// The clap command (every subcommand and flag): what `--help` shows, and what the fuzz target
/// builds its argument vectors from.
#[must_use]
pub fn command() -> clap::Command {
    Cli::command()
}

pub use crate::errors::CheckFailed;

/// Reads the arguments (`args[0]` is the program name) as clap does, and first refuses a flag
/// whose value is missing because the next argument is another flag (`--h --duration 2`:
/// the scene flags accept values starting with `-`, so clap would take `--duration` as the value
/// of `--h` and then complain about an "unexpected argument '2'").
///
/// # Errors
/// clap's error (usage, `--help` and `--version` included: [`clap::Error::exit_code`] says which).
pub fn parse_from<I, T>(args: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    missing_value(&args)?;
    Cli::try_parse_from(args)
}

/// `--flag` followed by a known flag of the same command, where `--flag` takes a value that may
/// start with `-`.
fn missing_value(args: &[OsString]) -> Result<(), clap::Error> {
    let mut cli = Cli::command();
    let Some(name) = args.get(1).and_then(|a| a.to_str()) else { return Ok(()) };
    let Some(sub) = cli.find_subcommand_mut(name) else { return Ok(()) };
    let long_of = |tok: &str| tok.strip_prefix("--").map(|t| t.split('=').next().unwrap_or(t).to_owned());
    let is_flag = |sub: &clap::Command, tok: &str| {
        long_of(tok)
            .is_some_and(|l| l == "help" || sub.get_arguments().any(|a| a.get_long() == Some(l.as_str())))
    };
    for pair in args.get(2..).unwrap_or_default().windows(2) {
        let (Some(tok), Some(next)) = (pair[0].to_str(), pair[1].to_str()) else { continue };
        if tok == "--" {
            break;
        }
        if tok.contains('=') {
            continue;
        }
        let Some(long) = long_of(tok) else { continue };
        let hyphen_value = sub.get_arguments().any(|a| {
            a.get_long() == Some(long.as_str())
                && a.get_action().takes_values()
                && a.is_allow_hyphen_values_set()
        });
        if hyphen_value && is_flag(sub, next) {
            let sub_name = format!("host-sim {name}");
            let mut sub = sub.clone().bin_name(sub_name);
            return Err(sub.error(
                clap::error::ErrorKind::InvalidValue,
                format!("a value is required for '{tok}' but none was supplied (the next argument, '{next}', is a flag)"),
            ));
        }
    }
    Ok(())
}

/// Runs a command and returns its exit status (see [`EXIT_STATUS_HELP`]).
///
/// # Errors
/// Bad input or an error while running (status 2), [`CheckFailed`] (status 1),
/// [`progress::Interrupted`] (status 130).
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    if cli.command.stops_on_ctrl_c() {
        progress::install_ctrl_c()?;
    }
    let text = match cli.command {
        Cmd::Version => version::run()?,
        Cmd::Lcp(args) => lcp::run(&args)?,
        Cmd::Run(args) => run_command::run(&args)?,
        Cmd::Report(args) => report::run(&args)?,
        Cmd::Envelope(args) => envelope::run(&args)?,
        Cmd::Map(args) => map::run(&args)?,
        Cmd::Stress(args) => stress::run(&args)?,
        Cmd::Scene(args) => scene::run(&args)?,
        Cmd::Monitor(args) => monitor::run(&args)?,
        Cmd::Qemu(args) => return qemu::run(&args),
        Cmd::Serve(args) => {
            serve::run(&args)?;
            String::new()
        }
    };
    print!("{text}");
    Ok(ExitCode::SUCCESS)
}

/// The exit status of an error: 1 for [`CheckFailed`], 130 for [`progress::Interrupted`], else 2.
#[must_use]
pub fn exit_status_of(e: &anyhow::Error) -> u8 {
    if progress::is_interrupted(e) {
        progress::EXIT_INTERRUPTED
    } else if e.chain().any(<dyn std::error::Error>::is::<CheckFailed>) {
        1
    } else {
        2
    }
}

/// `host-sim` with these arguments (`args[0]` is the program name): parses, runs, prints errors
/// and returns the exit status.
pub fn main_with<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2));
        }
    };
    let started = SystemTime::now();
    let out = cli.command.out_dir().map(Path::to_path_buf);
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            let status = exit_status_of(&e);
            if status == progress::EXIT_INTERRUPTED {
                eprintln!("host-sim: {}", written_since(out.as_deref(), started));
            } else {
                eprintln!("host-sim: error: {e:#}");
            }
            ExitCode::from(status)
        }
    }
}

/// After Ctrl-C: the files under `out` written since `started`, listed.
#[must_use]
pub fn written_since(out: Option<&Path>, started: SystemTime) -> String {
    let mut files = Vec::new();
    if let Some(out) = out {
        collect_newer(out, started, &mut files);
    }
    files.sort();
    let head = "stopped by Ctrl-C: no new run started, the runs under way were dropped";
    match (out, files.len()) {
        (None, _) => format!("{head}; nothing written"),
        (Some(out), 0) => format!("{head}; nothing written in {}", out.display()),
        (Some(out), n) => {
            const SHOWN: usize = 200;
            let mut s = format!("{head}; written so far in {} ({n} files):", out.display());
            for f in files.iter().take(SHOWN) {
                s.push_str("\n  ");
                s.push_str(&f.display().to_string());
            }
            if n > SHOWN {
                let _ = write!(s, "\n  ... and {} more", n - SHOWN);
            }
            s
        }
    }
}

fn collect_newer(dir: &Path, since: SystemTime, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let Ok(meta) = e.metadata() else { continue };
        if meta.is_dir() {
            collect_newer(&e.path(), since, out);
        } else if meta.modified().is_ok_and(|m| m >= since) {
            out.push(e.path());
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn exit_statuses_follow_the_error() {
        assert_eq!(exit_status_of(&anyhow::anyhow!("--h 0 s: must be greater than 0")), 2);
        let failed: anyhow::Error = CheckFailed("stress: a case failed".into()).into();
        assert_eq!(exit_status_of(&failed), 1);
        assert_eq!(exit_status_of(&failed.context("while writing")), 1);
        let stopped: anyhow::Error = progress::Interrupted.into();
        assert_eq!(exit_status_of(&stopped.context("map cell (0.1, 0.5)")), 130);
    }

    /// Every subcommand's `--help` states its exit status, and the top-level one lists them all.
    #[test]
    fn every_help_states_the_exit_status() {
        let mut cli = Cli::command();
        let top = cli.render_help().to_string();
        for line in
            ["0    done", "1    a check failed", "2    bad input", "130  stopped by Ctrl-C", "qemu exits"]
        {
            assert!(top.contains(line), "{line:?} missing from host-sim --help:\n{top}");
        }
        for sub in cli.get_subcommands_mut().filter(|s| s.get_name() != "help") {
            let help = sub.render_help().to_string();
            assert!(help.contains("Exit status: "), "host-sim {} --help:\n{help}", sub.get_name());
        }
    }

    /// `--h --duration 2`: the missing value is named. Before, clap took `--duration` as the value
    /// of `--h` and said "unexpected argument '2' found".
    #[test]
    fn a_flag_followed_by_a_flag_is_a_missing_value() {
        let e = parse_from(["host-sim", "run", "--h", "--duration", "2"]).unwrap_err().to_string();
        assert!(
            e.contains("a value is required for '--h' but none was supplied (the next argument, '--duration', is a flag)"),
            "{e}"
        );
        let e = parse_from(["host-sim", "scene", "--speed", "--help"]).unwrap_err().to_string();
        assert!(e.contains("'--speed' but none was supplied"), "{e}");
        // Negative numbers and lists are values.
        assert!(parse_from(["host-sim", "run", "--speed2", "-0.1", "--x2", "0.35"]).is_ok());
        assert!(parse_from(["host-sim", "run", "--speed", "-0.1,-0.2"]).is_ok());
        let e = parse_from(["host-sim", "run", "--h=--duration"]).unwrap_err().to_string();
        assert!(e.contains("\"--duration\" is not a number"), "an explicit value is the user's: {e}");
    }
}
