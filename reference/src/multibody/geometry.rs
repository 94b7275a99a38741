//! Multibody contact geometry (docs/formulation.md, "Several bodies"): boxes and discs, the
//! fixed table, and the corner-on-face and rim-on-face contacts between them.
//!
//! Body `i` is a box of half-width `a_i`, half-height `b_i` at `q_i = (x, y, theta)`. Its
//! corners (body frame) are lower-left `(-a, -b)`, lower-right `(a, -b)`, upper-left `(-a, b)`,
//! upper-right `(a, b)`; its top face is `y_b = b` with outward normal `R (0, 1)` and its lower
//! face `y_b = -b` with outward normal `R (0, -1)`, both spanning `|x_b| <= a`. The table is
//! fixed: its top face is the world line `y = 0` over `lo <= x <= hi` (either end may be
//! infinite), outward normal `(0, 1)`; each finite end is a corner.
//!
//! A **pair** `(upper U, lower S)` (S a body or the table) has four candidate contacts, in this
//! order: U's lower-left and lower-right corners on S's top face, then S's upper-left and
//! upper-right corners (for the table: its ends `lo`, `hi`, where finite) on U's lower face. For
//! corner `P` (world) on a face through `o` (the face's centre point; for the table `(0, 0)`)
//! with unit tangent `e` (the owner's body `+x`) and outward normal `n_f`: the coordinate along
//! the face is `s = (P - o) . e` and the gap `psi = (P - o) . n_f`. The contact is **active**
//! when the corner is over the face (`|s| <= a` for U's corners on S's face, `|s| < a` strictly
//! for S's corners on U's face, so that two coinciding corners make one contact; the table's
//! `lo <= s <= hi`), not past the face owner's centre line (`psi >= -b` of the owner; no limit
//! for the table), and within reach: `psi <= margin + h max(0, -n_f . v_rel)` with `v_rel` the
//! corner's velocity relative to the face owner's material point at `P` at the step's start.
//!
//! The contact's normal on the corner's owner `A` is `n = n_f`, its tangent `d = (n_y, -n_x)`
//! (`n` turned clockwise: `+x` on a level top face, `-x` on a level lower face), its levers
//! `r_A = P - com_A` and `r_B = P - com_B` (B the face's owner). A unit impulse along `t` on `A`
//! (and `-t` on `B`) has the row `J_t` of `3B` entries: `(t_x, t_y, r_A x t)` in `A`'s block,
//! `-(t_x, t_y, r_B x t)` in `B`'s, zero elsewhere (the table has no block), and `J_t . V` is
//! `t . v_rel`.
//!
//! A **disc** `U` (centre `c_U`, radius `r`) has no corners and no faces: its pair has one
//! candidate, the first, its rim's point nearest S's top face `P = c_U - r n_f`, a corner of `U`
//! on that face with every rule above (docs/formulation.md, "The rim-on-face contact"; its lever
//! `r_U = P - c_U = -r n_f`). A disc is never a pair's lower body (the scenes' validation refuses
//! it): such a pair has no candidates.

/// `R(theta) v`.
pub(super) fn rotate(theta: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// `a x b` in the plane.
pub(super) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// `a . b`.
pub(super) fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// A body's shape (docs/formulation.md, "Bodies, table and order").
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Shape {
    /// A box of half-width `a` (body `x`) and half-height `b` (body `y`), m.
    Box {
        /// `a`, m.
        half_width: f64,
        /// `b`, m.
        half_height: f64,
    },
    /// A disc (a solid cylinder seen end-on) of radius `r`, m: no faces, no corners; only ever a
    /// pair's upper body, touching the lower one with its rim.
    Disc {
        /// `r`, m.
        radius: f64,
    },
}

/// One rigid body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Body {
    /// Its shape.
    pub shape: Shape,
    /// Mass, kg.
    pub mass: f64,
    /// Inertia about the centre of mass, kg m^2: a box's `m (w^2 + h^2) / 12`, a disc's
    /// `m r^2 / 2`.
    pub inertia: f64,
}

impl Body {
    /// A box of width `w`, height `h`, mass `m` (uniform: `J = m (w^2 + h^2) / 12`).
    pub fn block(width: f64, height: f64, mass: f64) -> Self {
        Self {
            shape: Shape::Box { half_width: width / 2.0, half_height: height / 2.0 },
            mass,
            inertia: mass * (width * width + height * height) / 12.0,
        }
    }

    /// A disc of radius `r`, mass `m` (uniform: `J = m r^2 / 2`).
    pub fn disc(radius: f64, mass: f64) -> Self {
        Self { shape: Shape::Disc { radius }, mass, inertia: mass * radius * radius / 2.0 }
    }

    /// Its size: a box's largest extent `max(w, h)`, a disc's diameter `2 r`, m.
    pub fn size(&self) -> f64 {
        match self.shape {
            Shape::Box { half_width, half_height } => 2.0 * half_width.max(half_height),
            Shape::Disc { radius } => 2.0 * radius,
        }
    }

    /// The fastest point's distance from the centre of mass: a box's half diagonal, a disc's
    /// radius, m.
    pub fn reach(&self) -> f64 {
        match self.shape {
            Shape::Box { half_width, half_height } => half_width.hypot(half_height),
            Shape::Disc { radius } => radius,
        }
    }
}

/// The fixed table's top face `y = 0`, `lo <= x <= hi`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Table {
    /// Left end, m (may be `-inf`).
    pub lo: f64,
    /// Right end, m (may be `+inf`).
    pub hi: f64,
}

/// What lies under an upper body in a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Lower {
    /// The table.
    Table,
    /// Body `j`.
    Body(usize),
}

/// A pair `(upper, lower)` and its friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Pair {
    /// The upper body.
    pub upper: usize,
    /// What it rests on.
    pub lower: Lower,
    /// `mu_s`.
    pub mu_static: f64,
    /// `mu_k`.
    pub mu_kinetic: f64,
}

/// One candidate contact's geometry at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Frame {
    /// Whether it enters the step's LCP.
    pub active: bool,
    /// The pair it belongs to (index into the scene's pairs).
    pub pair: usize,
    /// The corner's owner `A` (`None`: the table).
    pub corner_body: Option<usize>,
    /// The face's owner `B` (`None`: the table).
    pub face_body: Option<usize>,
    /// Gap `psi`, m.
    pub gap: f64,
    /// Coordinate of the corner along the face, m.
    pub along: f64,
    /// The corner `P`, world.
    pub point: [f64; 2],
    /// `n` (on `A`).
    pub normal: [f64; 2],
    /// `d = (n_y, -n_x)`.
    pub tangent: [f64; 2],
    /// `P - com_A` (zero for the table).
    pub lever_corner: [f64; 2],
    /// `P - com_B` (zero for the table).
    pub lever_face: [f64; 2],
}

/// Velocity of body `i`'s material point at lever `r` (`None`: the table, at rest).
pub(super) fn point_velocity(v: &[[f64; 3]], body: Option<usize>, r: [f64; 2]) -> [f64; 2] {
    match body {
        None => [0.0; 2],
        Some(i) => [v[i][0] - v[i][2] * r[1], v[i][1] + v[i][2] * r[0]],
    }
}

impl Frame {
    /// The corner's velocity relative to the face owner's material point at it, `v_rel`.
    pub fn relative_velocity(&self, v: &[[f64; 3]]) -> [f64; 2] {
        let a = point_velocity(v, self.corner_body, self.lever_corner);
        let b = point_velocity(v, self.face_body, self.lever_face);
        [a[0] - b[0], a[1] - b[1]]
    }

    /// The row `J_t` (3 entries per body) of a unit impulse along `t` on the corner's owner.
    pub fn row(&self, t: [f64; 2], bodies: usize) -> Vec<f64> {
        let mut row = vec![0.0; 3 * bodies];
        if let Some(i) = self.corner_body {
            row[3 * i] += t[0];
            row[3 * i + 1] += t[1];
            row[3 * i + 2] += cross(self.lever_corner, t);
        }
        if let Some(j) = self.face_body {
            row[3 * j] -= t[0];
            row[3 * j + 1] -= t[1];
            row[3 * j + 2] -= cross(self.lever_face, t);
        }
        row
    }
}

/// A face: centre point, tangent `e`, outward normal, the extent along `e` and the depth below
/// it that still counts (the owner's half-height; infinite for the table).
struct Face {
    origin: [f64; 2],
    tangent: [f64; 2],
    normal: [f64; 2],
    lo: f64,
    hi: f64,
    strict: bool,
    depth: f64,
}

/// The world position of body corner `corner` (body frame).
fn corner_world(q: [f64; 3], corner: [f64; 2]) -> [f64; 2] {
    let r = rotate(q[2], corner);
    [q[0] + r[0], q[1] + r[1]]
}

/// The candidate contacts of every pair at state `(q, v)`, in the order of the module's
/// documentation: pair by pair, four per pair (fewer against a table with infinite ends; one,
/// the rim, for a disc on a face).
/// `margin` and `step` set the reach of the activity rule.
pub(super) fn frames(
    bodies: &[Body],
    table: &Table,
    pairs: &[Pair],
    q: &[[f64; 3]],
    v: &[[f64; 3]],
    margin: f64,
    step: f64,
) -> Vec<Frame> {
    let mut out = Vec::new();
    for (p, pair) in pairs.iter().enumerate() {
        let u = pair.upper;
        // The lower's top face and upper corners.
        let (top_face, lower_corners, lower_body): (Face, Vec<[f64; 2]>, Option<usize>) = match pair.lower {
            Lower::Table => (
                Face {
                    origin: [0.0, 0.0],
                    tangent: [1.0, 0.0],
                    normal: [0.0, 1.0],
                    lo: table.lo,
                    hi: table.hi,
                    strict: false,
                    depth: f64::INFINITY,
                },
                [table.lo, table.hi].into_iter().filter(|x| x.is_finite()).map(|x| [x, 0.0]).collect(),
                None,
            ),
            Lower::Body(j) => {
                // A disc has no top face: nothing rests on it.
                let Shape::Box { half_width, half_height } = bodies[j].shape else { continue };
                let c = rotate(q[j][2], [0.0, half_height]);
                (
                    Face {
                        origin: [q[j][0] + c[0], q[j][1] + c[1]],
                        tangent: rotate(q[j][2], [1.0, 0.0]),
                        normal: rotate(q[j][2], [0.0, 1.0]),
                        lo: -half_width,
                        hi: half_width,
                        strict: false,
                        depth: half_height,
                    },
                    vec![
                        corner_world(q[j], [-half_width, half_height]),
                        corner_world(q[j], [half_width, half_height]),
                    ],
                    Some(j),
                )
            }
        };
        let (half_width, half_height) = match bodies[u].shape {
            Shape::Box { half_width, half_height } => (half_width, half_height),
            Shape::Disc { radius } => {
                // The rim's point nearest the face, P = c_U - r n_f (docs/formulation.md, "The
                // rim-on-face contact"): candidate 1; candidates 2-4 do not exist.
                let n = top_face.normal;
                let rim = [q[u][0] - radius * n[0], q[u][1] - radius * n[1]];
                out.push(frame(p, rim, Some(u), &top_face, lower_body, q, v, margin, step));
                continue;
            }
        };
        let c = rotate(q[u][2], [0.0, -half_height]);
        let lower_face = Face {
            origin: [q[u][0] + c[0], q[u][1] + c[1]],
            tangent: rotate(q[u][2], [1.0, 0.0]),
            normal: rotate(q[u][2], [0.0, -1.0]),
            lo: -half_width,
            hi: half_width,
            strict: true,
            depth: half_height,
        };
        let upper_corners =
            [corner_world(q[u], [-half_width, -half_height]), corner_world(q[u], [half_width, -half_height])];
        for corner in upper_corners {
            out.push(frame(p, corner, Some(u), &top_face, lower_body, q, v, margin, step));
        }
        for corner in lower_corners {
            out.push(frame(p, corner, lower_body, &lower_face, Some(u), q, v, margin, step));
        }
    }
    out
}

/// One corner-on-face contact (a disc's rim point is its corner).
#[allow(clippy::too_many_arguments)]
fn frame(
    pair: usize,
    point: [f64; 2],
    corner_body: Option<usize>,
    face: &Face,
    face_body: Option<usize>,
    q: &[[f64; 3]],
    v: &[[f64; 3]],
    margin: f64,
    step: f64,
) -> Frame {
    let lever = |body: Option<usize>| match body {
        None => [0.0; 2],
        Some(i) => [point[0] - q[i][0], point[1] - q[i][1]],
    };
    let l = [point[0] - face.origin[0], point[1] - face.origin[1]];
    let along = dot(l, face.tangent);
    let gap = dot(l, face.normal);
    let n = face.normal;
    let mut f = Frame {
        active: false,
        pair,
        corner_body,
        face_body,
        gap,
        along,
        point,
        normal: n,
        tangent: [n[1], -n[0]],
        lever_corner: lever(corner_body),
        lever_face: lever(face_body),
    };
    let over =
        if face.strict { face.lo < along && along < face.hi } else { face.lo <= along && along <= face.hi };
    let approach = -dot(n, f.relative_velocity(v));
    f.active = over && gap >= -face.depth && gap <= margin + step * approach.max(0.0);
    f
}
