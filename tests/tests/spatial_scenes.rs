//! The scenes in three dimensions (`docs/scenes.md`, "Scenes in three dimensions"), run as every
//! front end runs them: built from the catalogue's parameters (`SceneParams`) and driven through
//! the one scene interface (`SceneView`). Checked against the discrete and closed-form laws (a
//! puck's stopping distance in any heading, the half-speed law across an incline, a billiard
//! ball's rolling time and velocity), against the spatial stepper driven directly (bit for bit),
//! and for their refusals. In f64 and f32.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::cast_precision_loss)]

use meterstick_core::scene::spatial::{Billiard, BilliardParams, Puck, PuckParams, SpatialScene};
use meterstick_core::scene::{
    LcpLayout, Outcome, OutcomeKind, Pose, Precision, SceneKind, SceneParams, SceneView, Velocity,
    ViewVisitor,
};
use meterstick_core::spatial::{Body, Mode, OneContact, Plane, SpatialSettings, SpatialShape, State, about};
use meterstick_core::{ParamError, Real};

/// A run through the view: its outcome, measures, steps, checksum and final position and velocity.
#[derive(Debug, Clone, PartialEq)]
struct Ran {
    outcome: Option<Outcome>,
    measured: [Option<f64>; 3],
    steps: u64,
    checksum: u32,
    position: [f64; 3],
    velocity: [f64; 3],
    /// The largest `|v| (1 + cos psi)` change from its start (`psi` the velocity's angle from
    /// down the slope): the half-speed law's invariant.
    invariant_drift: f64,
}

/// Drives a view to its outcome.
struct Run {
    down: [f64; 3],
}

impl ViewVisitor for Run {
    type Output = Ran;

    fn visit<T: Real>(self, view: &mut dyn SceneView<T>) -> Ran {
        let state = |view: &dyn SceneView<T>| {
            let body = view.body(0).unwrap();
            let (Pose::Spatial { position, .. }, Velocity::Spatial { linear, .. }) =
                (body.pose, body.velocity)
            else {
                panic!("a body in three dimensions")
            };
            (position.map(Real::as_f64), linear.map(Real::as_f64))
        };
        let invariant = |v: [f64; 3]| {
            let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            speed + (v[0] * self.down[0] + v[1] * self.down[1] + v[2] * self.down[2])
        };
        let start = invariant(state(view).1);
        let mut drift = 0.0_f64;
        while view.step() {
            drift = drift.max((invariant(state(view).1) - start).abs());
        }
        let (position, velocity) = state(view);
        Ran {
            outcome: view.outcome(),
            measured: view.measured().map(|m| m.map(Real::as_f64)),
            steps: view.summary().steps,
            checksum: view.checksum(),
            position,
            velocity,
            invariant_drift: drift,
        }
    }
}

fn run(params: &SceneParams, precision: Precision) -> Ran {
    let angle = params.get("angle").unwrap_or(0.0);
    let down = [0.0, angle.cos(), -angle.sin()];
    params.build_view::<0, _>(precision, LcpLayout::Full, Run { down }).unwrap()
}

fn puck(fields: &[(&str, f64)]) -> SceneParams {
    let mut p = SceneParams::defaults(SceneKind::Puck);
    for &(field, value) in fields {
        assert!(p.set(field, value), "{field}");
    }
    p
}

/// The discrete law of a puck on a level table: the first step at `mu_s`, then `mu_k`, each step
/// taking `a h` off the speed and moving `h v+`; it sticks on the step that would reverse it.
fn discrete_stop(speed: f64, mu_s: f64, mu_k: f64, g: f64, h: f64) -> f64 {
    let (mut v, mut x, mut a) = (speed, 0.0, mu_s * g);
    loop {
        v -= a * h;
        if v <= 0.0 {
            return x;
        }
        x += h * v;
        a = mu_k * g;
    }
}

/// On a level table the puck stops at the discrete law's distance along its heading, whatever the
/// heading, and its displacement's heading is its launch's.
fn puck_is_isotropic(precision: Precision, tolerance: f64) {
    let (speed, mu) = (1.5, 0.3);
    let law = discrete_stop(speed, mu, mu, 9.81, 1e-3);
    let mut distances = Vec::new();
    for k in 0..24 {
        let heading = -180.0 + 15.0 * f64::from(k) + 0.37;
        let p = puck(&[
            ("angle", 0.0),
            ("heading", heading.to_radians()),
            ("speed", speed),
            ("mu_static", mu),
            ("mu_kinetic", mu),
        ]);
        let ran = run(&p, precision);
        assert_eq!(ran.outcome, Some(Outcome::Stopped), "{heading}");
        let [_, Some(distance), Some(measured_heading)] = ran.measured else { panic!("{ran:?}") };
        assert!((distance - law).abs() <= 4.0 * tolerance * law, "{heading} deg: {distance} m, law {law} m");
        distances.push(distance);
        let turned = (measured_heading - heading + 180.0).rem_euclid(360.0) - 180.0;
        assert!(turned.abs() <= tolerance * 360.0, "{heading} deg: ended heading {measured_heading} deg");
    }
    let spread = distances.iter().copied().fold(f64::MIN, f64::max)
        - distances.iter().copied().fold(f64::MAX, f64::min);
    println!(
        "{precision:?}: stopping distance spread {:.2e} of the law's {law} m over 24 headings",
        spread / law
    );
    assert!(spread <= tolerance * law, "{precision:?}: the distance spreads by {spread} m over the headings");
}

#[test]
fn a_puck_stops_at_the_same_distance_in_every_heading() {
    // The bounds: equal to 1e-9 (f64) and 1e-5 (f32) of the distance in every heading.
    puck_is_isotropic(Precision::F64, 1e-9);
    puck_is_isotropic(Precision::F32, 1e-5);
}

/// Across an incline with `mu = tan(alpha)` the invariant `|v| (1 + cos psi)` holds to first order
/// in `h`, and the speed tends to half the launch speed.
#[test]
fn across_an_incline_at_mu_tan_alpha_the_puck_tends_to_half_its_speed() {
    let alpha = 20.0_f64.to_radians();
    let mu = alpha.tan();
    for precision in [Precision::F64, Precision::F32] {
        let p = puck(&[("angle", alpha), ("mu_static", mu), ("mu_kinetic", mu), ("max_time", 40.0)]);
        let ran = run(&p, precision);
        assert_eq!(ran.outcome, Some(Outcome::Slid), "{precision:?}");
        let [Some(speed), _, Some(heading)] = ran.measured else { panic!("{ran:?}") };
        assert!((speed / 0.9 - 0.5).abs() < 2e-3, "{precision:?}: {speed} m/s after 40 s");
        assert!(
            heading > 80.0 && heading < 90.0,
            "{precision:?}: heading {heading} deg (toward down the slope)"
        );
        println!(
            "{precision:?}: speed {speed} m/s after 40 s, invariant drift {:.2e} m/s",
            ran.invariant_drift
        );
        // First order in h (1.45e-3 of the launch speed at h = 1 ms in f64), f32's sums on top.
        let bound = if precision == Precision::F64 { 2e-3 } else { 3e-3 };
        assert!(
            ran.invariant_drift < bound * 0.9,
            "{precision:?}: invariant drifted by {}",
            ran.invariant_drift
        );
    }
}

/// On the slope the law decides between stopping and sliding on: `tan(alpha)` against `mu_k`.
#[test]
fn on_the_slope_the_puck_stops_iff_friction_exceeds_its_pull() {
    for (mu, want) in [(0.30, Outcome::Slid), (0.40, Outcome::Stopped)] {
        let p = puck(&[("mu_static", mu), ("mu_kinetic", mu), ("max_time", 3.0)]);
        for precision in [Precision::F64, Precision::F32] {
            assert_eq!(run(&p, precision).outcome, Some(want), "mu {mu} {precision:?}");
        }
    }
}

/// A billiard ball struck with spin rolls from `2 |u0| / (7 mu g)` (within the step that ends
/// there) at `(5 v0 + 2 R omega0 x z) / 7`.
#[test]
fn a_billiard_ball_rolls_at_the_law_s_time_and_velocity() {
    let d = BilliardParams::<f64>::default();
    for spin in
        [[0.0, 0.0, 0.0], [0.0, 80.0, 0.0], [0.0, -120.0, 0.0], [40.0, 30.0, 25.0], [-90.0, 10.0, -60.0]]
    {
        let mut p = SceneParams::defaults(SceneKind::Billiard);
        for (field, value) in ["spin_x", "spin_y", "spin_z"].into_iter().zip(spin) {
            assert!(p.set(field, value));
        }
        let (r, g, mu, v0) = (d.radius, d.gravity, d.mu_kinetic, d.speed);
        let t_roll = 2.0 * (v0 - r * spin[1]).hypot(r * spin[0]) / (7.0 * mu * g);
        let v_roll = [(5.0 * v0 + 2.0 * r * spin[1]) / 7.0, -2.0 * r * spin[0] / 7.0];
        for (precision, tolerance) in [(Precision::F64, 1e-12), (Precision::F32, 1e-5)] {
            let ran = run(&p, precision);
            assert_eq!(ran.outcome, Some(Outcome::Rolled), "{spin:?} {precision:?}");
            let [Some(t), Some(vx), Some(vy)] = ran.measured else { panic!("{ran:?}") };
            assert!(
                t >= t_roll - 1e-9 && t <= t_roll + d.step + 1e-6,
                "{spin:?} {precision:?}: rolls at {t} s, law {t_roll}"
            );
            let error = (vx - v_roll[0]).hypot(vy - v_roll[1]);
            assert!(error <= tolerance * v0, "{spin:?} {precision:?}: ({vx}, {vy}) against {v_roll:?}");
        }
    }
}

/// Through the view, each scene's trajectory is the spatial stepper's driven directly with the
/// docs' start, bit for bit; and a run repeated gives the same checksum.
#[test]
fn the_view_runs_the_stepper_s_trajectory() {
    let p = PuckParams::<f64> { heading: 0.4, ..PuckParams::default() };
    let (s, c) = p.angle.sin_cos();
    let (sh, ch) = p.heading.sin_cos();
    let m = p.mass;
    let across = m * (3.0 * p.radius * p.radius + p.thickness * p.thickness) / 12.0;
    let mut direct = OneContact::new(
        Body { mass: m, inertia: [across, across, m * p.radius * p.radius * 0.5] },
        [SpatialShape::Point { offset: [0.0; 3] }],
        Plane { point: [0.0; 3], normal: [0.0, s, c], mu_static: p.mu_static, mu_kinetic: p.mu_kinetic },
        SpatialSettings {
            step: p.step,
            gravity: [0.0, 0.0, -p.gravity],
            stick_speed: p.stick_speed,
            ..SpatialSettings::default()
        },
        State {
            position: [0.0; 3],
            orientation: about(&[1.0, 0.0, 0.0], -p.angle),
            velocity: [p.speed * ch, p.speed * sh * c, -p.speed * sh * s],
            angular_velocity: [0.0; 3],
        },
    )
    .unwrap();
    let mut scene = Puck::new(p).unwrap();
    let mut steps = 0;
    while let Some(report) = scene.step() {
        let want = direct.step().unwrap();
        assert_eq!(
            report.state.position.map(f64::to_bits),
            want.state.position.map(f64::to_bits),
            "step {steps}"
        );
        assert_eq!(
            report.state.velocity.map(f64::to_bits),
            want.state.velocity.map(f64::to_bits),
            "step {steps}"
        );
        steps += 1;
    }
    assert_eq!(scene.outcome(), Some(Outcome::Stopped));
    assert_eq!(direct.modes()[0], Mode::Sticking);
    assert!(steps > 100, "{steps} steps");
    for kind in [SceneKind::Puck, SceneKind::Billiard] {
        for precision in [Precision::F64, Precision::F32] {
            let params = SceneParams::defaults(kind);
            let (a, b) = (run(&params, precision), run(&params, precision));
            assert_eq!(a, b, "{kind} {precision:?}");
        }
    }
    let ball = Billiard::new(BilliardParams::<f32>::default()).unwrap();
    assert_eq!(ball.outcome(), None);
}

/// Bad parameters are refused by name before anything runs, in f64 and again in f32.
#[test]
fn bad_parameters_are_refused_by_name() {
    for (kind, field, value, want) in [
        (SceneKind::Puck, "angle", std::f64::consts::FRAC_PI_2, ParamError::OutOfRange("angle")),
        (SceneKind::Puck, "angle", -0.1, ParamError::OutOfRange("angle")),
        (SceneKind::Puck, "speed", -1.0, ParamError::Negative("speed")),
        (SceneKind::Puck, "mu_kinetic", 0.5, ParamError::KineticAboveStatic),
        (SceneKind::Puck, "heading", f64::NAN, ParamError::NonFinite("heading")),
        (SceneKind::Puck, "stick_speed", 0.0, ParamError::NotPositive("stick_speed")),
        (SceneKind::Puck, "step", 6.0, ParamError::OutOfRange("step")),
        (SceneKind::Billiard, "radius", 0.0, ParamError::NotPositive("radius")),
        (SceneKind::Billiard, "spin_x", f64::INFINITY, ParamError::NonFinite("spin_x")),
        (
            SceneKind::Billiard,
            "radius",
            1e-25,
            ParamError::InertiaOutOfRange { mass: "mass", size: "radius" },
        ),
    ] {
        let mut p = SceneParams::defaults(kind);
        assert!(p.set(field, value));
        let precision = if matches!(want, ParamError::InertiaOutOfRange { .. }) {
            Precision::F32
        } else {
            Precision::F64
        };
        let got = p.build_view::<0, _>(precision, LcpLayout::Full, Run { down: [0.0; 3] }).unwrap_err();
        assert_eq!(got, want, "{kind} {field} = {value}");
    }
    assert_eq!(OutcomeKind::Stopped.name(), "Stopped");
}
