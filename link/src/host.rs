//! The host's end of the link (feature `std`): [`Link`], a rig on a serial port (the Black
//! Pill's USB CDC port, a USB-serial adapter on a UART) or a TCP socket (QEMU's UART), commands
//! out and reports in, decoded on a reader thread; [`is_reply_to`], the reply table. `host-sim
//! monitor` (host-sim/src/monitor/) and the end-to-end tests (tests/tests/link_checks/) drive
//! rigs with it.

extern crate std;

use std::borrow::ToOwned;
use std::boxed::Box;
use std::collections::VecDeque;
use std::format;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::string::String;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};

use crate::{Command, ErrorCode, LinkStats, Report, ReportDecoder, encode};

/// How long to wait for the reply to one command.
pub const REPLY_TIMEOUT: Duration = Duration::from_secs(5);

/// An open link to a rig: commands out, reports in (decoded on a reader thread).
pub struct Link {
    writer: Box<dyn Write + Send>,
    reports: Receiver<Report>,
    stats: Arc<Mutex<LinkStats>>,
    /// Reports received while waiting for a reply (telemetry, events, state changes).
    pub backlog: VecDeque<Report>,
    /// Where it is connected (as the user gave it).
    pub name: String,
}

impl std::fmt::Debug for Link {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Link")
            .field("name", &self.name)
            .field("backlog", &self.backlog.len())
            .finish_non_exhaustive()
    }
}

impl Link {
    /// Opens `port`: `tcp:HOST:PORT`, or a serial port at `baud`.
    ///
    /// # Errors
    /// The port cannot be opened (named in the message).
    pub fn open(port: &str, baud: u32) -> anyhow::Result<Self> {
        if let Some(addr) = port.strip_prefix("tcp:") {
            let stream = TcpStream::connect(addr)
                .with_context(|| format!("--port {port}: cannot connect to {addr}"))?;
            return Self::tcp(stream, port);
        }
        let serial = serial2::SerialPort::open(port, baud)
            .with_context(|| format!("--port {port}: cannot open the serial port at {baud} baud"))?;
        let mut reader = serial.try_clone().with_context(|| format!("--port {port}"))?;
        reader.set_read_timeout(Duration::from_millis(200)).with_context(|| format!("--port {port}"))?;
        let name = port.to_owned();
        Ok(Self::start(
            Box::new(SerialWriter(serial)),
            move |buf| match reader.read(buf) {
                Ok(0) => Err(()),
                Ok(n) => Ok(n),
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => Ok(0),
                Err(_) => Err(()),
            },
            name,
        ))
    }

    /// A link over a connected TCP stream (named `name` in messages).
    ///
    /// # Errors
    /// The stream cannot be cloned for the reader thread.
    pub fn tcp(stream: TcpStream, name: &str) -> anyhow::Result<Self> {
        stream.set_nodelay(true).ok();
        let mut reader = stream.try_clone().with_context(|| format!("{name}: cloning the socket"))?;
        let mut link = Self::start(
            Box::new(stream),
            move |buf| match reader.read(buf) {
                Ok(0) | Err(_) => Err(()),
                Ok(n) => Ok(n),
            },
            name.to_owned(),
        );
        // Close off whatever the rig may have half-received (the link crate's rule).
        link.send_raw(&[crate::DELIMITER])?;
        Ok(link)
    }

    fn start(
        writer: Box<dyn Write + Send>,
        mut read: impl FnMut(&mut [u8]) -> Result<usize, ()> + Send + 'static,
        name: String,
    ) -> Self {
        let (tx, rx): (Sender<Report>, Receiver<Report>) = channel();
        let stats = Arc::new(Mutex::new(LinkStats::default()));
        let shared = Arc::clone(&stats);
        std::thread::spawn(move || {
            let mut decoder = ReportDecoder::new();
            let mut buf = [0u8; 4096];
            while let Ok(n) = read(&mut buf) {
                let mut open = true;
                decoder.feed(buf.get(..n).unwrap_or(&[]), |frame| {
                    if let Ok(report) = frame {
                        open &= tx.send(report).is_ok();
                    }
                });
                if let Ok(mut s) = shared.lock() {
                    *s = decoder.stats();
                }
                if !open {
                    break;
                }
            }
        });
        Self { writer, reports: rx, stats, backlog: VecDeque::new(), name }
    }

    /// The host's receive counters (frames decoded, CRC errors, ...).
    #[must_use]
    pub fn host_stats(&self) -> LinkStats {
        self.stats.lock().map(|s| *s).unwrap_or_default()
    }

    /// Sends one command.
    ///
    /// # Errors
    /// The write failed.
    pub fn send(&mut self, command: &Command) -> anyhow::Result<()> {
        let mut buf = [0u8; crate::MAX_FRAME];
        let frame = encode(command, &mut buf).context("encoding a command")?;
        self.send_raw(frame)
    }

    /// Sends raw bytes (tests: garbage, cut frames).
    ///
    /// # Errors
    /// The write failed.
    pub fn send_raw(&mut self, bytes: &[u8]) -> anyhow::Result<()> {
        self.writer
            .write_all(bytes)
            .and_then(|()| self.writer.flush())
            .with_context(|| format!("writing to {}", self.name))
    }

    /// The next report (the backlog first), waiting at most `timeout`; `None` on timeout.
    ///
    /// # Errors
    /// The link closed.
    pub fn next(&mut self, timeout: Duration) -> anyhow::Result<Option<Report>> {
        if let Some(r) = self.backlog.pop_front() {
            return Ok(Some(r));
        }
        match self.reports.recv_timeout(timeout) {
            Ok(r) => Ok(Some(r)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => bail!("{}: the link closed", self.name),
        }
    }

    /// Sends `command` and waits for its reply ([`is_reply_to`]); other reports received
    /// meanwhile go to [`Self::backlog`].
    ///
    /// # Errors
    /// No reply within `timeout`, or the link failed.
    pub fn request(&mut self, command: &Command, timeout: Duration) -> anyhow::Result<Report> {
        self.send(command)?;
        // A timeout too long for an `Instant`: each wait is the whole timeout.
        let deadline = Instant::now().checked_add(timeout);
        loop {
            let left = deadline.map_or(timeout, |d| d.saturating_duration_since(Instant::now()));
            match self.reports.recv_timeout(left) {
                Ok(r) if is_reply_to(command, &r) => return Ok(r),
                Ok(r) => self.backlog.push_back(r),
                Err(RecvTimeoutError::Timeout) => {
                    bail!("{}: no reply to {command:?} within {:.1} s", self.name, timeout.as_secs_f64())
                }
                Err(RecvTimeoutError::Disconnected) => bail!("{}: the link closed", self.name),
            }
        }
    }
}

struct SerialWriter(serial2::SerialPort);

impl Write for SerialWriter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.0.flush()
    }
}

/// `true` when `report` is the rig's reply to `command` (the link crate's reply table).
#[must_use]
pub fn is_reply_to(command: &Command, report: &Report) -> bool {
    let tag = command.tag();
    match (command, report) {
        (Command::Hello, Report::Hello { .. })
        | (Command::GetStats, Report::Stats(_))
        | (Command::Preset(_), Report::Rejected { .. }) => true,
        (Command::Ping { nonce }, Report::Pong { nonce: n }) => nonce == n,
        (Command::SelectScene(scene), Report::Error(ErrorCode::NoSuchScene(s))) => scene == s,
        (Command::GetParam { id }, Report::Param { id: i, .. })
        | (Command::SetParam { id, .. }, Report::Rejected { id: i, .. }) => id == i,
        (_, Report::Ack { command } | Report::Error(ErrorCode::NotAllowed { command, .. })) => {
            *command == tag
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use std::string::ToString;

    use super::*;
    use crate::{ParamId, RejectReason, RigState};

    #[test]
    fn a_port_that_cannot_be_opened_is_named() {
        let e = Link::open("/dev/meterstick-no-such-port", 115_200).unwrap_err().to_string();
        assert!(e.starts_with("--port /dev/meterstick-no-such-port: cannot open"), "{e}");
        // A closed local port: connection refused, named as given.
        let free = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
        let e = Link::open(&format!("tcp:127.0.0.1:{free}"), 0).unwrap_err().to_string();
        assert!(e.starts_with(&format!("--port tcp:127.0.0.1:{free}: cannot connect")), "{e}");
    }

    #[test]
    fn replies_match_their_commands() {
        let set = Command::SetParam { id: ParamId::Gravity, value: 1.0 };
        assert!(is_reply_to(&set, &Report::Ack { command: set.tag() }));
        assert!(is_reply_to(&set, &Report::Rejected { id: ParamId::Gravity, reason: RejectReason::Busy }));
        assert!(!is_reply_to(&set, &Report::Rejected { id: ParamId::Step, reason: RejectReason::Busy }));
        let fast = Command::Preset(crate::Preset::Fast);
        let beyond = Report::Rejected { id: ParamId::Finger1Velocity, reason: RejectReason::BeyondRig };
        assert!(is_reply_to(&fast, &beyond));
        assert!(is_reply_to(&Command::Ping { nonce: 3 }, &Report::Pong { nonce: 3 }));
        assert!(!is_reply_to(&Command::Ping { nonce: 3 }, &Report::Pong { nonce: 4 }));
        assert!(!is_reply_to(&Command::Start, &Report::Ack { command: Command::Stop.tag() }));
        assert!(is_reply_to(
            &Command::Start,
            &Report::Error(ErrorCode::NotAllowed { command: Command::Start.tag(), state: RigState::Running })
        ));
        assert!(!is_reply_to(&Command::Start, &Report::State(RigState::Running)));
        let stack = Command::SelectScene(crate::SceneId::Stack);
        assert!(is_reply_to(&stack, &Report::Error(ErrorCode::NoSuchScene(crate::SceneId::Stack))));
        assert!(!is_reply_to(&stack, &Report::Error(ErrorCode::NoSuchScene(crate::SceneId::Ladder))));
        assert!(is_reply_to(&stack, &Report::Ack { command: stack.tag() }));
    }
}
