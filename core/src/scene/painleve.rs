//! [`Painleve`]: Painlevé's paradox (`docs/scenes.md`, "painleve").
//!
//! A uniform rod of length `L` (`J = m L^2 / 12`) leans at `theta0` from a rough floor, its lower end
//! on the floor (contact 0: [`Feature::Point`] `(-L/2, 0)` on the line `y = 0`), its centre of mass to
//! the right of the end, and the whole rod moves along `x` at `speed = -V < 0`: the end slides away
//! from under the rod. Friction on the end points `+x` (`+d`) and turns the rod into the floor. With
//! `c = cos(theta0)`, `s = sin(theta0)`, the end's response to an impulse `P` on it is
//! `K = (1/m) [[1 + 3 s^2, -3 s c], [-3 s c, 1 + 3 c^2]]`, and while it slides the normal impulse
//! pushes the end *into* the floor when `1 + 3 c^2 - 3 mu s c < 0`, i.e. when
//! `mu > (1 + 3 c^2) / (3 s c)`: no sliding motion keeps the contact. Then the only motion is a
//! tangential impact that stops the end within one step (it **jams**), with the impulse
//! `P = K^-1 (V, 0) = (m V / 4) (1 + 3 c^2, 3 s c)`: friction `m V (1 + 3 c^2) / 4`, normal
//! `3 m V s c / 4`, which does not vanish as `h -> 0` (a force of order `1/h`), and lies in the
//! friction cone exactly when `mu >= (1 + 3 c^2) / (3 s c)`.
//!
//! **Sizes.** `N = 3` keeps `+d`, checked every step with the full form as fallback; `N = 4` is the
//! full form.

use super::outcome::Outcome;
use super::scene_trait::impl_scene;
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{
    Body, BodyState, Contact, ContactMode, EventLog, Feature, Layout, Model, Settings, StepReport, Stepper,
    Support, Tangents,
};
use crate::real::Real;

params! {
    /// Parameters of the Painlevé scene, SI units, angles in radians (`docs/scenes.md`).
    pub struct PainleveParams {
        /// Rod length `L` (m, > 0). 1.
        length: 1.0, Positive;
        /// Rod thickness (m, > 0; for drawing only). 0.02.
        thickness: 0.02, Positive;
        /// Rod mass (kg, > 0). 1.
        mass: 1.0, Positive;
        /// Gravity `g` (m/s^2, >= 0). 9.81.
        gravity: 9.81, NonNegative;
        /// The rod's angle from the floor (rad, `0 < theta0 < pi/2`). 30 degrees.
        angle: 0.523_598_775_598_298_8, Finite;
        /// The rod's velocity along `x` at the start (m/s; negative: its lower end slides away from
        /// under it, the paradox's case). -1.
        speed: -1.0, Finite;
        /// Static friction coefficient of the floor (>= 0). 3.
        mu_static: 3.0, NonNegative;
        /// Kinetic friction coefficient of the floor (0 <= mu_k <= mu_s). 3 (the jam needs
        /// `mu_k > (1 + 3 c^2) / (3 s c)`: 2.50 at 30 degrees, 1.67 at 45, 1.35 at 60).
        mu_kinetic: 3.0, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching contact whose slip speed is at most this sticks (m/s, >= 0). 1e-5.
        stick_speed: 1e-5, NonNegative;
        /// The run ends at this simulated time (s, > 0). 0.5.
        max_time: 0.5, Positive;
    }
}

impl<T: Real> PainleveParams<T> {
    /// Checks every parameter.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        check_step_within(self.step, self.max_time)?;
        Body::check_rod(self.mass, self.length, self.thickness, ["mass", "length", "thickness"])?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if !(self.angle > T::zero() && self.angle < T::frac_pi_2()) {
            return Err(ParamError::OutOfRange("angle"));
        }
        Ok(())
    }

    /// `(1 + 3 c^2) / (3 s c)`: the kinetic friction coefficient above which the sliding end jams.
    #[must_use]
    pub fn critical_mu(&self) -> T {
        let (s, c) = self.angle.sin_cos_portable();
        let three = T::of(3.0);
        (T::one() + three * c * c) / (three * s * c)
    }

    /// The analytic jam impulses `(friction, normal)` (N s): `(m V / 4) (1 + 3 c^2, 3 s c)`,
    /// `V = -speed` (for `speed < 0`).
    #[must_use]
    pub fn jam_impulses(&self) -> (T, T) {
        let (s, c) = self.angle.sin_cos_portable();
        let three = T::of(3.0);
        let q = -self.mass * self.speed / T::of(4.0);
        (q * (T::one() + three * c * c), q * three * s * c)
    }

    /// The start: the lower end at the origin, the centre of mass at `(L/2) (cos, sin)`, moving at
    /// `speed` along `x`, not turning.
    #[must_use]
    pub fn start_state(&self) -> BodyState<T> {
        let (s, c) = self.angle.sin_cos_portable();
        let half = self.length / T::of(2.0);
        let mut state = BodyState::at_rest(half * c, half * s, self.angle);
        state.vx = self.speed;
        state
    }
}

/// The step on which the end jammed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Jam<T> {
    /// The end of the step (s).
    pub time: T,
    /// Its normal impulse (N s).
    pub normal_impulse: T,
    /// Its friction impulse along `+x` (N s).
    pub friction_impulse: T,
}

/// The rod of Painlevé's paradox with an `N x N` LCP per step (3: `+d`, checked; 4: the full form)
/// and room for `E` switch events.
#[derive(Debug, Clone)]
pub struct Painleve<T: Real, const N: usize = 3, const E: usize = 64> {
    params: PainleveParams<T>,
    stepper: Stepper<T, 1, N, 4>,
    floor: Support<T>,
    events: EventLog<T, 1, E>,
    jam: Option<Jam<T>>,
    /// The last step's contact impulse, `p_n + |p_f|` (N s; 0 before the first step).
    last_impulse: T,
    outcome: Option<Outcome>,
}

impl<T: Real, const N: usize, const E: usize> Painleve<T, N, E> {
    /// The rod at its start.
    ///
    /// # Errors
    /// The first invalid parameter.
    pub fn new(params: PainleveParams<T>) -> Result<Self, ParamError> {
        const { assert!(N == 3 || N == 4, "the Painleve scene has N = 3 or N = 4") };
        params.validate()?;
        let p = &params;
        let end = Contact {
            feature: Feature::Point([-p.length / T::of(2.0), T::zero()]),
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
        };
        let settings = Settings { step: p.step, gravity: p.gravity, stick_speed: p.stick_speed };
        let model = Model { body: Body::rod(p.mass, p.length, p.thickness), contacts: [end], settings };
        let layout = const { Layout::<1, N>::new(if N == 4 { [Tangents::Both] } else { [Tangents::Plus] }) };
        let floor = Support::fixed_line([T::zero(); 2], [T::zero(), T::one()]);
        let stepper = Stepper::new(model, layout, Layout::full(), p.start_state(), [floor])?;
        Ok(Self {
            params,
            stepper,
            floor,
            events: EventLog::new(),
            jam: None,
            last_impulse: T::zero(),
            outcome: None,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &PainleveParams<T> {
        &self.params
    }

    /// The jam, once it happened.
    #[must_use]
    pub const fn jam(&self) -> Option<Jam<T>> {
        self.jam
    }

    /// Advances one step; `None` once the run has an outcome.
    fn advance(&mut self) -> Option<StepReport<T, 1>> {
        if self.outcome.is_some() {
            return None;
        }
        let before = self.stepper.modes()[0];
        let report = match self.stepper.step(&[self.floor]) {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.events.record(&report);
        let c = report.contacts[0];
        let s = report.state;
        // An impact, not a stop by deceleration: more than twice what finite forces give over a
        // step (the last step's impulse and the weight's), docs/scenes.md "painleve".
        let impulse = c.normal_impulse + c.friction_impulse.abs();
        let p = &self.params;
        let finite = self.last_impulse + p.mass * p.gravity * p.step;
        self.last_impulse = impulse;
        if before.is_sliding() && c.mode == ContactMode::Sticking && impulse > finite + finite {
            self.jam = Some(Jam {
                time: report.time,
                normal_impulse: c.normal_impulse,
                friction_impulse: c.friction_impulse,
            });
            self.outcome = Some(Outcome::Jammed);
        } else if s.theta <= T::zero() || s.y <= T::zero() {
            self.outcome = Some(Outcome::Fell);
        } else if report.time >= self.params.max_time {
            self.outcome = Some(if c.mode.is_sliding() { Outcome::Slid } else { Outcome::Unfinished });
        }
        Some(report)
    }
}

impl<T: Real, const N: usize, const E: usize> Painleve<T, N, E> {
    /// [`Scene::measured`](crate::scene::Scene::measured): the jam's time and impulses.
    fn measured_values(&self) -> [Option<T>; crate::scene::MAX_MEASURES] {
        let j = self.jam;
        [j.map(|j| j.time), j.map(|j| j.normal_impulse), j.map(|j| j.friction_impulse)]
    }
}

impl_scene!(Painleve, 1, |p| crate::scene::BodyShape::Box { width: p.length, height: p.thickness }, |p| {
    Body::rod(p.mass, p.length, p.thickness)
});

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn run<const N: usize>(p: PainleveParams<f64>) -> (Outcome, Option<Jam<f64>>) {
        let mut r = Painleve::<f64, N>::new(p).unwrap();
        let o = r.run(|_| {});
        (o, r.jam())
    }

    /// Above the critical coefficient the end jams on the first step, with the analytic impulses
    /// of a tangential impact, which do not shrink with `h` (the weight's impulse `m g h` does): at
    /// `h = 1e-3 .. 1e-6` the impulses stay within `m g h` of the impact's. Below it, the end slides.
    #[test]
    fn the_end_jams_with_an_impulse_that_does_not_vanish_as_h_shrinks() {
        for deg in [30.0_f64, 45.0, 60.0] {
            let base = PainleveParams { angle: deg.to_radians(), ..PainleveParams::default() };
            let mu_c = base.critical_mu();
            let jamming = PainleveParams { mu_static: 1.2 * mu_c, mu_kinetic: 1.2 * mu_c, ..base };
            let (pf, pn) = jamming.jam_impulses();
            assert!(pf / pn <= jamming.mu_kinetic, "the impact is in the friction cone");
            for h in [1e-3, 1e-4, 1e-5, 1e-6] {
                let p = PainleveParams { step: h, ..jamming };
                for full in [false, true] {
                    let (outcome, jam) = if full { run::<4>(p) } else { run::<3>(p) };
                    assert_eq!(outcome, Outcome::Jammed, "{deg} deg, h {h}, full {full}");
                    let jam = jam.unwrap();
                    assert!(jam.time <= h * 1.5, "within one step: {}", jam.time);
                    let weight = p.mass * p.gravity * h;
                    assert!(
                        (jam.normal_impulse - pn).abs() <= weight,
                        "{deg} deg, h {h}: pn {} vs {pn}",
                        jam.normal_impulse
                    );
                    assert!(
                        (jam.friction_impulse - pf).abs() <= weight,
                        "{deg} deg, h {h}: pf {} vs {pf}",
                        jam.friction_impulse
                    );
                }
            }
            let sliding =
                PainleveParams { mu_static: 0.5 * mu_c, mu_kinetic: 0.5 * mu_c, max_time: 0.05, ..base };
            let (outcome, jam) = run::<3>(sliding);
            assert_eq!((outcome, jam), (Outcome::Slid, None), "{deg} deg below the critical mu");
        }
    }

    /// Below the critical coefficient the end slides under finite forces: the first step's
    /// impulses are proportional to `h` (their ratio to `h` the same within 1 % for
    /// `h = 1e-3 .. 1e-6`), and a slide slowed to a stop is no jam (its stopping impulse is of the
    /// order of the step's forces): the rod goes on to its own outcome.
    #[test]
    fn below_the_critical_mu_the_impulses_vanish_with_h_and_a_stop_is_no_jam() {
        for deg in [30.0_f64, 45.0, 60.0] {
            let base = PainleveParams { angle: deg.to_radians(), ..PainleveParams::default() };
            let mu = 0.8 * base.critical_mu();
            let sliding = PainleveParams { mu_static: mu, mu_kinetic: mu, ..base };
            let mut per_h: Option<(f64, f64)> = None;
            for h in [1e-3, 1e-4, 1e-5, 1e-6] {
                let mut rod = Painleve::<f64, 3>::new(PainleveParams { step: h, ..sliding }).unwrap();
                let c = rod.step().unwrap().contacts[0];
                assert!(c.mode.is_sliding(), "{deg} deg, h {h}: {:?}", c.mode);
                let force = (c.normal_impulse / h, c.friction_impulse / h);
                assert!(force.0 > 0.0, "{deg} deg, h {h}: the end presses on the floor");
                let first = *per_h.get_or_insert(force);
                assert!((force.0 / first.0 - 1.0).abs() < 1e-2, "{deg} deg, h {h}: {force:?} vs {first:?}");
                assert!((force.1 / first.1 - 1.0).abs() < 1e-2, "{deg} deg, h {h}: {force:?} vs {first:?}");
            }
            // Slow enough to stop by friction within the run (deceleration of order mu g).
            let slow = PainleveParams { speed: -0.1, max_time: 1.0, ..sliding };
            let mut rod = Painleve::<f64, 3>::new(slow).unwrap();
            let mut stopped = false;
            let outcome = rod.run(|r| stopped |= r.contacts[0].mode == ContactMode::Sticking);
            assert!(stopped, "{deg} deg: the slow end stops sliding within the run");
            assert_eq!(rod.jam(), None, "{deg} deg: a stop by deceleration is no jam");
            assert_ne!(outcome, Outcome::Jammed, "{deg} deg");
        }
    }
}
