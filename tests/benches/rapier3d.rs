//! `cargo bench -p meterstick-tests --features rapier3d --bench rapier3d`: the puck on an incline
//! and the billiard ball, stepped by `rapier3d` 0.36 (f32) and by the core (f32), in one process,
//! side by side; the curling stone's terminal ratio in both; then the anisotropy of both (issue
//! #44, item 3). The planar peer is
//! `tests/benches/rapier.rs`; this file follows it.
//!
//! The core: `meterstick_core::scene::spatial::{Puck, Billiard}` at their defaults
//! (`core/src/scene/spatial/puck.rs`, `billiard.rs`; `docs/scenes.md`, "puck" and "billiard"),
//! Coulomb's circular cone, stepped until the scene's own outcome (the contact sticks: Stopped,
//! Rolled) or `max_time`.
//!
//! Rapier: one world per run, gravity `(0, 0, -g)`, `dt` the scene's step, contact recycling off
//! (as `tests/benches/rapier.rs`: a pair that moved less than a threshold would keep its previous
//! contacts), restitution 0, bodies never asleep, the solver and the friction model rapier's
//! defaults (`FrictionModel::Simplified`: one Coulomb friction constraint per manifold, its 2-D
//! tangent impulse clamped to a disc, plus a twist constraint). Rapier has one friction
//! coefficient per contact (no static/kinetic pair): every collider gets `mu_k` (equal to `mu_s`
//! at both scenes' defaults) and the pair's combined coefficient is that `mu`.
//! - The plane: a fixed cuboid (20 m x 20 m x 1 m) turned by `-alpha` about `x` so that its top
//!   face is the core's plane through the origin with normal `(0, sin alpha, cos alpha)`.
//! - The puck, two ways, each one contact region (one manifold) with the plane:
//!   **cylinder**, rapier's own cylinder (radius `r`, thickness `t`, mass `m`, its axis along the
//!   plane's normal, its face on the plane: a face contact, several points in one manifold; its
//!   centre of mass `t/2` above the plane where the core's is on it, so friction also tips it and
//!   the face's points carry that); and **ball, rotations locked**: a ball of radius `r` (mass
//!   `m`) with `lock_rotations()`, one contact point under its centre, the nearest rapier comes to
//!   the core's puck (one point contact whose friction has no torque about the centre of mass).
//!   Launched at the core's velocity, `speed (cos phi e_x + sin phi e_down)`.
//!   Stopped: its speed at most the core's `stick_speed` (1e-5 m/s) after a step.
//! - The ball: rapier's ball (radius `R`, mass `m`, so the moment `2 m R^2 / 5`), centre at
//!   `(0, 0, R)`, the core's velocity and spin. Rolled: after the first step whose slip
//!   `|v + omega x (-R z)|` is at most `stick_speed` or no smaller than the step before's (rapier's
//!   slip stops falling near 2 mm/s at the defaults, never reaching the core's 1e-5 m/s: its
//!   friction is no longer saturated); its velocity then is its rolling velocity, and its slip
//!   then is printed.
//!
//! Run time: the median over 15 repeats of the stepping loop alone (building the world or the
//! scene excluded), in ns per step, to each run's own end; the engines' runs interleaved, one of
//! each per round, so that the shared machine's load falls on all of them alike.
//!
//! Anisotropy, measured the same way in both: the puck launched on a level table (`alpha = 0`) at
//! 16 headings `phi = 0, 22.5, ... 337.5` degrees, each run to its stop; the spread of the
//! stopping distance (max - min over the mean; the closed form is `speed^2 / (2 mu g)` at every
//! heading) and the largest error of the final displacement's direction against `phi`. Then the
//! billiard ball's rolling velocity against the 5/7 law `v = (5 v0 + 2 R omega0 x z) / 7`
//! (`docs/scenes.md`, "billiard") at the defaults (no spin) and struck with side and back spin.
//! Last, the 3-block stack at headings to the table's edge: rapier3d's and the core's outcomes and
//! ns per step, their ratio on the held stack, and the reference's outcomes (`rapier3d/stack.rs`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::print_stderr, missing_docs)]

use std::f32::consts::PI;
use std::fmt::Write as _;
use std::time::Instant;

use meterstick_core::scene::Outcome;
use meterstick_core::scene::spatial::{
    Billiard, BilliardParams, Curling, CurlingParams, Puck, PuckParams, SpatialScene,
};
use rapier3d::prelude::*;

#[path = "rapier3d/stack.rs"]
mod stack;

/// Rounds of the timed runs (each run is short: 1,417 steps of the puck, 292 of the ball).
const REPEATS: usize = 15;

/// The anisotropy runs' headings: 16, every 22.5 degrees.
const HEADINGS: usize = 16;

/// How rapier models the puck (see the module doc).
#[derive(Clone, Copy)]
enum PuckShape {
    Cylinder,
    LockedBall,
}

impl PuckShape {
    const fn name(self) -> &'static str {
        match self {
            Self::Cylinder => "cylinder",
            Self::LockedBall => "ball, rotations locked",
        }
    }
}

/// The end of one run: its outcome, time, steps, ns per step of the stepping loop, and its final
/// measure (the puck's displacement in the plane `(across, down)`; the ball's velocity `(x, y)`
/// when it rolled).
struct End {
    outcome: &'static str,
    time: f32,
    steps: u64,
    ns_per_step: f64,
    measure: [f32; 2],
    /// Rapier's contact points with the plane after the first step (the core: 1).
    points: usize,
    /// The ball's slip `|v + omega x (-R z)|` when it rolled (the core's: below `stick_speed`).
    slip: f32,
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn v3(a: [f32; 3]) -> Vector {
    Vector::new(a[0], a[1], a[2])
}

fn outcome_name(o: Option<Outcome>) -> &'static str {
    match o {
        Some(Outcome::Stopped) => "Stopped",
        Some(Outcome::Rolled) => "Rolled",
        Some(Outcome::Slid) => "Slid",
        Some(Outcome::Unfinished) => "Unfinished",
        Some(_) => "other",
        None => "-",
    }
}

fn core_puck(p: PuckParams<f32>) -> End {
    let mut s = Puck::<f32>::new(p).unwrap();
    let start = Instant::now();
    while s.step().is_some() {}
    let ns = start.elapsed().as_nanos() as f64;
    let stepper = s.run().stepper();
    let steps = s.run().stats().steps;
    let (e_x, e_down) = p.plane_axes();
    let at = stepper.state().position;
    End {
        outcome: outcome_name(s.outcome()),
        time: stepper.time(),
        steps,
        ns_per_step: ns / steps as f64,
        measure: [dot(at, e_x), dot(at, e_down)],
        points: 1,
        slip: 0.0,
    }
}

fn core_ball(p: BilliardParams<f32>) -> End {
    let mut s = Billiard::<f32>::new(p).unwrap();
    let start = Instant::now();
    while s.step().is_some() {}
    let ns = start.elapsed().as_nanos() as f64;
    let steps = s.run().stats().steps;
    let m = s.measured();
    End {
        outcome: outcome_name(s.outcome()),
        time: s.run().stepper().time(),
        steps,
        ns_per_step: ns / steps as f64,
        measure: [m[1].unwrap_or(f32::NAN), m[2].unwrap_or(f32::NAN)],
        points: 1,
        slip: 0.0,
    }
}

/// The curling stone's end: its outcome, the time both speeds stopped, and `(terminal ratio,
/// spin stop - slide stop in s)`.
fn core_curling(p: CurlingParams<f32>) -> End {
    let mut s = Curling::<f32>::new(p).unwrap();
    let start = Instant::now();
    while s.step().is_some() {}
    let ns = start.elapsed().as_nanos() as f64;
    let steps = s.run().stats().steps;
    let [ratio, slide, spin] = s.measured();
    let (slide, spin) = (slide.unwrap_or(f32::NAN), spin.unwrap_or(f32::NAN));
    End {
        outcome: outcome_name(s.outcome()),
        time: s.run().stepper().time(),
        steps,
        ns_per_step: ns / steps as f64,
        measure: [ratio.unwrap_or(f32::NAN), spin - slide],
        points: p.count().unwrap_or(0),
        slip: 0.0,
    }
}

/// A world of the scene's step and gravity, contact recycling off.
fn world(step: f32, gravity: f32) -> PhysicsWorld {
    let mut w = PhysicsWorld { gravity: Vector::new(0.0, 0.0, -gravity), ..Default::default() };
    w.integration_parameters.dt = step;
    w.integration_parameters.contact_recycling = false;
    w
}

/// The plane through the origin, turned by `-angle` about `x` (normal `(0, sin, cos)`), friction
/// `mu`; its collider.
fn plane(w: &mut PhysicsWorld, angle: f32, mu: f32) -> ColliderHandle {
    let half = Vector::new(10.0, 10.0, 0.5);
    let (s, c) = angle.sin_cos();
    let centre = Vector::new(0.0, s, c) * -half.z;
    w.insert(
        RigidBodyBuilder::fixed().translation(centre).rotation(Vector::new(-angle, 0.0, 0.0)),
        ColliderBuilder::cuboid(half.x, half.y, half.z).friction(mu).restitution(0.0),
    )
    .1
}

/// The contact points between two colliders.
fn points(w: &PhysicsWorld, a: ColliderHandle, b: ColliderHandle) -> usize {
    w.narrow_phase.contact_pair(a, b).map_or(0, |pair| pair.manifolds().iter().map(|m| m.points.len()).sum())
}

fn rapier_puck(p: PuckParams<f32>, shape: PuckShape) -> End {
    let mut w = world(p.step, p.gravity);
    let mu = p.mu_kinetic;
    let table = plane(&mut w, p.angle, mu);
    let (e_x, e_down) = p.plane_axes();
    let (s, c) = p.angle.sin_cos();
    let normal = Vector::new(0.0, s, c);
    let (sh, ch) = p.heading.sin_cos();
    let velocity = (v3(e_x) * ch + v3(e_down) * sh) * p.speed;
    let body = RigidBodyBuilder::dynamic()
        .rotation(Vector::new(-p.angle, 0.0, 0.0))
        .linvel(velocity)
        .can_sleep(false);
    let (body, collider) = match shape {
        PuckShape::Cylinder => w.insert(
            body.translation(normal * (p.thickness / 2.0)),
            // Parry's cylinder stands along its local y: turned to the body's z.
            ColliderBuilder::cylinder(p.thickness / 2.0, p.radius)
                .rotation(Vector::new(PI / 2.0, 0.0, 0.0))
                .density(p.mass / (PI * p.radius * p.radius * p.thickness))
                .friction(mu)
                .restitution(0.0),
        ),
        PuckShape::LockedBall => w.insert(
            body.translation(normal * p.radius).lock_rotations(),
            ColliderBuilder::ball(p.radius)
                .density(p.mass / (4.0 / 3.0 * PI * p.radius.powi(3)))
                .friction(mu)
                .restitution(0.0),
        ),
    };
    let start_at = w.bodies[body].translation();
    let total = (p.max_time / p.step).round() as u64;
    let (mut steps, mut contact_points) = (0u64, 0);
    let start = Instant::now();
    let outcome = loop {
        w.step();
        steps += 1;
        if steps == 1 {
            contact_points = points(&w, table, collider);
        }
        if w.bodies[body].linvel().length() <= p.stick_speed {
            break "Stopped";
        }
        if steps >= total {
            break "Slid";
        }
    };
    let ns = start.elapsed().as_nanos() as f64;
    let moved = w.bodies[body].translation() - start_at;
    End {
        outcome,
        time: steps as f32 * p.step,
        steps,
        ns_per_step: ns / steps as f64,
        measure: [moved.dot(v3(e_x)), moved.dot(v3(e_down))],
        points: contact_points,
        slip: 0.0,
    }
}

fn rapier_ball(p: BilliardParams<f32>) -> End {
    let mut w = world(p.step, p.gravity);
    let table = plane(&mut w, 0.0, p.mu_kinetic);
    let (body, collider) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.0, p.radius))
            .linvel(Vector::new(p.speed, 0.0, 0.0))
            .angvel(Vector::new(p.spin_x, p.spin_y, p.spin_z))
            .can_sleep(false),
        ColliderBuilder::ball(p.radius)
            .density(p.mass / (4.0 / 3.0 * PI * p.radius.powi(3)))
            .friction(p.mu_kinetic)
            .restitution(0.0),
    );
    let down = Vector::new(0.0, 0.0, -p.radius);
    let total = (p.max_time / p.step).round() as u64;
    let (mut steps, mut contact_points, mut last_slip) = (0u64, 0, f32::INFINITY);
    let start = Instant::now();
    let rolled = loop {
        w.step();
        steps += 1;
        if steps == 1 {
            contact_points = points(&w, table, collider);
        }
        let b = &w.bodies[body];
        let slip = (b.linvel() + b.angvel().cross(down)).length();
        // Rapier's slip never falls to `stick_speed` (it settles near 2 mm/s at the defaults):
        // it rolled once the slip stops falling (friction no longer saturated).
        if slip <= p.stick_speed || slip >= last_slip {
            break Some((b.linvel(), slip));
        }
        last_slip = slip;
        if steps >= total {
            break None;
        }
    };
    let ns = start.elapsed().as_nanos() as f64;
    let (v, slip) = rolled.unwrap_or((Vector::splat(f32::NAN), f32::NAN));
    End {
        slip,
        outcome: if rolled.is_some() { "Rolled" } else { "Unfinished" },
        time: steps as f32 * p.step,
        steps,
        ns_per_step: ns / steps as f64,
        measure: [v.x, v.y],
        points: contact_points,
    }
}

/// The curling stone in rapier: its own cylinder (radius `R`, thickness `R / 10`, mass `m`, so
/// the uniform disc's moment `m R^2 / 2` about its axis), face down on a level table, launched at
/// `speed` along `x` spinning at `spin` about `z`. The ratio `v / (R omega)` is read as the core
/// reads it (while both are at least `10 mu g h`); sliding stops when `|v| <= stick_speed`,
/// spinning when `R |omega_z| <= stick_speed`; the run ends when both have, or at `max_time`.
fn rapier_curling(p: CurlingParams<f32>) -> End {
    let mut w = world(p.step, p.gravity);
    let table = plane(&mut w, 0.0, p.mu);
    let thickness = p.radius / 10.0;
    let (body, collider) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.0, thickness / 2.0))
            .linvel(Vector::new(p.speed, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, p.spin))
            .can_sleep(false),
        // Parry's cylinder stands along its local y: turned to the body's z.
        ColliderBuilder::cylinder(thickness / 2.0, p.radius)
            .rotation(Vector::new(PI / 2.0, 0.0, 0.0))
            .density(p.mass / (PI * p.radius * p.radius * thickness))
            .friction(p.mu)
            .restitution(0.0),
    );
    let floor = 10.0 * p.mu * p.gravity * p.step;
    let total = (p.max_time / p.step).round() as u64;
    let (mut steps, mut contact_points) = (0u64, 0);
    let (mut ratio, mut slide, mut spin) = (f32::NAN, None, None);
    let start = Instant::now();
    loop {
        let b = &w.bodies[body];
        let (v, rw) = (b.linvel().truncate().length(), p.radius * b.angvel().z.abs());
        if v >= floor && rw >= floor {
            ratio = v / rw;
        }
        w.step();
        steps += 1;
        if steps == 1 {
            contact_points = points(&w, table, collider);
        }
        let b = &w.bodies[body];
        let t = steps as f32 * p.step;
        if slide.is_none() && b.linvel().truncate().length() <= p.stick_speed {
            slide = Some(t);
        }
        if spin.is_none() && p.radius * b.angvel().z.abs() <= p.stick_speed {
            spin = Some(t);
        }
        if (slide.is_some() && spin.is_some()) || steps >= total {
            break;
        }
    }
    let ns = start.elapsed().as_nanos() as f64;
    End {
        outcome: if slide.is_some() && spin.is_some() { "Stopped" } else { "Slid" },
        time: steps as f32 * p.step,
        steps,
        ns_per_step: ns / steps as f64,
        measure: [ratio, spin.unwrap_or(f32::NAN) - slide.unwrap_or(f32::NAN)],
        points: contact_points,
        slip: 0.0,
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `repeats` rounds of every one of `runs`, interleaved (one run of each per round, so that a
/// change of the shared machine's load falls on all of them): each one's median ns per step and
/// its last run's end.
fn timed<const N: usize>(repeats: usize, runs: [&dyn Fn() -> End; N]) -> [(f64, End); N] {
    let mut ns: [Vec<f64>; N] = std::array::from_fn(|_| Vec::new());
    let mut last: [Option<End>; N] = std::array::from_fn(|_| None);
    for _ in 0..repeats {
        for (k, run) in runs.iter().enumerate() {
            let e = run();
            ns[k].push(e.ns_per_step);
            last[k] = Some(e);
        }
    }
    let mut ns = ns.into_iter();
    last.map(|e| (median(ns.next().unwrap()), e.unwrap()))
}

/// One engine's line; `what` names its measure, printed times `scale` in `unit`.
fn line(text: &mut String, name: &str, ns: f64, e: &End, (what, scale, unit): (&str, f32, &str)) {
    writeln!(
        text,
        "  {name:<42} {ns:>8.1} ns/step  {:>5} steps  ends {} at t = {:.3} s, {what} ({:+.4}, {:+.4}) {unit}{}",
        e.steps,
        e.outcome,
        e.time,
        scale * e.measure[0],
        scale * e.measure[1],
        if e.points == 1 { String::new() } else { format!(", {} contact points", e.points) }
    )
    .unwrap();
}

/// The puck's measure in [`line`]: its displacement in mm.
const MOVED: (&str, f32, &str) = ("moved", 1e3, "mm");

/// The ball's measure in [`line`]: its rolling velocity in m/s.
const ROLLING: (&str, f32, &str) = ("rolling at", 1.0, "m/s");

/// The side-by-side table's rows: a quantity, the core's figure, rapier3d's.
type Rows = Vec<[String; 3]>;

fn speed_section(text: &mut String, table: &mut Rows, repeats: usize) {
    let p = PuckParams::<f32>::default();
    writeln!(
        text,
        "puck on an incline (defaults: r = {} m, t = {} m, m = {} kg, alpha = {:.0} deg, heading {:.0} deg, \
         speed {} m/s, mu = {}, h = {} ms), {repeats} runs each, median;\n  ends at its stop (the core: its contact \
         sticks; rapier: |v| <= {} m/s) or {} s; displacement (across, down the slope):",
        p.radius,
        p.thickness,
        p.mass,
        p.angle.to_degrees(),
        p.heading.to_degrees(),
        p.speed,
        p.mu_kinetic,
        1e3 * p.step,
        p.stick_speed,
        p.max_time
    )
    .unwrap();
    let [(core, c), cylinder, ball] = timed(
        repeats,
        [&|| core_puck(p), &|| rapier_puck(p, PuckShape::Cylinder), &|| {
            rapier_puck(p, PuckShape::LockedBall)
        }],
    );
    line(text, "meterstick core f32 Puck", core, &c, MOVED);
    let (mut ratios, mut figures) = (Vec::new(), Vec::new());
    for (shape, (ns, e)) in [(PuckShape::Cylinder, cylinder), (PuckShape::LockedBall, ball)] {
        line(text, &format!("rapier3d 0.36 (f32), {}", shape.name()), ns, &e, MOVED);
        ratios.push(format!("{:.1}x ({})", ns / core, shape.name()));
        figures.push(format!("{ns:.0} ({})", shape.name()));
    }
    let ratios = ratios.join(", ");
    writeln!(text, "  ratio rapier3d / core: {ratios}").unwrap();
    table.push([
        "puck on an incline (defaults), ns/step".into(),
        format!("{core:.0}"),
        format!("{}; ratio {ratios}", figures.join(", ")),
    ]);

    let b = BilliardParams::<f32>::default();
    writeln!(
        text,
        "billiard ball (defaults: R = {} m, m = {} kg, struck at {} m/s along x, no spin, mu = {}, h = {} ms), \
         {repeats} runs each, median;\n  ends when it rolls (the core: its contact sticks; rapier: slip <= {} m/s or no longer falling):",
        b.radius,
        b.mass,
        b.speed,
        b.mu_kinetic,
        1e3 * b.step,
        b.stick_speed
    )
    .unwrap();
    let [(core, c), (ns, e)] = timed(repeats, [&|| core_ball(b), &|| rapier_ball(b)]);
    line(text, "meterstick core f32 Billiard", core, &c, ROLLING);
    line(text, "rapier3d 0.36 (f32), ball", ns, &e, ROLLING);
    writeln!(text, "  ratio rapier3d / core: {:.1}x", ns / core).unwrap();
    table.push([
        "billiard ball (defaults), ns/step".into(),
        format!("{core:.0}"),
        format!("{ns:.0}; ratio {:.1}x", ns / core),
    ]);
}

/// The puck's anisotropy on a level table: `(spread of the stopping distance, largest direction
/// error in degrees, mean distance)` over [`HEADINGS`] launches.
fn anisotropy(run: impl Fn(PuckParams<f32>) -> End) -> (f64, f64, f64) {
    let mut distances = Vec::new();
    let mut worst = 0.0f64;
    for k in 0..HEADINGS {
        let heading = 2.0 * std::f64::consts::PI * k as f64 / HEADINGS as f64;
        let p = PuckParams::<f32> { angle: 0.0, heading: heading as f32, ..PuckParams::default() };
        let e = run(p);
        if e.outcome != "Stopped" {
            eprintln!("heading {:.1} deg: {} at t = {:.3} s", heading.to_degrees(), e.outcome, e.time);
        }
        let [x, y] = e.measure.map(f64::from);
        distances.push(x.hypot(y));
        // The error of the direction, wrapped to [-pi, pi).
        let error = (y.atan2(x) - heading + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        worst = worst.max(error.abs().to_degrees());
    }
    let mean = distances.iter().sum::<f64>() / distances.len() as f64;
    let (lo, hi) =
        distances.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &d| (l.min(d), h.max(d)));
    ((hi - lo) / mean, worst, mean)
}

/// The 5/7 law's rolling velocity `(5 v0 + 2 R omega0 x z) / 7`, `(x, y)`.
fn five_sevenths(b: &BilliardParams<f32>) -> [f64; 2] {
    let (v0, r) = (f64::from(b.speed), f64::from(b.radius));
    // omega0 x z = (spin_y, -spin_x, 0).
    // `+ 0.0`: no negative zero printed.
    [(5.0 * v0 + 2.0 * r * f64::from(b.spin_y)) / 7.0, -2.0 * r * f64::from(b.spin_x) / 7.0 + 0.0]
}

fn anisotropy_section(text: &mut String, table: &mut Rows) {
    let p = PuckParams::<f32>::default();
    let closed = f64::from(p.speed).powi(2) / (2.0 * f64::from(p.mu_kinetic) * f64::from(p.gravity));
    writeln!(
        text,
        "anisotropy: the puck on a level table at {HEADINGS} headings (0, 22.5, ... 337.5 deg), speed {} m/s, \
         mu = {}: the spread (max - min) / mean of its stopping distance (closed form {:.2} mm at every heading) \
         and the largest error of its final direction against its heading:",
        p.speed,
        p.mu_kinetic,
        1e3 * closed
    )
    .unwrap();
    let core = anisotropy(core_puck);
    let rows = [
        ("meterstick core f32 Puck (circular cone)", core),
        ("rapier3d 0.36 (f32), cylinder", anisotropy(|p| rapier_puck(p, PuckShape::Cylinder))),
        (
            "rapier3d 0.36 (f32), ball, rotations locked",
            anisotropy(|p| rapier_puck(p, PuckShape::LockedBall)),
        ),
    ];
    let rapier = |f: fn(&(f64, f64, f64)) -> f64| {
        format!("{:.1e} (cylinder), {:.1e} (ball, rotations locked)", f(&rows[1].1), f(&rows[2].1))
    };
    table.push([
        "puck, level table, 16 headings: spread of the stopping distance".into(),
        format!("{:.1e}", core.0),
        rapier(|r| r.0),
    ]);
    table.push([
        "puck, level table, 16 headings: largest direction error (deg)".into(),
        format!("{:.1e}", core.1),
        rapier(|r| r.1),
    ]);
    for (name, (spread, worst, mean)) in rows {
        writeln!(
            text,
            "  {name:<44} spread {spread:.1e}  direction error {worst:.1e} deg  mean distance {:.2} mm",
            1e3 * mean
        )
        .unwrap();
    }
    writeln!(
        text,
        "the billiard ball's rolling velocity against the 5/7 law v = (5 v0 + 2 R omega0 x z) / 7:"
    )
    .unwrap();
    let cases = [
        ("defaults (no spin)", BilliardParams::<f32>::default()),
        (
            "spin (40, 40, 0) rad/s",
            BilliardParams::<f32> { spin_x: 40.0, spin_y: 40.0, ..BilliardParams::default() },
        ),
    ];
    for (case, b) in cases {
        let law = five_sevenths(&b);
        writeln!(text, "  {case}: the law's ({:.6}, {:.6}) m/s", law[0], law[1]).unwrap();
        let mut row = [
            format!("billiard ball, {case}: rolling velocity's relative error against the 5/7 law"),
            String::new(),
            String::new(),
        ];
        for (k, (name, e)) in
            [("meterstick core f32 Billiard", core_ball(b)), ("rapier3d 0.36 (f32), ball", rapier_ball(b))]
                .into_iter()
                .enumerate()
        {
            let [x, y] = e.measure.map(f64::from);
            let error = (x - law[0]).hypot(y - law[1]) / law[0].hypot(law[1]);
            row[k + 1] = format!("{error:.1e}");
            writeln!(
                text,
                "    {name:<30} ({x:.6}, {y:.6}) m/s at t = {:.3} s, relative error {error:.1e}{}",
                e.time,
                if e.slip > 0.0 { format!(", slip then {:.1e} m/s", e.slip) } else { String::new() }
            )
            .unwrap();
        }
        table.push(row);
    }
}

/// The curling stone (the uniform disc) in both: ns per step, and what Farkas et al. (PRL 90,
/// 248302, 2003) predict of a disc sliding and spinning under Coulomb friction, that sliding and
/// spinning stop together with `v / (R omega)` tending to 0.653 (`docs/scenes.md`, "curling").
fn curling_section(text: &mut String, table: &mut Rows, repeats: usize) {
    let p = CurlingParams::<f32>::default();
    writeln!(
        text,
        "curling stone, the uniform disc (defaults: R = {} m, m = {} kg, {} points, launched at {} m/s spinning at {} rad/s, \
         mu = {}, h = {} ms), {repeats} runs each, median;\n  ends when sliding and spinning have both stopped \
         (|v| and R |omega| <= {} m/s); (v / (R omega) read while both are >= 10 mu g h, spin stop - slide stop):",
        p.radius,
        p.mass,
        p.points,
        p.speed,
        p.spin,
        p.mu,
        1e3 * p.step,
        p.stick_speed
    )
    .unwrap();
    let [(core, c), (ns, e)] = timed(repeats, [&|| core_curling(p), &|| rapier_curling(p)]);
    let ratio = ("ratio, stops apart", 1.0, "(-, s)");
    line(text, "meterstick core f32 Curling (disc)", core, &c, ratio);
    line(text, "rapier3d 0.36 (f32), cylinder", ns, &e, ratio);
    writeln!(
        text,
        "  ratio rapier3d / core: {:.1}x; Farkas et al.'s terminal ratio for the disc: 0.653",
        ns / core
    )
    .unwrap();
    table.push([
        "curling stone, the disc (defaults), ns/step".into(),
        format!("{core:.0}"),
        format!("{ns:.0}; ratio {:.1}x", ns / core),
    ]);
    let stops = |e: &End| {
        if e.measure[1].is_nan() {
            format!("{:.3} (did not stop in {} s)", e.measure[0], p.max_time)
        } else {
            format!("{:.3}, spinning stops {:+.3} s after sliding", e.measure[0], e.measure[1])
        }
    };
    table.push([
        "curling stone, the disc (defaults): v / (R omega) before the stop (Farkas: 0.653, stopping together)".into(),
        stops(&c),
        stops(&e),
    ]);
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` passes nothing: run once, quickly.
    let repeats = if std::env::args().any(|a| a == "--bench") { REPEATS } else { 1 };
    let mut text = format!("rapier3d 0.36 and the core side by side, on {}:\n", machine());
    let mut table = Rows::new();
    speed_section(&mut text, &mut table, repeats);
    curling_section(&mut text, &mut table, repeats);
    anisotropy_section(&mut text, &mut table);
    stack::stack_section(&mut text, &mut table, repeats);
    print!("{text}");
    // The same figures side by side, a Markdown table under the printed block.
    let mut rows =
        String::from("\n| quantity | meterstick core (f32) | rapier3d 0.36 (f32) |\n|---|---|---|\n");
    for [what, core, rapier] in &table {
        writeln!(rows, "| {what} | {core} | {rapier} |").unwrap();
    }
    // Quoted in docs/performance.md ("Against rapier3d") by scripts/performance.sh.
    if repeats > 1 {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../out/bench");
        let written = std::fs::create_dir_all(&dir)
            .and_then(|()| std::fs::write(dir.join("rapier3d.md"), format!("```text\n{text}```\n{rows}")));
        if let Err(e) = written {
            eprintln!("could not write {}: {e}", dir.join("rapier3d.md").display());
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
