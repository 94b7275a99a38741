//! A scene of several bodies run in the core, through the registry.

use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::multibody::scenes::MultibodyScene;
use meterstick_core::planar::{BodyState, Checksum};
use meterstick_core::scene::{MultibodyVisitor, Outcome, Precision, SceneKind, SceneParams};

use super::{BodiesCounters, BodiesRow, BodiesRun};
use crate::progress::{self, CHECK_EVERY_STEPS};
use crate::trajectory::{Measured, RunOutcome};

/// A row of `states` at `t`, with each pair's interface force and candidates' loads.
fn row_of<T: Real>(t: T, states: &[BodyState<T>], forces: &[[T; 2]], loads: &[[[T; 2]; 4]]) -> BodiesRow {
    BodiesRow {
        t: t.as_f64(),
        q: states.iter().map(|s| [s.x.as_f64(), s.y.as_f64(), s.theta.as_f64()]).collect(),
        v: states.iter().map(|s| [s.vx.as_f64(), s.vy.as_f64(), s.omega.as_f64()]).collect(),
        interface_forces: forces.iter().map(|f| f.map(Real::as_f64)).collect(),
        corner_loads: loads.iter().map(|pair| pair.map(|c| c.map(Real::as_f64))).collect(),
    }
}

/// The core's run, through the registry.
struct CoreRun<'a> {
    kind: SceneKind,
    record: bool,
    bar: Option<&'a ProgressBar>,
}

impl MultibodyVisitor for CoreRun<'_> {
    type Output = anyhow::Result<BodiesRun>;

    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        mut scene: S,
    ) -> Self::Output {
        // The last step's interface forces and loads (the start's: zero).
        let (mut forces, mut loads) = ([[T::zero(); 2]; P], [[[T::zero(); 2]; 4]; P]);
        let start = row_of(scene.time(), scene.states(), &forces, &loads);
        let mut rows = if self.record { vec![start] } else { Vec::new() };
        let mut steps = 0_u64;
        let mut checksum = Checksum::new();
        while let Some(report) = scene.step() {
            steps += 1;
            report.add_to(&mut checksum);
            (forces, loads) = (report.interface_forces, report.corner_loads);
            if self.record {
                rows.push(row_of(report.time, &report.states, &forces, &loads));
            }
            if steps.is_multiple_of(CHECK_EVERY_STEPS) {
                progress::check()?;
                if let Some(bar) = self.bar {
                    bar.inc(CHECK_EVERY_STEPS);
                }
            }
        }
        let stats = scene.stats();
        Ok(BodiesRun {
            label: format!("core {}", T::NAME),
            scene: self.kind,
            steps,
            end_time: scene.time().as_f64(),
            rows,
            last: row_of(scene.time(), scene.states(), &forces, &loads),
            outcome: RunOutcome::from(scene.outcome().unwrap_or(Outcome::Unfinished)),
            measured: Measured::of(self.kind, scene.measured().map(|m| m.map(Real::as_f64))),
            counters: BodiesCounters {
                pivots: stats.pivots,
                max_pivots: stats.max_pivots,
                warm_direct: stats.warm_direct,
                max_active: stats.max_active,
                lcp_rows: S::ROWS,
                ambiguous_steps: stats.ambiguous_steps,
                rule_checked_steps: stats.rule_checked_steps,
                rule_enumerated_steps: stats.rule_enumerated_steps,
                rule_changed_answer: stats.rule_changed_answer,
            },
            checksum: Some(checksum.value()),
        })
    }
}

/// Runs `spec`, a scene of several bodies, in the core in `precision` to its outcome, keeping
/// every step when `record`, counting steps on `bar`.
///
/// # Errors
/// Invalid parameters (the core's complaint), or Ctrl-C.
pub fn run_core(
    spec: &SceneParams,
    precision: Precision,
    record: bool,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<BodiesRun> {
    progress::check()?;
    let run = spec
        .build_multibody(precision, CoreRun { kind: spec.kind(), record, bar })
        .map_err(|e| anyhow::anyhow!("{}", crate::scenes::flag_error(spec, e)))??;
    progress::check()?;
    Ok(run)
}
