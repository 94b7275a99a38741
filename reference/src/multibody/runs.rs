//! Each scene of several bodies run to its outcome: the loop that steps a [`System`], records its
//! rows at the sampling asked for and reads the scene's measured quantities (the scenes
//! themselves, their parameters and rules: `scenes.rs`).

use std::time::Instant;

use super::geometry::Lower;
use super::scenes::{BlockOnBlock, DiscOnBoard, Stack, Tablecloth};
use super::step::{Starts, Stepped};
use super::system::{State, System};
use super::{Outcome, Row, Run};
use crate::{Mode, Sample};

/// What the loop tracks beside the scene's own rules.
struct Loop {
    run: Run,
    sample: Sample,
    started: Instant,
}

impl Loop {
    fn new(sample: Sample) -> Self {
        Self {
            run: Run {
                rows: Vec::new(),
                outcome: Outcome::Unfinished,
                steps: 0,
                end_time: 0.0,
                q: Vec::new(),
                v: Vec::new(),
                interface_forces: Vec::new(),
                corner_loads: Vec::new(),
                lower_acceleration: None,
                upper_acceleration: None,
                block_displacement: None,
                max_speed: 0.0,
                ambiguous_steps: 0,
                max_rows: 0,
                seconds_per_step: 0.0,
            },
            sample,
            started: Instant::now(),
        }
    }

    /// Steps until `judge` gives an outcome or `max_time` passes (then `at_end` decides).
    fn drive(
        mut self,
        system: &System,
        state: &mut State,
        max_time: f64,
        mut judge: impl FnMut(&State, &Stepped) -> Option<Outcome>,
        at_end: impl FnOnce(&State) -> Outcome,
    ) -> Run {
        let max_steps = (max_time / system.step - 1e-9).ceil().max(1.0) as u64;
        self.run.rows.push(Row {
            t: 0.0,
            q: state.q.clone(),
            v: state.v.clone(),
            interface_forces: vec![[0.0; 2]; system.pairs.len()],
            corner_loads: vec![[[0.0; 2]; 4]; system.pairs.len()],
            ambiguous: false,
        });
        let outcome = loop {
            let stepped = match state.advance(system, Starts::ALL) {
                Ok(s) => s,
                Err(e) => break Outcome::Failed(e),
            };
            self.record(system, state, &stepped);
            if let Some(outcome) = judge(state, &stepped) {
                break outcome;
            }
            if state.steps >= max_steps {
                break at_end(state);
            }
        };
        self.run.outcome = outcome;
        self.run.steps = state.steps;
        self.run.end_time = state.time(system);
        self.run.q.clone_from(&state.q);
        self.run.v.clone_from(&state.v);
        self.run.seconds_per_step = self.started.elapsed().as_secs_f64() / state.steps.max(1) as f64;
        self.run
    }

    fn record(&mut self, system: &System, state: &State, stepped: &Stepped) {
        let r = &stepped.result;
        self.run.ambiguous_steps += u64::from(r.ambiguous);
        self.run.max_rows = self.run.max_rows.max(r.rows);
        for (v, b) in state.v.iter().zip(&system.bodies) {
            self.run.max_speed = self.run.max_speed.max(v[0].hypot(v[1]) + b.reach() * v[2].abs());
        }
        let mut forces = vec![[0.0; 2]; system.pairs.len()];
        let mut loads = vec![[[0.0; 2]; 4]; system.pairs.len()];
        let candidates = candidate_indices(system, &stepped.frames);
        for (i, f) in stepped.frames.iter().enumerate() {
            loads[f.pair][candidates[i]] = [r.normal[i] / system.step, r.friction[i] / system.step];
            let on_corner = [
                f.normal[0] * r.normal[i] + f.tangent[0] * r.friction[i],
                f.normal[1] * r.normal[i] + f.tangent[1] * r.friction[i],
            ];
            let sign = if f.corner_body == Some(system.pairs[f.pair].upper) { 1.0 } else { -1.0 };
            for c in 0..2 {
                forces[f.pair][c] += sign * on_corner[c] / system.step;
            }
        }
        let keep = match self.sample {
            Sample::All => true,
            Sample::Every(every) => every > 0 && state.steps.is_multiple_of(every),
            Sample::None => false,
        };
        if keep {
            self.run.rows.push(Row {
                t: state.time(system),
                q: state.q.clone(),
                v: state.v.clone(),
                interface_forces: forces.clone(),
                corner_loads: loads.clone(),
                ambiguous: r.ambiguous,
            });
        }
        self.run.interface_forces = forces;
        self.run.corner_loads = loads;
    }
}

/// Each frame's place among its pair's four candidates (the module documentation of
/// `geometry.rs`): the upper body's corners 0 and 1 (a disc's rim 0), the lower body's 2 and 3 (a
/// table without a `lo` end has only its `hi` end, 3).
fn candidate_indices(system: &System, frames: &[super::geometry::Frame]) -> Vec<usize> {
    let mut seen = vec![[0_usize; 2]; system.pairs.len()];
    frames
        .iter()
        .map(|f| {
            let pair = &system.pairs[f.pair];
            let seen = &mut seen[f.pair];
            if f.corner_body == Some(pair.upper) {
                seen[0] += 1;
                seen[0] - 1
            } else {
                let first = match pair.lower {
                    Lower::Table if !system.table.lo.is_finite() => 3,
                    _ => 2,
                };
                seen[1] += 1;
                first + seen[1] - 1
            }
        })
        .collect()
}

/// The candidates of pair `p` whose corner is the upper body's (its lower corners on the lower
/// one's top face).
fn upper_corners(system: &System, frames: &[super::geometry::Frame], p: usize) -> Vec<usize> {
    (0..frames.len())
        .filter(|&i| frames[i].pair == p && frames[i].corner_body == Some(system.pairs[p].upper))
        .collect()
}

/// Whether any contact of pair `p` slid after the step.
fn pair_slid(stepped: &Stepped, modes: &[Mode], p: usize) -> bool {
    stepped.frames.iter().zip(modes).any(|(f, m)| f.pair == p && m.is_sliding())
}

/// The accelerations along `x` of bodies 0 and 1 between the end of step 1 and the end of the
/// last step of the first run of steps after which every contact in `full` touched.
#[derive(Default)]
struct Window {
    first: Option<(f64, [f64; 2])>,
    last: Option<(f64, [f64; 2])>,
    open: bool,
}

impl Window {
    fn update(&mut self, t: f64, v: &[[f64; 3]], full: bool) {
        let vx = [v[0][0], v[1][0]];
        if self.first.is_none() {
            self.first = Some((t, vx));
            self.open = full;
            return;
        }
        if self.open && full {
            self.last = Some((t, vx));
        } else {
            self.open = false;
        }
    }

    fn accelerations(&self) -> (Option<f64>, Option<f64>) {
        match (self.first, self.last) {
            (Some((t1, v1)), Some((t2, v2))) if t2 > t1 => {
                (Some((v2[0] - v1[0]) / (t2 - t1)), Some((v2[1] - v1[1]) / (t2 - t1)))
            }
            _ => (None, None),
        }
    }
}

/// Runs a valid block-on-block scene (docs/scenes.md, "block-on-block").
pub(super) fn run_block_on_block(p: &BlockOnBlock, sample: Sample) -> Run {
    let system = p.system();
    let mut state = State::at_rest(&system, p.start());
    let (mut slid_top, mut slid_floor) = (false, false);
    let mut window = Window::default();
    let half = p.bottom_width / 2.0;
    let tilt = p.tilt_limit;
    let mut run = Loop::new(sample).drive(
        &system,
        &mut state,
        p.max_time,
        |state, stepped| {
            slid_floor |= pair_slid(stepped, &state.modes, 0);
            slid_top |= pair_slid(stepped, &state.modes, 1);
            let mut full = upper_corners(&system, &stepped.frames, 0);
            full.extend(upper_corners(&system, &stepped.frames, 1));
            window.update(
                state.time(&system),
                &state.v,
                full.iter().all(|&i| state.modes[i] != Mode::Separated),
            );
            let (bottom, top) = (state.q[0], state.q[1]);
            if top[2].abs() > tilt {
                Some(Outcome::Tipped)
            } else if (top[0] - bottom[0]).abs() > half {
                Some(Outcome::Slid)
            } else {
                None
            }
        },
        |_| Outcome::Unfinished,
    );
    if run.outcome == Outcome::Unfinished {
        run.outcome = if slid_top {
            Outcome::Slid
        } else if slid_floor {
            Outcome::Rode
        } else {
            Outcome::Held
        };
    }
    (run.lower_acceleration, run.upper_acceleration) = window.accelerations();
    run
}

/// Runs a valid tablecloth scene (docs/scenes.md, "tablecloth").
pub(super) fn run_tablecloth(p: &Tablecloth, sample: Sample) -> Run {
    let system = p.system();
    let q0 = p.start();
    let block_x0 = q0[1][0];
    let mut state = State::at_rest(&system, q0);
    let (mut slid_any, mut slid_block) = (false, false);
    let mut window = Window::default();
    let (half, reach, rest) = (p.board_length / 2.0, system.bodies[1].reach(), p.stick_speed);
    let mut run = Loop::new(sample).drive(
        &system,
        &mut state,
        p.max_time,
        |state, stepped| {
            slid_any |= state.modes.iter().any(|m| m.is_sliding());
            slid_block |= pair_slid(stepped, &state.modes, 1);
            let mut full = upper_corners(&system, &stepped.frames, 0);
            full.extend(upper_corners(&system, &stepped.frames, 1));
            window.update(
                state.time(&system),
                &state.v,
                full.iter().all(|&i| state.modes[i] != Mode::Separated),
            );
            let (board, block) = (state.q[0], state.q[1]);
            let v = state.v[1];
            let trailing = board[0] - half * board[2].cos();
            let at_rest = v[0].abs() <= rest && v[1].abs() <= rest && reach * v[2].abs() <= rest;
            (block[0] < trailing && at_rest).then_some(Outcome::Stayed)
        },
        |_| Outcome::Unfinished,
    );
    if run.outcome == Outcome::Unfinished {
        if !slid_any {
            run.outcome = Outcome::Held;
        } else if !slid_block {
            run.outcome = Outcome::Rode;
        }
    }
    (run.lower_acceleration, run.upper_acceleration) = window.accelerations();
    run.block_displacement = Some(run.q[1][0] - block_x0);
    run
}

/// Runs a valid stack scene (docs/scenes.md, "stack").
pub(super) fn run_stack(p: &Stack, sample: Sample) -> Run {
    let system = p.system();
    let q0 = p.start();
    let y0: Vec<f64> = q0.iter().map(|q| q[1]).collect();
    let mut state = State::at_rest(&system, q0);
    Loop::new(sample).drive(
        &system,
        &mut state,
        p.max_time,
        |state, _| {
            let fell =
                state.q.iter().zip(&y0).any(|(q, y)| q[2].abs() > p.tilt_limit || y - q[1] > p.drop_limit);
            fell.then_some(Outcome::Fell)
        },
        |_| Outcome::Held,
    )
}

/// Runs a valid disc-on-board scene: `Slid` once the disc's contact slid on the board, else
/// `Rolled` once the board slid on the floor, else `Held`, at `max_time`; `Unfinished` as soon as
/// the disc's contact point is beyond the board's ends (the rim-on-face contact has no edge: off
/// the board the disc would fall, which the scene does not model). The accelerations are
/// block-on-block's window (the board's and the disc centre's along `x`, while both bodies' contacts
/// touch).
pub(super) fn run_disc_on_board(p: &DiscOnBoard, sample: Sample) -> Run {
    let system = p.system();
    let mut state = State::at_rest(&system, p.start());
    let (mut slid_disc, mut slid_floor, mut left) = (false, false, false);
    let mut window = Window::default();
    let half = p.board_length / 2.0;
    let mut run = Loop::new(sample).drive(
        &system,
        &mut state,
        p.max_time,
        |state, stepped| {
            slid_floor |= pair_slid(stepped, &state.modes, 0);
            slid_disc |= pair_slid(stepped, &state.modes, 1);
            let mut full = upper_corners(&system, &stepped.frames, 0);
            full.extend(upper_corners(&system, &stepped.frames, 1));
            window.update(
                state.time(&system),
                &state.v,
                full.iter().all(|&i| state.modes[i] != Mode::Separated),
            );
            // The rim point's coordinate along the board's top face, `(c_U - o) . e` (`P - c_U`
            // is normal to the face, `o - com` too).
            let (board, disc) = (state.q[0], state.q[1]);
            let along = (disc[0] - board[0]) * board[2].cos() + (disc[1] - board[1]) * board[2].sin();
            left = along.abs() > half;
            left.then_some(Outcome::Unfinished)
        },
        |_| Outcome::Unfinished,
    );
    if run.outcome == Outcome::Unfinished && !left {
        run.outcome = if slid_disc {
            Outcome::Slid
        } else if slid_floor {
            Outcome::Rolled
        } else {
            Outcome::Held
        };
    }
    (run.lower_acceleration, run.upper_acceleration) = window.accelerations();
    run
}
