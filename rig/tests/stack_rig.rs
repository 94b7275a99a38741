//! The stack rig (`meterstick_rig::StackRig`: the one rig state machine over the 3-block stack) against
//! `embedded-hal-mock` pins: the default stack holds with every interface sticking, one beyond the
//! critical overhang falls with its interfaces tipping, the exact light transitions of both runs
//! (from the scene run beside the rig), the debounced start, stop and reset, the parameters it
//! refuses before touching a pin, and a failed or non-finite step as a fault.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

use embedded_hal_mock::eh1::digital::{Mock as PinMock, State, Transaction as T};
use meterstick_core::ParamError;
use meterstick_core::multibody::scenes::{MultibodyScene, Stack3, StackParams};
use meterstick_core::multibody::{StepError, SystemStepReport};
use meterstick_core::planar::{BodyState, ContactMode, Direction};
use meterstick_core::scene::Outcome;
use meterstick_rig::{
    InterfaceMode, ModeLights, NoActuator, Rig, RigConfig, RigError, RigFault, RigPins, RigScene, RigState,
    StackRig, Unperformable,
};

/// One button sample starts a run (the mocks list every read); any step.
const CONFIG: RigConfig = RigConfig { debounce_ticks: 1, ..RigConfig::default_rig() };

/// The lights (sticking, sliding, separated) an interface's candidates call for, by the rule the
/// rig documents, written out here: sliding if one slides; else by the touching candidates:
/// none separated, one tipping (sticking and separated), more sticking.
fn lights_for(candidates: [ContactMode; 4]) -> [bool; 3] {
    if candidates.iter().any(|m| m.is_sliding()) {
        return [false, true, false];
    }
    match candidates.iter().filter(|m| m.is_touching()).count() {
        0 => [false, false, true],
        1 => [true, false, true],
        _ => [true, false, false],
    }
}

/// Every pin's expected transactions, and the mocks (clones share their expectations).
struct Mocks<const I: usize> {
    start: PinMock,
    fault: PinMock,
    lights: [[PinMock; 3]; I],
}

/// The transactions of pins that start low (driven low by `new`) and then show `sets` in turn.
struct Expect<const I: usize> {
    button: Vec<T>,
    fault: Vec<T>,
    lights: [[Vec<T>; 3]; I],
    shown: [[bool; 3]; I],
}

impl<const I: usize> Expect<I> {
    fn new() -> Self {
        Self {
            button: vec![],
            fault: vec![T::set(State::Low)],
            lights: std::array::from_fn(|_| std::array::from_fn(|_| vec![T::set(State::Low)])),
            shown: [[false; 3]; I],
        }
    }

    /// The interfaces' lights become `sets`: each light that changes, one transaction.
    fn show(&mut self, sets: [[bool; 3]; I]) {
        for ((pins, shown), set) in self.lights.iter_mut().zip(&mut self.shown).zip(sets) {
            for ((pin, was), now) in pins.iter_mut().zip(shown.iter_mut()).zip(set) {
                if *was != now {
                    pin.push(T::set(if now { State::High } else { State::Low }));
                    *was = now;
                }
            }
        }
    }

    fn mocks(&self) -> Mocks<I> {
        Mocks {
            start: PinMock::new(&self.button),
            fault: PinMock::new(&self.fault),
            lights: std::array::from_fn(|i| std::array::from_fn(|l| PinMock::new(&self.lights[i][l]))),
        }
    }
}

impl<const I: usize> Mocks<I> {
    fn pins(&self) -> RigPins<PinMock, PinMock, I> {
        RigPins {
            start: self.start.clone(),
            lights: std::array::from_fn(|i| {
                let [sticking, sliding, separated] = self.lights[i].clone();
                ModeLights { sticking, sliding, separated }
            }),
            fault: self.fault.clone(),
        }
    }

    /// Every expectation was consumed (and no other call was made: the mocks fail on one).
    fn done(mut self) {
        self.start.done();
        self.fault.done();
        for pin in self.lights.iter_mut().flatten() {
            pin.done();
        }
    }
}

/// The scene's modes before the first step and after each step, run directly (no rig), and its
/// outcome.
fn reference_run(params: StackParams<f32>) -> (Vec<[[ContactMode; 4]; 3]>, Outcome) {
    let mut scene = Stack3::<f32>::new(params).unwrap();
    let mut modes = vec![*scene.stepper().modes()];
    while let Some(report) = scene.step() {
        modes.push(report.modes);
    }
    (modes, scene.outcome().unwrap())
}

/// Runs a stack rig on mocks that expect exactly the light transitions of the reference run; the
/// button pressed on the first tick. Returns the rig's end state, the steps it reported and the
/// lights it ends with.
fn run_against_reference(params: StackParams<f32>) -> (RigState, Outcome, usize, [[bool; 3]; 3]) {
    let (modes, outcome) = reference_run(params);
    let mut e = Expect::<3>::new();
    e.button = vec![T::get(State::Low)];
    for m in &modes {
        e.show(m.map(lights_for));
    }
    let mocks = e.mocks();
    let mut rig = StackRig::new(params, CONFIG, mocks.pins(), NoActuator).unwrap();
    assert_eq!(rig.tick().unwrap(), RigState::Running, "the press starts the run");
    let mut reported = Vec::new();
    let state = loop {
        let s = rig.tick_with(|r| reported.push(r.modes)).unwrap();
        if s != RigState::Running {
            break s;
        }
        assert!(reported.len() <= 20_000, "no outcome in 20,000 steps");
    };
    assert_eq!(reported, modes[1..], "the rig steps the scene as it runs alone");
    // Finished: further ticks touch no pin (the mocks would fail).
    for _ in 0..3 {
        assert_eq!(rig.tick().unwrap(), state);
    }
    let shown = rig.shown().map(|m| m.unwrap().lights_for_test());
    drop(rig);
    mocks.done();
    (state, outcome, reported.len(), shown)
}

/// The lights an [`InterfaceMode`] shows, as the test writes them.
trait LightsForTest {
    fn lights_for_test(self) -> [bool; 3];
}

impl LightsForTest for InterfaceMode {
    fn lights_for_test(self) -> [bool; 3] {
        match self {
            InterfaceMode::Sticking => [true, false, false],
            InterfaceMode::Sliding(_) => [false, true, false],
            InterfaceMode::Tipping => [true, false, true],
            InterfaceMode::Separated => [false, false, true],
        }
    }
}

#[test]
fn the_default_stack_holds_with_every_interface_sticking() {
    let params = StackParams::<f32>::default();
    assert_eq!(params.overhang, 0.98, "the catalogue's default stack, 2 % inside the critical overhang");
    let (state, outcome, steps, shown) = run_against_reference(params);
    assert_eq!(outcome, Outcome::Held);
    assert_eq!(state, RigState::Finished(Outcome::Held));
    assert_eq!(steps, 10_000, "max_time 10 s at h = 1 ms");
    assert_eq!(shown, [[true, false, false]; 3], "every interface ends sticking, nothing else lit");
}

#[test]
fn the_stack_beyond_the_critical_overhang_falls_and_its_interfaces_leave_sticking() {
    let params = StackParams::<f32> { overhang: 1.02, ..StackParams::default() };
    let (modes, _) = reference_run(params);
    assert_eq!(modes[0].map(lights_for), [[true, false, false]; 3], "it starts resting flat");
    let (state, outcome, steps, shown) = run_against_reference(params);
    assert_eq!(outcome, Outcome::Fell);
    assert_eq!(state, RigState::Finished(Outcome::Fell));
    assert!(steps < 1_000, "it falls within a second: {steps} steps");
    // Falling over the edge, every block pivots about one corner: each interface tips.
    assert_eq!(shown, [[true, false, true]; 3], "every interface ends tipping");
}

/// The headless stack rig (what QEMU runs): its pins count each light's rises.
#[test]
fn the_headless_stack_rig_falls_with_each_interface_tipping_once() {
    let params = StackParams::<f32> { overhang: 1.02, ..StackParams::default() };
    let mut rig = StackRig::headless(params, CONFIG).unwrap();
    let mut ticks = 0;
    let state = loop {
        let s = rig.tick().unwrap();
        ticks += 1;
        if !matches!(s, RigState::WaitingForStart | RigState::Running) || ticks > 1_000 {
            break s;
        }
    };
    assert_eq!(state, RigState::Finished(Outcome::Fell));
    assert_eq!(ticks, 1 + 200, "the press, then 200 steps");
    let (pins, NoActuator) = rig.release();
    assert_eq!(pins.fault.rises(), 0);
    for (i, l) in pins.lights.iter().enumerate() {
        // Sticking at the start; from the first step on one corner: the separated light joins.
        let rises = [l.sticking.rises(), l.sliding.rises(), l.separated.rises()];
        assert_eq!(rises, [1, 0, 1], "interface {i}");
    }
}

#[test]
fn interface_modes_follow_the_candidates() {
    use ContactMode::{Separated as X, Sliding, Sticking as S};
    assert_eq!(InterfaceMode::of([S, X, X, S]), InterfaceMode::Sticking);
    assert_eq!(InterfaceMode::of([S, S, S, S]), InterfaceMode::Sticking);
    assert_eq!(InterfaceMode::of([X, X, X, S]), InterfaceMode::Tipping);
    assert_eq!(InterfaceMode::of([X; 4]), InterfaceMode::Separated);
    let slide = Sliding(Direction::Minus);
    assert_eq!(InterfaceMode::of([S, X, slide, S]), InterfaceMode::Sliding(Direction::Minus));
    assert_eq!(InterfaceMode::of([X, X, slide, X]), InterfaceMode::Sliding(Direction::Minus));
    for (mode, name) in [
        (InterfaceMode::Sticking, "sticking"),
        (InterfaceMode::Sliding(Direction::Plus), "sliding+"),
        (InterfaceMode::Tipping, "tipping"),
        (InterfaceMode::Separated, "separated"),
    ] {
        assert_eq!(mode.name(), name);
    }
}

#[test]
fn a_debounced_press_starts_and_stop_and_reset_behave() {
    let params = StackParams::<f32>::default();
    let config = RigConfig { debounce_ticks: 3, ..CONFIG };
    let (h, l) = (T::get(State::High), T::get(State::Low));
    let mut e = Expect::<3>::new();
    // A bounce (two lows) does not start; three lows do, on the third.
    e.button = vec![h.clone(), l.clone(), l.clone(), h.clone(), l.clone(), l.clone(), l.clone()];
    let sticking = [[true, false, false]; 3];
    e.show(sticking);
    // stop(): nothing changes on the pins. A refused reset: nothing either. reset(): lights off,
    // fault low.
    e.show([[false; 3]; 3]);
    e.fault.push(T::set(State::Low));
    // The press that was held through the reset is spent: held (three lows), released (three
    // highs), pressed again (three lows): the run starts on the last.
    e.button.extend([l.clone(), l.clone(), l.clone(), h.clone(), h.clone(), h, l.clone(), l.clone(), l]);
    e.show(sticking);
    // A second reset, then a start on command (no button read).
    e.show([[false; 3]; 3]);
    e.fault.push(T::set(State::Low));
    e.show(sticking);
    let mocks = e.mocks();
    let mut rig = StackRig::new(params, config, mocks.pins(), NoActuator).unwrap();

    for tick in 1..=6 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart, "tick {tick}");
    }
    assert_eq!(rig.shown(), &[None; 3], "no light before the start");
    assert_eq!(rig.tick().unwrap(), RigState::Running);
    assert_eq!(rig.shown(), &[Some(InterfaceMode::Sticking); 3]);
    assert!(!rig.start().unwrap(), "already running");
    for _ in 0..5 {
        assert_eq!(rig.tick().unwrap(), RigState::Running);
    }
    assert_eq!(rig.scene().stats().steps, 5);
    assert!(rig.stop().unwrap());
    assert_eq!(rig.state(), RigState::Finished(Outcome::Unfinished));
    assert!(!rig.stop().unwrap(), "nothing to stop");
    assert!(!rig.start().unwrap(), "a finished run starts only after a reset");
    assert_eq!(rig.tick().unwrap(), RigState::Finished(Outcome::Unfinished));
    assert_eq!(rig.scene().stats().steps, 5, "a finished rig does not step");
    assert_eq!(rig.shown(), &[Some(InterfaceMode::Sticking); 3], "the lights keep the last modes");

    let bad = StackParams { mu_kinetic: 0.6, ..params };
    assert_eq!(rig.reset(bad), Err(RigError::Params(ParamError::KineticAboveStatic)));
    assert_eq!(rig.state(), RigState::Finished(Outcome::Unfinished), "a refused reset changes nothing");
    let taller = StackParams { height: 0.06, ..params };
    rig.reset(taller).unwrap();
    assert_eq!(rig.state(), RigState::WaitingForStart);
    assert_eq!(rig.params(), &taller);
    assert_eq!(rig.scene().stats().steps, 0, "a new scene");
    assert_eq!(rig.shown(), &[None; 3]);
    for tick in 1..=8 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart, "tick {tick} after the reset");
    }
    assert_eq!(rig.tick().unwrap(), RigState::Running);

    rig.reset(params).unwrap();
    assert!(rig.start().unwrap(), "a start on command");
    assert_eq!(rig.state(), RigState::Running);
    drop(rig);
    mocks.done();
}

/// After a reset the button must read released before a press starts a run, even when the
/// previous run was started on command (the debouncer never saw that press).
#[test]
fn a_reset_needs_the_button_released_before_a_press_starts() {
    let (h, l) = (T::get(State::High), T::get(State::Low));
    let mut e = Expect::<3>::new();
    e.show([[true, false, false]; 3]);
    e.show([[false; 3]; 3]);
    e.fault.push(T::set(State::Low));
    e.button = vec![l.clone(), l.clone(), h, l];
    e.show([[true, false, false]; 3]);
    let mocks = e.mocks();
    let mut rig = StackRig::new(StackParams::default(), CONFIG, mocks.pins(), NoActuator).unwrap();
    assert!(rig.start().unwrap());
    assert!(rig.stop().unwrap());
    rig.reset(StackParams::default()).unwrap();
    for tick in 1..=3 {
        assert_eq!(rig.tick().unwrap(), RigState::WaitingForStart, "tick {tick}: held, released");
    }
    assert_eq!(rig.tick().unwrap(), RigState::Running, "pressed again");
    drop(rig);
    mocks.done();
}

/// While waiting, a small number shows on interface 0's lights; the start replaces it with the
/// modes, and in other states it is ignored.
#[test]
fn indicate_shows_a_number_on_the_first_interface_while_waiting() {
    let mut e = Expect::<3>::new();
    e.show([[false, true, false], [false; 3], [false; 3]]);
    e.show([[false, false, true], [false; 3], [false; 3]]);
    e.show([[true, false, false]; 3]);
    let mocks = e.mocks();
    let mut rig = StackRig::new(StackParams::default(), CONFIG, mocks.pins(), NoActuator).unwrap();
    rig.indicate(Some(1)).unwrap();
    rig.indicate(Some(1)).unwrap();
    assert_eq!(rig.shown()[0], Some(InterfaceMode::Sliding(Direction::Plus)));
    rig.indicate(Some(2)).unwrap();
    assert!(rig.start().unwrap());
    rig.indicate(Some(0)).unwrap();
    assert_eq!(rig.shown(), &[Some(InterfaceMode::Sticking); 3], "ignored while running");
    drop(rig);
    mocks.done();
}

#[test]
fn invalid_parameters_are_refused_before_any_pin_is_touched() {
    let ok = StackParams::<f32>::default();
    let config = RigConfig { max_step: 2e-3, ..CONFIG };
    let cases = [
        (StackParams { overhang: 6.0, ..ok }, RigError::Params(ParamError::OutOfRange("overhang"))),
        (StackParams { mu_kinetic: 0.6, ..ok }, RigError::Params(ParamError::KineticAboveStatic)),
        (StackParams { mass: -1.0, ..ok }, RigError::Params(ParamError::NotPositive("mass"))),
        (StackParams { step: f32::NAN, ..ok }, RigError::Params(ParamError::NonFinite("step"))),
        (StackParams { step: 5e-3, ..ok }, RigError::Unperformable(Unperformable::Step)),
    ];
    for (params, expected) in cases.clone() {
        // No transaction expected: any pin call would fail the mock.
        let mocks = Expect::<3> {
            button: vec![],
            fault: vec![],
            lights: std::array::from_fn(|_| std::array::from_fn(|_| vec![])),
            shown: [[false; 3]; 3],
        }
        .mocks();
        let refused = StackRig::new(params, config, mocks.pins(), NoActuator);
        assert_eq!(refused.err(), Some(expected), "{params:?}");
        mocks.done();
    }
    // The same sets, refused by a rig that runs: it stays as it was.
    let e = Expect::<3>::new();
    let mocks = e.mocks();
    let mut rig = StackRig::new(ok, config, mocks.pins(), NoActuator).unwrap();
    assert_eq!(
        rig.reset(StackParams { step: 5e-3, ..ok }),
        Err(RigError::Unperformable(Unperformable::Step))
    );
    assert_eq!(rig.reset(StackParams { overhang: 6.0, ..ok }).err(), Some(cases[0].1.clone()));
    assert_eq!(rig.params(), &ok);
    drop(rig);
    mocks.done();
}

/// A scene of one block on the table that steps at rest (two corners sticking) until step
/// `fail_at`, where it fails as `failure` says: the rig's fault path.
#[derive(Debug)]
struct Failing {
    params: FailAt,
    steps: u32,
    outcome: Option<Outcome>,
    states: [BodyState<f32>; 1],
    modes: [[ContactMode; 4]; 1],
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct FailAt {
    step: u32,
    failure: Failure,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Failure {
    /// The step fails in the core (`Outcome::Failed`).
    Solver,
    /// The step reports a NaN state without failing.
    NonFiniteState,
}

impl RigScene<1> for Failing {
    type Params = FailAt;
    type Report = SystemStepReport<f32, 1, 1>;
    type Mode = InterfaceMode;
    const LIGHT: &'static str = "interface";
    const FIRST_LIGHT: usize = 0;

    fn build(params: FailAt) -> Result<Self, ParamError> {
        if params.step == 0 {
            return Err(ParamError::OutOfRange("step"));
        }
        let s = ContactMode::Sticking;
        let x = ContactMode::Separated;
        Ok(Self {
            params,
            steps: 0,
            outcome: None,
            states: [BodyState::at_rest(0.0, 0.025, 0.0)],
            modes: [[s, x, x, s]],
        })
    }
    fn check(config: &RigConfig, _: &FailAt) -> Result<(), Unperformable> {
        config.check_step(1e-3)
    }
    fn params(&self) -> &FailAt {
        &self.params
    }
    fn step_of(_: &FailAt) -> f32 {
        1e-3
    }
    fn advance(&mut self) -> Option<SystemStepReport<f32, 1, 1>> {
        if self.outcome.is_some() {
            return None;
        }
        self.steps += 1;
        let mut states = self.states;
        if self.steps == self.params.step {
            match self.params.failure {
                Failure::Solver => {
                    self.outcome = Some(Outcome::Failed(StepError::TooManyContacts(9)));
                    return None;
                }
                Failure::NonFiniteState => states[0].vy = f32::NAN,
            }
        }
        Some(SystemStepReport {
            time: self.steps as f32 * 1e-3,
            states,
            interface_forces: [[0.0; 2]],
            corner_loads: [[[0.0; 2]; 4]],
            modes: self.modes,
            active: 2,
            pivots: 0,
        })
    }
    fn finite(report: &SystemStepReport<f32, 1, 1>) -> bool {
        report.states.iter().all(BodyState::is_finite)
    }
    fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }
    fn time(&self) -> f32 {
        self.steps as f32 * 1e-3
    }
    fn start_modes(&self) -> [InterfaceMode; 1] {
        self.modes.map(InterfaceMode::of)
    }
    fn modes_of(report: &SystemStepReport<f32, 1, 1>) -> [InterfaceMode; 1] {
        report.modes.map(InterfaceMode::of)
    }
}

#[test]
fn a_failed_or_non_finite_step_is_a_fault_with_the_lights_off_and_no_panic() {
    for (failure, fault) in
        [(Failure::Solver, StepError::TooManyContacts(9)), (Failure::NonFiniteState, StepError::NonFinite)]
    {
        let mut e = Expect::<1>::new();
        e.button = vec![T::get(State::Low)];
        e.show([[true, false, false]]);
        e.show([[false; 3]]);
        e.fault.push(T::set(State::High));
        // A reset clears the fault.
        e.fault.push(T::set(State::Low));
        let mocks = e.mocks();
        let params = FailAt { step: 4, failure };
        let mut rig = Rig::<Failing, _, _, _, 1>::new(params, CONFIG, mocks.pins(), NoActuator).unwrap();
        assert_eq!(rig.tick().unwrap(), RigState::Running);
        let mut observed = 0;
        for _ in 0..3 {
            assert_eq!(rig.tick_with(|_| observed += 1).unwrap(), RigState::Running);
        }
        let state = rig.tick_with(|_| observed += 1).unwrap();
        assert_eq!(state, RigState::Fault(RigFault::Step(fault)), "{failure:?}");
        assert_eq!(observed, 3, "the failed step is not reported");
        assert_eq!(rig.shown(), &[None], "mode lights off");
        for _ in 0..3 {
            assert_eq!(rig.tick().unwrap(), state, "it stays in the fault, touching no pin");
        }
        rig.reset(params).unwrap();
        assert_eq!(rig.state(), RigState::WaitingForStart);
        drop(rig);
        mocks.done();
    }
}

/// The catalogue's stack, held for its 10 s on headless pins: each interface's sticking light
/// rises once at the start and no other light ever does (the lights do not flicker at rest).
#[test]
fn the_held_stack_lights_each_interface_sticking_once_and_nothing_else() {
    let mut rig = StackRig::headless(StackParams::<f32>::default(), CONFIG).unwrap();
    let mut ticks = 0;
    let state = loop {
        let s = rig.tick().unwrap();
        ticks += 1;
        if !matches!(s, RigState::WaitingForStart | RigState::Running) || ticks > 20_000 {
            break s;
        }
    };
    assert_eq!(state, RigState::Finished(Outcome::Held));
    assert_eq!(ticks, 1 + 10_000, "the press, then 10 s of 1 ms steps");
    let (pins, NoActuator) = rig.release();
    assert_eq!(pins.fault.rises(), 0);
    for (i, l) in pins.lights.iter().enumerate() {
        let rises = [l.sticking.rises(), l.sliding.rises(), l.separated.rises()];
        assert_eq!(rises, [1, 0, 0], "interface {i}");
    }
}
