//! One run of a scene as the host records it, whichever implementation produced it: the
//! trajectory (one [`Row`] per step), the switch events, the outcome, the scene's measured
//! quantities and counters. The core ([`run`] with [`Implementation::Core`]) and the independent
//! reference ([`Implementation::Reference`]) both fill a [`Trajectory`], so everything downstream
//! (CSV, plots, comparison, eq. 21 ratios) has one implementation.

use std::fmt;
use std::io::Write;
use std::path::Path;

use anyhow::Context as _;
use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::planar::{Checksum, ContactMode, Direction, RunStats, StepReport};
use meterstick_core::scene::{Cylinder, Incline, Ladder, MeterStick, Outcome, Painleve, Scene, ThreeFingers};
use serde::Serialize;

use crate::lcp_io::Precision;
use crate::progress;
use crate::reference;
use crate::scenes::{Implementation, LcpSize, SceneKind, SceneSpec, SpecExt as _};

/// One contact after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRow {
    /// Mode after the step.
    pub mode: ContactMode,
    /// Normal impulse (N s).
    pub normal_impulse: f64,
    /// Net friction impulse along the contact's `+d` (N s).
    pub friction_impulse: f64,
    /// The contact's coordinate along its tangent at the step's start (m).
    pub along: f64,
}

/// The state after one step, with `K` contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row<const K: usize = 2> {
    /// Time at the end of the step (s).
    pub t: f64,
    /// Centre of mass `x`, `y` (m) and angle `theta` (rad).
    pub q: [f64; 3],
    /// `vx`, `vy` (m/s), `omega` (rad/s).
    pub v: [f64; 3],
    /// Where each support touches: a finger tip, or the foot of the body's contact point on a
    /// support line (m).
    pub supports: [[f64; 2]; K],
    /// Each contact.
    pub contacts: [ContactRow; K],
}

/// A change of one contact's mode (of `K`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event<const K: usize = 2> {
    /// Time at the end of the step after which the new mode was found (s).
    pub t: f64,
    /// The contact, 0-based.
    pub contact: usize,
    /// The new mode.
    pub mode: ContactMode,
    /// Every contact's coordinate along it at that step's start (m).
    pub along: [f64; K],
    /// Where the supports touch at the end of that step (m).
    pub supports: [[f64; 2]; K],
}

/// How a run ended, by class: the core's one list of outcomes.
pub use meterstick_core::scene::OutcomeKind as OutcomeClass;

/// How a run ended: its class, and for a failure why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct RunOutcome {
    /// The class.
    pub class: OutcomeClass,
    /// Why it failed (`None` unless [`OutcomeClass::Failed`]).
    pub detail: Option<String>,
}

impl RunOutcome {
    /// A physical outcome.
    #[must_use]
    pub const fn of(class: OutcomeClass) -> Self {
        Self { class, detail: None }
    }
}

impl fmt::Display for RunOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.detail {
            Some(why) => write!(f, "{} ({why})", self.class),
            None => write!(f, "{}", self.class),
        }
    }
}

impl From<Outcome> for RunOutcome {
    fn from(o: Outcome) -> Self {
        match o {
            Outcome::Failed(e) => Self { class: OutcomeClass::Failed, detail: Some(e.to_string()) },
            other => Self::of(other.kind()),
        }
    }
}

/// The meter stick's meeting.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Meeting {
    /// When the fingers stopped (s).
    pub time_s: f64,
    /// Centre of mass from the fingers' midpoint, along the rod (m).
    pub com_offset_m: f64,
}

/// The scene's measured quantities (`docs/scenes.md`, "Measured").
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Measured {
    /// Meter stick: the meeting.
    pub meeting: Option<Meeting>,
    /// Incline: the acceleration down the slope while sliding; cylinder: after the first step
    /// (m/s^2).
    pub acceleration_m_s2: Option<f64>,
    /// Cylinder: the angular acceleration after the first step, counter-clockwise (rad/s^2; the
    /// reference's, absent from `summary.json` for a run without it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angular_acceleration_rad_s2: Option<f64>,
    /// Ladder: height of the top when it left the wall (m).
    pub wall_release_height_m: Option<f64>,
    /// Ladder: that height over the top's initial height (2/3 when frictionless).
    pub wall_release_ratio: Option<f64>,
    /// Painlevé: the jam step's impulses (absent from `summary.json` for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jam: Option<JamImpulses>,
}

/// The Painlevé rod's jam: the step on which the sliding end stopped.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JamImpulses {
    /// The end of that step (s).
    pub time_s: f64,
    /// Its normal impulse (N s).
    pub normal_impulse_ns: f64,
    /// Its friction impulse along `+x` (N s).
    pub friction_impulse_ns: f64,
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
    /// Steps of a reduced layout that needed the full one (core, 6x6).
    pub reduced_check_fired: u64,
    /// Of those, steps before the fingers met (meter stick).
    pub reduced_check_fired_before_meeting: u64,
    /// Solves answered by the solver's regularised retry (core).
    pub regularized_solves: u64,
    /// Steps whose LCP had solutions with different motions (reference).
    pub ambiguous_steps: u64,
    /// Steps resolved only to more than `ROUND_OFF_LIMIT` of their impulses (core; see
    /// [`meterstick_core::planar::StepReport::round_off_limited`]).
    pub round_off_limited: u64,
    /// Solves per path (core; `docs/formulation.md`, "Solving a step").
    pub paths: Paths,
}

/// Solves per [`meterstick_core::planar::SolvePath`] over a run, and the candidate bases tried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Paths {
    /// `z = 0` (nothing pushes).
    pub free: u64,
    /// The previous step's basis.
    pub warm: u64,
    /// A neighbouring basis.
    pub candidate: u64,
    /// Lemke's method.
    pub lemke: u64,
    /// Candidate bases solved, answered or not.
    pub candidates_tried: u64,
}

impl From<&meterstick_core::planar::PathCounts> for Paths {
    fn from(p: &meterstick_core::planar::PathCounts) -> Self {
        Self {
            free: p.free,
            warm: p.warm,
            candidate: p.candidate,
            lemke: p.lemke,
            candidates_tried: p.candidates_tried,
        }
    }
}

impl fmt::Display for Paths {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "free {}, warm {}, candidate {}, lemke {} ({} candidate bases tried)",
            self.free, self.warm, self.candidate, self.lemke, self.candidates_tried
        )
    }
}

impl SolverCounters {
    /// The warning a run with [`Self::round_off_limited`] steps gets, in the user's flags.
    #[must_use]
    pub fn round_off_warning(&self, steps: u64) -> Option<String> {
        (self.round_off_limited > 0).then(|| {
            format!(
                "warning: {} of {steps} steps resolved their impulses only to more than {:e} of their size \
                 (speed / (g h) too large for this precision: beyond the measured f32 envelope, \
                 `host-sim envelope`); use a larger --h or --precision f64",
                self.round_off_limited,
                meterstick_core::planar::ROUND_OFF_LIMIT
            )
        })
    }
}

impl From<&RunStats> for SolverCounters {
    fn from(s: &RunStats) -> Self {
        Self {
            pivots: s.pivots,
            max_pivots: s.max_pivots,
            warm_starts: s.warm_starts,
            reduced_check_fired: s.reduced_check_fired,
            regularized_solves: s.regularized_solves,
            round_off_limited: s.round_off_limited,
            paths: Paths::from(&s.paths),
            ..Self::default()
        }
    }
}

/// One run of a scene with `K` contacts, recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory<const K: usize = 2> {
    /// Who computed it.
    pub implementation: Implementation,
    /// Which scene.
    pub scene: SceneKind,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time at the end (s).
    pub end_time: f64,
    /// The recorded rows ([`Record`]).
    pub rows: Vec<Row<K>>,
    /// The contacts' modes before the first step.
    pub initial_modes: [ContactMode; K],
    /// Switch events in order.
    pub events: Vec<Event<K>>,
    /// How it ended.
    pub outcome: RunOutcome,
    /// The scene's measured quantities.
    pub measured: Measured,
    /// Solver counters.
    pub counters: SolverCounters,
    /// The core's trajectory checksum ([`meterstick_core::planar::Checksum`]: FNV-1a over the
    /// state's bits after every step, as the firmware and the browser page compute it).
    pub checksum: Option<u32>,
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
pub struct Recorder<const K: usize = 2> {
    mode: Record,
    rows: Vec<Row<K>>,
    last: Option<Row<K>>,
    next: u64,
}

impl<const K: usize> Recorder<K> {
    /// An empty recorder.
    #[must_use]
    pub fn new(mode: Record) -> Self {
        Self { mode, rows: Vec::new(), last: None, next: 0 }
    }

    /// Offers the row of the initial state or of the next step.
    pub fn push(&mut self, row: Row<K>) {
        match self.mode {
            Record::All => self.rows.push(row),
            Record::Nothing => {}
            Record::Grid(dt) => {
                let prev = self.last.unwrap_or(row);
                // A grid time between two rows is interpolated between them (an f32 run's
                // times `k h` carry rounding; a grid time just past this row waits for the next).
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
    pub fn finish(self) -> Vec<Row<K>> {
        self.rows
    }
}

/// The most steps `host-sim run` records: 2 x 10^6. It keeps every step of the core and of the
/// reference in memory (about 700 bytes a step in all) and writes them as CSV, so a run at the
/// general cap ([`crate::scenes::MAX_STEPS`], 10^8) would need about 70 GB; `host-sim scene`
/// runs up to that cap without recording.
pub const MAX_RECORDED_STEPS: f64 = 2e6;

/// Refuses a run that would record more than [`MAX_RECORDED_STEPS`] steps, in the user's words.
///
/// # Errors
/// The step count `--h` and `--duration` imply is above the cap.
pub fn check_recorded_steps(spec: &SceneSpec) -> anyhow::Result<()> {
    let steps = (spec.max_time() / spec.step()).ceil();
    anyhow::ensure!(
        steps <= MAX_RECORDED_STEPS,
        "--h {} s and --duration {} s imply {steps:.3e} steps; host-sim run records every step (about \
         700 bytes each) and takes at most {MAX_RECORDED_STEPS:e} (raise --h or lower --duration; \
         host-sim scene runs up to {:e} steps without recording)",
        crate::scenes::short_number(spec.step()),
        crate::scenes::short_number(spec.max_time()),
        crate::scenes::MAX_STEPS
    );
    Ok(())
}

/// Runs `spec` (a scene with two contacts) in `implementation` to its outcome and records it.
///
/// # Errors
/// Invalid parameters, or a scene without two contacts ([`run_k`]).
pub fn run(spec: &SceneSpec, implementation: Implementation, record: Record) -> anyhow::Result<Trajectory> {
    run_inner(spec, implementation, record, None)
}

/// Calls `$body` with the const `$k` set to the number of contacts of scene `$kind` (1, 2 or 3):
/// the commands that record a scene are generic over its contacts.
#[macro_export]
macro_rules! with_contacts {
    ($kind:expr, $k:ident => $body:expr) => {
        match $kind.info().contacts {
            1 => {
                const $k: usize = 1;
                $body
            }
            3 => {
                const $k: usize = 3;
                $body
            }
            _ => {
                const $k: usize = 2;
                $body
            }
        }
    };
}

/// Runs `spec`, a scene with `K` contacts, in `implementation` to its outcome and records it.
///
/// # Errors
/// Invalid parameters, or a scene with other than `K` contacts.
pub fn run_k<const K: usize>(
    spec: &SceneSpec,
    implementation: Implementation,
    record: Record,
) -> anyhow::Result<Trajectory<K>> {
    run_inner(spec, implementation, record, None)
}

/// As [`run`], counting the core's steps on `bar` (the reference's are not counted).
///
/// # Errors
/// As [`run`].
pub fn run_watched<const K: usize>(
    spec: &SceneSpec,
    implementation: Implementation,
    record: Record,
    bar: &ProgressBar,
) -> anyhow::Result<Trajectory<K>> {
    run_inner(spec, implementation, record, Some(bar))
}

/// Every run checks for Ctrl-C ([`crate::progress`]) before it starts and every
/// [`progress::CHECK_EVERY_STEPS`] steps; an interrupted run is dropped.
fn run_inner<const K: usize>(
    spec: &SceneSpec,
    implementation: Implementation,
    record: Record,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<Trajectory<K>> {
    let contacts = spec.kind().info().contacts;
    anyhow::ensure!(contacts == K, "scene {} has {contacts} contacts, not {K}", spec.kind());
    progress::check()?;
    let t = match implementation {
        Implementation::Reference => run_reference(spec, record),
        Implementation::Core(Precision::F32, LcpSize::Reduced) => core_run::<f32, 6, K>(spec, record, bar),
        Implementation::Core(Precision::F32, LcpSize::Full) => core_run::<f32, 8, K>(spec, record, bar),
        Implementation::Core(Precision::F64, LcpSize::Reduced) => core_run::<f64, 6, K>(spec, record, bar),
        Implementation::Core(Precision::F64, LcpSize::Full) => core_run::<f64, 8, K>(spec, record, bar),
    }?;
    progress::check()?;
    Ok(t)
}

fn invalid(e: meterstick_core::ParamError) -> anyhow::Error {
    anyhow::anyhow!("invalid scene: {e}")
}

/// Runs the core scene (scalar `T`, LCP size `N`) to its outcome and records it.
///
/// # Errors
/// Invalid parameters.
pub fn run_core<T: Real, const N: usize>(spec: &SceneSpec, record: Record) -> anyhow::Result<Trajectory> {
    let t = run_inner_core::<T, N, 2>(spec, record)?;
    progress::check()?;
    Ok(t)
}

fn run_inner_core<T: Real, const N: usize, const K: usize>(
    spec: &SceneSpec,
    record: Record,
) -> anyhow::Result<Trajectory<K>> {
    let contacts = spec.kind().info().contacts;
    anyhow::ensure!(contacts == K, "scene {} has {contacts} contacts, not {K}", spec.kind());
    core_run::<T, N, K>(spec, record, None)
}

/// The core's run of `spec` (its contacts are `K`: checked by the callers). `N` is the LCP size of
/// a two-contact scene (6 reduced, 8 full); other scenes run their own reduced or full layout
/// (three fingers 9 or 12, the cylinder 3 or 4).
fn core_run<T: Real, const N: usize, const K: usize>(
    spec: &SceneSpec,
    record: Record,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<Trajectory<K>> {
    let implementation =
        Implementation::Core(if T::NAME == "f32" { Precision::F32 } else { Precision::F64 }, size_of(N));
    Ok(match *spec {
        SceneSpec::MeterStick(p) => {
            let mut s = MeterStick::<T, N, 0>::new(p.cast()).map_err(invalid)?;
            let mut t = drive::<T, _, 2, K>(&mut s, implementation, SceneKind::MeterStick, record, bar);
            t.measured.meeting =
                s.meeting().map(|m| Meeting { time_s: m.time.as_f64(), com_offset_m: m.com_offset.as_f64() });
            t.counters.reduced_check_fired_before_meeting = s.reduced_check_fired_before_meeting();
            t
        }
        SceneSpec::Incline(p) => {
            let mut s = Incline::<T, N, 0>::new(p.cast()).map_err(invalid)?;
            let mut t = drive::<T, _, 2, K>(&mut s, implementation, SceneKind::Incline, record, bar);
            t.measured.acceleration_m_s2 = s.acceleration().map(Real::as_f64);
            t
        }
        SceneSpec::Ladder(p) => {
            let mut s = Ladder::<T, N, 0>::new(p.cast()).map_err(invalid)?;
            let mut t = drive::<T, _, 2, K>(&mut s, implementation, SceneKind::Ladder, record, bar);
            let height = s.wall_release_height().map(Real::as_f64);
            t.measured.wall_release_height_m = height;
            t.measured.wall_release_ratio = height.map(|h| h / s.start_top_height().as_f64());
            t
        }
        SceneSpec::ThreeFingers(p) => {
            let kind = SceneKind::ThreeFingers;
            if N == 6 {
                let mut s = ThreeFingers::<T, 9, 0>::new(p.cast()).map_err(invalid)?;
                drive::<T, _, 3, K>(&mut s, implementation, kind, record, bar)
            } else {
                let mut s = ThreeFingers::<T, 12, 0>::new(p.cast()).map_err(invalid)?;
                drive::<T, _, 3, K>(&mut s, implementation, kind, record, bar)
            }
        }
        SceneSpec::Cylinder(p) => {
            let kind = SceneKind::Cylinder;
            let (mut t, a) = if N == 6 {
                let mut s = Cylinder::<T, 3, 0>::new(p.cast()).map_err(invalid)?;
                (drive::<T, _, 1, K>(&mut s, implementation, kind, record, bar), s.acceleration())
            } else {
                let mut s = Cylinder::<T, 4, 0>::new(p.cast()).map_err(invalid)?;
                (drive::<T, _, 1, K>(&mut s, implementation, kind, record, bar), s.acceleration())
            };
            t.measured.acceleration_m_s2 = a.map(Real::as_f64);
            t
        }
        SceneSpec::Painleve(p) => {
            let kind = SceneKind::Painleve;
            let (mut t, jam) = if N == 6 {
                let mut s = Painleve::<T, 3, 0>::new(p.cast()).map_err(invalid)?;
                (drive::<T, _, 1, K>(&mut s, implementation, kind, record, bar), s.jam())
            } else {
                let mut s = Painleve::<T, 4, 0>::new(p.cast()).map_err(invalid)?;
                (drive::<T, _, 1, K>(&mut s, implementation, kind, record, bar), s.jam())
            };
            t.measured.jam = jam.map(|j| JamImpulses {
                time_s: j.time.as_f64(),
                normal_impulse_ns: j.normal_impulse.as_f64(),
                friction_impulse_ns: j.friction_impulse.as_f64(),
            });
            t
        }
    })
}

fn size_of(n: usize) -> LcpSize {
    if n == 6 { LcpSize::Reduced } else { LcpSize::Full }
}

/// Where each support touches the body: the contact point `com + r` moved back by the gap along
/// the normal (a finger's tip; the foot of a corner on a line).
fn touch_points<T: Real, S: Scene<T, KS>, const KS: usize, const K: usize>(scene: &S) -> [[f64; 2]; K] {
    let s = scene.state();
    let mut out = [[0.0; 2]; K];
    for (o, f) in out.iter_mut().zip(scene.frames()) {
        let (r, n, gap) = (f.r.map(Real::as_f64), f.normal().map(Real::as_f64), f.gap.as_f64());
        *o = [s.x.as_f64() + r[0] - gap * n[0], s.y.as_f64() + r[1] - gap * n[1]];
    }
    out
}

/// Steps `scene` (`KS` contacts) to its outcome, recording rows and events with `K` contacts
/// (`K = KS`, checked before the run starts; the rows are written once, in place).
fn drive<T: Real, S: Scene<T, KS>, const KS: usize, const K: usize>(
    scene: &mut S,
    implementation: Implementation,
    kind: SceneKind,
    record: Record,
    bar: Option<&ProgressBar>,
) -> Trajectory<K> {
    let modes = scene.modes();
    let initial_modes: [ContactMode; K] =
        core::array::from_fn(|i| modes.get(i).copied().unwrap_or(ContactMode::Separated));
    let mut rows = Recorder::new(record);
    let s = *scene.state();
    let contact0 =
        ContactRow { mode: ContactMode::Separated, normal_impulse: 0.0, friction_impulse: 0.0, along: 0.0 };
    let mut first = Row {
        t: 0.0,
        q: [s.x, s.y, s.theta].map(Real::as_f64),
        v: s.velocity().map(Real::as_f64),
        supports: touch_points(scene),
        contacts: [contact0; K],
    };
    for (c, m) in first.contacts.iter_mut().zip(initial_modes) {
        c.mode = m;
    }
    rows.push(first);
    let mut events = Vec::new();
    let mut checksum = Checksum::new();
    let mut steps = 0_u64;
    while let Some(r) = scene.step() {
        steps += 1;
        if steps.is_multiple_of(progress::CHECK_EVERY_STEPS) {
            if let Some(bar) = bar {
                bar.inc(progress::CHECK_EVERY_STEPS);
            }
            if progress::interrupted() {
                break;
            }
        }
        checksum.add(&r.state);
        let supports = touch_points(scene);
        let row = row_of::<T, KS, K>(&r, supports);
        for (i, mode) in r.switches() {
            events.push(Event { t: row.t, contact: i, mode, along: row.contacts.map(|c| c.along), supports });
        }
        rows.push(row);
    }
    let mut counters = SolverCounters::from(scene.stats());
    counters.reduced_check_fired_before_meeting = 0;
    Trajectory {
        implementation,
        scene: kind,
        steps: scene.stats().steps,
        end_time: scene.time().as_f64(),
        rows: rows.finish(),
        initial_modes,
        events,
        outcome: scene.outcome().unwrap_or(Outcome::Unfinished).into(),
        measured: Measured::default(),
        counters,
        checksum: Some(checksum.value()),
    }
}

fn row_of<T: Real, const KS: usize, const K: usize>(
    r: &StepReport<T, KS>,
    supports: [[f64; 2]; K],
) -> Row<K> {
    let s = &r.state;
    Row {
        t: r.time.as_f64(),
        q: [s.x, s.y, s.theta].map(Real::as_f64),
        v: s.velocity().map(Real::as_f64),
        supports,
        contacts: core::array::from_fn(|i| {
            r.contacts.get(i).map_or(
                ContactRow {
                    mode: ContactMode::Separated,
                    normal_impulse: 0.0,
                    friction_impulse: 0.0,
                    along: 0.0,
                },
                |c| ContactRow {
                    mode: c.mode,
                    normal_impulse: c.normal_impulse.as_f64(),
                    friction_impulse: c.friction_impulse.as_f64(),
                    along: c.along.as_f64(),
                },
            )
        }),
    }
}

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
pub fn run_reference<const K: usize>(spec: &SceneSpec, record: Record) -> anyhow::Result<Trajectory<K>> {
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
        reference::Outcome::Balanced => RunOutcome::of(OutcomeClass::Balanced),
        reference::Outcome::Fell => RunOutcome::of(OutcomeClass::Fell),
        reference::Outcome::Held => RunOutcome::of(OutcomeClass::Held),
        reference::Outcome::Slid => RunOutcome::of(OutcomeClass::Slid),
        reference::Outcome::Tipped => RunOutcome::of(OutcomeClass::Tipped),
        reference::Outcome::Rolled => RunOutcome::of(OutcomeClass::Rolled),
        reference::Outcome::Jammed => RunOutcome::of(OutcomeClass::Jammed),
        reference::Outcome::Unfinished => RunOutcome::of(OutcomeClass::Unfinished),
        reference::Outcome::Failed(why) => {
            RunOutcome { class: OutcomeClass::Failed, detail: Some(why.clone()) }
        }
    };
    let start_top = match spec {
        SceneSpec::Ladder(p) => p.length * p.angle.sin(),
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
                normal_impulse_ns: j.normal_impulse,
                friction_impulse_ns: j.friction_impulse,
            }),
        },
        counters: SolverCounters { ambiguous_steps: run.ambiguous_steps, ..SolverCounters::default() },
        checksum: None,
    })
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

/// The eq. 21 switches of a run: a contact that was sticking starts to slide while the other was
/// sliding before that step (modes before a step: the run's initial modes, then its events), and
/// strictly before the fingers stopped: a change at or after the stop is caused by the stop (the
/// moving finger halts under a rod that slides on), not by eq. 21's force balance (at 0.01 m/s
/// such a change had "ratio" 1.30 and dominated the summary's worst error). The stop is an event of
/// its own kind in the events CSV.
#[must_use]
pub fn switches<const K: usize>(run: &Trajectory<K>) -> Vec<Switch> {
    if K != 2 {
        return Vec::new(); // eq. 21 is a relation between two fingers
    }
    let stop = run.measured.meeting.map(|m| m.time_s);
    let mut mode = run.initial_modes;
    let mut before = mode;
    let mut step_time = None;
    let mut out = Vec::new();
    for e in &run.events {
        if step_time != Some(e.t.to_bits()) {
            step_time = Some(e.t.to_bits());
            before = mode;
        }
        let i = e.contact;
        if i >= K {
            continue;
        }
        let before_stop = stop.is_none_or(|s| e.t < s);
        if before_stop
            && before[i] == ContactMode::Sticking
            && e.mode.is_sliding()
            && before[1 - i].is_sliding()
        {
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

/// Largest `|a - b|` of the centre of mass (m) and of the angle (rad) over the steps both runs
/// have (same `h`: row `k` is time `k h` in both).
#[must_use]
pub fn max_deviation<const K: usize>(a: &Trajectory<K>, b: &Trajectory<K>) -> (f64, f64) {
    let mut com: f64 = 0.0;
    let mut angle: f64 = 0.0;
    for (ra, rb) in a.rows.iter().zip(&b.rows) {
        com = com.max((ra.q[0] - rb.q[0]).hypot(ra.q[1] - rb.q[1]));
        angle = angle.max((ra.q[2] - rb.q[2]).abs());
    }
    (com, angle)
}

/// Writes a CSV file: the header line, then one line per item.
///
/// # Errors
/// I/O, naming the file.
pub fn write_lines<I: IntoIterator<Item = String>>(
    path: &Path,
    header: &str,
    lines: I,
) -> anyhow::Result<()> {
    let mut w = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?,
    );
    let write = || -> std::io::Result<()> {
        writeln!(w, "{header}")?;
        for line in lines {
            writeln!(w, "{line}")?;
        }
        w.flush()
    };
    write().with_context(|| format!("writing {}", path.display()))
}

/// The trajectory CSV's header for `k` contacts: `t,x,y,theta,vx,vy,omega`, then each contact's
/// `support<i>_x,support<i>_y`, `mode<i>`, `pn<i>`, `pf<i>`, `along<i>` (each group over the
/// contacts; two contacts: `...,support2_y,mode1,mode2,pn1,pn2,pf1,pf2,along1,along2`).
#[must_use]
pub fn csv_header(k: usize) -> String {
    use std::fmt::Write as _;
    let mut h = String::from("t,x,y,theta,vx,vy,omega");
    for i in 1..=k {
        let _ = write!(h, ",support{i}_x,support{i}_y");
    }
    for group in ["mode", "pn", "pf", "along"] {
        for i in 1..=k {
            let _ = write!(h, ",{group}{i}");
        }
    }
    h
}

/// Writes the trajectory CSV ([`csv_header`]; SI units, impulses in N s).
///
/// # Errors
/// I/O, naming the file.
pub fn write_csv<const K: usize>(traj: &Trajectory<K>, path: &Path) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let lines = traj.rows.iter().map(|r| {
        let mut line = format!("{},{},{},{},{},{},{}", r.t, r.q[0], r.q[1], r.q[2], r.v[0], r.v[1], r.v[2]);
        for s in &r.supports {
            let _ = write!(line, ",{},{}", s[0], s[1]);
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.mode.name());
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.normal_impulse);
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.friction_impulse);
        }
        for c in &r.contacts {
            let _ = write!(line, ",{}", c.along);
        }
        line
    });
    write_lines(path, &csv_header(K), lines)
}

/// Writes the events CSV: `t,kind,contact,mode,along1,...,along<K>`, one row per mode switch
/// (`kind` `switch`, contact 1 to K) and, for the meter stick, one for the fingers' stop (`kind`
/// `stop`, contact and mode empty), in time order.
///
/// # Errors
/// I/O, naming the file.
pub fn write_events_csv<const K: usize>(traj: &Trajectory<K>, path: &Path) -> anyhow::Result<()> {
    let mut lines: Vec<(f64, String)> = traj
        .events
        .iter()
        .map(|e| {
            let along: Vec<String> = e.along.iter().map(f64::to_string).collect();
            (e.t, format!("{},switch,{},{},{}", e.t, e.contact + 1, e.mode.name(), along.join(",")))
        })
        .collect();
    if let Some(m) = traj.measured.meeting {
        // After the switches of the stopping step: they were found on it.
        let at = lines.partition_point(|(t, _)| *t <= m.time_s);
        lines.insert(at, (m.time_s, format!("{},stop,,{}", m.time_s, ",".repeat(K))));
    }
    let header: Vec<String> = (1..=K).map(|i| format!("along{i}")).collect();
    write_lines(path, &format!("t,kind,contact,mode,{}", header.join(",")), lines.into_iter().map(|(_, l)| l))
}

#[cfg(test)]
mod tests {
    use super::csv_header;

    /// Two contacts give the columns `core.csv` always had (README, "The main job").
    #[test]
    fn the_header_of_two_contacts_is_the_old_one() {
        assert_eq!(
            csv_header(2),
            "t,x,y,theta,vx,vy,omega,support1_x,support1_y,support2_x,support2_y,\
             mode1,mode2,pn1,pn2,pf1,pf2,along1,along2"
        );
        assert!(csv_header(3).ends_with(
            "support3_x,support3_y,mode1,mode2,mode3,pn1,pn2,pn3,pf1,pf2,pf3,along1,along2,along3"
        ));
    }
}
