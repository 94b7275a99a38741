//! # meterstick-rig
//!
//! The demo rig, independent of any board: a motor-driven finger carriage under a real meter
//! stick, with lights that show what the model (`meterstick-core`'s meter-stick scene) predicts
//! each finger is doing, and its end of the host link (`meterstick-link`). A board binding
//! (`firmware/`) supplies the pins, the timer and a byte port; everything else is here, and
//! tested on the host (`rig/tests/`: `embedded-hal-mock` pins, an in-memory port).
//!
//! * [`Rig`] (`rig.rs`): the state machine over `embedded-hal` 1.0 pins and delay, one scene
//!   step per [`Rig::tick`]; [`RigConfig`], [`RigPins`], [`RigState`], [`RigFault`],
//!   [`Unperformable`].
//! * [`PresetScene`] and [`PressDetector`] (`controls.rs`): what the link's [`Preset`]s are, and a
//!   button debouncer.
//! * [`HeadlessPin`] and [`NoDelay`] (`headless.rs`): the rig without hardware.
//! * [`session`]: the link session ([`session::Session`]) over a non-blocking byte
//!   [`session::Port`]: commands in, telemetry, events and replies out.
//!
//! `no_std`, no heap, no panic path (the firmware's builds prove it at link time). Feature
//! `defmt`: the rig's types derive `defmt::Format` and it logs through defmt (start, mode
//! switches, outcome, faults); without it the logging compiles to nothing.
#![cfg_attr(not(test), no_std)]
#![deny(missing_docs)]

#[macro_use]
#[allow(unused_macros)]
mod fmt;
mod controls;
mod headless;
mod rig;
pub mod session;

pub use controls::{Preset, PresetScene, PressDetector};
pub use headless::{HeadlessPin, NoDelay};
pub use rig::{ModeLights, Rig, RigConfig, RigError, RigFault, RigPins, RigState, Unperformable};
