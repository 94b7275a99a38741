//! Gaussian elimination with partial pivoting on a small dense system. Lemke's warm start solves a
//! basis' principal block `M_aa z_a = -q_a` with it ([`super::Lemke::solve_warm`]), the planar
//! stepper the at most `3 x 3` system of a basis' unknowns in the body's coordinates,
//! `H^T M^-1 G y = -q_H` (`crate::planar::FactoredLcp`; `docs/formulation.md`, "Solving a step"),
//! and the multibody stepper that system in the bodies' `3B` coordinates when it is not symmetric
//! (a symmetric one goes by `L D L^T`: `core/src/multibody/factored/systems.rs`;
//! `docs/formulation.md`, "Solving a multibody step (the core)").

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
        eliminate_column!(a, rhs, col, m, D, tiny);
    }
    for col in (0..D).rev() {
        if col >= m {
            continue;
        }
        back_substitute!(a, rhs, col, m, D);
    }
    true
}

/// Column `col < m` of [`solve_leading`]'s elimination in a `D x D` array: its pivot (the first
/// row of largest magnitude at or below `col`, swapped whole into row `col`), the rows below it
/// eliminated, the inverse pivot left on the diagonal; `return false` from the function it is in
/// when the pivot is at most `tiny`. A macro, so that [`solve_leading`] and a caller that writes
/// its columns out with constant indices (`col = 0, 1, ...`, then [`back_substitute!`] from `m -
/// 1` down to `0`) share one text and get the same operations in the same order.
macro_rules! eliminate_column {
    ($a:ident, $rhs:ident, $col:expr, $m:expr, $d:expr, $tiny:expr) => {{
        let (col, m) = ($col, $m);
        let mut piv = col;
        for r in col + 1..$d {
            if r < m && $a[r][col].abs_exact() > $a[piv][col].abs_exact() {
                piv = r;
            }
        }
        if $a[piv][col].abs_exact() <= $tiny {
            return false;
        }
        if piv != col {
            let (row, value) = ($a[col], $rhs[col]);
            $a[col] = $a[piv];
            $rhs[col] = $rhs[piv];
            $a[piv] = row;
            $rhs[piv] = value;
        }
        let inv = T::one() / $a[col][col];
        for r in col + 1..$d {
            if r >= m {
                break;
            }
            let f = $a[r][col] * inv;
            for c in col + 1..$d {
                if c < m {
                    let u = f * $a[col][c];
                    $a[r][c] -= u;
                }
            }
            let u = f * $rhs[col];
            $rhs[r] -= u;
        }
        $a[col][col] = inv;
    }};
}
pub(crate) use eliminate_column;

/// Row `col < m` of [`solve_leading`]'s back substitution in a `D x D` array (the rows after it
/// done): [`eliminate_column!`]'s counterpart.
macro_rules! back_substitute {
    ($a:ident, $rhs:ident, $col:expr, $m:expr, $d:expr) => {{
        let (col, m) = ($col, $m);
        let mut acc = $rhs[col];
        for c in col + 1..$d {
            if c < m {
                acc -= $a[col][c] * $rhs[c];
            }
        }
        $rhs[col] = acc * $a[col][col];
    }};
}
pub(crate) use back_substitute;
