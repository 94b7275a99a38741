//! `host-sim`: the meterstick host harness. The command line lives in the library
//! (`meterstick_host_sim::cli`), where tests reach it.

use std::process::ExitCode;

fn main() -> ExitCode {
    meterstick_host_sim::cli::main_with(std::env::args_os())
}
