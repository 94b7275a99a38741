//! Where f32 follows f64 in the scenes of several bodies: the upper body's mass over the lower
//! one's, measured ([`F32_MASS_RATIO_REACH`], `docs/host-sim.md`, "Where f32 holds: several
//! bodies"), and the typed warning a run beyond it gets ([`BodiesWarning`], [`warnings`]).
//!
//! Two things run out, one on each side. A heavy body on a light one: the light body's velocity is
//! the difference of impulses of the heavy one's size (the pull, the floor's friction, the
//! interface's), resolved to `eps` of them, so its slip reads as more than the stick speed and
//! riding reads `Slid`. A light body on a heavy one: the heavy body's rows of the LCP are `m / M`
//! of the light one's and its factored solve judges them on the light one's scale, so the step
//! fails or tips. The first is `eps (m / M) g h` against the stick speed (stated, and measured to
//! move with `h` and the stick speed); the second, and a heavy body's beyond what any stick speed
//! was measured to follow, the ratio against the measured table.

use std::fmt;

use meterstick_core::scene::{Precision, SceneKind, SceneParams};
use serde::Serialize;

use crate::scenes::{flag_of, short_number};

/// One scene's measured f32 reach over `upper / lower` mass ratio at its other defaults (h = 1e-3
/// s, stick speed 1e-5 m/s): every band's f32 run ends as f64's (which is the law's) for ratios in
/// `10^lowest ..= 10^highest`, and one band departs at `10^departs_below` and at
/// `10^departs_above` (each mass 1 kg when the other is the ratio's, the pull `k (m + M) g` of each
/// band). The upper edge is [`BodiesWarning::HeavyOnLight`]'s `eps (m / M) g h` against the stick
/// speed (it moves with `h`); the lower one is measured only.
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
    /// A `log10` below `lowest` (half a decade or a decade below it) where a band departs.
    pub departs_below: f64,
    /// The lowest above `highest` measured, where a band departs.
    pub departs_above: f64,
    /// The highest `log10(upper / lower)` where every band holds at a stick speed of 1e-3 m/s (so
    /// far from [`BodiesWarning::HeavyOnLight`]'s edge that another limit shows, at any `h`).
    pub highest_any: f64,
    /// Half a decade above it, where a band departs there.
    pub departs_any_above: f64,
}

impl MassRatioReach {
    /// The measured reach at any `h` and stick speed, `10^lowest` and `10^highest_any`.
    #[must_use]
    pub fn ratios(&self) -> (f64, f64) {
        (10f64.powf(self.lowest), 10f64.powf(self.highest_any))
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
        bands: &[("riding", 0.45), ("sliding", 1.0), ("pulled hard", 2.9)],
        lowest: -4.0,
        highest: 3.5,
        // At 10^-4.5 the hard pull departs or not with the masses' last digit.
        departs_below: -5.0,
        departs_above: 4.0,
        highest_any: 5.0,
        departs_any_above: 5.5,
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
        highest_any: 5.0,
        departs_any_above: 5.5,
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
        highest_any: 5.5,
        departs_any_above: 6.0,
    },
];

/// What a run of several bodies gets told about its precision, by cause.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "cause", rename_all = "snake_case")]
pub enum BodiesWarning {
    /// A heavy body on a light one: the light (lower) body's velocity is the difference of impulses
    /// of the heavy one's weight over a step, `m g h`, resolved to `eps` of them, `eps (m / M) g h`
    /// of its velocity; beyond the stick speed its sticking and sliding cannot be told apart
    /// (measured: riding reads `Slid` from there on, `docs/host-sim.md`).
    HeavyOnLight {
        /// The run's precision.
        precision: Precision,
        /// The upper body's mass flag (`--mass`) and value (kg).
        upper: (String, f64),
        /// The lower body's (`--mass2`).
        lower: (String, f64),
        /// `upper / lower`.
        ratio: f64,
        /// `eps (m / M) g h` (m/s).
        round_off_m_s: f64,
        /// The stick speed it exceeds (m/s).
        stick_speed_m_s: f64,
    },
    /// The ratio is outside [`F32_MASS_RATIO_REACH`]'s measured reach at any `h` and stick speed
    /// (a light body on a heavy one below its lowest ratio, a heavy one on a light one above its
    /// `highest_any`): the step fails or tips where f64 does not.
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
    },
}

impl fmt::Display for BodiesWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let masses = |upper: &(String, f64), lower: &(String, f64), ratio: f64| {
            format!(
                "{} {} on {} {}: mass ratio {}",
                upper.0,
                short_number(upper.1),
                lower.0,
                short_number(lower.1),
                crate::output::sci(ratio)
            )
        };
        match self {
            Self::HeavyOnLight { precision, upper, lower, ratio, round_off_m_s, stick_speed_m_s } => write!(
                f,
                "warning: {}: the light body's velocity resolved in {} only to eps (m / M) g h = {} m/s, more than \
                 the stick speed {} m/s: sticking reads as sliding (docs/host-sim.md, \"Where f32 holds: several \
                 bodies\"); use --precision f64, a smaller --h or masses closer together",
                masses(upper, lower, *ratio),
                precision.name(),
                crate::output::sci(*round_off_m_s),
                short_number(*stick_speed_m_s),
            ),
            Self::OutsideMeasured { precision, upper, lower, ratio, reach } => write!(
                f,
                "warning: {}: outside {} .. {}, the ratios {} was measured to follow f64 at (docs/host-sim.md, \
                 \"Where f32 holds: several bodies\"): the step may fail or tip; use --precision f64 or masses \
                 closer together",
                masses(upper, lower, *ratio),
                crate::output::sci(reach.0),
                crate::output::sci(reach.1),
                precision.name(),
            ),
        }
    }
}

/// The warnings a run of `spec` in `precision` gets (none in f64, none for scenes without a
/// measured reach): [`BodiesWarning::HeavyOnLight`] where `eps (m / M) g h` exceeds the stick
/// speed, [`BodiesWarning::OutsideMeasured`] outside [`F32_MASS_RATIO_REACH`]'s reach at any `h`.
#[must_use]
pub fn warnings(spec: &SceneParams, precision: Precision) -> Vec<BodiesWarning> {
    if precision != Precision::F32 {
        return Vec::new();
    }
    let eps = f64::from(f32::EPSILON);
    let mut out = Vec::new();
    for r in F32_MASS_RATIO_REACH.iter().filter(|r| r.scene == spec.kind()) {
        let (Some(m), Some(big_m), Some(g), Some(h), Some(stick)) = (
            spec.get(r.upper),
            spec.get(r.lower),
            spec.get("gravity"),
            spec.get("step"),
            spec.get("stick_speed"),
        ) else {
            continue;
        };
        let ratio = m / big_m;
        let flag = |field: &str| {
            flag_of(r.scene, field).map_or_else(|| field.to_string(), |f| format!("--{}", f.long))
        };
        let (upper, lower) = ((flag(r.upper), m), (flag(r.lower), big_m));
        let round_off = eps * ratio * g.abs() * h;
        if round_off > stick {
            out.push(BodiesWarning::HeavyOnLight {
                precision,
                upper: upper.clone(),
                lower: lower.clone(),
                ratio,
                round_off_m_s: round_off,
                stick_speed_m_s: stick,
            });
        }
        // In decades, a rounding's worth of slack: the edges themselves were measured.
        let decades = ratio.log10();
        if decades < r.lowest - 1e-9 || decades > r.highest_any + 1e-9 {
            out.push(BodiesWarning::OutsideMeasured { precision, upper, lower, ratio, reach: r.ratios() });
        }
    }
    out
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

    /// The reach is measured: at each edge of each scene's table row every band's f32 run ends as
    /// f64's, with no warning but a conservative [`BodiesWarning::HeavyOnLight`] (its round-off
    /// within twice the stick speed: the half decade the table is measured in); half a decade (or
    /// the step) beyond each edge some band's does not, and the run is warned. When this fails the
    /// reach has moved: measure it again (`docs/host-sim.md`) and update the table.
    #[test]
    fn the_reach_is_where_f32_follows_f64() {
        for reach in &F32_MASS_RATIO_REACH {
            for edge in [reach.lowest, reach.highest] {
                for &(band, k) in reach.bands {
                    let spec = spec_at(reach, edge, k);
                    let (f32, f64) = (outcome(&spec, Precision::F32), outcome(&spec, Precision::F64));
                    assert_eq!(f32, f64, "{} {band} at 1e{edge}", reach.scene);
                    for w in warnings(&spec, Precision::F32) {
                        assert!(
                            matches!(w, BodiesWarning::HeavyOnLight { round_off_m_s, stick_speed_m_s, .. }
                                if round_off_m_s <= 2.0 * stick_speed_m_s),
                            "{} at 1e{edge}: {w}",
                            reach.scene
                        );
                    }
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

    /// The heavy-on-light edge moves with the step as `eps (m / M) g h` against the stick speed
    /// says (8.6 / h in f32 at the defaults' stick speed, 1e-5 m/s): block-on-block riding holds
    /// unwarned half a decade below it at h = 1e-4 s and 1e-2 s and departs, warned, half a decade
    /// above.
    #[test]
    fn the_heavy_on_light_edge_follows_the_step() {
        let reach = &F32_MASS_RATIO_REACH[0];
        for (h, within, beyond) in [(1e-4, 4.5, 5.0), (1e-2, 2.5, 3.0)] {
            for (exponent, follows) in [(within, true), (beyond, false)] {
                let mut spec = spec_at(reach, exponent, reach.bands[0].1);
                assert!(spec.set("step", h));
                let same = outcome(&spec, Precision::F32) == outcome(&spec, Precision::F64);
                assert_eq!(same, follows, "h = {h} at 1e{exponent}");
                let w = warnings(&spec, Precision::F32);
                assert_eq!(w.is_empty(), follows, "h = {h} at 1e{exponent}: {w:?}");
                assert!(w.iter().all(|w| matches!(w, BodiesWarning::HeavyOnLight { .. })), "{w:?}");
            }
        }
    }

    /// Far from the round-off edge (stick speed 1e-3 m/s) another limit shows: every band holds
    /// unwarned at `highest_any` and some band departs, warned, half a decade above.
    #[test]
    fn beyond_the_round_off_edge_the_measured_cap_warns() {
        for reach in &F32_MASS_RATIO_REACH {
            for (exponent, follows) in [(reach.highest_any, true), (reach.departs_any_above, false)] {
                let specs: Vec<SceneParams> = reach
                    .bands
                    .iter()
                    .map(|&(_, k)| {
                        let mut spec = spec_at(reach, exponent, k);
                        assert!(spec.set("stick_speed", 1e-3));
                        spec
                    })
                    .collect();
                let all_same =
                    specs.iter().all(|spec| outcome(spec, Precision::F32) == outcome(spec, Precision::F64));
                assert_eq!(all_same, follows, "{} at 1e{exponent}", reach.scene);
                for spec in &specs {
                    let w = warnings(spec, Precision::F32);
                    assert_eq!(w.is_empty(), follows, "{} at 1e{exponent}: {w:?}", reach.scene);
                }
            }
        }
    }

    /// The edges depend on the ratio alone: block-on-block riding at 1e3 kg on 1e9 kg departs and is
    /// warned as 1 kg on 1e6 kg is, at 1e3 kg on 1e7 kg it holds unwarned; 10 kg on 1e-3 kg departs
    /// and is warned as 1e4 kg on 1 kg is.
    #[test]
    fn the_edges_depend_on_the_ratio_alone() {
        let reach = &F32_MASS_RATIO_REACH[0];
        for (m, big_m, follows) in [(1e3, 1e9, false), (1e3, 1e7, true), (10.0, 1e-3, false)] {
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
        // Both causes: the round-off, and beyond what was measured at any stick speed.
        let w = warnings(&spec, Precision::F32);
        assert!(
            matches!(w[..], [BodiesWarning::HeavyOnLight { ratio, .. }, BodiesWarning::OutsideMeasured { .. }]
                if (ratio - 1e6).abs() < 1e-6),
            "{w:?}"
        );
        let text = w[0].to_string();
        assert!(
            text.starts_with("warning: --mass 1000000 on --mass2 1: mass ratio 1.00e6: the light body's"),
            "{text}"
        );
        assert!(spec.set("top_mass", 1.0) && spec.set("bottom_mass", 1e6));
        let w = warnings(&spec, Precision::F32);
        assert!(matches!(w[..], [BodiesWarning::OutsideMeasured { .. }]), "{w:?}");
        assert!(
            w[0].to_string().starts_with("warning: --mass 1 on --mass2 1000000: mass ratio 1.00e-6: outside")
        );
    }
}
