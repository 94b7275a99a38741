//! One answer where a step's LCP has several that move the bodies differently
//! (`docs/formulation.md`, "One answer: the rule"): the least kinetic energy after the step
//! (maximum dissipation); energies within a tie of each other by the smallest `||z||_1`; then the
//! first offered. The same rule as the independent reference's (`reference/src/step.rs`).
//!
//! Written for the velocities `(vx, vy, omega)` of `B` bodies with a diagonal mass metric: one
//! planar body has `B = 1` (metric `1, 1, J/m` per unit mass), several bodies each their own
//! `m, m, J` block (`core/src/multibody/resolve.rs`). The caller enumerates its verified solutions
//! and offers them to a [`Choice`]; nothing here knows how a solution was found.

use crate::real::{Real, max};

/// What the rule compares of one verified solution of a step's LCP.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Answer<T, const B: usize> {
    /// Each body's velocities `(vx, vy, omega)` after the step.
    pub velocity: [[T; 3]; B],
    /// `||z||_1`: the sum of the LCP's unknowns (all non-negative).
    pub impulse_sum: T,
}

impl<T: Real, const B: usize> Answer<T, B> {
    /// The answer whose velocities after the step are `velocity` and whose LCP unknowns are `z`
    /// (all non-negative: their sum is `||z||_1`).
    #[must_use]
    pub fn of<const N: usize>(velocity: [[T; 3]; B], z: &[T; N]) -> Self {
        Self { velocity, impulse_sum: z.iter().fold(T::zero(), |s, &x| s + x) }
    }
}

/// The rule's metric and tolerances for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Rule<T, const B: usize> {
    /// The kinetic energy's diagonal metric: `E = sum_b sum_k metric_bk v_bk^2`.
    metric: [[T; 3]; B],
    /// The length that turns coordinate `k` of body `b` into a speed (1 for a linear velocity, the
    /// body's half size for an angular one).
    reach: [[T; 3]; B],
    /// Two velocities whose coordinate (times its reach) differ by more than this move the
    /// bodies differently: `max(1e-9, 256 eps) S`.
    velocity_tolerance: T,
    /// Energies within this of each other tie: `max(1e-12, (256 eps)^2) S^2`, the energy of a
    /// velocity within the velocity tolerance of rest (in f32, `256 eps S^2` let a rod slip at
    /// `1e-3 S` count as at rest).
    energy_tie: T,
    /// Sums within this fraction of each other tie: `max(1e-12, 256 eps)`.
    sum_tie: T,
}

impl<T: Real, const B: usize> Rule<T, B> {
    /// The rule for a step whose speed scale is `speed` (`S`: the fastest support's speed and the
    /// bodies' free velocities, each coordinate times its `reach`), with the energy's `metric`.
    /// The reference's tolerances (`1e-9 S`, `1e-12 S^2`, `1e-12`) where the scalar carries them;
    /// in f32 `256 eps S`, `(256 eps S)^2` and `256 eps`.
    #[must_use]
    pub fn new(metric: [[T; 3]; B], reach: [[T; 3]; B], speed: T) -> Self {
        let round_off = T::of(256.0) * T::EPS;
        let relative = |floor: f64| max(T::of(floor), round_off);
        let speed = max(speed, T::TINY);
        Self {
            metric,
            reach,
            velocity_tolerance: Self::velocity_tolerance_at(speed),
            energy_tie: max(T::of(1e-12), round_off * round_off) * speed * speed,
            sum_tie: relative(1e-12),
        }
    }

    /// Two velocities whose coordinates (times their reach) differ by more than this move the
    /// bodies differently: `max(1e-9, 256 eps) S`.
    #[must_use]
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    pub(crate) const fn velocity_tolerance(&self) -> T {
        self.velocity_tolerance
    }

    /// [`Self::velocity_tolerance`] of a rule whose speed scale is `speed`.
    #[must_use]
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    pub(crate) fn velocity_tolerance_at(speed: T) -> T {
        max(T::of(1e-9), T::of(256.0) * T::EPS) * max(speed, T::TINY)
    }

    /// The kinetic energy of `velocity` in the rule's metric.
    #[must_use]
    pub fn energy(&self, velocity: &[[T; 3]; B]) -> T {
        let mut e = T::zero();
        for b in 0..B {
            for k in 0..3 {
                e += self.metric[b][k] * velocity[b][k] * velocity[b][k];
            }
        }
        e
    }

    /// `true` when no solution can have a lower energy than `velocity`'s beyond the tie (its
    /// energy is within the tie of zero): it is the rule's choice without looking at the others
    /// (up to the `||z||_1` order among solutions of energies within the tie of zero).
    #[must_use]
    pub fn at_least_energy(&self, velocity: &[[T; 3]; B]) -> bool {
        self.energy(velocity) <= self.energy_tie
    }

    /// `true` when `velocity`'s energy is below `energy` beyond the tie (a descent's step).
    #[must_use]
    #[cfg_attr(not(feature = "fallback"), allow(dead_code))]
    pub(crate) fn lowers(&self, velocity: &[[T; 3]; B], energy: T) -> bool {
        self.energy(velocity) < energy - self.energy_tie
    }

    /// `true` when `a` and `b` move the bodies differently: a coordinate (times its reach)
    /// differs by more than the velocity tolerance.
    #[must_use]
    pub fn moves_differently(&self, a: &[[T; 3]; B], b: &[[T; 3]; B]) -> bool {
        (0..B).any(|i| {
            (0..3).any(|k| (self.reach[i][k] * (a[i][k] - b[i][k])).abs_exact() > self.velocity_tolerance)
        })
    }

    /// `true` when the rule takes `a` over `b`: a lower energy beyond the tie, or a tied energy
    /// and a smaller `||z||_1` beyond its tie.
    #[must_use]
    fn prefers(&self, a: &Answer<T, B>, energy_a: T, b: &Answer<T, B>, energy_b: T) -> bool {
        if energy_a < energy_b - self.energy_tie {
            return true;
        }
        energy_a <= energy_b + self.energy_tie && a.impulse_sum < b.impulse_sum * (T::one() - self.sum_tie)
    }
}

/// The rule applied over a step's solutions: the first (the answer the solver's path reached) and
/// then every other one offered ([`Self::offer`]) in a fixed order.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Choice<T, const B: usize> {
    rule: Rule<T, B>,
    first: Answer<T, B>,
    best: Answer<T, B>,
    best_energy: T,
    /// The offer that is `best` (`None`: the first).
    best_offer: Option<usize>,
    /// A solution offered moved the bodies differently from the first.
    several: bool,
}

impl<T: Real, const B: usize> Choice<T, B> {
    /// The choice with the path's answer `first` alone.
    #[must_use]
    pub fn new(rule: Rule<T, B>, first: Answer<T, B>) -> Self {
        let best_energy = rule.energy(&first.velocity);
        Self { rule, first, best: first, best_energy, best_offer: None, several: false }
    }

    /// Offers solution number `index`; returns `true` when it is now the rule's choice.
    pub fn offer(&mut self, index: usize, answer: Answer<T, B>) -> bool {
        self.several |= self.rule.moves_differently(&answer.velocity, &self.first.velocity);
        let energy = self.rule.energy(&answer.velocity);
        if self.rule.prefers(&answer, energy, &self.best, self.best_energy) {
            self.best = answer;
            self.best_energy = energy;
            self.best_offer = Some(index);
            return true;
        }
        false
    }

    /// `true` when the solutions offered move the bodies in more than one way.
    #[must_use]
    pub const fn ambiguous(&self) -> bool {
        self.several
    }

    /// The offer the rule takes, `None` when it keeps the first: the first is kept whenever no
    /// solution moves the bodies differently (its `z` may differ from another's, its motion not),
    /// and when it is the rule's choice.
    #[must_use]
    pub fn chosen(&self) -> Option<usize> {
        if self.several { self.best_offer } else { None }
    }

    /// `true` when the rule's choice moves the bodies differently from the first answer.
    #[must_use]
    pub fn changed(&self) -> bool {
        self.chosen().is_some() && self.rule.moves_differently(&self.best.velocity, &self.first.velocity)
    }

    /// What the rule did on a step whose solutions were all offered to this choice.
    #[must_use]
    pub(crate) fn resolution(&self) -> Resolution {
        Resolution { enumerated: true, ambiguous: self.ambiguous(), changed: self.changed() }
    }
}

/// What the rule did on one step (or one layout's solve): counted by the steppers' statistics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Resolution {
    /// The solutions were enumerated (for one body: the path's answer was not already at the least
    /// energy any solution can have; for several: at most `MAX_CONTACTS` active contacts).
    pub(crate) enumerated: bool,
    /// Solutions moved the bodies differently.
    pub(crate) ambiguous: bool,
    /// The rule's choice moves the bodies differently from the path's answer.
    pub(crate) changed: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn answer(v: [f64; 3], impulse_sum: f64) -> Answer<f64, 1> {
        Answer { velocity: [v], impulse_sum }
    }

    fn rule() -> Rule<f64, 1> {
        Rule::new([[1.0, 1.0, 1.0 / 12.0]], [[1.0, 1.0, 0.5]], 0.1)
    }

    #[test]
    fn the_least_energy_wins_and_the_step_is_ambiguous() {
        let mut c = Choice::new(rule(), answer([0.1, 0.0, 0.0], 1.0));
        assert!(!c.offer(0, answer([0.1, 0.0, 0.0], 1.5)), "same energy, a larger sum");
        assert!(c.offer(1, answer([0.0, 0.0, 0.0], 3.0)));
        assert!(!c.offer(2, answer([0.0, 0.05, 0.0], 0.1)));
        assert!(c.ambiguous() && c.changed());
        assert_eq!(c.chosen(), Some(1));
    }

    #[test]
    fn equal_energies_go_to_the_smaller_impulse_sum() {
        let mut c = Choice::new(rule(), answer([0.1, 0.0, 0.0], 1.0));
        assert!(c.offer(0, answer([-0.1, 0.0, 0.0], 0.5)));
        assert!(!c.offer(1, answer([0.0, 0.1, 0.0], 0.5)), "a tie of both keeps the earlier");
        assert_eq!(c.chosen(), Some(0));
        assert!(c.changed());
    }

    #[test]
    fn one_motion_keeps_the_first_answer_whatever_its_impulses() {
        let mut c = Choice::new(rule(), answer([0.0; 3], 2.0));
        c.offer(0, answer([1e-13, 0.0, 0.0], 1.0));
        assert!(!c.ambiguous() && !c.changed());
        assert_eq!(c.chosen(), None);
    }
}
