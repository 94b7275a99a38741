//! Logging shim: with the `defmt` feature the macros forward to `defmt`, without it they
//! compile to nothing (arguments are still type-checked, never evaluated at run time).

#[cfg(feature = "defmt")]
macro_rules! log_trace { ($($t:tt)*) => { ::defmt::trace!($($t)*) }; }
#[cfg(feature = "defmt")]
macro_rules! log_debug { ($($t:tt)*) => { ::defmt::debug!($($t)*) }; }
#[cfg(feature = "defmt")]
macro_rules! log_warn { ($($t:tt)*) => { ::defmt::warn!($($t)*) }; }

#[cfg(not(feature = "defmt"))]
macro_rules! log_trace { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }
#[cfg(not(feature = "defmt"))]
macro_rules! log_debug { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }
#[cfg(not(feature = "defmt"))]
macro_rules! log_warn { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }

#[allow(unused_imports)]
pub(crate) use {log_debug, log_trace, log_warn};
