//! The spatial core (`meterstick_core::spatial`, an LCP over one friction line turned to the
//! slip) against the independent f64 reference (`meterstick_reference::spatial`, one contact
//! solved by cases) on the scenes `puck` and `billiard` of docs/scenes.md: the same launches
//! stepped side by side in f64, positions within 1e-9 m, velocities within 1e-9 m/s and modes
//! equal at every step. The worst differences are printed (`-- --nocapture`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::print_stdout, clippy::float_cmp)]

use meterstick_core::spatial::{Body, Mode, OneContact, Plane, SpatialSettings, SpatialShape, State, about};
use meterstick_reference::spatial::{self as reference, Billiard, Puck, SpatialRun};

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn same_mode(core: Mode, reference: reference::Mode) -> bool {
    matches!(
        (core, reference),
        (Mode::Separated, reference::Mode::Separated)
            | (Mode::Sticking, reference::Mode::Sticking)
            | (Mode::Sliding, reference::Mode::Sliding)
    )
}

/// The worst differences of one launch.
#[derive(Debug, Default, Clone, Copy)]
struct Worst {
    position: f64,
    velocity: f64,
    orientation: f64,
    angular_velocity: f64,
    normal_impulse: f64,
    friction_impulse: f64,
}

impl Worst {
    fn max(self, o: Self) -> Self {
        Self {
            position: self.position.max(o.position),
            velocity: self.velocity.max(o.velocity),
            orientation: self.orientation.max(o.orientation),
            angular_velocity: self.angular_velocity.max(o.angular_velocity),
            normal_impulse: self.normal_impulse.max(o.normal_impulse),
            friction_impulse: self.friction_impulse.max(o.friction_impulse),
        }
    }
}

/// Steps `core` through the reference's run, comparing every step.
fn compare(label: &str, mut core: OneContact<f64>, run: &SpatialRun) -> Worst {
    let mut worst = Worst::default();
    for (k, row) in run.trajectory.iter().enumerate().skip(1) {
        let r = core.step().unwrap_or_else(|e| panic!("{label}: core step {k}: {e:?}"));
        let (s, c) = (r.state, r.contacts[0]);
        assert!(
            same_mode(c.mode, row.mode),
            "{label}: step {k}: core {:?}, reference {:?} ({c:?}, {row:?})",
            c.mode,
            row.mode
        );
        let q = s.orientation;
        // q and -q are one rotation.
        let dq = (0..4)
            .map(|i| (q[i] - row.orientation[i]).abs())
            .fold(0.0, f64::max)
            .min((0..4).map(|i| (q[i] + row.orientation[i]).abs()).fold(0.0, f64::max));
        let here = Worst {
            position: distance(s.position, row.position),
            velocity: distance(s.velocity, row.velocity),
            orientation: dq,
            angular_velocity: distance(s.angular_velocity, row.angular_velocity),
            normal_impulse: (c.normal_impulse - row.normal_impulse).abs(),
            friction_impulse: distance(c.friction_impulse, row.friction_impulse),
        };
        assert!(
            here.position <= 1e-9 && here.velocity <= 1e-9,
            "{label}: step {k}: core {s:?}, reference {row:?}"
        );
        assert!(here.orientation <= 1e-9 && here.angular_velocity <= 1e-9, "{label}: step {k}: {here:?}");
        assert!(
            here.normal_impulse <= 1e-12 && here.friction_impulse <= 1e-12,
            "{label}: step {k}: {here:?}"
        );
        worst = worst.max(here);
    }
    println!(
        "{label}: {:?} after {} steps; worst |dx| {:.1e} m, |dv| {:.1e} m/s, |dq| {:.1e}, |dw| {:.1e} rad/s, \
         |dp_n| {:.1e}, |dp_t| {:.1e} N s",
        run.outcome,
        run.steps,
        worst.position,
        worst.velocity,
        worst.orientation,
        worst.angular_velocity,
        worst.normal_impulse,
        worst.friction_impulse
    );
    worst
}

fn puck(label: &str, p: &Puck) -> Worst {
    let run = reference::run_puck(p).unwrap();
    let across = p.mass * (3.0 * p.radius * p.radius + p.thickness * p.thickness) / 12.0;
    let body = Body { mass: p.mass, inertia: [across, across, 0.5 * p.mass * p.radius * p.radius] };
    let plane = Plane { mu_static: p.mu_s, mu_kinetic: p.mu_k, ..Plane::incline(p.angle, p.mu_s) };
    let (s, c) = p.heading.sin_cos();
    let down = [0.0, p.angle.cos(), -p.angle.sin()];
    let state = State {
        position: [0.0; 3],
        // The face on the plane: body z along the normal (0, sin, cos), a turn by -alpha about x.
        orientation: about(&[1.0, 0.0, 0.0], -p.angle),
        velocity: [p.speed * c, p.speed * s * down[1], p.speed * s * down[2]],
        angular_velocity: [0.0; 3],
    };
    let settings = SpatialSettings {
        step: p.h,
        gravity: [0.0, 0.0, -p.g],
        stick_speed: p.stick_speed,
        ..SpatialSettings::default()
    };
    let core =
        OneContact::new(body, [SpatialShape::Point { offset: [0.0; 3] }], plane, settings, state).unwrap();
    compare(label, core, &run)
}

fn billiard(label: &str, b: &Billiard) -> Worst {
    let run = reference::run_billiard(b).unwrap();
    let plane = Plane { mu_static: b.mu_s, mu_kinetic: b.mu_k, ..Plane::table(0.0, b.mu_s) };
    let state = State {
        position: [0.0, 0.0, b.radius],
        orientation: [1.0, 0.0, 0.0, 0.0],
        velocity: [b.speed, 0.0, 0.0],
        angular_velocity: b.spin,
    };
    let settings = SpatialSettings {
        step: b.h,
        gravity: [0.0, 0.0, -b.g],
        stick_speed: b.stick_speed,
        ..SpatialSettings::default()
    };
    let core = OneContact::new(
        Body::sphere(b.mass, b.radius),
        [SpatialShape::Sphere { radius: b.radius }],
        plane,
        settings,
        state,
    )
    .unwrap();
    compare(label, core, &run)
}

#[test]
fn the_puck_agrees_with_the_reference() {
    let alpha = 20.0_f64.to_radians();
    let level = Puck { angle: 0.0, speed: 1.5, mu_s: 0.3, mu_k: 0.3, ..Puck::default() };
    let tan = Puck { mu_s: alpha.tan(), mu_k: alpha.tan(), ..Puck::default() };
    let mut worst = Worst::default();
    let mut launches: Vec<(String, Puck)> = vec![
        ("default".into(), Puck::default()),
        ("sticking start".into(), Puck { speed: 0.0, mu_s: 0.5, mu_k: 0.3, ..Puck::default() }),
        ("from rest down the slope".into(), Puck { speed: 0.0, mu_s: 0.3, mu_k: 0.3, ..Puck::default() }),
        ("mu_s > mu_k up the slope".into(), Puck { heading: -1.2, mu_s: 0.5, mu_k: 0.38, ..Puck::default() }),
        (
            "steep, h = 0.5 ms".into(),
            Puck { angle: 1.2, heading: 0.4, mu_s: 3.0, mu_k: 2.8, h: 5e-4, ..Puck::default() },
        ),
    ];
    for heading in [0.0, 1.0, 2.5, -2.0, 3.0] {
        launches.push((format!("level table, heading {heading}"), Puck { heading, ..level }));
    }
    for heading in [0.0, -0.7, 2.0] {
        launches.push((format!("mu = tan alpha, heading {heading}"), Puck { heading, ..tan }));
    }
    for (label, p) in &launches {
        worst = worst.max(puck(&format!("puck, {label}"), p));
    }
    println!("puck, all launches: {worst:?}");
}

#[test]
fn the_billiard_ball_agrees_with_the_reference() {
    let mut worst = Worst::default();
    for spin in [
        [0.0, 0.0, 0.0],
        [0.0, 80.0, 0.0],
        [0.0, -120.0, 0.0],
        [40.0, 30.0, 25.0],
        [-90.0, 10.0, -60.0],
        [15.0, -200.0, 300.0],
    ] {
        worst = worst
            .max(billiard(&format!("billiard, spin {spin:?}"), &Billiard { spin, ..Billiard::default() }));
    }
    let slow =
        Billiard { spin: [30.0, -50.0, 10.0], mu_s: 0.25, mu_k: 0.1, speed: 3.0, ..Billiard::default() };
    worst = worst.max(billiard("billiard, mu_s 0.25, mu_k 0.1", &slow));
    let unfinished =
        Billiard { spin: [0.0, -300.0, 0.0], mu_k: 0.05, mu_s: 0.05, max_time: 1.0, ..Billiard::default() };
    worst = worst.max(billiard("billiard, unfinished at 1 s", &unfinished));
    println!("billiard, all launches: {worst:?}");
}

/// What the core's turn of its friction line took on one launch: steps with a loaded contact,
/// steps that turned the line (more than one try), the tries of the loaded steps, the most on
/// one step, and the step it failed on, if any.
#[derive(Debug, Default, Clone, Copy)]
struct Tries {
    loaded: u32,
    turned: u32,
    total: u32,
    most: u32,
    failed: Option<usize>,
}

/// A box's corner (`Body::cuboid(1, 0.1, 0.06, 0.2)` touching a level table at the point fixed at
/// `(0.05, 0.03, -0.1)`, from `z = 0.1`, not turned; `h = 1 ms`) launched at `velocity`, `spin`
/// on a table of `mu`: the reference's 400 steps, and the core's compared at every one (to the
/// step it fails on, reported in its `Tries`).
fn corner(velocity: [f64; 3], spin: [f64; 3], mu: f64) -> (Worst, Tries) {
    let (mass, sides, offset, h) = (1.0, [0.1, 0.06, 0.2], [0.05, 0.03, -0.1], 1e-3);
    let body = Body::cuboid(mass, sides[0], sides[1], sides[2]);
    let state = State {
        position: [0.0, 0.0, 0.1],
        orientation: [1.0, 0.0, 0.0, 0.0],
        velocity,
        angular_velocity: spin,
    };
    let core = OneContact::new(
        body,
        [SpatialShape::Point { offset }],
        Plane::table(0.0, mu),
        SpatialSettings { step: h, ..SpatialSettings::default() },
        state,
    )
    .unwrap();
    let point = reference::OnePoint {
        mass,
        moments: body.inertia,
        offset,
        point: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
        mu_s: mu,
        mu_k: mu,
        gravity: [0.0, 0.0, -9.81],
        h,
        stick_speed: 1e-5,
    };
    let mut row = reference::Row {
        t: 0.0,
        position: state.position,
        orientation: state.orientation,
        velocity,
        angular_velocity: spin,
        mode: reference::Mode::Separated,
        normal_impulse: 0.0,
        friction_impulse: [0.0; 3],
    };
    let mut rows = vec![row];
    for _ in 0..400 {
        row = point.step(&row).unwrap();
        rows.push(row);
    }
    let label = format!("corner, v {velocity:?}, omega {spin:?}, mu {mu}");
    let (mut probe, mut tries) = (core.clone(), Tries::default());
    for k in 1..=400 {
        match probe.step() {
            Ok(r) => {
                let d = r.contacts[0].directions;
                if d > 0 {
                    tries.loaded += 1;
                    tries.total += d;
                    tries.most = tries.most.max(d);
                }
                if d > 1 {
                    tries.turned += 1;
                }
            }
            Err(e) => {
                println!(
                    "{label}: THE CORE FAILS at step {k} ({e:?}); the reference: {:?} -> {:?}, p_n {:.3e} N s, \
                     friction {:?} N s",
                    rows[k - 1].mode,
                    rows[k].mode,
                    rows[k].normal_impulse,
                    rows[k].friction_impulse
                );
                tries.failed = Some(k);
                break;
            }
        }
    }
    let steps = tries.failed.map_or(400, |k| k - 1);
    rows.truncate(steps + 1);
    let run = SpatialRun {
        outcome: reference::Outcome::Unfinished,
        measured: [None; 3],
        steps: steps as u64,
        trajectory: rows,
    };
    (compare(&label, core, &run), tries)
}

fn per_step(t: &Tries) -> f64 {
    f64::from(t.total) / f64::from(t.loaded.max(1))
}

/// Beyond the two scenes: a box's corner (the first launch is the core's own in
/// `tests/tests/spatial.rs`), where `W` couples the normal and the slip, so the core turns its
/// friction line by Newton's method and the reference takes its root search over the slip's
/// angle. The second launch sticks at step 49 well inside the cone (`|p_t|` about 0.15 of `mu
/// p_n`). Every step of 400 compared; the core must not fail.
#[test]
fn an_off_centre_corner_agrees_with_the_reference() {
    let mut worst = Worst::default();
    for (velocity, spin, mu) in [
        ([0.8, 0.3, 0.0], [1.0, -2.0, 3.0], 0.4),
        ([0.5, -0.6, 0.0], [-2.0, 1.0, 6.0], 0.3),
        ([1.2, 0.0, 0.0], [0.0, 4.0, -2.0], 0.6),
        ([0.3, 0.4, 0.0], [0.5, 0.5, 1.0], 0.5),
    ] {
        let (w, t) = corner(velocity, spin, mu);
        println!(
            "corner, v {velocity:?}, omega {spin:?}, mu {mu}: the core turned its line on {} of {} loaded steps, \
             {:.2} tries a loaded step, at most {}",
            t.turned,
            t.loaded,
            per_step(&t),
            t.most
        );
        assert!(
            t.failed.is_none(),
            "corner, v {velocity:?}, omega {spin:?}, mu {mu}: the core failed: {t:?}"
        );
        worst = worst.max(w);
    }
    println!("corner, all launches: {worst:?}");
}

/// Around the launch that sticks at step 49: a grid of 54 launches (`v_x`, `v_y`, the spin about
/// `z` and `mu`), 400 steps each, the core following the reference at every step and never
/// failing.
#[test]
fn corner_launches_around_the_sticking_one_agree_with_the_reference() {
    let (mut worst, mut all, mut failures) = (Worst::default(), Tries::default(), 0);
    let mut launches = 0;
    for vx in [0.4, 0.5, 0.6] {
        for vy in [-0.7, -0.6, -0.5] {
            for wz in [4.0, 6.0, 8.0] {
                for mu in [0.3, 0.5] {
                    let (w, t) = corner([vx, vy, 0.0], [-2.0, 1.0, wz], mu);
                    launches += 1;
                    failures += usize::from(t.failed.is_some());
                    worst = worst.max(w);
                    all.loaded += t.loaded;
                    all.turned += t.turned;
                    all.total += t.total;
                    all.most = all.most.max(t.most);
                }
            }
        }
    }
    println!(
        "corner grid: {launches} launches, the core failed on {failures}; turned its line on {} of {} loaded \
         steps, {:.2} tries a loaded step, at most {}; worst {worst:?}",
        all.turned,
        all.loaded,
        per_step(&all),
        all.most
    );
    assert_eq!(failures, 0, "the core failed on {failures} of {launches} launches");
}
