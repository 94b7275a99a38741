//! Exhaustive enumeration of the `2^n` complementary bases of an LCP, in f64, written
//! separately from the core solver: for each subset `S` (the `z_i` allowed to be non-zero)
//! solve `M_SS z_S = -q_S` by Gaussian elimination with partial pivoting, set
//! `w = M z + q`, and keep `z` when `z >= -tol` and `w >= -tol`.

/// A dense square matrix, row-major.
pub type Mat = Vec<Vec<f64>>;

/// Solves `a x = b` (Gaussian elimination, partial pivoting). `None` when singular.
#[must_use]
pub fn solve_dense(a: &Mat, b: &[f64]) -> Option<Vec<f64>> {
    let n = b.len();
    let mut a: Mat = a
        .iter()
        .zip(b)
        .map(|(row, &bi)| {
            let mut r = row.clone();
            r.push(bi);
            r
        })
        .collect();
    let scale = a.iter().flat_map(|r| r[..n].iter()).fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[p][k].abs() <= 1e-12 * scale {
            return None;
        }
        a.swap(k, p);
        for i in k + 1..n {
            let f = a[i][k] / a[k][k];
            for j in k..=n {
                a[i][j] -= f * a[k][j];
            }
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (a[k][n] - s) / a[k][k];
    }
    Some(x)
}

/// `w = M z + q`.
#[must_use]
pub fn w_of(m: &Mat, q: &[f64], z: &[f64]) -> Vec<f64> {
    m.iter().zip(q).map(|(row, &qi)| qi + row.iter().zip(z).map(|(a, b)| a * b).sum::<f64>()).collect()
}

/// The test's own acceptance check: `z >= -tol s`, `w >= -tol s`, `|z_i w_i| <= tol s^2`
/// with `s = 1 + ||M|| ||z|| + ||q||`.
#[must_use]
pub fn is_lcp_solution(m: &Mat, q: &[f64], z: &[f64], tol: f64) -> bool {
    let w = w_of(m, q, z);
    let mn = m.iter().map(|r| r.iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max);
    let zn = z.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let qn = q.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let s = 1.0 + mn * zn + qn;
    z.iter().zip(&w).all(|(&zi, &wi)| zi >= -tol * s && wi >= -tol * s && (zi * wi).abs() <= tol * s * s)
}

/// Every complementary basic solution of `(M, q)` (duplicates removed).
///
/// # Panics
/// When `n > 16` (enumeration is for small problems).
#[must_use]
pub fn all_solutions(m: &Mat, q: &[f64]) -> Vec<Vec<f64>> {
    let n = q.len();
    assert!(n <= 16, "enumeration is for small n");
    let mut found: Vec<Vec<f64>> = Vec::new();
    for mask in 0u32..(1 << n) {
        let s: Vec<usize> = (0..n).filter(|i| mask >> i & 1 == 1).collect();
        let mut z = vec![0.0; n];
        if !s.is_empty() {
            let a: Mat = s.iter().map(|&i| s.iter().map(|&j| m[i][j]).collect()).collect();
            let b: Vec<f64> = s.iter().map(|&i| -q[i]).collect();
            let Some(x) = solve_dense(&a, &b) else { continue };
            for (k, &i) in s.iter().enumerate() {
                z[i] = x[k];
            }
        }
        if is_lcp_solution(m, q, &z, 1e-9) {
            let z: Vec<f64> = z.into_iter().map(|x| x.max(0.0)).collect();
            if !found.iter().any(|f| f.iter().zip(&z).all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs()))) {
                found.push(z);
            }
        }
    }
    found
}

/// `max_S ||M_SS^-1||_inf` over all non-empty principal submatrices: the Lipschitz constant
/// of a P-matrix LCP's solution with respect to `q` (in the infinity norm).
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
