//! A warm basis' own answer from the contacts' structure (`super`'s module docs, 3). The LCP of `N
//! = 4 K` rows has, per loaded contact, one or two unknowns that matter; a contact's basic `z` say
//! its mode: none, separated; `p_n` alone, no friction; `p_n` and `p_+d` (or `p_-d`), sticking
//! along its line, its normal row and that friction row closed (the other friction row, `w_-d =
//! -w_+d` while `sigma` is zero, nil too); `p_n`, `p_+d`, `p_-d` and `sigma`, sticking with both
//! frictions basic, `p_+-d = (mu p_n +- p_t) / 2` by its `sigma` row, `sigma` zero; `p_n`, `p_+d`
//! (or `p_-d`) and `sigma`, sliding, its friction `mu p_n` by its `sigma` row, its normal row
//! closed, its `sigma` read from its friction row once the impulses are known. The basis'
//! complementary solution is then that of a system in the loaded contacts' normal impulses and the
//! sticking ones' frictions (at most `2 K` unknowns where Lemke's direct solve has the basis' up to
//! `4 K`: on the meter stick's pad and point, five or six where it had up to twelve), and Lemke's
//! verification ([`Lemke::accept`]) judges it on the whole problem as it judges its own warm answer
//! ([`Lemke::solve_warm`]), but for the rows zero in exact arithmetic, which may miss zero by the
//! step's velocity round-off ([`Contacts::slack`]), and, for one body, for `||M||_inf`, bounded
//! below from the contacts' own blocks (`Contacts::scales`: the check at least as strict). For one
//! body, a basis whose answer this check refuses is followed by the modes the answer says come
//! next ([`Contacts::switched`]), each solved
//! and verified the same way, up to [`MODE_SWITCHES`] times; a switched basis whose system is
//! singular (points that stopped sliding together leave a force between them open) is tried with
//! each of those points in turn back at its cone's edge ([`Contacts::at_edge`]). A basis of any other pattern goes to
//! [`Lemke::solve_warm`], one whose answer (and whose switches') this path's check refuses to
//! [`Lemke::solve_from_basis`] (Lemke's pivoting from its tableau, then the cold start).

use nalgebra::SVector;

use super::friction::Contacts;
use crate::StepError;
use crate::lcp::elimination::solve_leading;
use crate::lcp::{Basis, Lcp, LcpSolution, Lemke, Scales};
use crate::real::{Real, max, min};

/// One unknown of a basis' reduced system: the variables of `z` it moves, each by a factor, and how
/// many of them there are (one to three).
type Unknown<T> = ([(usize, T); 3], usize);

/// Row `row`'s bit in a mask of rows (none beyond 64).
fn row_bit(row: usize) -> u64 {
    1u64.checked_shl(u32::try_from(row).unwrap_or(u32::MAX)).unwrap_or(0)
}

/// The basic `z` of the contact whose rows start at `b`, as bits `(p_n, p_+d, p_-d, sigma)` from
/// the lowest: its mode (module docs).
fn contact_bits<const N: usize, const W: usize>(basis: Basis<N, W>, b: usize) -> u32 {
    (0..4).fold(0u32, |bits, k| bits | (u32::from(basis.is_z_basic(b + k)) << k))
}

/// The most times one body's contacts switch modes by their answer's signs before Lemke's pivots
/// ([`Contacts::switched`]): a slip that reverses sticks, then slides the other way when its
/// friction leaves the cone.
const MODE_SWITCHES: u32 = 3;

/// The most unknowns of a reduced system solved in its small array ([`Contacts::reduced`]).
const SMALL_SYSTEM: usize = 8;

impl<T: Real, const K: usize, const B: usize> Contacts<'_, T, K, B> {
    /// The verified answer of the contacts' LCP `lcp` ([`Contacts`]' layout: per contact `(p_n,
    /// p_+d, p_-d, sigma)`, then the padding rows `w = z + 1`) from the basis `basis`: its own
    /// complementary solution when it verifies (module docs), else (one body) that of the modes
    /// its answer switches to ([`Self::switched`]), else Lemke's method's. A lone contact's (`K =
    /// 1`: a puck, a ball) goes to [`Lemke::solve_warm`] whole. Several bodies' (a face on a face)
    /// where Lemke's method fails: the open loads' answer ([`Self::open_load`]), else in f64 the
    /// same again, Lemke's method first, with single precision's pivot floor
    /// ([`Lemke::single_precision_floor`]): every one verified on `lcp` to its own tolerance.
    ///
    /// # Errors
    /// [`StepError::Solver`].
    pub(super) fn answer<const N: usize, const W: usize>(
        &self,
        solver: &Lemke<T, N, W>,
        lcp: &Lcp<T, N>,
        basis: Basis<N, W>,
    ) -> Result<LcpSolution<T, N, W>, StepError> {
        // A lone contact's basis is of at most three unknowns: Lemke's own direct solve of it.
        // One body: the modes each answer says the contacts switch to, up to `MODE_SWITCHES`
        // times, before Lemke's pivots (one call of each piece: one copy of each in flash).
        let (mut tried, mut switches) = (basis, 0);
        // The basis before the last switch; a switched basis whose system was singular and the
        // next contact to try at its cone's edge ([`Self::at_edge`]).
        let (mut before, mut edge) = (basis, None);
        // One body's scales from its contacts' blocks (a lower bound of `||M||`, [`Self::scales`]:
        // a twelfth of the reads); several bodies' from the whole problem (their open loads'
        // answers are held to its norm).
        let scales = if B == 1 { Some(self.scales(lcp)) } else { lcp.scales() };
        let lemke = loop {
            let reduced = if K > 1 { self.basis_solution(lcp, tried) } else { None };
            // Data that are not finite: Lemke's method names them.
            let (Some((z, tied, own)), Some(scales)) = (reduced, scales.as_ref()) else {
                // A switched basis of no solution (its system singular): its tries at the edge.
                if B == 1
                    && switches > 0
                    && scales.is_some()
                    && let Some((next, at)) = Self::at_edge(edge.unwrap_or((tried, 0)), before)
                {
                    (edge, tried) = (Some(next), at);
                    continue;
                }
                break if switches == 0 {
                    solver.solve_warm(lcp, basis)
                } else {
                    solver.solve_from_basis(lcp, basis)
                };
            };
            let w = match solver.accept_with_w(scales, &z, lcp.w_of_sparse(&z), own, |i| self.slack(tied, i))
            {
                Ok(sol) => return Ok(sol),
                Err(w) => w,
            };
            // A try at the edge refused: the next one.
            if let Some(last) = edge {
                let Some((next, at)) = Self::at_edge(last, before) else {
                    break solver.solve_from_basis(lcp, basis);
                };
                (edge, tried) = (Some(next), at);
                continue;
            }
            let switched = if B == 1 && switches < MODE_SWITCHES { self.switched(own, &z, &w) } else { own };
            if switched == own {
                break solver.solve_from_basis(lcp, basis);
            }
            (before, tried, switches) = (tried, switched, switches + 1);
        };
        match lemke {
            Ok(sol) => Ok(sol),
            // A face on a face (several bodies: `B > 1`): Lemke's pivots through the open loads'
            // singular bases; the basis of the problem made strictly copositive, then that
            // basis' least-norm solution, verified on the problem itself.
            // In f64, the same again with single precision's pivot floor
            // ([`Lemke::single_precision_floor`]).
            Err(e) if K > 1 && B > 1 => Self::open_load(solver, lcp)
                .or_else(|| {
                    let coarse = solver.single_precision_floor()?;
                    coarse.solve_from_basis(lcp, basis).ok().or_else(|| Self::open_load(&coarse, lcp))
                })
                .ok_or(StepError::Solver(e)),
            Err(e) => Err(StepError::Solver(e)),
        }
    }

    /// The scales a basis' answer is verified on ([`Lemke::accept_with_w`]) for one body, from
    /// the contacts' own blocks of `lcp` alone: `||M||_inf` bounded below by the largest row sum
    /// within them (`|W_nn|` for a normal row, `2 |W_dd| + 1` for a friction row, `mu + 2` for a
    /// `sigma` row, `1` for a padding row or an inactive contact's: every row's sum over all of
    /// `M` is at least that), which makes the check at least as strict as on the whole problem's
    /// norm; `||q||_inf` and `min q` exact. Data that are not finite where the answer's `w` reads
    /// them (`q`, and `M`'s columns of the answer's non-zero `z`: [`Lcp::w_of_sparse`]) make `w`
    /// so, which the residual refuses, and Lemke's method then names them; a contact's other
    /// entries are of its arm, normal and line, which its rows of `q` are of too.
    fn scales<const N: usize>(&self, lcp: &Lcp<T, N>) -> Scales<T> {
        let (zero, one, two) = (T::zero(), T::one(), T::of(2.0));
        let entry = |r: usize| lcp.m.get((r, r)).copied().unwrap_or(zero).abs_exact();
        let mut m_norm = if N > 4 * K { one } else { zero };
        for (i, c) in self.touches.iter().enumerate() {
            let b = 4 * i;
            m_norm = if c.active {
                max(m_norm, max(entry(b), max(two * entry(b + 1) + one, c.mu.abs_exact() + two)))
            } else {
                max(m_norm, one)
            };
        }
        let (mut q_norm, mut q_min) = (zero, lcp.q[0]);
        for i in 0..N {
            let q = lcp.q[i];
            q_norm = max(q_norm, q.abs_exact());
            q_min = min(q_min, q);
        }
        // The bound's claim, checked wherever debug assertions are on (every test's run).
        debug_assert!(
            m_norm.partial_cmp(&lcp.m_norm_inf()) != Some(core::cmp::Ordering::Greater),
            "{m_norm:?} above ||M||"
        );
        Scales { m_norm, q_norm, q_min }
    }

    /// The basis of the modes `basis`' answer `(z, w)` says the contacts switch to: a contact's
    /// mode changes as its condition that failed says, one condition a contact, all contacts at
    /// once (a step where one contact starts or stops sliding, or lifts, or a body lands: the
    /// run's first step starts from no loaded contact). A loaded contact whose normal impulse came
    /// out negative separates; a sticking one whose friction came out beyond its cone (`w_sigma =
    /// mu p_n - p_+-d < 0`) slides, the same friction then `mu p_n`; a sliding one whose slip
    /// speed came out negative (beyond round-off: [`Self::basis_solution`]) sticks along its line;
    /// one sticking with both frictions basic whose friction along one side came out negative
    /// (`p_+-d = (mu p_n +- p_t) / 2 < 0`: `|p_t|` beyond the cone) slides, its friction on the
    /// other side at the cone's edge;
    /// a separated one whose normal row came out negative (closing) is loaded, sliding against its
    /// slip along its line when that is beyond the step's round-off (`w_+-d = +-d . u`), else
    /// sticking. Any other contact keeps its mode. The basis is only a guess: its answer is
    /// verified as a warm basis' is, and Lemke's method pivots from `basis` when it fails.
    fn switched<const N: usize, const W: usize>(
        &self,
        basis: Basis<N, W>,
        z: &SVector<T, N>,
        w: &SVector<T, N>,
    ) -> Basis<N, W> {
        let zero = T::zero();
        let mut switched = basis;
        for (i, c) in self.touches.iter().enumerate() {
            let b = 4 * i;
            let (Some(&p_n), Some(&sigma), Some(&w_n), Some(&w_d)) =
                (z.get(b), z.get(b + 3), w.get(b), w.get(b + 1))
            else {
                continue;
            };
            let bits = contact_bits(basis, b);
            let friction = |k: usize| z.get(b + k).copied().unwrap_or(zero);
            let mode = match bits {
                0b0011 | 0b0101 | 0b1011 | 0b1101 | 0b1111 if p_n < zero => 0b0000,
                0b0000 if c.active && w_n < zero => {
                    if w_d > self.slip_tolerance {
                        0b1101
                    } else if w_d < -self.slip_tolerance {
                        0b1011
                    } else {
                        0b0011
                    }
                }
                0b0011 | 0b0101 if c.mu * p_n - friction(1) - friction(2) < zero => bits | 0b1000,
                0b1011 | 0b1101 if sigma < zero => bits & 0b0111,
                0b1111 if friction(1) < zero => 0b1101,
                0b1111 if friction(2) < zero => 0b1011,
                _ => bits,
            };
            for k in 0..4 {
                switched.set_z_basic(b + k, (mode >> k) & 1 == 1);
            }
        }
        switched
    }

    /// The next of a singular switched basis' contacts, from a given one on (`(singular, from)`),
    /// that the switch stopped (sliding in `before`, sticking along the same side in `singular`),
    /// put back at its cone's edge: sliding, its `sigma` basic (its slip speed, zero in the answer
    /// that holds), its friction `mu p_n`. Three or more sticking points can leave a force between
    /// them open (a rod on two fingers that stop: the squeeze along the rod), their system
    /// singular; one point at the edge decides it, as Lemke's method's answer there does. The next
    /// `(singular, from)` and the basis to try; `None` when no contact is left.
    fn at_edge<const N: usize, const W: usize>(
        (singular, from): (Basis<N, W>, usize),
        before: Basis<N, W>,
    ) -> Option<((Basis<N, W>, usize), Basis<N, W>)> {
        (from..K).find_map(|i| {
            let b = 4 * i;
            let bits = contact_bits(singular, b);
            let mut at = singular;
            at.set_z_basic(b + 3, true);
            (matches!(bits, 0b0011 | 0b0101) && contact_bits(before, b) == bits | 0b1000)
                .then_some(((singular, i + 1), at))
        })
    }

    /// How far below zero row `row`'s `w` may come out, outside the basis, in a basis' own answer
    /// ([`Lemke::accept`]'s slack): [`Contacts::slip_tolerance`], the round-off of the step's
    /// velocities, for a row that is a velocity and zero in exact arithmetic: a sticking contact's
    /// other friction row (`tied`, [`Self::basis_solution`]) and, for several bodies, every
    /// contact's normal and friction rows (a face on a face closes them with its open loads,
    /// `super::stack`'s module docs, "The load": the unloaded fourth point's normal row, the
    /// friction rows of a loaded point that carries none); none for the `sigma` rows (a bound on
    /// an impulse) and the padding rows.
    ///
    /// Why the velocities' round-off and not the residual alone (`1024 N eps` of `||M|| ||z|| +
    /// ||q||`, `8e-3` of it in f32 for 64 rows, the stack's): a row beyond it is a slip the lines
    /// count as real. On a falling stack a loaded point with `p_n` alone basic comes out slipping
    /// along its line at `5e-5` m/s with no friction, its friction rows `-+5e-5`: a wrong mode.
    /// Accepted, it is the warm basis' answer again at every try of the lines
    /// ([`Contacts::solve_lines`]): turning a line moves that point's slip across the line but
    /// cannot change its mode, which only a pivot does, so the slips never run along the lines
    /// ([`StepError::ConeNotConverged`]). Within the bound the lines read the slip as none, and the
    /// answer is the one they converge on; beyond it the basis goes to Lemke's pivoting, which
    /// changes the mode. (A bound from the matrix alone, `N eps` of the same scale, is 25 times the
    /// velocities' round-off here.)
    fn slack(&self, tied: u64, row: usize) -> T {
        let structural =
            u32::try_from(row).ok().and_then(|i| tied.checked_shr(i)).is_some_and(|t| t & 1 == 1);
        let velocity = B > 1 && row < 4 * K && row % 4 != 3;
        if structural || velocity { self.slip_tolerance } else { T::zero() }
    }

    /// The answer of an LCP whose loads are open (`super::stack`'s module docs, "The load"), where
    /// Lemke's method failed: its tableau crosses the open loads' singular bases with more
    /// round-off than its answer's verification allows. The basis it ends in, from the cold start
    /// on `lcp` and then on `M + delta I` (`delta` from `16 N eps ||M||` up by sixteens,
    /// [`OPEN_LOAD_TRIES`] in all: strictly copositive, which Lemke's method always processes),
    /// is solved for itself: its system's least-norm solution ([`Self::least_norm_of`]), else
    /// Lemke's method from it on `lcp` and the least-norm solution of the basis it ends in. The
    /// first that [`Lemke::accept`] verifies on `lcp` is the answer; `None` when none does.
    fn open_load<const N: usize, const W: usize>(
        solver: &Lemke<T, N, W>,
        lcp: &Lcp<T, N>,
    ) -> Option<LcpSolution<T, N, W>> {
        let mut delta = T::zero();
        let mut regularized = *lcp;
        for _ in 0..OPEN_LOAD_TRIES {
            for i in 0..N {
                if let (Some(e), Some(m)) = (regularized.m.get_mut((i, i)), lcp.m.get((i, i))) {
                    *e = *m + delta;
                }
            }
            delta = if delta > T::zero() {
                delta * T::of(16.0)
            } else {
                T::of(16.0 * N as f64) * T::EPS * max(lcp.m_norm_inf(), T::TINY)
            };
            let Some(mut basis) = solver.terminal_basis(&regularized, Basis::all_w()) else { continue };
            // That basis' least-norm solution, else Lemke's method on `lcp` from it, whose end's
            // least-norm solution in turn.
            for _ in 0..2 {
                if let Some(answer) = Self::least_norm_of(solver, lcp, basis) {
                    return Some(answer);
                }
                let Some(next) = solver.terminal_basis(lcp, basis) else { break };
                basis = next;
            }
        }
        None
    }

    /// The least-norm solution of `basis`' system `M_bb z_b = -q_b` over its basic `z` ([`least_norm`]),
    /// round-off's negative entries zero, held to [`Lemke::accept`]'s residual on `lcp` (every row's
    /// slack infinite: the backward error Lemke's method verifies its own answers by; this is the
    /// answer after Lemke's method failed). `None` when it does not verify.
    fn least_norm_of<const N: usize, const W: usize>(
        solver: &Lemke<T, N, W>,
        lcp: &Lcp<T, N>,
        basis: Basis<N, W>,
    ) -> Option<LcpSolution<T, N, W>> {
        let (mut index, mut m) = ([0usize; N], 0usize);
        for i in (0..N).filter(|&i| basis.is_z_basic(i)) {
            if let Some(slot) = index.get_mut(m) {
                *slot = i;
                m += 1;
            }
        }
        // Row `r` of the system is the LCP's row `index[r]` (nothing beyond `m`).
        let row = |r: usize| index.get(r).copied().filter(|_| r < m);
        let system: [[T; N]; N] = core::array::from_fn(|r| {
            core::array::from_fn(|c| match (row(r), row(c)) {
                (Some(i), Some(j)) => lcp.m.get((i, j)).copied().unwrap_or(T::zero()),
                _ => T::zero(),
            })
        });
        let rhs: [T; N] =
            core::array::from_fn(|r| row(r).and_then(|i| lcp.q.get(i)).map_or(T::zero(), |q| -*q));
        let x = least_norm(&system, &rhs, m);
        let mut z = SVector::<T, N>::zeros();
        for (&i, &value) in index.iter().zip(&x).take(m) {
            if let Some(slot) = z.get_mut(i) {
                *slot = max(value, T::zero());
            }
        }
        solver.accept(lcp, &z, basis, |_| T::of(f64::INFINITY))
    }

    /// The complementary solution of `basis` for `lcp` by its reduced system (module docs): `None`
    /// when a contact's basic `z` are of no pattern listed there, a padding row's `z` or an inactive
    /// contact's is basic, or the system is numerically singular (a pivot within `N eps` of its
    /// largest entry). Its signs are not checked here ([`Lemke::accept`] does), but for two whose
    /// meaning does not change with them: a sticking contact's friction along its line that comes
    /// out negative is its other friction's (`basis` mirrored for that contact), and a sliding
    /// one's slip speed `sigma` below zero by no more than the step's velocity round-off is zero.
    /// With it the mask of the sticking contacts' other friction rows (`w_-d = -w_+d` while
    /// `sigma` is zero, both nil in exact arithmetic, their signs round-off's) and the basis whose
    /// answer it is.
    fn basis_solution<const N: usize, const W: usize>(
        &self,
        lcp: &Lcp<T, N>,
        basis: Basis<N, W>,
    ) -> Option<(SVector<T, N>, u64, Basis<N, W>)> {
        let zero = T::zero();
        // The padding rows' `z` are never basic in the contacts' answer.
        if (4 * K..N).any(|i| basis.is_z_basic(i)) {
            return None;
        }
        let (one, half) = (T::one(), T::of(0.5));
        let none: Unknown<T> = ([(0, zero); 3], 0);
        // The unknowns and, row for row, the rows of `w` they close; the sliding contacts' friction
        // rows and their `sigma`.
        // At most two a contact: `2 K` slots, filled in order.
        let (mut unknown_slots, mut row_slots, mut m) = ([[none; 2]; K], [[0usize; 2]; K], 0usize);
        let (unknowns, rows) = (unknown_slots.as_flattened_mut(), row_slots.as_flattened_mut());
        let (mut sigmas, mut slides) = ([(0usize, 0usize); K], 0usize);
        // The sticking contacts' basic friction and its other one.
        let (mut sticks, mut sticking) = ([(0usize, 0usize); K], 0usize);
        let mut tied = 0u64;
        let mut push = |unknown: Unknown<T>, row: usize| {
            if let (Some(u), Some(r)) = (unknowns.get_mut(m), rows.get_mut(m)) {
                (*u, *r) = (unknown, row);
                m += 1;
            }
        };
        for (i, c) in self.touches.iter().enumerate() {
            let b = 4 * i;
            let bits = contact_bits(basis, b);
            let plain = |variable| ([(variable, one), (variable, zero), (variable, zero)], 1);
            match (c.active, bits) {
                (_, 0b0000) => {}
                (true, 0b0001) => push(plain(b), b),
                (true, 0b0011 | 0b0101) => {
                    let (friction, other) = if bits == 0b0011 { (b + 1, b + 2) } else { (b + 2, b + 1) };
                    push(plain(b), b);
                    push(plain(friction), friction);
                    if let Some(s) = sticks.get_mut(sticking) {
                        *s = (friction, other);
                        sticking += 1;
                    }
                }
                (true, 0b1011 | 0b1101) => {
                    let friction = if bits == 0b1011 { b + 1 } else { b + 2 };
                    push(([(b, one), (friction, c.mu), (b, zero)], 2), b);
                    if let Some(s) = sigmas.get_mut(slides) {
                        *s = (friction, b + 3);
                        slides += 1;
                    }
                }
                // Sticking with both frictions basic and `sigma` zero: `p_+-d = (mu p_n +- p_t) / 2`.
                (true, 0b1111) => {
                    push(([(b, one), (b + 1, half * c.mu), (b + 2, half * c.mu)], 3), b);
                    push(([(b + 1, half), (b + 2, -half), (b, zero)], 2), b + 1);
                }
                _ => return None,
            }
        }
        let mut z = Self::solved_reduced(lcp, unknowns, rows, m)?;
        // A sticking contact's friction along its line holds either way: one that came out
        // negative is the other friction's, positive (its column and row are the first's negated,
        // but for `sigma`, which is zero: the mirrored basis' own answer, to the bit).
        let mut basis = basis;
        for &(friction, other) in sticks.iter().take(sticking) {
            let value = z.get(friction).copied().unwrap_or(zero);
            let tie = if value < zero {
                if let Some(p) = z.get_mut(friction) {
                    *p = zero;
                }
                if let Some(q) = z.get_mut(other) {
                    *q = -value;
                }
                basis.set_z_basic(friction, false);
                basis.set_z_basic(other, true);
                friction
            } else {
                other
            };
            tied |= row_bit(tie);
        }
        let entry = |r: usize, c: usize| lcp.m.get((r, c)).copied().unwrap_or(zero);
        // A sliding contact's `sigma` closes its friction row: `w_r = (M z + q)_r + M_rs sigma`;
        // `sigma` is its slip's speed, and one below zero by no more than the step's velocity
        // round-off (`slip_tolerance`: a contact at the edge of sticking) is zero.
        for &(row, sigma) in sigmas.iter().take(slides) {
            let rest =
                (0..N).fold(lcp.q.get(row).copied().unwrap_or(zero), |acc, j| acc + entry(row, j) * z[j]);
            let coefficient = entry(row, sigma);
            if coefficient <= zero {
                return None;
            }
            if let Some(slot) = z.get_mut(sigma) {
                let speed = -rest / coefficient;
                *slot = if speed < zero && speed >= -self.slip_tolerance {
                    // Its other friction row, `w = 2 sigma`, is then nil in exact arithmetic.
                    let other = if row + 1 == sigma { row - 1 } else { row + 1 };
                    tied |= row_bit(other);
                    zero
                } else {
                    speed
                };
            }
        }
        Some((z, tied, basis))
    }

    /// `z` of [`Self::basis_solution`]'s reduced system, its `m` unknowns and the rows they close
    /// (`None` as [`Self::reduced`]).
    fn solved_reduced<const N: usize>(
        lcp: &Lcp<T, N>,
        unknowns: &[Unknown<T>],
        rows: &[usize],
        m: usize,
    ) -> Option<SVector<T, N>> {
        // The system in an array of its own size: its elimination's loops run over the array's
        // rows and columns, so `m <= 8` unknowns (at most two a contact: always, up to four
        // contacts) go in an `8 x 8` array, not the problem's `N x N`, and up to 16 or 32 in
        // one of that size (the stack's); the same operations either way.
        let mut z = SVector::<T, N>::zeros();
        let mut spread = |x: &[T]| {
            for (u, &value) in unknowns.iter().zip(x).take(m) {
                for &(v, factor) in u.0.iter().take(u.1) {
                    if let Some(slot) = z.get_mut(v) {
                        *slot += factor * value;
                    }
                }
            }
        };
        match m {
            // Sizes below 8 for one body on up to four points (the boards' scenes) only: elsewhere
            // they would be code for systems that are seldom that small.
            0..=2 if 2 * K <= SMALL_SYSTEM => spread(&Self::reduced::<N, 2>(lcp, unknowns, rows, m)?),
            3 if 2 * K <= SMALL_SYSTEM => spread(&Self::reduced::<N, 3>(lcp, unknowns, rows, m)?),
            4 if 2 * K <= SMALL_SYSTEM => spread(&Self::reduced::<N, 4>(lcp, unknowns, rows, m)?),
            5 if 2 * K <= SMALL_SYSTEM => spread(&Self::reduced::<N, 5>(lcp, unknowns, rows, m)?),
            6 if 2 * K <= SMALL_SYSTEM => spread(&Self::reduced::<N, 6>(lcp, unknowns, rows, m)?),
            _ if 2 * K <= SMALL_SYSTEM || m <= SMALL_SYSTEM => {
                spread(&Self::reduced::<N, SMALL_SYSTEM>(lcp, unknowns, rows, m)?);
            }
            _ if m <= 16 => spread(&Self::reduced::<N, 16>(lcp, unknowns, rows, m)?),
            _ if 2 * K <= 32 || m <= 32 => spread(&Self::reduced::<N, 32>(lcp, unknowns, rows, m)?),
            _ => spread(&Self::reduced::<N, N>(lcp, unknowns, rows, m)?),
        }
        Some(z)
    }

    /// The reduced system of [`Self::basis_solution`]'s `m <= D` unknowns (each unknown's `z`
    /// moves, row for row the LCP's row it closes) solved in a `D x D` array: `None` when it is
    /// numerically singular (a pivot within `N eps` of its largest entry) for one body; for
    /// several, its solution of least norm ([`least_norm`]). Kept out of line: inlined, its arrays
    /// joined the frame of every instantiation of [`Self::answer`] (the curling stone's, whose
    /// systems never come here, grew by 8 kB of stack and 3,000 M4F instructions a step).
    #[inline(never)]
    fn reduced<const N: usize, const D: usize>(
        lcp: &Lcp<T, N>,
        unknowns: &[Unknown<T>],
        rows: &[usize],
        m: usize,
    ) -> Option<[T; D]> {
        let zero = T::zero();
        // The system into `a` and `x`, its largest entry's size returned: unknown by unknown, its
        // variables' columns of `M` (storage order) read at the rows, each entry its first
        // variable's term plus the others' (of a sum from zero, the same but for a zero's sign).
        let system = |a: &mut [[T; D]; D], x: &mut [T; D]| {
            let columns = lcp.m.as_slice();
            let column = |v: usize| columns.get(v * N..v * N + N).unwrap_or(&[]);
            let mut largest = zero;
            for (l, &([(v0, f0), (v1, f1), (v2, f2)], count)) in unknowns.iter().enumerate().take(m) {
                let (c0, c1, c2) = (column(v0), column(v1), column(v2));
                for (a_row, &row) in a.iter_mut().zip(rows).take(m) {
                    let at = |c: &[T]| c.get(row).copied().unwrap_or(zero);
                    let value = match count {
                        1 => f0 * at(c0),
                        2 => f0 * at(c0) + f1 * at(c1),
                        _ => f0 * at(c0) + f1 * at(c1) + f2 * at(c2),
                    };
                    if let Some(slot) = a_row.get_mut(l) {
                        *slot = value;
                    }
                    largest = max(largest, value.abs_exact());
                }
            }
            for (x_k, &row) in x.iter_mut().zip(rows).take(m) {
                *x_k = -lcp.q.get(row).copied().unwrap_or(zero);
            }
            largest
        };
        let (mut a, mut x) = ([[zero; D]; D], [zero; D]);
        let largest = system(&mut a, &mut x);
        let tiny = T::of(N as f64) * T::EPS * max(largest, T::TINY);
        // A small array is filled to its size with unknowns of their own, `largest x = 0`: the
        // elimination then runs over a constant size, its loops unrolled. Their rows and columns
        // are zero in the system's (no pivot is taken from them before their own, and their
        // `x` is zero), so the system's unknowns get the same operations in the same order.
        let size = if D <= SMALL_SYSTEM {
            for (k, row) in a.iter_mut().enumerate().skip(m) {
                if let Some(e) = row.get_mut(k) {
                    *e = max(largest, T::TINY);
                }
            }
            D
        } else {
            m
        };
        if !solve_leading(&mut a, &mut x, size, tiny) {
            // Four or more coplanar points of a face on a face (several bodies) leave the basis'
            // loads open: its solution of least norm (the load rule, `super`'s module docs, "The
            // load"), of the system made again (the elimination overwrote it). One body's
            // singular basis goes to Lemke's method.
            if B == 1 {
                return None;
            }
            let (mut a, mut rhs) = ([[zero; D]; D], [zero; D]);
            system(&mut a, &mut rhs);
            x = least_norm(&a, &rhs, m);
        }
        Some(x)
    }
}

/// The least-norm solution of the leading `m x m` system `a x = b` (possibly singular) by
/// iterated Tikhonov regularisation: from `x = 0`, [`LEAST_NORM_SWEEPS`] times `x += (A^T A + mu
/// I)^-1 A^T (b - A x)`, `mu = 64 eps` of `A^T A`'s largest diagonal entry. Each sweep shrinks the
/// error along a singular direction of value `s` by `mu / (s^2 + mu)` (`A^T A + mu I` factored once,
/// [`cholesky`]); a null direction, which
/// `A^T` never reaches, stays zero: for a consistent system, its solution of least norm. Its
/// residual is not checked here: the caller verifies the answer it builds from it.
fn least_norm<T: Real, const N: usize>(a: &[[T; N]; N], b: &[T; N], m: usize) -> [T; N] {
    let zero = T::zero();
    let mut normal = [[zero; N]; N];
    let mut largest = zero;
    for (r, row) in normal.iter_mut().enumerate().take(m) {
        for (c, e) in row.iter_mut().enumerate().take(m) {
            *e = a.iter().take(m).fold(zero, |acc, ak| acc + ak[r] * ak[c]);
        }
        largest = max(largest, row[r]);
    }
    let mu = T::of(64.0) * T::EPS * max(largest, T::TINY);
    let m = m.min(N);
    for (r, row) in normal.iter_mut().enumerate().take(m) {
        row[r] += mu;
    }
    let mut x = [zero; N];
    // `A^T A + mu I` is symmetric positive definite: factored once (Cholesky), solved each sweep.
    if !cholesky(&mut normal, m) {
        return x;
    }
    for _ in 0..LEAST_NORM_SWEEPS {
        let r: [T; N] = core::array::from_fn(|r| {
            if r < m {
                b[r] - a[r].iter().zip(&x).take(m).fold(zero, |acc, (a, x)| acc + *a * *x)
            } else {
                zero
            }
        });
        let mut step: [T; N] = core::array::from_fn(|c| {
            if c < m { a.iter().zip(&r).take(m).fold(zero, |acc, (ak, rk)| acc + ak[c] * *rk) } else { zero }
        });
        cholesky_solve(&normal, &mut step, m);
        for (x, s) in x.iter_mut().zip(&step).take(m) {
            *x += *s;
        }
    }
    x
}

/// The Cholesky factor `L` (`L L^T = g`) of `g`'s leading `m x m` block (`m <= N`), in place in its
/// lower triangle; `false` when a pivot is not positive (not positive definite to round-off).
fn cholesky<T: Real, const N: usize>(g: &mut [[T; N]; N], m: usize) -> bool {
    for i in 0..m {
        for j in 0..=i {
            let mut sum = g[i][j];
            for k in 0..j {
                sum -= g[i][k] * g[j][k];
            }
            if i == j {
                if sum <= T::zero() || !sum.finite() {
                    return false;
                }
                g[i][i] = sum.sqrt_rounded();
            } else {
                g[i][j] = sum / g[j][j];
            }
        }
    }
    true
}

/// `x` with `L L^T x = b` for [`cholesky`]'s factor `l` of the leading `m x m` block, in place.
fn cholesky_solve<T: Real, const N: usize>(l: &[[T; N]; N], b: &mut [T; N], m: usize) {
    for i in 0..m {
        let mut sum = b[i];
        for k in 0..i {
            sum -= l[i][k] * b[k];
        }
        b[i] = sum / l[i][i];
    }
    for i in (0..m).rev() {
        let mut sum = b[i];
        for k in i + 1..m {
            sum -= l[k][i] * b[k];
        }
        b[i] = sum / l[i][i];
    }
}

/// The regularisations an open load tries (`Contacts::open_load`), each a sixteenth of the last.
const OPEN_LOAD_TRIES: u32 = 5;

/// The sweeps of [`least_norm`]: enough for a singular value `s` with `s^2` a thousand times `mu`
/// to shrink its error below `eps`.
const LEAST_NORM_SWEEPS: u32 = 8;
