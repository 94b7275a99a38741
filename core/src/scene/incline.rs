//! [`Incline`]: a block on an inclined plane (`docs/scenes.md`, "incline").
//!
//! A box of width `w` and height `hgt` rests with its two lower corners (contacts 0 and 1, each a
//! [`Feature::Point`]) on a plane through the origin rising at `alpha`:
//! `n = (-sin alpha, cos alpha)`, `d = (cos alpha, sin alpha)` (up the slope). Analytically it
//! stays when `tan(alpha) <= mu_s` and `tan(alpha) < w / hgt`, slides with
//! `a = g (sin(alpha) - mu_k cos(alpha))` when `tan(alpha) > mu_s` (and it does not tip), and tips
//! over its lower edge when `w / hgt < tan(alpha) < mu_s`. Both corners sticking is statically
//! indeterminate in friction (how the holding force splits between them): the LCP then has many
//! solutions, all with the same motion, and the verified one is used.
//!
//! **Sizes.** `N = 6` keeps `+d` at both corners (friction on a block sliding or tipping down the
//! slope points up it), checked every step with the 8x8 fallback; `N = 8` is the full form.
//!
//! ```
//! use meterstick_core::scene::{Incline, InclineParams, Outcome, Scene};
//!
//! // 35 degrees, mu_s = 0.6 < tan 35 = 0.70: it slides at g (sin a - mu_k cos a).
//! let params = InclineParams::<f64>::default();
//! let mut block = Incline::<f64, 6>::new(params)?;
//! assert_eq!(block.run(|_| {}), Outcome::Slid);
//! let (s, c) = params.angle.sin_cos();
//! let exact = params.gravity * (s - params.mu_kinetic * c);
//! assert!((block.acceleration().unwrap() / exact - 1.0).abs() < 1e-9);
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
    /// Parameters of the incline scene, SI units, angles in radians (`docs/scenes.md`).
    pub struct InclineParams {
        /// Block width `w` along the slope (m, > 0). 0.1.
        width: 0.1, Positive;
        /// Block height `hgt` (m, > 0). 0.05.
        height: 0.05, Positive;
        /// Block mass (kg, > 0); inertia `m (w^2 + hgt^2) / 12`. 1.
        mass: 1.0, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-y`. 9.81.
        gravity: 9.81, NonNegative;
        /// Slope angle `alpha` (rad, `0 <= alpha < pi/2`). 35 degrees.
        angle: 0.610_865_238_198_015_3, Finite;
        /// Static friction coefficient of both corners (>= 0). 0.6.
        mu_static: 0.6, NonNegative;
        /// Kinetic friction coefficient of both corners (0 <= mu_k <= mu_s). 0.4.
        mu_kinetic: 0.4, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching corner whose slip speed is at most this sticks (m/s, >= 0). 1e-5.
        stick_speed: 1e-5, NonNegative;
        /// The run ends at this simulated time (s, > 0). 1.
        max_time: 1.0, Positive;
    }
}

impl<T: Real> InclineParams<T> {
    /// Checks every parameter.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if !(self.angle >= T::zero() && self.angle < T::frac_pi_2()) {
            return Err(ParamError::OutOfRange("angle"));
        }
        Body::block(self.mass, self.width, self.height).check_inertia("mass", "width")?;
        Ok(())
    }

    /// The block at rest with its lower face on the plane: angle `alpha`, centre of mass
    /// `R(alpha) (0, hgt/2)`.
    #[must_use]
    pub fn resting_state(&self) -> BodyState<T> {
        let (s, c) = self.angle.sin_cos_portable();
        let half = self.height / T::of(2.0);
        BodyState::at_rest(-s * half, c * half, self.angle)
    }

    /// The plane: through the origin, normal `(-sin alpha, cos alpha)`, at rest.
    #[must_use]
    pub fn plane(&self) -> Support<T> {
        let (s, c) = self.angle.sin_cos_portable();
        Support::fixed_line([T::zero(); 2], [-s, c])
    }
}

/// A block on an incline with an `N x N` LCP per step (6: `+d` at both corners, checked; 8: the
/// full form) and room for `E` switch events.
#[derive(Debug, Clone)]
pub struct Incline<T: Real, const N: usize = 6, const E: usize = 64> {
    params: InclineParams<T>,
    stepper: Stepper<T, 2, N, 8>,
    plane: Support<T>,
    tip_angle: T,
    events: EventLog<T, 2, E>,
    /// `(t_1, u(t_1))` at the first step after which a corner slid.
    first_slide: Option<(T, T)>,
    outcome: Option<Outcome>,
}

impl<T: Real, const N: usize, const E: usize> Incline<T, N, E> {
    /// The block at rest on the plane.
    ///
    /// # Errors
    /// The first invalid parameter.
    pub fn new(params: InclineParams<T>) -> Result<Self, ParamError> {
        const { assert!(N == 6 || N == 8, "the incline scene has N = 6 or N = 8") };
        params.validate()?;
        let p = &params;
        let body = Body::block(p.mass, p.width, p.height);
        let [c0, c1, ..] = body.corners();
        let corner = |point| Contact {
            feature: Feature::Point(point),
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
        };
        let settings = Settings { step: p.step, gravity: p.gravity, stick_speed: p.stick_speed };
        let model = Model { body, contacts: [corner(c0), corner(c1)], settings };
        let layout =
            const { Layout::<2, N>::new(if N == 8 { [Tangents::Both; 2] } else { [Tangents::Plus; 2] }) };
        let plane = p.plane();
        // The parameters' checks imply the stepper's.
        let stepper = Stepper::from_valid(model, layout, Layout::full(), p.resting_state(), [plane; 2])?;
        Ok(Self {
            params,
            stepper,
            plane,
            tip_angle: (p.width / p.height).atan_libm(),
            events: EventLog::new(),
            first_slide: None,
            outcome: None,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &InclineParams<T> {
        &self.params
    }
    /// The underlying stepper.
    #[must_use]
    pub const fn stepper(&self) -> &Stepper<T, 2, N, 8> {
        &self.stepper
    }

    /// The block's velocity down the slope, `-(vx cos alpha + vy sin alpha)` (m/s).
    #[must_use]
    pub fn speed_down_slope(&self) -> T {
        let Support::Line { normal, .. } = self.plane else { return T::zero() };
        // d = (n_y, -n_x) = (cos alpha, sin alpha).
        let s = self.stepper.state();
        -(s.vx * normal[1] - s.vy * normal[0])
    }

    /// The block's acceleration down the slope over its sliding phase (m/s^2):
    /// `(u(t_end) - u(t_1)) / (t_end - t_1)`, `t_1` the end of the first step after which a corner
    /// slid; `None` unless the run ended [`Outcome::Slid`].
    #[must_use]
    pub fn acceleration(&self) -> Option<T> {
        let (t1, u1) = self.first_slide?;
        let dt = self.stepper.time() - t1;
        (self.outcome == Some(Outcome::Slid) && dt > T::zero()).then(|| (self.speed_down_slope() - u1) / dt)
    }

    /// Advances one step; `None` once the run has an outcome.
    fn advance(&mut self) -> Option<StepReport<T, 2>> {
        if self.outcome.is_some() {
            return None;
        }
        let report = match self.stepper.step(&[self.plane; 2]) {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.events.record(&report);
        if self.first_slide.is_none() && report.contacts.iter().any(|c| c.mode.is_sliding()) {
            self.first_slide = Some((report.time, self.speed_down_slope()));
        }
        if (report.state.theta - self.params.angle).abs_exact() > self.tip_angle {
            self.outcome = Some(Outcome::Tipped);
        } else if report.time >= self.params.max_time {
            self.outcome = Some(if self.first_slide.is_some() { Outcome::Slid } else { Outcome::Held });
        }
        Some(report)
    }
}

impl<T: Real, const N: usize, const E: usize> Incline<T, N, E> {
    /// [`Scene::measured`](crate::scene::Scene::measured): the acceleration.
    fn measured_values(&self) -> [Option<T>; crate::scene::MAX_MEASURES] {
        [self.acceleration(), None, None]
    }
}

impl_scene!(Incline, 2, |p| crate::scene::BodyShape::Box { width: p.width, height: p.height }, |p| {
    Body::block(p.mass, p.width, p.height)
});
