//! [`Tableau`]: the dense tableau `[I, -M, -d | q]` of Lemke's method ([`super::Lemke`]), its
//! pivots with the lexicographic ratio test, and the basis and solution it holds.

use nalgebra::SVector;

use super::basis::Basis;
use super::error::LcpError;
use super::problem::Lcp;
use super::rows::Rows;
use crate::real::{Real, max};

/// A variable of the Lemke tableau `[I, -M, -d | q]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Var {
    W(u8),
    Z(u8),
    Artificial,
}

impl Var {
    /// The complement of a complementary variable (`w_i <-> z_i`).
    const fn complement(self) -> Self {
        match self {
            Self::W(i) => Self::Z(i),
            Self::Z(i) => Self::W(i),
            Self::Artificial => Self::Artificial,
        }
    }
}

pub(super) struct Tableau<T: Real, const N: usize, const WORDS: usize> {
    /// Columns of `w` in the current tableau: `B^-1` (row-major, `binv[row][col]`).
    binv: [[T; N]; N],
    /// Columns of `z`: `-B^-1 M`.
    zc: [[T; N]; N],
    /// Column of the artificial variable: `-B^-1 d`.
    art: [T; N],
    /// Right-hand side: values of the basic variables, `B^-1 q`.
    rhs: [T; N],
    /// Basic variable of each row.
    basis: [Var; N],
}

impl<T: Real, const N: usize, const WORDS: usize> Tableau<T, N, WORDS> {
    /// The cold-start tableau `[I, -M, -e | q]` with every `w_i` basic (covering vector `e`).
    pub(super) fn cold(lcp: &Lcp<T, N>) -> Self {
        let mut t = Self {
            binv: [[T::zero(); N]; N],
            zc: [[T::zero(); N]; N],
            art: [-T::one(); N],
            rhs: [T::zero(); N],
            basis: [Var::Artificial; N],
        };
        // The bound goes through `black_box` so that the compiler keeps this a loop: unrolled,
        // the N^2 copies were a kilobyte of a microcontroller's flash for a path (Lemke's method,
        // after the fast paths) that few steps take. `n = N` all the same.
        let n = N.min(core::hint::black_box(N));
        // Every access through `get`, whose `None` (never taken: `i, j < n <= N`) is no panic
        // path: for some `N` (9) the compiler could not see that bound through the indexing.
        for i in 0..n {
            for j in 0..n {
                if let (Some(b), Some(z), Some(&m)) = (t.binv.get_mut(i), t.zc.get_mut(i), lcp.m.get((i, j)))
                {
                    if i == j {
                        b[j] = T::one();
                    }
                    z[j] = -m;
                }
            }
            if let (Some(rhs), Some(basis), Some(&q)) = (t.rhs.get_mut(i), t.basis.get_mut(i), lcp.q.get(i)) {
                *rhs = q;
                *basis = Var::W(i as u8);
            }
        }
        t
    }

    /// This cold tableau ([`Self::cold`]) turned, in place (a tableau is a kilobyte and more: not
    /// moved), into that of the complementary basis `warm` by Gauss-Jordan elimination with
    /// partial pivoting. The artificial column is then reset to `-e` in these coordinates
    /// (covering vector `d = B e`). `None` when the basis matrix is numerically singular (the
    /// tableau is then unspecified). Returns the eliminations spent.
    pub(super) fn warm(&mut self, warm: Basis<N, WORDS>, scale: T) -> Option<u32> {
        let t = self;
        let mut eliminations = 0;
        for i in 0..N {
            if !warm.is_z_basic(i) {
                continue;
            }
            // Bring z_i in, replacing a w_k (k also in the warm basis) still basic.
            let mut best: Option<(usize, T)> = None;
            for r in 0..N {
                if let Var::W(k) = t.basis[r]
                    && warm.is_z_basic(k as usize)
                {
                    let a = t.zc[r][i].abs_exact();
                    if best.is_none_or(|(_, b)| a > b) {
                        best = Some((r, a));
                    }
                }
            }
            let (r, a) = best?;
            // `a` is finite (checked input) and non-negative: too small means singular.
            if a <= T::of(N as f64) * T::EPS * scale {
                return None;
            }
            t.pivot(r, Var::Z(i as u8));
            eliminations += 1;
        }
        t.art = [-T::one(); N];
        Some(eliminations)
    }

    /// The tableau column of `var`. One `match` and one index check per column, not per row:
    /// variable indices are below `N` by construction, and the first arm (never taken) lets
    /// the compiler drop the bounds checks in the loops.
    fn column(&self, var: Var) -> [T; N] {
        let mut column = [T::zero(); N];
        match var {
            Var::W(j) | Var::Z(j) if usize::from(j) >= N => {}
            Var::W(j) => {
                for i in 0..N {
                    column[i] = self.binv[i][usize::from(j)];
                }
            }
            Var::Z(j) => {
                for i in 0..N {
                    column[i] = self.zc[i][usize::from(j)];
                }
            }
            Var::Artificial => column = self.art,
        }
        column
    }

    /// Sets the tableau column of `var` to the unit vector `e_r` (index checks as in
    /// [`Self::column`]).
    fn set_unit_column(&mut self, var: Var, r: usize) {
        match var {
            Var::W(j) | Var::Z(j) if usize::from(j) >= N => {}
            Var::W(j) => {
                for i in 0..N {
                    self.binv[i][usize::from(j)] = T::zero();
                }
                self.binv[r][usize::from(j)] = T::one();
            }
            Var::Z(j) => {
                for i in 0..N {
                    self.zc[i][usize::from(j)] = T::zero();
                }
                self.zc[r][usize::from(j)] = T::one();
            }
            Var::Artificial => {
                self.art = [T::zero(); N];
                self.art[r] = T::one();
            }
        }
    }

    /// Pivots `entering` into the basis at row `r` (the pivot entry must be non-zero).
    fn pivot(&mut self, r: usize, entering: Var) {
        let column = self.column(entering);
        let inv = T::one() / column[r];
        for j in 0..N {
            self.binv[r][j] *= inv;
            self.zc[r][j] *= inv;
        }
        self.art[r] *= inv;
        self.rhs[r] *= inv;
        let (binv_r, zc_r, art_r, rhs_r) = (self.binv[r], self.zc[r], self.art[r], self.rhs[r]);
        for i in 0..N {
            let f = column[i];
            if i == r || f == T::zero() {
                continue;
            }
            for j in 0..N {
                self.binv[i][j] -= f * binv_r[j];
                self.zc[i][j] -= f * zc_r[j];
            }
            self.art[i] -= f * art_r;
            self.rhs[i] -= f * rhs_r;
        }
        // The basic column becomes exactly `e_r` (no round-off left in it).
        self.set_unit_column(entering, r);
        self.basis[r] = entering;
    }

    /// Breaks a tie among the rows in `ties` lexicographically: the row whose
    /// `binv[row] / div(row)` is lexicographically smallest. `B^-1` is non-singular, so in
    /// exact arithmetic exactly one row remains; with round-off the lowest index of the
    /// survivors is taken.
    fn lex_min(&self, mut ties: Rows<N, WORDS>, div: impl Fn(usize) -> T) -> usize {
        let n_eps = T::of(N as f64) * T::EPS;
        for j in 0..N {
            if ties.len() <= 1 {
                break;
            }
            let mut lo = T::zero();
            let mut mag = T::zero();
            let mut first = true;
            for i in 0..N {
                if ties.contains(i) {
                    let v = self.binv[i][j] / div(i);
                    mag = max(mag, v.abs_exact());
                    if first || v < lo {
                        lo = v;
                        first = false;
                    }
                }
            }
            let tol = n_eps * mag;
            for i in 0..N {
                if ties.contains(i) && self.binv[i][j] / div(i) > lo + tol {
                    ties.remove(i);
                }
            }
        }
        // `ties` always has a row; `first` is below `N` even for none, so the compiler sees that
        // every use of the row is in bounds (no panic path in the firmware).
        ties.first()
    }

    /// Row that leaves when the artificial variable enters first: the most negative
    /// right-hand side, ties broken by the lexicographically smallest row of `B^-1`
    /// (the artificial column is `-e`, so this is the lexicographic minimum ratio).
    fn first_leaving_row(&self) -> usize {
        let mut lo = self.rhs[0];
        for i in 0..N {
            if self.rhs[i] < lo {
                lo = self.rhs[i];
            }
        }
        let tol = T::of(N as f64) * T::EPS * lo.abs_exact();
        let mut ties = Rows::EMPTY;
        for i in 0..N {
            if self.rhs[i] <= lo + tol {
                ties.insert(i);
            }
        }
        self.lex_min(ties, |_| T::one())
    }

    /// Lexicographic minimum-ratio test for the column of `entering`, on its entries above
    /// `floor` times its largest ([`Self::run`]). `None` means the column has no such entry:
    /// ray termination. The artificial variable leaves whenever it is among the tied rows.
    fn leaving_row(&self, entering: Var, floor: T) -> Option<usize> {
        let col = self.column(entering);
        let mut col_max = T::zero();
        let mut rhs_max = T::zero();
        for i in 0..N {
            col_max = max(col_max, col[i].abs_exact());
            rhs_max = max(rhs_max, self.rhs[i].abs_exact());
        }
        let n_eps = T::of(N as f64) * T::EPS;
        let piv_tol = floor * col_max;
        let mut theta: Option<T> = None;
        for i in 0..N {
            if col[i] > piv_tol {
                let ratio = max(self.rhs[i], T::zero()) / col[i];
                if theta.is_none_or(|t| ratio < t) {
                    theta = Some(ratio);
                }
            }
        }
        let theta = theta?;
        let mut ties = Rows::EMPTY;
        for i in 0..N {
            if col[i] > piv_tol
                && max(self.rhs[i], T::zero()) / col[i] <= theta + n_eps * max(theta, rhs_max / col_max)
            {
                if self.basis[i] == Var::Artificial {
                    return Some(i);
                }
                ties.insert(i);
            }
        }
        Some(self.lex_min(ties, |i| col[i]))
    }

    /// Runs Lemke's pivoting from this tableau, pivoting only on a column's entries above
    /// `floor` times its largest ([`super::Lemke::with_pivot_floor`]). Returns the pivots on
    /// success (the artificial variable left the basis, or was never needed).
    pub(super) fn run(&mut self, max_pivots: u32, floor: T) -> Result<u32, LcpError> {
        if self.rhs.iter().all(|&x| x >= T::zero()) {
            return Ok(0);
        }
        let r = self.first_leaving_row();
        let mut leaving = self.basis[r];
        self.pivot(r, Var::Artificial);
        // The artificial variable's entry is not counted (the convention of Murty's
        // 2^n - 1 bound and of the corpus): `pivots` counts the complementary pivots.
        let mut pivots = 0u32;
        loop {
            let entering = leaving.complement();
            if pivots >= max_pivots {
                return Err(LcpError::MaxPivots { pivots });
            }
            let Some(r) = self.leaving_row(entering, floor) else {
                return Err(LcpError::Ray { pivots });
            };
            leaving = self.basis[r];
            self.pivot(r, entering);
            pivots += 1;
            if leaving == Var::Artificial {
                return Ok(pivots);
            }
        }
    }

    /// `z` and the basis of the current (terminal) tableau.
    ///
    /// The basic values get one step of iterative refinement against the original data:
    /// with `B` the basis columns of `[I, -M]`, `r = q - B x_B` and `x_B += B^-1 r`, using
    /// the tableau's own `B^-1` (`O(N^2)`). This removes most of the error that pivot growth
    /// leaves in long pivot sequences. Tiny negative basic values left by round-off are
    /// then clamped to zero; verification judges the result.
    pub(super) fn solution(&self, lcp: &Lcp<T, N>) -> (SVector<T, N>, Basis<N, WORDS>) {
        let mut x = self.rhs;
        let mut residual = [T::zero(); N];
        for i in 0..N {
            let mut acc = lcp.q[i];
            for k in 0..N {
                match self.basis[k] {
                    Var::W(j) if j as usize == i => acc -= x[k],
                    Var::W(_) | Var::Artificial => {}
                    Var::Z(j) => acc += lcp.m.get((i, j as usize)).copied().unwrap_or(T::zero()) * x[k],
                }
            }
            residual[i] = acc;
        }
        for k in 0..N {
            let mut delta = T::zero();
            for i in 0..N {
                delta += self.binv[k][i] * residual[i];
            }
            x[k] += delta;
        }
        let mut z = SVector::<T, N>::zeros();
        let mut basis = Basis::all_w();
        for r in 0..N {
            // `i < N` always (a basic `Z(i)` of this tableau); `get_mut` says so without a panic path.
            if let Var::Z(i) = self.basis[r]
                && let Some(zi) = z.get_mut(i as usize)
            {
                *zi = max(x[r], T::zero());
                basis.set_z_basic(i as usize, true);
            }
        }
        (z, basis)
    }
}
