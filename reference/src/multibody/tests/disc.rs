//! The disc on a pulled board (docs/formulation.md, "The rim-on-face contact"): the rim law, the
//! run that leaves the board, the rim contact's Jacobian.

use super::*;

// ---------------------------------------------------------------------------------------------
// disc-on-board (docs/formulation.md, "The rim-on-face contact").

/// The law of docs/formulation.md ("The rim-on-face contact") for `p`: the outcome and the
/// accelerations `(A, a_c)` of the board and the disc's centre.
fn disc_law(p: &DiscOnBoard) -> (Outcome, f64, f64) {
    let (big_m, m, g) = (p.board_mass, p.disc_mass, p.gravity);
    let floor = p.mu_floor * (big_m + m) * g;
    if p.force <= floor {
        return (Outcome::Held, 0.0, 0.0);
    }
    let rolling = (p.force - floor) / (big_m + m / 3.0);
    if rolling <= 3.0 * p.mu_static * g {
        (Outcome::Rolled, rolling, rolling / 3.0)
    } else {
        (Outcome::Slid, (p.force - p.mu_kinetic * m * g - floor) / big_m, p.mu_kinetic * g)
    }
}

#[test]
fn a_disc_on_a_pulled_board_follows_the_rim_law() {
    let p = DiscOnBoard::default();
    let (big_m, m, r) = (p.board_mass, p.disc_mass, p.disc_radius);
    let held = p.mu_floor * (big_m + m) * G;
    // The largest pull under which the disc rolls: A = 3 mu_s g.
    let rolls = 3.0 * p.mu_static * G * (big_m + m / 3.0) + held;
    let tol = 1e-9;
    let mut worst: f64 = 0.0;
    // The sliding runs are cut short: the disc slides back over the board's rear end (at 0.98 of
    // the threshold the rolling one stays on it for 0.3 s).
    for (force, max_time, expected) in [
        (0.5 * held, 0.3, Outcome::Held),
        (0.98 * held, 0.3, Outcome::Held),
        (1.02 * held, 0.3, Outcome::Rolled),
        (p.force, 0.3, Outcome::Rolled),
        (0.98 * rolls, 0.3, Outcome::Rolled),
        (1.02 * rolls, 0.2, Outcome::Slid),
        (100.0, 0.1, Outcome::Slid),
    ] {
        let q = DiscOnBoard { force, max_time, ..p };
        let (law, a_board, a_disc) = disc_law(&q);
        assert_eq!(law, expected, "the law's outcome at F = {force}");
        let run = run(&Spec::DiscOnBoard(q), Sample::All).unwrap();
        let (lower, upper) = (run.lower_acceleration.unwrap(), run.upper_acceleration.unwrap());
        let err = (lower - a_board).abs().max((upper - a_disc).abs());
        worst = worst.max(err);
        // Rolling: the rim's lowest point moves with the board, v_c + omega r = V (every step).
        let roll_slip = run
            .rows
            .iter()
            .map(|row| (row.v[1][0] + row.v[1][2] * r - row.v[0][0]).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "disc-on-board F = {force:7.3} N: {:?} after {} steps, A {lower:.12} (law {a_board:.12}), a_c {upper:.12} (law {a_disc:.12}), largest |v_c + omega r - V| {roll_slip:e} m/s, omega {:.6} rad/s, {} ambiguous",
            run.outcome, run.steps, run.v[1][2], run.ambiguous_steps
        );
        assert_eq!(run.outcome, expected, "F = {force}");
        assert_eq!(run.steps, (max_time / p.step).round() as u64);
        assert!(err < tol, "F = {force}: accelerations off the law by {err:e}");
        assert_eq!(run.ambiguous_steps, 0);
        // The disc never bounces or sinks: it stays on the board's top face.
        for row in &run.rows {
            let gap = row.q[1][1] - r - (row.q[0][1] + p.board_height / 2.0);
            assert!(gap.abs() < 1e-12 && row.q[0][2].abs() < 1e-12, "t {}: gap {gap:e}", row.t);
        }
        let [disc, floor] = [run.interface_forces[1], run.interface_forces[0]];
        match expected {
            Outcome::Held => assert!(run.max_speed < 1e-12, "held, yet moved at {:e} m/s", run.max_speed),
            Outcome::Rolled => {
                assert!(roll_slip < 1e-12, "rolling, yet slipping at {roll_slip:e} m/s");
                // Turning counter-clockwise at omega = (A - a_c) t / r, moving forward.
                let t = run.end_time;
                let omega = (a_board - a_disc) * t / r;
                assert!((run.v[1][2] - omega).abs() < 1e-9 * omega, "omega {} vs {omega}", run.v[1][2]);
                assert!(run.v[1][0] > 0.0 && run.v[1][0] < run.v[0][0], "{:?}", run.v);
                // The board's friction on the disc m A / 3 forward and its support m g; the
                // floor's on the board M A + m a_c - F along x (backward) and (M + m) g up.
                assert!((disc[0] - m * a_disc).abs() < 1e-9 && (disc[1] - m * G).abs() < 1e-9, "{disc:?}");
                let floor_x = big_m * a_board + m * a_disc - force;
                assert!(
                    (floor[0] - floor_x).abs() < 1e-9 && (floor[1] - (big_m + m) * G).abs() < 1e-9,
                    "{floor:?}"
                );
            }
            _ => {
                // Sliding back over the board: kinetic friction m mu_k g forward.
                assert!((disc[0] - m * p.mu_kinetic * G).abs() < 1e-9, "{disc:?}");
                assert!(roll_slip > 1e-3, "sliding, yet rolling");
            }
        }
    }
    eprintln!("disc-on-board: worst acceleration error {worst:e} m/s^2 (tolerance {tol:e})");
}

#[test]
fn a_disc_whose_contact_leaves_the_board_ends_the_run_unfinished() {
    // F = 100 N slides the disc back at A - mu_k g = 42.6 m/s^2: 0.5 m in about 0.153 s; a disc
    // started 5 cm from the rear end rolls back at 2 A / 3 = 4.87 m/s^2 and leaves within 0.15 s.
    for q in [
        DiscOnBoard { force: 100.0, ..DiscOnBoard::default() },
        DiscOnBoard { offset: -0.45, ..DiscOnBoard::default() },
    ] {
        let r = run(&Spec::DiscOnBoard(q), Sample::None).unwrap();
        let along = r.q[1][0] - r.q[0][0];
        eprintln!(
            "disc-on-board F {} offset {}: {:?} at {:.3} s, the disc {along:.4} m from the board's centre",
            q.force, q.offset, r.outcome, r.end_time
        );
        assert_eq!(r.outcome, Outcome::Unfinished);
        assert!(r.end_time < 0.2, "{}", r.end_time);
        assert!(along < -q.board_length / 2.0 && along > -q.board_length / 2.0 - 0.01, "{along}");
    }
}

/// A disc (body 1) on a tilted, moving board (body 0) on the floor, touching or nearly; `k`
/// (1..=3) active contacts.
fn random_disc_step(rng: &mut Random) -> RandomStep {
    let (length, height, radius) = (rng.uniform(0.3, 1.0), rng.uniform(0.01, 0.1), rng.uniform(0.02, 0.2));
    let mu_s = rng.uniform(0.1, 1.5);
    let system = System {
        bodies: vec![
            Body::block(length, height, rng.uniform(0.5, 3.0)),
            Body::disc(radius, rng.uniform(0.2, 2.0)),
        ],
        table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
        pairs: vec![
            Pair { upper: 0, lower: Lower::Table, mu_static: 0.3, mu_kinetic: 0.3 },
            Pair {
                upper: 1,
                lower: Lower::Body(0),
                mu_static: mu_s,
                mu_kinetic: mu_s * rng.uniform(0.3, 1.0),
            },
        ],
        forces: vec![[rng.uniform(-60.0, 60.0), 0.0], [rng.uniform(-5.0, 5.0), 0.0]],
        gravity: G,
        step: 1e-3,
        stick_speed: 1e-5,
        margin: 1e-3,
    };
    let tilt = rng.uniform(-0.01, 0.01);
    let q0 = [0.0, height / 2.0 + (length / 2.0) * tilt.abs() + rng.uniform(-1e-4, 1e-4), tilt];
    // The disc over the board at s, its centre r + gap along the face's normal.
    let s = rng.uniform(-0.45, 0.45) * length;
    let n = [-tilt.sin(), tilt.cos()];
    let e = [tilt.cos(), tilt.sin()];
    let lift = height / 2.0 + radius + rng.uniform(-1e-4, 1e-4);
    let q1 = [q0[0] + s * e[0] + lift * n[0], q0[1] + s * e[1] + lift * n[1], rng.uniform(-3.0, 3.0)];
    let v = vec![
        [rng.uniform(-0.5, 0.5), rng.uniform(-0.02, 0.02), rng.uniform(-0.2, 0.2)],
        [rng.uniform(-0.5, 0.5), rng.uniform(-0.05, 0.02), rng.uniform(-20.0, 20.0)],
    ];
    let frames = system.frames(&[q0, q1], &v);
    let mu = frames
        .iter()
        .map(|f| {
            let pair = system.pairs[f.pair];
            if rng.uniform(0.0, 1.0) < 0.5 { pair.mu_static } else { pair.mu_kinetic }
        })
        .collect();
    (system, vec![q0, q1], v, mu)
}

/// The world position after `q` moves to `moved` of body `i`'s material point at world `point`.
fn material_point(q: [f64; 3], moved: [f64; 3], point: [f64; 2]) -> [f64; 2] {
    let (s, c) = q[2].sin_cos();
    let l = [point[0] - q[0], point[1] - q[1]];
    let body = [c * l[0] + s * l[1], -s * l[0] + c * l[1]];
    let (s, c) = moved[2].sin_cos();
    [moved[0] + c * body[0] - s * body[1], moved[1] + s * body[0] + c * body[1]]
}

#[test]
fn the_rim_contacts_jacobian_is_its_closed_form_and_its_finite_differences() {
    let mut rng = Random(0x5eed_d15c_0b0a_4d00);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let (system, q, v, _) = random_disc_step(&mut rng);
        let frames = system.frames(&q, &v);
        // Pair 0: the board's two lower corners on the endless floor; pair 1: the rim alone.
        assert_eq!(frames.len(), 3);
        let f = frames[2];
        assert_eq!((f.pair, f.corner_body, f.face_body), (1, Some(1), Some(0)));
        let Shape::Disc { radius } = system.bodies[1].shape else { unreachable!() };
        let Shape::Box { half_height, .. } = system.bodies[0].shape else { unreachable!() };
        // P = c_U - r n_f, n = n_f = R(theta_S) (0, 1), d = (n_y, -n_x).
        let n = [-q[0][2].sin(), q[0][2].cos()];
        let d = [n[1], -n[0]];
        let rim = [q[1][0] - radius * n[0], q[1][1] - radius * n[1]];
        assert!(f.point.iter().zip(&rim).all(|(a, b)| (a - b).abs() < 1e-15), "{:?} {rim:?}", f.point);
        let face_centre = [q[0][0] + half_height * n[0], q[0][1] + half_height * n[1]];
        let gap = (q[1][0] - face_centre[0]) * n[0] + (q[1][1] - face_centre[1]) * n[1] - radius;
        assert!((f.gap - gap).abs() < 1e-15, "{} {gap}", f.gap);
        let r_s = [rim[0] - q[0][0], rim[1] - q[0][1]];
        // Closed form: the normal through the centre (r_U x n = 0), the friction's lever r
        // (r_U x d = r, r_U x -d = -r).
        for (t, spin) in [(n, 0.0), (d, radius), ([-d[0], -d[1]], -radius)] {
            let row = f.row(t, 2);
            let closed = [-t[0], -t[1], -(r_s[0] * t[1] - r_s[1] * t[0]), t[0], t[1], spin];
            for (a, b) in row.iter().zip(&closed) {
                assert!((a - b).abs() < 1e-14, "{row:?} vs {closed:?}");
            }
            // Finite differences: each body moved rigidly by +-eps V, the rim's material point
            // relative to the board's (both at P at the start) along t, over 2 eps, is J_t V.
            let eps = 1e-6;
            let moved = |sign: f64, i: usize| {
                [
                    q[i][0] + sign * eps * v[i][0],
                    q[i][1] + sign * eps * v[i][1],
                    q[i][2] + sign * eps * v[i][2],
                ]
            };
            let relative = |sign: f64| {
                let a = material_point(q[1], moved(sign, 1), rim);
                let b = material_point(q[0], moved(sign, 0), rim);
                (a[0] - b[0]) * t[0] + (a[1] - b[1]) * t[1]
            };
            let fd = (relative(1.0) - relative(-1.0)) / (2.0 * eps);
            let jv: f64 = row.iter().zip(v.iter().flatten()).map(|(a, b)| a * b).sum();
            let scale = v.iter().flatten().fold(1.0_f64, |s, x| s.max(x.abs()));
            worst = worst.max((fd - jv).abs() / scale);
            assert!((fd - jv).abs() < 1e-7 * scale, "finite differences {fd} vs J_t V {jv}");
            let t_dot_v_rel = dot(t, f.relative_velocity(&v));
            assert!((jv - t_dot_v_rel).abs() < 1e-13 * scale, "{jv} vs {t_dot_v_rel}");
        }
    }
    eprintln!("the rim contact's rows against finite differences: worst |fd - J_t V| / |V| = {worst:e}");
}

#[test]
fn the_solver_agrees_with_enumeration_on_disc_on_board_steps() {
    // Random disc-on-board steps, and every step of the scene's runs (held, rolling, sliding).
    let mut rng = Random(0x0dd5_eed5_d15c_0001);
    let mut steps: Vec<RandomStep> = Vec::new();
    while steps.len() < 150 {
        let step = random_disc_step(&mut rng);
        if step.0.frames(&step.1, &step.2).iter().any(|f| f.active && f.pair == 1) {
            steps.push(step);
        }
    }
    let mut scene_steps = 0;
    for force in [2.0, 20.0, 100.0] {
        let p = DiscOnBoard { force, max_time: 0.05, ..DiscOnBoard::default() };
        let system = p.system();
        let mut state = State::at_rest(&system, p.start());
        for _ in 0..50 {
            let frames = system.frames(&state.q, &state.v);
            let mu = system
                .friction(&frames)
                .iter()
                .zip(&state.modes)
                .map(|(&(mu_s, mu_k), mode)| if mode.is_sliding() { mu_k } else { mu_s })
                .collect();
            steps.push((system.clone(), state.q.clone(), state.v.clone(), mu));
            scene_steps += 1;
            state.advance(&system, Starts::ALL).unwrap();
        }
    }
    let (mut by_size, mut ambiguous, mut worst) = ([0_usize; 4], 0, 0.0_f64);
    for (case, (system, q, v, mu)) in steps.iter().enumerate() {
        let frames = system.frames(q, v);
        let lcp = assemble(system, q, v, &frames, mu);
        by_size[lcp.active.len()] += 1;
        let Some((expected, enumerated_ambiguous)) = enumerated_choice(system, &lcp) else {
            panic!("case {case}: the enumeration found no solution of a {}-row step", lcp.offset.len());
        };
        let result = solve(system, &lcp, &vec![0; frames.len()], frames.len(), Starts::ALL).unwrap();
        let got: Vec<f64> = result.velocity.iter().flatten().copied().collect();
        let scale = lcp.free.iter().fold(0.0_f64, |m, x| m.max(x.abs())).max(1e-3);
        let err = got.iter().zip(&expected).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
        worst = worst.max(err);
        ambiguous += usize::from(enumerated_ambiguous);
        assert!(err < 1e-9, "case {case}: v+ {got:?}, the enumeration's {expected:?}");
        assert_eq!(result.ambiguous, enumerated_ambiguous, "case {case}");
    }
    eprintln!(
        "disc-on-board steps: {} ({scene_steps} from the scene; {:?} with 1/2/3 contacts), {ambiguous} ambiguous by enumeration, worst |v - v_enum| / S = {worst:e}",
        steps.len(),
        &by_size[1..]
    );
    assert!(by_size[3] >= 100, "{by_size:?}");
}

#[test]
fn bad_disc_on_board_parameters_and_a_disc_under_a_body_are_refused_by_name() {
    for (spec, name) in [
        (DiscOnBoard { disc_radius: 0.0, ..DiscOnBoard::default() }, "disc_radius"),
        (DiscOnBoard { disc_mass: f64::NAN, ..DiscOnBoard::default() }, "disc_mass"),
        (DiscOnBoard { offset: 0.6, ..DiscOnBoard::default() }, "offset"),
        (DiscOnBoard { mu_kinetic: 0.6, ..DiscOnBoard::default() }, "mu_kinetic"),
        (DiscOnBoard { board_height: -0.02, ..DiscOnBoard::default() }, "board_height"),
        (DiscOnBoard { step: 1.0, ..DiscOnBoard::default() }, "step"),
    ] {
        let err = run(&Spec::DiscOnBoard(spec), Sample::None).unwrap_err();
        assert!(err.contains(name), "{name}: {err}");
    }
    // A board resting on the disc: refused, and the pair has no candidate (a disc has no face).
    let mut system = DiscOnBoard::default().system();
    system.pairs[1] = Pair { upper: 0, lower: Lower::Body(1), mu_static: 0.5, mu_kinetic: 0.4 };
    let err = system.check_pairs(&["board", "disc"]).unwrap_err();
    assert!(err.contains("board rests on disc, a disc"), "{err}");
    let q = DiscOnBoard::default().start();
    assert!(system.frames(&q, &[[0.0; 3]; 2]).iter().all(|f| f.pair == 0));
    assert!(DiscOnBoard::default().system().check_pairs(&["board", "disc"]).is_ok());
}

#[test]
fn a_disc_pushed_at_its_centre_on_the_table_rolls_at_two_thirds_of_f_over_m() {
    // The rim on the table (no face body): F at the centre, friction f back, m a = F - f,
    // (m r^2 / 2) alpha = r f, rolling a = alpha r: a = 2 F / (3 m) while F / 3 <= mu_s m g;
    // beyond, a = F / m - mu_k g and alpha = 2 mu_k g / r.
    let (m, r, mu_s, mu_k) = (1.5, 0.08, 0.4, 0.3);
    for (force, rolls) in [(6.0, true), (0.99 * 3.0 * mu_s * m * G, true), (20.0, false)] {
        let system = System {
            bodies: vec![Body::disc(r, m)],
            table: Table { lo: f64::NEG_INFINITY, hi: f64::INFINITY },
            pairs: vec![Pair { upper: 0, lower: Lower::Table, mu_static: mu_s, mu_kinetic: mu_k }],
            forces: vec![[force, 0.0]],
            gravity: G,
            step: 1e-3,
            stick_speed: 1e-5,
            margin: 1e-3,
        };
        let mut state = State::at_rest(&system, vec![[0.0, r, 0.0]]);
        let mut slid = false;
        for _ in 0..200 {
            let stepped = state.advance(&system, Starts::ALL).unwrap();
            assert_eq!(stepped.frames.len(), 1);
            slid |= state.modes[0].is_sliding();
        }
        let t = state.time(&system);
        // Sliding, the first step's friction is mu_s (the disc was sticking at rest), mu_k after.
        let (v_law, omega_law) = if rolls {
            (2.0 * force / (3.0 * m) * t, -2.0 * force / (3.0 * m * r) * t)
        } else {
            let h = system.step;
            (
                (force / m - mu_k * G) * t - h * (mu_s - mu_k) * G,
                -2.0 * G * (mu_k * t + h * (mu_s - mu_k)) / r,
            )
        };
        let v = state.v[0];
        eprintln!(
            "disc on the table F = {force:.4} N: v {:.12} (law {v_law:.12}), omega {:.9} (law {omega_law:.9}), slid {slid}",
            v[0], v[2]
        );
        assert_eq!(slid, !rolls, "F = {force}");
        // Moving to the right, turning clockwise (omega < 0).
        assert!((v[0] - v_law).abs() < 1e-12 && (v[2] - omega_law).abs() < 1e-10, "{v:?}");
        assert!((state.q[0][1] - r).abs() < 1e-12 && v[1].abs() < 1e-12, "{:?}", state.q);
    }
}
