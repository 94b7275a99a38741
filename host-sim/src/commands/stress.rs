//! `host-sim stress`: the stress grid ([`crate::stress`]), with a failed case as a failed check.

use crate::errors::CheckFailed;
use crate::stress::{self, StressArgs};

/// Runs the grid and returns its table; when a case failed, prints the table first and returns
/// [`CheckFailed`] (exit status 1).
///
/// # Errors
/// A case failed, bad input, or I/O.
pub fn run(args: &StressArgs) -> anyhow::Result<String> {
    let (text, all_passed) = stress::run(args)?;
    if !all_passed {
        print!("{text}");
        return Err(CheckFailed("stress: a case failed (see the table above)".into()).into());
    }
    Ok(text)
}
