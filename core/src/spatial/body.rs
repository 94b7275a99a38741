//! A rigid body with six degrees of freedom: its mass and principal moments, its state, and the
//! inertia in the world frame, the turn of a step.

use super::algebra::{Quaternion, Rotation, Vector, add, dot, finite, normalized, rotate, scale, unrotate};
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

/// `I_w^-1 = R diag(1 / I) R^T`: the inverse of a body's inertia in the world frame at one
/// orientation, symmetric, built once a step for the contacts' many products with it (each then
/// nine products, not two turns of a quaternion and three divisions). A body whose moments are
/// equal (a sphere) has `I_w^-1 = I^-1` at every orientation, kept exactly diagonal.
#[derive(Debug, Clone, Copy)]
pub(super) struct InverseInertia<T>([[T; 3]; 3]);

impl<T: Real> InverseInertia<T> {
    /// `body`'s at the orientation `q` (a unit quaternion).
    #[must_use]
    pub(super) fn new(body: &Body<T>, q: &Quaternion<T>) -> Self {
        let o = T::zero();
        let inverse = body.inertia.map(|i| T::one() / i);
        let [ia, ib, ic] = inverse;
        if ia == ib && ib == ic {
            return Self([[ia, o, o], [o, ia, o], [o, o, ia]]);
        }
        let Rotation(r) = Rotation::of(q);
        let entry = |a: usize, b: usize| {
            r[a][0] * inverse[0] * r[b][0] + r[a][1] * inverse[1] * r[b][1] + r[a][2] * inverse[2] * r[b][2]
        };
        let (xx, xy, xz, yy, yz, zz) =
            (entry(0, 0), entry(0, 1), entry(0, 2), entry(1, 1), entry(1, 2), entry(2, 2));
        Self([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    }

    /// `I_w^-1 a`.
    #[inline]
    #[must_use]
    pub(super) fn times(&self, a: &Vector<T>) -> Vector<T> {
        self.0.map(|row| dot(&row, a))
    }
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

/// A body the contacts push: its inertia, its inverse in the world frame at the step's start, and
/// its inverse mass per unit of the reference mass (`m0 / m`; 1 for the reference body itself).
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame<'a, T> {
    pub body: &'a Body<T>,
    /// Its `I_w^-1` at the step's start.
    pub inverse_inertia: InverseInertia<T>,
    pub inverse_mass: T,
}

/// Each body's velocity and angular velocity, world axes.
pub(super) type Motion<T, const B: usize> = [(Vector<T>, Vector<T>); B];

#[cfg(test)]
mod tests {
    use super::super::algebra::{about, norm, sub};
    use super::{Body, InverseInertia, inertia_times, inverse_inertia_times};

    #[test]
    fn the_world_inverse_inertia_undoes_the_inertia_at_any_orientation() {
        let body = Body::cuboid(2.0_f64, 0.3, 0.7, 1.1);
        let a = [0.4, -1.3, 2.2];
        for k in 0..12 {
            let angle = 0.55 * f64::from(k);
            let axis = [angle.cos() * 0.6, angle.sin() * 0.6, 0.8];
            let q = about(&axis, 1.7 * angle);
            let x = InverseInertia::new(&body, &q).times(&a);
            // `I_w (I_w^-1 a) = a`, and the quaternion's own product, to round-off.
            let back = inertia_times(&body, &q, &x);
            assert!(norm(&sub(&back, &a)) <= 1e-13 * norm(&a), "{k}: {back:?}");
            let turned = inverse_inertia_times(&body, &q, &a);
            assert!(norm(&sub(&turned, &x)) <= 1e-13 * norm(&x), "{k}: {turned:?} {x:?}");
        }
        // Equal moments: `a / I` exactly, whatever the orientation.
        let ball = Body::sphere(0.17_f64, 0.028);
        let x = InverseInertia::new(&ball, &about(&[0.0, 0.6, 0.8], 0.9)).times(&a);
        let exact = a.map(|c| c * (1.0 / ball.inertia[0]));
        assert_eq!(x.map(f64::to_bits), exact.map(f64::to_bits), "{x:?}");
    }
}
