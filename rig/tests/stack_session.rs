//! The stack rig over the link (`meterstick_rig::session` serving `StackRig`) on the host: a
//! headless stack rig and an in-memory port, driven as the firmware's loop drives them
//! (firmware/src/qemu_link.rs), against the host core's `Stack3` run directly: its hello, its
//! parameters read and set by name, a run whose outcome, step count and checksum, every body's
//! telemetry and every interface's switch events are the host core's; and a board with both rigs
//! switching between them on `SelectScene`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

mod common;

use std::convert::Infallible;

use common::{Pipe, frame};
use meterstick_core::multibody::scenes::{MultibodyScene as _, Stack3, StackParams};
use meterstick_core::planar::{Checksum, ContactMode, Direction};
use meterstick_link::{
    Command, ErrorCode, MAX_FRAME, Mode, OutcomeCode, ParamId, Preset, RejectReason, Report, ReportDecoder,
    RigState, SceneId,
};
use meterstick_rig::session::{LinkScene, Session, build_id};
use meterstick_rig::{
    Actuator, HeadlessPin, MeterStickRig, NoDelay, PresetScene as _, Rig, RigConfig, RigError, StackRig,
};

/// A start button that reads released (headless pins read low; active high): only `Start` starts.
const CONFIG: RigConfig =
    RigConfig { button_active_low: false, max_pulses_per_tick: 1_000_000, ..RigConfig::default_rig() };

/// One pass of the firmware's loop: commands, a tick, its reports, the queue drained; the reports
/// that arrived (each frame at most `MAX_FRAME` bytes) and the scene a command selected.
fn tick<S: LinkScene<L>, A: Actuator<S, Infallible>, const L: usize>(
    rig: &mut Rig<S, A, HeadlessPin, HeadlessPin, L>,
    session: &mut Session<S, L>,
    pipe: &mut Pipe,
) -> (Vec<Report>, Option<SceneId>)
where
    S::Report: Copy,
{
    let selected = match session.poll(pipe, rig) {
        Ok(s) => s,
        Err(RigError::Pin(never)) => match never {},
        Err(e) => panic!("{e:?}"),
    };
    rig.tick_with(|r| session.record(r)).unwrap();
    session.end_tick(rig, 1);
    session.flush(pipe);
    (decode(pipe), selected)
}

fn decode(pipe: &mut Pipe) -> Vec<Report> {
    let bytes = std::mem::take(&mut pipe.tx);
    for f in bytes.split_inclusive(|&b| b == 0) {
        assert!(f.len() <= MAX_FRAME, "a frame of {} bytes", f.len());
    }
    let mut out = Vec::new();
    ReportDecoder::new().feed(&bytes, |f| out.push(f.unwrap()));
    out
}

/// The lights an interface's candidates call for, by the rule the link documents (`Mode`),
/// written out here: sliding if one slides; else by the touching candidates: none separated,
/// one tipping, more sticking.
fn interface_mode(candidates: [ContactMode; 4]) -> Mode {
    if let Some(ContactMode::Sliding(d)) = candidates.iter().find(|m| m.is_sliding()) {
        return if *d == Direction::Plus { Mode::SlidingPositive } else { Mode::SlidingNegative };
    }
    match candidates.iter().filter(|m| **m == ContactMode::Sticking).count() {
        0 => Mode::Separated,
        1 => Mode::Tipping,
        _ => Mode::Sticking,
    }
}

/// The host core's run of the stack: outcome, steps, checksum of every block's state after every
/// step, each step's block states, and the interface switch events (step, interface, mode).
#[allow(clippy::type_complexity)]
fn host_run(params: StackParams<f32>) -> (OutcomeCode, u32, u32, Vec<[[f32; 6]; 3]>, Vec<(u32, u8, Mode)>) {
    let mut scene = Stack3::<f32>::new(params).unwrap();
    let mut checksum = Checksum::new();
    let mut last = scene.modes().map(interface_mode);
    let (mut states, mut switches) = (Vec::new(), Vec::new());
    let outcome = scene.run(|r| {
        for body in &r.states {
            checksum.add(body);
        }
        states.push(r.states.map(|s| {
            let [vx, vy, omega] = s.velocity();
            [s.x, s.y, s.theta, vx, vy, omega]
        }));
        let step = states.len() as u32;
        let now = r.modes.map(interface_mode);
        for (i, (a, b)) in last.iter().zip(&now).enumerate() {
            if a != b {
                switches.push((step, i as u8, *b));
            }
        }
        last = now;
    });
    let code = meterstick_rig::session::outcome_code(outcome);
    (code, states.len() as u32, checksum.value(), states, switches)
}

#[test]
fn the_stack_over_the_link_reports_what_the_host_core_computes() {
    let params = StackParams::<f32> { overhang: 1.02, ..StackParams::default() };
    let (outcome, steps, checksum, states, switches) = host_run(params);
    assert_eq!(outcome, OutcomeCode::Fell);
    assert!(switches.iter().any(|s| s.2 == Mode::Tipping), "{switches:?}");

    let mut rig = StackRig::headless(StackParams::default(), CONFIG).unwrap();
    let mut session = Session::new(0, (1, 2, 3), build_id("stack"));
    let mut pipe = Pipe::new();
    session.boot(&rig);
    session.flush(&mut pipe);
    let boot = decode(&mut pipe);
    assert!(
        matches!(boot[0], Report::Hello { scene: SceneId::Stack, lcp_size: 32, step_us: 1000, .. }),
        "{boot:?}"
    );
    assert_eq!(boot[1], Report::State(RigState::Waiting));

    // Parameters by name: the stack's own, the shared ones, and the meter stick's refused.
    let mut request = |rig: &mut StackRig<_, _>, session: &mut Session<_, 3>, c: Command| {
        pipe.rx.extend(frame(&c));
        tick(rig, session, &mut pipe).0
    };
    let r = request(&mut rig, &mut session, Command::GetParam { id: ParamId::Overhang });
    assert_eq!(r, [Report::Param { id: ParamId::Overhang, value: 0.98 }]);
    let set = Command::SetParam { id: ParamId::Overhang, value: 1.02 };
    assert_eq!(request(&mut rig, &mut session, set), [Report::Ack { command: set.tag() }]);
    let r = request(&mut rig, &mut session, Command::GetParam { id: ParamId::MuStatic });
    assert_eq!(r, [Report::Param { id: ParamId::MuStatic, value: 0.5 }]);
    let r = request(&mut rig, &mut session, Command::SetParam { id: ParamId::Finger1X, value: 0.1 });
    assert_eq!(r, [Report::Rejected { id: ParamId::Finger1X, reason: RejectReason::Other }]);
    let r = request(&mut rig, &mut session, Command::SetParam { id: ParamId::Mass, value: -1.0 });
    assert_eq!(r, [Report::Rejected { id: ParamId::Mass, reason: RejectReason::NotPositive }]);
    let r = request(&mut rig, &mut session, Command::Preset(Preset::Slow));
    assert!(matches!(r[..], [Report::Error(ErrorCode::NotAllowed { .. })]), "{r:?}");
    assert_eq!(*rig.params(), params);
    let every = Command::SetTelemetry { every_n_steps: 1 };
    assert_eq!(request(&mut rig, &mut session, every), [Report::Ack { command: every.tag() }]);

    // The run: bodies at step 0 (the start), then after every step.
    let mut all = request(&mut rig, &mut session, Command::Start);
    for _ in 0..20_000 {
        if all.iter().any(|r| matches!(r, Report::Outcome { .. })) {
            break;
        }
        all.extend(tick(&mut rig, &mut session, &mut pipe).0);
    }
    let end = all.iter().find(|r| matches!(r, Report::Outcome { .. })).unwrap();
    assert_eq!(*end, Report::Outcome { outcome, time: rig.scene().time(), steps, checksum });
    let bodies: Vec<(u32, u8, [f32; 6])> = all
        .iter()
        .filter_map(|r| match *r {
            Report::Body { step, body, state, .. } => Some((step, body, state)),
            _ => None,
        })
        .collect();
    assert_eq!(bodies.len(), 3 * (steps as usize + 1), "three bodies a step, the start's too");
    for (step, body, state) in bodies.iter().filter(|b| b.0 > 0) {
        assert_eq!(*state, states[*step as usize - 1][usize::from(*body)], "step {step} body {body}");
    }
    let rig_switches: Vec<(u32, u8, Mode)> = all
        .iter()
        .filter_map(|r| match *r {
            Report::InterfaceSwitch { step, interface, mode, .. } => Some((step, interface, mode)),
            _ => None,
        })
        .collect();
    assert_eq!(rig_switches, switches);
    assert!(!all.iter().any(|r| matches!(r, Report::Error(_) | Report::Telemetry { .. })), "{all:?}");
}

#[test]
fn select_scene_switches_between_the_boards_rigs() {
    const SCENES: &[SceneId] = &[SceneId::MeterStick, SceneId::Stack];
    let mut meter =
        MeterStickRig::<_, _, _, 6>::headless(Preset::Slow.params(1e-3), CONFIG, NoDelay).unwrap();
    let mut session = Session::new(0, (1, 2, 3), build_id("both")).with_scenes(SCENES);
    let mut pipe = Pipe::new();
    session.boot(&meter);
    session.flush(&mut pipe);
    decode(&mut pipe);

    // A scene the board lacks is refused; the one it runs is acknowledged and nothing changes.
    pipe.rx.extend(frame(&Command::SelectScene(SceneId::Ladder)));
    let (r, selected) = tick(&mut meter, &mut session, &mut pipe);
    assert_eq!((r, selected), (vec![Report::Error(ErrorCode::NoSuchScene(SceneId::Ladder))], None));
    let same = Command::SelectScene(SceneId::MeterStick);
    pipe.rx.extend(frame(&same));
    assert_eq!(tick(&mut meter, &mut session, &mut pipe), (vec![Report::Ack { command: same.tag() }], None));
    // Not while running.
    pipe.rx.extend(frame(&Command::Start));
    tick(&mut meter, &mut session, &mut pipe);
    let stack = Command::SelectScene(SceneId::Stack);
    pipe.rx.extend(frame(&stack));
    let (r, selected) = tick(&mut meter, &mut session, &mut pipe);
    assert!(matches!(r[..], [Report::Error(ErrorCode::NotAllowed { .. }), ..]), "{r:?}");
    assert_eq!(selected, None);
    pipe.rx.extend(frame(&Command::Reset));
    tick(&mut meter, &mut session, &mut pipe);

    // Waiting: acknowledged, and the board switches; the new session says hello as the stack.
    pipe.rx.extend(frame(&stack));
    let (r, selected) = tick(&mut meter, &mut session, &mut pipe);
    assert_eq!((r, selected), (vec![Report::Ack { command: stack.tag() }], Some(SceneId::Stack)));
    let mut rig = StackRig::headless(StackParams::default(), CONFIG).unwrap();
    let mut session = session.select(&rig);
    session.flush(&mut pipe);
    let r = decode(&mut pipe);
    assert!(matches!(r[..], [Report::Hello { scene: SceneId::Stack, .. }, Report::State(RigState::Waiting)]));
    pipe.rx.extend(frame(&Command::GetParam { id: ParamId::Overhang }));
    let (r, _) = tick(&mut rig, &mut session, &mut pipe);
    assert_eq!(r, [Report::Param { id: ParamId::Overhang, value: 0.98 }]);
    // The decoder's counters carried over: every frame so far decoded.
    pipe.rx.extend(frame(&Command::GetStats));
    let (r, _) = tick(&mut rig, &mut session, &mut pipe);
    assert!(matches!(r[..], [Report::Stats(s)] if s.frames_ok == 8 && s.dropped() == 0), "{r:?}");
}
