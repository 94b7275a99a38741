//! The candidates after the warm basis declined ([`SystemStepper::candidate`]): the bases next to the
//! warm one, each solved in factored form ([`crate::multibody::factored::Factored::solve_basis`]),
//! the first that answers taken. The basis in which every touching slot slides against its free
//! slip; the lifting chain ([`SystemStepper::lifting_chain`]: the slot whose normal impulse came out
//! negative lifts off, then the next); the failing slot's eight patterns ([`PATTERNS`], the
//! reference's descent), its pair's, every other slot's and pair's. None is solved twice.

use super::SystemStepper;
use super::solve::Solved;
use crate::lcp::Basis;
use crate::multibody::factored::{ContactBlocks, MOST_SLOTS};
use crate::multibody::resolve::DeclinedBases;
use crate::planar::{Declined, PathCounts, SolvePath};
use crate::real::Real;
use crate::slot::{PATTERNS, Pattern, Slot};

impl<T: Real, const B: usize, const P: usize, const N: usize> SystemStepper<T, B, P, N> {
    /// The candidates of [`Self::solve`] after the warm basis failed with `why`: the first that
    /// answers (written into `z`), or `None`; each that declines added to `declined` (for the
    /// rule, which does not solve it again).
    ///
    /// **Cost** (a contract): at most `1 + k + 8 k + 8 P` factored solves (the sliding basis, the
    /// lifting chain's `k`, the failing slot's and its pair's 8, the other slots' and pairs' 8
    /// each), none of one basis twice: a basis equal to the warm one, to one solved out of the
    /// list's order (the sliding one, the chain's) or to one of the failing pair's is skipped, and
    /// so is a pair's basis that changes one slot only (that slot's eight solve it).
    pub(super) fn candidate(
        &self,
        why: Declined,
        paths: &mut PathCounts,
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
        declined: &mut DeclinedBases,
    ) -> Option<Solved<T, B, N>> {
        let step = &self.lcp;
        let f = &step.factored;
        let tolerance = self.solver.tolerance();
        let warm = step.warm;
        let k = step.k.min(N / 4);
        let first = match why {
            Declined::Infeasible(v) => f.slot_of(usize::from(v)),
            Declined::Pattern | Declined::Singular | Declined::Unverified => 0,
        };
        // One slot's pattern replaced, or every slot of one pair at once (an interface that starts
        // or stops sliding changes both its corners: sticking and touching to sliding along the
        // same direction); sticking patterns pair-wide stick the pair's first slot and touch the
        // others (both sticking is singular). The failing slot first, then its pair, then the
        // other slots, then the other pairs.
        let pair_of = |j: usize| step.slots[j.min(N - 1)].0;
        let with_slot = |basis: Basis<N>, j: usize, pattern: Pattern| Slot::full(k, j).set(basis, pattern);
        let with_pair = |p: usize, pattern: Pattern| {
            let mut basis = warm;
            let mut slots = 0;
            for j in 0..k {
                if pair_of(j) == p {
                    let touch = pattern.is_sticking() && slots > 0;
                    basis = with_slot(basis, j, if touch { Pattern::TOUCH } else { pattern });
                    slots += 1;
                }
            }
            (slots > 1).then_some(basis)
        };
        // And the basis in which every touching slot slides against its free slip (the sign of
        // its `+d` row's `q`, the relative tangential velocity before any impulse): several
        // interfaces starting to slide in one step (a pushed block under another).
        let sliding = {
            let mut basis = warm;
            for j in 0..k {
                let [n, plus, ..] = crate::slot::full_rows(k, j);
                let q = f.q()[plus.min(N - 1)];
                if warm.is_z_basic(n) && q != T::zero() {
                    basis = with_slot(
                        basis,
                        j,
                        if q < T::zero() { Pattern::SLIDE_PLUS } else { Pattern::SLIDE_MINUS },
                    );
                }
            }
            basis
        };
        let first_pair = pair_of(first);
        let lifting = self.lifted(warm, why);
        // The warm basis, the bases solved out of the list's order (the sliding one, the lifting
        // chain's) and the failing pair's: a later basis equal to one of them is not solved again.
        let mut made = [warm; 2 + MOST_SLOTS + 8];
        let mut count = 1;
        // The sliding basis and why it declined, when it did: the chain goes on from it unsolved.
        let mut sliding_declined = None;
        // The slots (bits) in which `basis` differs from the warm one.
        let changed = |basis: Basis<N>| {
            let (diff, mut slots) = (basis.z_mask() ^ warm.z_mask(), 0u32);
            for j in 0..k {
                if Slot::full(k, j).read(diff) != Pattern::OFF {
                    slots |= 1 << j;
                }
            }
            slots
        };
        // The list, as one index (no iterator adapters: no panic path): the sliding one (one solve,
        // and the first step of a push needs it), the lifting chain, the failing slot's 8, its
        // pair's 8, the other slots' 8 each, the other pairs' 8 each.
        let slots = k.max(1);
        let others = 18 + 8 * (slots - 1);
        for n in 0..others + 8 * P {
            let basis = if n == 0 {
                Some(sliding)
            } else if n == 1 {
                let chain = (&mut made[..], &mut count, sliding_declined);
                if let Some(answer) = self.lifting_chain(lifting, (paths, &mut *declined), blocks, z, chain) {
                    return Some(answer);
                }
                None
            } else if n < 10 {
                Some(with_slot(warm, first, PATTERNS[(n - 2) % 8]))
            } else if n < 18 {
                // One slot changed: the failing slot's, solved above, or another's, solved below
                // (and skipped there).
                with_pair(first_pair, PATTERNS[(n - 2) % 8])
                    .filter(|&b| changed(b).count_ones() > 1 || changed(b) & 1 << first == 0)
            } else if n < others {
                let m = n - 18;
                Some(with_slot(warm, (first + 1 + m / 8) % slots, PATTERNS[m % 8]))
            } else {
                // One slot changed: solved above, as that slot's pattern.
                let m = n - others;
                (m / 8 != first_pair)
                    .then(|| with_pair(m / 8, PATTERNS[m % 8]))
                    .flatten()
                    .filter(|&b| changed(b).count_ones() > 1)
            };
            let Some(basis) = basis.filter(|b| !made[..count.min(made.len())].contains(b)) else {
                continue;
            };
            paths.candidates_tried += 1;
            match f.solve_basis(basis.z_mask(), tolerance, blocks, z, None) {
                Ok(a) => return Some(Solved::of(a, SolvePath::Candidate)),
                Err(why) => {
                    declined.add(basis.z_mask(), k);
                    if n == 0 {
                        sliding_declined = Some((basis, why));
                    }
                }
            }
            if (n == 0 || (10..18).contains(&n))
                && let Some(slot) = made.get_mut(count)
            {
                *slot = basis;
                count += 1;
            }
        }
        None
    }

    /// `basis` with the slot whose normal impulse came out negative (`why`) lifting off: its own
    /// pattern without `p_n` (a sliding contact keeps its friction row and sigma basic: separated
    /// while the support slips past; a sticking one separates and passes its pair's friction to
    /// another of the pair's slots that touches without friction, if one does), or `None`.
    fn lifted(&self, basis: Basis<N>, why: Declined) -> Option<Basis<N>> {
        let k = self.lcp.k.min(N / 4);
        let Declined::Infeasible(v) = why else { return None };
        let j = usize::from(v);
        if j >= k || !basis.is_z_basic(j) {
            return None;
        }
        let pair_of = |i: usize| self.lcp.slots[i.min(N - 1)].0;
        let current = Slot::full(k, j).read(basis.z_mask());
        if current.lifted().is_listed() {
            return Some(Slot::full(k, j).set(basis, current.lifted()));
        }
        if !current.is_sticking() {
            return None;
        }
        let mut lifted = Slot::full(k, j).set(basis, Pattern::OFF);
        let touching = (0..k)
            .find(|&i| pair_of(i) == pair_of(j) && Slot::full(k, i).read(lifted.z_mask()) == Pattern::TOUCH);
        if let Some(i) = touching {
            lifted = Slot::full(k, i).set(lifted, current);
        }
        Some(lifted)
    }

    /// The lifting candidate `start` ([`Self::lifted`]), and while its answer has another slot
    /// whose normal impulse is negative, that slot lifting too: the first basis that answers.
    /// Each lift takes one `p_n` out of the basis, so at most `k` solves (a stack tipping over its
    /// edges lifts one corner of each interface in its first step).
    ///
    /// `made` holds the first `count` bases solved so far (the warm one first), and adds each the
    /// chain solves (as many as it holds); `declined` a basis solved before and why it declined,
    /// which the chain goes on from without solving it again. Each basis that declines is added
    /// to `for_rule` (as in [`Self::candidate`]).
    fn lifting_chain(
        &self,
        start: Option<Basis<N>>,
        (paths, for_rule): (&mut PathCounts, &mut DeclinedBases),
        blocks: Option<&ContactBlocks<T>>,
        z: &mut [T; N],
        (made, count, declined): (&mut [Basis<N>], &mut usize, Option<(Basis<N>, Declined)>),
    ) -> Option<Solved<T, B, N>> {
        let (f, warm, tolerance) = (&self.lcp.factored, self.lcp.warm, self.solver.tolerance());
        let mut basis = start;
        while let Some(lifted) = basis.filter(|&b| b != warm) {
            if let Some((known, why)) = declined.filter(|&(known, _)| known == lifted) {
                basis = self.lifted(known, why);
                continue;
            }
            paths.candidates_tried += 1;
            match f.solve_basis(lifted.z_mask(), tolerance, blocks, z, None) {
                Ok(a) => return Some(Solved::of(a, SolvePath::Candidate)),
                Err(why) => {
                    for_rule.add(lifted.z_mask(), self.lcp.k);
                    basis = self.lifted(lifted, why);
                }
            }
            if let Some(slot) = made.get_mut(*count) {
                *slot = lifted;
                *count += 1;
            }
        }
        None
    }
}
