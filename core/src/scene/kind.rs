//! The scenes of the catalogue by kind ([`SceneKind`]: name, contacts, field names) and any
//! scene's parameters ([`SceneParams`]: get/set by field name, validation in a precision). What
//! the front ends say of them (titles, flags, refusals in English) is `meterstick-catalogue`'s
//! (`catalogue/`), which the firmware does not link.
//!
//! **Adding a scene**: its module (the scene, its `params!`), a [`SceneKind`] variant (its name and
//! contacts below), a [`SceneParams`] variant (the `match` arms below), its arm in
//! [`SceneParams::build`] (`registry.rs`) and its entry in `meterstick-catalogue`. A scene of
//! several bodies: its module in `crate::multibody::scenes` with its [`MultibodyScene`] (the
//! `multibody_scene!` line there), its variants here ([`SceneKind::is_multibody`] true,
//! `contacts` 0; appended last, after the page's scenes; each behind the feature
//! `scenes-multibody`, as its catalogue entry is behind the catalogue's `multibody`), its arm in
//! [`SceneParams::build_multibody`], its catalogue entry (its own flags after the page's), and in
//! `host-sim/src/multibody/` its reference and law (`Measured::of` in
//! `host-sim/src/trajectory/mod.rs` for its measures). A scene in three dimensions: its module in
//! `core/src/scene/spatial/` implementing `SpatialScene` (its view is `SpatialView`), its variants
//! here (`is_spatial` true, `contacts` 0; each behind the feature `scenes-spatial`, as its
//! catalogue entry is behind the catalogue's `spatial`; the stack in three dimensions behind
//! `scenes-stack-3d` and the catalogue's `stack-3d`), its arm in `build_spatial`
//! (`view/build.rs`) and in `view/held.rs`'s `SpaceIn`, and in `host-sim/src/bodies/` its
//! reference run and law.
//!
//! [`MultibodyScene`]: crate::multibody::scenes::MultibodyScene

use core::fmt;

#[cfg(any(feature = "scenes-multibody", feature = "scenes-stack-3d"))]
use super::stack_setup::{StackSetup, with_blocks};
use super::{
    CylinderParams, InclineParams, LadderParams, MeterStickParams, PainleveParams, ThreeFingersParams,
};
#[cfg(feature = "scenes-multibody")]
use crate::multibody::scenes::{BlockOnBlockParams, DiscOnBoardParams, StackParams, TableclothParams};
use crate::params::ParamError;
use crate::real::Real;
#[cfg(feature = "scenes-stack-3d")]
use crate::scene::spatial::Stack3dParams;
#[cfg(feature = "scenes-spatial")]
use crate::scene::spatial::{BilliardParams, CurlingParams, MeterStick3dParams, PuckParams};

/// A scene of the catalogue (`docs/scenes.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SceneKind {
    /// The paper's rod on two fingers.
    MeterStick,
    /// A block on an inclined plane.
    Incline,
    /// A rod leaning against a wall.
    Ladder,
    /// A rod on three fingers (`core/examples/three_fingers.rs`).
    ThreeFingers,
    /// A round body released on an incline: it rolls or slides.
    Cylinder,
    /// Painlevé's paradox: a rod whose end slides on a rough floor jams.
    Painleve,
    /// A block on a block pulled along a floor (several bodies, [`crate::multibody`]).
    #[cfg(feature = "scenes-multibody")]
    BlockOnBlock,
    /// A board pulled from under a block (several bodies).
    #[cfg(feature = "scenes-multibody")]
    Tablecloth,
    /// Two or three blocks stacked over a table's edge (several bodies).
    #[cfg(feature = "scenes-multibody")]
    Stack,
    /// A disc on a board pulled along a floor: it rolls or slides (several bodies).
    #[cfg(feature = "scenes-multibody")]
    DiscOnBoard,
    /// A puck launched across a table or an incline (three dimensions, `crate::spatial`).
    #[cfg(feature = "scenes-spatial")]
    Puck,
    /// A billiard ball struck with spin: it slides, then rolls (three dimensions).
    #[cfg(feature = "scenes-spatial")]
    Billiard,
    /// A ring or a uniform disc sliding and spinning: both stop together (three dimensions).
    #[cfg(feature = "scenes-spatial")]
    Curling,
    /// The paper's rod on two fingers, finger 1 moving along a path at a heading to the rod
    /// (three dimensions).
    #[cfg(feature = "scenes-spatial")]
    MeterStick3d,
    /// Two or three blocks stacked over a table's edge, the overhang at a heading to the edge
    /// (three dimensions, several bodies).
    #[cfg(feature = "scenes-stack-3d")]
    Stack3d,
}

/// The number of scenes this build names ([`SceneKind::ALL`]).
const SCENE_COUNT: usize = 6
    + if cfg!(feature = "scenes-multibody") { 4 } else { 0 }
    + if cfg!(feature = "scenes-spatial") { 4 } else { 0 }
    + if cfg!(feature = "scenes-stack-3d") { 1 } else { 0 };

/// The most quantities a scene measures ([`super::Scene::measured`]; `meterstick-catalogue` names
/// them).
pub const MAX_MEASURES: usize = 3;

impl SceneKind {
    /// Every scene, in the order of their numbers ([`Self::from_index`]): the scenes of one body,
    /// then those of several bodies (feature `scenes-multibody`), then those in three dimensions
    /// (feature `scenes-spatial`).
    pub const ALL: [Self; SCENE_COUNT] = [
        Self::MeterStick,
        Self::Incline,
        Self::Ladder,
        Self::ThreeFingers,
        Self::Cylinder,
        Self::Painleve,
        #[cfg(feature = "scenes-multibody")]
        Self::BlockOnBlock,
        #[cfg(feature = "scenes-multibody")]
        Self::Tablecloth,
        #[cfg(feature = "scenes-multibody")]
        Self::Stack,
        #[cfg(feature = "scenes-multibody")]
        Self::DiscOnBoard,
        #[cfg(feature = "scenes-spatial")]
        Self::Puck,
        #[cfg(feature = "scenes-spatial")]
        Self::Billiard,
        #[cfg(feature = "scenes-spatial")]
        Self::Curling,
        #[cfg(feature = "scenes-spatial")]
        Self::MeterStick3d,
        #[cfg(feature = "scenes-stack-3d")]
        Self::Stack3d,
    ];

    /// The scene's name on the command line and in the page's URL, e.g. `meter-stick`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::MeterStick => "meter-stick",
            Self::Incline => "incline",
            Self::Ladder => "ladder",
            Self::ThreeFingers => "three-fingers",
            Self::Cylinder => "cylinder",
            Self::Painleve => "painleve",
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock => "block-on-block",
            #[cfg(feature = "scenes-multibody")]
            Self::Tablecloth => "tablecloth",
            #[cfg(feature = "scenes-multibody")]
            Self::Stack => "stack",
            #[cfg(feature = "scenes-multibody")]
            Self::DiscOnBoard => "disc-on-board",
            #[cfg(feature = "scenes-spatial")]
            Self::Puck => "puck",
            #[cfg(feature = "scenes-spatial")]
            Self::Billiard => "billiard",
            #[cfg(feature = "scenes-spatial")]
            Self::Curling => "curling",
            #[cfg(feature = "scenes-spatial")]
            Self::MeterStick3d => "meter-stick-3d",
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d => "stack-3d",
        }
    }

    /// Its contacts (`K` of its [`super::Scene`]); 0 for a scene of several bodies, whose
    /// candidate contacts come and go ([`Self::is_multibody`]), and for a scene in three
    /// dimensions ([`Self::is_spatial`]), which is not a [`super::Scene`].
    #[must_use]
    pub const fn contacts(self) -> usize {
        match self {
            Self::MeterStick | Self::Incline | Self::Ladder => 2,
            Self::ThreeFingers => 3,
            Self::Cylinder | Self::Painleve => 1,
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock | Self::Tablecloth | Self::Stack | Self::DiscOnBoard => 0,
            #[cfg(feature = "scenes-spatial")]
            Self::Puck | Self::Billiard | Self::Curling | Self::MeterStick3d => 0,
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d => 0,
        }
    }

    /// `true` for a scene in three dimensions (`super::spatial`, feature `scenes-spatial`): it
    /// is built by [`SceneParams::build_view`] only, and has no LCP layout to choose.
    #[must_use]
    pub const fn is_spatial(self) -> bool {
        #[cfg(feature = "scenes-spatial")]
        return match self {
            Self::Puck | Self::Billiard | Self::Curling | Self::MeterStick3d => true,
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d => true,
            _ => false,
        };
        #[cfg(not(feature = "scenes-spatial"))]
        {
            let _ = self;
            false
        }
    }

    /// `true` for a scene of several bodies ([`crate::multibody`]): it is built by
    /// [`SceneParams::build_multibody`], not [`SceneParams::build`] (which refuses it), and has
    /// no LCP layout to choose (its LCP is the full form, sized by its candidate contacts).
    #[must_use]
    pub const fn is_multibody(self) -> bool {
        #[cfg(feature = "scenes-multibody")]
        return matches!(self, Self::BlockOnBlock | Self::Tablecloth | Self::Stack | Self::DiscOnBoard);
        #[cfg(not(feature = "scenes-multibody"))]
        {
            let _ = self;
            false
        }
    }

    /// `true` for a scene whose LCP layout a driver chooses ([`super::LcpLayout`]: reduced or
    /// full, [`SceneParams::build_view`]'s `layout`); `false` for one that solves its one form
    /// (a scene of several bodies: the full form, sized by its candidate contacts; a scene in
    /// three dimensions: one friction line a contact).
    #[must_use]
    pub const fn has_layout_choice(self) -> bool {
        !self.is_multibody() && !self.is_spatial()
    }

    /// The scene's number (its index in [`Self::ALL`]).
    #[must_use]
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The scene with number `i`.
    #[must_use]
    pub const fn from_index(i: u32) -> Option<Self> {
        if (i as usize) < Self::ALL.len() { Some(Self::ALL[i as usize]) } else { None }
    }

    /// The scene called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The core's field names of this scene's parameters, in declaration order.
    #[must_use]
    pub fn field_names(self) -> &'static [&'static str] {
        match self {
            Self::MeterStick => MeterStickParams::<f64>::NAMES,
            Self::Incline => InclineParams::<f64>::NAMES,
            Self::Ladder => LadderParams::<f64>::NAMES,
            Self::ThreeFingers => ThreeFingersParams::<f64>::NAMES,
            Self::Cylinder => CylinderParams::<f64>::NAMES,
            Self::Painleve => PainleveParams::<f64>::NAMES,
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock => BlockOnBlockParams::<f64>::NAMES,
            #[cfg(feature = "scenes-multibody")]
            Self::Tablecloth => TableclothParams::<f64>::NAMES,
            #[cfg(feature = "scenes-multibody")]
            Self::Stack => &STACK_FIELDS,
            #[cfg(feature = "scenes-multibody")]
            Self::DiscOnBoard => DiscOnBoardParams::<f64>::NAMES,
            #[cfg(feature = "scenes-spatial")]
            Self::Puck => PuckParams::<f64>::NAMES,
            #[cfg(feature = "scenes-spatial")]
            Self::Billiard => BilliardParams::<f64>::NAMES,
            #[cfg(feature = "scenes-spatial")]
            Self::Curling => CurlingParams::<f64>::NAMES,
            #[cfg(feature = "scenes-spatial")]
            Self::MeterStick3d => MeterStick3dParams::<f64>::NAMES,
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d => &STACK_3D_FIELDS,
        }
    }
}

/// Serialised as its [`SceneKind::name`] (`meter-stick-3d`).
#[cfg(feature = "serde")]
impl serde::Serialize for SceneKind {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl fmt::Display for SceneKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(feature = "scenes-multibody")]
/// The stack's fields: `blocks`, then [`StackParams`]'s.
const STACK_FIELDS: [&str; 14] = with_blocks(StackParams::<f64>::NAMES);

#[cfg(feature = "scenes-stack-3d")]
/// The stack in three dimensions' fields: `blocks`, then [`Stack3dParams`]'s.
const STACK_3D_FIELDS: [&str; 16] = with_blocks(Stack3dParams::<f64>::NAMES);

/// Any scene's parameters in the core's units (SI, radians), f64 as given; cast to the run's
/// precision when run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneParams {
    /// The meter stick.
    MeterStick(MeterStickParams<f64>),
    /// The block on an incline.
    Incline(InclineParams<f64>),
    /// The ladder.
    Ladder(LadderParams<f64>),
    /// The rod on three fingers.
    ThreeFingers(ThreeFingersParams<f64>),
    /// The round body on an incline.
    Cylinder(CylinderParams<f64>),
    /// Painlevé's rod.
    Painleve(PainleveParams<f64>),
    /// Block-on-block.
    #[cfg(feature = "scenes-multibody")]
    BlockOnBlock(BlockOnBlockParams<f64>),
    /// The tablecloth.
    #[cfg(feature = "scenes-multibody")]
    Tablecloth(TableclothParams<f64>),
    /// The stack.
    #[cfg(feature = "scenes-multibody")]
    Stack(StackSetup<StackParams<f64>>),
    /// Disc-on-board.
    #[cfg(feature = "scenes-multibody")]
    DiscOnBoard(DiscOnBoardParams<f64>),
    /// The puck.
    #[cfg(feature = "scenes-spatial")]
    Puck(PuckParams<f64>),
    /// The billiard ball.
    #[cfg(feature = "scenes-spatial")]
    Billiard(BilliardParams<f64>),
    /// The curling stone.
    #[cfg(feature = "scenes-spatial")]
    Curling(CurlingParams<f64>),
    /// The meter stick in three dimensions.
    #[cfg(feature = "scenes-spatial")]
    MeterStick3d(MeterStick3dParams<f64>),
    /// The stack in three dimensions.
    #[cfg(feature = "scenes-stack-3d")]
    Stack3d(StackSetup<Stack3dParams<f64>>),
}

impl SceneParams {
    /// The scene with the core's defaults.
    #[must_use]
    pub fn defaults(kind: SceneKind) -> Self {
        match kind {
            SceneKind::MeterStick => Self::MeterStick(MeterStickParams::default()),
            SceneKind::Incline => Self::Incline(InclineParams::default()),
            SceneKind::Ladder => Self::Ladder(LadderParams::default()),
            SceneKind::ThreeFingers => Self::ThreeFingers(ThreeFingersParams::default()),
            SceneKind::Cylinder => Self::Cylinder(CylinderParams::default()),
            SceneKind::Painleve => Self::Painleve(PainleveParams::default()),
            #[cfg(feature = "scenes-multibody")]
            SceneKind::BlockOnBlock => Self::BlockOnBlock(BlockOnBlockParams::default()),
            #[cfg(feature = "scenes-multibody")]
            SceneKind::Tablecloth => Self::Tablecloth(TableclothParams::default()),
            #[cfg(feature = "scenes-multibody")]
            SceneKind::Stack => Self::Stack(StackSetup::default()),
            #[cfg(feature = "scenes-multibody")]
            SceneKind::DiscOnBoard => Self::DiscOnBoard(DiscOnBoardParams::default()),
            #[cfg(feature = "scenes-spatial")]
            SceneKind::Puck => Self::Puck(PuckParams::default()),
            #[cfg(feature = "scenes-spatial")]
            SceneKind::Billiard => Self::Billiard(BilliardParams::default()),
            #[cfg(feature = "scenes-spatial")]
            SceneKind::Curling => Self::Curling(CurlingParams::default()),
            #[cfg(feature = "scenes-spatial")]
            SceneKind::MeterStick3d => Self::MeterStick3d(MeterStick3dParams::default()),
            #[cfg(feature = "scenes-stack-3d")]
            SceneKind::Stack3d => Self::Stack3d(StackSetup::default()),
        }
    }

    /// Which scene.
    #[must_use]
    pub const fn kind(&self) -> SceneKind {
        match self {
            Self::MeterStick(_) => SceneKind::MeterStick,
            Self::Incline(_) => SceneKind::Incline,
            Self::Ladder(_) => SceneKind::Ladder,
            Self::ThreeFingers(_) => SceneKind::ThreeFingers,
            Self::Cylinder(_) => SceneKind::Cylinder,
            Self::Painleve(_) => SceneKind::Painleve,
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock(_) => SceneKind::BlockOnBlock,
            #[cfg(feature = "scenes-multibody")]
            Self::Tablecloth(_) => SceneKind::Tablecloth,
            #[cfg(feature = "scenes-multibody")]
            Self::Stack(_) => SceneKind::Stack,
            #[cfg(feature = "scenes-multibody")]
            Self::DiscOnBoard(_) => SceneKind::DiscOnBoard,
            #[cfg(feature = "scenes-spatial")]
            Self::Puck(_) => SceneKind::Puck,
            #[cfg(feature = "scenes-spatial")]
            Self::Billiard(_) => SceneKind::Billiard,
            #[cfg(feature = "scenes-spatial")]
            Self::Curling(_) => SceneKind::Curling,
            #[cfg(feature = "scenes-spatial")]
            Self::MeterStick3d(_) => SceneKind::MeterStick3d,
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d(_) => SceneKind::Stack3d,
        }
    }

    /// The value of a field (core name).
    #[must_use]
    pub fn get(&self, field: &str) -> Option<f64> {
        match self {
            Self::MeterStick(p) => p.get(field),
            Self::Incline(p) => p.get(field),
            Self::Ladder(p) => p.get(field),
            Self::ThreeFingers(p) => p.get(field),
            Self::Cylinder(p) => p.get(field),
            Self::Painleve(p) => p.get(field),
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock(p) => p.get(field),
            #[cfg(feature = "scenes-multibody")]
            Self::Tablecloth(p) => p.get(field),
            #[cfg(feature = "scenes-multibody")]
            Self::Stack(p) => p.get(field),
            #[cfg(feature = "scenes-multibody")]
            Self::DiscOnBoard(p) => p.get(field),
            #[cfg(feature = "scenes-spatial")]
            Self::Puck(p) => p.get(field),
            #[cfg(feature = "scenes-spatial")]
            Self::Billiard(p) => p.get(field),
            #[cfg(feature = "scenes-spatial")]
            Self::Curling(p) => p.get(field),
            #[cfg(feature = "scenes-spatial")]
            Self::MeterStick3d(p) => p.get(field),
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d(p) => p.get(field),
        }
    }

    /// Sets a field (core name); `false` when the scene has none of that name.
    pub fn set(&mut self, field: &str, value: f64) -> bool {
        match self {
            Self::MeterStick(p) => p.set(field, value),
            Self::Incline(p) => p.set(field, value),
            Self::Ladder(p) => p.set(field, value),
            Self::ThreeFingers(p) => p.set(field, value),
            Self::Cylinder(p) => p.set(field, value),
            Self::Painleve(p) => p.set(field, value),
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock(p) => p.set(field, value),
            #[cfg(feature = "scenes-multibody")]
            Self::Tablecloth(p) => p.set(field, value),
            #[cfg(feature = "scenes-multibody")]
            Self::Stack(p) => p.set(field, value),
            #[cfg(feature = "scenes-multibody")]
            Self::DiscOnBoard(p) => p.set(field, value),
            #[cfg(feature = "scenes-spatial")]
            Self::Puck(p) => p.set(field, value),
            #[cfg(feature = "scenes-spatial")]
            Self::Billiard(p) => p.set(field, value),
            #[cfg(feature = "scenes-spatial")]
            Self::Curling(p) => p.set(field, value),
            #[cfg(feature = "scenes-spatial")]
            Self::MeterStick3d(p) => p.set(field, value),
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d(p) => p.set(field, value),
        }
    }

    /// Checks the parameters in f64 and again after rounding to `T` (a value may overflow f32,
    /// or round to an invalid one). A scene of one body whose registry rows this build leaves out
    /// (features `scenes-k1`..`scenes-k3`, as [`Self::build`]) is refused, unchecked: a driver
    /// that cannot run it links none of its checks (the page's module of several bodies).
    ///
    /// # Errors
    /// The core's first complaint; `OutOfRange("scene")` for a scene this build leaves out.
    pub fn validate_as<T: Real>(&self) -> Result<(), ParamError> {
        match self {
            #[cfg(feature = "scenes-k2")]
            Self::MeterStick(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-k2")]
            Self::Incline(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-k2")]
            Self::Ladder(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-k3")]
            Self::ThreeFingers(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-k1")]
            Self::Cylinder(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-k1")]
            Self::Painleve(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-multibody")]
            Self::BlockOnBlock(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-multibody")]
            Self::Tablecloth(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-multibody")]
            Self::Stack(p) => p.validate_as::<T>(),
            #[cfg(feature = "scenes-multibody")]
            Self::DiscOnBoard(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-spatial")]
            Self::Puck(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-spatial")]
            Self::Billiard(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-spatial")]
            Self::Curling(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-spatial")]
            Self::MeterStick3d(p) => {
                p.validate()?;
                p.cast::<T>().validate()
            }
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d(p) => p.validate_as::<T>(),
            #[allow(unreachable_patterns)] // every scene, when the build has them all
            _ => Err(ParamError::OutOfRange("scene")),
        }
    }

    /// The `i`-th field's value, in the order of [`SceneKind::field_names`].
    #[must_use]
    pub fn field(&self, i: usize) -> Option<f64> {
        self.kind().field_names().get(i).and_then(|name| self.get(name))
    }

    /// Every field, `(core name, value)`, in declaration order.
    pub fn fields(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.kind().field_names().iter().map(|name| (*name, self.get(name).unwrap_or(f64::NAN)))
    }

    /// The step `h` (s).
    #[must_use]
    pub fn step(&self) -> f64 {
        self.get("step").unwrap_or(f64::NAN)
    }

    /// The time limit (s).
    #[must_use]
    pub fn max_time(&self) -> f64 {
        self.get("max_time").unwrap_or(f64::NAN)
    }

    /// The steps `h` and the time limit imply (`ceil(max_time / h)`; NaN when undefined).
    #[must_use]
    pub fn steps(&self) -> f64 {
        libm::ceil(self.max_time() / self.step())
    }

    /// The field to blame for `error` (what the user should change): the error's own field, the
    /// kinetic coefficient above the static one, or the finger out of place (the first beyond an
    /// end of the rod, the one out of order; finger 1 when the scene does not say).
    #[must_use]
    pub fn field_at_fault(&self, error: ParamError) -> Option<&'static str> {
        let finger = match (error, self) {
            (ParamError::FingerOutsideRod, Self::MeterStick(p)) => p.finger_outside_rod(),
            (ParamError::FingerOutsideRod, Self::ThreeFingers(p)) => p.finger_outside_rod(),
            (ParamError::FingersCrossed, Self::ThreeFingers(p)) => p.finger_out_of_order(),
            _ => None,
        };
        match error {
            ParamError::KineticAboveStatic => Some("mu_kinetic"),
            ParamError::FingerOutsideRod | ParamError::FingersCrossed => Some(finger.unwrap_or("finger1_x")),
            other => other.field(),
        }
    }

    /// The meter stick's default time limit follows the fingers' travel: at least its default,
    /// and long enough for the fingers to meet and the rod to hold (`2 x` travel time + hold time
    /// + 1 s), so that a slow finger does not end "Unfinished" by default. Other scenes keep theirs.
    ///
    /// Returns `true` when it raised the time limit (a refusal then says so).
    pub fn follow_travel_time(&mut self) -> bool {
        if let Self::MeterStick(p) = self {
            let closing = p.finger1_velocity - p.finger2_velocity;
            if closing > 0.0 {
                let travel = (p.finger2_x - p.finger1_x - p.finger_width).max(0.0) / closing;
                let wanted = 2.0 * travel + p.hold_time + 1.0;
                if wanted.is_finite() && wanted > p.max_time {
                    p.max_time = wanted;
                    return true;
                }
            }
        }
        false
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_is_in_its_place() {
        for (i, kind) in SceneKind::ALL.into_iter().enumerate() {
            assert_eq!(SceneKind::from_index(i as u32), Some(kind));
            assert_eq!(SceneKind::from_name(kind.name()), Some(kind));
            assert_eq!(SceneParams::defaults(kind).kind(), kind);
            assert_eq!(SceneParams::defaults(kind).validate_as::<f32>(), Ok(()), "{kind}");
            for (j, name) in kind.field_names().iter().enumerate() {
                assert!(SceneParams::defaults(kind).field(j).is_some(), "{kind} {name}");
            }
        }
        assert_eq!(SceneKind::from_index(SceneKind::ALL.len() as u32), None);
    }

    /// The stack's blocks are a field like any other: 2 or 3, anything else refused by name.
    #[cfg(feature = "scenes-multibody")]
    #[test]
    fn the_stack_takes_two_or_three_blocks() {
        let mut p = SceneParams::defaults(SceneKind::Stack);
        assert_eq!(SceneKind::Stack.field_names()[1..], *StackParams::<f64>::NAMES);
        for (blocks, ok) in [(2.0, true), (3.0, true), (1.0, false), (2.5, false), (4.0, false)] {
            assert!(p.set("blocks", blocks));
            assert_eq!(p.get("blocks"), Some(blocks));
            let expected = if ok { Ok(()) } else { Err(ParamError::OutOfRange("blocks")) };
            assert_eq!(p.validate_as::<f64>(), expected, "{blocks}");
        }
        assert!(p.set("blocks", f64::NAN));
        assert_eq!(p.validate_as::<f64>(), Err(ParamError::NonFinite("blocks")));
    }

    /// The finger to blame is the one out of place (it was finger 1 for any finger).
    #[test]
    fn the_finger_out_of_place_is_blamed() {
        let mut p = SceneParams::defaults(SceneKind::ThreeFingers);
        assert!(p.set("finger3_x", 0.6));
        let e = p.validate_as::<f64>().unwrap_err();
        assert_eq!((e, p.field_at_fault(e)), (ParamError::FingerOutsideRod, Some("finger3_x")));
        assert!(p.set("finger3_x", -0.1));
        let e = p.validate_as::<f64>().unwrap_err();
        assert_eq!((e, p.field_at_fault(e)), (ParamError::FingersCrossed, Some("finger3_x")));
        let mut p = SceneParams::defaults(SceneKind::MeterStick);
        assert!(p.set("finger2_x", 0.51));
        let e = p.validate_as::<f64>().unwrap_err();
        assert_eq!((e, p.field_at_fault(e)), (ParamError::FingerOutsideRod, Some("finger2_x")));
    }
}
