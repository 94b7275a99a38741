//! An independent f64 reference of the planar contact scenes: the model of docs/formulation.md
//! and the scenes of docs/scenes.md (`meter-stick`, `incline`, `ladder`, `three-fingers`,
//! `cylinder`, `painleve`), written again from
//! those two texts and sharing no code with `meterstick-core` (this crate has no dependencies:
//! the crate graph shows it), to catch formulation and precision errors in it. Its exhaustive
//! LCP enumerator ([`enumerate`]) is also the integration tests' check of the core's solver.
//!
//! # The model (docs/formulation.md)
//!
//! One planar rigid body, `q = (x, y, theta)`, `v = (vx, vy, omega)`, `M = diag(m, m, J)`
//! (eq. 2), gravity `g` along `-y`, against `K` contacts whose supports the scene moves
//! (`geometry.rs`: a support point under the body's lower face, a body point on a support line,
//! or the body's round rim on a support line).
//! Each step of length `h` solves the LCP of eqs. 13-18 in impulse-velocity form
//! (`step.rs`):
//!
//! ```text
//! M (v+ - v) = h w_ext + sum_k (W_n p_n + W_f p_f)                          (eq. 14)
//! rho_n = W_n^T v+ - n . u + beta(psi)  >= 0  _|_  p_n   >= 0                (eq. 13)
//! rho_f = +-(W_d^T v+ - d . u) + sigma  >= 0  _|_  p_f   >= 0   (+d and -d)
//! s     = mu p_n - p_+d - p_-d          >= 0  _|_  sigma >= 0
//! q+    = q + h v+
//! ```
//!
//! **How this differs from `core`** (on purpose, so the two fail differently):
//! * **Sizes.** Only the `k` active contacts enter the LCP, always with the paper's full form (two
//!   friction directions and one `sigma` per contact): the LCP is `4k x 4k`. `core` keeps every
//!   contact (inactive ones decoupled) and may drop a friction direction.
//! * **Units.** Assembled per unit mass (`M~ = m M^-1 = diag(1, 1, m/J)`), the impulses reported
//!   physical (N s).
//! * **Solver.** Exhaustive enumeration of all `2^n` complementary bases (`enumerate.rs`) instead of
//!   Lemke's method; among several solutions the least kinetic energy after the step, ties
//!   (energies within round-off) by the smallest `||z||_1` (within round-off), then by the lowest
//!   basis; a step whose
//!   solutions move the body differently (by more than `1e-9` of the speed scale) counts as
//!   *ambiguous*.
//! * **Integration.** Plain f64 sums for `q+ = q + h v+` (`core` compensates its f32 sums);
//!   time after `n` steps is `n h`.
//!
//! The model's choices beyond the paper, all from docs/formulation.md: `mu_s` for a contact that
//! was sticking or separated after the previous step, `mu_k` for one that was sliding; a penetration
//! is pushed out at most at the speed of a fall through it, `beta = max(psi / h, -sqrt(2 g
//! |psi|))`; after a step a contact is separated when inactive or its normal impulse per unit mass
//! is at most `64 eps g h` (the round-off of one step's gravity impulse; docs/formulation.md, "Precision": not `eps V`), else sticking when its slip `|d . (u - v_P)|` is at most
//! `stick_speed`, else sliding in the direction of the slip; the modes before the first step come
//! from the slip of the supports' initial velocities against the body's start velocity (at rest
//! but in painleve).
//!
//! # The scenes (docs/scenes.md)
//!
//! [`MeterStick`], [`Incline`], [`Ladder`], [`ThreeFingers`], [`Cylinder`] and [`Painleve`] hold
//! each scene's parameters (defaults as docs/scenes.md, angles in radians); [`run`] validates them
//! and steps the scene to its outcome (`simulate.rs` the loop; `scenes.rs` and `other_scenes.rs`
//! the start states, support motions, outcome rules and measurements).
//!
//! # Three dimensions ([`spatial`])
//!
//! The first spatial scenes, `puck` and `billiard` (docs/scenes.md, "Scenes in three
//! dimensions"), on docs/formulation.md's "Three dimensions": one body with six degrees of freedom
//! touching a plane at one point, Coulomb's circular cone. Where the core solves each step as an
//! LCP over one friction line turned to the slip, [`spatial`] solves the one contact exactly by
//! cases (separated; sticking, `W p = -u` by `L D L^T`; sliding, in closed form for an isotropic
//! uncoupled Delassus matrix and otherwise by a safeguarded Newton search over the slip's angle
//! that asserts a unique answer), with its own vector, matrix and quaternion algebra.

pub mod enumerate;
mod geometry;
mod load;
pub mod multibody;
mod other_scenes;
mod scenes;
mod simulate;
pub mod spatial;
mod step;
#[cfg(test)]
mod tests;

pub use other_scenes::{Cylinder, Painleve, ThreeFingers};
pub use scenes::{Incline, Ladder, MeterStick};

use std::sync::atomic::{AtomicBool, Ordering};

/// How often (in steps) a run looks whether a stop was requested.
pub const CHECK_EVERY_STEPS: u64 = 4096;

static STOP: AtomicBool = AtomicBool::new(false);

/// Asks every run under way (and every later one) to stop at its next check: it ends
/// [`Outcome::Failed`] ("interrupted"). For a host's Ctrl-C (`host-sim`'s `progress.rs`).
pub fn request_stop() {
    STOP.store(true, Ordering::SeqCst);
}

/// `true` once a stop was requested.
#[must_use]
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}

/// A scene and its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spec {
    /// docs/scenes.md, "meter-stick".
    MeterStick(MeterStick),
    /// docs/scenes.md, "incline".
    Incline(Incline),
    /// docs/scenes.md, "ladder".
    Ladder(Ladder),
    /// docs/scenes.md, "three-fingers".
    ThreeFingers(ThreeFingers),
    /// docs/scenes.md, "cylinder".
    Cylinder(Cylinder),
    /// docs/scenes.md, "painleve".
    Painleve(Painleve),
}

/// A contact's mode after a step (docs/formulation.md, "Friction and contact modes").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Inactive, or its normal impulse at most the floor.
    Separated,
    /// Touching with a slip of at most `stick_speed`.
    Sticking,
    /// Sliding: the support moves along `+d` relative to the body.
    SlidingPositive,
    /// Sliding: the support moves along `-d` relative to the body.
    SlidingNegative,
}

impl Mode {
    /// Whether the contact slides (either way).
    #[must_use]
    pub fn is_sliding(self) -> bool {
        matches!(self, Self::SlidingPositive | Self::SlidingNegative)
    }
}

/// How a run ended (docs/scenes.md, each scene's "Outcome").
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// Meter stick: the fingers met and the rod rests on both, its centre of mass between them.
    Balanced,
    /// Meter stick: tilted, dropped or off both fingers; three-fingers: tilted or off every
    /// finger; ladder: the upper end reached the floor; painleve: the rod lay down or its centre
    /// of mass reached the floor.
    Fell,
    /// Incline, ladder: at `max_time` without any contact ever sliding; three-fingers: finger 1
    /// stopped at least `hold_time` ago.
    Held,
    /// Incline, cylinder: at `max_time` after a contact slid; painleve: at `max_time` with the
    /// end sliding.
    Slid,
    /// Cylinder: at `max_time` without ever sliding (it rolled).
    Rolled,
    /// Painleve: the end, sliding before a step, sticks after it under an impact (a contact
    /// impulse more than twice the previous step's and the weight's).
    Jammed,
    /// Incline: the centre of mass passed over a lower corner.
    Tipped,
    /// `max_time` reached and no other outcome applies.
    Unfinished,
    /// A step's LCP had no solution among the complementary bases, or the state became non-finite.
    Failed(String),
}

/// One contact in a recorded row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Mode after the step (row 0: the initial mode).
    pub mode: Mode,
    /// Normal impulse over the step, N s (0 in row 0 and when inactive).
    pub normal_impulse: f64,
    /// Net friction impulse over the step along `+d`, N s.
    pub friction_impulse: f64,
    /// Coordinate along the contact at the step's start, m (row 0: at `t = 0`).
    pub along: f64,
    /// Whether the contact was active at the step's start, i.e. entered its LCP (row 0: at `t = 0`).
    pub active: bool,
}

/// The state after one step (or the start, row 0).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// `t = n h`, s.
    pub t: f64,
    /// `(x, y, theta)` at `t`.
    pub q: [f64; 3],
    /// `(vx, vy, omega)` at `t` (the step's `v+`).
    pub v: [f64; 3],
    /// Each contact's support point at `t`, world: the finger tip, or for a support line the foot
    /// of the body point on the line.
    pub supports: Vec<[f64; 2]>,
    /// Each contact over the step.
    pub contacts: Vec<Contact>,
}

/// A switch event: a contact's mode after a step differs from its mode before it.
#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    /// The step's end, s.
    pub t: f64,
    /// The contact, 0-based.
    pub contact: usize,
    /// Its mode after the step.
    pub mode: Mode,
    /// Every contact's coordinate along it at the step's start, m.
    pub along: Vec<f64>,
}

/// Which rows a run keeps. Row 0 (the start: impulses 0, the initial modes, `along` at `t = 0`)
/// is always kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sample {
    /// Every step's row.
    All,
    /// The rows of steps `n, 2n, 3n, ...` (`Every(0)` keeps none).
    Every(u64),
    /// No step's row.
    None,
}

/// A finished run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The kept rows ([`Sample`]).
    pub rows: Vec<Row>,
    /// Each contact's mode before the first step.
    pub initial_modes: Vec<Mode>,
    /// Every switch event, in order (contacts in order within a step).
    pub events: Vec<Event>,
    /// How it ended.
    pub outcome: Outcome,
    /// Steps taken (a failed step is not counted).
    pub steps: u64,
    /// `steps h`, s.
    pub end_time: f64,
    /// Meter stick: `(time, com_offset)` of the first step that ended with the fingers stopped.
    pub meeting: Option<(f64, f64)>,
    /// Incline: the acceleration down the slope, m/s^2, for a run that ended [`Outcome::Slid`];
    /// cylinder: the same after the first step, for a run that ended [`Outcome::Rolled`] or
    /// [`Outcome::Slid`].
    pub acceleration: Option<f64>,
    /// Cylinder: the angular acceleration (counter-clockwise) after the first step, rad/s^2, for
    /// a run that ended [`Outcome::Rolled`] or [`Outcome::Slid`].
    pub angular_acceleration: Option<f64>,
    /// Ladder: the upper end's height at the end of the first step after which the wall contact
    /// was separated having touched before it, m.
    pub wall_release_height: Option<f64>,
    /// Painleve: the jam step's end time (s), normal impulse and friction impulse along `+x`
    /// (N s).
    pub jam: Option<Jam>,
    /// Steps whose LCP had solutions with different motions.
    pub ambiguous_steps: u64,
    /// The end time of the first such step, s.
    pub first_ambiguous: Option<f64>,
}

/// Painleve's jam (docs/scenes.md, "painleve", "Measured"): the step on which the sliding end
/// stuck.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jam {
    /// The step's end, s.
    pub t: f64,
    /// Its normal impulse, N s.
    pub normal_impulse: f64,
    /// Its friction impulse along `+d = +x`, N s.
    pub friction_impulse: f64,
}

/// A stick-to-slip switch of the meter stick's switch law (eq. 21, docs/scenes.md
/// "meter-stick", "Measured"): a contact sticking before a step slides after it while the other
/// contact was sliding before it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    /// The step's end, s.
    pub t: f64,
    /// The contact that starts to slide, 0-based.
    pub contact: usize,
    /// Its coordinate along it at the step's start (`x_start`), m.
    pub along_this: f64,
    /// The other contact's coordinate at the step's start (`x_stop`), m.
    pub along_other: f64,
    /// `|along_other / along_this|`, to compare with `mu_k / mu_s`.
    pub ratio: f64,
}

/// Validates `spec` (the validity rules of docs/scenes.md) and runs it to its outcome, keeping
/// the rows `sample` asks for.
///
/// # Errors
/// A broken validity rule, naming its parameter.
pub fn run(spec: &Spec, sample: Sample) -> Result<Run, String> {
    Ok(match *spec {
        Spec::MeterStick(p) => {
            p.validate()?;
            simulate::simulate(&mut scenes::MeterStickScene::new(p), &sample)
        }
        Spec::Incline(p) => {
            p.validate()?;
            simulate::simulate(&mut scenes::InclineScene::new(p), &sample)
        }
        Spec::Ladder(p) => {
            p.validate()?;
            simulate::simulate(&mut scenes::LadderScene::new(p), &sample)
        }
        Spec::ThreeFingers(p) => {
            p.validate()?;
            simulate::simulate(&mut other_scenes::ThreeFingersScene::new(p), &sample)
        }
        Spec::Cylinder(p) => {
            p.validate()?;
            simulate::simulate(&mut other_scenes::CylinderScene::new(p), &sample)
        }
        Spec::Painleve(p) => {
            p.validate()?;
            simulate::simulate(&mut other_scenes::PainleveScene::new(p), &sample)
        }
    })
}

/// The eq. 21 switches of a two-contact run, from its initial modes and events (empty for any
/// other number of contacts).
#[must_use]
pub fn eq21_switches(run: &Run) -> Vec<Switch> {
    let mut modes = run.initial_modes.clone();
    if modes.len() != 2 {
        return Vec::new();
    }
    let mut switches = Vec::new();
    let mut first = 0;
    while first < run.events.len() {
        // The events of one step share its end time (n h, computed once per step).
        let t = run.events[first].t;
        let last = first + run.events[first..].iter().take_while(|e| e.t.to_bits() == t.to_bits()).count();
        let before = modes.clone();
        for event in &run.events[first..last] {
            let this = event.contact;
            if this > 1 {
                continue;
            }
            let other = 1 - this;
            if before[this] == Mode::Sticking && event.mode.is_sliding() && before[other].is_sliding() {
                let (along_this, along_other) = (event.along[this], event.along[other]);
                switches.push(Switch {
                    t,
                    contact: this,
                    along_this,
                    along_other,
                    ratio: (along_other / along_this).abs(),
                });
            }
            modes[this] = event.mode;
        }
        first = last;
    }
    switches
}
