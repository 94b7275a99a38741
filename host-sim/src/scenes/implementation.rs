//! Who computes a run ([`Implementation`]) and its label, the LCP's size its scene gives
//! ([`ImplementationOf`]).

use std::fmt;

use serde::Serialize;

use super::{LcpLayout, Precision, SceneKind};

/// Who computed a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Implementation {
    /// `meterstick-core` in a precision and an LCP layout.
    Core(Precision, LcpLayout),
    /// The independent f64 reference (`crate::reference`, enumeration of the full form).
    Reference,
}

impl Implementation {
    /// The firmware's configuration: f32, reduced layout.
    pub const CORE_F32_REDUCED: Self = Self::Core(Precision::F32, LcpLayout::Reduced);
    /// Core, f32, full layout.
    pub const CORE_F32_FULL: Self = Self::Core(Precision::F32, LcpLayout::Full);
    /// Core, f64, full layout.
    pub const CORE_F64_FULL: Self = Self::Core(Precision::F64, LcpLayout::Full);

    /// The precision it computes in.
    #[must_use]
    pub const fn precision(self) -> Precision {
        match self {
            Self::Core(p, _) => p,
            Self::Reference => Precision::F64,
        }
    }
}

/// The label for a two-contact scene (the report's, the stress grid's columns); a run of any scene
/// is labelled by [`Implementation::of_scene`].
impl fmt::Display for Implementation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&ImplementationOf { implementation: *self, contacts: 2 }, f)
    }
}

impl Serialize for Implementation {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl Implementation {
    /// This implementation as it runs a scene of `kind`, whose contacts set its LCP's size.
    #[must_use]
    pub const fn of_scene(self, kind: SceneKind) -> ImplementationOf {
        ImplementationOf { implementation: self, contacts: kind.contacts() }
    }
}

/// An [`Implementation`] running a scene of `contacts` contacts: its label names the LCP's size,
/// `core f32 6x6` for a two-contact scene in the reduced layout, `core f32 3x3` for one contact,
/// `reference f64 8x8` (the reference solves the full form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ImplementationOf {
    /// Who computed the run.
    pub implementation: Implementation,
    /// The scene's contacts.
    pub contacts: usize,
}

impl fmt::Display for ImplementationOf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.implementation {
            // A scene of several bodies: its LCP's size is its own (`host-sim scene` says it).
            Implementation::Core(p, _) if self.contacts == 0 => write!(f, "core {}", p.name()),
            Implementation::Reference if self.contacts == 0 => f.write_str("reference f64"),
            Implementation::Core(p, layout) => {
                write!(f, "core {} {n}x{n}", p.name(), n = layout.size(self.contacts))
            }
            Implementation::Reference => {
                write!(f, "reference f64 {n}x{n}", n = LcpLayout::Full.size(self.contacts))
            }
        }
    }
}

impl Serialize for ImplementationOf {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run's label names the LCP its scene's contacts give: 3 per contact reduced, 4 full.
    #[test]
    fn labels_name_the_scenes_lcp_size() {
        let label = |i: Implementation, kind| i.of_scene(kind).to_string();
        assert_eq!(label(Implementation::CORE_F32_REDUCED, SceneKind::MeterStick), "core f32 6x6");
        assert_eq!(label(Implementation::CORE_F32_REDUCED, SceneKind::Cylinder), "core f32 3x3");
        assert_eq!(label(Implementation::CORE_F64_FULL, SceneKind::Painleve), "core f64 4x4");
        assert_eq!(label(Implementation::CORE_F32_FULL, SceneKind::ThreeFingers), "core f32 12x12");
        assert_eq!(label(Implementation::Reference, SceneKind::ThreeFingers), "reference f64 12x12");
        assert_eq!(
            label(Implementation::Reference, SceneKind::Ladder),
            Implementation::Reference.to_string()
        );
    }
}
