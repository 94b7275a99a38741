//! [`SceneInfo`] and [`SCENES`]: what the catalogue says of each scene; [`Catalogued`], its
//! lookup by [`SceneKind`].

use meterstick_core::scene::{MAX_MEASURES, OutcomeKind, SceneKind};

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
    /// long names from [`FLAGS`](crate::FLAGS), each one that applies to this scene.
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
        ranges: &[
            ("angle", "0 <= angle < 90"),
            ("step", "0 < h <= duration"),
            ("friction_directions", "0, or a whole number from 3 to 16"),
        ],
    },
    #[cfg(feature = "spatial")]
    SceneInfo {
        kind: SceneKind::Billiard,
        title: "A billiard ball struck with spin: it slides on a line or a parabola, then rolls",
        contact_names: &["the table"],
        main_flags: &["speed", "spin-x", "spin-y", "spin-z", "mu-s", "mu-k", "h"],
        outcomes: &[OutcomeKind::Rolled, OutcomeKind::Unfinished],
        measures: &["rolling_time_s", "rolling_velocity_x_m_s", "rolling_velocity_y_m_s"],
        ranges: &[
            ("step", "0 < h <= duration"),
            ("friction_directions", "0, or a whole number from 3 to 16"),
        ],
    },
    #[cfg(feature = "spatial")]
    SceneInfo {
        kind: SceneKind::Curling,
        title: "A curling stone, a ring or a disc, launched sliding and spinning: it stops sliding and spinning together",
        contact_names: &[
            "point 1", "point 2", "point 3", "point 4", "point 5", "point 6", "point 7", "point 8",
        ],
        main_flags: &["shape", "points", "speed", "spin", "mu", "radius", "h"],
        outcomes: &[OutcomeKind::Stopped, OutcomeKind::Slid],
        measures: &["terminal_ratio", "slide_stop_s", "spin_stop_s"],
        ranges: &[
            ("shape", "ring (0) or disc (1)"),
            ("points", "a whole number from 4 to 8"),
            ("step", "0 < h <= duration"),
        ],
    },
    #[cfg(feature = "spatial")]
    SceneInfo {
        kind: SceneKind::MeterStick3d,
        title: "The paper's rod on two fingers in three dimensions, finger 1 moving at a heading to the rod",
        contact_names: &["finger 1, one edge", "finger 1, the other edge", "finger 2"],
        main_flags: &["speed", "heading", "speed2", "x1", "x2", "mu-s", "mu-k", "h"],
        outcomes: &[OutcomeKind::Balanced, OutcomeKind::Fell, OutcomeKind::Unfinished],
        measures: &["meeting.time_s", "meeting.com_offset_m"],
        ranges: &[
            ("step", "0 < h <= duration"),
            ("rod_thickness", "0 < thickness < length"),
            ("heading", "-80 <= heading <= 80 deg"),
        ],
    },
    #[cfg(feature = "stack-3d")]
    SceneInfo {
        kind: SceneKind::Stack3d,
        title: "Blocks stacked over a table's edge in three dimensions, the overhang at a heading to the edge",
        contact_names: &[],
        main_flags: &["blocks", "overhang", "heading", "mu-s", "mu-k", "length", "width", "height"],
        outcomes: &[OutcomeKind::Held, OutcomeKind::Fell],
        measures: &["max_speed_m_s"],
        ranges: &[
            ("blocks", "2 or 3"),
            ("overhang", "0 <= overhang < 2 x blocks"),
            ("heading", "-60 <= heading <= 60 deg"),
            ("step", "0 < h <= duration"),
        ],
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
