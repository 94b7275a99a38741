//! The solution of one complementary basis in factored form ([`Factored::solve_basis`]): the
//! unknowns of the basis' pattern per slot, their system ([`super::systems`]; from the step's
//! [`ContactBlocks`] when every unknown is a sliding slot's normal impulse), then `z`, `dv`, `w`
//! in factored form and the acceptance rules (the parent module's "The solution of a basis"):
//! impulses `>= 0` exactly and not within round-off of the largest, each velocity row and `sigma`
//! `>= 0` within its own round-off ([`Factored::within_round_off`]), cone rows `>= 0` exactly,
//! finite, and the verification residual ([`crate::lcp::verify`]) on Lemke's scale or below.

use super::systems::{form_sliding, solve_four, solve_leading_out_of_line, solve_small, solve_symmetric};
use super::{Answer, ContactBlocks, Factored, MOST_SLOTS, UNKNOWNS, negated_if};
use crate::planar::Declined;
use crate::real::{AllFinite, Real, max};
use crate::slot::full_rows;

/// The scale of a basis answer's round-off ([`Factored::round_off_scale`]).
#[derive(Debug, Clone, Copy)]
struct RoundOffScale<T, const B: usize> {
    /// The non-zero impulses.
    terms: u32,
    /// `sum_v |M~ c_v| |z_v|` per body.
    sums: [[T; 3]; B],
}

impl<T: Real, const B: usize, const N: usize> Factored<T, B, N> {
    /// `true` when `w_v = wv < 0`, computed by [`Self::solve_basis`] from impulses whose scale is
    /// `scale` ([`Self::round_off_scale`]), is within row `v`'s round-off:
    /// `-wv <= (t + 8) eps (|q_v| + |c_v|^T sum_u |M~ c_u| |z_u|)`, `t` the non-zero impulses (the
    /// error bound of evaluating `w_v` from the computed `z`: `dv`'s sums of at most `t` products,
    /// the dot product of at most six and the sum with `q_v`; the basis solve's own error in `z`
    /// is not in it, so the test errs towards declining, and a declined basis goes to the next
    /// path), each row on its own data.
    ///
    /// A row's own scale, not `||A|| ||z||`: with masses 1000:1 apart that product pairs the light
    /// body's diagonal (per unit reference mass about 1000 times the heavy one's) with the heavy
    /// body's impulses, a floor of 6e-5 m/s that would pass a real slip of 2.2e-5 m/s, above the
    /// stick speed (`docs/formulation.md`, "Solving a multibody step (the core)").
    #[inline]
    fn within_round_off(&self, v: usize, wv: T, scale: &RoundOffScale<T, B>) -> bool {
        let v = v.min(N - 1);
        -wv <= T::of_count(scale.terms + 8)
            * T::EPS
            * (self.q[v].abs_exact() + self.column(v).0.dot_abs(&scale.sums))
    }

    /// `true` when the negative `wv` of a row whose round-off may excuse it is beyond that round-off
    /// ([`Self::within_round_off`] of row `row`; `row >= N`: no row excuses it, `w >= 0` exactly),
    /// the scale computed into `scale` at the first call for `z`. Out of line and cold: a basis
    /// answer reaches it only at a negative `w` (the resting stack never does).
    #[cold]
    #[inline(never)]
    fn beyond_round_off(
        &self,
        row: usize,
        wv: T,
        scale: &mut Option<RoundOffScale<T, B>>,
        z: &[T; N],
    ) -> bool {
        row >= N || !self.within_round_off(row, wv, scale.get_or_insert_with(|| self.round_off_scale(z)))
    }

    /// [`Self::solve_basis`]'s check of row `v` (`basic`: `z_v` basic) at `w_v = wv`: its
    /// finiteness, its violation (`|w_v|` for a basic row; else `-w_v`, a negative one declined
    /// beyond row `row`'s round-off, [`Self::beyond_round_off`], unless `row` is `N + 1`: held to
    /// the residual).
    #[inline(always)]
    #[allow(clippy::inline_always)] // a few instructions a row, in the solve's per-slot loop
    fn check_row(
        &self,
        (v, basic): (usize, bool),
        wv: T,
        row: usize,
        (finite, violation, scale): (&mut AllFinite<T>, &mut T, &mut Option<RoundOffScale<T, B>>),
        z: &[T; N],
    ) -> Result<(), Declined> {
        finite.add(wv);
        if basic {
            *violation = max(*violation, wv.abs_exact());
        } else if row == N + 1 {
            *violation = max(*violation, -wv);
        } else {
            if wv < T::zero() && self.beyond_round_off(row, wv, scale, z) {
                return Err(Declined::Infeasible(v as u8));
            }
            *violation = max(*violation, -wv);
        }
        Ok(())
    }

    /// [`Self::solve_basis`]'s pairs of the basis `mask` with a basic friction impulse (`held`) and
    /// of those the pairs whose basic friction sticks (`pinned`), as bits by pair.
    #[inline(never)]
    fn held_and_pinned(&self, mask: u32) -> (u32, u32) {
        let k = self.k.min(N / 4);
        let basic = |v: usize| mask.checked_shr(v as u32).unwrap_or(0) & 1 == 1;
        let (mut held, mut pinned) = (0u32, 0u32);
        for j in 0..k {
            let [_, plus, minus, sigma] = full_rows(k, j);
            if basic(plus) || basic(minus) {
                let bit = 1u32.checked_shl(u32::from(self.pair[j])).unwrap_or(0);
                held |= bit;
                if !basic(sigma) {
                    pinned |= bit;
                }
            }
        }
        (held, pinned)
    }

    /// The scale of [`Self::within_round_off`] for the impulses in `z`: the non-zero impulses `t`
    /// and `sum_v |M~ c_v| |z_v|` per body. Computed at a basis answer's first negative `w` (a
    /// resting contact's round-off), not for every answer.
    #[inline(never)]
    fn round_off_scale(&self, z: &[T; N]) -> RoundOffScale<T, B> {
        let mut scale = RoundOffScale { terms: 0, sums: [[T::zero(); 3]; B] };
        for v in 0..(3 * self.k.min(N / 4)).min(N) {
            let magnitude = z[v].abs_exact();
            if magnitude != T::zero() {
                let col = self.column(v).0;
                scale.terms += 1;
                for b in 0..B {
                    for c in 0..3 {
                        scale.sums[b][c] += col.mc[b][c].abs_exact() * magnitude;
                    }
                }
            }
        }
        scale
    }

    /// The complementary solution of the basis `mask` (bit `v`: `z_v` basic) in the bodies'
    /// coordinates, verified within `tolerance` (module docs), written into `z` (and `w`, when
    /// given: the stepper's paths need only `z`); returns `v+` and the basis answered, or why there
    /// is none. With the step's `blocks` ([`Self::form_blocks`]), a basis whose every unknown is a
    /// sliding slot's normal impulse takes its system from them ([`Self::solve_sliding`]).
    ///
    /// `z` must be zero on entry (only the answer's nonzero entries are written); a declined basis
    /// leaves it zero again, so that the next basis may be solved into the same array.
    ///
    /// # Errors
    /// [`Declined`]: a pattern this path does not take (an identity row's variable basic, `sigma`
    /// basic without exactly one friction row, more unknowns than it holds), a singular system,
    /// an infeasible basis, an answer that fails verification.
    #[inline(never)]
    pub(in crate::multibody) fn solve_basis(
        &self,
        mask: u32,
        tolerance: T,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
        w: Option<&mut [T; N]>,
    ) -> Result<Answer<T, B>, Declined> {
        let answer = self.solve_zeroed(mask, tolerance, blocks, z, w);
        // A pattern or a singular system is declined before any entry of `z` is written: only a
        // later decline has one to clear.
        if let Err(Declined::Infeasible(_) | Declined::Unverified) = answer {
            *z = [T::zero(); N];
        }
        answer
    }

    /// [`Self::solve_basis`] into `z` zero on entry, left as written when declined.
    #[allow(clippy::too_many_lines)] // the module docs' elimination, solve and checks, in order
    #[inline(always)]
    #[allow(clippy::inline_always)] // its one call: `solve_basis`'s body
    fn solve_zeroed(
        &self,
        mask: u32,
        tolerance: T,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
        mut w: Option<&mut [T; N]>,
    ) -> Result<Answer<T, B>, Declined> {
        let k = self.k.min(N / 4);
        let rows = 4 * k;
        let outside = if rows >= 32 { 0 } else { !((1u32 << rows) - 1) };
        if mask & outside != 0 {
            return Err(Declined::Pattern);
        }
        let basic = |v: usize| (mask >> v) & 1 == 1;
        let cap = UNKNOWNS.min(3 * B);
        // The unknowns: the variable each sets and the friction row following it at `mu` (`N`:
        // none).
        let mut var = [0u8; UNKNOWNS];
        let mut follower = [N; UNKNOWNS];
        let mut m = 0usize;
        for j in 0..k {
            let [_, plus, minus, sigma] = full_rows(k, j);
            let frictions = usize::from(basic(plus)) + usize::from(basic(minus));
            if basic(sigma) {
                if frictions != 1 {
                    return Err(Declined::Pattern);
                }
                let f = if basic(plus) { plus } else { minus };
                if basic(j) {
                    if m >= cap {
                        return Err(Declined::Pattern);
                    }
                    var[m] = j as u8;
                    follower[m] = f;
                    m += 1;
                }
                continue;
            }
            for v in [j, plus, minus] {
                if basic(v) {
                    if m >= cap {
                        return Err(Declined::Pattern);
                    }
                    var[m] = v as u8;
                    m += 1;
                }
            }
        }
        let m = m.min(UNKNOWNS);
        // H^T M~ G y = -q_H ([`Self::form_column`]).
        let symmetric = follower.iter().all(|&f| f == N);
        let tiny = T::of(N as f64) * T::EPS * self.m_low;
        // The two copies specialised to a count of unknowns are left out with `compact` (the
        // general one below does the same operations in the same order: the same bits).
        let from_blocks = blocks.filter(|_| follower[..m].iter().all(|&f| f < N));
        let (solved, mut y) = if let Some(blocks) = from_blocks {
            self.solve_sliding(blocks, (&var, &follower), m, tiny)
        } else if symmetric && m == UNKNOWNS && !cfg!(feature = "compact") {
            self.solve_nine_symmetric(&var, tiny)
        } else if !symmetric && m == 4 && !cfg!(feature = "compact") {
            self.solve_four_following((&var, &follower), tiny)
        } else {
            let mut a = [[T::zero(); UNKNOWNS]; UNKNOWNS];
            let mut y = [T::zero(); UNKNOWNS];
            for l in 0..m {
                self.form_column(&mut a, &mut y, (&var, &follower), l, symmetric, m);
            }
            let solved = if symmetric {
                solve_symmetric(&mut a, &mut y, m, tiny)
            } else {
                solve_leading_out_of_line(&mut a, &mut y, m, tiny)
            };
            (solved, y)
        };
        if !solved {
            return Err(Declined::Singular);
        }
        // Impulses `>= 0` exactly, no normal impulse positive within the round-off of the largest
        // (a degenerate basis: the one without it answers, `core/src/planar/factored.rs`). A
        // sticking contact's friction unknown of either sign is an answer: `c_-d = -c_+d`
        // exactly, so a negative `p_+d` is the same solution as `p_-d = -p_+d` in the basis with
        // `p_-d` basic instead (its row `w_-d = -w_+d = 0`, `w_+d = 0` outside it), and that basis
        // is the one kept. A friction impulse within round-off of zero (a resting stack's zero
        // tangential load) is kept: it holds the interface's slip at zero; declining it would leave
        // the interface without friction, whose slip round-off nothing opposes (the stack creeps).
        let (mut y_max, mut mask) = (T::zero(), mask);
        for l in 0..m {
            y_max = max(y_max, y[l].abs_exact());
            let v = usize::from(var[l]);
            if v >= k && y[l] < T::zero() {
                // The other direction of the same contact (`k + 2 j` <-> `k + 2 j + 1`).
                let other = if (v - k) & 1 == 0 { v + 1 } else { v - 1 };
                mask ^= (1u32 << v.min(31)) | (1u32 << other.min(31));
                var[l] = other as u8;
                y[l] = -y[l];
            }
        }
        let impulse_round_off = T::of(N as f64) * T::EPS * y_max;
        let basic = |v: usize| (mask >> v) & 1 == 1;
        // `p_norm`: the largest impulse (every other impulse is zero): the largest unknown (each
        // `|y_l|`, checked `>= 0` below) or a follower.
        let mut p_norm = y_max;
        for l in 0..m {
            let normal = usize::from(var[l]) < k;
            if y[l] < T::zero() || (normal && y[l] > T::zero() && y[l] <= impulse_round_off) {
                return Err(Declined::Infeasible(var[l]));
            }
            z[usize::from(var[l]).min(N - 1)] = y[l];
            if follower[l] < N {
                let friction = self.mu[usize::from(var[l]).min(N - 1)] * y[l];
                z[follower[l]] = friction;
                p_norm = max(p_norm, friction);
            }
        }
        let dv = self.velocity_change(z);
        // The pairs with a basic friction impulse (`held`): a touching contact of any other pair
        // holds its slip to `>= 0` in both directions exactly (zero), not within round-off. (Within
        // a pair every corner's slip is the one relative slip of the two bodies along their face,
        // held by the corner whose friction is basic; another pair's touching contact with no
        // friction would let that slip's round-off run unopposed.) Of those, the pairs whose basic
        // friction sticks (`pinned`: its row, basic, holds the slip at zero): another touching
        // corner's friction rows carry that row's `w` (the same slip) and are held to the
        // verification residual as it is; where it slides at its cone's edge the slip is its
        // `sigma >= 0`, and another corner's rows are held to their own round-off. Formed at the
        // first slot that reads them (a slot at its cone's edge does not).
        let mut pairs = None;
        // Slot by slot: each basic sigma from its friction row, `w` in factored form, feasibility
        // outside the basis (a negative velocity row or sigma within its own row's round-off,
        // [`Self::within_round_off`], its scale computed at the first negative one) and the
        // verification residual (`crate::lcp::verify`) bounded without a division per row, on the
        // scale `||A||_low ||z|| + ||q||`. The `-d` row is the `+d` row negated (its column and
        // `q`: the same bits, the same round-off bound). The identity's rows beyond `4 k` have
        // `w = 1`, `z = 0`: nothing to check.
        let mut violation = T::zero();
        let mut z_norm = p_norm;
        let mut finite = AllFinite::new();
        let mut scale = None;
        let mut along = [T::zero(); MOST_SLOTS];
        for j in 0..k.min(N / 4) {
            let [n, plus, minus, sigma] = full_rows(k, j).map(|v| v.min(N - 1));
            let slip = self.q[plus] + self.cols[plus].dot(&dv);
            if let Some(a) = along.get_mut(j) {
                *a = slip;
            }
            if basic(sigma) {
                let value = if basic(plus) { -slip } else { slip };
                if value < T::zero() && self.beyond_round_off(plus, value, &mut scale, z) {
                    return Err(Declined::Infeasible(sigma as u8));
                }
                z[sigma] = max(value, T::zero());
                z_norm = max(z_norm, z[sigma]);
                if value >= T::zero() && w.is_none() {
                    // `z_sigma = value` (not NaN): the slot's friction and cone rows hold exactly,
                    // as their checks below would conclude. The basic friction row's `w` is
                    // `slip - slip = 0`, the other's `2 z_sigma >= 0`, and `w_sigma = mu p_n - mu
                    // p_n - 0 = 0` (`p_f = mu p_n`, the same product; with no basic `p_n`, `0`): no
                    // violation, nothing infeasible; their finiteness is `2 z_sigma`'s and the
                    // impulses' (a non-finite `p_f` makes `dv`, and so the normal row's `w`, or
                    // `s_w` non-finite). Only the normal row is checked.
                    let wn = self.q[n] + self.cols[n].dot(&dv);
                    finite.add(value + value);
                    let checks = (&mut finite, &mut violation, &mut scale);
                    self.check_row((n, basic(n)), wn, n, checks, z)?;
                    continue;
                }
            }
            let rows_w = [
                self.q[n] + self.cols[n].dot(&dv),
                slip + z[sigma],
                -slip + z[sigma],
                self.mu[j] * z[n] - z[plus] - z[minus],
            ];
            if let Some(w) = w.as_deref_mut() {
                [w[n], w[plus], w[minus], w[sigma]] = rows_w;
            }
            let pair = u32::from(self.pair[j]);
            let (held, pinned) = *pairs.get_or_insert_with(|| self.held_and_pinned(mask));
            let unheld = basic(n) && held.checked_shr(pair).unwrap_or(0) & 1 == 0;
            let is_pinned = basic(n) && pinned.checked_shr(pair).unwrap_or(0) & 1 == 1;
            // The row whose round-off may excuse a negative `w` (`N`: none, `w >= 0` exactly; `N +
            // 1`: a touching corner of a pinned pair, held to the residual as the pair's basic
            // friction row is).
            let friction_row = if unheld {
                N
            } else if is_pinned {
                N + 1
            } else {
                plus
            };
            // The slot's four rows in order (written out: no loop over them).
            let mut check = |v: usize, wv: T, row: usize| {
                self.check_row((v, basic(v)), wv, row, (&mut finite, &mut violation, &mut scale), z)
            };
            check(n, rows_w[0], n)?;
            check(plus, rows_w[1], friction_row)?;
            check(minus, rows_w[2], friction_row)?;
            check(sigma, rows_w[3], N)?;
        }
        if let Some(w) = w {
            w[rows.min(N)..].copy_from_slice(&self.q[rows.min(N)..]);
        }
        let s_w = max(self.m_low * z_norm + self.q_norm, T::TINY);
        finite.add(s_w);
        if !finite.holds() || violation > tolerance * s_w {
            return Err(Declined::Unverified);
        }
        let mut v_plus = self.v_free;
        for b in 0..B {
            for c in 0..3 {
                v_plus[b][c] += dv[b][c];
            }
        }
        Ok(Answer { v_plus, mask, along })
    }
}

impl<T: Real, const B: usize, const N: usize> Factored<T, B, N> {
    /// [`Self::solve_basis`]'s system with every unknown and none with a follower (the 3-block
    /// stack's every step), out of line: whether it was regular, and the unknowns.
    #[inline(never)]
    fn solve_nine_symmetric(&self, var: &[u8; UNKNOWNS], tiny: T) -> (bool, [T; UNKNOWNS]) {
        // Every unknown, none with a follower (the 3-block stack's every step): the lower
        // triangle formed in place, `c_r^T M~ c_l` as [`Self::form_column`] forms it (no
        // array cleared first); the upper triangle zero (`solve_symmetric` writes it before
        // reading it).
        //
        // A `-d` unknown is solved for as its `+d` one (`S A S y = b` as `A' (S y) = S b`, `S` the
        // signs, `A'` the system of the stored columns: every entry and step of the elimination
        // negates exactly with its sign, the pivots are the same), its answer negated.
        let cols: [_; UNKNOWNS] = core::array::from_fn(|l| self.column(usize::from(var[l])));
        let mut a = core::array::from_fn(|r| {
            let row = cols[r].0;
            core::array::from_fn(|l| if l <= r { row.dot_scaled(cols[l].0) } else { T::zero() })
        });
        // `S b`: `-q` of the stored column (a `-d` row's `q` is its `+d` one's negated).
        let mut y = core::array::from_fn(|l| {
            let v = usize::from(var[l]);
            -self.q[if cols[l].1 { v - 1 } else { v }.min(N - 1)]
        });
        let solved = solve_symmetric(&mut a, &mut y, UNKNOWNS, tiny);
        for l in 0..UNKNOWNS {
            if cols[l].1 {
                y[l] = -y[l];
            }
        }
        (solved, y)
    }

    /// [`Self::solve_basis`]'s system of four unknowns with followers formed from the columns (a
    /// sliding step without [`ContactBlocks`]), out of line: whether it was regular, and the
    /// unknowns.
    #[inline(never)]
    fn solve_four_following(
        &self,
        (var, follower): (&[u8; UNKNOWNS], &[usize; UNKNOWNS]),
        tiny: T,
    ) -> (bool, [T; UNKNOWNS]) {
        // Four unknowns with followers (block-on-block's sliding steps): written out in a
        // `4 x 4` system, every entry formed (no array cleared first, no row of nine swapped).
        let (mut a, mut rhs) = ([[T::zero(); 4]; 4], [T::zero(); 4]);
        for l in [0, 1, 2, 3] {
            self.form_column(&mut a, &mut rhs, (var, follower), l, false, 4);
        }
        let solved = solve_four(&mut a, &mut rhs, tiny);
        let [y0, y1, y2, y3] = rhs;
        let zero = T::zero();
        (solved, [y0, y1, y2, y3, zero, zero, zero, zero, zero])
    }

    /// [`Self::solve_basis`]'s system when every unknown is a sliding slot's normal impulse with
    /// its friction row following ([`Self::only_sliding`]), from the step's [`ContactBlocks`]:
    /// `a_rl = N_rl + (+-mu_l) C_rl`; whether it was regular, and the unknowns. Out of line: the
    /// other bases' solve is compiled as without it.
    #[inline(never)]
    fn solve_sliding(
        &self,
        blocks: &ContactBlocks<T>,
        (var, follower): (&[u8; UNKNOWNS], &[usize; UNKNOWNS]),
        m: usize,
        tiny: T,
    ) -> (bool, [T; UNKNOWNS]) {
        // Every unknown a sliding slot's normal impulse (`var` its slot), its friction row
        // following at `+-mu` (`+d`: `+`): `a_rl = N_rl + (+-mu_l) C_rl` from the step's
        // blocks.
        let m4 = m.min(4);
        // Unknown `l`'s column: slot `j`'s, its friction row `+d` (`+mu`) or `-d` (`-mu`).
        let signed = |l: usize, j: usize| {
            let mu = self.mu[j];
            if follower[l].wrapping_sub(self.k) & 1 == 0 { mu } else { -mu }
        };
        let entry = |i: usize, j: usize, signed: T| {
            let normal = if j <= i { blocks.n[i][j] } else { blocks.n[j][i] };
            normal + signed * blocks.c[j][i]
        };
        if m4 == 4 && !cfg!(feature = "compact") {
            // Every slot sliding: unknown `l` is slot `l`'s (every entry formed: no array cleared
            // first; bounds constant: unrolled). Left out with `compact`: the loop below forms the
            // same entries and `solve_leading` does `solve_four`'s operations in the same order.
            let mu: [T; 4] = core::array::from_fn(|l| signed(l, l));
            let mut a = core::array::from_fn(|r| core::array::from_fn(|l| entry(r, l, mu[l])));
            let mut rhs = core::array::from_fn(|l| -self.q[l]);
            let solved = solve_four(&mut a, &mut rhs, tiny);
            let [y0, y1, y2, y3] = rhs;
            let zero = T::zero();
            return (solved, [y0, y1, y2, y3, zero, zero, zero, zero, zero]);
        }
        // Fewer unknowns: in a `4 x 4` array; with `compact` in the general solve's arrays (its one
        // copy of the elimination: the same operations).
        if cfg!(feature = "compact") {
            let (mut a, mut y) = ([[T::zero(); UNKNOWNS]; UNKNOWNS], [T::zero(); UNKNOWNS]);
            form_sliding(m4, (var, &signed, &entry), &self.q, (&mut a, &mut y));
            (solve_leading_out_of_line(&mut a, &mut y, m4, tiny), y)
        } else {
            let (mut a, mut rhs) = ([[T::zero(); 4]; 4], [T::zero(); 4]);
            form_sliding(m4, (var, &signed, &entry), &self.q, (&mut a, &mut rhs));
            let solved = solve_small(&mut a, &mut rhs, m4, tiny);
            let [y0, y1, y2, y3] = rhs;
            let zero = T::zero();
            (solved, [y0, y1, y2, y3, zero, zero, zero, zero, zero])
        }
    }

    /// Column `l` of [`Self::solve_basis`]'s system and its right-hand side: unknown `l`'s
    /// column `G_l = c_var + mu c_follower` (the same bodies), each row's `c_r^T M~ G_l`, taken
    /// from its mirror between two unknowns without a follower when that is already formed
    /// (`c_r^T M~ c_l`, symmetric); `symmetric`: the lower triangle only (all `solve_symmetric`
    /// reads).
    #[inline(always)]
    #[allow(clippy::inline_always)] // the point of it: `l` and `m` known at the call
    fn form_column<const D: usize>(
        &self,
        a: &mut [[T; D]; D],
        y: &mut [T; D],
        (var, follower): (&[u8; UNKNOWNS], &[usize; UNKNOWNS]),
        l: usize,
        symmetric: bool,
        m: usize,
    ) {
        let (l, m) = (l.min(D - 1).min(UNKNOWNS - 1), m.min(D));
        let (g, minus_l) = self.column(usize::from(var[l]));
        let mut g = *g;
        if follower[l] < N {
            // `+ mu c_-d` as `- mu c_+d` (`x + mu (-y)` is `x - mu y`: the same bits).
            let ((f, minus_f), mu) = (self.column(follower[l]), self.mu[usize::from(var[l]).min(N - 1)]);
            for b in 0..B {
                for c in 0..3 {
                    if minus_f {
                        g.mc[b][c] -= mu * f.mc[b][c];
                    } else {
                        g.mc[b][c] += mu * f.mc[b][c];
                    }
                }
            }
        }
        for r in (if symmetric { l } else { 0 })..m {
            a[r][l] = if r < l && follower[r] == N && follower[l] == N {
                a[l][r]
            } else {
                let (row, minus_r) = self.column(usize::from(var[r]));
                negated_if(row.dot_scaled(&g), minus_r ^ minus_l)
            };
        }
        y[l] = -self.q[usize::from(var[l]).min(N - 1)];
    }
}
