//! Framing: [`encode`] one message into one frame, [`FrameDecoder`] turns a byte stream back
//! into messages, counting what it drops in [`LinkStats`].
//!
//! Everything here is panic-free by construction: no indexing (only `get`/`get_mut`), no
//! unchecked arithmetic, no `unwrap`.

use core::fmt;
use core::marker::PhantomData;

use crc::{CRC_32_ISCSI, Crc};
use postcard::ser_flavors::Flavor;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// The frame delimiter. COBS guarantees it never occurs inside a frame.
pub const DELIMITER: u8 = 0x00;

/// Bytes of CRC at the end of each (decoded) frame.
pub const CRC_LEN: usize = 4;

/// CRC-32C (Castagnoli, polynomial `0x1EDC6F41`, reflected, init and xor-out `0xFFFFFFFF`;
/// check value `0xE3069283`), table-driven (a 1 KiB table).
static CRC32C: Crc<u32> = Crc::<u32>::new(&CRC_32_ISCSI);

/// The CRC-32C of `bytes`, as appended to every frame (little-endian).
#[must_use]
pub fn crc32c(bytes: &[u8]) -> u32 {
    CRC32C.checksum(bytes)
}

/// The length of the longest frame that can carry a postcard message of `message_len` bytes:
/// the message, its CRC, the COBS overhead (at most one byte per started 254-byte block) and
/// the delimiter. Exact for messages of up to 250 bytes (every message of this protocol);
/// beyond, a frame can be a few bytes shorter. Saturates at `usize::MAX`.
#[must_use]
pub const fn frame_len(message_len: usize) -> usize {
    let n = message_len.saturating_add(CRC_LEN);
    // COBS: one code byte for every started run of 254 bytes (n >= CRC_LEN > 0).
    let overhead = (n.saturating_sub(1) / 254).saturating_add(1);
    n.saturating_add(overhead).saturating_add(1)
}

/// Why [`encode`] failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EncodeError {
    /// The output buffer is too small for the frame (a buffer of
    /// [`MAX_FRAME`](crate::MAX_FRAME) bytes always fits a [`Command`](crate::Command) or a
    /// [`Report`](crate::Report)).
    BufferTooSmall,
    /// postcard could not serialise the value (not possible for this crate's types).
    Serialize,
}

impl fmt::Display for EncodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BufferTooSmall => f.write_str("frame buffer too small"),
            Self::Serialize => f.write_str("message cannot be serialised"),
        }
    }
}

impl core::error::Error for EncodeError {}

/// A postcard serialisation flavor that appends the CRC-32C and COBS-encodes on the fly
/// into a slice, ending with the delimiter. Code bytes are patched in place, so no scratch
/// buffer is needed.
struct FrameWriter<'a> {
    buf: &'a mut [u8],
    /// Next free index in `buf`.
    pos: usize,
    /// Index of the current COBS block's code byte.
    code_at: usize,
    /// The current block's code: 1 + its data bytes (0xFF = full, 254 data bytes).
    code: u8,
    digest: crc::Digest<'static, u32>,
}

impl<'a> FrameWriter<'a> {
    fn new(buf: &'a mut [u8]) -> postcard::Result<Self> {
        let mut w = Self { buf, pos: 0, code_at: 0, code: 1, digest: CRC32C.digest() };
        w.reserve()?;
        Ok(w)
    }

    /// Takes the next byte of `buf` for a code byte and starts a new block there.
    fn reserve(&mut self) -> postcard::Result<()> {
        self.code_at = self.pos;
        self.code = 1;
        self.put(0)
    }

    fn put(&mut self, byte: u8) -> postcard::Result<()> {
        let slot = self.buf.get_mut(self.pos).ok_or(postcard::Error::SerializeBufferFull)?;
        *slot = byte;
        self.pos = self.pos.checked_add(1).ok_or(postcard::Error::SerializeBufferFull)?;
        Ok(())
    }

    /// Writes the current block's code byte.
    fn close_block(&mut self) -> postcard::Result<()> {
        let slot = self.buf.get_mut(self.code_at).ok_or(postcard::Error::SerializeBufferFull)?;
        *slot = self.code;
        Ok(())
    }

    /// COBS-encodes one byte.
    fn cobs(&mut self, byte: u8) -> postcard::Result<()> {
        if self.code == 0xFF {
            // The block is full (254 data bytes, no implied zero): start the next one.
            self.close_block()?;
            self.reserve()?;
        }
        if byte == 0 {
            self.close_block()?;
            self.reserve()
        } else {
            self.put(byte)?;
            self.code = self.code.saturating_add(1);
            Ok(())
        }
    }
}

impl Flavor for FrameWriter<'_> {
    type Output = usize;

    fn try_push(&mut self, data: u8) -> postcard::Result<()> {
        self.digest.update(&[data]);
        self.cobs(data)
    }

    fn try_extend(&mut self, data: &[u8]) -> postcard::Result<()> {
        self.digest.update(data);
        data.iter().try_for_each(|&b| self.cobs(b))
    }

    fn finalize(mut self) -> postcard::Result<usize> {
        let crc = core::mem::replace(&mut self.digest, CRC32C.digest()).finalize();
        for b in crc.to_le_bytes() {
            self.cobs(b)?;
        }
        self.close_block()?;
        self.put(DELIMITER)?;
        Ok(self.pos)
    }
}

/// Encodes `msg` as one frame into `buf` and returns the frame: the postcard bytes of `msg`
/// followed by their CRC-32C (little-endian), COBS-encoded, then the `0x00` delimiter.
///
/// # Errors
/// [`EncodeError::BufferTooSmall`] if the frame does not fit in `buf` (a buffer of
/// [`MAX_FRAME`](crate::MAX_FRAME) bytes fits every [`Command`](crate::Command) and
/// [`Report`](crate::Report)); [`EncodeError::Serialize`] if postcard refuses the value.
pub fn encode<'b, M: Serialize + ?Sized>(msg: &M, buf: &'b mut [u8]) -> Result<&'b [u8], EncodeError> {
    let writer = FrameWriter::new(&mut *buf).map_err(|_| EncodeError::BufferTooSmall)?;
    let len = postcard::serialize_with_flavor(msg, writer).map_err(|e| match e {
        postcard::Error::SerializeBufferFull => EncodeError::BufferTooSmall,
        _ => EncodeError::Serialize,
    })?;
    buf.get(..len).ok_or(EncodeError::BufferTooSmall)
}

/// Receive counters of a [`FrameDecoder`] (sent by the rig as [`Report::Stats`](crate::Report::Stats)).
///
/// Every counter is a `u32` that **wraps** (modulo 2^32, like an SNMP `Counter32`): at USB
/// full speed `bytes` can pass 2^32 in about an hour, and a saturated counter would then read as
/// "no traffic". Take rates and differences with [`LinkStats::since`], which subtracts
/// modulo 2^32. The frame counters cannot wrap in practice (2^32 frames at 1,000 frames/s
/// take 50 days).
///
/// Every non-empty frame that reached a delimiter (or overflowed) is counted in exactly one
/// of `frames_ok`, `crc_errors`, `cobs_errors`, `decode_errors`, `overflows`; empty frames
/// (two delimiters in a row) are idle line and are not counted. `bytes` counts every byte
/// pushed, delimiters and dropped bytes included.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LinkStats {
    /// Frames that passed every check and decoded into a message.
    pub frames_ok: u32,
    /// Frames whose CRC did not match, or too short to hold one.
    pub crc_errors: u32,
    /// Frames whose COBS structure was broken (cut short: the last block's code byte
    /// announced more bytes than arrived before the delimiter).
    pub cobs_errors: u32,
    /// Frames with a good CRC that postcard could not decode as the message type: an
    /// unknown tag (e.g. a newer peer's message), a bad value, or too few bytes.
    pub decode_errors: u32,
    /// Frames longer than the decoder's capacity, dropped up to the next delimiter.
    pub overflows: u32,
    /// Bytes received (all of them).
    pub bytes: u32,
}

impl LinkStats {
    /// Frames dropped for any reason: the sum of the four error counters (wrapping).
    #[must_use]
    pub const fn dropped(&self) -> u32 {
        self.crc_errors
            .wrapping_add(self.cobs_errors)
            .wrapping_add(self.decode_errors)
            .wrapping_add(self.overflows)
    }

    /// The counts since `earlier` (field by field, modulo 2^32): correct across a wrap.
    #[must_use]
    pub const fn since(&self, earlier: &Self) -> Self {
        Self {
            frames_ok: self.frames_ok.wrapping_sub(earlier.frames_ok),
            crc_errors: self.crc_errors.wrapping_sub(earlier.crc_errors),
            cobs_errors: self.cobs_errors.wrapping_sub(earlier.cobs_errors),
            decode_errors: self.decode_errors.wrapping_sub(earlier.decode_errors),
            overflows: self.overflows.wrapping_sub(earlier.overflows),
            bytes: self.bytes.wrapping_sub(earlier.bytes),
        }
    }
}

/// Why a frame was dropped (each is counted in the matching [`LinkStats`] field).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrameError {
    /// CRC mismatch, or too short for a CRC ([`LinkStats::crc_errors`]).
    Crc,
    /// Broken COBS structure ([`LinkStats::cobs_errors`]).
    Cobs,
    /// Good CRC, but not a valid message: unknown tag or bad value
    /// ([`LinkStats::decode_errors`]).
    Decode,
    /// Longer than the decoder's capacity; the rest of it is skipped up to the next
    /// delimiter ([`LinkStats::overflows`]).
    Overflow,
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Crc => f.write_str("frame dropped: bad CRC"),
            Self::Cobs => f.write_str("frame dropped: broken COBS encoding"),
            Self::Decode => f.write_str("frame dropped: not a valid message (unknown tag?)"),
            Self::Overflow => f.write_str("frame dropped: longer than the receive buffer"),
        }
    }
}

impl core::error::Error for FrameError {}

/// Turns a byte stream into messages of type `M` (a [`Command`](crate::Command) on the rig, a
/// [`Report`](crate::Report) on the host), one byte at a time.
///
/// `CAP` is the longest frame accepted, delimiter included; the default,
/// [`MAX_FRAME`](crate::MAX_FRAME), accepts every frame of this protocol version. The decoder
/// holds a `[u8; CAP]` buffer and a few counters, never allocates, and does constant work per
/// byte, plus one CRC and one postcard decode, both linear in the frame's length (at most
/// `CAP`), at each delimiter.
///
/// Recovery: a frame ends at the next `0x00`, whatever came before it, so after any garbage,
/// cut or corruption the next complete frame decodes. A frame longer than `CAP` is reported
/// ([`FrameError::Overflow`]) as soon as it passes `CAP`, and its remaining bytes are skipped
/// up to the next delimiter.
///
/// ```
/// use meterstick_link::{encode, Command, CommandDecoder, MAX_FRAME};
///
/// let mut buf = [0u8; MAX_FRAME];
/// let frame = encode(&Command::Ping { nonce: 7 }, &mut buf).unwrap();
///
/// let mut decoder = CommandDecoder::new();
/// let mut got = None;
/// for &byte in b"\x13\x37 line noise\x00".iter().chain(frame) {
///     if let Some(Ok(cmd)) = decoder.push(byte) {
///         got = Some(cmd);
///     }
/// }
/// assert_eq!(got, Some(Command::Ping { nonce: 7 }));
/// assert_eq!(decoder.stats().frames_ok, 1);
/// assert_eq!(decoder.stats().dropped(), 1); // the noise
/// ```
pub struct FrameDecoder<M, const CAP: usize = { crate::MAX_FRAME }> {
    /// Decoded bytes of the current frame (message and CRC).
    buf: [u8; CAP],
    /// Decoded bytes in `buf`.
    len: usize,
    /// Encoded bytes of the current frame so far (delimiter excluded).
    raw: usize,
    /// Data bytes left in the current COBS block (0: the next byte is a code byte).
    remaining: u8,
    /// The current block ends with an implied zero (its code was below 0xFF); it is written
    /// when the next block starts, and dropped at the end of the frame.
    pending_zero: bool,
    /// Skipping an overflowed frame up to the next delimiter.
    skipping: bool,
    stats: LinkStats,
    _msg: PhantomData<fn() -> M>,
}

impl<M, const CAP: usize> fmt::Debug for FrameDecoder<M, CAP> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FrameDecoder")
            .field("cap", &CAP)
            .field("len", &self.len)
            .field("raw", &self.raw)
            .field("skipping", &self.skipping)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl<M, const CAP: usize> Default for FrameDecoder<M, CAP> {
    fn default() -> Self {
        Self::new()
    }
}

impl<M, const CAP: usize> FrameDecoder<M, CAP> {
    /// An idle decoder with zeroed counters.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            buf: [0; CAP],
            len: 0,
            raw: 0,
            remaining: 0,
            pending_zero: false,
            skipping: false,
            stats: LinkStats {
                frames_ok: 0,
                crc_errors: 0,
                cobs_errors: 0,
                decode_errors: 0,
                overflows: 0,
                bytes: 0,
            },
            _msg: PhantomData,
        }
    }

    /// The receive counters.
    #[must_use]
    pub const fn stats(&self) -> LinkStats {
        self.stats
    }

    /// Zeroes the receive counters.
    pub fn clear_stats(&mut self) {
        self.stats = LinkStats::default();
    }

    /// Forgets the frame in progress, uncounted (e.g. after reopening the port). Same as
    /// what a delimiter does, without reporting the partial frame.
    pub fn reset(&mut self) {
        self.len = 0;
        self.raw = 0;
        self.remaining = 0;
        self.pending_zero = false;
        self.skipping = false;
    }

    /// `true` between frames (no partial frame buffered).
    #[must_use]
    pub const fn is_idle(&self) -> bool {
        self.raw == 0 && !self.skipping
    }

    /// Starts skipping an overflowed frame.
    fn overflow(&mut self) -> FrameError {
        self.reset();
        self.skipping = true;
        self.stats.overflows = self.stats.overflows.wrapping_add(1);
        FrameError::Overflow
    }

    /// Appends one decoded byte.
    fn store(&mut self, byte: u8) -> Result<(), FrameError> {
        match self.buf.get_mut(self.len) {
            Some(slot) => {
                *slot = byte;
                self.len = self.len.saturating_add(1);
                Ok(())
            }
            // Unreachable (decoded bytes < encoded bytes <= CAP - 1), handled anyway.
            None => Err(self.overflow()),
        }
    }
}

impl<M: DeserializeOwned, const CAP: usize> FrameDecoder<M, CAP> {
    /// Feeds one byte. Returns `None` while a frame is in progress (and for idle
    /// delimiters), `Some(Ok(msg))` when a frame completes and decodes, and
    /// `Some(Err(_))` when a frame is dropped (already counted in [`Self::stats`]).
    pub fn push(&mut self, byte: u8) -> Option<Result<M, FrameError>> {
        self.stats.bytes = self.stats.bytes.wrapping_add(1);
        if byte == DELIMITER {
            return self.end_frame();
        }
        if self.skipping {
            return None;
        }
        // Accept at most CAP - 1 bytes before the delimiter.
        if self.raw >= CAP.saturating_sub(1) {
            return Some(Err(self.overflow()));
        }
        self.raw = self.raw.saturating_add(1);
        let stored = if self.remaining == 0 {
            // A code byte: the previous block's implied zero (if any) is now known to be
            // data, and the new block holds `byte - 1` data bytes.
            let zero = if self.pending_zero { self.store(0) } else { Ok(()) };
            self.remaining = byte.saturating_sub(1);
            self.pending_zero = byte != 0xFF;
            zero
        } else {
            self.remaining = self.remaining.saturating_sub(1);
            self.store(byte)
        };
        stored.err().map(Err)
    }

    /// Feeds a slice of bytes, calling `on_frame` for every frame that completes (a message
    /// or a drop, as [`Self::push`] returns them). Consumes all of `bytes`.
    pub fn feed(&mut self, bytes: &[u8], mut on_frame: impl FnMut(Result<M, FrameError>)) {
        for &b in bytes {
            if let Some(r) = self.push(b) {
                on_frame(r);
            }
        }
    }

    /// A delimiter: checks and decodes the frame it ends.
    fn end_frame(&mut self) -> Option<Result<M, FrameError>> {
        let (raw, len, remaining, skipping) = (self.raw, self.len, self.remaining, self.skipping);
        self.reset();
        if skipping || raw == 0 {
            // The end of an overflowed frame (reported already), or idle line.
            return None;
        }
        if remaining != 0 {
            self.stats.cobs_errors = self.stats.cobs_errors.wrapping_add(1);
            return Some(Err(FrameError::Cobs));
        }
        // The final implied zero (pending_zero) is the end of the data: dropped.
        let frame = self.buf.get(..len).unwrap_or_default();
        let Some((body, crc)) = frame.split_last_chunk::<CRC_LEN>() else {
            self.stats.crc_errors = self.stats.crc_errors.wrapping_add(1);
            return Some(Err(FrameError::Crc));
        };
        if crc32c(body) != u32::from_le_bytes(*crc) {
            self.stats.crc_errors = self.stats.crc_errors.wrapping_add(1);
            return Some(Err(FrameError::Crc));
        }
        if let Ok(msg) = postcard::from_bytes::<M>(body) {
            self.stats.frames_ok = self.stats.frames_ok.wrapping_add(1);
            Some(Ok(msg))
        } else {
            self.stats.decode_errors = self.stats.decode_errors.wrapping_add(1);
            Some(Err(FrameError::Decode))
        }
    }
}
