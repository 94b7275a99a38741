//! One run of a scene in the core, as the page drives it: [`Sim`] holds any scene of the catalogue
//! in the precision and layout asked for (the core's `AnyScene`), steps it, writes one row of numbers per step for the
//! animation and the plots (the columns of `host-sim run`'s `core.csv` for the scene's `K`
//! contacts, [`row_len`], so a live run and a replayed one are read alike), and keeps the
//! trajectory checksum (`planar::Checksum`, as the firmware and `host-sim scene` print it).

// A module built with some of the scene features leaves the others' helpers unused.
#![cfg_attr(
    not(all(feature = "k1", feature = "k2", feature = "k3", feature = "mb")),
    allow(dead_code, unused_imports, unused_mut, unused_variables)
)]

use meterstick_core::ParamError;
use meterstick_core::Real;
#[cfg(feature = "mb")]
use meterstick_core::multibody::scenes::MultibodyScene;
use meterstick_core::planar::{Checksum, ContactMode, Direction, RunStats, StepReport};
#[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
use meterstick_core::scene::AnyScene;
#[cfg(feature = "mb")]
use meterstick_core::scene::{AnyMultibody, MultibodyVisitor};
use meterstick_core::scene::{Outcome, OutcomeKind, Scene, SceneKind, SceneVisitor};

use crate::config::{LcpLayout, Precision, SceneParams, holds};

/// The most contacts a scene of the catalogue has (three fingers).
pub const MAX_CONTACTS: usize = 3;

/// Numbers per row for `k` contacts: time, the body's `x, y, theta, vx, vy, omega`, then each
/// contact's support point (x, y), and each contact's mode, normal impulse, friction impulse and
/// coordinate along it, in groups (`host-sim`'s `csv_header(k)`).
#[must_use]
pub const fn row_len(k: usize) -> usize {
    7 + 6 * k
}

/// The most bodies a scene of several bodies has (the stack of three; the core's `MAX_BODIES`).
pub const MAX_BODIES: usize = 3;

/// Numbers per row of a scene of several bodies: time, then each body's `x, y, theta` (body 0 the
/// lowest; NaN for a body the scene does not have), as `host-sim`'s trajectory of bodies.
pub const BODIES_ROW: usize = 1 + 3 * MAX_BODIES;

/// The longest row (a scene with [`MAX_CONTACTS`]).
pub const MAX_ROW: usize = row_len(MAX_CONTACTS);
const _: () = assert!(BODIES_ROW <= MAX_ROW);

/// The modes by code ([`mode_code`]), as `core.csv` spells them.
pub const MODES: [&str; 4] = ["separated", "sticking", "sliding+", "sliding-"];

/// The outcomes by code ([`outcome_code`]): the core's one list ([`OutcomeKind`]).
pub const OUTCOMES: [&str; OutcomeKind::ALL.len()] = OutcomeKind::names();

/// The most measured quantities a scene has (the catalogue's).
pub use meterstick_core::scene::MAX_MEASURES;

/// A mode's code: 0 separated, 1 sticking, 2 sliding+, 3 sliding- ([`MODES`]).
#[must_use]
pub const fn mode_code(m: ContactMode) -> u8 {
    match m {
        ContactMode::Separated => 0,
        ContactMode::Sticking => 1,
        ContactMode::Sliding(Direction::Plus) => 2,
        ContactMode::Sliding(Direction::Minus) => 3,
    }
}

/// An outcome's code, the index of its name in [`OUTCOMES`].
#[must_use]
pub const fn outcome_code(o: Outcome) -> u8 {
    o.kind().code()
}

/// A scene of one body or of several, held in place.
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per run, held in place: there is no heap on wasm
enum Held {
    /// A scene of one body (`E = 0`: the page finds switch events in the rows).
    #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
    One(AnyScene<0>),
    /// A scene of several bodies.
    #[cfg(feature = "mb")]
    Many(AnyMultibody),
}

/// The most steps a run goes on after its outcome ([`Sim::step_past_rows`]): 30 s at the
/// default step of 1 ms, so that nothing runs forever (the page stops sooner, when the bodies
/// rest or leave its view).
pub const MAX_PAST_STEPS: u32 = 30_000;

/// One run.
#[derive(Debug, Clone)]
pub struct Sim {
    /// The scene, from the core's registry.
    scene: Held,
    kind: SceneKind,
    checksum: Checksum,
    start: [f64; MAX_ROW],
    /// Once the run goes on past its outcome: the run as judged (what the accessors report).
    past: Option<Judged>,
}

/// A run as its judge left it (outcome, time, counters, measured quantities), kept while the
/// scene goes on past its outcome ([`Sim::step_past_rows`]); the checksum stays the judged run's
/// (the steps past the outcome are not added to it).
#[derive(Debug, Clone, Copy)]
struct Judged {
    outcome: Outcome,
    time: f64,
    stats: RunStats,
    measured: [f64; MAX_MEASURES],
    /// Steps taken past the outcome.
    steps: u32,
}

impl Sim {
    /// The scene of `spec` in `precision` and `layout`, at its start at `t = 0`.
    ///
    /// # Errors
    /// The core's complaint about the parameters (in its precision).
    pub fn new(spec: &SceneParams, precision: Precision, layout: LcpLayout) -> Result<Self, ParamError> {
        // A scene of another module (the page loads the module of the scene's contacts).
        if !holds(spec.kind()) {
            return Err(ParamError::OutOfRange("scene"));
        }
        let mut start = [0.0; MAX_ROW];
        let scene = if spec.kind().is_multibody() {
            #[cfg(feature = "mb")]
            {
                let mut scene = AnyMultibody::new(spec, precision)?;
                scene.visit_mut(BodiesStartRow(&mut start));
                Held::Many(scene)
            }
            #[cfg(not(feature = "mb"))]
            return Err(ParamError::OutOfRange("scene"));
        } else {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            {
                let mut scene = AnyScene::new(spec, precision, layout)?;
                scene.visit_mut(StartRow(&mut start));
                Held::One(scene)
            }
            #[cfg(not(any(feature = "k1", feature = "k2", feature = "k3")))]
            return Err(ParamError::OutOfRange("scene"));
        };
        Ok(Self { scene, kind: spec.kind(), checksum: Checksum::new(), start, past: None })
    }

    /// The scene.
    #[must_use]
    pub const fn kind(&self) -> SceneKind {
        self.kind
    }

    /// Numbers per row of this run ([`row_len`] of its contacts).
    #[must_use]
    pub const fn row_len(&self) -> usize {
        if self.kind.is_multibody() { BODIES_ROW } else { row_len(self.kind.contacts()) }
    }

    /// The row of the state at `t = 0` (the contacts' initial modes; no impulses).
    #[must_use]
    pub fn start_row(&self) -> &[f64] {
        &self.start[..self.row_len()]
    }

    /// Steps until the run ends or `rows` is full, writing one row per step into `rows`
    /// ([`Self::row_len`] numbers each); returns the steps taken (0 once the run has ended).
    pub fn step_rows(&mut self, rows: &mut [f64]) -> usize {
        if self.past.is_some() {
            return 0;
        }
        Self::held_rows(&mut self.scene, &mut self.checksum, rows)
    }

    /// After the outcome, steps the scene on past it (the core's `go_on` before each step: the
    /// bodies go on, the stack tumbles off the table), writing rows as [`Self::step_rows`] does;
    /// the run is reported as judged from then on (its outcome, checksum, time, counters, measured
    /// quantities: the judged run). At most [`MAX_PAST_STEPS`] in all; returns the steps taken (0
    /// before the outcome, once a step failed or the bound is reached).
    pub fn step_past_rows(&mut self, rows: &mut [f64]) -> usize {
        if self.past.is_none() {
            let Some(outcome) = self.outcome() else { return 0 };
            let judged = Judged {
                outcome,
                time: self.time(),
                stats: self.stats(),
                measured: self.measured(),
                steps: 0,
            };
            self.past = Some(judged);
        }
        let past_steps = self.past.map_or(0, |j| j.steps);
        let len = self.row_len();
        let end = ((MAX_PAST_STEPS - past_steps) as usize * len).min(rows.len());
        let mut n = 0;
        // One row at a time through the run's own stepping (one copy of the step in the module):
        // the outcome taken before each step.
        for row in rows[..end].chunks_exact_mut(len) {
            match &mut self.scene {
                #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
                Held::One(s) => s.visit_mut(GoOn),
                #[cfg(feature = "mb")]
                Held::Many(s) => s.visit_mut(GoOn),
            }
            if Self::held_rows(&mut self.scene, &mut Checksum::new(), row) == 0 {
                break;
            }
            n += 1;
        }
        if let Some(j) = &mut self.past {
            j.steps += n as u32;
        }
        n
    }

    /// Steps `scene` into `rows` (one place: the run and the steps past its outcome share it).
    #[inline(never)]
    fn held_rows(scene: &mut Held, checksum: &mut Checksum, rows: &mut [f64]) -> usize {
        match scene {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            Held::One(s) => s.visit_mut(StepRows { checksum, rows }),
            #[cfg(feature = "mb")]
            Held::Many(s) => s.visit_mut(BodiesStepRows { checksum, rows }),
        }
    }

    /// Steps until the run ends or `max` steps were taken, without rows (the outcome map, the
    /// benchmark); returns the steps taken.
    pub fn run(&mut self, max: u64) -> u64 {
        if self.past.is_some() {
            return 0;
        }
        match &mut self.scene {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            Held::One(s) => s.visit_mut(Run { checksum: &mut self.checksum, max }),
            #[cfg(feature = "mb")]
            Held::Many(s) => s.visit_mut(Run { checksum: &mut self.checksum, max }),
        }
    }

    /// The outcome, once the run has ended.
    #[must_use]
    pub fn outcome(&self) -> Option<Outcome> {
        if let Some(j) = &self.past {
            return Some(j.outcome);
        }
        match &self.scene {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            Held::One(s) => s.outcome(),
            #[cfg(feature = "mb")]
            Held::Many(s) => s.outcome(),
        }
    }

    /// The trajectory checksum so far (FNV-1a over the state's bits after every step).
    #[must_use]
    pub const fn checksum(&self) -> u32 {
        self.checksum.value()
    }

    /// Simulated time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        if let Some(j) = &self.past {
            return j.time;
        }
        match &self.scene {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            Held::One(s) => s.time(),
            #[cfg(feature = "mb")]
            Held::Many(s) => s.time(),
        }
    }

    /// The stepper's counters (steps, pivots, warm starts, full-layout fallbacks, ...); a scene of
    /// several bodies has steps, pivots, the most in a step and its warm starts (the rest 0).
    #[must_use]
    pub fn stats(&self) -> RunStats {
        if let Some(j) = &self.past {
            return j.stats;
        }
        match &self.scene {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            Held::One(s) => *s.stats(),
            #[cfg(feature = "mb")]
            Held::Many(s) => {
                let st = s.stats();
                RunStats {
                    steps: u64::from(st.steps),
                    pivots: st.pivots,
                    max_pivots: st.max_pivots,
                    warm_starts: u64::from(st.warm_direct),
                    ..RunStats::default()
                }
            }
        }
    }

    /// The scene's measured quantities so far, in the order of the catalogue's `measures` for
    /// the scene (`summary.json`'s keys, [`Scene::measured`]); NaN where there is none (yet).
    #[must_use]
    pub fn measured(&self) -> [f64; MAX_MEASURES] {
        if let Some(j) = &self.past {
            return j.measured;
        }
        let m = match &self.scene {
            #[cfg(any(feature = "k1", feature = "k2", feature = "k3"))]
            Held::One(s) => s.measured(),
            #[cfg(feature = "mb")]
            Held::Many(s) => s.measured(),
        };
        m.map(|v| v.unwrap_or(f64::NAN))
    }

    /// A scene of several bodies' body `i`'s `[width, height]` (m); `None` past its bodies or for
    /// a scene of one body.
    #[must_use]
    pub fn body_size(&self, i: usize) -> Option<[f64; 2]> {
        match &self.scene {
            #[cfg(feature = "mb")]
            Held::Many(s) => s.sizes().get(i).copied().flatten(),
            #[allow(unreachable_patterns)]
            _ => None,
        }
    }

    /// `true` when a scene of several bodies' body `i` is round (a disc whose rim rests on a face:
    /// [`meterstick_core::multibody::Shape::Disc`]); `false` for a box, past its bodies or for a
    /// scene of one body.
    #[must_use]
    pub fn body_round(&self, i: usize) -> bool {
        match &self.scene {
            #[cfg(feature = "mb")]
            Held::Many(s) => {
                s.shapes().get(i).copied().flatten() == Some(meterstick_core::multibody::Shape::Disc)
            }
            #[allow(unreachable_patterns)]
            _ => {
                let _ = i;
                false
            }
        }
    }

    /// A scene of several bodies' table ends `[lo, hi]` (m; `None` for an infinite end, and both
    /// for a scene of one body).
    #[must_use]
    pub fn table(&self) -> [Option<f64>; 2] {
        match &self.scene {
            #[cfg(feature = "mb")]
            Held::Many(s) => s.table(),
            #[allow(unreachable_patterns)]
            _ => [None, None],
        }
    }
}

/// A scene of several bodies' row: `time`, then every body's `x, y, theta` ([`BODIES_ROW`]; NaN
/// past its bodies).
fn bodies_row<T: Real>(time: T, states: &[meterstick_core::planar::BodyState<T>], row: &mut [f64]) {
    row[0] = time.as_f64();
    for (b, slot) in row[1..BODIES_ROW].chunks_exact_mut(3).enumerate() {
        let q = states.get(b).map_or([f64::NAN; 3], |s| [s.x.as_f64(), s.y.as_f64(), s.theta.as_f64()]);
        slot.copy_from_slice(&q);
    }
}

/// The start row of a scene of several bodies, as a visitor of the core's registry.
#[cfg(feature = "mb")]
struct BodiesStartRow<'a>(&'a mut [f64; MAX_ROW]);

#[cfg(feature = "mb")]
impl MultibodyVisitor for BodiesStartRow<'_> {
    type Output = ();
    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(self, scene: S) {
        bodies_row(scene.time(), scene.states(), &mut self.0[..]);
    }
}

/// Steps a scene of several bodies into rows of [`BODIES_ROW`], adding every body's state to
/// the checksum.
#[cfg(feature = "mb")]
struct BodiesStepRows<'a> {
    checksum: &'a mut Checksum,
    rows: &'a mut [f64],
}

/// Takes a scene's outcome so that its next step is taken (the core's `go_on`): a copy of the run
/// goes on past its outcome.
struct GoOn;

impl SceneVisitor for GoOn {
    type Output = ();
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, mut scene: S) {
        let _ = scene.go_on();
    }
}

#[cfg(feature = "mb")]
impl MultibodyVisitor for GoOn {
    type Output = ();
    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(self, mut scene: S) {
        let _ = scene.go_on();
    }
}

#[cfg(feature = "mb")]
impl MultibodyVisitor for BodiesStepRows<'_> {
    type Output = usize;
    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        mut scene: S,
    ) -> usize {
        let mut taken = 0;
        for row in self.rows.chunks_exact_mut(BODIES_ROW) {
            let Some(report) = scene.step() else { break };
            for s in &report.states {
                self.checksum.add(s);
            }
            bodies_row(report.time, &report.states, row);
            taken += 1;
        }
        taken
    }
}

#[cfg(feature = "mb")]
impl MultibodyVisitor for Run<'_> {
    type Output = u64;
    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(self, mut scene: S) -> u64 {
        let mut taken = 0;
        while taken < self.max {
            let Some(report) = scene.step() else { break };
            for s in &report.states {
                self.checksum.add(s);
            }
            taken += 1;
        }
        taken
    }
}

/// [`start_row`] as a visitor of the core's registry.
struct StartRow<'a>(&'a mut [f64; MAX_ROW]);

impl SceneVisitor for StartRow<'_> {
    type Output = ();
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, scene: S) {
        start_row(&scene, self.0);
    }
}

/// [`step_rows`] as a visitor of the core's registry.
struct StepRows<'a> {
    checksum: &'a mut Checksum,
    rows: &'a mut [f64],
}

impl SceneVisitor for StepRows<'_> {
    type Output = usize;
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, mut scene: S) -> usize {
        step_rows(&mut scene, self.checksum, self.rows)
    }
}

/// Steps until the run ends or `max` steps were taken, adding each state to the checksum.
struct Run<'a> {
    checksum: &'a mut Checksum,
    max: u64,
}

impl SceneVisitor for Run<'_> {
    type Output = u64;
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, mut scene: S) -> u64 {
        let mut taken = 0;
        while taken < self.max {
            let Some(report) = scene.step() else { break };
            self.checksum.add(&report.state);
            taken += 1;
        }
        taken
    }
}

/// The state's columns and where each support touches the body: the contact point moved back by
/// the gap along the normal (a finger's tip; the foot of a corner on a line; the rim's point on
/// the slope), as `host-sim` writes it.
fn state_columns<T: Real, S: Scene<T, K>, const K: usize>(scene: &S, row: &mut [f64]) {
    let s = scene.state();
    row[0] = scene.time().as_f64();
    for (slot, v) in row[1..7].iter_mut().zip(s.to_array()) {
        *slot = v.as_f64();
    }
    for (k, f) in scene.frames().iter().enumerate() {
        let (r, n, gap) = (f.r.map(Real::as_f64), f.normal().map(Real::as_f64), f.gap.as_f64());
        row[7 + 2 * k] = s.x.as_f64() + r[0] - gap * n[0];
        row[8 + 2 * k] = s.y.as_f64() + r[1] - gap * n[1];
    }
}

fn start_row<T: Real, S: Scene<T, K>, const K: usize>(scene: &S, row: &mut [f64]) {
    state_columns(scene, row);
    for (k, m) in scene.modes().into_iter().enumerate() {
        row[7 + 2 * K + k] = f64::from(mode_code(m));
    }
}

/// Steps `scene` into `rows` ([`row_len`] of `K` numbers each; the length known to the compiler).
fn step_rows<T: Real, S: Scene<T, K>, const K: usize>(
    scene: &mut S,
    checksum: &mut Checksum,
    rows: &mut [f64],
) -> usize {
    let mut taken = 0;
    for row in rows.chunks_exact_mut(row_len(K)) {
        let Some(report) = scene.step() else { break };
        checksum.add(&report.state);
        write_row(&*scene, &report, row);
        taken += 1;
    }
    taken
}

fn write_row<T: Real, S: Scene<T, K>, const K: usize>(scene: &S, report: &StepReport<T, K>, row: &mut [f64]) {
    state_columns(scene, row);
    row[0] = report.time.as_f64();
    let group = |g: usize, k: usize| 7 + 2 * K + g * K + k;
    for (k, c) in report.contacts.iter().enumerate() {
        row[group(0, k)] = f64::from(mode_code(c.mode));
        row[group(1, k)] = c.normal_impulse.as_f64();
        row[group(2, k)] = c.friction_impulse.as_f64();
        row[group(3, k)] = c.along.as_f64();
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)] // exact: values copied or rounded once, not computed
    use super::*;
    use crate::config::Config;
    use crate::flags::flag_index;

    const ROW: usize = row_len(2);

    fn sim(kind: SceneKind, given: &[(&str, f64)], precision: Precision, size: LcpLayout) -> Sim {
        let mut c = Config::new(kind);
        for (long, v) in given {
            c.give(flag_index(long).unwrap(), *v);
        }
        Sim::new(&c.resolve(precision).unwrap(), precision, size).unwrap()
    }

    #[test]
    fn rows_and_quiet_runs_agree() {
        let slow = [("x1", -0.35)];
        let mut a = sim(SceneKind::MeterStick, &slow, Precision::F32, LcpLayout::Reduced);
        let mut b = a.clone();
        let mut rows = [0.0; 64 * ROW];
        let mut steps = 0;
        let mut last = [0.0; ROW];
        loop {
            let n = a.step_rows(&mut rows);
            if n == 0 {
                break;
            }
            last.copy_from_slice(&rows[(n - 1) * ROW..n * ROW]);
            steps += n;
        }
        assert_eq!(b.run(u64::MAX), steps as u64);
        assert_eq!(a.checksum(), b.checksum());
        assert_eq!(a.outcome(), Some(Outcome::Balanced));
        assert_eq!(last[0], a.time());
        // The rod balanced on both fingers: both touch, the COM between them, the fingers 1 cm apart.
        assert!(last[11] != 0.0 && last[12] != 0.0, "{last:?}");
        assert!(last[7] < last[1] && last[1] < last[9], "{last:?}");
        assert!((last[9] - last[7] - 0.01).abs() < 1e-6, "{last:?}");
        assert!(a.measured()[1].abs() < 3e-3, "meeting.com_offset_m");
    }

    #[test]
    fn the_start_row_is_the_rest_state_with_the_initial_modes() {
        let s = sim(SceneKind::MeterStick, &[], Precision::F64, LcpLayout::Full);
        let row = s.start_row();
        assert_eq!(row.len(), 19, "core.csv's columns");
        assert_eq!(row[..4], [0.0, 0.0, 0.0025, 0.0]);
        assert_eq!(row[7..11], [-0.4, 0.0, 0.4, 0.0]);
        // Finger 1 starts sliding under the resting rod (sliding+), finger 2 sticks.
        assert_eq!((row[11], row[12]), (2.0, 1.0));
        let ladder = sim(SceneKind::Ladder, &[("angle", 60.0)], Precision::F32, LcpLayout::Reduced);
        let row = ladder.start_row();
        // The foot on the floor, the top against the wall (f32 round-off).
        assert!((row[7] + 0.5).abs() < 1e-6 && row[8].abs() < 1e-6, "{row:?}");
        assert!(row[9].abs() < 1e-6 && (row[10] - 0.75_f64.sqrt()).abs() < 1e-6, "{row:?}");
    }

    #[test]
    fn every_scene_precision_and_size_runs_to_its_outcome() {
        for (kind, want) in [
            (SceneKind::MeterStick, Outcome::Fell),
            (SceneKind::Incline, Outcome::Slid),
            (SceneKind::Ladder, Outcome::Fell),
            (SceneKind::ThreeFingers, Outcome::Held),
            (SceneKind::Cylinder, Outcome::Rolled),
            (SceneKind::Painleve, Outcome::Jammed),
        ] {
            for precision in [Precision::F32, Precision::F64] {
                for size in [LcpLayout::Reduced, LcpLayout::Full] {
                    let given: &[(&str, f64)] =
                        if kind == SceneKind::MeterStick { &[("speed", 1.0)] } else { &[] };
                    let mut s = sim(kind, given, precision, size);
                    let steps = s.run(u64::MAX);
                    assert_eq!(s.outcome(), Some(want), "{kind:?} {precision:?} {size:?}");
                    assert_eq!(s.stats().steps, steps);
                    assert_eq!(s.run(10), 0, "an ended run takes no step");
                }
            }
        }
    }

    #[test]
    fn rows_follow_the_scenes_contacts() {
        // The cylinder: one contact, rows of 13 (core.csv's columns for one contact).
        let mut c = sim(SceneKind::Cylinder, &[("angle", 30.0)], Precision::F64, LcpLayout::Reduced);
        assert_eq!((c.row_len(), c.start_row().len()), (13, 13));
        let mut rows = [0.0; 3 * 13 + 5];
        assert_eq!(c.step_rows(&mut rows), 3, "whole rows only");
        assert_eq!(rows[3 * 13..], [0.0; 5], "nothing past the last whole row");
        let r = &rows[2 * 13..3 * 13];
        assert_eq!(r[0], c.time());
        // The rim touches the slope below the centre (r = 0.1 along the normal), rolling: sticking,
        // a normal impulse of about m g cos(30 deg) h.
        let (n, a) = ([-0.5, 0.75_f64.sqrt()], 30_f64.to_radians());
        assert!(
            (r[7] - (r[1] - 0.1 * n[0])).abs() < 1e-9 && (r[8] - (r[2] - 0.1 * n[1])).abs() < 1e-9,
            "{r:?}"
        );
        assert_eq!(r[9], 1.0, "sticking");
        assert!((r[10] - 9.81 * a.cos() * 1e-3).abs() < 1e-5, "{r:?}");
        // Three fingers: rows of 25, the third finger's support and mode in their places.
        let t = sim(SceneKind::ThreeFingers, &[], Precision::F32, LcpLayout::Full);
        let r = t.start_row();
        assert_eq!(r.len(), 25);
        assert_eq!((r[7], r[9], r[11]), (f64::from(-0.4_f32), 0.0, f64::from(0.4_f32)));
        assert!(r[13..16].iter().all(|m| *m != 0.0), "every finger touches at the start: {r:?}");
    }

    #[test]
    fn measured_quantities_follow_the_catalogues_names() {
        for kind in SceneKind::ALL {
            assert!(meterstick_catalogue::Catalogued::info(kind).measures.len() <= MAX_MEASURES, "{kind}");
        }
        let mut p = sim(SceneKind::Painleve, &[], Precision::F64, LcpLayout::Reduced);
        p.run(u64::MAX);
        assert_eq!(p.outcome(), Some(Outcome::Jammed));
        let [t, pn, pf] = p.measured();
        // The defaults jam on the first step with about the tangential impact's impulses,
        // m V / 4 (1 + 3 c^2, 3 s c) at 30 degrees: (0.8125, 0.3248).
        assert_eq!(t, 1e-3);
        assert!((pf - 0.8125).abs() < 0.02 && (pn - 0.3248).abs() < 0.02, "{pn} {pf}");
        let l = sim(
            SceneKind::Ladder,
            &[("mu-floor", 0.0), ("mu-wall", 0.0)],
            Precision::F64,
            LcpLayout::Reduced,
        );
        let mut l = l;
        l.run(u64::MAX);
        let [h, ratio, none] = l.measured();
        assert!((ratio - 2.0 / 3.0).abs() < 0.01 && h > 0.0 && none.is_nan(), "{h} {ratio}");
    }
}
