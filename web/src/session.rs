//! [`Session`]: what the page's exports operate on (one per wasm instance: the page's live run,
//! or a map worker's runs), in safe Rust; `exports` is the thin C-style layer over it.

use core::fmt::Write as _;

use meterstick_core::scene::Outcome;

use crate::config::{Config, ConfigError, LcpLayout, MAX_STEPS, Module, Precision, SceneParams, holds};
use crate::flags::{Catalogued as _, FLAGS, SceneKind};
use crate::sim::{MAX_CONTACTS, MODES, OUTCOMES, Rows, Sim};
use crate::text::{Text, json_num, json_str};

/// Rows one `ms_step` call may write (the trace buffer holds this many).
pub const TRACE_ROWS: usize = 2048;
/// Bytes of text one call may return (the description, an error, an outcome): twice the
/// description's length, which is longer in a build that names the scenes in three dimensions
/// (feature `sp`).
pub const TEXT_BYTES: usize = if cfg!(any(feature = "sp", feature = "st")) { 48 * 1024 } else { 32 * 1024 };

/// Why [`Session::create`] made no run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CreateError {
    /// The configuration was refused (its message names the flag).
    Config(ConfigError),
    /// The parameters passed validation but the core still refused them.
    Core(meterstick_core::ParamError),
    /// The scene runs in another module ([`crate::config::holds`]).
    OtherModule(SceneKind),
}

/// A configuration being edited, the parameters it resolved to and the run made from them.
#[derive(Debug, Clone)]
pub struct Session {
    config: Config,
    spec: Option<SceneParams>,
    precision: Precision,
    sim: Option<Sim>,
}

impl Default for Session {
    fn default() -> Self {
        Self::new()
    }
}

impl Session {
    /// The meter stick with nothing given, no run.
    #[must_use]
    pub const fn new() -> Self {
        Self { config: Config::new(SceneKind::MeterStick), spec: None, precision: Precision::F32, sim: None }
    }

    /// Starts a new configuration of `kind` (the core's defaults); drops the run.
    pub fn configure(&mut self, kind: SceneKind) {
        self.config = Config::new(kind);
        self.spec = None;
        self.sim = None;
    }

    /// Gives a flag (index in [`FLAGS`]) a value in its unit; `false` for an unknown flag.
    pub fn give(&mut self, flag: usize, value: f64) -> bool {
        self.config.give(flag, value)
    }

    /// The configuration so far.
    #[must_use]
    pub const fn config(&self) -> &Config {
        &self.config
    }

    /// Resolves the configuration and makes the run (at `t = 0`).
    ///
    /// # Errors
    /// The refusal, to be shown in the user's words (`Display`).
    #[allow(clippy::result_large_err)] // the refusal carries the parameters it words; no heap on wasm
    pub fn create(&mut self, precision: Precision, size: LcpLayout) -> Result<(), CreateError> {
        self.sim = None;
        self.spec = None;
        if !holds(self.config.kind) {
            return Err(CreateError::OtherModule(self.config.kind));
        }
        let spec = self.config.resolve(precision).map_err(CreateError::Config)?;
        self.spec = Some(spec);
        self.precision = precision;
        self.sim = Some(Sim::new(&spec, precision, size).map_err(CreateError::Core)?);
        Ok(())
    }

    /// The parameters of the run (after [`Self::create`] succeeded).
    #[must_use]
    pub const fn spec(&self) -> Option<&SceneParams> {
        self.spec.as_ref()
    }

    /// What the run is told before it starts ([`meterstick_catalogue::cautions`]: friction beyond
    /// the precision, a mass ratio outside f32's measured reach), as `host-sim` tells it; none
    /// without a run.
    pub fn cautions(&self) -> impl Iterator<Item = meterstick_catalogue::Caution> + use<> {
        let all = self.spec.map(|spec| meterstick_catalogue::cautions(&spec, self.precision));
        all.into_iter().flatten().flatten()
    }

    /// The run.
    #[must_use]
    pub const fn sim(&self) -> Option<&Sim> {
        self.sim.as_ref()
    }

    /// The run, to step.
    pub const fn sim_mut(&mut self) -> Option<&mut Sim> {
        self.sim.as_mut()
    }
}

impl core::fmt::Display for CreateError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Config(e) => write!(f, "{e}"),
            Self::Core(e) => write!(f, "{e}"),
            Self::OtherModule(kind) => {
                write!(f, "scene {kind} runs in {}, not in this module", Module::of(*kind).file())
            }
        }
    }
}

/// Writes the description the page builds its controls from, as JSON: each scene of the
/// catalogue, in its order, with its name, title, core fields and defaults, contacts (named; a row
/// has [`crate::sim::row_len`] numbers for them; a scene of several bodies has `"contacts":[]`, `"bodies":true`
/// and rows of [`crate::sim::BODIES_ROW`]: time ([`Rows`]) and each body's `x, y, theta`), measured quantities
/// (`summary.json`'s keys) and the outcomes it can end in; each flag's name, unit, help and field
/// per scene; the mode and outcome names; the limits; `holds`, the contact counts of the scenes
/// this module runs (0: the scenes of several bodies).
///
/// # Errors
/// Never in practice (a [`Text`] drops what does not fit and says so).
pub fn describe(out: &mut Text<'_>) -> core::fmt::Result {
    let list = |out: &mut Text<'_>, key: &str, names: &mut dyn Iterator<Item = &str>| -> core::fmt::Result {
        write!(out, ",\"{key}\":[")?;
        for (i, name) in names.enumerate() {
            out.write_str(if i > 0 { "," } else { "" })?;
            json_str(out, name)?;
        }
        out.write_char(']')
    };
    out.write_str("{\"version\":")?;
    json_str(out, crate::VERSION)?;
    out.write_str(",\"scenes\":[")?;
    for (i, kind) in SceneKind::ALL.into_iter().filter(|k| crate::config::on_page(*k)).enumerate() {
        let info = kind.info();
        out.write_str(if i > 0 { ",{\"name\":" } else { "{\"name\":" })?;
        json_str(out, kind.name())?;
        out.write_str(",\"title\":")?;
        json_str(out, info.title)?;
        list(out, "fields", &mut kind.field_names().iter().copied())?;
        out.write_str(",\"defaults\":[")?;
        let spec = SceneParams::defaults(kind);
        for j in 0..kind.field_names().len() {
            out.write_str(if j > 0 { "," } else { "" })?;
            json_num(out, spec.field(j).unwrap_or(f64::NAN))?;
        }
        out.write_char(']')?;
        list(out, "contacts", &mut info.contact_names.iter().copied())?;
        let rows = Rows::of(kind);
        if rows == Rows::Bodies {
            out.write_str(",\"bodies\":true")?;
        }
        #[cfg(any(feature = "sp", feature = "st"))]
        if rows == Rows::Spatial {
            out.write_str(",\"spatial\":true")?;
        }
        write!(out, ",\"row\":{}", rows.width())?;
        list(out, "measures", &mut info.measures.iter().copied())?;
        list(out, "ends", &mut info.outcomes.iter().map(|o| o.name()))?;
        list(out, "main_flags", &mut info.main_flags.iter().copied())?;
        out.write_char('}')?;
    }
    out.write_str("],\"flags\":[")?;
    for (i, flag) in FLAGS.iter().enumerate() {
        out.write_str(if i > 0 { ",{\"long\":" } else { "{\"long\":" })?;
        json_str(out, flag.long)?;
        out.write_str(",\"unit\":")?;
        json_str(out, flag.unit)?;
        out.write_str(",\"help\":")?;
        json_str(out, flag.help)?;
        out.write_str(",\"fields\":{")?;
        for (j, (kind, field)) in flag.fields.iter().filter(|(k, _)| crate::config::on_page(*k)).enumerate() {
            out.write_str(if j > 0 { "," } else { "" })?;
            json_str(out, kind.name())?;
            out.write_char(':')?;
            json_str(out, field)?;
        }
        out.write_str("}}")?;
    }
    out.write_char(']')?;
    list(out, "modes", &mut MODES.iter().copied())?;
    list(out, "outcomes", &mut OUTCOMES.iter().copied())?;
    out.write_str(",\"holds\":[")?;
    let mut first = true;
    for k in 0..=MAX_CONTACTS {
        if SceneKind::ALL.iter().any(|s| s.contacts() == k && holds(*s)) {
            write!(out, "{}{k}", if first { "" } else { "," })?;
            first = false;
        }
    }
    write!(out, "],\"trace_rows\":{TRACE_ROWS},\"max_steps\":{MAX_STEPS}}}")
}

/// Writes an outcome as the core displays it (`Failed (solver: ...)` with its cause).
///
/// # Errors
/// Never in practice.
pub fn outcome_text(out: &mut Text<'_>, outcome: Outcome) -> core::fmt::Result {
    write!(out, "{outcome}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{LcpLayout, Precision};
    use crate::text::StackStr;

    #[test]
    fn the_host_build_runs_every_scene_and_a_module_words_what_it_does_not_hold() {
        let mut s = Session::new();
        for kind in SceneKind::ALL.into_iter().filter(|k| crate::config::on_page(*k)) {
            assert!(holds(kind), "{kind}");
            s.configure(kind);
            assert!(s.create(Precision::F32, LcpLayout::Reduced).is_ok(), "{kind}");
            assert_eq!(s.sim().map(Sim::row_len), Some(Rows::of(kind).width()), "{kind}");
        }
        let e = CreateError::OtherModule(SceneKind::Cylinder);
        assert_eq!(
            StackStr::<128>::of(format_args!("{e}")).as_str(),
            "scene cylinder runs in meterstick_web_k1.wasm, not in this module"
        );
        let e = CreateError::OtherModule(SceneKind::Tablecloth);
        assert_eq!(
            StackStr::<128>::of(format_args!("{e}")).as_str(),
            "scene tablecloth runs in meterstick_web_mb.wasm, not in this module"
        );
    }
}
