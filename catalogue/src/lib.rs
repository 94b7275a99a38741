//! The scene catalogue's words: what the front ends (`host-sim`'s command line, the browser page)
//! say of the core's scenes, written once. `host-sim`'s clap arguments and `--help`
//! (`host-sim/src/scenes/args.rs`) and the page's controls and URL contract (`web/src/`, through
//! `ms_describe`) are generated from it, and both word a refusal with [`Worded`], so a page URL
//! `?scene=meter-stick&speed=0.1&x1=-0.35` and `host-sim scene --speed 0.1 --x1 -0.35` describe the
//! same run and are refused alike.
//!
//! * [`SCENES`] ([`Catalogued::info`]): each scene's title, contact names, the outcomes it can end
//!   in ([`OutcomeKind`](meterstick_core::scene::OutcomeKind), the one list of outcomes) and what its summary measures;
//! * [`INTRODUCTIONS`]: each scene's heading and one-paragraph introduction for a class (apart from
//!   [`SCENES`], so that a front end that does not show them links none of their text);
//! * [`FLAGS`]: each parameter flag once (name, unit, help), with the core field it sets in each
//!   scene it applies to; defaults are read from the core's `Default`, the checks are the core's
//!   `validate` ([`SceneInfo::ranges`] words a range the core checks beyond a sign);
//! * [`Refusal`]: why a configuration was refused, in the user's words;
//! * [`Caution`] ([`cautions`]): what a run is told when its precision may not follow the physics
//!   (friction beyond it; a mass ratio outside f32's measured reach), in the user's words.
//!
//! The scenes themselves, their names, contacts and parameters
//! ([`SceneKind`](meterstick_core::scene::SceneKind), [`SceneParams`](meterstick_core::scene::SceneParams))
//! and the physics checks ([`ParamError`](meterstick_core::ParamError)) are the core's; this crate is
//! for the front ends only (the firmware does not depend on it). No heap, no feature: data and a few lookups.
//!
//! **Adding a scene**: its [`SceneInfo`] in [`SCENES`], its [`Introduction`] in [`INTRODUCTIONS`]
//! and its field in each [`FLAGS`] entry it uses (or a new flag), besides the core's part
//! (`core/src/scene/kind.rs`).
#![no_std]

#[cfg(test)]
extern crate std;

mod cautions;
mod flags;
mod intros;
mod refusals;
mod scenes;

pub use cautions::{Caution, F32_MASS_RATIO_REACH, MassRatioReach, WordedCaution, cautions};
pub use flags::{FLAG_COUNT, FLAGS, Flag, WORDS, flag_index, flag_of, word_value};
pub use intros::{INTRODUCTIONS, Introduction};
pub use refusals::{MAX_STEPS, Refusal, Short, Worded};
pub use scenes::{Catalogued, SCENES, SceneInfo};

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use std::format;
    use std::string::ToString;

    use meterstick_core::scene::{SceneKind, SceneParams};

    use super::*;

    #[test]
    fn every_scene_is_in_its_place_and_every_flag_names_a_field() {
        for (i, kind) in SceneKind::ALL.into_iter().enumerate() {
            assert_eq!(kind.info().kind, kind);
            assert_eq!(kind.index(), i);
            // A scene in three dimensions is not a planar `Scene` (`contacts` 0): its names are its
            // view's contacts', the curling stone's one a point of its base at most.
            let contacts = match kind {
                #[cfg(feature = "spatial")]
                SceneKind::Curling => meterstick_core::scene::spatial::MAX_POINTS,
                #[cfg(feature = "spatial")]
                SceneKind::MeterStick3d => meterstick_core::scene::spatial::ROD_POINTS,
                // Its contacts come and go with the faces' overlaps, as the planar stack's.
                #[cfg(feature = "stack-3d")]
                SceneKind::Stack3d => 0,
                _ if kind.is_spatial() => 1,
                _ => kind.contacts(),
            };
            assert_eq!(kind.info().contact_names.len(), contacts, "{kind}");
            for long in kind.info().main_flags {
                let flag = FLAGS.iter().find(|f| f.long == *long);
                assert!(flag.is_some_and(|f| f.field(kind).is_some()), "{kind}: main flag --{long}");
            }
        }
        for flag in FLAGS {
            assert_eq!(flag_index(flag.long).map(|i| FLAGS[i].long), Some(flag.long));
            for &(kind, field) in flag.fields {
                assert!(kind.field_names().contains(&field), "--{} sets {field} in {kind}", flag.long);
            }
        }
        for (intro, kind) in INTRODUCTIONS.iter().zip(SceneKind::ALL) {
            assert_eq!(intro.kind, kind);
            assert!(!intro.heading.is_empty() && intro.intro.len() > 200, "{kind}");
        }
        // The flags of the scenes of several bodies or in three dimensions alone come last (the
        // page lists those before).
        let page_flag = |f: &Flag| f.fields.iter().any(|(k, _)| !k.is_multibody() && !k.is_spatial());
        let first_other = FLAGS.iter().position(|f| !page_flag(f)).unwrap_or(FLAGS.len());
        assert!(
            FLAGS[first_other..].iter().all(|f| !page_flag(f)),
            "a page flag after --{}",
            FLAGS[first_other].long
        );
        // Every field of every scene has its flag.
        for kind in SceneKind::ALL {
            for field in kind.field_names() {
                assert!(flag_of(kind, field).is_some(), "{kind} {field}");
            }
        }
    }

    #[test]
    fn refusals_are_worded_with_the_prefix_asked_for() {
        let mut p = SceneParams::defaults(SceneKind::MeterStick);
        assert!(p.set("mu_kinetic", 0.7));
        let e = p.validate_as::<f32>().unwrap_err();
        let r = Refusal::Invalid { params: p, error: e };
        assert_eq!(r.worded("--").to_string(), "--mu-k 0.7 must not exceed --mu-s 0.6");
        assert_eq!(r.worded("").to_string(), "mu-k 0.7 must not exceed mu-s 0.6");
        assert_eq!(r.flag(), flag_index("mu-k"));
        // The finger the user moved is the one named (it was --x1 and --x2 for any finger).
        let mut p = SceneParams::defaults(SceneKind::ThreeFingers);
        assert!(p.set("finger3_x", 0.6));
        let r = Refusal::Invalid { params: p, error: p.validate_as::<f64>().unwrap_err() };
        assert_eq!(
            r.worded("--").to_string(),
            "a finger starts beyond an end of the rod: --x3 0.6 m must be within --length 1 m / 2"
        );
        assert_eq!(r.flag(), flag_index("x3"));
        assert!(p.set("finger3_x", -0.1));
        let r = Refusal::Invalid { params: p, error: p.validate_as::<f64>().unwrap_err() };
        assert_eq!(
            r.worded("--").to_string(),
            "finger 3 must start right of finger 2: --x3 -0.1 m > --x2 0 m"
        );
        assert_eq!(r.flag(), flag_index("x3"));
        #[cfg(feature = "multibody")]
        multibody_refusals();
        let r = Refusal::NotApplicable { kind: SceneKind::MeterStick, flag: flag_index("angle").unwrap() };
        let also = if cfg!(feature = "spatial") { ", puck" } else { "" };
        assert_eq!(
            r.worded("--").to_string(),
            format!(
                "--angle does not apply to --scene meter-stick (it is a parameter of incline, ladder, cylinder, painleve{also})"
            )
        );
    }

    /// The scenes of several bodies are refused in the user's words: a driver that does not run
    /// them yet, the top block's width above the bottom's, a stack of 4.
    #[cfg(feature = "multibody")]
    fn multibody_refusals() {
        let r = Refusal::NotYet { kind: SceneKind::Stack, driver: "host-sim stress" };
        assert_eq!(r.worded("--").to_string(), "--scene stack: not yet in host-sim stress");
        let mut p = SceneParams::defaults(SceneKind::BlockOnBlock);
        assert!(p.set("top_width", 0.5));
        let r = Refusal::Invalid { params: p, error: p.validate_as::<f64>().unwrap_err() };
        assert_eq!(
            r.worded("--").to_string(),
            "--width 0.5 m: out of range (the top block no wider than the bottom one: width <= width2)"
        );
        let mut p = SceneParams::defaults(SceneKind::Stack);
        assert!(p.set("blocks", 4.0));
        let r = Refusal::Invalid { params: p, error: p.validate_as::<f64>().unwrap_err() };
        assert_eq!(r.worded("--").to_string(), "--blocks 4: out of range (2 or 3)");
        let mut p = SceneParams::defaults(SceneKind::DiscOnBoard);
        assert!(p.set("offset", -0.6));
        let r = Refusal::Invalid { params: p, error: p.validate_as::<f64>().unwrap_err() };
        assert_eq!(
            r.worded("--").to_string(),
            "--offset -0.6 m: out of range (the disc starts over the board: |offset| <= length2 / 2)"
        );
        assert_eq!(r.flag(), flag_index("offset"));
    }
}
