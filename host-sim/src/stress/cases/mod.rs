//! The grid of `host-sim stress`: one [`Case`] per stiff or extreme scene, with what physics says
//! about it where physics decides.
//!
//! * `one_body.rs`: the scenes of one body (the meter stick, the incline, the ladder, Painlevé's
//!   rod, the cylinder, three fingers) and what the statics and dynamics of each decide.
//! * `several_bodies.rs`: the scenes of several bodies and what `docs/scenes.md`'s laws decide.
//! * `spatial.rs`: the scenes in three dimensions and what their laws decide.

mod one_body;
mod several_bodies;
mod spatial;

use crate::scenes::SceneParams;
use crate::trajectory::OutcomeKind;

/// A physics claim a case makes beyond the generic criteria.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Claim {
    /// None: the generic criteria only.
    None,
    /// While finger 1 is left of the centre of mass (by 1 % of `L`), the rod does not move along
    /// `x` (frictionless contacts or `mu_k = 0`: no force can drag it).
    NotDragged,
    /// The body does not move at all (zero finger speed, zero gravity, a block held by friction;
    /// a scene of several bodies: none of them moves).
    BodyStill,
    /// Block-on-block: the measured accelerations in full contact are the laws' (`docs/scenes.md`,
    /// within [`super::bodies::acceleration_tolerance`]).
    LawAccelerations,
}

/// One scene of the grid.
#[derive(Debug, Clone)]
pub struct Case {
    /// Which part of the grid.
    pub group: &'static str,
    /// A short name, unique.
    pub name: String,
    /// The scene.
    pub spec: SceneParams,
    /// Meter stick: start height above the resting position (m; negative: penetrating).
    pub start_dy: f64,
    /// The outcome class physics decides, if any.
    pub outcome: Option<OutcomeKind>,
    /// Further claim.
    pub claim: Claim,
}

/// The grid (`quick`: the subset the test command runs).
#[must_use]
pub fn cases(quick: bool) -> Vec<Case> {
    let mut out = one_body::cases(quick);
    out.extend(several_bodies::cases(quick));
    out.extend(spatial::cases(quick));
    if quick {
        // Short runs (at most 5 s simulated): the subset checks the criteria, not long physics; a
        // run cut short cannot balance.
        for c in &mut out {
            if c.spec.max_time() > 5.0 {
                c.spec.set("max_time", 5.0);
                if c.outcome == Some(OutcomeKind::Balanced) {
                    c.outcome = Some(OutcomeKind::Unfinished);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quick_grid_is_a_subset_with_unique_names() {
        let full = cases(false);
        let quick = cases(true);
        assert!(quick.len() < full.len());
        for c in &quick {
            assert!(full.iter().any(|f| f.name == c.name), "{}", c.name);
        }
        let mut names: Vec<&str> = full.iter().map(|c| c.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), full.len());
    }
}
