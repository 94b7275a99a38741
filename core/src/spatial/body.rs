//! A rigid body with six degrees of freedom: its mass and principal moments, its state, and the
//! inertia in the world frame, the turn of a step.

use super::algebra::{Quaternion, Vector, add, dot, finite, normalized, rotate, scale, unrotate};
use crate::ParamError;
use crate::real::Real;

/// A body's inertia: mass (kg) and principal moments (kg m^2) about its centre of mass, along the
/// axes of its own frame.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Body<T> {
    /// Mass, kg (finite, positive).
    pub mass: T,
    /// Principal moments of inertia about the body's axes `x`, `y`, `z`, kg m^2 (finite,
    /// positive, each at most the sum of the other two: the triangle inequality every real body
    /// satisfies).
    pub inertia: [T; 3],
}

impl<T: Real> Body<T> {
    /// A uniform solid sphere of `mass` and `radius`: `I = 2/5 m R^2` about every axis.
    #[must_use]
    pub fn sphere(mass: T, radius: T) -> Self {
        let i = T::of(0.4) * mass * radius * radius;
        Self { mass, inertia: [i, i, i] }
    }

    /// A uniform box of `mass` and full sides `a`, `b`, `c` along its `x`, `y`, `z`.
    #[must_use]
    pub fn cuboid(mass: T, a: T, b: T, c: T) -> Self {
        let k = mass / T::of(12.0);
        Self { mass, inertia: [k * (b * b + c * c), k * (a * a + c * c), k * (a * a + b * b)] }
    }

    /// Refuses a mass or a moment that is not finite and positive, or moments no body has.
    ///
    /// # Errors
    /// [`ParamError::NonFinite`] or [`ParamError::NotPositive`] naming `mass` or `inertia`;
    /// [`ParamError::OutOfRange`] for moments that break the triangle inequality beyond round-off.
    pub fn validate(&self) -> Result<(), ParamError> {
        if !self.mass.finite() {
            return Err(ParamError::NonFinite("mass"));
        }
        if self.mass <= T::zero() {
            return Err(ParamError::NotPositive("mass"));
        }
        if !self.inertia.iter().all(|i| i.finite()) {
            return Err(ParamError::NonFinite("inertia"));
        }
        if !self.inertia.iter().all(|i| *i > T::zero()) {
            return Err(ParamError::NotPositive("inertia"));
        }
        let [a, b, c] = self.inertia;
        let slack = T::of(1.0 + 1e-6);
        if a > (b + c) * slack || b > (a + c) * slack || c > (a + b) * slack {
            return Err(ParamError::OutOfRange("inertia"));
        }
        Ok(())
    }
}

/// Where a body is and how it moves: world frame, `z` up.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct State<T> {
    /// Centre of mass, m.
    pub position: Vector<T>,
    /// The rotation from the body's frame to the world's (a unit quaternion `[w, x, y, z]`).
    pub orientation: Quaternion<T>,
    /// Velocity of the centre of mass, m/s.
    pub velocity: Vector<T>,
    /// Angular velocity, rad/s, world axes.
    pub angular_velocity: Vector<T>,
}

impl<T: Real> State<T> {
    /// `true` when every number is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        finite(&self.position)
            && self.orientation.iter().all(|x| x.finite())
            && finite(&self.velocity)
            && finite(&self.angular_velocity)
    }

    /// Kinetic energy `m |v|^2 / 2 + omega . I omega / 2`, J.
    #[must_use]
    pub fn kinetic_energy(&self, body: &Body<T>) -> T {
        let w = unrotate(&self.orientation, &self.angular_velocity);
        let spin =
            body.inertia[0] * w[0] * w[0] + body.inertia[1] * w[1] * w[1] + body.inertia[2] * w[2] * w[2];
        T::of(0.5) * (body.mass * dot(&self.velocity, &self.velocity) + spin)
    }

    /// Angular momentum about the centre of mass, world axes, kg m^2/s.
    #[must_use]
    pub fn angular_momentum(&self, body: &Body<T>) -> Vector<T> {
        let w = unrotate(&self.orientation, &self.angular_velocity);
        let l = [body.inertia[0] * w[0], body.inertia[1] * w[1], body.inertia[2] * w[2]];
        rotate(&self.orientation, &l)
    }
}

/// `I_w^-1 a`: the inverse of the body's inertia in the world frame (orientation `q`) applied to
/// `a`: `R diag(1 / I) R^T a`.
#[must_use]
pub(super) fn inverse_inertia_times<T: Real>(body: &Body<T>, q: &Quaternion<T>, a: &Vector<T>) -> Vector<T> {
    let b = unrotate(q, a);
    rotate(q, &[b[0] / body.inertia[0], b[1] / body.inertia[1], b[2] / body.inertia[2]])
}

/// `I_w a`: the body's inertia in the world frame (orientation `q`) applied to `a`.
#[must_use]
pub(super) fn inertia_times<T: Real>(body: &Body<T>, q: &Quaternion<T>, a: &Vector<T>) -> Vector<T> {
    let b = unrotate(q, a);
    rotate(q, &[b[0] * body.inertia[0], b[1] * body.inertia[1], b[2] * body.inertia[2]])
}

/// The orientation after a step of `h` at the constant angular velocity `omega`: `exp(h omega / 2)
/// q`, the exact rotation, renormalised.
#[must_use]
pub(super) fn turned<T: Real>(q: &Quaternion<T>, omega: &Vector<T>, h: T) -> Quaternion<T> {
    let speed = dot(omega, omega).sqrt_rounded();
    if speed <= T::zero() || !speed.finite() {
        return *q;
    }
    let turn = super::algebra::about(&scale(T::one() / speed, omega), speed * h);
    normalized(&super::algebra::mul(&turn, q))
}

/// `a + b` for the integration's sums (kept here so the stepper reads as the equations do).
#[inline]
#[must_use]
pub(super) fn advanced<T: Real>(a: &Vector<T>, h: T, rate: &Vector<T>) -> Vector<T> {
    add(a, &scale(h, rate))
}

/// A body the contacts push: its inertia, its orientation at the step's start, and its inverse
/// mass per unit of the reference mass (`m0 / m`; 1 for the reference body itself).
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame<'a, T> {
    pub body: &'a Body<T>,
    pub orientation: &'a Quaternion<T>,
    pub inverse_mass: T,
}

/// Each body's velocity and angular velocity, world axes.
pub(super) type Motion<T, const B: usize> = [(Vector<T>, Vector<T>); B];
