//! One contact point with Coulomb's circular cone, solved exactly by cases (not an LCP).
//!
//! Per unit mass, an impulse `p` at the contact changes the contact point's velocity by `W p`,
//! `W` the Delassus matrix (symmetric positive definite). With `u` the point's free velocity plus
//! the gap's bias along the unit normal `n` (`u . n` is the normal row's free value), the answer
//! `p = p_n n + p_t` satisfies
//!
//! ```text
//! u+ = u + W p,   u+ . n >= 0 _|_ p_n >= 0,   |p_t| <= mu p_n,
//! p_t = -mu p_n s / |s|  where the slip s = u+ - (u+ . n) n is not zero.
//! ```
//!
//! The cases, in order:
//!
//! 1. **Apart**: `u . n >= 0`. `p = 0` (the trivial answer, which every complementarity
//!    solver returns for a non-negative free row).
//! 2. **Stuck**: `u+ = 0`, i.e. `W p = -u`, solved by `L D L^T` (no square roots: a `W` that is
//!    the identity, a point under the centre of mass, gives `p = -u` exactly). Taken when `p_n >=
//!    0` and `|p_t| <= mu p_n`.
//! 3. **Slides**: `p = p_n (n - mu e)`, `e` the unit slip direction after the step.
//!    - *Isotropic and uncoupled* `W` (`W = a (I - n n^T) + c n n^T` to `64 eps` of its trace: a
//!      sphere, a point under the centre of mass): in closed form, `p_n = -(u . n) / c`, `e` the
//!      free slip's direction, the slip after the step `(|u_t| - a mu p_n) e`. **Unique**: the
//!      normal row alone fixes `p_n`, and the tangential answer minimises the strictly convex
//!      `|u_t + a p_t|^2` over the disc `|p_t| <= mu p_n`, so cases 2 and 3 are one projection.
//!    - *Otherwise*: `e(theta) = cos theta t1 + sin theta t2` (`t1` along the free slip, `t2 = n x
//!      t1`); for each `theta` the normal row gives `p_n(theta) = -(u . n) / (n . W (n - mu e))`
//!      (its denominator `D > 0`) and the slip `s(theta)`; a solution is a root of `f(theta) =
//!      (n x e) . s` with `e . s > 0`. `f` is sampled at 64 angles around the circle; every sign
//!      change (with `D > 0` at both ends) is refined by Newton's method with its analytic
//!      derivative, safeguarded by bisection of the bracket. Exactly one admissible root is
//!      accepted; none is [`ContactError::NoSlidingSolution`], several
//!      [`ContactError::SeveralSlidingSolutions`] (uniqueness is asserted among sliding answers
//!      only: a sticking answer, case 2, is taken first). A double root that the sampling does
//!      not bracket is missed (it would read as no solution, an error, not a wrong answer).

use super::algebra::{
    M3, V3, ZERO, apply, cross, dot, in_plane, length, minus, plus, some_perpendicular, times,
};

/// Why a contact's impulse could not be found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactError {
    /// The Delassus matrix is not positive definite (a pivot of its `L D L^T` not positive).
    NotPositiveDefinite,
    /// The contact neither separates nor sticks, and no sliding direction satisfies the
    /// conditions (or the sampling did not bracket it).
    NoSlidingSolution,
    /// Several sliding directions satisfy the conditions.
    SeveralSlidingSolutions {
        /// How many.
        count: usize,
    },
    /// Newton's method with bisection did not converge within its iterations.
    NotConverged,
    /// Several contacts' data of the wrong sizes, not finite, a normal not unit, a negative
    /// `mu`, or too many contacts (`cone.rs`).
    InvalidInput,
    /// No combination of the contacts' cases meets the cone's conditions (`cone.rs`).
    NoAnswer,
}

impl std::fmt::Display for ContactError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NotPositiveDefinite => write!(f, "the Delassus matrix is not positive definite"),
            Self::NoSlidingSolution => write!(f, "no sliding direction satisfies the contact's conditions"),
            Self::SeveralSlidingSolutions { count } => {
                write!(f, "{count} sliding directions satisfy the contact's conditions")
            }
            Self::NotConverged => write!(f, "the sliding direction's iteration did not converge"),
            Self::InvalidInput => write!(f, "the contacts' data are not a contact problem"),
            Self::NoAnswer => write!(f, "no combination of the contacts' cases meets the cone's conditions"),
        }
    }
}

/// Which case answered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Case {
    Apart,
    Stuck,
    Slides,
}

/// One contact's data for the solve, per unit mass.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point {
    /// Unit normal, out of the plane toward the body.
    pub n: V3,
    /// The Delassus matrix per unit mass, world axes.
    pub w: M3,
    /// The contact point's free velocity plus the gap's bias along `n`.
    pub u: V3,
    /// The friction coefficient of this step.
    pub mu: f64,
}

/// The impulse per unit mass (world axes) and the case that gave it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Answer {
    pub p: V3,
    pub case: Case,
}

/// Angles sampled around the circle in the general sliding case.
const SAMPLES: usize = 64;
/// Newton-with-bisection iterations at most per bracket.
const ITERATIONS: usize = 200;

/// `x` with `w x = b` by `L D L^T` (`w` symmetric); `None` for a pivot that is not positive.
pub(crate) fn solve_spd(w: &M3, b: V3) -> Option<V3> {
    let d0 = w[0][0];
    if d0.is_nan() || d0 <= 0.0 {
        return None;
    }
    let (l10, l20) = (w[1][0] / d0, w[2][0] / d0);
    let d1 = w[1][1] - l10 * l10 * d0;
    if d1.is_nan() || d1 <= 0.0 {
        return None;
    }
    let l21 = (w[2][1] - l20 * l10 * d0) / d1;
    let d2 = w[2][2] - l20 * l20 * d0 - l21 * l21 * d1;
    if d2.is_nan() || d2 <= 0.0 {
        return None;
    }
    let y1 = b[1] - l10 * b[0];
    let y2 = b[2] - l20 * b[0] - l21 * y1;
    let x2 = y2 / d2;
    let x1 = y1 / d1 - l21 * x2;
    let x0 = b[0] / d0 - l10 * x1 - l20 * x2;
    Some([x0, x1, x2])
}

/// The contact's impulse by the module's cases.
///
/// # Errors
/// [`ContactError`] as the module says.
pub(crate) fn solve(c: &Point) -> Result<Answer, ContactError> {
    let (n, mu) = (c.n, c.mu);
    let un = dot(c.u, n);
    if un >= 0.0 {
        return Ok(Answer { p: ZERO, case: Case::Apart });
    }
    let p = solve_spd(&c.w, times(-1.0, c.u)).ok_or(ContactError::NotPositiveDefinite)?;
    let pn = dot(p, n);
    if pn >= 0.0 && length(in_plane(p, n)) <= mu * pn {
        return Ok(Answer { p, case: Case::Stuck });
    }
    let ut = in_plane(c.u, n);
    let slip = length(ut);
    let t1 = if slip > 0.0 { times(1.0 / slip, ut) } else { some_perpendicular(n) };
    let t2 = cross(n, t1);
    if let Some((a, cn)) = isotropic(&c.w, n, t1, t2) {
        // Closed form: the slip keeps its direction.
        let pn = -un / cn;
        let after = slip - a * mu * pn;
        // Case 2 was refused, so `|u_t| / a > mu p_n` but for round-off.
        if after < -1e-12 * slip.max(a * mu * pn) {
            return Err(ContactError::NoSlidingSolution);
        }
        return Ok(Answer { p: times(pn, minus(n, times(mu, t1))), case: Case::Slides });
    }
    let e = general_direction(c, t1, t2)?;
    let pn = -un / dot(n, apply(&c.w, minus(n, times(mu, e))));
    Ok(Answer { p: times(pn, minus(n, times(mu, e))), case: Case::Slides })
}

/// `Some((a, c))` when `w = a (I - n n^T) + c n n^T` to `64 eps` of its trace.
fn isotropic(w: &M3, n: V3, t1: V3, t2: V3) -> Option<(f64, f64)> {
    let tol = 64.0 * f64::EPSILON * (w[0][0] + w[1][1] + w[2][2]).abs();
    let (wn, w1, w2) = (apply(w, n), apply(w, t1), apply(w, t2));
    let coupling = length(in_plane(wn, n)).max(dot(n, w1).abs()).max(dot(n, w2).abs());
    let (a1, a2, a12) = (dot(t1, w1), dot(t2, w2), dot(t1, w2));
    (coupling <= tol && (a1 - a2).abs() <= tol && a12.abs() <= tol).then(|| (0.5 * (a1 + a2), dot(n, wn)))
}

/// `f(theta)`, its derivative, and what decides admissibility: the normal row's denominator
/// `D` and `e . s`.
#[derive(Debug, Clone, Copy)]
struct Sample {
    f: f64,
    df: f64,
    denominator: f64,
    along: f64,
}

fn sample(c: &Point, t1: V3, t2: V3, theta: f64) -> Sample {
    let (n, mu, w) = (c.n, c.mu, &c.w);
    let (sin, cos) = theta.sin_cos();
    let e = plus(times(cos, t1), times(sin, t2));
    let across = plus(times(-sin, t1), times(cos, t2)); // n x e = de/dtheta
    let k = apply(w, minus(n, times(mu, e)));
    let dk = times(-mu, apply(w, across));
    let denominator = dot(n, k);
    let pn = -dot(c.u, n) / denominator;
    let dpn = -pn * dot(n, dk) / denominator;
    let s = in_plane(plus(c.u, times(pn, k)), n);
    let ds = in_plane(plus(times(dpn, k), times(pn, dk)), n);
    let f = dot(across, s);
    // d(n x e)/dtheta = -e.
    let df = -dot(e, s) + dot(across, ds);
    Sample { f, df, denominator, along: dot(e, s) }
}

/// The sliding direction for a `W` that couples or is not isotropic (module docs, case 3).
fn general_direction(c: &Point, t1: V3, t2: V3) -> Result<V3, ContactError> {
    let step = std::f64::consts::TAU / SAMPLES as f64;
    let angle = |j: usize| -std::f64::consts::PI + (j as f64 + 0.5) * step;
    let values: Vec<Sample> = (0..=SAMPLES).map(|j| sample(c, t1, t2, angle(j))).collect();
    let mut roots: Vec<f64> = Vec::new();
    for j in 0..SAMPLES {
        let (a, b) = (values[j], values[j + 1]);
        if a.denominator <= 0.0 || b.denominator <= 0.0 || a.f.is_nan() || b.f.is_nan() {
            continue;
        }
        let root = if a.f == 0.0 {
            angle(j)
        } else if a.f.signum() == b.f.signum() || b.f == 0.0 {
            // No sign change here (a zero at `b` is the next interval's `a`).
            continue;
        } else {
            refine(c, t1, t2, (angle(j), a.f), (angle(j + 1), b.f))?
        };
        let at = sample(c, t1, t2, root);
        if at.denominator > 0.0 && at.along > 0.0 {
            let wrapped = |x: f64| (x + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
            if !roots.iter().any(|&r| {
                let d = (wrapped(r) - wrapped(root)).abs();
                d.min(std::f64::consts::TAU - d) < 1e-9
            }) {
                roots.push(root);
            }
        }
    }
    match roots.as_slice() {
        [] => Err(ContactError::NoSlidingSolution),
        [theta] => {
            let (sin, cos) = theta.sin_cos();
            Ok(plus(times(cos, t1), times(sin, t2)))
        }
        more => Err(ContactError::SeveralSlidingSolutions { count: more.len() }),
    }
}

/// The root of `f` in the bracket `[lo, hi]` (`f(lo)` and `f(hi)` of opposite signs) by
/// Newton's method, a step that leaves the bracket or shrinks too slowly replaced by bisection.
fn refine(
    c: &Point,
    t1: V3,
    t2: V3,
    (mut lo, f_lo): (f64, f64),
    (mut hi, _): (f64, f64),
) -> Result<f64, ContactError> {
    let mut x = 0.5 * (lo + hi);
    let mut last_step = hi - lo;
    for _ in 0..ITERATIONS {
        let s = sample(c, t1, t2, x);
        if s.f == 0.0 {
            return Ok(x);
        }
        if s.f.signum() == f_lo.signum() {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - s.f / s.df;
        let next = if s.df != 0.0 && newton > lo && newton < hi && (newton - x).abs() < 0.5 * last_step {
            newton
        } else {
            0.5 * (lo + hi)
        };
        last_step = (next - x).abs();
        x = next;
        if last_step <= 4.0 * f64::EPSILON || hi - lo <= 4.0 * f64::EPSILON {
            return Ok(x);
        }
    }
    Err(ContactError::NotConverged)
}
