//! Logging shim: with the `defmt` feature the macros forward to `defmt`, without it they
//! compile to nothing (arguments are still type-checked, never evaluated at run time).

#[cfg(feature = "defmt")]
macro_rules! log_trace { ($($t:tt)*) => { ::defmt::trace!($($t)*) }; }
#[cfg(feature = "defmt")]
macro_rules! log_debug { ($($t:tt)*) => { ::defmt::debug!($($t)*) }; }
#[cfg(feature = "defmt")]
macro_rules! log_info { ($($t:tt)*) => { ::defmt::info!($($t)*) }; }
#[cfg(feature = "defmt")]
macro_rules! log_warn { ($($t:tt)*) => { ::defmt::warn!($($t)*) }; }
#[cfg(feature = "defmt")]
macro_rules! log_error { ($($t:tt)*) => { ::defmt::error!($($t)*) }; }

#[cfg(not(feature = "defmt"))]
macro_rules! log_trace { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }
#[cfg(not(feature = "defmt"))]
macro_rules! log_debug { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }
#[cfg(not(feature = "defmt"))]
macro_rules! log_info { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }
#[cfg(not(feature = "defmt"))]
macro_rules! log_warn { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }
#[cfg(not(feature = "defmt"))]
macro_rules! log_error { ($($t:tt)*) => {{ if false { let _ = ($($t)*,); } }}; }

#[allow(unused_imports)]
pub(crate) use {log_debug, log_error, log_info, log_trace, log_warn};
