//! # meterstick-link: the host link protocol of the meterstick rig
//!
//! Framed, versioned binary messages between a teacher's laptop (the **host**) and the
//! **rig** (the simulation on a Cortex-M: USB CDC on the STM32F411 Black Pill, a UART under
//! QEMU's mps2-an386 exposed as a TCP socket), over any byte stream. `no_std`, no allocation,
//! no panic path: every parser is total, and bad input is dropped and counted.
//!
//! - Host to rig: [`Command`] (set a parameter, choose a preset, start, stop, reset, set the
//!   telemetry rate, ask for statistics or a parameter's value, ping).
//! - Rig to host: [`Report`] (hello, telemetry, switch events, outcome, real-time margin,
//!   acknowledgements and rejections, errors, statistics, state).
//! - [`encode`] makes one frame; [`FrameDecoder`] ([`CommandDecoder`] on the rig,
//!   [`ReportDecoder`] on the host) turns a byte stream back into messages.
//! - [`write_message`], [`read_into`] and [`poll_into`] do the same over
//!   [`embedded_io`] 0.6 `Read`/`ReadReady`/`Write`.
//!
//! ## Frame format
//!
//! ```text
//!  payload  = postcard(message)                      variable, <= MAX_MESSAGE (60) bytes
//!           ‖ CRC-32C(postcard(message))              4 bytes, little-endian
//!
//!  +-----+------------------------+----+----+----+----+
//!  | tag |  fields                | c0 | c1 | c2 | c3 |   tag: varint variant index
//!  +-----+------------------------+----+----+----+----+   fields: varint integers,
//!  \____________________ COBS-encode ________________/      f32 as 4 bytes LE, enums as
//!                            |                              varint tags, arrays and tuples
//!                            v                              in order, no lengths
//!  +------+------------------------------------------+------+
//!  | code |  payload bytes, each 0x00 replaced        | 0x00 |   on the wire:
//!  +------+  by a code byte (never 0x00 inside)       +------+   <= MAX_FRAME (66) bytes
//!          \_________ payload length + 1 _____________/ delim
//! ```
//!
//! For example `Command::Ping { nonce: 7 }` is postcard `08 07` (tag 8, varint 7), its CRC-32C
//! is `0xB8BF_D081`, and the frame is `07 08 07 81 D0 BF B8 00`.
//!
//! ### Why this framing
//!
//! - **COBS** (Consistent Overhead Byte Stuffing, Cheshire and Baker 1999), the framing of
//!   postcard's ecosystem: after encoding, `0x00` never occurs inside a frame, so `0x00` is an
//!   unambiguous delimiter. A receiver that starts mid-stream, loses bytes or receives garbage
//!   resynchronises at the very next `0x00`, with no escape state to get stuck in. The
//!   overhead is fixed and tiny: one byte per started 254 bytes (1 byte for every message
//!   here) plus the delimiter, whatever the data, where SLIP/HDLC byte stuffing grows with
//!   the data (up to 2x) and so makes the largest frame depend on the values sent. Decoding
//!   is streaming, constant work per byte.
//! - **CRC-32C** (Castagnoli, polynomial `0x1EDC6F41`, the `CRC_32_ISCSI` of the `crc`
//!   crate; also iSCSI, SCTP, ext4, Btrfs) over the postcard bytes, appended little-endian
//!   and checked **before** decoding, so corruption is counted as a CRC error, not mistaken
//!   for a decode error. For messages up to 655 bytes (ours are at most 60) it has Hamming
//!   distance 6 (Koopman 2002): every error of up to 5 flipped bits is detected, as is every
//!   burst up to 32 bits; the IEEE 802.3 polynomial keeps HD 6 only up to 33 bytes (HD 5 at
//!   our lengths). A 16-bit CRC would save 2 bytes a frame but let about one randomly
//!   corrupted frame in 65,536 through: with 1 % of frames damaged at 100 frames/s, a wrong
//!   message every 18 hours; 32 bits make that one in 4 x 10^9 (over a century). Cost: a 1 KiB
//!   table in flash and roughly ten cycles per byte. (The STM32F4 CRC unit computes only the MPEG-2 polynomial over 32-bit
//!   words, so it cannot help either choice.) postcard's own `use-crc` flavour was not used:
//!   it checks the CRC only after deserialising, so most corrupted frames would be counted
//!   as decode errors, not CRC errors; and its COBS flavour patches code bytes through
//!   `IndexMut`. The few lines of COBS here use `get`/`get_mut` only (see "No panics").
//! - **postcard** (serde, stable wire format since 1.0): compact (varints, no field names),
//!   `no_std`, no allocation. Enums are tagged by a varint of the variant index, so an
//!   unknown tag is a decode error, counted in [`LinkStats::decode_errors`].
//! - **Sizes**: the largest message is a [`Report::Telemetry`] whose `step` needs a 5-byte
//!   varint: [`MAX_MESSAGE`] = 60 bytes, so [`MAX_FRAME`] = 60 + 4 (CRC) + 1 (COBS) + 1
//!   (delimiter) = **66 bytes**. Commands are at most 12 bytes on the wire.
//!
//! ## Versions
//!
//! [`PROTOCOL_VERSION`] (now 7) is sent by the rig in [`Report::Hello`]. It changes with any
//! change a peer could see: a field added, removed, reordered or retyped, a variant added,
//! or a meaning changed. postcard is not self-describing, so the host must compare it and
//! refuse (or warn about) a rig with another version rather than guess. Two things never
//! change, so that the comparison is always possible: [`Command::Hello`] and
//! [`Report::Hello`] are tag 0, and `Report::Hello` starts with `protocol: u16` (fields are
//! only appended to it). The decoder ignores bytes after a complete message, so an older host
//! still reads the beginning of a newer rig's `Hello`. Variants are only appended, never
//! renumbered: an older peer counts a newer message as a decode error and carries on.
//!
//! Version 2 (after version 1, the first): `ParamId` gained `TiltLimit`, `DropLimit`,
//! `HoldTime` and `MaxTime` (every meter-stick parameter can be set), `Command::GetParam` /
//! `Report::Param` read the rig's parameter set back, and `Report::Margin` gained `worst_step`.
//!
//! Version 3: `OutcomeCode::ActuatorOverrun` and `ErrorCode::ActuatorOverrun` (the carriage
//! could not follow: no longer reported as a core fault and an unfinished run),
//! `RejectReason::BeyondRig` (a value the model accepts but the rig cannot perform), and a
//! refused `Command::Preset` may be answered with `Report::Rejected` naming the parameter.
//!
//! Version 4: `RejectReason::OutOfRange` and `RejectReason::InertiaOutOfRange` (a value outside
//! its range, such as a step longer than the run or a rod as thick as it is long, and a mass and
//! size whose moment of inertia the rig's precision cannot hold; both were `Other`).
//!
//! Version 5: `OutcomeCode::Rolled`, `OutcomeCode::Jammed`, `OutcomeCode::Rode` and
//! `OutcomeCode::Stayed`, so that every outcome of the core crosses the link as itself (a run
//! ending in `Rolled` or `Jammed` was reported as `Unfinished`; `Rode` and `Stayed` are the
//! scenes of several bodies').
//!
//! Version 6: `OutcomeCode::Stopped` (the puck's outcome).
//!
//! Version 7: one rig, several scenes. `Command::SelectScene` (and `CommandTag::SelectScene`)
//! switches the rig to another scene it runs, `ErrorCode::NoSuchScene` refusing one it does not;
//! `SceneId::Stack`; the stack's parameters `ParamId::Length`, `Height`, `Mass`, `Overhang` and
//! `ContactMargin` (its other parameters share the meter stick's names); telemetry of several
//! bodies, `Report::Body` (one report per body and telemetry step, at most 36 bytes, so that
//! every frame stays within [`MAX_FRAME`]) and `Report::InterfaceSwitch`; `Mode::Tipping`, an
//! interface on one corner.
//!
//! ## Errors and counting
//!
//! A [`FrameDecoder`] never panics and never stalls: whatever the input, each byte is
//! consumed, and every non-empty frame ends up in exactly one [`LinkStats`] counter:
//! `frames_ok`, `crc_errors` (including frames too short for a CRC), `cobs_errors` (a
//! block cut short), `decode_errors` (good CRC, but postcard refuses it: unknown tag, bad
//! enum value, too few bytes) or `overflows` (longer than the decoder's capacity; skipped up
//! to the next `0x00`). Empty frames (`00 00`) are idle line, not counted. Counters are
//! `u32` and **wrap** (see [`LinkStats`]). The rig sends its counters in [`Report::Stats`]
//! on [`Command::GetStats`]; a dropped command gets no reply, so the host uses a timeout.
//!
//! What damage costs: a corrupted or cut frame is lost by itself, as long as the delimiter
//! after it survives. Bytes without a `0x00` (line noise, a frame cut without its
//! delimiter) merge with the frame that follows and cost that frame too. So each side writes
//! a lone [`DELIMITER`] when it opens the link (the rig at boot, before its `Hello`; the host
//! after connecting): whatever the other side had half-received is closed off and counted,
//! and the first real frame starts clean. A receiver that starts mid-frame (the host
//! connecting while the rig streams) loses only that frame.
//!
//! ## Throughput
//!
//! A telemetry frame is 62 to 66 bytes (64 for steps 16,384 to 2,097,151, i.e. from 16 s to
//! 35 min of a 1 kHz run; 66 at worst). At 1 kHz steps with telemetry every
//! [`DEFAULT_TELEMETRY_EVERY`] = 10 steps (100 frames/s):
//!
//! | link | capacity | 100 telemetry frames/s (6,600 B/s worst case) |
//! |---|---|---|
//! | UART 115,200 baud, 8N1 | 11,520 B/s | 57 % |
//! | USB full-speed CDC (bulk, 19 x 64 B per 1 ms frame) | 1,216,000 B/s | 0.54 % |
//!
//! Switch events (26 bytes), margins (at most 27) and replies add little. On the UART, keep
//! `every_n_steps >= 8` at 1 kHz (8,250 B/s, 72 %); every step (66,000 B/s) needs USB. The
//! rig should drop telemetry rather than block when its transmit path is full, and say so
//! with [`ErrorCode::TxDropped`].
//!
//! ## Host side
//!
//! ```
//! use meterstick_link::{
//!     read_into, write_message, Command, ParamId, RejectReason, Report, ReportDecoder,
//!     PROTOCOL_VERSION,
//! };
//!
//! // The host's half of the link: `to_rig` stands in for the serial port's output.
//! let mut to_rig = [0u8; 64];
//! let mut tx: &mut [u8] = &mut to_rig;
//! write_message(&mut tx, &Command::Hello)?;
//! write_message(&mut tx, &Command::SetParam { id: ParamId::MuKinetic, value: 0.9 })?;
//!
//! // What came back: the host connected in the middle of a telemetry frame, so the first
//! // bytes are that frame's tail; then a Hello and a rejection.
//! let mut telemetry = Vec::new();
//! write_message(&mut telemetry, &Report::Telemetry {
//!     step: 1234,
//!     time: 1.234,
//!     state: [0.0, 0.0, 0.01, 0.0, 0.0, -0.2],
//!     fingers: [-0.3, 0.4],
//!     contacts: [meterstick_link::ContactTelemetry {
//!         mode: meterstick_link::Mode::Sticking,
//!         normal_impulse: 1e-3,
//!         friction_impulse: 0.0,
//!     }; 2],
//! })?;
//! let mut from_rig = telemetry[40..].to_vec();
//! let hello = Report::Hello {
//!     protocol: PROTOCOL_VERSION,
//!     firmware: (0, 1, 0),
//!     core: (0, 1, 0),
//!     build: *b"1a2b3c4d",
//!     scene: meterstick_link::SceneId::MeterStick,
//!     lcp_size: 6,
//!     step_us: 1000,
//! };
//! write_message(&mut from_rig, &hello)?;
//! write_message(
//!     &mut from_rig,
//!     &Report::Rejected { id: ParamId::MuKinetic, reason: RejectReason::KineticAboveStatic },
//! )?;
//!
//! let mut port: &[u8] = &from_rig;
//! let mut decoder = ReportDecoder::new();
//! let mut reports = Vec::new();
//! while read_into(&mut port, &mut decoder, |frame| {
//!     if let Ok(report) = frame {
//!         reports.push(report);
//!     }
//! })? > 0 {}
//!
//! match reports.first() {
//!     Some(Report::Hello { protocol, .. }) if *protocol == PROTOCOL_VERSION => {}
//!     other => panic!("not a rig of this protocol version: {other:?}"),
//! }
//! if let Some(Report::Rejected { id, reason }) = reports.get(1) {
//!     assert_eq!((id.name(), *reason), ("mu_kinetic", RejectReason::KineticAboveStatic));
//! }
//! assert_eq!(decoder.stats().frames_ok, 2);
//! assert_eq!(decoder.stats().dropped(), 1); // the tail of the telemetry frame
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Rig side
//!
//! ```
//! use meterstick_link::{
//!     write_message, Command, CommandDecoder, ErrorCode, RejectReason, Report, RigState,
//!     WriteError,
//! };
//!
//! /// Called from the rig's main loop with the bytes the UART interrupt queued since the last
//! /// call (or use `poll_into` to read a `ReadReady` port directly). One reply per command.
//! fn service<W: embedded_io::Write>(
//!     received: &[u8],
//!     tx: &mut W,
//!     decoder: &mut CommandDecoder,
//!     state: &mut RigState,
//! ) -> Result<(), WriteError<W::Error>> {
//!     for &byte in received {
//!         // `None`: mid-frame. `Some(Err(_))`: dropped, and counted in `decoder.stats()`.
//!         let Some(Ok(command)) = decoder.push(byte) else { continue };
//!         let ack = Report::Ack { command: command.tag() };
//!         let reply = match (command, *state) {
//!             (Command::GetStats, _) => Report::Stats(decoder.stats()),
//!             (Command::Ping { nonce }, _) => Report::Pong { nonce },
//!             (Command::SetParam { id, .. }, RigState::Running) => {
//!                 Report::Rejected { id, reason: RejectReason::Busy }
//!             }
//!             (Command::SetParam { id, value }, _) if !value.is_finite() => {
//!                 Report::Rejected { id, reason: RejectReason::NotFinite }
//!             }
//!             (Command::SetParam { .. }, _) => ack, // after the core accepted it
//!             (Command::Start, RigState::Waiting) => {
//!                 *state = RigState::Running;
//!                 ack
//!             }
//!             (other, state) => {
//!                 Report::Error(ErrorCode::NotAllowed { command: other.tag(), state })
//!             }
//!         };
//!         write_message(tx, &reply)?;
//!     }
//!     Ok(())
//! }
//!
//! // What the host sent: Start twice, the second cut by a glitch, then Ping.
//! let mut wire = [0u8; 32];
//! let mut host: &mut [u8] = &mut wire;
//! write_message(&mut host, &Command::Start).unwrap();
//! write_message(&mut host, &Command::Start).unwrap();
//! write_message(&mut host, &Command::Ping { nonce: 99 }).unwrap();
//! let used = 32 - host.len();
//! wire[5] ^= 0x10; // a bit flip in the second frame
//!
//! let mut out = [0u8; 64];
//! let mut tx: &mut [u8] = &mut out;
//! let mut decoder = CommandDecoder::new();
//! let mut state = RigState::Waiting;
//! service(&wire[..used], &mut tx, &mut decoder, &mut state).unwrap();
//! assert_eq!(state, RigState::Running);
//! assert_eq!(decoder.stats().frames_ok, 2); // Start (acknowledged) and Ping (answered)
//! assert_eq!(decoder.stats().crc_errors, 1); // the damaged Start: no reply
//! ```
//!
//! ## No panics
//!
//! The rig's firmware must link with a panic handler that references an undefined symbol, so
//! no panic path may survive optimisation. In this crate: no indexing or slicing (`get`,
//! `split_last_chunk`, iterators), no unchecked arithmetic (wrapping counters, saturating or
//! checked sizes), no `unwrap`/`expect`/`panic!`; clippy's `indexing_slicing`,
//! `arithmetic_side_effects`, `unwrap_used`, `expect_used`, `panic` and `unreachable` are
//! denied in library code. Not `embedded_io::Write::write_all` either: it panics when a writer
//! returns `Ok(0)`; [`write_all`] here returns [`WriteError::WriteZero`]. `nopanic/check.sh`
//! verifies it: it links a Cortex-M binary that drives every public function with opaque
//! inputs and such a panic handler, for `thumbv7em-none-eabihf` and `thumbv6m-none-eabi`, at
//! opt-levels `s` and 3 with fat LTO (about 11 kB of code at `s` for both decoders and
//! encoders, plus the 1 KiB CRC table).
//!
//! ## Fuzzing
//!
//! Every parser here is the [`FrameDecoder`] (COBS, CRC, postcard for both message types).
//! The property tests in `tests/proptest.rs` feed it arbitrary bytes (and arbitrary bytes
//! around valid frames) and check that nothing panics, that counts add up and that the
//! buffered state stays within `CAP`. Run them longer with, e.g.,
//! `PROPTEST_CASES=100000 cargo test --release --test proptest`.

#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod frame;
#[cfg(feature = "std")]
pub mod host;
mod io;
mod wire;

pub use frame::{
    CRC_LEN, DELIMITER, EncodeError, FrameDecoder, FrameError, LinkStats, crc32c, encode, frame_len,
};
pub use io::{READ_CHUNK, WriteError, poll_into, read_into, write_all, write_message};
pub use wire::{
    Command, CommandTag, ContactTelemetry, ErrorCode, Mode, OutcomeCode, ParamId, Preset, RejectReason,
    Report, RigState, SceneId,
};

/// The protocol version, sent in [`Report::Hello`]. Bumped on every change a peer could
/// see (see the crate docs, "Versions").
pub const PROTOCOL_VERSION: u16 = 7;

/// The largest postcard message of this protocol version, in bytes: a [`Report::Telemetry`]
/// (tag 1, `step` up to a 5-byte varint, 13 `f32`, 2 modes).
pub const MAX_MESSAGE: usize = 60;

/// The largest frame of this protocol version, delimiter included: [`MAX_MESSAGE`], the
/// CRC, one COBS code byte and the delimiter (66 bytes). A buffer of this size fits any
/// encoded [`Command`] or [`Report`], and a [`FrameDecoder`] of this capacity accepts all of
/// them.
pub const MAX_FRAME: usize = frame_len(MAX_MESSAGE);

/// The telemetry rate proposed as the default: one [`Report::Telemetry`] every 10 steps
/// (100 frames/s, 6.6 kB/s at 1 kHz steps; see "Throughput").
pub const DEFAULT_TELEMETRY_EVERY: u16 = 10;

/// The rig's decoder: commands, frames of up to [`MAX_FRAME`] bytes.
pub type CommandDecoder = FrameDecoder<Command, MAX_FRAME>;

/// The host's decoder: reports, frames of up to [`MAX_FRAME`] bytes.
pub type ReportDecoder = FrameDecoder<Report, MAX_FRAME>;
