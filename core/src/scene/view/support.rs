//! [`SupportView`]: what a scene holds its bodies on, where it is and how it moves.

/// A support: a scene of one body's moved or fixed support, or the table of a scene of several
/// bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum SupportView<T> {
    /// A point (a finger tip) at `position` moving at `velocity` (world, m and m/s).
    Point {
        /// Its position.
        position: [T; 2],
        /// Its velocity.
        velocity: [T; 2],
    },
    /// A line (a floor, a wall, an incline) through `position` with unit `normal` toward the body,
    /// moving at `velocity`.
    Line {
        /// A point of the line.
        position: [T; 2],
        /// Its unit normal, toward the body.
        normal: [T; 2],
        /// Its velocity.
        velocity: [T; 2],
    },
    /// A finger lying across a rod in three dimensions (`crate::spatial::Finger`): the horizontal
    /// line through `tip` along `across`, moving at `velocity` (world, `z` up).
    #[cfg(feature = "spatial")]
    Finger {
        /// A point of the line (the finger's tip), m.
        tip: [T; 3],
        /// The line's unit direction.
        across: [T; 3],
        /// Its velocity, m/s.
        velocity: [T; 3],
    },
    /// A plane in three dimensions (a table, an incline) through `point` with unit `normal`
    /// toward the body (world, `z` up), fixed.
    #[cfg(feature = "spatial")]
    Plane {
        /// A point of the plane.
        point: [T; 3],
        /// Its unit normal, toward the body.
        normal: [T; 3],
    },
    /// The fixed table: its top face is the line `y = 0` over `lo <= x <= hi` (in three
    /// dimensions the plane `z = 0` over `lo <= x <= hi`), an end that is `None` infinite.
    Table {
        /// The left end (m).
        lo: Option<T>,
        /// The right end (m).
        hi: Option<T>,
    },
}
