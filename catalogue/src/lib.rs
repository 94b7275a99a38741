//! The scene catalogue's words: what the front ends (`host-sim`'s command line, the browser page)
//! say of the core's scenes, written once. `host-sim`'s clap arguments and `--help`
//! (`host-sim/src/scenes/args.rs`) and the page's controls and URL contract (`web/src/`, through
//! `ms_describe`) are generated from it, and both word a refusal with [`Worded`], so a page URL
//! `?scene=meter-stick&speed=0.1&x1=-0.35` and `host-sim scene --speed 0.1 --x1 -0.35` describe the
//! same run and are refused alike.
//!
//! * [`SCENES`] ([`Catalogued::info`]): each scene's title, contact names, the outcomes it can end
//!   in ([`OutcomeKind`], the one list of outcomes) and what its summary measures;
//! * [`INTRODUCTIONS`]: each scene's heading and one-paragraph introduction for a class (apart from
//!   [`SCENES`], so that a front end that does not show them links none of their text);
//! * [`FLAGS`]: each parameter flag once (name, unit, help), with the core field it sets in each
//!   scene it applies to; defaults are read from the core's `Default`, the checks are the core's
//!   `validate` ([`SceneInfo::ranges`] words a range the core checks beyond a sign);
//! * [`Refusal`]: why a configuration was refused, in the user's words.
//!
//! The scenes themselves, their names, contacts and parameters ([`SceneKind`], [`SceneParams`])
//! and the physics checks ([`ParamError`]) are the core's; this crate is for the front ends only
//! (the firmware does not depend on it). No heap, no feature: data and a few lookups.
//!
//! **Adding a scene**: its [`SceneInfo`] in [`SCENES`], its [`Introduction`] in [`INTRODUCTIONS`]
//! and its field in each [`FLAGS`] entry it uses (or a new flag), besides the core's part
//! (`core/src/scene/kind.rs`).
#![no_std]

#[cfg(test)]
extern crate std;

use core::fmt::{self, Write as _};

use meterstick_core::ParamError;
use meterstick_core::scene::{MAX_MEASURES, OutcomeKind, SceneKind, SceneParams};

/// What the catalogue says of one scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SceneInfo {
    /// The scene.
    pub kind: SceneKind,
    /// One line of what it is.
    pub title: &'static str,
    /// Each contact's name, in the scene's order (contact 1 first).
    pub contact_names: &'static [&'static str],
    /// The flags a lesson turns first (the page shows them, the others under "More parameters"):
    /// long names from [`FLAGS`], each one that applies to this scene.
    pub main_flags: &'static [&'static str],
    /// The outcomes it can end in (besides [`OutcomeKind::Failed`], which any run can).
    pub outcomes: &'static [OutcomeKind],
    /// What its summary measures: the keys of `host-sim`'s `summary.json` (`docs/scenes.md`,
    /// "Measured"), a quantity with parts by each part (`meeting.time_s`).
    pub measures: &'static [&'static str],
    /// Ranges the core checks beyond a sign, worded for a refusal: `(field, range)`.
    pub ranges: &'static [(&'static str, &'static str)],
}

const _: () = {
    let mut i = 0;
    while i < SCENES.len() {
        assert!(SCENES[i].measures.len() <= MAX_MEASURES, "a scene measures more than MAX_MEASURES");
        i += 1;
    }
};

/// Every scene, in the order of [`SceneKind::ALL`] (their numbers on the page).
pub const SCENES: [SceneInfo; SceneKind::ALL.len()] = [
    SceneInfo {
        kind: SceneKind::MeterStick,
        title: "The paper's rod on two fingers",
        contact_names: &["finger 1", "finger 2"],
        main_flags: &["speed", "speed2", "x1", "x2", "mu-s", "mu-k", "h"],
        outcomes: &[OutcomeKind::Balanced, OutcomeKind::Fell, OutcomeKind::Unfinished],
        measures: &["meeting.time_s", "meeting.com_offset_m"],
        ranges: &[("step", "0 < h <= duration"), ("rod_thickness", "0 < thickness < length")],
    },
    SceneInfo {
        kind: SceneKind::Incline,
        title: "A block on an inclined plane",
        contact_names: &["lower left corner", "lower right corner"],
        main_flags: &["angle", "mu-s", "mu-k", "width", "height", "h"],
        outcomes: &[OutcomeKind::Tipped, OutcomeKind::Slid, OutcomeKind::Held],
        measures: &["acceleration_m_s2"],
        ranges: &[("angle", "0 <= angle < 90 deg"), ("step", "0 < h <= duration")],
    },
    SceneInfo {
        kind: SceneKind::Ladder,
        title: "A rod leaning against a wall",
        contact_names: &["foot (floor)", "top (wall)"],
        main_flags: &["angle", "mu-floor", "mu-wall", "length", "h"],
        outcomes: &[OutcomeKind::Fell, OutcomeKind::Held, OutcomeKind::Unfinished],
        measures: &["wall_release_height_m", "wall_release_ratio"],
        ranges: &[
            ("angle", "0 < angle < 90 deg"),
            ("step", "0 < h <= duration"),
            ("thickness", "0 < thickness < length"),
        ],
    },
    SceneInfo {
        kind: SceneKind::ThreeFingers,
        title: "A rod on three fingers, finger 1 moving to finger 2",
        contact_names: &["finger 1", "finger 2", "finger 3"],
        main_flags: &["speed", "x1", "x2", "x3", "mu-s", "mu-k", "h"],
        outcomes: &[OutcomeKind::Fell, OutcomeKind::Held, OutcomeKind::Unfinished],
        measures: &[],
        ranges: &[("step", "0 < h <= duration"), ("rod_thickness", "0 < thickness < length")],
    },
    SceneInfo {
        kind: SceneKind::Cylinder,
        title: "A round body released on an incline: it rolls or slides",
        contact_names: &["rim"],
        main_flags: &["angle", "mu-s", "mu-k", "radius", "inertia-ratio", "h"],
        outcomes: &[OutcomeKind::Rolled, OutcomeKind::Slid],
        measures: &["acceleration_m_s2", "angular_acceleration_rad_s2"],
        ranges: &[("angle", "0 <= angle < 90 deg"), ("step", "0 < h <= duration")],
    },
    SceneInfo {
        kind: SceneKind::Painleve,
        title: "Painleve's paradox: a rod sliding on a rough floor jams",
        contact_names: &["lower end"],
        main_flags: &["angle", "speed", "mu-s", "mu-k", "length", "h"],
        outcomes: &[OutcomeKind::Jammed, OutcomeKind::Slid, OutcomeKind::Fell, OutcomeKind::Unfinished],
        measures: &["jam.time_s", "jam.normal_impulse_n_s", "jam.friction_impulse_n_s"],
        ranges: &[
            ("angle", "0 < angle < 90 deg"),
            ("step", "0 < h <= duration"),
            ("thickness", "0 < thickness < length"),
        ],
    },
    #[cfg(feature = "multibody")]
    SceneInfo {
        kind: SceneKind::BlockOnBlock,
        title: "A block on a block pulled along a floor: held, riding, sliding or tipping",
        contact_names: &[],
        main_flags: &["force", "mu-s", "mu-k", "mu-floor", "mass", "mass2", "width", "height"],
        outcomes: &[OutcomeKind::Held, OutcomeKind::Rode, OutcomeKind::Slid, OutcomeKind::Tipped],
        measures: &["acceleration_m_s2", "top_acceleration_m_s2"],
        ranges: &[
            ("top_width", "the top block no wider than the bottom one: width <= width2"),
            ("step", "0 < h <= duration"),
        ],
    },
    #[cfg(feature = "multibody")]
    SceneInfo {
        kind: SceneKind::Tablecloth,
        title: "A board pulled from under a block: the harder the pull, the less the block moves",
        contact_names: &[],
        main_flags: &["force", "offset", "mu-s", "mu-k", "mu-floor", "mass", "mass2"],
        outcomes: &[OutcomeKind::Stayed, OutcomeKind::Rode, OutcomeKind::Held, OutcomeKind::Unfinished],
        measures: &["block_displacement_m"],
        ranges: &[
            ("offset", "the block starts on the board: offset + width <= length2"),
            ("contact_margin", "0 <= margin < thickness2"),
            ("step", "0 < h <= duration"),
        ],
    },
    #[cfg(feature = "multibody")]
    SceneInfo {
        kind: SceneKind::Stack,
        title: "Blocks stacked over a table's edge with harmonic overhangs",
        contact_names: &[],
        main_flags: &["blocks", "overhang", "mu-s", "mu-k", "length", "height"],
        outcomes: &[OutcomeKind::Held, OutcomeKind::Fell],
        measures: &["max_speed_m_s"],
        ranges: &[
            ("blocks", "2 or 3"),
            ("overhang", "0 <= overhang < 2 x blocks"),
            ("step", "0 < h <= duration"),
        ],
    },
    #[cfg(feature = "multibody")]
    SceneInfo {
        kind: SceneKind::DiscOnBoard,
        title: "A cylinder on a pulled board: it rolls back on the board at a third of its acceleration, or slides",
        contact_names: &[],
        main_flags: &["force", "mu-s", "mu-k", "mu-floor", "mass", "mass2", "radius", "offset"],
        outcomes: &[OutcomeKind::Held, OutcomeKind::Rolled, OutcomeKind::Slid, OutcomeKind::Unfinished],
        measures: &["acceleration_m_s2", "top_acceleration_m_s2"],
        ranges: &[
            ("offset", "the disc starts over the board: |offset| <= length2 / 2"),
            ("step", "0 < h <= duration"),
        ],
    },
    #[cfg(feature = "spatial")]
    SceneInfo {
        kind: SceneKind::Puck,
        title: "A puck launched across a table or an incline: friction against its slip, whichever way it heads",
        contact_names: &["its face"],
        main_flags: &["speed", "heading", "angle", "mu-s", "mu-k", "h"],
        outcomes: &[OutcomeKind::Stopped, OutcomeKind::Slid],
        measures: &["final_speed_m_s", "displacement_m", "displacement_heading_deg"],
        ranges: &[("angle", "0 <= angle < 90"), ("step", "0 < h <= duration")],
    },
    #[cfg(feature = "spatial")]
    SceneInfo {
        kind: SceneKind::Billiard,
        title: "A billiard ball struck with spin: it slides on a line or a parabola, then rolls",
        contact_names: &["the table"],
        main_flags: &["speed", "spin-x", "spin-y", "spin-z", "mu-s", "mu-k", "h"],
        outcomes: &[OutcomeKind::Rolled, OutcomeKind::Unfinished],
        measures: &["rolling_time_s", "rolling_velocity_x_m_s", "rolling_velocity_y_m_s"],
        ranges: &[("step", "0 < h <= duration")],
    },
];

/// A scene's heading and one-paragraph introduction, for a teacher: what the scene shows and what
/// to look for. Kept apart from [`SceneInfo`] so that a front end that does not show them (the
/// page's wasm modules, which are within a size budget) does not link their text: the page reads
/// them from `pkg/intros.json`, which `web/examples/intros.rs` writes from [`INTRODUCTIONS`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Introduction {
    /// The scene.
    pub kind: SceneKind,
    /// Its heading.
    pub heading: &'static str,
    /// One paragraph: what it shows, what to look for.
    pub intro: &'static str,
}

/// Every scene's [`Introduction`], in the order of [`SCENES`].
pub const INTRODUCTIONS: [Introduction; SceneKind::ALL.len()] = [
    Introduction {
        kind: SceneKind::MeterStick,
        heading: "The meter-stick trick",
        intro: "Rest a meter stick on two fingers and slide one finger toward the other: the stick never \
                falls, the fingers meet under its centre of mass. The finger farther from the centre of \
                mass carries less weight, so its friction limit is lower and it slides while the other \
                sticks; as it comes closer its load grows until the sticking finger's friction gives way \
                and the roles swap. Look for the switches marked under the plots: at each stick-to-slip \
                switch the ratio x_stop/x_start is close to mu_k/mu_s (the paper's eq. 21). Moved fast, \
                the stick no longer follows the quasi-static story: it tips and falls.",
    },
    Introduction {
        kind: SceneKind::Incline,
        heading: "A block on an inclined plane",
        intro: "A block is set down at rest on a slope. It stays where it is while tan(angle) <= mu_s; on \
                a steeper slope it slides, accelerating at g (sin a - mu_k cos a) whatever its mass. A \
                block taller than it is wide tips over its lower corner instead once tan(angle) exceeds \
                width/height, before friction gives way. Look for the normal force moving to the lower \
                corner as the slope steepens, and compare the measured acceleration with the formula.",
    },
    Introduction {
        kind: SceneKind::Ladder,
        heading: "A ladder sliding down a wall",
        intro: "A rod leans against a wall with its foot on the floor. Friction at the foot must supply \
                the horizontal push that keeps the foot in place; at a steep angle little is needed and \
                the ladder stands, at a shallow one it slides: the foot moves out, the top slides down \
                the wall. Without friction the top leaves the wall when it has come down to 2/3 of its \
                starting height, and the rod falls free. Look for the moment the top leaves the wall \
                (the wall contact turns hollow) and the measured release height.",
    },
    Introduction {
        kind: SceneKind::ThreeFingers,
        heading: "A rod on three fingers",
        intro: "The meter-stick trick with a third finger. A rod on three supports is statically \
                indeterminate: the rigid-body equations of balance do not say how its weight is shared \
                among them. Finger 1 moves toward finger 2 while finger 3 stays: the contact solver \
                chooses at each step which fingers stick, which slide and which lose contact. Look for \
                the normal-force arrows: the weight shifts between the fingers as finger 1 moves, and \
                a finger that carries nothing lets go.",
    },
    Introduction {
        kind: SceneKind::Cylinder,
        heading: "Rolling or sliding down a slope",
        intro: "A round body is released on a slope. If friction can supply the torque, it rolls without \
                slipping and accelerates at g sin a / (1 + k), slower than a sliding block, where \
                J = k m r^2 (k = 1/2 for a solid cylinder, 1 for a ring). That needs \
                tan(angle) <= mu_s (1 + k) / k; on a steeper slope it slides while friction spins it up, \
                and its centre accelerates at g (sin a - mu_k cos a). Look for the spoke: rolling turns \
                it by exactly the distance travelled, slipping turns it less.",
    },
    Introduction {
        kind: SceneKind::Painleve,
        heading: "Painlev\u{e9}'s paradox: the jamming rod",
        intro: "A tilted rod slides with its lower end on a rough floor. For a uniform rod at angle a, \
                sliding with friction mu above (1 + 3 cos^2 a) / (3 sin a cos a) (2.5 at 30 degrees, \
                4/3 at the least) has no consistent rigid-body answer: friction would drive the end \
                into the floor. Painlev\u{e9} found this in 1895; the way out is an impulse: the end \
                stops dead (it jams) with a finite normal and friction impulse in one step. Look for the \
                jam's time and impulses; with smaller mu the end slides on.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::BlockOnBlock,
        heading: "A block on a pulled block",
        intro: "A block rests on another block, which is pulled along the floor by a force F (the arrow). \
                A gentle pull that beats the floor's friction drags both together: friction between the \
                blocks carries the top one along at the same acceleration. The top block can only be \
                accelerated by that friction, at most mu_s g; pull harder and it slips, falling behind \
                at mu_k g while the bottom block runs ahead until the top one slides off its back. A tall \
                top block tips over instead. Look for the two measured accelerations.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::Tablecloth,
        heading: "The tablecloth trick",
        intro: "A board (the tablecloth) is pulled out from under a block. While the board slides beneath \
                it, kinetic friction accelerates the block forward at no more than mu_k g, and only for \
                as long as the board is under it. The harder the pull, the sooner the board is gone, so \
                the less the block moves: compare 10 N with 20 N side by side. A gentle pull drags the \
                block along with the board instead. Look for the block's displacement, measured once it \
                has come to rest behind the board.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::Stack,
        heading: "Blocks stacked over a table's edge",
        intro: "Blocks of length L are stacked over a table's edge, the k-th from the top reaching \
                s L / (2k) past the one below it: the harmonic overhangs. With s = 1 the centre of mass \
                of the blocks above each block lies exactly over that block's edge, and that of the \
                whole stack over the table's edge: the largest overhang, L/2 (1 + 1/2 + 1/3) = 11/12 L \
                for three blocks, the top block wholly beyond the table. Below overhang 1 the stack holds; past it, it \
                tips and falls. Look at 0.98 against 1.02 side by side: a few percent decide.",
    },
    #[cfg(feature = "multibody")]
    Introduction {
        kind: SceneKind::DiscOnBoard,
        heading: "A cylinder on a pulled board",
        intro: "A solid cylinder lies on a board that a force pulls along the floor (the arrow). Friction \
                at the cylinder's bottom both pushes its centre forward and spins it backward: rolling \
                without slipping on a board that accelerates at A, its centre accelerates at only A/3, \
                so it rolls back along the board. That needs friction m A/3, at most mu_s m g: pulled \
                harder (A > 3 mu_s g) it slides. Look for the spoke turning and the two measured \
                accelerations, a third of one another while it rolls.",
    },
    #[cfg(feature = "spatial")]
    Introduction {
        kind: SceneKind::Puck,
        heading: "A puck on a table or an incline",
        intro: "A puck is launched across a level table or an inclined plane. Coulomb's friction opposes \
                the puck's slip, whatever direction it has: on a level table it slides straight along \
                its heading and stops after v^2 / (2 mu g), the same distance in every direction. Across \
                an incline with mu = tan(angle), friction and the slope's pull cancel along the slope: \
                the path bends down the slope and the speed tends to exactly half the launch speed. \
                Look for the path and the final speed, and turn the heading: the distance does not \
                change (simulators that approximate the friction cone by a pyramid bend the path \
                toward their axes).",
    },
    #[cfg(feature = "spatial")]
    Introduction {
        kind: SceneKind::Billiard,
        heading: "A billiard ball struck with spin",
        intro: "A ball is struck along the table with spin. Its contact point slips, and friction against \
                the slip slows the ball and turns its spin until the slip stops: from then on it rolls. \
                The slip keeps its direction, so a ball with side spin curves on a parabola. It rolls \
                from t = 2 |u0| / (7 mu g) at v = (5 v0 + 2 R omega0 x z) / 7, whatever its mass; the \
                spin about the vertical stays, since a point of contact has no friction against it. \
                Look for the moment it starts rolling and the rolling velocity.",
    },
];

/// The catalogue's entry of a scene.
pub trait Catalogued {
    /// The catalogue's entry.
    fn info(self) -> &'static SceneInfo;
    /// How the range of `field` is worded in a refusal.
    fn range_of(self, field: &str) -> &'static str;
}

impl Catalogued for SceneKind {
    fn info(self) -> &'static SceneInfo {
        &SCENES[self.index()]
    }

    fn range_of(self, field: &str) -> &'static str {
        self.info().ranges.iter().find(|(f, _)| *f == field).map_or("its documented range", |(_, r)| r)
    }
}

/// One parameter flag: the command line's `--long`, the page's control and URL key `long`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Flag {
    /// The flag's name, without `--`.
    pub long: &'static str,
    /// Its unit (`deg` is converted to the core's radians).
    pub unit: &'static str,
    /// What it is.
    pub help: &'static str,
    /// The core field it sets in each scene it applies to.
    pub fields: &'static [(SceneKind, &'static str)],
}

impl Flag {
    /// The core field this flag sets in `kind`, if it applies to it.
    #[must_use]
    pub fn field(&self, kind: SceneKind) -> Option<&'static str> {
        self.fields.iter().find(|(k, _)| *k == kind).map(|(_, f)| *f)
    }

    /// From the flag's unit to the core's.
    #[must_use]
    pub fn to_core(&self, value: f64) -> f64 {
        if self.unit == "deg" { value.to_radians() } else { value }
    }

    /// From the core's unit to the flag's.
    #[must_use]
    pub fn from_core(&self, value: f64) -> f64 {
        if self.unit == "deg" { value.to_degrees() } else { value }
    }
}

#[cfg(feature = "spatial")]
use SceneKind::{Billiard as BI, Puck as PK};
#[cfg(feature = "multibody")]
use SceneKind::{BlockOnBlock as BB, DiscOnBoard as DB, Stack as ST, Tablecloth as TC};
use SceneKind::{
    Cylinder as C, Incline as I, Ladder as L, MeterStick as M, Painleve as P, ThreeFingers as F,
};

/// Every scene flag, each once. Its order is the command line's and the page's, and decides which
/// complaint comes first.
pub const FLAGS: &[Flag] = &[
    Flag {
        long: "speed",
        unit: "m/s",
        help: "Finger 1's velocity (+x: toward finger 2); painleve: the rod's velocity along x at the start (negative: its lower end slides away from under it); puck: the launch speed (>= 0); billiard: the ball's speed along +x (>= 0)",
        fields: &[
            (M, "finger1_velocity"),
            (F, "finger1_velocity"),
            (P, "speed"),
            #[cfg(feature = "spatial")]
            (PK, "speed"),
            #[cfg(feature = "spatial")]
            (BI, "speed"),
        ],
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
        fields: &[(M, "finger1_x"), (F, "finger1_x")],
    },
    Flag {
        long: "x2",
        unit: "m",
        help: "Start x of finger 2 (> x1 + finger width)",
        fields: &[(M, "finger2_x"), (F, "finger2_x")],
    },
    Flag {
        long: "x3",
        unit: "m",
        help: "x of finger 3 (three-fingers; > x2, within +-L/2)",
        fields: &[(F, "finger3_x")],
    },
    Flag { long: "y1", unit: "m", help: "Height of finger 1's tip", fields: &[(M, "finger1_y")] },
    Flag { long: "y2", unit: "m", help: "Height of finger 2's tip", fields: &[(M, "finger2_y")] },
    Flag {
        long: "finger-width",
        unit: "m",
        help: "Approaching fingers stop when their tips are this far apart (>= 0)",
        fields: &[(M, "finger_width"), (F, "finger_width")],
    },
    Flag {
        long: "mu-s",
        unit: "",
        help: "Static friction coefficient (>= 0; between the bodies; stack: every contact's)",
        fields: &[
            (M, "mu_static"),
            (I, "mu_static"),
            (F, "mu_static"),
            (C, "mu_static"),
            (P, "mu_static"),
            #[cfg(feature = "multibody")]
            (BB, "mu_static"),
            #[cfg(feature = "multibody")]
            (TC, "mu_static"),
            #[cfg(feature = "multibody")]
            (ST, "mu_static"),
            #[cfg(feature = "multibody")]
            (DB, "mu_static"),
            #[cfg(feature = "spatial")]
            (PK, "mu_static"),
            #[cfg(feature = "spatial")]
            (BI, "mu_static"),
        ],
    },
    Flag {
        long: "mu-k",
        unit: "",
        help: "Kinetic friction coefficient (0 <= mu-k <= mu-s)",
        fields: &[
            (M, "mu_kinetic"),
            (I, "mu_kinetic"),
            (F, "mu_kinetic"),
            (C, "mu_kinetic"),
            (P, "mu_kinetic"),
            #[cfg(feature = "multibody")]
            (BB, "mu_kinetic"),
            #[cfg(feature = "multibody")]
            (TC, "mu_kinetic"),
            #[cfg(feature = "multibody")]
            (ST, "mu_kinetic"),
            #[cfg(feature = "multibody")]
            (DB, "mu_kinetic"),
            #[cfg(feature = "spatial")]
            (PK, "mu_kinetic"),
            #[cfg(feature = "spatial")]
            (BI, "mu_kinetic"),
        ],
    },
    Flag {
        long: "mu-floor",
        unit: "",
        help: "Friction coefficient at the floor, static and kinetic (>= 0)",
        fields: &[
            (L, "mu_floor"),
            #[cfg(feature = "multibody")]
            (BB, "mu_floor"),
            #[cfg(feature = "multibody")]
            (TC, "mu_floor"),
            #[cfg(feature = "multibody")]
            (DB, "mu_floor"),
        ],
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
        help: "Slope angle (incline, cylinder, puck: 0 <= a < 90; puck: about x, 0 a level table) or start angle from the floor (ladder, painleve: 0 < a < 90)",
        fields: &[
            (I, "angle"),
            (L, "angle"),
            (C, "angle"),
            (P, "angle"),
            #[cfg(feature = "spatial")]
            (PK, "angle"),
        ],
    },
    Flag {
        long: "mass",
        unit: "kg",
        help: "Mass of the body (> 0; the upper block; each block of a stack; disc-on-board the disc)",
        fields: &[
            (M, "rod_mass"),
            (I, "mass"),
            (L, "mass"),
            (F, "rod_mass"),
            (C, "mass"),
            (P, "mass"),
            #[cfg(feature = "multibody")]
            (BB, "top_mass"),
            #[cfg(feature = "multibody")]
            (TC, "block_mass"),
            #[cfg(feature = "multibody")]
            (ST, "mass"),
            #[cfg(feature = "multibody")]
            (DB, "disc_mass"),
            #[cfg(feature = "spatial")]
            (PK, "mass"),
            #[cfg(feature = "spatial")]
            (BI, "mass"),
        ],
    },
    Flag {
        long: "length",
        unit: "m",
        help: "Rod length (> 0; stack: each block's)",
        fields: &[
            (M, "rod_length"),
            (L, "length"),
            (F, "rod_length"),
            (P, "length"),
            #[cfg(feature = "multibody")]
            (ST, "length"),
        ],
    },
    Flag {
        long: "thickness",
        unit: "m",
        help: "Rod thickness (> 0, less than its length)",
        fields: &[
            (M, "rod_thickness"),
            (L, "thickness"),
            (F, "rod_thickness"),
            (P, "thickness"),
            #[cfg(feature = "spatial")]
            (PK, "thickness"),
        ],
    },
    Flag {
        long: "width",
        unit: "m",
        help: "Block width (> 0; incline: along the slope; the upper block)",
        fields: &[
            (I, "width"),
            #[cfg(feature = "multibody")]
            (BB, "top_width"),
            #[cfg(feature = "multibody")]
            (TC, "block_width"),
        ],
    },
    Flag {
        long: "height",
        unit: "m",
        help: "Block height (> 0; the upper block; each block of a stack)",
        fields: &[
            (I, "height"),
            #[cfg(feature = "multibody")]
            (BB, "top_height"),
            #[cfg(feature = "multibody")]
            (TC, "block_height"),
            #[cfg(feature = "multibody")]
            (ST, "height"),
        ],
    },
    Flag {
        long: "radius",
        unit: "m",
        help: "Radius of the round body (> 0)",
        fields: &[
            (C, "radius"),
            #[cfg(feature = "multibody")]
            (DB, "disc_radius"),
            #[cfg(feature = "spatial")]
            (PK, "radius"),
            #[cfg(feature = "spatial")]
            (BI, "radius"),
        ],
    },
    Flag {
        long: "inertia-ratio",
        unit: "",
        help: "k in J = k m r^2 (> 0): 0.5 a solid cylinder, 1 a thin ring",
        fields: &[(C, "inertia_factor")],
    },
    Flag {
        long: "gravity",
        unit: "m/s^2",
        help: "Gravity (>= 0)",
        fields: &[
            (M, "gravity"),
            (I, "gravity"),
            (L, "gravity"),
            (F, "gravity"),
            (C, "gravity"),
            (P, "gravity"),
            #[cfg(feature = "multibody")]
            (BB, "gravity"),
            #[cfg(feature = "multibody")]
            (TC, "gravity"),
            #[cfg(feature = "multibody")]
            (ST, "gravity"),
            #[cfg(feature = "multibody")]
            (DB, "gravity"),
            #[cfg(feature = "spatial")]
            (PK, "gravity"),
            #[cfg(feature = "spatial")]
            (BI, "gravity"),
        ],
    },
    Flag {
        long: "h",
        unit: "s",
        help: "Time step (> 0, at most the duration)",
        fields: &[
            (M, "step"),
            (I, "step"),
            (L, "step"),
            (F, "step"),
            (C, "step"),
            (P, "step"),
            #[cfg(feature = "multibody")]
            (BB, "step"),
            #[cfg(feature = "multibody")]
            (TC, "step"),
            #[cfg(feature = "multibody")]
            (ST, "step"),
            #[cfg(feature = "multibody")]
            (DB, "step"),
            #[cfg(feature = "spatial")]
            (PK, "step"),
            #[cfg(feature = "spatial")]
            (BI, "step"),
        ],
    },
    Flag {
        long: "duration",
        unit: "s",
        help: "Longest simulated time (> 0); a run still going then ends Unfinished (the meter stick's default grows with the fingers' travel time)",
        fields: &[
            (M, "max_time"),
            (I, "max_time"),
            (L, "max_time"),
            (F, "max_time"),
            (C, "max_time"),
            (P, "max_time"),
            #[cfg(feature = "multibody")]
            (BB, "max_time"),
            #[cfg(feature = "multibody")]
            (TC, "max_time"),
            #[cfg(feature = "multibody")]
            (ST, "max_time"),
            #[cfg(feature = "multibody")]
            (DB, "max_time"),
            #[cfg(feature = "spatial")]
            (PK, "max_time"),
            #[cfg(feature = "spatial")]
            (BI, "max_time"),
        ],
    },
    Flag {
        long: "stick-speed",
        unit: "m/s",
        help: "A touching contact whose slip speed is at most this sticks (>= 0)",
        fields: &[
            (M, "stick_speed"),
            (I, "stick_speed"),
            (L, "stick_speed"),
            (F, "stick_speed"),
            (C, "stick_speed"),
            (P, "stick_speed"),
            #[cfg(feature = "multibody")]
            (BB, "stick_speed"),
            #[cfg(feature = "multibody")]
            (TC, "stick_speed"),
            #[cfg(feature = "multibody")]
            (ST, "stick_speed"),
            #[cfg(feature = "multibody")]
            (DB, "stick_speed"),
            #[cfg(feature = "spatial")]
            (PK, "stick_speed"),
            #[cfg(feature = "spatial")]
            (BI, "stick_speed"),
        ],
    },
    Flag {
        long: "tilt-limit",
        unit: "rad",
        help: "The body has fallen (tipped) when it tilted this far from its start angle (> 0)",
        fields: &[
            (M, "tilt_limit"),
            (F, "tilt_limit"),
            #[cfg(feature = "multibody")]
            (BB, "tilt_limit"),
            #[cfg(feature = "multibody")]
            (ST, "tilt_limit"),
        ],
    },
    Flag {
        long: "drop-limit",
        unit: "m",
        help: "The body has fallen when its centre of mass dropped this far (> 0)",
        fields: &[
            (M, "drop_limit"),
            #[cfg(feature = "multibody")]
            (ST, "drop_limit"),
        ],
    },
    Flag {
        long: "hold-time",
        unit: "s",
        help: "After the fingers meet, the rod must stay on them this long to balance (>= 0)",
        fields: &[(M, "hold_time"), (F, "hold_time")],
    },
    // The scenes of several bodies' own flags, last: a build without the feature `multibody` lists
    // the flags before them with their numbers unchanged.
    #[cfg(feature = "multibody")]
    Flag {
        long: "mass2",
        unit: "kg",
        help: "Mass of the lower body (> 0): block-on-block the bottom block, tablecloth and disc-on-board the board",
        fields: &[(BB, "bottom_mass"), (TC, "board_mass"), (DB, "board_mass")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "length2",
        unit: "m",
        help: "Length of the board (> 0; tablecloth: at least offset + width)",
        fields: &[(TC, "board_length"), (DB, "board_length")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "width2",
        unit: "m",
        help: "Width of the bottom block (> 0)",
        fields: &[(BB, "bottom_width")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "height2",
        unit: "m",
        help: "Height of the bottom block (> 0)",
        fields: &[(BB, "bottom_height")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "thickness2",
        unit: "m",
        help: "Thickness of the board (> 0; tablecloth: more than the margin)",
        fields: &[(TC, "board_thickness"), (DB, "board_height")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "force",
        unit: "N",
        help: "The pull along +x on the lower body at its centre of mass (>= 0): block-on-block the bottom block, tablecloth and disc-on-board the board",
        fields: &[(BB, "force"), (TC, "force"), (DB, "force")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "offset",
        unit: "m",
        help: "Tablecloth: the block's rear (left) face from the board's trailing (left) end (>= 0); disc-on-board: the disc's centre from the board's centre (within +-length2 / 2)",
        fields: &[(TC, "offset"), (DB, "offset")],
    },
    #[cfg(feature = "multibody")]
    Flag { long: "blocks", unit: "", help: "Blocks in the stack: 2 or 3", fields: &[(ST, "blocks")] },
    #[cfg(feature = "multibody")]
    Flag {
        long: "overhang",
        unit: "",
        help: "The harmonic overhangs' scale s (0 <= s < 2 x blocks): each block reaches s L / (2k) past the one below; below 1 the stack holds, above it falls",
        fields: &[(ST, "overhang")],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "margin",
        unit: "m",
        help: "The activity rule's margin: a corner this near a face is a candidate contact (>= 0)",
        fields: &[
            (BB, "contact_margin"),
            (TC, "contact_margin"),
            (ST, "contact_margin"),
            (DB, "contact_margin"),
        ],
    }, // The scenes in three dimensions' own flags, last.
    #[cfg(feature = "spatial")]
    Flag {
        long: "heading",
        unit: "deg",
        help: "The launch's heading from +x (across the slope) toward down the slope; on a level table counter-clockwise from +x",
        fields: &[(PK, "heading")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "spin-x",
        unit: "rad/s",
        help: "Spin about the world's x at the start",
        fields: &[(BI, "spin_x")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "spin-y",
        unit: "rad/s",
        help: "Spin about the world's y at the start (negative: topspin, positive: backspin)",
        fields: &[(BI, "spin_y")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "spin-z",
        unit: "rad/s",
        help: "Spin about the vertical at the start (side spin; a point contact has no friction against it)",
        fields: &[(BI, "spin_z")],
    },
];

/// The number of flags.
pub const FLAG_COUNT: usize = FLAGS.len();

/// The flag that sets `field` in `kind`.
#[must_use]
pub fn flag_of(kind: SceneKind, field: &str) -> Option<&'static Flag> {
    FLAGS.iter().find(|f| f.field(kind) == Some(field))
}

/// The index in [`FLAGS`] of the flag called `long`.
#[must_use]
pub fn flag_index(long: &str) -> Option<usize> {
    FLAGS.iter().position(|f| f.long == long)
}

/// The most steps one run may take: 10^8 (about 30 s of the core on a host); a step count beyond
/// it is refused before anything runs.
pub const MAX_STEPS: f64 = 1e8;

/// Why a configuration was refused, before anything ran.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Refusal {
    /// A flag was given that does not apply to the scene (its index in [`FLAGS`]).
    NotApplicable {
        /// The scene.
        kind: SceneKind,
        /// The flag's index.
        flag: usize,
    },
    /// The core rejected a parameter (the message says so when only f32 refuses it).
    Invalid {
        /// The parameters as resolved.
        params: SceneParams,
        /// The core's complaint.
        error: ParamError,
    },
    /// The scene is one of several bodies ([`SceneKind::is_multibody`]) and this front end
    /// (`driver`: `host-sim stress`, the page) does not run those yet.
    NotYet {
        /// The scene.
        kind: SceneKind,
        /// What does not run it, as the user knows it.
        driver: &'static str,
    },
    /// `h` and the time limit imply more than `limit` steps.
    TooManySteps {
        /// The parameters as resolved.
        params: SceneParams,
        /// The steps they imply.
        steps: f64,
        /// The most a run may take.
        limit: f64,
        /// The time limit is the meter stick's default raised to the fingers' travel time
        /// ([`SceneParams::follow_travel_time`]), not a duration the user gave.
        followed: bool,
    },
}

impl Refusal {
    /// The flag the user should change (its index in [`FLAGS`]), where one is to blame.
    #[must_use]
    pub fn flag(&self) -> Option<usize> {
        let index = |kind: SceneKind, field: &str| {
            flag_of(kind, field).and_then(|f| FLAGS.iter().position(|g| g.long == f.long))
        };
        match *self {
            Self::NotApplicable { flag, .. } => Some(flag),
            Self::Invalid { params, error } => {
                params.field_at_fault(error).and_then(|f| index(params.kind(), f))
            }
            Self::TooManySteps { params, .. } => index(params.kind(), "step"),
            Self::NotYet { .. } => None,
        }
    }

    /// The refusal in the user's words, flags written with `prefix` (`--` on the command line,
    /// nothing on the page): `--mu-k 0.7 must not exceed --mu-s 0.6`.
    #[must_use]
    pub const fn worded(self, prefix: &'static str) -> Worded {
        Worded { refusal: self, prefix }
    }
}

/// A [`Refusal`] in the user's words ([`Refusal::worded`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Worded {
    refusal: Refusal,
    prefix: &'static str,
}

/// A field as the user set it: `--flag value unit` (e.g. `--mu-k 0.7`, `--angle 95 deg`).
struct Shown<'a>(&'a SceneParams, &'a str, &'static str);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self(params, field, prefix) = *self;
        match (flag_of(params.kind(), field), params.get(field)) {
            (Some(flag), Some(v)) => {
                write!(f, "{prefix}{} {}", flag.long, Short(flag.from_core(v)))?;
                if !flag.unit.is_empty() {
                    write!(f, " {}", flag.unit)?;
                }
                Ok(())
            }
            _ => f.write_str(field),
        }
    }
}

impl fmt::Display for Worded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.prefix;
        match self.refusal {
            Refusal::NotApplicable { kind, flag } => {
                let Some(flag) = FLAGS.get(flag) else { return f.write_str("unknown flag") };
                write!(
                    f,
                    "{p}{} does not apply to {p}scene {} (it is a parameter of ",
                    flag.long,
                    kind.name()
                )?;
                for (i, (k, _)) in flag.fields.iter().enumerate() {
                    write!(f, "{}{}", if i > 0 { ", " } else { "" }, k.name())?;
                }
                f.write_str(")")
            }
            Refusal::Invalid { params, error } => {
                let show = |field| Shown(&params, field, p);
                match error {
                    ParamError::NonFinite(x) => write!(f, "{}: not a finite number", show(x)),
                    ParamError::NotPositive(x) => write!(f, "{}: must be greater than 0", show(x)),
                    ParamError::Negative(x) => write!(f, "{}: must not be negative", show(x)),
                    ParamError::OutOfRange(x) => {
                        write!(f, "{}: out of range ({})", show(x), params.kind().range_of(x))
                    }
                    ParamError::KineticAboveStatic => {
                        write!(f, "{} must not exceed {}", show("mu_kinetic"), show("mu_static"))
                    }
                    ParamError::FingerOutsideRod => write!(
                        f,
                        "a finger starts beyond an end of the rod: {} must be within {} / 2",
                        show(params.field_at_fault(error).unwrap_or("finger1_x")),
                        show("rod_length")
                    ),
                    ParamError::FingersCrossed if params.field_at_fault(error) == Some("finger3_x") => {
                        write!(
                            f,
                            "finger 3 must start right of finger 2: {} > {}",
                            show("finger3_x"),
                            show("finger2_x")
                        )
                    }
                    ParamError::FingersCrossed => write!(
                        f,
                        "finger 1 must start left of finger 2 by more than the finger width: {} < {} - {}",
                        show("finger1_x"),
                        show("finger2_x"),
                        show("finger_width")
                    ),
                    ParamError::InertiaOutOfRange { mass, size } => write!(
                        f,
                        "{} and {}: the moment of inertia they give is not a positive finite number",
                        show(mass),
                        show(size)
                    ),
                    other => write!(f, "{other}"),
                }?;
                // Parameters that pass in f64 failed in f32.
                if params.validate_as::<f64>().is_ok() {
                    write!(f, " as f32 ({p}precision f32; f64 accepts it)")?;
                }
                Ok(())
            }
            Refusal::NotYet { kind, driver } => write!(f, "{p}scene {}: not yet in {driver}", kind.name()),
            Refusal::TooManySteps { params, steps, limit, followed } => {
                write!(
                    f,
                    "{p}h {} s and {p}duration {} s imply {steps:.3e} steps; a run may take at most {limit:e} \
                     (raise {p}h or lower {p}duration)",
                    Short(params.step()),
                    Short(params.max_time())
                )?;
                if followed {
                    write!(f, "; the default {p}duration follows the fingers' travel time")?;
                }
                Ok(())
            }
        }
    }
}

/// A number as a person typed it: `{}` when that is short; else 9 decimals with the trailing zeros
/// dropped when that is the same number to 12 digits (so a round trip through radians shows `95`,
/// not `95.00000000000001`); else the shorter of `{}` and `{:e}` (`1e-30`, `1e39`, never a rounded
/// `0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Short(pub f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let plain = Buf::of(format_args!("{v}"));
        if plain.as_str().len() <= 12 || !v.is_finite() {
            return f.write_str(plain.as_str());
        }
        let fixed = Buf::of(format_args!("{v:.9}"));
        let trimmed = fixed.as_str().trim_end_matches('0').trim_end_matches('.');
        if trimmed.len() <= 12
            && trimmed.parse::<f64>().is_ok_and(|t| libm::fabs(t - v) <= 1e-12 * libm::fabs(v))
        {
            return f.write_str(trimmed);
        }
        let exp = Buf::of(format_args!("{v:e}"));
        f.write_str(if exp.as_str().len() < plain.as_str().len() { exp.as_str() } else { plain.as_str() })
    }
}

/// A number's text on the stack (an f64's `{}` is at most about 330 bytes).
struct Buf {
    bytes: [u8; 400],
    len: usize,
}

impl Buf {
    fn of(args: fmt::Arguments<'_>) -> Self {
        let mut b = Self { bytes: [0; 400], len: 0 };
        let _ = b.write_fmt(args);
        b
    }

    fn as_str(&self) -> &str {
        core::str::from_utf8(&self.bytes[..self.len]).unwrap_or("")
    }
}

impl fmt::Write for Buf {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let take = s.len().min(self.bytes.len() - self.len);
        self.bytes[self.len..self.len + take].copy_from_slice(&s.as_bytes()[..take]);
        self.len += take;
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use std::format;
    use std::string::ToString;

    use super::*;

    #[test]
    fn every_scene_is_in_its_place_and_every_flag_names_a_field() {
        for (i, kind) in SceneKind::ALL.into_iter().enumerate() {
            assert_eq!(kind.info().kind, kind);
            assert_eq!(kind.index(), i);
            // A scene in three dimensions is not a planar `Scene` (`contacts` 0): its names are its
            // view's contacts'.
            let contacts = if kind.is_spatial() { 1 } else { kind.contacts() };
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
