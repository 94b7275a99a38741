//! Shared test helpers: one message of every variant, a small PRNG, a reference decoder.
#![allow(
    dead_code,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::as_conversions,
    clippy::cast_precision_loss
)]

use meterstick_link::{
    Command, ContactTelemetry, ErrorCode, FrameError, LinkStats, Mode, OutcomeCode, ParamId, Preset,
    RejectReason, Report, RigState, SceneId, crc32c,
};
use serde::de::DeserializeOwned;
use serde::ser::{Serialize, SerializeTuple, Serializer};

/// Every command variant, with every enum value it can carry.
pub fn all_commands() -> Vec<Command> {
    let mut v = vec![Command::Hello];
    for (i, id) in ParamId::ALL.into_iter().enumerate() {
        v.push(Command::SetParam { id, value: 0.25 * i as f32 - 1.5 });
    }
    v.extend(Preset::ALL.map(Command::Preset));
    v.extend([
        Command::Start,
        Command::Stop,
        Command::Reset,
        Command::SetTelemetry { every_n_steps: 0 },
        Command::SetTelemetry { every_n_steps: 10 },
        Command::SetTelemetry { every_n_steps: u16::MAX },
        Command::GetStats,
        Command::Ping { nonce: 0 },
        Command::Ping { nonce: u32::MAX },
    ]);
    v.extend(SCENES.map(Command::SelectScene));
    v.extend(ParamId::ALL.map(|id| Command::GetParam { id }));
    v
}

pub const MODES: [Mode; 5] =
    [Mode::Separated, Mode::Sticking, Mode::SlidingPositive, Mode::SlidingNegative, Mode::Tipping];
pub const OUTCOMES: [OutcomeCode; 14] = [
    OutcomeCode::Balanced,
    OutcomeCode::Fell,
    OutcomeCode::Held,
    OutcomeCode::Slid,
    OutcomeCode::Tipped,
    OutcomeCode::Unfinished,
    OutcomeCode::SolverFailed,
    OutcomeCode::NonFinite,
    OutcomeCode::ReducedModelLeftRange,
    OutcomeCode::ActuatorOverrun,
    OutcomeCode::Rolled,
    OutcomeCode::Jammed,
    OutcomeCode::Rode,
    OutcomeCode::Stayed,
];
pub const STATES: [RigState; 4] = [RigState::Waiting, RigState::Running, RigState::Finished, RigState::Fault];
pub const REASONS: [RejectReason; 9] = [
    RejectReason::NotFinite,
    RejectReason::NotPositive,
    RejectReason::Negative,
    RejectReason::KineticAboveStatic,
    RejectReason::FingerOutsideRod,
    RejectReason::FingersCrossed,
    RejectReason::Busy,
    RejectReason::Other,
    RejectReason::BeyondRig,
];
pub const SCENES: [SceneId; 4] = [SceneId::MeterStick, SceneId::Incline, SceneId::Ladder, SceneId::Stack];

/// A telemetry report; `step` decides its size (varint).
pub fn telemetry(step: u32) -> Report {
    Report::Telemetry {
        step,
        time: step as f32 * 1e-3,
        state: [0.01, -0.002, 0.05, -0.1, 0.0, 1.5],
        fingers: [-0.4, 0.4],
        contacts: [
            ContactTelemetry { mode: Mode::Sticking, normal_impulse: 9.81e-4, friction_impulse: 1e-5 },
            ContactTelemetry { mode: Mode::SlidingNegative, normal_impulse: 0.0, friction_impulse: -3e-4 },
        ],
    }
}

/// Every report variant, with every enum value it can carry.
pub fn all_reports() -> Vec<Report> {
    let mut v = Vec::new();
    for scene in SCENES {
        v.push(Report::Hello {
            protocol: meterstick_link::PROTOCOL_VERSION,
            firmware: (0, 1, 2),
            core: (3, 4, 255),
            build: *b"deadbeef",
            scene,
            lcp_size: 6,
            step_us: 1000,
        });
    }
    v.extend([telemetry(0), telemetry(12_345), telemetry(u32::MAX)]);
    for (i, mode) in MODES.into_iter().enumerate() {
        v.push(Report::Switch {
            step: 500 + i as u32,
            time: 0.5,
            contact: (i % 2) as u8,
            mode,
            along: [-0.3, 0.31],
        });
    }
    for outcome in OUTCOMES {
        v.push(Report::Outcome { outcome, time: 4.2, steps: 4200, checksum: 0xDEAD_BEEF });
    }
    v.push(Report::Margin { worst_cycles: 61_234, period_cycles: 100_000, overruns: 0, worst_step: 1_234 });
    for tag in all_commands().iter().map(Command::tag) {
        v.push(Report::Ack { command: tag });
    }
    for (i, reason) in REASONS.into_iter().enumerate() {
        v.push(Report::Rejected { id: ParamId::ALL[i], reason });
    }
    for state in STATES {
        v.push(Report::Error(ErrorCode::NotAllowed { command: meterstick_link::CommandTag::Start, state }));
        v.push(Report::State(state));
    }
    v.extend([
        Report::Error(ErrorCode::TxDropped { count: 17 }),
        Report::Error(ErrorCode::RxOverrun),
        Report::Error(ErrorCode::CoreFault),
        Report::Error(ErrorCode::Other(0xBEEF)),
        Report::Error(ErrorCode::ActuatorOverrun),
        Report::Error(ErrorCode::NoSuchScene(SceneId::Stack)),
        Report::Stats(LinkStats {
            frames_ok: u32::MAX,
            crc_errors: u32::MAX,
            cobs_errors: u32::MAX,
            decode_errors: u32::MAX,
            overflows: u32::MAX,
            bytes: u32::MAX,
        }),
        Report::Stats(LinkStats::default()),
        Report::Pong { nonce: 0x1234_5678 },
    ]);
    for (i, id) in ParamId::ALL.into_iter().enumerate() {
        v.push(Report::Param { id, value: 0.5 * i as f32 - 2.0 });
    }
    // The body report at its largest (a 5-byte step) and smallest.
    for (i, mode) in MODES.into_iter().enumerate() {
        let step = [0, u32::MAX][i % 2];
        let state = [0.1, 0.075, -0.02, 1e-3, -9.81e-3, 0.5];
        v.push(Report::Body { step, time: 2.5, body: i as u8, state, mode });
        v.push(Report::InterfaceSwitch { step, time: 2.5, interface: i as u8, mode });
    }
    v
}

/// xorshift64*: deterministic test randomness.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn byte(&mut self) -> u8 {
        (self.next_u64() >> 56) as u8
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// Serialises a byte slice as a postcard tuple: exactly these bytes, no length prefix, so
/// `encode(&Raw(p))` frames an arbitrary payload `p`.
pub struct Raw<'a>(pub &'a [u8]);

impl Serialize for Raw<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(self.0.len())?;
        for b in self.0 {
            t.serialize_element(b)?;
        }
        t.end()
    }
}

/// A frame around arbitrary decoded bytes `body ‖ crc` (CRC given), COBS by the `cobs` crate.
pub fn frame_with_crc(body: &[u8], crc: u32) -> Vec<u8> {
    let mut payload = body.to_vec();
    payload.extend_from_slice(&crc.to_le_bytes());
    let mut f = cobs::encode_vec(&payload);
    f.push(0);
    f
}

/// A frame around `body` with its correct CRC (independent of `encode`).
pub fn frame_of(body: &[u8]) -> Vec<u8> {
    frame_with_crc(body, crc32c(body))
}

/// Textbook COBS decode of one segment (no delimiter); `None` if a block is cut short.
pub fn ref_cobs_decode(seg: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < seg.len() {
        let code = seg[i] as usize;
        assert_ne!(code, 0);
        i += 1;
        let end = i + code - 1;
        if end > seg.len() {
            return None;
        }
        out.extend_from_slice(&seg[i..end]);
        i = end;
        if code < 0xFF && i < seg.len() {
            out.push(0);
        }
    }
    Some(out)
}

/// What the decoder must report for one non-empty segment (the bytes between two
/// delimiters), by a plain non-streaming model.
pub fn model_segment<M: DeserializeOwned>(seg: &[u8], cap: usize) -> Result<M, FrameError> {
    if seg.len() >= cap {
        return Err(FrameError::Overflow);
    }
    let payload = ref_cobs_decode(seg).ok_or(FrameError::Cobs)?;
    if payload.len() < 4 {
        return Err(FrameError::Crc);
    }
    let (body, crc) = payload.split_at(payload.len() - 4);
    if crc32c(body) != u32::from_le_bytes(crc.try_into().unwrap()) {
        return Err(FrameError::Crc);
    }
    postcard::from_bytes(body).map_err(|_| FrameError::Decode)
}

/// Splits a stream at delimiters into its non-empty segments; the last one only if it is
/// followed by a delimiter.
pub fn segments(stream: &[u8]) -> Vec<&[u8]> {
    let mut v: Vec<&[u8]> = stream.split(|&b| b == 0).filter(|s| !s.is_empty()).collect();
    if stream.last().is_some_and(|&b| b != 0) {
        v.pop();
    }
    v
}

/// Bitwise equality for messages that may hold NaN: equal postcard encodings.
pub fn same_bits<M: Serialize>(a: &M, b: &M) -> bool {
    let (mut x, mut y) = ([0u8; 512], [0u8; 512]);
    meterstick_link::encode(a, &mut x).unwrap() == meterstick_link::encode(b, &mut y).unwrap()
}
