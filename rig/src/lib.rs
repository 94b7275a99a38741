//! # meterstick-rig
//!
//! The demo rig, independent of any board: a motor-driven finger carriage under a real meter
//! stick, with lights that show what the model (`meterstick-core`'s meter-stick scene) predicts
//! each finger is doing, and its end of the host link (`meterstick-link`); and the rig of a scene
//! of several bodies (the 3-block stack), whose lights show what the model predicts each
//! interface of a real stack is doing. A board binding
//! (`firmware/`) supplies the pins, the timer and a byte port; everything else is here, and
//! tested on the host (`rig/tests/`: `embedded-hal-mock` pins, an in-memory port).
//!
//! * [`Rig`] (`rig.rs`): the one state machine over any scene a board runs ([`RigScene`],
//!   `rig_scene.rs`) and the [`Actuator`] that follows it (`actuator.rs`), on `embedded-hal` 1.0
//!   pins ([`RigPins`]: a [`ModeLights`] per finger or interface, `lights.rs`), one scene step per
//!   [`Rig::tick`]; [`RigState`], [`RigFault`], [`RigError`]. [`MeterStickRig`]: the meter stick
//!   with its [`Carriage`]; [`StackRig`]: the 3-block stack, [`NoActuator`].
//! * [`RigConfig`] and [`Unperformable`] (`config.rs`): what a board's rig can perform.
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
mod actuator;
mod config;
mod controls;
mod headless;
mod interface;
mod lights;
mod rig;
mod rig_scene;
pub mod session;

pub use actuator::{Actuator, Carriage, CarriedFinger, NoActuator};
pub use config::{RigConfig, Unperformable};
pub use controls::{Preset, PresetScene, PressDetector};
pub use headless::{HeadlessPin, NoDelay};
pub use interface::InterfaceMode;
pub use lights::ModeLights;
pub use rig::{MeterStickRig, Rig, RigError, RigFault, RigPins, RigState, StackRig};
pub use rig_scene::RigScene;
