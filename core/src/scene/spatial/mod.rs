//! The scenes in three dimensions (`docs/scenes.md`, "Scenes in three dimensions"; feature
//! `scenes-spatial`): [`Puck`] and [`Billiard`], one body touching a plane at one point, stepped by
//! [`crate::spatial::OneContact`] with Coulomb's circular cone, and seen by the front ends through
//! [`SpatialView`] like every other scene.
//!
//! Each scene is a [`Run`] (the stepper, the outcome, the counters) and its own rules: its start
//! from its parameters, the outcome it judges after each step, what it measures.

mod billiard;
mod puck;
mod view;

pub use billiard::{Billiard, BilliardParams};
pub use puck::{Puck, PuckParams};
pub use view::SpatialView;

use crate::real::Real;
use crate::scene::BodyShape;
use crate::scene::{MAX_MEASURES, Outcome};
use crate::spatial::{OneContact, SpatialStepReport};

/// A scene in three dimensions, as [`SpatialView`] drives it.
pub trait SpatialScene<T: Real> {
    /// Advances one step and judges it; `None` once the run has an outcome (nothing done).
    fn step(&mut self) -> Option<SpatialStepReport<T, 1>>;
    /// Takes the outcome so that the run goes on ([`crate::scene::SceneView::go_on`]); `None`
    /// before it.
    fn go_on(&mut self) -> Option<Outcome>;
    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;
    /// The body's outline.
    fn shape(&self) -> BodyShape<T>;
    /// The run: its stepper and counters.
    fn run(&self) -> &Run<T>;
    /// What the scene measures, in its catalogue entry's order.
    fn measured(&self) -> [Option<T>; MAX_MEASURES];
}

/// One body on a plane at one point, stepped to an outcome: the part every scene in three
/// dimensions shares.
#[derive(Debug, Clone)]
pub struct Run<T: Real> {
    stepper: OneContact<T>,
    max_time: T,
    outcome: Option<Outcome>,
    steps: u64,
    pivots: u64,
    max_pivots: u32,
    warm_starts: u64,
}

impl<T: Real> Run<T> {
    const fn new(stepper: OneContact<T>, max_time: T) -> Self {
        Self { stepper, max_time, outcome: None, steps: 0, pivots: 0, max_pivots: 0, warm_starts: 0 }
    }

    /// The stepper.
    #[must_use]
    pub const fn stepper(&self) -> &OneContact<T> {
        &self.stepper
    }

    /// Steps taken.
    #[must_use]
    pub const fn steps(&self) -> u64 {
        self.steps
    }

    /// Lemke pivots over the run.
    #[must_use]
    pub const fn pivots(&self) -> u64 {
        self.pivots
    }

    /// The most pivots of one step.
    #[must_use]
    pub const fn max_pivots(&self) -> u32 {
        self.max_pivots
    }

    /// Steps the warm basis answered without a pivot.
    #[must_use]
    pub const fn warm_starts(&self) -> u64 {
        self.warm_starts
    }

    /// One step, judged by `judge` (the scene's rule on the step's report), then by the time
    /// limit (`at_limit`); a failed step ends the run with its error.
    fn advance(
        &mut self,
        judge: impl FnOnce(&SpatialStepReport<T, 1>) -> Option<Outcome>,
        at_limit: Outcome,
    ) -> Option<SpatialStepReport<T, 1>> {
        if self.outcome.is_some() {
            return None;
        }
        match self.stepper.step() {
            Err(e) => {
                self.outcome = Some(e.into());
                None
            }
            Ok(report) => {
                self.steps += 1;
                self.pivots += u64::from(report.pivots);
                self.max_pivots = self.max_pivots.max(report.pivots);
                if report.pivots == 0 {
                    self.warm_starts += 1;
                }
                self.outcome = judge(&report).or((report.time >= self.max_time).then_some(at_limit));
                Some(report)
            }
        }
    }
}
