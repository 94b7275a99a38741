//! Random matrices of known LCP classes, from plain `f64` parameters (so proptest shrinks
//! them), written independently of the core.

use crate::enumeration::Mat;

/// `A A^T + (S - S^T) + c I`: positive definite (so a P-matrix) for `c > 0`, non-symmetric.
/// `a` and `s` are `n*n` entries, row-major.
#[must_use]
pub fn positive_definite(n: usize, a: &[f64], s: &[f64], c: f64) -> Mat {
    let mut m = psd(n, n, a, s);
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += c;
    }
    m
}

/// `A A^T + (S - S^T)` with `A` of size `n x k`: positive semidefinite (rank <= k),
/// non-symmetric. `a` has `n*k` entries, `s` has `n*n`.
#[must_use]
pub fn psd(n: usize, k: usize, a: &[f64], s: &[f64]) -> Mat {
    let mut m = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..n {
            let aat: f64 = (0..k).map(|l| a[i * k + l] * a[j * k + l]).sum();
            m[i][j] = aat + s[i * n + j] - s[j * n + i];
        }
    }
    m
}
