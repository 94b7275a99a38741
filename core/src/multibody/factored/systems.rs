//! The basis solve's small dense systems ([`super::Factored::solve_basis`]): `H^T M~ G y = -q_H`
//! of at most [`UNKNOWNS`] unknowns. Symmetric (no unknown has a follower: `G^T M~ G`, symmetric
//! positive semidefinite) by `L D L^T` without pivoting ([`solve_symmetric`]); otherwise by
//! Gaussian elimination with partial pivoting ([`solve_leading`]), in copies specialised to a
//! count of unknowns (block-on-block's four sliding contacts, [`solve_four`]) or one out of line
//! for any count. A pivot not above `tiny` is a singular
//! system (both corners of one interface sticking: four rows of rank three).

use super::UNKNOWNS;
use crate::lcp::elimination::{back_substitute, eliminate_column, solve_leading};
use crate::real::Real;

/// The basis' `m x m` system by [`solve_leading`], one copy out of line for any `m`
/// ([`solve_four`]: block-on-block's usual four unknowns).
#[inline(never)]
pub(super) fn solve_leading_out_of_line<T: Real>(
    a: &mut [[T; UNKNOWNS]; UNKNOWNS],
    rhs: &mut [T; UNKNOWNS],
    m: usize,
    tiny: T,
) -> bool {
    solve_leading(a, rhs, m, tiny)
}

/// The leading `m x m` block of a symmetric system (`H = G`: no unknown has a follower, the
/// matrix `G^T M~ G` is symmetric positive semidefinite) by `L D L^T` without pivoting, from its
/// lower triangle: about half the operations of [`solve_leading`] and backward stable for a
/// positive definite matrix. A pivot `d` not above `tiny` (a rank-deficient set of rows: both
/// corners of one interface sticking; or not finite) is a singular system: `false`. The solution
/// is written into `rhs`, `a` overwritten. One copy for any `m`, one for
/// `m = 9` (the 3-block stack's every step).
#[inline(never)]
pub(super) fn solve_symmetric<T: Real>(
    a: &mut [[T; UNKNOWNS]; UNKNOWNS],
    rhs: &mut [T; UNKNOWNS],
    m: usize,
    tiny: T,
) -> bool {
    if m == UNKNOWNS { solve_symmetric_all(a, rhs, tiny) } else { ldl_leading(a, rhs, m, tiny) }
}

/// [`solve_symmetric`] with every unknown (`m = 9`): each row's and each back substitution's
/// step called with its index written out, so that every loop's bounds are constants (unrolled:
/// no loop counters), the same operations in the same order as [`ldl_leading`].
#[inline(never)]
fn solve_symmetric_all<T: Real>(a: &mut [[T; UNKNOWNS]; UNKNOWNS], rhs: &mut [T; UNKNOWNS], tiny: T) -> bool {
    const _: () = assert!(UNKNOWNS == 9, "the rows below are written out for nine unknowns");
    let mut inv = [T::zero(); UNKNOWNS];
    let factored = ldl_row(a, rhs, &mut inv, tiny, 0)
        && ldl_row(a, rhs, &mut inv, tiny, 1)
        && ldl_row(a, rhs, &mut inv, tiny, 2)
        && ldl_row(a, rhs, &mut inv, tiny, 3)
        && ldl_row(a, rhs, &mut inv, tiny, 4)
        && ldl_row(a, rhs, &mut inv, tiny, 5)
        && ldl_row(a, rhs, &mut inv, tiny, 6)
        && ldl_row(a, rhs, &mut inv, tiny, 7)
        && ldl_row(a, rhs, &mut inv, tiny, 8);
    if !factored {
        return false;
    }
    for i in [8, 7, 6, 5, 4, 3, 2, 1, 0] {
        ldl_back(a, rhs, &inv, i, UNKNOWNS);
    }
    true
}

/// [`solve_symmetric`]'s factorisation and substitutions.
#[inline(always)]
#[allow(clippy::inline_always)] // the point of it: `m` known at the call
fn ldl_leading<T: Real>(
    a: &mut [[T; UNKNOWNS]; UNKNOWNS],
    rhs: &mut [T; UNKNOWNS],
    m: usize,
    tiny: T,
) -> bool {
    let m = m.min(UNKNOWNS);
    let mut inv = [T::zero(); UNKNOWNS];
    for i in 0..m {
        if !ldl_row(a, rhs, &mut inv, tiny, i) {
            return false;
        }
    }
    for i in (0..m).rev() {
        ldl_back(a, rhs, &inv, i, m);
    }
    true
}

/// Row `i` of [`ldl_leading`]'s factorisation and forward substitution: `false` for a pivot not
/// above `tiny`. Row by row (each sum a dot product along rows): `a`'s lower triangle becomes
/// `U = L D` (`u_ij = a_ij - sum_{k<j} u_ik l_jk`), its upper triangle holds `L^T`
/// (`a[j][i] = l_ij`, `j < i`: no other array to clear), `inv` holds `1 / d`.
#[inline(always)]
#[allow(clippy::inline_always)] // the point of it: `i` known at the call
fn ldl_row<T: Real>(
    a: &mut [[T; UNKNOWNS]; UNKNOWNS],
    rhs: &mut [T; UNKNOWNS],
    inv: &mut [T; UNKNOWNS],
    tiny: T,
    i: usize,
) -> bool {
    let i = i.min(UNKNOWNS - 1);
    for j in 0..i {
        let mut u = a[i][j];
        for k in 0..j {
            u -= a[i][k] * a[k][j];
        }
        a[i][j] = u;
        a[j][i] = u * inv[j];
    }
    let mut d = a[i][i];
    for k in 0..i {
        d -= a[i][k] * a[k][i];
    }
    if d.partial_cmp(&tiny) != Some(core::cmp::Ordering::Greater) {
        return false;
    }
    inv[i] = T::one() / d;
    // Forward: `L y = rhs`.
    let mut y = rhs[i];
    for k in 0..i {
        y -= a[k][i] * rhs[k];
    }
    rhs[i] = y;
    true
}

/// Row `i` of [`ldl_leading`]'s back substitution, `L^T x = D^-1 y` (rows after `i` done).
#[inline(always)]
#[allow(clippy::inline_always)] // the point of it: `i` known at the call
fn ldl_back<T: Real>(
    a: &[[T; UNKNOWNS]; UNKNOWNS],
    rhs: &mut [T; UNKNOWNS],
    inv: &[T; UNKNOWNS],
    i: usize,
    m: usize,
) {
    let (i, m) = (i.min(UNKNOWNS - 1), m.min(UNKNOWNS));
    let mut x = rhs[i] * inv[i];
    for k in i + 1..m {
        x -= a[i][k] * rhs[k];
    }
    rhs[i] = x;
}

/// [`super::Factored::solve_sliding`]'s system of `m4 < 4` unknowns into `a` and `y`: unknown `l` slot
/// `var[l]`'s, its column's entries `entry(row's slot, slot, signed(l, slot))`.
pub(super) fn form_sliding<T: Real, const D: usize>(
    m4: usize,
    (var, signed, entry): (&[u8; UNKNOWNS], impl Fn(usize, usize) -> T, impl Fn(usize, usize, T) -> T),
    q: &[T],
    (a, y): (&mut [[T; D]; D], &mut [T; D]),
) {
    for l in 0..m4.min(D) {
        let j = usize::from(var[l]).min(3);
        let mu = signed(l, j);
        for r in 0..m4.min(D) {
            a[r][l] = entry(usize::from(var[r]).min(3), j, mu);
        }
        y[l] = -q.get(j).copied().unwrap_or(T::zero());
    }
}

/// [`solve_leading`] with fewer than four unknowns in a `4 x 4` array (left out with `compact`).
#[inline(never)]
pub(super) fn solve_small<T: Real>(a: &mut [[T; 4]; 4], rhs: &mut [T; 4], m: usize, tiny: T) -> bool {
    solve_leading(a, rhs, m, tiny)
}

/// [`solve_leading`] with four unknowns (two interfaces of two corners each sliding, each `p_n`
/// with its friction row following: block-on-block's usual step), column by column with each
/// index written out (its loops unrolled): the same operations in the same order (the same bits).
#[inline(always)]
#[allow(clippy::inline_always)] // in the sliding solve: its system kept where it was formed
pub(super) fn solve_four<T: Real>(a: &mut [[T; 4]; 4], rhs: &mut [T; 4], tiny: T) -> bool {
    eliminate_column!(a, rhs, 0, 4, 4, tiny);
    eliminate_column!(a, rhs, 1, 4, 4, tiny);
    eliminate_column!(a, rhs, 2, 4, 4, tiny);
    eliminate_column!(a, rhs, 3, 4, 4, tiny);
    back_substitute!(a, rhs, 3, 4, 4);
    back_substitute!(a, rhs, 2, 4, 4);
    back_substitute!(a, rhs, 1, 4, 4);
    back_substitute!(a, rhs, 0, 4, 4);
    true
}
