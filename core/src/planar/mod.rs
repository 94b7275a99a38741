//! The planar contact core: one rigid body against `K` supports, stepped by an LCP per step.
//!
//! The model is that of `docs/formulation.md` (the paper's eqs. 13-18 generalised from two finger
//! contacts to `K` contacts). A scene declares:
//!
//! * the **body** ([`Body`]: a box, with its mass and inertia) and its **contacts** ([`Contact`]:
//!   which [`Feature`] of the body touches a support, with `mu_s` and `mu_k`);
//! * the **layout** of each step's LCP ([`Layout`]): which friction directions each contact keeps,
//!   and from that the LCP size `N`, checked at compile time; optionally a reduced layout with a
//!   full one to fall back to;
//! * each step, where its **supports** are ([`Support`]: a point or a line, position and velocity).
//!
//! The [`Stepper`] does the rest: assembly ([`assemble`](mod@assemble)), the warm-started verified
//! solve, the reduced layout's check and fallback, integration, contact modes ([`ContactMode`]) and
//! the [`StepReport`] with each contact's impulses and mode switches. Scenes built on it are in
//! [`crate::scene`]; `core/examples/three_fingers.rs` writes one outside the crate.
//!
//! # Example: a block at rest on a floor
//! ```
//! use meterstick_core::planar::{
//!     Body, BodyState, Contact, Feature, Layout, Model, Settings, Stepper, Support,
//! };
//!
//! let body = Body::block(1.0_f64, 0.2, 0.1);
//! let corner = |x: f64| Contact { feature: Feature::Point([x, -0.05]), mu_static: 0.5, mu_kinetic: 0.5 };
//! let settings = Settings { step: 1e-3, gravity: 9.81, stick_speed: 1e-5 };
//! let model = Model { body, contacts: [corner(-0.1), corner(0.1)], settings };
//! const FULL: Layout<2, 8> = Layout::full();
//! let floor = Support::fixed_line([0.0, 0.0], [0.0, 1.0]);
//! let mut stepper = Stepper::new(model, FULL, FULL, BodyState::at_rest(0.0, 0.05, 0.0), [floor; 2])?;
//! let report = stepper.step(&[floor; 2])?;
//! // The floor carries the block's weight, half on each corner: m g h / 2 each.
//! let weight = 1.0 * 9.81 * 1e-3;
//! assert!((report.contacts[0].normal_impulse - weight / 2.0).abs() < 1e-12);
//! assert!(report.state.vy.abs() < 1e-12);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

// In the order they depend on one another (each imports only modules above it, and `body`,
// `contact`, `layout`): the step's inputs, its factored rows and their basis solve, the
// neighbouring bases, the dense form, the solve strategy, the reports, the stepper.
mod body;
mod checksum;
mod contact;
mod events;
mod layout;
mod model;

pub(crate) mod inputs;

mod factored;

mod candidates;

pub mod assemble;

mod strategy;

pub(crate) mod resolve;

mod report;

mod stepper;

pub use crate::{RunStats, StepError};
pub use body::{Body, BodyState};
pub use checksum::Checksum;
pub use contact::{Contact, ContactFrame, ContactMode, Feature, Pose, Support};
pub use events::{EventLog, SwitchEvent};
pub use factored::{BasisAnswer, Declined, FactoredLcp};
pub(crate) use factored::{MU_WEIGHTED_FROM, cone_scale};
pub use layout::{Direction, Layout, Tangents, Variable};
pub(crate) use model::check_friction;
pub use model::{Model, Settings};
pub use report::{
    ContactReport, FRICTION_ROUND_OFF_LIMIT, ROUND_OFF_LIMIT, StepReport, friction_beyond_precision,
    friction_limit,
};
pub use stepper::Stepper;
pub use strategy::{PathCounts, SolvePath};
