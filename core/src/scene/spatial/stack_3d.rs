//! [`Stack3d`]: the planar stack in three dimensions, its overhang at a heading to the table's
//! edge (`docs/scenes.md`, "stack-3d"), stepped by [`BlockStack`].

use crate::RunStats;
use crate::params::{ParamError, check_step_within, params};
use crate::real::{Real, max};
use crate::scene::{BodyShape, Outcome};
use crate::spatial::{
    BlockStack, Body, Quaternion, SpatialSettings, StackStepReport, State, Vector, about, norm, rotate,
};

params! {
    /// The stack's parameters (`docs/scenes.md`, "stack-3d"): the planar stack's
    /// ([`crate::multibody::scenes::StackParams`], the same names and defaults), the blocks' width
    /// and the heading; the number of blocks is the type's `B`.
    pub struct Stack3dParams {
        /// `L` (m).
        length: 0.2, Positive;
        /// `W` (m).
        width: 0.1, Positive;
        /// `hb` (m).
        height: 0.05, Positive;
        /// `m` (kg), each block.
        mass: 1.0, Positive;
        /// Every contact's static friction coefficient.
        mu_static: 0.5, NonNegative;
        /// Every contact's kinetic friction coefficient (at most `mu_static`).
        mu_kinetic: 0.5, NonNegative;
        /// `s`: the harmonic overhangs' scale (1 the critical stack).
        overhang: 0.98, NonNegative;
        /// The overhang's heading from the table edge's normal `+x` toward `+y`, rad (`|psi| <=
        /// 60 deg`; the command line's `--heading` in degrees).
        heading: 0.0, Finite;
        /// `g` (m/s^2).
        gravity: 9.81, NonNegative;
        /// The time step (s).
        step: 0.001, Positive;
        /// Stick threshold (m/s).
        stick_speed: 1e-5, Positive;
        /// A block whose top normal turned more than this from `z` (rad) fell.
        tilt_limit: 0.1, Positive;
        /// A block whose centre dropped more than this below its start (m) fell.
        drop_limit: 0.01, Positive;
        /// The activity rule's margin (m).
        contact_margin: 1e-3, Positive;
        /// Duration (s).
        max_time: 10.0, Positive;
    }
}

impl<T: Real> Stack3dParams<T> {
    /// The validity rules of `docs/scenes.md`, "stack-3d", for `blocks` blocks (2 or 3).
    ///
    /// # Errors
    /// The first broken rule, naming its field.
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
        if self.heading.abs_exact() > T::of(60.0_f64.to_radians()) {
            return Err(ParamError::OutOfRange("heading"));
        }
        check_step_within(self.step, self.max_time)?;
        Body::cuboid(self.mass, self.length, self.width, self.height).validate()
    }

    /// Each block's start (block 0 the bottom), at rest, turned by the heading about `z`: block
    /// `i = B - k` (the `k`-th from the top) centred at `(R_k - L/2) d + (i + 1/2) hb z`, `R_k = s
    /// (L/2) (1/k + ... + 1/B)`, `d = (cos psi, sin psi, 0)`.
    fn start<const B: usize>(&self) -> [State<T>; B] {
        let half = T::of(0.5);
        let (sin, cos) = self.heading.sin_cos_portable();
        let orientation: Quaternion<T> = about(&[T::zero(), T::zero(), T::one()], self.heading);
        let mut states = [State {
            position: [T::zero(); 3],
            orientation,
            velocity: [T::zero(); 3],
            angular_velocity: [T::zero(); 3],
        }; B];
        let mut right = T::zero();
        let mut k = u32::try_from(B).unwrap_or(u32::MAX);
        for (i, state) in (0u32..).zip(states.iter_mut()) {
            right += self.overhang * half * self.length / T::of_count(k);
            let along = right - half * self.length;
            let up = (T::of_count(i) + half) * self.height;
            state.position = [along * cos, along * sin, up];
            k = k.saturating_sub(1).max(1);
        }
        states
    }
}

/// `B` blocks over the table's edge in three dimensions, `K` contact slots, an LCP of `N` rows
/// in `W` words ([`Stack3d2`], [`Stack3d3`]).
#[derive(Debug, Clone)]
pub struct Stack3d<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> {
    params: Stack3dParams<T>,
    stepper: BlockStack<T, B, K, N, W>,
    start_z: [T; B],
    outcome: Option<Outcome>,
    stats: RunStats,
    /// The largest `|v| + reach |omega|` so far, m/s.
    max_speed: T,
    /// Half a block's diagonal, m: the farthest a block's point is from its centre.
    reach: T,
}

/// Two blocks: the table's overlap (at most five points) and one pair's (four, eight at most).
pub type Stack3d2<T> = Stack3d<T, 2, 13, 52, 2>;
/// Three blocks: 16 slots, the 64 rows Lemke's method holds.
pub type Stack3d3<T> = Stack3d<T, 3, 16, 64, 2>;

impl<T: Real, const B: usize, const K: usize, const N: usize, const W: usize> Stack3d<T, B, K, N, W> {
    /// Validates `params` and stacks the blocks at rest.
    ///
    /// # Errors
    /// As [`Stack3dParams::validate`] and [`BlockStack::new`].
    pub fn new(params: Stack3dParams<T>) -> Result<Self, ParamError> {
        params.validate(B)?;
        let p = params;
        let half = T::of(0.5);
        let settings = SpatialSettings {
            step: p.step,
            gravity: [T::zero(), T::zero(), -p.gravity],
            stick_speed: p.stick_speed,
            margin: p.contact_margin,
            ..SpatialSettings::default()
        };
        let states = p.start::<B>();
        let stepper = BlockStack::new(
            Body::cuboid(p.mass, p.length, p.width, p.height),
            [half * p.length, half * p.width, half * p.height],
            [p.mu_static, p.mu_kinetic],
            settings,
            states,
        )?;
        let reach = half * (p.length * p.length + p.width * p.width + p.height * p.height).sqrt_rounded();
        let start_z = states.map(|s| s.position[2]);
        Ok(Self {
            params,
            stepper,
            start_z,
            outcome: None,
            stats: RunStats::default(),
            max_speed: T::zero(),
            reach,
        })
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &Stack3dParams<T> {
        &self.params
    }

    /// The stepper.
    #[must_use]
    pub const fn stepper(&self) -> &BlockStack<T, B, K, N, W> {
        &self.stepper
    }

    /// The outcome, once the run has ended.
    #[must_use]
    pub const fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }

    /// Takes the outcome so that the run goes on ([`crate::scene::SceneView::go_on`]); `None`
    /// before it.
    pub const fn go_on(&mut self) -> Option<Outcome> {
        self.outcome.take()
    }

    /// The run's counters: steps, pivots, the steps the warm basis answered without a pivot.
    #[must_use]
    pub const fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// `max_speed` (`docs/scenes.md`, "stack-3d", "Measured"): the largest `|v| + reach |omega|`
    /// over the steps so far and the blocks, `reach` half a block's diagonal (m/s).
    #[must_use]
    pub const fn max_speed(&self) -> T {
        self.max_speed
    }

    /// A block's outline.
    #[must_use]
    pub const fn shape(&self) -> BodyShape<T> {
        let p = &self.params;
        BodyShape::Cuboid { length: p.length, width: p.width, height: p.height }
    }

    /// Advances one step and judges it (`docs/scenes.md`, "stack-3d", "Outcome"): **Fell** when a
    /// block's top normal turned more than `tilt_limit` from `z` or its centre dropped more than
    /// `drop_limit` below its start, **Held** at `max_time`, **Failed** on a step's error. `None`
    /// once the run has an outcome.
    pub fn step(&mut self) -> Option<StackStepReport<T, B, K>> {
        if self.outcome.is_some() {
            return None;
        }
        let report = match self.stepper.step() {
            Ok(report) => report,
            Err(e) => {
                self.outcome = Some(Outcome::Failed(e));
                return None;
            }
        };
        self.stats.steps += 1;
        self.stats.count_pivots(report.pivots);
        self.stats.warm_starts += u64::from(report.pivots == 0);
        let p = &self.params;
        for st in &report.states {
            let speed = norm(&st.velocity) + self.reach * norm(&st.angular_velocity);
            self.max_speed = max(self.max_speed, speed);
        }
        let cos_limit = p.tilt_limit.sin_cos_portable().1;
        let fell = report.states.iter().zip(&self.start_z).any(|(st, z0)| {
            let up: Vector<T> = rotate(&st.orientation, &[T::zero(), T::zero(), T::one()]);
            up[2] < cos_limit || *z0 - st.position[2] > p.drop_limit
        });
        if fell {
            self.outcome = Some(Outcome::Fell);
        } else if report.time >= p.max_time {
            self.outcome = Some(Outcome::Held);
        }
        Some(report)
    }
}
