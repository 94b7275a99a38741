//! One run of a scene as the host records it, whichever implementation produced it: the
//! trajectory (one [`Row`] per step), the switch events, the outcome and counters. The core
//! ([`run_core`]) and the f64 reference ([`crate::reference`]) both fill a [`Trajectory`], so
//! everything downstream (CSV, plots, comparison, eq. 21 ratios) has one implementation.

use std::fmt;
use std::io::Write;
use std::path::Path;

use anyhow::Context as _;
use meterstick_core::Real;
use meterstick_core::scene::{ContactMode, Outcome, RunStats, Scene, SceneParams};
use serde::Serialize;

/// The state after one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Time at the end of the step (s).
    pub t: f64,
    /// Centre of mass `x`, `y` (m) and angle `theta` (rad).
    pub q: [f64; 3],
    /// Finger tip `x` positions (m).
    pub fingers: [f64; 2],
    /// Each finger's signed distance from the centre of mass along the rod, at the start of
    /// the step (m).
    pub along: [f64; 2],
    /// Each finger's mode after the step.
    pub modes: [ContactMode; 2],
    /// Normal impulses (N s).
    pub normal_impulse: [f64; 2],
    /// Net friction impulses along the rod's `+x` (N s).
    pub friction_impulse: [f64; 2],
}

/// A change of one finger's mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// Time at the end of the step where the new mode was found (s).
    pub t: f64,
    /// 0 (moving finger) or 1 (fixed finger).
    pub finger: usize,
    /// The new mode.
    pub mode: ContactMode,
    /// Both fingers' signed distances from the centre of mass along the rod (m).
    pub along: [f64; 2],
    /// Both fingers' world `x` positions at the end of that step (m).
    pub fingers: [f64; 2],
}

/// How a run ended, for any implementation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RunOutcome {
    /// See [`Outcome::Balanced`].
    Balanced,
    /// See [`Outcome::Fell`].
    Fell,
    /// `max_time` passed.
    Unfinished,
    /// The implementation could not continue (solver error, non-finite state): why.
    Failed(String),
}

impl RunOutcome {
    /// `Balanced`, `Fell`, `Unfinished` or `Failed`.
    #[must_use]
    pub fn class(&self) -> &'static str {
        match self {
            Self::Balanced => "Balanced",
            Self::Fell => "Fell",
            Self::Unfinished => "Unfinished",
            Self::Failed(_) => "Failed",
        }
    }
}

impl fmt::Display for RunOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Failed(why) => write!(f, "Failed({why})"),
            other => f.write_str(other.class()),
        }
    }
}

impl From<Outcome> for RunOutcome {
    fn from(o: Outcome) -> Self {
        match o {
            Outcome::Balanced => Self::Balanced,
            Outcome::Fell => Self::Fell,
            Outcome::Unfinished => Self::Unfinished,
            Outcome::NonFinite => Self::Failed("non-finite state".into()),
            Outcome::SolverFailed(e) => Self::Failed(format!("solver: {e}")),
            Outcome::ReducedModelLeftRange => Self::Failed("the 6x6 model left its range".into()),
        }
    }
}

/// Solver counters of a run (zero where an implementation has no such thing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct SolverCounters {
    /// Lemke pivots in all (core).
    pub pivots: u64,
    /// Most pivots in one step (core).
    pub max_pivots: u32,
    /// Steps answered by the warm-start basis (core).
    pub warm_starts: u64,
    /// 6x6 check firings, and those before the fingers met (core, 6x6).
    pub reduced_check_fired: u64,
    /// See [`RunStats::reduced_check_fired_before_meeting`].
    pub reduced_check_fired_before_meeting: u64,
    /// Steps whose LCP had solutions with different rod velocities (reference).
    pub ambiguous_steps: u64,
}

impl From<&RunStats> for SolverCounters {
    fn from(s: &RunStats) -> Self {
        Self {
            pivots: s.pivots,
            max_pivots: s.max_pivots,
            warm_starts: s.warm_starts,
            reduced_check_fired: s.reduced_check_fired,
            reduced_check_fired_before_meeting: s.reduced_check_fired_before_meeting,
            ambiguous_steps: 0,
        }
    }
}

/// One run, recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Which implementation: e.g. `core f32 6x6`, `reference f64 8x8`.
    pub label: String,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time at the end (s).
    pub end_time: f64,
    /// The recorded rows ([`Record`]).
    pub rows: Vec<Row>,
    /// Both fingers' modes before the first step.
    pub initial_modes: [ContactMode; 2],
    /// Switch events in order.
    pub events: Vec<Event>,
    /// How it ended.
    pub outcome: RunOutcome,
    /// `(time, COM offset from the fingers' midpoint)` when the fingers met.
    pub meeting: Option<(f64, f64)>,
    /// Solver counters.
    pub counters: SolverCounters,
}

/// Which rows a run keeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Record {
    /// The initial state and every step.
    All,
    /// Rows at times `k dt` only (`k = 0, 1, ...`), the position linearly interpolated between
    /// the steps around each (for comparing runs with different `h` without keeping every step).
    Grid(f64),
    /// No rows.
    Nothing,
}

/// Keeps the rows a [`Record`] asks for.
#[derive(Debug)]
pub struct Recorder {
    mode: Record,
    rows: Vec<Row>,
    last: Option<Row>,
    next: u64,
}

impl Recorder {
    /// An empty recorder.
    #[must_use]
    pub fn new(mode: Record) -> Self {
        Self { mode, rows: Vec::new(), last: None, next: 0 }
    }

    /// Offers the row of the initial state or of the next step.
    pub fn push(&mut self, row: Row) {
        match self.mode {
            Record::All => self.rows.push(row),
            Record::Nothing => {}
            Record::Grid(dt) => {
                let prev = self.last.unwrap_or(row);
                while (self.next as f64) * dt <= row.t + 1e-9 * dt {
                    let tk = self.next as f64 * dt;
                    let a =
                        if row.t > prev.t { ((tk - prev.t) / (row.t - prev.t)).clamp(0.0, 1.0) } else { 1.0 };
                    let mut q = row.q;
                    for d in 0..3 {
                        q[d] = prev.q[d] + a * (row.q[d] - prev.q[d]);
                    }
                    self.rows.push(Row { t: tk, q, ..row });
                    self.next += 1;
                }
                self.last = Some(row);
            }
        }
    }

    /// The rows kept.
    #[must_use]
    pub fn finish(self) -> Vec<Row> {
        self.rows
    }
}

/// The events buffer of the core runs made here (the summary reports any overflow).
pub const CORE_EVENTS: usize = 1024;

/// Runs the core scene (scalar `T`, LCP size `N`) to its outcome and records it.
///
/// # Errors
/// Invalid parameters.
pub fn run_core<T: Real, const N: usize>(
    params: &SceneParams<f64>,
    record: Record,
) -> anyhow::Result<Trajectory> {
    let p = convert(params);
    let mut scene = Scene::<T, N, CORE_EVENTS>::new(p).map_err(|e| anyhow::anyhow!("invalid scene: {e}"))?;
    let s = scene.state();
    let f = scene.fingers();
    let initial_modes = scene.modes();
    let mut rows = Recorder::new(record);
    rows.push(Row {
        t: 0.0,
        q: [s.x.as_f64(), s.y.as_f64(), s.theta.as_f64()],
        fingers: [f[0].as_f64(), f[1].as_f64()],
        along: [f[0].as_f64() - s.x.as_f64(), f[1].as_f64() - s.x.as_f64()],
        modes: scene.modes(),
        normal_impulse: [0.0; 2],
        friction_impulse: [0.0; 2],
    });
    let mut events = Vec::new();
    while let Some(r) = scene.step() {
        let fingers = [r.fingers[0].as_f64(), r.fingers[1].as_f64()];
        for e in &scene.events()[events.len()..] {
            events.push(Event {
                t: e.time.as_f64(),
                finger: usize::from(e.finger),
                mode: e.mode,
                along: [e.along[0].as_f64(), e.along[1].as_f64()],
                fingers,
            });
        }
        if r.error.is_some() {
            break;
        }
        rows.push(Row {
            t: r.time.as_f64(),
            q: [r.state.x.as_f64(), r.state.y.as_f64(), r.state.theta.as_f64()],
            fingers,
            along: [r.along[0].as_f64(), r.along[1].as_f64()],
            modes: r.modes,
            normal_impulse: [r.normal_impulse[0].as_f64(), r.normal_impulse[1].as_f64()],
            friction_impulse: [r.friction_impulse[0].as_f64(), r.friction_impulse[1].as_f64()],
        });
    }
    Ok(Trajectory {
        label: format!("core {} {N}x{N}", T::NAME),
        steps: scene.stats().steps,
        end_time: scene.time().as_f64(),
        rows: rows.finish(),
        initial_modes,
        events,
        outcome: scene.outcome().unwrap_or(Outcome::Unfinished).into(),
        meeting: scene.meeting().map(|m| (m.time.as_f64(), m.com_offset.as_f64())),
        counters: scene.stats().into(),
    })
}

/// The parameters in scalar `T`.
#[must_use]
pub fn convert<T: Real>(p: &SceneParams<f64>) -> SceneParams<T> {
    SceneParams {
        rod_length: T::of(p.rod_length),
        rod_thickness: T::of(p.rod_thickness),
        rod_mass: T::of(p.rod_mass),
        gravity: T::of(p.gravity),
        finger1_x: T::of(p.finger1_x),
        finger2_x: T::of(p.finger2_x),
        finger_width: T::of(p.finger_width),
        finger_speed: T::of(p.finger_speed),
        mu_static: T::of(p.mu_static),
        mu_kinetic: T::of(p.mu_kinetic),
        step: T::of(p.step),
        stick_speed: T::of(p.stick_speed),
        tilt_limit: T::of(p.tilt_limit),
        drop_limit: T::of(p.drop_limit),
        hold_time: T::of(p.hold_time),
        max_time: T::of(p.max_time),
    }
}

/// One eq. 21 switch: a sticking finger starts to slide while the other slides.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Switch {
    /// Time (s).
    pub t: f64,
    /// The finger that starts to slide (1 or 2).
    pub finger: usize,
    /// Its distance from the centre of mass (m).
    pub x_start: f64,
    /// The other (sliding) finger's distance (m).
    pub x_stop: f64,
    /// `x_stop / x_start`, to compare with `mu_k / mu_s` (eq. 21).
    pub ratio: f64,
}

/// The eq. 21 switches of a run: a finger that was sticking starts to slide while the other
/// finger was sliding before that step (modes before a step: the run's initial modes, then
/// its events).
#[must_use]
pub fn switches(run: &Trajectory) -> Vec<Switch> {
    let mut mode = run.initial_modes;
    let mut before = mode;
    let mut step_time = None;
    let mut out = Vec::new();
    for e in &run.events {
        if step_time != Some(e.t.to_bits()) {
            step_time = Some(e.t.to_bits());
            before = mode;
        }
        let i = e.finger;
        if before[i] == ContactMode::Sticking && e.mode.is_sliding() && before[1 - i].is_sliding() {
            out.push(Switch {
                t: e.t,
                finger: i + 1,
                x_start: e.along[i].abs(),
                x_stop: e.along[1 - i].abs(),
                ratio: (e.along[1 - i] / e.along[i]).abs(),
            });
        }
        mode[i] = e.mode;
    }
    out
}

/// Largest `|a - b|` of the COM position (m) and of the angle (rad) over the steps both runs
/// have (same `h`: row `k` is time `k h` in both).
#[must_use]
pub fn max_deviation(a: &Trajectory, b: &Trajectory) -> (f64, f64) {
    let mut com: f64 = 0.0;
    let mut angle: f64 = 0.0;
    for (ra, rb) in a.rows.iter().zip(&b.rows) {
        com = com.max((ra.q[0] - rb.q[0]).hypot(ra.q[1] - rb.q[1]));
        angle = angle.max((ra.q[2] - rb.q[2]).abs());
    }
    (com, angle)
}

/// Writes a CSV file: the header line, then one line per item.
fn write_lines<I: IntoIterator<Item = String>>(path: &Path, header: &str, lines: I) -> anyhow::Result<()> {
    let mut w = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?,
    );
    writeln!(w, "{header}")?;
    for line in lines {
        writeln!(w, "{line}")?;
    }
    w.flush().with_context(|| format!("writing {}", path.display()))
}

/// Writes the trajectory CSV: `t,x,y,theta,finger1,finger2,mode1,mode2,pn1,pn2,pf1,pf2`.
///
/// # Errors
/// I/O.
pub fn write_csv(traj: &Trajectory, path: &Path) -> anyhow::Result<()> {
    let lines = traj.rows.iter().map(|r| {
        format!(
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            r.t,
            r.q[0],
            r.q[1],
            r.q[2],
            r.fingers[0],
            r.fingers[1],
            r.modes[0].name(),
            r.modes[1].name(),
            r.normal_impulse[0],
            r.normal_impulse[1],
            r.friction_impulse[0],
            r.friction_impulse[1]
        )
    });
    write_lines(path, "t,x,y,theta,finger1,finger2,mode1,mode2,pn1,pn2,pf1,pf2", lines)
}

/// Writes the events CSV: `t,finger,mode,x1_from_com,x2_from_com,finger1,finger2`.
///
/// # Errors
/// I/O.
pub fn write_events_csv(traj: &Trajectory, path: &Path) -> anyhow::Result<()> {
    let lines = traj.events.iter().map(|e| {
        format!(
            "{},{},{},{},{},{},{}",
            e.t,
            e.finger + 1,
            e.mode.name(),
            e.along[0],
            e.along[1],
            e.fingers[0],
            e.fingers[1]
        )
    });
    write_lines(path, "t,finger,mode,x1_from_com,x2_from_com,finger1,finger2", lines)
}
