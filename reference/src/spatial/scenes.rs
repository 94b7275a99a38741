//! The puck and the billiard ball (docs/scenes.md, "Scenes in three dimensions"): parameters,
//! validity, start, outcome rules and measured quantities, and the stepping loop they share.

use super::algebra::{V3, ZERO, dot, length, minus};
use super::step::{Ground, Kinematics, Rigid, Toucher, World};
use super::{Error, MAX_STEPS, Mode, Outcome, Row, Rule, SpatialRun};

/// The puck's measured quantities, in [`SpatialRun::measured`]'s order.
pub const PUCK_QUANTITIES: [&str; 3] = ["final_speed_m_s", "displacement_m", "displacement_heading_deg"];
/// The billiard ball's measured quantities, in [`SpatialRun::measured`]'s order.
pub const BILLIARD_QUANTITIES: [&str; 3] =
    ["rolling_time_s", "rolling_velocity_x_m_s", "rolling_velocity_y_m_s"];

/// docs/scenes.md, "puck": a disc sliding on its face on a plane inclined by `angle` about the
/// world's `x` axis, touching it at its centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Puck {
    /// `r`, m.
    pub radius: f64,
    /// `t`, m.
    pub thickness: f64,
    /// `m`, kg.
    pub mass: f64,
    /// `g`, m/s^2.
    pub g: f64,
    /// `alpha`, rad, in `[0, pi / 2)`.
    pub angle: f64,
    /// `phi`, rad, from `e_x` toward `e_down`.
    pub heading: f64,
    /// Launch speed, m/s.
    pub speed: f64,
    /// `mu_s`.
    pub mu_s: f64,
    /// `mu_k`.
    pub mu_k: f64,
    /// `h`, s.
    pub h: f64,
    /// m/s.
    pub stick_speed: f64,
    /// s.
    pub max_time: f64,
}

impl Default for Puck {
    fn default() -> Self {
        Self {
            radius: 0.0381,
            thickness: 0.0254,
            mass: 0.17,
            g: 9.81,
            angle: 20.0_f64.to_radians(),
            heading: 0.0,
            speed: 0.9,
            mu_s: 0.4,
            mu_k: 0.4,
            h: 0.001,
            stick_speed: 1e-5,
            max_time: 5.0,
        }
    }
}

/// docs/scenes.md, "billiard": a ball on a level table struck along `+x` with a spin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Billiard {
    /// `R`, m.
    pub radius: f64,
    /// `m`, kg.
    pub mass: f64,
    /// `g`, m/s^2.
    pub g: f64,
    /// Launch speed along `+x`, m/s.
    pub speed: f64,
    /// `omega0 = (spin_x, spin_y, spin_z)`, rad/s, world axes.
    pub spin: [f64; 3],
    /// `mu_s`.
    pub mu_s: f64,
    /// `mu_k`.
    pub mu_k: f64,
    /// `h`, s.
    pub h: f64,
    /// m/s.
    pub stick_speed: f64,
    /// s.
    pub max_time: f64,
}

impl Default for Billiard {
    fn default() -> Self {
        Self {
            radius: 0.028_575,
            mass: 0.17,
            g: 9.81,
            speed: 2.0,
            spin: [0.0; 3],
            mu_s: 0.2,
            mu_k: 0.2,
            h: 0.001,
            stick_speed: 1e-5,
            max_time: 5.0,
        }
    }
}

pub(super) fn invalid(field: &'static str, rule: Rule) -> Error {
    Error::Invalid { field, rule }
}

/// The rules both scenes share, after their own finiteness checks.
pub(super) fn common(
    positive: &[(&'static str, f64)],
    non_negative: &[(&'static str, f64)],
    (mu_s, mu_k): (f64, f64),
    (h, max_time): (f64, f64),
) -> Result<(), Error> {
    for &(field, value) in positive.iter().chain(non_negative) {
        if !value.is_finite() {
            return Err(invalid(field, Rule::NotFinite));
        }
    }
    if let Some(&(field, _)) = positive.iter().find(|(_, v)| *v <= 0.0) {
        return Err(invalid(field, Rule::NotPositive));
    }
    if let Some(&(field, _)) = non_negative.iter().find(|(_, v)| *v < 0.0) {
        return Err(invalid(field, Rule::Negative));
    }
    if mu_k > mu_s {
        return Err(invalid("mu_k", Rule::KineticAboveStatic));
    }
    if h > max_time {
        return Err(invalid("h", Rule::StepAboveMaxTime));
    }
    Ok(())
}

impl Puck {
    /// docs/scenes.md, "puck", "Validity".
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that breaks a rule.
    pub fn validate(&self) -> Result<(), Error> {
        for (field, value) in [("angle", self.angle), ("heading", self.heading)] {
            if !value.is_finite() {
                return Err(invalid(field, Rule::NotFinite));
            }
        }
        common(
            &[
                ("radius", self.radius),
                ("thickness", self.thickness),
                ("mass", self.mass),
                ("h", self.h),
                ("max_time", self.max_time),
                ("stick_speed", self.stick_speed),
            ],
            &[("g", self.g), ("speed", self.speed), ("mu_s", self.mu_s), ("mu_k", self.mu_k)],
            (self.mu_s, self.mu_k),
            (self.h, self.max_time),
        )?;
        if !(0.0..std::f64::consts::FRAC_PI_2).contains(&self.angle) {
            return Err(invalid("angle", Rule::OutOfRange));
        }
        Ok(())
    }

    /// The plane's normal `(0, sin alpha, cos alpha)`.
    #[must_use]
    pub fn normal(&self) -> [f64; 3] {
        let (s, c) = self.angle.sin_cos();
        [0.0, s, c]
    }

    /// Down the slope, `(0, cos alpha, -sin alpha)`.
    #[must_use]
    pub fn down(&self) -> [f64; 3] {
        let (s, c) = self.angle.sin_cos();
        [0.0, c, -s]
    }

    /// The start orientation: the puck's axis (body `z`) along the plane's normal, its face on
    /// the plane. That is the rotation by `-alpha` about `x` (by `+alpha` about `x` turns `z` to
    /// `(0, -sin alpha, cos alpha)`, away from the normal).
    #[must_use]
    pub fn start_orientation(&self) -> [f64; 4] {
        let (s, c) = (0.5 * self.angle).sin_cos();
        [c, -s, 0.0, 0.0]
    }

    /// The characteristic speed `V = speed`.
    #[must_use]
    pub fn characteristic_speed(&self) -> f64 {
        self.speed
    }

    fn world(&self) -> World {
        let m = self.mass;
        let across = m * (3.0 * self.radius * self.radius + self.thickness * self.thickness) / 12.0;
        World {
            body: Rigid { mass: m, moments: [across, across, 0.5 * m * self.radius * self.radius] },
            toucher: Toucher::Point { offset: ZERO },
            ground: Ground { point: ZERO, normal: self.normal(), mu_s: self.mu_s, mu_k: self.mu_k },
            gravity: [0.0, 0.0, -self.g],
            h: self.h,
            stick_speed: self.stick_speed,
        }
    }

    fn start(&self) -> Kinematics {
        let (s, c) = self.heading.sin_cos();
        let down = self.down();
        let v = [self.speed * c, self.speed * s * down[1], self.speed * s * down[2]];
        Kinematics { x: ZERO, q: self.start_orientation(), v, omega: ZERO }
    }
}

impl Billiard {
    /// docs/scenes.md, "billiard", "Validity".
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that breaks a rule.
    pub fn validate(&self) -> Result<(), Error> {
        for (field, value) in [("spin_x", self.spin[0]), ("spin_y", self.spin[1]), ("spin_z", self.spin[2])] {
            if !value.is_finite() {
                return Err(invalid(field, Rule::NotFinite));
            }
        }
        common(
            &[
                ("radius", self.radius),
                ("mass", self.mass),
                ("h", self.h),
                ("max_time", self.max_time),
                ("stick_speed", self.stick_speed),
            ],
            &[("g", self.g), ("speed", self.speed), ("mu_s", self.mu_s), ("mu_k", self.mu_k)],
            (self.mu_s, self.mu_k),
            (self.h, self.max_time),
        )
    }

    /// The characteristic speed `V = speed + R |omega0|`.
    #[must_use]
    pub fn characteristic_speed(&self) -> f64 {
        self.speed + self.radius * length(self.spin)
    }

    fn world(&self) -> World {
        let moment = 0.4 * self.mass * self.radius * self.radius;
        World {
            body: Rigid { mass: self.mass, moments: [moment; 3] },
            toucher: Toucher::Sphere { radius: self.radius },
            ground: Ground { point: ZERO, normal: [0.0, 0.0, 1.0], mu_s: self.mu_s, mu_k: self.mu_k },
            gravity: [0.0, 0.0, -self.g],
            h: self.h,
            stick_speed: self.stick_speed,
        }
    }

    fn start(&self) -> Kinematics {
        Kinematics {
            x: [0.0, 0.0, self.radius],
            q: [1.0, 0.0, 0.0, 0.0],
            v: [self.speed, 0.0, 0.0],
            omega: self.spin,
        }
    }
}

/// The rows of a run, its outcome and steps: `stopped` when the contact sticks after a step,
/// `timeout` at `t >= max_time`.
fn simulate(
    world: &World,
    start: Kinematics,
    max_time: f64,
    (stopped, timeout): (Outcome, Outcome),
    keep: Keep,
) -> Result<(Outcome, u64, Vec<Row>), Error> {
    let h = world.h;
    let needed = (max_time / h).ceil();
    if needed > MAX_STEPS as f64 {
        return Err(Error::TooManySteps { steps: needed });
    }
    let row = |t: f64, s: &Kinematics, mode: Mode, normal_impulse: f64, friction_impulse: V3| Row {
        t,
        position: s.x,
        orientation: s.q,
        velocity: s.v,
        angular_velocity: s.omega,
        mode,
        normal_impulse,
        friction_impulse,
    };
    let mut rows = Vec::with_capacity(if keep == Keep::All { needed as usize + 1 } else { 2 });
    rows.push(row(0.0, &start, Mode::Separated, 0.0, ZERO));
    let (mut state, mut mode) = (start, Mode::Separated);
    let mut steps = 0_u64;
    loop {
        let next = world.step(&state, mode).map_err(|error| Error::Contact { step: steps + 1, error })?;
        steps += 1;
        let s = next.state;
        if !(s.x.iter().chain(&s.q).chain(&s.v).chain(&s.omega)).all(|c| c.is_finite()) {
            return Err(Error::NonFinite { step: steps });
        }
        let t = steps as f64 * h;
        let kept = row(t, &s, next.mode, next.normal_impulse, next.friction_impulse);
        match (keep, rows.get_mut(1)) {
            (Keep::StartAndEnd, Some(last)) => *last = kept,
            _ => rows.push(kept),
        }
        state = s;
        mode = next.mode;
        if mode == Mode::Sticking {
            return Ok((stopped, steps, rows));
        }
        if t >= max_time || steps >= MAX_STEPS {
            return Ok((timeout, steps, rows));
        }
    }
}

/// Which rows a run keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// Every step's: `steps + 1` rows.
    All,
    /// The start's and the last step's (two rows; one when no step was taken): a run of any
    /// length in a fixed memory.
    StartAndEnd,
}

/// Validates `p` and runs the puck to its outcome (docs/scenes.md, "puck"), keeping every row.
///
/// # Errors
/// As [`run_puck_keeping`].
pub fn run_puck(p: &Puck) -> Result<SpatialRun, Error> {
    run_puck_keeping(p, Keep::All)
}

/// Validates `b` and runs the ball to its outcome (docs/scenes.md, "billiard"), keeping every row.
///
/// # Errors
/// As [`run_billiard_keeping`].
pub fn run_billiard(b: &Billiard) -> Result<SpatialRun, Error> {
    run_billiard_keeping(b, Keep::All)
}

/// Validates `p` and runs the puck to its outcome (docs/scenes.md, "puck"), keeping `keep`.
///
/// # Errors
/// [`Error::Invalid`], [`Error::TooManySteps`], or a step's failure.
pub fn run_puck_keeping(p: &Puck, keep: Keep) -> Result<SpatialRun, Error> {
    p.validate()?;
    let start = p.start();
    let (outcome, steps, trajectory) =
        simulate(&p.world(), start, p.max_time, (Outcome::Stopped, Outcome::Slid), keep)?;
    let end = trajectory.last().map_or(start.x, |r| r.position);
    let v_end = trajectory.last().map_or(start.v, |r| r.velocity);
    let moved = minus(end, start.x);
    let displacement = length(moved);
    // Moved less than a sticking contact creeps in one step: no heading (docs/scenes.md).
    let heading =
        (displacement > p.stick_speed * p.h).then(|| dot(moved, p.down()).atan2(moved[0]).to_degrees());
    Ok(SpatialRun {
        outcome,
        measured: [Some(length(v_end)), Some(displacement), heading],
        steps,
        trajectory,
    })
}

/// Validates `b` and runs the billiard ball to its outcome (docs/scenes.md, "billiard"), keeping `keep`.
///
/// # Errors
/// [`Error::Invalid`], [`Error::TooManySteps`], or a step's failure.
pub fn run_billiard_keeping(b: &Billiard, keep: Keep) -> Result<SpatialRun, Error> {
    b.validate()?;
    let (outcome, steps, trajectory) =
        simulate(&b.world(), b.start(), b.max_time, (Outcome::Rolled, Outcome::Unfinished), keep)?;
    let measured = match (outcome, trajectory.last()) {
        (Outcome::Rolled, Some(r)) => [Some(r.t), Some(r.velocity[0]), Some(r.velocity[1])],
        _ => [None; 3],
    };
    Ok(SpatialRun { outcome, measured, steps, trajectory })
}

/// A body touching a fixed plane at one point fixed in it (a box's corner, off its centre of
/// mass): the scenes' step opened for checks beyond them, where `W` couples the normal and the
/// slip and the contact's sliding case takes the root search (`contact.rs`). Not validated:
/// the caller passes a body (positive moments), a unit normal and `0 <= mu_k <= mu_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OnePoint {
    /// kg.
    pub mass: f64,
    /// Principal moments about the body's axes, kg m^2.
    pub moments: [f64; 3],
    /// The contact point's offset from the centre of mass, body axes, m.
    pub offset: [f64; 3],
    /// A point of the plane, m.
    pub point: [f64; 3],
    /// The plane's unit normal, toward the body.
    pub normal: [f64; 3],
    /// `mu_s`.
    pub mu_s: f64,
    /// `mu_k`.
    pub mu_k: f64,
    /// Gravity, m/s^2, world axes.
    pub gravity: [f64; 3],
    /// `h`, s.
    pub h: f64,
    /// m/s.
    pub stick_speed: f64,
}

impl OnePoint {
    /// One step from `row` (its state, and its mode as the mode before the step): the row after
    /// it, `t` advanced by `h`.
    ///
    /// # Errors
    /// The contact's solve failing.
    pub fn step(&self, row: &Row) -> Result<Row, super::ContactError> {
        let world = World {
            body: Rigid { mass: self.mass, moments: self.moments },
            toucher: Toucher::Point { offset: self.offset },
            ground: Ground { point: self.point, normal: self.normal, mu_s: self.mu_s, mu_k: self.mu_k },
            gravity: self.gravity,
            h: self.h,
            stick_speed: self.stick_speed,
        };
        let start =
            Kinematics { x: row.position, q: row.orientation, v: row.velocity, omega: row.angular_velocity };
        let next = world.step(&start, row.mode)?;
        let s = next.state;
        Ok(Row {
            t: row.t + self.h,
            position: s.x,
            orientation: s.q,
            velocity: s.v,
            angular_velocity: s.omega,
            mode: next.mode,
            normal_impulse: next.normal_impulse,
            friction_impulse: next.friction_impulse,
        })
    }
}
