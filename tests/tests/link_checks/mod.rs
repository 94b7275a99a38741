//! The host link's checks, shared by the firmware under QEMU (`qemu_link.rs`) and the Pico's on
//! an emulated RP2040 (`pico_emu.rs`): a rig on the other end of a [`Link`] (`meterstick-link`'s
//! host end), driven with `host-sim monitor`'s library (`meterstick_host_sim::monitor`):
//!
//! 1. `Hello` (protocol version, 6x6); refused parameters get `Rejected` naming them (the
//!    core's validation); a held parameter set is applied and read back exactly;
//! 2. a run with telemetry on every step: outcome, steps, checksum, every switch event (f32
//!    bits) and every telemetry state equal to the host's f32 6x6 build of the same parameters;
//! 3. garbage, cut frames, corrupted frames, an unknown message, an overlong frame and a flood
//!    of 2,000 pings: every ping answered, every bad frame counted, none taken for a command,
//!    and the rig still runs (the fast preset, again identical to the host), and stops on
//!    command;
//! 4. on a rig of both scenes, `SelectScene` switches it to the 3-block stack, whose run beyond
//!    the critical overhang (set over the link) falls with outcome, steps, checksum, every
//!    interface switch and every body's telemetry equal to the host core's `Stack3`; then back
//!    to the meter stick, which runs as on the host again ([`stack_over_the_link`]).
// Exact float comparisons are the point: values read back from the rig must be the bits sent.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

use std::collections::HashSet;
use std::time::{Duration, Instant};

use meterstick_core::multibody::scenes::{MultibodyScene as _, Stack3};
use meterstick_host_sim::monitor::{
    Margin, RigComparison, apply_params, compare, compare_stack, read_params, read_stack_params, record_run,
    record_stack_run,
};
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{
    Command, ErrorCode, LinkStats, OutcomeCode, PROTOCOL_VERSION, ParamId, Preset, RejectReason, Report,
    RigState, SceneId, encode,
};

/// The checks up to the flood, in order, on the rig at the other end of `link` (`name` in
/// messages); [`still_runs_and_stops`] follows with a preset of the caller's.
pub fn all(link: &mut Link, name: &str) {
    handshake_and_refusals(link);
    let params = held_parameter_set(link);
    run_against_the_host(link, params);
    damage_and_flood(link, name);
}

/// Pings in the flood.
pub const FLOOD: u32 = 2000;

pub fn frame(c: Command) -> Vec<u8> {
    let mut buf = [0u8; 66];
    encode(&c, &mut buf).unwrap().to_vec()
}

pub fn stats(link: &mut Link) -> LinkStats {
    match link.request(&Command::GetStats, REPLY_TIMEOUT).unwrap() {
        Report::Stats(s) => s,
        other => panic!("GetStats: {other:?}"),
    }
}

pub fn check_identical(what: &str, cmp: &RigComparison) {
    println!("{what}: {cmp:?}");
    assert!(cmp.same_outcome && cmp.same_steps, "{what}: outcome/steps differ: {cmp:?}");
    assert!(cmp.same_checksum, "{what}: checksum {} vs host {}", cmp.rig_checksum, cmp.host_checksum);
    assert!(cmp.same_events, "{what}: switch events differ");
    assert_eq!(cmp.rows_differing, 0, "{what}: telemetry states differ from the host's");
}

/// xorshift64*: deterministic garbage.
pub struct Rng(u64);
impl Rng {
    pub fn byte(&mut self) -> u8 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 56) as u8
    }
}

/// 1. Who the rig is; refusals.
pub fn handshake_and_refusals(link: &mut Link) {
    match link.request(&Command::Hello, REPLY_TIMEOUT).unwrap() {
        Report::Hello { protocol, lcp_size, step_us, .. } => {
            assert_eq!((protocol, lcp_size, step_us), (PROTOCOL_VERSION, 6, 1000));
        }
        other => panic!("Hello: {other:?}"),
    }
    // Refusals name the parameter, with the core's reason; the rig keeps its valid set.
    for (id, value, reason) in [
        (ParamId::MuKinetic, 0.9, RejectReason::KineticAboveStatic),
        (ParamId::Step, -1e-3, RejectReason::NotPositive),
        (ParamId::RodMass, f32::NAN, RejectReason::NotFinite),
        (ParamId::Finger1X, -0.7, RejectReason::FingerOutsideRod),
        (ParamId::Finger2X, -0.36, RejectReason::FingersCrossed),
        (ParamId::Gravity, -9.81, RejectReason::Negative),
    ] {
        let reply = link.request(&Command::SetParam { id, value }, REPLY_TIMEOUT).unwrap();
        assert_eq!(reply, Report::Rejected { id, reason }, "{} = {value}", id.name());
    }
}

/// A held parameter set, applied and read back exactly.
pub fn held_parameter_set(link: &mut Link) -> meterstick_core::scene::MeterStickParams<f32> {
    let defaults = read_params(link).unwrap();
    assert_eq!(defaults.finger1_velocity, 0.1, "the slow preset at boot");

    // A held parameter set: slower friction, another start, a time limit; read back exactly.
    let held = [
        (ParamId::Finger1X, -0.3f32),
        (ParamId::Finger1Velocity, 0.2),
        (ParamId::MuStatic, 0.5),
        (ParamId::MuKinetic, 0.35),
        (ParamId::MaxTime, 20.0),
    ];
    assert!(apply_params(link, &held).unwrap().is_empty());
    let params = read_params(link).unwrap();
    for (id, value) in held {
        assert_eq!(params.get(id.name()), Some(value), "{} read back", id.name());
    }
    assert_eq!(params.rod_length, defaults.rod_length);
    params
}

/// 2. A run with telemetry on every step, bit for bit against the host.
pub fn run_against_the_host(link: &mut Link, params: meterstick_core::scene::MeterStickParams<f32>) {
    assert_eq!(
        link.request(&Command::SetTelemetry { every_n_steps: 1 }, REPLY_TIMEOUT).unwrap(),
        ack(Command::SetTelemetry { every_n_steps: 1 })
    );

    let rec = record_run(link, params, true, Duration::from_secs(60), &mut |_: &Report| {}).unwrap();
    assert_eq!(rec.dropped, 0);
    assert_eq!(rec.telemetry_frames, rec.trajectory.steps + 1, "telemetry every step, and step 0");
    let (_, cmp) = compare(&rec).unwrap();
    check_identical("held parameter set", &cmp);
    assert!(rec.trajectory.events.len() >= 4, "a run with switches: {:?}", rec.trajectory.events);
    // A finished run refuses Start until reset; SetParam is allowed again (and resets).
    assert!(matches!(link.request(&Command::Start, REPLY_TIMEOUT).unwrap(), Report::Error(_)));
}

/// 3. Damage and a flood: every ping answered, every bad frame counted.
pub fn damage_and_flood(link: &mut Link, name: &str) {
    let before = stats(link);
    let mut rng = Rng(0x00C0_FFEE);
    let mut wire = Vec::new();
    // Line noise (zeros included), closed by a delimiter.
    wire.extend((0..1000).map(|_| rng.byte()));
    wire.push(0);
    let ping = frame(Command::Ping { nonce: 7 });
    let mut bad = 0u32;
    for i in 0..10 {
        // Cut: the frame without its last three bytes before the delimiter.
        wire.extend_from_slice(&ping[..ping.len() - 4]);
        wire.push(0);
        // Corrupted: one bit flipped (never into a 0x00), the delimiter kept.
        let mut f = ping.clone();
        let k = 1 + i % (f.len() - 2);
        f[k] ^= if f[k] == 0x01 { 0x02 } else { 0x01 };
        wire.extend_from_slice(&f);
        bad += 2;
    }
    // An unknown message (tag 200) with a valid CRC, and an overlong frame.
    let mut unknown = vec![200u8, 1];
    unknown.extend_from_slice(&meterstick_link::crc32c(&[200, 1]).to_le_bytes());
    wire.extend(cobs_frame(&unknown));
    wire.extend(std::iter::repeat_n(0x55, 300));
    wire.push(0);
    bad += 2;
    // The flood.
    for nonce in 0..FLOOD {
        wire.extend(frame(Command::Ping { nonce: 1000 + nonce }));
    }
    let sent = Instant::now();
    link.send_raw(&wire).unwrap();
    let mut pongs = HashSet::new();
    let deadline = Instant::now() + Duration::from_secs(60);
    while pongs.len() < FLOOD as usize && Instant::now() < deadline {
        match link.next(Duration::from_secs(5)).unwrap() {
            Some(Report::Pong { nonce }) => {
                assert!((1000..1000 + FLOOD).contains(&nonce), "pong {nonce}: no such ping was sent");
                pongs.insert(nonce);
            }
            Some(other) => panic!("unexpected report during the flood: {other:?}"),
            None => {}
        }
    }
    println!("{name}: the flood answered in {:.1} s", sent.elapsed().as_secs_f64());
    let after = stats(link);
    if pongs.len() < FLOOD as usize {
        let missing: Vec<u32> = (1000..1000 + FLOOD).filter(|n| !pongs.contains(n)).take(20).collect();
        panic!(
            "{} of {FLOOD} pings answered; unanswered (first 20): {missing:?}; rig: {:?}; host: {:?}",
            pongs.len(),
            after.since(&before),
            link.host_stats()
        );
    }
    let d = after.since(&before);
    println!("{name}: after garbage and the flood: {d:?}");
    assert_eq!(d.frames_ok, FLOOD + 1, "the flood's pings and this GetStats, nothing else");
    assert!(d.dropped() >= bad, "{} bad frames sent, {} counted: {d:?}", bad, d.dropped());
    // Cut frames are COBS errors (a block runs past the delimiter), flipped ones mostly CRC errors.
    assert!(d.crc_errors + d.cobs_errors >= 20 && d.decode_errors >= 1 && d.overflows >= 1, "{d:?}");
    assert_eq!(
        link.request(&Command::Ping { nonce: 42 }, REPLY_TIMEOUT).unwrap(),
        Report::Pong { nonce: 42 }
    );
}

/// The rig still runs after all that (`preset`, ending in `outcome`, identical to the host), and
/// stops on command.
pub fn still_runs_and_stops(link: &mut Link, preset: Preset, outcome: OutcomeCode) {
    runs_as_on_the_host(link, preset, outcome);

    // Stop on command: the slow preset made a run that cannot end before the stop arrives, even on
    // QEMU's rig, which steps as fast as its reports go out (the slow preset's 7,900 steps once
    // ended between a reply and the stop): finger 1 at 1 mm/s and h = 1e-4 s, 300,000 steps to
    // the time limit.
    link.request(&Command::Preset(Preset::Slow), REPLY_TIMEOUT).unwrap();
    for (id, value) in [(ParamId::Finger1Velocity, 1e-3), (ParamId::Step, 1e-4)] {
        let set = Command::SetParam { id, value };
        assert_eq!(link.request(&set, REPLY_TIMEOUT).unwrap(), ack(set));
    }
    start_when_homed(link);
    let mut seen = 0;
    while seen < 5 {
        if let Some(Report::Telemetry { .. }) = link.next(Duration::from_secs(5)).unwrap() {
            seen += 1;
        }
    }
    // While running, parameters are refused as busy.
    assert_eq!(
        link.request(&Command::SetParam { id: ParamId::Gravity, value: 1.0 }, REPLY_TIMEOUT).unwrap(),
        Report::Rejected { id: ParamId::Gravity, reason: RejectReason::Busy }
    );
    assert_eq!(link.request(&Command::Stop, REPLY_TIMEOUT).unwrap(), ack(Command::Stop));
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut stopped = None;
    while Instant::now() < deadline {
        match link.next(Duration::from_secs(1)).unwrap() {
            Some(Report::Outcome { outcome: o, .. }) => stopped = Some(o),
            Some(Report::State(RigState::Finished)) => break,
            _ => {}
        }
    }
    assert_eq!(stopped, Some(OutcomeCode::Unfinished));
    assert_eq!(link.request(&Command::Reset, REPLY_TIMEOUT).unwrap(), ack(Command::Reset));
}

/// A run of the meter stick's `preset` at its step of 1 ms (telemetry every 10 steps), ending in
/// `outcome`, identical to the host.
pub fn runs_as_on_the_host(link: &mut Link, preset: Preset, outcome: OutcomeCode) {
    for c in [Command::SetParam { id: ParamId::Step, value: 1e-3 }, Command::Preset(preset)] {
        assert_eq!(link.request(&c, REPLY_TIMEOUT).unwrap(), ack(c));
    }
    assert_eq!(
        link.request(&Command::SetTelemetry { every_n_steps: 10 }, REPLY_TIMEOUT).unwrap(),
        ack(Command::SetTelemetry { every_n_steps: 10 })
    );
    let params = read_params(link).unwrap();
    start_when_homed(link);
    let rec = record_run(link, params, false, Duration::from_secs(60), &mut |_: &Report| {}).unwrap();
    assert_eq!(rec.outcome, outcome);
    check_identical(&format!("{preset:?} preset"), &compare(&rec).unwrap().1);
}

/// The stack's run over the link ([`stack_over_the_link`]).
#[derive(Debug)]
pub struct StackRun {
    /// Steps to the outcome.
    pub steps: u32,
    /// The rig's checksum (the host's).
    pub checksum: u32,
    /// The real-time margin the rig reported after the run.
    pub margin: Option<Margin>,
}

/// Check 4, on a rig of both scenes: `SelectScene` switches it to the 3-block stack, whose run beyond
/// the critical overhang (1.02, set over the link) falls; outcome, steps, checksum and every
/// interface switch equal to the host core's `Stack3` of the parameters read back
/// (`compare_stack`), and every body's telemetry, `every` steps apart (at most the rate the link
/// carries in real time: three `Body` frames a step), equal to the host's states bit for bit.
/// Then back to the meter stick, which runs `preset` to `outcome` as on the host
/// ([`runs_as_on_the_host`]: the rig it left, back).
pub fn stack_over_the_link(link: &mut Link, every: u16, preset: Preset, outcome: OutcomeCode) -> StackRun {
    assert_eq!(link.request(&Command::Reset, REPLY_TIMEOUT).unwrap(), ack(Command::Reset));
    let select = Command::SelectScene(SceneId::Stack);
    assert_eq!(link.request(&select, REPLY_TIMEOUT).unwrap(), ack(select));
    // The new scene's hello follows the ack (after any report still waiting from before).
    let hello = loop {
        let report = link.next(REPLY_TIMEOUT).unwrap().expect("a Hello after SelectScene");
        if matches!(report, Report::Hello { .. }) {
            break report;
        }
    };
    assert!(matches!(hello, Report::Hello { scene: SceneId::Stack, lcp_size: 32, .. }), "{hello:?}");
    assert_eq!(link.next(REPLY_TIMEOUT).unwrap(), Some(Report::State(RigState::Waiting)));
    for c in [
        Command::SetParam { id: ParamId::Overhang, value: 1.02 },
        Command::SetTelemetry { every_n_steps: every },
    ] {
        assert_eq!(link.request(&c, REPLY_TIMEOUT).unwrap(), ack(c));
    }
    let params = read_stack_params(link).unwrap();
    assert_eq!(params.overhang, 1.02, "the overhang read back");
    let rec = record_stack_run(link, params, true, Duration::from_secs(120), &mut |_: &Report| {}).unwrap();
    // The margin follows the outcome, then the state.
    let mut margin = None;
    loop {
        match link.next(REPLY_TIMEOUT).unwrap().expect("the margin and the state after the outcome") {
            Report::Margin { worst_cycles, period_cycles, overruns, worst_step } => {
                margin = Some(Margin { worst_cycles, period_cycles, overruns, worst_step });
            }
            Report::State(RigState::Finished) => break,
            other => panic!("after the stack's outcome: {other:?}"),
        }
    }
    let cmp = compare_stack(&rec).unwrap();
    println!("stack over the link: {cmp:?}, margin {margin:?}");
    assert!(cmp.identical(), "the stack's run differs from the host's: {cmp:?}");
    assert_eq!(rec.outcome, OutcomeCode::Fell);
    assert!(rec.switches.iter().any(|s| s.3 == meterstick_link::Mode::Tipping), "{:?}", rec.switches);
    assert_eq!(rec.dropped, 0, "reports dropped");

    // Every body's state, against the host core's at the start and after the same step.
    let state6 = |s: &meterstick_core::planar::BodyState<f32>| {
        let [vx, vy, omega] = s.velocity();
        [s.x, s.y, s.theta, vx, vy, omega]
    };
    let mut scene = Stack3::<f32>::new(params).unwrap();
    let mut states: Vec<Vec<[f32; 6]>> = vec![scene.states().iter().map(state6).collect()];
    scene.run(|r| states.push(r.states.iter().map(state6).collect()));
    let steps = u32::try_from(states.len() - 1).unwrap();
    assert_eq!(rec.steps, steps);
    assert_eq!(rec.body_frames, 3 * rec.frames.len() as u64, "three bodies a telemetry step");
    let expected: Vec<u32> = (0..=steps).step_by(usize::from(every)).collect();
    let sent: Vec<u32> = rec.frames.iter().map(|f| f.step).collect();
    assert_eq!(sent, expected, "telemetry every {every} steps and at the start");
    for f in &rec.frames {
        assert_eq!(f.states, states[f.step as usize], "step {}", f.step);
    }
    println!("stack over the link: fell after {steps} steps, checksum {}", cmp.rig_checksum);

    // Back to the meter stick.
    assert_eq!(link.request(&Command::Reset, REPLY_TIMEOUT).unwrap(), ack(Command::Reset));
    let select = Command::SelectScene(SceneId::MeterStick);
    assert_eq!(link.request(&select, REPLY_TIMEOUT).unwrap(), ack(select));
    let hello = link.request(&Command::Hello, REPLY_TIMEOUT).unwrap();
    assert!(matches!(hello, Report::Hello { scene: SceneId::MeterStick, lcp_size: 6, .. }), "{hello:?}");
    runs_as_on_the_host(link, preset, outcome);
    StackRun { steps, checksum: rec.checksum, margin }
}

/// Sends `Start` until the rig takes it: after a reset (a preset) the carriage first drives back
/// to its origin, at most `max_pulses_per_tick` pulses a tick, and the rig refuses `Start`
/// meanwhile (core/src/rig.rs, `Rig::start`; instant where that limit is practically none, as
/// under QEMU: firmware/src/qemu_link.rs).
pub fn start_when_homed(link: &mut Link) {
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        match link.request(&Command::Start, REPLY_TIMEOUT).unwrap() {
            Report::Ack { command } if command == Command::Start.tag() => return,
            Report::Error(ErrorCode::NotAllowed { state: RigState::Waiting, .. })
                if Instant::now() < deadline =>
            {
                std::thread::sleep(Duration::from_millis(100));
            }
            other => panic!("Start: {other:?}"),
        }
    }
}

pub fn ack(c: Command) -> Report {
    Report::Ack { command: c.tag() }
}

/// COBS of `payload` plus the delimiter (a payload shorter than 254 bytes).
pub fn cobs_frame(payload: &[u8]) -> Vec<u8> {
    assert!(payload.len() < 254);
    let mut out = vec![0u8];
    let (mut code_at, mut code) = (0, 1u8);
    for &b in payload {
        if b == 0 {
            out[code_at] = code;
            code_at = out.len();
            out.push(0);
            code = 1;
        } else {
            out.push(b);
            code += 1;
        }
    }
    out[code_at] = code;
    out.push(0);
    out
}
