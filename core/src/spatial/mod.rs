//! Three dimensions: a rigid body with six degrees of freedom on a plane, with **isotropic**
//! Coulomb friction (feature `spatial`; a planar build compiles none of it). World axes: `z` up.
//!
//! # The step
//!
//! The paper's time-stepping (velocity-level impulses, Stewart & Trinkle, Anitescu & Potra), in
//! space. A body of mass `m` and principal moments `I` (its own frame) is at `x`, turned by the
//! unit quaternion `q`, moving at `v` and `omega` (world axes). Over a step `h`:
//!
//! 1. The free velocities: `v~ = v + h g`, `omega~ = omega` (no torque but the contact's).
//! 2. The contact (a point at `r` from the centre of mass, on a plane of unit normal `n`, within
//!    the margin): its velocity `u~ = v~ + omega~ x r`, its normal row `u_n = n . u~ + b` (`b`
//!    the gap's bias, as the planar model's `normal_bias`) and its slip `u_t`, the rest of `u~`.
//!    Per unit mass, an impulse `p` changes the point's velocity by `W p`, `e . W f = e . f + m (r
//!    x e) . I_w^-1 (r x f)`.
//! 3. **Friction along the slip.** Coulomb's law in space: `|p_t| <= mu p_n`, and a sliding
//!    contact's friction opposes its slip, `p_t = -mu p_n s / |s|` (`s` the slip after the step).
//!    A polyhedral cone (`k` fixed directions) bends a sliding body's path toward them; here the
//!    contact keeps one friction line `d`, chosen along the slip, and the paper's LCP in the
//!    unknowns `(p_n, p_+d, p_-d, sigma)`:
//!
//!    ```text
//!    w = [ W_nn  W_nd  -W_nd  0 ] z + [ u_n  ]     z >= 0, w >= 0, z . w = 0
//!        [ W_dn  W_dd  -W_dd  1 ]     [ u_d  ]
//!        [-W_dn -W_dd   W_dd  1 ]     [ -u_d ]
//!        [ mu    -1     -1    0 ]     [ 0    ]
//!    ```
//!
//!    solved by Lemke's method and verified ([`crate::lcp`]). The answer holds when the slip after
//!    the step has no component across `d` (within `256 eps` of the step's velocity scale): its
//!    friction then lies on the slip's line, opposing it (the LCP's complementarity) or stopping it.
//!    Otherwise `d` turns to the new slip (a saturated contact) or to the tangential impulse that
//!    would stop the slip (a sticking one) and the LCP is solved again, at most
//!    [`MAX_DIRECTIONS`] times ([`StepError::ConeNotConverged`]). Where the contact's tangential
//!    response is isotropic and uncoupled from its normal (a sphere; a point under the centre of
//!    mass) the first direction, the free slip's, holds: one LCP a step. Every answer is checked
//!    against the circular cone ([`ContactReport::cone_residual`], in units of `mu p_n`).
//! 4. `v+ = v~ + p`, `omega+ = omega~ + m I_w^-1 (r x p)`, `x+ = x + h v+`. **The gyroscopic
//!    term**: between the impulses no torque acts, so the angular momentum `L = I_w(q) omega+`
//!    (world axes) is the body's all through the step, and its angular velocity at any
//!    orientation `q'` is `I_w(q')^-1 L`. The turn is taken at the midpoint's: `q_half = exp(h
//!    omega+ / 4) q`, `q+ = exp(h I_w(q_half)^-1 L / 2) q`, renormalised (second order), and
//!    `omega` after the step is `I_w(q+)^-1 L`. A free body keeps `L` to round-off; its energy
//!    drifts by `O(h^2)` (a box tumbling at 10 rad/s, `h = 1 ms`: 1.7e-6 of itself over 1e5 steps
//!    in f64). The explicit term `h omega x I omega` feeds energy into such a box, an implicit one
//!    takes it out (7 % over the same run, measured) and moves `L`.
//!
//! `mu` is `mu_k` after a sliding step and `mu_s` otherwise, as in the paper.
//!
//! # Checked against (tests/tests/spatial.rs)
//!
//! - A billiard ball struck with any spin rolls from `t = 2 |u0| / (7 mu g)` at `v = (5 v0 + 2 R
//!   omega0 x z) / 7`: the step's friction keeps the slip's direction, so the ball's velocity at
//!   rolling is the closed form's to round-off; its spin about `z` persists (a point contact has no
//!   drilling friction).
//! - A puck launched across a level table in any heading stops at the same distance along it.
//! - A puck launched horizontally across an incline with `mu = tan(angle)` tends to half its
//!   launch speed.
//! - A free box tumbling at 10 rad/s keeps its angular momentum and its energy over 1e5 steps.
//!
//! Scope: one body, one point of contact on one plane. Several contacts (a disc's base, a rod
//! on two fingers, a stack) and the front ends are to come (`CHANGELOG.md`).

mod algebra;
mod body;
mod stepper;

pub use algebra::{Quaternion, Vector, about, identity, rotate};
pub use body::{Body, State};
pub use stepper::{
    ContactReport, MAX_DIRECTIONS, Mode, Plane, Settings, Shape, StepError, StepReport, Stepper,
};
