//! One body with six degrees of freedom on a plane, one point of contact: the step of
//! `super`'s module docs.

use super::algebra::{Vector, add, cross, direction, dot, norm, perpendicular, rotate, scale, sub};
use super::body::{Body, State, advanced, inertia_times, inverse_inertia_times, turned};
use crate::ParamError;
use crate::lcp::{Basis, Lcp, LcpError, Lemke};
use crate::planar::assemble::normal_bias;
use crate::real::{Real, max};

/// The most friction directions a step tries before it gives up ([`StepError::ConeNotConverged`]):
/// a contact whose tangential response is isotropic and uncoupled from its normal (a sphere, a
/// point under the centre of mass) needs one.
pub const MAX_DIRECTIONS: u32 = 16;

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
pub enum Shape<T> {
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
}

/// The contact's mode after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Mode {
    /// No normal impulse.
    Separated,
    /// A normal impulse and a slip of at most the stick speed.
    Sticking,
    /// A normal impulse and a slip beyond it; friction opposes the slip.
    Sliding,
}

/// The step's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Settings<T> {
    /// Time step `h`, s. Default `1e-3`.
    pub step: T,
    /// Gravity, m/s^2, world axes. Default `(0, 0, -9.81)`.
    pub gravity: Vector<T>,
    /// Slip speed below which a loaded contact reads sticking, m/s. Default `1e-5`.
    pub stick_speed: T,
    /// Gap within which the contact enters the step's LCP, m. Default `1e-3`.
    pub margin: T,
}

impl<T: Real> Default for Settings<T> {
    fn default() -> Self {
        Self {
            step: T::of(1e-3),
            gravity: [T::zero(), T::zero(), T::of(-9.81)],
            stick_speed: T::of(1e-5),
            margin: T::of(1e-3),
        }
    }
}

/// The contact after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ContactReport<T> {
    /// Its mode.
    pub mode: Mode,
    /// Normal impulse, N s.
    pub normal_impulse: T,
    /// Friction impulse on the body, N s, world axes (in the plane).
    pub friction_impulse: Vector<T>,
    /// The contact point's velocity along the plane after the step, m/s, world axes.
    pub slip: Vector<T>,
    /// The friction directions the step tried (1 when the first, along the free slip, held).
    pub directions: u32,
    /// The circular cone's residual of the answer: `|p_t + mu p_n s^|` over `mu p_n` when
    /// sliding (`s^` the slip's direction), `(|p_t| - mu p_n)+` over `mu p_n` when sticking; 0
    /// when separated.
    pub cone_residual: T,
}

impl<T: Real> ContactReport<T> {
    /// No contact: separated, nothing carried.
    fn separated() -> Self {
        Self {
            mode: Mode::Separated,
            normal_impulse: T::zero(),
            friction_impulse: [T::zero(); 3],
            slip: [T::zero(); 3],
            directions: 0,
            cone_residual: T::zero(),
        }
    }
}

/// A contact's report and the body's velocity and angular velocity after its impulse.
type Contacted<T> = (ContactReport<T>, Vector<T>, Vector<T>);

/// One step's result.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StepReport<T> {
    /// Time at the end of the step, s.
    pub time: T,
    /// The body after the step.
    pub state: State<T>,
    /// Its contact.
    pub contact: ContactReport<T>,
}

/// Why a step failed; the state is then unchanged.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum StepError {
    /// The contact's LCP had no verified answer.
    Solver(LcpError),
    /// The friction direction and the slip did not agree within [`MAX_DIRECTIONS`] tries.
    ConeNotConverged,
    /// The answer broke the circular cone's conditions beyond round-off (the residual, as
    /// [`ContactReport::cone_residual`]).
    ConeUnverified {
        /// The residual.
        residual: f32,
    },
    /// The state after the step would not be finite.
    NonFinite,
}

/// A body on a plane, stepped as `super`'s module docs say.
#[derive(Debug, Clone)]
pub struct Stepper<T: Real> {
    body: Body<T>,
    shape: Shape<T>,
    plane: Plane<T>,
    settings: Settings<T>,
    state: State<T>,
    mode: Mode,
    steps: u64,
    solver: Lemke<T, 4>,
    basis: Basis<4>,
}

impl<T: Real> Stepper<T> {
    /// A stepper for `body` of `shape` on `plane`, starting at `state`.
    ///
    /// # Errors
    /// [`ParamError`] naming what is refused: the body ([`Body::validate`]), a radius that is not
    /// finite and positive (`radius`), an offset that is not finite (`offset`), a plane whose
    /// normal is not a unit vector (`normal`) or whose point is not finite (`point`), `mu_kinetic
    /// < 0` (`mu_kinetic`) or `mu_kinetic > mu_static`, a step, stick speed or margin that is not
    /// finite and positive, non-finite gravity (`gravity`), a state that is not finite.
    pub fn new(
        body: Body<T>,
        shape: Shape<T>,
        plane: Plane<T>,
        settings: Settings<T>,
        state: State<T>,
    ) -> Result<Self, ParamError> {
        body.validate()?;
        match shape {
            Shape::Sphere { radius } if !radius.finite() => return Err(ParamError::NonFinite("radius")),
            Shape::Sphere { radius } if radius <= T::zero() => return Err(ParamError::NotPositive("radius")),
            Shape::Point { offset } if !super::algebra::finite(&offset) => {
                return Err(ParamError::NonFinite("offset"));
            }
            _ => {}
        }
        if !super::algebra::finite(&plane.point) {
            return Err(ParamError::NonFinite("point"));
        }
        let n = norm(&plane.normal);
        if !n.finite() || (n - T::one()).abs_exact() > T::of(64.0) * T::EPS {
            return Err(ParamError::OutOfRange("normal"));
        }
        for (value, name) in [(plane.mu_static, "mu_static"), (plane.mu_kinetic, "mu_kinetic")] {
            if !value.finite() {
                return Err(ParamError::NonFinite(name));
            }
            if value < T::zero() {
                return Err(ParamError::Negative(name));
            }
        }
        if plane.mu_kinetic > plane.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        for (value, name) in
            [(settings.step, "step"), (settings.stick_speed, "stick_speed"), (settings.margin, "margin")]
        {
            if !value.finite() {
                return Err(ParamError::NonFinite(name));
            }
            if value <= T::zero() {
                return Err(ParamError::NotPositive(name));
            }
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
            shape,
            plane,
            settings,
            state,
            mode: Mode::Separated,
            steps: 0,
            solver: Lemke::new(),
            basis: Basis::all_w(),
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

    /// The contact's mode after the last step.
    #[must_use]
    pub const fn mode(&self) -> Mode {
        self.mode
    }

    /// Simulated time, s.
    #[must_use]
    pub fn time(&self) -> T {
        T::of_count(u32::try_from(self.steps).unwrap_or(u32::MAX)) * self.settings.step
    }

    /// The contact point's offset from the centre of mass, world axes, at `state`.
    fn arm(&self, state: &State<T>) -> Vector<T> {
        match self.shape {
            Shape::Sphere { radius } => scale(-radius, &self.plane.normal),
            Shape::Point { offset } => rotate(&state.orientation, &offset),
        }
    }

    /// `e . W f` per unit mass: the contact point's velocity change along `e` for a unit impulse
    /// per unit mass along `f`, `e . f + m (r x e) . I_w^-1 (r x f)`.
    fn delassus(&self, r: &Vector<T>, e: &Vector<T>, f: &Vector<T>) -> T {
        let turn = inverse_inertia_times(&self.body, &self.state.orientation, &cross(r, f));
        dot(e, f) + self.body.mass * dot(&cross(r, e), &turn)
    }

    /// Advances one step of `h`.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged.
    pub fn step(&mut self) -> Result<StepReport<T>, StepError> {
        let s = self.settings;
        let h = s.step;
        let st = self.state;
        let v_free = advanced(&st.velocity, h, &s.gravity);
        let w_free = st.angular_velocity;
        let r = self.arm(&st);
        let gap = dot(&self.plane.normal, &sub(&add(&st.position, &r), &self.plane.point));
        let (contact, v, w) = if gap <= s.margin {
            self.contact(gap, &r, &v_free, &w_free)?
        } else {
            (ContactReport::separated(), v_free, w_free)
        };
        // A body whose moments are equal (a sphere) has `I_w = I` at every orientation: its
        // angular velocity is its momentum's, unchanged, with no round-off of the turns.
        let [ia, ib, ic] = self.body.inertia;
        let (orientation, angular_velocity) = if ia == ib && ib == ic {
            (turned(&st.orientation, &w, h), w)
        } else {
            let momentum = inertia_times(&self.body, &st.orientation, &w);
            let half = turned(&st.orientation, &w, h * T::of(0.5));
            let orientation =
                turned(&st.orientation, &inverse_inertia_times(&self.body, &half, &momentum), h);
            (orientation, inverse_inertia_times(&self.body, &orientation, &momentum))
        };
        let state =
            State { position: advanced(&st.position, h, &v), orientation, velocity: v, angular_velocity };
        if !state.is_finite() {
            return Err(StepError::NonFinite);
        }
        self.state = state;
        self.mode = contact.mode;
        self.steps += 1;
        Ok(StepReport { time: self.time(), state, contact })
    }

    /// The contact within the margin at `gap`, arm `r`: its impulse by the LCPs of friction lines
    /// turned to the slip (module docs, 3), checked against the circular cone; the report and the
    /// velocities after it.
    fn contact(
        &mut self,
        gap: T,
        r: &Vector<T>,
        v_free: &Vector<T>,
        w_free: &Vector<T>,
    ) -> Result<Contacted<T>, StepError> {
        let (s, st, n) = (self.settings, self.state, self.plane.normal);
        let size = norm(r);
        let round_off =
            T::of(4.0) * T::EPS * (st.position.iter().fold(T::zero(), |a, x| a + x.abs_exact()) + size);
        let bias = normal_bias(gap, s.step, norm(&s.gravity), round_off);
        let u_free = add(v_free, &cross(w_free, r));
        let un = dot(&n, &u_free) + bias;
        let ut = sub(&u_free, &scale(dot(&n, &u_free), &n));
        let mu = if self.mode == Mode::Sliding { self.plane.mu_kinetic } else { self.plane.mu_static };
        // The step's velocity scale: the round-off of slips and of the cone's conditions.
        let slip_tolerance = T::of(256.0) * T::EPS * (norm(&u_free) + norm(&s.gravity) * s.step + T::TINY);
        // The friction line `d = (e1 + t e2) / |e1 + t e2|` in the plane: `e1` the free slip's
        // direction (or any), `t` what the tries move.
        let e1 = direction(&ut).unwrap_or_else(|| perpendicular(&n));
        let e2 = cross(&n, &e1);
        let (mut t, mut previous): (T, Option<(T, T)>) = (T::zero(), None);
        let mut d = e1;
        for tries in 1..=MAX_DIRECTIONS {
            let (wnn, wnd, wdd) =
                (self.delassus(r, &n, &n), self.delassus(r, &n, &d), self.delassus(r, &d, &d));
            let ud = dot(&d, &ut);
            let (o, one) = (T::zero(), T::one());
            let lcp = Lcp::from_rows(
                &[[wnn, wnd, -wnd, o], [wnd, wdd, -wdd, one], [-wnd, -wdd, wdd, one], [mu, -one, -one, o]],
                &[un, ud, -ud, o],
            );
            let sol = self.solver.solve_warm(&lcp, self.basis).map_err(StepError::Solver)?;
            self.basis = sol.basis;
            let (pn, pt) = (sol.z[0], sol.z[1] - sol.z[2]);
            let p = add(&scale(pn, &n), &scale(pt, &d));
            let v = add(v_free, &p);
            let turn = inverse_inertia_times(&self.body, &st.orientation, &cross(r, &p));
            let w = add(w_free, &scale(self.body.mass, &turn));
            let u = add(&v, &cross(&w, r));
            let slip = sub(&u, &scale(dot(&n, &u), &n));
            let across = cross(&n, &d);
            let off = dot(&slip, &across);
            if off.abs_exact() <= slip_tolerance {
                let report = self.report(pn, &scale(pt, &d), &slip, mu, slip_tolerance, tries)?;
                return Ok((report, v, w));
            }
            // Turn the line: a saturated contact's toward the slip (friction opposes it), by the
            // secant on the slip across the line once two tries are known (the plain turn to
            // the slip converges only linearly where the response is coupled); a sticking one's
            // to the tangential impulse that stops the slip with this normal one.
            let saturated = pt.abs_exact() >= mu * pn * (one - T::of(1e-3));
            let target = if saturated {
                slip
            } else {
                let (wda, waa, wna) = (
                    self.delassus(r, &d, &across),
                    self.delassus(r, &across, &across),
                    self.delassus(r, &n, &across),
                );
                let (ra, rb) = (-(ud + wnd * pn), -(dot(&across, &ut) + wna * pn));
                let det = wdd * waa - wda * wda;
                let (qd, qa) = ((ra * waa - rb * wda) / det, (rb * wdd - ra * wda) / det);
                add(&scale(qd, &d), &scale(qa, &across))
            };
            let along = dot(&target, &e1);
            let next = match previous {
                Some((t0, off0)) if saturated && off != off0 => t - off * (t - t0) / (off - off0),
                _ if along.abs_exact() > T::zero() => dot(&target, &e2) / along,
                _ => t,
            };
            previous = Some((t, off));
            t = next;
            d = direction(&add(&e1, &scale(t, &e2))).unwrap_or(d);
        }
        Err(StepError::ConeNotConverged)
    }

    /// The report of a contact whose impulse per unit mass is `pn` along the normal and `pt` in
    /// the plane, slipping at `slip` after the step, held to the circular cone's conditions (every
    /// LCP answer is verified already; this checks the cone the LCP's line stood for).
    fn report(
        &self,
        pn: T,
        pt: &Vector<T>,
        slip: &Vector<T>,
        mu: T,
        slip_tolerance: T,
        tries: u32,
    ) -> Result<ContactReport<T>, StepError> {
        let s = self.settings;
        let limit = mu * pn;
        let (slip_speed, friction) = (norm(slip), norm(pt));
        let residual = if pn <= T::zero() {
            T::zero()
        } else if limit <= T::zero() {
            friction / pn
        } else if slip_speed > slip_tolerance {
            norm(&add(pt, &scale(limit / slip_speed, slip))) / limit
        } else {
            max(friction - limit, T::zero()) / limit
        };
        if residual > T::of(4096.0) * T::EPS || !residual.finite() {
            return Err(StepError::ConeUnverified { residual: residual.as_f32() });
        }
        let floor = T::of(64.0) * T::EPS * norm(&s.gravity) * s.step;
        let mode = if pn <= floor {
            Mode::Separated
        } else if slip_speed <= s.stick_speed {
            Mode::Sticking
        } else {
            Mode::Sliding
        };
        let m = self.body.mass;
        Ok(ContactReport {
            mode,
            normal_impulse: pn * m,
            friction_impulse: scale(m, pt),
            slip: *slip,
            directions: tries,
            cone_residual: residual,
        })
    }
}
