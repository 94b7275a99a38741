//! # meterstick-web
//!
//! `meterstick-core` for the browser. Built for `wasm32-unknown-unknown` (`no_std`, no heap, no
//! bindings generator) it is the module the page in `web/page/` loads with
//! `WebAssembly.instantiate`; built for the host it is an ordinary library whose tests check the
//! export layer against `host-sim` (same flags, same refusals, same parameters, same checksum).
//!
//! * [`flags`]: the scenes and their parameter flags, named as on `host-sim`'s command line;
//! * [`config`]: a scene's configuration resolved to the core's parameters as `host-sim scene`
//!   resolves it, and refusals in the user's words;
//! * [`sim`]: one run in f32/f64 x 6x6/8x8, one row of numbers per step, the trajectory checksum;
//! * [`session`]: what the exports operate on;
//! * `spatial` (feature `sp`): the rows, solid and supports of a scene in three dimensions;
//! * `exports`: the plain `extern "C"` functions the page calls (listed in `docs/page.md`).
#![cfg_attr(target_arch = "wasm32", no_std)]

pub mod config;
mod exports;
pub mod flags;
mod modes;
pub mod session;
pub mod sim;
#[cfg(any(feature = "sp", feature = "st"))]
pub mod spatial;
pub mod text;

pub use exports::*;

/// This crate's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// A panic cannot happen on valid use (the exports check their arguments); should one happen, the
/// wasm instance traps and the page reports the error.
#[cfg(target_arch = "wasm32")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    core::arch::wasm32::unreachable()
}
