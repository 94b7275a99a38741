//! The stack in three dimensions against its laws (docs/scenes.md, "stack-3d"): held at 0.98 and
//! fallen at 1.02 at every heading, the table carrying the stack's weight, and at heading 0 the
//! planar reference's stack (`crate::multibody`, a separate model: two-dimensional, its own
//! contacts and rule).
#![allow(clippy::unwrap_used, clippy::float_cmp, clippy::panic)]

use super::stack::{Stack3d, run_stack_3d_keeping};
use super::{Keep, Outcome};
use crate::Sample;
use crate::multibody::{Spec, Stack, run};

/// 2 and 3 blocks at headings -45 to 60 degrees: at `s = 0.98` held over 0.3 s with every speed
/// round-off's and the table carrying `n m g h` a step; at 1.02 fallen, every step within the
/// reference's sticking cases.
#[test]
fn the_stack_holds_at_098_and_falls_at_102_at_every_heading() {
    for blocks in [2, 3] {
        for heading_deg in [0.0f64, 15.0, 30.0, -45.0, 60.0] {
            let base =
                Stack3d { blocks, heading: heading_deg.to_radians(), max_time: 0.3, ..Stack3d::default() };
            let held = run_stack_3d_keeping(&Stack3d { overhang: 0.98, ..base }, Keep::StartAndEnd).unwrap();
            assert_eq!(held.outcome, Outcome::Held, "{blocks} blocks at {heading_deg} deg, s = 0.98");
            assert!(
                held.max_speed < 1e-9,
                "{blocks} blocks at {heading_deg} deg: max speed {}",
                held.max_speed
            );
            let weight = blocks as f64 * base.mass * base.g * base.h;
            assert!(
                (held.table_impulse - weight).abs() <= 1e-9 * weight,
                "{blocks} blocks at {heading_deg} deg: the table carries {} N s a step, the stack weighs {weight}",
                held.table_impulse
            );
            let fell = run_stack_3d_keeping(&Stack3d { overhang: 1.02, ..base }, Keep::StartAndEnd)
                .unwrap_or_else(|e| panic!("{blocks} blocks at {heading_deg} deg, s = 1.02: {e}"));
            assert_eq!(fell.outcome, Outcome::Fell, "{blocks} blocks at {heading_deg} deg, s = 1.02");
            assert!(fell.steps < 300, "{blocks} blocks at {heading_deg} deg fell after {} steps", fell.steps);
        }
    }
}

/// Heading 0: each block's centre of mass `(x, z)` is the planar reference's `(x, y)`, and its
/// turn about `-y` the planar `theta`, step by step, falling at 1.02 and held at 0.98.
#[test]
fn heading_zero_is_the_planar_stack() {
    for overhang in [0.98, 1.02] {
        let spatial = Stack3d { overhang, max_time: 0.3, ..Stack3d::default() };
        let three = run_stack_3d_keeping(&spatial, Keep::All).unwrap();
        let planar = Stack { overhang, max_time: 0.3, ..Stack::default() };
        let two = run(&Spec::Stack(planar), Sample::All).unwrap();
        assert_eq!(two.steps, three.steps, "s = {overhang}: steps");
        let mut worst = 0.0f64;
        for (row, (t, x, q)) in two.rows.iter().zip(&three.trajectory) {
            assert!((row.t - t).abs() <= 1e-12);
            for (b, (p, qq)) in x.iter().zip(q).enumerate() {
                let [px, py, theta] = row.q[b];
                // A turn by theta about -y: q = (cos(theta/2), 0, -sin(theta/2), 0).
                let (c, s) = ((0.5 * theta).cos(), -(0.5 * theta).sin());
                let turn = (qq[0] - c).abs().max((qq[2] - s).abs()).max(qq[1].abs()).max(qq[3].abs());
                worst = worst.max((p[0] - px).abs()).max((p[2] - py).abs()).max(p[1].abs()).max(turn);
            }
        }
        assert!(worst <= 1e-9, "s = {overhang}: the spatial stack is {worst} from the planar one");
    }
}

/// The parameters the docs refuse, by name.
#[test]
fn invalid_stacks_are_refused_by_name() {
    use super::{Error, Rule};
    let p = Stack3d::default();
    for (bad, field) in [
        (Stack3d { blocks: 1, ..p }, "blocks"),
        (Stack3d { width: 0.0, ..p }, "width"),
        (Stack3d { heading: 61f64.to_radians(), ..p }, "heading"),
        (Stack3d { mu_k: 0.6, ..p }, "mu_k"),
        (Stack3d { overhang: 6.0, ..p }, "overhang"),
    ] {
        match run_stack_3d_keeping(&bad, Keep::StartAndEnd) {
            Err(Error::Invalid { field: f, rule }) => {
                assert_eq!(f, field, "{rule:?}");
            }
            other => panic!("{field}: {other:?}"),
        }
    }
    assert!(matches!(
        run_stack_3d_keeping(&Stack3d { length: f64::NAN, ..p }, Keep::StartAndEnd),
        Err(Error::Invalid { field: "length", rule: Rule::NotFinite })
    ));
}
