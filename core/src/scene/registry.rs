//! Every catalogue scene as a runnable scene, written once: [`SceneParams::build`] turns a scene's
//! parameters, a [`Precision`] and an [`LcpLayout`] into the concrete scene (`MeterStick<f32, 6>`,
//! `ThreeFingers<f64, 12>`, ...) and hands it to a [`SceneVisitor`], whose one generic method
//! drives any of them; [`AnyScene`] holds any of them in place for a driver that keeps a run between
//! calls (the browser page). The scenes x layouts are one table here (`scene_table!`); a driver
//! (`host-sim`'s run, scene, stress and map commands, the page) names no scene type and no LCP
//! size.
//!
//! **Adding a scene**: its two rows in the `scene_table!` table (besides its kind and parameters,
//! `kind.rs`).

#[cfg(feature = "scenes-k3")]
use super::ThreeFingers;
use super::kind::SceneParams;
#[cfg(feature = "scenes-k1")]
use super::{Cylinder, Painleve};
#[cfg(feature = "scenes-k2")]
use super::{Incline, Ladder};
use super::{MeterStick, Scene};
#[cfg(any(
    feature = "scenes-k1",
    feature = "scenes-k2",
    feature = "scenes-k3",
    feature = "scenes-multibody"
))]
use crate::RunStats;
#[cfg(feature = "scenes-multibody")]
use crate::multibody::scenes::{BlockOnBlock, DiscOnBoard, MultibodyScene, Stack2, Stack3, Tablecloth};
use crate::params::ParamError;
use crate::real::Real;
#[cfg(any(
    feature = "scenes-k1",
    feature = "scenes-k2",
    feature = "scenes-k3",
    feature = "scenes-multibody"
))]
use {super::Outcome, super::kind::MAX_MEASURES};

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

/// What a driver does with a scene of several bodies ([`SceneKind::is_multibody`]), whichever it
/// is: [`Self::visit`] receives the concrete scene (scalar `T`, `B` bodies, `P` resting pairs)
/// from [`SceneParams::build_multibody`]. A driver that has no such visitor refuses these scenes
/// by their kind before anything runs.
///
/// [`SceneKind::is_multibody`]: super::SceneKind::is_multibody
#[cfg(feature = "scenes-multibody")]
pub trait MultibodyVisitor {
    /// What the visit gives.
    type Output;

    /// Drives `scene`.
    fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
        self,
        scene: S,
    ) -> Self::Output;
}

#[cfg(feature = "scenes-multibody")]
impl SceneParams {
    /// A scene of several bodies in `precision`, handed to `visitor` (its LCP is the full form:
    /// no layout to choose). Generic: a build that never calls it links none of the multibody
    /// core.
    ///
    /// # Errors
    /// The core's first complaint about the parameters in `precision` (the scene's `new`);
    /// `OutOfRange("scene")` for a scene of one body ([`Self::build`] builds those), and
    /// `OutOfRange("blocks")` for a stack of other than 2 or 3 blocks.
    pub fn build_multibody<V: MultibodyVisitor>(
        &self,
        precision: Precision,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        match precision {
            Precision::F32 => self.build_multibody_in::<f32, V>(visitor),
            Precision::F64 => self.build_multibody_in::<f64, V>(visitor),
        }
    }

    /// [`Self::build_multibody`] with the precision a type.
    pub(crate) fn build_multibody_in<T: Real, V: MultibodyVisitor>(
        &self,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        match *self {
            Self::BlockOnBlock(p) => visit_built(|| BlockOnBlock::<T>::new(p.cast()), visitor),
            Self::Tablecloth(p) => visit_built(|| Tablecloth::<T>::new(p.cast()), visitor),
            Self::Stack(s) => match s.block_count() {
                Some(2) => visit_built(|| Stack2::<T>::new(s.params.cast()), visitor),
                Some(3) => visit_built(|| Stack3::<T>::new(s.params.cast()), visitor),
                _ => Err(ParamError::OutOfRange("blocks")),
            },
            Self::DiscOnBoard(p) => visit_built(|| DiscOnBoard::<T>::new(p.cast()), visitor),
            _ => Err(ParamError::OutOfRange("scene")),
        }
    }
}

/// The scene `build` makes, handed to `visitor`, in a frame of its own: the stack holds the one
/// scene built, not a slot for each scene [`SceneParams::build_multibody`] can build (each scene is
/// kilobytes: a slot per arm was 8 kB more stack on the M4F with a fourth scene).
#[cfg(feature = "scenes-multibody")]
#[inline(never)]
fn visit_built<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>, V: MultibodyVisitor>(
    build: impl FnOnce() -> Result<S, ParamError>,
    visitor: V,
) -> Result<V::Output, ParamError> {
    Ok(visitor.visit(build()?))
}

impl SceneParams {
    /// The scene in `precision` and `layout`, keeping `E` switch events, handed to `visitor`.
    ///
    /// # Errors
    /// The core's first complaint about the parameters in `precision` (the scene's `new`);
    /// `OutOfRange("scene")` for a scene of several bodies (`Self::build_multibody` builds
    /// those) or one this build leaves out.
    pub fn build<const E: usize, V: SceneVisitor>(
        &self,
        precision: Precision,
        layout: LcpLayout,
        visitor: V,
    ) -> Result<V::Output, ParamError> {
        #[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
        return match precision {
            Precision::F32 => self.build_in::<f32, E, V>(layout, visitor),
            Precision::F64 => self.build_in::<f64, E, V>(layout, visitor),
        };
        #[cfg(not(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3")))]
        {
            let _ = (precision, layout, visitor);
            Err(ParamError::OutOfRange("scene"))
        }
    }
}

/// Builds a scene and hands it to `visitor` (a single-body scene's arm of
/// [`SceneParams::build_in`]): out of line, so that each arm's scene is in a frame of its own. In
/// one function the arms' scenes did not share their stack slots: a Cortex-M0 driver's frame of all
/// of them was 8.7 KB of its 16 KB.
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
#[inline(never)]
fn hand_built<S, V, R>(
    build: impl FnOnce() -> Result<S, ParamError>,
    hand: impl FnOnce(S, V) -> R,
    visitor: V,
) -> Result<R, ParamError> {
    Ok(hand(build()?, visitor))
}

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
/// Hands a scene to a visitor: the meter stick to [`SceneVisitor::visit_meter_stick`], any other
/// to [`SceneVisitor::visit`].
macro_rules! hand {
    (visit_meter_stick, $visitor:expr, $scene:expr, $t:ty, $k:literal, $n:literal) => {
        $visitor.visit_meter_stick($scene)
    };
    (visit, $visitor:expr, $scene:expr, $t:ty, $k:literal, $n:literal) => {
        $visitor.visit::<$t, $k, $n, _>($scene)
    };
}

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
/// [`SceneIn`] and [`SceneParams::build_in`] of the registry's table (`scene_table!`).
macro_rules! registry {
    ($(#[$built:meta] $variant:ident: $scene:ident<$k:literal, $n:literal> = $params:ident, $layout:ident, $hand:ident;)*) => {
        /// Any catalogue scene in scalar `T` and either layout, keeping `E` switch events, held in
        /// place (no heap: as large as the largest).
        #[derive(Debug, Clone)]
        #[allow(clippy::large_enum_variant)] // one scene per run, held in place: no heap
        pub enum SceneIn<T: Real, const E: usize> {
            $(
                #[doc = concat!("`", stringify!($scene), "` with a ", stringify!($n), "x", stringify!($n), " LCP.")]
                #[$built]
                $variant($scene<T, $n, E>),
            )*
        }

        impl SceneParams {
            /// The scene in scalar `T` and `layout`, keeping `E` switch events, handed to
            /// `visitor`: [`Self::build`] with the precision a type (a microcontroller's driver
            /// builds only `f32`'s code), the scene on the stack for the visit only.
            ///
            /// # Errors
            /// The core's first complaint about the parameters in `T` (the scene's `new`); a scene
            /// this build leaves out (features `scenes-k1`..`scenes-k3`) is `OutOfRange("scene")`.
            pub fn build_in<T: Real, const E: usize, V: SceneVisitor>(
                &self,
                layout: LcpLayout,
                visitor: V,
            ) -> Result<V::Output, ParamError> {
                Ok(match (*self, layout) {
                    $(#[$built] (SceneParams::$params(p), LcpLayout::$layout) => hand_built(
                        move || $scene::<T, $n, E>::new(p.cast()),
                        |scene, visitor: V| hand!($hand, visitor, scene, T, $k, $n),
                        visitor,
                    )?,)*
                    // A scene this build leaves out (features `scenes-k1`..`scenes-k3`).
                    #[allow(unreachable_patterns)]
                    _ => return Err(ParamError::OutOfRange("scene")),
                })
            }
        }

        impl<T: Real, const E: usize> SceneIn<T, E> {
            /// The scene of `params` in `layout`, at its start.
            ///
            /// # Errors
            /// The core's first complaint about the parameters in `T` (the scene's `new`).
            pub fn new(params: &SceneParams, layout: LcpLayout) -> Result<Self, ParamError> {
                Ok(match (*params, layout) {
                    $(#[$built] (SceneParams::$params(p), LcpLayout::$layout) => Self::$variant($scene::new(p.cast())?),)*
                    // A scene this build leaves out (features `scenes-k1`..`scenes-k3`).
                    #[allow(unreachable_patterns)]
                    _ => return Err(ParamError::OutOfRange("scene")),
                })
            }

            /// Hands the scene to `visitor`.
            pub fn visit<V: SceneVisitor>(self, visitor: V) -> V::Output {
                match self {
                    $(#[$built] Self::$variant(s) => hand!($hand, visitor, s, T, $k, $n),)*
                }
            }

            /// Hands the scene, in place, to `visitor`.
            pub fn visit_mut<V: SceneVisitor>(&mut self, visitor: V) -> V::Output {
                match self {
                    $(#[$built] Self::$variant(s) => visitor.visit::<T, $k, $n, _>(s),)*
                }
            }

            /// The outcome, once the run has ended ([`Scene::outcome`]).
            #[must_use]
            pub fn outcome(&self) -> Option<Outcome> {
                match self {
                    $(#[$built] Self::$variant(s) => s.outcome(),)*
                }
            }

            /// Simulated time ([`Scene::time`]).
            #[must_use]
            pub fn time(&self) -> T {
                match self {
                    $(#[$built] Self::$variant(s) => s.time(),)*
                }
            }

            /// The stepper's counters ([`Scene::stats`]).
            #[must_use]
            pub fn stats(&self) -> &RunStats {
                match self {
                    $(#[$built] Self::$variant(s) => s.stats(),)*
                }
            }

            /// What the scene measures ([`Scene::measured`]).
            #[must_use]
            pub fn measured(&self) -> [Option<T>; MAX_MEASURES] {
                match self {
                    $(#[$built] Self::$variant(s) => s.measured(),)*
                }
            }
        }
    };
}

/// The registry's table, one row per scene and layout, handed to the macro `$then`: `#[cfg(the
/// feature that builds it)] variant: Scene<K contacts, N> = SceneParams variant, layout, visitor
/// method`. `registry!` makes [`SceneIn`] and [`SceneParams::build_in`] of it, the views' holder
/// (`view/held.rs`) its scenes seen as views.
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
macro_rules! scene_table {
    ($then:ident) => {
        $then! {
            #[cfg(feature = "scenes-k2")]
            MeterStickReduced: MeterStick<2, 6> = MeterStick, Reduced, visit_meter_stick;
            #[cfg(feature = "scenes-k2")]
            MeterStickFull: MeterStick<2, 8> = MeterStick, Full, visit_meter_stick;
            #[cfg(feature = "scenes-k2")]
            InclineReduced: Incline<2, 6> = Incline, Reduced, visit;
            #[cfg(feature = "scenes-k2")]
            InclineFull: Incline<2, 8> = Incline, Full, visit;
            #[cfg(feature = "scenes-k2")]
            LadderReduced: Ladder<2, 6> = Ladder, Reduced, visit;
            #[cfg(feature = "scenes-k2")]
            LadderFull: Ladder<2, 8> = Ladder, Full, visit;
            #[cfg(feature = "scenes-k3")]
            ThreeFingersReduced: ThreeFingers<3, 9> = ThreeFingers, Reduced, visit;
            #[cfg(feature = "scenes-k3")]
            ThreeFingersFull: ThreeFingers<3, 12> = ThreeFingers, Full, visit;
            #[cfg(feature = "scenes-k1")]
            CylinderReduced: Cylinder<1, 3> = Cylinder, Reduced, visit;
            #[cfg(feature = "scenes-k1")]
            CylinderFull: Cylinder<1, 4> = Cylinder, Full, visit;
            #[cfg(feature = "scenes-k1")]
            PainleveReduced: Painleve<1, 3> = Painleve, Reduced, visit;
            #[cfg(feature = "scenes-k1")]
            PainleveFull: Painleve<1, 4> = Painleve, Full, visit;
        }
    };
}
#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
pub(super) use scene_table;

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
scene_table!(registry);

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
/// Any catalogue scene in any precision and layout ([`SceneIn`] in f32 or f64), held in place:
/// for a driver that keeps a run between calls (the browser page steps a frame at a time).
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one scene per run, held in place: there is no heap on wasm
pub enum AnyScene<const E: usize> {
    /// In f32.
    F32(SceneIn<f32, E>),
    /// In f64.
    F64(SceneIn<f64, E>),
}

#[cfg(any(feature = "scenes-k1", feature = "scenes-k2", feature = "scenes-k3"))]
impl<const E: usize> AnyScene<E> {
    /// The scene of `params` in `precision` and `layout`, at its start.
    ///
    /// # Errors
    /// The core's first complaint about the parameters in `precision`.
    pub fn new(params: &SceneParams, precision: Precision, layout: LcpLayout) -> Result<Self, ParamError> {
        Ok(match precision {
            Precision::F32 => Self::F32(SceneIn::new(params, layout)?),
            Precision::F64 => Self::F64(SceneIn::new(params, layout)?),
        })
    }

    /// Hands the scene, in place, to `visitor`.
    pub fn visit_mut<V: SceneVisitor>(&mut self, visitor: V) -> V::Output {
        match self {
            Self::F32(s) => s.visit_mut(visitor),
            Self::F64(s) => s.visit_mut(visitor),
        }
    }

    /// The outcome, once the run has ended.
    #[must_use]
    pub fn outcome(&self) -> Option<Outcome> {
        match self {
            Self::F32(s) => s.outcome(),
            Self::F64(s) => s.outcome(),
        }
    }

    /// Simulated time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        match self {
            Self::F32(s) => s.time().as_f64(),
            Self::F64(s) => s.time(),
        }
    }

    /// The stepper's counters.
    #[must_use]
    pub fn stats(&self) -> &RunStats {
        match self {
            Self::F32(s) => s.stats(),
            Self::F64(s) => s.stats(),
        }
    }

    /// What the scene measures, in f64.
    #[must_use]
    pub fn measured(&self) -> [Option<f64>; MAX_MEASURES] {
        match self {
            Self::F32(s) => s.measured().map(|v| v.map(Real::as_f64)),
            Self::F64(s) => s.measured(),
        }
    }
}

#[cfg(feature = "scenes-multibody")]
impl<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P> + ?Sized> MultibodyScene<T, B, P>
    for &mut S
{
    const ROWS: usize = S::ROWS;
    fn step(&mut self) -> Option<crate::multibody::SystemStepReport<T, B, P>> {
        (**self).step()
    }
    fn go_on(&mut self) -> Option<Outcome> {
        (**self).go_on()
    }
    fn outcome(&self) -> Option<Outcome> {
        (**self).outcome()
    }
    fn states(&self) -> &[crate::planar::BodyState<T>; B] {
        (**self).states()
    }
    fn system(&self) -> &crate::multibody::System<T, B, P> {
        (**self).system()
    }
    fn frames(&self) -> &[[crate::multibody::CornerFrame<T>; 4]; P] {
        (**self).frames()
    }
    fn modes(&self) -> &[[crate::planar::ContactMode; 4]; P] {
        (**self).modes()
    }
    fn time(&self) -> T {
        (**self).time()
    }
    fn stats(&self) -> &RunStats {
        (**self).stats()
    }
    fn measured(&self) -> [Option<T>; MAX_MEASURES] {
        (**self).measured()
    }
}

/// The most bodies a scene of several bodies has (the stack of three).
#[cfg(feature = "scenes-multibody")]
pub const MAX_BODIES: usize = 3;

#[cfg(all(test, feature = "scenes"))]
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

    /// Takes up to its number of steps; gives the steps taken and the state's bits after them.
    struct Steps(u64);

    impl SceneVisitor for Steps {
        type Output = (u64, [u64; 6]);
        fn visit<T: Real, const K: usize, const N: usize, S: Scene<T, K>>(
            self,
            mut scene: S,
        ) -> Self::Output {
            let mut taken = 0;
            while taken < self.0 && scene.step().is_some() {
                taken += 1;
            }
            (taken, scene.state().to_array().map(|v| v.as_f64().to_bits()))
        }
    }

    /// Reports what it was given: the scalar's name, the bodies, the pairs and the LCP's rows.
    #[cfg(feature = "scenes-multibody")]
    struct Bodies;

    #[cfg(feature = "scenes-multibody")]
    impl MultibodyVisitor for Bodies {
        type Output = (&'static str, usize, usize, usize);
        fn visit<T: Real, const B: usize, const P: usize, S: MultibodyScene<T, B, P>>(
            self,
            _: S,
        ) -> Self::Output {
            (T::NAME, B, P, S::ROWS)
        }
    }

    /// The scenes of several bodies are built with their bodies, pairs and LCP capacity; the
    /// stack with the blocks asked for; a scene of one body is not theirs.
    #[cfg(feature = "scenes-multibody")]
    #[test]
    fn every_multibody_scene_is_built_as_asked() {
        let build = |kind, blocks: Option<f64>, precision| {
            let mut p = SceneParams::defaults(kind);
            if let Some(b) = blocks {
                assert!(p.set("blocks", b));
            }
            p.build_multibody(precision, Bodies)
        };
        assert_eq!(build(SceneKind::BlockOnBlock, None, Precision::F32), Ok(("f32", 2, 2, 24)));
        assert_eq!(build(SceneKind::Tablecloth, None, Precision::F64), Ok(("f64", 2, 3, 24)));
        assert_eq!(build(SceneKind::Stack, Some(2.0), Precision::F32), Ok(("f32", 2, 2, 24)));
        assert_eq!(build(SceneKind::Stack, Some(3.0), Precision::F64), Ok(("f64", 3, 3, 32)));
        assert_eq!(build(SceneKind::DiscOnBoard, None, Precision::F32), Ok(("f32", 2, 2, 24)));
        assert_eq!(build(SceneKind::Stack, Some(4.0), Precision::F64), Err(ParamError::OutOfRange("blocks")));
        assert_eq!(build(SceneKind::Incline, None, Precision::F64), Err(ParamError::OutOfRange("scene")));
    }

    /// Every scene is built in the precision and layout asked for, with its catalogue's contacts
    /// and the LCP size the layout gives them.
    #[test]
    fn every_scene_is_built_as_asked() {
        for kind in SceneKind::ALL.into_iter().filter(|k| k.has_layout_choice()) {
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
        // Held in place and visited step by step, a scene runs as built and handed over whole.
        for kind in SceneKind::ALL.into_iter().filter(|k| k.has_layout_choice()) {
            for precision in Precision::ALL {
                for layout in LcpLayout::ALL {
                    let params = SceneParams::defaults(kind);
                    let whole = params.build::<0, _>(precision, layout, Steps(300)).unwrap();
                    let mut held = AnyScene::<0>::new(&params, precision, layout).unwrap();
                    let (a, b) = (held.visit_mut(Steps(100)), held.visit_mut(Steps(200)));
                    let state = held.visit_mut(Steps(0)).1;
                    assert_eq!((a.0 + b.0, state), whole, "{kind} {precision:?} {layout:?}");
                    assert_eq!(held.stats().steps, whole.0, "{kind}");
                }
            }
        }
        // Only a scene of one planar body is a `Scene`: the others are refused by name.
        for kind in SceneKind::ALL.into_iter().filter(|k| !k.has_layout_choice()) {
            assert_eq!(
                SceneParams::defaults(kind).build::<0, _>(Precision::F32, LcpLayout::Full, Sizes),
                Err(ParamError::OutOfRange("scene")),
                "{kind}"
            );
        }
        let mut p = SceneParams::defaults(SceneKind::Incline);
        assert!(p.set("mass", -1.0));
        assert_eq!(
            p.build::<0, _>(Precision::F32, LcpLayout::Full, Sizes),
            Err(ParamError::NotPositive("mass"))
        );
    }
}
