//! How a step's LCP is solved (`docs/formulation.md`, "Solving a step"): [`SolvePath::Free`]
//! (`q >= 0`, `z = 0`), else [`SolvePath::Warm`] (the previous basis solved in factored form,
//! [`FactoredLcp::solve_basis`]), else [`SolvePath::Candidate`] (its neighbours,
//! [`super::candidates`]), else [`SolvePath::Lemke`] (Lemke's method on the dense form,
//! [`super::assemble`], warm-started from the previous basis). Every path's answer is verified
//! ([`crate::lcp::verify`]); a path that cannot answer hands the step to the next.

use super::assemble::{cone_weights, fill_from_factored};
use super::candidates::CANDIDATES;
use super::factored::{Declined, FactoredLcp, PlanCache};
use crate::lcp::{Basis, Lcp, LcpError, Lemke};
use crate::nalgebra::{SMatrix, SVector};
use crate::real::Real;

/// Which path answered a step's LCP (`docs/formulation.md`, "Solving a step"). Every path's
/// answer is verified; a path that cannot answer hands the step to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SolvePath {
    /// `q >= 0`: no impulse is needed, `z = 0` (as Lemke's method answers it, before any pivot).
    Free,
    /// The previous step's basis, solved in the body's coordinates ([`FactoredLcp`]).
    Warm,
    /// One of the bases next to the previous one (one contact's mode changed), solved the same way.
    Candidate,
    /// Lemke's method on the assembled LCP, warm-started from the previous basis: the solver of
    /// record, for whatever the other paths do not answer.
    Lemke,
}

impl SolvePath {
    /// Every path, in the order they are tried.
    pub const ALL: [Self; 4] = [Self::Free, Self::Warm, Self::Candidate, Self::Lemke];

    /// A short stable name: `free`, `warm`, `candidate`, `lemke`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Free => "free",
            Self::Warm => "warm",
            Self::Candidate => "candidate",
            Self::Lemke => "lemke",
        }
    }
}

/// How many solves each [`SolvePath`] answered over a run (a step that fell back to the full
/// layout counts two solves), and how many candidate bases were tried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PathCounts {
    /// Answered with `z = 0`.
    pub free: u64,
    /// Answered by the previous basis.
    pub warm: u64,
    /// Answered by a candidate basis.
    pub candidate: u64,
    /// Answered by Lemke's method (or failed there).
    pub lemke: u64,
    /// Candidate bases solved, answered or not.
    pub candidates_tried: u64,
}

impl PathCounts {
    /// The solves `path` answered.
    #[must_use]
    pub const fn of(&self, path: SolvePath) -> u64 {
        match path {
            SolvePath::Free => self.free,
            SolvePath::Warm => self.warm,
            SolvePath::Candidate => self.candidate,
            SolvePath::Lemke => self.lemke,
        }
    }

    pub(crate) fn count(&mut self, path: SolvePath) {
        match path {
            SolvePath::Free => self.free += 1,
            SolvePath::Warm => self.warm += 1,
            SolvePath::Candidate => self.candidate += 1,
            SolvePath::Lemke => self.lemke += 1,
        }
    }
}

/// One layout's verified answer ([`solve`]); `z` and `w` are written into the caller's arrays.
pub(crate) struct Solved<T: Real, const M: usize> {
    pub(crate) v_plus: [T; 3],
    pub(crate) basis: Basis<M>,
    pub(crate) pivots: u32,
    pub(crate) warm_start_used: bool,
    pub(crate) residual: T,
    pub(crate) path: SolvePath,
}

/// Solves the step's LCP `factored` (`docs/formulation.md`, "Solving a step"): `z = 0` when
/// `q >= 0`; else the previous basis `warm` in the body's coordinates; else its neighbours the same
/// way; else Lemke's method on the assembled LCP, warm-started from `warm`. Every answer is
/// verified; `z` and `w` receive it. Counts the path (and each candidate tried) in `paths`, and an
/// answer of Lemke's regularised retry in `regularized_solves`.
/// `plan` keeps the warm basis' unknowns from one call to the next ([`FactoredLcp`]'s layout must
/// be the same each call; a default one for a one-off).
// Inlined into the step without `host-tuned`: out of line, every step pays a call and its
// answer's copy through memory.
#[cfg_attr(not(feature = "host-tuned"), inline(always))]
#[allow(clippy::inline_always)] // measured, as said above
#[allow(clippy::too_many_arguments)] // the two counters of `RunStats` it writes, passed on their own
pub(crate) fn solve<T: Real, const K: usize, const M: usize>(
    factored: &FactoredLcp<T, K, M>,
    warm: Basis<M>,
    plan: &mut PlanCache<K>,
    solver: &Lemke<T, M>,
    paths: &mut PathCounts,
    regularized_solves: &mut u64,
    z: &mut [T; M],
    w: &mut [T; M],
) -> Result<Solved<T, M>, LcpError> {
    if !factored.is_finite() {
        return Err(LcpError::NonFiniteInput);
    }
    if factored.is_free() {
        *z = [T::zero(); M];
        *w = *factored.q();
        paths.count(SolvePath::Free);
        return Ok(Solved {
            v_plus: *factored.v_free(),
            basis: Basis::all_w(),
            pivots: 0,
            warm_start_used: false,
            residual: T::zero(),
            path: SolvePath::Free,
        });
    }
    match factored.solve_basis_cached_into(warm, plan, solver.tolerance(), z, w) {
        Ok((v_plus, residual)) => {
            paths.count(SolvePath::Warm);
            Ok(Solved {
                v_plus,
                basis: warm,
                pivots: 0,
                warm_start_used: true,
                residual,
                path: SolvePath::Warm,
            })
        }
        // The weighted cone rows first (`docs/formulation.md`, "Precision"); when Lemke's method
        // has no verified answer to them (an ill-conditioned step at extreme friction: two
        // fingers' columns nearly parallel at their meeting), the model's own rows, verified on
        // their own scale. (The pivots reported are the answering solve's.) The retry is a second
        // call, not a loop around Lemke's method: one copy of it, and no state kept across it.
        Err(why) => match solve_cold(factored, warm, Some(why), solver, paths, regularized_solves, z, w) {
            Err(_) if factored.cone_scaled != 0 => {
                solve_cold(factored, warm, None, solver, paths, regularized_solves, z, w)
            }
            answer => answer,
        },
    }
}

/// [`solve`] after the previous basis failed with `why`: its neighbours, then Lemke's method on
/// the step's LCP with its cone rows weighted as `factored` says ([`fill_from_factored`]); with
/// `why` `None` (a retry after that failed), Lemke's method on the model's own rows alone. A
/// weighted solve's `w` is the model's, recomputed in factored form. Out of line, so that the
/// warm path the most steps take stays small.
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)] // as `solve`
fn solve_cold<T: Real, const K: usize, const M: usize>(
    factored: &FactoredLcp<T, K, M>,
    warm: Basis<M>,
    why: Option<Declined>,
    solver: &Lemke<T, M>,
    paths: &mut PathCounts,
    regularized_solves: &mut u64,
    z: &mut [T; M],
    w: &mut [T; M],
) -> Result<Solved<T, M>, LcpError> {
    let weighted = why.is_some() && factored.cone_scaled != 0;
    if let Some(why) = why {
        let tolerance = solver.tolerance();
        let answer = (0..CANDIDATES * K).find_map(|k| {
            let basis = factored.candidate(warm, why, k)?;
            paths.candidates_tried += 1;
            factored.solve_basis_into(basis, tolerance, z, w).ok().map(|(v_plus, residual)| Solved {
                v_plus,
                basis,
                pivots: 0,
                warm_start_used: false,
                residual,
                path: SolvePath::Candidate,
            })
        });
        if let Some(answer) = answer {
            paths.count(SolvePath::Candidate);
            return Ok(answer);
        }
        paths.count(SolvePath::Lemke);
    }
    // `A` and `q` alone: Lemke's method needs no wrench columns.
    let mut lcp = Lcp::new(SMatrix::zeros(), SVector::zeros());
    let weights = if weighted { cone_weights(factored) } else { [T::one(); K] };
    fill_from_factored(factored, &weights, &mut lcp);
    let sol = solver.solve_from_basis(&lcp, warm)?;
    *regularized_solves += u64::from(sol.regularized);
    for j in 0..M {
        z[j] = sol.z[j];
        w[j] = sol.w[j];
    }
    if weighted {
        // The model's `w` (its cone rows unweighted), in factored form.
        factored.w_into(z, w);
    }
    Ok(Solved {
        v_plus: factored.velocity_after(z),
        basis: sol.basis,
        pivots: sol.pivots,
        warm_start_used: sol.warm_start_used,
        residual: sol.residual,
        path: SolvePath::Lemke,
    })
}
