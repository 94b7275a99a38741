//! Running a firmware ELF under QEMU and decoding its defmt output.
//!
//! The firmware writes defmt frames (rzCOBS) to semihosting stdout and ends with a
//! semihosting exit status. [`run`] starts `qemu-system-arm`, collects stdout, enforces a
//! timeout (a hung firmware is killed and reported), and decodes every frame with the
//! ELF's own `.defmt` table.

use std::io::Read as _;
use std::net::{TcpListener, TcpStream};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};

/// A QEMU machine the firmware is built for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Machine {
    /// ARM MPS2 AN386, Cortex-M4F (`thumbv7em-none-eabihf`); `SysTick` at 25 MHz.
    Mps2An386,
    /// BBC micro:bit, nRF51822, Cortex-M0 (`thumbv6m-none-eabi`).
    Microbit,
    /// ARM MPS2+ AN505 (SSE-200), Cortex-M33 with FPU (`thumbv8m.main-none-eabihf`), run in Secure
    /// state; `SysTick` at 20 MHz.
    Mps2An505,
}

impl Machine {
    /// QEMU's `-machine` argument.
    #[must_use]
    pub const fn qemu_name(self) -> &'static str {
        match self {
            Self::Mps2An386 => "mps2-an386",
            Self::Microbit => "microbit",
            Self::Mps2An505 => "mps2-an505",
        }
    }

    fn cpu_args(self) -> &'static [&'static str] {
        match self {
            Self::Mps2An386 => &["-cpu", "cortex-m4"],
            Self::Microbit => &[],
            Self::Mps2An505 => &["-cpu", "cortex-m33"],
        }
    }
}

/// What one firmware run printed and how it ended.
#[derive(Debug, Clone)]
pub struct FirmwareRun {
    /// Semihosting exit status (`None` when QEMU was killed or ended by a signal).
    pub exit_code: Option<i32>,
    /// `true` when the run hit the timeout and was killed.
    pub timed_out: bool,
    /// The decoded defmt messages, one per frame.
    pub lines: Vec<String>,
}

/// Runs `elf` on `machine` under QEMU with semihosting, for at most `timeout`.
/// With `icount`, QEMU counts one instruction per virtual nanosecond (`-icount shift=0`),
/// which makes `SysTick` a deterministic instruction counter.
///
/// # Errors
/// QEMU missing or not startable, an unreadable ELF, or undecodable output.
pub fn run(elf: &Path, machine: Machine, timeout: Duration, icount: bool) -> anyhow::Result<FirmwareRun> {
    let elf_bytes =
        crate::input::read(elf, crate::input::ELF_FILE_CAP).context("reading the firmware ELF")?;
    let mut cmd = Command::new("qemu-system-arm");
    cmd.args(["-machine", machine.qemu_name()])
        .args(machine.cpu_args())
        .args(["-nographic", "-monitor", "none", "-serial", "none"])
        .args(["-semihosting-config", "enable=on,target=native"]);
    if icount {
        cmd.args(["-icount", "shift=0"]);
    }
    cmd.arg("-kernel").arg(elf).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
    let mut child = cmd.spawn().context("starting qemu-system-arm (run scripts/setup.sh to install it)")?;
    let mut stdout = child.stdout.take().context("qemu stdout")?;
    let reader = std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = stdout.read_to_end(&mut buf);
        buf
    });
    let start = Instant::now();
    let mut timed_out = false;
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        if start.elapsed() > timeout {
            timed_out = true;
            let _ = child.kill();
            break child.wait()?;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let raw = reader.join().map_err(|_| anyhow::anyhow!("qemu stdout reader panicked"))?;
    let lines = decode_defmt(&elf_bytes, &raw)?;
    Ok(FirmwareRun { exit_code: if timed_out { None } else { status.code() }, timed_out, lines })
}

/// A firmware with the host link (`link` feature) running under QEMU, its UART connected to a
/// TCP socket of this process (QEMU connects to it: `-serial tcp:127.0.0.1:PORT`). Killed on
/// drop.
#[derive(Debug)]
pub struct LinkedFirmware {
    child: Child,
    stdout: Option<JoinHandle<Vec<u8>>>,
    elf: Vec<u8>,
    /// The UART's other end.
    pub stream: TcpStream,
}

impl LinkedFirmware {
    /// Starts `elf` on `machine` (with `icount`, deterministic instruction counting) and
    /// accepts QEMU's connection to the UART socket.
    ///
    /// # Errors
    /// QEMU missing or not startable, no connection within 20 s.
    pub fn start(elf: &Path, machine: Machine, icount: bool) -> anyhow::Result<Self> {
        let elf_bytes =
            crate::input::read(elf, crate::input::ELF_FILE_CAP).context("reading the firmware ELF")?;
        let listener = TcpListener::bind("127.0.0.1:0").context("binding a local TCP port for the UART")?;
        let port = listener.local_addr()?.port();
        let mut cmd = Command::new("qemu-system-arm");
        cmd.args(["-machine", machine.qemu_name()])
            .args(machine.cpu_args())
            .args(["-nographic", "-monitor", "none"])
            .args(["-serial", &format!("tcp:127.0.0.1:{port}")])
            .args(["-semihosting-config", "enable=on,target=native"]);
        if icount {
            cmd.args(["-icount", "shift=0"]);
        }
        cmd.arg("-kernel").arg(elf).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::null());
        let mut child =
            cmd.spawn().context("starting qemu-system-arm (run scripts/setup.sh to install it)")?;
        let mut stdout = child.stdout.take().context("qemu stdout")?;
        let reader = std::thread::spawn(move || {
            let mut buf = Vec::new();
            let _ = stdout.read_to_end(&mut buf);
            buf
        });
        listener.set_nonblocking(true)?;
        let start = Instant::now();
        let stream = loop {
            match listener.accept() {
                Ok((stream, _)) => break stream,
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
                Err(e) => return Err(e).context("accepting QEMU's UART connection"),
            }
            if let Some(status) = child.try_wait()? {
                bail!("qemu-system-arm exited ({status}) before connecting its UART");
            }
            if start.elapsed() > Duration::from_secs(20) {
                let _ = child.kill();
                bail!("QEMU did not connect its UART within 20 s");
            }
            std::thread::sleep(Duration::from_millis(10));
        };
        stream.set_nonblocking(false)?;
        Ok(Self { child, stdout: Some(reader), elf: elf_bytes, stream })
    }

    /// Ends QEMU and returns the firmware's decoded defmt output.
    ///
    /// # Errors
    /// Undecodable output.
    pub fn stop(mut self) -> anyhow::Result<Vec<String>> {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let raw = self.stdout.take().map(|h| h.join().unwrap_or_default()).unwrap_or_default();
        decode_defmt(&self.elf, &raw)
    }
}

impl Drop for LinkedFirmware {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Decodes a defmt byte stream with the table of `elf`.
///
/// # Errors
/// The ELF has no defmt table, or the stream holds a malformed frame.
pub fn decode_defmt(elf: &[u8], raw: &[u8]) -> anyhow::Result<Vec<String>> {
    let Some(table) = defmt_decoder::Table::parse(elf)? else {
        bail!("the firmware ELF has no .defmt table");
    };
    let mut decoder = table.new_stream_decoder();
    decoder.received(raw);
    let mut lines = Vec::new();
    loop {
        match decoder.decode() {
            Ok(frame) => lines.push(frame.display_message().to_string()),
            Err(defmt_decoder::DecodeError::UnexpectedEof) => break,
            Err(defmt_decoder::DecodeError::Malformed) => {
                bail!("malformed defmt frame after {} good ones", lines.len())
            }
        }
    }
    Ok(lines)
}
