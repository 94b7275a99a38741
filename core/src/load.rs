//! The load where rigid contact leaves it open (`docs/formulation.md`, "The load: the least
//! norm"): once a step's motion is chosen ([`crate::rule`]), the impulses that produce it are
//! taken to be those of **least 2-norm**.
//!
//! A rigid body on more supports than its equilibrium needs (a rod on three fingers, a box's face
//! on a table, two corners sticking side by side) reaches the same motion with a whole set of
//! impulses. With the motion fixed, each contact `c` may carry:
//!
//! - nothing, when it separates (or is inactive);
//! - a normal impulse `x_n >= 0` and a friction impulse `|x_f| <= mu x_n`, when it sticks;
//! - a normal impulse `x_n >= 0` and the friction `x_f = s mu x_n` against its slip, when it
//!   slides (`s` the sign of the friction along the contact's `+d`).
//!
//! and the impulses together must give the motion's momentum change: `W x = W x_path`, `W` the
//! columns of the contacts' normal and friction impulses in the bodies' coordinates and `x_path`
//! the answer the step's solver (and the rule) reached. Among those loads the core takes the one
//! of least `sum_c x_n^2 + x_f^2`. For a body on equally stiff supports this is the load that
//! elasticity gives (Menabrea: the forces of a statically admissible set that minimise the
//! complementary energy `sum F^2 / (2 k)`): for collinear supports under a rod, normal loads affine
//! in the supports' positions (`N_i = a + b x_i`), a support that would pull carrying nothing; a
//! uniform pressure under a centred flat base; a friction force shared equally by the corners of
//! one face.
//!
//! The set is the polyhedron `{x : E x = E x_path, A x >= 0}`: `E` holds `W`'s rows and, for
//! each sliding contact, `x_f - s mu x_n = 0`, for each carrying nothing `x_n = x_f = 0`; `A` holds
//! `x_n >= 0` and the cone's `mu x_n - x_f >= 0`, `mu x_n + x_f >= 0`. With `Q` an orthonormal
//! basis of `E`'s rows (modified Gram-Schmidt, twice) and `P = I - Q^T Q` the projection on its
//! null space, the least-norm point of the affine set is `x0 = Q^T Q x_path`, and the answer is
//! `x = x0 + P A^T lambda` where `lambda` solves the LCP of the problem's optimality conditions:
//!
//! ```text
//! w = (A P A^T) lambda + A x0 >= 0,   lambda >= 0,   w^T lambda = 0
//! ```
//!
//! (`A P A^T` is positive semidefinite and the set is not empty, so Lemke's method solves it.)
//! Three steps, each cheaper than the next, each taken only when the one before does not answer:
//!
//! 1. **Determinate**: `E` has rank `2C` (no direction in which the load can move): the path's
//!    load is the only one. Nothing else is done.
//! 2. **Projection**: `x0` satisfies `A x0 >= 0` (within round-off): no inequality binds and `x0`
//!    is the answer (a rod at rest on three fingers whose affine split loads every finger; a
//!    load already of least norm, as a resting stack's every step).
//! 3. **LCP**: [`Lemke`], warm-started from the previous such step's basis (a rest state keeps
//!    its basis: no pivot), verified as every LCP answer is.
//!
//! For one body on two sticking contacts ([`least_norm_two_sticking`]) the null space is a line
//! and the problem a clamp on it, in closed form.
//!
//! `C` contacts, `B` bodies (`3B` coordinates), `L` rows of the LCP: three per contact that may
//! carry (contact `c` at rows `3c..3c + 3`, so each must have `3c + 2 < L`), the others decoupled
//! (`w = 1`), so that a caller shares a solver size it already has (the planar full layout's
//! `4K`, the multibody stepper's `N` with at most `N / 4` slots). No heap; failure is an [`LcpError`].

use crate::lcp::{Basis, Lcp, LcpError, Lemke};
use crate::real::{Real, max, min};

/// How a contact may carry load at the step's motion.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum Carry<T> {
    /// Separating or inactive: no impulse.
    Nothing,
    /// Touching without slip: `x_n >= 0`, `|x_f| <= mu x_n`.
    Sticking {
        /// The step's friction coefficient of the contact.
        mu: T,
    },
    /// Touching and slipping: `x_n >= 0`, `x_f = friction_per_normal x_n`.
    Sliding {
        /// `s mu`: the step's coefficient, signed as the friction along the contact's `+d`.
        friction_per_normal: T,
    },
}

/// One contact as the load sees it: its impulses' columns and what it may carry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LoadContact<T, const B: usize> {
    /// The normal impulse's column in the bodies' coordinates `(x, y, theta)` per body.
    pub normal: [[T; 3]; B],
    /// The friction impulse's column (along the contact's `+d`).
    pub tangent: [[T; 3]; B],
    /// What the contact may carry at the step's motion.
    pub carry: Carry<T>,
}

/// How [`least_norm`] reached its answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum LoadPath {
    /// The contacts decide the load: the path's answer is the only one.
    Determinate,
    /// The projection of the path's load on its affine set: no inequality binds.
    Projection,
    /// The least-norm problem's LCP, with its pivots (0 when its warm basis answered).
    Lcp(u32),
}

/// A vector of the load's unknowns: `(x_n, x_f)` per contact.
type Unknowns<T, const C: usize> = [[T; 2]; C];

fn dot<T: Real, const C: usize>(a: &Unknowns<T, C>, b: &Unknowns<T, C>) -> T {
    let mut s = T::zero();
    for c in 0..C {
        s += a[c][0] * b[c][0] + a[c][1] * b[c][1];
    }
    s
}

fn add_scaled<T: Real, const C: usize>(to: &mut Unknowns<T, C>, k: T, v: &Unknowns<T, C>) {
    for c in 0..C {
        to[c][0] += k * v[c][0];
        to[c][1] += k * v[c][1];
    }
}

/// An orthonormal basis of the rows offered ([`Self::offer`]) and of the unit rows of the
/// contacts that carry nothing: the rows of `E`.
struct RowSpace<T, const C: usize> {
    /// The first `rank` are orthonormal and zero at every contact that carries nothing; at most
    /// `2C` of them.
    rows: [[Unknowns<T, C>; 2]; C],
    rank: usize,
    /// The contacts that carry nothing: `x_n = x_f = 0` are two rows of `E` each, kept as a mask.
    nothing: [bool; C],
}

impl<T: Real, const C: usize> RowSpace<T, C> {
    fn new(carry: &[Carry<T>; C]) -> Self {
        Self {
            rows: [[[[T::zero(); 2]; C]; 2]; C],
            rank: 0,
            nothing: carry.map(|c| matches!(c, Carry::Nothing)),
        }
    }

    /// The rank of `E`: the rows kept and two per contact that carries nothing.
    fn rank(&self) -> usize {
        self.rank + 2 * self.nothing.iter().filter(|&&n| n).count()
    }

    fn row(&self, k: usize) -> &Unknowns<T, C> {
        &self.rows[(k / 2) % C][k % 2]
    }

    /// `v` less its projection on the rows of `E`: zero at the contacts that carry nothing, then
    /// less its projection on each row kept.
    fn reject(&self, v: &mut Unknowns<T, C>) {
        for (x, &nothing) in v.iter_mut().zip(&self.nothing) {
            if nothing {
                *x = [T::zero(); 2];
            }
        }
        for k in 0..self.rank {
            let q = *self.row(k);
            let along = dot(v, &q);
            add_scaled(v, -along, &q);
        }
    }

    /// Adds `v`'s direction when it is not in the span of `E`'s rows so far, within round-off of
    /// `v`'s own length (modified Gram-Schmidt, applied twice: "twice is enough").
    fn offer(&mut self, mut v: Unknowns<T, C>) {
        if self.rank() >= 2 * C {
            return;
        }
        let length = dot(&v, &v).sqrt_rounded();
        if length <= T::zero() || !length.finite() {
            return;
        }
        self.reject(&mut v);
        self.reject(&mut v);
        let rest = dot(&v, &v).sqrt_rounded();
        if rest <= T::of(64.0 * (2 * C) as f64) * T::EPS * length {
            return;
        }
        let inv = T::one() / rest;
        for x in &mut v {
            x[0] *= inv;
            x[1] *= inv;
        }
        let k = self.rank;
        if let Some(slot) = self.rows.get_mut(k / 2).and_then(|r| r.get_mut(k % 2)) {
            *slot = v;
            self.rank += 1;
        }
    }

    /// `P v`: `v`'s projection on the null space of `E`.
    fn null_part(&self, v: &Unknowns<T, C>) -> Unknowns<T, C> {
        let mut out = *v;
        self.reject(&mut out);
        out
    }
}

/// The rows of `A`: row `3c` is `x_n >= 0`, `3c + 1` is `mu x_n - x_f >= 0`, `3c + 2` is
/// `mu x_n + x_f >= 0`, for a sticking contact; a sliding one has only `x_n >= 0`. `None`: a row
/// that does not constrain this step (and every row past `3C`).
fn inequality<T: Real, const C: usize>(carry: &[Carry<T>; C], row: usize) -> Option<Unknowns<T, C>> {
    let c = row / 3;
    let mut a = [[T::zero(); 2]; C];
    let slot = a.get_mut(c)?;
    match (carry.get(c)?, row % 3) {
        (Carry::Sticking { .. } | Carry::Sliding { .. }, 0) => slot[0] = T::one(),
        (Carry::Sticking { mu }, 1) => *slot = [*mu, -T::one()],
        (Carry::Sticking { mu }, _) => *slot = [*mu, T::one()],
        _ => return None,
    }
    Some(a)
}

/// The load of least 2-norm that gives the same momentum change as `path` (`(x_n, x_f)` per
/// contact), among the loads `contacts` may carry ("The load where rigid contact leaves it open",
/// above). `warm` is the basis of the last step that needed the LCP; it receives this step's.
/// `path` itself must be such a load (the step's verified answer); the answer is returned with
/// how it was reached.
///
/// # Errors
/// The least-norm LCP's [`LcpError`] (it has a solution whenever `path` is a load the contacts
/// may carry: an error means round-off broke that); [`LcpError::NonFiniteInput`] for a contact
/// that may carry beyond the LCP's rows (a caller's error, not a step's).
#[inline(never)] // one copy per size, shared by every stepper of it
pub(crate) fn least_norm<T: Real, const C: usize, const B: usize, const L: usize>(
    contacts: &[LoadContact<T, B>; C],
    path: &Unknowns<T, C>,
    warm: &mut Basis<L>,
) -> Result<(Unknowns<T, C>, LoadPath), LcpError> {
    let carry = contacts.map(|c| c.carry);
    // A contact whose rows would fall past the LCP's `L` cannot be constrained: none may carry.
    if carry.iter().enumerate().any(|(c, k)| 3 * c + 2 >= L && !matches!(k, Carry::Nothing)) {
        return Err(LcpError::NonFiniteInput);
    }
    let mut space = RowSpace::<T, C>::new(&carry);
    for b in 0..B {
        for k in 0..3 {
            let mut row = [[T::zero(); 2]; C];
            for (r, contact) in row.iter_mut().zip(contacts) {
                *r = [contact.normal[b][k], contact.tangent[b][k]];
            }
            space.offer(row);
        }
    }
    for (c, contact) in contacts.iter().enumerate() {
        if let Carry::Sliding { friction_per_normal } = contact.carry {
            let mut row = [[T::zero(); 2]; C];
            row[c] = [-friction_per_normal, T::one()];
            space.offer(row);
        }
    }
    if space.rank() >= 2 * C {
        return Ok((*path, LoadPath::Determinate));
    }
    let x0 = {
        let free = space.null_part(path);
        let mut x0 = *path;
        add_scaled(&mut x0, -T::one(), &free);
        x0
    };
    // Round-off of the load: a few eps of its largest entry per unknown.
    let mut scale = T::zero();
    for p in path {
        scale = max(scale, max(p[0].abs_exact(), p[1].abs_exact()));
    }
    let tolerance = T::of(64.0 * L as f64) * T::EPS * scale;
    if (0..L).all(|i| inequality(&carry, i).is_none_or(|a| dot(&a, &x0) >= -tolerance)) {
        return Ok((x0, LoadPath::Projection));
    }
    let mut projected = [[[T::zero(); 2]; C]; L];
    let mut q = [T::zero(); L];
    for i in 0..L {
        match inequality(&carry, i) {
            Some(a) => {
                projected[i] = space.null_part(&a);
                q[i] = dot(&a, &x0);
            }
            None => q[i] = T::one(),
        }
    }
    // Built in place (no `L x L` array beside it: the Cortex-M0's stack holds this under a step).
    let lcp = Lcp {
        m: nalgebra::SMatrix::from_fn(|i, j| dot(&projected[i], &projected[j])),
        q: nalgebra::SVector::from_fn(|i, _| q[i]),
    };
    let solution = Lemke::<T, L>::new().solve_from_basis(&lcp, *warm)?;
    *warm = solution.basis;
    let mut x = x0;
    for (i, a) in projected.iter().enumerate() {
        add_scaled(&mut x, solution.z[i], a);
    }
    Ok((x, LoadPath::Lcp(solution.pivots)))
}

/// [`least_norm`] for one body on two sticking contacts (four unknowns `x = (x_n1, x_f1, x_n2,
/// x_f2)` in three coordinates), in closed form. `columns` are the unknowns' columns in the body's
/// coordinates, in that order. When they span the three coordinates the loads with the path's
/// motion are the line `path + t n`, `n` the columns' null vector (its entries the signed 3x3
/// minors, `n_j = (-1)^j det(columns without j)`), and the least norm on it is at
/// `t* = -path . n / n . n`; each inequality `a . x >= 0` ([`inequality`]'s rows) holds for `t`
/// on one side of `-a . path / a . n`, so `t*` clamped into the interval they leave is the answer:
/// the same as [`least_norm`]'s LCP, without Gram-Schmidt or pivots. `None` when the columns span
/// less (`n . n` within round-off of zero: the null space is more than a line), for the caller
/// to take [`least_norm`].
#[must_use]
pub(crate) fn least_norm_two_sticking<T: Real>(
    columns: &[[T; 3]; 4],
    mu: [T; 2],
    path: &Unknowns<T, 2>,
) -> Option<Unknowns<T, 2>> {
    let det = |a: &[T; 3], b: &[T; 3], c: &[T; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    };
    let [c0, c1, c2, c3] = columns;
    let n = [[det(c1, c2, c3), -det(c0, c2, c3)], [det(c0, c1, c3), -det(c0, c1, c2)]];
    let nn = dot(&n, &n);
    // `|det| <= |a| |b| |c|`: the minors' scale is the columns' size cubed.
    let mut size = T::zero();
    for c in columns {
        size += c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    }
    let round_off = T::of(64.0) * T::EPS;
    // (Written so that a NaN `nn` also answers `None`.)
    if nn.partial_cmp(&(round_off * round_off * size * size * size)) != Some(core::cmp::Ordering::Greater) {
        return None;
    }
    let (mut lo, mut hi): (Option<T>, Option<T>) = (None, None);
    for c in 0..2 {
        let (p, d, m) = (path[c], n[c], mu[c]);
        // `x_n >= 0`, `mu x_n - x_f >= 0`, `mu x_n + x_f >= 0`: `g0 + t g1 >= 0`.
        for (g0, g1) in [(p[0], d[0]), (m * p[0] - p[1], m * d[0] - d[1]), (m * p[0] + p[1], m * d[0] + d[1])]
        {
            if g1 > T::zero() {
                lo = Some(lo.map_or(-g0 / g1, |l| max(l, -g0 / g1)));
            } else if g1 < T::zero() {
                hi = Some(hi.map_or(-g0 / g1, |h| min(h, -g0 / g1)));
            }
        }
    }
    let mut t = -dot(path, &n) / nn;
    if let Some(l) = lo {
        t = max(t, l);
    }
    if let Some(h) = hi {
        t = min(t, h);
    }
    // The path is a load the contacts may carry (`t = 0` within the interval, but for round-off):
    // an interval that round-off closed keeps it.
    if let (Some(l), Some(h)) = (lo, hi)
        && l > h
    {
        t = T::zero();
    }
    let mut x = *path;
    add_scaled(&mut x, t, &n);
    Some(x)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::cast_precision_loss)]

    use super::*;

    /// A level rod of thickness `t` on point fingers at `xs` (coordinates `(x, y, theta)`, the
    /// centre of mass at the origin): normal `(0, 1, x)`, friction along `+x` `(1, 0, t / 2)`
    /// (the contact point `t/2` below the centre: `r x d = -(-t/2) * 1`).
    fn rod<const C: usize>(xs: [f64; C], carry: [Carry<f64>; C]) -> [LoadContact<f64, 1>; C] {
        core::array::from_fn(|c| LoadContact {
            normal: [[0.0, 1.0, xs[c]]],
            tangent: [[1.0, 0.0, 0.0025]],
            carry: carry[c],
        })
    }

    /// The elastic split of a weight `w` over collinear supports at `xs` under a centre of mass at
    /// 0 (every support loaded): `N_i = a + b x_i` with `sum N = w`, `sum N x = 0`.
    fn affine<const C: usize>(xs: [f64; C], w: f64) -> [f64; C] {
        let n = C as f64;
        let (sx, sxx) = (xs.iter().sum::<f64>(), xs.iter().map(|x| x * x).sum::<f64>());
        // a n + b sx = w, a sx + b sxx = 0.
        let b = -w * sx / (n * sxx - sx * sx);
        let a = (w - b * sx) / n;
        xs.map(|x| a + b * x)
    }

    #[test]
    fn three_fingers_at_rest_carry_the_affine_split_from_any_vertex() {
        let xs = [-0.45, -0.05, 0.3];
        let stick = [Carry::Sticking { mu: 0.6 }; 3];
        let expected = affine(xs, 1.0);
        // Every vertex of the statically indeterminate set: two fingers loaded, the third not.
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let (xi, xj) = (xs[i], xs[j]);
            let mut path = [[0.0; 2]; 3];
            path[i][0] = xj / (xj - xi);
            path[j][0] = -xi / (xj - xi);
            let mut warm = Basis::<9>::all_w();
            let (x, how) = least_norm(&rod(xs, stick), &path, &mut warm).unwrap();
            assert_eq!(how, LoadPath::Projection);
            for c in 0..3 {
                assert!((x[c][0] - expected[c]).abs() < 1e-14, "{x:?} {expected:?}");
                assert!(x[c][1].abs() < 1e-14, "{x:?}");
            }
        }
    }

    #[test]
    fn a_support_that_would_pull_carries_nothing() {
        // The centre of mass near the right finger: the affine split over all three would pull
        // at the left one, so it carries nothing and the other two carry the rod.
        let xs = [-0.4, -0.3, 0.02];
        assert!(affine(xs, 1.0)[0] < 0.0);
        let stick = [Carry::Sticking { mu: 0.6 }; 3];
        // A vertex: the outer fingers carry it.
        let path = [[0.02 / 0.42, 0.0], [0.0, 0.0], [0.4 / 0.42, 0.0]];
        let mut warm = Basis::<9>::all_w();
        let (x, how) = least_norm(&rod(xs, stick), &path, &mut warm).unwrap();
        assert!(matches!(how, LoadPath::Lcp(_)), "{how:?}");
        let expected = [0.0, 0.02 / 0.32, 0.3 / 0.32];
        for c in 0..3 {
            assert!((x[c][0] - expected[c]).abs() < 1e-14, "{x:?} {expected:?}");
            assert!(x[c][1].abs() < 1e-14, "{x:?}");
        }
        // Warm-started again from its own basis: no pivot, the same split.
        let (again, how) = least_norm(&rod(xs, stick), &x, &mut warm).unwrap();
        assert_eq!(how, LoadPath::Lcp(0));
        for c in 0..3 {
            assert!((again[c][0] - expected[c]).abs() < 1e-14, "{again:?}");
        }
    }

    #[test]
    fn two_contacts_one_sliding_are_determinate() {
        let xs = [-0.3, 0.4];
        let carry = [Carry::Sticking { mu: 0.6 }, Carry::Sliding { friction_per_normal: -0.4 }];
        let path = [[0.5, 0.1], [0.5, -0.2]];
        let (x, how) = least_norm(&rod(xs, carry), &path, &mut Basis::<6>::all_w()).unwrap();
        assert_eq!(how, LoadPath::Determinate);
        assert_eq!(x, path);
    }

    #[test]
    fn two_sticking_corners_share_their_friction_equally() {
        let xs = [-0.05, 0.05];
        let stick = [Carry::Sticking { mu: 0.6 }; 2];
        // All the friction on one corner (a vertex), the normals balancing its moment.
        let f = 0.3;
        let path = [[0.5 - 0.0025 * f / 0.1, f], [0.5 + 0.0025 * f / 0.1, 0.0]];
        let (x, how) = least_norm(&rod(xs, stick), &path, &mut Basis::<6>::all_w()).unwrap();
        assert_eq!(how, LoadPath::Projection);
        assert!((x[0][1] - f / 2.0).abs() < 1e-14 && (x[1][1] - f / 2.0).abs() < 1e-14, "{x:?}");
        assert!((x[0][0] - path[0][0]).abs() < 1e-14 && (x[1][0] - path[1][0]).abs() < 1e-14, "{x:?}");
    }
    /// The closed form for two sticking contacts against [`least_norm`]'s LCP, on random bodies
    /// (any columns, not only a rod's) and random loads the contacts may carry, the cones' edges
    /// included (a load at `|x_f| = mu x_n` binds an inequality): the same answer to round-off.
    #[test]
    fn two_sticking_contacts_in_closed_form_agree_with_the_lcp() {
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut uniform = |lo: f64, hi: f64| {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
        };
        let (mut projections, mut lcp_answers) = (0, 0);
        for case in 0..2000 {
            let mu = [uniform(0.05, 1.5), uniform(0.05, 1.5)];
            let columns: [[f64; 3]; 4] =
                core::array::from_fn(|_| [uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-0.5, 0.5)]);
            let mut path = [[0.0; 2]; 2];
            for c in 0..2 {
                path[c][0] = uniform(0.0, 1.0);
                // A third of the cases on an edge of the cone.
                let f = if case % 3 == 0 { 1.0 } else { uniform(-1.0, 1.0) };
                path[c][1] = f * mu[c] * path[c][0];
            }
            let contacts: [LoadContact<f64, 1>; 2] = core::array::from_fn(|c| LoadContact {
                normal: [columns[2 * c]],
                tangent: [columns[2 * c + 1]],
                carry: Carry::Sticking { mu: mu[c] },
            });
            let mut warm = Basis::<6>::all_w();
            let (by_lcp, how) = least_norm(&contacts, &path, &mut warm).unwrap();
            lcp_answers += usize::from(matches!(how, LoadPath::Lcp(_)));
            let closed = least_norm_two_sticking(&columns, mu, &path).unwrap();
            for c in 0..2 {
                for k in 0..2 {
                    assert!(
                        (closed[c][k] - by_lcp[c][k]).abs() < 1e-12,
                        "case {case}: {closed:?} {by_lcp:?}"
                    );
                }
            }
            projections += usize::from(how == LoadPath::Projection);
        }
        // Both kinds of case were met: the projection and an inequality binding.
        assert!(lcp_answers > 100, "{lcp_answers} cases bound an inequality");
        assert!(projections > 100, "{projections} cases answered by the projection");
    }

    #[test]
    fn two_contacts_at_one_point_have_no_closed_form() {
        let c = [[0.0, 1.0, 0.3], [1.0, 0.0, 0.0025]];
        let columns = [c[0], c[1], c[0], c[1]];
        assert!(least_norm_two_sticking(&columns, [0.6, 0.6], &[[0.5, 0.0], [0.5, 0.0]]).is_none());
    }
}
