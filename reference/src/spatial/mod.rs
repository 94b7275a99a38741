//! The scenes in three dimensions, `puck`, `billiard`, `curling`, `meter-stick-3d` and `stack-3d`
//! (docs/scenes.md, "Scenes in three dimensions"; the curling stone's step in `curling.rs`, a
//! minimisation of its own; the meter stick's three contacts in `meter_stick.rs`, by the
//! several-contact cone of `cone.rs`; the stack's blocks in `stack.rs`, sticking or separating), on
//! the spatial model of docs/formulation.md ("Three dimensions"), written again from those texts and
//! sharing no code with `meterstick-core`'s `spatial` module.
//!
//! # The model
//!
//! One body of mass `m` and principal moments `I` at `x`, turned by the unit quaternion `q`
//! (`[w, x, y, z]`, body to world), moving at `v` and `omega` (world axes, `z` up), touching a
//! fixed plane of unit normal `n` at one point, offset `r` from the centre of mass. Over a step
//! `h` (`step.rs`):
//!
//! ```text
//! v~ = v + h g,  omega~ = omega
//! u  = v~ + omega~ x r + beta(psi') n              (psi the gap, shrunk by its round-off)
//! W  = I3 + m [r]x^T I_w^-1 [r]x                   (per unit mass, I_w^-1 = R diag(1/I) R^T)
//! p  : the contact's impulse per unit mass          (contact.rs: by cases, the circular cone)
//! v+ = v~ + p,  omega+ = omega~ + m I_w^-1 (r x p),  x+ = x + h v+
//! q+, omega: the midpoint rule on L = I_w(q) omega+ (equal moments: a turn by h omega+)
//! ```
//!
//! The contact enters the step when its gap is at most `1e-3` m; `mu` is `mu_k` after a sliding
//! step and `mu_s` on the first step and after any other. After the step the contact is
//! *separated* when it did not enter or its normal impulse per unit mass is at most `64 eps g h`,
//! else *sticking* when its slip `|(v+ + omega+ x r)_t|` is at most `stick_speed`, else
//! *sliding*. Time after `n` steps is `n h`; positions are plain f64 sums.
//!
//! **How this differs from the core** (on purpose): the core solves each step as an LCP over one
//! friction line turned toward the slip (Lemke's method, Newton's turns of the line); here the one
//! contact is solved exactly by cases (`contact.rs`): separated, sticking by an `L D L^T` solve
//! of `W p = -u`, sliding in closed form for an isotropic uncoupled `W` (a sphere, a point under
//! the centre of mass) and otherwise by a root search over the slip's angle with an asserted
//! unique answer. Rotations go through matrices, not quaternion sandwiches. Only the circular
//! cone: no pyramid baseline.
//!
//! # The scenes
//!
//! [`Puck`] and [`Billiard`] hold the parameters (docs' defaults, SI units, angles in radians);
//! [`run_puck`] and [`run_billiard`] validate them and step to the outcome (`scenes.rs`),
//! keeping every step's [`Row`] (row 0 the start). A run longer than [`MAX_STEPS`] steps is
//! refused ([`Error::TooManySteps`]): a full trajectory costs about 160 bytes a step.
//!
//! [`MeterStick3d`] (a rod on two fingers in space, `run_meter_stick_3d_keeping`) touches at three
//! points, the pad's two and finger 2's, not in a line: each step's contacts are solved by cases
//! (`cone.rs`): every combination of each point's case (apart, stuck, sliding), its linear system by
//! the singular value decomposition (stuck points' internal forces move nothing: the least-norm
//! impulses, moved along those forces into their cones where they leave them), the sliding
//! directions by Newton's method on their angles, the first combination whose answer meets the
//! circular cone's conditions taken (the step before's cases tried first). It keeps the rod's
//! [`Row`]s and each point's [`RodPoint`].
//!
//! [`Stack3d`] (`run_stack_3d_keeping`) is several blocks, each pair's contacts the vertices of its
//! faces' overlap; each step's loads by the active-set method of nonnegative least squares over the
//! contacts' three rows, every loaded contact stuck (a step in which one would slide is refused,
//! [`Error::Sliding`]): `stack.rs`'s module docs.
//!
//! [`OnePoint`] opens the same step for a point fixed in the body off its centre of mass (a box's
//! corner), where `W` couples the normal and the slip and the sliding case takes the root search:
//! `tests/tests/spatial_reference.rs` steps it beside the core.

mod algebra;
mod cone;
#[cfg(test)]
mod cone_tests;
mod contact;
mod curling;
mod dense;
mod fingers;
mod meter_stick;
#[cfg(test)]
mod meter_stick_tests;
mod scenes;
mod stack;
#[cfg(test)]
mod stack_tests;
mod step;
#[cfg(test)]
mod tests;

pub use contact::ContactError;
pub use curling::{CURLING_QUANTITIES, Curling, MOST_POINTS, run_curling_keeping};
pub use meter_stick::{
    METER_STICK_3D_QUANTITIES, MeterStick3d, MeterStick3dRun, ROD_POINTS, RodPoint,
    run_meter_stick_3d_keeping,
};
pub use scenes::{
    BILLIARD_QUANTITIES, Billiard, Keep, OnePoint, PUCK_QUANTITIES, Puck, run_billiard, run_billiard_keeping,
    run_puck, run_puck_keeping,
};
pub use stack::{
    Block as StackBlock, Contact as StackContact, LOAD_SETS, Stack3d, StackRun, contacts as stack_contacts,
    run_stack_3d_keeping,
};

/// The most steps a run may take (`ceil(max_time / h)`): `10^7`.
pub const MAX_STEPS: u64 = 10_000_000;

/// The contact's mode after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Out of the margin, or a normal impulse per unit mass of at most `64 eps g h`.
    Separated,
    /// Loaded, slipping at most `stick_speed`.
    Sticking,
    /// Loaded, slipping faster; friction against the slip.
    Sliding,
}

/// How a run ended (docs/scenes.md, each scene's "Outcome").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Puck: the contact sticking after a step.
    Stopped,
    /// Puck: at `max_time` still moving.
    Slid,
    /// Billiard: the contact sticking after a step (the ball rolls).
    Rolled,
    /// Billiard, meter stick: at `max_time` without another outcome.
    Unfinished,
    /// Meter stick: the fingers met under the centre of mass and every point stayed on for
    /// `hold_time`.
    Balanced,
    /// Meter stick: the face tilted or the centre of mass dropped past its limit, or no finger
    /// is under the rod; stack: a block tilted or dropped past its limit.
    Fell,
    /// Stack: at `max_time`, no block tilted or dropped past its limit.
    Held,
}

/// The state after a step (row 0: the start, separated, no impulse).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// `n h`, s.
    pub t: f64,
    /// Centre of mass, m.
    pub position: [f64; 3],
    /// Body to world, `[w, x, y, z]`.
    pub orientation: [f64; 4],
    /// m/s.
    pub velocity: [f64; 3],
    /// rad/s, world axes.
    pub angular_velocity: [f64; 3],
    /// The contact's mode after the step.
    pub mode: Mode,
    /// Normal impulse over the step, N s.
    pub normal_impulse: f64,
    /// Friction impulse on the body over the step, N s, world axes.
    pub friction_impulse: [f64; 3],
}

/// A finished run.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialRun {
    /// How it ended.
    pub outcome: Outcome,
    /// The measured quantities in the docs' order ([`PUCK_QUANTITIES`], [`BILLIARD_QUANTITIES`]);
    /// `None` where the docs define none.
    pub measured: [Option<f64>; 3],
    /// Steps taken.
    pub steps: u64,
    /// Row `k` after `k` steps: `steps + 1` rows.
    pub trajectory: Vec<Row>,
}

/// Which rule a parameter breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// Not finite.
    NotFinite,
    /// Must be `> 0`.
    NotPositive,
    /// Must be `>= 0`.
    Negative,
    /// `mu_k` above `mu_s`.
    KineticAboveStatic,
    /// `h` above `max_time`.
    StepAboveMaxTime,
    /// `angle` outside `[0, 90 deg)`.
    OutOfRange,
}

/// Why a run could not be made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Error {
    /// A parameter breaks a validity rule.
    Invalid {
        /// The parameter's field name.
        field: &'static str,
        /// The rule.
        rule: Rule,
    },
    /// `ceil(max_time / h)` steps, more than [`MAX_STEPS`].
    TooManySteps {
        /// The steps the run would take.
        steps: f64,
    },
    /// A step's contact had no answer.
    Contact {
        /// The step (1 the first).
        step: u64,
        /// Why.
        error: ContactError,
    },
    /// Stack: a step in which a loaded contact would slide (its friction beyond `mu p_n` if it
    /// stuck): beyond the cases the stack's reference answers.
    Sliding {
        /// The step (1 the first).
        step: u64,
    },
    /// Stack: a step whose contacts' problem found no verified answer.
    Unsolved {
        /// The step (1 the first).
        step: u64,
    },
    /// A step's state was not finite.
    NonFinite {
        /// The step (1 the first).
        step: u64,
    },
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Invalid { field, rule } => write!(f, "{field}: {rule:?}"),
            Self::TooManySteps { steps } => write!(f, "{steps} steps, more than {MAX_STEPS}"),
            Self::Contact { step, error } => write!(f, "step {step}: {error}"),
            Self::Sliding { step } => {
                write!(f, "step {step}: a contact would slide, beyond the stack reference's sticking cases")
            }
            Self::Unsolved { step } => write!(f, "step {step}: no verified answer of the contacts"),
            Self::NonFinite { step } => write!(f, "step {step}: the state is not finite"),
        }
    }
}

impl std::error::Error for Error {}
