//! The step's LCP and its solution (`docs/formulation.md`, "Solving a multibody step (the
//! core)"): [`SystemStepper::refill`] writes the active candidates' rows in factored form and the warm
//! basis; [`SystemStepper::solve`] takes the paths in order, `z = 0` when `q >= 0`, the warm basis in
//! factored form, the candidates (`candidates.rs`), Lemke's method on the assembled LCP from the
//! warm basis and its retries ([`SystemStepper::retry`]); every answer verified.

use super::SystemStepper;
use crate::StepError;
use crate::lcp::{Basis, Lcp, LcpError, LcpSolution, verify};
use crate::multibody::factored::{Answer, ContactBlocks, MOST_SLOTS};
use crate::multibody::resolve::{self, DeclinedBases};
use crate::planar::assemble::normal_bias;
use crate::planar::{Declined, PathCounts, SolvePath};
use crate::real::Real;
use crate::rule::Resolution;
use crate::slot::{PATTERNS, Slot};

impl<T: Real, const B: usize, const P: usize, const N: usize> SystemStepper<T, B, P, N> {
    /// The retries after a failed solve (a ray, the pivot cap, an answer that failed
    /// verification) of `lcp` from the warm basis `warm`, which has run Lemke's method from
    /// `warm`'s tableau, then from the cold start and its regularised retry
    /// ([`crate::lcp::Lemke::solve_from_basis`]). The friction LCP is not copositive-plus, so
    /// Lemke's method may end in a ray although a solution exists: the `sigma` of a contact
    /// without normal impulse is unbounded above (its column touches only its friction rows), a ray of the
    /// solution set; and a long pivot sequence in f32 can lose the precision its answer is
    /// verified to.
    ///
    /// 1. Each cone row's `q` is opened by `sqrt(eps) ||q||_inf` and Lemke's method run cold there
    ///    (with its regularised retry: another LCP, so another run); the basis it ends on is run
    ///    from its tableau on the exact problem (verified), or the opened answer counts if it
    ///    verifies against the exact problem (`docs/formulation.md`, "Solving a multibody step",
    ///    4).
    /// 2. The warm basis with one active contact's pattern replaced by each of [`PATTERNS`] (the
    ///    eight of the reference's descent: sticking, sliding either way; touching without
    ///    friction; separated; separated while slipping either way), each by Lemke's method from
    ///    its tableau only.
    ///
    /// **Cost** (a contract): no run is made twice. Bases whose run has been made on `lcp` are
    /// skipped: `warm` itself (one pattern replaced by its own), the trivial basis (its tableau is
    /// the cold start's) and the opened answer's. So at most two cold runs (the opened LCP's and
    /// its regularised retry) and `1 + 8 k` runs from a tableau, each within the pivot cap.
    ///
    /// Every answer is verified against the exact problem; the first error is the step's when none
    /// answers.
    fn retry(
        &self,
        lcp: &Lcp<T, N>,
        k: usize,
        warm: Basis<N>,
        error: LcpError,
    ) -> Result<LcpSolution<T, N>, StepError> {
        // `k <= N / 4` (said so: every row index below is in range, no panic path).
        let k = k.min(N / 4);
        let mut opened = *lcp;
        let delta = T::EPS.sqrt_rounded() * lcp.q_norm_inf();
        for j in 3 * k..4 * k {
            opened.q[j] += delta;
        }
        // The bases whose run from the tableau (or, for the trivial one, the cold run) is made.
        let made = [warm, Basis::all_w()];
        let mut near_basis = None;
        if let Ok(near) = self.solver.solve(&opened) {
            if !made.contains(&near.basis)
                && let Some(exact) = self.solver.solve_from_tableau(lcp, near.basis)
            {
                return Ok(exact);
            }
            let check = verify(lcp, &near.z, self.solver.tolerance());
            if check.passed() {
                return Ok(LcpSolution {
                    w: lcp.w_of(&near.z),
                    warm_start_used: false,
                    scale: check.scale,
                    ..near
                });
            }
            near_basis = Some(near.basis);
        }
        for j in 0..k {
            for pattern in PATTERNS {
                let basis = Slot::full(k, j).set(warm, pattern);
                if made.contains(&basis) || Some(basis) == near_basis {
                    continue;
                }
                if let Some(solution) = self.solver.solve_from_tableau(lcp, basis) {
                    return Ok(solution);
                }
            }
        }
        Err(StepError::Solver(error))
    }

    /// Refills this step's LCP in factored form ([`super::StepLcp`], kept in the stepper and
    /// refilled in place each step: no copy of its rows): the active candidates in candidate order (`slots`),
    /// `v~ = V + h M^-1 w_ext` (eq. 16), each slot's Jacobian rows, bias and `mu`; and the warm
    /// basis (each slot's pattern of the last step).
    ///
    /// # Errors
    /// [`StepError::TooManyContacts`].
    pub(in crate::multibody) fn refill(&mut self) -> Result<(), StepError> {
        let s = self.system.settings.base;
        let h = s.step;
        let out = &mut self.lcp;
        let mut k = 0usize;
        let mut active = 0u8;
        for p in 0..P {
            for c in 0..4 {
                if self.frames[p][c].active {
                    active = active.saturating_add(1);
                    if 4 * (k + 1) <= N {
                        out.slots[k] = (p, c);
                        k += 1;
                    }
                }
            }
        }
        if usize::from(active) > k {
            return Err(StepError::TooManyContacts(active));
        }
        // `k <= N / 4` already; said so that every row index below (< 4 k) is in range without a
        // check (no panic path).
        let k = k.min(N / 4);
        let mut v_free = [[T::zero(); 3]; B];
        for i in 0..B {
            let (st, f, m) = (&self.states[i], self.system.forces[i], self.system.bodies[i].mass);
            v_free[i] = [st.vx + h * f[0] / m, st.vy + h * (f[1] / m - s.gravity), st.omega];
        }
        out.factored.reset(k, v_free);
        // The warm basis' bit mask (bit `row`: `z_row` basic), each slot's pattern at its rows.
        let mut warm = 0u32;
        for (j, &(p, c)) in out.slots[..k].iter().enumerate() {
            // Every slot's (p, c) is below (P, 4) by construction: said so, so that no index below
            // needs a check (no panic path).
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let d = f.tangent;
            let pair = &self.system.pairs[p];
            let mu = if self.modes[p][c].is_sliding() { pair.mu_kinetic } else { pair.mu_static };
            out.factored.set_slot(
                j,
                // `p < P <= 32` ([`Self::SIZE_CHECK`]): exact.
                p as u8,
                [f.dense_row(f.normal), f.dense_row(d)],
                normal_bias(f.gap, h, s.gravity, f.gap_round_off),
                mu,
                &self.inverse_mass,
            );
            warm |= Slot::full(k, j).bits(self.patterns[p][c]);
        }
        out.factored.finish();
        out.k = k;
        out.active = active;
        out.warm = Basis::from_z_mask(warm);
        Ok(())
    }

    /// Solves the step's LCP (`docs/formulation.md`, "Solving a multibody step (the core)", and its
    /// worst case of a step, a contract: no solve or Lemke run made twice): `z = 0`
    /// when `q >= 0` ([`SolvePath::Free`]); else the warm basis in factored form
    /// ([`SolvePath::Warm`]); else the bases of [`Self::candidate`] ([`SolvePath::Candidate`]);
    /// else Lemke's method on
    /// the assembled LCP from the warm basis, with its retries ([`SolvePath::Lemke`]). Every answer
    /// is verified. Writes `z` (zero on entry, as
    /// [`crate::multibody::factored::Factored::solve_basis`] wants it: the step's own array);
    /// returns `v+`, the basis and the pivots.
    pub(super) fn solve(
        &self,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
    ) -> Result<Solved<T, B, N>, StepError> {
        let step = &self.lcp;
        let f = &step.factored;
        if !f.is_finite() {
            return Err(StepError::Solver(LcpError::NonFiniteInput));
        }
        if f.is_free() {
            return Ok(Solved {
                v_plus: *f.v_free(),
                basis: Basis::all_w(),
                pivots: 0,
                path: SolvePath::Free,
                along: None,
                ruled: false,
                rule: None,
            });
        }
        let tolerance = self.solver.tolerance();
        let warm = step.warm;
        let why = match f.solve_basis(warm.z_mask(), tolerance, blocks, z, None) {
            Ok(a) => return Ok(Solved::of(a, SolvePath::Warm)),
            Err(why) => why,
        };
        self.unwarmed(why, paths, blocks, z)
    }

    /// [`Self::solve`] after the warm basis declined (`why`): the candidates, then Lemke's method.
    /// Out of line and cold: a warm step (most steps) does not reach it. Lemke's method, per
    /// assembled LCP (at most two: the weighted cone rows, then the model's): one run from the warm
    /// basis' tableau, one cold run and its regularised retry, then [`Self::retry`]'s (two cold
    /// runs, at most `1 + 8 k` from a tableau).
    #[cold]
    #[inline(never)]
    fn unwarmed(
        &self,
        why: Declined,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
    ) -> Result<Solved<T, B, N>, StepError> {
        // The bases solved and declined, for the rule (not solved again there): the warm one first.
        let mut declined = DeclinedBases::new();
        declined.add(self.lcp.warm.z_mask(), self.lcp.k);
        let mut solved = match self.candidate(why, paths, blocks, z, &mut declined) {
            Some(answer) => answer,
            None => self.lemke(z)?,
        };
        // The rule here, where the bases declined are known (`SystemStepper::step` applies it to a warm
        // answer).
        let mut mask = solved.basis.z_mask();
        let answer = (&mut solved.v_plus, z, &mut mask);
        let rule = resolve::apply(
            &self.detector,
            &self.lcp.factored,
            blocks,
            self.solver.tolerance(),
            Some(&declined),
            answer,
        );
        solved.basis = Basis::from_z_mask(mask);
        (solved.ruled, solved.rule) = (true, rule);
        Ok(solved)
    }

    /// Lemke's method on the assembled LCP from the warm basis, with its retries (at most two
    /// LCPs: the weighted cone rows, then the model's); its answer written into `z`. Inlined: its
    /// LCPs in [`Self::unwarmed`]'s frame, as before it was a function of its own.
    #[allow(clippy::inline_always)] // one frame for the cold path
    #[inline(always)]
    fn lemke(&self, z: &mut [T; N]) -> Result<Solved<T, B, N>, StepError> {
        let (step, warm) = (&self.lcp, self.lcp.warm);
        let f = &step.factored;
        let k = step.k.min(N / 4);
        // The weighted cone rows first (`docs/formulation.md`, "Extreme friction: the cone rows
        // weighted"; the same solutions), with their retries; when none answers, the model's own
        // rows, verified on their own scale.
        let mut weighted = f.is_weighted();
        let solution = loop {
            let lcp = f.assemble(weighted);
            let solved = match self.solver.solve_from_basis(&lcp, warm) {
                Err(LcpError::NonFiniteInput) => return Err(StepError::Solver(LcpError::NonFiniteInput)),
                Err(error) => self.retry(&lcp, k, warm, error),
                Ok(solution) => Ok(solution),
            };
            match solved {
                Ok(solution) => break solution,
                Err(_) if weighted => weighted = false,
                Err(error) => return Err(error),
            }
        };
        for j in 0..N {
            z[j] = solution.z[j];
        }
        Ok(Solved {
            v_plus: f.velocity_after(z),
            basis: solution.basis,
            pivots: solution.pivots,
            path: SolvePath::Lemke,
            along: None,
            ruled: false,
            rule: None,
        })
    }
}

/// A step's verified answer ([`SystemStepper::solve`]; `z` is written into the caller's array).
pub(super) struct Solved<T, const B: usize, const N: usize> {
    /// `v+ = v~ + M~ J^T z`.
    pub(super) v_plus: [[T; 3]; B],
    /// The basis of the answer (the next step's warm basis).
    pub(super) basis: Basis<N>,
    /// Lemke pivots spent.
    pub(super) pivots: u32,
    /// The path that answered.
    pub(super) path: SolvePath,
    /// Each slot's `c_+d^T v+` as a basis solve formed it ([`Answer`]), `None`
    /// from Lemke's method or with no impulse.
    pub(super) along: Option<[T; MOST_SLOTS]>,
    /// Whether the path applied the rule (the candidates' and Lemke's method's answers, where the
    /// bases declined before are known and not solved again), and what it did; else the stepper
    /// applies it (a warm or free answer).
    pub(super) ruled: bool,
    /// What the rule did, when `ruled`.
    pub(super) rule: Option<Resolution>,
}

impl<T: Copy, const B: usize, const N: usize> Solved<T, B, N> {
    /// A basis solve's answer `a`, reached by `path` (no pivot).
    #[inline]
    pub(super) fn of(a: Answer<T, B>, path: SolvePath) -> Self {
        Self {
            v_plus: a.v_plus,
            basis: Basis::from_z_mask(a.mask),
            pivots: 0,
            path,
            along: Some(a.along),
            ruled: false,
            rule: None,
        }
    }
}
