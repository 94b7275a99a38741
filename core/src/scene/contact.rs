//! Contact geometry of a finger tip under the tilted rod, and contact modes.

use crate::real::Real;

/// Which way a sliding finger moves along the rod, relative to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Slide {
    /// The finger moves toward the rod's `+x` end (rod frame), e.g. finger 1 dragged under
    /// the rod toward the centre.
    TowardPositiveEnd,
    /// The finger moves toward the rod's `-x` end.
    TowardNegativeEnd,
}

/// The mode of one finger's contact, decided after each step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ContactMode {
    /// No normal impulse: the finger does not touch the rod (or is outside it).
    Separated,
    /// Normal impulse and tangential slip speed at most `stick_speed`.
    Sticking,
    /// Normal impulse and the finger slides along the rod.
    Sliding(Slide),
}

impl ContactMode {
    /// A short stable name: `separated`, `sticking`, `sliding+`, `sliding-`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Separated => "separated",
            Self::Sticking => "sticking",
            Self::Sliding(Slide::TowardPositiveEnd) => "sliding+",
            Self::Sliding(Slide::TowardNegativeEnd) => "sliding-",
        }
    }

    /// The mode of a contact that carries a normal impulse, from the finger's tangential slip
    /// relative to the rod ([`ContactFrame::slip`]): sticking when `|slip| <= stick_speed`,
    /// sliding in the slip's direction otherwise.
    #[must_use]
    pub fn from_slip<T: Real>(slip: T, stick_speed: T) -> Self {
        if slip.abs_exact() <= stick_speed {
            Self::Sticking
        } else if slip > T::zero() {
            Self::Sliding(Slide::TowardPositiveEnd)
        } else {
            Self::Sliding(Slide::TowardNegativeEnd)
        }
    }

    /// `true` for either sliding direction.
    #[must_use]
    pub const fn is_sliding(self) -> bool {
        matches!(self, Self::Sliding(_))
    }
}

/// The geometry of one finger tip against the rod at the start of a step
/// (formulation.md, "State and contacts").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFrame<T> {
    /// Finger tip in the rod frame: `l = R(theta)^T (f - com)`; `l.x` is the finger's
    /// signed distance from the centre of mass along the rod.
    pub along: T,
    /// Gap `psi_n = -l.y - t/2` (positive when apart, negative when penetrating).
    pub gap: T,
    /// `true` when the tip is under the rod: `|l.x| <= L/2` and not above its centre line.
    pub active: bool,
    /// Normal wrench column `W_n = [n; r x n]`, `n = R (0, 1)`.
    pub wn: [T; 3],
    /// Tangential wrench column `W_t = [d; r x d]`, `d = R (1, 0)`.
    pub wt: [T; 3],
    /// Unit normal `n` (world).
    pub normal: [T; 2],
    /// Unit tangent `d` (world).
    pub tangent: [T; 2],
    /// Contact point relative to the centre of mass, `r = R (l.x, -t/2)` (world).
    pub r: [T; 2],
}

impl<T: Real> ContactFrame<T> {
    /// The frame of the finger tip at world `(fx, fy)` under a rod with centre of mass
    /// `(x, y)`, angle `theta` given as `(sin, cos)`, length `len`, thickness `thick`.
    #[must_use]
    pub fn new(fx: T, fy: T, x: T, y: T, (s, c): (T, T), len: T, thick: T) -> Self {
        let half_t = thick / T::of(2.0);
        let (dx, dy) = (fx - x, fy - y);
        let lx = c * dx + s * dy;
        let ly = c * dy - s * dx;
        let gap = -ly - half_t;
        let active = lx.abs_exact() <= len / T::of(2.0) && ly <= T::zero();
        let r = [c * lx + s * half_t, s * lx - c * half_t];
        let normal = [-s, c];
        let tangent = [c, s];
        let cross = |a: [T; 2]| r[0] * a[1] - r[1] * a[0];
        Self {
            along: lx,
            gap,
            active,
            wn: [normal[0], normal[1], cross(normal)],
            wt: [tangent[0], tangent[1], cross(tangent)],
            normal,
            tangent,
            r,
        }
    }

    /// Velocity of the rod's material point at the contact: `v + omega x r`.
    #[must_use]
    pub fn point_velocity(&self, v: [T; 3]) -> [T; 2] {
        [v[0] - v[2] * self.r[1], v[1] + v[2] * self.r[0]]
    }

    /// Tangential slip of the finger relative to the rod, `d . (u_f - v_point)`:
    /// positive when the finger moves toward the rod's `+x` end.
    #[must_use]
    pub fn slip(&self, v: [T; 3], finger_velocity: [T; 2]) -> T {
        let p = self.point_velocity(v);
        self.tangent[0] * (finger_velocity[0] - p[0]) + self.tangent[1] * (finger_velocity[1] - p[1])
    }
}
