//! Exhaustive enumeration of the complementary bases of a small LCP (docs/formulation.md, eq. 1
//! and "Checks that need no simulation to trust"): the reference's solver ([`enumerate`]) and the
//! integration tests' independent check of the core's Lemke solver ([`all_solutions`],
//! [`is_lcp_solution`], [`solve_dense`]). Both walk the same bases with the same elimination
//! ([`each_basic_solution`]); they differ in what they accept.
//!
//! Find `z` with `w = A z + b`, `z >= 0`, `w >= 0`, `z . w = 0`. A complementary basis is a set
//! `a` of indices: `w_i = 0` and `z_i` basic for `i` in `a`, `z_i = 0` and `w_i` basic outside it.
//! For each of the `2^n` sets, solve `A_aa z_a = -b_a` by Gaussian elimination with partial
//! pivoting. [`enumerate`] keeps the basis when
//! `z_a >= -tol` and `w_i >= -tol` for every `i` outside `a`, with `tol = 1e-13 (|b|_max +
//! |A|_max |z_a|_max)` (f64 elimination on these well-conditioned systems of size <= 12 is good
//! to ~1e-15; a looser tolerance admits near-solutions). A principal submatrix whose pivot falls
//! to `1e-12 |A|_max` is singular and its basis skipped. Every basic solution Lemke's method can
//! end on has a nonsingular complementary basis, so the enumeration finds it.

/// The largest LCP enumerated: `2^16` bases of at most `16 x 16` (4 active contacts).
pub const MAX_ENUMERATED: usize = 16;

/// One LCP `w = A z + b`.
#[derive(Debug, Clone, PartialEq)]
pub struct Lcp {
    /// Its size `n`.
    pub size: usize,
    /// `A`, row-major, `n x n`.
    pub matrix: Vec<f64>,
    /// `b`, `n`.
    pub offset: Vec<f64>,
}

/// One solution found by the enumeration.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// The complementary basis: bit `i` set when `z_i` is basic.
    pub basis: u64,
    /// `z`, with round-off negatives clamped to 0.
    pub z: Vec<f64>,
}

/// A dense square matrix, row-major, as the tests write them.
pub type Mat = Vec<Vec<f64>>;

/// Solves the `k x k` system `a x = rhs` (`a` row-major with stride `k`) in place by Gaussian
/// elimination with partial pivoting; `rhs` becomes `x`. `false` when a pivot is at most `tiny`.
fn solve_in_place(a: &mut [f64], rhs: &mut [f64], k: usize, tiny: f64) -> bool {
    for col in 0..k {
        let mut pivot = col;
        for row in col + 1..k {
            if a[row * k + col].abs() > a[pivot * k + col].abs() {
                pivot = row;
            }
        }
        if a[pivot * k + col].abs() <= tiny {
            return false;
        }
        if pivot != col {
            for c in 0..k {
                a.swap(col * k + c, pivot * k + c);
            }
            rhs.swap(col, pivot);
        }
        for row in col + 1..k {
            let factor = a[row * k + col] / a[col * k + col];
            if factor != 0.0 {
                for c in col..k {
                    a[row * k + c] -= factor * a[col * k + c];
                }
                rhs[row] -= factor * rhs[col];
            }
        }
    }
    for row in (0..k).rev() {
        let mut s = rhs[row];
        for c in row + 1..k {
            s -= a[row * k + c] * rhs[c];
        }
        rhs[row] = s / a[row * k + row];
    }
    true
}

/// Calls `visit(basis, z)` for each of the `2^n` complementary bases of `lcp` whose principal
/// system `A_aa z_a = -b_a` is regular (no pivot at most `1e-12 |A|_max`), in increasing basis
/// order, with `z` that system's solution (zero outside the basis, not clamped).
///
/// # Panics
/// When `lcp.size > MAX_ENUMERATED` or the matrix or offset has the wrong length (programming
/// errors: the caller checks the size).
pub fn each_basic_solution(lcp: &Lcp, mut visit: impl FnMut(u64, &[f64])) {
    let n = lcp.size;
    assert!(n <= MAX_ENUMERATED, "enumeration of a {n}x{n} LCP");
    assert!(lcp.matrix.len() == n * n && lcp.offset.len() == n, "malformed LCP");
    let (a, b) = (&lcp.matrix, &lcp.offset);
    let a_max = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let tiny = 1e-12 * a_max.max(f64::MIN_POSITIVE);
    let mut basic = Vec::with_capacity(n);
    let mut sub = vec![0.0; n * n];
    let mut z_basic = vec![0.0; n];
    let mut z = vec![0.0; n];
    for basis in 0..(1_u64 << n) {
        basic.clear();
        basic.extend((0..n).filter(|&i| basis >> i & 1 == 1));
        let k = basic.len();
        for (r, &row) in basic.iter().enumerate() {
            for (c, &col) in basic.iter().enumerate() {
                sub[r * k + c] = a[row * n + col];
            }
            z_basic[r] = -b[row];
        }
        if !solve_in_place(&mut sub[..k * k], &mut z_basic[..k], k, tiny) {
            continue;
        }
        z.fill(0.0);
        for (r, &row) in basic.iter().enumerate() {
            z[row] = z_basic[r];
        }
        visit(basis, &z);
    }
}

/// Every solution among the `2^n` complementary bases with a regular principal system, in
/// increasing basis order: the basis is kept when `z_a >= -tol` and `w_i >= -tol` outside it,
/// `tol = 1e-13 (|b|_max + |A|_max |z_a|_max)`.
///
/// # Panics
/// As [`each_basic_solution`].
#[must_use]
pub fn enumerate(lcp: &Lcp) -> Vec<Solution> {
    let n = lcp.size;
    let (a, b) = (&lcp.matrix, &lcp.offset);
    let a_max = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let b_max = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut found = Vec::new();
    each_basic_solution(lcp, |basis, z| {
        let z_max = z.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let tol = 1e-13 * (b_max + a_max * z_max);
        if z.iter().any(|&x| x < -tol) {
            return;
        }
        let complementary = (0..n)
            .all(|i| basis >> i & 1 == 1 || (0..n).map(|j| a[i * n + j] * z[j]).sum::<f64>() + b[i] >= -tol);
        if complementary {
            found.push(Solution { basis, z: z.iter().map(|x| x.max(0.0)).collect() });
        }
    });
    found
}

/// Solves `a x = b` (Gaussian elimination, partial pivoting). `None` when a pivot is at most
/// `1e-12 |a|_max`.
#[must_use]
pub fn solve_dense(a: &Mat, b: &[f64]) -> Option<Vec<f64>> {
    let n = b.len();
    let mut flat: Vec<f64> = a.iter().flat_map(|r| r[..n].iter().copied()).collect();
    let scale = flat.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    let mut x = b.to_vec();
    solve_in_place(&mut flat, &mut x, n, 1e-12 * scale).then_some(x)
}

/// `w = M z + q`.
#[must_use]
pub fn w_of(m: &Mat, q: &[f64], z: &[f64]) -> Vec<f64> {
    m.iter().zip(q).map(|(row, &qi)| qi + row.iter().zip(z).map(|(a, b)| a * b).sum::<f64>()).collect()
}

/// The tests' acceptance check: `z >= -tol s`, `w >= -tol s`, `|z_i w_i| <= tol s^2` with
/// `s = 1 + ||M|| ||z|| + ||q||`.
#[must_use]
pub fn is_lcp_solution(m: &Mat, q: &[f64], z: &[f64], tol: f64) -> bool {
    let w = w_of(m, q, z);
    let mn = m.iter().map(|r| r.iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max);
    let zn = z.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let qn = q.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let s = 1.0 + mn * zn + qn;
    z.iter().zip(&w).all(|(&zi, &wi)| zi >= -tol * s && wi >= -tol * s && (zi * wi).abs() <= tol * s * s)
}

/// Every complementary basic solution of `(M, q)` that [`is_lcp_solution`] accepts within
/// `1e-9`, clamped at 0, duplicates removed: the tests' set of answers an LCP solver may give.
///
/// # Panics
/// When `n > 16` (enumeration is for small problems).
#[must_use]
pub fn all_solutions(m: &Mat, q: &[f64]) -> Vec<Vec<f64>> {
    let n = q.len();
    let lcp =
        Lcp { size: n, matrix: m.iter().flat_map(|r| r[..n].iter().copied()).collect(), offset: q.to_vec() };
    let mut found: Vec<Vec<f64>> = Vec::new();
    each_basic_solution(&lcp, |_, z| {
        if is_lcp_solution(m, q, z, 1e-9) {
            let z: Vec<f64> = z.iter().map(|x| x.max(0.0)).collect();
            if !found.iter().any(|f| f.iter().zip(&z).all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs()))) {
                found.push(z);
            }
        }
    });
    found
}

/// `max_S ||M_SS^-1||_inf` over all non-empty principal submatrices: the Lipschitz constant of a
/// P-matrix LCP's solution with respect to `q` (in the infinity norm).
#[must_use]
pub fn max_principal_inverse_norm(m: &Mat) -> f64 {
    let n = m.len();
    let mut worst: f64 = 0.0;
    for mask in 1u32..(1 << n) {
        let s: Vec<usize> = (0..n).filter(|i| mask >> i & 1 == 1).collect();
        let a: Mat = s.iter().map(|&i| s.iter().map(|&j| m[i][j]).collect()).collect();
        let k = s.len();
        let mut norm_rows = vec![0.0; k];
        for c in 0..k {
            let mut e = vec![0.0; k];
            e[c] = 1.0;
            let Some(col) = solve_dense(&a, &e) else { return f64::INFINITY };
            for r in 0..k {
                norm_rows[r] += col[r].abs();
            }
        }
        worst = worst.max(norm_rows.into_iter().fold(0.0, f64::max));
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_p_matrix_lcp_has_exactly_one_solution() {
        // A = [[2, 1], [1, 2]], b = [-5, -6]: z = (4/3, 7/3), w = 0.
        let lcp = Lcp { size: 2, matrix: vec![2.0, 1.0, 1.0, 2.0], offset: vec![-5.0, -6.0] };
        let found = enumerate(&lcp);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].basis, 0b11);
        assert!((found[0].z[0] - 4.0 / 3.0).abs() < 1e-14 && (found[0].z[1] - 7.0 / 3.0).abs() < 1e-14);
        // b >= 0: z = 0 only.
        let lcp = Lcp { size: 2, matrix: vec![2.0, 1.0, 1.0, 2.0], offset: vec![1.0, 0.5] };
        assert_eq!(enumerate(&lcp), vec![Solution { basis: 0, z: vec![0.0, 0.0] }]);
    }

    #[test]
    fn a_degenerate_lcp_lists_every_vertex() {
        // A = [[1, 1], [1, 1]], b = [-1, -1]: z1 + z2 = 1, vertices (1, 0) and (0, 1); the basis
        // {1, 2} is singular and skipped.
        let lcp = Lcp { size: 2, matrix: vec![1.0; 4], offset: vec![-1.0, -1.0] };
        let found = enumerate(&lcp);
        let bases: Vec<u64> = found.iter().map(|s| s.basis).collect();
        assert_eq!(bases, vec![0b01, 0b10]);
    }

    #[test]
    fn an_empty_lcp_has_the_empty_solution() {
        let lcp = Lcp { size: 0, matrix: Vec::new(), offset: Vec::new() };
        assert_eq!(enumerate(&lcp), vec![Solution { basis: 0, z: Vec::new() }]);
    }
}
