//! The session's transmit queue: a byte ring buffer the board drains without blocking.

use super::{Port, TX_CAP};

/// A byte ring buffer.
pub(super) struct TxQueue {
    buf: [u8; TX_CAP],
    head: usize,
    pub(super) len: usize,
}

impl TxQueue {
    #[inline]
    pub(super) const fn new() -> Self {
        Self { buf: [0; TX_CAP], head: 0, len: 0 }
    }

    #[inline]
    pub(super) const fn free(&self) -> usize {
        TX_CAP.saturating_sub(self.len)
    }

    /// Appends all of `bytes`, or nothing when they do not fit.
    #[inline]
    pub(super) fn push(&mut self, bytes: &[u8]) -> bool {
        if bytes.len() > self.free() {
            return false;
        }
        for &b in bytes {
            if let Some(slot) = self.buf.get_mut(self.head.wrapping_add(self.len) % TX_CAP) {
                *slot = b;
            }
            self.len = self.len.wrapping_add(1);
        }
        true
    }

    /// Hands the queue to `port` until it takes no more.
    pub(super) fn drain(&mut self, port: &mut impl Port) {
        while self.len > 0 {
            let end = self.head.saturating_add(self.len).min(TX_CAP);
            let Some(chunk) = self.buf.get(self.head..end) else { return };
            let n = port.write(chunk).min(chunk.len());
            if n == 0 {
                return;
            }
            self.head = self.head.wrapping_add(n) % TX_CAP;
            self.len = self.len.saturating_sub(n);
        }
    }
}
