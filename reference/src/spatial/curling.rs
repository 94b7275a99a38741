//! The curling stone (docs/scenes.md, "curling"), written from that text: a ring or a uniform disc
//! of radius `R` and mass `m` on a level table, touching it at `n` points in the plane of its
//! centre of mass, launched sliding along `+x` and spinning about `+z`.
//!
//! # The step, as a minimisation
//!
//! The base lies in the plane of the centre of mass, so friction tips nothing: the body stays flat
//! and its motion in a step is `u = (vx, vy, omega_z)`. Every point's normal row closed gives the
//! normal impulses' sum `m g h` and their moment about the centre nil; of those loads the
//! least-norm one is taken (docs/formulation.md, "The load: the least norm": uniform for these
//! symmetric bases), `P = A^T (A A^T)^-1 b`, `A` the rows `(1, x_i, y_i)` of the points and
//! `b = (m g h, 0, 0)`. With the loads known, Coulomb's law at the velocity level (each point's
//! friction `mu P_i` against its slip after the step, or anything within its disc where the slip
//! is nil) is exactly the optimality condition of
//!
//! ```text
//! min_u  1/2 (u - u~)^T M (u - u~) + sum_i mu P_i |J_i u|,   M = diag(m, m, I_z),
//! J_i u = (vx - omega y_i, vy + omega x_i)                    (point i's slip, world axes)
//! ```
//!
//! (the subgradient of `|s|` at `s = 0` is the unit disc): a strictly convex function, whose
//! minimiser is the step's one answer. It lies where no slip vanishes (then Newton's method on the
//! smooth function finds it), or where exactly one does (the body turns about that point: on that
//! line the function is `a omega^2 / 2 - b omega + K |omega|` plus a constant, minimised in closed
//! form), or at rest (two points with nil slip fix the body). The candidates are computed and the
//! lowest value taken; Newton's answer, when it converged with every slip nonzero, is the minimum
//! by convexity (tried from the free motion, then from beside the best kink: a minimum whose slip
//! is small but not nil lies there).
//!
//! **How this differs from the core** (on purpose): the core solves an LCP over one friction line
//! a point turned toward its slip, or steps the sliding base on the least-norm load and stops a
//! point whose slip reached the stick speed; here the step is the convex minimisation above,
//! solved by cases, with no stick speed inside the step. The stick speed only names the modes
//! after it and the stops, as the docs say.

use super::algebra::{V3, apply, cross, dot, length, matrix_of, turn};
use super::scenes::{Keep, common, invalid};
use super::{Error, MAX_STEPS, Mode, Outcome, Row, Rule, SpatialRun};

/// The curling stone's measured quantities, in [`SpatialRun::measured`]'s order.
pub const CURLING_QUANTITIES: [&str; 3] = ["terminal_ratio", "slide_stop_s", "spin_stop_s"];

/// The most points of the base (docs/scenes.md: 4 to 8).
pub const MOST_POINTS: usize = 8;

/// docs/scenes.md, "curling".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curling {
    /// `true` for the ring (its points on its rim, `I_z = m R^2`); `false` for the uniform disc
    /// (its points at the centroids of `n` equal sectors, `I_z = m R^2 / 2`).
    pub ring: bool,
    /// `R`, m.
    pub radius: f64,
    /// `m`, kg.
    pub mass: f64,
    /// `n`, 4 to 8.
    pub points: usize,
    /// `g`, m/s^2.
    pub g: f64,
    /// Launch speed along `+x`, m/s.
    pub speed: f64,
    /// Launch spin about `+z`, rad/s.
    pub spin: f64,
    /// `mu`.
    pub mu: f64,
    /// `h`, s.
    pub h: f64,
    /// m/s.
    pub stick_speed: f64,
    /// s.
    pub max_time: f64,
}

impl Default for Curling {
    fn default() -> Self {
        Self {
            ring: false,
            radius: 0.145,
            mass: 19.96,
            points: 8,
            g: 9.81,
            speed: 1.0,
            spin: 5.0,
            mu: 0.1,
            h: 0.001,
            stick_speed: 1e-5,
            max_time: 10.0,
        }
    }
}

impl Curling {
    /// Checks the docs' validity rules.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that breaks one.
    pub fn validate(&self) -> Result<(), Error> {
        if !self.spin.is_finite() {
            return Err(invalid("spin", Rule::NotFinite));
        }
        common(
            &[
                ("radius", self.radius),
                ("mass", self.mass),
                ("mu", self.mu),
                ("h", self.h),
                ("max_time", self.max_time),
                ("stick_speed", self.stick_speed),
            ],
            &[("g", self.g), ("speed", self.speed)],
            (self.mu, self.mu),
            (self.h, self.max_time),
        )?;
        if !(4..=MOST_POINTS).contains(&self.points) {
            return Err(invalid("points", Rule::OutOfRange));
        }
        Ok(())
    }

    /// The points' distance from the centre: `R` (ring), `(2 / 3) R sin(pi / n) / (pi / n)` (disc).
    #[must_use]
    pub fn point_radius(&self) -> f64 {
        if self.ring {
            return self.radius;
        }
        let half = std::f64::consts::PI / self.points as f64;
        2.0 / 3.0 * self.radius * half.sin() / half
    }

    /// `I_z`: `m R^2` (ring), `m R^2 / 2` (disc).
    #[must_use]
    pub fn spin_moment(&self) -> f64 {
        let k = if self.ring { 1.0 } else { 0.5 };
        k * self.mass * self.radius * self.radius
    }

    /// The points in the body's frame, at `2 pi i / n` from `+x`.
    fn body_points(&self) -> Vec<V3> {
        let rho = self.point_radius();
        (0..self.points)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / self.points as f64;
                [rho * a.cos(), rho * a.sin(), 0.0]
            })
            .collect()
    }
}

/// The least-norm normal impulses of points at horizontal offsets `r` carrying `total` with no
/// moment: `P = A^T (A A^T)^-1 (total, 0, 0)`, `A` the rows `(1, x_i, y_i)` (Cramer's rule on the
/// 3x3 system, [`solve3`]).
fn least_norm_loads(r: &[V3], total: f64) -> Vec<f64> {
    let rows = |i: usize| [1.0, r[i][0], r[i][1]];
    let mut g = [[0.0; 3]; 3];
    for i in 0..r.len() {
        let a = rows(i);
        for (j, gj) in g.iter_mut().enumerate() {
            for (k, gjk) in gj.iter_mut().enumerate() {
                *gjk += a[j] * a[k];
            }
        }
    }
    // A layout of points not all on a line: `G` is positive definite. Were it not, NaN loads end
    // the run (`Error::NonFinite`).
    let lambda = solve3(&g, [total, 0.0, 0.0]).unwrap_or([f64::NAN; 3]);
    (0..r.len()).map(|i| dot(rows(i), lambda)).collect()
}

/// One step's friction problem: `min 1/2 (u - u~)^T M (u - u~) + sum c_i |J_i u|`.
struct Problem<'a> {
    /// `(m, m, I_z)`.
    mass: [f64; 3],
    /// `u~`.
    free: [f64; 3],
    /// The points' horizontal offsets from the centre (world axes).
    r: &'a [V3],
    /// `mu P_i`.
    c: &'a [f64],
}

impl Problem<'_> {
    /// Point `i`'s slip for `u`.
    fn slip(&self, i: usize, u: [f64; 3]) -> [f64; 2] {
        [u[0] - u[2] * self.r[i][1], u[1] + u[2] * self.r[i][0]]
    }

    fn value(&self, u: [f64; 3]) -> f64 {
        let kinetic: f64 = (0..3).map(|k| 0.5 * self.mass[k] * (u[k] - self.free[k]).powi(2)).sum();
        kinetic + (0..self.r.len()).map(|i| self.c[i] * hypot2(self.slip(i, u))).sum::<f64>()
    }

    /// Newton's method on the smooth function (every slip nonzero), with a backtracking line
    /// search; the answer when its gradient vanished to round-off with every slip nonzero.
    fn smooth(&self, start: [f64; 3]) -> Option<[f64; 3]> {
        let mut u = start;
        let scale = (0..3).map(|k| self.mass[k] * self.free[k].abs()).fold(0.0, f64::max)
            + self.c.iter().sum::<f64>() * (1.0 + self.r.iter().map(|r| length(*r)).fold(0.0, f64::max));
        for _ in 0..100 {
            let mut g: [f64; 3] = std::array::from_fn(|k| self.mass[k] * (u[k] - self.free[k]));
            let mut h = [[0.0; 3]; 3];
            for (k, hk) in h.iter_mut().enumerate() {
                hk[k] = self.mass[k];
            }
            for i in 0..self.r.len() {
                let s = self.slip(i, u);
                let n = hypot2(s);
                if n == 0.0 {
                    return None;
                }
                let e = [s[0] / n, s[1] / n];
                // J_i^T: rows of d s / d u.
                let j = [[1.0, 0.0, -self.r[i][1]], [0.0, 1.0, self.r[i][0]]];
                for k in 0..3 {
                    g[k] += self.c[i] * (e[0] * j[0][k] + e[1] * j[1][k]);
                }
                // c / |s| J^T (I - e e^T) J.
                let p = [[1.0 - e[0] * e[0], -e[0] * e[1]], [-e[0] * e[1], 1.0 - e[1] * e[1]]];
                for a in 0..3 {
                    for b in 0..3 {
                        let mut sum = 0.0;
                        for x in 0..2 {
                            for y in 0..2 {
                                sum += j[x][a] * p[x][y] * j[y][b];
                            }
                        }
                        h[a][b] += self.c[i] / n * sum;
                    }
                }
            }
            if (0..3).map(|k| g[k].abs()).fold(0.0, f64::max) <= 64.0 * f64::EPSILON * scale {
                return Some(u);
            }
            let d = solve3(&h, g)?;
            // A step whose decrease is below the value's round-off is taken whole (near the answer
            // the value no longer tells the iterates apart; the gradient does).
            let f0 = self.value(u);
            let tolerance = 16.0 * f64::EPSILON * f0.abs();
            let mut t = 1.0;
            let next = loop {
                let trial: [f64; 3] = std::array::from_fn(|k| u[k] - t * d[k]);
                if self.value(trial) <= f0 + tolerance {
                    break Some(trial);
                }
                t *= 0.5;
                if t < 1e-12 {
                    break None;
                }
            };
            let next = next?;
            if next.map(f64::to_bits) == u.map(f64::to_bits) {
                // No representable progress: the gradient is round-off.
                return Some(u);
            }
            u = next;
        }
        None
    }

    /// The minimiser with point `i`'s slip nil: `u = omega (y_i, -x_i, 1)`, the function
    /// `a omega^2 / 2 - b omega + K |omega|` plus a constant.
    fn pivot(&self, i: usize) -> [f64; 3] {
        let [x, y, _] = self.r[i];
        let d = [y, -x, 1.0];
        let a: f64 = (0..3).map(|k| self.mass[k] * d[k] * d[k]).sum();
        let b: f64 = (0..3).map(|k| self.mass[k] * d[k] * self.free[k]).sum();
        let k_sum: f64 = (0..self.r.len())
            .filter(|&j| j != i)
            .map(|j| self.c[j] * (self.r[j][0] - x).hypot(self.r[j][1] - y))
            .sum();
        let omega = b.signum() * (b.abs() - k_sum).max(0.0) / a;
        d.map(|dk| omega * dk)
    }

    /// The step's answer and where it lies.
    fn solve(&self) -> (Answer, [f64; 3]) {
        if let Some(u) = self.smooth(self.free) {
            return (Answer::Sliding, u);
        }
        let mut best = (Answer::Rest, [0.0; 3], self.value([0.0; 3]));
        for i in 0..self.r.len() {
            let u = self.pivot(i);
            let f = self.value(u);
            if f < best.2 {
                best = (Answer::Pivot(i), u, f);
            }
        }
        // Newton's method from beside the best kink: a minimum where a slip is small but not
        // nil lies there, and Newton's iterates from the free motion may have run into a kink on
        // the way (its curvature grows as `1 / |s|`).
        for step in [1e-3, 1e-6, 1e-9] {
            let start: [f64; 3] = std::array::from_fn(|k| best.1[k] + step * (self.free[k] - best.1[k]));
            if let Some(u) = self.smooth(start)
                && self.value(u) < best.2
            {
                return (Answer::Sliding, u);
            }
        }
        (best.0, best.1)
    }
}

/// Where a step's answer lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Answer {
    /// Every slip nonzero.
    Sliding,
    /// Turning about this point, its slip nil.
    Pivot(usize),
    /// At rest.
    Rest,
}

fn hypot2(s: [f64; 2]) -> f64 {
    s[0].hypot(s[1])
}

/// `H^-1 g` for a symmetric positive definite 3x3 `H` (Cramer); `None` when singular.
fn solve3(h: &[[f64; 3]; 3], g: [f64; 3]) -> Option<[f64; 3]> {
    let det3 = |m: &[[f64; 3]; 3]| dot(m[0], cross(m[1], m[2]));
    let d = det3(h);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    Some(std::array::from_fn(|c| {
        let mut m = *h;
        for (row, m_row) in m.iter_mut().enumerate() {
            m_row[c] = g[row];
        }
        det3(&m) / d
    }))
}

/// Validates `c` and runs the stone to its outcome (docs/scenes.md, "curling"), keeping `keep`.
///
/// # Errors
/// [`Error::Invalid`], [`Error::TooManySteps`], or [`Error::NonFinite`].
pub fn run_curling_keeping(c: &Curling, keep: Keep) -> Result<SpatialRun, Error> {
    c.validate()?;
    let h = c.h;
    let needed = (c.max_time / h).ceil();
    if needed > MAX_STEPS as f64 {
        return Err(Error::TooManySteps { steps: needed });
    }
    let body_points = c.body_points();
    let rho = c.point_radius();
    let mass = [c.mass, c.mass, c.spin_moment()];
    let floor = 10.0 * c.mu * c.g * h;
    let (mut x, mut q, mut u) = ([0.0; 3], [1.0, 0.0, 0.0, 0.0], [c.speed, 0.0, c.spin]);
    let row = |t: f64, x: V3, q, u: [f64; 3], mode, normal_impulse, friction_impulse| Row {
        t,
        position: x,
        orientation: q,
        velocity: [u[0], u[1], 0.0],
        angular_velocity: [0.0, 0.0, u[2]],
        mode,
        normal_impulse,
        friction_impulse,
    };
    let mut rows = Vec::with_capacity(if keep == Keep::All { needed as usize + 1 } else { 2 });
    rows.push(row(0.0, x, q, u, Mode::Separated, 0.0, [0.0; 3]));
    let (mut ratio, mut slide, mut spin) = (None, None, None);
    let mut steps = 0_u64;
    let outcome = loop {
        let (v0, w0) = (u[0].hypot(u[1]), c.radius * u[2].abs());
        if v0 >= floor && w0 >= floor {
            ratio = Some(v0 / w0);
        }
        let turn_of = matrix_of(q);
        let r: Vec<V3> = body_points.iter().map(|p| apply(&turn_of, *p)).collect();
        let loads = least_norm_loads(&r, c.mass * c.g * h);
        let limits: Vec<f64> = loads.iter().map(|p| c.mu * p).collect();
        let problem = Problem { mass, free: u, r: &r, c: &limits };
        let (_, next) = problem.solve();
        let friction = [mass[0] * (next[0] - u[0]), mass[1] * (next[1] - u[1]), 0.0];
        u = next;
        x = [x[0] + h * u[0], x[1] + h * u[1], x[2]];
        q = turn(q, [0.0, 0.0, h * u[2]]);
        steps += 1;
        if !(x.iter().chain(&q).chain(&u).all(|v| v.is_finite())) {
            return Err(Error::NonFinite { step: steps });
        }
        let t = steps as f64 * h;
        let sliding = (0..r.len()).any(|i| hypot2(problem.slip(i, u)) > c.stick_speed);
        let mode = if sliding { Mode::Sliding } else { Mode::Sticking };
        let kept = row(t, x, q, u, mode, c.mass * c.g * h, friction);
        match (keep, rows.get_mut(1)) {
            (Keep::StartAndEnd, Some(last)) => *last = kept,
            _ => rows.push(kept),
        }
        if slide.is_none() && u[0].hypot(u[1]) <= c.stick_speed {
            slide = Some(t);
        }
        if spin.is_none() && rho * u[2].abs() <= c.stick_speed {
            spin = Some(t);
        }
        if (slide.is_some() && spin.is_some()) || !sliding {
            break Outcome::Stopped;
        }
        if t >= c.max_time || steps >= MAX_STEPS {
            break Outcome::Slid;
        }
    };
    Ok(SpatialRun { outcome, measured: [ratio, slide, spin], steps, trajectory: rows })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::cast_precision_loss)]
mod tests {
    use super::*;

    /// A small generator of its own (the reference depends on nothing): xorshift64.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// Each step's answer is the minimum: no nearby `u` (random directions, at four scales)
    /// has a value lower by more than 1e-14 of it, over launches that slide, that end turning about a point and that
    /// come to rest, for the ring and the disc at every number of points.
    #[test]
    fn every_answer_is_the_minimum_of_the_step_s_function() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut kinds = [0_usize; 3];
        for case in 0..400 {
            let c = Curling { ring: case % 2 == 0, points: 4 + case % 5, ..Curling::default() };
            let r = c.body_points();
            let loads = least_norm_loads(&r, c.mass * c.g * c.h);
            let total: f64 = loads.iter().sum();
            assert!((total - c.mass * c.g * c.h).abs() <= 1e-15, "{total}");
            let limits: Vec<f64> = loads.iter().map(|p| c.mu * p).collect();
            // Speeds from a few steps' worth of friction to metres a second.
            let size = 10f64.powf(-3.0 + 3.0 * (rng.next() + 1.0));
            let free = [size * rng.next(), size * rng.next(), size / c.radius * rng.next()];
            let p = Problem { mass: [c.mass, c.mass, c.spin_moment()], free, r: &r, c: &limits };
            let (kind, u) = p.solve();
            kinds[match kind {
                Answer::Sliding => 0,
                Answer::Pivot(_) => 1,
                Answer::Rest => 2,
            }] += 1;
            let f = p.value(u);
            for scale in [1e-9, 1e-6, 1e-3, 1.0] {
                for _ in 0..20 {
                    let d = [rng.next(), rng.next(), rng.next() / c.radius].map(|x| x * scale * size);
                    let g = p.value(std::array::from_fn(|k| u[k] + d[k]));
                    assert!(
                        g >= f - 1e-14 * f.abs().max(1e-300),
                        "case {case}: {u:?} {f} against {g} at {d:?}"
                    );
                }
            }
        }
        assert!(kinds.iter().all(|&k| k > 0), "sliding, turning about a point, at rest: {kinds:?}");
    }

    /// The ring stops sliding and spinning in one step with `v / (R omega)` near 1, the disc of
    /// 8 points near its layout's `rho_8 / R = 0.650` (docs/scenes.md, "curling").
    #[test]
    fn the_ring_ends_at_one_and_the_disc_at_its_points_radius() {
        let ring =
            run_curling_keeping(&Curling { ring: true, points: 4, ..Curling::default() }, Keep::StartAndEnd)
                .unwrap();
        assert_eq!(ring.outcome, Outcome::Stopped);
        assert_eq!(ring.measured[1], ring.measured[2], "the ring's stops");
        assert!((ring.measured[0].unwrap() - 1.0).abs() < 1e-3, "{:?}", ring.measured);
        let disc = run_curling_keeping(&Curling::default(), Keep::StartAndEnd).unwrap();
        assert_eq!(disc.outcome, Outcome::Stopped);
        assert_eq!(disc.measured[1], disc.measured[2], "the disc's stops");
        let rho = Curling::default().point_radius() / Curling::default().radius;
        assert!((disc.measured[0].unwrap() - rho).abs() < 1e-3, "{:?} against {rho}", disc.measured);
    }
}
