//! [`MeterStick3d`]: the paper's rod on two fingers in three dimensions, finger 1 moving along a
//! path at `heading` to the rod's axis (`docs/scenes.md`, "meter-stick-3d").
//!
//! The rod is a box `L x w x t` (`rod_length`, `rod_width`, `rod_thickness`) along the world's
//! `x`, `z` up. Each finger is a [`Finger`] lying across it along the world's `y` (touching its
//! lower face where its long edges cross the finger: `crate::spatial`'s "Fingers lie across the
//! rod"), four support points in all, stepped by [`SupportedStepper`]. The fingers start at
//! `finger1_x`, `finger2_x` on the rod's axis at heights `finger1_y`, `finger2_y` (the planar
//! scene's names: its `y` is up, here `z`) and move at `finger1_velocity`, `finger2_velocity`
//! along `(cos heading, sin heading, 0)`. Approaching fingers stop when their `x` are
//! `finger_width` apart, as the planar scene's ([`crate::scene::MeterStick`]): at heading 0 every
//! input is the planar scene's, and so is the motion.
//!
//! **Outcome.** [`Outcome::Fell`] when the rod's face tilted more than `tilt_limit` from its start
//! (the angle between its normals: pitch and roll; yaw is free), its centre of mass dropped more
//! than `drop_limit`, or no finger is under it; [`Outcome::Balanced`] when the fingers met with
//! the centre of mass between them along the rod and every point stayed on for `hold_time`;
//! [`Outcome::Unfinished`] at `max_time`.

use heapless::Vec;

use super::view::SeenContact;
use crate::RunStats;
use crate::params::{ParamError, params};
use crate::real::Real;
use crate::scene::{Meeting, MeterStickParams, Outcome};
use crate::spatial::{
    Body, Finger, LowerFace, Mode, SpatialSettings, SpatialStepReport, SupportPoint, SupportedStepper,
    Vector, about, cross, dot, norm, rotate,
};

/// The support points: finger 1's two (a pad across the rod), finger 2's one (on the rod's
/// centre line).
pub const ROD_POINTS: usize = 3;

/// Each support point's finger and its share of the finger's place along the rod.
const FINGER_OF: [(usize, f64); ROD_POINTS] = [(0, 0.5), (0, 0.5), (1, 1.0)];

/// The rows of the rod's LCP: one friction line per point.
pub const ROD_ROWS: usize = 4 * ROD_POINTS;

/// The switch events a run keeps.
pub const ROD_EVENTS: usize = 64;

params! {
    /// Parameters of the meter stick in three dimensions, SI units: the planar scene's
    /// ([`MeterStickParams`], the same names and defaults), the rod's width and the path's heading.
    pub struct MeterStick3dParams {
        /// Rod length `L` (m, > 0). 1.
        rod_length: 1.0, Positive;
        /// Rod thickness `t` (m, > 0). 0.005.
        rod_thickness: 0.005, Positive;
        /// Rod width `w` (m, > 0): the fingers touch its lower face at its two long edges. 0.025.
        rod_width: 0.025, Positive;
        /// Rod mass `m` (kg, > 0). 0.2.
        rod_mass: 0.2, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-z`. 9.81.
        gravity: 9.81, NonNegative;
        /// Start `x` of finger 1 (m), left of finger 2. -0.4.
        finger1_x: -0.4, Finite;
        /// Start `x` of finger 2 (m). 0.4.
        finger2_x: 0.4, Finite;
        /// Height of finger 1 (m, along `z`). 0.
        finger1_y: 0.0, Finite;
        /// Height of finger 2 (m, along `z`). 0.
        finger2_y: 0.0, Finite;
        /// Speed of finger 1 along its path (m/s). 0.1.
        finger1_velocity: 0.1, Finite;
        /// Speed of finger 2 along the same heading (m/s). 0.
        finger2_velocity: 0.0, Finite;
        /// The path's heading from the rod's axis toward `+y`, rad (`|heading| <= 80 deg`; the
        /// command line's `--heading` in degrees). 0.
        heading: 0.0, Finite;
        /// Finger width along the rod (m, >= 0): approaching fingers stop when their `x` are this
        /// far apart. 0.01.
        finger_width: 0.01, NonNegative;
        /// Static friction coefficient of both fingers (>= 0). 0.6.
        mu_static: 0.6, NonNegative;
        /// Kinetic friction coefficient (0 <= mu_k <= mu_s). 0.4.
        mu_kinetic: 0.4, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching point whose slip speed is at most this sticks (m/s, > 0). 1e-5.
        stick_speed: 1e-5, Positive;
        /// The rod has fallen when its face tilted more than this (rad, > 0). 0.35.
        tilt_limit: 0.35, Positive;
        /// The rod has fallen when its centre of mass dropped this far (m, > 0). 0.02.
        drop_limit: 0.02, Positive;
        /// After the fingers meet, the rod must stay on them this long to balance (s, >= 0). 0.5.
        hold_time: 0.5, NonNegative;
        /// A run ends unfinished at this simulated time (s, > 0). 30.
        max_time: 30.0, Positive;
    }
}

impl<T: Real> MeterStick3dParams<T> {
    /// The planar scene of the same rod and fingers (the path's heading and the rod's width
    /// dropped, the speeds along `x` those of the path's `x`).
    #[must_use]
    pub fn planar(&self) -> MeterStickParams<T> {
        let c = self.heading_sin_cos().1;
        MeterStickParams {
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

    /// `(sin, cos)` of the heading.
    #[must_use]
    pub fn heading_sin_cos(&self) -> (T, T) {
        self.heading.sin_cos_portable()
    }

    /// The rod: a uniform box `L x w x t`.
    #[must_use]
    pub fn body(&self) -> Body<T> {
        Body::cuboid(self.rod_mass, self.rod_length, self.rod_width, self.rod_thickness)
    }

    /// Checks every parameter: the planar scene's ([`MeterStickParams::validate`]), the heading
    /// (`|heading| <= 80 deg`) and the rod's box.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        if self.heading.abs_exact() > T::of(80.0_f64.to_radians()) {
            return Err(ParamError::OutOfRange("heading"));
        }
        self.planar().validate()?;
        self.body()
            .validate()
            .map_err(|_| ParamError::InertiaOutOfRange { mass: "rod_mass", size: "rod_width" })
    }
}

/// A change of one finger's mode: its two points' (sliding when either slides, sticking when
/// either touches, separated when neither does).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FingerSwitch<T> {
    /// s.
    pub time: T,
    /// 0 or 1.
    pub finger: u8,
    /// The finger's mode from this step on.
    pub mode: Mode,
}

/// A finger's velocity at `x` speed `v` along the path `(sin, cos)` of its heading: `(v, v tan, 0)`.
fn along_path<T: Real>((sin, cos): (T, T), v: T) -> Vector<T> {
    [v, v * sin / cos, T::zero()]
}

/// Each finger's mode from its points' ([`FingerSwitch`]).
#[must_use]
pub fn finger_modes(points: [Mode; ROD_POINTS]) -> [Mode; 2] {
    let [a, b, c] = points;
    [[a, b], [c, c]].map(|pair| {
        if pair.contains(&Mode::Sliding) {
            Mode::Sliding
        } else if pair.contains(&Mode::Sticking) {
            Mode::Sticking
        } else {
            Mode::Separated
        }
    })
}

/// The meter stick in three dimensions, as `docs/scenes.md` defines it.
#[derive(Debug, Clone)]
pub struct MeterStick3d<T: Real> {
    params: MeterStick3dParams<T>,
    stepper: SupportedStepper<T, ROD_POINTS, ROD_ROWS>,
    /// The path's heading, `(sin, cos)`.
    path: (T, T),
    /// Where approaching fingers stop (`x`); `None` when they do not approach.
    stops: Option<[T; 2]>,
    /// The fingers' `x` velocities over a step before they stop.
    travel_velocity: [T; 2],
    /// The fingers' tips now.
    tips: [Vector<T>; 2],
    modes: [Mode; 2],
    events: Vec<FingerSwitch<T>, ROD_EVENTS>,
    meeting: Option<Meeting<T>>,
    outcome: Option<Outcome>,
    start_normal: Vector<T>,
    start_z: T,
    /// The fingers' `x` velocities over the last step.
    velocity: [T; 2],
    /// Where the fingers cross under the rod now, moving at `velocity` ([`Self::fingers_at`]).
    crossings: [Option<SupportPoint<T>>; ROD_POINTS],
    stats: RunStats,
}

impl<T: Real> MeterStick3d<T> {
    /// The rod at rest on the fingers (the planar scene's resting state, turned about `-y`).
    ///
    /// # Errors
    /// The first invalid parameter ([`MeterStick3dParams::validate`]).
    pub fn new(params: MeterStick3dParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let planar = params.planar();
        let rest = planar.resting_state();
        let p = &params;
        let (sin, cos) = p.heading_sin_cos();
        let stops = planar.fingers_approach().then(|| {
            let w = p.finger_width;
            let (v1, v2) = (planar.finger1_velocity, planar.finger2_velocity);
            if v2 == T::zero() {
                [p.finger2_x - w, p.finger2_x]
            } else if v1 == T::zero() {
                [p.finger1_x, p.finger1_x + w]
            } else {
                let t_stop = (p.finger2_x - p.finger1_x - w) / (v1 - v2);
                let s1 = p.finger1_x + v1 * t_stop;
                [s1, s1 + w]
            }
        });
        let orientation = about(&[T::zero(), -T::one(), T::zero()], rest.theta);
        let state = crate::spatial::State {
            position: [rest.x, T::zero(), rest.y],
            orientation,
            velocity: [T::zero(); 3],
            angular_velocity: [T::zero(); 3],
        };
        let settings = SpatialSettings {
            step: p.step,
            gravity: [T::zero(), T::zero(), -p.gravity],
            stick_speed: p.stick_speed,
            ..SpatialSettings::default()
        };
        let half = T::of(0.5);
        let face = LowerFace {
            half_length: p.rod_length * half,
            half_width: p.rod_width * half,
            half_thickness: p.rod_thickness * half,
        };
        let (sin_cos, h) = ((sin, cos), p.step);
        let velocity = [planar.finger1_velocity, planar.finger2_velocity];
        let tips = [[p.finger1_x, T::zero(), p.finger1_y], [p.finger2_x, T::zero(), p.finger2_y]];
        let start = Self::fingers_at(&face, &state, sin_cos, &tips, velocity);
        let stepper =
            SupportedStepper::new(p.body(), face, [p.mu_static, p.mu_kinetic], settings, state, &start)?;
        let modes = finger_modes(*stepper.modes());
        Ok(Self {
            params,
            stepper,
            path: sin_cos,
            stops,
            travel_velocity: [planar.finger1_velocity * h / h, planar.finger2_velocity * h / h],
            tips,
            modes,
            events: Vec::new(),
            meeting: None,
            outcome: None,
            start_normal: rotate(&orientation, &[T::zero(), T::zero(), T::one()]),
            start_z: rest.y,
            velocity,
            crossings: start,
            stats: RunStats::default(),
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &MeterStick3dParams<T> {
        &self.params
    }

    /// The stepper.
    #[must_use]
    pub const fn stepper(&self) -> &SupportedStepper<T, ROD_POINTS, ROD_ROWS> {
        &self.stepper
    }

    /// The fingers' path's heading to the rod's axis, `(sin psi, cos psi)`.
    #[must_use]
    pub const fn path(&self) -> (T, T) {
        self.path
    }

    /// The fingers' tips now (m, world axes).
    #[must_use]
    pub const fn tips(&self) -> [Vector<T>; 2] {
        self.tips
    }

    /// When and where the fingers met, once they have (the offset along the rod's axis).
    #[must_use]
    pub const fn meeting(&self) -> Option<Meeting<T>> {
        self.meeting
    }

    /// The outcome, once the run has ended.
    #[must_use]
    pub const fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }

    /// The fingers' switches so far (the first [`ROD_EVENTS`]).
    #[must_use]
    pub fn events(&self) -> &[FingerSwitch<T>] {
        &self.events
    }

    /// The run's counters: steps, pivots, the steps the warm basis answered without a pivot.
    #[must_use]
    pub const fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// Takes the outcome so that the run goes on (`SceneView::go_on`); `None` before it.
    pub fn go_on(&mut self) -> Option<Outcome> {
        self.outcome.take()
    }

    /// Finger `i` (0 or 1) now: the line across the rod at its tip, moving at its velocity over
    /// the last step.
    #[must_use]
    pub fn finger(&self, i: usize) -> Option<Finger<T>> {
        let (tip, v) = (*self.tips.get(i)?, *self.velocity.get(i)?);
        Some(Finger { tip, across: [T::zero(), T::one(), T::zero()], velocity: along_path(self.path, v) })
    }

    /// Support point `i` (finger 1's two, then finger 2's) against the rod now; `None` past
    /// [`ROD_POINTS`] or when its finger runs along the rod.
    #[must_use]
    pub fn contact(&self, i: usize) -> Option<SeenContact<T>> {
        let p = (*self.crossings.get(i)?)?;
        let touch = self.stepper.touch(&p.position);
        Some(SeenContact {
            lever: touch.lever,
            gap: touch.gap,
            normal: self.stepper.normal(),
            active: touch.under && touch.gap <= self.stepper.settings().margin,
            support: u8::from(i >= 2),
        })
    }

    /// Each finger's mode after the last step (its two points', [`FingerSwitch`]).
    #[must_use]
    pub const fn finger_modes(&self) -> [Mode; 2] {
        self.modes
    }

    /// The fingers as lines across the rod along `y`, at tips `tips` moving at `velocity` (`x`
    /// speeds) along the path `(cos, sin)` of `sin_cos`: finger 1 a pad (the face's edges),
    /// finger 2 a point (its centre line).
    fn fingers_at(
        face: &LowerFace<T>,
        state: &crate::spatial::State<T>,
        (sin, cos): (T, T),
        tips: &[Vector<T>; 2],
        velocity: [T; 2],
    ) -> [Option<SupportPoint<T>>; ROD_POINTS] {
        let across = [T::zero(), T::one(), T::zero()];
        let [a, b] =
            [0, 1].map(|i| Finger { tip: tips[i], across, velocity: along_path((sin, cos), velocity[i]) });
        let pad = a.crossings(face, state);
        [pad[0], pad[1], b.crossing(T::zero(), state)]
    }

    /// The `x` of each finger's crossings along the rod (body frame), their mean per finger; and
    /// whether each finger is under the rod (`|x| <= L/2`, below its centre).
    fn along(&self, points: &[Option<SupportPoint<T>>; ROD_POINTS]) -> ([T; 2], [bool; 2]) {
        let (half, mut along, mut under) = (self.params.rod_length * T::of(0.5), [T::zero(); 2], [false; 2]);
        for (i, point) in points.iter().enumerate() {
            if let Some(p) = point {
                let (finger, share) = FINGER_OF[i];
                let l = self.stepper.in_body(&p.position);
                along[finger] += l[0] * T::of(share);
                under[finger] |= l[0].abs_exact() <= half && l[2] <= T::zero();
            }
        }
        (along, under)
    }

    /// Advances one step; `None` once the run has an outcome (a failed step ends the run with
    /// [`Outcome::Failed`]).
    pub fn step(&mut self) -> Option<SpatialStepReport<T, ROD_POINTS>> {
        if self.outcome.is_some() {
            return None;
        }
        let p = self.params;
        let h = p.step;
        let t_end = self.stepper.next_time();
        let (v1, v2) = (self.travel_velocity[0], self.travel_velocity[1]);
        let free = [p.finger1_x + v1 * t_end, p.finger2_x + v2 * t_end];
        let stopped = self.stops.is_some_and(|s| {
            if v1 > T::zero() {
                free[0] >= s[0]
            } else if v1 < T::zero() {
                free[0] <= s[0]
            } else {
                free[1] <= s[1]
            }
        });
        let x = [self.tips[0][0], self.tips[1][0]];
        let (ends, velocity) = match self.stops {
            Some(s) if stopped => (s, [(s[0] - x[0]) / h, (s[1] - x[1]) / h]),
            _ => (free, self.travel_velocity),
        };
        let start = [p.finger1_x, p.finger2_x];
        let heights = [p.finger1_y, p.finger2_y];
        let tips: [Vector<T>; 2] =
            core::array::from_fn(|i| [ends[i], (ends[i] - start[i]) * self.path.0 / self.path.1, heights[i]]);
        // The contacts' geometry is the step's start's: the rod's state and the fingers' places
        // then (the last step's crossings), each moving at its velocity over the step (as the
        // planar stepper's frames).
        let moving;
        let supports = if velocity == self.velocity {
            &self.crossings
        } else {
            let mut supports = self.crossings;
            for (support, (finger, _)) in supports.iter_mut().zip(FINGER_OF) {
                if let (Some(point), Some(&v)) = (support.as_mut(), velocity.get(finger)) {
                    point.velocity = along_path(self.path, v);
                }
            }
            moving = supports;
            &moving
        };
        let report = match self.stepper.step(supports) {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.tips = tips;
        self.velocity = velocity;
        self.stats.steps += 1;
        self.stats.count_pivots(report.pivots);
        if report.pivots == 0 {
            self.stats.warm_starts += 1;
        }
        let modes = finger_modes(report.contacts.map(|c| c.mode));
        for (f, (&now, &before)) in modes.iter().zip(&self.modes).enumerate() {
            if now != before {
                // A full log keeps its first events.
                let _ = self.events.push(FingerSwitch { time: report.time, finger: f as u8, mode: now });
            }
        }
        self.modes = modes;
        self.crossings =
            Self::fingers_at(self.stepper.face(), self.stepper.state(), self.path, &tips, velocity);
        self.judge(stopped, &report);
        Some(report)
    }

    /// The outcome rules (module docs) on the state after a step (its crossings `self.crossings`).
    fn judge(&mut self, stopped: bool, report: &SpatialStepReport<T, ROD_POINTS>) {
        let p = &self.params;
        let (along, under) = self.along(&self.crossings);
        let time = report.time;
        if self.meeting.is_none() && stopped {
            self.meeting = Some(Meeting { time, com_offset: -(along[0] + along[1]) / T::of(2.0) });
        }
        let normal = self.stepper.normal();
        // The angle between the normals; beyond a right angle, fallen whatever the limit.
        let (sin, cos) = (norm(&cross(&normal, &self.start_normal)), dot(&normal, &self.start_normal));
        let fell = !(cos > T::zero() && (sin / cos).atan_libm() <= p.tilt_limit)
            || report.state.position[2] < self.start_z - p.drop_limit
            || !(under[0] || under[1]);
        if fell {
            self.outcome = Some(Outcome::Fell);
        } else if let Some(meeting) = self.meeting
            && time - meeting.time >= p.hold_time
            && report.contacts.iter().all(|c| c.mode != Mode::Separated)
            && along[0] <= T::zero()
            && along[1] >= T::zero()
        {
            self.outcome = Some(Outcome::Balanced);
        } else if time >= p.max_time {
            self.outcome = Some(Outcome::Unfinished);
        }
    }

    /// Runs to the outcome.
    pub fn run(&mut self) -> Outcome {
        while self.step().is_some() {}
        self.outcome.unwrap_or(Outcome::Unfinished)
    }
}
