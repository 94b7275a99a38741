//! [`Basis`]: which variable of each complementary pair `(w_i, z_i)` is basic.

/// A complementary basis of an `N`-sized LCP: for each `i`, either `z_i` or `w_i` is basic.
///
/// Stored as a bit mask (bit `i` set: `z_i` basic), so it is `Copy`, tiny, and can be kept
/// from one time step to the next for a warm start. `N` may be at most 64; the mask as a `u32`
/// ([`Self::from_z_mask`], [`Self::z_mask`]) is for `N <= 32`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Basis<const N: usize> {
    z_basic: u64,
}

impl<const N: usize> Default for Basis<N> {
    fn default() -> Self {
        Self::all_w()
    }
}

impl<const N: usize> Basis<N> {
    const CHECK: () = assert!(N > 0 && N <= 64, "Basis<N> needs 1 <= N <= 64");
    const NARROW: () = assert!(N <= 32, "a Basis<N> as a u32 mask needs N <= 32");

    /// The trivial basis: every `w_i` basic (the solution `z = 0` when `q >= 0`).
    #[must_use]
    pub const fn all_w() -> Self {
        let () = Self::CHECK;
        Self { z_basic: 0 }
    }

    /// Builds a basis from the bit mask of basic `z_i` (bits at or above `N` are ignored);
    /// `N <= 32` (checked at compile time).
    #[must_use]
    pub const fn from_z_mask(mask: u32) -> Self {
        let () = Self::CHECK;
        let () = Self::NARROW;
        let keep = if N == 32 { u32::MAX } else { (1u32 << N) - 1 };
        Self { z_basic: (mask & keep) as u64 }
    }

    /// The bit mask of basic `z_i`; `N <= 32` (checked at compile time).
    #[must_use]
    #[allow(clippy::cast_possible_truncation)] // N <= 32: the bits above 32 are zero
    pub const fn z_mask(self) -> u32 {
        let () = Self::NARROW;
        self.z_basic as u32
    }

    /// The bit mask of basic `z_i`, any `N`.
    #[must_use]
    pub(crate) const fn z_bits(self) -> u64 {
        self.z_basic
    }

    /// How many `z_i` are basic.
    #[must_use]
    pub const fn z_count(self) -> u32 {
        self.z_basic.count_ones()
    }

    /// `true` when `z_i` is basic (`i < N`).
    #[must_use]
    pub const fn is_z_basic(self, i: usize) -> bool {
        i < N && (self.z_basic >> i) & 1 == 1
    }

    /// Marks `z_i` basic (`true`) or `w_i` basic (`false`); `i >= N` is ignored.
    pub const fn set_z_basic(&mut self, i: usize, z_basic: bool) {
        if i < N {
            if z_basic {
                self.z_basic |= 1 << i;
            } else {
                self.z_basic &= !(1 << i);
            }
        }
    }
}
