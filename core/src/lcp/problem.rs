//! [`Lcp`]: the data `(M, q)` of one linear complementarity problem.

use nalgebra::{SMatrix, SVector};

use crate::real::{Real, max, min};

/// The scales of an LCP's data, from one pass over it ([`Lcp::scales`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scales<T> {
    /// `||M||_inf`.
    pub m_norm: T,
    /// `||q||_inf`.
    pub q_norm: T,
    /// `min_i q_i`.
    pub q_min: T,
}

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
        let mut finite = true;
        for i in 0..N {
            finite &= self.q[i].finite();
            for j in 0..N {
                finite &= self.m[(i, j)].finite();
            }
        }
        finite
    }

    /// `||M||_inf`, the largest absolute row sum of `M`.
    #[must_use]
    pub fn m_norm_inf(&self) -> T {
        let mut norm = T::zero();
        for row in self.row_abs_sums() {
            norm = max(norm, row);
        }
        norm
    }

    /// Each row's `sum_j |M_ij|`, its terms added in the order `j = 0 .. N`. `M` is stored by
    /// columns, so the sums are taken column by column (every row's next term at once, a read
    /// in storage order): the same operations in the same order per row as row by row.
    #[inline]
    fn row_abs_sums(&self) -> [T; N] {
        let mut rows = [T::zero(); N];
        for column in self.m.as_slice().chunks_exact(N) {
            for (row, m) in rows.iter_mut().zip(column) {
                *row += m.abs_exact();
            }
        }
        rows
    }

    /// `||M||_inf`, `||q||_inf` and `min q` in one pass over the data (the solver's entry:
    /// one read of `M` instead of one each for finiteness, the norm and `q >= 0`). `None`
    /// when an entry is not finite, or when the sum of all `|entries|` overflows: then there
    /// is no finite scale to measure round-off against (the solver reports
    /// [`super::LcpError::NonFiniteInput`]). The sum is finite exactly when every entry is
    /// finite and the `N^2 + N` magnitudes add up within the type's range.
    #[must_use]
    pub(crate) fn scales(&self) -> Option<Scales<T>> {
        let mut m_norm = T::zero();
        let mut total = T::zero();
        for row in self.row_abs_sums() {
            m_norm = max(m_norm, row);
            total += row;
        }
        let mut q_norm = T::zero();
        let mut q_min = self.q[0];
        for i in 0..N {
            let q = self.q[i];
            total += q.abs_exact();
            q_norm = max(q_norm, q.abs_exact());
            q_min = min(q_min, q);
        }
        total.finite().then_some(Scales { m_norm, q_norm, q_min })
    }

    /// `||q||_inf`.
    #[must_use]
    pub fn q_norm_inf(&self) -> T {
        let mut norm = T::zero();
        for i in 0..N {
            norm = max(norm, self.q[i].abs_exact());
        }
        norm
    }

    /// `w = M z + q`, computed from the original data in a fixed order of operations: each `w_i`
    /// is `q_i` plus its terms `M_ij z_j` in the order `j = 0 .. N`. They are added column by
    /// column, `M`'s storage order (every row's next term at once, independent of each other):
    /// the same operations in the same order per row as row by row.
    #[must_use]
    #[inline]
    pub fn w_of(&self, z: &SVector<T, N>) -> SVector<T, N> {
        self.w_over::<false>(z)
    }

    /// [`Self::w_of`] with the terms of `z`'s zero entries left out, the others added in the
    /// same order: the same `w` but for the sign of a zero `w_i` and for a non-finite `M_ij`
    /// against a zero `z_j` (whose `0 M_ij` is a NaN there), for a `z` with few entries not zero
    /// (a basis' answer: one column read for each) from data whose finiteness the caller knows
    /// otherwise.
    #[cfg(feature = "spatial")]
    #[must_use]
    #[inline]
    pub(crate) fn w_of_sparse(&self, z: &SVector<T, N>) -> SVector<T, N> {
        self.w_over::<true>(z)
    }

    /// [`Self::w_of`]'s sum, column by column; with `SKIP_ZEROS` the columns of `z`'s zero
    /// entries left out ([`Self::w_of_sparse`]).
    #[inline]
    fn w_over<const SKIP_ZEROS: bool>(&self, z: &SVector<T, N>) -> SVector<T, N> {
        let mut w = self.q;
        for (column, &zj) in self.m.as_slice().chunks_exact(N).zip(z.as_slice()) {
            if SKIP_ZEROS && zj == T::zero() {
                continue;
            }
            for (wi, &m) in w.as_mut_slice().iter_mut().zip(column) {
                *wi += m * zj;
            }
        }
        w
    }
}
