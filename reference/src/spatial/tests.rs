//! The spatial reference against the closed forms of docs/scenes.md ("Scenes in three
//! dimensions"), its contact solve against its own conditions, and its validity rules. The
//! measured numbers are printed (`-- --nocapture`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

use super::algebra::{
    M3, V3, apply, congruent, cross, dot, identity3, in_plane, length, matrix_of, minus, plus, product, skew,
    times, transpose, unit,
};
use super::contact::{self, Case, Point};
use super::*;

fn norm(a: [f64; 3]) -> f64 {
    length(a)
}

#[test]
fn a_billiard_ball_rolls_when_and_as_the_closed_form_says() {
    let b0 = Billiard::default();
    let (g, h) = (b0.g, b0.h);
    let mut worst = (0.0_f64, 0.0_f64);
    for spin in [
        [0.0, 0.0, 0.0],
        [0.0, 80.0, 0.0],
        [0.0, -120.0, 0.0],
        [40.0, 30.0, 25.0],
        [-90.0, 10.0, -60.0],
        [0.0, 70.0, 0.0],
        [15.0, -200.0, 300.0],
    ] {
        for mu in [0.2, 0.05] {
            let b = Billiard { spin, mu_s: mu, mu_k: mu, ..b0 };
            let run = run_billiard(&b).unwrap();
            let (r, v0) = (b.radius, b.speed);
            let u0 = [v0 - r * spin[1], r * spin[0], 0.0];
            let t_roll = 2.0 * norm(u0) / (7.0 * mu * g);
            let v_roll = [(5.0 * v0 + 2.0 * r * spin[1]) / 7.0, (-2.0 * r * spin[0]) / 7.0];
            assert_eq!(run.outcome, Outcome::Rolled, "spin {spin:?}");
            let [t, vx, vy] = run.measured.map(Option::unwrap);
            assert!(t >= t_roll - 1e-12 && t <= t_roll + h + 1e-12, "spin {spin:?}: {t} s, law {t_roll} s");
            let dv = (vx - v_roll[0]).hypot(vy - v_roll[1]) / v0;
            assert!(dv <= 1e-12, "spin {spin:?}: ({vx}, {vy}), law {v_roll:?}: {dv:e}");
            let last = run.trajectory.last().unwrap();
            assert!((last.angular_velocity[2] - spin[2]).abs() <= 1e-12 * (1.0 + spin[2].abs()));
            assert!(last.velocity[2] == 0.0 && (last.position[2] - r).abs() <= 1e-15, "{last:?}");
            // The slip keeps its direction while it slides.
            for row in &run.trajectory[1..run.trajectory.len() - 1] {
                assert_eq!(row.mode, Mode::Sliding);
                let s = plus(row.velocity, cross(row.angular_velocity, [0.0, 0.0, -r]));
                let across = (s[0] * u0[1] - s[1] * u0[0]) / norm(u0);
                assert!(across.abs() <= 1e-13 * norm(u0), "spin {spin:?}: slip {s:?} turned from {u0:?}");
            }
            eprintln!(
                "billiard spin {spin:?} mu {mu}: rolls at {t:.4} s (law {t_roll:.6}, {} steps), velocity off by {dv:.1e} of the speed",
                run.steps
            );
            worst = (worst.0.max(dv), worst.1.max((t - t_roll) / h));
        }
    }
    eprintln!(
        "billiard: worst velocity {:.1e} of the speed, rolling time at most {:.3} h late",
        worst.0, worst.1
    );
}

/// The discrete stop on a level table: `v_1 = v_0 - mu_s g h`, then `v_k = v_{k-1} - mu_k g h`
/// while positive, `x = h sum v_k` (the last step stops the puck: `v = 0`).
fn discrete_stop(v0: f64, mu_s: f64, mu_k: f64, g: f64, h: f64) -> (f64, u64) {
    let v1 = v0 - mu_s * g * h;
    if v1 <= 0.0 {
        return (0.0, 1);
    }
    let a = mu_k * g * h;
    // v_k = v1 - (k - 1) a > 0 for k = 1 ..= n: n = ceil(v1 / a) (v1 / a not an integer here).
    let n = (v1 / a).ceil();
    (h * (n * v1 - a * n * (n - 1.0) / 2.0), n as u64 + 1)
}

#[test]
fn a_puck_on_a_level_table_stops_at_the_same_distance_in_every_heading() {
    for (speed, mu_s, mu_k) in [(0.9, 0.4, 0.4), (1.5, 0.3, 0.3), (0.9, 0.5, 0.35)] {
        let p0 = Puck { angle: 0.0, speed, mu_s, mu_k, ..Puck::default() };
        let (g, h) = (p0.g, p0.h);
        let (exact, steps) = discrete_stop(speed, mu_s, mu_k, g, h);
        let law = speed * speed / (2.0 * mu_k * g);
        let run0 = run_puck(&p0).unwrap();
        let along0 = run0.measured[1].unwrap();
        assert_eq!(run0.outcome, Outcome::Stopped);
        assert_eq!(run0.steps, steps);
        let discrete = (along0 - exact).abs() / exact;
        assert!(discrete <= 1e-13, "{along0} m, discrete law {exact} m");
        if mu_s == mu_k {
            assert!((along0 - law).abs() <= speed * h, "{along0} m, law {law} m");
        }
        let mut spread = 0.0_f64;
        for k in 0..16 {
            let heading = f64::from(k) * std::f64::consts::TAU / 16.0 + 0.1;
            let run = run_puck(&Puck { heading, ..p0 }).unwrap();
            let [speed_end, along, bearing] = run.measured;
            assert_eq!(run.outcome, Outcome::Stopped);
            assert_eq!(speed_end, Some(0.0));
            let along = along.unwrap();
            let e = (along - along0).abs() / along0;
            let turn = (bearing.unwrap().to_radians() - heading).sin().abs();
            assert!(e <= 1e-12 && turn <= 1e-12, "heading {heading}: {along} m ({e:e}), bearing {bearing:?}");
            spread = spread.max(e).max(turn);
        }
        eprintln!(
            "puck speed {speed} mu_s {mu_s} mu_k {mu_k}: stops at {along0:.9} m after {steps} steps, discrete law {discrete:.1e} off, \
             v^2/(2 mu_k g) {law:.6} m; 16 headings within {spread:.1e}"
        );
    }
}

/// Across an incline with `mu = tan alpha`: the invariant `v (1 + cos psi)` over `speed (1 + cos
/// psi0)`; its worst relative error over `seconds` and the final speed over the launch speed.
fn half_speed(h: f64, seconds: f64, heading: f64) -> (f64, f64) {
    let angle = 20.0_f64.to_radians();
    let p = Puck {
        angle,
        mu_s: angle.tan(),
        mu_k: angle.tan(),
        h,
        max_time: seconds,
        heading,
        ..Puck::default()
    };
    let run = run_puck(&p).unwrap();
    assert_eq!(run.outcome, Outcome::Slid);
    let down = p.down();
    let invariant = |v: [f64; 3]| norm(v) + dot(v, down);
    let start = invariant(run.trajectory[0].velocity);
    let worst =
        run.trajectory.iter().map(|r| (invariant(r.velocity) - start).abs() / start).fold(0.0, f64::max);
    (worst, norm(run.trajectory.last().unwrap().velocity) / p.speed)
}

#[test]
fn a_puck_across_an_incline_with_mu_tan_angle_tends_to_half_its_speed() {
    for heading in [0.0, -0.7, 2.0] {
        let (coarse, _) = half_speed(2e-3, 4.0, heading);
        let (fine, _) = half_speed(1e-3, 4.0, heading);
        eprintln!(
            "puck, mu = tan alpha, heading {heading}: invariant off by {coarse:.2e} (h = 2 ms), {fine:.2e} (1 ms)"
        );
        assert!(fine < 1e-2 && fine < 0.6 * coarse, "{coarse} -> {fine}");
    }
    let (_, end) = half_speed(1e-3, 40.0, 0.0);
    eprintln!("puck, mu = tan alpha: speed after 40 s {end} of the launch speed");
    assert!((end - 0.5).abs() < 0.01, "{end}");
}

#[test]
fn a_puck_with_mu_s_above_tan_angle_stops_where_it_is() {
    let p = Puck { speed: 0.0, mu_s: 0.5, mu_k: 0.3, ..Puck::default() };
    let run = run_puck(&p).unwrap();
    assert_eq!((run.outcome, run.steps), (Outcome::Stopped, 1));
    assert_eq!(run.measured, [Some(0.0), Some(0.0), None]);
    let row = run.trajectory[1];
    let weight = p.mass * p.g * p.h;
    let (s, c) = p.angle.sin_cos();
    assert!((row.normal_impulse - weight * c).abs() <= 1e-15 * weight);
    assert!((norm(row.friction_impulse) - weight * s).abs() <= 1e-15 * weight);
    // Its face on the plane: the body's axis along the normal.
    let axis = apply(&matrix_of(p.start_orientation()), [0.0, 0.0, 1.0]);
    assert!(norm(minus(axis, p.normal())) <= 1e-15, "{axis:?}");
    // Below tan alpha it slides down the slope from rest.
    let run = run_puck(&Puck { speed: 0.0, mu_s: 0.3, mu_k: 0.3, max_time: 0.5, ..Puck::default() }).unwrap();
    assert_eq!(run.outcome, Outcome::Slid);
    assert!((run.measured[2].unwrap() - 90.0).abs() < 1e-9, "{:?}", run.measured);
}

/// Checks `answer` against the contact's conditions: `u+ . n >= 0 _|_ p_n >= 0`, the cone, and
/// friction against the slip; returns the worst residual (in units of the free velocity).
fn residual(c: &Point, p: V3, case: Case) -> f64 {
    let after = plus(c.u, apply(&c.w, p));
    let (pn, pt) = (dot(p, c.n), in_plane(p, c.n));
    let (un, slip) = (dot(after, c.n), in_plane(after, c.n));
    let scale = norm(c.u);
    match case {
        Case::Apart => (norm(p) + (-un).max(0.0)) / scale,
        Case::Stuck => {
            assert!(pn >= 0.0 && norm(pt) <= c.mu * pn * (1.0 + 1e-12));
            norm(after) / scale
        }
        Case::Slides => {
            assert!(pn > 0.0);
            let against = plus(pt, times(c.mu * pn / norm(slip), slip));
            (un.abs() + norm(against) / pn.max(1e-300) * scale) / scale
        }
    }
}

/// A pseudo-random number in `[-1, 1)` (xorshift).
fn next(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

#[test]
fn the_contact_solve_meets_its_conditions_for_coupled_points() {
    // A box's corner, turned at random, on tilted planes: W couples normal and slip.
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut counts = [0_usize; 3];
    let mut worst = 0.0_f64;
    for _ in 0..2000 {
        let n = {
            let a = [0.3 * next(&mut seed), 0.3 * next(&mut seed), 1.0];
            times(1.0 / norm(a), a)
        };
        let q = unit([next(&mut seed), next(&mut seed), next(&mut seed), next(&mut seed)]);
        let r = [0.2 * next(&mut seed), 0.1 * next(&mut seed), -0.05];
        let r = apply(&matrix_of(q), r);
        let moments = [0.004, 0.0109, 0.0131];
        let inv = congruent(&matrix_of(q), moments.map(|i| 1.0 / i));
        let rx = skew(r);
        let coupling = product(&transpose(&rx), &product(&inv, &rx));
        let mut w: M3 = identity3();
        for i in 0..3 {
            for j in 0..3 {
                w[i][j] += coupling[i][j];
            }
        }
        let u = [next(&mut seed), next(&mut seed), -0.01 - 0.1 * next(&mut seed).abs()];
        let mu = 0.5 * (next(&mut seed) + 1.0);
        let c = Point { n, w, u, mu };
        let answer = contact::solve(&c).unwrap();
        counts[answer.case as usize] += 1;
        let e = residual(&c, answer.p, answer.case);
        assert!(e <= 1e-12, "{c:?}: {answer:?} off by {e:e}");
        worst = worst.max(e);
    }
    eprintln!("contact solve: apart/stuck/slides {counts:?}, worst residual {worst:.1e} of |u|");
    assert!(counts.iter().all(|&k| k > 0), "{counts:?}");
}

#[test]
fn the_closed_form_and_the_root_search_agree_on_an_isotropic_point() {
    // The isotropic W nudged just past the closed form's tolerance takes the root search.
    let w = [[3.5, 1e-12, 0.0], [1e-12, 3.5, 0.0], [0.0, 0.0, 1.0]];
    let c = Point { n: [0.0, 0.0, 1.0], w, u: [0.3, -0.2, -0.00981], mu: 0.2 };
    let general = contact::solve(&c).unwrap();
    let exact =
        contact::solve(&Point { w: [[3.5, 0.0, 0.0], [0.0, 3.5, 0.0], [0.0, 0.0, 1.0]], ..c }).unwrap();
    assert_eq!((general.case, exact.case), (Case::Slides, Case::Slides));
    assert!(norm(minus(general.p, exact.p)) <= 1e-12 * norm(exact.p), "{general:?} {exact:?}");
}

#[test]
fn validity_names_the_field() {
    let cases: [(Puck, &str, Rule); 6] = [
        (Puck { radius: 0.0, ..Puck::default() }, "radius", Rule::NotPositive),
        (Puck { speed: -1.0, ..Puck::default() }, "speed", Rule::Negative),
        (Puck { mu_k: 0.5, ..Puck::default() }, "mu_k", Rule::KineticAboveStatic),
        (Puck { h: 6.0, ..Puck::default() }, "h", Rule::StepAboveMaxTime),
        (Puck { angle: std::f64::consts::FRAC_PI_2, ..Puck::default() }, "angle", Rule::OutOfRange),
        (Puck { heading: f64::NAN, ..Puck::default() }, "heading", Rule::NotFinite),
    ];
    for (p, field, rule) in cases {
        assert_eq!(run_puck(&p).unwrap_err(), Error::Invalid { field, rule });
    }
    let b = Billiard { spin: [0.0, f64::INFINITY, 0.0], ..Billiard::default() };
    assert_eq!(b.validate(), Err(Error::Invalid { field: "spin_y", rule: Rule::NotFinite }));
    let b = Billiard { stick_speed: 0.0, ..Billiard::default() };
    assert_eq!(b.validate(), Err(Error::Invalid { field: "stick_speed", rule: Rule::NotPositive }));
    let b = Billiard { h: 1e-7, max_time: 2.0, ..Billiard::default() };
    assert!(matches!(run_billiard(&b), Err(Error::TooManySteps { .. })));
    assert!(Puck::default().validate().is_ok() && Billiard::default().validate().is_ok());
}

#[test]
fn the_defaults_run_to_their_outcomes() {
    let puck = run_puck(&Puck::default()).unwrap();
    let ball = run_billiard(&Billiard::default()).unwrap();
    eprintln!("puck default: {:?} after {} steps, {:?}", puck.outcome, puck.steps, puck.measured);
    eprintln!("billiard default: {:?} after {} steps, {:?}", ball.outcome, ball.steps, ball.measured);
    assert_eq!(puck.trajectory.len() as u64, puck.steps + 1);
    assert_eq!(ball.outcome, Outcome::Rolled);
}
