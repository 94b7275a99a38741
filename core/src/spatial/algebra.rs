//! Three-vectors and unit quaternions for the spatial core: the few operations a step needs,
//! written out on `[T; 3]` and `[T; 4]` so that f32 and f64 run the same operations in the same
//! order (no library's choice of fused or reordered arithmetic between the two).

use crate::real::Real;

/// A vector of three coordinates (world axes unless said otherwise: `z` up).
pub type Vector<T> = [T; 3];

/// `a + b`.
#[inline]
#[must_use]
pub fn add<T: Real>(a: &Vector<T>, b: &Vector<T>) -> Vector<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
#[inline]
#[must_use]
pub fn sub<T: Real>(a: &Vector<T>, b: &Vector<T>) -> Vector<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `k a`.
#[inline]
#[must_use]
pub fn scale<T: Real>(k: T, a: &Vector<T>) -> Vector<T> {
    [k * a[0], k * a[1], k * a[2]]
}

/// `a . b`.
#[inline]
#[must_use]
pub fn dot<T: Real>(a: &Vector<T>, b: &Vector<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b`.
#[inline]
#[must_use]
pub fn cross<T: Real>(a: &Vector<T>, b: &Vector<T>) -> Vector<T> {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `|a|`.
#[inline]
#[must_use]
pub fn norm<T: Real>(a: &Vector<T>) -> T {
    dot(a, a).sqrt_rounded()
}

/// `true` when every coordinate is finite.
#[inline]
#[must_use]
pub fn finite<T: Real>(a: &Vector<T>) -> bool {
    a.iter().all(|x| x.finite())
}

/// A unit quaternion `[w, x, y, z]` (`w` the scalar part): the rotation from a body's frame to
/// the world's, `v_world = q v_body q*`.
pub type Quaternion<T> = [T; 4];

/// The identity rotation.
#[must_use]
pub fn identity<T: Real>() -> Quaternion<T> {
    [T::one(), T::zero(), T::zero(), T::zero()]
}

/// The rotation by `angle` (rad) about the unit `axis`.
#[must_use]
pub fn about<T: Real>(axis: &Vector<T>, angle: T) -> Quaternion<T> {
    let (s, c) = (angle * T::of(0.5)).sin_cos_portable();
    [c, s * axis[0], s * axis[1], s * axis[2]]
}

/// The Hamilton product `a b` (`b` applied first).
#[must_use]
pub fn mul<T: Real>(a: &Quaternion<T>, b: &Quaternion<T>) -> Quaternion<T> {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `q` divided by its length (a unit quaternion again after round-off has moved it).
#[must_use]
pub fn normalized<T: Real>(q: &Quaternion<T>) -> Quaternion<T> {
    let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt_rounded();
    let inv = T::one() / n;
    [q[0] * inv, q[1] * inv, q[2] * inv, q[3] * inv]
}

/// `q v q*`: `v` in the body's frame turned into the world's.
#[must_use]
pub fn rotate<T: Real>(q: &Quaternion<T>, v: &Vector<T>) -> Vector<T> {
    // v + 2 w (u x v) + 2 u x (u x v), u the vector part.
    let u = [q[1], q[2], q[3]];
    let t = scale(T::of(2.0), &cross(&u, v));
    add(&add(v, &scale(q[0], &t)), &cross(&u, &t))
}

/// The matrix `R` of a unit quaternion's rotation (body axes to world axes), row by row: built
/// once for several turns by one orientation, each then nine products (`R v`, `R^T v`) where
/// [`rotate`] takes two cross products, and its columns, the body's axes in the world, free.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rotation<T>(pub(crate) [[T; 3]; 3]);

impl<T: Real> Rotation<T> {
    /// The rotation `q` (unit).
    #[must_use]
    pub(crate) fn of(q: &Quaternion<T>) -> Self {
        let (one, two) = (T::one(), T::of(2.0));
        let [w, x, y, z] = *q;
        Self([
            [one - two * (y * y + z * z), two * (x * y - w * z), two * (x * z + w * y)],
            [two * (x * y + w * z), one - two * (x * x + z * z), two * (y * z - w * x)],
            [two * (x * z - w * y), two * (y * z + w * x), one - two * (x * x + y * y)],
        ])
    }

    /// `R v`: `v` in the body's frame turned into the world's.
    #[inline]
    #[must_use]
    pub(crate) fn apply(&self, v: &Vector<T>) -> Vector<T> {
        self.0.map(|row| dot(&row, v))
    }

    /// `R^T v`: `v` in the world's frame turned into the body's.
    #[inline]
    #[must_use]
    pub(crate) fn unapply(&self, v: &Vector<T>) -> Vector<T> {
        let r = &self.0;
        core::array::from_fn(|i| r[0][i] * v[0] + r[1][i] * v[1] + r[2][i] * v[2])
    }

    /// The body's axis `i` (0, 1, 2: its x, y, z) in the world: `R`'s column `i`.
    #[inline]
    #[must_use]
    pub(crate) fn axis(&self, i: usize) -> Vector<T> {
        self.0.map(|row| row.get(i).copied().unwrap_or(T::zero()))
    }
}

/// `q* v q`: `v` in the world's frame turned into the body's.
#[must_use]
pub fn unrotate<T: Real>(q: &Quaternion<T>, v: &Vector<T>) -> Vector<T> {
    rotate(&[q[0], -q[1], -q[2], -q[3]], v)
}

/// The unit vector along `a`, or `None` when `a` is zero or not finite.
#[must_use]
pub fn direction<T: Real>(a: &Vector<T>) -> Option<Vector<T>> {
    let n = norm(a);
    (n > T::zero() && n.finite()).then(|| scale(T::one() / n, a))
}

/// A unit vector perpendicular to the unit `n`: `n` crossed with the world axis least along it.
#[must_use]
pub fn perpendicular<T: Real>(n: &Vector<T>) -> Vector<T> {
    let axis = if n[0].abs_exact() <= n[1].abs_exact() && n[0].abs_exact() <= n[2].abs_exact() {
        [T::one(), T::zero(), T::zero()]
    } else if n[1].abs_exact() <= n[2].abs_exact() {
        [T::zero(), T::one(), T::zero()]
    } else {
        [T::zero(), T::zero(), T::one()]
    };
    let t = cross(n, &axis);
    scale(T::one() / norm(&t), &t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_turns_axes_as_the_right_hand_rule_says() {
        let q = about(&[0.0, 0.0, 1.0], core::f64::consts::FRAC_PI_2);
        let x = rotate(&q, &[1.0, 0.0, 0.0]);
        assert!((x[0]).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15 && x[2].abs() < 1e-15, "{x:?}");
        let back = unrotate(&q, &x);
        assert!((back[0] - 1.0).abs() < 1e-15 && back[1].abs() < 1e-15, "{back:?}");
        // Two quarter turns about x after one about z: composition order.
        let qx = about(&[1.0, 0.0, 0.0], core::f64::consts::PI);
        let y = rotate(&mul(&qx, &q), &[1.0, 0.0, 0.0]);
        assert!((y[1] + 1.0).abs() < 1e-15, "{y:?}");
        let p = perpendicular(&[0.0_f64, 0.6, 0.8]);
        assert!(dot(&p, &[0.0, 0.6, 0.8]).abs() < 1e-15 && (norm(&p) - 1.0).abs() < 1e-15);
    }

    /// The rotation's matrix turns vectors as the quaternion does, both ways, and its columns are
    /// the body's axes turned, at orientations about several axes.
    #[test]
    fn rotation_matrix_agrees_with_the_quaternion() {
        let v = [0.3, -1.7, 2.2];
        for (k, axis) in [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [1.0, 2.0, -2.0]].iter().enumerate() {
            let unit = scale(1.0 / norm(axis), axis);
            let q = mul(&about(&unit, 0.4 + 1.1 * k as f64), &about(&[1.0, 0.0, 0.0], -0.7));
            let r = Rotation::of(&q);
            let close = |a: Vector<f64>, b: Vector<f64>| norm(&sub(&a, &b)) < 1e-14;
            assert!(close(r.apply(&v), rotate(&q, &v)), "{k}: {:?} {:?}", r.apply(&v), rotate(&q, &v));
            assert!(close(r.unapply(&v), unrotate(&q, &v)), "{k}");
            for (i, e) in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].iter().enumerate() {
                assert!(close(r.axis(i), rotate(&q, e)), "{k}, axis {i}");
            }
            assert!(close(r.unapply(&r.apply(&v)), v), "{k}");
        }
    }
}
