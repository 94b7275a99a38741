//! [`SceneView`]: one interface over every scene of every engine, object-safe, so a front end can
//! drive, record and draw any scene through `&mut dyn SceneView<T>` without naming its engine, its
//! number of bodies or its number of contacts.
//!
//! A scene of one body ([`super::Scene`]) is seen through [`PlanarView`], a scene of several
//! bodies ([`crate::multibody::scenes::MultibodyScene`]) through [`MultibodyView`]. Each wraps
//! the scene it is given and keeps what the scene's own interface hands out only once, with each
//! step: the last step's contact impulses and the trajectory checksum. Stepping through the view
//! steps the scene itself: the trajectory is the scene's, bit for bit.
//!
//! What the view gives are small `Copy` records:
//!
//! * [`BodyView`]: a body's [`BodyShape`], [`Pose`], [`Velocity`] and applied [`Force`] (each an
//!   enum of the dimension it is in: a spatial body is another variant, not another method);
//! * [`ContactView`]: a contact between two [`Thing`]s, its point, normal, gap, mode and
//!   impulses;
//! * [`SupportView`]: a support, moving or fixed, or the table;
//! * [`EventView`]: a contact's switch of mode, as the scene keeps them;
//! * [`RunStats`]: the counters every engine keeps;
//! * [`StepStats`]: what the last step's solve took;
//! * [`StepFigure`]: a quantity of the last step an engine reports beyond these, named by what it
//!   is ([`FigureName`]).
//!
//! [`crate::scene::SceneParams::build_view`] builds any catalogue scene and hands it to a
//! [`ViewVisitor`] as a `&mut dyn SceneView<T>`; a [`HeldView`] (`held.rs`: [`AnyView`] and the
//! holders of each engine's scenes) keeps one built between calls and hands it to a
//! [`ViewVisitor`] or a [`ViewReader`].

mod body;
mod build;
mod contact;
mod event;
mod figure;
mod held;
mod multibody;
mod planar;
mod step;
mod support;

pub use crate::RunStats;
pub use body::{BodyShape, BodyView, Force, Pose, Velocity};
pub use build::ViewVisitor;
pub use contact::{ContactView, Thing};
pub use event::EventView;
pub use figure::{Axis, FigureName, LoadPart, StepFigure};
#[cfg(all(
    any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"),
    feature = "scenes-multibody"
))]
pub use held::AnyView;
#[cfg(feature = "scenes-multibody")]
pub use held::MultibodyViews;
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
pub use held::PlanarViews;
pub use held::{HeldView, ViewReader};
#[cfg(feature = "scenes-spatial")]
pub use held::{SpatialViews, SpatialViewsIn};
#[cfg(feature = "scenes-stack-3d")]
pub use held::{StackViews, StackViewsIn};
pub use multibody::MultibodyView;
pub use planar::PlanarView;
pub use step::StepStats;
pub use support::SupportView;

use super::kind::MAX_MEASURES;

/// The components of a view's world vectors ([`ViewVector`]): `(x, y, z)` in a build with three
/// dimensions (feature `spatial`), `(x, y)` in a planar build, which carries no `z`.
pub const DIMENSIONS: usize = if cfg!(feature = "spatial") { 3 } else { 2 };

/// A world vector as the view gives it ([`ContactView`]): [`DIMENSIONS`] components, `z = 0` for
/// a scene in the plane.
pub type ViewVector<T> = [T; DIMENSIONS];

/// A planar vector `(x, y)` as a [`ViewVector`] (`(x, y, 0)` with three dimensions).
pub(crate) fn in_space<T: Real>(xy: [T; 2]) -> ViewVector<T> {
    core::array::from_fn(|i| xy.get(i).copied().unwrap_or_else(T::zero))
}
use super::outcome::Outcome;
use crate::real::Real;

/// What a driver asks of any scene, in scalar `T`: step it, read its bodies and contacts, its
/// time, outcome, measured quantities, counters and trajectory checksum.
///
/// Indices run over a fixed list for the scene: [`Self::body`] from `0` to
/// [`Self::body_count`], [`Self::contact`] from `0` to [`Self::contact_count`]; past the end
/// they give `None`. Every contact the scene's engine considers is listed, touching or not (a
/// separated one has mode [`crate::planar::ContactMode::Separated`] and no impulse).
pub trait SceneView<T: Real> {
    /// Advances one step; `false` once the run has an outcome (and nothing is done).
    fn step(&mut self) -> bool;
    /// Lets a run that has its outcome go on (the scene's own `go_on`): takes the outcome and
    /// returns it, so that the next [`Self::step`] is taken. `None` (and nothing done) before the
    /// outcome, or for a scene that does not go on.
    fn go_on(&mut self) -> Option<Outcome>;
    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;
    /// Simulated time (s).
    fn time(&self) -> T;
    /// The number of bodies the scene moves.
    fn body_count(&self) -> usize;
    /// Body `i` now (body 0 the lowest of a scene of several bodies).
    fn body(&self, i: usize) -> Option<BodyView<T>>;
    /// The number of contacts (a scene of one body: its supports; of several: four candidates per
    /// resting pair).
    fn contact_count(&self) -> usize;
    /// Contact `i`: its geometry now and its impulses over the last step (zero before the first).
    fn contact(&self, i: usize) -> Option<ContactView<T>>;
    /// The number of supports (a scene of one body: one per contact, [`Thing::Support`]'s index;
    /// a scene of several bodies: its table, [`Thing::Table`]).
    fn support_count(&self) -> usize;
    /// Support `i` where the last step left it (before the first: where it starts).
    fn support(&self, i: usize) -> Option<SupportView<T>>;
    /// The number of switch events the scene keeps ([`super::Scene::events`]; a scene of several
    /// bodies keeps none; by default none).
    fn event_count(&self) -> usize {
        0
    }
    /// Switch event `i`, oldest first (by default none).
    fn event(&self, i: usize) -> Option<EventView<T>> {
        let _ = i;
        None
    }
    /// What the scene measures, in the order of its catalogue entry's `measures`; `None` where a
    /// quantity has no value (yet).
    fn measured(&self) -> [Option<T>; MAX_MEASURES];
    /// The engine's counters, as far as every engine keeps them.
    fn summary(&self) -> RunStats;
    /// What the last step taken through this view solved (`None` before the first).
    fn last_step(&self) -> Option<StepStats<T>>;
    /// The rows of the largest LCP a step of the scene may solve (a scene of one body on `K`
    /// contacts: the full layout's `4 K`, which the reduced one falls back to; of several bodies:
    /// its full form's capacity).
    fn lcp_capacity(&self) -> usize;
    /// The number of figures the engine reports of each step beyond the records above (a scene of
    /// one body: none; of several: each pair's force and candidates' loads; by default none).
    fn figure_count(&self) -> usize {
        0
    }
    /// Figure `i` of the last step (before the first: zero), in the same order after every step
    /// (by default none).
    fn figure(&self, i: usize) -> Option<StepFigure<T>> {
        let _ = i;
        None
    }
    /// The trajectory checksum ([`crate::planar::Checksum`]) over every body's state, in body
    /// order, after every step taken through this view: the fingerprint the firmware prints.
    fn checksum(&self) -> u32;
}
