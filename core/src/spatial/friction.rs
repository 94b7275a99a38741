//! The impulses of one step's contacts: one friction line per contact, every line turned to its
//! contact's slip until each slip runs along its line, then each answer held to the circular
//! cone (`super`'s module docs, 3).

use super::algebra::{Vector, add, cross, direction, dot, norm, perpendicular, scale, sub};
use super::body::{Frame, Motion};
use super::report::{MAX_DIRECTIONS, Mode, SpatialContactReport};
use crate::StepError;
use crate::lcp::{Basis, Lcp, LcpSolution, Lemke};
use crate::real::{Real, max, min};

/// Every this many tries a solve whose worst slip across a line has not shrunk fourfold in the
/// last try starts its lines again from the cone's own problem ([`Contacts::restart`]); one that
/// has not restarted by half its tries (its worst slip swinging, shrunk in every fourth try)
/// restarts then.
const RESTART_EVERY: u32 = 4;

/// A contact's first line is its free slip's direction when that slip exceeds this many times
/// the step's round-off (its direction then known to about `1 / FREE_LINE` rad), else its rest
/// line where it has one ([`Touch::rest_line`]): a slip within a few round-offs points anywhere.
const FREE_LINE: f64 = 16.0;

/// The projected Gauss-Seidel sweeps of a restart ([`Contacts::restart`]).
const RESTART_SWEEPS: u32 = 256;

/// What the solve needs of one contact, per unit mass.
#[derive(Debug, Clone, Copy)]
pub(super) struct Touch<T> {
    /// Whether it is within the margin (and enters the LCP).
    pub active: bool,
    /// The contact point's offset from the centre of mass, world axes.
    pub arm: Vector<T>,
    /// Its free normal velocity with the gap's bias: the normal row's `q`.
    pub normal_free: T,
    /// Its free slip: the free relative velocity's part in the plane.
    pub slip_free: Vector<T>,
    /// The velocity of the support's material at the point (zero on a fixed plane; a moving
    /// finger's): slips are the body point's velocity less this.
    pub carried: Vector<T>,
    /// The friction line to start from when the free slip is within [`FREE_LINE`] times the
    /// step's round-off (`None`: the free slip's direction whatever its size, or the plane's
    /// `perpendicular`).
    pub rest_line: Option<Vector<T>>,
    /// Its friction coefficient this step.
    pub mu: T,
    /// The unit normal of its plane, world axes: the push on its body.
    pub normal: Vector<T>,
    /// The body it pushes (`+p`): its index in [`Contacts::bodies`].
    pub body: usize,
    /// The body beneath it, pushed back (`-p`), and the point's arm from that body's centre of
    /// mass (`None`: a fixed plane or a support; `super::space`).
    pub beneath: Option<(usize, Vector<T>)>,
}

impl<T: Real> Touch<T> {
    /// A slot that touches nothing this step (its plane's unit normal `normal`): inactive, every
    /// velocity zero, no rest line, pushing body 0.
    pub(super) fn idle(normal: Vector<T>) -> Self {
        let zero = [T::zero(); 3];
        Self {
            active: false,
            arm: zero,
            normal_free: T::zero(),
            slip_free: zero,
            carried: zero,
            rest_line: None,
            mu: T::zero(),
            normal,
            body: 0,
            beneath: None,
        }
    }
}

/// The turn's linear system ([`Contacts::turn`]): per row its contact, the direction of its
/// condition, its residual and its term on its own unknown; per unknown its contact and which of
/// the contact's unknowns it is; per contact and unknown, the impulse's change per unit of the
/// unknown and that change's sides `S` (`super::space`'s `Contacts::sides`).
pub(super) struct System<'a, T, S, const K: usize> {
    pub rows: &'a [(usize, Vector<T>, T, T)],
    pub unknowns: &'a [(usize, usize)],
    pub effects: &'a [[(Vector<T>, S); 3]; K],
}

/// One contact's friction line: a unit vector `d` in the plane; friction acts along `+d` or
/// `-d`.
#[derive(Debug, Clone, Copy)]
struct Line<T> {
    d: Vector<T>,
}

/// What a restart's sweeps need of one contact ([`Contacts::restart`]): its gap bias (its normal
/// row less its free point's normal velocity), its plane's axes `(t1, t2)`, `W_nn` and the
/// inverse of its tangential block of `W` (row by row).
type Local<T> = (T, Vector<T>, Vector<T>, T, [T; 4]);

/// The bodies' velocities after the step's impulses and each contact's report.
pub(super) type Solved<T, const K: usize> = ([SpatialContactReport<T>; K], Vector<T>, Vector<T>);

/// The contacts of `B` bodies (one on a plane or supports, or several resting on each other:
/// `super::space`), in the unknowns `(p_n, p_+d, p_-d, sigma)` of each contact in turn (`N = 4
/// K`), impulses per unit of the reference mass `mass`.
pub(super) struct Contacts<'a, T: Real, const K: usize, const B: usize = 1> {
    pub bodies: [Frame<'a, T>; B],
    /// The reference mass `m0`, kg: the first body's.
    pub mass: T,
    /// The plane's unit normal, for one body on one plane (the flat base's load, the pyramid).
    pub normal: Vector<T>,
    pub touches: &'a [Touch<T>; K],
    /// The round-off of the step's velocities: slips within it count as zero.
    pub slip_tolerance: T,
    /// Normal impulses per unit mass at or below it read separated.
    pub floor: T,
    /// The stick speed, m/s.
    pub stick_speed: T,
}

impl<T: Real, const K: usize, const B: usize> Contacts<'_, T, K, B> {
    /// Solves the step: the LCP of every contact's line, warm-started from `basis` (which it
    /// leaves at the last answer's), the lines turned until every active contact's slip runs
    /// along its line, each answer checked against the circular cone. The bodies' motion after
    /// the impulses on the free motion `free`, and each contact's report.
    ///
    /// # Errors
    /// [`StepError::Solver`], [`StepError::ConeNotConverged`], [`StepError::ConeUnverified`].
    pub fn solve_lines<const N: usize, const W: usize>(
        &self,
        solver: &Lemke<T, N, W>,
        basis: &mut Basis<N, W>,
        pivots: &mut u32,
        free: &Motion<T, B>,
    ) -> Result<([SpatialContactReport<T>; K], Motion<T, B>), StepError> {
        let zero = [T::zero(); 3];
        let mut lines = self.touches.map(|c| Line {
            d: match c.rest_line {
                Some(d) if norm(&c.slip_free) <= T::of(FREE_LINE) * self.slip_tolerance => d,
                _ => direction(&c.slip_free).unwrap_or_else(|| perpendicular(&c.normal)),
            },
        });
        // The worst slip across a line not held at the last try; whether the lines have been
        // restarted.
        let (mut last_worst, mut restarted) = (T::zero(), false);
        let mut lcp = Lcp::<T, N>::new(nalgebra::SMatrix::zeros(), nalgebra::SVector::zeros());
        for tries in 1..=MAX_DIRECTIONS {
            self.write_lcp(&lines, &mut lcp);
            let sol = self.answer(solver, &lcp, *basis)?;
            *basis = sol.basis;
            *pivots = pivots.saturating_add(sol.pivots);
            let mut impulses = [(T::zero(), T::zero()); K];
            let mut full = [zero; K];
            for (i, (c, line)) in self.touches.iter().zip(&lines).enumerate() {
                if c.active {
                    let (pn, pt) = (sol.z[4 * i], sol.z[4 * i + 1] - sol.z[4 * i + 2]);
                    full[i] = add(&scale(pn, &c.normal), &scale(pt, &line.d));
                    impulses[i] = (pn, pt);
                }
            }
            let motion = self.moved_all(&full, free);
            // Each contact's slip after the impulses, once a try.
            let slips: [Vector<T>; K] = core::array::from_fn(|i| Self::slip_in(&motion, &self.touches[i]));
            // After a restart, a contact slipping within the stick speed reads sticking, as its
            // report does: the cone alone holds it (its slip's direction is not asked for).
            let resting: [bool; K] = core::array::from_fn(|i| {
                restarted && norm(&slips[i]) <= max(self.slip_tolerance, self.stick_speed)
            });
            let held: [bool; K] = core::array::from_fn(|i| {
                let c = &self.touches[i];
                // An unloaded contact carries no friction on any line.
                !c.active
                    || impulses[i].0 <= T::zero()
                    || dot(&slips[i], &cross(&c.normal, &lines[i].d)).abs_exact() <= self.slip_tolerance
                    || resting[i]
            });
            if held.iter().all(|&h| h) {
                // The LCP's verification scale, `||M|| ||z|| + ||q||`, times its tolerance: what
                // a cone's condition may miss by in absolute terms.
                let bound = verification_bound(solver, &sol);
                let mut reports = [SpatialContactReport::separated(); K];
                for (i, c) in self.touches.iter().enumerate() {
                    if c.active {
                        let (pn, pt) = impulses[i];
                        reports[i] =
                            self.report(pn, &scale(pt, &lines[i].d), &slips[i], c.mu, (tries, bound, true))?;
                    }
                }
                return Ok((reports, motion));
            }
            let worst = self
                .touches
                .iter()
                .zip(&slips)
                .zip(&lines)
                .zip(&held)
                .filter(|(_, h)| !**h)
                .fold(T::zero(), |a, (((c, s), line), _)| {
                    max(a, dot(s, &cross(&c.normal, &line.d)).abs_exact())
                });
            let stalled = tries % RESTART_EVERY == 0 && worst * T::of(4.0) > last_worst
                || tries == MAX_DIRECTIONS / 2 && !restarted;
            last_worst = worst;
            if stalled {
                restarted = true;
                self.restart(&mut lines, &full, free);
            } else {
                self.turn::<N>(&mut lines, &impulses, &slips, &resting);
            }
        }
        Err(StepError::ConeNotConverged)
    }
}

impl<T: Real, const K: usize> Contacts<'_, T, K> {
    /// [`Self::solve_lines`] for the one body, on its free velocity `v_free` and angular velocity
    /// `w_free`.
    ///
    /// # Errors
    /// As [`Self::solve_lines`].
    pub fn solve<const N: usize>(
        &self,
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        v_free: &Vector<T>,
        w_free: &Vector<T>,
    ) -> Result<Solved<T, K>, StepError> {
        let (reports, [(v, w)]) = self.solve_lines(solver, basis, pivots, &[(*v_free, *w_free)])?;
        Ok((reports, v, w))
    }

    /// Solves the step with each contact's friction in a pyramid of `k` directions fixed in the
    /// plane ([`super::FrictionCone::Pyramid`]): one LCP (Stewart & Trinkle's), per contact the
    /// unknowns `(p_n, beta_1 .. beta_k, lambda)` and the rows `w_n = W_nn p_n + W_nd beta + u_n`,
    /// `w_l = W_ln p_n + W_ld beta + lambda + d_l . u_t`, `w_lambda = mu p_n - sum beta`.
    ///
    /// # Errors
    /// [`StepError::Solver`], [`StepError::ConeUnverified`] (a friction beyond `mu p_n`).
    pub fn solve_pyramid<const N: usize>(
        &self,
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        k: usize,
        v_free: &Vector<T>,
        w_free: &Vector<T>,
    ) -> Result<Solved<T, K>, StepError> {
        let n = self.normal;
        let (o, one) = (T::zero(), T::one());
        let t1 = perpendicular(&n);
        let t2 = cross(&n, &t1);
        let edge = |l: usize| {
            let angle = T::of(core::f64::consts::TAU) * T::of_count(u32::try_from(l).unwrap_or(0))
                / T::of_count(u32::try_from(k).unwrap_or(1));
            let (sin, cos) = angle.sin_cos_portable();
            add(&scale(cos, &t1), &scale(sin, &t2))
        };
        let size = k + 2;
        let mut m = [[o; N]; N];
        let mut q = [o; N];
        // Entries by `get_mut`: `k` is the scene's run-time count of directions, so no index here
        // is known in range at compile time, and none may panic (`scripts/panic-paths.sh`); the
        // scene sizes `N` for its directions (`PYRAMID_ROWS`), so none falls outside.
        let put = |m: &mut [[T; N]; N], r: usize, c: usize, v: T| {
            if let Some(e) = m.get_mut(r).and_then(|row| row.get_mut(c)) {
                *e = v;
            }
        };
        let put_q = |q: &mut [T; N], r: usize, v: T| {
            if let Some(e) = q.get_mut(r) {
                *e = v;
            }
        };
        for (i, ci) in self.touches.iter().enumerate() {
            let b = size * i;
            if !ci.active {
                for row in b..b + size {
                    put(&mut m, row, row, one);
                    put_q(&mut q, row, one);
                }
                continue;
            }
            // Row `a` of contact i reads the velocity along `ea` (the normal, then each edge).
            for a in 0..=k {
                let ea = if a == 0 { n } else { edge(a - 1) };
                for (j, cj) in self.touches.iter().enumerate().filter(|(_, c)| c.active) {
                    for c in 0..=k {
                        let fc = if c == 0 { n } else { edge(c - 1) };
                        put(&mut m, b + a, size * j + c, self.delassus(ci, &ea, cj, &fc));
                    }
                }
                if a > 0 {
                    put(&mut m, b + a, b + k + 1, one);
                    put(&mut m, b + k + 1, b + a, -one);
                    put_q(&mut q, b + a, dot(&ea, &ci.slip_free));
                }
            }
            put(&mut m, b + k + 1, b, ci.mu);
            put_q(&mut q, b, ci.normal_free);
        }
        pad(&mut m, &mut q, size * K);
        let lcp = Lcp::from_rows(&m, &q);
        let sol = solver.solve_warm(&lcp, *basis).map_err(StepError::Solver)?;
        *basis = sol.basis;
        *pivots = pivots.saturating_add(sol.pivots);
        let zero = [o; 3];
        let mut impulses = [(o, zero); K];
        let mut full = [zero; K];
        // Zipped, not indexed: no index that may panic (`scripts/panic-paths.sh`).
        let each = self.touches.iter().zip(impulses.iter_mut().zip(full.iter_mut())).enumerate();
        for (i, (_, (impulse, total))) in each.filter(|(_, (c, _))| c.active) {
            let z = |r: usize| sol.z.get(r).copied().unwrap_or(o);
            let pn = z(size * i);
            let pt = (0..k).fold(zero, |a, l| add(&a, &scale(z(size * i + 1 + l), &edge(l))));
            *total = add(&scale(pn, &n), &pt);
            *impulse = (pn, pt);
        }
        let (v, w) = self.moved(&full, v_free, w_free);
        let bound = verification_bound(solver, &sol);
        let mut reports = [SpatialContactReport::separated(); K];
        for ((c, &(pn, pt)), report) in self.touches.iter().zip(&impulses).zip(reports.iter_mut()) {
            if c.active {
                *report = self.report(pn, &pt, &Self::slip(&v, &w, c), c.mu, (1, bound, false))?;
            }
        }
        Ok((reports, v, w))
    }
}

impl<T: Real, const K: usize, const B: usize> Contacts<'_, T, K, B> {
    /// The LCP of the contacts' lines: per contact the rows of `p_n`, `p_+d`, `p_-d` and
    /// `sigma`; a contact beyond the margin's rows `w = z + 1` (its impulse zero). Each entry is
    /// [`Self::delassus`]'s, its two factors computed once a contact and direction (`r x e` and
    /// `I_w^-1 (r x f)`: `2 K` products with `I_w^-1`, not `4 K^2`), in place in the problem's matrix;
    /// `W` symmetric, each pair's once (`K (2 K + 1)` couplings, not `4 K^2`), the block below the
    /// diagonal the transpose of the one above.
    ///
    /// Written in place in `lcp`, which starts zero: which entries are written depends on which
    /// contacts are active alone, so the lines' next try writes the same entries again and the
    /// rest stay zero (one problem a solve, not one a try).
    fn write_lcp<const N: usize>(&self, lines: &[Line<T>; K], lcp: &mut Lcp<T, N>) {
        let (o, one) = (T::zero(), T::one());
        // Per contact, along its normal then its line: each side's `r x e` and `I_w^-1 (r x e)`.
        let sides = core::array::from_fn::<_, K, _>(|i| {
            let c = &self.touches[i];
            [self.sides(c, &c.normal), self.sides(c, &lines[i].d)]
        });
        let set = |lcp: &mut Lcp<T, N>, r: usize, c: usize, v: T| {
            if let Some(e) = lcp.m.get_mut((r, c)) {
                *e = v;
            }
        };
        for (i, ((ci, li), [sn_i, sd_i])) in self.touches.iter().zip(lines).zip(&sides).enumerate() {
            let b = 4 * i;
            if !ci.active {
                for k in b..b + 4 {
                    set(lcp, k, k, one);
                }
                continue;
            }
            for (j, ((cj, lj), [sn_j, sd_j])) in self.touches.iter().zip(lines).zip(&sides).enumerate() {
                if !cj.active {
                    continue;
                }
                let c = 4 * j;
                // `W` is symmetric (`e . W f = f . W e`): a block below the diagonal is the
                // transpose of the one above it, written already, each coupling computed once.
                if j < i {
                    for k in 0..3 {
                        for l in 0..3 {
                            let v = lcp.m.get((c + l, b + k)).copied().unwrap_or(o);
                            set(lcp, b + k, c + l, v);
                        }
                    }
                    continue;
                }
                let (ni, nj, di, dj) = (&ci.normal, &cj.normal, &li.d, &lj.d);
                // Two contacts on no common body do not couple: every entry `+0`, as the
                // coupling's empty sum.
                let (wnn, wnd, wdn, wdd) = if B == 1 || Self::share_a_body(ci, cj) {
                    let wnd = self.coupling(sn_i, ni, sd_j, dj);
                    (
                        self.coupling(sn_i, ni, sn_j, nj),
                        wnd,
                        if i == j { wnd } else { self.coupling(sd_i, di, sn_j, nj) },
                        self.coupling(sd_i, di, sd_j, dj),
                    )
                } else {
                    (o, o, o, o)
                };
                set(lcp, b, c, wnn);
                set(lcp, b, c + 1, wnd);
                set(lcp, b, c + 2, -wnd);
                set(lcp, b + 1, c, wdn);
                set(lcp, b + 1, c + 1, wdd);
                set(lcp, b + 1, c + 2, -wdd);
                set(lcp, b + 2, c, -wdn);
                set(lcp, b + 2, c + 1, -wdd);
                set(lcp, b + 2, c + 2, wdd);
            }
            set(lcp, b + 1, b + 3, one);
            set(lcp, b + 2, b + 3, one);
            set(lcp, b + 3, b, ci.mu);
            set(lcp, b + 3, b + 1, -one);
            set(lcp, b + 3, b + 2, -one);
        }
        for row in 4 * K..N {
            set(lcp, row, row, one);
        }
        for (i, (ci, li)) in self.touches.iter().zip(lines).enumerate() {
            let b = 4 * i;
            let entries = if ci.active {
                let ud = dot(&li.d, &ci.slip_free);
                [ci.normal_free, ud, -ud, o]
            } else {
                [one; 4]
            };
            for (k, v) in entries.into_iter().enumerate() {
                if let Some(e) = lcp.q.get_mut(b + k) {
                    *e = v;
                }
            }
        }
        for row in 4 * K..N {
            if let Some(e) = lcp.q.get_mut(row) {
                *e = one;
            }
        }
    }

    /// Turns the lines (module docs, 3) by one step of Newton's method on every loaded contact's
    /// conditions, the LCP's modes held. A loaded contact's normal row stays closed (`n . u = 0`)
    /// and its normal impulse moves by `dp_n`: with the point off the centre of mass `W` couples
    /// the normal and the slip, so every friction change moves the normal impulses and they move
    /// the slips. A sliding (saturated) contact `j` turns its line by `dtheta_j` about `n`, which
    /// moves its friction `p_j d_j` by `p_j dtheta_j a_j` (`a = n x d`; `p_j / p_n,j dp_n,j d_j`
    /// with its normal impulse, the friction staying on the cone's edge) and its condition, the
    /// slip across its line `a_j . s_j`, by `-dtheta_j (d_j . s_j)` besides; a sticking one
    /// changes its friction by `(dq_d, dq_a)` along `(d, a)`, toward the impulse that stops its
    /// slip (both components of its slip its conditions). The velocities move by the Delassus
    /// operator `W` of the impulses' changes; the linear system over all of them (at most `3 K`
    /// unknowns) is solved once and each line set to its new friction's direction. A contact is
    /// sliding here when its friction is on the cone's edge (within `1e-3`) and it slips along its
    /// line beyond round-off, or its friction is the edge's to `64 eps` (one stopped just inside
    /// the edge sticks); a sliding one `resting` (within the stick speed, after a restart) keeps
    /// its line, its friction following its normal impulse.
    fn turn<const N: usize>(
        &self,
        lines: &mut [Line<T>; K],
        impulses: &[(T, T); K],
        slips: &[Vector<T>; K],
        resting: &[bool; K],
    ) {
        let (zero, one) = (T::zero(), T::one());
        let loaded: [bool; K] = core::array::from_fn(|i| self.touches[i].active && impulses[i].0 > zero);
        let saturated: [bool; K] = core::array::from_fn(|i| {
            let (c, (pn, pt)) = (&self.touches[i], impulses[i]);
            loaded[i]
                && pt.abs_exact() >= c.mu * pn * (one - T::of(1e-3))
                && (dot(&lines[i].d, &slips[i]).abs_exact() > self.slip_tolerance
                    || pt.abs_exact() >= c.mu * pn * (one - T::of(64.0) * T::EPS))
        });
        // A sliding contact slipping within the stick speed (after a restart, `resting`) keeps
        // its line: its slip's direction is not asked for, its friction follows its normal
        // impulse.
        let kept: [bool; K] = core::array::from_fn(|i| resting[i] && saturated[i]);
        let across: [Vector<T>; K] = core::array::from_fn(|i| cross(&self.touches[i].normal, &lines[i].d));
        // Unknowns `3 i`, `3 i + 1`, `3 i + 2` of contact `i`: `(dp_n, dtheta, -)` sliding,
        // `(dp_n, dq_d, dq_a)` sticking; an unknown no contact uses has the row `x = 0`.
        // `N = 4 K >= 3 K`. The impulse's change per unit of unknown `3 j + k`.
        let effect = |j: usize, k: usize| -> Vector<T> {
            let ((pn, pt), n) = (impulses[j], self.touches[j].normal);
            match (saturated[j], k) {
                (true, 0) => add(&n, &scale(pt / pn, &lines[j].d)),
                (false, 0) => n,
                (true, 1) => scale(pt, &across[j]),
                (false, 1) => lines[j].d,
                (false, _) => across[j],
                (true, _) => [zero; 3],
            }
        };
        let counts: [usize; K] = core::array::from_fn(|j| match (kept[j], saturated[j]) {
            (true, _) => 1,
            (false, true) => 2,
            (false, false) => 3,
        });
        let used = |j: usize| counts.get(j).copied().unwrap_or(0);
        // Each unknown's impulse change and its sides ([`Self::sides`]: its turns), once: every
        // condition's row reads them.
        let effects: [[(Vector<T>, _); 3]; K] = core::array::from_fn(|j| {
            core::array::from_fn(|k| {
                if loaded[j] && k < used(j) {
                    let f = effect(j, k);
                    (f, self.sides(&self.touches[j], &f))
                } else {
                    ([zero; 3], [None, None])
                }
            })
        });
        // The system over the loaded contacts' unknowns alone, in order (`m <= 3 K`), row for row
        // the conditions they hold: contact `i`'s normal row (closed at the LCP's answer: no
        // residual); sliding, the slip across its line; sticking, its slip across and along `d`.
        // Row `r`: its contact, its direction, its residual and its term on its own unknown (a
        // sliding contact's condition moves by `-dtheta (d . s)` besides); unknown `r`: `(j, k)`.
        let mut rows = [(0usize, [zero; 3], zero, zero); N];
        let mut unknowns = [(0usize, 0usize); N];
        let mut m = 0;
        for (i, ci) in self.touches.iter().enumerate().filter(|&(i, _)| loaded.get(i) == Some(&true)) {
            let (Some(a), Some(line), Some(slip)) = (across.get(i), lines.get(i), slips.get(i)) else {
                continue;
            };
            let own = if saturated.get(i) == Some(&true) { -dot(&line.d, slip) } else { zero };
            let conditions =
                [(ci.normal, zero, zero), (*a, -dot(a, slip), own), (line.d, -dot(&line.d, slip), zero)];
            for (k, &(e, r, own)) in conditions.iter().enumerate().take(used(i)) {
                if let (Some(row), Some(unknown)) = (rows.get_mut(m), unknowns.get_mut(m)) {
                    (*row, *unknown) = ((i, e, r, own), (i, k));
                    m += 1;
                }
            }
        }
        let system = System {
            rows: rows.get(..m).unwrap_or(&[]),
            unknowns: unknowns.get(..m).unwrap_or(&[]),
            effects: &effects,
        };
        // In an array of `3 K` for up to three contacts (a puck's, the meter stick's), else `N`.
        let solved_x: [T; N] = match K {
            1 => self.turn_solved::<3, N>(&system),
            2 => self.turn_solved::<6, N>(&system),
            3 => self.turn_solved::<9, N>(&system),
            _ => self.turn_solved::<N, N>(&system),
        };
        let mut x = [zero; N];
        for (&(j, k), &value) in unknowns.iter().zip(&solved_x).take(m) {
            put_in(&mut x, 3 * j + k, value);
        }
        for i in (0..K).filter(|&i| loaded[i] && !kept[i]) {
            let (d, a) = (lines[i].d, across[i]);
            let next = if saturated[i] {
                // The turn by `dtheta` to first order, `d + dtheta a` (normalised below): Newton's
                // step needs no more, and no sine. A turn of more than a right angle is no longer
                // a correction: it is held to `tan` of 1.5 rad.
                let angle = max(min(entry(&x, 3 * i + 1), T::of(14.0)), T::of(-14.0));
                add(&d, &scale(angle, &a))
            } else {
                add(&scale(impulses[i].1 + entry(&x, 3 * i + 1), &d), &scale(entry(&x, 3 * i + 2), &a))
            };
            lines[i].d = direction(&next).unwrap_or(d);
        }
    }

    /// The restart (`super`'s module docs, 3): the lines from the circular cone's own problem,
    /// solved roughly by [`RESTART_SWEEPS`] sweeps of projected Gauss-Seidel from the impulses
    /// `full` (per unit mass, on the free velocities `v_free`, `w_free`): contact by contact, the
    /// normal impulse that closes its row (`p_n >= 0`), then the friction that stops its slip
    /// (its tangential block of `W` inverted) held to the disc `|p_t| <= mu p_n`. Each active
    /// contact's line is then its friction's direction (kept where it has none).
    fn restart(&self, lines: &mut [Line<T>; K], full: &[Vector<T>; K], free: &Motion<T, B>) {
        let zero = T::zero();
        let mut p = *full;
        let mut motion = self.moved_all(&p, free);
        let local: [Local<T>; K] = core::array::from_fn(|i| {
            let c = &self.touches[i];
            let n = c.normal;
            let bias = c.normal_free - dot(&n, &Self::velocity(free, c));
            let t1 = lines[i].d;
            let t2 = cross(&n, &t1);
            let (a11, a12) = (self.delassus(c, &t1, c, &t1), self.delassus(c, &t1, c, &t2));
            let (a21, a22) = (self.delassus(c, &t2, c, &t1), self.delassus(c, &t2, c, &t2));
            let det = a11 * a22 - a12 * a21;
            let inverse = if det > zero { [a22 / det, -a12 / det, -a21 / det, a11 / det] } else { [zero; 4] };
            (bias, t1, t2, self.delassus(c, &n, c, &n), inverse)
        });
        for _ in 0..RESTART_SWEEPS {
            for ((c, &(bias, t1, t2, wnn, [b11, b12, b21, b22])), p) in
                self.touches.iter().zip(&local).zip(p.iter_mut()).filter(|((c, _), _)| c.active)
            {
                let n = c.normal;
                let u = Self::velocity(&motion, c);
                let pn_now = dot(&n, p);
                let pn = if wnn > zero { max(pn_now - (dot(&n, &u) + bias) / wnn, zero) } else { pn_now };
                let (s1, s2) = (dot(&t1, &u), dot(&t2, &u));
                let (q1, q2) = (b11 * s1 + b12 * s2, b21 * s1 + b22 * s2);
                let pt = sub(p, &scale(pn_now, &n));
                let mut next = sub(&pt, &add(&scale(q1, &t1), &scale(q2, &t2)));
                let (size, limit) = (norm(&next), c.mu * pn);
                if size > limit {
                    next = scale(limit / size, &next);
                }
                let change = sub(&add(&scale(pn, &n), &next), p);
                *p = add(p, &change);
                self.push(&mut motion, c, &change);
            }
        }
        for ((line, c), p) in lines.iter_mut().zip(self.touches).zip(&p) {
            if let Some(d) = direction(&sub(p, &scale(dot(&c.normal, p), &c.normal))).filter(|_| c.active) {
                line.d = d;
            }
        }
    }

    /// The report of a contact whose impulse per unit mass is `pn` along the normal and `pt` in
    /// the plane, slipping at `slip` after the step, held to the circular cone's conditions (every
    /// LCP answer is verified already; this checks the cone the LCP's line stood for). Then: the
    /// tries it took, `bound` (the LCP's verification scale, in impulse per unit mass), and
    /// whether the friction must oppose the slip (not a pyramid's).
    pub(super) fn report(
        &self,
        pn: T,
        pt: &Vector<T>,
        slip: &Vector<T>,
        mu: T,
        (tries, bound, against_slip): (u32, T, bool),
    ) -> Result<SpatialContactReport<T>, StepError> {
        let limit = mu * pn;
        let (slip_speed, friction) = (norm(slip), norm(pt));
        // A slip within the stick speed reads sticking (in f32 its direction can be round-off's):
        // the cone alone holds it.
        let sliding =
            pn > T::zero() && limit > T::zero() && slip_speed > max(self.slip_tolerance, self.stick_speed);
        let residual = if pn <= T::zero() {
            T::zero()
        } else if limit <= T::zero() {
            friction / pn
        } else if sliding {
            // Sliding: the cone's edge against the slip.
            norm(&add(pt, &scale(limit / slip_speed, slip))) / limit
        } else {
            max(friction - limit, T::zero()) / limit
        };
        // Held to `4096 eps` of the cone, or, for a cone far smaller than the LCP's own scale (a
        // light load at the edge of sticking), to the LCP's verification on that scale.
        // A pyramid's friction need not oppose the slip (`against_slip` false): only its bound,
        // `|p_t| <= mu p_n`, is a failure; its residual against the circle is reported.
        // A sliding contact's slip is known to the step's round-off, `slip_tolerance` (the
        // solve's own test of it), so its direction to `slip_tolerance / |s|`: its friction is
        // held to `-mu p_n` along the slip, short of it by at most `mu p_n (1 - cos)` of that angle
        // (at most `mu p_n` times half its square), and across it to `mu p_n` times the angle.
        let excess = if !against_slip {
            max(friction - limit, T::zero()) / max(limit, T::TINY)
        } else if sliding {
            let along = dot(pt, slip) / slip_speed;
            let across = norm(&sub(pt, &scale(along / slip_speed, slip)));
            let angle = self.slip_tolerance / slip_speed;
            // The part against the slip short of the edge (`>= 0`), or beyond it.
            let short = along + limit;
            let along_miss = if short >= T::zero() {
                max(short - limit * angle * angle * T::of(0.5), T::zero())
            } else {
                -short
            };
            max(along_miss, max(across - limit * angle, T::zero())) / limit
        } else {
            residual
        };
        if !residual.finite() || (excess > T::of(4096.0) * T::EPS && excess * limit > bound) {
            return Err(StepError::ConeUnverified { residual: residual.as_f32() });
        }
        let mode = if pn <= self.floor {
            Mode::Separated
        } else if slip_speed <= self.stick_speed {
            Mode::Sticking
        } else {
            Mode::Sliding
        };
        let m = self.mass;
        Ok(SpatialContactReport {
            mode,
            normal_impulse: pn * m,
            friction_impulse: scale(m, pt),
            slip: *slip,
            directions: tries,
            cone_residual: residual,
        })
    }
}

/// `x` with `m x = b`, by Gaussian elimination with partial pivoting; a pivot of zero leaves its
/// unknown zero (a contact whose turn the system does not decide keeps its line).
pub(super) fn solved<T: Real, const K: usize>(mut m: [[T; K]; K], mut b: [T; K]) -> [T; K] {
    for col in 0..K {
        let mut pivot = col;
        for row in col + 1..K {
            if m[row][col].abs_exact() > m[pivot][col].abs_exact() {
                pivot = row;
            }
        }
        m.swap(col, pivot);
        b.swap(col, pivot);
        let p = m[col][col];
        if p == T::zero() {
            continue;
        }
        for row in col + 1..K {
            let f = m[row][col] / p;
            for k in col..K {
                m[row][k] -= f * m[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [T::zero(); K];
    for col in (0..K).rev() {
        let mut sum = b[col];
        for k in col + 1..K {
            sum -= m[col][k] * x[k];
        }
        if m[col][col] != T::zero() {
            x[col] = sum / m[col][col];
        }
    }
    x
}

/// `m[r][c] = v`, or nothing where `(r, c)` is beyond `m`: a contact's rows are computed (`3 i`,
/// `size * j + c`), so no index is known in range at compile time and none may panic
/// (`scripts/panic-paths.sh`); the scene sizes `N` for its contacts, so none falls outside.
pub(super) fn put<T: Real, const N: usize>(m: &mut [[T; N]; N], r: usize, c: usize, v: T) {
    if let Some(e) = m.get_mut(r).and_then(|row| row.get_mut(c)) {
        *e = v;
    }
}

/// `row[c] = v` ([`put`]).
pub(super) fn put_row<T: Real, const N: usize>(row: &mut [T; N], c: usize, v: T) {
    if let Some(e) = row.get_mut(c) {
        *e = v;
    }
}

/// `x[r] = v` ([`put`]).
pub(super) fn put_in<T: Real, const N: usize>(x: &mut [T; N], r: usize, v: T) {
    if let Some(e) = x.get_mut(r) {
        *e = v;
    }
}

/// `x[r]`, zero beyond `x` ([`put`]).
fn entry<T: Real, const N: usize>(x: &[T; N], r: usize) -> T {
    x.get(r).copied().unwrap_or(T::zero())
}

/// Rows `from..N` of an LCP no contact uses: `w = z + 1` (their `z` zero).
pub(super) fn pad<T: Real, const N: usize>(m: &mut [[T; N]; N], q: &mut [T; N], from: usize) {
    for row in from..N {
        m[row][row] = T::one();
        q[row] = T::one();
    }
}

/// What a cone's condition may miss by, in impulse per unit mass: the LCP's verification
/// tolerance times the scale its answer was verified on, `||M|| ||z|| + ||q||`
/// ([`LcpSolution::scale`], `crate::lcp::verify`), four times over.
pub(super) fn verification_bound<T: Real, const N: usize, const W: usize>(
    solver: &Lemke<T, N, W>,
    sol: &LcpSolution<T, N, W>,
) -> T {
    T::of(4.0) * solver.tolerance() * sol.scale
}
