//! The slot layout of a multibody step's LCP (`docs/formulation.md`, "One step"): the `k` active
//! candidates' variables `(p_n[1..k], p_+d[1], p_-d[1], ..., sigma[1..k])`, and each slot's
//! pattern of basic variables, read from and written into a basis. One codec, which the stepper's
//! paths and the rule's search share.

use crate::lcp::Basis;

/// The basic variables of one candidate's slot: bit 0 `p_n`, 1 `p_+d`, 2 `p_-d`, 3 `sigma`.
pub(super) type Pattern = u8;

/// Touching without friction (`p_n` basic).
pub(super) const TOUCH: Pattern = 0b0001;

/// The eight patterns of a contact the candidates and a retry try, in order: sticking with `p_+d`,
/// `p_-d`; sliding along `+d`, `-d`; touching without friction; separated; separated while
/// slipping along `+d`, `-d`.
pub(super) const PATTERNS: [Pattern; 8] = [0b0011, 0b0101, 0b1011, 0b1101, 0b0001, 0b0000, 0b1010, 0b1100];

/// Slot `j`'s variables among `k` slots: `p_n`, `p_+d`, `p_-d`, `sigma` (the bits of a
/// [`Pattern`] in order).
#[inline]
pub(super) const fn slot_rows(k: usize, j: usize) -> [usize; 4] {
    [j, k + 2 * j, k + 2 * j + 1, 3 * k + j]
}

/// Slot `j`'s [`Pattern`] (among `k` slots) in the basis mask `mask` (bit `v`: `z_v` basic): the
/// bits of its rows `p_n`, `p_+d` and `p_-d` (adjacent), `sigma`.
#[inline]
pub(super) fn slot_pattern(mask: u32, k: usize, j: usize) -> Pattern {
    let [n, plus, _, sigma] = slot_rows(k, j);
    let bits = |v: usize, width: u32| mask.checked_shr(v as u32).unwrap_or(0) & ((1 << width) - 1);
    (bits(n, 1) | bits(plus, 2) << 1 | bits(sigma, 1) << 3) as Pattern
}

/// The basis mask of slot `j`'s [`Pattern`] `pattern` (among `k` slots): [`slot_pattern`]'s
/// inverse.
#[inline]
pub(super) fn pattern_bits(pattern: Pattern, k: usize, j: usize) -> u32 {
    let [n, plus, _, sigma] = slot_rows(k, j);
    let place = |bits: u8, v: usize| u32::from(bits).checked_shl(v as u32).unwrap_or(0);
    place(pattern & 1, n) | place(pattern >> 1 & 3, plus) | place(pattern >> 3 & 1, sigma)
}

/// `basis` with slot `j`'s variables (among `k` slots) set to `pattern`.
#[inline]
pub(super) fn with_pattern<const N: usize>(
    mut basis: Basis<N>,
    k: usize,
    j: usize,
    pattern: Pattern,
) -> Basis<N> {
    for (bit, row) in slot_rows(k, j).into_iter().enumerate() {
        basis.set_z_basic(row, pattern >> bit & 1 == 1);
    }
    basis
}
