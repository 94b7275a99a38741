//! The scenes of several bodies (`docs/scenes.md`, "Scenes of several bodies"): [`BlockOnBlock`],
//! [`Tablecloth`] and [`Stack`], each with its parameters, validity rules, outcome and measures.
//!
//! Their outcomes are the one list's, [`Outcome`] (`crate::scene::Outcome`; a failed step is
//! [`Outcome::MultibodyFailed`]). They do not implement `crate::scene::Scene`, which is shaped for one body (its
//! `StepReport<T, K>` carries one `BodyState`, its `frames` one support per contact); each has
//! `step()` and `run()` of its own returning [`super::StepReport`] (every body's state, each
//! pair's interface force).

mod block_on_block;
mod stack;
mod tablecloth;

pub use block_on_block::{BLOCK_ON_BLOCK_ROWS, BlockOnBlock, BlockOnBlockParams};
pub use stack::{Stack, Stack2, Stack3, StackParams};
pub use tablecloth::{TABLECLOTH_ROWS, Tablecloth, TableclothParams};

use crate::real::Real;
use crate::scene::Outcome;

/// The accelerations along `x` of a lower and an upper body while both are in full contact
/// (`docs/scenes.md`, block-on-block, "Measured"): `(vx(t_2) - vx(t_1)) / (t_2 - t_1)` over the
/// first unbroken run of steps after which the four contacts touch, `t_1` the end of its first
/// step, `t_2` of its last.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FullContact<T> {
    first: Option<(T, [T; 2])>,
    last: Option<(T, [T; 2])>,
    ended: bool,
}

impl<T: Real> FullContact<T> {
    const fn new() -> Self {
        Self { first: None, last: None, ended: false }
    }

    /// Records a step that ended at `time` with the two bodies' `vx`; `touching` when all four
    /// contacts touch after it.
    fn record(&mut self, touching: bool, time: T, vx: [T; 2]) {
        if self.ended {
            return;
        }
        if !touching {
            self.ended = self.first.is_some();
        } else if self.first.is_none() {
            self.first = Some((time, vx));
        } else {
            self.last = Some((time, vx));
        }
    }

    /// `[a_lower, a_upper]` (m/s^2), once the run has two steps.
    fn accelerations(&self) -> Option<[T; 2]> {
        let ((t1, v1), (t2, v2)) = (self.first?, self.last?);
        let dt = t2 - t1;
        Some([(v2[0] - v1[0]) / dt, (v2[1] - v1[1]) / dt])
    }
}

/// `|(vx, vy)| + reach |omega|`: the speed bound of a box's fastest point (`reach` half its
/// diagonal).
fn point_speed_bound<T: Real>(state: &crate::planar::BodyState<T>, reach: T) -> T {
    (state.vx * state.vx + state.vy * state.vy).sqrt_libm() + reach * state.omega.abs_exact()
}
