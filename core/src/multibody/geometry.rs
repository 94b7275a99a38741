//! The table, the pairs of resting bodies, and the corner-on-face contact of each candidate, or a
//! disc's rim-on-face contact (`docs/formulation.md`, "Several bodies": "Bodies, table and order",
//! "The corner-on-face contact", "The rim-on-face contact").

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
pub enum RestsOn {
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
    pub lower: RestsOn,
    /// Static friction coefficient (used while a contact sticks or is separated).
    pub mu_static: T,
    /// Kinetic friction coefficient (used while a contact slides).
    pub mu_kinetic: T,
    /// The upper body's shape: a box rests by its corners (the four candidates), a disc by its
    /// rim (the first). Every pair naming a body as its upper gives it the same shape.
    pub upper_shape: Shape,
}

impl<T> Pair<T> {
    /// A box `upper` resting on `lower` by its corners, with the pair's friction coefficients.
    #[must_use]
    pub const fn boxed(upper: u8, lower: RestsOn, mu_static: T, mu_kinetic: T) -> Self {
        Self { upper, lower, mu_static, mu_kinetic, upper_shape: Shape::Box }
    }

    /// A disc `upper` resting on `lower` by its rim, with the pair's friction coefficients.
    #[must_use]
    pub const fn disc(upper: u8, lower: RestsOn, mu_static: T, mu_kinetic: T) -> Self {
        Self { upper, lower, mu_static, mu_kinetic, upper_shape: Shape::Disc }
    }
}

/// The four candidate contacts of a pair, in their order (`docs/formulation.md`, "Bodies, table
/// and order").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Candidate {
    /// The upper body's lower-left corner on the lower one's top face (a disc's rim, the one
    /// candidate of a disc's pair).
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
/// on a face of body `face` (or the table). Only an active frame's fields are the step's: the
/// geometry of an inactive candidate is computed only as far as the activity rule needs, and its
/// frame keeps every field but `active` from before.
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

impl<T: Real> CornerFrame<T> {
    /// [`Self::row`] dense in the bodies' `3B` coordinates, [`JacobianRow::dense`] of it (the
    /// same entries): each body's three entries selected by its index, zero for a body the
    /// contact does not touch.
    #[inline]
    pub(crate) fn dense_row<const B: usize>(&self, t: [T; 2]) -> [[T; 3]; B] {
        let (corner, face) = (self.corner.map(usize::from), self.face.map(usize::from));
        core::array::from_fn(|b| {
            if corner == Some(b) {
                [t[0], t[1], cross(self.lever_corner, t)]
            } else if face == Some(b) {
                [-t[0], -t[1], -cross(self.lever_face, t)]
            } else {
                [T::zero(); 3]
            }
        })
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

/// A body's pose at a step's start and its terms of a contact's round-off: centre, `R(theta)` as
/// `(cos, sin)`, half extents, `|x| + |y| + size` and `size + |y|`.
#[derive(Clone, Copy)]
pub(crate) struct PoseTerms<T> {
    com: [T; 2],
    cos: T,
    sin: T,
    half: [T; 2],
    /// `|x| + |y| + size`: the body's term of a gap's round-off.
    extent: T,
    /// `size + |y|`: the body's term of the touching threshold.
    height: T,
}

impl<T: Real> PoseTerms<T> {
    fn of(body: &Body<T>, state: &BodyState<T>) -> Self {
        let (sin, cos) = state.theta.sin_cos_portable();
        let size = body.size();
        Self {
            com: [state.x, state.y],
            cos,
            sin,
            half: body.half_extents(),
            extent: state.x.abs_exact() + state.y.abs_exact() + size,
            height: size + state.y.abs_exact(),
        }
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

    /// `P - com` for a world point `P`.
    fn lever(&self, point: [T; 2]) -> [T; 2] {
        [point[0] - self.com[0], point[1] - self.com[1]]
    }
}

/// A face: its centre `o`, tangent `e` and outward normal `n_f`.
#[derive(Clone, Copy)]
struct Face<T> {
    centre: [T; 2],
    tangent: [T; 2],
    normal: [T; 2],
}

impl<T: Real> Face<T> {
    /// A body's top face.
    fn top(p: &PoseTerms<T>) -> Self {
        Self {
            centre: p.world([T::zero(), p.half[1]]),
            tangent: p.rotate([T::one(), T::zero()]),
            normal: p.rotate([T::zero(), T::one()]),
        }
    }

    /// A body's lower face.
    fn bottom(p: &PoseTerms<T>) -> Self {
        Self {
            centre: p.world([T::zero(), -p.half[1]]),
            tangent: p.rotate([T::one(), T::zero()]),
            normal: p.rotate([T::zero(), -T::one()]),
        }
    }

    /// The table's top face.
    fn table() -> Self {
        Self { centre: [T::zero(); 2], tangent: [T::one(), T::zero()], normal: [T::zero(), T::one()] }
    }

    /// The coordinate along the face `s = l . e` and the gap `psi = l . n_f` of a corner `P`,
    /// `l = P - o`.
    fn locate(&self, point: [T; 2]) -> (T, T) {
        let l = [point[0] - self.centre[0], point[1] - self.centre[1]];
        (dot(l, self.tangent), dot(l, self.normal))
    }
}

/// The owner of a candidate's corner or face: the body's index and pose, `None` for the table.
type Owner<'a, T> = Option<(u8, &'a PoseTerms<T>)>;

/// What the four candidates of a pair share: the states (for the approach), the settings' `margin`
/// and step `h`, and the touching threshold.
struct Reach<'a, T, const B: usize> {
    states: &'a [BodyState<T>; B],
    margin: T,
    h: T,
    touch: T,
}

/// One candidate located on its face: the corner `P` and its owner, the face's owner and normal,
/// `s` and `psi` ([`Face::locate`]).
struct Located<'a, T> {
    corner: Owner<'a, T>,
    face: Owner<'a, T>,
    point: [T; 2],
    normal: [T; 2],
    along: T,
    gap: T,
}

/// Each body's pose (one sine and cosine per body, shared by the pairs it is in).
pub(crate) fn poses<T: Real, const B: usize>(
    bodies: &[Body<T>; B],
    states: &[BodyState<T>; B],
) -> [PoseTerms<T>; B] {
    let zero = [T::zero(); 2];
    let mut poses = [PoseTerms {
        com: zero,
        cos: T::one(),
        sin: T::zero(),
        half: zero,
        extent: T::zero(),
        height: T::zero(),
    }; B];
    for ((pose, body), state) in poses.iter_mut().zip(bodies).zip(states) {
        *pose = PoseTerms::of(body, state);
    }
    poses
}

/// The frames of the four candidates of `pair` (`docs/formulation.md`, "The corner-on-face
/// contact"), given the bodies' states and [`poses`], the table and the settings' `margin` and
/// step `h`, written into `frames` (in place: no copy of the four). An inactive candidate's frame
/// gets `active: false` and keeps its other fields: the tests "over the face" and "not past its
/// owner's centre line" come first, and only an active candidate's levers, approach and
/// round-off are computed.
pub(crate) fn pair_frames<T: Real, const B: usize>(
    pair: &Pair<T>,
    states: &[BodyState<T>; B],
    poses: &[PoseTerms<T>; B],
    table: &Table<T>,
    margin: T,
    h: T,
    frames: &mut [CornerFrame<T>; 4],
) {
    // A pair naming a body that does not exist (`SystemStepper::new` refuses it) has no contact.
    let Some(upper) = poses.get(usize::from(pair.upper)) else {
        *frames = [CornerFrame::inactive(); 4];
        return;
    };
    // Each support in a copy of its own (the table's missing corners and limits known there).
    match pair.lower {
        RestsOn::Body(s) => {
            let Some(p) = poses.get(usize::from(s)) else {
                *frames = [CornerFrame::inactive(); 4];
                return;
            };
            four_frames((pair.upper, upper), Some((s, p)), table, states, margin, h, frames);
        }
        RestsOn::Table => four_frames((pair.upper, upper), None, table, states, margin, h, frames),
    }
}

/// [`pair_frames`] for the upper body (index, pose) on `lower` (`None`: the table).
#[allow(clippy::inline_always)] // twice in `pair_frames`, `lower`'s variant known in each
#[inline(always)]
fn four_frames<T: Real, const B: usize>(
    (upper_index, upper): (u8, &PoseTerms<T>),
    lower: Owner<'_, T>,
    table: &Table<T>,
    states: &[BodyState<T>; B],
    margin: T,
    h: T,
    frames: &mut [CornerFrame<T>; 4],
) {
    let upper_owner = Some((upper_index, upper));
    let lower_height = lower.map_or(T::zero(), |(_, p)| p.height);
    // `64 eps (size + |y|)` summed over the two bodies (the table's term 0): the same bits for every
    // candidate, whichever body owns its corner (IEEE addition commutes).
    let touch = T::of(64.0) * T::EPS * (upper.height + lower_height);
    let reach = Reach { states, margin, h, touch };
    // The upper body's lower-left and lower-right corners on the lower one's top face: over it,
    // `|s| <= w / 2` (the table: `lo <= s <= hi`), and not past its centre line `psi >= -hgt / 2`
    // (no limit on the table).
    let top = lower.map_or_else(Face::table, |(_, p)| Face::top(p));
    for (k, x) in [-upper.half[0], upper.half[0]].into_iter().enumerate() {
        let point = upper.world([x, -upper.half[1]]);
        let (along, gap) = top.locate(point);
        let in_rule = on_top(lower, table, along, gap);
        let located = Located { corner: upper_owner, face: lower, point, normal: top.normal, along, gap };
        settle(&mut frames[k], in_rule, &located, &reach);
    }
    // The lower body's upper-left and upper-right corners (the table's ends `lo`, `hi`) on the
    // upper one's lower face: over it, `|s| < w / 2` (strict), not past its centre line.
    let bottom = Face::bottom(upper);
    for (k, left) in [(2, true), (3, false)] {
        let point = if let Some((_, p)) = lower {
            p.world([if left { -p.half[0] } else { p.half[0] }, p.half[1]])
        } else if let Some(x) = if left { table.lo } else { table.hi } {
            [x, T::zero()]
        } else {
            // No table edge on this side: no candidate.
            frames[k].active = false;
            continue;
        };
        let (along, gap) = bottom.locate(point);
        let in_rule = along.abs_exact() < upper.half[0] && gap >= -upper.half[1];
        let located = Located { corner: lower, face: upper_owner, point, normal: bottom.normal, along, gap };
        settle(&mut frames[k], in_rule, &located, &reach);
    }
}

/// The rule for a point of the upper body at `along`, `gap` on the lower's top face (`lower`:
/// its owner, `None` for the table): over the face, `|s| <= w / 2` with its ends included
/// (`lo <= s <= hi` on the table), and not past its owner's centre line, `psi >= -hgt / 2` (no
/// limit on the table).
#[allow(clippy::inline_always)] // in the four candidates' loop, `lower`'s variant known there
#[inline(always)]
fn on_top<T: Real>(lower: Owner<'_, T>, table: &Table<T>, along: T, gap: T) -> bool {
    match lower {
        Some((_, p)) => along.abs_exact() <= p.half[0] && gap >= -p.half[1],
        None => table.covers(along),
    }
}

/// Writes one candidate's frame: `active: false` when `in_rule` (over the face, not past its
/// owner's centre line) fails or the corner is out of reach, `psi > margin + h max(0, approach)`;
/// else the whole frame.
#[allow(clippy::inline_always)] // four times in `pair_frames`, its owners known there
#[inline(always)]
fn settle<T: Real, const B: usize>(
    frame: &mut CornerFrame<T>,
    in_rule: bool,
    c: &Located<'_, T>,
    reach: &Reach<'_, T, B>,
) {
    if !in_rule {
        frame.active = false;
        return;
    }
    let lever = |owner: Owner<'_, T>| owner.map_or([T::zero(); 2], |(_, p)| p.lever(c.point));
    let (lever_corner, lever_face) = (lever(c.corner), lever(c.face));
    // Within reach: `margin` plus what the approach closes within the step (`reach >= margin`:
    // the approach is needed only beyond the margin).
    let within_reach = || {
        let point_velocity = |owner: Owner<'_, T>, r: [T; 2]| {
            owner
                .and_then(|(b, _)| reach.states.get(usize::from(b)))
                .map_or([T::zero(); 2], |s| [s.vx - s.omega * r[1], s.vy + s.omega * r[0]])
        };
        let (va, vb) = (point_velocity(c.corner, lever_corner), point_velocity(c.face, lever_face));
        let approach = -dot([va[0] - vb[0], va[1] - vb[1]], c.normal);
        c.gap <= reach.margin + reach.h * if approach > T::zero() { approach } else { T::zero() }
    };
    if !(c.gap <= reach.margin || within_reach()) {
        frame.active = false;
        return;
    }
    let extent = |owner: Owner<'_, T>| owner.map_or(T::zero(), |(_, p)| p.extent);
    let n = c.normal;
    *frame = CornerFrame {
        active: true,
        corner: c.corner.map(|(b, _)| b),
        face: c.face.map(|(b, _)| b),
        gap: c.gap,
        along: c.along,
        point: c.point,
        normal: n,
        tangent: [n[1], -n[0]],
        lever_corner,
        lever_face,
        gap_round_off: T::of(4.0)
            * T::EPS
            * (c.point[0].abs_exact() + c.point[1].abs_exact() + extent(c.corner) + extent(c.face)),
        touch: reach.touch,
    };
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
/// [`pair_frames`] (the same face, rule and frame code); the other three do not exist
/// (`active: false`). Same inputs as [`pair_frames`], and as there an inactive frame keeps its
/// other fields, but the rim's `along` and `gap`, always this step's (the rim's place on the face
/// is defined wherever the disc is: a scene reads where it is, e.g. past an end).
#[inline(never)] // a scene of boxes calls it never: kept out of the step's code
pub(crate) fn rim_frames<T: Real, const B: usize>(
    pair: &Pair<T>,
    states: &[BodyState<T>; B],
    poses: &[PoseTerms<T>; B],
    table: &Table<T>,
    margin: T,
    h: T,
    frames: &mut [CornerFrame<T>; 4],
) {
    // A pair naming a body that does not exist (`SystemStepper::new` refuses it) has no contact.
    let lower = match pair.lower {
        RestsOn::Body(s) => poses.get(usize::from(s)).map(|p| Some((s, p))),
        RestsOn::Table => Some(None),
    };
    let (Some(disc), Some(lower)) = (poses.get(usize::from(pair.upper)), lower) else {
        *frames = [CornerFrame::inactive(); 4];
        return;
    };
    for frame in frames.iter_mut().skip(1) {
        frame.active = false;
    }
    let top = lower.map_or_else(Face::table, |(_, p)| Face::top(p));
    let radius = disc.half[0];
    let point = [disc.com[0] - radius * top.normal[0], disc.com[1] - radius * top.normal[1]];
    let (along, gap) = top.locate(point);
    (frames[0].along, frames[0].gap) = (along, gap);
    let in_rule = on_top(lower, table, along, gap);
    let touch = T::of(64.0) * T::EPS * (disc.height + lower.map_or(T::zero(), |(_, p)| p.height));
    let located =
        Located { corner: Some((pair.upper, disc)), face: lower, point, normal: top.normal, along, gap };
    settle(&mut frames[0], in_rule, &located, &Reach { states, margin, h, touch });
}
