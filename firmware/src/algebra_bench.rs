//! The spatial core's hand-written rotations against nalgebra's (`UnitQuaternion`, `Matrix3`) on
//! the Cortex-M4F in f32 (`docs/formulation.md`, "Three dimensions", the algebra): SysTick ticks
//! (QEMU's `-icount shift=0`: instructions) for 1,000 of each operation a step repeats, printed as
//! `algebra <operation> hand=<ticks> nalgebra=<ticks>` (`host-sim qemu`).
//!
//! * `rotate`: a vector turned by a unit quaternion (`q v q*`): the core's
//!   `meterstick_core::spatial::rotate` against `UnitQuaternion::transform_vector`.
//! * `inverse-inertia`: a world vector times the world's inverse inertia `R D^-1 R^T a` (the
//!   Delassus operator's factor, per contact and direction): the core's two turns against
//!   nalgebra's quaternion turns, and against `R D^-1 R^T` built once as a `Matrix3`
//!   (`matrix-built`, once per body and step) then applied (`matrix-applied`).

use core::hint::black_box;

use meterstick_core::Real;
use meterstick_core::spatial::rotate;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

use crate::systick;

/// How many times each operation is timed.
const TIMES: u32 = 1_000;

/// Ticks for [`TIMES`] calls of `op` on the counter's inputs.
fn ticks(mut op: impl FnMut(u32) -> [f32; 3]) -> u32 {
    let t0 = systick::now();
    for i in 0..TIMES {
        black_box(op(black_box(i)));
    }
    systick::elapsed(t0, systick::now())
}

/// Times the operations and prints them.
pub fn run() {
    // A turn of 0.7 rad about a tilted axis (a unit quaternion), a vector, a body's inverse moments.
    let (sin, cos) = 0.35f32.sin_cos_portable();
    let axis = [0.48f32, -0.6, 0.64];
    let turn = black_box([cos, sin * axis[0], sin * axis[1], sin * axis[2]]);
    let vector = black_box([0.3f32, -1.2, 0.5]);
    let inverse = black_box([12.0f32, 3.0, 2.5]);
    let unit = UnitQuaternion::new_unchecked(Quaternion::new(turn[0], turn[1], turn[2], turn[3]));
    let moved = |i: u32| [vector[0] + i as f32, vector[1], vector[2]];
    let theirs_of = |a: [f32; 3]| Vector3::new(a[0], a[1], a[2]);
    let ours_of = |a: Vector3<f32>| [a[0], a[1], a[2]];

    let hand = ticks(|i| rotate(&black_box(turn), &moved(i)));
    let theirs = ticks(|i| ours_of(black_box(unit).transform_vector(&theirs_of(moved(i)))));
    defmt::println!("algebra rotate hand={=u32} nalgebra={=u32}", hand, theirs);

    let hand = ticks(|i| {
        let at = black_box(turn);
        let body = rotate(&[at[0], -at[1], -at[2], -at[3]], &moved(i));
        rotate(&at, &[inverse[0] * body[0], inverse[1] * body[1], inverse[2] * body[2]])
    });
    let theirs = ticks(|i| {
        let at = black_box(unit);
        let body = at.inverse_transform_vector(&theirs_of(moved(i)));
        ours_of(at.transform_vector(&body.component_mul(&theirs_of(inverse))))
    });
    defmt::println!("algebra inverse-inertia hand={=u32} nalgebra={=u32}", hand, theirs);

    let world = |at: UnitQuaternion<f32>, moments: [f32; 3]| -> Matrix3<f32> {
        let rotation = at.to_rotation_matrix().into_inner();
        rotation * Matrix3::from_diagonal(&theirs_of(moments)) * rotation.transpose()
    };
    let built = ticks(|i| {
        let matrix = world(black_box(unit), [inverse[0] + i as f32, inverse[1], inverse[2]]);
        [matrix[(0, 0)], matrix[(1, 1)], matrix[(2, 2)]]
    });
    let matrix = black_box(world(unit, inverse));
    let applied = ticks(|i| ours_of(black_box(matrix) * theirs_of(moved(i))));
    defmt::println!("algebra matrix-built nalgebra={=u32} matrix-applied nalgebra={=u32}", built, applied);
}
