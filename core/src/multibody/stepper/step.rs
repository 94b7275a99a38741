//! The step itself ([`SystemStepper::step`]): refill, solve, the rule (`resolve.rs`), `V+ = v~ + M~
//! J^T z` and `q+ = q + h V+` (compensated sums), the modes after the step, each pair's interface
//! force and corner loads, the next warm patterns; where the load is open, the load of least
//! 2-norm with the step's motion in place of the answer's ([`SystemStepper::decide_load`];
//! `docs/formulation.md`, "The load: the least norm").

#[cfg(feature = "fallback")]
use super::LoadMemory;
use super::SystemStepper;
use super::report::SystemStepReport;
use super::solve::Solved;
use crate::StepError;
#[cfg(feature = "fallback")]
use crate::load::{Carry, LoadContact, LoadPath, least_norm};
use crate::multibody::factored::MOST_SLOTS;
use crate::multibody::geometry::slip;
use crate::multibody::resolve;
#[cfg(feature = "fallback")]
use crate::planar::assemble::normal_bias;
use crate::planar::{ContactMode, SolvePath};
#[cfg(feature = "fallback")]
use crate::real::max;
use crate::real::{Real, compensated_add};
use crate::slot::{FullPatterns, Pattern, full_rows};

impl<T: Real, const B: usize, const P: usize, const N: usize> SystemStepper<T, B, P, N> {
    /// The load of least 2-norm with this step's motion `v_plus` (`crate::load`) in place of the
    /// answer `z`'s: each slot's mode, its pair's summed impulse and its corner's load rewritten
    /// (`report`). A slot touches when it carries load or its normal velocity `c_n^T v+ + bias` is
    /// within the rule's velocity tolerance (`max(1e-9, 256 eps) S`, `S` the rule's speed scale)
    /// of zero, and sticks when its slip is within it too. A rest state (the answer at the least
    /// energy, the same slots with the same modes before the step, the answer's load the same
    /// within round-off as the step before) keeps the load decided then: not solved again.
    #[cfg(feature = "fallback")]
    #[cold]
    #[inline(never)]
    #[allow(clippy::type_complexity)]
    fn decide_load(
        &mut self,
        (k, stuck): (usize, u32),
        z: &[T; N],
        v_plus: &[[T; 3]; B],
        report: (&mut [[ContactMode; 4]; P], &mut [[T; 2]; P], &mut [[[T; 2]; 4]; P]),
    ) -> Result<(), StepError> {
        let (modes, impulses, corner_loads) = report;
        let s = self.system.settings.base;
        let rule = self.detector.rule(&self.lcp.factored);
        // Every index below is in range: said so (no panic path).
        let slots = k.min(MOST_SLOTS).min(N / 4);
        let mut path = [[T::zero(); 2]; MOST_SLOTS];
        let mut before = [ContactMode::Separated; MOST_SLOTS];
        let mut scale = T::zero();
        for j in 0..slots {
            let rows = full_rows(k, j);
            path[j] = [z[rows[0]], z[rows[1]] - z[rows[2]]];
            scale = max(scale, max(path[j][0].abs_exact(), path[j][1].abs_exact()));
            let (p, c) = self.lcp.slots[j];
            before[j] = self.modes[p.min(P - 1)][c.min(3)];
        }
        // A rest state keeps the load decided the step before: the answer at the least energy, the
        // same slots with the same modes before the step, the answer's load the same within
        // round-off.
        let round_off = T::of(64.0 * N as f64) * T::EPS * scale;
        let memory = &self.load_memory;
        let kept = rule.at_least_energy(v_plus)
            && (0..MOST_SLOTS).all(|j| {
                j >= slots
                    || (memory.slots[j] == self.lcp.slots[j]
                        && memory.before[j] == before[j]
                        && (path[j][0] - memory.path[j][0]).abs_exact() <= round_off
                        && (path[j][1] - memory.path[j][1]).abs_exact() <= round_off)
            })
            && memory.count == slots;
        let (load, after) = if kept {
            // The memory stays but for the path, which the next step's is compared with.
            let (load, after) = (memory.load, memory.after);
            self.load_memory.path = path;
            (load, after)
        } else {
            let tolerance = rule.velocity_tolerance();
            let off = LoadContact {
                normal: [[T::zero(); 3]; B],
                tangent: [[T::zero(); 3]; B],
                carry: Carry::Nothing,
            };
            let mut contacts = [off; MOST_SLOTS];
            let mut slips = [T::zero(); MOST_SLOTS];
            for j in 0..slots {
                let (p, c) = self.lcp.slots[j];
                let (p, c) = (p.min(P - 1), c.min(3));
                let f = &self.frames[p][c];
                let normal = f.dense_row::<B>(f.normal);
                let mut normal_velocity = normal_bias(f.gap, s.step, s.gravity, f.gap_round_off);
                for (row, v) in normal.iter().zip(v_plus) {
                    normal_velocity += row[0] * v[0] + row[1] * v[1] + row[2] * v[2];
                }
                slips[j] = slip(f, v_plus);
                if path[j][0] <= self.impulse_floor && normal_velocity > tolerance {
                    continue;
                }
                let pair = &self.system.pairs[p];
                let mu = if before[j].is_sliding() { pair.mu_kinetic } else { pair.mu_static };
                let carry = if slips[j].abs_exact() <= tolerance {
                    Carry::Sticking { mu }
                } else {
                    Carry::Sliding { friction_per_normal: if slips[j] > T::zero() { mu } else { -mu } }
                };
                contacts[j] = LoadContact { normal, tangent: f.dense_row::<B>(f.tangent), carry };
            }
            let (load, how) =
                least_norm(&contacts, &path, &mut self.load_basis).map_err(StepError::Solver)?;
            if how == LoadPath::Determinate {
                return Ok(());
            }
            let mut after = [ContactMode::Separated; MOST_SLOTS];
            for j in 0..slots {
                if load[j][0] > self.impulse_floor {
                    // As the step's modes: a pair whose answer's slip is zero (`stuck`) sticks.
                    let pair = self.lcp.slots[j].0 as u32;
                    after[j] = if stuck.checked_shr(pair).unwrap_or(0) & 1 == 1 {
                        ContactMode::Sticking
                    } else {
                        ContactMode::from_slip(slips[j], s.stick_speed)
                    };
                }
            }
            let mut remembered = [(usize::MAX, usize::MAX); MOST_SLOTS];
            for (r, &slot) in remembered.iter_mut().zip(&self.lcp.slots).take(slots) {
                *r = slot;
            }
            self.load_memory = LoadMemory { slots: remembered, count: slots, before, path, load, after };
            (load, after)
        };
        self.stats.load_decided_steps += 1;
        // The report again, from the load.
        *impulses = [[T::zero(); 2]; P];
        let per_second = self.system.bodies[0].mass / s.step;
        for j in 0..slots {
            let (p, c) = self.lcp.slots[j];
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let [pn, pf] = load[j];
            modes[p][c] = after[j];
            corner_loads[p][c] = [pn * per_second, pf * per_second];
            let sign = if c >= 2 { -T::one() } else { T::one() };
            impulses[p][0] += sign * (pn * f.normal[0] + pf * f.tangent[0]);
            impulses[p][1] += sign * (pn * f.normal[1] + pf * f.tangent[1]);
        }
        Ok(())
    }

    /// Every loaded corner of the pairs `stuck` (bits by pair) sticks ([`Self::step`]'s modes
    /// after the step, `modes`); returns whether the load may be open and its unknowns, counted
    /// again as the step counts them. Out of line and cold: only where a corner of a pair whose
    /// answer's slip is zero read sliding (a heavy body on a light one in f32).
    #[cold]
    #[inline(never)]
    fn stick_pairs(&self, k: usize, stuck: u32, modes: &mut [[ContactMode; 4]; P]) -> (bool, usize) {
        let (mut open, mut unknowns, mut sticking_pair) = (false, 0, usize::MAX);
        for &(p, c) in self.lcp.slots.iter().take(k) {
            let (p, c) = (p.min(P - 1), c.min(3));
            let mode = &mut modes[p][c];
            if *mode == ContactMode::Separated {
                continue;
            }
            if stuck.checked_shr(p as u32).unwrap_or(0) & 1 == 1 {
                *mode = ContactMode::Sticking;
            }
            if *mode == ContactMode::Sticking {
                unknowns += 2;
                open |= sticking_pair == p;
                sticking_pair = p;
            } else {
                unknowns += 1;
            }
        }
        (open, unknowns)
    }

    /// Advances one step: the active candidates' LCP (per unit reference mass) in factored form,
    /// solved by the paths of `docs/formulation.md` ("Solving a multibody step") and verified;
    /// `V+ = v~ + M~ J^T z`, `q+ = q + h V+` (compensated sums), modes after the step.
    ///
    /// # Errors
    /// [`StepError`]; the state is then unchanged.
    pub fn step(&mut self) -> Result<SystemStepReport<T, B, P>, StepError> {
        #[cfg(feature = "fallback")]
        if self.load_next {
            return self.step_loading();
        }
        self.step_with::<false>()
    }

    /// [`Self::step`] after a step whose load was open (`docs/formulation.md`, "The load: the least
    /// norm"): out of line, so that the other steps' copy has none of the load's code.
    #[cfg(feature = "fallback")]
    #[inline(never)]
    fn step_loading(&mut self) -> Result<SystemStepReport<T, B, P>, StepError> {
        self.step_with::<true>()
    }

    /// [`Self::step`], deciding the load where it is open when `LOAD`.
    #[inline(always)]
    #[allow(clippy::inline_always)] // into `step` and `step_loading`: two copies, as said there
    #[allow(clippy::too_many_lines)] // the module docs' steps in order, each slot's modes and loads in one pass
    fn step_with<const LOAD: bool>(&mut self) -> Result<SystemStepReport<T, B, P>, StepError> {
        let s = self.system.settings.base;
        let h = s.step;
        self.refill()?;
        let (k, active) = (self.lcp.k.min(N / 4), self.lcp.active);
        let mut z = [T::zero(); N];
        let mut paths = self.stats.paths;
        // A sliding step's blocks, formed once for its solve and its detection.
        self.lcp.factored.form_blocks(self.lcp.warm.z_mask());
        let blocks = self.lcp.factored.blocks();
        let Solved { mut v_plus, basis, pivots, path, along, ruled, mut rule } =
            self.solve(&mut paths, blocks, &mut z)?;
        let mut mask = basis.z_mask();
        let (tolerance, f) = (self.solver.tolerance(), &self.lcp.factored);
        // The rule on a warm or free answer (the other paths applied it: `SystemStepper::solve`).
        if !ruled {
            rule =
                resolve::apply(&self.detector, f, blocks, tolerance, None, (&mut v_plus, &mut z, &mut mask));
        }
        // The slips the basis solve formed, unless the rule took another answer.
        let (along, from_solve) = match along {
            Some(along) if rule.is_none_or(|r| !r.changed) => (along, true),
            _ => ([T::zero(); MOST_SLOTS], false),
        };
        let m_ref = self.system.bodies[0].mass;
        // q+ = q + h V+, compensated sums.
        let mut states = self.states;
        let mut carry = self.carry;
        for i in 0..B {
            let st = &mut states[i];
            [st.vx, st.vy, st.omega] = v_plus[i];
            for (c, coordinate) in [&mut st.x, &mut st.y, &mut st.theta].into_iter().enumerate() {
                compensated_add(coordinate, &mut carry[i][c], h * v_plus[i][c]);
            }
            if !st.is_finite() {
                return Err(StepError::NonFinite);
            }
        }
        // Modes after the step, interface forces, each corner's load, the next warm patterns.
        let mut modes = [[ContactMode::Separated; 4]; P];
        let mut patterns = [[Pattern::OFF; 4]; P];
        let mut impulses = [[T::zero(); 2]; P];
        let mut corner_loads = [[[T::zero(); 2]; 4]; P];
        let per_second = m_ref / h;
        // Whether the load may be open (`docs/formulation.md`, "The load: the least norm"): two
        // sticking corners of one pair carrying load, or more unknowns (two per sticking slot,
        // one per sliding one) than the bodies' `3B` coordinates.
        #[cfg(feature = "fallback")]
        let (mut open, mut unknowns, mut sticking_pair) = (false, 0, usize::MAX);
        // The pairs with a loaded slot whose `sigma` is not basic (`stuck`, bits by pair): its `w_+d
        // = slip` and `w_-d = -slip` are both `>= 0`, so the answer's slip is zero, and every corner
        // of one interface has the one slip of its two bodies along their face: each sticks. (The
        // slip formed from the bodies' velocities is that zero's round-off, which a heavy body on a
        // light one makes larger than the stick speed.) Another corner of such a pair read sliding
        // (`sliding`) is turned after the loop ([`Self::stick_pairs`]).
        let (mut stuck, mut sliding) = (0u32, 0u32);
        let mut read = FullPatterns::new(mask, k);
        for j in 0..k {
            let (p, c) = self.lcp.slots[j];
            let (p, c) = (p.min(P - 1), c.min(3));
            let f = &self.frames[p][c];
            let rows = full_rows(k, j);
            let pattern = read.next_pattern();
            patterns[p][c] = pattern;
            let sigma_basic = pattern.bits() & 0b1000 != 0;
            let (pn, pf) = (z[rows[0]], z[rows[1]] - z[rows[2]]);
            if pn > self.impulse_floor {
                // `p < P <= 32` ([`Self::SIZE_CHECK`]): the mask is the pair's own bit.
                let bit = 1u32 << (p as u32 & 31);
                // Else the slip `-c_+d^T v+` as the solve formed it, or from the frame.
                let mode = if sigma_basic {
                    let slip = if from_solve { -along[j.min(MOST_SLOTS - 1)] } else { slip(f, &v_plus) };
                    ContactMode::from_slip(slip, s.stick_speed)
                } else {
                    stuck |= bit;
                    ContactMode::Sticking
                };
                if mode.is_sliding() {
                    sliding |= bit;
                }
                modes[p][c] = mode;
                #[cfg(feature = "fallback")]
                if mode == ContactMode::Sticking {
                    unknowns += 2;
                    open |= sticking_pair == p;
                    sticking_pair = p;
                } else {
                    unknowns += 1;
                }
            }
            corner_loads[p][c] = [pn * per_second, pf * per_second];
            // On the upper body: + for its corners, - for the lower body's (negated: the bits of
            // `+-1` times it, a product by `+-1` being exact).
            let impulse = &mut impulses[p];
            let mut along = [pn * f.normal[0] + pf * f.tangent[0], pn * f.normal[1] + pf * f.tangent[1]];
            if c >= 2 {
                along = [-along[0], -along[1]];
            }
            impulse[0] += along[0];
            impulse[1] += along[1];
        }
        if stuck & sliding != 0 {
            #[cfg(feature = "fallback")]
            {
                (open, unknowns) = self.stick_pairs(k, stuck, &mut modes);
            }
            #[cfg(not(feature = "fallback"))]
            self.stick_pairs(k, stuck, &mut modes);
        }
        // The load, where it may be open: in place of the answer's, before the frames move on.
        #[cfg(feature = "fallback")]
        {
            self.load_next = open || unknowns > 3 * B;
            if LOAD && self.load_next {
                self.decide_load((k, stuck), &z, &v_plus, (&mut modes, &mut impulses, &mut corner_loads))?;
            }
        }
        let mut interface_forces = [[T::zero(); 2]; P];
        for p in 0..P {
            interface_forces[p] = [impulses[p][0] * m_ref / h, impulses[p][1] * m_ref / h];
        }
        self.states = states;
        self.carry = carry;
        self.modes = modes;
        self.patterns = patterns;
        self.stats.steps += 1;
        self.update_frames();
        paths.count(path);
        self.stats.paths = paths;
        self.stats.count_answer(rule, pivots, path == SolvePath::Warm, active);
        Ok(SystemStepReport {
            time: self.time(),
            states,
            interface_forces,
            corner_loads,
            modes,
            active,
            pivots,
        })
    }
}
