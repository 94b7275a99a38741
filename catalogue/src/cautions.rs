//! [`Caution`]: what a run is told before it starts when its precision may not follow the
//! physics, worded as the user typed the flags ([`WordedCaution`]), so that `host-sim` and the
//! page say the same.
//!
//! Two causes, each measured where it is named:
//! - **friction beyond the precision** ([`meterstick_core::planar::friction_beyond_precision`]):
//!   sticking friction impulses up to `mu` times the normal ones cancel, and the net impulse they
//!   leave is resolved only to `mu eps` of itself; past `mu eps = 2^-9` the stick/slip decision is
//!   round-off (`docs/host-sim.md`, "Where f32 holds");
//! - **a mass ratio outside f32's measured reach** ([`F32_MASS_RATIO_REACH`], scenes of several
//!   bodies): a heavy body on a light one, the light body's velocity is the difference of impulses
//!   of the heavy one's size; a light body on a heavy one, the heavy body's rows of the LCP are
//!   `m / M` of the light one's. Each scene's edges are measured (`docs/host-sim.md`, "Where f32
//!   holds: several bodies"; `host-sim/src/bodies/reach.rs` runs every edge again).

use core::fmt;

use meterstick_core::planar::{friction_beyond_precision, friction_limit};
use meterstick_core::scene::{Precision, SceneKind, SceneParams};

use crate::refusals::Shown;
use crate::{Short, flag_of};

/// One scene's measured f32 reach over `upper / lower` mass ratio at its other defaults (h = 1e-3
/// s, stick speed 1e-5 m/s; the upper edge the same at h = 1e-4 and 1e-2 s and stick speeds 1e-6
/// .. 1e-3 m/s): every band's f32 run ends as f64's (which is the law's) for ratios in
/// `10^lowest ..= 10^highest`, and one band departs at `10^departs_below` and at
/// `10^departs_above` (each mass 1 kg when the other is the ratio's, the pull `k (m + M) g` of each
/// band).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassRatioReach {
    /// The scene.
    pub scene: SceneKind,
    /// The upper body's mass (the scene's field).
    pub upper: &'static str,
    /// The lower body's mass.
    pub lower: &'static str,
    /// The bands measured: a name and the pull over `(m + M) g`.
    pub bands: &'static [(&'static str, f64)],
    /// The lowest `log10(upper / lower)` where every band holds.
    pub lowest: f64,
    /// The highest.
    pub highest: f64,
    /// A `log10` below `lowest` (half a decade or a decade below it) where a band departs; `None`
    /// where none was measured to (`lowest` the lowest measured).
    pub departs_below: Option<f64>,
    /// Half a decade above `highest`, where a band departs.
    pub departs_above: f64,
}

impl MassRatioReach {
    /// The measured reach, `10^lowest` and `10^highest`.
    #[must_use]
    pub fn ratios(&self) -> (f64, f64) {
        (decades(self.lowest), decades(self.highest))
    }

    /// `true` when `upper / lower = ratio` is inside the reach (its edges, measured, included,
    /// with a rounding's worth of slack).
    #[must_use]
    pub fn holds(&self, ratio: f64) -> bool {
        let (low, high) = self.ratios();
        ratio >= low * (1.0 - 1e-9) && ratio <= high * (1.0 + 1e-9)
    }
}

/// `10^d` for the table's whole and half decades (`d = n` or `n + 1/2`; a half by `sqrt(10)`):
/// exact to round-off, without `libm::pow` in the page's modules.
fn decades(d: f64) -> f64 {
    let whole = libm::floor(d);
    let mut x = if d > whole { libm::sqrt(10.0) } else { 1.0 };
    let mut n = libm::fabs(whole);
    while n >= 1.0 {
        x = if whole < 0.0 { x / 10.0 } else { x * 10.0 };
        n -= 1.0;
    }
    x
}

/// f32's measured reach in each scene of two bodies of different masses (the stack's blocks all
/// weigh the same): measured with `host-sim scene` over `log10(upper / lower)` from -6 to 6 in
/// steps of one (half a step at the edges; disc-on-board down to -9).
#[cfg(feature = "multibody")]
pub const F32_MASS_RATIO_REACH: [MassRatioReach; 3] = [
    MassRatioReach {
        scene: SceneKind::BlockOnBlock,
        upper: "top_mass",
        lower: "bottom_mass",
        bands: &[("riding", 0.45), ("sliding", 1.0), ("pulled hard", 2.9)],
        lowest: -4.0,
        highest: 5.0,
        // At 10^-4.5 the hard pull departs or not with the masses' last digit.
        departs_below: Some(-5.0),
        departs_above: 5.5,
    },
    MassRatioReach {
        scene: SceneKind::Tablecloth,
        upper: "block_mass",
        lower: "board_mass",
        bands: &[("riding", 0.55), ("pulled out", 2.9)],
        lowest: -5.0,
        highest: 5.0,
        departs_below: Some(-5.5),
        departs_above: 5.5,
    },
    MassRatioReach {
        scene: SceneKind::DiscOnBoard,
        upper: "disc_mass",
        lower: "board_mass",
        bands: &[("rolling", 0.4)],
        lowest: -9.0,
        highest: 5.5,
        departs_below: None,
        departs_above: 6.0,
    },
];

/// No scene of several bodies in this build: no reach to hold a run to.
#[cfg(not(feature = "multibody"))]
pub const F32_MASS_RATIO_REACH: [MassRatioReach; 0] = [];

/// Why a run's precision may not follow the physics: told before the run, which runs all the same.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Caution {
    /// A friction coefficient beyond what `precision` resolves (`mu eps > 2^-9`).
    FrictionBeyondPrecision {
        /// The run's parameters.
        params: SceneParams,
        /// The run's precision.
        precision: Precision,
    },
    /// The scene's mass ratio is outside f32's measured reach.
    MassRatioOutsideReach {
        /// The run's parameters.
        params: SceneParams,
        /// The run's precision.
        precision: Precision,
        /// The scene's measured reach.
        reach: &'static MassRatioReach,
        /// `upper / lower`.
        ratio: f64,
    },
}

/// The cautions a run of `params` in `precision` gets, at most one of each cause (none in f64 for
/// the mass ratio, which was measured for f32).
#[must_use]
pub fn cautions(params: &SceneParams, precision: Precision) -> [Option<Caution>; 2] {
    let beyond: fn(f64) -> bool = match precision {
        Precision::F32 => friction_beyond_precision::<f32>,
        Precision::F64 => friction_beyond_precision::<f64>,
    };
    let friction = params
        .fields()
        .any(|(f, mu)| f.starts_with("mu_") && beyond(mu))
        .then_some(Caution::FrictionBeyondPrecision { params: *params, precision });
    let mass = (precision == Precision::F32)
        .then(|| {
            let reach = F32_MASS_RATIO_REACH.iter().find(|r| r.scene == params.kind())?;
            let ratio = params.get(reach.upper)? / params.get(reach.lower)?;
            (!reach.holds(ratio)).then_some(Caution::MassRatioOutsideReach {
                params: *params,
                precision,
                reach,
                ratio,
            })
        })
        .flatten();
    [friction, mass]
}

impl Caution {
    /// The caution in the user's words, flags written with `prefix` (`--` on the command line,
    /// nothing on the page).
    #[must_use]
    pub const fn worded(self, prefix: &'static str) -> WordedCaution {
        WordedCaution { caution: self, prefix }
    }
}

/// A [`Caution`] in the user's words ([`Caution::worded`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WordedCaution {
    caution: Caution,
    prefix: &'static str,
}

/// `x` as `1.00e6` (as `{:.2e}` writes it, whose code the page's modules would link only for
/// this: a mantissa to two decimals, which [`Short`]'s fixed notation links already).
struct Sci(f64);

impl fmt::Display for Sci {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() {
            return write!(f, "{x}");
        }
        // The decade by steps of ten (at most ~630 of them), not `log10`: no `libm::log10` or
        // `pow` in the page's modules for this.
        let (mut mantissa, mut exponent) = (x, 0_i32);
        while libm::fabs(mantissa) >= 10.0 {
            mantissa /= 10.0;
            exponent += 1;
        }
        while libm::fabs(mantissa) < 1.0 {
            mantissa *= 10.0;
            exponent -= 1;
        }
        // A mantissa that rounds to 10.00 moves a decade.
        if libm::fabs(mantissa) >= 9.995 {
            mantissa /= 10.0;
            exponent += 1;
        }
        write!(f, "{mantissa:.2}e{exponent}")
    }
}

impl fmt::Display for WordedCaution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.prefix;
        match self.caution {
            Caution::FrictionBeyondPrecision { params, precision } => {
                let (beyond, limit, eps): (fn(f64) -> bool, f64, f64) = match precision {
                    Precision::F32 => {
                        (friction_beyond_precision::<f32>, friction_limit::<f32>(), f64::from(f32::EPSILON))
                    }
                    Precision::F64 => {
                        (friction_beyond_precision::<f64>, friction_limit::<f64>(), f64::EPSILON)
                    }
                };
                let mut worst = 0.0_f64;
                let mut first = true;
                for (field, mu) in params.fields().filter(|&(f, mu)| f.starts_with("mu_") && beyond(mu)) {
                    if !first {
                        f.write_str(" and ")?;
                    }
                    first = false;
                    worst = worst.max(mu);
                    match flag_of(params.kind(), field) {
                        Some(flag) => write!(f, "{p}{} {}", flag.long, Short(mu))?,
                        None => write!(f, "{field} {}", Short(mu))?,
                    }
                }
                let precision = precision.name();
                write!(
                    f,
                    ": friction beyond what {precision} resolves (mu eps = {} > 2^-9: sticking friction \
                     impulses up to mu times the normal ones cancel, and the net impulse they leave is resolved \
                     only to mu eps of itself; {precision} resolves mu up to {}); use {p}precision f64 or a \
                     smaller friction coefficient",
                    Sci(worst * eps),
                    Short(limit)
                )
            }
            Caution::MassRatioOutsideReach { params, precision, reach, ratio } => {
                let (low, high) = reach.ratios();
                write!(
                    f,
                    "{} on {}: mass ratio {}: outside {} .. {}, the ratios {} was measured to follow f64 at \
                     (docs/host-sim.md, \"Where f32 holds: several bodies\"): the outcome may depart from \
                     f64's; use {p}precision f64 or masses closer together",
                    Shown(&params, reach.upper, p),
                    Shown(&params, reach.lower, p),
                    Sci(ratio),
                    Sci(low),
                    Sci(high),
                    precision.name(),
                )
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use std::string::ToString;

    use super::*;

    /// `Sci` writes what `{:.2e}` writes.
    #[test]
    fn sci_is_two_decimals_in_exponent_form() {
        for x in [
            1e6,
            1e-6,
            1e5,
            1e-4,
            1.19e-2,
            0.011_920_929,
            9.996e3,
            9.994e3,
            -3.2e-7,
            316_227.766,
            1.0,
            123.456,
        ] {
            assert_eq!(Sci(x).to_string(), std::format!("{x:.2e}"), "{x}");
        }
        assert_eq!(Sci(0.0).to_string(), "0");
    }

    #[test]
    fn friction_beyond_f32_is_worded_with_the_flags_typed() {
        let mut p = SceneParams::defaults(SceneKind::MeterStick);
        assert_eq!(cautions(&p, Precision::F32), [None, None]);
        assert!(p.set("mu_static", 1e5) && p.set("mu_kinetic", 1e5));
        let [friction, mass] = cautions(&p, Precision::F32);
        assert_eq!(mass, None);
        let c = friction.unwrap();
        assert!(matches!(c, Caution::FrictionBeyondPrecision { .. }));
        let text = c.worded("--").to_string();
        assert!(
            text.starts_with(
                "--mu-s 100000 and --mu-k 100000: friction beyond what f32 resolves (mu eps = 1.19e-2"
            ),
            "{text}"
        );
        assert!(text.ends_with("use --precision f64 or a smaller friction coefficient"), "{text}");
        assert!(c.worded("").to_string().starts_with("mu-s 100000 and mu-k 100000: friction"));
        assert_eq!(cautions(&p, Precision::F64), [None, None]);
    }

    #[cfg(feature = "multibody")]
    #[test]
    fn a_mass_ratio_outside_the_reach_is_worded_in_both_directions() {
        for reach in &F32_MASS_RATIO_REACH {
            let p = SceneParams::defaults(reach.scene);
            assert_eq!(cautions(&p, Precision::F32), [None, None], "{}", reach.scene);
            let ten = |d: f64| libm::pow(10.0, d);
            assert!(reach.holds(ten(reach.lowest)) && reach.holds(ten(reach.highest)), "{}", reach.scene);
            assert!(!reach.holds(ten(reach.departs_above)), "{}", reach.scene);
            if let Some(below) = reach.departs_below {
                assert!(!reach.holds(ten(below)), "{}", reach.scene);
            }
            let (low, high) = reach.ratios();
            assert!(libm::fabs(low / ten(reach.lowest) - 1.0) < 1e-14, "{}", reach.scene);
            assert!(libm::fabs(high / ten(reach.highest) - 1.0) < 1e-14, "{}", reach.scene);
        }
        let mut p = SceneParams::defaults(SceneKind::BlockOnBlock);
        assert!(p.set("top_mass", 1e6) && p.set("bottom_mass", 1.0));
        assert_eq!(cautions(&p, Precision::F64), [None, None]);
        let [friction, mass] = cautions(&p, Precision::F32);
        assert_eq!(friction, None);
        let c = mass.unwrap();
        assert_eq!(
            c.worded("--").to_string(),
            "--mass 1000000 kg on --mass2 1 kg: mass ratio 1.00e6: outside 1.00e-4 .. 1.00e5, the ratios f32 \
             was measured to follow f64 at (docs/host-sim.md, \"Where f32 holds: several bodies\"): the outcome \
             may depart from f64's; use --precision f64 or masses closer together"
        );
        assert!(p.set("top_mass", 1.0) && p.set("bottom_mass", 1e6));
        let [friction, mass] = cautions(&p, Precision::F32);
        assert_eq!(friction, None);
        let c = mass.unwrap();
        assert!(
            c.worded("")
                .to_string()
                .starts_with("mass 1 kg on mass2 1000000 kg: mass ratio 1.00e-6: outside")
        );
    }
}
