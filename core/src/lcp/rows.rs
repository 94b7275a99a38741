//! [`Rows`]: a set of rows of an LCP, as bits in 32-bit words.

/// A set of rows `i < N` of an `N`-row LCP, in `WORDS` 32-bit words: row `i` is bit `i % 32` of
/// word `i / 32` (`N <= 32 WORDS`, checked by the types that hold one, [`super::Basis`] and
/// [`super::Lemke`], with `WORDS` 1 or 2). Every row passed to it is below `N` (the callers' loops'
/// bound, or checked by the caller: [`super::Basis::set_z_basic`]), so no member is at or above
/// `N`.
///
/// Words of 32 bits because the cores this runs on are 32-bit: a 64-bit shift, count or
/// trailing-zero count takes several instructions there, where a 32-bit one takes one or two.
/// With one word (`N <= 32`) every operation is the `u32` mask's own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Rows<const N: usize, const WORDS: usize> {
    words: [u32; WORDS],
}

impl<const N: usize> Rows<N, 1> {
    /// The set of rows whose bit is set in `mask`, rows at or above `N` left out.
    pub(crate) const fn from_mask(mask: u32) -> Self {
        let keep = if N >= 32 { u32::MAX } else { (1u32 << N) - 1 };
        Self { words: [mask & keep] }
    }

    /// The set as the bits of a `u32`.
    pub(crate) const fn mask(self) -> u32 {
        self.words[0]
    }
}

impl<const N: usize, const WORDS: usize> Rows<N, WORDS> {
    /// The empty set.
    pub(crate) const EMPTY: Self = Self { words: [0; WORDS] };

    /// The word that holds row `i < N` (`WORDS` is 1 or 2; the index is below it for any `i`: no
    /// panic path).
    const fn word(i: usize) -> usize {
        if WORDS == 1 { 0 } else { (i >> 5) & 1 }
    }

    /// `true` when row `i` is in the set; `i < N` (the callers' loops' bound).
    pub(crate) const fn contains(self, i: usize) -> bool {
        (self.words[Self::word(i)] >> (i & 31)) & 1 == 1
    }

    /// Puts row `i < N` in the set.
    pub(crate) const fn insert(&mut self, i: usize) {
        self.words[Self::word(i)] |= 1 << (i & 31);
    }

    /// Takes row `i < N` out of the set.
    pub(crate) const fn remove(&mut self, i: usize) {
        self.words[Self::word(i)] &= !(1 << (i & 31));
    }

    /// How many rows are in the set.
    pub(crate) const fn len(self) -> u32 {
        let low = self.words[0].count_ones();
        if WORDS == 1 { low } else { low + self.words[WORDS - 1].count_ones() }
    }

    /// The lowest row in the set; `N - 1` for the empty set (so that the row is always in bounds).
    pub(crate) fn first(self) -> usize {
        let first = if WORDS == 1 || self.words[0] != 0 {
            self.words[0].trailing_zeros() as usize
        } else {
            32 + self.words[WORDS - 1].trailing_zeros() as usize
        };
        first.min(N - 1)
    }
}
