//! [`Basis`]: which variable of each complementary pair `(w_i, z_i)` is basic.

use super::rows::Rows;

/// A complementary basis of an `N`-sized LCP: for each `i`, either `z_i` or `w_i` is basic.
///
/// Stored as the set of rows whose `z_i` is basic, as bits in `WORDS` 32-bit words, so it is
/// `Copy`, tiny, and can be kept from one time step to the next for a warm start. `N` may be at
/// most 64, and at most 32 `WORDS`: one word (the default) for `N <= 32`, two above (checked at
/// compile time). With one word the basis is a `u32` mask ([`Self::from_z_mask`],
/// [`Self::z_mask`]), and costs what one does: a basis of two words is `Basis<N, 2>`, used with
/// `Lemke<T, N, 2>`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Basis<const N: usize, const WORDS: usize = 1> {
    z_basic: Rows<N, WORDS>,
}

impl<const N: usize, const WORDS: usize> Default for Basis<N, WORDS> {
    fn default() -> Self {
        Self::all_w()
    }
}

impl<const N: usize> Basis<N> {
    /// Builds a basis from the bit mask of basic `z_i` (bits at or above `N` are ignored).
    #[must_use]
    pub const fn from_z_mask(mask: u32) -> Self {
        let () = Self::CHECK;
        Self { z_basic: Rows::from_mask(mask) }
    }

    /// The bit mask of basic `z_i`.
    #[must_use]
    pub const fn z_mask(self) -> u32 {
        self.z_basic.mask()
    }
}

impl<const N: usize, const WORDS: usize> Basis<N, WORDS> {
    const CHECK: () = assert!(
        N > 0 && N <= 64 && (WORDS == 1 || WORDS == 2) && N <= 32 * WORDS,
        "Basis<N, WORDS> needs 1 <= N <= 64 and N <= 32 WORDS, WORDS 1 or 2"
    );

    /// The trivial basis: every `w_i` basic (the solution `z = 0` when `q >= 0`).
    #[must_use]
    pub const fn all_w() -> Self {
        let () = Self::CHECK;
        Self { z_basic: Rows::EMPTY }
    }

    /// How many `z_i` are basic.
    #[must_use]
    pub const fn z_count(self) -> u32 {
        self.z_basic.len()
    }

    /// The rows whose `z_i` is basic.
    pub(crate) const fn z_rows(self) -> Rows<N, WORDS> {
        self.z_basic
    }

    /// `true` when `z_i` is basic (`i < N`).
    #[must_use]
    pub const fn is_z_basic(self, i: usize) -> bool {
        i < N && self.z_basic.contains(i)
    }

    /// Marks `z_i` basic (`true`) or `w_i` basic (`false`); `i >= N` is ignored.
    pub const fn set_z_basic(&mut self, i: usize, z_basic: bool) {
        if i < N {
            if z_basic {
                self.z_basic.insert(i);
            } else {
                self.z_basic.remove(i);
            }
        }
    }
}
