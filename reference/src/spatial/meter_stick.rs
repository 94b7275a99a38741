//! The meter stick in three dimensions (docs/scenes.md, "meter-stick-3d"), written from that
//! text: a box `L x w x t` on two fingers lying across it along the world's `y`, finger 1 a pad
//! touching the lower face at its two long edges, finger 2 a point on its centre line; three
//! contacts of one body, solved each step by the several-contact cone (`cone.rs`).
//!
//! The step (docs/formulation.md, "Three dimensions"): each contact's geometry is read at the
//! step's start, the rod's state then and the fingers where they were. A finger is the line
//! through its tip along `y`; it touches the face where it crosses the face's line `y_b = b` of
//! the rod's frame (`b = -w/2, +w/2` for the pad, `0` for finger 2), unless the line runs within
//! `acos(1/16)` of the rod's axis. The crossing `P` in the rod's frame, `l = R^T (P - x)`, is
//! under the face when `|l_x| <= L/2`, `|l_y| <= w/2` (to `16 eps` of the positions) and `l_z <=
//! 0`; its gap is `-l_z - t/2`, its arm `r = R (l_x, l_y, -t/2)`, its normal the face's, `R e_z`.
//! A contact under the face within the margin `1e-3` m enters the step with its free velocity
//! `v~ + omega x r - V_finger` and the gap's bias (`step::bias`, its dead band
//! `4 eps (|x| + |y| + |z| + |r|)`); `W_ij = I3 + m [r_i]x^T I_w^-1 [r_j]x`. After the step a contact is separated
//! when it did not enter or its normal impulse per unit mass is at most `64 eps g h`, sticking
//! when its slip against its finger is at most `stick_speed`, else sliding; `mu` is `mu_k` after
//! a sliding step and `mu_s` otherwise. Before the first step a contact touching (its gap within
//! `64 eps (|x| + |y| + |z| + L/2 + w/2)`) slides when its slip exceeds `stick_speed`, else
//! sticks.

use super::algebra::{
    V3, ZERO, apply, congruent, cross, dot, in_plane, length, matrix_of, plus, times, transpose,
};
use super::cone::{self, Contacts, PointCase};
use super::fingers::{FingerParams, Fingers};
use super::scenes::{Keep, invalid};
use super::step::{MARGIN, bias, turned};
use super::{Error, MAX_STEPS, Mode, Outcome, Row, Rule, SpatialRun};

/// The measured quantities, in [`SpatialRun::measured`]'s order.
pub const METER_STICK_3D_QUANTITIES: [&str; 2] = ["meeting.time_s", "meeting.com_offset_m"];

/// The contact points: the pad's two (`y_b = -w/2`, `+w/2`), finger 2's one.
pub const ROD_POINTS: usize = 3;

/// docs/scenes.md, "meter-stick-3d": the planar scene's parameters (the same names and
/// defaults), the rod's width and the path's heading (radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeterStick3d {
    /// `L`, m.
    pub rod_length: f64,
    /// `t`, m.
    pub rod_thickness: f64,
    /// `w`, m.
    pub rod_width: f64,
    /// `m`, kg.
    pub rod_mass: f64,
    /// `g`, m/s^2, along `-z`.
    pub gravity: f64,
    /// Finger 1's start `x`, m.
    pub finger1_x: f64,
    /// Finger 2's start `x`, m.
    pub finger2_x: f64,
    /// Finger 1's height (`z`), m.
    pub finger1_y: f64,
    /// Finger 2's height (`z`), m.
    pub finger2_y: f64,
    /// Finger 1's speed along the path, m/s (its `x` moves at this times `cos psi`).
    pub finger1_velocity: f64,
    /// Finger 2's, m/s.
    pub finger2_velocity: f64,
    /// `psi`, rad, `|psi| <= 80 deg`.
    pub heading: f64,
    /// Approaching fingers stop when their `x` are this far apart, m.
    pub finger_width: f64,
    /// `mu_s`.
    pub mu_static: f64,
    /// `mu_k`.
    pub mu_kinetic: f64,
    /// `h`, s.
    pub step: f64,
    /// m/s.
    pub stick_speed: f64,
    /// rad.
    pub tilt_limit: f64,
    /// m.
    pub drop_limit: f64,
    /// s.
    pub hold_time: f64,
    /// s.
    pub max_time: f64,
}

impl Default for MeterStick3d {
    fn default() -> Self {
        let planar = crate::MeterStick::default();
        Self::from_planar(&planar, 0.025, 0.0)
    }
}

/// One contact point after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodPoint {
    /// Its mode after the step.
    pub mode: Mode,
    /// Normal impulse, N s.
    pub normal_impulse: f64,
    /// Friction impulse on the rod, N s, world axes.
    pub friction_impulse: [f64; 3],
    /// The contact point (on the face) at the step's start, world axes, m; the finger's tip when
    /// it does not cross the face.
    pub point: [f64; 3],
}

/// A finished run: the rod's rows and its points'.
#[derive(Debug, Clone, PartialEq)]
pub struct MeterStick3dRun {
    /// The rod's rows (each row's mode: sliding when a point slides, else sticking when one
    /// touches; impulses the points' sums), the outcome, the meeting's time and offset.
    pub run: SpatialRun,
    /// Each kept row's points (row 0: the modes before the first step, no impulse).
    pub points: Vec<[RodPoint; ROD_POINTS]>,
    /// Steps whose first guess at the contacts' cases (the step before's) did not verify.
    pub guesses_missed: u64,
    /// Steps whose stuck points' least-norm impulses left a cone and were moved into it along
    /// the internal forces (`cone.rs`).
    pub cones_fitted: u64,
    /// The worst step's miss of the cone's conditions, over its velocity scale (`cone.rs`).
    pub worst_residual: f64,
}

impl MeterStick3d {
    /// The scene of the planar `p`'s rod and fingers, `width` wide, the path at `heading`: the
    /// planar fingers' speeds are the path's `x` speeds, so the path's are those over `cos psi`.
    #[must_use]
    pub fn from_planar(p: &crate::MeterStick, width: f64, heading: f64) -> Self {
        let c = heading.cos();
        Self {
            rod_length: p.rod_length,
            rod_thickness: p.rod_thickness,
            rod_width: width,
            rod_mass: p.rod_mass,
            gravity: p.gravity,
            finger1_x: p.finger1_x,
            finger2_x: p.finger2_x,
            finger1_y: p.finger1_y,
            finger2_y: p.finger2_y,
            finger1_velocity: p.finger1_velocity / c,
            finger2_velocity: p.finger2_velocity / c,
            heading,
            finger_width: p.finger_width,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            step: p.step,
            stick_speed: p.stick_speed,
            tilt_limit: p.tilt_limit,
            drop_limit: p.drop_limit,
            hold_time: p.hold_time,
            max_time: p.max_time,
        }
    }

    /// The planar scene of the same rod and fingers (`MeterStick3dParams::planar`): the fingers'
    /// `x` speeds `v cos psi`.
    #[must_use]
    pub fn planar(&self) -> crate::MeterStick {
        let c = self.heading.cos();
        crate::MeterStick {
            rod_length: self.rod_length,
            rod_thickness: self.rod_thickness,
            rod_mass: self.rod_mass,
            gravity: self.gravity,
            finger1_x: self.finger1_x,
            finger2_x: self.finger2_x,
            finger1_y: self.finger1_y,
            finger2_y: self.finger2_y,
            finger1_velocity: self.finger1_velocity * c,
            finger2_velocity: self.finger2_velocity * c,
            finger_width: self.finger_width,
            mu_static: self.mu_static,
            mu_kinetic: self.mu_kinetic,
            step: self.step,
            stick_speed: self.stick_speed,
            tilt_limit: self.tilt_limit,
            drop_limit: self.drop_limit,
            hold_time: self.hold_time,
            max_time: self.max_time,
        }
    }

    /// docs/scenes.md, "meter-stick-3d", "Validity": the planar scene's rules, `w > 0`, `|psi| <=
    /// 80 deg`.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that breaks a rule (the planar scene's rules
    /// on the fingers' places as [`Rule::OutOfRange`] of `finger2_x` or the finger's `x`).
    pub fn validate(&self) -> Result<(), Error> {
        for (field, value) in [
            ("finger1_x", self.finger1_x),
            ("finger2_x", self.finger2_x),
            ("finger1_y", self.finger1_y),
            ("finger2_y", self.finger2_y),
            ("finger1_velocity", self.finger1_velocity),
            ("finger2_velocity", self.finger2_velocity),
            ("heading", self.heading),
        ] {
            if !value.is_finite() {
                return Err(invalid(field, Rule::NotFinite));
            }
        }
        super::scenes::common(
            &[
                ("rod_length", self.rod_length),
                ("rod_thickness", self.rod_thickness),
                ("rod_width", self.rod_width),
                ("rod_mass", self.rod_mass),
                ("step", self.step),
                ("tilt_limit", self.tilt_limit),
                ("drop_limit", self.drop_limit),
                ("max_time", self.max_time),
            ],
            &[
                ("gravity", self.gravity),
                ("finger_width", self.finger_width),
                ("mu_static", self.mu_static),
                ("mu_kinetic", self.mu_kinetic),
                ("stick_speed", self.stick_speed),
                ("hold_time", self.hold_time),
            ],
            (self.mu_static, self.mu_kinetic),
            (self.step, self.max_time),
        )?;
        if self.heading.abs() > 80.0_f64.to_radians() {
            return Err(invalid("heading", Rule::OutOfRange));
        }
        // The planar scene's rules on the rod and the fingers' places.
        self.planar().validate().map_err(|why| {
            let field = ["finger1_x", "finger2_x", "rod_thickness"]
                .into_iter()
                .find(|f| why.starts_with(f))
                .unwrap_or("rod_length");
            invalid(field, Rule::OutOfRange)
        })?;
        if self.moments().iter().any(|i| !(i.is_finite() && *i > 0.0)) {
            return Err(invalid("rod_mass", Rule::OutOfRange));
        }
        Ok(())
    }

    /// The box's principal moments: `m (w^2 + t^2) / 12`, `m (L^2 + t^2) / 12`, `m (L^2 + w^2) / 12`.
    #[must_use]
    pub fn moments(&self) -> [f64; 3] {
        let (l, w, t, k) = (self.rod_length, self.rod_width, self.rod_thickness, self.rod_mass / 12.0);
        [k * (w * w + t * t), k * (l * l + t * t), k * (l * l + w * w)]
    }

    /// The planar scene's resting state `(x, y, theta)`: `theta0 = atan` of the fingers' slope,
    /// the centre of mass `t/2` above the foot on the face's line above world `x = 0` (docs/scenes.md,
    /// "meter-stick", "Start").
    fn rest(&self) -> (f64, f64, f64) {
        let slope = (self.finger2_y - self.finger1_y) / (self.finger2_x - self.finger1_x);
        let theta = slope.atan();
        let half = 0.5 * self.rod_thickness;
        let foot_x = theta.sin() * half;
        let foot_y = self.finger1_y + slope * (foot_x - self.finger1_x);
        let (s, c) = theta.sin_cos();
        (foot_x - half * s, foot_y + half * c, theta)
    }
}

/// The rod's state.
#[derive(Debug, Clone, Copy)]
struct State {
    x: V3,
    q: [f64; 4],
    v: V3,
    omega: V3,
}

/// A contact read at a step's start.
#[derive(Debug, Clone, Copy)]
struct Touch {
    /// The finger's crossing of the face's line, world; `None` when the finger runs along the rod.
    crossing: Option<V3>,
    /// In the rod's frame.
    local: V3,
    arm: V3,
    gap: f64,
    under: bool,
}

#[cfg(test)]
thread_local! {
    /// When `Some`, every step's contact problem (its step, 1 the first), for the tests.
    pub(crate) static PROBLEMS: std::cell::RefCell<Option<Vec<(u64, Contacts)>>> = const { std::cell::RefCell::new(None) };
}

/// How a step's contacts were solved.
#[derive(Debug, Clone, Copy, Default)]
struct Solve {
    /// The step before's cases did not verify.
    missed: bool,
    /// The answer's worst miss (`cone.rs`).
    residual: f64,
    /// The stuck points' impulses were moved into their cones.
    fitted: bool,
}

/// The rod's row: sliding when a point slides, else sticking when one touches; the points'
/// impulses summed.
fn rod_row(t: f64, s: &State, points: &[RodPoint; ROD_POINTS]) -> Row {
    let mode = if points.iter().any(|q| q.mode == Mode::Sliding) {
        Mode::Sliding
    } else if points.iter().any(|q| q.mode == Mode::Sticking) {
        Mode::Sticking
    } else {
        Mode::Separated
    };
    Row {
        t,
        position: s.x,
        orientation: s.q,
        velocity: s.v,
        angular_velocity: s.omega,
        mode,
        normal_impulse: points.iter().map(|q| q.normal_impulse).sum(),
        friction_impulse: points.iter().fold(ZERO, |a, q| plus(a, q.friction_impulse)),
    }
}

/// The scene while it runs.
struct Scene {
    p: MeterStick3d,
    fingers: Fingers,
    moments: V3,
}

impl Scene {
    /// Finger `f`'s line crossing the face's line `y_b = b`, and that point against the face.
    fn touch(&self, s: &State, tip: V3, b: f64) -> Touch {
        let r = matrix_of(s.q);
        let rt = transpose(&r);
        let l0 = apply(&rt, [tip[0] - s.x[0], tip[1] - s.x[1], tip[2] - s.x[2]]);
        let e = apply(&rt, [0.0, 1.0, 0.0]);
        let none = Touch { crossing: None, local: ZERO, arm: ZERO, gap: f64::INFINITY, under: false };
        if e[1].is_nan() || e[1].abs() < 1.0 / 16.0 {
            return none;
        }
        let point = [tip[0], tip[1] + (b - l0[1]) / e[1], tip[2]];
        let l = apply(&rt, [point[0] - s.x[0], point[1] - s.x[1], point[2] - s.x[2]]);
        let half_t = 0.5 * self.p.rod_thickness;
        let arm = apply(&r, [l[0], l[1], -half_t]);
        let size = length(arm) + s.x.iter().map(|c| c.abs()).sum::<f64>();
        let edge = 0.5 * self.p.rod_width + 16.0 * f64::EPSILON * size;
        let under = l[0].abs() <= 0.5 * self.p.rod_length && l[1].abs() <= edge && l[2] <= 0.0;
        Touch { crossing: Some(point), local: l, arm, gap: -l[2] - half_t, under }
    }

    fn touches(&self, s: &State, tips: &[V3; 2]) -> [Touch; ROD_POINTS] {
        let half_w = 0.5 * self.p.rod_width;
        [self.touch(s, tips[0], -half_w), self.touch(s, tips[0], half_w), self.touch(s, tips[1], 0.0)]
    }

    /// The points before the first step (module docs): their modes, no impulse.
    fn start(&self, s: &State) -> [RodPoint; ROD_POINTS] {
        let p = &self.p;
        let (tips, velocity) = (self.fingers.tips(0), self.fingers.velocity_over(0));
        let size: f64 = s.x.iter().map(|c| c.abs()).sum::<f64>() + 0.5 * (p.rod_length + p.rod_width);
        let touches = self.touches(s, &tips);
        let n = Self::normal(s);
        std::array::from_fn(|i| {
            let (t, finger) = (&touches[i], usize::from(i == 2));
            let slip = length(in_plane(times(-1.0, velocity[finger]), n));
            let mode = if !(t.under && t.gap <= 64.0 * f64::EPSILON * size) {
                Mode::Separated
            } else if slip <= p.stick_speed {
                Mode::Sticking
            } else {
                Mode::Sliding
            };
            let point = t.crossing.map_or(tips[finger], |_| plus(s.x, t.arm));
            RodPoint { mode, normal_impulse: 0.0, friction_impulse: ZERO, point }
        })
    }

    /// Each finger's place along the rod (the pad's mean of its points') at `steps h`, and
    /// whether it is under the rod.
    fn along(&self, s: &State, steps: u64) -> ([f64; 2], [bool; 2]) {
        let ends = self.touches(s, &self.fingers.tips(steps));
        let (mut along, mut under) = ([0.0; 2], [false; 2]);
        for (i, e) in ends.iter().enumerate() {
            if e.crossing.is_some() {
                let (finger, share) = if i == 2 { (1, 1.0) } else { (0, 0.5) };
                along[finger] += share * e.local[0];
                under[finger] |= e.local[0].abs() <= 0.5 * self.p.rod_length && e.local[2] <= 0.0;
            }
        }
        (along, under)
    }

    fn normal(s: &State) -> V3 {
        apply(&matrix_of(s.q), [0.0, 0.0, 1.0])
    }

    fn inverse_inertia(&self, s: &State) -> [[f64; 3]; 3] {
        congruent(&matrix_of(s.q), self.moments.map(|i| 1.0 / i))
    }

    /// One step from `s` at `steps h`, the modes before it `before` and the cases the step
    /// before found (`guess`).
    fn step(
        &self,
        s: &State,
        steps: u64,
        before: [Mode; ROD_POINTS],
        guess: &mut Vec<PointCase>,
    ) -> Result<(State, [RodPoint; ROD_POINTS], Solve), super::ContactError> {
        let p = &self.p;
        let (h, m, g) = (p.step, p.rod_mass, p.gravity);
        let tips = self.fingers.tips(steps);
        let finger_v = self.fingers.velocity_over(steps);
        let touches = self.touches(s, &tips);
        let n = Self::normal(s);
        let v_free = [s.v[0], s.v[1], s.v[2] - h * g];
        let inv = self.inverse_inertia(s);
        let position_size: f64 = s.x.iter().map(|c| c.abs()).sum();
        let carried = |i: usize| finger_v[usize::from(i == 2)];
        let active: Vec<usize> =
            (0..ROD_POINTS).filter(|&i| touches[i].under && touches[i].gap <= MARGIN).collect();
        let mut impulses = [ZERO; ROD_POINTS];
        let mut solve = Solve::default();
        if active.is_empty() {
            guess.clear();
        } else {
            let k = active.len();
            let arms: Vec<V3> = active.iter().map(|&i| touches[i].arm).collect();
            let w = cone::delassus(m, &inv, &arms);
            let u: Vec<V3> = active
                .iter()
                .map(|&i| {
                    let t = &touches[i];
                    let free = plus(plus(v_free, cross(s.omega, t.arm)), times(-1.0, carried(i)));
                    let fuzz = 4.0 * f64::EPSILON * (position_size + length(t.arm));
                    plus(free, times(bias(t.gap, h, g, fuzz), n))
                })
                .collect();
            let mu: Vec<f64> = active
                .iter()
                .map(|&i| if before[i] == Mode::Sliding { p.mu_kinetic } else { p.mu_static })
                .collect();
            let contacts = Contacts { normals: vec![n; k], w, u, mu };
            #[cfg(test)]
            PROBLEMS.with(|record| {
                if let Some(list) = record.borrow_mut().as_mut() {
                    list.push((steps + 1, contacts.clone()));
                }
            });
            let hint = (guess.len() == k).then_some(guess.as_slice());
            let solved = cone::solve(&contacts, hint)?;
            solve = Solve {
                missed: hint.is_some_and(|g| g != solved.cases.as_slice()),
                residual: solved.residual,
                fitted: solved.fitted,
            };
            guess.clone_from(&solved.cases);
            for (slot, &i) in active.iter().enumerate() {
                impulses[i] = solved.p[slot];
            }
        }
        let v = impulses.iter().fold(v_free, |acc, pi| plus(acc, *pi));
        let torque = (0..ROD_POINTS).fold(ZERO, |acc, i| plus(acc, cross(touches[i].arm, impulses[i])));
        let omega = plus(s.omega, times(m, apply(&inv, torque)));
        let points = std::array::from_fn(|i| {
            let t = &touches[i];
            let pn = dot(impulses[i], n);
            let slip = in_plane(plus(plus(v, cross(omega, t.arm)), times(-1.0, carried(i))), n);
            let mode = if !active.contains(&i) || pn <= 64.0 * f64::EPSILON * g * h {
                Mode::Separated
            } else if length(slip) <= p.stick_speed {
                Mode::Sticking
            } else {
                Mode::Sliding
            };
            let point = t.crossing.map_or(tips[usize::from(i == 2)], |_| plus(s.x, t.arm));
            RodPoint {
                mode,
                normal_impulse: m * pn,
                friction_impulse: times(m, in_plane(impulses[i], n)),
                point,
            }
        });
        let (q, omega) = turned(self.moments, h, s.q, omega);
        Ok((State { x: plus(s.x, times(h, v)), q, v, omega }, points, solve))
    }
}

/// Validates `p` and runs the rod to its outcome (docs/scenes.md, "meter-stick-3d"), keeping
/// `keep`'s rows.
///
/// # Errors
/// [`Error::Invalid`], [`Error::TooManySteps`], a step's contacts without an answer
/// ([`Error::Contact`]) or a state not finite.
pub fn run_meter_stick_3d_keeping(p: &MeterStick3d, keep: Keep) -> Result<MeterStick3dRun, Error> {
    p.validate()?;
    let h = p.step;
    let needed = (p.max_time / h).ceil();
    if needed > MAX_STEPS as f64 {
        return Err(Error::TooManySteps { steps: needed });
    }
    let fingers = Fingers::new(&FingerParams {
        x: [p.finger1_x, p.finger2_x],
        height: [p.finger1_y, p.finger2_y],
        speed: [p.finger1_velocity, p.finger2_velocity],
        width: p.finger_width,
        heading: p.heading,
        h: p.step,
    });
    let scene = Scene { p: *p, fingers, moments: p.moments() };
    let (x0, z0, theta0) = p.rest();
    let (sin, cos) = (0.5 * theta0).sin_cos();
    let mut state = State { x: [x0, 0.0, z0], q: [cos, 0.0, -sin, 0.0], v: ZERO, omega: ZERO };
    let start_normal = Scene::normal(&state);
    let start_points = scene.start(&state);
    let mut modes = start_points.map(|q| q.mode);
    let capacity = if keep == Keep::All { needed as usize + 1 } else { 2 };
    let (mut rows, mut points) = (Vec::with_capacity(capacity), Vec::with_capacity(capacity));
    rows.push(rod_row(0.0, &state, &start_points));
    points.push(start_points);
    let mut guess: Vec<PointCase> = Vec::new();
    let (mut steps, mut missed_count, mut fitted_count, mut worst_residual) = (0_u64, 0_u64, 0_u64, 0.0_f64);
    let mut meeting: Option<(f64, f64)> = None;
    let outcome = loop {
        let (next, after, solve) = scene
            .step(&state, steps, modes, &mut guess)
            .map_err(|error| Error::Contact { step: steps + 1, error })?;
        steps += 1;
        missed_count += u64::from(solve.missed);
        fitted_count += u64::from(solve.fitted);
        worst_residual = worst_residual.max(solve.residual);
        if !(next.x.iter().chain(&next.q).chain(&next.v).chain(&next.omega)).all(|c| c.is_finite()) {
            return Err(Error::NonFinite { step: steps });
        }
        state = next;
        modes = after.map(|q| q.mode);
        let t = steps as f64 * h;
        let kept = rod_row(t, &state, &after);
        if let (Keep::StartAndEnd, Some(last), Some(last_points)) = (keep, rows.get_mut(1), points.get_mut(1))
        {
            (*last, *last_points) = (kept, after);
        } else {
            rows.push(kept);
            points.push(after);
        }
        // The outcome (docs/scenes.md), on the points at the step's end.
        let (along, under) = scene.along(&state, steps);
        if meeting.is_none() && scene.fingers.stopped(steps) {
            meeting = Some((t, -(along[0] + along[1]) / 2.0));
        }
        let normal = Scene::normal(&state);
        let (sin, cos) = (length(cross(normal, start_normal)), dot(normal, start_normal));
        let fell = !(cos > 0.0 && (sin / cos).atan() <= p.tilt_limit)
            || state.x[2] < z0 - p.drop_limit
            || !(under[0] || under[1]);
        if fell {
            break Outcome::Fell;
        }
        if meeting.is_some_and(|(met, _)| t - met >= p.hold_time)
            && modes.iter().all(|&m| m != Mode::Separated)
            && along[0] <= 0.0
            && along[1] >= 0.0
        {
            break Outcome::Balanced;
        }
        if t >= p.max_time || steps >= MAX_STEPS {
            break Outcome::Unfinished;
        }
    };
    let measured = [meeting.map(|m| m.0), meeting.map(|m| m.1), None];
    Ok(MeterStick3dRun {
        run: SpatialRun { outcome, measured, steps, trajectory: rows },
        points,
        guesses_missed: missed_count,
        cones_fitted: fitted_count,
        worst_residual,
    })
}
