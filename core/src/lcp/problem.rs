//! [`Lcp`]: the data `(M, q)` of one linear complementarity problem.

use nalgebra::{SMatrix, SVector};

use crate::real::{Real, max};

/// One linear complementarity problem of size `N`:
/// find `z` with `w = M z + q`, `z >= 0`, `w >= 0`, `z . w = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lcp<T: Real, const N: usize> {
    /// The matrix `M` (`N x N`).
    pub m: SMatrix<T, N, N>,
    /// The vector `q` (`N`).
    pub q: SVector<T, N>,
}

impl<T: Real, const N: usize> Lcp<T, N> {
    /// Wraps `M` and `q`.
    #[must_use]
    pub const fn new(m: SMatrix<T, N, N>, q: SVector<T, N>) -> Self {
        Self { m, q }
    }

    /// Builds the problem from row-major arrays (`m[row][col]`).
    #[must_use]
    pub fn from_rows(m: &[[T; N]; N], q: &[T; N]) -> Self {
        Self { m: SMatrix::from_fn(|i, j| m[i][j]), q: SVector::from_fn(|i, _| q[i]) }
    }

    /// `true` when every entry of `M` and `q` is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.m.iter().all(|x| x.finite()) && self.q.iter().all(|x| x.finite())
    }

    /// `||M||_inf`, the largest absolute row sum of `M`.
    #[must_use]
    pub fn m_norm_inf(&self) -> T {
        let mut norm = T::zero();
        for i in 0..N {
            let mut row = T::zero();
            for j in 0..N {
                row += self.m[(i, j)].abs_exact();
            }
            norm = max(norm, row);
        }
        norm
    }

    /// `||q||_inf`.
    #[must_use]
    pub fn q_norm_inf(&self) -> T {
        self.q.iter().fold(T::zero(), |acc, x| max(acc, x.abs_exact()))
    }

    /// `w = M z + q`, computed from the original data in a fixed order of operations.
    #[must_use]
    pub fn w_of(&self, z: &SVector<T, N>) -> SVector<T, N> {
        SVector::from_fn(|i, _| {
            let mut acc = self.q[i];
            for j in 0..N {
                acc += self.m[(i, j)] * z[j];
            }
            acc
        })
    }
}
