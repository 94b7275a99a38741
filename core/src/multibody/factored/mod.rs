//! One multibody step's LCP in factored form, and its solution for a given complementary basis in
//! the bodies' `3B` coordinates: the stepper's fast path (`docs/formulation.md`, "Solving a
//! multibody step"). The single body's form (`core/src/planar/factored.rs`) in `3B` coordinates.
//!
//! # The factored form
//! With `k` active candidates the variables are laid out as the stepper's LCP
//! ([`super::SystemStepper`]): `p_n` of slot `j` at `j`, `p_+d` at `k + 2 j`, `p_-d` at `k + 2 j + 1`,
//! `sigma` at `3 k + j`; rows `4 k .. N` are the identity's (`q = 1`). Impulse variable `v` has
//! the Jacobian column `c_v`, dense in the bodies' `3B` coordinates (zero at a body the contact
//! does not touch: a contact on the table touches one body, one between two bodies both), `M~ c_v`
//! (per unit reference mass) and `q_v = c_v^T v~ + c0_v`; a slot's `-d` column is its `+d` column
//! negated and is not stored ([`Factored::column`]), so that
//!
//! ```text
//! w_v     = q_v + c_v^T dv (+ sigma_j for a friction row of slot j),   dv = sum_v M~ c_v p_v
//! w_sigma = mu_j p_n,j - p_+d,j - p_-d,j
//! ```
//!
//! Nothing here forms the `N x N` matrix; a row costs `B` 3-vector dot products.
//!
//! # The solution of a basis
//! Per slot the eliminations of the single body's form: `sigma` basic with one friction row `f`
//! basic (sliding, or at the cone's edge): `p_f = mu p_n`, one unknown `p_n` acting through
//! `c_n + mu c_f`, held by its normal row, `sigma = -(q_f + c_f^T dv)` afterwards (without a basic
//! `p_n`, only `sigma`); `sigma` not basic: each basic `p_n`, `p_f` is an unknown held by its own
//! row; any other pattern is declined. At most `min(3 B, UNKNOWNS)` unknowns (more rows than the
//! bodies' degrees of freedom make the system singular): `H^T M~ G y = -q_H`, by `L D L^T`
//! without pivoting when it is symmetric (no unknown has a follower: `G^T M~ G`,
//! [`systems::solve_symmetric`]), else by elimination with partial pivoting
//! ([`crate::lcp::elimination::solve_leading`]); then `z`,
//! `dv`, `w` in factored form and the single body's acceptance rules with its round-off floors:
//! impulses `>= 0` exactly and not within `N eps` of the largest, velocity rows and `sigma`s
//! `>= 0` within each row's own round-off ([`Factored::within_round_off`]), cone rows `>= 0`
//! exactly, finite, and the verification residual ([`crate::lcp::verify`]) held to a scale no
//! larger than Lemke's (`||A||_inf` replaced by `max_v (|A_vv| + the row's unit entries)`, a lower
//! bound). A singular system (both corners of one interface sticking: four rows of rank three) is
//! declined.
//!
//! # The files
//! * this one: the form ([`Factored`]: its columns, `q` and scales, set slot by slot each step),
//!   the step's [`ContactBlocks`], `dv` and `v+` from `z`, and the assembled LCP (the solver of
//!   record's form, [`Factored::assemble`]);
//! * `basis.rs`: the solution of a basis and its acceptance ([`Factored::solve_basis`]);
//! * `systems.rs`: the basis' dense system, by `L D L^T` or by elimination;
//! * `tests.rs`: the factored solve against the assembled LCP (proptests).

mod basis;
mod systems;
#[cfg(test)]
#[allow(clippy::float_cmp, clippy::expect_used)] // exact zeros are the point; a test's setup may fail loudly
mod tests;

use nalgebra::{SMatrix, SVector};

use crate::lcp::Lcp;
use crate::planar::inputs::dot3;
use crate::planar::{MU_WEIGHTED_FROM, cone_scale};
use crate::real::{AllFinite, Real, max, min};
use crate::slot::full_rows;

/// The most unknowns a basis may have here: three bodies' degrees of freedom (a basis of more is
/// declined, and Lemke's method answers it).
pub(super) const UNKNOWNS: usize = 9;

/// A basis' verified answer ([`Factored::solve_basis`]; `z`, and `w` when asked for, are written
/// into the caller's arrays).
#[derive(Debug, Clone, Copy)]
pub(super) struct Answer<T, const B: usize> {
    /// `v+ = v~ + dv`.
    pub(super) v_plus: [[T; 3]; B],
    /// The basis answered (the one given, a sticking contact's friction turned to the direction
    /// its impulse takes).
    pub(super) mask: u32,
    /// Each slot's `c_+d^T v+` as the checks formed it, `q_+d + c_+d^T dv` (the negated slip of
    /// its corner, `super::geometry::slip`), for the first [`MOST_SLOTS`] slots.
    pub(super) along: [T; MOST_SLOTS],
}

/// The most slots a step has (`N <= 32` rows, four a slot).
pub(super) const MOST_SLOTS: usize = 8;

/// The column of one impulse variable, dense in the bodies' `3B` coordinates: `c_v` and `M~ c_v`,
/// zero in the columns of a body the contact does not touch (a contact touches one body or two).
/// Every sum below runs over all `B` bodies; a body the column does not touch adds a signed zero
/// (`0 x finite`), which changes no sum but a zero's sign, and at most two terms are not zero, so
/// their order does not matter either (IEEE addition commutes): the sums of the terms of the
/// touched bodies only, as exactly.
#[derive(Debug, Clone, Copy)]
pub(super) struct Column<T, const B: usize> {
    /// `c_v` per body.
    c: [[T; 3]; B],
    /// `M~ c_v` per body.
    mc: [[T; 3]; B],
}

impl<T: Real, const B: usize> Column<T, B> {
    fn zero() -> Self {
        Self { c: [[T::zero(); 3]; B], mc: [[T::zero(); 3]; B] }
    }

    /// `c^T v` for velocities (or velocity changes) `v` in `3B` coordinates.
    #[cfg_attr(not(feature = "compact"), inline)]
    #[cfg_attr(feature = "compact", inline(never))] // the page's module: one copy
    fn dot(&self, v: &[[T; 3]; B]) -> T {
        let mut sum = T::zero();
        for b in 0..B {
            sum += dot3(&self.c[b], &v[b]);
        }
        sum
    }

    /// `c^T (M~ g)` for the column `g` (`g`'s `M~ c`): the entry of `J M~ J^T` in this row and
    /// `g`'s column.
    #[cfg_attr(not(feature = "compact"), inline)]
    #[cfg_attr(feature = "compact", inline(never))] // the page's module: one copy
    fn dot_scaled(&self, g: &Self) -> T {
        let mut sum = T::zero();
        for b in 0..B {
            sum += dot3(&self.c[b], &g.mc[b]);
        }
        sum
    }

    /// `dv += M~ c z`.
    #[cfg_attr(not(feature = "compact"), inline)]
    #[cfg_attr(feature = "compact", inline(never))] // the page's module: one copy
    fn add_scaled_to(&self, z: T, dv: &mut [[T; 3]; B]) {
        for b in 0..B {
            for c in 0..3 {
                dv[b][c] += self.mc[b][c] * z;
            }
        }
    }

    /// `|c|^T a` for per-body magnitudes `a >= 0`: this row's share of a round-off bound
    /// ([`Factored::within_round_off`]).
    #[inline]
    fn dot_abs(&self, a: &[[T; 3]; B]) -> T {
        let mut sum = T::zero();
        for b in 0..B {
            for c in 0..3 {
                sum += self.c[b][c].abs_exact() * a[b][c];
            }
        }
        sum
    }
}

/// The factored rows of one multibody step's LCP (module docs).
#[derive(Debug, Clone, Copy)]
pub(super) struct Factored<T, const B: usize, const N: usize> {
    /// Active slots `k` (`4 k <= N`).
    k: usize,
    /// The `-d` variables `k + 2 j + 1` as bits ([`Self::column`]).
    minus: u32,
    /// Each impulse variable's column (`v < 3 k`).
    cols: [Column<T, B>; N],
    /// `q`.
    q: [T; N],
    /// Each slot's friction coefficient this step.
    mu: [T; N],
    /// Each slot's pair (its two bodies: the corners of one interface share their slip).
    pair: [u8; N],
    /// `v~`.
    v_free: [[T; 3]; B],
    /// `max_v (|A_vv| + the row's unit entries)`, a lower bound of `||A||_inf`.
    m_low: T,
    /// `||q||_inf`.
    q_norm: T,
    /// `min_v q_v`.
    q_min: T,
    /// `max |q_v|` over the friction rows ([`Self::set_slot`]; [`Self::finish`] closes `q_norm` and
    /// `q_min` over it).
    q_friction: T,
    /// Every entry of `q` and every diagonal entry `A_vv` is finite (and so every entry of `c` and
    /// `M~ c`, [`Self::set_slot`]).
    finite: bool,
    /// The finiteness of the columns set so far this step ([`Self::set_slot`]).
    columns_finite: AllFinite<T>,
    /// The `k` of the last [`Self::finish`] (`q`'s sigma and identity rows are its), `usize::MAX`
    /// before the first.
    finished_k: usize,
    /// Some slot's cone row is weighted (`mu >= MU_WEIGHTED_FROM`, [`crate::planar::cone_scale`]).
    weighted: bool,
    /// The step's [`ContactBlocks`], when [`Self::form_blocks`] formed them (`blocks_formed`; kept
    /// here, written in place: no array cleared or copied for them).
    blocks: ContactBlocks<T>,
    /// [`Self::form_blocks`] formed `blocks` for this step's columns (cleared by [`Self::reset`]).
    blocks_formed: bool,
}

/// The normal block `N` (lower triangle: `n[i][j]`, `j <= i`) and the friction coupling `C` (by
/// columns: `c[j][i] = C_ij`) of a step's four slots ([`Factored::contact_blocks`]), formed once
/// for the step: a basis of sliding contacts takes its system from them (`N + C S mu`,
/// [`Factored::solve_basis`]) and the rule's detection its test ([`super::resolve::flags`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct ContactBlocks<T> {
    /// `N_ij = c_n,i^T M~ c_n,j`, `j <= i`.
    pub(super) n: [[T; 4]; 4],
    /// `C_ij = c_n,i^T M~ c_+d,j` at `c[j][i]`.
    pub(super) c: [[T; 4]; 4],
}

impl<T: Real, const B: usize, const N: usize> Factored<T, B, N> {
    /// No contact: [`Self::reset`] it for a step.
    pub(super) fn new() -> Self {
        // Every variable's index (`< N`) is a bit of a `u32` basis mask and fits the `u8` of a
        // [`Declined::Infeasible`] and of an unknown's variable: their narrowings are exact.
        const { assert!(N >= 4 && N <= 32, "Factored<T, B, N> needs 4 <= N <= 32") };
        Self {
            k: 0,
            minus: 0,
            cols: [Column::zero(); N],
            q: [T::zero(); N],
            mu: [T::zero(); N],
            pair: [0; N],
            v_free: [[T::zero(); 3]; B],
            m_low: T::one(),
            q_norm: T::zero(),
            q_min: T::zero(),
            q_friction: T::zero(),
            finite: true,
            columns_finite: AllFinite::new(),
            finished_k: usize::MAX,
            weighted: false,
            blocks: ContactBlocks { n: [[T::zero(); 4]; 4], c: [[T::zero(); 4]; 4] },
            blocks_formed: false,
        }
    }

    /// A step of `k` active slots with `v~`, in place (nothing cleared: [`Self::set_slot`] writes
    /// each active slot's variables, [`Self::finish`] the rest); the scales and finiteness the
    /// slots accumulate start over.
    pub(super) fn reset(&mut self, k: usize, v_free: [[T; 3]; B]) {
        self.k = k.min(N / 4);
        // Bits `k + 1, k + 3, .., 3 k - 1` (`3 k <= 24` for any `N` a `u32` basis holds).
        let k = self.k.min(8);
        self.minus = (0x5555_u32 & ((1u32 << (2 * k)) - 1)) << (k + 1);
        self.v_free = v_free;
        self.m_low = T::one();
        self.columns_finite = AllFinite::new();
        self.weighted = false;
        self.blocks_formed = false;
        self.q_norm = T::zero();
        self.q_friction = T::zero();
        // Above every row's `q` but the identity's (a step with slots has sigma rows, `q = 0`).
        self.q_min = T::one();
    }

    /// Slot `j` of pair `pair`: its three impulse columns from its Jacobian rows `n` and `+d`, dense
    /// in the bodies' `3B` coordinates ([`super::JacobianRow::dense`]; the `-d` column is the `+d`
    /// one negated, [`Self::column`]), its normal row's bias `c0` and its `mu`; `inverse_mass` is
    /// `M~`'s diagonal per body. Accumulates [`Self::finish`]'s scales (`||A||`'s lower bound,
    /// `||q||`, `min q`) and finiteness while the slot's values are at hand, and writes the normal
    /// row's diagonal as `N_jj` of [`Self::form_blocks`]' blocks (`j < 4`).
    #[allow(clippy::too_many_arguments)] // a slot's data, as the stepper has them
    #[inline(always)]
    #[allow(clippy::inline_always)] // one call per slot in the refill: its rows built in place there
    pub(super) fn set_slot(
        &mut self,
        j: usize,
        pair: u8,
        rows: [[[T; 3]; B]; 2],
        bias: T,
        mu: T,
        inverse_mass: &[[T; 3]; B],
    ) {
        let k = self.k.min(N / 4);
        if j >= k {
            return;
        }
        // `finish`'s scale and finiteness of the columns, accumulated here (each slot's normal and
        // `+d` columns: the `-d` one is the `+d` one negated, the same diagonal, finite with it).
        let (mut m_low, mut finite) = (self.m_low, self.columns_finite);
        let (mut q_norm, mut q_min, mut q_friction) = (self.q_norm, self.q_min, self.q_friction);
        let [normal, plus, ..] = full_rows(k, j);
        for (r, row) in rows.iter().enumerate() {
            let v = if r == 0 { normal } else { plus };
            let col = Column {
                c: *row,
                mc: core::array::from_fn(|b| {
                    let m = &inverse_mass[b];
                    [row[b][0] * m[0], row[b][1] * m[1], row[b][2] * m[2]]
                }),
            };
            let mut q = col.dot(&self.v_free);
            if r == 0 {
                q += bias;
            }
            // `q`'s finiteness and scales (the `-d` row's `-q`: as finite, as large, and the
            // smaller of the two is `-|q|`).
            finite.add(q);
            // A friction row's `|q|` counts in `||q||` as `q_norm`'s, in `min q` as `-||q_f||`
            // ([`Self::finish`]): the `+d` row's `q` and the `-d` row's `-q`.
            if r == 0 {
                q_norm = max(q_norm, q.abs_exact());
                q_min = min(q_min, q);
            } else {
                q_friction = max(q_friction, q.abs_exact());
            }
            // `A_vv = c^T M~ c` (the two bodies differ: `dot_scaled` of the column with itself);
            // its finiteness stands for the column's: a non-finite entry of `M~ c` (or of `c`,
            // `M~` being finite) makes its product with `c`, and so the sum, infinite or NaN
            // (`0 x inf` is NaN), and a diagonal beyond the format's range is refused with them.
            let diagonal = col.dot_scaled(&col);
            finite.add(diagonal);
            let unit = if r == 0 { T::zero() } else { T::one() };
            m_low = max(m_low, diagonal.abs_exact() + unit);
            if r == 0
                && let Some(n) = self.blocks.n.get_mut(j)
            {
                // `N_jj` of [`Self::form_blocks`]' blocks (the same sum), at hand.
                n[j.min(3)] = diagonal;
            }
            if let (Some(slot), Some(qv)) = (self.cols.get_mut(v), self.q.get_mut(v)) {
                *qv = q;
                *slot = col;
            }
            if r == 1
                && let Some(qv) = self.q.get_mut(v + 1)
            {
                // `-d`'s `q`, the `+d` one negated (every product and sum negates exactly: the
                // same bits as computing it from `-d`); its column is the `+d` one read negated
                // ([`Self::column`]).
                *qv = -q;
            }
        }
        // The sigma row's `|mu| + 2` (its entries `mu`, `-1`, `-1`); from `mu >= MU_WEIGHTED_FROM`
        // on it counts weighted by its power of two, `s (mu + 2)` in `[1, 4)`, as the single body's
        // (`docs/formulation.md`, "Extreme friction: the cone rows weighted"): the floors, pivot
        // tolerance and verification scale stay the velocity rows' instead of `mu` times theirs.
        let mut cone_row = mu.abs_exact() + T::of(2.0);
        if mu.abs_exact() >= T::of(MU_WEIGHTED_FROM) {
            cone_row = cone_scale(mu.abs_exact()) * cone_row;
            self.weighted = true;
        }
        self.m_low = max(m_low, cone_row);
        self.columns_finite = finite;
        self.q_norm = q_norm;
        self.q_min = q_min;
        self.q_friction = q_friction;
        if let (Some(m), Some(g)) = (self.mu.get_mut(j), self.pair.get_mut(j)) {
            *m = mu;
            *g = pair;
        }
    }

    /// After every slot is set: the sigma rows' `q` (0) and the identity's beyond `4 k` (when `k`
    /// changed), the scales and finiteness the slots accumulated closed over those rows.
    pub(super) fn finish(&mut self) {
        let k = self.k.min(N / 4);
        // Written when the slots' count changed (no other row writes them).
        if self.finished_k != k {
            for v in 3 * k..N {
                self.q[v] = if v < 4 * k { T::zero() } else { T::one() };
            }
            self.finished_k = k;
        }
        let (m_low, finite) = (self.m_low, self.columns_finite);
        // `q`'s scales over the impulse rows (`set_slot`'s), the sigma rows' (`q = 0`) and the
        // identity's (`q = 1`) when there are any.
        let (mut q_norm, mut q_min) = (max(self.q_norm, self.q_friction), min(self.q_min, -self.q_friction));
        if k > 0 {
            q_min = min(q_min, T::zero());
        }
        if 4 * k < N {
            q_norm = max(q_norm, T::one());
            q_min = min(q_min, T::one());
        }
        self.m_low = m_low;
        self.q_norm = q_norm;
        self.q_min = q_min;
        self.finite = finite.holds();
    }

    /// `true` when every entry of `q` and of the columns is finite (and every diagonal entry
    /// `c^T M~ c` within the format's range).
    pub(super) const fn is_finite(&self) -> bool {
        self.finite
    }

    /// `true` when some slot's cone row is weighted ([`Self::assemble`]).
    pub(super) const fn is_weighted(&self) -> bool {
        self.weighted
    }

    /// Forms the step's [`ContactBlocks`] ([`Self::blocks`]) when it has four slots and the basis
    /// `mask` (bit `v`: `z_v` basic) slides at every touching slot ([`Self::only_sliding`]): the
    /// warm basis of block-on-block's sliding steps, whose system ([`Self::solve_basis`]) and
    /// detection ([`super::resolve::flags`]) both read them, as do the step's candidates whose every
    /// unknown is a normal impulse with its friction row following. Any other step has none: its
    /// bases take their system from the columns and its detection forms its own blocks (a resting
    /// stack's sticking bases; its detection does not run at rest).
    #[inline]
    pub(super) fn form_blocks(&mut self, mask: u32) {
        self.blocks_formed = self.slots() == 4 && self.only_sliding(mask);
        if self.blocks_formed {
            self.four_blocks();
        }
    }

    /// The [`ContactBlocks`] [`Self::form_blocks`] formed for this step's columns, if it did.
    pub(super) const fn blocks(&self) -> Option<&ContactBlocks<T>> {
        if self.blocks_formed { Some(&self.blocks) } else { None }
    }

    /// [`Self::form_blocks`]' blocks of four slots, in place (every entry but `N`'s unread upper
    /// triangle written), out of line (a resting stack's step never calls it).
    #[inline(never)]
    fn four_blocks(&mut self) {
        if cfg!(feature = "compact") {
            // The detection's copy for up to eight slots (the same entries in the same order),
            // not one more for four.
            let (mut n, mut c) = ([[T::zero(); 8]; 8], [[T::zero(); 8]; 8]);
            self.contact_blocks_of_eight(&mut n, &mut c);
            for i in 0..4 {
                self.blocks.n[i].copy_from_slice(&n[i][..4]);
                self.blocks.c[i].copy_from_slice(&c[i][..4]);
            }
        } else {
            contact_blocks(&self.cols, 4, (4, true), &mut self.blocks.n, &mut self.blocks.c);
        }
    }

    /// `true` when no slot of the basis `mask` has a basic impulse without its `sigma` basic: every
    /// unknown of [`Self::solve_basis`] is a normal impulse with its friction row following.
    fn only_sliding(&self, mask: u32) -> bool {
        let k = self.slots();
        let low = |bits: u32, from: usize, count: usize| {
            bits.checked_shr(from as u32).unwrap_or(0) & ((1 << count) - 1)
        };
        // Per slot `j`: bit `j` of the normals, of either friction row, of the sigmas.
        let normals = low(mask, 0, k);
        let sigmas = low(mask, 3 * k, k);
        let mut frictions = 0u32;
        for j in 0..k {
            if low(mask, full_rows(k, j)[1], 2) != 0 {
                frictions |= 1 << j;
            }
        }
        (normals | frictions) & !sigmas == 0
    }

    /// Active slots `k`.
    pub(super) const fn slots(&self) -> usize {
        if self.k < N / 4 { self.k } else { N / 4 }
    }

    /// Variable `v`'s column as stored, and whether it is read negated: a `-d` column is its
    /// slot's `+d` column negated, and only that one is stored ([`Self::set_slot`]).
    #[inline(always)]
    #[allow(clippy::inline_always)] // an index and a flag, at every read of a column
    fn column(&self, v: usize) -> (&Column<T, B>, bool) {
        let minus = self.minus.checked_shr(v as u32).unwrap_or(0) & 1;
        (&self.cols[(v - minus as usize).min(N - 1)], minus == 1)
    }

    /// `c_r^T M~ c_c`: the entry of `J M~ J^T` in row `r` and column `c` (`r, c < 3 k`).
    #[cfg(test)] // the tests' entry-by-entry reference of `contact_blocks`
    pub(super) fn entry(&self, r: usize, c: usize) -> T {
        let ((row, minus_r), (col, minus_c)) = (self.column(r), self.column(c));
        negated_if(row.dot_scaled(col), minus_r ^ minus_c)
    }

    /// Slot `j`'s pair.
    pub(super) fn pair(&self, j: usize) -> u8 {
        self.pair[j.min(N - 1)]
    }

    /// Slot `j`'s friction coefficient this step.
    pub(super) fn mu(&self, j: usize) -> T {
        self.mu[j.min(N - 1)]
    }

    /// `true` when the data are finite and `q >= 0`: `z = 0` solves the LCP exactly.
    pub(super) fn is_free(&self) -> bool {
        self.finite && self.q_min >= T::zero()
    }

    /// `q`.
    pub(super) const fn q(&self) -> &[T; N] {
        &self.q
    }

    /// `v~`.
    pub(super) const fn v_free(&self) -> &[[T; 3]; B] {
        &self.v_free
    }

    /// The slot the variable `v` belongs to (0 for an identity row's).
    pub(super) const fn slot_of(&self, v: usize) -> usize {
        let k = if self.k < N / 4 { self.k } else { N / 4 };
        if v < k {
            v
        } else if v < 3 * k {
            (v - k) / 2
        } else if v < 4 * k {
            v - 3 * k
        } else {
            0
        }
    }

    /// `dv = M~ J^T p` for the impulses in `z` (eq. 16), summed on its own: `M~ c_v z_v` over the
    /// impulses `v` in order (the normals, then each slot's `+d` and `-d`), each non-zero one
    /// added.
    pub(super) fn velocity_change(&self, z: &[T; N]) -> [[T; 3]; B] {
        let k = self.k.min(N / 4);
        let mut dv = [[T::zero(); 3]; B];
        for j in 0..k {
            let zn = z[j];
            if zn != T::zero() {
                self.cols[j].add_scaled_to(zn, &mut dv);
            }
        }
        for j in 0..k {
            // Slot `j`'s `+d` column once for both directions (`-d`'s `M~ c z` as
            // `M~ c_+d (-z)`: the same product).
            let [_, plus, minus, _] = full_rows(k, j).map(|v| v.min(N - 1));
            let col = &self.cols[plus];
            let (plus, minus) = (z[plus], z[minus]);
            if plus != T::zero() {
                col.add_scaled_to(plus, &mut dv);
            }
            if minus != T::zero() {
                col.add_scaled_to(-minus, &mut dv);
            }
        }
        dv
    }

    /// `v+ = v~ + dv` with `dv` of [`Self::velocity_change`].
    pub(super) fn velocity_after(&self, z: &[T; N]) -> [[T; 3]; B] {
        let dv = self.velocity_change(z);
        let mut v = self.v_free;
        for b in 0..B {
            for c in 0..3 {
                v[b][c] += dv[b][c];
            }
        }
        v
    }

    /// The assembled LCP (the solver of record's form): `J M~ J^T` from the columns, the cone
    /// rows, the identity beyond `4 k`. With `weighted`, each cone row with `mu >=
    /// MU_WEIGHTED_FROM` multiplied by its power of two `s` ([`crate::planar::cone_scale`]): `s mu`
    /// and `-s`, exact; the same solutions (`docs/formulation.md`, "Extreme friction: the cone rows
    /// weighted").
    pub(super) fn assemble(&self, weighted: bool) -> Lcp<T, N> {
        let k = self.k.min(N / 4);
        let mut a = SMatrix::<T, N, N>::zeros();
        let rows = (3 * k).min(N);
        for i in 0..rows {
            for j in i..rows {
                let ((row, minus_i), (col, minus_j)) = (self.column(i), self.column(j));
                let e = negated_if(row.dot_scaled(col), minus_i ^ minus_j);
                for entry in [(i, j), (j, i)] {
                    if let Some(x) = a.get_mut(entry) {
                        *x = e;
                    }
                }
            }
        }
        let from = T::of(MU_WEIGHTED_FROM);
        for j in 0..k {
            let [_, plus, minus, sigma] = full_rows(k, j);
            let mu = self.mu[j.min(N - 1)];
            let s = if weighted && mu >= from { cone_scale(mu) } else { T::one() };
            let cone = [
                ((plus, sigma), T::one()),
                ((minus, sigma), T::one()),
                ((sigma, j), s * mu),
                ((sigma, plus), -s),
                ((sigma, minus), -s),
            ];
            for (entry, value) in cone {
                if let Some(x) = a.get_mut(entry) {
                    *x = value;
                }
            }
        }
        for i in 4 * k..N {
            a[(i, i)] = T::one();
        }
        Lcp::new(a, SVector::from(self.q))
    }

    #[inline(always)]
    #[allow(clippy::inline_always)] // `rows` a constant in the four slots' copy: its loops unrolled
    pub(super) fn contact_blocks<const K: usize>(
        &self,
        rows: usize,
        n: &mut [[T; K]; K],
        c: &mut [[T; K]; K],
    ) {
        contact_blocks(&self.cols, self.slots(), (rows, false), n, c);
    }

    /// [`Self::contact_blocks`] of every slot (at most eight) in arrays of eight, one copy out of
    /// line: the detection's for any count, and with `compact` the sliding step's blocks too.
    #[inline(never)]
    pub(super) fn contact_blocks_of_eight(&self, n: &mut [[T; 8]; 8], c: &mut [[T; 8]; 8]) {
        contact_blocks(&self.cols, self.slots(), (8, false), n, c);
    }
}

/// The active slots' normal block `N_ij = c_n,i^T M~ c_n,j` (its lower triangle `j <= i`
/// only: `N` is symmetric) into `n[i][j]` and their friction coupling `C_ij = c_n,i^T M~
/// c_+d,j` by columns into `c[j][i]`, for the first `min(k, K)` slots; every other entry is
/// left as given. Each entry is [`Column::dot_scaled`] of the two columns, straight from the
/// columns, slot `j`'s normal and friction `M~ c` against every slot's normal `c` in turn; with
/// `diagonal_formed`, `N`'s diagonal is left as [`Factored::set_slot`] wrote it (the same sums).
/// No decision made from these blocks reads a zero's sign: [`super::resolve::flags`] adds,
/// subtracts, multiplies, divides by its pivots (each `> 0`), takes magnitudes and compares.
#[inline(always)]
#[allow(clippy::inline_always)] // `rows` a constant in the four slots' copy: its loops unrolled
fn contact_blocks<T: Real, const B: usize, const N: usize, const K: usize>(
    cols: &[Column<T, B>; N],
    k: usize,
    (rows, diagonal_formed): (usize, bool),
    n: &mut [[T; K]; K],
    c: &mut [[T; K]; K],
) {
    let rows = rows.min(k).min(K);
    let col = |v: usize| &cols[v.min(N - 1)];
    // Column `j`'s normal and friction `M~ c` against every slot's normal `c`.
    for j in 0..rows {
        let [normal, plus, ..] = full_rows(k, j);
        let (a, f) = (col(normal), col(plus));
        for i in 0..rows {
            let u = col(i);
            if i > j || (i == j && !diagonal_formed) {
                n[i][j] = u.dot_scaled(a);
            }
            c[j][i] = u.dot_scaled(f);
        }
    }
}

/// `x`, or `0 - x` when `negate`: what a sum from zero gives for a column read negated
/// ([`Factored::column`]). A [`Column`]'s sums start from `+0`, so `x` is never `-0`, and with one
/// column negated every term negates exactly: the sum is `-x`, or `+0` when `x` is zero, which is
/// `0 - x` in both cases (the same bits as summing with the negated column).
#[inline(always)]
#[allow(clippy::inline_always)] // one subtraction at each entry read negated
fn negated_if<T: Real>(x: T, negate: bool) -> T {
    if negate { T::zero() - x } else { x }
}
