//! Property tests: round trip of arbitrary messages, and the decoder as a fuzz target
//! (arbitrary bytes, arbitrary bytes around valid frames, random damage to valid streams).
//!
//! Case counts are set per test (see `cases`); `PROPTEST_CASES=N` overrides them all, e.g.
//! `PROPTEST_CASES=100000 cargo test --release --test proptest` for a long fuzzing run.
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
    clippy::needless_pass_by_value
)]

mod common;

use common::{model_segment, same_bits, segments};
use meterstick_link::{
    Command, CommandTag, ContactTelemetry, ErrorCode, FrameDecoder, FrameError, LinkStats, MAX_FRAME, Mode,
    ParamId, Preset, Report, RigState, encode,
};
use proptest::prelude::*;
use proptest::sample::select;

/// `default` cases, unless PROPTEST_CASES is set.
fn cases(default: u32) -> ProptestConfig {
    let mut c = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = default;
    }
    c
}

/// Every f32 bit pattern (NaNs, infinities, subnormals included).
fn any_f32() -> impl Strategy<Value = f32> {
    any::<u32>().prop_map(f32::from_bits)
}

fn mode() -> impl Strategy<Value = Mode> {
    select(common::MODES.to_vec())
}

fn rig_state() -> impl Strategy<Value = RigState> {
    select(common::STATES.to_vec())
}

fn command_tag() -> impl Strategy<Value = CommandTag> {
    select(common::all_commands().iter().map(Command::tag).collect::<Vec<_>>())
}

fn command() -> impl Strategy<Value = Command> {
    prop_oneof![
        Just(Command::Hello),
        (select(ParamId::ALL.to_vec()), any_f32()).prop_map(|(id, value)| Command::SetParam { id, value }),
        select(Preset::ALL.to_vec()).prop_map(Command::Preset),
        Just(Command::Start),
        Just(Command::Stop),
        Just(Command::Reset),
        any::<u16>().prop_map(|every_n_steps| Command::SetTelemetry { every_n_steps }),
        Just(Command::GetStats),
        any::<u32>().prop_map(|nonce| Command::Ping { nonce }),
        select(ParamId::ALL.to_vec()).prop_map(|id| Command::GetParam { id }),
        select(common::SCENES.to_vec()).prop_map(Command::SelectScene),
    ]
}

fn contact() -> impl Strategy<Value = ContactTelemetry> {
    (mode(), any_f32(), any_f32()).prop_map(|(mode, normal_impulse, friction_impulse)| ContactTelemetry {
        mode,
        normal_impulse,
        friction_impulse,
    })
}

fn stats() -> impl Strategy<Value = LinkStats> {
    any::<[u32; 6]>().prop_map(|[a, b, c, d, e, f]| LinkStats {
        frames_ok: a,
        crc_errors: b,
        cobs_errors: c,
        decode_errors: d,
        overflows: e,
        bytes: f,
    })
}

fn error_code() -> impl Strategy<Value = ErrorCode> {
    prop_oneof![
        (command_tag(), rig_state()).prop_map(|(command, state)| ErrorCode::NotAllowed { command, state }),
        any::<u32>().prop_map(|count| ErrorCode::TxDropped { count }),
        Just(ErrorCode::RxOverrun),
        Just(ErrorCode::CoreFault),
        Just(ErrorCode::ActuatorOverrun),
        any::<u16>().prop_map(ErrorCode::Other),
        select(common::SCENES.to_vec()).prop_map(ErrorCode::NoSuchScene),
    ]
}

fn report() -> impl Strategy<Value = Report> {
    prop_oneof![
        (
            any::<u16>(),
            any::<(u8, u8, u8)>(),
            any::<(u8, u8, u8)>(),
            any::<[u8; 8]>(),
            select(common::SCENES.to_vec()),
            any::<u8>(),
            any::<u32>()
        )
            .prop_map(|(protocol, firmware, core, build, scene, lcp_size, step_us)| Report::Hello {
                protocol,
                firmware,
                core,
                build,
                scene,
                lcp_size,
                step_us
            }),
        (
            any::<u32>(),
            any_f32(),
            prop::array::uniform6(any_f32()),
            prop::array::uniform2(any_f32()),
            prop::array::uniform2(contact())
        )
            .prop_map(|(step, time, state, fingers, contacts)| Report::Telemetry {
                step,
                time,
                state,
                fingers,
                contacts
            }),
        (any::<u32>(), any_f32(), any::<u8>(), mode(), prop::array::uniform2(any_f32())).prop_map(
            |(step, time, contact, mode, along)| Report::Switch { step, time, contact, mode, along }
        ),
        (select(common::OUTCOMES.to_vec()), any_f32(), any::<u32>(), any::<u32>())
            .prop_map(|(outcome, time, steps, checksum)| Report::Outcome { outcome, time, steps, checksum }),
        any::<[u32; 4]>().prop_map(|[worst_cycles, period_cycles, overruns, worst_step]| Report::Margin {
            worst_cycles,
            period_cycles,
            overruns,
            worst_step
        }),
        command_tag().prop_map(|command| Report::Ack { command }),
        (select(ParamId::ALL.to_vec()), select(common::REASONS.to_vec()))
            .prop_map(|(id, reason)| Report::Rejected { id, reason }),
        error_code().prop_map(Report::Error),
        stats().prop_map(Report::Stats),
        any::<u32>().prop_map(|nonce| Report::Pong { nonce }),
        rig_state().prop_map(Report::State),
        (select(ParamId::ALL.to_vec()), any_f32()).prop_map(|(id, value)| Report::Param { id, value }),
        (any::<u32>(), any_f32(), any::<u8>(), prop::array::uniform6(any_f32()), mode())
            .prop_map(|(step, time, body, state, mode)| Report::Body { step, time, body, state, mode }),
        (any::<u32>(), any_f32(), any::<u8>(), mode()).prop_map(|(step, time, interface, mode)| {
            Report::InterfaceSwitch { step, time, interface, mode }
        }),
    ]
}

fn frame<M: serde::Serialize>(m: &M) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME];
    encode(m, &mut buf).unwrap().to_vec()
}

/// Feeds `stream` and checks the decoder against the model and the counting rules.
fn check<M, const CAP: usize>(stream: &[u8]) -> Result<Vec<Result<M, FrameError>>, TestCaseError>
where
    M: serde::de::DeserializeOwned + serde::Serialize + std::fmt::Debug,
{
    let mut dec = FrameDecoder::<M, CAP>::new();
    let mut got = Vec::new();
    for &b in stream {
        if let Some(r) = dec.push(b) {
            got.push(r);
        }
    }
    let segs = segments(stream);
    let tail_overflowed = stream.rsplit(|&b| b == 0).next().is_some_and(|t| t.len() >= CAP);
    prop_assert_eq!(got.len(), segs.len() + usize::from(tail_overflowed));
    for (g, seg) in got.iter().zip(&segs) {
        let want = model_segment::<M>(seg, CAP);
        let agree = match (g, &want) {
            (Ok(a), Ok(b)) => same_bits(a, b),
            (Err(a), Err(b)) => a == b,
            _ => false,
        };
        prop_assert!(agree, "decoder {:?}, model {:?}", g, want);
    }
    let s = dec.stats();
    prop_assert_eq!(s.bytes as usize, stream.len());
    prop_assert_eq!((s.frames_ok + s.dropped()) as usize, got.len());
    prop_assert_eq!(dec.is_idle(), stream.last().is_none_or(|&b| b == 0));
    Ok(got)
}

proptest! {
    #![proptest_config(cases(2000))]

    /// Arbitrary commands round-trip bit for bit, and fit in MAX_FRAME.
    #[test]
    fn commands_round_trip(c in command()) {
        let f = frame(&c);
        prop_assert!(f.len() <= MAX_FRAME);
        let mut dec = FrameDecoder::<Command>::new();
        let mut got = Vec::new();
        dec.feed(&f, |r| got.push(r));
        prop_assert_eq!(got.len(), 1);
        let back = got.pop().unwrap().unwrap();
        prop_assert!(same_bits(&back, &c));
        if !format!("{c:?}").contains("NaN") {
            prop_assert_eq!(back, c);
        }
    }

    /// Arbitrary reports round-trip bit for bit, and fit in MAX_FRAME.
    #[test]
    fn reports_round_trip(r in report()) {
        let f = frame(&r);
        prop_assert!(f.len() <= MAX_FRAME);
        let mut dec = FrameDecoder::<Report>::new();
        let mut got = Vec::new();
        dec.feed(&f, |x| got.push(x));
        prop_assert_eq!(got.len(), 1);
        let back = got.pop().unwrap().unwrap();
        prop_assert!(same_bits(&back, &r));
        if !format!("{r:?}").contains("NaN") {
            prop_assert_eq!(back, r);
        }
    }
}

proptest! {
    #![proptest_config(cases(3000))]

    /// Fuzz target: arbitrary bytes (zeros over-represented, so frames are short) into both
    /// decoders and a small one: no panic, results equal the model's, counts add up.
    #[test]
    fn fuzz_arbitrary_bytes(bytes in prop::collection::vec(prop_oneof![3 => any::<u8>(), 1 => Just(0u8)], 0..1500)) {
        check::<Command, MAX_FRAME>(&bytes)?;
        check::<Report, MAX_FRAME>(&bytes)?;
        check::<Report, 16>(&bytes)?;
        check::<(), 300>(&bytes)?;
    }

    /// Fuzz target: uniform bytes (zeros rare: long frames, overflows).
    #[test]
    fn fuzz_uniform_bytes(bytes in prop::collection::vec(any::<u8>(), 0..4000)) {
        check::<Report, MAX_FRAME>(&bytes)?;
        check::<Command, 32>(&bytes)?;
    }
}

proptest! {
    #![proptest_config(cases(1000))]

    /// Valid frames, each after a delimiter, between arbitrary garbage: all delivered in order.
    #[test]
    fn frames_survive_garbage_around_them(
        parts in prop::collection::vec((prop::collection::vec(any::<u8>(), 0..120), report()), 1..20),
        tail in prop::collection::vec(any::<u8>(), 0..120),
    ) {
        let mut stream = Vec::new();
        for (garbage, r) in &parts {
            stream.extend(garbage);
            stream.push(0);
            stream.extend(frame(r));
        }
        stream.extend(&tail);
        let got = check::<Report, MAX_FRAME>(&stream)?;
        let delivered: Vec<&Report> = got.iter().filter_map(|r| r.as_ref().ok()).collect();
        // Garbage could, with probability 2^-32 per segment, pass the CRC: the model check
        // above covers that; here every sent frame must be among the delivered, in order.
        let mut it = delivered.iter();
        for (_, r) in &parts {
            prop_assert!(it.any(|d| same_bits(*d, r)), "lost {:?}", r);
        }
    }

    /// A stream of valid frames with random bytes overwritten: never a message that was not
    /// sent, every frame not touched is delivered, counts add up.
    #[test]
    fn damaged_streams(
        msgs in prop::collection::vec(command(), 1..30),
        hits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..10),
    ) {
        let mut stream = Vec::new();
        let mut spans = Vec::new();
        for m in &msgs {
            let start = stream.len();
            stream.extend(frame(m));
            spans.push(start..stream.len());
        }
        let mut touched = vec![false; stream.len()];
        for (at, b) in &hits {
            let i = at.index(stream.len());
            if stream[i] != *b {
                stream[i] = *b;
                touched[i] = true;
            }
        }
        stream.push(0);
        let got = check::<Command, MAX_FRAME>(&stream)?;
        let delivered: Vec<Command> = got.into_iter().filter_map(Result::ok).collect();
        for d in &delivered {
            prop_assert!(msgs.iter().any(|m| same_bits(m, d)), "never sent: {:?}", d);
        }
        // A frame is intact if neither it nor the delimiter before it was touched.
        let mut it = delivered.iter();
        for (k, span) in spans.iter().enumerate() {
            let before_ok = k == 0 || !touched[span.start - 1];
            if before_ok && !touched[span.clone()].contains(&true) {
                prop_assert!(it.any(|d| same_bits(d, &msgs[k])), "lost intact frame {}", k);
            }
        }
    }
}
