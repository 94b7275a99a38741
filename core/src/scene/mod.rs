//! The meter-stick scene: a planar rod on two finger contacts, stepped by an LCP per step.
//!
//! # Model (Leong & Lv, sections III-V; `shared/design/formulation.md`)
//! Configuration `q = (x, y, theta)`, velocity `v = (vx, vy, omega)`,
//! `M = diag(m, m, J)`, `J = m L^2 / 12`. For each finger tip `f`, in the rod frame
//! `l = R(theta)^T (f - com)`; the tip is under the rod when `|l.x| <= L/2`, with gap
//! `psi_n = -l.y - t/2`. Contact point `r = R (l.x, -t/2)`, normal `n = R (0, 1)`,
//! tangent `d = R (1, 0)`, wrench columns `W_n = [n; r x n]`, `W_t = [d; r x d]`
//! ([`ContactFrame`]).
//!
//! One step of `h` (eqs. 13-18, impulse-velocity form):
//!
//! ```text
//! M (v+ - v) = h w_ext + W_n p_n + W_f p_f
//! rho_n = W_n^T v+ - n.u_f + psi_n / h   >= 0  _|_ p_n   >= 0
//! rho_f = W_f^T v+ - D^T u_f + E sigma    >= 0  _|_ p_f   >= 0
//! s     = U p_n - E^T p_f                 >= 0  _|_ sigma >= 0
//! q+    = q + h v+
//! ```
//!
//! eliminated to an LCP in `z = (p_n, p_f, sigma)` ([`assemble`](mod@assemble)) and solved by
//! [`crate::lcp::Lemke`], warm-started from the previous step's basis.
//!
//! **Friction.** Each contact uses `mu_s` while its previous mode was sticking (or
//! separated) and `mu_k` while it was sliding. After a step, a contact with a normal
//! impulse sticks when its tangential slip speed `|d . (u_f - v_point)|` is at most
//! [`SceneParams::stick_speed`] (default `1e-5` m/s, i.e. 1e-4 of the slow finger speed),
//! and slides otherwise. Before the first step the same rule is applied to the prescribed
//! motion at `t = 0`: finger 1 starts at full speed under a resting rod, so it is sliding
//! (`mu_k`) from the start and finger 2 sticks. (Starting both as sticking gave finger 1
//! `mu_s` in step 1, which dragged the rod when `mu_s N_1 > mu_s N_2` and, once finger 2 had
//! slipped, left both on `mu_k`: a start artefact whose size depended on `h` through
//! `stick_speed`, found by the convergence study of `host-sim report`.)
//!
//! **Sizes.** `N = 8` is the paper's form (two friction directions per finger).
//! `N = 6` keeps only the direction each finger can use while finger 1 moves toward
//! finger 2. After each 6x6 step the dropped rows are checked; when one would be negative
//! the step is re-solved with the 8x8 form and [`StepReport::reduced_check_failed`] says
//! so; [`RunStats::reduced_check_fired`] counts it.
//!
//! **Outcome.** [`Outcome::Balanced`] when the fingers met (finger 1 stopped at
//! `finger_width` from finger 2) with the centre of mass between them and the rod stayed on
//! both for `hold_time`; [`Outcome::Fell`] when `|theta| > tilt_limit`, the centre of mass
//! dropped more than `drop_limit`, or no finger is under the rod any more.
//!
//! # Example
//! ```
//! use meterstick_core::scene::{Outcome, Scene6, SceneParams};
//!
//! let mut params = SceneParams::<f32>::paper();
//! params.finger1_x = -0.35; // asymmetric start
//! let mut scene = Scene6::<f32>::new(params).expect("valid parameters");
//! let first = scene.step().expect("the run has just started");
//! assert!(first.error.is_none());
//! assert_eq!(scene.run(|_| {}), Outcome::Balanced);
//! let meeting = scene.meeting().expect("the fingers met");
//! assert!(meeting.com_offset.abs() < 0.003); // the fingers stop 1 cm apart
//! ```

pub mod assemble;
mod contact;
mod params;
mod sim;

pub use contact::{ContactFrame, ContactMode, Slide};
pub use params::{ParamError, SceneParams};
pub use sim::{Meeting, Outcome, RodState, RunStats, Scene, Scene6, Scene8, StepReport, SwitchEvent};
