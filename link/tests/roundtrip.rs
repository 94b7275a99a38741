//! Wire types and encoder: every variant round-trips, tags and sizes are what the docs say,
//! the framing matches an independent COBS implementation, the I/O helpers work.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::as_conversions,
    clippy::cast_precision_loss,
    clippy::cast_lossless,
    clippy::items_after_statements,
    clippy::type_complexity,
    clippy::cast_possible_truncation,
    clippy::float_cmp
)]

mod common;

use common::{Raw, Rng, all_commands, all_reports, frame_of, telemetry};
use embedded_io::{ErrorType, Read, ReadReady, Write};
use meterstick_link::{
    Command, CommandDecoder, CommandTag, EncodeError, FrameDecoder, MAX_FRAME, MAX_MESSAGE, PROTOCOL_VERSION,
    ParamId, Report, ReportDecoder, WriteError, crc32c, encode, frame_len, poll_into, read_into, write_all,
    write_message,
};

fn postcard_len<M: serde::Serialize>(m: &M) -> usize {
    let mut buf = [0u8; 256];
    postcard::to_slice(m, &mut buf).unwrap().len()
}

fn first_byte<M: serde::Serialize>(m: &M) -> u8 {
    let mut buf = [0u8; 256];
    postcard::to_slice(m, &mut buf).unwrap()[0]
}

/// Encodes, then decodes byte by byte; the message must come back equal, exactly once.
fn round_trip<M>(m: &M)
where
    M: serde::Serialize + serde::de::DeserializeOwned + PartialEq + std::fmt::Debug,
{
    let mut buf = [0u8; MAX_FRAME];
    let frame = encode(m, &mut buf).unwrap();
    assert_eq!(frame.last(), Some(&0), "{m:?}: frame ends with the delimiter");
    assert!(!frame[..frame.len() - 1].contains(&0), "{m:?}: no 0x00 inside the frame");
    assert_eq!(frame.len(), frame_len(postcard_len(m)), "{m:?}: frame_len");
    let mut dec = FrameDecoder::<M>::new();
    let mut got = Vec::new();
    for (i, &b) in frame.iter().enumerate() {
        match dec.push(b) {
            None => assert!(i + 1 < frame.len(), "{m:?}: the delimiter must complete the frame"),
            Some(r) => {
                assert_eq!(i + 1, frame.len(), "{m:?}: only the delimiter completes the frame");
                got.push(r.unwrap());
            }
        }
    }
    assert_eq!(got.len(), 1);
    assert_eq!(&got[0], m);
    let s = dec.stats();
    assert_eq!((s.frames_ok, s.dropped(), s.bytes as usize), (1, 0, frame.len()));
    assert!(dec.is_idle());
}

#[test]
fn every_command_round_trips() {
    let all = all_commands();
    for c in &all {
        round_trip(c);
    }
    // Every tag 0..=10 is covered (a new variant must be added to `all_commands`).
    let mut tags: Vec<u8> = all.iter().map(first_byte).collect();
    tags.sort_unstable();
    tags.dedup();
    assert_eq!(tags, (0..=10).collect::<Vec<u8>>());
}

#[test]
fn every_report_round_trips() {
    let all = all_reports();
    for r in &all {
        round_trip(r);
    }
    let mut tags: Vec<u8> = all.iter().map(first_byte).collect();
    tags.sort_unstable();
    tags.dedup();
    assert_eq!(tags, (0..=13).collect::<Vec<u8>>());
}

/// The tags are the protocol: a reordering of variants must fail here (and bump the version).
#[test]
fn tags_are_stable() {
    let commands = [
        (Command::Hello, 0),
        (Command::SetParam { id: ParamId::Finger1X, value: 0.0 }, 1),
        (Command::Preset(meterstick_link::Preset::Slow), 2),
        (Command::Start, 3),
        (Command::Stop, 4),
        (Command::Reset, 5),
        (Command::SetTelemetry { every_n_steps: 1 }, 6),
        (Command::GetStats, 7),
        (Command::Ping { nonce: 1 }, 8),
        (Command::GetParam { id: ParamId::MaxTime }, 9),
        (Command::SelectScene(meterstick_link::SceneId::Stack), 10),
    ];
    for (c, tag) in commands {
        assert_eq!(first_byte(&c), tag, "{c:?}");
        assert_eq!(first_byte(&c.tag()), tag, "CommandTag mirrors Command: {c:?}");
    }
    let reports: Vec<(u8, fn(&Report) -> bool)> = vec![
        (0, |r| matches!(r, Report::Hello { .. })),
        (1, |r| matches!(r, Report::Telemetry { .. })),
        (2, |r| matches!(r, Report::Switch { .. })),
        (3, |r| matches!(r, Report::Outcome { .. })),
        (4, |r| matches!(r, Report::Margin { .. })),
        (5, |r| matches!(r, Report::Ack { .. })),
        (6, |r| matches!(r, Report::Rejected { .. })),
        (7, |r| matches!(r, Report::Error(_))),
        (8, |r| matches!(r, Report::Stats(_))),
        (9, |r| matches!(r, Report::Pong { .. })),
        (10, |r| matches!(r, Report::State(_))),
        (11, |r| matches!(r, Report::Param { .. })),
        (12, |r| matches!(r, Report::Body { .. })),
        (13, |r| matches!(r, Report::InterfaceSwitch { .. })),
    ];
    for r in all_reports() {
        let tag = first_byte(&r);
        if let Some((_, is)) = reports.iter().find(|(t, _)| *t == tag) {
            assert!(is(&r), "{r:?} has tag {tag}");
        }
    }
    // ParamId tags, in the documented order.
    for (i, id) in ParamId::ALL.into_iter().enumerate() {
        assert_eq!(first_byte(&id) as usize, i, "{id:?}");
    }
    // Report::Hello: tag 0, then `protocol` as a varint (one byte below 128).
    let hello = all_reports().into_iter().find(|r| matches!(r, Report::Hello { .. })).unwrap();
    let mut buf = [0u8; 64];
    let bytes = postcard::to_slice(&hello, &mut buf).unwrap();
    assert_eq!(&bytes[..2], &[0, PROTOCOL_VERSION as u8]);
}

#[test]
fn sizes_match_the_docs() {
    let largest = all_reports().iter().map(postcard_len).chain(all_commands().iter().map(postcard_len)).max();
    assert_eq!(largest, Some(MAX_MESSAGE));
    assert_eq!(postcard_len(&telemetry(u32::MAX)), MAX_MESSAGE, "the largest message is a Telemetry");
    let mut buf = [0u8; 128];
    assert_eq!(encode(&telemetry(u32::MAX), &mut buf).unwrap().len(), MAX_FRAME);
    assert_eq!(MAX_FRAME, 66);
    // Telemetry frames: 62 bytes while step < 128, 64 for step in 16,384..2,097,152, 66 at worst.
    for (step, len) in
        [(0, 62), (127, 62), (128, 63), (16_383, 63), (16_384, 64), (2_097_151, 64), (2_097_152, 65)]
    {
        assert_eq!(encode(&telemetry(step), &mut buf).unwrap().len(), len, "step {step}");
    }
    for c in all_commands() {
        assert!(encode(&c, &mut buf).unwrap().len() <= 12, "{c:?}");
    }
    // Other frames quoted in the throughput notes.
    let switch = Report::Switch {
        step: u32::MAX,
        time: 0.0,
        contact: 0,
        mode: meterstick_link::Mode::Sticking,
        along: [0.0; 2],
    };
    assert_eq!(encode(&switch, &mut buf).unwrap().len(), 26);
    let margin = Report::Margin {
        worst_cycles: u32::MAX,
        period_cycles: u32::MAX,
        overruns: u32::MAX,
        worst_step: u32::MAX,
    };
    assert_eq!(encode(&margin, &mut buf).unwrap().len(), 27);
}

#[test]
fn known_answers() {
    // CRC-32C check value (Rocksoft model): "123456789" -> 0xE3069283.
    assert_eq!(crc32c(b"123456789"), 0xE306_9283);
    // The example frame in the crate docs.
    let mut buf = [0u8; MAX_FRAME];
    let frame = encode(&Command::Ping { nonce: 7 }, &mut buf).unwrap();
    let crc = crc32c(&[0x08, 0x07]);
    assert_eq!(crc, 0xB8BF_D081, "update the crate docs");
    assert_eq!(frame, &[0x07, 0x08, 0x07, 0x81, 0xD0, 0xBF, 0xB8, 0x00]);
}

/// `encode` equals COBS (by the `cobs` crate) of `payload ‖ CRC` plus the delimiter, for
/// payloads across COBS's 254-byte block boundaries, with and without zeros; and such frames
/// decode (with a large enough capacity).
#[test]
fn framing_matches_reference_cobs() {
    let mut rng = Rng(0x5EED);
    let mut buf = vec![0u8; 2048];
    for len in (0..=300).chain(500..=520).chain([762, 763, 1016, 1017]) {
        for zeros in [0u32, 1, 8, 128] {
            let payload: Vec<u8> =
                (0..len).map(|_| if (rng.byte() as u32) < zeros { 0 } else { rng.byte().max(1) }).collect();
            let frame = encode(&Raw(&payload), &mut buf).unwrap();
            assert_eq!(frame, frame_of(&payload).as_slice(), "payload of {len} bytes, zero rate {zeros}/256");
            // frame_len is the longest frame: exact up to 250 bytes of message (one COBS
            // block); beyond, a zero in the right place saves a code byte.
            assert!(frame.len() <= frame_len(len), "frame_len({len})");
            if len <= 250 {
                assert_eq!(frame.len(), frame_len(len), "frame_len({len})");
            }
            let mut dec = FrameDecoder::<(), 1100>::new();
            let mut ok = 0;
            dec.feed(frame, |r| {
                r.unwrap();
                ok += 1;
            });
            assert_eq!(ok, 1, "payload of {len} bytes");
        }
    }
}

#[test]
fn encode_into_small_buffers_fails_cleanly() {
    for m in all_reports() {
        let mut big = [0u8; MAX_FRAME];
        let n = encode(&m, &mut big).unwrap().len();
        for size in 0..n {
            let mut small = vec![0u8; size];
            assert_eq!(encode(&m, &mut small), Err(EncodeError::BufferTooSmall), "{m:?} into {size} bytes");
        }
        let mut exact = vec![0u8; n];
        assert_eq!(encode(&m, &mut exact).unwrap(), &big[..n]);
    }
}

#[test]
fn names_and_units() {
    let mut names: Vec<&str> = ParamId::ALL.iter().map(|p| p.name()).collect();
    assert_eq!(names[0], "finger1_x");
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), ParamId::ALL.len(), "names are unique");
    assert_eq!(ParamId::Gravity.unit(), "m/s^2");
    assert_eq!(ParamId::MuStatic.unit(), "");
    assert_eq!(Command::SetTelemetry { every_n_steps: 3 }.tag(), CommandTag::SetTelemetry);
}

#[test]
fn helpers_over_embedded_io() {
    // write_message into a slice, read_into from a slice, two messages glued.
    let mut wire = [0u8; 64];
    let mut tx: &mut [u8] = &mut wire;
    let n1 = write_message(&mut tx, &Command::Reset).unwrap();
    let n2 = write_message(&mut tx, &Command::Ping { nonce: 5 }).unwrap();
    let used = n1 + n2;
    assert_eq!(64 - tx.len(), used);
    let mut rx: &[u8] = &wire[..used];
    let mut dec = CommandDecoder::new();
    let mut got = Vec::new();
    while read_into(&mut rx, &mut dec, |r| got.push(r.unwrap())).unwrap() > 0 {}
    assert_eq!(got, [Command::Reset, Command::Ping { nonce: 5 }]);

    // A full slice: the writer refuses; no panic.
    let mut tiny = [0u8; 3];
    let mut tx: &mut [u8] = &mut tiny;
    assert!(matches!(write_message(&mut tx, &Command::Reset), Err(WriteError::Io(_))));

    // A writer that returns Ok(0): an error, not a panic (unlike embedded-io's write_all).
    struct Stuck;
    impl ErrorType for Stuck {
        type Error = core::convert::Infallible;
    }
    impl Write for Stuck {
        fn write(&mut self, _: &[u8]) -> Result<usize, Self::Error> {
            Ok(0)
        }
        fn flush(&mut self) -> Result<(), Self::Error> {
            Ok(())
        }
    }
    assert_eq!(write_message(&mut Stuck, &Command::Reset), Err(WriteError::WriteZero));
    assert_eq!(write_all(&mut Stuck, &[]), Ok(()));

    // A writer taking one byte at a time.
    struct Trickle(Vec<u8>);
    impl ErrorType for Trickle {
        type Error = core::convert::Infallible;
    }
    impl Write for Trickle {
        fn write(&mut self, b: &[u8]) -> Result<usize, Self::Error> {
            self.0.extend_from_slice(&b[..1]);
            Ok(1)
        }
        fn flush(&mut self) -> Result<(), Self::Error> {
            Ok(())
        }
    }
    let mut t = Trickle(Vec::new());
    let n = write_message(&mut t, &telemetry(9)).unwrap();
    assert_eq!(t.0.len(), n);

    // Too big for MAX_FRAME: an encode error.
    let big = [1u8; 100];
    assert_eq!(
        write_message(&mut Trickle(Vec::new()), &Raw(&big)),
        Err(WriteError::Encode(EncodeError::BufferTooSmall))
    );

    // poll_into: nothing ready -> Ok(0) without reading; then the bytes.
    struct Port {
        data: Vec<u8>,
        ready: bool,
        reads: usize,
    }
    impl ErrorType for Port {
        type Error = core::convert::Infallible;
    }
    impl Read for Port {
        fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
            self.reads += 1;
            let n = buf.len().min(self.data.len());
            buf[..n].copy_from_slice(&self.data[..n]);
            self.data.drain(..n);
            Ok(n)
        }
    }
    impl ReadReady for Port {
        fn read_ready(&mut self) -> Result<bool, Self::Error> {
            Ok(self.ready && !self.data.is_empty())
        }
    }
    let mut frames = Vec::new();
    for r in all_reports() {
        let mut buf = [0u8; MAX_FRAME];
        frames.extend_from_slice(encode(&r, &mut buf).unwrap());
    }
    let mut port = Port { data: frames.clone(), ready: false, reads: 0 };
    let mut dec = ReportDecoder::new();
    let mut got = Vec::new();
    assert_eq!(poll_into(&mut port, &mut dec, |r| got.push(r.unwrap())).unwrap(), 0);
    assert_eq!(port.reads, 0);
    port.ready = true;
    let mut calls = 0;
    loop {
        let n = poll_into(&mut port, &mut dec, |r| got.push(r.unwrap())).unwrap();
        assert!(n <= meterstick_link::READ_CHUNK);
        if n == 0 {
            break;
        }
        calls += 1;
    }
    assert_eq!(calls, frames.len().div_ceil(meterstick_link::READ_CHUNK));
    assert_eq!(got, all_reports());
}
