//! Contacts between the body and its supports: what touches what ([`Feature`], [`Support`],
//! [`Contact`]), the geometry of one contact at one instant ([`ContactFrame`]), and its mode
//! ([`ContactMode`]). The two contact kinds and their formulas are those of `docs/formulation.md`,
//! "Contacts".

use super::layout::Direction;
use crate::real::{Real, zero_if_finite};

/// The part of the body a contact acts on.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Feature<T> {
    /// The body's lower face, `y = -height/2` for `|x| <= width/2` in the body frame, touched from
    /// below by a [`Support::Point`] (a finger tip under a rod).
    LowerFace,
    /// A point fixed in the body (body frame, from the centre of mass) on a [`Support::Line`]: a
    /// corner of a block, an end of a ladder.
    Point([T; 2]),
    /// A round body of this radius (m) about its centre of mass on a [`Support::Line`]: a
    /// cylinder, a wheel. It touches the line at `com - radius n`, whatever its angle.
    Round(T),
}

/// A support whose motion the scene prescribes: where it is at the end of a step and how fast it
/// moved over the step (world frame, m and m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Support<T> {
    /// A point, e.g. a finger tip.
    Point {
        /// Its position.
        position: [T; 2],
        /// Its velocity.
        velocity: [T; 2],
    },
    /// A line (a floor, a wall, an incline): through `position`, with unit `normal` pointing to the
    /// side the body is on.
    Line {
        /// A point of the line.
        position: [T; 2],
        /// Its unit normal, toward the body.
        normal: [T; 2],
        /// Its velocity.
        velocity: [T; 2],
    },
}

impl<T: Real> Support<T> {
    /// A point at `position` moving at `velocity`.
    #[must_use]
    pub const fn point(position: [T; 2], velocity: [T; 2]) -> Self {
        Self::Point { position, velocity }
    }

    /// A line through `position` with unit normal `normal`, at rest.
    #[must_use]
    pub fn fixed_line(position: [T; 2], normal: [T; 2]) -> Self {
        Self::Line { position, normal, velocity: [T::zero(); 2] }
    }

    /// `true` when the support can carry a contact: its position is finite and, for a line, its
    /// normal is a unit vector (`|n . n - 1| <= 64 eps`). (A NaN position left its contact
    /// silently inactive; a zero normal let the body fall through the line.)
    #[must_use]
    #[inline]
    pub fn is_well_formed(&self) -> bool {
        match *self {
            Self::Point { position, .. } => both_finite(position),
            Self::Line { position, normal, .. } => {
                let unit = (normal[0] * normal[0] + normal[1] * normal[1] - T::one()).abs_exact()
                    <= T::of(64.0) * T::EPS;
                both_finite(position) & unit
            }
        }
    }

    /// Its velocity.
    #[must_use]
    pub const fn velocity(&self) -> [T; 2] {
        match *self {
            Self::Point { velocity, .. } | Self::Line { velocity, .. } => velocity,
        }
    }

    /// Its position (the point, or the line's point).
    #[must_use]
    pub const fn position(&self) -> [T; 2] {
        match *self {
            Self::Point { position, .. } | Self::Line { position, .. } => position,
        }
    }

    /// `true` when it can support `feature` (a point under a face, a line under a point).
    #[must_use]
    pub const fn fits(&self, feature: &Feature<T>) -> bool {
        matches!(
            (feature, self),
            (Feature::LowerFace, Self::Point { .. })
                | (Feature::Point(_) | Feature::Round(_), Self::Line { .. })
        )
    }
}

/// One contact of the body: its feature and its friction coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Contact<T> {
    /// What part of the body touches the support.
    pub feature: Feature<T>,
    /// Static friction coefficient: used in a step when the contact was sticking or separated
    /// after the previous one.
    pub mu_static: T,
    /// Kinetic friction coefficient: used in a step when the contact was sliding.
    pub mu_kinetic: T,
}

/// The body's pose as the contact geometry needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose<T> {
    /// Centre of mass.
    pub com: [T; 2],
    /// `(sin theta, cos theta)`.
    pub sin_cos: (T, T),
}

/// The geometry of one contact at one instant (`docs/formulation.md`, "Contacts").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFrame<T> {
    /// The contact's coordinate along its tangent: for a point under the lower face, the point's
    /// signed distance from the centre of mass along the body (`l.x`); for a point on a line,
    /// `(P - o) . d`.
    pub along: T,
    /// Gap `psi` (positive when apart, negative when penetrating).
    pub gap: T,
    /// `true` when the contact can act: a point under the face (`|l.x| <= width/2`, not above
    /// the centre line); always for a point on a line.
    pub active: bool,
    /// Normal wrench column `W_n = [n; r x n]`; `n` is its first two entries.
    pub wn: [T; 3],
    /// Tangential wrench column `W_d = [d; r x d]`; `d` is its first two entries.
    pub wt: [T; 3],
    /// Contact point relative to the centre of mass (world).
    pub r: [T; 2],
}

impl<T: Real> ContactFrame<T> {
    /// The frame of `feature` against `support` for a body in `pose` whose box has half extents
    /// `half` (`width/2`, `height/2`); `None` when the support does not fit the feature
    /// ([`Support::fits`]).
    ///
    /// Inlined into the stepper's frame update (every step, every contact): with a third arm the
    /// compiler kept it out of line, 15 % of the host's step (`web/examples/bench.rs` under perf).
    #[must_use]
    #[inline(always)]
    #[allow(clippy::inline_always)] // measured, as said above
    pub fn new(feature: &Feature<T>, support: &Support<T>, pose: &Pose<T>, half: [T; 2]) -> Option<Self> {
        match (feature, support) {
            (Feature::LowerFace, Support::Point { position, .. }) => {
                Some(Self::under_lower_face(*position, pose, half))
            }
            (Feature::Point(p), Support::Line { position, normal, .. }) => {
                Some(Self::point_on_line(*p, *position, *normal, pose))
            }
            (Feature::Round(radius), Support::Line { position, normal, .. }) => {
                Some(Self::round_on_line(*radius, *position, *normal, pose))
            }
            _ => None,
        }
    }

    /// A support point `f` under the body's lower face: `l = R^T (f - com)`, active when
    /// `|l.x| <= width/2` and `l.y <= 0`, gap `-l.y - height/2`, contact point `R (l.x, -height/2)`,
    /// `n = R (0, 1)`, `d = R (1, 0)`.
    #[must_use]
    pub fn under_lower_face(f: [T; 2], pose: &Pose<T>, half: [T; 2]) -> Self {
        let (s, c) = pose.sin_cos;
        let (dx, dy) = (f[0] - pose.com[0], f[1] - pose.com[1]);
        let lx = c * dx + s * dy;
        let ly = c * dy - s * dx;
        let r = [c * lx + s * half[1], s * lx - c * half[1]];
        let (n, d) = ([-s, c], [c, s]);
        // The torque arms in the body frame, where the contact point is `(lx, -hgt/2)`, the normal
        // `(0, 1)` and the tangent `(1, 0)`: a cross product does not change under rotation, so
        // `r x n = lx` and `r x d = hgt/2` exactly, with no rounding from `r`.
        Self {
            along: lx,
            gap: -ly - half[1],
            active: lx.abs_exact() <= half[0] && ly <= T::zero(),
            wn: [n[0], n[1], lx],
            wt: [d[0], d[1], half[1]],
            r,
        }
    }

    /// A body point `p` (body frame) on the line through `o` with unit normal `n`: `r = R p`,
    /// `P = com + r`, gap `(P - o) . n`, `d = (n_y, -n_x)`, along `(P - o) . d`; always active.
    #[must_use]
    pub fn point_on_line(p: [T; 2], o: [T; 2], n: [T; 2], pose: &Pose<T>) -> Self {
        let (s, c) = pose.sin_cos;
        let r = [c * p[0] - s * p[1], s * p[0] + c * p[1]];
        let rel = [pose.com[0] + r[0] - o[0], pose.com[1] + r[1] - o[1]];
        let d = [n[1], -n[0]];
        Self {
            along: rel[0] * d[0] + rel[1] * d[1],
            gap: rel[0] * n[0] + rel[1] * n[1],
            active: true,
            wn: [n[0], n[1], cross(r, n)],
            wt: [d[0], d[1], cross(r, d)],
            r,
        }
    }

    /// A round body of `radius` about its centre of mass on the line through `o` with unit normal
    /// `n`: contact point `r = -radius n`, gap `(com - o) . n - radius`, `d = (n_y, -n_x)`, along
    /// `(com - o) . d`; always active. `r x n = 0` and `r x d = radius` exactly.
    /// Out of line: the fingers' and corners' frames are on every step's path, and this arm must
    /// not change how they are inlined.
    #[must_use]
    #[inline(never)]
    pub fn round_on_line(radius: T, o: [T; 2], n: [T; 2], pose: &Pose<T>) -> Self {
        let rel = [pose.com[0] - o[0], pose.com[1] - o[1]];
        let d = [n[1], -n[0]];
        Self {
            along: rel[0] * d[0] + rel[1] * d[1],
            gap: rel[0] * n[0] + rel[1] * n[1] - radius,
            active: true,
            wn: [n[0], n[1], T::zero()],
            wt: [d[0], d[1], radius],
            r: [-radius * n[0], -radius * n[1]],
        }
    }

    /// The unit normal `n` (world): the direction of the normal impulse on the body.
    #[must_use]
    pub const fn normal(&self) -> [T; 2] {
        [self.wn[0], self.wn[1]]
    }

    /// The unit tangent `d` (world).
    #[must_use]
    pub const fn tangent(&self) -> [T; 2] {
        [self.wt[0], self.wt[1]]
    }

    /// Velocity of the body's material point at the contact: `v + omega x r`.
    #[must_use]
    pub fn point_velocity(&self, v: [T; 3]) -> [T; 2] {
        [v[0] - v[2] * self.r[1], v[1] + v[2] * self.r[0]]
    }

    /// Tangential slip of the support relative to the body, `d . (u - v_P)`: positive when the
    /// support moves along `+d` relative to the body.
    #[must_use]
    pub fn slip(&self, v: [T; 3], support_velocity: [T; 2]) -> T {
        let p = self.point_velocity(v);
        self.wt[0] * (support_velocity[0] - p[0]) + self.wt[1] * (support_velocity[1] - p[1])
    }
}

/// `true` when both entries are finite: `(a - a) + (b - b)` is exactly `+0` for finite entries
/// and NaN otherwise.
#[inline]
fn both_finite<T: Real>([a, b]: [T; 2]) -> bool {
    zero_if_finite(a) + zero_if_finite(b) == T::zero()
}

/// `r x a = r_x a_y - r_y a_x`.
#[inline]
fn cross<T: Real>(r: [T; 2], a: [T; 2]) -> T {
    r[0] * a[1] - r[1] * a[0]
}

/// The mode of one contact, decided after each step (`docs/formulation.md`, "Friction and contact
/// modes").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ContactMode {
    /// No normal impulse: the support does not touch the body (or the contact is inactive).
    Separated,
    /// Normal impulse and a tangential slip speed of at most the stick threshold.
    Sticking,
    /// Normal impulse and the support slides along the body, in this direction of `d` relative to
    /// it (friction on the body then points the same way).
    Sliding(Direction),
}

impl ContactMode {
    /// A short stable name: `separated`, `sticking`, `sliding+`, `sliding-`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Separated => "separated",
            Self::Sticking => "sticking",
            Self::Sliding(Direction::Plus) => "sliding+",
            Self::Sliding(Direction::Minus) => "sliding-",
        }
    }

    /// The mode of a contact that carries a normal impulse, from its slip ([`ContactFrame::slip`]):
    /// sticking when `|slip| <= stick_speed`, sliding in the slip's direction otherwise.
    #[must_use]
    pub fn from_slip<T: Real>(slip: T, stick_speed: T) -> Self {
        if slip.abs_exact() <= stick_speed {
            Self::Sticking
        } else if slip > T::zero() {
            Self::Sliding(Direction::Plus)
        } else {
            Self::Sliding(Direction::Minus)
        }
    }

    /// `true` for either sliding direction.
    #[must_use]
    pub const fn is_sliding(self) -> bool {
        matches!(self, Self::Sliding(_))
    }

    /// `true` when the contact touches (sticking or sliding).
    #[must_use]
    pub const fn is_touching(self) -> bool {
        !matches!(self, Self::Separated)
    }
}
