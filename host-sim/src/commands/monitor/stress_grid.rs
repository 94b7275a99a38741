//! `host-sim monitor --stress-grid`: each meter-stick case of `host-sim stress` that starts at
//! rest, run on the rig (telemetry off, cut at `--max-steps`), its worst step (the rig's margin)
//! tabulated with what the host's f32 build did in that step; writes `worst-steps.csv`.

use std::fmt::Write as _;
use std::time::Duration;

use anyhow::bail;
use meterstick_core::scene::{MeterStick6, Scene as _};
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, ParamId, Preset, Report};
use serde::Serialize;

use super::MonitorArgs;
use crate::monitor::{Margin, apply_params, compare, read_params, record_run};
use crate::output::{create_dir, write_lines};
use crate::scenes::SceneParams;
use crate::trajectory::OutcomeKind;

/// One case of `--stress-grid`.
#[derive(Debug, Clone, Serialize)]
pub struct WorstStep {
    /// The stress case.
    pub case: String,
    /// Steps run (at most `--max-steps`).
    pub steps: u64,
    /// The rig's outcome (`Unfinished` when cut).
    pub outcome: OutcomeKind,
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

/// `--stress-grid`: the worst step of each meter-stick stress case on the rig; returns the
/// closing line.
///
/// # Errors
/// A refused command or parameter, a missing reply, or I/O.
pub fn run(link: &mut Link, args: &MonitorArgs) -> anyhow::Result<String> {
    let timeout = Duration::from_secs_f64(args.timeout_s);
    match link.request(&Command::SetTelemetry { every_n_steps: 0 }, REPLY_TIMEOUT)? {
        Report::Ack { .. } => {}
        other => bail!("--stress-grid: telemetry off refused: {other:?}"),
    }
    let mut rows = Vec::new();
    for case in crate::stress::cases::cases(false) {
        let SceneParams::MeterStick(p) = case.spec else { continue };
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
            bail!("--stress-grid {}: the rig refused {}: {}", case.name, r.id.name(), r.reason.words());
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
    create_dir(&args.out)?;
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
    write_lines(
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
