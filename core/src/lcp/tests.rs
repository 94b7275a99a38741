//! Named problems from the literature, with known answers.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::*;
use nalgebra::SVector;

fn solve<const N: usize>(m: [[f64; N]; N], q: [f64; N]) -> Result<LcpSolution<f64, N>, LcpError> {
    Lemke::<f64, N>::new().solve(&Lcp::from_rows(&m, &q))
}

fn assert_z<const N: usize>(z: &SVector<f64, N>, expect: [f64; N]) {
    for i in 0..N {
        assert!((z[i] - expect[i]).abs() < 1e-12, "z = {z:?}, expected {expect:?}");
    }
}

/// Kostreva's 3x3 example (Cottle-Pang-Stone, Example 4.9.2 family): every ratio ties in
/// the first step, and Lemke's method without a tie-breaking rule cycles on it.
#[test]
fn cycling_example_terminates() {
    let m = [[1.0, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]];
    let sol = solve(m, [-1.0, -1.0, -1.0]).unwrap();
    assert_z(&sol.z, [1.0 / 3.0; 3]);
    assert!(sol.pivots <= 7, "pivots {}", sol.pivots);
}

/// Murty (1988), chapter 6: plain Lemke needs 2^n - 1 pivots on this n = 6 problem.
#[test]
fn murty_exponential_example() {
    let mut m = [[0.0; 6]; 6];
    for i in 0..6 {
        m[i][i] = 1.0;
        for j in i + 1..6 {
            m[i][j] = 2.0;
        }
    }
    let q = [-126.0, -124.0, -120.0, -112.0, -96.0, -64.0];
    let sol = solve(m, q).unwrap();
    assert_z(&sol.z, [0.0, 0.0, 0.0, 0.0, 0.0, 64.0]);
    assert_eq!(sol.pivots, 63);
    // A cap below 2^n - 1 is a named error, not a silent stop.
    let capped = Lemke::<f64, 6>::new().with_max_pivots(40).solve(&Lcp::from_rows(&m, &q));
    assert_eq!(capped, Err(LcpError::MaxPivots { pivots: 40 }));
}

/// Cottle-Pang-Stone Example 4.4.7 (corpus lcp_CPS_2): z = (0, 1, 3).
#[test]
fn cps_example_4_4_7() {
    let m = [[0.0, -1.0, 2.0], [2.0, 0.0, -2.0], [-1.0, 1.0, 0.0]];
    let sol = solve(m, [-3.0, 6.0, -1.0]).unwrap();
    assert_z(&sol.z, [0.0, 1.0, 3.0]);
}

/// CPS Remark 4.1.14 (corpus lcp_CPS_1): PSD M = ones, tied q; every z with
/// z1 + z2 = 1 solves it. The lexicographic rule picks one, deterministically.
#[test]
fn psd_tie_case() {
    let sol = solve([[1.0, 1.0], [1.0, 1.0]], [-1.0, -1.0]).unwrap();
    assert!((sol.z[0] + sol.z[1] - 1.0).abs() < 1e-12);
    assert_eq!(sol.pivots, 1);
    assert!(is_solution(&Lcp::from_rows(&[[1.0, 1.0], [1.0, 1.0]], &[-1.0, -1.0]), &sol.z));
}

/// w = -z - 1 >= 0 has no solution with z >= 0: ray termination.
#[test]
fn unsolvable_is_ray() {
    assert_eq!(solve([[-1.0]], [-1.0]), Err(LcpError::Ray { pivots: 0 }));
    // Pang's isolated solution, perturbed (corpus): no complementary solution.
    let m = [[0.0, -1.0, -1.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]];
    let r = solve(m, [-0.0001, -1.0, 1.0]);
    assert!(matches!(r, Err(LcpError::Ray { .. })), "{r:?}");
}

/// A bimatrix game (Siconos corpus, CPS_3) has no solution. The regularised retry after the
/// ray finds `z ~ 1/delta` with `w = -1`, which must not pass as a solution (f32 and f64).
#[test]
fn infeasible_game_stays_a_ray() {
    let m = [[0.0, 0.0, 10.0, 30.0], [0.0, 0.0, 20.0, 15.0], [10.0, 30.0, 0.0, 0.0], [20.0, 15.0, 0.0, 0.0]];
    let r = solve(m, [-1.0; 4]);
    assert!(matches!(r, Err(LcpError::Ray { .. })), "{r:?}");
    let m32 = m.map(|row| row.map(|x| x as f32));
    let r32 = Lemke::<f32, 4>::new().solve(&Lcp::from_rows(&m32, &[-1.0; 4]));
    assert!(matches!(r32, Err(LcpError::Ray { .. })), "{r32:?}");
}

/// A step of the mu = 10 scene (`host-sim stress`): the two fingers' friction columns are
/// parallel up to round-off, and plain Lemke ends on a ray in f64 although the LCP has a
/// solution (exhaustive enumeration of the 256 complementary bases finds exactly one, whose
/// impulses are checked below). The regularised retry solves it, verified on the original
/// data.
#[test]
fn round_off_ray_on_a_degenerate_friction_lcp_is_rescued() {
    let (a, b, c) = (1.000_075, 7.494_790_117_123_762e-4, 7.505_209_882_876_218e-4);
    let m = [
        [1.007_489_583_853_298_2, 0.992_500_003_619_050_7, -b, b, -b, b, 0.0, 0.0],
        [0.992_500_003_619_050_7, 1.007_510_423_384_803_1, c, -c, c, -c, 0.0, 0.0],
        [-b, c, a, -a, a, -a, 1.0, 0.0],
        [b, -c, -a, a, -a, a, 1.0, 0.0],
        [-b, c, a, -a, a, -a, 0.0, 1.0],
        [b, -c, -a, a, -a, a, 0.0, 1.0],
        [10.0, 0.0, -1.0, -1.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 10.0, 0.0, 0.0, -1.0, -1.0, 0.0, 0.0],
    ];
    let q = [-0.009_81, -0.009_81, -0.1, 0.1, -1.076_279_950_579_24e-19, 1.076_279_950_579_24e-19, 0.0, 0.0];
    let lcp = Lcp::from_rows(&m, &q);
    let sol = Lemke::<f64, 8>::new().solve(&lcp).unwrap();
    assert!(sol.regularized);
    assert!(is_solution(&lcp, &sol.z));
    // All the weight on finger 1, which drags the rod with mu p_n.
    let expected = [0.009_810_051_073_714_03, 0.0, 0.098_100_510_737_140_3, 0.0, 0.0, 0.0];
    for (i, e) in expected.iter().enumerate() {
        assert!((sol.z[i] - e).abs() < 1e-12, "{:?}", sol.z);
    }
}

/// The pivot floor is a trade. `M = [[1e-9, 0], [1, 1]]`, `q = (-1, 1)` has the one solution
/// `z = (1e9, 0)`, reached by a pivot on `1e-9` in a column whose largest entry is about 1:
/// Lemke's method takes it at the default floor (`N eps`); at single precision's
/// ([`Lemke::single_precision_floor`], `N 2^-23`) it is not pivoted on and the run ends in a
/// ray. That floor is therefore a retry's (the spatial stepper's open loads), not the default.
#[test]
#[allow(clippy::float_cmp)] // the floors are exact: N times a power of two
fn a_pivot_below_the_floor_is_not_taken() {
    let lcp = Lcp::from_rows(&[[1e-9, 0.0], [1.0, 1.0]], &[-1.0, 1.0]);
    let lemke = Lemke::<f64, 2>::new();
    let sol = lemke.solve(&lcp).unwrap();
    assert!((sol.z[0] - 1e9).abs() <= 1e-6 && sol.z[1] == 0.0, "{:?}", sol.z);
    let coarse = lemke.single_precision_floor().unwrap();
    assert_eq!(coarse.pivot_floor(), 2.0 * f64::from(f32::EPSILON));
    assert!(matches!(coarse.solve(&lcp), Err(LcpError::Ray { .. })), "{:?}", coarse.solve(&lcp));
    // f32's default floor is single precision's already.
    assert!(Lemke::<f32, 2>::new().single_precision_floor().is_none());
    assert_eq!(Lemke::<f32, 2>::new().pivot_floor(), 2.0 * f32::EPSILON);
}

#[test]
fn nonnegative_q_takes_zero_pivots() {
    let sol = solve([[2.0, -7.0], [3.0, 1.0]], [0.0, 4.0]).unwrap();
    assert_eq!(sol.pivots, 0);
    assert_eq!(sol.z, SVector::<f64, 2>::zeros());
    assert_eq!(sol.w, SVector::<f64, 2>::new(0.0, 4.0));
}

#[test]
fn non_finite_input_is_rejected() {
    assert_eq!(solve([[f64::NAN]], [-1.0]), Err(LcpError::NonFiniteInput));
    assert_eq!(solve([[1.0]], [f64::NEG_INFINITY]), Err(LcpError::NonFiniteInput));
}

/// The previous solution's basis, on a slightly changed q, solves with no pivot.
#[test]
fn warm_start_takes_at_most_one_pivot() {
    let m = [[4.0, 1.0, 0.0], [1.0, 4.0, 1.0], [0.0, 1.0, 4.0]];
    let solver = Lemke::<f64, 3>::new();
    let first = solver.solve(&Lcp::from_rows(&m, &[-1.0, 2.0, -3.0])).unwrap();
    assert!(first.pivots >= 2);
    let lcp2 = Lcp::from_rows(&m, &[-1.1, 2.0, -2.9]);
    let warm = solver.solve_warm(&lcp2, first.basis).unwrap();
    assert!(warm.warm_start_used);
    assert!(warm.pivots <= 1, "pivots {}", warm.pivots);
    let cold = solver.solve(&lcp2).unwrap();
    assert!((warm.z - cold.z).norm() < 1e-12);
    // A basis that is no longer feasible still gives the right answer.
    let lcp3 = Lcp::from_rows(&m, &[1.0, -2.0, 3.0]);
    let moved = solver.solve_warm(&lcp3, first.basis).unwrap();
    let cold3 = solver.solve(&lcp3).unwrap();
    assert!((moved.z - cold3.z).norm() < 1e-12);
}

/// f32 gets its own tolerance: the same problem verifies in f32.
#[test]
fn f32_solves_with_f32_tolerance() {
    let m = [[1.0f32, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]];
    let lcp = Lcp::from_rows(&m, &[-1.0, -1.0, -1.0]);
    let sol = Lemke::<f32, 3>::new().solve(&lcp).unwrap();
    assert!(sol.residual <= default_tolerance::<f32, 3>());
    for i in 0..3 {
        assert!((sol.z[i] - 1.0 / 3.0).abs() < 1e-6);
    }
}

#[test]
fn verification_rejects_wrong_answers() {
    let lcp = Lcp::from_rows(&[[2.0, 1.0], [1.0, 2.0]], &[-5.0, -6.0]);
    assert!(is_solution(&lcp, &SVector::<f64, 2>::new(4.0 / 3.0, 7.0 / 3.0)));
    assert!(!is_solution(&lcp, &SVector::<f64, 2>::new(1.3, 2.3)));
    assert!(!is_solution(&lcp, &SVector::<f64, 2>::new(0.0, 0.0)));
    assert!(!is_solution(&lcp, &SVector::<f64, 2>::new(-1.0, 3.5)));
}

/// [`Lemke::accept`] on a caller's answer of a basis: Kostreva's problem at `z = 1/3` (every `z`
/// basic, `w = 0`) is taken as Lemke's method's own answer; a `z` with a negative entry, one whose
/// `w` is negative outside the basis, and one off the solution are refused; a row granted a
/// slack may be negative by it, and no further (a finite slack), nor beyond the residual's
/// tolerance (an infinite one).
#[test]
fn accept_holds_a_callers_answer_to_the_warm_answers_terms() {
    let lemke = Lemke::<f64, 3>::new();
    let kostreva = Lcp::from_rows(&[[1.0, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]], &[-1.0, -1.0, -1.0]);
    let all = Basis::from_z_mask(0b111);
    let z = SVector::from([1.0 / 3.0; 3]);
    let sol = lemke.accept(&kostreva, &z, all, |_| 0.0).expect("the solution");
    assert_z(&sol.z, [1.0 / 3.0; 3]);
    assert_eq!((sol.pivots, sol.basis, sol.warm_start_used), (0, all, true));
    assert!(lemke.accept(&kostreva, &SVector::from([0.5, 0.5, -0.1]), all, |_| 0.0).is_none(), "z < 0");
    assert!(
        lemke.accept(&kostreva, &SVector::from([0.3, 0.3, 0.3]), all, |_| 0.0).is_none(),
        "not complementary"
    );
    // `w = z - 1 + (0, e, 0)`: `z = (1, 0, 0)` with only `z_0` basic leaves `w_1` at `-e`.
    let e = 1e-18;
    let tied = Lcp::from_rows(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], &[-1.0, -e, 1.0]);
    let first = Basis::from_z_mask(0b001);
    let z = SVector::from([1.0, 0.0, 0.0]);
    assert!(lemke.accept(&tied, &z, first, |_| 0.0).is_none(), "w_1 < 0 outside the basis");
    let slack = |s: f64| move |i: usize| if i == 1 { s } else { 0.0 };
    assert!(lemke.accept(&tied, &z, first, slack(2.0 * e)).is_some(), "w_1 within its slack");
    assert!(lemke.accept(&tied, &z, first, slack(0.5 * e)).is_none(), "w_1 beyond its slack");
    assert!(lemke.accept(&tied, &z, first, slack(f64::INFINITY)).is_some(), "w_1 held to the residual");
    let far = Lcp::from_rows(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], &[-1.0, -0.5, 1.0]);
    assert!(lemke.accept(&far, &z, first, slack(f64::INFINITY)).is_none(), "w_1 = -0.5 fails the residual");
}

/// Beyond 32 rows (the basis's second word, the ties' sets): a P-matrix LCP of `N` rows built
/// from a chosen answer (`M = 4 I` plus ones beside the diagonal, every third `z_i` basic,
/// `q = w* - M z*`), whose one solution is that answer, solved cold, then warm from its basis
/// with no pivot.
fn wide_known_answer<const N: usize, const WORDS: usize>() {
    let mut m = [[0.0; N]; N];
    let (mut z, mut w) = ([0.0; N], [0.0; N]);
    for i in 0..N {
        m[i][i] = 4.0;
        if i + 1 < N {
            m[i][i + 1] = 1.0;
            m[i + 1][i] = 1.0;
        }
        if i % 3 == 0 {
            z[i] = 1.0 + (i as f64) / 16.0;
        } else {
            w[i] = 0.5 + (i as f64) / 32.0;
        }
    }
    let q: [f64; N] = core::array::from_fn(|i| w[i] - (0..N).map(|j| m[i][j] * z[j]).sum::<f64>());
    let lcp = Lcp::from_rows(&m, &q);
    let lemke = Lemke::<f64, N, WORDS>::new();
    let sol = lemke.solve(&lcp).unwrap();
    assert_z(&sol.z, z);
    assert!(sol.basis.is_z_basic(N - 1) == (z[N - 1] > 0.0) && sol.basis.is_z_basic(33));
    assert_eq!(sol.basis.z_count() as usize, (0..N).filter(|i| i % 3 == 0).count());
    let warm = lemke.solve_warm(&lcp, sol.basis).unwrap();
    assert_z(&warm.z, z);
    assert_eq!(warm.pivots, 0, "the answer's basis is its own warm start");
}

#[test]
fn lcps_of_more_than_32_rows() {
    wide_known_answer::<48, 2>();
    wide_known_answer::<64, 2>();
}

/// A dense, unsymmetric LCP of `N` rows with a chosen answer, solved through two words: `M` of
/// pseudo-random entries in `[-1, 1)` off the diagonal and `1 + sum_j |m_ij|` on it (strictly
/// diagonally dominant with a positive diagonal, so every principal submatrix is too and has a
/// positive determinant: a P-matrix, whose LCP has exactly one solution), `z*` and `w*` chosen
/// row by row (`z*_i > 0`, `w*_i > 0`, or both zero: degenerate rows, where the ratio test ties),
/// `q = w* - M z*`. Lemke's answer, cold and warm from a basis one row off, must be `z*`, and
/// `M z + q` must be `w*`.
fn dense_known_answer<const N: usize, const WORDS: usize>(seed: u64) {
    let mut state = seed;
    let mut uniform = || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut m = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            if i != j {
                m[i][j] = 2.0 * uniform() - 1.0;
            }
        }
        m[i][i] = 1.0 + (0..N).map(|j| m[i][j].abs()).sum::<f64>();
    }
    let (mut z, mut w) = ([0.0; N], [0.0; N]);
    for i in 0..N {
        let u = uniform();
        if u < 0.4 {
            z[i] = 0.5 + 2.0 * uniform();
        } else if u < 0.85 {
            w[i] = 0.5 + 2.0 * uniform();
        }
    }
    let q: [f64; N] = core::array::from_fn(|i| w[i] - (0..N).map(|j| m[i][j] * z[j]).sum::<f64>());
    let lcp = Lcp::from_rows(&m, &q);
    let lemke = Lemke::<f64, N, WORDS>::new();
    let close = |sol: &LcpSolution<f64, N, WORDS>| {
        for i in 0..N {
            assert!((sol.z[i] - z[i]).abs() < 1e-9, "z_{i} = {} against {}", sol.z[i], z[i]);
            let wi: f64 = q[i] + (0..N).map(|j| m[i][j] * sol.z[j]).sum::<f64>();
            assert!((wi - w[i]).abs() < 1e-9, "w_{i} = {wi} against {}", w[i]);
        }
    };
    let cold = lemke.solve(&lcp).unwrap();
    close(&cold);
    assert!(cold.pivots > 0 && !cold.warm_start_used);
    // The answer's basis with its last basic `z` swapped for a `w`: a warm start that is wrong
    // in one row, in the second word when the answer has a basic `z` there.
    let mut off = cold.basis;
    let last = (0..N).rev().find(|&i| z[i] > 0.0).unwrap();
    off.set_z_basic(last, false);
    assert!(!off.is_z_basic(last) && off.z_count() + 1 == cold.basis.z_count());
    close(&lemke.solve_warm(&lcp, off).unwrap());
}

#[test]
fn dense_lcps_of_48_and_64_rows_reach_their_chosen_answers() {
    for seed in [1, 2, 3] {
        dense_known_answer::<48, 2>(seed);
        dense_known_answer::<64, 2>(seed);
    }
}

/// Ties across both words: `M = diag(d)`, `q = -e`, whose answer is `z_i = 1 / d_i`. Every row
/// ties in the first ratio test and, after it, every row but the pivot's is degenerate, so every
/// pivot breaks a tie of up to `N` rows lexicographically.
#[test]
fn ties_over_64_rows_break_lexicographically() {
    const N: usize = 64;
    let d: [f64; N] = core::array::from_fn(|i| 1.0 + (i as f64) / 8.0);
    let m: [[f64; N]; N] =
        core::array::from_fn(|i| core::array::from_fn(|j| if i == j { d[i] } else { 0.0 }));
    let sol = Lemke::<f64, N, 2>::new().solve(&Lcp::from_rows(&m, &[-1.0; N])).unwrap();
    assert_z(&sol.z, core::array::from_fn(|i| 1.0 / d[i]));
    assert_eq!(sol.basis.z_count() as usize, N);
}

/// [`rows::Rows`] of 60 rows in two words against a set of booleans: the same members, count and
/// lowest member after every insertion and removal.
#[test]
fn sets_of_60_rows_match_a_set_of_booleans() {
    const N: usize = 60;
    let mut rows = rows::Rows::<N, 2>::EMPTY;
    let mut model = [false; N];
    let mut state = 7u64;
    for _ in 0..2000 {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let i = (state >> 33) as usize % N;
        if (state >> 20) & 1 == 1 {
            rows.insert(i);
            model[i] = true;
        } else {
            rows.remove(i);
            model[i] = false;
        }
        assert!((0..N).all(|k| rows.contains(k) == model[k]));
        assert_eq!(rows.len() as usize, model.iter().filter(|&&b| b).count());
        assert_eq!(rows.first(), model.iter().position(|&b| b).unwrap_or(N - 1));
    }
}

/// `w` summed over `z`'s entries that are not zero is `w` summed over all of them, entry for entry
/// (a zero of either sign equal), on a problem whose columns against a zero `z_j` are not zero.
#[cfg(feature = "spatial")]
#[test]
#[allow(clippy::float_cmp)] // the point of it: the same sums, to the bit
fn sparse_w_is_the_whole_sum() {
    let m = [[4.0, -1.0, 0.5, 2.0], [-1.0, 3.0, -0.25, 1.0], [0.5, -0.25, 2.0, -3.0], [2.0, 1.0, -3.0, 5.0]];
    let lcp = Lcp::from_rows(&m, &[-1.0, 0.5, -0.125, 3.0]);
    for z in [
        [0.0, 0.0, 0.0, 0.0],
        [0.7, 0.0, 0.0, 0.0],
        [0.0, 1.3, 0.0, 0.2],
        [0.3, 0.0, 2.5, 0.0],
        [1.0, 2.0, 3.0, 4.0],
    ] {
        let z = SVector::from(z);
        let (sparse, whole) = (lcp.w_of_sparse(&z), lcp.w_of(&z));
        assert!(sparse.iter().zip(&whole).all(|(a, b)| a == b), "{sparse:?} against {whole:?}");
    }
}
