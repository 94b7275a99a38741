//! `cargo bench -p meterstick-tests --features rapier --bench rapier`: the same meter-stick scene
//! stepped by `rapier2d` and by the core, in one process, side by side.
//!
//! The rapier scene: the rod is a dynamic cuboid (L x t, mass m), the fingers are kinematic
//! (velocity-based) balls of diameter `finger_width` whose tops touch the rod's bottom face;
//! finger 1 moves at v toward finger 2 and stops `finger_width` from it. Step h = 1 ms, gravity
//! g, restitution 0. Rapier has one Coulomb coefficient per contact (no static/kinetic pair), so
//! it gets mu_k; contact recycling (on by default: a pair that moved less than a threshold
//! keeps its previous contacts) is turned off for honest contacts. Each engine runs the slow
//! scene to its outcome; run time is the median over repeats of the stepping loop alone.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::print_stderr, missing_docs)]

use std::fmt::Write as _;
use std::time::Instant;

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
