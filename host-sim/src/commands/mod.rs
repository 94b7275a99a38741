//! The `host-sim` commands, one module each, thin over the libraries of this crate: a command
//! reads its options, calls the libraries and writes its files; no command imports another.
//!
//! **One entry point.** Each module has its options, `<Name>Args` (a `clap::Args` struct, held by
//! the variant of [`crate::cli::Cmd`]), and `pub fn run(args: &<Name>Args) -> anyhow::Result<T>`,
//! which [`crate::cli::run`] calls: `T` is the text the command prints (a `String`), except
//! `qemu` (the firmware's exit status: it prints the firmware's lines itself) and `serve`
//! (serves until stopped). `version` has no options. A failed check is
//! [`crate::errors::CheckFailed`] (exit status 1).

pub mod envelope;
pub mod lcp;
pub mod map;
pub mod monitor;
pub mod qemu;
pub mod report;
pub mod run;
pub mod scene;
pub mod serve;
pub mod stress;
pub mod version;
