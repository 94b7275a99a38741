//! # meterstick-host-sim
//!
//! The std host harness around `meterstick-core`: the `host-sim` command line ([`cli`]), input
//! files read with a size cap ([`input`]), progress and Ctrl-C ([`progress`]), the LCP
//! file reader ([`lcp_io`]), the scenes and their flags ([`scenes`]), the independent f64
//! reference of the scenes ([`mod@reference`]), the main job ([`run_cmd`]), the error-vs-run-time report ([`report`]), the stress grid ([`stress`]) and the QEMU firmware
//! runner ([`qemu`]).

pub mod cli;
pub mod envelope;
pub mod errors;
pub mod input;
pub mod lcp_io;
pub mod map;
pub mod monitor;
pub mod plot;
pub mod progress;
pub mod qemu;
pub use meterstick_reference as reference;
pub mod report;
pub mod run_cmd;
pub mod scene_cmd;
pub mod scenes;
pub mod serve;
pub mod stress;
pub mod trajectory;

/// This crate's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
