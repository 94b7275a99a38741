//! The demo rig's loop (`meterstick_rig::Rig`) against `embedded-hal-mock` pins: the exact
//! pin transitions of a short scene, the fault path, a whole run, the debounced start button and
//! the parameters the rig refuses.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

use std::cell::Cell;
use std::convert::Infallible;
use std::rc::Rc;

use embedded_hal::digital::{ErrorType, InputPin};
use embedded_hal_mock::eh1::delay::NoopDelay;
use embedded_hal_mock::eh1::digital::{Mock as PinMock, State, Transaction as T};
use meterstick_core::planar::ContactMode;
use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};
use meterstick_rig::{
    Carriage, HeadlessPin, MeterStickRig, ModeLights, NoDelay, Preset, PresetScene as _, RigConfig, RigError,
    RigFault, RigPins, RigState, Unperformable,
};

/// Finger 1 close to the eq. 21 switch (x1/x2 = 0.675 > mu_k/mu_s), moving fast: finger 2
/// starts to slide within a few steps, so a short run changes a light. 1 mm per step at
/// 1000 steps/m: one pulse per tick.
fn short_scene() -> MeterStickParams<f32> {
    MeterStickParams { finger1_x: -0.27, finger1_velocity: 1.0, ..MeterStickParams::paper() }
}

/// One button sample starts a run here (the mocks list every read); any step.
const CONFIG: RigConfig = RigConfig {
    steps_per_meter: 1000.0,
    pulse_ns: 2_000,
    max_pulses_per_tick: 10,
    button_active_low: true,
    debounce_ticks: 1,
    ..RigConfig::default_rig()
};

fn light_of(m: ContactMode) -> usize {
    match m {
        ContactMode::Sticking => 0,
        ContactMode::Sliding(_) => 1,
        ContactMode::Separated => 2,
    }
}

struct Expect {
    button: Vec<T>,
    step: Vec<T>,
    dir: Vec<T>,
    fault: Vec<T>,
    lights: [[Vec<T>; 3]; 2],
}

impl Expect {
    /// Every output driven low by `Rig::new`.
    fn new() -> Self {
        let low = || vec![T::set(State::Low)];
        Self {
            button: vec![],
            step: low(),
            dir: low(),
            fault: low(),
            lights: [[low(), low(), low()], [low(), low(), low()]],
        }
    }

    /// The rig's pins and its carriage's.
    fn pins(&self) -> (RigPins<PinMock, PinMock, 2>, Carriage<PinMock, NoopDelay>) {
        let m = |t: &Vec<T>| PinMock::new(t);
        let carriage = Carriage::new(m(&self.step), m(&self.dir), NoopDelay::new());
        let pins = RigPins {
            start: m(&self.button),
            lights: [0, 1].map(|i| ModeLights {
                sticking: m(&self.lights[i][0]),
                sliding: m(&self.lights[i][1]),
                separated: m(&self.lights[i][2]),
            }),
            fault: m(&self.fault),
        };
        (pins, carriage)
    }
}

fn done((pins, carriage): (RigPins<PinMock, PinMock, 2>, Carriage<PinMock, NoopDelay>)) {
    let RigPins { mut start, lights, mut fault } = pins;
    let (mut step, mut dir) = (carriage.step, carriage.dir);
    start.done();
    step.done();
    dir.done();
    fault.done();
    for l in lights {
        let ModeLights { mut sticking, mut sliding, mut separated } = l;
        sticking.done();
        sliding.done();
        separated.done();
    }
}

#[test]
fn a_short_scene_drives_the_expected_pin_transitions() {
    const TICKS: usize = 12;
    // What the rig must show, from the scene itself: its modes and finger 1 after each step.
    let params = short_scene();
    let mut scene = MeterStick6::<f32, 8>::new(params).unwrap();
    let initial = scene.modes();
    let steps: Vec<([ContactMode; 2], f32)> =
        (0..TICKS).map(|_| scene.step().map(|r| (r.modes(), scene.fingers()[0])).unwrap()).collect();
    assert!(
        steps.iter().any(|(m, _)| m[1].is_sliding()),
        "finger 2 should start to slide within {TICKS} steps: {steps:?}"
    );

    let mut e = Expect::new();
    // Tick 1: button not pressed (reads high); tick 2: pressed.
    e.button = vec![T::get(State::High), T::get(State::Low)];
    e.dir.push(T::set(State::High));
    let mut lit = [light_of(initial[0]), light_of(initial[1])];
    for i in 0..2 {
        e.lights[i][lit[i]].push(T::set(State::High));
    }
    let mut pulses = 0i64;
    for (modes, x1) in &steps {
        let target = ((x1 - params.finger1_x) * CONFIG.steps_per_meter).round() as i64;
        for _ in pulses..target {
            e.step.extend([T::set(State::High), T::set(State::Low)]);
        }
        pulses = pulses.max(target);
        for i in 0..2 {
            let now = light_of(modes[i]);
            if now != lit[i] {
                e.lights[i][lit[i]].push(T::set(State::Low));
                e.lights[i][now].push(T::set(State::High));
                lit[i] = now;
            }
        }
    }
    assert_eq!(pulses, i64::try_from(TICKS).unwrap(), "1 mm per step at 1000 steps/m");

    let mut rig = {
        let (pins, carriage) = e.pins();
        MeterStickRig::<_, _, _, 6>::new(params, CONFIG, pins, carriage)
    }
    .unwrap();
    assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart);
    assert_eq!(rig.tick().unwrap(), RigState::Running);
    for _ in 0..TICKS {
        assert_eq!(rig.tick().unwrap(), RigState::Running);
    }
    assert_eq!(rig.pulses(), pulses);
    done(rig.release());
}

/// 1 nm per pulse, at most 10 pulses per tick: finger 1 at 5 um/s needs 5 pulses per tick, so the
/// rig accepts it, but its position is an f32 near -0.35 m, which moves by whole ulps (30 nm):
/// 30 pulses due in one tick, more than the carriage can emit.
fn nanometre_rig() -> (MeterStickParams<f32>, RigConfig) {
    let config = RigConfig { steps_per_meter: 1e9, max_pulses_per_tick: 10, ..CONFIG };
    let params = MeterStickParams { finger1_x: -0.35, finger1_velocity: 5e-6, ..MeterStickParams::paper() };
    (params, config)
}

#[test]
fn an_actuator_overrun_is_a_fault_with_the_fault_light_on_and_no_panic() {
    // The limit is checked up front: a carriage that cannot follow at all is refused.
    let slow = RigConfig { max_pulses_per_tick: 0, ..CONFIG };
    let refused = MeterStickRig::<_, _, _, 6>::headless(short_scene(), slow, NoDelay);
    assert!(matches!(refused, Err(RigError::Unperformable(Unperformable::Finger1TooFast))));
    // An overrun that gets past the check (a position quantised coarser than a pulse) is a fault.
    let (params, config) = nanometre_rig();
    let initial = MeterStick6::<f32, 8>::new(params).unwrap().modes();
    let mut e = Expect::new();
    e.button = vec![T::get(State::Low)];
    e.dir.push(T::set(State::High));
    for i in 0..2 {
        let l = light_of(initial[i]);
        e.lights[i][l].extend([T::set(State::High), T::set(State::Low)]); // on at start, off at the fault
    }
    e.fault.push(T::set(State::High));
    let mut rig = {
        let (pins, carriage) = e.pins();
        MeterStickRig::<_, _, _, 6>::new(params, config, pins, carriage)
    }
    .unwrap();
    assert_eq!(rig.tick().unwrap(), RigState::Running);
    let fault = RigState::Fault(RigFault::ActuatorOverrun);
    let mut ticks = 0;
    while rig.tick().unwrap() == RigState::Running {
        ticks += 1;
        assert!(ticks < 10, "no overrun within 10 steps");
    }
    assert_eq!(rig.state(), fault);
    // It stays there and touches no pin (the mocks would fail on an unexpected call).
    for _ in 0..5 {
        assert_eq!(rig.tick().unwrap(), fault);
    }
    assert_eq!(rig.pulses(), 0);
    done(rig.release());
}

#[test]
fn a_whole_slow_run_balances_and_the_carriage_travels_with_the_finger() {
    let params = MeterStickParams::<f32> { finger1_x: -0.35, ..MeterStickParams::paper() };
    let config = RigConfig::default_rig();
    let mut rig = MeterStickRig::<_, _, _, 6>::headless(params, config, NoDelay).unwrap();
    let mut ticks = 0;
    let state = loop {
        let s = rig.tick().unwrap();
        ticks += 1;
        if matches!(s, RigState::Finished(_) | RigState::Fault(_)) || ticks > 100_000 {
            break s;
        }
    };
    assert_eq!(state, RigState::Finished(Outcome::Balanced));
    let travel = rig.scene().fingers()[0] - params.finger1_x;
    assert_eq!(rig.pulses(), (travel * config.steps_per_meter).round() as i64);
    assert_eq!(rig.pulses(), 59_200, "0.74 m at 80 steps/mm");
    let switches = rig.scene().events().len() as u32 + rig.scene().events_dropped();
    let (pins, carriage) = rig.release();
    assert_eq!(carriage.step.rises(), 59_200);
    assert_eq!(pins.fault.rises(), 0);
    // Each finger's light changes at its switches: as many rises in all as mode changes
    // between light classes, plus the two lit at the start.
    let rises: u32 =
        pins.lights.iter().map(|l| l.sticking.rises() + l.sliding.rises() + l.separated.rises()).sum();
    assert!(rises >= 2 + 8 && rises <= 2 + switches, "{rises} light rises for {switches} switch events");
}

/// Runs on demand: a finished run is reset (the carriage driven back at most
/// `max_pulses_per_tick` pulses per tick, DIR low, no start meanwhile), started by command,
/// stopped by command; refused parameters leave the rig as it was.
#[test]
fn reset_homes_the_carriage_and_runs_start_and_stop_on_demand() {
    let config =
        RigConfig { steps_per_meter: 10_000.0, max_pulses_per_tick: 1_000, ..RigConfig::default_rig() };
    let fast = Preset::Fast.params(1e-3);
    let mut rig = MeterStickRig::<_, _, _, 6>::headless(fast, config, NoDelay).unwrap();
    let mut steps = 0u64;
    let state = loop {
        let s = rig.tick_with(|_| steps += 1).unwrap();
        if matches!(s, RigState::Finished(_) | RigState::Fault(_)) {
            break s;
        }
    };
    assert_eq!(state, RigState::Finished(Outcome::Fell));
    assert_eq!(steps, rig.scene().stats().steps, "tick_with reports every step once");
    let out = rig.pulses();
    assert!(out > 2_000, "the carriage travelled {out} pulses");
    // A refused parameter set changes nothing.
    let bad = MeterStickParams { mu_kinetic: 0.9, ..fast };
    assert!(matches!(rig.reset(bad), Err(RigError::Params(_))));
    assert_eq!(rig.state(), state);
    // Reset: back to waiting, the carriage homes at 1,000 pulses per tick; no start meanwhile
    // (and the headless button, always pressed, must be released first).
    rig.reset(Preset::Slow.params(1e-3)).unwrap();
    assert_eq!(rig.state(), RigState::WaitingForStart);
    assert!(rig.homing());
    assert!(!rig.start().unwrap(), "no start while homing");
    let mut ticks = 0;
    while rig.homing() {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart);
        ticks += 1;
    }
    assert_eq!(ticks, (out + 999) / 1_000, "{out} pulses back at 1,000 a tick");
    assert_eq!(rig.pulses(), 0);
    for _ in 0..3 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart, "the held button does not restart");
    }
    assert_eq!(*rig.params(), Preset::Slow.params(1e-3));
    // Start and stop on command.
    assert!(rig.start().unwrap());
    for _ in 0..10 {
        assert_eq!(rig.tick().unwrap(), RigState::Running);
    }
    assert!(rig.stop().unwrap());
    assert_eq!(rig.state(), RigState::Finished(Outcome::Unfinished));
    assert!(!rig.stop().unwrap());
    let run = rig.pulses();
    assert_eq!(run, 10, "10 steps of 0.1 mm at 0.1 mm per pulse");
    let (_, carriage) = rig.release();
    assert_eq!(
        i64::from(carriage.step.rises()),
        2 * out + run,
        "out and back, then the stopped run's pulses"
    );
}

#[test]
fn presets_and_the_press_detector() {
    use meterstick_rig::PressDetector;
    let outcomes: Vec<Outcome> =
        Preset::ALL.iter().map(|p| MeterStick6::<f32, 8>::new(p.params(1e-3)).unwrap().run(|_| {})).collect();
    assert_eq!(outcomes, [Outcome::Balanced, Outcome::Fell, Outcome::Balanced]);
    assert_eq!(Preset::Slow.next().next().next(), Preset::Slow);
    assert_eq!(Preset::ALL.map(Preset::index), [0, 1, 2]);
    // 3 equal samples to change state; bounces do not count; one press per press.
    let mut d = PressDetector::new(3);
    let samples = [true, false, true, true, true, true, true, false, false, false, true, true, true];
    let presses: Vec<usize> =
        samples.iter().enumerate().filter_map(|(i, &s)| d.sample(s).then_some(i)).collect();
    assert_eq!(presses, [4, 12]);
    // A spent press (the one that started a run) held on is not a new one; after a release it is.
    let mut d = PressDetector::new(3);
    d.spend_press();
    let held = [true, true, true, true, false, false, false, true, true, true];
    let presses: Vec<usize> =
        held.iter().enumerate().filter_map(|(i, &s)| d.sample(s).then_some(i)).collect();
    assert_eq!(presses, [9]);
}

/// A start button the test presses and releases (`true`: pressed; active low: reads low).
#[derive(Clone, Default)]
struct Button(Rc<Cell<bool>>);

impl ErrorType for Button {
    type Error = Infallible;
}

impl InputPin for Button {
    fn is_high(&mut self) -> Result<bool, Infallible> {
        Ok(!self.0.get())
    }
    fn is_low(&mut self) -> Result<bool, Infallible> {
        Ok(self.0.get())
    }
}

fn rig_with_button(config: RigConfig) -> (MeterStickRig<Button, HeadlessPin, NoDelay, 6>, Rc<Cell<bool>>) {
    let button = Button::default();
    let pressed = Rc::clone(&button.0);
    let lights = || ModeLights {
        sticking: HeadlessPin::default(),
        sliding: HeadlessPin::default(),
        separated: HeadlessPin::default(),
    };
    let pins = RigPins { start: button, lights: [lights(), lights()], fault: HeadlessPin::default() };
    let carriage = Carriage::new(HeadlessPin::default(), HeadlessPin::default(), NoDelay);
    (MeterStickRig::new(Preset::Slow.params(1e-3), config, pins, carriage).unwrap(), pressed)
}

/// The start button is debounced while waiting (`debounce_ticks` equal samples): a glitch at
/// boot does not start a run, nor does the release bounce of the press that reset one; a
/// steady press does, on its `debounce_ticks`-th sample. (The rig read it raw: a single
/// "pressed" sample started a run.)
#[test]
fn a_start_needs_a_debounced_press() {
    let config = RigConfig::default_rig();
    assert_eq!(config.debounce_ticks, 20);
    let (mut rig, pressed) = rig_with_button(config);
    // Boot: a one-tick glitch, then a two-tick one.
    for glitch in [&[true][..], &[true, true]] {
        for &p in glitch {
            pressed.set(p);
            assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart, "a glitch started a run");
        }
        pressed.set(false);
        for _ in 0..3 {
            assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart);
        }
    }
    // A steady press starts the run on its 20th sample.
    pressed.set(true);
    for _ in 1..20 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart);
    }
    assert_eq!(rig.tick().unwrap(), RigState::Running);
    for _ in 0..10 {
        rig.tick().unwrap();
    }
    rig.stop().unwrap();
    // A press held through the reset, then released with a bounce: no start.
    rig.reset(*rig.params()).unwrap();
    while rig.homing() {
        rig.tick().unwrap();
    }
    for p in [true, true, false, true, true, false, false, true, false, false, false] {
        pressed.set(p);
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart, "a bounce started a run");
    }
    // Released for 20 samples, then pressed for 20: a start.
    pressed.set(false);
    for _ in 0..20 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart);
    }
    pressed.set(true);
    for _ in 1..20 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart);
    }
    assert_eq!(rig.tick().unwrap(), RigState::Running);
}

/// Parameters the core accepts but the rig cannot perform are refused by `Rig::new` and
/// `Rig::reset` (which then change nothing): finger 1 faster than the carriage, finger 1
/// moving away from finger 2, finger 2 moving, a step outside the board's tick range. (The rig
/// took them: the fast preset faulted at step 1, a backward or a moving finger 2 ran with no
/// pulses at all.)
#[test]
fn parameters_the_rig_cannot_perform_are_refused() {
    // The Black Pill's rig at 100 MHz: SysTick periods of 1,000 ..= 2^24 - 1 cycles.
    let config = RigConfig::default_rig().ticked_by(100_000_000, 1_000, 0x00FF_FFFF);
    assert_eq!(config.min_step, 1e-5);
    assert!((config.max_step - 0.167_772_15).abs() < 1e-8, "{}", config.max_step);
    let slow = Preset::Slow.params(1e-3);
    let unperformable = |p: MeterStickParams<f32>| -> Option<Unperformable> {
        match MeterStickRig::<_, _, _, 6>::headless(p, config, NoDelay) {
            Ok(_) => None,
            Err(RigError::Unperformable(u)) => Some(u),
            Err(e) => panic!("{e:?}"),
        }
    };
    let with = |f: fn(&mut MeterStickParams<f32>)| {
        let mut p = slow;
        f(&mut p);
        p
    };
    assert_eq!(unperformable(slow), None);
    assert_eq!(unperformable(Preset::Fast.params(1e-3)), Some(Unperformable::Finger1TooFast));
    assert_eq!(unperformable(with(|p| p.finger1_velocity = 2.0)), Some(Unperformable::Finger1TooFast));
    // 1.24 m/s is 99.2 pulses a tick, within 100 and half a pulse; 1.25 m/s is not.
    assert_eq!(unperformable(with(|p| p.finger1_velocity = 1.24)), None);
    assert_eq!(unperformable(with(|p| p.finger1_velocity = 1.25)), Some(Unperformable::Finger1TooFast));
    assert_eq!(unperformable(with(|p| p.finger1_velocity = -0.1)), Some(Unperformable::Finger1Backward));
    assert_eq!(unperformable(with(|p| p.finger1_velocity = 0.0)), None);
    assert_eq!(unperformable(with(|p| p.finger2_velocity = -0.1)), Some(Unperformable::Finger2Moves));
    assert_eq!(unperformable(with(|p| p.step = 0.5)), Some(Unperformable::Step));
    assert_eq!(unperformable(with(|p| p.step = 1e-6)), Some(Unperformable::Step));
    assert_eq!(unperformable(with(|p| p.step = 1e-5)), None);
    assert_eq!(
        unperformable(with(|p| p.step = 0.1)),
        Some(Unperformable::Finger1TooFast),
        "1,000 pulses a tick"
    );
    assert_eq!(unperformable(with(|p| (p.step, p.finger1_velocity) = (0.16, 0.005))), None);
    // A refused reset leaves the rig as it was.
    let mut rig = MeterStickRig::<_, _, _, 6>::headless(slow, config, NoDelay).unwrap();
    for _ in 0..30 {
        rig.tick().unwrap();
    }
    let state = rig.state();
    assert_eq!(state, RigState::Running, "the headless button (held) starts the run");
    rig.stop().unwrap();
    let state = rig.state();
    for bad in [Preset::Fast.params(1e-3), with(|p| p.finger2_velocity = 0.1), with(|p| p.step = 0.2)] {
        assert!(matches!(rig.reset(bad), Err(RigError::Unperformable(_))));
        assert_eq!(rig.state(), state);
        assert_eq!(*rig.params(), slow);
    }
}
