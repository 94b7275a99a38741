//! The meter-stick, incline and ladder scenes of docs/scenes.md (`other_scenes.rs` the others): parameters with their defaults and validity rules, start
//! states, support motions, outcome rules and measurements.

use std::f64::consts::FRAC_PI_2;

use super::geometry::{Body, Support, frame, rotate};
use super::simulate::{Scene, StepEnd};
use super::step::Model;
use super::{Mode, Outcome, Run};

/// The meter stick (docs/scenes.md, "meter-stick"): a rod on two fingers, contacts 1 and 2 the
/// fingers' tips under its lower face. Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeterStick {
    /// Rod length `L`, m.
    pub rod_length: f64,
    /// Rod thickness `t`, m.
    pub rod_thickness: f64,
    /// Rod mass `m`, kg (the inertia is the thin rod's `m L^2 / 12`).
    pub rod_mass: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// Finger 1's start `x1`, m.
    pub finger1_x: f64,
    /// Finger 2's start `x2`, m.
    pub finger2_x: f64,
    /// Finger 1's height `y1`, m.
    pub finger1_y: f64,
    /// Finger 2's height `y2`, m.
    pub finger2_y: f64,
    /// Finger 1's velocity `v1` (along world `x`), m/s.
    pub finger1_velocity: f64,
    /// Finger 2's velocity `v2`, m/s.
    pub finger2_velocity: f64,
    /// Finger width `w`: approaching fingers stop at this horizontal distance, m.
    pub finger_width: f64,
    /// `mu_s` (both fingers).
    pub mu_static: f64,
    /// `mu_k` (both fingers).
    pub mu_kinetic: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Largest `|theta - theta0|` before the rod counts as fallen, rad.
    pub tilt_limit: f64,
    /// Largest drop of the centre of mass below its start before the rod counts as fallen, m.
    pub drop_limit: f64,
    /// Time after the meeting before the rod can be judged balanced, s.
    pub hold_time: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for MeterStick {
    /// The paper's scene.
    fn default() -> Self {
        Self {
            rod_length: 1.0,
            rod_thickness: 0.005,
            rod_mass: 0.2,
            gravity: 9.81,
            finger1_x: -0.4,
            finger2_x: 0.4,
            finger1_y: 0.0,
            finger2_y: 0.0,
            finger1_velocity: 0.1,
            finger2_velocity: 0.0,
            finger_width: 0.01,
            mu_static: 0.6,
            mu_kinetic: 0.4,
            step: 0.001,
            stick_speed: 1e-5,
            tilt_limit: 0.35,
            drop_limit: 0.02,
            hold_time: 0.5,
            max_time: 30.0,
        }
    }
}

/// A block on an incline (docs/scenes.md, "incline"): contacts 1 and 2 its lower corners on the
/// plane. Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Incline {
    /// Block width `w` (along the slope at rest), m.
    pub width: f64,
    /// Block height `hgt`, m.
    pub height: f64,
    /// Mass `m`, kg (inertia `m (w^2 + hgt^2) / 12`).
    pub mass: f64,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// The slope `alpha` (rising to the right), rad.
    pub angle: f64,
    /// `mu_s` (both corners).
    pub mu_static: f64,
    /// `mu_k` (both corners).
    pub mu_kinetic: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for Incline {
    fn default() -> Self {
        Self {
            width: 0.1,
            height: 0.05,
            mass: 1.0,
            gravity: 9.81,
            angle: 35_f64.to_radians(),
            mu_static: 0.6,
            mu_kinetic: 0.4,
            step: 0.001,
            stick_speed: 1e-5,
            max_time: 1.0,
        }
    }
}

/// A ladder (docs/scenes.md, "ladder"): a thin rod, contact 1 its lower end on the floor `y = 0`,
/// contact 2 its upper end against the wall `x = 0`. Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ladder {
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
    /// Floor friction `mu_f` (static and kinetic).
    pub mu_floor: f64,
    /// Wall friction `mu_w` (static and kinetic).
    pub mu_wall: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// Time limit, s.
    pub max_time: f64,
}

impl Default for Ladder {
    fn default() -> Self {
        Self {
            length: 1.0,
            thickness: 0.02,
            mass: 1.0,
            gravity: 9.81,
            angle: 45_f64.to_radians(),
            mu_floor: 0.4,
            mu_wall: 0.3,
            step: 0.001,
            stick_speed: 1e-5,
            max_time: 3.0,
        }
    }
}

/// `Err` unless every value is finite.
pub(super) fn finite(values: &[(&str, f64)]) -> Result<(), String> {
    match values.iter().find(|(_, x)| !x.is_finite()) {
        Some((name, x)) => Err(format!("{name} must be finite (got {x})")),
        None => Ok(()),
    }
}

/// `Err` unless every value is `> 0`.
pub(super) fn positive(values: &[(&str, f64)]) -> Result<(), String> {
    match values.iter().find(|(_, x)| x.is_nan() || *x <= 0.0) {
        Some((name, x)) => Err(format!("{name} must be > 0 (got {x})")),
        None => Ok(()),
    }
}

/// `Err` unless every value is `>= 0`.
pub(super) fn non_negative(values: &[(&str, f64)]) -> Result<(), String> {
    match values.iter().find(|(_, x)| x.is_nan() || *x < 0.0) {
        Some((name, x)) => Err(format!("{name} must be >= 0 (got {x})")),
        None => Ok(()),
    }
}

/// `Err` unless `mu_k <= mu_s`.
pub(super) fn kinetic_at_most_static(mu_static: f64, mu_kinetic: f64) -> Result<(), String> {
    if mu_kinetic <= mu_static {
        Ok(())
    } else {
        Err(format!("mu_kinetic ({mu_kinetic}) must be <= mu_static ({mu_static})"))
    }
}

impl MeterStick {
    /// Checks the validity rules of docs/scenes.md ("meter-stick", "Validity").
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
            ("finger1_y", self.finger1_y),
            ("finger2_y", self.finger2_y),
            ("finger1_velocity", self.finger1_velocity),
            ("finger2_velocity", self.finger2_velocity),
            ("finger_width", self.finger_width),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("tilt_limit", self.tilt_limit),
            ("drop_limit", self.drop_limit),
            ("hold_time", self.hold_time),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("rod_length", self.rod_length),
            ("rod_thickness", self.rod_thickness),
            ("rod_mass", self.rod_mass),
            ("step", self.step),
            ("tilt_limit", self.tilt_limit),
            ("drop_limit", self.drop_limit),
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
        if self.finger2_x - self.finger1_x <= self.finger_width {
            return Err(format!(
                "finger2_x ({}) must exceed finger1_x ({}) by more than finger_width ({})",
                self.finger2_x, self.finger1_x, self.finger_width
            ));
        }
        let scene = MeterStickScene::new(*self);
        let q = scene.start();
        for (name, support) in ["finger1_x", "finger2_x"].into_iter().zip(scene.supports(0)) {
            let along = frame(&scene.body(), q, &support).along;
            if along.is_nan() || along.abs() > self.rod_length / 2.0 {
                return Err(format!(
                    "{name}: the finger's coordinate along the rod at the start, {along}, must be within \
                     rod_length / 2"
                ));
            }
        }
        Ok(())
    }
}

impl Incline {
    /// Checks the validity rules of docs/scenes.md ("incline", "Validity").
    ///
    /// # Errors
    /// The first rule broken, naming its parameter.
    pub fn validate(&self) -> Result<(), String> {
        finite(&[
            ("width", self.width),
            ("height", self.height),
            ("mass", self.mass),
            ("gravity", self.gravity),
            ("angle", self.angle),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("max_time", self.max_time),
        ])?;
        positive(&[
            ("width", self.width),
            ("height", self.height),
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
        if !(0.0..FRAC_PI_2).contains(&self.angle) {
            return Err(format!("angle ({}) must be in [0, pi/2)", self.angle));
        }
        Ok(())
    }
}

impl Ladder {
    /// Checks the validity rules of docs/scenes.md ("ladder", "Validity").
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
            ("mu_floor", self.mu_floor),
            ("mu_wall", self.mu_wall),
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
            ("mu_floor", self.mu_floor),
            ("mu_wall", self.mu_wall),
            ("stick_speed", self.stick_speed),
        ])?;
        if !(self.angle > 0.0 && self.angle < FRAC_PI_2) {
            return Err(format!("angle ({}) must be in (0, pi/2)", self.angle));
        }
        Ok(())
    }
}

/// The meter stick's finger motion: docs/scenes.md, "Finger motion".
#[derive(Debug, Clone, Copy, PartialEq)]
struct Fingers {
    /// `(x1, x2)` at `t = 0`.
    start: [f64; 2],
    /// `(v1, v2)`.
    velocity: [f64; 2],
    /// `(y1, y2)`.
    height: [f64; 2],
    /// The stop positions `(s1, s2)` of approaching fingers (`v1 > v2`), none otherwise.
    stop: Option<[f64; 2]>,
    /// `h`.
    step: f64,
}

/// Where approaching fingers (`v1 > v2`) stop, `(s1, s2)`, their `x` `w` apart (docs/scenes.md,
/// "meter-stick", "Finger motion"), from their start `x` and `x` speeds; none otherwise.
pub(crate) fn finger_stops([x1, x2]: [f64; 2], [v1, v2]: [f64; 2], w: f64) -> Option<[f64; 2]> {
    (v1 > v2).then(|| {
        if v2 == 0.0 {
            [x2 - w, x2]
        } else if v1 == 0.0 {
            [x1, x1 + w]
        } else {
            let s1 = x1 + v1 * ((x2 - x1 - w) / (v1 - v2));
            [s1, s1 + w]
        }
    })
}

impl Fingers {
    fn new(p: &MeterStick) -> Self {
        let [x1, x2] = [p.finger1_x, p.finger2_x];
        let [v1, v2] = [p.finger1_velocity, p.finger2_velocity];
        let stop = finger_stops([x1, x2], [v1, v2], p.finger_width);
        Self { start: [x1, x2], velocity: [v1, v2], height: [p.finger1_y, p.finger2_y], stop, step: p.step }
    }

    /// `x_i + v_i t` at `t = steps h`.
    fn free(&self, steps: u64) -> [f64; 2] {
        let t = steps as f64 * self.step;
        [self.start[0] + self.velocity[0] * t, self.start[1] + self.velocity[1] * t]
    }

    /// Whether the fingers are stopped at `t = steps h`: finger 1 moves and has reached `s1` in
    /// its direction of motion, or finger 1 is still and finger 2 has reached `s2`. (The test is
    /// monotone in `t`, so "from that step on" needs no memory.)
    fn stopped(&self, steps: u64) -> bool {
        let Some([s1, s2]) = self.stop else { return false };
        let [x1, x2] = self.free(steps);
        let v1 = self.velocity[0];
        if v1 > 0.0 {
            x1 >= s1
        } else if v1 < 0.0 {
            x1 <= s1
        } else {
            x2 <= s2
        }
    }

    /// The tips' `x` at `t = steps h`.
    fn positions(&self, steps: u64) -> [f64; 2] {
        match self.stop {
            Some(stop) if self.stopped(steps) => stop,
            _ => self.free(steps),
        }
    }

    /// The tips' velocities over the step from `steps h`: `v_i`, or on and after the stop
    /// (end position - start position) / h.
    fn velocity_over(&self, steps: u64) -> [f64; 2] {
        if self.stopped(steps + 1) {
            let [a1, a2] = self.positions(steps);
            let [b1, b2] = self.positions(steps + 1);
            [(b1 - a1) / self.step, (b2 - a2) / self.step]
        } else {
            self.velocity
        }
    }
}

/// The meter-stick scene while it runs.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct MeterStickScene {
    p: MeterStick,
    fingers: Fingers,
    /// `theta0`.
    theta0: f64,
    /// The centre of mass's start `(x, y)`.
    com0: [f64; 2],
    /// `(time, com_offset)` of the first step that ended stopped.
    meeting: Option<(f64, f64)>,
}

impl MeterStickScene {
    /// The start: the rod at rest on both tips, its centre of mass above `x = 0`.
    pub(super) fn new(p: MeterStick) -> Self {
        let [x1, x2] = [p.finger1_x, p.finger2_x];
        let [y1, y2] = [p.finger1_y, p.finger2_y];
        let slope = (y2 - y1) / (x2 - x1);
        let theta0 = slope.atan();
        let foot_x = theta0.sin() * p.rod_thickness / 2.0;
        let foot_y = y1 + slope * (foot_x - x1);
        let up = rotate(theta0, [0.0, p.rod_thickness / 2.0]);
        Self { p, fingers: Fingers::new(&p), theta0, com0: [foot_x + up[0], foot_y + up[1]], meeting: None }
    }

    fn body(&self) -> Body {
        Body {
            half_width: self.p.rod_length / 2.0,
            half_height: self.p.rod_thickness / 2.0,
            mass: self.p.rod_mass,
            inertia: self.p.rod_mass * self.p.rod_length * self.p.rod_length / 12.0,
        }
    }
}

impl Scene for MeterStickScene {
    fn model(&self) -> Model {
        Model {
            body: self.body(),
            gravity: self.p.gravity,
            step: self.p.step,
            speed: self.p.finger1_velocity.abs().max(self.p.finger2_velocity.abs()),
            stick_speed: self.p.stick_speed,
            size: self.p.rod_length,
        }
    }

    fn start(&self) -> [f64; 3] {
        [self.com0[0], self.com0[1], self.theta0]
    }

    fn friction(&self) -> Vec<(f64, f64)> {
        vec![(self.p.mu_static, self.p.mu_kinetic); 2]
    }

    fn supports(&self, steps: u64) -> Vec<Support> {
        let x = self.fingers.positions(steps);
        (0..2).map(|i| Support::Point { tip: [x[i], self.fingers.height[i]] }).collect()
    }

    fn initial_support_velocity(&self) -> Vec<[f64; 2]> {
        self.fingers.velocity.iter().map(|&v| [v, 0.0]).collect()
    }

    fn support_velocity(&self, steps: u64) -> Vec<[f64; 2]> {
        self.fingers.velocity_over(steps).iter().map(|&v| [v, 0.0]).collect()
    }

    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome> {
        let p = &self.p;
        let [along1, along2] = [end.end[0].along, end.end[1].along];
        if self.meeting.is_none() && self.fingers.stopped(end.steps) {
            self.meeting = Some((end.t, -(along1 + along2) / 2.0));
        }
        if (end.q[2] - self.theta0).abs() > p.tilt_limit
            || end.q[1] < self.com0[1] - p.drop_limit
            || !end.end.iter().any(|f| f.active)
        {
            Some(Outcome::Fell)
        } else if self.meeting.is_some_and(|(t_meet, _)| end.t - t_meet >= p.hold_time)
            && end.after.iter().all(|&m| m != Mode::Separated)
            && along1 <= 0.0
            && 0.0 <= along2
        {
            Some(Outcome::Balanced)
        } else if end.t >= p.max_time {
            Some(Outcome::Unfinished)
        } else {
            None
        }
    }

    fn measure(&self, run: &mut Run) {
        run.meeting = self.meeting;
    }
}

/// The incline scene while it runs.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct InclineScene {
    p: Incline,
    /// `(t_1, u(t_1))` at the end of the first step after which a contact was sliding.
    first_slide: Option<(f64, f64)>,
    /// `(t, u(t))` at the last step's end.
    last: (f64, f64),
}

impl InclineScene {
    pub(super) fn new(p: Incline) -> Self {
        Self { p, first_slide: None, last: (0.0, 0.0) }
    }

    /// The velocity down the slope, `u = -(vx cos alpha + vy sin alpha)`.
    fn down_slope(&self, v: [f64; 3]) -> f64 {
        let (s, c) = self.p.angle.sin_cos();
        -(v[0] * c + v[1] * s)
    }
}

impl Scene for InclineScene {
    fn model(&self) -> Model {
        let p = &self.p;
        Model {
            body: Body {
                half_width: p.width / 2.0,
                half_height: p.height / 2.0,
                mass: p.mass,
                inertia: p.mass * (p.width * p.width + p.height * p.height) / 12.0,
            },
            gravity: p.gravity,
            step: p.step,
            speed: 0.0,
            stick_speed: p.stick_speed,
            size: p.width.max(p.height),
        }
    }

    fn start(&self) -> [f64; 3] {
        let (s, c) = self.p.angle.sin_cos();
        [-s * self.p.height / 2.0, c * self.p.height / 2.0, self.p.angle]
    }

    fn friction(&self) -> Vec<(f64, f64)> {
        vec![(self.p.mu_static, self.p.mu_kinetic); 2]
    }

    fn supports(&self, _steps: u64) -> Vec<Support> {
        let (s, c) = self.p.angle.sin_cos();
        let [a, b] = [self.p.width / 2.0, self.p.height / 2.0];
        [[-a, -b], [a, -b]]
            .into_iter()
            .map(|body_point| Support::Line { body_point, origin: [0.0, 0.0], normal: [-s, c] })
            .collect()
    }

    fn initial_support_velocity(&self) -> Vec<[f64; 2]> {
        vec![[0.0; 2]; 2]
    }

    fn support_velocity(&self, _steps: u64) -> Vec<[f64; 2]> {
        vec![[0.0; 2]; 2]
    }

    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome> {
        let p = &self.p;
        self.last = (end.t, self.down_slope(end.v));
        if self.first_slide.is_none() && end.after.iter().any(|m| m.is_sliding()) {
            self.first_slide = Some(self.last);
        }
        if (end.q[2] - p.angle).abs() > (p.width / p.height).atan() {
            Some(Outcome::Tipped)
        } else if end.t >= p.max_time {
            Some(if self.first_slide.is_some() { Outcome::Slid } else { Outcome::Held })
        } else {
            None
        }
    }

    fn measure(&self, run: &mut Run) {
        run.acceleration = match (&run.outcome, self.first_slide) {
            (Outcome::Slid, Some((t1, u1))) if self.last.0 > t1 => {
                Some((self.last.1 - u1) / (self.last.0 - t1))
            }
            _ => None,
        };
    }
}

/// The ladder scene while it runs.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct LadderScene {
    p: Ladder,
    /// Whether a contact was sliding after any step.
    slid: bool,
    /// The upper end's height at the end of the first step that separated it from the wall.
    release: Option<f64>,
}

impl LadderScene {
    pub(super) fn new(p: Ladder) -> Self {
        Self { p, slid: false, release: None }
    }
}

impl Scene for LadderScene {
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
            speed: 0.0,
            stick_speed: p.stick_speed,
            size: p.length,
        }
    }

    fn start(&self) -> [f64; 3] {
        let (s, c) = self.p.angle.sin_cos();
        [-self.p.length / 2.0 * c, self.p.length / 2.0 * s, self.p.angle]
    }

    fn friction(&self) -> Vec<(f64, f64)> {
        vec![(self.p.mu_floor, self.p.mu_floor), (self.p.mu_wall, self.p.mu_wall)]
    }

    fn supports(&self, _steps: u64) -> Vec<Support> {
        let half = self.p.length / 2.0;
        vec![
            Support::Line { body_point: [-half, 0.0], origin: [0.0, 0.0], normal: [0.0, 1.0] },
            Support::Line { body_point: [half, 0.0], origin: [0.0, 0.0], normal: [-1.0, 0.0] },
        ]
    }

    fn initial_support_velocity(&self) -> Vec<[f64; 2]> {
        vec![[0.0; 2]; 2]
    }

    fn support_velocity(&self, _steps: u64) -> Vec<[f64; 2]> {
        vec![[0.0; 2]; 2]
    }

    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome> {
        let top = end.q[1] + self.p.length / 2.0 * end.q[2].sin();
        if self.release.is_none() && end.before[1] != Mode::Separated && end.after[1] == Mode::Separated {
            self.release = Some(top);
        }
        self.slid |= end.after.iter().any(|m| m.is_sliding());
        if top <= 0.0 {
            Some(Outcome::Fell)
        } else if end.t >= self.p.max_time {
            Some(if self.slid { Outcome::Unfinished } else { Outcome::Held })
        } else {
            None
        }
    }

    fn measure(&self, run: &mut Run) {
        run.wall_release_height = self.release;
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn fingers(x: [f64; 2], v: [f64; 2]) -> Fingers {
        let p = MeterStick {
            finger1_x: x[0],
            finger2_x: x[1],
            finger1_velocity: v[0],
            finger2_velocity: v[1],
            step: 0.25,
            ..MeterStick::default()
        };
        Fingers::new(&p)
    }

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15
    }

    #[test]
    fn finger_one_moving_stops_a_finger_width_short_of_finger_two() {
        // x1 = -0.4 at 0.1 m/s toward x2 = 0.4 still: s1 = 0.39, reached at t = 7.9, step 32
        // (h = 0.25).
        let f = fingers([-0.4, 0.4], [0.1, 0.0]);
        assert!(close(f.stop.unwrap(), [0.39, 0.4]));
        assert!(!f.stopped(31) && f.stopped(32) && f.stopped(33));
        assert!(close(f.positions(31), [-0.4 + 0.1 * 7.75, 0.4]));
        assert!(close(f.positions(32), [0.39, 0.4]));
        assert!(close(f.velocity_over(30), [0.1, 0.0]));
        // The stopping step: the partial travel 0.39 - 0.375 over h.
        assert!(close(f.velocity_over(31), [0.015 / 0.25, 0.0]));
        assert!(close(f.velocity_over(32), [0.0, 0.0]));
    }

    #[test]
    fn finger_two_moving_stops_a_finger_width_short_of_finger_one() {
        let f = fingers([-0.4, 0.35], [0.0, -0.1]);
        assert!(close(f.stop.unwrap(), [-0.4, -0.39]));
        // x2 + v2 t <= -0.39 from t = 7.4 (step 29.6): step 30.
        assert!(!f.stopped(29) && f.stopped(30));
        assert!(close(f.velocity_over(29), [0.0, (-0.39 - (0.35 - 0.1 * 7.25)) / 0.25]));
    }

    #[test]
    fn both_fingers_moving_stop_where_finger_one_reaches_its_meeting_point() {
        // Closing speed 0.3, gap 0.79: t_s = 2.6333; s1 = -0.4 + 0.1 t_s.
        let f = fingers([-0.4, 0.4], [0.1, -0.2]);
        let t_stop = 0.79 / 0.3;
        let [s1, s2] = f.stop.unwrap();
        assert!((s1 - (-0.4 + 0.1 * t_stop)).abs() < 1e-15 && (s2 - s1 - 0.01).abs() < 1e-15);
        assert!(!f.stopped(10) && f.stopped(11));
        // Receding fingers never stop.
        let apart = fingers([-0.4, 0.4], [-0.1, 0.1]);
        assert!(apart.stop.is_none() && !apart.stopped(1000));
        assert!(close(apart.velocity_over(1000), [-0.1, 0.1]));
    }

    #[test]
    fn a_tilted_rod_starts_on_both_tips() {
        let p = MeterStick { finger2_y: 0.05, finger1_velocity: 0.0, ..MeterStick::default() };
        let scene = MeterStickScene::new(p);
        let q = scene.start();
        assert!(q[0].abs() < 1e-17, "{q:?}");
        for support in scene.supports(0) {
            let f = frame(&scene.body(), q, &support);
            assert!(f.active && f.gap.abs() < 1e-16, "{f:?}");
        }
    }
}
