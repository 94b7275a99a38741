//! [`Scene`]: what every scene offers its drivers (host tools, firmware, the browser page).

use super::kind::MAX_MEASURES;
use super::outcome::Outcome;
use super::view::BodyShape;
use crate::planar::{Body, BodyState, ContactFrame, ContactMode, RunStats, StepReport, Support, SwitchEvent};
use crate::real::Real;

/// A scene: one body on `K` supports the scene moves, stepped to an [`Outcome`].
///
/// Implemented by every scene of the catalogue (`super::kind`); a scene of your own
/// implements it the same way (`core/examples/three_fingers.rs`).
pub trait Scene<T: Real, const K: usize> {
    /// Advances one step; `None` once the run has an outcome (a failed step ends the run with
    /// [`Outcome::Failed`]).
    fn step(&mut self) -> Option<StepReport<T, K>>;
    /// Lets a run that has its outcome go on: takes the outcome (and returns it), so that the next
    /// [`Self::step`] is taken and judged afresh. A front end that shows the body go on after the
    /// outcome (the rod falling off the fingers after `Fell`) calls it before each such step on a
    /// copy of the judged run, whose outcome it keeps; events and measured quantities go on too.
    /// It bounds the steps it takes. `None` (and nothing done) before the outcome, or for a scene
    /// that does not go on (the default).
    fn go_on(&mut self) -> Option<Outcome> {
        None
    }
    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;
    /// The body's outline.
    fn shape(&self) -> BodyShape<T>;
    /// The body the scene moves: its extent, mass (kg) and moment of inertia about its centre of
    /// mass (kg m^2), as the scene's stepper holds them.
    fn body(&self) -> Body<T>;
    /// The body's state now.
    fn state(&self) -> &BodyState<T>;
    /// Simulated time (s).
    fn time(&self) -> T;
    /// The supports where the last step left them.
    fn supports(&self) -> &[Support<T>; K];
    /// Each contact's geometry now (contact point, normal, tangent, gap).
    fn frames(&self) -> &[ContactFrame<T>; K];
    /// Each contact's mode after the last step (before the first: from the prescribed motion).
    fn modes(&self) -> [ContactMode; K];
    /// The stepper's counters.
    fn stats(&self) -> &RunStats;
    /// The switch events so far (a contact's mode changed after a step), as many as the scene
    /// keeps (a catalogue scene its `E`, counting the rest); a scene that keeps none has none.
    fn events(&self) -> &[SwitchEvent<T, K>] {
        &[]
    }
    /// What the scene measures, in the order of its catalogue entry's `measures`
    /// (`meterstick-catalogue`'s `SceneInfo`, the keys of `host-sim`'s `summary.json`); `None` where a
    /// quantity has no value (yet). A scene outside the catalogue measures nothing.
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        [None; MAX_MEASURES]
    }

    /// Runs until an outcome, calling `observe` after every step; returns the outcome.
    fn run(&mut self, mut observe: impl FnMut(&StepReport<T, K>)) -> Outcome
    where
        Self: Sized,
    {
        while let Some(report) = self.step() {
            observe(&report);
        }
        self.outcome().unwrap_or(Outcome::Unfinished)
    }
}

/// A scene borrowed mutably is a scene (a driver steps a scene it keeps: [`super::AnyScene`]).
impl<T: Real, const K: usize, S: Scene<T, K> + ?Sized> Scene<T, K> for &mut S {
    fn step(&mut self) -> Option<StepReport<T, K>> {
        (**self).step()
    }
    fn go_on(&mut self) -> Option<Outcome> {
        (**self).go_on()
    }
    fn outcome(&self) -> Option<Outcome> {
        (**self).outcome()
    }
    fn shape(&self) -> BodyShape<T> {
        (**self).shape()
    }
    fn body(&self) -> Body<T> {
        (**self).body()
    }
    fn state(&self) -> &BodyState<T> {
        (**self).state()
    }
    fn time(&self) -> T {
        (**self).time()
    }
    fn supports(&self) -> &[Support<T>; K] {
        (**self).supports()
    }
    fn frames(&self) -> &[ContactFrame<T>; K] {
        (**self).frames()
    }
    fn modes(&self) -> [ContactMode; K] {
        (**self).modes()
    }
    fn stats(&self) -> &RunStats {
        (**self).stats()
    }
    fn events(&self) -> &[SwitchEvent<T, K>] {
        (**self).events()
    }
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        (**self).measured()
    }
}

/// Implements [`Scene`] for a scene struct with a `stepper` field, an `outcome` field, a `params`
/// field and an inherent `advance` method (its step); `|p| shape` gives its outline from its
/// parameters, `|p| body` its body (the one its stepper was given).
macro_rules! impl_scene {
    ($scene:ident, $k:literal, |$p:ident| $shape:expr, |$q:ident| $body:expr) => {
        impl<T: Real, const N: usize, const E: usize> $crate::scene::Scene<T, $k> for $scene<T, N, E> {
            fn step(&mut self) -> Option<$crate::planar::StepReport<T, $k>> {
                self.advance()
            }
            fn go_on(&mut self) -> Option<$crate::scene::Outcome> {
                self.outcome.take()
            }
            fn outcome(&self) -> Option<$crate::scene::Outcome> {
                self.outcome
            }
            fn shape(&self) -> $crate::scene::BodyShape<T> {
                let $p = &self.params;
                $shape
            }
            fn body(&self) -> $crate::planar::Body<T> {
                let $q = &self.params;
                $body
            }
            fn state(&self) -> &$crate::planar::BodyState<T> {
                self.stepper.state()
            }
            fn time(&self) -> T {
                self.stepper.time()
            }
            fn supports(&self) -> &[$crate::planar::Support<T>; $k] {
                self.stepper.supports()
            }
            fn frames(&self) -> &[$crate::planar::ContactFrame<T>; $k] {
                self.stepper.frames()
            }
            fn modes(&self) -> [$crate::planar::ContactMode; $k] {
                self.stepper.modes()
            }
            fn stats(&self) -> &$crate::planar::RunStats {
                self.stepper.stats()
            }
            fn events(&self) -> &[$crate::planar::SwitchEvent<T, $k>] {
                self.events.events()
            }
            fn measured(&self) -> [Option<T>; $crate::scene::MAX_MEASURES] {
                self.measured_values()
            }
        }
    };
}

pub(crate) use impl_scene;
