//! The stepping loop every scene shares: docs/scenes.md, "Common rules", and docs/formulation.md,
//! "Integration".
//!
//! From the start state (at rest but in painleve), with the initial modes from the prescribed
//! motion at `t = 0` against the body's start velocity,
//! each step `n -> n + 1`: the contacts' geometry at `t_n = n h` (supports at `t_n`), the
//! supports' velocities over the step, `mu_s` for a contact sticking or separated before the step
//! and `mu_k` for one sliding; the step's LCP (`step.rs`); `q+ = q + h v+`; `t = (n + 1) h`;
//! the modes after the step, a switch event for each contact whose mode changed; the scene's
//! outcome rules on the state at the step's end.

use super::geometry::{Frame, Support, frame};
use super::step::{Model, initial_modes, modes_after, solve};
use super::{Contact, Event, Mode, Outcome, Row, Run, Sample};

/// The state at the end of a step, as the outcome rules see it.
#[derive(Debug, Clone, Copy)]
pub(super) struct StepEnd<'a> {
    /// Steps taken.
    pub steps: u64,
    /// `t = steps h`.
    pub t: f64,
    /// Configuration.
    pub q: [f64; 3],
    /// Velocity.
    pub v: [f64; 3],
    /// Modes before the step.
    pub before: &'a [Mode],
    /// Modes after the step.
    pub after: &'a [Mode],
    /// Contact geometry at the step's end (supports at `t`).
    pub end: &'a [Frame],
    /// Each contact's normal impulse over the step, N s.
    pub normal: &'a [f64],
    /// Each contact's net friction impulse over the step along `+d`, N s.
    pub friction: &'a [f64],
}

/// One scene: its body, supports and outcome rules.
pub(super) trait Scene {
    /// What every step shares.
    fn model(&self) -> Model;
    /// The start configuration.
    fn start(&self) -> [f64; 3];
    /// The start velocity `(vx, vy, omega)`: at rest but in painleve (docs/scenes.md).
    fn start_velocity(&self) -> [f64; 3] {
        [0.0; 3]
    }
    /// Each contact's `(mu_s, mu_k)`.
    fn friction(&self) -> Vec<(f64, f64)>;
    /// Each contact's support at `t = steps h`.
    fn supports(&self, steps: u64) -> Vec<Support>;
    /// Each support's velocity in the prescribed motion at `t = 0`.
    fn initial_support_velocity(&self) -> Vec<[f64; 2]>;
    /// Each support's velocity over the step from `steps h` to `(steps + 1) h`.
    fn support_velocity(&self, steps: u64) -> Vec<[f64; 2]>;
    /// The outcome rules, in the scene's order, after a step; records measurements on the way.
    fn judge(&mut self, end: &StepEnd<'_>) -> Option<Outcome>;
    /// Writes the scene's measured quantities into `run` (its outcome is set).
    fn measure(&self, run: &mut Run);
}

/// The geometry of every contact at configuration `q`.
fn frames(model: &Model, q: [f64; 3], supports: &[Support]) -> Vec<Frame> {
    supports.iter().map(|s| frame(&model.body, q, s)).collect()
}

/// Whether the row after `steps` steps is kept.
fn keeps(sample: &Sample, steps: u64) -> bool {
    match *sample {
        Sample::All => true,
        Sample::Every(every) => every > 0 && steps.is_multiple_of(every),
        Sample::None => false,
    }
}

/// The row at `t`: `start` is the contacts' geometry at the step's start, `end` at `t`, `modes`
/// after the step, `impulses` the normal and friction impulses over it (N s).
fn row(
    t: f64,
    q: [f64; 3],
    v: [f64; 3],
    start: &[Frame],
    end: &[Frame],
    modes: &[Mode],
    impulses: [&[f64]; 2],
) -> Row {
    Row {
        t,
        q,
        v,
        supports: end.iter().map(|f| f.support_point).collect(),
        contacts: (0..start.len())
            .map(|i| Contact {
                mode: modes[i],
                normal_impulse: impulses[0][i],
                friction_impulse: impulses[1][i],
                along: start[i].along,
                active: start[i].active,
            })
            .collect(),
    }
}

/// Runs `scene` to its outcome.
pub(super) fn simulate(scene: &mut impl Scene, sample: &Sample) -> Run {
    let model = scene.model();
    let h = model.step;
    let friction = scene.friction();
    let mut q = scene.start();
    let mut v = scene.start_velocity();
    let mut start = frames(&model, q, &scene.supports(0));
    let initial = initial_modes(&model, q, v, &start, &scene.initial_support_velocity());
    let mut run = Run {
        rows: Vec::new(),
        initial_modes: initial.clone(),
        events: Vec::new(),
        outcome: Outcome::Unfinished,
        steps: 0,
        end_time: 0.0,
        meeting: None,
        acceleration: None,
        angular_acceleration: None,
        wall_release_height: None,
        jam: None,
        ambiguous_steps: 0,
        first_ambiguous: None,
    };
    let zero = vec![0.0; start.len()];
    run.rows.push(row(0.0, q, v, &start, &start, &initial, [&zero, &zero]));
    let mut modes = initial;
    let mut slipping_unloaded = vec![false; modes.len()];
    let mut steps = 0_u64;
    let outcome = loop {
        // A stop requested (`crate::request_stop`, a host's Ctrl-C): the run stops here and the
        // caller drops it.
        if steps.is_multiple_of(crate::CHECK_EVERY_STEPS) && crate::stop_requested() {
            break Outcome::Failed(format!("interrupted at t = {}", steps as f64 * h));
        }
        let u = scene.support_velocity(steps);
        // A contact the last load left touching, slipping and unloaded slides on: `mu_k`.
        let mu: Vec<f64> = modes
            .iter()
            .zip(&friction)
            .zip(&slipping_unloaded)
            .map(|((m, &(mu_s, mu_k)), &unloaded)| match m {
                Mode::SlidingPositive | Mode::SlidingNegative => mu_k,
                Mode::Separated if unloaded => mu_k,
                Mode::Sticking | Mode::Separated => mu_s,
            })
            .collect();
        let result = match solve(&model, q, v, &start, &u, &mu) {
            Ok(result) => result,
            Err(why) => break Outcome::Failed(format!("{why} at t = {}", steps as f64 * h)),
        };
        if result.ambiguous {
            run.ambiguous_steps += 1;
            run.first_ambiguous.get_or_insert((steps + 1) as f64 * h);
        }
        // Eq. 14: q+ = q + h v+.
        v = result.velocity;
        for c in 0..3 {
            q[c] += h * v[c];
        }
        steps += 1;
        let t = steps as f64 * h;
        let after = modes_after(&model, &start, &u, &result);
        let along: Vec<f64> = start.iter().map(|f| f.along).collect();
        for (contact, (&before, &now)) in modes.iter().zip(&after).enumerate() {
            if before != now {
                run.events.push(Event { t, contact, mode: now, along: along.clone() });
            }
        }
        let end = frames(&model, q, &scene.supports(steps));
        let physical = |per_mass: &[f64]| per_mass.iter().map(|x| model.body.mass * x).collect::<Vec<f64>>();
        let impulses = [physical(&result.normal), physical(&result.friction)];
        if keeps(sample, steps) {
            run.rows.push(row(t, q, v, &start, &end, &after, [&impulses[0], &impulses[1]]));
        }
        if !q.iter().chain(&v).all(|x| x.is_finite()) {
            break Outcome::Failed(format!("non-finite state at t = {t}"));
        }
        let judged = scene.judge(&StepEnd {
            steps,
            t,
            q,
            v,
            before: &modes,
            after: &after,
            end: &end,
            normal: &impulses[0],
            friction: &impulses[1],
        });
        modes = after;
        slipping_unloaded.clone_from(&result.slipping_unloaded);
        start = end;
        if let Some(outcome) = judged {
            break outcome;
        }
    };
    run.outcome = outcome;
    run.steps = steps;
    run.end_time = steps as f64 * h;
    scene.measure(&mut run);
    run
}
