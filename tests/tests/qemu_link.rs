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
//!    every body's telemetry (every step) and every interface switch equal to the host core's
//!    `Stack3`; then back to the meter stick, whose fast preset falls as on the host
//!    (`link_checks::stack_over_the_link`). The micro:bit's build (16 KiB of RAM) refuses the
//!    stack.
//!
//! Ignored in a plain `cargo test` (they need the ELFs and `qemu-system-arm`).
// Exact float comparisons are the point: values read back from the rig must be the bits sent.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::float_cmp)]

mod link_checks;

use std::path::PathBuf;
use std::time::Instant;

use meterstick_host_sim::qemu::{LinkedFirmware, Machine};
use meterstick_link::host::{Link, REPLY_TIMEOUT};
use meterstick_link::{Command, ErrorCode, OutcomeCode, Preset, Report, SceneId};

fn elf(var: &str) -> PathBuf {
    PathBuf::from(std::env::var(var).unwrap_or_else(|_| panic!("{var} is not set: run scripts/test.sh")))
}

fn session(var: &str, machine: Machine) {
    let started = Instant::now();
    let fw = LinkedFirmware::start(&elf(var), machine, false).expect("QEMU with the link firmware");
    let mut link = Link::tcp(fw.stream.try_clone().unwrap(), machine.qemu_name()).unwrap();

    link_checks::all(&mut link, machine.qemu_name());
    // The fast preset: it falls (the QEMU binding has no practical pulse limit per tick).
    link_checks::still_runs_and_stops(&mut link, Preset::Fast, OutcomeCode::Fell);
    if machine == Machine::Mps2An386 {
        let stack = link_checks::stack_over_the_link(&mut link, 1, Preset::Fast, OutcomeCode::Fell);
        println!(
            "{}: the stack fell after {} steps, checksum {:08x}; margin {:?}",
            machine.qemu_name(),
            stack.steps,
            stack.checksum,
            stack.margin
        );
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
