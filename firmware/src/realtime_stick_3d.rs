//! The meter stick in three dimensions on the real-time loop (`rig-stick-3d`, a Pico 2 or Pico
//! build without the link; `docs/scenes.md`, "meter-stick-3d"): its parameters at boot and its
//! buttons. One scene step per SysTick period `h` (1 ms), the carriage following finger 1 along
//! its path (`meterstick_rig::CarriedFinger`: the rail laid at the path's heading to the rod),
//! a light set per finger (finger 1's the pad's two points), as the meter-stick rig.
//!
//! Buttons (debounced, [`DEBOUNCE_TICKS`] ticks): a press of the start button starts a run; once
//! it has ended, a press resets it (the carriage drives back to its origin) and the next press
//! starts it again. While no run is in progress, the preset button cycles the path's heading
//! through [`HEADINGS_DEG`], shown on finger 1's lights (sticking, sliding, separated) until the
//! start: the rail must be laid at the selected heading.

use core::convert::Infallible;

use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::scene::spatial::{MeterStick3d, MeterStick3dParams};
use meterstick_rig::{Carriage, PressDetector, Rig, RigPins, RigState};

use crate::realtime::{CycleDelay, DEBOUNCE_TICKS, RestartButton, STEP_HZ, config};

/// The headings of finger 1's path to the rod's axis the preset button selects (degrees), the
/// first at boot: 0 the paper's trick (the rod balances), 10 (it balances, carried sideways and
/// turned), 30 (its sideways slide outlasts the fingers' meeting: it falls).
pub const HEADINGS_DEG: [f32; 3] = [0.0, 10.0, 30.0];

/// The rig of the meter stick in three dimensions on this board.
pub type Stick3dRig<B, P> = Rig<MeterStick3d<f32>, Carriage<P, CycleDelay>, B, P, 2>;

/// The catalogue's scene at h = 1 ms, its path at `heading_deg`.
fn params_at(heading_deg: f32) -> MeterStick3dParams<f32> {
    MeterStick3dParams {
        heading: heading_deg.to_radians(),
        step: 1.0 / STEP_HZ as f32,
        ..MeterStick3dParams::default()
    }
}

/// The rig with `pins`, its carriage on the stepper driver's `step` and `dir`, the first of
/// [`HEADINGS_DEG`], its start button debounced over [`DEBOUNCE_TICKS`] and the steps SysTick can
/// tick at `sysclk_hz`; `None` if it cannot start (logged).
pub fn new_rig<B, P>(pins: RigPins<B, P, 2>, step: P, dir: P, sysclk_hz: u32) -> Option<Stick3dRig<B, P>>
where
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    let carriage = Carriage::new(step, dir, CycleDelay::new(sysclk_hz));
    let rig = Rig::new(params_at(HEADINGS_DEG[0]), config(sysclk_hz), pins, carriage);
    #[cfg(feature = "log")]
    if let Err(e) = &rig {
        defmt::error!("rig not started: {}", e);
    }
    rig.ok()
}

/// The rig's buttons between runs: the preset button cycles the heading (shown on finger 1's
/// lights), the start button resets a finished run (the next press starts it).
pub struct Buttons {
    /// The selected entry of [`HEADINGS_DEG`].
    selected: u8,
    preset_press: PressDetector,
    restart: RestartButton,
}

impl Buttons {
    /// The first of [`HEADINGS_DEG`] selected (the rig's at boot, [`new_rig`]).
    pub const fn new() -> Self {
        Self { selected: 0, preset_press: PressDetector::new(DEBOUNCE_TICKS), restart: RestartButton::new() }
    }

    /// One sample per tick, after it: `state` the rig's, `preset_pressed` the preset button
    /// (`true`: pressed).
    pub fn between_runs<B, P>(&mut self, rig: &mut Stick3dRig<B, P>, state: RigState, preset_pressed: bool)
    where
        B: InputPin<Error = Infallible>,
        P: OutputPin<Error = Infallible>,
    {
        // Pins on these HALs cannot fail (`Infallible`); every heading is valid for the core and
        // within the carriage's speed (0.1 m/s along the path).
        if self.preset_press.sample(preset_pressed) && !matches!(state, RigState::Running) {
            let next = (self.selected + 1) % HEADINGS_DEG.len() as u8;
            if let Some(&heading) = HEADINGS_DEG.get(usize::from(next))
                && rig.reset(MeterStick3dParams { heading: heading.to_radians(), ..*rig.params() }).is_ok()
            {
                self.selected = next;
                let _ = rig.indicate(Some(next));
            }
        }
        let ended = matches!(state, RigState::Finished(_) | RigState::Fault(_));
        if self.restart.sample(ended, || rig.start_pressed().unwrap_or(false)) {
            let _ = rig.reset(*rig.params());
        }
    }
}
