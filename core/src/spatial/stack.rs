//! Blocks resting on each other over a table's edge (`docs/scenes.md`, "stack-3d"): `B` equal
//! boxes, block 0 on the table's top (`z = 0` over `x <= 0`), block `i` on block `i - 1`, each pair
//! touching at the vertices of its faces' overlap ([`face_patch`], the corner-on-face rule).
//!
//! The step is `super`'s module docs' (3 and 4) for several bodies: the free motion `v~ = v + h g`,
//! `omega~ = omega` of each block; each contact's impulse pushes its upper block and, but on the
//! table, the block beneath it back (`super::space`: the Delassus operator over both), every
//! contact's friction line turned to its slip until the slips agree with the lines, every answer
//! verified against the circular cone; then each block turns at its own midpoint's angular
//! velocity of its momentum (`super::stepper::moved_state`). The contacts of the pairs fill the
//! `K` slots in turn, pair by pair (the table's first), so a contact keeps its slot while its pair
//! keeps its count, and with it its mode (`mu_s` after a step it stuck, `mu_k` after one it slid)
//! and its place in the warm basis.
//!
//! **The load.** Four points of a face on a face leave their loads open: three conditions, the
//! face's motion out of its plane, decide three of them (and their frictions likewise), so the
//! LCP's rows are degenerate. The motion is the rigid one whichever load the answer carries. A
//! warm basis that is singular on them is solved for its least-norm solution (`super::direct`:
//! the load rule's, `docs/formulation.md`, "The load: the least norm", among that basis'
//! solutions); where Lemke's method crosses such bases with more round-off than its
//! verification allows, the basis it ends in (or that of the problem made strictly copositive)
//! is solved so, and verified on the problem itself (`super::direct`'s open loads); in f64, where
//! the round-off of its pivots on those bases outgrows its ratio test's floor (`N eps`) and it
//! pivots into a ray, all of that again with single precision's floor (`N 2^-23`,
//! [`crate::lcp::Lemke::single_precision_floor`]), whose answers are verified in f64 all the
//! same. The rows the open loads close (the unloaded fourth point's normal row, the friction rows of a loaded point
//! that carries none) come out of a basis' answer at zero to round-off, of either sign: they are
//! held to the step's velocity round-off (`super::direct`'s slack), so a stack at rest keeps its
//! warm basis without a pivot, and a slip beyond it, a wrong mode, goes to Lemke's pivoting.
//! Every answer is verified to `1024 N eps` (four times Lemke's default,
//! [`crate::lcp::default_tolerance`]): one step of three blocks falling at 30 deg needs 1.23
//! times the default.
//!
//! Checked (`tests/tests/stack_3d.rs`): in f64 held at 0.98 and fallen at 1.02 at headings -45
//! to 60 deg, 2 and 3 blocks, every step within `2.5e-12` m and `3.2e-11` rad of the independent
//! reference's; at heading 0 the planar engine's stack to `4.4e-14`. In f32 the same outcomes.

use super::algebra::{Vector, add, cross, dot, finite, norm, normalized, scale, sub};
use super::body::{Body, Frame, InverseInertia, Motion, State, advanced};
use super::face_patch::{Beneath, FaceContact, face_patch};
use super::friction::{Contacts, Touch};
use super::report::{Mode, SpatialContactReport};
use super::stepper::{Solve, SpatialSettings, check_friction, moved_state};
use crate::ParamError;
use crate::StepError;
use crate::planar::assemble::normal_bias;
use crate::real::{Real, max};

/// The most vertices one pair's overlap has: a quadrilateral clipped by the four sides of a
/// rectangle.
pub const PATCH_POINTS: usize = 8;

/// Each slot's pair (the upper block's index) and contact (its point, normal and gap, world
/// axes, m); `None` for a slot no contact filled.
pub type SlotContacts<T, const K: usize> = [Option<(usize, FaceContact<T>)>; K];

/// One step's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StackStepReport<T, const B: usize, const K: usize> {
    /// Time at the end of the step, s.
    pub time: T,
    /// Each block after the step, block 0 the bottom.
    pub states: [State<T>; B],
    /// Each slot's contact: its report (impulses on the upper block).
    pub contacts: [SpatialContactReport<T>; K],
    /// Each slot's pair (the upper block's index) and contact (its point, normal and gap before
    /// the step, world axes, m); `None` for a slot no contact filled.
    pub points: SlotContacts<T, K>,
    /// Lemke pivots of the step's solves.
    pub pivots: u32,
}

/// `B` equal blocks (half extents `half`) stacked over the table's edge, `K` contact slots (`N
/// = 4 K` LCP rows, their bases in `W` words of 32 rows: `crate::lcp::Basis`), stepped as the
/// module docs say.
#[derive(Debug, Clone)]
pub struct BlockStack<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> {
    body: Body<T>,
    half: Vector<T>,
    mu: [T; 2],
    settings: SpatialSettings<T>,
    states: [State<T>; B],
    /// Each slot's pair and contact at `states` ([`Self::contacts`]), found once a step.
    patches: Result<SlotContacts<T, K>, StepError>,
    modes: [Mode; K],
    steps: u64,
    solve: Solve<T, N, W>,
}

/// A step's contacts: each slot's touch and its pair and point, the largest free contact speed
/// and the largest sum of the terms a free slip is summed from (`super::stepper`).
type Gathered<T, const K: usize> = ([Touch<T>; K], SlotContacts<T, K>, T, T);

impl<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> BlockStack<T, B, K, N, W> {
    /// A stack of `B` blocks of inertia `body` and half extents `half` (along their `x`, `y`,
    /// `z`), friction `mu_static` and `mu_kinetic` at every contact, from `states` (block 0 the
    /// bottom). Before the first step a touching slot (gap within the margin) reads sliding when
    /// its free slip exceeds the stick speed, else sticking.
    ///
    /// # Errors
    /// [`ParamError`]: the body's ([`Body::validate`]), half extents not finite and positive
    /// (`half`), `mu_kinetic < 0` or above `mu_static`, a step, stick speed or margin not finite
    /// and positive, gravity or a state not finite; more contacts at the start than `K` slots
    /// (`blocks`).
    pub fn new(
        body: Body<T>,
        half: Vector<T>,
        [mu_static, mu_kinetic]: [T; 2],
        settings: SpatialSettings<T>,
        states: [State<T>; B],
    ) -> Result<Self, ParamError> {
        const {
            assert!(
                B >= 1 && K >= 1 && N >= 4 * K && N <= 64,
                "BlockStack needs B, K >= 1 and 4 K <= N <= 64"
            );
        };
        body.validate()?;
        if !half.iter().all(|h| h.finite() && *h > T::zero()) {
            return Err(ParamError::OutOfRange("half"));
        }
        check_friction(mu_static, mu_kinetic)?;
        settings.check_steps()?;
        if !finite(&settings.gravity) {
            return Err(ParamError::NonFinite("gravity"));
        }
        if !states.iter().all(State::is_finite) {
            return Err(ParamError::NonFiniteState);
        }
        let states = states.map(|st| State { orientation: normalized(&st.orientation), ..st });
        let mut stack = Self {
            body,
            half,
            mu: [mu_static, mu_kinetic],
            settings,
            states,
            patches: Ok([None; K]),
            modes: [Mode::Sticking; K],
            steps: 0,
            // Verified to `1024 N eps` (module docs, "The load").
            solve: Solve::with_tolerance(T::of(1024.0 * N as f64) * T::EPS),
        };
        stack.patches = stack.patches_at(&states);
        let free = states.map(|st| (st.velocity, st.angular_velocity));
        let (touches, ..) = stack.gather(&free).map_err(|_| ParamError::OutOfRange("blocks"))?;
        stack.modes = touches.map(|c| match (c.active, norm(&c.slip_free) <= settings.stick_speed) {
            (false, _) => Mode::Separated,
            (true, true) => Mode::Sticking,
            (true, false) => Mode::Sliding,
        });
        Ok(stack)
    }

    /// Each block now, block 0 the bottom.
    #[must_use]
    pub const fn states(&self) -> &[State<T>; B] {
        &self.states
    }

    /// Every block's inertia.
    #[must_use]
    pub const fn body(&self) -> &Body<T> {
        &self.body
    }

    /// The blocks' half extents along their `x`, `y`, `z`, m.
    #[must_use]
    pub const fn half(&self) -> &Vector<T> {
        &self.half
    }

    /// The step's settings.
    #[must_use]
    pub const fn settings(&self) -> &SpatialSettings<T> {
        &self.settings
    }

    /// Each slot's mode after the last step.
    #[must_use]
    pub const fn modes(&self) -> &[Mode; K] {
        &self.modes
    }

    /// Simulated time, s.
    #[must_use]
    pub fn time(&self) -> T {
        T::of_count(u32::try_from(self.steps).unwrap_or(u32::MAX)) * self.settings.step
    }

    /// Each slot's pair (the upper block's index) and contact now, the pairs' contacts filling
    /// the slots in turn as a step fills them (module docs); `None` for a slot none fills.
    ///
    /// # Errors
    /// [`StepError::TooManyContacts`] when the pairs touch at more points than `K`.
    pub const fn contacts(&self) -> Result<SlotContacts<T, K>, StepError> {
        self.patches
    }

    /// Each slot's pair and contact at `states`: the pairs' face patches ([`face_patch`]) filling
    /// the slots in turn (module docs).
    ///
    /// # Errors
    /// [`StepError::TooManyContacts`] (the count so far) when the pairs touch at more points
    /// than `K`.
    fn patches_at(&self, states: &[State<T>; B]) -> Result<SlotContacts<T, K>, StepError> {
        let mut points = [None; K];
        let mut slot = 0usize;
        for (upper, st) in states.iter().enumerate() {
            let beneath = match upper.checked_sub(1).and_then(|l| states.get(l)) {
                Some(state) => Beneath::Block { state, half: self.half },
                None => Beneath::Table,
            };
            let patch = face_patch::<T, PATCH_POINTS>(st, &self.half, beneath, self.settings.margin)
                .map_err(|_| StepError::TooManyContacts(u8::try_from(slot).unwrap_or(u8::MAX)))?;
            for c in &patch {
                let Some(point) = points.get_mut(slot) else {
                    return Err(StepError::TooManyContacts(u8::try_from(slot + 1).unwrap_or(u8::MAX)));
                };
                *point = Some((upper, *c));
                slot += 1;
            }
        }
        Ok(points)
    }

    /// The contacts of every pair now ([`Self::contacts`]) on the motion `free` (module docs).
    ///
    /// # Errors
    /// [`StepError::TooManyContacts`] (the count so far) when the pairs touch at more points
    /// than `K`.
    fn gather(&self, free: &Motion<T, B>) -> Result<Gathered<T, K>, StepError> {
        let s = &self.settings;
        let zero = [T::zero(); 3];
        let points = self.patches?;
        let mut touches = [Touch::idle([T::zero(), T::zero(), T::one()]); K];
        let (mut speed, mut terms) = (T::zero(), T::zero());
        let gravity = norm(&s.gravity);
        for (slot, (touch, point)) in touches.iter_mut().zip(&points).enumerate() {
            let Some((upper, c)) = point else { break };
            let upper = *upper;
            let (Some(st), Some((v, w))) = (self.states.get(upper), free.get(upper)) else { break };
            let lower = upper.checked_sub(1).and_then(|l| self.states.get(l).zip(free.get(l)));
            let arm = sub(&c.point, &st.position);
            let mut u = add(v, &cross(w, &arm));
            let mut term = norm(v) + norm(w) * norm(&arm);
            let mut size = st.position.iter().fold(norm(&arm), |a, x| a + x.abs_exact());
            let under = lower.map(|(state, (vl, wl))| {
                let arm = sub(&c.point, &state.position);
                u = sub(&u, &add(vl, &cross(wl, &arm)));
                term += norm(vl) + norm(wl) * norm(&arm);
                size += state.position.iter().fold(norm(&arm), |a, x| a + x.abs_exact());
                (upper - 1, arm)
            });
            speed = max(speed, norm(&u));
            terms = max(terms, term);
            let n = c.normal;
            let round_off = T::of(4.0) * T::EPS * size;
            let slid = self.modes.get(slot) == Some(&Mode::Sliding);
            *touch = Touch {
                active: true,
                arm,
                normal_free: dot(&n, &u) + normal_bias(c.gap, s.step, gravity, round_off),
                slip_free: sub(&u, &scale(dot(&n, &u), &n)),
                carried: zero,
                rest_line: None,
                mu: if slid { self.mu[1] } else { self.mu[0] },
                normal: n,
                body: upper,
                beneath: under,
            };
        }
        Ok((touches, points, speed, terms))
    }

    /// Advances one step of `h`.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged: the contacts' solve's
    /// ([`StepError::Solver`], [`StepError::ConeNotConverged`], [`StepError::ConeUnverified`]),
    /// [`StepError::TooManyContacts`], [`StepError::NonFinite`].
    pub fn step(&mut self) -> Result<StackStepReport<T, B, K>, StepError> {
        let s = self.settings;
        let h = s.step;
        let free: Motion<T, B> =
            self.states.map(|st| (advanced(&st.velocity, h, &s.gravity), st.angular_velocity));
        let (touches, points, speed, terms) = self.gather(&free)?;
        let mut pivots = 0;
        let (contacts, motion) = if touches.iter().any(|c| c.active) {
            let contacts = Contacts {
                bodies: self.states.each_ref().map(|st| Frame {
                    body: &self.body,
                    inverse_inertia: InverseInertia::new(&self.body, &st.orientation),
                    inverse_mass: T::one(),
                }),
                mass: self.body.mass,
                normal: [T::zero(), T::zero(), T::one()],
                touches: &touches,
                // As one body's (`super::stepper`): `256 eps` of the step's velocity scale, at
                // least `8 eps` of the terms a slip is summed from.
                slip_tolerance: max(
                    T::of(256.0) * T::EPS * (speed + norm(&s.gravity) * h + T::TINY),
                    T::of(8.0) * T::EPS * terms,
                ),
                floor: T::of(64.0) * T::EPS * norm(&s.gravity) * h,
                stick_speed: s.stick_speed,
            };
            self.solve.lines(&contacts, &free, &mut pivots)?
        } else {
            ([SpatialContactReport::separated(); K], free)
        };
        let mut states = self.states;
        for (state, (v, w)) in states.iter_mut().zip(motion) {
            *state = moved_state(&self.body, state, v, w, h);
            if !state.is_finite() {
                return Err(StepError::NonFinite);
            }
        }
        self.states = states;
        self.patches = self.patches_at(&states);
        self.modes = contacts.map(|c| c.mode);
        self.steps += 1;
        Ok(StackStepReport { time: self.time(), states, contacts, points, pivots })
    }
}
