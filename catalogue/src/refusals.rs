//! [`Refusal`]: why a configuration was refused, worded as the user typed it ([`Worded`]).

use core::fmt::{self, Write as _};

use meterstick_core::ParamError;
use meterstick_core::scene::{SceneKind, SceneParams};

use crate::{Catalogued, FLAGS, flag_of};

/// The most steps one run may take: 10^8 (about 30 s of the core on a host); a step count beyond
/// it is refused before anything runs.
pub const MAX_STEPS: f64 = 1e8;

/// Why a configuration was refused, before anything ran.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Refusal {
    /// A flag was given that does not apply to the scene (its index in [`FLAGS`]).
    NotApplicable {
        /// The scene.
        kind: SceneKind,
        /// The flag's index.
        flag: usize,
    },
    /// The core rejected a parameter (the message says so when only f32 refuses it).
    Invalid {
        /// The parameters as resolved.
        params: SceneParams,
        /// The core's complaint.
        error: ParamError,
    },
    /// The scene is one of several bodies ([`SceneKind::is_multibody`]) and this front end
    /// (`driver`: `host-sim stress`, the page) does not run those yet.
    NotYet {
        /// The scene.
        kind: SceneKind,
        /// What does not run it, as the user knows it.
        driver: &'static str,
    },
    /// `h` and the time limit imply more than `limit` steps.
    TooManySteps {
        /// The parameters as resolved.
        params: SceneParams,
        /// The steps they imply.
        steps: f64,
        /// The most a run may take.
        limit: f64,
        /// The time limit is the meter stick's default raised to the fingers' travel time
        /// ([`SceneParams::follow_travel_time`]), not a duration the user gave.
        followed: bool,
    },
}

impl Refusal {
    /// The flag the user should change (its index in [`FLAGS`]), where one is to blame.
    #[must_use]
    pub fn flag(&self) -> Option<usize> {
        let index = |kind: SceneKind, field: &str| {
            flag_of(kind, field).and_then(|f| FLAGS.iter().position(|g| g.long == f.long))
        };
        match *self {
            Self::NotApplicable { flag, .. } => Some(flag),
            Self::Invalid { params, error } => {
                params.field_at_fault(error).and_then(|f| index(params.kind(), f))
            }
            Self::TooManySteps { params, .. } => index(params.kind(), "step"),
            Self::NotYet { .. } => None,
        }
    }

    /// The refusal in the user's words, flags written with `prefix` (`--` on the command line,
    /// nothing on the page): `--mu-k 0.7 must not exceed --mu-s 0.6`.
    #[must_use]
    pub const fn worded(self, prefix: &'static str) -> Worded {
        Worded { refusal: self, prefix }
    }
}

/// A [`Refusal`] in the user's words ([`Refusal::worded`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Worded {
    refusal: Refusal,
    prefix: &'static str,
}

/// A field as the user set it: `--flag value unit` (e.g. `--mu-k 0.7`, `--angle 95 deg`).
pub(crate) struct Shown<'a>(pub(crate) &'a SceneParams, pub(crate) &'a str, pub(crate) &'static str);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self(params, field, prefix) = *self;
        match (flag_of(params.kind(), field), params.get(field)) {
            (Some(flag), Some(v)) => {
                write!(f, "{prefix}{} {}", flag.long, Short(flag.from_core(v)))?;
                if !flag.unit.is_empty() {
                    write!(f, " {}", flag.unit)?;
                }
                Ok(())
            }
            _ => f.write_str(field),
        }
    }
}

impl fmt::Display for Worded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.prefix;
        match self.refusal {
            Refusal::NotApplicable { kind, flag } => {
                let Some(flag) = FLAGS.get(flag) else { return f.write_str("unknown flag") };
                write!(
                    f,
                    "{p}{} does not apply to {p}scene {} (it is a parameter of ",
                    flag.long,
                    kind.name()
                )?;
                for (i, (k, _)) in flag.fields.iter().enumerate() {
                    write!(f, "{}{}", if i > 0 { ", " } else { "" }, k.name())?;
                }
                f.write_str(")")
            }
            Refusal::Invalid { params, error } => {
                let show = |field| Shown(&params, field, p);
                match error {
                    ParamError::NonFinite(x) => write!(f, "{}: not a finite number", show(x)),
                    ParamError::NotPositive(x) => write!(f, "{}: must be greater than 0", show(x)),
                    ParamError::Negative(x) => write!(f, "{}: must not be negative", show(x)),
                    ParamError::OutOfRange(x) => {
                        write!(f, "{}: out of range ({})", show(x), params.kind().range_of(x))
                    }
                    ParamError::KineticAboveStatic => {
                        write!(f, "{} must not exceed {}", show("mu_kinetic"), show("mu_static"))
                    }
                    ParamError::FingerOutsideRod => write!(
                        f,
                        "a finger starts beyond an end of the rod: {} must be within {} / 2",
                        show(params.field_at_fault(error).unwrap_or("finger1_x")),
                        show("rod_length")
                    ),
                    ParamError::FingersCrossed if params.field_at_fault(error) == Some("finger3_x") => {
                        write!(
                            f,
                            "finger 3 must start right of finger 2: {} > {}",
                            show("finger3_x"),
                            show("finger2_x")
                        )
                    }
                    ParamError::FingersCrossed => write!(
                        f,
                        "finger 1 must start left of finger 2 by more than the finger width: {} < {} - {}",
                        show("finger1_x"),
                        show("finger2_x"),
                        show("finger_width")
                    ),
                    ParamError::InertiaOutOfRange { mass, size } => write!(
                        f,
                        "{} and {}: the moment of inertia they give is not a positive finite number",
                        show(mass),
                        show(size)
                    ),
                    other => write!(f, "{other}"),
                }?;
                // Parameters that pass in f64 failed in f32.
                if params.validate_as::<f64>().is_ok() {
                    write!(f, " as f32 ({p}precision f32; f64 accepts it)")?;
                }
                Ok(())
            }
            Refusal::NotYet { kind, driver } => write!(f, "{p}scene {}: not yet in {driver}", kind.name()),
            Refusal::TooManySteps { params, steps, limit, followed } => {
                write!(
                    f,
                    "{p}h {} s and {p}duration {} s imply {steps:.3e} steps; a run may take at most {limit:e} \
                     (raise {p}h or lower {p}duration)",
                    Short(params.step()),
                    Short(params.max_time())
                )?;
                if followed {
                    write!(f, "; the default {p}duration follows the fingers' travel time")?;
                }
                Ok(())
            }
        }
    }
}

/// A number as a person typed it: `{}` when that is short; else 9 decimals with the trailing zeros
/// dropped when that is the same number to 12 digits (so a round trip through radians shows `95`,
/// not `95.00000000000001`); else the shorter of `{}` and `{:e}` (`1e-30`, `1e39`, never a rounded
/// `0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Short(pub f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let plain = Buf::of(format_args!("{v}"));
        if plain.as_str().len() <= 12 || !v.is_finite() {
            return f.write_str(plain.as_str());
        }
        let fixed = Buf::of(format_args!("{v:.9}"));
        let trimmed = fixed.as_str().trim_end_matches('0').trim_end_matches('.');
        if trimmed.len() <= 12
            && trimmed.parse::<f64>().is_ok_and(|t| libm::fabs(t - v) <= 1e-12 * libm::fabs(v))
        {
            return f.write_str(trimmed);
        }
        let exp = Buf::of(format_args!("{v:e}"));
        f.write_str(if exp.as_str().len() < plain.as_str().len() { exp.as_str() } else { plain.as_str() })
    }
}

/// A number's text on the stack (an f64's `{}` is at most about 330 bytes).
struct Buf {
    bytes: [u8; 400],
    len: usize,
}

impl Buf {
    fn of(args: fmt::Arguments<'_>) -> Self {
        let mut b = Self { bytes: [0; 400], len: 0 };
        let _ = b.write_fmt(args);
        b
    }

    fn as_str(&self) -> &str {
        core::str::from_utf8(&self.bytes[..self.len]).unwrap_or("")
    }
}

impl fmt::Write for Buf {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let take = s.len().min(self.bytes.len() - self.len);
        self.bytes[self.len..self.len + take].copy_from_slice(&s.as_bytes()[..take]);
        self.len += take;
        Ok(())
    }
}
