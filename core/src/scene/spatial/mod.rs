//! The scenes in three dimensions (`docs/scenes.md`, "Scenes in three dimensions"; feature
//! `scenes-spatial`): [`Puck`] and [`Billiard`], one body touching a plane at one point, stepped by
//! [`crate::spatial::OneContact`] with Coulomb's circular cone (or, with `friction_directions`
//! set, a stepper of [`PYRAMID_ROWS`] rows with the pyramid of LCP engines, the baseline), and
//! [`Curling`], a ring or a disc touching it at up to [`MAX_POINTS`] points (its flat base's load
//! the least-norm one, `crate::spatial`'s "The load"); and [`MeterStick3d`], the paper's rod on a
//! finger pad and a point finger ([`crate::spatial::SupportedStepper`]); each seen by the front
//! ends through [`SpatialView`] ([`SpatialSeen`]) like every other scene.
//!
//! Each scene is a [`Run`] (the stepper, the outcome, the counters) and its own rules: its start
//! from its parameters, the outcome it judges after each step, what it measures.

mod billiard;
mod curling;
mod meter_stick_3d;
mod puck;
mod stack_3d;
#[cfg(feature = "scenes-stack-3d")]
mod stack_view;
mod view;

pub use billiard::{Billiard, BilliardParams};
pub use curling::{CURLING_ROWS, Curling, CurlingParams, MAX_POINTS};
pub use meter_stick_3d::{
    FingerSwitch, MeterStick3d, MeterStick3dParams, ROD_EVENTS, ROD_POINTS, ROD_ROWS, finger_modes,
};
pub use puck::{Puck, PuckParams};
pub use stack_3d::{Stack3d, Stack3d2, Stack3d3, Stack3dParams};
#[cfg(feature = "scenes-stack-3d")]
pub use stack_view::StackView;
pub use view::{SeenContact, SpatialSeen, SpatialView};

use crate::RunStats;
use crate::params::ParamError;
use crate::real::Real;
use crate::scene::BodyShape;
use crate::scene::{MAX_MEASURES, Outcome};
use crate::spatial::{FrictionCone, SpatialStepReport, SpatialStepper};

/// The rows of a scene's LCP with Coulomb's circular cone: one contact, one friction line.
pub const CIRCULAR_ROWS: usize = 4;

/// The rows of a scene's LCP with the pyramid baseline: one contact of at most 16 friction
/// directions (`directions + 2` rows).
pub const PYRAMID_ROWS: usize = 18;

/// A scene's friction cone from its `friction_directions` parameter: 0 Coulomb's circular cone,
/// else the pyramid of that many directions (a whole number from 3 to 16).
///
/// # Errors
/// [`ParamError::OutOfRange`]`("friction_directions")` for any other value.
pub fn friction_cone<T: Real>(directions: T) -> Result<FrictionCone, ParamError> {
    let d = directions.as_f64();
    if d == 0.0 {
        return Ok(FrictionCone::Circular);
    }
    // A whole number: exactly its floor.
    #[allow(clippy::float_cmp)]
    if (3.0..=16.0).contains(&d) && d == libm::floor(d) {
        // A whole number from 3 to 16: exact as a u8.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        return Ok(FrictionCone::Pyramid { directions: d as u8 });
    }
    Err(ParamError::OutOfRange("friction_directions"))
}

/// A scene in three dimensions, as [`SpatialView`] drives it; its LCP has `N` rows
/// ([`CIRCULAR_ROWS`] or [`PYRAMID_ROWS`]).
pub trait SpatialScene<T: Real, const N: usize = CIRCULAR_ROWS, const K: usize = 1> {
    /// Advances one step and judges it; `None` once the run has an outcome (nothing done).
    fn step(&mut self) -> Option<SpatialStepReport<T, K>>;
    /// Takes the outcome so that the run goes on ([`crate::scene::SceneView::go_on`]); `None`
    /// before it.
    fn go_on(&mut self) -> Option<Outcome>;
    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;
    /// The body's outline.
    fn shape(&self) -> BodyShape<T>;
    /// The run: its stepper and counters.
    fn run(&self) -> &Run<T, N, K>;
    /// What the scene measures, in its catalogue entry's order.
    fn measured(&self) -> [Option<T>; MAX_MEASURES];
}

/// One body on a plane at `K` points, stepped to an outcome by an LCP of `N` rows: the part every
/// scene in three dimensions shares.
#[derive(Debug, Clone)]
pub struct Run<T: Real, const N: usize = CIRCULAR_ROWS, const K: usize = 1> {
    stepper: SpatialStepper<T, K, N>,
    max_time: T,
    outcome: Option<Outcome>,
    stats: RunStats,
}

impl<T: Real, const N: usize, const K: usize> Run<T, N, K> {
    fn new(stepper: SpatialStepper<T, K, N>, max_time: T) -> Self {
        Self { stepper, max_time, outcome: None, stats: RunStats::default() }
    }

    /// The stepper.
    #[must_use]
    pub const fn stepper(&self) -> &SpatialStepper<T, K, N> {
        &self.stepper
    }

    /// The run's counters: steps, pivots, the steps the warm basis answered without a pivot.
    #[must_use]
    pub const fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// One step, judged by `judge` (the scene's rule on the step's report), then by the time
    /// limit (`at_limit`); a failed step ends the run with its error.
    fn advance(
        &mut self,
        judge: impl FnOnce(&SpatialStepReport<T, K>) -> Option<Outcome>,
        at_limit: Outcome,
    ) -> Option<SpatialStepReport<T, K>> {
        if self.outcome.is_some() {
            return None;
        }
        match self.stepper.step() {
            Err(e) => {
                self.outcome = Some(e.into());
                None
            }
            Ok(report) => {
                self.stats.steps += 1;
                self.stats.count_pivots(report.pivots);
                if report.pivots == 0 {
                    self.stats.warm_starts += 1;
                }
                self.outcome = judge(&report).or((report.time >= self.max_time).then_some(at_limit));
                Some(report)
            }
        }
    }
}
