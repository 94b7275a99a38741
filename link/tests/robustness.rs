//! The decoder against damage: bit flips, truncation, glued frames, garbage, floods, unknown
//! tags, overflow. Each check compares with a plain non-streaming model
//! (`common::model_segment`) as well as with the frames that were sent.
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
    clippy::cast_possible_truncation
)]

mod common;

use common::{
    Raw, Rng, all_commands, all_reports, frame_of, frame_with_crc, model_segment, same_bits, segments,
    telemetry,
};
use meterstick_link::{
    Command, CommandDecoder, FrameDecoder, FrameError, LinkStats, MAX_FRAME, Report, ReportDecoder, crc32c,
    encode,
};

fn frame<M: serde::Serialize>(m: &M) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME];
    encode(m, &mut buf).unwrap().to_vec()
}

fn run<M: serde::de::DeserializeOwned, const CAP: usize>(
    dec: &mut FrameDecoder<M, CAP>,
    bytes: &[u8],
) -> Vec<Result<M, FrameError>> {
    let mut out = Vec::new();
    dec.feed(bytes, |r| out.push(r));
    out
}

/// The decoder's output equals the model's, segment by segment, and the counters add up.
fn check_against_model<M, const CAP: usize>(stream: &[u8]) -> (Vec<Result<M, FrameError>>, LinkStats)
where
    M: serde::de::DeserializeOwned + serde::Serialize + std::fmt::Debug,
{
    let mut dec = FrameDecoder::<M, CAP>::new();
    let got = run(&mut dec, stream);
    let segs = segments(stream);
    // An overflow is reported when it happens, possibly before the delimiter arrives.
    let pending_overflow = stream.rsplit(|&b| b == 0).next().is_some_and(|tail| tail.len() >= CAP);
    assert_eq!(got.len(), segs.len() + usize::from(pending_overflow), "one result per non-empty frame");
    for (g, seg) in got.iter().zip(&segs) {
        let want = model_segment::<M>(seg, CAP);
        match (g, &want) {
            (Ok(a), Ok(b)) => assert!(same_bits(a, b), "{a:?} vs {b:?}"),
            (Err(a), Err(b)) => assert_eq!(a, b),
            _ => panic!("decoder {g:?}, model {want:?} for segment {seg:02x?}"),
        }
    }
    let s = dec.stats();
    assert_eq!(s.bytes as usize, stream.len());
    assert_eq!((s.frames_ok + s.dropped()) as usize, got.len(), "{s:?}");
    let count = |e: FrameError| got.iter().filter(|r| r.as_ref().err() == Some(&e)).count() as u32;
    assert_eq!(s.crc_errors, count(FrameError::Crc));
    assert_eq!(s.cobs_errors, count(FrameError::Cobs));
    assert_eq!(s.decode_errors, count(FrameError::Decode));
    assert_eq!(s.overflows, count(FrameError::Overflow));
    (got, s)
}

/// Every single-bit flip of the payload (message and CRC) of a frame is caught by the CRC:
/// exhaustive over the largest frame and a Hello.
#[test]
fn crc_catches_every_single_bit_flip_of_the_payload() {
    for m in [telemetry(u32::MAX), all_reports()[0]] {
        let mut buf = [0u8; 128];
        let body = postcard::to_slice(&m, &mut buf).unwrap().to_vec();
        let mut payload = body.clone();
        payload.extend_from_slice(&crc32c(&body).to_le_bytes());
        let mut flips = 0;
        for bit in 0..payload.len() * 8 {
            let mut p = payload.clone();
            p[bit / 8] ^= 1 << (bit % 8);
            let (b, c) = p.split_at(p.len() - 4);
            let wire = frame_with_crc(b, u32::from_le_bytes(c.try_into().unwrap()));
            let mut dec = ReportDecoder::new();
            let got = run(&mut dec, &wire);
            assert_eq!(got, [Err(FrameError::Crc)], "flip of bit {bit}");
            flips += 1;
        }
        assert_eq!(flips, payload.len() * 8);
    }
}

/// Every double-bit flip of the largest payload (message and CRC, 64 bytes: 130,816 pairs) is
/// caught too (CRC-32C has Hamming distance 6 at this length).
#[test]
fn crc_catches_every_double_bit_flip_of_the_largest_payload() {
    let mut buf = [0u8; 128];
    let body = postcard::to_slice(&telemetry(u32::MAX), &mut buf).unwrap().to_vec();
    let mut payload = body.clone();
    payload.extend_from_slice(&crc32c(&body).to_le_bytes());
    let bits = payload.len() * 8;
    let mut pairs = 0;
    for i in 0..bits {
        for j in i + 1..bits {
            let mut p = payload.clone();
            p[i / 8] ^= 1 << (i % 8);
            p[j / 8] ^= 1 << (j % 8);
            let (b, c) = p.split_at(p.len() - 4);
            assert_ne!(crc32c(b), u32::from_le_bytes(c.try_into().unwrap()), "bits {i} and {j}");
            pairs += 1;
        }
    }
    assert_eq!(pairs, 130_816);
}

/// Every single-bit flip anywhere on the wire (code bytes and delimiter included): no wrong
/// message is delivered, the damage is counted, and the next frame is delivered intact.
#[test]
fn every_single_bit_flip_on_the_wire_is_dropped_and_recovered() {
    let next = Report::Pong { nonce: 0x00C0_FFEE };
    for m in [telemetry(u32::MAX), telemetry(3), all_reports()[0], Report::Stats(LinkStats::default())] {
        let f = frame(&m);
        for bit in 0..f.len() * 8 {
            let mut wire = f.clone();
            wire[bit / 8] ^= 1 << (bit % 8);
            // A flipped delimiter merges this frame with what follows: an idle delimiter
            // (as a sender may emit between frames) bounds the damage.
            wire.push(0);
            wire.extend(frame(&next));
            let (got, s) = check_against_model::<Report, MAX_FRAME>(&wire);
            let oks: Vec<&Report> = got.iter().filter_map(|r| r.as_ref().ok()).collect();
            assert_eq!(oks, [&next], "flip of bit {bit} of {m:?}");
            assert!(s.dropped() >= 1, "flip of bit {bit}: counted");
        }
    }
}

/// Every truncation of a frame is dropped; the decoder then recovers.
#[test]
fn truncated_frames() {
    for m in all_reports() {
        let f = frame(&m);
        let after = frame(&Report::Pong { nonce: 1 });
        for cut in 1..f.len() - 1 {
            // Cut, then a delimiter (the sender restarted): dropped, counted, next frame ok.
            let mut wire = f[..cut].to_vec();
            wire.push(0);
            wire.extend(&after);
            let (got, s) = check_against_model::<Report, MAX_FRAME>(&wire);
            assert!(got[0].is_err(), "{m:?} cut at {cut}");
            assert_eq!(got[1], Ok(Report::Pong { nonce: 1 }));
            assert_eq!((s.frames_ok, s.dropped()), (1, 1));

            // Cut with no delimiter: it merges with the next frame (both lost, one count),
            // and the frame after that is delivered.
            let mut wire = f[..cut].to_vec();
            wire.extend(&after);
            wire.extend(frame(&m));
            let (got, _) = check_against_model::<Report, MAX_FRAME>(&wire);
            assert!(got[0].is_err(), "{m:?} cut at {cut}, merged");
            assert!(same_bits(got.last().unwrap().as_ref().unwrap(), &m));
        }
        // Cut before the delimiter only: nothing yet, and the delimiter completes it.
        let mut dec = ReportDecoder::new();
        assert!(run(&mut dec, &f[..f.len() - 1]).is_empty());
        assert!(!dec.is_idle());
        assert_eq!(dec.push(0), Some(Ok(m)));
    }
}

#[test]
fn glued_frames() {
    let reports = all_reports();
    let mut wire = Vec::new();
    for r in &reports {
        wire.extend(frame(r));
    }
    // In one slice.
    let mut dec = ReportDecoder::new();
    let got: Vec<Report> = run(&mut dec, &wire).into_iter().map(Result::unwrap).collect();
    assert_eq!(got, reports);
    // In chunks of every size from 1 to 70: frame boundaries anywhere in a chunk.
    for chunk in 1..=70 {
        let mut dec = ReportDecoder::new();
        let mut got = Vec::new();
        for c in wire.chunks(chunk) {
            dec.feed(c, |r| got.push(r.unwrap()));
        }
        assert_eq!(got, reports, "chunks of {chunk}");
    }
    // Two frames glued with extra idle delimiters around: idle is not counted.
    let mut wire = vec![0, 0];
    wire.extend(frame(&Command::Start));
    wire.extend([0, 0, 0]);
    wire.extend(frame(&Command::Stop));
    let mut dec = CommandDecoder::new();
    let got = run(&mut dec, &wire);
    assert_eq!(got, [Ok(Command::Start), Ok(Command::Stop)]);
    assert_eq!(dec.stats().dropped(), 0);
}

/// Random garbage before, between and inside frames: the next clean frame is always delivered,
/// everything else is counted (and matches the model).
#[test]
fn garbage_before_between_and_inside() {
    let mut rng = Rng(42);
    let cmds = all_commands();
    for round in 0..2000 {
        let garbage: Vec<u8> = (0..rng.below(80)).map(|_| rng.byte()).collect();
        let a = cmds[rng.below(cmds.len())];
        let b = cmds[rng.below(cmds.len())];
        let fa = frame(&a);
        let fb = frame(&b);

        // Before: garbage, a delimiter, the frame.
        let mut wire = garbage.clone();
        wire.push(0);
        wire.extend(&fa);
        let (got, _) = check_against_model::<Command, MAX_FRAME>(&wire);
        assert_eq!(got.last(), Some(&Ok(a)), "round {round}");

        // Between two frames, without a delimiter of its own: the second frame is hit (merged
        // with the garbage), the first and a third are delivered.
        let mut wire = fa.clone();
        wire.extend(&garbage);
        wire.extend(&fb);
        wire.extend(&fa);
        let (got, _) = check_against_model::<Command, MAX_FRAME>(&wire);
        assert_eq!(got.first(), Some(&Ok(a)), "round {round}");
        assert_eq!(got.last(), Some(&Ok(a)), "round {round}");

        // Inside a frame: it is dropped (the model says how), the next one is delivered.
        let at = 1 + rng.below(fa.len() - 1);
        let mut wire = fa[..at].to_vec();
        wire.extend(&garbage);
        wire.extend(&fa[at..]);
        wire.extend(&fb);
        let (got, _) = check_against_model::<Command, MAX_FRAME>(&wire);
        assert_eq!(got.last(), Some(&Ok(b)), "round {round}");
    }
}

/// 10^5 random bytes with valid frames interleaved (each after a delimiter): every one of
/// them is delivered, in order, and the counters add up.
#[test]
fn flood_of_random_bytes_with_interleaved_frames() {
    let mut rng = Rng(0xF100D);
    let reports = all_reports();
    let mut wire = Vec::with_capacity(200_000);
    let mut sent = Vec::new();
    let mut garbage_bytes = 0;
    while garbage_bytes < 100_000 {
        // Garbage of random length: uniform bytes; a fifth with many zeros (short segments);
        // a tenth long runs without a zero, to overflow the decoder; a tenth damaged frames
        // (one byte changed: CRC errors, mostly), a tenth cut frames.
        let kind = rng.below(30);
        let start = wire.len();
        match kind {
            0..3 => wire.extend((0..60 + rng.below(200)).map(|_| rng.byte().max(1))),
            3..9 => wire.extend((0..rng.below(100)).map(|_| if rng.below(8) == 0 { 0 } else { rng.byte() })),
            9..15 => {
                let mut f = frame(&reports[rng.below(reports.len())]);
                let at = rng.below(f.len() - 1);
                let was = f[at];
                while f[at] == was {
                    f[at] = rng.byte().max(1);
                }
                wire.push(0);
                wire.extend(f);
            }
            15..18 => {
                let f = frame(&reports[rng.below(reports.len())]);
                wire.extend(&f[..rng.below(f.len() - 1)]);
            }
            _ => wire.extend((0..rng.below(100)).map(|_| rng.byte())),
        }
        let n = wire.len() - start;
        garbage_bytes += n;
        if rng.below(2) == 0 {
            let r = reports[rng.below(reports.len())];
            wire.push(0);
            wire.extend(frame(&r));
            sent.push(r);
        }
    }
    wire.push(0);
    let (got, s) = check_against_model::<Report, MAX_FRAME>(&wire);
    let delivered: Vec<Report> = got.into_iter().filter_map(Result::ok).collect();
    assert_eq!(delivered, sent, "every clean frame, in order, and nothing else");
    assert_eq!(s.frames_ok as usize, sent.len());
    assert!(sent.len() > 500);
    assert!(
        s.overflows > 50 && s.crc_errors > 50 && s.cobs_errors > 50,
        "the flood exercised every path: {s:?}"
    );
    // decode and COBS errors are rarer in random data; the model check covers them.
    println!("flood: {} bytes, {} frames sent, stats {s:?}", wire.len(), sent.len());
}

#[test]
fn unknown_tags_are_decode_errors() {
    // Commands have tags 0..=10, reports 0..=13. Tags as postcard varints (1 or more bytes).
    let cases: [(&[u8], bool); 8] = [
        (&[11], true),                           // first unknown command tag
        (&[127], true),                          //
        (&[0x80, 0x01], true),                   // tag 128, two-byte varint
        (&[0xFF, 0xFF, 0xFF, 0xFF, 0x0F], true), // tag u32::MAX
        (&[0xFF, 0xFF, 0xFF, 0xFF, 0xFF], true), // varint too long
        (&[1, 24, 0, 0, 0, 0], true),            // SetParam with ParamId 24 (unknown)
        (&[], true),                             // no tag at all
        (&[8, 0x80], true),                      // Ping, nonce varint cut short
    ];
    for (body, _) in cases {
        let mut dec = CommandDecoder::new();
        assert_eq!(run(&mut dec, &frame_of(body)), [Err(FrameError::Decode)], "{body:02x?}");
        let s = dec.stats();
        assert_eq!((s.decode_errors, s.crc_errors, s.frames_ok), (1, 0, 0));
    }
    for tag in [14u8, 15, 100] {
        let mut dec = ReportDecoder::new();
        assert_eq!(
            run(&mut dec, &frame_of(&[tag, 0, 0, 0, 0])),
            [Err(FrameError::Decode)],
            "report tag {tag}"
        );
        assert_eq!(dec.stats().decode_errors, 1);
    }
    // Bytes after a complete message are ignored (forward compatibility of Hello).
    let mut body = postcard::to_slice(&Command::Ping { nonce: 3 }, &mut [0u8; 16]).unwrap().to_vec();
    body.extend([1, 2, 3]);
    let mut dec = CommandDecoder::new();
    assert_eq!(run(&mut dec, &frame_of(&body)), [Ok(Command::Ping { nonce: 3 })]);
}

#[test]
fn short_frames_are_crc_errors_and_cobs_cuts_are_cobs_errors() {
    let mut dec = CommandDecoder::new();
    // Decoded lengths 0..=3: too short for a CRC.
    for wire in [&[0x01, 0][..], &[0x02, 0x08, 0], &[0x01, 0x01, 0x01, 0], &[0x04, 1, 2, 3, 0]] {
        assert_eq!(run(&mut dec, wire), [Err(FrameError::Crc)], "{wire:02x?}");
    }
    // A code byte announcing more than arrives.
    assert_eq!(run(&mut dec, &[0x05, 1, 2, 0]), [Err(FrameError::Cobs)]);
    assert_eq!(run(&mut dec, &[0xFF, 0]), [Err(FrameError::Cobs)]);
    let s = dec.stats();
    assert_eq!((s.crc_errors, s.cobs_errors, s.bytes), (4, 2, 20));
}

/// A frame longer than CAP is dropped and counted once, as soon as it passes CAP; the frame
/// after it is delivered. Frames of exactly CAP bytes (delimiter included) are accepted.
#[test]
fn frames_longer_than_cap_overflow() {
    let big = frame(&telemetry(u32::MAX));
    let small = frame(&Report::Pong { nonce: 2 });
    let mut dec = FrameDecoder::<Report, 32>::new();
    let mut wire = big.clone();
    wire.extend(&small);
    let got = run(&mut dec, &wire);
    assert_eq!(got, [Err(FrameError::Overflow), Ok(Report::Pong { nonce: 2 })]);
    assert_eq!(dec.stats().overflows, 1);
    // Reported at the 32nd byte (31 bytes fit before the delimiter), not at the delimiter.
    let mut dec = FrameDecoder::<Report, 32>::new();
    for (i, &b) in big.iter().enumerate() {
        let r = dec.push(b);
        assert_eq!(r.is_some(), i == 31, "byte {i}");
    }
    assert!(dec.is_idle());

    // The boundary, with raw payloads: CAP = 40 accepts a 40-byte frame, not a 41-byte one.
    for (len, ok) in [(34, true), (35, false)] {
        let payload = vec![7u8; len];
        let mut buf = [0u8; 64];
        let f = encode(&Raw(&payload), &mut buf).unwrap();
        assert_eq!(f.len(), len + 6);
        let mut dec = FrameDecoder::<(), 40>::new();
        let got = run(&mut dec, f);
        assert_eq!(got, [if ok { Ok(()) } else { Err(FrameError::Overflow) }], "{len}");
    }

    // MAX_FRAME accepts the largest message; MAX_FRAME - 1 does not.
    assert_eq!(run(&mut ReportDecoder::new(), &big), [Ok(telemetry(u32::MAX))]);
    assert_eq!(run(&mut FrameDecoder::<Report, { MAX_FRAME - 1 }>::new(), &big), [Err(FrameError::Overflow)]);

    // A million bytes without a delimiter: one overflow, bounded state, then recovery.
    let mut dec = ReportDecoder::new();
    let mut rng = Rng(7);
    let mut results = 0;
    for _ in 0..1_000_000 {
        if dec.push(rng.byte().max(1)).is_some() {
            results += 1;
        }
    }
    assert_eq!((results, dec.stats().overflows), (1, 1));
    assert_eq!(run(&mut dec, &[0]), []);
    assert_eq!(run(&mut dec, &small), [Ok(Report::Pong { nonce: 2 })]);
    assert_eq!(dec.stats().bytes, 1_000_001 + small.len() as u32);
}

#[test]
fn degenerate_capacities_never_panic() {
    let f = frame(&Command::Start);
    let mut d0 = FrameDecoder::<Command, 0>::new();
    let mut d1 = FrameDecoder::<Command, 1>::new();
    let mut d5 = FrameDecoder::<Command, 5>::new();
    for _ in 0..3 {
        assert_eq!(run(&mut d0, &f), [Err(FrameError::Overflow)]);
        assert_eq!(run(&mut d1, &f), [Err(FrameError::Overflow)]);
        assert_eq!(run(&mut d5, &f), [Err(FrameError::Overflow)]);
    }
    assert_eq!(f.len(), 7);
    assert_eq!(run(&mut FrameDecoder::<Command, 7>::new(), &f), [Ok(Command::Start)]);
}

#[test]
fn reset_and_stats() {
    let f = frame(&Command::Start);
    let mut dec = CommandDecoder::new();
    assert!(run(&mut dec, &f[..3]).is_empty());
    dec.reset();
    assert!(dec.is_idle());
    assert_eq!(run(&mut dec, &f), [Ok(Command::Start)]);
    assert_eq!(dec.stats().dropped(), 0, "reset drops the partial frame uncounted");
    dec.clear_stats();
    assert_eq!(dec.stats(), LinkStats::default());

    let earlier = LinkStats { bytes: u32::MAX - 5, frames_ok: 10, ..LinkStats::default() };
    let now = LinkStats { bytes: 4, frames_ok: 12, crc_errors: 1, ..LinkStats::default() };
    let d = now.since(&earlier);
    assert_eq!((d.bytes, d.frames_ok, d.crc_errors, d.dropped()), (10, 2, 1, 1));

    // Counters wrap, they do not saturate or panic.
    let mut dec = FrameDecoder::<Command, 8>::new();
    let wire = [0u8; 1000];
    run(&mut dec, &wire);
    assert_eq!(dec.stats().bytes, 1000);
    assert!(format!("{dec:?}").contains("FrameDecoder"));
}
