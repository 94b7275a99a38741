//! The dense form of one step's LCP (`docs/formulation.md`, "One time step"; paper, eq. 18) for
//! any [`Layout`]: `A` and `q` written out, for Lemke's method ([`crate::lcp::Lemke`]) when the
//! factored solve declines (`docs/formulation.md`, "Solving a step"), and for tests.
//!
//! With `c_j` the wrench column of impulse variable `j` (`W_n` of its contact, or `+-W_d` for a
//! friction row along `+-d`) and `M^-1` per unit mass:
//!
//! ```text
//! A[j][k] = c_j^T M^-1 c_k                      impulse rows and columns (symmetric)
//! A[f][sigma_i] = 1, A[sigma_i][f] = -1         for each friction row f of contact i (E, -E^T)
//! A[sigma_i][n_i] = mu_i                        (U)
//! ```
//!
//! and `q` the right-hand side of eq. 18 ([`StepInputs`], [`normal_bias`]). An inactive contact keeps its
//! rows decoupled: identity rows and columns and `q = 1`, so its variables are zero. The entries
//! are those of the factored rows ([`FactoredLcp`]), which this module only writes out.

pub use super::inputs::{StepInputs, normal_bias};

use super::factored::{FactoredLcp, cone_scale};
use super::inputs::dot3;
use super::layout::Layout;
use crate::lcp::Lcp;
use crate::nalgebra::{SMatrix, SVector};
use crate::real::Real;

/// The step's LCP and the wrench column of each variable (zero for `sigma` and for the rows of an
/// inactive contact).
#[derive(Debug, Clone, Copy)]
pub struct StepLcp<T: Real, const N: usize> {
    /// `(A, b)`.
    pub lcp: Lcp<T, N>,
    /// Wrench column of each variable of `z`.
    pub columns: [[T; 3]; N],
}

/// Assembles the LCP of eq. 18 for `layout`.
///
/// The impulse block `W^T M^-1 W` is symmetric: its upper triangle is computed and mirrored (10 of
/// the 16 dot products for two contacts with one direction each), which also makes it exactly
/// symmetric. The stepper forms `A` only for Lemke's method, when its fast path declines
/// (`docs/formulation.md`, "Solving a step").
#[must_use]
pub fn assemble<T: Real, const K: usize, const N: usize>(
    layout: &Layout<K, N>,
    input: &StepInputs<'_, T, K>,
) -> StepLcp<T, N> {
    let mut out = StepLcp::zeros();
    assemble_into(layout, input, &mut out);
    out
}

impl<T: Real, const N: usize> StepLcp<T, N> {
    /// Every entry zero (what [`assemble_into`] writes into).
    #[must_use]
    pub fn zeros() -> Self {
        Self { lcp: Lcp::new(SMatrix::zeros(), SVector::zeros()), columns: [[T::zero(); 3]; N] }
    }
}

/// Writes the entries of eq. 18 for `layout` into `out`, which must hold zeros
/// ([`StepLcp::zeros`]): only the entries that can be non-zero are written. The stepper assembles
/// into a zeroed local this way, with no copy of the result.
#[inline]
pub fn assemble_into<T: Real, const K: usize, const N: usize>(
    layout: &Layout<K, N>,
    input: &StepInputs<'_, T, K>,
    out: &mut StepLcp<T, N>,
) {
    let factored = FactoredLcp::new(layout, input);
    out.columns = factored.col;
    fill_from_factored(&factored, &[T::one(); K], &mut out.lcp);
}

/// Writes `A` and `q` of the step whose factored rows are `f` into `lcp` (zeroed): the impulse
/// block `C^T M^-1 C` (its upper triangle computed and mirrored, so it is exactly symmetric), the
/// friction cone's `E`, `-E^T` and `U`, and an inactive contact's identity rows. Contact `i`'s
/// cone row is written multiplied by `weights[i]`: `s mu` and `-s`, exact for a power of two
/// (1, or a weighted row's [`cone_scale`]; `docs/formulation.md`, "Precision").
pub(crate) fn fill_from_factored<T: Real, const K: usize, const N: usize>(
    f: &FactoredLcp<T, K, N>,
    weights: &[T; K],
    lcp: &mut Lcp<T, N>,
) {
    let sigma_start = Layout::<K, N>::SIGMA_START;
    let Lcp { m: a, q: b } = lcp;
    for j in 0..N {
        b[j] = f.q[j];
    }
    for j in 0..sigma_start {
        for k in j..sigma_start {
            let entry = dot3(&f.mcol[j], &f.col[k]);
            a[(j, k)] = entry;
            a[(k, j)] = entry;
        }
    }
    let mut j = K;
    for i in 0..K {
        let end = (j + f.tangents()[i].count()).min(sigma_start);
        let active = (f.inactive >> i) & 1 == 0;
        let s = weights[i];
        for row in j..end {
            if active {
                a[(row, sigma_start + i)] = T::one();
                a[(sigma_start + i, row)] = -s;
            }
        }
        j = end;
        if active {
            a[(sigma_start + i, i)] = s * f.mu[i];
        }
    }
    for v in 0..N {
        if (f.inactive >> v) & 1 == 1 {
            a[(v, v)] = T::one();
        }
    }
}

/// The weight of each contact's cone row in the step `f`: [`cone_scale`] of its `mu` where `f`
/// weighs it (its bit of `cone_scaled`), 1 elsewhere ([`fill_from_factored`]).
pub(crate) fn cone_weights<T: Real, const K: usize, const N: usize>(f: &FactoredLcp<T, K, N>) -> [T; K] {
    let mut weights = [T::one(); K];
    for (i, weight) in weights.iter_mut().enumerate() {
        if (f.cone_scaled >> i) & 1 == 1 {
            *weight = cone_scale(f.mu[i]);
        }
    }
    weights
}
