//! Verification of a candidate LCP solution against the original `(M, q)`.
//!
//! Every solution the solver returns passes through [`verify`]; callers and tests can use
//! [`is_solution`] on anything.
//!
//! # The residual
//! With `w = M z + q` recomputed from the original data, the scales
//! `s_z = max(||z||_inf, tiny)` and `s_w = max(||M||_inf ||z||_inf + ||q||_inf, tiny)`
//! (the size of the terms that make up `w`), the normalised residual is
//!
//! ```text
//! r = max_i max( max(-z_i, 0) / s_z,  max(-w_i, 0) / s_w,  min(|z_i| / s_z, |w_i| / s_w) )
//! ```
//!
//! i.e. the worst violation of `z >= 0`, `w >= 0` and of "one of `z_i`, `w_i` is zero",
//! each relative to the magnitude it is computed from. This is a backward-error measure:
//! a solution computed stably in precision `eps` has `r = O(N eps)` whatever the condition
//! of `M`. A scale `s_w` beyond the scalar's range fails (the residual is then infinite: divided
//! by it, every `w_i` would read as 0). The default tolerance is `r <= 256 N eps` of the scalar
//! type ([`default_tolerance`]): for `N = 6` that is `1.8e-4` in f32 and `3.4e-13` in f64.

use nalgebra::SVector;

use super::problem::Lcp;
use crate::real::{Real, max, min};

/// The outcome of [`verify`]: the normalised residual and the tolerance it was held to.
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use]
pub struct Verification<T> {
    /// Normalised residual `r` (see the module docs).
    pub residual: T,
    /// Tolerance `r` was compared with.
    pub tolerance: T,
    /// The scale `s_w = ||M||_inf ||z||_inf + ||q||_inf` that `w`'s violations were divided by
    /// (module docs): the size of the terms `w` is summed from.
    pub scale: T,
}

impl<T: Real> Verification<T> {
    /// `z` with `w = M z + q` already computed, held to `tolerance` on the data's scales
    /// `||M||_inf` and `||q||_inf` ([`residual`]).
    pub(crate) fn of<const N: usize>(
        z: &SVector<T, N>,
        w: &SVector<T, N>,
        (m_norm, q_norm): (T, T),
        tolerance: T,
    ) -> Self {
        let (residual, scale) = residual(z, w, m_norm, q_norm);
        Self { residual, tolerance, scale }
    }

    /// `true` when the residual is finite and within the tolerance.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.residual.finite() && self.residual <= self.tolerance
    }
}

/// The default verification tolerance for size `N`: `256 N eps`.
#[must_use]
pub fn default_tolerance<T: Real, const N: usize>() -> T {
    T::of(256.0 * N as f64) * T::EPS
}

/// Computes the normalised residual of `z` for `lcp` and compares it with `tolerance`.
pub fn verify<T: Real, const N: usize>(lcp: &Lcp<T, N>, z: &SVector<T, N>, tolerance: T) -> Verification<T> {
    let w = lcp.w_of(z);
    Verification::of(z, &w, (lcp.m_norm_inf(), lcp.q_norm_inf()), tolerance)
}

/// The normalised residual of `z` with `w = M z + q` already computed and the data's scales
/// `||M||_inf`, `||q||_inf` given (the solver's hot path has all three), and the scale `s_w` it
/// divided `w` by. The residual is infinite when `z` or
/// `w` has a non-finite entry, or when the scale `s_w` is not finite (`||M|| ||z||` beyond the
/// scalar's range: every `w_i` divided by it would read as 0, a violation included, so nothing
/// can be verified in this precision). The scales are inverted once: two divisions, not `3 N`.
#[inline]
pub(crate) fn residual<T: Real, const N: usize>(
    z: &SVector<T, N>,
    w: &SVector<T, N>,
    m_norm: T,
    q_norm: T,
) -> (T, T) {
    let mut z_norm = T::zero();
    for i in 0..N {
        z_norm = max(z_norm, z[i].abs_exact());
    }
    let s_w = m_norm * z_norm + q_norm;
    let inv_s_z = T::one() / max(z_norm, T::TINY);
    let inv_s_w = T::one() / max(s_w, T::TINY);
    // `max_i (-z_i)` and `max_i (-w_i)` are scaled once: a product by a positive scale keeps the
    // order of its factors (rounding is monotone), so the largest of the scaled violations is
    // the scaled largest, to the bit. `0 x` is zero for every finite `x` and NaN otherwise:
    // their sum says whether all were finite.
    let zero = T::zero();
    let (mut neg_z, mut neg_w, mut comp, mut probe) = (zero, zero, zero, zero * s_w);
    for i in 0..N {
        let (zi, wi) = (z[i], w[i]);
        probe += zero * zi + zero * wi;
        neg_z = max(neg_z, -zi);
        neg_w = max(neg_w, -wi);
        comp = max(comp, min(zi.abs_exact() * inv_s_z, wi.abs_exact() * inv_s_w));
    }
    if probe != T::zero() {
        return (T::of(f64::INFINITY), s_w);
    }
    (max(neg_z * inv_s_z, max(neg_w * inv_s_w, comp)), s_w)
}

/// `true` when `z` solves `lcp` within the default tolerance ([`default_tolerance`]).
#[must_use]
pub fn is_solution<T: Real, const N: usize>(lcp: &Lcp<T, N>, z: &SVector<T, N>) -> bool {
    verify(lcp, z, default_tolerance::<T, N>()).passed()
}
