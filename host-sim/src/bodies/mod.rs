//! The scenes recorded body by body ([`runs`]: every scene but one body on its supports; today
//! those of several bodies, `docs/scenes.md`, "Scenes of several bodies", and in three dimensions,
//! "Scenes in three dimensions"), in `host-sim`: a run in the core ([`run_core`], through the core's one scene interface,
//! [`SceneView`](meterstick_core::scene::SceneView), its pair forces and loads the view's figures) or
//! in the independent reference ([`run_reference`], `meterstick_reference::multibody::run`), recorded as a
//! [`BodiesRun`] (every body's state after every step, the outcome, what the scene measures, the
//! solver's counters); the laws of `docs/scenes.md` ([`law`]); what `host-sim scene` prints
//! ([`summarise`]) and `host-sim run` writes ([`run_all`]: the trajectories as CSV, the plots, the
//! summaries, the deviation between two runs); f32's measured reach over mass ratio and the typed
//! warning a run beyond it gets ([`warnings`]). `host-sim map` drives them too (`host-sim stress`
//! through `crate::stress::bodies`).
//!
//! * `core_run.rs`, `reference_run.rs`: one run in each implementation.
//! * `law.rs`: the laws.
//! * `reach.rs`: where f32 follows f64 over mass ratio, and the warning beyond it.
//! * `report.rs`: `scene`'s text, `run`'s summaries and text.
//! * `csv.rs`, `plots.rs`: `run`'s files.

mod core_run;
mod csv;
pub(crate) use csv::write_trajectory;
mod law;
mod plots;
mod reach;
mod reference_run;
mod report;

use meterstick_core::scene::SceneKind;
use serde::Serialize;

use crate::trajectory::{Measured, RunOutcome};

pub use core_run::run_core;
pub use law::{Law, disc_on_board_law, law};
pub use reach::{BodiesWarning, F32_MASS_RATIO_REACH, MassRatioReach, warnings};
pub use reference_run::{has_reference, run_reference, stack_3d_reference, to_reference};

/// `true` for a scene this module records: every scene but one body on a fixed list of supports
/// (its catalogue row's [`SceneKind::contacts`], 1 to 3), which `crate::trajectory` records with
/// each support's touch point and switch events. The choice is the record's shape, not the
/// engine's: a scene of a new engine is recorded here with no change.
#[must_use]
pub const fn runs(kind: SceneKind) -> bool {
    kind.contacts() == 0
}
pub use report::{
    BodiesComparison, BodiesImplementation, BodiesSummary, LawSummary, max_deviation, run_all, summarise,
};

/// Every body's state after one step (row 0: the start).
#[derive(Debug, Clone, PartialEq)]
pub struct BodiesRow {
    /// Time at the end of the step (s).
    pub t: f64,
    /// Each body's `(x, y, theta)` (m, m, rad), body 0 the lowest.
    pub q: Vec<[f64; 3]>,
    /// Each body's `(vx, vy, omega)`.
    pub v: Vec<[f64; 3]>,
    /// Each pair's summed contact force on its upper body over the step, world `(x, y)` (N; row 0:
    /// zero).
    pub interface_forces: Vec<[f64; 2]>,
    /// Each pair's four candidate contacts' normal and friction force over the step (N, along
    /// each candidate's normal and its `+d`; zero when not in the step's LCP): the upper body's
    /// lower-left and lower-right corners on the lower one, then the lower body's upper-left and
    /// upper-right corners (the table's ends) on the upper one; where rigid contact leaves the
    /// split open, the least-norm load (`docs/formulation.md`, "The load: the least norm"). Row
    /// 0: zero.
    pub corner_loads: Vec<[[f64; 2]; 4]>,
    /// Each body in three dimensions (a scene in three dimensions' bodies: `q` and `v` then hold
    /// none).
    pub spatial: Vec<SpatialBody>,
    /// A scene in three dimensions' contacts, each over the step (none for a planar scene).
    pub contacts: Vec<ContactRow>,
}

/// A body in three dimensions after a step (world axes, `z` up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialBody {
    /// Its centre of mass (m).
    pub position: [f64; 3],
    /// Its orientation, the unit quaternion `[w, x, y, z]`.
    pub orientation: [f64; 4],
    /// Its centre of mass's velocity (m/s).
    pub velocity: [f64; 3],
    /// Its angular velocity (rad/s).
    pub angular: [f64; 3],
}

/// A contact of a scene in three dimensions over a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRow {
    /// Its mode after the step: 0 separated, 1 sticking, 2 sliding.
    pub mode: u8,
    /// Its point (m, world).
    pub point: [f64; 3],
    /// The normal impulse (N s).
    pub normal_impulse: f64,
    /// The friction impulse on the body (N s, world).
    pub friction_impulse: [f64; 3],
}

/// A run's solver counters (zero where an implementation has no such thing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct BodiesCounters {
    /// Lemke pivots in all (core).
    pub pivots: u64,
    /// Most pivots in one step (core).
    pub max_pivots: u32,
    /// Steps the warm basis solved without a pivot (core).
    pub warm_direct: u32,
    /// The most candidate contacts one step's LCP held (core; `None` for an engine whose every
    /// step's LCP holds all its contacts, `RunStats::most_lcp_contacts`).
    pub max_active: Option<u8>,
    /// The LCP's capacity (core) or its largest size (reference), rows.
    pub lcp_rows: usize,
    /// Steps whose verified solutions moved the bodies differently (reference; core: of the
    /// steps its rule enumerated).
    pub ambiguous_steps: u64,
    /// Steps the core's rule looked at: not at rest and flagged as possibly having several
    /// answers (core; `docs/formulation.md`, "One answer: the rule").
    pub rule_checked_steps: u64,
    /// Of those, steps whose solutions it enumerated (core).
    pub rule_enumerated_steps: u64,
    /// Steps where the rule's choice moved the bodies differently from the answer the solver's
    /// path reached first (core).
    pub rule_changed_answer: u64,
}

/// One run of a scene of several bodies, recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct BodiesRun {
    /// Who computed it: `core f32`, `reference f64`.
    pub label: String,
    /// Which scene.
    pub scene: SceneKind,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time at the end (s).
    pub end_time: f64,
    /// The recorded rows (all, or none: [`Self::last`] is kept either way).
    pub rows: Vec<BodiesRow>,
    /// The state at the end.
    pub last: BodiesRow,
    /// How it ended.
    pub outcome: RunOutcome,
    /// What the scene measures.
    pub measured: Measured,
    /// Solver counters.
    pub counters: BodiesCounters,
    /// The trajectory checksum over every step's states of all bodies in body order
    /// ([`meterstick_core::multibody::SystemStepReport::add_to`]: the firmware's fingerprint; the core's
    /// runs only).
    pub checksum: Option<u32>,
}
