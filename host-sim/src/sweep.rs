//! The error against run time of `host-sim report` ([`crate::commands::report`]): the asymmetric
//! slow scene (`x1 = -0.35 m`, `v = 0.1 m/s`, paper otherwise) run with each `h` of a sweep in
//! four configurations ([`CONFIGS`]: core f32 6x6, core f32 8x8, core f64 8x8 and the f64
//! reference). Errors are measured against a *converged reference*: the reference with
//! `h_min / 4`. Quantities (all well defined for a run that balances):
//! * COM error: `max_t |com(t) - com_ref(t)|` on a 10 ms grid over a fixed horizon (positions
//!   interpolated linearly between steps);
//! * meeting error: `|offset - offset_ref|` of the COM from the fingers' midpoint when they meet;
//! * eq. 21 ratio error: the largest `|ratio_k - ratio_ref,k|` over the first four switches.
//!
//! Run time is host nanoseconds per step, the median of repeated runs of the whole scene without
//! recording (one repeat when a run takes over a second), and from it the host time to simulate
//! one second. The observed order in `h` is the least-squares slope of `log(COM error)` against
//! `log h` from the largest `h` down to the `h` of the smallest error (below that, the f32
//! rounding floor or the reference's own error dominates): [`order_fit`].

use std::time::Instant;

use meterstick_core::scene::MeterStickParams;
use rayon::prelude::*;

use crate::progress::bar as progress;
use crate::scenes::{Implementation, SceneParams};
use crate::trajectory::{OutcomeKind, Paths, Record, Trajectory, run as run_scene, switches};

/// The implementations the report compares.
pub const CONFIGS: [Implementation; 4] = [
    Implementation::CORE_F32_REDUCED,
    Implementation::CORE_F32_FULL,
    Implementation::CORE_F64_FULL,
    Implementation::Reference,
];

/// The sweep's scene with step `h`: the paper's, finger 1 from -0.35 m.
#[must_use]
pub fn sweep_scene(h: f64) -> SceneParams {
    SceneParams::MeterStick(MeterStickParams { finger1_x: -0.35, step: h, ..MeterStickParams::paper() })
}

/// The longest COM-error horizon the sweep can measure (s): its scene's converged run ends,
/// balanced, when the fingers have met (their travel at constant speed) and held for the hold
/// time.
#[must_use]
pub fn max_horizon() -> f64 {
    let p = MeterStickParams { finger1_x: -0.35, ..MeterStickParams::paper() };
    let travel = (p.finger2_x - p.finger1_x - p.finger_width) / (p.finger1_velocity - p.finger2_velocity);
    travel + p.hold_time
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
    pub outcome: OutcomeKind,
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
    pub paths: Option<Paths>,
    /// Timing repeats.
    pub repeats: usize,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The median host ns per step of `p`'s whole run in `config`: the core stepped through its scene
/// interface to the outcome with nothing read ([`crate::view_run::run_view`]), the reference run
/// unrecorded.
fn time_run(config: Implementation, p: &SceneParams) -> anyhow::Result<(f64, usize)> {
    let mut samples = Vec::new();
    loop {
        let start = Instant::now();
        let steps = match config {
            Implementation::Core(precision, layout) => crate::view_run::run_view(p, precision, layout)?.steps,
            Implementation::Reference => run_scene(p, config, Record::Nothing)?.steps,
        };
        let s = start.elapsed().as_secs_f64();
        samples.push(1e9 * s / steps.max(1) as f64);
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

/// The sweep: its rows (configuration by `h`, the largest `h` last) and the converged
/// reference's step.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// One row per configuration and `h`.
    pub rows: Vec<SweepRow>,
    /// The converged reference's step, `h_min / 4` (s).
    pub h_converged: f64,
}

/// The steps swept (s): nine from 1e-1 to 1e-5 s, or three (1e-1, 1e-2, 1e-3) when `quick`.
#[must_use]
pub fn steps(quick: bool) -> Vec<f64> {
    if quick { vec![1e-1, 1e-2, 1e-3] } else { vec![1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5] }
}

/// Runs the sweep over `hs`: the error runs (in parallel, recorded on the 10 ms grid), then the
/// timing runs (one at a time, so that runs do not share a core); errors over `horizon` (s).
///
/// # Errors
/// A run that cannot run.
pub fn run(hs: &[f64], horizon: f64) -> anyhow::Result<Sweep> {
    let h_min = hs.iter().copied().fold(f64::INFINITY, f64::min);
    let h_converged = h_min / 4.0;
    let runs = error_runs(hs, h_converged)?;
    let rows = timing_runs(&runs, horizon)?;
    Ok(Sweep { rows, h_converged })
}

/// The error runs: each `(configuration, h)` and its run, and the converged reference's run.
struct ErrorRuns {
    jobs: Vec<(Implementation, f64)>,
    runs: Vec<Trajectory>,
    converged: Trajectory,
}

/// The error runs (parallel), the converged reference first in the queue (the longest job).
fn error_runs(hs: &[f64], h_converged: f64) -> anyhow::Result<ErrorRuns> {
    let mut jobs: Vec<(Option<Implementation>, f64)> = vec![(None, h_converged)];
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
    let jobs = jobs.into_iter().map(|(c, h)| (c.unwrap_or(Implementation::Reference), h)).collect();
    Ok(ErrorRuns { jobs, runs, converged })
}

/// The timing runs (sequential, so that runs do not share a core), one row per error run.
fn timing_runs(error_runs: &ErrorRuns, horizon: f64) -> anyhow::Result<Vec<SweepRow>> {
    let ErrorRuns { jobs, runs, converged } = error_runs;
    let bar = progress(jobs.len() as u64, "timing runs");
    let mut rows = Vec::new();
    for (&(config, h), run) in jobs.iter().zip(runs) {
        let (ns, repeats) = time_run(config, &sweep_scene(h))?;
        bar.inc(1);
        rows.push(SweepRow {
            config,
            h,
            steps: run.steps,
            outcome: run.outcome.class,
            errors: errors(run, converged, horizon),
            ns_per_step: ns,
            ms_per_sim_second: ns / h * 1e-6,
            pivots_per_step: (config != Implementation::Reference)
                .then(|| run.counters.pivots as f64 / run.steps.max(1) as f64),
            paths: (config != Implementation::Reference).then_some(run.counters.paths),
            repeats,
        });
    }
    bar.finish_and_clear();
    Ok(rows)
}
