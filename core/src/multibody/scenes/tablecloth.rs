//! [`Tablecloth`]: a board pulled from under a block (`docs/scenes.md`, "tablecloth").

use super::{FullContact, Outcome, Run, settings_of};
use crate::multibody::{Pair, RestsOn, System, SystemStepReport, Table};
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{Body, BodyState};
use crate::real::Real;

params! {
    /// The tablecloth's parameters (`docs/scenes.md`, "tablecloth").
    pub struct TableclothParams {
        /// `m_b` (kg).
        board_mass: 0.2, Positive;
        /// `L_b` (m).
        board_length: 1.0, Positive;
        /// `t_b` (m).
        board_thickness: 0.005, Positive;
        /// `m` (kg).
        block_mass: 0.5, Positive;
        /// `w` (m).
        block_width: 0.05, Positive;
        /// `h` (m).
        block_height: 0.05, Positive;
        /// The block's rear face from the board's trailing end (m).
        offset: 0.1, NonNegative;
        /// The pull `F` on the board along `+x` (N).
        force: 20.0, NonNegative;
        /// Static friction between block and board.
        mu_static: 0.5, NonNegative;
        /// Kinetic friction between block and board.
        mu_kinetic: 0.4, NonNegative;
        /// Friction on the table (board and block; static and kinetic).
        mu_floor: 0.3, NonNegative;
        /// `g` (m/s^2).
        gravity: 9.81, NonNegative;
        /// The time step (s).
        step: 0.001, Positive;
        /// Stick threshold (m/s).
        stick_speed: 1e-5, NonNegative;
        /// The activity rule's margin (m).
        contact_margin: 1e-3, NonNegative;
        /// Duration (s).
        max_time: 1.0, Positive;
    }
}

impl<T: Real> TableclothParams<T> {
    /// The validity rules of `docs/scenes.md`, "tablecloth".
    ///
    /// # Errors
    /// The first broken rule, naming its field.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if self.offset + self.block_width > self.board_length {
            return Err(ParamError::OutOfRange("offset"));
        }
        if self.contact_margin >= self.board_thickness {
            return Err(ParamError::OutOfRange("contact_margin"));
        }
        check_step_within(self.step, self.max_time)?;
        self.board().check_inertia("board_mass", "board_length")?;
        self.block().check_inertia("block_mass", "block_width")
    }

    fn board(&self) -> Body<T> {
        Body::block(self.board_mass, self.board_length, self.board_thickness)
    }

    fn block(&self) -> Body<T> {
        Body::block(self.block_mass, self.block_width, self.block_height)
    }
}

/// The LCP rows of the tablecloth: room for 6 active contacts of its 12 candidates.
pub const TABLECLOTH_ROWS: usize = 24;

/// The tablecloth: body 0 the board, body 1 the block; pair 0 (board, table), pair 1 (block,
/// board), pair 2 (block, table).
#[derive(Debug, Clone)]
pub struct Tablecloth<T: Real> {
    pub(super) run: Run<T, TableclothParams<T>, 2, 3, TABLECLOTH_ROWS>,
    start_x: T,
    /// Pair `p` slid after some step.
    slid: [bool; 3],
    full_contact: FullContact<T>,
}

impl<T: Real> Tablecloth<T> {
    /// Validates `params` and sets the board and the block at rest.
    ///
    /// # Errors
    /// As [`TableclothParams::validate`].
    pub fn new(params: TableclothParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let p = params;
        let half = T::of(0.5);
        let floor = |upper| Pair::boxed(upper, RestsOn::Table, p.mu_floor, p.mu_floor);
        let system = System {
            bodies: [p.board(), p.block()],
            table: Table::floor(),
            pairs: [floor(0), Pair::boxed(1, RestsOn::Body(0), p.mu_static, p.mu_kinetic), floor(1)],
            forces: [[p.force, T::zero()], [T::zero(); 2]],
            settings: settings_of!(p),
        };
        let start_x = -half * p.board_length + p.offset + half * p.block_width;
        let states = [
            BodyState::at_rest(T::zero(), half * p.board_thickness, T::zero()),
            BodyState::at_rest(start_x, p.board_thickness + half * p.block_height, T::zero()),
        ];
        Ok(Self {
            run: Run::new(params, system, states)?,
            start_x,
            slid: [false; 3],
            full_contact: FullContact::new(),
        })
    }

    /// Advances one step; `None` once the run has an outcome.
    pub fn step(&mut self) -> Option<SystemStepReport<T, 2, 3>> {
        let report = self.run.advance()?;
        for p in 0..3 {
            self.slid[p] |= report.pair_slid(p);
        }
        let [board, block] = report.states;
        let touching = report.touching(&[(0, 0), (0, 1), (1, 0), (1, 1)]);
        self.full_contact.record(touching, report.time, [board.vx, block.vx]);
        let p = &self.run.params;
        let half = T::of(0.5);
        let (_, cos) = board.theta.sin_cos_portable();
        let behind = block.x < board.x - half * p.board_length * cos;
        let reach = half * (p.block_width * p.block_width + p.block_height * p.block_height).sqrt_rounded();
        let at_rest = block.vx.abs_exact() <= p.stick_speed
            && block.vy.abs_exact() <= p.stick_speed
            && reach * block.omega.abs_exact() <= p.stick_speed;
        if behind && at_rest {
            self.run.outcome = Some(Outcome::Stayed);
        } else if report.time >= p.max_time {
            self.run.outcome = Some(if !self.slid.iter().any(|&s| s) {
                Outcome::Held
            } else if !self.slid[1] {
                Outcome::Rode
            } else {
                Outcome::Unfinished
            });
        }
        Some(report)
    }

    /// `block_displacement_m`: the block's `x` now less its start (m).
    #[must_use]
    pub fn block_displacement(&self) -> T {
        self.run.stepper.states()[1].x - self.start_x
    }

    /// `[a_board, a_block]` (m/s^2) while both are in full contact; `None` before two such steps.
    #[must_use]
    pub fn accelerations(&self) -> Option<[T; 2]> {
        self.full_contact.accelerations()
    }
}
