//! `cargo bench -p meterstick-tests --features rapier --bench rapier`: the same meter-stick scene,
//! then the same 3-block stack, stepped by `rapier2d` and by the core, in one process, side by side.
//!
//! The rapier scene: the rod is a dynamic cuboid (L x t, mass m), the fingers are kinematic
//! (velocity-based) balls of diameter `finger_width` whose tops touch the rod's bottom face;
//! finger 1 moves at v toward finger 2 and stops `finger_width` from it. Step h = 1 ms, gravity
//! g, restitution 0. Rapier has one Coulomb coefficient per contact (no static/kinetic pair), so
//! it gets mu_k; contact recycling (on by default: a pair that moved less than a threshold
//! keeps its previous contacts) is turned off for honest contacts. Each engine runs the slow
//! scene to its outcome; run time is the median over repeats of the stepping loop alone.
//!
//! Then the 3-block stack over a table's edge (`docs/scenes.md`, "stack"; the core's `Stack3`):
//! in rapier the blocks are dynamic cuboids (L x hb, mass m each, never asleep), the table a fixed
//! cuboid whose top-right corner is the edge at (0, 0), each block where the core's `Stack3`
//! starts it (harmonic offsets scaled by the overhang s, read from its stepper). Every collider has friction mu_s (rapier has one coefficient; the
//! stack's default mu_k equals its mu_s) and the `Min` combine rule (the pair's coefficient is mu_s), restitution 0; gravity, h and the duration are `StackParams`' defaults,
//! rapier's solver its defaults, contact recycling off. The same judge for both engines: a block
//! whose centre drops more than `drop_limit` below its start or tilts beyond `tilt_limit` fell;
//! all standing after `max_time` held. Run time: the median over repeats of the held stack at
//! s = 0.98 (every step of the duration); the outcome at s = 0.98 and s = 1.02 from one run each.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::print_stderr, missing_docs)]

use std::fmt::Write as _;
use std::time::Instant;

use meterstick_core::Real;
use meterstick_core::RunStats;
use meterstick_core::multibody::scenes::{MultibodyScene as _, Stack3, StackParams};
use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};
use rapier2d::prelude::*;

const REPEATS: usize = 7;

fn params() -> MeterStickParams<f32> {
    MeterStickParams { finger1_x: -0.35, ..MeterStickParams::paper() }
}

struct End {
    outcome: &'static str,
    time: f32,
    steps: u64,
    meeting_offset: Option<f32>,
    ns_per_step: f64,
}

fn core_run(p: &MeterStickParams<f32>) -> End {
    let mut s = MeterStick6::<f32, 64>::new(*p).unwrap();
    let start = Instant::now();
    let outcome = s.run(|_| {});
    let ns = start.elapsed().as_nanos() as f64;
    let steps = s.stats().steps;
    End {
        outcome: match outcome {
            Outcome::Balanced => "Balanced",
            Outcome::Fell => "Fell",
            _ => "other",
        },
        time: s.time(),
        steps,
        meeting_offset: s.meeting().map(|m| m.com_offset),
        ns_per_step: ns / steps as f64,
    }
}

fn rapier_run(p: &MeterStickParams<f32>) -> End {
    let mut world = PhysicsWorld { gravity: Vector::new(0.0, -p.gravity), ..Default::default() };
    world.integration_parameters.dt = p.step;
    world.integration_parameters.contact_recycling = false;
    let (hl, ht) = (p.rod_length / 2.0, p.rod_thickness / 2.0);
    let (rod, _) = world.insert(
        RigidBodyBuilder::dynamic().translation(Vector::new(0.0, ht)).can_sleep(false),
        ColliderBuilder::cuboid(hl, ht)
            .density(p.rod_mass / (p.rod_length * p.rod_thickness))
            .friction(p.mu_kinetic)
            .restitution(0.0),
    );
    let r = p.finger_width / 2.0;
    let finger = |world: &mut PhysicsWorld, x: f32| {
        world
            .insert(
                RigidBodyBuilder::kinematic_velocity_based().translation(Vector::new(x, -r)),
                ColliderBuilder::ball(r).friction(p.mu_kinetic).restitution(0.0),
            )
            .0
    };
    let f1 = finger(&mut world, p.finger1_x);
    let f2 = finger(&mut world, p.finger2_x);
    let y0 = ht;
    let (mut steps, mut meeting, mut met_at) = (0u64, None, None::<f32>);
    let start = Instant::now();
    let outcome = loop {
        let x1 = world.bodies[f1].translation().x;
        let x2 = world.bodies[f2].translation().x;
        let room = (x2 - x1 - p.finger_width).max(0.0);
        let v = (p.finger1_velocity * p.step).min(room) / p.step;
        world.bodies[f1].set_linvel(Vector::new(v, 0.0), true);
        world.step();
        steps += 1;
        let t = steps as f32 * p.step;
        let body = &world.bodies[rod];
        let (pos, angle) = (body.translation(), body.rotation().angle());
        if meeting.is_none() && v < p.finger1_velocity {
            meeting = Some(pos.x - f32::midpoint(x1, x2));
            met_at = Some(t);
        }
        if angle.abs() > p.tilt_limit || pos.y < y0 - p.drop_limit {
            break "Fell";
        }
        if met_at.is_some_and(|m| t - m >= p.hold_time) {
            break "Balanced";
        }
        if t >= p.max_time {
            break "Unfinished";
        }
    };
    let ns = start.elapsed().as_nanos() as f64;
    End {
        outcome,
        time: steps as f32 * p.step,
        steps,
        meeting_offset: meeting.map(|m| -m),
        ns_per_step: ns / steps as f64,
    }
}

/// The overhang scales whose outcome both engines report: just under and just over the critical
/// stack (`s = 1`).
const OVERHANGS: [f64; 2] = [0.98, 1.02];

/// The timed run: the held stack.
const TIMED_OVERHANG: f64 = 0.98;

/// The end of one stack run.
struct StackEnd {
    outcome: Outcome,
    time: f64,
    ns_per_step: f64,
    /// The core's solver counters (`None` for rapier).
    stats: Option<RunStats>,
}

fn stack_params<T: Real>(overhang: f64) -> StackParams<T> {
    StackParams { overhang: T::of(overhang), ..StackParams::<T>::default() }
}

fn core_stack_run<T: Real>(overhang: f64) -> StackEnd {
    let mut s = Stack3::<T>::new(stack_params::<T>(overhang)).unwrap();
    let start = Instant::now();
    let outcome = s.run(|_| {});
    let ns = start.elapsed().as_nanos() as f64;
    let stats = *s.stepper().stats();
    StackEnd {
        outcome,
        time: s.stepper().time().as_f64(),
        ns_per_step: ns / stats.steps as f64,
        stats: Some(stats),
    }
}

fn rapier_stack_run(overhang: f64) -> StackEnd {
    let p = stack_params::<f32>(overhang);
    let mut world = PhysicsWorld { gravity: Vector::new(0.0, -p.gravity), ..Default::default() };
    world.integration_parameters.dt = p.step;
    world.integration_parameters.contact_recycling = false;
    let (hl, hh) = (p.length / 2.0, p.height / 2.0);
    let collider = |half_x: f32, half_y: f32| {
        ColliderBuilder::cuboid(half_x, half_y)
            .friction(p.mu_static)
            .friction_combine_rule(CoefficientCombineRule::Min)
            .restitution(0.0)
    };
    // The table: its top face y = 0 for x <= 0, its top-right corner the edge (0, 0).
    let table_half = Vector::new(2.0 * p.length, p.length);
    world.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(-table_half.x, -table_half.y)),
        collider(table_half.x, table_half.y),
    );
    // The core's own start (its harmonic offsets scaled by s), read from a fresh `Stack3`.
    let starts = *Stack3::<f32>::new(p).unwrap().stepper().states();
    let blocks = starts.map(|st| {
        world
            .insert(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(st.x, st.y))
                    .rotation(st.theta)
                    .can_sleep(false),
                collider(hl, hh).density(p.mass / (p.length * p.height)),
            )
            .0
    });
    let total = (p.max_time / p.step).round() as u64;
    let mut steps = 0u64;
    let start = Instant::now();
    let outcome = loop {
        world.step();
        steps += 1;
        let fell = blocks.iter().zip(&starts).any(|(&b, st)| {
            let body = &world.bodies[b];
            body.rotation().angle().abs() > p.tilt_limit || st.y - body.translation().y > p.drop_limit
        });
        if fell {
            break Outcome::Fell;
        }
        if steps >= total {
            break Outcome::Held;
        }
    };
    let ns = start.elapsed().as_nanos() as f64;
    StackEnd { outcome, time: steps as f64 * f64::from(p.step), ns_per_step: ns / steps as f64, stats: None }
}

/// One engine's line: the timed runs' median and the outcome at each of [`OVERHANGS`]; for the
/// core, a second line with the timed run's solver counters.
fn stack_line(text: &mut String, name: &str, repeats: usize, run: impl Fn(f64) -> StackEnd) -> f64 {
    let timed: Vec<StackEnd> = (0..repeats).map(|_| run(TIMED_OVERHANG)).collect();
    let stats = timed[0].stats;
    let ns = median(timed.into_iter().map(|e| e.ns_per_step).collect());
    write!(text, "  {name:<26} {ns:>9.1} ns/step").unwrap();
    for s in OVERHANGS {
        let e = run(s);
        let how = if e.outcome == Outcome::Held { "for" } else { "at t =" };
        write!(text, "  s = {s:.2}: {} {how} {:.3} s", e.outcome.name(), e.time).unwrap();
    }
    text.push('\n');
    if let Some(st) = stats {
        writeln!(
            text,
            "    (s = {TIMED_OVERHANG}: warm basis solved {:.0}% of steps without a pivot, {:.2} pivots/step, \
             at most {} active contacts)",
            100.0 * st.warm_starts as f64 / st.steps as f64,
            st.pivots as f64 / st.steps as f64,
            st.most_lcp_contacts.unwrap_or(0)
        )
        .unwrap();
    }
    ns
}

fn stack_section(text: &mut String, repeats: usize) {
    let p = StackParams::<f64>::default();
    writeln!(
        text,
        "3-block stack over a table's edge (L = {} m, hb = {} m, m = {} kg, mu_s = mu_k = {}, g = {} m/s^2, h = {} ms, \
         {} s),\n  fell: a block's centre {} mm below its start or tilted beyond {} rad; ns/step: {repeats} runs each of \
         the held stack at s = {TIMED_OVERHANG}, median:",
        p.length,
        p.height,
        p.mass,
        p.mu_static,
        p.gravity,
        1e3 * p.step,
        p.max_time,
        1e3 * p.drop_limit,
        p.tilt_limit
    )
    .unwrap();
    let c32 = stack_line(text, "meterstick core f32 Stack3", repeats, core_stack_run::<f32>);
    let c64 = stack_line(text, "meterstick core f64 Stack3", repeats, core_stack_run::<f64>);
    let r = stack_line(text, "rapier2d 0.36 (f32)", repeats, rapier_stack_run);
    writeln!(text, "  ratio rapier2d / core: {:.1}x (f32), {:.1}x (f64)", r / c32, r / c64).unwrap();
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` passes nothing: run once, quickly.
    let repeats = if std::env::args().any(|a| a == "--bench") { REPEATS } else { 1 };
    let p = params();
    let mut core_ns = Vec::new();
    let mut rapier_ns = Vec::new();
    let (mut core_end, mut rapier_end) = (None, None);
    for _ in 0..repeats {
        let c = core_run(&p);
        core_ns.push(c.ns_per_step);
        core_end = Some(c);
        let r = rapier_run(&p);
        rapier_ns.push(r.ns_per_step);
        rapier_end = Some(r);
    }
    let (c, r) = (core_end.unwrap(), rapier_end.unwrap());
    let (cm, rm) = (median(core_ns), median(rapier_ns));
    let mut text = format!(
        "meter-stick slow scene (v = 0.1 m/s, x1 = -0.35 m, h = 1 ms), {repeats} runs each, median, on {}:\n",
        machine()
    );
    for (name, e, ns) in [("meterstick core f32 6x6", &c, cm), ("rapier2d 0.36 (f32)", &r, rm)] {
        writeln!(
            text,
            "  {name:<24} {:>9.1} ns/step  {:>6} steps  ends {} at t = {:.3} s, COM {} from the fingers' midpoint at the meeting",
            ns,
            e.steps,
            e.outcome,
            e.time,
            e.meeting_offset.map_or_else(|| "-".to_string(), |m| format!("{:+.2} mm", 1e3 * m))
        )
        .unwrap();
    }
    writeln!(text, "  ratio rapier2d / core: {:.1}x", rm / cm).unwrap();
    stack_section(&mut text, repeats);
    print!("{text}");
    // For `host-sim report` (its "Performance" section includes this file when present).
    if repeats > 1 {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../out/bench");
        let written = std::fs::create_dir_all(&dir)
            .and_then(|()| std::fs::write(dir.join("rapier.md"), format!("```text\n{text}```\n")));
        if let Err(e) = written {
            eprintln!("could not write {}: {e}", dir.join("rapier.md").display());
        }
    }
}

/// The CPU model and the number of cores, from `/proc/cpuinfo` where it exists.
fn machine() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = info
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name").and_then(|r| r.split_once(':')).map(|(_, m)| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(0, std::num::NonZero::get);
    format!("{model}, {cores} cores")
}
