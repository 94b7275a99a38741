//! A run as the rig reports it, recorded in `host-sim run`'s form.

use std::time::{Duration, Instant};

use anyhow::bail;
use meterstick_core::planar::{ContactMode, Direction};
use meterstick_core::scene::MeterStickParams;
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, ContactTelemetry, ErrorCode, Mode, OutcomeCode, Report, RigState};
use serde::Serialize;

use crate::scenes::{Implementation, SceneKind};
use crate::trajectory::{
    ContactRow, Event, Measured, OutcomeKind, Row, RunOutcome, SolverCounters, Trajectory,
};

/// The rig's scene is the meter stick: two contacts (its telemetry's `contacts`).
const RIG_CONTACTS: usize = 2;

/// The real-time margin the rig reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Margin {
    /// The longest step (CPU cycles; under QEMU SysTick ticks).
    pub worst_cycles: u32,
    /// The step period (cycles; 0: not real time).
    pub period_cycles: u32,
    /// Steps over their period.
    pub overruns: u32,
    /// The step number of the longest step.
    pub worst_step: u32,
}

/// A run as the rig reported it.
#[derive(Debug, Clone)]
pub struct Recording {
    /// The parameters the rig ran (read back before the start).
    pub params: MeterStickParams<f32>,
    /// The run, in `host-sim run`'s form (rows: the telemetry frames).
    pub trajectory: Trajectory,
    /// The rig's outcome code.
    pub outcome: OutcomeCode,
    /// The rig's checksum of the run.
    pub checksum: u32,
    /// The last margin.
    pub margin: Option<Margin>,
    /// Reports the rig said it dropped.
    pub dropped: u32,
    /// Telemetry frames received.
    pub telemetry_frames: u64,
    /// Wall time from start to outcome (s).
    pub wall_s: f64,
}

/// How the rig's modes map to the core's (an interface's [`Mode::Tipping`], which the meter
/// stick's contacts never report, as the sticking of its one touching corner).
#[must_use]
pub const fn mode_of(m: Mode) -> ContactMode {
    match m {
        Mode::Separated => ContactMode::Separated,
        Mode::Sticking | Mode::Tipping => ContactMode::Sticking,
        Mode::SlidingPositive => ContactMode::Sliding(Direction::Plus),
        Mode::SlidingNegative => ContactMode::Sliding(Direction::Minus),
    }
}

/// The run outcome a rig reported: each outcome of the core as itself
/// (`meterstick_rig::session::outcome_code` is the other direction), a fault with its code.
#[must_use]
pub fn outcome_of(o: OutcomeCode) -> RunOutcome {
    match o {
        OutcomeCode::Balanced => RunOutcome::of(OutcomeKind::Balanced),
        OutcomeCode::Fell => RunOutcome::of(OutcomeKind::Fell),
        OutcomeCode::Held => RunOutcome::of(OutcomeKind::Held),
        OutcomeCode::Slid => RunOutcome::of(OutcomeKind::Slid),
        OutcomeCode::Tipped => RunOutcome::of(OutcomeKind::Tipped),
        OutcomeCode::Rolled => RunOutcome::of(OutcomeKind::Rolled),
        OutcomeCode::Jammed => RunOutcome::of(OutcomeKind::Jammed),
        OutcomeCode::Rode => RunOutcome::of(OutcomeKind::Rode),
        OutcomeCode::Stayed => RunOutcome::of(OutcomeKind::Stayed),
        OutcomeCode::Stopped => RunOutcome::of(OutcomeKind::Stopped),
        OutcomeCode::Unfinished => RunOutcome::of(OutcomeKind::Unfinished),
        other => RunOutcome { class: OutcomeKind::Failed, detail: Some(format!("{other:?}")) },
    }
}

/// What [`record_run`] shows while it records.
pub trait Observer {
    /// Every report of the run, as it arrives.
    fn report(&mut self, report: &Report);
}

impl<F: FnMut(&Report)> Observer for F {
    fn report(&mut self, report: &Report) {
        self(report);
    }
}

/// Records a run until its outcome (and the margin after it): with `start`, sends `Start`
/// first; otherwise waits for a run to begin (the rig's button). `params` are the rig's.
///
/// # Errors
/// The start refused, no outcome within `timeout`, or the link failed.
pub fn record_run(
    link: &mut Link,
    params: MeterStickParams<f32>,
    start: bool,
    timeout: Duration,
    observer: &mut dyn Observer,
) -> anyhow::Result<Recording> {
    let began = Instant::now();
    if start {
        match link.request(&Command::Start, REPLY_TIMEOUT)? {
            Report::Ack { .. } => {}
            other => bail!("the rig refused to start: {other:?}"),
        }
    }
    let deadline = began + timeout;
    let heights = [f64::from(params.finger1_y), f64::from(params.finger2_y)];
    let mut rows = Vec::new();
    let mut events = Vec::new();
    let mut initial_modes = None;
    let mut outcome = None;
    let mut margin = None;
    let mut dropped = 0_u32;
    let mut telemetry_frames = 0;
    let mut running = !start;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let Some(report) = link.next(left.min(Duration::from_millis(500)))? else {
            if Instant::now() >= deadline {
                bail!("{}: no outcome within {:.0} s", link.name, timeout.as_secs_f64());
            }
            continue;
        };
        observer.report(&report);
        match report {
            Report::State(RigState::Running) => running = true,
            Report::Telemetry { step, time, state, fingers, contacts } if running => {
                telemetry_frames += 1;
                let row = row_of(time, state, fingers, contacts, heights);
                if step == 0 {
                    initial_modes = Some(contacts.map(|c| mode_of(c.mode)));
                }
                rows.push(row);
            }
            Report::Switch { time, contact, mode, along, .. } if running => events.push(Event {
                t: f64::from(time),
                contact: usize::from(contact),
                mode: mode_of(mode),
                along: along.map(f64::from),
                supports: [[f64::NAN; 2]; RIG_CONTACTS],
            }),
            Report::Outcome { outcome: code, time, steps, checksum } if running => {
                outcome = Some((code, time, steps, checksum));
            }
            Report::Margin { worst_cycles, period_cycles, overruns, worst_step } => {
                margin = Some(Margin { worst_cycles, period_cycles, overruns, worst_step });
            }
            Report::Error(ErrorCode::TxDropped { count }) => dropped = dropped.saturating_add(count),
            _ => {}
        }
        // After the outcome the rig sends the run's margin, then its new state.
        if outcome.is_some() && matches!(report, Report::State(s) if s != RigState::Running) {
            break;
        }
    }
    let Some((code, time, steps, checksum)) = outcome else { bail!("no outcome") };
    let trajectory = Trajectory {
        implementation: Implementation::CORE_F32_REDUCED,
        scene: SceneKind::MeterStick,
        steps: u64::from(steps),
        end_time: f64::from(time),
        initial_modes: initial_modes.unwrap_or([ContactMode::Separated; RIG_CONTACTS]),
        rows,
        events,
        outcome: outcome_of(code),
        measured: Measured::default(),
        counters: SolverCounters::default(),
        checksum: Some(checksum),
    };
    Ok(Recording {
        params,
        trajectory,
        outcome: code,
        checksum,
        margin,
        dropped,
        telemetry_frames,
        wall_s: began.elapsed().as_secs_f64(),
    })
}

fn row_of(
    time: f32,
    state: [f32; 6],
    fingers: [f32; 2],
    contacts: [ContactTelemetry; 2],
    heights: [f64; 2],
) -> Row {
    let s = state.map(f64::from);
    let (sin, cos) = s[2].sin_cos();
    let contact = |i: usize| {
        let c = contacts[i];
        let (dx, dy) = (f64::from(fingers[i]) - s[0], heights[i] - s[1]);
        ContactRow {
            mode: mode_of(c.mode),
            normal_impulse: f64::from(c.normal_impulse),
            friction_impulse: f64::from(c.friction_impulse),
            along: dx * cos + dy * sin,
        }
    };
    Row {
        t: f64::from(time),
        q: [s[0], s[1], s[2]],
        v: [s[3], s[4], s[5]],
        supports: [[f64::from(fingers[0]), heights[0]], [f64::from(fingers[1]), heights[1]]],
        contacts: [contact(0), contact(1)],
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::panic)]
    use super::*;

    #[test]
    fn telemetry_rows_carry_supports_and_along() {
        let c = ContactTelemetry { mode: Mode::Sticking, normal_impulse: 1e-3, friction_impulse: 0.0 };
        let row = row_of(0.5, [0.1, 0.0025, 0.0, 0.0, 0.0, 0.0], [-0.3, 0.4], [c, c], [0.0, 0.0]);
        assert_eq!(row.supports, [[f64::from(-0.3f32), 0.0], [f64::from(0.4f32), 0.0]]);
        assert!((row.contacts[0].along - (f64::from(-0.3f32) - f64::from(0.1f32))).abs() < 1e-12);
        assert_eq!(row.contacts[1].mode, ContactMode::Sticking);
    }
}
