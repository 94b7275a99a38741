//! `host-sim monitor`: the host end of the rig's link (`meterstick-link`). Connects to a serial
//! port (the Black Pill's USB CDC port, e.g. `/dev/ttyACM0`) or a TCP port (`tcp:HOST:PORT`:
//! QEMU's UART), sends commands from flags, prints a line per event and a progress line, records
//! a run in the same files as `host-sim run` and compares it with the host's f32 build of the
//! same scene (bit-identical checksum and events expected).
//!
//! Files (under `--out`, default `out/monitor`): `rig.csv` and `rig-events.csv` (what the rig
//! sent; `host-sim run`'s trajectory and event columns, one row per telemetry frame), `core.csv`
//! and `core-events.csv` (the host's core f32 6x6 run of the parameters the rig reported, every
//! step), `summary.json` ([`MonitorSummary`]). In `rig.csv`, `along1/along2` are computed from
//! the state after the step (the rig sends them with the switch events only), and the supports
//! are the finger tips at the fingers' reported `x` and their parameter heights.
//!
//! The library part ([`read_params`], [`apply_params`], [`record_run`], [`compare`]), over
//! `meterstick-link`'s [`Link`] (link/src/host.rs), is what the end-to-end tests
//! (`tests/tests/link_checks/`) drive.

use std::fmt::Write as _;
use std::io::IsTerminal as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};
use meterstick_core::planar::{ContactMode, Direction};
use meterstick_core::scene::MeterStickParams;
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{
    Command, ContactTelemetry, ErrorCode, Mode, OutcomeCode, PROTOCOL_VERSION, ParamId, Preset, RejectReason,
    Report, RigState,
};
use serde::Serialize;

use crate::output::{parameters_json, write_json};
use crate::scenes::{Implementation, SceneKind, SceneSpec};
use crate::trajectory::{
    ContactRow, Event, Measured, OutcomeClass, Record, Row, RunOutcome, SolverCounters, Trajectory, run_core,
    write_csv, write_events_csv,
};

/// The rig's scene is the meter stick: two contacts (its telemetry's `contacts`).
const RIG_CONTACTS: usize = 2;

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

/// `host-sim monitor` options. Commands go out in this order: reset, preset, each `--set`,
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
    /// With `--stress-grid`: the most steps of one case.
    #[arg(long, default_value_t = 20_000)]
    pub max_steps: u32,
    /// Give up waiting for a reply or an outcome after this many seconds.
    #[arg(long, default_value_t = 120.0)]
    pub timeout_s: f64,
    /// Where the recording goes (created; files in it are overwritten).
    #[arg(long, default_value = "out/monitor")]
    pub out: PathBuf,
    /// Do not run the host's f32 build for comparison.
    #[arg(long)]
    pub no_compare: bool,
}

/// The rig's parameter set, read back with `GetParam` (every [`ParamId`]).
///
/// # Errors
/// A missing reply, or a name the core does not know.
pub fn read_params(link: &mut Link) -> anyhow::Result<MeterStickParams<f32>> {
    let mut p = MeterStickParams::<f32>::default();
    for id in ParamId::ALL {
        match link.request(&Command::GetParam { id }, REPLY_TIMEOUT)? {
            Report::Param { value, .. } => {
                if !p.set(id.name(), value) {
                    bail!("the rig's parameter {} is not a meter-stick parameter", id.name());
                }
            }
            other => bail!("GetParam {}: unexpected reply {other:?}", id.name()),
        }
    }
    Ok(p)
}

/// A parameter the rig refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Refused {
    /// Which.
    pub id: ParamId,
    /// Why (the core's validation).
    pub reason: RejectReason,
}

/// Sets `values` on the rig in order; a value refused because of another one not yet set
/// (finger outside the rod, crossed fingers, mu_k above mu_s) is tried again after the others.
/// Returns the refusals that remain.
///
/// # Errors
/// A missing reply.
pub fn apply_params(link: &mut Link, values: &[(ParamId, f32)]) -> anyhow::Result<Vec<Refused>> {
    let mut todo: Vec<(ParamId, f32)> = values.to_vec();
    let mut refused = Vec::new();
    for _pass in 0..3 {
        refused.clear();
        let mut again = Vec::new();
        for &(id, value) in &todo {
            match link.request(&Command::SetParam { id, value }, REPLY_TIMEOUT)? {
                Report::Ack { .. } => {}
                Report::Rejected { reason, .. } => {
                    refused.push(Refused { id, reason });
                    again.push((id, value));
                }
                other => bail!("SetParam {}: unexpected reply {other:?}", id.name()),
            }
        }
        if again.is_empty() || again.len() == todo.len() {
            break;
        }
        todo = again;
    }
    Ok(refused)
}

/// The real-time margin the rig reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Margin {
    /// The longest step (CPU cycles; under QEMU SysTick ticks).
    pub worst_cycles: u32,
    /// The step period (cycles; 0: not real time).
    pub period_cycles: u32,
    /// Steps over their period.
    pub overruns: u32,
    /// The step number of the longest step.
    pub worst_step: u32,
}

/// A run as the rig reported it.
#[derive(Debug, Clone)]
pub struct Recording {
    /// The parameters the rig ran (read back before the start).
    pub params: MeterStickParams<f32>,
    /// The run, in `host-sim run`'s form (rows: the telemetry frames).
    pub trajectory: Trajectory,
    /// The rig's outcome code.
    pub outcome: OutcomeCode,
    /// The rig's checksum of the run.
    pub checksum: u32,
    /// The last margin.
    pub margin: Option<Margin>,
    /// Reports the rig said it dropped.
    pub dropped: u32,
    /// Telemetry frames received.
    pub telemetry_frames: u64,
    /// Wall time from start to outcome (s).
    pub wall_s: f64,
}

/// How the rig's modes map to the core's.
#[must_use]
pub const fn mode_of(m: Mode) -> ContactMode {
    match m {
        Mode::Separated => ContactMode::Separated,
        Mode::Sticking => ContactMode::Sticking,
        Mode::SlidingPositive => ContactMode::Sliding(Direction::Plus),
        Mode::SlidingNegative => ContactMode::Sliding(Direction::Minus),
    }
}

fn outcome_of(o: OutcomeCode) -> RunOutcome {
    match o {
        OutcomeCode::Balanced => RunOutcome::of(OutcomeClass::Balanced),
        OutcomeCode::Fell => RunOutcome::of(OutcomeClass::Fell),
        OutcomeCode::Held => RunOutcome::of(OutcomeClass::Held),
        OutcomeCode::Slid => RunOutcome::of(OutcomeClass::Slid),
        OutcomeCode::Tipped => RunOutcome::of(OutcomeClass::Tipped),
        OutcomeCode::Unfinished => RunOutcome::of(OutcomeClass::Unfinished),
        other => RunOutcome { class: OutcomeClass::Failed, detail: Some(format!("{other:?}")) },
    }
}

/// What [`record_run`] shows while it records.
pub trait Observer {
    /// Every report of the run, as it arrives.
    fn report(&mut self, report: &Report);
}

impl<F: FnMut(&Report)> Observer for F {
    fn report(&mut self, report: &Report) {
        self(report);
    }
}

/// Records a run until its outcome (and the margin after it): with `start`, sends `Start`
/// first; otherwise waits for a run to begin (the rig's button). `params` are the rig's.
///
/// # Errors
/// The start refused, no outcome within `timeout`, or the link failed.
pub fn record_run(
    link: &mut Link,
    params: MeterStickParams<f32>,
    start: bool,
    timeout: Duration,
    observer: &mut dyn Observer,
) -> anyhow::Result<Recording> {
    let began = Instant::now();
    if start {
        match link.request(&Command::Start, REPLY_TIMEOUT)? {
            Report::Ack { .. } => {}
            other => bail!("the rig refused to start: {other:?}"),
        }
    }
    let deadline = began + timeout;
    let heights = [f64::from(params.finger1_y), f64::from(params.finger2_y)];
    let mut rows = Vec::new();
    let mut events = Vec::new();
    let mut initial_modes = None;
    let mut outcome = None;
    let mut margin = None;
    let mut dropped = 0_u32;
    let mut telemetry_frames = 0;
    let mut running = !start;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let Some(report) = link.next(left.min(Duration::from_millis(500)))? else {
            if Instant::now() >= deadline {
                bail!("{}: no outcome within {:.0} s", link.name, timeout.as_secs_f64());
            }
            continue;
        };
        observer.report(&report);
        match report {
            Report::State(RigState::Running) => running = true,
            Report::Telemetry { step, time, state, fingers, contacts } if running => {
                telemetry_frames += 1;
                let row = row_of(time, state, fingers, contacts, heights);
                if step == 0 {
                    initial_modes = Some(contacts.map(|c| mode_of(c.mode)));
                }
                rows.push(row);
            }
            Report::Switch { time, contact, mode, along, .. } if running => events.push(Event {
                t: f64::from(time),
                contact: usize::from(contact),
                mode: mode_of(mode),
                along: along.map(f64::from),
                supports: [[f64::NAN; 2]; RIG_CONTACTS],
            }),
            Report::Outcome { outcome: code, time, steps, checksum } if running => {
                outcome = Some((code, time, steps, checksum));
            }
            Report::Margin { worst_cycles, period_cycles, overruns, worst_step } => {
                margin = Some(Margin { worst_cycles, period_cycles, overruns, worst_step });
            }
            Report::Error(ErrorCode::TxDropped { count }) => dropped = dropped.saturating_add(count),
            _ => {}
        }
        // After the outcome the rig sends the run's margin, then its new state.
        if outcome.is_some() && matches!(report, Report::State(s) if s != RigState::Running) {
            break;
        }
    }
    let Some((code, time, steps, checksum)) = outcome else { bail!("no outcome") };
    let trajectory = Trajectory {
        implementation: Implementation::CORE_F32_6,
        scene: SceneKind::MeterStick,
        steps: u64::from(steps),
        end_time: f64::from(time),
        initial_modes: initial_modes.unwrap_or([ContactMode::Separated; RIG_CONTACTS]),
        rows,
        events,
        outcome: outcome_of(code),
        measured: Measured::default(),
        counters: SolverCounters::default(),
        checksum: Some(checksum),
    };
    Ok(Recording {
        params,
        trajectory,
        outcome: code,
        checksum,
        margin,
        dropped,
        telemetry_frames,
        wall_s: began.elapsed().as_secs_f64(),
    })
}

fn row_of(
    time: f32,
    state: [f32; 6],
    fingers: [f32; 2],
    contacts: [ContactTelemetry; 2],
    heights: [f64; 2],
) -> Row {
    let s = state.map(f64::from);
    let (sin, cos) = s[2].sin_cos();
    let contact = |i: usize| {
        let c = contacts[i];
        let (dx, dy) = (f64::from(fingers[i]) - s[0], heights[i] - s[1]);
        ContactRow {
            mode: mode_of(c.mode),
            normal_impulse: f64::from(c.normal_impulse),
            friction_impulse: f64::from(c.friction_impulse),
            along: dx * cos + dy * sin,
        }
    };
    Row {
        t: f64::from(time),
        q: [s[0], s[1], s[2]],
        v: [s[3], s[4], s[5]],
        supports: [[f64::from(fingers[0]), heights[0]], [f64::from(fingers[1]), heights[1]]],
        contacts: [contact(0), contact(1)],
    }
}

/// The rig's run against the host's core f32 6x6 run of the same parameters.
#[derive(Debug, Clone, Serialize)]
#[allow(clippy::struct_excessive_bools)] // one verdict per property compared
pub struct RigComparison {
    /// Same outcome.
    pub same_outcome: bool,
    /// Same number of steps.
    pub same_steps: bool,
    /// Same trajectory checksum (bit-identical states at every step).
    pub same_checksum: bool,
    /// Same switch events: count, contact, mode and time (bit-identical f32).
    pub same_events: bool,
    /// The rig's checksum.
    pub rig_checksum: String,
    /// The host's.
    pub host_checksum: String,
    /// Telemetry rows whose state differs from the host's at the same step (must be 0).
    pub rows_differing: usize,
}

impl RigComparison {
    /// Everything agrees.
    #[must_use]
    pub const fn identical(&self) -> bool {
        self.same_outcome
            && self.same_steps
            && self.same_checksum
            && self.same_events
            && self.rows_differing == 0
    }
}

/// Runs the recorded parameters in the host's core (f32, 6x6, every step) and compares.
///
/// # Errors
/// The parameters are invalid on the host.
pub fn compare(rec: &Recording) -> anyhow::Result<(Trajectory, RigComparison)> {
    let spec = SceneSpec::MeterStick(rec.params.cast::<f64>());
    // The rig's parameters, not the user's: bounded like `host-sim run`'s before anything runs.
    crate::trajectory::check_recorded_steps(&spec).map_err(|e| {
        anyhow::anyhow!("the rig's step and max_time: {e}; --no-compare records the rig's run alone")
    })?;
    let host = run_core::<f32, 6>(&spec, Record::All)?;
    let rig = &rec.trajectory;
    let same_events = rig.events.len() == host.events.len()
        && rig
            .events
            .iter()
            .zip(&host.events)
            .all(|(a, b)| a.t.to_bits() == b.t.to_bits() && a.contact == b.contact && a.mode == b.mode);
    // Row k of the host is step k (row 0: the start); the rig's rows carry their time, n h.
    let h = f64::from(rec.params.step);
    let rows_differing = rig
        .rows
        .iter()
        .filter(|r| {
            let k = (r.t / h).round() as usize;
            let bits = |a: [f64; 3]| a.map(f64::to_bits);
            host.rows.get(k).is_none_or(|hr| bits(hr.q) != bits(r.q) || bits(hr.v) != bits(r.v))
        })
        .count();
    let host_sum = host.checksum.unwrap_or(0);
    let cmp = RigComparison {
        same_outcome: rig.outcome.class == host.outcome.class,
        same_steps: rig.steps == host.steps,
        same_checksum: rec.checksum == host_sum,
        same_events,
        rig_checksum: format!("{:08x}", rec.checksum),
        host_checksum: format!("{host_sum:08x}"),
        rows_differing,
    };
    Ok((host, cmp))
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
    pub outcome: OutcomeClass,
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

/// Prints one line per event and keeps a progress line on stderr (when it is a terminal).
struct Printer {
    last_progress: Instant,
    terminal: bool,
}

impl Printer {
    fn clear(&self) {
        if self.terminal {
            eprint!("\r\x1b[K");
        }
    }

    fn line(&self, s: &str) {
        self.clear();
        println!("{s}");
    }
}

impl Observer for Printer {
    fn report(&mut self, r: &Report) {
        match *r {
            Report::Telemetry { step, time, state, contacts, .. }
                if self.terminal && self.last_progress.elapsed() > Duration::from_millis(100) =>
            {
                self.last_progress = Instant::now();
                eprint!(
                    "\r\x1b[Kt = {time:8.3} s  step {step:7}  x = {:+.4} m  theta = {:+.4} rad  fingers {} / {}",
                    state[0],
                    state[2],
                    mode_of(contacts[0].mode).name(),
                    mode_of(contacts[1].mode).name()
                );
            }
            Report::Switch { step, time, contact, mode, along } => self.line(&format!(
                "t = {time:.3} s (step {step}): finger {} -> {}   (fingers at {:+.4} / {:+.4} m from the centre of mass)",
                contact + 1,
                mode_of(mode).name(),
                along[0],
                along[1]
            )),
            Report::Outcome { outcome, time, steps, checksum } => self.line(&format!(
                "outcome {outcome:?} at t = {time:.3} s after {steps} steps, checksum {checksum:08x}"
            )),
            Report::Margin { worst_cycles, period_cycles, overruns, worst_step } if period_cycles > 0 => {
                self.line(&format!(
                    "real time: worst step {worst_cycles} of {period_cycles} cycles ({:.0} %, step {worst_step}), {overruns} overruns",
                    100.0 * f64::from(worst_cycles) / f64::from(period_cycles)
                ));
            }
            Report::Error(e) => self.line(&format!("rig error: {e:?}")),
            Report::State(s) => self.line(&format!("rig state: {s:?}")),
            _ => {}
        }
    }
}

/// `host-sim monitor`: returns the closing summary (the live lines are printed as they come).
///
/// # Errors
/// Bad flags, the port, a refused command, a missing reply, or I/O.
pub fn monitor(args: &MonitorArgs) -> anyhow::Result<String> {
    let sets: Vec<(ParamId, f32)> = args.set.iter().map(|s| parse_set(s)).collect::<anyhow::Result<_>>()?;
    if !(args.timeout_s.is_finite() && args.timeout_s > 0.0) {
        bail!("--timeout-s {}: must be a positive number of seconds", args.timeout_s);
    }
    let timeout = Duration::from_secs_f64(args.timeout_s);
    let mut link = Link::open(&args.port, args.baud)?;
    let mut printer = Printer { last_progress: Instant::now(), terminal: std::io::stderr().is_terminal() };
    let hello = link.request(&Command::Hello, REPLY_TIMEOUT)?;
    if let Report::Hello { protocol, firmware, build, lcp_size, step_us, .. } = hello {
        if protocol != PROTOCOL_VERSION {
            bail!(
                "{}: the rig speaks protocol version {protocol}, this host-sim version {PROTOCOL_VERSION}",
                args.port
            );
        }
        printer.line(&format!(
            "rig: firmware {}.{}.{} ({}), {lcp_size}x{lcp_size} LCP, h = {step_us} us, protocol {protocol}",
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
        bail!("--set {}: the rig refused it ({:?})", r.id.name(), r.reason);
    }
    if let Some(n) = args.telemetry {
        simple(&mut link, Command::SetTelemetry { every_n_steps: n }, "--telemetry")?;
    }
    if args.stop {
        simple(&mut link, Command::Stop, "--stop")?;
    }
    let mut summary = String::new();
    if args.start || args.follow {
        summary = record_and_write(&mut link, args, timeout, &mut printer)?;
    }
    if args.stress_grid {
        summary.push_str(&stress_grid(&mut link, args)?);
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
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
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
        parameters: parameters_json(&SceneSpec::MeterStick(rec.params.cast())),
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
    if s.comparison.as_ref().is_some_and(|c| !c.identical()) {
        // Exit status 1: a check failed (not bad input).
        return Err(crate::errors::CheckFailed(format!(
            "{summary}the rig's run differs from the host's f32 build (see {})",
            args.out.join("summary.json").display()
        ))
        .into());
    }
    Ok(summary)
}

/// One case of `--stress-grid`.
#[derive(Debug, Clone, Serialize)]
pub struct WorstStep {
    /// The stress case.
    pub case: String,
    /// Steps run (at most `--max-steps`).
    pub steps: u64,
    /// The rig's outcome (`Unfinished` when cut).
    pub outcome: OutcomeClass,
    /// The rig's longest step (cycles; SysTick ticks under QEMU).
    pub worst_cycles: u32,
    /// Its step number.
    pub worst_step: u32,
    /// That step on the host's f32 build: Lemke pivots.
    pub pivots: u32,
    /// It needed the 8x8 form.
    pub full_layout_used: bool,
    /// The warm-start basis answered it.
    pub warm_start_used: bool,
    /// The rig's run is bit-identical to the host's.
    pub identical: bool,
}

/// `--stress-grid`: the worst step of each meter-stick stress case on the rig.
fn stress_grid(link: &mut Link, args: &MonitorArgs) -> anyhow::Result<String> {
    use meterstick_core::scene::{MeterStick6, Scene as _};
    let timeout = Duration::from_secs_f64(args.timeout_s);
    match link.request(&Command::SetTelemetry { every_n_steps: 0 }, REPLY_TIMEOUT)? {
        Report::Ack { .. } => {}
        other => bail!("--stress-grid: telemetry off refused: {other:?}"),
    }
    let mut rows = Vec::new();
    for case in crate::stress::cases::cases(false) {
        let SceneSpec::MeterStick(p) = case.spec else { continue };
        if case.start_dy != 0.0 {
            continue; // the link sets parameters, not an initial state
        }
        let mut params = p.cast::<f32>();
        params.max_time = params.max_time.min(args.max_steps as f32 * params.step);
        // Start from the slow preset (a valid set), then every parameter.
        link.request(&Command::Reset, REPLY_TIMEOUT)?;
        link.request(&Command::Preset(Preset::Slow), REPLY_TIMEOUT)?;
        let values: Vec<(ParamId, f32)> =
            ParamId::ALL.iter().filter_map(|&id| params.get(id.name()).map(|v| (id, v))).collect();
        if let Some(r) = apply_params(link, &values)?.first() {
            bail!("--stress-grid {}: the rig refused {} ({:?})", case.name, r.id.name(), r.reason);
        }
        let params = read_params(link)?;
        let rec = record_run(link, params, true, timeout, &mut |_: &Report| {})?;
        let margin =
            rec.margin.unwrap_or(Margin { worst_cycles: 0, period_cycles: 0, overruns: 0, worst_step: 0 });
        let identical = compare(&rec).map(|(_, c)| c.same_checksum && c.same_events && c.same_steps)?;
        // The worst step on the host: the same scene, stepped to it.
        let mut scene =
            MeterStick6::<f32, 8>::new(params).map_err(|e| anyhow::anyhow!("{}: {e}", case.name))?;
        let mut step = None;
        for _ in 0..margin.worst_step {
            step = scene.step();
        }
        let (pivots, full, warm) =
            step.map_or((0, false, false), |r| (r.pivots, r.full_layout_used, r.warm_start_used));
        println!(
            "{:<44} {:>6} steps {:>10}  worst {:>7} at step {:>6}: {} pivots{}{}{}",
            case.name,
            rec.trajectory.steps,
            rec.trajectory.outcome.class.name(),
            margin.worst_cycles,
            margin.worst_step,
            pivots,
            if full { ", 8x8 fallback" } else { "" },
            if warm { ", warm start" } else { "" },
            if identical { "" } else { ", DIFFERS from the host" }
        );
        rows.push(WorstStep {
            case: case.name.clone(),
            steps: rec.trajectory.steps,
            outcome: rec.trajectory.outcome.class,
            worst_cycles: margin.worst_cycles,
            worst_step: margin.worst_step,
            pivots,
            full_layout_used: full,
            warm_start_used: warm,
            identical,
        });
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let lines = rows.iter().map(|r| {
        format!(
            "{},{},{},{},{},{},{},{},{}",
            r.case.replace(',', ";"),
            r.steps,
            r.outcome.name(),
            r.worst_cycles,
            r.worst_step,
            r.pivots,
            r.full_layout_used,
            r.warm_start_used,
            r.identical
        )
    });
    let path = args.out.join("worst-steps.csv");
    crate::trajectory::write_lines(
        &path,
        "case,steps,outcome,worst_cycles,worst_step,pivots,full_layout_used,warm_start_used,identical",
        lines,
    )?;
    let worst = rows.iter().max_by_key(|r| r.worst_cycles);
    let mut out = String::new();
    if let Some(w) = worst {
        let _ = writeln!(
            out,
            "{} cases; the worst step: {} cycles in \"{}\" (step {}: {} pivots{}); {} not identical to the host; {}",
            rows.len(),
            w.worst_cycles,
            w.case,
            w.worst_step,
            w.pivots,
            if w.full_layout_used { ", 8x8 fallback" } else { "" },
            rows.iter().filter(|r| !r.identical).count(),
            path.display()
        );
    }
    Ok(out)
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

    #[test]
    fn telemetry_rows_carry_supports_and_along() {
        let c = ContactTelemetry { mode: Mode::Sticking, normal_impulse: 1e-3, friction_impulse: 0.0 };
        let row = row_of(0.5, [0.1, 0.0025, 0.0, 0.0, 0.0, 0.0], [-0.3, 0.4], [c, c], [0.0, 0.0]);
        assert_eq!(row.supports, [[f64::from(-0.3f32), 0.0], [f64::from(0.4f32), 0.0]]);
        assert!((row.contacts[0].along - (f64::from(-0.3f32) - f64::from(0.1f32))).abs() < 1e-12);
        assert_eq!(row.contacts[1].mode, ContactMode::Sticking);
    }
}
