//! Independent checks for the meterstick integration tests.
//!
//! Nothing here calls the core solver: [`enumeration`] (the independent reference's enumerator,
//! `reference/src/enumerate.rs`) solves small LCPs by trying every complementary basis,
//! [`generate`] makes random matrices of known classes.

pub use meterstick_reference::enumerate as enumeration;
pub mod generate;

/// The vendored copy of the Siconos LCP corpus (`tests/data/lcp-corpus`, see its README).
#[must_use]
pub fn corpus_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/lcp-corpus")
}
