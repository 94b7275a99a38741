//! Assembly of one time step's LCP (paper, eqs. 13-18; formulation.md "One time step").
//!
//! Variables `z = (p_n, p_f, sigma)`:
//! * `N = 8` (the paper's form): `(p_n1, p_n2, p_f1+, p_f1-, p_f2+, p_f2-, sigma_1, sigma_2)`;
//! * `N = 6` (reduced): `(p_n1, p_n2, p_f1+, p_f2-, sigma_1, sigma_2)`, keeping the one
//!   friction direction each finger can use while finger 1 moves toward finger 2: finger 1
//!   drags the rod toward `+d`, finger 2 holds it back along `-d`.
//!
//! With `c_j` the wrench column of impulse `j` (`W_n` or `+-W_t`), `M^-1 = diag(1/m, 1/m, 1/J)`
//! and `v~ = v + h M^-1 w_ext`:
//!
//! ```text
//! A[j][k] = c_j^T M^-1 c_k                         (impulse rows and columns, eq. 18)
//! A[f][sigma_i] = 1      for the friction rows f of contact i      (E)
//! A[sigma_i][n_i] = mu_i,  A[sigma_i][f] = -1                      (U, -E^T)
//! b_n = W_n^T v~ - n . u_i + beta(psi_i)                            (eq. 13, normal row)
//! b_f = +-(W_t^T v~ - d . u_i)                                    (friction rows)
//! b_sigma = 0
//! ```
//!
//! **Penetration recovery.** The paper's normal row has `beta = psi / h`: a gap may close in
//! one step, and a penetration is pushed out in one step. Pushing out at `|psi| / h` gives the
//! rod the kinetic energy `m psi^2 / (2 h^2)`, which exceeds the potential energy the
//! penetration represents, `m g |psi|`, by `|psi| / (2 g h^2)` (5x for 0.1 mm at h = 1 ms,
//! 5e4x at h = 1e-5 s: the rod is shot up; found by `host-sim stress`). So for `psi < 0` the
//! push-out speed is capped at the speed of a fall through the penetration depth:
//! `beta = max(psi / h, -sqrt(2 g |psi|))`. The rod then climbs at most back to where it
//! should rest. (Without gravity the cap is zero: a penetration stays and does not grow.)
//! Mass scaling: every row of the LCP is a velocity when `m_inv` is `diag(M^-1)` times the
//! rod mass (the scene's choice, impulses per unit mass); see [`StepInputs::m_inv`].
//!
//! A contact whose finger is not under the rod is decoupled: its rows and columns become
//! those of the identity and `b = 1`, so its variables are zero.

use crate::lcp::Lcp;
use crate::nalgebra::{SMatrix, SVector};
use crate::real::Real;

use super::contact::ContactFrame;

/// The friction directions of the size-`N` model: `(contact, sign of d)` per column.
#[must_use]
pub const fn friction_directions(n: usize) -> &'static [(usize, i8)] {
    if n == 8 { &[(0, 1), (0, -1), (1, 1), (1, -1)] } else { &[(0, 1), (1, -1)] }
}

/// Index of `sigma_i` in `z`.
#[must_use]
pub const fn sigma_index(n: usize, contact: usize) -> usize {
    n - 2 + contact
}

/// The step's LCP and the wrench column of each impulse variable (zero for `sigma`).
#[derive(Debug, Clone, Copy)]
pub struct StepLcp<T: Real, const N: usize> {
    /// `(A, b)`.
    pub lcp: Lcp<T, N>,
    /// Wrench column of each variable of `z`.
    pub columns: [[T; 3]; N],
}

/// Inputs of one step's assembly.
#[derive(Debug, Clone, Copy)]
pub struct StepInputs<'a, T> {
    /// The two contact frames.
    pub frames: &'a [ContactFrame<T>; 2],
    /// Friction coefficient of each contact this step.
    pub mu: [T; 2],
    /// Each finger's velocity over the step (world).
    pub finger_velocity: [[T; 2]; 2],
    /// `v~ = v + h M^-1 w_ext`.
    pub v_free: [T; 3],
    /// `diag(M^-1)` times any positive mass scale `s`; the impulses `z` then come out
    /// divided by `s`. The scene uses `s = m`, i.e. `(1, 1, m / J)`: impulses per unit mass,
    /// in m/s like every `w` row, so the LCP's entries are O(1) whatever the rod's mass.
    /// (With the physical `M^-1`, the impulse block scales as `1/m` and the friction-cone
    /// rows do not, and tolerances scaled by `||M||_inf` go blind to one block or the other:
    /// at m = 1e4 kg, f32 let 1e-5 m/s velocity errors through and the rod rocked.)
    pub m_inv: [T; 3],
    /// Step `h`.
    pub h: T,
    /// Gravity `g` (for the penetration-recovery cap).
    pub gravity: T,
}

/// The normal row's stabilisation term `beta(psi)` (module docs): `psi / h` for a gap, the
/// push-out speed capped at `sqrt(2 g |psi|)` for a penetration.
#[must_use]
pub fn normal_bias<T: Real>(gap: T, h: T, gravity: T) -> T {
    let one_step = gap / h;
    if gap >= T::zero() {
        return one_step;
    }
    let cap = -(T::of(2.0) * gravity * -gap).sqrt_libm();
    if one_step > cap { one_step } else { cap }
}

#[inline]
fn dot3<T: Real>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn dot2<T: Real>(a: &[T; 2], b: &[T; 2]) -> T {
    a[0] * b[0] + a[1] * b[1]
}

/// The contact (0 or 1) variable `j` of the size-`n` model belongs to.
const fn owner(n: usize, j: usize) -> usize {
    if j < 2 {
        j
    } else if j < n - 2 {
        friction_directions(n)[j - 2].0
    } else {
        j - (n - 2)
    }
}

/// Assembles the LCP of eq. 18 for the size-`N` model (`N` is 6 or 8).
///
/// The impulse block `A = W^T M^-1 W` is symmetric: its upper triangle is computed and
/// mirrored (10 of the 16 dot products for `N = 6`, 21 of 36 for `N = 8`), which also makes
/// the computed block exactly symmetric.
#[must_use]
pub fn assemble<T: Real, const N: usize>(input: &StepInputs<'_, T>) -> StepLcp<T, N> {
    const { assert!(N == 6 || N == 8, "the meter-stick LCP has size 6 or 8") };
    let dirs = friction_directions(N);
    let n_imp = N - 2;
    let mut columns = [[T::zero(); 3]; N];
    let mut b = SVector::<T, N>::zeros();
    for i in 0..2 {
        let f = &input.frames[i];
        columns[i] = f.wn;
        b[i] = dot3(&f.wn, &input.v_free) - dot2(&f.normal, &input.finger_velocity[i])
            + normal_bias(f.gap, input.h, input.gravity);
    }
    for (k, &(i, sign)) in dirs.iter().enumerate() {
        let f = &input.frames[i];
        let s = if sign > 0 { T::one() } else { -T::one() };
        let j = 2 + k;
        columns[j] = [s * f.wt[0], s * f.wt[1], s * f.wt[2]];
        b[j] = s * (dot3(&f.wt, &input.v_free) - dot2(&f.tangent, &input.finger_velocity[i]));
    }
    let mut a = SMatrix::<T, N, N>::zeros();
    for j in 0..n_imp {
        let mc =
            [columns[j][0] * input.m_inv[0], columns[j][1] * input.m_inv[1], columns[j][2] * input.m_inv[2]];
        for k in j..n_imp {
            let entry = dot3(&mc, &columns[k]);
            a[(j, k)] = entry;
            a[(k, j)] = entry;
        }
    }
    for (k, &(i, _)) in dirs.iter().enumerate() {
        a[(2 + k, sigma_index(N, i))] = T::one();
        a[(sigma_index(N, i), 2 + k)] = -T::one();
    }
    for i in 0..2 {
        a[(sigma_index(N, i), i)] = input.mu[i];
    }
    for i in 0..2 {
        if input.frames[i].active {
            continue;
        }
        for j in 0..N {
            if owner(N, j) != i {
                continue;
            }
            for k in 0..N {
                a[(j, k)] = T::zero();
                a[(k, j)] = T::zero();
            }
            a[(j, j)] = T::one();
            b[j] = T::one();
            columns[j] = [T::zero(); 3];
        }
    }
    StepLcp { lcp: Lcp::new(a, b), columns }
}
