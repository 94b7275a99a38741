//! The host's end of the rig's link (`meterstick-link`), over its [`Link`]
//! (`link/src/host.rs`: a serial port or TCP, reports decoded on a thread): the parameters read
//! and set ([`read_params`], [`apply_params`]), a run recorded in `host-sim run`'s form
//! ([`record_run`]: the telemetry frames as rows; `along1/along2` computed from the state after
//! the step, as the rig sends them with the switch events only, and the supports at the
//! fingers' reported `x` and their parameter heights), and the run compared with the host's f32
//! build of the same scene ([`compare`]: bit-identical checksum and events expected); the stack's
//! run the same way ([`record_stack_run`], [`compare_stack`]: `stack.rs`).
//!
//! `host-sim monitor` ([`crate::commands::monitor`]) and the end-to-end tests
//! (`tests/tests/link_checks/`) drive it.
//!
//! [`Link`]: meterstick_link::host::Link

mod client;
mod comparison;
mod recording;
mod stack;

pub use client::{Refused, apply_params, read_params};
pub use comparison::{RigComparison, compare};
pub use recording::{Margin, Observer, Recording, mode_of, outcome_of, record_run};
pub use stack::{
    BodiesFrame, InterfaceSwitch, StackComparison, StackRecording, compare_stack, interface_mode,
    read_stack_params, record_stack_run,
};
