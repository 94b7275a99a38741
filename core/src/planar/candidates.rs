//! The complementary bases the stepper tries besides the previous step's (`docs/formulation.md`,
//! "Solving a step", item 3): each contact's variables read as a [`Pattern`] of the crate's slot
//! codec (`core/src/slot.rs`: separated, touching, sticking, sliding, skidding), and the bases
//! that change one contact's pattern, in an
//! order set by the variable that made the previous basis fail. Also the basis of the initial
//! modes ([`basis_of_modes`]) and a reduced basis turned to a dropped direction
//! ([`FactoredLcp::with_direction`]).
//!
//! A basis is only proposed here; [`FactoredLcp::solve_basis`] solves and verifies it.

use super::contact::ContactMode;
use super::factored::{Declined, FactoredLcp, slot_of};
use super::layout::{Direction, Layout, Tangents};
use crate::lcp::Basis;
use crate::real::Real;
use crate::slot::Pattern;

impl<T: Real, const K: usize, const N: usize> FactoredLcp<T, K, N> {
    /// `basis` with contact `i`'s friction turned to `direction` (sliding, sticking or skidding
    /// as before): the full layout's first try when a reduced layout's dropped direction was
    /// needed.
    ///
    /// Inlined into the step's fallback: out of line, each step solved again in the full layout
    /// pays a call; measured, the slow scene's worst step on the Cortex-M33F is one SysTick tick
    /// (50 instructions) longer that way.
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    #[inline(always)]
    #[allow(clippy::inline_always)] // measured, as said above
    pub(crate) fn with_direction(&self, basis: Basis<N>, i: usize, direction: Direction) -> Basis<N> {
        let slot = slot_of::<K, N>(&self.tangents, i);
        let current = slot.read(basis.z_mask());
        if current.direction().is_none() || !current.is_listed() {
            return basis;
        }
        slot.set(basis, current.along(direction))
    }

    /// Candidate `k` (`k < CANDIDATES * K`) of the bases near `basis`, which failed with `why`
    /// ([`candidate`]); `None` for a slot that has no basis (a direction not kept, or the
    /// contact's current pattern).
    pub(crate) fn candidate(&self, basis: Basis<N>, why: Declined, k: usize) -> Option<Basis<N>> {
        let (first, hint) = match why {
            Declined::Infeasible(v) => variable_of::<K, N>(&self.tangents, usize::from(v)),
            Declined::Pattern | Declined::Singular | Declined::Unverified => (0, Hint::None),
        };
        candidate(&self.tangents, basis, first, hint, k)
    }
}

/// What kind of variable made a basis infeasible: it orders the first contact's candidates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Hint {
    /// Nothing known.
    None,
    /// The normal impulse or row: the contact wants to separate (or to touch).
    Normal,
    /// `sigma`: the slip reversed, the contact wants to stick.
    Sigma,
    /// A friction impulse or row along this direction.
    Friction(Direction),
}

/// Slots per contact in the list of candidate bases ([`candidate`]).
pub(crate) const CANDIDATES: usize = 8;

/// The bases near `basis` worth trying when it fails, at most `K x 7` (`K x 4` with one kept
/// direction per contact), in a fixed order: for each contact from `first` on, every other
/// pattern of its variables with the other contacts as they are: sliding and sticking along each
/// kept direction (`direction` first for contact `first`), separated, touching without friction,
/// separated with the support slipping past. A mode change of one contact is what a step usually
/// brings; a step that changes two goes to Lemke's method. Candidate `k` is slot `k % 8` of
/// contact `(first + k / 8) % K`; `None` for a slot with no basis (a direction not kept, or the
/// contact's current pattern). The first contact's slots are ordered by `hint`, the kind of
/// variable that failed: a normal tries separating first, a sigma (the slip reversed) sticking.
pub(crate) fn candidate<const K: usize, const N: usize>(
    tangents: &[Tangents; K],
    basis: Basis<N>,
    first: usize,
    hint: Hint,
    k: usize,
) -> Option<Basis<N>> {
    // Slots: 0 slide along d0, 1 stick along d0, 2 slide along d1, 3 stick along d1, 4 off,
    // 5 touch, 6 skid along d0, 7 skid along d1; the order of the first contact's follows the
    // variable that failed (a normal: separate first; a sigma: stick first), the others' is 0..8.
    const ORDER: [[usize; CANDIDATES]; 3] =
        [[0, 1, 2, 3, 4, 5, 6, 7], [4, 5, 1, 0, 3, 2, 6, 7], [1, 5, 3, 2, 0, 4, 6, 7]];
    let i = (first + k / CANDIDATES) % K;
    let slot = slot_of::<K, N>(tangents, i);
    let current = slot.read(basis.z_mask());
    let (order, d0) = match (i == first, hint) {
        (true, Hint::Normal) => (1, None),
        (true, Hint::Sigma) => (2, None),
        (true, Hint::Friction(d)) => (0, Some(d)),
        (true, Hint::None) | (false, _) => (0, None),
    };
    // d0: the failing friction row's direction, else the contact's current one, else +d.
    let d0 = d0.or(if current.is_listed() { current.direction() } else { None }).unwrap_or(Direction::Plus);
    let d1 = d0.opposite();
    let p = match ORDER[order][k % CANDIDATES] {
        0 => Pattern::SLIDE_PLUS.along(d0),
        1 => Pattern::STICK_PLUS.along(d0),
        2 => Pattern::SLIDE_PLUS.along(d1),
        3 => Pattern::STICK_PLUS.along(d1),
        4 => Pattern::OFF,
        5 => Pattern::TOUCH,
        6 => Pattern::SKID_PLUS.along(d0),
        _ => Pattern::SKID_PLUS.along(d1),
    };
    // `current` unlisted (no contact's) never equals `p`.
    (slot.holds(p) && current != p).then(|| slot.set(basis, p))
}

/// A basis for contacts in `modes` (before the first step: the modes of the prescribed
/// motion): sticking and sliding contacts touch, the others are off; a sliding contact's
/// friction opposes its slip; a sticking contact's takes its first kept direction.
pub(crate) fn basis_of_modes<const K: usize, const N: usize>(
    tangents: &[Tangents; K],
    modes: &[ContactMode; K],
) -> Basis<N> {
    let mut basis = Basis::all_w();
    for i in 0..K {
        let t = tangents[i];
        let first = if t.keeps(Direction::Plus) { Direction::Plus } else { Direction::Minus };
        let p = match modes[i] {
            ContactMode::Separated => Pattern::OFF,
            ContactMode::Sticking => Pattern::STICK_PLUS.along(first),
            ContactMode::Sliding(d) if t.keeps(d) => Pattern::SLIDE_PLUS.along(d),
            ContactMode::Sliding(_) => Pattern::TOUCH,
        };
        basis = slot_of::<K, N>(tangents, i).set(basis, p);
    }
    basis
}

/// The contact variable `v` belongs to, and what kind of variable it is.
fn variable_of<const K: usize, const N: usize>(tangents: &[Tangents; K], v: usize) -> (usize, Hint) {
    let sigma_start = Layout::<K, N>::SIGMA_START;
    if v < K {
        return (v, Hint::Normal);
    }
    if v >= sigma_start {
        return ((v - sigma_start).min(K - 1), Hint::Sigma);
    }
    let mut j = K;
    for (i, t) in tangents.iter().enumerate() {
        for d in [Direction::Plus, Direction::Minus] {
            if t.keeps(d) {
                if j == v {
                    return (i, Hint::Friction(d));
                }
                j += 1;
            }
        }
    }
    (0, Hint::None)
}

/// The rule's enumeration's order of a contact's patterns ([`super::resolve`], which walks
/// their bases with [`crate::slot::each_basis`]): off, touching, sticking `+d`, sticking `-d`,
/// sliding `+d`, sliding `-d`, skidding `+d`, skidding `-d` (the slot codec's
/// [`crate::slot::PATTERNS`] in the order the planar rule offers them).
pub(crate) const RULE_ORDER: [Pattern; 8] = [
    Pattern::OFF,
    Pattern::TOUCH,
    Pattern::STICK_PLUS,
    Pattern::STICK_MINUS,
    Pattern::SLIDE_PLUS,
    Pattern::SLIDE_MINUS,
    Pattern::SKID_PLUS,
    Pattern::SKID_MINUS,
];
