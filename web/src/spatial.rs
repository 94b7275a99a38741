//! The scenes in three dimensions on the page (feature `sp`, the module
//! `meterstick_web_sp.wasm`): the row a step writes ([`write_row`], [`SPATIAL_ROW`] numbers), the
//! body's solid ([`Solid`]) and the supports ([`SupportOf`]) the page draws in perspective. The
//! run itself is [`crate::sim::Sim`]'s, through the core's `SceneView` as every other scene.

use meterstick_core::Real;
use meterstick_core::scene::{BodyShape, Pose, SceneView, SupportView, Velocity, ViewReader};

use crate::modes::mode_code;

/// The most bodies a scene in three dimensions moves (the stack's three blocks; the others one).
pub const SPATIAL_BODIES: usize = 3;

/// The most contacts a scene in three dimensions lists (the stack's sixteen slots; the curling
/// stone's ring of points eight, the meter stick three, the puck and the ball one).
pub const SPATIAL_CONTACTS: usize = 16;
const _: () = assert!(
    SPATIAL_CONTACTS >= meterstick_core::scene::spatial::MAX_POINTS
        && SPATIAL_CONTACTS >= meterstick_core::scene::spatial::ROD_POINTS
);

/// Numbers per contact in a row: the point (3), the normal on the body (3), the friction's
/// direction (3), the mode's code, the normal impulse and the friction impulse's magnitude.
pub const CONTACT_NUMBERS: usize = 12;

/// Numbers per body in a row: the position (3), the orientation `[w, x, y, z]` (4), the velocity
/// (3) and the angular velocity (3), world axes, `z` up.
pub const STATE_NUMBERS: usize = 13;

/// Numbers before the contacts: time, then each of [`SPATIAL_BODIES`] bodies' state (NaN past
/// the scene's bodies; body 0 the lowest).
pub const BODY_NUMBERS: usize = 1 + STATE_NUMBERS * SPATIAL_BODIES;

/// Numbers per row of a scene in three dimensions: the bodies, then [`SPATIAL_CONTACTS`]
/// contacts (NaN past the scene's contacts).
pub const SPATIAL_ROW: usize = BODY_NUMBERS + CONTACT_NUMBERS * SPATIAL_CONTACTS;

/// Writes `view`'s row as it is now into `row` ([`SPATIAL_ROW`] numbers): the contacts' impulses
/// over its last step (zero before the first).
pub fn write_row<T: Real>(view: &dyn SceneView<T>, row: &mut [f64]) {
    row[0] = view.time().as_f64();
    for (b, slot) in row[1..BODY_NUMBERS].chunks_exact_mut(STATE_NUMBERS).enumerate() {
        let Some(body) = view.body(b) else {
            slot.fill(f64::NAN);
            continue;
        };
        if let (Pose::Spatial { position, orientation }, Velocity::Spatial { linear, angular }) =
            (body.pose, body.velocity)
        {
            let state = position.into_iter().chain(orientation).chain(linear).chain(angular);
            for (s, x) in slot.iter_mut().zip(state) {
                *s = x.as_f64();
            }
        }
    }
    for (i, slot) in row[BODY_NUMBERS..SPATIAL_ROW].chunks_exact_mut(CONTACT_NUMBERS).enumerate() {
        let Some(c) = view.contact(i) else {
            slot.fill(f64::NAN);
            continue;
        };
        for (s, x) in slot.iter_mut().zip(c.point.into_iter().chain(c.normal).chain(c.tangent)) {
            *s = x.as_f64();
        }
        slot[9] = f64::from(mode_code(c.mode));
        slot[10] = c.normal_impulse.as_f64();
        slot[11] = c.friction_impulse.as_f64();
    }
}

/// The bodies' solid as the page draws it: `[code, a, b, c]`, code 0 a box `a` long by `b` thick
/// (square section; the meter stick), 1 a ball of radius `a`, 2 a flat cylinder of radius `a` and
/// thickness `b` about the body's `z` (the puck, the curling stone), 3 a box `a` long, `b` wide
/// and `c` high (each block of the stack; every body of a scene has body 0's); `None` without a
/// body.
#[derive(Debug)]
pub struct Solid;

impl ViewReader for Solid {
    type Output = Option<[f64; 4]>;
    fn read<T: Real>(self, view: &dyn SceneView<T>) -> Option<[f64; 4]> {
        match view.body(0)?.shape {
            BodyShape::Box { width, height } => Some([0.0, width.as_f64(), height.as_f64(), 0.0]),
            BodyShape::Ball { radius } => Some([1.0, radius.as_f64(), 0.0, 0.0]),
            BodyShape::Puck { radius, thickness } => Some([2.0, radius.as_f64(), thickness.as_f64(), 0.0]),
            BodyShape::Cuboid { length, width, height } => {
                Some([3.0, length.as_f64(), width.as_f64(), height.as_f64()])
            }
            _ => None,
        }
    }
}

/// Support `i` as the page draws it: `[code, p, d]` with code 1 a fixed plane through `p` with
/// unit normal `d`, 2 a finger lying along `d` through its tip `p` (where the last step left it),
/// 3 the table whose top `z = 0` ends at the edge `x = p_x` (its side `x <= p_x`; `d` its normal,
/// `z`); `None` past the scene's supports.
#[derive(Debug)]
pub struct SupportOf(pub usize);

impl ViewReader for SupportOf {
    type Output = Option<[f64; 7]>;
    fn read<T: Real>(self, view: &dyn SceneView<T>) -> Option<[f64; 7]> {
        let (code, p, d) = match view.support(self.0)? {
            SupportView::Plane { point, normal } => (1.0, point, normal),
            SupportView::Finger { tip, across, .. } => (2.0, tip, across),
            SupportView::Table { hi: Some(edge), .. } => {
                let zero = T::zero();
                (3.0, [edge, zero, zero], [zero, zero, T::one()])
            }
            _ => return None,
        };
        let mut out = [code, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        for (s, x) in out[1..].iter_mut().zip(p.into_iter().chain(d)) {
            *s = x.as_f64();
        }
        Some(out)
    }
}
