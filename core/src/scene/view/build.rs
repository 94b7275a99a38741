//! [`ViewVisitor`] and [`SceneParams::build_view`]: any catalogue scene, of any engine, built and
//! handed to a driver as a `&mut dyn SceneView<T>`.

#[cfg(feature = "scenes-multibody")]
use super::MultibodyView;
use super::{PlanarView, SceneView};
#[cfg(feature = "scenes-multibody")]
use crate::multibody::scenes::MultibodyScene;
use crate::params::ParamError;
use crate::real::Real;
#[cfg(feature = "scenes-multibody")]
use crate::scene::MultibodyVisitor;
use crate::scene::{LcpLayout, Precision, Scene, SceneParams, SceneVisitor};

/// What a driver does with any scene, whichever its engine: [`Self::visit`] receives it as a
/// [`SceneView`] in scalar `T` from [`SceneParams::build_view`].
pub trait ViewVisitor {
    /// What the visit gives.
    type Output;

    /// Drives `view`.
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output;
}

/// A [`ViewVisitor`] as the registry's visitor of either engine.
struct Viewing<V>(V);

impl<V: ViewVisitor> SceneVisitor for Viewing<V> {
    type Output = V::Output;

    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, scene: S) -> V::Output {
        self.0.visit(&mut PlanarView::new(scene))
    }
}

#[cfg(feature = "scenes-multibody")]
impl<V: ViewVisitor> MultibodyVisitor for Viewing<V> {
    type Output = V::Output;

    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        scene: S,
    ) -> V::Output {
        self.0.visit(&mut MultibodyView::new(scene))
    }
}

impl SceneParams {
    /// The scene in `precision`, keeping `E` switch events, handed to `visitor` as a
    /// [`SceneView`]: a scene of one body in `layout` ([`Self::build`]), a scene of several bodies
    /// in its one layout ([`Self::build_multibody`], `layout` unused), a scene in three
    /// dimensions through its `crate::scene::spatial::SpatialView` (`layout` unused).
    ///
    /// # Errors
    /// As [`Self::build`] or [`Self::build_multibody`]: the core's first complaint about the
    /// parameters; `OutOfRange("scene")` for a scene this build leaves out.
    pub fn build_view<const E: usize, V: ViewVisitor>(
        &self,
        precision: Precision,
        layout: LcpLayout,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        #[cfg(feature = "scenes-spatial")]
        if self.kind().is_spatial() {
            return match precision {
                Precision::F32 => self.build_spatial::<f32, V>(visitor),
                Precision::F64 => self.build_spatial::<f64, V>(visitor),
            };
        }
        if self.kind().is_multibody() {
            #[cfg(feature = "scenes-multibody")]
            return self.build_multibody(precision, Viewing(visitor));
            #[cfg(not(feature = "scenes-multibody"))]
            return Err(ParamError::OutOfRange("scene"));
        }
        self.build::<E, _>(precision, layout, Viewing(visitor))
    }
}

#[cfg(feature = "scenes-spatial")]
impl SceneParams {
    /// A scene in three dimensions in `T`, checked in f64 and `T` first.
    fn build_spatial<T: Real, V: ViewVisitor>(&self, visitor: V) -> Result<V::Output, ParamError> {
        use crate::scene::spatial::{
            Billiard, CIRCULAR_ROWS, Curling, MeterStick3d, PYRAMID_ROWS, Puck, SpatialView,
        };
        self.validate_as::<T>()?;
        // Coulomb's circular cone in an LCP of its own size; the pyramid baseline in one that
        // holds 16 directions.
        let circular = |directions: f64| directions == 0.0;
        match self {
            Self::Puck(p) if circular(p.friction_directions) => {
                Ok(visitor.visit(&mut SpatialView::new(Puck::<T, CIRCULAR_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Puck(p) => {
                Ok(visitor.visit(&mut SpatialView::new(Puck::<T, PYRAMID_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Billiard(p) if circular(p.friction_directions) => {
                Ok(visitor.visit(&mut SpatialView::new(Billiard::<T, CIRCULAR_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Billiard(p) => {
                Ok(visitor.visit(&mut SpatialView::new(Billiard::<T, PYRAMID_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Curling(p) => Ok(visitor.visit(&mut SpatialView::new(Curling::<T>::new(p.cast::<T>())?))),
            Self::MeterStick3d(p) => {
                Ok(visitor.visit(&mut SpatialView::new(MeterStick3d::<T>::new(p.cast::<T>())?)))
            }
            _ => Err(ParamError::OutOfRange("scene")),
        }
    }
}
