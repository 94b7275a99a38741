//! Linear complementarity problems and Lemke's method.
//!
//! # The problem
//! Given `M` (`N x N`) and `q` (`N`), find `z` such that
//!
//! ```text
//! w = M z + q,   z >= 0,   w >= 0,   z . w = 0            (paper, eq. 1)
//! ```
//!
//! Every time step of the meter-stick scene is one such problem (paper, eq. 18), so the
//! solver is statically sized (`const N: usize`, checked `1 <= N <= 64` at compile time),
//! generic over the scalar ([`crate::Real`]: `f32` on the microcontroller, `f64` on the
//! host), and keeps everything in fixed arrays on the stack: for `N = 6` in f32 the
//! tableau is 6 x 14 floats (336 bytes). Its sets of rows (the [`Basis`], the ties of the ratio
//! test) are bits in `WORDS` 32-bit words, a const parameter that is 1 by default, for
//! `N <= 32`, and 2 for `N <= 64` (`Lemke<T, N, 2>`, `Basis<N, 2>`): one word costs what a `u32`
//! mask costs, and no set needs 64-bit arithmetic, which takes several instructions on a 32-bit
//! core.
//!
//! # The algorithm
//! Lemke's complementary pivoting, as in the paper's reference \[4\] (P. L. Fackler and
//! M. J. Miranda, `lemke.m`, 1997) and Cottle, Pang and Stone, *The Linear Complementarity
//! Problem* (1992), section 4.4. An artificial variable `z0` with covering vector `d = e`
//! is added, `w - M z - d z0 = q`, and the tableau `[I, -M, -d | q]` starts from the basis
//! of all `w`:
//! 1. if `q >= 0`, `z = 0` is the solution, with zero pivots;
//! 2. otherwise `z0` enters and the row with the most negative `q_i` leaves, which makes
//!    the basis feasible;
//! 3. the complement of the variable that just left enters; a minimum-ratio test picks
//!    the row that leaves; repeat until `z0` leaves (a solution) or the entering column has
//!    no positive entry (ray termination: no solution found).
//!
//! **Lexicographic ratio test.** Ties in the ratio test (degenerate problems) are broken
//! by comparing the rows of `[B^-1 q | B^-1] / a_i` lexicographically, which keeps every
//! row lexicographically positive and so no basis repeats: Lemke's method cannot cycle
//! (Cottle-Pang-Stone, section 4.9; Eaves, "The linear complementarity problem",
//! *Management Science* 17, 1971). The artificial variable leaves whenever it is among
//! the tied rows, so the method stops at the first solution it reaches.
//!
//! **Tolerances**, all scaled to the problem and to the scalar's `eps`:
//! * pivot: an entry of the entering column counts as positive when it exceeds
//!   `N eps max_i |a_i|`;
//! * ties: ratios within `N eps max(theta, ||rhs||_inf / max|a|)` of the minimum tie;
//!   lexicographic comparisons use `N eps` times the column's magnitude;
//! * verification ([`verify`]): normalised residual at most `256 N eps`.
//!
//! **Pivot cap.** [`default_max_pivots`]`(N) = 2^min(N,10) + 4N` (Murty's example needs
//! `2^N - 1`); reaching it is the error [`LcpError::MaxPivots`], never a silent stop.
//!
//! **Warm start.** [`Lemke::solve_warm`] takes a complementary [`Basis`] (the previous
//! time step's) and first solves it directly: `M_aa z_a = -q_a` by Gaussian elimination with
//! partial pivoting over the basis' rows and columns, `z = 0` elsewhere; when `z_a >= 0`,
//! `w >= 0` outside `a` and the answer verifies, that is the solution, with zero pivots.
//! Otherwise the basis is factorised by Gauss-Jordan elimination in the tableau and Lemke's
//! method runs from it with covering vector `d = B e` (the artificial column is `-e` in the new
//! coordinates), and if that does not end in a verified solution, from the cold start.
//! [`Lemke::solve_from_basis`] skips the direct solve, for a caller that has just tried the
//! basis itself (the planar stepper, in the body's coordinates: `docs/formulation.md`, "Solving
//! a step").
//!
//! **Verification.** Every solution returned has passed [`verify`] against the original
//! `M` and `q`; anything else is an [`LcpError`]. Nothing in this module panics.
//!
//! # What is guaranteed
//! * `M` a **P-matrix** (all principal minors positive, e.g. positive definite): a unique
//!   solution exists for every `q` and Lemke's method finds it (Cottle-Pang-Stone 4.4.1).
//! * `M` **copositive-plus** (e.g. positive semidefinite): Lemke's method finds a solution
//!   whenever the problem is feasible; ray termination proves it infeasible (CPS 4.4.9).
//! * Other matrices (the meter-stick LCP, whose friction block `[U, -E^T, 0]` is not
//!   copositive-plus, among them): the method may stop in a ray although a solution
//!   exists. The solver then reports [`LcpError::Ray`]; it never guesses.

mod basis;
pub(crate) mod elimination;
mod error;
mod lemke;
mod problem;
mod rows;
mod tableau;
mod verify;

pub use basis::Basis;
pub use error::LcpError;
pub use lemke::{LcpSolution, Lemke, default_max_pivots, default_pivot_floor};
pub use problem::Lcp;
#[cfg(feature = "spatial")]
pub(crate) use problem::Scales;
pub use verify::{Verification, default_tolerance, is_solution, verify};

#[cfg(test)]
mod tests;
