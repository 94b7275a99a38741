//! The complementary bases the stepper tries besides the previous step's (`docs/formulation.md`,
//! "Solving a step", item 3): each contact's variables read as a [`Pattern`] (separated,
//! touching, sticking, sliding, skidding), and the bases that change one contact's pattern, in an
//! order set by the variable that made the previous basis fail. Also the basis of the initial
//! modes ([`basis_of_modes`]) and a reduced basis turned to a dropped direction
//! ([`FactoredLcp::with_direction`]).
//!
//! A basis is only proposed here; [`FactoredLcp::solve_basis`] solves and verifies it.

use super::contact::ContactMode;
use super::factored::{Declined, FactoredLcp, rows_of};
use super::layout::{Direction, Layout, Tangents};
use crate::lcp::Basis;
use crate::real::Real;

/// What a contact's variables do in a basis: which are basic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Pattern {
    /// Nothing basic: separated (or touching with no impulse).
    Off,
    /// Only `p_n` basic: touching with no friction impulse (frictionless, or a slip the kept
    /// directions do not oppose).
    Touch,
    /// `p_n` and `p_f` along the direction basic: sticking.
    Stick(Direction),
    /// `p_n`, `p_f` and `sigma` basic: sliding, friction on the cone's edge.
    Slide(Direction),
    /// `p_f` (at zero) and `sigma` basic: separated while the support slips past.
    Skid(Direction),
}

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
        let turned = match pattern(&self.tangents, basis, i) {
            Some(Pattern::Slide(_)) => Pattern::Slide(direction),
            Some(Pattern::Stick(_)) => Pattern::Stick(direction),
            Some(Pattern::Skid(_)) => Pattern::Skid(direction),
            Some(Pattern::Off | Pattern::Touch) | None => return basis,
        };
        with_pattern(&self.tangents, basis, i, turned)
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
    let current = pattern(tangents, basis, i);
    let (order, d0) = match (i == first, hint) {
        (true, Hint::Normal) => (1, None),
        (true, Hint::Sigma) => (2, None),
        (true, Hint::Friction(d)) => (0, Some(d)),
        (true, Hint::None) | (false, _) => (0, None),
    };
    // d0: the failing friction row's direction, else the contact's current one, else +d.
    let d0 = d0
        .or(match current {
            Some(Pattern::Slide(d) | Pattern::Stick(d) | Pattern::Skid(d)) => Some(d),
            _ => None,
        })
        .unwrap_or(Direction::Plus);
    let d1 = d0.opposite();
    let p = match ORDER[order][k % CANDIDATES] {
        0 => Pattern::Slide(d0),
        1 => Pattern::Stick(d0),
        2 => Pattern::Slide(d1),
        3 => Pattern::Stick(d1),
        4 => Pattern::Off,
        5 => Pattern::Touch,
        6 => Pattern::Skid(d0),
        _ => Pattern::Skid(d1),
    };
    let kept = match p {
        Pattern::Slide(d) | Pattern::Stick(d) | Pattern::Skid(d) => {
            tangents.get(i).is_some_and(|t| t.keeps(d))
        }
        Pattern::Off | Pattern::Touch => true,
    };
    (kept && current != Some(p)).then(|| with_pattern(tangents, basis, i, p))
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
            ContactMode::Separated => Pattern::Off,
            ContactMode::Sticking => Pattern::Stick(first),
            ContactMode::Sliding(d) if t.keeps(d) => Pattern::Slide(d),
            ContactMode::Sliding(_) => Pattern::Touch,
        };
        basis = with_pattern(tangents, basis, i, p);
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

/// The pattern of contact `i` in `basis`, `None` when it is none of [`Pattern`]'s.
fn pattern<const K: usize, const N: usize>(
    tangents: &[Tangents; K],
    basis: Basis<N>,
    i: usize,
) -> Option<Pattern> {
    let (n, f, s) = rows_of::<K, N>(tangents, i);
    let (bn, bs) = (basis.is_z_basic(n), basis.is_z_basic(s));
    let fp = f[0].is_some_and(|f| basis.is_z_basic(f));
    let fm = f[1].is_some_and(|f| basis.is_z_basic(f));
    let d = match (fp, fm) {
        (false, false) => {
            return match (bn, bs) {
                (false, false) => Some(Pattern::Off),
                (true, false) => Some(Pattern::Touch),
                _ => None,
            };
        }
        (true, true) => return None,
        (true, false) => Direction::Plus,
        (false, true) => Direction::Minus,
    };
    match (bn, bs) {
        (true, false) => Some(Pattern::Stick(d)),
        (true, true) => Some(Pattern::Slide(d)),
        (false, true) => Some(Pattern::Skid(d)),
        (false, false) => None,
    }
}

/// `basis` with contact `i`'s variables set to `pattern`. Inlined into each caller: a few bit
/// operations once `i` and `pattern` are known there, where a call costs more (out of line, each
/// candidate basis a step tries pays for one).
#[inline(always)]
#[allow(clippy::inline_always)] // measured, as said above
fn with_pattern<const K: usize, const N: usize>(
    tangents: &[Tangents; K],
    basis: Basis<N>,
    i: usize,
    pattern: Pattern,
) -> Basis<N> {
    let (n, f, s) = rows_of::<K, N>(tangents, i);
    // Bit masks of the contact's variables (an index beyond 31 gives no bit).
    let bit = |v: Option<usize>| v.map_or(0, |v| 1u32.checked_shl(v as u32).unwrap_or(0));
    let (bn, bs) = (bit(Some(n)), bit(Some(s)));
    let bf = |d: Direction| match d {
        Direction::Plus => bit(f[0]),
        Direction::Minus => bit(f[1]),
    };
    let set = match pattern {
        Pattern::Off => 0,
        Pattern::Touch => bn,
        Pattern::Stick(d) => bn | bf(d),
        Pattern::Slide(d) => bn | bf(d) | bs,
        Pattern::Skid(d) => bf(d) | bs,
    };
    let all = bn | bit(f[0]) | bit(f[1]) | bs;
    Basis::from_z_mask((basis.z_mask() & !all) | set)
}

/// Patterns per contact that [`pattern_basis`] numbers: off, touching, and sticking, sliding and
/// skidding along each direction.
pub(crate) const PATTERN_COUNT: usize = 8;

/// `basis` with contact `i` set to its pattern number `slot` (`slot < PATTERN_COUNT`: off, touching,
/// sticking `+d`, sticking `-d`, sliding `+d`, sliding `-d`, skidding `+d`, skidding `-d`);
/// `None` when the slot's direction is not kept. The rule's enumeration of a step's solutions
/// ([`super::resolve`]) walks these.
pub(crate) fn pattern_basis<const K: usize, const N: usize>(
    tangents: &[Tangents; K],
    basis: Basis<N>,
    i: usize,
    slot: usize,
) -> Option<Basis<N>> {
    let d = if slot.is_multiple_of(2) { Direction::Plus } else { Direction::Minus };
    let p = match slot {
        0 => Pattern::Off,
        1 => Pattern::Touch,
        2 | 3 => Pattern::Stick(d),
        4 | 5 => Pattern::Slide(d),
        _ => Pattern::Skid(d),
    };
    let kept = slot < 2 || tangents.get(i).is_some_and(|t| t.keeps(d));
    kept.then(|| with_pattern(tangents, basis, i, p))
}
