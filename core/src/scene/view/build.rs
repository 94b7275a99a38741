//! [`ViewVisitor`] and [`SceneParams::build_view`]: any catalogue scene, of any engine, built and
//! handed to a driver as a [`SceneView`]: a `&mut dyn SceneView<T>`, or the view's concrete type
//! for a driver that asks for it ([`ViewVisitor::visit_concrete`]).

#[cfg(feature = "scenes-multibody")]
use super::MultibodyView;
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
use super::PlanarView;
use super::SceneView;
#[cfg(feature = "scenes-multibody")]
use crate::multibody::scenes::MultibodyScene;
use crate::params::ParamError;
use crate::real::Real;
#[cfg(feature = "scenes-multibody")]
use crate::scene::MultibodyVisitor;
use crate::scene::{LcpLayout, Precision, SceneParams};
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
use crate::scene::{Scene, SceneVisitor};

/// What a driver does with any scene, whichever its engine: [`Self::visit`] receives it as a
/// [`SceneView`] in scalar `T` from [`SceneParams::build_view`].
pub trait ViewVisitor {
    /// What the visit gives.
    type Output;

    /// Drives `view`.
    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output;

    /// Drives `view` as its concrete type `V` (the view of one scene type of one engine), which
    /// [`SceneParams::build_view`] hands every visitor: by default as [`Self::visit`] does, through
    /// `dyn`. A driver whose every call to the view must dispatch statically (a microcontroller
    /// timing each step) drives it here, compiled once per view type; the scene and the view are
    /// the same either way.
    fn visit_concrete<T: Real, V: SceneView<T>>(self, view: &mut V) -> Self::Output
    where
        Self: Sized,
    {
        self.visit(view)
    }
}

/// A [`ViewVisitor`] as the registry's visitor of either engine.
#[cfg(any(
    feature = "scenes-k1",
    feature = "scenes-k2",
    feature = "scenes-k3",
    feature = "scenes-multibody"
))]
struct Viewing<V>(V);

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
impl<V: ViewVisitor> SceneVisitor for Viewing<V> {
    type Output = V::Output;

    /// The view holds the scene by `&mut`: where the registry built it, not moved into the view's
    /// frame (a microcontroller's stack holds the scene once).
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, mut scene: S) -> V::Output {
        self.0.visit_concrete(&mut PlanarView::new(&mut scene))
    }
}

#[cfg(feature = "scenes-multibody")]
impl<V: ViewVisitor> MultibodyVisitor for Viewing<V> {
    type Output = V::Output;

    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        scene: S,
    ) -> V::Output {
        self.0.visit_concrete(&mut MultibodyView::new(scene))
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
        match precision {
            Precision::F32 => self.build_view_in::<f32, E, V>(layout, visitor),
            Precision::F64 => self.build_view_in::<f64, E, V>(layout, visitor),
        }
    }

    /// [`Self::build_view`] with the precision a type: a microcontroller's driver builds only
    /// `f32`'s code.
    ///
    /// # Errors
    /// As [`Self::build_view`].
    pub fn build_view_in<T: Real, const E: usize, V: ViewVisitor>(
        &self,
        layout: LcpLayout,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        #[cfg(feature = "scenes-spatial")]
        if self.kind().is_spatial() {
            return self.build_spatial::<T, V>(visitor);
        }
        if self.kind().is_multibody() {
            #[cfg(feature = "scenes-multibody")]
            return self.build_multibody_in::<T, _>(Viewing(visitor));
            #[cfg(not(feature = "scenes-multibody"))]
            return Err(ParamError::OutOfRange("scene"));
        }
        #[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
        return self.build_in::<T, E, _>(layout, Viewing(visitor));
        #[cfg(not(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3")))]
        {
            let _ = (layout, visitor);
            Err(ParamError::OutOfRange("scene"))
        }
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
                Ok(visitor
                    .visit_concrete(&mut SpatialView::new(Puck::<T, CIRCULAR_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Puck(p) => {
                Ok(visitor
                    .visit_concrete(&mut SpatialView::new(Puck::<T, PYRAMID_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Billiard(p) if circular(p.friction_directions) => Ok(visitor
                .visit_concrete(&mut SpatialView::new(Billiard::<T, CIRCULAR_ROWS>::new(p.cast::<T>())?))),
            Self::Billiard(p) => {
                Ok(visitor
                    .visit_concrete(&mut SpatialView::new(Billiard::<T, PYRAMID_ROWS>::new(p.cast::<T>())?)))
            }
            Self::Curling(p) => {
                Ok(visitor.visit_concrete(&mut SpatialView::new(Curling::<T>::new(p.cast::<T>())?)))
            }
            Self::MeterStick3d(p) => {
                Ok(visitor.visit_concrete(&mut SpatialView::new(MeterStick3d::<T>::new(p.cast::<T>())?)))
            }
            // Validated above: 2 or 3 blocks.
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d(s) if s.block_count() == Some(2) => {
                use crate::scene::spatial::{Stack3d2, StackView};
                Ok(visitor.visit_concrete(&mut StackView::new(Stack3d2::<T>::new(s.params.cast::<T>())?)))
            }
            #[cfg(feature = "scenes-stack-3d")]
            Self::Stack3d(s) => {
                use crate::scene::spatial::{Stack3d3, StackView};
                Ok(visitor.visit_concrete(&mut StackView::new(Stack3d3::<T>::new(s.params.cast::<T>())?)))
            }
            _ => Err(ParamError::OutOfRange("scene")),
        }
    }
}

#[cfg(all(test, feature = "scenes"))]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scene::SceneKind;

    /// Up to 300 steps through the view, driven as the view's concrete type (`concrete`) or
    /// through `dyn` (the default [`ViewVisitor::visit_concrete`]); gives which way it was driven,
    /// the steps taken and the checksum.
    struct Run {
        concrete: bool,
    }

    fn steps<T: Real, V: SceneView<T> + ?Sized>(view: &mut V) -> (usize, u32) {
        let taken = (0..300).take_while(|_| view.step()).count();
        (taken, view.checksum())
    }

    impl ViewVisitor for Run {
        type Output = (bool, (usize, u32));
        fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
            (false, steps(view))
        }
        fn visit_concrete<T: Real, V: SceneView<T>>(self, view: &mut V) -> Self::Output {
            if self.concrete { (true, steps(view)) } else { self.visit(view) }
        }
    }

    /// Every scene is handed over as its concrete view, which runs as it does through `dyn`; and
    /// [`SceneParams::build_view_in`] in f32 builds what [`SceneParams::build_view`] does in
    /// [`Precision::F32`].
    #[test]
    fn every_scene_is_handed_over_as_its_concrete_view() {
        let layout = LcpLayout::Reduced;
        for kind in SceneKind::ALL {
            let params = SceneParams::defaults(kind);
            for precision in Precision::ALL {
                let (concrete, run) =
                    params.build_view::<0, _>(precision, layout, Run { concrete: true }).unwrap();
                let (through_dyn, dyn_run) =
                    params.build_view::<0, _>(precision, layout, Run { concrete: false }).unwrap();
                assert!(concrete && !through_dyn, "{kind} {precision:?}");
                assert!(run.0 > 0, "{kind} {precision:?}: no step");
                assert_eq!(run, dyn_run, "{kind} {precision:?}");
            }
            let f32_run = params.build_view::<0, _>(Precision::F32, layout, Run { concrete: true }).unwrap();
            let typed = params.build_view_in::<f32, 0, _>(layout, Run { concrete: true }).unwrap();
            assert_eq!(typed, f32_run, "{kind}");
        }
    }
}
