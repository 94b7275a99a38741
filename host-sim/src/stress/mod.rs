//! `host-sim stress`: numerical stability on stiff and extreme cases.
//!
//! A grid of scenes ([`cases`]: the meter stick at extreme speeds, steps, friction, masses, shapes,
//! gravities and edge geometries; blocks on steep and shallow inclines, very tall and very flat;
//! ladders frictionless, at and near the critical angle; Painlevé's rod jamming, at tiny steps,
//! huge speeds and friction; cylinders rolling and slipping; the scenes of several bodies at mass
//! ratios 1:1000, steps 1e-6..0.1 s and friction up to 1e4, [`bodies`]; the scenes in three
//! dimensions at extreme masses, steps, friction, speeds and spins), each run in the core as f32 6x6 (the
//! firmware's), f32 8x8 and f64 8x8 (a one-contact scene: 3x3, 4x4 and 4x4), with metrics computed here in f64 from what the core reports
//! after every step ([`metrics`]) and judged by the criteria of [`mod@judge`]; [`output`] writes the
//! report.

pub mod bodies;
pub mod cases;
pub mod figures;
pub mod judge;
pub mod metrics;
pub mod output;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context as _;
use rayon::prelude::*;

use self::cases::Case;
use self::judge::{Verdict, judge};
use self::metrics::Metrics;
use crate::progress::bar as progress;
use crate::scenes::{Implementation, LcpLayout, Precision};

/// `host-sim stress` options.
#[derive(Debug, Clone, clap::Args)]
pub struct StressArgs {
    /// Output directory (created; files in it are overwritten).
    #[arg(long, default_value = "out/stress")]
    pub out: PathBuf,
    /// The small subset (a few seconds, for tests).
    #[arg(long)]
    pub quick: bool,
    /// Only cases whose name contains this (an error lists the names when none does).
    #[arg(long)]
    pub only: Option<String>,
}

/// The core configurations the grid runs.
pub const CONFIGS: [Implementation; 3] =
    [Implementation::CORE_F32_REDUCED, Implementation::CORE_F32_FULL, Implementation::CORE_F64_FULL];

/// Runs `case` in `config`, catching a panic.
#[must_use]
pub fn run_case(case: &Case, config: Implementation) -> Metrics {
    let stride = ((case.spec.max_time() / case.spec.step()) / 100_000.0).ceil().max(1.0) as u64;
    let (precision, layout) = match config {
        Implementation::Core(precision, layout) => (precision, layout),
        Implementation::Reference => (Precision::F64, LcpLayout::Full),
    };
    let run = std::panic::catch_unwind(|| {
        if crate::bodies::runs(case.spec.kind()) {
            bodies::measure(case, precision, stride)
        } else {
            metrics::measure(case, precision, layout, stride)
        }
    });
    run.unwrap_or_default()
}

/// One case's runs.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The case.
    pub case: Case,
    /// One per [`CONFIGS`] entry.
    pub runs: Vec<(Metrics, Verdict)>,
    /// Largest `|COM_f32 - COM_f64|` (m) of the f32 6x6 and f32 8x8 runs against f64 8x8, over the
    /// sampled steps both have.
    pub deviation: [f64; 2],
}

impl CaseResult {
    /// `true` when every implementation passed.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.runs.iter().all(|(_, v)| v.passed())
    }
}

fn deviation(a: &Metrics, b: &Metrics) -> f64 {
    a.trace.iter().zip(&b.trace).fold(0.0, |acc, (x, y)| acc.max((x[0] - y[0]).hypot(x[1] - y[1])))
}

/// Runs every case in every configuration (in parallel). After Ctrl-C ([`crate::progress`]) no
/// new run starts, the runs under way finish, and only the cases whose runs all finished are
/// returned.
#[must_use]
pub fn run_all(cases: Vec<Case>) -> Vec<CaseResult> {
    let jobs: Vec<(usize, Implementation)> =
        (0..cases.len()).flat_map(|i| CONFIGS.iter().map(move |&c| (i, c))).collect();
    let bar = progress(jobs.len() as u64, "stress runs");
    let done: Vec<(usize, usize, Metrics)> = jobs
        .par_iter()
        .filter_map(|&(i, config)| {
            if crate::progress::interrupted() {
                return None;
            }
            let m = run_case(&cases[i], config);
            bar.inc(1);
            Some((i, CONFIGS.iter().position(|c| *c == config).unwrap_or(0), m))
        })
        .collect();
    bar.finish_and_clear();
    let mut per_case: Vec<Vec<(usize, Metrics)>> = (0..cases.len()).map(|_| Vec::new()).collect();
    for (i, c, m) in done {
        per_case[i].push((c, m));
    }
    let mut results: Vec<CaseResult> = Vec::new();
    for (case, mut runs) in cases.into_iter().zip(per_case) {
        if runs.len() < CONFIGS.len() {
            continue;
        }
        runs.sort_by_key(|(c, _)| *c);
        let mut mine: Vec<(Metrics, Verdict)> = runs
            .into_iter()
            .map(|(_, m)| {
                let v = judge(&case, &m);
                (m, v)
            })
            .collect();
        let dev = |a: usize| match (mine.get(a), mine.get(2)) {
            (Some(x), Some(y)) => deviation(&x.0, &y.0),
            _ => f64::NAN,
        };
        let deviation = [dev(0), dev(1)];
        for (m, _) in &mut mine {
            m.trace = Vec::new();
        }
        results.push(CaseResult { case, runs: mine, deviation });
    }
    results
}

/// `host-sim stress`: runs the grid, writes `report.md`, `cases.csv`, `summary.json` and
/// `criteria.svg` to `args.out`, and returns the terminal summary and whether every case passed.
///
/// # Errors
/// `--only` matching no case (the error lists the names), or I/O.
pub fn run(args: &StressArgs) -> anyhow::Result<(String, bool)> {
    let mut cases = cases::cases(args.quick);
    if let Some(only) = &args.only {
        let names: Vec<String> = cases.iter().map(|c| c.name.clone()).collect();
        cases.retain(|c| c.name.contains(only.as_str()));
        anyhow::ensure!(
            !cases.is_empty(),
            "--only {only:?} matches no case{}; the cases are:\n  {}",
            if args.quick { " of --quick" } else { "" },
            names.join("\n  ")
        );
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let started = Instant::now();
    let results = run_all(cases);
    if results.is_empty() {
        // Only after Ctrl-C before any case finished: nothing to report.
        crate::progress::check()?;
    }
    let wall = started.elapsed().as_secs_f64();
    output::write(&args.out, &results, wall)?;
    crate::progress::check()?;
    Ok((output::terminal(&results, wall, &args.out), results.iter().all(CaseResult::passed)))
}
