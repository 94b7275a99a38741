//! [`MeterStick`]: the paper's scene, a rod on two fingers (`docs/scenes.md`, "meter-stick").
//!
//! The rod is a thin box (`J = m L^2 / 12`) resting on two finger tips, contacts 0 and 1, each a
//! [`Support::Point`] under its lower face. Both fingers have a start position, a height and a
//! horizontal velocity (finger 1 alone, both inward, finger 2 alone, or apart); when they approach
//! they stop `finger_width` apart ("the fingers meet").
//!
//! **Sizes.** `N = 8` is the paper's form (both friction directions at both fingers). `N = 6` keeps
//! the direction each finger can use: while the fingers approach (or stand still), finger 1 drags
//! the rod toward `+x` (`+d`) and finger 2 holds it back (`-d`); while they move apart, the
//! opposite. After each 6x6 step the dropped directions are checked and, when one is needed, the
//! step is solved again in 8x8 (feature `fallback`; [`StepReport::full_layout_used`]).
//!
//! **Outcome.** [`Outcome::Fell`] when the rod tilted more than `tilt_limit` from its start angle,
//! its centre of mass dropped more than `drop_limit`, or no finger is under it;
//! [`Outcome::Balanced`] when the fingers met with the centre of mass between them and the rod
//! stayed on both for `hold_time`; [`Outcome::Unfinished`] at `max_time`.
//!
//! # Example
//! ```
//! use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};
//!
//! let params = MeterStickParams { finger1_x: -0.35, ..MeterStickParams::<f32>::paper() };
//! let mut scene = MeterStick6::<f32>::new(params).expect("valid parameters");
//! assert_eq!(scene.run(|_| {}), Outcome::Balanced);
//! let meeting = scene.meeting().expect("the fingers met");
//! assert!(meeting.com_offset.abs() < 0.003); // the fingers stop 1 cm apart
//! ```

use super::outcome::Outcome;
use super::scene_trait::impl_scene;
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{
    Body, BodyState, Contact, EventLog, Feature, Layout, Model, Settings, StepReport, Stepper, Support,
    Tangents,
};
use crate::real::Real;

params! {
    /// Parameters of the meter-stick scene, SI units; the defaults are the paper's scene
    /// (Leong & Lv, section V.A; `docs/scenes.md`).
    ///
    /// World `x` to the right, `y` up; the rod's centre of mass starts above `x = 0`, resting on
    /// the finger tips. Finger 1 is the left one.
    pub struct MeterStickParams {
        /// Rod length `L` (m, > 0). Paper: 1.
        rod_length: 1.0, Positive;
        /// Rod thickness `t` (m, > 0); the contacts sit on its lower face. Paper: 0.005.
        rod_thickness: 0.005, Positive;
        /// Rod mass `m` (kg, > 0); inertia `m L^2 / 12`. Paper: 0.2.
        rod_mass: 0.2, Positive;
        /// Gravity `g` (m/s^2, >= 0), along `-y`. 9.81.
        gravity: 9.81, NonNegative;
        /// Start `x` of finger 1 (m), left of finger 2. Paper: -0.4.
        finger1_x: -0.4, Finite;
        /// Start `x` of finger 2 (m). Paper: +0.4.
        finger2_x: 0.4, Finite;
        /// Height of finger 1's tip (m). 0.
        finger1_y: 0.0, Finite;
        /// Height of finger 2's tip (m). 0.
        finger2_y: 0.0, Finite;
        /// Horizontal velocity of finger 1 (m/s, `+x` to the right). Paper's slow case: 0.1.
        finger1_velocity: 0.1, Finite;
        /// Horizontal velocity of finger 2 (m/s). 0.
        finger2_velocity: 0.0, Finite;
        /// Finger width (m, >= 0): approaching fingers stop when their tips are this far apart.
        /// 0.01.
        finger_width: 0.01, NonNegative;
        /// Static friction coefficient of both fingers (>= 0). 0.6 (the paper gives none).
        mu_static: 0.6, NonNegative;
        /// Kinetic friction coefficient of both fingers (0 <= mu_k <= mu_s). 0.4.
        mu_kinetic: 0.4, NonNegative;
        /// Time step `h` (s, > 0). 1e-3.
        step: 1e-3, Positive;
        /// A touching finger whose slip speed is at most this sticks (m/s, >= 0). 1e-5.
        stick_speed: 1e-5, NonNegative;
        /// The rod has fallen when it tilted more than this from its start angle (rad, > 0). 0.35.
        tilt_limit: 0.35, Positive;
        /// The rod has fallen when its centre of mass dropped this far (m, > 0). 0.02.
        drop_limit: 0.02, Positive;
        /// After the fingers meet, the rod must stay on them this long to balance (s, >= 0). 0.5.
        hold_time: 0.5, NonNegative;
        /// A run ends unfinished at this simulated time (s, > 0). 30.
        max_time: 30.0, Positive;
    }
}

impl<T: Real> MeterStickParams<T> {
    /// The paper's scene (the defaults): L = 1 m, t = 0.5 cm, m = 0.2 kg, fingers at -/+0.4 m,
    /// finger 1 at 0.1 m/s, mu_s = 0.6, mu_k = 0.4, h = 1 ms.
    #[must_use]
    pub fn paper() -> Self {
        Self::default()
    }

    /// The rod's moment of inertia about its centre of mass, `m L^2 / 12`.
    #[must_use]
    pub fn inertia(&self) -> T {
        Body::rod(self.rod_mass, self.rod_length, self.rod_thickness).inertia
    }

    /// `true` when the fingers approach each other (and so meet).
    #[must_use]
    pub fn fingers_approach(&self) -> bool {
        self.finger1_velocity > self.finger2_velocity
    }

    /// The rod at rest on both finger tips (`docs/scenes.md`, "Start").
    #[must_use]
    pub fn resting_state(&self) -> BodyState<T> {
        let half_t = self.rod_thickness / T::of(2.0);
        let slope = (self.finger2_y - self.finger1_y) / (self.finger2_x - self.finger1_x);
        let theta = slope.atan_libm();
        let (s, c) = theta.sin_cos_portable();
        let foot_x = s * half_t;
        let foot_y = self.finger1_y + slope * (foot_x - self.finger1_x);
        BodyState::at_rest(foot_x - s * half_t, foot_y + c * half_t, theta)
    }

    /// The first finger (its field) that starts beyond an end of the rod
    /// ([`ParamError::FingerOutsideRod`]).
    #[must_use]
    pub fn finger_outside_rod(&self) -> Option<&'static str> {
        // The tips lie on the rod's lower face at rest; their distance along it from the foot of
        // the centre of mass (above x = 0) is the horizontal distance times sqrt(1 + slope^2).
        let slope = (self.finger2_y - self.finger1_y) / (self.finger2_x - self.finger1_x);
        let stretch = (T::one() + slope * slope).sqrt_rounded();
        let foot_x = slope / stretch * (self.rod_thickness / T::of(2.0));
        let half = self.rod_length / T::of(2.0);
        [("finger1_x", self.finger1_x), ("finger2_x", self.finger2_x)]
            .into_iter()
            .find(|&(_, x)| {
                let along = (x - foot_x) * stretch;
                !along.finite() || along.abs_exact() > half
            })
            .map(|(field, _)| field)
    }

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
        let gap = self.finger2_x - self.finger1_x;
        if !gap.finite() || gap <= self.finger_width {
            return Err(ParamError::FingersCrossed);
        }
        Ok(())
    }
}

/// When and where the fingers met.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Meeting<T> {
    /// Time the fingers stopped (s).
    pub time: T,
    /// Offset of the centre of mass from the midpoint between the fingers, along the rod (m): the
    /// meeting-point error.
    pub com_offset: T,
}

/// The meter-stick scene with an `N x N` LCP per step (`N = 8`: the paper's form; `N = 6`: one
/// friction direction per finger, checked) and room for `E` switch events.
#[derive(Debug, Clone)]
pub struct MeterStick<T: Real, const N: usize, const E: usize = 64> {
    params: MeterStickParams<T>,
    stepper: Stepper<T, 2, N, 8>,
    /// Where approaching fingers stop; `None` when they do not approach.
    stops: Option<[T; 2]>,
    /// The fingers' velocities over a step before they stop, `(v h) / h` (the travel a step makes;
    /// constant, so computed once).
    travel_velocity: [T; 2],
    fingers: [T; 2],
    events: EventLog<T, 2, E>,
    meeting: Option<Meeting<T>>,
    outcome: Option<Outcome>,
    start_theta: T,
    start_y: T,
    fired_before_meeting: u64,
}

/// The paper's 8x8 scene.
pub type MeterStick8<T, const E: usize = 64> = MeterStick<T, 8, E>;
/// The reduced 6x6 scene.
pub type MeterStick6<T, const E: usize = 64> = MeterStick<T, 6, E>;

impl<T: Real, const N: usize, const E: usize> MeterStick<T, N, E> {
    /// The rod at rest on the fingers ([`MeterStickParams::resting_state`]).
    ///
    /// # Errors
    /// The first invalid parameter ([`MeterStickParams::validate`]).
    pub fn new(params: MeterStickParams<T>) -> Result<Self, ParamError> {
        let rest = params.resting_state();
        Self::build(params, rest, rest.theta)
    }

    /// The scene from a given initial rod state (e.g. slightly above the fingers).
    ///
    /// # Errors
    /// An invalid parameter, or a non-finite state.
    pub fn with_state(params: MeterStickParams<T>, state: BodyState<T>) -> Result<Self, ParamError> {
        Self::build(params, state, params.resting_state().theta)
    }

    /// The scene from `state`, judging tilt against `start_theta` (the resting angle).
    fn build(params: MeterStickParams<T>, state: BodyState<T>, start_theta: T) -> Result<Self, ParamError> {
        const { assert!(N == 6 || N == 8, "the meter-stick scene has N = 6 or N = 8") };
        params.validate()?;
        if !state.is_finite() {
            return Err(ParamError::NonFiniteState);
        }
        let p = &params;
        let stops = p.fingers_approach().then(|| {
            let w = p.finger_width;
            if p.finger2_velocity == T::zero() {
                [p.finger2_x - w, p.finger2_x]
            } else if p.finger1_velocity == T::zero() {
                [p.finger1_x, p.finger1_x + w]
            } else {
                let t_stop = (p.finger2_x - p.finger1_x - w) / (p.finger1_velocity - p.finger2_velocity);
                let s1 = p.finger1_x + p.finger1_velocity * t_stop;
                [s1, s1 + w]
            }
        });
        let finger =
            Contact { feature: Feature::LowerFace, mu_static: p.mu_static, mu_kinetic: p.mu_kinetic };
        let model = Model {
            body: Body::rod(p.rod_mass, p.rod_length, p.rod_thickness),
            contacts: [finger; 2],
            settings: Settings { step: p.step, gravity: p.gravity, stick_speed: p.stick_speed },
        };
        let layout = if p.fingers_approach() || p.finger1_velocity == p.finger2_velocity {
            const { Self::layout([Tangents::Plus, Tangents::Minus]) }
        } else {
            const { Self::layout([Tangents::Minus, Tangents::Plus]) }
        };
        let supports = [
            Support::point([p.finger1_x, p.finger1_y], [p.finger1_velocity, T::zero()]),
            Support::point([p.finger2_x, p.finger2_y], [p.finger2_velocity, T::zero()]),
        ];
        // The parameters' checks imply the stepper's (finite supports, body and friction).
        let stepper = Stepper::from_valid(model, layout, Layout::full(), state, supports)?;
        Ok(Self {
            params,
            stepper,
            stops,
            travel_velocity: [p.finger1_velocity * p.step / p.step, p.finger2_velocity * p.step / p.step],
            fingers: [p.finger1_x, p.finger2_x],
            events: EventLog::new(),
            meeting: None,
            outcome: None,
            start_theta,
            start_y: state.y,
            fired_before_meeting: 0,
        })
    }

    /// The layout of size `N`: the full one for 8, `reduced` for 6.
    const fn layout(reduced: [Tangents; 2]) -> Layout<2, N> {
        Layout::new(if N == 8 { [Tangents::Both; 2] } else { reduced })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &MeterStickParams<T> {
        &self.params
    }
    /// Finger tip `x` positions (m).
    #[must_use]
    pub const fn fingers(&self) -> [T; 2] {
        self.fingers
    }
    /// Switch events that did not fit the buffer.
    #[must_use]
    pub const fn events_dropped(&self) -> u32 {
        self.events.dropped()
    }
    /// When and where the fingers met, once they have.
    #[must_use]
    pub const fn meeting(&self) -> Option<Meeting<T>> {
        self.meeting
    }
    /// Steps of the 6x6 scene that needed the 8x8 form before the fingers met.
    #[must_use]
    pub const fn reduced_check_fired_before_meeting(&self) -> u64 {
        self.fired_before_meeting
    }
    /// The underlying stepper (contact frames, supports, layout).
    #[must_use]
    pub const fn stepper(&self) -> &Stepper<T, 2, N, 8> {
        &self.stepper
    }

    /// Advances one step of `h`; `None` once the run has an outcome (a failed step ends the run
    /// with [`Outcome::Failed`] and returns `None`).
    fn advance(&mut self) -> Option<StepReport<T, 2>> {
        if self.outcome.is_some() {
            return None;
        }
        let p = &self.params;
        let h = p.step;
        let t_end = self.stepper.next_time();
        let free = [p.finger1_x + p.finger1_velocity * t_end, p.finger2_x + p.finger2_velocity * t_end];
        let stopped = self.stops.is_some_and(|s| {
            if p.finger1_velocity > T::zero() {
                free[0] >= s[0]
            } else if p.finger1_velocity < T::zero() {
                free[0] <= s[0]
            } else {
                free[1] <= s[1]
            }
        });
        let (ends, velocity) = match self.stops {
            Some(s) if stopped => (s, [(s[0] - self.fingers[0]) / h, (s[1] - self.fingers[1]) / h]),
            _ => (free, self.travel_velocity),
        };
        let supports = [
            Support::point([ends[0], p.finger1_y], [velocity[0], T::zero()]),
            Support::point([ends[1], p.finger2_y], [velocity[1], T::zero()]),
        ];
        let report = match self.stepper.step(&supports) {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        if report.full_layout_used && self.meeting.is_none() && !stopped {
            self.fired_before_meeting += 1;
        }
        self.fingers = ends;
        self.events.record(&report);
        self.judge(stopped, &report);
        Some(report)
    }

    /// The outcome rules of `docs/scenes.md`, on the state after a step.
    fn judge(&mut self, stopped: bool, report: &StepReport<T, 2>) {
        let p = &self.params;
        let frames = self.stepper.frames();
        let along = [frames[0].along, frames[1].along];
        let time = report.time;
        if self.meeting.is_none() && stopped {
            self.meeting = Some(Meeting { time, com_offset: -(along[0] + along[1]) / T::of(2.0) });
        }
        let s = &report.state;
        let fell = (s.theta - self.start_theta).abs_exact() > p.tilt_limit
            || s.y < self.start_y - p.drop_limit
            || !(frames[0].active || frames[1].active);
        if fell {
            self.outcome = Some(Outcome::Fell);
        } else if let Some(meeting) = self.meeting
            && time - meeting.time >= p.hold_time
            && report.contacts.iter().all(|c| c.mode.is_touching())
            && along[0] <= T::zero()
            && along[1] >= T::zero()
        {
            self.outcome = Some(Outcome::Balanced);
        } else if time >= p.max_time {
            self.outcome = Some(Outcome::Unfinished);
        }
    }
}

impl<T: Real, const N: usize, const E: usize> MeterStick<T, N, E> {
    /// [`Scene::measured`](crate::scene::Scene::measured): the meeting's time and offset.
    fn measured_values(&self) -> [Option<T>; crate::scene::MAX_MEASURES] {
        let m = self.meeting();
        [m.map(|m| m.time), m.map(|m| m.com_offset), None]
    }
}

impl_scene!(
    MeterStick,
    2,
    |p| crate::scene::BodyShape::Box { width: p.rod_length, height: p.rod_thickness },
    |p| Body::rod(p.rod_mass, p.rod_length, p.rod_thickness)
);
