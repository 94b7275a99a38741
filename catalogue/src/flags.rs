//! [`Flag`] and [`FLAGS`]: every parameter flag once, with the core field it sets in each scene.

use meterstick_core::scene::SceneKind;

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

#[cfg(feature = "stack-3d")]
use SceneKind::Stack3d as S3;
#[cfg(feature = "spatial")]
use SceneKind::{Billiard as BI, Curling as CU, MeterStick3d as M3, Puck as PK};
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
        help: "Finger 1's velocity (+x: toward finger 2); painleve: the rod's velocity along x at the start (negative: its lower end slides away from under it); puck: the launch speed (>= 0); billiard: the ball's speed along +x (>= 0); curling: the launch speed along +x (>= 0)",
        fields: &[
            (M, "finger1_velocity"),
            #[cfg(feature = "spatial")]
            (M3, "finger1_velocity"),
            (F, "finger1_velocity"),
            (P, "speed"),
            #[cfg(feature = "spatial")]
            (PK, "speed"),
            #[cfg(feature = "spatial")]
            (BI, "speed"),
            #[cfg(feature = "spatial")]
            (CU, "speed"),
        ],
    },
    Flag {
        long: "speed2",
        unit: "m/s",
        help: "Finger 2's velocity (-x: toward finger 1)",
        fields: &[
            (M, "finger2_velocity"),
            #[cfg(feature = "spatial")]
            (M3, "finger2_velocity"),
        ],
    },
    Flag {
        long: "x1",
        unit: "m",
        help: "Start x of finger 1 (from the rod's centre of mass; within +-L/2)",
        fields: &[
            (M, "finger1_x"),
            #[cfg(feature = "spatial")]
            (M3, "finger1_x"),
            (F, "finger1_x"),
        ],
    },
    Flag {
        long: "x2",
        unit: "m",
        help: "Start x of finger 2 (> x1 + finger width)",
        fields: &[
            (M, "finger2_x"),
            #[cfg(feature = "spatial")]
            (M3, "finger2_x"),
            (F, "finger2_x"),
        ],
    },
    Flag {
        long: "x3",
        unit: "m",
        help: "x of finger 3 (three-fingers; > x2, within +-L/2)",
        fields: &[(F, "finger3_x")],
    },
    Flag {
        long: "y1",
        unit: "m",
        help: "Height of finger 1's tip",
        fields: &[
            (M, "finger1_y"),
            #[cfg(feature = "spatial")]
            (M3, "finger1_y"),
        ],
    },
    Flag {
        long: "y2",
        unit: "m",
        help: "Height of finger 2's tip",
        fields: &[
            (M, "finger2_y"),
            #[cfg(feature = "spatial")]
            (M3, "finger2_y"),
        ],
    },
    Flag {
        long: "finger-width",
        unit: "m",
        help: "Approaching fingers stop when their tips are this far apart (>= 0)",
        fields: &[
            (M, "finger_width"),
            #[cfg(feature = "spatial")]
            (M3, "finger_width"),
            (F, "finger_width"),
        ],
    },
    Flag {
        long: "mu-s",
        unit: "",
        help: "Static friction coefficient (>= 0; between the bodies; stack: every contact's)",
        fields: &[
            (M, "mu_static"),
            #[cfg(feature = "spatial")]
            (M3, "mu_static"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "mu_static"),
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
            #[cfg(feature = "spatial")]
            (M3, "mu_kinetic"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "mu_kinetic"),
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
            #[cfg(feature = "spatial")]
            (M3, "rod_mass"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "mass"),
            #[cfg(feature = "multibody")]
            (DB, "disc_mass"),
            #[cfg(feature = "spatial")]
            (PK, "mass"),
            #[cfg(feature = "spatial")]
            (BI, "mass"),
            #[cfg(feature = "spatial")]
            (CU, "mass"),
        ],
    },
    Flag {
        long: "length",
        unit: "m",
        help: "Rod length (> 0; stack: each block's)",
        fields: &[
            (M, "rod_length"),
            #[cfg(feature = "spatial")]
            (M3, "rod_length"),
            (L, "length"),
            (F, "rod_length"),
            (P, "length"),
            #[cfg(feature = "multibody")]
            (ST, "length"),
            #[cfg(feature = "stack-3d")]
            (S3, "length"),
        ],
    },
    Flag {
        long: "thickness",
        unit: "m",
        help: "Rod thickness (> 0, less than its length)",
        fields: &[
            (M, "rod_thickness"),
            #[cfg(feature = "spatial")]
            (M3, "rod_thickness"),
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
        help: "Block width (> 0; incline: along the slope; the upper block); meter-stick-3d: the rod's width, across it",
        fields: &[
            (I, "width"),
            #[cfg(feature = "spatial")]
            (M3, "rod_width"),
            #[cfg(feature = "multibody")]
            (BB, "top_width"),
            #[cfg(feature = "multibody")]
            (TC, "block_width"),
            #[cfg(feature = "stack-3d")]
            (S3, "width"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "height"),
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
            #[cfg(feature = "spatial")]
            (CU, "radius"),
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
            #[cfg(feature = "spatial")]
            (M3, "gravity"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "gravity"),
            #[cfg(feature = "multibody")]
            (DB, "gravity"),
            #[cfg(feature = "spatial")]
            (PK, "gravity"),
            #[cfg(feature = "spatial")]
            (BI, "gravity"),
            #[cfg(feature = "spatial")]
            (CU, "gravity"),
        ],
    },
    Flag {
        long: "h",
        unit: "s",
        help: "Time step (> 0, at most the duration)",
        fields: &[
            (M, "step"),
            #[cfg(feature = "spatial")]
            (M3, "step"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "step"),
            #[cfg(feature = "multibody")]
            (DB, "step"),
            #[cfg(feature = "spatial")]
            (PK, "step"),
            #[cfg(feature = "spatial")]
            (BI, "step"),
            #[cfg(feature = "spatial")]
            (CU, "step"),
        ],
    },
    Flag {
        long: "duration",
        unit: "s",
        help: "Longest simulated time (> 0); a run still going then ends Unfinished (the meter stick's default grows with the fingers' travel time)",
        fields: &[
            (M, "max_time"),
            #[cfg(feature = "spatial")]
            (M3, "max_time"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "max_time"),
            #[cfg(feature = "multibody")]
            (DB, "max_time"),
            #[cfg(feature = "spatial")]
            (PK, "max_time"),
            #[cfg(feature = "spatial")]
            (BI, "max_time"),
            #[cfg(feature = "spatial")]
            (CU, "max_time"),
        ],
    },
    Flag {
        long: "stick-speed",
        unit: "m/s",
        help: "A touching contact whose slip speed is at most this sticks (>= 0)",
        fields: &[
            (M, "stick_speed"),
            #[cfg(feature = "spatial")]
            (M3, "stick_speed"),
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
            #[cfg(feature = "stack-3d")]
            (S3, "stick_speed"),
            #[cfg(feature = "multibody")]
            (DB, "stick_speed"),
            #[cfg(feature = "spatial")]
            (PK, "stick_speed"),
            #[cfg(feature = "spatial")]
            (BI, "stick_speed"),
            #[cfg(feature = "spatial")]
            (CU, "stick_speed"),
        ],
    },
    Flag {
        long: "tilt-limit",
        unit: "rad",
        help: "The body has fallen (tipped) when it tilted this far from its start angle (> 0)",
        fields: &[
            (M, "tilt_limit"),
            #[cfg(feature = "spatial")]
            (M3, "tilt_limit"),
            (F, "tilt_limit"),
            #[cfg(feature = "multibody")]
            (BB, "tilt_limit"),
            #[cfg(feature = "multibody")]
            (ST, "tilt_limit"),
            #[cfg(feature = "stack-3d")]
            (S3, "tilt_limit"),
        ],
    },
    Flag {
        long: "drop-limit",
        unit: "m",
        help: "The body has fallen when its centre of mass dropped this far (> 0)",
        fields: &[
            (M, "drop_limit"),
            #[cfg(feature = "spatial")]
            (M3, "drop_limit"),
            #[cfg(feature = "multibody")]
            (ST, "drop_limit"),
            #[cfg(feature = "stack-3d")]
            (S3, "drop_limit"),
        ],
    },
    Flag {
        long: "hold-time",
        unit: "s",
        help: "After the fingers meet, the rod must stay on them this long to balance (>= 0)",
        fields: &[
            (M, "hold_time"),
            #[cfg(feature = "spatial")]
            (M3, "hold_time"),
            (F, "hold_time"),
        ],
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
    Flag {
        long: "blocks",
        unit: "",
        help: "Blocks in the stack: 2 or 3",
        fields: &[
            (ST, "blocks"),
            #[cfg(feature = "stack-3d")]
            (S3, "blocks"),
        ],
    },
    #[cfg(feature = "multibody")]
    Flag {
        long: "overhang",
        unit: "",
        help: "The harmonic overhangs' scale s (0 <= s < 2 x blocks): each block reaches s L / (2k) past the one below; below 1 the stack holds, above it falls",
        fields: &[
            (ST, "overhang"),
            #[cfg(feature = "stack-3d")]
            (S3, "overhang"),
        ],
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
            #[cfg(feature = "stack-3d")]
            (S3, "contact_margin"),
            (DB, "contact_margin"),
        ],
    }, // The scenes in three dimensions' own flags, last.
    #[cfg(feature = "spatial")]
    Flag {
        long: "heading",
        unit: "deg",
        help: "The launch's heading from +x (across the slope) toward down the slope; on a level table counter-clockwise from +x; meter-stick-3d: finger 1's path from the rod's axis toward +y (|heading| <= 80); stack-3d: the overhang's from the table edge's normal +x toward +y (|heading| <= 60)",
        fields: &[
            (PK, "heading"),
            (M3, "heading"),
            #[cfg(feature = "stack-3d")]
            (S3, "heading"),
        ],
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
    #[cfg(feature = "spatial")]
    Flag {
        long: "friction-directions",
        unit: "",
        help: "0 (the default): Coulomb's circular cone; 3 to 16: the pyramid of that many friction directions \
               that LCP engines use instead (a sliding body's path bends toward them)",
        fields: &[(PK, "friction_directions"), (BI, "friction_directions")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "shape",
        unit: "",
        help: "curling: the base, ring (0: its points on its rim) or disc (1: a uniform disc)",
        fields: &[(CU, "shape")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "points",
        unit: "",
        help: "curling: the points of the base touching the table (a whole number from 4 to 8)",
        fields: &[(CU, "points")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "spin",
        unit: "rad/s",
        help: "curling: the launch spin about the vertical (+z)",
        fields: &[(CU, "spin")],
    },
    #[cfg(feature = "spatial")]
    Flag {
        long: "mu",
        unit: "",
        help: "curling: the coefficient of friction with the table (> 0)",
        fields: &[(CU, "mu")],
    },
];

/// The words a flag takes for its values, `(flag, word, value)`: `--shape ring` is `--shape 0`.
pub const WORDS: &[(&str, &str, f64)] = &[("shape", "ring", 0.0), ("shape", "disc", 1.0)];

/// The value `word` stands for in flag `long` ([`WORDS`]).
#[must_use]
pub fn word_value(long: &str, word: &str) -> Option<f64> {
    WORDS.iter().find(|(f, w, _)| *f == long && *w == word).map(|(_, _, v)| *v)
}

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
