//! [`RigScene`]: what the one rig state machine ([`crate::Rig`]) needs of the scene it shows, so
//! that one loop runs every scene a board runs: the meter stick (`MeterStick<f32, N, E>`, a light
//! per finger), the stack of blocks (`Stack<f32, B, N>`, a light per interface) and, with the
//! feature `spatial`, the meter stick in three dimensions (`MeterStick3d<f32>`, a light per
//! finger).

use meterstick_core::ParamError;
use meterstick_core::multibody::SystemStepReport;
use meterstick_core::multibody::scenes::{MultibodyScene, Stack, StackParams};
use meterstick_core::planar::{BodyState, ContactMode, StepReport};
use meterstick_core::scene::{MeterStick, MeterStickParams, Outcome, Scene};

use crate::lights::Shown;
use crate::{InterfaceMode, RigConfig, Unperformable};

/// A scene in f32 whose run a [`crate::Rig`] shows on `L` [`crate::ModeLights`] (one per contact
/// or interface the rig shows a mode of), one scene step per tick.
pub trait RigScene<const L: usize>: Sized {
    /// The scene's parameters.
    type Params: Copy + core::fmt::Debug;
    /// What one step reports (handed to [`crate::Rig::tick_with`]'s observer).
    type Report;
    /// The mode each of the `L` lights shows.
    type Mode: Shown + core::fmt::Debug;
    /// What each light shows, in logs: `finger` or `interface`.
    const LIGHT: &'static str;
    /// The number the first light's contact or interface has in the scene's docs (the fingers
    /// count from 1, the interfaces from 0).
    const FIRST_LIGHT: usize;

    /// The scene at its start, from `params` validated by the core (the scene's `new`).
    ///
    /// # Errors
    /// The core's first complaint about `params`.
    fn build(params: Self::Params) -> Result<Self, ParamError>;

    /// Whether a rig configured by `config` can perform `params` (already valid for the core).
    ///
    /// # Errors
    /// What it cannot perform.
    fn check(config: &RigConfig, params: &Self::Params) -> Result<(), Unperformable>;

    /// The parameters the scene was built from.
    fn params(&self) -> &Self::Params;

    /// The time step of `params` (s): the rig ticks once per step.
    fn step_of(params: &Self::Params) -> f32;

    /// One step, unless the run has its outcome ([`Self::outcome`]; a failed step ends the run
    /// with [`Outcome::Failed`]).
    fn advance(&mut self) -> Option<Self::Report>;

    /// Whether the state a step reports is finite (the rig faults on one that is not).
    fn finite(report: &Self::Report) -> bool;

    /// The outcome, once the run has ended.
    fn outcome(&self) -> Option<Outcome>;

    /// Simulated time (s).
    fn time(&self) -> f32;

    /// Each light's mode at the scene's start.
    fn start_modes(&self) -> [Self::Mode; L];

    /// Each light's mode after the step `report` reports.
    fn modes_of(report: &Self::Report) -> [Self::Mode; L];
}

/// The meter stick (`docs/scenes.md`, "meter stick"): a light per finger, finger 1's first.
impl<const N: usize, const E: usize> RigScene<2> for MeterStick<f32, N, E> {
    type Params = MeterStickParams<f32>;
    type Report = StepReport<f32, 2>;
    type Mode = ContactMode;
    const LIGHT: &'static str = "finger";
    const FIRST_LIGHT: usize = 1;

    #[inline]
    fn build(params: MeterStickParams<f32>) -> Result<Self, ParamError> {
        Self::new(params)
    }

    /// [`RigConfig::check`]: the carriage follows finger 1.
    #[inline]
    fn check(config: &RigConfig, params: &MeterStickParams<f32>) -> Result<(), Unperformable> {
        config.check(params)
    }

    #[inline]
    fn params(&self) -> &MeterStickParams<f32> {
        MeterStick::params(self)
    }

    #[inline]
    fn step_of(params: &MeterStickParams<f32>) -> f32 {
        params.step
    }

    #[inline]
    fn advance(&mut self) -> Option<StepReport<f32, 2>> {
        Scene::step(self)
    }

    /// Always: the core fails a step whose state is not finite, and the carriage checks the
    /// target it follows.
    #[inline]
    fn finite(_: &StepReport<f32, 2>) -> bool {
        true
    }

    #[inline]
    fn outcome(&self) -> Option<Outcome> {
        Scene::outcome(self)
    }

    #[inline]
    fn time(&self) -> f32 {
        Scene::time(self)
    }

    #[inline]
    fn start_modes(&self) -> [ContactMode; 2] {
        self.modes()
    }

    #[inline]
    fn modes_of(report: &StepReport<f32, 2>) -> [ContactMode; 2] {
        report.modes()
    }
}

/// The stack of `B` blocks over a table's edge (`docs/scenes.md`, "stack"): a light per
/// interface, pair 0 the table and the bottom block, pair `i` blocks `i - 1` and `i` (counted from
/// the bottom), each showing its [`InterfaceMode`].
impl<const B: usize, const N: usize> RigScene<B> for Stack<f32, B, N> {
    type Params = StackParams<f32>;
    type Report = SystemStepReport<f32, B, B>;
    type Mode = InterfaceMode;
    const LIGHT: &'static str = "interface";
    const FIRST_LIGHT: usize = 0;

    #[inline]
    fn build(params: StackParams<f32>) -> Result<Self, ParamError> {
        Self::new(params)
    }

    /// [`RigConfig::check_step`]: nothing on the rig moves.
    #[inline]
    fn check(config: &RigConfig, params: &StackParams<f32>) -> Result<(), Unperformable> {
        config.check_step(params.step)
    }

    #[inline]
    fn params(&self) -> &StackParams<f32> {
        Stack::params(self)
    }

    #[inline]
    fn step_of(params: &StackParams<f32>) -> f32 {
        params.step
    }

    #[inline]
    fn advance(&mut self) -> Option<SystemStepReport<f32, B, B>> {
        MultibodyScene::step(self)
    }

    #[inline]
    fn finite(report: &SystemStepReport<f32, B, B>) -> bool {
        report.states.iter().all(BodyState::is_finite)
    }

    #[inline]
    fn outcome(&self) -> Option<Outcome> {
        Stack::outcome(self)
    }

    #[inline]
    fn time(&self) -> f32 {
        MultibodyScene::time(self)
    }

    #[inline]
    fn start_modes(&self) -> [InterfaceMode; B] {
        MultibodyScene::modes(self).map(InterfaceMode::of)
    }

    #[inline]
    fn modes_of(report: &SystemStepReport<f32, B, B>) -> [InterfaceMode; B] {
        report.modes.map(InterfaceMode::of)
    }
}

/// The meter stick in three dimensions (`docs/scenes.md`, "meter-stick-3d"; feature `spatial`): a
/// light per finger, finger 1's (the pad: sliding when either of its points slides, sticking when
/// either touches) first.
#[cfg(feature = "spatial")]
impl RigScene<2> for meterstick_core::scene::spatial::MeterStick3d<f32> {
    type Params = meterstick_core::scene::spatial::MeterStick3dParams<f32>;
    type Report =
        meterstick_core::spatial::SpatialStepReport<f32, { meterstick_core::scene::spatial::ROD_POINTS }>;
    type Mode = meterstick_core::spatial::Mode;
    const LIGHT: &'static str = "finger";
    const FIRST_LIGHT: usize = 1;

    #[inline]
    fn build(params: Self::Params) -> Result<Self, ParamError> {
        Self::new(params)
    }

    /// [`RigConfig::check`] of the scene with finger 1 moving at its speed along its path (the
    /// carriage runs along the path, `crate::Carriage`).
    #[inline]
    fn check(config: &RigConfig, params: &Self::Params) -> Result<(), Unperformable> {
        let (_, cos) = params.heading_sin_cos();
        let planar = params.planar();
        config.check(&MeterStickParams { finger1_velocity: planar.finger1_velocity / cos, ..planar })
    }

    #[inline]
    fn params(&self) -> &Self::Params {
        Self::params(self)
    }

    #[inline]
    fn step_of(params: &Self::Params) -> f32 {
        params.step
    }

    #[inline]
    fn advance(&mut self) -> Option<Self::Report> {
        self.step()
    }

    /// Always: the core fails a step whose state is not finite, and the carriage checks the
    /// target it follows.
    #[inline]
    fn finite(_: &Self::Report) -> bool {
        true
    }

    #[inline]
    fn outcome(&self) -> Option<Outcome> {
        Self::outcome(self)
    }

    #[inline]
    fn time(&self) -> f32 {
        self.stepper().time()
    }

    #[inline]
    fn start_modes(&self) -> [Self::Mode; 2] {
        self.finger_modes()
    }

    #[inline]
    fn modes_of(report: &Self::Report) -> [Self::Mode; 2] {
        meterstick_core::scene::spatial::finger_modes(report.contacts.map(|c| c.mode))
    }
}
