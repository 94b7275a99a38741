//! Small dense least squares by the singular value decomposition (one-sided Jacobi, Hestenes):
//! the rank-revealing solve the several-contact cone (`cone.rs`) needs, where the sticking
//! contacts' rows are singular (their internal forces, equal and opposite along the lines that
//! join them, move nothing).

/// `a = U diag(s) V^T` of an `m x n` matrix given by its columns (`m >= n`).
pub(crate) struct Svd {
    /// `U`'s columns (unit where `s > 0`).
    u: Vec<Vec<f64>>,
    s: Vec<f64>,
    /// `V`'s columns.
    v: Vec<Vec<f64>>,
}

/// Jacobi sweeps at most (each sweep's rotations shrink the columns' cosines quadratically).
const SWEEPS: usize = 64;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl Svd {
    /// The decomposition of the matrix of columns `columns` (each of one length): rotations of
    /// column pairs until every pair is orthogonal to `eps` of its lengths. `None` when a sweep
    /// limit passes first or an entry is not finite.
    pub(crate) fn of(columns: &[Vec<f64>]) -> Option<Self> {
        let n = columns.len();
        let mut u: Vec<Vec<f64>> = columns.to_vec();
        if u.iter().flatten().any(|x| !x.is_finite()) {
            return None;
        }
        let mut v: Vec<Vec<f64>> =
            (0..n).map(|j| (0..n).map(|i| f64::from(u8::from(i == j))).collect()).collect();
        // A column whose length is round-off's of the largest (a rank-deficient matrix) is
        // zero: rotating it against another only trades round-off, and would never end.
        let largest = u.iter().map(|c| dot(c, c)).fold(0.0, f64::max);
        let negligible = (f64::EPSILON * f64::EPSILON) * largest;
        // A dot product of columns of this length carries round-off of about its length times
        // `eps` of their sizes: pairs orthogonal to that are orthogonal.
        #[allow(clippy::cast_precision_loss)]
        let rows = u.first().map_or(1, Vec::len) as f64;
        let mut converged = false;
        for _ in 0..SWEEPS {
            let mut rotated = false;
            for p in 0..n {
                for q in p + 1..n {
                    let (alpha, beta, gamma) = (dot(&u[p], &u[p]), dot(&u[q], &u[q]), dot(&u[p], &u[q]));
                    if gamma == 0.0
                        || gamma.abs() <= rows * f64::EPSILON * (alpha * beta).sqrt()
                        || alpha.min(beta) <= negligible
                    {
                        continue;
                    }
                    rotated = true;
                    let zeta = (beta - alpha) / (2.0 * gamma);
                    let t = zeta.signum() / (zeta.abs() + zeta.hypot(1.0));
                    let c = 1.0 / t.hypot(1.0);
                    let s = c * t;
                    for m in [&mut u, &mut v] {
                        let (left, right) = m.split_at_mut(q);
                        for (a, b) in left[p].iter_mut().zip(right[0].iter_mut()) {
                            let (x, y) = (*a, *b);
                            *a = c * x - s * y;
                            *b = s * x + c * y;
                        }
                    }
                }
            }
            if !rotated {
                converged = true;
                break;
            }
        }
        if !converged {
            return None;
        }
        let s: Vec<f64> = u.iter().map(|c| dot(c, c).sqrt()).collect();
        for (c, &sj) in u.iter_mut().zip(&s) {
            if sj > 0.0 {
                for x in c.iter_mut() {
                    *x /= sj;
                }
            }
        }
        Some(Self { u, s, v })
    }

    /// The singular values below `relative` of the largest count as zero: the least-norm
    /// least-squares solution of `a x = b`, and the null space's basis (`V`'s columns of the
    /// zero singular values).
    pub(crate) fn solve(&self, b: &[f64], relative: f64) -> (Vec<f64>, Vec<Vec<f64>>) {
        let n = self.v.len();
        let largest = self.s.iter().copied().fold(0.0, f64::max);
        let mut x = vec![0.0; n];
        let mut null = Vec::new();
        for j in 0..n {
            if self.s[j] > relative * largest && self.s[j] > 0.0 {
                let k = dot(&self.u[j], b) / self.s[j];
                for (xi, vi) in x.iter_mut().zip(&self.v[j]) {
                    *xi += k * vi;
                }
            } else {
                null.push(self.v[j].clone());
            }
        }
        (x, null)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_rank_deficient_system_gets_its_least_norm_answer_and_null_space() {
        // Columns (1, 1, 0), (1, 1, 0), (0, 0, 2): rank 2; b in the range.
        let a = vec![vec![1.0, 1.0, 0.0], vec![1.0, 1.0, 0.0], vec![0.0, 0.0, 2.0]];
        let (x, null) = Svd::of(&a).unwrap().solve(&[2.0, 2.0, 4.0], 1e-12);
        // x1 + x2 = 2 with the least norm: (1, 1); x3 = 2.
        for (xi, want) in x.iter().zip([1.0, 1.0, 2.0]) {
            assert!((xi - want).abs() <= 1e-15, "{x:?}");
        }
        assert_eq!(null.len(), 1);
        let z = &null[0];
        assert!((z[0] + z[1]).abs() <= 1e-15 && z[2].abs() <= 1e-15 && (dot(z, z) - 1.0).abs() <= 1e-15);
    }
}
