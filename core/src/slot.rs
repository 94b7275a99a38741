//! The slot-layout codec of a contact LCP (`docs/formulation.md`, "One step"), one for every
//! engine of the crate: a contact's variables `(p_n, p_+d, p_-d, sigma)` (its *slot*), which of
//! them are basic in a complementary basis (its [`Pattern`]), read from a basis mask and written
//! into one, and the one list of the eight patterns a contact takes ([`PATTERNS`]).
//!
//! For `k` contacts with both tangent directions the variables are
//!
//! ```text
//! z = (p_n[0..k], p_+d[0], p_-d[0], ..., p_+d[k-1], p_-d[k-1], sigma[0..k])
//! slot j: rows (j, k + 2 j, k + 2 j + 1, 3 k + j)            ([`full_rows`], [`Slot::full`])
//! ```
//!
//! the planar engine's full layout and every step of the multibody engine. A planar reduced
//! layout (`planar::Layout`) keeps one tangent direction at some contacts: such a slot has no row
//! for the other direction ([`Slot::new`] with `None`), its pattern's bit for it always clear,
//! and a pattern along it has no basis there ([`Slot::holds`]).
//!
//! A pattern is four bits, one per variable in the slot's order (bit 0 `p_n`, 1 `p_+d`, 2 `p_-d`,
//! 3 `sigma`): reading and writing are a few shifts and masks, which the engines' candidate
//! paths inline. Of the sixteen, eight are a contact's (complementarity with the cone leaves no
//! other): separated ([`Pattern::OFF`]), touching without friction ([`Pattern::TOUCH`]), sticking
//! (`p_n`, `p_f` basic), sliding (`p_n`, `p_f`, `sigma`: friction on the cone's edge) and skidding
//! (`p_f` at zero and `sigma`: separated while the support slips past) along each direction.
//!
//! [`each_basis`] walks the bases of several slots' patterns (an odometer, the first slot the
//! fastest digit): the rule's searches (`planar/resolve.rs`, `multibody/resolve.rs`) enumerate
//! their bases with it.

use crate::lcp::Basis;
use crate::planar::Direction;

/// The basic variables of one contact's slot: bit 0 `p_n`, 1 `p_+d`, 2 `p_-d`, 3 `sigma`
/// (module docs). Any four bits; [`Self::is_listed`] says whether they are one of [`PATTERNS`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Pattern(u8);

impl Pattern {
    /// Nothing basic: separated (or touching with no impulse).
    pub(crate) const OFF: Self = Self(0b0000);
    /// Only `p_n` basic: touching with no friction impulse (frictionless, or a slip the kept
    /// directions do not oppose).
    pub(crate) const TOUCH: Self = Self(0b0001);
    /// `p_n` and `p_+d` basic: sticking.
    pub(crate) const STICK_PLUS: Self = Self(0b0011);
    /// `p_n` and `p_-d` basic: sticking.
    pub(crate) const STICK_MINUS: Self = Self(0b0101);
    /// `p_n`, `p_+d` and `sigma` basic: sliding (friction along `+d` on the cone's edge).
    pub(crate) const SLIDE_PLUS: Self = Self(0b1011);
    /// `p_n`, `p_-d` and `sigma` basic: sliding.
    pub(crate) const SLIDE_MINUS: Self = Self(0b1101);
    /// `p_+d` (at zero) and `sigma` basic: separated while the support slips past.
    pub(crate) const SKID_PLUS: Self = Self(0b1010);
    /// `p_-d` (at zero) and `sigma` basic.
    pub(crate) const SKID_MINUS: Self = Self(0b1100);
    /// Every variable of the slot: its mask in a basis ([`Slot::bits`]).
    pub(crate) const ALL: Self = Self(0b1111);

    /// Its bits.
    #[inline]
    pub(crate) const fn bits(self) -> u8 {
        self.0
    }

    /// `true` when it is one of [`PATTERNS`] (a contact's).
    #[inline]
    pub(crate) fn is_listed(self) -> bool {
        PATTERNS.contains(&self)
    }

    /// `true` for sticking along either direction.
    #[inline]
    pub(crate) fn is_sticking(self) -> bool {
        self == Self::STICK_PLUS || self == Self::STICK_MINUS
    }

    /// The direction whose friction impulse is basic: `+d` when `p_+d` is (whatever else is),
    /// else `-d` when `p_-d` is, else `None`.
    #[inline]
    pub(crate) const fn direction(self) -> Option<Direction> {
        if self.0 & 0b0010 != 0 {
            Some(Direction::Plus)
        } else if self.0 & 0b0100 != 0 {
            Some(Direction::Minus)
        } else {
            None
        }
    }

    /// The same pattern with its friction along `direction` (sticking, sliding or skidding as
    /// before); a pattern without a friction impulse as it is.
    #[inline]
    pub(crate) const fn along(self, direction: Direction) -> Self {
        if self.0 & 0b0110 == 0 {
            return self;
        }
        let friction = match direction {
            Direction::Plus => 0b0010,
            Direction::Minus => 0b0100,
        };
        Self(self.0 & 0b1001 | friction)
    }

    /// The same pattern without `p_n`: a contact lifting off (sticking and touching become
    /// [`Self::OFF`]-like, sliding becomes skidding).
    #[inline]
    pub(crate) const fn lifted(self) -> Self {
        Self(self.0 & !1)
    }
}

/// The eight patterns of a contact (module docs), in the order the multibody stepper's
/// candidates and its retry try them: sticking along `+d`, `-d`; sliding along `+d`, `-d`;
/// touching without friction; separated; skidding along `+d`, `-d`. An engine that walks them in
/// another order (the planar rule's enumeration) names its order from these.
pub(crate) const PATTERNS: [Pattern; 8] = [
    Pattern::STICK_PLUS,
    Pattern::STICK_MINUS,
    Pattern::SLIDE_PLUS,
    Pattern::SLIDE_MINUS,
    Pattern::TOUCH,
    Pattern::OFF,
    Pattern::SKID_PLUS,
    Pattern::SKID_MINUS,
];

/// Slot `j`'s rows among `k` slots that all keep both directions: `p_n`, `p_+d`, `p_-d`, `sigma`
/// (the bits of a [`Pattern`] in order; module docs).
#[inline]
pub(crate) const fn full_rows(k: usize, j: usize) -> [usize; 4] {
    [j, k + 2 * j, k + 2 * j + 1, 3 * k + j]
}

/// The rows of one contact's variables in the LCP: `p_n`, `p_+d` and `p_-d` where kept, `sigma`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Slot {
    normal: usize,
    friction: [Option<usize>; 2],
    sigma: usize,
}

/// The mask of row `v` in a basis (none for a row at or beyond 32, which no basis has).
#[inline(always)]
#[allow(clippy::inline_always)] // one shift: a call would cost more than it
const fn bit(v: Option<usize>) -> u32 {
    match v {
        Some(v) if v < 32 => 1 << v,
        _ => 0,
    }
}

impl Slot {
    /// The slot of rows `normal`, `friction` (`[+d, -d]`, `None` for a direction the layout does
    /// not keep) and `sigma`.
    #[inline]
    pub(crate) const fn new(normal: usize, friction: [Option<usize>; 2], sigma: usize) -> Self {
        Self { normal, friction, sigma }
    }

    /// Slot `j` among `k` that all keep both directions ([`full_rows`]).
    #[inline]
    pub(crate) const fn full(k: usize, j: usize) -> Self {
        let [normal, plus, minus, sigma] = full_rows(k, j);
        Self { normal, friction: [Some(plus), Some(minus)], sigma }
    }

    /// The friction rows `[+d, -d]`, `None` where not kept.
    #[inline]
    pub(crate) const fn friction(self) -> [Option<usize>; 2] {
        self.friction
    }

    /// The `sigma` row.
    #[inline]
    pub(crate) const fn sigma(self) -> usize {
        self.sigma
    }

    /// The mask of `pattern`'s variables of this slot (a bit of a direction not kept: none).
    /// Inlined into each caller, as [`Self::write`] and [`Self::set`]: a few bit operations once
    /// the slot and the pattern are known there, where a call costs more (out of line, each
    /// candidate basis a planar step tries pays for one: `planar/candidates.rs`).
    #[inline(always)]
    #[allow(clippy::inline_always)] // measured, as said above
    pub(crate) fn bits(self, pattern: Pattern) -> u32 {
        let p = pattern.0;
        let on = |b: u8, v: u32| if p & b == 0 { 0 } else { v };
        on(1, bit(Some(self.normal)))
            | on(2, bit(self.friction[0]))
            | on(4, bit(self.friction[1]))
            | on(8, bit(Some(self.sigma)))
    }

    /// The slot's pattern in the basis mask `mask` (bit `v`: `z_v` basic); a direction not kept
    /// reads as not basic.
    #[inline]
    pub(crate) fn read(self, mask: u32) -> Pattern {
        let basic = |v: u32, b: u8| if mask & v == 0 { 0 } else { b };
        Pattern(
            basic(bit(Some(self.normal)), 1)
                | basic(bit(self.friction[0]), 2)
                | basic(bit(self.friction[1]), 4)
                | basic(bit(Some(self.sigma)), 8),
        )
    }

    /// `mask` with the slot's variables set to `pattern` ([`Self::read`]'s inverse where the
    /// slot [`Self::holds`] it).
    #[inline(always)]
    #[allow(clippy::inline_always)] // as `bits`
    pub(crate) fn write(self, mask: u32, pattern: Pattern) -> u32 {
        mask & !self.bits(Pattern::ALL) | self.bits(pattern)
    }

    /// `basis` with the slot's variables set to `pattern` ([`Self::write`]).
    #[inline(always)]
    #[allow(clippy::inline_always)] // as `write`
    pub(crate) fn set<const N: usize>(self, basis: Basis<N>, pattern: Pattern) -> Basis<N> {
        Basis::from_z_mask(self.write(basis.z_mask(), pattern))
    }

    /// `true` when the slot has a row for each of `pattern`'s variables (a reduced layout's slot
    /// holds no pattern along the direction it drops).
    #[inline]
    pub(crate) const fn holds(self, pattern: Pattern) -> bool {
        (pattern.0 & 2 == 0 || self.friction[0].is_some())
            && (pattern.0 & 4 == 0 || self.friction[1].is_some())
    }
}

/// Every slot's [`Pattern`] of a basis mask of `k` full slots ([`full_rows`]), slot by slot in
/// order: the normals', frictions' and sigmas' bits shifted out as it goes, a few operations a
/// slot where [`Slot::read`] would form each slot's four bits anew (the multibody step reads
/// every slot's after each step: measured, the stack's step 0.8% dearer with a read a slot).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FullPatterns {
    normals: u32,
    frictions: u32,
    sigmas: u32,
}

impl FullPatterns {
    /// The patterns of `mask`'s `k` slots (`k <= 8`, the most a basis of 32 variables has;
    /// a larger `k` reads as 8).
    #[inline]
    pub(crate) const fn new(mask: u32, k: usize) -> Self {
        let k = if k < 8 { k } else { 8 };
        // `3 k <= 24 < 32`: every shift in range.
        Self { normals: mask, frictions: mask >> k, sigmas: mask >> (3 * k) }
    }

    /// The next slot's pattern (the first slot's first).
    #[inline]
    pub(crate) fn next_pattern(&mut self) -> Pattern {
        let bits = self.normals & 1 | (self.frictions & 3) << 1 | (self.sigmas & 1) << 3;
        (self.normals, self.frictions, self.sigmas) =
            (self.normals >> 1, self.frictions >> 2, self.sigmas >> 1);
        // Four bits: exact.
        Pattern(u8::try_from(bits & 0b1111).unwrap_or(0))
    }
}

/// Calls `visit(code, mask)` for each basis of `slots`' patterns from `patterns`, the other
/// variables as in `base`: `patterns.len()^slots.len()` codes, `code`'s digits in base
/// `patterns.len()` the slots' patterns' indices, the first slot the fastest digit; a code whose
/// pattern a slot does not hold ([`Slot::holds`]) is passed over (the others keep their numbers).
/// Nothing when the count does not fit a `usize`.
#[inline]
pub(crate) fn each_basis(base: u32, slots: &[Slot], patterns: &[Pattern], mut visit: impl FnMut(usize, u32)) {
    let Ok(digits) = u32::try_from(slots.len()) else { return };
    let Some(count) = patterns.len().checked_pow(digits) else { return };
    'bases: for code in 0..count {
        let mut mask = base;
        let mut rest = code;
        for slot in slots {
            let Some(&pattern) = patterns.get(rest % patterns.len()) else { return };
            if !slot.holds(pattern) {
                continue 'bases;
            }
            mask = slot.write(mask, pattern);
            rest /= patterns.len();
        }
        visit(code, mask);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reading is writing's inverse for every listed pattern on a full slot, and the eight are
    /// the sixteen bit patterns that complementarity with the cone admits.
    #[test]
    fn read_inverts_write_and_the_list_is_eight_distinct_patterns() {
        for k in 1..=8 {
            for j in 0..k {
                let slot = Slot::full(k, j);
                for p in PATTERNS {
                    let mask = slot.write(u32::MAX, p);
                    assert_eq!(slot.read(mask), p);
                    assert_eq!(mask | slot.bits(Pattern::ALL), u32::MAX);
                    assert!(slot.holds(p));
                }
            }
        }
        // Shifted out slot by slot, as read one by one.
        for mask in [0u32, u32::MAX, 0x5a5a_a5a5, 0x1234_5678] {
            for k in 1..=8 {
                let mut all = FullPatterns::new(mask, k);
                for j in 0..k {
                    assert_eq!(all.next_pattern(), Slot::full(k, j).read(mask), "{mask:x} {k} {j}");
                }
            }
        }
        for (a, p) in PATTERNS.iter().enumerate() {
            assert!(PATTERNS[a + 1..].iter().all(|q| q != p));
            assert!(p.is_listed());
            // Never both directions; sigma only with a friction impulse.
            assert_ne!(p.bits() & 0b0110, 0b0110);
            assert!(p.bits() & 8 == 0 || p.direction().is_some());
        }
    }

    /// A reduced slot (one kept direction) holds no pattern along the other, reads it as not
    /// basic, and a pattern turned to the kept direction is held.
    #[test]
    fn a_reduced_slot_holds_its_direction_only() {
        let slot = Slot::new(0, [None, Some(2)], 4);
        assert!(!slot.holds(Pattern::STICK_PLUS) && slot.holds(Pattern::STICK_MINUS));
        assert_eq!(slot.read(u32::MAX), Pattern(0b1101));
        assert_eq!(Pattern::SLIDE_PLUS.along(Direction::Minus), Pattern::SLIDE_MINUS);
        assert_eq!(Pattern::TOUCH.along(Direction::Minus), Pattern::TOUCH);
        assert_eq!(Pattern::SLIDE_MINUS.lifted(), Pattern::SKID_MINUS);
        assert_eq!(slot.write(0, Pattern::SKID_MINUS), 0b10100);
    }

    /// The odometer: every code in order, the first slot the fastest digit, a slot that does not
    /// hold a pattern passing over its codes.
    #[test]
    fn each_basis_counts_the_first_slot_fastest() {
        let slots = [Slot::full(2, 0), Slot::new(1, [Some(5), None], 7)];
        let mut seen = Vec::new();
        each_basis(0, &slots, &PATTERNS, |code, mask| seen.push((code, mask)));
        // Slot 1 holds 5 of the 8 (not STICK_MINUS, SLIDE_MINUS, SKID_MINUS).
        assert_eq!(seen.len(), 8 * 5);
        assert!(seen.windows(2).all(|w| w[0].0 < w[1].0));
        for &(code, mask) in &seen {
            assert_eq!(slots[0].read(mask), PATTERNS[code % 8]);
            assert_eq!(slots[1].read(mask), PATTERNS[code / 8]);
        }
    }
}
