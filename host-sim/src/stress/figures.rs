//! A scene's bodies as the stress runs need them (mass, size, inertia, the pull), read through the
//! core's [`SceneView`]: shared by the measures of one body ([`super::metrics`]) and of several
//! ([`super::bodies`]).

use meterstick_core::Real;
use meterstick_core::scene::{BodyShape, Force, LcpLayout, SceneParams, SceneView, ViewVisitor};

use crate::scenes::Precision;

/// Each body's `(mass, width, height, inertia)` (body 0 the lowest; a disc's width and height its
/// diameter) and the pull on body 0 (N, along `x`), as the scene's f64 build holds them, read
/// through its [`SceneView`] (no figure here names a scene); none for a scene the core refuses.
#[must_use]
pub fn bodies_of(spec: &SceneParams) -> (Vec<(f64, f64, f64, f64)>, f64) {
    spec.build_view::<0, _>(Precision::F64, LcpLayout::Full, Figures).unwrap_or_default()
}

/// [`bodies_of`] as a visitor of the core's views.
struct Figures;

impl ViewVisitor for Figures {
    type Output = (Vec<(f64, f64, f64, f64)>, f64);

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Self::Output {
        let bodies = (0..view.body_count())
            .filter_map(|i| view.body(i))
            .map(|b| {
                let (w, h) = match b.shape {
                    BodyShape::Box { width, height } => (width.as_f64(), height.as_f64()),
                    BodyShape::Disc { radius } => ((radius + radius).as_f64(), (radius + radius).as_f64()),
                    _ => (f64::NAN, f64::NAN),
                };
                (b.mass.as_f64(), w, h, b.inertia.as_f64())
            })
            .collect();
        let pull = match view.body(0).map(|b| b.force) {
            Some(Force::Planar { fx, .. }) => fx.as_f64(),
            _ => 0.0,
        };
        (bodies, pull)
    }
}
