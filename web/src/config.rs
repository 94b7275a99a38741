//! A scene's configuration as the page gives it: the scene, the flags the user set (in their
//! units), the precision and the LCP layout; [`Config::resolve`] turns it into the core's
//! parameters exactly as `host-sim scene` does (`SceneArgs::specs`: flags in table order, the
//! meter stick's time limit following the fingers' travel unless `duration` is given, validation
//! in f64 and in the run's precision, at most [`MAX_STEPS`] steps), and [`ConfigError`] words a
//! refusal as `host-sim` does (the catalogue's `Refusal`), with the flag names as the page shows
//! them (without `--`).

use core::fmt;

pub use meterstick_catalogue::MAX_STEPS;
use meterstick_catalogue::Refusal;
use meterstick_core::ParamError;

use crate::flags::{FLAGS, SceneKind};

/// Scalar precision and LCP layout of a run: the core's, as `host-sim`'s `--precision` and
/// `--layout`.
pub use meterstick_core::scene::{LcpLayout, Precision};

/// The layout the page's `lcp-size` names by its size for two contacts: 6 reduced, 8 full (a scene
/// of one or three contacts runs the same layout: 3 or 4, 9 or 12).
#[must_use]
pub const fn layout_of_page_size(n: u32) -> Option<LcpLayout> {
    match n {
        6 => Some(LcpLayout::Reduced),
        8 => Some(LcpLayout::Full),
        _ => None,
    }
}

/// A scene with its parameters in the core's units (SI, radians), f64 as given: the catalogue's.
pub use meterstick_core::scene::SceneParams;

/// A page module: the wasm file that runs a scene (`scripts/lib.sh` `build_web` builds each with
/// its cargo feature; the page loads [`Self::Two`] first and another when a scene of it is chosen).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Module {
    /// `meterstick_web_k1.wasm` (feature `k1`): the scenes of one contact.
    One,
    /// `meterstick_web.wasm` (feature `k2`): the scenes of two contacts.
    Two,
    /// `meterstick_web_k3.wasm` (feature `k3`): the scenes of three contacts.
    Three,
    /// `meterstick_web_mb.wasm` (feature `mb`): the scenes whose contacts come and go, none
    /// counted (the scenes of several bodies).
    Bodies,
    /// `meterstick_web_sp.wasm` (feature `sp`): the scenes in three dimensions of one body, in
    /// f32; in f64 `meterstick_web_sp64.wasm` (features `sp` and `sp64`, [`Self::file_for`]).
    Spatial,
    /// `meterstick_web_st.wasm` (feature `st`): the stack in three dimensions, in f32; in f64
    /// `meterstick_web_st64.wasm` (features `st` and `st64`).
    Stacked,
}

impl Module {
    /// The module that runs `kind`: a scene in three dimensions ([`SceneKind::is_spatial`]) its
    /// own, another by the contacts the catalogue counts for it (the page's `moduleUrl`,
    /// `web/page/core.js`; the page learns a scene in three dimensions' module from
    /// `pkg/intros.json`, `examples/intros.rs`).
    #[must_use]
    pub const fn of(kind: SceneKind) -> Self {
        #[cfg(feature = "st")]
        if matches!(kind, SceneKind::Stack3d) {
            return Self::Stacked;
        }
        if kind.is_spatial() {
            return Self::Spatial;
        }
        match kind.contacts() {
            0 => Self::Bodies,
            1 => Self::One,
            2 => Self::Two,
            _ => Self::Three,
        }
    }

    /// Its file in `web/page/pkg/`.
    #[must_use]
    pub const fn file(self) -> &'static str {
        match self {
            Self::One => "meterstick_web_k1.wasm",
            Self::Two => "meterstick_web.wasm",
            Self::Three => "meterstick_web_k3.wasm",
            Self::Bodies => "meterstick_web_mb.wasm",
            Self::Spatial => "meterstick_web_sp.wasm",
            Self::Stacked => "meterstick_web_st.wasm",
        }
    }

    /// Its file for a run in `precision`: the scenes in three dimensions have a module for each
    /// precision (each within the page's size budget), the other scenes one for both.
    #[must_use]
    pub const fn file_for(self, precision: Precision) -> &'static str {
        match (self, precision) {
            (Self::Spatial, Precision::F64) => "meterstick_web_sp64.wasm",
            (Self::Stacked, Precision::F64) => "meterstick_web_st64.wasm",
            _ => self.file(),
        }
    }

    /// `true` when this build runs its scenes (its cargo feature; the host build has them all).
    #[must_use]
    pub const fn built(self) -> bool {
        match self {
            Self::One => cfg!(feature = "k1"),
            Self::Two => cfg!(feature = "k2"),
            Self::Three => cfg!(feature = "k3"),
            Self::Bodies => cfg!(feature = "mb"),
            Self::Spatial => cfg!(feature = "sp"),
            Self::Stacked => cfg!(feature = "st"),
        }
    }
}

/// `true` when this build runs `kind` (its [`Module`]).
#[must_use]
pub const fn holds(kind: SceneKind) -> bool {
    on_page(kind) && Module::of(kind).built()
}

/// `true` for a scene this build describes to the page: every scene it names, those in three
/// dimensions with the feature `sp` only (a host build of the whole workspace names them without
/// running them; the planar page modules do not name them).
#[must_use]
pub const fn on_page(kind: SceneKind) -> bool {
    !kind.is_spatial() || cfg!(any(feature = "sp", feature = "st"))
}

/// Checks the parameters in f64 and, for an f32 run, again after rounding to f32.
///
/// # Errors
/// The core's first complaint.
pub fn validate(spec: &SceneParams, precision: Precision) -> Result<(), ParamError> {
    // Only the scenes this module holds (`holds`; the session refuses the others
    // before this): naming them keeps the other scenes' checks out of the module.
    if !holds(spec.kind()) {
        return Err(ParamError::OutOfRange("scene"));
    }
    match precision {
        Precision::F32 => spec.validate_as::<f32>(),
        Precision::F64 => spec.validate_as::<f64>(),
    }
}

/// Why a configuration was refused: the catalogue's [`Refusal`], worded without `--`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConfigError(pub Refusal);

impl ConfigError {
    /// The flag the user should change (its index in [`FLAGS`]), where one is to blame.
    #[must_use]
    pub fn flag(&self) -> Option<usize> {
        self.0.flag()
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0.worded(""))
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
    pub fn resolve(&self, precision: Precision) -> Result<SceneParams, ConfigError> {
        let mut spec = SceneParams::defaults(self.kind);
        for (i, (flag, value)) in FLAGS.iter().zip(self.given).enumerate() {
            let Some(value) = value else { continue };
            let Some(field) = flag.field(self.kind) else {
                return Err(ConfigError(Refusal::NotApplicable { kind: self.kind, flag: i }));
            };
            spec.set(field, flag.to_core(value));
        }
        let duration = FLAGS.iter().position(|f| f.long == "duration");
        let followed = duration.and_then(|i| self.given[i]).is_none() && spec.follow_travel_time();
        validate(&spec, precision).map_err(|error| ConfigError(Refusal::Invalid { params: spec, error }))?;
        let steps = spec.steps();
        if steps.is_nan() || steps > MAX_STEPS {
            return Err(ConfigError(Refusal::TooManySteps {
                params: spec,
                steps,
                limit: MAX_STEPS,
                followed,
            }));
        }
        Ok(spec)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)] // exact: values copied or rounded once, not computed
    use super::*;
    use crate::flags::flag_index;
    use crate::text::StackStr;

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
            "width does not apply to scene meter-stick (it is a parameter of incline, meter-stick-3d, block-on-block, tablecloth, stack-3d)"
        );
        let c = config(SceneKind::Ladder, &[("h", 1e-9)]);
        assert_eq!(
            message(&c).as_str(),
            "h 0.000000001 s and duration 3 s imply 3.000e9 steps; a run may take at most 1e8 \
             (raise h or lower duration)"
        );
        // A duration the user did not give, raised to the fingers' travel time, is said to be so.
        let c = config(SceneKind::MeterStick, &[("speed", 1e-5)]);
        assert!(
            message(&c).as_str().ends_with(
                "(raise h or lower duration); the default duration follows the fingers' travel time"
            ),
            "{}",
            message(&c).as_str()
        );
        // An inertia out of f32's range, from values each in range.
        let c = config(SceneKind::MeterStick, &[("mass", 1e-45)]);
        assert!(
            message(&c).as_str().contains("the moment of inertia they give is not a positive finite number"),
            "{}",
            message(&c).as_str()
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

    /// A scene in three dimensions runs in the module of its kind, one file a precision; the others
    /// in one file for both.
    #[test]
    fn a_scene_in_three_dimensions_has_a_module_a_precision() {
        assert_eq!(Module::of(SceneKind::Curling), Module::Spatial);
        assert_eq!(Module::Spatial.file_for(Precision::F32), "meterstick_web_sp.wasm");
        assert_eq!(Module::Spatial.file_for(Precision::F64), "meterstick_web_sp64.wasm");
        assert_eq!(Module::of(SceneKind::Stack), Module::Bodies);
        assert_eq!(Module::Bodies.file_for(Precision::F64), "meterstick_web_mb.wasm");
        assert!(holds(SceneKind::Puck), "the host build runs every scene");
        assert_eq!(Module::of(SceneKind::Stack3d), Module::Stacked);
        assert_eq!(Module::Stacked.file_for(Precision::F64), "meterstick_web_st64.wasm");
        assert!(holds(SceneKind::Stack3d), "the host build runs every scene");
    }

    #[test]
    fn a_value_is_checked_in_the_runs_precision() {
        // 1e39 is finite in f64 and infinite in f32.
        let c = config(SceneKind::MeterStick, &[("mass", 1e39)]);
        assert!(c.resolve(Precision::F64).is_ok());
        // Not `mass 999999999999999939709166371603178586112 kg: not a finite number`: 39 digits,
        // and no word that only f32 refuses it.
        assert_eq!(
            message(&c).as_str(),
            "mass 1e39 kg: not a finite number as f32 (precision f32; f64 accepts it)"
        );
    }
}
