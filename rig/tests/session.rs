//! The rig's end of the host link (`meterstick_rig::session`) on the host: a headless rig and
//! an in-memory port, driven as the firmware's loop drives them (firmware/src/qemu_link.rs),
//! against the host core: the boot reports, a run on demand whose outcome, step count, checksum
//! and switch events are the host core's, the presets, refused parameters, damaged and cut
//! frames (no reply, counted), a flood of pings (every one answered, in order), stop, a port
//! that takes nothing for a while (telemetry dropped first, every report received or counted),
//! and on `embedded-hal-mock` pins, the pin operations the commands cause.
// Exact float comparisons are the point: the rig's figures must be the host core's bits.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]
#![allow(clippy::trivially_copy_pass_by_ref)] // commands as the link's `encode` takes them

mod common;

use std::collections::VecDeque;
use std::convert::Infallible;

use common::{Pipe, frame};

use meterstick_core::planar::{Checksum, ContactMode, Direction};
use meterstick_core::scene::{MeterStick6, MeterStickParams, Outcome, Scene};
use meterstick_link::{
    Command, DELIMITER, ErrorCode, MAX_FRAME, Mode, OutcomeCode, PROTOCOL_VERSION, ParamId, Preset,
    RejectReason, Report, ReportDecoder, RigState, SceneId,
};
use meterstick_rig::session::LinkScene;
use meterstick_rig::session::{MARGIN_EVERY, POLL_BYTES, Session, build_id, version};
use meterstick_rig::{
    Actuator, Carriage, HeadlessPin, MeterStickRig, NoDelay, PresetScene as _, Rig, RigConfig, RigError,
};

/// The QEMU build's rig: 1 cm per pulse, no practical limit per tick, and a start button that
/// reads released (a headless pin reads low; active high), so only `Start` starts a run.
const CONFIG: RigConfig = RigConfig {
    steps_per_meter: 100.0,
    pulse_ns: 2_000,
    max_pulses_per_tick: 1_000_000,
    button_active_low: false,
    ..RigConfig::default_rig()
};

const H: f32 = 1e-3;
const FIRMWARE: (u8, u8, u8) = (1, 2, 3);

/// The rig of scene `S` (actuator `A`, `L` lights) on headless pins, its session, the pipe and
/// the host's decoder.
struct Bench<S: LinkScene<L>, A, const L: usize> {
    rig: Rig<S, A, HeadlessPin, HeadlessPin, L>,
    session: Session<S, L>,
    pipe: Pipe,
    decoder: ReportDecoder,
    /// Reports decoded so far and not yet taken.
    reports: VecDeque<Report>,
}

/// The QEMU link build's meter-stick rig.
type MeterBench = Bench<MeterStick6<f32, 8>, Carriage<HeadlessPin, NoDelay>, 2>;

impl MeterBench {
    fn new(params: MeterStickParams<f32>) -> Self {
        Self::with(params, CONFIG)
    }

    fn with(params: MeterStickParams<f32>, config: RigConfig) -> Self {
        Bench::boot(MeterStickRig::headless(params, config, NoDelay).unwrap())
    }
}

impl<S: LinkScene<L>, A: Actuator<S, Infallible>, const L: usize> Bench<S, A, L>
where
    S::Report: Copy,
{
    fn boot(rig: Rig<S, A, HeadlessPin, HeadlessPin, L>) -> Self {
        let mut session = Session::new(0, FIRMWARE, build_id("abc1234-dirty"));
        session.boot(&rig);
        let pipe = Pipe::new();
        let mut bench = Self { rig, session, pipe, decoder: ReportDecoder::new(), reports: VecDeque::new() };
        bench.session.flush(&mut bench.pipe);
        bench.receive();
        bench
    }

    fn send_raw(&mut self, bytes: &[u8]) {
        self.pipe.rx.extend(bytes);
    }

    fn send(&mut self, command: &Command) {
        self.send_raw(&frame(command));
    }

    /// One pass of the firmware's loop (firmware/src/qemu_link.rs): commands, a tick, its
    /// reports, the queue drained into the port; then the host decodes what arrived.
    fn tick(&mut self) {
        match self.session.poll(&mut self.pipe, &mut self.rig) {
            Ok(None) => {}
            Ok(Some(scene)) => panic!("a bench runs one scene, not {scene:?}"),
            Err(RigError::Pin(never)) => match never {},
            Err(e) => panic!("{e:?}"),
        }
        let session = &mut self.session;
        self.rig.tick_with(|r| session.record(r)).unwrap();
        self.session.end_tick(&self.rig, 1);
        self.session.flush(&mut self.pipe);
        self.receive();
    }

    fn receive(&mut self) {
        let bytes = std::mem::take(&mut self.pipe.tx);
        let reports = &mut self.reports;
        self.decoder.feed(&bytes, |frame| reports.push_back(frame.expect("the rig's frames decode")));
    }

    /// Sends `command`, ticks once and returns the reports that came back.
    fn request(&mut self, command: &Command) -> Vec<Report> {
        self.send(command);
        self.tick();
        self.reports.drain(..).collect()
    }

    /// The one reply to `command` among the reports (state changes and the like may follow).
    fn reply(&mut self, command: &Command) -> Report {
        let reports = self.request(command);
        let replies: Vec<&Report> = reports.iter().filter(|r| is_reply(r)).collect();
        assert_eq!(replies.len(), 1, "one reply to {command:?}: {reports:?}");
        *replies[0]
    }

    /// Ticks until the run has ended (at most `limit` ticks); every report on the way.
    fn run_to_end(&mut self, limit: usize) -> Vec<Report> {
        let mut all = Vec::new();
        for _ in 0..limit {
            self.tick();
            let done = self.reports.iter().any(|r| matches!(r, Report::Outcome { .. }));
            all.extend(self.reports.drain(..));
            if done {
                // The reports after the outcome (margin, state) come in the same tick.
                return all;
            }
        }
        panic!("no outcome within {limit} ticks");
    }
}

/// A reply to some command (the link crate's reply table), not an event or a state report.
fn is_reply(r: &Report) -> bool {
    matches!(
        r,
        Report::Hello { .. }
            | Report::Ack { .. }
            | Report::Rejected { .. }
            | Report::Param { .. }
            | Report::Pong { .. }
            | Report::Stats(_)
            | Report::Error(ErrorCode::NotAllowed { .. })
    )
}

fn ack(c: &Command) -> Report {
    Report::Ack { command: c.tag() }
}

/// A switch event: step, time, contact, mode.
type Switch = (u32, f32, u8, Mode);

/// What the host core does with `params`: outcome, steps, checksum of every step's state, and
/// the switch events (step, time, contact, mode).
fn host_run(params: MeterStickParams<f32>) -> (Outcome, u32, u32, Vec<Switch>) {
    let mut scene = MeterStick6::<f32, 8>::new(params).unwrap();
    let mut checksum = Checksum::new();
    let mut steps = 0u32;
    let mut switches = Vec::new();
    let outcome = scene.run(|r| {
        steps += 1;
        checksum.add(&r.state);
        for (contact, mode) in r.switches() {
            switches.push((steps, r.time, contact as u8, mode_of(mode)));
        }
    });
    (outcome, steps, checksum.value(), switches)
}

fn mode_of(m: ContactMode) -> Mode {
    match m {
        ContactMode::Separated => Mode::Separated,
        ContactMode::Sticking => Mode::Sticking,
        ContactMode::Sliding(Direction::Plus) => Mode::SlidingPositive,
        ContactMode::Sliding(Direction::Minus) => Mode::SlidingNegative,
    }
}

#[test]
fn boot_says_hello_and_waits() {
    let rig = MeterStickRig::<_, _, _, 6>::headless(Preset::Slow.params(H), CONFIG, NoDelay).unwrap();
    let mut session = Session::new(0, version("0.7.12-rc.1"), build_id("abc"));
    session.boot(&rig);
    let mut pipe = Pipe::new();
    session.flush(&mut pipe);
    assert_eq!(pipe.tx[0], DELIMITER, "a lone delimiter first: it closes a half-received frame");
    let mut reports = Vec::new();
    ReportDecoder::new().feed(&pipe.tx, |f| reports.push(f.unwrap()));
    assert_eq!(
        reports,
        [
            Report::Hello {
                protocol: PROTOCOL_VERSION,
                firmware: (0, 7, 12),
                core: version(meterstick_core::VERSION),
                build: *b"abc     ",
                scene: SceneId::MeterStick,
                lcp_size: 6,
                step_us: 1000,
            },
            Report::State(RigState::Waiting),
        ]
    );
    assert!(!session.busy());
    assert_eq!(build_id("abc1234-dirty"), *b"abc1234-");
    assert_eq!(version("12.0.255"), (12, 0, 255));
}

/// A run on demand, telemetry on every step: the rig's outcome, step count, checksum, switch
/// events and last telemetry state are the host core's, bit for bit; then the margin and the
/// state; a second start is refused until a reset.
#[test]
fn a_run_on_demand_reports_what_the_host_core_computes() {
    let params = Preset::Slow.params(H);
    let (outcome, steps, checksum, switches) = host_run(params);
    assert_eq!(outcome, Outcome::Balanced);

    let mut b = MeterBench::new(params);
    b.reports.clear();
    let every = Command::SetTelemetry { every_n_steps: 1 };
    assert_eq!(b.reply(&every), ack(&every));
    let start = Command::Start;
    let reports = b.request(&start);
    assert_eq!(reports[0], ack(&start), "{reports:?}");
    assert_eq!(reports[1], Report::State(RigState::Running));
    assert!(matches!(reports[2], Report::Telemetry { step: 0, time, .. } if time == 0.0), "{reports:?}");
    let mut all = reports[3..].to_vec();
    all.extend(b.run_to_end(20_000));

    let outcome_report = all.iter().find(|r| matches!(r, Report::Outcome { .. })).unwrap();
    assert_eq!(
        *outcome_report,
        Report::Outcome { outcome: OutcomeCode::Balanced, time: b.rig.scene().time(), steps, checksum }
    );
    let rig_switches: Vec<Switch> = all
        .iter()
        .filter_map(|r| match *r {
            Report::Switch { step, time, contact, mode, .. } => Some((step, time, contact, mode)),
            _ => None,
        })
        .collect();
    assert!(rig_switches.len() >= 8, "{} switches", rig_switches.len());
    assert_eq!(rig_switches, switches);
    let telemetry: Vec<u32> = all
        .iter()
        .filter_map(|r| if let Report::Telemetry { step, .. } = r { Some(*step) } else { None })
        .collect();
    assert_eq!(telemetry, (1..=steps).collect::<Vec<_>>(), "a telemetry frame every step, none dropped");
    let margins = all.iter().filter(|r| matches!(r, Report::Margin { .. })).count() as u32;
    assert_eq!(margins, steps / MARGIN_EVERY + 1, "one every {MARGIN_EVERY} steps and one at the end");
    let n = all.len();
    assert!(matches!(all[n - 2], Report::Margin { worst_cycles: 1, period_cycles: 0, overruns: 0, .. }));
    assert_eq!(all[n - 1], Report::State(RigState::Finished));
    assert!(!all.iter().any(|r| matches!(r, Report::Error(_))), "nothing dropped, no fault");

    // Finished: a new start needs a reset first.
    assert!(matches!(
        b.reply(&start),
        Report::Error(ErrorCode::NotAllowed { state: RigState::Finished, .. })
    ));
    let reports = b.request(&Command::Reset);
    assert_eq!(reports, [ack(&Command::Reset), Report::State(RigState::Waiting)]);
    // The carriage homes (7.4 m at 100 pulses/m, all in one tick here), then a start runs again.
    b.tick();
    assert!(!b.rig.homing());
    assert_eq!(b.reply(&start), ack(&start));
}

/// Presets by command: each loads its parameters (read back with `GetParam`) at the current
/// step; refused while running. The fast preset falls, as on the host.
#[test]
fn presets_load_their_parameters_and_the_fast_one_falls_as_on_the_host() {
    let mut b = MeterBench::new(Preset::Slow.params(H));
    b.reports.clear();
    for (preset, speed) in [(Preset::Fast, 5.0), (Preset::NearThreshold, 0.3), (Preset::Slow, 0.1)] {
        let c = Command::Preset(preset);
        assert_eq!(b.reply(&c), ack(&c));
        assert_eq!(*b.rig.params(), preset.params(H));
        let get = Command::GetParam { id: ParamId::Finger1Velocity };
        assert_eq!(b.reply(&get), Report::Param { id: ParamId::Finger1Velocity, value: speed });
        let get = Command::GetParam { id: ParamId::Finger1X };
        assert_eq!(b.reply(&get), Report::Param { id: ParamId::Finger1X, value: -0.35 });
    }
    // A preset keeps the step set from the host.
    let set = Command::SetParam { id: ParamId::Step, value: 5e-4 };
    assert_eq!(b.reply(&set), ack(&set));
    let fast = Command::Preset(Preset::Fast);
    assert_eq!(b.reply(&fast), ack(&fast));
    assert_eq!(*b.rig.params(), Preset::Fast.params(5e-4));

    let (outcome, steps, checksum, _) = host_run(Preset::Fast.params(5e-4));
    assert_eq!(outcome, Outcome::Fell);
    assert_eq!(b.reply(&Command::Start), ack(&Command::Start));
    // Running: no preset, no parameter.
    assert!(matches!(b.reply(&fast), Report::Error(ErrorCode::NotAllowed { state: RigState::Running, .. })));
    let set = Command::SetParam { id: ParamId::MuStatic, value: 0.5 };
    assert_eq!(b.reply(&set), Report::Rejected { id: ParamId::MuStatic, reason: RejectReason::Busy });
    let all = b.run_to_end(10_000);
    assert!(all.contains(&Report::Outcome {
        outcome: OutcomeCode::Fell,
        time: b.rig.scene().time(),
        steps,
        checksum
    }));
}

/// Refused parameters: the core's validation names the reason, and the rig keeps its set.
#[test]
fn refused_parameters_leave_the_rig_as_it_was() {
    let params = Preset::Slow.params(H);
    let mut b = MeterBench::new(params);
    b.reports.clear();
    for (id, value, reason) in [
        (ParamId::MuKinetic, 0.9, RejectReason::KineticAboveStatic),
        (ParamId::Step, 0.0, RejectReason::NotPositive),
        (ParamId::RodMass, f32::NAN, RejectReason::NotFinite),
        (ParamId::Finger1X, -0.6, RejectReason::FingerOutsideRod),
        // A step longer than the run, a rod as thick as it is long, a mass whose inertia
        // underflows f32: named, not `Other`.
        (ParamId::Step, 100.0, RejectReason::OutOfRange),
        (ParamId::RodThickness, 1e3, RejectReason::OutOfRange),
        (ParamId::RodMass, 1e-45, RejectReason::InertiaOutOfRange),
    ] {
        let c = Command::SetParam { id, value };
        assert_eq!(b.reply(&c), Report::Rejected { id, reason }, "{id:?} = {value}");
        assert_eq!(*b.rig.params(), params);
    }
    let c = Command::SetParam { id: ParamId::MuKinetic, value: 0.25 };
    assert_eq!(b.reply(&c), ack(&c));
    assert_eq!(b.rig.params().mu_kinetic, 0.25);
}

/// Garbage, a cut frame, a corrupted frame and an overlong one get no reply and are counted;
/// a command after each is answered.
#[test]
fn damaged_and_truncated_frames_are_refused_and_counted() {
    let mut b = MeterBench::new(Preset::Slow.params(H));
    b.reports.clear();
    let ping = |nonce| Command::Ping { nonce };

    // A frame cut short, closed by the next frame's delimiter: the next command is still read.
    let cut = frame(&ping(1));
    b.send_raw(&cut[..cut.len() - 3]);
    b.send_raw(&[DELIMITER]);
    // One bit flipped: a CRC error.
    let mut bad = frame(&ping(2));
    bad[3] ^= 0x10;
    b.send_raw(&bad);
    // Garbage between delimiters.
    b.send_raw(&[0x01, 0xff, 0x37, 0x42, DELIMITER]);
    // Longer than any frame.
    b.send_raw(&[0x55; 2 * MAX_FRAME]);
    b.send_raw(&[DELIMITER]);
    // A valid command after all that.
    assert_eq!(b.reply(&ping(3)), Report::Pong { nonce: 3 });

    let Report::Stats(s) = b.reply(&Command::GetStats) else { panic!("no stats") };
    assert_eq!(s.frames_ok, 2, "the ping and this GetStats: {s:?}");
    assert_eq!(s.crc_errors + s.cobs_errors + s.decode_errors + s.overflows, 4, "{s:?}");
    assert!(s.overflows >= 1 && s.crc_errors >= 1, "{s:?}");
    assert_eq!(b.rig.state(), meterstick_rig::RigState::WaitingForStart, "no bad frame taken for a command");
}

/// 2,000 pings at once: the rig reads at most `POLL_BYTES` a tick, and answers every one, in
/// order, none dropped; then it still runs and stops on command.
#[test]
fn a_flood_of_pings_is_answered_in_order_then_a_run_stops_on_command() {
    const FLOOD: u32 = 2000;
    let mut b = MeterBench::new(Preset::Fast.params(H));
    b.reports.clear();
    for nonce in 0..FLOOD {
        b.send(&Command::Ping { nonce });
    }
    let bytes = b.pipe.rx.len();
    let mut ticks = 0;
    while !b.pipe.rx.is_empty() {
        let before = b.pipe.rx.len();
        b.tick();
        assert!(before - b.pipe.rx.len() <= POLL_BYTES, "bounded work per tick");
        ticks += 1;
    }
    assert!(ticks >= bytes / POLL_BYTES, "{ticks} ticks for {bytes} bytes");
    let pongs: Vec<Report> = b.reports.drain(..).collect();
    assert_eq!(pongs, (0..FLOOD).map(|nonce| Report::Pong { nonce }).collect::<Vec<_>>());
    let Report::Stats(s) = b.reply(&Command::GetStats) else { panic!("no stats") };
    assert_eq!((s.frames_ok, s.dropped()), (FLOOD + 1, 0));

    // Start, a few steps, stop: the run ends unfinished, reported with its checksum.
    let mut host = MeterStick6::<f32, 8>::new(Preset::Fast.params(H)).unwrap();
    let mut checksum = Checksum::new();
    for _ in 0..25 {
        checksum.add(&host.step().unwrap().state);
    }
    assert_eq!(b.reply(&Command::Start), ack(&Command::Start));
    for _ in 0..24 {
        b.tick();
    }
    // The stop is read before the 26th step: 25 steps in all (the start's tick made the first).
    let reports = b.request(&Command::Stop);
    let outcome = Report::Outcome {
        outcome: OutcomeCode::Unfinished,
        time: host.time(),
        steps: 25,
        checksum: checksum.value(),
    };
    let at = |r: &Report| reports.iter().position(|x| x == r);
    assert!(at(&ack(&Command::Stop)).unwrap() < at(&outcome).unwrap(), "{reports:?}");
    assert_eq!(reports.last(), Some(&Report::State(RigState::Finished)));
    assert_eq!(b.rig.state(), meterstick_rig::RigState::Finished(Outcome::Unfinished));
    assert!(matches!(b.reply(&Command::Stop), Report::Error(ErrorCode::NotAllowed { .. })));
}

/// A port that takes nothing for a while: telemetry is dropped first (it must leave a reserve
/// for replies and events), and the drops are counted and announced once there is room: every
/// report due is either received or counted.
#[test]
fn a_stalled_port_drops_telemetry_first_and_announces_it() {
    let mut b = MeterBench::new(Preset::Fast.params(H));
    b.reports.clear();
    let every = Command::SetTelemetry { every_n_steps: 1 };
    assert_eq!(b.reply(&every), ack(&every));
    b.pipe.room = 0;
    b.send(&Command::Start);
    for _ in 0..100 {
        b.tick();
    }
    b.send(&Command::Ping { nonce: 9 });
    b.tick();
    assert!(b.session.busy());
    b.pipe.room = usize::MAX;
    b.tick();
    let reports: Vec<Report> = b.reports.drain(..).collect();
    assert_eq!(reports[..2], [ack(&Command::Start), Report::State(RigState::Running)], "{reports:?}");
    let counted: u32 = reports
        .iter()
        .filter_map(
            |r| if let Report::Error(ErrorCode::TxDropped { count }) = r { Some(*count) } else { None },
        )
        .sum();
    let received =
        reports.iter().filter(|r| !matches!(r, Report::Error(ErrorCode::TxDropped { .. }))).count();
    let telemetry = reports.iter().filter(|r| matches!(r, Report::Telemetry { .. })).count();
    assert!(
        telemetry < 20 && counted > 80,
        "{telemetry} telemetry frames received, {counted} reports dropped"
    );
    // Due: the start's ack and state, telemetry at step 0 and every step since, the switch
    // events of those steps (the host core's), the pong.
    let steps = b.rig.scene().stats().steps;
    let mut host = MeterStick6::<f32, 8>::new(Preset::Fast.params(H)).unwrap();
    let switches: usize = (0..steps).map(|_| host.step().unwrap().switches().count()).sum();
    assert_eq!(received + counted as usize, 2 + 1 + steps as usize + switches + 1, "{reports:?}");
    // One reply per command: the pong came through the stall (the space kept for replies was not
    // spent on announcing the drops).
    assert_eq!(
        reports.iter().filter(|r| matches!(r, Report::Pong { nonce: 9 })).count(),
        1,
        "the pong was lost: {reports:?}"
    );
}

/// Commands over the port drive the rig's pins, on `embedded-hal-mock` pins: `Start` sets DIR
/// toward finger 2 and lights each finger's mode (then each step's modes, as the host core
/// finds them); `Stop` leaves the lights; `Reset` turns them off, the fault light and DIR low;
/// a `Preset` does the same with nothing lit; every pin operation is accounted for.
#[test]
fn commands_over_the_port_drive_the_pins() {
    use embedded_hal_mock::eh1::delay::NoopDelay;
    use embedded_hal_mock::eh1::digital::{Mock as PinMock, State, Transaction as T};
    use meterstick_rig::{Carriage, ModeLights, RigPins};

    const TICKS: usize = 5;
    let params = Preset::Slow.params(H);
    let light = |m: ContactMode| match m {
        ContactMode::Sticking => 0,
        ContactMode::Sliding(_) => 1,
        ContactMode::Separated => 2,
    };
    // The pins' expected operations: all outputs low at `Rig::new`; then the run's.
    let low = || vec![T::set(State::Low)];
    let mut dir = low();
    let mut fault = low();
    let mut lights: [[Vec<T>; 3]; 2] = [[low(), low(), low()], [low(), low(), low()]];
    let mut host = MeterStick6::<f32, 8>::new(params).unwrap();
    let mut lit = host.modes().map(light);
    dir.push(T::set(State::High));
    for i in 0..2 {
        lights[i][lit[i]].push(T::set(State::High));
    }
    for _ in 0..TICKS {
        let modes = host.step().unwrap().modes().map(light);
        for i in 0..2 {
            if modes[i] != lit[i] {
                lights[i][lit[i]].push(T::set(State::Low));
                lights[i][modes[i]].push(T::set(State::High));
                lit[i] = modes[i];
            }
        }
    }
    // Reset: the lit lights off, the fault light and DIR low; a preset: the same, nothing lit.
    for i in 0..2 {
        lights[i][lit[i]].push(T::set(State::Low));
    }
    fault.extend([T::set(State::Low), T::set(State::Low)]);
    dir.extend([T::set(State::Low), T::set(State::Low)]);
    // Waiting (before the start, after the reset, after the preset): the start button read
    // once a tick, released (high, active low).
    let button = vec![T::get(State::High); 3];

    let m = |t: &Vec<T>| PinMock::new(t);
    let carriage = Carriage::new(m(&vec![T::set(State::Low)]), m(&dir), NoopDelay::new());
    let pins = RigPins {
        start: m(&button),
        lights: [0, 1].map(|i| ModeLights {
            sticking: m(&lights[i][0]),
            sliding: m(&lights[i][1]),
            separated: m(&lights[i][2]),
        }),
        fault: m(&fault),
    };
    let config = RigConfig { steps_per_meter: 1000.0, max_pulses_per_tick: 10, ..RigConfig::default_rig() };
    let mut rig = MeterStickRig::<_, _, _, 6>::new(params, config, pins, carriage).unwrap();
    let mut session = Session::new(0, FIRMWARE, build_id("mock"));
    session.boot(&rig);
    let mut pipe = Pipe::new();
    let mut decoder = ReportDecoder::new();
    let mut tick =
        |rig: &mut MeterStickRig<PinMock, PinMock, NoopDelay, 6>, pipe: &mut Pipe| -> Vec<Report> {
            session.poll(pipe, rig).unwrap();
            rig.tick_with(|r| session.record(r)).unwrap();
            session.end_tick(rig, 1);
            session.flush(pipe);
            let mut out = Vec::new();
            decoder.feed(&std::mem::take(&mut pipe.tx), |f| out.push(f.unwrap()));
            out
        };
    tick(&mut rig, &mut pipe);
    pipe.rx.extend(frame(&Command::Start));
    assert!(tick(&mut rig, &mut pipe).contains(&ack(&Command::Start)));
    for _ in 1..TICKS {
        tick(&mut rig, &mut pipe);
    }
    pipe.rx.extend(frame(&Command::Stop));
    assert!(tick(&mut rig, &mut pipe).contains(&ack(&Command::Stop)));
    pipe.rx.extend(frame(&Command::Reset));
    assert!(tick(&mut rig, &mut pipe).contains(&ack(&Command::Reset)));
    pipe.rx.extend(frame(&Command::Preset(Preset::Fast)));
    assert!(tick(&mut rig, &mut pipe).contains(&ack(&Command::Preset(Preset::Fast))));
    assert_eq!(rig.state(), meterstick_rig::RigState::WaitingForStart);
    assert_eq!(*rig.params(), Preset::Fast.params(H));

    let (pins, carriage) = rig.release();
    let RigPins { mut start, lights, mut fault } = pins;
    let (mut step, mut dir) = (carriage.step, carriage.dir);
    for p in [&mut start, &mut step, &mut dir, &mut fault] {
        p.done();
    }
    for l in lights {
        let ModeLights { mut sticking, mut sliding, mut separated } = l;
        for p in [&mut sticking, &mut sliding, &mut separated] {
            p.done();
        }
    }
}

/// The Black Pill's rig (80 steps/mm, at most 100 pulses a tick, SysTick at 100 MHz: steps of
/// 10 us ..= 0.168 s), with a start button that reads released.
fn black_pill() -> RigConfig {
    RigConfig { button_active_low: false, ..RigConfig::default_rig() }.ticked_by(
        100_000_000,
        1_000,
        0x00FF_FFFF,
    )
}

/// What the core accepts but the rig cannot perform is refused, naming the parameter, with
/// `BeyondRig`: a preset faster than the carriage, finger 1 too fast or backward, finger 2
/// moving, a step the board cannot tick in real time; the rig keeps its set. (The rig acked
/// them: the fast preset and 2 m/s then faulted at step 1, -0.1 m/s and a moving finger 2 ran
/// with no pulses, h = 0.5 s ran 3 times too fast.)
#[test]
fn values_the_rig_cannot_perform_are_refused_with_beyond_rig() {
    let params = Preset::Slow.params(H);
    let mut b = MeterBench::with(params, black_pill());
    b.reports.clear();
    let fast = Command::Preset(Preset::Fast);
    let refused = Report::Rejected { id: ParamId::Finger1Velocity, reason: RejectReason::BeyondRig };
    assert_eq!(b.reply(&fast), refused);
    assert_eq!(*b.rig.params(), params);
    for (id, value) in [
        (ParamId::Finger1Velocity, 2.0),
        (ParamId::Finger1Velocity, 1.25),
        (ParamId::Finger1Velocity, -0.1),
        (ParamId::Finger2Velocity, -0.1),
        (ParamId::Finger2Velocity, 0.1),
        (ParamId::Step, 0.5),
        (ParamId::Step, 0.17),
        (ParamId::Step, 1e-6),
        (ParamId::Step, 9e-6),
    ] {
        let c = Command::SetParam { id, value };
        assert_eq!(b.reply(&c), Report::Rejected { id, reason: RejectReason::BeyondRig }, "{id:?} = {value}");
        assert_eq!(*b.rig.params(), params);
    }
    for (id, value) in
        [(ParamId::Finger1Velocity, 1.2), (ParamId::Finger1Velocity, 0.0), (ParamId::Step, 1e-5)]
    {
        let c = Command::SetParam { id, value };
        assert_eq!(b.reply(&c), ack(&c), "{id:?} = {value}");
    }
    // The other presets load; a run starts and runs.
    let near = Command::Preset(Preset::NearThreshold);
    assert_eq!(b.reply(&near), ack(&near));
    assert_eq!(b.reply(&Command::Start), ack(&Command::Start));
    for _ in 0..50 {
        b.tick();
    }
    assert_eq!(b.rig.state(), meterstick_rig::RigState::Running);
}

/// An actuator overrun is reported as one: `Error(ActuatorOverrun)`, then the outcome
/// `ActuatorOverrun`, then the fault state. (It was `Error(CoreFault)` and `Unfinished`.) The
/// carriage: 1 nm per pulse, 10 a tick; finger 1 at 5 um/s needs 5 a tick, but its f32 position
/// near -0.35 m moves by whole ulps (30 nm).
#[test]
fn an_actuator_overrun_is_reported_as_one() {
    let config = RigConfig { steps_per_meter: 1e9, max_pulses_per_tick: 10, ..CONFIG };
    let params = MeterStickParams { finger1_x: -0.35, finger1_velocity: 5e-6, ..MeterStickParams::paper() };
    let mut b = MeterBench::with(params, config);
    b.reports.clear();
    assert_eq!(b.reply(&Command::Start), ack(&Command::Start));
    let all = b.run_to_end(100);
    assert_eq!(b.rig.state(), meterstick_rig::RigState::Fault(meterstick_rig::RigFault::ActuatorOverrun));
    let ends: Vec<&Report> = all
        .iter()
        .filter(|r| matches!(r, Report::Error(_) | Report::Outcome { .. } | Report::State(_)))
        .collect();
    assert!(
        matches!(
            ends[..],
            [
                Report::Error(ErrorCode::ActuatorOverrun),
                Report::Outcome { outcome: OutcomeCode::ActuatorOverrun, .. },
                Report::State(RigState::Fault)
            ]
        ),
        "{ends:?}"
    );
}

/// `Hello` reports the step rounded to whole microseconds (5.01e-4 s is 501 us; truncated, it
/// was 500, and so were 2,886 of the 199,999 whole-microsecond steps up to 0.2 s).
#[test]
fn hello_rounds_the_step_to_microseconds() {
    let mut b = MeterBench::new(Preset::Slow.params(H));
    b.reports.clear();
    for us in (1..200_000u32).step_by(97).chain([501, 700, 1_700, 300]) {
        let step: f32 = format!("{us}e-6").parse().unwrap();
        let set = Command::SetParam { id: ParamId::Step, value: step };
        assert_eq!(b.reply(&set), ack(&set));
        match b.reply(&Command::Hello) {
            Report::Hello { step_us, .. } => assert_eq!(step_us, us, "step {step:e} s"),
            r => panic!("{r:?}"),
        }
    }
}
