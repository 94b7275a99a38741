//! The scenes and their parameter flags, as the page names them: the same names, units and field
//! mapping as `host-sim`'s command line (`host-sim/src/scenes.rs`, `FLAGS`), so that a page URL
//! `?scene=meter-stick&speed=0.1&x1=-0.35` and `host-sim scene --speed 0.1 --x1 -0.35` describe
//! the same run. `host-sim` depends on `clap` and `std`, so the table is repeated here; the host
//! test `tests/host_sim.rs` checks that both tables are equal, entry for entry.

use meterstick_core::scene::{InclineParams, LadderParams, MeterStickParams};

/// A scene the page can run (`docs/scenes.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneKind {
    /// The paper's rod on two fingers.
    MeterStick,
    /// A block on an inclined plane.
    Incline,
    /// A rod leaning against a wall.
    Ladder,
}

impl SceneKind {
    /// Every scene, in the order of their numbers ([`Self::from_index`]).
    pub const ALL: [Self; 3] = [Self::MeterStick, Self::Incline, Self::Ladder];

    /// The scene's name on the command line and in the page's URL, e.g. `meter-stick`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::MeterStick => "meter-stick",
            Self::Incline => "incline",
            Self::Ladder => "ladder",
        }
    }

    /// The scene with number `i` (0 meter stick, 1 incline, 2 ladder).
    #[must_use]
    pub const fn from_index(i: u32) -> Option<Self> {
        match i {
            0 => Some(Self::MeterStick),
            1 => Some(Self::Incline),
            2 => Some(Self::Ladder),
            _ => None,
        }
    }

    /// The core's field names of this scene's parameters, in declaration order.
    #[must_use]
    pub fn field_names(self) -> &'static [&'static str] {
        match self {
            Self::MeterStick => MeterStickParams::<f64>::NAMES,
            Self::Incline => InclineParams::<f64>::NAMES,
            Self::Ladder => LadderParams::<f64>::NAMES,
        }
    }
}

/// One parameter flag.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Flag {
    /// The flag's name (the CLI's `--name` without `--`; the URL's query key).
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

use SceneKind::{Incline as I, Ladder as L, MeterStick as M};

/// Every scene flag, in `host-sim`'s order (which decides which complaint comes first).
pub const FLAGS: &[Flag] = &[
    Flag {
        long: "speed",
        unit: "m/s",
        help: "Finger 1's velocity (+x: toward finger 2)",
        fields: &[(M, "finger1_velocity")],
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
        fields: &[(M, "finger1_x")],
    },
    Flag {
        long: "x2",
        unit: "m",
        help: "Start x of finger 2 (> x1 + finger width)",
        fields: &[(M, "finger2_x")],
    },
    Flag { long: "y1", unit: "m", help: "Height of finger 1's tip", fields: &[(M, "finger1_y")] },
    Flag { long: "y2", unit: "m", help: "Height of finger 2's tip", fields: &[(M, "finger2_y")] },
    Flag {
        long: "finger-width",
        unit: "m",
        help: "Approaching fingers stop when their tips are this far apart (>= 0)",
        fields: &[(M, "finger_width")],
    },
    Flag {
        long: "mu-s",
        unit: "",
        help: "Static friction coefficient (>= 0)",
        fields: &[(M, "mu_static"), (I, "mu_static")],
    },
    Flag {
        long: "mu-k",
        unit: "",
        help: "Kinetic friction coefficient (0 <= mu-k <= mu-s)",
        fields: &[(M, "mu_kinetic"), (I, "mu_kinetic")],
    },
    Flag {
        long: "mu-floor",
        unit: "",
        help: "Friction coefficient at the floor, static and kinetic (>= 0)",
        fields: &[(L, "mu_floor")],
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
        help: "Slope angle (incline, 0 <= a < 90) or start angle from the floor (ladder, 0 < a < 90)",
        fields: &[(I, "angle"), (L, "angle")],
    },
    Flag {
        long: "mass",
        unit: "kg",
        help: "Mass of the body (> 0)",
        fields: &[(M, "rod_mass"), (I, "mass"), (L, "mass")],
    },
    Flag { long: "length", unit: "m", help: "Rod length (> 0)", fields: &[(M, "rod_length"), (L, "length")] },
    Flag {
        long: "thickness",
        unit: "m",
        help: "Rod thickness (> 0)",
        fields: &[(M, "rod_thickness"), (L, "thickness")],
    },
    Flag { long: "width", unit: "m", help: "Block width along the slope (> 0)", fields: &[(I, "width")] },
    Flag { long: "height", unit: "m", help: "Block height (> 0)", fields: &[(I, "height")] },
    Flag {
        long: "gravity",
        unit: "m/s^2",
        help: "Gravity (>= 0)",
        fields: &[(M, "gravity"), (I, "gravity"), (L, "gravity")],
    },
    Flag { long: "h", unit: "s", help: "Time step (> 0)", fields: &[(M, "step"), (I, "step"), (L, "step")] },
    Flag {
        long: "duration",
        unit: "s",
        help: "Longest simulated time (> 0); a run still going then ends Unfinished (the meter stick's default grows with the fingers' travel time)",
        fields: &[(M, "max_time"), (I, "max_time"), (L, "max_time")],
    },
    Flag {
        long: "stick-speed",
        unit: "m/s",
        help: "A touching contact whose slip speed is at most this sticks (>= 0)",
        fields: &[(M, "stick_speed"), (I, "stick_speed"), (L, "stick_speed")],
    },
    Flag {
        long: "tilt-limit",
        unit: "rad",
        help: "The rod has fallen when it tilted more than this from its start angle (> 0)",
        fields: &[(M, "tilt_limit")],
    },
    Flag {
        long: "drop-limit",
        unit: "m",
        help: "The rod has fallen when its centre of mass dropped this far (> 0)",
        fields: &[(M, "drop_limit")],
    },
    Flag {
        long: "hold-time",
        unit: "s",
        help: "After the fingers meet, the rod must stay on them this long to balance (>= 0)",
        fields: &[(M, "hold_time")],
    },
];

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
