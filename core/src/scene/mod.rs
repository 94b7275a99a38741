//! Scenes on the planar contact core ([`crate::planar`]): each owns its supports' motion, its
//! outcome and its measured quantities, as `docs/scenes.md` defines them.
//!
//! * [`MeterStick`]: the paper's rod on two fingers (6x6 or 8x8), with the meeting point and the
//!   eq. 21 switches;
//! * [`Incline`]: a block on an inclined plane, with its sliding acceleration;
//! * [`Ladder`]: a rod against a wall, with the height at which its top leaves the wall;
//! * [`ThreeFingers`]: a rod on three fingers (`core/examples/three_fingers.rs` with parameters);
//! * [`Cylinder`]: a round body on an incline, rolling or sliding as the analytic law says;
//! * [`Painleve`]: a rod whose sliding end jams on a rough floor (Painlevé's paradox).
//!
//! [`SceneKind`] names them and [`SceneParams`] holds any one's parameters (`kind.rs`; what the
//! front ends say of them is `meterstick-catalogue`'s);
//! [`SceneParams::build`] makes any of them, in a [`Precision`] and an [`LcpLayout`], for a
//! [`SceneVisitor`] (`registry.rs`); the scenes of several bodies ([`crate::multibody::scenes`],
//! [`SceneKind::is_multibody`]) are [`SceneParams::build_multibody`]'s, for a
//! [`MultibodyVisitor`].
//!
//! All implement [`Scene`] and run to an [`Outcome`]; parameters are validated first ([`crate::ParamError`]); a step that
//! fails ends the run with [`Outcome::Failed`] and the state before it. A scene of your own is about
//! a hundred lines on [`crate::planar::Stepper`]: see `core/examples/three_fingers.rs`.
//!
//! [`SceneView`] is one interface over the scenes of every engine, for a driver that names none
//! ([`PlanarView`] over a [`Scene`], [`MultibodyView`] over a scene of several bodies,
//! `spatial::SpatialView` over a scene in three dimensions: `spatial`, feature `scenes-spatial`).

mod cylinder;
mod incline;
mod kind;
mod ladder;
mod meter_stick;
mod outcome;
mod painleve;
mod registry;
mod scene_trait;
#[cfg(feature = "scenes-spatial")]
pub mod spatial;
#[cfg(any(feature = "scenes-multibody", feature = "scenes-stack-3d"))]
mod stack_setup;
mod three_fingers;
mod view;

pub use cylinder::{Cylinder, CylinderParams};
pub use incline::{Incline, InclineParams};
pub use kind::{MAX_MEASURES, SceneKind, SceneParams};
pub use ladder::{Ladder, LadderParams};
pub use meter_stick::{Meeting, MeterStick, MeterStick6, MeterStick8, MeterStickParams};
pub use outcome::{Outcome, OutcomeKind};
pub use painleve::{Jam, Painleve, PainleveParams};
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
pub use registry::{AnyScene, SceneIn};
pub use registry::{LcpLayout, Precision, SceneVisitor};
#[cfg(feature = "scenes-multibody")]
pub use registry::{MAX_BODIES, MultibodyVisitor};
pub use scene_trait::Scene;
#[cfg(any(feature = "scenes-multibody", feature = "scenes-stack-3d"))]
pub use stack_setup::{StackSetup, StackedParams};
pub use three_fingers::{ThreeFingers, ThreeFingersParams};
#[cfg(all(
    any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"),
    feature = "scenes-multibody"
))]
pub use view::AnyView;
#[cfg(feature = "scenes-multibody")]
pub use view::MultibodyViews;
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
pub use view::PlanarViews;
pub use view::{
    Axis, BodyShape, BodyView, ContactView, DIMENSIONS, EventView, FigureName, Force, HeldView, LoadPart,
    MultibodyView, PlanarView, Pose, RunStats, SceneView, StepFigure, StepStats, SupportView, Thing,
    Velocity, ViewReader, ViewVector, ViewVisitor,
};
#[cfg(feature = "scenes-spatial")]
pub use view::{SpatialViews, SpatialViewsIn};
#[cfg(feature = "scenes-stack-3d")]
pub use view::{StackViews, StackViewsIn};
