//! Several point contacts of one body with Coulomb's circular cone, solved by enumerating each
//! contact's case (not an LCP, no friction lines).
//!
//! Per unit mass, impulses `p_j` at the contacts change contact `i`'s velocity by `sum_j W_ij
//! p_j`, `W` the Delassus matrix (`3K x 3K`, symmetric, positive *semi*definite: a body has six
//! freedoms, so three or more contacts leave internal forces, equal and opposite along the lines
//! joining them, that move nothing). With `u_i` contact `i`'s free velocity plus its gap's bias
//! along its unit normal `n_i`, the answer satisfies, for every contact,
//!
//! ```text
//! u+_i = u_i + sum_j W_ij p_j,   n_i . u+_i >= 0 _|_ p_n,i >= 0,   |p_t,i| <= mu_i p_n,i,
//! p_t,i = -mu_i p_n,i s_i / |s_i|  where the slip s_i (u+_i less its normal part) is not zero.
//! ```
//!
//! **The method.** Each contact is in one of three cases: *apart* (`p_i = 0`, `n_i . u+_i >= 0`),
//! *stuck* (`u+_i = 0`, `p_i` free within its cone) or *slides* (`n_i . u+_i = 0`, `p_i = p_n,i
//! (n_i - mu_i e_i)`, `e_i` a unit direction of the tangent plane at angle `theta_i`, and the slip
//! along `e_i`). For a combination of cases and given angles, the unknowns (three impulse
//! components per stuck contact, one normal impulse per sliding one) solve a square linear
//! system, its rows the stuck contacts' velocities and the sliding ones' normal rows. That system
//! is singular where two or more contacts stick (the internal forces): it is solved by the
//! singular value decomposition (`dense.rs`), least norm, and its null space kept. The sliding
//! directions are the roots of `f_i(theta) = (n_i x e_i) . s_i` with `e_i . s_i > 0`, found by
//! Newton's method (a Jacobian of differences) from the free slips' directions, then from a grid
//! of angles. The stuck contacts' impulses are then moved along the null space until each is in
//! its cone (Newton's steps on the violated cones' linearisations, a convex feasibility problem):
//! the least-norm split of two sticking pad points' friction need not fit the lighter one's cone
//! where another split does.
//!
//! The combinations are tried in order: the caller's guess first (the modes of the step before),
//! then by how far they differ from it, fewer sliding contacts first; the first whose answer
//! **verifies** is taken: every condition above within `2^14 eps` of the step's velocity scale
//! (`max |u_i| + max |W| max |p_i|`) and every cone within `2^12 eps` of the largest impulse.
//! Several contacts may have several answers (Coulomb's law in velocities does not promise one);
//! uniqueness is not asserted here, unlike the lone contact's search (`contact.rs`).
//!
//! **Why this method** (and not the core's): the core solves an LCP with one friction line per
//! contact turned to the slip by Newton's steps, by Lemke's pivots. Here nothing is linearised in
//! the cone: each case's conditions are the cone's own, the sliding friction exactly `-mu p_n`
//! along the slip's direction, and the answer is checked against them as a whole. With `K <= 3`
//! contacts there are at most 27 combinations, and the step before names the right one nearly
//! always.

use super::algebra::{
    M3, V3, ZERO, apply, cross, dot, in_plane, length, plus, product, skew, some_perpendicular, times,
    transpose,
};
use super::contact::ContactError;
use super::dense::Svd;

/// `W` of contacts at the arms `arms` (from the centre of mass, world axes) of a body of mass
/// `mass` and world inverse inertia `inverse`: `W_ij = I3 + m [r_i]x^T I_w^-1 [r_j]x`, rows first.
pub(crate) fn delassus(mass: f64, inverse: &M3, arms: &[V3]) -> Vec<f64> {
    let k = arms.len();
    let mut w = vec![0.0; 9 * k * k];
    for (a, ra) in arms.iter().enumerate() {
        for (b, rb) in arms.iter().enumerate() {
            let block = product(&transpose(&skew(*ra)), &product(inverse, &skew(*rb)));
            for r in 0..3 {
                for c in 0..3 {
                    w[(3 * a + r) * 3 * k + 3 * b + c] = mass * block[r][c] + f64::from(u8::from(r == c));
                }
            }
        }
    }
    w
}

/// A contact's case in the answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum PointCase {
    Apart,
    Stuck,
    Slides,
}

const CASES: [PointCase; 3] = [PointCase::Stuck, PointCase::Slides, PointCase::Apart];

/// The most contacts (the combinations grow as `3^K`).
pub(crate) const MOST_CONTACTS: usize = 6;

/// The step's contact problem, per unit mass.
#[derive(Debug, Clone)]
pub(crate) struct Contacts {
    /// Unit normals.
    pub normals: Vec<V3>,
    /// `W`, `3K x 3K`, rows first.
    pub w: Vec<f64>,
    /// Free velocities, the gap's bias along the normal included.
    pub u: Vec<V3>,
    /// Friction coefficients.
    pub mu: Vec<f64>,
}

/// The verified answer.
#[derive(Debug, Clone)]
pub(crate) struct Solved {
    /// Impulses per unit mass, world axes.
    pub p: Vec<V3>,
    pub cases: Vec<PointCase>,
    /// The worst condition's miss, over the step's velocity scale.
    pub residual: f64,
    /// Whether the stuck contacts' least-norm impulses left a cone and were moved along the
    /// internal forces into it.
    pub fitted: bool,
}

/// A singular value below this part of the largest is nil.
const RANK: f64 = 1e-10;
/// Newton's iterations at most from one start.
const ITERATIONS: usize = 24;

impl Contacts {
    fn k(&self) -> usize {
        self.normals.len()
    }

    fn block(&self, i: usize, j: usize) -> M3 {
        let n = 3 * self.k();
        std::array::from_fn(|a| std::array::from_fn(|b| self.w[(3 * i + a) * n + 3 * j + b]))
    }

    pub(crate) fn after(&self, p: &[V3]) -> Vec<V3> {
        (0..self.k())
            .map(|i| (0..self.k()).fold(self.u[i], |acc, j| plus(acc, apply(&self.block(i, j), p[j]))))
            .collect()
    }

    fn largest_w(&self) -> f64 {
        self.w.iter().fold(0.0, |a, x| a.max(x.abs()))
    }

    /// The tangent basis `(t1, t2)` of contact `i`: `t1` along the free slip.
    fn frame(&self, i: usize) -> (V3, V3) {
        let n = self.normals[i];
        let slip = in_plane(self.u[i], n);
        let size = length(slip);
        let t1 = if size > 0.0 { times(1.0 / size, slip) } else { some_perpendicular(n) };
        (t1, cross(n, t1))
    }
}

/// One combination's evaluation at given sliding angles.
struct Eval {
    x: Vec<f64>,
    null: Vec<Vec<f64>>,
    p: Vec<V3>,
    after: Vec<V3>,
    /// Each sliding contact's direction (zero for the others).
    e: Vec<V3>,
}

struct Combination<'a> {
    c: &'a Contacts,
    cases: &'a [PointCase],
    frames: Vec<(V3, V3)>,
}

impl Combination<'_> {
    fn sliding(&self) -> Vec<usize> {
        (0..self.cases.len()).filter(|&i| self.cases[i] == PointCase::Slides).collect()
    }

    /// Impulses from the unknowns `x` (three per stuck contact, one per sliding one).
    fn impulses(&self, x: &[f64], e: &[V3]) -> Vec<V3> {
        let mut at = 0;
        self.cases
            .iter()
            .enumerate()
            .map(|(i, case)| match case {
                PointCase::Apart => ZERO,
                PointCase::Stuck => {
                    at += 3;
                    [x[at - 3], x[at - 2], x[at - 1]]
                }
                PointCase::Slides => {
                    at += 1;
                    times(x[at - 1], plus(self.c.normals[i], times(-self.c.mu[i], e[i])))
                }
            })
            .collect()
    }

    fn evaluate(&self, theta: &[f64]) -> Option<Eval> {
        let c = self.c;
        let mut e = vec![ZERO; c.k()];
        for (&i, &angle) in self.sliding().iter().zip(theta) {
            let (sin, cos) = angle.sin_cos();
            e[i] = plus(times(cos, self.frames[i].0), times(sin, self.frames[i].1));
        }
        // The unknowns' columns: each an impulse direction at one contact.
        let mut unknowns: Vec<(usize, V3)> = Vec::new();
        for (j, case) in self.cases.iter().enumerate() {
            match case {
                PointCase::Apart => {}
                PointCase::Stuck => {
                    unknowns.extend([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|d| (j, d)));
                }
                PointCase::Slides => unknowns.push((j, plus(c.normals[j], times(-c.mu[j], e[j])))),
            }
        }
        let rows = |v: &dyn Fn(usize) -> V3| -> Vec<f64> {
            let mut out = Vec::new();
            for (i, case) in self.cases.iter().enumerate() {
                match case {
                    PointCase::Apart => {}
                    PointCase::Stuck => out.extend(v(i)),
                    PointCase::Slides => out.push(dot(c.normals[i], v(i))),
                }
            }
            out
        };
        let columns: Vec<Vec<f64>> =
            unknowns.iter().map(|&(j, d)| rows(&|i| apply(&c.block(i, j), d))).collect();
        let b: Vec<f64> = rows(&|i| c.u[i]).iter().map(|x| -x).collect();
        let (x, null) =
            if columns.is_empty() { (Vec::new(), Vec::new()) } else { Svd::of(&columns)?.solve(&b, RANK) };
        let p = self.impulses(&x, &e);
        let after = c.after(&p);
        Some(Eval { x, null, p, after, e })
    }

    /// The sliding contacts' direction conditions `(n x e) . s`.
    fn conditions(&self, ev: &Eval) -> Vec<f64> {
        self.sliding().iter().map(|&i| dot(cross(self.c.normals[i], ev.e[i]), ev.after[i])).collect()
    }

    /// Newton's method on the sliding angles from `theta`; the evaluation where the conditions
    /// vanished to `tol`.
    fn newton(&self, mut theta: Vec<f64>, tol: f64) -> Option<Eval> {
        let d = theta.len();
        for _ in 0..ITERATIONS {
            let ev = self.evaluate(&theta)?;
            let f = self.conditions(&ev);
            if f.iter().all(|x| x.abs() <= tol) {
                return Some(ev);
            }
            let delta = 1e-7;
            let mut columns = Vec::with_capacity(d);
            for k in 0..d {
                let mut moved = theta.clone();
                moved[k] += delta;
                let g = self.conditions(&self.evaluate(&moved)?);
                columns.push(g.iter().zip(&f).map(|(a, b)| (a - b) / delta).collect::<Vec<f64>>());
            }
            let minus_f: Vec<f64> = f.iter().map(|x| -x).collect();
            let (step, _) = Svd::of(&columns)?.solve(&minus_f, 1e-12);
            let size = step.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
            let k = if size > 0.5 { 0.5 / size } else { 1.0 };
            for (t, s) in theta.iter_mut().zip(&step) {
                *t += k * s;
            }
            if size <= 4.0 * f64::EPSILON {
                let ev = self.evaluate(&theta)?;
                return self.conditions(&ev).iter().all(|x| x.abs() <= tol).then_some(ev);
            }
        }
        None
    }

    /// Moves the stuck contacts' impulses along the null space until every cone holds (Newton's
    /// steps on the violated cones, each aimed `2^-20` of its bound inside it); `false` when they
    /// do not fit.
    fn fit_cones(&self, ev: &mut Eval, tol_p: f64, fitted: &mut bool) -> bool {
        let c = self.c;
        let violation = |p: &[V3], i: usize| {
            let n = c.normals[i];
            length(in_plane(p[i], n)) - c.mu[i] * dot(p[i], n)
        };
        let stuck: Vec<usize> = (0..c.k()).filter(|&i| self.cases[i] == PointCase::Stuck).collect();
        for _ in 0..32 {
            let violated: Vec<usize> =
                stuck.iter().copied().filter(|&i| violation(&ev.p, i) > tol_p).collect();
            if violated.is_empty() {
                return true;
            }
            if ev.null.is_empty() {
                return false;
            }
            // Each null direction's change of each violated cone's function.
            let moved = |t: &[f64]| -> Vec<V3> {
                let x: Vec<f64> = (0..ev.x.len())
                    .map(|r| ev.x[r] + ev.null.iter().zip(t).map(|(z, tk)| z[r] * tk).sum::<f64>())
                    .collect();
                self.impulses(&x, &ev.e)
            };
            *fitted = true;
            let g0: Vec<f64> = violated.iter().map(|&i| violation(&ev.p, i)).collect();
            let scale = ev.p.iter().fold(0.0_f64, |a, p| a.max(length(*p)));
            let delta = 1e-7 * scale.max(f64::MIN_POSITIVE);
            let mut columns = Vec::new();
            for k in 0..ev.null.len() {
                let mut t = vec![0.0; ev.null.len()];
                t[k] = delta;
                let p = moved(&t);
                columns.push(
                    violated
                        .iter()
                        .zip(&g0)
                        .map(|(&i, g)| (violation(&p, i) - g) / delta)
                        .collect::<Vec<f64>>(),
                );
            }
            // Rows: the violated cones; columns: the null directions (transposed for the solve).
            let rows = violated.len();
            let transposed: Vec<Vec<f64>> =
                (0..rows).map(|r| columns.iter().map(|col| col[r]).collect()).collect();
            let target: Vec<f64> = violated
                .iter()
                .zip(&g0)
                .map(|(&i, g)| -g - c.mu[i] * dot(ev.p[i], c.normals[i]) * 2.0_f64.powi(-20))
                .collect();
            // The least-norm step: t = J^T y with (J J^T) y = target, J = transposed.
            let gram: Vec<Vec<f64>> = (0..rows)
                .map(|a| {
                    (0..rows)
                        .map(|b| transposed[a].iter().zip(&transposed[b]).map(|(x, y)| x * y).sum())
                        .collect()
                })
                .collect();
            let Some(svd) = Svd::of(&gram) else { return false };
            let (y, _) = svd.solve(&target, 1e-12);
            let t: Vec<f64> =
                (0..ev.null.len()).map(|k| (0..rows).map(|r| transposed[r][k] * y[r]).sum()).collect();
            let x: Vec<f64> = (0..ev.x.len())
                .map(|r| ev.x[r] + ev.null.iter().zip(&t).map(|(z, tk)| z[r] * tk).sum::<f64>())
                .collect();
            ev.p = self.impulses(&x, &ev.e);
            ev.x = x;
            ev.after = c.after(&ev.p);
        }
        false
    }

    /// The worst miss of the conditions (module docs) over the velocity scale; `None` when a
    /// condition fails beyond its tolerance.
    fn verify(&self, ev: &Eval) -> Option<f64> {
        let c = self.c;
        let pmax = ev.p.iter().fold(0.0_f64, |a, p| a.max(length(*p)));
        let scale = c.u.iter().fold(0.0_f64, |a, u| a.max(length(*u))) + c.largest_w() * pmax;
        if scale == 0.0 {
            return Some(0.0);
        }
        let (tol_v, tol_p) = (16384.0 * f64::EPSILON * scale, 4096.0 * f64::EPSILON * pmax);
        let mut worst = 0.0_f64;
        for i in 0..c.k() {
            let (n, p, after) = (c.normals[i], ev.p[i], ev.after[i]);
            let (pn, pt) = (dot(p, n), length(in_plane(p, n)));
            let miss = match self.cases[i] {
                PointCase::Apart => (-dot(after, n)).max(0.0),
                PointCase::Stuck => {
                    if pn < -tol_p || pt > c.mu[i] * pn + tol_p {
                        return None;
                    }
                    length(after)
                }
                PointCase::Slides => {
                    let s = in_plane(after, n);
                    if pn < -tol_p || dot(ev.e[i], s) < -tol_v {
                        return None;
                    }
                    dot(after, n).abs().max(dot(cross(n, ev.e[i]), s).abs())
                }
            };
            if miss > tol_v {
                return None;
            }
            worst = worst.max(miss / scale);
        }
        Some(worst)
    }

    /// The sliding angles' starts: the free slips' directions, then a grid.
    fn starts(&self) -> Vec<Vec<f64>> {
        let d = self.sliding().len();
        let per = match d {
            0 => return vec![Vec::new()],
            1 => 12,
            2 => 6,
            _ => 4,
        };
        let mut out = vec![vec![0.0; d]];
        let count = (per as u32).pow(d as u32) as usize;
        for mut code in 0..count {
            let mut theta = Vec::with_capacity(d);
            for _ in 0..d {
                theta.push(std::f64::consts::TAU * ((code % per) as f64 + 0.5) / per as f64);
                code /= per;
            }
            out.push(theta);
        }
        out
    }

    fn solve(&self) -> Option<Solved> {
        let c = self.c;
        let scale = c.u.iter().fold(0.0_f64, |a, u| a.max(length(*u)));
        for theta in self.starts() {
            let Some(mut ev) = self.newton(theta, 1024.0 * f64::EPSILON * scale) else { continue };
            let pmax = ev.p.iter().fold(0.0_f64, |a, p| a.max(length(*p)));
            let mut fitted = false;
            if !self.fit_cones(&mut ev, 1024.0 * f64::EPSILON * pmax, &mut fitted) {
                continue;
            }
            if let Some(residual) = self.verify(&ev) {
                return Some(Solved { p: ev.p, cases: self.cases.to_vec(), residual, fitted });
            }
        }
        None
    }
}

/// Every combination of cases for `k` contacts, `guess` first, then by the contacts that differ
/// from it, then by the sliding ones.
fn combinations(k: usize, guess: Option<&[PointCase]>) -> Vec<Vec<PointCase>> {
    let mut all: Vec<Vec<PointCase>> = vec![Vec::new()];
    for _ in 0..k {
        all =
            all.into_iter().flat_map(|head| CASES.map(|case| [head.clone(), vec![case]].concat())).collect();
    }
    let key = |combo: &Vec<PointCase>| {
        let differ = guess.map_or(0, |g| combo.iter().zip(g).filter(|(a, b)| a != b).count());
        let sliding = combo.iter().filter(|&&c| c == PointCase::Slides).count();
        let apart = combo.iter().filter(|&&c| c == PointCase::Apart).count();
        (differ, sliding, apart)
    };
    all.sort_by_key(key);
    all
}

/// The step's impulses by the module's cases, `guess` (each contact's case) tried first.
///
/// # Errors
/// [`ContactError::InvalidInput`] for data of the wrong sizes, not finite, or more than
/// [`MOST_CONTACTS`] contacts; [`ContactError::NoAnswer`] when no combination verifies.
pub(crate) fn solve(c: &Contacts, guess: Option<&[PointCase]>) -> Result<Solved, ContactError> {
    let k = c.k();
    let finite =
        c.w.iter()
            .chain(c.mu.iter())
            .chain(c.u.iter().flatten())
            .chain(c.normals.iter().flatten())
            .all(|x| x.is_finite());
    if k > MOST_CONTACTS
        || c.u.len() != k
        || c.mu.len() != k
        || c.w.len() != 9 * k * k
        || guess.is_some_and(|g| g.len() != k)
        || !finite
        || c.mu.iter().any(|&m| m < 0.0)
        || c.normals.iter().any(|&n| (length(n) - 1.0).abs() > 1e-12)
    {
        return Err(ContactError::InvalidInput);
    }
    let frames: Vec<(V3, V3)> = (0..k).map(|i| c.frame(i)).collect();
    for cases in combinations(k, guess) {
        let combination = Combination { c, cases: &cases, frames: frames.clone() };
        if let Some(solved) = combination.solve() {
            return Ok(solved);
        }
    }
    Err(ContactError::NoAnswer)
}

/// Every combination whose answer verifies (`solve` takes the first): where several do, the step's
/// contact problem has several answers.
#[cfg(test)]
pub(crate) fn every_answer(c: &Contacts) -> Vec<Solved> {
    let frames: Vec<(V3, V3)> = (0..c.k()).map(|i| c.frame(i)).collect();
    combinations(c.k(), None)
        .iter()
        .filter_map(|cases| Combination { c, cases, frames: frames.clone() }.solve())
        .collect()
}
