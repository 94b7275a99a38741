//! What the session tests share: an in-memory port and a command's frame.
#![allow(dead_code, clippy::unwrap_used)]
#![allow(clippy::trivially_copy_pass_by_ref)] // commands as the link's `encode` takes them

use std::collections::VecDeque;

use meterstick_link::{Command, MAX_FRAME, encode};
use meterstick_rig::session::Port;

/// An in-memory byte pipe: what the host wrote waits in `rx`; what the rig wrote lands in `tx`,
/// at most `room` bytes per write (`usize::MAX`: all).
pub struct Pipe {
    pub rx: VecDeque<u8>,
    pub tx: Vec<u8>,
    pub room: usize,
    pub reads: usize,
}

impl Port for Pipe {
    fn read(&mut self, buf: &mut [u8]) -> usize {
        self.reads += 1;
        let n = buf.len().min(self.rx.len());
        for (b, byte) in buf.iter_mut().zip(self.rx.drain(..n)) {
            *b = byte;
        }
        n
    }
    fn write(&mut self, bytes: &[u8]) -> usize {
        let n = bytes.len().min(self.room);
        self.tx.extend_from_slice(&bytes[..n]);
        n
    }
}

impl Pipe {
    /// Empty both ways, taking every write whole.
    pub fn new() -> Self {
        Self { rx: VecDeque::new(), tx: Vec::new(), room: usize::MAX, reads: 0 }
    }
}

/// The frame of `command`.
pub fn frame(command: &Command) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME];
    encode(command, &mut buf).unwrap().to_vec()
}
