//! # meterstick-core
//!
//! A `no_std`, heap-free simulation core for the meter-stick trick (Leong & Lv, "Linear
//! Complementarity Problem Simulation of The Meter Stick Trick"): a rod resting on two
//! fingers, one finger moving toward the other, contact modes (stick, slide, separate)
//! emerging from a linear complementarity problem solved by Lemke's method every step.
//!
//! * [`lcp`]: the statically sized Lemke solver ([`lcp::Lemke`]) and its verification.
//! * [`scene`]: the meter-stick scene, 6x6 or 8x8, stepped in f32 or f64.
//! * [`Real`]: the scalar trait (`f32` on a microcontroller, `f64` on a host).
//!
//! * [`rig`] (feature `rig`): the demo rig's control loop over `embedded-hal` 1.0 pins.
//!
//! Features: `defmt` (public types derive `defmt::Format`; logging goes to defmt, and
//! compiles to nothing without it), `fallback-8x8` (default: the 6x6 scene re-solves a step
//! with the 8x8 form when its check fails; without it no 8x8 code is linked), `rig`.
#![cfg_attr(not(test), no_std)]
#![deny(missing_docs)]

#[macro_use]
#[allow(unused_macros)]
mod fmt;
pub mod lcp;
mod real;
#[cfg(feature = "rig")]
pub mod rig;
pub mod scene;

pub use real::Real;

/// The `nalgebra` this crate is built with (its `SMatrix`/`SVector` appear in the API).
pub use nalgebra;

/// The version of this crate.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
