//! Parameter sets and their validation: [`ParamError`], and the `params!` macro that declares a
//! parameter struct from one field list (name, default, check), so that its `Default`, its
//! validation, its field names and its conversion between precisions cannot drift apart.

use crate::real::Real;

/// Why a parameter set (or the set-up of a [`crate::planar::Stepper`]) was rejected. Variants that
/// concern one parameter carry the field's name as the struct spells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ParamError {
    /// A parameter is NaN or infinite.
    NonFinite(&'static str),
    /// A parameter that must be positive is zero or negative.
    NotPositive(&'static str),
    /// A parameter that must not be negative is negative.
    Negative(&'static str),
    /// A parameter is outside its range (e.g. an angle; the field's docs give the range).
    OutOfRange(&'static str),
    /// A kinetic friction coefficient exceeds the static one.
    KineticAboveStatic,
    /// A finger starts beyond an end of the rod.
    FingerOutsideRod,
    /// Finger 1 does not start left of finger 2 by more than the finger width.
    FingersCrossed,
    /// The initial state holds a NaN or an infinity.
    NonFiniteState,
    /// A support cannot carry its contact's feature (a line under a face, a point under a point):
    /// the contact's index.
    SupportMismatch(u8),
    /// The full layout lacks a variable of the layout each step solves.
    LayoutNotInFull,
    /// The body's moment of inertia, from the fields `mass` and `size`, is not a positive
    /// finite number in the scalar type (or `m / J` is not finite): a mass or size whose
    /// product underflows to 0 or overflows (f32 holds `1e-45 .. 3.4e38`).
    InertiaOutOfRange {
        /// The mass field.
        mass: &'static str,
        /// The size field the inertia grows with.
        size: &'static str,
    },
}

impl ParamError {
    /// The parameter's field name, for the variants that concern one parameter.
    #[must_use]
    pub const fn field(&self) -> Option<&'static str> {
        match *self {
            Self::NonFinite(f) | Self::NotPositive(f) | Self::Negative(f) | Self::OutOfRange(f) => Some(f),
            Self::InertiaOutOfRange { mass, .. } => Some(mass),
            _ => None,
        }
    }
}

impl core::fmt::Display for ParamError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NonFinite(name) => write!(f, "parameter {name} is not finite"),
            Self::NotPositive(name) => write!(f, "parameter {name} must be positive"),
            Self::Negative(name) => write!(f, "parameter {name} must not be negative"),
            Self::OutOfRange(name) => write!(f, "parameter {name} is out of its range"),
            Self::KineticAboveStatic => {
                f.write_str("the kinetic friction coefficient must not exceed the static one")
            }
            Self::FingerOutsideRod => f.write_str("a finger starts outside the rod (|x| > L/2)"),
            Self::FingersCrossed => {
                f.write_str("finger 1 must start left of finger 2 by more than the finger width")
            }
            Self::NonFiniteState => f.write_str("the initial state is not finite"),
            Self::SupportMismatch(i) => write!(f, "the support of contact {i} cannot carry its feature"),
            Self::LayoutNotInFull => f.write_str("the full layout lacks a variable of the solved layout"),
            Self::InertiaOutOfRange { mass, size } => write!(
                f,
                "the moment of inertia from parameters {mass} and {size} is not a positive finite number"
            ),
        }
    }
}

impl core::error::Error for ParamError {}

/// The rule every scene's run shares beyond its fields' own: at least one step within the
/// duration (`h <= max_time`; an `h` of 1e23 s was accepted and failed at the first step).
///
/// # Errors
/// [`ParamError::OutOfRange`]`("step")`.
#[inline]
pub(crate) fn check_step_within<T: Real>(step: T, max_time: T) -> Result<(), ParamError> {
    if step > max_time { Err(ParamError::OutOfRange("step")) } else { Ok(()) }
}

/// The check a parameter must pass (besides being finite, which all must).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check {
    /// Any finite value.
    Finite,
    /// `> 0`.
    Positive,
    /// `>= 0`.
    NonNegative,
}

/// Checks a field list: every value finite (first failure in field order), then each value against
/// its [`Check`] (again in field order).
///
/// # Errors
/// The first failure.
pub fn check_fields<T: Real>(fields: &[(&'static str, T, Check)]) -> Result<(), ParamError> {
    for &(name, value, _) in fields {
        if !value.finite() {
            return Err(ParamError::NonFinite(name));
        }
    }
    for &(name, value, check) in fields {
        match check {
            Check::Positive if value <= T::zero() => return Err(ParamError::NotPositive(name)),
            Check::NonNegative if value < T::zero() => return Err(ParamError::Negative(name)),
            _ => {}
        }
    }
    Ok(())
}

/// Declares a parameter struct generic over the scalar from one list of
/// `field: default, Check;` entries (defaults as `f64` literals), with `Default`, `fields()`,
/// `NAMES`, `set`/`get` by name, `cast::<U>()` and `check_fields()`.
macro_rules! params {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$fmeta:meta])* $field:ident : $default:expr, $check:ident; )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name<T> {
            $( $(#[$fmeta])* pub $field: T, )*
        }

        impl<T: $crate::Real> Default for $name<T> {
            fn default() -> Self {
                Self { $( $field: T::of($default), )* }
            }
        }

        impl<T: $crate::Real> $name<T> {
            /// The field names, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($field)),*];

            /// Every field's name, value and check, in declaration order.
            #[must_use]
            pub fn fields(&self) -> [(&'static str, T, $crate::params::Check); { [$(stringify!($field)),*].len() }] {
                [$((stringify!($field), self.$field, $crate::params::Check::$check)),*]
            }

            /// Sets the field called `name` (as [`Self::NAMES`] spells it); `false` when there is none.
            pub fn set(&mut self, name: &str, value: T) -> bool {
                match name {
                    $( stringify!($field) => { self.$field = value; true } )*
                    _ => false,
                }
            }

            /// The value of the field called `name`, if there is one.
            #[must_use]
            pub fn get(&self, name: &str) -> Option<T> {
                match name {
                    $( stringify!($field) => Some(self.$field), )*
                    _ => None,
                }
            }

            /// The same parameters in precision `U`, each value rounded to nearest.
            #[must_use]
            pub fn cast<U: $crate::Real>(&self) -> $name<U> {
                $name { $( $field: U::of(self.$field.as_f64()), )* }
            }

            /// Every field finite and passing its own check ([`$crate::params::check_fields`]).
            fn check_fields(&self) -> Result<(), $crate::ParamError> {
                $crate::params::check_fields(&self.fields())
            }
        }
    };
}

pub(crate) use params;
