//! # meterstick-host-sim
//!
//! The std host harness around `meterstick-core`: the `host-sim` command line, the LCP
//! file reader ([`lcp_io`]) and the QEMU firmware runner ([`qemu`]).

pub mod lcp_io;
pub mod qemu;
pub mod scene_cmd;

/// This crate's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
