//! Where a block's flat bottom face rests on a flat face below it: the contacts of
//! `docs/scenes.md`, "stack-3d", "Contacts", on fixed arrays (no heap, no panic), in `f32` or
//! `f64`.
//!
//! # The rule
//!
//! The upper block (centre `x_u`, orientation `q_u`, half extents `(a, b, c)` along its own axes)
//! has the bottom face of corners `x_u + q_u (±a, ±b, -c)`, its outward normal `-n_u`, `n_u` the
//! block's own `z` in the world. The lower face ([`Beneath`]) is
//!
//! - a block's top face: centre `x_l + q_l (0, 0, c_l)`, axes `e_s`, `e_t` (the lower block's own
//!   `x` and `y`), normal `n_l` (its own `z`), the rectangle `|s| <= a_l`, `|t| <= b_l`;
//! - the table: centre `0`, axes `x`, `y`, normal `z`, the half-plane `s <= 0` (`x <= 0`; its edge
//!   the line `x = 0`, `z = 0`).
//!
//! 1. **The overlap.** The upper face's corners, taken in the order `(-a, -b)`, `(a, -b)`, `(a, b)`,
//!    `(-a, b)`, are projected along `n_l` onto the lower face's plane, `(s, t) = ((P - centre) .
//!    e_s, (P - centre) . e_t)`, and the quadrilateral is clipped by the lower face's half-planes
//!    (Sutherland & Hodgman), for each half-plane `f <= 0` in turn, in the order `s <= a_l`, `-s
//!    <= a_l`, `t <= b_l`, `-t <= b_l`, or the table's `s <= 0`. A vertex within `delta = 64 eps
//!    (2 a + 2 b)` of the line (`|f| <= delta`; `64 eps` of the upper face's length plus width) is
//!    on it, and kept; one with `f < -delta` is kept; one with `f > delta` is dropped; where an
//!    edge's ends lie beyond `delta` on the line's two sides a point of the line is added, at
//!    `prev + f_prev / (f_prev - f_cur) (cur - prev)`. A kept vertex of the quadrilateral is an
//!    *upper corner*; every added one (a lower corner, a point of the table's edge, two edges
//!    crossing) is not.
//!
//!    The band makes blocks of one width standing edge on edge (the stack's start, and any tilt
//!    about the blocks' common `e`) one overlap whatever the round-off: without it, the side of
//!    the line each of the two corners of a side falls on is round-off's, and a corner a hair
//!    outside with its neighbour a hair inside puts a crossing anywhere along the side between
//!    them (two implementations rounding differently find four vertices or five, and a corner or
//!    a crossing, whose normals differ by the blocks' relative tilt). A corner carried past the
//!    side beyond the band is clipped away, and the crossing beside it takes its place.
//! 2. **Coinciding vertices.** Consecutive vertices (the last and the first included) within
//!    `delta` of each other are one vertex: an upper corner where one of them is (the upper
//!    face's), otherwise the first.
//! 3. **Facing.** When `n_u . n_l <= 0` the faces do not face each other: no contacts.
//! 4. **Each vertex** `(s, t)`, the lower face's point `Q = centre + s e_s + t e_t`, the upper
//!    face's height over it along `n_l`, `lambda = n_u . (x_u - c n_u - Q) / (n_u . n_l)`:
//!    - an upper corner is that corner on the lower face: point `Q + lambda n_l`, normal `n_l`,
//!      gap `lambda`;
//!    - any other vertex is the lower body's point on the upper face: point `Q`, normal `n_u`
//!      (the upper face's, turned up), gap `lambda (n_u . n_l)`, `Q`'s distance to the upper
//!      face's plane.
//! 5. **Active** when `gap <= margin`. The normal is the direction of the push on the upper
//!    block; the caller knows the lower body, which takes the opposite push.
//!
//! # Fixed sizes
//!
//! Clipping a polygon of `n` vertices by a half-plane keeps `k` of them and adds one per edge from
//! a kept vertex to a dropped one or back, at most `2 min(k, n - k)` of them: at most `3 n / 2` in all, however
//! round-off bends the polygon (a convex one gains at most one). The quadrilateral's four clips
//! hold at most `4, 6, 9, 13, 19` vertices ([`SCRATCH`]), so no vertex is ever lost. At most `C`
//! active contacts fit a [`FacePatch`], and more is [`PatchOverflow`]: two rectangles overlap in
//! at most an octagon, a rectangle cut by the table's edge in at most a pentagon (a convex polygon
//! gains at most one vertex a clip), so `C = 8` holds every patch of the stack.

use super::algebra::{Vector, add, dot, rotate, scale, sub};
use super::body::State;
use crate::real::Real;
use heapless::Vec;

/// The vertices the clipping of a quadrilateral by four half-planes can hold (`4 -> 6 -> 9 -> 13
/// -> 19`, the module docs' "Fixed sizes").
pub const SCRATCH: usize = 19;

/// What a block's bottom face rests on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Beneath<'a, T> {
    /// The table: the top face `z = 0` over `x <= 0`, its edge the line `x = 0`, `z = 0`.
    Table,
    /// A block's top face: the block at `state`, of half extents `half` along its own axes.
    Block {
        /// The lower block.
        state: &'a State<T>,
        /// Its half extents along its own `x`, `y`, `z`, m.
        half: Vector<T>,
    },
}

/// One contact of a face on a face: a vertex of the overlap polygon (module docs, 4).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FaceContact<T> {
    /// Where the impulse acts, world, m.
    pub point: Vector<T>,
    /// Unit, world: the direction of the push on the upper block.
    pub normal: Vector<T>,
    /// The gap along `normal`, m (negative: the faces overlap).
    pub gap: T,
    /// `true` for a corner of the upper face (the lower face's normal), `false` for the lower
    /// body's point on the upper face (the upper face's normal).
    pub upper_corner: bool,
}

/// The active contacts of one face on another, at most `C` of them, in the overlap polygon's order.
#[derive(Debug, Clone, PartialEq)]
pub struct FacePatch<T, const C: usize> {
    contacts: Vec<FaceContact<T>, C>,
}

impl<T, const C: usize> FacePatch<T, C> {
    /// The contacts, in the overlap polygon's order.
    #[must_use]
    pub fn as_slice(&self) -> &[FaceContact<T>] {
        &self.contacts
    }

    /// The contacts, in the overlap polygon's order.
    pub fn iter(&self) -> core::slice::Iter<'_, FaceContact<T>> {
        self.contacts.iter()
    }

    /// How many contacts.
    #[must_use]
    pub fn len(&self) -> usize {
        self.contacts.len()
    }

    /// `true` when the faces do not touch within the margin.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.contacts.is_empty()
    }
}

impl<'p, T, const C: usize> IntoIterator for &'p FacePatch<T, C> {
    type Item = &'p FaceContact<T>;
    type IntoIter = core::slice::Iter<'p, FaceContact<T>>;
    fn into_iter(self) -> Self::IntoIter {
        self.contacts.iter()
    }
}

/// More vertices than an array holds: `needed` where `capacity` fit. From [`face_patch`], the
/// active contacts against the patch's `C` (the clipping's scratch, [`SCRATCH`], holds every
/// vertex by the module docs' count).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PatchOverflow {
    /// The array's size.
    pub capacity: usize,
    /// The vertices it was asked to hold.
    pub needed: usize,
}

/// A vertex of the overlap polygon in the lower face's coordinates `(s, t)`.
#[derive(Debug, Clone, Copy)]
struct Vertex<T> {
    at: [T; 2],
    upper_corner: bool,
}

type Polygon<T> = Vec<Vertex<T>, SCRATCH>;

/// A half-plane `sign * v[axis] <= limit` of the lower face's coordinates.
#[derive(Clone, Copy)]
struct HalfPlane<T> {
    axis: usize,
    sign: T,
    limit: T,
}

impl<T: Real> HalfPlane<T> {
    /// `sign * v[axis] - limit`: `<= 0` inside (on the line included).
    fn side(&self, v: &Vertex<T>) -> T {
        self.sign * v.at.get(self.axis).copied().unwrap_or_else(T::zero) - self.limit
    }
}

/// Where a vertex lies from a half-plane's line: beyond `band` of it (`In` or `Out`) or on it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    In,
    On,
    Out,
}

/// `poly` clipped to `plane` (Sutherland & Hodgman, a vertex within `band` of the line on it; the
/// module docs, 1).
fn clip<T: Real>(poly: &Polygon<T>, plane: HalfPlane<T>, band: T) -> Result<Polygon<T>, PatchOverflow> {
    let side = |f: T| {
        if f > band {
            Side::Out
        } else if f < -band {
            Side::In
        } else {
            Side::On
        }
    };
    let mut out = Polygon::new();
    let push = |v: Vertex<T>, out: &mut Polygon<T>| {
        out.push(v).map_err(|_| PatchOverflow { capacity: SCRATCH, needed: SCRATCH + 1 })
    };
    let Some(mut prev) = poly.last().copied() else {
        return Ok(out);
    };
    for cur in poly {
        let (fp, fc) = (plane.side(&prev), plane.side(cur));
        let (sp, sc) = (side(fp), side(fc));
        if matches!((sp, sc), (Side::In, Side::Out) | (Side::Out, Side::In)) {
            let k = fp / (fp - fc);
            let at = [prev.at[0] + k * (cur.at[0] - prev.at[0]), prev.at[1] + k * (cur.at[1] - prev.at[1])];
            push(Vertex { at, upper_corner: false }, &mut out)?;
        }
        if sc != Side::Out {
            push(*cur, &mut out)?;
        }
        prev = *cur;
    }
    Ok(out)
}

/// `true` when `p` and `q` are within `merge` of each other.
fn coincide<T: Real>(p: &Vertex<T>, q: &Vertex<T>, merge: T) -> bool {
    let (ds, dt) = (p.at[0] - q.at[0], p.at[1] - q.at[1]);
    ds * ds + dt * dt <= merge * merge
}

/// Coinciding consecutive vertices made one, the upper corner kept (module docs, 2).
fn merged<T: Real>(poly: &Polygon<T>, merge: T) -> Polygon<T> {
    let mut out = Polygon::new();
    for v in poly {
        match out.last_mut() {
            Some(kept) if coincide(kept, v, merge) => {
                if v.upper_corner && !kept.upper_corner {
                    *kept = *v;
                }
            }
            // `out` holds no more vertices than `poly`: the push cannot fail.
            _ => out.push(*v).unwrap_or(()),
        }
    }
    if out.len() > 1 {
        let last = out.last().copied();
        if let (Some(first), Some(last)) = (out.first_mut(), last)
            && coincide(first, &last, merge)
        {
            if last.upper_corner && !first.upper_corner {
                *first = last;
            }
            out.pop();
        }
    }
    out
}

/// The lower face: its centre, axes `e_s`, `e_t`, normal, and half-planes.
struct Below<T> {
    centre: Vector<T>,
    axes: [Vector<T>; 3],
    planes: Vec<HalfPlane<T>, 4>,
}

impl<T: Real> Below<T> {
    fn of(beneath: &Beneath<'_, T>) -> Self {
        let (zero, one) = (T::zero(), T::one());
        match beneath {
            Beneath::Table => {
                let mut planes = Vec::new();
                // One plane into a vector of four: cannot fail.
                planes.push(HalfPlane { axis: 0, sign: one, limit: zero }).unwrap_or(());
                Self {
                    centre: [zero; 3],
                    axes: [[one, zero, zero], [zero, one, zero], [zero, zero, one]],
                    planes,
                }
            }
            Beneath::Block { state, half } => {
                let q = &state.orientation;
                let axes = [
                    rotate(q, &[one, zero, zero]),
                    rotate(q, &[zero, one, zero]),
                    rotate(q, &[zero, zero, one]),
                ];
                let centre = add(&state.position, &scale(half[2], &axes[2]));
                let planes = Vec::from_array([
                    HalfPlane { axis: 0, sign: one, limit: half[0] },
                    HalfPlane { axis: 0, sign: -one, limit: half[0] },
                    HalfPlane { axis: 1, sign: one, limit: half[1] },
                    HalfPlane { axis: 1, sign: -one, limit: half[1] },
                ]);
                Self { centre, axes, planes }
            }
        }
    }
}

/// The active contacts (`gap <= margin`) of the block at `upper`, of half extents `half` along
/// its own axes, resting its bottom face on `beneath`: `docs/scenes.md`, "stack-3d", "Contacts",
/// as the module docs write it out. Empty when the faces do not face each other (`n_u . n_l <=
/// 0`), do not overlap, or stand apart beyond `margin`.
///
/// # Errors
/// [`PatchOverflow`] when more than `C` contacts are active (`needed` counts them all); never a
/// contact dropped.
pub fn face_patch<T: Real, const C: usize>(
    upper: &State<T>,
    half: &Vector<T>,
    beneath: Beneath<'_, T>,
    margin: T,
) -> Result<FacePatch<T, C>, PatchOverflow> {
    let mut patch = FacePatch { contacts: Vec::new() };
    let lower = Below::of(&beneath);
    let [e_s, e_t, n_lower] = lower.axes;
    let q = &upper.orientation;
    let n_upper = rotate(q, &[T::zero(), T::zero(), T::one()]);
    let across = dot(&n_upper, &n_lower);
    if !across.finite() || across <= T::zero() {
        return Ok(patch);
    }
    let bottom = add(&upper.position, &scale(-half[2], &n_upper));
    let (one, two) = (T::one(), T::of(2.0));
    let mut poly = Polygon::new();
    for (ss, st) in [(-one, -one), (one, -one), (one, one), (-one, one)] {
        let corner = add(&upper.position, &rotate(q, &[ss * half[0], st * half[1], -half[2]]));
        let r = sub(&corner, &lower.centre);
        // Four corners into nineteen places: cannot fail.
        poly.push(Vertex { at: [dot(&r, &e_s), dot(&r, &e_t)], upper_corner: true }).unwrap_or(());
    }
    let merge = T::of(64.0) * T::EPS * two * (half[0] + half[1]);
    for plane in &lower.planes {
        poly = clip(&poly, *plane, merge)?;
    }
    let mut needed = 0;
    for v in &merged(&poly, merge) {
        let on_lower = add(&lower.centre, &add(&scale(v.at[0], &e_s), &scale(v.at[1], &e_t)));
        let lambda = dot(&n_upper, &sub(&bottom, &on_lower)) / across;
        let contact = if v.upper_corner {
            FaceContact {
                point: add(&on_lower, &scale(lambda, &n_lower)),
                normal: n_lower,
                gap: lambda,
                upper_corner: true,
            }
        } else {
            FaceContact { point: on_lower, normal: n_upper, gap: lambda * across, upper_corner: false }
        };
        if contact.gap <= margin {
            needed += 1;
            // A full patch is counted on and refused below.
            patch.contacts.push(contact).unwrap_or(());
        }
    }
    if needed > C {
        return Err(PatchOverflow { capacity: C, needed });
    }
    Ok(patch)
}

#[cfg(test)]
#[path = "face_patch_tests.rs"]
mod tests;
