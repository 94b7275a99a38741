//! `host-sim run`, the main job: the paper's scenes in the core (f32, 6x6 by default, as the
//! firmware runs them) beside the independent f64 reference, with CSVs, `summary.json`, plots
//! and a terminal summary.
//!
//! Output, per scene `v<speed>/` under the output directory:
//! `core.csv`, `reference.csv` (trajectories), `core-events.csv`, `reference-events.csv`,
//! `summary.json`, `positions.svg` (figs. 2, 3, 5: fingers and centre of mass over time),
//! `relative.svg` (fingers relative to the centre of mass); and `summary.json` over all scenes.
#![allow(clippy::format_push_string)]

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use indicatif::{ProgressBar, ProgressStyle};
use meterstick_core::scene::SceneParams;
use rayon::prelude::*;
use serde_json::{Value, json};

use crate::plot;
use crate::reference::Reference;
use crate::scene_cmd::{SceneArgs, run_configured};
use crate::trajectory::{Record, Trajectory, max_deviation, switches, write_csv, write_events_csv};

/// The paper's finger speeds (m/s): the slow case (figs. 2-3) and the fast cases of fig. 5.
pub const PAPER_SPEEDS: [f64; 5] = [0.1, 0.5, 1.0, 5.0, 10.0];

/// `host-sim run` options.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Finger 1 speeds toward finger 2 (m/s, >= 0), one scene each (comma-separated or
    /// repeated). Default: the paper's 0.1 (slow) and 0.5, 1, 5, 10 (fast, fig. 5).
    #[arg(long, value_delimiter = ',', num_args = 1, default_values_t = PAPER_SPEEDS, allow_hyphen_values = true)]
    pub speed: Vec<f64>,
    /// The scene (shared by all speeds).
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output directory (created; existing files in it are overwritten).
    #[arg(long, default_value = "out/run")]
    pub out: PathBuf,
}

/// A progress bar over `len` jobs on stderr (hidden when stderr is not a terminal).
#[must_use]
pub fn progress(len: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(what.to_owned());
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar
}

/// The parameters as JSON.
#[must_use]
pub fn params_json(p: &SceneParams<f64>) -> Value {
    json!({
        "rod_length_m": p.rod_length, "rod_thickness_m": p.rod_thickness, "rod_mass_kg": p.rod_mass,
        "gravity_m_s2": p.gravity, "finger1_x_m": p.finger1_x, "finger2_x_m": p.finger2_x,
        "finger_width_m": p.finger_width, "finger_speed_m_s": p.finger_speed, "mu_static": p.mu_static,
        "mu_kinetic": p.mu_kinetic, "step_s": p.step, "stick_speed_m_s": p.stick_speed,
        "tilt_limit_rad": p.tilt_limit, "drop_limit_m": p.drop_limit, "hold_time_s": p.hold_time,
        "max_time_s": p.max_time,
    })
}

/// One implementation's part of a summary.
#[must_use]
pub fn run_json(t: &Trajectory, mu_ratio: f64, wall_s: f64) -> Value {
    let sw = switches(t);
    let worst = sw
        .iter()
        .map(|s| (s.ratio - mu_ratio).abs())
        .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
    json!({
        "label": t.label,
        "outcome": t.outcome.class(),
        "outcome_detail": t.outcome.to_string(),
        "end_time_s": t.end_time,
        "steps": t.steps,
        "meeting": t.meeting.map(|(time, off)| json!({"time_s": time, "com_offset_m": off})),
        "switch_events": t.events.len(),
        "eq21_switches": sw,
        "eq21_worst_ratio_error": worst,
        "counters": t.counters,
        "pivots_per_step": t.counters.pivots as f64 / t.steps.max(1) as f64,
        "wall_time_s": wall_s,
        "ns_per_step": 1e9 * wall_s / t.steps.max(1) as f64,
    })
}

/// One scene's result.
#[derive(Debug)]
pub struct SceneResult {
    /// Directory name, e.g. `v0.1`.
    pub name: String,
    /// The summary written to `summary.json`.
    pub summary: Value,
    /// The core's run.
    pub core: Trajectory,
    /// The reference's run.
    pub reference: Trajectory,
}

/// A job: (scene index, is it the reference).
type Job = (usize, bool);
/// A run and its wall time (s).
type Timed = (Trajectory, f64);

fn scene_name(speed: f64) -> String {
    format!("v{speed}")
}

/// Runs every scene and writes the output files; returns the terminal summary.
///
/// # Errors
/// Invalid parameters (before anything runs), or I/O.
pub fn run(args: &RunArgs) -> anyhow::Result<String> {
    anyhow::ensure!(!args.speed.is_empty(), "no --speed given");
    let params: Vec<SceneParams<f64>> =
        args.speed.iter().map(|&v| args.scene.params(v)).collect::<anyhow::Result<_>>()?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let bar = progress(2 * params.len() as u64, "running scenes");
    // Jobs: (scene, is_reference), longest (slowest finger, reference) first.
    let mut jobs: Vec<(usize, bool)> = (0..params.len()).flat_map(|k| [(k, true), (k, false)]).collect();
    jobs.sort_by(|a, b| params[a.0].finger_speed.total_cmp(&params[b.0].finger_speed).then(b.1.cmp(&a.1)));
    let done: Vec<(Job, anyhow::Result<Timed>)> = jobs
        .par_iter()
        .map(|&(k, is_ref)| {
            let start = Instant::now();
            let traj = if is_ref {
                Reference::new(params[k]).map(|r| r.run(Record::All))
            } else {
                run_configured(args.scene.precision, args.scene.lcp_size, &params[k], Record::All)
            };
            bar.inc(1);
            ((k, is_ref), traj.map(|t| (t, start.elapsed().as_secs_f64())))
        })
        .collect();
    bar.finish_and_clear();
    let mut slots: Vec<[Option<(Trajectory, f64)>; 2]> = (0..params.len()).map(|_| [None, None]).collect();
    for ((k, is_ref), r) in done {
        slots[k][usize::from(is_ref)] = Some(r?);
    }
    let mut results = Vec::new();
    for (k, [core, reference]) in slots.into_iter().enumerate() {
        let (Some((core, core_s)), Some((reference, ref_s))) = (core, reference) else {
            anyhow::bail!("scene {k} did not run");
        };
        let p = &params[k];
        let name = scene_name(p.finger_speed);
        let dir = args.out.join(&name);
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        let mu_ratio = p.mu_kinetic / p.mu_static;
        let (dev_com, dev_angle) = max_deviation(&core, &reference);
        let meeting_gap = match (core.meeting, reference.meeting) {
            (Some(a), Some(b)) => Some((a.1 - b.1).abs()),
            _ => None,
        };
        let summary = json!({
            "scene": name,
            "parameters": params_json(p),
            "mu_k_over_mu_s": mu_ratio,
            "core": run_json(&core, mu_ratio, core_s),
            "reference": run_json(&reference, mu_ratio, ref_s),
            "comparison": {
                "same_outcome": core.outcome.class() == reference.outcome.class(),
                "max_com_deviation_m": dev_com,
                "max_angle_deviation_rad": dev_angle,
                "compared_steps": core.rows.len().min(reference.rows.len()).saturating_sub(1),
                "meeting_offset_difference_m": meeting_gap,
            },
        });
        write_csv(&core, &dir.join("core.csv"))?;
        write_csv(&reference, &dir.join("reference.csv"))?;
        write_events_csv(&core, &dir.join("core-events.csv"))?;
        write_events_csv(&reference, &dir.join("reference-events.csv"))?;
        write_json(&dir.join("summary.json"), &summary)?;
        let title = format!("v = {} m/s: {} (solid) and reference (dashed)", p.finger_speed, core.label);
        plot::positions(&dir.join("positions.svg"), &title, &[&core, &reference])?;
        plot::relative(&dir.join("relative.svg"), &title, &[&core, &reference])?;
        results.push(SceneResult { name, summary, core, reference });
    }
    let all: Vec<&Value> = results.iter().map(|r| &r.summary).collect();
    write_json(&args.out.join("summary.json"), &json!({ "scenes": all }))?;
    Ok(terminal_summary(&results, &args.out))
}

/// Writes pretty JSON.
///
/// # Errors
/// I/O.
pub fn write_json(path: &Path, v: &Value) -> anyhow::Result<()> {
    std::fs::write(path, serde_json::to_string_pretty(v)? + "\n")
        .with_context(|| format!("writing {}", path.display()))
}

fn mm(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |x| format!("{:+.2}", 1e3 * x))
}

fn terminal_summary(results: &[SceneResult], out: &Path) -> String {
    let mut s = String::new();
    s += "scene     impl                outcome     t_end(s)  meet(mm)  eq21 ratios (min..max)  steps   piv/step  6x6 check\n";
    for r in results {
        for t in [&r.core, &r.reference] {
            let sw = switches(t);
            let ratios = if sw.is_empty() {
                "-".to_string()
            } else {
                let lo = sw.iter().map(|x| x.ratio).fold(f64::INFINITY, f64::min);
                let hi = sw.iter().map(|x| x.ratio).fold(f64::NEG_INFINITY, f64::max);
                format!("{lo:.4}..{hi:.4} ({})", sw.len())
            };
            let check = if t.label.contains("6x6") {
                format!(
                    "{} ({} before meeting)",
                    t.counters.reduced_check_fired, t.counters.reduced_check_fired_before_meeting
                )
            } else {
                "-".into()
            };
            s += &format!(
                "{:<9} {:<19} {:<11} {:>8.3}  {:>8}  {:<22}  {:>6}  {:>8.4}  {}\n",
                r.name,
                t.label,
                t.outcome.class(),
                t.end_time,
                mm(t.meeting.map(|m| m.1)),
                ratios,
                t.steps,
                t.counters.pivots as f64 / t.steps.max(1) as f64,
                check
            );
        }
        let c = &r.summary["comparison"];
        s += &format!(
            "{:<9} core vs reference: max |COM| deviation {:.3e} m, max |angle| deviation {:.3e} rad{}\n",
            "",
            c["max_com_deviation_m"].as_f64().unwrap_or(f64::NAN),
            c["max_angle_deviation_rad"].as_f64().unwrap_or(f64::NAN),
            if c["same_outcome"].as_bool() == Some(true) { "" } else { "  OUTCOMES DIFFER" }
        );
    }
    s += &format!("mu_k/mu_s = eq. 21's target ratio; files in {}\n", out.display());
    s
}
