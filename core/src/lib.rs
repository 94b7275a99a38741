//! # meterstick-core
//!
//! A `no_std`, heap-free simulation core for planar rigid contact, born from the meter-stick trick
//! (Leong & Lv, "Linear Complementarity Problem Simulation of The Meter Stick Trick"): one rigid
//! body on supports the scene moves, contact modes (stick, slide, separate) emerging from a linear
//! complementarity problem solved by Lemke's method every step. The model is written out in
//! `docs/formulation.md`, the scenes in `docs/scenes.md`.
//!
//! * [`lcp`]: the statically sized Lemke solver ([`lcp::Lemke`]) and its verification.
//! * [`planar`]: the generic stepper: a body, its contacts, a friction [`planar::Layout`] that
//!   fixes the LCP size at compile time, supports a scene moves.
//! * [`scene`]: the meter stick (6x6 or 8x8), a block on an incline, a ladder.
//! * [`Real`]: the scalar trait (`f32` on a microcontroller, `f64` on a host).
//! * `spatial` (feature `spatial`): a body with six degrees of freedom on a plane, with isotropic
//!   friction.
//! * [`soft_float`]: `f32` multiplication on the bits for cores without an FPU (the firmware's
//!   Cortex-M0 builds install it as `__aeabi_fmul`).
//!
//! Features: `defmt` (public types derive `defmt::Format`; logging goes to defmt, and compiles to
//! nothing without it), `fallback` (default: a step of a reduced friction layout whose dropped
//! direction is needed is solved again in the full layout; without it no full-layout code is
//! linked and such a step ends the run). The demo rig's control loop over `embedded-hal` pins and
//! its end of the host link are the `meterstick-rig` crate (`rig/`).
#![cfg_attr(not(test), no_std)]
#![deny(missing_docs)]

#[macro_use]
#[allow(unused_macros)]
mod fmt;
pub mod lcp;
#[cfg(feature = "fallback")]
mod load;
pub mod multibody;
mod params;
pub mod planar;
mod real;
pub mod rule;
mod run_stats;
pub mod scene;
mod slot;
pub mod soft_float;
#[cfg(feature = "spatial")]
pub mod spatial;
mod step_error;

pub use params::{Check, ParamError, check_fields};
pub use real::Real;
pub use run_stats::RunStats;
pub use step_error::StepError;

/// The `nalgebra` this crate is built with (its `SMatrix`/`SVector` appear in the API).
pub use nalgebra;

/// The version of this crate.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
