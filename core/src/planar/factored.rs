//! One step's LCP in factored form, and its solution for a given complementary basis in the
//! body's three degrees of freedom: the stepper's fast path (`docs/formulation.md`, "Solving a
//! step").
//!
//! # The factored form
//! With `c_j` the wrench column of impulse variable `j` (`W_n`, or `+-W_d` for a friction row),
//! `M^-1` per unit mass and `q_j = c_j^T v~ + c0_j` (eq. 18's right-hand side), the LCP matrix is
//!
//! ```text
//! A = [ C^T M^-1 C   E ]      C = [c_1 .. c_(N-K)]  (3 x (N - K)),  rank C^T M^-1 C <= 3
//!     [ U         -E^T 0 ]
//! ```
//!
//! so `w = A z + q` is, with `dv = M^-1 C p` the velocity change the impulses `p` make (eq. 16),
//!
//! ```text
//! w_j     = q_j + c_j^T dv + sigma_i      a friction row j of contact i (no sigma in a normal row)
//! w_sigma = mu_i p_n,i - sum_(f of i) p_f
//! ```
//!
//! Nothing here forms `A`: a row costs a 3-vector dot product.
//!
//! # The solution of a basis
//! A complementary basis says which `z_j` may be non-zero; its rows then have `w_j = 0`. Per
//! contact, the basic variables eliminate as follows:
//!
//! * `sigma_i` basic with one friction row `f` basic (sliding, or a contact at its cone's edge):
//!   the cone row `w_sigma = 0` gives `p_f = mu p_n`, so the contact has one unknown, `p_n`, acting
//!   through `W_n + mu c_f` and held by its normal row; `sigma_i = -(q_f + c_f^T dv)` follows from
//!   row `f` once `dv` is known. Without a basic `p_n`, `p_f = 0` (a separated contact whose
//!   support slips past it) and only `sigma_i` is left.
//! * `sigma_i` not basic: each basic `p_n`, `p_f` is an unknown held by its own row
//!   (`c_j^T v+ + c0_j = 0`: touching, not slipping).
//! * any other pattern (`sigma_i` basic with no or two basic friction rows) is declined: its
//!   system is singular or needs both directions at once, and Lemke's method takes it.
//!
//! The unknowns `y` (at most 3: a body in the plane has three degrees of freedom, so more rows
//! than 3 make the system singular) solve `H^T M^-1 G y = -q_H`, with `G` their columns and `H`
//! the rows holding them: an `m x m` system, `m <= 3`, by elimination with partial pivoting.
//! Then `z` is assembled, `dv = M^-1 C p` recomputed from `z`, and every `w` from the factored
//! rows above: the answer is kept only when the impulses and the cone rows are `>= 0` exactly,
//! the velocity rows and the `sigma`s `>= 0` within their round-off, no impulse (normal or
//! friction) is positive but within round-off of zero (such a basis is declined even though it
//! solves the LCP, as Lemke's method would accept it: the neighbour without that impulse, or Lemke's
//! method, answers; `docs/formulation.md`, "Solving a step", has the rules and why), the
//! data are finite, and when it passes the verification
//! residual ([`crate::lcp::verify`]) held to a scale no larger than Lemke's own: `||M||_inf` is
//! replaced by the lower bound `max_j (|A_jj| + row's unit entries)` (every row sum is at least
//! its diagonal), which makes the check at least as strict.
//!
//! This is the complementary solution of the same basis that Lemke's warm start computes from
//! the assembled `A` (the same `z` to round-off); the property tests compare the two.

use super::inputs::{StepInputs, dot2, dot3, normal_bias, sign};
use super::layout::{Direction, Layout, Tangents};
use crate::lcp::Basis;
use crate::lcp::elimination::solve_leading;
use crate::real::{AllFinite, Real, max, min};
use crate::slot::Slot;

/// The factored rows of one step's LCP (`docs/formulation.md`, "Solving a step"; the rows and
/// the elimination are written out in the docs of `core/src/planar/factored.rs`).
#[derive(Debug, Clone, Copy)]
pub struct FactoredLcp<T, const K: usize, const N: usize> {
    /// `c_j`, the wrench column of impulse variable `j` (zero for the `sigma`s and for an inactive
    /// contact's variables).
    pub(crate) col: [[T; 3]; N],
    /// `M^-1 c_j` per unit mass.
    pub(crate) mcol: [[T; 3]; N],
    /// `q_j`: eq. 18's right-hand side (0 for a `sigma`; 1 for an inactive contact's variables,
    /// whose rows are decoupled).
    pub(crate) q: [T; N],
    /// Each contact's friction coefficient for this step.
    pub(crate) mu: [T; K],
    /// The kept tangent directions.
    pub(crate) tangents: [Tangents; K],
    /// Bit `j` set: variable `j` belongs to an inactive contact.
    pub(crate) inactive: u32,
    /// Bit `j` of entry `i` set: variable `j` belongs to contact `i`.
    variables_of: [u32; K],
    /// `v~`.
    v_free: [T; 3],
    /// Bit `i` set: contact `i`'s cone row is weighted by [`cone_scale`] of its `mu`.
    pub(crate) cone_scaled: u32,
    /// A lower bound of `||A||_inf` from the structure ([`Self::new`]).
    m_low: T,
    /// `||q||_inf`.
    q_norm: T,
    /// `min_j q_j`.
    q_min: T,
    /// Every entry of `q` and of `M^-1 C` is finite.
    finite: bool,
}

/// A basis' complementary solution, verified ([`FactoredLcp::solve_basis`]).
#[derive(Debug, Clone, Copy)]
pub struct BasisAnswer<T, const N: usize> {
    /// `z` (per unit mass).
    pub z: [T; N],
    /// `v+ = v~ + dv`.
    pub v_plus: [T; 3],
    /// `w = A z + q`, computed in factored form.
    pub w: [T; N],
    /// The normalised verification residual.
    pub residual: T,
}

/// Why [`FactoredLcp::solve_basis`] gave no answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Declined {
    /// A pattern this path does not take: an inactive contact's variable basic, `sigma` basic
    /// with no or two friction rows, more unknowns than the body's three degrees of freedom.
    Pattern,
    /// The basis' system is numerically singular.
    Singular,
    /// The basis' solution is infeasible: variable `j`'s `z_j < 0`, or its `w_j < 0` outside the
    /// basis (the first such variable found).
    Infeasible(u8),
    /// The solution failed verification.
    Unverified,
}

/// A basis' unknowns ([`FactoredLcp::solve_basis_cached_into`]): what the elimination needs of
/// the basis alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(not(feature = "host-tuned"), allow(dead_code))] // the cache is the host's
pub(crate) struct Plan<const K: usize> {
    /// The variable each unknown sets (whose own row holds it).
    var: [usize; DOF],
    /// The friction row that follows each unknown at `mu` (a sliding contact's normal impulse;
    /// `N`: none).
    follower: [usize; DOF],
    /// How many unknowns.
    m: usize,
    /// The friction row that gives each contact's basic sigma.
    sigma_row: [Option<usize>; K],
}

/// The stepper's [`Plan`] of its last warm basis, with the basis' mask: with `host-tuned`
/// ([`FactoredLcp::solve_basis_cached_into`]).
#[cfg(feature = "host-tuned")]
pub(crate) type PlanCache<const K: usize> = Option<(u32, Plan<K>)>;

/// The stepper's [`Plan`] of its last warm basis: nothing without `host-tuned`.
#[cfg(not(feature = "host-tuned"))]
pub(crate) type PlanCache<const K: usize> = ();

/// At most this many unknowns: the body's degrees of freedom.
const DOF: usize = 3;

impl<T: Real, const K: usize, const N: usize> FactoredLcp<T, K, N> {
    /// The factored rows of `layout`'s LCP for the step `input` (the same numbers
    /// [`super::assemble::assemble_into`] writes into `A` and `q`).
    #[must_use]
    pub fn new(layout: &Layout<K, N>, input: &StepInputs<'_, T, K>) -> Self {
        let mut out = Self::empty(layout);
        out.refill_out_of_line(input);
        out
    }

    /// The rows of `layout` with every column and `q` zero, ready for [`Self::refill`].
    #[must_use]
    pub(crate) fn empty(layout: &Layout<K, N>) -> Self {
        let zero3 = [T::zero(); 3];
        let mut variables_of = [0; K];
        for (v, variable) in layout.variables().iter().enumerate() {
            if let Some(bits) = variables_of.get_mut(variable.contact()) {
                *bits |= 1 << v;
            }
        }
        Self {
            variables_of,
            col: [zero3; N],
            mcol: [zero3; N],
            q: [T::zero(); N],
            mu: [T::zero(); K],
            tangents: *layout.tangents(),
            inactive: 0,
            v_free: [T::zero(); 3],
            cone_scaled: 0,
            m_low: T::zero(),
            q_norm: T::zero(),
            q_min: T::zero(),
            finite: true,
        }
    }

    /// Replaces the rows with those of the step `input`, in place (the stepper keeps one
    /// `FactoredLcp` and refills it each step: no copy of the rows, no clearing). Every impulse
    /// row's column and `q` is written; the `sigma` rows' columns stay zero, as [`Self::empty`]
    /// made them.
    ///
    /// Inlined into its caller without `host-tuned` on a target with the hard-float ABI
    /// (`target_abi = "eabihf"`: the Cortex-M4F and M33F): the step of a model without the rule's
    /// steps (itself inlined into its caller; measured on the Cortex-M4F with the step's
    /// `impulses` inlined too, the slow scene's step 27 instructions fewer than with this call out
    /// of line). The other
    /// callers take [`Self::refill_out_of_line`]: a copy in each cost the Cortex-M0's build 32 kB
    /// of flash. With software floats the refill is mostly library calls and the copy does not
    /// pay: on the Cortex-M0 the slow scene's step is 317 instructions fewer without it, and its
    /// flash 13.6 kB smaller.
    #[cfg_attr(all(not(feature = "host-tuned"), target_abi = "eabihf"), inline(always))]
    #[allow(clippy::inline_always)] // measured, as said above
    pub(crate) fn refill(&mut self, input: &StepInputs<'_, T, K>) {
        let sigma_start = Layout::<K, N>::SIGMA_START;
        let zero3 = [T::zero(); 3];
        let out = self;
        out.mu = input.mu;
        out.inactive = 0;
        for v in sigma_start..N {
            out.q[v] = T::zero();
        }
        for i in 0..K {
            let f = &input.frames[i];
            out.col[i] = f.wn;
            out.q[i] = dot3(&f.wn, &input.v_free) - dot2(&f.normal(), &input.support_velocity[i])
                + normal_bias(f.gap, input.h, input.gravity, input.gap_round_off);
        }
        // Friction rows contact by contact, `+d` before `-d` (the running index is guarded).
        let mut j = K;
        for i in 0..K {
            let f = &input.frames[i];
            let g = dot3(&f.wt, &input.v_free) - dot2(&f.tangent(), &input.support_velocity[i]);
            for direction in [Direction::Plus, Direction::Minus] {
                if !out.tangents[i].keeps(direction) || j >= sigma_start {
                    continue;
                }
                let s = sign::<T>(direction);
                out.col[j] = [s * f.wt[0], s * f.wt[1], s * f.wt[2]];
                out.q[j] = s * g;
                j += 1;
            }
        }
        // Per unit mass the linear entries of `M^-1` are exactly 1 (`Body::inverse_mass_per_unit_mass`):
        // multiplying by them changes no bit, and on a core without an FPU each is a library call.
        let unit = input.m_inv[0] == T::one() && input.m_inv[1] == T::one();
        for j in 0..sigma_start {
            let c = &out.col[j];
            out.mcol[j] = if unit {
                [c[0], c[1], c[2] * input.m_inv[2]]
            } else {
                [c[0] * input.m_inv[0], c[1] * input.m_inv[1], c[2] * input.m_inv[2]]
            };
        }
        for i in 0..K {
            if !input.frames[i].active {
                out.inactive |= out.variables_of[i];
            }
        }
        if out.inactive != 0 {
            for v in 0..N {
                if (out.inactive >> v) & 1 == 1 {
                    out.col[v] = zero3;
                    out.mcol[v] = zero3;
                    out.q[v] = T::one();
                }
            }
        }
        // ||A||_inf from below, from the structure alone: an active contact's impulse rows have a
        // diagonal `c_j^T M^-1 c_j >= min(M^-1_xx, M^-1_yy)` (the linear part of `c_j` is a unit
        // vector), a friction row its sigma's 1 besides, a sigma row sums to `mu + kept
        // directions` exactly; an inactive contact's rows are the identity's.
        // A cone row with `mu >= MU_WEIGHTED_FROM` counts weighted by its `cone_scale`: its sum
        // is then `s (mu + kept directions)`, in `[1, 3)`.
        let linear = min(input.m_inv[0], input.m_inv[1]);
        let from = T::of(MU_WEIGHTED_FROM);
        let mut m_low = T::one();
        out.cone_scaled = 0;
        for i in 0..K {
            if (out.inactive >> i) & 1 == 0 {
                let mu = out.mu[i];
                let mut cone_row = mu + T::of_count(out.tangents[i].count() as u32);
                if mu >= from {
                    cone_row = out.weigh_cone_row(i, cone_row);
                }
                m_low = max(m_low, max(linear + T::one(), cone_row));
            }
        }
        // Finite data: `q` finite implies `c_j` finite (`q_j = c_j^T v~ + c0_j`, and an infinite
        // or NaN entry of `c_j` makes the dot product infinite or NaN, `0 inf` included), so of
        // `M^-1 c_j` only the products with `M^-1` remain to be checked: the angular one, and with
        // a non-unit linear `M^-1` the linear ones too.
        let (mut q_norm, mut q_min) = (T::zero(), out.q[0]);
        let mut finite = AllFinite::new();
        for v in 0..N {
            finite.add(out.q[v]);
            q_norm = max(q_norm, out.q[v].abs_exact());
            q_min = min(q_min, out.q[v]);
        }
        for j in 0..sigma_start {
            let c = &out.mcol[j];
            finite.add(c[2]);
            if !unit {
                finite.add(c[0]);
                finite.add(c[1]);
            }
        }
        out.m_low = m_low;
        out.q_norm = q_norm;
        out.q_min = q_min;
        out.finite = finite.holds();
        // Last: the step writes `input` just before this call, `v~` (in f32) as three 4-byte
        // stores, and this copy reads it as an 8-byte and a 4-byte load, which an x86 core cannot
        // forward from stores still in its store buffer: it waits for them to reach the cache.
        out.v_free = input.v_free;
    }

    /// [`Self::refill`] out of line: one copy for the callers off the determinate step's path.
    #[inline(never)]
    pub(crate) fn refill_out_of_line(&mut self, input: &StepInputs<'_, T, K>) {
        self.refill(input);
    }

    /// Weighs contact `i`'s cone row by [`cone_scale`] of its `mu` (sets its bit of `cone_scaled`
    /// and its `cone_scale`) and returns the weighted row's sum, `cone_row` (its sum unweighted)
    /// times the weight. Out of line: only a run at extreme friction comes here.
    #[cold]
    #[inline(never)]
    fn weigh_cone_row(&mut self, i: usize, cone_row: T) -> T {
        self.cone_scaled |= 1 << i;
        cone_scale(self.mu[i]) * cone_row
    }

    /// `true` when every entry of `q` and of the columns is finite; otherwise no path may answer
    /// (the stepper reports [`crate::lcp::LcpError::NonFiniteInput`], as Lemke's method does).
    #[must_use]
    pub const fn is_finite(&self) -> bool {
        self.finite
    }

    /// `true` when the data are finite and `q >= 0`, so that `z = 0` solves the LCP exactly
    /// (`w = q >= 0`, `z . w = 0`: the answer Lemke's method gives such a problem before any pivot).
    #[must_use]
    pub fn is_free(&self) -> bool {
        self.finite && self.q_min >= T::zero()
    }

    /// The kept tangent directions of each contact.
    #[must_use]
    pub const fn tangents(&self) -> &[Tangents; K] {
        &self.tangents
    }

    /// `q`.
    #[must_use]
    pub const fn q(&self) -> &[T; N] {
        &self.q
    }

    /// `v~`.
    #[must_use]
    pub const fn v_free(&self) -> &[T; 3] {
        &self.v_free
    }

    /// `v+ = v~ + M^-1 C p` for the impulses in `z` (eq. 16).
    #[must_use]
    #[cfg_attr(not(feature = "host-tuned"), inline(never))] // called from the fast path and Lemke's: one copy of flash
    pub fn velocity_after(&self, z: &[T; N]) -> [T; 3] {
        let dv = self.velocity_change(z);
        [self.v_free[0] + dv[0], self.v_free[1] + dv[1], self.v_free[2] + dv[2]]
    }

    /// `dv = M^-1 C p` for the impulses in `z`, summed on its own (not `v+ - v~`, which would
    /// lose `eps |v~|` when the body moves fast and the impulses change it little).
    // Inlined with `host-tuned`: called, it reads `z` (in f32) as 8-byte pairs of values just
    // written one by one, which an x86 core cannot forward from its store buffer. Otherwise out
    // of line: one copy (flash).
    #[cfg_attr(not(feature = "host-tuned"), inline(never))]
    #[cfg_attr(feature = "host-tuned", inline(always))]
    #[allow(clippy::inline_always)] // measured, as said above
    fn velocity_change(&self, z: &[T; N]) -> [T; 3] {
        let mut dv = [T::zero(); 3];
        for j in 0..Layout::<K, N>::SIGMA_START {
            let (c, zj) = (&self.mcol[j], z[j]);
            for k in 0..3 {
                dv[k] += c[k] * zj;
            }
        }
        dv
    }

    /// The complementary solution of `basis`, computed in the body's coordinates and verified
    /// within `tolerance` (`docs/formulation.md`, "Solving a step"), or why there is none
    /// ([`Declined`]). Never a solution that failed.
    ///
    /// # Errors
    /// [`Declined`]: a pattern this path does not take, a singular system, an infeasible basis
    /// (`z < 0`, or `w < 0` outside it), an answer that fails verification.
    pub fn solve_basis(&self, basis: Basis<N>, tolerance: T) -> Result<BasisAnswer<T, N>, Declined> {
        let (mut z, mut w) = ([T::zero(); N], [T::zero(); N]);
        let (v_plus, residual) = self.solve_basis_into(basis, tolerance, &mut z, &mut w)?;
        Ok(BasisAnswer { z, v_plus, w, residual })
    }

    /// [`Self::solve_basis`] writing `z` and `w` into the caller's arrays (their contents are
    /// unspecified when it fails); returns `v+` and the residual.
    pub(crate) fn solve_basis_into(
        &self,
        basis: Basis<N>,
        tolerance: T,
        z: &mut [T; N],
        w: &mut [T; N],
    ) -> Result<([T; 3], T), Declined> {
        self.solve_basis_with(
            basis,
            #[cfg(feature = "host-tuned")]
            None,
            tolerance,
            z,
            w,
        )
    }

    /// [`Self::solve_basis_into`] with the basis' [`Plan`] kept in `cache` from the last call with
    /// the same basis (the stepper's warm basis is usually the previous step's: its unknowns need
    /// not be found again). Same answer, same bits. With `host-tuned` only: on a Cortex-M4F it
    /// cost more than it saved, so without it `cache` is `()`.
    pub(crate) fn solve_basis_cached_into(
        &self,
        basis: Basis<N>,
        cache: &mut PlanCache<K>,
        tolerance: T,
        z: &mut [T; N],
        w: &mut [T; N],
    ) -> Result<([T; 3], T), Declined> {
        #[cfg(not(feature = "host-tuned"))]
        let () = *cache;
        #[cfg(not(feature = "host-tuned"))]
        return self.solve_basis_into(basis, tolerance, z, w);
        #[cfg(feature = "host-tuned")]
        return self.solve_basis_with(basis, Some(cache), tolerance, z, w);
    }

    /// [`Self::solve_basis_into`], with the basis' unknowns taken from `cache` when it holds them
    /// (and put there when it does not). With `host-tuned` inlined into both callers (without a
    /// cache, `None` is a constant there); without it there is no cache and this is the plain
    /// solve (a split into a search and a solve costs a Cortex-M4F time or flash).
    #[cfg_attr(feature = "host-tuned", inline(always))]
    #[allow(clippy::inline_always, clippy::too_many_lines)] // the module docs' elimination, solve and checks, in order
    fn solve_basis_with(
        &self,
        basis: Basis<N>,
        #[cfg(feature = "host-tuned")] cache: Option<&mut Option<(u32, Plan<K>)>>,
        tolerance: T,
        z: &mut [T; N],
        w: &mut [T; N],
    ) -> Result<([T; 3], T), Declined> {
        let mask = basis.z_mask();
        if mask & self.inactive != 0 {
            return Err(Declined::Pattern); // an inactive contact's decoupled rows have z = 0
        }
        let basic = |v: usize| (mask >> v) & 1 == 1;
        let sigma_start = Layout::<K, N>::SIGMA_START;
        // The unknowns: the variable each sets (whose own row holds it) and the friction row that
        // follows it at `mu` (a sliding contact's normal impulse; `N`: none).
        let mut var = [0usize; DOF];
        let mut follower = [N; DOF];
        let mut m = 0usize;
        // The friction row that gives each contact's basic sigma.
        let mut sigma_row: [Option<usize>; K] = [None; K];
        // From the cache when it holds this basis (`m` clamped as the search below clamps it).
        #[cfg(feature = "host-tuned")]
        let found = match &cache {
            Some(Some((key, plan))) if *key == mask => {
                (var, follower, m, sigma_row) = (plan.var, plan.follower, plan.m.min(DOF), plan.sigma_row);
                true
            }
            _ => false,
        };
        #[cfg(not(feature = "host-tuned"))]
        let found = false;
        if !found {
            let mut j = K;
            for i in 0..K {
                let kept = self.tangents[i].count();
                let (first, last) = (j, (j + kept).min(sigma_start));
                j = last;
                let mut frictions = 0;
                let mut friction = first;
                for f in first..last {
                    if basic(f) {
                        frictions += 1;
                        friction = f;
                    }
                }
                if basic(sigma_start + i) {
                    if frictions != 1 {
                        return Err(Declined::Pattern);
                    }
                    sigma_row[i] = Some(friction);
                    if basic(i) {
                        if m >= DOF {
                            return Err(Declined::Pattern);
                        }
                        var[m] = i;
                        follower[m] = friction;
                        m += 1;
                    }
                    continue;
                }
                for v in core::iter::once(i).chain(first..last) {
                    if basic(v) {
                        if m >= DOF {
                            return Err(Declined::Pattern);
                        }
                        var[m] = v;
                        m += 1;
                    }
                }
            }
            #[cfg(feature = "host-tuned")]
            if let Some(cache) = cache {
                *cache = Some((mask, Plan { var, follower, m, sigma_row }));
            }
        }
        // With `host-tuned` each number of unknowns the warm path meets gets its own copy of the
        // rest, with `m` a constant: its loops unrolled, the same operations in the same order (the
        // same bits). Without it one copy (flash, module size).
        #[cfg(feature = "host-tuned")]
        match m {
            3 => return self.solve_unknowns(mask, &var, &follower, 3, &sigma_row, tolerance, z, w),
            2 => return self.solve_unknowns(mask, &var, &follower, 2, &sigma_row, tolerance, z, w),
            _ => {}
        }
        self.solve_unknowns(mask, &var, &follower, m, &sigma_row, tolerance, z, w)
    }

    /// [`Self::solve_basis_with`] once the basis' unknowns are known: the elimination, `z`, `w`
    /// and the checks. Inlined where it is called, so that a constant `m` specialises it.
    #[inline(always)]
    #[allow(clippy::inline_always, clippy::too_many_arguments)] // the point of it: `m` known at the call
    fn solve_unknowns(
        &self,
        mask: u32,
        var: &[usize; DOF],
        follower: &[usize; DOF],
        m: usize,
        sigma_row: &[Option<usize>; K],
        tolerance: T,
        z: &mut [T; N],
        w: &mut [T; N],
    ) -> Result<([T; 3], T), Declined> {
        let basic = |v: usize| (mask >> v) & 1 == 1;
        let sigma_start = Layout::<K, N>::SIGMA_START;
        // H^T M^-1 G y = -q_H.
        // Unknown `l`'s column `M^-1 G` (formed where it is used: nothing to clear or store).
        let gm = |l: usize| {
            let mn = &self.mcol[var[l].min(N - 1)];
            if follower[l] < N {
                let (mf, mu) = (&self.mcol[follower[l]], self.mu[var[l].min(K - 1)]);
                [mn[0] + mu * mf[0], mn[1] + mu * mf[1], mn[2] + mu * mf[2]]
            } else {
                *mn
            }
        };
        let mut a = [[T::zero(); DOF]; DOF];
        let mut y = [T::zero(); DOF];
        for l in 0..m {
            let g = gm(l);
            for k in 0..m {
                a[k][l] = dot3(&self.col[var[k].min(N - 1)], &g);
            }
        }
        for k in 0..m {
            y[k] = -self.q[var[k].min(N - 1)];
        }
        let tiny = T::of(N as f64) * T::EPS * self.m_low;
        #[cfg(feature = "host-tuned")]
        let solved = solve_leading(&mut a, &mut y, m, tiny);
        #[cfg(not(feature = "host-tuned"))]
        let solved = solve_small(&mut a, &mut y, m, tiny);
        if !solved {
            return Err(Declined::Singular);
        }
        // An impulse is held to `>= 0` exactly; one that is positive but within the round-off of
        // the step's impulses (`N eps` of the largest) is the round-off of a zero: the basis is
        // degenerate, and the one without it (the contact off, an exact zero) is the answer that
        // injects no noise (a rod balanced on a finger under its centre of mass, the other finger
        // touching without load, is tipped over by such an impulse; `docs/formulation.md`).
        let mut y_max = T::zero();
        for k in 0..m {
            y_max = max(y_max, y[k]);
        }
        let impulse_round_off = T::of(N as f64) * T::EPS * y_max;
        *z = [T::zero(); N];
        for k in 0..m {
            if y[k] < T::zero() || (y[k] > T::zero() && y[k] <= impulse_round_off) {
                return Err(Declined::Infeasible(var[k] as u8));
            }
            z[var[k].min(N - 1)] = y[k];
            if follower[k] < N {
                z[follower[k]] = self.mu[var[k].min(K - 1)] * y[k];
            }
        }
        // dv recomputed from z, then each basic sigma from its friction row.
        let dv = self.velocity_change(z);
        let v_plus = [self.v_free[0] + dv[0], self.v_free[1] + dv[1], self.v_free[2] + dv[2]];
        // A velocity (a normal or friction row's w, a sigma) within the round-off of the rows it
        // comes from, `N eps (||A|| ||p|| + ||q||)`, is zero: a sticking contact has both friction
        // rows at zero slip (one basic, one not), and a contact held at its cone's edge without
        // slipping (the rod resting on two sticking fingers) has a zero sigma; computed, either is
        // of either sign by chance. The impulses and the cone rows (on the impulses' own scale,
        // far below the velocities' when `V >> g h`) are held to `>= 0` exactly.
        let mut p_norm = T::zero();
        for v in 0..sigma_start {
            p_norm = max(p_norm, z[v]);
        }
        let speed_round_off = T::of(N as f64) * T::EPS * (self.m_low * p_norm + self.q_norm);
        for i in 0..K {
            if let Some(f) = sigma_row[i] {
                let f = f.min(N - 1);
                let sigma = -(self.q[f] + dot3(&self.col[f], &dv));
                if sigma < -speed_round_off {
                    return Err(Declined::Infeasible((sigma_start + i) as u8));
                }
                z[(sigma_start + i).min(N - 1)] = max(sigma, T::zero());
            }
        }
        self.w_of(z, &dv, w);
        // Feasibility outside the basis, and the verification residual of `crate::lcp::verify`
        // bounded without a division per row: with `z >= 0` (held above), a row's residual is at
        // most `|w_j| / s_w` in the basis and `max(-w_j, 0) / s_w` outside it (`z_j = 0`), with
        // `s_w = ||A|| ||z|| + ||q||` (here `||A||`'s lower bound: a smaller scale, a stricter
        // test).
        // The impulse rows' `w_j = q_j + c_j^T dv (+ sigma)` are finite only if `dv` is, and `dv`
        // only if every basic impulse is (each acts through a non-zero column: an infinity or a
        // NaN in it reaches every row, `0 inf` too); the sigmas and the cone rows follow from
        // those. So their finiteness is the answer's.
        let mut violation = T::zero();
        let mut z_norm = p_norm;
        for v in sigma_start..N {
            z_norm = max(z_norm, z[v]);
        }
        let mut finite = AllFinite::new();
        for v in 0..N {
            let wv = w[v];
            if v < sigma_start {
                finite.add(wv);
            }
            if basic(v) {
                violation = max(violation, wv.abs_exact());
            } else {
                let floor = if v < sigma_start { -speed_round_off } else { T::zero() };
                if wv < floor {
                    return Err(Declined::Infeasible(v as u8));
                }
                violation = max(violation, -wv);
            }
        }
        // A scale beyond the scalar's range would make every violation read as 0: unverifiable.
        let s_w = max(self.m_low * z_norm + self.q_norm, T::TINY);
        finite.add(s_w);
        if !finite.holds() || violation > tolerance * s_w {
            return Err(Declined::Unverified);
        }
        Ok((v_plus, violation / s_w))
    }

    /// `w = A z + q` of the model's LCP (its cone rows unweighted) for `z`, in factored form.
    pub(crate) fn w_into(&self, z: &[T; N], w: &mut [T; N]) {
        self.w_of(z, &self.velocity_change(z), w);
    }

    /// `w = A z + q` in factored form, with `dv = M^-1 C p` of the same `z`.
    #[cfg_attr(not(feature = "host-tuned"), inline(never))]
    fn w_of(&self, z: &[T; N], dv: &[T; 3], w: &mut [T; N]) {
        let sigma_start = Layout::<K, N>::SIGMA_START;
        for v in 0..sigma_start {
            w[v] = self.q[v] + dot3(&self.col[v], dv);
        }
        let mut j = K;
        for i in 0..K {
            let s = sigma_start + i;
            let inactive = (self.inactive >> i) & 1 == 1;
            let sigma = z[s];
            let mut cone = self.mu[i] * z[i];
            let end = (j + self.tangents[i].count()).min(sigma_start);
            for f in j..end {
                w[f] += sigma;
                cone -= z[f];
            }
            j = end;
            // An inactive contact's rows are the identity's: w = z + 1.
            w[s] = if inactive { self.q[s] + sigma } else { cone };
            if inactive {
                w[i] += z[i];
            }
        }
    }

    /// Each contact's slip after the step whose answer is `z`, `w`: the support's velocity along
    /// `d` relative to the body's contact point, `d . (u - v_P) = -(W_d^T v+ - d . u)`, read from
    /// the contact's first kept friction row (`w_f = s (W_d^T v+ - d . u) + sigma`) instead of
    /// being computed again. Meaningless for an inactive contact (its rows are decoupled).
    #[must_use]
    pub fn slips(&self, z: &[T], w: &[T]) -> [T; K] {
        let mut slips = [T::zero(); K];
        for i in 0..K {
            let slot = slot_of::<K, N>(&self.tangents, i);
            let s = slot.sigma();
            let (row, sign) = match slot.friction() {
                [Some(f), _] => (f, T::one()),
                [None, Some(f)] => (f, -T::one()),
                [None, None] => continue,
            };
            if let (Some(&wf), Some(&sigma)) = (w.get(row), z.get(s)) {
                slips[i] = -(sign * (wf - sigma));
            }
        }
        slips
    }
}

/// The friction coefficient from which a contact's cone row `mu p_n - sum p_f >= 0` is weighted
/// ([`cone_scale`]): 64, in either precision. Every other row of the LCP sums to at most about 3 (a
/// velocity row: its `c_j^T M^-1 c_k` of a unit-speed column and its sigma's 1; per unit mass), so
/// from 64 on the cone row's `mu` sets `||A||_inf` more than 20 times above them, and with it every
/// round-off floor, pivot tolerance and verification scale of the step (`docs/formulation.md`,
/// "Precision"). Measured: unweighted, f32 misses f64's outcome on the meter stick from `mu = 1e3`
/// and f64 fails it at 1,783 (a Lemke ray at the meeting); weighted, both balance. Below it (every
/// built-in scene's default, `mu <= 3`) nothing changes, not a bit. A power of two: `2^6`.
pub(crate) const MU_WEIGHTED_FROM: f64 = 64.0;

/// The weight of a cone row with friction coefficient `mu >= 1`: `s = 2^-k` with `2^k <= mu <
/// 2^(k+1)`, so that the weighted row `s mu p_n - s sum p_f >= 0` has entries `s mu` in `[1, 2)`
/// and `-s`. A power of two: every weighted entry and every product with it is exact (the weighted
/// LCP has the same solutions and, row for row, `w` times `s` to the bit; `docs/formulation.md`,
/// "Precision").
#[must_use]
pub(crate) fn cone_scale<T: Real>(mu: T) -> T {
    T::one() / mu.power_of_two_below()
}

/// Contact `i`'s [`Slot`]: its normal, its friction rows `[+d, -d]` (as kept) and its sigma
/// (in the full layout, `crate::slot::full_rows(K, i)`).
pub(crate) fn slot_of<const K: usize, const N: usize>(tangents: &[Tangents; K], i: usize) -> Slot {
    let mut j = K;
    for k in 0..i.min(K) {
        j += tangents[k].count();
    }
    let t = tangents.get(i).copied().unwrap_or(Tangents::Both);
    let plus = t.keeps(Direction::Plus).then_some(j);
    let minus = t.keeps(Direction::Minus).then_some(j + usize::from(plus.is_some()));
    Slot::new(i, [plus, minus], Layout::<K, N>::SIGMA_START + i)
}

/// The basis' `m x m` system by [`solve_leading`], in one copy out of line (flash): without
/// `host-tuned`. With it, [`solve_leading`] is inlined into each copy of
/// [`FactoredLcp::solve_unknowns`], with `m` a constant.
#[cfg(not(feature = "host-tuned"))]
#[inline(never)]
fn solve_small<T: Real>(a: &mut [[T; DOF]; DOF], rhs: &mut [T; DOF], m: usize, tiny: T) -> bool {
    solve_leading(a, rhs, m, tiny)
}

#[cfg(test)]
mod tests {
    use super::{MU_WEIGHTED_FROM, cone_scale};
    use crate::real::Real;

    /// The weighting starts at `2^6`, above every built-in default (`mu <= 3`), and a power of two.
    #[test]
    fn weighting_starts_at_64() {
        assert!((MU_WEIGHTED_FROM - 64.0).abs() < f64::EPSILON);
        assert_eq!(MU_WEIGHTED_FROM.to_bits() & ((1 << 52) - 1), 0);
    }

    /// A cone row's weight is a power of two that brings `mu` into `[1, 2)`, exactly.
    #[test]
    fn a_cone_rows_weight_is_the_power_of_two_below_one_over_mu() {
        fn check<T: Real>(mu: f64) {
            let mu = T::of(mu);
            let s = cone_scale(mu);
            assert_eq!(s * s.power_of_two_below(), s * s, "{s:?} is a power of two");
            let weighted = s * mu;
            assert!(weighted >= T::one() && weighted < T::one() + T::one(), "mu {mu:?}: s mu = {weighted:?}");
            // Exact: weighing and unweighing give back the same bits.
            assert_eq!(weighted * mu.power_of_two_below(), mu);
        }
        for mu in [64.0, 100.0, 1e3, 1e4, 16384.0, 3e4, 1e5, 1e6, 1e30] {
            check::<f32>(mu);
            check::<f64>(mu);
        }
    }
}
