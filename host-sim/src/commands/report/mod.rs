//! `host-sim report`: error against run time over a sweep of `h` ([`crate::sweep`]), a success
//! map in three implementations ([`crate::map`], one grid for the three: `maps.rs`), where f32
//! holds ([`crate::envelope`]'s table), the scenes in three dimensions against their closed forms
//! and where f32 holds for the puck ([`crate::spatial_sweep`]) and the performance figures; writes
//! `report.md` (`markdown.rs`) with its tables and pictures.
//!
//! [`run`] is a list of named steps: compute the sweep, the maps and the envelope, then write the
//! sweep's table and pictures, the maps' files, `report.json` and `report.md`.
#![allow(clippy::format_push_string)]

mod maps;
mod markdown;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde_json::json;

use crate::envelope;
use crate::output::{create_dir, sci, write_json};
use crate::plot;
use crate::scenes::Implementation;
use crate::spatial_sweep::{self, CASES, SpatialRow};
use crate::sweep::{self, CONFIGS, Sweep, SweepRow, order_fit};
use meterstick_catalogue::Short;

use maps::SuccessMaps;

/// `host-sim report` options.
#[derive(Debug, Clone, clap::Args)]
pub struct ReportArgs {
    /// Output directory (created; files in it are overwritten).
    #[arg(long, default_value = "out/report")]
    pub out: PathBuf,
    /// A small sweep and map (seconds, for tests): h in {1e-3, 1e-2, 1e-1}, a 2x2 map.
    #[arg(long)]
    pub quick: bool,
    /// Horizon of the COM error (s; at most when the sweep's scene ends, 7.9 s).
    #[arg(long, default_value_t = 2.0)]
    pub horizon: f64,
    /// The firmware figures (flash/RAM, Cortex-M instructions per step) written by
    /// `scripts/firmware-report.sh`; included in report.md when the file exists.
    #[arg(long, default_value = "out/firmware/report.md")]
    pub firmware_figures: PathBuf,
    /// The side-by-side figures (core and rapier2d in one process) written by
    /// `cargo bench -p meterstick-tests --features rapier --bench rapier`; included in
    /// report.md when the file exists.
    #[arg(long, default_value = "out/bench/rapier.md")]
    pub bench_figures: PathBuf,
}

/// One configuration's order fit ([`order_fit`]: order, `h` range, floor error, `h` at the
/// floor) and its fastest host ns per step.
type Fit = (Implementation, (Option<f64>, (f64, f64), f64, f64), f64);

/// Runs the report and writes `report.md`, the tables and the pictures; returns a short text.
///
/// # Errors
/// I/O or plotting.
pub fn run(args: &ReportArgs) -> anyhow::Result<String> {
    let most = sweep::max_horizon();
    if !(args.horizon > 0.0 && args.horizon <= most) {
        anyhow::bail!(
            "--horizon {:?}: must be a positive number of seconds, at most {most:.3} (when the sweep's \
             scene ends: its fingers meet and hold)",
            Short(args.horizon)
        );
    }
    for (flag, path) in
        [("--firmware-figures", &args.firmware_figures), ("--bench-figures", &args.bench_figures)]
    {
        markdown::check_figures(flag, path)?;
    }
    let out = &args.out;
    create_dir(out)?;
    let sweep = sweep::run(&sweep::steps(args.quick), args.horizon)?;
    let maps = SuccessMaps::compute(args.quick)?;
    let envelope = envelope::compute(args.quick, 2_000_000)?;
    let spatial_steps = spatial_sweep::steps(args.quick);
    let spatial = spatial_sweep::sweep(&spatial_steps)?;
    let spatial_envelope = spatial_sweep::envelope(&spatial_steps)?;
    let fits = write_sweep(out, &sweep, args.horizon)?;
    write_spatial(out, &spatial)?;
    let comparison = maps.write(out)?;
    write_json(
        &out.join("report.json"),
        &json!({
            "sweep": sweep.rows,
            "h_converged_s": sweep.h_converged,
            "horizon_s": args.horizon,
            "spatial_sweep": spatial,
            "spatial_envelope": spatial_envelope,
        }),
    )?;
    let md =
        markdown::report(args, &sweep, &fits, &envelope, (&spatial, &spatial_envelope), &maps, &comparison);
    std::fs::write(out.join("report.md"), &md)?;
    Ok(terminal_text(&fits, &maps, &comparison, out))
}

/// Writes `error_vs_runtime.csv`, `error_vs_runtime.svg` and `error_vs_h.svg`; returns each
/// configuration's order fit.
fn write_sweep(out: &Path, sweep: &Sweep, horizon: f64) -> anyhow::Result<Vec<Fit>> {
    let rows = &sweep.rows;
    let mut csv = String::from(
        "config,h_s,steps,outcome,com_error_m,meeting_error_m,ratio_error,ns_per_step,ms_per_sim_second,pivots_per_step,repeats\n",
    );
    for r in rows {
        writeln!(
            csv,
            "{},{},{},{},{},{},{},{:.1},{:.4},{},{}",
            r.config,
            r.h,
            r.steps,
            r.outcome,
            r.errors.com_m,
            r.errors.meeting_m,
            r.errors.ratio,
            r.ns_per_step,
            r.ms_per_sim_second,
            r.pivots_per_step.map_or_else(|| "NaN".into(), |p| format!("{p:.5}")),
            r.repeats
        )?;
    }
    std::fs::write(out.join("error_vs_runtime.csv"), csv)?;
    let mut series = Vec::new();
    let mut fits = Vec::new();
    for c in CONFIGS {
        let mine: Vec<&SweepRow> = rows.iter().filter(|r| r.config == c).collect();
        let points = mine.iter().map(|r| (r.ms_per_sim_second, r.errors.com_m)).collect();
        series.push(plot::Series { label: c.to_string(), points, dashed: false });
        fits.push((c, order_fit(&mine), mine.iter().map(|r| r.ns_per_step).fold(f64::NAN, f64::min)));
    }
    plot::lines(
        &out.join("error_vs_runtime.svg"),
        &format!("COM error over {horizon} s vs host run time (each point one h)"),
        ("host run time per simulated second (ms)", "max COM error (m)"),
        &series,
        true,
        &plot::SeriesLabelPosition::UpperRight,
    )?;
    let conv_series: Vec<plot::Series> = CONFIGS
        .iter()
        .map(|c| {
            let points = rows.iter().filter(|r| r.config == *c).map(|r| (r.h, r.errors.com_m)).collect();
            plot::Series { label: c.to_string(), points, dashed: false }
        })
        .collect();
    plot::lines(
        &out.join("error_vs_h.svg"),
        &format!("COM error over {horizon} s vs h (converged: reference, h = {:e} s)", sweep.h_converged),
        ("h (s)", "max COM error (m)"),
        &conv_series,
        true,
        &plot::SeriesLabelPosition::LowerRight,
    )?;
    Ok(fits)
}

/// Writes `spatial_error_vs_h.csv` and `spatial_error_vs_h.svg` (each case's error against `h`,
/// f32 and f64).
fn write_spatial(out: &Path, rows: &[SpatialRow]) -> anyhow::Result<()> {
    let mut csv = String::from("case,unit,precision,h_s,steps,error,ns_per_step\n");
    for r in rows {
        writeln!(
            csv,
            "{},{},{},{},{},{},{:.1}",
            r.case, r.unit, r.precision, r.h, r.steps, r.error, r.ns_per_step
        )?;
    }
    std::fs::write(out.join("spatial_error_vs_h.csv"), csv)?;
    let series: Vec<plot::Series> = CASES
        .iter()
        .filter(|c| c.unit == "relative")
        .flat_map(|c| {
            ["f32", "f64"].map(|precision| plot::Series {
                label: format!("{} ({precision})", c.name),
                points: rows
                    .iter()
                    .filter(|r| r.case == c.name && r.precision == precision && r.error > 0.0)
                    .map(|r| (r.h, r.error))
                    .collect(),
                dashed: precision == "f32",
            })
        })
        .collect();
    plot::lines(
        &out.join("spatial_error_vs_h.svg"),
        "Three dimensions: error against the closed forms vs h",
        ("h (s)", "relative error"),
        &series,
        true,
        &plot::SeriesLabelPosition::LowerRight,
    )
}

/// The lines the terminal gets: each configuration's order and best error, and the map's count
/// of disagreements.
fn terminal_text(fits: &[Fit], maps: &SuccessMaps, comparison: &maps::Comparison, out: &Path) -> String {
    let mut text = String::new();
    for (c, (order, _, floor, h_floor), ns) in fits {
        text += &format!(
            "{:<18} order {:>5}  best COM error {} m at h = {h_floor:e} s  {:>7.0} ns/step\n",
            c.to_string(),
            order.map_or_else(|| "n/a".into(), |o| format!("{o:.2}")),
            sci(*floor),
            ns
        );
    }
    text += &format!(
        "success map: {} cells, {} disagreements; report in {}\n",
        maps.cells(),
        comparison.disagreements.len(),
        out.join("report.md").display()
    );
    text
}
