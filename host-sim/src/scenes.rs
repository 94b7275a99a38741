//! The scenes `host-sim` runs: which ([`SceneKind`]), with which parameters ([`SceneParams`]), in
//! which implementation ([`Implementation`]); and their command-line flags ([`SceneArgs`]).
//!
//! **Written once.** The scenes and their parameters are the core's ([`SceneKind`],
//! [`SceneParams`]), their flags and refusals the catalogue's (`catalogue/src/lib.rs`): [`FLAGS`]
//! (a flag and the field it sets in each scene it applies to), `Refusal`. The clap arguments are generated
//! from it; `--help` shows each scene's default, read from the core's `Default`; an invalid value
//! is reported with the flag the user typed ([`flag_error`]), in the words the page uses too.

use std::fmt;

use anyhow::bail;
use clap::{Arg, ArgAction, ArgMatches, Command};
use meterstick_core::ParamError;
use serde::Serialize;

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
    /// bodies: `crate::multibody::to_reference`).
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
            Self::BlockOnBlock(_) | Self::Tablecloth(_) | Self::Stack(_) | Self::DiscOnBoard(_) => {
                return None;
            }
        })
    }
}

/// `--precision`'s values: the core's [`Precision`]s by name (`f32`, `f64`).
#[must_use]
pub fn precision_parser() -> impl clap::builder::TypedValueParser<Value = Precision> {
    use clap::builder::{PossibleValuesParser, TypedValueParser as _};
    PossibleValuesParser::new(Precision::ALL.map(Precision::name))
        .map(|name| Precision::from_name(&name).unwrap_or_default())
}

/// `--layout`'s values: the core's [`LcpLayout`]s by name (`reduced`, `full`), each with the LCP
/// sizes it gives.
#[must_use]
pub fn layout_parser() -> impl clap::builder::TypedValueParser<Value = LcpLayout> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser as _};
    PossibleValuesParser::new([
        PossibleValue::new(LcpLayout::Reduced.name())
            .help("one friction direction per contact, checked, as the firmware: 6x6 for two contacts, 3x3 for one, 9x9 for three"),
        PossibleValue::new(LcpLayout::Full.name()).help("the paper's form: 8x8 for two contacts, 4x4 for one, 12x12 for three"),
    ])
    .map(|name| LcpLayout::from_name(&name).unwrap_or_default())
}

/// Who computed a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Implementation {
    /// `meterstick-core` in a precision and an LCP layout.
    Core(Precision, LcpLayout),
    /// The independent f64 reference (`crate::reference`, enumeration of the full form).
    Reference,
}

impl Implementation {
    /// The firmware's configuration: f32, reduced layout.
    pub const CORE_F32_REDUCED: Self = Self::Core(Precision::F32, LcpLayout::Reduced);
    /// Core, f32, full layout.
    pub const CORE_F32_FULL: Self = Self::Core(Precision::F32, LcpLayout::Full);
    /// Core, f64, full layout.
    pub const CORE_F64_FULL: Self = Self::Core(Precision::F64, LcpLayout::Full);

    /// The precision it computes in.
    #[must_use]
    pub const fn precision(self) -> Precision {
        match self {
            Self::Core(p, _) => p,
            Self::Reference => Precision::F64,
        }
    }
}

/// The label for a two-contact scene (the report's, the stress grid's columns); a run of any scene
/// is labelled by [`Implementation::of_scene`].
impl fmt::Display for Implementation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&ImplementationOf { implementation: *self, contacts: 2 }, f)
    }
}

impl Serialize for Implementation {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl Implementation {
    /// This implementation as it runs a scene of `kind`, whose contacts set its LCP's size.
    #[must_use]
    pub const fn of_scene(self, kind: SceneKind) -> ImplementationOf {
        ImplementationOf { implementation: self, contacts: kind.contacts() }
    }
}

/// An [`Implementation`] running a scene of `contacts` contacts: its label names the LCP's size,
/// `core f32 6x6` for a two-contact scene in the reduced layout, `core f32 3x3` for one contact,
/// `reference f64 8x8` (the reference solves the full form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ImplementationOf {
    /// Who computed the run.
    pub implementation: Implementation,
    /// The scene's contacts.
    pub contacts: usize,
}

impl fmt::Display for ImplementationOf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.implementation {
            // A scene of several bodies: its LCP's size is its own (`host-sim scene` says it).
            Implementation::Core(p, _) if self.contacts == 0 => write!(f, "core {}", p.name()),
            Implementation::Reference if self.contacts == 0 => f.write_str("reference f64"),
            Implementation::Core(p, layout) => {
                write!(f, "core {} {n}x{n}", p.name(), n = layout.size(self.contacts))
            }
            Implementation::Reference => {
                write!(f, "reference f64 {n}x{n}", n = LcpLayout::Full.size(self.contacts))
            }
        }
    }
}

impl Serialize for ImplementationOf {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
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
/// precision resolves ([`meterstick_core::planar::friction_beyond_precision`]), in the user's flags
/// (`--mu-s 1e5 and --mu-k 1e5: friction beyond what f32 resolves ...`); `None` when none is.
#[must_use]
pub fn friction_warning(spec: &SceneParams, precision: Precision) -> Option<String> {
    use meterstick_core::planar::{friction_beyond_precision, friction_limit};
    let (beyond, limit): (fn(f64) -> bool, f64) = match precision {
        Precision::F32 => (friction_beyond_precision::<f32>, friction_limit::<f32>()),
        Precision::F64 => (friction_beyond_precision::<f64>, friction_limit::<f64>()),
    };
    let eps = match precision {
        Precision::F32 => f64::from(f32::EPSILON),
        Precision::F64 => f64::EPSILON,
    };
    let beyond: Vec<(&str, f64)> =
        spec.fields().filter(|&(f, mu)| f.starts_with("mu_") && beyond(mu)).collect();
    let worst = beyond.iter().map(|&(_, mu)| mu).fold(0.0, f64::max);
    let flags: Vec<String> = beyond
        .iter()
        .map(|&(field, mu)| {
            flag_of(spec.kind(), field).map_or_else(
                || format!("{field} {}", short_number(mu)),
                |f| format!("--{} {}", f.long, short_number(mu)),
            )
        })
        .collect();
    let precision = precision.name();
    (!flags.is_empty()).then(|| {
        format!(
            "warning: {}: friction beyond what {precision} resolves (mu eps = {} > 2^-9: sticking friction \
             impulses up to mu times the normal ones cancel, and the net impulse they leave is resolved only to \
             mu eps of itself; {precision} resolves mu up to {}); use --precision f64 or a smaller friction \
             coefficient",
            flags.join(" and "),
            crate::output::sci(worst * eps),
            short_number(limit)
        )
    })
}

/// A number as a person typed it (the catalogue's [`Short`]): `{}` when that is short; else 9
/// decimals with the trailing zeros dropped when that is the same number to 12 digits; else the
/// shorter of `{}` and `{:e}` (`1e-30`, `1e39`, never a rounded `0`).
#[must_use]
pub fn short_number(v: f64) -> String {
    Short(v).to_string()
}

/// The scene options of a command: `--scene` and every scene flag, each taking a number or a
/// comma-separated list (at most one flag may list several values: one run each).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SceneArgs {
    /// `--scene` (default: meter-stick).
    pub scene: Option<SceneKind>,
    /// The flags given: `(flag, values in the flag's unit)`.
    pub given: Vec<(&'static Flag, Vec<f64>)>,
    /// `--precision`.
    pub precision: Precision,
    /// `--layout`.
    pub layout: LcpLayout,
    /// `--layout` was typed (not its default): refused for a scene of several bodies.
    pub layout_given: bool,
}

/// Parses `"0.1"` or `"0.1,0.5"`.
fn parse_list(s: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|t| {
            let t = t.trim();
            t.parse::<f64>().map_err(|_| {
                if t.starts_with("--") {
                    format!("{t:?} is not a number: every flag needs a value")
                } else {
                    format!("{t:?} is not a number")
                }
            })
        })
        .collect()
}

/// A flag's help line: what, unit, and each scene's default.
fn help_of(flag: &Flag) -> String {
    let defaults: Vec<String> = flag
        .fields
        .iter()
        .filter_map(|&(kind, field)| {
            SceneParams::defaults(kind).get(field).map(|v| format!("{kind} {}", Short(flag.from_core(v))))
        })
        .collect();
    let unit = if flag.unit.is_empty() { String::new() } else { format!(", {}", flag.unit) };
    format!("{}{unit} [default: {}]", flag.help, defaults.join("; "))
}

/// `--scene`'s values: the catalogue's names, each with its title.
fn scene_parser() -> impl clap::builder::TypedValueParser<Value = SceneKind> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser as _};
    PossibleValuesParser::new(SceneKind::ALL.map(|k| PossibleValue::new(k.name()).help(k.info().title)))
        .map(|name| SceneKind::from_name(&name).unwrap_or(SceneKind::MeterStick))
}

impl clap::Args for SceneArgs {
    fn augment_args(cmd: Command) -> Command {
        let mut cmd = cmd
            .arg(
                Arg::new("scene")
                    .long("scene")
                    .value_name("SCENE")
                    .value_parser(scene_parser())
                    .help("The scene (docs/scenes.md) [default: meter-stick]"),
            )
            .arg(
                Arg::new("precision")
                    .long("precision")
                    .value_parser(precision_parser())
                    .default_value(Precision::F32.name())
                    .help("Scalar precision of the core"),
            )
            .arg(
                Arg::new("layout")
                    .long("layout")
                    .value_parser(layout_parser())
                    .default_value(LcpLayout::Reduced.name())
                    .value_name("LAYOUT")
                    .help("LCP layout of the core (a scene of K contacts solves a 3K x 3K or 4K x 4K LCP)"),
            );
        for flag in FLAGS {
            let value_name = if flag.unit.is_empty() { "X" } else { flag.unit };
            cmd = cmd.arg(
                Arg::new(flag.long)
                    .long(flag.long)
                    .value_name(value_name)
                    .allow_hyphen_values(true)
                    .action(ArgAction::Set)
                    .value_parser(parse_list)
                    .help(help_of(flag)),
            );
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl clap::FromArgMatches for SceneArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = Self::default();
        args.update_from_arg_matches(m)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        if let Some(k) = m.get_one::<SceneKind>("scene") {
            self.scene = Some(*k);
        }
        if let Some(p) = m.get_one::<Precision>("precision") {
            self.precision = *p;
        }
        if let Some(l) = m.get_one::<LcpLayout>("layout") {
            self.layout = *l;
        }
        if m.value_source("layout") == Some(clap::parser::ValueSource::CommandLine) {
            self.layout_given = true;
        }
        for flag in FLAGS {
            if let Some(v) = m.get_one::<Vec<f64>>(flag.long) {
                self.given.retain(|(f, _)| f.long != flag.long);
                self.given.push((flag, v.clone()));
            }
        }
        Ok(())
    }
}

impl SceneArgs {
    /// The scene.
    #[must_use]
    pub fn kind(&self) -> SceneKind {
        self.scene.unwrap_or(SceneKind::MeterStick)
    }

    /// The core implementation these options ask for.
    #[must_use]
    pub const fn implementation(&self) -> Implementation {
        Implementation::Core(self.precision, self.layout)
    }

    /// The scenes to run, `(name, spec)`: the defaults with the flags applied, one per value of
    /// the one flag that lists several (`default_list` supplies that list when the flag is not
    /// given, e.g. the paper's speeds), each validated in f64 and in `--precision` before
    /// anything runs. Repeated values run once.
    ///
    /// # Errors
    /// A flag that does not apply to the scene, several listing flags, or an invalid value (in
    /// the user's words).
    pub fn specs(&self, default_list: Option<(&str, &[f64])>) -> anyhow::Result<Vec<(String, SceneParams)>> {
        let kind = self.kind();
        if kind.is_multibody() && self.layout_given {
            bail!(
                "--layout does not apply to --scene {kind}: a scene of several bodies solves the full form, \
                 sized by its active contacts"
            );
        }
        let mut base = SceneParams::defaults(kind);
        let mut list: Option<(&Flag, Vec<f64>)> = None;
        for (flag, values) in &self.given {
            let Some(field) = flag.field(kind) else {
                let flag = FLAGS.iter().position(|f| f.long == flag.long).unwrap_or(usize::MAX);
                bail!("{}", Refusal::NotApplicable { kind, flag }.worded("--"));
            };
            match values.as_slice() {
                [] => bail!("--{}: no value", flag.long),
                [one] => {
                    base.set(field, flag.to_core(*one));
                }
                many => {
                    if let Some((other, _)) = &list {
                        bail!(
                            "--{} and --{} both list several values: only one flag may",
                            other.long,
                            flag.long
                        );
                    }
                    let mut unique: Vec<f64> = Vec::new();
                    for v in many {
                        if !unique.iter().any(|u| u.to_bits() == v.to_bits()) {
                            unique.push(*v);
                        }
                    }
                    list = Some((flag, unique));
                }
            }
        }
        if list.is_none()
            && let Some((name, values)) = default_list
            && let Some(flag) = FLAGS.iter().find(|f| f.long == name)
            && flag.field(kind).is_some()
            && !self.given.iter().any(|(f, _)| f.long == name)
        {
            list = Some((flag, values.to_vec()));
        }
        let duration_given = self.given.iter().any(|(f, _)| f.long == "duration");
        let mut out = Vec::new();
        let runs: Vec<(String, SceneParams)> = match list {
            None => vec![(kind.name().to_string(), base)],
            Some((flag, values)) => values
                .iter()
                .map(|&v| {
                    let mut spec = base;
                    if let Some(field) = flag.field(kind) {
                        spec.set(field, flag.to_core(v));
                    }
                    (run_name(flag, v), spec)
                })
                .collect(),
        };
        for (name, mut spec) in runs {
            let followed = !duration_given && spec.follow_travel_time();
            spec.validate(self.precision).map_err(|e| anyhow::anyhow!("{}", flag_error(&spec, e)))?;
            let steps = spec.steps();
            if steps.is_nan() || steps > MAX_STEPS {
                let refusal = Refusal::TooManySteps { params: spec, steps, limit: MAX_STEPS, followed };
                bail!("{}", refusal.worded("--"));
            }
            out.push((name, spec));
        }
        Ok(out)
    }
}

/// The folder name of a run in a list: `v0.1` for `--speed 0.1`, `<flag><value>` otherwise; the
/// value in at most 12 characters (`{:e}` with 6 digits when `{}` is longer), so a name never
/// exceeds a file system's limits.
#[must_use]
pub fn run_name(flag: &Flag, value: f64) -> String {
    let prefix = if flag.long == "speed" { "v" } else { flag.long };
    let plain = format!("{value}");
    let v = if plain.len() <= 12 { plain } else { format!("{value:.6e}") };
    format!("{prefix}{v}")
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

    /// A run's label names the LCP its scene's contacts give: 3 per contact reduced, 4 full.
    #[test]
    fn labels_name_the_scenes_lcp_size() {
        let label = |i: Implementation, kind| i.of_scene(kind).to_string();
        assert_eq!(label(Implementation::CORE_F32_REDUCED, SceneKind::MeterStick), "core f32 6x6");
        assert_eq!(label(Implementation::CORE_F32_REDUCED, SceneKind::Cylinder), "core f32 3x3");
        assert_eq!(label(Implementation::CORE_F64_FULL, SceneKind::Painleve), "core f64 4x4");
        assert_eq!(label(Implementation::CORE_F32_FULL, SceneKind::ThreeFingers), "core f32 12x12");
        assert_eq!(label(Implementation::Reference, SceneKind::ThreeFingers), "reference f64 12x12");
        assert_eq!(
            label(Implementation::Reference, SceneKind::Ladder),
            Implementation::Reference.to_string()
        );
    }
}
