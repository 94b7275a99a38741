//! `host-sim version`: the versions of host-sim and of meterstick-core.

/// The two lines.
///
/// # Errors
/// None.
pub fn run() -> anyhow::Result<String> {
    Ok(format!("host-sim {}\nmeterstick-core {}\n", crate::VERSION, meterstick_core::VERSION))
}
