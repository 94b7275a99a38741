//! The scenes of several bodies (`docs/scenes.md`, "Scenes of several bodies"): [`BlockOnBlock`],
//! [`Tablecloth`], [`Stack`] and [`DiscOnBoard`], each with its parameters, validity rules, outcome
//! and measures.
//!
//! Their outcomes are the one list's, [`Outcome`] (`crate::scene::Outcome`; a failed step is
//! [`Outcome::Failed`]). They do not implement `crate::scene::Scene`, which is shaped for
//! one body (its `crate::planar::StepReport<T, K>` carries one `BodyState`, its `frames` one support per contact);
//! each has
//! `step()` and `run()` of its own returning [`super::SystemStepReport`] (every body's state, each
//! pair's interface force), and [`MultibodyScene`], what a driver asks of any of them;
//! [`crate::scene::MultibodyView`] shows any of them as a [`crate::scene::SceneView`], the one
//! interface of every engine's scenes.

mod block_on_block;
mod disc_on_board;
mod stack;
mod tablecloth;

pub use block_on_block::{BLOCK_ON_BLOCK_ROWS, BlockOnBlock, BlockOnBlockParams};
pub use disc_on_board::{DiscOnBoard, DiscOnBoardParams};
pub use stack::{Stack, Stack2, Stack3, StackParams};
pub use tablecloth::{TABLECLOTH_ROWS, Tablecloth, TableclothParams};

use super::{CornerFrame, System, SystemStepReport, SystemStepper};
use crate::RunStats;
use crate::params::ParamError;
use crate::planar::{BodyState, ContactMode};
use crate::real::Real;
use crate::scene::{MAX_MEASURES, Outcome};

/// What a driver asks of any scene of several bodies, `B` bodies and `P` resting pairs (the
/// counterpart of [`crate::scene::Scene`], which is shaped for one body): the registry
/// ([`crate::scene::SceneParams::build_multibody`]) hands one to a
/// [`crate::scene::MultibodyVisitor`].
pub trait MultibodyScene<T: Real, const B: usize, const P: usize> {
    /// The LCP's capacity in rows (4 per active candidate contact).
    const ROWS: usize;
    /// Advances one step; `None` once the run has an outcome.
    fn step(&mut self) -> Option<SystemStepReport<T, B, P>>;
    /// Lets a run that has its outcome go on: takes the outcome (and returns it), so that the next
    /// [`Self::step`] is taken and judged afresh. A front end that shows the bodies go on after
    /// the outcome (the stack tumbling off the table after `Fell`) calls it before each such step
    /// on a copy of the judged run, whose outcome it keeps; what the scene measures goes on too.
    /// It bounds the steps it takes. `None` (and nothing done) before the outcome, or for a scene
    /// that does not go on (the default).
    fn go_on(&mut self) -> Option<Outcome> {
        None
    }
    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;
    /// Every body's state (body 0 the lowest).
    fn states(&self) -> &[BodyState<T>; B];
    /// The system stepped: the bodies, the table, the pairs, the forces, the step's scalars.
    fn system(&self) -> &System<T, B, P>;
    /// Each pair's candidates' geometry now ([`super::SystemStepper::frames`]).
    fn frames(&self) -> &[[CornerFrame<T>; 4]; P];
    /// Each pair's candidates' modes after the last step ([`super::SystemStepper::modes`]).
    fn modes(&self) -> &[[ContactMode; 4]; P];
    /// Simulated time (s).
    fn time(&self) -> T;
    /// The stepper's counters.
    fn stats(&self) -> &RunStats;
    /// What the scene measures so far, in the order the catalogue names them (`docs/scenes.md`,
    /// each scene's "Measured"): block-on-block `[a_bottom, a_top]`, the tablecloth the block's
    /// displacement, the stack its largest point speed, disc-on-board `[a_board, a_disc]`.
    fn measured(&self) -> [Option<T>; MAX_MEASURES];

    /// Runs until an outcome, calling `observe` after every step.
    fn run(&mut self, mut observe: impl FnMut(&SystemStepReport<T, B, P>)) -> Outcome
    where
        Self: Sized,
    {
        while let Some(report) = self.step() {
            observe(&report);
        }
        self.outcome().unwrap_or(Outcome::Unfinished)
    }
}

/// What every scene of several bodies keeps besides its own judge: its parameters, its stepper
/// and its outcome once decided.
#[derive(Debug, Clone)]
struct Run<T: Real, Params, const B: usize, const P: usize, const N: usize> {
    params: Params,
    stepper: SystemStepper<T, B, P, N>,
    outcome: Option<Outcome>,
}

impl<T: Real, Params, const B: usize, const P: usize, const N: usize> Run<T, Params, B, P, N> {
    /// The scene's parameters (validated by the caller), its system and its bodies' start.
    fn new(params: Params, system: System<T, B, P>, states: [BodyState<T>; B]) -> Result<Self, ParamError> {
        Ok(Self { params, stepper: SystemStepper::new(system, states)?, outcome: None })
    }

    /// One step, unless the run has its outcome; a step that fails ends the run
    /// ([`Outcome::Failed`]; the state is that before the step).
    fn advance(&mut self) -> Option<SystemStepReport<T, B, P>> {
        if self.outcome.is_some() {
            return None;
        }
        match self.stepper.step() {
            Ok(report) => Some(report),
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                None
            }
        }
    }
}

/// The step's scalars of a scene's parameters (each has `step`, `gravity`, `stick_speed` and
/// `contact_margin`).
macro_rules! settings_of {
    ($p:expr) => {
        $crate::multibody::SystemSettings {
            base: $crate::planar::Settings {
                step: $p.step,
                gravity: $p.gravity,
                stick_speed: $p.stick_speed,
            },
            margin: $p.contact_margin,
        }
    };
}
use settings_of;

/// A scene's accessors of its [`Run`] (`outcome`, `stepper`, `params`) and [`MultibodyScene`],
/// given its inherent `step` and what it measures.
macro_rules! multibody_scene {
    ($scene:ty, [$($generics:tt)*], $params:ty, $b:expr, $p:expr, $rows:expr, |$s:ident| $measured:expr) => {
        impl<$($generics)*> $scene {
            /// The outcome, once the run has ended.
            #[must_use]
            pub const fn outcome(&self) -> Option<Outcome> {
                self.run.outcome
            }

            /// The stepper (states, frames, modes, counters).
            #[must_use]
            pub const fn stepper(&self) -> &SystemStepper<T, $b, $p, $rows> {
                &self.run.stepper
            }

            /// The parameters.
            #[must_use]
            pub const fn params(&self) -> &$params {
                &self.run.params
            }
        }

        impl<$($generics)*> MultibodyScene<T, $b, $p> for $scene {
            const ROWS: usize = $rows;
            fn step(&mut self) -> Option<SystemStepReport<T, $b, $p>> {
                <$scene>::step(self)
            }
            fn go_on(&mut self) -> Option<Outcome> {
                self.run.outcome.take()
            }
            fn outcome(&self) -> Option<Outcome> {
                <$scene>::outcome(self)
            }
            fn states(&self) -> &[BodyState<T>; $b] {
                self.stepper().states()
            }
            fn system(&self) -> &System<T, $b, $p> {
                self.stepper().system()
            }
            fn frames(&self) -> &[[CornerFrame<T>; 4]; $p] {
                self.stepper().frames()
            }
            fn modes(&self) -> &[[ContactMode; 4]; $p] {
                self.stepper().modes()
            }
            fn time(&self) -> T {
                self.stepper().time()
            }
            fn stats(&self) -> &RunStats {
                self.stepper().stats()
            }
            fn measured(&self) -> [Option<T>; MAX_MEASURES] {
                let $s = self;
                $measured
            }
        }
    };
}

multibody_scene!(BlockOnBlock<T>, [T: Real], BlockOnBlockParams<T>, 2, 2, BLOCK_ON_BLOCK_ROWS, |s| {
    let a = s.accelerations();
    [a.map(|a| a[0]), a.map(|a| a[1]), None]
});
multibody_scene!(DiscOnBoard<T>, [T: Real], DiscOnBoardParams<T>, 2, 2, BLOCK_ON_BLOCK_ROWS, |s| {
    let a = s.accelerations();
    [a.map(|a| a[0]), a.map(|a| a[1]), None]
});
multibody_scene!(Tablecloth<T>, [T: Real], TableclothParams<T>, 2, 3, TABLECLOTH_ROWS, |s| [Some(s.block_displacement()), None, None]);
multibody_scene!(Stack<T, B, N>, [T: Real, const B: usize, const N: usize], StackParams<T>, B, B, N, |s| [
    Some(s.max_speed()),
    None,
    None
]);

/// The accelerations along `x` of a lower and an upper body while both are in full contact
/// (`docs/scenes.md`, block-on-block, "Measured"): `(vx(t_2) - vx(t_1)) / (t_2 - t_1)` over the
/// first unbroken run of steps after which the four contacts touch, `t_1` the end of its first
/// step, `t_2` of its last.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FullContact<T> {
    first: Option<(T, [T; 2])>,
    last: Option<(T, [T; 2])>,
    ended: bool,
}

impl<T: Real> FullContact<T> {
    const fn new() -> Self {
        Self { first: None, last: None, ended: false }
    }

    /// Records a step that ended at `time` with the two bodies' `vx`; `touching` when all four
    /// contacts touch after it.
    fn record(&mut self, touching: bool, time: T, vx: [T; 2]) {
        if self.ended {
            return;
        }
        if !touching {
            self.ended = self.first.is_some();
        } else if self.first.is_none() {
            self.first = Some((time, vx));
        } else {
            self.last = Some((time, vx));
        }
    }

    /// `[a_lower, a_upper]` (m/s^2), once the run has two steps.
    fn accelerations(&self) -> Option<[T; 2]> {
        let ((t1, v1), (t2, v2)) = (self.first?, self.last?);
        let dt = t2 - t1;
        Some([(v2[0] - v1[0]) / dt, (v2[1] - v1[1]) / dt])
    }
}

/// `|(vx, vy)| + reach |omega|`: the speed bound of a box's fastest point (`reach` half its
/// diagonal).
fn point_speed_bound<T: Real>(state: &BodyState<T>, reach: T) -> T {
    (state.vx * state.vx + state.vy * state.vy).sqrt_rounded() + reach * state.omega.abs_exact()
}
