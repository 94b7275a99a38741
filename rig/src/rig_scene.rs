//! [`RigScene`]: what the rig of several bodies ([`crate::MultibodyRig`]) needs of its scene
//! beyond the core's [`MultibodyScene`]: to be built, and validated, from its parameters, and the
//! step those ask for.

use meterstick_core::ParamError;
use meterstick_core::multibody::scenes::{MultibodyScene, Stack, StackParams};

/// A scene of several bodies in f32 (`B` bodies, `P` resting pairs, each with four candidate
/// contacts) that a [`crate::MultibodyRig`] can show.
pub trait RigScene<const B: usize, const P: usize>: MultibodyScene<f32, B, P> + Sized {
    /// The scene's parameters.
    type Params: Copy + core::fmt::Debug;

    /// The scene at its start, from `params` validated by the core (the scene's `new`).
    ///
    /// # Errors
    /// The core's first complaint about `params`.
    fn build(params: Self::Params) -> Result<Self, ParamError>;

    /// The time step `params` ask for (s): the rig ticks one step per timer period.
    fn step_of(params: &Self::Params) -> f32;
}

/// The stack of `B` blocks over a table's edge (`docs/scenes.md`, "stack"): pair 0 the table and
/// the bottom block, pair `i` blocks `i - 1` and `i` (counted from the bottom).
impl<const B: usize, const N: usize> RigScene<B, B> for Stack<f32, B, N> {
    type Params = StackParams<f32>;

    #[inline]
    fn build(params: StackParams<f32>) -> Result<Self, ParamError> {
        Self::new(params)
    }

    #[inline]
    fn step_of(params: &StackParams<f32>) -> f32 {
        params.step
    }
}
