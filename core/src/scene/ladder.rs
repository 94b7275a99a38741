//! [`Ladder`]: a rod leaning against a wall (`docs/scenes.md`, "ladder").
//!
//! A thin rod (`J = m L^2 / 12`) with its lower end (contact 0, body point `(-L/2, 0)`) on the floor
//! `y = 0` and its upper end (contact 1, body point `(L/2, 0)`) against the wall `x = 0` (facing
//! `-x`), released from rest at `theta0` from the floor. Analytically (statics) it stands iff
//! `tan(theta0) >= (1 - mu_f mu_w) / (2 mu_f)`; frictionless, its top leaves the wall when it has
//! fallen to 2/3 of its initial height. A standing ladder with friction at both ends is statically
//! indeterminate (four impulses, three equations): its motion is unique (none), its impulses are not.
//!
//! **Sizes.** `N = 6` keeps `+d` at both ends (the foot slides away from the wall, so the floor's
//! friction on it points toward the wall; the top slides down, so the wall's points up), checked
//! with the 8x8 fallback; `N = 8` is the full form.
//!
//! ```
//! use meterstick_core::scene::{Ladder, LadderParams, Outcome, Scene};
//!
//! // Frictionless from 60 degrees: the top leaves the wall at 2/3 of its starting height.
//! let params = LadderParams { angle: 60f64.to_radians(), mu_floor: 0.0, mu_wall: 0.0, step: 1e-4, ..LadderParams::default() };
//! let mut ladder = Ladder::<f64, 6>::new(params)?;
//! assert_eq!(ladder.run(|_| {}), Outcome::Fell);
//! let ratio = ladder.wall_release_height().unwrap() / ladder.start_top_height();
//! assert!((ratio / (2.0 / 3.0) - 1.0).abs() < 0.01, "{ratio}");
//! # Ok::<(), meterstick_core::ParamError>(())
//! ```

use super::outcome::Outcome;
use super::scene_trait::impl_scene;
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{
    Body, BodyState, Contact, EventLog, Feature, Layout, Model, Settings, StepReport, Stepper, Support,
    Tangents,
};
use crate::real::Real;

params! {
    /// Parameters of the ladder scene, SI units, angles in radians (`docs/scenes.md`).
    pub struct LadderParams {
        /// Rod length `L` (m, > 0). 1.
        length: 1.0, Positive;
        /// Rod thickness (m, > 0): drawing only (the contacts are the rod's ends, on its axis). 0.02.
        thickness: 0.02, Positive;
        /// Rod mass (kg, > 0); inertia `m L^2 / 12`. 1.
        mass: 1.0, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-y`. 9.81.
        gravity: 9.81, NonNegative;
        /// Start angle `theta0` from the floor (rad, `0 < theta0 < pi/2`). 45 degrees.
        angle: core::f64::consts::FRAC_PI_4, Finite;
        /// Friction coefficient at the floor, static and kinetic (>= 0). 0.4.
        mu_floor: 0.4, NonNegative;
        /// Friction coefficient at the wall, static and kinetic (>= 0). 0.3.
        mu_wall: 0.3, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching end whose slip speed is at most this sticks (m/s, >= 0). 1e-5.
        stick_speed: 1e-5, NonNegative;
        /// The run ends at this simulated time (s, > 0). 3.
        max_time: 3.0, Positive;
    }
}

impl<T: Real> LadderParams<T> {
    /// Checks every parameter.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        Body::check_rod(self.mass, self.length, self.thickness, ["mass", "length", "thickness"])?;
        if !(self.angle > T::zero() && self.angle < T::frac_pi_2()) {
            return Err(ParamError::OutOfRange("angle"));
        }
        Ok(())
    }

    /// The ladder at rest: lower end at `(-L cos theta0, 0)`, upper end at `(0, L sin theta0)`.
    #[must_use]
    pub fn resting_state(&self) -> BodyState<T> {
        let (s, c) = self.angle.sin_cos_portable();
        let half = self.length / T::of(2.0);
        BodyState::at_rest(-half * c, half * s, self.angle)
    }

    /// The critical angle of the statics, `atan((1 - mu_f mu_w) / (2 mu_f))` (rad; `pi/2` when
    /// `mu_f = 0`): the ladder stands at or above it.
    #[must_use]
    pub fn critical_angle(&self) -> T {
        if self.mu_floor <= T::zero() {
            return T::frac_pi_2();
        }
        ((T::one() - self.mu_floor * self.mu_wall) / (T::of(2.0) * self.mu_floor)).atan_libm()
    }
}

/// The floor `y = 0` and the wall `x = 0` facing `-x`.
fn floor_and_wall<T: Real>() -> [Support<T>; 2] {
    [
        Support::fixed_line([T::zero(); 2], [T::zero(), T::one()]),
        Support::fixed_line([T::zero(); 2], [-T::one(), T::zero()]),
    ]
}

/// A ladder with an `N x N` LCP per step (6: `+d` at both ends, checked; 8: the full form) and room
/// for `E` switch events.
#[derive(Debug, Clone)]
pub struct Ladder<T: Real, const N: usize = 6, const E: usize = 64> {
    params: LadderParams<T>,
    stepper: Stepper<T, 2, N, 8>,
    events: EventLog<T, 2, E>,
    slid: bool,
    release_height: Option<T>,
    outcome: Option<Outcome>,
}

impl<T: Real, const N: usize, const E: usize> Ladder<T, N, E> {
    /// The ladder at rest against the wall.
    ///
    /// # Errors
    /// The first invalid parameter.
    pub fn new(params: LadderParams<T>) -> Result<Self, ParamError> {
        const { assert!(N == 6 || N == 8, "the ladder scene has N = 6 or N = 8") };
        params.validate()?;
        let p = &params;
        let half = p.length / T::of(2.0);
        let end =
            |x: T, mu: T| Contact { feature: Feature::Point([x, T::zero()]), mu_static: mu, mu_kinetic: mu };
        let settings = Settings { step: p.step, gravity: p.gravity, stick_speed: p.stick_speed };
        let model = Model {
            body: Body::rod(p.mass, p.length, p.thickness),
            contacts: [end(-half, p.mu_floor), end(half, p.mu_wall)],
            settings,
        };
        let layout =
            const { Layout::<2, N>::new(if N == 8 { [Tangents::Both; 2] } else { [Tangents::Plus; 2] }) };
        // The parameters' checks imply the stepper's.
        let stepper =
            Stepper::from_valid(model, layout, Layout::full(), p.resting_state(), floor_and_wall())?;
        Ok(Self {
            params,
            stepper,
            events: EventLog::new(),
            slid: false,
            release_height: None,
            outcome: None,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &LadderParams<T> {
        &self.params
    }
    /// The underlying stepper.
    #[must_use]
    pub const fn stepper(&self) -> &Stepper<T, 2, N, 8> {
        &self.stepper
    }

    /// Height of the upper end now, `y + (L/2) sin(theta)` (m).
    #[must_use]
    pub fn top_height(&self) -> T {
        // The wall contact's r is R (L/2, 0): its y is (L/2) sin(theta).
        self.stepper.state().y + self.stepper.frames()[1].r[1]
    }

    /// Height of the upper end at the start, `L sin(theta0)` (m).
    #[must_use]
    pub fn start_top_height(&self) -> T {
        self.params.length * self.params.angle.sin_cos_portable().0
    }

    /// Height of the upper end at the end of the first step after which it left the wall (m);
    /// `None` while it has not.
    #[must_use]
    pub const fn wall_release_height(&self) -> Option<T> {
        self.release_height
    }

    /// Advances one step; `None` once the run has an outcome.
    fn advance(&mut self) -> Option<StepReport<T, 2>> {
        if self.outcome.is_some() {
            return None;
        }
        let report = match self.stepper.step(&floor_and_wall()) {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.events.record(&report);
        self.slid |= report.contacts.iter().any(|c| c.mode.is_sliding());
        let wall = &report.contacts[1];
        let top = self.top_height();
        if self.release_height.is_none() && wall.previous_mode.is_touching() && !wall.mode.is_touching() {
            self.release_height = Some(top);
        }
        if top <= T::zero() {
            self.outcome = Some(Outcome::Fell);
        } else if report.time >= self.params.max_time {
            self.outcome = Some(if self.slid { Outcome::Unfinished } else { Outcome::Held });
        }
        Some(report)
    }
}

impl<T: Real, const N: usize, const E: usize> Ladder<T, N, E> {
    /// [`Scene::measured`](crate::scene::Scene::measured): the wall release's height and its
    /// ratio to the top's start height.
    fn measured_values(&self) -> [Option<T>; crate::scene::MAX_MEASURES] {
        let h = self.wall_release_height();
        // The ratio of a ladder started (almost) flat is not a number: no measure rather than an infinity.
        [h, h.map(|h| h / self.start_top_height()).filter(|r| r.finite()), None]
    }
}

impl_scene!(Ladder, 2, |p| crate::scene::BodyShape::Box { width: p.length, height: p.thickness }, |p| {
    Body::rod(p.mass, p.length, p.thickness)
});
