//! The independent reference's run (`meterstick-reference`), converted to a [`Trajectory`]: its
//! modes, outcomes and measured quantities named as the core names them (data only).

use meterstick_core::planar::{ContactMode, Direction};

use super::{
    ContactRow, Event, JamImpulses, Measured, Meeting, OutcomeKind, Record, Recorder, Row, RunOutcome,
    SolverCounters, Trajectory,
};
use crate::progress;
use crate::reference;
use crate::scenes::{Implementation, ParamsExt as _, SceneParams};

/// The reference's mode as the core names it (data only).
fn mode_of(m: reference::Mode) -> ContactMode {
    match m {
        reference::Mode::Separated => ContactMode::Separated,
        reference::Mode::Sticking => ContactMode::Sticking,
        reference::Mode::SlidingPositive => ContactMode::Sliding(Direction::Plus),
        reference::Mode::SlidingNegative => ContactMode::Sliding(Direction::Minus),
    }
}

fn pair<T: Copy + Default, const K: usize>(v: &[T]) -> [T; K] {
    core::array::from_fn(|i| v.get(i).copied().unwrap_or_default())
}

/// Runs the independent reference and records it as a [`Trajectory`].
///
/// # Errors
/// Invalid parameters (the reference's own checks).
pub fn run_reference<const K: usize>(spec: &SceneParams, record: Record) -> anyhow::Result<Trajectory<K>> {
    let Some(reference_spec) = spec.to_reference() else {
        anyhow::bail!("scene {} has no independent reference", spec.kind());
    };
    let sample = match record {
        Record::All => reference::Sample::All,
        Record::Nothing => reference::Sample::None,
        // Keep every n-th step when n h = dt exactly, else every step (the grid interpolates).
        Record::Grid(dt) => {
            let n = (dt / spec.step()).round();
            if n >= 1.0 && (n * spec.step() - dt).abs() <= 1e-9 * dt {
                reference::Sample::Every(n as u64)
            } else {
                reference::Sample::All
            }
        }
    };
    let run = reference::run(&reference_spec, sample).map_err(|e| anyhow::anyhow!("invalid scene: {e}"))?;
    progress::check()?;
    let mut rows = Recorder::new(record);
    for r in &run.rows {
        let contact = |c: &reference::Contact| ContactRow {
            mode: mode_of(c.mode),
            normal_impulse: c.normal_impulse,
            friction_impulse: c.friction_impulse,
            along: c.along,
        };
        let contacts: Vec<ContactRow> = r.contacts.iter().map(contact).collect();
        let c0 = ContactRow {
            mode: ContactMode::Separated,
            normal_impulse: 0.0,
            friction_impulse: 0.0,
            along: 0.0,
        };
        rows.push(Row {
            t: r.t,
            q: r.q,
            v: r.v,
            supports: pair(&r.supports),
            contacts: core::array::from_fn(|i| contacts.get(i).copied().unwrap_or(c0)),
        });
    }
    let events = run
        .events
        .iter()
        .map(|e| Event {
            t: e.t,
            contact: e.contact,
            mode: mode_of(e.mode),
            along: pair(&e.along),
            supports: [[f64::NAN; 2]; K],
        })
        .collect();
    let outcome = match &run.outcome {
        reference::Outcome::Balanced => RunOutcome::of(OutcomeKind::Balanced),
        reference::Outcome::Fell => RunOutcome::of(OutcomeKind::Fell),
        reference::Outcome::Held => RunOutcome::of(OutcomeKind::Held),
        reference::Outcome::Slid => RunOutcome::of(OutcomeKind::Slid),
        reference::Outcome::Tipped => RunOutcome::of(OutcomeKind::Tipped),
        reference::Outcome::Rolled => RunOutcome::of(OutcomeKind::Rolled),
        reference::Outcome::Jammed => RunOutcome::of(OutcomeKind::Jammed),
        reference::Outcome::Unfinished => RunOutcome::of(OutcomeKind::Unfinished),
        reference::Outcome::Failed(why) => {
            RunOutcome { class: OutcomeKind::Failed, detail: Some(why.clone()) }
        }
    };
    let start_top = match spec {
        SceneParams::Ladder(p) => p.length * p.angle.sin(),
        _ => f64::NAN,
    };
    Ok(Trajectory {
        implementation: Implementation::Reference,
        scene: spec.kind(),
        steps: run.steps,
        end_time: run.end_time,
        rows: rows.finish(),
        initial_modes: core::array::from_fn(|i| {
            run.initial_modes.get(i).map_or(ContactMode::Separated, |m| mode_of(*m))
        }),
        events,
        outcome,
        measured: Measured {
            meeting: run.meeting.map(|(time_s, com_offset_m)| Meeting { time_s, com_offset_m }),
            acceleration_m_s2: run.acceleration,
            angular_acceleration_rad_s2: run.angular_acceleration,
            wall_release_height_m: run.wall_release_height,
            wall_release_ratio: run.wall_release_height.map(|h| h / start_top),
            jam: run.jam.map(|j| JamImpulses {
                time_s: j.t,
                normal_impulse_n_s: j.normal_impulse,
                friction_impulse_n_s: j.friction_impulse,
            }),
        },
        counters: SolverCounters { ambiguous_steps: run.ambiguous_steps, ..SolverCounters::default() },
        checksum: None,
    })
}
