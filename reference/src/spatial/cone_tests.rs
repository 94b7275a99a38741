//! The several-contact cone (`cone.rs`) against closed forms, against the lone contact's cases
//! (`contact.rs`), and against its own conditions checked here again from the impulses alone.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

use super::algebra::{
    M3, V3, apply, congruent, cross, dot, in_plane, length, matrix_of, minus, plus, times, unit,
};
use super::cone::{self, Contacts, PointCase};
use super::contact::{self, Case, Point};

const UP: V3 = [0.0, 0.0, 1.0];

/// A pseudo-random number in `[-1, 1)` (xorshift).
fn next(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// `x` of the 3x3 system `a x = b` by Cramer's rule.
fn cramer(a: &M3, b: V3) -> V3 {
    let det = |m: &M3| dot(m[0], cross(m[1], m[2]));
    let d = det(a);
    std::array::from_fn(|c| {
        let mut m = *a;
        for (row, b_row) in m.iter_mut().zip(b) {
            row[c] = b_row;
        }
        det(&m) / d
    })
}

/// A tripod of unit mass, its feet `depth` below the centre of mass, sliding along `+x` at 1 m/s
/// on a level table without turning: every foot slides with friction `mu N_i` along `-x`, and the
/// loads are the balance's, `sum N = g h`, `sum N y_i = 0`, `sum N x_i = mu depth sum N` (the
/// friction's moment about `y` taken up by the loads).
#[test]
fn a_tripod_sliding_without_turning_carries_the_balance_s_loads() {
    let (g, h, mu, depth) = (9.81, 1e-3, 0.3, 0.05);
    for feet in [
        [[0.2, 0.0], [-0.1, 0.17], [-0.1, -0.17]],
        [[0.3, 0.05], [-0.15, 0.2], [-0.05, -0.25]],
        [[0.1, -0.1], [0.12, 0.2], [-0.3, 0.02]],
    ] {
        let arms: Vec<V3> = feet.iter().map(|f| [f[0], f[1], -depth]).collect();
        let inverse = congruent(&matrix_of([1.0, 0.0, 0.0, 0.0]), [1.0 / 0.02, 1.0 / 0.03, 1.0 / 0.04]);
        let c = Contacts {
            normals: vec![UP; 3],
            w: cone::delassus(1.0, &inverse, &arms),
            u: vec![[1.0, 0.0, -g * h]; 3],
            mu: vec![mu; 3],
        };
        let solved = cone::solve(&c, None).unwrap();
        assert_eq!(solved.cases, vec![PointCase::Slides; 3]);
        let rows = [[1.0; 3], feet.map(|f| f[1]), feet.map(|f| f[0] - mu * depth)];
        let loads = cramer(&rows, [g * h, 0.0, 0.0]);
        for (p, load) in solved.p.iter().zip(loads) {
            let want = [-mu * load, 0.0, load];
            assert!(length(minus(*p, want)) <= 1e-15, "{p:?} against {want:?}");
        }
        eprintln!("tripod {feet:?}: loads {loads:?} per unit mass, residual {:.1e}", solved.residual);
    }
}

/// The cone's conditions checked from the impulses alone; the worst miss over `|u|`.
fn check(c: &Contacts, p: &[V3], cases: &[PointCase]) -> f64 {
    let k = c.normals.len();
    let scale = c.u.iter().fold(0.0_f64, |a, u| a.max(length(*u)));
    let mut worst = 0.0_f64;
    for i in 0..k {
        let n = c.normals[i];
        let after = (0..k).fold(c.u[i], |acc, j| {
            let block: M3 =
                std::array::from_fn(|a| std::array::from_fn(|b| c.w[(3 * i + a) * 3 * k + 3 * j + b]));
            plus(acc, apply(&block, p[j]))
        });
        let (pn, pt, un, s) = (dot(p[i], n), in_plane(p[i], n), dot(after, n), in_plane(after, n));
        let limit = c.mu[i] * pn;
        assert!(pn >= -1e-15 * scale && length(pt) <= limit + 1e-12 * limit.max(1e-300), "{i}: {p:?}");
        let miss = match cases[i] {
            PointCase::Apart => length(p[i]) + (-un).max(0.0),
            PointCase::Stuck => length(after),
            PointCase::Slides => un.abs() + length(plus(pt, times(limit / length(s), s))) / pn * length(s),
        };
        worst = worst.max(miss / scale);
    }
    worst
}

/// One point: the cases of `contact.rs` (a different search: a sampled root search on the slip's
/// angle with asserted uniqueness) give the same impulse.
#[test]
fn one_contact_is_the_lone_contact_s_answer() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut counts = [0_usize; 3];
    for _ in 0..500 {
        let n = unit4_normal(&mut seed);
        let q = unit([next(&mut seed), next(&mut seed), next(&mut seed), next(&mut seed)]);
        let arm = apply(&matrix_of(q), [0.2 * next(&mut seed), 0.1 * next(&mut seed), -0.05]);
        let inverse = congruent(&matrix_of(q), [1.0 / 0.004, 1.0 / 0.0109, 1.0 / 0.0131]);
        let w = cone::delassus(1.0, &inverse, &[arm]);
        let u = [next(&mut seed), next(&mut seed), -0.01 - 0.1 * next(&mut seed).abs()];
        let mu = 0.5 * (next(&mut seed) + 1.0);
        let block: M3 = std::array::from_fn(|a| std::array::from_fn(|b| w[3 * a + b]));
        let lone = contact::solve(&Point { n, w: block, u, mu }).unwrap();
        let c = Contacts { normals: vec![n], w, u: vec![u], mu: vec![mu] };
        let several = cone::solve(&c, None).unwrap();
        let want = match lone.case {
            Case::Apart => PointCase::Apart,
            Case::Stuck => PointCase::Stuck,
            Case::Slides => PointCase::Slides,
        };
        counts[lone.case as usize] += 1;
        assert_eq!(several.cases[0], want);
        assert!(
            length(minus(several.p[0], lone.p)) <= 1e-12 * length(lone.p).max(1e-300),
            "{several:?} {lone:?}"
        );
    }
    eprintln!("one contact: apart/stuck/slides {counts:?}, the same impulses to 1e-12");
    assert!(counts.iter().all(|&k| k > 0), "{counts:?}");
}

fn unit4_normal(seed: &mut u64) -> V3 {
    let a = [0.3 * next(seed), 0.3 * next(seed), 1.0];
    times(1.0 / length(a), a)
}

/// Three points under a turned box's face, launched at random: every answer meets the
/// conditions checked here again, each case turns up, and two sticking points share a friction
/// the least-norm split would not fit.
#[test]
fn three_points_meet_their_conditions() {
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut seen = std::collections::HashMap::new();
    let (mut worst, mut fitted) = (0.0_f64, 0);
    for _ in 0..400 {
        let q = unit([1.0, 0.05 * next(&mut seed), 0.05 * next(&mut seed), next(&mut seed)]);
        let turn = matrix_of(q);
        let n = apply(&turn, UP);
        let arms: Vec<V3> = [[-0.4, -0.0125], [-0.4, 0.0125], [0.3 + 0.1 * next(&mut seed), 0.0]]
            .iter()
            .map(|a| apply(&turn, [a[0], a[1], -0.0025]))
            .collect();
        let inverse = congruent(&turn, [1.0 / 5.4e-5, 1.0 / 0.0834, 1.0 / 0.0834]);
        let base = [0.004 * next(&mut seed), 0.004 * next(&mut seed), -0.00981];
        // Pads sticking (slow fingers, the base's slip small) or sliding.
        let (speed, slope) = (if next(&mut seed) > 0.0 { 0.1 } else { 0.002 }, 0.7 * next(&mut seed));
        // A rigid motion's point velocities less the fingers'.
        let spin = [0.01 * next(&mut seed), 0.01 * next(&mut seed), 0.01 * next(&mut seed)];
        let u: Vec<V3> = arms
            .iter()
            .enumerate()
            .map(|(i, _)| {
                let finger = if i < 2 { [speed, speed * slope, 0.0] } else { [0.0; 3] };
                plus(minus(base, finger), cross(spin, arms[i]))
            })
            .collect();
        let mu = 0.3 + 0.3 * next(&mut seed).abs();
        let c = Contacts { normals: vec![n; 3], w: cone::delassus(1.0, &inverse, &arms), u, mu: vec![mu; 3] };
        let solved = cone::solve(&c, None).unwrap();
        let e = check(&c, &solved.p, &solved.cases);
        assert!(e <= 1e-11, "{c:?}: {solved:?} off by {e:e}");
        worst = worst.max(e);
        *seen.entry(solved.cases.clone()).or_insert(0) += 1;
        fitted += usize::from(solved.fitted);
    }
    eprintln!(
        "three points: {} combinations seen {seen:?}, {fitted} answers fitted into their cones, worst miss {worst:.1e} of |u|",
        seen.len()
    );
    assert!(seen.len() >= 3 && fitted > 0, "{seen:?}, {fitted} fitted");
}
