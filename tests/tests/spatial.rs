//! The spatial core (`meterstick_core::spatial`) against closed forms that only three dimensions
//! show: a billiard ball's rolling time and velocity for any spin, a puck's isotropic stopping
//! distance on a level table, the half-speed law of a puck launched across an incline with
//! `mu = tan(angle)`, and a free spinning box's energy and angular momentum. In f64 and f32.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss, clippy::print_stdout)]

use meterstick_core::Real;
use meterstick_core::spatial::{
    Body, FrictionCone, Mode, OneContact, Plane, SpatialSettings, SpatialShape, SpatialStepper, State, about,
    identity,
};

const G: f64 = 9.81;

fn at_rest_on<T: Real>(position: [f64; 3]) -> State<T> {
    State {
        position: position.map(T::of),
        orientation: identity(),
        velocity: [T::zero(); 3],
        angular_velocity: [T::zero(); 3],
    }
}

/// `|a - b| / |b|` over the coordinates, `|b|` at least `floor`.
fn relative(a: [f64; 3], b: [f64; 3], floor: f64) -> f64 {
    let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
    d / (b[0].powi(2) + b[1].powi(2) + b[2].powi(2)).sqrt().max(floor)
}

fn f64s<T: Real>(v: [T; 3]) -> [f64; 3] {
    v.map(Real::as_f64)
}

/// A ball of radius `R` struck along `+x` at `v0` with spin `omega0` slides with its slip `u`
/// shrinking along its own direction at `7 mu g / 2` and rolls from `t = 2 |u0| / (7 mu g)` at `v
/// = (5 v0 + 2 R omega0 x z) / 7`; its spin about `z` stays.
fn billiard<T: Real>(tolerance: f64) {
    let (radius, mass, mu, h) = (0.028_575, 0.17, 0.2, 1e-3);
    for spin in
        [[0.0, 0.0, 0.0], [0.0, 80.0, 0.0], [0.0, -120.0, 0.0], [40.0, 30.0, 25.0], [-90.0, 10.0, -60.0]]
    {
        let v0 = [2.0, 0.0, 0.0];
        let mut state = at_rest_on::<T>([0.0, 0.0, radius]);
        state.velocity = v0.map(T::of);
        state.angular_velocity = spin.map(T::of);
        let settings = SpatialSettings { step: T::of(h), ..SpatialSettings::default() };
        let mut ball = OneContact::new(
            Body::sphere(T::of(mass), T::of(radius)),
            [SpatialShape::Sphere { radius: T::of(radius) }],
            Plane::table(T::zero(), T::of(mu)),
            settings,
            state,
        )
        .unwrap();
        // u0 = v0 + omega0 x (-R z): the contact point's slip.
        let u0 = [v0[0] - radius * spin[1], v0[1] + radius * spin[0], 0.0];
        let u0_speed = (u0[0] * u0[0] + u0[1] * u0[1]).sqrt();
        let t_roll = 2.0 * u0_speed / (7.0 * mu * G);
        // (5 v0 + 2 R omega0 x z) / 7, omega0 x z = (omega_y, -omega_x, 0).
        let v_roll =
            [(5.0 * v0[0] + 2.0 * radius * spin[1]) / 7.0, (5.0 * v0[1] - 2.0 * radius * spin[0]) / 7.0, 0.0];
        let mut rolled = None;
        for _ in 0..(t_roll / h) as usize + 50 {
            let r = ball.step().unwrap();
            assert!(r.contacts[0].directions == 1, "spin {spin:?}: {:?}", r.contacts[0]);
            if r.contacts[0].mode == Mode::Sliding {
                // The slip keeps the direction it started with.
                let s = f64s(r.contacts[0].slip);
                let across = (s[0] * u0[1] - s[1] * u0[0]) / u0_speed;
                assert!(across.abs() <= tolerance * u0_speed, "spin {spin:?}: slip {s:?} turned from {u0:?}");
            } else if rolled.is_none() && r.contacts[0].mode == Mode::Sticking {
                rolled = Some(r.time.as_f64());
            }
        }
        let t = rolled.expect("the ball rolls");
        assert!(
            t >= t_roll - tolerance && t <= t_roll + h + tolerance,
            "spin {spin:?}: rolls at {t} s, law {t_roll} s"
        );
        let v = f64s(ball.state().velocity);
        // Relative to the launch speed: f32's round-off over up to 800 steps.
        let e = relative(v, v_roll, 2.0);
        assert!(e <= tolerance, "spin {spin:?}: rolls at {v:?}, law {v_roll:?} ({e:e})");
        let spin_z = ball.state().angular_velocity[2].as_f64();
        assert!(
            (spin_z - spin[2]).abs() <= tolerance * (1.0 + spin[2].abs()),
            "spin about z {spin_z}, launched {}",
            spin[2]
        );
        println!(
            "{} billiard spin {spin:?}: rolls at {t:.4} s (law {t_roll:.4}), velocity off by {e:.1e}",
            T::NAME
        );
    }
}

#[test]
fn a_billiard_ball_rolls_when_and_as_the_closed_form_says() {
    billiard::<f64>(1e-9);
    billiard::<f32>(1e-5);
}

/// At `h = 1e-6` a ball struck with spin `(30, -40, 0)` rad/s slips at 1e-4 m/s near rolling on a
/// surface turning at 1 m/s: the slip's round-off is that of its terms, `|v| + R |omega|`, and
/// the first friction line, the free slip's, holds every step (a sphere's tangential response is
/// isotropic). It rolls at `t = 2 |u0| / (7 mu g)` (the step whose slip falls within the stick
/// speed, `1e-5 / (7 mu g / 2)` s before, ends it) and then runs at `v = (5 v0 + 2 R omega0 x z) /
/// 7`: in f64 to `tolerance` of the launch speed; in f32 the velocity's round-off over the run's `t / h`
/// steps, each adding a half ulp of `|v0| + R |omega0|` at most, bounds it.
fn billiard_at_a_microsecond<T: Real>(tolerance: f64) {
    let (radius, mass, mu, h) = (0.028_575, 0.17, 0.2, 1e-6);
    let (v0, spin) = ([2.0, 0.0, 0.0], [30.0, -40.0, 0.0]);
    let mut state = at_rest_on::<T>([0.0, 0.0, radius]);
    state.velocity = v0.map(T::of);
    state.angular_velocity = spin.map(T::of);
    let settings = SpatialSettings { step: T::of(h), ..SpatialSettings::default() };
    let mut ball = OneContact::new(
        Body::sphere(T::of(mass), T::of(radius)),
        [SpatialShape::Sphere { radius: T::of(radius) }],
        Plane::table(T::zero(), T::of(mu)),
        settings,
        state,
    )
    .unwrap();
    let u0 = [v0[0] - radius * spin[1], v0[1] + radius * spin[0], 0.0];
    let u0_speed = (u0[0] * u0[0] + u0[1] * u0[1]).sqrt();
    let t_roll = 2.0 * u0_speed / (7.0 * mu * G);
    let v_roll =
        [(5.0 * v0[0] + 2.0 * radius * spin[1]) / 7.0, (5.0 * v0[1] - 2.0 * radius * spin[0]) / 7.0, 0.0];
    let steps = (t_roll / h) as usize;
    let surface = v0[0] + radius * (spin[0] * spin[0] + spin[1] * spin[1]).sqrt();
    let tolerance = tolerance.max(steps as f64 * T::EPS.as_f64() / 2.0 * surface);
    let mut rolled = None;
    for _ in 0..steps + 50 {
        let r = ball.step().unwrap();
        assert!(r.contacts[0].directions == 1, "{} at {}: {:?}", T::NAME, r.time.as_f64(), r.contacts[0]);
        if rolled.is_none() && r.contacts[0].mode == Mode::Sticking {
            rolled = Some(r.time.as_f64());
        }
    }
    let t = rolled.expect("the ball rolls");
    let v = f64s(ball.state().velocity);
    let e = relative(v, v_roll, v0[0]);
    println!("{} billiard h = 1e-6: rolls at {t:.6} s (law {t_roll:.6}), velocity off by {e:.1e}", T::NAME);
    let early = 1e-5 / (3.5 * mu * G) + h;
    let slack = tolerance * t_roll;
    assert!(t >= t_roll - early - slack && t <= t_roll + h + slack, "rolls at {t} s, law {t_roll} s");
    assert!(e <= tolerance, "rolls at {v:?}, law {v_roll:?} ({e:e} > {tolerance:e})");
}

#[test]
fn a_billiard_ball_at_a_microsecond_step_rolls_as_the_closed_form_says() {
    billiard_at_a_microsecond::<f64>(1e-9);
    billiard_at_a_microsecond::<f32>(0.0);
}

/// Launched at `speed` across a level table in `heading`, a puck (one contact under its centre
/// of mass) stops at the same distance along its heading whatever the heading: the friction
/// opposes the slip, not the world's axes. Returns the distance along and across the heading.
fn puck_on_table<T: Real>(heading: f64, speed: f64, mu: f64, h: f64) -> (f64, f64) {
    let (s, c) = heading.sin_cos();
    let mut state = at_rest_on::<T>([0.0, 0.0, 0.0]);
    state.velocity = [T::of(speed * c), T::of(speed * s), T::zero()];
    let mut puck = OneContact::new(
        Body::cuboid(T::of(0.17), T::of(0.0762), T::of(0.0762), T::of(0.0254)),
        [SpatialShape::Point { offset: [T::zero(); 3] }],
        Plane::table(T::zero(), T::of(mu)),
        SpatialSettings { step: T::of(h), ..SpatialSettings::default() },
        state,
    )
    .unwrap();
    for _ in 0..100_000 {
        let r = puck.step().unwrap();
        if r.contacts[0].mode == Mode::Sticking {
            break;
        }
    }
    assert_eq!(puck.modes()[0], Mode::Sticking, "the puck stops");
    let p = f64s(puck.state().position);
    (p[0] * c + p[1] * s, -p[0] * s + p[1] * c)
}

fn isotropy<T: Real>(tolerance: f64) {
    let (speed, mu, h) = (1.5, 0.3, 1e-3);
    let (along0, _) = puck_on_table::<T>(0.0, speed, mu, h);
    // The closed form `v^2 / (2 mu g)`, to the step's travel: the discrete stop is within `v h`.
    let law = speed * speed / (2.0 * mu * G);
    assert!((along0 - law).abs() <= speed * h, "{along0} m, law {law} m");
    for k in 1..24 {
        let heading = f64::from(k) * 15.0_f64.to_radians() + 0.1;
        let (along, across) = puck_on_table::<T>(heading, speed, mu, h);
        assert!(
            (along - along0).abs() <= tolerance * along0,
            "heading {heading}: {along} m, at 0: {along0} m"
        );
        assert!(across.abs() <= tolerance * along0, "heading {heading}: {across} m across its heading");
    }
}

#[test]
fn a_puck_stops_at_the_same_distance_in_every_heading() {
    isotropy::<f64>(1e-9);
    isotropy::<f32>(1e-5);
}

/// A puck launched horizontally (across the slope) at `v0` on an incline with `mu = tan(angle)`:
/// along its path `dv/dt = g sin(angle) (cos(phi) - 1)` and across it `v dphi/dt = -g
/// sin(angle) sin(phi)` (`phi` from the fall line), so `v (1 + cos(phi)) = v0` and `v -> v0 / 2`.
/// Returns the invariant's largest relative error over `seconds` and the final speed.
fn half_speed<T: Real>(h: f64, seconds: f64) -> (f64, f64) {
    let angle = 0.3_f64;
    let v0 = 1.0;
    let plane = Plane::incline(T::of(angle), T::of(angle.tan()));
    let mut state = at_rest_on::<T>([0.0, 0.0, 0.0]);
    state.velocity = [T::of(v0), T::zero(), T::zero()];
    let mut puck = OneContact::new(
        Body::cuboid(T::of(0.17), T::of(0.0762), T::of(0.0762), T::of(0.0254)),
        [SpatialShape::Point { offset: [T::zero(); 3] }],
        plane,
        SpatialSettings { step: T::of(h), ..SpatialSettings::default() },
        state,
    )
    .unwrap();
    // The fall line: down the slope, in the plane.
    let fall = [0.0, angle.cos(), -angle.sin()];
    let mut worst = 0.0_f64;
    let mut speed = v0;
    for _ in 0..(seconds / h) as usize {
        let r = puck.step().unwrap();
        assert_eq!(r.contacts[0].mode, Mode::Sliding);
        let v = f64s(r.state.velocity);
        speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let cos_phi = (v[0] * fall[0] + v[1] * fall[1] + v[2] * fall[2]) / speed;
        worst = worst.max((speed * (1.0 + cos_phi) - v0).abs() / v0);
    }
    (worst, speed)
}

#[test]
fn a_puck_across_an_incline_with_mu_tan_angle_tends_to_half_its_speed() {
    for (name, coarse, fine, end) in [
        ("f64", half_speed::<f64>(2e-3, 4.0), half_speed::<f64>(1e-3, 4.0), half_speed::<f64>(1e-3, 40.0).1),
        ("f32", half_speed::<f32>(2e-3, 4.0), half_speed::<f32>(1e-3, 4.0), half_speed::<f32>(1e-3, 40.0).1),
    ] {
        println!(
            "{name}: v (1 + cos phi) / v0 - 1 at most {:.2e} (h = 2 ms), {:.2e} (1 ms); speed after 40 s {end}",
            coarse.0, fine.0
        );
        // First order in h: halving the step halves the invariant's error.
        assert!(fine.0 < 1e-2 && fine.0 < 0.6 * coarse.0, "{name}: {coarse:?} -> {fine:?}");
        assert!((end - 0.5).abs() < 0.01, "{name}: speed {end} after 40 s, law 0.5");
    }
}

/// A box tumbling at 10 rad/s in free flight (its spin not along a principal axis): over 1e5 steps
/// its angular momentum stays to round-off and its energy within `O(h^2)`. Returns the energy's
/// largest relative change and the momentum's at the end.
fn free_spin<T: Real>() -> (f64, f64) {
    let body = Body::cuboid(T::of(1.0), T::of(0.1), T::of(0.2), T::of(0.3));
    let mut state = at_rest_on::<T>([0.0, 0.0, 10.0]);
    state.orientation = about(&[T::of(0.6), T::zero(), T::of(0.8)], T::of(0.4));
    state.angular_velocity = [T::of(0.3), T::of(-0.2), T::of(10.0)];
    let settings = SpatialSettings { gravity: [T::zero(); 3], ..SpatialSettings::default() };
    let mut stepper = OneContact::new(
        body,
        [SpatialShape::Point { offset: [T::zero(); 3] }],
        Plane::table(T::of(-100.0), T::zero()),
        settings,
        state,
    )
    .unwrap();
    let (e0, l0) = (state.kinetic_energy(&body).as_f64(), f64s(state.angular_momentum(&body)));
    let mut energy = 0.0_f64;
    for _ in 0..100_000 {
        let s = stepper.step().unwrap().state;
        energy = energy.max((s.kinetic_energy(&body).as_f64() - e0).abs() / e0);
    }
    let l = f64s(stepper.state().angular_momentum(&body));
    (energy, relative(l, l0, 1e-12))
}

#[test]
fn a_free_tumbling_box_keeps_its_momentum_and_energy() {
    for (name, (energy, momentum), (energy_bound, momentum_bound)) in
        [("f64", free_spin::<f64>(), (1e-5, 1e-9)), ("f32", free_spin::<f32>(), (1e-2, 1e-2))]
    {
        println!(
            "{name}: over 1e5 steps energy within {energy:.2e} of itself, angular momentum moved {momentum:.2e}"
        );
        assert!(energy < energy_bound, "{name}: energy {energy}");
        assert!(momentum < momentum_bound, "{name}: momentum {momentum}");
    }
}
/// A point off the centre of mass (a box's corner) couples the contact's normal and tangential
/// response and makes it anisotropic: the first friction direction, the free slip's, does not
/// hold and the step turns it. Checked from the reports alone: while sliding, the friction is
/// `mu` times the normal impulse and points against the slip; while sticking, within the cone.
fn corner<T: Real>(tolerance: f64) -> u32 {
    let (mu, h) = (0.4, 1e-3);
    let offset = [0.05, 0.03, -0.1];
    let mut state = at_rest_on::<T>([0.0, 0.0, 0.1]);
    state.velocity = [T::of(0.8), T::of(0.3), T::zero()];
    state.angular_velocity = [T::of(1.0), T::of(-2.0), T::of(3.0)];
    let mut corner = OneContact::new(
        Body::cuboid(T::of(1.0), T::of(0.1), T::of(0.06), T::of(0.2)),
        [SpatialShape::Point { offset: offset.map(T::of) }],
        Plane::table(T::zero(), T::of(mu)),
        SpatialSettings { step: T::of(h), ..SpatialSettings::default() },
        state,
    )
    .unwrap();
    let mut turned = 0;
    for _ in 0..400 {
        let r = corner.step().unwrap();
        let c = r.contacts[0];
        if c.directions > 1 {
            turned += 1;
        }
        let (n, f, s) = (c.normal_impulse.as_f64(), f64s(c.friction_impulse), f64s(c.slip));
        let (fm, sm) = (
            (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt(),
            (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt(),
        );
        match c.mode {
            Mode::Sliding => {
                assert!((fm - mu * n).abs() <= tolerance * mu * n, "{c:?}");
                let against = (f[0] * s[0] + f[1] * s[1] + f[2] * s[2]) / (fm * sm);
                assert!(against + 1.0 <= tolerance, "friction not against the slip: {c:?}");
            }
            Mode::Sticking => assert!(fm <= mu * n * (1.0 + tolerance), "{c:?}"),
            Mode::Separated => assert!(n <= 1e-12, "{c:?}"),
        }
    }
    turned
}

#[test]
fn an_off_centre_point_turns_its_friction_to_the_slip() {
    for (name, turned) in [("f64", corner::<f64>(1e-9)), ("f32", corner::<f32>(1e-4))] {
        println!("{name}: {turned} steps turned the friction's direction");
        assert!(turned > 0, "{name}: no step needed a second direction: the test exercises nothing");
    }
}

#[test]
fn bad_input_is_refused_by_name() {
    let ok = || {
        (
            Body::sphere(1.0, 0.1),
            [SpatialShape::Sphere { radius: 0.1 }],
            Plane::table(0.0, 0.3),
            SpatialSettings::default(),
            at_rest_on::<f64>([0.0, 0.0, 0.1]),
        )
    };
    let (b, s, p, st, x) = ok();
    assert!(OneContact::new(b, s, p, st, x).is_ok());
    let field = |r: Result<OneContact<f64>, meterstick_core::ParamError>| r.err().and_then(|e| e.field());
    assert_eq!(field(OneContact::new(Body::sphere(-1.0, 0.1), s, p, st, x)), Some("mass"));
    assert_eq!(field(OneContact::new(b, [SpatialShape::Sphere { radius: 0.0 }], p, st, x)), Some("radius"));
    assert_eq!(field(OneContact::new(b, s, Plane { normal: [0.0, 0.0, 2.0], ..p }, st, x)), Some("normal"));
    assert_eq!(field(OneContact::new(b, s, Plane { mu_kinetic: -0.1, ..p }, st, x)), Some("mu_kinetic"));
    assert_eq!(field(OneContact::new(b, s, p, SpatialSettings { step: 0.0, ..st }, x)), Some("step"));
    // A pyramid of 2 directions, or one the LCP's `N = 4` cannot hold (4 directions need 6).
    for directions in [2, 4] {
        let cone = SpatialSettings { friction: FrictionCone::Pyramid { directions }, ..st };
        assert_eq!(field(OneContact::new(b, s, p, cone, x)), Some("friction_directions"));
    }
    assert_eq!(
        field(OneContact::new(Body { mass: 1.0, inertia: [1.0, 1.0, 3.0] }, s, p, st, x)),
        Some("inertia")
    );
    assert!(OneContact::new(b, s, Plane { mu_kinetic: 0.5, ..p }, st, x).is_err());
}

/// The baseline (`FrictionCone::Pyramid`): a puck launched across a level table in 16 headings
/// with `k` fixed friction directions. Returns the spread of its stopping distance along its
/// heading over the closed form `v^2 / (2 mu g)` (max - min) and the largest angle (rad) between
/// its heading and where it ended.
fn pyramid_spread<T: Real>(cone: FrictionCone) -> (f64, f64) {
    let (speed, mu, h) = (1.5, 0.3, 1e-3);
    let law = speed * speed / (2.0 * mu * G);
    let (mut lo, mut hi, mut bend) = (f64::INFINITY, 0.0_f64, 0.0_f64);
    for k in 0..16 {
        // 23.7 degrees apart: no multiple of a pyramid's angle, so each heading meets the edges
        // at another angle.
        let heading = f64::from(k) * 23.7_f64.to_radians() + 0.1;
        let (s, c) = heading.sin_cos();
        let mut state = at_rest_on::<T>([0.0, 0.0, 0.0]);
        state.velocity = [T::of(speed * c), T::of(speed * s), T::zero()];
        let mut puck = SpatialStepper::<T, 1, 18>::new(
            Body::cuboid(T::of(0.17), T::of(0.0762), T::of(0.0762), T::of(0.0254)),
            [SpatialShape::Point { offset: [T::zero(); 3] }],
            Plane::table(T::zero(), T::of(mu)),
            SpatialSettings { step: T::of(h), friction: cone, ..SpatialSettings::default() },
            state,
        )
        .unwrap();
        for _ in 0..100_000 {
            if puck.step().unwrap().contacts[0].mode == Mode::Sticking {
                break;
            }
        }
        let p = f64s(puck.state().position);
        let (along, across) = (p[0] * c + p[1] * s, -p[0] * s + p[1] * c);
        lo = lo.min(along / law);
        hi = hi.max(along / law);
        bend = bend.max(across.atan2(along).abs());
    }
    (hi - lo, bend)
}

#[test]
fn a_pyramid_of_fixed_directions_bends_the_puck_and_the_circle_does_not() {
    let (spread, bend) = pyramid_spread::<f64>(FrictionCone::Circular);
    println!("circular: spread {spread:.1e} of the law, bend {bend:.1e} rad");
    assert!(spread < 1e-9 && bend < 1e-9, "circular: {spread:e}, {bend:e}");
    let mut last = f64::INFINITY;
    for directions in [4, 8, 16] {
        let (spread, bend) = pyramid_spread::<f64>(FrictionCone::Pyramid { directions });
        println!(
            "pyramid of {directions}: spread {spread:.2e} of the law, bend up to {:.2} deg",
            bend.to_degrees()
        );
        // The baseline is anisotropic (what the test measures), less so with more directions.
        assert!(spread > 1e-3 && bend > 1e-3 && bend < last, "{directions}: {spread:e}, {bend:e}");
        last = bend;
    }
    let (spread, bend) = pyramid_spread::<f32>(FrictionCone::Pyramid { directions: 8 });
    assert!(spread > 1e-3 && bend > 1e-3, "f32, 8: {spread:e}, {bend:e}");
}
