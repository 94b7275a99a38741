//! Scenes on the planar contact core ([`crate::planar`]): each owns its supports' motion, its
//! outcome and its measured quantities, as `docs/scenes.md` defines them.
//!
//! * [`MeterStick`]: the paper's rod on two fingers (6x6 or 8x8), with the meeting point and the
//!   eq. 21 switches;
//! * [`Incline`]: a block on an inclined plane, with its sliding acceleration;
//! * [`Ladder`]: a rod against a wall, with the height at which its top leaves the wall.
//!
//! All implement [`Scene`] and run to an [`Outcome`]; parameters are validated first ([`crate::ParamError`]); a step that
//! fails ends the run with [`Outcome::Failed`] and the state before it. A scene of your own is about
//! a hundred lines on [`crate::planar::Stepper`]: see `core/examples/three_fingers.rs`.

mod incline;
mod ladder;
mod meter_stick;
mod outcome;
mod scene_trait;

pub use incline::{Incline, InclineParams};
pub use ladder::{Ladder, LadderParams};
pub use meter_stick::{Meeting, MeterStick, MeterStick6, MeterStick8, MeterStickParams};
pub use outcome::Outcome;
pub use scene_trait::Scene;
