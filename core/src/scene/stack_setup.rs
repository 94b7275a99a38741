//! [`StackSetup`]: a stack's parameters and its number of blocks, the planar stack's
//! ([`crate::multibody::scenes::Stack`]) and the stack in three dimensions'
//! (`crate::scene::spatial::Stack3d`) alike.

use crate::params::ParamError;
use crate::real::Real;

/// The parameters of a stack of blocks, whose rules depend on the number of blocks (the overhang
/// below twice that number).
pub trait StackedParams: Copy + Default + PartialEq {
    /// The field names, in declaration order (the `params!` struct's `NAMES`).
    const NAMES: &'static [&'static str];

    /// The rules for `blocks` blocks, checked in f64 and in `T`.
    ///
    /// # Errors
    /// The core's first complaint.
    fn validate_as<T: Real>(&self, blocks: usize) -> Result<(), ParamError>;

    /// The field called `name`.
    fn get(&self, name: &str) -> Option<f64>;

    /// Sets the field called `name`; `false` when there is none.
    fn set(&mut self, name: &str, value: f64) -> bool;
}

/// Implements [`StackedParams`] for a `params!` struct with `validate(&self, blocks)`.
macro_rules! stacked_params {
    ($params:ident) => {
        impl StackedParams for $params<f64> {
            const NAMES: &'static [&'static str] = $params::<f64>::NAMES;

            fn validate_as<T: Real>(&self, blocks: usize) -> Result<(), ParamError> {
                self.validate(blocks)?;
                self.cast::<T>().validate(blocks)
            }

            fn get(&self, name: &str) -> Option<f64> {
                $params::get(self, name)
            }

            fn set(&mut self, name: &str, value: f64) -> bool {
                $params::set(self, name, value)
            }
        }
    };
}

#[cfg(feature = "scenes-multibody")]
use crate::multibody::scenes::StackParams;
#[cfg(feature = "scenes-multibody")]
stacked_params!(StackParams);
#[cfg(feature = "scenes-stack-3d")]
use crate::scene::spatial::Stack3dParams;
#[cfg(feature = "scenes-stack-3d")]
stacked_params!(Stack3dParams);

/// A stack's parameters `P` and its number of blocks (the `B` of its scene: 2 or 3 here), a
/// number as every field is so that it is set and refused by name like them (`blocks` 2.5 is out
/// of range).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StackSetup<P> {
    /// The blocks: 2 or 3 (default 3, `docs/scenes.md`).
    pub blocks: f64,
    /// The rest.
    pub params: P,
}

impl<P: StackedParams> Default for StackSetup<P> {
    fn default() -> Self {
        Self { blocks: 3.0, params: P::default() }
    }
}

impl<P: StackedParams> StackSetup<P> {
    /// The blocks as a count, when it is 2 or 3.
    #[must_use]
    pub fn block_count(&self) -> Option<usize> {
        [2_u8, 3].into_iter().find(|&n| self.blocks.to_bits() == f64::from(n).to_bits()).map(usize::from)
    }

    /// The stack's rules ([`StackedParams::validate_as`]) in f64 and in `T`, and 2 or 3 blocks.
    ///
    /// # Errors
    /// `NonFinite("blocks")`, `OutOfRange("blocks")`, or the core's first complaint.
    pub fn validate_as<T: Real>(&self) -> Result<(), ParamError> {
        if !self.blocks.is_finite() {
            return Err(ParamError::NonFinite("blocks"));
        }
        let blocks = self.block_count().ok_or(ParamError::OutOfRange("blocks"))?;
        self.params.validate_as::<T>(blocks)
    }

    pub(super) fn get(&self, field: &str) -> Option<f64> {
        if field == "blocks" { Some(self.blocks) } else { self.params.get(field) }
    }

    pub(super) fn set(&mut self, field: &str, value: f64) -> bool {
        if field == "blocks" {
            self.blocks = value;
            true
        } else {
            self.params.set(field, value)
        }
    }
}

/// `blocks`, then the `M - 1` names of `names` (a stack's field names, [`StackSetup`]'s order).
pub(super) const fn with_blocks<const M: usize>(names: &[&'static str]) -> [&'static str; M] {
    assert!(names.len() + 1 == M, "M is one more than the names");
    let mut out = ["blocks"; M];
    let mut i = 0;
    while i < names.len() {
        out[i + 1] = names[i];
        i += 1;
    }
    out
}
