//! A scene's configuration as the page gives it: the scene, the flags the user set (in their
//! units), the precision and the LCP size; [`Config::resolve`] turns it into the core's
//! parameters exactly as `host-sim scene` does (`SceneArgs::specs`: flags in table order, the
//! meter stick's time limit following the fingers' travel unless `duration` is given, validation
//! in f64 and in the run's precision, at most [`MAX_STEPS`] steps), and [`ConfigError`] words a
//! refusal as `host-sim` does, with the flag names as the page shows them (without `--`).

use core::fmt;

use meterstick_core::ParamError;
use meterstick_core::scene::{InclineParams, LadderParams, MeterStickParams};

use crate::flags::{FLAGS, SceneKind, flag_of};
use crate::text::StackStr;

/// Scalar precision of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Precision {
    /// `f32`, as on the microcontroller (the default).
    #[default]
    F32,
    /// `f64`.
    F64,
}

impl Precision {
    /// From the number of bits (32 or 64).
    #[must_use]
    pub const fn from_bits(bits: u32) -> Option<Self> {
        match bits {
            32 => Some(Self::F32),
            64 => Some(Self::F64),
            _ => None,
        }
    }
}

/// LCP size of a run: 6x6 (one friction direction per contact, checked, with the 8x8 fallback;
/// the firmware's) or 8x8 (the paper's form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LcpSize {
    /// 6x6 (the default).
    #[default]
    Reduced,
    /// 8x8.
    Full,
}

impl LcpSize {
    /// From `n` (6 or 8).
    #[must_use]
    pub const fn from_n(n: u32) -> Option<Self> {
        match n {
            6 => Some(Self::Reduced),
            8 => Some(Self::Full),
            _ => None,
        }
    }
}

/// The most steps one run may take (`host-sim`'s limit, 10^8).
pub const MAX_STEPS: f64 = 1e8;

/// A scene with its parameters in the core's units (SI, radians), f64 as given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spec {
    /// The meter stick.
    MeterStick(MeterStickParams<f64>),
    /// The block on an incline.
    Incline(InclineParams<f64>),
    /// The ladder.
    Ladder(LadderParams<f64>),
}

impl Spec {
    /// The scene with the core's defaults.
    #[must_use]
    pub fn defaults(kind: SceneKind) -> Self {
        match kind {
            SceneKind::MeterStick => Self::MeterStick(MeterStickParams::default()),
            SceneKind::Incline => Self::Incline(InclineParams::default()),
            SceneKind::Ladder => Self::Ladder(LadderParams::default()),
        }
    }

    /// Which scene.
    #[must_use]
    pub const fn kind(&self) -> SceneKind {
        match self {
            Self::MeterStick(_) => SceneKind::MeterStick,
            Self::Incline(_) => SceneKind::Incline,
            Self::Ladder(_) => SceneKind::Ladder,
        }
    }

    /// The value of a field (core name).
    #[must_use]
    pub fn get(&self, field: &str) -> Option<f64> {
        match self {
            Self::MeterStick(p) => p.get(field),
            Self::Incline(p) => p.get(field),
            Self::Ladder(p) => p.get(field),
        }
    }

    /// Sets a field (core name); `false` when the scene has none of that name.
    pub fn set(&mut self, field: &str, value: f64) -> bool {
        match self {
            Self::MeterStick(p) => p.set(field, value),
            Self::Incline(p) => p.set(field, value),
            Self::Ladder(p) => p.set(field, value),
        }
    }

    /// The `i`-th field's value, in the order of [`SceneKind::field_names`].
    #[must_use]
    pub fn field(&self, i: usize) -> Option<f64> {
        self.kind().field_names().get(i).and_then(|name| self.get(name))
    }

    /// The step `h` (s).
    #[must_use]
    pub fn step(&self) -> f64 {
        self.get("step").unwrap_or(f64::NAN)
    }

    /// The time limit (s).
    #[must_use]
    pub fn max_time(&self) -> f64 {
        self.get("max_time").unwrap_or(f64::NAN)
    }

    /// Checks the parameters in f64 and, for an f32 run, again after rounding to f32.
    ///
    /// # Errors
    /// The core's first complaint.
    pub fn validate(&self, precision: Precision) -> Result<(), ParamError> {
        let f32_too = precision == Precision::F32;
        match self {
            Self::MeterStick(p) => {
                p.validate()?;
                if f32_too {
                    p.cast::<f32>().validate()?;
                }
            }
            Self::Incline(p) => {
                p.validate()?;
                if f32_too {
                    p.cast::<f32>().validate()?;
                }
            }
            Self::Ladder(p) => {
                p.validate()?;
                if f32_too {
                    p.cast::<f32>().validate()?;
                }
            }
        }
        Ok(())
    }
}

/// Why a configuration was refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConfigError {
    /// A flag was given that does not apply to the scene (its index in [`FLAGS`]).
    NotApplicable {
        /// The scene.
        kind: SceneKind,
        /// The flag's index.
        flag: usize,
    },
    /// The core rejected a parameter.
    Invalid {
        /// The parameters as resolved.
        spec: Spec,
        /// The core's complaint.
        error: ParamError,
    },
    /// `h` and the time limit imply more than [`MAX_STEPS`] steps.
    TooManySteps {
        /// The parameters as resolved.
        spec: Spec,
        /// The steps they imply.
        steps: f64,
    },
}

impl ConfigError {
    /// The flag the user should change (its index in [`FLAGS`]), where one is to blame.
    #[must_use]
    pub fn flag(&self) -> Option<usize> {
        let index = |kind: SceneKind, field: &str| {
            flag_of(kind, field).and_then(|f| FLAGS.iter().position(|g| g.long == f.long))
        };
        match *self {
            Self::NotApplicable { flag, .. } => Some(flag),
            Self::Invalid { spec, error } => {
                let field = match error {
                    ParamError::KineticAboveStatic => Some("mu_kinetic"),
                    ParamError::FingerOutsideRod | ParamError::FingersCrossed => Some("finger1_x"),
                    other => other.field(),
                };
                field.and_then(|f| index(spec.kind(), f))
            }
            Self::TooManySteps { spec, .. } => index(spec.kind(), "step"),
        }
    }
}

/// A number as a person typed it, as `host-sim`'s `short_number` writes it: `{}` when that is
/// short; else 9 decimals with the trailing zeros dropped when that is the same number to 12
/// digits; else the shorter of `{}` and `{:e}`.
fn short_number(out: &mut impl fmt::Write, v: f64) -> fmt::Result {
    let plain = StackStr::<400>::of(format_args!("{v}"));
    if plain.as_str().len() <= 12 || !v.is_finite() {
        return out.write_str(plain.as_str());
    }
    let fixed = StackStr::<400>::of(format_args!("{v:.9}"));
    let trimmed = fixed.as_str().trim_end_matches('0').trim_end_matches('.');
    if trimmed.len() <= 12 && trimmed.parse::<f64>().is_ok_and(|t| libm::fabs(t - v) <= 1e-12 * libm::fabs(v))
    {
        return out.write_str(trimmed);
    }
    let exp = StackStr::<400>::of(format_args!("{v:e}"));
    out.write_str(if exp.as_str().len() < plain.as_str().len() { exp.as_str() } else { plain.as_str() })
}

/// A number written by [`short_number`].
struct Short(f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        short_number(f, self.0)
    }
}

/// A field as the user set it: `flag value unit` (e.g. `mu-k 0.7`, `angle 95 deg`).
struct Shown<'a>(&'a Spec, &'a str);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self(spec, field) = *self;
        match (flag_of(spec.kind(), field), spec.get(field)) {
            (Some(flag), Some(v)) => {
                write!(f, "{} ", flag.long)?;
                short_number(f, flag.from_core(v))?;
                if !flag.unit.is_empty() {
                    write!(f, " {}", flag.unit)?;
                }
                Ok(())
            }
            _ => f.write_str(field),
        }
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NotApplicable { kind, flag } => {
                let flag = &FLAGS[flag];
                write!(f, "{} does not apply to scene {} (it is a parameter of ", flag.long, kind.name())?;
                for (i, (k, _)) in flag.fields.iter().enumerate() {
                    write!(f, "{}{}", if i > 0 { ", " } else { "" }, k.name())?;
                }
                f.write_str(")")
            }
            Self::Invalid { spec, error } => {
                let show = |field| Shown(&spec, field);
                match error {
                    ParamError::NonFinite(x) => write!(f, "{}: not a finite number", show(x)),
                    ParamError::NotPositive(x) => write!(f, "{}: must be greater than 0", show(x)),
                    ParamError::Negative(x) => write!(f, "{}: must not be negative", show(x)),
                    ParamError::OutOfRange(x) => {
                        let range = match (spec.kind(), x) {
                            (SceneKind::Incline, "angle") => "0 <= angle < 90 deg",
                            (SceneKind::Ladder, "angle") => "0 < angle < 90 deg",
                            _ => "its documented range",
                        };
                        write!(f, "{}: out of range ({range})", show(x))
                    }
                    ParamError::KineticAboveStatic => {
                        write!(f, "{} must not exceed {}", show("mu_kinetic"), show("mu_static"))
                    }
                    ParamError::FingerOutsideRod => write!(
                        f,
                        "a finger starts beyond an end of the rod: {} and {} must be within {} / 2",
                        show("finger1_x"),
                        show("finger2_x"),
                        show("rod_length")
                    ),
                    ParamError::FingersCrossed => write!(
                        f,
                        "finger 1 must start left of finger 2 by more than the finger width: {} < {} - {}",
                        show("finger1_x"),
                        show("finger2_x"),
                        show("finger_width")
                    ),
                    other => write!(f, "{other}"),
                }?;
                // Parameters that pass in f64 failed in f32 (as `host-sim`'s `flag_error` says).
                if spec.validate(Precision::F64).is_ok() {
                    f.write_str(" as f32 (precision f32; f64 accepts it)")?;
                }
                Ok(())
            }
            Self::TooManySteps { spec, steps } => write!(
                f,
                "h {} s and duration {} s imply {steps:.3e} steps; a run may take at most {MAX_STEPS:e} \
                 (raise h or lower duration)",
                Short(spec.step()),
                Short(spec.max_time())
            ),
        }
    }
}

/// A scene and the flags the user gave, in their units (`deg` for angles); unset flags keep the
/// core's defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Config {
    /// The scene.
    pub kind: SceneKind,
    /// Each flag's value, by index in [`FLAGS`] (`None`: not given).
    pub given: [Option<f64>; FLAGS.len()],
}

impl Config {
    /// The scene with nothing given.
    #[must_use]
    pub const fn new(kind: SceneKind) -> Self {
        Self { kind, given: [None; FLAGS.len()] }
    }

    /// Gives flag `flag` (index in [`FLAGS`]) the value `value`; `false` for an unknown index.
    pub fn give(&mut self, flag: usize, value: f64) -> bool {
        self.given.get_mut(flag).map(|slot| *slot = Some(value)).is_some()
    }

    /// The core's parameters, as `host-sim scene` resolves the same flags.
    ///
    /// # Errors
    /// A flag that does not apply to the scene, an invalid value, or too many steps.
    #[allow(clippy::result_large_err)] // the refusal carries the parameters it words; no heap on wasm
    pub fn resolve(&self, precision: Precision) -> Result<Spec, ConfigError> {
        let mut spec = Spec::defaults(self.kind);
        for (i, (flag, value)) in FLAGS.iter().zip(self.given).enumerate() {
            let Some(value) = value else { continue };
            let Some(field) = flag.field(self.kind) else {
                return Err(ConfigError::NotApplicable { kind: self.kind, flag: i });
            };
            spec.set(field, flag.to_core(value));
        }
        let duration = FLAGS.iter().position(|f| f.long == "duration");
        if duration.and_then(|i| self.given[i]).is_none() {
            follow_travel_time(&mut spec);
        }
        spec.validate(precision).map_err(|error| ConfigError::Invalid { spec, error })?;
        let steps = libm::ceil(spec.max_time() / spec.step());
        if steps.is_nan() || steps > MAX_STEPS {
            return Err(ConfigError::TooManySteps { spec, steps });
        }
        Ok(spec)
    }
}

/// The meter stick's default time limit follows the fingers' travel: at least 30 s, and long
/// enough for the fingers to meet and the rod to hold (`2 x` travel time + hold time + 1 s), as in
/// `host-sim`.
fn follow_travel_time(spec: &mut Spec) {
    if let Spec::MeterStick(p) = spec {
        let closing = p.finger1_velocity - p.finger2_velocity;
        if closing > 0.0 {
            let travel = (p.finger2_x - p.finger1_x - p.finger_width).max(0.0) / closing;
            let wanted = 2.0 * travel + p.hold_time + 1.0;
            if wanted.is_finite() && wanted > p.max_time {
                p.max_time = wanted;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)] // exact: values copied or rounded once, not computed
    use super::*;
    use crate::flags::flag_index;

    fn config(kind: SceneKind, given: &[(&str, f64)]) -> Config {
        let mut c = Config::new(kind);
        for (long, v) in given {
            assert!(c.give(flag_index(long).unwrap(), *v), "{long}");
        }
        c
    }

    fn message(c: &Config) -> StackStr<1024> {
        let e = c.resolve(Precision::F32).unwrap_err();
        StackStr::of(format_args!("{e}"))
    }

    #[test]
    fn refusals_name_the_flag_value_and_rule() {
        let c = config(SceneKind::MeterStick, &[("mu-k", 0.7)]);
        assert_eq!(message(&c).as_str(), "mu-k 0.7 must not exceed mu-s 0.6");
        assert_eq!(c.resolve(Precision::F32).unwrap_err().flag(), flag_index("mu-k"));
        let c = config(SceneKind::Incline, &[("angle", 95.0)]);
        assert_eq!(message(&c).as_str(), "angle 95 deg: out of range (0 <= angle < 90 deg)");
        let c = config(SceneKind::MeterStick, &[("width", 0.1)]);
        assert_eq!(
            message(&c).as_str(),
            "width does not apply to scene meter-stick (it is a parameter of incline)"
        );
        let c = config(SceneKind::Ladder, &[("h", 1e-9)]);
        assert_eq!(
            message(&c).as_str(),
            "h 0.000000001 s and duration 3 s imply 3.000e9 steps; a run may take at most 1e8 \
             (raise h or lower duration)"
        );
    }

    #[test]
    fn the_meter_sticks_time_limit_follows_slow_fingers() {
        let slow = config(SceneKind::MeterStick, &[("speed", 0.01)]).resolve(Precision::F32).unwrap();
        assert_eq!(slow.max_time(), 2.0 * 0.79 / 0.01 + 0.5 + 1.0);
        let fixed = config(SceneKind::MeterStick, &[("speed", 0.01), ("duration", 5.0)])
            .resolve(Precision::F32)
            .unwrap();
        assert_eq!(fixed.max_time(), 5.0);
        let fast = config(SceneKind::MeterStick, &[("speed", 1.0)]).resolve(Precision::F32).unwrap();
        assert_eq!(fast.max_time(), 30.0);
    }

    #[test]
    fn a_value_is_checked_in_the_runs_precision() {
        // 1e39 is finite in f64 and infinite in f32.
        let c = config(SceneKind::MeterStick, &[("mass", 1e39)]);
        assert!(c.resolve(Precision::F64).is_ok());
        // Before #17 the value was shown as `mass 999999999999999939709166371603178586112 kg: not
        // a finite number`: 39 digits, and no word that only f32 refuses it.
        assert_eq!(
            message(&c).as_str(),
            "mass 1e39 kg: not a finite number as f32 (precision f32; f64 accepts it)"
        );
    }
}
