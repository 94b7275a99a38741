//! Progress and Ctrl-C for the commands that can run long (`run`, `report`, `map`, `envelope`,
//! `stress`, `scene`): one implementation they share.
//!
//! **Progress.** [`bar`] makes an indicatif bar on stderr when stderr is a terminal; otherwise
//! (a log file, CI, a pipe) it prints a plain line every [`period`] seconds while the bar runs
//! (`host-sim: map cells: 120/1547 (8%), 12 s`), and nothing for work that ends sooner.
//! `MS_PROGRESS_SECS` sets the period (default 5 s).
//!
//! **Ctrl-C.** [`install_ctrl_c`] (called by the command line for those commands) turns the
//! first Ctrl-C into a request: no new run starts, every run under way stops at its next check
//! (every 4,096 steps, in the core's loop and the reference's) and is dropped, and the command
//! returns [`Interrupted`]; `host-sim` then lists the files written so far and exits with status
//! 130. A second Ctrl-C quits at once.

use std::io::IsTerminal as _;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

static INTERRUPTED: AtomicBool = AtomicBool::new(false);
static PRESSES: AtomicUsize = AtomicUsize::new(0);
static INSTALLED: std::sync::OnceLock<Result<(), String>> = std::sync::OnceLock::new();

/// The exit status after Ctrl-C (128 + SIGINT, as a shell reports it).
pub const EXIT_INTERRUPTED: u8 = 130;

/// How many steps a run takes between two checks for Ctrl-C.
pub const CHECK_EVERY_STEPS: u64 = crate::reference::CHECK_EVERY_STEPS;

/// The command was stopped by Ctrl-C (or by [`request_stop`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Interrupted;

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("interrupted (Ctrl-C)")
    }
}

impl std::error::Error for Interrupted {}

/// `true` when `e` (or what it wraps) is [`Interrupted`].
#[must_use]
pub fn is_interrupted(e: &anyhow::Error) -> bool {
    e.chain().any(<dyn std::error::Error>::is::<Interrupted>)
}

/// Turns Ctrl-C (SIGINT; on Windows Ctrl-C and Ctrl-Break) into [`request_stop`]; a second one
/// exits at once with [`EXIT_INTERRUPTED`]. Installs once; later calls do nothing.
///
/// # Errors
/// The handler cannot be installed (another handler is set).
pub fn install_ctrl_c() -> anyhow::Result<()> {
    INSTALLED
        .get_or_init(|| {
            ctrlc::set_handler(|| {
                if PRESSES.fetch_add(1, Ordering::SeqCst) == 0 {
                    request_stop();
                    eprintln!(
                        "\nhost-sim: Ctrl-C: no new run starts, the runs under way stop; Ctrl-C again quits at once"
                    );
                } else {
                    std::process::exit(i32::from(EXIT_INTERRUPTED));
                }
            })
            .map_err(|e| e.to_string())
        })
        .clone()
        .map_err(|e| anyhow::anyhow!("installing the Ctrl-C handler: {e}"))
}

/// Asks every run to stop (what the first Ctrl-C does).
pub fn request_stop() {
    INTERRUPTED.store(true, Ordering::SeqCst);
    crate::reference::request_stop();
}

/// `true` once a stop was requested.
#[must_use]
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// `Err(Interrupted)` once a stop was requested.
///
/// # Errors
/// [`Interrupted`].
pub fn check() -> Result<(), Interrupted> {
    if interrupted() { Err(Interrupted) } else { Ok(()) }
}

/// The period of the plain progress lines: `MS_PROGRESS_SECS` (seconds, > 0), default 5 s.
#[must_use]
pub fn period() -> Duration {
    std::env::var("MS_PROGRESS_SECS")
        .ok()
        .and_then(|s| s.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
        .map_or(Duration::from_secs(5), |s| Duration::from_secs_f64(s.min(86_400.0)))
}

/// A progress bar over `len` jobs on stderr: drawn on a terminal; otherwise a plain line every
/// [`period`] while it runs (a thread that ends with the bar).
#[must_use]
pub fn bar(len: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(what.to_owned());
    if std::io::stderr().is_terminal() {
        bar.enable_steady_tick(Duration::from_millis(200));
    } else {
        plain_lines(&bar, period());
    }
    bar
}

/// The line [`bar`] prints off a terminal.
#[must_use]
pub fn line(what: &str, pos: u64, len: Option<u64>, elapsed: Duration) -> String {
    let secs = elapsed.as_secs_f64();
    match len {
        Some(len) if len > 0 => {
            let pct = 100.0 * pos as f64 / len as f64;
            format!("host-sim: {what}: {pos}/{len} ({pct:.0}%), {secs:.0} s")
        }
        _ => format!("host-sim: {what}: {pos}, {secs:.0} s"),
    }
}

fn plain_lines(bar: &ProgressBar, period: Duration) {
    let weak = bar.downgrade();
    let tick = period.min(Duration::from_millis(100));
    let spawned = std::thread::Builder::new().name("progress".into()).spawn(move || {
        let mut since = Duration::ZERO;
        loop {
            std::thread::sleep(tick);
            since += tick;
            let Some(bar) = weak.upgrade() else { return };
            if bar.is_finished() {
                return;
            }
            if since >= period {
                since = Duration::ZERO;
                eprintln!("{}", line(&bar.message(), bar.position(), bar.length(), bar.elapsed()));
            }
        }
    });
    // No thread, no lines: the work goes on without them.
    drop(spawned);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_say_what_how_far_and_how_long() {
        assert_eq!(
            line("map cells", 120, Some(1547), Duration::from_secs(12)),
            "host-sim: map cells: 120/1547 (8%), 12 s"
        );
        assert_eq!(line("steps", 5, None, Duration::from_millis(400)), "host-sim: steps: 5, 0 s");
    }
}
