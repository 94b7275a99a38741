//! [`SceneParams`]: the meter-stick scene's parameters, with the paper's defaults, and
//! their validation ([`ParamError`]).

use crate::real::Real;

/// Parameters of the meter-stick scene, SI units. [`SceneParams::paper`] gives the paper's
/// values (Leong & Lv, section V.A; `../shared/design/formulation.md`).
///
/// Coordinates: world `x` to the right, `y` up; the rod's centre of mass starts at
/// `x = 0`, resting horizontally on the finger tips at `y = 0`. Finger 1 (left) moves
/// toward finger 2 (right) at `finger_speed`; finger 2 stays still. The fingers stop when
/// their tips are `finger_width` apart ("the fingers meet").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneParams<T> {
    /// Rod length `L` (m). Paper: 1.
    pub rod_length: T,
    /// Rod thickness `t` (m); contacts sit at `r_y = -t/2`. Paper: 0.005.
    pub rod_thickness: T,
    /// Rod mass `m` (kg); inertia is `m L^2 / 12`. Paper: 0.2 (the extracted text reads
    /// ".2"; 1.2 is possible, and the slow-case claims hold for either).
    pub rod_mass: T,
    /// Gravity `g` (m/s^2), acting in `-y`. 9.81.
    pub gravity: T,
    /// Start `x` of finger 1 (moving), relative to the rod's centre of mass (m). Paper: -0.4.
    pub finger1_x: T,
    /// Start `x` of finger 2 (fixed) (m). Paper: +0.4.
    pub finger2_x: T,
    /// Finger width (m): finger 1 stops when the tips are this far apart. Default 0.01.
    pub finger_width: T,
    /// Speed of finger 1 toward finger 2 (m/s, >= 0). Paper's slow case: 0.1.
    pub finger_speed: T,
    /// Static friction coefficient, used while a contact sticks. Default 0.6 (the paper
    /// gives none).
    pub mu_static: T,
    /// Kinetic friction coefficient, used while a contact slides. Default 0.4.
    pub mu_kinetic: T,
    /// Time step `h` (s). Default 1e-3.
    pub step: T,
    /// A contact whose tangential slip speed is at most this sticks (m/s). Default 1e-5.
    pub stick_speed: T,
    /// The rod has fallen when `|theta|` exceeds this (rad). Default 0.35 (20 degrees).
    pub tilt_limit: T,
    /// The rod has fallen when its centre of mass dropped this far below its start (m).
    /// Default 0.02.
    pub drop_limit: T,
    /// After the fingers meet, the rod must stay on them this long to count as balanced (s).
    /// Default 0.5.
    pub hold_time: T,
    /// A run stops unfinished at this simulated time (s). Default 30.
    pub max_time: T,
}

/// Why a [`SceneParams`] was rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ParamError {
    /// A parameter is NaN or infinite (the field's name).
    NonFinite(&'static str),
    /// A parameter that must be positive is zero or negative (the field's name).
    NotPositive(&'static str),
    /// A parameter that must not be negative is negative (the field's name).
    Negative(&'static str),
    /// `mu_kinetic > mu_static`.
    KineticAboveStatic,
    /// A finger starts beyond an end of the rod.
    FingerOutsideRod,
    /// Finger 1 does not start left of finger 2 by more than the finger width.
    FingersCrossed,
    /// The initial state given to the scene holds a NaN or an infinity.
    NonFiniteState,
}

impl core::fmt::Display for ParamError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NonFinite(name) => write!(f, "parameter {name} is not finite"),
            Self::NotPositive(name) => write!(f, "parameter {name} must be positive"),
            Self::Negative(name) => write!(f, "parameter {name} must not be negative"),
            Self::KineticAboveStatic => f.write_str("mu_kinetic must not exceed mu_static"),
            Self::FingerOutsideRod => f.write_str("a finger starts outside the rod (|x| > L/2)"),
            Self::FingersCrossed => {
                f.write_str("finger 1 must start left of finger 2 by more than the finger width")
            }
            Self::NonFiniteState => f.write_str("the initial state is not finite"),
        }
    }
}

impl core::error::Error for ParamError {}

impl<T: Real> SceneParams<T> {
    /// The paper's scene: L = 1 m, t = 0.5 cm, m = 0.2 kg, fingers at -/+0.4 m, slow
    /// finger 0.1 m/s, mu_s = 0.6, mu_k = 0.4, h = 1 ms.
    #[must_use]
    pub fn paper() -> Self {
        Self {
            rod_length: T::of(1.0),
            rod_thickness: T::of(0.005),
            rod_mass: T::of(0.2),
            gravity: T::of(9.81),
            finger1_x: T::of(-0.4),
            finger2_x: T::of(0.4),
            finger_width: T::of(0.01),
            finger_speed: T::of(0.1),
            mu_static: T::of(0.6),
            mu_kinetic: T::of(0.4),
            step: T::of(1e-3),
            stick_speed: T::of(1e-5),
            tilt_limit: T::of(0.35),
            drop_limit: T::of(0.02),
            hold_time: T::of(0.5),
            max_time: T::of(30.0),
        }
    }

    /// The rod's moment of inertia about its centre of mass, `m L^2 / 12`.
    #[must_use]
    pub fn inertia(&self) -> T {
        self.rod_mass * self.rod_length * self.rod_length / T::of(12.0)
    }

    /// Checks every parameter.
    ///
    /// # Errors
    /// The first problem found, as a [`ParamError`].
    pub fn validate(&self) -> Result<(), ParamError> {
        let fields: [(&'static str, T); 16] = [
            ("rod_length", self.rod_length),
            ("rod_thickness", self.rod_thickness),
            ("rod_mass", self.rod_mass),
            ("gravity", self.gravity),
            ("finger1_x", self.finger1_x),
            ("finger2_x", self.finger2_x),
            ("finger_width", self.finger_width),
            ("finger_speed", self.finger_speed),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("step", self.step),
            ("stick_speed", self.stick_speed),
            ("tilt_limit", self.tilt_limit),
            ("drop_limit", self.drop_limit),
            ("hold_time", self.hold_time),
            ("max_time", self.max_time),
        ];
        for (name, value) in fields {
            if !value.finite() {
                return Err(ParamError::NonFinite(name));
            }
        }
        let positive = [
            ("rod_length", self.rod_length),
            ("rod_thickness", self.rod_thickness),
            ("rod_mass", self.rod_mass),
            ("step", self.step),
            ("tilt_limit", self.tilt_limit),
            ("drop_limit", self.drop_limit),
            ("max_time", self.max_time),
        ];
        for (name, value) in positive {
            if value <= T::zero() {
                return Err(ParamError::NotPositive(name));
            }
        }
        let non_negative = [
            ("gravity", self.gravity),
            ("finger_width", self.finger_width),
            ("finger_speed", self.finger_speed),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic),
            ("stick_speed", self.stick_speed),
            ("hold_time", self.hold_time),
        ];
        for (name, value) in non_negative {
            if value < T::zero() {
                return Err(ParamError::Negative(name));
            }
        }
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        let half = self.rod_length / T::of(2.0);
        if self.finger1_x.abs_exact() > half || self.finger2_x.abs_exact() > half {
            return Err(ParamError::FingerOutsideRod);
        }
        if self.finger2_x - self.finger1_x <= self.finger_width {
            return Err(ParamError::FingersCrossed);
        }
        Ok(())
    }
}
