//! `host-sim monitor` on the rig's stack (`--scene stack`): a run recorded, compared with the
//! host core's f32 `Stack3` of the parameters the rig reported, and written under `--out`:
//! `rig.csv` (the bodies' telemetry, a row per telemetry step, in `host-sim run`'s columns for
//! the scenes of several bodies: `t`, each body's `x, y, theta, vx, vy, omega`) and
//! `summary.json` ([`StackSummary`]).

use std::fmt::Write as _;
use std::time::Duration;

use meterstick_link::host::Link;
use serde::Serialize;

use super::print::Printer;
use super::{MonitorArgs, answer};
use crate::bodies::write_trajectory;
use crate::monitor::{
    BodiesFrame, StackComparison, compare_stack, outcome_of, read_stack_params, record_stack_run,
};
use crate::output::{create_dir, parameters_json, write_json};
use crate::scenes::{SceneKind, SceneParams};
use crate::trajectory::OutcomeKind;
use meterstick_core::scene::StackSetup;

/// `summary.json` of `host-sim monitor --scene stack`.
#[derive(Debug, Clone, Serialize)]
pub struct StackSummary {
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
    pub steps: u32,
    /// The rig's trajectory checksum.
    pub checksum: String,
    /// Interface switch events.
    pub interface_switches: usize,
    /// Body telemetry frames received.
    pub body_frames: u64,
    /// Reports the rig dropped (its transmit queue was full).
    pub dropped_reports: u32,
    /// Wall time of the run (s).
    pub wall_time_s: f64,
    /// Against the host's f32 build (absent with `--no-compare`).
    pub comparison: Option<StackComparison>,
}

/// Records a stack run (`--start` or `--follow`), compares it with the host, writes
/// `summary.json` and returns the closing lines.
///
/// # Errors
/// The link, I/O, or (exit status 1) a run that differs from the host's.
pub fn record_and_write(
    link: &mut Link,
    args: &MonitorArgs,
    timeout: Duration,
    printer: &mut Printer,
) -> anyhow::Result<String> {
    let mut summary = String::new();
    let params = read_stack_params(link)?;
    let rec = record_stack_run(link, params, args.start, timeout, printer)?;
    printer.clear();
    create_dir(&args.out)?;
    let rows: Vec<_> = rec.frames.iter().map(BodiesFrame::row).collect();
    write_trajectory(&rows, &args.out.join("rig.csv"))?;
    let comparison = if args.no_compare {
        None
    } else {
        let cmp = compare_stack(&rec)?;
        let _ = writeln!(
            summary,
            "host f32 stack: checksum {}: {}",
            cmp.host_checksum,
            if cmp.identical() { "identical to the rig's run" } else { "DIFFERENT from the rig's run" }
        );
        Some(cmp)
    };
    let s = StackSummary {
        port: args.port.clone(),
        scene: SceneKind::Stack,
        parameters: parameters_json(&SceneParams::Stack(StackSetup {
            blocks: 3.0,
            params: rec.params.cast(),
        })),
        outcome: outcome_of(rec.outcome).class,
        end_time_s: f64::from(rec.end_time),
        steps: rec.steps,
        checksum: format!("{:08x}", rec.checksum),
        interface_switches: rec.switches.len(),
        body_frames: rec.body_frames,
        dropped_reports: rec.dropped,
        wall_time_s: rec.wall_s,
        comparison,
    };
    write_json(&args.out.join("summary.json"), &s)?;
    let _ = writeln!(
        summary,
        "rig: {:?} at t = {:.3} s after {} steps, checksum {:08x}, {} interface switches, {} body frames ({} dropped) in {:.1} s; files in {}",
        rec.outcome,
        rec.end_time,
        rec.steps,
        rec.checksum,
        rec.switches.len(),
        rec.body_frames,
        rec.dropped,
        rec.wall_s,
        args.out.display()
    );
    answer(summary, s.comparison.as_ref().is_none_or(StackComparison::identical), &args.out)
}
