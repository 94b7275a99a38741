//! [`LinkScene`]: what the link session ([`super::Session`]) needs of a scene beyond the rig's
//! [`RigScene`], so that one session serves every scene a board runs: its id and parameters as
//! the link names them, the trajectory checksum, the events and the telemetry of a step.

use meterstick_core::multibody::SystemStepReport;
use meterstick_core::multibody::scenes::{MultibodyScene, Stack};
use meterstick_core::planar::{Checksum, StepReport};
use meterstick_core::scene::{MeterStick, Scene as _};
use meterstick_link::{ContactTelemetry, ParamId, Preset, Report, SceneId};

use super::codes::{interface_mode_of, mode_of};
use crate::{InterfaceMode, PresetScene as _, RigScene};

/// A scene the link session serves, shown on `L` lights.
pub trait LinkScene<const L: usize>: RigScene<L> {
    /// Its id on the link ([`Report::Hello`], [`meterstick_link::Command::SelectScene`]).
    const SCENE: SceneId;
    /// The LCP size announced in [`Report::Hello`] (the meter stick's 6 or 8; the stack's
    /// rows, 32 for three blocks).
    const LCP_SIZE: u8;

    /// The value of the parameter `id` in `params`; `None` if the scene has no such parameter.
    fn param(params: &Self::Params, id: ParamId) -> Option<f32>;

    /// Sets the parameter `id` of `params` to `value` (unvalidated); `false` if the scene has no
    /// such parameter.
    fn set_param(params: &mut Self::Params, id: ParamId, value: f32) -> bool;

    /// The preset `preset` at the time step of `params`; `None` if the scene has no presets.
    fn preset(preset: Preset, params: &Self::Params) -> Option<Self::Params>;

    /// Adds the state a step reports to the run's `checksum` (as the host's run of the scene
    /// does, so that the two compare).
    fn checksum(checksum: &mut Checksum, report: &Self::Report);

    /// Sends the switch events of the step `step` that `report` reports: `before` and `after`
    /// are the rig's lights' modes ([`crate::Rig::shown`]) before and after the tick.
    fn events(
        report: &Self::Report,
        before: &[Option<Self::Mode>; L],
        after: &[Option<Self::Mode>; L],
        step: u32,
        send: impl FnMut(&Report),
    );

    /// Sends the telemetry of step `step`: the state after the step `report` reports (at its
    /// time), or (without one) the scene's start (time 0); `shown` the rig's lights' modes.
    fn telemetry(
        &self,
        report: Option<&Self::Report>,
        shown: &[Option<Self::Mode>; L],
        step: u32,
        send: impl FnMut(&Report),
    );
}

impl<const N: usize, const E: usize> LinkScene<2> for MeterStick<f32, N, E> {
    const SCENE: SceneId = SceneId::MeterStick;
    #[allow(clippy::cast_possible_truncation)] // 6 or 8
    const LCP_SIZE: u8 = N as u8;

    #[inline]
    fn param(params: &Self::Params, id: ParamId) -> Option<f32> {
        params.get(id.name())
    }

    #[inline]
    fn set_param(params: &mut Self::Params, id: ParamId, value: f32) -> bool {
        params.set(id.name(), value)
    }

    #[inline]
    fn preset(preset: Preset, params: &Self::Params) -> Option<Self::Params> {
        Some(preset.params(params.step))
    }

    #[inline]
    fn checksum(checksum: &mut Checksum, report: &StepReport<f32, 2>) {
        checksum.add(&report.state);
    }

    /// Each finger's contact that switched on the step ([`StepReport::switches`]), with both
    /// fingers' positions along the rod.
    fn events(
        report: &StepReport<f32, 2>,
        _: &[Option<Self::Mode>; 2],
        _: &[Option<Self::Mode>; 2],
        step: u32,
        mut send: impl FnMut(&Report),
    ) {
        let along = report.along();
        for (contact, mode) in report.switches() {
            send(&Report::Switch {
                step,
                time: report.time,
                contact: u8::try_from(contact).unwrap_or(u8::MAX),
                mode: mode_of(mode),
                along,
            });
        }
    }

    /// One [`Report::Telemetry`]: the rod's state, the fingers, each contact's mode and impulses
    /// over the step (none at the start).
    fn telemetry(
        &self,
        report: Option<&StepReport<f32, 2>>,
        _: &[Option<Self::Mode>; 2],
        step: u32,
        mut send: impl FnMut(&Report),
    ) {
        let time = report.map_or(0.0, |r| r.time);
        let contacts = match report {
            Some(r) => r.contacts.map(|c| ContactTelemetry {
                mode: mode_of(c.mode),
                normal_impulse: c.normal_impulse,
                friction_impulse: c.friction_impulse,
            }),
            None => self.modes().map(|m| ContactTelemetry {
                mode: mode_of(m),
                normal_impulse: 0.0,
                friction_impulse: 0.0,
            }),
        };
        let s = self.state();
        let [vx, vy, omega] = s.velocity();
        send(&Report::Telemetry {
            step,
            time,
            state: [s.x, s.y, s.theta, vx, vy, omega],
            fingers: self.fingers(),
            contacts,
        });
    }
}

impl<const B: usize, const N: usize> LinkScene<B> for Stack<f32, B, N> {
    const SCENE: SceneId = SceneId::Stack;
    #[allow(clippy::cast_possible_truncation)] // 24 or 32
    const LCP_SIZE: u8 = N as u8;

    #[inline]
    fn param(params: &Self::Params, id: ParamId) -> Option<f32> {
        params.get(id.name())
    }

    #[inline]
    fn set_param(params: &mut Self::Params, id: ParamId, value: f32) -> bool {
        params.set(id.name(), value)
    }

    /// None: the presets are the meter stick's.
    #[inline]
    fn preset(_: Preset, _: &Self::Params) -> Option<Self::Params> {
        None
    }

    /// Every block's state, from the bottom up (as `host-sim run stack` and the QEMU build's
    /// stack rig).
    #[inline]
    fn checksum(checksum: &mut Checksum, report: &SystemStepReport<f32, B, B>) {
        for body in &report.states {
            checksum.add(body);
        }
    }

    /// Each interface whose lights changed on the step ([`InterfaceMode`]: a slide that changes
    /// direction is a change), as [`Report::InterfaceSwitch`].
    fn events(
        report: &SystemStepReport<f32, B, B>,
        before: &[Option<InterfaceMode>; B],
        after: &[Option<InterfaceMode>; B],
        step: u32,
        mut send: impl FnMut(&Report),
    ) {
        for (interface, (old, new)) in before.iter().zip(after).enumerate() {
            if let Some(mode) = new
                && old != new
            {
                send(&Report::InterfaceSwitch {
                    step,
                    time: report.time,
                    interface: u8::try_from(interface).unwrap_or(u8::MAX),
                    mode: interface_mode_of(*mode),
                });
            }
        }
    }

    /// One [`Report::Body`] per block, from the bottom up, each with the mode of the interface it
    /// rests on.
    fn telemetry(
        &self,
        report: Option<&SystemStepReport<f32, B, B>>,
        shown: &[Option<InterfaceMode>; B],
        step: u32,
        mut send: impl FnMut(&Report),
    ) {
        let time = report.map_or(0.0, |r| r.time);
        for (body, (s, mode)) in MultibodyScene::states(self).iter().zip(shown).enumerate() {
            let [vx, vy, omega] = s.velocity();
            send(&Report::Body {
                step,
                time,
                body: u8::try_from(body).unwrap_or(u8::MAX),
                state: [s.x, s.y, s.theta, vx, vy, omega],
                mode: mode.map_or(meterstick_link::Mode::Separated, interface_mode_of),
            });
        }
    }
}
