//! [`Body`]: the one rigid body a [`super::Stepper`] moves, and its [`BodyState`].

use crate::params::ParamError;
use crate::real::{AllFinite, Real};

/// A planar rigid body shaped as a box centred on its centre of mass (a rod is a long thin box).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Body<T> {
    /// Extent along the body's `x` (m): a rod's length.
    pub width: T,
    /// Extent along the body's `y` (m): a rod's thickness.
    pub height: T,
    /// Mass `m` (kg).
    pub mass: T,
    /// Moment of inertia about the centre of mass `J` (kg m^2).
    pub inertia: T,
}

impl<T: Real> Body<T> {
    /// A thin rod of length `length`: `J = m L^2 / 12` (the paper's; the thickness adds no inertia).
    #[must_use]
    pub fn rod(mass: T, length: T, thickness: T) -> Self {
        Self { width: length, height: thickness, mass, inertia: mass * length * length / T::of(12.0) }
    }

    /// A solid disc (a cylinder seen end-on) of radius `radius`: width and height its diameter,
    /// `J = m r^2 / 2`. In a multibody system the pair it rests in says it is one
    /// (`crate::multibody::Pair::upper_shape`); a body is otherwise a box of its width and height.
    #[must_use]
    pub fn disc(mass: T, radius: T) -> Self {
        let diameter = radius + radius;
        Self { width: diameter, height: diameter, mass, inertia: mass * radius * radius / T::of(2.0) }
    }

    /// A solid box: `J = m (w^2 + h^2) / 12`.
    #[must_use]
    pub fn block(mass: T, width: T, height: T) -> Self {
        Self { width, height, mass, inertia: mass * (width * width + height * height) / T::of(12.0) }
    }

    /// A rod's own rules, its fields named `[mass, length, thickness]`: thinner than it is long (a
    /// 1e7 m thick meter stick ended in a ray), and its inertia in `T`'s range
    /// ([`Self::check_inertia`]).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the thickness, or [`ParamError::InertiaOutOfRange`].
    #[inline]
    pub fn check_rod(
        mass: T,
        length: T,
        thickness: T,
        [m, l, t]: [&'static str; 3],
    ) -> Result<(), ParamError> {
        if thickness >= length {
            return Err(ParamError::OutOfRange(t));
        }
        Self::rod(mass, length, thickness).check_inertia(m, l)
    }

    /// Checks that the inertia `J` and `m / J` are positive finite numbers in `T`: a mass or size
    /// can be finite while their product underflows to 0 or overflows (in f32, a mass of 1e-45
    /// kg, a rod of 1e20 m). `mass` and `size` name the fields they came from.
    ///
    /// # Errors
    /// [`ParamError::InertiaOutOfRange`].
    pub fn check_inertia(&self, mass: &'static str, size: &'static str) -> Result<(), ParamError> {
        let ratio = self.mass / self.inertia;
        if self.inertia.finite() && self.inertia > T::zero() && ratio.finite() {
            Ok(())
        } else {
            Err(ParamError::InertiaOutOfRange { mass, size })
        }
    }

    /// `diag(M^-1)` times the mass: `(1, 1, m / J)`. The LCP is solved for impulses per unit mass,
    /// so every row is a velocity (`docs/formulation.md`, "Per unit mass").
    #[must_use]
    pub fn inverse_mass_per_unit_mass(&self) -> [T; 3] {
        [T::one(), T::one(), self.mass / self.inertia]
    }

    /// Half the extents, `(width/2, height/2)`.
    #[must_use]
    pub fn half_extents(&self) -> [T; 2] {
        [self.width / T::of(2.0), self.height / T::of(2.0)]
    }

    /// The body's size, `max(width, height)`: the length scale of its round-off.
    #[must_use]
    pub fn size(&self) -> T {
        if self.width > self.height { self.width } else { self.height }
    }

    /// The corners `(-w/2, -h/2)`, `(w/2, -h/2)`, `(w/2, h/2)`, `(-w/2, h/2)` (body frame; lower
    /// left first, counter-clockwise).
    #[must_use]
    pub fn corners(&self) -> [[T; 2]; 4] {
        let [a, b] = self.half_extents();
        [[-a, -b], [a, -b], [a, b], [-a, b]]
    }
}

/// Position and velocity of the body's centre of mass and its angle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BodyState<T> {
    /// `x` of the centre of mass (m).
    pub x: T,
    /// `y` of the centre of mass (m).
    pub y: T,
    /// Angle `theta` (rad, counter-clockwise).
    pub theta: T,
    /// `dx/dt` (m/s).
    pub vx: T,
    /// `dy/dt` (m/s).
    pub vy: T,
    /// `d theta / dt` (rad/s).
    pub omega: T,
}

impl<T: Real> BodyState<T> {
    /// At rest at `(x, y)`, angle `theta`.
    #[must_use]
    pub fn at_rest(x: T, y: T, theta: T) -> Self {
        Self { x, y, theta, vx: T::zero(), vy: T::zero(), omega: T::zero() }
    }

    /// `true` when every component is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        let mut finite = AllFinite::new();
        for v in [self.x, self.y, self.theta, self.vx, self.vy, self.omega] {
            finite.add(v);
        }
        finite.holds()
    }

    /// The velocity `(vx, vy, omega)`.
    #[must_use]
    pub const fn velocity(&self) -> [T; 3] {
        [self.vx, self.vy, self.omega]
    }

    /// The six components in the order of the fields (for checksums and logs).
    #[must_use]
    pub const fn to_array(&self) -> [T; 6] {
        [self.x, self.y, self.theta, self.vx, self.vy, self.omega]
    }
}
