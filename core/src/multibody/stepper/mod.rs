//! [`SystemStepper`]: `B` boxes on each other and on a table, one LCP per step, solved in the bodies'
//! coordinates when a basis near the last one answers and by Lemke's method otherwise
//! (`docs/formulation.md`, "Several bodies", "One step", "Solving a multibody step (the core)").
//!
//! # The files
//! * this one: the public types ([`System`], [`SystemSettings`], [`StepError`], [`SystemStepper`]), the
//!   constructor and its checks ([`SystemStepper::new`]), the candidates' frames;
//! * `step.rs`: the step ([`SystemStepper::step`]) and the load where it is open;
//! * `solve.rs`: the step's LCP in factored form and the solve's paths;
//! * `candidates.rs`: the bases next to the warm one, tried after it declined;
//! * `report.rs`: [`SystemStepReport`];
//! * `tests.rs`: the constructor's refusals.
//!
//! The rule's enumeration and decision is `resolve.rs`, beside this module.

mod candidates;
mod report;
mod solve;
mod step;
#[cfg(test)]
#[allow(clippy::expect_used)] // a test's setup may fail loudly
mod tests;

pub use report::SystemStepReport;

use super::factored::Factored;
#[cfg(feature = "fallback")]
use super::factored::MOST_SLOTS;
use super::geometry::{CornerFrame, Pair, Shape, Table, pair_frames, poses, rim_frames};
use super::resolve::SystemDetector;
use crate::RunStats;
use crate::lcp::{Basis, Lemke};
use crate::params::{Check, ParamError, check_fields};
use crate::planar::check_friction;
use crate::planar::{Body, BodyState, ContactMode};
use crate::real::Real;
use crate::slot::Pattern;

/// The scalars of a step: one body's ([`crate::planar::Settings`]: time step, gravity, stick
/// threshold) and the activity rule's margin.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SystemSettings<T> {
    /// Time step `h` (s), gravity `g` (m/s^2, along world `-y`), and the slip (m/s) at or below
    /// which a contact sticks.
    pub base: crate::planar::Settings<T>,
    /// The activity rule's `margin` (m): a corner further than this (plus what the approach speed
    /// closes within the step) from a face is not a contact.
    pub margin: T,
}

/// The bodies, the table, the `P` resting pairs and the external forces of a system of `B` bodies
/// (boxes, or discs resting by their rims).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct System<T, const B: usize, const P: usize> {
    /// The bodies, in body order (body 0's mass is the reference mass of the LCP).
    pub bodies: [Body<T>; B],
    /// The fixed table.
    pub table: Table<T>,
    /// Which body rests on which, each with its friction coefficients.
    pub pairs: [Pair<T>; P],
    /// The external force on each body at its centre of mass (N, world), besides its weight.
    pub forces: [[T; 2]; B],
    /// The step's scalars.
    pub settings: SystemSettings<T>,
}

impl<T, const B: usize, const P: usize> System<T, B, P> {
    /// Each body's shape: a disc when a pair says its upper body is one
    /// ([`Pair::upper_shape`]), else a box ([`SystemStepper::new`] refuses pairs that disagree).
    #[must_use]
    pub fn shapes(&self) -> [Shape; B] {
        let mut shapes = [Shape::Box; B];
        for pair in &self.pairs {
            if let (Shape::Disc, Some(shape)) = (pair.upper_shape, shapes.get_mut(usize::from(pair.upper))) {
                *shape = Shape::Disc;
            }
        }
        shapes
    }
}

/// Steps a [`System`] of `B` bodies and `P` pairs (`4 P` candidate contacts) with an LCP of
/// capacity `N` rows (at most `N / 4` active contacts; `N <= 32`, Lemke's limit).
///
/// **Layout.** The `k` active candidates fill the leading `4 k` rows in candidate order, as
/// `docs/formulation.md` ("One step") writes the LCP: `(p_n[1..k], p_+d[1], p_-d[1], ...,
/// sigma[1..k])`; rows `4 k .. N` are trivially decoupled (the identity, `q = 1`: their `z` is 0
/// and no pivot touches them). So a step's LCP is the model's, whatever `N`.
///
/// **Indeterminacy.** Two sticking corners of one box on another leave the split of the load
/// between them undetermined: the impulse block `J M~ J^T` is singular and the LCP has a set of
/// solutions. A singular basis (both corners sticking) is declined by the factored solve; the
/// regular one in which one corner carries the interface's friction and the other only its
/// normal is what the first step's guess, the candidates and Lemke's method (with its
/// lexicographic rule, `core/src/lcp/tableau.rs`) leave, and the warm path keeps it (it is the
/// next step's warm basis). What is reported is the load of least 2-norm with the step's motion
/// (`docs/formulation.md`, "The load: the least norm"; each corner's share in
/// [`SystemStepReport::corner_loads`], their sum per pair in [`SystemStepReport::interface_forces`]). Where
/// solutions move the bodies differently (the model's "ambiguous" steps), this stepper takes the
/// reference's rule, the least kinetic energy after the step (`docs/formulation.md`, "Several
/// bodies: the rule"; `resolve.rs`).
#[derive(Debug, Clone)]
pub struct SystemStepper<T: Real, const B: usize, const P: usize, const N: usize> {
    system: System<T, B, P>,
    /// `m_ref diag(M^-1)` per body (`m_ref` body 0's mass).
    inverse_mass: [[T; 3]; B],
    states: [BodyState<T>; B],
    /// Kahan carries of each body's `x`, `y`, `theta`.
    carry: [[T; 3]; B],
    frames: [[CornerFrame<T>; 4]; P],
    modes: [[ContactMode; 4]; P],
    patterns: [[Pattern; 4]; P],
    /// `64 eps g h m_min / m_ref`: a normal impulse per unit reference mass at most this is none.
    impulse_floor: T,
    solver: Lemke<T, N>,
    /// The step's LCP in factored form, refilled each step ([`Self::refill`]).
    pub(super) lcp: StepLcp<T, B, N>,
    /// The rule's metric and reaches (`docs/formulation.md`, "One answer: the rule").
    detector: SystemDetector<T, B>,
    /// The basis of the last step whose load needed the least-norm LCP (`crate::load`; its rows
    /// in this stepper's LCP size, three per slot).
    #[cfg(feature = "fallback")]
    load_basis: Basis<N>,
    /// The last load the rule decided, for a rest state to keep.
    #[cfg(feature = "fallback")]
    load_memory: LoadMemory<T>,
    /// The last step's load was open: the next step takes the copy that decides it
    /// ([`Self::step_loading`]; the first step does).
    #[cfg(feature = "fallback")]
    load_next: bool,
    stats: RunStats,
}

impl<T: Real, const B: usize, const P: usize, const N: usize> SystemStepper<T, B, P, N> {
    /// `P <= 32`: the pairs' bit sets are `u32` (`Factored::held_and_pinned`), and a pair's
    /// index narrows to the `u8` a slot keeps exactly.
    const SIZE_CHECK: () = assert!(
        B > 0 && B < 255 && P > 0 && P <= 32 && N >= 4 && N <= 32,
        "SystemStepper needs 0 < B < 255, 0 < P <= 32, 4 <= N <= 32"
    );

    /// A stepper at `states` (every body at rest: the modes before the first step are sticking
    /// for an active touching candidate, separated otherwise).
    ///
    /// # Errors
    /// The first of, in this order:
    /// * a body's `width`, `height`, `mass` or `inertia` not finite ([`ParamError::NonFinite`]) or
    ///   not positive ([`ParamError::NotPositive`]), or its `mass / inertia` not finite
    ///   ([`ParamError::InertiaOutOfRange`]);
    /// * the settings' `step` not finite or not positive, `gravity`, `stick_speed` or `margin`
    ///   not finite or negative ([`ParamError::Negative`]);
    /// * a pair's `mu_static` or `mu_kinetic` not finite or negative, or
    ///   [`ParamError::KineticAboveStatic`];
    /// * [`ParamError::OutOfRange`]`("upper_shape")` for a disc whose width and height differ or a
    ///   body the pairs give two shapes, [`ParamError::OutOfRange`]`("pairs")` for a pair naming a
    ///   body that does not exist, resting on itself or on a disc;
    /// * [`ParamError::NonFinite`]`("table")` for a table end that is not finite,
    ///   [`ParamError::OutOfRange`]`("table")` for `lo > hi`;
    /// * [`ParamError::NonFinite`]`("forces")` for an external force that is not finite;
    /// * [`ParamError::NonFiniteState`] for a non-finite state;
    /// * [`ParamError::OutOfRange`]`("mass")` for a body whose mass or inertia per body 0's mass
    ///   (the LCP's unit) is not a positive finite number in `T`.
    pub fn new(system: System<T, B, P>, states: [BodyState<T>; B]) -> Result<Self, ParamError> {
        let () = Self::SIZE_CHECK;
        validate(&system, &states)?;
        let shapes = system.shapes();
        let m_ref = system.bodies[0].mass;
        let mut m_min = m_ref;
        let mut inverse_mass = [[T::zero(); 3]; B];
        for (i, body) in system.bodies.iter().enumerate() {
            inverse_mass[i] = [m_ref / body.mass, m_ref / body.mass, m_ref / body.inertia];
            if body.mass < m_min {
                m_min = body.mass;
            }
        }
        // Each body's `M~` (per body 0's mass) in `T`'s range: a mass ratio whose quotient
        // overflows or underflows is refused here rather than stepped.
        if !inverse_mass.iter().flatten().all(|&m| m.finite() && m > T::zero()) {
            return Err(ParamError::OutOfRange("mass"));
        }
        let s = system.settings.base;
        let mut stepper = Self {
            system,
            inverse_mass,
            states,
            carry: [[T::zero(); 3]; B],
            frames: [[CornerFrame::inactive(); 4]; P],
            modes: [[ContactMode::Separated; 4]; P],
            patterns: [[Pattern::OFF; 4]; P],
            impulse_floor: T::of(64.0) * T::EPS * s.gravity * s.step * m_min / m_ref,
            solver: Lemke::new(),
            lcp: StepLcp {
                factored: Factored::new(),
                slots: [(0, 0); N],
                k: 0,
                active: 0,
                warm: Basis::all_w(),
            },
            detector: SystemDetector::new(&system.bodies, &shapes, &inverse_mass),
            #[cfg(feature = "fallback")]
            load_basis: Basis::all_w(),
            #[cfg(feature = "fallback")]
            load_memory: LoadMemory::none(),
            #[cfg(feature = "fallback")]
            load_next: true,
            stats: RunStats::default(),
        };
        stepper.update_frames();
        for p in 0..P {
            let mut sticking = false;
            for c in 0..4 {
                let f = &stepper.frames[p][c];
                if f.active && f.gap <= f.touch {
                    stepper.modes[p][c] = ContactMode::Sticking;
                    // The warm start's guess: the pair's first touching corner sticks (`p_n`,
                    // `p_+d`), the others touch (`p_n`): both sticking is singular.
                    stepper.patterns[p][c] = if sticking { Pattern::TOUCH } else { Pattern::STICK_PLUS };
                    sticking = true;
                }
            }
        }
        Ok(stepper)
    }

    /// The system stepped.
    #[must_use]
    pub const fn system(&self) -> &System<T, B, P> {
        &self.system
    }

    /// Each body's state now.
    #[must_use]
    pub const fn states(&self) -> &[BodyState<T>; B] {
        &self.states
    }

    /// Each candidate's geometry now (the next step's frames): an active candidate's frame; an
    /// inactive one's `active` is `false` and its other fields are from an earlier step.
    #[must_use]
    pub const fn frames(&self) -> &[[CornerFrame<T>; 4]; P] {
        &self.frames
    }

    /// Each candidate's mode after the last step (before the first: from the start).
    #[must_use]
    pub const fn modes(&self) -> &[[ContactMode; 4]; P] {
        &self.modes
    }

    /// The run's counters.
    #[must_use]
    pub const fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// Time now, `n h` after `n` steps (s).
    #[must_use]
    pub fn time(&self) -> T {
        T::of_count(u32::try_from(self.stats.steps).unwrap_or(u32::MAX)) * self.system.settings.base.step
    }

    fn update_frames(&mut self) {
        let s = self.system.settings;
        let poses = poses(&self.system.bodies, &self.states);
        for p in 0..P {
            let (pair, frames) = (&self.system.pairs[p], &mut self.frames[p]);
            let (states, table) = (&self.states, &self.system.table);
            if pair.upper_shape == Shape::Disc {
                rim_frames(pair, states, &poses, table, s.margin, s.base.step, frames);
            } else {
                pair_frames(pair, states, &poses, table, s.margin, s.base.step, frames);
            }
        }
    }
}

/// The set-up checks of [`SystemStepper::new`] (its `# Errors`, in that order) but the mass ratios:
/// each body as [`crate::planar::Stepper`]'s body is checked, and its height positive too (a box
/// or a disc); the settings as its settings, and the margin; each pair's friction as a contact's;
/// the pairs' bodies and shapes; the table's ends; the forces; the states.
fn validate<T: Real, const B: usize, const P: usize>(
    system: &System<T, B, P>,
    states: &[BodyState<T>; B],
) -> Result<(), ParamError> {
    for body in &system.bodies {
        check_fields(&body.fields())?;
        check_fields(&[("height", body.height, Check::Positive)])?;
        body.check_inertia("mass", "width")?;
    }
    let [step, gravity, stick_speed] = system.settings.base.fields();
    check_fields(&[step, gravity, stick_speed, ("margin", system.settings.margin, Check::NonNegative)])?;
    for pair in &system.pairs {
        check_friction(pair.mu_static, pair.mu_kinetic)?;
    }
    let shapes = system.shapes();
    for (body, shape) in system.bodies.iter().zip(&shapes) {
        if *shape == Shape::Disc && body.width != body.height {
            return Err(ParamError::OutOfRange("upper_shape"));
        }
    }
    for pair in &system.pairs {
        let bad_lower = match pair.lower {
            // A body that does not exist has no shape: refused as a disc is.
            super::RestsOn::Body(s) => s == pair.upper || shapes.get(usize::from(s)) != Some(&Shape::Box),
            super::RestsOn::Table => false,
        };
        if shapes.get(usize::from(pair.upper)).is_some_and(|shape| *shape != pair.upper_shape) {
            return Err(ParamError::OutOfRange("upper_shape"));
        }
        if usize::from(pair.upper) >= B || bad_lower {
            return Err(ParamError::OutOfRange("pairs"));
        }
    }
    let Table { lo, hi } = system.table;
    if !lo.into_iter().chain(hi).all(Real::finite) {
        return Err(ParamError::NonFinite("table"));
    }
    if let (Some(lo), Some(hi)) = (lo, hi)
        && lo > hi
    {
        return Err(ParamError::OutOfRange("table"));
    }
    if !system.forces.iter().flatten().all(|f| f.finite()) {
        return Err(ParamError::NonFinite("forces"));
    }
    if !states.iter().all(BodyState::is_finite) {
        return Err(ParamError::NonFiniteState);
    }
    Ok(())
}

/// The last load the rule decided ([`SystemStepper::decide_load`]): its slots and their modes before
/// the step, the path's load, the decided one and the modes it gave.
#[cfg(feature = "fallback")]
#[derive(Debug, Clone, Copy)]
struct LoadMemory<T> {
    slots: [(usize, usize); MOST_SLOTS],
    count: usize,
    before: [ContactMode; MOST_SLOTS],
    path: [[T; 2]; MOST_SLOTS],
    load: [[T; 2]; MOST_SLOTS],
    after: [ContactMode; MOST_SLOTS],
}

#[cfg(feature = "fallback")]
impl<T: Real> LoadMemory<T> {
    /// No load decided yet: matches no step.
    fn none() -> Self {
        Self {
            slots: [(usize::MAX, usize::MAX); MOST_SLOTS],
            count: usize::MAX,
            before: [ContactMode::Separated; MOST_SLOTS],
            path: [[T::zero(); 2]; MOST_SLOTS],
            load: [[T::zero(); 2]; MOST_SLOTS],
            after: [ContactMode::Separated; MOST_SLOTS],
        }
    }
}

/// One step's LCP in factored form with its slots and warm basis ([`SystemStepper::refill`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct StepLcp<T, const B: usize, const N: usize> {
    /// The factored rows.
    pub(super) factored: Factored<T, B, N>,
    /// The active candidates `(pair, candidate)` in slot order.
    pub(super) slots: [(usize, usize); N],
    /// How many slots.
    pub(super) k: usize,
    /// Active candidates (`k`, as a count).
    pub(super) active: u8,
    /// The last step's patterns as a basis.
    pub(super) warm: Basis<N>,
}
