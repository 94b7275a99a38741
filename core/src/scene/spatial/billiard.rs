//! [`Billiard`]: a billiard ball struck with spin, sliding until it rolls (`docs/scenes.md`,
//! "billiard").

use super::{Run, SpatialScene};
use crate::params::{ParamError, check_step_within, params};
use crate::real::Real;
use crate::scene::BodyShape;
use crate::scene::{MAX_MEASURES, Outcome};
use crate::spatial::{
    Body, FrictionCone, Mode, OneContact, Plane, SpatialSettings, SpatialShape, SpatialStepReport, State,
    identity,
};

params! {
    /// Parameters of the billiard scene, SI units (`docs/scenes.md`, "billiard").
    pub struct BilliardParams {
        /// Radius `R` (m, > 0). 0.028575 (a pool ball).
        radius: 0.028_575, Positive;
        /// Mass `m` (kg, > 0). 0.17.
        mass: 0.17, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-z`. 9.81.
        gravity: 9.81, NonNegative;
        /// The speed it is struck at, along `+x` (m/s, >= 0). 2.
        speed: 2.0, NonNegative;
        /// Its spin about the world's `x` at the start (rad/s). 0.
        spin_x: 0.0, Finite;
        /// Its spin about the world's `y` (rad/s; negative is topspin, positive backspin). 0.
        spin_y: 0.0, Finite;
        /// Its spin about the world's `z` (rad/s; a point contact has no friction against it). 0.
        spin_z: 0.0, Finite;
        /// Static friction coefficient (>= 0). 0.2.
        mu_static: 0.2, NonNegative;
        /// Kinetic friction coefficient (0 <= mu_k <= mu_s). 0.2.
        mu_kinetic: 0.2, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A loaded contact whose slip is at most this sticks (m/s, > 0). 1e-5.
        stick_speed: 1e-5, Positive;
        /// The run ends at this simulated time (s, > 0). 5.
        max_time: 5.0, Positive;
    }
}

impl<T: Real> BilliardParams<T> {
    /// Checks the parameters (`docs/scenes.md`, "billiard", Validity).
    ///
    /// # Errors
    /// The first field refused: not finite, not positive or negative as its check says, `step`
    /// beyond `max_time`, `mu_kinetic` above `mu_static`, a moment a precision cannot hold.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        Body::sphere(self.mass, self.radius)
            .validate()
            .map_err(|_| ParamError::InertiaOutOfRange { mass: "mass", size: "radius" })
    }
}

/// The billiard scene, as `docs/scenes.md` defines it.
#[derive(Debug, Clone)]
pub struct Billiard<T: Real> {
    params: BilliardParams<T>,
    run: Run<T>,
    /// When it rolled and its velocity then.
    rolled: Option<(T, [T; 3])>,
}

impl<T: Real> Billiard<T> {
    /// The ball at its start.
    ///
    /// # Errors
    /// [`BilliardParams::validate`]'s, or the stepper's ([`OneContact::new`]).
    pub fn new(params: BilliardParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let mut plane = Plane::table(T::zero(), params.mu_static);
        plane.mu_kinetic = params.mu_kinetic;
        let settings = SpatialSettings {
            step: params.step,
            gravity: [T::zero(), T::zero(), -params.gravity],
            stick_speed: params.stick_speed,
            friction: FrictionCone::Circular,
            ..SpatialSettings::default()
        };
        let state = State {
            position: [T::zero(), T::zero(), params.radius],
            orientation: identity(),
            velocity: [params.speed, T::zero(), T::zero()],
            angular_velocity: [params.spin_x, params.spin_y, params.spin_z],
        };
        let stepper = OneContact::new(
            Body::sphere(params.mass, params.radius),
            [SpatialShape::Sphere { radius: params.radius }],
            plane,
            settings,
            state,
        )?;
        Ok(Self { params, run: Run::new(stepper, params.max_time), rolled: None })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &BilliardParams<T> {
        &self.params
    }
}

impl<T: Real> SpatialScene<T> for Billiard<T> {
    fn step(&mut self) -> Option<SpatialStepReport<T, 1>> {
        let rolled = &mut self.rolled;
        self.run.advance(
            |r| {
                (r.contacts[0].mode == Mode::Sticking).then(|| {
                    if rolled.is_none() {
                        *rolled = Some((r.time, r.state.velocity));
                    }
                    Outcome::Rolled
                })
            },
            Outcome::Unfinished,
        )
    }

    fn go_on(&mut self) -> Option<Outcome> {
        self.run.outcome.take()
    }

    fn outcome(&self) -> Option<Outcome> {
        self.run.outcome
    }

    fn shape(&self) -> BodyShape<T> {
        BodyShape::Ball { radius: self.params.radius }
    }

    fn run(&self) -> &Run<T> {
        &self.run
    }

    /// `rolling_time_s`, `rolling_velocity_x_m_s`, `rolling_velocity_y_m_s`, once it rolled.
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        self.rolled.map_or([None; MAX_MEASURES], |(t, v)| [Some(t), Some(v[0]), Some(v[1])])
    }
}
