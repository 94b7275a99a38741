//! The scenes `host-sim` runs: which ([`SceneKind`]), with which parameters ([`SceneSpec`]), in
//! which implementation ([`Implementation`]); and their command-line flags ([`SceneArgs`]).
//!
//! **One field list.** The parameters are the core's (`MeterStickParams`, `InclineParams`,
//! `LadderParams`: each declared once, with its defaults and checks). The flags are one table
//! ([`FLAGS`]) mapping a flag to the field it sets in each scene it applies to; `--help` shows each
//! scene's default, read from the core's `Default`; an invalid value is reported with the flag
//! the user typed ([`flag_error`]).

use std::fmt;

use anyhow::bail;
use clap::{Arg, ArgAction, ArgMatches, Command};
use meterstick_core::ParamError;
use meterstick_core::scene::{InclineParams, LadderParams, MeterStickParams};
use serde::Serialize;

use crate::lcp_io::Precision;

/// A scene `host-sim` can run (`docs/scenes.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SceneKind {
    /// The paper's rod on two fingers.
    MeterStick,
    /// A block on an inclined plane.
    Incline,
    /// A rod leaning against a wall.
    Ladder,
}

impl SceneKind {
    /// Every scene.
    pub const ALL: [Self; 3] = [Self::MeterStick, Self::Incline, Self::Ladder];

    /// The name on the command line, e.g. `meter-stick`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::MeterStick => "meter-stick",
            Self::Incline => "incline",
            Self::Ladder => "ladder",
        }
    }

    /// The core's field names of this scene's parameters.
    #[must_use]
    pub fn field_names(self) -> &'static [&'static str] {
        match self {
            Self::MeterStick => MeterStickParams::<f64>::NAMES,
            Self::Incline => InclineParams::<f64>::NAMES,
            Self::Ladder => LadderParams::<f64>::NAMES,
        }
    }
}

impl fmt::Display for SceneKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A scene with its parameters (SI units, angles in radians, f64 as given; cast to the
/// implementation's precision when run).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneSpec {
    /// The meter stick.
    MeterStick(MeterStickParams<f64>),
    /// The block on an incline.
    Incline(InclineParams<f64>),
    /// The ladder.
    Ladder(LadderParams<f64>),
}

impl SceneSpec {
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

    /// Sets a field (core name); `false` when the scene has no such field.
    pub fn set(&mut self, field: &str, value: f64) -> bool {
        match self {
            Self::MeterStick(p) => p.set(field, value),
            Self::Incline(p) => p.set(field, value),
            Self::Ladder(p) => p.set(field, value),
        }
    }

    /// Every field, `(core name, value)`, in declaration order.
    #[must_use]
    pub fn fields(&self) -> Vec<(&'static str, f64)> {
        match self {
            Self::MeterStick(p) => p.fields().iter().map(|f| (f.0, f.1)).collect(),
            Self::Incline(p) => p.fields().iter().map(|f| (f.0, f.1)).collect(),
            Self::Ladder(p) => p.fields().iter().map(|f| (f.0, f.1)).collect(),
        }
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

    /// Checks the parameters in f64 and in `precision` (a value may overflow f32, or round to
    /// an invalid one), before anything runs.
    ///
    /// # Errors
    /// The core's first complaint.
    pub fn validate(&self, precision: Precision) -> Result<(), ParamError> {
        match self {
            Self::MeterStick(p) => {
                p.validate()?;
                if precision == Precision::F32 {
                    p.cast::<f32>().validate()?;
                }
            }
            Self::Incline(p) => {
                p.validate()?;
                if precision == Precision::F32 {
                    p.cast::<f32>().validate()?;
                }
            }
            Self::Ladder(p) => {
                p.validate()?;
                if precision == Precision::F32 {
                    p.cast::<f32>().validate()?;
                }
            }
        }
        Ok(())
    }

    /// The same scene for the independent reference (its own parameter types: data only).
    #[must_use]
    pub fn to_reference(&self) -> crate::reference::Spec {
        use crate::reference as r;
        match *self {
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
        }
    }
}

/// The LCP size of the core: the reduced layout (6x6, as the firmware) or the full one (8x8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum, Serialize)]
pub enum LcpSize {
    /// 6x6: one friction direction per contact, checked, with the 8x8 fallback.
    #[default]
    #[value(name = "6")]
    Reduced,
    /// 8x8: the paper's form.
    #[value(name = "8")]
    Full,
}

impl LcpSize {
    /// 6 or 8.
    #[must_use]
    pub const fn n(self) -> usize {
        match self {
            Self::Reduced => 6,
            Self::Full => 8,
        }
    }
}

/// Who computed a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Implementation {
    /// `meterstick-core` in a precision and an LCP size.
    Core(Precision, LcpSize),
    /// The independent f64 reference (`crate::reference`, enumeration of the full form).
    Reference,
}

impl Implementation {
    /// The firmware's configuration.
    pub const CORE_F32_6: Self = Self::Core(Precision::F32, LcpSize::Reduced);
    /// Core, f32, 8x8.
    pub const CORE_F32_8: Self = Self::Core(Precision::F32, LcpSize::Full);
    /// Core, f64, 8x8.
    pub const CORE_F64_8: Self = Self::Core(Precision::F64, LcpSize::Full);

    /// The precision it computes in.
    #[must_use]
    pub const fn precision(self) -> Precision {
        match self {
            Self::Core(p, _) => p,
            Self::Reference => Precision::F64,
        }
    }
}

impl fmt::Display for Implementation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Core(p, n) => write!(f, "core {} {n}x{n}", p.name(), n = n.n()),
            Self::Reference => f.write_str("reference f64 8x8"),
        }
    }
}

impl Serialize for Implementation {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// One command-line flag of a scene parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Flag {
    /// The flag, without `--`.
    pub long: &'static str,
    /// Unit on the command line (`deg` is converted to the core's radians).
    pub unit: &'static str,
    /// What it is.
    pub help: &'static str,
    /// The field it sets in each scene it applies to.
    pub fields: &'static [(SceneKind, &'static str)],
}

impl Flag {
    /// The core field this flag sets in `kind`.
    #[must_use]
    pub fn field(&self, kind: SceneKind) -> Option<&'static str> {
        self.fields.iter().find(|(k, _)| *k == kind).map(|(_, f)| *f)
    }

    /// From the command line's unit to the core's.
    #[must_use]
    pub fn to_core(&self, value: f64) -> f64 {
        if self.unit == "deg" { value.to_radians() } else { value }
    }

    /// From the core's unit to the command line's.
    #[must_use]
    pub fn from_core(&self, value: f64) -> f64 {
        if self.unit == "deg" { value.to_degrees() } else { value }
    }
}

use SceneKind::{Incline as I, Ladder as L, MeterStick as M};

/// Every scene flag. A flag given for a scene it does not apply to is refused.
pub const FLAGS: &[Flag] = &[
    Flag {
        long: "speed",
        unit: "m/s",
        help: "Finger 1's velocity (+x: toward finger 2)",
        fields: &[(M, "finger1_velocity")],
    },
    Flag {
        long: "speed2",
        unit: "m/s",
        help: "Finger 2's velocity (-x: toward finger 1)",
        fields: &[(M, "finger2_velocity")],
    },
    Flag {
        long: "x1",
        unit: "m",
        help: "Start x of finger 1 (from the rod's centre of mass; within +-L/2)",
        fields: &[(M, "finger1_x")],
    },
    Flag {
        long: "x2",
        unit: "m",
        help: "Start x of finger 2 (> x1 + finger width)",
        fields: &[(M, "finger2_x")],
    },
    Flag { long: "y1", unit: "m", help: "Height of finger 1's tip", fields: &[(M, "finger1_y")] },
    Flag { long: "y2", unit: "m", help: "Height of finger 2's tip", fields: &[(M, "finger2_y")] },
    Flag {
        long: "finger-width",
        unit: "m",
        help: "Approaching fingers stop when their tips are this far apart (>= 0)",
        fields: &[(M, "finger_width")],
    },
    Flag {
        long: "mu-s",
        unit: "",
        help: "Static friction coefficient (>= 0)",
        fields: &[(M, "mu_static"), (I, "mu_static")],
    },
    Flag {
        long: "mu-k",
        unit: "",
        help: "Kinetic friction coefficient (0 <= mu-k <= mu-s)",
        fields: &[(M, "mu_kinetic"), (I, "mu_kinetic")],
    },
    Flag {
        long: "mu-floor",
        unit: "",
        help: "Friction coefficient at the floor, static and kinetic (>= 0)",
        fields: &[(L, "mu_floor")],
    },
    Flag {
        long: "mu-wall",
        unit: "",
        help: "Friction coefficient at the wall, static and kinetic (>= 0)",
        fields: &[(L, "mu_wall")],
    },
    Flag {
        long: "angle",
        unit: "deg",
        help: "Slope angle (incline, 0 <= a < 90) or start angle from the floor (ladder, 0 < a < 90)",
        fields: &[(I, "angle"), (L, "angle")],
    },
    Flag {
        long: "mass",
        unit: "kg",
        help: "Mass of the body (> 0)",
        fields: &[(M, "rod_mass"), (I, "mass"), (L, "mass")],
    },
    Flag { long: "length", unit: "m", help: "Rod length (> 0)", fields: &[(M, "rod_length"), (L, "length")] },
    Flag {
        long: "thickness",
        unit: "m",
        help: "Rod thickness (> 0)",
        fields: &[(M, "rod_thickness"), (L, "thickness")],
    },
    Flag { long: "width", unit: "m", help: "Block width along the slope (> 0)", fields: &[(I, "width")] },
    Flag { long: "height", unit: "m", help: "Block height (> 0)", fields: &[(I, "height")] },
    Flag {
        long: "gravity",
        unit: "m/s^2",
        help: "Gravity (>= 0)",
        fields: &[(M, "gravity"), (I, "gravity"), (L, "gravity")],
    },
    Flag { long: "h", unit: "s", help: "Time step (> 0)", fields: &[(M, "step"), (I, "step"), (L, "step")] },
    Flag {
        long: "duration",
        unit: "s",
        help: "Longest simulated time (> 0); a run still going then ends Unfinished (the meter stick's default grows with the fingers' travel time)",
        fields: &[(M, "max_time"), (I, "max_time"), (L, "max_time")],
    },
    Flag {
        long: "stick-speed",
        unit: "m/s",
        help: "A touching contact whose slip speed is at most this sticks (>= 0)",
        fields: &[(M, "stick_speed"), (I, "stick_speed"), (L, "stick_speed")],
    },
    Flag {
        long: "tilt-limit",
        unit: "rad",
        help: "The rod has fallen when it tilted more than this from its start angle (> 0)",
        fields: &[(M, "tilt_limit")],
    },
    Flag {
        long: "drop-limit",
        unit: "m",
        help: "The rod has fallen when its centre of mass dropped this far (> 0)",
        fields: &[(M, "drop_limit")],
    },
    Flag {
        long: "hold-time",
        unit: "s",
        help: "After the fingers meet, the rod must stay on them this long to balance (>= 0)",
        fields: &[(M, "hold_time")],
    },
];

/// The flag that sets `field` in `kind`.
#[must_use]
pub fn flag_of(kind: SceneKind, field: &str) -> Option<&'static Flag> {
    FLAGS.iter().find(|f| f.field(kind) == Some(field))
}

/// A [`ParamError`] in the user's words: the flag, the value given (in the flag's unit) and the
/// allowed range; when the parameters pass in f64 the error came from f32, and the message says so
/// (`--mass 1e39 kg: not a finite number as f32 (--precision f32; f64 accepts it)`).
#[must_use]
pub fn flag_error(spec: &SceneSpec, e: ParamError) -> String {
    let text = flag_error_text(spec, e);
    if spec.validate(Precision::F64).is_ok() {
        format!("{text} as f32 (--precision f32; f64 accepts it)")
    } else {
        text
    }
}

fn flag_error_text(spec: &SceneSpec, e: ParamError) -> String {
    let kind = spec.kind();
    let show = |field: &str| match (flag_of(kind, field), spec.get(field)) {
        (Some(flag), Some(v)) => {
            let unit = if flag.unit.is_empty() { String::new() } else { format!(" {}", flag.unit) };
            format!("--{} {}{unit}", flag.long, short_number(flag.from_core(v)))
        }
        _ => field.to_string(),
    };
    match e {
        ParamError::NonFinite(f) => format!("{}: not a finite number", show(f)),
        ParamError::NotPositive(f) => format!("{}: must be greater than 0", show(f)),
        ParamError::Negative(f) => format!("{}: must not be negative", show(f)),
        ParamError::OutOfRange(f) => {
            let range = match (kind, f) {
                (SceneKind::Incline, "angle") => "0 <= angle < 90 deg",
                (SceneKind::Ladder, "angle") => "0 < angle < 90 deg",
                _ => "its documented range",
            };
            format!("{}: out of range ({range})", show(f))
        }
        ParamError::KineticAboveStatic => {
            format!("{} must not exceed {}", show("mu_kinetic"), show("mu_static"))
        }
        ParamError::FingerOutsideRod => format!(
            "a finger starts beyond an end of the rod: {} and {} must be within {} / 2",
            show("finger1_x"),
            show("finger2_x"),
            show("rod_length")
        ),
        ParamError::FingersCrossed => format!(
            "finger 1 must start left of finger 2 by more than the finger width: {} < {} - {}",
            show("finger1_x"),
            show("finger2_x"),
            show("finger_width")
        ),
        other => other.to_string(),
    }
}

/// A number as a person typed it: `{}` when that is short; else 9 decimals with the trailing zeros
/// dropped when that is the same number to 12 digits (so a round trip through radians shows `95`,
/// not `95.00000000000001`); else the shorter of `{}` and `{:e}` (`1e-30`, `1e39`, never a rounded
/// `0`).
#[must_use]
pub fn short_number(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() <= 12 || !v.is_finite() {
        return plain;
    }
    let fixed = format!("{v:.9}");
    let trimmed = fixed.trim_end_matches('0').trim_end_matches('.');
    if trimmed.len() <= 12 && trimmed.parse::<f64>().is_ok_and(|t| (t - v).abs() <= 1e-12 * v.abs()) {
        return trimmed.to_string();
    }
    let exp = format!("{v:e}");
    if exp.len() < plain.len() { exp } else { plain }
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
    /// `--lcp-size`.
    pub lcp_size: LcpSize,
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
            SceneSpec::defaults(kind).get(field).map(|v| format!("{kind} {}", flag.from_core(v)))
        })
        .collect();
    let unit = if flag.unit.is_empty() { String::new() } else { format!(", {}", flag.unit) };
    format!("{}{unit} [default: {}]", flag.help, defaults.join("; "))
}

impl clap::Args for SceneArgs {
    fn augment_args(cmd: Command) -> Command {
        let mut cmd = cmd
            .arg(
                Arg::new("scene")
                    .long("scene")
                    .value_parser(clap::builder::EnumValueParser::<SceneKind>::new())
                    .help("The scene (docs/scenes.md) [default: meter-stick]"),
            )
            .arg(
                Arg::new("precision")
                    .long("precision")
                    .value_parser(clap::builder::EnumValueParser::<Precision>::new())
                    .default_value("f32")
                    .help("Scalar precision of the core"),
            )
            .arg(
                Arg::new("lcp-size")
                    .long("lcp-size")
                    .value_parser(clap::builder::EnumValueParser::<LcpSize>::new())
                    .default_value("6")
                    .help("LCP size of the core: 6 (one friction direction per contact, checked; as the firmware) or 8 (the paper's form)"),
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
        if let Some(n) = m.get_one::<LcpSize>("lcp-size") {
            self.lcp_size = *n;
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
        Implementation::Core(self.precision, self.lcp_size)
    }

    /// The scenes to run, `(name, spec)`: the defaults with the flags applied, one per value of
    /// the one flag that lists several (`default_list` supplies that list when the flag is not
    /// given, e.g. the paper's speeds), each validated in f64 and in `--precision` before
    /// anything runs. Repeated values run once.
    ///
    /// # Errors
    /// A flag that does not apply to the scene, several listing flags, or an invalid value (in
    /// the user's words).
    pub fn specs(&self, default_list: Option<(&str, &[f64])>) -> anyhow::Result<Vec<(String, SceneSpec)>> {
        let kind = self.kind();
        let mut base = SceneSpec::defaults(kind);
        let mut list: Option<(&Flag, Vec<f64>)> = None;
        for (flag, values) in &self.given {
            let Some(field) = flag.field(kind) else {
                let applies: Vec<&str> = flag.fields.iter().map(|(k, _)| k.name()).collect();
                bail!(
                    "--{} does not apply to --scene {kind} (it is a parameter of {})",
                    flag.long,
                    applies.join(", ")
                );
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
        let runs: Vec<(String, SceneSpec)> = match list {
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
            if !duration_given {
                follow_travel_time(&mut spec);
            }
            spec.validate(self.precision).map_err(|e| anyhow::anyhow!("{}", flag_error(&spec, e)))?;
            let steps = (spec.max_time() / spec.step()).ceil();
            if steps.is_nan() || steps > MAX_STEPS {
                bail!(
                    "--h {} s and --duration {} s imply {steps:.3e} steps; a run may take at most {MAX_STEPS:e} \
                     (raise --h or lower --duration)",
                    short_number(spec.step()),
                    short_number(spec.max_time())
                );
            }
            out.push((name, spec));
        }
        Ok(out)
    }
}

/// The most steps one run may take: 10^8 (about 30 s of the core on a host, an hour of the
/// reference); a step count beyond it is refused before anything runs.
pub const MAX_STEPS: f64 = 1e8;

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

/// The meter stick's default time limit follows the fingers' travel: at least 30 s, and long
/// enough for the fingers to meet and the rod to hold (`2 x` travel time + hold time), so that a
/// slow finger does not end "Unfinished" by default.
fn follow_travel_time(spec: &mut SceneSpec) {
    if let SceneSpec::MeterStick(p) = spec {
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
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Numbers in messages as the user typed them. Before #17 was finished, `1e-30` and `1e-50`
    /// were shown as `0` (9 decimals, trailing zeros dropped) and `1e39` as
    /// `999999999999999939709166371603178586112`.
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
        let mut spec = SceneSpec::defaults(SceneKind::MeterStick);
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
}
