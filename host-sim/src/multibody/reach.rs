//! Where f32 follows f64 in the scenes of several bodies: the upper body's mass over the lower
//! one's, measured ([`F32_MASS_RATIO_REACH`], `docs/host-sim.md`, "Where f32 holds: several
//! bodies"), and the typed warning a run beyond it gets ([`BodiesWarning`], [`warnings`]).
//!
//! Two things run out, one on each side. A heavy body on a light one: the light body's velocity is
//! the difference of impulses of the heavy one's size (the pull, the floor's friction, the
//! interface's), resolved to `eps` of them, so its slip reads as more than the stick speed and
//! riding reads `Slid`. A light body on a heavy one: the heavy body's rows of the LCP are `m / M`
//! of the light one's and its factored solve judges them on the light one's scale, so the step
//! fails or tips. Both depend on the mass ratio alone at a scene's other parameters, so the
//! criterion is the ratio against the measured table.

use std::fmt;

use meterstick_core::scene::{Precision, SceneKind, SceneParams};
use serde::Serialize;

use crate::scenes::{flag_of, short_number};

/// One scene's measured f32 reach over `upper / lower` mass ratio: every band's f32 run ends as
/// f64's (which is the law's) for ratios in `10^lowest ..= 10^highest`, and one band departs at
/// `10^departs_below` and at `10^departs_above` (each mass 1 kg when the other is the ratio's,
/// the pull `k (m + M) g` of each band).
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
    /// The highest `log10` below `lowest` measured (half a decade below it), where a band departs.
    pub departs_below: f64,
    /// The lowest above `highest` measured, where a band departs.
    pub departs_above: f64,
}

impl MassRatioReach {
    /// The reach's ratios, `10^lowest` and `10^highest`.
    #[must_use]
    pub fn ratios(&self) -> (f64, f64) {
        (10f64.powf(self.lowest), 10f64.powf(self.highest))
    }
}

/// f32's measured reach in each scene of two bodies of different masses (the stack's blocks all
/// weigh the same): `docs/host-sim.md`, "Where f32 holds: several bodies", measured with
/// `host-sim scene` over `log10(upper / lower)` from -6 to 6 in steps of one (half a step at the
/// edges); the tests in this module run every edge again.
pub const F32_MASS_RATIO_REACH: [MassRatioReach; 3] = [
    MassRatioReach {
        scene: SceneKind::BlockOnBlock,
        upper: "top_mass",
        lower: "bottom_mass",
        bands: &[("riding", 0.45), ("sliding", 1.0)],
        lowest: -5.0,
        highest: 3.5,
        departs_below: -5.5,
        departs_above: 4.0,
    },
    MassRatioReach {
        scene: SceneKind::Tablecloth,
        upper: "block_mass",
        lower: "board_mass",
        bands: &[("riding", 0.55), ("pulled out", 2.9)],
        lowest: -5.0,
        highest: 3.5,
        departs_below: -5.5,
        departs_above: 4.0,
    },
    MassRatioReach {
        scene: SceneKind::DiscOnBoard,
        upper: "disc_mass",
        lower: "board_mass",
        bands: &[("rolling", 0.4)],
        lowest: -5.5,
        highest: 4.0,
        departs_below: -6.0,
        departs_above: 5.0,
    },
];

/// What a run of several bodies gets told about its precision, by cause.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "cause", rename_all = "snake_case")]
pub enum BodiesWarning {
    /// The upper body's mass over the lower one's is outside [`F32_MASS_RATIO_REACH`]: f32 was
    /// measured not to follow f64 there.
    MassRatio {
        /// The run's precision.
        precision: Precision,
        /// The upper body's mass flag (`--mass`) and value (kg).
        upper: (String, f64),
        /// The lower body's (`--mass2`).
        lower: (String, f64),
        /// `upper / lower`.
        ratio: f64,
        /// The measured reach, `upper / lower` from and to.
        reach: (f64, f64),
    },
}

impl fmt::Display for BodiesWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::MassRatio { precision, upper, lower, ratio, reach } => write!(
                f,
                "warning: {} {} on {} {}: mass ratio {} beyond what {} follows (measured: {} reaches f64's outcome \
                 for mass ratios {} .. {}, docs/host-sim.md, \"Where f32 holds: several bodies\"); use --precision \
                 f64 or masses closer together",
                upper.0,
                short_number(upper.1),
                lower.0,
                short_number(lower.1),
                crate::output::sci(*ratio),
                precision.name(),
                precision.name(),
                crate::output::sci(reach.0),
                crate::output::sci(reach.1),
            ),
        }
    }
}

/// The warnings a run of `spec` in `precision` gets (none in f64, none for scenes without a
/// measured reach).
#[must_use]
pub fn warnings(spec: &SceneParams, precision: Precision) -> Vec<BodiesWarning> {
    if precision != Precision::F32 {
        return Vec::new();
    }
    F32_MASS_RATIO_REACH
        .iter()
        .filter(|r| r.scene == spec.kind())
        .filter_map(|r| {
            let (m, big_m) = (spec.get(r.upper)?, spec.get(r.lower)?);
            let ratio = m / big_m;
            let reach = r.ratios();
            let flag = |field: &str| {
                flag_of(r.scene, field).map_or_else(|| field.to_string(), |f| format!("--{}", f.long))
            };
            // In decades, a rounding's worth of slack: the edges themselves were measured.
            let decades = ratio.log10();
            let within = decades >= r.lowest - 1e-9 && decades <= r.highest + 1e-9;
            (!within).then(|| BodiesWarning::MassRatio {
                precision,
                upper: (flag(r.upper), m),
                lower: (flag(r.lower), big_m),
                ratio,
                reach,
            })
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::multibody::run_core;
    use meterstick_core::scene::OutcomeKind;

    /// `reach`'s scene with `upper / lower = 10^exponent` (the other 1 kg), pulled at `k (m + M) g`.
    fn spec_at(reach: &MassRatioReach, exponent: f64, k: f64) -> SceneParams {
        let ratio = 10f64.powf(exponent);
        let (m, big_m) = if ratio >= 1.0 { (ratio, 1.0) } else { (1.0, 1.0 / ratio) };
        let mut spec = SceneParams::defaults(reach.scene);
        let g = spec.get("gravity").unwrap();
        assert!(
            spec.set(reach.upper, m)
                && spec.set(reach.lower, big_m)
                && spec.set("force", k * (m + big_m) * g)
        );
        spec
    }

    fn outcome(spec: &SceneParams, precision: Precision) -> OutcomeKind {
        run_core(spec, precision, false, None).unwrap().outcome.class
    }

    /// The table is measured: at each edge of each scene's reach every band's f32 run ends as f64's,
    /// and half a decade (or the step) beyond each edge some band's does not. When this fails the
    /// reach has moved: measure it again (`docs/host-sim.md`) and update the table.
    #[test]
    fn the_reach_is_where_f32_follows_f64() {
        for reach in &F32_MASS_RATIO_REACH {
            for edge in [reach.lowest, reach.highest] {
                for &(band, k) in reach.bands {
                    let spec = spec_at(reach, edge, k);
                    let (f32, f64) = (outcome(&spec, Precision::F32), outcome(&spec, Precision::F64));
                    assert_eq!(f32, f64, "{} {band} at 1e{edge}", reach.scene);
                    assert!(warnings(&spec, Precision::F32).is_empty());
                }
            }
            for beyond in [reach.departs_below, reach.departs_above] {
                let departs = reach.bands.iter().any(|&(_, k)| {
                    let spec = spec_at(reach, beyond, k);
                    outcome(&spec, Precision::F32) != outcome(&spec, Precision::F64)
                });
                assert!(departs, "{}: f32 follows f64 at 1e{beyond}: the reach grew", reach.scene);
                let spec = spec_at(reach, beyond, reach.bands[0].1);
                assert_eq!(warnings(&spec, Precision::F32).len(), 1, "{} at 1e{beyond}", reach.scene);
                assert!(warnings(&spec, Precision::F64).is_empty());
            }
        }
    }

    /// The warning names the flags and values typed, and the ratio; the defaults get none.
    #[test]
    fn the_warning_names_the_mass_flags() {
        for reach in &F32_MASS_RATIO_REACH {
            assert!(
                warnings(&SceneParams::defaults(reach.scene), Precision::F32).is_empty(),
                "{}",
                reach.scene
            );
        }
        let mut spec = SceneParams::defaults(SceneKind::BlockOnBlock);
        assert!(spec.set("top_mass", 1e6) && spec.set("bottom_mass", 1.0));
        let w = warnings(&spec, Precision::F32);
        assert!(
            matches!(w[..], [BodiesWarning::MassRatio { ratio, .. }] if (ratio - 1e6).abs() < 1e-6),
            "{w:?}"
        );
        let text = w[0].to_string();
        assert!(
            text.starts_with("warning: --mass 1000000 on --mass2 1: mass ratio 1.00e6 beyond what f32"),
            "{text}"
        );
    }
}
