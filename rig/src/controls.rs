//! The rig's controls between runs: [`PresetScene`], what the link's [`Preset`]s are (slow, fast,
//! near the fall threshold), and [`PressDetector`], which debounces a button into presses.

use meterstick_core::scene::MeterStickParams;
pub use meterstick_link::Preset;

#[cfg(doc)]
use crate::Rig;

/// The rig's preset scenes are the link's [`Preset`]s (`link/src/wire.rs`: one list for the wire
/// and the rig); this is what the rig makes of them: the paper's rod with finger 1 starting at
/// -0.35 m (as the QEMU runs and `host-sim run`'s slow scene), at three finger speeds.
pub trait PresetScene: Sized {
    /// The preset's parameters, at time step `step` (s): slow 0.1 m/s, the paper's slow finger
    /// (the rod balances, 7.9 s); fast 5 m/s (the rod falls); near-threshold 0.3 m/s (it
    /// balances, and falls from 0.31 m/s and at 0.2 m/s: the outcome is sensitive to the
    /// parameters).
    ///
    /// The presets are the scenes as the link names them, not clamped to a rig: a rig whose
    /// carriage cannot follow one refuses it ([`Rig::reset`] checks [`crate::RigConfig::check`];
    /// the session answers `Rejected` naming `Finger1Velocity`), e.g. the fast preset on
    /// [`crate::RigConfig::default_rig`] (5 m/s needs 400 pulses per 1 ms tick, it emits 100).
    /// Slowed down to what such a carriage follows, it would no longer be the scene whose rod
    /// falls that the host and the other builds run under the same name.
    #[must_use]
    fn params(self, step: f32) -> MeterStickParams<f32>;
    /// The next preset, cyclically (a button press).
    #[must_use]
    fn next(self) -> Self;
    /// Its position in [`Preset::ALL`] (what [`Rig::indicate`] shows).
    #[must_use]
    fn index(self) -> u8;
}

impl PresetScene for Preset {
    #[inline]
    fn params(self, step: f32) -> MeterStickParams<f32> {
        let finger1_velocity = match self {
            Self::Slow => 0.1,
            Self::Fast => 5.0,
            Self::NearThreshold => 0.3,
        };
        MeterStickParams { finger1_x: -0.35, finger1_velocity, step, ..MeterStickParams::paper() }
    }

    #[inline]
    fn next(self) -> Self {
        match self {
            Self::Slow => Self::Fast,
            Self::Fast => Self::NearThreshold,
            Self::NearThreshold => Self::Slow,
        }
    }

    #[inline]
    fn index(self) -> u8 {
        match self {
            Self::Slow => 0,
            Self::Fast => 1,
            Self::NearThreshold => 2,
        }
    }
}

/// Debounces a button sampled once per tick into presses: a press counts once the button has
/// read pressed for `ticks` consecutive samples after reading released for as long.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PressDetector {
    ticks: u16,
    count: u16,
    pressed: bool,
}

impl PressDetector {
    /// A detector that needs `ticks` equal samples (e.g. 20 at 1 kHz: 20 ms) to change state;
    /// it starts released.
    #[must_use]
    pub const fn new(ticks: u16) -> Self {
        Self { ticks, count: 0, pressed: false }
    }

    /// Takes the button as held by a press already acted on (the one that started a run): the
    /// next press counts only after the button has read released for `ticks` samples.
    pub fn spend_press(&mut self) {
        self.pressed = true;
        self.count = 0;
    }

    /// Feeds one sample; `true` on the tick a press is recognised.
    pub fn sample(&mut self, pressed: bool) -> bool {
        if pressed == self.pressed {
            self.count = 0;
            return false;
        }
        self.count = self.count.saturating_add(1);
        if self.count < self.ticks {
            return false;
        }
        self.count = 0;
        self.pressed = pressed;
        pressed
    }
}
