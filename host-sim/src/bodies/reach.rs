//! Where f32 follows f64 in the scenes of several bodies: the upper body's mass over the lower
//! one's, measured ([`F32_MASS_RATIO_REACH`], the catalogue's, which the page words too;
//! `docs/host-sim.md`, "Where f32 holds: several bodies"), the typed warning a run beyond it gets
//! in `summary.json` ([`BodiesWarning`], [`warnings`]), and the tests that run every edge again.
//!
//! A heavy body on a light one: the light body's velocity is the difference of impulses of the
//! heavy one's size, resolved to `eps` of them, more than the stick speed; the step reads a
//! contact's mode from the LCP's answer (a contact whose `sigma` is not basic has zero slip), not
//! from that velocity, so the edge is where the step itself gives out (it fails, or the block stays
//! behind), at any step and stick speed measured. A light body on a heavy one: the heavy body's rows
//! of the LCP are `m / M` of the light one's and its factored solve judges them on the light one's
//! scale, so the step fails or tips. Both edges are measured only.

use std::fmt;

use meterstick_catalogue::{Caution, cautions};
pub use meterstick_catalogue::{F32_MASS_RATIO_REACH, MassRatioReach};
use meterstick_core::scene::{Precision, SceneParams};
use serde::Serialize;

use crate::scenes::flag_of;

/// What a run of several bodies gets told about its precision, by cause (`summary.json`'s
/// `warnings`); worded as the page words it ([`meterstick_catalogue::Caution`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "cause", rename_all = "snake_case")]
pub enum BodiesWarning {
    /// The ratio is outside [`F32_MASS_RATIO_REACH`]'s measured reach (a light body on a heavy one
    /// below its lowest ratio, a heavy one on a light one above its highest): the outcome may
    /// depart from f64's (the step fails, the block tips, or stays behind).
    OutsideMeasured {
        /// The run's precision.
        precision: Precision,
        /// The upper body's mass flag and value (kg).
        upper: (String, f64),
        /// The lower body's.
        lower: (String, f64),
        /// `upper / lower`.
        ratio: f64,
        /// The measured reach, `upper / lower` from and to.
        reach: (f64, f64),
        /// The caution, for its words.
        #[serde(skip)]
        caution: Caution,
    },
}

impl fmt::Display for BodiesWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::OutsideMeasured { caution, .. } => write!(f, "warning: {}", caution.worded("--")),
        }
    }
}

/// The warnings a run of `spec` in `precision` gets (none in f64, none for scenes without a
/// measured reach): [`BodiesWarning::OutsideMeasured`] outside [`F32_MASS_RATIO_REACH`]'s reach.
#[must_use]
pub fn warnings(spec: &SceneParams, precision: Precision) -> Vec<BodiesWarning> {
    let [_, mass] = cautions(spec, precision);
    mass.into_iter()
        .filter_map(|caution| {
            let Caution::MassRatioOutsideReach { params, precision, reach, ratio } = caution else {
                return None;
            };
            let flag = |field: &str| {
                let value = params.get(field).unwrap_or(f64::NAN);
                let name = flag_of(reach.scene, field)
                    .map_or_else(|| field.to_string(), |f| format!("--{}", f.long));
                (name, value)
            };
            Some(BodiesWarning::OutsideMeasured {
                precision,
                upper: flag(reach.upper),
                lower: flag(reach.lower),
                ratio,
                reach: reach.ratios(),
                caution,
            })
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::bodies::run_core;
    use meterstick_core::scene::{OutcomeKind, SceneKind};

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

    /// f32 reaches f64's outcome to a 1e4 ratio both ways (issue #45): block-on-block and the
    /// tablecloth riding at 1e4 and 1e-4 end `Rode` in f32 as in f64, unwarned.
    #[test]
    fn f32_rides_as_f64_at_1e4_both_ways() {
        for (reach, k) in [(&F32_MASS_RATIO_REACH[0], 0.45), (&F32_MASS_RATIO_REACH[1], 0.55)] {
            for exponent in [4.0, -4.0] {
                let spec = spec_at(reach, exponent, k);
                let (f32, f64) = (outcome(&spec, Precision::F32), outcome(&spec, Precision::F64));
                assert_eq!(
                    (f32, f64),
                    (OutcomeKind::Rode, OutcomeKind::Rode),
                    "{} at 1e{exponent}",
                    reach.scene
                );
                assert!(warnings(&spec, Precision::F32).is_empty(), "{} at 1e{exponent}", reach.scene);
            }
        }
    }

    /// The reach is measured: at each edge of each scene's table row every band's f32 run ends as
    /// f64's, unwarned; half a decade (or the step) beyond each edge some band's does not, and the
    /// run is warned. When this fails the reach has moved: measure it again (`docs/host-sim.md`) and
    /// update the table.
    #[test]
    fn the_reach_is_where_f32_follows_f64() {
        for reach in &F32_MASS_RATIO_REACH {
            for edge in [reach.lowest, reach.highest] {
                for &(band, k) in reach.bands {
                    let spec = spec_at(reach, edge, k);
                    let (f32, f64) = (outcome(&spec, Precision::F32), outcome(&spec, Precision::F64));
                    assert_eq!(f32, f64, "{} {band} at 1e{edge}", reach.scene);
                    assert!(warnings(&spec, Precision::F32).is_empty(), "{} at 1e{edge}", reach.scene);
                }
            }
            for beyond in reach.departs_below.into_iter().chain([reach.departs_above]) {
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

    /// The upper edge is not the light body's round-off against the stick speed (`eps (m / M) g h`,
    /// 1.2e-4 m/s at 1e5 and h = 1e-3 s): block-on-block riding follows f64 at 1e5 and departs at
    /// 10^5.5 at h = 1e-4 s and at stick speeds 1e-6 and 1e-3 m/s as at the defaults.
    #[test]
    fn the_upper_edge_holds_at_other_steps_and_stick_speeds() {
        let reach = &F32_MASS_RATIO_REACH[0];
        for (field, value) in [("step", 1e-4), ("stick_speed", 1e-6), ("stick_speed", 1e-3)] {
            for (exponent, follows) in [(reach.highest, true), (reach.departs_above, false)] {
                let mut spec = spec_at(reach, exponent, reach.bands[0].1);
                assert!(spec.set(field, value));
                let same = outcome(&spec, Precision::F32) == outcome(&spec, Precision::F64);
                assert_eq!(same, follows, "{field} = {value} at 1e{exponent}");
            }
        }
    }

    /// The edges depend on the ratio alone: block-on-block riding at 1e3 kg on 1e9 kg departs and is
    /// warned as 1 kg on 1e6 kg is, at 1e3 kg on 1e7 kg it holds unwarned; 10 kg on 10^-4.5 kg
    /// departs and is warned as 10^5.5 kg on 1 kg is, 10 kg on 1e-4 kg holds.
    #[test]
    fn the_edges_depend_on_the_ratio_alone() {
        let reach = &F32_MASS_RATIO_REACH[0];
        let light = 10f64.powf(-4.5);
        for (m, big_m, follows) in
            [(1e3, 1e9, false), (1e3, 1e7, true), (10.0, light, false), (10.0, 1e-4, true)]
        {
            let mut spec = SceneParams::defaults(reach.scene);
            let g = spec.get("gravity").unwrap();
            let force = reach.bands[0].1 * (m + big_m) * g;
            assert!(spec.set(reach.upper, m) && spec.set(reach.lower, big_m) && spec.set("force", force));
            let same = outcome(&spec, Precision::F32) == outcome(&spec, Precision::F64);
            assert_eq!(same, follows, "{m} kg on {big_m} kg");
            assert_eq!(warnings(&spec, Precision::F32).is_empty(), follows, "{m} kg on {big_m} kg");
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
            matches!(w[..], [BodiesWarning::OutsideMeasured { ratio, reach, .. }]
                if (ratio - 1e6).abs() < 1e-6 && (reach.1 - 1e5).abs() < 1e-6),
            "{w:?}"
        );
        let text = w[0].to_string();
        assert!(
            text.starts_with(
                "warning: --mass 1000000 kg on --mass2 1 kg: mass ratio 1.00e6: outside 1.00e-4 .. 1.00e5"
            ),
            "{text}"
        );
        assert!(spec.set("top_mass", 1.0) && spec.set("bottom_mass", 1e6));
        let w = warnings(&spec, Precision::F32);
        assert!(matches!(w[..], [BodiesWarning::OutsideMeasured { .. }]), "{w:?}");
        assert!(
            w[0].to_string()
                .starts_with("warning: --mass 1 kg on --mass2 1000000 kg: mass ratio 1.00e-6: outside")
        );
    }
}
