//! The load of a flat base (`super`'s module docs, "The load"): four or more points touching the
//! plane, every one sliding, carry the normal impulses of least 2-norm that give the body's motion
//! out of the plane (`docs/formulation.md`, "The load: the least norm").
//!
//! With each point's friction along its slip, `p_t,i = -mu p_n,i s_i` (`s_i` the unit slip after
//! the step), contact `i`'s impulse per unit mass is `x_i e_i`, `e_i = n - mu s_i`, and the body's
//! velocity changes by `sum x_i e_i` and its angular velocity by `m I_w^-1 sum x_i (r_i x e_i)`.
//! Its motion out of the plane, `(n . v, t1 . omega, t2 . omega)` (`t1`, `t2` the plane's axes), is
//! what holds each point on the plane: three linear conditions `G x = g`, `g` the LCP's answer's.
//! The friction's size follows the load (`mu x_i`), so the normal impulses' least norm is the
//! impulses' (`sum x_i^2 (1 + mu^2)`, one `mu` for every point of one plane). The least-norm point of
//! `{x : G x = g}` is `x0 = G^T (G G^T)^-1 g`; when some `x0_i < 0` the problem's optimality
//! conditions are the LCP `w = P lambda + x0`, `P = I - G^T (G G^T)^-1 G` (positive semidefinite),
//! `x = w` (as `core/src/load.rs` for the planar core), solved by Lemke's method and verified.
//!
//! The load moves the body's motion in the plane (every point's friction has its own direction),
//! so the slips move: the directions are set to the new slips and the load taken again until they
//! agree within the step's round-off, at most [`LOAD_TRIES`] times ([`PATIENT_TRIES`], each try
//! halfway to the slips, when the contacts' LCP did not converge either).
//!
//! # Points that stop
//!
//! A base of point loads ends turning about one of its points (`docs/scenes.md`, "curling", "The
//! layout"), and its last step brings every point to rest. Both are stepped on the same load:
//! - **a pivot**: the touching point of least slip before the step. The others slide as above;
//!   the pivot carries its least-norm normal load and, in the plane, the impulse `f = -D^-1 s`
//!   that stops its slip `s` under the others' impulses (`D` its 2x2 Delassus matrix on the plane's
//!   axes) when `|f| <= mu x` (it sticks), or else the impulse on the cone's edge against the slip
//!   it is left with, `f = -(D + lambda I)^-1 s`, `|f| = mu x` (the slip after is `-lambda f`);
//! - **a rest**: three unknowns that stop the base in the plane (`t1 . v`, `t2 . v`, `n . omega`
//!   nil: for a base in the plane of its centre of mass every point then rests), each point's
//!   friction within its cone: first the friction affine in the points' position, `a + b n x r_i`
//!   (the least norm that stops the base), else the pivot's impulse in the plane and every other
//!   point's friction along its slip times one common factor.
//!
//! The friction's push out of the plane (nil for a base in the plane of the centre of mass) is
//! taken off `g` and the load taken again until it settles. The pivot is tried when a point's slip
//! is within the stick speed before the step or the base's sliding as a whole does not answer; the
//! rest when the pivot does not. A step none of them answers (two points within the stick speed
//! before it, directions that do not settle, a friction beyond its cone) is the contacts' LCP's,
//! with its vertex load.

use super::algebra::{Vector, add, cross, direction, dot, norm, perpendicular, scale, sub};
use super::friction::{Contacts, Solved, Touch, pad, put, put_in, solved};
use super::report::SpatialContactReport;
use crate::StepError;
use crate::lcp::{Basis, Lcp, Lemke};
use crate::real::{Real, max};

/// The most times a flat base's directions are set to its slips, or a stopping point's friction
/// and the load taken again in turn (module docs), before the step takes another way.
pub(super) const LOAD_TRIES: u32 = 16;

/// The most times a flat base's directions are moved toward its slips when the contacts' LCP did
/// not converge either ([`Contacts::flat_base`]'s last try), each time halfway (the bisector of
/// the direction and the slip's): near a base's stop the directions set to the slips close in by
/// a factor that grows toward one (a curling stone spun at `1e3` rad/s, in f64, two seconds
/// before it stops: 0.2 a try, 16 tries short of the round-off), or swing between two sets.
pub(super) const PATIENT_TRIES: u32 = 256;

/// The fewest points touching the plane whose load is left open by the motion: three not in a
/// line decide theirs.
pub(super) const OPEN_FROM: usize = 4;

/// Each point's normal load and friction held (`Contacts::held_load`), per unit mass.
type HeldLoad<T, const K: usize> = ([T; K], [Vector<T>; K]);

/// Which points of a flat base stop in the step (module docs, "Points that stop").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stop {
    /// None: every point slides.
    None,
    /// This one: the body turns about it, the others sliding.
    Pivot(usize),
    /// All: the base comes to rest in the plane, its friction affine in the points' position
    /// (`None`) or this one the pivot.
    Rest(Option<usize>),
}

impl<T: Real, const K: usize> Contacts<'_, T, K> {
    /// The step of a flat base, without the contacts' LCP: every active point (at least
    /// [`OPEN_FROM`]) touching, the motion out of the plane that closes every point's normal row
    /// (`n . v + (r_i x n) . omega` with the gap's bias, by least squares over the points, their
    /// residual within round-off), then the least-norm load of that motion with every point
    /// sliding, or one point stopping (a pivot), or all (a rest) (module docs). `None` where none
    /// applies: too few points, a point that lifts (a residual) or needs a pull (no load `x >= 0`),
    /// or none of the three (module docs, "Points that stop"); the step is then the LCP's. The
    /// directions are set to the slips at most `tries` times: [`LOAD_TRIES`], or, after the LCP's
    /// lines did not converge, [`PATIENT_TRIES`] each halfway to the slips.
    ///
    /// # Errors
    /// As [`Self::least_norm`].
    pub fn flat_base<const N: usize>(
        &self,
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        v_free: &Vector<T>,
        w_free: &Vector<T>,
        tries: u32,
    ) -> Result<Option<Solved<T, K>>, StepError> {
        let moving = max(self.slip_tolerance, self.stick_speed);
        let touching: [bool; K] = core::array::from_fn(|i| self.touches[i].active);
        if touching.iter().filter(|&&t| t).count() < OPEN_FROM {
            return Ok(None);
        }
        let slow = self.touches.iter().filter(|c| c.active && norm(&c.slip_free) <= moving).count();
        let (n, zero) = (self.normal, T::zero());
        let (t1, lever) = self.plane_axes();
        let t2 = cross(&n, &t1);
        // Point i's normal velocity per unit of the motion out of the plane `y`:
        // `y_0 + (r_i x n) . (t1 y_1 + t2 y_2) / lever`.
        let rows: [[T; 3]; K] = core::array::from_fn(|i| {
            let a = cross(&self.touches[i].arm, &n);
            [T::one(), dot(&a, &t1) / lever, dot(&a, &t2) / lever]
        });
        let mut normal_matrix = [[zero; 3]; 3];
        let mut rhs = [zero; 3];
        for ((row, _), c) in rows.iter().zip(&touching).zip(self.touches).filter(|((_, t), _)| **t) {
            for a in 0..3 {
                rhs[a] -= row[a] * c.normal_free;
                for b in 0..3 {
                    normal_matrix[a][b] += row[a] * row[b];
                }
            }
        }
        let g = solved(normal_matrix, rhs);
        let closes =
            self.touches.iter().zip(touching).zip(&rows).filter(|((_, t), _)| *t).all(|((c, _), row)| {
                let w = c.normal_free + row[0] * g[0] + row[1] * g[1] + row[2] * g[2];
                w.abs_exact() <= self.slip_tolerance
            });
        if !closes {
            return Ok(None);
        }
        let slips = self.touches.map(|c| c.slip_free);
        let mut settle = |stop| {
            self.settle(solver, basis, pivots, &touching, slips, &g, v_free, w_free, (false, tries), stop)
        };
        if slow == 0
            && let Some(answer) = settle(Stop::None)?
        {
            return Ok(Some(answer));
        }
        // One point sticks (the body turns about it): the slowest.
        let pivot = self
            .touches
            .iter()
            .enumerate()
            .filter(|(_, c)| c.active)
            .fold(None, |best: Option<(usize, T)>, (i, c)| {
                let s = norm(&c.slip_free);
                match best {
                    Some((_, b)) if b <= s => best,
                    _ => Some((i, s)),
                }
            })
            .map(|(i, _)| i);
        let Some(j) = pivot else {
            return Ok(None);
        };
        if slow <= 1
            && let Some(answer) = settle(Stop::Pivot(j))?
        {
            return Ok(Some(answer));
        }
        if let Some(answer) = settle(Stop::Rest(None))? {
            return Ok(Some(answer));
        }
        settle(Stop::Rest(Some(j)))
    }

    /// The least-norm load of the LCP's answer `path` (module docs), or `path` itself when fewer
    /// than [`OPEN_FROM`] points touch or one of them does not slide.
    ///
    /// # Errors
    /// [`StepError::Solver`] (the least-norm LCP), [`StepError::ConeUnverified`] (the load misses
    /// the motion out of the plane, or an answer the circular cone's conditions, beyond
    /// round-off).
    pub fn least_norm<const N: usize>(
        &self,
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        path: Solved<T, K>,
        v_free: &Vector<T>,
        w_free: &Vector<T>,
    ) -> Result<Solved<T, K>, StepError> {
        let (reports, v0, w0) = path;
        let (n, zero) = (self.normal, T::zero());
        let (dv, dw) = (sub(&v0, v_free), sub(&w0, w_free));
        let moving = max(self.slip_tolerance, self.stick_speed);
        // A point touches when it carries load or its normal velocity after the step is nil.
        let touching: [bool; K] = core::array::from_fn(|i| {
            let c = &self.touches[i];
            let normal = c.normal_free + dot(&n, &add(&dv, &cross(&dw, &c.arm)));
            c.active && (reports[i].normal_impulse > zero || normal <= self.slip_tolerance)
        });
        if touching.iter().filter(|&&t| t).count() < OPEN_FROM {
            return Ok(path);
        }
        let mut slips = [[zero; 3]; K];
        for ((c, _), slip) in
            self.touches.iter().zip(&touching).zip(slips.iter_mut()).filter(|((_, t), _)| **t)
        {
            *slip = Self::slip(&v0, &w0, c);
            if norm(slip) <= moving {
                return Ok(path);
            }
        }
        let (t1, lever) = self.plane_axes();
        let t2 = cross(&n, &t1);
        let g = [dot(&n, &dv), lever * dot(&t1, &dw), lever * dot(&t2, &dw)];
        let settled = self.settle(
            solver,
            basis,
            pivots,
            &touching,
            slips,
            &g,
            v_free,
            w_free,
            (true, LOAD_TRIES),
            Stop::None,
        )?;
        Ok(settled.unwrap_or(path))
    }

    /// The plane's first axis `t1` and the largest lever (the angular rows' scale, in velocity's
    /// units).
    fn plane_axes(&self) -> (Vector<T>, T) {
        let lever = self.touches.iter().fold(T::TINY, |a, c| max(a, norm(&c.arm)));
        (perpendicular(&self.normal), lever)
    }

    /// The least-norm load of the `touching` points that moves the body out of the plane by `g`
    /// (`(n . dv, lever t1 . domega, lever t2 . domega)`), each sliding point's friction along its
    /// slip, the slips set again until they agree (module docs); the points `stop` names carry the
    /// friction `held_load` gives them (module docs, "Points that stop"). `None` when a sliding
    /// point would stop or turn back, a point at rest would not, the directions do not settle in
    /// `most` tries (beyond [`LOAD_TRIES`], each halfway to the slips), or `held_load` gives none
    /// (or, unless `feasible`, no load `x >= 0` gives `g`).
    #[allow(clippy::too_many_arguments)]
    fn settle<const N: usize>(
        &self,
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        touching: &[bool; K],
        mut slips: [Vector<T>; K],
        g: &[T; 3],
        v_free: &Vector<T>,
        w_free: &Vector<T>,
        (feasible, most): (bool, u32),
        stop: Stop,
    ) -> Result<Option<Solved<T, K>>, StepError> {
        let (n, zero) = (self.normal, T::zero());
        let moving = max(self.slip_tolerance, self.stick_speed);
        let (t1, lever) = self.plane_axes();
        let t2 = cross(&n, &t1);
        let out_of_plane =
            |v: &Vector<T>, w: &Vector<T>| [dot(&n, v), lever * dot(&t1, w), lever * dot(&t2, w)];
        let size = g.iter().fold(T::TINY, |a, x| max(a, x.abs_exact()));
        let round_off = T::of(64.0 * K as f64) * T::EPS * size;
        // A point that stops carries the friction `held_load` gives it, along no slip.
        let is_pivot = |i: usize| matches!(stop, Stop::Rest(_)) || stop == Stop::Pivot(i);
        for tries in 1..=most {
            let unit: [Vector<T>; K] = core::array::from_fn(|i| {
                if is_pivot(i) { [zero; 3] } else { direction(&slips[i]).unwrap_or([zero; 3]) }
            });
            let e: [Vector<T>; K] = core::array::from_fn(|i| sub(&n, &scale(self.touches[i].mu, &unit[i])));
            // G's column of point i: the motion out of the plane per unit of its load.
            let columns: [[T; 3]; K] = core::array::from_fn(|i| {
                if !touching[i] {
                    return [zero; 3];
                }
                let turn = self.inverse_inertia().times(&cross(&self.touches[i].arm, &e[i]));
                out_of_plane(&e[i], &scale(self.body().mass, &turn))
            });
            let Some((x, held)) = self.held_load(
                solver, basis, pivots, &columns, touching, g, &e, v_free, w_free, feasible, stop,
            )?
            else {
                return Ok(None);
            };
            let impulses: [Vector<T>; K] = core::array::from_fn(|i| add(&scale(x[i], &e[i]), &held[i]));
            let (v, w) = self.moved(&impulses, v_free, w_free);
            let next: [Vector<T>; K] = core::array::from_fn(|i| Self::slip(&v, &w, &self.touches[i]));
            if (0..K).any(|i| touching[i] && !is_pivot(i) && norm(&next[i]) <= moving)
                || matches!(stop, Stop::Rest(_)) && (0..K).any(|i| touching[i] && norm(&next[i]) > moving)
            {
                return Ok(None);
            }
            let agree = (0..K).all(|i| {
                !touching[i]
                    || is_pivot(i)
                    || dot(&next[i], &cross(&n, &unit[i])).abs_exact() <= self.slip_tolerance
                        && dot(&next[i], &unit[i]) > zero
            });
            if !agree {
                // A patient solve's directions go halfway: a swing between two sets damps out.
                slips = if most > LOAD_TRIES {
                    core::array::from_fn(|i| add(&unit[i], &direction(&next[i]).unwrap_or([zero; 3])))
                } else {
                    next
                };
                continue;
            }
            // Verified: the motion out of the plane is `g`, each answer the cone's.
            let reached = out_of_plane(&sub(&v, v_free), &sub(&w, w_free));
            let miss = (0..3).fold(zero, |a, k| max(a, (reached[k] - g[k]).abs_exact()));
            if miss.partial_cmp(&round_off) != Some(core::cmp::Ordering::Less) && miss != zero {
                return Err(StepError::ConeUnverified { residual: (miss / size).as_f32() });
            }
            let mut out = [SpatialContactReport::separated(); K];
            // Zipped, not indexed: no index that may panic (`scripts/panic-paths.sh`).
            let each = self
                .touches
                .iter()
                .zip(touching)
                .zip(out.iter_mut())
                .zip(x.iter().zip(unit.iter().zip(&next)))
                .zip(&held)
                .enumerate();
            for (i, ((((c, _), report), (&xi, (u, slip))), stopped)) in
                each.filter(|(_, ((((_, t), _), _), _))| **t)
            {
                let friction = if is_pivot(i) { *stopped } else { scale(-c.mu * xi, u) };
                *report = self.report(xi, &friction, slip, c.mu, (tries, self.floor, true))?;
            }
            return Ok(Some((out, v, w)));
        }
        // The directions did not settle (a point's slip near its end turns with the load): the
        // step is the LCP's.
        Ok(None)
    }

    /// The least-norm load `x` of `columns` (each touching point's push out of the plane per unit
    /// of its load, along `e`) and the friction `held` of the points that `stop` names (module
    /// docs, "Points that stop"): `held` from the points' slips in the plane under `x`, `x` the
    /// least norm's for `g` less `held`'s push out of the plane, the two taken again in turn until
    /// that push settles within round-off. `None` when it does not in [`LOAD_TRIES`] turns, a
    /// resting point's friction leaves its cone, or (`feasible` false) no load `x >= 0` gives
    /// `g`. With [`Stop::None`], `held` is zero and `x` the least norm's for `g`.
    #[allow(clippy::too_many_arguments)]
    fn held_load<const N: usize>(
        &self,
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        columns: &[[T; 3]; K],
        touching: &[bool; K],
        g: &[T; 3],
        e: &[Vector<T>; K],
        v_free: &Vector<T>,
        w_free: &Vector<T>,
        feasible: bool,
        stop: Stop,
    ) -> Result<Option<HeldLoad<T, K>>, StepError> {
        let (n, zero) = (self.normal, T::zero());
        let mut load =
            |target: &[T; 3]| match Self::least_norm_load(solver, basis, pivots, columns, touching, target) {
                Ok(x) => Ok(Some(x)),
                Err(StepError::Solver(crate::lcp::LcpError::Ray { .. })) if !feasible => Ok(None),
                Err(e) => Err(e),
            };
        if stop == Stop::None {
            return Ok(load(g)?.map(|x| (x, [[zero; 3]; K])));
        }
        let (t1, lever) = self.plane_axes();
        let t2 = cross(&n, &t1);
        let size = g.iter().fold(T::TINY, |a, x| max(a, x.abs_exact()));
        let round_off = T::of(64.0 * K as f64) * T::EPS * size;
        let mut push = [zero; 3];
        for _ in 0..LOAD_TRIES {
            let target = [g[0] - push[0], g[1] - push[1], g[2] - push[2]];
            let Some(x) = load(&target)? else {
                return Ok(None);
            };
            let impulses: [Vector<T>; K] = core::array::from_fn(|i| scale(x[i], &e[i]));
            let (v, w) = self.moved(&impulses, v_free, w_free);
            let held = match stop {
                Stop::None => [[zero; 3]; K],
                Stop::Pivot(j) => {
                    let (Some(c), Some(&load)) = (self.touches.get(j), x.get(j)) else {
                        return Ok(None);
                    };
                    let f = self.pivot_friction(c, &Self::slip(&v, &w, c), c.mu * load, [t1, t2]);
                    core::array::from_fn(|i| if i == j { f } else { [zero; 3] })
                }
                Stop::Rest(j) => {
                    let Some(held) = self.rest_friction(touching, &x, j, &v, &w, [t1, t2], lever) else {
                        return Ok(None);
                    };
                    let within = (0..K).all(|i| {
                        norm(&held[i]) <= self.touches[i].mu * x[i] * (T::one() + T::of(4096.0) * T::EPS)
                    });
                    if !within {
                        return Ok(None);
                    }
                    held
                }
            };
            let (dv, dw) = self.moved(&held, &[zero; 3], &[zero; 3]);
            let next = [dot(&n, &dv), lever * dot(&t1, &dw), lever * dot(&t2, &dw)];
            let moved = (0..3).fold(zero, |a, k| max(a, (next[k] - push[k]).abs_exact()));
            if moved <= round_off {
                return Ok(Some((x, held)));
            }
            push = next;
        }
        Ok(None)
    }

    /// The friction of the pivot `c` slipping at `slip` under the other impulses, its cone's edge
    /// `limit`: the impulse in the plane that stops the slip, `-D^-1 slip` (`D` the pivot's 2x2
    /// Delassus matrix on the plane's axes), when it is within the cone; otherwise the impulse on
    /// the edge against the slip it leaves, `-(D + lambda I)^-1 slip` with `|.| = limit`
    /// (`lambda >= 0` by bisection: the slip after is `-lambda` times the friction).
    fn pivot_friction(&self, c: &Touch<T>, slip: &Vector<T>, limit: T, axes: [Vector<T>; 2]) -> Vector<T> {
        // `D_ab = t_a . t_b + m (r x t_a) . I_w^-1 (r x t_b)` (`Self::delassus`), each turn once.
        let turn = axes.map(|t| scale(self.body().mass, &self.inverse_inertia().times(&cross(&c.arm, &t))));
        let delassus: [[T; 2]; 2] = core::array::from_fn(|a| {
            core::array::from_fn(|b| dot(&axes[a], &axes[b]) + dot(&cross(&c.arm, &axes[a]), &turn[b]))
        });
        let s = [dot(&axes[0], slip), dot(&axes[1], slip)];
        let with = |lambda: T| {
            let m = [[delassus[0][0] + lambda, delassus[0][1]], [delassus[1][0], delassus[1][1] + lambda]];
            let y = solved(m, [-s[0], -s[1]]);
            add(&scale(y[0], &axes[0]), &scale(y[1], &axes[1]))
        };
        let stops = with(T::zero());
        if norm(&stops) <= limit {
            return stops;
        }
        // `|f(lambda)|` falls as `lambda` grows, to at most `|slip| / lambda`.
        let (mut lo, mut hi) = (T::zero(), norm(slip) / max(limit, T::TINY));
        // To the scalar's precision of the first bracket: `lambda`'s error moves the friction by
        // a part in `1 / eps` of the slip's.
        let precision = T::of(4.0) * T::EPS * hi;
        for _ in 0..128 {
            let mid = (lo + hi) * T::of(0.5);
            if hi - lo <= precision || mid <= lo || mid >= hi {
                break;
            }
            if norm(&with(mid)) > limit {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        with(hi)
    }

    /// The friction that brings the `touching` points to rest in the plane at once, loaded `x`
    /// and moving at `v`, `w` under that load, the answer of the three conditions `t1 . v =
    /// t2 . v = 0`, `n . omega = 0` after the step (a base in the plane of the centre of mass: its
    /// points then rest) in three unknowns: without a pivot, the friction affine in the points'
    /// position, `a + b n x r_i / lever` (the least norm that meets them); with the point `pivot`,
    /// its impulse in the plane and every other point's `-c mu x_i s_i` along its slip `s_i` (one
    /// common factor `c`). `None` when those conditions are singular.
    #[allow(clippy::too_many_arguments)]
    fn rest_friction(
        &self,
        touching: &[bool; K],
        x: &[T; K],
        pivot: Option<usize>,
        v: &Vector<T>,
        w: &Vector<T>,
        axes: [Vector<T>; 2],
        lever: T,
    ) -> Option<[Vector<T>; K]> {
        let (n, zero) = (self.normal, T::zero());
        let shape = |k: usize, i: usize| -> Vector<T> {
            let c = &self.touches[i];
            match (k, pivot.map(|j| i == j)) {
                (0 | 1, None | Some(true)) => axes[k & 1],
                (2, None) => scale(T::one() / lever, &cross(&n, &c.arm)),
                (2, Some(false)) => {
                    let along = direction(&Self::slip(v, w, c)).unwrap_or([zero; 3]);
                    scale(-c.mu * x[i], &along)
                }
                _ => [zero; 3],
            }
        };
        let motion =
            |dv: &Vector<T>, dw: &Vector<T>| [dot(&axes[0], dv), dot(&axes[1], dv), lever * dot(&n, dw)];
        let mut m = [[zero; 3]; 3];
        for k in 0..3 {
            let unit: [Vector<T>; K] =
                core::array::from_fn(|i| if touching[i] { shape(k, i) } else { [zero; 3] });
            let (dv, dw) = self.moved(&unit, &[zero; 3], &[zero; 3]);
            let column = motion(&dv, &dw);
            for (row, entry) in m.iter_mut().zip(column) {
                row[k] = entry;
            }
        }
        let now = motion(v, w);
        let y = solved(m, [-now[0], -now[1], -now[2]]);
        let answer: [Vector<T>; K] = core::array::from_fn(|i| {
            if !touching[i] {
                return [zero; 3];
            }
            add(&add(&scale(y[0], &shape(0, i)), &scale(y[1], &shape(1, i))), &scale(y[2], &shape(2, i)))
        });
        // A singular system leaves an unknown zero: the conditions it meets say whether it did.
        let (dv, dw) = self.moved(&answer, v, w);
        let after = motion(&dv, &dw);
        let scale_of = now.iter().fold(T::TINY, |a, x| max(a, x.abs_exact()));
        after
            .iter()
            .all(|x| x.abs_exact() <= T::of(64.0 * K as f64) * T::EPS * scale_of + self.slip_tolerance)
            .then_some(answer)
    }

    /// The least-norm `x >= 0` with `sum_i x_i columns_i = g` over the `touching` points (module
    /// docs): the projection `x0`, or the LCP when it has a negative entry.
    fn least_norm_load<const N: usize>(
        solver: &Lemke<T, N>,
        basis: &mut Basis<N>,
        pivots: &mut u32,
        columns: &[[T; 3]; K],
        touching: &[bool; K],
        g: &[T; 3],
    ) -> Result<[T; K], StepError> {
        let zero = T::zero();
        let mut gram = [[zero; 3]; 3];
        for (a, row) in gram.iter_mut().enumerate() {
            for (b, slot) in row.iter_mut().enumerate() {
                *slot = columns.iter().fold(zero, |s, c| s + c[a] * c[b]);
            }
        }
        // `G^T (G G^T)^-1 a` for `a` of three entries.
        let lift = |a: &[T; 3]| -> [T; K] {
            let y = solved(gram, *a);
            core::array::from_fn(|i| dot(&columns[i], &y))
        };
        let x0 = lift(g);
        let largest = x0.iter().fold(T::TINY, |a, x| max(a, x.abs_exact()));
        let round_off = T::of(64.0 * K as f64) * T::EPS * largest;
        if x0.iter().all(|&x| x >= -round_off) {
            return Ok(x0.map(|x| max(x, zero)));
        }
        // `P = I - G^T (G G^T)^-1 G` over the touching points, the LCP's first rows; the others
        // decoupled.
        let mut m = [[zero; N]; N];
        let mut q = [zero; N];
        // Written by `put`: `N >= K` is the scene's, not known here (`scripts/panic-paths.sh`).
        for ((j, column), _) in columns.iter().enumerate().zip(touching).filter(|(_, t)| **t) {
            let column = lift(column);
            for ((i, &entry), _) in column.iter().enumerate().zip(touching).filter(|(_, t)| **t) {
                put(&mut m, i, j, if i == j { T::one() } else { zero } - entry);
            }
        }
        for ((i, &t), &x) in touching.iter().enumerate().zip(&x0) {
            if t {
                put_in(&mut q, i, x);
            } else {
                put(&mut m, i, i, T::one());
                put_in(&mut q, i, T::one());
            }
        }
        pad(&mut m, &mut q, K);
        let lcp = Lcp::from_rows(&m, &q);
        let sol = solver.solve_warm(&lcp, *basis).map_err(StepError::Solver)?;
        *basis = sol.basis;
        *pivots = pivots.saturating_add(sol.pivots);
        Ok(core::array::from_fn(|i| {
            if touching[i] { max(sol.w.get(i).copied().unwrap_or(zero), zero) } else { zero }
        }))
    }
}
