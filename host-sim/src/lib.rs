//! # meterstick-host-sim
//!
//! The std host harness around `meterstick-core` and the `host-sim` command line ([`cli`]:
//! its arguments, dispatch and exit status). The commands are in [`commands`] (one module each,
//! `run(&args)`), except `monitor` ([`monitor`], still one module); the libraries they share:
//! input files read with a size cap ([`input`]), progress and Ctrl-C ([`progress`]), the LCP
//! file reader ([`lcp_io`]), the scenes and their flags ([`scenes`]), the independent f64
//! reference of the scenes ([`mod@reference`]), recorded runs ([`trajectory`]), what the commands
//! write ([`output`]) and draw ([`plot`]), the outcome map ([`map`]), the error against run time
//! over `h` ([`sweep`]), where f32 holds
//! ([`envelope`]), the stress grid ([`stress`]), the page's server ([`serve`]) and the QEMU
//! firmware runner ([`qemu`]).

pub mod cli;
pub mod commands;
pub mod envelope;
pub mod errors;
pub mod input;
pub mod lcp_io;
pub mod map;
pub mod monitor;
pub mod output;
pub mod plot;
pub mod progress;
pub mod qemu;
pub use meterstick_reference as reference;
pub mod scenes;
pub mod serve;
pub mod stress;
pub mod sweep;
pub mod trajectory;

/// This crate's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The paths `stress/` still imports (`crate::run_cmd::...`, before the commands moved to
/// [`commands`]); it goes when `stress/` imports [`output`] and [`progress`] itself.
#[doc(hidden)]
pub mod run_cmd {
    pub use crate::output::{parameters_json, sci, write_json};
    pub use crate::progress::bar as progress;
}

/// The path `web/tests/host_sim.rs` still imports (`scene_cmd::{SceneCmd, run_scene}`); it goes
/// when that test imports [`commands::scene`].
#[doc(hidden)]
pub mod scene_cmd {
    pub use crate::commands::scene::{SceneCmdArgs as SceneCmd, run as run_scene};
}
