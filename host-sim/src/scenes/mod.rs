//! The scenes `host-sim` runs: which ([`SceneKind`]), with which parameters ([`SceneParams`]), in
//! which implementation ([`Implementation`]); and their command-line flags ([`SceneArgs`]).
//!
//! **Written once.** The scenes and their parameters are the core's ([`SceneKind`],
//! [`SceneParams`]), their flags and refusals the catalogue's (`catalogue/src/lib.rs`): [`FLAGS`]
//! (a flag and the field it sets in each scene it applies to), `Refusal`. The clap arguments are generated
//! from it; `--help` shows each scene's default, read from the core's `Default`; an invalid value
//! is reported with the flag the user typed ([`flag_error`]), in the words the page uses too.
//!
//! * `implementation.rs`: who computes a run, and its label.
//! * `args.rs`: the command-line flags of a scene, and the runs they ask for.

mod args;
mod implementation;

use meterstick_core::ParamError;

pub use args::{SceneArgs, layout_parser, precision_parser, run_name};
pub use implementation::{Implementation, ImplementationOf};
pub use meterstick_catalogue::{Catalogued, FLAGS, Flag, INTRODUCTIONS, Introduction, MAX_STEPS, flag_of};
use meterstick_catalogue::{Refusal, Short};
pub use meterstick_core::scene::{LcpLayout, Precision, SceneKind};

/// A scene with its parameters (SI units, angles in radians, f64 as given; cast to the
/// implementation's precision when run): the catalogue's.
pub use meterstick_core::scene::SceneParams;

/// What `host-sim` adds to a [`SceneParams`]: validation in a [`Precision`] and the same scene for
/// the independent reference.
pub trait ParamsExt {
    /// Checks the parameters in f64 and in `precision` (a value may overflow f32, or round to
    /// an invalid one), before anything runs.
    ///
    /// # Errors
    /// The core's first complaint.
    fn validate(&self, precision: Precision) -> Result<(), ParamError>;

    /// The same scene for the independent reference (its own parameter types: data only);
    /// `None` for a scene the single-body reference does not implement (a scene of several
    /// bodies: `crate::bodies::to_reference`).
    fn to_reference(&self) -> Option<crate::reference::Spec>;
}

impl ParamsExt for SceneParams {
    fn validate(&self, precision: Precision) -> Result<(), ParamError> {
        match precision {
            Precision::F32 => self.validate_as::<f32>(),
            Precision::F64 => self.validate_as::<f64>(),
        }
    }

    fn to_reference(&self) -> Option<crate::reference::Spec> {
        use crate::reference as r;
        Some(match *self {
            Self::MeterStick(p) => r::Spec::MeterStick(r::MeterStick {
                rod_length: p.rod_length,
                rod_thickness: p.rod_thickness,
                rod_mass: p.rod_mass,
                gravity: p.gravity,
                finger1_x: p.finger1_x,
                finger2_x: p.finger2_x,
                finger1_y: p.finger1_y,
                finger2_y: p.finger2_y,
                finger1_velocity: p.finger1_velocity,
                finger2_velocity: p.finger2_velocity,
                finger_width: p.finger_width,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                step: p.step,
                stick_speed: p.stick_speed,
                tilt_limit: p.tilt_limit,
                drop_limit: p.drop_limit,
                hold_time: p.hold_time,
                max_time: p.max_time,
            }),
            Self::Incline(p) => r::Spec::Incline(r::Incline {
                width: p.width,
                height: p.height,
                mass: p.mass,
                gravity: p.gravity,
                angle: p.angle,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                step: p.step,
                stick_speed: p.stick_speed,
                max_time: p.max_time,
            }),
            Self::Ladder(p) => r::Spec::Ladder(r::Ladder {
                length: p.length,
                thickness: p.thickness,
                mass: p.mass,
                gravity: p.gravity,
                angle: p.angle,
                mu_floor: p.mu_floor,
                mu_wall: p.mu_wall,
                step: p.step,
                stick_speed: p.stick_speed,
                max_time: p.max_time,
            }),
            Self::ThreeFingers(p) => r::Spec::ThreeFingers(r::ThreeFingers {
                rod_length: p.rod_length,
                rod_thickness: p.rod_thickness,
                rod_mass: p.rod_mass,
                gravity: p.gravity,
                finger1_x: p.finger1_x,
                finger2_x: p.finger2_x,
                finger3_x: p.finger3_x,
                finger1_velocity: p.finger1_velocity,
                finger_width: p.finger_width,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                step: p.step,
                stick_speed: p.stick_speed,
                tilt_limit: p.tilt_limit,
                hold_time: p.hold_time,
                max_time: p.max_time,
            }),
            Self::Cylinder(p) => r::Spec::Cylinder(r::Cylinder {
                radius: p.radius,
                mass: p.mass,
                inertia_factor: p.inertia_factor,
                gravity: p.gravity,
                angle: p.angle,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                step: p.step,
                stick_speed: p.stick_speed,
                max_time: p.max_time,
            }),
            Self::Painleve(p) => r::Spec::Painleve(r::Painleve {
                length: p.length,
                thickness: p.thickness,
                mass: p.mass,
                gravity: p.gravity,
                angle: p.angle,
                speed: p.speed,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                step: p.step,
                stick_speed: p.stick_speed,
                max_time: p.max_time,
            }),
            Self::BlockOnBlock(_)
            | Self::Tablecloth(_)
            | Self::Stack(_)
            | Self::DiscOnBoard(_)
            | Self::Puck(_)
            | Self::Billiard(_)
            | Self::Curling(_)
            | Self::MeterStick3d(_)
            | Self::Stack3d(_) => return None,
        })
    }
}

/// A [`ParamError`] in the user's words: the flag, the value given (in the flag's unit) and the
/// allowed range; when the parameters pass in f64 the error came from f32, and the message says so
/// (`--mass 1e39 kg: not a finite number as f32 (--precision f32; f64 accepts it)`).
#[must_use]
pub fn flag_error(spec: &SceneParams, e: ParamError) -> String {
    Refusal::Invalid { params: *spec, error: e }.worded("--").to_string()
}

/// The warning a run of `spec` in `precision` gets when a friction coefficient is beyond what the
/// precision resolves ([`meterstick_catalogue::Caution::FrictionBeyondPrecision`], worded as the
/// page words it), in the user's flags (`--mu-s 1e5 and --mu-k 1e5: friction beyond what f32
/// resolves ...`); `None` when none is.
#[must_use]
pub fn friction_warning(spec: &SceneParams, precision: Precision) -> Option<String> {
    let [friction, _] = meterstick_catalogue::cautions(spec, precision);
    friction.map(|c| format!("warning: {}", c.worded("--")))
}

/// A number as a person typed it (the catalogue's [`Short`]): `{}` when that is short; else 9
/// decimals with the trailing zeros dropped when that is the same number to 12 digits; else the
/// shorter of `{}` and `{:e}` (`1e-30`, `1e39`, never a rounded `0`).
#[must_use]
pub fn short_number(v: f64) -> String {
    Short(v).to_string()
}
#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Numbers in messages as the user typed them: not `1e-30` and `1e-50` shown as `0` (9
    /// decimals, trailing zeros dropped), nor `1e39` as `999999999999999939709166371603178586112`.
    #[test]
    fn numbers_read_as_typed() {
        for (v, shown) in [
            (1e-30, "1e-30"),
            (1e-50, "1e-50"),
            (-1e-20, "-1e-20"),
            (1e39, "1e39"),
            (0.1, "0.1"),
            (1e-9, "0.000000001"),
            (95f64.to_radians().to_degrees(), "95"),
            (0.1 + 0.2, "0.3"),
            (-0.400_000_000_1, "-0.4000000001"),
            (123_456_789.123, "123456789.123"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            assert_eq!(short_number(v), shown, "{v:e}");
        }
    }

    /// A value only f32 refuses says so.
    #[test]
    fn an_f32_only_refusal_says_so() {
        let mut spec = SceneParams::defaults(SceneKind::MeterStick);
        spec.set("rod_mass", 1e39);
        let e = spec.validate(Precision::F32).unwrap_err();
        assert_eq!(
            flag_error(&spec, e),
            "--mass 1e39 kg: not a finite number as f32 (--precision f32; f64 accepts it)"
        );
        spec.set("rod_mass", -1.0);
        let e = spec.validate(Precision::F32).unwrap_err();
        assert_eq!(flag_error(&spec, e), "--mass -1 kg: must be greater than 0");
    }

    /// Friction beyond what f32 resolves gets a warning naming the flags and values the user
    /// typed, in f32 only, from `mu eps > 2^-9` (f32: mu > 16384); within it, none.
    #[test]
    fn friction_beyond_f32_is_named_in_the_users_flags() {
        let mut spec = SceneParams::defaults(SceneKind::MeterStick);
        assert!(spec.set("mu_static", 1e5) && spec.set("mu_kinetic", 1e4));
        let w = friction_warning(&spec, Precision::F32).unwrap();
        assert!(w.starts_with("warning: --mu-s 100000: friction beyond what f32 resolves"), "{w}");
        assert!(w.contains("mu eps = 1.19e-2") && w.contains("up to 16384"), "{w}");
        assert_eq!(friction_warning(&spec, Precision::F64), None);
        assert!(spec.set("mu_kinetic", 4e4));
        let w = friction_warning(&spec, Precision::F32).unwrap();
        assert!(w.starts_with("warning: --mu-s 100000 and --mu-k 40000: friction"), "{w}");
        assert!(spec.set("mu_static", 16384.0) && spec.set("mu_kinetic", 1e4));
        assert_eq!(friction_warning(&spec, Precision::F32), None);
        let mut ladder = SceneParams::defaults(SceneKind::Ladder);
        assert!(ladder.set("mu_wall", 1e6));
        let w = friction_warning(&ladder, Precision::F32).unwrap();
        assert!(w.starts_with("warning: --mu-wall 1000000: friction"), "{w}");
        // The round-off warning then blames the friction, not speed / (g h).
        let counters = crate::trajectory::SolverCounters { round_off_limited: 3, ..Default::default() };
        let r = counters.round_off_warning(10, true).unwrap();
        assert!(r.contains("the friction above") && !r.contains("speed / (g h)"), "{r}");
        assert!(counters.round_off_warning(10, false).unwrap().contains("speed / (g h)"));
    }
}
