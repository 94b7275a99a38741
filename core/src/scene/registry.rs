//! Every catalogue scene as a runnable scene, written once: [`SceneParams::build`] turns a scene's
//! parameters, a [`Precision`] and an [`LcpLayout`] into the concrete scene (`MeterStick<f32, 6>`,
//! `ThreeFingers<f64, 12>`, ...) and hands it to a [`SceneVisitor`], whose one generic method
//! drives any of them. The one `match` over scene kinds x precisions x layouts is here; a driver
//! (`host-sim`'s run, scene, stress and map commands) names no scene type and no LCP size.
//!
//! **Adding a scene**: its arm in [`SceneParams::build`] (besides its kind and parameters,
//! `kind.rs`).

use super::kind::SceneParams;
use super::{Cylinder, Incline, Ladder, MeterStick, Painleve, Scene, ThreeFingers};
use crate::params::ParamError;
use crate::real::Real;

/// Scalar precision of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize), serde(rename_all = "lowercase"))]
pub enum Precision {
    /// `f32`, as on the microcontroller (the default).
    #[default]
    F32,
    /// `f64`.
    F64,
}

impl Precision {
    /// Both, f32 first.
    pub const ALL: [Self; 2] = [Self::F32, Self::F64];

    /// `f32` or `f64`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::F64 => "f64",
        }
    }

    /// The precision called `name` (`f32`, `f64`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// From the number of bits (32 or 64).
    #[must_use]
    pub const fn from_bits(bits: u32) -> Option<Self> {
        match bits {
            32 => Some(Self::F32),
            64 => Some(Self::F64),
            _ => None,
        }
    }
}

/// The layout of a scene's LCP (`docs/formulation.md`): per contact its normal, its slack and one
/// friction direction (reduced, checked each step with the full form as fallback: the firmware's)
/// or two (full: the paper's form). A scene of `K` contacts solves a `3K x 3K` or `4K x 4K` LCP
/// ([`Self::size`]): 6x6 or 8x8 for two contacts, 3x3 or 4x4 for one, 9x9 or 12x12 for three.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize), serde(rename_all = "lowercase"))]
pub enum LcpLayout {
    /// One friction direction per contact (the default).
    #[default]
    Reduced,
    /// Two friction directions per contact.
    Full,
}

impl LcpLayout {
    /// Both, reduced first.
    pub const ALL: [Self; 2] = [Self::Reduced, Self::Full];

    /// `reduced` or `full`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Reduced => "reduced",
            Self::Full => "full",
        }
    }

    /// The layout called `name` (`reduced`, `full`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|l| l.name() == name)
    }

    /// The LCP's size `N` for a scene of `contacts` contacts: 3 or 4 per contact.
    #[must_use]
    pub const fn size(self, contacts: usize) -> usize {
        contacts
            * match self {
                Self::Reduced => 3,
                Self::Full => 4,
            }
    }
}

/// What a driver does with a scene, whichever it is: [`Self::visit`] receives the concrete scene
/// (scalar `T`, `K` contacts, an `N x N` LCP) from [`SceneParams::build`].
pub trait SceneVisitor {
    /// What the visit gives.
    type Output;

    /// Drives `scene`.
    fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, scene: S) -> Self::Output;

    /// Drives the meter stick, which reports more than [`Scene`] (its meeting's counters) and can
    /// start from another state ([`MeterStick::with_state`]); by default as any scene.
    fn visit_meter_stick<T: Real, const N: usize, const E: usize>(
        self,
        scene: MeterStick<T, N, E>,
    ) -> Self::Output
    where
        Self: Sized,
    {
        self.visit::<T, 2, N, _>(scene)
    }
}

impl SceneParams {
    /// The scene in `precision` and `layout`, keeping `E` switch events, handed to `visitor`.
    ///
    /// # Errors
    /// The core's first complaint about the parameters in `precision` (the scene's `new`).
    pub fn build<const E: usize, V: SceneVisitor>(
        &self,
        precision: Precision,
        layout: LcpLayout,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        match precision {
            Precision::F32 => self.build_in::<f32, E, V>(layout, visitor),
            Precision::F64 => self.build_in::<f64, E, V>(layout, visitor),
        }
    }

    fn build_in<T: Real, const E: usize, V: SceneVisitor>(
        &self,
        layout: LcpLayout,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        use LcpLayout::{Full, Reduced};
        Ok(match (*self, layout) {
            (Self::MeterStick(p), Reduced) => {
                visitor.visit_meter_stick(MeterStick::<T, 6, E>::new(p.cast())?)
            }
            (Self::MeterStick(p), Full) => visitor.visit_meter_stick(MeterStick::<T, 8, E>::new(p.cast())?),
            (Self::Incline(p), Reduced) => visitor.visit::<T, 2, 6, _>(Incline::<T, 6, E>::new(p.cast())?),
            (Self::Incline(p), Full) => visitor.visit::<T, 2, 8, _>(Incline::<T, 8, E>::new(p.cast())?),
            (Self::Ladder(p), Reduced) => visitor.visit::<T, 2, 6, _>(Ladder::<T, 6, E>::new(p.cast())?),
            (Self::Ladder(p), Full) => visitor.visit::<T, 2, 8, _>(Ladder::<T, 8, E>::new(p.cast())?),
            (Self::ThreeFingers(p), Reduced) => {
                visitor.visit::<T, 3, 9, _>(ThreeFingers::<T, 9, E>::new(p.cast())?)
            }
            (Self::ThreeFingers(p), Full) => {
                visitor.visit::<T, 3, 12, _>(ThreeFingers::<T, 12, E>::new(p.cast())?)
            }
            (Self::Cylinder(p), Reduced) => visitor.visit::<T, 1, 3, _>(Cylinder::<T, 3, E>::new(p.cast())?),
            (Self::Cylinder(p), Full) => visitor.visit::<T, 1, 4, _>(Cylinder::<T, 4, E>::new(p.cast())?),
            (Self::Painleve(p), Reduced) => visitor.visit::<T, 1, 3, _>(Painleve::<T, 3, E>::new(p.cast())?),
            (Self::Painleve(p), Full) => visitor.visit::<T, 1, 4, _>(Painleve::<T, 4, E>::new(p.cast())?),
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::scene::SceneKind;

    /// Reports what it was given: the scalar's name, the contacts and the LCP's size.
    struct Sizes;

    impl SceneVisitor for Sizes {
        type Output = (&'static str, usize, usize);
        fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(self, _: S) -> Self::Output {
            (T::NAME, K, N)
        }
    }

    /// Every scene is built in the precision and layout asked for, with its catalogue's contacts
    /// and the LCP size the layout gives them.
    #[test]
    fn every_scene_is_built_as_asked() {
        for kind in SceneKind::ALL {
            for precision in Precision::ALL {
                for layout in LcpLayout::ALL {
                    let built = SceneParams::defaults(kind).build::<0, _>(precision, layout, Sizes).unwrap();
                    let k = kind.contacts();
                    assert_eq!(
                        built,
                        (precision.name(), k, layout.size(k)),
                        "{kind} {precision:?} {layout:?}"
                    );
                }
            }
        }
        let mut p = SceneParams::defaults(SceneKind::Incline);
        assert!(p.set("mass", -1.0));
        assert_eq!(
            p.build::<0, _>(Precision::F32, LcpLayout::Full, Sizes),
            Err(ParamError::NotPositive("mass"))
        );
    }
}
