//! [`ThreeFingers`]: a rod on three fingers, finger 1 moving toward finger 2 until they are the
//! finger width apart (`core/examples/three_fingers.rs`, written from the public API only, with
//! its numbers as parameters here so that the catalogue can offer it: `host-sim scene --scene
//! three-fingers`).
//!
//! With three supports under a rigid rod the normal forces are statically indeterminate (only
//! their sum and moment are fixed), so each step's LCP has a family of solutions, and since friction
//! is `mu` times the normal force, different splits drag the rod differently: rigid contact with
//! friction does not decide this motion. The stepper takes the motion of least kinetic energy and,
//! with it, the load of least 2-norm (`docs/formulation.md`, "The load: the least norm"): at rest
//! the split equally stiff fingers give, `N_i = a + b x_i`.
//!
//! **Sizes.** `N = 9`: finger 1 keeps `+d`, fingers 2 and 3 keep `-d`, checked every step against
//! the full layout (12); `N = 12` is the full form.
//!
//! **Outcome** after each step: **Fell** when `|theta| > tilt_limit` or no finger is under the rod;
//! **Held** when finger 1 stopped at least `hold_time` ago; **Unfinished** at `max_time`.

use super::outcome::Outcome;
use super::scene_trait::impl_scene;
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{
    Body, BodyState, Contact, EventLog, Feature, Layout, Model, Settings, StepReport, Stepper, Support,
    Tangents,
};
use crate::real::Real;

params! {
    /// Parameters of the three-finger scene, SI units (`core/examples/three_fingers.rs`'s numbers).
    pub struct ThreeFingersParams {
        /// Rod length `L` (m, > 0). 1.
        rod_length: 1.0, Positive;
        /// Rod thickness (m, > 0). 0.005.
        rod_thickness: 0.005, Positive;
        /// Rod mass (kg, > 0). 0.2.
        rod_mass: 0.2, Positive;
        /// Gravity (m/s^2, >= 0). 9.81.
        gravity: 9.81, NonNegative;
        /// Finger 1's start x (m, within `L/2`). -0.4.
        finger1_x: -0.4, Finite;
        /// Finger 2's x (m). 0.
        finger2_x: 0.0, Finite;
        /// Finger 3's x (m). 0.4.
        finger3_x: 0.4, Finite;
        /// Finger 1's velocity (m/s); it stops at `finger2_x - finger_width`. 0.1.
        finger1_velocity: 0.1, Finite;
        /// Finger 1 stops this far from finger 2 (m, >= 0). 0.01.
        finger_width: 0.01, NonNegative;
        /// Static friction coefficient of every finger (>= 0). 0.6.
        mu_static: 0.6, NonNegative;
        /// Kinetic friction coefficient of every finger (0 <= mu_k <= mu_s). 0.4.
        mu_kinetic: 0.4, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching contact whose slip speed is at most this sticks (m/s, >= 0). 1e-5.
        stick_speed: 1e-5, NonNegative;
        /// The rod has fallen when it tilted more than this (rad, > 0). 0.35.
        tilt_limit: 0.35, Positive;
        /// The rod holds when it stayed on the fingers this long after finger 1 stopped (s, >= 0). 0.5.
        hold_time: 0.5, NonNegative;
        /// The run ends at this simulated time (s, > 0). 30.
        max_time: 30.0, Positive;
    }
}

impl<T: Real> ThreeFingersParams<T> {
    /// Checks every parameter.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        Body::check_rod(
            self.rod_mass,
            self.rod_length,
            self.rod_thickness,
            ["rod_mass", "rod_length", "rod_thickness"],
        )?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if self.finger_outside_rod().is_some() {
            return Err(ParamError::FingerOutsideRod);
        }
        if self.finger_out_of_order().is_some() {
            return Err(ParamError::FingersCrossed);
        }
        Ok(())
    }

    /// The first finger (its field) that starts beyond an end of the rod
    /// ([`ParamError::FingerOutsideRod`]).
    #[must_use]
    pub fn finger_outside_rod(&self) -> Option<&'static str> {
        let half = self.rod_length / T::of(2.0);
        [("finger1_x", self.finger1_x), ("finger2_x", self.finger2_x), ("finger3_x", self.finger3_x)]
            .into_iter()
            .find(|(_, x)| x.abs_exact() > half)
            .map(|(field, _)| field)
    }

    /// The finger (its field) out of order ([`ParamError::FingersCrossed`]): `finger1_x` when
    /// finger 1 does not start left of finger 2 by more than the finger width, `finger3_x` when
    /// finger 3 does not start right of finger 2.
    #[must_use]
    pub fn finger_out_of_order(&self) -> Option<&'static str> {
        if self.finger2_x - self.finger1_x > self.finger_width {
            if self.finger3_x > self.finger2_x { None } else { Some("finger3_x") }
        } else {
            Some("finger1_x")
        }
    }

    /// Where finger 1 stops.
    #[must_use]
    pub fn stop_x(&self) -> T {
        self.finger2_x - self.finger_width
    }

    fn fingers(&self, x1: T, v1: T) -> [Support<T>; 3] {
        let z = T::zero();
        [
            Support::point([x1, z], [v1, z]),
            Support::point([self.finger2_x, z], [z; 2]),
            Support::point([self.finger3_x, z], [z; 2]),
        ]
    }
}

/// A rod on three fingers with an `N x N` LCP per step (9: finger 1 `+d`, fingers 2 and 3 `-d`,
/// checked; 12: the full form) and room for `E` switch events.
#[derive(Debug, Clone)]
pub struct ThreeFingers<T: Real, const N: usize = 9, const E: usize = 64> {
    params: ThreeFingersParams<T>,
    stepper: Stepper<T, 3, N, 12>,
    events: EventLog<T, 3, E>,
    stopped_at: Option<T>,
    outcome: Option<Outcome>,
}

impl<T: Real, const N: usize, const E: usize> ThreeFingers<T, N, E> {
    /// The rod at rest, level, on the three finger tips.
    ///
    /// # Errors
    /// The first invalid parameter.
    pub fn new(params: ThreeFingersParams<T>) -> Result<Self, ParamError> {
        const { assert!(N == 9 || N == 12, "the three-finger scene has N = 9 or N = 12") };
        params.validate()?;
        let p = &params;
        let finger =
            Contact { feature: Feature::LowerFace, mu_static: p.mu_static, mu_kinetic: p.mu_kinetic };
        let model = Model {
            body: Body::rod(p.rod_mass, p.rod_length, p.rod_thickness),
            contacts: [finger; 3],
            settings: Settings { step: p.step, gravity: p.gravity, stick_speed: p.stick_speed },
        };
        let layout = const {
            Layout::<3, N>::new(if N == 12 {
                [Tangents::Both; 3]
            } else {
                [Tangents::Plus, Tangents::Minus, Tangents::Minus]
            })
        };
        let start = BodyState::at_rest(T::zero(), p.rod_thickness / T::of(2.0), T::zero());
        let stepper =
            Stepper::new(model, layout, Layout::full(), start, p.fingers(p.finger1_x, p.finger1_velocity))?;
        Ok(Self { params, stepper, events: EventLog::new(), stopped_at: None, outcome: None })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &ThreeFingersParams<T> {
        &self.params
    }

    /// When finger 1 stopped (s), once it has.
    #[must_use]
    pub const fn stopped_at(&self) -> Option<T> {
        self.stopped_at
    }

    /// Advances one step; `None` once the run has an outcome.
    fn advance(&mut self) -> Option<StepReport<T, 3>> {
        if self.outcome.is_some() {
            return None;
        }
        let p = self.params;
        let t = self.stepper.next_time();
        let x = p.finger1_x + p.finger1_velocity * t;
        let (x1, v1) = if x < p.stop_x() { (x, p.finger1_velocity) } else { (p.stop_x(), T::zero()) };
        let report = match self.stepper.step(&p.fingers(x1, v1)) {
            Ok(r) => r,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.events.record(&report);
        if v1 == T::zero() && self.stopped_at.is_none() {
            self.stopped_at = Some(t);
        }
        let on_a_finger = self.stepper.frames().iter().any(|f| f.active);
        if report.state.theta.abs_exact() > p.tilt_limit || !on_a_finger {
            self.outcome = Some(Outcome::Fell);
        } else if self.stopped_at.is_some_and(|s| t - s >= p.hold_time) {
            self.outcome = Some(Outcome::Held);
        } else if report.time >= p.max_time {
            self.outcome = Some(Outcome::Unfinished);
        }
        Some(report)
    }
}

impl<T: Real, const N: usize, const E: usize> ThreeFingers<T, N, E> {
    /// [`Scene::measured`](crate::scene::Scene::measured): nothing.
    #[allow(clippy::unused_self)] // the scene measures nothing; `impl_scene!` calls it
    fn measured_values(&self) -> [Option<T>; crate::scene::MAX_MEASURES] {
        [None; crate::scene::MAX_MEASURES]
    }
}

impl_scene!(
    ThreeFingers,
    3,
    |p| crate::scene::BodyShape::Box { width: p.rod_length, height: p.rod_thickness },
    |p| Body::rod(p.rod_mass, p.rod_length, p.rod_thickness)
);

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// Finger 1 slides under the rod to the middle finger and stops there; the rod stays on the
    /// fingers, level, and every step carries the rod's weight (`sum p_n = m g h` at rest).
    #[test]
    fn finger_one_reaches_the_middle_and_the_rod_holds() {
        for full in [false, true] {
            let p = ThreeFingersParams::<f64>::default();
            let (outcome, last) = if full {
                let mut s = ThreeFingers::<f64, 12>::new(p).unwrap();
                let mut last = None;
                (s.run(|r| last = Some(*r)), last.unwrap())
            } else {
                let mut s = ThreeFingers::<f64, 9>::new(p).unwrap();
                let mut last = None;
                (s.run(|r| last = Some(*r)), last.unwrap())
            };
            assert_eq!(outcome, Outcome::Held, "full {full}");
            let total: f64 = last.contacts.iter().map(|c| c.normal_impulse).sum();
            assert!((total / (p.rod_mass * p.gravity * p.step) - 1.0).abs() < 1e-9, "{total}");
            assert!(last.state.theta.abs() < 1e-9);
        }
    }

    #[test]
    fn crossed_fingers_are_refused() {
        let p = ThreeFingersParams::<f64> { finger2_x: -0.395, ..Default::default() };
        assert_eq!(ThreeFingers::<f64>::new(p).err(), Some(ParamError::FingersCrossed));
        let p = ThreeFingersParams::<f64> { finger3_x: 0.6, ..Default::default() };
        assert_eq!(ThreeFingers::<f64>::new(p).err(), Some(ParamError::FingerOutsideRod));
    }
}
