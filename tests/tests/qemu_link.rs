//! The rig's host link end to end: the firmware with `link` (built by `scripts/test.sh`, paths
//! in `MS_FIRMWARE_M4_LINK` and `MS_FIRMWARE_M0_LINK`) runs under QEMU with its UART connected
//! to a TCP socket of this test, which talks to it through `meterstick_link::host::Link` with
//! `host-sim monitor`'s library (`meterstick_host_sim::monitor`; the checks are in
//! `link_checks/`, shared with the Pico on an emulated RP2040, `pico_emu.rs`):
//!
//! 1. `Hello` (protocol version, 6x6); refused parameters get `Rejected` naming them (the
//!    core's validation); a held parameter set is applied and read back exactly;
//! 2. a run with telemetry on every step: outcome, steps, checksum, every switch event (f32
//!    bits) and every telemetry state equal to the host's f32 6x6 build of the same parameters;
//! 3. garbage, cut frames, corrupted frames, an unknown message, an overlong frame and a flood
//!    of 2,000 pings: every ping answered, every bad frame counted, none taken for a command,
//!    and the rig still runs (the fast preset, again identical to the host), and stops on
//!    command;
//! 4. the Cortex-M4F build's second scene: `SelectScene` switches it to the 3-block stack, whose
//!    run beyond the critical overhang (set over the link) falls with outcome, steps, checksum,
//!    every body's telemetry and every interface switch equal to the host core's `Stack3`; then
//!    back to the meter stick. The micro:bit's build (16 KiB of RAM) refuses the stack.
//!
//! Ignored in a plain `cargo test` (they need the ELFs and `qemu-system-arm`).
// Exact float comparisons are the point: values read back from the rig must be the bits sent.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

mod link_checks;

use std::path::PathBuf;
use std::time::Instant;

use std::time::Duration;

use meterstick_core::multibody::scenes::{MultibodyScene as _, Stack3, StackParams};
use meterstick_core::planar::{Checksum, ContactMode, Direction};
use meterstick_host_sim::qemu::{LinkedFirmware, Machine};
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, ErrorCode, Mode, OutcomeCode, ParamId, Preset, Report, RigState, SceneId};

fn elf(var: &str) -> PathBuf {
    PathBuf::from(std::env::var(var).unwrap_or_else(|_| panic!("{var} is not set: run scripts/test.sh")))
}

/// An interface's mode from its candidates, by the rule the link documents (`Mode`), written out
/// here: sliding if one slides; else by the touching candidates: none separated, one tipping, more
/// sticking.
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

/// The stack over the link (the M4F build's second scene), against the host core's `Stack3`.
fn stack_over_the_link(link: &mut Link) {
    let select = Command::SelectScene(SceneId::Stack);
    assert_eq!(link.request(&select, REPLY_TIMEOUT).unwrap(), link_checks::ack(select));
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
        Command::SetTelemetry { every_n_steps: 1 },
        Command::Start,
    ] {
        assert_eq!(link.request(&c, REPLY_TIMEOUT).unwrap(), link_checks::ack(c));
    }
    let (mut bodies, mut switches, mut end) = (Vec::new(), Vec::new(), None);
    while end.is_none() {
        match link.next(Duration::from_secs(30)).unwrap().expect("the stack's reports") {
            Report::Body { step, body, state, .. } => bodies.push((step, body, state)),
            Report::InterfaceSwitch { step, interface, mode, .. } => switches.push((step, interface, mode)),
            Report::Outcome { outcome, steps, checksum, .. } => end = Some((outcome, steps, checksum)),
            Report::Error(e) => panic!("the stack rig: {e:?}"),
            _ => {}
        }
    }

    // The host core, run directly: every block's state after every step, its checksum (as the
    // QEMU build's stack rig sums it), each interface's switches.
    let mut scene = Stack3::<f32>::new(StackParams { overhang: 1.02, ..StackParams::default() }).unwrap();
    let mut checksum = Checksum::new();
    let mut last = scene.modes().map(interface_mode);
    let (mut states, mut host_switches) = (Vec::new(), Vec::new());
    scene.run(|r| {
        r.states.iter().for_each(|b| checksum.add(b));
        states.push(r.states.map(|s| {
            let [vx, vy, omega] = s.velocity();
            [s.x, s.y, s.theta, vx, vy, omega]
        }));
        let now = r.modes.map(interface_mode);
        for (i, (a, b)) in last.iter().zip(&now).enumerate() {
            if a != b {
                host_switches.push((states.len() as u32, i as u8, *b));
            }
        }
        last = now;
    });
    let steps = states.len() as u32;
    assert_eq!(end, Some((OutcomeCode::Fell, steps, checksum.value())), "outcome, steps, checksum");
    assert_eq!(bodies.len(), 3 * (states.len() + 1), "three bodies a step and at the start");
    for (step, body, state) in bodies.into_iter().filter(|b| b.0 > 0) {
        assert_eq!(state, states[step as usize - 1][usize::from(body)], "step {step} body {body}");
    }
    assert!(host_switches.iter().any(|s| s.2 == Mode::Tipping), "{host_switches:?}");
    assert_eq!(switches, host_switches);
    println!("stack over the link: fell after {steps} steps, checksum {:08x}", checksum.value());

    // Back to the meter stick.
    link.request(&Command::Reset, REPLY_TIMEOUT).unwrap();
    let select = Command::SelectScene(SceneId::MeterStick);
    assert_eq!(link.request(&select, REPLY_TIMEOUT).unwrap(), link_checks::ack(select));
    let hello = link.request(&Command::Hello, REPLY_TIMEOUT).unwrap();
    assert!(matches!(hello, Report::Hello { scene: SceneId::MeterStick, lcp_size: 6, .. }), "{hello:?}");
}

fn session(var: &str, machine: Machine) {
    let started = Instant::now();
    let fw = LinkedFirmware::start(&elf(var), machine, false).expect("QEMU with the link firmware");
    let mut link = Link::tcp(fw.stream.try_clone().unwrap(), machine.qemu_name()).unwrap();

    link_checks::all(&mut link, machine.qemu_name());
    // The fast preset: it falls (the QEMU binding has no practical pulse limit per tick).
    link_checks::still_runs_and_stops(&mut link, Preset::Fast, OutcomeCode::Fell);
    if machine == Machine::Mps2An386 {
        stack_over_the_link(&mut link);
    } else {
        let select = Command::SelectScene(SceneId::Stack);
        let refused = Report::Error(ErrorCode::NoSuchScene(SceneId::Stack));
        assert_eq!(link.request(&select, REPLY_TIMEOUT).unwrap(), refused);
    }
    println!("host side: {:?}", link.host_stats());
    let lines = fw.stop().unwrap();
    assert!(lines.first().is_some_and(|l| l.contains("link on the UART")), "{lines:?}");
    println!("{}: {:.1} s", machine.qemu_name(), started.elapsed().as_secs_f64());
}

#[test]
#[ignore = "needs the cross-built link firmware and qemu-system-arm: run scripts/test.sh"]
fn link_end_to_end_on_cortex_m4f_mps2_an386() {
    session("MS_FIRMWARE_M4_LINK", Machine::Mps2An386);
}

#[test]
#[ignore = "needs the cross-built link firmware and qemu-system-arm: run scripts/test.sh"]
fn link_end_to_end_on_cortex_m0_microbit() {
    session("MS_FIRMWARE_M0_LINK", Machine::Microbit);
}
