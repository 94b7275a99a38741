//! One step of a rigid body touching a fixed plane at one point (docs/formulation.md, "Three
//! dimensions"; the equations of the core's spatial module documentation), written with matrices:
//! `R` of the orientation, `I_w^-1 = R diag(1 / I) R^T`, `W = I3 + m [r]x^T I_w^-1 [r]x`.

use super::Mode;
use super::algebra::{
    M3, Quat, V3, apply, congruent, cross, dot, identity3, in_plane, length, matrix_of, minus, plus, product,
    skew, times, transpose, turn,
};
use super::contact::{self, Case, ContactError, Point};

/// The gap within which the contact enters the step, m (docs/scenes.md, "Scenes in three
/// dimensions").
pub(crate) const MARGIN: f64 = 1e-3;

/// A rigid body: mass and principal moments about its own axes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rigid {
    pub mass: f64,
    pub moments: V3,
}

/// The body's point that touches the plane.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Toucher {
    /// A sphere about the centre of mass: its point nearest the plane, `-radius n`.
    Sphere { radius: f64 },
    /// A point fixed in the body at this offset (body axes) from the centre of mass.
    Point { offset: V3 },
}

/// A fixed plane with its friction.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ground {
    pub point: V3,
    pub normal: V3,
    pub mu_s: f64,
    pub mu_k: f64,
}

/// What every step shares.
#[derive(Debug, Clone, Copy)]
pub(crate) struct World {
    pub body: Rigid,
    pub toucher: Toucher,
    pub ground: Ground,
    /// Gravity, world axes.
    pub gravity: V3,
    pub h: f64,
    pub stick_speed: f64,
}

/// The body's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Kinematics {
    pub x: V3,
    pub q: Quat,
    pub v: V3,
    pub omega: V3,
}

/// A step's result.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stepped {
    pub state: Kinematics,
    pub mode: Mode,
    /// N s.
    pub normal_impulse: f64,
    /// N s, world axes.
    pub friction_impulse: V3,
}

/// The normal row's bias from the gap `psi` (docs/formulation.md, "Penetration recovery" and
/// "Round-off is not a gap"): the gap is first shrunk toward zero by its round-off `fuzz`; a gap
/// closes in one step (`psi' / h`), a penetration opens at most at the speed of a fall through it
/// (`max(psi' / h, -sqrt(2 g |psi'|))`).
pub(crate) fn bias(psi: f64, h: f64, g: f64, fuzz: f64) -> f64 {
    let shrunk = psi.abs() - fuzz;
    if shrunk <= 0.0 {
        0.0
    } else if psi > 0.0 {
        shrunk / h
    } else {
        (-shrunk / h).max(-(2.0 * g * shrunk).sqrt())
    }
}

impl World {
    /// `I_w^-1` at orientation `q`.
    fn inverse_inertia(&self, q: Quat) -> M3 {
        congruent(&matrix_of(q), self.body.moments.map(|i| 1.0 / i))
    }

    /// The contact point's offset from the centre of mass, world axes.
    fn arm(&self, q: Quat) -> V3 {
        match self.toucher {
            Toucher::Sphere { radius } => times(-radius, self.ground.normal),
            Toucher::Point { offset } => apply(&matrix_of(q), offset),
        }
    }

    /// One step from `s`, whose contact's mode after the previous step was `before` (separated
    /// before the first).
    ///
    /// # Errors
    /// The contact's solve failing.
    pub(crate) fn step(&self, s: &Kinematics, before: Mode) -> Result<Stepped, ContactError> {
        let (h, n, m) = (self.h, self.ground.normal, self.body.mass);
        let g = length(self.gravity);
        let v_free = plus(s.v, times(h, self.gravity));
        let r = self.arm(s.q);
        let psi = dot(n, minus(plus(s.x, r), self.ground.point));
        // The gap's round-off: 4 eps (|x| + |y| + |z| + |r|) (the core's spatial stepper; the
        // planar docs' `size` is the arm's length here).
        let fuzz = 4.0 * f64::EPSILON * (s.x.iter().map(|c| c.abs()).sum::<f64>() + length(r));
        let inv = self.inverse_inertia(s.q);
        let mut p = [0.0; 3];
        let mut case = Case::Apart;
        if psi <= MARGIN {
            let mu = if before == Mode::Sliding { self.ground.mu_k } else { self.ground.mu_s };
            let rx = skew(r);
            // W = I3 + m [r]x^T I_w^-1 [r]x.
            let coupling = product(&transpose(&rx), &product(&inv, &rx));
            let mut w = identity3();
            for i in 0..3 {
                for j in 0..3 {
                    w[i][j] += m * coupling[i][j];
                }
            }
            let u = plus(v_free, cross(s.omega, r));
            let u = plus(u, times(bias(psi, h, g, fuzz), n));
            let answer = contact::solve(&Point { n, w, u, mu })?;
            p = answer.p;
            case = answer.case;
        }
        let v = plus(v_free, p);
        let omega = plus(s.omega, times(m, apply(&inv, cross(r, p))));
        let pn = dot(p, n);
        let slip = in_plane(plus(v, cross(omega, r)), n);
        let mode = if case == Case::Apart || pn <= 64.0 * f64::EPSILON * g * h {
            Mode::Separated
        } else if length(slip) <= self.stick_speed {
            Mode::Sticking
        } else {
            Mode::Sliding
        };
        let (q, omega) = self.turned(s.q, omega);
        let state = Kinematics { x: plus(s.x, times(h, v)), q, v, omega };
        Ok(Stepped { state, mode, normal_impulse: m * pn, friction_impulse: times(m, in_plane(p, n)) })
    }

    /// The orientation after the step and the angular velocity then, from `omega+`
    /// (docs/formulation.md, "The gyroscopic term"). Equal moments (a sphere): `I_w = I` at every
    /// orientation, so the turn is by `omega+` and `omega` stays. Otherwise the momentum `L =
    /// I_w(q) omega+` is held: the midpoint `q_half = exp(h omega+ / 4) q` (a rotation by `h
    /// omega+ / 2`), `q+ = exp(h I_w(q_half)^-1 L / 2) q` (by `h I_w(q_half)^-1 L`), `omega =
    /// I_w(q+)^-1 L`.
    fn turned(&self, q: Quat, omega: V3) -> (Quat, V3) {
        turned(self.body.moments, self.h, q, omega)
    }
}

/// [`World::turned`] for a body of principal moments `moments` over a step `h`.
pub(crate) fn turned(moments: V3, h: f64, q: Quat, omega: V3) -> (Quat, V3) {
    let [a, b, c] = moments;
    #[allow(clippy::float_cmp)]
    if a == b && b == c {
        return (turn(q, times(h, omega)), omega);
    }
    let inverse = |q: Quat| congruent(&matrix_of(q), moments.map(|i| 1.0 / i));
    let momentum = apply(&congruent(&matrix_of(q), moments), omega);
    let half = turn(q, times(0.5 * h, omega));
    let q_next = turn(q, times(h, apply(&inverse(half), momentum)));
    (q_next, apply(&inverse(q_next), momentum))
}
