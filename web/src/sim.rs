//! One run of a scene in the core, as the page drives it: [`Sim`] holds the scene in the
//! precision and LCP size asked for (f32/f64 x 6x6/8x8, any of the three scenes), steps it,
//! writes one row of numbers per step for the animation and the plots ([`COLUMNS`]: the columns of
//! `host-sim run`'s `core.csv`, so a live run and a replayed one are read alike), and keeps the
//! trajectory checksum (`planar::Checksum`, as the firmware and `host-sim scene` print it).

use meterstick_core::ParamError;
use meterstick_core::Real;
use meterstick_core::planar::{Checksum, ContactMode, Direction, RunStats, StepReport};
use meterstick_core::scene::{Incline, Ladder, MeterStick, Outcome, OutcomeKind, Scene};

use crate::config::{LcpSize, Precision, Spec};

/// The columns of a row, as `core.csv` names them: time (s), the body's `x, y, theta, vx, vy,
/// omega` (m, rad, m/s, rad/s), where each support touches (m), each contact's mode ([`mode_code`]),
/// normal and friction impulse (N s) and coordinate along it at the step's start (m).
pub const COLUMNS: [&str; ROW] = [
    "t",
    "x",
    "y",
    "theta",
    "vx",
    "vy",
    "omega",
    "support1_x",
    "support1_y",
    "support2_x",
    "support2_y",
    "mode1",
    "mode2",
    "pn1",
    "pn2",
    "pf1",
    "pf2",
    "along1",
    "along2",
];

/// Numbers per row.
pub const ROW: usize = 19;

/// The modes by code ([`mode_code`]), as `core.csv` spells them.
pub const MODES: [&str; 4] = ["separated", "sticking", "sliding+", "sliding-"];

/// The outcomes by code ([`outcome_code`]): the core's one list ([`OutcomeKind`]).
pub const OUTCOMES: [&str; OutcomeKind::ALL.len()] = OutcomeKind::names();

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

/// The scene in its precision and LCP size (`E = 0`: the page finds switch events in the rows).
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per session, held in place: there is no heap on wasm
enum AnyScene {
    MeterStickF32R(MeterStick<f32, 6, 0>),
    MeterStickF32F(MeterStick<f32, 8, 0>),
    MeterStickF64R(MeterStick<f64, 6, 0>),
    MeterStickF64F(MeterStick<f64, 8, 0>),
    InclineF32R(Incline<f32, 6, 0>),
    InclineF32F(Incline<f32, 8, 0>),
    InclineF64R(Incline<f64, 6, 0>),
    InclineF64F(Incline<f64, 8, 0>),
    LadderF32R(Ladder<f32, 6, 0>),
    LadderF32F(Ladder<f32, 8, 0>),
    LadderF64R(Ladder<f64, 6, 0>),
    LadderF64F(Ladder<f64, 8, 0>),
}

/// Runs `$body` with `$s` bound to the scene, whatever its type.
macro_rules! each {
    ($any:expr, $s:ident => $body:expr) => {
        match $any {
            AnyScene::MeterStickF32R($s) => $body,
            AnyScene::MeterStickF32F($s) => $body,
            AnyScene::MeterStickF64R($s) => $body,
            AnyScene::MeterStickF64F($s) => $body,
            AnyScene::InclineF32R($s) => $body,
            AnyScene::InclineF32F($s) => $body,
            AnyScene::InclineF64R($s) => $body,
            AnyScene::InclineF64F($s) => $body,
            AnyScene::LadderF32R($s) => $body,
            AnyScene::LadderF32F($s) => $body,
            AnyScene::LadderF64R($s) => $body,
            AnyScene::LadderF64F($s) => $body,
        }
    };
}

/// The scene's measured quantities (`docs/scenes.md`, "Measured"); NaN where there is none.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Meter stick: when the fingers met (s).
    pub meeting_time: f64,
    /// Meter stick: the centre of mass from the fingers' midpoint then, along the rod (m).
    pub meeting_offset: f64,
    /// Incline: the acceleration down the slope while sliding (m/s^2).
    pub acceleration: f64,
    /// Ladder: the height of the top when it left the wall (m).
    pub wall_release_height: f64,
    /// Ladder: that height over the top's start height.
    pub wall_release_ratio: f64,
}

impl Measured {
    /// The five values in field order.
    #[must_use]
    pub const fn to_array(&self) -> [f64; 5] {
        [
            self.meeting_time,
            self.meeting_offset,
            self.acceleration,
            self.wall_release_height,
            self.wall_release_ratio,
        ]
    }
}

/// One run.
#[derive(Debug, Clone)]
pub struct Sim {
    scene: AnyScene,
    checksum: Checksum,
    start: [f64; ROW],
}

impl Sim {
    /// The scene of `spec` in `precision` and `size`, at rest at `t = 0`.
    ///
    /// # Errors
    /// The core's complaint about the parameters (in its precision).
    pub fn new(spec: &Spec, precision: Precision, size: LcpSize) -> Result<Self, ParamError> {
        use {LcpSize::Full as Fu, LcpSize::Reduced as Re, Precision::F32, Precision::F64};
        let scene = match (*spec, precision, size) {
            (Spec::MeterStick(p), F32, Re) => AnyScene::MeterStickF32R(MeterStick::new(p.cast())?),
            (Spec::MeterStick(p), F32, Fu) => AnyScene::MeterStickF32F(MeterStick::new(p.cast())?),
            (Spec::MeterStick(p), F64, Re) => AnyScene::MeterStickF64R(MeterStick::new(p)?),
            (Spec::MeterStick(p), F64, Fu) => AnyScene::MeterStickF64F(MeterStick::new(p)?),
            (Spec::Incline(p), F32, Re) => AnyScene::InclineF32R(Incline::new(p.cast())?),
            (Spec::Incline(p), F32, Fu) => AnyScene::InclineF32F(Incline::new(p.cast())?),
            (Spec::Incline(p), F64, Re) => AnyScene::InclineF64R(Incline::new(p)?),
            (Spec::Incline(p), F64, Fu) => AnyScene::InclineF64F(Incline::new(p)?),
            (Spec::Ladder(p), F32, Re) => AnyScene::LadderF32R(Ladder::new(p.cast())?),
            (Spec::Ladder(p), F32, Fu) => AnyScene::LadderF32F(Ladder::new(p.cast())?),
            (Spec::Ladder(p), F64, Re) => AnyScene::LadderF64R(Ladder::new(p)?),
            (Spec::Ladder(p), F64, Fu) => AnyScene::LadderF64F(Ladder::new(p)?),
            // The page draws and traces two-contact scenes ([`crate::session::Session::create`]
            // refuses the others before this).
            _ => return Err(ParamError::SupportMismatch(2)),
        };
        let mut start = [0.0; ROW];
        each!(&scene, s => start_row(s, &mut start));
        Ok(Self { scene, checksum: Checksum::new(), start })
    }

    /// The row of the state at `t = 0` (the contacts' initial modes; no impulses).
    #[must_use]
    pub const fn start_row(&self) -> &[f64; ROW] {
        &self.start
    }

    /// Steps until the run ends or `rows` is full, writing one row per step into `rows`
    /// ([`ROW`] numbers each); returns the steps taken (0 once the run has ended).
    pub fn step_rows(&mut self, rows: &mut [f64]) -> usize {
        let checksum = &mut self.checksum;
        each!(&mut self.scene, s => {
            let mut taken = 0;
            for row in rows.chunks_exact_mut(ROW) {
                let Some(report) = s.step() else { break };
                checksum.add(&report.state);
                write_row(&*s, &report, row);
                taken += 1;
            }
            taken
        })
    }

    /// Steps until the run ends or `max` steps were taken, without rows (the outcome map, the
    /// benchmark); returns the steps taken.
    pub fn run(&mut self, max: u64) -> u64 {
        let checksum = &mut self.checksum;
        each!(&mut self.scene, s => {
            let mut taken = 0;
            while taken < max {
                let Some(report) = s.step() else { break };
                checksum.add(&report.state);
                taken += 1;
            }
            taken
        })
    }

    /// The outcome, once the run has ended.
    #[must_use]
    pub fn outcome(&self) -> Option<Outcome> {
        each!(&self.scene, s => s.outcome())
    }

    /// The trajectory checksum so far (FNV-1a over the state's bits after every step).
    #[must_use]
    pub const fn checksum(&self) -> u32 {
        self.checksum.value()
    }

    /// Simulated time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        each!(&self.scene, s => s.time().as_f64())
    }

    /// The stepper's counters (steps, pivots, warm starts, 8x8 fallbacks, ...).
    #[must_use]
    pub fn stats(&self) -> RunStats {
        each!(&self.scene, s => *s.stats())
    }

    /// The scene's measured quantities so far.
    #[must_use]
    pub fn measured(&self) -> Measured {
        let mut m = Measured {
            meeting_time: f64::NAN,
            meeting_offset: f64::NAN,
            acceleration: f64::NAN,
            wall_release_height: f64::NAN,
            wall_release_ratio: f64::NAN,
        };
        let meeting = |t: f64, offset: f64, m: &mut Measured| {
            m.meeting_time = t;
            m.meeting_offset = offset;
        };
        match &self.scene {
            AnyScene::MeterStickF32R(s) => {
                s.meeting().inspect(|x| meeting(x.time.as_f64(), x.com_offset.as_f64(), &mut m));
            }
            AnyScene::MeterStickF32F(s) => {
                s.meeting().inspect(|x| meeting(x.time.as_f64(), x.com_offset.as_f64(), &mut m));
            }
            AnyScene::MeterStickF64R(s) => {
                s.meeting().inspect(|x| meeting(x.time, x.com_offset, &mut m));
            }
            AnyScene::MeterStickF64F(s) => {
                s.meeting().inspect(|x| meeting(x.time, x.com_offset, &mut m));
            }
            AnyScene::InclineF32R(s) => m.acceleration = s.acceleration().map_or(f64::NAN, Real::as_f64),
            AnyScene::InclineF32F(s) => m.acceleration = s.acceleration().map_or(f64::NAN, Real::as_f64),
            AnyScene::InclineF64R(s) => m.acceleration = s.acceleration().unwrap_or(f64::NAN),
            AnyScene::InclineF64F(s) => m.acceleration = s.acceleration().unwrap_or(f64::NAN),
            AnyScene::LadderF32R(s) => wall(s.wall_release_height(), s.start_top_height(), &mut m),
            AnyScene::LadderF32F(s) => wall(s.wall_release_height(), s.start_top_height(), &mut m),
            AnyScene::LadderF64R(s) => wall(s.wall_release_height(), s.start_top_height(), &mut m),
            AnyScene::LadderF64F(s) => wall(s.wall_release_height(), s.start_top_height(), &mut m),
        }
        m
    }
}

/// The ladder's wall release: its height and its ratio to the top's start height.
fn wall<T: Real>(height: Option<T>, start: T, m: &mut Measured) {
    if let Some(h) = height {
        m.wall_release_height = h.as_f64();
        m.wall_release_ratio = h.as_f64() / start.as_f64();
    }
}

/// Where each support touches the body: the contact point moved back by the gap along the normal
/// (a finger's tip; the foot of a corner on a line), as `host-sim` writes it.
fn touch_points<T: Real, S: Scene<T, 2>>(scene: &S, row: &mut [f64]) {
    let s = scene.state();
    for (k, f) in scene.frames().iter().enumerate() {
        let (r, n, gap) = (f.r.map(Real::as_f64), f.normal().map(Real::as_f64), f.gap.as_f64());
        row[7 + 2 * k] = s.x.as_f64() + r[0] - gap * n[0];
        row[8 + 2 * k] = s.y.as_f64() + r[1] - gap * n[1];
    }
}

fn state_columns<T: Real, S: Scene<T, 2>>(scene: &S, row: &mut [f64]) {
    let s = scene.state();
    row[0] = scene.time().as_f64();
    for (slot, v) in row[1..7].iter_mut().zip(s.to_array()) {
        *slot = v.as_f64();
    }
    touch_points(scene, row);
}

fn start_row<T: Real, S: Scene<T, 2>>(scene: &S, row: &mut [f64; ROW]) {
    state_columns(scene, row);
    for (k, m) in scene.modes().into_iter().enumerate() {
        row[11 + k] = f64::from(mode_code(m));
    }
}

fn write_row<T: Real, S: Scene<T, 2>>(scene: &S, report: &StepReport<T, 2>, row: &mut [f64]) {
    state_columns(scene, row);
    row[0] = report.time.as_f64();
    for (k, c) in report.contacts.iter().enumerate() {
        row[11 + k] = f64::from(mode_code(c.mode));
        row[13 + k] = c.normal_impulse.as_f64();
        row[15 + k] = c.friction_impulse.as_f64();
        row[17 + k] = c.along.as_f64();
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)] // exact: values copied or rounded once, not computed
    use super::*;
    use crate::config::Config;
    use crate::flags::{SceneKind, flag_index};

    fn sim(kind: SceneKind, given: &[(&str, f64)], precision: Precision, size: LcpSize) -> Sim {
        let mut c = Config::new(kind);
        for (long, v) in given {
            c.give(flag_index(long).unwrap(), *v);
        }
        Sim::new(&c.resolve(precision).unwrap(), precision, size).unwrap()
    }

    #[test]
    fn rows_and_quiet_runs_agree() {
        let slow = [("x1", -0.35)];
        let mut a = sim(SceneKind::MeterStick, &slow, Precision::F32, LcpSize::Reduced);
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
        assert!(a.measured().meeting_offset.abs() < 3e-3);
    }

    #[test]
    fn the_start_row_is_the_rest_state_with_the_initial_modes() {
        let s = sim(SceneKind::MeterStick, &[], Precision::F64, LcpSize::Full);
        let row = s.start_row();
        assert_eq!(row[..4], [0.0, 0.0, 0.0025, 0.0]);
        assert_eq!(row[7..11], [-0.4, 0.0, 0.4, 0.0]);
        // Finger 1 starts sliding under the resting rod (sliding+), finger 2 sticks.
        assert_eq!((row[11], row[12]), (2.0, 1.0));
        let ladder = sim(SceneKind::Ladder, &[("angle", 60.0)], Precision::F32, LcpSize::Reduced);
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
        ] {
            for precision in [Precision::F32, Precision::F64] {
                for size in [LcpSize::Reduced, LcpSize::Full] {
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
}
