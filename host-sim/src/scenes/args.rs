//! The scene options of a command ([`SceneArgs`]: `--scene` and every scene flag, generated from
//! the catalogue's [`FLAGS`]), `--precision` and `--layout`, and the runs they ask for
//! ([`SceneArgs::specs`]).

use anyhow::bail;
use clap::{Arg, ArgAction, ArgMatches, Command};
use meterstick_catalogue::{Catalogued as _, Refusal, Short};

use super::{
    FLAGS, Flag, Implementation, LcpLayout, MAX_STEPS, ParamsExt as _, Precision, SceneKind, SceneParams,
    flag_error,
};

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

/// Parses `"0.1"` or `"0.1,0.5"`, each value a number or one of the words flag `long` takes
/// (`meterstick_catalogue::WORDS`: `--shape ring`).
fn parse_list(long: &'static str, s: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|t| {
            let t = t.trim();
            meterstick_catalogue::word_value(long, t).map_or_else(|| t.parse::<f64>(), Ok).map_err(|_| {
                let words: Vec<&str> =
                    meterstick_catalogue::WORDS.iter().filter(|w| w.0 == long).map(|w| w.1).collect();
                if t.starts_with("--") {
                    format!("{t:?} is not a number: every flag needs a value")
                } else if words.is_empty() {
                    format!("{t:?} is not a number")
                } else {
                    format!("{t:?} is not a number nor {}", words.join(" nor "))
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
                    .value_parser(move |s: &str| parse_list(flag.long, s))
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
        if !kind.has_layout_choice() && self.layout_given {
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
