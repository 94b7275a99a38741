//! [`DiscOnBoard`]: a disc on a board pulled along a floor (`docs/scenes.md`, "disc-on-board";
//! the rim-on-face contact of `docs/formulation.md`).

use super::{BLOCK_ON_BLOCK_ROWS, FullContact, Outcome, Run, settings_of};
use crate::multibody::{Pair, RestsOn, System, SystemStepReport, Table};
use crate::params::{ParamError, check_step_within, params};
use crate::planar::{Body, BodyState};
use crate::real::Real;

params! {
    /// Disc-on-board's parameters (`docs/scenes.md`, "disc-on-board"); `board_*` the board (`M`
    /// there), `disc_*` the disc (`m`, `r`).
    pub struct DiscOnBoardParams {
        /// `M` (kg).
        board_mass: 2.0, Positive;
        /// The board's length (m).
        board_length: 1.0, Positive;
        /// The board's height (m).
        board_height: 0.02, Positive;
        /// `m` (kg).
        disc_mass: 1.0, Positive;
        /// `r` (m).
        disc_radius: 0.05, Positive;
        /// The disc's start along `x` from the board's centre (m; `|offset| <= board_length / 2`).
        offset: 0.0, Finite;
        /// The pull `F` on the board along `+x` (N).
        force: 20.0, NonNegative;
        /// Static friction between the disc and the board.
        mu_static: 0.5, NonNegative;
        /// Kinetic friction between the disc and the board.
        mu_kinetic: 0.4, NonNegative;
        /// Friction between the board and the floor (static and kinetic).
        mu_floor: 0.1, NonNegative;
        /// `g` (m/s^2).
        gravity: 9.81, NonNegative;
        /// The time step (s).
        step: 0.001, Positive;
        /// Stick threshold (m/s).
        stick_speed: 1e-5, NonNegative;
        /// The activity rule's margin (m).
        contact_margin: 1e-3, NonNegative;
        /// Duration (s).
        max_time: 0.3, Positive;
    }
}

impl<T: Real> DiscOnBoardParams<T> {
    /// The validity rules of `docs/scenes.md`, "disc-on-board".
    ///
    /// # Errors
    /// The first broken rule, naming its field.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.check_fields()?;
        if self.mu_kinetic > self.mu_static {
            return Err(ParamError::KineticAboveStatic);
        }
        if self.offset.abs_exact() > self.board_length / T::of(2.0) {
            return Err(ParamError::OutOfRange("offset"));
        }
        check_step_within(self.step, self.max_time)?;
        self.board().check_inertia("board_mass", "board_length")?;
        self.disc().check_inertia("disc_mass", "disc_radius")
    }

    fn board(&self) -> Body<T> {
        Body::block(self.board_mass, self.board_length, self.board_height)
    }

    fn disc(&self) -> Body<T> {
        Body::disc(self.disc_mass, self.disc_radius)
    }
}

/// Disc-on-board: body 0 the board, body 1 the disc; pair 0 (board, floor), pair 1 (disc,
/// board: its one candidate, the rim's point nearest the board's top face). Its LCP has
/// block-on-block's capacity ([`BLOCK_ON_BLOCK_ROWS`]; 3 candidates need 12 rows), so that both
/// scenes share one stepper's code.
#[derive(Debug, Clone)]
pub struct DiscOnBoard<T: Real> {
    pub(super) run: Run<T, DiscOnBoardParams<T>, 2, 2, BLOCK_ON_BLOCK_ROWS>,
    /// Pair 0 / pair 1 slid after some step.
    slid: [bool; 2],
    full_contact: FullContact<T>,
}

impl<T: Real> DiscOnBoard<T> {
    /// Validates `params` and sets the board and the disc at rest, the disc on the board's top
    /// face `offset` from its centre.
    ///
    /// # Errors
    /// As [`DiscOnBoardParams::validate`].
    pub fn new(params: DiscOnBoardParams<T>) -> Result<Self, ParamError> {
        params.validate()?;
        let p = params;
        let half = T::of(0.5);
        let system = System {
            bodies: [p.board(), p.disc()],
            table: Table::floor(),
            pairs: [
                Pair::boxed(0, RestsOn::Table, p.mu_floor, p.mu_floor),
                Pair::disc(1, RestsOn::Body(0), p.mu_static, p.mu_kinetic),
            ],
            forces: [[p.force, T::zero()], [T::zero(); 2]],
            settings: settings_of!(p),
        };
        let states = [
            BodyState::at_rest(T::zero(), half * p.board_height, T::zero()),
            BodyState::at_rest(p.offset, p.board_height + p.disc_radius, T::zero()),
        ];
        Ok(Self {
            run: Run::new(params, system, states)?,
            slid: [false; 2],
            full_contact: FullContact::new(),
        })
    }

    /// Advances one step; `None` once the run has an outcome: `Unfinished` as soon as the rim's
    /// point is beyond an end of the board (the rim-on-face contact has no edge: off the board the
    /// disc would fall, which the scene does not model); at `max_time` `Slid` once the disc slid on
    /// the board, else `Rolled` once the board slid on the floor, else `Held`.
    pub fn step(&mut self) -> Option<SystemStepReport<T, 2, 2>> {
        let report = self.run.advance()?;
        for p in 0..2 {
            self.slid[p] |= report.pair_slid(p);
        }
        let [board, disc] = report.states;
        let touching = report.touching(&[(0, 0), (0, 1), (1, 0)]);
        self.full_contact.record(touching, report.time, [board.vx, disc.vx]);
        let p = &self.run.params;
        // The rim point's coordinate along the board's top face at the step's end, as the activity
        // rule computed it for the next step (`rim_frames`: the same number, one formula).
        let along = self.run.stepper.frames()[1][0].along;
        if along.abs_exact() > p.board_length / T::of(2.0) {
            self.run.outcome = Some(Outcome::Unfinished);
        } else if report.time >= p.max_time {
            self.run.outcome = Some(match self.slid {
                [_, true] => Outcome::Slid,
                [true, false] => Outcome::Rolled,
                [false, false] => Outcome::Held,
            });
        }
        Some(report)
    }

    /// `[a_board, a_disc]` (m/s^2): the board's and the disc centre's accelerations along `x`
    /// while the board's two corners and the rim touch; `None` before two such steps.
    #[must_use]
    pub fn accelerations(&self) -> Option<[T; 2]> {
        self.full_contact.accelerations()
    }
}
