//! The contact modes by code, the one table the page's rows read ([`crate::sim::MODES`] names
//! them): the rows of the scenes in the plane (`crate::sim`) and in three dimensions
//! (`crate::spatial`) both write [`mode_code`].

use meterstick_core::planar::{ContactMode, Direction};

/// A mode's code: 0 separated, 1 sticking, 2 sliding+, 3 sliding- ([`crate::sim::MODES`]).
#[must_use]
pub const fn mode_code(m: ContactMode) -> u8 {
    match m {
        ContactMode::Separated => 0,
        ContactMode::Sticking => 1,
        ContactMode::Sliding(Direction::Plus) => 2,
        ContactMode::Sliding(Direction::Minus) => 3,
    }
}
