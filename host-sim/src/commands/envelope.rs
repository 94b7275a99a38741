//! `host-sim envelope`: where f32 holds ([`crate::envelope`]): the f32 core against the f64 core
//! over finger speed x `h`, with f64's own error, and over friction `mu` (meter stick, incline,
//! Painleve); writes `envelope.csv`, `envelope-mu.csv`, `envelope.json` and `envelope.md`.

use std::path::PathBuf;

use crate::envelope;
use crate::output::{create_dir, write_json, write_lines};

/// `host-sim envelope` options.
#[derive(Debug, Clone, clap::Args)]
pub struct EnvelopeArgs {
    /// Output directory (created; files in it are overwritten).
    #[arg(long, default_value = "out/envelope")]
    pub out: PathBuf,
    /// Two speeds (0.1, 1 m/s) x two steps (1e-3, 1e-2 s), for tests.
    #[arg(long)]
    pub quick: bool,
    /// The most steps of one run (slower fingers are cut short, and the table says so).
    #[arg(long, default_value_t = 2_000_000)]
    pub max_steps: u64,
}

/// `host-sim envelope`: runs the table, writes `envelope.csv`, `envelope.json` and
/// `envelope.md`, and returns the Markdown.
///
/// # Errors
/// As [`envelope::compute`], and I/O naming the file.
pub fn run(args: &EnvelopeArgs) -> anyhow::Result<String> {
    let envelope = envelope::compute(args.quick, args.max_steps)?;
    create_dir(&args.out)?;
    let lines = envelope.cells.iter().map(|c| {
        format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            c.speed_m_s,
            c.h_s,
            c.horizon_s,
            c.capped,
            c.steps,
            c.outcome_f32,
            c.outcome_f64,
            c.f32_deviation_m,
            c.events_agree,
            c.event_time_deviation_s,
            c.flagged_steps,
            c.f64_own_error_m,
            c.outcome_f64_half,
            c.f64_events_converged,
            c.converged,
            c.reference_deviation_m.map_or_else(|| "NaN".into(), |d| d.to_string()),
            c.verdict.name()
        )
    });
    write_lines(
        &args.out.join("envelope.csv"),
        "speed_m_s,h_s,horizon_s,capped,steps,outcome_f32,outcome_f64,f32_deviation_m,events_agree,\
         event_time_deviation_s,flagged_steps,f64_own_error_m,outcome_f64_half,f64_events_converged,converged,reference_deviation_m,verdict",
        lines,
    )?;
    let friction = envelope.friction.iter().map(|c| {
        format!(
            "{},{},{},{},{},{},{}",
            c.scene,
            c.layout.name(),
            c.mu,
            c.outcome_f32,
            c.outcome_f64,
            c.agrees(),
            c.beyond_f32
        )
    });
    write_lines(
        &args.out.join("envelope-mu.csv"),
        "scene,layout,mu,outcome_f32,outcome_f64,agree,beyond_f32",
        friction,
    )?;
    write_json(&args.out.join("envelope.json"), &envelope)?;
    let md = envelope.markdown();
    std::fs::write(args.out.join("envelope.md"), &md)
        .map_err(|e| anyhow::anyhow!("writing {}: {e}", args.out.join("envelope.md").display()))?;
    Ok(md)
}
