//! The multibody reference's LCP solver (docs/formulation.md, "Several bodies", "Solving a
//! multibody step"): Lemke's complementary pivoting with the lexicographic minimum-ratio rule
//! (Cottle, Pang & Stone, *The Linear Complementarity Problem*, 1992, section 4.4, with the
//! lexicographic degeneracy resolution: the tableau `w - A z - d z0 = b` started from the basis
//! `w`, `z0` entering first, each later entering variable the complement of the one that left,
//! until `z0` leaves), a solve of one
//! given complementary basis ([`solve_basis`]), and the check every answer passes before it is
//! used ([`verify`]).
//!
//! Nothing here is shared with `core/src/lcp/` or with [`crate::enumerate`]: the enumerator is
//! these functions' independent check in the tests.
//!
//! **Lexicographic rule.** Among the rows whose entry `c_i` in the entering column is positive,
//! the leaving row minimises `(b_i, B^-1_i) / c_i` lexicographically (`B^-1` read from the
//! tableau's `w` columns: the starting basis is the identity), which keeps every row of
//! `(b, B^-1)` lexicographically positive and so never repeats a basis: the method ends after
//! finitely many pivots, on a solution or on a ray. Ratios within `1e-12` of each other
//! (relative) count as equal and go to the next component, so that round-off does not decide a
//! degenerate tie. An entry counts as positive above `1e-9` of the column's largest entry.

/// Why [`lemke`] gave no solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LemkeFailure {
    /// The entering column had no positive entry: the method ended on a ray (for the copositive-
    /// plus matrices of a friction step this means the LCP has no solution; in floating point it
    /// may be round-off).
    Ray,
    /// More pivots than the limit.
    PivotLimit,
}

/// A complementary basis: `basic[i]` when `z_i` is basic (`w_i = 0`), else `w_i` basic
/// (`z_i = 0`).
pub type Basis = Vec<bool>;

/// `w = A z + b` for `A` row-major `n x n`.
#[must_use]
pub fn residual(a: &[f64], b: &[f64], z: &[f64]) -> Vec<f64> {
    let n = b.len();
    (0..n).map(|i| b[i] + (0..n).map(|j| a[i * n + j] * z[j]).sum::<f64>()).collect()
}

/// The verification tolerance of an answer `z` of `(A, b)`:
/// `64 n eps (||A||_inf ||z||_inf + ||b||_inf)` (the round-off of forming `w` from `z` and of
/// solving for `z`, with a margin).
#[must_use]
pub fn tolerance(a: &[f64], b: &[f64], z: &[f64]) -> f64 {
    let n = b.len();
    let a_norm = (0..n).map(|i| (0..n).map(|j| a[i * n + j].abs()).sum::<f64>()).fold(0.0, f64::max);
    let z_norm = z.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let b_norm = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    64.0 * n as f64 * f64::EPSILON * (a_norm * z_norm + b_norm)
}

/// Whether `z` solves `(A, b)`: every value finite, `z >= -tol`, `w >= -tol` and
/// `|min(z_i, w_i)| <= tol` (complementarity, on the scale of each pair: both are velocities in
/// a step per unit mass), `tol` from [`tolerance`].
#[must_use]
pub fn verify(a: &[f64], b: &[f64], z: &[f64]) -> bool {
    let w = residual(a, b, z);
    let tol = tolerance(a, b, z);
    tol.is_finite()
        && z.iter().zip(&w).all(|(&zi, &wi)| zi.is_finite() && wi.is_finite() && zi.min(wi).abs() <= tol)
}

/// Solves the `k x k` system `m x = rhs` in place by Gaussian elimination with partial pivoting.
/// `false` when a pivot is at most `tiny`.
fn eliminate(m: &mut [f64], rhs: &mut [f64], k: usize, tiny: f64) -> bool {
    for col in 0..k {
        let pivot =
            (col..k).max_by(|&r, &s| m[r * k + col].abs().total_cmp(&m[s * k + col].abs())).unwrap_or(col);
        if m[pivot * k + col].abs() <= tiny {
            return false;
        }
        if pivot != col {
            for c in 0..k {
                m.swap(col * k + c, pivot * k + c);
            }
            rhs.swap(col, pivot);
        }
        for row in col + 1..k {
            let factor = m[row * k + col] / m[col * k + col];
            if factor != 0.0 {
                for c in col..k {
                    m[row * k + c] -= factor * m[col * k + c];
                }
                rhs[row] -= factor * rhs[col];
            }
        }
    }
    for row in (0..k).rev() {
        let mut s = rhs[row];
        for c in row + 1..k {
            s -= m[row * k + c] * rhs[c];
        }
        rhs[row] = s / m[row * k + row];
    }
    true
}

/// The complementary solution of `basis`: `A_aa z_a = -b_a`, `z = 0` outside it. `None` when
/// the principal system is singular (a pivot at most `1e-12 ||A||_max`); the answer is not
/// verified (call [`verify`]).
#[must_use]
pub fn solve_basis(a: &[f64], b: &[f64], basis: &[bool]) -> Option<Vec<f64>> {
    let n = b.len();
    let basic: Vec<usize> = (0..n).filter(|&i| basis[i]).collect();
    let k = basic.len();
    let mut m = vec![0.0; k * k];
    let mut rhs = vec![0.0; k];
    for (r, &row) in basic.iter().enumerate() {
        for (c, &col) in basic.iter().enumerate() {
            m[r * k + c] = a[row * n + col];
        }
        rhs[r] = -b[row];
    }
    let a_max = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if !eliminate(&mut m, &mut rhs, k, 1e-12 * a_max.max(f64::MIN_POSITIVE)) {
        return None;
    }
    let mut z = vec![0.0; n];
    for (r, &row) in basic.iter().enumerate() {
        z[row] = rhs[r];
    }
    Some(z)
}

/// `x / c` compared lexicographically between two rows, ratios within `1e-12` (relative) equal.
fn lex_less(first: &[f64], c_first: f64, second: &[f64], c_second: f64) -> bool {
    for (&x, &y) in first.iter().zip(second) {
        let (p, q) = (x / c_first, y / c_second);
        let scale = p.abs().max(q.abs());
        if (p - q).abs() > 1e-12 * scale {
            return p < q;
        }
    }
    false
}

/// Lemke's method on `w = A z + b` with the covering vector `d > 0` (all ones is the usual
/// choice), lexicographic rule, at most `max_pivots` pivots. Returns `z` (round-off negatives
/// clamped to 0) and its complementary basis; the answer is not verified (call [`verify`]).
///
/// # Errors
/// [`LemkeFailure`].
pub fn lemke(a: &[f64], b: &[f64], d: &[f64], max_pivots: usize) -> Result<(Vec<f64>, Basis), LemkeFailure> {
    let n = b.len();
    if b.iter().all(|&x| x >= 0.0) {
        return Ok((vec![0.0; n], vec![false; n]));
    }
    // Columns: w 0..n, z n..2n, z0 2n, rhs 2n + 1.
    let width = 2 * n + 2;
    let (z0, rhs) = (2 * n, 2 * n + 1);
    let mut t = vec![0.0; n * width];
    for i in 0..n {
        t[i * width + i] = 1.0;
        for j in 0..n {
            t[i * width + n + j] = -a[i * n + j];
        }
        t[i * width + z0] = -d[i];
        t[i * width + rhs] = b[i];
    }
    // basic_of_row[i]: the column basic in row i.
    let mut basic_of_row: Vec<usize> = (0..n).collect();
    // Lexicographic key of row i: (rhs, B^-1 row) = columns rhs then 0..n.
    let key = |t: &[f64], i: usize| -> Vec<f64> {
        let mut k = Vec::with_capacity(n + 1);
        k.push(t[i * width + rhs]);
        k.extend_from_slice(&t[i * width..i * width + n]);
        k
    };
    // First pivot: z0 enters; the row minimising (b_i, e_i) / d_i leaves (all rows qualify).
    let mut leave = 0;
    for i in 1..n {
        if lex_less(&key(&t, i), d[i], &key(&t, leave), d[leave]) {
            leave = i;
        }
    }
    let mut entering = z0;
    for _ in 0..max_pivots {
        pivot(&mut t, width, n, leave, entering);
        let left = basic_of_row[leave];
        basic_of_row[leave] = entering;
        if left == z0 {
            return Ok(extract(&t, width, n, &basic_of_row));
        }
        // The complement of the variable that left enters.
        entering = if left < n { left + n } else { left - n };
        let column_max = (0..n).fold(0.0_f64, |m, i| m.max(t[i * width + entering].abs()));
        let positive = 1e-9 * column_max;
        let mut best: Option<usize> = None;
        for i in 0..n {
            let c = t[i * width + entering];
            if c > positive {
                best = match best {
                    Some(r) if !lex_less(&key(&t, i), c, &key(&t, r), t[r * width + entering]) => Some(r),
                    _ => Some(i),
                };
            }
        }
        let Some(row) = best else { return Err(LemkeFailure::Ray) };
        // Prefer z0 leaving on a tie of the ratio (ends the method at once).
        leave = row;
        for i in 0..n {
            if basic_of_row[i] == z0 && t[i * width + entering] > positive {
                let (ri, rr) = (
                    t[i * width + rhs] / t[i * width + entering],
                    t[row * width + rhs] / t[row * width + entering],
                );
                if (ri - rr).abs() <= 1e-12 * ri.abs().max(rr.abs()) {
                    leave = i;
                }
            }
        }
    }
    Err(LemkeFailure::PivotLimit)
}

/// Pivots the tableau on `(row, col)`.
fn pivot(t: &mut [f64], width: usize, n: usize, row: usize, col: usize) {
    let p = t[row * width + col];
    for c in 0..width {
        t[row * width + c] /= p;
    }
    for i in 0..n {
        if i != row {
            let factor = t[i * width + col];
            if factor != 0.0 {
                for c in 0..width {
                    t[i * width + c] -= factor * t[row * width + c];
                }
            }
        }
    }
}

/// `z` and its basis from a final tableau.
fn extract(t: &[f64], width: usize, n: usize, basic_of_row: &[usize]) -> (Vec<f64>, Basis) {
    let mut z = vec![0.0; n];
    let mut basis = vec![false; n];
    for (i, &col) in basic_of_row.iter().enumerate() {
        if (n..2 * n).contains(&col) {
            z[col - n] = t[i * width + 2 * n + 1].max(0.0);
            basis[col - n] = true;
        }
    }
    (z, basis)
}
