//! Three dimensions: a rigid body with six degrees of freedom touching a plane at up to eight
//! points, with **isotropic** Coulomb friction (feature `spatial`; a planar build compiles none of
//! it). World axes: `z` up.
//!
//! # The step
//!
//! The paper's time-stepping (velocity-level impulses, Stewart & Trinkle, Anitescu & Potra), in
//! space. A body of mass `m` and principal moments `I` (its own frame) is at `x`, turned by the
//! unit quaternion `q`, moving at `v` and `omega` (world axes). Over a step `h`:
//!
//! 1. The free velocities: `v~ = v + h g`, `omega~ = omega` (no torque but the contact's).
//! 2. Each contact `i` (a point at `r_i` from the centre of mass, on a plane of unit normal `n`,
//!    within the margin): its velocity `u~ = v~ + omega~ x r_i`, its normal row `u_n = n . u~ + b`
//!    (`b` the gap's bias, as the planar model's `normal_bias`) and its slip `u_t`, the rest of
//!    `u~`. Per unit mass, an impulse `p` at contact `j` changes contact `i`'s velocity by `W_ij
//!    p`, `e . W_ij f = e . f + m (r_i x e) . I_w^-1 (r_j x f)`.
//! 3. **Friction along the slip.** Coulomb's law in space: `|p_t| <= mu p_n`, and a sliding
//!    contact's friction opposes its slip, `p_t = -mu p_n s / |s|` (`s` the slip after the step).
//!    A polyhedral cone (`k` fixed directions) bends a sliding body's path toward them; here each
//!    contact keeps one friction line `d`, chosen along its slip (its free slip's direction; one
//!    within 16 times the step's round-off points anywhere, and a support's line then starts along
//!    the body's axis), and the paper's LCP in the
//!    unknowns `(p_n, p_+d, p_-d, sigma)` of every contact in turn (`N = 4 K`), one contact's
//!    block (the blocks between contacts are the same with `W_ij`, and zero in `sigma`):
//!
//!    ```text
//!    w = [ W_nn  W_nd  -W_nd  0 ] z + [ u_n  ]     z >= 0, w >= 0, z . w = 0
//!        [ W_dn  W_dd  -W_dd  1 ]     [ u_d  ]
//!        [-W_dn -W_dd   W_dd  1 ]     [ -u_d ]
//!        [ mu    -1     -1    0 ]     [ 0    ]
//!    ```
//!
//!    solved by Lemke's method and verified ([`crate::lcp`]), the last answer's basis first solved
//!    in the contacts' normal impulses and sticking frictions alone (`direct`'s module docs) and
//!    verified on the whole problem as Lemke's own warm answer is. The answer holds when every loaded
//!    contact's slip after the step has no component across its `d` (within `256 eps` of the
//!    step's velocity scale, the largest free slip and `g h`, and at least `8 eps` of the largest
//!    contact's `|v~| + |omega~| |r_i|`: a slip is summed from those terms, so its round-off is
//!    of their size, not its own, about `3 eps` of them; a ball near rolling slips at 1e-4 m/s on
//!    a surface turning at 1 m/s, and no turn of its line meets a finer test): its friction then lies on the slip's line, opposing it (the LCP's
//!    complementarity) or stopping it. Otherwise the lines turn together by one step of Newton's
//!    method on those conditions, the LCP's modes held: each loaded contact's normal row stays
//!    closed and its normal impulse moves with the friction (`W` couples the two off the centre of
//!    mass), a sliding contact's line turns by an angle (turning it turns its friction and the
//!    direction its condition is read in; its friction's size follows its normal impulse), a
//!    sticking one's friction moves toward the tangential impulse that stops its slip, the
//!    velocities moving by `W` of the impulses' changes (a linear system of at most `3 K`
//!    unknowns); the LCP is solved again, at most [`MAX_DIRECTIONS`] times
//!    ([`StepError::ConeNotConverged`]). A contact counts as sliding there when its friction is on
//!    the cone's edge (within `1e-3`) and it slips along its line beyond round-off, or its
//!    friction is the edge's to `64 eps`: one whose slip the LCP stopped just inside the edge
//!    sticks, and modelled as sliding (its condition's `d . s` zero) its turn is singular and the
//!    tries converge only linearly. **A restart.** Newton's step holds the LCP's modes; where
//!    those of the answer differ (a rod's yaw stopping about one finger: that finger's free slip
//!    round-off's, its first line anywhere, the LCP sticking the others along theirs, each try
//!    trading which one slides), the tries wander. Every fourth try, when the worst slip across a
//!    line not held has not shrunk fourfold in the last one, the lines start again from the
//!    cone's own problem, solved roughly by projected Gauss-Seidel (256 sweeps from the try's
//!    impulses: each contact's normal impulse closing its row, then the friction that stops its
//!    slip held to the disc `|p_t| <= mu p_n`): each line along its contact's friction, whose
//!    modes are the answer's, and Newton's turns go on from there. From a restart on, a contact
//!    slipping within the stick speed reads sticking, as its report does (the cone alone holds
//!    it, its slip's direction is not asked for), and a sliding one so slow keeps its line (its
//!    friction following its load): at the stick/slip edge the slip tends to zero as the tries
//!    go, its direction's condition degenerate (Newton's step halving it per try). Where every contact's tangential response is isotropic
//!    and uncoupled from its normal (a sphere; a point under the centre of mass) the first lines,
//!    the free slips', hold: one LCP a step; a lone sticking contact's conditions are linear,
//!    one turn meets them; a box's corner sliding and spinning needs two to six, a tripod two to four.
//!    Every answer is checked against the circular cone ([`SpatialContactReport::cone_residual`], in
//!    units of `mu p_n`, or the LCP's own verification scale where the cone is far smaller than
//!    it: a light load at the edge of sticking). A sliding slip `s` is known to the step's
//!    velocity round-off (the `256 eps` above), its direction to that over `|s|`: across the slip
//!    the friction is held to `mu p_n` times that angle besides, along it to `mu p_n` times half
//!    the angle's square (the edge's `1 - cos`).
//!
//!    **The baseline** ([`FrictionCone::Pyramid`]): the pyramid of LCP engines, `k` directions
//!    fixed in the plane, one LCP a step (Stewart & Trinkle). Its friction points at the pyramid's
//!    nearest edge, not against the slip; its circular residual is reported, only `|p_t| <= mu
//!    p_n` is a failure.
//!
//!    **The load.** Up to three points (not in a line) carry a load the step decides. Four or more
//!    points of a flat base leave it open, and the LCP would answer with one of its vertices; the
//!    core takes the load of least 2-norm (`docs/formulation.md`, "The load: the least norm"), the
//!    one elasticity gives equally stiff points (Menabrea): with every touching point sliding, each
//!    point's friction `mu p_n` against its slip, the normal impulses of least norm that give the
//!    body's motion out of the plane (`n . v` and the turn about the plane's two axes), `p_n >= 0`
//!    (`super::load`'s module): uniform under a centred base whose centre of mass is in its plane,
//!    affine in the points' positions when the friction's moment tips it. A base sliding as a whole
//!    (every point touching and slipping before the step) is stepped that way without the
//!    contacts' LCP (whose degenerate rows, four or more coplanar normals, end Lemke's method on a
//!    ray at some orientations); its motion out of the plane is the one that closes every point's
//!    normal row. Otherwise the LCP's answer is taken and, when four or more points touch and all
//!    slide after it, its load replaced by the least-norm one. Either way the directions are set to
//!    the slips until they agree (16 tries) and every answer is verified (the motion
//!    out of the plane, the circular cone, `p_n >= 0`). A base with a sticking point keeps the
//!    LCP's load (a vertex).
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
//! - A ring of four to eight feet sliding without turning carries the least-norm (Menabrea) load,
//!   uniform when its centre of mass is in the feet's plane (`tests/tests/flat_base.rs`).
//! - A tripod sliding without turning carries the loads its balance of forces and moments gives
//!   (`tests/tests/spatial_contacts.rs`); spinning as it slides, it stops sliding and spinning in
//!   the same step (Farkas, Bartels, Unger & Wolf, PRL 90, 248302 (2003)), and the same launch
//!   turned about the vertical ends turned.
//!
//! Scope: one body, on one fixed plane ([`SpatialStepper`]) or on support points carried under its
//! flat lower face ([`SupportedStepper`], `supported`'s module docs: fingers lying across a rod;
//! the same step, each slip the body point's velocity less the support's); and blocks resting on
//! each other over a table's edge ([`BlockStack`], `stack`'s module docs: each contact pushes its
//! upper block and the one beneath it back, the Delassus operator over both, `space`'s module
//! docs; the contacts of a face on a face, [`face_patch`]). Their scenes (a puck, a billiard ball,
//! a curling stone, the meter stick, the stack) are `crate::scene::spatial`'s (feature
//! `scenes-spatial`).

mod algebra;
mod body;
mod direct;
mod face_patch;
mod friction;
mod load;
mod report;
mod space;
mod stack;
mod stepper;
mod supported;

pub use crate::StepError;
pub use algebra::{Quaternion, Vector, about, cross, dot, identity, norm, perpendicular, rotate};
pub use body::{Body, State};
pub use face_patch::{Beneath, FaceContact, FacePatch, PatchOverflow, SCRATCH, face_patch};
pub use report::{MAX_DIRECTIONS, Mode, SpatialContactReport, SpatialStepReport};
pub use stack::{BlockStack, PATCH_POINTS, SlotContacts, StackStepReport};
pub use stepper::{FrictionCone, OneContact, Plane, SpatialSettings, SpatialShape, SpatialStepper};
pub use supported::{FaceTouch, Finger, LowerFace, SupportPoint, SupportedStepper};
