//! One run of a scene as the host records it, whichever implementation produced it: the
//! trajectory (one [`Row`] per step), the switch events, the outcome, the scene's measured
//! quantities and counters. The core ([`run()`] with [`Implementation::Core`]) and the independent
//! reference ([`Implementation::Reference`]) both fill a [`Trajectory`], so everything downstream
//! (CSV, plots, comparison, eq. 21 ratios) has one implementation.
//!
//! This module holds the types; the rest, by concern: which rows a run keeps and how many it may
//! record (`record.rs`), running a scene in the chosen implementation (`run.rs`), the core's run
//! (`core_run.rs`), the reference's run converted (`reference_run.rs`), the eq. 21 switches and
//! the deviation between two runs (`compare.rs`), the trajectory and event CSVs (`csv.rs`).

mod compare;
mod core_run;
mod csv;
mod record;
mod reference_run;
mod run;

use std::fmt;

use meterstick_core::planar::{ContactMode, RunStats};
use meterstick_core::scene::{MAX_MEASURES, Outcome};
use serde::Serialize;

use crate::scenes::{Implementation, SceneKind};

pub use compare::{Switch, max_deviation, switches};
pub use core_run::run_core;
pub use csv::{csv_header, write_csv, write_events_csv};
pub use record::{MAX_RECORDED_STEPS, Record, Recorder, check_recorded_steps, check_total_recorded_steps};
pub use reference_run::run_reference;
pub use run::{UnrecordedContacts, run, run_k, run_watched};

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

/// How a run ended, by kind: the core's one list of outcomes.
pub use meterstick_core::scene::OutcomeKind;

/// How a run ended: its class, and for a failure why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct RunOutcome {
    /// The class.
    pub class: OutcomeKind,
    /// Why it failed (`None` unless [`OutcomeKind::Failed`]).
    pub detail: Option<String>,
}

impl RunOutcome {
    /// A physical outcome.
    #[must_use]
    pub const fn of(class: OutcomeKind) -> Self {
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
            Outcome::Failed(e) => Self { class: OutcomeKind::Failed, detail: Some(e.to_string()) },
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
    /// Cylinder: the angular acceleration after the first step, counter-clockwise (rad/s^2;
    /// absent from `summary.json` for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angular_acceleration_rad_s2: Option<f64>,
    /// Ladder: height of the top when it left the wall (m).
    pub wall_release_height_m: Option<f64>,
    /// Ladder: that height over the top's initial height (2/3 when frictionless).
    pub wall_release_ratio: Option<f64>,
    /// Painlevé: the jam step's impulses (absent from `summary.json` for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jam: Option<JamImpulses>,
    /// Block-on-block: the top block's acceleration along `x` while both blocks are in full
    /// contact (`acceleration_m_s2` is the bottom block's); disc-on-board: the disc centre's while
    /// the board and the rim touch (`acceleration_m_s2` the board's); m/s^2; absent for other
    /// scenes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub top_acceleration_m_s2: Option<f64>,
    /// Tablecloth: the block's displacement along `x` at the end (m; absent for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub block_displacement_m: Option<f64>,
    /// Stack: the largest `|(vx, vy)| + reach |omega|` over the run and the blocks (m/s; absent
    /// for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_speed_m_s: Option<f64>,
    /// Puck: its speed at the end (m/s; absent for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_speed_m_s: Option<f64>,
    /// Puck: how far it ended from its start (m; absent for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub displacement_m: Option<f64>,
    /// Puck: the heading of its displacement, from `x` toward down the slope (degrees; absent
    /// for other scenes and before it moved).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub displacement_heading_deg: Option<f64>,
    /// Billiard: when it started rolling (s; absent for other scenes and before it rolled).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolling_time_s: Option<f64>,
    /// Billiard: its velocity along `x` then (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolling_velocity_x_m_s: Option<f64>,
    /// Billiard: its velocity along `y` then (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolling_velocity_y_m_s: Option<f64>,
    /// Curling: `v / (R omega)` ten steps of friction before the end (absent for other scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub terminal_ratio: Option<f64>,
    /// Curling: when it stopped sliding (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slide_stop_s: Option<f64>,
    /// Curling: when it stopped spinning (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spin_stop_s: Option<f64>,
}

impl Measured {
    /// The typed summary of what a scene of `kind` measured: `values` in the order of its
    /// catalogue entry's `measures` ([`meterstick_core::scene::Scene::measured`]).
    #[must_use]
    pub fn of(kind: SceneKind, values: [Option<f64>; MAX_MEASURES]) -> Self {
        let [a, b, c] = values;
        let mut m = Self::default();
        match kind {
            SceneKind::MeterStick | SceneKind::MeterStick3d => {
                m.meeting = a.zip(b).map(|(time_s, com_offset_m)| Meeting { time_s, com_offset_m });
            }
            SceneKind::Incline => m.acceleration_m_s2 = a,
            SceneKind::Ladder => (m.wall_release_height_m, m.wall_release_ratio) = (a, b),
            SceneKind::ThreeFingers => {}
            SceneKind::Cylinder => (m.acceleration_m_s2, m.angular_acceleration_rad_s2) = (a, b),
            SceneKind::Painleve => {
                m.jam = a.zip(b).zip(c).map(|((time_s, normal_impulse_n_s), friction_impulse_n_s)| {
                    JamImpulses { time_s, normal_impulse_n_s, friction_impulse_n_s }
                });
            }
            SceneKind::BlockOnBlock | SceneKind::DiscOnBoard => {
                (m.acceleration_m_s2, m.top_acceleration_m_s2) = (a, b);
            }
            SceneKind::Tablecloth => m.block_displacement_m = a,
            SceneKind::Stack | SceneKind::Stack3d => m.max_speed_m_s = a,
            SceneKind::Puck => (m.final_speed_m_s, m.displacement_m, m.displacement_heading_deg) = (a, b, c),
            SceneKind::Billiard => {
                (m.rolling_time_s, m.rolling_velocity_x_m_s, m.rolling_velocity_y_m_s) = (a, b, c);
            }
            SceneKind::Curling => (m.terminal_ratio, m.slide_stop_s, m.spin_stop_s) = (a, b, c),
        }
        m
    }

    /// The values [`Self::of`] was given for a scene of `kind`, in the order of its catalogue
    /// entry's `measures`.
    #[must_use]
    pub fn values(&self, kind: SceneKind) -> [Option<f64>; MAX_MEASURES] {
        let m = self;
        match kind {
            SceneKind::MeterStick | SceneKind::MeterStick3d => {
                [m.meeting.map(|x| x.time_s), m.meeting.map(|x| x.com_offset_m), None]
            }
            SceneKind::Incline => [m.acceleration_m_s2, None, None],
            SceneKind::Ladder => [m.wall_release_height_m, m.wall_release_ratio, None],
            SceneKind::ThreeFingers => [None; MAX_MEASURES],
            SceneKind::Cylinder => [m.acceleration_m_s2, m.angular_acceleration_rad_s2, None],
            SceneKind::Painleve => [
                m.jam.map(|j| j.time_s),
                m.jam.map(|j| j.normal_impulse_n_s),
                m.jam.map(|j| j.friction_impulse_n_s),
            ],
            SceneKind::BlockOnBlock | SceneKind::DiscOnBoard => {
                [m.acceleration_m_s2, m.top_acceleration_m_s2, None]
            }
            SceneKind::Tablecloth => [m.block_displacement_m, None, None],
            SceneKind::Stack | SceneKind::Stack3d => [m.max_speed_m_s, None, None],
            SceneKind::Puck => [m.final_speed_m_s, m.displacement_m, m.displacement_heading_deg],
            SceneKind::Billiard => [m.rolling_time_s, m.rolling_velocity_x_m_s, m.rolling_velocity_y_m_s],
            SceneKind::Curling => [m.terminal_ratio, m.slide_stop_s, m.spin_stop_s],
        }
    }
}

/// The Painlevé rod's jam: the step on which the sliding end stopped.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JamImpulses {
    /// The end of that step (s).
    pub time_s: f64,
    /// Its normal impulse (N s).
    pub normal_impulse_n_s: f64,
    /// Its friction impulse along `+x` (N s).
    pub friction_impulse_n_s: f64,
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
    /// Steps whose LCP had solutions with different motions (reference; core: of the steps its
    /// rule enumerated).
    pub ambiguous_steps: u64,
    /// Steps the core's rule looked at (flagged as possibly having several answers; core).
    pub rule_checked_steps: u64,
    /// Of those, steps whose solutions it enumerated (the solver's answer not at rest; core).
    pub rule_enumerated_steps: u64,
    /// Steps where the rule's choice moved the body differently from the answer the solver's
    /// path reached first (core).
    pub rule_changed_answer: u64,
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
    /// The warning a run with [`Self::round_off_limited`] steps gets, in the user's flags. With
    /// `friction_beyond` (the run's friction is beyond its precision,
    /// [`crate::scenes::friction_warning`]) the cause named is that, not `speed / (g h)`: the
    /// flagged steps' speeds are then what the unresolved friction made of the motion.
    #[must_use]
    pub fn round_off_warning(&self, steps: u64, friction_beyond: bool) -> Option<String> {
        (self.round_off_limited > 0).then(|| {
            let cause = if friction_beyond {
                "the friction above, beyond this precision: the speeds follow from it; use --precision f64"
            } else {
                "speed / (g h) too large for this precision: beyond the measured f32 envelope, \
                 `host-sim envelope`; use a larger --h or --precision f64"
            };
            format!(
                "warning: {} of {steps} steps resolved their impulses only to more than {:e} of their size \
                 ({cause})",
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
            ambiguous_steps: s.ambiguous_steps,
            rule_checked_steps: s.rule_checked_steps,
            rule_enumerated_steps: s.rule_enumerated_steps,
            rule_changed_answer: s.rule_changed_answer,
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
