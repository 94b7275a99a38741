//! `host-sim run`, the main job: a scene (the meter stick by default: the paper's slow finger and
//! the fast ones of fig. 5) in the core (f32 6x6 by default, as the firmware runs it) beside the
//! independent f64 reference, with CSVs, `summary.json`, plots and a terminal summary.
//!
//! Output, per run `<name>/` under the output directory (`v0.1` for `--speed 0.1`, the scene's
//! name for a single run): `core.csv`, `reference.csv` (trajectories), `core-events.csv`,
//! `reference-events.csv`, `summary.json`, `positions.svg` (supports and centre of mass over time:
//! the paper's figs. 2, 3, 5), `motion.svg` (angle and height of the body, so that a fall shows),
//! `relative.svg` (meter stick: the fingers relative to the centre of mass); and `summary.json`
//! over all runs.
#![allow(clippy::format_push_string)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;
use serde::Serialize;

use crate::output::{create_dir, parameters_json, write_json};
use crate::plot;
use crate::progress::{Interrupted, interrupted, is_interrupted};
use crate::scenes::{
    Catalogued as _, Implementation, ImplementationOf, ParamsExt as _, SceneArgs, SceneKind, SceneParams,
};
use crate::trajectory::{
    Measured, OutcomeKind, Record, SolverCounters, Switch, Trajectory, check_recorded_steps,
    check_total_recorded_steps, max_deviation, run_k, switches, write_csv, write_events_csv,
};

/// The paper's finger speeds (m/s): the slow case (figs. 2-3) and the fast cases of fig. 5.
pub const PAPER_SPEEDS: [f64; 5] = [0.1, 0.5, 1.0, 5.0, 10.0];

/// `host-sim run` options.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// The scene and its parameters. For the meter stick, `--speed` defaults to the paper's
    /// 0.1 (slow), 0.5, 1, 5, 10 m/s (fig. 5): one run each.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output directory (created; existing files in it are overwritten).
    #[arg(long, default_value = "out/run")]
    pub out: PathBuf,
}

/// One implementation's part of a [`RunStats`]'s scene.
#[derive(Debug, Clone, Serialize)]
pub struct ImplementationSummary {
    /// Who computed it.
    pub implementation: ImplementationOf,
    /// How it ended.
    pub outcome: OutcomeKind,
    /// Why it failed, if it did.
    pub outcome_detail: Option<String>,
    /// Simulated time at the end (s).
    pub end_time_s: f64,
    /// Steps.
    pub steps: u64,
    /// The scene's measured quantities.
    pub measured: Measured,
    /// Switch events.
    pub switch_events: usize,
    /// The eq. 21 switches (meter stick).
    pub eq21_switches: Vec<Switch>,
    /// Largest `|ratio - mu_k/mu_s|` over them.
    pub eq21_worst_ratio_error: Option<f64>,
    /// Solver counters.
    pub counters: SolverCounters,
    /// Pivots per step.
    pub pivots_per_step: f64,
    /// Wall-clock time of the run (s).
    pub wall_time_s: f64,
    /// Host ns per step (recording included).
    pub ns_per_step: f64,
}

impl ImplementationSummary {
    fn of<const K: usize>(t: &Trajectory<K>, mu_ratio: Option<f64>, wall_s: f64) -> Self {
        let sw = if t.scene == SceneKind::MeterStick { switches(t) } else { Vec::new() };
        let worst = mu_ratio.and_then(|m| sw.iter().map(|s| (s.ratio - m).abs()).reduce(f64::max));
        let steps = t.steps.max(1) as f64;
        Self {
            implementation: t.implementation.of_scene(t.scene),
            outcome: t.outcome.class,
            outcome_detail: t.outcome.detail.clone(),
            end_time_s: t.end_time,
            steps: t.steps,
            measured: t.measured,
            switch_events: t.events.len(),
            eq21_switches: sw,
            eq21_worst_ratio_error: worst,
            counters: t.counters,
            pivots_per_step: t.counters.pivots as f64 / steps,
            wall_time_s: wall_s,
            ns_per_step: 1e9 * wall_s / steps,
        }
    }
}

/// Core against reference.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Same outcome class.
    pub same_outcome: bool,
    /// Largest distance between the two centres of mass over the steps both have (m).
    pub max_com_deviation_m: f64,
    /// Largest angle difference (rad).
    pub max_angle_deviation_rad: f64,
    /// Steps compared.
    pub compared_steps: usize,
}

/// One run of a scene, core and reference: `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct RunStats {
    /// The run's folder name.
    pub name: String,
    /// Which scene.
    pub scene: SceneKind,
    /// Every parameter (core names, SI units, radians).
    pub parameters: serde_json::Map<String, serde_json::Value>,
    /// `mu_k / mu_s` (meter stick: eq. 21's target ratio).
    pub mu_k_over_mu_s: Option<f64>,
    /// The core's run.
    pub core: ImplementationSummary,
    /// The reference's run (`None` for a scene the reference does not implement).
    pub reference: Option<ImplementationSummary>,
    /// Core against reference.
    pub comparison: Option<Comparison>,
    /// The core's friction is beyond its precision: the warning, in the user's flags
    /// ([`crate::scenes::friction_warning`]).
    pub friction_warning: Option<String>,
}

/// A run and who computes it.
type Job = (usize, Implementation);
/// A recorded run and its wall time (s).
type Timed<const K: usize> = (Trajectory<K>, f64);

/// Runs every scene of `args` in the core and the reference, writes the files, and returns the
/// terminal summary.
///
/// # Errors
/// Invalid parameters (before anything runs), or I/O.
pub fn run(args: &RunArgs) -> anyhow::Result<String> {
    // The paper's speeds are the meter stick's (three-fingers has a `--speed` too, and one run).
    let paper = (args.scene.kind() == SceneKind::MeterStick).then_some(("speed", &PAPER_SPEEDS[..]));
    let specs = args.scene.specs(paper)?;
    if crate::bodies::runs(args.scene.kind()) {
        for (_, spec) in &specs {
            check_recorded_steps(spec)?;
        }
        return crate::bodies::run_all(&specs, args.scene.precision, &args.out);
    }
    // Only the meter stick's default duration follows its fingers ([`SceneParams::follow_travel_time`]).
    let followed = args.scene.kind() == SceneKind::MeterStick
        && !args.scene.given.iter().any(|(f, _)| f.long == "duration");
    let travel_time = |e: anyhow::Error| {
        if followed { e.context("the default --duration follows the fingers' travel time") } else { e }
    };
    for (_, spec) in &specs {
        check_recorded_steps(spec).map_err(travel_time)?;
    }
    if specs.len() > 1 {
        // Every run's steps stay in memory until the last has finished: the list is bounded too.
        let (listed, flag) = match args.scene.given.iter().find(|(_, v)| v.len() > 1) {
            Some((flag, values)) => (list_text(flag, values), flag.long),
            None => {
                (format!("--speed (not given: the paper's {} m/s)", list_text_values(&PAPER_SPEEDS)), "speed")
            }
        };
        check_total_recorded_steps(&specs, &listed, flag).map_err(travel_time)?;
    }
    crate::with_contacts!(args.scene.kind(), K => run_all::<K>(args, &specs))
}

/// A list as given: `--angle 10,11,12,13 deg`.
fn list_text(flag: &crate::scenes::Flag, values: &[f64]) -> String {
    let unit = if flag.unit.is_empty() { String::new() } else { format!(" {}", flag.unit) };
    format!("--{} {}{unit}", flag.long, list_text_values(values))
}

/// Values as typed: `0.1,0.5,1`.
fn list_text_values(values: &[f64]) -> String {
    values.iter().map(|&v| crate::scenes::short_number(v)).collect::<Vec<_>>().join(",")
}

/// Runs the scenes (of `K` contacts each) and writes their files (the reference beside the core
/// where the reference implements the scene).
fn run_all<const K: usize>(args: &RunArgs, specs: &[(String, SceneParams)]) -> anyhow::Result<String> {
    let core = args.scene.implementation();
    let has_reference = specs.iter().all(|(_, s)| s.to_reference().is_some());
    let per_run = if has_reference { 2 } else { 1 };
    create_dir(&args.out)?;
    let bar = crate::progress::bar(per_run * specs.len() as u64, "running scenes");
    // Jobs: (run, implementation), the longest (the reference of the longest run) first.
    let mut jobs: Vec<(usize, Implementation)> = (0..specs.len())
        .flat_map(|k| [(k, Implementation::Reference), (k, core)])
        .filter(|(_, i)| has_reference || *i != Implementation::Reference)
        .collect();
    jobs.sort_by(|a, b| {
        let steps = |k: usize| specs[k].1.max_time() / specs[k].1.step();
        steps(b.0)
            .total_cmp(&steps(a.0))
            .then((b.1 == Implementation::Reference).cmp(&(a.1 == Implementation::Reference)))
    });
    let done: Vec<(Job, anyhow::Result<Timed<K>>)> = jobs
        .par_iter()
        .map(|&(k, implementation)| {
            if interrupted() {
                return ((k, implementation), Err(Interrupted.into()));
            }
            let start = Instant::now();
            let t = run_k::<K>(&specs[k].1, implementation, Record::All);
            bar.inc(1);
            ((k, implementation), t.map(|t| (t, start.elapsed().as_secs_f64())))
        })
        .collect();
    bar.finish_and_clear();
    let mut slots: Vec<[Option<Timed<K>>; 2]> = (0..specs.len()).map(|_| [None, None]).collect();
    // After Ctrl-C: the runs whose core and reference both finished are written, the others
    // dropped.
    let mut stopped = false;
    for ((k, implementation), r) in done {
        match r {
            Ok(t) => slots[k][usize::from(implementation == Implementation::Reference)] = Some(t),
            Err(e) if is_interrupted(&e) => stopped = true,
            Err(e) => return Err(e),
        }
    }
    let mut summaries = Vec::new();
    for (k, [core, reference]) in slots.into_iter().enumerate() {
        let (Some((core, core_s)), Some(reference)) =
            (core, if has_reference { reference.map(Some) } else { Some(None) })
        else {
            if stopped {
                continue;
            }
            anyhow::bail!("run {k} did not complete");
        };
        let (name, spec) = &specs[k];
        let dir = args.out.join(name);
        create_dir(&dir)?;
        // The scenes with a static and a kinetic coefficient (the ladder's are one each).
        let mu_ratio = spec.get("mu_kinetic").zip(spec.get("mu_static")).map(|(k, s)| k / s);
        let comparison = reference.as_ref().map(|(reference, _)| {
            let (dev_com, dev_angle) = max_deviation(&core, reference);
            Comparison {
                same_outcome: core.outcome.class == reference.outcome.class,
                max_com_deviation_m: dev_com,
                max_angle_deviation_rad: dev_angle,
                compared_steps: core.rows.len().min(reference.rows.len()).saturating_sub(1),
            }
        });
        let summary = RunStats {
            name: name.clone(),
            scene: spec.kind(),
            parameters: parameters_json(spec),
            mu_k_over_mu_s: mu_ratio,
            core: ImplementationSummary::of(&core, mu_ratio, core_s),
            reference: reference.as_ref().map(|(r, ref_s)| ImplementationSummary::of(r, mu_ratio, *ref_s)),
            comparison,
            friction_warning: crate::scenes::friction_warning(spec, args.scene.precision),
        };
        write_csv(&core, &dir.join("core.csv"))?;
        write_events_csv(&core, &dir.join("core-events.csv"))?;
        if let Some((reference, _)) = &reference {
            write_csv(reference, &dir.join("reference.csv"))?;
            write_events_csv(reference, &dir.join("reference-events.csv"))?;
        }
        write_json(&dir.join("summary.json"), &summary)?;
        plot_run(&dir, spec, &core, reference.as_ref().map(|(r, _)| r))?;
        summaries.push(summary);
    }
    write_json(&args.out.join("summary.json"), &serde_json::json!({ "runs": summaries }))?;
    if stopped {
        return Err(Interrupted.into());
    }
    Ok(terminal_summary(&summaries, &args.out))
}

/// The run's pictures, titled with the scene, the parameters that vary and both outcomes.
fn plot_run<const K: usize>(
    dir: &Path,
    spec: &SceneParams,
    core: &Trajectory<K>,
    reference: Option<&Trajectory<K>>,
) -> anyhow::Result<()> {
    let what = match spec {
        SceneParams::MeterStick(p) => {
            format!("meter stick, v1 = {} m/s, v2 = {} m/s", p.finger1_velocity, p.finger2_velocity)
        }
        SceneParams::Incline(p) => format!(
            "incline {:.1} deg, mu_s = {}, mu_k = {}",
            p.angle.to_degrees(),
            p.mu_static,
            p.mu_kinetic
        ),
        SceneParams::Ladder(p) => format!(
            "ladder {:.1} deg, mu_floor = {}, mu_wall = {}",
            p.angle.to_degrees(),
            p.mu_floor,
            p.mu_wall
        ),
        other => other.kind().info().title.to_lowercase(),
    };
    let title = match reference {
        Some(reference) => format!(
            "{what}: {} {} (solid), reference {} (dashed)",
            core.implementation.of_scene(core.scene),
            core.outcome.class,
            reference.outcome.class
        ),
        None => {
            format!(
                "{what}: {} {} (no reference for this scene)",
                core.implementation.of_scene(core.scene),
                core.outcome.class
            )
        }
    };
    let runs: Vec<&Trajectory<K>> = std::iter::once(core).chain(reference).collect();
    plot::positions(&dir.join("positions.svg"), &title, &runs)?;
    plot::motion(&dir.join("motion.svg"), &title, &runs)?;
    if matches!(spec.kind(), SceneKind::MeterStick | SceneKind::ThreeFingers) {
        plot::relative(&dir.join("relative.svg"), &title, &runs)?;
    }
    Ok(())
}

fn mm(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |x| format!("{:+.2}", 1e3 * x))
}

/// The scene's measured quantity, for the table.
fn measured_text(m: &Measured) -> String {
    if let Some(meeting) = m.meeting {
        return format!("meet {} mm", mm(Some(meeting.com_offset_m)));
    }
    if let Some(j) = m.jam {
        return format!("jam {:.4}, {:.4} N s", j.normal_impulse_n_s, j.friction_impulse_n_s);
    }
    if let (Some(a), Some(w)) = (m.acceleration_m_s2, m.angular_acceleration_rad_s2) {
        return format!("a = {a:.4}, {w:.3} rad/s^2");
    }
    if let Some(a) = m.acceleration_m_s2 {
        return format!("a = {a:.5} m/s^2");
    }
    if let (Some(h), Some(r)) = (m.wall_release_height_m, m.wall_release_ratio) {
        return format!("release {h:.4} m ({r:.4})");
    }
    "-".into()
}

fn terminal_summary(runs: &[RunStats], out: &Path) -> String {
    let mut s = String::new();
    // The runs' names set the first column's width (`three-fingers` is longer than `slow`).
    let w = runs.iter().map(|r| r.name.len()).max().unwrap_or(0).max(9);
    let _ = writeln!(
        s,
        "{:<w$} impl                outcome     t_end(s)  measured                    eq21 ratios (min..max)  steps   piv/step  reduced check",
        "run"
    );
    for r in runs {
        for t in std::iter::once(&r.core).chain(&r.reference) {
            let ratios = if t.eq21_switches.is_empty() {
                "-".to_string()
            } else {
                let lo = t.eq21_switches.iter().map(|x| x.ratio).fold(f64::INFINITY, f64::min);
                let hi = t.eq21_switches.iter().map(|x| x.ratio).fold(f64::NEG_INFINITY, f64::max);
                format!("{lo:.4}..{hi:.4} ({})", t.eq21_switches.len())
            };
            let check = match t.implementation.implementation {
                Implementation::Core(_, crate::scenes::LcpLayout::Reduced) => format!(
                    "{} ({} before meeting)",
                    t.counters.reduced_check_fired, t.counters.reduced_check_fired_before_meeting
                ),
                _ => "-".into(),
            };
            let _ = writeln!(
                s,
                "{:<w$} {:<19} {:<11} {:>8.3}  {:<26}  {:<22}  {:>6}  {:>8.4}  {}",
                r.name,
                t.implementation.to_string(),
                t.outcome.name(),
                t.end_time_s,
                measured_text(&t.measured),
                ratios,
                t.steps,
                t.pivots_per_step,
                check
            );
        }
        match &r.comparison {
            Some(c) => {
                let _ = writeln!(
                    s,
                    "{:<w$} core vs reference: max |COM| deviation {:.3e} m, max |angle| deviation {:.3e} rad{}",
                    "",
                    c.max_com_deviation_m,
                    c.max_angle_deviation_rad,
                    if c.same_outcome { "" } else { "  OUTCOMES DIFFER" }
                );
                let ambiguous = r.reference.as_ref().map_or(0, |t| t.counters.ambiguous_steps);
                if ambiguous > 0 {
                    let _ = writeln!(
                        s,
                        "{:<w$} the reference found {ambiguous} steps whose LCP has solutions that move the body \
                         differently; both take the least kinetic energy after the step (docs/formulation.md, \
                         \"One answer: the rule\")",
                        ""
                    );
                }
            }
            None => {
                let _ =
                    writeln!(s, "{:<w$} no independent reference for scene {}: the core alone", "", r.scene);
            }
        }
        if let Some(warning) = &r.friction_warning {
            let _ = writeln!(s, "{:<w$} {warning}", "");
        }
        if let Some(warning) = r.core.counters.round_off_warning(r.core.steps, r.friction_warning.is_some()) {
            let _ = writeln!(s, "{:<w$} {warning}", "");
        }
        let c = &r.core.counters;
        if c.rule_checked_steps > 0 {
            let _ = writeln!(
                s,
                "{:<w$} core: {} steps flagged as possibly having several answers ({} at rest, the rule's \
                 choice as they were); of the {} enumerated {} had several, and the rule changed the solver's \
                 first answer on {}",
                "",
                c.rule_checked_steps,
                c.rule_checked_steps - c.rule_enumerated_steps,
                c.rule_enumerated_steps,
                c.ambiguous_steps,
                c.rule_changed_answer
            );
        }
    }
    if runs.iter().any(|r| r.scene == SceneKind::MeterStick) {
        s += "eq21 ratios: x_stop/x_start at each stick-to-slip switch; eq. 21 says mu_k/mu_s.\n";
    }
    let _ = writeln!(s, "files in {}", out.display());
    s
}
