//! A multibody scene's bodies, table, pairs and loads, and the stepping of its state
//! (docs/formulation.md, "Several bodies"; the loop as `reference/src/simulate.rs`: the
//! contacts' geometry at the step's start, `mu_s` for a contact sticking or separated before the
//! step and `mu_k` for one sliding, the step's LCP, `q+ = q + h v+`, `t = n h`, the modes after
//! the step).

use super::geometry::{Body, Frame, Lower, Pair, Shape, Table, dot, frames};
use crate::Mode;

/// Everything a multibody scene's steps share.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct System {
    /// The bodies, in the scene's order.
    pub bodies: Vec<Body>,
    /// The table.
    pub table: Table,
    /// The pairs, in the scene's order.
    pub pairs: Vec<Pair>,
    /// External force at each body's centre of mass (besides gravity), N.
    pub forces: Vec<[f64; 2]>,
    /// `g`, m/s^2.
    pub gravity: f64,
    /// `h`, s.
    pub step: f64,
    /// Slip speed at or below which a touching contact sticks, m/s.
    pub stick_speed: f64,
    /// The activity rule's reach beyond the step's approach, m.
    pub margin: f64,
}

impl System {
    /// Checks that every pair rests on a box or the table (docs/formulation.md, "Bodies, table and
    /// order": a disc is only ever a pair's upper body), naming the bodies by `names` (one per
    /// body, the scene's words).
    ///
    /// # Errors
    /// The first pair whose lower body is a disc.
    pub fn check_pairs(&self, names: &[&str]) -> Result<(), String> {
        for pair in &self.pairs {
            if let Lower::Body(j) = pair.lower
                && let Shape::Disc { .. } = self.bodies[j].shape
            {
                return Err(format!(
                    "{} rests on {}, a disc: a disc has no faces and is only ever the upper body of a pair",
                    names[pair.upper], names[j]
                ));
            }
        }
        Ok(())
    }

    /// `m_ref`: body 0's mass.
    pub fn reference_mass(&self) -> f64 {
        self.bodies[0].mass
    }

    /// `diag(M~) = m_ref M^-1`, flattened.
    pub fn weights(&self) -> Vec<f64> {
        let m_ref = self.reference_mass();
        self.bodies.iter().flat_map(|b| [m_ref / b.mass, m_ref / b.mass, m_ref / b.inertia]).collect()
    }

    /// `v~ = v + h M^-1 (f - m g e_y)`, flattened (eq. 16).
    pub fn free_velocity(&self, v: &[[f64; 3]]) -> Vec<f64> {
        let h = self.step;
        v.iter()
            .zip(&self.bodies)
            .zip(&self.forces)
            .flat_map(|((v, b), f)| {
                [v[0] + h * f[0] / b.mass, v[1] + h * (f[1] / b.mass - self.gravity), v[2]]
            })
            .collect()
    }

    /// `beta(psi)` after shrinking the gap by `round_off` toward zero (docs/formulation.md, "One
    /// time step": round-off is not a gap; a penetration pushed out at most at the speed of a
    /// fall through it).
    pub fn recovery(&self, gap: f64, round_off: f64) -> f64 {
        let gap = gap.signum() * (gap.abs() - round_off).max(0.0);
        (gap / self.step).max(-(2.0 * self.gravity * gap.abs()).sqrt())
    }

    /// The round-off of a contact's gap: `4 eps (|P_x| + |P_y| + sum over its bodies of
    /// (|x| + |y| + size))`.
    pub fn gap_round_off(&self, q: &[[f64; 3]], f: &Frame) -> f64 {
        let mut s = f.point[0].abs() + f.point[1].abs();
        for i in [f.corner_body, f.face_body].into_iter().flatten() {
            s += q[i][0].abs() + q[i][1].abs() + self.bodies[i].size();
        }
        4.0 * f64::EPSILON * s
    }

    /// The normal impulse (N s) at or below which a contact is separated: `64 eps g h m_min`
    /// (the round-off of one step's gravity impulse on the lightest body).
    pub fn impulse_floor(&self) -> f64 {
        let m_min = self.bodies.iter().map(|b| b.mass).fold(f64::INFINITY, f64::min);
        64.0 * f64::EPSILON * self.gravity * self.step * m_min
    }

    /// The candidate contacts at `(q, v)`.
    pub fn frames(&self, q: &[[f64; 3]], v: &[[f64; 3]]) -> Vec<Frame> {
        frames(&self.bodies, &self.table, &self.pairs, q, v, self.margin, self.step)
    }

    /// Each candidate's `(mu_s, mu_k)`.
    pub(super) fn friction(&self, frames: &[Frame]) -> Vec<(f64, f64)> {
        frames.iter().map(|f| (self.pairs[f.pair].mu_static, self.pairs[f.pair].mu_kinetic)).collect()
    }
}

/// The state of a run and its step.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct State {
    /// Steps taken.
    pub steps: u64,
    /// Configuration per body.
    pub q: Vec<[f64; 3]>,
    /// Velocity per body.
    pub v: Vec<[f64; 3]>,
    /// Each candidate's mode after the last step (before the first: the initial modes).
    pub modes: Vec<Mode>,
    /// Each candidate's pattern of basic variables in the last step.
    pub patterns: Vec<u8>,
}

impl State {
    /// At rest at `q`, with the initial modes: an active candidate touching
    /// (`psi <= 64 eps (sizes + |y|)`) sticks (every body starts at rest), any other is
    /// separated.
    pub fn at_rest(system: &System, q: Vec<[f64; 3]>) -> Self {
        let v = vec![[0.0; 3]; q.len()];
        let frames = system.frames(&q, &v);
        let modes = frames
            .iter()
            .map(|f| {
                let mut scale = 0.0;
                for i in [f.corner_body, f.face_body].into_iter().flatten() {
                    scale += system.bodies[i].size() + q[i][1].abs();
                }
                if f.active && f.gap <= 64.0 * f64::EPSILON * scale {
                    slip_mode(-dot(f.tangent, f.relative_velocity(&v)), system.stick_speed)
                } else {
                    Mode::Separated
                }
            })
            .collect();
        let patterns = vec![0; frames.len()];
        Self { steps: 0, q, v, modes, patterns }
    }

    /// `t = n h`.
    pub fn time(&self, system: &System) -> f64 {
        self.steps as f64 * system.step
    }
}

/// The mode of a touching contact with slip `s`.
pub(super) fn slip_mode(slip: f64, stick_speed: f64) -> Mode {
    if slip.abs() <= stick_speed {
        Mode::Sticking
    } else if slip > 0.0 {
        Mode::SlidingPositive
    } else {
        Mode::SlidingNegative
    }
}
