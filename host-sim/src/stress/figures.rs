//! A scene's bodies as the stress runs need them (mass, size, inertia, the pull), read through the
//! core's [`SceneView`]: shared by the measures of one body ([`super::metrics`]) and of several
//! ([`super::bodies`]); and the principal moments of a body in three dimensions ([`moments_of`]),
//! from the parameters (the view gives a planar body's one moment).

use meterstick_core::Real;
use meterstick_core::scene::{BodyShape, Force, LcpLayout, SceneParams, SceneView, ViewVisitor};

use crate::scenes::Precision;

/// Each body's `(mass, width, height, inertia)` (body 0 the lowest; a disc's or a ball's width
/// and height its diameter, a puck's its diameter and thickness) and the pull on body 0 (N, along `x`), as the scene's f64 build holds them, read
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
                    BodyShape::Disc { radius } | BodyShape::Ball { radius } => {
                        ((radius + radius).as_f64(), (radius + radius).as_f64())
                    }
                    BodyShape::Puck { radius, thickness } => ((radius + radius).as_f64(), thickness.as_f64()),
                    // A block of the stack in three dimensions: its length and its height.
                    BodyShape::Cuboid { length, height, .. } => (length.as_f64(), height.as_f64()),
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

/// A scene in three dimensions' bodies' principal moments of inertia, in their own frames (kg
/// m^2), from the parameters as `docs/scenes.md` defines the bodies: the puck a uniform cylinder
/// (`m (3 r^2 + t^2) / 12` across, `m r^2 / 2` about its axis), the billiard ball a uniform sphere
/// (`2 m R^2 / 5`), the curling stone a thin ring (`m R^2` about its axis, half that across) or a
/// uniform disc (`m R^2 / 2`, `m R^2 / 4`), each block of the stack a uniform box (`m (W^2 + hb^2)
/// / 12`, `m (L^2 + hb^2) / 12`, `m (L^2 + W^2) / 12`); none for another scene.
#[must_use]
pub fn moments_of(spec: &SceneParams) -> Vec<[f64; 3]> {
    match spec {
        SceneParams::Puck(p) => {
            let (m, r, t) = (p.mass, p.radius, p.thickness);
            let across = m * (3.0 * r * r + t * t) / 12.0;
            vec![[across, across, m * r * r / 2.0]]
        }
        SceneParams::Billiard(p) => vec![[0.4 * p.mass * p.radius * p.radius; 3]],
        SceneParams::Curling(p) => {
            let axis = if p.is_ring() { 1.0 } else { 0.5 } * p.mass * p.radius * p.radius;
            vec![[axis / 2.0, axis / 2.0, axis]]
        }
        SceneParams::Stack3d(s) => {
            let p = s.params;
            let (m, l, w, h) = (p.mass, p.length, p.width, p.height);
            let block = [m * (w * w + h * h) / 12.0, m * (l * l + h * h) / 12.0, m * (l * l + w * w) / 12.0];
            vec![block; s.block_count().unwrap_or(0)]
        }
        _ => Vec::new(),
    }
}
