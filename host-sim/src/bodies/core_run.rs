//! A scene of several bodies run in the core, through the core's one scene interface
//! ([`SceneView`], built by [`SceneParams::build_view`]).

use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::planar::ContactMode;
use meterstick_core::scene::{
    Axis, FigureName, LcpLayout, LoadPart, Outcome, Pose, Precision, SceneKind, SceneParams, SceneView,
    Velocity, ViewVisitor,
};

use super::{BodiesCounters, BodiesRow, BodiesRun, ContactRow, SpatialBody};
use crate::progress::{self, CHECK_EVERY_STEPS};
use crate::trajectory::{Measured, RunOutcome};

/// The view's bodies and figures now as a row: each body's state, each pair's interface force
/// and candidates' loads (the view's [`FigureName::PairForce`] and [`FigureName::CandidateLoad`]).
fn row_of<T: Real>(view: &dyn SceneView<T>) -> BodiesRow {
    let mut row = BodiesRow {
        t: view.time().as_f64(),
        q: Vec::new(),
        v: Vec::new(),
        interface_forces: Vec::new(),
        corner_loads: Vec::new(),
        spatial: Vec::new(),
        contacts: Vec::new(),
    };
    let f64s = |v: [T; 3]| v.map(Real::as_f64);
    for b in (0..view.body_count()).filter_map(|i| view.body(i)) {
        match (b.pose, b.velocity) {
            (Pose::Planar { x, y, theta }, Velocity::Planar { vx, vy, omega }) => {
                row.q.push(f64s([x, y, theta]));
                row.v.push(f64s([vx, vy, omega]));
            }
            (Pose::Spatial { position, orientation }, Velocity::Spatial { linear, angular }) => {
                row.spatial.push(SpatialBody {
                    position: f64s(position),
                    orientation: orientation.map(Real::as_f64),
                    velocity: f64s(linear),
                    angular: f64s(angular),
                });
            }
            _ => {
                row.q.push([f64::NAN; 3]);
                row.v.push([f64::NAN; 3]);
            }
        }
    }
    if !row.spatial.is_empty() {
        for c in (0..view.contact_count()).filter_map(|i| view.contact(i)) {
            let friction = c.friction_impulse.as_f64();
            row.contacts.push(ContactRow {
                mode: match c.mode {
                    ContactMode::Separated => 0,
                    ContactMode::Sticking => 1,
                    ContactMode::Sliding(_) => 2,
                },
                point: f64s(c.point),
                normal_impulse: c.normal_impulse.as_f64(),
                friction_impulse: f64s(c.tangent).map(|t| t * friction),
            });
        }
    }
    for figure in (0..view.figure_count()).filter_map(|i| view.figure(i)) {
        let value = figure.value.as_f64();
        match figure.name {
            FigureName::PairForce { pair, axis } => {
                let pair = usize::from(pair);
                if row.interface_forces.len() <= pair {
                    row.interface_forces.resize(pair + 1, [0.0; 2]);
                }
                row.interface_forces[pair][usize::from(axis == Axis::Y)] = value;
            }
            FigureName::CandidateLoad { pair, candidate, part } => {
                let pair = usize::from(pair);
                if row.corner_loads.len() <= pair {
                    row.corner_loads.resize(pair + 1, [[0.0; 2]; 4]);
                }
                if let Some(load) = row.corner_loads[pair].get_mut(usize::from(candidate)) {
                    load[usize::from(part == LoadPart::Friction)] = value;
                }
            }
            _ => {}
        }
    }
    row
}

/// The core's run, through the view.
struct CoreRun<'a> {
    kind: SceneKind,
    record: bool,
    bar: Option<&'a ProgressBar>,
}

impl ViewVisitor for CoreRun<'_> {
    type Output = anyhow::Result<BodiesRun>;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        // The start's interface forces and loads are zero (no step yet).
        let mut rows = if self.record { vec![row_of(view)] } else { Vec::new() };
        let mut steps = 0_u64;
        while view.step() {
            steps += 1;
            if self.record {
                rows.push(row_of(view));
            }
            if steps.is_multiple_of(CHECK_EVERY_STEPS) {
                progress::check()?;
                if let Some(bar) = self.bar {
                    bar.inc(CHECK_EVERY_STEPS);
                }
            }
        }
        let summary = view.summary();
        Ok(BodiesRun {
            label: format!("core {}", T::NAME),
            scene: self.kind,
            steps,
            end_time: view.time().as_f64(),
            rows,
            last: row_of(view),
            outcome: RunOutcome::from(view.outcome().unwrap_or(Outcome::Unfinished)),
            measured: Measured::of(self.kind, view.measured().map(|m| m.map(Real::as_f64))),
            counters: BodiesCounters {
                pivots: summary.pivots,
                max_pivots: summary.max_pivots,
                warm_direct: u32::try_from(summary.warm_starts).unwrap_or(u32::MAX),
                max_active: summary.most_lcp_contacts,
                lcp_rows: view.lcp_capacity(),
                ambiguous_steps: summary.ambiguous_steps,
                rule_checked_steps: summary.rule_checked_steps,
                rule_enumerated_steps: summary.rule_enumerated_steps,
                rule_changed_answer: summary.rule_changed_answer,
            },
            checksum: Some(view.checksum()),
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
        .build_view::<0, _>(precision, LcpLayout::Full, CoreRun { kind: spec.kind(), record, bar })
        .map_err(|e| anyhow::anyhow!("{}", crate::scenes::flag_error(spec, e)))??;
    progress::check()?;
    Ok(run)
}
