//! The error a command returns when a check it ran failed (exit status 1, [`crate::cli`]), in a
//! module of its own so that the commands need not import the command line (`monitor` did: an
//! import cycle).

/// A check failed (exit status 1): the message says which.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckFailed(pub String);

impl std::fmt::Display for CheckFailed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CheckFailed {}
