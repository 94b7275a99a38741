//! The three-fingers, cylinder and painleve scenes of docs/scenes.md: parameters with their
//! defaults and validity rules, start states, support motions, outcome rules and measurements.
//!
//! * **three-fingers**: a rod on three finger tips under its lower face; finger 1 moves toward
//!   finger 2 and stops `w` short of it. Its normal forces are statically indeterminate, so its
//!   steps may have solutions that move the rod differently: the reference takes the least
//!   kinetic energy (`step.rs`) and counts such steps as ambiguous.
//! * **cylinder**: a round rim (`geometry.rs`, `Support::Round`) on an incline. Analytic law: it
//!   rolls iff `tan(alpha) <= mu_s (1 + k) / k`, at `a = g sin(alpha) / (1 + k)`,
//!   `omega_dot = a / r`; else it slides at `a = g (sin(alpha) - mu_k cos(alpha))`,
//!   `omega_dot = mu_k g cos(alpha) / (k r)`.
//! * **painleve**: a rod's end (a body point on the floor line) sliding away from under the rod.
//!   Above `mu = (1 + 3 c^2) / (3 s c)` the end jams with the impulse
//!   `(m V / 4) (1 + 3 c^2, 3 s c)` (friction, normal) as `h -> 0`; below it, it slides. A jam is
//!   a slide-to-stick under an impact, `p_n + |p_f| > 2 (|P_prev| + m g h)`; a slide that friction
//!   slows to a stop is none.

use std::f64::consts::FRAC_PI_2;

use super::geometry::{Body, Support};
use super::scenes::{finite, kinetic_at_most_static, non_negative, positive};
use super::simulate::{Scene, StepEnd};
use super::step::Model;
use super::{Jam, Mode, Outcome, Run};

/// A rod on three fingers (docs/scenes.md, "three-fingers"): contacts 1 to 3 the tips under its
/// lower face, finger 1 moving toward finger 2, fingers 2 and 3 still. Heights 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThreeFingers {
    /// Rod length `L`, m.
    pub rod_length: f64,
    /// Rod thickness `t`, m.
    pub rod_thickness: f64,
    /// Rod mass `m`, kg (inertia `m L^2 / 12`).
    pub rod_mass: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// Finger 1's start `x1`, m.
    pub finger1_x: f64,
    /// Finger 2's `x2`, m.
    pub finger2_x: f64,
    /// Finger 3's `x3`, m.
    pub finger3_x: f64,
    /// Finger 1's velocity `v1` (along world `x`), m/s.
    pub finger1_velocity: f64,
    /// Finger 1 stops at `x2 - w`, m.
    pub finger_width: f64,
    /// `mu_s` (every finger).
    pub mu_static: f64,
    /// `mu_k` (every finger).
    pub mu_kinetic: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Largest `|theta|` before the rod counts as fallen, rad.
    pub tilt_limit: f64,
    /// Time after finger 1 stopped before the rod counts as held, s.
    pub hold_time: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for ThreeFingers {
    fn default() -> Self {
        Self {
            rod_length: 1.0,
            rod_thickness: 0.005,
            rod_mass: 0.2,
            gravity: 9.81,
            finger1_x: -0.4,
            finger2_x: 0.0,
            finger3_x: 0.4,
            finger1_velocity: 0.1,
            finger_width: 0.01,
            mu_static: 0.6,
            mu_kinetic: 0.4,
            step: 0.001,
            stick_speed: 1e-5,
            tilt_limit: 0.35,
            hold_time: 0.5,
            max_time: 30.0,
        }
    }
}

/// A round body on an incline (docs/scenes.md, "cylinder"): contact 1 its rim on the plane.
/// Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// Radius `r`, m.
    pub radius: f64,
    /// Mass `m`, kg.
    pub mass: f64,
    /// `k` in `J = k m r^2` (1/2 a solid cylinder, 1 a thin ring).
    pub inertia_factor: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// The slope `alpha` (rising to the right), rad.
    pub angle: f64,
    /// `mu_s`.
    pub mu_static: f64,
    /// `mu_k`.
    pub mu_kinetic: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for Cylinder {
    fn default() -> Self {
        Self {
            radius: 0.1,
            mass: 1.0,
            inertia_factor: 0.5,
            gravity: 9.81,
            angle: 30_f64.to_radians(),
            mu_static: 0.6,
            mu_kinetic: 0.4,
            step: 0.001,
            stick_speed: 1e-5,
            max_time: 1.0,
        }
    }
}

/// Painlevé's rod (docs/scenes.md, "painleve"): contact 1 its lower end, body point `(-L/2, 0)`,
/// on the floor `y = 0`, the rod moving toward `-x`. Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Painleve {
    /// Length `L`, m.
    pub length: f64,
    /// Thickness `t` (for drawing only), m.
    pub thickness: f64,
    /// Mass `m`, kg (inertia `m L^2 / 12`).
    pub mass: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// Start angle `theta0` from the floor, rad.
    pub angle: f64,
    /// The rod's start velocity along `x`, m/s: `-V` (negative: the end slides away from under
    /// the rod).
    pub speed: f64,
    /// The floor's static `mu_s`.
    pub mu_static: f64,
    /// The floor's kinetic `mu_k` (at most `mu_s`).
    pub mu_kinetic: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for Painleve {
    fn default() -> Self {
        Self {
            length: 1.0,
            thickness: 0.02,
            mass: 1.0,
            gravity: 9.81,
            angle: 30_f64.to_radians(),
            speed: -1.0,
            mu_static: 3.0,
            mu_kinetic: 3.0,
            step: 0.001,
            stick_speed: 1e-5,
            max_time: 0.5,
        }
    }
}

impl ThreeFingers {
    /// Checks the validity rules of docs/scenes.md ("three-fingers", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("rod_length", self.rod_length),
            ("rod_thickness", self.rod_thickness),
            ("rod_mass", self.rod_mass),
            ("gravity", self.gravity),
            ("finger1_x", self.finger1_x),
            ("finger2_x", self.finger2_x),
            ("finger3_x", self.finger3_x),
            ("finger1_velocity", self.finger1_velocity),
            ("finger_width", self.finger_width),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("tilt_limit", self.tilt_limit),
            ("hold_time", self.hold_time),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("rod_length", self.rod_length),
            ("rod_thickness", self.rod_thickness),
            ("rod_mass", self.rod_mass),
            ("step", self.step),
            ("tilt_limit", self.tilt_limit),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("gravity", self.gravity),
            ("finger_width", self.finger_width),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("stick_speed", self.stick_speed),
            ("hold_time", self.hold_time),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        for (name, x) in
            [("finger1_x", self.finger1_x), ("finger2_x", self.finger2_x), ("finger3_x", self.finger3_x)]
        {
            if x.abs() > self.rod_length / 2.0 {
                return Err(format!("{name} ({x}) must be within rod_length / 2 of the centre"));
            }
        }
        if self.finger2_x - self.finger1_x <= self.finger_width {
            return Err(format!(
                "finger2_x ({}) must exceed finger1_x ({}) by more than finger_width ({})",
                self.finger2_x, self.finger1_x, self.finger_width
            ));
        }
        if self.finger3_x <= self.finger2_x {
            return Err(format!("finger3_x ({}) must exceed finger2_x ({})", self.finger3_x, self.finger2_x));
        }
        Ok(())
    }
}

impl Cylinder {
    /// Checks the validity rules of docs/scenes.md ("cylinder", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("radius", self.radius),
            ("mass", self.mass),
            ("inertia_factor", self.inertia_factor),
            ("gravity", self.gravity),
            ("angle", self.angle),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("radius", self.radius),
            ("mass", self.mass),
            ("inertia_factor", self.inertia_factor),
            ("step", self.step),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("gravity", self.gravity),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("stick_speed", self.stick_speed),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        if !(self.angle >= 0.0 && self.angle < FRAC_PI_2) {
            return Err(format!("angle ({}) must be in [0, pi/2)", self.angle));
        }
        Ok(())
    }
}

impl Painleve {
    /// Checks the validity rules of docs/scenes.md ("painleve", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("length", self.length),
            ("thickness", self.thickness),
            ("mass", self.mass),
            ("gravity", self.gravity),
            ("angle", self.angle),
            ("speed", self.speed),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("length", self.length),
            ("thickness", self.thickness),
            ("mass", self.mass),
            ("step", self.step),
            ("max_time", self.max_time),
        ])?;
        non_negative(&[
            ("gravity", self.gravity),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("stick_speed", self.stick_speed),
        ])?;
        kinetic_at_most_static(self.mu_static, self.mu_kinetic)?;
        if !(self.angle > 0.0 && self.angle < FRAC_PI_2) {
            return Err(format!("angle ({}) must be in (0, pi/2)", self.angle));
        }
        Ok(())
    }
}

/// The three-fingers scene while it runs.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ThreeFingersScene {
    p: ThreeFingers,
    /// The end of the first step over which finger 1's velocity was 0.
    stopped_at: Option<f64>,
}

impl ThreeFingersScene {
    pub(super) fn new(p: ThreeFingers) -> Self {
        Self { p, stopped_at: None }
    }

    /// Finger 1's stop, `x2 - w`.
    fn stop(&self) -> f64 {
        self.p.finger2_x - self.p.finger_width
    }

    /// Finger 1's `x` at `t = steps h`: `x1 + v1 t` while below the stop, then the stop.
    fn finger1_at(&self, steps: u64) -> f64 {
        let x = self.p.finger1_x + self.p.finger1_velocity * (steps as f64 * self.p.step);
        if x < self.stop() { x } else { self.stop() }
    }

    /// Finger 1's velocity over the step from `steps h`: `v1` when it ends below the stop, else 0.
    fn finger1_velocity_over(&self, steps: u64) -> f64 {
        let end = self.p.finger1_x + self.p.finger1_velocity * ((steps + 1) as f64 * self.p.step);
        if end < self.stop() { self.p.finger1_velocity } else { 0.0 }
    }
}

impl Scene for ThreeFingersScene {
    fn model(&self) -> Model {
        let p = &self.p;
        Model {
            body: Body {
                half_width: p.rod_length / 2.0,
                half_height: p.rod_thickness / 2.0,
                mass: p.rod_mass,
                inertia: p.rod_mass * p.rod_length * p.rod_length / 12.0,
            },
            gravity: p.gravity,
            step: p.step,
            speed: p.finger1_velocity.abs(),
            stick_speed: p.stick_speed,
            size: p.rod_length.max(p.rod_thickness),
        }
    }

    fn start(&self) -> [f64; 3] {
        [0.0, self.p.rod_thickness / 2.0, 0.0]
    }

    fn friction(&self) -> Vec<(f64, f64)> {
        vec![(self.p.mu_static, self.p.mu_kinetic); 3]
    }

    fn supports(&self, steps: u64) -> Vec<Support> {
        [self.finger1_at(steps), self.p.finger2_x, self.p.finger3_x]
            .into_iter()
            .map(|x| Support::Point { tip: [x, 0.0] })
            .collect()
    }

    fn initial_support_velocity(&self) -> Vec<[f64; 2]> {
        // Finger 1 starts below its stop (validity), so at t = 0 it moves at v1.
        vec![[self.p.finger1_velocity, 0.0], [0.0; 2], [0.0; 2]]
    }

    fn support_velocity(&self, steps: u64) -> Vec<[f64; 2]> {
        vec![[self.finger1_velocity_over(steps), 0.0], [0.0; 2], [0.0; 2]]
    }

    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome> {
        let p = &self.p;
        if self.stopped_at.is_none() && self.finger1_velocity_over(end.steps - 1) == 0.0 {
            self.stopped_at = Some(end.t);
        }
        if end.q[2].abs() > p.tilt_limit || !end.end.iter().any(|f| f.active) {
            Some(Outcome::Fell)
        } else if self.stopped_at.is_some_and(|t_stop| end.t - t_stop >= p.hold_time) {
            Some(Outcome::Held)
        } else if end.t >= p.max_time {
            Some(Outcome::Unfinished)
        } else {
            None
        }
    }

    fn measure(&self, _run: &mut Run) {}
}

/// The cylinder scene while it runs.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CylinderScene {
    p: Cylinder,
    /// `(t, u, omega)` at the end of the first step.
    first: Option<[f64; 3]>,
    /// `(t, u, omega)` at the last step's end.
    last: [f64; 3],
    /// Whether the contact was sliding after any step.
    slid: bool,
}

impl CylinderScene {
    pub(super) fn new(p: Cylinder) -> Self {
        Self { p, first: None, last: [0.0; 3], slid: false }
    }
}

impl Scene for CylinderScene {
    fn model(&self) -> Model {
        let p = &self.p;
        Model {
            body: Body {
                half_width: p.radius,
                half_height: p.radius,
                mass: p.mass,
                inertia: p.inertia_factor * p.mass * p.radius * p.radius,
            },
            gravity: p.gravity,
            step: p.step,
            speed: 0.0,
            stick_speed: p.stick_speed,
            size: 2.0 * p.radius,
        }
    }

    fn start(&self) -> [f64; 3] {
        // The centre at r n, n = (-sin(alpha), cos(alpha)).
        let (s, c) = self.p.angle.sin_cos();
        [-s * self.p.radius, c * self.p.radius, 0.0]
    }

    fn friction(&self) -> Vec<(f64, f64)> {
        vec![(self.p.mu_static, self.p.mu_kinetic)]
    }

    fn supports(&self, _steps: u64) -> Vec<Support> {
        let (s, c) = self.p.angle.sin_cos();
        vec![Support::Round { radius: self.p.radius, origin: [0.0, 0.0], normal: [-s, c] }]
    }

    fn initial_support_velocity(&self) -> Vec<[f64; 2]> {
        vec![[0.0; 2]]
    }

    fn support_velocity(&self, _steps: u64) -> Vec<[f64; 2]> {
        vec![[0.0; 2]]
    }

    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome> {
        let (s, c) = self.p.angle.sin_cos();
        // u, the velocity down the slope: -(v . d), d = (cos(alpha), sin(alpha)).
        self.last = [end.t, -(end.v[0] * c + end.v[1] * s), end.v[2]];
        if self.first.is_none() {
            self.first = Some(self.last);
        }
        self.slid |= end.after[0].is_sliding();
        (end.t >= self.p.max_time).then_some(if self.slid { Outcome::Slid } else { Outcome::Rolled })
    }

    fn measure(&self, run: &mut Run) {
        let Some([t1, u1, w1]) = self.first else { return };
        let [t, u, w] = self.last;
        if matches!(run.outcome, Outcome::Rolled | Outcome::Slid) && t > t1 {
            run.acceleration = Some((u - u1) / (t - t1));
            run.angular_acceleration = Some((w - w1) / (t - t1));
        }
    }
}

/// The painleve scene while it runs.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PainleveScene {
    p: Painleve,
    jam: Option<Jam>,
    /// The previous step's contact impulse `|P| = p_n + |p_f|`, N s (0 before the first).
    previous: f64,
}

impl PainleveScene {
    pub(super) fn new(p: Painleve) -> Self {
        Self { p, jam: None, previous: 0.0 }
    }
}

impl Scene for PainleveScene {
    fn model(&self) -> Model {
        let p = &self.p;
        Model {
            body: Body {
                half_width: p.length / 2.0,
                half_height: p.thickness / 2.0,
                mass: p.mass,
                inertia: p.mass * p.length * p.length / 12.0,
            },
            gravity: p.gravity,
            step: p.step,
            speed: p.speed.abs(),
            stick_speed: p.stick_speed,
            size: p.length.max(p.thickness),
        }
    }

    fn start(&self) -> [f64; 3] {
        let (s, c) = self.p.angle.sin_cos();
        [self.p.length / 2.0 * c, self.p.length / 2.0 * s, self.p.angle]
    }

    fn start_velocity(&self) -> [f64; 3] {
        [self.p.speed, 0.0, 0.0]
    }

    fn friction(&self) -> Vec<(f64, f64)> {
        vec![(self.p.mu_static, self.p.mu_kinetic)]
    }

    fn supports(&self, _steps: u64) -> Vec<Support> {
        vec![Support::Line {
            body_point: [-self.p.length / 2.0, 0.0],
            origin: [0.0, 0.0],
            normal: [0.0, 1.0],
        }]
    }

    fn initial_support_velocity(&self) -> Vec<[f64; 2]> {
        vec![[0.0; 2]]
    }

    fn support_velocity(&self, _steps: u64) -> Vec<[f64; 2]> {
        vec![[0.0; 2]]
    }

    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome> {
        // An impact: more than twice what finite forces give over a step, the previous step's
        // impulse and the weight's (a slide that friction slows to a stop is no jam).
        let impulse = end.normal[0] + end.friction[0].abs();
        let impact = impulse > 2.0 * (self.previous + self.p.mass * self.p.gravity * self.p.step);
        self.previous = impulse;
        if end.before[0].is_sliding() && end.after[0] == Mode::Sticking && impact {
            self.jam =
                Some(Jam { t: end.t, normal_impulse: end.normal[0], friction_impulse: end.friction[0] });
            Some(Outcome::Jammed)
        } else if end.q[2] <= 0.0 || end.q[1] <= 0.0 {
            Some(Outcome::Fell)
        } else if end.t >= self.p.max_time {
            Some(if end.after[0].is_sliding() { Outcome::Slid } else { Outcome::Unfinished })
        } else {
            None
        }
    }

    fn measure(&self, run: &mut Run) {
        run.jam = self.jam;
    }
}
