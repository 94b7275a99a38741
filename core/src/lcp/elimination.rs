//! Gaussian elimination with partial pivoting on a small dense system: the crate's one
//! elimination. Lemke's warm start solves a basis' principal block `M_aa z_a = -q_a` with it
//! ([`super::Lemke::solve_warm`]), and the planar stepper the at most `3 x 3` system of a basis'
//! unknowns in the body's coordinates, `H^T M^-1 G y = -q_H` (`crate::planar::FactoredLcp`;
//! `docs/formulation.md`, "Solving a step").

use crate::real::Real;

/// Solves the leading `m x m` block of `a y = rhs` in place (`y` returned in `rhs`) by Gaussian
/// elimination with partial pivoting (the first row of largest magnitude in each column; rows
/// swapped whole), `m <= D`. `false` when a pivot is at most `tiny`: numerically singular (`a`
/// and `rhs` are then unspecified). Rows and columns at or beyond `m` are neither read nor
/// written; `a` is left holding the elimination, with the inverse pivots on its diagonal.
///
/// Every loop has the constant bound `D`, with the rows and columns at or beyond `m` skipped, so
/// that every index is provably in range (no panic path is linked). Inlined where it is called,
/// so that a caller passing a constant `m` gets a copy specialised to it (its loops unrolled,
/// the same operations in the same order: the same bits); a caller that wants one shared copy
/// calls it from a function of its own kept out of line.
#[inline(always)]
#[allow(clippy::inline_always)] // the point of it: `m` known at the call
pub(crate) fn solve_leading<T: Real, const D: usize>(
    a: &mut [[T; D]; D],
    rhs: &mut [T; D],
    m: usize,
    tiny: T,
) -> bool {
    for col in 0..D {
        if col >= m {
            break;
        }
        let mut piv = col;
        for r in col + 1..D {
            if r < m && a[r][col].abs_exact() > a[piv][col].abs_exact() {
                piv = r;
            }
        }
        if a[piv][col].abs_exact() <= tiny {
            return false;
        }
        if piv != col {
            let (row, value) = (a[col], rhs[col]);
            a[col] = a[piv];
            rhs[col] = rhs[piv];
            a[piv] = row;
            rhs[piv] = value;
        }
        let inv = T::one() / a[col][col];
        for r in col + 1..D {
            if r >= m {
                break;
            }
            let f = a[r][col] * inv;
            for c in col + 1..D {
                if c < m {
                    let u = f * a[col][c];
                    a[r][c] -= u;
                }
            }
            let u = f * rhs[col];
            rhs[r] -= u;
        }
        a[col][col] = inv;
    }
    for col in (0..D).rev() {
        if col >= m {
            continue;
        }
        let mut acc = rhs[col];
        for c in col + 1..D {
            if c < m {
                acc -= a[col][c] * rhs[c];
            }
        }
        rhs[col] = acc * a[col][col];
    }
    true
}
