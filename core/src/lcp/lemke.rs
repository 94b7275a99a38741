//! [`Lemke`]: Lemke's complementary pivoting with a lexicographic ratio test, statically
//! sized, no heap, no panics. The algorithm is described in the [module docs](super).

use nalgebra::SVector;

use super::basis::Basis;
use super::elimination::solve_leading;
use super::error::LcpError;
use super::problem::{Lcp, Scales};
use super::tableau::Tableau;
use super::verify::{Verification, default_tolerance};
use crate::real::{Real, max};

/// A verified solution of an LCP (`WORDS`: its basis', as the solver's, [`Lemke`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use]
pub struct LcpSolution<T: Real, const N: usize, const WORDS: usize = 1> {
    /// `z >= 0`.
    pub z: SVector<T, N>,
    /// `w = M z + q >= 0`, recomputed from the original data.
    pub w: SVector<T, N>,
    /// Complementary pivots performed after the artificial variable entered (its entry is
    /// not counted, as in Murty's `2^n - 1`); 0 when `q >= 0` or the warm basis was feasible.
    pub pivots: u32,
    /// Gauss-Jordan eliminations spent setting up a warm-start basis (0 for a cold start).
    pub setup_eliminations: u32,
    /// `true` when the returned solution came from the warm-start basis.
    pub warm_start_used: bool,
    /// The terminal complementary basis; pass it to [`Lemke::solve_warm`] next time.
    pub basis: Basis<N, WORDS>,
    /// Normalised verification residual (see [`super::verify`]).
    pub residual: T,
    /// The scale the residual divided `w` by, `||M||_inf ||z||_inf + ||q||_inf` (`||q||_inf`
    /// alone for a [`Self::regularized`] answer): what `w`'s entries are summed from, so that
    /// `residual * scale` bounds the violation of `w >= 0` and of complementarity in `w`'s units.
    pub scale: T,
    /// `true` when the answer came from the regularised retry after a ray termination
    /// ([`Lemke::solve_warm`]); it is verified against the original `(M, q)` all the same.
    pub regularized: bool,
}

/// Lemke's method for LCPs of size `N` in scalar `T`, with its pivot cap and verification
/// tolerance. Its bases ([`Basis<N, WORDS>`]) and its ties are sets of rows in `WORDS` 32-bit
/// words: 1 (the default) for `N <= 32`, 2 for `N <= 64` (checked at compile time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lemke<T: Real, const N: usize, const WORDS: usize = 1> {
    max_pivots: u32,
    tolerance: T,
    pivot_floor: T,
}

impl<T: Real, const N: usize, const WORDS: usize> Default for Lemke<T, N, WORDS> {
    fn default() -> Self {
        Self::new()
    }
}

/// The default pivot floor, `N eps`: the ratio test pivots only on a column's entries above it
/// times the column's largest ([`Lemke::with_pivot_floor`]).
#[must_use]
pub fn default_pivot_floor<T: Real, const N: usize>() -> T {
    T::of(N as f64) * T::EPS
}

/// The default pivot cap: `2^min(N, 10) + 4 N`.
///
/// Lemke's method can need `2^N - 1` pivots (Murty's example); the cap allows that up to
/// `N = 10` and grows linearly beyond. `N = 6`: 88, `N = 8`: 288, `N = 16`: 1088.
#[must_use]
pub const fn default_max_pivots(n: usize) -> u32 {
    let exp = if n < 10 { n } else { 10 };
    (1u32 << exp) + 4 * n as u32
}

/// The complementary solution of basis `warm` (set `a` of basic `z`): `M_aa z_a = -q_a`,
/// `z = 0` elsewhere, by Gaussian elimination with partial pivoting (`|a|^3 / 3`
/// multiply-adds, [`solve_leading`]). `Some(z)` only when `z_a >= 0` as computed (no tolerance:
/// a basis that is infeasible by round-off goes through Lemke's lexicographic pivoting instead,
/// so switches are not delayed); `None` when `M_aa` is numerically singular (a pivot at most
/// `N eps scale`) or `z_a` has a negative entry. The caller checks the other half of
/// feasibility, `w >= 0` outside `a`, on the `w` it verifies with.
///
/// `M_aa` and `-q_a` are gathered, the basis' indices in increasing order, into the leading
/// `|a| x |a|` block of a local array (moves only: the floating-point work is exactly that of
/// the `|a| x |a|` system, which matters on a Cortex-M0, where every float operation, compares
/// included, is a library call). Every loop has the constant bound `N`, each index is clamped
/// below `N`: no panic path.
fn basis_solution<T: Real, const N: usize, const WORDS: usize>(
    lcp: &Lcp<T, N>,
    warm: Basis<N, WORDS>,
    scale: T,
) -> Option<SVector<T, N>> {
    let set = warm.z_rows();
    let mut index = [0usize; N];
    let mut m = 0usize;
    for i in 0..N {
        if set.contains(i)
            && let Some(slot) = index.get_mut(m)
        {
            *slot = i;
            m += 1;
        }
    }
    let mut a = [[T::zero(); N]; N];
    let mut x = [T::zero(); N];
    for k in 0..N {
        if k >= m {
            break;
        }
        let row = index[k].min(N - 1);
        for l in 0..N {
            if l >= m {
                break;
            }
            a[k][l] = lcp.m[(row, index[l].min(N - 1))];
        }
        x[k] = -lcp.q[row];
    }
    let tiny = T::of(N as f64) * T::EPS * scale;
    if !solve_leading(&mut a, &mut x, m, tiny) {
        return None;
    }
    let mut z = SVector::<T, N>::zeros();
    for k in 0..N {
        if k >= m {
            break;
        }
        if x[k] < T::zero() {
            return None;
        }
        z[index[k].min(N - 1)] = x[k];
    }
    Some(z)
}

impl<T: Real, const N: usize, const WORDS: usize> Lemke<T, N, WORDS> {
    const SIZE_CHECK: () = assert!(
        N > 0 && N <= 64 && (WORDS == 1 || WORDS == 2) && N <= 32 * WORDS,
        "Lemke<T, N, WORDS> needs 1 <= N <= 64 and N <= 32 WORDS, WORDS 1 or 2"
    );

    /// A solver with the default pivot cap ([`default_max_pivots`]) and verification
    /// tolerance ([`default_tolerance`]).
    #[must_use]
    pub fn new() -> Self {
        let () = Self::SIZE_CHECK;
        Self {
            max_pivots: default_max_pivots(N),
            tolerance: default_tolerance::<T, N>(),
            pivot_floor: default_pivot_floor::<T, N>(),
        }
    }

    /// Sets the pivot cap (at least 1).
    #[must_use]
    pub fn with_max_pivots(mut self, max_pivots: u32) -> Self {
        self.max_pivots = max_pivots.max(1);
        self
    }

    /// Sets the verification tolerance on the normalised residual.
    #[must_use]
    pub fn with_tolerance(mut self, tolerance: T) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Sets the pivot floor: the ratio test pivots only on a column's entries above `floor`
    /// times the column's largest (clamped to at least the default, [`default_pivot_floor`]).
    #[must_use]
    pub fn with_pivot_floor(mut self, floor: T) -> Self {
        self.pivot_floor = max(floor, default_pivot_floor::<T, N>());
        self
    }

    /// This solver with single precision's pivot floor, `N 2^-23` (the default of `f32`), where
    /// that is coarser than `T`'s default: `None` in `f32`, which has it already.
    ///
    /// For a caller that retries a problem Lemke's method failed on with singular bases on its
    /// path (the spatial stepper's open loads, `crate::spatial`): there, in `f64`, the round-off
    /// of the pivots grows past `N eps` on entries that are zero in exact arithmetic, the ratio
    /// test pivots on them and the run ends in a ray; `f32`'s floor keeps them out (`host-sim
    /// scene --scene stack-3d --overhang 1.1 --precision f64`, docs/scenes.md). Not the default:
    /// on other paths the finer pivots are needed (its answers are verified all the same).
    #[must_use]
    pub fn single_precision_floor(&self) -> Option<Self> {
        let floor = T::of(N as f64 * f64::from(f32::EPSILON));
        (floor > default_pivot_floor::<T, N>()).then(|| self.with_pivot_floor(max(floor, self.pivot_floor)))
    }

    /// The pivot floor ([`Self::with_pivot_floor`]).
    #[must_use]
    pub const fn pivot_floor(&self) -> T {
        self.pivot_floor
    }

    /// The pivot cap.
    #[must_use]
    pub const fn max_pivots(&self) -> u32 {
        self.max_pivots
    }

    /// The verification tolerance.
    #[must_use]
    pub const fn tolerance(&self) -> T {
        self.tolerance
    }

    /// Solves `lcp` from the trivial basis (cold start).
    ///
    /// # Errors
    /// [`LcpError::NonFiniteInput`], [`LcpError::Ray`], [`LcpError::MaxPivots`] or
    /// [`LcpError::Unverified`]; never a solution that failed verification.
    pub fn solve(&self, lcp: &Lcp<T, N>) -> Result<LcpSolution<T, N, WORDS>, LcpError> {
        self.solve_warm(lcp, Basis::all_w())
    }

    /// Solves `lcp`, trying the complementary basis `warm` (e.g. the previous time step's
    /// [`LcpSolution::basis`]) first. When that basis is still feasible the solve takes no
    /// pivot; otherwise Lemke's method runs from it, and if that fails, from the cold start.
    /// [`LcpSolution::warm_start_used`] tells which one produced the answer; the reported
    /// pivots are the total spent.
    ///
    /// # Errors
    /// As [`Lemke::solve`].
    pub fn solve_warm(
        &self,
        lcp: &Lcp<T, N>,
        warm: Basis<N, WORDS>,
    ) -> Result<LcpSolution<T, N, WORDS>, LcpError> {
        self.solve_warm_inner(lcp, warm, true)
    }

    /// `z`, the complementary solution of the basis `basis` (`z_i = 0` where `w_i` is basic, `w_i
    /// = 0` meant where `z_i` is) that a caller computed its own way, accepted on
    /// [`Self::solve_warm`]'s terms for its warm basis' answer: `z >= 0` and `w = M z + q >= 0`
    /// outside the basis as computed, and the normalised residual ([`super::verify`]) within the
    /// tolerance. The exception is the `slack` a caller grants a row outside the basis: its `w_i`
    /// may be as low as `-slack(i)` (zero: none; infinite: held to the residual alone, as Lemke's
    /// pivoting holds every `w`), for rows whose `w` its problem's structure makes zero in exact
    /// arithmetic, their sign round-off's, and that it knows the size of that round-off for. For
    /// a caller that knows its problem's structure (the spatial stepper solves a basis in its
    /// contacts' few unknowns, `crate::spatial`); on `None` it goes on with
    /// [`Self::solve_from_basis`]. The answer has no pivots and [`LcpSolution::warm_start_used`].
    #[must_use]
    pub fn accept(
        &self,
        lcp: &Lcp<T, N>,
        z: &SVector<T, N>,
        basis: Basis<N, WORDS>,
        slack: impl Fn(usize) -> T,
    ) -> Option<LcpSolution<T, N, WORDS>> {
        self.accept_with_w(&lcp.scales()?, z, lcp.w_of(z), basis, slack).ok()
    }

    /// [`Self::accept`] with `w = M z + q` computed by the caller, on `scales` computed once by a
    /// caller that tries several bases of one problem, whose `m_norm` may be a lower bound of
    /// `||M||_inf` (the check is then at least as strict: the spatial stepper's one body bounds
    /// it from its contacts' own blocks, a pass over `M` fewer a try); a refused `z`'s `w` is
    /// the error, for the caller's next try.
    pub(crate) fn accept_with_w(
        &self,
        scales: &Scales<T>,
        z: &SVector<T, N>,
        w: SVector<T, N>,
        basis: Basis<N, WORDS>,
        slack: impl Fn(usize) -> T,
    ) -> Result<LcpSolution<T, N, WORDS>, SVector<T, N>> {
        let mut feasible = true;
        for i in 0..N {
            feasible &= z[i] >= T::zero() && (basis.is_z_basic(i) || w[i] >= T::zero() || w[i] >= -slack(i));
        }
        let check = Verification::of(z, &w, (scales.m_norm, scales.q_norm), self.tolerance);
        if !(feasible && check.passed()) {
            return Err(w);
        }
        Ok(LcpSolution {
            z: *z,
            w,
            pivots: 0,
            setup_eliminations: 0,
            warm_start_used: true,
            basis,
            residual: check.residual,
            scale: check.scale,
            regularized: false,
        })
    }

    /// The basis Lemke's method ends in on `lcp` from `warm`'s tableau (the cold start's for the
    /// trivial basis), whether or not its answer verifies: for a caller that solves that basis'
    /// own system its own way and then verifies the answer ([`Self::accept`]; the spatial
    /// stepper's open loads, whose singular bases Lemke's tableau crosses with too much round-off
    /// to verify, `crate::spatial`). `None` on a ray, at the pivot cap, for a singular `warm` or
    /// for data that are not finite.
    #[must_use]
    pub fn terminal_basis(&self, lcp: &Lcp<T, N>, warm: Basis<N, WORDS>) -> Option<Basis<N, WORDS>> {
        let () = Self::SIZE_CHECK;
        let scales = lcp.scales()?;
        let mut tab = Tableau::cold(lcp);
        if warm != Basis::all_w() {
            tab.warm(warm, max(scales.m_norm, T::TINY))?;
        }
        tab.run(self.max_pivots, self.pivot_floor).ok()?;
        Some(tab.solution(lcp).1)
    }

    /// [`Self::solve_warm`] without its first step, the direct solve of `warm`'s own complementary
    /// solution: for a caller that has just tried that basis itself (the planar stepper solves it
    /// in the body's coordinates, `crate::planar::FactoredLcp`). Lemke's method runs from `warm`'s
    /// tableau, then from the cold start, as in [`Self::solve_warm`]; the guarantees are the same.
    ///
    /// # Errors
    /// As [`Lemke::solve`].
    pub fn solve_from_basis(
        &self,
        lcp: &Lcp<T, N>,
        warm: Basis<N, WORDS>,
    ) -> Result<LcpSolution<T, N, WORDS>, LcpError> {
        self.solve_warm_inner(lcp, warm, false)
    }

    fn solve_warm_inner(
        &self,
        lcp: &Lcp<T, N>,
        warm: Basis<N, WORDS>,
        direct: bool,
    ) -> Result<LcpSolution<T, N, WORDS>, LcpError> {
        let () = Self::SIZE_CHECK;
        let Some(scales) = lcp.scales() else {
            return Err(LcpError::NonFiniteInput);
        };
        if scales.q_min >= T::zero() {
            return Ok(LcpSolution {
                z: SVector::zeros(),
                w: lcp.q,
                pivots: 0,
                setup_eliminations: 0,
                warm_start_used: false,
                basis: Basis::all_w(),
                residual: T::zero(),
                scale: scales.q_norm,
                regularized: false,
            });
        }
        let mut spent = 0;
        let mut eliminations = 0;
        if warm != Basis::all_w() {
            let scale = max(scales.m_norm, T::TINY);
            // Fast path: the warm basis solved directly, kept only when strictly feasible
            // (`z_a >= 0` there, `w >= 0` outside `a` here) and verified.
            if let Some(z) = direct.then(|| basis_solution(lcp, warm, scale)).flatten() {
                let w = lcp.w_of(&z);
                let mut feasible = true;
                for i in 0..N {
                    feasible &= warm.is_z_basic(i) || w[i] >= T::zero();
                }
                let check = Verification::of(&z, &w, (scales.m_norm, scales.q_norm), self.tolerance);
                if feasible && check.passed() {
                    return Ok(LcpSolution {
                        z,
                        w,
                        pivots: 0,
                        setup_eliminations: warm.z_count(),
                        warm_start_used: true,
                        basis: warm,
                        residual: check.residual,
                        scale: check.scale,
                        regularized: false,
                    });
                }
            }
            match self.run_from_tableau(lcp, &scales, warm, scale) {
                Ok(sol) => return Ok(sol),
                Err((pivots, elim)) => (spent, eliminations) = (pivots, elim),
            }
        }
        let mut tab = Tableau::cold(lcp);
        let budget = self.max_pivots.saturating_sub(spent).max(1);
        match tab.run(budget, self.pivot_floor) {
            Ok(pivots) => return self.finish(lcp, &scales, &tab, spent + pivots, eliminations, false, false),
            Err(LcpError::Ray { pivots }) => spent += pivots,
            Err(LcpError::MaxPivots { pivots }) => {
                return Err(LcpError::MaxPivots { pivots: spent + pivots });
            }
            Err(e) => return Err(e),
        }
        // A ray on a degenerate problem can be round-off: with nearly parallel columns (the
        // two fingers' friction directions have the same lever arm `t/2` on a level rod) a
        // column entry that is positive in exact arithmetic computes as zero, although a
        // solution exists (found by `host-sim stress` at mu = 10, in f64 too). One retry on
        // `M + delta I`, `delta = 4 N eps ||M||_inf`: for copositive `M` (the friction LCP)
        // that is strictly copositive, which Lemke's method always processes. An infeasible
        // LCP becomes feasible that way, with `z ~ 1/delta` (the corpus's CPS_3 got
        // z = 3e12 in f64): its `w < 0` is invisible to the backward-error residual, which
        // is relative to `||M|| ||z||`. So this answer is verified against the original
        // `(M, q)` on the data's own scale, `s_w = ||q||_inf` ([`Self::finish`]): `delta z`
        // then costs about `4 N eps ||M|| ||z|| / ||q||` of the `256 N eps` tolerance, and an
        // inflated `z` fails.
        let delta = T::of(4.0 * N as f64) * T::EPS * max(scales.m_norm, T::TINY);
        let mut regularized = *lcp;
        for i in 0..N {
            regularized.m[(i, i)] += delta;
        }
        let mut tab = Tableau::cold(&regularized);
        let budget = self.max_pivots.saturating_sub(spent).max(1);
        // When the retry does not rescue the solve, the error is the first one: a ray.
        match tab.run(budget, self.pivot_floor) {
            Ok(pivots) => self
                .finish(lcp, &scales, &tab, spent + pivots, eliminations, false, true)
                .map_err(|_| LcpError::Ray { pivots: spent + pivots }),
            Err(LcpError::Ray { pivots }) => Err(LcpError::Ray { pivots: spent + pivots }),
            Err(LcpError::MaxPivots { pivots }) => Err(LcpError::MaxPivots { pivots: spent + pivots }),
            Err(e) => Err(e),
        }
    }

    /// [`Self::solve_from_basis`] without the cold start and its regularised retry: Lemke's method
    /// from `warm`'s tableau only, its answer verified. For a caller that has already run the cold
    /// start on `lcp` and tries several bases near its answer (the multibody stepper's retries):
    /// each such basis costs one run from its tableau, not the same cold run again. `None` when
    /// `warm` is the trivial basis (its tableau is the cold start's), the data are not finite, the
    /// basis is singular or the run fails or does not verify.
    #[inline(never)] // its tableau in a frame of its own, not in its caller's
    pub(crate) fn solve_from_tableau(
        &self,
        lcp: &Lcp<T, N>,
        warm: Basis<N, WORDS>,
    ) -> Option<LcpSolution<T, N, WORDS>> {
        let scales = lcp.scales()?;
        if warm == Basis::all_w() {
            return None;
        }
        self.run_from_tableau(lcp, &scales, warm, max(scales.m_norm, T::TINY)).ok()
    }

    /// Lemke's method from the tableau of `warm` (not the trivial basis), its answer verified; on
    /// failure the pivots spent and the eliminations that set the tableau up (none when `warm` is
    /// singular). Inlined: in [`Self::solve_warm_inner`] its tableau shares the frame of the cold
    /// start's (a call would stack the two frames).
    #[allow(clippy::inline_always)] // one frame for the warm and the cold tableaux
    #[inline(always)]
    fn run_from_tableau(
        &self,
        lcp: &Lcp<T, N>,
        scales: &Scales<T>,
        warm: Basis<N, WORDS>,
        scale: T,
    ) -> Result<LcpSolution<T, N, WORDS>, (u32, u32)> {
        let mut tab = Tableau::cold(lcp);
        let Some(elim) = tab.warm(warm, scale) else { return Err((0, 0)) };
        match tab.run(self.max_pivots, self.pivot_floor) {
            Ok(pivots) => {
                self.finish(lcp, scales, &tab, pivots, elim, true, false).map_err(|e| (e.pivots(), elim))
            }
            Err(e) => Err((e.pivots(), elim)),
        }
    }

    #[allow(clippy::too_many_arguments)] // the solve's bookkeeping, passed through once
    fn finish(
        &self,
        lcp: &Lcp<T, N>,
        scales: &Scales<T>,
        tab: &Tableau<T, N, WORDS>,
        pivots: u32,
        setup_eliminations: u32,
        warm_start_used: bool,
        regularized: bool,
    ) -> Result<LcpSolution<T, N, WORDS>, LcpError> {
        let (z, basis) = tab.solution(lcp);
        // A regularised answer is held to `w`'s scale `||q||` alone (see `solve_warm`).
        let m_scale = if regularized { T::zero() } else { scales.m_norm };
        let w = lcp.w_of(&z);
        let check = Verification::of(&z, &w, (m_scale, scales.q_norm), self.tolerance);
        if !check.passed() {
            return Err(LcpError::Unverified {
                residual: check.residual.as_f32(),
                tolerance: check.tolerance.as_f32(),
                pivots,
            });
        }
        Ok(LcpSolution {
            z,
            w,
            pivots,
            setup_eliminations,
            warm_start_used,
            basis,
            residual: check.residual,
            scale: check.scale,
            regularized,
        })
    }
}
