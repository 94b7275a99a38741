//! [`ContactView`]: one contact of a scene, between two [`Thing`]s.

use super::ViewVector;
use crate::planar::ContactMode;

/// What a contact is between: a body of the scene, one of a scene's supports, or the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Thing {
    /// The body of this index ([`super::SceneView::body`]).
    Body(u8),
    /// A support a scene of one body moves or holds (a finger, the floor, the wall, the plane),
    /// by its contact's index.
    Support(u8),
    /// The fixed table of a scene of several bodies.
    Table,
}

/// One contact: what touches what, where, and what passed between them over the last step.
///
/// The normal impulse acts on `between[0]` along `normal` and on `between[1]` against it; the
/// friction impulse on `between[0]` along `tangent`. Vectors are world [`ViewVector`]s: `(x, y)`
/// in a planar build; `(x, y, z)` with three dimensions (feature `spatial`), where a contact in
/// the plane has `z = 0` (the plane's `z` points out of it, toward the viewer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactView<T> {
    /// The two things in contact: the one the impulses are given on first.
    pub between: [Thing; 2],
    /// `true` when the contact enters the next step (a support that can act; a candidate the
    /// activity rule keeps). The geometry of an inactive candidate of a scene of several bodies is
    /// that of when it was last computed.
    pub active: bool,
    /// The contact point, world (m): the point of `between[0]` that touches.
    pub point: ViewVector<T>,
    /// `point` from `between[0]`'s centre of mass (m, world), as the engine keeps it (the body's
    /// position plus this is `point` before rounding: a driver that adds them in another scalar
    /// gets that scalar's sum).
    pub lever: ViewVector<T>,
    /// The unit normal, world, on `between[0]`.
    pub normal: ViewVector<T>,
    /// The unit tangent, world, the direction of positive friction impulse: in the plane the
    /// normal turned clockwise, `(n_y, -n_x)`; in three dimensions the friction impulse's
    /// direction (where there is none, the slip's; where neither, a fixed direction in the plane).
    pub tangent: ViewVector<T>,
    /// The gap (m, positive when apart, negative when penetrating).
    pub gap: T,
    /// The mode after the last step (before the first: from the start).
    pub mode: ContactMode,
    /// Normal impulse over the last step (N s; zero before the first).
    pub normal_impulse: T,
    /// Friction impulse over the last step along `tangent` (N s; zero before the first; in three
    /// dimensions its magnitude).
    pub friction_impulse: T,
    /// Where along the other thing the contact is (m): a scene of one body, the coordinate along
    /// the tangent at which the last step's impulses acted ([`crate::planar::ContactReport::along`];
    /// zero before the first step); a scene of several bodies, the corner's coordinate along the
    /// face from its centre now ([`crate::multibody::CornerFrame::along`]); a scene in three
    /// dimensions, zero.
    pub along: T,
}
