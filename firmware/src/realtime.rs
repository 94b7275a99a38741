//! The real-time loop every board binding runs (the Black Pill, the Pico 2, the Pico), for
//! either rig (`run`, [`serve`]: the meter stick's [`MeterStickRig`], the stack's
//! `meterstick_rig::StackRig`): one tick per SysTick period `h` on the core clock, the buttons
//! between runs, the real-time margin and, with `link`, the host link.
//!
//! SysTick wraps every `h` (the scene's step; reprogrammed when `h` changes between runs); each
//! wrap runs one tick, i.e. one scene step in real time. The time a tick took is read from
//! SysTick: the worst is logged (with `log`) once a second as the real-time margin, and sent to
//! the host (with `link`) in `Report::Margin`; a tick that overran its period is counted. The
//! link's port is serviced while the loop waits for the next tick. A board whose rig runs both
//! scenes switches between them on the host's `SelectScene` (`crate::realtime_stack::run_both_scenes`,
//! the Picos with `link`), a [`serve`] each.
//!
//! The meter-stick rig's buttons ([`Buttons`]; the stack's are `crate::realtime_stack`'s),
//! debounced over [`DEBOUNCE_TICKS`] ticks: a press of the start button starts a run (the rig
//! debounces it while waiting); once the run has ended, a press resets it (the carriage drives
//! back to its origin) and the next press starts it again. While no run is in progress, the
//! preset button cycles slow / fast / near the fall threshold, shown on finger 1's lights
//! (sticking / sliding / separated), skipping a preset the rig cannot perform (the fast one,
//! 5 m/s, on the Black Pill's carriage: about 1.24 m/s at h = 1 ms).

use core::convert::Infallible;

use cortex_m::peripheral::SYST;
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{InputPin, OutputPin};
#[cfg(not(feature = "link"))]
use meterstick_rig::RigScene;
#[cfg(feature = "link")]
use meterstick_rig::session::LinkScene;
use meterstick_rig::session::SceneId;
#[cfg(feature = "link")]
use meterstick_rig::session::Session;
use meterstick_rig::{
    Actuator, Carriage, MeterStickRig, Preset, PresetScene as _, PressDetector, Rig, RigConfig, RigError,
    RigPins, RigState,
};

use crate::systick;

/// Scene steps per second at boot (h = 1 ms); one SysTick period per step.
pub const STEP_HZ: u32 = 1_000;
/// Button samples (ticks) that must agree before a press counts (the rig's start button while
/// waiting, and both buttons here).
pub const DEBOUNCE_TICKS: u16 = 20;
/// The shortest SysTick period (cycles) a step may take: below it the loop could not even
/// wait for the wrap. The longest is SysTick's 24-bit range ([`systick::MASK`]). The rig
/// refuses steps outside them ([`RigConfig::ticked_by`]), so a tick is always one step.
const MIN_PERIOD: u32 = 1_000;

/// What [`run`] and [`serve`] need of a scene: the link's ([`LinkScene`]: its parameters and
/// telemetry by the protocol's names) with `link`, the rig's alone (`meterstick_rig::RigScene`)
/// without.
#[cfg(feature = "link")]
pub trait RunScene<const L: usize>: LinkScene<L> {}
#[cfg(feature = "link")]
impl<S: LinkScene<L>, const L: usize> RunScene<L> for S {}
/// What [`run`] and [`serve`] need of a scene: the rig's (`meterstick_rig::RigScene`; with
/// `link`, the link's too).
#[cfg(not(feature = "link"))]
pub trait RunScene<const L: usize>: RigScene<L> {}
#[cfg(not(feature = "link"))]
impl<S: RigScene<L>, const L: usize> RunScene<L> for S {}

/// Busy-wait delay on the core clock, timed by SysTick, which runs on it for the ticks
/// ([`Ticker::start`] starts it before the rig's first tick): the cycles asked plus at most one poll, on
/// any core. (`asm::delay` assumes two cycles a loop: the Cortex-M0+ takes three, and the
/// emulated RP2040 counted about six, so the stepper's pulses were 1.5 to 3 times `pulse_ns`, a
/// tenth of the Pico's worst tick.) Before SysTick runs (a counter that does not move), it falls
/// back to `asm::delay`.
#[derive(Debug, Clone, Copy)]
pub struct CycleDelay {
    /// Core cycles per 1,024 ns, rounded up (a shift, not a division, per delay: the Cortex-M0
    /// divides in software).
    per_1024_ns: u32,
}

impl CycleDelay {
    /// The delay on a core clock of `sysclk_hz`.
    #[must_use]
    pub const fn new(sysclk_hz: u32) -> Self {
        // cycles per 1,024 ns = sysclk_hz * 1,024e-9, rounded up: at least the time asked.
        Self { per_1024_ns: ((sysclk_hz as u64 * 1_024).div_ceil(1_000_000_000)) as u32 }
    }
}

/// Polls of a counter that does not move before [`CycleDelay`] takes SysTick as stopped.
const STOPPED_POLLS: u32 = 16;

impl DelayNs for CycleDelay {
    #[inline]
    fn delay_ns(&mut self, ns: u32) {
        let mut left = ns.saturating_mul(self.per_1024_ns) >> 10;
        let period = (SYST::get_reload() & systick::MASK) + 1;
        let mut last = SYST::get_current();
        let mut still = 0;
        while left > 0 {
            let now = SYST::get_current();
            if now == last {
                still += 1;
                if still > STOPPED_POLLS {
                    cortex_m::asm::delay(left);
                    return;
                }
                continue;
            }
            still = 0;
            // It counts down from `period - 1` and wraps to it.
            let passed = if now < last { last - now } else { last + period - now };
            left = left.saturating_sub(passed);
            last = now;
        }
    }
}

/// SysTick period (cycles) for a step of `h` seconds on a `sysclk_hz` core clock. The rig accepts
/// only steps of [`MIN_PERIOD`] ..= [`systick::MASK`] cycles (its [`RigConfig`]); the clamp only
/// absorbs the last cycle of rounding at the ends of that range.
pub fn period_of(h: f32, sysclk_hz: u32) -> u32 {
    let cycles = h * sysclk_hz as f32;
    // A valid `h` is positive; the cast saturates (and maps NaN to 0), the clamp bounds it.
    #[allow(clippy::cast_sign_loss)]
    let cycles = cycles as u32;
    cycles.clamp(MIN_PERIOD, systick::MASK)
}

/// The host link's port, serviced while the loop waits for the next tick (USB needs polling;
/// a UART has nothing to do).
#[cfg(feature = "link")]
pub trait LinkPort: meterstick_rig::session::Port {
    /// Services the port.
    fn poll(&mut self) {}
}

/// The rig's constants on this loop: the default carriage, the buttons debounced over
/// [`DEBOUNCE_TICKS`], the steps SysTick can tick at `sysclk_hz`.
pub fn config(sysclk_hz: u32) -> RigConfig {
    RigConfig { debounce_ticks: DEBOUNCE_TICKS, ..RigConfig::default_rig() }.ticked_by(
        sysclk_hz,
        MIN_PERIOD,
        systick::MASK,
    )
}

/// The rig with `pins`, its carriage on the stepper driver's `step` and `dir`, and the slow preset
/// at h = 1 ms, its start button debounced over [`DEBOUNCE_TICKS`], and the steps SysTick can tick
/// at `sysclk_hz`; `None` if it cannot start (logged).
pub fn new_rig<B, P>(
    pins: RigPins<B, P, 2>,
    step: P,
    dir: P,
    sysclk_hz: u32,
) -> Option<MeterStickRig<B, P, CycleDelay, 6>>
where
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    let params = Preset::Slow.params(1.0 / STEP_HZ as f32);
    let carriage = Carriage::new(step, dir, CycleDelay::new(sysclk_hz));
    let rig = MeterStickRig::<_, _, _, 6>::new(params, config(sysclk_hz), pins, carriage);
    #[cfg(feature = "log")]
    if let Err(e) = &rig {
        defmt::error!("rig not started: {}", e);
    }
    rig.ok()
}

/// The host link's session for `rig`, at boot (`Hello` and the state queued), its margins
/// against `ticker`'s period; it also runs `scenes` (`Session::with_scenes`: none but the rig's
/// own on a board that runs one scene).
#[cfg(feature = "link")]
pub fn open_session<S, A, B, P, const L: usize>(
    rig: &Rig<S, A, B, P, L>,
    ticker: &Ticker,
    scenes: &'static [SceneId],
) -> Session<S, L>
where
    S: LinkScene<L>,
    A: Actuator<S, Infallible>,
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    use meterstick_rig::session::{build_id, version};
    let mut session =
        Session::new(ticker.period(), version(env!("CARGO_PKG_VERSION")), build_id(env!("MS_BUILD_ID")))
            .with_scenes(scenes);
    session.boot(rig);
    session
}

/// Runs `rig` (either scene: the meter stick's, the stack's) in real time on SysTick at
/// `sysclk_hz` (the core clock), forever; with `link`, the host link serves it and this scene
/// only. `between_runs` is the scene's buttons, called after every tick with the state
/// (`Buttons::between_runs`, `crate::realtime_stack::Buttons::between_runs`). (A rig of both
/// scenes runs `crate::realtime_stack::run_both_scenes` instead.)
#[cfg(not(both_scenes))]
pub fn run<S, A, B, P, const L: usize>(
    mut rig: Rig<S, A, B, P, L>,
    mut between_runs: impl FnMut(&mut Rig<S, A, B, P, L>, RigState),
    syst: SYST,
    sysclk_hz: u32,
    #[cfg(feature = "link")] mut port: impl LinkPort,
) -> !
where
    S: RunScene<L>,
    S::Report: Copy,
    A: Actuator<S, Infallible>,
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    let mut ticker = Ticker::start(syst, period_of(S::step_of(rig.params()), sysclk_hz));
    #[cfg(feature = "link")]
    let mut session = open_session(&rig, &ticker, &[]);
    loop {
        // This build's one scene: the session refuses a `SelectScene` of another
        // (`NoSuchScene`), never returns one.
        let _ = serve(
            &mut rig,
            &mut between_runs,
            &mut ticker,
            sysclk_hz,
            #[cfg(feature = "link")]
            &mut session,
            #[cfg(feature = "link")]
            &mut port,
        );
    }
}

/// The loop of `run`: one tick of `rig` per SysTick period, `between_runs` after each, the
/// period following the scene's step between runs; with `link`, the session polled before the
/// tick and its reports flushed after it. Returns the scene the host selects
/// (`meterstick_rig::session::Session::poll`; the rig is not running then), for the board to switch to
/// (`crate::realtime_stack::run_both_scenes`); never without `link`.
pub fn serve<S, A, B, P, const L: usize>(
    rig: &mut Rig<S, A, B, P, L>,
    between_runs: &mut impl FnMut(&mut Rig<S, A, B, P, L>, RigState),
    ticker: &mut Ticker,
    sysclk_hz: u32,
    #[cfg(feature = "link")] session: &mut Session<S, L>,
    #[cfg(feature = "link")] port: &mut impl LinkPort,
) -> SceneId
where
    S: RunScene<L>,
    S::Report: Copy,
    A: Actuator<S, Infallible>,
    B: InputPin<Error = Infallible>,
    P: OutputPin<Error = Infallible>,
{
    loop {
        while !ticker.due() {
            #[cfg(feature = "link")]
            port.poll();
        }
        // Pins on these HALs cannot fail; `Params` and `Unperformable` the session answers
        // itself (a `Rejected`).
        #[cfg(feature = "link")]
        match session.poll(port, rig) {
            Ok(Some(scene)) => return scene,
            Err(RigError::Pin(never)) => match never {},
            Ok(None) | Err(RigError::Params(_) | RigError::Unperformable(_)) => {}
        }
        #[cfg(feature = "link")]
        let (state, used) = ticker.time(|| rig.tick_with(|r| session.record(r)));
        #[cfg(not(feature = "link"))]
        let (state, used) = ticker.time(|| rig.tick());
        #[cfg(feature = "link")]
        {
            session.end_tick(rig, used);
            session.flush(port);
        }
        #[cfg(not(feature = "link"))]
        let _ = used;
        let state = match state {
            Ok(s) => s,
            // `Params` and `Unperformable` only come from `new` and `reset`; pins on these HALs
            // cannot fail.
            Err(RigError::Params(_) | RigError::Unperformable(_)) => continue,
            Err(RigError::Pin(never)) => match never {},
        };
        between_runs(rig, state);
        // A new `h` (from the host or a preset): a new tick period.
        let want = period_of(S::step_of(rig.params()), sysclk_hz);
        if want != ticker.period() && !matches!(state, RigState::Running) {
            ticker.set_period(want);
            #[cfg(feature = "link")]
            session.set_period(want);
        }
    }
}

/// SysTick as the loop's clock (every board binding's, for either rig: [`serve`]): it wraps every
/// period, each wrap starts one tick; the time a tick took is read from SysTick, and (with `log`)
/// the real-time margin recorded.
pub struct Ticker {
    syst: SYST,
    period: u32,
    /// The previous tick overran its period: the wrap that starts the next one has happened (and
    /// reading it cleared the flag), so the next tick starts at once.
    late: bool,
    #[cfg(feature = "log")]
    margin: Margin,
}

impl Ticker {
    /// SysTick started on a period of `period` cycles ([`period_of`]: at least [`MIN_PERIOD`];
    /// 0 would be SysTick's longest, [`systick::MASK`] + 1).
    pub fn start(mut syst: SYST, period: u32) -> Self {
        systick::start(&mut syst, period.wrapping_sub(1));
        Self {
            syst,
            period,
            late: false,
            #[cfg(feature = "log")]
            margin: Margin::default(),
        }
    }

    /// The period (cycles).
    #[inline]
    pub const fn period(&self) -> u32 {
        self.period
    }

    /// SysTick restarted on a period of `period` cycles (between runs; as [`Self::start`]).
    pub fn set_period(&mut self, period: u32) {
        self.period = period;
        systick::start(&mut self.syst, period.wrapping_sub(1));
    }

    /// Whether the next tick is due: SysTick has wrapped since the last poll, or at once after a
    /// tick that overran. The loop polls it while waiting (servicing a port meanwhile).
    #[inline]
    pub fn due(&mut self) -> bool {
        self.late || self.syst.has_wrapped()
    }

    /// Runs `tick`, timed: its result and the cycles it took (an overrun counted a period
    /// longer), recorded in the margin with `log`. SysTick's flag holds one wrap: a tick of
    /// several periods (the stack rig's first falling step) is counted as an overrun, but read as
    /// less than two periods.
    #[inline]
    pub fn time<T>(&mut self, tick: impl FnOnce() -> T) -> (T, u32) {
        let start = systick::now();
        let result = tick();
        let end = systick::now();
        // The counter counts down from `period - 1` and reloads at 0: the difference of the two
        // readings is taken modulo the period (a later reading above the earlier one has wrapped
        // between them). SysTick wrapped during the tick: it overran, and that difference is only
        // its excess over one period (a tick of 1.2 periods read as 0.2), counted a period
        // longer: exact for a tick shorter than two periods (a longer one is read as under two:
        // SysTick's flag holds one wrap); one that started late and crossed a boundary in less
        // than a period is counted a period longer too. A wrap in the few cycles between
        // the second reading and the flag's counts the tick a period longer: an overrun reported,
        // never one missed.
        self.late = self.syst.has_wrapped();
        let within = if end <= start { start - end } else { start.saturating_add(self.period) - end };
        let used = within.saturating_add(if self.late { self.period } else { 0 });
        #[cfg(feature = "log")]
        self.margin.record(used, self.late, self.period);
        (result, used)
    }
}

/// The start button between runs, on every rig: until the run has ended, the press that starts
/// (or started) it is spent, so that one still held when the run ends is that press, not the next
/// one (which must follow a release): taken as a new press, it would reset a run that faulted in its
/// first step while the button was still down.
pub struct RestartButton(PressDetector);

impl RestartButton {
    /// Debounced over [`DEBOUNCE_TICKS`].
    pub const fn new() -> Self {
        Self(PressDetector::new(DEBOUNCE_TICKS))
    }

    /// One sample per tick: `ended` whether the run has ended (finished or faulted), `pressed`
    /// reads the start button; `true` on the tick a new press asks to reset the ended run.
    #[inline]
    pub fn sample(&mut self, ended: bool, pressed: impl FnOnce() -> bool) -> bool {
        if ended {
            self.0.sample(pressed())
        } else {
            self.0.spend_press();
            false
        }
    }
}

/// The meter-stick rig's buttons between runs: the preset button cycles the presets (shown on
/// finger 1's lights), the start button resets a finished run (the next press starts it).
pub struct Buttons {
    preset: Preset,
    preset_press: PressDetector,
    restart: RestartButton,
}

impl Buttons {
    /// The slow preset selected (the rig's at boot, [`new_rig`]).
    pub const fn new() -> Self {
        Self {
            preset: Preset::Slow,
            preset_press: PressDetector::new(DEBOUNCE_TICKS),
            restart: RestartButton::new(),
        }
    }

    /// One sample per tick, after it: `state` the rig's, `preset_pressed` the preset button
    /// (`true`: pressed).
    pub fn between_runs<B, P, D>(
        &mut self,
        rig: &mut MeterStickRig<B, P, D, 6>,
        state: RigState,
        preset_pressed: bool,
    ) where
        B: InputPin<Error = Infallible>,
        P: OutputPin<Error = Infallible>,
        D: DelayNs,
    {
        // Pins on these HALs cannot fail (`Infallible`). A preset the rig cannot perform at the
        // current step (the fast one on the Black Pill's carriage) is refused by the rig and
        // skipped: the lights show the preset that is loaded, or none changes.
        if self.preset_press.sample(preset_pressed) && !matches!(state, RigState::Running) {
            let mut next = self.preset;
            for _ in 0..Preset::ALL.len() {
                next = next.next();
                if rig.reset(next.params(rig.params().step)).is_ok() {
                    self.preset = next;
                    let _ = rig.indicate(Some(next.index()));
                    break;
                }
            }
        }
        let ended = matches!(state, RigState::Finished(_) | RigState::Fault(_));
        if self.restart.sample(ended, || rig.start_pressed().unwrap_or(false)) {
            let _ = rig.reset(*rig.params());
        }
    }
}

/// The real-time margin: the worst tick and the ticks that overran their period.
#[cfg(feature = "log")]
#[derive(Default)]
struct Margin {
    worst: u32,
    overruns: u32,
    ticks: u32,
}

#[cfg(feature = "log")]
impl Margin {
    /// Records a tick that took `used` cycles (`overran`: SysTick wrapped during it), and logs
    /// the margin once a second (at h = 1 ms).
    fn record(&mut self, used: u32, overran: bool, period: u32) {
        self.worst = self.worst.max(used);
        self.overruns += u32::from(overran);
        self.ticks += 1;
        if self.ticks == STEP_HZ {
            self.ticks = 0;
            defmt::info!(
                "real time: worst tick {=u32} of {=u32} cycles ({=u32}% used), {=u32} overruns",
                self.worst,
                period,
                self.worst * 100 / period.max(1),
                self.overruns
            );
        }
    }
}

/// Stops here for good (a board that cannot start).
pub fn halt() -> ! {
    loop {
        cortex_m::asm::nop();
    }
}
