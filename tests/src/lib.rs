//! Independent checks for the meterstick integration tests.
//!
//! Nothing here calls the core solver: [`enumeration`] solves small LCPs by trying every
//! complementary basis, [`generate`] makes random matrices of known classes.

pub mod enumeration;
pub mod generate;

/// The vendored copy of the Siconos LCP corpus (`tests/data/lcp-corpus`, see its README).
#[must_use]
pub fn corpus_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/lcp-corpus")
}
