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
//! * [`Rig`] (`rig.rs`): the state machine over `embedded-hal` 1.0 pins and delay, one scene
//!   step per [`Rig::tick`]; [`RigConfig`], [`RigPins`], [`RigState`], [`RigFault`],
//!   [`Unperformable`].
//! * [`MultibodyRig`] (`multibody_rig.rs`): the rig of a scene of several bodies ([`RigScene`],
//!   `rig_scene.rs`), one scene step per [`MultibodyRig::tick`], a [`ModeLights`] (`lights.rs`)
//!   per interface; [`StackRig`], the 3-block stack's; [`MultibodyRigPins`],
//!   [`MultibodyRigState`]. It has no host link.
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
mod interface;
mod lights;
mod multibody_rig;
mod rig;
mod rig_scene;
pub mod session;

pub use controls::{Preset, PresetScene, PressDetector};
pub use headless::{HeadlessPin, NoDelay};
pub use interface::InterfaceMode;
pub use lights::ModeLights;
pub use multibody_rig::{MultibodyRig, MultibodyRigPins, MultibodyRigState, StackRig};
pub use rig::{Rig, RigConfig, RigError, RigFault, RigPins, RigState, Unperformable};
pub use rig_scene::RigScene;
