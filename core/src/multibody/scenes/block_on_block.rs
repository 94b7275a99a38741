//! [`BlockOnBlock`]: a block on a block pulled along a floor (`docs/scenes.md`, "block-on-block").

use super::{FullContact, Outcome, Run, settings_of};
use crate::multibody::{Pair, RestsOn, System, SystemStepReport, Table};
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{Body, BodyState};
use crate::real::Real;

params! {
    /// Block-on-block's parameters (`docs/scenes.md`, "block-on-block"); `top_*` the top block
    /// (`m`, `w`, `h` there), `bottom_*` the bottom one (`M`, `w2`, `h2`).
    pub struct BlockOnBlockParams {
        /// `m` (kg).
        top_mass: 1.0, Positive;
        /// `w` (m).
        top_width: 0.1, Positive;
        /// `h` (m).
        top_height: 0.1, Positive;
        /// `M` (kg).
        bottom_mass: 2.0, Positive;
        /// `w2` (m).
        bottom_width: 0.4, Positive;
        /// `h2` (m).
        bottom_height: 0.1, Positive;
        /// The pull `F` on the bottom block along `+x` (N).
        force: 30.0, NonNegative;
        /// Static friction between the blocks.
        mu_static: 0.5, NonNegative;
        /// Kinetic friction between the blocks.
        mu_kinetic: 0.4, NonNegative;
        /// Friction between the bottom block and the floor (static and kinetic).
        mu_floor: 0.2, NonNegative;
        /// `g` (m/s^2).
        gravity: 9.81, NonNegative;
        /// The time step (s).
        step: 0.001, Positive;
        /// Stick threshold (m/s).
        stick_speed: 1e-5, NonNegative;
        /// The top block tips beyond this `|theta|` (rad).
        tilt_limit: 0.2, Positive;
        /// The activity rule's margin (m).
        contact_margin: 1e-3, NonNegative;
        /// Duration (s).
        max_time: 0.3, Positive;
    }
}

impl<T: Real> BlockOnBlockParams<T> {
    /// The validity rules of `docs/scenes.md`, "block-on-block".
    ///
    /// # Errors
    /// The first broken rule, naming its field.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if self.top_width > self.bottom_width {
            return Err(ParamError::OutOfRange("top_width"));
        }
        check_step_within(self.step, self.max_time)?;
        self.top().check_inertia("top_mass", "top_width")?;
        self.bottom().check_inertia("bottom_mass", "bottom_width")
    }

    fn top(&self) -> Body<T> {
        Body::block(self.top_mass, self.top_width, self.top_height)
    }

    fn bottom(&self) -> Body<T> {
        Body::block(self.bottom_mass, self.bottom_width, self.bottom_height)
    }
}

/// The LCP rows of block-on-block: room for 6 active contacts of its 8 candidates (4 in full
/// contact).
pub const BLOCK_ON_BLOCK_ROWS: usize = 24;

/// Block-on-block: body 0 the bottom block, body 1 the top one; pair 0 (bottom, floor), pair 1
/// (top, bottom).
#[derive(Debug, Clone)]
pub struct BlockOnBlock<T: Real> {
    pub(super) run: Run<T, BlockOnBlockParams<T>, 2, 2, BLOCK_ON_BLOCK_ROWS>,
    /// Pair 0 / pair 1 slid after some step.
    slid: [bool; 2],
    full_contact: FullContact<T>,
}

impl<T: Real> BlockOnBlock<T> {
    /// Validates `params` and sets the blocks at rest.
    ///
    /// # Errors
    /// As [`BlockOnBlockParams::validate`].
    pub fn new(params: BlockOnBlockParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let p = params;
        let half = T::of(0.5);
        let system = System {
            bodies: [p.bottom(), p.top()],
            table: Table::floor(),
            pairs: [
                Pair::boxed(0, RestsOn::Table, p.mu_floor, p.mu_floor),
                Pair::boxed(1, RestsOn::Body(0), p.mu_static, p.mu_kinetic),
            ],
            forces: [[p.force, T::zero()], [T::zero(); 2]],
            settings: settings_of!(p),
        };
        let states = [
            BodyState::at_rest(T::zero(), half * p.bottom_height, T::zero()),
            BodyState::at_rest(T::zero(), p.bottom_height + half * p.top_height, T::zero()),
        ];
        Ok(Self {
            run: Run::new(params, system, states)?,
            slid: [false; 2],
            full_contact: FullContact::new(),
        })
    }

    /// Advances one step; `None` once the run has an outcome.
    pub fn step(&mut self) -> Option<SystemStepReport<T, 2, 2>> {
        let report = self.run.advance()?;
        for p in 0..2 {
            self.slid[p] |= report.pair_slid(p);
        }
        let [bottom, top] = report.states;
        let touching = report.touching(&[(0, 0), (0, 1), (1, 0), (1, 1)]);
        self.full_contact.record(touching, report.time, [bottom.vx, top.vx]);
        let p = &self.run.params;
        if top.theta.abs_exact() > p.tilt_limit {
            self.run.outcome = Some(Outcome::Tipped);
        } else if (top.x - bottom.x).abs_exact() > p.bottom_width / T::of(2.0) {
            self.run.outcome = Some(Outcome::Slid);
        } else if report.time >= p.max_time {
            self.run.outcome = Some(match self.slid {
                [_, true] => Outcome::Slid,
                [true, false] => Outcome::Rode,
                [false, false] => Outcome::Held,
            });
        }
        Some(report)
    }

    /// `[a_bottom, a_top]` (m/s^2): the blocks' accelerations along `x` while both are in full
    /// contact; `None` before two such steps.
    #[must_use]
    pub fn accelerations(&self) -> Option<[T; 2]> {
        self.full_contact.accelerations()
    }
}
