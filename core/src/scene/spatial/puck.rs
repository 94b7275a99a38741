//! [`Puck`]: a puck launched across a level table or an incline (`docs/scenes.md`, "puck").

use super::{Run, SpatialScene};
use crate::params::{ParamError, check_step_within, params};
use crate::real::Real;
use crate::scene::BodyShape;
use crate::scene::{MAX_MEASURES, Outcome};
use crate::spatial::{
    Body, FrictionCone, Mode, OneContact, Plane, SpatialSettings, SpatialShape, SpatialStepReport, State,
    Vector, about,
};

params! {
    /// Parameters of the puck scene, SI units, angles in radians (`docs/scenes.md`, "puck").
    pub struct PuckParams {
        /// Radius `r` (m, > 0). 0.0381 (an ice-hockey puck).
        radius: 0.0381, Positive;
        /// Thickness `t` (m, > 0): its moments, not its contact (it touches at its centre). 0.0254.
        thickness: 0.0254, Positive;
        /// Mass `m` (kg, > 0). 0.17.
        mass: 0.17, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-z`. 9.81.
        gravity: 9.81, NonNegative;
        /// The plane's incline `alpha` about the world's `x` axis (rad, `0 <= alpha < pi/2`; 0 a
        /// level table). 20 degrees.
        angle: 0.349_065_850_398_865_9, Finite;
        /// The launch's heading `phi` from `x` (across the slope) toward down the slope (rad).
        /// 0.
        heading: 0.0, Finite;
        /// The launch speed (m/s, >= 0). 0.9.
        speed: 0.9, NonNegative;
        /// Static friction coefficient (>= 0). 0.4.
        mu_static: 0.4, NonNegative;
        /// Kinetic friction coefficient (0 <= mu_k <= mu_s). 0.4.
        mu_kinetic: 0.4, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A loaded contact whose slip is at most this sticks (m/s, > 0). 1e-5.
        stick_speed: 1e-5, Positive;
        /// The run ends at this simulated time (s, > 0). 5.
        max_time: 5.0, Positive;
    }
}

impl<T: Real> PuckParams<T> {
    /// Checks the parameters (`docs/scenes.md`, "puck", Validity).
    ///
    /// # Errors
    /// The first field refused: not finite, not positive or negative as its check says, `step`
    /// beyond `max_time`, `mu_kinetic` above `mu_static`, `angle` outside `[0, pi/2)`, moments a
    /// precision cannot hold.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if !(self.angle >= T::zero() && self.angle < T::frac_pi_2()) {
            return Err(ParamError::OutOfRange("angle"));
        }
        self.body().validate().map_err(|_| ParamError::InertiaOutOfRange { mass: "mass", size: "radius" })
    }

    /// The puck: a uniform cylinder, moments `m (3 r^2 + t^2) / 12` about its face's axes and
    /// `m r^2 / 2` about its own.
    #[must_use]
    pub fn body(&self) -> Body<T> {
        let (m, r, t) = (self.mass, self.radius, self.thickness);
        let across = m * (T::of(3.0) * r * r + t * t) / T::of(12.0);
        Body { mass: m, inertia: [across, across, m * r * r * T::of(0.5)] }
    }

    /// `(e_x, e_down)`: across the slope and down it, in the plane.
    #[must_use]
    pub fn plane_axes(&self) -> (Vector<T>, Vector<T>) {
        let (s, c) = self.angle.sin_cos_portable();
        ([T::one(), T::zero(), T::zero()], [T::zero(), c, -s])
    }
}

/// The puck scene, as `docs/scenes.md` defines it.
#[derive(Debug, Clone)]
pub struct Puck<T: Real> {
    params: PuckParams<T>,
    run: Run<T>,
}

impl<T: Real> Puck<T> {
    /// The puck at its start.
    ///
    /// # Errors
    /// [`PuckParams::validate`]'s, or the stepper's ([`OneContact::new`]).
    pub fn new(params: PuckParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let (s, c) = params.angle.sin_cos_portable();
        let (e_x, e_down) = params.plane_axes();
        let (sh, ch) = params.heading.sin_cos_portable();
        let velocity = core::array::from_fn(|i| params.speed * (ch * e_x[i] + sh * e_down[i]));
        let plane = Plane {
            point: [T::zero(); 3],
            normal: [T::zero(), s, c],
            mu_static: params.mu_static,
            mu_kinetic: params.mu_kinetic,
        };
        let settings = SpatialSettings {
            step: params.step,
            gravity: [T::zero(), T::zero(), -params.gravity],
            stick_speed: params.stick_speed,
            friction: FrictionCone::Circular,
            ..SpatialSettings::default()
        };
        let state = State {
            position: [T::zero(); 3],
            // Its axis along the plane's normal (0, sin, cos): a turn by -alpha about x.
            orientation: about(&[T::one(), T::zero(), T::zero()], -params.angle),
            velocity,
            angular_velocity: [T::zero(); 3],
        };
        let stepper = OneContact::new(
            params.body(),
            [SpatialShape::Point { offset: [T::zero(); 3] }],
            plane,
            settings,
            state,
        )?;
        Ok(Self { params, run: Run::new(stepper, params.max_time) })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &PuckParams<T> {
        &self.params
    }
}

impl<T: Real> SpatialScene<T> for Puck<T> {
    fn step(&mut self) -> Option<SpatialStepReport<T, 1>> {
        self.run
            .advance(|r| (r.contacts[0].mode == Mode::Sticking).then_some(Outcome::Stopped), Outcome::Slid)
    }

    fn go_on(&mut self) -> Option<Outcome> {
        self.run.outcome.take()
    }

    fn outcome(&self) -> Option<Outcome> {
        self.run.outcome
    }

    fn shape(&self) -> BodyShape<T> {
        BodyShape::Puck { radius: self.params.radius, thickness: self.params.thickness }
    }

    fn run(&self) -> &Run<T> {
        &self.run
    }

    /// `final_speed_m_s`, `displacement_m`, `displacement_heading_deg` (none while it has moved
    /// less than `stick_speed h`).
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        let state = self.run.stepper.state();
        let speed = crate::spatial::norm(&state.velocity);
        let moved = state.position;
        let displacement = crate::spatial::norm(&moved);
        let (e_x, e_down) = self.params.plane_axes();
        // Moved less than a sticking contact creeps in one step: no heading (round-off's).
        let heading = (displacement > self.params.stick_speed * self.params.step).then(|| {
            let across = crate::spatial::dot(&moved, &e_x).as_f64();
            let down = crate::spatial::dot(&moved, &e_down).as_f64();
            T::of(libm::atan2(down, across).to_degrees())
        });
        [Some(speed), Some(displacement), heading]
    }
}
