//! The 3-block stack over a table's edge in three dimensions (docs/scenes.md, "stack-3d"), its
//! overhang at headings to the edge: rapier3d's and the core's outcomes and times per step (both
//! in f32, `Stack3d3`), the ratio of the two on the held stack, and the independent reference's
//! outcome (`meterstick_reference::spatial::run_stack_3d_keeping`).
//!
//! Rapier: the table a fixed cuboid whose top face is `z = 0` over `x <= 0`; each block a cuboid
//! `L x W x hb` (mass `m`), at the scene's start (the planar stack's harmonic offsets along `d =
//! (cos psi, sin psi, 0)`, turned by `psi` about `z`), friction `mu_s` with the `Min` combine rule,
//! restitution 0, never asleep, contact recycling off, its default solver. Fell: a block's top
//! normal turned more than `tilt_limit` from `z` or its centre dropped more than `drop_limit`;
//! Held at `max_time` (10 s). The reference's outcome over 1 s (it falls within 0.3 s or holds).

use std::fmt::Write as _;
use std::time::Instant;

use meterstick_core::scene::spatial::{Stack3d3, Stack3dParams};
use meterstick_reference::spatial::{Keep, Outcome, Stack3d, run_stack_3d_keeping};
use rapier3d::prelude::*;

/// The headings of the overhang to the edge's normal, degrees.
const HEADINGS: [f64; 3] = [0.0, 30.0, 60.0];
/// Just under and just over the critical stack.
const OVERHANGS: [f64; 2] = [0.98, 1.02];

/// rapier3d's run of `p` (f32): its outcome name, the time it ended (s) and ns per step.
fn rapier_stack(p: &Stack3d) -> (&'static str, f64, f64) {
    let f = |x: f64| x as f32;
    let mut w = super::world(f(p.h), f(p.g));
    let collider = |half: [f32; 3]| {
        ColliderBuilder::cuboid(half[0], half[1], half[2])
            .friction(f(p.mu_s))
            .friction_combine_rule(CoefficientCombineRule::Min)
            .restitution(0.0)
    };
    let table = [2.0 * f(p.length), 4.0 * f(p.length), f(p.length)];
    w.insert(RigidBodyBuilder::fixed().translation(Vector::new(-table[0], 0.0, -table[2])), collider(table));
    let half = [f(p.length) / 2.0, f(p.width) / 2.0, f(p.height) / 2.0];
    let density = f(p.mass) / (f(p.length) * f(p.width) * f(p.height));
    let (sin, cos) = p.heading.sin_cos();
    let mut right = 0.0;
    let starts: Vec<[f64; 3]> = (0..p.blocks)
        .map(|i| {
            right += p.overhang * 0.5 * p.length / (p.blocks - i) as f64;
            let along = right - 0.5 * p.length;
            [along * cos, along * sin, (i as f64 + 0.5) * p.height]
        })
        .collect();
    let blocks: Vec<RigidBodyHandle> = starts
        .iter()
        .map(|s| {
            w.insert(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(f(s[0]), f(s[1]), f(s[2])))
                    .rotation(Vector::new(0.0, 0.0, f(p.heading)))
                    .can_sleep(false),
                collider(half).density(density),
            )
            .0
        })
        .collect();
    let total = (p.max_time / p.h).round() as u64;
    let mut steps = 0u64;
    let start = Instant::now();
    let outcome = loop {
        w.step();
        steps += 1;
        let fell = blocks.iter().zip(&starts).any(|(&b, s)| {
            let body = &w.bodies[b];
            let up = *body.rotation() * Vector::new(0.0, 0.0, 1.0);
            f64::from(up.z.clamp(-1.0, 1.0)).acos() > p.tilt_limit
                || s[2] - f64::from(body.translation().z) > p.drop_limit
        });
        if fell {
            break "Fell";
        }
        if steps >= total {
            break "Held";
        }
    };
    let ns = start.elapsed().as_nanos() as f64;
    (outcome, steps as f64 * p.h, ns / steps as f64)
}

/// The core's run of `p` (f32, `Stack3d3`): its outcome, the time it ended (s) and ns per step.
fn core_stack(p: &Stack3d) -> (String, f64, f64) {
    let f = |x: f64| x as f32;
    let params = Stack3dParams::<f32> {
        length: f(p.length),
        width: f(p.width),
        height: f(p.height),
        mass: f(p.mass),
        mu_static: f(p.mu_s),
        mu_kinetic: f(p.mu_k),
        overhang: f(p.overhang),
        heading: f(p.heading),
        gravity: f(p.g),
        step: f(p.h),
        stick_speed: f(p.stick_speed),
        tilt_limit: f(p.tilt_limit),
        drop_limit: f(p.drop_limit),
        contact_margin: f(p.margin),
        max_time: f(p.max_time),
    };
    let mut scene = Stack3d3::<f32>::new(params).expect("the stack's defaults are valid");
    let mut steps = 0u64;
    let start = Instant::now();
    while scene.step().is_some() {
        steps += 1;
    }
    let ns = start.elapsed().as_nanos() as f64 / steps.max(1) as f64;
    let outcome = scene.outcome().map_or_else(|| "none".to_string(), |o| format!("{o:?}"));
    (outcome, steps as f64 * p.h, ns)
}

/// The reference's outcome of `p` over 1 s.
fn reference_stack(p: &Stack3d) -> String {
    match run_stack_3d_keeping(&Stack3d { max_time: 1.0, ..*p }, Keep::StartAndEnd) {
        Ok(r) if r.outcome == Outcome::Fell => format!("Fell at t = {:.3} s", r.steps as f64 * p.h),
        Ok(r) => format!("{:?} for {:.3} s", r.outcome, r.steps as f64 * p.h),
        Err(e) => format!("no answer ({e})"),
    }
}

/// The section: per heading, rapier3d's outcome at each overhang and its ns per step on the held
/// stack (the median of `repeats` runs), the reference's outcomes beside; one table row each.
pub fn stack_section(text: &mut String, table: &mut super::Rows, repeats: usize) {
    let base = Stack3d::default();
    writeln!(
        text,
        "3-block stack over a table's edge in three dimensions (L = {} m, W = {} m, hb = {} m, m = {} kg, mu = {}, \
         h = {} ms; rapier3d {} s, the reference 1 s), its overhang at a heading to the edge:",
        base.length,
        base.width,
        base.height,
        base.mass,
        base.mu_s,
        1e3 * base.h,
        base.max_time
    )
    .unwrap();
    for heading in HEADINGS {
        let p = Stack3d { heading: heading.to_radians(), ..base };
        let held = Stack3d { overhang: OVERHANGS[0], ..p };
        let ns = super::median((0..repeats).map(|_| rapier_stack(&held).2).collect());
        let core_ns = super::median((0..repeats).map(|_| core_stack(&held).2).collect());
        let (mut rapier, mut core, mut reference) = (Vec::new(), Vec::new(), Vec::new());
        for s in OVERHANGS {
            let how = |outcome: &str| if outcome == "Held" { "for" } else { "at t =" };
            let (outcome, t, _) = rapier_stack(&Stack3d { overhang: s, ..p });
            rapier.push(format!("s = {s:.2}: {outcome} {} {t:.3} s", how(outcome)));
            let (outcome, t, _) = core_stack(&Stack3d { overhang: s, ..p });
            core.push(format!("s = {s:.2}: {outcome} {} {t:.3} s", how(&outcome)));
            reference.push(format!("s = {s:.2}: {}", reference_stack(&Stack3d { overhang: s, ..p })));
        }
        writeln!(
            text,
            "  heading {heading:>4.1} deg  rapier3d 0.36 (f32) {ns:>9.1} ns/step  {}",
            rapier.join("  ")
        )
        .unwrap();
        writeln!(text, "  {:>17}  core (f32)          {core_ns:>9.1} ns/step  {}", "", core.join("  "))
            .unwrap();
        writeln!(text, "  {:>17}  reference (f64)  {}", "", reference.join("  ")).unwrap();
        writeln!(text, "  {:>17}  ratio rapier3d / core: {:.2}x", "", ns / core_ns).unwrap();
        table.push([
            format!("3-block stack at heading {heading} deg: outcome at s = 0.98 / 1.02; ns/step held"),
            format!("{}; {core_ns:.0} ns/step", core.join("; ")),
            format!("{}; {ns:.0} ns/step", rapier.join("; ")),
        ]);
    }
}
