//! What a step reports ([`SystemStepReport`]: the states, interface forces, corner loads and modes).

use crate::planar::{BodyState, Checksum, ContactMode};
use crate::real::Real;

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use]
pub struct SystemStepReport<T, const B: usize, const P: usize> {
    /// Time at the step's end (s).
    pub time: T,
    /// Each body's state after the step.
    pub states: [BodyState<T>; B],
    /// Each pair's summed contact force on its upper body over the step (N, world):
    /// `(1/h) sum +-(p_n n + p_f d)`.
    pub interface_forces: [[T; 2]; P],
    /// Each candidate's normal and friction force over the step (N, along its normal and its
    /// `+d`; zero when not active): where the contacts leave the split open, the least-norm load
    /// (`docs/formulation.md`, "The load: the least norm").
    pub corner_loads: [[[T; 2]; 4]; P],
    /// Each candidate's mode after the step.
    pub modes: [[ContactMode; 4]; P],
    /// Active candidates this step (the LCP has `4` rows for each).
    pub active: u8,
    /// Lemke pivots spent (0 when a basis solved in the bodies' coordinates answered).
    pub pivots: u32,
}

impl<T, const B: usize, const P: usize> SystemStepReport<T, B, P> {
    /// `true` when a contact of pair `p` was sliding after the step.
    #[must_use]
    pub fn pair_slid(&self, p: usize) -> bool {
        self.modes.get(p).is_some_and(|m| m.iter().any(|m| m.is_sliding()))
    }

    /// `true` when every listed `(pair, candidate)` touches (is not separated) after the step.
    #[must_use]
    pub fn touching(&self, contacts: &[(usize, usize)]) -> bool {
        contacts.iter().all(|&(p, c)| {
            self.modes.get(p).and_then(|m| m.get(c)).is_some_and(|m| *m != ContactMode::Separated)
        })
    }
}

impl<T: Real, const B: usize, const P: usize> SystemStepReport<T, B, P> {
    /// Adds every body's state after the step, in body order, to a trajectory checksum: over a
    /// run, the fingerprint the firmware prints and the host compares bit for bit.
    pub fn add_to(&self, checksum: &mut Checksum) {
        for state in &self.states {
            checksum.add(state);
        }
    }
}
