//! [`Curling`]: a ring or a uniform disc launched sliding and spinning on a level table; it stops
//! sliding and spinning together (`docs/scenes.md`, "curling").

use super::{Run, SpatialScene};
use crate::params::{ParamError, check_step_within, params};
use crate::real::Real;
use crate::scene::BodyShape;
use crate::scene::{MAX_MEASURES, Outcome};
use crate::spatial::{
    Body, Mode, Plane, SpatialSettings, SpatialShape, SpatialStepReport, SpatialStepper, State, Vector,
    identity, norm,
};

/// The most points of the base: the stepper's `K` (its LCP `4 K` rows, at most 32).
pub const MAX_POINTS: usize = 8;

/// The rows of the curling stone's LCP: one friction line per point.
pub const CURLING_ROWS: usize = 4 * MAX_POINTS;

params! {
    /// Parameters of the curling scene, SI units (`docs/scenes.md`, "curling").
    pub struct CurlingParams {
        /// The base: 0 a ring (its points on its rim), 1 a uniform disc (its points each the
        /// centroid of an equal sector of its area). 1.
        shape: 1.0, NonNegative;
        /// Radius `R` (m, > 0). 0.145 (a curling stone's running band is 0.065; its body 0.145).
        radius: 0.145, Positive;
        /// Mass `m` (kg, > 0). 19.96.
        mass: 19.96, Positive;
        /// The points of the base (a whole number from 4 to 8). 8.
        points: 8.0, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-z`. 9.81.
        gravity: 9.81, NonNegative;
        /// The launch speed along `+x` (m/s, >= 0). 1.
        speed: 1.0, NonNegative;
        /// The launch spin about `+z` (rad/s). 5.
        spin: 5.0, Finite;
        /// Coefficient of friction (> 0). 0.1.
        mu: 0.1, Positive;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A loaded contact whose slip is at most this sticks (m/s, > 0). 1e-5.
        stick_speed: 1e-5, Positive;
        /// The run ends at this simulated time (s, > 0). 10.
        max_time: 10.0, Positive;
    }
}

impl<T: Real> CurlingParams<T> {
    /// Checks the parameters (`docs/scenes.md`, "curling", Validity).
    ///
    /// # Errors
    /// The first field refused: not finite, not positive or negative as its check says, `step`
    /// beyond `max_time`, `shape` neither 0 nor 1, `points` not a whole number from 4 to 8.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        let shape = self.shape.as_f64();
        // Exactly 0 or exactly 1: the two bases.
        #[allow(clippy::float_cmp)]
        if shape != 0.0 && shape != 1.0 {
            return Err(ParamError::OutOfRange("shape"));
        }
        self.count().ok_or(ParamError::OutOfRange("points"))?;
        self.body().validate().map_err(|_| ParamError::InertiaOutOfRange { mass: "mass", size: "radius" })
    }

    /// `true` for the ring, `false` for the disc.
    #[must_use]
    pub fn is_ring(&self) -> bool {
        self.shape.as_f64() == 0.0
    }

    /// The points, when `points` is a whole number from 4 to [`MAX_POINTS`].
    #[must_use]
    pub fn count(&self) -> Option<usize> {
        let p = self.points.as_f64();
        // A whole number from 4 to 8 (exactly its floor): exact as a usize.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::float_cmp)]
        ((4.0..=MAX_POINTS as f64).contains(&p) && p == libm::floor(p)).then_some(p as usize)
    }

    /// The body: a thin ring (`m R^2` about its axis, `m R^2 / 2` about a diameter) or a thin
    /// uniform disc (`m R^2 / 2`, `m R^2 / 4`).
    #[must_use]
    pub fn body(&self) -> Body<T> {
        let axis = if self.is_ring() { T::one() } else { T::of(0.5) } * self.mass * self.radius * self.radius;
        let across = axis * T::of(0.5);
        Body { mass: self.mass, inertia: [across, across, axis] }
    }

    /// The radius of the base's points off its centre (m): the rim for the ring; for the disc of
    /// `n` points, the centroid of each of its `n` equal sectors, `(2 / 3) R sin(pi / n) / (pi /
    /// n)` (`docs/scenes.md`, "curling": a layout of point loads ends turning about one of its
    /// points, so this radius over `R` is the ratio it ends at).
    #[must_use]
    pub fn rim(&self, n: usize) -> T {
        let r = self.radius;
        if self.is_ring() {
            return r;
        }
        let half = core::f64::consts::PI / n as f64;
        T::of(2.0 / 3.0 * libm::sin(half) / half) * r
    }

    /// The base's points in the body's frame (its centre of mass in their plane), `Unused` past
    /// `points`.
    #[must_use]
    pub fn base(&self) -> [SpatialShape<T>; MAX_POINTS] {
        let n = self.count().unwrap_or(MAX_POINTS);
        let rim = self.rim(n);
        core::array::from_fn(|i| {
            if i >= n {
                return SpatialShape::Unused;
            }
            let a = T::of(core::f64::consts::TAU * i as f64 / n as f64);
            let (s, c) = a.sin_cos_portable();
            SpatialShape::Point { offset: [rim * c, rim * s, T::zero()] }
        })
    }
}

/// What the run has measured: when sliding and spinning stopped, the last ratio.
#[derive(Debug, Clone, Copy)]
struct Stops<T> {
    slide: Option<T>,
    spin: Option<T>,
    ratio: Option<T>,
}

/// The curling scene, as `docs/scenes.md` defines it.
#[derive(Debug, Clone)]
pub struct Curling<T: Real> {
    params: CurlingParams<T>,
    run: Run<T, CURLING_ROWS, MAX_POINTS>,
    stops: Stops<T>,
}

impl<T: Real> Curling<T> {
    /// The stone at its start, its base on the table.
    ///
    /// # Errors
    /// [`CurlingParams::validate`]'s, or the stepper's ([`SpatialStepper::new`]).
    pub fn new(params: CurlingParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let settings = SpatialSettings {
            step: params.step,
            gravity: [T::zero(), T::zero(), -params.gravity],
            stick_speed: params.stick_speed,
            ..SpatialSettings::default()
        };
        let state = State {
            position: [T::zero(); 3],
            orientation: identity(),
            velocity: [params.speed, T::zero(), T::zero()],
            angular_velocity: [T::zero(), T::zero(), params.spin],
        };
        let stepper = SpatialStepper::new(
            params.body(),
            params.base(),
            Plane::table(T::zero(), params.mu),
            settings,
            state,
        )?;
        Ok(Self {
            params,
            run: Run::new(stepper, params.max_time),
            stops: Stops { slide: None, spin: None, ratio: None },
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &CurlingParams<T> {
        &self.params
    }
}

/// The sliding speed `|v|` and the rim's speed `R |omega_z|` of `state`.
fn speeds<T: Real>(velocity: &Vector<T>, spin: T, radius: T) -> (T, T) {
    (norm(&[velocity[0], velocity[1], T::zero()]), radius * spin.abs_exact())
}

impl<T: Real> SpatialScene<T, CURLING_ROWS, MAX_POINTS> for Curling<T> {
    fn step(&mut self) -> Option<SpatialStepReport<T, MAX_POINTS>> {
        let (p, stops) = (self.params, &mut self.stops);
        let before = *self.run.stepper.state();
        let (v0, w0) = speeds(&before.velocity, before.angular_velocity[2], p.radius);
        // The ratio is read while both speeds are at least ten steps of friction's deceleration,
        // `10 mu g h` (the last steps are the step's, not the motion's).
        let floor = T::of(10.0) * p.mu * p.gravity * p.step;
        if v0 >= floor && w0 >= floor {
            stops.ratio = Some(v0 / w0);
        }
        let time = self.run.stepper.time() + p.step;
        let rim = p.rim(p.count().unwrap_or(MAX_POINTS));
        self.run.advance(
            |r| {
                // Spinning stops when the base's outermost point's turning speed does.
                let (v, w) = speeds(&r.state.velocity, r.state.angular_velocity[2], rim);
                if stops.slide.is_none() && v <= p.stick_speed {
                    stops.slide = Some(time);
                }
                if stops.spin.is_none() && w <= p.stick_speed {
                    stops.spin = Some(time);
                }
                (stops.slide.is_some() && stops.spin.is_some()
                    || r.contacts.iter().all(|c| c.mode != Mode::Sliding))
                .then_some(Outcome::Stopped)
            },
            Outcome::Slid,
        )
    }

    fn go_on(&mut self) -> Option<Outcome> {
        self.run.outcome.take()
    }

    fn outcome(&self) -> Option<Outcome> {
        self.run.outcome
    }

    fn shape(&self) -> BodyShape<T> {
        BodyShape::Puck { radius: self.params.radius, thickness: self.params.radius * T::of(0.1) }
    }

    fn run(&self) -> &Run<T, CURLING_ROWS, MAX_POINTS> {
        &self.run
    }

    /// `terminal_ratio`, `slide_stop_s`, `spin_stop_s`, each once it is known.
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        [self.stops.ratio, self.stops.slide, self.stops.spin]
    }
}
