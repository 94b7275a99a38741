//! What `host-sim scene` prints of a scene of several bodies ([`summarise`]), and what `host-sim
//! run` writes and prints of them ([`run_all`]): the summaries, core against reference.

use meterstick_core::scene::{OutcomeKind, Precision, SceneKind, SceneParams};
use serde::Serialize;

use super::csv::write_trajectory;
use super::plots::write_plots;
use super::{
    BodiesCounters, BodiesRow, BodiesRun, BodiesWarning, Law, has_reference, law, run_core, run_reference,
    warnings,
};
use crate::progress;
use crate::trajectory::Measured;

/// The largest distance between the same body's centres of mass (m) and the largest angle
/// difference (rad) over the rows both runs recorded (row `i` is step `i` in both), and over
/// their final states when both ended on the same step.
#[must_use]
pub fn max_deviation(a: &BodiesRun, b: &BodiesRun) -> (f64, f64) {
    let mut worst = (0.0_f64, 0.0_f64);
    let mut compare = |p: &BodiesRow, q: &BodiesRow| {
        for (x, y) in p.q.iter().zip(&q.q) {
            worst.0 = worst.0.max((x[0] - y[0]).hypot(x[1] - y[1]));
            worst.1 = worst.1.max((x[2] - y[2]).abs());
        }
        for (x, y) in p.spatial.iter().zip(&q.spatial) {
            let d = (0..3).map(|i| (x.position[i] - y.position[i]).powi(2)).sum::<f64>().sqrt();
            // The angle of the turn from one orientation to the other: the chord between the unit
            // quaternions (the nearer of q2 and -q2) is 2 sin(angle / 4), exact for small angles.
            let sign = if (0..4).map(|i| x.orientation[i] * y.orientation[i]).sum::<f64>() < 0.0 {
                -1.0
            } else {
                1.0
            };
            let chord =
                (0..4).map(|i| (x.orientation[i] - sign * y.orientation[i]).powi(2)).sum::<f64>().sqrt();
            worst.0 = worst.0.max(d);
            worst.1 = worst.1.max(4.0 * (chord / 2.0).min(1.0).asin());
        }
    };
    for (p, q) in a.rows.iter().zip(&b.rows) {
        compare(p, q);
    }
    if a.steps == b.steps {
        compare(&a.last, &b.last);
    }
    worst
}

/// The core's rule counters in words (`docs/formulation.md`, "One answer: the rule").
fn rule_text(c: &BodiesCounters) -> String {
    format!(
        "core: {} steps not at rest flagged as possibly having several answers; of the {} enumerated {} had \
         several, and the rule changed the solver's first answer on {}",
        c.rule_checked_steps, c.rule_enumerated_steps, c.ambiguous_steps, c.rule_changed_answer
    )
}

/// The scene's measured quantities in words, beside the law's where it gives them.
fn measured_text(spec: &SceneParams, m: &Measured, law: Option<&Law>) -> String {
    let of = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |v| format!("{v:.6}"));
    let lower = law.and_then(|l| l.lower_acceleration);
    let upper = law.and_then(|l| l.upper_acceleration);
    match spec.kind() {
        SceneKind::BlockOnBlock => format!(
            "acceleration in full contact: bottom block {} m/s^2 (law {}), top block {} m/s^2 (law {})",
            of(m.acceleration_m_s2),
            of(lower),
            of(m.top_acceleration_m_s2),
            of(upper)
        ),
        SceneKind::DiscOnBoard => format!(
            "acceleration while touching: board {} m/s^2 (law {}), disc centre {} m/s^2 (law {})",
            of(m.acceleration_m_s2),
            of(lower),
            of(m.top_acceleration_m_s2),
            of(upper)
        ),
        SceneKind::Tablecloth => format!(
            "block displacement {} m (the law's accelerations in full contact: board {} m/s^2, block {} m/s^2)",
            of(m.block_displacement_m),
            of(lower),
            of(upper)
        ),
        SceneKind::Puck | SceneKind::Billiard | SceneKind::Curling | SceneKind::MeterStick3d => {
            let keys = meterstick_catalogue::SCENES[spec.kind().index()].measures;
            let ours = m.values(spec.kind());
            let theirs = law.map(|l| l.measured.values(spec.kind()));
            keys.iter()
                .enumerate()
                .map(|(i, key)| {
                    let predicted =
                        theirs.and_then(|t| t[i]).map_or_else(String::new, |v| format!(" (law {v:.6})"));
                    format!("{key} {}{predicted}", of(ours[i]))
                })
                .collect::<Vec<_>>()
                .join(", ")
        }
        _ => format!(
            "largest point speed {} m/s",
            m.max_speed_m_s.map_or_else(|| "-".to_string(), |v| format!("{v:.3e}"))
        ),
    }
}

/// `host-sim scene` for a scene of several bodies: one run in the core, summarised beside the
/// laws of `docs/scenes.md`.
///
/// # Errors
/// Invalid parameters, or Ctrl-C.
pub fn summarise(spec: &SceneParams, precision: Precision) -> anyhow::Result<String> {
    use std::fmt::Write as _;
    let bar = progress::bar(spec.steps() as u64, "steps");
    let run = run_core(spec, precision, false, Some(&bar))?;
    bar.finish_and_clear();
    let law = law(spec);
    let mut out = String::new();
    let params: Vec<String> = spec.fields().map(|(k, v)| format!("{k} = {v}")).collect();
    let _ = writeln!(out, "scene {}: {}", spec.kind(), params.join(", "));
    let _ = writeln!(out, "{}: outcome {} at t = {:.3} s", run.label, run.outcome, run.end_time);
    if let Some(law) = &law {
        let predicted =
            law.outcome.map_or_else(|| "undecided (at its threshold)".to_string(), |o| o.to_string());
        let _ = writeln!(out, "law: {predicted} ({})", law.text);
    }
    let _ = writeln!(out, "{}", measured_text(spec, &run.measured, law.as_ref()));
    let c = &run.counters;
    let contacts = match (c.max_active, spec.get("friction_directions")) {
        (Some(active), _) => {
            format!("most active contacts {active} (LCP of {} rows, the full form)", c.lcp_rows)
        }
        (None, Some(d)) if d > 0.0 => {
            format!("LCP of {} rows (the pyramid of {d} friction directions, the baseline)", c.lcp_rows)
        }
        (None, _) => format!("LCP of {} rows (one friction line a contact, turned to its slip)", c.lcp_rows),
    };
    let _ = writeln!(
        out,
        "steps {}, pivots {} (mean {:.4}/step, max {}), warm basis solved {} steps directly, {contacts}",
        run.steps,
        c.pivots,
        c.pivots as f64 / run.steps.max(1) as f64,
        c.max_pivots,
        c.warm_direct,
    );
    // The one-answer rule's counts, for an engine whose rule looks at its steps (the core's run).
    if run.checksum.is_some() && c.max_active.is_some() {
        let _ = writeln!(out, "{}", rule_text(c));
    }
    if let Some(warning) = crate::scenes::friction_warning(spec, precision) {
        let _ = writeln!(out, "{warning}");
    }
    for warning in warnings(spec, precision) {
        let _ = writeln!(out, "{warning}");
    }
    if let Some(sum) = run.checksum {
        let _ = writeln!(out, "checksum {sum:08x}");
    }
    Ok(out)
}

/// One implementation's part of a [`BodiesSummary`].
#[derive(Debug, Clone, Serialize)]
pub struct BodiesImplementation {
    /// Who computed it.
    pub implementation: String,
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
    /// Solver counters.
    pub counters: BodiesCounters,
    /// Wall-clock time of the run (s).
    pub wall_time_s: f64,
    /// Host ns per step (recording included).
    pub ns_per_step: f64,
    /// Each pair's summed contact force on its upper body over the last step, world `(x, y)` (N).
    pub interface_forces_n: Vec<[f64; 2]>,
    /// Each pair's four candidates' `[normal, friction]` force over the last step (N;
    /// [`BodiesRow::corner_loads`]).
    pub corner_loads_n: Vec<[[f64; 2]; 4]>,
}

impl BodiesImplementation {
    fn of(run: &BodiesRun, wall_s: f64) -> Self {
        Self {
            implementation: run.label.clone(),
            outcome: run.outcome.class,
            outcome_detail: run.outcome.detail.clone(),
            end_time_s: run.end_time,
            steps: run.steps,
            measured: run.measured,
            counters: run.counters,
            wall_time_s: wall_s,
            ns_per_step: 1e9 * wall_s / run.steps.max(1) as f64,
            interface_forces_n: run.last.interface_forces.clone(),
            corner_loads_n: run.last.corner_loads.clone(),
        }
    }
}

/// Core against reference.
#[derive(Debug, Clone, Serialize)]
pub struct BodiesComparison {
    /// Same outcome class.
    pub same_outcome: bool,
    /// Largest distance between the same body's centres of mass over the steps both have (m).
    pub max_position_deviation_m: f64,
    /// Largest angle difference (rad).
    pub max_angle_deviation_rad: f64,
    /// Steps compared.
    pub compared_steps: usize,
}

/// The law's part of a [`BodiesSummary`].
#[derive(Debug, Clone, Serialize)]
pub struct LawSummary {
    /// The outcome it predicts (`None` at its threshold).
    pub outcome: Option<OutcomeKind>,
    /// The lower body's acceleration (m/s^2).
    pub lower_acceleration_m_s2: Option<f64>,
    /// The upper body's (m/s^2).
    pub upper_acceleration_m_s2: Option<f64>,
    /// The scene's measured quantities where the law gives them (a scene in three dimensions).
    pub measured: Measured,
}

/// One run of a scene of several bodies, core and reference: its `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct BodiesSummary {
    /// The run's folder name.
    pub name: String,
    /// Which scene.
    pub scene: SceneKind,
    /// Every parameter (core names, SI units).
    pub parameters: serde_json::Map<String, serde_json::Value>,
    /// The core's run.
    pub core: BodiesImplementation,
    /// The reference's run (`None` for a scene the reference does not have).
    pub reference: Option<BodiesImplementation>,
    /// Core against reference (`None` without a reference).
    pub comparison: Option<BodiesComparison>,
    /// What `docs/scenes.md`'s laws say.
    pub law: Option<LawSummary>,
    /// What the core's run is warned of, by cause ([`super::warnings`]; empty when nothing).
    pub warnings: Vec<BodiesWarning>,
}

impl BodiesSummary {
    /// The summary of run `name` of `spec`: the core's run (and its wall time), the reference's
    /// where it has the scene, the two compared, the law's figures and the core's warnings.
    fn of(
        name: &str,
        spec: &SceneParams,
        precision: Precision,
        (core, core_s): (&BodiesRun, f64),
        reference: Option<&(BodiesRun, f64)>,
        law: Option<&Law>,
    ) -> Self {
        Self {
            name: name.to_string(),
            scene: spec.kind(),
            parameters: crate::output::parameters_json(spec),
            core: BodiesImplementation::of(core, core_s),
            reference: reference.map(|(r, s)| BodiesImplementation::of(r, *s)),
            comparison: reference.map(|(reference, _)| {
                let (dev_q, dev_angle) = max_deviation(core, reference);
                BodiesComparison {
                    same_outcome: core.outcome.class == reference.outcome.class,
                    max_position_deviation_m: dev_q,
                    max_angle_deviation_rad: dev_angle,
                    compared_steps: core.rows.len().min(reference.rows.len()).saturating_sub(1),
                }
            }),
            law: law.map(|l| LawSummary {
                outcome: l.outcome,
                lower_acceleration_m_s2: l.lower_acceleration,
                upper_acceleration_m_s2: l.upper_acceleration,
                measured: l.measured,
            }),
            warnings: warnings(spec, precision),
        }
    }
}

/// `run`'s lines comparing the core with the reference (or saying there is none), and the rule's
/// counts for an engine whose rule looks at its steps.
fn comparison_text(
    text: &mut String,
    name: &str,
    spec: &SceneParams,
    core: &BodiesRun,
    reference: Option<(&BodiesRun, &BodiesComparison)>,
) {
    use std::fmt::Write as _;
    let Some((reference, comparison)) = reference else {
        let _ =
            writeln!(text, "{name}: the independent reference does not have this scene: the core's run only");
        return;
    };
    let _ = writeln!(
        text,
        "{name}: core vs reference: max position deviation {:.3e} m, max angle deviation {:.3e} rad{}",
        comparison.max_position_deviation_m,
        comparison.max_angle_deviation_rad,
        if comparison.same_outcome { "" } else { "  OUTCOMES DIFFER" }
    );
    if let Some(d) = spec.get("friction_directions").filter(|&d| d > 0.0) {
        let _ = writeln!(
            text,
            "{name}: the core ran the pyramid of {d} friction directions, the reference Coulomb's circular cone: the deviation is the pyramid's error"
        );
    }
    if core.counters.max_active.is_some() {
        let _ = writeln!(
            text,
            "{name}: the reference found {} steps whose LCP has solutions that move the bodies differently; both take the least kinetic energy after the step (docs/formulation.md, \"One answer: the rule\")",
            reference.counters.ambiguous_steps
        );
        let _ = writeln!(text, "{name}: {}", rule_text(&core.counters));
    }
}

/// `host-sim run` for scenes recorded body by body: each in the core (`precision`) beside the
/// independent reference where the reference has the scene ([`super::has_reference`]), each
/// body's trajectory as CSV (`core.csv`, `reference.csv`), its plots (`write_plots`), its
/// `summary.json`, and `summary.json` over all runs under `out`.
///
/// # Errors
/// Invalid parameters (before anything runs), Ctrl-C, or I/O.
pub fn run_all(
    specs: &[(String, SceneParams)],
    precision: Precision,
    out: &std::path::Path,
) -> anyhow::Result<String> {
    use std::fmt::Write as _;
    let timed = |f: &dyn Fn() -> anyhow::Result<BodiesRun>| {
        let start = std::time::Instant::now();
        f().map(|r| (r, start.elapsed().as_secs_f64()))
    };
    crate::output::create_dir(out)?;
    let mut summaries = Vec::new();
    // The third plot of each run: its angles, or its path seen from above.
    let mut plots = std::collections::BTreeSet::new();
    let mut text = String::new();
    for (name, spec) in specs {
        let (core, reference) = rayon::join(
            || timed(&|| run_core(spec, precision, true, None)),
            || has_reference(spec).then(|| timed(&|| run_reference(spec, true))),
        );
        let (core, core_s) = core?;
        let reference = reference.transpose()?;
        let law = law(spec);
        let summary =
            BodiesSummary::of(name, spec, precision, (&core, core_s), reference.as_ref(), law.as_ref());
        let dir = out.join(name);
        crate::output::create_dir(&dir)?;
        write_trajectory(&core.rows, &dir.join("core.csv"))?;
        let reference = reference.map(|(r, _)| r);
        if let Some(reference) = &reference {
            write_trajectory(&reference.rows, &dir.join("reference.csv"))?;
        }
        let runs: Vec<&BodiesRun> = std::iter::once(&core).chain(reference.as_ref()).collect();
        plots.insert(write_plots(name, &runs, &dir)?);
        crate::output::write_json(&dir.join("summary.json"), &summary)?;
        for run in &runs {
            let _ = writeln!(
                text,
                "{name}: {:<14} {:<10} t = {:.3} s, {} steps; {}",
                run.label,
                run.outcome.to_string(),
                run.end_time,
                run.steps,
                measured_text(spec, &run.measured, law.as_ref())
            );
        }
        if let Some(law) = &law {
            let predicted = law.outcome.map_or_else(|| "undecided".to_string(), |o| o.to_string());
            let _ = writeln!(text, "{name}: law {predicted} ({})", law.text);
        }
        if let Some(warning) = crate::scenes::friction_warning(spec, precision) {
            let _ = writeln!(text, "{name}: {warning}");
        }
        for warning in &summary.warnings {
            let _ = writeln!(text, "{name}: {warning}");
        }
        comparison_text(&mut text, name, spec, &core, reference.as_ref().zip(summary.comparison.as_ref()));
        summaries.push(summary);
    }
    crate::output::write_json(&out.join("summary.json"), &serde_json::json!({ "runs": summaries }))?;
    let _ = writeln!(
        text,
        "files in {} (each run: core.csv, reference.csv where the reference has the scene, positions.svg, velocities.svg, {}, summary.json)",
        out.display(),
        plots.into_iter().collect::<Vec<_>>().join(" or ")
    );
    Ok(text)
}
