//! `host-sim qemu`: a firmware ELF under QEMU ([`crate::qemu`]), its defmt output decoded, and
//! the firmware's own exit status.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use crate::qemu;

/// `host-sim qemu` options.
#[derive(Debug, Clone, clap::Args)]
pub struct QemuArgs {
    /// The firmware ELF (at most 64 MiB is read).
    pub elf: PathBuf,
    /// The QEMU machine.
    #[arg(long, value_enum)]
    pub machine: qemu::Machine,
    /// Kill the run after this many seconds.
    #[arg(long, default_value_t = 60)]
    pub timeout_s: u64,
    /// Deterministic instruction counting (`-icount shift=0`).
    #[arg(long)]
    pub icount: bool,
    /// Print one JSON object instead of the lines: the exit, the lines and the step timing
    /// in instructions (`scripts/firmware-report.sh` reads it).
    #[arg(long)]
    pub json: bool,
}

/// Runs the firmware, prints its lines (or the JSON object) and returns its exit status: the
/// firmware's, 124 timed out, 125 no status.
///
/// # Errors
/// Bad input, or QEMU not startable.
pub fn run(args: &QemuArgs) -> anyhow::Result<ExitCode> {
    let QemuArgs { elf, machine, timeout_s, icount, json } = args;
    let run = qemu::run(elf, *machine, Duration::from_secs(*timeout_s), *icount)?;
    if *json {
        let summary = qemu::RunStats {
            exit_code: run.exit_code,
            timed_out: run.timed_out,
            timing: qemu::timing(&run.lines)?,
            lines: run.lines.clone(),
        };
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        for line in &run.lines {
            println!("{line}");
        }
    }
    if run.timed_out {
        eprintln!("host-sim: firmware timed out after {timeout_s} s");
        return Ok(ExitCode::from(124));
    }
    let code = run.exit_code.unwrap_or(125);
    eprintln!("host-sim: firmware exit status {code}");
    Ok(ExitCode::from(u8::try_from(code).unwrap_or(125)))
}
