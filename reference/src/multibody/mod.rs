//! The independent f64 reference for several bodies (docs/formulation.md, "Several bodies";
//! docs/scenes.md, "block-on-block", "tablecloth", "stack"): planar boxes (and discs) resting on
//! each other and on a fixed table, coupled through corner-on-face (and rim-on-face) contacts in
//! one LCP per step, written
//! from those texts and sharing no code with `meterstick-core` or with the single-body
//! reference (its enumerator, [`crate::enumerate`], is only its tests' check).
//!
//! * `geometry.rs`: boxes, discs, the table, the candidate contacts of each pair and their
//!   activity rule, the Jacobian rows in `3B` coordinates.
//! * `lcp.rs`: Lemke's method with the lexicographic rule, the solve of one basis, the
//!   verification.
//! * `step.rs`: the step's LCP and the least-kinetic-energy choice among the verified solutions
//!   found from the previous basis, Lemke's method and a descent over neighbouring bases.
//! * `system.rs`: the bodies, pairs and loads of a scene, and one step of its state.
//! * `scenes.rs`: [`BlockOnBlock`], [`Tablecloth`], [`Stack`] and [`DiscOnBoard`], their
//!   parameters, starts and rules;
//! * `runs.rs`: each run to its outcome by [`run`].

mod geometry;
pub mod lcp;
mod runs;
mod scenes;
mod step;
mod system;
#[cfg(test)]
mod tests;

pub use scenes::{BlockOnBlock, DiscOnBoard, Stack, Tablecloth};

use crate::Sample;

/// A multibody scene and its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spec {
    /// docs/scenes.md, "block-on-block".
    BlockOnBlock(BlockOnBlock),
    /// docs/scenes.md, "tablecloth".
    Tablecloth(Tablecloth),
    /// docs/scenes.md, "stack".
    Stack(Stack),
    /// docs/formulation.md, "The rim-on-face contact": a disc on a pulled board.
    DiscOnBoard(DiscOnBoard),
}

/// How a multibody run ended (docs/scenes.md, each scene's "Outcome").
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// Nothing slid (block-on-block, tablecloth, disc-on-board) or nothing fell (stack) by
    /// `max_time`.
    Held,
    /// The bodies moved together: the lower one slid on the floor, the upper one never slid on
    /// it.
    Rode,
    /// Disc-on-board: the board slid on the floor, the disc never slid on it (it rolled).
    Rolled,
    /// Block-on-block: the top block slid on the bottom one; disc-on-board: the disc slid on the
    /// board.
    Slid,
    /// Block-on-block: the top block tipped.
    Tipped,
    /// Tablecloth: the board came out from under the block, which came to rest.
    Stayed,
    /// Stack: a block tilted or dropped.
    Fell,
    /// `max_time` and no other outcome applies; disc-on-board: the disc's contact point went
    /// beyond the board's ends (the run ends there).
    Unfinished,
    /// A step found no verified solution, or the state became non-finite.
    Failed(String),
}

/// The state after one step (or the start, row 0).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// `t = n h`, s.
    pub t: f64,
    /// Each body's `(x, y, theta)`.
    pub q: Vec<[f64; 3]>,
    /// Each body's `(vx, vy, omega)` (the step's `v+`).
    pub v: Vec<[f64; 3]>,
    /// Each pair's summed contact force on its upper body over the step, world, N (row 0: zero).
    pub interface_forces: Vec<[f64; 2]>,
    /// Each pair's four candidate contacts' normal and friction force over the step (N, along
    /// the candidate's normal and its `+d`; zero for a candidate not in the step's LCP or that
    /// the pair lacks), in the candidates' order (`geometry.rs`: the upper body's lower-left and
    /// lower-right corners, then the lower body's upper-left and upper-right corners, the table's
    /// `lo` and `hi` ends; a disc's rim the first). Row 0: zero.
    pub corner_loads: Vec<[[f64; 2]; 4]>,
    /// Whether the step's verified solutions moved the bodies differently.
    pub ambiguous: bool,
}

/// A finished multibody run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The kept rows ([`crate::Sample`]; row 0, the start, always).
    pub rows: Vec<Row>,
    /// How it ended.
    pub outcome: Outcome,
    /// Steps taken.
    pub steps: u64,
    /// `steps h`, s.
    pub end_time: f64,
    /// Each body's `(x, y, theta)` at the end.
    pub q: Vec<[f64; 3]>,
    /// Each body's `(vx, vy, omega)` at the end.
    pub v: Vec<[f64; 3]>,
    /// Each pair's summed contact force on its upper body over the last step, world, N (the
    /// model decides the sum, not one corner's share).
    pub interface_forces: Vec<[f64; 2]>,
    /// Each pair's candidates' normal and friction force over the last step, N ([`Row::corner_loads`]).
    pub corner_loads: Vec<[[f64; 2]; 4]>,
    /// Block-on-block: the bottom block's acceleration along `x` while both are in full contact;
    /// tablecloth: the board's (docs/scenes.md, "Measured"); disc-on-board: the board's while the
    /// board and the disc touch, m/s^2.
    pub lower_acceleration: Option<f64>,
    /// Block-on-block: the top block's; tablecloth: the block's; disc-on-board: the disc
    /// centre's, m/s^2.
    pub upper_acceleration: Option<f64>,
    /// Tablecloth: the block's displacement along `x` at the end, m.
    pub block_displacement: Option<f64>,
    /// The largest body speed over the run, `|(vx, vy)| + reach |omega|`, m/s.
    pub max_speed: f64,
    /// Steps whose verified solutions moved the bodies differently.
    pub ambiguous_steps: u64,
    /// The largest LCP of the run, rows.
    pub max_rows: usize,
    /// The run's wall time per step, s (for reports; never asserted).
    pub seconds_per_step: f64,
}

/// Validates `spec` and runs it to its outcome, keeping the rows `sample` asks for.
///
/// # Errors
/// A broken validity rule, naming its parameter.
pub fn run(spec: &Spec, sample: Sample) -> Result<Run, String> {
    match *spec {
        Spec::BlockOnBlock(p) => {
            p.validate()?;
            Ok(runs::run_block_on_block(&p, sample))
        }
        Spec::Tablecloth(p) => {
            p.validate()?;
            Ok(runs::run_tablecloth(&p, sample))
        }
        Spec::Stack(p) => {
            p.validate()?;
            Ok(runs::run_stack(&p, sample))
        }
        Spec::DiscOnBoard(p) => {
            p.validate()?;
            Ok(runs::run_disc_on_board(&p, sample))
        }
    }
}
