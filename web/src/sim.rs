//! One run of a scene in the core, as the page drives it: [`Sim`] holds any scene this module
//! runs, built and seen through the core's `SceneView` (a `HeldView`, [`Held`]), steps it, writes
//! one row of numbers per step for the animation and the plots ([`Rows`]: for a scene with a fixed
//! list of contacts the columns of `host-sim run`'s `core.csv`, so a live run and a replayed one
//! are read alike), and reports the view's trajectory checksum (`planar::Checksum`, as the firmware
//! and `host-sim scene` print it).

use meterstick_core::ParamError;
use meterstick_core::Real;
// The contacts' modes by code are `crate::modes`' table (`mode_code`, re-exported below).
use meterstick_core::scene::{
    BodyShape, HeldView, Outcome, OutcomeKind, Pose, RunStats, SceneKind, SceneView, SupportView, Velocity,
    ViewReader, ViewVisitor,
};

use crate::config::{LcpLayout, Precision, SceneParams, holds};

/// The holder of the scenes this build runs: the host build (every feature) holds any scene, a
/// page module (`scripts/lib.sh` `build_web`) the scenes of its engine only, so that it links no
/// other engine's steppers.
#[cfg(all(any(feature = "k1", feature = "k2", feature = "k3"), feature = "mb"))]
pub type Held = meterstick_core::scene::AnyView<0>;
/// The holder of the scenes this build runs: a module of scenes of one body.
#[cfg(all(any(feature = "k1", feature = "k2", feature = "k3"), not(feature = "mb")))]
pub type Held = meterstick_core::scene::PlanarViews<0>;
/// The holder of the scenes this build runs: the module of the scenes of several bodies.
#[cfg(not(any(
    feature = "k1",
    feature = "k2",
    feature = "k3",
    all(feature = "sp", not(feature = "mb")),
    all(feature = "st", not(feature = "mb"))
)))]
pub type Held = meterstick_core::scene::MultibodyViews;

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

/// The longest row (a scene with [`MAX_CONTACTS`]; one in three dimensions with the feature `sp`).
pub const MAX_ROW: usize =
    if cfg!(any(feature = "sp", feature = "st")) { SPATIAL_ROW } else { row_len(MAX_CONTACTS) };
/// Numbers per row of a scene in three dimensions ([`crate::spatial::SPATIAL_ROW`]; none without
/// the feature `sp`).
#[cfg(any(feature = "sp", feature = "st"))]
pub use crate::spatial::SPATIAL_ROW;
/// Numbers per row of a scene in three dimensions: none without the feature `sp`.
#[cfg(not(any(feature = "sp", feature = "st")))]
pub const SPATIAL_ROW: usize = 0;
const _: () = assert!(BODIES_ROW <= MAX_ROW);

/// The modes by code ([`mode_code`]), as `core.csv` spells them.
pub const MODES: [&str; 4] = ["separated", "sticking", "sliding+", "sliding-"];

/// The outcomes by code ([`outcome_code`]): the core's one list ([`OutcomeKind`]).
pub const OUTCOMES: [&str; OutcomeKind::ALL.len()] = OutcomeKind::names();

/// The most measured quantities a scene has (the catalogue's).
pub use meterstick_core::scene::MAX_MEASURES;

/// What each row of a scene holds: its length and columns, from the scene's contacts as the
/// catalogue counts them ([`SceneKind::contacts`]), the numbers from its view.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rows {
    /// A scene of one body on a fixed list of `k` contacts: time, the body's `x, y, theta, vx,
    /// vy, omega`, then each contact's support point, mode, normal impulse, friction impulse and
    /// coordinate along it ([`row_len`], `host-sim`'s `core.csv`).
    Contacts(usize),
    /// A scene whose contacts come and go (none counted): time, then each body's `x, y, theta`
    /// ([`BODIES_ROW`]; NaN past its bodies), as `host-sim`'s trajectory of bodies.
    Bodies,
    /// A scene in three dimensions: the body's pose (a quaternion), its velocities and each
    /// contact's point, normal, friction direction, mode and impulses ([`crate::spatial::write_row`]).
    #[cfg(any(feature = "sp", feature = "st"))]
    Spatial,
}

impl Rows {
    /// The rows of `kind`.
    #[must_use]
    pub const fn of(kind: SceneKind) -> Self {
        #[cfg(any(feature = "sp", feature = "st"))]
        if kind.is_spatial() {
            return Self::Spatial;
        }
        match kind.contacts() {
            0 => Self::Bodies,
            k => Self::Contacts(k),
        }
    }

    /// Numbers per row.
    #[must_use]
    pub const fn width(self) -> usize {
        match self {
            Self::Contacts(k) => row_len(k),
            Self::Bodies => BODIES_ROW,
            #[cfg(any(feature = "sp", feature = "st"))]
            Self::Spatial => SPATIAL_ROW,
        }
    }

    /// Writes `view`'s row as it is now into `row` ([`Self::width`] numbers): the contacts' impulses
    /// and coordinates over its last step (zero before the first).
    fn write<T: Real>(self, view: &dyn SceneView<T>, row: &mut [f64]) {
        row[0] = view.time().as_f64();
        match self {
            Self::Contacts(k) => {
                let Some((q, v)) = view.body(0).and_then(|b| planar(&b)) else { return };
                for (slot, x) in row[1..7].iter_mut().zip(q.into_iter().chain(v)) {
                    *slot = x.as_f64();
                }
                let group = |g: usize, i: usize| 7 + 2 * k + g * k + i;
                for i in 0..k {
                    let Some(c) = view.contact(i) else { continue };
                    // Where the support touches the body: the contact point moved back by the gap
                    // along the normal (a finger's tip; the foot of a corner on a line; the rim's
                    // point on the slope), in f64 from the body's position as `host-sim` writes it.
                    let (r, n, gap) = (c.lever.map(Real::as_f64), c.normal.map(Real::as_f64), c.gap.as_f64());
                    row[7 + 2 * i] = q[0].as_f64() + r[0] - gap * n[0];
                    row[8 + 2 * i] = q[1].as_f64() + r[1] - gap * n[1];
                    row[group(0, i)] = f64::from(mode_code(c.mode));
                    row[group(1, i)] = c.normal_impulse.as_f64();
                    row[group(2, i)] = c.friction_impulse.as_f64();
                    row[group(3, i)] = c.along.as_f64();
                }
            }
            Self::Bodies => {
                for (b, slot) in row[1..BODIES_ROW].chunks_exact_mut(3).enumerate() {
                    let q = view
                        .body(b)
                        .and_then(|b| planar(&b))
                        .map_or([f64::NAN; 3], |(q, _)| q.map(Real::as_f64));
                    slot.copy_from_slice(&q);
                }
            }
            #[cfg(any(feature = "sp", feature = "st"))]
            Self::Spatial => crate::spatial::write_row(view, row),
        }
    }
}

/// A body's `[x, y, theta]` and `[vx, vy, omega]` in the plane (`None` for a body in another
/// dimension).
fn planar<T: Real>(body: &meterstick_core::scene::BodyView<T>) -> Option<([T; 3], [T; 3])> {
    let Pose::Planar { x, y, theta } = body.pose else { return None };
    let Velocity::Planar { vx, vy, omega } = body.velocity else { return None };
    Some(([x, y, theta], [vx, vy, omega]))
}

/// One run: the scene held in place ([`Held`]: the scenes of this build's features, those in
/// three dimensions with the feature `sp`), the rows it writes ([`Rows`]), its start, and once it
/// goes on past its outcome the run as judged (what the accessors report then: the steps past the
/// outcome are not in it).
#[derive(Debug, Clone)]
pub struct Sim {
    /// The scene, built and seen through its view.
    view: Held,
    kind: SceneKind,
    rows: Rows,
    start: [f64; MAX_ROW],
    /// Once the run goes on past its outcome: the run as judged (what the accessors report).
    past: Option<Judged>,
}

/// What the accessors report of a run: its outcome, time, counters, measured quantities (NaN
/// where there is none) and checksum.
#[derive(Debug, Clone, Copy)]
struct Status {
    outcome: Option<Outcome>,
    time: f64,
    summary: RunStats,
    measured: [f64; MAX_MEASURES],
    checksum: u32,
}

/// A run as its judge left it, kept while the scene goes on past its outcome
/// ([`Sim::step_past_rows`]): the steps past the outcome are not in what it reports.
#[derive(Debug, Clone, Copy)]
struct Judged {
    status: Status,
    /// Steps taken past the outcome.
    steps: u32,
}

impl Sim {
    /// The scene of `spec` in `precision` and `layout`, at its start at `t = 0`.
    ///
    /// # Errors
    /// The core's complaint about the parameters (in its precision); `OutOfRange("scene")` for a
    /// scene of another module.
    pub fn new(spec: &SceneParams, precision: Precision, layout: LcpLayout) -> Result<Self, ParamError> {
        // A scene of another module (the page loads the module that runs it).
        if !holds(spec.kind()) {
            return Err(ParamError::OutOfRange("scene"));
        }
        let view = Held::new(spec, precision, layout)?;
        let rows = Rows::of(spec.kind());
        let mut start = [0.0; MAX_ROW];
        view.read(RowNow { rows, row: &mut start[..rows.width()] });
        Ok(Self { view, kind: spec.kind(), rows, start, past: None })
    }

    /// The scene.
    #[must_use]
    pub const fn kind(&self) -> SceneKind {
        self.kind
    }

    /// Numbers per row of this run ([`Rows::width`]).
    #[must_use]
    pub const fn row_len(&self) -> usize {
        self.rows.width()
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
        self.view.visit_mut(StepRows { rows: self.rows, out: rows, go_on: false })
    }

    /// After the outcome, steps the scene on past it (the core's `go_on` before each step: the
    /// bodies go on, the stack tumbles off the table), writing rows as [`Self::step_rows`] does;
    /// the run is reported as judged from then on (its outcome, checksum, time, counters, measured
    /// quantities: the judged run). At most [`MAX_PAST_STEPS`] in all; returns the steps taken (0
    /// before the outcome, once a step failed or the bound is reached).
    pub fn step_past_rows(&mut self, rows: &mut [f64]) -> usize {
        if self.past.is_none() {
            let status = self.status();
            if status.outcome.is_none() {
                return 0;
            }
            self.past = Some(Judged { status, steps: 0 });
        }
        let Some(judged) = self.past else { return 0 };
        let len = self.row_len();
        let end = ((MAX_PAST_STEPS - judged.steps) as usize * len).min(rows.len());
        let n = self.view.visit_mut(StepRows { rows: self.rows, out: &mut rows[..end], go_on: true });
        self.past = Some(Judged { steps: judged.steps + n as u32, ..judged });
        n
    }

    /// Steps until the run ends or `max` steps were taken, without rows (the outcome map, the
    /// benchmark); returns the steps taken.
    pub fn run(&mut self, max: u64) -> u64 {
        if self.past.is_some() {
            return 0;
        }
        self.view.visit_mut(Run(max))
    }

    /// The run as reported: as judged once it goes on past its outcome, else as it is.
    fn status(&self) -> Status {
        self.past.map_or_else(|| self.view.read(Now), |j| j.status)
    }

    /// The outcome, once the run has ended.
    #[must_use]
    pub fn outcome(&self) -> Option<Outcome> {
        self.status().outcome
    }

    /// The trajectory checksum so far (FNV-1a over the bodies' states after every step).
    #[must_use]
    pub fn checksum(&self) -> u32 {
        self.status().checksum
    }

    /// Simulated time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.status().time
    }

    /// The engine's counters (steps, pivots, warm starts, reduced layouts' fallbacks, ...: those
    /// an engine does not keep are 0).
    #[must_use]
    pub fn stats(&self) -> RunStats {
        self.status().summary
    }

    /// The scene's measured quantities so far, in the order of the catalogue's `measures` for
    /// the scene (`summary.json`'s keys); NaN where there is none (yet).
    #[must_use]
    pub fn measured(&self) -> [f64; MAX_MEASURES] {
        self.status().measured
    }

    /// Body `i`'s outline: `[width, height]` of a box, the diameter twice for a disc (m); `None`
    /// past its bodies.
    #[must_use]
    pub fn body_size(&self, i: usize) -> Option<[f64; 2]> {
        match self.view.read(ShapeOf(i))? {
            BodyShape::Box { width, height } => Some([width, height]),
            BodyShape::Disc { radius } => Some([2.0 * radius; 2]),
            _ => None,
        }
    }

    /// `true` when body `i` is round (a disc, drawn with a spoke so that its turning shows);
    /// `false` for a box or past its bodies.
    #[must_use]
    pub fn body_round(&self, i: usize) -> bool {
        matches!(self.view.read(ShapeOf(i)), Some(BodyShape::Disc { .. }))
    }

    /// The bodies' solid, `[code, a, b, c]` ([`crate::spatial::Solid`]): a scene in three
    /// dimensions.
    #[cfg(any(feature = "sp", feature = "st"))]
    #[must_use]
    pub fn solid(&self) -> Option<[f64; 4]> {
        self.view.read(crate::spatial::Solid)
    }

    /// Support `i`, `[code, point, direction]` ([`crate::spatial::SupportOf`]): a scene in three
    /// dimensions.
    #[cfg(any(feature = "sp", feature = "st"))]
    #[must_use]
    pub fn support(&self, i: usize) -> Option<[f64; 7]> {
        self.view.read(crate::spatial::SupportOf(i))
    }

    /// The ends `[lo, hi]` of the table the scene's bodies rest on (m; `None` for an infinite end,
    /// and both for a scene without a table).
    #[must_use]
    pub fn table(&self) -> [Option<f64>; 2] {
        self.view.read(Table)
    }
}

/// The most steps a run goes on after its outcome ([`Sim::step_past_rows`]): 30 s at the
/// default step of 1 ms, so that nothing runs forever (the page stops sooner, when the bodies
/// rest or leave its view).
pub const MAX_PAST_STEPS: u32 = 30_000;

/// A mode's code: 0 separated, 1 sticking, 2 sliding+, 3 sliding- ([`MODES`]). The one table of
/// them is `crate::modes`, so that the rows of the scenes in the plane (this module's) and in three
/// dimensions (`crate::spatial`'s) both read it without either module importing the other.
///
/// These ten lines keep the length of the function they replaced: the planar page modules carry
/// each bounds check's source line (its panic location) from this file, and they are kept byte
/// for byte. A change above `Sim`'s end that adds or removes lines changes them; one below does
/// not.
#[doc(inline)]
pub use crate::modes::mode_code;

/// An outcome's code, the index of its name in [`OUTCOMES`].
#[must_use]
pub const fn outcome_code(o: Outcome) -> u8 {
    o.kind().code()
}

/// The holder of the scenes this build runs: the module of the scenes in three dimensions in f32.
#[cfg(all(
    not(any(
        feature = "k1",
        feature = "k2",
        feature = "k3",
        feature = "mb",
        feature = "sp64",
        feature = "st"
    )),
    feature = "sp"
))]
pub type Held = meterstick_core::scene::SpatialViewsIn<f32>;
/// The holder of the scenes this build runs: the module of the scenes in three dimensions in f64.
#[cfg(all(
    not(any(feature = "k1", feature = "k2", feature = "k3", feature = "mb", feature = "st")),
    feature = "sp64"
))]
pub type Held = meterstick_core::scene::SpatialViewsIn<f64>;
/// The holder of the scenes this build runs: the module of the stack in three dimensions in f32.
#[cfg(all(
    not(any(
        feature = "k1",
        feature = "k2",
        feature = "k3",
        feature = "mb",
        feature = "sp",
        feature = "st64"
    )),
    feature = "st"
))]
pub type Held = meterstick_core::scene::StackViewsIn<f32>;
/// The holder of the scenes this build runs: the module of the stack in three dimensions in f64.
#[cfg(all(
    not(any(feature = "k1", feature = "k2", feature = "k3", feature = "mb", feature = "sp")),
    feature = "st64"
))]
pub type Held = meterstick_core::scene::StackViewsIn<f64>;

/// A view's row as it is now ([`Rows::write`]).
struct RowNow<'a> {
    rows: Rows,
    row: &'a mut [f64],
}

impl ViewReader for RowNow<'_> {
    type Output = ();
    fn read<T: Real>(self, view: &dyn SceneView<T>) {
        self.rows.write(view, self.row);
    }
}

/// Steps until the run ends or `out` is full, one row per step ([`Rows::write`]); first takes the
/// outcome before each step when it goes on past it (the core's `go_on`).
struct StepRows<'a> {
    rows: Rows,
    out: &'a mut [f64],
    go_on: bool,
}

impl ViewVisitor for StepRows<'_> {
    type Output = usize;
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> usize {
        let mut taken = 0;
        for row in self.out.chunks_exact_mut(self.rows.width()) {
            if self.go_on {
                let _ = view.go_on();
            }
            if !view.step() {
                break;
            }
            self.rows.write(&*view, row);
            taken += 1;
        }
        taken
    }
}

/// Steps until the run ends or its number of steps were taken.
struct Run(u64);

impl ViewVisitor for Run {
    type Output = u64;
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> u64 {
        let mut taken = 0;
        while taken < self.0 && view.step() {
            taken += 1;
        }
        taken
    }
}

/// The run as it is now ([`Status`]).
struct Now;

impl ViewReader for Now {
    type Output = Status;
    fn read<T: Real>(self, view: &dyn SceneView<T>) -> Status {
        Status {
            outcome: view.outcome(),
            time: view.time().as_f64(),
            summary: view.summary(),
            measured: view.measured().map(|v| v.map_or(f64::NAN, Real::as_f64)),
            checksum: view.checksum(),
        }
    }
}

/// Body `i`'s outline, in f64.
struct ShapeOf(usize);

impl ViewReader for ShapeOf {
    type Output = Option<BodyShape<f64>>;
    fn read<T: Real>(self, view: &dyn SceneView<T>) -> Option<BodyShape<f64>> {
        match view.body(self.0)?.shape {
            BodyShape::Box { width, height } => {
                Some(BodyShape::Box { width: width.as_f64(), height: height.as_f64() })
            }
            BodyShape::Disc { radius } => Some(BodyShape::Disc { radius: radius.as_f64() }),
            _ => None,
        }
    }
}

/// The ends of the first table among the scene's supports.
struct Table;

impl ViewReader for Table {
    type Output = [Option<f64>; 2];
    fn read<T: Real>(self, view: &dyn SceneView<T>) -> [Option<f64>; 2] {
        (0..view.support_count())
            .find_map(|i| match view.support(i)? {
                SupportView::Table { lo, hi } => Some([lo.map(Real::as_f64), hi.map(Real::as_f64)]),
                _ => None,
            })
            .unwrap_or([None, None])
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
