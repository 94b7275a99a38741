//! The table, the pairs of resting bodies, and the corner-on-face contact of each candidate
//! (`docs/formulation.md`, "Several bodies": "Bodies, table and order", "The corner-on-face
//! contact").

use crate::planar::{Body, BodyState};
use crate::real::Real;

/// The fixed table: its top face is the world line `y = 0` over `lo <= x <= hi`; an end that is
/// `None` is infinite. Each finite end is a corner a body's lower face can rest on.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Table<T> {
    /// The left end (m), `None` for none.
    pub lo: Option<T>,
    /// The right end (m), `None` for none.
    pub hi: Option<T>,
}

impl<T: Real> Table<T> {
    /// A table without ends (a floor).
    #[must_use]
    pub const fn floor() -> Self {
        Self { lo: None, hi: None }
    }

    /// `true` when `x` is on the table's top face (ends included).
    fn covers(&self, x: T) -> bool {
        self.lo.is_none_or(|lo| lo <= x) && self.hi.is_none_or(|hi| x <= hi)
    }
}

/// What the upper body of a [`Pair`] rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Support {
    /// The body of this index.
    Body(u8),
    /// The table.
    Table,
}

/// A body's shape (`docs/formulation.md`, "Bodies, table and order"): what of it touches the body it
/// rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Shape {
    /// A box of the body's width and height: its corners on faces, faces under corners.
    Box,
    /// A disc whose diameter is the body's width (and height): its rim on the face it rests on
    /// ("The rim-on-face contact"). Only ever a pair's upper body (it has no faces).
    Disc,
}

/// A body `upper` resting on `lower`, with the pair's friction coefficients. A box's four candidate
/// contacts, in order ([`Candidate`]): `upper`'s lower-left and lower-right corners on `lower`'s top
/// face, `lower`'s upper-left and upper-right corners (the table's ends `lo`, `hi`) on `upper`'s
/// lower face.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pair<T> {
    /// The resting body's index.
    pub upper: u8,
    /// What it rests on.
    pub lower: Support,
    /// Static friction coefficient (used while a contact sticks or is separated).
    pub mu_static: T,
    /// Kinetic friction coefficient (used while a contact slides).
    pub mu_kinetic: T,
    /// The upper body's shape: a box rests by its corners (the four candidates), a disc by its
    /// rim (the first). Every pair naming a body as its upper gives it the same shape.
    pub upper_shape: Shape,
}

/// The four candidate contacts of a pair, in their order (`docs/formulation.md`, "Bodies, table
/// and order").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Candidate {
    /// The upper body's lower-left corner on the lower one's top face.
    UpperLeftOnLower,
    /// The upper body's lower-right corner on the lower one's top face.
    UpperRightOnLower,
    /// The lower body's upper-left corner (the table's `lo` end) on the upper one's lower face.
    LowerLeftUnderUpper,
    /// The lower body's upper-right corner (the table's `hi` end) on the upper one's lower face.
    LowerRightUnderUpper,
}

impl Candidate {
    /// The four, in candidate order.
    pub const ALL: [Self; 4] = [
        Self::UpperLeftOnLower,
        Self::UpperRightOnLower,
        Self::LowerLeftUnderUpper,
        Self::LowerRightUnderUpper,
    ];

    /// `true` for the upper body's corners (their impulse acts on the upper body with `+`).
    #[must_use]
    pub const fn is_upper_corner(self) -> bool {
        matches!(self, Self::UpperLeftOnLower | Self::UpperRightOnLower)
    }
}

/// One candidate contact's geometry at a step's start: a corner of body `corner` (or the table)
/// on a face of body `face` (or the table).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CornerFrame<T> {
    /// The activity rule holds: the contact enters this step's LCP.
    pub active: bool,
    /// The corner's owner, `None` for the table.
    pub corner: Option<u8>,
    /// The face's owner, `None` for the table.
    pub face: Option<u8>,
    /// The gap `psi` (m, positive when apart).
    pub gap: T,
    /// The corner's coordinate along the face from its centre, `s` (m).
    pub along: T,
    /// The corner, world (m).
    pub point: [T; 2],
    /// The normal `n` on the corner's owner (the face's outward normal).
    pub normal: [T; 2],
    /// The tangent `d = (n_y, -n_x)`.
    pub tangent: [T; 2],
    /// `P - com` of the corner's owner (zero for the table).
    pub lever_corner: [T; 2],
    /// `P - com` of the face's owner (zero for the table).
    pub lever_face: [T; 2],
    /// The gap's round-off, `4 eps (|P_x| + |P_y| + sum over the bodies (|x| + |y| + size))`.
    pub gap_round_off: T,
    /// The touching threshold of the modes before the first step,
    /// `64 eps sum over the bodies (size + |y|)`.
    pub touch: T,
}

impl<T: Real> CornerFrame<T> {
    /// An inactive frame (no geometry).
    pub(crate) fn inactive() -> Self {
        let zero = [T::zero(); 2];
        Self {
            active: false,
            corner: None,
            face: None,
            gap: T::zero(),
            along: T::zero(),
            point: zero,
            normal: zero,
            tangent: zero,
            lever_corner: zero,
            lever_face: zero,
            gap_round_off: T::zero(),
            touch: T::zero(),
        }
    }

    /// The Jacobian row of direction `t` (`n`, `+d` or `-d`): `(t_x, t_y, r_corner x t)` in the
    /// corner owner's columns, `-(t_x, t_y, r_face x t)` in the face owner's (eq. 3 for each body).
    #[must_use]
    pub fn row(&self, t: [T; 2]) -> JacobianRow<T> {
        let entries = |r: [T; 2], sign: T| [sign * t[0], sign * t[1], sign * cross(r, t)];
        JacobianRow {
            corner: self.corner.map(|b| (b, entries(self.lever_corner, T::one()))),
            face: self.face.map(|b| (b, entries(self.lever_face, -T::one()))),
        }
    }
}

/// A row of the contact Jacobian in `3B` coordinates, stored by its (at most two) bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobianRow<T> {
    /// The corner owner's index and its three entries.
    pub corner: Option<(u8, [T; 3])>,
    /// The face owner's index and its three entries.
    pub face: Option<(u8, [T; 3])>,
}

impl<T: Real> JacobianRow<T> {
    /// `J V` for the stacked velocities `v` (one `[vx, vy, omega]` per body).
    #[must_use]
    pub fn dot<const B: usize>(&self, v: &[[T; 3]; B]) -> T {
        let part = |e: Option<(u8, [T; 3])>| {
            e.and_then(|(b, c)| v.get(usize::from(b)).map(|u| c[0] * u[0] + c[1] * u[1] + c[2] * u[2]))
                .unwrap_or(T::zero())
        };
        part(self.corner) + part(self.face)
    }

    /// The row dense in `3B` coordinates (zero outside its bodies).
    #[must_use]
    pub fn dense<const B: usize>(&self) -> [[T; 3]; B] {
        let mut row = [[T::zero(); 3]; B];
        for (b, c) in [self.corner, self.face].into_iter().flatten() {
            if let Some(slot) = row.get_mut(usize::from(b)) {
                *slot = c;
            }
        }
        row
    }
}

/// `a x b = a_x b_y - a_y b_x`.
#[inline]
fn cross<T: Real>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[1] - a[1] * b[0]
}

#[inline]
fn dot<T: Real>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[0] + a[1] * b[1]
}

/// A body's pose: centre, `R(theta)` as `(cos, sin)`, half extents.
#[derive(Clone, Copy)]
pub(crate) struct Pose<T> {
    com: [T; 2],
    cos: T,
    sin: T,
    half: [T; 2],
}

impl<T: Real> Pose<T> {
    fn of(body: &Body<T>, state: &BodyState<T>) -> Self {
        let (sin, cos) = state.theta.sin_cos_portable();
        Self { com: [state.x, state.y], cos, sin, half: body.half_extents() }
    }

    /// `R v`.
    fn rotate(&self, v: [T; 2]) -> [T; 2] {
        [self.cos * v[0] - self.sin * v[1], self.sin * v[0] + self.cos * v[1]]
    }

    /// `com + R p` for a body-frame point `p`.
    fn world(&self, p: [T; 2]) -> [T; 2] {
        let r = self.rotate(p);
        [self.com[0] + r[0], self.com[1] + r[1]]
    }
}

/// A face: its owner, centre `o`, tangent `e`, outward normal, half width and half height of its
/// owner (the centre-line limit), `None` for the table's.
#[derive(Clone, Copy)]
struct Face<T> {
    owner: Option<u8>,
    centre: [T; 2],
    tangent: [T; 2],
    normal: [T; 2],
}

/// Each body's pose (one sine and cosine per body, shared by the pairs it is in).
pub(crate) fn poses<T: Real, const B: usize>(
    bodies: &[Body<T>; B],
    states: &[BodyState<T>; B],
) -> [Pose<T>; B] {
    let zero = [T::zero(); 2];
    let mut poses = [Pose { com: zero, cos: T::one(), sin: T::zero(), half: zero }; B];
    for ((pose, body), state) in poses.iter_mut().zip(bodies).zip(states) {
        *pose = Pose::of(body, state);
    }
    poses
}

/// The frames of the four candidates of `pair` (`docs/formulation.md`, "The corner-on-face
/// contact"), given the bodies, their states and [`poses`], the table and the settings' `margin`
/// and step `h`, written into `frames` (in place: no copy of the four).
#[allow(clippy::too_many_arguments, clippy::too_many_lines)] // the geometry's inputs; the four candidates in order
pub(crate) fn pair_frames<T: Real, const B: usize>(
    pair: &Pair<T>,
    bodies: &[Body<T>; B],
    states: &[BodyState<T>; B],
    poses: &[Pose<T>; B],
    table: &Table<T>,
    margin: T,
    h: T,
    frames: &mut [CornerFrame<T>; 4],
) {
    let two = T::of(2.0);
    // A pair naming a body that does not exist (`Stepper::new` refuses it) has no contact (body
    // and state looked up too: their indices below are then provably in range, no panic path).
    let pose = |b: u8| {
        let i = usize::from(b);
        bodies.get(i).and(states.get(i)).and(poses.get(i)).copied()
    };
    let lower = match pair.lower {
        Support::Body(s) => pose(s).map(|p| Some((s, p))),
        Support::Table => Some(None),
    };
    let (Some(upper), Some(lower)) = (pose(pair.upper), lower) else {
        *frames = [CornerFrame::inactive(); 4];
        return;
    };
    // The lower's top face and the upper's lower face.
    let top = lower.map_or(
        Face {
            owner: None,
            centre: [T::zero(); 2],
            tangent: [T::one(), T::zero()],
            normal: [T::zero(), T::one()],
        },
        |(s, p)| Face {
            owner: Some(s),
            centre: p.world([T::zero(), p.half[1]]),
            tangent: p.rotate([T::one(), T::zero()]),
            normal: p.rotate([T::zero(), T::one()]),
        },
    );
    let bottom = Face {
        owner: Some(pair.upper),
        centre: upper.world([T::zero(), -upper.half[1]]),
        tangent: upper.rotate([T::one(), T::zero()]),
        normal: upper.rotate([T::zero(), -T::one()]),
    };
    let com = |b: Option<u8>| b.map(|b| [states[usize::from(b)].x, states[usize::from(b)].y]);
    let velocity = |b: Option<u8>| b.map(|b| states[usize::from(b)].velocity());
    // |x| + |y| + size of a body, and size + |y|.
    let extent = |b: Option<u8>| {
        b.map_or(T::zero(), |b| {
            let s = &states[usize::from(b)];
            s.x.abs_exact() + s.y.abs_exact() + bodies[usize::from(b)].size()
        })
    };
    let height = |b: Option<u8>| {
        b.map_or(T::zero(), |b| bodies[usize::from(b)].size() + states[usize::from(b)].y.abs_exact())
    };
    // The upper and lower bodies' extents and heights (the table's 0), once per pair: a corner's
    // owner and its face's owner are these two, in an order the candidate gives.
    let lower_body = lower.map(|(s, _)| s);
    let extents = [extent(Some(pair.upper)), extent(lower_body)];
    let heights = [height(Some(pair.upper)), height(lower_body)];
    // Half the height of the upper body (the face of the lower candidates) and of the lower one
    // (the table's face has none).
    let half_heights = [
        Some(bodies[usize::from(pair.upper)].height / two),
        lower_body.map(|b| bodies[usize::from(b)].height / two),
    ];
    for (k, candidate) in Candidate::ALL.into_iter().enumerate() {
        // The corner (owner, world point), the face, and the rule "over the face".
        let (corner_owner, point, face) = match candidate {
            Candidate::UpperLeftOnLower => {
                (Some(pair.upper), upper.world([-upper.half[0], -upper.half[1]]), top)
            }
            Candidate::UpperRightOnLower => {
                (Some(pair.upper), upper.world([upper.half[0], -upper.half[1]]), top)
            }
            Candidate::LowerLeftUnderUpper | Candidate::LowerRightUnderUpper => {
                let left = candidate == Candidate::LowerLeftUnderUpper;
                if let Some((s, p)) = lower {
                    let x = if left { -p.half[0] } else { p.half[0] };
                    (Some(s), p.world([x, p.half[1]]), bottom)
                } else if let Some(x) = if left { table.lo } else { table.hi } {
                    (None, [x, T::zero()], bottom)
                } else {
                    // No table edge on this side: no candidate.
                    frames[k] = CornerFrame::inactive();
                    continue;
                }
            }
        };
        let l = [point[0] - face.centre[0], point[1] - face.centre[1]];
        let along = dot(l, face.tangent);
        let gap = dot(l, face.normal);
        let over = match (candidate.is_upper_corner(), lower) {
            (true, Some((_, p))) => along.abs_exact() <= p.half[0],
            (true, None) => table.covers(along),
            (false, _) => along.abs_exact() < upper.half[0],
        };
        // Not past the face owner's centre line (no limit on the table).
        let face_half_height = half_heights[usize::from(candidate.is_upper_corner())];
        let above_centre = face_half_height.is_none_or(|half| gap >= -half);
        let lever = |b: Option<u8>| com(b).map_or([T::zero(); 2], |c| [point[0] - c[0], point[1] - c[1]]);
        let (lever_corner, lever_face) = (lever(corner_owner), lever(face.owner));
        // Within reach: `margin` plus what the approach closes within the step (`reach >= margin`:
        // the approach is needed only for a candidate over the face beyond the margin).
        let within_reach = || {
            let point_velocity = |b: Option<u8>, r: [T; 2]| {
                velocity(b).map_or([T::zero(); 2], |v| [v[0] - v[2] * r[1], v[1] + v[2] * r[0]])
            };
            let (va, vb) =
                (point_velocity(corner_owner, lever_corner), point_velocity(face.owner, lever_face));
            let approach = -dot([va[0] - vb[0], va[1] - vb[1]], face.normal);
            let reach = margin + h * if approach > T::zero() { approach } else { T::zero() };
            gap <= reach
        };
        let n = face.normal;
        // Indices into `extents`, `heights`: the corner's owner's, the face's owner's.
        let owners = if candidate.is_upper_corner() { [0, 1] } else { [1, 0] };
        frames[k] = CornerFrame {
            active: over && above_centre && (gap <= margin || within_reach()),
            corner: corner_owner,
            face: face.owner,
            gap,
            along,
            point,
            normal: n,
            tangent: [n[1], -n[0]],
            lever_corner,
            lever_face,
            gap_round_off: T::of(4.0)
                * T::EPS
                * (point[0].abs_exact() + point[1].abs_exact() + extents[owners[0]] + extents[owners[1]]),
            touch: T::of(64.0) * T::EPS * (heights[owners[0]] + heights[owners[1]]),
        };
    }
}

/// The velocity of the corner's owner relative to the face's owner at the frame's point,
/// `v_rel` (the table's terms are zero).
pub(crate) fn relative_velocity<T: Real, const B: usize>(frame: &CornerFrame<T>, v: &[[T; 3]; B]) -> [T; 2] {
    let at = |b: Option<u8>, r: [T; 2]| {
        b.and_then(|b| v.get(usize::from(b)))
            .map_or([T::zero(); 2], |u| [u[0] - u[2] * r[1], u[1] + u[2] * r[0]])
    };
    let (a, f) = (at(frame.corner, frame.lever_corner), at(frame.face, frame.lever_face));
    [a[0] - f[0], a[1] - f[1]]
}

/// The slip of a contact: `-d . v_rel` (the face's owner moving along `+d` relative to the corner
/// is positive).
pub(crate) fn slip<T: Real, const B: usize>(frame: &CornerFrame<T>, v: &[[T; 3]; B]) -> T {
    -dot(frame.tangent, relative_velocity(frame, v))
}

/// The frames of a pair whose upper body is a disc (`docs/formulation.md`, "The rim-on-face
/// contact"): the first candidate is the rim's point nearest the lower body's top face (or the
/// table), `P = c_U - r n_f`, a corner of the disc on that face under every rule of
/// [`pair_frames`]; the other three do not exist (inactive). Same inputs as [`pair_frames`].
#[allow(clippy::too_many_arguments)] // as pair_frames
#[inline(never)] // a scene of boxes calls it never: kept out of the step's code
pub(crate) fn rim_frames<T: Real, const B: usize>(
    pair: &Pair<T>,
    bodies: &[Body<T>; B],
    states: &[BodyState<T>; B],
    poses: &[Pose<T>; B],
    table: &Table<T>,
    margin: T,
    h: T,
    frames: &mut [CornerFrame<T>; 4],
) {
    *frames = [CornerFrame::inactive(); 4];
    let look = |b: u8| {
        let i = usize::from(b);
        match (bodies.get(i), states.get(i), poses.get(i)) {
            (Some(body), Some(state), Some(pose)) => Some((body, state, pose)),
            _ => None,
        }
    };
    let lower = match pair.lower {
        Support::Body(s) => look(s).map(|l| Some((s, l))),
        Support::Table => Some(None),
    };
    let (Some((disc, disc_state, _)), Some(lower)) = (look(pair.upper), lower) else {
        return;
    };
    let radius = disc.width / T::of(2.0);
    // The lower body's top face: centre `o`, tangent `e`, outward normal `n_f`; the table's at `y = 0`.
    let (centre, tangent, n) = match lower {
        Some((_, (_, _, p))) => (
            p.world([T::zero(), p.half[1]]),
            p.rotate([T::one(), T::zero()]),
            p.rotate([T::zero(), T::one()]),
        ),
        None => ([T::zero(); 2], [T::one(), T::zero()], [T::zero(), T::one()]),
    };
    let com = [disc_state.x, disc_state.y];
    let point = [com[0] - radius * n[0], com[1] - radius * n[1]];
    let l = [point[0] - centre[0], point[1] - centre[1]];
    let along = dot(l, tangent);
    let gap = dot(l, n);
    let (over, above_centre) = match lower {
        Some((_, (body, _, p))) => (along.abs_exact() <= p.half[0], gap >= -(body.height / T::of(2.0))),
        None => (table.covers(along), true),
    };
    let lever_corner = [point[0] - com[0], point[1] - com[1]];
    let lever_face = lower.map_or([T::zero(); 2], |(_, (_, st, _))| [point[0] - st.x, point[1] - st.y]);
    let face = lower.map(|(s, _)| s);
    // Within reach: `margin` plus what the approach closes within the step.
    let at = |v: [T; 3], r: [T; 2]| [v[0] - v[2] * r[1], v[1] + v[2] * r[0]];
    let va = at(disc_state.velocity(), lever_corner);
    let vb = lower.map_or([T::zero(); 2], |(_, (_, st, _))| at(st.velocity(), lever_face));
    let approach = -dot([va[0] - vb[0], va[1] - vb[1]], n);
    let reach = margin + h * if approach > T::zero() { approach } else { T::zero() };
    // `|x| + |y| + size` and `size + |y|` of the disc and of the lower body (the table's 0).
    let extent = |b: &Body<T>, st: &BodyState<T>| st.x.abs_exact() + st.y.abs_exact() + b.size();
    let height = |b: &Body<T>, st: &BodyState<T>| b.size() + st.y.abs_exact();
    let (lower_extent, lower_height) =
        lower.map_or((T::zero(), T::zero()), |(_, (b, st, _))| (extent(b, st), height(b, st)));
    frames[0] = CornerFrame {
        active: over && above_centre && gap <= reach,
        corner: Some(pair.upper),
        face,
        gap,
        along,
        point,
        normal: n,
        tangent: [n[1], -n[0]],
        lever_corner,
        lever_face,
        gap_round_off: T::of(4.0)
            * T::EPS
            * (point[0].abs_exact() + point[1].abs_exact() + extent(disc, disc_state) + lower_extent),
        touch: T::of(64.0) * T::EPS * (height(disc, disc_state) + lower_height),
    };
}
