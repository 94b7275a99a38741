//! Where the f32 core holds to the f64 solution, over finger speed x `h`: the table of
//! `host-sim envelope` ([`crate::commands::envelope`]) and of `host-sim report`'s section.
//!
//! For each finger speed (1e-4 .. 10 m/s) and step `h` (1e-5 .. 1e-2 s) the meter stick (the
//! paper's rod, fingers starting at -/+0.4 m, `mu_s = 0.6`, `mu_k = 0.4`) runs in:
//! * the core f32 6x6 (the firmware's configuration) and the core f64 8x8, both with `h`. The
//!   **f32 deviation** is `max |COM_f32 - COM_f64|` over the run, and the **event times** are
//!   compared switch by switch in order (`max |t_f32 - t_f64|` over the switches both have
//!   alike, and whether the two sequences of (contact, mode) agree);
//! * the core f64 8x8 with `h / 2`: **f64's own error** is `max |COM_f64(h) - COM_f64(h/2)|`
//!   (for a first-order method about half its error against the exact motion). The f64 run is
//!   **converged** where its outcome and its sequence of switch events (contact, mode) are the
//!   same at `h / 2` and its own error is at most 1 mm.
//!
//! The target, wherever the f64 run is converged: an f32 deviation of at most 1e-5 m, the same
//! outcome, the same sequence of switch events, and event times within `1e-5 m / speed` (the
//! finger moves at most 1e-5 m in the difference). Positions are compared on a grid of at most
//! 20,000 times per run (every step when there are fewer), the same times in all three runs.
//!
//! A run takes at most `--max-steps` steps (default 2e6): a slow finger at a small `h` is cut
//! at `max_steps h` of simulated time: such a cell's verdict holds for that time only
//! ([`Verdict::HoldsCut`]). The f64 core stands in for the independent reference (they agree to
//! round-off on every scene, `tests/tests/reference.rs`); the envelope checks that again on every
//! cell of at most 50,000 steps. Each cell also counts the f32 steps the core flagged
//! `round_off_limited` (`docs/formulation.md`, "Precision").
#![allow(clippy::format_push_string)]

use std::time::Instant;

use anyhow::bail;
use meterstick_core::scene::MeterStickParams;
use rayon::prelude::*;
use serde::Serialize;

use crate::output::sci;
use crate::progress::bar as progress;
use crate::scenes::{Implementation, LcpLayout, MAX_STEPS, Precision, SceneKind, SceneParams};
use crate::trajectory::{OutcomeKind, Record, Trajectory, max_deviation, run, run_k};
use meterstick_core::planar::{friction_beyond_precision, friction_limit};

/// The friction coefficients of the friction table (`mu_s = mu_k`; `docs/formulation.md`,
/// "Precision").
pub const MUS: [f64; 5] = [1e2, 1e3, 1e4, 1e5, 1e6];
/// The scenes of the friction table, each at its defaults but for `mu`.
pub const FRICTION_SCENES: [SceneKind; 3] = [SceneKind::MeterStick, SceneKind::Incline, SceneKind::Painleve];

/// The finger speeds of the table (m/s).
pub const SPEEDS: [f64; 9] = [1e-4, 1e-3, 1e-2, 0.1, 0.2, 0.3, 0.5, 1.0, 10.0];
/// The steps of the table (s).
pub const STEPS: [f64; 4] = [1e-5, 1e-4, 1e-3, 1e-2];
/// The target: f32 deviation (m) wherever f64 is converged.
pub const TARGET_M: f64 = 1e-5;
/// f64 is converged where its own error is at most this (m) and its outcome holds at `h / 2`.
pub const CONVERGED_M: f64 = 1e-3;
/// The independent reference is run beside the f64 core on cells of at most this many steps.
pub const REFERENCE_STEPS: u64 = 50_000;
/// Positions are compared at most this many times per run.
const SAMPLES: f64 = 20_000.0;

/// How a cell of the table fares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Verdict {
    /// f32 meets the target against f64 over the whole run.
    Holds,
    /// f32 meets the target over the runs' first `horizon_s` only: the step cap cut them.
    HoldsCut,
    /// f32 misses the target, but f64 itself is not converged there.
    F64NotConverged,
    /// f32 misses the target where f64 is converged.
    Exceeds,
}

impl Verdict {
    /// The verdict's name in `envelope.csv`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Holds => "holds",
            Self::HoldsCut => "holds_cut",
            Self::F64NotConverged => "f64_not_converged",
            Self::Exceeds => "exceeds",
        }
    }
}

/// One cell: a finger speed and a step.
// A record of the table's columns: each bool is one yes/no column.
#[allow(clippy::struct_excessive_bools)]
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cell {
    /// Finger 1's speed (m/s).
    pub speed_m_s: f64,
    /// The step (s).
    pub h_s: f64,
    /// Simulated time of the runs (s): to the outcome, or to the step cap.
    pub horizon_s: f64,
    /// The runs were cut at the step cap before the fingers met.
    pub capped: bool,
    /// Steps of the f32 run.
    pub steps: u64,
    /// Outcome of the f32 run.
    pub outcome_f32: OutcomeKind,
    /// Outcome of the f64 run.
    pub outcome_f64: OutcomeKind,
    /// `max |COM_f32 - COM_f64|` (m).
    pub f32_deviation_m: f64,
    /// Switch events of the f32 and f64 runs.
    pub events: [usize; 2],
    /// The two sequences of (contact, mode) are the same.
    pub events_agree: bool,
    /// `max |t_f32 - t_f64|` over the switches both runs have alike, in order (s; NaN: none).
    pub event_time_deviation_s: f64,
    /// f32 steps flagged `round_off_limited` by the core.
    pub flagged_steps: u64,
    /// `max |COM_f64(h) - COM_f64(h/2)|` (m).
    pub f64_own_error_m: f64,
    /// Outcome of the f64 run with `h / 2`.
    pub outcome_f64_half: OutcomeKind,
    /// f64 at `h / 2` has the same sequence of switch events (contact, mode) as at `h`.
    pub f64_events_converged: bool,
    /// f64 converged (same outcome and switch sequence at `h / 2`, own error at most
    /// [`CONVERGED_M`]).
    pub converged: bool,
    /// `max |COM_f64 - COM_reference|` (m), on cells of at most [`REFERENCE_STEPS`] steps.
    pub reference_deviation_m: Option<f64>,
    /// The verdict.
    pub verdict: Verdict,
}

/// One cell of the friction table: a scene in one layout at one `mu = mu_s = mu_k`, in f32 and f64.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrictionCell {
    /// The scene.
    pub scene: SceneKind,
    /// The layout both runs solve.
    pub layout: LcpLayout,
    /// `mu_s = mu_k`.
    pub mu: f64,
    /// Outcome of the f32 run.
    pub outcome_f32: OutcomeKind,
    /// Outcome of the f64 run.
    pub outcome_f64: OutcomeKind,
    /// `mu` is beyond what f32 resolves ([`meterstick_core::planar::friction_beyond_precision`]):
    /// `host-sim run` warns.
    pub beyond_f32: bool,
}

impl FrictionCell {
    /// f32 reaches f64's outcome.
    #[must_use]
    pub fn agrees(&self) -> bool {
        self.outcome_f32 == self.outcome_f64
    }
}

/// The scene `kind` at its defaults with `mu_s = mu_k = mu`.
fn friction_scene(kind: SceneKind, mu: f64) -> anyhow::Result<SceneParams> {
    let mut spec = SceneParams::defaults(kind);
    if !(spec.set("mu_static", mu) && spec.set("mu_kinetic", mu)) {
        bail!("internal: scene {kind} has no mu_static and mu_kinetic");
    }
    Ok(spec)
}

/// The friction table: every scene of [`FRICTION_SCENES`] in both layouts at every `mu` of `mus`,
/// in f32 and f64.
fn friction_cells(mus: &[f64]) -> anyhow::Result<Vec<FrictionCell>> {
    let mut jobs = Vec::new();
    for &kind in &FRICTION_SCENES {
        for layout in [LcpLayout::Reduced, LcpLayout::Full] {
            for &mu in mus {
                jobs.push((kind, layout, mu));
            }
        }
    }
    let bar = progress(2 * jobs.len() as u64, "friction runs");
    let cells = jobs
        .par_iter()
        .map(|&(kind, layout, mu)| {
            let spec = friction_scene(kind, mu)?;
            let outcome = |precision| {
                let implementation = Implementation::Core(precision, layout);
                let t = crate::with_contacts!(kind, K => run_k::<K>(&spec, implementation, Record::Nothing)
                    .map(|t| t.outcome.class));
                bar.inc(1);
                t
            };
            Ok(FrictionCell {
                scene: kind,
                layout,
                mu,
                outcome_f32: outcome(Precision::F32)?,
                outcome_f64: outcome(Precision::F64)?,
                beyond_f32: friction_beyond_precision::<f32>(mu),
            })
        })
        .collect();
    bar.finish_and_clear();
    cells
}

/// The whole table and what it took.
#[derive(Debug, Clone, Serialize)]
pub struct Envelope {
    /// The finger speeds (rows, m/s).
    pub speeds: Vec<f64>,
    /// The steps (columns, s).
    pub steps: Vec<f64>,
    /// Cells, speed-major: `cells[row * steps.len() + column]`.
    pub cells: Vec<Cell>,
    /// The friction coefficients of the friction table.
    pub mus: Vec<f64>,
    /// The friction table: scene-, layout-, then `mu`-major ([`FRICTION_SCENES`], both layouts, `mus`).
    pub friction: Vec<FrictionCell>,
    /// The step cap.
    pub max_steps: u64,
    /// Wall-clock time (s).
    pub wall_s: f64,
}

/// The scene of a cell, with its horizon and whether the cap cut it.
fn scene(speed: f64, h: f64, max_steps: u64) -> (MeterStickParams<f64>, bool) {
    let p = MeterStickParams { finger1_velocity: speed, step: h, ..MeterStickParams::paper() };
    let travel = (p.finger2_x - p.finger1_x - p.finger_width) / speed;
    let natural = travel + p.hold_time + 1.0;
    let cap = max_steps as f64 * h;
    (MeterStickParams { max_time: natural.min(cap), ..p }, natural > cap)
}

/// Who runs, and with which step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Job {
    F32,
    F64,
    F64Half,
    Reference,
}

fn run_job(speed: f64, h: f64, max_steps: u64, job: Job) -> anyhow::Result<Trajectory> {
    let (p, _) = scene(speed, h, max_steps);
    let steps = (p.max_time / h).ceil();
    let every = (steps / SAMPLES).ceil().max(1.0);
    let record = Record::Grid(every * h);
    let (implementation, p) = match job {
        Job::F32 => (Implementation::CORE_F32_REDUCED, p),
        Job::F64 => (Implementation::CORE_F64_FULL, p),
        Job::F64Half => (Implementation::CORE_F64_FULL, MeterStickParams { step: h / 2.0, ..p }),
        Job::Reference => (Implementation::Reference, p),
    };
    run(&SceneParams::MeterStick(p), implementation, record)
}

/// The switch events of `a` and `b` compared in order: whether they agree, and the largest time
/// difference over the common prefix of alike events (NaN when there is none).
fn compare_events(a: &Trajectory, b: &Trajectory) -> (bool, f64) {
    let mut dt = f64::NAN;
    for (x, y) in a.events.iter().zip(&b.events) {
        if (x.contact, x.mode) != (y.contact, y.mode) {
            return (false, dt);
        }
        dt = dt.max((x.t - y.t).abs());
    }
    (a.events.len() == b.events.len(), dt)
}

/// Runs the table.
///
/// # Errors
/// A `--max-steps` of 0 or beyond [`MAX_STEPS`] (before anything runs), or a run that cannot
/// run.
pub fn compute(quick: bool, max_steps: u64) -> anyhow::Result<Envelope> {
    if max_steps == 0 || max_steps as f64 > MAX_STEPS / 2.0 {
        bail!(
            "--max-steps {max_steps}: between 1 and {:e} (the h/2 run takes twice as many)",
            MAX_STEPS / 2.0
        );
    }
    let (speeds, hs): (&[f64], &[f64]) = if quick { (&[0.1, 1.0], &[1e-3, 1e-2]) } else { (&SPEEDS, &STEPS) };
    let mus: &[f64] = if quick { &[1e2, 1e4] } else { &MUS };
    // Jobs by (row, column, who).
    let mut jobs = Vec::new();
    for (i, &v) in speeds.iter().enumerate() {
        for (k, &h) in hs.iter().enumerate() {
            let (p, _) = scene(v, h, max_steps);
            let small = (p.max_time / h) as u64 <= REFERENCE_STEPS;
            let mine = [Job::F64Half, Job::F64, Job::F32].into_iter().chain(small.then_some(Job::Reference));
            jobs.extend(mine.map(|j| (i, k, j)));
        }
    }
    // The longest first: the h/2 runs, then by steps.
    let cost = |&(i, k, j): &(usize, usize, Job)| {
        let (v, h) = (speeds[i], hs[k]);
        scene(v, h, max_steps).0.max_time / h * if j == Job::F64Half { 2.0 } else { 1.0 }
    };
    jobs.sort_by(|a, b| cost(b).total_cmp(&cost(a)));
    let started = Instant::now();
    let bar = progress(jobs.len() as u64, "envelope runs");
    let done: Vec<anyhow::Result<Trajectory>> = jobs
        .par_iter()
        .map(|&(i, k, j)| {
            let r = run_job(speeds[i], hs[k], max_steps, j);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let done = done.into_iter().collect::<anyhow::Result<Vec<_>>>()?;
    let find = |i: usize, k: usize, j: Job| {
        jobs.iter().zip(&done).find(|(job, _)| **job == (i, k, j)).map(|(_, t)| t)
    };
    let mut cells = Vec::new();
    for (i, &v) in speeds.iter().enumerate() {
        for (k, &h) in hs.iter().enumerate() {
            let (p, capped) = scene(v, h, max_steps);
            let (Some(f32), Some(f64), Some(half)) =
                (find(i, k, Job::F32), find(i, k, Job::F64), find(i, k, Job::F64Half))
            else {
                bail!("internal: a run of the cell v = {v}, h = {h} is missing");
            };
            let (events_agree, event_dt) = compare_events(f32, f64);
            let f32_deviation_m = max_deviation(f32, f64).0;
            let f64_own_error_m = max_deviation(f64, half).0;
            let f64_events_converged = compare_events(f64, half).0;
            let converged = half.outcome.class == f64.outcome.class
                && f64_own_error_m <= CONVERGED_M
                && f64_events_converged;
            // NaN (no common switch) passes: the sequences' agreement is checked on its own.
            let events_within = event_dt.is_nan() || event_dt * v <= TARGET_M;
            let meets = f32_deviation_m <= TARGET_M
                && f32.outcome.class == f64.outcome.class
                && events_agree
                && events_within;
            let verdict = if meets && capped {
                Verdict::HoldsCut
            } else if meets {
                Verdict::Holds
            } else if converged {
                Verdict::Exceeds
            } else {
                Verdict::F64NotConverged
            };
            cells.push(Cell {
                speed_m_s: v,
                h_s: h,
                horizon_s: f32.end_time.max(f64.end_time).min(p.max_time),
                capped,
                steps: f32.steps,
                outcome_f32: f32.outcome.class,
                outcome_f64: f64.outcome.class,
                f32_deviation_m,
                events: [f32.events.len(), f64.events.len()],
                events_agree,
                event_time_deviation_s: event_dt,
                flagged_steps: f32.counters.round_off_limited,
                f64_own_error_m,
                outcome_f64_half: half.outcome.class,
                f64_events_converged,
                converged,
                reference_deviation_m: find(i, k, Job::Reference).map(|r| max_deviation(f64, r).0),
                verdict,
            });
        }
    }
    let friction = friction_cells(mus)?;
    Ok(Envelope {
        speeds: speeds.to_vec(),
        steps: hs.to_vec(),
        cells,
        mus: mus.to_vec(),
        friction,
        max_steps,
        wall_s: started.elapsed().as_secs_f64(),
    })
}

impl Envelope {
    /// The table in Markdown, rows by speed and columns by step, with its legend.
    #[must_use]
    pub fn markdown(&self) -> String {
        let (speeds, hs) = (&self.speeds, &self.steps);
        let mut md = String::from("| finger speed (m/s) |");
        for h in hs {
            md += &format!(" h = {h:e} s |");
        }
        md += "\n|---|";
        md += &"---|".repeat(hs.len());
        md += "\n";
        for (i, v) in speeds.iter().enumerate() {
            md += &format!("| {v} |");
            for k in 0..hs.len() {
                let Some(c) = self.cells.get(i * hs.len() + k) else {
                    md += " |";
                    continue;
                };
                let mark = match c.verdict {
                    Verdict::Holds => "ok".to_owned(),
                    Verdict::HoldsCut => format!("ok for the first {} s", c.horizon_s),
                    Verdict::F64NotConverged => "f64 not converged".to_owned(),
                    Verdict::Exceeds => "**exceeds**".to_owned(),
                };
                let events = if c.events_agree {
                    format!("{} events, dt {}", c.events[0], sci(c.event_time_deviation_s))
                } else {
                    format!("events differ ({} / {})", c.events[0], c.events[1])
                };
                let outcome = if c.outcome_f32 == c.outcome_f64 {
                    String::new()
                } else {
                    format!("; outcome {} / {}", c.outcome_f32, c.outcome_f64)
                };
                let flagged = if c.flagged_steps > 0 {
                    format!("; flagged {:.0} %", 100.0 * c.flagged_steps as f64 / c.steps.max(1) as f64)
                } else {
                    String::new()
                };
                md += &format!(
                    " {} m; {events}{outcome}; f64 own {} m{flagged}; {mark} |",
                    sci(c.f32_deviation_m),
                    sci(c.f64_own_error_m)
                );
            }
            md += "\n";
        }
        let holds =
            self.cells.iter().filter(|c| matches!(c.verdict, Verdict::Holds | Verdict::HoldsCut)).count();
        let exceeds = self.cells.iter().filter(|c| c.verdict == Verdict::Exceeds).count();
        let reference = self
            .cells
            .iter()
            .filter_map(|c| c.reference_deviation_m)
            .fold(None, |m: Option<f64>, d| Some(m.map_or(d, |m| m.max(d))));
        md += &format!(
            "\nEach cell: the f32 6x6 core's largest COM deviation from the f64 8x8 core at the same h; the \
             switch events (f32) and the largest difference of their times (s), or \"events differ\" when the \
             two sequences of (contact, mode) do; the outcomes when they differ; f64's own error (against f64 \
             at h/2); the share of f32 steps the core flagged `round_off_limited`; the verdict. The target: \
             COM within {} m, the same outcome and switch sequence, and switch times within 1e-5 m of finger \
             travel (\"f64 not converged\": f32 misses it but f64 itself moves more than {} m, or changes \
             outcome or switch sequence, when h halves; \"ok for the first T s\": runs cut at {} steps). {holds} of {} cells \
             hold, {exceeds} exceed the target where f64 is converged. The f64 core against the independent \
             reference on the cells of at most {REFERENCE_STEPS} steps: largest deviation {} m. {:.0} s wall \
             on this machine.\n",
            sci(TARGET_M),
            sci(CONVERGED_M),
            self.max_steps,
            self.cells.len(),
            reference.map_or_else(|| "n/a".into(), sci),
            self.wall_s
        );
        md += &self.friction_markdown();
        md
    }

    /// The friction table in Markdown: rows by scene and layout, columns by `mu`, each cell the f32
    /// and f64 outcomes.
    #[must_use]
    pub fn friction_markdown(&self) -> String {
        let mut md = String::from("\n| scene (layout) |");
        for mu in &self.mus {
            md += &format!(" mu = {mu:e} |");
        }
        md += "\n|---|";
        md += &"---|".repeat(self.mus.len());
        for (k, c) in self.friction.iter().enumerate() {
            if k % self.mus.len().max(1) == 0 {
                md += &format!("\n| {} ({}) |", c.scene, c.layout.name());
            }
            let verdict = if c.agrees() { "ok" } else { "**differs**" };
            let beyond = if c.beyond_f32 { "; beyond f32 (warned)" } else { "" };
            md += &format!(" {} / {}; {verdict}{beyond} |", c.outcome_f32, c.outcome_f64);
        }
        let agree = self.friction.iter().filter(|c| c.agrees()).count();
        let within = self.friction.iter().filter(|c| !c.beyond_f32);
        let (within_n, within_agree) = within.fold((0, 0), |(n, a), c| (n + 1, a + usize::from(c.agrees())));
        md += &format!(
            "\n\nEach cell: the f32 and f64 cores' outcomes (same layout) with mu_s = mu_k = mu, every other \
             parameter at the scene's default; \"beyond f32\": mu eps > 2^-9 (mu > {}), where `host-sim run` \
             warns that f32 does not resolve the friction (`docs/formulation.md`, \"Precision\"). {agree} of {} \
             cells agree; within f32's friction limit {within_agree} of {within_n}.\n",
            friction_limit::<f32>(),
            self.friction.len()
        );
        md
    }
}
