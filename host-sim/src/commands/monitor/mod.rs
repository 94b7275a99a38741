//! `host-sim monitor`: the host end of the rig's link ([`crate::monitor`]). Connects to a serial
//! port (the Black Pill's USB CDC port, e.g. `/dev/ttyACM0`) or a TCP port (`tcp:HOST:PORT`:
//! QEMU's UART), selects the rig's scene (`--scene`: the meter stick or the 3-block stack, on a
//! rig that runs both), sends commands from flags, prints a line per event and a progress line
//! ([`mod@print`]), records a run in the same files as `host-sim run` and compares it with the host's
//! f32 build of the same scene (bit-identical checksum and events expected); with
//! `--stress-grid`, the worst step of each meter-stick stress case on the rig ([`stress_grid`]).
//!
//! Files (under `--out`, default `out/monitor`): `rig.csv` and `rig-events.csv` (what the rig
//! sent; `host-sim run`'s trajectory and event columns, one row per telemetry frame), `core.csv`
//! and `core-events.csv` (the host's core f32 6x6 run of the parameters the rig reported, every
//! step), `summary.json` ([`MonitorSummary`]); with `--stress-grid`, `worst-steps.csv`.

pub mod print;
pub mod stack;
pub mod stress_grid;

use std::fmt::Write as _;
use std::io::IsTerminal as _;
use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context as _, bail};
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, PROTOCOL_VERSION, ParamId, Preset, Report, SceneId};
use serde::Serialize;

use crate::monitor::{Margin, RigComparison, apply_params, compare, read_params, record_run};
use crate::output::{create_dir, parameters_json, write_json};
use crate::scenes::{SceneKind, SceneParams};
use crate::trajectory::{OutcomeKind, write_csv, write_events_csv};
use meterstick_catalogue::Short;

use print::Printer;

/// A scene of the rig, as the command line spells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SceneArg {
    /// The meter stick (the carriage under a rod).
    MeterStick,
    /// The 3-block stack over a table's edge (its parameters: `length`, `height`, `mass`,
    /// `overhang`, `mu_static`, ...).
    Stack,
}

impl From<SceneArg> for SceneId {
    fn from(s: SceneArg) -> Self {
        match s {
            SceneArg::MeterStick => Self::MeterStick,
            SceneArg::Stack => Self::Stack,
        }
    }
}

/// A preset, as the command line spells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PresetArg {
    /// 0.1 m/s: the rod balances.
    Slow,
    /// 5 m/s: the rod falls.
    Fast,
    /// 0.3 m/s, next to the fall threshold.
    NearThreshold,
}

impl From<PresetArg> for Preset {
    fn from(p: PresetArg) -> Self {
        match p {
            PresetArg::Slow => Self::Slow,
            PresetArg::Fast => Self::Fast,
            PresetArg::NearThreshold => Self::NearThreshold,
        }
    }
}

/// `host-sim monitor` options. Commands go out in this order: scene, reset, preset, each `--set`,
/// telemetry rate, stop, start (then the run is recorded until its outcome).
#[derive(Debug, Clone, clap::Args)]
#[allow(clippy::struct_excessive_bools)] // command-line switches
pub struct MonitorArgs {
    /// The rig: a serial port (`/dev/ttyACM0`, `COM3`) or `tcp:HOST:PORT` (QEMU's UART, e.g.
    /// `qemu-system-arm ... -serial tcp::4444,server=on,wait=off` and `--port tcp:127.0.0.1:4444`).
    #[arg(long)]
    pub port: String,
    /// Baud rate of a serial port (ignored by USB CDC and TCP).
    #[arg(long, default_value_t = 115_200)]
    pub baud: u32,
    /// Switch the rig to this scene first (`SelectScene`; refused while a run is in progress, and
    /// by a rig that does not run it).
    #[arg(long, value_enum)]
    pub scene: Option<SceneArg>,
    /// Send `Reset` first (stops a run in progress, clears a fault).
    #[arg(long)]
    pub reset: bool,
    /// Load a preset.
    #[arg(long, value_enum)]
    pub preset: Option<PresetArg>,
    /// Set a parameter, `NAME=VALUE` (the core's names as in `host-sim run --help`, e.g.
    /// `finger1_velocity=0.2`; SI units, angles in radians); repeat the flag for more. The rig's
    /// core validates each and refuses a bad value by name.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Telemetry every N steps (0: off; the rig's default is 10).
    #[arg(long, value_name = "N")]
    pub telemetry: Option<u16>,
    /// Send `Stop` (ends a run in progress, unfinished).
    #[arg(long)]
    pub stop: bool,
    /// Start a run and record it until its outcome.
    #[arg(long)]
    pub start: bool,
    /// Wait for a run started on the rig (its button) and record it.
    #[arg(long, conflicts_with = "start")]
    pub follow: bool,
    /// Print the rig's link counters at the end.
    #[arg(long)]
    pub stats: bool,
    /// Run every meter-stick case of `host-sim stress` that starts at rest on the rig
    /// (telemetry off), each cut at `--max-steps`, and tabulate its worst step (the rig's
    /// margin) with what the host's f32 build did in that step (pivots, 8x8 fallback, warm
    /// start); writes `worst-steps.csv`. Under QEMU with `-icount shift=0` the cycles are
    /// SysTick ticks (40 instructions each on mps2-an386, 62.5 on the micro:bit).
    #[arg(long, conflicts_with_all = ["start", "follow"])]
    pub stress_grid: bool,
    /// With `--stress-grid`: the most steps of one case (at least 1).
    #[arg(long, default_value_t = 20_000)]
    pub max_steps: u32,
    /// Give up waiting for a reply or an outcome after this many seconds (at most a year).
    #[arg(long, default_value_t = 120.0)]
    pub timeout_s: f64,
    /// Where the recording goes (created; files in it are overwritten).
    #[arg(long, default_value = "out/monitor")]
    pub out: PathBuf,
    /// Do not run the host's f32 build for comparison.
    #[arg(long)]
    pub no_compare: bool,
}

/// `summary.json` of `host-sim monitor`.
#[derive(Debug, Clone, Serialize)]
pub struct MonitorSummary {
    /// Where the rig was.
    pub port: String,
    /// Which scene.
    pub scene: SceneKind,
    /// Every parameter the rig ran (core names, SI units, radians).
    pub parameters: serde_json::Map<String, serde_json::Value>,
    /// The rig's outcome.
    pub outcome: OutcomeKind,
    /// Simulated time at the end (s).
    pub end_time_s: f64,
    /// Steps.
    pub steps: u64,
    /// The rig's trajectory checksum.
    pub checksum: String,
    /// Switch events.
    pub switch_events: usize,
    /// Telemetry frames received.
    pub telemetry_frames: u64,
    /// Reports the rig dropped (its transmit queue was full).
    pub dropped_reports: u32,
    /// The rig's real-time margin.
    pub margin: Option<Margin>,
    /// Wall time of the run (s).
    pub wall_time_s: f64,
    /// Against the host's f32 build (absent with `--no-compare`).
    pub comparison: Option<RigComparison>,
}

/// Parses `NAME=VALUE` of `--set`.
///
/// # Errors
/// Not `NAME=VALUE`, an unknown name, or a value that is not a number (naming `--set`).
pub fn parse_set(s: &str) -> anyhow::Result<(ParamId, f32)> {
    let Some((name, value)) = s.split_once('=') else {
        bail!("--set {s}: expected NAME=VALUE, e.g. --set finger1_velocity=0.2");
    };
    let name = name.trim().replace('-', "_");
    let Some(id) = ParamId::ALL.into_iter().find(|p| p.name() == name) else {
        let names: Vec<&str> = ParamId::ALL.iter().map(|p| p.name()).collect();
        bail!("--set {s}: no parameter {name:?} (the rig has {})", names.join(", "));
    };
    let value: f32 = value.trim().parse().with_context(|| format!("--set {s}: {value:?} is not a number"))?;
    Ok((id, value))
}

/// The longest `--timeout-s`: a year (a deadline must stay within what `Instant` can hold).
const MAX_TIMEOUT_S: f64 = 365.0 * 86_400.0;

/// `host-sim monitor`: returns the closing summary (the live lines are printed as they come).
///
/// # Errors
/// Bad flags, the port, a refused command, a missing reply, or I/O.
pub fn run(args: &MonitorArgs) -> anyhow::Result<String> {
    let sets: Vec<(ParamId, f32)> = args.set.iter().map(|s| parse_set(s)).collect::<anyhow::Result<_>>()?;
    if !(args.timeout_s.is_finite() && args.timeout_s > 0.0 && args.timeout_s <= MAX_TIMEOUT_S) {
        bail!(
            "--timeout-s {}: must be a positive number of seconds, at most {MAX_TIMEOUT_S} (a year)",
            Short(args.timeout_s)
        );
    }
    if args.stress_grid && args.max_steps == 0 {
        bail!("--max-steps 0: each case needs at least one step");
    }
    let timeout = Duration::from_secs_f64(args.timeout_s);
    let mut link = Link::open(&args.port, args.baud)?;
    let mut printer = Printer::new(std::io::stderr().is_terminal());
    let mut hello = link.request(&Command::Hello, REPLY_TIMEOUT)?;
    if let (Some(want), Report::Hello { scene, .. }) = (args.scene, hello)
        && scene != SceneId::from(want)
    {
        let select = Command::SelectScene(want.into());
        match link.request(&select, REPLY_TIMEOUT)? {
            Report::Ack { .. } => {}
            other => bail!("--scene: the rig refused it: {other:?}"),
        }
        // The new scene's Hello follows the acknowledgement (after the boot's, if still waiting).
        hello = loop {
            match link.next(REPLY_TIMEOUT)? {
                Some(h @ Report::Hello { scene, .. }) if scene == SceneId::from(want) => break h,
                Some(_) => {}
                None => bail!("--scene: no Hello from the rig's new scene"),
            }
        };
    }
    let mut scene = SceneId::MeterStick;
    if let Report::Hello { protocol, firmware, build, lcp_size, step_us, scene: s, .. } = hello {
        scene = s;
        if protocol != PROTOCOL_VERSION {
            bail!(
                "{}: the rig speaks protocol version {protocol}, this host-sim version {PROTOCOL_VERSION}",
                args.port
            );
        }
        printer.line(&format!(
            "rig: {s:?}, firmware {}.{}.{} ({}), {lcp_size}x{lcp_size} LCP, h = {step_us} us, protocol {protocol}",
            firmware.0,
            firmware.1,
            firmware.2,
            String::from_utf8_lossy(&build).trim()
        ));
    }
    let simple = |link: &mut Link, command: Command, flag: &str| -> anyhow::Result<()> {
        match link.request(&command, REPLY_TIMEOUT)? {
            Report::Ack { .. } => Ok(()),
            other => bail!("{flag}: the rig refused it: {other:?}"),
        }
    };
    if args.reset {
        simple(&mut link, Command::Reset, "--reset")?;
    }
    if let Some(p) = args.preset {
        simple(&mut link, Command::Preset(p.into()), "--preset")?;
    }
    let refused = apply_params(&mut link, &sets)?;
    if let Some(r) = refused.first() {
        bail!("--set {}: the rig refused it: {}", r.id.name(), r.reason.words());
    }
    if let Some(n) = args.telemetry {
        simple(&mut link, Command::SetTelemetry { every_n_steps: n }, "--telemetry")?;
    }
    if args.stop {
        simple(&mut link, Command::Stop, "--stop")?;
    }
    let mut summary = String::new();
    if (args.start || args.follow) && scene == SceneId::Stack {
        summary = stack::record_and_write(&mut link, args, timeout, &mut printer)?;
    } else if args.start || args.follow {
        summary = record_and_write(&mut link, args, timeout, &mut printer)?;
    }
    if args.stress_grid && scene != SceneId::MeterStick {
        bail!("--stress-grid: the stress cases are the meter stick's, the rig runs {scene:?}");
    }
    if args.stress_grid {
        summary.push_str(&stress_grid::run(&mut link, args)?);
    }
    if args.stats {
        if let Report::Stats(s) = link.request(&Command::GetStats, REPLY_TIMEOUT)? {
            let _ = writeln!(
                summary,
                "rig link: {} frames ok, {} CRC errors, {} COBS errors, {} decode errors, {} overflows, {} bytes",
                s.frames_ok, s.crc_errors, s.cobs_errors, s.decode_errors, s.overflows, s.bytes
            );
        }
        let h = link.host_stats();
        let _ = writeln!(
            summary,
            "host link: {} frames ok, {} dropped, {} bytes",
            h.frames_ok,
            h.dropped(),
            h.bytes
        );
    }
    Ok(summary)
}

/// Records a run (`--start` or `--follow`), writes its files, compares it with the host and
/// returns the closing lines.
fn record_and_write(
    link: &mut Link,
    args: &MonitorArgs,
    timeout: Duration,
    printer: &mut Printer,
) -> anyhow::Result<String> {
    let mut summary = String::new();
    let params = read_params(link)?;
    let rec = record_run(link, params, args.start, timeout, printer)?;
    printer.clear();
    create_dir(&args.out)?;
    write_csv(&rec.trajectory, &args.out.join("rig.csv"))?;
    write_events_csv(&rec.trajectory, &args.out.join("rig-events.csv"))?;
    let comparison = if args.no_compare {
        None
    } else {
        let (host, cmp) = compare(&rec)?;
        write_csv(&host, &args.out.join("core.csv"))?;
        write_events_csv(&host, &args.out.join("core-events.csv"))?;
        let _ = writeln!(
            summary,
            "host f32 6x6: {} after {} steps, checksum {}: {}",
            host.outcome,
            host.steps,
            cmp.host_checksum,
            if cmp.identical() { "identical to the rig's run" } else { "DIFFERENT from the rig's run" }
        );
        Some(cmp)
    };
    let t = &rec.trajectory;
    let s = MonitorSummary {
        port: args.port.clone(),
        scene: SceneKind::MeterStick,
        parameters: parameters_json(&SceneParams::MeterStick(rec.params.cast())),
        outcome: t.outcome.class,
        end_time_s: t.end_time,
        steps: t.steps,
        checksum: format!("{:08x}", rec.checksum),
        switch_events: t.events.len(),
        telemetry_frames: rec.telemetry_frames,
        dropped_reports: rec.dropped,
        margin: rec.margin,
        wall_time_s: rec.wall_s,
        comparison,
    };
    write_json(&args.out.join("summary.json"), &s)?;
    let _ = writeln!(
        summary,
        "rig: {} at t = {:.3} s after {} steps, checksum {:08x}, {} events, {} telemetry frames ({} dropped) in {:.1} s; files in {}",
        t.outcome,
        t.end_time,
        t.steps,
        rec.checksum,
        t.events.len(),
        rec.telemetry_frames,
        rec.dropped,
        rec.wall_s,
        args.out.display()
    );
    answer(summary, s.comparison.as_ref().is_none_or(RigComparison::identical), &args.out)
}

/// `summary` as the command's answer; when the rig's run is not `identical` to the host's, a
/// failed check (exit status 1, not bad input) naming `summary.json` in `out`.
fn answer(summary: String, identical: bool, out: &std::path::Path) -> anyhow::Result<String> {
    if identical {
        return Ok(summary);
    }
    Err(crate::errors::CheckFailed(format!(
        "{summary}the rig's run differs from the host's f32 build (see {})",
        out.join("summary.json").display()
    ))
    .into())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::panic)]
    use super::*;

    #[test]
    fn set_flags_parse_and_name_themselves_in_errors() {
        assert_eq!(parse_set("mu_kinetic=0.35").unwrap(), (ParamId::MuKinetic, 0.35));
        assert_eq!(parse_set("finger1-velocity = 0.2").unwrap(), (ParamId::Finger1Velocity, 0.2));
        let e = parse_set("mu=0.3").unwrap_err().to_string();
        assert!(e.starts_with("--set mu=0.3: no parameter \"mu\"") && e.contains("mu_static"), "{e}");
        let e = parse_set("gravity=fast").unwrap_err().to_string();
        assert!(e.contains("--set gravity=fast") && e.contains("not a number"), "{e}");
        assert!(parse_set("gravity").unwrap_err().to_string().contains("expected NAME=VALUE"));
    }
}
