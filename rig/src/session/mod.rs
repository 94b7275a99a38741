//! The rig's end of the host link, independent of the board: commands from a [`Port`] (a UART
//! under QEMU and on the Picos, USB CDC or USART2 on the Black Pill) are decoded with
//! `meterstick-link`'s [`CommandDecoder`] and carried out on the [`Rig`]; telemetry, switch
//! events, outcomes, real-time margins and replies are encoded into a transmit queue that the
//! board drains without blocking. One session serves any scene a board runs ([`LinkScene`]: the
//! meter stick, one [`Report::Telemetry`] a telemetry step and [`Report::Switch`] events; the
//! stack, one [`Report::Body`] per block and [`Report::InterfaceSwitch`] events), and a board that
//! runs several switches between them on [`Command::SelectScene`] ([`Session::poll`] returns the
//! scene asked for, [`Session::select`] carries the session over to it).
//!
//! The board's loop, once per tick:
//!
//! ```text
//! session.poll(&mut port, &mut rig)         // commands (bounded work per call)
//! t0 = now; rig.tick_with(|r| session.record(r)); t1 = now
//! session.end_tick(&rig, cycles(t0, t1))    // checksum, events, telemetry, state changes
//! session.flush(&mut port)                  // as much of the queue as the port takes now
//! ```
//!
//! Rules (the link crate's docs, "reply rule"): every decoded command gets exactly one reply;
//! a frame that does not decode gets none and is counted by the decoder ([`Command::GetStats`]
//! reads the counters). Parameters are validated by the core (the scene's `validate`, through
//! [`Rig::reset`]) and checked against the rig ([`crate::RigScene::check`]): a refused
//! value gets [`Report::Rejected`] naming it ([`RejectReason::BeyondRig`] for a value the rig
//! cannot perform; a preset the rig cannot perform, e.g. the fast one on a carriage slower than
//! 5 m/s, is refused the same way, naming the parameter), and the rig keeps its previous, valid
//! set. A run that ends in a fault is reported as an error naming it
//! ([`ErrorCode::ActuatorOverrun`] when the carriage could not follow, else
//! [`ErrorCode::CoreFault`]), then the outcome with the same cause. When the queue is full,
//! telemetry is dropped first (it needs [`RESERVE`] bytes to spare); anything dropped is counted
//! and announced with [`ErrorCode::TxDropped`] once there is room again. Nothing here can panic:
//! no indexing, no slicing that can fail, no unchecked arithmetic that matters (counters wrap).

mod codes;
mod queue;
mod scene;

pub use codes::outcome_code;
/// The link's scene ids, for a board that selects among its scenes ([`Session::with_scenes`]).
pub use meterstick_link::SceneId;
pub use scene::LinkScene;

use embedded_hal::digital::{InputPin, OutputPin};
use meterstick_core::planar::Checksum;
use meterstick_link::{
    Command, CommandDecoder, DEFAULT_TELEMETRY_EVERY, DELIMITER, ErrorCode, MAX_FRAME, OutcomeCode,
    PROTOCOL_VERSION, RejectReason, Report, RigState, encode,
};

use codes::{fault_code, fault_error, param_of, reason_of, state_of};
use queue::TxQueue;

use crate::{Actuator, Rig, RigError, RigState as CoreState};

/// A byte link that never blocks.
pub trait Port {
    /// Moves the bytes received so far (at most `buf.len()`) into `buf`; returns how many.
    fn read(&mut self, buf: &mut [u8]) -> usize;
    /// Sends as many of `bytes` as the link takes now; returns how many (0: none).
    fn write(&mut self, bytes: &[u8]) -> usize;
}

/// Transmit queue size (bytes): 15 telemetry frames.
pub const TX_CAP: usize = 1024;
/// Bytes a telemetry frame must leave free in the queue, for replies and events.
pub const RESERVE: usize = 3 * MAX_FRAME;
/// Received bytes handled per [`Session::poll`] at most (bounded work per tick; a flood waits
/// in the port, whose own buffer or flow control holds it).
pub const POLL_BYTES: usize = 256;
/// Bytes asked of the port per read ([`POLL_BYTES`] is a multiple of it).
const POLL_CHUNK: usize = 32;
const _: () = assert!(POLL_BYTES.is_multiple_of(POLL_CHUNK));
/// A [`Report::Margin`] every this many steps while running (and one at the end of the run).
pub const MARGIN_EVERY: u32 = 1000;

/// The link session for the scene `S` shown on `L` lights: decoder, transmit queue, telemetry
/// rate and the current run's figures.
pub struct Session<S: LinkScene<L>, const L: usize> {
    decoder: CommandDecoder,
    tx: TxQueue,
    every: u16,
    checksum: Checksum,
    steps: u32,
    last: RigState,
    pending: Option<S::Report>,
    /// The rig's lights after the last tick (what a step's events compare with).
    shown: [Option<S::Mode>; L],
    /// The scenes the board runs besides `S` ([`Command::SelectScene`]).
    scenes: &'static [SceneId],
    worst: u32,
    worst_step: u32,
    overruns: u32,
    period: u32,
    dropped: u32,
    firmware: (u8, u8, u8),
    build: [u8; 8],
}

impl<S: LinkScene<L>, const L: usize> core::fmt::Debug for Session<S, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Session")
            .field("steps", &self.steps)
            .field("state", &self.last)
            .field("queued", &self.tx.len)
            .field("dropped", &self.dropped)
            .finish_non_exhaustive()
    }
}

impl<S: LinkScene<L>, const L: usize> Session<S, L> {
    /// A session for a rig whose step period is `period_cycles` CPU cycles (0 when it does not
    /// run in real time, e.g. under QEMU), for firmware version `firmware` ([`version`] of the
    /// firmware crate's `CARGO_PKG_VERSION`) and build id `build` (see [`build_id`]), both sent
    /// in [`Report::Hello`]. It runs `S` only until [`Self::with_scenes`] names others.
    #[must_use]
    #[inline]
    pub const fn new(period_cycles: u32, firmware: (u8, u8, u8), build: [u8; 8]) -> Self {
        Self {
            decoder: CommandDecoder::new(),
            tx: TxQueue::new(),
            every: DEFAULT_TELEMETRY_EVERY,
            checksum: Checksum::new(),
            steps: 0,
            last: RigState::Waiting,
            pending: None,
            shown: [None; L],
            scenes: &[],
            worst: 0,
            worst_step: 0,
            overruns: 0,
            period: period_cycles,
            dropped: 0,
            firmware,
            build,
        }
    }

    /// The session with `scenes`, the scenes the board runs ([`Command::SelectScene`] is
    /// refused with [`ErrorCode::NoSuchScene`] for any other than these and `S`).
    #[must_use]
    #[inline]
    pub const fn with_scenes(mut self, scenes: &'static [SceneId]) -> Self {
        self.scenes = scenes;
        self
    }

    /// At boot: a lone delimiter (closes whatever the host had half-received), then
    /// [`Report::Hello`] and [`Report::State`].
    pub fn boot<A, B, P, E>(&mut self, rig: &Rig<S, A, B, P, L>)
    where
        A: Actuator<S, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        let _ = self.tx.push(&[DELIMITER]);
        self.announce(rig);
    }

    /// [`Report::Hello`] and [`Report::State`] for `rig`.
    fn announce<A, B, P, E>(&mut self, rig: &Rig<S, A, B, P, L>)
    where
        A: Actuator<S, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        self.send(&hello::<S, L>(rig.params(), self.firmware, self.build));
        self.last = state_of(rig.state());
        self.shown = *rig.shown();
        self.send(&Report::State(self.last));
    }

    /// The session carried over to the scene `S2` of `rig` (after [`Self::poll`] returned it):
    /// the decoder, its counters, the queue and the telemetry rate kept, the run's figures
    /// cleared; it announces the new scene ([`Report::Hello`], [`Report::State`]).
    #[must_use]
    pub fn select<S2, A, B, P, E, const L2: usize>(self, rig: &Rig<S2, A, B, P, L2>) -> Session<S2, L2>
    where
        S2: LinkScene<L2>,
        A: Actuator<S2, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        let mut next = Session::<S2, L2> {
            decoder: self.decoder,
            tx: self.tx,
            every: self.every,
            period: self.period,
            dropped: self.dropped,
            firmware: self.firmware,
            build: self.build,
            scenes: self.scenes,
            ..Session::new(self.period, self.firmware, self.build)
        };
        next.announce(rig);
        next
    }

    /// Sets the step period (CPU cycles) the margins are reported against.
    #[inline]
    pub fn set_period(&mut self, period_cycles: u32) {
        self.period = period_cycles;
    }

    /// Reads and carries out the commands received (at most [`POLL_BYTES`] bytes); returns the
    /// scene a [`Command::SelectScene`] asked for (acknowledged), for the board to switch to
    /// ([`Self::select`]); the commands after it wait in the port.
    ///
    /// # Errors
    /// A pin error from the rig.
    pub fn poll<Pt, A, B, P, E>(
        &mut self,
        port: &mut Pt,
        rig: &mut Rig<S, A, B, P, L>,
    ) -> Result<Option<SceneId>, RigError<E>>
    where
        Pt: Port,
        A: Actuator<S, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        // Whole chunks only: every byte taken from the port is handled, at most POLL_BYTES of
        // them, and the ports' reads get a fixed-size buffer (a slice of run-time length keeps
        // a bounds check, a panic path, in rp235x-hal's UART read).
        let mut chunk = [0u8; POLL_CHUNK];
        for _ in 0..POLL_BYTES / POLL_CHUNK {
            let n = port.read(&mut chunk).min(POLL_CHUNK);
            for &byte in chunk.get(..n).unwrap_or(&[]) {
                if let Some(Ok(command)) = self.decoder.push(byte)
                    && let Some(scene) = self.handle(command, rig)?
                {
                    // The bytes after it in this chunk are lost with the scene's session: a host
                    // waits for the new Hello before it sends more.
                    return Ok(Some(scene));
                }
            }
            if n < POLL_CHUNK {
                break; // the port has nothing more now
            }
        }
        Ok(None)
    }

    /// Keeps the report of the step the rig just made (call from [`Rig::tick_with`]).
    #[inline]
    pub fn record(&mut self, report: &S::Report)
    where
        S::Report: Copy,
    {
        self.pending = Some(*report);
    }

    /// After a tick that took `cycles`: the step's checksum, switch events, telemetry and
    /// margin, then the reports of a state change (run started: state and the step-0
    /// telemetry; run ended: outcome, margin and state).
    pub fn end_tick<A, B, P, E>(&mut self, rig: &Rig<S, A, B, P, L>, cycles: u32)
    where
        A: Actuator<S, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        if let Some(report) = self.pending.take() {
            self.steps = self.steps.wrapping_add(1);
            S::checksum(&mut self.checksum, &report);
            if cycles > self.worst {
                self.worst = cycles;
                self.worst_step = self.steps;
            }
            if self.period > 0 && cycles > self.period {
                self.overruns = self.overruns.wrapping_add(1);
            }
            let (before, shown) = (self.shown, *rig.shown());
            S::events(&report, &before, &shown, self.steps, |r| self.send(r));
            self.shown = shown;
            if self.every > 0 && self.steps.is_multiple_of(u32::from(self.every)) {
                rig.scene().telemetry(Some(&report), &shown, self.steps, |r| self.send_telemetry(r));
            }
            if self.steps.is_multiple_of(MARGIN_EVERY) {
                self.send(&self.margin());
            }
        }
        self.sync(rig);
    }

    /// Sends as much of the transmit queue as `port` takes now; announces dropped reports once
    /// there is room, and not in the space kept for replies ([`RESERVE`]): while the port stalls,
    /// the count grows instead (an announcement per flush filled that space, and a `Pong` was
    /// lost).
    pub fn flush(&mut self, port: &mut impl Port) {
        self.tx.drain(port);
        if self.dropped > 0 {
            let mut buf = [0u8; MAX_FRAME];
            if let Ok(frame) = encode(&Report::Error(ErrorCode::TxDropped { count: self.dropped }), &mut buf)
                && self.tx.free() >= frame.len().saturating_add(RESERVE)
                && self.tx.push(frame)
            {
                self.dropped = 0;
                self.tx.drain(port);
            }
        }
    }

    /// `true` while reports wait to be sent.
    #[must_use]
    #[inline]
    pub const fn busy(&self) -> bool {
        self.tx.len > 0
    }

    #[inline]
    fn margin(&self) -> Report {
        Report::Margin {
            worst_cycles: self.worst,
            period_cycles: self.period,
            overruns: self.overruns,
            worst_step: self.worst_step,
        }
    }

    /// Queues a report that must not be lost (a reply, an event, an outcome): dropped (and
    /// counted) only when the queue is full.
    #[inline]
    fn send(&mut self, report: &Report) {
        let mut buf = [0u8; MAX_FRAME];
        let ok = match encode(report, &mut buf) {
            Ok(frame) => self.tx.push(frame),
            Err(_) => false,
        };
        if !ok {
            self.dropped = self.dropped.wrapping_add(1);
        }
    }

    /// Queues a telemetry report: only while it leaves [`RESERVE`] bytes free (else dropped and
    /// counted).
    fn send_telemetry(&mut self, report: &Report) {
        let mut buf = [0u8; MAX_FRAME];
        let ok = match encode(report, &mut buf) {
            Ok(frame) => self.tx.free() >= frame.len().saturating_add(RESERVE) && self.tx.push(frame),
            Err(_) => false,
        };
        if !ok {
            self.dropped = self.dropped.wrapping_add(1);
        }
    }

    /// Reports a change of the rig's state since the last call.
    fn sync<A, B, P, E>(&mut self, rig: &Rig<S, A, B, P, L>)
    where
        A: Actuator<S, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        let core = rig.state();
        let now = state_of(core);
        if now == self.last {
            return;
        }
        if now == RigState::Running {
            self.checksum = Checksum::new();
            self.steps = 0;
            self.worst = 0;
            self.worst_step = 0;
            self.overruns = 0;
            self.pending = None;
            self.shown = *rig.shown();
            self.send(&Report::State(now));
            if self.every > 0 {
                let shown = self.shown;
                rig.scene().telemetry(None, &shown, 0, |r| self.send_telemetry(r));
            }
        } else {
            if self.last == RigState::Running {
                let outcome = match core {
                    CoreState::Finished(o) => outcome_code(o),
                    CoreState::Fault(f) => {
                        self.send(&Report::Error(fault_error(f)));
                        fault_code(f)
                    }
                    _ => OutcomeCode::Unfinished,
                };
                self.send(&Report::Outcome {
                    outcome,
                    time: rig.scene().time(),
                    steps: self.steps,
                    checksum: self.checksum.value(),
                });
                self.send(&self.margin());
            }
            self.send(&Report::State(now));
        }
        self.last = now;
    }

    /// Carries out `command` and queues its reply; returns the scene a
    /// [`Command::SelectScene`] switches to.
    fn handle<A, B, P, E>(
        &mut self,
        command: Command,
        rig: &mut Rig<S, A, B, P, L>,
    ) -> Result<Option<SceneId>, RigError<E>>
    where
        A: Actuator<S, E>,
        B: InputPin<Error = E>,
        P: OutputPin<Error = E>,
    {
        let tag = command.tag();
        let ack = Report::Ack { command: tag };
        let state = state_of(rig.state());
        let not_allowed = Report::Error(ErrorCode::NotAllowed { command: tag, state });
        let reply = match command {
            Command::Hello => hello::<S, L>(rig.params(), self.firmware, self.build),
            Command::Ping { nonce } => Report::Pong { nonce },
            Command::GetStats => Report::Stats(self.decoder.stats()),
            Command::GetParam { id } => {
                Report::Param { id, value: S::param(rig.params(), id).unwrap_or(f32::NAN) }
            }
            Command::SetTelemetry { every_n_steps } => {
                self.every = every_n_steps;
                ack
            }
            Command::SetParam { id, .. } if state == RigState::Running => {
                Report::Rejected { id, reason: RejectReason::Busy }
            }
            Command::SetParam { id, value } => {
                let mut params = *rig.params();
                if S::set_param(&mut params, id, value) {
                    match rig.reset(params) {
                        Ok(()) => ack,
                        Err(RigError::Params(e)) => Report::Rejected { id, reason: reason_of(e) },
                        Err(RigError::Unperformable(_)) => {
                            Report::Rejected { id, reason: RejectReason::BeyondRig }
                        }
                        Err(e) => return Err(e),
                    }
                } else {
                    Report::Rejected { id, reason: RejectReason::Other }
                }
            }
            Command::Preset(_) if state == RigState::Running => not_allowed,
            Command::Preset(p) => match S::preset(p, rig.params()).map(|params| rig.reset(params)) {
                Some(Ok(())) => ack,
                None | Some(Err(RigError::Params(_))) => not_allowed,
                Some(Err(RigError::Unperformable(u))) => {
                    Report::Rejected { id: param_of(u), reason: RejectReason::BeyondRig }
                }
                Some(Err(e)) => return Err(e),
            },
            Command::Start => {
                if rig.start()? {
                    ack
                } else {
                    not_allowed
                }
            }
            Command::Stop => {
                if rig.stop()? {
                    ack
                } else {
                    not_allowed
                }
            }
            Command::Reset => {
                rig.stop()?;
                self.sync(rig);
                rig.reset(*rig.params())?;
                ack
            }
            Command::SelectScene(scene) if scene == S::SCENE => ack,
            Command::SelectScene(scene) if !self.scenes.contains(&scene) => {
                Report::Error(ErrorCode::NoSuchScene(scene))
            }
            Command::SelectScene(_) if state == RigState::Running => not_allowed,
            Command::SelectScene(scene) => {
                self.send(&ack);
                return Ok(Some(scene));
            }
        };
        self.send(&reply);
        self.sync(rig);
        Ok(None)
    }
}

/// The rig's identity.
fn hello<S: LinkScene<L>, const L: usize>(
    params: &S::Params,
    firmware: (u8, u8, u8),
    build: [u8; 8],
) -> Report {
    Report::Hello {
        protocol: PROTOCOL_VERSION,
        firmware,
        core: CORE_VERSION,
        build,
        scene: S::SCENE,
        lcp_size: S::LCP_SIZE,
        // Rounded (5.01e-4 s is 501 us, not 500); saturating: a valid step is positive and finite.
        #[allow(clippy::cast_sign_loss)]
        step_us: libm::roundf(S::step_of(params) * 1e6) as u32,
    }
}

/// `major.minor.patch` of a version string (digits up to the first non-digit of each part),
/// evaluated at compile time.
#[must_use]
pub const fn version(v: &str) -> (u8, u8, u8) {
    let b = v.as_bytes();
    let mut parts = [0u8; 3];
    let (mut i, mut part) = (0, 0);
    while i < b.len() && part < 3 {
        let c = b[i];
        if c == b'.' {
            part += 1;
        } else if c.is_ascii_digit() {
            parts[part] = parts[part].wrapping_mul(10).wrapping_add(c - b'0');
        } else {
            break;
        }
        i += 1;
    }
    (parts[0], parts[1], parts[2])
}

const CORE_VERSION: (u8, u8, u8) = version(meterstick_core::VERSION);

/// The build id: the first 8 bytes of `id` (e.g. a git hash), space-padded.
#[must_use]
#[inline]
pub fn build_id(id: &str) -> [u8; 8] {
    let mut out = [b' '; 8];
    for (o, b) in out.iter_mut().zip(id.bytes()) {
        *o = b;
    }
    out
}
