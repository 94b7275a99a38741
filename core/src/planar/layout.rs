//! [`Layout`]: the friction directions each contact keeps, and from them the LCP's variables.
//!
//! A step's LCP (`docs/formulation.md`, eq. 18) has, for `K` contacts, one normal impulse per
//! contact, one friction impulse per kept tangent direction, and one `sigma` per contact, in that
//! order:
//!
//! ```text
//! z = (p_n[0..K], p_f[contact 0: +d, -d as kept; contact 1: ...], sigma[0..K])
//! N = K + sum_k kept_k + K
//! ```
//!
//! So the paper's form (both directions everywhere) has `N = 4 K` and a layout keeping one direction
//! per contact `N = 3 K`. The variable table ([`Layout::variable`]), the owner of each row and the
//! mapping of a reduced layout into a full one ([`Layout::index_in`]) are all derived from the
//! per-contact [`Tangents`]; nothing is written out by hand.
//!
//! `N` stays a const parameter (it sizes the solver's arrays); [`Layout::new`] checks it against the
//! tangents. Build layouts in `const` items, where that check runs at compile time:
//!
//! ```
//! use meterstick_core::planar::{Layout, Tangents};
//!
//! // Two contacts, one direction each: N = 2 + 2 + 2.
//! const REDUCED: Layout<2, 6> = Layout::new([Tangents::Plus, Tangents::Minus]);
//! const FULL: Layout<2, 8> = Layout::full();
//! assert_eq!(REDUCED.index_in(&FULL), Some([0, 1, 2, 5, 6, 7]));
//! ```
//!
//! A size that does not match fails to compile:
//!
//! ```compile_fail
//! use meterstick_core::planar::{Layout, Tangents};
//! const WRONG: Layout<2, 7> = Layout::new([Tangents::Plus, Tangents::Minus]);
//! let _ = WRONG;
//! ```

/// The tangent directions a contact's friction keeps in the LCP.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Tangents {
    /// Both `+d` and `-d` (the paper's form): friction in either direction.
    Both,
    /// Only `+d`: the friction impulse on the body can only point along the contact's `+d`.
    Plus,
    /// Only `-d`.
    Minus,
}

impl Tangents {
    /// How many friction rows the contact has: 2 or 1.
    #[must_use]
    pub const fn count(self) -> usize {
        match self {
            Self::Both => 2,
            Self::Plus | Self::Minus => 1,
        }
    }

    /// `true` when the direction is kept.
    #[must_use]
    pub const fn keeps(self, direction: Direction) -> bool {
        matches!(
            (self, direction),
            (Self::Both, _) | (Self::Plus, Direction::Plus) | (Self::Minus, Direction::Minus)
        )
    }
}

/// One tangent direction of a contact: `+d` or `-d`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Direction {
    /// `+d`.
    Plus,
    /// `-d`.
    Minus,
}

impl Direction {
    /// The other direction.
    #[must_use]
    pub const fn opposite(self) -> Self {
        match self {
            Self::Plus => Self::Minus,
            Self::Minus => Self::Plus,
        }
    }
}

/// What one variable of `z` is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Variable {
    /// The normal impulse of a contact.
    Normal(u8),
    /// A friction impulse of a contact along one tangent direction.
    Friction(u8, Direction),
    /// The `sigma` of a contact (its sliding-speed estimate).
    Sigma(u8),
}

impl Variable {
    /// The contact the variable belongs to.
    #[must_use]
    pub const fn contact(self) -> usize {
        match self {
            Self::Normal(i) | Self::Friction(i, _) | Self::Sigma(i) => i as usize,
        }
    }
}

/// The LCP variables of `K` contacts with the given kept tangent directions; `N` is their count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout<const K: usize, const N: usize> {
    tangents: [Tangents; K],
    variables: [Variable; N],
}

impl<const K: usize, const N: usize> Layout<K, N> {
    /// The size of the LCP of these tangents: `2 K + sum of kept directions`.
    #[must_use]
    pub const fn size_of(tangents: &[Tangents; K]) -> usize {
        let mut n = 2 * K;
        let mut i = 0;
        while i < K {
            n += tangents[i].count();
            i += 1;
        }
        n
    }

    /// The layout of `tangents`.
    ///
    /// # Panics
    /// When `N` is not [`Self::size_of`]`(tangents)`, or `K` is 0 or above 8. In a `const` item
    /// (as intended) that is a compile error, never a run-time panic.
    #[must_use]
    pub const fn new(tangents: [Tangents; K]) -> Self {
        const { assert!(K >= 1 && K <= 8 && N <= 32, "a layout has 1..=8 contacts and at most 32 variables") };
        assert!(Self::size_of(&tangents) == N, "N must be 2 K + the kept tangent directions");
        let mut variables = [Variable::Normal(0); N];
        let mut i = 0;
        while i < K {
            variables[i] = Variable::Normal(i as u8);
            variables[N - K + i] = Variable::Sigma(i as u8);
            i += 1;
        }
        let (mut i, mut j) = (0, K);
        while i < K {
            if tangents[i].keeps(Direction::Plus) {
                variables[j] = Variable::Friction(i as u8, Direction::Plus);
                j += 1;
            }
            if tangents[i].keeps(Direction::Minus) {
                variables[j] = Variable::Friction(i as u8, Direction::Minus);
                j += 1;
            }
            i += 1;
        }
        Self { tangents, variables }
    }

    /// The layout of `tangents`, or `None` when `N` does not match them (for layouts chosen at run
    /// time; [`Self::new`] in a `const` item checks at compile time).
    #[must_use]
    pub const fn try_new(tangents: [Tangents; K]) -> Option<Self> {
        if Self::size_of(&tangents) == N { Some(Self::new(tangents)) } else { None }
    }

    /// The paper's form: both directions at every contact (`N = 4 K`).
    ///
    /// # Panics
    /// As [`Self::new`].
    #[must_use]
    pub const fn full() -> Self {
        Self::new([Tangents::Both; K])
    }

    /// The kept directions of each contact.
    #[must_use]
    pub const fn tangents(&self) -> &[Tangents; K] {
        &self.tangents
    }

    /// What variable `j` is (`j < N`; the last variable for `j >= N`).
    #[must_use]
    pub const fn variable(&self, j: usize) -> Variable {
        if j < N { self.variables[j] } else { self.variables[N - 1] }
    }

    /// Every variable, in order.
    #[must_use]
    pub const fn variables(&self) -> &[Variable; N] {
        &self.variables
    }

    /// Index of the first friction row (`K`).
    pub const FRICTION_START: usize = K;
    /// Index of the first `sigma` (`N - K`); the impulses are the variables before it.
    pub const SIGMA_START: usize = N - K;

    /// `true` when every contact keeps both directions.
    #[must_use]
    pub const fn is_full(&self) -> bool {
        N == 4 * K
    }

    /// Where each of this layout's variables sits in `full`'s, or `None` when `full` lacks one of
    /// them (it is then not a full layout of this one).
    #[must_use]
    pub const fn index_in<const NF: usize>(&self, full: &Layout<K, NF>) -> Option<[usize; N]> {
        // Where the variable would sit in `full`'s order (normals, friction rows contact by
        // contact with `+d` before `-d`, sigmas), then one comparison: O(N K), not a search.
        let mut map = [0usize; N];
        let mut j = 0;
        while j < N {
            let v = self.variables[j];
            let k = match v {
                Variable::Normal(i) => i as usize,
                Variable::Sigma(i) => NF - K + i as usize,
                Variable::Friction(i, direction) => {
                    let mut k = K;
                    let mut c = 0;
                    while c < i as usize && c < K {
                        k += full.tangents[c].count();
                        c += 1;
                    }
                    if matches!(direction, Direction::Minus)
                        && (i as usize) < K
                        && full.tangents[i as usize].keeps(Direction::Plus)
                    {
                        k += 1;
                    }
                    k
                }
            };
            if k >= NF || !variables_equal(v, full.variables[k]) {
                return None;
            }
            map[j] = k;
            j += 1;
        }
        Some(map)
    }

    /// The direction contact `i` keeps when it keeps exactly one and `full` keeps both: then the
    /// other one is dropped and must be checked after each step ([`super::Stepper`]).
    #[must_use]
    pub const fn kept_alone<const NF: usize>(&self, full: &Layout<K, NF>, i: usize) -> Option<Direction> {
        if i >= K || full.tangents[i].count() != 2 {
            return None;
        }
        match self.tangents[i] {
            Tangents::Plus => Some(Direction::Plus),
            Tangents::Minus => Some(Direction::Minus),
            Tangents::Both => None,
        }
    }
}

/// `==` for [`Variable`] in a `const fn`.
const fn variables_equal(a: Variable, b: Variable) -> bool {
    match (a, b) {
        (Variable::Normal(x), Variable::Normal(y))
        | (Variable::Sigma(x), Variable::Sigma(y))
        | (Variable::Friction(x, Direction::Plus), Variable::Friction(y, Direction::Plus))
        | (Variable::Friction(x, Direction::Minus), Variable::Friction(y, Direction::Minus)) => x == y,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_meter_sticks_layouts() {
        const FULL: Layout<2, 8> = Layout::full();
        const REDUCED: Layout<2, 6> = Layout::new([Tangents::Plus, Tangents::Minus]);
        use Direction::{Minus, Plus};
        use Variable::{Friction, Normal, Sigma};
        assert_eq!(
            FULL.variables(),
            &[
                Normal(0),
                Normal(1),
                Friction(0, Plus),
                Friction(0, Minus),
                Friction(1, Plus),
                Friction(1, Minus),
                Sigma(0),
                Sigma(1)
            ]
        );
        assert_eq!(
            REDUCED.variables(),
            &[Normal(0), Normal(1), Friction(0, Plus), Friction(1, Minus), Sigma(0), Sigma(1)]
        );
        assert_eq!(REDUCED.index_in(&FULL), Some([0, 1, 2, 5, 6, 7]));
        assert_eq!(REDUCED.kept_alone(&FULL, 0), Some(Plus));
        assert_eq!(REDUCED.kept_alone(&FULL, 1), Some(Minus));
        assert_eq!(FULL.kept_alone(&FULL, 0), None);
        assert!(FULL.is_full() && !REDUCED.is_full());
        assert_eq!((Layout::<2, 6>::FRICTION_START, Layout::<2, 6>::SIGMA_START), (2, 4));
    }

    /// [`Layout::index_in`]'s formula against a search of the other layout's variables, for every
    /// pair of three-contact layouts (each contact keeping `+d`, `-d` or both).
    #[test]
    fn index_in_agrees_with_a_search() {
        fn search<const N: usize, const NF: usize>(
            a: &Layout<3, N>,
            b: &Layout<3, NF>,
        ) -> Option<[usize; N]> {
            let mut map = [0; N];
            for (j, v) in a.variables().iter().enumerate() {
                map[j] = b.variables().iter().position(|w| w == v)?;
            }
            Some(map)
        }
        fn against<const N: usize, const NF: usize>(all: &[[Tangents; 3]]) -> usize {
            let mut pairs = 0;
            for &ta in all {
                for &tb in all {
                    if let (Some(a), Some(b)) = (Layout::<3, N>::try_new(ta), Layout::<3, NF>::try_new(tb)) {
                        assert_eq!(a.index_in(&b), search(&a, &b), "{ta:?} in {tb:?}");
                        pairs += 1;
                    }
                }
            }
            pairs
        }
        let kinds = [Tangents::Plus, Tangents::Minus, Tangents::Both];
        let mut all = Vec::new();
        for a in kinds {
            for b in kinds {
                for c in kinds {
                    all.push([a, b, c]);
                }
            }
        }
        let pairs = against::<9, 9>(&all)
            + against::<9, 10>(&all)
            + against::<10, 11>(&all)
            + against::<10, 12>(&all)
            + against::<11, 12>(&all)
            + against::<12, 12>(&all)
            + against::<11, 10>(&all);
        // 8x8 + 8x12 + 12x6 + 12x1 + 6x1 + 1x1 + 6x12 pairs of layouts.
        assert_eq!(pairs, 64 + 96 + 72 + 12 + 6 + 1 + 72);
    }

    #[test]
    fn a_layout_that_is_not_inside_another_has_no_map() {
        const A: Layout<2, 6> = Layout::new([Tangents::Plus, Tangents::Minus]);
        const B: Layout<2, 7> = Layout::new([Tangents::Both, Tangents::Plus]);
        const C: Layout<3, 11> = Layout::new([Tangents::Both, Tangents::Plus, Tangents::Both]);
        assert_eq!(A.index_in(&B), None); // B lacks contact 1's -d
        assert_eq!(C.variable(5), Variable::Friction(1, Direction::Plus));
        assert_eq!(C.variable(7), Variable::Friction(2, Direction::Minus));
        assert_eq!(C.variable(8), Variable::Sigma(0));
        assert_eq!(Layout::<3, 11>::size_of(C.tangents()), 11);
    }
}
