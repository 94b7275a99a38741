//! The outputs of `host-sim stress`: `cases.csv`, `summary.json`, `criteria.svg`, `report.md` and
//! the terminal summary, all from the [`CaseResult`]s.
#![allow(clippy::format_push_string)]

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use super::{CONFIGS, CaseResult};
use crate::output::{parameters_json, sci, write_json, write_lines};
use crate::plot;
use crate::scenes::Implementation;
use crate::trajectory::OutcomeKind;

fn outcome_text(m: &super::Metrics) -> String {
    m.outcome.as_ref().map_or_else(|| "Panicked".to_string(), ToString::to_string)
}

/// One run in `summary.json`.
#[derive(Debug, Serialize)]
struct RunJson<'a> {
    implementation: Implementation,
    outcome: Option<OutcomeKind>,
    outcome_detail: Option<&'a str>,
    steps: u64,
    failures: &'a [super::judge::Failure],
}

/// One case in `summary.json`.
#[derive(Debug, Serialize)]
struct CaseJson<'a> {
    name: &'a str,
    group: &'a str,
    scene: crate::scenes::SceneKind,
    passed: bool,
    parameters: serde_json::Map<String, serde_json::Value>,
    start_dy_m: f64,
    deviation_f32x6_m: f64,
    deviation_f32x8_m: f64,
    runs: Vec<RunJson<'a>>,
}

/// `summary.json`.
#[derive(Debug, Serialize)]
struct SummaryJson<'a> {
    cases: usize,
    runs: usize,
    passed: usize,
    failed: usize,
    steps: u64,
    wall_s: f64,
    cases_detail: Vec<CaseJson<'a>>,
}

/// Writes every output file.
///
/// # Errors
/// I/O or plotting, naming the file.
pub fn write(out: &Path, results: &[CaseResult], wall: f64) -> anyhow::Result<()> {
    write_csv(&out.join("cases.csv"), results)?;
    plot_criteria(&out.join("criteria.svg"), results)?;
    let md = markdown(results, wall);
    std::fs::write(out.join("report.md"), &md)
        .map_err(|e| anyhow::anyhow!("writing {}: {e}", out.join("report.md").display()))?;
    let passed = results.iter().filter(|r| r.passed()).count();
    let summary = SummaryJson {
        cases: results.len(),
        runs: results.len() * CONFIGS.len(),
        passed,
        failed: results.len() - passed,
        steps: results.iter().flat_map(|r| r.runs.iter().map(|(m, _)| m.steps)).sum(),
        wall_s: wall,
        cases_detail: results
            .iter()
            .map(|r| CaseJson {
                name: &r.case.name,
                group: r.case.group,
                scene: r.case.spec.kind(),
                passed: r.passed(),
                parameters: parameters_json(&r.case.spec),
                start_dy_m: r.case.start_dy,
                deviation_f32x6_m: r.deviation[0],
                deviation_f32x8_m: r.deviation[1],
                runs: r
                    .runs
                    .iter()
                    .zip(CONFIGS)
                    .map(|((m, v), implementation)| RunJson {
                        implementation,
                        outcome: m.class(),
                        outcome_detail: m.outcome.as_ref().and_then(|o| o.detail.as_deref()),
                        steps: m.steps,
                        failures: &v.failures,
                    })
                    .collect(),
            })
            .collect(),
    };
    write_json(&out.join("summary.json"), &summary)
}

/// The terminal summary: totals, and each failing case with why.
#[must_use]
pub fn terminal(results: &[CaseResult], wall: f64, out: &Path) -> String {
    let passed = results.iter().filter(|r| r.passed()).count();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "stress: {} cases x {} implementations in {wall:.1} s: {passed} passed, {} failed",
        results.len(),
        CONFIGS.len(),
        results.len() - passed
    );
    for r in results.iter().filter(|r| !r.passed()) {
        let why: Vec<String> = r
            .runs
            .iter()
            .zip(CONFIGS)
            .filter(|((_, v), _)| !v.passed())
            .map(|((m, v), c)| format!("{c}: {} ({})", v.describe(), outcome_text(m)))
            .collect();
        let _ = writeln!(s, "  {} [FAIL]: {}", r.case.name, why.join("; "));
    }
    let _ = writeln!(s, "report: {}", out.join("report.md").display());
    s
}

fn write_csv(path: &Path, results: &[CaseResult]) -> anyhow::Result<()> {
    let header = "group,case,scene,passed,config,outcome,steps,residual_over_tol,max_penetration_m,penetration_over_bound,\
                  max_step_energy_gain_J,max_energy_gain_J,energy_gain_over_allowance,max_pivots,mean_pivots,\
                  reduced_check_fired,regularized_solves,claim_motion_m,deviation_from_f64_m,failures,wall_s";
    let mut lines = Vec::new();
    for r in results {
        for (k, ((m, v), c)) in r.runs.iter().zip(CONFIGS).enumerate() {
            let dev = r.deviation.get(k).map_or(String::new(), ToString::to_string);
            lines.push(format!(
                "{},\"{}\",{},{},{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\",{}",
                r.case.group,
                r.case.name,
                r.case.spec.kind(),
                v.passed(),
                c,
                outcome_text(m),
                m.steps,
                m.residual_ratio,
                m.penetration,
                m.penetration_ratio,
                m.step_energy_gain,
                m.energy_gain,
                m.energy_ratio,
                m.max_pivots,
                m.mean_pivots,
                m.reduced_check_fired,
                m.regularized_solves,
                m.claim_motion,
                dev,
                v.describe(),
                m.wall_s
            ));
        }
    }
    write_lines(path, header, lines)
}

/// The heat map: one row per case, one column per (implementation, criterion), coloured by
/// `log10(value / bound)`.
fn plot_criteria(path: &Path, results: &[CaseResult]) -> anyhow::Result<()> {
    let mut columns = Vec::new();
    for c in CONFIGS {
        let short = c.to_string().trim_start_matches("core ").to_string();
        for what in ["res.", "pen.", "energy"] {
            columns.push(format!("{short} {what}"));
        }
    }
    // Rows are drawn bottom-up: reversed, the first case is at the top.
    let rows: Vec<String> = results.iter().rev().map(|r| r.case.name.clone()).collect();
    let values: Vec<Vec<Option<f64>>> = results
        .iter()
        .rev()
        .map(|r| {
            r.runs
                .iter()
                .flat_map(|(m, _)| {
                    let ran = m.steps > 0;
                    [m.residual_ratio, m.penetration_ratio, m.energy_ratio].map(|x| ran.then_some(x))
                })
                .collect()
        })
        .collect();
    plot::ratio_map(
        path,
        "stress: each criterion's worst value over its bound (log10)",
        &columns,
        &rows,
        &values,
    )
}

fn markdown(results: &[CaseResult], wall: f64) -> String {
    let passed = results.iter().filter(|r| r.passed()).count();
    let mut md = String::new();
    let _ = writeln!(md, "# meterstick stress report\n");
    let _ = writeln!(
        md,
        "{} cases x {} implementations (core f32 6x6, f32 8x8, f64 8x8), {} steps in all, {wall:.1} s wall \
         clock: **{passed} passed, {} failed**.\n",
        results.len(),
        CONFIGS.len(),
        results.iter().flat_map(|r| r.runs.iter().map(|(m, _)| m.steps)).sum::<u64>(),
        results.len() - passed,
    );
    md.push_str(CRITERIA_MD);
    md.push_str("\n![criteria](criteria.svg)\n\n");
    let _ = writeln!(
        md,
        "| group | case | pass | f32 6x6 | f32 8x8 | f64 8x8 | steps (f32 6x6) | residual/tol | \
         max penetration (m) | pen./bound | max step gain (J) | max run gain (J) | gain/allowance | \
         max pivots | mean pivots | reduced check | regularised | dev. f32 6x6 / 8x8 vs f64 (m) |"
    );
    let _ = writeln!(md, "|{}", "---|".repeat(18));
    for r in results {
        let worst = |f: fn(&super::Metrics) -> f64| r.runs.iter().map(|(m, _)| f(m)).fold(0.0_f64, f64::max);
        let outcome = |k: usize| {
            r.runs.get(k).map_or_else(String::new, |(m, v)| {
                if v.passed() { outcome_text(m) } else { format!("{} ✗ {}", outcome_text(m), v.describe()) }
            })
        };
        let first = r.runs.first().map(|(m, _)| m);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.3} | {} | {} | {} / {} |",
            r.case.group,
            r.case.name,
            if r.passed() { "pass" } else { "FAIL" },
            outcome(0),
            outcome(1),
            outcome(2),
            first.map_or(0, |m| m.steps),
            sci(worst(|m| m.residual_ratio)),
            sci(worst(|m| m.penetration)),
            sci(worst(|m| m.penetration_ratio)),
            sci(worst(|m| m.step_energy_gain)),
            sci(worst(|m| m.energy_gain)),
            sci(worst(|m| m.energy_ratio)),
            r.runs.iter().map(|(m, _)| m.max_pivots).max().unwrap_or(0),
            first.map_or(0.0, |m| m.mean_pivots),
            first.map_or(0, |m| m.reduced_check_fired),
            r.runs.iter().map(|(m, _)| m.regularized_solves).sum::<u64>(),
            sci(r.deviation[0]),
            sci(r.deviation[1]),
        );
    }
    md
}

const CRITERIA_MD: &str = "\
## Criteria (per case and implementation; a case passes when every implementation passes)

1. no panic;
2. a physical outcome: no non-finite state, no solver error;
3. every LCP verified: the normalised residual over the solver's tolerance (256 N eps) at most 1;
4. penetration at most the start's penetration plus the second-order terms of one step,
   h^2 (|omega| (|u| + |v|) + size omega^2 / 2 + g), plus 64 eps (size + |x| + |y|) of round-off;
5. no energy from nowhere: over the run, E(t) - E(0) - W_supports(0, t) at most m g pen_0 (what a
   start penetration owes) plus 4096 N eps m (g (size + |y|) + V^2 + |v|^2 + (size omega)^2). The
   implicit step satisfies E+ - E <= sum u . P - sum p_n min(psi, 0) / h exactly, so only round-off
   and penetration recovery can add energy;
6. the case's physics claim where physics decides: the outcome class (similar scenes, mass
   scaling, quasi-static slow fingers, fast fingers; for the incline and the ladder, statics:
   held when tan a <= mu_s and tan a < w/h, tipped when w/h < tan a < mu_s, slid when
   tan a > mu_s and mu_k < w/h; a ladder stands iff tan theta >= (1 - mu_f mu_w) / (2 mu_f), no
   claim within 2 degrees of it; Painleve's rod jams when mu_k > 1.05 (1 + 3 c^2) / (3 s c) and the
   impact m V (1 + 3 c^2) / 4 exceeds 4 m g h; a cylinder rolls iff tan a <= mu_s (1 + k) / k, no
   claim within 2 %), 'not dragged' (frictionless or mu_k = 0: while finger 1 is left
   of the COM the rod does not move along x by more than 64 eps L), 'still' (zero speed or gravity,
   a held block or ladder: the body does not move by more than 64 eps size).

The scenes of several bodies (block-on-block, the tablecloth, the stack, disc-on-board; their LCP's layout is
its own, so the two f32 columns are one run): every LCP is verified in the core (a step it cannot
verify ends the run Failed: no residual is reported) and penetration is not measured (0); energy
as 5. with W the pull's work F (x+ - x) on the lower body, the allowance 4096 N eps
(sum_b m_b (g (size_b + |y_b|) + |v_b|^2 + (size_b omega_b)^2) + |F| size); the outcome by the laws of
docs/scenes.md, no claim within 5 % of a threshold (nor for a tablecloth block that would tip, a
board not out within half the run, or a disc whose rim would leave its board); 'still' (held): no
body moves by more than 64 eps (size + |x| + |y|) of its start; block-on-block's and
disc-on-board's accelerations within 1e-3 (|a| + g) of the laws'.

Energies in J, lengths in m. 'dev.' is the largest distance between the f32 and the f64 8x8
centre of mass over the sampled steps both runs have (a chaotic case diverges legitimately).
";
