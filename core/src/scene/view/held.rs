//! Scenes built and held in place, seen as [`SceneView`]s, for a driver that keeps a run between
//! calls (the browser page steps a frame at a time, and has no heap): a [`HeldView`] hands its
//! scene to a [`ViewVisitor`] as a `&mut dyn SceneView<T>`, or to a [`ViewReader`] as a
//! `&dyn SceneView<T>`.
//!
//! * [`PlanarViews`]: any scene of one body (the registry's table, `registry.rs`), each through
//!   its [`PlanarView`];
//! * [`MultibodyViews`]: any scene of several bodies, each through its [`MultibodyView`];
//! * [`SpatialViews`]: any scene in three dimensions of one body (feature `scenes-spatial`), each
//!   through its [`SpatialView`]; [`SpatialViewsIn`] in one precision;
//! * `StackViews`: the stack in three dimensions (feature `scenes-stack-3d`), through its
//!   `StackView`; `StackViewsIn` in one precision;
//! * [`AnyView`]: any scene of the catalogue, one of them by the scene's engine.
//!
//! A build that runs the scenes of one engine only (a page module) holds that engine's holder:
//! naming the other's links none of its steppers.

#[cfg(feature = "scenes-multibody")]
use super::MultibodyView;
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
use super::PlanarView;
use super::{SceneView, ViewVisitor};
#[cfg(feature = "scenes-multibody")]
use crate::multibody::scenes::{BlockOnBlock, DiscOnBoard, Stack2, Stack3, Tablecloth};
use crate::params::ParamError;
use crate::real::Real;
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
use crate::scene::SceneIn;
#[cfg(feature = "scenes-k3")]
use crate::scene::ThreeFingers;
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
use crate::scene::registry::scene_table;
#[cfg(feature = "scenes-spatial")]
use crate::scene::spatial::{
    Billiard, CURLING_ROWS, Curling, MAX_POINTS, MeterStick3d, Puck, ROD_POINTS, ROD_ROWS, SpatialView,
};
#[cfg(feature = "scenes-stack-3d")]
use crate::scene::spatial::{Stack3d2, Stack3d3, StackView};
#[cfg(feature = "scenes-k1")]
use crate::scene::{Cylinder, Painleve};
#[cfg(feature = "scenes-k2")]
use crate::scene::{Incline, Ladder, MeterStick};
use crate::scene::{LcpLayout, Precision, SceneParams};

/// What a driver reads of any scene, whichever its engine: [`Self::read`] receives it as a
/// [`SceneView`] in scalar `T` from [`HeldView::read`].
pub trait ViewReader {
    /// What the reading gives.
    type Output;

    /// Reads `view`.
    fn read<T: Real>(self, view: &dyn SceneView<T>) -> Self::Output;
}

/// A scene built and held in place, seen as a [`SceneView`] in the precision it was built in.
pub trait HeldView: Sized {
    /// The scene of `params` in `precision` and `layout` (a scene of several bodies has one
    /// layout: `layout` unused), at its start, seen from there (no impulses, an empty checksum).
    ///
    /// # Errors
    /// The core's first complaint about the parameters in `precision`; `OutOfRange("scene")` for
    /// a scene this holder does not hold (or this build leaves out).
    fn new(params: &SceneParams, precision: Precision, layout: LcpLayout) -> Result<Self, ParamError>;

    /// Hands the scene, in place, to `visitor`: steps taken through the view are the run's.
    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output;

    /// Hands the scene to `reader`.
    fn read<R: ViewReader>(&self, reader: R) -> R::Output;
}

/// A held scene in scalar `T`, seen as a view.
#[cfg(any(
    feature = "scenes-k1",
    feature = "scenes-k2",
    feature = "scenes-k3",
    feature = "scenes-multibody",
    feature = "scenes-spatial"
))]
trait Seen<T: Real> {
    fn view_mut(&mut self) -> &mut dyn SceneView<T>;
    fn view(&self) -> &dyn SceneView<T>;
}

/// A held scene in f32 (`A`) or f64 (`B`).
#[cfg(any(
    feature = "scenes-k1",
    feature = "scenes-k2",
    feature = "scenes-k3",
    feature = "scenes-multibody",
    feature = "scenes-spatial"
))]
#[derive(Debug, Clone)]
enum InPrecision<A, B> {
    F32(A),
    F64(B),
}

#[cfg(any(
    feature = "scenes-k1",
    feature = "scenes-k2",
    feature = "scenes-k3",
    feature = "scenes-multibody",
    feature = "scenes-spatial"
))]
impl<A: Seen<f32>, B: Seen<f64>> InPrecision<A, B> {
    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        match self {
            Self::F32(s) => visitor.visit(s.view_mut()),
            Self::F64(s) => visitor.visit(s.view_mut()),
        }
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        match self {
            Self::F32(s) => reader.read(s.view()),
            Self::F64(s) => reader.read(s.view()),
        }
    }
}

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
/// [`PlanarIn`] of the registry's table: each row's scene through its [`PlanarView`].
macro_rules! planar_in {
    ($(#[$built:meta] $variant:ident: $scene:ident<$k:literal, $n:literal> = $params:ident, $layout:ident, $hand:ident;)*) => {
        /// Any scene of one body in scalar `T`, keeping `E` switch events ([`SceneIn`]), seen
        /// through its [`PlanarView`].
        #[derive(Debug, Clone)]
        #[allow(clippy::large_enum_variant)] // one scene per run, held in place: no heap
        enum PlanarIn<T: Real, const E: usize> {
            $(#[$built] $variant(PlanarView<T, $k, $scene<T, $n, E>>),)*
        }

        impl<T: Real, const E: usize> PlanarIn<T, E> {
            /// `scene` seen through its view.
            fn of(scene: SceneIn<T, E>) -> Self {
                match scene {
                    $(#[$built] SceneIn::$variant(s) => Self::$variant(PlanarView::new(s)),)*
                }
            }
        }

        impl<T: Real, const E: usize> Seen<T> for PlanarIn<T, E> {
            fn view_mut(&mut self) -> &mut dyn SceneView<T> {
                match self {
                    $(#[$built] Self::$variant(v) => v,)*
                }
            }

            fn view(&self) -> &dyn SceneView<T> {
                match self {
                    $(#[$built] Self::$variant(v) => v,)*
                }
            }
        }
    };
}

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
scene_table!(planar_in);

/// Any scene of one body in any precision and layout, keeping `E` switch events, held in place
/// and seen through its [`PlanarView`].
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
#[derive(Debug, Clone)]
pub struct PlanarViews<const E: usize>(InPrecision<PlanarIn<f32, E>, PlanarIn<f64, E>>);

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
impl<const E: usize> HeldView for PlanarViews<E> {
    fn new(params: &SceneParams, precision: Precision, layout: LcpLayout) -> Result<Self, ParamError> {
        Ok(Self(match precision {
            Precision::F32 => InPrecision::F32(PlanarIn::of(SceneIn::new(params, layout)?)),
            Precision::F64 => InPrecision::F64(PlanarIn::of(SceneIn::new(params, layout)?)),
        }))
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        self.0.visit_mut(visitor)
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        self.0.read(reader)
    }
}

/// Any scene of several bodies in scalar `T`, seen through its [`MultibodyView`].
#[cfg(feature = "scenes-multibody")]
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per run, held in place: no heap
enum ManyIn<T: Real> {
    BlockOnBlock(MultibodyView<T, 2, 2, BlockOnBlock<T>>),
    Tablecloth(MultibodyView<T, 2, 3, Tablecloth<T>>),
    Stack2(MultibodyView<T, 2, 2, Stack2<T>>),
    Stack3(MultibodyView<T, 3, 3, Stack3<T>>),
    DiscOnBoard(MultibodyView<T, 2, 2, DiscOnBoard<T>>),
}

#[cfg(feature = "scenes-multibody")]
/// `$body` with `$v` bound to the held view, whichever it is.
macro_rules! each_many {
    ($held:expr, $v:ident => $body:expr) => {
        match $held {
            ManyIn::BlockOnBlock($v) => $body,
            ManyIn::Tablecloth($v) => $body,
            ManyIn::Stack2($v) => $body,
            ManyIn::Stack3($v) => $body,
            ManyIn::DiscOnBoard($v) => $body,
        }
    };
}

#[cfg(feature = "scenes-multibody")]
impl<T: Real> Seen<T> for ManyIn<T> {
    fn view_mut(&mut self) -> &mut dyn SceneView<T> {
        each_many!(self, v => v)
    }

    fn view(&self) -> &dyn SceneView<T> {
        each_many!(self, v => v)
    }
}

/// Any scene of several bodies in either precision, held in place and seen through its
/// [`MultibodyView`].
#[cfg(feature = "scenes-multibody")]
#[derive(Debug, Clone)]
pub struct MultibodyViews(InPrecision<ManyIn<f32>, ManyIn<f64>>);

#[cfg(feature = "scenes-multibody")]
impl<T: Real> ManyIn<T> {
    /// The scene of `params` in `T` (each built in its view's place: no copy of the scene).
    fn new(params: &SceneParams) -> Result<Self, ParamError> {
        Ok(match *params {
            SceneParams::BlockOnBlock(p) => {
                Self::BlockOnBlock(MultibodyView::new(BlockOnBlock::new(p.cast())?))
            }
            SceneParams::Tablecloth(p) => Self::Tablecloth(MultibodyView::new(Tablecloth::new(p.cast())?)),
            SceneParams::DiscOnBoard(p) => Self::DiscOnBoard(MultibodyView::new(DiscOnBoard::new(p.cast())?)),
            SceneParams::Stack(s) => match s.block_count() {
                Some(2) => Self::Stack2(MultibodyView::new(Stack2::new(s.params.cast())?)),
                Some(3) => Self::Stack3(MultibodyView::new(Stack3::new(s.params.cast())?)),
                _ => return Err(ParamError::OutOfRange("blocks")),
            },
            _ => return Err(ParamError::OutOfRange("scene")),
        })
    }
}

#[cfg(feature = "scenes-multibody")]
impl HeldView for MultibodyViews {
    fn new(params: &SceneParams, precision: Precision, _: LcpLayout) -> Result<Self, ParamError> {
        Ok(Self(match precision {
            Precision::F32 => InPrecision::F32(ManyIn::new(params)?),
            Precision::F64 => InPrecision::F64(ManyIn::new(params)?),
        }))
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        self.0.visit_mut(visitor)
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        self.0.read(reader)
    }
}

/// Any scene in three dimensions in scalar `T`, seen through its [`SpatialView`]. The puck and the
/// ball are held in an LCP of the curling stone's capacity ([`CURLING_ROWS`], which holds Coulomb's
/// circular cone's rows and the pyramid baseline's, [`PYRAMID_ROWS`]): one copy of the contact
/// solve for the three (a page module's size) where [`SceneParams::build_view`] sizes each cone's
/// LCP to fit. The same operations on the rows in use (the same bits: the page's test checks its
/// checksums against `host-sim scene`'s).
#[cfg(feature = "scenes-spatial")]
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per run, held in place: no heap
enum SpaceIn<T: Real> {
    Puck(SpatialView<T, Puck<T, CURLING_ROWS>, CURLING_ROWS>),
    Billiard(SpatialView<T, Billiard<T, CURLING_ROWS>, CURLING_ROWS>),
    Curling(SpatialView<T, Curling<T>, CURLING_ROWS, MAX_POINTS>),
    MeterStick3d(SpatialView<T, MeterStick3d<T>, ROD_ROWS, ROD_POINTS>),
}

#[cfg(feature = "scenes-spatial")]
/// `$body` with `$v` bound to the held view, whichever it is.
macro_rules! each_space {
    ($held:expr, $v:ident => $body:expr) => {
        match $held {
            SpaceIn::Puck($v) => $body,
            SpaceIn::Billiard($v) => $body,
            SpaceIn::Curling($v) => $body,
            SpaceIn::MeterStick3d($v) => $body,
        }
    };
}

#[cfg(feature = "scenes-spatial")]
impl<T: Real> Seen<T> for SpaceIn<T> {
    fn view_mut(&mut self) -> &mut dyn SceneView<T> {
        each_space!(self, v => v)
    }

    fn view(&self) -> &dyn SceneView<T> {
        each_space!(self, v => v)
    }
}

#[cfg(feature = "scenes-spatial")]
impl<T: Real> SpaceIn<T> {
    /// The scene of `params` in `T`, checked in f64 and `T` first (as [`SceneParams::build_view`]).
    fn new(params: &SceneParams) -> Result<Self, ParamError> {
        params.validate_as::<T>()?;
        Ok(match *params {
            SceneParams::Puck(p) => Self::Puck(SpatialView::new(Puck::new(p.cast())?)),
            SceneParams::Billiard(p) => Self::Billiard(SpatialView::new(Billiard::new(p.cast())?)),
            SceneParams::Curling(p) => Self::Curling(SpatialView::new(Curling::new(p.cast())?)),
            SceneParams::MeterStick3d(p) => {
                Self::MeterStick3d(SpatialView::new(MeterStick3d::new(p.cast())?))
            }
            _ => return Err(ParamError::OutOfRange("scene")),
        })
    }
}

#[cfg(feature = "scenes-spatial")]
const _: () = assert!(CURLING_ROWS >= crate::scene::spatial::PYRAMID_ROWS);

/// Any scene in three dimensions in either precision, held in place and seen through its
/// [`SpatialView`] (one layout: `layout` unused).
#[cfg(feature = "scenes-spatial")]
#[derive(Debug, Clone)]
pub struct SpatialViews(InPrecision<SpaceIn<f32>, SpaceIn<f64>>);

#[cfg(feature = "scenes-spatial")]
impl HeldView for SpatialViews {
    fn new(params: &SceneParams, precision: Precision, _: LcpLayout) -> Result<Self, ParamError> {
        Ok(Self(match precision {
            Precision::F32 => InPrecision::F32(SpaceIn::new(params)?),
            Precision::F64 => InPrecision::F64(SpaceIn::new(params)?),
        }))
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        self.0.visit_mut(visitor)
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        self.0.read(reader)
    }
}

/// Any scene in three dimensions in one precision, `T`, held in place and seen through its
/// [`SpatialView`]: a build that runs them in that precision only (a page module of one
/// precision, half the code of [`SpatialViews`]), refusing the other as `OutOfRange("precision")`.
#[cfg(feature = "scenes-spatial")]
#[derive(Debug, Clone)]
pub struct SpatialViewsIn<T: Real>(SpaceIn<T>);

#[cfg(feature = "scenes-spatial")]
impl<T: Real> HeldView for SpatialViewsIn<T> {
    fn new(params: &SceneParams, precision: Precision, _: LcpLayout) -> Result<Self, ParamError> {
        if precision.name() != T::NAME {
            return Err(ParamError::OutOfRange("precision"));
        }
        Ok(Self(SpaceIn::new(params)?))
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        visitor.visit(self.0.view_mut())
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        reader.read(self.0.view())
    }
}

/// The stack in three dimensions in scalar `T`, 2 or 3 blocks, seen through its [`StackView`].
#[cfg(feature = "scenes-stack-3d")]
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per run, held in place: no heap
enum StackIn<T: Real> {
    Two(StackView<T, 2, 13, 52, 2>),
    Three(StackView<T, 3, 16, 64, 2>),
}

#[cfg(feature = "scenes-stack-3d")]
impl<T: Real> Seen<T> for StackIn<T> {
    fn view_mut(&mut self) -> &mut dyn SceneView<T> {
        match self {
            Self::Two(v) => v,
            Self::Three(v) => v,
        }
    }

    fn view(&self) -> &dyn SceneView<T> {
        match self {
            Self::Two(v) => v,
            Self::Three(v) => v,
        }
    }
}

#[cfg(feature = "scenes-stack-3d")]
impl<T: Real> StackIn<T> {
    /// The stack of `params` in `T`, checked in f64 and `T` first (as [`SceneParams::build_view`]).
    fn new(params: &SceneParams) -> Result<Self, ParamError> {
        params.validate_as::<T>()?;
        match params {
            // Validated above: 2 or 3 blocks.
            SceneParams::Stack3d(s) if s.block_count() == Some(2) => {
                Ok(Self::Two(StackView::new(Stack3d2::new(s.params.cast())?)))
            }
            SceneParams::Stack3d(s) => Ok(Self::Three(StackView::new(Stack3d3::new(s.params.cast())?))),
            _ => Err(ParamError::OutOfRange("scene")),
        }
    }
}

/// The stack in three dimensions in either precision, held in place and seen through its
/// [`StackView`] (one layout: `layout` unused); any other scene is refused.
#[cfg(feature = "scenes-stack-3d")]
#[derive(Debug, Clone)]
pub struct StackViews(InPrecision<StackIn<f32>, StackIn<f64>>);

#[cfg(feature = "scenes-stack-3d")]
impl HeldView for StackViews {
    fn new(params: &SceneParams, precision: Precision, _: LcpLayout) -> Result<Self, ParamError> {
        Ok(Self(match precision {
            Precision::F32 => InPrecision::F32(StackIn::new(params)?),
            Precision::F64 => InPrecision::F64(StackIn::new(params)?),
        }))
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        self.0.visit_mut(visitor)
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        self.0.read(reader)
    }
}

/// The stack in three dimensions in one precision, `T`, held in place: a page module of its own
/// (its steppers are the size of the other scenes in three dimensions together), refusing the
/// other precision as `OutOfRange("precision")`.
#[cfg(feature = "scenes-stack-3d")]
#[derive(Debug, Clone)]
pub struct StackViewsIn<T: Real>(StackIn<T>);

#[cfg(feature = "scenes-stack-3d")]
impl<T: Real> HeldView for StackViewsIn<T> {
    fn new(params: &SceneParams, precision: Precision, _: LcpLayout) -> Result<Self, ParamError> {
        if precision.name() != T::NAME {
            return Err(ParamError::OutOfRange("precision"));
        }
        Ok(Self(StackIn::new(params)?))
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        visitor.visit(self.0.view_mut())
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        reader.read(self.0.view())
    }
}

/// Any scene of the catalogue, of either engine, held in place and seen as a [`SceneView`]: a
/// scene of one body as [`PlanarViews`] holds it, a scene of several bodies as
/// [`MultibodyViews`] does.
#[cfg(all(
    any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"),
    feature = "scenes-multibody"
))]
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per run, held in place: no heap
pub enum AnyView<const E: usize> {
    /// A scene of one body.
    Planar(PlanarViews<E>),
    /// A scene of several bodies.
    Multibody(MultibodyViews),
    /// A scene in three dimensions.
    #[cfg(feature = "scenes-spatial")]
    Spatial(SpatialViews),
    /// The stack in three dimensions.
    #[cfg(feature = "scenes-stack-3d")]
    Stack(StackViews),
}

#[cfg(all(
    any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"),
    feature = "scenes-multibody"
))]
impl<const E: usize> HeldView for AnyView<E> {
    fn new(params: &SceneParams, precision: Precision, layout: LcpLayout) -> Result<Self, ParamError> {
        #[cfg(feature = "scenes-stack-3d")]
        if matches!(params, SceneParams::Stack3d(_)) {
            return Ok(Self::Stack(StackViews::new(params, precision, layout)?));
        }
        #[cfg(feature = "scenes-spatial")]
        if params.kind().is_spatial() {
            return Ok(Self::Spatial(SpatialViews::new(params, precision, layout)?));
        }
        Ok(if params.kind().is_multibody() {
            Self::Multibody(MultibodyViews::new(params, precision, layout)?)
        } else {
            Self::Planar(PlanarViews::new(params, precision, layout)?)
        })
    }

    fn visit_mut<V: ViewVisitor>(&mut self, visitor: V) -> V::Output {
        match self {
            Self::Planar(v) => v.visit_mut(visitor),
            Self::Multibody(v) => v.visit_mut(visitor),
            #[cfg(feature = "scenes-spatial")]
            Self::Spatial(v) => v.visit_mut(visitor),
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack(v) => v.visit_mut(visitor),
        }
    }

    fn read<R: ViewReader>(&self, reader: R) -> R::Output {
        match self {
            Self::Planar(v) => v.read(reader),
            Self::Multibody(v) => v.read(reader),
            #[cfg(feature = "scenes-spatial")]
            Self::Spatial(v) => v.read(reader),
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack(v) => v.read(reader),
        }
    }
}

#[cfg(all(test, feature = "scenes"))]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scene::{BodyShape, Pose, SceneKind, SupportView};

    /// Takes up to its number of steps through the view; gives the steps taken, every body's `x`
    /// (its bits; 0 past the bodies) and the checksum.
    struct Steps(usize);

    impl ViewVisitor for Steps {
        type Output = (usize, [u64; 3], u32);
        fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
            let taken = (0..self.0).take_while(|_| view.step()).count();
            let x = core::array::from_fn(|i| {
                view.body(i).map_or(0, |b| match b.pose {
                    Pose::Planar { x, .. } => x.as_f64().to_bits(),
                    #[cfg(feature = "spatial")]
                    Pose::Spatial { position, .. } => position[0].as_f64().to_bits(),
                })
            });
            (taken, x, view.checksum())
        }
    }

    /// The scene's steps, its bodies' outlines and its table's ends.
    struct Outline;

    impl ViewReader for Outline {
        type Output = (u64, [Option<BodyShape<f64>>; 3], [Option<f64>; 2]);
        fn read<T: Real>(self, view: &dyn SceneView<T>) -> Self::Output {
            let shapes = core::array::from_fn(|i| {
                view.body(i).map(|b| match b.shape {
                    BodyShape::Box { width, height } => {
                        BodyShape::Box { width: width.as_f64(), height: height.as_f64() }
                    }
                    BodyShape::Disc { radius } => BodyShape::Disc { radius: radius.as_f64() },
                    #[cfg(feature = "spatial")]
                    BodyShape::Ball { radius } => BodyShape::Ball { radius: radius.as_f64() },
                    #[cfg(feature = "spatial")]
                    BodyShape::Puck { radius, thickness } => {
                        BodyShape::Puck { radius: radius.as_f64(), thickness: thickness.as_f64() }
                    }
                    #[cfg(feature = "spatial")]
                    BodyShape::Cuboid { length, width, height } => BodyShape::Cuboid {
                        length: length.as_f64(),
                        width: width.as_f64(),
                        height: height.as_f64(),
                    },
                })
            });
            let table = match view.support(0) {
                Some(SupportView::Table { lo, hi }) => [lo.map(Real::as_f64), hi.map(Real::as_f64)],
                _ => [None, None],
            };
            (view.summary().steps, shapes, table)
        }
    }

    /// Held in place and visited step by step, any scene runs as built and handed over whole
    /// ([`SceneParams::build_view`]): the same steps, bodies and checksum.
    #[test]
    fn a_held_scene_runs_as_built() {
        for kind in SceneKind::ALL {
            for precision in Precision::ALL {
                let params = SceneParams::defaults(kind);
                let whole = params.build_view::<0, _>(precision, LcpLayout::Reduced, Steps(300)).unwrap();
                let mut held = AnyView::<0>::new(&params, precision, LcpLayout::Reduced).unwrap();
                let (a, b) = (held.visit_mut(Steps(100)), held.visit_mut(Steps(200)));
                assert_eq!((a.0 + b.0, b.1, b.2), whole, "{kind} {precision:?}");
                assert_eq!(held.read(Outline).0, whole.0 as u64, "{kind} {precision:?}");
            }
        }
    }

    /// A holder of the scenes in three dimensions in one precision runs them as the holder of both
    /// (the same steps and checksum) and refuses the other precision.
    #[cfg(feature = "scenes-spatial")]
    #[test]
    fn a_holder_of_one_precision_runs_as_the_holder_of_both() {
        let layout = LcpLayout::Reduced;
        for kind in SceneKind::ALL.into_iter().filter(|k| k.is_spatial()) {
            let params = SceneParams::defaults(kind);
            #[cfg(feature = "scenes-stack-3d")]
            if kind == SceneKind::Stack3d {
                let mut both = StackViews::new(&params, Precision::F64, layout).unwrap();
                let mut one = StackViewsIn::<f64>::new(&params, Precision::F64, layout).unwrap();
                assert_eq!(one.visit_mut(Steps(200)), both.visit_mut(Steps(200)), "{kind}");
                assert!(SpatialViews::new(&params, Precision::F64, layout).is_err(), "its own holder");
                continue;
            }
            let mut both = SpatialViews::new(&params, Precision::F64, layout).unwrap();
            let mut one = SpatialViewsIn::<f64>::new(&params, Precision::F64, layout).unwrap();
            assert_eq!(one.visit_mut(Steps(200)), both.visit_mut(Steps(200)), "{kind}");
            assert_eq!(
                SpatialViewsIn::<f32>::new(&params, Precision::F64, layout).err(),
                Some(ParamError::OutOfRange("precision")),
                "{kind}"
            );
        }
    }

    /// Each engine's holder holds its scenes only; a held scene gives its bodies and its table.
    #[test]
    fn a_holder_holds_its_engines_scenes() {
        let (precision, layout) = (Precision::F32, LcpLayout::Reduced);
        let refused = Some(ParamError::OutOfRange("scene"));
        assert_eq!(
            MultibodyViews::new(&SceneParams::defaults(SceneKind::Incline), precision, layout).err(),
            refused
        );
        assert_eq!(
            PlanarViews::<0>::new(&SceneParams::defaults(SceneKind::Tablecloth), precision, layout).err(),
            refused
        );
        let stack = MultibodyViews::new(&SceneParams::defaults(SceneKind::Stack), precision, layout).unwrap();
        let (_, shapes, table) = stack.read(Outline);
        assert_eq!(shapes.iter().flatten().count(), 3, "three blocks");
        assert_eq!(table, [None, Some(0.0)], "the table's edge at 0");
        let disc =
            MultibodyViews::new(&SceneParams::defaults(SceneKind::DiscOnBoard), Precision::F64, layout)
                .unwrap();
        let (_, shapes, table) = disc.read(Outline);
        assert!(
            matches!(shapes, [Some(BodyShape::Box { .. }), Some(BodyShape::Disc { .. }), None]),
            "{shapes:?}"
        );
        assert_eq!(table, [None, None], "a floor without ends");
    }
}
