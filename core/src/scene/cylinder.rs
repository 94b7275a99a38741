//! [`Cylinder`]: a round body released from rest on an incline (`docs/scenes.md`, "cylinder").
//!
//! A body of radius `r`, mass `m` and inertia `J = k m r^2` (`k = 1/2`: a solid cylinder; `1`: a
//! thin ring) touches the plane through the origin rising at `alpha` ([`Feature::Round`] on a
//! line, contact 0): `n = (-sin alpha, cos alpha)`, `d = (cos alpha, sin alpha)` (up the slope).
//! Rolling without slipping needs the friction `f = m g sin(alpha) k / (1 + k)` and the normal
//! force `m g cos(alpha)`, so it **rolls** iff `tan(alpha) <= mu_s (1 + k) / k`, accelerating at
//! `a = g sin(alpha) / (1 + k)`; otherwise it **slides** (and spins up) with
//! `a = g (sin(alpha) - mu_k cos(alpha))`.
//!
//! **Sizes.** `N = 3` keeps `+d` (friction on a body moving down the slope points up it), checked
//! every step with the full form as fallback; `N = 4` is the full form.

use super::outcome::Outcome;
use super::scene_trait::impl_scene;
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{
    Body, BodyState, Contact, EventLog, Feature, Layout, Model, Settings, StepReport, Stepper, Support,
    Tangents,
};
use crate::real::Real;

params! {
    /// Parameters of the cylinder scene, SI units, angles in radians (`docs/scenes.md`).
    pub struct CylinderParams {
        /// Radius `r` (m, > 0). 0.1.
        radius: 0.1, Positive;
        /// Mass (kg, > 0). 1.
        mass: 1.0, Positive;
        /// `k` in `J = k m r^2` (> 0): 0.5 a solid cylinder, 1 a thin ring. 0.5.
        inertia_factor: 0.5, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-y`. 9.81.
        gravity: 9.81, NonNegative;
        /// Slope angle `alpha` (rad, `0 <= alpha < pi/2`). 30 degrees.
        angle: 0.523_598_775_598_298_8, Finite;
        /// Static friction coefficient (>= 0). 0.6.
        mu_static: 0.6, NonNegative;
        /// Kinetic friction coefficient (0 <= mu_k <= mu_s). 0.4.
        mu_kinetic: 0.4, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching contact whose slip speed is at most this sticks (m/s, >= 0). 1e-5.
        stick_speed: 1e-5, NonNegative;
        /// The run ends at this simulated time (s, > 0). 1.
        max_time: 1.0, Positive;
    }
}

impl<T: Real> CylinderParams<T> {
    /// The body: a disc of the radius, `J = k m r^2`.
    #[must_use]
    pub fn body(&self) -> Body<T> {
        Body {
            width: self.radius + self.radius,
            height: self.radius + self.radius,
            mass: self.mass,
            inertia: self.inertia_factor * self.mass * self.radius * self.radius,
        }
    }

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
        self.body().check_inertia("mass", "radius")?;
        Ok(())
    }

    /// `true` when the analytic law says it rolls: `tan(alpha) <= mu_s (1 + k) / k`.
    #[must_use]
    pub fn rolls(&self) -> bool {
        let (s, c) = self.angle.sin_cos_portable();
        let k = self.inertia_factor;
        s * k <= self.mu_static * (T::one() + k) * c
    }

    /// The analytic acceleration down the slope (m/s^2): `g sin / (1 + k)` rolling,
    /// `g (sin - mu_k cos)` sliding.
    #[must_use]
    pub fn analytic_acceleration(&self) -> T {
        let (s, c) = self.angle.sin_cos_portable();
        if self.rolls() {
            self.gravity * s / (T::one() + self.inertia_factor)
        } else {
            self.gravity * (s - self.mu_kinetic * c)
        }
    }

    /// At rest on the plane: centre `r n = (-sin(alpha) r, cos(alpha) r)`, angle 0.
    #[must_use]
    pub fn resting_state(&self) -> BodyState<T> {
        let (s, c) = self.angle.sin_cos_portable();
        BodyState::at_rest(-s * self.radius, c * self.radius, T::zero())
    }

    /// The plane: through the origin, normal `(-sin alpha, cos alpha)`, at rest.
    #[must_use]
    pub fn plane(&self) -> Support<T> {
        let (s, c) = self.angle.sin_cos_portable();
        Support::fixed_line([T::zero(); 2], [-s, c])
    }
}

/// A round body on an incline with an `N x N` LCP per step (3: `+d`, checked; 4: the full form)
/// and room for `E` switch events.
#[derive(Debug, Clone)]
pub struct Cylinder<T: Real, const N: usize = 3, const E: usize = 64> {
    params: CylinderParams<T>,
    stepper: Stepper<T, 1, N, 4>,
    plane: Support<T>,
    events: EventLog<T, 1, E>,
    /// `(t_1, u(t_1), omega(t_1))` at the end of the first step.
    first: Option<(T, T, T)>,
    slid: bool,
    outcome: Option<Outcome>,
}

impl<T: Real, const N: usize, const E: usize> Cylinder<T, N, E> {
    /// The body at rest on the plane.
    ///
    /// # Errors
    /// The first invalid parameter.
    pub fn new(params: CylinderParams<T>) -> Result<Self, ParamError> {
        const { assert!(N == 3 || N == 4, "the cylinder scene has N = 3 or N = 4") };
        params.validate()?;
        let p = &params;
        let body = p.body();
        let contact =
            Contact { feature: Feature::Round(p.radius), mu_static: p.mu_static, mu_kinetic: p.mu_kinetic };
        let settings = Settings { step: p.step, gravity: p.gravity, stick_speed: p.stick_speed };
        let model = Model { body, contacts: [contact], settings };
        let layout = const { Layout::<1, N>::new(if N == 4 { [Tangents::Both] } else { [Tangents::Plus] }) };
        let plane = p.plane();
        let stepper = Stepper::new(model, layout, Layout::full(), p.resting_state(), [plane])?;
        Ok(Self { params, stepper, plane, events: EventLog::new(), first: None, slid: false, outcome: None })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &CylinderParams<T> {
        &self.params
    }

    /// The velocity down the slope, `-(vx cos alpha + vy sin alpha)` (m/s).
    #[must_use]
    pub fn speed_down_slope(&self) -> T {
        let Support::Line { normal, .. } = self.plane else { return T::zero() };
        let s = self.stepper.state();
        -(s.vx * normal[1] - s.vy * normal[0])
    }

    /// The acceleration down the slope after the first step (m/s^2):
    /// `(u(t_end) - u(t_1)) / (t_end - t_1)`, `t_1` the end of the first step (which used `mu_s`);
    /// `None` before the run ended.
    #[must_use]
    pub fn acceleration(&self) -> Option<T> {
        let (t1, u1, _) = self.first?;
        let dt = self.stepper.time() - t1;
        (self.outcome.is_some_and(|o| o.is_physical()) && dt > T::zero())
            .then(|| (self.speed_down_slope() - u1) / dt)
    }

    /// The angular acceleration after the first step, counter-clockwise (rad/s^2):
    /// `(omega(t_end) - omega(t_1)) / (t_end - t_1)`, as [`Self::acceleration`]; rolling down the
    /// slope (toward `-x`) it is `a / r`; `None` before the run ended.
    #[must_use]
    pub fn angular_acceleration(&self) -> Option<T> {
        let (t1, _, w1) = self.first?;
        let dt = self.stepper.time() - t1;
        (self.outcome.is_some_and(|o| o.is_physical()) && dt > T::zero())
            .then(|| (self.stepper.state().omega - w1) / dt)
    }

    /// [`Scene::measured`](crate::scene::Scene::measured): the acceleration and the angular
    /// acceleration.
    fn measured_values(&self) -> [Option<T>; crate::scene::MAX_MEASURES] {
        [self.acceleration(), self.angular_acceleration(), None]
    }

    /// Advances one step; `None` once the run has an outcome.
    fn advance(&mut self) -> Option<StepReport<T, 1>> {
        if self.outcome.is_some() {
            return None;
        }
        let report = match self.stepper.step(&[self.plane]) {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.events.record(&report);
        if self.first.is_none() {
            self.first = Some((report.time, self.speed_down_slope(), report.state.omega));
        }
        self.slid |= report.contacts[0].mode.is_sliding();
        if report.time >= self.params.max_time {
            self.outcome = Some(if self.slid { Outcome::Slid } else { Outcome::Rolled });
        }
        Some(report)
    }
}

impl_scene!(Cylinder, 1, |p| crate::scene::BodyShape::Disc { radius: p.radius }, |p| p.body());

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// The scene's measured quantities after a run in the full (4) or reduced (3) layout.
    fn measured(p: CylinderParams<f64>, full: bool) -> [Option<f64>; crate::scene::MAX_MEASURES] {
        if full {
            let mut c = Cylinder::<f64, 4>::new(p).unwrap();
            c.run(|_| {});
            c.measured()
        } else {
            let mut c = Cylinder::<f64, 3>::new(p).unwrap();
            c.run(|_| {});
            c.measured()
        }
    }

    fn run<const N: usize>(p: CylinderParams<f64>) -> (Outcome, f64, BodyState<f64>) {
        let mut c = Cylinder::<f64, N>::new(p).unwrap();
        let o = c.run(|_| {});
        (o, c.acceleration().unwrap(), *c.state())
    }

    /// Below the critical angle `atan(mu_s (1 + k) / k)` it rolls at `g sin / (1 + k)` with
    /// `omega r = u` (counter-clockwise, down a slope rising to the right: toward `-x`); above it,
    /// it slides at `g (sin - mu_k cos)` and spins slower than rolling needs. `k = 0.5`, `mu_s = 0.2`: critical angle 30.96 degrees.
    #[test]
    fn rolls_below_the_critical_angle_and_slides_above_it() {
        for k in [0.5, 1.0, 0.4] {
            let critical = (0.2_f64 * (1.0 + k) / k).atan().to_degrees();
            for (deg, want) in [(critical - 2.0, Outcome::Rolled), (critical + 2.0, Outcome::Slid)] {
                let p = CylinderParams {
                    angle: deg.to_radians(),
                    mu_static: 0.2,
                    mu_kinetic: 0.15,
                    inertia_factor: k,
                    ..CylinderParams::default()
                };
                assert_eq!(p.rolls(), want == Outcome::Rolled);
                for full in [false, true] {
                    let (outcome, a, s) = if full { run::<4>(p) } else { run::<3>(p) };
                    assert_eq!(outcome, want, "k {k}, {deg} deg, full {full}");
                    let exact = p.analytic_acceleration();
                    assert!((a / exact - 1.0).abs() < 1e-9, "k {k}, {deg} deg: {a} vs {exact}");
                    // Rolling: a / r; sliding: friction's torque mu_k N r / J = mu_k g cos / (k r).
                    let spin = if want == Outcome::Rolled {
                        exact / p.radius
                    } else {
                        p.mu_kinetic * p.gravity * deg.to_radians().cos() / (k * p.radius)
                    };
                    let c = measured(p, full);
                    assert_eq!(c[0], Some(a), "measured: the acceleration first");
                    let w = c[1].unwrap();
                    assert!((w / spin - 1.0).abs() < 1e-9, "k {k}, {deg} deg: omega' {w} vs {spin}");
                    let u = -(s.vx * deg.to_radians().cos() + s.vy * deg.to_radians().sin());
                    if want == Outcome::Rolled {
                        assert!((s.omega * p.radius - u).abs() < 1e-9, "rolling: omega r = u");
                    } else {
                        assert!(u - s.omega * p.radius > 1e-3, "sliding: slips");
                    }
                }
            }
        }
    }

    #[test]
    fn a_bad_radius_is_refused() {
        let p = CylinderParams::<f64> { radius: 0.0, ..CylinderParams::default() };
        assert_eq!(Cylinder::<f64>::new(p).err(), Some(ParamError::NotPositive("radius")));
    }
}
