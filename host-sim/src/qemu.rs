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

/// Reads the firmware ELF `elf` and checks that its defmt table can be read, before QEMU starts
/// (its output is decoded with that table).
///
/// # Errors
/// The file cannot be read, is not an ELF, or has no `.defmt` table (each naming the file).
fn read_firmware(elf: &Path) -> anyhow::Result<Vec<u8>> {
    let bytes = crate::input::read(elf, crate::input::ELF_FILE_CAP).context("reading the firmware ELF")?;
    match defmt_decoder::Table::parse(&bytes) {
        Ok(Some(_)) => Ok(bytes),
        Ok(None) => {
            bail!("{}: the firmware ELF has no .defmt table (not a meterstick firmware?)", elf.display())
        }
        Err(e) => bail!("{}: not a firmware ELF ({e})", elf.display()),
    }
}

/// Runs `elf` on `machine` under QEMU with semihosting, for at most `timeout`.
/// With `icount`, QEMU counts one instruction per virtual nanosecond (`-icount shift=0`),
/// which makes `SysTick` a deterministic instruction counter.
///
/// # Errors
/// QEMU missing or not startable, an unreadable ELF, or undecodable output.
pub fn run(elf: &Path, machine: Machine, timeout: Duration, icount: bool) -> anyhow::Result<FirmwareRun> {
    let elf_bytes = read_firmware(elf)?;
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
        let elf_bytes = read_firmware(elf)?;
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

/// What a firmware run printed and how it ended, with its timing read into numbers
/// (`host-sim qemu --json`; `scripts/firmware-report.sh` reads it).
#[derive(Debug, Clone, serde::Serialize)]
pub struct RunStats {
    /// Semihosting exit status (`None` when QEMU was killed or ended by a signal).
    pub exit_code: Option<i32>,
    /// `true` when the run hit the timeout and was killed.
    pub timed_out: bool,
    /// The decoded defmt messages.
    pub lines: Vec<String>,
    /// The timing lines, converted to instructions (`None` without a calibration line).
    pub timing: Option<Timing>,
}

/// The firmware's step timing in instructions (`-icount shift=0`: the `SysTick` ticks converted
/// with the firmware's calibration loop of known length).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Timing {
    /// Instructions per `SysTick` tick.
    pub instructions_per_tick: f64,
    /// Each scene timed step by step: through the rig loop (`<scene> rig ..`) or driven through the
    /// core's scene interface (`<scene> timing ..`, every other scene).
    pub scenes: Vec<SceneTiming>,
    /// The RAM the stack may grow into (`ram stack_room_bytes=..`: the stack top less the end of
    /// the static data); `None` when the firmware does not print it.
    pub stack_room_bytes: Option<u64>,
    /// Every run whose stack the firmware painted (`<scene> stack peak_bytes=..`), timed or not, in
    /// the order it printed them.
    pub stack_peaks: Vec<StackPeak>,
}

/// The deepest the stack grew in one run (`firmware/src/stack_peak.rs`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct StackPeak {
    /// The firmware's name for the run.
    pub scene: String,
    /// Bytes below the stack top.
    pub peak_bytes: u64,
}

/// One scene's steps.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SceneTiming {
    /// The firmware's name for the run (`slow`, `fast`, `block-on-block`, `stack`).
    pub scene: String,
    /// Steps taken.
    pub steps: u64,
    /// Mean instructions per step.
    pub mean_instructions: f64,
    /// The worst step's instructions.
    pub worst_instructions: f64,
    /// The same per solve path (`SolvePath`'s names), for the steps each answered, and
    /// [`FAILED`] for the step that failed (not among `steps`) where the firmware prints it.
    pub paths: Vec<PathTiming>,
    /// The deepest the stack grew during the scene, in bytes below the stack top (the firmware
    /// paints the free RAM before it: `firmware/src/stack_peak.rs`); `None` when the line has none.
    pub stack_peak_bytes: Option<u64>,
}

/// [`PathTiming::path`] of the step that failed: every path tried, the step's `StepError` (the
/// scenes of several bodies print it, `<scene> path=failed ..`; at most one a run, which it ends).
pub const FAILED: &str = "failed";

/// The steps one solve path answered in a scene (or, [`FAILED`], the step that failed).
#[derive(Debug, Clone, serde::Serialize)]
pub struct PathTiming {
    /// `free`, `warm`, `candidate` or `lemke` (`meterstick_core::planar::SolvePath::name`), or
    /// [`FAILED`].
    pub path: &'static str,
    /// Steps.
    pub steps: u64,
    /// Mean instructions per step (`None` without steps).
    pub mean_instructions: Option<f64>,
    /// The worst step's instructions.
    pub worst_instructions: f64,
}

/// The `key=value` fields of a line after its first `skip` words.
fn fields(line: &str, skip: usize) -> std::collections::HashMap<&str, &str> {
    line.split_whitespace().skip(skip).filter_map(|w| w.split_once('=')).collect()
}

/// Reads the firmware's timing lines (`calibration instructions=.. systicks=..`, `<scene> rig
/// .. systicks=.. worst_step_systicks=.. steps=..` or `<scene> timing systicks=..
/// worst_step_systicks=.. steps=..`, `<scene> path=<name> steps=.. systicks=..
/// worst_step_systicks=..`, `<scene> stack peak_bytes=..`; `firmware/src/qemu.rs` prints them)
/// into instructions. `None` without
/// a calibration line; a malformed number is an error naming the line.
///
/// # Errors
/// A timing line whose number does not parse, or a path name the core does not have.
pub fn timing(lines: &[String]) -> anyhow::Result<Option<Timing>> {
    use meterstick_core::planar::SolvePath;
    let number = |line: &str, f: &std::collections::HashMap<&str, &str>, key: &str| -> anyhow::Result<u64> {
        let v = f.get(key).with_context(|| format!("firmware line without {key}=: {line}"))?;
        v.parse().with_context(|| format!("firmware line with {key}={v}, not a count: {line}"))
    };
    let Some(cal) = lines.iter().find(|l| l.starts_with("calibration ")) else { return Ok(None) };
    let f = fields(cal, 1);
    let ticks = number(cal, &f, "systicks")?;
    if ticks == 0 {
        bail!("firmware calibration with 0 ticks: {cal}");
    }
    let per_tick = number(cal, &f, "instructions")? as f64 / ticks as f64;
    let mut scenes = Vec::new();
    for line in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        if !matches!(words.get(1), Some(&("rig" | "timing"))) || !line.contains("worst_step_systicks=") {
            continue;
        }
        let f = fields(line, 2);
        let steps = number(line, &f, "steps")?;
        let mut paths = Vec::new();
        // The solve paths, then the step that failed after trying them all (scenes of several
        // bodies print it, `path=failed`).
        for path in SolvePath::ALL.map(SolvePath::name).into_iter().chain([FAILED]) {
            let prefix = format!("{} path={path} ", words[0]);
            let Some(p) = lines.iter().find(|l| l.starts_with(&prefix)) else { continue };
            let g = fields(p, 2);
            let n = number(p, &g, "steps")?;
            paths.push(PathTiming {
                path,
                steps: n,
                mean_instructions: (n > 0)
                    .then(|| number(p, &g, "systicks").map(|t| t as f64 * per_tick / n as f64))
                    .transpose()?,
                worst_instructions: number(p, &g, "worst_step_systicks")? as f64 * per_tick,
            });
        }
        scenes.push(SceneTiming {
            scene: words[0].to_owned(),
            steps,
            mean_instructions: number(line, &f, "systicks")? as f64 * per_tick / steps.max(1) as f64,
            worst_instructions: number(line, &f, "worst_step_systicks")? as f64 * per_tick,
            paths,
            stack_peak_bytes: lines
                .iter()
                .find(|l| l.starts_with(&format!("{} stack ", words[0])))
                .map(|l| number(l, &fields(l, 2), "peak_bytes"))
                .transpose()?,
        });
    }
    let mut stack_peaks = Vec::new();
    for line in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        if let [scene, "stack", _] = words[..] {
            stack_peaks.push(StackPeak {
                scene: scene.to_owned(),
                peak_bytes: number(line, &fields(line, 2), "peak_bytes")?,
            });
        }
    }
    let stack_room_bytes = lines
        .iter()
        .find(|l| l.starts_with("ram "))
        .map(|l| number(l, &fields(l, 1), "stack_room_bytes"))
        .transpose()?;
    Ok(Some(Timing { instructions_per_tick: per_tick, scenes, stack_room_bytes, stack_peaks }))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod timing_tests {
    use super::timing;

    #[test]
    fn timing_lines_become_instructions() {
        let lines: Vec<String> = [
            "calibration instructions=2000002 systicks=50000",
            "slow rig pulses=7000 systicks=400000 worst_step_systicks=150 steps=7900",
            "slow path=free steps=0 systicks=0 worst_step_systicks=0",
            "slow path=warm steps=7871 systicks=398000 worst_step_systicks=58",
            "slow path=candidate steps=29 systicks=2000 worst_step_systicks=150",
            "stack outcome=Held t=10 steps=10000 pivots=0 max_active=3 checksum=0badcafe",
            "stack timing systicks=1000000 worst_step_systicks=900 steps=10000",
            "stack stack peak_bytes=6144",
            "ram stack_room_bytes=16368",
            "three-fingers stack peak_bytes=15412",
        ]
        .map(String::from)
        .to_vec();
        let t = timing(&lines).unwrap().unwrap();
        let per = 2_000_002.0 / 50_000.0;
        assert!((t.instructions_per_tick - per).abs() < 1e-12);
        let s = &t.scenes[0];
        assert_eq!((s.scene.as_str(), s.steps), ("slow", 7900));
        assert!((s.mean_instructions - 400_000.0 * per / 7900.0).abs() < 1e-9);
        assert!((s.worst_instructions - 150.0 * per).abs() < 1e-9);
        assert_eq!(s.paths.iter().map(|p| p.path).collect::<Vec<_>>(), ["free", "warm", "candidate"]);
        assert_eq!(s.paths[0].mean_instructions, None);
        assert_eq!(s.paths[2].steps, 29);
        // A scene driven through the scene interface (here without solve paths): its `timing` line.
        let m = &t.scenes[1];
        assert_eq!((m.scene.as_str(), m.steps, t.scenes.len()), ("stack", 10_000, 2));
        assert!((m.mean_instructions - 1_000_000.0 * per / 10_000.0).abs() < 1e-9);
        assert!((m.worst_instructions - 900.0 * per).abs() < 1e-9);
        assert!(m.paths.is_empty());
        assert_eq!((s.stack_peak_bytes, m.stack_peak_bytes), (None, Some(6144)));
        // Every painted run, timed or not, and the room the stack has.
        let peaks: Vec<_> = t.stack_peaks.iter().map(|p| (p.scene.as_str(), p.peak_bytes)).collect();
        assert_eq!(peaks, [("stack", 6144), ("three-fingers", 15_412)]);
        assert_eq!(t.stack_room_bytes, Some(16_368));
        let bad = vec!["calibration instructions=2000002 systicks=0".to_owned()];
        assert!(timing(&bad).is_err());
        let garbled = vec!["calibration instructions=x systicks=5".to_owned()];
        assert!(format!("{:#}", timing(&garbled).unwrap_err()).contains("instructions=x"));
        assert!(timing(&[]).unwrap().is_none());
    }

    /// A scene of several bodies prints its steps by path and the step that failed
    /// (`firmware/src/qemu.rs`, `print_paths`): the paths' steps sum to the scene's, the failed
    /// step is apart, and a path's worst is within the scene's.
    #[test]
    fn multibody_paths_and_the_failed_step() {
        let lines: Vec<String> = [
            "calibration instructions=2000002 systicks=50000",
            "block-on-block timing systicks=31000 worst_step_systicks=375 steps=255",
            "block-on-block path=free steps=0 systicks=0 worst_step_systicks=0",
            "block-on-block path=warm steps=252 systicks=30000 worst_step_systicks=300",
            "block-on-block path=candidate steps=3 systicks=1000 worst_step_systicks=375",
            "block-on-block path=lemke steps=0 systicks=0 worst_step_systicks=0",
            "block-on-block path=failed steps=0 systicks=0 worst_step_systicks=0",
            "heavy-top timing systicks=0 worst_step_systicks=0 steps=0",
            "heavy-top path=free steps=0 systicks=0 worst_step_systicks=0",
            "heavy-top path=warm steps=0 systicks=0 worst_step_systicks=0",
            "heavy-top path=candidate steps=0 systicks=0 worst_step_systicks=0",
            "heavy-top path=lemke steps=0 systicks=0 worst_step_systicks=0",
            "heavy-top path=failed steps=1 systicks=90000 worst_step_systicks=90000",
        ]
        .map(String::from)
        .to_vec();
        let t = timing(&lines).unwrap().unwrap();
        let per = t.instructions_per_tick;
        for s in &t.scenes {
            let names: Vec<_> = s.paths.iter().map(|p| p.path).collect();
            assert_eq!(names, ["free", "warm", "candidate", "lemke", super::FAILED], "{}", s.scene);
            let answered: u64 = s.paths.iter().filter(|p| p.path != super::FAILED).map(|p| p.steps).sum();
            assert_eq!(answered, s.steps, "{}", s.scene);
            for p in s.paths.iter().filter(|p| p.path != super::FAILED) {
                assert!(p.worst_instructions <= s.worst_instructions, "{}: {}", s.scene, p.path);
            }
        }
        let failed = &t.scenes[1].paths[4];
        assert_eq!(failed.steps, 1);
        assert!((failed.worst_instructions - 90_000.0 * per).abs() < 1e-6);
        assert_eq!(failed.mean_instructions, Some(failed.worst_instructions));
        assert_eq!(t.scenes[0].paths[4].mean_instructions, None);
    }
}
