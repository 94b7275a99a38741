//! `host-sim report`: error against run time over a sweep of `h`, and a success map.
//!
//! **Error against run time.** The asymmetric slow scene (`x1 = -0.35 m`, `v = 0.1 m/s`, paper
//! otherwise) is run with each `h` of the sweep in four configurations: core f32 6x6, core f32
//! 8x8, core f64 8x8 and the f64 reference. Errors are measured against a *converged reference*:
//! the reference with `h_min / 4`. Quantities (all well defined for a run that balances):
//! * COM error: `max_t |com(t) - com_ref(t)|` on a 10 ms grid over a fixed horizon (positions
//!   interpolated linearly between steps);
//! * meeting error: `|offset - offset_ref|` of the COM from the fingers' midpoint when they meet;
//! * eq. 21 ratio error: the largest `|ratio_k - ratio_ref,k|` over the first four switches.
//!
//! Run time is host nanoseconds per step, the median of repeated runs of the whole scene without
//! recording (one repeat when a run takes over a second), and from it the host time to simulate
//! one second. The observed order in `h` is the least-squares slope of `log(COM error)` against
//! `log h` from the largest `h` down to the `h` of the smallest error (below that, the f32
//! rounding floor or the reference's own error dominates).
//!
//! **Success map.** The outcome over a grid of finger speed and `mu_k/mu_s` (`mu_s = 0.6`), for
//! the core f32 6x6 (the firmware's configuration), the core f64 8x8 and the reference
//! ([`crate::map`], one grid for the three).
//!
//! **Where f32 holds.** [`crate::envelope`]'s table: f32 6x6 against f64 8x8 over finger speed x
//! `h`, with f64's own error.
#![allow(clippy::format_push_string)]

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context as _;
use meterstick_core::scene::MeterStickParams;
use rayon::prelude::*;
use serde_json::json;

use crate::output::{sci, write_json};
use crate::progress::bar as progress;
use crate::scenes::{Implementation, SceneSpec};
use crate::trajectory::{OutcomeClass, Record, Trajectory, run as run_scene, switches};
use crate::{envelope, map, plot};

/// `host-sim report` options.
#[derive(Debug, Clone, clap::Args)]
pub struct ReportArgs {
    /// Output directory (created; files in it are overwritten).
    #[arg(long, default_value = "out/report")]
    pub out: PathBuf,
    /// A small sweep and map (seconds, for tests): h in {1e-3, 1e-2, 1e-1}, a 2x2 map.
    #[arg(long)]
    pub quick: bool,
    /// Horizon of the COM error (s).
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

/// The implementations the report compares.
pub const CONFIGS: [Implementation; 4] = [
    Implementation::CORE_F32_6,
    Implementation::CORE_F32_8,
    Implementation::CORE_F64_8,
    Implementation::Reference,
];

/// The sweep's scene with step `h`: the paper's, finger 1 from -0.35 m.
#[must_use]
pub fn sweep_scene(h: f64) -> SceneSpec {
    SceneSpec::MeterStick(MeterStickParams { finger1_x: -0.35, step: h, ..MeterStickParams::paper() })
}

const GRID_DT: f64 = 0.01;
const RATIOS_COMPARED: usize = 4;

/// Errors of one run against the converged reference.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Errors {
    /// Max COM distance over the horizon (m).
    pub com_m: f64,
    /// Meeting offset difference (m); NaN when either did not meet.
    pub meeting_m: f64,
    /// Largest eq. 21 ratio difference over the first switches; NaN when none to compare.
    pub ratio: f64,
}

/// Compares `run` (recorded on the 10 ms grid) with the converged reference.
#[must_use]
pub fn errors(run: &Trajectory, converged: &Trajectory, horizon: f64) -> Errors {
    let mut com_m: f64 = 0.0;
    for (a, b) in run.rows.iter().zip(&converged.rows) {
        if a.t > horizon + 1e-9 {
            break;
        }
        com_m = com_m.max((a.q[0] - b.q[0]).hypot(a.q[1] - b.q[1]));
    }
    let covered = run.rows.last().is_some_and(|r| r.t >= horizon - 1e-9);
    if !covered {
        com_m = f64::NAN; // the run ended (fell) before the horizon
    }
    let meeting_m = match (run.measured.meeting, converged.measured.meeting) {
        (Some(a), Some(b)) => (a.com_offset_m - b.com_offset_m).abs(),
        _ => f64::NAN,
    };
    let (sa, sb) = (switches(run), switches(converged));
    let k = sa.len().min(sb.len()).min(RATIOS_COMPARED);
    let ratio = if k == 0 {
        f64::NAN
    } else {
        sa.iter().zip(&sb).take(k).map(|(a, b)| (a.ratio - b.ratio).abs()).fold(0.0, f64::max)
    };
    Errors { com_m, meeting_m, ratio }
}

/// One row of the error-vs-run-time table.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SweepRow {
    /// Implementation.
    pub config: Implementation,
    /// Step (s).
    pub h: f64,
    /// Steps of the whole run.
    pub steps: u64,
    /// Outcome class.
    pub outcome: OutcomeClass,
    /// Errors against the converged reference.
    pub errors: Errors,
    /// Median host ns per step.
    pub ns_per_step: f64,
    /// Host ms to simulate one second (`ns_per_step / h`).
    pub ms_per_sim_second: f64,
    /// Lemke pivots per step, averaged over the run (the core's warm-started solver; `None`
    /// for the reference, which enumerates).
    pub pivots_per_step: Option<f64>,
    /// Solves per path (the core's; `None` for the reference).
    pub paths: Option<crate::trajectory::Paths>,
    /// Timing repeats.
    pub repeats: usize,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time_run(config: Implementation, p: &SceneSpec) -> anyhow::Result<(f64, usize)> {
    let mut samples = Vec::new();
    loop {
        let start = Instant::now();
        let t = run_scene(p, config, Record::Nothing)?;
        let s = start.elapsed().as_secs_f64();
        samples.push(1e9 * s / t.steps.max(1) as f64);
        if samples.len() >= 5 || s > 1.0 || (s > 0.3 && samples.len() >= 3) {
            break;
        }
    }
    let n = samples.len();
    Ok((median(samples), n))
}

/// Least-squares slope of `log y` against `log x`.
#[must_use]
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> =
        points.iter().filter(|p| p.0 > 0.0 && p.1 > 0.0).map(|p| (p.0.ln(), p.1.ln())).collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The order fit of one configuration: `(order, h range of the fit, floor error, h at floor)`.
#[must_use]
pub fn order_fit(rows: &[&SweepRow]) -> (Option<f64>, (f64, f64), f64, f64) {
    let mut pts: Vec<(f64, f64)> =
        rows.iter().map(|r| (r.h, r.errors.com_m)).filter(|p| p.1.is_finite() && p.1 > 0.0).collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0)); // largest h first
    let Some(best) = pts.iter().enumerate().min_by(|a, b| a.1.1.total_cmp(&b.1.1)).map(|(i, _)| i) else {
        return (None, (f64::NAN, f64::NAN), f64::NAN, f64::NAN);
    };
    let fit = &pts[..=best];
    (loglog_slope(fit), (fit[fit.len() - 1].0, fit[0].0), pts[best].1, pts[best].0)
}

/// The report's "Performance" section: host ns/step, steps/s and pivots/step of each
/// configuration at h = 1 ms (from the timing runs above), then the side-by-side run against
/// rapier2d and the firmware figures when their files exist.
fn performance_section(rows: &[SweepRow], args: &ReportArgs) -> String {
    let mut md = String::from("## Performance\n\n");
    md += "The sweep's scene at h = 1 ms, timed above (median of the repeats, one run at a time):\n\n";
    md += "| config | host ns/step | steps/s | pivots/step | solves by path: free / warm / candidate / lemke |\n\
           |---|---|---|---|---|\n";
    for r in rows.iter().filter(|r| (r.h - 1e-3).abs() < 1e-12) {
        md += &format!(
            "| {} | {:.0} | {:.2e} | {} | {} |\n",
            r.config,
            r.ns_per_step,
            1e9 / r.ns_per_step,
            r.pivots_per_step.map_or_else(|| "- (enumeration)".into(), |p| format!("{p:.4}")),
            r.paths.map_or_else(
                || "-".into(),
                |p| format!("{} / {} / {} / {}", p.free, p.warm, p.candidate, p.lemke)
            )
        );
    }
    md += "\nThe solve paths (`docs/formulation.md`, \"Solving a step\"): `q >= 0` (free), the previous basis in the \
           body's coordinates (warm), a neighbouring basis (candidate), Lemke's method. Per-path instruction \
           counts on the emulated Cortex-M cores: `scripts/firmware-report.sh`.\n\n";
    md += "\nCriterion benchmarks of each piece (one Lemke solve, cold and warm, 6x6 and 8x8, f32 and f64; one \
           step; a whole run): `cargo bench -p meterstick-tests --bench core`.\n\n";
    md += &included_figures(
        &args.bench_figures,
        "### Against rapier2d",
        "`cargo bench -p meterstick-tests --features rapier --bench rapier`",
        "the same scene stepped by rapier2d and by the core in one process",
    );
    md += &included_figures(
        &args.firmware_figures,
        "### On the microcontroller",
        "`scripts/firmware-report.sh`",
        "the same f32 6x6 core, counted in instructions per step under QEMU",
    );
    md
}

/// A subsection holding the figures file `path` written by `command`, or a line saying how
/// to include them when the file does not exist.
fn included_figures(path: &std::path::Path, heading: &str, command: &str, what: &str) -> String {
    match std::fs::read_to_string(path) {
        Ok(figures) => format!(
            "{heading}\n\nFrom `{}` ({command}): {what}.\n\n{}\n",
            path.display(),
            figures.replacen("# Firmware figures", "", 1)
        ),
        Err(_) => format!(
            "({heading}: run {command} before this report to include {what}.)\n\n",
            heading = heading.trim_start_matches("### ")
        ),
    }
}

/// Runs the report and writes `report.md`, the tables and the pictures; returns a short text.
///
/// # Errors
/// I/O or plotting.
#[allow(clippy::too_many_lines)] // one linear script: sweep, fit, map, write
pub fn run(args: &ReportArgs) -> anyhow::Result<String> {
    let out = &args.out;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let hs: Vec<f64> = if args.quick {
        vec![1e-1, 1e-2, 1e-3]
    } else {
        vec![1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5]
    };
    let h_min = hs.iter().copied().fold(f64::INFINITY, f64::min);
    let h_conv = h_min / 4.0;

    // 1. Error runs (parallel), converged reference first in the queue (the longest job).
    let mut jobs: Vec<(Option<Implementation>, f64)> = vec![(None, h_conv)];
    for &h in hs.iter().rev() {
        for c in CONFIGS {
            jobs.push((Some(c), h));
        }
    }
    let bar = progress(jobs.len() as u64, "error runs");
    let runs: Vec<anyhow::Result<Trajectory>> = jobs
        .par_iter()
        .map(|&(c, h)| {
            let r = run_scene(&sweep_scene(h), c.unwrap_or(Implementation::Reference), Record::Grid(GRID_DT));
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let mut runs = runs.into_iter().collect::<anyhow::Result<Vec<_>>>()?;
    let converged = runs.remove(0);
    jobs.remove(0);

    // 2. Timing runs (sequential, so that runs do not share a core).
    let bar = progress(jobs.len() as u64, "timing runs");
    let mut rows = Vec::new();
    for ((c, h), run) in jobs.iter().zip(&runs) {
        let config = c.unwrap_or(Implementation::Reference);
        let (ns, repeats) = time_run(config, &sweep_scene(*h))?;
        bar.inc(1);
        rows.push(SweepRow {
            config,
            h: *h,
            steps: run.steps,
            outcome: run.outcome.class,
            errors: errors(run, &converged, args.horizon),
            ns_per_step: ns,
            ms_per_sim_second: ns / h * 1e-6,
            pivots_per_step: (config != Implementation::Reference)
                .then(|| run.counters.pivots as f64 / run.steps.max(1) as f64),
            paths: (config != Implementation::Reference).then_some(run.counters.paths),
            repeats,
        });
    }
    bar.finish_and_clear();

    // 3. Success map: one grid, three implementations.
    let grid = if args.quick {
        map::Grid::speed_by_mu_ratio((0.05, 1.25), [2, 2], 0.0)?
    } else {
        map::Grid::speed_by_mu_ratio((0.05, 1.25), [48, 16], 0.0)?
    };
    let map_base = SceneSpec::MeterStick(MeterStickParams { mu_static: 0.6, ..MeterStickParams::paper() });
    let map_configs = [Implementation::CORE_F32_6, Implementation::CORE_F64_8, Implementation::Reference];
    let maps = map_configs.map(|c| map::compute(&map_base, &grid, c));
    let [f32_map, f64_map, ref_map] = maps;
    let maps = [f32_map?, f64_map?, ref_map?];

    // 4. Where f32 holds (its own runs, in parallel).
    let envelope = envelope::compute(args.quick, 2_000_000)?;

    // 5. Write tables, pictures and report.md.
    let mut csv = String::from(
        "config,h_s,steps,outcome,com_error_m,meeting_error_m,ratio_error,ns_per_step,ms_per_sim_second,pivots_per_step,repeats\n",
    );
    for r in &rows {
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
        &format!("COM error over {} s vs host run time (each point one h)", args.horizon),
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
        &format!("COM error over {} s vs h (converged: reference, h = {h_conv:e} s)", args.horizon),
        ("h (s)", "max COM error (m)"),
        &conv_series,
        true,
        &plot::SeriesLabelPosition::LowerRight,
    )?;
    map::write(&maps[0], &out.join("map"))?;
    let mut map_csv = String::from("speed_m_s,mu_k_over_mu_s");
    for c in map_configs {
        map_csv += &format!(",{}", c.to_string().replace(' ', "_"));
    }
    map_csv += "\n";
    let mut disagreements = Vec::new();
    // Of those, cells with a neighbour (left, right, above, below) of another outcome in f64.
    let mut at_boundary = 0;
    let (xs, ys) = (&maps[0].xs, &maps[0].ys);
    let f64_outcomes = &maps[1].outcomes;
    for (j, y) in ys.iter().enumerate() {
        for (i, x) in xs.iter().enumerate() {
            let o = maps.each_ref().map(|m| m.outcomes[j][i]);
            writeln!(map_csv, "{x},{y},{},{},{}", o[0], o[1], o[2])?;
            if o[0] != o[1] || o[1] != o[2] {
                disagreements
                    .push(format!("v = {x:.4} m/s, mu_k/mu_s = {y:.3}: {} / {} / {}", o[0], o[1], o[2]));
                let neighbours = [(j, i.wrapping_sub(1)), (j, i + 1), (j.wrapping_sub(1), i), (j + 1, i)];
                at_boundary += usize::from(neighbours.iter().any(|&(b, a)| {
                    f64_outcomes.get(b).and_then(|row| row.get(a)).is_some_and(|&n| n != o[1])
                }));
            }
        }
    }
    std::fs::write(out.join("success_map.csv"), &map_csv)?;
    write_json(
        &out.join("report.json"),
        &json!({ "sweep": rows, "h_converged_s": h_conv, "horizon_s": args.horizon }),
    )?;

    // report.md
    let mut md = String::new();
    md += "# meterstick report: error against run time, and where the trick works\n\n";
    md += &format!(
        "Generated by `host-sim report{}`. Scene of the sweep: the paper's rod, fingers starting at -0.35 / +0.40 m \
         (asymmetric), v = 0.1 m/s, mu_s = 0.6, mu_k = 0.4. Errors are against a converged reference: the \
         independent f64 reference with h = {h_conv:e} s.\n\n",
        if args.quick { " --quick" } else { "" }
    );
    md += "## Error against run time\n\n![error vs run time](error_vs_runtime.svg)\n\n![error vs h](error_vs_h.svg)\n\n";
    md += "| config | h (s) | steps | outcome | COM error (m) | meeting error (m) | eq.21 ratio error | host ns/step | host ms per simulated s | pivots/step |";
    md += "\n|---|---|---|---|---|---|---|---|---|---|\n";
    for r in &rows {
        md += &format!(
            "| {} | {:e} | {} | {} | {} | {} | {} | {:.0} | {:.3} | {} |\n",
            r.config,
            r.h,
            r.steps,
            r.outcome,
            sci(r.errors.com_m),
            sci(r.errors.meeting_m),
            sci(r.errors.ratio),
            r.ns_per_step,
            r.ms_per_sim_second,
            r.pivots_per_step.map_or_else(|| "-".into(), |p| format!("{p:.4}"))
        );
    }
    md += "\n(also in `error_vs_runtime.csv`; NaN/n/a: the quantity does not exist for that run, e.g. no switch to compare).\n\n";
    md += "### What the pictures show\n\n";
    for (c, (order, _, floor, h_floor), _) in &fits {
        let mine: Vec<&SweepRow> = rows.iter().filter(|r| r.config == *c).collect();
        let at_min = mine.iter().find(|r| r.h <= h_min * 1.0001).map_or(f64::NAN, |r| r.errors.com_m);
        let order_text = order.map_or_else(
            || "no order could be fitted".to_string(),
            |o| format!("converges with order {o:.2}"),
        );
        if *h_floor > h_min * 1.0001 {
            md += &format!(
                "- {}: {order_text} down to h = {h_floor:e} s, where its error bottoms out at {} m (its floor); \
                 below that h the error grows again, to {} m at h = {h_min:e} s, while the run time per simulated \
                 second keeps rising: f32 round-off (about 6e-8 m per position update, accumulated over 1/h \
                 steps, plus stick/slip decisions that flip on round-off) overtakes the discretisation error.\n",
                c,
                sci(*floor),
                sci(at_min)
            );
        } else {
            md += &format!(
                "- {}: {order_text} all the way to the smallest h swept ({h_min:e} s, error {} m): no floor in range.\n",
                c,
                sci(*floor)
            );
        }
    }
    md += "\nThe scheme is a first-order time-stepping method (semi-implicit Euler with contact and friction \
           resolved as one LCP per step; switches happen at step boundaries), so about one decade of error per \
           decade of h is expected; the pictures show where each configuration stops paying off.\n\n";
    md += "## Where f32 holds\n\n";
    md += "The f32 6x6 core (the firmware's) against the f64 8x8 core with the same h, over finger speed x h \
           (`host-sim envelope`; `docs/formulation.md`, \"Precision\"). Steps beyond `eps V / (g h)` = 1e-4 are \
           flagged in the step report (`round_off_limited`) and by `host-sim scene`/`run`.\n\n";
    md += &envelope.markdown();
    md += "\n";
    md += &performance_section(&rows, args);
    md += "## Success map\n\n![success map](map/map.svg)\n\n";
    let cells = xs.len() * ys.len();
    md += &format!(
        "Outcome of the paper's symmetric start (fingers at -/+0.4 m, h = 1 ms) over finger speed ({} .. {} m/s, \
         {} columns) and mu_k/mu_s ({} rows), mu_s = 0.6, in the core f32 6x6 (the picture), the core f64 8x8 \
         and the reference (`success_map.csv`; `host-sim map` draws finer maps with the boundaries bisected). \
         Green: balanced (the fingers met under the centre of mass); red: the rod fell; grey: undecided at \
         max-time (the rod still rocking on the met fingers: its contacts are 1 cm apart against a radius of \
         gyration of 29 cm, so each inelastic impact keeps almost all the angular momentum). {}\n\n\
         The boundary is not monotone in speed: finger 1 stops abruptly when the fingers meet, and if the rod \
         is riding on it at that moment it slides on by about v^2 / (2 mu_k g) (5 mm at 0.2 m/s, 1.1 cm at \
         0.3 m/s with mu_k = 0.4), which may carry the centre of mass past a finger 1 cm away; whether it is \
         riding depends on the phase of the stick-slip cycle at the stop.\n\n",
        grid.x.0,
        grid.x.1,
        grid.cells[0],
        grid.cells[1],
        if disagreements.is_empty() {
            "All three implementations agree on every cell.".to_string()
        } else {
            format!(
                "They disagree on {} of {cells} cells, {at_boundary} of them next to a cell of another \
                 outcome in f64: {}.",
                disagreements.len(),
                disagreements.join("; ")
            )
        }
    );
    for (c, m) in map_configs.iter().zip(&maps) {
        let counts: Vec<String> = m.summary.counts.iter().map(|(o, n)| format!("{o} {n}")).collect();
        md += &format!("- {c}: {}\n", counts.join(", "));
    }
    md += "\n";
    std::fs::write(out.join("report.md"), &md)?;
    let mut text = String::new();
    for (c, (order, _, floor, h_floor), ns) in &fits {
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
        xs.len() * ys.len(),
        disagreements.len(),
        out.join("report.md").display()
    );
    Ok(text)
}
