//! The load where the contacts leave it open (`docs/formulation.md`, "The load: the least
//! norm"): [`Stepper::decide_load`] and its closed form for two sticking contacts,
//! [`Stepper::split_two_sticking`]; the load kept from one step to the next
//! ([`PlanarLoadMemory`]).

use super::Stepper;
use crate::StepError;
use crate::load::{Carry, LoadContact, LoadPath, least_norm, least_norm_two_sticking};
use crate::planar::contact::{Contact, ContactMode, Support};
use crate::planar::report::ContactReport;
use crate::planar::resolve::Detector;
use crate::real::{Real, max};

impl<T: Real, const K: usize, const N: usize, const NF: usize> Stepper<T, K, N, NF> {
    /// [`Self::decide_load`] for two contacts that both stick: the closed form of
    /// [`crate::load::least_norm_two_sticking`] when both slips are within the rule's velocity
    /// tolerance (else a slip decides a friction and the load is determinate), its modes as
    /// `decide_load`'s; `decide_load` itself when the contacts' columns span less than the
    /// coordinates.
    #[cold]
    #[inline(never)]
    pub(super) fn split_two_sticking(
        &mut self,
        supports: &[Support<T>; K],
        v_plus: [T; 3],
        slips: [T; 2],
        pair: [ContactReport<T>; 2],
    ) -> Result<Option<[ContactReport<T>; 2]>, StepError> {
        let v_free =
            [self.state.vx, self.state.vy - self.settings.step * self.settings.gravity, self.state.omega];
        let support_velocity = supports.map(|u| u.velocity());
        let tolerance = Detector::velocity_tolerance(&v_free, &support_velocity, self.size);
        let (Some(a), Some(b), Some(ca), Some(cb)) =
            (self.frames.first(), self.frames.get(1), self.contacts.first(), self.contacts.get(1))
        else {
            return Ok(None);
        };
        if slips.iter().any(|s| s.abs_exact() > tolerance) {
            return Ok(None);
        }
        let mu_of = |c: &Contact<T>, r: &ContactReport<T>| {
            if r.previous_mode.is_sliding() { c.mu_kinetic } else { c.mu_static }
        };
        let mu = [mu_of(ca, &pair[0]), mu_of(cb, &pair[1])];
        let columns = [a.wn, a.wt, b.wn, b.wt];
        let path = pair.map(|r| [r.normal_impulse, r.friction_impulse]);
        let Some(load) = least_norm_two_sticking(&columns, mu, &path) else {
            // The columns span less than the coordinates: the general least norm (both contacts
            // carry load, so no normal velocity is read).
            let mut contacts = [pair[0]; K];
            let (mut mu_k, mut slip_k) = ([T::zero(); K], [T::zero(); K]);
            for i in 0..K {
                contacts[i] = pair[i % 2];
                (mu_k[i], slip_k[i]) = (mu[i % 2], slips[i % 2]);
            }
            self.decide_load(&support_velocity, &mu_k, &v_plus, &[], &slip_k, &mut contacts)?;
            return Ok(Some([contacts[0], contacts[1 % K]]));
        };
        self.stats.load_decided_steps += 1;
        let mut split = pair;
        for (i, (report, x)) in split.iter_mut().zip(load).enumerate() {
            (report.normal_impulse, report.friction_impulse) = (x[0], x[1]);
            report.mode = if x[0] > self.impulse_floor * self.mass {
                ContactMode::from_slip(slips[i], self.settings.stick_speed)
            } else {
                ContactMode::Separated
            };
            if let Some(m) = self.modes.get_mut(i) {
                *m = report.mode;
            }
        }
        Ok(Some(split))
    }

    /// The load of least 2-norm with this step's motion (`crate::load`), in place of the path's
    /// impulses and modes in `contacts` (and the modes kept for the next step): a contact touches
    /// when it carries load or its normal row in `w` (its normal velocity) is within the rule's
    /// velocity tolerance of zero, and sticks when its `slips` is within it too. Called before the
    /// state is advanced (the rule's speed scale is from the step's free velocity).
    #[cold]
    #[inline(never)]
    pub(super) fn decide_load(
        &mut self,
        support_velocity: &[[T; 2]; K],
        mu: &[T; K],
        v_plus: &[T; 3],
        w: &[T],
        slips: &[T; K],
        contacts: &mut [ContactReport<T>; K],
    ) -> Result<(), StepError> {
        let v_free =
            [self.state.vx, self.state.vy - self.settings.step * self.settings.gravity, self.state.omega];
        let rule = Detector::rule_of(&self.m_inv, &v_free, support_velocity, self.size);
        let tolerance = rule.velocity_tolerance();
        let mut loads =
            [LoadContact { normal: [[T::zero(); 3]], tangent: [[T::zero(); 3]], carry: Carry::Nothing }; K];
        let mut path = [[T::zero(); 2]; K];
        for i in 0..K {
            let (f, report, mu) = (&self.frames[i], &contacts[i], mu[i]);
            path[i] = [report.normal_impulse, report.friction_impulse];
            let normal_velocity = w.get(i).copied().unwrap_or(T::zero());
            if !f.active || (report.mode == ContactMode::Separated && normal_velocity > tolerance) {
                continue;
            }
            let carry = if slips[i].abs_exact() <= tolerance {
                Carry::Sticking { mu }
            } else {
                Carry::Sliding { friction_per_normal: if slips[i] > T::zero() { mu } else { -mu } }
            };
            loads[i] = LoadContact { normal: [f.wn], tangent: [f.wt], carry };
        }
        // A rest state keeps the load decided the step before: the answer at the least energy,
        // the same contacts carrying the same way at the same places on the body (a finger sliding
        // under a resting rod moves its split), its load the same within round-off.
        let kinds = loads.map(|l| l.carry);
        let levers = loads.map(|l| [l.normal[0][2], l.tangent[0][2]]);
        // The arms' own round-off (`|r| <= size`): a contact that moves on the body by more, over
        // the steps since the load was decided, moves the split (at rest the body does not turn).
        let reach = T::of(16.0) * T::EPS * (T::one() + self.size);
        let mut scale = T::zero();
        for p in &path {
            scale = max(scale, max(p[0].abs_exact(), p[1].abs_exact()));
        }
        let round_off = T::of(64.0 * NF as f64) * T::EPS * scale;
        let memory = &self.load_memory;
        let kept = rule.at_least_energy(&[*v_plus])
            && memory.kinds == kinds
            && levers
                .iter()
                .zip(&memory.levers)
                .all(|(a, b)| (a[0] - b[0]).abs_exact() <= reach && (a[1] - b[1]).abs_exact() <= reach)
            && path.iter().zip(&memory.path).all(|(a, b)| {
                (a[0] - b[0]).abs_exact() <= round_off && (a[1] - b[1]).abs_exact() <= round_off
            });
        let (load, how) = if kept {
            (memory.load, LoadPath::Projection)
        } else {
            least_norm(&loads, &path, &mut self.load_basis).map_err(StepError::Solver)?
        };
        if how != LoadPath::Determinate {
            if !kept {
                self.load_memory = PlanarLoadMemory { kinds, levers, path, load };
            }
            self.stats.load_decided_steps += 1;
            for i in 0..K {
                let report = &mut contacts[i];
                (report.normal_impulse, report.friction_impulse) = (load[i][0], load[i][1]);
                report.mode = if self.frames[i].active && load[i][0] > self.impulse_floor * self.mass {
                    ContactMode::from_slip(slips[i], self.settings.stick_speed)
                } else {
                    ContactMode::Separated
                };
                self.modes[i] = report.mode;
            }
        }
        // A contact the load leaves touching but unloaded while the body slips over it reads
        // separated (no force), but its next step's coefficient is the sliding one: `mu_s` would
        // make the rule's least energy load it at once, and the load would flip from finger to
        // finger every step (a rod sliding over three fingers).
        for i in 0..K {
            self.slipping_unloaded[i] = K >= 3
                && !matches!(kinds[i], Carry::Nothing)
                && contacts[i].mode == ContactMode::Separated
                && slips[i].abs_exact() > self.settings.stick_speed;
        }
        Ok(())
    }
}

/// The last load the rule decided ([`Stepper::decide_load`]): what each contact could carry, the
/// path's load and the decided one (a rest state keeps it).
#[derive(Debug, Clone, Copy)]
pub(super) struct PlanarLoadMemory<T, const K: usize> {
    kinds: [Carry<T>; K],
    /// Each contact's torque arms `r x n`, `r x d` (where the contact is on the body).
    levers: [[T; 2]; K],
    path: [[T; 2]; K],
    load: [[T; 2]; K],
}

impl<T: Real, const K: usize> PlanarLoadMemory<T, K> {
    /// No load decided yet.
    pub(super) fn none() -> Self {
        Self {
            kinds: [Carry::Nothing; K],
            levers: [[T::zero(); 2]; K],
            path: [[T::zero(); 2]; K],
            load: [[T::zero(); 2]; K],
        }
    }
}
