//! [`Stack`]: `B` blocks stacked over a table's edge with harmonic overhangs (`docs/scenes.md`,
//! "stack").

use super::{Outcome, Run, point_speed_bound, settings_of};
use crate::multibody::{Pair, RestsOn, System, SystemStepReport, Table};
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{Body, BodyState};
use crate::real::Real;

params! {
    /// The stack's parameters (`docs/scenes.md`, "stack"); the number of blocks is the type's `B`.
    pub struct StackParams {
        /// `L` (m).
        length: 0.2, Positive;
        /// `hb` (m).
        height: 0.05, Positive;
        /// `m` (kg), each block.
        mass: 1.0, Positive;
        /// Every contact's static friction coefficient.
        mu_static: 0.5, NonNegative;
        /// Every contact's kinetic friction coefficient (at most `mu_static`; the default equals
        /// its default).
        mu_kinetic: 0.5, NonNegative;
        /// `s`: the harmonic overhangs' scale (1 the critical stack).
        overhang: 0.98, NonNegative;
        /// `g` (m/s^2).
        gravity: 9.81, NonNegative;
        /// The time step (s).
        step: 0.001, Positive;
        /// Stick threshold (m/s).
        stick_speed: 1e-5, NonNegative;
        /// A block beyond this `|theta|` (rad) fell.
        tilt_limit: 0.1, Positive;
        /// A block whose centre dropped more than this below its start (m) fell.
        drop_limit: 0.01, Positive;
        /// The activity rule's margin (m).
        contact_margin: 1e-3, NonNegative;
        /// Duration (s).
        max_time: 10.0, Positive;
    }
}

impl<T: Real> StackParams<T> {
    /// The validity rules of `docs/scenes.md`, "stack", for `blocks` blocks (2 or 3: the stacks
    /// built, [`Stack2`] and [`Stack3`]).
    ///
    /// # Errors
    /// The first broken rule, naming its field: [`ParamError::OutOfRange`]`("blocks")` for other
    /// than 2 or 3 blocks.
    pub fn validate(&self, blocks: usize) -> Result<(), ParamError> {
        self.check_fields()?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        let Some(blocks) = u32::try_from(blocks).ok().filter(|b| (2..=3).contains(b)) else {
            return Err(ParamError::OutOfRange("blocks"));
        };
        if self.overhang >= T::of(2.0) * T::of_count(blocks) {
            return Err(ParamError::OutOfRange("overhang"));
        }
        check_step_within(self.step, self.max_time)?;
        Body::block(self.mass, self.length, self.height).check_inertia("mass", "length")
    }

    /// Each body's start (body 0 at the bottom): `R_k = s (L/2) (1/k + ... + 1/B)` for the `k`-th
    /// from the top, centre `(R_k - L/2, (i + 1/2) hb)` for body `i = B - k`; `blocks` is `B`.
    fn start<const B: usize>(&self, blocks: u8) -> [BodyState<T>; B] {
        let half = T::of(0.5);
        let mut states = [BodyState::at_rest(T::zero(), T::zero(), T::zero()); B];
        // Body i is the k-th from the top, k = B - i: upward from the bottom, R_k adds s L / (2k).
        let mut right = T::zero();
        for (i, state) in (0..blocks).zip(states.iter_mut()) {
            right += self.overhang * half * self.length / T::of_count(u32::from(blocks - i));
            *state = BodyState::at_rest(
                right - half * self.length,
                (T::of_count(u32::from(i)) + half) * self.height,
                T::zero(),
            );
        }
        states
    }
}

/// `B` blocks over a table's edge (the table's top face `x <= 0`): body 0 the bottom block, body
/// `i` on body `i - 1`; pair 0 (block 0, table: its corner `(0, 0)`), pair `i` (block `i`, block
/// `i - 1`). `N` is the LCP's capacity ([`Stack2`], [`Stack3`]).
#[derive(Debug, Clone)]
pub struct Stack<T: Real, const B: usize, const N: usize> {
    pub(super) run: Run<T, StackParams<T>, B, B, N>,
    start_y: [T; B],
    reach: T,
    max_speed: T,
}

/// Two blocks: room for 6 active contacts (4 when held).
pub type Stack2<T> = Stack<T, 2, 24>;
/// Three blocks: room for 8 active contacts (6 when held).
pub type Stack3<T> = Stack<T, 3, 32>;

impl<T: Real, const B: usize, const N: usize> Stack<T, B, N> {
    /// Validates `params` and stacks the blocks at rest.
    ///
    /// # Errors
    /// As [`StackParams::validate`].
    pub fn new(params: StackParams<T>) -> Result<Self, ParamError> {
        params.validate(B)?;
        // 2 or 3 (validated).
        let blocks = u8::try_from(B).map_err(|_| ParamError::OutOfRange("blocks"))?;
        let p = params;
        let block = Body::block(p.mass, p.length, p.height);
        let (mu_static, mu_kinetic) = (p.mu_static, p.mu_kinetic);
        let mut pairs = [Pair::boxed(0, RestsOn::Table, mu_static, mu_kinetic); B];
        for (upper, pair) in (1..blocks).zip(pairs.iter_mut().skip(1)) {
            *pair = Pair::boxed(upper, RestsOn::Body(upper - 1), mu_static, mu_kinetic);
        }
        let system = System {
            bodies: [block; B],
            table: Table { lo: None, hi: Some(T::zero()) },
            pairs,
            forces: [[T::zero(); 2]; B],
            settings: settings_of!(p),
        };
        let states = p.start::<B>(blocks);
        let mut start_y = [T::zero(); B];
        for i in 0..B {
            start_y[i] = states[i].y;
        }
        Ok(Self {
            run: Run::new(params, system, states)?,
            start_y,
            reach: T::of(0.5) * (p.length * p.length + p.height * p.height).sqrt_rounded(),
            max_speed: T::zero(),
        })
    }

    /// Advances one step; `None` once the run has an outcome.
    pub fn step(&mut self) -> Option<SystemStepReport<T, B, B>> {
        let report = self.run.advance()?;
        let p = &self.run.params;
        let mut fell = false;
        for (i, st) in report.states.iter().enumerate() {
            let speed = point_speed_bound(st, self.reach);
            if speed > self.max_speed {
                self.max_speed = speed;
            }
            fell |= st.theta.abs_exact() > p.tilt_limit || self.start_y[i] - st.y > p.drop_limit;
        }
        if fell {
            self.run.outcome = Some(Outcome::Fell);
        } else if report.time >= p.max_time {
            self.run.outcome = Some(Outcome::Held);
        }
        Some(report)
    }

    /// `max_speed`: the largest `|(vx, vy)| + reach |omega|` over the steps so far and the blocks
    /// (m/s).
    #[must_use]
    pub const fn max_speed(&self) -> T {
        self.max_speed
    }
}

#[cfg(test)]
#[allow(clippy::expect_used)] // a test's setup may fail loudly
mod tests {
    use super::*;

    /// Only the stacks built (2 and 3 blocks) pass; any other count is refused by name.
    #[test]
    fn the_stack_takes_two_or_three_blocks() {
        let p = StackParams::<f64>::default();
        for (blocks, expected) in [
            (0, Err(ParamError::OutOfRange("blocks"))),
            (1, Err(ParamError::OutOfRange("blocks"))),
            (2, Ok(())),
            (3, Ok(())),
            (4, Err(ParamError::OutOfRange("blocks"))),
            (usize::MAX, Err(ParamError::OutOfRange("blocks"))),
            // 2^32 + 2 is not 2.
            (
                usize::try_from(u64::from(u32::MAX) + 3).unwrap_or(usize::MAX),
                Err(ParamError::OutOfRange("blocks")),
            ),
        ] {
            assert_eq!(p.validate(blocks), expected, "{blocks}");
        }
        assert_eq!(Stack::<f64, 4, 32>::new(p).err(), Some(ParamError::OutOfRange("blocks")));
        assert_eq!(Stack::<f64, 1, 8>::new(p).err(), Some(ParamError::OutOfRange("blocks")));
        assert!(Stack2::<f64>::new(p).is_ok() && Stack3::<f64>::new(p).is_ok());
    }

    /// The pairs stack each block on the one below, block 0 on the table.
    #[test]
    fn each_block_rests_on_the_one_below() {
        let stack = Stack3::<f64>::new(StackParams::default()).expect("valid");
        let pairs = stack.stepper().system().pairs;
        assert_eq!(
            pairs.map(|p| (p.upper, p.lower)),
            [(0, RestsOn::Table), (1, RestsOn::Body(0)), (2, RestsOn::Body(1)),]
        );
    }
}
