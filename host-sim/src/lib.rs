//! # meterstick-host-sim
//!
//! The std host harness around `meterstick-core` and the `host-sim` command line ([`cli`]:
//! its arguments, dispatch and exit status), in two layers.
//!
//! **The commands** ([`commands`]), one module each, thin: `run`, `report`, `map`, `envelope`,
//! `stress`, `scene`, `lcp`, `qemu`, `monitor`, `serve`, `version`; each has its options and
//! `run(&args)`, and none imports another.
//!
//! **The libraries** they are written over, each named for what it is: the scenes and their flags
//! ([`scenes`]); one recorded run of a scene in the core or the independent f64 reference
//! ([`mod@reference`]) ([`trajectory`]: its types, the rows kept, the core's run, the reference's
//! run, the eq. 21 switches and deviations, the CSVs); the same of a scene of several bodies or in
//! three dimensions, recorded body by body, with its laws and files ([`bodies`]); a run of any scene in the core, of either
//! engine, through its one scene interface ([`view_run`]); what the commands write ([`output`]) and
//! draw ([`plot`]); the outcome over two parameters ([`map`]); the error against run time over
//! `h` ([`sweep`]; of the scenes in three dimensions, [`spatial_sweep`]); where f32 holds ([`envelope`]); the stress grid ([`stress`]); the rig over
//! its link ([`monitor`]: parameters, recording, comparison); firmware under QEMU ([`qemu`]); the
//! page's file server ([`serve`]); the LCP file reader ([`lcp_io`]); input files read with a size
//! cap ([`input`]); progress and Ctrl-C ([`progress`]); the failed-check error ([`errors`]).

pub mod bodies;
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
pub mod spatial_sweep;
pub mod stress;
pub mod sweep;
pub mod trajectory;
pub mod view_run;

/// This crate's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
