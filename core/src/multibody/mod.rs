//! Several rigid boxes (or discs) resting on each other and on a fixed table (`docs/formulation.md`,
//! "Several bodies"; issue #32): velocities in `3B` coordinates, corner-on-face contacts between a
//! box and the table or between two boxes, rim-on-face contacts of a disc on a box or the table,
//! one LCP per step in the paper's full friction form, solved in the bodies' coordinates from the
//! last step's basis or a neighbour of it, else by Lemke's method
//! ([`crate::lcp::Lemke`]), and verified.
//!
//! * [`System`]: `B` bodies ([`crate::planar::Body`], each of a [`Shape`]), the [`Table`], `P`
//!   resting [`Pair`]s (each with four candidate contacts, [`Candidate`]; a disc's pair one),
//!   external forces and [`SystemSettings`].
//! * [`SystemStepper`]: the step (activity rule, the LCP per unit reference mass in factored form, the
//!   paths free, warm, candidate and Lemke, each answer verified, compensated integration, contact
//!   modes), each pair's summed interface force.
//! * [`scenes`]: block-on-block, the tablecloth and the stack, returning the one
//!   [`crate::scene::Outcome`].
//!
//! A build that steps only single-body scenes links none of this: the steppers and scenes are
//! generic, compiled where something names them (the registry's rows of several bodies, behind the
//! `scenes-multibody` feature; a driver or firmware that builds a scene). The rest of the core names
//! some of it unconditionally: the view of a scene of several bodies, [`crate::scene::MultibodyView`], generic over its scene
//! ([`scenes::MultibodyScene`], [`Shape`], [`RestsOn`]).

mod factored;
mod geometry;
mod resolve;
pub mod scenes;
mod stepper;

pub use crate::RunStats;
pub use crate::StepError;
pub use geometry::{Candidate, CornerFrame, JacobianRow, Pair, RestsOn, Shape, Table};
pub use stepper::{System, SystemSettings, SystemStepReport, SystemStepper};
