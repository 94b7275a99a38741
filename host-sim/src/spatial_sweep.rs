//! The scenes in three dimensions in `host-sim report` ([`crate::commands::report`]): their error
//! against run time as the step shrinks, and where f32 holds over launch speed x step.
//!
//! **Error against run time** ([`sweep`]). Each [`CASES`] entry is a scene with a closed form
//! (`docs/scenes.md`; [`crate::bodies::law`]), run in the
//! core in f32 and in f64 with each `h` of a sweep through the one scene interface
//! ([`crate::view_run::run_view`]); its error is the measured quantity's against the law's:
//! * the puck on a level table launched at 30 degrees: its stopping distance against
//!   `v^2 / (2 mu_k g)` (relative), and the heading of its displacement against its launch heading
//!   (degrees: the isotropy of its friction);
//! * the billiard ball struck along `+x` with back and side spin: its rolling velocity against
//!   `(5 v0 + 2 R omega0 x z) / 7` (relative, the difference's length), and when it rolls against
//!   `2 |u0| / (7 mu_k g)` (relative).
//!
//! Velocity-level stepping removes the friction impulse `mu_k g h` a step, so the puck slides
//! `h` times the sum of its speeds after each step: its distance carries an error of order `h`,
//! and so does the ball's rolling time, which the run sees at the end of a step.
//!
//! Run time is host nanoseconds per step, the fastest of [`REPEATS`] runs without recording.
//!
//! **Where f32 holds** ([`envelope`]): the puck's stopping distance in f32 against f64 at the same
//! launch speed and step (the precision's error alone, the step's being the same in both), over
//! speeds x steps; a cell holds when they agree to [`ENVELOPE_TOLERANCE`].

use std::time::Instant;

use meterstick_core::scene::spatial::{BilliardParams, PuckParams};
use meterstick_core::scene::{SceneKind, SceneParams};

use crate::scenes::{LcpLayout, Precision};
use crate::trajectory::Measured;
use crate::view_run::{ViewRun, run_view};

/// The fastest of this many runs is a row's run time.
pub const REPEATS: usize = 3;

/// A cell of [`envelope`] holds when f32's stopping distance is within this of f64's (relative).
pub const ENVELOPE_TOLERANCE: f64 = 1e-3;

/// The puck's launch heading in the sweep (degrees from `x`).
const PUCK_HEADING_DEG: f64 = 30.0;

/// One quantity of one scene the sweep checks against its law.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// What is compared, in words (the report's row label).
    pub name: &'static str,
    /// The unit of the error (`"relative"` or `"deg"`).
    pub unit: &'static str,
    /// The scene with step `h`.
    pub scene: fn(f64) -> SceneParams,
    /// The error of a run's measured quantities against the law's; `None` when either lacks it.
    pub error: fn(&Measured, &Measured) -> Option<f64>,
    /// The stepping keeps the law exactly (its error is round-off at every step), rather than to
    /// an error that shrinks with `h`.
    pub exact: bool,
}

/// The puck on a level table, launched at [`PUCK_HEADING_DEG`], with step `h`.
fn puck(h: f64) -> SceneParams {
    SceneParams::Puck(PuckParams {
        angle: 0.0,
        heading: PUCK_HEADING_DEG.to_radians(),
        step: h,
        ..Default::default()
    })
}

/// The billiard ball struck at 2 m/s with back spin and side spin (a parabola), with step `h`.
fn billiard(h: f64) -> SceneParams {
    SceneParams::Billiard(BilliardParams { spin_x: 30.0, spin_y: -40.0, step: h, ..Default::default() })
}

/// `|a - b| / |b|`.
fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The scenes and quantities of the sweep.
pub const CASES: [Case; 4] = [
    Case {
        name: "puck: stopping distance",
        unit: "relative",
        scene: puck,
        error: |run, law| Some(relative(run.displacement_m?, law.displacement_m?)),
        exact: false,
    },
    Case {
        name: "puck: heading of its path",
        unit: "deg",
        scene: puck,
        error: |run, law| Some((run.displacement_heading_deg? - law.displacement_heading_deg?).abs()),
        exact: true,
    },
    Case {
        name: "billiard: rolling velocity",
        unit: "relative",
        scene: billiard,
        error: |run, law| {
            let (x, y) = (law.rolling_velocity_x_m_s?, law.rolling_velocity_y_m_s?);
            let d = (run.rolling_velocity_x_m_s? - x).hypot(run.rolling_velocity_y_m_s? - y);
            Some(d / x.hypot(y))
        },
        exact: true,
    },
    Case {
        name: "billiard: when it rolls",
        unit: "relative",
        scene: billiard,
        error: |run, law| Some(relative(run.rolling_time_s?, law.rolling_time_s?)),
        exact: false,
    },
];

/// One run of the sweep.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SpatialRow {
    /// The case's name ([`Case::name`]).
    pub case: &'static str,
    /// Its error's unit.
    pub unit: &'static str,
    /// The core's precision.
    pub precision: &'static str,
    /// The step (s).
    pub h: f64,
    /// Steps to the outcome.
    pub steps: u64,
    /// The error against the law (NaN when the run measured nothing).
    pub error: f64,
    /// Host nanoseconds per step, the fastest of [`REPEATS`].
    pub ns_per_step: f64,
}

/// The steps of the sweep: `1e-2` down to `1e-5` (quick: `1e-2`, `1e-3`).
#[must_use]
pub fn steps(quick: bool) -> Vec<f64> {
    if quick { vec![1e-2, 1e-3] } else { vec![1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5] }
}

/// Runs `spec` [`REPEATS`] times (once when `repeat` is false): the last run and the fastest
/// nanoseconds per step.
fn timed(spec: &SceneParams, precision: Precision, repeat: bool) -> anyhow::Result<(ViewRun, f64)> {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..if repeat { REPEATS } else { 1 } {
        let start = Instant::now();
        let run = run_view(spec, precision, LcpLayout::Reduced)?;
        best = best.min(start.elapsed().as_secs_f64() * 1e9 / run.steps.max(1) as f64);
        last = Some(run);
    }
    last.map(|r| (r, best)).ok_or_else(|| anyhow::anyhow!("no run"))
}

/// Every case in f32 and f64 at each of `steps`.
///
/// # Errors
/// A scene the core refuses, or Ctrl-C.
pub fn sweep(steps: &[f64]) -> anyhow::Result<Vec<SpatialRow>> {
    let mut rows = Vec::new();
    for case in &CASES {
        for precision in [Precision::F32, Precision::F64] {
            for &h in steps {
                let spec = (case.scene)(h);
                let (run, ns_per_step) = timed(&spec, precision, true)?;
                let measured = Measured::of(spec.kind(), run.measured);
                rows.push(SpatialRow {
                    case: case.name,
                    unit: case.unit,
                    precision: precision.name(),
                    h,
                    steps: run.steps,
                    error: crate::bodies::law(&spec)
                        .and_then(|law| (case.error)(&measured, &law.measured))
                        .unwrap_or(f64::NAN),
                    ns_per_step,
                });
            }
        }
    }
    Ok(rows)
}

/// One cell of [`envelope`].
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct EnvelopeCell {
    /// The puck's launch speed (m/s).
    pub speed: f64,
    /// The step (s).
    pub h: f64,
    /// f32's stopping distance against f64's (relative; NaN when either did not stop).
    pub difference: f64,
    /// `difference <= ENVELOPE_TOLERANCE`.
    pub holds: bool,
}

/// The puck's launch speeds of the envelope (m/s).
pub const ENVELOPE_SPEEDS: [f64; 4] = [0.01, 0.1, 1.0, 10.0];

/// Where f32 holds for the puck on a level table: its stopping distance in f32 against f64 over
/// [`ENVELOPE_SPEEDS`] x `steps` (each run long enough to stop: `v / (mu_k g)` and a second).
///
/// # Errors
/// A scene the core refuses, or Ctrl-C.
pub fn envelope(steps: &[f64]) -> anyhow::Result<Vec<EnvelopeCell>> {
    let mut cells = Vec::new();
    for speed in ENVELOPE_SPEEDS {
        for &h in steps {
            let SceneParams::Puck(p) = puck(h) else { continue };
            let stops = speed / (p.mu_kinetic * p.gravity);
            let spec = SceneParams::Puck(PuckParams { speed, max_time: stops + 1.0, ..p });
            let distance = |precision| -> anyhow::Result<Option<f64>> {
                let run = run_view(&spec, precision, LcpLayout::Reduced)?;
                Ok(Measured::of(SceneKind::Puck, run.measured).displacement_m)
            };
            let difference = match (distance(Precision::F32)?, distance(Precision::F64)?) {
                // Both stopped within the first step, where they started.
                (Some(a), Some(b)) if a == 0.0 && b == 0.0 => 0.0,
                (Some(a), Some(b)) => relative(a, b),
                _ => f64::NAN,
            };
            cells.push(EnvelopeCell { speed, h, difference, holds: difference <= ENVELOPE_TOLERANCE });
        }
    }
    Ok(cells)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::panic, clippy::float_cmp)]
mod tests {
    use super::*;

    /// In f64 the errors of the step shrink with it (each such case's error at `1e-3` below its
    /// error at `1e-2`, and under 5%), and what the stepping keeps exactly holds to round-off at
    /// every step: the puck's heading (isotropic friction) to 1e-9 degrees, the ball's rolling
    /// velocity to 1e-12.
    #[test]
    fn errors_shrink_with_the_step_and_the_heading_holds() {
        let rows = sweep(&steps(true)).unwrap();
        assert_eq!(rows.len(), CASES.len() * 2 * 2);
        for case in &CASES {
            let f64_rows: Vec<&SpatialRow> =
                rows.iter().filter(|r| r.case == case.name && r.precision == "f64").collect();
            let [coarse, fine] = f64_rows.as_slice() else { panic!("{}: {f64_rows:?}", case.name) };
            assert!(fine.error.is_finite() && coarse.error.is_finite(), "{}: {f64_rows:?}", case.name);
            if case.exact {
                let bound = if case.unit == "deg" { 1e-9 } else { 1e-12 };
                assert!(coarse.error < bound && fine.error < bound, "{}: {f64_rows:?}", case.name);
            } else {
                assert!(fine.error < coarse.error, "{}: {f64_rows:?}", case.name);
                assert!(fine.error < 0.05, "{}: {f64_rows:?}", case.name);
            }
        }
    }

    /// f32 follows f64 at a moderate speed and step, and a cell's verdict is its difference's.
    #[test]
    fn f32_holds_at_a_moderate_speed_and_step() {
        let cells = envelope(&[1e-3]).unwrap();
        assert_eq!(cells.len(), ENVELOPE_SPEEDS.len());
        let at_1 = cells.iter().find(|c| c.speed == 1.0).unwrap();
        assert!(at_1.holds && at_1.difference < 1e-4, "{at_1:?}");
        for c in &cells {
            assert_eq!(c.holds, c.difference <= ENVELOPE_TOLERANCE, "{c:?}");
        }
    }
}
