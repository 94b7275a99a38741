//! The scenes' analytic laws (docs/scenes.md, "block-on-block", "tablecloth", "stack") on the
//! reference's own runs, and its refusals.

use super::*;

// ---------------------------------------------------------------------------------------------
// block-on-block.

#[test]
fn block_on_block_follows_its_laws() {
    let p = BlockOnBlock::default();
    let (m, big_m) = (p.top_mass, p.bottom_mass);
    let held = p.mu_floor * (big_m + m) * G;
    let slides = (p.mu_static + p.mu_floor) * (big_m + m) * G;
    let tol = 1e-9;
    let mut worst: f64 = 0.0;
    for (force, expected) in [
        (0.5 * held, Outcome::Held),
        (0.98 * held, Outcome::Held),
        (1.02 * held, Outcome::Rode),
        (0.5 * (held + slides), Outcome::Rode),
        (0.98 * slides, Outcome::Rode),
        (1.02 * slides, Outcome::Slid),
        (1.5 * slides, Outcome::Slid),
        (3.0 * slides, Outcome::Slid),
    ] {
        let r = run_spec(Spec::BlockOnBlock(BlockOnBlock { force, ..p }));
        let (lower, upper) = (r.lower_acceleration.unwrap(), r.upper_acceleration.unwrap());
        let (expected_lower, expected_upper) = match expected {
            Outcome::Held => (0.0, 0.0),
            Outcome::Rode => {
                let a = force / (big_m + m) - p.mu_floor * G;
                (a, a)
            }
            _ => ((force - p.mu_kinetic * m * G - p.mu_floor * (big_m + m) * G) / big_m, p.mu_kinetic * G),
        };
        let err = (lower - expected_lower).abs().max((upper - expected_upper).abs());
        worst = worst.max(err);
        eprintln!(
            "block-on-block F = {force:7.3} N: {:?}, a_bottom {lower:.12} (law {expected_lower:.12}), a_top {upper:.12} (law {expected_upper:.12}), {} ambiguous",
            r.outcome, r.ambiguous_steps
        );
        assert_eq!(r.outcome, expected, "F = {force}");
        assert!(err < tol, "F = {force}: accelerations off the law by {err:e}");
        // Held or riding to the end: the summed force of the bottom block on the top one (the
        // model decides the sum, not the corners' shares) is m a along x and m g up; the
        // floor's on the pair (M + m) a - F along x and (M + m) g up.
        if expected != Outcome::Slid {
            let [top, floor] = [r.interface_forces[1], r.interface_forces[0]];
            let floor_x = (big_m + m) * expected_upper - force;
            assert!((top[0] - m * expected_upper).abs() < 1e-9 && (top[1] - m * G).abs() < 1e-9, "{top:?}");
            assert!(
                (floor[0] - floor_x).abs() < 1e-9 && (floor[1] - (big_m + m) * G).abs() < 1e-9,
                "{floor:?}"
            );
        }
        if expected == Outcome::Held {
            assert!(r.max_speed < 1e-12, "held, yet moved at {:e} m/s", r.max_speed);
        }
    }
    eprintln!("block-on-block: worst acceleration error {worst:e} m/s^2 (tolerance {tol:e})");
}

#[test]
fn a_tall_top_block_tips_above_g_w_over_h() {
    // w / h = 1/4 < mu_s: tipping comes first, at a = g w / h.
    let p = BlockOnBlock { top_width: 0.05, top_height: 0.2, max_time: 1.0, ..BlockOnBlock::default() };
    let total = p.top_mass + p.bottom_mass;
    let tips = total * (G * p.top_width / p.top_height + p.mu_floor * G);
    assert!(p.top_width / p.top_height < p.mu_static);
    for (factor, expected) in
        [(0.9, Outcome::Rode), (0.97, Outcome::Rode), (1.03, Outcome::Tipped), (1.2, Outcome::Tipped)]
    {
        let force = factor * tips;
        let r = run_spec(Spec::BlockOnBlock(BlockOnBlock { force, ..p }));
        eprintln!(
            "tall top block F = {force:.3} N ({factor} of the tipping force): {:?} at t = {:.3} s",
            r.outcome, r.end_time
        );
        assert_eq!(r.outcome, expected, "F = {force}");
        if expected == Outcome::Rode {
            let a = force / total - p.mu_floor * G;
            assert!((r.upper_acceleration.unwrap() - a).abs() < 1e-9, "{r:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// tablecloth.

#[test]
fn tablecloth_follows_its_laws() {
    let p = Tablecloth::default();
    let (m, mb) = (p.block_mass, p.board_mass);
    let held = p.mu_floor * (m + mb) * G;
    let rides = (p.mu_static + p.mu_floor) * (m + mb) * G;
    let tol = 1e-9;
    let mut worst: f64 = 0.0;
    for (force, expected) in [
        (0.5 * held, Outcome::Held),
        (0.98 * held, Outcome::Held),
        (1.02 * held, Outcome::Rode),
        (0.98 * rides, Outcome::Rode),
    ] {
        let r = run_spec(Spec::Tablecloth(Tablecloth { force, max_time: 0.3, ..p }));
        let a = if expected == Outcome::Held { 0.0 } else { force / (m + mb) - p.mu_floor * G };
        let (lower, upper) = (r.lower_acceleration.unwrap(), r.upper_acceleration.unwrap());
        eprintln!(
            "tablecloth F = {force:.3} N: {:?}, a_board {lower:.12}, a_block {upper:.12} (law {a:.12})",
            r.outcome
        );
        assert_eq!(r.outcome, expected, "F = {force}");
        worst = worst.max((lower - a).abs()).max((upper - a).abs());
        assert!((lower - a).abs() < tol && (upper - a).abs() < tol, "{r:?}");
    }
    let mut previous = f64::INFINITY;
    for factor in [1.03, 1.5, 3.0, 6.0, 12.0] {
        let force = factor * rides;
        let r = run_spec(Spec::Tablecloth(Tablecloth { force, ..p }));
        let a_board = (force - p.mu_kinetic * m * G - p.mu_floor * (m + mb) * G) / mb;
        let a_block = p.mu_kinetic * G;
        let (lower, upper) = (r.lower_acceleration.unwrap(), r.upper_acceleration.unwrap());
        let d = r.block_displacement.unwrap();
        // The block leaves the board after a relative travel between `offset` (its rear corner
        // reaches the trailing edge) and `offset + w` (its front corner does), accelerating at
        // mu_k g until then (time `t = sqrt(2 s / a_rel)`, speed `v = mu_k g t`); it then drops
        // the board's thickness `t_b` (at most `sqrt(2 t_b / g)` in the air) and slides to rest
        // at mu_floor g, having lost at most `mu_floor sqrt(2 g t_b)` of speed in the landing.
        let travel = |s: f64| {
            let t = (2.0 * s / (a_board - a_block)).sqrt();
            (0.5 * a_block * t * t, a_block * t)
        };
        let stop = |v: f64| v * v / (2.0 * p.mu_floor * G);
        let (x_low, v_low) = travel(p.offset);
        let low = x_low + stop((v_low - p.mu_floor * (2.0 * G * p.board_thickness).sqrt()).max(0.0));
        let (x_high, v_high) = travel(p.offset + p.block_width);
        let high = x_high + v_high * (2.0 * p.board_thickness / G).sqrt() + stop(v_high);
        eprintln!(
            "tablecloth F = {force:.3} N: {:?} at {:.3} s, a_board {lower:.9} (law {a_board:.9}), a_block {upper:.9} (law {a_block:.9}), displacement {d:.6} m in [{low:.6}, {high:.6}]",
            r.outcome, r.end_time
        );
        assert_eq!(r.outcome, Outcome::Stayed, "F = {force}");
        worst = worst.max((lower - a_board).abs() / a_board).max((upper - a_block).abs());
        assert!((lower - a_board).abs() < tol * a_board && (upper - a_block).abs() < tol, "{r:?}");
        assert!(low <= d && d <= high, "displacement {d} outside [{low}, {high}]");
        assert!(d < previous, "pulling harder moved the block more: {d} after {previous}");
        previous = d;
    }
    eprintln!(
        "tablecloth: worst acceleration error {worst:e} (m/s^2, the board's above the threshold relative)"
    );
}

// ---------------------------------------------------------------------------------------------
// stack.

#[test]
fn the_stack_holds_below_the_harmonic_overhangs_and_falls_above() {
    for blocks in [2, 3] {
        for (overhang, expected) in
            [(0.9, Outcome::Held), (0.98, Outcome::Held), (1.02, Outcome::Fell), (1.1, Outcome::Fell)]
        {
            let r = run_spec(Spec::Stack(Stack { blocks, overhang, max_time: 1.0, ..Stack::default() }));
            eprintln!(
                "stack of {blocks} at overhang {overhang}: {:?} at {:.3} s, max speed {:e} m/s, {} rows, {:.1} us/step",
                r.outcome,
                r.end_time,
                r.max_speed,
                r.max_rows,
                r.seconds_per_step * 1e6
            );
            assert_eq!(r.outcome, expected, "{blocks} blocks at {overhang}");
            if expected == Outcome::Held {
                assert!(r.max_speed < 1e-12, "held, yet moved at {:e} m/s", r.max_speed);
            }
        }
    }
}

#[test]
fn a_held_stack_of_three_does_not_creep_in_ten_seconds() {
    let p = Stack::default();
    assert_eq!((p.blocks, p.overhang, p.max_time, p.step), (3, 0.98, 10.0, 1e-3));
    let start = p.start();
    let r = run_spec(Spec::Stack(p));
    let drift =
        r.q.iter()
            .zip(&start)
            .flat_map(|(q, s)| (0..3).map(move |c| (q[c] - s[c]).abs()))
            .fold(0.0, f64::max);
    eprintln!(
        "stack of 3 at 0.98 over 10 s: {:?}, max speed {:e} m/s, largest drift {drift:e}, interface forces {:?} N, {} rows, {:.1} us/step",
        r.outcome,
        r.max_speed,
        r.interface_forces,
        r.max_rows,
        r.seconds_per_step * 1e6
    );
    assert_eq!(r.outcome, Outcome::Held);
    assert_eq!(r.steps, 10_000);
    assert!(r.max_speed < 1e-12, "creep: {:e} m/s", r.max_speed);
    assert!(drift < 1e-12, "drift {drift:e}");
    // The table carries the whole stack; each interface the blocks above it (the sums the
    // model decides).
    for (pair, f) in r.interface_forces.iter().enumerate() {
        let carried = (p.blocks - pair) as f64 * p.mass * G;
        assert!((f[1] - carried).abs() < 1e-9 * carried && f[0].abs() < 1e-9 * carried, "pair {pair}: {f:?}");
    }
    assert_eq!(r.ambiguous_steps, 0);
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let err =
        run(&Spec::BlockOnBlock(BlockOnBlock { top_width: 0.5, ..BlockOnBlock::default() }), Sample::None)
            .unwrap_err();
    assert!(err.contains("top_width"), "{err}");
    let err = run(&Spec::Tablecloth(Tablecloth { mu_kinetic: 0.9, ..Tablecloth::default() }), Sample::None)
        .unwrap_err();
    assert!(err.contains("mu_kinetic"), "{err}");
    let err =
        run(&Spec::Tablecloth(Tablecloth { contact_margin: 0.01, ..Tablecloth::default() }), Sample::None)
            .unwrap_err();
    assert!(err.contains("contact_margin"), "{err}");
    let err = run(&Spec::Stack(Stack { blocks: 6, ..Stack::default() }), Sample::None).unwrap_err();
    assert!(err.contains("blocks"), "{err}");
    let err = run(&Spec::Stack(Stack { overhang: f64::NAN, ..Stack::default() }), Sample::None).unwrap_err();
    assert!(err.contains("overhang"), "{err}");
}

#[test]
fn stacks_of_four_and_five_solve_32_and_40_rows_and_an_aligned_stack_holds() {
    // Four blocks: 4 interfaces x 2 contacts = 8 contacts, a 32-row LCP each step; five: 40.
    for (blocks, overhang, expected, max_time) in [
        (4, 0.98, Outcome::Held, 1.0),
        (4, 1.02, Outcome::Fell, 1.0),
        (5, 0.98, Outcome::Held, 0.3),
        (5, 1.02, Outcome::Fell, 1.0),
        (3, 0.0, Outcome::Held, 1.0),
    ] {
        let p = Stack { blocks, overhang, max_time, ..Stack::default() };
        let r = run_spec(Spec::Stack(p));
        eprintln!(
            "stack of {blocks} at overhang {overhang}: {:?} at {:.3} s, max speed {:e} m/s, {} rows, {:.1} us/step",
            r.outcome,
            r.end_time,
            r.max_speed,
            r.max_rows,
            r.seconds_per_step * 1e6
        );
        assert_eq!(r.outcome, expected);
        assert_eq!(r.max_rows, 8 * blocks);
        if expected == Outcome::Held {
            assert!(r.max_speed < 1e-12, "held, yet moved at {:e} m/s", r.max_speed);
            // Aligned blocks (overhang 0) rest on both corners: indeterminate, the sums decided.
            for (pair, f) in r.interface_forces.iter().enumerate() {
                let carried = (blocks - pair) as f64 * p.mass * G;
                assert!(
                    (f[1] - carried).abs() < 1e-9 * carried && f[0].abs() < 1e-9 * carried,
                    "pair {pair}: {f:?}"
                );
            }
        }
    }
}
