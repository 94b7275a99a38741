//! Three-vectors, 3x3 matrices and quaternions for the spatial reference, written out on plain
//! arrays. The core turns vectors with the quaternion sandwich; here every rotation goes through
//! its matrix (`matrix_of`), and the inertia through `R diag(1 / I) R^T` built once a step.

/// A vector, world axes unless said otherwise (`z` up).
pub(crate) type V3 = [f64; 3];
/// A 3x3 matrix, rows first.
pub(crate) type M3 = [[f64; 3]; 3];
/// A unit quaternion `[w, x, y, z]`: the rotation from the body's frame to the world's.
pub(crate) type Quat = [f64; 4];

pub(crate) const ZERO: V3 = [0.0; 3];

pub(crate) fn plus(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn minus(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn times(k: f64, a: V3) -> V3 {
    a.map(|x| k * x)
}

pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub(crate) fn length(a: V3) -> f64 {
    a[0].hypot(a[1]).hypot(a[2])
}

/// `a` without its part along the unit `n`: its projection on the plane of normal `n`.
pub(crate) fn in_plane(a: V3, n: V3) -> V3 {
    minus(a, times(dot(a, n), n))
}

/// `[a]x`, the matrix of `b -> a x b`.
pub(crate) fn skew(a: V3) -> M3 {
    [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
}

pub(crate) fn apply(m: &M3, a: V3) -> V3 {
    [dot(m[0], a), dot(m[1], a), dot(m[2], a)]
}

pub(crate) fn transpose(m: &M3) -> M3 {
    [[m[0][0], m[1][0], m[2][0]], [m[0][1], m[1][1], m[2][1]], [m[0][2], m[1][2], m[2][2]]]
}

pub(crate) fn product(a: &M3, b: &M3) -> M3 {
    let bt = transpose(b);
    [
        [dot(a[0], bt[0]), dot(a[0], bt[1]), dot(a[0], bt[2])],
        [dot(a[1], bt[0]), dot(a[1], bt[1]), dot(a[1], bt[2])],
        [dot(a[2], bt[0]), dot(a[2], bt[1]), dot(a[2], bt[2])],
    ]
}

pub(crate) fn identity3() -> M3 {
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
}

/// `R diag(d) R^T`.
pub(crate) fn congruent(r: &M3, d: V3) -> M3 {
    let scaled = [
        [r[0][0] * d[0], r[0][1] * d[1], r[0][2] * d[2]],
        [r[1][0] * d[0], r[1][1] * d[1], r[1][2] * d[2]],
        [r[2][0] * d[0], r[2][1] * d[1], r[2][2] * d[2]],
    ];
    product(&scaled, &transpose(r))
}

/// The rotation matrix of the unit quaternion `q` (its columns: the body's axes in the world).
pub(crate) fn matrix_of(q: Quat) -> M3 {
    let [w, x, y, z] = q;
    [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
    ]
}

/// The Hamilton product `a b` (`b` first, then `a`).
pub(crate) fn compose(a: Quat, b: Quat) -> Quat {
    let (aw, av) = (a[0], [a[1], a[2], a[3]]);
    let (bw, bv) = (b[0], [b[1], b[2], b[3]]);
    let v = plus(plus(times(aw, bv), times(bw, av)), cross(av, bv));
    [aw * bw - dot(av, bv), v[0], v[1], v[2]]
}

/// The rotation by the angle `|phi|` about `phi`'s direction (the identity for `phi = 0`).
pub(crate) fn rotation_by(phi: V3) -> Quat {
    let angle = length(phi);
    if angle == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let half = 0.5 * angle;
    let k = half.sin() / angle;
    [half.cos(), k * phi[0], k * phi[1], k * phi[2]]
}

/// `q` scaled to unit length.
pub(crate) fn unit(q: Quat) -> Quat {
    let n = q[0].hypot(q[1]).hypot(q[2].hypot(q[3]));
    q.map(|x| x / n)
}

/// `q` turned by the world-axes rotation vector `phi`: `rotation_by(phi) q`, renormalised; `q`
/// itself when `phi = 0`.
pub(crate) fn turn(q: Quat, phi: V3) -> Quat {
    if phi == ZERO { q } else { unit(compose(rotation_by(phi), q)) }
}

/// A unit vector perpendicular to the unit `n`: `n x e` for the world axis `e` least along `n`.
pub(crate) fn some_perpendicular(n: V3) -> V3 {
    let a = n.map(f64::abs);
    let e = if a[0] <= a[1] && a[0] <= a[2] {
        [1.0, 0.0, 0.0]
    } else if a[1] <= a[2] {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let t = cross(n, e);
    times(1.0 / length(t), t)
}
