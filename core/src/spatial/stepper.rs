//! One body with six degrees of freedom on a plane, touching it at up to `K` points: the step of
//! `super`'s module docs (the contacts' impulses: `super::friction`).

use super::algebra::{Vector, add, cross, dot, norm, rotate, scale, sub};
use super::body::{
    Body, Frame, InverseInertia, Motion, State, advanced, inertia_times, inverse_inertia_times, turned,
};
use super::friction::{Contacts, Touch};
use super::load::{LOAD_TRIES, PATIENT_TRIES};
use super::report::{Mode, SpatialContactReport, SpatialStepReport};
use crate::ParamError;
use crate::StepError;
use crate::lcp::{Basis, Lemke};
use crate::planar::assemble::normal_bias;
use crate::real::{Real, max};

/// A plane the body rests on or slides over: a table, an incline. Fixed in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Plane<T> {
    /// A point of the plane, m.
    pub point: Vector<T>,
    /// Its unit normal, pointing out of the solid (toward the body).
    pub normal: Vector<T>,
    /// Static friction coefficient (`>= mu_kinetic`).
    pub mu_static: T,
    /// Kinetic friction coefficient (`>= 0`).
    pub mu_kinetic: T,
}

impl<T: Real> Plane<T> {
    /// A level table at height `z` with one coefficient of friction.
    #[must_use]
    pub fn table(z: T, mu: T) -> Self {
        Self {
            point: [T::zero(), T::zero(), z],
            normal: [T::zero(), T::zero(), T::one()],
            mu_static: mu,
            mu_kinetic: mu,
        }
    }

    /// A plane through the origin inclined by `angle` (rad) about the world's `x` axis, normal `(0,
    /// sin, cos)`: it falls toward `+y` (down the slope `(0, cos, -sin)`); `x` runs horizontally
    /// across it.
    #[must_use]
    pub fn incline(angle: T, mu: T) -> Self {
        let (s, c) = angle.sin_cos_portable();
        Self { point: [T::zero(); 3], normal: [T::zero(), s, c], mu_static: mu, mu_kinetic: mu }
    }
}

/// Which point of the body touches the plane.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SpatialShape<T> {
    /// A sphere of this radius about the centre of mass: it touches at `-radius` along the
    /// plane's normal, wherever it has turned.
    Sphere {
        /// m.
        radius: T,
    },
    /// A point fixed in the body, at this offset from the centre of mass in the body's frame (a
    /// puck sliding on its face, taken at its centre: offset zero).
    Point {
        /// m, body axes.
        offset: Vector<T>,
    },
    /// A slot the body leaves empty (a base of fewer points than the stepper's `K`): it never
    /// touches, enters no LCP and has no lever.
    Unused,
}

/// How a contact's friction cone is taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrictionCone {
    /// Coulomb's circular cone: one friction line per contact, turned to its slip (module docs,
    /// 3). The default.
    #[default]
    Circular,
    /// The baseline of LCP engines (Stewart & Trinkle): a pyramid of this many friction directions
    /// fixed in the plane (the first along the plane's `perpendicular` of its normal, the others
    /// evenly turned about it), one LCP a step, no turn. A sliding body's friction then points at
    /// the pyramid's nearest edge, not against its slip: its path bends toward those directions.
    /// From 3 to 16; the LCP needs `N >= K (directions + 2)`.
    Pyramid {
        /// The directions (3 to 16).
        directions: u8,
    },
}

/// The step's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpatialSettings<T> {
    /// Time step `h`, s. Default `1e-3`.
    pub step: T,
    /// Gravity, m/s^2, world axes. Default `(0, 0, -9.81)`.
    pub gravity: Vector<T>,
    /// Slip speed below which a loaded contact reads sticking, m/s. Default `1e-5`.
    pub stick_speed: T,
    /// Gap within which the contact enters the step's LCP, m. Default `1e-3`.
    pub margin: T,
    /// The friction cone. Default [`FrictionCone::Circular`].
    pub friction: FrictionCone,
}

impl<T: Real> Default for SpatialSettings<T> {
    fn default() -> Self {
        Self {
            step: T::of(1e-3),
            gravity: [T::zero(), T::zero(), T::of(-9.81)],
            stick_speed: T::of(1e-5),
            margin: T::of(1e-3),
            friction: FrictionCone::Circular,
        }
    }
}

impl<T: Real> SpatialSettings<T> {
    /// Refuses a step, stick speed or margin that is not finite and positive.
    ///
    /// # Errors
    /// [`ParamError::NonFinite`] or [`ParamError::NotPositive`] naming `step`, `stick_speed` or
    /// `margin`.
    pub(super) fn check_steps(&self) -> Result<(), ParamError> {
        for (value, name) in [(self.step, "step"), (self.stick_speed, "stick_speed"), (self.margin, "margin")]
        {
            if !value.finite() {
                return Err(ParamError::NonFinite(name));
            }
            if value <= T::zero() {
                return Err(ParamError::NotPositive(name));
            }
        }
        Ok(())
    }
}

/// Refuses friction coefficients that are not finite, negative, or kinetic above static.
///
/// # Errors
/// [`ParamError::NonFinite`] or [`ParamError::Negative`] naming `mu_static` or `mu_kinetic`;
/// [`ParamError::KineticAboveStatic`].
pub(super) fn check_friction<T: Real>(mu_static: T, mu_kinetic: T) -> Result<(), ParamError> {
    for (value, name) in [(mu_static, "mu_static"), (mu_kinetic, "mu_kinetic")] {
        if !value.finite() {
            return Err(ParamError::NonFinite(name));
        }
        if value < T::zero() {
            return Err(ParamError::Negative(name));
        }
    }
    if mu_kinetic > mu_static {
        return Err(ParamError::KineticAboveStatic);
    }
    Ok(())
}

/// A body on a plane touching it at up to `K` points (`N = 4 K`, the LCP's size: one friction
/// line per contact), stepped as `super`'s module docs say.
#[derive(Debug, Clone)]
pub struct SpatialStepper<T: Real, const K: usize, const N: usize> {
    body: Body<T>,
    shapes: [SpatialShape<T>; K],
    plane: Plane<T>,
    settings: SpatialSettings<T>,
    state: State<T>,
    modes: [Mode; K],
    steps: u64,
    solve: Solve<T, N>,
}

/// A body touching the plane at one point (a sphere, a puck).
pub type OneContact<T> = SpatialStepper<T, 1, 4>;

impl<T: Real, const K: usize, const N: usize> SpatialStepper<T, K, N> {
    /// A stepper for `body` touching `plane` at the points `shapes` name, starting at `state`.
    ///
    /// `K` from 1 to 8 and `N` from `4 K` to 32 (checked at compile time); a pyramid of `k`
    /// directions needs `N >= K (k + 2)`.
    ///
    /// # Errors
    /// [`ParamError`] naming what is refused: the body ([`Body::validate`]), a radius that is not
    /// finite and positive (`radius`), an offset that is not finite (`offset`), a plane whose
    /// normal is not a unit vector (`normal`) or whose point is not finite (`point`), `mu_kinetic
    /// < 0` (`mu_kinetic`) or `mu_kinetic > mu_static`, a step, stick speed or margin that is not
    /// finite and positive, non-finite gravity (`gravity`), a state that is not finite, a pyramid
    /// of fewer than 3 or more than 16 directions or more than `N` holds (`friction_directions`).
    pub fn new(
        body: Body<T>,
        shapes: [SpatialShape<T>; K],
        plane: Plane<T>,
        settings: SpatialSettings<T>,
        state: State<T>,
    ) -> Result<Self, ParamError> {
        const {
            assert!(
                K >= 1 && K <= 8 && N >= 4 * K && N <= 32,
                "SpatialStepper<T, K, N> needs 1 <= K <= 8, 4 K <= N <= 32"
            );
        };
        body.validate()?;
        for shape in shapes {
            match shape {
                SpatialShape::Sphere { radius } if !radius.finite() => {
                    return Err(ParamError::NonFinite("radius"));
                }
                SpatialShape::Sphere { radius } if radius <= T::zero() => {
                    return Err(ParamError::NotPositive("radius"));
                }
                SpatialShape::Point { offset } if !super::algebra::finite(&offset) => {
                    return Err(ParamError::NonFinite("offset"));
                }
                _ => {}
            }
        }
        if !super::algebra::finite(&plane.point) {
            return Err(ParamError::NonFinite("point"));
        }
        let n = norm(&plane.normal);
        if !n.finite() || (n - T::one()).abs_exact() > T::of(64.0) * T::EPS {
            return Err(ParamError::OutOfRange("normal"));
        }
        check_friction(plane.mu_static, plane.mu_kinetic)?;
        settings.check_steps()?;
        if matches!(settings.friction, FrictionCone::Pyramid { directions }
            if !(3..=16).contains(&directions) || K * (usize::from(directions) + 2) > N)
        {
            return Err(ParamError::OutOfRange("friction_directions"));
        }
        if !super::algebra::finite(&settings.gravity) {
            return Err(ParamError::NonFinite("gravity"));
        }
        if !state.is_finite() {
            return Err(ParamError::NonFiniteState);
        }
        let state = State { orientation: super::algebra::normalized(&state.orientation), ..state };
        Ok(Self {
            body,
            shapes,
            plane,
            settings,
            state,
            modes: [Mode::Separated; K],
            steps: 0,
            solve: Solve::new(),
        })
    }

    /// The body's state now.
    #[must_use]
    pub const fn state(&self) -> &State<T> {
        &self.state
    }

    /// The body.
    #[must_use]
    pub const fn body(&self) -> &Body<T> {
        &self.body
    }

    /// Each contact's mode after the last step.
    #[must_use]
    pub const fn modes(&self) -> &[Mode; K] {
        &self.modes
    }

    /// The plane.
    #[must_use]
    pub const fn plane(&self) -> &Plane<T> {
        &self.plane
    }

    /// The step's settings.
    #[must_use]
    pub const fn settings(&self) -> &SpatialSettings<T> {
        &self.settings
    }

    /// Contact `i`'s point from the centre of mass now, world axes (m); `None` past `K` and for
    /// a slot left [`SpatialShape::Unused`].
    #[must_use]
    pub fn lever(&self, i: usize) -> Option<Vector<T>> {
        self.shapes
            .get(i)
            .filter(|shape| !matches!(shape, SpatialShape::Unused))
            .map(|shape| self.arm(shape, &self.state))
    }

    /// The contacts the body has: the slots not left [`SpatialShape::Unused`].
    #[must_use]
    pub fn used(&self) -> usize {
        self.shapes.iter().filter(|s| !matches!(s, SpatialShape::Unused)).count()
    }

    /// Contact `i`'s gap now: its point's height over the plane along the plane's normal (m,
    /// negative when it has sunk in); `None` past `K`.
    #[must_use]
    pub fn gap(&self, i: usize) -> Option<T> {
        let r = self.lever(i)?;
        Some(dot(&self.plane.normal, &sub(&add(&self.state.position, &r), &self.plane.point)))
    }

    /// Simulated time, s.
    #[must_use]
    pub fn time(&self) -> T {
        T::of_count(u32::try_from(self.steps).unwrap_or(u32::MAX)) * self.settings.step
    }

    /// A contact point's offset from the centre of mass, world axes, at `state`.
    fn arm(&self, shape: &SpatialShape<T>, state: &State<T>) -> Vector<T> {
        match *shape {
            SpatialShape::Sphere { radius } => scale(-radius, &self.plane.normal),
            SpatialShape::Point { offset } => rotate(&state.orientation, &offset),
            SpatialShape::Unused => [T::zero(); 3],
        }
    }

    /// Advances one step of `h`.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged.
    pub fn step(&mut self) -> Result<SpatialStepReport<T, K>, StepError> {
        let s = self.settings;
        let (h, st, n) = (s.step, self.state, self.plane.normal);
        let v_free = advanced(&st.velocity, h, &s.gravity);
        let w_free = st.angular_velocity;
        let position_size = st.position.iter().fold(T::zero(), |a, x| a + x.abs_exact());
        let (mut speed, mut terms) = (T::zero(), T::zero());
        let (v_size, w_size) = (norm(&v_free), norm(&w_free));
        let touches = core::array::from_fn(|i| {
            let r = self.arm(&self.shapes[i], &st);
            let gap = dot(&n, &sub(&add(&st.position, &r), &self.plane.point));
            let round_off = T::of(4.0) * T::EPS * (position_size + norm(&r));
            let u_free = add(&v_free, &cross(&w_free, &r));
            speed = max(speed, norm(&u_free));
            // The slip is summed from `v~` and `omega~ x r`: its round-off is of their sizes, not
            // of its own (a ball near rolling slips slowly on a fast surface).
            terms = max(terms, v_size + w_size * norm(&r));
            let mu =
                if self.modes[i] == Mode::Sliding { self.plane.mu_kinetic } else { self.plane.mu_static };
            Touch {
                active: gap <= s.margin && !matches!(self.shapes[i], SpatialShape::Unused),
                arm: r,
                normal_free: dot(&n, &u_free) + normal_bias(gap, h, norm(&s.gravity), round_off),
                slip_free: sub(&u_free, &scale(dot(&n, &u_free), &n)),
                carried: [T::zero(); 3],
                rest_line: None,
                mu,
                normal: n,
                body: 0,
                beneath: None,
            }
        });
        let (state, contacts, pivots) =
            self.solve.advance(&self.body, &s, &st, n, &touches, (speed, terms), &v_free, &w_free)?;
        self.state = state;
        self.modes = contacts.map(|c| c.mode);
        self.steps += 1;
        Ok(SpatialStepReport { time: self.time(), state, contacts, pivots })
    }
}

/// A step's end: the state, each contact's report, the pivots taken.
pub(super) type Advanced<T, const K: usize> = (State<T>, [SpatialContactReport<T>; K], u32);

/// The solver a stepper keeps between steps: Lemke's method and its warm bases (`W` words of rows:
/// 1 for up to 32, 2 for up to 64, `crate::lcp::Basis`).
#[derive(Debug, Clone)]
pub(super) struct Solve<T: Real, const N: usize, const W: usize = 1> {
    solver: Lemke<T, N, W>,
    basis: Basis<N, W>,
    /// The warm basis of the flat base's least-norm load (`super::load`).
    load_basis: Basis<N, W>,
}

impl<T: Real, const N: usize, const W: usize> Solve<T, N, W> {
    pub(super) fn new() -> Self {
        Self { solver: Lemke::new(), basis: Basis::all_w(), load_basis: Basis::all_w() }
    }

    /// A solver whose answers are verified to `tolerance` ([`Lemke::with_tolerance`]).
    pub(super) fn with_tolerance(tolerance: T) -> Self {
        Self { solver: Lemke::new().with_tolerance(tolerance), ..Self::new() }
    }

    /// The impulses of `contacts` on the bodies' free motion `free` ([`Contacts::solve_lines`],
    /// warm-started from the last step's basis), the pivots added to `pivots`.
    ///
    /// # Errors
    /// As [`Contacts::solve_lines`].
    pub(super) fn lines<const K: usize, const B: usize>(
        &mut self,
        contacts: &Contacts<'_, T, K, B>,
        free: &Motion<T, B>,
        pivots: &mut u32,
    ) -> Result<([SpatialContactReport<T>; K], Motion<T, B>), StepError> {
        contacts.solve_lines(&self.solver, &mut self.basis, pivots, free)
    }
}

impl<T: Real, const N: usize> Solve<T, N> {
    /// The step from `st` (`super`'s module docs, 3 and 4): the impulses of the `touches` (a
    /// plane of unit normal `normal`; `speed` the largest free point speed, the step's velocity
    /// scale, and `terms` the largest sum of the sizes a free slip is summed from, its round-off's
    /// scale) on the free velocities `v_free`, `w_free`, then the turn. The state after the step,
    /// each contact's report and the pivots taken.
    ///
    /// # Errors
    /// [`StepError`]: the contacts' solve's, or a state that is not finite.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn advance<const K: usize>(
        &mut self,
        body: &Body<T>,
        s: &SpatialSettings<T>,
        st: &State<T>,
        n: Vector<T>,
        touches: &[Touch<T>; K],
        (speed, terms): (T, T),
        v_free: &Vector<T>,
        w_free: &Vector<T>,
    ) -> Result<Advanced<T, K>, StepError> {
        let h = s.step;
        let mut pivots = 0;
        let (contacts, v, w) = if touches.iter().any(|c: &Touch<T>| c.active) {
            let contacts = Contacts {
                bodies: [Frame {
                    body,
                    inverse_inertia: InverseInertia::new(body, &st.orientation),
                    inverse_mass: T::one(),
                }],
                mass: body.mass,
                normal: n,
                touches,
                // The round-off of slips and of the cone's conditions: `256 eps` of the step's
                // velocity scale, at least `8 eps` of the terms a slip is summed from.
                slip_tolerance: max(
                    T::of(256.0) * T::EPS * (speed + norm(&s.gravity) * h + T::TINY),
                    T::of(8.0) * T::EPS * terms,
                ),
                floor: T::of(64.0) * T::EPS * norm(&s.gravity) * h,
                stick_speed: s.stick_speed,
            };
            match s.friction {
                FrictionCone::Circular => {
                    let (solver, load) = (&self.solver, &mut self.load_basis);
                    if let Some(answer) =
                        contacts.flat_base(solver, load, &mut pivots, v_free, w_free, LOAD_TRIES)?
                    {
                        answer
                    } else {
                        match contacts.solve(solver, &mut self.basis, &mut pivots, v_free, w_free) {
                            Ok(path) => {
                                contacts.least_norm(solver, load, &mut pivots, path, v_free, w_free)?
                            }
                            // A flat base near its stop: its lines' loads may flip between
                            // vertices of the open load at every try; its own directions,
                            // given more tries, settle.
                            Err(StepError::ConeNotConverged) => contacts
                                .flat_base(solver, load, &mut pivots, v_free, w_free, PATIENT_TRIES)?
                                .ok_or(StepError::ConeNotConverged)?,
                            Err(e) => return Err(e),
                        }
                    }
                }
                FrictionCone::Pyramid { directions } => contacts.solve_pyramid(
                    &self.solver,
                    &mut self.basis,
                    &mut pivots,
                    usize::from(directions),
                    v_free,
                    w_free,
                )?,
            }
        } else {
            ([SpatialContactReport::separated(); K], *v_free, *w_free)
        };
        let state = moved_state(body, st, v, w, h);
        if !state.is_finite() {
            return Err(StepError::NonFinite);
        }
        Ok((state, contacts, pivots))
    }
}

/// The body at `st` after a step `h` at velocity `v` and angular velocity `w` (`super`'s module
/// docs, 4): `x + h v`, the turn at the midpoint's angular velocity of the momentum `I_w w`, and
/// the angular velocity of that momentum at the new orientation.
pub(super) fn moved_state<T: Real>(
    body: &Body<T>,
    st: &State<T>,
    v: Vector<T>,
    w: Vector<T>,
    h: T,
) -> State<T> {
    // A body whose moments are equal (a sphere) has `I_w = I` at every orientation: its
    // angular velocity is its momentum's, unchanged, with no round-off of the turns.
    let [ia, ib, ic] = body.inertia;
    let (orientation, angular_velocity) = if ia == ib && ib == ic {
        (turned(&st.orientation, &w, h), w)
    } else {
        let momentum = inertia_times(body, &st.orientation, &w);
        let half = turned(&st.orientation, &w, h * T::of(0.5));
        let orientation = turned(&st.orientation, &inverse_inertia_times(body, &half, &momentum), h);
        (orientation, inverse_inertia_times(body, &orientation, &momentum))
    };
    State { position: advanced(&st.position, h, &v), orientation, velocity: v, angular_velocity }
}
