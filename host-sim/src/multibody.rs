//! The scenes of several bodies (`docs/scenes.md`, "Scenes of several bodies"; [`SceneKind::is_multibody`])
//! in `host-sim`: a run in the core (the registry's [`SceneParams::build_multibody`]) or in the
//! independent reference (`meterstick_reference::multibody::run`), recorded as a [`BodiesRun`]
//! (every body's state after every step, the outcome, what the scene measures, the solver's
//! counters), the deviation between two runs, and the laws of `docs/scenes.md` they are shown
//! beside, its plots. `host-sim scene`, `run` and `map` drive them (`host-sim stress` through
//! `crate::stress::bodies`).

use indicatif::ProgressBar;
use meterstick_core::Real;
use meterstick_core::multibody::scenes::{DiscOnBoardParams, MultibodyScene};
use meterstick_core::planar::{BodyState, Checksum};
use meterstick_core::scene::{MultibodyVisitor, Outcome, OutcomeKind, Precision, SceneKind, SceneParams};
use serde::Serialize;

use crate::plot::{self, Series, SeriesLabelPosition};
use crate::progress::{self, CHECK_EVERY_STEPS};
use crate::reference::Sample;
use crate::reference::multibody as reference;
use crate::trajectory::{Measured, RunOutcome};

/// Every body's state after one step (row 0: the start).
#[derive(Debug, Clone, PartialEq)]
pub struct BodiesRow {
    /// Time at the end of the step (s).
    pub t: f64,
    /// Each body's `(x, y, theta)` (m, m, rad), body 0 the lowest.
    pub q: Vec<[f64; 3]>,
    /// Each body's `(vx, vy, omega)`.
    pub v: Vec<[f64; 3]>,
}

/// A run's solver counters (zero where an implementation has no such thing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct BodiesCounters {
    /// Lemke pivots in all (core).
    pub pivots: u64,
    /// Most pivots in one step (core).
    pub max_pivots: u32,
    /// Steps the warm basis solved without a pivot (core).
    pub warm_direct: u32,
    /// The most active candidate contacts of one step (core).
    pub max_active: u8,
    /// The LCP's capacity (core) or its largest size (reference), rows.
    pub lcp_rows: usize,
    /// Steps whose verified solutions moved the bodies differently (reference; core: of the
    /// steps its rule enumerated).
    pub ambiguous_steps: u64,
    /// Steps the core's rule looked at: not at rest and flagged as possibly having several
    /// answers (core; `docs/formulation.md`, "One answer: the rule").
    pub rule_checked_steps: u64,
    /// Of those, steps whose solutions it enumerated (core).
    pub rule_enumerated_steps: u64,
    /// Steps where the rule's choice moved the bodies differently from the answer the solver's
    /// path reached first (core).
    pub rule_changed_answer: u64,
}

/// One run of a scene of several bodies, recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct BodiesRun {
    /// Who computed it: `core f32`, `reference f64`.
    pub label: String,
    /// Which scene.
    pub scene: SceneKind,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time at the end (s).
    pub end_time: f64,
    /// The recorded rows (all, or none: [`Self::last`] is kept either way).
    pub rows: Vec<BodiesRow>,
    /// The state at the end.
    pub last: BodiesRow,
    /// How it ended.
    pub outcome: RunOutcome,
    /// What the scene measures.
    pub measured: Measured,
    /// Solver counters.
    pub counters: BodiesCounters,
    /// The trajectory checksum over every step's states of all bodies in body order
    /// ([`meterstick_core::multibody::StepReport::add_to`]: the firmware's fingerprint; the core's
    /// runs only).
    pub checksum: Option<u32>,
}

fn row_of<T: Real>(t: T, states: &[BodyState<T>]) -> BodiesRow {
    BodiesRow {
        t: t.as_f64(),
        q: states.iter().map(|s| [s.x.as_f64(), s.y.as_f64(), s.theta.as_f64()]).collect(),
        v: states.iter().map(|s| [s.vx.as_f64(), s.vy.as_f64(), s.omega.as_f64()]).collect(),
    }
}

/// The core's run, through the registry.
struct CoreRun<'a> {
    kind: SceneKind,
    record: bool,
    bar: Option<&'a ProgressBar>,
}

impl MultibodyVisitor for CoreRun<'_> {
    type Output = anyhow::Result<BodiesRun>;

    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        mut scene: S,
    ) -> Self::Output {
        let start = row_of(scene.time(), scene.states());
        let mut rows = if self.record { vec![start.clone()] } else { Vec::new() };
        let mut steps = 0_u64;
        let mut checksum = Checksum::new();
        while let Some(report) = scene.step() {
            steps += 1;
            report.add_to(&mut checksum);
            if self.record {
                rows.push(row_of(report.time, &report.states));
            }
            if steps.is_multiple_of(CHECK_EVERY_STEPS) {
                progress::check()?;
                if let Some(bar) = self.bar {
                    bar.inc(CHECK_EVERY_STEPS);
                }
            }
        }
        let stats = scene.stats();
        Ok(BodiesRun {
            label: format!("core {}", T::NAME),
            scene: self.kind,
            steps,
            end_time: scene.time().as_f64(),
            rows,
            last: row_of(scene.time(), scene.states()),
            outcome: RunOutcome::from(scene.outcome().unwrap_or(Outcome::Unfinished)),
            measured: Measured::of(self.kind, scene.measured().map(|m| m.map(Real::as_f64))),
            counters: BodiesCounters {
                pivots: stats.pivots,
                max_pivots: stats.max_pivots,
                warm_direct: stats.warm_direct,
                max_active: stats.max_active,
                lcp_rows: S::ROWS,
                ambiguous_steps: stats.ambiguous_steps,
                rule_checked_steps: stats.rule_checked_steps,
                rule_enumerated_steps: stats.rule_enumerated_steps,
                rule_changed_answer: stats.rule_changed_answer,
            },
            checksum: Some(checksum.value()),
        })
    }
}

/// Runs `spec`, a scene of several bodies, in the core in `precision` to its outcome, keeping
/// every step when `record`, counting steps on `bar`.
///
/// # Errors
/// Invalid parameters (the core's complaint), or Ctrl-C.
pub fn run_core(
    spec: &SceneParams,
    precision: Precision,
    record: bool,
    bar: Option<&ProgressBar>,
) -> anyhow::Result<BodiesRun> {
    progress::check()?;
    let run = spec
        .build_multibody(precision, CoreRun { kind: spec.kind(), record, bar })
        .map_err(|e| anyhow::anyhow!("{}", crate::scenes::flag_error(spec, e)))??;
    progress::check()?;
    Ok(run)
}

/// The same scene for the independent reference (its own parameter types: data only).
#[must_use]
pub fn to_reference(spec: &SceneParams) -> Option<reference::Spec> {
    Some(match *spec {
        SceneParams::BlockOnBlock(p) => reference::Spec::BlockOnBlock(reference::BlockOnBlock {
            top_mass: p.top_mass,
            top_width: p.top_width,
            top_height: p.top_height,
            bottom_mass: p.bottom_mass,
            bottom_width: p.bottom_width,
            bottom_height: p.bottom_height,
            force: p.force,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            mu_floor: p.mu_floor,
            gravity: p.gravity,
            step: p.step,
            stick_speed: p.stick_speed,
            tilt_limit: p.tilt_limit,
            contact_margin: p.contact_margin,
            max_time: p.max_time,
        }),
        SceneParams::Tablecloth(p) => reference::Spec::Tablecloth(reference::Tablecloth {
            board_mass: p.board_mass,
            board_length: p.board_length,
            board_thickness: p.board_thickness,
            block_mass: p.block_mass,
            block_width: p.block_width,
            block_height: p.block_height,
            offset: p.offset,
            force: p.force,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            mu_floor: p.mu_floor,
            gravity: p.gravity,
            step: p.step,
            stick_speed: p.stick_speed,
            contact_margin: p.contact_margin,
            max_time: p.max_time,
        }),
        SceneParams::Stack(s) => {
            let p = s.params;
            reference::Spec::Stack(reference::Stack {
                blocks: s.block_count()?,
                length: p.length,
                height: p.height,
                mass: p.mass,
                mu_static: p.mu_static,
                mu_kinetic: p.mu_kinetic,
                overhang: p.overhang,
                gravity: p.gravity,
                step: p.step,
                stick_speed: p.stick_speed,
                tilt_limit: p.tilt_limit,
                drop_limit: p.drop_limit,
                contact_margin: p.contact_margin,
                max_time: p.max_time,
            })
        }
        SceneParams::DiscOnBoard(p) => reference::Spec::DiscOnBoard(reference::DiscOnBoard {
            board_mass: p.board_mass,
            board_length: p.board_length,
            board_height: p.board_height,
            disc_mass: p.disc_mass,
            disc_radius: p.disc_radius,
            offset: p.offset,
            force: p.force,
            mu_static: p.mu_static,
            mu_kinetic: p.mu_kinetic,
            mu_floor: p.mu_floor,
            gravity: p.gravity,
            step: p.step,
            stick_speed: p.stick_speed,
            contact_margin: p.contact_margin,
            max_time: p.max_time,
        }),
        _ => return None,
    })
}

fn reference_row(r: &reference::Row) -> BodiesRow {
    BodiesRow { t: r.t, q: r.q.clone(), v: r.v.clone() }
}

/// Runs `spec` in the independent reference to its outcome, keeping every step when `record`.
///
/// # Errors
/// A scene the reference does not have, or its refusal of the parameters.
pub fn run_reference(spec: &SceneParams, record: bool) -> anyhow::Result<BodiesRun> {
    let kind = spec.kind();
    let Some(r_spec) = to_reference(spec) else {
        anyhow::bail!("scene {kind} has no multibody reference");
    };
    progress::check()?;
    let sample = if record { Sample::All } else { Sample::None };
    let r = reference::run(&r_spec, sample).map_err(|e| anyhow::anyhow!("reference: {e}"))?;
    progress::check()?;
    let outcome = match r.outcome {
        reference::Outcome::Held => RunOutcome::of(OutcomeKind::Held),
        reference::Outcome::Rode => RunOutcome::of(OutcomeKind::Rode),
        reference::Outcome::Rolled => RunOutcome::of(OutcomeKind::Rolled),
        reference::Outcome::Slid => RunOutcome::of(OutcomeKind::Slid),
        reference::Outcome::Tipped => RunOutcome::of(OutcomeKind::Tipped),
        reference::Outcome::Stayed => RunOutcome::of(OutcomeKind::Stayed),
        reference::Outcome::Fell => RunOutcome::of(OutcomeKind::Fell),
        reference::Outcome::Unfinished => RunOutcome::of(OutcomeKind::Unfinished),
        reference::Outcome::Failed(why) => RunOutcome { class: OutcomeKind::Failed, detail: Some(why) },
    };
    let measures = match kind {
        SceneKind::BlockOnBlock | SceneKind::DiscOnBoard => {
            [r.lower_acceleration, r.upper_acceleration, None]
        }
        SceneKind::Tablecloth => [r.block_displacement, None, None],
        _ => [Some(r.max_speed), None, None],
    };
    Ok(BodiesRun {
        label: "reference f64".into(),
        scene: kind,
        steps: r.steps,
        end_time: r.end_time,
        rows: r.rows.iter().map(reference_row).collect(),
        last: BodiesRow { t: r.end_time, q: r.q.clone(), v: r.v.clone() },
        outcome,
        measured: Measured::of(kind, measures),
        counters: BodiesCounters {
            lcp_rows: r.max_rows,
            ambiguous_steps: r.ambiguous_steps,
            ..BodiesCounters::default()
        },
        checksum: None,
    })
}

/// The largest distance between the same body's centres of mass (m) and the largest angle
/// difference (rad) over the rows both runs recorded (row `i` is step `i` in both), and over
/// their final states when both ended on the same step.
#[must_use]
pub fn max_deviation(a: &BodiesRun, b: &BodiesRun) -> (f64, f64) {
    let mut worst = (0.0_f64, 0.0_f64);
    let mut compare = |p: &BodiesRow, q: &BodiesRow| {
        for (x, y) in p.q.iter().zip(&q.q) {
            worst.0 = worst.0.max((x[0] - y[0]).hypot(x[1] - y[1]));
            worst.1 = worst.1.max((x[2] - y[2]).abs());
        }
    };
    for (p, q) in a.rows.iter().zip(&b.rows) {
        compare(p, q);
    }
    if a.steps == b.steps {
        compare(&a.last, &b.last);
    }
    worst
}

/// The core's rule counters in words (`docs/formulation.md`, "One answer: the rule").
fn rule_text(c: &BodiesCounters) -> String {
    format!(
        "core: {} steps not at rest flagged as possibly having several answers; of the {} enumerated {} had \
         several, and the rule changed the solver's first answer on {}",
        c.rule_checked_steps, c.rule_enumerated_steps, c.ambiguous_steps, c.rule_changed_answer
    )
}

/// What `docs/scenes.md`'s laws say of a scene of several bodies: the outcome, and the
/// accelerations where the law gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Law {
    /// The outcome the law predicts (`None` where it does not decide: a run at a threshold).
    pub outcome: Option<OutcomeKind>,
    /// The lower body's acceleration along `x` while both are in full contact (m/s^2).
    pub lower_acceleration: Option<f64>,
    /// The upper body's (m/s^2).
    pub upper_acceleration: Option<f64>,
    /// The law in words, with its thresholds.
    pub text: &'static str,
}

/// The laws of block-on-block and the tablecloth (`docs/scenes.md`): the floor holds the pull
/// `F` up to `mu_floor (M + m) g`; up to `(mu_s + mu_floor) (M + m) g` both ride at
/// `a = F / (M + m) - mu_floor g` (block-on-block: a tall top block tips first when
/// `g w / h < a`); above it the upper one slides back at `mu_k g` and the lower one accelerates
/// at `(F - mu_k m g - mu_floor (M + m) g) / M`; the stack holds iff its overhang scale is below 1;
/// disc-on-board's ([`disc_on_board_law`]).
#[must_use]
pub fn law(spec: &SceneParams) -> Option<Law> {
    let pulled = |force: f64, lower: f64, upper: f64, mu_s: f64, mu_k: f64, mu_floor: f64, g: f64| {
        let total = lower + upper;
        let (held, riding) = (mu_floor * total * g, (mu_s + mu_floor) * total * g);
        if force <= held {
            (OutcomeKind::Held, 0.0, 0.0)
        } else if force <= riding {
            let a = force / total - mu_floor * g;
            (OutcomeKind::Rode, a, a)
        } else {
            (OutcomeKind::Slid, (force - mu_k * upper * g - mu_floor * total * g) / lower, mu_k * g)
        }
    };
    Some(match *spec {
        SceneParams::BlockOnBlock(p) => {
            let (mut outcome, a_bottom, a_top) =
                pulled(p.force, p.bottom_mass, p.top_mass, p.mu_static, p.mu_kinetic, p.mu_floor, p.gravity);
            if outcome == OutcomeKind::Rode && a_top > p.gravity * p.top_width / p.top_height {
                outcome = OutcomeKind::Tipped;
            }
            Law {
                outcome: Some(outcome),
                lower_acceleration: Some(a_bottom),
                upper_acceleration: Some(a_top),
                text: "Held iff F <= mu_floor (M + m) g; Rode iff F <= (mu_s + mu_floor) (M + m) g, at \
                       F / (M + m) - mu_floor g (Tipped when that exceeds g w / h); else Slid: a_top = mu_k g",
            }
        }
        SceneParams::Tablecloth(p) => {
            let (outcome, a_board, a_block) =
                pulled(p.force, p.board_mass, p.block_mass, p.mu_static, p.mu_kinetic, p.mu_floor, p.gravity);
            let outcome = if outcome == OutcomeKind::Slid { OutcomeKind::Stayed } else { outcome };
            Law {
                outcome: Some(outcome),
                lower_acceleration: Some(a_board),
                upper_acceleration: Some(a_block),
                text: "Held iff F <= mu_floor (m + m_b) g; Rode iff F <= (mu_s + mu_floor) (m + m_b) g; \
                       else the board comes out and the block Stayed, moved less the harder the pull",
            }
        }
        SceneParams::Stack(s) => Law {
            outcome: if s.params.overhang < 1.0 {
                Some(OutcomeKind::Held)
            } else if s.params.overhang > 1.0 {
                Some(OutcomeKind::Fell)
            } else {
                None
            },
            lower_acceleration: None,
            upper_acceleration: None,
            text: "Held iff the overhang scale s < 1 (every block's load inside the edge below it), Fell above",
        },
        SceneParams::DiscOnBoard(p) => disc_on_board_law(&p),
        _ => return None,
    })
}

/// Disc-on-board's law (`docs/scenes.md`, "disc-on-board"; `docs/formulation.md`, "The rim-on-face
/// contact"): the floor holds the pull `F` up to `mu_floor (M + m) g`; beyond it the board
/// accelerates at `A = (F - mu_floor (M + m) g) / (M + m / 3)` with the disc rolling, its centre
/// at `a_c = A / 3` (the board's friction `m A / 3` on the disc, its turning `J alpha = r m A / 3`
/// with `J = m r^2 / 2`, and the rim's point moving with the board: `a_c + r alpha = A`), while that
/// friction is within `mu_s m g`: `A <= 3 mu_s g`; beyond, the disc slides at `a_c = mu_k g` and
/// the board accelerates at `(F - mu_k m g - mu_floor (M + m) g) / M`. The rim's point moves along
/// the board by `(a_c - A) t^2 / 2`: past an end of the board (`|offset + (a_c - A) T^2 / 2| >
/// L / 2` by `max_time` `T`) the run ends `Unfinished`.
#[must_use]
pub fn disc_on_board_law(p: &DiscOnBoardParams<f64>) -> Law {
    let (big_m, m, g) = (p.board_mass, p.disc_mass, p.gravity);
    let floor = p.mu_floor * (big_m + m) * g;
    let rolling = (p.force - floor) / (big_m + m / 3.0);
    let (outcome, a_board, a_disc) = if p.force <= floor {
        (OutcomeKind::Held, 0.0, 0.0)
    } else if rolling <= 3.0 * p.mu_static * g {
        (OutcomeKind::Rolled, rolling, rolling / 3.0)
    } else {
        (OutcomeKind::Slid, (p.force - p.mu_kinetic * m * g - floor) / big_m, p.mu_kinetic * g)
    };
    let travel = p.offset + 0.5 * (a_disc - a_board) * p.max_time * p.max_time;
    let outcome = if travel.abs() > p.board_length / 2.0 { OutcomeKind::Unfinished } else { outcome };
    Law {
        outcome: Some(outcome),
        lower_acceleration: Some(a_board),
        upper_acceleration: Some(a_disc),
        text: "Held iff F <= mu_floor (M + m) g; else Rolled at A = (F - mu_floor (M + m) g) / (M + m / 3), \
               a_disc = A / 3, iff A <= 3 mu_s g; else Slid: a_disc = mu_k g; Unfinished once the rim's point \
               passes an end of the board",
    }
}

/// The scene's measured quantities in words, beside the law's where it gives them.
fn measured_text(spec: &SceneParams, m: &Measured, law: Option<&Law>) -> String {
    let of = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |v| format!("{v:.6}"));
    let lower = law.and_then(|l| l.lower_acceleration);
    let upper = law.and_then(|l| l.upper_acceleration);
    match spec.kind() {
        SceneKind::BlockOnBlock => format!(
            "acceleration in full contact: bottom block {} m/s^2 (law {}), top block {} m/s^2 (law {})",
            of(m.acceleration_m_s2),
            of(lower),
            of(m.top_acceleration_m_s2),
            of(upper)
        ),
        SceneKind::DiscOnBoard => format!(
            "acceleration while touching: board {} m/s^2 (law {}), disc centre {} m/s^2 (law {})",
            of(m.acceleration_m_s2),
            of(lower),
            of(m.top_acceleration_m_s2),
            of(upper)
        ),
        SceneKind::Tablecloth => format!(
            "block displacement {} m (the law's accelerations in full contact: board {} m/s^2, block {} m/s^2)",
            of(m.block_displacement_m),
            of(lower),
            of(upper)
        ),
        _ => format!(
            "largest point speed {} m/s",
            m.max_speed_m_s.map_or_else(|| "-".to_string(), |v| format!("{v:.3e}"))
        ),
    }
}

/// `host-sim scene` for a scene of several bodies: one run in the core, summarised beside the
/// laws of `docs/scenes.md`.
///
/// # Errors
/// Invalid parameters, or Ctrl-C.
pub fn summarise(spec: &SceneParams, precision: Precision) -> anyhow::Result<String> {
    use std::fmt::Write as _;
    let bar = progress::bar(spec.steps() as u64, "steps");
    let run = run_core(spec, precision, false, Some(&bar))?;
    bar.finish_and_clear();
    let law = law(spec);
    let mut out = String::new();
    let params: Vec<String> = spec.fields().map(|(k, v)| format!("{k} = {v}")).collect();
    let _ = writeln!(out, "scene {}: {}", spec.kind(), params.join(", "));
    let _ = writeln!(out, "{}: outcome {} at t = {:.3} s", run.label, run.outcome, run.end_time);
    if let Some(law) = &law {
        let predicted =
            law.outcome.map_or_else(|| "undecided (at its threshold)".to_string(), |o| o.to_string());
        let _ = writeln!(out, "law: {predicted} ({})", law.text);
    }
    let _ = writeln!(out, "{}", measured_text(spec, &run.measured, law.as_ref()));
    let c = &run.counters;
    let _ = writeln!(
        out,
        "steps {}, pivots {} (mean {:.4}/step, max {}), warm basis solved {} steps directly, most active contacts {} (LCP of {} rows, the full form)",
        run.steps,
        c.pivots,
        c.pivots as f64 / run.steps.max(1) as f64,
        c.max_pivots,
        c.warm_direct,
        c.max_active,
        c.lcp_rows
    );
    if run.checksum.is_some() {
        let _ = writeln!(out, "{}", rule_text(c));
    }
    if let Some(warning) = crate::scenes::friction_warning(spec, precision) {
        let _ = writeln!(out, "{warning}");
    }
    if let Some(sum) = run.checksum {
        let _ = writeln!(out, "checksum {sum:08x}");
    }
    Ok(out)
}

/// One implementation's part of a [`BodiesSummary`].
#[derive(Debug, Clone, Serialize)]
pub struct BodiesImplementation {
    /// Who computed it.
    pub implementation: String,
    /// How it ended.
    pub outcome: OutcomeKind,
    /// Why it failed, if it did.
    pub outcome_detail: Option<String>,
    /// Simulated time at the end (s).
    pub end_time_s: f64,
    /// Steps.
    pub steps: u64,
    /// The scene's measured quantities.
    pub measured: Measured,
    /// Solver counters.
    pub counters: BodiesCounters,
    /// Wall-clock time of the run (s).
    pub wall_time_s: f64,
    /// Host ns per step (recording included).
    pub ns_per_step: f64,
}

impl BodiesImplementation {
    fn of(run: &BodiesRun, wall_s: f64) -> Self {
        Self {
            implementation: run.label.clone(),
            outcome: run.outcome.class,
            outcome_detail: run.outcome.detail.clone(),
            end_time_s: run.end_time,
            steps: run.steps,
            measured: run.measured,
            counters: run.counters,
            wall_time_s: wall_s,
            ns_per_step: 1e9 * wall_s / run.steps.max(1) as f64,
        }
    }
}

/// Core against reference.
#[derive(Debug, Clone, Serialize)]
pub struct BodiesComparison {
    /// Same outcome class.
    pub same_outcome: bool,
    /// Largest distance between the same body's centres of mass over the steps both have (m).
    pub max_position_deviation_m: f64,
    /// Largest angle difference (rad).
    pub max_angle_deviation_rad: f64,
    /// Steps compared.
    pub compared_steps: usize,
}

/// The law's part of a [`BodiesSummary`].
#[derive(Debug, Clone, Serialize)]
pub struct LawSummary {
    /// The outcome it predicts (`None` at its threshold).
    pub outcome: Option<OutcomeKind>,
    /// The lower body's acceleration (m/s^2).
    pub lower_acceleration_m_s2: Option<f64>,
    /// The upper body's (m/s^2).
    pub upper_acceleration_m_s2: Option<f64>,
}

/// One run of a scene of several bodies, core and reference: its `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct BodiesSummary {
    /// The run's folder name.
    pub name: String,
    /// Which scene.
    pub scene: SceneKind,
    /// Every parameter (core names, SI units).
    pub parameters: serde_json::Map<String, serde_json::Value>,
    /// The core's run.
    pub core: BodiesImplementation,
    /// The reference's run.
    pub reference: BodiesImplementation,
    /// Core against reference.
    pub comparison: BodiesComparison,
    /// What `docs/scenes.md`'s laws say.
    pub law: Option<LawSummary>,
}

/// Writes a run's trajectory: `t`, then each body's `x, y, theta, vx, vy, omega` (body 0 the
/// lowest).
fn write_trajectory(run: &BodiesRun, path: &std::path::Path) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let bodies = run.rows.first().map_or(0, |r| r.q.len());
    let mut header = String::from("t");
    for b in 0..bodies {
        for name in ["x", "y", "theta", "vx", "vy", "omega"] {
            let _ = write!(header, ",{name}{b}");
        }
    }
    let lines = run.rows.iter().map(|r| {
        let mut line = format!("{}", r.t);
        for (q, v) in r.q.iter().zip(&r.v) {
            for x in q.iter().chain(v) {
                let _ = write!(line, ",{x}");
            }
        }
        line
    });
    crate::output::write_lines(path, &header, lines)
}

/// Body `i`'s name in `docs/scenes.md`'s words.
fn body_name(kind: SceneKind, i: usize) -> String {
    match (kind, i) {
        (SceneKind::BlockOnBlock, 0) => "bottom block".into(),
        (SceneKind::BlockOnBlock, _) => "top block".into(),
        (SceneKind::Tablecloth | SceneKind::DiscOnBoard, 0) => "board".into(),
        (SceneKind::Tablecloth, _) => "block".into(),
        (SceneKind::DiscOnBoard, _) => "disc".into(),
        (_, 0) => "block 1 (bottom)".into(),
        _ => format!("block {}", i + 1),
    }
}

/// One series per body and run of `quantity` over time: the first run's solid, the others'
/// dashed, each body in the same colour in every run.
fn body_series(runs: &[&BodiesRun], quantity: &str, value: impl Fn(&BodiesRow, usize) -> f64) -> Vec<Series> {
    let bodies = runs.first().map_or(0, |r| r.last.q.len());
    let mut series = Vec::new();
    for (k, run) in runs.iter().enumerate() {
        for body in 0..bodies {
            series.push(Series {
                label: format!("{} {quantity} ({})", body_name(run.scene, body), run.label),
                points: run.rows.iter().map(|r| (r.t, value(r, body))).collect(),
                dashed: k > 0,
            });
        }
    }
    series
}

/// A run's plots in `dir`: every body's position (`positions.svg`: `x`, and `y` in a second
/// panel), velocity (`velocities.svg`: `vx`, `vy`) and angle (`angles.svg`) over time, core
/// solid, reference dashed.
fn write_plots(name: &str, runs: &[&BodiesRun], dir: &std::path::Path) -> anyhow::Result<()> {
    let legend = SeriesLabelPosition::UpperLeft;
    for (file, title, panels) in [
        ("positions.svg", "positions", [("x (m)", 0, "x"), ("y (m)", 1, "y")]),
        ("velocities.svg", "velocities", [("vx (m/s)", 3, "vx"), ("vy (m/s)", 4, "vy")]),
    ] {
        let panels = panels.map(|(axis, index, quantity)| {
            let series =
                body_series(runs, quantity, |r, b| if index < 3 { r.q[b][index] } else { r.v[b][index - 3] });
            (axis, series, legend.clone())
        });
        plot::panels(&dir.join(file), &format!("{name}: {title}"), "t (s)", &panels)?;
    }
    let angles = body_series(runs, "angle", |r, b| r.q[b][2].to_degrees());
    plot::lines(
        &dir.join("angles.svg"),
        &format!("{name}: angles"),
        ("t (s)", "angle (deg)"),
        &angles,
        false,
        &legend,
    )
}

/// `host-sim run` for scenes of several bodies: each in the core (`precision`) beside the
/// independent reference, each body's trajectory as CSV (`core.csv`, `reference.csv`), its plots
/// (`write_plots`), its `summary.json`, and `summary.json` over all runs under `out`.
///
/// # Errors
/// Invalid parameters (before anything runs), Ctrl-C, or I/O.
pub fn run_all(
    specs: &[(String, SceneParams)],
    precision: Precision,
    out: &std::path::Path,
) -> anyhow::Result<String> {
    use std::fmt::Write as _;
    let timed = |f: &dyn Fn() -> anyhow::Result<BodiesRun>| {
        let start = std::time::Instant::now();
        f().map(|r| (r, start.elapsed().as_secs_f64()))
    };
    crate::output::create_dir(out)?;
    let mut summaries = Vec::new();
    let mut text = String::new();
    for (name, spec) in specs {
        let (core, reference) = rayon::join(
            || timed(&|| run_core(spec, precision, true, None)),
            || timed(&|| run_reference(spec, true)),
        );
        let ((core, core_s), (reference, reference_s)) = (core?, reference?);
        let (dev_q, dev_angle) = max_deviation(&core, &reference);
        let law = law(spec);
        let summary = BodiesSummary {
            name: name.clone(),
            scene: spec.kind(),
            parameters: crate::output::parameters_json(spec),
            core: BodiesImplementation::of(&core, core_s),
            reference: BodiesImplementation::of(&reference, reference_s),
            comparison: BodiesComparison {
                same_outcome: core.outcome.class == reference.outcome.class,
                max_position_deviation_m: dev_q,
                max_angle_deviation_rad: dev_angle,
                compared_steps: core.rows.len().min(reference.rows.len()).saturating_sub(1),
            },
            law: law.as_ref().map(|l| LawSummary {
                outcome: l.outcome,
                lower_acceleration_m_s2: l.lower_acceleration,
                upper_acceleration_m_s2: l.upper_acceleration,
            }),
        };
        let dir = out.join(name);
        crate::output::create_dir(&dir)?;
        write_trajectory(&core, &dir.join("core.csv"))?;
        write_trajectory(&reference, &dir.join("reference.csv"))?;
        write_plots(name, &[&core, &reference], &dir)?;
        crate::output::write_json(&dir.join("summary.json"), &summary)?;
        for run in [&core, &reference] {
            let _ = writeln!(
                text,
                "{name}: {:<14} {:<10} t = {:.3} s, {} steps; {}",
                run.label,
                run.outcome.to_string(),
                run.end_time,
                run.steps,
                measured_text(spec, &run.measured, law.as_ref())
            );
        }
        if let Some(law) = &law {
            let predicted = law.outcome.map_or_else(|| "undecided".to_string(), |o| o.to_string());
            let _ = writeln!(text, "{name}: law {predicted} ({})", law.text);
        }
        if let Some(warning) = crate::scenes::friction_warning(spec, precision) {
            let _ = writeln!(text, "{name}: {warning}");
        }
        let _ = writeln!(
            text,
            "{name}: core vs reference: max position deviation {dev_q:.3e} m, max angle deviation {dev_angle:.3e} rad{}",
            if summary.comparison.same_outcome { "" } else { "  OUTCOMES DIFFER" }
        );
        let _ = writeln!(
            text,
            "{name}: the reference found {} steps whose LCP has solutions that move the bodies differently; both take the least kinetic energy after the step (docs/formulation.md, \"One answer: the rule\")",
            reference.counters.ambiguous_steps
        );
        let _ = writeln!(text, "{name}: {}", rule_text(&core.counters));
        summaries.push(summary);
    }
    crate::output::write_json(&out.join("summary.json"), &serde_json::json!({ "runs": summaries }))?;
    let _ = writeln!(
        text,
        "files in {} (each run: core.csv, reference.csv, positions.svg, velocities.svg, angles.svg, summary.json)",
        out.display()
    );
    Ok(text)
}
