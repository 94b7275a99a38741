//! A body resting on supports that move: points under its flat lower face, each carried along a
//! path the caller gives step by step (fingers under a rod). The step is `super`'s module docs'
//! (3 and 4) with each contact's slip the body point's velocity less the support's.
//!
//! # Fingers lie across the rod
//!
//! Two point supports under a rod's centre line hold it in neutral balance at best about that
//! line: its centre of mass sits half its thickness above them, so any roll grows, and a finger
//! that slides across the rod (a path not along its axis) turns the friction into a moment about
//! it. A real finger is a pad lying across the rod. A [`Finger`] here is a horizontal line
//! through its tip along `across`, carried at one velocity; it touches the face where the line
//! crosses a line of the face along the rod ([`Finger::crossing`]): a pad touches at the face's
//! two long edges ([`Finger::crossings`], the rod's width apart), a point finger on its centre
//! line.
//!
//! **A pad and a point.** `crate::scene::spatial::MeterStick3d` puts finger 1 as a pad and finger
//! 2 as a point: three points not in a line, which hold the rod against roll and decide every
//! point's load (the body's motion out of the face's plane, three conditions, fixes three loads).
//! Two pads would give four coplanar points, whose normal rows leave one load open: the LCP's
//! rows are then degenerate: on the meter stick's run Lemke's method returned, 36 steps in, an
//! answer it could not verify (residual `7e-6` after 23 pivots; `super`'s "The load" takes the
//! least-norm load only for a base sliding as a whole, and here one finger always sticks). At a path along the rod's axis (the
//! paper's trick) the pad's two points are mirror images across the centre line: their loads are
//! equal (the roll's balance), their frictions along the axis, and with finger 2's point their
//! sums are two point fingers' at the tips: the planar scene's motion
//! (`tests/tests/meter_stick_3d.rs`).
//!
//! **The step's geometry** is its start's, as the planar stepper's frames: the body's state then
//! and the supports where they were, each moving at its velocity over the step.
//!
//! What the finger's width along the rod decides (how close the fingers come) is the scene's.

use super::algebra::{Rotation, Vector, add, cross, dot, norm, scale, sub, unrotate};
use super::body::{Body, State, advanced};
use super::friction::Touch;
use super::report::{Mode, SpatialStepReport};
use super::stepper::{Solve, SpatialSettings, check_friction};
use crate::ParamError;
use crate::StepError;
use crate::planar::assemble::normal_bias;
use crate::real::{Real, max};

/// A body's flat lower face: the rectangle `|x| <= half_length`, `|y| <= half_width` at `z =
/// -half_thickness` in the body's frame, its outward normal `-z` (the supports push along `+z`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LowerFace<T> {
    /// Half the face's length along the body's `x`, m (> 0).
    pub half_length: T,
    /// Half its width along the body's `y`, m (> 0).
    pub half_width: T,
    /// The face's depth under the centre of mass, m (>= 0).
    pub half_thickness: T,
}

/// A support point under the face: where it is at the step's start and how its material moves
/// over the step, world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SupportPoint<T> {
    /// m.
    pub position: Vector<T>,
    /// m/s.
    pub velocity: Vector<T>,
}

/// A finger lying across the body (module docs): the horizontal line through `tip` along the
/// unit vector `across`, its material moving at `velocity`, world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Finger<T> {
    /// A point of the line (the finger's tip), m.
    pub tip: Vector<T>,
    /// The line's direction (unit).
    pub across: Vector<T>,
    /// m/s.
    pub velocity: Vector<T>,
}

impl<T: Real> Finger<T> {
    /// Where the finger's line crosses the line `y = along_y` of the face's plane (body frame)
    /// at `state`: with `l0 = R^T (tip - x)` and `e = R^T across`, the line's point `l0 + s e`
    /// at `s = (along_y - l0.y) / e.y`. `None` when the line runs within `acos(1/16)` (86.4 deg)
    /// of the body's `x` axis (`|e.y| < 1/16`: the crossing runs off to the ends; the finger then
    /// carries nothing).
    #[must_use]
    pub fn crossing(&self, along_y: T, state: &State<T>) -> Option<SupportPoint<T>> {
        self.crossing_in(along_y, &self.in_body(state))
    }

    /// The finger's line in the body's frame at `state`: `(R^T (tip - x), R^T across)`.
    fn in_body(&self, state: &State<T>) -> (Vector<T>, Vector<T>) {
        (
            unrotate(&state.orientation, &sub(&self.tip, &state.position)),
            unrotate(&state.orientation, &self.across),
        )
    }

    /// [`Self::crossing`] with the line in the body's frame, `(l0, e)`, given ([`Self::in_body`]).
    fn crossing_in(&self, along_y: T, (l0, e): &(Vector<T>, Vector<T>)) -> Option<SupportPoint<T>> {
        // Not at least 1/16 (NaN included).
        if e[1].abs_exact().partial_cmp(&T::of(1.0 / 16.0)).is_none_or(core::cmp::Ordering::is_lt) {
            return None;
        }
        let s = (along_y - l0[1]) / e[1];
        Some(SupportPoint { position: add(&self.tip, &scale(s, &self.across)), velocity: self.velocity })
    }

    /// Where the face's long edges (`y = -half_width`, then `+half_width`) cross the finger's line
    /// ([`Self::crossing`]): a pad across the whole face.
    #[must_use]
    pub fn crossings(&self, face: &LowerFace<T>, state: &State<T>) -> [Option<SupportPoint<T>>; 2] {
        let line = self.in_body(state);
        [-face.half_width, face.half_width].map(|b| self.crossing_in(b, &line))
    }
}

/// A support point against the face ([`SupportedStepper::touch`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceTouch<T> {
    /// The contact point's offset from the centre of mass, world axes, m.
    pub lever: Vector<T>,
    /// The point's depth below the face, m (negative when sunk in).
    pub gap: T,
    /// Whether it is under the face.
    pub under: bool,
}

/// A body on `K` support points under its [`LowerFace`] (`N = 4 K` LCP rows), each carried as the
/// caller says step by step, stepped as `super`'s module docs say.
#[derive(Debug, Clone)]
pub struct SupportedStepper<T: Real, const K: usize, const N: usize> {
    body: Body<T>,
    face: LowerFace<T>,
    mu: [T; 2],
    settings: SpatialSettings<T>,
    state: State<T>,
    modes: [Mode; K],
    steps: u64,
    solve: Solve<T, N>,
}

impl<T: Real, const K: usize, const N: usize> SupportedStepper<T, K, N> {
    /// A stepper for `body` of lower face `face`, friction `mu_static` and `mu_kinetic` at every
    /// support, from `state` on the supports `start` (where they are and move at the start). The
    /// modes before the first step: a support under the face touching it (its gap within `64 eps`
    /// of the positions) slides when its slip exceeds the stick speed, else sticks; any other is
    /// separated (the planar stepper's rule).
    ///
    /// # Errors
    /// [`ParamError`]: the body's ([`Body::validate`]), a face's half length or width not finite
    /// and positive or its half thickness negative (`face`), `mu_kinetic < 0` or above
    /// `mu_static`, a step, stick speed or margin not finite and positive, gravity or the state
    /// not finite.
    pub fn new(
        body: Body<T>,
        face: LowerFace<T>,
        [mu_static, mu_kinetic]: [T; 2],
        settings: SpatialSettings<T>,
        state: State<T>,
        start: &[Option<SupportPoint<T>>; K],
    ) -> Result<Self, ParamError> {
        const {
            assert!(
                K >= 1 && K <= 8 && N >= 4 * K && N <= 32,
                "SupportedStepper needs 1 <= K <= 8, 4 K <= N <= 32"
            );
        };
        body.validate()?;
        let [l, w, t] = [face.half_length, face.half_width, face.half_thickness];
        if !(l.finite() && w.finite() && t.finite() && l > T::zero() && w > T::zero() && t >= T::zero()) {
            return Err(ParamError::OutOfRange("face"));
        }
        check_friction(mu_static, mu_kinetic)?;
        settings.check_steps()?;
        if !super::algebra::finite(&settings.gravity) {
            return Err(ParamError::NonFinite("gravity"));
        }
        if !state.is_finite() {
            return Err(ParamError::NonFiniteState);
        }
        let state = State { orientation: super::algebra::normalized(&state.orientation), ..state };
        let mut stepper = Self {
            body,
            face,
            mu: [mu_static, mu_kinetic],
            settings,
            state,
            modes: [Mode::Separated; K],
            steps: 0,
            solve: Solve::new(),
        };
        let size = state.position.iter().fold(face.half_length + face.half_width, |a, x| a + x.abs_exact());
        let touching = T::of(64.0) * T::EPS * size;
        let n = stepper.normal();
        let mut modes = [Mode::Separated; K];
        for (mode, support) in modes.iter_mut().zip(start) {
            let Some(p) = support else { continue };
            let FaceTouch { lever: r, gap, under } = stepper.touch(&p.position);
            if under && gap <= touching {
                let u = sub(&add(&state.velocity, &cross(&state.angular_velocity, &r)), &p.velocity);
                let slip = norm(&sub(&u, &scale(dot(&n, &u), &n)));
                *mode = if slip <= settings.stick_speed { Mode::Sticking } else { Mode::Sliding };
            }
        }
        stepper.modes = modes;
        Ok(stepper)
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

    /// The lower face.
    #[must_use]
    pub const fn face(&self) -> &LowerFace<T> {
        &self.face
    }

    /// The step's settings.
    #[must_use]
    pub const fn settings(&self) -> &SpatialSettings<T> {
        &self.settings
    }

    /// Each contact's mode after the last step.
    #[must_use]
    pub const fn modes(&self) -> &[Mode; K] {
        &self.modes
    }

    /// Simulated time, s.
    #[must_use]
    pub fn time(&self) -> T {
        T::of_count(u32::try_from(self.steps).unwrap_or(u32::MAX)) * self.settings.step
    }

    /// The time at the end of the next step, s: where the caller puts the supports.
    #[must_use]
    pub fn next_time(&self) -> T {
        T::of_count(u32::try_from(self.steps.saturating_add(1)).unwrap_or(u32::MAX)) * self.settings.step
    }

    /// The face's normal now (unit, world axes): the direction the supports push.
    #[must_use]
    pub fn normal(&self) -> Vector<T> {
        Rotation::of(&self.state.orientation).axis(2)
    }

    /// A support point at `p` against the face now: `l = R^T (p - x)`, under the face when
    /// `|l.x| <= half_length`, `|l.y| <= half_width` (within `16 eps` of the positions:
    /// [`Finger::crossings`] puts points on its edges) and `l.z <= 0`; its gap `-l.z -
    /// half_thickness`, its contact point `R (l.x, l.y, -half_thickness)`.
    #[must_use]
    pub fn touch(&self, p: &Vector<T>) -> FaceTouch<T> {
        self.touch_turned(&Rotation::of(&self.state.orientation), p)
    }

    /// [`Self::touch`] with the body's rotation now, `rotation`, built already.
    fn touch_turned(&self, rotation: &Rotation<T>, p: &Vector<T>) -> FaceTouch<T> {
        let (st, f) = (&self.state, &self.face);
        let l = rotation.unapply(&sub(p, &st.position));
        let lever = rotation.apply(&[l[0], l[1], -f.half_thickness]);
        let size = st.position.iter().fold(norm(&lever), |a, x| a + x.abs_exact());
        let edge = f.half_width + T::of(16.0) * T::EPS * size;
        FaceTouch {
            lever,
            gap: -l[2] - f.half_thickness,
            under: l[0].abs_exact() <= f.half_length && l[1].abs_exact() <= edge && l[2] <= T::zero(),
        }
    }

    /// Support `p` in the body's frame: `R^T (p - x)`.
    #[must_use]
    pub fn in_body(&self, p: &Vector<T>) -> Vector<T> {
        unrotate(&self.state.orientation, &sub(p, &self.state.position))
    }

    /// Advances one step of `h` on the `supports` (`None`: a slot that touches nothing this step):
    /// a support point enters the step's LCP when it is under the face ([`Self::touch`]) and its
    /// gap is within the margin.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged. [`StepError::NonFinite`] for a support that is
    /// not finite.
    pub fn step(
        &mut self,
        supports: &[Option<SupportPoint<T>>; K],
    ) -> Result<SpatialStepReport<T, K>, StepError> {
        let s = self.settings;
        let (h, st) = (s.step, self.state);
        // The body's rotation, once for the step: its normal and axis, every support's touch.
        let rotation = Rotation::of(&st.orientation);
        let n = rotation.axis(2);
        let v_free = advanced(&st.velocity, h, &s.gravity);
        let w_free = st.angular_velocity;
        let position_size = st.position.iter().fold(T::zero(), |a, x| a + x.abs_exact());
        // A support whose free slip is too small to say its direction starts its friction along
        // the body's axis (the face's length).
        let axis = rotation.axis(0);
        let (mut speed, mut terms) = (T::zero(), T::zero());
        let (v_size, w_size) = (norm(&v_free), norm(&w_free));
        let mut finite = true;
        // Written in place (an array built by a closure is copied out).
        let mut touches = [Touch::idle(n); K];
        for ((touch, support), &mode) in touches.iter_mut().zip(supports).zip(&self.modes) {
            let Some(support) = support else {
                continue;
            };
            finite &= super::algebra::finite(&support.position) && super::algebra::finite(&support.velocity);
            let FaceTouch { lever: r, gap, under } = self.touch_turned(&rotation, &support.position);
            let round_off = T::of(4.0) * T::EPS * (position_size + norm(&r));
            let u_free = sub(&add(&v_free, &cross(&w_free, &r)), &support.velocity);
            speed = max(speed, norm(&u_free));
            // The slip is summed from `v~`, `omega~ x r` and the support's velocity: its round-off
            // is of their sizes (as on a plane, `super::stepper`).
            terms = max(terms, v_size + w_size * norm(&r) + norm(&support.velocity));
            let mu = if mode == Mode::Sliding { self.mu[1] } else { self.mu[0] };
            *touch = Touch {
                active: under && gap <= s.margin,
                arm: r,
                normal_free: dot(&n, &u_free) + normal_bias(gap, h, norm(&s.gravity), round_off),
                slip_free: sub(&u_free, &scale(dot(&n, &u_free), &n)),
                carried: support.velocity,
                rest_line: Some(axis),
                mu,
                normal: n,
                body: 0,
                beneath: None,
            };
        }
        if !finite {
            return Err(StepError::NonFinite);
        }
        let (state, contacts, pivots) =
            self.solve.advance(&self.body, &s, &st, n, &touches, (speed, terms), &v_free, &w_free)?;
        self.state = state;
        self.modes = contacts.map(|c| c.mode);
        self.steps += 1;
        Ok(SpatialStepReport { time: self.time(), state, contacts, pivots })
    }
}
