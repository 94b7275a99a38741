//! The face patch against geometry worked out by hand: a block on a wider one, a block over the
//! table's edge at two headings, a tilted block over the edge, two equal squares at 45 degrees (an
//! octagon), a lifted block, an upturned one, and a patch too small.
#![allow(clippy::unwrap_used, clippy::float_cmp, clippy::panic)]

use super::super::algebra::{Vector, about, identity};
use super::super::body::State;
use super::{Beneath, FaceContact, FacePatch, PatchOverflow, face_patch};
use crate::real::Real;

const HALF: [f64; 3] = [0.1, 0.05, 0.025];
const MARGIN: f64 = 1e-3;

fn state<T: Real>(position: [f64; 3], axis: [f64; 3], angle: f64) -> State<T> {
    let axis = axis.map(T::of);
    State {
        position: position.map(T::of),
        orientation: if angle == 0.0 { identity() } else { about(&axis, T::of(angle)) },
        velocity: [T::zero(); 3],
        angular_velocity: [T::zero(); 3],
    }
}

fn half<T: Real>(h: [f64; 3]) -> Vector<T> {
    h.map(T::of)
}

/// The contact of `patch` at `point` (within `tol`), which must be there.
fn at<T: Real>(patch: &[FaceContact<T>], point: [f64; 3], tol: f64) -> &FaceContact<T> {
    let found: Vec<_> =
        patch.iter().filter(|c| (0..3).all(|i| (c.point[i].as_f64() - point[i]).abs() <= tol)).collect();
    assert_eq!(found.len(), 1, "one contact at {point:?} in {patch:?}");
    found[0]
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
}

fn centred_on_wider<T: Real>(tol: f64) {
    // The lower block twice as long and wide, its top at z = 0.05; the upper level on it.
    let lower = state::<T>([0.0, 0.0, 0.025], [0.0, 0.0, 1.0], 0.0);
    let upper = state::<T>([0.0, 0.0, 0.075], [0.0, 0.0, 1.0], 0.0);
    let below = Beneath::Block { state: &lower, half: half([0.2, 0.1, 0.025]) };
    let patch: FacePatch<T, 8> = face_patch(&upper, &half(HALF), below, T::of(MARGIN)).unwrap();
    assert_eq!(patch.len(), 4, "{patch:?}");
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let c = at(patch.as_slice(), [sx * HALF[0], sy * HALF[1], 0.05], tol);
        assert!(c.upper_corner, "{c:?}");
        assert!(c.gap.as_f64().abs() <= tol, "{c:?}");
        assert!(close(c.normal.map(T::as_f64), [0.0, 0.0, 1.0], tol), "{c:?}");
    }
}

#[test]
fn face_patch_of_a_level_block_centred_on_a_wider_one_is_its_four_corners() {
    centred_on_wider::<f64>(1e-15);
    centred_on_wider::<f32>(1e-7);
}

/// Half the block over the table's edge at heading 0: its two corners on the table, the edge's
/// two points under the block's sides.
fn half_over_the_edge<T: Real>(tol: f64) {
    let upper = state::<T>([0.0, 0.0, HALF[2]], [0.0, 0.0, 1.0], 0.0);
    let patch: FacePatch<T, 6> = face_patch(&upper, &half(HALF), Beneath::Table, T::of(MARGIN)).unwrap();
    assert_eq!(patch.len(), 4, "{patch:?}");
    for sy in [-1.0, 1.0] {
        let corner = at(patch.as_slice(), [-HALF[0], sy * HALF[1], 0.0], tol);
        assert!(corner.upper_corner);
        let edge = at(patch.as_slice(), [0.0, sy * HALF[1], 0.0], tol);
        assert!(!edge.upper_corner);
        for c in [corner, edge] {
            assert!(c.gap.as_f64().abs() <= tol && close(c.normal.map(T::as_f64), [0.0, 0.0, 1.0], tol));
        }
    }
}

#[test]
fn face_patch_of_a_block_half_over_the_table_edge_is_two_corners_and_two_edge_points() {
    half_over_the_edge::<f64>(1e-15);
    half_over_the_edge::<f32>(1e-7);
}

/// At heading 30 degrees, centred at `x = -0.08`: the corner `c + a d - b e` is past the edge
/// (`x = c + a cos psi + b sin psi > 0`), the other three on the table, and the edge `x = 0` cuts
/// the two sides from it: along `d` at `P - (P_x / cos psi) d`, along `e` at `P + (P_x / sin psi)
/// e`.
fn heading_30<T: Real>(tol: f64) {
    let psi = 30f64.to_radians();
    let (s, c) = psi.sin_cos();
    let (d, e) = ([c, s, 0.0], [-s, c, 0.0]);
    let centre = [-0.08, 0.0, HALF[2]];
    let upper = state::<T>(centre, [0.0, 0.0, 1.0], psi);
    let patch: FacePatch<T, 6> = face_patch(&upper, &half(HALF), Beneath::Table, T::of(MARGIN)).unwrap();
    assert_eq!(patch.len(), 5, "{patch:?}");
    let corner = |sx: f64, sy: f64| {
        [0, 1, 2].map(|i| centre[i] + sx * HALF[0] * d[i] + sy * HALF[1] * e[i] - [0.0, 0.0, HALF[2]][i])
    };
    let past = corner(1.0, -1.0);
    assert!(past[0] > 0.0);
    for (sx, sy) in [(-1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        assert!(at(patch.as_slice(), corner(sx, sy), tol).upper_corner);
    }
    let along_d = [0, 1, 2].map(|i| past[i] - past[0] / c * d[i]);
    let along_e = [0, 1, 2].map(|i| past[i] + past[0] / s * e[i]);
    for point in [along_d, along_e] {
        assert!(point[0].abs() < 1e-15);
        let edge = at(patch.as_slice(), point, tol);
        assert!(!edge.upper_corner && edge.gap.as_f64().abs() <= tol, "{edge:?}");
    }
}

#[test]
fn face_patch_at_heading_30_deg_with_one_corner_past_the_edge_has_five_vertices() {
    heading_30::<f64>(1e-15);
    heading_30::<f32>(2e-7);
}

/// Pitched by `theta` about `y`, the bottom face's centre `(0, 0, h0)`: the face's plane is `z =
/// h0 - x tan theta`. The corners on the table, `(-a cos theta, ±b, h0 + a sin theta)`, rest
/// along `z` at that height; the edge's points `(0, ±b, 0)` push along the face's normal `(sin
/// theta, 0, cos theta)` at its distance `h0 cos theta`.
#[test]
fn face_patch_of_a_tilted_block_takes_each_vertex_by_the_corner_on_face_rule() {
    let (theta, h0) = (-0.005f64, 1e-4);
    let (s, c) = theta.sin_cos();
    let [a, b, hz] = HALF;
    let upper = state::<f64>([hz * s, 0.0, h0 + hz * c], [0.0, 1.0, 0.0], theta);
    let patch: FacePatch<f64, 6> = face_patch(&upper, &HALF, Beneath::Table, MARGIN).unwrap();
    assert_eq!(patch.len(), 4, "{patch:?}");
    for sy in [-1.0, 1.0] {
        let corner = at(patch.as_slice(), [-a * c, sy * b, h0 + a * s], 1e-15);
        assert!(corner.upper_corner && close(corner.normal, [0.0, 0.0, 1.0], 1e-15));
        assert!((corner.gap - (h0 + a * s)).abs() <= 1e-15, "{corner:?}");
        let edge = at(patch.as_slice(), [0.0, sy * b, 0.0], 1e-15);
        assert!(!edge.upper_corner && close(edge.normal, [s, 0.0, c], 1e-15));
        assert!((edge.gap - h0 * c).abs() <= 1e-15, "{edge:?}");
    }
}

/// Two squares of half side `h`, one turned 45 degrees on the other: they overlap in the regular
/// octagon `|x|, |y| <= h`, `|x ± y| <= h sqrt 2`, whose vertices `(±h, ±(sqrt 2 - 1) h)` and
/// `(±(sqrt 2 - 1) h, ±h)` are all crossings of edges.
#[test]
fn face_patch_of_equal_squares_at_45_deg_is_an_octagon_of_crossings() {
    let hs = 0.05;
    let lower = state::<f64>([0.0, 0.0, 0.025], [0.0, 0.0, 1.0], 0.0);
    let upper = state::<f64>([0.0, 0.0, 0.075], [0.0, 0.0, 1.0], 45f64.to_radians());
    let square = [hs, hs, 0.025];
    let below = Beneath::Block { state: &lower, half: square };
    let patch: FacePatch<f64, 8> = face_patch(&upper, &square, below, MARGIN).unwrap();
    assert_eq!(patch.len(), 8, "{patch:?}");
    let k = (2f64.sqrt() - 1.0) * hs;
    for (x, y) in [(hs, k), (hs, -k), (-hs, k), (-hs, -k), (k, hs), (-k, hs), (k, -hs), (-k, -hs)] {
        let c = at(patch.as_slice(), [x, y, 0.05], 1e-15);
        assert!(!c.upper_corner && c.gap.abs() <= 1e-15, "{c:?}");
    }
    // Seven places are too few: refused, every contact counted.
    let small: Result<FacePatch<f64, 7>, _> = face_patch(&upper, &square, below, MARGIN);
    assert_eq!(small.unwrap_err(), PatchOverflow { capacity: 7, needed: 8 });
}

fn lifted<T: Real>() {
    let lower = state::<T>([0.0, 0.0, 0.025], [0.0, 0.0, 1.0], 0.0);
    let below = Beneath::Block { state: &lower, half: half([0.2, 0.1, 0.025]) };
    // Lifted by twice the margin: nothing; by half of it: the four corners at that gap.
    let high = state::<T>([0.0, 0.0, 0.075 + 2.0 * MARGIN], [0.0, 0.0, 1.0], 0.0);
    let none: FacePatch<T, 4> = face_patch(&high, &half(HALF), below, T::of(MARGIN)).unwrap();
    assert!(none.is_empty(), "{none:?}");
    let near = state::<T>([0.0, 0.0, 0.075 + 0.5 * MARGIN], [0.0, 0.0, 1.0], 0.0);
    let four: FacePatch<T, 4> = face_patch(&near, &half(HALF), below, T::of(MARGIN)).unwrap();
    assert_eq!(four.len(), 4);
    // The heights' round-off: a few eps of 0.1 m.
    let tol = 8.0 * T::EPS.as_f64() * 0.1;
    assert!(four.iter().all(|c| (c.gap.as_f64() - 0.5 * MARGIN).abs() <= tol), "{four:?}");
}

#[test]
fn face_patch_of_a_block_lifted_beyond_the_margin_is_empty() {
    lifted::<f64>();
    lifted::<f32>();
}

#[test]
fn face_patch_of_faces_turned_away_is_empty() {
    // Upside down on the table (n_u . n_l = -1), and turned just past its side.
    for angle in [core::f64::consts::PI, core::f64::consts::FRAC_PI_2 + 0.1] {
        let upper = state::<f64>([-0.1, 0.0, HALF[2]], [1.0, 0.0, 0.0], angle);
        let patch: FacePatch<f64, 6> = face_patch(&upper, &HALF, Beneath::Table, 1.0).unwrap();
        assert!(patch.is_empty(), "{angle}: {patch:?}");
    }
}

#[test]
fn face_patch_too_small_for_its_contacts_is_an_error_not_a_drop() {
    let upper = state::<f32>([0.0, 0.0, 0.025], [0.0, 0.0, 1.0], 0.0);
    let err = face_patch::<f32, 3>(&upper, &half(HALF), Beneath::Table, 1e-3).unwrap_err();
    assert_eq!(err, PatchOverflow { capacity: 3, needed: 4 });
}

/// Blocks of one width edge on edge at heading 30 degrees, the upper `o = 0.05` further along
/// `d`: the overlap is `-a <= u <= a - o`, `|w| <= b` of the upper's own axes, its two corners
/// at `u = -a` the upper face's, the two at `u = a - o` the lower's. Moved across by `delta`
/// within the band (`64 eps (2 a + 2 b)`, 4.3e-15 m) its sides are still on the lower's: the same
/// four vertices; moved by 1e-13 m the corners on that side are clipped, crossings in their place.
#[test]
fn face_patch_of_blocks_of_one_width_edge_on_edge_is_four_vertices_whatever_the_round_off() {
    let psi = 30f64.to_radians();
    let (s, c) = psi.sin_cos();
    let [a, b, hz] = HALF;
    let o = 0.05;
    let lower = state::<f64>([0.0, 0.0, hz], [0.0, 0.0, 1.0], psi);
    let below = Beneath::Block { state: &lower, half: HALF };
    for delta in [-3e-15, -1e-15, 0.0, 1e-15, 3e-15, 1e-13] {
        let centre = [o * c - delta * s, o * s + delta * c, 3.0 * hz];
        let upper = state::<f64>(centre, [0.0, 0.0, 1.0], psi);
        let patch: FacePatch<f64, 8> = face_patch(&upper, &HALF, below, MARGIN).unwrap();
        assert_eq!(patch.len(), 4, "delta {delta}: {patch:?}");
        for (u, w, upper_corner) in [(-a, -b, true), (-a, b, true), (a - o, -b, false), (a - o, b, false)] {
            let w = if delta > 1e-14 && w > 0.0 { w - delta } else { w };
            let point = [centre[0] + u * c - w * s, centre[1] + u * s + w * c, 2.0 * hz];
            let found = at(patch.as_slice(), point, 1e-15);
            let expected = upper_corner && !(delta > 1e-14 && w > 0.0);
            assert_eq!(found.upper_corner, expected, "delta {delta}: {found:?}");
        }
    }
}
