//! Byte-stream helpers over the blocking [`embedded_io`] traits: write one message, read
//! bytes into a [`FrameDecoder`].
//!
//! On the rig these wrap the UART or USB CDC halves; on a host, anything that implements
//! `embedded_io::{Read, Write}` (e.g. a `std::net::TcpStream` through
//! `embedded-io-adapters`' `FromStd`, or a small wrapper).

use core::fmt;

use embedded_io::{Read, ReadReady, Write};
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::MAX_FRAME;
use crate::frame::{EncodeError, FrameDecoder, FrameError, encode};

/// Bytes read per call of [`read_into`] / [`poll_into`] at most (a stack buffer).
pub const READ_CHUNK: usize = 32;

/// Why [`write_message`] failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum WriteError<E> {
    /// The message does not fit in a frame of [`MAX_FRAME`] bytes (only possible for a type
    /// other than [`Command`](crate::Command) / [`Report`](crate::Report)).
    Encode(EncodeError),
    /// The writer failed; part of the frame may have been written (the receiver drops it
    /// and resynchronises at the next delimiter).
    Io(E),
    /// The writer accepted no byte (`write` returned `Ok(0)`), or claimed more than it was
    /// given: it cannot take the frame.
    WriteZero,
}

impl<E: fmt::Debug> fmt::Display for WriteError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Encode(e) => write!(f, "cannot encode the message: {e}"),
            Self::Io(e) => write!(f, "write failed: {e:?}"),
            Self::WriteZero => f.write_str("the writer accepted no bytes"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for WriteError<E> {}

/// Encodes `msg` into one frame (on the stack, [`MAX_FRAME`] bytes) and writes all of it.
/// Returns the frame's length. Does not flush.
///
/// Unlike `embedded_io::Write::write_all`, a writer that returns `Ok(0)` is an error
/// ([`WriteError::WriteZero`]), not a panic.
///
/// # Errors
/// See [`WriteError`].
pub fn write_message<W, M>(w: &mut W, msg: &M) -> Result<usize, WriteError<W::Error>>
where
    W: Write + ?Sized,
    M: Serialize + ?Sized,
{
    let mut buf = [0u8; MAX_FRAME];
    let frame = encode(msg, &mut buf).map_err(WriteError::Encode)?;
    write_all(w, frame)?;
    Ok(frame.len())
}

/// Writes all of `bytes` (e.g. a frame from [`encode`]); see [`write_message`].
///
/// # Errors
/// [`WriteError::Io`] or [`WriteError::WriteZero`].
pub fn write_all<W: Write + ?Sized>(w: &mut W, mut bytes: &[u8]) -> Result<(), WriteError<W::Error>> {
    while !bytes.is_empty() {
        match w.write(bytes) {
            Ok(0) => return Err(WriteError::WriteZero),
            Ok(n) => bytes = bytes.get(n..).ok_or(WriteError::WriteZero)?,
            Err(e) => return Err(WriteError::Io(e)),
        }
    }
    Ok(())
}

/// One blocking `read` of up to [`READ_CHUNK`] bytes, all fed to `decoder`; `on_frame` gets
/// every frame completed by them (see [`FrameDecoder::push`]). Returns the number of bytes
/// read: 0 means the end of the stream.
///
/// # Errors
/// The reader's error; nothing was fed then.
pub fn read_into<R, M, const CAP: usize>(
    r: &mut R,
    decoder: &mut FrameDecoder<M, CAP>,
    on_frame: impl FnMut(Result<M, FrameError>),
) -> Result<usize, R::Error>
where
    R: Read + ?Sized,
    M: DeserializeOwned,
{
    let mut chunk = [0u8; READ_CHUNK];
    let n = r.read(&mut chunk)?;
    // A reader claiming more than the buffer is broken: feed what the buffer holds.
    let got = chunk.get(..n).unwrap_or(&chunk);
    decoder.feed(got, on_frame);
    Ok(got.len())
}

/// Like [`read_into`], but returns `Ok(0)` at once when the reader has no byte ready: for a
/// rig's main loop, which must not block. At most one `read` of [`READ_CHUNK`] bytes per
/// call, so the work per call is bounded; call it again while it returns `Ok(n)` with
/// `n > 0` to drain a backlog.
///
/// # Errors
/// The reader's error.
pub fn poll_into<R, M, const CAP: usize>(
    r: &mut R,
    decoder: &mut FrameDecoder<M, CAP>,
    on_frame: impl FnMut(Result<M, FrameError>),
) -> Result<usize, R::Error>
where
    R: Read + ReadReady + ?Sized,
    M: DeserializeOwned,
{
    if r.read_ready()? { read_into(r, decoder, on_frame) } else { Ok(0) }
}
